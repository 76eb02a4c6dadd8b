#!/usr/bin/env python3
"""Session 49 (hunt49): "never interferes" tolerance certificates (`hipair tolerance
--certify-interference`, claim tolerance, property no_interference) with altered numbers against
hipair-verify, judged by an oracle of the test's own (the sibling of certificate_alterations.py
and motion_certificate_alterations.py).  The pair is lever-stop.json with the stop made a slider
along x (limits -5 .. 15 mm, so that it has a follower coordinate u): a lever of length L and width w
turning about (0, 0) by theta, and the rectangle [20 + u, 40 + u] x [h, h + 10], h = w/2 + g
(g: stop-gap).  Closed form, derived here and not taken from the library:
  * the lever is the segment from (0, 0) to L (cos theta, sin theta) grown by r = w/2 (the two
    sides, the tip's and the hub's half-discs);
  * for theta in [-0.6, 0.35], u in [-3, 14] and the parameters near nominal (L in [59, 61], w in
    [7, 9], g in [0, 4]) every vertex (a, y) of the stop projects into (0, L) on the lever's axis
    (a cos + y sin in (9, 58): a in [17, 54], y in [3.5, 18.5]) and the upper left vertex lies
    above the axis' line (tan theta <= 0.365 < 13.5 / 34 <= (h + 10) / (20 + u)), so the parts'
    distance is the least signed distance of the stop's vertices to that line minus r when that
    is positive, and the lever's axis crosses the stop when it is not: the closed parts are
    disjoint iff
        F = min(h cos theta - (20 + u) sin theta, h cos theta - (40 + u) sin theta) - w/2 > 0
    (the upper vertices are 10 cos theta further).  F = g cos - (w/2)(1 - cos) - a sin is
    increasing in g, decreasing in w, independent of L, least at a = 40 + u_max (sin > 0) or
    20 + u_min (sin < 0), and decreasing in theta over [-0.6, 0.35] (its derivative is
    -(h sin + a cos) < 0 there: a >= 17, h < 8.5).  (Checked once against a brute-force
    segment-to-rectangle distance at 400 000 random points of the domain: no disagreement; at
    theta = 0.5 the stop can lie wholly below the line and the form is wrong, hence 0.35.)  So the claim over parameters x driver range
    [t0, t1] x follower range [u0, u1] holds iff F > 0 at g = g_min, w = w_max, theta = t1 and u
    = u1 (t1 > 0) or u0 (t1 < 0); where it fails that corner is an exact counterexample.
Truth, at 80 digits (a comparison closer than 10^-70: undecided): the parameter ranges are the
hull of the certificate's box and scale x the tolerances (the statement names the scale, the
leaves cover the box: a claim true over both is true whatever the verifier says of their
disagreement), a parameter not in `varied` nominal; ranges outside the domain above: undecided.
Each number of the claim is altered (sign, +-1/den, the last digit, x(1 + 10^-k): the range, the
follower range, the scale, the box, every leaf bound and split value), and moved across the
truth's boundary: the driver range's end, the follower range's far end and the scale (box with
it) 2^-60 before / past the point where the parts touch, with and without the leaves covering the
extension; a leaf dropped; a varied parameter dropped.  The statement is restated for the altered
data.  A false certificate accepted (exit 0) is a finding; so is an exit other than 0/1/3 or more
than one line of output.  True certificates rejected are counted (the verifier is sound, not
complete).  (Session 51: for a no_jam certificate an 'unproven' verdict, exit 3, on a false claim
is a finding too: it still asserts checks 1-6, the named sides apart over every leaf.)
Session 50 (hunt50): one case in three is a second pair, the lever against a 2 x 2 mm block
[u, u + 2] x [-1, 1] sliding along the lever's axis (limits -20 .. 100 mm), where the follower's
motion moves the parts' distance one for one and the block fits inside the lever.  Its truth is
exact in rationals: the lever is the segment (0, 0) .. L (cos theta, sin theta) grown by r = w/2
(r > 1), so (a) for u0 > L + r the block lies outside the disc of radius L + r about the pivot that
holds the lever: apart for every theta; (b) for u1 + 2 < -r and |theta| <= 3/2 (cos > 0) every
point of the lever has x >= -r: apart; (c) at theta = 0 the lever is the stadium [0, L] x [-r, r]
with round ends, and the block meets it iff -r - 2 <= u <= L + r (|y| <= 1 < r), so a claim whose
driver range holds 0 and whose follower range meets [-r - 2, L + r] at the largest L and r is
false; anything else is undecided.  Its crossings are the follower range's near end (the block
nearing the tip) and the scale; its own alteration shifts the follower range and every leaf's
follower interval into the lever ([6, 36] mm, the block wholly inside for |theta| <= 0.06: no
boundary meets, only the ray-parity test at the leaf's centre finds the interference).
Also session 50: one case in four is a "no jam" tolerance certificate (`hipair tolerance --certify`,
property no_jam) on scotch-yoke.json's crank:yoke pair with the slot made tight (width 10.04 mm
for 10.4, so that the channel closes at scale 1 and certificates near the crossing stay small): the crank pin (radius r at crank radius R)
in the yoke's slot (width s, centred on x = R + offset, half-length 37), so the follower's free
offsets at crank angle theta are R cos theta - R + [-(s/2 - r), s/2 - r] whatever theta: the
channel between the slot's walls never closes iff s - 2r > 0 at the box's least s and largest r
(exact in rationals; with the pin inside the slot's length, R + r < 37, else undecided).  Its
crossing is the scale (0.04 - 0.04 x scale: 1), from certificates at 0.5 .. 0.97.
Session 51 (hunt51): every crossing of a "no jam" certificate is also judged with every leaf's
brackets widened by 2 mm on both sides (re-fitted: each side's contact function is least where the
wall's line passes through the pin's centre, r = 5 mm (yoke) or 5 r / 4 (V slot) beyond its root
on the far side, and grows on the channel's side, so the wider bracket still holds one sign
change, certain over the leaf, and the function stays monotone between the witness and its end;
the centre intervals widened by 1 mm alike, since moving the driver range's end moves a leaf's
centre) and
once more with second-order margins of 10^-30 claimed on every witness: past the crossing the old
brackets fail their sign test before the witness checks are reached (session 50: four mutated
witness checks went unseen), the re-fitted ones do not.  And one case in eight (in place of a
yoke case) is a yoke with a V-shaped slot: walls through (R -+ s/2, h) at slope 3/4 outwards
(x = R -+ (s/2 + 3/4 (y - h))), apex at y = h - 2 s/3, so the pin (centre R (cos, sin)) fits
where the walls are 2 r sqrt(1 + 9/16) = 5 r / 2 apart along x: the follower's free offsets
have width W = s + 3/2 (R sin theta - h) - 5 r / 2, which grows with theta (0.25 <= theta0 <
theta1 <= 1.3: the tangent points, 3 below the pin's centre, lie between the apex and the top y = 37),
with s and with R: no jam iff W > 0 at theta0, s_min, R_min, r_max, a corner of box x range; its
crossings are the driver range's start and the scale, certificates 0.002 .. 0.03 rad above the
crossing at scale 1 (each case its own model file, the yoke's initial offset R cos theta0 - R).
usage: tolerance_certificate_alterations.py HIPAIR HIPAIR_VERIFY REPO OUTDIR SEED N_CERTIFICATES"""
import copy, json, os, random, subprocess, sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_oracle import D, sin_cos, compare, dec, bisect, altered_numbers, judged_certificate, BatchVerifier

