#!/usr/bin/env bash
# A pin-slot part's angle limits (session 53, pinslot53): the film advance with its follower's
# angle_limits widened to a whole turn or more ([-180, 180], [0, 360], [-1e400, 1e400] deg) is
# the whole turn — the cam pair's stack is the one without limits, and the film pair's whole turn
# (its exact critical values searched in pieces) is built in seconds, not the minutes of one
# search over the whole range before; limits of less than a turn across the half turn
# ([150, 200] deg) are refused with one message naming the field, writing nothing.
# usage: run_pin_slot_limits_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
# film-advance.json with the follower's angle_limits LIMITS (JSON text, or "none") and initial angle ANGLE
variant() {
  python3 - "$source/examples/models/film-advance.json" "$@" <<'PY'
import json, sys
source, target, limits, angle = sys.argv[1:5]
text = open(source).read()
model = json.loads(text)
follower = next(p for p in model["parts"] if p["name"] == "follower")
if limits == "none":
    del follower["motion"]["pin_slot"]["angle_limits"]
else:
    follower["motion"]["pin_slot"]["angle_limits"] = "@LIMITS@"
follower["initial"]["angle"] = int(angle)
out = json.dumps(model, indent=1)
open(target, "w").write(out.replace('"@LIMITS@"', limits))   # 1e400 kept as written
PY
}
# the JSON documents A and B equal but for statistics and timings
same_json() {
  python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("statistics", None)
sys.exit(0 if a == b else 1)
PY
}
variant "$work/none.json" none 0
timeout 120 "$hipair" cspace "$work/none.json" --pair cam:follower --json "$work/none-cam.json" >/dev/null 2>"$work/err.txt" ||
  fail "no limits, cam pair: exit $?: $(head -c 300 "$work/err.txt")"
i=0
for limits in '[-180, 180]' '[0, 360]' '[-1e400, 1e400]' '[-1e400, 8]'; do
  i=$((i + 1))
  variant "$work/turn-$i.json" "$limits" 0
  timeout 120 "$hipair" cspace "$work/turn-$i.json" --pair cam:follower --json "$work/turn-$i-cam.json" >/dev/null 2>"$work/err.txt" ||
    { fail "$limits deg, cam pair: exit $?: $(head -c 300 "$work/err.txt")"; continue; }
  same_json "$work/turn-$i-cam.json" "$work/none-cam.json" || fail "$limits deg: the cam pair's stack is not the whole turn's"
done
# the film pair over a whole turn (1e400 deg): exact critical values, in seconds (about 14 s CPU)
timeout 240 "$hipair" cspace "$work/turn-3.json" --pair film:follower --json "$work/turn-film.json" >/dev/null 2>"$work/err.txt" ||
  fail "[-1e400, 1e400] deg, film pair: exit $? (124: over 240 s): $(head -c 300 "$work/err.txt")"
if [ -f "$work/turn-film.json" ]; then
  python3 - "$work/turn-film.json" <<'PY' || fail "film pair over a whole turn: $(cat "$work/check.txt")"
import json, sys
d = json.load(open(sys.argv[1]))
ok = d["critical_values_exact"] and len(d["critical_values"]) >= 22 and d["slices"][0]["degrees"] < -160 and d["slices"][-1]["degrees"] > 160
sys.exit(0 if ok else 1)
PY
fi
# across the half turn: refused, one message naming the field, nothing written (an existing file kept)
variant "$work/across.json" '[150, 200]' 170
echo keep >"$work/across-out.json"
if "$hipair" cspace "$work/across.json" --pair cam:follower --json "$work/across-out.json" >/dev/null 2>"$work/err.txt"; then
  fail "[150, 200] deg accepted"
else
  grep -q 'angle_limits' "$work/err.txt" || fail "[150, 200] deg: the message does not name angle_limits: $(head -c 300 "$work/err.txt")"
  grep -q '/parts/1/motion' "$work/err.txt" || fail "[150, 200] deg: the message does not name the part's motion: $(head -c 300 "$work/err.txt")"
  [ "$(wc -l <"$work/err.txt")" -le 2 ] || fail "[150, 200] deg: more than one message: $(head -c 300 "$work/err.txt")"
  [ "$(cat "$work/across-out.json")" = keep ] || fail "[150, 200] deg: the existing output was overwritten"
fi
((failures == 0)) || { echo "pin-slot limits tests: $failures failure(s) (seed $seed)"; exit 1; }
echo "pin-slot limits tests passed (seed $seed)"
