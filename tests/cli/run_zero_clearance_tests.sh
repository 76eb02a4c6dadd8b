#!/usr/bin/env bash
# Zero-clearance variants of the ratchet, cam follower, Scotch yoke, escapement and lever, every
# C-space cell checked at its sample by certificates (tests/fuzz/zero_clearance_hunt.py), session
# 46 (hunt46). usage: run_zero_clearance_tests.sh HIPAIR_BINARY HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)')
hipair=$1 verify=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
"$hipair_python" "$source/tests/fuzz/zero_clearance_hunt.py" "$hipair" "$verify" "$source/examples/models" "$work" ||
  { echo "zero-clearance tests failed"; exit 1; }
echo "zero-clearance tests passed"
