#!/usr/bin/env bash
# A simulate run stopped by a jam keeps what it computed (session 69, jam69): generated jams of
# the three simulators, each against its closed form —
#  - fixed-axis: cam-drive.json's constant-speed eccentric cam (e = 8 mm) lifts the flat-faced
#    follower (offset e sin(w t)) into a fixed stop H mm above its start: the jam at
#    t* = asin(H / e) / w;
#  - planar parts: a pusher at a constant V mm/s strikes a 6 mm block plastically and carries it
#    into a wall at x = W: the jam at t* = (W - 6 + 35) / V, whatever the block's start;
#  - pin-slot: the film advance driven at a constant speed pulls its film to its -20 mm limit
#    (film68's reproducer, perforation 2): the jam at 0.3424 s (the unit tests hold its closed form).
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

# check_stopped NAME OUT_DIR EXPECTED_T TOLERANCE DRIVER PART CONTACT DECISION [PICTURES]
# (DECISION: exact, or approximate where a verdict is found on doubles; the fixed-axis cam exact since session 70)
check_stopped() {
  local name=$1 out=$2 expected=$3 tol=$4 driver=$5 part=$6 contact=$7 decision=$8 pictures=${9:-}
  local code
  code=$(cat "$work/$name.code")
  [ "$code" -eq 3 ] || fail "$name: exit $code, not 3: $(tail -c 300 "$work/$name.err")"
  grep -q "the constant-speed driver '$driver' jams '$part' (a jam)" "$work/$name.err" \
    || fail "$name: no jam named: $(head -c 400 "$work/$name.err")"
  grep -qF "$contact" "$work/$name.err" || fail "$name: contact '$contact' not named: $(head -c 600 "$work/$name.err")"
  grep -q "were written to $out" "$work/$name.err" || fail "$name: the error does not say what was written"
  grep -q "^  stopped early at t = " "$work/$name.out" || fail "$name: no 'stopped early' line in the summary"
  for f in trajectory.csv events.json events.txt $pictures; do
    [ -s "$out/$f" ] || fail "$name: $f not written"
  done
  # written whole: nothing but the run's files in the directory
  local extra
  extra=$(ls -A "$out" | grep -vxE 'trajectory.csv|events.json|events.txt|positions.svg|velocities.svg|animation.svg|cspace-.*\.svg')
  [ -z "$extra" ] || fail "$name: stray files in $out: $extra"
  python3 - "$out" "$expected" "$tol" "$contact" "$decision" <<'EOF' || fail "$name: the stopped run's files"
import csv, json, sys
out, expected, tol, contact, decision = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4], sys.argv[5]
doc = json.load(open(out + "/events.json"))
stop = doc.get("stopped")
assert stop, "events.json has no 'stopped'"
assert stop["reason"] == "jam" and stop["decision"] == decision, stop
assert contact in stop["message"], stop["message"]
t = stop["time"]
assert abs(t - expected) <= tol, f"stopped at {t!r}, closed form {expected!r}, tolerance {tol!r}"
assert doc["t_end"] == t, (doc["t_end"], t)
rows = list(csv.reader(open(out + "/trajectory.csv")))
last = float(rows[-1][0])
# (trajectory.csv's numbers have 12 significant digits: within half a unit of the 12th)
assert abs(last - t) <= 5e-12 * abs(t), f"the trajectory ends at {last!r}, the jam at {t!r}"
times = [float(r[0]) for r in rows[1:]]
assert times == sorted(times) and len(times) > 2, "the trajectory is not the run's samples"
assert all(e["time"] <= t for e in doc["events"]), "an event after the jam"
lines = open(out + "/events.txt").read().splitlines()
said = ": stopped early (a jam" + ("" if decision == "exact" else ", approximate") + "): "
assert lines[-1].split(said)[1] == stop["message"], lines[-1]
print(f"  stopped at {t!r}, closed form {expected!r}: error {(t - expected) / tol:+.3g} of the tolerance")
EOF
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
