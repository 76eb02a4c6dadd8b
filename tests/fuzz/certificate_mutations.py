#!/usr/bin/env python3
"""Session 29 (hunt29): mutations of the valid certificates of tests/data/certificates against
hipair-verify.  Oracles:
  * an equivalent rewrite of a valid certificate (keys reordered, whitespace, the JSON escaped
    differently) must stay `valid` (exit 0);
  * a corrupted one (truncated, a key duplicated with another value, a number or rational made
    malformed / NaN / infinite / huge, a string made a number, a field dropped) must not be
    `valid`; any run must exit 1, 2 or 3 with one line, never a signal, an abort or a time-out.
usage: certificate_mutations.py HIPAIR_VERIFY REPO OUTDIR SEED N"""
import json, os, random, sys, re, copy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems

verify, repo, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
rng = random.Random(seed)
corpus = os.path.join(repo, 'tests/data/certificates')
bases = []
for line in open(os.path.join(corpus, 'EXPECTED.txt')):
    if line.startswith('#') or not line.strip():
        continue
    cert, model, expected, base = [f.strip() for f in line.split('|')]
    if expected == 'valid' and cert == base and 'tolerance-no-jam' not in cert:
        bases.append((cert, model))
os.makedirs(outdir, exist_ok=True)

def nodes(tree, path=()):
    yield path, tree
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from nodes(v, path + (k,))
    elif isinstance(tree, list):
        for i, v in enumerate(tree):
            yield from nodes(v, path + (i,))

def get(tree, path):
    for p in path:
        tree = tree[p]
    return tree

def reorder(tree):
    if isinstance(tree, dict):
        items = list(tree.items())
        rng.shuffle(items)
        return {k: reorder(v) for k, v in items}
    if isinstance(tree, list):
        return [reorder(v) for v in tree]
    return tree

RATIONAL = re.compile(r'^-?[0-9]+(/[0-9]+)?$')
BAD_NUMBERS = ['NaN', 'nan', 'inf', '-inf', 'Infinity', '1e999999999', '1e-999999999', '1/0', '0/0',
               '-0/0', '1/-2', '+1', ' 1', '1 ', '0x10', '1.5e', '1/2/3', '', '-', '1e400', '1' * 5000,
               '9' * 20000 + '/7', '１', '1_000', '1,5']

def equivalent(text, tree):
    """a rewrite with the same JSON content"""
    k = rng.randrange(4)
    if k == 0:
        return 'keys reordered', json.dumps(reorder(tree), indent=rng.choice([None, 1, 4]))
    if k == 1:
        return 'minified', json.dumps(tree, separators=(',', ':'))
    if k == 2:
        return 'ascii-escaped strings', json.dumps(tree, ensure_ascii=True).replace('"claim"', '"\\u0063laim"')
    return 'CRLF and tabs', json.dumps(tree, indent='\t').replace('\n', '\r\n')