hipair, verify, repo, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6])
rng = random.Random(seed)
os.makedirs(outdir, exist_ok=True)

model_json = json.load(open(os.path.join(repo, 'examples/models/lever-stop.json')))
model_json['name'] = 'lever-and-sliding-stop'
model_json['parts'][1]['motion'] = {'translation': {'direction': [1, 0], 'limits': [-5, 15]}}
model = os.path.join(outdir, 'lever-sliding-stop.json')
json.dump(model_json, open(model, 'w'), indent=1)
model_json['name'] = 'lever-and-sliding-block'
model_json['parts'][1] = {'name': 'block', 'motion': {'translation': {'direction': [1, 0], 'limits': [-20, 100]}},
                          'loops': [{'start': [0, -1], 'edges': [{'line_to': [2, -1]}, {'line_to': [2, 1]},
                                                                 {'line_to': [0, 1]}, {'line_to': [0, -1]}]}]}
block_model = os.path.join(outdir, 'lever-sliding-block.json')
json.dump(model_json, open(block_model, 'w'), indent=1)
NOMINAL = {'lever-length': F(60), 'lever-width': F(8), 'stop-gap': F(2)}
TOLERANCE = {'lever-length': (F(-1, 20), F(1, 20)), 'lever-width': (F(-1, 50), F(1, 50)), 'stop-gap': (F(-1, 10), F(1, 10))}
DOMAIN = {'lever-length': (F(59), F(61)), 'lever-width': (F(7), F(9)), 'stop-gap': (F(0), F(4))}
VSLOT_NOMINAL = {'crank-radius': F(30), 'pin-radius': F(5), 'slot-width': F(1255, 100)}
VSLOT_HEIGHT = F(10)


