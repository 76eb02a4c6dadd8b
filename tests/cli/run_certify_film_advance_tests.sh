#!/usr/bin/env bash
# `hipair certify --claim connected` on a pin-in-slot pair (session 71): the film advance's claw
# (examples/models/film-advance.json: the follower on its pin, 2 degrees in, s = 4.2, in the
# perforation of the film at offset 0.24) retracts and the film advances one frame (-7.56):
# certified, verified, byte-identical to examples/certificates/film-advance-claw-connected.json
# (which is verified as committed), and the committed certificate of the claw moving on to the next
# perforation (examples/certificates/film-advance-claw-next-perforation.json) verified. Mutations rejected with their reasons: the film moved with the
# claw in its perforation, two coordinates at once, detours beyond the film's, the slide's and the
# angle's limits, and generated detours of the film by 1 to 4.8 mm with the claw in (each passes a
# configuration that `certify --claim interference` certifies overlapping: an oracle of its own).
# Bad input exits 2 naming the option, nothing written.
# usage: run_certify_film_advance_tests.sh HIPAIR_BINARY HIPAIR_VERIFY_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
source "$(dirname "$0")/seeded_verify_test.sh" "$@"

model="$work/film-advance.json"
cp "$source/examples/models/film-advance.json" "$model"
example="$source/examples/certificates/film-advance-claw-connected.json"
statement="Part 'follower' moves from s=21/5, t=3491012985643517/200000000000000000 ('film' at offset 6/25) to s=21/5, t=0 ('film' at offset -189/25) without touching part 'film'."
"$hipair" certify "$model" --claim connected --pair film:follower --at follower=4.2,2deg --at film=0.24 \
  --to follower=4.2,0 --to film=-7.56 --out "$work/claw.json" >"$work/claw.out" 2>&1 \
  || fail "certify --claim connected refuses the claw's retraction: $(cat "$work/claw.out")"
grep -qF "certified sliced_connected: $statement" "$work/claw.out" || fail "certify --claim connected: not the statement: $(cat "$work/claw.out")"
cmp -s "$work/claw.json" "$example" || fail "the certificate differs from $example: $(diff "$work/claw.json" "$example" | head -5)"
for certificate in "$work/claw.json" "$example"; do
  out=$("$verify" "$certificate" "$source/examples/models/film-advance.json") || fail "hipair-verify refuses $certificate: $out"
  case "$out" in "valid: sliced_connected: part 'follower' moves from s=21/5"*"without touching 'film' (2 steps, 2 moves proved free"*) ;;
    *) fail "hipair-verify: not the summary: $out" ;; esac
done

# the claw from its perforation to the next (retract, advance, re-enter: the producer's box search,
# about 90 s of CPU, so the committed certificate is verified, not produced here), and it
# without its steps between the ends (the film moved with the claw in)
next="$source/examples/certificates/film-advance-claw-next-perforation.json"
out=$("$verify" "$next" "$source/examples/models/film-advance.json") || fail "hipair-verify refuses $next: $out"
case "$out" in "valid: sliced_connected: part 'follower' moves from s=21/5"*"('film' at offset -189/25) without touching 'film' (144 steps"*) ;;
  *) fail "hipair-verify: not the summary of the next perforation: $out" ;; esac
mutate_certificate "$next" sliced_connected "$model" next-direct 'body["steps"] = [body["steps"][0], body["steps"][-1]]' "move 0 (q=6/25, s=21/5"

mutate() { mutate_certificate "$work/claw.json" sliced_connected "$model" "$@"; }   # NAME PYTHON-STATEMENTS MESSAGE
restate='c["statement"] = c["statement"].replace("to s=21/5, t=0 (", "to s=21/5, t=" + body["to"]["tangent"] + " (")'
mutate claw-in "body[\"to\"][\"tangent\"] = body[\"from\"][\"tangent\"]; body[\"steps\"] = [body[\"steps\"][0], [\"-189/25\", \"21/5\", body[\"from\"][\"tangent\"]]]; $restate" \
  "move 0 (q=6/25, s=21/5"
mutate two-at-once 'body["steps"] = [body["steps"][0], body["steps"][-1]]' "it changes two coordinates at once"
detour() {   # NAME AXIS VALUE MESSAGE: from the first step to VALUE along AXIS (0 q, 1 s, 2 u) and back
  mutate "$1" "s = list(body[\"steps\"][0]); s[$2] = \"$3\"; body[\"steps\"][1:1] = [s, body[\"steps\"][0]]" "$4"
}
detour film-beyond 0 6 "the offset of 'film' (q in [6/25, 6]) leaves its limits"
detour slide-beyond 1 7 "the slide of 'follower' (s in [21/5, 7]) leaves its limits"
detour angle-beyond 2 1/10 "the angle of 'follower' (u in ["
# generated: the film moved by d in [1, 4.8] mm either way with the claw in its 3 mm perforation (the
# claw is 2 mm thick): the detour passes the film's solid part, certified overlapping at 2.6 mm
for k in 1 2 3 4; do
  d=$(python3 -c "import random; random.seed($seed * 10 + $k); print(random.choice([-1, 1]) * random.randint(100, 480) / 100)")
  over=$(python3 -c "d = $d; print(0.24 + (2.6 if d > 0 else -2.6) if abs(d) >= 2.6 else 0.24 + d)")
  if [ "$(python3 -c "print(abs($d) >= 2.6)")" = True ]; then
    "$hipair" certify "$model" --claim interference --pair film:follower --at follower=4.2,2deg --at film="$over" \
      --out "$work/over-$k.json" >"$work/over-$k.out" 2>&1 || fail "detour $d: the film at $over does not overlap the claw: $(cat "$work/over-$k.out")"
  fi
  q=$(python3 -c "from fractions import Fraction as F; print(F('6/25') + F('$d'))")
  detour "film-detour-$k" 0 "$q" "move 0 (q=6/25, s=21/5"
done

# bad input: exit 2, one message naming the option, nothing written
expect_refused() {   # NAME MESSAGE ARGS...
  local name=$1 message=$2
  shift 2
  "$hipair" certify "$model" --pair film:follower "$@" --out "$work/$name.json" >"$work/$name.out" 2>&1
  local status=$?
  [ $status -eq 2 ] || fail "$name: exit $status, not 2: $(cat "$work/$name.out")"
  [ ! -e "$work/$name.json" ] || fail "$name: a certificate was written"
  grep -qF -- "$message" "$work/$name.out" || fail "$name: not '$message': $(cat "$work/$name.out")"
}
expect_refused refused-no-to "--claim connected needs --to follower=SLIDE,ANGLE and --to film=VALUE" --claim connected --at follower=4.2,0
expect_refused refused-slide "the slide of 'follower' (7) is outside its limits" --claim connected --at follower=7,0 --to follower=4.2,0 --to film=0
expect_refused refused-bad-to "--to expects follower=SLIDE,ANGLE" --claim connected --to follower=4.2 --to film=0

[ $failures -eq 0 ] && echo "certify film advance CLI tests passed"
exit $((failures > 0))
