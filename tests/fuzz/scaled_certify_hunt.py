#!/usr/bin/env python3
"""Session 62 (hunt62): certify and hipair-verify at every scale, judged by scale covariance.

Each example (examples/models/NAME.json) is scaled exactly by each factor (tests/fuzz/scale_model.py;
angles unchanged, every length times S) and for each declared pair `hipair certify` is asked for
a clearance and an interference at the initial configuration, free passage over the driver's
turn (a rotating driver) and a jam (the default search; a translating driver's step and travel
times S). Oracles:
  * the truth of each claim is the same at every scale (angles are unchanged, lengths scale), so
    the certify exit code must be the same at every scale as at S = 1 (a difference is printed
    as a finding to look at);
  * every certificate written verifies (exit 0) against its own scaled model;
  * a clearance certificate's distance, moved up by 2^-k of itself (k = 4, 30, 64), gets the
    same verdict at every scale (the claim "at least d(1 + 2^-k)" is as true at S as at 1);
  * (--mutants N) N numbers of a claim's data, each moved by the same relative amount
    (1 +- 2^-k, k = 3, 30, 80) in the certificate at S and at 1 when both have the same shape: the
    claim's data are accepted (valid, or refused only for the statement, which is checked last)
    at S exactly when at 1 (the two claims are one claim in other units);
  * no signal, no crash text, at most one line of error.
usage: scaled_certify_hunt.py HIPAIR HIPAIR_VERIFY REPO WORK MODELS SCALES [--mutants N --seed S]
  MODELS  comma-separated names; SCALES comma-separated factors (1 is always run first)"""
import json, os, random, re, subprocess, sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems

hipair, verify, repo, work, models, scales = sys.argv[1:7]
options = dict(zip(sys.argv[7::2], sys.argv[8::2]))
mutants = int(options.get('--mutants', 0))
# the seed: --seed, else HIPAIR_TEST_SEED (a number, or "random"), else 62 (printed on a finding)
seed_text = options.get('--seed') or os.environ.get('HIPAIR_TEST_SEED') or '62'
seed = random.SystemRandom().randrange(2 ** 32) if seed_text == 'random' else int(seed_text)
rng = random.Random(seed)
scales = ['1'] + [s for s in scales.split(',') if s != '1']
os.makedirs(work, exist_ok=True)
findings = 0


def finding(text):
    global findings
    findings += 1
    print('  FINDING:', text)


def factor(text):
    m = re.fullmatch(r'1e(-?\d+)', text)
    return F(10) ** int(m.group(1)) if m else F(text)


def scaled_model(name, scale):
    out = f'{work}/{name}@{scale}.json'
    if scale == '1':
        return f'{repo}/examples/models/{name}.json'
    subprocess.run([sys.executable, f'{repo}/tests/fuzz/scale_model.py', f'{repo}/examples/models/{name}.json', scale, out],
                   check=True)
    return out


def literal(q):
    return f'{q.numerator}/{q.denominator}' if q.denominator != 1 else str(q.numerator)


# claims beyond the defaults (angles only: the same at every scale)
EXTRA = {('cam-follower', 'cam', 'follower'): [('free', ('--driver', 'cam', '--from', '0', '--to', '1/20'))],
         ('lever-stop', 'lever', 'stop'): [('free', ('--driver', 'lever', '--from', '-1/2', '--to', '1/25'))],
         ('ratchet', 'wheel', 'pawl'): [('free', ('--driver', 'wheel', '--from', '0', '--to', '1/50'))]}


def leaves(tree, path=()):
    """(path, Fraction) of every exact number of a claim's data"""
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from leaves(v, path + (k,))
    elif isinstance(tree, list):
        for i, v in enumerate(tree):
            yield from leaves(v, path + (i,))
    elif isinstance(tree, str):
        try:
            yield path, F(tree)
        except (ValueError, ZeroDivisionError):
            pass


def accepted(certificate, model):
    """the verifier's verdict on the claim's data: valid, or refused only for the statement"""
    path = f'{work}/alike.json'
    json.dump(certificate, open(path, 'w'))
    rc, out, err = run([verify, path, model], timeout=300)
    text = (out + err).strip()
    if crash_problems(rc, text) or rc not in (0, 1, 3) or len(text.splitlines()) != 1:
        finding(f'verify of a mutant: exit {rc}: {text[-300:]}')
    return rc == 0 or "the statement does not say what the claim's data prove" in text, text


def mutate_alike(name, key, base, other, scale):
    one, many = base[1], other[1]
    body_one, body_many = one[one['claim']], many[many['claim']]
    paths_one = [p for p, v in leaves(body_one)]
    if paths_one != [p for p, v in leaves(body_many)]:
        print(f'  {name} {key}: the certificates at 1 and {scale} differ in shape: no mutants')
        return
    values_one, values_many = dict(leaves(body_one)), dict(leaves(body_many))
    chosen = [p for p in paths_one if values_one[p] != 0]
    rng.shuffle(chosen)
    for path in chosen[:mutants]:
        for k in (3, 30, 80):
            sign = rng.choice((-1, 1))
            verdicts = []
            for certificate, values, model in ((one, values_one, base[3]), (many, values_many, other[3])):
                m = json.loads(json.dumps(certificate))
                node = m[m['claim']]
                for step in path[:-1]:
                    node = node[step]
                q = values[path] * (1 + sign * F(1, 2 ** k))
                node[path[-1]] = f'{q.numerator}/{q.denominator}' if q.denominator != 1 else str(q.numerator)
                verdicts.append(accepted(m, model))
            if verdicts[0][0] != verdicts[1][0]:
                finding(f'{name} {key} {"/".join(map(str, path))} x (1 {"+" if sign > 0 else "-"} 2^-{k}): '
                        f'accepted {verdicts[0][0]} at 1, {verdicts[1][0]} at {scale}: {verdicts[0][1][:200]} | {verdicts[1][1][:200]}')


