#!/usr/bin/env bash
# Hostile command lines and models, session 38 (hunt38): what a console line may echo, and what
# a terminal shows during a long exact classification. Generated cases (a seed per run, printed
# on failure):
#  1. model, part and parameter names of 201 ... 1 000 000 bytes (ASCII or two-byte UTF-8):
#     `show` and `validate` succeed, no console line is longer than 400 bytes, the name's length
#     is given, and the SVG keeps the whole name (main 5edee72 printed 1 MB lines);
#  2. option values of 201 ... 100 000 characters to the numeric options of every command: the
#     exit code of a short bad value, a message under 400 bytes naming the length (CLI11's
#     "Could not convert: --t-end = ..." and "Value ... not in range" echoed them whole);
#  3. on a terminal (util-linux `script`), two rotating squares of 10^-a and 10^b mm (a + b about
#     100): `cspace` shows "classifying chart" with the coefficients' width as the reason (main
#     was silent after "chart 4/4" for minutes at 10^-30 / 10^400 mm).
# usage: run_hostile_cli_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
# the longest line of a file, in bytes
longest() { LC_ALL=C awk '{ if (length($0) > m) m = length($0) } END { print m + 0 }' "$1"; }
repeat() { head -c "$2" /dev/zero | tr '\0' "$1"; }

# 1. long names
for round in 1 2 3; do
  case $round in
    1) length=$((201 + RANDOM % 50)) ;;
    2) length=$((1000 + RANDOM * 3)) ;;
    3) length=1000000 ;;
  esac
  if [ $((RANDOM % 2)) -eq 0 ]; then
    name=$(repeat x "$length")
    chars=$length
  else   # "é" (two bytes) after an "a": a cut must not split a sequence
    name="a$(repeat x $((length / 2)) | sed 's/x/é/g')"
    chars=$(printf '%s' "$name" | wc -c)
  fi
  model="$work/long-$round.json"
  printf '%s' "$name" >"$work/name-$round.txt"
  target=$((RANDOM % 3))
  # the name from a file (a 1 MB argument is too long for a command line)
  case $target in
    0) pattern='"name": "lever-and-stop"' replacement='"name": "@"' ;;
    1) pattern='"name": "lever"' replacement='"name": "@"' ;;
    2) pattern='lever-width' replacement='@' ;;
  esac
  awk -v pattern="$pattern" -v replacement="$replacement" 'NR == FNR { name = $0; next }
    { out = ""; while ((i = index($0, pattern)) > 0) { r = replacement; sub(/@/, name, r); out = out substr($0, 1, i - 1) r; $0 = substr($0, i + length(pattern)) }
      print out $0 }' "$work/name-$round.txt" "$source/examples/models/lever-stop.json" >"$model"
  if [ $target -eq 2 ] && LC_ALL=C grep -q $'\303' "$work/name-$round.txt"; then
    # not a parameter name (letters, digits, '-' and '_'): refused in one short line naming it
    for command in validate show; do
      extra=()
      [ $command = show ] && extra=(--svg "$work/long-$round.svg")
      "$hipair" $command "$model" "${extra[@]}" >"$work/long-$round.err" 2>&1
      code=$?
      [ $code -eq 2 ] || fail "$command, a $chars-byte invalid parameter name: exit $code"
      [ "$(wc -l <"$work/long-$round.err")" -eq 1 ] && [ "$(longest "$work/long-$round.err")" -le 400 ] ||
        fail "$command, a $chars-byte invalid parameter name: $(wc -c <"$work/long-$round.err") bytes of message"
      grep -q "^hipair: error: /parameters/a.*\.\.\. ([0-9]* characters) invalid parameter name" "$work/long-$round.err" ||
        fail "$command, a $chars-byte invalid parameter name: not named: $(head -c 300 "$work/long-$round.err")"
    done
    continue
  fi
  "$hipair" validate "$model" >"$work/long-$round.validate" 2>&1 || fail "validate, $chars-byte name ($target): exit $?"
  [ "$(longest "$work/long-$round.validate")" -le 400 ] ||
    fail "validate prints a line of $(longest "$work/long-$round.validate") bytes for a $chars-byte name ($target)"
  grep -q "($chars characters)" "$work/long-$round.validate" ||
    fail "validate does not give the $chars-byte name's length ($target): $(head -c 300 "$work/long-$round.validate")"
  "$hipair" show "$model" --svg "$work/long-$round.svg" >"$work/long-$round.show" 2>&1 || fail "show, $chars-byte name: exit $?"
  [ "$(longest "$work/long-$round.show")" -le 400 ] || fail "show prints a line of $(longest "$work/long-$round.show") bytes"
  if [ $target -eq 0 ]; then
    grep -q "($chars characters)')$" "$work/long-$round.show" || fail "show does not give the name's length: $(head -c 300 "$work/long-$round.show")"
    [ "$(LC_ALL=C tr -cd 'x\303\251' <"$work/long-$round.svg" | wc -c)" -ge "$chars" ] || fail "the SVG does not keep the whole $chars-byte name"
  fi
