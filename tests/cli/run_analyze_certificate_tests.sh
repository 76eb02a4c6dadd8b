#!/usr/bin/env bash
# Session 37 (hunt37): the certificates `hipair analyze --out` writes for its findings must verify
# against the model file with `hipair-verify`. Until session 37 analyze dropped its --set values
# (the certificate recorded the file's nominal values as not overridden, so it described another
# model and failed to verify), and under --rounding it recorded roundings the verifier (which reads
# the file's own rounding key) does not make.
# Generated cases: two bars turning about pivots 20 s apart (s = 10^k, k in -300 ... 300), the
# second one's inner end at (10 + gap) s with gap set by --set within its tolerance and below 0,
# so the bars overlap at the initial configuration by construction (x in [(10 + gap) s, 10 s],
# y in [-s, s]); its upper side at w s, w a rational or a square root (a rounding).
# Oracle: the overlap by construction (analyze must certify it), and hipair-verify must answer
# `valid` for every certificate written; the certificate records gap = the --set value, overridden.
# Under --rounding a certificate is written only if it verifies (else "not certified: ...").
# usage: run_analyze_certificate_tests.sh HIPAIR HIPAIR_VERIFY WORK_DIR [SEED]
set -uo pipefail
# python3 resolved once to the interpreter itself: a pyenv shim starts a shell script per call
# (~0.7 s of CPU each), and these scripts call python3 in loops (session 43, build43).
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
hipair=$1 verify=$2 work=$3 seed=${4:-37}
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
RANDOM=$seed

model() {   # model FILE EXPONENT W: the two bars at scale 10^EXPONENT
  local s="1e$2" w=$3
  cat >"$1" <<EOF
{ "hipair": 1, "name": "overlapping-bars",
  "parameters": { "gap": { "nominal": "$s", "tolerance": "3 * $s" }, "w": { "nominal": "$w * $s" } },
  "parts": [
    { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [
      { "start": [0, "-$s"], "edges": [ {"line_to": ["10 * $s", "-$s"]}, {"line_to": ["10 * $s", "$s"]},
                                       {"line_to": [0, "$s"]}, {"line_to": [0, "-$s"]} ] } ] },
    { "name": "b", "motion": { "rotation": { "pivot": ["20 * $s", 0] } }, "loops": [
      { "start": ["10 * $s + gap", "-$s"], "edges": [ {"line_to": ["20 * $s", "-$s"]}, {"line_to": ["20 * $s", "w"]},
                                                     {"line_to": ["10 * $s + gap", "w"]}, {"line_to": ["10 * $s + gap", "-$s"]} ] } ] }
  ] }
EOF
}

cases=0
for round in 1 2 3 4 5 6 7 8; do
  exponents=(-300 -30 0 0 30 300)
  e=${exponents[$((RANDOM % 6))]}
  ws=("sqrt(2)" "sqrt(3)" "3/2" "1" "7/5")
  w=${ws[$((RANDOM % 5))]}
  [ $round -eq 1 ] && e=0 w="sqrt(2)"   # always one rounded value at scale 1
  gap="-$((RANDOM % 19 + 1))e$((e - 1))"   # -(1 ... 19)/10 s, within the tolerance +-3 s
  m="$work/bars-$round.json"
  model "$m" "$e" "$w"
  for rounding in "" 1e-6; do
    cases=$((cases + 1))
    out="$work/out-$round${rounding:+-r}"
    args=(analyze "$m" --set "gap=$gap" --out "$out" --no-pictures --quiet --range 0:0.01)
    [ -n "$rounding" ] && args+=(--rounding "$rounding")
    "$hipair" "${args[@]}" >"$out.log" 2>&1 || { fail "round $round (10^$e, w $w, gap $gap${rounding:+, --rounding $rounding}): analyze failed: $(tail -2 "$out.log")"; continue; }
    certificate="$out/certificate-1.json"
    if [ ! -f "$certificate" ]; then
      # only under --rounding with a rounded w may the certificate be withheld, and then said so
      if [ -z "$rounding" ] || [[ $w != sqrt* ]] || ! grep -q "^not certified: interference of a:b .*--rounding" "$out.log"; then
        fail "round $round (10^$e, w $w, gap $gap${rounding:+, --rounding $rounding}): no certificate of the overlap: $(grep -m1 'not certified' "$out.log")"
      fi
      continue
    fi
    "$verify" "$certificate" "$m" >"$out.verify" 2>&1 \
      || fail "round $round (10^$e, w $w, gap $gap${rounding:+, --rounding $rounding}): analyze wrote a certificate hipair-verify rejects: $(cat "$out.verify")"
    python3 - "$certificate" "$gap" <<'EOF' || fail "round $round: the certificate does not record gap=$gap as overridden"
import json, sys
from fractions import Fraction
from decimal import Decimal
c = json.load(open(sys.argv[1]))
g = c['model']['parameters']['gap']
want = Fraction(Decimal(sys.argv[2]))
sys.exit(0 if g['overridden'] and Fraction(g['value']) == want else 1)
EOF
  done
done
echo "$cases cases, $failures failures"
[ $failures -eq 0 ]
