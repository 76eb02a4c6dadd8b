#!/usr/bin/env bash
# An operating region around an overlapping start, session 45 (hunt45): docs/cli.md "cspace".
# The lever of lever-stop.json against its stop made to turn (about (45, 30)), the stop's face
# moved into the lever by a generated overlap (10^-k mm, k in 1..12, or a random fraction of a
# mm): the start (both parts at angle 0) overlaps, which certify --claim interference proves and
# hipair-verify accepts (the exact overlap predicate). `cspace --region operating` must refuse it,
# exit 3, "the parts certainly overlap at the seed configuration", nothing written: until session
# 45 an overlap shallower than the region's quadtree cell was built as a region around a blocked
# start (exit 0, a free and a blocked cell), a deeper one refused. Controls: the stop's face
# exactly on the lever (zero clearance: touching, no interference certificate) and the model's own
# gap build, exit 0. Generated cases (a seed per run, printed on failure; HIPAIR_TEST_SEED repeats
# one).
# usage: run_blocked_start_tests.sh HIPAIR_BINARY HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"
# the model with its stop-gap's nominal value G (no tolerance): a certificate holds for the file
turning_stop() {   # G FILE
  python3 - "$source/examples/models/lever-stop.json" "$1" "$2" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
t['parameters']['stop-gap'] = {'nominal': sys.argv[2]}
t['parts'][1]['motion'] = {'rotation': {'pivot': [45, 30]}}
t['parts'][1]['initial'] = {'angle': 0}
json.dump(t, open(sys.argv[3], 'w'), indent=1)
PY
}
gaps=("-1e-$((RANDOM % 12 + 1))" "-$((RANDOM % 999 + 1))/1000")
for g in "${gaps[@]}"; do
  what="stop-gap $g"
  model=$work/turning-stop.json
  turning_stop "$g" "$model"
  # the start overlaps: proved by the exact predicate (certify + hipair-verify)
  "$hipair" certify "$model" --claim interference --at lever=0 --at stop=0 --out "$work/i.json" \
    >"$work/i.out" 2>&1 || { fail "$what: the start's interference is not certified: $(tail -c 300 "$work/i.out")"; continue; }
  "$verify" "$work/i.json" "$model" >"$work/v.out" 2>&1 || fail "$what: hipair-verify: $(cat "$work/v.out")"
  rm -f "$work/x.json"
  timeout 120 "$hipair" cspace "$model" --region operating --json "$work/x.json" >"$work/c.out" 2>"$work/c.err"
  code=$?
  [ $code -eq 3 ] || fail "$what: cspace --region operating: exit $code, want 3: $(head -c 300 "$work/c.err")"
  grep -qF "hipair: error: operating region of 'lever' and 'stop': the parts certainly overlap at the seed configuration" \
    "$work/c.err" || fail "$what: message: $(head -c 300 "$work/c.err")"
  [ "$(wc -l <"$work/c.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/c.err")"
  [ -e "$work/x.json" ] && fail "$what: wrote --json"
done
# controls: touching at the start (no interference), and the model's own gap
for g in 0 2; do
  model=$work/turning-stop-$g.json
  turning_stop "$g" "$model"
  "$hipair" certify "$model" --claim interference --at lever=0 --at stop=0 --out "$work/i.json" >"$work/i.out" 2>&1
  [ $? -eq 1 ] || fail "stop-gap $g: an interference at the start was certified: $(tail -c 300 "$work/i.out")"
  timeout 120 "$hipair" cspace "$model" --region operating --json "$work/ok.json" >"$work/ok.out" 2>&1 ||
    fail "stop-gap $g: cspace --region operating: exit $?: $(tail -c 300 "$work/ok.out")"
done

# The oracle of a start: certify --claim interference at the initial configuration and
# hipair-verify. An overlap proved must be refused by cspace --region operating (exit 3, one line
# containing MESSAGE, no --json written); parts that do not overlap must build (exit 0, and
# with WANT_JSON 1 the --json written).
check_start() {   # WHAT MODEL MESSAGE WANT_JSON
  local what=$1 model=$2 message=$3 want_json=$4 certified code
  "$hipair" certify "$model" --claim interference --out "$work/i.json" >"$work/i.out" 2>&1
  certified=$?
  rm -f "$work/x.json"
  timeout 120 "$hipair" cspace "$model" --region operating --json "$work/x.json" >"$work/c.out" 2>"$work/c.err"
  code=$?
  if [ $certified -eq 0 ]; then
    "$verify" "$work/i.json" "$model" >"$work/v.out" 2>&1 || { fail "$what: hipair-verify: $(cat "$work/v.out")"; return; }
    [ $code -eq 3 ] || fail "$what: overlap verified, cspace --region operating: exit $code, want 3: $(head -c 300 "$work/c.err")"
    grep -qF "$message" "$work/c.err" || fail "$what: message: $(head -c 300 "$work/c.err")"
    [ "$(wc -l <"$work/c.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/c.err")"
    [ -e "$work/x.json" ] && fail "$what: wrote --json"
  elif [ $certified -eq 1 ]; then
    [ $code -eq 0 ] || fail "$what: no overlap (certify: $(tail -c 100 "$work/i.out")), cspace --region operating: exit $code: $(head -c 300 "$work/c.err")"
    [ "$want_json" = 1 ] && { [ -s "$work/x.json" ] || fail "$what: no overlap, and no --json written"; }
  else
    fail "$what: certify --claim interference: exit $certified: $(tail -c 300 "$work/i.out")"
  fi
}

# Session 46 (hunt46): starts at other angles (a transcendental half-angle tangent) and 1-D
# regions. The lever turned to its contact angle with the stop's corner (40, 6) plus a generated
# delta (+-10^-k deg, k in 1..9, or a random fraction of a degree), the stop fixed (a 1-D pair) or
# turning about (45, 30) by 0 or +-10^-k deg (its corner moved with it, the contact angle solved
# for the moved corner in doubles, far below the deltas). The oracle: certify --claim
# interference at the initial configuration (angles rounded within 1e-17 rad) and hipair-verify;
# an overlap proved must be refused (exit 3, the message, nothing written; base46 wrote a region:
# exit 0), parts that do not overlap must build (exit 0). Until session 46 the check ran only at
# angle 0 and only in 2-D.
at_angle() {   # DELTA_DEG STOP_DEG KIND(fixed|turn) FILE
  python3 - "$source/examples/models/lever-stop.json" "$@" <<'PY2'
import json, math, sys
src, delta, stop_deg, kind, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4], sys.argv[5]
t = json.load(open(src))
s = math.radians(stop_deg) if kind == 'turn' else 0.0
px, py = 45 + math.cos(s) * (40 - 45) - math.sin(s) * (6 - 30), 30 + math.sin(s) * (40 - 45) + math.cos(s) * (6 - 30)
# the lever's upper side (y = 4 at angle 0) through the corner: -px sin a + py cos a = 4
r, phi = math.hypot(px, py), math.atan2(px, py)
contact = math.degrees(math.acos(4 / r) - phi)
if kind == 'turn':
    t['parts'][1]['motion'] = {'rotation': {'pivot': [45, 30]}}
    t['parts'][1]['initial'] = {'angle': stop_deg}
t['parts'][0]['initial'] = {'angle': contact + delta}
json.dump(t, open(out, 'w'), indent=1)
PY2
}
for round in 1 2 3 4 5 6; do
  kinds=(fixed turn)
  kind=${kinds[$((RANDOM % 2))]}
  sign=$([ $((RANDOM % 3)) -eq 0 ] && echo - || echo)
  delta=$sign$([ $((RANDOM % 4)) -eq 0 ] && echo "0.$((RANDOM % 900 + 100))" || echo "1e-$((RANDOM % 9 + 1))")
  stop=0
  [ "$kind" = turn ] && [ $((RANDOM % 2)) -eq 0 ] && stop=$([ $((RANDOM % 2)) -eq 0 ] && echo - || echo)1e-$((RANDOM % 6 + 2))
  what="lever at contact ${delta} deg, stop $kind at $stop deg"
  model=$work/angle-$round.json
  at_angle "$delta" "$stop" "$kind" "$model"
  check_start "$what" "$model" "hipair: error: operating region of 'lever' and 'stop': the parts certainly overlap at the seed configuration" 0
done

# Session 65 (perf65): spur gears at zero backlash (tests/fuzz/zero_backlash_gears.py), where the
# arc flanks interfere at the start for many tooth counts. An exact start whose parts' interiors
# meet (the exact overlap predicate) is refused before the channel is built: base65 built the
# whole operating region first and then located the start in a blocked cell, the same refusal
# after 38 s of CPU for the 19 x 40 pair (coprime tooth counts: the channel meets every tooth
# pair, 8 058 tiles). The new refusal says it came from the predicate ("by the exact overlap
# predicate"; base65: "lies in blocked space of the exact C-space built around it"). Cases: the
# 19 x 40 pair hunt64 found, a generated pair of 6..16 teeth with a gear of z1 or 2 z1 teeth
# (most such starts overlap), and the controls 17 x 17 and 18 x 18 (their starts do not overlap:
# the region is built, exit 0). The oracle: certify --claim interference at the start and
# hipair-verify.
z=$((RANDOM % 11 + 6))
for p in "19 40" "$z $((z * (RANDOM % 2 + 1)))" "17 17" "18 18"; do
  set -- $p
  what="spur gears $1 x $2, zero backlash"
  model=$work/gears-$1-$2.json
  python3 "$source/tests/fuzz/zero_backlash_gears.py" "$source/examples/models/spur-gears.json" "$1" "$2" "$model"
  check_start "$what" "$model" "hipair: error: operating region of 'pinion' and 'gear': the parts certainly overlap at the seed configuration (their interiors meet at the initial configuration, by the exact overlap predicate" 1
done
[ "$p" = "18 18" ] || fail "the gear cases did not all run"

if [ $failures -gt 0 ]; then
  echo "$failures failure(s) (seed $seed)"
  exit 1
fi
echo "blocked-start tests passed (seed $seed)"
