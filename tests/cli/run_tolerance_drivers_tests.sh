#!/usr/bin/env bash
# Session 75 (tol75, hostile74 M2): every driver that `hipair analyze` accepts, `hipair tolerance`
# analyses or refuses cleanly, never with an internal error. Generated over the example models:
# every part with a rotation or translation motion is tried as --driver (analyze first: exit 0 means
# it accepts that driver); tolerance (16 positions, 1 thread) must then exit 0, or 2 with one line
# "hipair: error: ...". base75 stopped with exit 3 ("C-space slicer: pair A:B is sliced across its
# x axis only") wherever the driver is its pair's second part: cam-follower's follower (hostile74
# M2), geneva's wheel, scotch-yoke's yoke, lift-chain's lifters, ratchet's pawl, two-pin-wedge's
# plunger. The first such driver of a model is also given as --pair DRIVER:OTHER --threshold. The gear
# trains, the spur gears and the escapement are left out for their cost (minutes, or 12 s for
# the balance; their large pairs take analyze's kernel path, as before).
# usage: run_tolerance_drivers_tests.sh HIPAIR SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
models=$source/examples/models
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }

# "PART SECOND OTHER" per moving part: SECOND 1 when, in the first pair of two moving parts holding
# it (the pair tolerance takes), it is the second part; OTHER that pair's other part ("-": none)
moving_parts() {
  python3 - "$1" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
def moves(p):
    mo = p.get("motion")
    return isinstance(mo, dict) and ("rotation" in mo or "translation" in mo)
moving = {p["name"] for p in m.get("parts", []) if moves(p)}
for p in m.get("parts", []):
    if p["name"] not in moving:
        continue
    second, other = 0, "-"
    for pair in m.get("pairs", []):
        a, b = pair["parts"]
        if a in moving and b in moving and p["name"] in (a, b):
            second, other = (1, a) if b == p["name"] else (0, b)
            break
    print(p["name"], second, other)
PY
}

analysed=0 second_analysed=0 refused=0 paired=
for model in cam-drive cam-follower cam-follower-lever cam-shim-stack geneva geneva-drive geneva-template lift-chain \
             ratchet scotch-yoke two-pin-wedge lever-stop film-advance bouncing-bar; do
  file=$models/$model.json
  [ -f "$file" ] || { fail "$model: missing"; continue; }
  parts=$(moving_parts "$file") || { fail "$model: not read"; continue; }
  while read -r part second other; do
    [ -n "$part" ] || continue
    "$hipair" analyze "$file" --driver "$part" >"$work/a.out" 2>&1
    [ $? -eq 0 ] || continue   # a driver analyze refuses is not asked of tolerance
    forms=("--driver $part")
    # the --pair form once per model, with the threshold search (hostile74 M2's three forms)
    if [ "$second" = 1 ] && [ "$paired" != "$model" ]; then
      forms+=("--pair $part:$other --threshold")
      paired=$model
    fi
    for form in "${forms[@]}"; do
      out=$work/$model-$part-${form:2:4}.out
      # shellcheck disable=SC2086  # the form is two words
      "$hipair" tolerance "$file" $form --positions 16 --threads 1 --quiet >"$out" 2>"$out.err"
      status=$?
      case $status in
        0)
          grep -q "^Tolerance analysis of '" "$out" || fail "$model $form: exit 0 without the report"
          analysed=$((analysed + 1))
          [ "$second" = 1 ] && second_analysed=$((second_analysed + 1))
          ;;
        2)
          lines=$(wc -l <"$out.err")
          if [ "$lines" -ne 1 ] || ! grep -q '^hipair: error: ' "$out.err"; then
            fail "$model $form: exit 2 without one clear line: $(head -c 300 "$out.err")"
          fi
          grep -qi "slicer\|x axis" "$out.err" && fail "$model $form: refused naming internal machinery: $(head -c 300 "$out.err")"
          refused=$((refused + 1))
          ;;
        *)
          fail "$model $form: exit $status (analyze accepts this driver): $(head -c 300 "$out.err")"
          ;;
      esac
    done
  done <<<"$parts"
done
# not vacuous: drivers analysed, among them drivers that are their pair's second part
[ "$analysed" -ge 20 ] || fail "only $analysed tolerance analyses ran"
[ "$second_analysed" -ge 15 ] || fail "only $second_analysed analyses of a pair's second part as driver ran"
echo "tolerance analyses: $analysed (of a pair's second part as driver: $second_analysed), clean refusals: $refused"
if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all tolerance driver tests passed"
