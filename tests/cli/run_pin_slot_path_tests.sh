#!/usr/bin/env bash
# `hipair cspace --at ... --to ...` on pin-in-slot pairs (session 69, pincli69): a path through
# the film advance's film:follower stack between seeded pairs of its cells' samples (drawn
# from the stack's own JSON): found paths start and end at the requested configurations
# exactly, every motion is of one of the certified kinds and agrees with its waypoints, every
# waypoint on a slice names it, the SVG draws the path; ends the stack does not show connected
# give status not_shown_connected, exit 1, the JSON written with it. Bad ends (malformed
# numbers, unknown parts, a missing angle, blocked, outside the limits, --at without --to,
# --to without a pin-slot pair or with several) exit 2 with one message naming the option,
# writing nothing (an existing output kept).
# usage: run_pin_slot_path_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
model="$source/examples/models/film-advance.json"
stack=(cspace "$model" --pair film:follower --slices 6)
timeout 120 "$hipair" "${stack[@]}" --json "$work/stack.json" >/dev/null 2>"$work/err.txt" ||
  fail "the stack: exit $?: $(head -c 300 "$work/err.txt")"
# seeded pairs of cell samples (one of different groups, up to six of one group: run until two
# paths are found) as --at/--to assignments: slide
# and film offset exact, the slice's angle in degrees to 12 digits (the CLI rounds it to an
# exact tau near the slice's, joined to a slice by a witnessed turn or, rarely, not: then
# not_shown_connected, never not_found); the path's ends are compared with the options exactly
python3 - "$work/stack.json" "$seed" >"$work/pairs.txt" <<'PY'
import json, math, random, sys
from fractions import Fraction
d = json.load(open(sys.argv[1]))
random.seed(int(sys.argv[2]))
cells = [(s["index"], s["tau"], c) for s in d["slices"] for c in s["free_cells"]]
def end(i, tau, c):
    t = float(Fraction(tau))
    deg = 2 * math.degrees(math.atan(t))
    return "follower=%s,%.12fdeg film=%s" % (c["sample"]["slide"], deg, c["sample"]["other"]["offset"])
same = [(a, b) for a in cells for b in cells if a[2]["group"] == b[2]["group"] and a[0] != b[0]]
apart = [(a, b) for a in cells for b in cells if a[2]["group"] != b[2]["group"]]
for kind, pool, n in (("apart", apart, 1), ("same", same, 6)):
    for a, b in random.sample(pool, min(n, len(pool))):
        print(kind, end(*a), "|", end(*b))
