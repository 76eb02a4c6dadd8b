#!/usr/bin/env bash
# `hipair simulate` on values beyond the doubles' range and a bare unknown argument, session 43
# (hunt43). Generated cases (a seed per run, printed on failure):
#  1. a bundled simulation model with one value of its dynamics data (a pair's friction, a
#     driver's speed, a mass, an initial velocity, a spring's rest) or a moving part's initial
#     coordinate set to ±1e{309..1000} or ±1e-{309..1000}: exit 2, one line naming the value's
#     JSON pointer, no signal, and an existing --out directory left as it was (main 0bdc449 died
#     of SIGFPE — GMP's mpq_set_d(inf) — on a friction, a driver speed or an initial angle of
#     1e400, and integrated a non-finite state on a mass or velocity of 1e400);
#  2. `hipair --OPTION` and `hipair WORD` (no subcommand): exit 109 naming the argument (main said
#     "A subcommand is required" and named neither).
#  3. a rotating driver too fast for the doubles (session 59, escape59): cam-drive.json or
#     geneva-drive.json with the driver at ±1e{154..307} rad/s (written into the model, or with
#     --set on a widened tolerance): exit 2, one line naming /simulation/drivers/0/speed, the driver
#     and the doubles' range, --out left as it was (base59 said "the integration produced a
#     non-finite state (a singular contact constraint?)" or "a jammed contact change", exit 3);
#     at half the largest speed the message gives, the run is not refused and does not end in a
#     non-finite state.
#  4. a driver fast enough that the time in seconds cannot resolve the steps the accuracy asks for
#     (session 59, speed59, found it; session 60, geneva60, fixed it: the simulator integrates in
#     a time unit of 2^-e s at such speeds): geneva-drive.json at 1e{10..20} rad/s (--set,
#     --allow-out-of-tolerance) over 100 rad of the driver: exit 0, and the events of the run at
#     1 rad/s over 100 s (the wheel carries no load: the motion in w t is the same at every w):
#     the same kinds and feature pairs, driver angles w t within 1e-6 rad (base60 stopped with
#     exit 3, "10000 steps in a row did not move the time on").
#  (5., 6. and 7.: see there, session 60)
# usage: run_simulate_range_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"

# refused_simulate WHAT POINTER_TEXT REASON_REGEX [ARG...]: `simulate $model ARG...` into a kept --out
# exits 2 with one line holding POINTER_TEXT (fixed) and REASON_REGEX (grep), --out left as it
# was; returns 1 (after a failure) when the exit status was not 2
refused_simulate() {
  local what=$1 pointer_text=$2 reason=$3 status
  shift 3
  rm -rf "$work/out" && mkdir -p "$work/out" && echo keep >"$work/out/sentinel"
  timeout 120 "$hipair" simulate "$model" --t-end 0.01 --no-pictures "$@" --out "$work/out" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  [ "$status" -eq 2 ] || { fail "$what: exit $status, not 2: $(head -c 300 "$work/bad.err")"; return 1; }
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/bad.err")"
  grep -qF -- "$pointer_text" "$work/bad.err" || fail "$what: the message names no $pointer_text: $(head -c 300 "$work/bad.err")"
  grep -q "$reason" "$work/bad.err" || fail "$what: no reason ($reason): $(head -c 300 "$work/bad.err")"
  [ "$(ls "$work/out")" = sentinel ] && [ "$(cat "$work/out/sentinel")" = keep ] || fail "$what: --out changed: $(ls "$work/out")"
}

