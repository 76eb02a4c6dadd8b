#!/usr/bin/env bash
# A simulate run that stops after it began keeps what it computed (session 70, stop70; the jam:
# run_simulate_jam_tests.sh, session 69):
#  1. a motion limit (fixed axis): cam-drive.json's constant-speed cam (e = 8 mm, w rad/s) lifts
#     the follower (offset e sin(w t)) to its own upper motion limit L (its "limits" [-12, L], not
#     a contact): the stop at t* = asin(L / e) / w, kind "motion limit", the part and the limit
#     named, the follower at L in the trajectory's last row. Until session 70: exit 3 "cannot be
#     moved off its contact (a jammed contact change)", nothing written;
#  2. numeric errors mid-run: the ladder pulled along its floor by gravity m 1e200 mm/s^2
#     (planar; its initial energy finite, its first step's m g x ~ m g^2 t^2 / 2 not): "the run's
#     energy is not finite" — kind "numeric error", the files up to the last completed step (every
#     number in them finite, events.json's t_end and energy that step's). Until session 70:
#     nothing written. Not a stop (session 72, jam72): an initial state whose energy is already
#     beyond the doubles — the ladder (1 kg) under gravity m 1e308 mm/s^2, the pin-slot cam's follower
#     thrown down at m 1e160 mm/s — is bad input, exit 2 at the datum's pointer, nothing written
#     (sessions 70-71 wrote the initial state alone with "energy": null, exit 3);
#  3. the files are published whole: a publication made to fail at its N-th rename (N random)
#     leaves an existing --out directory byte for byte as it was and no staging directory; an
#     output directory that takes no entry (read-only, when not root) is refused before the run;
#  4. not stops (nothing written, as before): a run out of its step budget (--max-steps), and
#     bad input (exit 2).
# Each stopped run: exit 3 with the stop's message saying what was written; events.json's
# "stopped" {time, reason, message[, part, limit]}, t_end its time; trajectory.csv ending there;
# events.txt's last line "t = T s: stopped early (a KIND): MESSAGE"; the summary's "stopped early"
# line; no stray file; without --out nothing is written.
# usage: run_simulate_stop_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"

# shellcheck source=stopped_run_checks.sh
source "$(dirname "$0")/stopped_run_checks.sh"

# check_stop NAME OUT_DIR KIND EXPECTED_T TOLERANCE MESSAGE_PART [PICTURES]
# (EXPECTED_T "-": no closed form, only the files' agreement; stopped_run_checks.sh)
check_stop() {
  check_stopped_run "$1" "$2" "$3" - "$4" "$5" 1 "${7:-}" "$6"
}

# 1. fixed axis: the cam lifts the follower to its own motion limit
for trial in 1 2 3; do
  read -r model expected tol limit <<<"$(python3 - "$source/examples/models/cam-drive.json" "$work/limit-$trial.json" "$seed" "$trial" <<'EOF'
import json, math, random, sys
source, target, seed, trial = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
rng = random.Random(seed * 100 + 20 + trial)
m = json.load(open(source))
L = round(rng.uniform(1.5, 6.5), 3)   # the follower's upper limit (mm; printed as given)
w = rng.uniform(20, 150)              # rad/s, below the critical speed 187: the follower rides the cam
m["name"] = "cam-limit"
m["parameters"]["cam-speed"]["nominal"] = w
follower = next(p for p in m["parts"] if p["name"] == "follower")
follower["motion"]["translation"]["limits"] = [-12, L]
json.dump(m, open(target, "w"), indent=1)
# the offset reaches L at e sin(w t) = L; tolerance: 1e-6 mm of offset over the lift's rate
t = math.asin(L / 8) / w
print(target, repr(t), repr(1e-6 / (8 * w * math.cos(w * t))), L)
EOF
)"
  pictures="positions.svg velocities.svg animation.svg cspace-cam-follower.svg"
  extra=(--fps 25)
  [ "$trial" -eq 3 ] && { pictures=""; extra=(--no-pictures); }
  "$hipair" simulate "$model" --t-end "$(python3 -c "print(2 * $expected)")" "${extra[@]}" --out "$work/limit-$trial" \
    >"$work/limit-$trial.out" 2>"$work/limit-$trial.err"
  echo $? >"$work/limit-$trial.code"
  check_stop "limit-$trial" "$work/limit-$trial" "motion limit" "$expected" "$tol" "translating part 'follower' (/parts/1/motion) is at " "$pictures"
  python3 - "$work/limit-$trial" "$limit" <<'EOF' || fail "limit-$trial: the part, the limit or the follower's last position"
