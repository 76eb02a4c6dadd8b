#!/usr/bin/env python3
"""Summarise a crossing-query trace (tests/perf/crossing_trace.patch; docs/performance.md,
"Session 74 (speed74)").

Apply the patch to a scratch checkout, build `hipair`, run e.g.
  SPEED74_TRACE=1 build/hipair simulate examples/models/escapement.json --t-end 0.5 \
      --accuracy 1e-3 --no-pictures --out /tmp/esc 2> trace.txt
and then `python3 tests/perf/crossing_trace.py trace.txt`. The trace has one START line per
first_crossing query (its CrossingRun and the space's parts), one TR line per stretch of its
subdivision (start and width in resolution cells, possible curves left, Newton proposal), a CYC
line before each TR (the stretch evaluation's time-stamp-counter cycles: a rough relative cost,
not instructions), END per located bracket end, and (SPEED74_TRACE_MV=1) MV / MV0 / SO lines from
the mean-value and second-order exclusions (start value, rates, curvature; read them by eye).
Queries of one sweep interleave: lines
are matched to queries by the CrossingRun address, reused by later queries after a START.
"""
import collections
import math
import sys


def read(path):
    current, queries = {}, []
    cycles = None
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == 'START':
            q = {'pair': parts[2] if len(parts) > 2 else '?', 'stretches': [], 'ends': 0}
            current[parts[1]] = q
            queries.append(q)
        elif parts[0] == 'CYC':
            cycles = int(parts[1])
        elif parts[0] == 'TR' and parts[1] in current:
            s = dict(kv.split('=') for kv in parts[2:])
            s['cycles'] = cycles
            cycles = None
            current[parts[1]]['stretches'].append(s)
        elif parts[0] == 'END' and parts[1] in current:
            current[parts[1]]['ends'] += 1
    return queries


def main():
    queries = read(sys.argv[1])
    stretches = [s for q in queries for s in q['stretches']]
    print(f'{len(queries)} queries, {len(stretches)} stretch evaluations, '
          f'{sum(1 for q in queries if q["ends"])} with a located bracket end')
    per_pair = collections.defaultdict(lambda: [0, 0, 0])
    for q in queries:
        p = per_pair[q['pair']]
        p[0] += 1
        p[1] += len(q['stretches'])
        p[2] += 1 if len(q['stretches']) >= 20 else 0
    for pair, (n, e, long_) in sorted(per_pair.items()):
        print(f'  {pair}: {n} queries, {e} stretches, {long_} queries of >= 20 stretches')
    counts = collections.Counter(len(q['stretches']) for q in queries)
    print('stretches per query:', dict(sorted(counts.items())))
    # classes: the upper tree (> 2^30 cells) with or without possible curves, the middle, the tail
    # (the median per class, times the class's count: a single descheduled evaluation on a
    # loaded machine would dominate a plain sum)
    cls = collections.defaultdict(list)
    for s in stretches:
        w = float(s['w'])
        key = ('wide' if w > 2 ** 30 else 'middle' if w > 32 else 'tail',
               'possible' if s['poss'] != '0' else 'clear')
        cls[key].append(s['cycles'] or 0)
    weight = {key: len(c) * sorted(c)[len(c) // 2] for key, c in cls.items()}
    total = sum(weight.values()) or 1
    for key in sorted(cls):
        c = sorted(cls[key])
        print(f'  {key[0]:6} {key[1]:8}: {len(c):4} stretches, median {c[len(c) // 2]:6} cycles, '
              f'count x median {weight[key] / total:6.1%}')
    print('longest queries (log2 width in cells : possible curves, N = Newton proposal, E = end):')
    for q in sorted(queries, key=lambda q: -len(q['stretches']))[:8]:
        seq = ' '.join(f'{round(math.log2(float(s["w"]))) if float(s["w"]) > 0 else 0}:{s["poss"]}'
                       f'{"N" if s["newton"] == "1" else ""}' for s in q['stretches'])
        print(f'  {q["pair"]}: {seq}{" E" * q["ends"]}')


if __name__ == '__main__':
    main()
