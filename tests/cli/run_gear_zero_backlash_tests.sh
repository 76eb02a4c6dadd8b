#!/usr/bin/env bash
# Spur gears at zero backlash, session 47 (hunt47): docs/certify.md "Session 47 (hunt47)".
# Generated pairs of spur-gears.json's gears (z1 in 6..30 teeth, z2 in z1..z1+12), the backlash
# parameter 0 and the centre distance exactly the sum of the pitch radii. `analyze --range 0:0.3
# --out` is run and every claim of its report is checked:
#  - its verdict at the initial configuration ("INTERFERENCE at the initial configuration" or
#    "no parts overlap") against the exact overlap predicate: `certify --claim interference` at
#    the initial configuration (exit 0 only with a point strictly inside both parts) and
#    hipair-verify, which re-checks the point exactly;
#  - every certificate it writes verifies;
#  - a BLOCKED verdict names its blocking contacts, or says that no contact bounds the blocked
#    range (base47 printed "Blocking contacts: " followed by nothing);
#  - "the analysis starts from the nearest position where they only touch" is said only when the
#    analysis found such a position (a follower piece); base47 said it and then stopped at once;
#  - where no position is free, the uncertified jam's note does not blame the quasi-static model;
#  - a jam it could not certify does not say "the parts overlap at the start" next to
#    "Initial configuration: no parts overlap" (base47: the jam search's own start, from the
#    analysis's double samples, overlapped; the note did not say which start);
#  - with no position of the gear on the path, no play is reported (session 48: base48 printed
#    "Play ... 0.000° all along").
# usage: run_gear_zero_backlash_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"

gears() {   # Z1 Z2 FILE
  python3 - "$source/examples/models/spur-gears.json" "$@" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
t['parameters']['teeth-1'] = {'nominal': int(sys.argv[2])}
t['parameters']['teeth-2'] = {'nominal': int(sys.argv[3])}
t['parameters']['backlash'] = {'nominal': 0}
t['parameters']['center-distance'] = {'nominal': 'module * (teeth-1 + teeth-2) / 2'}
json.dump(t, open(sys.argv[4], 'w'), indent=1)
PY
}

# two small pairs (where the zero-backlash profiles overlap at the start), one near 17 teeth
# (where they mesh and jam), one random pair of 6..30 teeth
pairs=("$((RANDOM % 5 + 6)) $((RANDOM % 3 + 7))" "$((RANDOM % 4 + 11)) $((RANDOM % 4 + 12))"
       "$((RANDOM % 2 + 17)) $((RANDOM % 2 + 17))" "$((RANDOM % 25 + 6)) 0")
for p in "${pairs[@]}"; do
  set -- $p
  z1=$1 z2=$2
  [ "$z2" -eq 0 ] && z2=$((z1 + RANDOM % 13))
  what="$z1 x $z2 teeth, zero backlash"
  model=$work/gears-$z1-$z2.json
  out=$work/out-$z1-$z2
  gears "$z1" "$z2" "$model"
  timeout 200 "$hipair" analyze "$model" --range 0:0.3 --no-pictures --quiet --out "$out" >"$out.txt" 2>"$out.err" ||
    { fail "$what: analyze: exit $?: $(head -c 300 "$out.err")"; continue; }
  "$hipair" certify "$model" --claim interference --out "$work/i.json" >"$work/i.out" 2>&1
  certified=$?
  if [ $certified -eq 0 ]; then
    "$verify" "$work/i.json" "$model" >"$work/v.out" 2>&1 || fail "$what: hipair-verify rejects the start's interference: $(cat "$work/v.out")"
    grep -q "^INTERFERENCE at the initial configuration: pinion:gear" "$out.txt" ||
      fail "$what: the start overlaps (certified, verified), analyze says: $(grep -m1 'Initial configuration' "$out.txt")"
  elif [ $certified -eq 1 ]; then
    grep -q "^INTERFERENCE at the initial configuration" "$out.txt" &&
      fail "$what: analyze reports interference at the start, no point inside both parts exists: $(tail -c 200 "$work/i.out")"
  else
    fail "$what: certify --claim interference: exit $certified: $(tail -c 300 "$work/i.out")"
  fi
  for c in "$out"/certificate-*.json; do
    [ -e "$c" ] || continue
    "$verify" "$c" "$model" >"$work/v.out" 2>&1 || fail "$what: analyze wrote $(basename "$c"), hipair-verify: $(cat "$work/v.out")"
  done
  if grep -q "^Blocking: the driver is BLOCKED" "$out.txt"; then
    line=$(grep -m1 "^  Blocking contacts:" "$out.txt")
    [ -n "${line#  Blocking contacts:}" ] && [ "${line#  Blocking contacts: }" != "" ] ||
      fail "$what: BLOCKED, and the blocking contacts are an empty list: '$line'"
    # "no position of gear is free" at the initial driver position: the gear at 12 generated
    # angles over one tooth pitch must each overlap the pinion (certify + hipair-verify)
    if [[ $line == *"no position of gear is free"* ]]; then
      grep -q "BLOCKED at 0.000°" "$out.txt" || fail "$what: no free position said away from the start: $(grep -m1 BLOCKED "$out.txt")"
      for k in $(seq 0 11); do
        angle=$(python3 -c "import math, random; random.seed($seed * 100 + $k); print(repr(($k + random.random()) / 12 * 2 * math.pi / $z2))")
        "$hipair" certify "$model" --claim interference --at pinion=0 --at "gear=$angle" --out "$work/g.json" >"$work/g.out" 2>&1 &&
          "$verify" "$work/g.json" "$model" >"$work/v.out" 2>&1 ||
          fail "$what: 'no position of gear is free', yet at gear $angle rad no overlap is certified: $(tail -c 200 "$work/g.out")"
      done
    fi
  fi
  # overlapping at the start and stopped there: the jam is no quasi-static effect
  if grep -q "^INTERFERENCE at the initial configuration" "$out.txt" && grep -q "BLOCKED at 0.000°" "$out.txt" &&
     grep -q "^not certified: jam: .*the stop comes from the quasi-static" "$out.txt"; then
    fail "$what: stopped at an overlapping start, and the jam's note says the stop comes from the quasi-static model"
  fi
  if grep -q "starts from the nearest position where they only touch" "$out.txt" &&
     grep -q "In all: 0 drive periods .* and 0 dwell periods" "$out.txt"; then
    fail "$what: 'starts from the nearest position where they only touch', then no motion at all: $(grep -m1 BLOCKED "$out.txt")"
  fi
  # no sample of the gear on the path: no play to report (base48 printed "Play ... 0.000° all
  # along" from a summary of zeros; session 48, hunt48)
  if ! grep -q "In all: 0 drive periods .* and 0 dwell periods" "$out.txt"; then :
  elif grep -q "^  Play (backlash" "$out.txt" || ! grep -q "^  Play: not measured: the analysis has no position of gear" "$out.txt"; then
    fail "$what: no position of the gear on the path, and the report says: $(grep -m1 '^  Play' "$out.txt")"
  fi
  if grep -q "^Initial configuration: no parts overlap" "$out.txt" && grep -q "(the parts overlap at the start)" "$out.txt"; then
    fail "$what: 'no parts overlap' at the start and a note 'the parts overlap at the start': $(grep -m1 'not certified' "$out.txt")"
  fi
done

if [ $failures -gt 0 ]; then
  echo "$failures failure(s) (seed $seed)"
  exit 1
fi
echo "gear zero-backlash tests passed (seed $seed)"
