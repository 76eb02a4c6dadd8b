#!/usr/bin/env bash
# tests/ctest_costs_check.sh BUILD_DIR [COSTS_FILE]: does tests/ctest_costs.txt (ctest's cost file,
# seeded by setup.sh) list every test of BUILD_DIR once, no test that no longer exists, sorted by
# name (LC_ALL=C sort)? Prints each problem and exits 1 if there is one. Not a ctest test: run it
# after adding or renaming tests (session 74, ci74). Disabled gtest tests keep a line too (ctest
# lists them; their name is the one before " (Disabled)").
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [COSTS_FILE]}
costs=${2:-$(cd "$(dirname "$0")" && pwd)/ctest_costs.txt}
listing=$(ctest --test-dir "$build" -N) || { echo "ctest -N failed in $build" >&2; exit 2; }
tests=$(sed -n 's/^ *Test *#[0-9]*: //p' <<<"$listing" | sed 's/ (Disabled)$//' | LC_ALL=C sort)
names=$(awk 'NF { print $1 }' "$costs")
status=0
missing=$(LC_ALL=C comm -23 <(printf '%s\n' "$tests") <(printf '%s\n' "$names" | LC_ALL=C sort))
stale=$(LC_ALL=C comm -13 <(printf '%s\n' "$tests") <(printf '%s\n' "$names" | LC_ALL=C sort -u))
repeated=$(printf '%s\n' "$names" | LC_ALL=C sort | uniq -d)
malformed=$(awk 'NF && (NF != 3 || $2 !~ /^[0-9]+$/ || $3 !~ /^[0-9.]+$/) { print NR": "$0 }' "$costs")
for kind in missing stale repeated malformed; do
  if [ -n "${!kind}" ]; then
    status=1
    echo "$kind:"
    sed 's/^/  /' <<<"${!kind}"
  fi
done
if ! LC_ALL=C sort -c "$costs" 2>/dev/null; then
  status=1
  echo "not sorted: LC_ALL=C sort -o $costs $costs"
fi
if [ -s "$costs" ] && [ "$(tail -c 1 "$costs" | od -An -c | tr -d ' ')" != '\n' ]; then
  status=1
  echo "no newline at the end of $costs"
fi
[ $status = 0 ] && echo "$costs: $(wc -l <"$costs") lines, one per test of $build, sorted"
exit $status
