#!/usr/bin/env bash
# "Never interferes" tolerance certificates with altered numbers against hipair-verify, judged by
# an exact oracle of the test's own (tests/fuzz/tolerance_certificate_alterations.py: the closed
# form of the least clearance between lever-stop.json's lever and its stop made a slider, at its
# worst corner of parameters x driver x follower, 80 digits; not the verifier's or the library's
# code), session 49 (hunt49): generated scales, driver ranges and follower ranges, each number
# of the claim and its leaves altered, a leaf or a varied parameter dropped, and the range's end,
# the follower range's end and the scale moved 2^-60 across the truth's boundary.
# usage: run_tolerance_certificate_alteration_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
"$hipair_python" "$source/tests/fuzz/tolerance_certificate_alterations.py" "$hipair" "$verify" "$source" "$work" "$seed" 12 ||
  { echo "tolerance certificate alteration tests failed (seed $seed)"; exit 1; }
echo "tolerance certificate alteration tests passed (seed $seed)"
