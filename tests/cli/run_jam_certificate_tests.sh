#!/usr/bin/env bash
# Session 75 (jamcert75): `hipair analyze --out` of a small rotating pair that jams must finish
# in about the analysis's time and write a jam certificate hipair-verify accepts, whose trap
# holds the jam the report locates. Until session 75 the certificate's search started with a
# driver grid point on the located jam itself: the trap's cut was the closing, where the parts
# barely overlap, and its cover ran for minutes (hostile75 M2: > 110 s where the analysis takes
# 0.2 s), without bound.
# Generated cases: hostile75's cvx-style rotating pairs (tests/cli/jam_certificate_pairs.py,
# seeded: two parts of random convex integer loops turning about integer pivots): generator seeds
# 57 and 73 (the two hostile75 found) and 9, 24, 33 (a jam 0.28 deg from the start), of the 12 of
# 0..40 whose analysis jams as its free range closes (all 12 pass; 4 kept: the test's cost).
# Oracles: hipair-verify (valid), the trap's driver interval [lo, hi] (free start at lo, the motion
# cannot pass hi) holds the report's certified jam interval, and each run ends within a timeout
# of more than 10x its measured time (at most 1.2 s of CPU, 3 s wall under load; 30 s). A jam no search certifies (seed 17:
# `certify --claim jam` cannot either) must say "not certified: jam ..." after the bounded search.
# usage: run_jam_certificate_tests.sh HIPAIR HIPAIR_VERIFY WORK_DIR
set -uo pipefail
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
hipair=$1 verify=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

for seed in 57 73 9 24 33 17; do
  model="$work/rr-$seed.json" out="$work/out-$seed"
  python3 "$here/jam_certificate_pairs.py" "$seed" "$model"
  timeout 30 "$hipair" analyze "$model" --driver a --no-pictures --out "$out" >"$work/stdout-$seed" 2>"$work/stderr-$seed"
  rc=$?
  if [ "$rc" -ne 0 ]; then fail "seed $seed: analyze --out exit $rc: $(head -c 300 "$work/stderr-$seed")"; continue; fi
  stdout=$(cat "$work/stdout-$seed")
  if ! grep -q "BLOCKED at" <<<"$stdout"; then fail "seed $seed: the analysis no longer jams"; continue; fi
  jam=""
  for certificate in "$out"/certificate-*.json; do
    [ -e "$certificate" ] || continue
    grep -q '"claim": "jam"' "$certificate" && jam=$certificate
  done
  if [ "$seed" = 17 ]; then
    grep -q "^not certified: jam: " <<<"$stdout" || fail "seed $seed: no jam certificate and no 'not certified: jam' line"
    continue
  fi
  if [ -z "$jam" ]; then fail "seed $seed: no jam certificate written: $(grep 'not certified' <<<"$stdout")"; continue; fi
  verdict=$("$verify" "$jam" "$model" 2>&1)
  grep -q "^valid: jam" <<<"$verdict" || { fail "seed $seed: hipair-verify: $(head -c 300 <<<"$verdict")"; continue; }
  # the report's certified jam interval (degrees, doubles: within a few ulps of 360, 1e-13 deg)
  # lies in the trap's driver interval (exact rationals, rad)
  python3 - "$out/report.json" "$jam" <<'PY' || fail "seed $seed: the report's jam lies outside the certificate's trap"
import json, sys
from fractions import Fraction as F
from decimal import Decimal, getcontext
getcontext().prec = 50
PI = Decimal('3.14159265358979323846264338327950288419716939937510582')
report, certificate = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
lo_deg, hi_deg = report['blocked']['at']['certified']
ulps = Decimal('1e-13')
lo = (Decimal(repr(lo_deg)) - ulps) * PI / 180
hi = (Decimal(repr(hi_deg)) + ulps) * PI / 180
trap = [F(v) for v in certificate['jam']['trap']['driver']]
inside = trap[0] <= F(lo) and F(hi) <= trap[1]
print('jam [%s, %s] rad, trap [%s, %s]' % (lo, hi, float(trap[0]), float(trap[1])))
sys.exit(0 if inside else 1)
PY
done
if [ "$failures" -ne 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "jam certificates of analyze --out: all passed"
