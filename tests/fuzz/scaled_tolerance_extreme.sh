#!/usr/bin/env bash
# `hipair tolerance` at 10^-300, 10^-320 and 10^400 against the unscaled run (session 56, scale56):
#  - the Geneva and the cam follower with a Monte Carlo (--threads 1) and the jamming threshold:
#    the same text, tolerance.json and CSVs up to the lengths' exponent (scaled_outputs.py);
#  - the Geneva's no-jam certificate (--certify): certified at every scale, the certificate the
#    unscaled one's with its second-order margins times 10^2K or 10^4K (contact functions of degree
#    2 or 4 in lengths), and hipair-verify answers 'valid' against each scaled model file (until
#    session 56 refused outside about 1e-9 .. 1e9 mm; margins at the copy's scale fail at 10^-300);
#  - the cam follower (a translating follower) with --certify: refused with one message naming
#    the part, nothing written.
# usage: scaled_tolerance_extreme.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK
set -uo pipefail
hipair=$1 verify=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
python3 "$source/tests/fuzz/scaled_outputs.py" "$hipair" "$source" "$work/a" \
  "tolerance=--monte-carlo 40 --threads 1 --threshold" geneva,cam-follower -300,-320,400 300 || fail "analysis at scale"
python3 "$source/tests/fuzz/scaled_outputs.py" "$hipair" "$source" "$work/c" \
  "tolerance=--range 2.2:2.3 --positions 720 --accuracy 0.5 --certify --certify-scale 2 --threads 1" geneva \
  -300,-320,400 300 || fail "certificate at scale"
for k in 0 -300 -320 400; do
  model="$source/examples/models/geneva.json"
  [ "$k" = 0 ] || model="$work/c/geneva@1e$k.json"
  grep -q "CERTIFIED: " "$work/c/out/geneva@$k/report.txt" || fail "x 1e$k: not certified"
  "$verify" "$work/c/out/geneva@$k/tolerance-certificate.json" "$model" >"$work/verify$k.txt" 2>&1 \
    || fail "x 1e$k: hipair-verify: $(tail -c 300 "$work/verify$k.txt")"
  grep -q "^valid: tolerance" "$work/verify$k.txt" || fail "x 1e$k: hipair-verify did not answer valid"
done
# the scaled certificate is not the unscaled model's (the verifier tells them apart)
"$verify" "$work/c/out/geneva@-300/tolerance-certificate.json" "$source/examples/models/geneva.json" \
  >"$work/verify-mixed.txt" 2>&1 && fail "the x 1e-300 certificate verified against the unscaled model"
python3 "$source/tests/fuzz/scale_model.py" "$source/examples/models/cam-follower.json" 1e-300 "$work/cam.json"
"$hipair" tolerance "$work/cam.json" --certify --quiet --out "$work/cam-out" >"$work/cam.txt" 2>&1
rc=$?
[ "$rc" = 2 ] || fail "cam follower x 1e-300 --certify: exit $rc, not 2"
[ "$(grep -c . "$work/cam.txt")" = 1 ] || fail "cam follower x 1e-300 --certify: not one line: $(cat "$work/cam.txt")"
grep -q "^hipair: error: /parts/1: --certify: .*part 'follower' translates" "$work/cam.txt" \
  || fail "cam follower x 1e-300 --certify: $(cat "$work/cam.txt")"
[ -e "$work/cam-out/tolerance.json" ] && fail "cam follower x 1e-300 --certify wrote tolerance.json"
echo "scaled_tolerance_extreme: ok"
