# The checks of a `hipair simulate` run that stopped after it began and kept its files (sourced by
# run_simulate_stop_tests.sh and run_simulate_jam_tests.sh after seeded_test.sh; session 71,
# jam71: the two tests' copies made one).
#   check_stopped_run NAME OUT_DIR KIND DECISION EXPECTED_T TOLERANCE MIN_ROWS "PICTURES" SAID...
# The run's exit code, stdout and stderr in $work/NAME.code, .out, .err. KIND: events.json's
# "stopped" reason ("jam", "motion limit", "numeric error", "geometry error"); DECISION: a jam's
# "exact" or "approximate" ("-" for the other kinds, which have none); EXPECTED_T "-": no closed
# form, only the files' agreement; MIN_ROWS: the trajectory's least number of rows; PICTURES: the
# pictures that must be written (space-separated, may be empty); every SAID (a fixed string) is
# said in the error and in events.json's stop message. Checked: exit 3; the error says what was
# written; the summary's "stopped early (a KIND[, approximate]): " line; the files written whole
# (no stray file, no staging directory); events.json's "stopped" {time, reason, decision only for
# a jam, message}, its t_end the stop's time, its energy a finite number (the state written
# last) or null where the stop says the run's energy is not finite; trajectory.csv the run's samples, every number finite, its last
# row at the stop's time; every event at or before the stop (for every kind of stop, session
# 71); events.txt's last line "t = T: stopped early (a KIND...): MESSAGE".
check_stopped_run() {
  local name=$1 out=$2 kind=$3 decision=$4 expected=$5 tol=$6 min_rows=$7 pictures=$8
  shift 8
  local code words=$kind
  [ "$kind" = jam ] && [ "$decision" = approximate ] && words="jam, approximate"
  code=$(cat "$work/$name.code")
  [ "$code" -eq 3 ] || { fail "$name: exit $code, not 3: $(tail -c 300 "$work/$name.err")"; return; }
  local said
  for said in "$@"; do
    grep -qF -- "$said" "$work/$name.err" || fail "$name: '$said' not said: $(head -c 600 "$work/$name.err")"
  done
  grep -q "were written to $out" "$work/$name.err" || fail "$name: the error does not say what was written"
  grep "^  stopped early at t = " "$work/$name.out" | grep -qF " (a $words): " \
    || fail "$name: no 'stopped early (a $words)' line in the summary"
  local f
  for f in trajectory.csv events.json events.txt $pictures; do
    [ -s "$out/$f" ] || fail "$name: $f not written"
  done
  local extra
  extra=$(ls -A "$out" | grep -vxE 'trajectory.csv|events.json|events.txt|positions.svg|velocities.svg|animation.svg|cspace-.*\.svg')
  [ -z "$extra" ] || fail "$name: stray files in $out: $extra"
  [ -z "$(ls -A "$(dirname "$out")" | grep -F ".$(basename "$out").tmp-")" ] || fail "$name: a staging directory was left"
  python3 - "$out" "$kind" "$decision" "$expected" "$tol" "$min_rows" "$words" "$@" <<'EOF' || fail "$name: the stopped run's files"
import csv, json, math, sys
out, kind, decision, expected, tol, min_rows, words = sys.argv[1:8]
said = sys.argv[8:]
doc = json.load(open(out + "/events.json"))
stop = doc.get("stopped")
assert stop, "events.json has no 'stopped'"
assert stop["reason"] == kind, stop
if kind == "jam":
    assert stop["decision"] == decision, stop
else:
    assert "decision" not in stop, stop
for s in said:
    assert s in stop["message"], (s, stop["message"])
t = stop["time"]
assert doc["t_end"] == t, (doc["t_end"], t)
# a finite number, or null only where the stop says the run's energy is not finite (the pin-slot
# overflow run's initial state)
if doc["energy"] is None:
    assert "energy is not finite" in stop["message"], "energy written as null: " + stop["message"]
else:
    assert math.isfinite(doc["energy"]), doc["energy"]
rows = list(csv.reader(open(out + "/trajectory.csv")))
times = [float(r[0]) for r in rows[1:]]
assert len(times) >= int(min_rows) and times == sorted(times), "the trajectory is not the run's samples"
# (trajectory.csv's numbers have 12 significant digits: within half a unit of the 12th)
assert abs(times[-1] - t) <= 5e-12 * abs(t), f"the trajectory ends at {times[-1]!r}, the stop at {t!r}"
assert all(math.isfinite(float(x)) for r in rows[1:] for x in r), "a number in the trajectory is not finite"
late = [e for e in doc["events"] if not e["time"] <= t]
assert not late, f"events after the stop at {t!r}: {late[:3]}"
lines = open(out + "/events.txt").read().splitlines()
w = f": stopped early (a {words}): "
assert w in lines[-1] and lines[-1].split(w)[1] == stop["message"], lines[-1]
if expected != "-":
    expected, tol = float(expected), float(tol)
    assert abs(t - expected) <= tol, f"stopped at {t!r}, closed form {expected!r}, tolerance {tol!r}"
    print(f"  stopped at {t!r}, closed form {expected!r}: error {(t - expected) / tol:+.3g} of the tolerance")
else:
    print(f"  stopped at {t!r} after {len(times)} samples")
EOF
}
