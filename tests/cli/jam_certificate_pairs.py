# cvx-style rotating pairs (hostile75's cvx.py, kind rr): two parts of 1-2 random convex loops
# (small integer coordinates), each turning about an integer pivot; seeded.
import json, random, sys
def hull(pts):
    pts = sorted(set(pts))
    if len(pts) < 3: return None
    def cr(o, a, b): return (a[0]-o[0])*(b[1]-o[1]) - (a[1]-o[1])*(b[0]-o[0])
    lo, up = [], []
    for p in pts:
        while len(lo) >= 2 and cr(lo[-2], lo[-1], p) <= 0: lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(up) >= 2 and cr(up[-2], up[-1], p) <= 0: up.pop()
        up.append(p)
    h = lo[:-1] + up[:-1]
    return h if len(h) >= 3 else None
def randpoly(rng, cx, cy, r):
    for _ in range(100):
        h = hull([(cx+rng.randint(-r, r), cy+rng.randint(-r, r)) for _ in range(rng.randint(3, 6))])
        if h: return h
def boxes_apart(P, Q):
    return (max(x for x, y in P) < min(x for x, y in Q) or max(x for x, y in Q) < min(x for x, y in P) or
            max(y for x, y in P) < min(y for x, y in Q) or max(y for x, y in Q) < min(y for x, y in P))
def gen(seed):
    rng = random.Random(seed)
    def loops(cx, cy, n):
        L = []
        while len(L) < n:
            p = randpoly(rng, cx+rng.randint(-3, 3), cy+rng.randint(-3, 3), rng.randint(1, 3))
            if all(boxes_apart([(x-1, y-1) for x, y in p]+[(x+1, y+1) for x, y in p], q) for q in L): L.append(p)
        return L
    A = loops(0, 0, rng.randint(1, 2)); B = loops(rng.randint(2, 5), rng.randint(-2, 2), rng.randint(1, 2))
    pa = [rng.randint(-2, 2), rng.randint(-2, 2)]
    pb = [rng.randint(3, 7), rng.randint(-2, 2)]
    def lj(L): return [{'start': [str(c) for c in p[0]], 'edges': [{'line_to': [str(c) for c in q]} for q in p[1:]+[p[0]]]} for p in L]
    return {'hipair': 1, 'name': 'cvx-rr-%d' % seed, 'units': {'length': 'mm', 'angle': 'rad'},
            'parts': [{'name': 'a', 'motion': {'rotation': {'pivot': [str(v) for v in pa]}}, 'loops': lj(A)},
                      {'name': 'b', 'motion': {'rotation': {'pivot': [str(v) for v in pb]}}, 'loops': lj(B)}],
            'pairs': [{'parts': ['a', 'b']}]}
if __name__ == '__main__':
    json.dump(gen(int(sys.argv[1])), open(sys.argv[2], 'w'))
