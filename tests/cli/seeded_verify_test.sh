# Shared preamble of the CLI tests that run both hipair and hipair-verify (sourced with the
# test's own arguments):
#   source "$(dirname "$0")/seeded_verify_test.sh" "$@"   # HIPAIR_BINARY HIPAIR_VERIFY SOURCE_DIR WORK_DIR
# python3 resolved once to the interpreter itself (a pyenv shim starts a shell script per call,
# ~0.7 s of CPU each, and these scripts call python3 in loops: session 43, build43); sets verify,
# then everything seeded_test.sh sets (hipair, source, work emptied, failures=0, seed, fail).
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
verify=$2
# shellcheck source=seeded_test.sh
source "$(dirname "${BASH_SOURCE[0]}")/seeded_test.sh" "$1" "$3" "$4"
