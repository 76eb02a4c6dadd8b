#!/usr/bin/env python3
"""The certified tolerance band against the exact expansion of the model at parameter vectors.

usage: tolerance_band_oracle.py HIPAIR MODEL WORKDIR [--pair D:F] [--positions N] [--vectors K]
                                [--seed S] [--chain] [--scale E] [--factor F]

`hipair tolerance MODEL --positions N` gives the certified band (variation.csv: certified_lower,
certified_upper at each driver position in contact). The oracle is independent of the tolerance
code: K parameter vectors (the box's corners first, in random order, then random decimal points
inside the box) are each written into a copy of the model as the parameters' nominal values (exact
decimal literals, tolerances removed), so the reader expands every feature template exactly at
those values, and `hipair analyze --steps N --no-reversal` of that model gives the follower's
position at the same driver positions. Each must lie in the certified band at every position in
contact, within the printed precision (analyze prints 9 decimals of a degree, the band 12
significant digits, and analyze's grid angle differs from the band's by its rational rounding,
< 1e-10 rad: slack 2e-9 rad). A position outside is printed with the vector; exit 1.
--factor F: the vectors F times as far from the nominal (a self-test: F = 3 must fail).
--scale E: the model scaled by 10^E first (tests/fuzz/scale_model.py); lengths of the vectors
scale with it (the band of an angle follower is the same).
"""
import csv
import json
import math
import os
import random
import subprocess
import sys
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems  # noqa: E402

SLACK = 2e-9


def decimal(value):
    """an exact decimal literal of a Fraction whose denominator divides a power of 10"""
    sign = '-' if value < 0 else ''
    value = abs(value)
    digits = 0
    while (value * 10 ** digits).denominator != 1:
        digits += 1
        if digits > 60:
            raise ValueError('not a decimal: %s' % value)
    n = (value * 10 ** digits).numerator
    if digits == 0:
        return sign + str(n)
    s = str(n).rjust(digits + 1, '0')
    return sign + s[:-digits] + '.' + s[-digits:]


def literal(x):
    """the exact value of a JSON number as the model text wrote it (json parsed floats: use repr)"""
    return Fraction(repr(x)) if isinstance(x, float) else Fraction(x)


def toleranced(model):
    """[(name, nominal, lo, hi)] of the parameters with a numeric nominal and a tolerance"""
    out = []
    for name, p in model.get('parameters', {}).items():
        if not isinstance(p, dict) or 'tolerance' not in p or isinstance(p.get('nominal'), str):
            continue
        nominal = literal(p['nominal'])
        t = p['tolerance']
        if isinstance(t, list):
            lo, hi = nominal + literal(t[0]), nominal + literal(t[1])
        else:
            lo, hi = nominal - literal(t), nominal + literal(t)
        if lo != hi:
            out.append((name, nominal, lo, hi))
    return out


