#!/usr/bin/env bash
# Zero-backlash spur-gear pairs swept over tooth counts, driven forwards and backwards (session 54,
# gear54): every jam `hipair analyze` reports must come with a certificate that hipair-verify
# accepts, and none may be left uncertified ("not certified: jam"). Prints one line a run (the
# verdict, the certificate's fate, the CPU seconds of analyze) and a summary; exit 1 on any
# uncertified or refused jam, or an analysis that fails.
#
#   tests/perf/gear_jam_sweep.sh HIPAIR HIPAIR_VERIFY [Z_LO Z_HI [WORK_DIR]]
#
# Pairs: pinion Z1 and gear Z2 teeth, both in Z_LO..Z_HI (default 12..20), spur-gears.json with
# the backlash 0 and the centre distance the sum of the pitch radii; `analyze --range 0:0.3` and
# `--range 0:-0.3`. Not a CTest test: the default sweep (162 analyses) takes minutes of CPU.
set -uo pipefail
hipair=$(readlink -f "$1") verify=$(readlink -f "$2")
lo=${3:-12} hi=${4:-20}
work=${5:-$(mktemp -d)}
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$work"

gears() {   # Z1 Z2 FILE
  python3 "$source_dir/tests/fuzz/zero_backlash_gears.py" "$source_dir/examples/models/spur-gears.json" "$@"
}

failures=0 runs=0 jams=0 certified=0 total=0
printf '%-7s %-6s %-44s %-26s %8s\n' pair range verdict certificate "cpu s"
for z1 in $(seq "$lo" "$hi"); do
  for z2 in $(seq "$lo" "$hi"); do
    model=$work/gears-$z1-$z2.json
    gears "$z1" "$z2" "$model"
    for range in 0:0.3 0:-0.3; do
      out=$work/out-$z1-$z2-${range#0:}
      rm -rf "$out"
      runs=$((runs + 1))
      TIMEFORMAT=%U
      cpu=$( { time "$hipair" analyze "$model" --range "$range" --no-pictures --quiet --out "$out" >"$out.txt" 2>"$out.err"; } 2>&1 )
      status=$?
      total=$(python3 -c "print(round($total + ${cpu:-0}, 2))")
      if [ $status -ne 0 ]; then
        printf '%-7s %-6s %-44s %-26s %8s\n' "${z1}x$z2" "$range" "analyze exit $status" - "$cpu"
        failures=$((failures + 1))
        continue
      fi
      if grep -q "^INTERFERENCE at the initial configuration" "$out.txt"; then verdict="overlap at the start"
      elif line=$(grep -m1 "^Blocking: the driver is BLOCKED at" "$out.txt"); then
        verdict=$(sed -E 's/^Blocking: the driver is (BLOCKED at -?[0-9.]+°).*/\1/' <<<"$line")
        [[ $line == *"free range closed"* ]] && verdict="$verdict, range closed"
      else verdict="completes the range"
      fi
      fate=-
      kind=jam
      [ "$verdict" = "overlap at the start" ] && kind=interference
      cert=""
      for c in "$out"/certificate-*.json; do
        [ -e "$c" ] && grep -q "\"claim\": \"$kind\"" "$c" && cert=$c
      done
      if [ -n "$cert" ]; then
        if "$verify" "$cert" "$model" >"$out.verify" 2>&1; then
          fate="$kind certified, verified"
        else
          fate="$kind REFUSED by hipair-verify"
          failures=$((failures + 1))
        fi
      fi
      if [ $kind = jam ] && [[ $verdict == BLOCKED* ]]; then
        jams=$((jams + 1))
        if grep -q "^not certified: jam" "$out.txt" || [ -z "$cert" ]; then
          fate="jam NOT CERTIFIED"
          failures=$((failures + 1))
        elif [[ $fate == *verified ]]; then
          certified=$((certified + 1))
        fi
      elif [ $kind = interference ] && [ -z "$cert" ]; then
        fate="interference NOT CERTIFIED"
        failures=$((failures + 1))
      fi
      printf '%-7s %-6s %-44s %-26s %8s\n' "${z1}x$z2" "$range" "$verdict" "$fate" "$cpu"
    done
  done
done
echo "$runs analyses ($total s CPU), $jams jams after the start: $certified certified and verified, $failures failure(s)"
[ $failures -eq 0 ]
