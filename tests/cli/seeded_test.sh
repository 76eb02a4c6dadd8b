# Shared preamble of the generated CLI tests (sourced with the test's own arguments):
#   source "$(dirname "$0")/seeded_test.sh" "$@"    # HIPAIR_BINARY SOURCE_DIR WORK_DIR
# Sets hipair, source and work (emptied), failures=0, seed (HIPAIR_TEST_SEED; a fixed default, so
# that a CI run repeats; HIPAIR_TEST_SEED=random draws one; bash's RANDOM seeded with it), and fail MESSAGE, which prints the
# message with the seed and counts a failure.
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
seed=${HIPAIR_TEST_SEED:-61}; [ "$seed" = random ] && seed=$RANDOM
RANDOM=$seed
fail() { echo "FAIL (seed $seed): $*"; failures=$((failures + 1)); }
