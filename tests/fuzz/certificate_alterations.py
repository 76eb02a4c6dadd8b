#!/usr/bin/env python3
"""Session 47 (hunt47): certificates with altered numbers against hipair-verify, with an oracle of
its own (session 48, hunt48: also film-advance.json's pin-slot claims, the film against the
follower posed by slide and tangent, and the part and geometry helpers in exact_planar.py /
exact_oracle.py).  lever-stop.json (a lever of two segments and two arcs turning about (0, 0) against a
fixed rectangular stop) is certified at generated lever angles on both sides of its contact with
the stop (`hipair certify --claim interference` and `--claim clearance`); then each number of the
claim is altered in turn (the last digit, the sign, moved by 1/den, and for a clearance the
distance moved across the exact distance) and the verifier's verdict is compared with the truth
decided here, in exact rational arithmetic (fractions, sign tests in Q(sqrt D)), without the
verifier's or the library's code:
  * interference: the witness point lies strictly inside the lever posed at the half-angle
    tangent t (cos = (1 - t^2)/(1 + t^2), sin = 2t/(1 + t^2)) and strictly inside the stop, and
    |2 atan t - angle| <= angle_error <= 10^-12 (its series at 80 digits, far inside the margins);
  * clearance: distance > 0 and every point of the posed lever's boundary is at least `distance`
    from every point of the stop's boundary (segment-segment, segment-arc exactly; the parts do
    not nest), and the angle as above.
A false certificate accepted (exit 0) is a finding; so is a true one rejected whose witness
still holds (for a clearance: any true one; for an interference: a true one, the point being the
witness).  Any exit other than 0/1/3 or more than one line of output is a finding.
usage: certificate_alterations.py HIPAIR HIPAIR_VERIFY REPO OUTDIR SEED N_CONFIGURATIONS"""
import copy, decimal, json, os, random, subprocess, sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_planar import sgn, sign_q, posed, cross, sub, dot, in_span, locate, segments_meet, parts_apart_by, shifted
from exact_oracle import PI, two_atan, decimal_text, claim_number, bisect, altered_numbers, verdict_problems, BatchVerifier

hipair, verify, repo, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6])
rng = random.Random(seed)

os.makedirs(outdir, exist_ok=True)

# lever-stop.json at its nominal parameters (lever-length 60, lever-width 8, stop-gap 2);
# an edge is ('s', P, Q) or ('a', P, Q, C) (a counter-clockwise arc from P to Q about C)
L, W, G = F(60), F(8), F(2)
LEVER = [('s', (F(0), -W / 2), (L, -W / 2)), ('a', (L, -W / 2), (L, W / 2), (L, F(0))),
         ('s', (L, W / 2), (F(0), W / 2)), ('a', (F(0), W / 2), (F(0), -W / 2), (F(0), F(0)))]
y0 = W / 2 + G
STOP = [('s', (F(20), y0), (F(40), y0)), ('s', (F(40), y0), (F(40), y0 + 10)),
        ('s', (F(40), y0 + 10), (F(20), y0 + 10)), ('s', (F(20), y0 + 10), (F(20), y0))]


def angle_holds(conf):
    t, a, e = F(conf['tangent']), F(conf['angle']), F(conf['angle_error'])
    if e < 0 or e > F(1, 10 ** 12) or abs(t) >= 1:
        return None if abs(t) >= 1 else False
    dec = lambda f: decimal.Decimal(f.numerator) / decimal.Decimal(f.denominator)
    diff = abs(two_atan(t) - dec(a)) - dec(e)
    if abs(diff) < decimal.Decimal(10) ** -70:
        return None   # too close to decide at 80 digits
    return diff <= 0


# ---- the pairs: how a certificate's numbers pose the parts ----------------------------------
# lever-stop.json: rotating claims `interference` / `clearance`, the lever's half-angle tangent
# peg-in-hole.json: 3-DOF claims `planar_interference` / `planar_clearance`, the peg's pose
# (x, y, tangent): turned about its pivot (0, 0) by 2 atan t, then shifted by (x, y)
HOLE, PEG_SIDE = F(12), F(10)
def square(h, x0=F(0), y0=F(0)):
    c = [(x0 - h, y0 - h), (x0 + h, y0 - h), (x0 + h, y0 + h), (x0 - h, y0 + h)]
    return [('s', c[i], c[(i + 1) % 4]) for i in range(4)]
PLATE = square(F(9)) + square(HOLE / 2)
PEG = square(PEG_SIDE / 2)