def vslot_model(path, initial):
    """the V-slot yoke (docstring) with the yoke's initial offset `initial` (text)"""
    m = {'hipair': 1, 'name': 'v-slot-yoke', 'units': {'length': 'mm', 'angle': 'rad'},
         'parameters': {'crank-radius': {'nominal': 30, 'tolerance': 0.02}, 'pin-radius': {'nominal': 5, 'tolerance': 0.01},
                        'slot-width': {'nominal': 12.55, 'tolerance': 0.02}, 'slot-height': {'nominal': 10}},
         'parts': [{'name': 'crank', 'motion': {'rotation': {'pivot': [0, 0]}}, 'initial': {'angle': 0},
                    'features': [{'pin': {'center': ['crank-radius', 0], 'radius': 'pin-radius'}}]},
                   {'name': 'yoke', 'motion': {'translation': {'direction': [1, 0], 'limits': [-65, 5]}},
                    'initial': {'offset': initial},
                    'loops': [{'label': 'frame', 'start': ['crank-radius - 40', -45], 'edges': [
                                  {'line_to': ['crank-radius + 40', -45]}, {'line_to': ['crank-radius + 40', 45]},
                                  {'line_to': ['crank-radius - 40', 45]}, {'line_to': ['crank-radius - 40', -45]}]},
                              {'label': 'v slot', 'start': ['crank-radius', 'slot-height - slot-width*2/3'], 'edges': [
                                  {'line_to': ['crank-radius + slot-width/2 + 0.75*(37 - slot-height)', 37], 'label': 'wall R'},
                                  {'line_to': ['crank-radius - slot-width/2 - 0.75*(37 - slot-height)', 37], 'label': 'top'},
                                  {'line_to': ['crank-radius', 'slot-height - slot-width*2/3'], 'label': 'wall L'}]}]}],
         'pairs': [{'parts': ['crank', 'yoke']}]}
    json.dump(m, open(path, 'w'), indent=1)


model_json = json.load(open(os.path.join(repo, 'examples/models/scotch-yoke.json')))
model_json['name'] = 'scotch-yoke-tight'
model_json['parameters']['slot-width']['nominal'] = 10.04
yoke_model = os.path.join(outdir, 'scotch-yoke-tight.json')
json.dump(model_json, open(yoke_model, 'w'), indent=1)
NOMINAL.update({'crank-radius': F(30), 'pin-radius': F(5), 'slot-width': F(1004, 100)})
TOLERANCE.update({'crank-radius': (F(-1, 50), F(1, 50)), 'pin-radius': (F(-1, 100), F(1, 100)), 'slot-width': (F(-1, 50), F(1, 50))})


def parameter_ranges(t, nominal=NOMINAL):
    """{name: (lo, hi)} of the claim's parameters (the hull of box and scale x tolerance); None
    when a name or the sizes are not the model's"""
    scale = F(t['scale'])
    ranges = dict((k, (v, v)) for k, v in nominal.items())
    if len(t['box']) != len(t['varied']) or len(set(t['varied'])) != len(t['varied']):
        return None
    for name, (lo, hi) in zip(t['varied'], t['box']):
        if name not in nominal:
            return None
        lo, hi = F(lo), F(hi)
        e_lo, e_hi = scale * TOLERANCE[name][0], scale * TOLERANCE[name][1]
        ranges[name] = (nominal[name] + min(lo, e_lo, hi, e_hi), nominal[name] + max(lo, e_lo, hi, e_hi))
    return ranges


