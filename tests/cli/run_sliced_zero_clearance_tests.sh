#!/usr/bin/env bash
# Session 53 (hunt53): the 3-DOF `cspace` of a square peg in a square hole at zero and tiny
# clearance, and hostile inputs on the 3-DOF path; output-option messages of show and simulate.
#  1. the 10 mm peg of examples/models/peg-in-hole.json in a hole of side 10 (zero clearance:
#     the peg only touches in the hole): 1 component in --stats, in --json ("components" and
#     every free cell's "component") and in the --svg heading (main: 4); a hole of side
#     10 + a random 10^-k (k in 20..40): 5;
#  2. hostile 3-DOF models (a zero-length edge, a zero-area spike, a self-crossing loop, a part
#     with no loops): one line "hipair: error: /parts/..." naming the place, exit 2, nothing written;
#     a peg equal to the plate (coincident parts): 1 component (main: 4);
#  3. `show --svg` under a regular file is refused before the model is read (a broken model
#     file is not what the message names), nothing written;
#  4. `simulate --t-end 1e300` with pictures: the too-many-frames message names --t-end.
#  (2b, session 58: a planar part against a rotating or translating part: the refusal names the pair;
#   session 59: `analyze` of such a model names the pair and the reason likewise.)
# usage: run_sliced_zero_clearance_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
peg="$source/examples/models/peg-in-hole.json"

# A refusal: exit EXPECTED (or any error code below 128: "error"), one line matching PATTERN
# (extended regex), and WRITTEN not created.
refused() { # LABEL EXPECTED CODE OUT PATTERN WRITTEN
  local label=$1 expected=$2 code=$3 out=$4 pattern=$5 written=$6
  if [ "$expected" = error ]; then
    { [ "$code" -ne 0 ] && [ "$code" -lt 128 ]; } || fail "$label: exit $code"
  else
    [ "$code" -eq "$expected" ] || fail "$label: exit $code"
  fi
  [ "$(grep -c . "$out")" = 1 ] || fail "$label: not one line: $(head -c 400 "$out")"
  grep -Eq "$pattern" "$out" || fail "$label: $(head -c 400 "$out")"
  [ -e "$written" ] && fail "$label: wrote $written"
}

# 1. zero and tiny clearance
sed 's/"hole-side": { "nominal": 12 }/"hole-side": { "nominal": 10 }/' "$peg" >"$work/peg10.json"
"$hipair" cspace "$work/peg10.json" --stats --json "$work/peg10.cspace.json" --svg "$work/peg10.svg" >"$work/peg10.out" 2>&1 ||
  fail "peg10: exit $?: $(head -c 300 "$work/peg10.out")"
grep -q "components 1;" "$work/peg10.out" || fail "peg10: --stats: $(grep components "$work/peg10.out")"
python3 - "$work/peg10.cspace.json" <<'PY' || fail "peg10: --json components"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["components"] == 1, d["components"]
cells = [c for s in d["slices"] for c in s["free_cells"]]
assert cells and all(c["component"] == 0 for c in cells), [c["component"] for c in cells]
PY
grep -q "1 free component)" "$work/peg10.svg" || fail "peg10: the SVG heading does not say 1 component"
k=$((20 + RANDOM % 21))
sed "s/\"hole-side\": { \"nominal\": 12 }/\"hole-side\": { \"nominal\": 10.$(printf '%0*d' $((k - 1)) 0)1 }/" "$peg" >"$work/peg-tiny.json"
"$hipair" cspace "$work/peg-tiny.json" --stats >"$work/peg-tiny.out" 2>&1 || fail "peg 10 + 1e-$k: exit $?"
grep -q "components 5;" "$work/peg-tiny.out" || fail "peg 10 + 1e-$k: $(grep components "$work/peg-tiny.out")"

# 2. hostile 3-DOF models
model() { # NAME FIXED_LOOPS FREE_LOOPS
  cat >"$work/$1.json" <<JSON
{ "hipair": 1, "name": "$1", "parts": [
  { "name": "plate", "motion": "fixed", "loops": [ $2 ] },
  { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ $3 ] } ] }
