#!/usr/bin/env bash
# `hipair tolerance --certify --certify-witness-splits N` (session 71, tol71): the no-jam
# producer's witness-split budget at the command line. A leaf whose named sides checks 1-6 prove
# apart from their slopes alone, without a witness follower path, is split along the driver at most
# N times along a branch, then accepted: the certificate is written, `unproven`, naming that leaf.
# On the escapement (the wheel driving the anchor) every range across a drop needs at least one
# such split, so N = 0 reaches the exhausted path:
# - driver 0.2 .. 0.45 rad (the first drop at 0.40 rad), and 2 generated ranges of 0.1 rad across a
#   random tooth's drop at 1/2 or 3/4 of the tolerances: exit 0 (the analysis ran; the verdict is
#   the report's), report.txt says "WRITTEN, NOT PROVED" with the reason "leaf K has no witness path
#   for the follower" and names the budget's option, tolerance.json's certificate.verifier_verdict is "unproven", and hipair-verify
#   answers the written tolerance-certificate.json `unproven: ... leaf K ...` with exit 3 (the same
#   leaf K);
# - the default budget (6) on 0.2 .. 0.45 rad: CERTIFIED, hipair-verify `valid`, exit 0;
# - bad input, one message naming the option, nothing written: N = 65 (beyond 64), N = -1,
#   N without --certify, N with --certify-interference;
# - session 72: tolerance.json's `budgets` records the witness-split budget (0, 6) and the leaf
#   budget; `--chain-split-budget` refused without --chain, at 0 and beyond 1024.
# usage: run_tolerance_witness_budget_tests.sh HIPAIR_BINARY HIPAIR_VERIFY_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"
model="$source/examples/models/escapement.json"

# exhausted NAME RANGE SCALE: the budget-0 run over RANGE at SCALE x the tolerances
exhausted() {
  local name=$1 range=$2 scale=$3 dir="$work/$1"
  "$hipair" tolerance "$model" --range "$range" --certify --certify-scale "$scale" --certify-witness-splits 0 \
    --accuracy 0.5 --threads 1 --quiet --out "$dir" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  [ $code -eq 0 ] || { fail "$name (--range $range, scale $scale): exit $code: $(cat "$work/$name.err")"; return; }
  local line
  line=$(grep -F "WRITTEN, NOT PROVED" "$dir/report.txt")
  [ -n "$line" ] || { fail "$name: the report does not say WRITTEN, NOT PROVED: $(grep -A1 'certificate (' "$dir/report.txt")"; return; }
  local leaf
  leaf=$(grep -oE "leaf [0-9]+ has no witness path for the follower" <<<"$line" | head -n 1 | awk '{ print $2 }')
  [ -n "$leaf" ] || { fail "$name: the reason names no leaf without a witness path: $line"; return; }
  grep -qF "split at most --certify-witness-splits times along a branch" <<<"$line" \
    || fail "$name: the report does not say what the budget is: $line"
  # the budget the result was computed with is recorded (session 72: tolerance.json's budgets)
  grep -qE '"certify_witness_splits": 0,?$' "$dir/tolerance.json" \
    || fail "$name: tolerance.json does not record the budget 0: $(grep -F certify_witness_splits "$dir/tolerance.json")"
  grep -qF '"verifier_verdict": "unproven"' "$dir/tolerance.json" \
    || fail "$name: tolerance.json's verdict is not unproven: $(grep -F verifier_verdict "$dir/tolerance.json")"
  [ -s "$dir/tolerance-certificate.json" ] || { fail "$name: no tolerance-certificate.json written"; return; }
  # the leaf named has indeed no witness path in the written file
  python3 - "$dir/tolerance-certificate.json" "$leaf" <<'PY' || fail "$name: leaf $leaf of the written certificate has a witness path"
import json, sys
c = json.load(open(sys.argv[1]))
leaves = c["tolerance"]["leaves"]
sys.exit(0 if leaves[int(sys.argv[2])].get("witness") is None else 1)
PY
  local out
  out=$("$verify" "$dir/tolerance-certificate.json" "$model" 2>&1)
  code=$?
  [ $code -eq 3 ] || fail "$name: hipair-verify exit $code, not 3 (unproven): $out"
  case "$out" in unproven:*"leaf $leaf has no witness path for the follower"*) ;;
    *) fail "$name: hipair-verify does not answer unproven naming leaf $leaf: $out" ;; esac
}