class Lever:
    model = 'examples/models/lever-stop.json'
    kinds = ('interference', 'clearance')
    def random_at(self, kind):
        # the lever's contact with the stop's corner (40, 6) is near 0.0499 rad: overlaps above it
        return ['--at', 'lever=%r' % (rng.uniform(0.051, 0.5) if kind == 'interference' else rng.uniform(-0.5, 0.048))]
    def coordinates(self, cert):
        return {'tangent': ('configuration', 'lever', 'tangent')}
    def parts(self, cert):
        conf = cert[cert['claim']]['configuration']['lever']
        return posed(LEVER, F(conf['tangent'])), STOP
    def angle_ok(self, cert):
        return angle_holds(cert[cert['claim']]['configuration']['lever'])
    def restated(self, cert):
        claim = cert['claim']
        c = cert[claim]
        conf = c['configuration']['lever']
        conf['angle'] = str(F(int((two_atan(F(conf['tangent'])) * 10 ** 20).to_integral_value()), 10 ** 20))
        conf['angle_error'] = '1/10000000000000000000'
    def statement(self, cert):
        claim = cert['claim']
        c = cert[claim]
        a = decimal_text(F(c['configuration']['lever']['angle']), 12)
        if claim == 'clearance':
            return "Parts 'lever' and 'stop' are at least %s mm apart with lever at %s rad." % (claim_number(F(c['distance'])), a)
        return "Parts 'lever' and 'stop' overlap with lever at %s rad." % a


class Peg:
    model = 'examples/models/peg-in-hole.json'
    kinds = ('interference', 'clearance')
    def random_at(self, kind):
        return ['--pair', 'plate:peg', '--at', 'peg=%r,%r,%r' % (rng.uniform(-1.8, 1.8), rng.uniform(-1.8, 1.8), rng.uniform(-0.4, 0.4))]
    def coordinates(self, cert):
        return {k: ('pose', k) for k in ('x', 'y', 'tangent')}
    def parts(self, cert):
        pose = cert[cert['claim']]['pose']
        return shifted(posed(PEG, F(pose['tangent'])), F(pose['x']), F(pose['y'])), PLATE
    def angle_ok(self, cert):
        return True
    def restated(self, cert):
        pass
    def statement(self, cert):
        claim = cert['claim']
        c = cert[claim]
        pose = c['pose']
        words = "Part 'plate' and 'peg' shifted by (%s, %s) mm and turned by 2 atan(%s) rad" % (
            claim_number(F(pose['x'])), claim_number(F(pose['y'])), F(pose['tangent']))
        return words + (' overlap.' if claim == 'planar_interference' else ' are at least %s mm apart.' % claim_number(F(c['distance'])))


# film-advance.json: pin-slot claims `planar_interference` / `planar_clearance` of the film
# (translating along y by its offset) against the follower posed by its slide s and half-angle
# tangent t: body point q goes to pivot + R(q - pivot) + s R (0, 1), pivot (0, 40); the slide within
# [-6, 6] mm, the angle within [-8, 8] deg, the film's offset within [-20, 5] mm (the model's limits)
def model_loops(path, part):
    """the part's loops as lists of segments, its parameters' nominal values put in exactly"""
    import re
    m = json.load(open(path))
    names = sorted(m['parameters'], key=len, reverse=True)
    values = {k: F(str(v['nominal'])) for k, v in m['parameters'].items()}
    def num(x):
        if not isinstance(x, str):
            return F(str(x))
        text = x
        for i, k in enumerate(names):
            text = text.replace(k, '_p%d' % i)
        text = re.sub(r'(?<![_\w])(\d+(\.\d+)?)', r"F('\1')", text)
        return eval(text, {'F': F}, {'_p%d' % i: values[k] for i, k in enumerate(names)})
    loops = []
    for loop in next(q for q in m['parts'] if q['name'] == part)['loops']:
        points = [tuple(map(num, loop['start']))] + [tuple(map(num, e['line_to'])) for e in loop['edges']]
        loops.append([('s', points[i], points[i + 1]) for i in range(len(points) - 1)])
    return loops


