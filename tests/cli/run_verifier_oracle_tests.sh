#!/usr/bin/env bash
# A fuzz test that judges hipair / hipair-verify verdicts by an exact oracle of the test's own
# (tests/fuzz/SCRIPT: rational geometry or closed forms at 80 digits, not the verifier's or the
# library's code), at the seed seeded_test.sh picks; tests/CMakeLists.txt says what each one
# alters and checks (certificate_alteration, motion_ and tolerance_certificate_alteration,
# analyze_contact_side).
# usage: run_verifier_oracle_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR SCRIPT CASES LABEL
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
verify=$2
script=$5
cases=$6
label=$7
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
"$hipair_python" "$source/tests/fuzz/$script" "$hipair" "$verify" "$source" "$work" "$seed" "$cases" ||
  { echo "$label tests failed (seed $seed)"; exit 1; }
echo "$label tests passed (seed $seed)"
