#!/usr/bin/env bash
# Session 75 (fine75), generated (seeded by $SEED, default 75): coordinates written too finely.
#  - geneva-template.json with the wheel's centre at y = 10^-k (k in 300 .. 1000) and ratchet.json
#    with the wheel's centre at y = 10^-k (k in 620 .. 1000): `cspace` refuses at once (exit 3, one
#    line naming the wheel's feature and the 2048-bit limit, no --json or --svg written); base75
#    ran for minutes (hostile74 H1: the Geneva one over 282 s CPU at 1e-400);
#  - the ratchet at y = 10^-k (k in 30 .. 120) is built, with the counts of the ratchet at
#    y = 10^-30 (a perturbation that small no longer changes the arrangement) and the free cells,
#    faces and contact edges of the unshifted ratchet;
#  - certify --at PART=VALUE with a literal's decimal exponent beyond 1000 (1e1001, -1e-1001,
#    1e1001deg, 3e+1234) is refused naming --at as out of range (exit 2, nothing written);
#    1e1000 is read (base75 read them all, reduced modulo 2 pi: hostile74 L3).
# usage: run_fine75_tests.sh HIPAIR SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
RANDOM=${SEED:-75}
models=$source/examples/models

# a copy of MODEL with the first feature's template centre at (0, VALUE) (VALUE written as a JSON number)
offset_centre() { # MODEL OUT VALUE
  python3 - "$@" <<'PY'
import json, sys
model, out, value = sys.argv[1:]
data = json.load(open(model))
for part in data["parts"]:
    for feature in part.get("features", []):
        template = next(iter(feature.values()))
        if isinstance(template, dict) and "center" in template:
            template["center"] = [0, "@VALUE@"]
            open(out, "w").write(json.dumps(data, indent=1).replace('"@VALUE@"', value))
            sys.exit(0)
sys.exit("no template centre in " + model)
PY
}

# counts of `cspace --stats`: "vertices V, edges E (contact C), faces F, cells N"
counts() { grep -E '^  vertices ' "$1" | head -1; }

refused() { # NAME MODEL POINTER
  local name=$1 model=$2 pointer=$3
  timeout 60 "$hipair" cspace "$model" --json "$work/$name.json" --svg "$work/$name.svg" >"$work/$name.out" 2>"$work/$name.err"
  local rc=$?
  [ $rc -eq 3 ] || fail "$name: exit $rc (expected 3 at once): $(head -c 300 "$work/$name.err")"
  grep -qF "'wheel' ($pointer)" "$work/$name.err" || fail "$name: the message does not name the wheel's feature $pointer: $(head -c 300 "$work/$name.err")"
  grep -qF "beyond the 2048 bits" "$work/$name.err" || fail "$name: the message does not give the limit: $(head -c 300 "$work/$name.err")"
  [ "$(wc -l <"$work/$name.err")" -eq 1 ] || fail "$name: more than one line of error"
  [ ! -e "$work/$name.json" ] && [ ! -e "$work/$name.svg" ] || fail "$name: an output was written"
}

for k in 300 $((301 + RANDOM % 699)) $((301 + RANDOM % 699)) 1000; do
  offset_centre "$models/geneva-template.json" "$work/geneva-$k.model.json" "1e-$k"
  refused "geneva-$k" "$work/geneva-$k.model.json" /parts/1/features/0/geneva_wheel
done
for k in 620 $((621 + RANDOM % 379)) 1000; do
  offset_centre "$models/ratchet.json" "$work/ratchet-$k.model.json" "$((1 + RANDOM % 9))e-$k"
  refused "ratchet-$k" "$work/ratchet-$k.model.json" /parts/0/features/0/ratchet_wheel
done

# built: the ratchet a hair off centre has the arrangement of the ratchet at 1e-30, and the cells,
# faces and contact edges of the unshifted one
"$hipair" cspace "$models/ratchet.json" --stats >"$work/ratchet-0.stats" 2>&1 || fail "ratchet: $(head -c 300 "$work/ratchet-0.stats")"
offset_centre "$models/ratchet.json" "$work/ratchet-30.model.json" "1e-30"
"$hipair" cspace "$work/ratchet-30.model.json" --stats >"$work/ratchet-30.stats" 2>&1 || fail "ratchet 1e-30: $(head -c 300 "$work/ratchet-30.stats")"
reference=$(counts "$work/ratchet-30.stats")
unshifted=$(counts "$work/ratchet-0.stats" | sed -E 's/.*\(contact/(contact/')
[ -n "$reference" ] && [ -n "$unshifted" ] || fail "ratchet: no counts"
[ "$(sed -E 's/.*\(contact/(contact/' <<<"$reference")" = "$unshifted" ] || fail "ratchet 1e-30: '$reference', unshifted '$unshifted'"
for round in 1 2 3; do
  k=$((31 + RANDOM % 90))
  value="$((1 + RANDOM % 9))e-$k"
  offset_centre "$models/ratchet.json" "$work/ratchet-small-$round.model.json" "$value"
  timeout 60 "$hipair" cspace "$work/ratchet-small-$round.model.json" --stats --json "$work/ratchet-small-$round.json" \
    >"$work/ratchet-small-$round.stats" 2>&1 || fail "ratchet $value: $(head -c 300 "$work/ratchet-small-$round.stats")"
  [ "$(counts "$work/ratchet-small-$round.stats")" = "$reference" ] ||
    fail "ratchet $value: '$(counts "$work/ratchet-small-$round.stats")', at 1e-30 '$reference'"
done

# certify --at: the literals' exponent limit
lever=$models/lever-stop.json
for value in 1e1001 -1e-1001 1e1001deg 3e+1234; do
  "$hipair" certify "$lever" --claim interference --at "lever=$value" --out "$work/at.json" >"$work/at.out" 2>&1
  rc=$?
  [ $rc -eq 2 ] || fail "--at lever=$value: exit $rc (expected 2): $(head -c 300 "$work/at.out")"
  grep -qE -- "--at .*out of range: the decimal exponent is limited to 1000" "$work/at.out" ||
    fail "--at lever=$value: $(head -c 300 "$work/at.out")"
  [ ! -e "$work/at.json" ] || fail "--at lever=$value: a certificate was written"
done
"$hipair" certify "$lever" --claim interference --at lever=1e1000 --out "$work/at.json" >"$work/at.out" 2>&1
grep -q "out of range" "$work/at.out" && fail "--at lever=1e1000 refused as out of range: $(head -c 300 "$work/at.out")"

[ $failures -eq 0 ] && echo "fine75 CLI tests passed"
exit $((failures > 0))