def clearance(t1, u0, u1, w, g):
    """F (above) at the worst corner, 80 digits"""
    s, c = sin_cos(dec(t1))
    a = 40 + u1 if t1 > 0 else 20 + u0
    return (dec(w / 2 + g)) * c - dec(a) * s - dec(w / 2)


def claim_data(cert, follower, driver='lever', prop='no_interference', nominal=NOMINAL):
    """(t0, t1, u0, u1, parameter ranges) of a well-formed claim on driver:follower (u0 = u1 = 0
    for no_jam), else None"""
    t = cert['tolerance']
    if t['property'] != prop or t['driver'] != driver or t['follower'] != follower:
        return None
    t0, t1 = (F(v) for v in t['range'])
    u0, u1 = (F(v) for v in t['follower_range']) if prop == 'no_interference' else (F(0), F(0))
    ranges = parameter_ranges(t, nominal)
    if ranges is None or not t0 <= t1 or not u0 <= u1:
        return None
    return t0, t1, u0, u1, ranges


def yoke_truth(cert):
    """the crank pin in the yoke's slot: no jam iff s - 2 r > 0 over the box (the docstring)"""
    data = claim_data(cert, 'yoke', 'crank', 'no_jam')
    if data is None:
        return False
    ranges = data[4]
    if ranges['crank-radius'][1] + ranges['pin-radius'][1] >= 37 or ranges['pin-radius'][0] <= 0:
        return None
    return ranges['slot-width'][0] - 2 * ranges['pin-radius'][1] > 0


def vslot_truth(cert):
    """the pin in the V slot: no jam iff W > 0 at the corner (theta0, s_min, R_min, r_max), the
    docstring; 80 digits"""
    data = claim_data(cert, 'yoke', 'crank', 'no_jam', VSLOT_NOMINAL)
    if data is None:
        return False
    t0, t1, _, _, ranges = data
    if not (F(1, 4) <= t0 and t1 <= F(13, 10)) or ranges['pin-radius'][0] <= 0 or ranges['crank-radius'][0] <= 0:
        return None
    s, c = sin_cos(dec(t0))
    width = dec(ranges['slot-width'][0]) + D(3) / 2 * (dec(ranges['crank-radius'][0]) * s - dec(VSLOT_HEIGHT)) \
        - D(5) / 2 * dec(ranges['pin-radius'][1])
    c = compare(width, D(0))
    return None if c is None else c > 0


def block_truth(cert):
    """the lever against the sliding block, exact (the docstring's (a), (b), (c))"""
    data = claim_data(cert, 'block')
    if data is None:
        return False
    t0, t1, u0, u1, ranges = data
    length, r = ranges['lever-length'][1], ranges['lever-width'][1] / 2
    if ranges['lever-width'][0] <= 2 or ranges['lever-length'][0] <= 0:
        return None
    if u0 > length + r or (u1 + 2 < -r and F(-3, 2) <= t0 and t1 <= F(3, 2)):
        return True
    if t0 <= 0 <= t1 and u0 <= length + r and u1 >= -r - 2:
        return False
    return None


def truth(cert):
    data = claim_data(cert, 'stop')
    if data is None:
        return False
    t0, t1, u0, u1, ranges = data
    if not (F(-6, 10) <= t0 and t1 <= F(7, 20) and -3 <= u0 and u1 <= 14 and
            all(DOMAIN[k][0] <= ranges[k][0] and ranges[k][1] <= DOMAIN[k][1] for k in DOMAIN)):
        return None
    c = compare(clearance(t1, u0, u1, ranges['lever-width'][1], ranges['stop-gap'][0]), D(0))
    if c is None:
        return None
    return c > 0


def statement(cert):
    t = cert['tolerance']
    if t['property'] == 'no_jam':
        return ("For every value of the %d varied parameters within %s x their tolerance ranges, driving '%s' over [%s, %s], "
                "the channel of '%s' between its two contact sides never closes: the pair does not jam." %
                (len(t['varied']), F(t['scale']), t['driver'], F(t['range'][0]), F(t['range'][1]), t['follower']))
    return ("For every value of the %d varied parameters within %s x their tolerance ranges, with 'lever' over "
            "[%s, %s] and '%s' over [%s, %s], the two parts are apart: they never interfere." %
            (len(t['varied']), F(t['scale']), F(t['range'][0]), F(t['range'][1]), t['follower'],
             F(t['follower_range'][0]), F(t['follower_range'][1])))


