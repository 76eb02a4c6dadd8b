#!/usr/bin/env python3
"""Session 47 (hunt47): certificates with altered numbers against hipair-verify, with an oracle of
its own.  lever-stop.json (a lever of two segments and two arcs turning about (0, 0) against a
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
from exact_oracle import two_atan, decimal_text, claim_number, bisect, altered_numbers, judged

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


def sgn(x):
    return (x > 0) - (x < 0)


def sign_q(a, b, d):
    """sign of a + b sqrt(d), d >= 0, exactly"""
    if d == 0 or b == 0:
        return sgn(a)
    sa, sb = sgn(a), sgn(b)
    if sa == 0 or sa == sb:
        return sb if sa == 0 else sa
    return sa * sgn(a * a - b * b * d)


def posed(edges, t):
    c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
    rot = lambda p: (c * p[0] - s * p[1], s * p[0] + c * p[1])
    return [tuple([e[0]] + [rot(p) for p in e[1:]]) for e in edges]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def in_span(e, qa, qb, d):
    """is the circle point c + (qa[0] + qa[1] sqrt d, qb[0] + qb[1] sqrt d) on the ccw arc e (ends included)?"""
    _, p, q, c = e
    s, t = sub(p, c), sub(q, c)
    # cross(s, v) and cross(v, t) for v = (vx, vy) with components a + b sqrt(d)
    cs = sign_q(s[0] * qb[0] - s[1] * qa[0], s[0] * qb[1] - s[1] * qa[1], d)
    ct = sign_q(qa[0] * t[1] - qb[0] * t[0], qa[1] * t[1] - qb[1] * t[0], d)
    if cross(s, t) > 0 or (cross(s, t) == 0 and dot(s, t) < 0 and False):
        return cs >= 0 and ct >= 0
    return cs >= 0 or ct >= 0


def locate(edges, p):
    """'inside', 'outside', 'boundary' or None (the ray meets a vertex: undecided) for one loop"""
    px, py = p
    crossings = 0
    for e in edges:
        a, b = e[1], e[2]
        if e[0] == 's':
            if cross(sub(b, a), sub(p, a)) == 0 and min(a[0], b[0]) <= px <= max(a[0], b[0]) and \
                    min(a[1], b[1]) <= py <= max(a[1], b[1]):
                return 'boundary'
        else:
            c = e[3]
            r2 = dot(sub(a, c), sub(a, c))
            if dot(sub(p, c), sub(p, c)) == r2 and in_span(e, (p[0] - c[0], F(0)), (p[1] - c[1], F(0)), F(0)):
                return 'boundary'
        if a[1] == py or b[1] == py:
            return None
        if e[0] == 's':
            if (a[1] < py) != (b[1] < py):
                x = a[0] + (py - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
                crossings += x > px
        else:
            c = e[3]
            r2 = dot(sub(a, c), sub(a, c))
            d = r2 - (py - c[1]) ** 2
            if d < 0:
                continue
            if d == 0:
                return None
            for s in (1, -1):   # x = c.x + s sqrt(d)
                if sign_q(c[0] - px, F(s), d) > 0 and in_span(e, (F(0), F(s)), (py - c[1], F(0)), d):
                    crossings += 1
    return 'inside' if crossings % 2 else 'outside'


def point_segment_at_least(p, a, b, dist2):
    ab, ap = sub(b, a), sub(p, a)
    u = dot(ap, ab)
    n2 = dot(ab, ab)
    if u <= 0:
        return dot(ap, ap) >= dist2
    if u >= n2:
        bp = sub(p, b)
        return dot(bp, bp) >= dist2
    return cross(ab, ap) ** 2 >= dist2 * n2


def segments_meet(a, b, c, d):
    o = lambda p, q, r: sgn(cross(sub(q, p), sub(r, p)))
    o1, o2, o3, o4 = o(a, b, c), o(a, b, d), o(c, d, a), o(c, d, b)
    if o1 != o2 and o3 != o4 and o1 * o2 <= 0 and o3 * o4 <= 0:
        return True
    on = lambda p, q, r: min(p[0], q[0]) <= r[0] <= max(p[0], q[0]) and min(p[1], q[1]) <= r[1] <= max(p[1], q[1])
    return (o1 == 0 and on(a, b, c)) or (o2 == 0 and on(a, b, d)) or (o3 == 0 and on(c, d, a)) or (o4 == 0 and on(c, d, b))


def point_arc_at_least(p, e, d):
    _, a, b, c = e
    r2 = dot(sub(a, c), sub(a, c))
    v = sub(p, c)
    if in_span(e, (v[0], F(0)), (v[1], F(0)), F(0)):
        # | |v| - r | >= d  <=>  |v| >= r + d  or  |v| <= r - d   (r = sqrt(r2))
        v2 = dot(v, v)
        # |v| >= r + d  <=>  v2 - r2 - d^2 >= 2 d sqrt(r2)
        if sign_q(v2 - r2 - d * d, -2 * d, r2) >= 0:
            return True
        # |v| <= r - d  <=>  r >= d and r2 + d^2 - v2 >= 2 d r... (r - d)^2 >= v2 with r >= d
        return sign_q(F(0) - d, F(1), r2) >= 0 and sign_q(r2 + d * d - v2, -2 * d, r2) >= 0
    return all(dot(sub(p, q), sub(p, q)) >= d * d for q in (a, b))


def segment_arc_at_least(s, e, d):
    p, q = s[1], s[2]
    if not (point_arc_at_least(p, e, d) and point_arc_at_least(q, e, d)):
        return False
    if not all(point_segment_at_least(x, p, q, d * d) for x in (e[1], e[2])):
        return False
    _, a, b, c = e
    r2 = dot(sub(a, c), sub(a, c))
    pq, pc = sub(q, p), sub(c, p)
    n2 = dot(pq, pq)
    u = F(dot(pc, pq), n2)
    if 0 < u < 1:
        f = (p[0] + u * pq[0], p[1] + u * pq[1])
        v = sub(f, c)
        if in_span(e, (v[0], F(0)), (v[1], F(0)), F(0)) and dot(v, v) >= r2:
            if sign_q(dot(v, v) - r2 - d * d, -2 * d, r2) < 0:
                return False
    # the segment meets the arc: |p + s pq - c|^2 = r2, s in [0, 1], the point on the arc
    A, B, C = n2, -2 * dot(pc, pq), dot(pc, pc) - r2
    disc = B * B - 4 * A * C
    if disc >= 0:
        for k in (1, -1):   # s = (-B + k sqrt(disc)) / 2A
            if sign_q(-B, F(k), disc) >= 0 and sign_q(-B - 2 * A, F(k), disc) <= 0:
                qa = (p[0] - c[0] + pq[0] * (-B) / (2 * A), pq[0] * k / (2 * A))
                qb = (p[1] - c[1] + pq[1] * (-B) / (2 * A), pq[1] * k / (2 * A))
                if in_span(e, qa, qb, disc):
                    return False
    return True


def parts_apart_by(first, second, d):
    """every boundary point of `first` at least d from every boundary point of `second`, and
    neither part inside the other (d > 0); arcs only in `first`"""
    if d <= 0:
        return False
    for e in first:
        for s in second:
            if e[0] == 's':
                if segments_meet(e[1], e[2], s[1], s[2]):
                    return False
                if not all(point_segment_at_least(x, s[1], s[2], d * d) for x in (e[1], e[2])) or \
                        not all(point_segment_at_least(x, e[1], e[2], d * d) for x in (s[1], s[2])):
                    return False
            elif not segment_arc_at_least(s, e, d):
                return False
    return locate(second, first[0][1]) == 'outside' and locate(first, second[0][1]) == 'outside'


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


def shifted(edges, x, y):
    return [tuple([e[0]] + [(p[0] + x, p[1] + y) for p in e[1:]]) for e in edges]


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
    return ok and parts_apart_by(first, second, F(c['distance']))


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
    if 'configuration' in body:
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


findings, counts = 0, {'true accepted': 0, 'true rejected': 0, 'false rejected': 0, 'undecided': 0, 'base': 0}
pairs = [Lever(), Peg()]
for case in range(n):
    pair = pairs[case % 2]
    kind = pair.kinds[(case // 2) % 2]
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
        problems, code, text = judged(verify, os.path.join(outdir, 'c%d.json' % case), model, altered, true, counts)
        if code != 0 and true:
            # a true claim the verifier cannot prove (its witness within its margins): reported
            print('note: case %d (%s %s) %s: true, rejected: %s' % (case, pair.model, kind, what, text[:200]), flush=True)
        if os.environ.get('ALTERATIONS_VERBOSE'):
            print('  %s %s: %s -> exit %d' % (kind, what, true, code))
        if problems:
            findings += 1
            print('case %d (%s %s, %s) %s: %s: %s' % (case, pair.model, kind, ' '.join(at), what, problems, text[:200]), flush=True)
print('%s, %d findings' % (counts, findings))
sys.exit(1 if findings else 0)