# MODEL POINTER (JSON pointer of the value to set; the key is created if absent)
cases=(
  "cam-drive.json /pairs/0/friction"
  "cam-drive.json /simulation/drivers/0/speed"
  "cam-drive.json /parts/0/initial/angle"
  "cam-drive.json /parts/1/dynamics/mass"
  "bouncing-bar.json /parts/0/initial/angle"
  "bouncing-bar.json /simulation/velocities/bar"
  "bouncing-bar.json /parts/0/dynamics/torsional_spring/rest"
  "spring-block.json /parts/1/initial/x"
  "spring-block.json /simulation/springs/0/rest_length"
  "spring-block.json /simulation/gravity/1"
)
for c in "${cases[@]}"; do
  read -r file pointer <<<"$c"
  for round in 1 2; do
    # (from 311: cam-drive.json is in degrees, and 1e309 or 1e310 deg is 1.7e307 or 1.7e308 rad,
    # inside the doubles: not refused, a failure of 2 seeds in 692 per angle case; hunt60, seed 21)
    exponent=$((311 + RANDOM % 690))
    sign=$([ $((RANDOM % 2)) -eq 0 ] && echo "" || echo "-")
    # huge in round 1; tiny (nonzero) in round 2 only where the value is dynamics data (an
    # initial coordinate below the range is harmless: it is 0 in doubles)
    if [ $round -eq 2 ]; then
      case $pointer in */initial/*) continue ;; esac
      literal="${sign}1e-$exponent"
    else
      literal="${sign}1e$exponent"
    fi
    # friction, mass, rest length must not be negative: keep them positive (the sign check would
    # name the same pointer, but the range is what is tested)
    case $pointer in */friction|*/mass|*/rest_length) literal=${literal#-} ;; esac
    model="$work/m.json"
    python3 - "$source/examples/models/$file" "$pointer" "$literal" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
keys = [k for k in sys.argv[2].split('/')[1:]]
o = doc
for k in keys[:-1]:
    o = o[int(k)] if isinstance(o, list) else o[k]
last = keys[-1]
marker = "@@MARK@@"
if isinstance(o, list): o[int(last)] = marker
else: o[last] = marker
open(sys.argv[4], 'w').write(json.dumps(doc).replace('"' + marker + '"', sys.argv[3]))
PY
    refused_simulate "simulate $file with $pointer = $literal" "$pointer: " "too \(large\|small\) for the simulator"
  done
done

# 2. no subcommand, an unknown argument
for arg in --bogus -q --t-end bogus validat; do
  "$hipair" "$arg" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  [ "$status" -eq 109 ] || fail "hipair $arg: exit $status, not 109: $(cat "$work/bad.err")"
  grep -qF -- "$arg" "$work/bad.err" || fail "hipair $arg: the message does not name it: $(cat "$work/bad.err")"
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "hipair $arg: not one line: $(cat "$work/bad.err")"
done
"$hipair" >"$work/bad.out" 2>"$work/bad.err"
status=$?
[ "$status" -eq 106 ] && grep -q "A subcommand is required" "$work/bad.err" || fail "hipair alone: exit $status: $(cat "$work/bad.err")"

# 3. a rotating driver too fast for the doubles
for file in cam-drive.json geneva-drive.json; do
  driver=$([ "$file" = cam-drive.json ] && echo cam || echo driver)
  parameter=$([ "$file" = cam-drive.json ] && echo cam-speed || echo driver-speed)
  # (from 157: cam-drive.json is in degrees, 1e154..1e156 deg/s are 1.7e152..1.7e154 rad/s, whose
  # w^2 r fits the doubles; they ran and were not refused, a failure of 3 seeds in 154: hunt60)
  exponent=$((157 + RANDOM % 151))
  sign=$([ $((RANDOM % 2)) -eq 0 ] && echo "" || echo "-")
  for how in literal set; do
    model="$work/fast.json"
    python3 - "$source/examples/models/$file" "$parameter" "$how" "${sign}1e$exponent" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
if sys.argv[3] == 'literal':
    doc['simulation']['drivers'][0]['speed'] = float(sys.argv[4])
else:   # a tolerance wide enough for --set
    doc['parameters'][sys.argv[2]]['tolerance'] = [-1e308, 1e308]
    doc['simulation']['drivers'][0]['speed'] = sys.argv[2] + ' rad'
json.dump(doc, open(sys.argv[5], 'w'))
PY
    extra=()
    [ "$how" = set ] && extra=(--set "$parameter=${sign}1e$exponent")
    what="simulate $file with the driver at ${sign}1e$exponent rad/s ($how)"
    refused_simulate "$what" "/simulation/drivers/0/speed: driver '$driver' turns at " "beyond the doubles' range" \
      "${extra[@]}" || continue
    # half the largest speed the message gives: not refused, no non-finite state
    largest=$(sed -n "s/.*give a driver speed of at most \([0-9.e+]*\) rad.*/\1/p" "$work/bad.err")
    [ -n "$largest" ] || { fail "$what: no largest speed in the message"; continue; }
    [ "$how" = literal ] || continue
    python3 - "$source/examples/models/$file" "$largest" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc['simulation']['drivers'][0]['speed'] = float(sys.argv[2]) / 2
json.dump(doc, open(sys.argv[3], 'w'))
PY
    rm -rf "$work/out2"
    timeout 120 "$hipair" simulate "$model" --t-end 1e-150 --no-pictures --quiet --out "$work/out2" >"$work/half.out" 2>"$work/half.err"
    status=$?
    [ "$status" -eq 0 ] || [ "$status" -eq 3 ] || fail "$file at half of $largest rad/s: exit $status: $(head -c 300 "$work/half.err")"
    grep -q "non-finite state\|drivers/0" "$work/half.err" && fail "$file at half of $largest rad/s: $(head -c 300 "$work/half.err")"
  done
done

exponent=$((10 + RANDOM % 11))
t_end=$(python3 -c "print(100 / 1e$exponent)")
what="simulate geneva-drive.json with the driver at 1e$exponent rad/s"
rm -rf "$work/fast" "$work/slow"
timeout 120 "$hipair" simulate "$source/examples/models/geneva-drive.json" --t-end "$t_end" --set "driver-speed=1e$exponent" \
  --allow-out-of-tolerance --no-pictures --quiet --out "$work/fast" >"$work/res.out" 2>"$work/res.err"
status=$?
timeout 120 "$hipair" simulate "$source/examples/models/geneva-drive.json" --t-end 100 --set "driver-speed=1" \
  --allow-out-of-tolerance --no-pictures --quiet --out "$work/slow" >"$work/slow.out" 2>"$work/slow.err"
slow_status=$?
if [ "$status" -ne 0 ] || [ "$slow_status" -ne 0 ]; then
  fail "$what: exit $status (at 1 rad/s: $slow_status): $(head -c 300 "$work/res.err") $(head -c 300 "$work/slow.err")"
else
  python3 - "$work/fast/events.json" "$work/slow/events.json" "1e$exponent" <<'PY' || fail "$what: not the events of 1 rad/s"
import json, sys
fast, slow = (json.load(open(p))['events'] for p in sys.argv[1:3])
w = float(sys.argv[3])
if len(slow) < 50 or len(fast) != len(slow):
    sys.exit(print(f'{len(fast)} events, {len(slow)} at 1 rad/s') or 1)
for i, (a, b) in enumerate(zip(fast, slow)):
    if a['kind'] != b['kind'] or a['features'] != b['features'] or abs(a['time'] * w - b['time']) > 1e-6:
        sys.exit(print(f'event {i}: {a["kind"]} {a["features"]} at w t = {a["time"] * w}; at 1 rad/s '
                       f'{b["kind"]} {b["features"]} at {b["time"]}') or 1)
PY
fi

# 5. several parts free in the plane thrown or pulled beyond the doubles (session 60, hunt60;
#    tests/fuzz/simulate_mutations.py): friction-slide.json or pushed-block.json with the block's
#    initial x velocity at ±m·1e308 (m in [1, 1.79]) or gravity's y at ±m·1e308: no signal, exit 0
#    or 3 with one line and --out left as it was (base60 died of SIGFPE, GMP's mpq_set_d(inf) on the
#    query radius of a step that covered an infinite distance); since session 72 (jam72) exit 2 at
#    the datum where the initial state's energy is beyond the doubles (nothing written).
for round in 1 2 3; do
  file=$( ((RANDOM % 2)) && echo friction-slide.json || echo pushed-block.json)
  value="$( ((RANDOM % 2)) && echo - )1.$((RANDOM % 79))e308"
  where=$( ((RANDOM % 2)) && echo velocity || echo gravity)
  model="$work/huge-$round.json"
  python3 - "$source/examples/models/$file" "$where" "$value" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
if sys.argv[2] == 'velocity':
    doc['simulation'].setdefault('velocities', {})['block'] = {'x': float(sys.argv[3])}
else:
    doc['simulation']['gravity'][1] = float(sys.argv[3])
json.dump(doc, open(sys.argv[4], 'w'))
PY
  what="simulate $file with the block's $where at $value"
  rm -rf "$work/out" && mkdir -p "$work/out" && echo keep >"$work/out/sentinel"
  timeout 120 "$hipair" simulate "$model" --t-end 0.01 --max-steps 2000 --no-pictures --quiet --out "$work/out" \
    >"$work/res.out" 2>"$work/res.err"
  status=$?
  if [ "$status" -eq 2 ]; then
    # (session 72, jam72) an initial state whose energy is beyond the doubles: bad input at the
    # datum's pointer (the block's velocity or gravity's y), nothing written
    [ "$(wc -l <"$work/res.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/res.err")"
    grep -qE "^hipair: error: /simulation/(velocities/block/x|gravity/1): the initial state's energy is not finite" "$work/res.err" \
      || fail "$what: exit 2 not at the datum: $(head -c 300 "$work/res.err")"
    [ "$(ls -A "$work/out")" = sentinel ] || fail "$what: exit 2 wrote into --out: $(ls "$work/out")"
  elif [ "$status" -ne 0 ]; then
    [ "$status" -eq 3 ] || fail "$what: exit $status, not 0, 2 or 3: $(head -c 300 "$work/res.err")"
    [ "$(wc -l <"$work/res.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/res.err")"
    # (session 70: a run stopped after it began writes its results up to the stop beside the
    # directory's other files; until then --out was left as it was)
    [ "$(cat "$work/out/sentinel")" = keep ] && grep -q '"stopped"' "$work/out/events.json" 2>/dev/null \
      || fail "$what: --out: $(ls "$work/out")"
  fi
done

# 6. data within the doubles in the file's units but not in the simulator's (s, mN; session 60,
#    hunt60): a rate of m·1e306 rad/ms is m·1e309 rad/s, a torque of m·1e306 N mm m·1e309 mN mm.
#    Refused at the value's pointer naming the internal units and the largest value allowed
#    (base60: exit 3 at t = 0, "moving at inf rad/ms" or "the loads ... are not finite", no pointer);
#    at that largest value over 2 not refused there.
for c in "bouncing-bar.json /simulation/velocities/bar ms" "escapement.json /parts/0/dynamics/torque s" \
         "spring-block.json /simulation/springs/0/stiffness s" "spring-block.json /simulation/gravity/1 ms"; do
  read -r file pointer time <<<"$c"
  value="$((1 + RANDOM % 9)).$((RANDOM % 10))e$((306 + RANDOM % 2))"
  # (a stiffness must not be negative: a rate, a torque and gravity take either sign)
  [[ $pointer == */stiffness ]] || { ((RANDOM % 2)) && value="-$value"; }
  model="$work/internal.json"
  write_internal() {
    python3 - "$source/examples/models/$file" "$pointer" "$1" "$time" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc['simulation']['units'] = {'time': sys.argv[4], 'force': 'N'}
node, keys = doc, sys.argv[2].strip('/').split('/')
for key in keys[:-1]:
    node = node[int(key)] if isinstance(node, list) else node[key]
last = keys[-1]
node[int(last) if isinstance(node, list) else last] = sys.argv[3]
json.dump(doc, open(sys.argv[5], 'w'))
PY
  }
  write_internal "$value"
  refused_simulate "simulate $file with $pointer at $value ($time, N)" "$pointer: '" \
    "in the simulator's internal units (s, mN), beyond the doubles' range" --quiet || continue
  largest=$(sed -n "s/.*give at most \([-0-9.e]*\) .*/\1/p" "$work/bad.err")
  [ -n "$largest" ] || { fail "$file $pointer: no largest value given: $(head -c 300 "$work/bad.err")"; continue; }
  write_internal "$(python3 -c "print(repr(float('$largest') / 2))")"
  timeout 120 "$hipair" simulate "$model" --t-end 1e-200 --max-steps 20000 --no-pictures --quiet >"$work/half.out" 2>"$work/half.err"
  grep -qF "$pointer: '" "$work/half.err" && fail "$file $pointer at half of $largest: $(head -c 300 "$work/half.err")"
done

# 7. a sweep's N written as 1e9 or beyond a long: one line saying what N is taken (session 60;
#    base60 said "N must be a whole number" of 1e9 and of 99999999999999999999)
for n in 1e9 99999999999999999999 2.5; do
  "$hipair" simulate "$source/examples/models/escapement.json" --t-end 0.001 --sweep "drive-torque=-200:-100:$n" \
    >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  [ "$status" -eq 2 ] && [ "$(wc -l <"$work/bad.err")" -eq 1 ] &&
    grep -qF "N must be a whole number written in digits, from 1 to 10000" "$work/bad.err" ||
    fail "--sweep N = $n: exit $status: $(head -c 300 "$work/bad.err")"
done

echo "simulate range tests: $failures failure(s) (seed $seed)"
[ "$failures" -eq 0 ]