done
# a name of 200 bytes is printed whole
short=$(repeat y 200)
sed "s/\"name\": \"lever-and-stop\"/\"name\": \"$short\"/" "$source/examples/models/lever-stop.json" >"$work/short.json"
"$hipair" show "$work/short.json" --svg "$work/short.svg" >"$work/short.show" 2>&1
[ "$(cat "$work/short.show")" = "wrote $work/short.svg (2 parts of '$short')" ] || fail "a 200-byte name is not printed whole: $(cat "$work/short.show")"

# 2. long option values: the exit code of a short bad value, a short message
models="$source/examples/models"
options=(
  "simulate $models/escapement.json --out $work/o --t-end"
  "simulate $models/escapement.json --t-end 1 --out $work/o --accuracy"
  "tolerance $models/geneva.json --out $work/o --monte-carlo"
  "cspace $models/geneva.json --tiles"
  "show $models/geneva.json --svg $work/o.svg --width"
  "analyze $models/geneva.json --out $work/o --positions"
  "validate $models/geneva.json"
)
for option in "${options[@]}"; do
  length=$((201 + RANDOM * 3))
  digits="$((1 + RANDOM % 9))$(repeat 1 $((length - 1)))"
  [ $((RANDOM % 2)) -eq 0 ] && digits="1/$(repeat 3 $((length - 2)))"
  # shellcheck disable=SC2086
  "$hipair" $option 12x >"$work/short-value.out" 2>&1
  expected=$?
  # shellcheck disable=SC2086
  "$hipair" $option "${digits}x" >"$work/long-value.out" 2>&1
  code=$?
  [ $code -ne 0 ] && [ $code -lt 128 ] || fail "'$option <$length characters>': exit $code"
  [ $code -eq $expected ] || fail "'$option <$length characters>': exit $code, $expected for a short bad value"
  [ "$(wc -c <"$work/long-value.out")" -le 400 ] ||
    fail "'$option <$length characters>' echoes the value: $(head -c 200 "$work/long-value.out")"
  grep -q "($((${#digits} + 1)) characters)" "$work/long-value.out" ||
    fail "'$option <$length characters>': the length is not given: $(head -c 300 "$work/long-value.out")"
done
[ -e "$work/o" ] && fail "an output directory was written by a refused command"

# 3. progress on a terminal during the classification of a mixed-scale pair
if script -qc true /dev/null >/dev/null 2>&1; then
  # ratios of 10^120 … 10^128: coefficients of ≈ 400 bits, well over the 300 the reason needs
  # (10^85 … 10^103 straddled it: seed 28812 drew 1e-28 / 1e62, 300 bits or fewer, no reason)
  small=$((25 + RANDOM % 5)) large=$((95 + RANDOM % 5))
  cat >"$work/mixed.json" <<EOF
{ "hipair": 1, "name": "mixed", "parts": [
  { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } },
    "loops": [ { "start": ["-1e-$small", "-1e-$small"], "edges": [
      { "line_to": ["1e-$small", "-1e-$small"] }, { "line_to": ["1e-$small", "1e-$small"] },
      { "line_to": ["-1e-$small", "1e-$small"] }, { "line_to": ["-1e-$small", "-1e-$small"] } ] } ] },
  { "name": "b", "motion": { "rotation": { "pivot": ["1e-$small + 1.001e$large", 0] } },
    "loops": [ { "start": ["1e-$small + 0.001e$large", "-1e$large"], "edges": [
      { "line_to": ["1e-$small + 2.001e$large", "-1e$large"] }, { "line_to": ["1e-$small + 2.001e$large", "1e$large"] },
      { "line_to": ["1e-$small + 0.001e$large", "1e$large"] }, { "line_to": ["1e-$small + 0.001e$large", "-1e$large"] } ] } ] } ] }
EOF
  script -qc "timeout 120 '$hipair' cspace '$work/mixed.json' --json '$work/mixed-cs.json'" "$work/mixed.tty" >/dev/null 2>&1
  tr '\r' '\n' <"$work/mixed.tty" >"$work/mixed.lines"
  grep -q "^hipair: a:b classifying chart 1/4: [0-9]*% (exact signs, coefficients of up to [0-9]* bits" "$work/mixed.lines" ||
    fail "1e-$small / 1e$large mm squares: no classification progress on a terminal: $(tail -c 300 "$work/mixed.lines")"
  [ -s "$work/mixed-cs.json" ] || fail "1e-$small / 1e$large mm squares: cspace did not finish in 120 s"
  # the same pair at one scale: progress without the reason
  sed "s/1e-$small/1/g; s/e$large//g" "$work/mixed.json" >"$work/plain.json"
  script -qc "'$hipair' cspace '$work/plain.json'" "$work/plain.tty" >/dev/null 2>&1
  grep -q "bits" "$work/plain.tty" && fail "a pair at one scale is said to have wide coefficients: $(tr '\r' '\n' <"$work/plain.tty" | grep bits | tail -1)"
