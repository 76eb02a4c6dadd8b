#!/usr/bin/env python3
"""Session 47 (hunt47): `analyze`'s contact list against the exact overlap predicate.
Generated variants (parameters drawn within their tolerances with --set) of the lever driving a
turning stop (lever-stop.json with the stop on a pivot), the ratchet, the cam follower and the
Geneva drive are analysed (`analyze --out --no-pictures`); at generated grid samples of
kinematics.csv away from the contact changes:
  * a sample in a contact piece (the report names its contacts and its side s: the contact lies on
    the upper (+1) or lower (-1) side of the follower's play): the follower moved by s*delta into
    the contact overlaps the driver (certify --claim interference + hipair-verify: a point strictly
    inside both, exact), and moved by -s*delta it is apart (certify --claim clearance + verify);
  * a sample of a free dwell (no contact named): the parts are apart there (clearance certified
    and verified): no unreported contact.
delta = 10^-6 rad or mm is far above the CSV's rounding (10^-9 deg or mm) and far below any
play of these mechanisms at the chosen samples (a sample is taken only where the reported play
exceeds 10 delta).
Session 62 (hunt62): an optional MODELS argument (comma-separated names) chooses among them and
`gears`: spur-gears.json with tooth counts drawn from 6..40 each (the backlash drawn within its
tolerance, the exact centre distance m (z1 + z2) / 2).
usage: analyze_contact_sides.py HIPAIR HIPAIR_VERIFY REPO OUTDIR SEED N_MODELS [MODELS]"""
import csv, json, math, os, random, subprocess, sys

hipair, verify, repo, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6])
rng = random.Random(seed)
os.makedirs(outdir, exist_ok=True)
DELTA = 1e-6


def run(args):
    r = subprocess.run(args, capture_output=True, text=True, timeout=300)
    return r.returncode, (r.stdout + r.stderr).strip()


def turning_stop(path):
    t = json.load(open(os.path.join(repo, 'examples/models/lever-stop.json')))
    t['parts'][1]['motion'] = {'rotation': {'pivot': [45, 30]}}
    t['parts'][1]['initial'] = {'angle': 0}
    json.dump(t, open(path, 'w'), indent=1)
    return path


def gears(path):
    t = json.load(open(os.path.join(repo, 'examples/models/spur-gears.json')))
    t['parameters']['teeth-1'] = {'nominal': rng.randrange(6, 41)}
    t['parameters']['teeth-2'] = {'nominal': rng.randrange(6, 41)}
    json.dump(t, open(path, 'w'), indent=1)
    return path


MODELS = [('turning-stop', lambda p: turning_stop(p), ['--range', '0:60']),
          ('ratchet', lambda p: os.path.join(repo, 'examples/models/ratchet.json'), ['--range', '0:40']),
          ('cam-follower', lambda p: os.path.join(repo, 'examples/models/cam-follower.json'), ['--range', '0:180']),
          ('geneva', lambda p: os.path.join(repo, 'examples/models/geneva.json'), ['--range', '130:240'])]
if len(sys.argv) > 7:
    MODELS = [m for m in MODELS + [('gears', gears, ['--range', '0:40'])] if m[0] in sys.argv[7].split(',')]


def variant_sets(model):
    """--set NAME=V for each toleranced parameter, V drawn within its tolerance (a rational)"""
    t = json.load(open(model))
    sets = []
    for name, p in t.get('parameters', {}).items():
        if not isinstance(p, dict) or 'tolerance' not in p or not isinstance(p['nominal'], (int, float)):
            continue
        tol = p['tolerance']
        lo, hi = (-tol, tol) if isinstance(tol, (int, float)) else (tol[0], tol[1])
        k = rng.randrange(0, 11)
        sets += ['--set', '%s=%s' % (name, format(p['nominal'] + lo + (hi - lo) * k / 10, '.6f'))]
    return sets


findings, checks = 0, 0
tally = {}
for case in range(n):
    name, make, options = MODELS[case % len(MODELS)]
    model = make(os.path.join(outdir, '%s-%d.json' % (name, case)))
    sets = variant_sets(model) if rng.random() < 0.75 else []
    out = os.path.join(outdir, 'out-%d' % case)
    rc, text = run([hipair, 'analyze', model, '--no-pictures', '--quiet', '--out', out] + options + sets)
    if rc != 0:
        print('case %d %s %s: analyze exit %d: %s' % (case, name, ' '.join(sets), rc, text[-300:]))
        findings += 1
        continue
    report = json.load(open(os.path.join(out, 'report.json')))
    driver = report['driver']['part']
    unit = report['units']['angle']
    to_rad = (lambda v: math.radians(v)) if unit == 'deg' else (lambda v: v)
    rows = list(csv.DictReader(open(os.path.join(out, 'kinematics.csv'))))
    events = [e['at']['value'] for e in report['events']]
    for f in report['followers']:
        follower, rotates = f['part'], f['motion'] == 'rotation'
        columns = [c for c in rows[0] if c.startswith(follower + '_')] if rows else []
        pos_col = next((c for c in columns if c in (follower + '_angle_deg', follower + '_angle_rad', follower + '_offset_mm')), None)
        play_col = next((c for c in columns if c.startswith(follower + '_play')), None)
        if pos_col is None or play_col is None:
            print('case %d %s: no position/play column for %s in %s' % (case, name, follower, list(rows[0])))
            findings += 1
            continue
        drv_col = next(c for c in rows[0] if c.startswith('driver_'))
        step = abs(float(rows[1][drv_col]) - float(rows[0][drv_col])) if len(rows) > 1 else 1
        picked = [r for r in rows if float(r[play_col]) > 10 * (math.degrees(DELTA) if rotates and unit == 'deg' else DELTA)
                  and all(abs(float(r[drv_col]) - e) > 1.5 * step for e in events)]
        rng.shuffle(picked)
        for r in picked[:4]:
            d = float(r[drv_col])
            piece = next((p for p in report['pieces'] if p['part'] == follower and
                          p['start']['value'] < d < p['end']['value']), None)
            if piece is None:
                continue
            p = to_rad(float(r[pos_col])) if rotates else float(r[pos_col])
            at_driver = '%s=%r' % (driver, to_rad(d))
            what = 'case %d %s %s: driver %s %s, %s at %s (%s)' % (case, name, ' '.join(sets), driver, d, follower,
                                                                   r[pos_col], r[follower + '_contacts'] or 'free')
            cert = os.path.join(outdir, 'c.json')
            tries = []
            if piece['contacts'] and piece['side'] in (1, -1):
                s = piece['side'] * (-1 if os.environ.get('CONTACT_SIDES_MUTANT') == 'side' else 1)
                tries = [('interference', p + s * DELTA), ('clearance', p - s * DELTA)]
            elif not piece['contacts'] and piece['type'] == 'dwell':
                tries = [('clearance', p)]
            for claim, q in tries:
                checks += 1
                tally[claim] = tally.get(claim, 0) + 1
                args = [hipair, 'certify', model, '--claim', claim, '--pair', '%s:%s' % (driver, follower),
                        '--at', at_driver, '--at', '%s=%r' % (follower, q), '--out', cert] + sets
                rc, text = run(args)
                if rc == 0:
                    rc, text = run([verify, cert, model])
                    if rc != 0:
                        text = 'hipair-verify: ' + text
                if rc != 0:
                    findings += 1
                    print('%s: %s at %s %r not certified: %s' % (what, claim, follower, q, text[-250:]), flush=True)
print('%d checks %s, %d findings' % (checks, tally, findings))
sys.exit(1 if findings else 0)