JSON
}
square() { echo "{ \"start\": [-$1, -$1], \"edges\": [ {\"line_to\": [$1, -$1]}, {\"line_to\": [$1, $1]}, {\"line_to\": [-$1, $1]}, {\"line_to\": [-$1, -$1]} ] }"; }
plate="$(square 20), $(square 6)"
model zero-length "$plate" '{ "start": [-5, -5], "edges": [ {"line_to": [5, -5]}, {"line_to": [5, -5]}, {"line_to": [5, 5]}, {"line_to": [-5, -5]} ] }'
model spike "$plate" '{ "start": [-5, 0], "edges": [ {"line_to": [5, 0]}, {"line_to": [-5, 0]} ] }'
model bowtie "$plate" '{ "start": [-5, -5], "edges": [ {"line_to": [5, 5]}, {"line_to": [5, -5]}, {"line_to": [-5, 5]}, {"line_to": [-5, -5]} ] }'
model no-loops "$plate" ''
for name in zero-length spike bowtie no-loops; do
  "$hipair" cspace "$work/$name.json" --json "$work/$name.out.json" >"$work/$name.out" 2>&1
  refused "$name" 2 $? "$work/$name.out" "^hipair: error: /parts/1" "$work/$name.out.json"
done
model coincident "$(square 5)" "$(square 5)"
"$hipair" cspace "$work/coincident.json" --stats >"$work/coincident.out" 2>&1 || fail "coincident: exit $?"
grep -q "components 1;" "$work/coincident.out" || fail "coincident: $(grep components "$work/coincident.out")"

# 2b. a planar part against a rotating or translating part (4 dimensions, not built): one message
#     naming the pair and its JSON pointer, with --pair (either order) and without, exit
#     non-zero, nothing written (session 58; until then "part 'peg' moves with more than one
#     degree of freedom; its pair is not a fixed-axis pair", naming neither)
planar_reason="\(/pairs/0\): the planar part 'peg' \(/parts/1/motion\) against the (rotating|translating) part 'plate' \(/parts/0/motion\) has a C-space of 4 dimensions"
for motion in '{"rotation": {"pivot": [0, 0]}}' '{"translation": {"direction": [1, 0]}}'; do
  python3 - "$peg" "$work/moving-plate.json" "$motion" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["parts"][0]["motion"] = json.loads(sys.argv[3])
json.dump(m, open(sys.argv[2], "w"))
PY
  for args in "--pair plate:peg" "--pair peg:plate" ""; do
    rm -f "$work/moving.json"
    # shellcheck disable=SC2086
    "$hipair" cspace "$work/moving-plate.json" $args --json "$work/moving.json" >"$work/moving.out" 2>&1
    refused "planar against $motion ($args)" error $? "$work/moving.out" "pair '(plate':'peg|peg':'plate)' $planar_reason" \
      "$work/moving.json"
  done
  # `analyze` names the pair and why likewise (session 59; until then "part 'plate' is in no
  # pair that can be analysed", naming neither the pair nor the reason)
  rm -rf "$work/moving-analysis"
  "$hipair" analyze "$work/moving-plate.json" --out "$work/moving-analysis" >"$work/moving.out" 2>&1
  refused "analyze, planar against $motion" error $? "$work/moving.out" \
    "part 'plate' is in no pair that can be analysed: pair 'plate':'peg' $planar_reason, which the kinematic analysis does not take" \
    "$work/moving-analysis/report.json"
done

# 3. show --svg under a regular file, before reading the model
: >"$work/regular"
printf '{ broken' >"$work/broken.json"
"$hipair" show "$work/broken.json" --svg "$work/regular/picture.svg" >"$work/show.out" 2>&1
code=$?
[ $code -ne 0 ] || fail "show under a regular file: exit 0"
grep -q -- "--svg .*regular.* exists and is not a directory" "$work/show.out" || fail "show: $(head -c 300 "$work/show.out")"
[ -s "$work/regular" ] && fail "show: wrote into the regular file"

# 4. simulate --t-end 1e300 names --t-end
"$hipair" simulate "$source/examples/models/scotch-yoke.json" --t-end 1e300 --out "$work/sim" >"$work/sim.out" 2>&1
code=$?
[ $code -ne 0 ] || fail "simulate --t-end 1e300: exit 0"
grep -q -- "--t-end" "$work/sim.out" || fail "simulate --t-end 1e300: $(head -c 300 "$work/sim.out")"
[ ! -e "$work/sim" ] || fail "simulate --t-end 1e300: wrote $work/sim"

[ $failures -eq 0 ] && echo "all zero-clearance CLI tests passed (seed $seed)"
[ $failures -eq 0 ]