import csv, json, sys
out, L = sys.argv[1], float(sys.argv[2])
stop = json.load(open(out + "/events.json"))["stopped"]
assert stop["part"] == "follower", stop
assert stop["limit"] == f"upper limit {sys.argv[2]} mm of [-12, {sys.argv[2]}]", stop["limit"]
rows = list(csv.reader(open(out + "/trajectory.csv")))
col = rows[0].index("follower_position")
assert abs(float(rows[-1][col]) - L) <= 1e-6, (rows[-1][col], L)
EOF
  [ "$trial" -eq 3 ] && [ -e "$work/limit-3/animation.svg" ] && fail "limit-3: --no-pictures wrote animation.svg"
done
# without --out: exit 3, the stop named, nothing claimed written
"$hipair" simulate "$work/limit-1.json" --t-end 1 >"$work/limit-none.out" 2>"$work/limit-none.err"
code=$?
[ $code -eq 3 ] || fail "limit without --out: exit $code"
grep -q "(a motion limit, not a contact" "$work/limit-none.err" || fail "limit without --out: $(head -c 300 "$work/limit-none.err")"
grep -q "written" "$work/limit-none.err" && fail "limit without --out: claims a write: $(cat "$work/limit-none.err")"

# 2. numeric errors mid-run: energies beyond the doubles (planar, pin-slot)
read -r g g_initial v <<<"$(python3 -c "import random; r = random.Random($seed * 100 + 30); print(repr(r.uniform(1, 9) * 1e200), repr(r.uniform(1, 1.79) * 1e308), repr(-r.uniform(1, 9) * 1e160))")"
python3 - "$source/examples/models/ladder.json" "$source/tests/data/simulation/pin-slot-cam.json" "$work" "$g" "$v" "$g_initial" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
m["simulation"]["gravity"] = [float(sys.argv[4]), -9810]
json.dump(m, open(sys.argv[3] + "/ladder-overflow.json", "w"))
m["simulation"]["gravity"] = [float(sys.argv[6]), -9810]
m["parts"][1]["dynamics"]["mass"] = 1   # (m g x = 22.7 g: beyond the doubles for every g >= 1e308)
json.dump(m, open(sys.argv[3] + "/ladder-initial-overflow.json", "w"))
p = json.load(open(sys.argv[2]))
p["simulation"]["velocities"] = {"follower": {"slide": float(sys.argv[5])}}
json.dump(p, open(sys.argv[3] + "/pin-slot-overflow.json", "w"))
EOF
"$hipair" simulate "$work/ladder-overflow.json" --t-end 0.02 --max-steps 2000 --out "$work/ladder" \
  >"$work/ladder.out" 2>"$work/ladder.err"
echo $? >"$work/ladder.code"
check_stop ladder "$work/ladder" "numeric error" - - "the run's energy is not finite" "positions.svg velocities.svg"
# an initial state beyond the doubles (session 72, jam72): exit 2, one line beginning with the
# datum's pointer, the term named, --out (holding one file) untouched
initial_overflow() {   # NAME MODEL POINTER TERM ARGS...
  local name=$1 model=$2 pointer=$3 term=$4; shift 4
  rm -rf "$work/$name" && mkdir -p "$work/$name" && echo keep >"$work/$name/sentinel"
  "$hipair" simulate "$model" "$@" --out "$work/$name" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  [ $code -eq 2 ] || fail "$name: exit $code, not 2: $(head -c 400 "$work/$name.err")"
  [ "$(wc -l <"$work/$name.err")" -eq 1 ] || fail "$name: not one line: $(head -c 400 "$work/$name.err")"
  grep -qF "hipair: error: $pointer: the initial state's energy is not finite" "$work/$name.err" \
    || fail "$name: not refused at $pointer: $(head -c 400 "$work/$name.err")"
  grep -qF "its largest term is $term" "$work/$name.err" || fail "$name: the term is not $term: $(head -c 400 "$work/$name.err")"
  { [ "$(ls -A "$work/$name")" = sentinel ] && [ "$(cat "$work/$name/sentinel")" = keep ]; } \
    || fail "$name: --out changed: $(ls -A "$work/$name")"
}
initial_overflow ladder-initial "$work/ladder-initial-overflow.json" /simulation/gravity/0 "the work of gravity on part 'ladder'" \
  --t-end 0.02 --max-steps 2000
