#!/usr/bin/env bash
# Runs hipair-verify on the certificate corpus (tests/data/certificates/EXPECTED.txt): the valid
# certificates must verify (exit 0), every mutation must be rejected (exit 1) with its reason.
# usage: run_corpus.sh HIPAIR_VERIFY SOURCE_DIR
set -u
verify=$1
cd "$2" || exit 2
failures=0
count=0
while IFS='|' read -r certificate model reason; do
  case "$certificate" in '#'*|'') continue ;; esac
  certificate=$(echo $certificate); model=$(echo $model)
  reason=$(echo "$reason" | sed 's/^ *//;s/ *$//')
  output=$("$verify" "tests/data/certificates/$certificate" "$model")
  status=$?
  count=$((count + 1))
  if [ "$reason" = valid ]; then
    [ $status -eq 0 ] || { echo "FAIL $certificate: expected valid, got: $output"; failures=$((failures + 1)); }
  elif [ $status -ne 1 ] || ! printf '%s' "$output" | grep -qF -- "$reason"; then
    echo "FAIL $certificate: expected exit 1 and '$reason', got $status: $output"
    failures=$((failures + 1))
  fi
done < tests/data/certificates/EXPECTED.txt
# Usage errors exit 2.
"$verify" > /dev/null 2>&1; [ $? -eq 2 ] || { echo "FAIL: no arguments should exit 2"; failures=$((failures + 1)); }
echo "$count certificates checked, $failures failures"
[ $failures -eq 0 ]
