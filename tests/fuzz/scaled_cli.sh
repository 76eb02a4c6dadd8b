#!/usr/bin/env bash
# Runs CLI commands on models scaled by extreme factors (tests/fuzz/scale_model.py) and checks
# the command-line contract at every scale (docs/cli.md): each run either succeeds, or exits
# non-zero with a clear "hipair: error: ..." line on stderr; never a crash (a signal: exit >= 128)
# and never a half-written output (no atomic-write temporary left, every JSON written parses,
# every SVG written is complete). A run that outlives TIMEOUT seconds is reported as TIMEOUT.
#
# usage: scaled_cli.sh HIPAIR SOURCE_DIR WORK_DIR TIMEOUT COMMANDS MODELS [SCALES]
#   COMMANDS  comma-separated: validate,show,cspace,analyze,certify,tolerance,simulate
#   MODELS    comma-separated example names (examples/models/NAME.json) or "all"
#   SCALES    comma-separated factors (default 1e-300,1e-100,1e100,1e300,1e400)
# exit: 0 every run kept the contract (timeouts allowed when ALLOW_TIMEOUT=1); 1 otherwise; 2 usage.
set -uo pipefail
if [ $# -lt 6 ]; then sed -n '2,13p' "$0" >&2; exit 2; fi
hipair=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
source_dir=$(cd "$2" && pwd)
work=$3 limit=$4 commands=$5 models=$6 scales=${7:-1e-300,1e-100,1e100,1e300,1e400}
mkdir -p "$work" && work=$(cd "$work" && pwd)

if [ "$models" = all ]; then
  models=$(cd "$source_dir/examples/models" && ls *.json | sed 's/\.json$//' | paste -sd, -)
fi

failures=0 runs=0
report() { echo "$1"; [ "${2:-}" = bad ] && failures=$((failures + 1)); }

# One Python process parses every JSON file the runs write (a coprocess that answers "ok" or
# "bad" per path), and writes every scaled model at once: an interpreter start per file (a pyenv
# shim costs ~0.7 s of CPU) was most of this script's time (session 43, build43).
python=$(python3 -c 'import sys; print(sys.executable)') || { echo "scaled_cli: no python3" >&2; exit 2; }
coproc JSON_CHECK { "$python" -u -c '
import json, sys
for line in sys.stdin:
    try:
        with open(line[:-1], encoding="utf-8") as f:
            json.load(f)
        print("ok")
    except Exception:
        print("bad")
'; }

# Per run the script starts only the command (under timeout) and, per SVG written, tail and grep:
# the directory walk, the file names and the first error line are bash's own (session 73, ci73:
# find, basename, mv, grep and cut and their subshells were ~10 processes a run, ~0.2 s CPU of the
# ~0.4 s a run cost at load 14).
shopt -s globstar dotglob nullglob
check_outputs() {  # DIR: every file complete, no temporary left; the finding in $problem
  local dir=$1 file answer
  problem=""
  for file in "$dir"/**; do
    [ -f "$file" ] && [ ! -L "$file" ] || continue   # regular files, as find -type f
    case "${file##*/}" in
      .*.tmp*) problem="temporary left: $file" ;;
      *.json) echo "$file" >&"${JSON_CHECK[1]}" && IFS= read -r answer <&"${JSON_CHECK[0]}" &&
                [ "$answer" = ok ] || problem="unparsable JSON: $file" ;;
      *.svg) tail -c 64 "$file" | grep -q '</svg>' || problem="incomplete SVG: $file" ;;
    esac
  done
}

IFS=, read -ra command_list <<<"$commands"
IFS=, read -ra model_list <<<"$models"
IFS=, read -ra scale_list <<<"$scales"
mkdir -p "$work/models"
generator_args=()
for name in "${model_list[@]}"; do
  for scale in "${scale_list[@]}"; do
    rm -f "$work/models/$name@$scale.json"
    generator_args+=("$source_dir/examples/models/$name.json" "$scale" "$work/models/$name@$scale.json")
  done
done
"$python" "$source_dir/tests/fuzz/scale_model.py" "${generator_args[@]}"  # a failed model: no file

for name in "${model_list[@]}"; do
  for scale in "${scale_list[@]}"; do
    model="$work/models/$name@$scale.json"
    [ -f "$model" ] || { report "GENERATOR $name@$scale" bad; continue; }
    for command in "${command_list[@]}"; do
      out="$work/out/$name@$scale/$command"
      [ -e "$out" ] && rm -rf "$out"
      mkdir -p "$out"
      case "$command" in
        validate)  args=(validate "$model") ;;
        show)      args=(show "$model" --svg "$out/show.svg") ;;
        cspace)    args=(cspace "$model" --json "$out/cspace.json" --svg "$out/cspace.svg") ;;
        analyze)   args=(analyze "$model" --out "$out") ;;
        certify)   args=(certify "$model" --claim clearance --out "$out/certificate.json") ;;
        tolerance) args=(tolerance "$model" --out "$out") ;;
        simulate)  args=(simulate "$model" --t-end 0.01 --no-pictures --out "$out") ;;
        *) echo "unknown command $command" >&2; exit 2 ;;
      esac
      runs=$((runs + 1))
      start=${EPOCHREALTIME/[.,]/}
      stderr="$work/out/$name@$scale/$command.stderr"
      cd "$out" || exit 2   # the run's working directory (every path given is absolute)
      timeout -k 5 "$limit" "$hipair" "${args[@]}" >"$work/out/$name@$scale/$command.stdout" 2>"$stderr"
      rc=$?
      cd "$work" || exit 2
      tenths=$(( (${EPOCHREALTIME/[.,]/} - start + 50000) / 100000 ))
      seconds=$((tenths / 10)).$((tenths % 10))
      message=""
      while IFS= read -r line || [ -n "$line" ]; do
        if [[ $line == "hipair: error:"* ]]; then message=${line:0:160}; break; fi
      done <"$stderr"
      check_outputs "$out"
      what="$command $name@$scale (${seconds}s)"
      if [ "$rc" -eq 124 ] || { [ "$rc" -eq 137 ] && [ "$tenths" -ge $((limit * 10)) ]; }; then
        if [ "${ALLOW_TIMEOUT:-0}" = 1 ]; then report "TIMEOUT $what"; else report "TIMEOUT $what" bad; fi
      elif [ "$rc" -ge 128 ]; then
        report "CRASH rc=$rc $what: $(tail -c 300 "$stderr" | tr '\n' ' ')" bad
      elif [ -n "$problem" ]; then
        report "OUTPUT rc=$rc $what: $problem" bad
      elif [ "$rc" -ne 0 ] && [ -z "$message" ] && ! { [ "$command" = certify ] && [ "$rc" -eq 1 ] && [ -s "$stderr" ]; }; then
        report "UNCLEAR rc=$rc $what: $(tail -c 300 "$stderr" | tr '\n' ' ')" bad
      elif [ "$rc" -ne 0 ]; then
        report "ERROR rc=$rc $what: ${message:-$(head -c 160 "$stderr" | tr '\n' ' ')}"
      else
        report "OK $what"
      fi
    done
  done
done
echo "scaled_cli: $runs runs, $failures broke the contract"
[ "$failures" -eq 0 ]
