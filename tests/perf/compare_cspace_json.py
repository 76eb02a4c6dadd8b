#!/usr/bin/env python3
"""Compares two `hipair cspace --json` outputs as C-spaces, not as arrangements.

Same cells (kind, wrapping, neighbour kinds, the contact chains on their boundary), the same
contact and touching boundary: maximal chains of contact edges per chart, polynomial, feature
pairs and the kinds of the two sides, identified by their end vertices' exact coordinates
(rationals exactly; algebraic numbers by overlapping isolating intervals, since the same number
may come with another defining polynomial and interval; a chain's end is matched to one of the
other's). Cells are compared by kind, wrapping, neighbour kinds and their number of contact
chains.
Spurious edges, seams and the splitting of a chain by spurious edges may differ.
Prints the differences; exit 1 if there is one.

  python3 compare_cspace_json.py [--up-to-sign] BEFORE.json AFTER.json

--up-to-sign compares edge polynomials up to their overall sign (the quadratic traits exports a
chart's curve as generated, CGAL's algebraic traits with a positive leading coefficient: the
same curve and the same sides, see docs/performance.md).
"""
import collections
from fractions import Fraction
import json
import re
import sys

UP_TO_SIGN = False


def polynomial_key(text):
    """The polynomial text, with every term's sign flipped when UP_TO_SIGN and it starts with '-'."""
    t = text.strip()
    if not UP_TO_SIGN or not t.startswith("-"):
        return t
    return re.sub(r" ([+-]) ", lambda m: " - " if m.group(1) == "+" else " + ", t[1:])


def coordinate(c):
    """A rational exactly; an algebraic number as (lower, upper) of its isolating interval
    (the same number may come with another defining polynomial and interval)."""
    exact = c["exact"]
    if "interval" in c:
        lo, hi = (Fraction(v) for v in c["interval"])
        return ("algebraic", float(lo), float(hi))
    return ("rational", exact)


def same_point(a, b):
    # the same vertex: equal rationals, or overlapping enclosures (a rational inside one)
    def bounds(c):
        if c[0] == "algebraic":
            return c[1], c[2]
        v = float(Fraction(c[1]))
        return v, v
    if a[0] == "rational" and b[0] == "rational":
        return a[1] == b[1]
    (alo, ahi), (blo, bhi) = bounds(a), bounds(b)
    slack = 1e-12 * (1 + abs(alo) + abs(blo))
    return alo <= bhi + slack and blo <= ahi + slack


def same_ends(a, b):
    # two chains' sorted end lists: the same vertices in some order
    if len(a) != len(b):
        return False
    used = [False] * len(b)
    for p in a:
        for k, q in enumerate(b):
            if not used[k] and p[0] == q[0] and same_point(p[1], q[1]) and same_point(p[2], q[2]):
                used[k] = True
                break
        else:
            return False
    return True


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
        groups[(e["chart"], e["role"], polynomial_key(e["polynomial"]), labels(e), sides)].append(i)
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
            chain = (key, tuple(sorted(ends, key=repr)))
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


def matched(a, b):
    """Counters of chains a and b are the same up to equal vertices (same_ends)."""
    left = [c for c, n in a.items() for _ in range(n)]
    right = [c for c, n in b.items() for _ in range(n)]
    by_key = collections.defaultdict(list)
    for k, c in enumerate(right):
        by_key[c[0]].append(k)
    used = set()
    unmatched = []
    for c in left:
        for k in by_key.get(c[0], []):
            if k not in used and same_ends(c[1], right[k][1]):
                used.add(k)
                break
        else:
            unmatched.append(c)
    return unmatched, [right[k] for k in range(len(right)) if k not in used]


def main():
    global UP_TO_SIGN
    args = sys.argv[1:]
    if args and args[0] == "--up-to-sign":
        UP_TO_SIGN = True
        args = args[1:]
    before = json.load(open(args[0]))
    after = json.load(open(args[1]))
    a_spaces, b_spaces = spaces(before), spaces(after)
    differ = len(a_spaces) != len(b_spaces)
    for a, b in zip(a_spaces, b_spaces):
        ca, cella, ra = summary(a)
        cb, cellb, rb = summary(b)
        name = a.get("pair", "?")
        only_a, only_b = matched(ca, cb)
        if only_a or only_b:
            differ = True
            print(name, "contact chains differ:", len(only_a), "only before,", len(only_b), "only after")
            for c in only_a[:5]:
                print("  only before:", c)
            for c in only_b[:5]:
                print("  only after:", c)
        # cells: kinds, wrapping, neighbour kinds and how many contact chains bound them
        shape = lambda cells: collections.Counter((c[0], c[1], c[2], c[3], len(c[4])) for c in cells.elements())
        if shape(cella) != shape(cellb):
            differ = True
            print(name, "cells differ")
        print(name, "edges before", dict(ra), "after", dict(rb), "chains", sum(ca.values()), "cells", sum(cella.values()))
    print("DIFFERENT" if differ else "SAME C-space")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
