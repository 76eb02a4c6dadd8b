# Shared by the CLI tests of refused input (sourced): a run whose exit status is in $status and
# whose stdout and stderr are in $work/bad.out and $work/bad.err must exit 2 with one line on
# stderr that holds PATTERN (grep's option MODE, default -q: a basic regular expression; -qF: a
# fixed string), nothing on stdout, and none of the outputs out, x.svg, x.json, c.json in $work.
# Calls the test's fail function. usage: expect_refused WHAT PATTERN [MODE]
expect_refused() {
  local what=$1 pattern=$2 mode=${3:--q}
  [ "$status" -eq 2 ] || fail "$what: exit $status, not 2: $(head -c 300 "$work/bad.err")"
  [ -s "$work/bad.out" ] && fail "$what: writes to stdout: $(head -c 300 "$work/bad.out")"
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "$what: not one line: $(head -c 300 "$work/bad.err")"
  grep "$mode" -- "$pattern" "$work/bad.err" || fail "$what: the message names no ${pattern:0:60}: $(head -c 300 "$work/bad.err")"
  for f in out x.svg x.json c.json; do [ -e "$work/$f" ] && fail "$what: wrote $f"; done
}
