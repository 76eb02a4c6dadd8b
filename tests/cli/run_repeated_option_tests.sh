#!/usr/bin/env bash
# Session 35 (hunt35): inputs that were silently taken, the last one winning, and a free passage
# the mechanism cannot make.
#  - A repeatable option naming one target twice (`--set p=a --set p=b`, `--load`, `--at`,
#    `--config driver=1,driver=2`, `--sweep p=...` with `--set p=...`) is a usage error naming the
#    option and the target, exit 114 (as CLI11 refuses a single-valued option given twice),
#    nothing written, in every command; different targets are still taken.
#  - `certify --claim free` with a follower path beyond the follower's motion limits is an input
#    error naming the part and its limits (exit 2, nothing written); main certified it, and its
#    hipair-verify accepted it.
# Values are drawn at random (seeded by $SEED, default 35) within the parameters' tolerances.
# usage: run_repeated_option_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 verify=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
RANDOM=${SEED:-35}
models=$source/examples/models
geneva=$models/geneva.json lever=$models/lever-stop.json esc=$models/escapement.json cam=$models/cam-follower.json
# a value within +-0.019 of a nominal given in thousandths, written in one of the literal forms the
# reader takes: near 4500 -> 4.487, 4513/1000 or 4509e-3
near() {
  local n=$(($1 + RANDOM % 39 - 19))
  case $((RANDOM % 3)) in
    0) printf '%d.%03d\n' $((n / 1000)) $((n % 1000)) ;;
    1) echo "$n/1000" ;;
    2) echo "${n}e-3" ;;
  esac
}
# refused NAME OPTION TARGET COMMAND...: exit 114, the option and the target named, no output
refused() {
  local name=$1 option=$2 target=$3
  shift 3
  "$hipair" "$@" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  [ $code -eq 114 ] || fail "$name: exit $code, want 114 (a repeated $option target): $(head -c 300 "$work/$name.err")"
  grep -q -- "^hipair: error: $option: .*'$target' is given twice" "$work/$name.err" ||
    fail "$name: the message does not name $option and '$target': $(head -c 300 "$work/$name.err")"
  [ -e "$work/$name.svg" ] || [ -e "$work/$name.json" ] || [ -e "$work/$name.dir" ] && fail "$name: wrote output"
}
for round in 1 2 3; do
  a=$(near 4500) b=$(near 4500)
  refused "validate-set-$round" --set pin-radius validate "$geneva" --set pin-radius=$a --set outer-arc-radius=46 --set pin-radius=$b
  refused "show-set-$round" --set pin-radius show "$geneva" --set pin-radius=$a --set pin-radius=$a --svg "$work/show-set-$round.svg"
  refused "analyze-set-$round" --set pin-radius analyze "$geneva" --set pin-radius=$a --set pin-radius=$b --out "$work/analyze-set-$round.dir" --quiet
  refused "cspace-set-$round" --set pin-radius cspace "$geneva" --set pin-radius=$b --set pin-radius=$a --svg "$work/cspace-set-$round.svg"
  refused "tolerance-set-$round" --set pin-radius tolerance "$geneva" --set pin-radius=$a --set pin-radius=$b --out "$work/tolerance-set-$round.dir" --quiet
  refused "simulate-set-$round" --set wheel-radius simulate "$esc" --t-end 0.001 --set wheel-radius=$(near 10000) --set wheel-radius=$(near 10000) --out "$work/simulate-set-$round.dir"
  g=$(near 2000)
  refused "certify-set-$round" --set stop-gap certify "$lever" --claim clearance --set stop-gap=$g --set stop-gap=$(near 2000) --out "$work/certify-set-$round.json"
  angle=0.$((RANDOM % 9))
  refused "certify-at-$round" --at lever certify "$lever" --claim clearance --at lever=$angle --at lever=-0.$((RANDOM % 5)) --out "$work/certify-at-$round.json"
  refused "show-config-list-$round" --config driver.angle show "$geneva" --config driver=$angle,wheel=0,driver=1 --svg "$work/show-config-list-$round.svg"
  refused "show-config-coordinate-$round" --config wheel.angle show "$geneva" --config wheel=$angle --config " wheel.angle=$angle" --svg "$work/show-config-coordinate-$round.svg"
  refused "analyze-load-$round" --load wheel analyze "$geneva" --load wheel=cw --load " wheel =spring:0.$((RANDOM % 9))" --out "$work/analyze-load-$round.dir" --quiet
  refused "simulate-sweep-$round" --sweep wheel-radius simulate "$esc" --t-end 0.001 --set wheel-radius=$(near 10000) --sweep wheel-radius=9.99:10.01:2 --allow-out-of-tolerance
