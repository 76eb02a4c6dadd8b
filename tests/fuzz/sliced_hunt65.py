#!/usr/bin/env python3
"""Session-65 hunt (hunt65) on 3-DOF pairs (a peg free in the plane against a plate): generated,
seeded (HIPAIR_TEST_SEED, default 6500), judged by exact oracles of this script's own.

usage: sliced_hunt65.py HIPAIR HIPAIR_VERIFY WORKDIR [--quick]

1. Connectivity across scales (`hipair cspace --json`): the peg 2 wide that passes the 3 mm slot
   only turned upright (2 components), the peg 0.01 too wide (3.01: 3), the square peg of side 10
   that turns in a hole of 14.15 (2) and not in one of 14.14 (5: the diagonal is 14.142), each at
   scale 1, 10^-300 and 10^400 (tests/fuzz/scale_model.py) and with the pivot 10^6 mm away: the
   same components, the same critical angles (exact strings), the same free cells per slice and
   the same partition of the cells into components.
2. Sliced certificates (`planar_clearance` / `planar_interference`) of a square peg of side p in
   a hole of side p + c, c = 0 or 2^-k (k <= 200), and of the peg in the slot, certified at poses
   on and 2^-k beside contacts; every number of the claim (x, y, tangent, distance, the point)
   moved by 2^-10, 2^-40 and 2^-200 of itself (by 2^-k when it is 0) either way, its sign
   changed, the pose given to the plate, the pair's order swapped, the half-turn chart added, a
   field dropped. The truth of each is decided here (exact rationals: a point strictly inside
   both posed parts; every boundary point of one at least d from the other's and neither inside
   the other); hipair-verify must accept every original and never accept a false one (exit 1),
   with one line and an exit of 0/1/3.
3. Bad inputs on these pairs: malformed planar and pin-slot motions (zero-length and missing slot
   directions, reversed or empty limits, a pivot of one number or a string), degenerate arcs
   (zero radius, start = end, a centre far from the ends), numbers like 1e100000 / 1e-100000 and
   non-numbers: one line naming the JSON pointer, exit 2, no output file written.
Exit 0 when every check passed, 1 with one line per finding (FINDING: ...).
(--quick: the ctest `sliced_hunt65`: 1 at scale 10^400 for the square pegs only,
2 for four certificates, 3 in full.)
"""
import copy
import json
import os
import random
import subprocess
import sys
import time
from fractions import Fraction as F

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from exact_planar import locate, parts_apart_by  # noqa: E402
from exact_oracle import claim_number, judged  # noqa: E402
from hunt_common import run, crash_problems, report_findings  # noqa: E402
from sliced_oracle_hunt import model_json, peg_in_hole, peg_in_slot, lit  # noqa: E402


def write_model(path, plate, peg, pivot=(F(0), F(0))):
    with open(path, 'w') as f:
        json.dump(model_json('hunt65', plate, peg, (lit(pivot[0]), lit(pivot[1]))), f)


# ------------------------------------------------------------------ 1. connectivity across scales

def structure(d):
    """what must not depend on the scale or the pivot: components, critical angles, cells per
    slice, and the partition of the cells into components (as sets of (slice, cell))"""
    crit = ['pi' if c['half_turn'] else c['t']['exact'].split(', t in')[0] for c in d['critical_angles']]
    cells = [len(s['free_cells']) for s in d['slices']]
    groups = {}
    for s in d['slices']:
        for c in s['free_cells']:
            groups.setdefault(c['component'], set()).add((s['index'], c['index']))
    return d['components'], crit, cells, sorted(sorted(g) for g in groups.values())


def cspace(hipair, path, out, findings, label, timeout=300):
    t0 = time.time()
    rc, so, se = run([hipair, 'cspace', path, '--json', out], timeout)
    problems = crash_problems(rc, so + se)
    if problems or rc != 0:
        findings.append('%s: cspace rc=%s %s %s' % (label, rc, problems, se.strip()[-300:]))
        return None
    with open(out) as f:
        d = json.load(f)
    print('%-44s components %d, critical angles %d (%.1f s)' % (label, d['components'], len(d['critical_angles']),
                                                              time.time() - t0), flush=True)
    return d