initial_overflow pinslot "$work/pin-slot-overflow.json" /simulation/velocities/follower/slide "the kinetic energy of part 'follower'" \
  --t-end 0.01 --max-steps 100 --no-pictures

# 3. published whole: a failed publication leaves an existing --out as it was, no staging left
d="$work/existing"
mkdir -p "$d"
"$hipair" simulate "$source/examples/models/bouncing-bar.json" --t-end 0.01 --no-pictures --out "$d" >/dev/null 2>&1 \
  || fail "bouncing-bar into $d failed"
echo "a note" >"$d/notes.txt"
before=$(cd "$d" && md5sum ./* | LC_ALL=C sort)
at=$((RANDOM % 3 + 1))
HIPAIR_TEST_PUBLISH_FAIL_AT=$at "$hipair" simulate "$work/ladder-overflow.json" --t-end 0.02 --max-steps 2000 --out "$d" \
  >"$work/fail.out" 2>"$work/fail.err"
code=$?
[ $code -eq 3 ] || fail "publication failing at rename $at: exit $code, not 3"
grep -q "cannot move" "$work/fail.err" || fail "publication failing at rename $at: $(head -c 300 "$work/fail.err")"
[ "$(cd "$d" && md5sum ./* | LC_ALL=C sort)" = "$before" ] || fail "publication failing at rename $at changed $d"
[ -z "$(ls -A "$work" | grep -F ".existing.tmp-")" ] || fail "publication failing at rename $at left its staging directory"
# the same stopped run without the failure replaces the earlier run's files, keeps the note
"$hipair" simulate "$work/ladder-overflow.json" --t-end 0.02 --max-steps 2000 --out "$d" >/dev/null 2>&1
grep -q '"reason": "numeric error"' "$d/events.json" || fail "the stopped run did not replace $d/events.json"
[ "$(cat "$d/notes.txt")" = "a note" ] || fail "the stopped run touched $d/notes.txt"
if [ "$(id -u)" -ne 0 ]; then   # (root writes into a read-only directory)
  mkdir -p "$work/ro" && chmod a-w "$work/ro"
  "$hipair" simulate "$work/limit-1.json" --t-end 1 --out "$work/ro/out" >"$work/ro.out" 2>"$work/ro.err"
  code=$?
  [ $code -eq 3 ] || fail "read-only: exit $code, not 3"
  [ -s "$work/ro.out" ] && fail "read-only: the run went on: $(head -c 200 "$work/ro.out")"
  chmod u+w "$work/ro"
fi

# 4. not stops: the step budget and bad input write nothing
"$hipair" simulate "$work/limit-1.json" --t-end 0.05 --max-steps 3 --out "$work/budget" >/dev/null 2>"$work/budget.err"
code=$?
[ $code -eq 3 ] || fail "step budget: exit $code, not 3"
grep -q "used up its step budget (--max-steps 3).*nothing was written" "$work/budget.err" || fail "step budget: $(cat "$work/budget.err")"
[ -e "$work/budget" ] && fail "step budget: wrote $work/budget"
python3 - "$work/limit-1.json" "$work/bad.json" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
next(p for p in m["parts"] if p["name"] == "follower")["motion"]["translation"]["limits"] = [-12, "x"]
json.dump(m, open(sys.argv[2], "w"))
EOF
"$hipair" simulate "$work/bad.json" --t-end 1 --out "$work/bad" >/dev/null 2>"$work/bad.err"
code=$?
[ $code -eq 2 ] || fail "bad input: exit $code, not 2: $(cat "$work/bad.err")"
[ -e "$work/bad" ] && fail "bad input: wrote $work/bad"

[ $failures -eq 0 ] && echo "all simulate stop CLI tests passed (seed $seed)"
[ $failures -eq 0 ]
