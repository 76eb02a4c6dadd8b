#!/usr/bin/env bash
# Command-line behaviour of `hipair`: help, validation of every example and every bad model
# (one error line, non-zero exit, no crash), atomic outputs (a failure leaves no file behind
# and never clobbers an existing one).
# usage: run_cli_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$hipair" --help >"$work/help.txt" 2>&1 || fail "--help exits non-zero"
grep -q "validate" "$work/help.txt" || fail "--help does not list validate"

for model in "$source"/examples/models/*.json; do
  name=$(basename "$model" .json)
  "$hipair" validate "$model" >"$work/$name.validate.txt" 2>&1 \
    || fail "validate rejects example $name: $(tail -n 3 "$work/$name.validate.txt")"
  "$hipair" show "$model" --svg "$work/$name.svg" >/dev/null 2>"$work/$name.show.err" \
    || fail "show fails on example $name: $(cat "$work/$name.show.err")"
  [ -s "$work/$name.svg" ] || fail "show wrote no SVG for $name"
  grep -q "</svg>" "$work/$name.svg" 2>/dev/null || fail "SVG for $name is not complete"
done

shopt -s nullglob
bad_models=("$source"/tests/data/bad/*.json)
[ ${#bad_models[@]} -ge 30 ] || fail "only ${#bad_models[@]} bad models in tests/data/bad (want >= 30)"
for model in "${bad_models[@]}"; do
  name=$(basename "$model" .json)
  echo "old" >"$work/bad-$name.svg"
  "$hipair" show "$model" --svg "$work/bad-$name.svg" >/dev/null 2>"$work/bad-$name.err"
  code=$?
  if [ $code -eq 0 ]; then fail "show accepts bad model $name"; continue; fi
  [ $code -ge 128 ] && fail "show crashed on $name (exit $code)"
  [ "$(wc -l <"$work/bad-$name.err")" -eq 1 ] || fail "bad model $name: not exactly one error line: $(cat "$work/bad-$name.err")"
  grep -q "^hipair: error: " "$work/bad-$name.err" || fail "bad model $name: message not prefixed: $(cat "$work/bad-$name.err")"
  [ "$(cat "$work/bad-$name.svg")" = "old" ] || fail "bad model $name clobbered an existing output"
  "$hipair" validate "$model" >/dev/null 2>&1
  code=$?
  { [ $code -ne 0 ] && [ $code -lt 128 ]; } || fail "validate exit code $code on bad model $name"
done

# Output into a directory that does not exist: clear error, nothing written.
"$hipair" show "$source/examples/models/geneva.json" --svg "$work/no/such/dir/x.svg" >/dev/null 2>"$work/nodir.err"
[ $? -ne 0 ] || fail "show into a missing directory succeeded"
grep -q "^hipair: error: " "$work/nodir.err" || fail "missing directory: unclear message: $(cat "$work/nodir.err")"

# A missing model file.
"$hipair" validate "$work/does-not-exist.json" >/dev/null 2>"$work/missing.err"
[ $? -ne 0 ] || fail "validate of a missing file succeeded"
grep -q "does-not-exist.json" "$work/missing.err" || fail "missing file not named: $(cat "$work/missing.err")"

# Out of memory (also inside GMP, which aborted with "GNU MP: Cannot allocate memory", exit
# 134): exit 4 and one line, no output file.
(ulimit -v 200000; "$hipair" cspace "$source/examples/models/spur-gears.json" --json "$work/oom.json" \
  >/dev/null 2>"$work/oom.err")
code=$?
[ $code -eq 4 ] || fail "out of memory: exit $code, want 4: $(tail -c 300 "$work/oom.err")"
[ "$(wc -l <"$work/oom.err")" -eq 1 ] && grep -q "^hipair: error: out of memory" "$work/oom.err" \
  || fail "out of memory: not one clear line: $(tail -c 300 "$work/oom.err")"
[ -e "$work/oom.json" ] && fail "out of memory left an output file"

# A Geneva pair whose locking clearance is closed (locking arc radius = wheel's locking
# radius): the jammed run with its pictures finishes (the C-space build crashed in CGAL on the
# coincident arcs, or the picture never finished).
sed 's/"lock-outer-radius": { "nominal": 46.0/"lock-outer-radius": { "nominal": 46.683/' \
  "$source/examples/models/geneva-template.json" >"$work/geneva-closed.json"
timeout 120 "$hipair" analyze "$work/geneva-closed.json" --out "$work/geneva-closed" >"$work/geneva-closed.out" 2>&1
code=$?
[ $code -eq 0 ] || fail "analyze --out on the closed-clearance Geneva: exit $code: $(tail -c 300 "$work/geneva-closed.out")"
for file in report.json kinematics.csv kinematics.svg cspace-driver-wheel.svg; do
  [ -s "$work/geneva-closed/$file" ] || fail "closed-clearance Geneva: no $file"
done
grep -q "</svg>" "$work/geneva-closed/cspace-driver-wheel.svg" 2>/dev/null || fail "closed-clearance Geneva: C-space SVG incomplete"

# No stray temporary files left by atomic writes.
ls -a "$work" | grep -q '\.tmp' && fail "temporary files left behind"

if [ $failures -ne 0 ]; then
  echo "$failures CLI check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
