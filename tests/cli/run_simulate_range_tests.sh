#!/usr/bin/env bash
# `hipair simulate` on values beyond the doubles' range and a bare unknown argument, session 43
# (hunt43). Generated cases (a seed per run, printed on failure):
#  1. a bundled simulation model with one value of its dynamics data (a pair's friction, a
#     driver's speed, a mass, an initial velocity, a spring's rest) or a moving part's initial
#     coordinate set to ±1e{309..1000} or ±1e-{309..1000}: exit 2, one line naming the value's
#     JSON pointer, no signal, and an existing --out directory left as it was (main 0bdc449 died
#     of SIGFPE — GMP's mpq_set_d(inf) — on a friction, a driver speed or an initial angle of
#     1e400, and integrated a non-finite state on a mass or velocity of 1e400);
#  2. `hipair --OPTION` and `hipair WORD` (no subcommand): exit 109 naming the argument (main said
#     "A subcommand is required" and named neither).
# usage: run_simulate_range_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"

# MODEL POINTER (JSON pointer of the value to set; the key is created if absent)
cases=(
  "cam-drive.json /pairs/0/friction"
  "cam-drive.json /simulation/drivers/0/speed"
  "cam-drive.json /parts/0/initial/angle"
  "cam-drive.json /parts/1/dynamics/mass"
  "bouncing-bar.json /parts/0/initial/angle"
  "bouncing-bar.json /simulation/velocities/bar"
  "bouncing-bar.json /parts/0/dynamics/torsional_spring/rest"
  "spring-block.json /parts/1/initial/x"
  "spring-block.json /simulation/springs/0/rest_length"
  "spring-block.json /simulation/gravity/1"
)
for c in "${cases[@]}"; do
  read -r file pointer <<<"$c"
  for round in 1 2; do
    exponent=$((309 + RANDOM % 692))
    sign=$([ $((RANDOM % 2)) -eq 0 ] && echo "" || echo "-")
    # huge in round 1; tiny (nonzero) in round 2 only where the value is dynamics data (an
    # initial coordinate below the range is harmless: it is 0 in doubles)
    if [ $round -eq 2 ]; then
      case $pointer in */initial/*) continue ;; esac
      literal="${sign}1e-$exponent"
    else
      literal="${sign}1e$exponent"
    fi
    # friction, mass, rest length must not be negative: keep them positive (the sign check would
    # name the same pointer, but the range is what is tested)
    case $pointer in */friction|*/mass|*/rest_length) literal=${literal#-} ;; esac
    model="$work/m.json"
    python3 - "$source/examples/models/$file" "$pointer" "$literal" "$model" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
keys = [k for k in sys.argv[2].split('/')[1:]]
o = doc
for k in keys[:-1]:
    o = o[int(k)] if isinstance(o, list) else o[k]
last = keys[-1]
marker = "@@MARK@@"
if isinstance(o, list): o[int(last)] = marker
else: o[last] = marker
open(sys.argv[4], 'w').write(json.dumps(doc).replace('"' + marker + '"', sys.argv[3]))
PY
    rm -rf "$work/out" && mkdir -p "$work/out" && echo keep >"$work/out/sentinel"
    timeout 120 "$hipair" simulate "$model" --t-end 0.01 --no-pictures --out "$work/out" >"$work/bad.out" 2>"$work/bad.err"
    status=$?
    what="simulate $file with $pointer = $literal"
    [ "$status" -eq 2 ] || { fail "$what: exit $status, not 2: $(head -c 300 "$work/bad.err")"; continue; }
    [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/bad.err")"
    grep -qF -- "$pointer: " "$work/bad.err" || fail "$what: the message names no $pointer: $(head -c 300 "$work/bad.err")"
    grep -q "too \(large\|small\) for the simulator" "$work/bad.err" || fail "$what: no range reason: $(head -c 300 "$work/bad.err")"
    [ "$(ls "$work/out")" = sentinel ] && [ "$(cat "$work/out/sentinel")" = keep ] || fail "$what: --out changed: $(ls "$work/out")"
  done
done

# 2. no subcommand, an unknown argument
for arg in --bogus -q --t-end bogus validat; do
  "$hipair" "$arg" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  [ "$status" -eq 109 ] || fail "hipair $arg: exit $status, not 109: $(cat "$work/bad.err")"
  grep -qF -- "$arg" "$work/bad.err" || fail "hipair $arg: the message does not name it: $(cat "$work/bad.err")"
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "hipair $arg: not one line: $(cat "$work/bad.err")"
done
"$hipair" >"$work/bad.out" 2>"$work/bad.err"
status=$?
[ "$status" -eq 106 ] && grep -q "A subcommand is required" "$work/bad.err" || fail "hipair alone: exit $status: $(cat "$work/bad.err")"

echo "simulate range tests: $failures failure(s) (seed $seed)"
[ "$failures" -eq 0 ]
