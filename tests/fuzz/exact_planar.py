"""Exact planar geometry for the certificate oracles (certificate_alterations.py; sessions 47-48):
parts as lists of edges ('s', P, Q) or ('a', P, Q, C) (a counter-clockwise arc from P to Q about
C) with Fraction coordinates, decided in rational arithmetic and sign tests in Q(sqrt D), without
the verifier's or the library's code."""
from fractions import Fraction as F


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


def parts_apart_by(first, second, d, starts=None):
    """every boundary point of `first` at least d from every boundary point of `second`, and
    neither part inside the other (d > 0); arcs only in `first`.  `starts`: a vertex of each loop
    of the two parts (first's, second's), default the first edge's start of each"""
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
    ours, theirs = starts or ([first[0][1]], [second[0][1]])
    return all(locate(second, p) == 'outside' for p in ours) and all(locate(first, p) == 'outside' for p in theirs)


def shifted(edges, x, y):
    return [tuple([e[0]] + [(p[0] + x, p[1] + y) for p in e[1:]]) for e in edges]
