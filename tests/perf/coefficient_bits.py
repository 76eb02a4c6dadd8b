#!/usr/bin/env python3
"""Coefficient sizes of the contact-curve polynomials of a C-space (`hipair cspace M --json F`).

For every distinct polynomial supporting an edge (seams excluded), the size in bits of its
largest integer coefficient; prints the count, the median and the maximum of those sizes, and
the median over all coefficients. Usage: coefficient_bits.py FILE.json [FILE.json ...]
"""
import json
import re
import statistics
import sys


def sizes(path):
    data = json.load(open(path))
    spaces = data if isinstance(data, list) else [data]
    polynomials = set()
    for space in spaces:
        for edge in space.get("edges", []):
            if edge.get("role") != "seam" and edge.get("polynomial"):
                polynomials.add(edge["polynomial"])
    per_polynomial, every = [], []
    for text in polynomials:
        bits = [int(n).bit_length() for n in re.findall(r"\d+", re.sub(r"\^\d+", "", text))]
        if bits:
            per_polynomial.append(max(bits))
            every.extend(bits)
    return per_polynomial, every


if __name__ == "__main__":
    for path in sys.argv[1:]:
        per_polynomial, every = sizes(path)
        if not per_polynomial:
            print(f"{path}: no polynomials")
            continue
        print(f"{path}: {len(per_polynomial)} polynomials, largest coefficient bits median "
              f"{statistics.median(per_polynomial):.0f}, max {max(per_polynomial)}; all coefficients median "
              f"{statistics.median(every):.0f}")