else
  echo "script(1) cannot run here: the terminal progress case is skipped"
fi

# analyze keeps every turn's samples: a driver range of thousands of turns ran out of memory
# before "driver range too long" (session 41, hunt41); at most 100 turns or cycles
turns=$((101 + RANDOM % 100000))
for option in "--range 0:$((turns * 400))" "--range=-$((turns * 400)):0" "--cycles $turns" "--cycles 1e$((3 + RANDOM % 300))"; do
  rm -rf "$work/turns"
  # shellcheck disable=SC2086
  timeout 30 "$hipair" analyze "$source/examples/models/cam-follower.json" $option --out "$work/turns" \
    >"$work/turns.out" 2>"$work/turns.err"
  status=$?
  [ $status -eq 2 ] || fail "analyze $option: exit $status, not 2: $(head -c 300 "$work/turns.err")"
  grep -q "^hipair: error: ${option%%[ =]*} .*\(turns\|cycles\)" "$work/turns.err" ||
    fail "analyze $option: $(head -c 300 "$work/turns.err")"
  [ -e "$work/turns" ] && fail "analyze $option: wrote its --out directory"
done

# tolerance's nominal path and chains go through the library's kinematics, which now refuses a
# rotating driver's range of more than 100 turns (session 41, integrator: `tolerance --range
# 0:100000` grew past 1 GB in 20 s on the cam follower)
for case in "cam-follower.json --range 0:$((turns * 400))" "geneva.json --range=-$((turns * 7)).5:0" \
            "gear-train.json --driver gear-A --chain --range 0:$((turns * 7))" "lift-chain.json --driver cam --chain --range 0:1e$((3 + RANDOM % 300))"; do
  rm -rf "$work/turns"
  # shellcheck disable=SC2086
  timeout 30 "$hipair" tolerance "$source/examples/models/"$case --quiet --out "$work/turns" >"$work/turns.out" 2>"$work/turns.err"
  status=$?
  [ $status -eq 2 ] || fail "tolerance $case: exit $status, not 2: $(head -c 300 "$work/turns.err")"
  grep -q "^hipair: error: the driver range .* spans more than 100 turns of the driver" "$work/turns.err" &&
    [ "$(wc -l <"$work/turns.err")" -eq 1 ] || fail "tolerance $case: $(head -c 300 "$work/turns.err")"
  [ -e "$work/turns" ] && fail "tolerance $case: wrote its --out directory"
done

# `show --config` places a part only where its motion limits allow (session 56: lever=1e400 drew
# the lever through its stop with exit 0): refused exactly beyond a limit, drawn exactly at it,
# and the SVG not written
lever="$source/examples/models/lever-stop.json"
for case in "lever=1e400" "lever=-30.000000001deg" "lever=120.000000001" "lever=-0.5236rad"; do
  rm -f "$work/limit.svg"
  timeout 30 "$hipair" show "$lever" --config "$case" --svg "$work/limit.svg" >"$work/limit.out" 2>"$work/limit.err"
  status=$?
  [ $status -eq 2 ] || fail "show --config $case: exit $status, not 2: $(head -c 300 "$work/limit.err")"
  [ "$(wc -l <"$work/limit.err")" -eq 1 ] || fail "show --config $case: not one line: $(head -c 300 "$work/limit.err")"
  [ -e "$work/limit.svg" ] && fail "show --config $case: wrote its SVG"
done
grep -q "part 'lever' at .* lies outside its angle limits" "$work/limit.err" 2>/dev/null ||
  grep -q "lever" "$work/limit.err" || fail "show --config: the message names no part: $(head -c 300 "$work/limit.err")"
for case in "lever=-30" "lever=120deg" "lever=0.5rad" "lever=-30deg"; do
  timeout 30 "$hipair" show "$lever" --config "$case" --svg "$work/limit.svg" >/dev/null 2>"$work/limit.err" ||
    fail "show --config $case (inside the limits) refused: $(head -c 300 "$work/limit.err")"
done

if [ $failures -ne 0 ]; then
  echo "$failures hostile CLI check(s) failed (seed $seed)"
  exit 1
fi
echo "hostile CLI checks passed (seed $seed)"
