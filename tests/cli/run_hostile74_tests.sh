#!/usr/bin/env bash
# Session 74 (hostile74's findings, fixed by the integrator), generated (seeded by $SEED, default 74):
#  - certify --claim clearance without --distance on the lever 10^-k mm from its stop (k = 60 .. 320)
#    certifies a distance at most the gap, and hipair-verify accepts it (base74: "touch or overlap");
#  - two outputs that are one file through a symbolic link (--svg link -> the --json file) are
#    refused before anything is written (base74 wrote both, one lost);
#  - certify --at for a fixed part is refused naming it (base74 ignored it);
#  - tolerance --vary naming a parameter twice is refused as every repeated target is (exit 114).
# usage: run_hostile74_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 verify=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
RANDOM=${SEED:-74}
models=$source/examples/models


# a JSON copy of MODEL with the value at the path set (a tiny python edit; the value is a string literal)
edited() {
  python3 - "$@" <<'PY'
import json, sys
model, out, value, *path = sys.argv[1:]
data = json.load(open(model))
node = data
for key in path[:-1]:
    node = node[int(key)] if isinstance(node, list) else node[key]
last = path[-1]
node[int(last) if isinstance(node, list) else last] = value
json.dump(data, open(out, "w"), indent=1)
PY
}

for round in 1 2 3; do
  k=$((60 + RANDOM % 261))
  edited "$models/lever-stop.json" "$work/gap-$round.json" "$((1 + RANDOM % 9))e-$k" parameters stop-gap nominal
  "$hipair" certify "$work/gap-$round.json" --claim clearance --out "$work/gap-$round.cert.json" >"$work/gap-$round.out" 2>&1 ||
    fail "gap-$round (1e-$k): $(head -c 300 "$work/gap-$round.out")"
  "$verify" "$work/gap-$round.cert.json" "$work/gap-$round.json" >"$work/gap-$round.verify" 2>&1 ||
    fail "gap-$round (1e-$k): not verified: $(head -c 300 "$work/gap-$round.verify")"
done

mkdir -p "$work/alias" && ln -s y.json "$work/alias/link.svg"
"$hipair" cspace "$models/lever-stop.json" --json "$work/alias/y.json" --svg "$work/alias/link.svg" >"$work/alias.out" 2>&1
code=$?
[ $code -ne 0 ] || fail "alias: exit 0"
grep -q "refusing to write one file twice" "$work/alias.out" || fail "alias: message: $(head -c 300 "$work/alias.out")"
[ -e "$work/alias/y.json" ] && fail "alias: wrote output"

"$hipair" certify "$models/lever-stop.json" --claim interference --at stop=1 --out "$work/fixed-at.json" >"$work/fixed-at.out" 2>&1
code=$?
[ $code -eq 2 ] || fail "fixed-at: exit $code, want 2"
grep -q -- "--at stop=1: part 'stop' is fixed and has no position" "$work/fixed-at.out" || fail "fixed-at: message: $(head -c 300 "$work/fixed-at.out")"
[ -e "$work/fixed-at.json" ] && fail "fixed-at: wrote output"

"$hipair" tolerance "$models/geneva.json" --threshold --vary pin-radius --vary pin-radius --out "$work/vary.dir" --quiet >"$work/vary.out" 2>&1
code=$?
[ $code -eq 114 ] || fail "vary: exit $code, want 114"
grep -q -- "--vary: parameter 'pin-radius' is given twice" "$work/vary.out" || fail "vary: message: $(head -c 300 "$work/vary.out")"
[ -e "$work/vary.dir" ] && fail "vary: wrote output"

# hostile75 L1 (session 75, integrator): simulate --out DIR whose DIR holds the model under a name
# every run writes is refused before the run (base75 made the whole run, printed it, then refused)
for name in trajectory.csv events.json events.txt; do
  mkdir -p "$work/io-$name"
  cp "$models/bouncing-bar.json" "$work/io-$name/$name"
  "$hipair" simulate "$work/io-$name/$name" --t-end 200 --out "$work/io-$name" --no-pictures --quiet >"$work/io.stdout" 2>"$work/io.stderr"
  code=$?
  [ $code -eq 3 ] || fail "simulate io $name: exit $code, want 3"
  [ -s "$work/io.stdout" ] && fail "simulate io $name: printed a run before refusing: $(head -c 200 "$work/io.stdout")"
  grep -q "is the input file" "$work/io.stderr" || fail "simulate io $name: message: $(head -c 300 "$work/io.stderr")"
  cmp -s "$models/bouncing-bar.json" "$work/io-$name/$name" || fail "simulate io $name: the model was changed"
done
mkdir -p "$work/io-sweep"
cp "$models/bouncing-bar.json" "$work/io-sweep/sweep.json"
"$hipair" simulate "$work/io-sweep/sweep.json" --sweep speed=1:2:2 --allow-out-of-tolerance --t-end 1 --out "$work/io-sweep" --quiet >"$work/io.stdout" 2>"$work/io.stderr"
code=$?
[ $code -eq 3 ] || fail "simulate io sweep: exit $code, want 3"
[ -s "$work/io.stdout" ] && fail "simulate io sweep: printed a sweep before refusing: $(head -c 200 "$work/io.stdout")"
grep -q "is the input file" "$work/io.stderr" || fail "simulate io sweep: message: $(head -c 300 "$work/io.stderr")"

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "hostile74 CLI checks passed"