def restated(t):
    t['statement'] = statement(t)
    return t


def number_leaves(body, path=()):
    """the paths of every exact number under the claim (not the tree's leaf indices)"""
    if isinstance(body, dict):
        return [p for k, v in body.items() for p in number_leaves(v, path + (k,))]
    if isinstance(body, list):
        return [p for i, v in enumerate(body) for p in number_leaves(v, path + (i,))]
    return [path] if isinstance(body, str) and body and body[0] in '-0123456789' else []


def node_of(tree, path):
    for k in path[:-1]:
        tree = tree[k]
    return tree


def moved(cert, where, value, drag):
    """the certificate with the claim's bound `where` (('range', 1), ('follower_range', 1) or
    ('scale',)) set to value; with drag, every leaf bound equal to the old one moved with it, so
    that the leaves still cover the claim; the scale's box moved with it unless drag is 'box kept'"""
    c = copy.deepcopy(cert)
    t = c['tolerance']
    if where == ('scale',):
        old = F(t['scale'])
        t['scale'] = str(value)
        if drag == 'box kept':
            return restated(c)
        t['box'] = [[str(value * TOLERANCE[p][0]), str(value * TOLERANCE[p][1])] for p in t['varied']]
        if drag:
            for leaf in t['leaves']:
                for i, p in enumerate(t['varied']):
                    for e in (0, 1):
                        if F(leaf['parameters'][i][e]) == old * TOLERANCE[p][e]:
                            leaf['parameters'][i][e] = str(value * TOLERANCE[p][e])
        return restated(c)
    key, end = where
    old = F(t[key][end])
    t[key][end] = str(value)
    if drag:
        for leaf in t['leaves']:
            field = 'driver' if key == 'range' else 'follower'
            if F(leaf[field][end]) == old:
                leaf[field][end] = str(value)
    return restated(c)


def alterations(cert, truth, crossings):
    """every alteration of cert: its numbers, a leaf or a varied parameter dropped, and each of
    crossings ((where, far): a claim bound moved from its value towards far) bisected to 2^-60 of
    the point where the truth changes"""
    t = cert['tolerance']
    out = []
    for path in number_leaves(t):
        for what, v in altered_numbers(rng, node_of(t, path)[path[-1]]):
            a = copy.deepcopy(cert)
            node_of(a['tolerance'], path)[path[-1]] = str(v)
            out.append(('%s %s' % ('/'.join(map(str, path)), what), restated(a)))
    for i in range(len(t['leaves'])):
        a = copy.deepcopy(cert)
        del a['tolerance']['leaves'][i]
        out.append(('leaf %d dropped' % i, a))
    for i in range(len(t['varied'])):
        a = copy.deepcopy(cert)
        del a['tolerance']['varied'][i], a['tolerance']['box'][i]
        for leaf in a['tolerance']['leaves']:
            del leaf['parameters'][i]
        out.append(('varied %s dropped' % t['varied'][i], restated(a)))
    for where, far in crossings:
        good = F(node_of(t, where)[where[-1]])
        holds = lambda v: truth(moved(cert, where, v, True)) is True
        if not holds(good) or truth(moved(cert, where, far, True)) is not False:
            continue
        lo, hi = bisect(holds, good, far)
        for what, v in (('just before', lo), ('just past', hi)):
            for drag in (False, True) + (('box kept',) if where == ('scale',) else ()):
                out.append(('%s %s the truth changes%s' % ('/'.join(map(str, where)), what,
                                                          {False: '', True: ', the leaves with it',
                                                           'box kept': ', box and leaves kept'}[drag]),
                            moved(cert, where, v, drag)))
            if t['property'] == 'no_jam':
                for margins in (False, True):
                    out.append(('%s %s the truth changes, the leaves with it, brackets widened%s' %
                                ('/'.join(map(str, where)), what, ', margins claimed' if margins else ''),
                                refitted(moved(cert, where, v, True), margins)))
    return out