done
# a single-valued option given twice: CLI11's own refusal, exit 114
"$hipair" show "$geneva" --svg "$work/twice-a.svg" --svg "$work/twice-b.svg" >/dev/null 2>"$work/twice.err"
code=$?
[ $code -eq 114 ] || fail "show --svg twice: exit $code, want 114"
[ -e "$work/twice-a.svg" ] || [ -e "$work/twice-b.svg" ] && fail "show --svg twice wrote output"
# controls: different targets are taken
"$hipair" validate "$geneva" --set pin-radius=$(near 4500) --set outer-arc-radius=$(near 46000) >"$work/ok-set.out" 2>&1 ||
  fail "validate with two different --set targets fails: $(tail -c 300 "$work/ok-set.out")"
"$hipair" show "$geneva" --config driver=0.5 --config wheel=0.1 --svg "$work/ok-config.svg" >/dev/null 2>"$work/ok-config.err" ||
  fail "show with two different --config targets fails: $(cat "$work/ok-config.err")"
"$hipair" certify "$lever" --claim clearance --at lever=-0.3 --set stop-gap=$(near 2000) --set lever-width=8 --out "$work/ok-at.json" >/dev/null 2>"$work/ok-at.err" ||
  fail "certify with one --at and two different --set targets fails: $(cat "$work/ok-at.err")"

# a free passage beyond the follower's limits (the cam follower's offset, limits [-12, 12] mm)
for ratio in 100 -30 115000001/10000000 -13; do   # the path from 0.5 mm, driver 0 ... 1 rad: beyond +12 or -12 (the third by 1e-7)
  to=1
  name=free-beyond-$(echo "$ratio" | tr '/' '_')
  "$hipair" certify "$cam" --claim free --pair cam:follower --from 0 --to $to --ratio "$ratio" --out "$work/$name.json" >"$work/$name.out" 2>"$work/$name.err"
  code=$?
  [ $code -eq 2 ] || fail "$name: exit $code, want 2: $(head -c 300 "$work/$name.err")"
  grep -q "^hipair: error: /parts/1: the follower path of 'follower' runs over .*not within its motion limits \[-12, 12\] mm" "$work/$name.err" ||
    fail "$name: message: $(head -c 300 "$work/$name.err")"
  [ -e "$work/$name.json" ] && fail "$name: wrote a certificate"
done
# controls: a path within the limits, and one ending exactly at the limit, certified and verified
for ratio in 11 23/2; do
  name=free-within-$(echo "$ratio" | tr '/' '_')
  "$hipair" certify "$cam" --claim free --pair cam:follower --from 0 --to 1 --ratio "$ratio" --out "$work/$name.json" >"$work/$name.out" 2>&1 ||
    fail "$name: not certified: $(tail -c 300 "$work/$name.out")"
  "$verify" "$work/$name.json" "$cam" >"$work/$name.verify" 2>&1 || fail "$name: not verified: $(cat "$work/$name.verify")"
done

# Session 42: every command-line usage error (CLI11's own and ours) is one line on stderr,
# "hipair: error: ... (see 'hipair COMMAND --help')", with CLI11's exit code (103-114), nothing on
# stdout, nothing written. Each case is drawn with a random subcommand and a random bad value.
usage_case() {
  local command=$1 out=$work/usage-$RANDOM
  case $((RANDOM % 7)) in
    0) echo "$command"; echo "" ;;                                   # the model missing
    1) echo "$command $geneva --no-such-option-$RANDOM" ;;           # an unknown option
    2) echo "$command $work/no-such-model-$RANDOM.json" ;;           # a model file that does not exist
    3) echo "$command $geneva --set" ;;                               # an option without its value
    4) echo "$command $geneva --rounding x$RANDOM" ;;                # a value that does not convert
    5) echo "$command $geneva --out $out.a --out $out.b" ;;           # a single-valued option twice
    6) echo "$command $geneva $geneva" ;;                             # a second model
  esac
}
for round in $(seq 1 40); do
  commands=(validate show analyze cspace tolerance simulate certify)
  command=${commands[$((RANDOM % ${#commands[@]}))]}
  read -r -a args <<<"$(usage_case "$command" | head -1)"
  "$hipair" "${args[@]}" >"$work/usage.out" 2>"$work/usage.err"
  code=$?
  what="usage error '${args[*]}'"
  if [ $code -eq 0 ] || [ $code -eq 5 ] || [ $code -gt 114 ]; then fail "$what: exit $code"; fi
  [ -s "$work/usage.out" ] && fail "$what: writes to stdout: $(head -c 300 "$work/usage.out")"
  [ "$(wc -l <"$work/usage.err")" -eq 1 ] || fail "$what: not one line on stderr: $(head -c 300 "$work/usage.err")"
  grep -q "^hipair: error: " "$work/usage.err" || fail "$what: no 'hipair: error: ' prefix: $(head -c 300 "$work/usage.err")"
  if [ $code -ge 103 ]; then
    grep -qF "(see 'hipair $command --help')" "$work/usage.err" || fail "$what: names no help: $(head -c 300 "$work/usage.err")"
  fi
  ls "$work"/usage-* >/dev/null 2>&1 && fail "$what: wrote $(ls "$work"/usage-*)"
done

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "repeated-option and free-path-limit tests passed"
