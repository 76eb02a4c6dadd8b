#!/usr/bin/env bash
# `hipair simulate` of the 18 x 27 spur gears (examples/models/spur-gears.json), session 57
# (simgear57). Until then the default --region full built the pair's whole torus (z1 z2 tooth
# encounters): `--t-end 0.01` ran for minutes with nothing shown. Now --region auto (the default)
# builds the operating region of a pair of more than 120 boundary edges:
#  1. a short run (a random --t-end of 0.01 ... 0.03 s) finishes within 120 s, exit 0, its files
#     written, its events naming the gears' teeth;
#  2. on a terminal (script(1)) the build shows its tiles; with --quiet nothing but the summary.
# (--region full still builds the whole torus, minutes: not run here.)
# usage: run_simulate_gears_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
model=$source/examples/models/spur-gears.json

# 1. a short run, bounded
t_end=0.0$((1 + RANDOM % 3))
start=$(date +%s)
timeout 120 "$hipair" simulate "$model" --t-end "$t_end" --no-pictures --out "$work/g" >"$work/g.out" 2>"$work/g.err"
rc=$?
[ $rc -eq 0 ] || fail "simulate --t-end $t_end: exit $rc (124: over 120 s): $(tail -c 300 "$work/g.err")"
grep -q "^simulated spur-gears to t = $t_end s in [0-9]* steps" "$work/g.out" ||
  fail "simulate --t-end $t_end: no summary: $(head -c 300 "$work/g.out")"
grep -q "impact  pinion / gear  \[pinion tooth [0-9]* flank . [a-z]* / gear tooth [0-9]* flank" "$work/g.out" ||
  fail "simulate --t-end $t_end: no tooth impact in the events: $(head -c 600 "$work/g.out")"
for f in trajectory.csv events.json events.txt; do
  [ -s "$work/g/$f" ] || fail "simulate --t-end $t_end: $f not written"
done
[ -s "$work/g.err" ] && fail "simulate off a terminal wrote to stderr: $(head -c 300 "$work/g.err")"
echo "spur gears to $t_end s: $(($(date +%s) - start)) s wall"

# 2. progress on a terminal, none with --quiet
if script -qc true /dev/null >/dev/null 2>&1; then
  script -qc "timeout 120 '$hipair' simulate '$model' --t-end 0.01 --no-pictures" "$work/tty" >/dev/null 2>&1
  tr '\r' '\n' <"$work/tty" >"$work/tty.lines"
  grep -q "^hipair: pinion:gear tile [0-9]*/[0-9]*" "$work/tty.lines" ||
    fail "no build progress on a terminal: $(head -c 300 "$work/tty.lines")"
  grep -q "^simulated spur-gears to t = 0.01 s" "$work/tty.lines" ||
    fail "no summary on a terminal: $(tail -c 300 "$work/tty.lines")"
  script -qc "timeout 120 '$hipair' simulate '$model' --t-end 0.01 --no-pictures --quiet" "$work/quiet" >/dev/null 2>&1
  # (script's own first and last lines name the command)
  tr '\r' '\n' <"$work/quiet" | grep -v "^Script " >"$work/quiet.lines"
  grep -q "tile\|classifying\|simulate: \|building" "$work/quiet.lines" &&
    fail "--quiet: progress on the terminal: $(grep "tile\|classifying\|simulate: \|building" "$work/quiet.lines" | head -2)"
  grep -q "simulated spur-gears to t = 0.01 s" "$work/quiet" || fail "--quiet: no summary: $(tail -c 300 "$work/quiet")"
else
  echo "script(1) cannot run here: the terminal progress cases are skipped"
fi

echo "simulate gears tests: $failures failure(s) (seed $seed)"
[ "$failures" -eq 0 ]
