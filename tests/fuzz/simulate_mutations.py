#!/usr/bin/env python3
"""Mutations of every dynamics datum a simulation reads (session 60, hunt60).

usage: simulate_mutations.py HIPAIR SOURCE_DIR WORKDIR [--all] [--seed S] [--only SUBSTRING]

For each base model (fixed-axis, planar, several planar, pin-slot with a torque-driven cam and a
translating part, springs between moving parts, static/kinetic friction) every leaf of its
`simulation` object, of each part's `dynamics` and `initial`, and of each pair's `friction` and
`restitution` is replaced by hostile values (negative, zero, non-numbers, strings that are no
expression, 1e400, 1e-400, arrays, objects, null, booleans) or removed. Each run
(`hipair simulate MODEL --t-end T --quiet --no-pictures --out DIR --max-steps 2000`, DIR
holding one file beforehand; the step budget bounds the runs that loads of 1e308 press into steps
of 1e-154 s) must:
  - end within the time-out, without a crash text, a signal or an abort;
  - exit 0, 2 (model) or 3 (run); on failure print ONE line on stderr, `hipair: error: ...`, and
    leave DIR exactly as it was (its one file untouched, nothing added);
  - refuse a value of the wrong type or no number (a string that is no expression, an array
    where a number is wanted, null, a boolean) with exit 2 at a pointer that is the mutated
    place or lies on its path (a missing required key is named at its parent);
  - exit 0 with the model unchanged in meaning when the mutation was a no-op.
Without --all a seeded sample of the mutations runs (the ctest); --all runs every one.
Found by it (session 60): several planar parts (friction-slide.json, pushed-block.json) with an
initial velocity or gravity of 1e308 died of SIGFPE (GMP's mpq_set_d(inf) on a step's query
radius); a rate, gravity, force, torque, stiffness or damping within the doubles in the file's
units but not in the simulator's (1e306 rad/ms) ran to "not finite" at t = 0 without a pointer.
"""
import copy
import json
import os
import random
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hunt_common import run, crash_problems  # noqa: E402

# values that are no number of any kind: must be refused (exit 2) wherever a number is read
NOT_A_NUMBER = [('string-abc', 'abc'), ('string-nan', 'nan'), ('string-inf', 'inf'), ('null', None),
                ('true', True), ('array-empty', []), ('object-empty', {}), ('string-empty', '')]
# numbers that may be legal or not; whatever happens, no crash, one line, nothing written
HOSTILE_NUMBERS = [('negative', -1), ('zero', 0), ('huge-1e400', '1e400'), ('tiny-1e-400', '1e-400'),
                   ('max-double', 1.7976931348623157e308), ('subnormal', '5e-324'), ('minus-huge', '-1e308')]


def bases(source):
    """(name, path or model, --t-end, extra arguments)"""
    ex = os.path.join(source, 'examples', 'models')
    data = os.path.join(source, 'tests', 'data', 'simulation')

    def load(path):
        return json.load(open(path))

    cam = load(os.path.join(ex, 'cam-drive.json'))
    # a damped spring between the moving follower and the rotating cam (both fixed-axis parts)
    cam['simulation']['springs'] = [{'parts': ['follower', 'cam'], 'points': [[0, 40], [0, 5]],
                                     'stiffness': 0.5, 'rest_length': 30, 'damping': 0.001}]
    cam['pairs'] = [{'parts': ['cam', 'follower'], 'friction': {'static': 0.3, 'kinetic': 0.2},
                     'restitution': 0.4}]
    film = load(os.path.join(data, 'film-advance-dynamics.json'))
    return [
        ('bouncing-bar', load(os.path.join(ex, 'bouncing-bar.json')), '0.05', []),
        ('cam-drive-spring', cam, '0.05', []),
        ('geneva-drive', load(os.path.join(ex, 'geneva-drive.json')), '0.05', []),
        ('spring-block', load(os.path.join(ex, 'spring-block.json')), '0.05', []),
        ('friction-slide', load(os.path.join(ex, 'friction-slide.json')), '0.02', []),
        ('pushed-block', load(os.path.join(ex, 'pushed-block.json')), '0.05', []),
        ('pin-slot-cam', load(os.path.join(data, 'pin-slot-cam.json')), '0.02', []),
        ('film-dynamics', film, '0.005', []),
        ('ratchet-touch', load(os.path.join(data, 'ratchet-corner-touch.json')), '0.01', []),
    ]