def vectors(params, count, rng):
    n = len(params)
    corners = []
    if n <= 12:
        corners = [[(i >> k) & 1 for k in range(n)] for i in range(2 ** n)]
        rng.shuffle(corners)
    else:
        corners = [[rng.randint(0, 1) for _ in range(n)] for _ in range(count)]
    out = []
    for c in corners[:max(1, count // 2)]:
        out.append([hi if bit else lo for (_, _, lo, hi), bit in zip(params, c)])
    while len(out) < count:
        out.append([lo + Fraction(rng.randint(0, 1000), 1000) * (hi - lo) for (_, _, lo, hi) in params])
    return out


def read_band(path):
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            if r['contact']:
                rows.append((float(r['driver']), float(r['certified_lower']), float(r['certified_upper'])))
    return rows


def main(argv):
    if len(argv) < 4:
        print(__doc__)
        return 2
    hipair, model_path, work = argv[1], argv[2], argv[3]
    opts = {'--factor': '1', '--pair': None, '--positions': '72', '--vectors': '12', '--seed': '1', '--scale': None}
    chain = '--chain' in argv
    rest = [a for a in argv[4:] if a != '--chain']
    for k, v in zip(rest[::2], rest[1::2]):
        opts[k] = v
    os.makedirs(work, exist_ok=True)
    if opts['--scale']:
        scaled = os.path.join(work, 'scaled.json')
        subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'scale_model.py'),
                        model_path, '1e' + opts['--scale'], scaled], check=True)
        model_path = scaled
    model = json.load(open(model_path))
    params = toleranced(model)
    band_dir = os.path.join(work, 'band')
    args = [hipair, 'tolerance', model_path, '--positions', opts['--positions'], '--threads', '1', '--quiet', '--out', band_dir]
    if opts['--pair']:
        args += ['--pair', opts['--pair']]
    if chain:
        args.append('--chain')
    rc, so, se = run(args, 600)
    if rc != 0 or crash_problems(rc, so + se):
        print('tolerance failed (exit %s): %s' % (rc, se.strip()[-400:]))
        return 1
    band = read_band(os.path.join(band_dir, 'variation.csv'))
    report = json.load(open(os.path.join(band_dir, 'tolerance.json')))
    driver, follower = report.get('driver'), report.get('follower')
    if not band:
        print('no position in contact')
        return 1
    rng = random.Random(int(opts['--seed']))
    with open(os.path.join(band_dir, 'variation.csv')) as f:
        grid = [float(r['driver']) for r in csv.DictReader(f)]
    first, last = grid[0], grid[-1]
    rotating = [p for p in model['parts'] if p['name'] == driver][0]['motion'] != 'fixed' and \
        'rotation' in [p for p in model['parts'] if p['name'] == driver][0]['motion']
    failures = 0
    checked = 0
    factor = Fraction(opts['--factor'])
    for index, vector in enumerate(vectors(params, int(opts['--vectors']), rng)):
        vector = [n + factor * (v - n) for (_, n, _, _), v in zip(params, vector)]
        m = json.loads(json.dumps(model))
        # the pair alone (as the tolerance analysis takes it), driven the band's way over its range
        m['pairs'] = [p for p in m.get('pairs', []) if set(p.get('parts', [])) == {driver, follower}] or \
            [{'parts': [driver, follower]}]
        m.pop('simulation', None)
        for (name, _, _, _), value in zip(params, vector):
            p = m['parameters'][name]
            p.pop('tolerance', None)
            p['nominal'] = '__EXACT__%s__' % decimal(value)
        text = json.dumps(m, indent=1)
        for (name, _, _, _), value in zip(params, vector):
            text = text.replace('"__EXACT__%s__"' % decimal(value), decimal(value))
        path = os.path.join(work, 'vector%d.json' % index)
        open(path, 'w').write(text)
        out = os.path.join(work, 'analyze%d' % index)
        args = [hipair, 'analyze', path, '--steps', opts['--positions'], '--no-reversal', '--quiet', '--out', out,
                '--driver', driver, '--direction', 'ccw' if rotating else '+',
                '--range=%.15g%s:%.15g%s' % (first, 'rad' if rotating else '', last, 'rad' if rotating else '')]
        rc, so, se = run(args, 600)
        if rc != 0 or crash_problems(rc, so + se):
            print('vector %d: analyze failed (exit %s): %s' % (index, rc, se.strip()[-300:]))
            failures += 1
            continue
        with open(os.path.join(out, 'kinematics.csv')) as f:
            rows = list(csv.DictReader(f))
        dcol = [c for c in rows[0] if c.startswith('driver_')][0]
        fcol = [c for c in rows[0] if c.startswith(follower + '_') and not any(
            c.endswith(s) for s in ('_velocity_ratio', '_play_deg', '_play_mm', '_play_rad', '_contacts'))][0]
        unit = math.pi / 180 if dcol.endswith('_deg') else 1.0
        funit = math.pi / 180 if fcol.endswith('_deg') else 1.0
        positions = [(float(r[dcol]) * unit, float(r[fcol]) * funit) for r in rows]
        bad = []
        for d, lo, hi in band:
            near = min(positions, key=lambda p: abs(p[0] - d))
            if abs(near[0] - d) > 1e-6:
                continue
            f = near[1]
            # the follower's angle modulo a turn, nearest the band
            if funit != 1.0 or fcol.endswith('_rad'):
                f += 2 * math.pi * round(((lo + hi) / 2 - f) / (2 * math.pi))
            checked += 1
            if not (lo - SLACK <= f <= hi + SLACK):
                bad.append((d, f, lo, hi))
        if bad:
            failures += 1
            d, f, lo, hi = max(bad, key=lambda b: max(b[2] - b[1], b[1] - b[3]))
            print('vector %d (%s): %d positions outside the certified band, worst at driver %.9g: %.12g not in [%.12g, %.12g]'
                  % (index, ', '.join('%s=%s' % (p[0], decimal(v)) for p, v in zip(params, vector)), len(bad), d, f, lo, hi))
    print('%s: %d parameters, %d vectors, %d positions checked against the certified band, %d failing vectors'
          % (os.path.basename(model_path), len(params), int(opts['--vectors']), checked, failures))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
