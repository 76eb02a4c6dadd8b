#!/usr/bin/env bash
# Expected contacts and loads outside the driven chain, session 46 (hunt46): docs/cli.md "Options
# that do not apply". A model of two mechanisms side by side (generated names; a lever against a
# stop that turns, twice, or a spur pair and a lever): `analyze --driver D --expect P` where only a
# pair the driver does not move (the other mechanism's) has a contact label containing P, and
# `--load PART=+` on a part of the other mechanism, are refused with one line naming the option,
# the pair or part and the driver, exit 2, nothing written (until session 46 both were taken and
# ignored: the pattern matched no contact of the run, so every contact was "unintended"; the load
# acted on nothing). Controls: the same pattern with the other mechanism's part as --driver, and a
# pattern of the driven pair, are taken (exit 0). Generated cases (a seed per run, printed on
# failure; HIPAIR_TEST_SEED repeats one).
# usage: run_expect_chain_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
# shellcheck source=seeded_test.sh
source "$(dirname "$0")/seeded_test.sh" "$@"
# shellcheck source=expect_refused.sh
source "$(dirname "$0")/expect_refused.sh"
refused() {   # WHAT PATTERN ARGS... (PATTERN a fixed string)
  local what=$1 pattern=$2
  shift 2
  rm -rf "$work/out"
  timeout 120 "$hipair" "$@" --out "$work/out" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  expect_refused "$what" "$pattern" -qF
}
taken() {   # WHAT ARGS...
  local what=$1
  shift
  timeout 300 "$hipair" "$@" --quiet >"$work/ok.out" 2>"$work/ok.err" || fail "$what: exit $?: $(head -c 300 "$work/ok.err")"
}
word() { printf '%s' "$(tr -dc 'a-z' </dev/urandom | head -c $((RANDOM % 5 + 3)))$RANDOM"; }

# MODEL KIND(0: two levers, 1: gears and a lever) NAMES...: the first mechanism's parts (two), then
# the second's (a lever and its stop); the second mechanism lies SHIFT mm below the first
two_mechanisms() {
  python3 - "$source/examples/models" "$@" <<'PY'
import copy, json, sys
models, out, kind = sys.argv[1], sys.argv[2], int(sys.argv[3])
names = sys.argv[4:8]
shift = int(sys.argv[8])
lever = json.load(open(models + '/lever-stop.json'))
def turning(t):
    t['parts'][1]['motion'] = {'rotation': {'pivot': [45, 30]}}
    t['parts'][1]['initial'] = {'angle': 0}
def moved(part, dy):
    part = copy.deepcopy(part)
    def sh(p): return [p[0], (p[1] + ' - ' + str(dy)) if isinstance(p[1], str) else p[1] - dy]
    rot = part['motion'].get('rotation') if isinstance(part['motion'], dict) else None
    if rot: rot['pivot'] = sh(rot['pivot'])
    for loop in part['loops']:
        loop['start'] = sh(loop['start'])
        for e in loop['edges']:
            for k in ('line_to', 'arc_to', 'center'):
                if k in e: e[k] = sh(e[k])
    return part
turning(lever)
second = [moved(p, shift) for p in lever['parts']]
if kind == 0:
    model = copy.deepcopy(lever)
else:
    model = json.load(open(models + '/spur-gears.json'))
    model['parameters'].update(lever['parameters'])
    model['pairs'] = []
for p, name in zip(model['parts'] + second, names):
    p['name'] = name
model['parts'] = model['parts'][:2] + second
model['pairs'] = [{'parts': names[0:2]}, {'parts': names[2:4]}]
json.dump(model, open(out, 'w'), indent=1)
PY
}

for round in $(seq 1 6); do
  kind=$((RANDOM % 2))
  a=$(word) b=$(word) c=$(word) d=$(word)
  model=$work/two-$round.json
  two_mechanisms "$model" $kind "$a" "$b" "$c" "$d" $((RANDOM % 900 + 300))
  driver=$a
  [ $((RANDOM % 2)) -eq 0 ] && driver=$b
  # a pattern only the second mechanism's labels contain: its lever's or its stop's name with a
  # feature (a label is "<part> <feature> / <part> <feature> (<how>)")
  features=("$c upper side" "$c tip" "$c lower side" "$d stop face" "$c upper side / $d" "$c" "$d")
  pattern=${features[$((RANDOM % ${#features[@]}))]}
  refused "round $round: --driver $driver --expect '$pattern'" \
    "--expect $pattern: only a contact of $c:$d has a label containing it, a pair the analysis driven by '$driver' does not move (its pairs: $a:$b;" \
    analyze "$model" --driver "$driver" --expect "$pattern"
  # the expected contacts of both mechanisms: the second's pattern still refused
  refused "round $round: --expect '$a' --expect '$pattern'" "--expect $pattern: only a contact of $c:$d" \
    analyze "$model" --driver "$driver" --expect "$a" --expect "$pattern"
  load=$c
  [ $((RANDOM % 2)) -eq 0 ] && load=$d
  refused "round $round: --driver $driver --load $load=+" \
    "--load $load=+: '$load' is not moved by the analysis driven by '$driver' (no chain of pairs connects them" \
    analyze "$model" --driver "$driver" --load "$load=+"
  # controls: driven by the second mechanism's lever, its pattern and its stop's load are taken
  if [ "$round" -le 2 ]; then
    taken "round $round: --driver $c --expect '$pattern' --load $d=+" analyze "$model" --driver "$c" --expect "$pattern" --load "$d=+"
    [ $kind -eq 0 ] && taken "round $round: --driver $a --expect '$a'" analyze "$model" --driver "$a" --expect "$a"
  fi
done

if [ $failures -gt 0 ]; then
  echo "$failures failure(s) (seed $seed)"
  exit 1
fi
echo "expect-chain tests passed (seed $seed)"
