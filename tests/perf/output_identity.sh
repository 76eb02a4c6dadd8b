#!/usr/bin/env bash
# Output identity across a change: runs one `hipair` binary over every bundled example
# (validate, cspace JSON + SVG, analyze --out, a short simulate --out, the Geneva and gear-train
# tolerance rows, the spur-gear operating region) and writes every output, stdout, stderr and exit
# code into OUTDIR. Run it with the binary before and after a change, then compare the two
# directories with `tests/perf/output_identity.sh --compare DIR_A DIR_B` (exit 0: identical once
# each directory's own path and the JSON reports' stage timings are set aside).
#
#   tests/perf/output_identity.sh BIN OUTDIR [JOBS]
#   tests/perf/output_identity.sh --compare DIR_A DIR_B
#
# Not a CTest test: a developer's tool (the full run takes minutes of CPU). Lines of stdout that
# report wall or CPU time are dropped before comparison (they are the only nondeterministic text).
set -uo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)

# A copy of an output directory with what legitimately differs between runs made equal: the
# directory's own path (files name where they were written) and the stage timings of the JSON
# reports ("seconds", "cpu_seconds").
normalized_copy() { # SRC DST
  cp -r "$1" "$2"
  grep -rlIF -- "$1" "$2" | xargs -r sed -i "s#$1#@OUT@#g"
  grep -rlIE '"(cpu_)?seconds"' "$2" | python3 -c '
import json, sys
def blank(o):
    if isinstance(o, dict):
        return {k: (0 if k in ("seconds", "cpu_seconds") else blank(v)) for k, v in o.items()}
    return [blank(v) for v in o] if isinstance(o, list) else o
for name in sys.stdin.read().split("\n"):
    try:
        data = json.load(open(name))
    except (OSError, ValueError):
        continue
    json.dump(blank(data), open(name, "w"), indent=1)
'
}

if [ "${1:-}" = "--compare" ]; then
  a=$(readlink -f "$2") b=$(readlink -f "$3") work=$(mktemp -d)
  normalized_copy "$a" "$work/a"; normalized_copy "$b" "$work/b"
  if diff -r -q "$work/a" "$work/b" >/dev/null; then
    echo "identical: $(find "$a" -type f | wc -l) files"; rm -rf "$work"; exit 0
  fi
  diff -r -q "$work/a" "$work/b" | sed "s#$work/##g" | head -40
  rm -rf "$work"; exit 1
fi

bin=$(readlink -f "$1"); out=$(readlink -m "$2"); jobs=${3:-2}
[ -x "$bin" ] || { echo "output_identity: $1 is not an executable" >&2; exit 64; }
rm -rf "$out"; mkdir -p "$out"
models=$here/examples/models

# One job per line: NAME<TAB>ARGS (ARGS may use @OUT@ for the job's own output directory).
jobs_file=$(mktemp)
for m in "$models"/*.json; do
  n=$(basename "$m" .json)
  printf '%s\t%s\n' "$n.validate" "validate $m" >>"$jobs_file"
  printf '%s\t%s\n' "$n.analyze" "analyze $m --quiet --out @OUT@/a" >>"$jobs_file"
  # the spur gears' whole torus (C-space and simulation) takes over 15 min: their operating
  # region below stands for them
  [ "$n" = spur-gears ] && continue
  printf '%s\t%s\n' "$n.cspace" "cspace $m --json @OUT@/cspace.json --svg @OUT@/cspace.svg" >>"$jobs_file"
  printf '%s\t%s\n' "$n.simulate" "simulate $m --t-end 0.5 --no-pictures --out @OUT@/s" >>"$jobs_file"
done
printf '%s\t%s\n' "geneva.tolerance" "tolerance $models/geneva.json --out @OUT@/t" >>"$jobs_file"
printf '%s\t%s\n' "gear-train.tolerance-row" \
  "tolerance $models/gear-train.json --driver gear-A --chain --range 0:0.1 --positions 120 --threads 1 --quiet --out @OUT@/t" >>"$jobs_file"
printf '%s\t%s\n' "spur-gears.operating" "cspace $models/spur-gears.json --region operating --json @OUT@/op.json" >>"$jobs_file"

run_one() {
  local name=$1 args=$2 dir="$out/$1"
  mkdir -p "$dir"
  args=${args//@OUT@/$dir}
  # shellcheck disable=SC2086
  (cd "$dir" && timeout 900 "$bin" $args >stdout.txt 2>stderr.txt; echo "rc $?" >rc.txt)
  sed -i -E '/([0-9.]+ ?(s|ms) (user|wall|cpu|CPU))|(elapsed|wall time|CPU time|took [0-9])/d' \
    "$dir/stdout.txt" "$dir/stderr.txt"
}
export -f run_one; export bin out
tr '\t' '\037' <"$jobs_file" | xargs -P "$jobs" -I{} bash -c 'IFS=$'"'"'\037'"'"' read -r n a <<<"$1"; run_one "$n" "$a"' _ {}
rm -f "$jobs_file"
echo "output_identity: $(find "$out" -type f | wc -l) files in $out"
