#!/usr/bin/env bash
# Produces the valid base certificates of the corpus with `hipair certify`.
# usage: make_bases.sh HIPAIR_CLI SOURCE_DIR OUT_DIR
set -eu
hipair=$1; models=$2/examples/models; out=$3
mkdir -p "$out"
"$hipair" certify "$models/lever-stop.json" --claim interference --at lever=30deg --out "$out/lever-interference.json"
"$hipair" certify "$models/lever-stop.json" --claim clearance --out "$out/lever-clearance.json"
"$hipair" certify "$models/lever-stop.json" --claim free --from -0.5 --to 0.02 --out "$out/lever-free.json"
"$hipair" certify "$models/lever-stop.json" --claim jam --out "$out/lever-jam.json"
"$hipair" certify "$models/ratchet.json" --claim jam --direction -1 --out "$out/ratchet-jam.json"
"$hipair" certify "$models/geneva.json" --claim interference --at driver=1.2 --at wheel=0.3 --out "$out/geneva-interference.json"
"$hipair" certify "$models/cam-follower.json" --claim free --pair follower:guide --from -2 --to 3 --out "$out/follower-guide-free.json"
"$hipair" certify "$models/peg-in-hole.json" --claim clearance --out "$out/peg-planar-clearance.json"
"$hipair" certify "$models/peg-in-hole.json" --claim interference --at peg=2,0,10deg --out "$out/peg-planar-interference.json"
"$hipair" certify "$models/film-advance.json" --claim clearance --pair cam:follower --out "$out/film-cam-clearance.json"
"$hipair" certify "$models/film-advance.json" --claim clearance --pair pin:follower --at follower=-2,-3deg --out "$out/film-pin-clearance.json"
"$hipair" certify "$models/film-advance.json" --claim interference --pair film:follower --at film=0 --at follower=4,5deg --out "$out/film-claw-interference.json"
# Gear pairs (arcs-only involute flanks; session 45): the spur gears apart at their initial
# configuration, overlapping with the pinion turned 0.05 rad, and free over 0.05 rad of the pinion
# with the gear following at the tooth ratio -18/27.
"$hipair" certify "$models/spur-gears.json" --claim clearance --at pinion=0 --at gear=0 --out "$out/spur-clearance.json"
"$hipair" certify "$models/spur-gears.json" --claim interference --at pinion=0.05 --at gear=0 --out "$out/spur-interference.json"
"$hipair" certify "$models/spur-gears.json" --claim free --driver pinion --from 0 --to 0.05 --ratio -2/3 --out "$out/spur-free.json"
# Tolerance certificates (`hipair tolerance`, docs/certify.md "Tolerance"): no jam of the Geneva
# over the pin's entry at 2 x the declared tolerances, and never interferes with the wheel held
# at 0 while the pin enters slot 1's mouth.
tmp=$(mktemp -d)
"$hipair" tolerance "$models/geneva.json" --range 2.2:2.3 --positions 720 --accuracy 0.5 --certify --certify-scale 2 \
  --quiet --out "$tmp/nojam" > /dev/null
cp "$tmp/nojam/tolerance-certificate.json" "$out/geneva-tolerance-no-jam.json"
# ... and at 0.9 x the jamming threshold (x 8.484 on this range): leaves proved by the
# second-order witness test (docs/certify.md "Tolerance", check 6).
"$hipair" tolerance "$models/geneva.json" --range 2.2:2.3 --positions 720 --accuracy 0.5 --certify \
  --certify-scale 1527/200 --quiet --out "$tmp/nojam09" > /dev/null
cp "$tmp/nojam09/tolerance-certificate.json" "$out/geneva-tolerance-no-jam-0.9-threshold.json"
# ... and at 4 x with leaves whose witness paths check 7 proves free (--certify-free-path, session 17):
# valid, where the plain search's 4 x certificate is unproven (its path meets the wheel's lock arc).
"$hipair" tolerance "$models/geneva.json" --range 2.2:2.3 --positions 720 --accuracy 0.5 --certify \
  --certify-scale 4 --certify-free-path --quiet --out "$tmp/nojam4f" > /dev/null
cp "$tmp/nojam4f/tolerance-certificate.json" "$out/geneva-tolerance-no-jam-4x-free-path.json"
"$hipair" tolerance "$models/geneva.json" --certify-interference --pair driver:wheel --range 1:2.4 --follower-range 0 \
  --quiet --out "$tmp/noint" > /dev/null
cp "$tmp/noint/interference-certificate.json" "$out/geneva-tolerance-no-interference.json"
rm -rf "$tmp"
