#!/usr/bin/env python3
"""Session 56 (hunt56): `hipair certify --claim jam`'s search against the driver's own motion
limits, on generated cases judged by a closed form (no code of the library or the verifier).
lever-stop.json's lever (nominal parameters: half-width 4, stop [20, 40] x [6, 16]) overlaps the
stop exactly for theta in (theta_c, theta_x), theta_c = atan(3/20) - atan(4/sqrt(1620)) ~ 0.049834
(the stop's corner (40, 6) on the lever's upper side) and theta_x = atan(4/5) + atan(4/sqrt(640))
~ 0.831557 (the corner (20, 16) on its lower side; tests/fuzz/motion_certificate_alterations.py).
Each case draws the lever's limits [lo, hi] (deg) and a start inside them (outside the overlap)
and a direction, then expects:
  * the contact ahead of the start within the limits (forward from below theta_c with hi beyond
    it, backward from above theta_x with lo below it): a certified jam whose cut lies at the
    contact, not before it and at most 9 search steps (0.002 rad) past it, which hipair-verify
    accepts;
  * else: exit 1, "no jam found: 'lever' reaches its motion limit L rad without being blocked",
    L the limit ahead (within 1e-9 rad), no file written;
  * a start beyond the limits: exit 2, one line naming the limits, no file written.
Until session 56 the search went through the limits (a jam 2 pi further on, or "cannot certify").
Prints each disagreement and "findings N"; exit 1 when N > 0.
usage: jam_search_limits.py HIPAIR HIPAIR_VERIFY REPO WORK_DIR SEED N"""
import math, os, random, re, subprocess, sys

hipair, verify, repo, work, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6])
rng = random.Random(seed)
os.makedirs(work, exist_ok=True)
THETA_C = math.atan(3 / 20) - math.atan(4 / math.sqrt(1620))
THETA_X = math.atan(4 / 5) + math.atan(4 / math.sqrt(640))
STEP = 0.002
text = open(os.path.join(repo, 'examples/models/lever-stop.json')).read()
assert '"limits": [-30, 120]' in text
findings = 0
kinds = {}


def away(value, points, margin):
    return all(abs(value - p) > margin for p in points)


for case in range(n):
    while True:
        lo, hi = rng.randint(-80, -2), rng.randint(1, 175)
        lo_r, hi_r = math.radians(lo), math.radians(hi)
        if away(lo_r, (THETA_C, THETA_X), 0.03) and away(hi_r, (THETA_C, THETA_X), 0.03):
            break
    beyond = case % 5 == 4
    while True:
        start = round(rng.uniform(lo_r - 1, hi_r + 1) if beyond else rng.uniform(lo_r, hi_r), 6)
        inside = lo_r < start < hi_r
        if beyond and not inside and away(start, (lo_r, hi_r), 1e-3):
            break
        if not beyond and inside and not (THETA_C - 0.005 < start < THETA_X + 0.005) and away(start, (lo_r, hi_r), 1e-3):
            break
    direction = rng.choice([1, -1])
    model = os.path.join(work, 'lever-%d.json' % case)
    open(model, 'w').write(text.replace('"limits": [-30, 120]', '"limits": [%d, %d]' % (lo, hi)))
    out = os.path.join(work, 'jam-%d.json' % case)
    if os.path.exists(out):
        os.remove(out)
    args = [hipair, 'certify', model, '--claim', 'jam', '--start', repr(start), '--direction', '%+d' % direction, '--out', out]
    p = subprocess.run(args, capture_output=True, text=True, timeout=300)
    err = p.stderr.strip()
    label = 'case %d (limits [%d, %d] deg, --start %r, direction %+d)' % (case, lo, hi, start, direction)
    problems = []
    if beyond:
        kind = 'start beyond the limits'
        if p.returncode != 2 or len(err.splitlines()) != 1 or 'outside the motion limits' not in err:
            problems.append('exit %d, not 2 with one line naming the limits: %s' % (p.returncode, err[:200]))
    else:
        contact = THETA_C if direction > 0 else THETA_X
        jam = (start < THETA_C and hi_r > THETA_C) if direction > 0 else (start > THETA_X and lo_r < THETA_X)
        if jam:
            kind = 'jam'
            if p.returncode != 0:
                problems.append('not certified (exit %d): %s' % (p.returncode, err[:200]))
            else:
                import json
                from fractions import Fraction as F
                c = json.load(open(out))['jam']
                a, b = map(F, c['trap']['driver'])
                far = float(b if direction > 0 else a)
                past = (far - contact) * direction
                if not (0 <= past <= 9 * STEP):
                    problems.append('the cut %.6f is %.6f rad past the contact %.6f' % (far, past, contact))
                v = subprocess.run([verify, out, model], capture_output=True, text=True, timeout=300)
                if v.returncode != 0:
                    problems.append('hipair-verify: %s' % (v.stdout + v.stderr).strip()[:200])
        else:
            kind = 'limit'
            limit = hi_r if direction > 0 else lo_r
            m = re.fullmatch(r"hipair: cannot certify: no jam found: 'lever' reaches its motion limit (\S+) rad without being blocked", err)
            if p.returncode != 1 or not m or abs(float(m.group(1)) - limit) > 1e-9:
                problems.append('exit %d, not 1 naming the limit %.12f: %s' % (p.returncode, limit, err[:200]))
    if kind != 'jam' and os.path.exists(out):
        problems.append('a certificate written')
    kinds[kind] = kinds.get(kind, 0) + 1
    if problems:
        findings += 1
        print('%s: %s' % (label, '; '.join(problems)), flush=True)
print('%s, findings %d' % (kinds, findings))
sys.exit(1 if findings else 0)
