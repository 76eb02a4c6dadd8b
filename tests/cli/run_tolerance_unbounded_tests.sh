#!/usr/bin/env bash
# `hipair tolerance --certify` over a driver range where the follower's channel has one side only
# (session 51, hunt51): scotch-yoke.json from a generated start of 2.5 .. 5 rad, where the yoke,
# started at its initial offset 0 (or pushed to the nearest touching position), has the crank pin
# outside its slot. The certificate is undecided, and the message must say where in the units the
# option takes and the report shows (rad and deg), which part has no contact on which side, and
# what makes the range certifiable (it said only "not bounded on both sides at driver 2.500000").
# A range starting inside the slot (0 .. 0.3 rad) still certifies.
# usage: run_tolerance_unbounded_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_test.sh" "$@"
yoke="$source/examples/models/scotch-yoke.json"
for case in 1 2 3 4 5 6; do
  start=$(awk -v r=$RANDOM 'BEGIN { printf "%.3f", 2.5 + 2.5 * r / 32768 }')
  end=$(awk -v s="$start" 'BEGIN { printf "%.3f", s + 0.05 }')
  out="$work/u$case"
  "$hipair" tolerance "$yoke" --range "$start:$end" --certify --quiet >"$out.txt" 2>&1
  code=$?
  [ $code -eq 0 ] || fail "--range $start:$end: exit $code: $(tail -n 2 "$out.txt")"
  line=$(grep "undecided (no certificate)" "$out.txt")
  [ -n "$line" ] || { fail "--range $start:$end: not undecided: $(grep -A1 'certificate (' "$out.txt")"; continue; }
  deg=$(awk -v s="$start" 'BEGIN { printf "%.6g", s * 180 / 3.14159265358979 }')
  grep -qF "at driver $(awk -v s="$start" 'BEGIN { printf "%.6g", s }') rad ($deg deg)" <<<"$line" \
    || fail "--range $start:$end: the driver is not given in rad and deg: $line"
  grep -qE "'yoke' at -?[0-9.e+-]+ mm has no contact (above it \(increasing|below it \(decreasing|on either side)" <<<"$line" \
    || fail "--range $start:$end: the message does not say which side of the yoke is open: $line"
  grep -qF "start the range where the pair is engaged" <<<"$line" \
    || fail "--range $start:$end: the message does not say what makes the range certifiable: $line"
done
start=$(awk -v r=$RANDOM 'BEGIN { printf "%.3f", 0.25 * r / 32768 }')
"$hipair" tolerance "$yoke" --range "$start:$(awk -v s="$start" 'BEGIN { printf "%.3f", s + 0.05 }')" --certify --quiet \
  >"$work/inside.txt" 2>&1 || fail "--range from $start: exit non-zero"
grep -q "CERTIFIED" "$work/inside.txt" || fail "--range from $start (inside the slot): not certified: $(grep -A1 'certificate (' "$work/inside.txt")"
[ $failures -eq 0 ] && echo "tolerance unbounded-channel tests passed (seed $seed)"
exit $((failures > 0))
