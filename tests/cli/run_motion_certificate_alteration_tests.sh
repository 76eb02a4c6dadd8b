#!/usr/bin/env bash
# Jam and free-passage certificates with altered numbers against hipair-verify, judged by an
# exact oracle of the test's own (tests/fuzz/motion_certificate_alterations.py: closed forms of
# lever-stop.json's overlap interval and distance at 80 digits, not the verifier's or the
# library's code), session 48 (hunt48): generated traps (forward and backward) and driver ranges
# at a generated stop gap, each number altered and the trap's far end, the start, the range's end
# and the distance moved 2^-60 across the truth's boundary.
# usage: run_motion_certificate_alteration_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
"$hipair_python" "$source/tests/fuzz/motion_certificate_alterations.py" "$hipair" "$verify" "$source" "$work" "$seed" 12 ||
  { echo "motion certificate alteration tests failed (seed $seed)"; exit 1; }
echo "motion certificate alteration tests passed (seed $seed)"
