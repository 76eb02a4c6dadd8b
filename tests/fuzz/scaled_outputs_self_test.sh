#!/usr/bin/env bash
# tests/fuzz/scaled_outputs.py must fail when an output differs (session 54): the scaled run's
# output (analyze: kinematics.csv or report.json; simulate: trajectory.csv; tolerance:
# variation.csv) has one digit changed
# after the run by a wrapper around hipair, and the comparison must say DIFFERENT naming that
# file and exit 1; the same runs unperturbed must give "same" and exit 0 (the control).
# usage: scaled_outputs_self_test.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
hipair="$(realpath "$1")" source="$(realpath "$2")" work="$3"
rm -rf "$work" && mkdir -p "$work" && work="$(realpath "$work")"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# the wrapper: hipair, then one digit of FILE in the output folder of a run at 10^30 changed
cat >"$work/hipair" <<WRAPPER
#!/usr/bin/env bash
"$hipair" "\$@"
rc=\$?
out=""
while [ \$# -gt 0 ]; do [ "\$1" = --out ] && out="\$2"; shift; done
if [ -n "\${PERTURB:-}" ] && [ "\${out##*@}" = 30 ] && [ -f "\$out/\$PERTURB" ]; then
  python3 - "\$out/\$PERTURB" <<'PY'
import re, sys
path = sys.argv[1]
text = open(path, encoding="utf-8").read()
line = text.index("\n") + 1                        # past a CSV's header or a JSON's first line
m = re.compile(r"[1-8]").search(text, line)         # the first digit after it, one more
open(path, "w", encoding="utf-8").write(text[:m.start()] + str(int(m.group()) + 1) + text[m.end():])
PY
fi
exit \$rc
WRAPPER
chmod +x "$work/hipair"

# check NAME COMMAND MODEL PERTURB: scaled_outputs.py through the wrapper, perturbing PERTURB ("" none)
check() {
  local name=$1 command=$2 model=$3 perturb=$4
  PERTURB="$perturb" python3 "$source/tests/fuzz/scaled_outputs.py" "$work/hipair" "$source" "$work/$name" "$command" \
    "$model" 30 120 >"$work/$name.txt" 2>&1
  local rc=$?
  if [ -z "$perturb" ]; then
    [ $rc -eq 0 ] && grep -q 'x1e30: same' "$work/$name.txt" || fail "$name: the unperturbed control did not pass (exit $rc): $(tail -c 400 "$work/$name.txt")"
  else
    [ $rc -eq 1 ] || fail "$name: exit $rc with $perturb changed (expected 1): $(tail -c 400 "$work/$name.txt")"
    grep -q "x1e30: DIFFERENT: $perturb " "$work/$name.txt" ||
      fail "$name: no difference named in $perturb: $(tail -c 400 "$work/$name.txt")"
  fi
}
check analyze-control analyze cam-follower ""
check analyze-csv analyze cam-follower kinematics.csv
check analyze-json analyze cam-follower report.json
check simulate-control simulate=0.01 cam-follower ""
check simulate-csv simulate=0.01 cam-follower trajectory.csv
check tolerance-control tolerance cam-follower ""
check tolerance-csv tolerance cam-follower variation.csv
((failures == 0)) || { echo "scaled_outputs self-test: $failures failure(s)"; exit 1; }
echo "scaled_outputs self-test passed"
