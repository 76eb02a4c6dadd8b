#!/usr/bin/env bash
# The integrator's instruction counts (callgrind: repeatable whatever the machine's load).
#
#   tests/perf/callgrind_suite.sh BUILD_DIR [OUTFILE]
#
# BUILD_DIR holds hipair and tests/perf/hipair_simulation_speed (a build tree, or a copy with the
# same layout). Prints one line per work: NAME <TAB> instructions. Rows:
#   cspace escapement / geneva (whole process), analyze ratchet / geneva --out (whole process),
#   the gear-train tolerance row (whole process), the escapement and Geneva simulation loops
#   (--toggle-collect on Simulation::run_until, one benchmark each).
# Valgrind rounds to nearest whatever rounding mode a program sets, and CGAL's interval filters
# need the upward mode: a work that decides CGAL predicates at degenerate configurations can stop
# under valgrind only (the film advance's film:follower pair at tau = 1/60). Measure such a work
# on a build configured with -DHIPAIR_CGAL_ROUND_TO_NEAREST=ON (CMakeLists.txt), both sides.
set -uo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(readlink -f "$1"); result=${2:-/dev/stdout}
models=$here/examples/models
tmp=$(mktemp -d)
count() { # NAME CALLGRIND-ARGS... -- COMMAND...
  local name=$1; shift
  local vg=()
  while [ "$1" != "--" ]; do vg+=("$1"); shift; done; shift
  (cd "$tmp" && valgrind --tool=callgrind --callgrind-out-file="$tmp/$name.cg" "${vg[@]}" "$@" \
    >"$tmp/$name.out" 2>"$tmp/$name.err")
  local total
  total=$(callgrind_annotate "$tmp/$name.cg" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1; exit}')
  printf '%s\t%s\n' "$name" "${total:-failed}"
}
{
  count cspace_escapement -- "$build/hipair" cspace "$models/escapement.json" --json "$tmp/e.json"
  count cspace_geneva -- "$build/hipair" cspace "$models/geneva.json" --json "$tmp/g.json"
  count analyze_ratchet -- "$build/hipair" analyze "$models/ratchet.json" --quiet --out "$tmp/ar"
  count analyze_geneva -- "$build/hipair" analyze "$models/geneva.json" --quiet --out "$tmp/ag"
  count gear_row -- "$build/hipair" tolerance "$models/gear-train.json" --driver gear-A --chain \
    --range 0:0.1 --positions 120 --threads 1 --quiet
  for s in Escapement Geneva; do
    count "loop_$s" --toggle-collect='hipair::Simulation::run_until*' -- \
      "$build/tests/perf/hipair_simulation_speed" \
      --benchmark_filter="BM_Simulate$s/accuracy:1e-03/carried:1/"
  done
} | tee "$result"
rm -rf "$tmp"