for name in models.split(','):
    source = json.load(open(f'{repo}/examples/models/{name}.json'))
    parts = {p['name']: p for p in source['parts']}
    pairs = [p['parts'] for p in source.get('pairs', [])] or [[p['name'] for p in source['parts'][:2]]]
    results = {}   # (pair, claim) -> {scale: (rc, certificate or None)}
    for scale in scales:
        model = scaled_model(name, scale)
        s = factor(scale)
        for a, b in pairs:
            kinds = [parts[x]['motion'] if isinstance(parts[x]['motion'], str) else next(iter(parts[x]['motion'])) for x in (a, b)]
            if any(k in ('planar', 'pin_slot') for k in kinds):
                claims = [('clearance', []), ('interference', [])]
            else:
                driver = a if kinds[0] != 'fixed' else b
                dkind = kinds[0] if driver == a else kinds[1]
                claims = [('clearance', []), ('interference', [])]
                if dkind == 'rotation':
                    claims += [('free', ['--driver', driver]), ('jam', ['--driver', driver])]
                else:
                    claims += [('jam', ['--driver', driver, '--step', literal(s / 100), '--travel', literal(100 * s)])]
            claims += [(claim, list(extra)) for claim, extra in EXTRA.get((name, a, b), [])]
            for index, (claim, extra) in enumerate(claims):
                cert = f'{work}/{name}@{scale}-{a}-{b}-{claim}-{index}.json'
                if os.path.exists(cert):
                    os.remove(cert)
                rc, out, err = run([hipair, 'certify', model, '--claim', claim, '--pair', f'{a}:{b}', *extra, '--out', cert],
                                   timeout=300)
                problems = crash_problems(rc, out + err)
                if problems:
                    finding(f'{name}@{scale} {a}:{b} certify {claim}: {problems} {err.strip()[-200:]}')
                    continue
                if rc not in (0, 1, 2):
                    finding(f'{name}@{scale} {a}:{b} certify {claim}: exit {rc}: {err.strip()[-200:]}')
                if rc != 0 and len(err.strip().splitlines()) > 1:
                    finding(f'{name}@{scale} {a}:{b} certify {claim}: {len(err.strip().splitlines())} lines: {err.strip()[-300:]}')
                c = None
                if rc == 0:
                    vrc, vout, verr = run([verify, cert, model], timeout=300)
                    if vrc != 0:
                        finding(f'{name}@{scale} {a}:{b} certify {claim} verifies {vrc}: {(vout + verr).strip()[-300:]}')
                    c = json.load(open(cert))
                results.setdefault((a, b, f'{claim}#{index}'), {})[scale] = (rc, c, err.strip().splitlines()[-1:] if rc else '', model)
                # clearance moved up by 2^-k, scale by scale (compared below)
                if c and claim in ('clearance', 'free'):
                    body = c[c['claim']]
                    d = F(body['distance'])
                    verdicts = []
                    for k in (4, 30, 64):
                        m = json.loads(json.dumps(c))
                        mb = m[m['claim']]
                        mb['distance'] = literal(d * (1 + F(1, 2 ** k)))
                        mfile = f'{work}/mutant.json'
                        json.dump(m, open(mfile, 'w'))
                        vrc, vout, verr = run([verify, mfile, model], timeout=300)
                        if crash_problems(vrc, vout + verr):
                            finding(f'{name}@{scale} {claim} +2^-{k}: crash {vout + verr}')
                        verdicts.append(vrc)
                    results[(a, b, f'{claim}#{index}')][scale] += (verdicts,)
                elif c:
                    results[(a, b, f'{claim}#{index}')][scale] += (None,)
    for key, by_scale in results.items():
        base = by_scale.get('1')
        line = f'{name} {key[0]}:{key[1]} {key[2]}: ' + ', '.join(f'{s}: {v[0]}' + (f' {v[4]}' if len(v) > 4 and v[4] else '') for s, v in by_scale.items())
        print(line)
        for scale, v in by_scale.items():
            if base and v[0] != base[0]:
                finding(f'{name} {key}: certify exit {v[0]} at {scale}, {base[0]} at 1: {v[2]} / {base[2]}')
            if base and len(v) > 4 and len(base) > 4 and v[4] != base[4]:
                finding(f'{name} {key}: verdicts of the raised distance {v[4]} at {scale}, {base[4]} at 1')
            if mutants and scale != '1' and base and base[1] and v[1]:
                mutate_alike(name, key, base, v, scale)
            if base and base[1] and v[1] and key[2].startswith('clearance'):
                d1, ds = F(base[1][base[1]['claim']]['distance']), F(v[1][v[1]['claim']]['distance'])
                if d1 > 0 and abs(ds / factor(scale) / d1 - 1) > F(1, 10 ** 6):
                    finding(f'{name} {key}: distance {ds} at {scale}, {d1} at 1')
print('findings', findings, '(seed %d)' % seed if findings else '')
sys.exit(1 if findings else 0)
