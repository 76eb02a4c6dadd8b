#!/usr/bin/env python3
"""Session-57 hunt (hunt57) on 3-DOF pairs: `hipair cspace --json` of generated polygonal pairs (a
plate with a hole, a peg free in the plane) judged by an exact oracle of this script's own.

usage: sliced_oracle_hunt.py HIPAIR WORKDIR [--quick]
(--quick: the ctest `sliced_oracle_hunt`, six builds: the peg of side 10 in holes of side 12 and
10 about its centre, in 12 with its pivot 10^6 mm away, in the hole 10^-9 wider about its centre
and 10^6 mm away (session 58: 12 components for 5 and 32 critical angles for 28 there), and the
peg in the slot 10^6 mm away.)

Each generated model is written with literal rationals, its C-space built by `hipair cspace MODEL
--json`, and the JSON checked:
  * every free cell's sample, at its slice's representative angle, is free: the parts' closed sets
    are disjoint (exact, fractions; tests/fuzz/exact_planar.py's tests, no library code);
  * every crossing's witnesses are free, and so is the certified motion between them at 17
    rational points in between (a necessary condition of "certified free"): the straight motion of
    the chart (the offset moving linearly with the half-angle tangent: a pure rotation when the two
    offsets are equal, as about a pivot on the part; about a far pivot the chord between the two
    ends of a turn about the part's centre, session 58);
  * the critical angles are in increasing order of t, every representative lies strictly between
    its interval's two critical angles (exact interval bounds), each slice's free cells have
    component numbers below `components`;
  * the component count is the closed form of the family:
      square peg of side s in a square hole of side h:  h <= s: 1 (the hole holds no free
      configuration; touching is not free), s < h < s sqrt 2: 5 (one outside, one in the hole per
      fitting orientation), h > s sqrt 2: 2 (the peg turns in the hole);
      rectangle of width p and length 12 in two chambers joined by a slot of width w through a wall
      4 mm thick: p < w: 2 (the chambers connect, the peg turned upright), p >= w: 3;
  * the same count and the same critical angles (exact strings) whatever the free part's pivot
    (the pivot is a choice of coordinates: the slice at theta about P is the slice about P0
    translated by (I - R)(P - P0)): the peg's centre, 10^6 mm, 10^30 mm and 10^400 mm away, and
    (session 59) at (-10^6, -7 10^5) and (1234567.89, -98765.4321)
    (session 57: 9 components for 5 from 10^6 mm, 2 320 critical angles for 12 at 10^12 mm, no
    answer within 2 minutes at 10^400 mm);
  * the same count and critical angles for the model scaled by 10^-300 and 10^400
    (tests/fuzz/scale_model.py).
Exit 0 when every check passed, 1 with one line per finding.
"""
import json
import os
import subprocess
import sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import report_findings  # noqa: E402
from exact_planar import cross, sub, segments_meet  # noqa: E402
from hunt_common import run, crash_problems  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


# ------------------------------------------------------------------ exact oracle (polygons)

def rotation(t, half_turn=False):
    if half_turn:
        return F(-1), F(0)
    d = 1 + t * t
    return (1 - t * t) / d, 2 * t / d


def posed_loops(loops, pivot, t, x, y, half_turn=False):
    c, s = rotation(t, half_turn)
    px, py = pivot
    return [[(px + c * (p[0] - px) - s * (p[1] - py) + x, py + s * (p[0] - px) + c * (p[1] - py) + y) for p in loop]
            for loop in loops]


