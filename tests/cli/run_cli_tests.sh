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

# A zero-clearance fit (issue 9): the crank pin in a slot of exactly its diameter runs on a
# touching channel: a contact, not an interference.
exact_fit="$source/tests/data/zero-clearance/scotch-yoke-exact-fit.json"
"$hipair" analyze "$exact_fit" --driver crank >"$work/exact-fit.txt" 2>&1 \
  || fail "analyze fails on the exact fit: $(tail -n 3 "$work/exact-fit.txt")"
grep -q "INTERFERENCE" "$work/exact-fit.txt" && fail "analyze reports the exact fit as an interference"
grep -q "guided with zero clearance" "$work/exact-fit.txt" || fail "analyze does not report the zero-clearance contact"
"$hipair" cspace "$exact_fit" --pair crank:yoke --stats --svg "$work/exact-fit-cspace.svg" >"$work/exact-fit-stats.txt" 2>&1 \
  || fail "cspace fails on the exact fit: $(tail -n 3 "$work/exact-fit-stats.txt")"
grep -q "touching edges" "$work/exact-fit-stats.txt" || fail "cspace --stats shows no touching edge for the exact fit"
grep -q "zero clearance" "$work/exact-fit-cspace.svg" || fail "the C-space picture does not draw the zero-clearance channel"

# No stray temporary files left by atomic writes.
ls -a "$work" | grep -q '\.tmp' && fail "temporary files left behind"

if [ $failures -ne 0 ]; then
  echo "$failures CLI check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
