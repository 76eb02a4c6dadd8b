#!/usr/bin/env bash
# analyze's contacts against the exact overlap predicate at generated samples (the follower moved
# 10^-6 into the named contact overlaps, away from it is apart; a free dwell is apart:
# tests/fuzz/analyze_contact_sides.py), on generated in-tolerance variants of the turning-stop
# lever, ratchet, cam follower and Geneva drive, session 47 (hunt47).
# usage: run_analyze_contact_side_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
"$hipair_python" "$source/tests/fuzz/analyze_contact_sides.py" "$hipair" "$verify" "$source" "$work" "$seed" 8 ||
  { echo "analyze contact-side tests failed (seed $seed)"; exit 1; }
echo "analyze contact-side tests passed (seed $seed)"
