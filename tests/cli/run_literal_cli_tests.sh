#!/usr/bin/env bash
# Exact literals outside the format, session 40 (hunt40): `--set NAME=VALUE` of every command
# that reads a model, `simulate --sweep NAME=A:B:N`, and a certificate's rationals read by
# hipair-verify take the model's exact literal (docs/model-format.md "Numbers"): an optional
# '-', digits with '.', an exponent and '/'; no space, tab or '+' around it, ASCII digits only,
# the exponent within 1000. Generated cases (a seed per run, printed on failure; HIPAIR_TEST_SEED
# repeats one): a valid value of lever-length spoiled by one of the malformations below must be
# refused with exit 2 (the verifier: 1), one line naming the option or the JSON pointer, nothing
# on stdout and no --out directory; the same values unspoiled must still be read. An empty
# model.file is refused at its pointer.
# usage: run_literal_cli_tests.sh HIPAIR_BINARY HIPAIR_VERIFY_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"
# shellcheck source=expect_refused.sh
source "$(dirname "$0")/expect_refused.sh"
model="$source/examples/models/lever-stop.json"
certificate="$source/tests/data/certificates/lever-clearance.json"

# values of lever-length inside its tolerance range [59.95, 60.05], as exact literals
valid=(60 60.0 60. 6e1 6E+1 600e-1 0.6e2 .6e2 1200/20 120/2.0 6e3/1e2 60.04 5996e-2)
# one malformation of a valid literal v, chosen by $1 (a certificate number is 2, the same way)
spoil() {
  local v=$1 digits=("٦" "６" "۶" "६" "𝟔")
  case $2 in
    0) printf ' %s' "$v" ;;
    1) printf '%s ' "$v" ;;
    2) printf '\t%s' "$v" ;;
    3) printf '%s\t' "$v" ;;
    4) printf '+%s' "$v" ;;
    5) printf '%s%s' "${digits[RANDOM % 5]}" "${v:1}" ;;   # a non-ASCII digit first
    6) printf '%s/0' "$v" ;;
    7) printf '%se' "$v" ;;
    8) printf '%se+' "$v" ;;
    9) printf '%se%d' "$v" $((1001 + RANDOM * 97)) ;;
    10) printf '%se-%d' "$v" $((1001 + RANDOM)) ;;
    11) printf '' ;;
    12) printf '%s' "${v:0:1} ${v:1}" ;;
    13) printf 'nan' ;;
    14) printf '0x%x' 60 ;;
    15) printf '%s/-2' "$v" ;;
    16) printf -- '--%s' "$v" ;;
    17) printf '%s/%s/1' "$v" "$v" ;;
    18) printf '%s.' "${v%.}.0" ;;
    19) printf '%s\xc2\xa0' "$v" ;;   # no-break space
  esac
}
kinds=20
commands=(validate "show --svg $work/x.svg" "cspace --json $work/x.json" "analyze --out $work/out"
          "tolerance --out $work/out" "certify --claim clearance --out $work/c.json" "simulate --t-end 0.01 --out $work/out")

# valid values are read
for i in 1 2 3 4; do
  v=${valid[RANDOM % ${#valid[@]}]}
  "$hipair" validate "$model" --set "lever-length=$v" >"$work/ok.out" 2>&1 \
    || fail "validate refuses --set lever-length=$v: $(head -c 300 "$work/ok.out")"
done

cases=0
for round in $(seq 1 $kinds); do
  v=${valid[RANDOM % ${#valid[@]}]}
  kind=$((round - 1))
  bad=$(spoil "$v" $kind)
  command=${commands[RANDOM % ${#commands[@]}]}
  rm -rf "$work/out" "$work/x.svg" "$work/x.json" "$work/c.json"
  # shellcheck disable=SC2086
  "$hipair" $command "$model" --set "lever-length=$bad" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  cases=$((cases + 1))
  what="$command --set lever-length=[$bad] (kind $kind)"
  expect_refused "$what" "^hipair: error: --set lever-length="
  # the sweep's ends (simulate --sweep NAME=A:B:N, A or B the spoiled literal)
  if [ $((round % 3)) -eq 0 ]; then
    ends="$bad:60:2"; [ $((RANDOM % 2)) -eq 0 ] && ends="60:$bad:2"
    "$hipair" simulate "$model" --t-end 0.01 --sweep "lever-length=$ends" --out "$work/out" >"$work/bad.out" 2>"$work/bad.err"
    status=$?
    [ $status -eq 2 ] || fail "--sweep lever-length=[$ends]: exit $status, not 2: $(head -c 300 "$work/bad.err")"
    grep -q "^hipair: error: --sweep lever-length=" "$work/bad.err" || fail "--sweep [$ends]: $(cat "$work/bad.err")"
    [ -e "$work/out" ] && fail "--sweep [$ends]: wrote its --out directory"
  fi
  # the certificate's distance (2) or a parameter's value, spoiled the same way
  c2=$(spoil "${v//6/2}" $kind)
  python3 - "$certificate" "$work/bad-certificate.json" "$c2" $((RANDOM % 3)) <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
where = int(sys.argv[4])
if where == 0: c["clearance"]["distance"] = sys.argv[3]
elif where == 1: c["model"]["parameters"]["stop-gap"]["value"] = sys.argv[3]
else: c["clearance"]["configuration"]["lever"]["tangent"] = sys.argv[3]
json.dump(c, open(sys.argv[2], "w"), ensure_ascii=False)
PY
  "$verify" "$work/bad-certificate.json" "$model" >"$work/verify.out" 2>"$work/verify.err"
  status=$?
  [ $status -eq 1 ] || fail "certificate number [$c2]: hipair-verify exit $status, not 1: $(head -c 300 "$work/verify.out")"
  grep -q "^invalid: malformed certificate: /[a-z/_-]*: not an exact rational: " "$work/verify.out" \
    || fail "certificate number [$c2]: $(head -c 300 "$work/verify.out")"
  [ "$(wc -l <"$work/verify.out")" -eq 1 ] && [ ! -s "$work/verify.err" ] || fail "certificate number [$c2]: not one line on stdout"
done

# the unspoiled certificate still verifies; with an equal value in another valid form as well
"$verify" "$certificate" "$model" >"$work/verify.out" 2>&1 || fail "lever-clearance.json: $(cat "$work/verify.out")"
python3 -c '
import json, sys
c = json.load(open(sys.argv[1])); c["clearance"]["distance"] = "4/2"; c["model"]["parameters"]["stop-gap"]["value"] = "0.2e1"
json.dump(c, open(sys.argv[2], "w"))' "$certificate" "$work/other-forms.json"
"$verify" "$work/other-forms.json" "$model" >"$work/verify.out" 2>&1 || fail "4/2 and 0.2e1 refused: $(cat "$work/verify.out")"
# an empty model.file
python3 -c '
import json, sys
c = json.load(open(sys.argv[1])); c["model"]["file"] = ""
json.dump(c, open(sys.argv[2], "w"))' "$certificate" "$work/empty-file.json"
"$verify" "$work/empty-file.json" "$model" >"$work/verify.out" 2>&1
[ $? -eq 1 ] && grep -q "^invalid: malformed certificate: /model/file: an empty file name" "$work/verify.out" \
  || fail "an empty model.file: $(cat "$work/verify.out")"

echo "$cases spoiled literals (seed $seed), $failures failures"
[ $failures -eq 0 ]
