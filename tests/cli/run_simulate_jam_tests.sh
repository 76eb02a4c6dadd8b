#!/usr/bin/env bash
# A simulate run stopped by a jam keeps what it computed (session 69, jam69): generated jams of
# the three simulators, each against its closed form —
#  - fixed-axis: cam-drive.json's constant-speed eccentric cam (e = 8 mm) lifts the flat-faced
#    follower (offset e sin(w t)) into a fixed stop H mm above its start: the jam at
#    t* = asin(H / e) / w;
#  - planar parts: a pusher at a constant V mm/s strikes a 6 mm block plastically and carries it
#    into a wall at x = W: the jam at t* = (W - 6 + 35) / V, whatever the block's start;
#  - pin-slot: the film advance driven at a constant speed pulls its film to its -20 mm limit
#    (film68's reproducer, perforation 2): the jam at 0.3424 s (the unit tests hold its closed form);
#  - (session 71, jam71) a --sweep of the cam's speed whose runs jam: reported "stopped" with
#    their reason, not "failed".
# Each run: exit 3 with the jam's message (the driver, the part, the contacts) saying what was
# written; trajectory.csv, events.json/.txt (and the pictures) up to the jam, its last row the
# jam's time; events.json's "stopped" {time, reason "jam", decision, message}; the summary's "stopped early"
# line; no temporary file left; without --out nothing is written. Until session 69 such runs
# wrote nothing (exit 3 only; and the fixed-axis and planar messages named no jam: "the impact
# problem ... has no solution").
# usage: run_simulate_jam_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"

# shellcheck source=stopped_run_checks.sh
source "$(dirname "$0")/stopped_run_checks.sh"

# check_stopped NAME OUT_DIR EXPECTED_T TOLERANCE DRIVER PART CONTACT DECISION [PICTURES]
# (DECISION: exact, or approximate where a verdict is found on doubles; the fixed-axis cam exact
# since session 70; the files' checks: stopped_run_checks.sh, at least 3 trajectory rows)
check_stopped() {
  check_stopped_run "$1" "$2" jam "$8" "$3" "$4" 3 "${9:-}" "the constant-speed driver '$5' jams '$6' (a jam)" "$7"
}

# 1. fixed-axis: the cam lifts the follower into a stop
for trial in 1 2; do
  read -r model expected tol <<<"$(python3 - "$source/examples/models/cam-drive.json" "$work/cam-$trial.json" "$seed" "$trial" <<'EOF'
import json, math, random, sys
source, target, seed, trial = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
rng = random.Random(seed * 100 + trial)
m = json.load(open(source))
h = rng.uniform(1.5, 6.5)         # the stop's height above the follower's start (its faceplate top at 31)
w = rng.uniform(20, 150)          # rad/s, below the critical speed 187: the follower rides the cam
m["name"] = "cam-stop-jam"
m["parameters"]["cam-speed"]["nominal"] = w
m["parts"].append({"name": "stop", "motion": "fixed", "loops": [{"label": "stop", "start": [12, 31 + h], "edges": [
    {"line_to": [18, 31 + h], "label": "stop face"}, {"line_to": [18, 31 + h + 5]}, {"line_to": [12, 31 + h + 5]},
    {"line_to": [12, 31 + h]}]}]})
m["pairs"].append({"parts": ["stop", "follower"], "friction": 0, "restitution": 0})
json.dump(m, open(target, "w"), indent=1)
# the offset reaches h at e sin(w t) = h; tolerance: 1e-6 mm of offset (10^3 x the model's
# accuracy 1e-9 over its 33 mm reach) over the lift's rate e w cos(w t)
t = math.asin(h / 8) / w
print(target, repr(t), repr(1e-6 / (8 * w * math.cos(w * t))))
EOF
)"
  "$hipair" simulate "$model" --t-end "$(python3 -c "print(2 * $expected)")" --fps 25 --out "$work/cam-$trial" \
    >"$work/cam-$trial.out" 2>"$work/cam-$trial.err"
  echo $? >"$work/cam-$trial.code"
  check_stopped "cam-$trial" "$work/cam-$trial" "$expected" "$tol" cam follower "stop face / follower shoulder R" \
    exact "positions.svg velocities.svg animation.svg cspace-cam-follower.svg"
done
# the same run without --out: exit 3, nothing written
"$hipair" simulate "$work/cam-1.json" --t-end 1 >"$work/cam-none.out" 2>"$work/cam-none.err"
code=$?
[ $code -eq 3 ] || fail "cam without --out: exit $code"
grep -q "(a jam)" "$work/cam-none.err" || fail "cam without --out: $(head -c 300 "$work/cam-none.err")"
grep -q "written" "$work/cam-none.err" && fail "cam without --out: claims a write: $(cat "$work/cam-none.err")"

# 1b. --sweep over the cam's speed (session 71, jam71): a jammed run of a sweep is reported
# "stopped" (early: not at t-end, "completes" false) with its reason, decision, time and message
# (sweep.json's "stopped", the table's "stopped early at t = T (a jam): MESSAGE"); its parts'
# data up to the jam. Until session 71 it was "failed" with the message as an error.
read -r w1 w2 <<<"$(python3 -c "import random; r = random.Random($seed * 100 + 5); a = r.randint(30, 80); print(a, a + r.randint(10, 60))")"
read -r h tend <<<"$(python3 - "$work/cam-1.json" "$w1" <<'EOF'
import json, math, sys
m = json.load(open(sys.argv[1]))
stop = next(p for p in m["parts"] if p["name"] == "stop")
h = stop["loops"][0]["start"][1] - 31
print(repr(h), repr(2 * math.asin(h / 8) / float(sys.argv[2])))
EOF
)"
"$hipair" simulate "$work/cam-1.json" --t-end "$tend" --sweep "cam-speed=$w1:$w2:2" --jobs 1 --out "$work/sweep" \
  >"$work/sweep.out" 2>"$work/sweep.err"
