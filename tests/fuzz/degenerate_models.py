#!/usr/bin/env python3
"""Session 29 (hunt29): degenerate geometry and references built on purpose in the example
models (a zero-length edge, a loop crossing itself, three collinear corners, an arc of zero
radius or whose centre is not equidistant, a duplicated part name, a pair naming an unknown part
or one part twice, a negative or zero mass or inertia, a loop of one edge), each through
`hipair validate` and one command. Oracle: a model error is one line `hipair: error: /pointer...`
with exit 2 (or 3 for geometry HIPAIR declines), never a signal, an abort, a time-out, a crash
text, or an output file left by a failed run.
usage: degenerate_models.py HIPAIR MODELS_DIR OUTDIR SEED N"""
import copy, json, os, random, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems

hipair, models_dir, outdir, seed, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
rng = random.Random(seed)
models = sorted(f for f in os.listdir(models_dir) if f.endswith('.json'))
os.makedirs(outdir, exist_ok=True)

def edges_of(tree):
    out = []
    for i, part in enumerate(tree.get('parts', [])):
        for j, loop in enumerate(part.get('loops', []) if isinstance(part.get('loops'), list) else []):
            if isinstance(loop, dict) and isinstance(loop.get('edges'), list):
                out.append((i, j, loop))
    return out

def end_of(loop, k):
    e = loop['edges'][k]
    return e.get('line_to', e.get('arc_to'))

def mutate(tree):
    loops = edges_of(tree)
    kind = rng.randrange(11)
    if not loops:
        return None
    i, j, loop = rng.choice(loops)
    edges = loop['edges']
    k = rng.randrange(len(edges))
    prev = loop['start'] if k == 0 else end_of(loop, k - 1)
    if kind == 0:                                   # zero-length edge
        edges.insert(k, {'line_to': copy.deepcopy(prev)})
        return 'zero-length edge before /parts/%d/loops/%d/edges/%d' % (i, j, k)
    if kind == 1:                                   # the loop crosses itself: two ends swapped
        if len(edges) < 3:
            return None
        a, b = rng.sample(range(len(edges)), 2)
        ea, eb = edges[a], edges[b]
        ka = 'line_to' if 'line_to' in ea else 'arc_to'
        kb = 'line_to' if 'line_to' in eb else 'arc_to'
        ea[ka], eb[kb] = eb[kb], ea[ka]
        return 'ends of edges %d and %d swapped in /parts/%d/loops/%d' % (a, b, i, j)
    if kind == 2:                                   # collinear: a midpoint inserted on a line
        e = edges[k]
        if 'line_to' not in e:
            return None
        to = e['line_to']
        mid = ['(%s + %s)/2' % (prev[0], to[0]), '(%s + %s)/2' % (prev[1], to[1])]
        edges.insert(k, {'line_to': mid})
        return 'collinear midpoint in /parts/%d/loops/%d/edges/%d' % (i, j, k)
    if kind == 3:                                   # arc of zero radius: centre at its start
        edges[k] = {'arc_to': copy.deepcopy(end_of(loop, k)), 'center': copy.deepcopy(prev), 'dir': 'ccw'}
        return 'arc centred at its start /parts/%d/loops/%d/edges/%d' % (i, j, k)
    if kind == 4:                                   # arc whose centre is off (not equidistant)
        edges[k] = {'arc_to': copy.deepcopy(end_of(loop, k)), 'center': ['(%s) + 1/7' % prev[0], '(%s) - 3' % prev[1]], 'dir': 'cw'}
        return 'arc with an unequal centre /parts/%d/loops/%d/edges/%d' % (i, j, k)
    if kind == 5:                                   # duplicate part name
        if len(tree['parts']) < 2:
            return None
        tree['parts'][1]['name'] = tree['parts'][0]['name']
        return 'duplicate part name'
    if kind == 6:                                   # a pair with an unknown part / the same part twice
        tree.setdefault('pairs', []).append({'parts': [tree['parts'][0]['name'], rng.choice(['nobody', tree['parts'][0]['name']])]})
        return 'bad pair %s' % tree['pairs'][-1]
    if kind == 7:                                   # negative or zero mass / inertia
        part = tree['parts'][i]
        d = part.setdefault('dynamics', {})
        key = rng.choice(['mass', 'moment_of_inertia'])
        d[key] = rng.choice([0, -1, '-1e-300', '0/1', -0.0])
        return 'dynamics %s = %r at /parts/%d' % (key, d[key], i)
    if kind == 8:                                   # a loop of one edge back to its start
        loop['edges'] = [{'line_to': copy.deepcopy(loop['start'])}]
        return 'one-edge loop /parts/%d/loops/%d' % (i, j)
    if kind == 9:                                   # a loop not closed
        e = edges[-1]
        key = 'line_to' if 'line_to' in e else 'arc_to'
        if not isinstance(e.get(key), list):
            return None
        e[key] = ['(%s) + 1/3' % e[key][0], e[key][1]]
        return 'loop not closed /parts/%d/loops/%d' % (i, j)
    # the whole part's loops duplicated (coincident boundaries)
    tree['parts'][i]['loops'].append(copy.deepcopy(loop))
    return 'coincident loop copy in /parts/%d' % i

COMMANDS = [
    ['cspace', '{m}', '--json', '{o}/cs.json', '--svg', '{o}/cs.svg'],
    ['show', '{m}', '--svg', '{o}/show.svg'],
    ['certify', '{m}', '--claim', 'clearance', '--out', '{o}/cert.json'],
]


findings = 0
reached = 0
kinds = {}
for case in range(n):
    name = rng.choice(models)
    tree = json.load(open(os.path.join(models_dir, name)))
    what = mutate(tree)
    if what is None:
        continue
    label = what.split(' /')[0].split(' in')[0].split(' {')[0].split(' =')[0]
    label = 'ends swapped' if label.startswith('ends of edges') else label
    kinds[label] = kinds.get(label, 0) + 1
    cdir = os.path.join(outdir, 'case%04d' % case)
    os.makedirs(cdir, exist_ok=True)
    m = os.path.join(cdir, 'model.json')
    json.dump(tree, open(m, 'w'), indent=1)
    for args in (['validate', m], [c.format(m=m, o=cdir) for c in rng.choice(COMMANDS)]):
        before = set(os.listdir(cdir))
        rc, out, err = run([hipair] + args, 120)
        problems = crash_problems(rc, out + err)
        if rc == 5 or 'internal' in out + err:
            problems.append('internal error rc=%s' % rc)
        if rc not in (0, 'timeout'):
            lines = err.strip().splitlines()
            if len(lines) != 1 or not lines[0].startswith('hipair: '):
                problems.append('not one message line: %r' % err[:200])
            left = set(os.listdir(cdir)) - before
            if left:
                problems.append('left output %s' % sorted(left))
        if problems:
            findings += 1
            print('case %d %s %s (%s): %s\n  stderr: %s' % (case, name, args[0], what, problems, err.strip()[:300]), flush=True)
        if rc != 0:
            break
        if args[0] != 'validate':
            reached += 1
print('%s; %d cases reached their command; %d findings' % (kinds, reached, findings))
