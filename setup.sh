#!/usr/bin/env bash
# HIPAIR set-up: installs what is missing (Debian 12 packages), builds, and then either runs
# the main job on the bundled Geneva example (`./setup.sh demo`) or the whole test suite
# (`./setup.sh test`). Idempotent; run as root (or with sudo available).
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(
  build-essential cmake ccache git clang libclang-rt-14-dev
  libcgal-dev libgmp-dev libmpfr-dev libmpfi-dev libeigen3-dev libboost-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev libbox2d-dev
  libmujoco-dev libexpat1-dev librsvg2-bin libjemalloc-dev python3 python3-jsonschema
)
BUILD_DIR=${HIPAIR_BUILD_DIR:-build}
JOBS=${HIPAIR_JOBS:-$(nproc)}

install_missing() {
  local missing=() package
  for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
      || missing+=("$package")
  done
  if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
}

# Both jobs build everything, the benchmark programs (tests/perf) too: no test runs them, but the
# test job (CI's) is where a change that breaks their compilation must fail (session 74: review74
# ci74 M1; docs/performance.md "Session 74 (ci74)").
build() {
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j "$JOBS"
}

demo() {
  local out=${HIPAIR_OUT:-out/geneva}
  mkdir -p "$out"
  "$BUILD_DIR"/hipair validate examples/models/geneva.json >"$out/validate.txt"
  echo "setup: model is valid (summary in $out/validate.txt)"
  "$BUILD_DIR"/hipair show examples/models/geneva.json --svg "$out/geneva.svg"
  "$BUILD_DIR"/hipair analyze examples/models/geneva.json --out "$out"
  echo
  echo "setup: outputs are in $(cd "$out" && pwd):"
  ls -1 "$out" | sed 's/^/  /'
}

run_tests() {
  # A fresh build directory has no timings, and ctest would start the longest tests last (a
  # long single-file tail). tests/ctest_costs.txt is ctest's own cost file (name, runs, seconds)
  # as measured on the project's machine: seeded once, ctest starts the longest tests first and
  # keeps its own timings from then on.
  local costs="$BUILD_DIR/Testing/Temporary/CTestCostData.txt"
  if [ ! -f "$costs" ]; then
    mkdir -p "$(dirname "$costs")"
    cp tests/ctest_costs.txt "$costs"
  fi
  ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS"
}

case "${1:-}" in
  demo) install_missing; build; demo ;;
  test) install_missing; build; run_tests ;;
  *) echo "usage: $0 demo|test" >&2; exit 64 ;;
esac
