#!/usr/bin/env python3
"""Hostile model data through every exact command (session 61, hunt61).

usage: hostile_commands.py HIPAIR HIPAIR_VERIFY SOURCE_DIR WORKDIR [--all] [--seed S] [--only SUBSTRING]

Bundled models (a cam and follower, a lever against a stop, a ratchet, a Geneva template, a peg in
a slot) have one datum of their geometry, motion or
parameters replaced by a hostile value (1e400, 1e-400, 1e-300, 1.7976931348623157e308, zero,
-1, "nan", "abc", an empty array, null), or a structure changed (a duplicated part name, empty
`parts`/`pairs`/`loops`/`edges`, a template's tooth count of 10^7 or 0, an arc whose end is its
start). Each is run through `validate`, `cspace --json --svg`, `analyze --out`, `tolerance --out`
and `certify --claim interference` (and `hipair-verify` on a certificate written). Each run must:
  - end within the time-out (60 s), without a signal, an abort or a crash text;
  - exit 0, 2 (the model or a command line) or 3 (the geometry or a run HIPAIR declines);
  - on failure print ONE line `hipair: error: ...` that names where: a JSON pointer (the mutated
    place, one on its path, or the part or parameter it feeds), an option, or the file;
  - on failure leave its output as it was: the --out directory holding one file keeps it and
    gains nothing, a --json/--svg/certificate file is not written.
Without --all a seeded sample runs (fixed default seed; HIPAIR_TEST_SEED=<n> or =random picks
another); --all runs every mutation.
"""
import copy
import json
import os
import random
import re
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems  # noqa: E402

HOSTILE = [('1e400', '1e400'), ('1e-400', '1e-400'), ('1e-300', 1e-300), ('max-double', 1.7976931348623157e308),
           ('zero', 0), ('minus-one', -1), ('string-nan', 'nan'), ('string-abc', 'abc'), ('array-empty', []),
           ('null', None)]
# (gear-train.json is left out: its unmutated cspace/analyze/tolerance runs take over the time-out
# on a loaded machine; its tooth counts of 10^7, 1e400, 0, -3, 2.5 and "abc" were run by hand in
# session 61: each refused at .../spur_gear/teeth, exit 2)
MODELS = ['cam-follower.json', 'lever-stop.json', 'ratchet.json', 'geneva-template.json', 'peg-in-slot.json']
POINTER_TOKEN = re.compile(r"(?<![\w/])(/(?:parts|pairs|parameters|units|templates|simulation|motion|name|hipair)"
                           r"(?:/[A-Za-z0-9_.~-]+)*)")


def leaves(model):
    """key paths of every number or numeric string outside the dynamics data"""
    out = []

    def walk(value, path):
        if isinstance(value, dict):
            for k, v in value.items():
                if k in ('simulation', 'dynamics', 'description', 'name', 'label', 'kind'):
                    continue
                walk(v, path + [k])
        elif isinstance(value, list):
            for i, v in enumerate(value):
                walk(v, path + [i])
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out.append(path)
        elif isinstance(value, str) and path and path[-1] != 'parts' and not isinstance(path[-1], str):
            out.append(path)   # an expression in a coordinate list
        elif isinstance(value, str) and path and path[-1] in ('nominal', 'radius', 'angle', 'offset', 'x', 'y'):
            out.append(path)
    walk(model, [])
    return out


def pointer(path):
    return ''.join('/' + str(k).replace('~', '~0').replace('/', '~1') for k in path)


def set_at(model, path, value):
    node = model
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value


def structural(model):
    """(label, changed model, pointer the change is at)"""
    out = []
    parts = model.get('parts', [])
    if len(parts) >= 2:
        m = copy.deepcopy(model)
        m['parts'][1]['name'] = m['parts'][0]['name']
        out.append(('duplicate-part-name', m, '/parts/1/name'))
    for key in ('parts', 'pairs'):
        if key in model:
            m = copy.deepcopy(model)
            m[key] = []
            out.append(('empty-' + key, m, '/' + key))
    for i, part in enumerate(parts):
        if isinstance(part.get('loops'), list) and part['loops']:
            m = copy.deepcopy(model)
            m['parts'][i]['loops'] = []
            out.append(('empty-loops-%d' % i, m, '/parts/%d/loops' % i))
            m = copy.deepcopy(model)
            m['parts'][i]['loops'][0]['edges'] = []
            out.append(('empty-edges-%d' % i, m, '/parts/%d/loops/0/edges' % i))
            loop = part['loops'][0]
            for k, edge in enumerate(loop.get('edges', [])):
                if isinstance(edge, dict) and 'arc_to' in edge:
                    m = copy.deepcopy(model)
                    start = loop['start'] if k == 0 else list(loop['edges'][k - 1].values())[0]
                    m['parts'][i]['loops'][0]['edges'][k]['arc_to'] = copy.deepcopy(start)
                    out.append(('arc-to-its-start-%d-%d' % (i, k), m, '/parts/%d/loops/0/edges/%d' % (i, k)))
                    break
        for j, template in enumerate(part.get('templates', []) if isinstance(part.get('templates'), list) else []):
            pass
        features = part.get('features')
        if isinstance(features, list):
            for j, feature in enumerate(features):
                if not isinstance(feature, dict):
                    continue
                for kind, body in feature.items():
                    if isinstance(body, dict) and 'teeth' in body:
                        for teeth in (10000000, 0, -3, 2.5):
                            m = copy.deepcopy(model)
                            m['parts'][i]['features'][j][kind]['teeth'] = teeth
                            out.append(('teeth-%s-%d-%d' % (teeth, i, j), m, '/parts/%d/features/%d/%s/teeth' % (i, j, kind)))
    for name, param in (model.get('parameters') or {}).items():
        if isinstance(param, dict) and 'tolerance' in param:
            m = copy.deepcopy(model)
            m['parameters'][name]['tolerance'] = [5, -5]
            out.append(('tolerance-reversed-' + name, m, '/parameters/%s/tolerance' % name))
            break
    return out


