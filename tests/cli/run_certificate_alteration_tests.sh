#!/usr/bin/env bash
# Certificates with altered numbers against hipair-verify, judged by an exact oracle of the test's
# own (tests/fuzz/certificate_alterations.py: rational geometry, not the verifier's or the
# library's code), session 47 (hunt47): lever-stop.json's interference / clearance and
# peg-in-hole.json's planar ones at generated configurations, each number altered (last digit,
# sign, 1/den, a relative 10^-k, the point, a coordinate or the distance moved 2^-60 across the
# contact); session 48 (hunt48): film-advance.json's pin-slot claims (film against the follower).
# usage: run_certificate_alteration_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
"$hipair_python" "$source/tests/fuzz/certificate_alterations.py" "$hipair" "$verify" "$source" "$work" "$seed" 12 ||
  { echo "certificate alteration tests failed (seed $seed)"; exit 1; }
echo "certificate alteration tests passed (seed $seed)"