class Film:
    model = 'examples/models/film-advance.json'
    kinds = ('interference', 'clearance')
    def __init__(self):
        path = os.path.join(repo, self.model)
        self.film, self.follower = model_loops(path, 'film'), model_loops(path, 'follower')
    def random_at(self, kind):
        # the claw (body x 14..20, y -13..-11) turned about (0, 40) reaches the film's perforations
        # (x 20.5..21.5) at a few degrees: both claims occur
        return ['--pair', 'film:follower', '--at', 'follower=%r,%rdeg' % (rng.uniform(-5.5, 5.5), rng.uniform(-7.5, 7.5)),
                '--at', 'film=%r' % rng.uniform(-19, 4)]
    def coordinates(self, cert):
        return {'slide': ('pose', 'slide'), 'tangent': ('pose', 'tangent'), 'offset': ('configuration', 'film', 'offset')}
    def posed_parts(self, cert):
        c = cert[cert['claim']]
        s, t, o = F(c['pose']['slide']), F(c['pose']['tangent']), F(c['configuration']['film']['offset'])
        cos, sin = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
        # pivot + R (q - pivot) + s R (0, 1) = R (q + (0, s - 40)) + (0, 40)
        place = lambda q: (cos * q[0] - sin * (q[1] + s - 40), sin * q[0] + cos * (q[1] + s - 40) + 40)
        follower = [[('s', place(e[1]), place(e[2])) for e in loop] for loop in self.follower]
        film = [[('s', (e[1][0], e[1][1] + o), (e[2][0], e[2][1] + o)) for e in loop] for loop in self.film]
        return film, follower
    def parts(self, cert):
        film, follower = self.posed_parts(cert)
        return [e for loop in film for e in loop], [e for loop in follower for e in loop]
    def loop_starts(self, cert):
        film, follower = self.posed_parts(cert)
        return [loop[0][1] for loop in film], [loop[0][1] for loop in follower]
    def angle_ok(self, cert):
        c = cert[cert['claim']]
        s, t, o = F(c['pose']['slide']), F(c['pose']['tangent']), F(c['configuration']['film']['offset'])
        if not (-6 <= s <= 6 and -20 <= o <= 5) or abs(t) >= 1:
            return False
        limit = decimal.Decimal(8) * PI / 180
        diff = limit - abs(two_atan(t))
        return None if abs(diff) < decimal.Decimal(10) ** -70 else diff > 0
    def restated(self, cert):
        pass
    def statement(self, cert):
        claim = cert['claim']
        c = cert[claim]
        words = "Part 'film' at offset %s mm and 'follower' turned by 2 atan(%s) rad and slid by %s mm" % (
            claim_number(F(c['configuration']['film']['offset'])), F(c['pose']['tangent']), claim_number(F(c['pose']['slide'])))
        return words + (' overlap.' if claim == 'planar_interference' else ' are at least %s mm apart.' % claim_number(F(c['distance'])))


def truth(pair, cert):
    ok = pair.angle_ok(cert)
    if ok is None:
        return None
    first, second = pair.parts(cert)
    c = cert[cert['claim']]
    if 'point' in c:
        p = (F(c['point'][0]), F(c['point'][1]))
        where = (locate(first, p), locate(second, p))
        if None in where:
            return None
        return ok and where == ('inside', 'inside')
    return ok and parts_apart_by(first, second, F(c['distance']), pair.loop_starts(cert) if hasattr(pair, 'loop_starts') else None)


def node_of(tree, path):
    for k in path[:-1]:
        tree = tree[k]
    return tree


def with_value(pair, cert, path, value, restate_angle=False):
    t = copy.deepcopy(cert)
    node_of(t[t['claim']], path)[path[-1]] = str(value)
    if restate_angle:
        pair.restated(t)
    t['statement'] = pair.statement(t)
    return t