def leaves(model):
    """JSON pointers (as key lists) of the dynamics data a simulation reads"""
    out = []

    def walk(value, path):
        if isinstance(value, dict):
            for k, v in value.items():
                walk(v, path + [k])
        elif isinstance(value, list) and value and not all(isinstance(v, (int, float, str)) for v in value):
            for i, v in enumerate(value):
                walk(v, path + [i])
        else:
            out.append(path)
            if isinstance(value, list):
                for i in range(len(value)):
                    out.append(path + [i])
    if 'simulation' in model:
        walk(model['simulation'], ['simulation'])
    for i, part in enumerate(model['parts']):
        for key in ('dynamics', 'initial'):
            if key in part:
                walk(part[key], ['parts', i, key])
    for i, pair in enumerate(model.get('pairs', [])):
        for key in ('friction', 'restitution'):
            if key in pair:
                walk(pair[key], ['pairs', i, key])
    return out


def pointer(path):
    return ''.join('/' + str(k).replace('~', '~0').replace('/', '~1') for k in path)


def set_at(model, path, value, remove=False):
    node = model
    for k in path[:-1]:
        node = node[k]
    if remove:
        if isinstance(node, list):
            del node[path[-1]]
        else:
            del node[path[-1]]
    else:
        node[path[-1]] = value


def snapshot(directory):
    return {name: open(os.path.join(directory, name), 'rb').read() for name in sorted(os.listdir(directory))}


def main(argv):
    args = [a for a in argv[1:]]
    everything = '--all' in args
    # a fixed default seed (a CI run repeats); HIPAIR_TEST_SEED=<n> or =random picks another
    seed_text = os.environ.get('HIPAIR_TEST_SEED', '') or '61'
    seed = random.randrange(1 << 30) if seed_text == 'random' else int(seed_text)
    only = None
    if '--seed' in args:
        seed = int(args[args.index('--seed') + 1])
        del args[args.index('--seed'):args.index('--seed') + 2]
    if '--only' in args:
        only = args[args.index('--only') + 1]
        del args[args.index('--only'):args.index('--only') + 2]
    args = [a for a in args if a != '--all']
    if len(args) != 3:
        print(__doc__)
        return 2
    hipair, source, work = args
    os.makedirs(work, exist_ok=True)
    rng = random.Random(seed)
    cases = []
    for name, model, t_end, extra in bases(source):
        if only and only not in name:
            continue
        for path in leaves(model):
            mutations = [('removed', None, True)] + [(n, v, False) for n, v in NOT_A_NUMBER + HOSTILE_NUMBERS]
            if not everything:
                mutations = rng.sample(mutations, 3)
            for label, value, remove in mutations:
                cases.append((name, model, t_end, extra, path, label, value, remove))
    print('seed %d, %d cases' % (seed, len(cases)))
    failures = 0
    for name, model, t_end, extra, path, label, value, remove in cases:
        m = copy.deepcopy(model)
        try:
            set_at(m, path, value, remove)
        except (KeyError, IndexError, TypeError):
            continue
        tag = '%s%s=%s' % (name, pointer(path), label)
        model_path = os.path.join(work, 'model.json')
        with open(model_path, 'w') as f:
            json.dump(m, f, indent=1)
        out = os.path.join(work, 'out')
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        with open(os.path.join(out, 'keep.txt'), 'w') as f:
            f.write('a file that was here before\n')
        before = snapshot(out)
        start = time.time()
        rc, so, se = run([hipair, 'simulate', model_path, '--t-end', t_end, '--quiet', '--no-pictures',
                          '--out', out, '--max-steps', '2000'] + extra, timeout=90)
        seconds = time.time() - start
        problems = crash_problems(rc, so + se)
        lines = [line for line in se.splitlines() if line.strip()]
        if not problems:
            if rc not in (0, 2, 3):
                problems.append('exit %s' % rc)
            if rc != 0:
                if len(lines) != 1:
                    problems.append('%d lines on stderr' % len(lines))
                elif not lines[0].startswith('hipair: error: '):
                    problems.append('not a hipair error line')
                if snapshot(out) != before:
                    problems.append('the output directory changed on failure')
            if (label, value) in NOT_A_NUMBER and not remove:
                if rc != 2:
                    problems.append('a non-number accepted (exit %s)' % rc)
                elif lines:
                    named = lines[0][len('hipair: error: '):].split(':')[0]
                    if not pointer(path).startswith(named):
                        problems.append('names %s, not %s' % (named, pointer(path)))
            if rc == 2 and lines and not remove and (label, value) not in NOT_A_NUMBER:
                named = lines[0][len('hipair: error: '):].split(':')[0]
                if not named.startswith('/') and not named.startswith('-'):
                    problems.append('no pointer or option named')
        status = 'ok' if not problems else 'PROBLEM ' + '; '.join(problems)
        if problems or everything:
            print('%-60s exit %-7s %5.1f s  %s | %s' % (tag, rc, seconds, status, (lines[-1] if lines else '')[:200]))
            sys.stdout.flush()
        failures += bool(problems)
    print('%d of %d cases failed (seed %d)' % (failures, len(cases), seed))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
