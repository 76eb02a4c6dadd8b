#!/usr/bin/env python3
"""Are a spur gear's tooth placements exactly periodic? (docs/performance.md, Session 66 (gear66))

Replays the model's rounding of each tooth axis (src/model/templates_gears.cpp `direction`,
src/model/exact_trig.cpp `unit_small_angle`: the simplest rational half-angle tangent strictly
inside tan((a -+ B) / 2), B the rounding bound 1e-12, the angle reduced modulo pi) in exact
fractions with 300-bit mpmath ends, and reports for each tooth count whether turn[k] is exactly
turn[k-1] * turn[1], the spread of the angle errors, and how far turn[1]^z misses the identity.
A developer's tool, not a test.  usage: gear_tooth_periodicity.py [Z ...]
"""
import sys
from fractions import Fraction as F

import mpmath as mp

mp.mp.prec = 300
BOUND = mp.mpf(10) ** -12


def simplest_between(lo, hi):
    """The simplest rational in the open interval (lo, hi), lo < hi (continued fractions)."""
    if lo < 0 < hi:
        return F(0)
    if hi <= 0:
        return -simplest_between(-hi, -lo)
    floor = lo.numerator // lo.denominator
    if floor + 1 < hi:
        return F(floor + 1)
    return floor + 1 / simplest_between(1 / (hi - floor), 1 / (lo - floor))


def exact(x):
    mantissa, exponent = mp.frexp(x)
    return F(int(mp.ldexp(mantissa, 300))) * F(2) ** (exponent - 300)


def turn(k, z):
    a = 2 * mp.pi * k / z
    reduced = a - mp.pi * mp.nint(a / mp.pi)
    turns = int(mp.nint((a - reduced) / mp.pi))
    margin = F(1, 2**240)
    t = simplest_between(exact(mp.tan((reduced - BOUND) / 2)) + margin, exact(mp.tan((reduced + BOUND) / 2)) - margin)
    x, y = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
    return (t, (-x, -y) if turns % 2 else (x, y))


def times(u, v):
    return (u[0] * v[0] - u[1] * v[1], u[0] * v[1] + u[1] * v[0])


def angle(u):
    return mp.atan2(mp.mpf(u[1].numerator) / u[1].denominator, mp.mpf(u[0].numerator) / u[0].denominator)


for z in [int(a) for a in sys.argv[1:]] or [7, 8, 18, 19, 27, 40]:
    turns = [turn(k, z) for k in range(z)]
    errors = []
    for k, (_, u) in enumerate(turns):
        e = angle(u) - 2 * mp.pi * k / z
        errors.append(e - 2 * mp.pi * mp.nint(e / (2 * mp.pi)))
    step = turns[1][1]
    not_periodic = sum(1 for k in range(2, z) if times(turns[k - 1][1], step) != turns[k][1])
    power = (F(1), F(0))
    for _ in range(z):
        power = times(power, step)
    print(f"z={z}: turn[k] != turn[k-1]*turn[1] for {not_periodic} of {z - 2} k >= 2; angle errors in "
          f"[{mp.nstr(min(errors), 3)}, {mp.nstr(max(errors), 3)}] rad; half-angle tangents' denominators <= "
          f"{max(t.denominator.bit_length() for t, _ in turns)} bits; turn[1]^z misses the identity by "
          f"{mp.nstr(angle(power), 3)} rad, its denominators {power[0].denominator.bit_length()} bits")