def hunt_scales(hipair, work, quick, findings):
    cases = [('square 10 in 14.15', peg_in_hole(10, F('14.15')), 2), ('square 10 in 14.14', peg_in_hole(10, F('14.14')), 5)]
    if not quick:
        cases += [('peg 2 in the 3 mm slot', peg_in_slot(2, 3), 2), ('peg 3.01 in the 3 mm slot', peg_in_slot(F('3.01'), 3), 3)]
    n = 0
    for label, (plate, peg), comps in cases:
        path = os.path.join(work, 'scale.json')
        ys = [p[1] for l in peg for p in l]
        centre = (F(0), (min(ys) + max(ys)) / 2)
        write_model(path, plate, peg, centre)
        variants = [('x1', path)]
        for factor in ('1e400',) if quick else ('1e-300', '1e400'):
            scaled = os.path.join(work, 'scaled%s.json' % factor)
            subprocess.run([sys.executable, os.path.join(HERE, 'scale_model.py'), path, factor, scaled], check=True)
            variants.append(('x' + factor, scaled))
        if not quick:
            far = os.path.join(work, 'far.json')
            write_model(far, plate, peg, (F(10) ** 6, centre[1]))
            variants.append(('pivot 1e6 mm away', far))
        reference = None
        for name, model in variants:
            d = cspace(hipair, model, os.path.join(work, 'out.json'), findings, '%s %s' % (label, name))
            n += 1
            if d is None:
                continue
            s = structure(d)
            if s[0] != comps:
                findings.append('%s %s: %d components, the closed form says %d' % (label, name, s[0], comps))
            if reference is None:
                reference = s
            elif s != reference:
                what = [k for k, a, b in zip(('components', 'critical angles', 'cells per slice', 'component partition'), s, reference)
                        if a != b]
                findings.append('%s %s: %s differ from scale 1' % (label, name, ', '.join(what)))
    return n


# ------------------------------------------------------------------ 2. sliced certificates

def edges_of(loops):
    return [('s', l[i], l[(i + 1) % len(l)]) for l in loops for i in range(len(l))]


def posed_peg(peg, pose):
    t = F(pose['tangent'])
    if pose.get('centre') == 'pi':
        c, s = F(-1) * (1 - t * t) / (1 + t * t), F(-1) * 2 * t / (1 + t * t)
    else:
        c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
    x, y = F(pose['x']), F(pose['y'])
    return [[(c * p[0] - s * p[1] + x, s * p[0] + c * p[1] + y) for p in l] for l in peg]


