#!/usr/bin/env python3
"""Time of the film-advance pin-slot stack against the number of features (issue 13).

Generates variants of examples/models/film-advance.json whose film has K perforation-cut pieces
(4 edges each; K = 8 is the example) below the example's top piece, the film's travel extended
by a pitch per extra piece so that every piece passes the claw, and times
`hipair cspace MODEL --pair film:follower --json OUT` as a fresh process (user CPU seconds,
best of --runs). Prints K, features (film edges + follower edges), CPU seconds, and the growth
exponent of CPU against features (least squares on logs).

  python3 film_features.py HIPAIR [--pieces 2,4,8,16] [--runs 1] [--baseline HIPAIR2]
"""
import argparse
import copy
import json
import math
import os
import resource
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def variant(model, pieces):
    m = copy.deepcopy(model)
    film = next(p for p in m["parts"] if p["name"] == "film")
    pitch = m["parameters"]["pitch"]["nominal"]
    top = 2  # the example's pieces are film -5 .. film 2
    loops = []
    for i in range(top - pieces + 1, top + 1):
        def y(base, k):
            return f"{base} + {k} * pitch" if k >= 0 else f"{base} - {-k} * pitch"
        loops.append({"label": f"film {i}", "start": [20.5, y(-6.2, i)],
                      "edges": [{"line_to": [21.5, y(-6.2, i)]}, {"line_to": [21.5, y(-9.2, i + 1)]},
                                {"line_to": [20.5, y(-9.2, i + 1)]}, {"line_to": [20.5, y(-6.2, i)]}]})
    film["loops"] = loops
    lo, hi = film["motion"]["translation"]["limits"]
    film["motion"]["translation"]["limits"] = [lo, hi + (pieces - 8) * pitch] if pieces >= 8 else [lo, hi]
    return m


def cpu_of(binary, path, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    subprocess.run([binary, "cspace", path, "--pair", "film:follower", "--json", out], check=True,
                   stdout=subprocess.DEVNULL)
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hipair")
    ap.add_argument("--pieces", default="2,4,8,16")
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--baseline")
    args = ap.parse_args()
    model = json.load(open(os.path.join(ROOT, "examples", "models", "film-advance.json")))
    follower = next(p for p in model["parts"] if p["name"] == "follower")
    follower_edges = sum(len(l["edges"]) for l in follower["loops"])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in [int(x) for x in args.pieces.split(",")]:
            path = os.path.join(tmp, f"film{k}.json")
            json.dump(variant(model, k), open(path, "w"))
            t = min(cpu_of(args.hipair, path, os.path.join(tmp, "a.json")) for _ in range(args.runs))
            b = None
            if args.baseline:
                b = min(cpu_of(args.baseline, path, os.path.join(tmp, "b.json")) for _ in range(args.runs))
                same = open(os.path.join(tmp, "a.json")).read() == open(os.path.join(tmp, "b.json")).read()
            features = 4 * k + follower_edges
            rows.append((k, features, t))
            line = f"pieces {k:3d}  features {features:3d}  cpu {t:7.2f} s"
            if b is not None:
                line += f"  baseline {b:7.2f} s  ratio {t / b:5.2f}  json {'identical' if same else 'DIFFERENT'}"
            print(line, flush=True)
    xs = [math.log(f) for _, f, _ in rows]
    ys = [math.log(max(t, 1e-3)) for _, _, t in rows]
    n = len(xs)
    if n >= 2:
        mx, my = sum(xs) / n, sum(ys) / n
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
        print(f"growth exponent (cpu ~ features^e): e = {slope:.2f}")


if __name__ == "__main__":
    sys.exit(main())
