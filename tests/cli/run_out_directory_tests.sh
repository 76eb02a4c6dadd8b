#!/usr/bin/env bash
# `--out DIR` that cannot be a directory, and `simulate --sweep` values the model refuses, session 52
# (hunt52): docs/cli.md "Outputs".
# - analyze, tolerance and simulate (one run, a sweep, a part free in the plane) with --out naming
#   an existing regular file (a generated name and content), the model file itself, or a path
#   below such a file: refused before the computation — one line naming --out and the path,
#   exit 3, nothing on stdout (until session 52 the whole analysis or simulation ran, its results
#   were printed, and only the publication failed, exit 3: hours for a long simulate), the file
#   unchanged, nothing created beside it;
# - `cspace --json/--svg` of a 3-DOF and a pin-slot pair and `certify --out` with a file's
#   directory being a regular file: refused before the build or search (until session 52 the
#   whole C-space was built first), one line naming the option and the file in the way;
# - an empty output path (`--out ""`, an unset shell variable) refused by every command that
#   writes, naming the option, exit 105 (until session 52 each took it as no output: exit 0,
#   nothing written, `analyze` even suggesting --out);
# - an existing --out DIR with earlier files survives every failing run (a sweep value the model
#   refuses, a run out of step budget) byte for byte;
# - a sweep value the model refuses is named with the --sweep option, the run and the value
#   (until session 52 only the model's pointer: `/parts/0/features/0/escape_wheel/teeth: must
#   be at least 3`);
# - a subnormal --t-end (below 2.2e-308) is refused naming --t-end, exit 2, nothing written (until
#   session 52 it ran, its times and states off in their 4th digit: v = -g t printed -9.805e-317
#   for -9.81e-317 at --t-end 1e-320).
# Generated cases (a seed per run, printed on failure; HIPAIR_TEST_SEED repeats one). Controls:
# a new --out DIR and an existing one are written.
# usage: run_out_directory_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
m=$source/examples/models
escapement=$source/tests/data/simulation/escapement-frictionless.json
cam=$m/cam-follower.json film=$m/film-advance.json peg=$m/peg-throw.json

word() { printf '%s' "$(tr -dc 'a-z' </dev/urandom | head -c $((RANDOM % 6 + 4)))q$RANDOM"; }
listing() { (cd "$work" && find . -path ./run -prune -o -print | LC_ALL=C sort | xargs -d '\n' md5sum 2>/dev/null; find . | LC_ALL=C sort); }

