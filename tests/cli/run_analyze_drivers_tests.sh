#!/usr/bin/env bash
# Session 75 (drive75): every driver a user can name, `hipair analyze` answers or refuses cleanly.
# Generated over every example model (examples/models/*.json): the model's default driver (no
# --driver) and every part of the model as --driver. Each run must exit 0 with the report, or 2
# with exactly one line "hipair: error: ..." (naming --driver when --driver was given), never 3
# or another code, never exception text. (analyze has no --pair: the pairs are the driver's chain.)
# To keep it seconds: --quiet, --steps 16, and --cycles 1/360 (one degree of a turn) where the
# driven analysis applies (a model with a pin-in-slot part is analysed as its work cycle, which
# takes --steps only). base75 (integ 72bbecb9) exited 3 for film-advance's follower, pin and film
# ("pin-slot cycle: the driver 'film' does not rotate"), and refused bouncing-bar's bar and
# lever-stop's lever as --driver with "/pairs: part 'bar' drives no other part", naming no option.
# usage: run_analyze_drivers_tests.sh HIPAIR SOURCE_DIR WORK_DIR
set -uo pipefail
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }

# "FILE CYCLE PART" a line for every example model: first PART "-" (the default driver), then each
# part; CYCLE 1 when a pin-slot part is paired with a rotating part (the work cycle: analyze's
# has_pin_slot_part). One python for all models (a python a model cost a second of the run).
runs_of() {
  python3 - "$@" <<'PY'
import json, sys
for path in sys.argv[1:]:
    m = json.load(open(path))
    parts = m.get("parts", [])
    kinds = {}
    for p in parts:
        mo = p.get("motion")
        kinds[p["name"]] = next(iter(mo)) if isinstance(mo, dict) else str(mo)
    cycle = any({kinds.get(a), kinds.get(b)} == {"pin_slot", "rotation"} for a, b in (q["parts"] for q in m.get("pairs", [])))
    for name in ["-"] + [p["name"] for p in parts]:
        print(path, int(cycle), name)
PY
}

analysed=0 refused=0 runs=0
check() {   # MODEL_NAME DRIVER(or "") OUT ERR STATUS
  local model=$1 driver=$2 out=$3 err=$4 status=$5 what
  what="$model ${driver:+--driver $driver}"
  runs=$((runs + 1))
  if grep -qi "what()\|exception\|terminate\|assert\|internal error" "$err"; then
    fail "$what: exception text on stderr: $(head -c 300 "$err")"
  fi
  case $status in
    0)
      [ -s "$out" ] || fail "$what: exit 0 without a report"
      [ -s "$err" ] && fail "$what: exit 0 with stderr: $(head -c 300 "$err")"
      analysed=$((analysed + 1))
      ;;
    2)
      if [ "$(wc -l <"$err")" -ne 1 ] || ! grep -q '^hipair: error: ' "$err"; then
        fail "$what: exit 2 without exactly one line 'hipair: error: ...': $(head -c 300 "$err")"
      fi
      if [ -n "$driver" ] && ! grep -q -- '--driver' "$err"; then
        fail "$what: refused without naming --driver: $(head -c 300 "$err")"
      fi
      [ -s "$out" ] && fail "$what: refused with output on stdout"
      refused=$((refused + 1))
      ;;
    *)
      fail "$what: exit $status: $(head -c 300 "$err")"
      ;;
  esac
}

plan=$(runs_of "$source"/examples/models/*.json) || fail "the example models are not read"
models=$(grep -c ' -$' <<<"$plan")
while read -r file cycle part; do
  [ -n "$part" ] || continue
  model=$(basename "$file" .json)
  options=(--quiet --steps 16 --cycles 1/360)
  [ "$cycle" = 1 ] && options=(--steps 16)   # (--quiet leaves out the cycle's report; stderr is no terminal)
  if [ "$part" = - ]; then
    out=$work/$model.out
    "$hipair" analyze "$file" "${options[@]}" >"$out" 2>"$out.err"
    check "$model" "" "$out" "$out.err" $?
  else
    out=$work/$model-$part.out
    "$hipair" analyze "$file" --driver "$part" "${options[@]}" >"$out" 2>"$out.err"
    check "$model" "$part" "$out" "$out.err" $?
  fi
done <<<"$plan"

# the film advance driven by its film (run above): refused naming --driver and the part that can
# drive; its cam still drives the work cycle
grep -q -- "--driver: part 'film' is translating.*parts that can drive: 'cam'" "$work/film-advance-film.out.err" ||
  fail "film-advance --driver film: not the refusal expected: $(head -c 300 "$work/film-advance-film.out.err")"
grep -q "work cycle of follower (pin-in-slot) driven by cam" "$work/film-advance-cam.out" ||
  fail "film-advance --driver cam: no work cycle"

# not vacuous: every example model, drivers analysed and drivers refused
[ "$models" -ge 30 ] || fail "only $models example models"
[ "$analysed" -ge 40 ] || fail "only $analysed analyses ran"
[ "$refused" -ge 30 ] || fail "only $refused clean refusals"
echo "example models: $models, runs: $runs (analysed: $analysed, refused cleanly: $refused)"
if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all analyze driver tests passed"