def truth(plate, peg, cert):
    """True / False / None (undecided) for a planar claim of the peg (pivot (0, 0)) against the plate"""
    claim = cert.get('claim')
    body = cert.get(claim)
    try:
        pose = body['pose']
        if pose.get('part') != 'peg' or cert.get('pair') not in (['plate', 'peg'], ['peg', 'plate']):
            return False
        if set(pose) - {'part', 'x', 'y', 'tangent', 'centre'} or pose.get('centre', '0') not in ('0', 'pi'):
            return False
        placed = posed_peg(peg, pose)
        if claim == 'planar_interference':
            p = (F(body['point'][0]), F(body['point'][1]))
            in_plate = [locate(edges_of([l]), p) for l in plate]
            in_peg = [locate(edges_of([l]), p) for l in placed]
            if None in in_plate + in_peg:
                return None
            return in_plate == ['inside'] + ['outside'] * (len(plate) - 1) and in_peg == ['inside'] * len(placed)
        if claim == 'planar_clearance':
            d = F(body['distance'])
            first, second = edges_of(placed), edges_of(plate)
            if not parts_apart_by(first, second, d, ([], [])):   # the boundaries at least d apart
                return False
            # and neither part inside the other: a point of each loop decided against the other part
            # (the boundaries are apart, so any point of a loop will do: one whose ray meets no vertex)
            for loops, other in ((placed, second), (plate, first)):
                for l in loops:
                    where = next((w for w in (locate(other, q) for q in l + [((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
                                                                               for a, b in zip(l, l[1:] + l[:1])]) if w is not None), None)
                    if where is None:
                        return None
                    if where != 'outside':
                        return False
            return True
    except (KeyError, TypeError, ValueError, ZeroDivisionError, IndexError):
        return False
    return False


def statement(cert):
    c = cert[cert['claim']]
    pose = c['pose']
    words = "Part 'plate' and 'peg' shifted by (%s, %s) mm and turned by 2 atan(%s)%s rad" % (
        claim_number(F(pose['x'])), claim_number(F(pose['y'])), F(pose['tangent']), ' + pi' if pose.get('centre') == 'pi' else '')
    return words + (' overlap.' if cert['claim'] == 'planar_interference' else ' are at least %s mm apart.' % claim_number(F(c['distance'])))


def mutations(cert, k):
    """(what, certificate) pairs: numbers moved by 2^-10, 2^-40, 2^-200 of themselves, signs,
    names, charts, dropped fields; the statement restated when it can be"""
    claim = cert['claim']
    out = []

    def put(what, change, restate=True):
        t = copy.deepcopy(cert)
        change(t[claim], t)
        if restate:
            try:
                t['statement'] = statement(t)
            except (KeyError, ValueError, ZeroDivisionError, TypeError):
                pass
        out.append((what, t))

    def setter(path, value):
        def change(body, _):
            node = body
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = str(value)
        return change

    paths = [('pose', 'x'), ('pose', 'y'), ('pose', 'tangent')]
    paths += [('point', 0), ('point', 1)] if claim == 'planar_interference' else [('distance',)]
    body = cert[claim]
    for path in paths:
        node = body
        for key in path[:-1]:
            node = node[key]
        v = F(node[path[-1]])
        for j in (10, 40, 200):
            delta = v / 2 ** j if v != 0 else F(1, 2 ** k)
            for sign in (1, -1):
                put('%s %s 2^-%d' % ('/'.join(map(str, path)), '+' if sign > 0 else '-', j), setter(path, v + sign * delta))
        if v != 0:
            put('%s sign' % '/'.join(map(str, path)), setter(path, -v))
    put('pose given to the plate', lambda b, _: b['pose'].__setitem__('part', 'plate'))
    put('pair swapped', lambda b, t: t.__setitem__('pair', t['pair'][::-1]), restate=False)
    put('half-turn chart', lambda b, _: b['pose'].__setitem__('centre', 'pi'))
    for field in ('x', 'y', 'tangent'):
        put('pose/%s dropped' % field, lambda b, _, f=field: b['pose'].pop(f), restate=False)
    put('%s dropped' % ('point' if claim == 'planar_interference' else 'distance'),
        lambda b, _: b.pop('point' if claim == 'planar_interference' else 'distance'), restate=False)
    return out


def hunt_certificates(hipair, verify, work, quick, rng, findings):
    true_rejected = {}
    counts = {'base': 0, 'undecided': 0, 'true rejected': 0, 'true accepted': 0, 'false rejected': 0}
    model = os.path.join(work, 'cert_model.json')
    certificate = os.path.join(work, 'cert.json')
    altered = os.path.join(work, 'altered.json')
    pairs = []
    for _ in range(1 if quick else 3):
        k = rng.randrange(1, 201)
        p = rng.choice([F(10), F(rng.randrange(50, 150), rng.randrange(7, 13))])
        for c in (F(0), F(1, 2 ** k)):
            pairs.append(('square p=%s c=%s' % (p, '0' if c == 0 else '2^-%d' % k), peg_in_hole(p, p + c), k, p, c))
    if not quick:
        k = rng.randrange(1, 201)
        pairs.append(('slot p=3 w=3', peg_in_slot(3, 3), k, F(3), F(0)))
    for label, (plate, peg), k, p, c in pairs:
        # peg_in_slot's peg is centred at y = -11 - ...: re-centre the peg on its pivot
        ys = [q[1] for q in peg[0]]
        cy = (min(ys) + max(ys)) / 2
        peg = [[(q[0], q[1] - cy) for q in peg[0]]]
        write_model(model, plate, peg)
        eps = F(1, 2 ** k)
        # poses: centred (the fit: touching when c = 0), shifted by c/2 (touching), by c/2 + 2^-k
        # (overlapping), turned by 2^-k (overlapping), and out beside the plate's outer edge
        outer = max(q[0] for q in plate[0])
        poses = [(F(0), F(0), F(0)), (c / 2 + eps, F(0), F(0)), (F(0), F(0), eps), (c / 4, -c / 4, F(0)),
                 (outer + p / 2 + eps, F(0), F(0)), (outer + p / 2, F(1, 3), F(0)), (outer + p, eps, F(1, 7))]
        if quick:
            poses = poses[1:3] + poses[4:5] + poses[6:]
        for x, y, t in poses:
            for claim in ('interference', 'clearance'):
                r = subprocess.run([hipair, 'certify', model, '--claim', claim, '--pair', 'plate:peg', '--out', certificate,
                                    '--at', 'peg=%s,%s,%s' % (x, y, 2 * t if t else 0)], capture_output=True, text=True, timeout=120)
                if r.returncode != 0:
                    continue
                cert = json.load(open(certificate))
                tag = '%s at (%s, %s, %s) %s' % (label, x, y, t, claim)
                counts['base'] += 1
                if truth(plate, peg, cert) is not True:
                    findings.append('%s: the produced certificate is not true by the oracle' % tag)
                if statement(cert) != cert['statement']:
                    findings.append('%s: statement %r, restated %r' % (tag, cert['statement'], statement(cert)))
                rc = subprocess.run([verify, certificate, model], capture_output=True, text=True, timeout=120).returncode
                if rc != 0:
                    findings.append('%s: the original certificate is rejected (exit %d)' % (tag, rc))
                for what, t2 in mutations(cert, k):
                    true = truth(plate, peg, t2)
                    problems, code, text = judged(verify, altered, model, t2, true, counts)
                    if true and code != 0:   # sound, not complete: counted by kind, not a finding
                        kind = what.split(' 2^')[0] + ': ' + text.split(':')[1].strip()[:60] if ':' in text else what
                        true_rejected[kind] = true_rejected.get(kind, 0) + 1
                    for pr in problems:
                        findings.append('%s %s: %s: %s' % (tag, what, pr, text[:200]))
    print('certificates: %s' % counts, flush=True)
    for kind, n in sorted(true_rejected.items()):
        print('  true, rejected: %d x %s' % (n, kind))
    return counts


# ------------------------------------------------------------------ 3. bad inputs

def bad_models():
    """(label, model dict, pointer expected in the message)"""
    plate, peg = peg_in_hole(10, 12)
    base = model_json('bad', plate, peg, ('0', '0'))
    out = []

    def variant(label, pointer, change):
        m = copy.deepcopy(base)
        change(m)
        out.append((label, m, pointer))

    def motion(value):
        return lambda m: m['parts'][1].__setitem__('motion', value)

    variant('planar pivot of one number', '/parts/1/motion/planar/pivot', motion({'planar': {'pivot': ['0']}}))
    variant('planar pivot a string', '/parts/1/motion/planar/pivot', motion({'planar': {'pivot': 'origin'}}))
    variant('planar pivot 1e100000', '/parts/1/motion/planar/pivot', motion({'planar': {'pivot': ['1e100000', '0']}}))
    variant('planar pivot NaN', '/parts/1/motion/planar/pivot', motion({'planar': {'pivot': ['nan', '0']}}))
    slot = {'pivot': ['0', '0'], 'direction': ['0', '1'], 'angle_limits': ['-8', '8'], 'limits': ['-6', '6']}
    for label, key, value in (('zero-length slot direction', 'direction', ['0', '0']),
                              ('slot direction of one number', 'direction', ['1']),
                              ('slot direction 1e-100000', 'direction', ['1e-100000', '0']),
                              ('reversed slot limits', 'limits', ['6', '-6']),
                              ('empty slot limits', 'limits', ['2', '2']),
                              ('slot limits 1e100000', 'limits', ['-1e100000', '1e100000']),
                              ('reversed angle limits', 'angle_limits', ['8', '-8']),
                              ('angle limits a string', 'angle_limits', 'all')):
        s = dict(slot)
        s[key] = value
        variant(label, '/parts/1/motion/pin_slot/' + key, motion({'pin_slot': s}))
    s = dict(slot)
    del s['direction']
    variant('slot without a direction', '/parts/1/motion/pin_slot', motion({'pin_slot': s}))
    # degenerate arcs on the peg's loop: its first edge replaced
    def arc(edge):
        def change(m):
            m['parts'][1]['loops'][0]['edges'][0] = edge
        return change
    variant('arc of zero radius', '/parts/1/loops/0/edges/0', arc({'arc_to': ['5', '-5'], 'center': ['-5', '-5'], 'dir': 'ccw'}))
    variant('arc with start = end', '/parts/1/loops/0/edges/0', arc({'arc_to': ['-5', '-5'], 'center': ['0', '-5'], 'dir': 'ccw'}))
    variant('arc centre not equidistant', '/parts/1/loops/0/edges/0', arc({'arc_to': ['5', '-5'], 'center': ['1', '-1e999'], 'dir': 'ccw'}))
    variant('arc centre 1e-999 off the bisector', '/parts/1/loops/0/edges/0', arc({'arc_to': ['5', '-5'], 'center': ['1e-999', '-5'], 'dir': 'ccw'}))
    variant('segment to 1e100000', '/parts/1/loops/0/edges/0', arc({'line_to': ['1e100000', '-5']}))
    variant('zero-length segment', '/parts/1/loops/0/edges/0', arc({'line_to': ['-5', '-5']}))
    return out


def hunt_bad_inputs(hipair, work, findings):
    n = 0
    for label, m, pointer in bad_models():
        path = os.path.join(work, 'bad.json')
        with open(path, 'w') as f:
            json.dump(m, f)
        for command in (['cspace', path, '--json', os.path.join(work, 'bad_out.json')],
                        ['certify', path, '--claim', 'clearance', '--at', 'peg=20,0,0', '--out', os.path.join(work, 'bad_out.json')]):
            out = os.path.join(work, 'bad_out.json')
            if os.path.exists(out):
                os.remove(out)
            rc, so, se = run([hipair] + command, 120)
            n += 1
            text = (so + se).strip()
            problems = crash_problems(rc, text)
            if rc != 2:
                problems.append('exit %s' % rc)
            if len(text.splitlines()) != 1:
                problems.append('%d lines' % len(text.splitlines()))
            if pointer.rsplit('/', 1)[0] not in text:
                problems.append('no pointer %s' % pointer)
            if os.path.exists(out):
                problems.append('an output written')
            if problems:
                findings.append('bad input %s (%s): %s: %s' % (label, command[0], '; '.join(problems), text[:200].replace('\n', ' | ')))
    return n


def hunt_extreme_poses(hipair, verify, work, findings):
    """`certify --at` on the peg in the hole of side 12 with huge, tiny and malformed coordinates:
    exit 0 and a certificate hipair-verify accepts, or exit 1 / 2 with one line and nothing
    written (session 65: 1e400 rad stopped with exit 3, 1e77 rad was placed 9.5 degrees off)"""
    model = os.path.join(work, 'extreme.json')
    plate, peg = peg_in_hole(10, 12)
    write_model(model, plate, peg)
    out = os.path.join(work, 'extreme_cert.json')
    n = 0
    for at in ('20,0,1e400', '20,0,-1e999', '20,0,1e77', '20,0,1e1000', '20,0,1e400deg', '20,0,-1e999deg', '1e400,0,0',
               '1e-400,0,0', '0,0,1e-400', '20,1e-999,1e-999', '1e999,1e999,1e999', '20,0,1e1001', '20,0,nan', '20,0,inf',
               '20,0,1/0', '20,0', '20,0,0,0', 'x,0,0'):
        for claim in ('clearance', 'interference'):
            if os.path.exists(out):
                os.remove(out)
            rc, so, se = run([hipair, 'certify', model, '--claim', claim, '--at', 'peg=' + at, '--out', out], 120)
            n += 1
            text = (so + se).strip()
            problems = crash_problems(rc, text)
            if rc == 0:
                vr, vo, ve = run([verify, out, model], 120)
                if vr != 0:
                    problems.append('hipair-verify rejects it: ' + (vo + ve).strip()[:150])
            elif rc in (1, 2):
                if len(se.strip().splitlines()) != 1:   # (stdout may say how a 'deg' angle was taken)
                    problems.append('%d lines on stderr' % len(se.strip().splitlines()))
                if os.path.exists(out):
                    problems.append('an output written')
                if rc == 2 and '--at' not in text and '/parts' not in text:
                    problems.append('no option or pointer named')
            else:
                problems.append('exit %s' % rc)
            if problems:
                findings.append('certify --claim %s --at peg=%s: %s: %s' % (claim, at, '; '.join(problems), text[:200]))
    return n


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    hipair, verify, work = sys.argv[1], sys.argv[2], sys.argv[3]
    quick = '--quick' in sys.argv[4:]
    seed = os.environ.get('HIPAIR_TEST_SEED', '6500')
    seed = random.randrange(10 ** 9) if seed == 'random' else int(seed)
    print('seed %d' % seed)
    rng = random.Random(seed)
    os.makedirs(work, exist_ok=True)
    findings = []
    builds = hunt_scales(hipair, work, quick, findings)
    counts = hunt_certificates(hipair, verify, work, quick, rng, findings)
    bad = hunt_bad_inputs(hipair, work, findings) + hunt_extreme_poses(hipair, verify, work, findings)
    print('%d builds, %d certificates with %d alterations, %d bad inputs' %
          (builds, counts['base'], sum(counts.values()) - counts['base'], bad))
    return report_findings(findings)


if __name__ == '__main__':
    sys.exit(main())
