#!/usr/bin/env bash
# `hipair certify --claim connected` and `hipair-verify` on sliced_connected certificates (session
# 68): the 10 mm square peg of examples/models/peg-in-hole.json turns a quarter in a 14.15 mm hole
# (certified, verified) but not in a 14.14 mm one (exit 1, not certified: "different components"
# is the sliced C-space's verdict; `--claim apart` certifies it: run_certify_apart_tests.sh); the certificate edited
# (an end moved, a vertex moved so that a move passes through the plate, the statement) is
# invalid with its reason; bad input exits 2 naming the option, nothing written.
# usage: run_certify_connected_tests.sh HIPAIR_BINARY HIPAIR_VERIFY_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"

for hole in 14.15 14.14; do
  sed "s/\"hole-side\": { \"nominal\": 12 }/\"hole-side\": { \"nominal\": $hole }/" "$source/examples/models/peg-in-hole.json" >"$work/peg-$hole.json"
done
wide="$work/peg-14.15.json" narrow="$work/peg-14.14.json"
"$hipair" certify "$wide" --claim connected --at peg=0,0,0 --to peg=0,0,90deg --out "$work/turn.json" >"$work/turn.out" 2>&1 \
  || fail "certify --claim connected refuses the peg turning in the 14.15 mm hole: $(cat "$work/turn.out")"
grep -qF "certified sliced_connected: Part 'peg' moves from x=0, y=0, t=0 to x=0, y=0, t=1 without touching part 'plate'." "$work/turn.out" \
  || fail "certify --claim connected: not the statement: $(cat "$work/turn.out")"
out=$("$verify" "$work/turn.json" "$wide") || fail "hipair-verify refuses the connected certificate: $out"
case "$out" in "valid: sliced_connected: part 'peg' moves from x=0, y=0, t=0 to x=0, y=0, t=1 without touching 'plate'"*) ;;
  *) fail "hipair-verify: not the summary: $out" ;; esac
# the same certificate on the narrow hole's file: the content hash differs
out=$("$verify" "$work/turn.json" "$narrow") && fail "the certificate verifies on the 14.14 mm hole"
case "$out" in "invalid: model hash mismatch"*) ;; *) fail "narrow hole: not a hash mismatch: $out" ;; esac

"$hipair" certify "$narrow" --claim connected --at peg=0,0,0 --to peg=0,0,90deg --out "$work/stuck.json" >"$work/stuck.out" 2>&1
[ $? -eq 1 ] && [ ! -e "$work/stuck.json" ] || fail "the 14.14 mm hole: certified or not exit 1: $(cat "$work/stuck.out")"
grep -qF "different components of the sliced free space (not certified" "$work/stuck.out" || fail "the 14.14 mm hole: $(cat "$work/stuck.out")"

# edited certificates
mutate() { mutate_certificate "$work/turn.json" sliced_connected "$wide" "$@"; }   # NAME PYTHON-STATEMENTS-ON-c-AND-body MESSAGE
mutate end-moved 'body["to"]["x"] = "1/10"' "the path ends at x=0, y=0, t=1, not at the claim's end x=1/10"
mutate through-plate 'body["path"].insert(1, ["20", "0", "0"])' "move 0 (x=0, y=0, t=0 to x=20, y=0, t=0): the parts overlap"
mutate turned-off-centre 'body["path"] = [["0", "0", "0"], ["1", "0", "0"], ["1", "0", "1"], ["0", "0", "1"]]' "move 1 (x=1, y=0, t=0 to x=1, y=0, t=1): the parts overlap"
mutate diagonal 'body["path"] = [["0", "0", "0"], ["0", "1/1000", "1"], ["0", "0", "1"]]' "move 0 (x=0, y=0, t=0 to x=0, y=1/1000, t=1): it changes both the offset and the rotation"
mutate statement 'c["statement"] = c["statement"].replace("plate", "nothing")' "the statement does not say what the claim's data prove"
mutate unknown-key 'body["speed"] = "1"' "malformed certificate: /sliced_connected/speed: unknown key 'speed'"

# bad input: exit 2, nothing written
refused() {   # NAME MESSAGE ARGS...
  local name=$1 message=$2; shift 2
  "$hipair" certify "$@" --out "$work/$name.json" >"$work/$name.out" 2>&1
  local got=$?
  [ $got -eq 2 ] || fail "certify $* : exit $got, not 2: $(cat "$work/$name.out")"
  grep -qF -- "$message" "$work/$name.out" || fail "certify $* : message not '$message': $(cat "$work/$name.out")"
  [ -e "$work/$name.json" ] && fail "certify $* wrote output although it was refused"
}
refused no-to "--claim connected needs --to peg=X,Y,ANGLE" "$wide" --claim connected --at peg=0,0,0
refused bad-to "--to expects peg=X,Y,ANGLE" "$wide" --claim connected --to peg=0,0
refused not-planar "--claim connected: the pair lever:stop must be a fixed part and a part free in the plane" \
  "$source/examples/models/lever-stop.json" --claim connected --to lever=0,0,0
refused distance "--distance: applies to --claim clearance or free, not to --claim connected" "$wide" --claim connected --to peg=0,0,0 --distance 1

if [ $failures -ne 0 ]; then
  echo "$failures connected certify CLI check(s) failed"
  exit 1
fi
echo "all connected certify CLI checks passed"