def snapshot(directory):
    if not os.path.isdir(directory):
        return None
    return {name: open(os.path.join(directory, name), 'rb').read() for name in sorted(os.listdir(directory))}


def names_place(message):
    return bool(POINTER_TOKEN.search(message)) or ' --' in message or re.search(r"'--[a-z]", message) or \
        'model file' in message


def check_run(tag, args, rc, so, se, outputs, problems):
    problems += crash_problems(rc, so + se)
    lines = [line for line in se.splitlines() if line.strip()]
    if rc == 'timeout' or problems:
        return
    if rc == 1 and args[1] == 'certify' and len(lines) == 1 and lines[0].startswith('hipair: cannot certify'):
        return   # the claim does not hold there (docs/certify.md): exit 1, one line, no certificate
    if rc not in (0, 2, 3):
        problems.append('exit %s' % rc)
    if rc != 0:
        if len(lines) != 1:
            problems.append('%d lines on stderr' % len(lines))
        elif not lines[0].startswith('hipair: error: ') and not lines[0].startswith('hipair-verify'):
            problems.append('not a hipair error line')
        elif not names_place(lines[0]):
            problems.append('the message names no place')
        for path, before in outputs:
            after = snapshot(path) if before is not None else (os.path.exists(path) or None)
            if after != before:
                problems.append('output %s changed on failure' % os.path.basename(path))


def main(argv):
    args = list(argv[1:])
    everything = '--all' in args
    args = [a for a in args if a != '--all']
    seed_text = os.environ.get('HIPAIR_TEST_SEED', '') or '61'
    seed = random.randrange(1 << 30) if seed_text == 'random' else int(seed_text)
    only = None
    if '--seed' in args:
        seed = int(args[args.index('--seed') + 1])
        del args[args.index('--seed'):args.index('--seed') + 2]
    if '--only' in args:
        only = args[args.index('--only') + 1]
        del args[args.index('--only'):args.index('--only') + 2]
    if len(args) != 4:
        print(__doc__)
        return 2
    hipair, verify, source, work = args
    os.makedirs(work, exist_ok=True)
    rng = random.Random(seed)
    cases = []
    for name in MODELS:
        if only and only not in name:
            continue
        model = json.load(open(os.path.join(source, 'examples', 'models', name)))
        for path in leaves(model):
            values = HOSTILE if everything else rng.sample(HOSTILE, 1)
            for label, value in values:
                m = copy.deepcopy(model)
                set_at(m, path, value)
                cases.append(('%s%s=%s' % (name, pointer(path), label), m))
        for label, m, at in structural(model):
            cases.append(('%s%s=%s' % (name, at, label), m))
    if not everything:
        rng.shuffle(cases)
        cases = cases[:60]
    print('seed %d, %d cases' % (seed, len(cases)))
    failures = 0
    for tag, m in cases:
        model_path = os.path.join(work, 'model.json')
        with open(model_path, 'w') as f:
            json.dump(m, f, indent=1)
        out = os.path.join(work, 'out')
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        with open(os.path.join(out, 'keep.txt'), 'w') as f:
            f.write('a file that was here before\n')
        json_out, svg_out, cert = (os.path.join(work, n) for n in ('c.json', 'c.svg', 'cert.json'))
        for path in (json_out, svg_out, cert):
            if os.path.exists(path):
                os.remove(path)
        commands = [
            ('validate', [hipair, 'validate', model_path], []),
            ('cspace', [hipair, 'cspace', model_path, '--json', json_out, '--svg', svg_out], [(json_out, None), (svg_out, None)]),
            ('analyze', [hipair, 'analyze', model_path, '--out', out], [(out, 'directory')]),
            ('tolerance', [hipair, 'tolerance', model_path, '--out', out], [(out, 'directory')]),
            ('certify', [hipair, 'certify', model_path, '--claim', 'interference', '--out', cert], [(cert, None)]),
        ]
        for command, line, outputs in commands:
            problems = []
            outputs = [(path, snapshot(path) if before == 'directory' else before) for path, before in outputs]
            start = time.time()
            rc, so, se = run(line, timeout=60)
            seconds = time.time() - start
            check_run(tag, line, rc, so, se, outputs, problems)
            if command == 'certify' and rc == 0 and os.path.exists(cert):
                vrc, vso, vse = run([verify, cert, model_path], timeout=60)
                problems += ['verify: ' + p for p in crash_problems(vrc, vso + vse)]
                if vrc not in (0, 1, 2, 3) and vrc != 'timeout':
                    problems.append('verify exit %s' % vrc)
            lines = [x for x in se.splitlines() if x.strip()]
            status = 'ok' if not problems else 'PROBLEM ' + '; '.join(problems)
            if problems or everything:
                print('%-60s %-9s exit %-7s %5.1f s  %s | %s' % (tag[:60], command, rc, seconds, status,
                                                                 (lines[0] if lines else '')[:200]))
                sys.stdout.flush()
            failures += bool(problems)
            if command == 'validate' and rc == 2:
                break   # a model refused by validate: the others read it the same way
    print('%d failures (seed %d)' % (failures, seed))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
