# Shared preamble of the generated CLI tests (sourced with the test's own arguments):
#   source "$(dirname "$0")/seeded_test.sh" "$@"    # HIPAIR_BINARY SOURCE_DIR WORK_DIR
# Sets hipair, source and work (emptied), failures=0, seed (HIPAIR_TEST_SEED, or a random one;
# bash's RANDOM seeded with it, so a failing run repeats), and fail MESSAGE, which prints the
# message with the seed and counts a failure.
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
seed=${HIPAIR_TEST_SEED:-$RANDOM}
RANDOM=$seed
fail() { echo "FAIL (seed $seed): $*"; failures=$((failures + 1)); }
