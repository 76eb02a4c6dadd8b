#!/usr/bin/env python3
"""Session 48 (hunt48): jam and free-passage certificates with altered numbers against
hipair-verify, judged by an oracle of the test's own (the sibling of certificate_alterations.py,
which covers interference and clearance).  The pair is lever-stop.json with its stop-gap g
generated within its tolerance [1.9, 2.1] (`--set`; the other parameters nominal): a lever of
half-width 4 (straight sides from x = 0 to 60, half-disc ends) turning about (0, 0) against the
fixed rectangle [20, 40] x [h, h + 10], h = 4 + g.  Closed forms, derived here and not taken from
the library (written for h = 6):
  * every stop point P = r (cos phi, sin phi) has 0 < r cos(phi - theta) < 60 for theta in the
    lever's limits [-pi/6, 2pi/3] while phi - theta stays within (-pi/2, pi/2), so P lies inside
    the lever iff |phi - theta| < asin(4 / r); over the rectangle the overlap is the open interval
    (theta_c, theta_x), theta_c = atan(3/20) - atan(4/sqrt(1620)) (the corner (40, 6) on the upper
    side, ~0.049834) and theta_x = atan(4/5) + atan(4/sqrt(640)) (the corner (20, 16) on the lower
    side, ~0.831557);
  * for theta in [-pi/6, theta_c] the parts' distance is min(6 cos - 40 sin, 6 cos - 20 sin) - 4
    (the signed distance of the stop's lower corners to the upper side's line: linear in P, so
    least at a vertex), and both terms decrease in theta there (their derivative -6 sin - k cos is
    negative for tan theta > -k/6), so over a range [r0, r1] the least distance is the one at r1.
Truth, with theta's sines and cosines at 80 digits (a comparison closer than 10^-70: undecided):
  * jam (direction +1 / -1, trap [a, b], start s): a < b, a <= s <= b, s within the limits and
    not in the overlap, and the motion from s towards the far end meets the overlap: (s, b]
    (forward) or [a, s) (backward) meets (theta_c, theta_x).  A monotone motion never overlapping
    from s cannot then reach the far end; if that interval is free, it can.
  * free passage (range [r0, r1], distance d): d > 0, -pi/6 <= r0 < r1 <= 2pi/3, r1 < theta_c and
    the distance at r1 at least d (a range reaching theta_c overlaps; one beyond theta_x is not
    generated and left undecided).
Each number of the claim is altered (sign, +-1/den, the last digit, x(1 + 10^-k)), and moved across
the truth's boundary: the trap's far end and the start just before / past theta_c (or theta_x),
the range's end just before / past the point where the distance is d (with the last box
stretched to it, so the verifier judges the geometry, not the cover), d just below / above the
exact distance; the direction is reversed.  The statement is restated for the altered data.  A
false certificate accepted (exit 0) is a finding; so is an exit other than 0/1/3 or more than one
line of output.  True certificates rejected are counted (the verifier is sound, not complete).
usage: motion_certificate_alterations.py HIPAIR HIPAIR_VERIFY REPO OUTDIR SEED N_CERTIFICATES"""
import copy, json, os, random, subprocess, sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_oracle import D, atan, PI, sin_cos, compare, dec, claim_number, bisect, rational_near, altered_numbers, judged_certificate, BatchVerifier

hipair, verify, repo, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6])
rng = random.Random(seed)
os.makedirs(outdir, exist_ok=True)
model = os.path.join(repo, 'examples/models/lever-stop.json')

GAP = F(rng.randrange(190, 211), 100)
H = 4 + GAP
THETA_C = atan(dec(H / 40)) - atan(4 / dec(1600 + H * H - 16).sqrt())
THETA_X = atan(dec((H + 10) / 20)) + atan(4 / dec(400 + (H + 10) ** 2 - 16).sqrt())
LIMITS = (-PI / 6, 2 * PI / 3)


def within_limits(x):
    """is the rational angle x within the lever's limits? None when undecided"""
    lo, hi = compare(dec(x), LIMITS[0]), compare(dec(x), LIMITS[1])
    return None if None in (lo, hi) else lo >= 0 and hi <= 0


def blocked(x):
    """does the lever at the rational angle x overlap the stop? None when undecided"""
    a, b = compare(dec(x), THETA_C), compare(dec(x), THETA_X)
    return None if None in (a, b) else a > 0 and b < 0


def open_interval_meets_overlap(lo, hi):
    """does the interval from lo to hi (rationals, lo <= hi; its ends open or closed alike: the
    overlap is open) meet (theta_c, theta_x)?"""
    a, b = compare(dec(hi), THETA_C), compare(dec(lo), THETA_X)
    return None if None in (a, b) else a > 0 and b < 0


def distance_at(x):
    """the parts' distance at the rational angle x <= theta_c, 80 digits"""
    s, c = sin_cos(dec(x))
    return min(dec(H) * c - 40 * s, dec(H) * c - 20 * s) - 4


def jam_truth(cert):
    j = cert['jam']
    a, b = (F(v) for v in j['trap']['driver'])
    s, direction = F(j['start']['driver']), j['direction']
    if not a < b or not a <= s <= b or direction not in (1, -1):
        return False
    ok, free = within_limits(s), blocked(s)
    if ok is None or free is None:
        return None
    if not ok or free:
        return False
    return open_interval_meets_overlap(s, b) if direction > 0 else open_interval_meets_overlap(a, s)


def free_truth(cert):
    p = cert['free_passage']
    r0, r1, d = F(p['range'][0]), F(p['range'][1]), F(p['distance'])
    if d <= 0 or not r0 < r1:
        return False
    ok = (within_limits(r0), within_limits(r1))
    if None in ok:
        return None
    if not all(ok):
        return False
    if compare(dec(r1), THETA_C) is None:
        return None
    if dec(r1) > THETA_C:
        return False if compare(dec(r0), THETA_X) == -1 else None
    c = compare(distance_at(r1), dec(d))
    return None if c is None else c >= 0


