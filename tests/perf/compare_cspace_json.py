#!/usr/bin/env python3
"""Compares two `hipair cspace --json` outputs as C-spaces, not as arrangements.

Same cells (kind, wrapping, neighbour kinds, the contact chains on their boundary), the same
contact and touching boundary: maximal chains of contact edges per chart, polynomial, feature
pairs and the kinds of the two sides, identified by their end vertices' exact coordinates
(rationals exactly; algebraic numbers by a 12-digit decimal, since the same number may come
with another defining polynomial and isolating interval).
Spurious edges, seams and the splitting of a chain by spurious edges may differ.
Prints the differences; exit 1 if there is one.

  python3 compare_cspace_json.py BEFORE.json AFTER.json
"""
import collections
import json
import re
import sys


def coordinate(c):
    exact = c["exact"]
    if " in (" in exact or " = 0" in exact or "root" in exact:
        # algebraic: its value to 12 digits (the same number comes with different defining
        # polynomials, e.g. another factor of a resultant, and other isolating intervals)
        return "~ %.12g" % c["decimal"]
    return exact


def spaces(document):
    if "edges" in document:
        return [document]
    return document.get("pairs", document.get("spaces", []))


def summary(d):
    cells = d["cells"]
    kind = lambda c: None if c is None else cells[c]["kind"]
    vkey = lambda v: (d["vertices"][v]["chart"], coordinate(d["vertices"][v]["x"]), coordinate(d["vertices"][v]["y"]))
    labels = lambda e: tuple(sorted(d["feature_pairs"][i]["label"] for i in e["feature_pairs"]))
    groups = collections.defaultdict(list)
    for i, e in enumerate(d["edges"]):
        if e["role"] not in ("contact", "touching"):
            continue
        sides = tuple(sorted([str(kind(e["left_cell"])), str(kind(e["right_cell"]))]))
        groups[(e["chart"], e["role"], e["polynomial"], labels(e), sides)].append(i)
    chains = collections.Counter()
    chain_of_edge = {}
    for key, edges in groups.items():
        degree = collections.Counter()
        at = collections.defaultdict(list)
        for i in edges:
            for v in (d["edges"][i]["source"], d["edges"][i]["target"]):
                degree[v] += 1
                at[v].append(i)
        seen = set()
        for i in edges:
            if i in seen:
                continue
            # walk both ways through vertices of degree 2 in the group
            component, stack, ends = [], [i], []
            seen.add(i)
            while stack:
                j = stack.pop()
                component.append(j)
                for v in (d["edges"][j]["source"], d["edges"][j]["target"]):
                    if degree[v] != 2:
                        ends.append(vkey(v))
                        continue
                    for k in at[v]:
                        if k not in seen:
                            seen.add(k)
                            stack.append(k)
            chain = (key, tuple(sorted(ends)))
            chains[chain] += 1
            for j in component:
                chain_of_edge[j] = chain
    cell_list = []
    for c in cells:
        boundary = {chain_of_edge[e] for e in c["boundary_edges"] if e in chain_of_edge}
        neighbours = sorted(str(kind(n)) for n in c.get("neighbours", []))
        cell_list.append((c["kind"], c.get("wraps_x"), c.get("wraps_y"), tuple(neighbours),
                          tuple(sorted(boundary))))
    roles = collections.Counter(e["role"] for e in d["edges"])
    return chains, collections.Counter(cell_list), roles


def main():
    before = json.load(open(sys.argv[1]))
    after = json.load(open(sys.argv[2]))
    a_spaces, b_spaces = spaces(before), spaces(after)
    differ = len(a_spaces) != len(b_spaces)
    for a, b in zip(a_spaces, b_spaces):
        ca, cella, ra = summary(a)
        cb, cellb, rb = summary(b)
        name = a.get("pair", "?")
        if ca != cb:
            differ = True
            print(name, "contact chains differ:", len(ca), "vs", len(cb))
            for c in list((ca - cb).keys())[:5]:
                print("  only before:", c)
            for c in list((cb - ca).keys())[:5]:
                print("  only after:", c)
        if cella != cellb:
            differ = True
            print(name, "cells differ")
        print(name, "edges before", dict(ra), "after", dict(rb), "chains", sum(ca.values()), "cells", sum(cella.values()))
    print("DIFFERENT" if differ else "SAME C-space")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
