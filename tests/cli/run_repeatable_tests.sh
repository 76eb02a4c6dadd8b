#!/usr/bin/env bash
# Identical input, identical bytes: each command runs twice, in two processes started more than a
# second apart (CGAL seeded its default random generator from the clock, which changed the
# certified extents of cspace --json and the vertex coordinates of cspace-*.svg between runs),
# and the outputs are compared with cmp.
# usage: run_repeatable_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# python3 resolved once to the interpreter itself: a pyenv shim starts a shell script per call
# (~0.7 s of CPU each), and these scripts call python3 in loops (session 43, build43).
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
hipair=$1 source=$2 work=$3
models=$source/examples/models
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# twice NAME COMMAND...: runs COMMAND with OUT replaced by $work/NAME-1 then $work/NAME-2
# (a file or a directory), and compares every file written.
twice() {
  local name=$1
  shift
  for run in 1 2; do
    [ $run = 2 ] && sleep 1.1
    local args=()
    for a in "$@"; do args+=("${a//OUT/$work/$name-$run}"); done
    "$hipair" "${args[@]}" >"$work/$name-$run.stdout" 2>"$work/$name-$run.stderr" \
      || { fail "$name: $* exits non-zero: $(head -3 "$work/$name-$run.stderr")"; return; }
  done
  if [ -d "$work/$name-1" ]; then
    local files
    files=$(cd "$work/$name-1" && find . -type f | sort)
    [ -n "$files" ] || fail "$name: no output written"
    for f in $files; do
      case "$(basename "$f")" in report.json | tolerance.json)
        # wall and CPU times ("seconds", "cpu_seconds") are the only fields that may differ
        python3 - "$work/$name-1/$f" "$work/$name-2/$f" <<'PY' || fail "$name: $f differs between two runs (besides its times)"
import json, sys
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if k not in ("seconds", "cpu_seconds")}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
a, b = (strip(json.load(open(p))) for p in sys.argv[1:3])
sys.exit(0 if json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True) else 1)
PY
        continue ;;
      esac
      if true; then
        cmp -s "$work/$name-1/$f" "$work/$name-2/$f" || fail "$name: $f differs between two runs"
      fi
    done
  else
    cmp -s "$work/$name-1" "$work/$name-2" || fail "$name: output differs between two runs"
  fi
}

twice escapement-cspace cspace "$models/escapement.json" --pair anchor:balance --json OUT
twice geneva-template-cspace cspace "$models/geneva-template.json" --json OUT
mkdir -p "$work/escapement-svg-1" "$work/escapement-svg-2"
twice escapement-svg cspace "$models/escapement.json" --pair anchor:balance --svg OUT/cspace.svg
mkdir -p "$work/geneva-template-analyze-1" "$work/geneva-template-analyze-2"
twice geneva-template-analyze analyze "$models/geneva-template.json" --out OUT
mkdir -p "$work/escapement-analyze-1" "$work/escapement-analyze-2"
twice escapement-analyze analyze "$models/escapement.json" --out OUT

# 3-DOF (sliced) and pin-in-slot pairs: their stage times too are written only with --stats
mkdir -p "$work/peg-in-hole-cspace-1" "$work/peg-in-hole-cspace-2"
twice peg-in-hole-cspace cspace "$models/peg-in-hole.json" --json OUT/space.json
mkdir -p "$work/film-advance-cspace-1" "$work/film-advance-cspace-2"
twice film-advance-cspace cspace "$models/film-advance.json" --json OUT/space.json

twice lever-stop-certify certify "$models/lever-stop.json" --claim jam --out OUT
twice geneva-tolerance tolerance "$models/geneva.json" --quiet --out OUT

if [ $failures -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all repeatability checks passed"
