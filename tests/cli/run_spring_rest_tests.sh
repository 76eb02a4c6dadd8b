#!/usr/bin/env bash
# A spring-loaded follower's rest against its contact, decided exactly (session 49, exact49):
# generated variants of cam-follower.json (eccentricity e, so the cam lifts the flat face to e at
# the driver's 90° grid sample) analysed with `--load follower=spring:R`, R = e + d 2^-k for
# d in {-1, 0, +1} and k in 53..88 (R an exact fraction; until session 49 the rest was rounded
# to a double and a follower within 1e-12 of it was not moved). Closed form: at 90° the follower
# touches the cam exactly when R <= e (held against it by its spring; R = e: at rest on it), and
# it moves (a drive of 2^-k) exactly when R < e; R > e: free at its rest all turn, no drive.
# And the model's own spring (rest -20 mm: held against the cam all turn) with a tiny
# eccentricity e = 2^-k, k in 41..70: the follower sweeps 2e < 10^-12 mm, a drive (until session
# 49 a piece whose doubles spanned at most 1e-12 was called a dwell).
# A rotating follower: cam-follower-lever.json (eccentricity e) with `--load lever=spring:R` (rad),
# R = phi* + d 2^-k, k in 53..80, phi* = atan2(15 - e, 60) - asin(10 / sqrt(3600 + (15 - e)^2)) the
# lever's angle where its underside touches the follower's stem tip at the 90° sample (offset e;
# mpmath at 1400 bits): the lever touches it at 90° exactly when R > phi*, and then only it moves.
# No rational R equals phi*: the engine separates them by certified enclosures.
# usage: run_spring_rest_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
# cam-follower.json with eccentricity e = QUARTERS/4 written to MODEL; prints the rest
# R = e + D 2^-K as a fraction and the closed form's contact start and end, asin(R / e) and
# 180° - asin(R / e) in degrees (mpmath, 1400 bits; 90° 90° when R >= e)
cam_variant() {
  python3 - "$source/examples/models/cam-follower.json" "$@" <<'EOF'
import json, sys
from fractions import Fraction
import mpmath
source, target, quarters, k, d = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
model = json.load(open(source))
e = Fraction(quarters, 4)
model["parameters"]["eccentricity"]["nominal"] = float(e)
json.dump(model, open(target, "w"), indent=1)
rest = e + d * Fraction(1, 2 ** k)
mpmath.mp.prec = 1400
ratio = mpmath.mpf(rest.numerator) / rest.denominator / (mpmath.mpf(quarters) / 4)
start = mpmath.degrees(mpmath.asin(min(ratio, 1)))
print(f"{rest.numerator}/{rest.denominator}", mpmath.nstr(start, 40), mpmath.nstr(180 - start, 40))
EOF
}
cases=${HIPAIR_SPRING_REST_CASES:-6}
for ((i = 0; i < cases; ++i)); do
  e_quarters=$((24 + RANDOM % 17))            # e = 6 .. 10 mm in quarters
  k=$((53 + RANDOM % 36))   # the push lasts ~2 sqrt(2^(1-k) / e) rad of driver: above the 2^-46 events' resolution
  d=$(((i % 3) - 1))                          # below, at, above the top lift
  model="$work/cam-$i.json"
  read -r rest _ _ < <(cam_variant "$model" "$e_quarters" "$k" "$d")
  what="e = $e_quarters/4 mm, rest e ${d}·2^-$k = $rest"
  out="$work/out-$i"
  timeout 300 "$hipair" analyze "$model" --load "follower=spring:$rest" --no-pictures --out "$out" >"$work/report-$i.txt" 2>"$work/err-$i.txt" ||
    { fail "$what: exit $?: $(head -c 300 "$work/err-$i.txt")"; continue; }
  row=$(grep '^90\.000000000,' "$out/kinematics.csv")
  [ -n "$row" ] || { fail "$what: no 90° sample in kinematics.csv"; continue; }
  contacts=${row##*,}
  if ((d <= 0)); then
    [ "$contacts" != '""' ] || fail "$what: no contact at 90° (the cam lifts the face to e >= rest)"
  else
    [ "$contacts" = '""' ] || fail "$what: contact $contacts at 90° (the rest lies above the cam's top lift)"
  fi
  if ((d < 0)); then
    grep -q '  In all: 1 drive period' "$work/report-$i.txt" ||
      fail "$what: the follower is pushed 2^-$k above its rest, but: $(grep '  In all:' "$work/report-$i.txt")"
  else
    grep -q '  In all: 0 drive periods' "$work/report-$i.txt" ||
      fail "$what: the follower never leaves its rest, but: $(grep '  In all:' "$work/report-$i.txt")"
  fi
done
# A push shorter than the events' resolution (session 51): R = e - 2^-k, k in 92..160, so the
# contact lasts from asin(R / e) to 180° - asin(R / e), ~2^(1 - k/2) rad of driver in all:
# both events are located next to the 90° sample, to certified driver intervals that overlap.
# Until session 51 the piece was dropped as empty (0 drive periods: the push reported as
# nothing); now a drive of unresolved length whose ends' certified intervals hold the closed
# form's contact start and end (mpmath, 1400 bits). R = e + 2^-k: no contact, no drive.
for ((i = 0; i < 3; ++i)); do
  e_quarters=$((24 + RANDOM % 17))
  k=$((92 + RANDOM % 69))
  d=$((i < 2 ? -1 : 1))
  model="$work/short-$i.json"
  read -r rest start_deg end_deg < <(cam_variant "$model" "$e_quarters" "$k" "$d")
  what="e = $e_quarters/4 mm, rest e ${d}·2^-$k = $rest (a push shorter than the events' resolution)"
  out="$work/short-out-$i"
  timeout 300 "$hipair" analyze "$model" --load "follower=spring:$rest" --no-pictures --out "$out" >"$work/short-$i.txt" 2>"$work/short-err-$i.txt" ||
    { fail "$what: exit $?: $(head -c 300 "$work/short-err-$i.txt")"; continue; }
  if ((d > 0)); then
    grep -q '  In all: 0 drive periods' "$work/short-$i.txt" ||
      fail "$what: the follower never leaves its rest, but: $(grep '  In all:' "$work/short-$i.txt")"
    continue
  fi
  grep -q '  In all: 1 drive period' "$work/short-$i.txt" ||
    fail "$what: the cam pushes the follower 2^-$k off its rest, but: $(grep '  In all:' "$work/short-$i.txt")"
  check=$(python3 - "$out/report.json" "$start_deg" "$end_deg" <<'EOF'
import json, sys
import mpmath
mpmath.mp.prec = 1400
report = json.load(open(sys.argv[1]))
start, end = mpmath.mpf(sys.argv[2]), mpmath.mpf(sys.argv[3])
drives = [p for p in report["pieces"] if p["type"] == "drive"]
inside = lambda x, c: mpmath.mpf(c[0]) <= x <= mpmath.mpf(c[1])
if len(drives) != 1:
    print(f"{len(drives)} drive pieces in report.json")
elif not drives[0].get("unresolved_length"):
    print("the drive is not marked unresolved_length")
elif not inside(start, drives[0]["start"]["certified"]) or not inside(end, drives[0]["end"]["certified"]):
    print(f"the drive's certified ends {drives[0]['start']['certified']} .. {drives[0]['end']['certified']} miss the "
          f"contact {mpmath.nstr(start, 20)} .. {mpmath.nstr(end, 20)}")
EOF
)
  [ -z "$check" ] || fail "$what: $check"
done
for ((i = 0; i < 2; ++i)); do
  k=$((41 + RANDOM % 30))
  model="$work/tiny-$i.json"
  python3 - "$source/examples/models/cam-follower.json" "$model" "$k" <<'EOF'
import json, sys
model = json.load(open(sys.argv[1]))
model["parameters"]["eccentricity"] = {"nominal": 2.0 ** -int(sys.argv[3])}
json.dump(model, open(sys.argv[2], "w"), indent=1)
EOF
  what="eccentricity 2^-$k mm, the model's spring"
  timeout 300 "$hipair" analyze "$model" --no-pictures >"$work/tiny-$i.txt" 2>"$work/tiny-err-$i.txt" ||
    { fail "$what: exit $?: $(head -c 300 "$work/tiny-err-$i.txt")"; continue; }
  grep -q '  In all: 1 drive period' "$work/tiny-$i.txt" ||
    fail "$what: the follower rides the cam (sweeps 2^-$((k - 1)) mm), but: $(grep '  In all:' "$work/tiny-$i.txt")"
done
for ((i = 0; i < 2; ++i)); do
  e_quarters=$((24 + RANDOM % 17))
  k=$((53 + RANDOM % 28))
  d=$((2 * ((i + RANDOM) % 2) - 1))
  model="$work/lever-$i.json"
  rest=$(python3 - "$source/examples/models/cam-follower-lever.json" "$model" "$e_quarters" "$k" "$d" <<'EOF'
import json, sys
import mpmath
source, target, quarters, k, d = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
model = json.load(open(source))
model["parameters"]["eccentricity"]["nominal"] = quarters / 4
json.dump(model, open(target, "w"), indent=1)
mpmath.mp.prec = 1400
e = mpmath.mpf(quarters) / 4
phi = mpmath.atan2(15 - e, 60) - mpmath.asin(10 / mpmath.sqrt(3600 + (15 - e) ** 2))
grid = phi * 2 ** k
numerator = int(mpmath.floor(grid)) if d < 0 else int(mpmath.ceil(grid))
print(f"{numerator}/{2 ** k}")
EOF
)
  what="lever, e = $e_quarters/4 mm, rest phi* ${d}·2^-$k = $rest rad"
  out="$work/lever-out-$i"
  timeout 300 "$hipair" analyze "$model" --load "lever=spring:$rest" --no-pictures --out "$out" >"$work/lever-$i.txt" 2>"$work/lever-err-$i.txt" ||
    { fail "$what: exit $?: $(head -c 300 "$work/lever-err-$i.txt")"; continue; }
  row=$(grep '^90\.000000000,' "$out/kinematics.csv")
  contacts=${row##*,}
  if ((d > 0)); then
    [ -n "$row" ] && [ "$contacts" != '""' ] || fail "$what: no contact of the lever at 90° (its rest lies beyond the stem tip)"
    grep -A5 'Motion of lever' "$work/lever-$i.txt" | grep -q '  In all: 1 drive period' ||
      fail "$what: the stem tip pushes the lever 2^-$k off its rest, but: $(grep -A5 'Motion of lever' "$work/lever-$i.txt" | grep '  In all:')"
  else
    [ -n "$row" ] && [ "$contacts" = '""' ] || fail "$what: contact $contacts of the lever at 90° (its rest lies short of the stem tip)"
    grep -A5 'Motion of lever' "$work/lever-$i.txt" | grep -q '  In all: 0 drive periods' ||
      fail "$what: the lever never leaves its rest, but: $(grep -A5 'Motion of lever' "$work/lever-$i.txt" | grep '  In all:')"
  fi
done
((failures == 0)) || { echo "spring rest tests: $failures failure(s) (seed $seed)"; exit 1; }
echo "spring rest tests passed (seed $seed, $cases + 3 + 2 + 2 cases)"
