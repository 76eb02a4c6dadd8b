#!/usr/bin/env bash
# `hipair certify --claim apart` and `hipair-verify` on sliced_apart certificates (session 69): the
# 10 mm square peg of examples/models/peg-in-hole.json (12 mm hole) cannot turn a quarter
# (certified, verified); the certificate edited (the domain's boundary opened, a leaf dropped, b
# moved into a's component, a crossing's piece perturbed, the statement) is invalid with its
# reason; bad input exits 2 naming the option, nothing written.
# usage: run_certify_apart_tests.sh HIPAIR_BINARY HIPAIR_VERIFY_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"

model="$work/peg-in-hole.json"
cp "$source/examples/models/peg-in-hole.json" "$model"
"$hipair" certify "$model" --claim apart --at peg=0,0,0 --to peg=0,0,90deg --out "$work/apart.json" >"$work/apart.out" 2>&1 \
  || fail "certify --claim apart refuses the peg in the 12 mm hole: $(cat "$work/apart.out")"
grep -qF "certified sliced_apart: Part 'peg' cannot move from x=0, y=0, t=0 to x=0, y=0, t=1 without touching part 'plate'." "$work/apart.out" \
  || fail "certify --claim apart: not the statement: $(cat "$work/apart.out")"
out=$("$verify" "$work/apart.json" "$model") || fail "hipair-verify refuses the apart certificate: $out"
case "$out" in "valid: sliced_apart: part 'peg' cannot move from x=0, y=0, t=0 to x=0, y=0, t=1 without touching 'plate'"*) ;;
  *) fail "hipair-verify: not the summary: $out" ;; esac

mutate() { mutate_certificate "$work/apart.json" sliced_apart "$model" "$@"; }   # NAME PYTHON-STATEMENTS-ON-c-AND-body MESSAGE
# the first leaf holds the domain's lowest corner: blocked, its proof the first
mutate boundary-opened 'i = min(body["tree"].index("o"), body["tree"].index("b")); body["tree"] = body["tree"][:i] + "o" + body["tree"][i + 1:]; body["proofs"].pop(0)' \
  "touches the domain's boundary"
mutate leaf-dropped 'body["tree"] = body["tree"][:-1]' "the tree ends before it covers the domain"
mutate same-component 'body["b"]["tangent"] = "1/50"; c["statement"] = c["statement"].replace("t=1 without", "t=1/50 without")' \
  "a and b lie in one component"
mutate piece-perturbed 'p = next(p for p in body["proofs"] if p[0] == "cross"); p[6] = "0"; p[7] = "1/1000000"' \
  "the crossing does not hold over the box"
mutate statement 'c["statement"] = "Part peg cannot move."' "the statement does not say"
mutate unknown-key 'body["speed"] = "1"' "malformed certificate: /sliced_apart/speed: unknown key 'speed'"

# bad input: exit 2, one message naming the option, nothing written
expect_refused_on() {   # MODEL NAME MESSAGE ARGS...
  local on=$1 name=$2 message=$3
  shift 3
  "$hipair" certify "$on" "$@" --out "$work/$name.json" >"$work/$name.out" 2>&1
  local status=$?
  [ $status -eq 2 ] || fail "$name: exit $status, not 2: $(cat "$work/$name.out")"
  [ ! -e "$work/$name.json" ] || fail "$name: a certificate was written"
  grep -qF -- "$message" "$work/$name.out" || fail "$name: not '$message': $(cat "$work/$name.out")"
}
expect_refused() { expect_refused_on "$model" "$@"; }   # NAME MESSAGE ARGS...
expect_refused no-to "--claim apart needs --to peg=X,Y,ANGLE" --claim apart --at peg=0,0,0
expect_refused distance "--distance: applies to --claim clearance or free, not to --claim apart" --claim apart --to peg=0,0,1 --distance 1
expect_refused bad-to "--to expects peg=X,Y,ANGLE" --claim apart --to peg=0,0

# Pin-in-slot pairs (session 70): a bar on a pin at the origin, sliding along itself within
# [-2, 2], cannot turn from 0 to 90 degrees past a post at 45 degrees (its tip and its tail both
# meet it). Certified over (s, u), verified; mutated (b into a's component, the slide's face
# opened, a position given to the fixed post) invalid; bad input exits 2, nothing written.
bar="$work/bar-post.json"
cat >"$bar" <<'JSON'
{ "hipair": 1, "name": "bar-post", "parts": [
  { "name": "post", "motion": "fixed", "loops": [ { "start": [3.25, 3.5], "edges": [
    { "line_to": [4.75, 3.5] }, { "line_to": [4.75, 5] }, { "line_to": [3.25, 5] }, { "line_to": [3.25, 3.5] } ] } ] },
  { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "limits": [-2, 2] } },
    "loops": [ { "start": [-10, -0.5], "edges": [
    { "line_to": [10, -0.5] }, { "line_to": [10, 0.5] }, { "line_to": [-10, 0.5] }, { "line_to": [-10, -0.5] } ] } ] } ],
  "pairs": [{"parts": ["post", "bar"]}] }