PY
n=0 found=0
while read -r kind rest; do
  # pairs in one group until two paths are found (an end a rounded angle makes blocked is skipped)
  [ "$kind" = same ] && [ "$found" -ge 2 ] && break
  n=$((n + 1))
  from=${rest%%|*} to=${rest#*|}
  args=()
  for a in $from; do args+=(--at "$a"); done
  for a in $to; do args+=(--to "$a"); done
  timeout 120 "$hipair" "${stack[@]}" "${args[@]}" --json "$work/path-$n.json" --svg "$work/path-$n.svg" >"$work/out-$n.txt" 2>"$work/err.txt"
  code=$?
  if [ "$code" = 2 ]; then   # an end a sample at a rounded angle made blocked: not this test's point
    grep -q -- '--at\|--to' "$work/err.txt" || fail "pair $n ($kind): exit 2 without naming the option: $(head -c 300 "$work/err.txt")"
    continue
  fi
  python3 - "$work/path-$n.json" "$kind" "$code" "$rest" >"$work/check.txt" 2>&1 <<'PY' || fail "pair $n ($kind): $(cat "$work/check.txt")"
import json, sys
from fractions import Fraction as F
d = json.load(open(sys.argv[1]))
kind, code, ends = sys.argv[2], int(sys.argv[3]), sys.argv[4]
p = d["path"]
if kind == "apart" or p["status"] == "not_shown_connected":
    assert code == 1, "exit %d for ends not shown connected" % code
    assert p["status"] == "not_shown_connected", p["status"]
    assert p["waypoints"] == [] and p["motions"] == [], "waypoints without a path"
    sys.exit(0)
assert code == 0 and p["status"] == "found", "exit %d, status %s" % (code, p["status"])
print("PATH-FOUND")
w, m = p["waypoints"], p["motions"]
assert len(m) == len(w) - 1 >= 1, "motions do not join the waypoints"
# the ends: the options' slide and film offset exactly
def parse(text):
    out = {}
    for a in text.split():
        name, value = a.split("=")
        out[name] = value
    return out
a, b = (parse(t) for t in ends.split("|"))
for q, e in ((w[0], a), (w[-1], b)):
    assert F(q["slide"]) == F(e["follower"].split(",")[0]), ("slide", q["slide"], e)
    assert F(q["other"]["offset"]) == F(e["film"]), ("offset", q["other"], e)
taus = {s["index"]: F(s["tau"]) for s in d["slices"]}
for q in w:
    assert abs(float(F(q["slide"])) - q["slide_mm"]) <= 1e-9 * max(1, abs(q["slide_mm"])), "slide double"
    if q["slice"] is not None:
        assert taus[q["slice"]] == F(q["tau"]), "waypoint names the wrong slice"
    else:
        assert F(q["tau"]) not in taus.values(), "a waypoint on a slice names none"
for i, mo in enumerate(m):
    p0, p1 = w[mo["from"]], w[mo["to"]]
    assert (mo["from"], mo["to"]) == (i, i + 1)
    same_tau = F(p0["tau"]) == F(p1["tau"])
    same_s = F(p0["slide"]) == F(p1["slide"])
    same_other = F(p0["other"]["offset"]) == F(p1["other"]["offset"])
    k = mo["kind"]
    assert k in ("in_slice", "turn", "plane"), k
    assert (k == "in_slice") == same_tau, ("motion", i, k)
    if k == "turn": assert same_s and same_other, ("turn", i)
    if k == "plane": assert same_s, ("plane", i)
PY
  grep -qx PATH-FOUND "$work/check.txt" && found=$((found + 1))
  if [ "$kind" = same ] && grep -qx PATH-FOUND "$work/check.txt"; then
    grep -q 'path: found' "$work/path-$n.svg" || fail "pair $n: the SVG does not say the path was found"
    grep -q '&lt;- \|-&gt; ' "$work/path-$n.svg" || fail "pair $n: the SVG marks no move between slices"
    if grep -q '"in_slice"' "$work/path-$n.json"; then
      grep -q 'stroke="#1f4e9c"' "$work/path-$n.svg" || fail "pair $n: the SVG draws no in-slice motion"
    fi
    grep -q 'path film:follower: found' "$work/out-$n.txt" || fail "pair $n: no summary line: $(cat "$work/out-$n.txt")"
  fi
done <"$work/pairs.txt"
[ "$n" -ge 3 ] || fail "only $n pairs drawn"
[ "$found" -ge 2 ] || fail "only $found of $n pairs in one group found"
# bad ends: exit 2, one message naming the option, nothing written (an existing file kept)
refused() {   # EXPECTED-TEXT ARGS...
  local expected=$1
  shift
  echo keep >"$work/kept.json"
  "$hipair" "$@" --json "$work/kept.json" >/dev/null 2>"$work/err.txt"
  local code=$?
  [ "$code" = 2 ] || { fail "$*: exit $code, not 2: $(head -c 300 "$work/err.txt")"; return; }
  grep -q -- "$expected" "$work/err.txt" || fail "$*: the message does not name '$expected': $(head -c 300 "$work/err.txt")"
  [ "$(wc -l <"$work/err.txt")" -le 1 ] || fail "$*: more than one message: $(head -c 300 "$work/err.txt")"
  [ "$(cat "$work/kept.json")" = keep ] || fail "$*: the existing output was overwritten"
}
refused '--to follower=x,1deg' "${stack[@]}" --to follower=x,1deg
refused '--to follower=1,1dog' "${stack[@]}" --to follower=1,1dog
refused "--to expects follower=SLIDE,ANGLE" "${stack[@]}" --to follower=1
refused "--to expects follower=SLIDE,ANGLE or film=VALUE" "${stack[@]}" --to cam=1
refused '--at film=abc' "${stack[@]}" --at film=abc --to follower=0,0
refused "--at: the start of a path" "${stack[@]}" --at follower=0,0
refused "--to follower=5,6deg --to film=-8: the configuration is blocked" "${stack[@]}" --to follower=5,6deg --to film=-8
refused "--to.*outside the limits" "${stack[@]}" --to follower=0,30deg
refused "--at.*outside the limits" "${stack[@]}" --at follower=7,0 --to follower=0,0
refused "--to: a path is planned through one pin-in-slot pair" cspace "$model" --to follower=0,0
refused "--to: a path's end, for pin-in-slot pairs" cspace "$source/examples/models/cam-follower.json" --to follower=0
((failures == 0)) || { echo "pin-slot path tests: $failures failure(s) (seed $seed)"; exit 1; }
echo "pin-slot path tests passed (seed $seed, $n pairs, $found paths found)"
