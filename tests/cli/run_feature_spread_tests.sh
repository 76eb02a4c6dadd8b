#!/usr/bin/env bash
# Session 53 (scale53): a pair whose smallest edge is below 2^-1330 (about 1e-400) of its extent is
# refused before work by every command that builds or slices it (the exact arithmetic's cost
# grows with the square of the spread's exponent: cam-follower.json with a 1e-999 mm face ran
# for about 110 s in `cspace`, and `analyze`, `tolerance`, `simulate` likewise, until session 53).
# Generated widths 10^-E, E in 405..999 (random), of the follower's flat face of cam-follower.json
# (its nominal, written into a copy of the model): each command exits 3 within 5 s with one message naming
# the part, the edge's pointer and the limit, writes nothing; `validate` and `show` still accept
# the model (they build no pair); a uniform scale (the model x 1e-300 with a 1e-300 face width,
# read exactly) is not refused by the limit (its spread is the model's own).
# usage: run_feature_spread_tests.sh HIPAIR SOURCE_DIR WORK_DIR [SEED]
set -uo pipefail
hipair=$1 source=$2 work=$3 seed=${4:-53}
rm -rf "$work" && mkdir -p "$work"
model="$source/examples/models/cam-follower.json"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
RANDOM=$seed
for round in 1 2 3; do
  e=$((405 + RANDOM % 595))
  narrow="$work/narrow-$round.json"
  python3 - "$model" "$narrow" "1e-$e" <<'PY' || fail "writing the model"
import json, sys
with open(sys.argv[1], encoding="utf-8") as f:
    model = json.load(f)
model["parameters"]["face-width"] = {"nominal": sys.argv[3]}
with open(sys.argv[2], "w", encoding="utf-8") as f:
    json.dump(model, f)
PY
  for command in cspace analyze tolerance simulate certify; do
    out="$work/$command-$round"
    case $command in
      cspace) args=(cspace "$narrow" --json "$out.json") ;;
      analyze) args=(analyze "$narrow" --quiet --out "$out") ;;
      tolerance) args=(tolerance "$narrow" --quiet --out "$out") ;;
      simulate) args=(simulate "$narrow" --t-end 0.01 --no-pictures --out "$out") ;;
      certify) args=(certify "$narrow" --claim clearance --out "$out.json") ;;
    esac
    start=$SECONDS
    timeout 60 "$hipair" "${args[@]}" >"$out.stdout" 2>"$out.stderr"
    rc=$?
    [ $rc -eq 3 ] || fail "$command face 1e-$e: exit $rc (expected 3): $(head -c 300 "$out.stderr")"
    [ $((SECONDS - start)) -le 5 ] || fail "$command face 1e-$e: $((SECONDS - start)) s before the refusal"
    grep -q "^hipair: error: part 'follower' (/parts/1) has an edge (/parts/1/loops/0/edges/[0-9]) of about 2^-[0-9]* mm in its pair with 'cam'.*at least 2^-1330 (about 1e-400) of its extent" "$out.stderr" \
      || fail "$command face 1e-$e: message $(head -c 300 "$out.stderr")"
    [ -e "$out" ] || [ -e "$out.json" ] && fail "$command face 1e-$e: output written"
  done
  "$hipair" validate "$narrow" >/dev/null 2>&1 || fail "validate refused the face 1e-$e"
done
# a uniformly tiny model keeps its spread: analyze runs (rescaled, session 53)
python3 "$source/tests/fuzz/scale_model.py" "$model" 1e-300 "$work/tiny.json" || fail "scale_model"
"$hipair" analyze "$work/tiny.json" --quiet --no-pictures >/dev/null 2>"$work/tiny.stderr" \
  || fail "analyze x1e-300: $(head -c 300 "$work/tiny.stderr")"
echo "feature spread: $failures failure(s)"
[ $failures -eq 0 ]