JSON
"$hipair" certify "$bar" --claim apart --at bar=1,0 --to bar=-1,90deg --out "$work/bar-apart.json" >"$work/bar-apart.out" 2>&1 \
  || fail "certify --claim apart refuses the bar and post: $(cat "$work/bar-apart.out")"
grep -qF "certified sliced_apart: Part 'bar' cannot move from s=1, t=0 to s=-1, t=1 without touching part 'post'." "$work/bar-apart.out" \
  || fail "certify --claim apart (pin-slot): not the statement: $(cat "$work/bar-apart.out")"
out=$("$verify" "$work/bar-apart.json" "$bar") || fail "hipair-verify refuses the pin-slot apart certificate: $out"
case "$out" in "valid: sliced_apart: part 'bar' cannot move from s=1, t=0 to s=-1, t=1 without touching 'post'"*) ;;
  *) fail "hipair-verify (pin-slot): not the summary: $out" ;; esac
mutate_bar() { mutate_certificate "$work/bar-apart.json" sliced_apart "$bar" "$@"; }
mutate_bar bar-same-component 'body["b"]["tangent"] = "1/50"; body["b"]["slide"] = "1"; c["statement"] = c["statement"].replace("s=-1, t=1 without", "s=1, t=1/50 without")' \
  "a and b lie in one component"
mutate_bar bar-face-opened 'body["domain"]["slide"] = ["-1", "2"]' "touches the domain's boundary"
mutate_bar bar-fixed-position 'body["a_other"] = {"tangent": "0"}; body["b_other"] = {"tangent": "0"}' \
  "the domain needs the other part's range"
mutate_bar bar-mark 'body["tree"] = "x" + body["tree"][1:]' "is not q, s, u, o or b"
expect_refused_bar() { expect_refused_on "$bar" "$@"; }   # NAME MESSAGE ARGS...
expect_refused_bar bar-no-to "--claim apart needs --to bar=SLIDE,ANGLE" --claim apart --at bar=0,0
expect_refused_bar bar-bad-to "--to expects bar=SLIDE,ANGLE" --claim apart --to bar=0
"$hipair" certify "$bar" --claim apart --to bar=0,1 --to bar=0,2 --out "$work/bar-twice.json" >"$work/bar-twice.out" 2>&1
status=$?
[ $status -eq 114 ] || fail "bar-twice: exit $status, not 114 (a repeated --to target): $(cat "$work/bar-twice.out")"
grep -qF -- "--to: part 'bar' is given twice" "$work/bar-twice.out" || fail "bar-twice: $(cat "$work/bar-twice.out")"
[ ! -e "$work/bar-twice.json" ] || fail "bar-twice: a certificate was written"

# The issue's "one 0.01 mm too large is not [connected]": the 10 mm peg in a 14.14 mm hole
# (0.0021 mm under 10 sqrt 2) cannot turn a quarter. Its certificate (30 585 boxes, 50 s to
# produce, too slow for a test) is committed, made by
#   hipair certify tests/data/sliced-apart/peg-in-hole-14.14.json --claim apart --at peg=0,0,0 \
#     --to peg=0,0,90deg --out tests/data/sliced-apart/peg-14.14-quarter-turn-apart.json
# hipair-verify accepts it (1.5 s) and refuses it for the 14.15 mm hole, where the turn is possible.
data="$source/tests/data/sliced-apart"
out=$("$verify" "$data/peg-14.14-quarter-turn-apart.json" "$data/peg-in-hole-14.14.json") \
  || fail "hipair-verify refuses the 14.14 mm hole's apart certificate: $out"
case "$out" in "valid: sliced_apart: part 'peg' cannot move from x=0, y=0, t=0 to x=0, y=0, t=1 without touching 'plate'"*) ;;
  *) fail "the 14.14 mm hole: not the summary: $out" ;; esac
sed 's/"hole-side": { "nominal": 14.14 }/"hole-side": { "nominal": 14.15 }/' "$data/peg-in-hole-14.14.json" >"$work/peg-14.15.json"
grep -q '"nominal": 14.15' "$work/peg-14.15.json" || fail "the 14.15 mm model was not made"
out=$("$verify" "$data/peg-14.14-quarter-turn-apart.json" "$work/peg-14.15.json")
[ $? -eq 1 ] || fail "the 14.14 mm certificate against the 14.15 mm hole: not invalid: $out"
case "$out" in "invalid: model hash mismatch"*) ;; *) fail "the 14.14 mm certificate against the 14.15 mm hole: $out" ;; esac

[ $failures -eq 0 ] && echo "certify apart CLI tests passed"
exit $((failures > 0))
