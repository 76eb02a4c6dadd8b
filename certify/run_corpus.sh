#!/usr/bin/env bash
# End to end: produces the corpus's base certificates with `hipair certify` (against the current
# model reader), writes the mutations (make_corpus.py), and runs hipair-verify on every one:
# the valid certificates must verify (exit 0), the no_jam tolerance bases that check 7 does not
# prove must be answered "unproven" (exit 3: their evidence passes checks 1-6, the free follower
# path is not proved; docs/certify.md), every
# mutation must be rejected (exit 1) with its reason. With WORK_DIR = tests/data/certificates it checks the committed snapshot instead.
# usage: run_corpus.sh HIPAIR_VERIFY HIPAIR_CLI SOURCE_DIR WORK_DIR
set -u
verify=$1; cli=$2; source=$3; work=$4
corpus=$source/tests/data/certificates
if [ "$(cd "$work" 2>/dev/null && pwd)" != "$(cd "$corpus" && pwd)" ]; then
  rm -rf "$work" && mkdir -p "$work"
  bash "$corpus/make_bases.sh" "$cli" "$source" "$work" > "$work/bases.log" || { cat "$work/bases.log"; exit 1; }
  python3 "$corpus/make_corpus.py" --dir "$work" --source "$source" || exit 1
fi
cd "$source" || exit 2
failures=0
count=0
while IFS="|" read -r certificate model reason base; do
  case "$certificate" in '#'*|'') continue ;; esac
  certificate=$(echo $certificate); model=$(echo $model)
  reason=$(echo "$reason" | sed 's/^ *//;s/ *$//')
  output=$("$verify" "$work/$certificate" "$model")
  status=$?
  count=$((count + 1))
  if [ "$reason" = valid ]; then
    [ $status -eq 0 ] && printf '%s' "$output" | grep -q '^valid: ' ||
      { echo "FAIL $certificate: expected valid, got $status: $output"; failures=$((failures + 1)); }
  elif [ "$reason" = unproven ]; then
    [ $status -eq 3 ] && printf '%s' "$output" | grep -q '^unproven: .*; not proved: a free path for the follower' ||
      { echo "FAIL $certificate: expected exit 3 and 'unproven:', got $status: $output"; failures=$((failures + 1)); }
  elif [ $status -ne 1 ] || ! printf '%s' "$output" | grep -qF -- "$reason"; then
    echo "FAIL $certificate: expected exit 1 and '$reason', got $status: $output"
    failures=$((failures + 1))
  fi
done < "$work/EXPECTED.txt"
# Usage errors exit 2.
"$verify" > /dev/null 2>&1; [ $? -eq 2 ] || { echo "FAIL: no arguments should exit 2"; failures=$((failures + 1)); }
echo "$count certificates checked, $failures failures"
[ $failures -eq 0 ]