def statement(cert):
    if cert['claim'] == 'jam':
        j = cert['jam']
        a, b = (F(v) for v in j['trap']['driver'])
        far = b if j['direction'] > 0 else a
        return "Driving 'lever' %s from within [%s, %s] rad, the motion cannot pass %s rad." % (
            'forward' if j['direction'] > 0 else 'backward', claim_number(a), claim_number(b), claim_number(far))
    p = cert['free_passage']
    return "Moving 'lever' from %s to %s rad, parts 'lever' and 'stop' never overlap and stay at least %s mm apart." % (
        claim_number(F(p['range'][0])), claim_number(F(p['range'][1])), claim_number(F(p['distance'])))


def truth(cert):
    return jam_truth(cert) if cert['claim'] == 'jam' else free_truth(cert)


def node_of(tree, path):
    for k in path[:-1]:
        tree = tree[k]
    return tree


def with_values(cert, changes):
    """the certificate with each (path under the claim, value) changed, the statement restated"""
    t = copy.deepcopy(cert)
    for path, value in changes:
        node_of(t[t['claim']], path)[path[-1]] = value if isinstance(value, int) else str(value)
    t['statement'] = statement(t)
    return t


def number_leaves(body, path=()):
    """the paths of every exact number under the claim (not the edges' indices)"""
    if isinstance(body, dict):
        return [p for k, v in body.items() if k not in ('edge', 'across') for p in number_leaves(v, path + (k,))]
    if isinstance(body, list):
        return [p for i, v in enumerate(body) for p in number_leaves(v, path + (i,))]
    return [path] if isinstance(body, str) and body and body[0] in '-0123456789' else []


def alterations(cert):
    claim = cert['claim']
    body = cert[claim]
    out = []
    for path in number_leaves(body):
        for what, v in altered_numbers(rng, node_of(body, path)[path[-1]]):
            out.append(('%s %s' % ('/'.join(map(str, path)), what), with_values(cert, [(path, v)])))
    crossings = []
    if claim == 'jam':
        out.append(('direction reversed', with_values(cert, [(('direction',), -body['direction'])])))
        far_index = 1 if body['direction'] > 0 else 0
        edge = THETA_C if body['direction'] > 0 else THETA_X
        # the far end and the start just before / past the overlap's edge
        for path in (('trap', 'driver', far_index), ('start', 'driver')):
            f = F(node_of(body, path)[path[-1]])
            other = rational_near(edge + (edge - dec(f)), 30)
            crossings.append((path, f, other, []))
    else:
        r1, d = F(body['range'][1]), F(body['distance'])
        exact = distance_at(r1)
        below, above = rational_near(exact - D(10) ** -40, 45), rational_near(exact + D(10) ** -40, 45)
        out += [('distance just below the exact distance', with_values(cert, [(('distance',), below)])),
                ('distance just above the exact distance', with_values(cert, [(('distance',), above)]))]
        last = ('boxes', len(body['boxes']) - 1, 'driver', 1)
        crossings.append((('range', 1), r1, rational_near(THETA_C, 30), [last]))
    for path, good, far, dragged in crossings:
        holds = lambda v: truth(with_values(cert, [(p, v) for p in [path] + dragged])) is True
        if not holds(good) or holds(far):
            continue
        lo, hi = bisect(holds, good, far)
        for what, v in (('just before', lo), ('just past', hi)):
            out.append(('%s %s the truth changes' % ('/'.join(map(str, path)), what), with_values(cert, [(path, v)])))
            if dragged:
                out.append(('%s %s the truth changes, the last box with it' % ('/'.join(map(str, path)), what),
                            with_values(cert, [(p, v) for p in [path] + dragged])))
    return out


def generated(case):
    """the arguments of one certify run: a jam over a trap across an edge of the overlap, or a free
    passage short of it"""
    kind = ('jam', 'free')[case % 2]
    if kind == 'jam':
        if rng.random() < 0.6:
            a, b = rng.uniform(-0.4, 0.04), rng.uniform(0.056, 0.6)
            return kind, ['--trap', '%r:%r' % (a, b), '--direction', '+1']
        a, b = rng.uniform(0.2, 0.82), rng.uniform(0.84, 2.0)
        return kind, ['--trap', '%r:%r' % (a, b), '--direction', '-1']
    r0 = rng.uniform(-0.5, 0.0)
    return kind, ['--from', '%r' % r0, '--to', '%r' % rng.uniform(r0 + 0.01, 0.044)]


batch = BatchVerifier(verify)   # one hipair-verify --list per 250 altered certificates (session 75)
findings, counts = 0, {'true accepted': 0, 'true rejected': 0, 'false rejected': 0, 'undecided': 0, 'base': 0}
for case in range(n):
    kind, args = generated(case)
    base = os.path.join(outdir, 'base-%d.json' % case)
    r = subprocess.run([hipair, 'certify', model, '--claim', kind, '--out', base, '--set', 'stop-gap=%s' % GAP] + args,
                       capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        print('case %d (stop-gap %s): %s %s not certified: %s' % (case, GAP, kind, ' '.join(args), r.stderr.strip()[:200]))
        findings += 1
        continue
    cert = json.load(open(base))
    findings += judged_certificate(batch, os.path.join(outdir, 'c%d.json' % case), model, cert, 'case %d (%s %s)' % (case, kind, ' '.join(args)),
                                   truth, statement, alterations, counts)
batch.flush()
findings += batch.findings
print('stop-gap %s: %s, %d findings' % (GAP, counts, findings))
sys.exit(1 if findings else 0)