def refitted(cert, margins):
    """cert with every leaf's brackets widened by 2 mm on both sides and its centre intervals by 1 mm (the docstring: still one
    certain sign change each), with margins also 10^-30 claimed for each side on every witness"""
    for leaf in cert['tolerance']['leaves']:
        for side in ('lower', 'upper'):
            b = leaf[side]['bracket']
            leaf[side]['bracket'] = [str(F(b[0]) - 2), str(F(b[1]) + 2)]
            c = leaf[side]['centre']
            leaf[side]['centre'] = [str(F(c[0]) - 1), str(F(c[1]) + 1)]
        if margins and 'witness' in leaf:
            leaf['witness']['second_order_margins'] = [str(F(1, 10 ** 30))] * 2
    return cert


def block_alterations(cert):
    """alterations() with the block's crossings, and the claim shifted into the lever"""
    out = alterations(cert, block_truth, ((('follower_range', 0), F(60)), (('scale',), F(19))))
    t = cert['tolerance']
    shift = F(rng.randrange(60, 360), 10) - F(t['follower_range'][0])
    c = copy.deepcopy(cert)
    c['tolerance']['follower_range'] = [str(F(v) + shift) for v in t['follower_range']]
    for leaf in c['tolerance']['leaves']:
        leaf['follower'] = [str(F(v) + shift) for v in leaf['follower']]
    out.append(('follower range and leaves shifted by %s (the block inside the lever)' % shift, restated(c)))
    return out


def stop_alterations(cert):
    return alterations(cert, truth, ((('range', 1), F(7, 20)), (('follower_range', 1), F(14)), (('scale',), F(19))))


def yoke_alterations(cert):
    """alterations() with the scale's crossing, and the scale put exactly at 1, where the slot's
    least width is exactly twice the pin's largest radius (10.02 = 2 x 5.01: the pin touches both
    walls at the box's corner, the channel is closed), the leaves dragged and re-fitted"""
    out = alterations(cert, yoke_truth, ((('scale',), F(6, 5)),))
    for margins in (False, True):
        out.append(('scale exactly 1 (the pin touches both walls), the leaves with it, brackets widened%s' %
                    (', margins claimed' if margins else ''), refitted(moved(cert, ('scale',), F(1), True), margins)))
    return out


def vslot_alterations(cert):
    return alterations(cert, vslot_truth, ((('range', 0), F(1, 4)), (('scale',), F(19))))


def generated_vslot(path):
    """the arguments of one certify run on the V-slot yoke, its model written to path: scale 1, a
    driver range of 0.01 .. 0.05 rad starting 0.002 .. 0.03 rad above where the channel closes at
    the box's corner (theta_c = 0.33995...), the yoke starting on the channel's middle"""
    t0 = F(34, 100) + F(rng.randrange(2, 30), 1000)
    t1 = t0 + F(rng.randrange(1, 5), 100)
    s, c = sin_cos(dec(t0))
    vslot_model(path, '%.9f' % (30 * c - 30))
    return ['--certify-scale', '1', '--range', '%s:%s' % (t0, t1)]


def generated_yoke():
    """the arguments of one certify run on the tight scotch yoke: a scale 0.5 .. 0.97 and a driver
    range of 0.02 .. 0.1 rad starting within 0.3 rad of 0 (the analysis starts the yoke at its initial
    offset at the range's start: from 2.5 rad on the pin is then outside the slot, "not bounded on
    both sides")"""
    scale = rng.choice([F(1, 2), F(9, 10), F(19, 20), F(97, 100)])
    t0 = F(rng.randrange(-30, 30), 100)
    t1 = t0 + F(rng.randrange(2, 10), 100)
    return ['--certify-scale', str(scale), '--range', '%s:%s' % (t0, t1)]