def corrupt(text, tree):
    k = rng.randrange(9)
    all_nodes = [p for p, _ in nodes(tree) if p]
    if k == 0:
        cut = rng.randrange(1, len(text))
        return 'truncated at %d' % cut, text[:cut]
    if k == 1:                                    # a key duplicated with another value
        dicts = [(p, v) for p, v in nodes(tree) if isinstance(v, dict) and v]
        p, d = rng.choice(dicts)
        key = rng.choice(list(d.keys()))
        other = [v for q, v in nodes(tree) if q and v != d[key] and type(v) == type(d[key])]
        if not other:
            return None
        dup = json.dumps(rng.choice(other))
        body = json.dumps(tree)
        target = json.dumps(d)
        if body.count(target) != 1:
            return None
        first = rng.random() < 0.5
        inner = target[1:-1]
        new = '{"%s": %s, %s}' % (key, dup, inner) if first else '{%s, "%s": %s}' % (inner, key, dup)
        return 'key %s at %s duplicated (%s copy) with %s' % (key, p, 'first' if first else 'last', dup[:60]), \
            body.replace(target, new)
    if k == 2:                                    # a rational string made malformed
        rats = [p for p, v in nodes(tree) if p and isinstance(v, str) and RATIONAL.match(v)]
        if not rats:
            return None
        p = rng.choice(rats)
        t = copy.deepcopy(tree)
        bad = rng.choice(BAD_NUMBERS)
        get(t, p[:-1])[p[-1]] = bad
        return 'rational %s = %r' % (p, bad[:40]), json.dumps(t)
    if k == 3:                                    # a rational string made a JSON number
        rats = [p for p, v in nodes(tree) if p and isinstance(v, str) and re.match(r'^-?[0-9]+$', v)]
        if not rats:
            return None
        p = rng.choice(rats)
        t = copy.deepcopy(tree)
        get(t, p[:-1])[p[-1]] = int(get(t, p))
        return 'rational %s as a JSON number' % (p,), json.dumps(t)
    if k == 4:                                    # a field dropped
        p = rng.choice(all_nodes)
        t = copy.deepcopy(tree)
        del get(t, p[:-1])[p[-1]]
        return 'dropped %s' % (p,), json.dumps(t)
    if k == 5:                                    # a value's type changed
        p = rng.choice(all_nodes)
        t = copy.deepcopy(tree)
        get(t, p[:-1])[p[-1]] = rng.choice([None, True, 0, -1, [], {}, "", 1e308, [[[]]], "x"])
        if get(t, p) == get(tree, p):
            return None
        return 'type of %s changed to %r' % (p, get(t, p)), json.dumps(t)
    if k == 6:                                    # the pair swapped
        if 'pair' not in tree or not isinstance(tree['pair'], list) or len(tree['pair']) != 2:
            return None
        t = copy.deepcopy(tree)
        t['pair'] = t['pair'][::-1]
        return 'pair swapped', json.dumps(t)
    if k == 7:                                    # a rational nudged by 1/10^40 (may stay true)
        rats = [p for p, v in nodes(tree) if p and isinstance(v, str) and RATIONAL.match(v)]
        if not rats:
            return None
        p = rng.choice(rats)
        t = copy.deepcopy(tree)
        from fractions import Fraction
        v = Fraction(get(t, p)) + rng.choice([-1, 1]) * Fraction(1, 10 ** 40)
        get(t, p[:-1])[p[-1]] = str(v)
        return 'NUDGE %s by 1e-40' % (p,), json.dumps(t)
    # trailing garbage / a second document
    return 'trailing content', text + rng.choice(['x', '{}', ',', '\0', ' ]', '\n{"hipair_certificate": 1}'])


findings = 0
count = {'equivalent': 0, 'corrupt': 0, 'neutral': 0}
for case in range(n):
    cert, model = rng.choice(bases)
    text = open(os.path.join(corpus, cert)).read()
    tree = json.loads(text)
    kind = 'equivalent' if rng.random() < 0.25 else 'corrupt'
    m = (equivalent if kind == 'equivalent' else corrupt)(text, tree)
    if m is None:
        continue
    what, new = m
    # no verdict oracle: a nudged rational may leave the claim true; interference, clearance
    # and the tolerance claims are symmetric in the pair; the model's file name is informative
    if what.startswith('NUDGE') or what == 'pair swapped' or "('model', 'file')" in what:
        kind = 'neutral'
    count[kind] += 1
    path = os.path.join(outdir, 'c%05d.json' % case)
    open(path, 'w', newline='').write(new)
    rc, out, err = run([verify, path, os.path.join(repo, model)])
    problems = crash_problems(rc, out + err)
    if kind == 'equivalent' and rc != 0:
        problems.append('equivalent rewrite not valid: rc=%s %s' % (rc, (out + err).strip()[:200]))
    if kind == 'corrupt' and rc == 0:
        problems.append('corrupted certificate accepted')
    if rc not in (0, 'timeout') and len((out + err).strip().splitlines()) != 1:
        problems.append('%d lines of output' % len((out + err).strip().splitlines()))
    if problems:
        findings += 1
        print('case %d %s (%s): %s\n  %s\n  out: %s' % (case, cert, what, problems, path, (out + err).strip()[:300]), flush=True)
    else:
        os.remove(path)
print('%s, %d findings' % (count, findings))