exhausted drop1 0.2:0.45 1
for trial in 1 2; do
  tooth=$((RANDOM % 14 + 1))
  from=$(awk -v t="$tooth" 'BEGIN { printf "%.6f", 0.33 + t * 0.41887902 }')
  to=$(awk -v f="$from" 'BEGIN { printf "%.6f", f + 0.1 }')
  scales=(1/2 3/4)
  exhausted "generated$trial" "$from:$to" "${scales[$((RANDOM % 2))]}"
done

# the default budget on the same range: proved
dir="$work/default"
"$hipair" tolerance "$model" --range 0.2:0.45 --certify --accuracy 0.5 --threads 1 --quiet --out "$dir" \
  >"$work/default.out" 2>&1 || fail "default budget: exit non-zero: $(tail -n 2 "$work/default.out")"
grep -q "CERTIFIED" "$dir/report.txt" || fail "default budget: not CERTIFIED: $(grep -A1 'certificate (' "$dir/report.txt")"
grep -qE '"certify_witness_splits": 6,?$' "$dir/tolerance.json" \
  || fail "default budget: tolerance.json does not record the budget 6: $(grep -F certify_witness_splits "$dir/tolerance.json")"
grep -qE '"certify_max_leaves": 20000,?$' "$dir/tolerance.json" \
  || fail "default budget: tolerance.json does not record the leaf budget: $(grep -F certify_max_leaves "$dir/tolerance.json")"
out=$("$verify" "$dir/tolerance-certificate.json" "$model" 2>&1) || fail "default budget: hipair-verify exit $?: $out"
case "$out" in valid:*) ;; *) fail "default budget: hipair-verify does not answer valid: $out" ;; esac

# bad input: one message naming the option, non-zero exit, nothing written
refused() {
  local name=$1 expect=$2
  shift 2
  "$hipair" tolerance "$model" "$@" --quiet --out "$work/$name" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  [ $code -ne 0 ] || fail "$name: accepted ($*)"
  grep -qF -- "$expect" "$work/$name.err" || fail "$name: not '$expect': $(cat "$work/$name.err")"
  [ ! -e "$work/$name" ] || fail "$name: $work/$name written"
  [ "$(grep -c . "$work/$name.err")" -eq 1 ] || fail "$name: not one line: $(cat "$work/$name.err")"
}
refused beyond "--certify-witness-splits" --range 0.2:0.45 --certify --certify-witness-splits 65
refused negative "--certify-witness-splits" --range 0.2:0.45 --certify --certify-witness-splits -1
refused alone "--certify-witness-splits is for --certify or --certify-free-path" --range 0.2:0.45 --certify-witness-splits 3
refused interference "--certify-witness-splits is for the no-jam certificate" --certify-interference --range 0:0.1 \
  --follower-range -0.1:0.1 --certify-witness-splits 3
# the chain's split budget (session 72): for --chain only, 1 to 1024
refused chain_alone "--chain-split-budget is for --chain" --range 0.2:0.45 --chain-split-budget 8
refused chain_zero "--chain-split-budget" --driver escape-wheel --chain --range 0.2:0.45 --chain-split-budget 0
refused chain_beyond "--chain-split-budget" --driver escape-wheel --chain --range 0.2:0.45 --chain-split-budget 1025

[ $failures -eq 0 ] && echo "tolerance witness-budget tests passed (seed $seed)"
exit $((failures > 0))
