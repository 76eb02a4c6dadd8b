# Shared preamble of the CLI tests that run both hipair and hipair-verify (sourced with the
# test's own arguments):
#   source "$(dirname "$0")/seeded_verify_test.sh" "$@"   # HIPAIR_BINARY HIPAIR_VERIFY SOURCE_DIR WORK_DIR
# python3 resolved once to the interpreter itself (a pyenv shim starts a shell script per call,
# ~0.7 s of CPU each, and these scripts call python3 in loops: session 43, build43); sets verify,
# then everything seeded_test.sh sets (hipair, source, work emptied, failures=0, seed, fail).
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
verify=$2
# shellcheck source=seeded_test.sh
source "$(dirname "${BASH_SOURCE[0]}")/seeded_test.sh" "$1" "$3" "$4"

# mutate_certificate SOURCE KEY MODEL NAME STATEMENTS MESSAGE: the certificate SOURCE edited by the
# Python STATEMENTS (on c, the whole document, and body = c[KEY]) into $work/NAME.json, which
# hipair-verify must find invalid against MODEL (exit 1) with MESSAGE in its output.
mutate_certificate() {
  python3 - "$1" "$work/$4.json" "$2" "$5" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
body = c[sys.argv[3]]
exec(sys.argv[4])
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
  local out
  out=$("$verify" "$work/$4.json" "$3")
  [ $? -eq 1 ] || fail "mutation $4 not invalid: $out"
  case "$out" in *"$6"*) ;; *) fail "mutation $4: not '$6': $out" ;; esac
}