def alterations(pair, cert):
    """(what, altered certificate) for each number of the claim, the statement restated"""
    claim = cert['claim']
    body = cert[claim]
    leaves = list(pair.coordinates(cert).values())
    if 'lever' in body.get('configuration', {}):
        leaves += [('configuration', 'lever', 'angle'), ('configuration', 'lever', 'angle_error')]
    leaves += [('point', 0), ('point', 1)] if 'point' in body else [('distance',)]
    out = []
    for path in leaves:
        for what, nv in altered_numbers(rng, node_of(body, path)[path[-1]]):
            out.append(('%s %s' % ('/'.join(map(str, path)), what), with_value(pair, cert, path, nv)))
    # numbers moved across a tangency: the last true value and the first false one
    if 'distance' in body:
        lo, hi = bisect(lambda d: truth(pair, with_value(pair, cert, ('distance',), d)) is True,
                        F(body['distance']), 2 * F(body['distance']) + 1, 40)
        out += [('distance just below the exact distance', with_value(pair, cert, ('distance',), lo)),
                ('distance just above the exact distance', with_value(pair, cert, ('distance',), hi))]
    else:
        first, second = pair.parts(cert)
        inside = lambda q: locate(first, q) == 'inside' and locate(second, q) == 'inside'
        a = (F(body['point'][0]), F(body['point'][1]))
        b = (F(rng.randrange(-200, 200), 3), F(rng.choice([-100, 100])))
        for _ in range(60):
            m = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
            a, b = (m, b) if inside(m) else (a, m)
        points = [('point just inside the overlap', a), ('point just outside the overlap', b)]
        # the point exactly on the boundary between them, where a segment crosses [a, b]
        for e in first + second:
            if e[0] == 's' and segments_meet(a, b, e[1], e[2]):
                d, u = sub(b, a), sub(e[2], e[1])
                if cross(d, u) != 0:
                    k = cross(sub(e[1], a), u) / cross(d, u)
                    points.append(('point on the boundary', (a[0] + k * d[0], a[1] + k * d[1])))
                    break
        for what, q in points:
            t = copy.deepcopy(cert)
            t[claim]['point'] = [str(q[0]), str(q[1])]
            out.append((what, t))
    # each coordinate moved across the contact, the rest kept
    for name, path in pair.coordinates(cert).items():
        f = F(node_of(body, path)[path[-1]])
        holds = lambda v: truth(pair, with_value(pair, cert, path, v, True)) is True
        for far in (f - 3, f + 3) if name != 'tangent' else (F(-1, 3), F(1, 3)):
            if holds(far) or not holds(f):
                continue
            good, bad = bisect(holds, f, far)
            out += [('%s just before the contact' % name, with_value(pair, cert, path, good, True)),
                    ('%s just past the contact' % name, with_value(pair, cert, path, bad, True))]
    return out


batch = BatchVerifier(verify)   # one hipair-verify --list per 250 altered certificates (session 75)
findings, counts = 0, {'true accepted': 0, 'true rejected': 0, 'false rejected': 0, 'undecided': 0, 'base': 0}
pairs = [Lever(), Peg(), Film()]
for case in range(n):
    # the film pair's exact geometry costs about 4 lever or peg cases: one case in six
    pair = pairs[2] if case % 6 == 5 else pairs[case % 2]
    kind = pair.kinds[(case // 6 if case % 6 == 5 else case // 2) % 2]
    at = pair.random_at(kind)
    model = os.path.join(repo, pair.model)
    base = os.path.join(outdir, 'base-%d.json' % case)
    r = subprocess.run([hipair, 'certify', model, '--claim', kind, '--out', base] + at, capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        # the generated configuration was on the other side of contact: the other claim
        kind = pair.kinds[1 - pair.kinds.index(kind)]
        r = subprocess.run([hipair, 'certify', model, '--claim', kind, '--out', base] + at, capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        print('case %d: neither claim certified at %s: %s' % (case, at, r.stderr.strip()[:200]))
        findings += 1
        continue
    cert = json.load(open(base))
    counts['base'] += 1
    if truth(pair, cert) is not True:
        print('case %d: the produced %s certificate is not true by the oracle (%s)' % (case, kind, truth(pair, cert)))
        findings += 1
    if pair.statement(cert) != cert['statement']:
        print('case %d: the oracle restates %r as %r' % (case, cert['statement'], pair.statement(cert)))
        findings += 1
    for what, altered in alterations(pair, cert):
        true = truth(pair, altered)

        def then(code, text, case=case, pair=pair, kind=kind, at=at, what=what, true=true):
            problems = verdict_problems(code, text, true, counts)
            if code != 0 and true:
                # a true claim the verifier cannot prove (its witness within its margins): reported
                print('note: case %d (%s %s) %s: true, rejected: %s' % (case, pair.model, kind, what, text[:200]), flush=True)
            if os.environ.get('ALTERATIONS_VERBOSE'):
                print('  %s %s: %s -> exit %d' % (kind, what, true, code))
            if problems:
                batch.findings += 1
                print('case %d (%s %s, %s) %s: %s: %s' % (case, pair.model, kind, ' '.join(at), what, problems, text[:200]), flush=True)
            return bool(problems)
        batch.add(os.path.join(outdir, 'c%d' % case), model, altered, then)
batch.flush()
findings += batch.findings
print('%s, %d findings' % (counts, findings))
sys.exit(1 if findings else 0)
