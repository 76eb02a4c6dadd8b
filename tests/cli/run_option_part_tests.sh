#!/usr/bin/env bash
# Parts named on the command line, session 44 (hunt44): docs/cli.md "Usage errors". An option that
# names a part (certify --pair/--at/--driver, cspace --pair, tolerance --pair) and names one the
# model does not have, the same part twice, or a part outside the pair, is refused with one line
# that names the option (until session 44: "/parts: no part called 'x'", "/pairs: a pair needs two
# different parts", "/pairs: no pair ... matches", "/pairs: the driver ... is not a part of the
# pair", none naming the option; certify --at took a third part's position and dropped it
# silently). An argument before the subcommand that nothing takes (`hipair --bogus validate M`)
# points at 'hipair --help', not at the subcommand's help. Generated cases (a seed per run, printed
# on failure; HIPAIR_TEST_SEED repeats one): exit 2 (CLI11's code for the top-level extra), one
# line naming the option, nothing on stdout, nothing written. Controls: the same commands with
# the pair's own parts are taken.
# usage: run_option_part_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
# shellcheck source=expect_refused.sh
source "$(dirname "$0")/expect_refused.sh"
train=$source/examples/models/gear-train-3.json   # gear-A - gear-B - gear-C (pairs A:B, B:C)
lever=$source/examples/models/lever-stop.json     # lever (rotating) - stop (fixed)
geneva=$source/examples/models/geneva.json        # driver - wheel
parts=(gear-A gear-B gear-C)

# a name the model does not have: a random word, an empty name, a part's name with one character
# changed or a space added
unknown_name() {
  case $((RANDOM % 4)) in
    0) printf 'part%d' $RANDOM ;;
    1) printf '' ;;
    2) printf 'gear-%s' "$(printf '%s' DEFGHXYZ | cut -c$((RANDOM % 8 + 1)))" ;;
    3) printf '%s ' "${parts[$((RANDOM % 3))]}" ;;
  esac
}

# one refused run: WHAT PATTERN ARGS... (PATTERN a fixed string)
refused() {
  local what=$1 pattern=$2
  shift 2
  rm -rf "$work/out" "$work/x.svg" "$work/x.json" "$work/c.json"
  "$hipair" "$@" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  expect_refused "$what" "$pattern" -qF
}

for round in $(seq 1 6); do
  # certify --pair with an unknown part, in either place
  u=$(unknown_name) p=${parts[$((RANDOM % 3))]}
  if ((RANDOM % 2)); then pair="$p:$u"; else pair="$u:$p"; fi
  claims=(interference clearance jam free)
  claim=${claims[$((RANDOM % 4))]}
  refused "certify --claim $claim --pair '$pair'" "--pair $pair: no part called '$u'" \
    certify "$train" --claim "$claim" --pair "$pair" --out "$work/c.json"
  # certify --pair naming one part twice
  refused "certify --pair $p:$p" "--pair $p:$p: a pair needs two different parts" \
    certify "$train" --claim "$claim" --pair "$p:$p" --out "$work/c.json"
  # certify --at a part outside the pair (or unknown) for interference/clearance
  claim=${claims[$((RANDOM % 2))]}
  angle=$((RANDOM % 7))/$((RANDOM % 9 + 1))
  refused "certify --claim $claim --pair gear-A:gear-B --at gear-C=$angle" "--at gear-C=$angle: 'gear-C' is not in the pair gear-A:gear-B" \
    certify "$train" --claim "$claim" --pair gear-A:gear-B --at "gear-A=$angle" --at "gear-C=$angle" --out "$work/c.json"
  refused "certify --claim $claim --at '$u=$angle'" "--at $u=$angle: no part called '$u'" \
    certify "$train" --claim "$claim" --pair gear-B:gear-C --at "$u=$angle" --out "$work/c.json"
  # certify --driver outside the pair, or unknown (jam, free)
  claim=${claims[$((RANDOM % 2 + 2))]}
  refused "certify --claim $claim --pair gear-B:gear-C --driver gear-A" "--driver gear-A: 'gear-A' is not in the pair gear-B:gear-C" \
    certify "$train" --claim "$claim" --pair gear-B:gear-C --driver gear-A --out "$work/c.json"
  d=$u
  [ -n "$d" ] || d=lever-$RANDOM   # an empty --driver is no --driver: the default
  refused "certify --claim $claim --driver '$d'" "--driver $d: no part called '$d'" \
    certify "$lever" --claim "$claim" --driver "$d" --out "$work/c.json"
  # cspace --pair: unknown, or one part twice (before any C-space is built)
  refused "cspace --pair '$pair'" "--pair $pair: no part called '$u'" cspace "$train" --pair "$pair" --json "$work/x.json"
  refused "cspace --pair $p:$p" "--pair $p:$p: a pair needs two different parts" cspace "$train" --pair "$p:$p" --svg "$work/x.svg"
  # tolerance --pair naming one part twice
  g=$( ((RANDOM % 2)) && echo driver || echo wheel)
  refused "tolerance --pair $g:$g" "--pair: '$g' twice" tolerance "$geneva" --pair "$g:$g" --quiet --out "$work/out"
  # an unknown option before the subcommand: the top level's help (CLI11's exit code 109)
  option=--no-such-$RANDOM
  commands=(validate show analyze cspace tolerance simulate certify)
  command=${commands[$((RANDOM % 7))]}
  "$hipair" "$option" "$command" "$lever" >"$work/bad.out" 2>"$work/bad.err"
  code=$?
  [ $code -eq 109 ] || fail "$option $command: exit $code, want 109: $(head -c 300 "$work/bad.err")"
  [ -s "$work/bad.out" ] && fail "$option $command: writes to stdout"
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "$option $command: not one line: $(head -c 300 "$work/bad.err")"
  grep -qF "hipair: error: The following argument was not expected: $option (see 'hipair --help')" "$work/bad.err" ||
    fail "$option $command: message: $(head -c 300 "$work/bad.err")"
  # the same option after the subcommand keeps the subcommand's help
  "$hipair" "$command" "$lever" "$option" >"$work/bad.out" 2>"$work/bad.err"
  grep -qF "(see 'hipair $command --help')" "$work/bad.err" || fail "$command ... $option: message: $(head -c 300 "$work/bad.err")"
done

# controls: the pair's own parts are taken (a clearance certified and verified at the pair's
# initial configuration; the lever's jam search; cspace of a listed pair)
"$hipair" certify "$train" --claim clearance --pair gear-B:gear-C --at gear-B=0 --at gear-C=0 --out "$work/ok.json" \
  >"$work/ok.out" 2>&1 || fail "certify clearance gear-B:gear-C with --at of both parts: $(tail -c 300 "$work/ok.out")"
"$hipair" certify "$lever" --claim jam --driver lever --direction + --out "$work/ok-jam.json" >"$work/ok-jam.out" 2>&1
code=$?
{ [ $code -eq 0 ] || [ $code -eq 1 ]; } || fail "certify jam --driver lever: exit $code: $(tail -c 300 "$work/ok-jam.out")"
"$hipair" validate "$lever" >/dev/null 2>"$work/ok.err" || fail "validate lever-stop: $(cat "$work/ok.err")"

if [ $failures -gt 0 ]; then
  echo "$failures failure(s) (seed $seed)"
  exit 1
fi
echo "option part tests passed (seed $seed)"