def inside_even_odd(loops, p):
    """strictly inside the even-odd region of the loops, or 'boundary'"""
    px, py = p
    inside = False
    for loop in loops:
        n = len(loop)
        for i in range(n):
            a, b = loop[i], loop[(i + 1) % n]
            if cross(sub(b, a), sub(p, a)) == 0 and min(a[0], b[0]) <= px <= max(a[0], b[0]) and \
                    min(a[1], b[1]) <= py <= max(a[1], b[1]):
                return 'boundary'
            if (a[1] > py) != (b[1] > py):
                xi = a[0] + (py - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
                if xi > px:
                    inside = not inside
    return inside


def apart(fixed_loops, free_loops):
    """the two closed regions are disjoint (exact)"""
    for la in fixed_loops:
        for lb in free_loops:
            for i in range(len(la)):
                for j in range(len(lb)):
                    if segments_meet(la[i], la[(i + 1) % len(la)], lb[j], lb[(j + 1) % len(lb)]):
                        return False
    # boundaries disjoint: one region inside the other only if a loop's vertex is inside
    for lb in free_loops:
        if inside_even_odd(fixed_loops, lb[0]) is not False:
            return False
    for la in fixed_loops:
        if inside_even_odd(free_loops, la[0]) is not False:
            return False
    return True


# ------------------------------------------------------------------ generated models

def lit(v):
    v = F(v)
    return str(v.numerator) if v.denominator == 1 else '%d/%d' % (v.numerator, v.denominator)


def loop_json(points, label):
    return {'label': label, 'start': [lit(points[0][0]), lit(points[0][1])],
            'edges': [{'line_to': [lit(p[0]), lit(p[1])]} for p in points[1:] + points[:1]]}


def model_json(name, plate, peg, pivot):
    return {'hipair': 1, 'name': name, 'units': {'length': 'mm', 'angle': 'deg'},
            'parts': [{'name': 'plate', 'motion': 'fixed',
                       'loops': [loop_json(l, 'plate %d' % i) for i, l in enumerate(plate)]},
                      {'name': 'peg', 'motion': {'planar': {'pivot': [pivot[0], pivot[1]]}},
                       'loops': [loop_json(l, 'peg %d' % i) for i, l in enumerate(peg)]}],
            'pairs': [{'parts': ['plate', 'peg']}]}


def square(h, cx=F(0), cy=F(0)):
    h = F(h) / 2
    return [(cx - h, cy - h), (cx + h, cy - h), (cx + h, cy + h), (cx - h, cy + h)]


def peg_in_hole(s, h):
    plate = [square(max(F(18), F(h) + 6)), square(h)]
    return plate, [square(s)]


def peg_in_slot(p, w):
    w2 = F(w) / 2
    plate = [[(F(-15), F(-25)), (F(15), F(-25)), (F(15), F(25)), (F(-15), F(25))],
             [(F(-10), F(-20)), (F(10), F(-20)), (F(10), F(-2)), (w2, F(-2)), (w2, F(2)), (F(10), F(2)),
              (F(10), F(20)), (F(-10), F(20)), (F(-10), F(2)), (-w2, F(2)), (-w2, F(-2)), (F(-10), F(-2))]]
    p2 = F(p) / 2
    peg = [[(F(-6), -11 - p2), (F(6), -11 - p2), (F(6), -11 + p2), (F(-6), -11 + p2)]]
    return plate, peg


# ------------------------------------------------------------------ checks of one JSON

def t_of(side):
    return None if side.get('half_turn') else F(side['t'])


def bounds(c):
    """exact rational bounds of a critical angle's t (a rational one: itself)"""
    if 'interval' in c['t']:
        return tuple(F(v) for v in c['t']['interval'])
    return F(c['t']['exact']), F(c['t']['exact'])


def critical_key(c):
    """a critical angle as its polynomial (or rational) and its rank among that polynomial's roots"""
    return 'pi' if c['half_turn'] else c['t']['exact'].split(', t in')[0]


def check_json(label, d, plate, peg, pivot, expected_components, findings, rotations=17):
    def free_at(x, y, t, half_turn=False):
        return apart(plate, posed_loops(peg, pivot, t, x, y, half_turn))

    critical = d['critical_angles']
    ts = [c for c in critical if not c['half_turn']]
    for a, b in zip(ts, ts[1:]):
        if bounds(a)[0] >= bounds(b)[1]:
            findings.append('%s: critical angles %d, %d out of order' % (label, a['index'], b['index']))
    for sl in d['slices']:
        rep = sl['representative']
        t = F(rep['t']) if not rep.get('half_turn') else None
        for key in ('lower_critical', 'upper_critical'):
            k = sl.get(key)
            if k is None or t is None or critical[k]['half_turn']:
                continue
            lo, hi = bounds(critical[k])
            if lo <= t <= hi and lo != hi:
                continue   # inside the isolating interval: undecided here
            wrong = (key == 'lower_critical' and sl['index'] != 0 and t <= lo) or \
                    (key == 'upper_critical' and sl['index'] != len(d['slices']) - 1 and t >= hi) or t == lo
            if wrong:
                findings.append('%s: slice %d representative t = %s not beyond its %s (%s)' %
                                (label, sl['index'], rep['t'], key, critical[k]['t']['exact']))
        for cell in sl['free_cells']:
            if cell['component'] >= d['components']:
                findings.append('%s: slice %d cell %d component %d >= %d' %
                                (label, sl['index'], cell['index'], cell['component'], d['components']))
            x, y = F(cell['sample']['x']), F(cell['sample']['y'])
            if not free_at(x, y, t, rep.get('half_turn', False)):
                findings.append('%s: slice %d free cell %d sample (%s, %s) at t = %s is not free' %
                                (label, sl['index'], cell['index'], x, y, rep['t']))
    for cr in d['crossings']:
        for w in cr['witnesses']:
            left, right = w['left'], w['right']
            x, y = F(left['x']), F(left['y'])
            x1, y1 = F(right['x']), F(right['y'])   # (session 58: about a far pivot the ends differ)
            if w['through_half_turn']:
                # the chart about pi: u = -1/t from u(left) to u(right)
                ul = F(-1) / F(left['t']) if not left.get('half_turn') else F(0)
                ur = F(-1) / F(right['t']) if not right.get('half_turn') else F(0)
                us = [ul + (ur - ul) * k / (rotations + 1) for k in range(rotations + 2)]
                angles = [(None, True) if u == 0 else (F(-1) / u, False) for u in us]
            else:
                tl, tr = t_of(left), t_of(right)
                angles = [(tl + (tr - tl) * k / (rotations + 1), False) for k in range(rotations + 2)]
            # the straight motion of the chart: the offset moves linearly with the chart's coordinate
            for k, (t, half) in enumerate(angles):
                px, py = x + (x1 - x) * k / (rotations + 1), y + (y1 - y) * k / (rotations + 1)
                if not free_at(px, py, t, half):
                    findings.append('%s: crossing %d witness (%s, %s) not free at t = %s' %
                                    (label, cr['critical'], px, py, 'pi' if half else t))
                    break
    if expected_components is not None and d['components'] != expected_components:
        findings.append('%s: %d components, expected %d' % (label, d['components'], expected_components))


def build(hipair, path, out, findings, label, timeout=180):
    rc, so, se = run([hipair, 'cspace', path, '--json', out], timeout)
    problems = crash_problems(rc, so + se)
    if problems or rc != 0:
        findings.append('%s: cspace rc=%s %s %s' % (label, rc, problems, se.strip()[-300:]))
        return None
    with open(out) as f:
        return json.load(f)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    hipair, work = sys.argv[1], sys.argv[2]
    quick = '--quick' in sys.argv[3:]
    os.makedirs(work, exist_ok=True)
    findings = []
    cases = []
    # (label, plate, peg, expected components); the square family: s = 10
    for h, comps in ((F(12), 5), (F(10), 1), (F(10) + F(1, 10**9), 5), (F(10) - F(1, 10**9), 1),
                     (F(1414213562373095, 10**14), 5), (F(1414213562373096, 10**14), 2)):
        if quick and h not in (F(12), F(10), F(10) + F(1, 10**9)):
            continue
        plate, peg = peg_in_hole(10, h)
        cases.append(('peg-in-hole h=%s' % h, plate, peg, comps))
    for p, comps in ((F(2), 2), (F(3), 3), (F(3) - F(1, 10**9), 2), (F(3) + F(1, 10**9), 3)):
        if quick and p != F(2):
            continue
        plate, peg = peg_in_slot(p, 3)
        cases.append(('peg-in-slot p=%s' % p, plate, peg, comps))
    reference = {}
    for label, plate, peg, comps in cases:
        # the pivot: the peg's centre, then far away (the same critical angles and components)
        pivots = [('centre', None)] + [(far, far) for far in ('1e6', '1e30', '1e400')]
        # (session 59, hunt59: far pivots off the axis, in a negative direction and at odd decimals)
        pivots += [('(-1e6, -7e5)', (F(-10**6), F(-7 * 10**5))), ('(1234567.89, -98765.4321)',
                                                                   (F(123456789, 100), F(-987654321, 10**4)))]
        if quick:   # the ctest: the square family about its centre and 10^6 mm away, the slot 10^6 mm away
            pivots = {'peg-in-hole h=12': pivots[:2], 'peg-in-hole h=10': pivots[:1], 'peg-in-slot p=2': pivots[1:2],
                      'peg-in-hole h=10000000001/1000000000': pivots[:2]}[label]
        for name, far in pivots:
            xs = [p[0] for l in peg for p in l]
            ys = [p[1] for l in peg for p in l]
            centre = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
            pivot = centre if far is None else far if isinstance(far, tuple) else (F(10) ** int(far[2:]), centre[1])
            tag = '%s pivot %s' % (label, name)
            path = os.path.join(work, 'm.json')
            with open(path, 'w') as f:
                json.dump(model_json('hunt57', plate, peg, (lit(pivot[0]), lit(pivot[1]))), f)
            d = build(hipair, path, os.path.join(work, 'out.json'), findings, tag)
            if d is None:
                continue
            check_json(tag, d, plate, peg, pivot, comps, findings)
            crit = [critical_key(c) for c in d['critical_angles']]
            if label in reference and crit != reference[label]:
                findings.append('%s: critical angles %d differ from those about the centre (%d)' %
                                (tag, len(crit), len(reference[label])))
            reference.setdefault(label, crit)
            print('%-48s components %d, critical angles %d' % (tag, d['components'], len(crit)), flush=True)
    # scales: the square peg of side 10 in the hole of side 12
    plate, peg = peg_in_hole(10, 12)
    path = os.path.join(work, 'm.json')
    with open(path, 'w') as f:
        json.dump(model_json('hunt57', plate, peg, ('0', '0')), f)
    for factor in () if quick else ('1e-300', '1e400'):
        scaled = os.path.join(work, 'scaled.json')
        subprocess.run([sys.executable, os.path.join(HERE, 'scale_model.py'), path, factor, scaled], check=True)
        d = build(hipair, scaled, os.path.join(work, 'out.json'), findings, 'peg-in-hole x%s' % factor)
        if d is None:
            continue
        crit = [critical_key(c) for c in d['critical_angles']]
        if d['components'] != 5 or crit != reference.get('peg-in-hole h=12', crit):
            findings.append('peg-in-hole x%s: %d components, %d critical angles (5 and %d at x1)' %
                            (factor, d['components'], len(crit), len(reference.get('peg-in-hole h=12', []))))
        print('%-48s components %d, critical angles %d' % ('peg-in-hole h=12 x' + factor, d['components'], len(crit)))
    return report_findings(findings)


if __name__ == '__main__':
    sys.exit(main())