def generated_block(narrow):
    """the arguments of one certify run on the block: a scale, a driver range about 0 within
    |theta| <= 0.06 and a follower range beginning 0.05 .. 1 mm past the lever's reach; every
    other one (narrow) within |theta| <= 0.002, 0.2 .. 0.6 mm from 0.05 .. 0.3 mm past the reach,
    where a leaf's mean-value form separates the parts and the follower's term in it decides the
    crossing"""
    scale = F(rng.choice([1, 1, 2, 5]))
    reach = NOMINAL['lever-length'] + scale * TOLERANCE['lever-length'][1] + (NOMINAL['lever-width'] + scale * TOLERANCE['lever-width'][1]) / 2
    if narrow:
        t0, t1 = -F(rng.randrange(1, 20), 10000), F(rng.randrange(1, 20), 10000)
        u0 = reach + F(rng.randrange(5, 30), 100)
        u1 = u0 + F(rng.randrange(2, 7), 10)
    else:
        t0, t1 = -F(rng.randrange(1, 60), 1000), F(rng.randrange(1, 60), 1000)
        u0 = reach + F(rng.randrange(5, 100), 100)
        u1 = u0 + F(rng.choice([0, rng.randrange(1, 40)]), 10)
    return ['--certify-scale', str(scale), '--range', '%s:%s' % (t0, t1), '--follower-range', '%s:%s' % (u0, u1)]


def generated():
    """the arguments of one certify run: a scale, a driver range (mostly ending just past 0, where
    the follower's and the scale's crossings exist) and a follower range whose worst corner keeps
    the parts at least 0.15 mm apart"""
    while True:
        scale = F(rng.choice([1, 1, 2, 5]))
        t0 = F(rng.randrange(-55, 0), 100)
        t1 = t0 + F(rng.randrange(5, 50), 100) if rng.random() < 0.25 else F(rng.randrange(25, 46), 1000)
        u0 = F(rng.randrange(-25, 20), 10)
        u1 = u0 + F(rng.choice([0, rng.randrange(1, 30)]), 10)
        if t1 > F(7, 20):
            continue
        w, g = NOMINAL['lever-width'] + scale * TOLERANCE['lever-width'][1], NOMINAL['stop-gap'] + scale * TOLERANCE['stop-gap'][0]
        if clearance(t1, u0, u1, w, g) > D('0.15'):
            return ['--certify-scale', str(scale), '--range', '%s:%s' % (t0, t1), '--follower-range', '%s:%s' % (u0, u1)]


batch = BatchVerifier(verify)   # one hipair-verify --list per 250 altered certificates (session 75)
findings, counts = 0, {'true accepted': 0, 'true rejected': 0, 'false rejected': 0, 'undecided': 0, 'base': 0}
# kind: (model, pair, certify option, certificate file, generator, truth, alterations)
KINDS = {'stop': (model, 'lever:stop', '--certify-interference', 'interference-certificate.json', generated, truth, stop_alterations),
         'block': (block_model, 'lever:block', '--certify-interference', 'interference-certificate.json', generated_block,
                   block_truth, block_alterations),
         'yoke': (yoke_model, 'crank:yoke', '--certify', 'tolerance-certificate.json', generated_yoke, yoke_truth, yoke_alterations),
         'vslot': (None, 'crank:yoke', '--certify', 'tolerance-certificate.json', generated_vslot, vslot_truth, vslot_alterations)}
only = os.environ.get('ALTERATIONS_KINDS')   # e.g. "yoke,vslot": only those cases (mutant runs by hand)
for case in range(n):
    kind = ('stop', 'stop', 'block', 'yoke', 'stop', 'stop', 'block', 'vslot')[case % 8]
    if only and kind not in only.split(','):
        continue
    pair_model, pair, option, name, generator, pair_truth, pair_alterations = KINDS[kind]
    if kind == 'vslot':
        pair_model = os.path.join(outdir, 'v-slot-%d.json' % case)
        args = generator(pair_model)
    else:
        args = generated_block(case % 8 == 2) if kind == 'block' else generator()
    out = os.path.join(outdir, 'base-%d' % case)
    r = subprocess.run([hipair, 'tolerance', pair_model, option, '--pair', pair, '--out', out, '--quiet'] + args,
                       capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        print('case %d: %s not certified: %s' % (case, ' '.join(args), (r.stdout + r.stderr).strip()[-300:]))
        findings += 1
        continue
    cert = json.load(open(os.path.join(out, name)))
    findings += judged_certificate(batch, os.path.join(outdir, 'c%d.json' % case), pair_model, cert,
                                   'case %d (%s, %s)' % (case, kind, ' '.join(args)), pair_truth, statement, pair_alterations, counts,
                                   option == '--certify')
batch.flush()
findings += batch.findings
print('%s, %d findings' % (counts, findings))
sys.exit(1 if findings else 0)