code=$?
[ $code -eq 0 ] || fail "sweep of jams: exit $code: $(head -c 300 "$work/sweep.err")"
[ "$(grep -cE $'\tstopped\t.*\tstopped early at t = .* \\(a jam\\): .*the constant-speed driver .cam. jams .follower. \\(a jam\\)' "$work/sweep.out")" -eq 2 ] \
  || fail "sweep of jams: the table does not report two stopped jams: $(head -c 1500 "$work/sweep.out")"
python3 - "$work/sweep/sweep.json" "$h" "$w1" "$w2" <<'EOF' || fail "sweep of jams: sweep.json"
import json, math, sys
doc = json.load(open(sys.argv[1]))
h = float(sys.argv[2])
runs = doc["runs"]
assert len(runs) == 2, runs
for run, w in zip(runs, (float(sys.argv[3]), float(sys.argv[4]))):
    assert run["value"] == w, (run["value"], w)
    assert run["status"] == "stopped" and run["completes"] is False, run
    stop = run["stopped"]
    assert stop["reason"] == "jam" and stop["decision"] == "exact", stop
    assert "the constant-speed driver 'cam' jams 'follower' (a jam)" in stop["message"], stop["message"]
    t = math.asin(h / 8) / w
    tol = 1e-6 / (8 * w * math.cos(w * t))   # (as the single runs' above)
    assert abs(stop["time"] - t) <= tol, (stop["time"], t, tol)
    assert "follower" in run["parts"], run
    print(f"  sweep run {w:g} rad/s stopped at {stop['time']!r}, closed form {t!r}")
EOF

# 2. planar parts: a pusher carries a block into a wall
for trial in 1 2; do
  read -r model expected tol <<<"$(python3 - "$source/examples/models/pusher-blocks.json" "$work/push-$trial.json" "$seed" "$trial" <<'EOF'
import json, random, sys
source, target, seed, trial = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
rng = random.Random(seed * 100 + 10 + trial)
m = json.load(open(source))
v, x0, wall = rng.uniform(20, 400), rng.uniform(-20, 30), rng.uniform(50, 80)
m["name"] = "pusher-jam"
m["parts"] = [p for p in m["parts"] if p["name"] != "small"]
m["parts"][0]["loops"][0]["start"] = [wall, -20]
m["parts"][0]["loops"][0]["edges"] = [{"line_to": [wall + 10, -20]}, {"line_to": [wall + 10, 20]},
                                     {"line_to": [wall, 20]}, {"line_to": [wall, -20], "label": "wall face"}]
m["parts"][2]["initial"] = {"x": x0, "y": 0}
m["pairs"] = [{"parts": ["pusher", "block"], "restitution": 0}, {"parts": ["wall", "block"], "restitution": 0}]
m["simulation"]["drivers"][0]["speed"]["x"] = v
json.dump(m, open(target, "w"), indent=1)
# the pusher's face (x = 5 - 40 at the start) travels to the wall less the block's 6 mm; tolerance
# 10^3 x the model's accuracy 1e-10 over the 100 mm travel, over V
t = (wall - 6 + 35) / v
print(target, repr(t), repr(1e3 * 1e-10 * 100 / v))
EOF
)"
  "$hipair" simulate "$model" --t-end "$(python3 -c "print(2 * $expected)")" --no-pictures --out "$work/push-$trial" \
    >"$work/push-$trial.out" 2>"$work/push-$trial.err"
  echo $? >"$work/push-$trial.code"
  check_stopped "push-$trial" "$work/push-$trial" "$expected" "$tol" pusher block "(wall face)" exact
done

# 3. pin-slot: the film pulled to its travel limit by a constant-speed cam; an earlier run's
# files in --out are replaced
python3 - "$source/tests/data/simulation/film-advance-dynamics.json" "$work/film.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
del j["parts"][0]["dynamics"]
j["parameters"]["pitch"]["nominal"] = 7.8
j["parts"][3]["initial"]["offset"] = 0.2 - 2 * 7.8
j["parts"][3]["dynamics"]["damping"] = 0.004
j["simulation"]["drivers"] = [{"part": "cam", "speed": -360}]
j["simulation"]["accuracy"] = 1e-5
json.dump(j, open(sys.argv[2], "w"), indent=1)
EOF
mkdir -p "$work/film"
echo "old" >"$work/film/trajectory.csv"
"$hipair" simulate "$work/film.json" --t-end 1 --fps 10 --out "$work/film" >"$work/film.out" 2>"$work/film.err"
echo $? >"$work/film.code"
# (the closed form and its tolerance: SimulationPinSlot.FilmAtItsTravelLimitJams...: 0.3424 s here)
check_stopped film "$work/film" 0.3424 0.001 cam follower "film offset limit (lower end)" exact "positions.svg velocities.svg"
python3 - "$work/film/trajectory.csv" <<'EOF' || fail "film: the film is not at its -20 mm limit at the jam"
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
col = rows[0].index("film_offset")
assert abs(float(rows[-1][col]) + 20) < 1e-3, rows[-1]
EOF

[ $failures -eq 0 ] && echo "all simulate jam CLI tests passed (seed $seed)"
[ $failures -eq 0 ]