refused() {   # WHAT TEXT REGEX ARGS...: the command ARGS refused before it ran, exit 3, one line holding
              # TEXT (fixed) and matching REGEX, nothing on stdout, no file changed
  local what=$1 text=$2 regex=$3
  shift 3
  local before
  before=$(listing)
  (cd "$work" && timeout 120 "$hipair" "$@" >"$work/run/bad.out" 2>"$work/run/bad.err")
  status=$?
  [ "$status" -eq 3 ] || fail "$what: exit $status, not 3: $(head -c 300 "$work/run/bad.err")"
  [ -s "$work/run/bad.out" ] && fail "$what: ran before refusing (stdout: $(head -c 200 "$work/run/bad.out"))"
  [ "$(wc -l <"$work/run/bad.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/run/bad.err")"
  grep -qF -- "$text" "$work/run/bad.err" || fail "$what: the message lacks '$text': $(head -c 300 "$work/run/bad.err")"
  grep -qE -- "$regex" "$work/run/bad.err" || fail "$what: the message says not why: $(head -c 300 "$work/run/bad.err")"
  [ "$(listing)" = "$before" ] || fail "$what: files changed"
}
refused_out() {   # WHAT OUT ARGS... (the command with --out OUT last)
  local what=$1 out=$2
  shift 2
  refused "$what" "--out '$out': " "is not a directory" "$@" --out "$out"
}

mkdir -p "$work/run" && touch "$work/run/bad.out" "$work/run/bad.err"
for round in $(seq 1 3); do
  f=$(word).$(word)
  head -c $((RANDOM % 300 + 1)) /dev/urandom >"$work/$f"
  cp "$cam" "$work/cam.json"
  commands=("analyze $cam --quiet" "analyze $film --quiet" "tolerance $cam --positions 16 --quiet"
            "simulate $escapement --t-end 0.02 --allow-out-of-tolerance --no-pictures"
            "simulate $escapement --t-end 0.02 --allow-out-of-tolerance --sweep drive-torque=-200:-300:2"
            "simulate $peg --t-end 0.02 --no-pictures")
  for c in "${commands[@]}"; do
    # shellcheck disable=SC2206
    command=($c)
    refused_out "$c --out FILE" "$f" "${command[@]}"
    refused_out "$c --out FILE/sub/dir" "$f/$(word)/$(word)" "${command[@]}"
  done
  for c in "cspace $m/peg-in-hole.json --json" "cspace $film --pair cam:follower --svg" "certify $m/lever-stop.json --claim jam --out"; do
    # shellcheck disable=SC2206
    command=($c)
    target="$f/$(word).$( ((RANDOM % 2)) && echo json || echo svg)"
    before=$(listing)
    (cd "$work" && timeout 120 "$hipair" "${command[@]}" "$target" >"$work/run/bad.out" 2>"$work/run/bad.err")
    status=$?
    [ "$status" -eq 3 ] || fail "$c FILE/x: exit $status, not 3: $(head -c 300 "$work/run/bad.err")"
    [ -s "$work/run/bad.out" ] && fail "$c FILE/x: wrote to stdout"
    grep -qF -- "${command[-1]} '$target': '$work/$f' exists and is not a directory, so the file cannot be written there" \
      "$work/run/bad.err" || fail "$c FILE/x: the message names not the option and the file in the way: $(head -c 300 "$work/run/bad.err")"
    grep -qF "nothing was built or written" "$work/run/bad.err" || fail "$c FILE/x: refused after the build: $(head -c 300 "$work/run/bad.err")"
    [ "$(listing)" = "$before" ] || fail "$c FILE/x: files changed"
  done
  refused_out "tolerance --out its own model" "$work/cam.json" tolerance "$work/cam.json" --positions 16 --quiet
  refused_out "analyze --out its own model" "$work/cam.json" analyze "$work/cam.json" --quiet
  rm -f "$work/$f" "$work/cam.json"

  # an existing DIR survives failing runs
  d=$work/$(word)
  mkdir -p "$d"
  for name in trajectory.csv events.json sweep.json $(word).txt; do head -c $((RANDOM % 100 + 1)) /dev/urandom >"$d/$name"; done
  before=$(cd "$d" && md5sum ./* | LC_ALL=C sort)
  teeth=$((RANDOM % 2 + 1))   # 1 or 2: the escape wheel needs at least 3 teeth
  timeout 120 "$hipair" simulate "$escapement" --t-end 0.01 --allow-out-of-tolerance \
    --sweep "wheel-teeth=$teeth:$((teeth + 20)):3" --out "$d" >"$work/run/bad.out" 2>"$work/run/bad.err"
  status=$?
  [ "$status" -eq 2 ] || fail "sweep wheel-teeth=$teeth: exit $status, not 2"
  [ -s "$work/run/bad.out" ] && fail "sweep wheel-teeth=$teeth: writes to stdout"
  grep -qF -- "--sweep wheel-teeth=$teeth:$((teeth + 20)):3: the model of run 1 of 3, wheel-teeth=$teeth ;" "$work/run/bad.err" ||
    fail "sweep wheel-teeth=$teeth: the message names not the sweep's run and value: $(head -c 300 "$work/run/bad.err")"
  grep -qF "/parts/0/features/0/escape_wheel/teeth: must be at least 3" "$work/run/bad.err" ||
    fail "sweep wheel-teeth=$teeth: the model's pointer is lost: $(head -c 300 "$work/run/bad.err")"
  timeout 120 "$hipair" simulate "$escapement" --t-end 0.01 --allow-out-of-tolerance --max-steps $((RANDOM % 3 + 1)) \
    --out "$d" >"$work/run/bad.out" 2>"$work/run/bad.err"
  status=$?
  [ "$status" -eq 3 ] || fail "simulate out of step budget: exit $status, not 3"
  [ "$(cd "$d" && md5sum ./* | LC_ALL=C sort)" = "$before" ] || fail "an existing --out DIR changed under failing runs"
  # controls: an existing DIR and a new one are written
  timeout 120 "$hipair" simulate "$escapement" --t-end 0.002 --allow-out-of-tolerance --no-pictures --out "$d" \
    >"$work/run/ok.out" 2>&1 || fail "simulate into an existing DIR: exit $?: $(tail -c 300 "$work/run/ok.out")"
  grep -q "escape-wheel" "$d/trajectory.csv" || fail "simulate into an existing DIR wrote no trajectory"
  timeout 120 "$hipair" simulate "$escapement" --t-end 0.002 --allow-out-of-tolerance \
    --sweep "drive-torque=-200:-300:2" --out "$d/$(word)/$(word)" >"$work/run/ok.out" 2>&1 ||
    fail "sweep into a new DIR: exit $?: $(tail -c 300 "$work/run/ok.out")"
  rm -rf "$d"
done

# Places that take no new entry (session 63, hunt63): a directory under /proc (which takes none,
# even from root), a directory without write permission (when not root), and for one-file outputs
# a directory that does not exist (their writer makes none). Each refused before the computation
# naming the option and the place, exit 3, nothing on stdout, nothing created; until session 63
# the whole analysis, simulation, C-space build or search ran first (`cspace gear-train.json
# --json /proc/x.json`: 7.6 s, then `cannot write '/proc/x.json'`; `simulate --out /sys/x` printed
# its results, then `cannot create '/sys/.x.tmp-N'`).
refused_place() {   # WHAT EXPECTED-TEXT ARGS... (the command, its output path last)
  local what=$1 text=$2
  shift 2
  refused "$what" "$text" "nothing was (run|built) or written\)$" "$@"
}
places=()
if [ -d /proc/self ] && ! mkdir "/proc/hipair-probe-$RANDOM" 2>/dev/null; then places+=("/proc:/proc/$(word)"); fi
if [ "$(id -u)" != 0 ]; then
  mkdir -p "$work/locked" && chmod 0555 "$work/locked" && places+=("$work/locked:$work/locked/$(word)")
fi
for place in "${places[@]}"; do
  at=${place%%:*} path=${place#*:}
  for c in "analyze $cam --quiet" "tolerance $cam --positions 16 --quiet" \
           "simulate $escapement --t-end 0.02 --allow-out-of-tolerance --no-pictures" \
           "simulate $escapement --t-end 0.02 --allow-out-of-tolerance --sweep drive-torque=-200:-300:2" \
           "simulate $peg --t-end 0.02 --no-pictures"; do
    # shellcheck disable=SC2206
    command=($c)
    for out in "$path" "$path/$(word)"; do
      refused_place "$c --out $out" "--out '$out': nothing can be created in '$at': " "${command[@]}" --out "$out"
    done
  done
done
for c in "cspace $m/gear-train.json --json" "cspace $m/peg-in-hole.json --svg" "certify $m/lever-stop.json --claim jam --out" \
         "show $m/lever-stop.json --svg"; do
  # shellcheck disable=SC2206
  command=($c)
  missing="$work/$(word)/$(word).$( ((RANDOM % 2)) && echo json || echo svg)"
  refused_place "$c MISSING-DIR/x" "${command[-1]} '$missing': directory '${missing%/*}' does not exist" "${command[@]}" "$missing"
  for place in "${places[@]}"; do
    at=${place%%:*} path=${place#*:}.json
    refused_place "$c $path" "${command[-1]} '$path': nothing can be created in '$at': " "${command[@]}" "$path"
  done
done
[ -d "$work/locked" ] && chmod 0755 "$work/locked" && rmdir "$work/locked"

# an empty output path
for c in "simulate $escapement --t-end 0.002 --allow-out-of-tolerance --out" "analyze $cam --quiet --out" \
         "tolerance $cam --positions 16 --quiet --out" "cspace $m/lever-stop.json --json" "cspace $m/lever-stop.json --svg" \
         "certify $m/lever-stop.json --claim jam --out" "show $m/lever-stop.json --svg"; do
  # shellcheck disable=SC2206
  command=($c)
  timeout 120 "$hipair" "${command[@]}" "" >"$work/run/bad.out" 2>"$work/run/bad.err"
  status=$?
  [ "$status" -eq 105 ] || fail "$c '': exit $status, not 105"
  [ -s "$work/run/bad.out" ] && fail "$c '': ran (stdout: $(head -c 100 "$work/run/bad.out"))"
  grep -qF -- "hipair: error: ${command[-1]}: an empty path names no file or directory to write" "$work/run/bad.err" ||
    fail "$c '': the message names not the option: $(head -c 300 "$work/run/bad.err")"
done

# a subnormal --t-end
for t in 1e-320 4.9e-324 2.2e-308 "$((RANDOM % 9 + 1))e-$((RANDOM % 15 + 309))"; do
  timeout 60 "$hipair" simulate "$escapement" --t-end "$t" --allow-out-of-tolerance --out "$work/sub" >"$work/run/bad.out" 2>"$work/run/bad.err"
  status=$?
  [ "$status" -eq 2 ] || fail "simulate --t-end $t: exit $status, not 2"
  grep -q -- "^hipair: error: --t-end .*: below the least normal double" "$work/run/bad.err" ||
    fail "simulate --t-end $t: the message names no --t-end: $(head -c 300 "$work/run/bad.err")"
  [ -e "$work/sub" ] && fail "simulate --t-end $t wrote its --out"
  rm -rf "$work/sub"
done
timeout 60 "$hipair" simulate "$escapement" --t-end 2.2250738585072014e-308 --allow-out-of-tolerance --no-pictures \
  >"$work/run/ok.out" 2>&1 || fail "simulate --t-end at the least normal double: exit $?: $(tail -c 300 "$work/run/ok.out")"

if [ $failures -gt 0 ]; then
  echo "$failures failure(s) (seed $seed)"
  exit 1
fi
echo "out-directory tests passed (seed $seed)"
