#!/usr/bin/env python3
"""The escapement at x 1 with its banking pins' centres written as long decimals (session 55, esc55).

usage: long_digit_escapement.py HIPAIR SOURCE_DIR WORK [DIGITS] [TIMEOUT]
  DIGITS  comma-separated lengths of the literals (default 120,300,600,1200; at least 2 of them)

examples/models/escapement.json has the pins' centres as the expression
(fork-width / 2 + banking-pin-radius + banking-pin-height * sin(banking)) / cos(banking), which the
reader rounds within 1e-12. Here each centre's x is that irrational number written as an exact
decimal literal of DIGITS significant digits (computed here to the last digit, correctly rounded).
Literals of 292 digits and more (numerators beyond 960 bits: curve coefficients beyond the
doubles' range) made `simulate` stop at t = 0.00821243 s with "a jammed contact change" (exit 3):
every point query of the anchor/banking pair answered "in contact". The oracle is the shortest
literal's run: models whose pins differ by less than 10^-(DIGITS-2) mm must give the same outputs
as printed (stdout but its CPU time and paths, trajectory.csv, events.json, events.txt) byte for
byte, and the event sequence of the x 1 model itself (kinds, pairs, features; its times may differ
in the last printed digits: its pins are 1e-12 away). Exit 0 when all agree, 1 otherwise.
"""
from decimal import Decimal, getcontext
import json
import os
import re
import shutil
import subprocess
import sys


def sin_cos(x, digits):
    """sin x, cos x for a small Decimal x by their series, to `digits` + 20 digits."""
    getcontext().prec = digits + 30
    eps = Decimal(10) ** -(digits + 25)
    s, c = Decimal(0), Decimal(0)
    term, n = Decimal(1), 0   # x^n / n!
    while n < 2 or abs(term) > eps:
        if n % 4 == 0:
            c += term
        elif n % 4 == 1:
            s += term
        elif n % 4 == 2:
            c -= term
        else:
            s -= term
        n += 1
        term = term * x / n
    return s, c


def pi(digits):
    """pi by Machin's formula to `digits` + 20 digits."""
    getcontext().prec = digits + 30
    eps = Decimal(10) ** -(digits + 25)

    def arctan_inv(k):
        total, power, n, sign = Decimal(0), Decimal(1) / k, 1, 1
        while power > eps:
            total += sign * power / n
            power /= k * k
            n += 2
            sign = -sign
        return total
    return 16 * arctan_inv(5) - 4 * arctan_inv(239)


def pin_x(digits):
    """(5/2 + 1 + 17 sin 9deg) / cos 9deg with `digits` significant digits."""
    s, c = sin_cos(pi(digits) * 9 / 180, digits)
    value = (Decimal(5) / 2 + 1 + 17 * s) / c
    getcontext().prec = digits
    return +value   # rounded to `digits` significant digits


def model_with(source, digits):
    with open(source, encoding="utf-8") as f:
        model = json.load(f)
    x = format(pin_x(digits), "f")
    banking = next(p for p in model["parts"] if p["name"] == "banking")
    banking["loops"][0]["circle"]["center"][0] = "-" + x
    banking["loops"][1]["circle"]["center"][0] = x
    return model


def simulate(hipair, model_path, out, timeout):
    if os.path.exists(out):
        shutil.rmtree(out)
    try:
        p = subprocess.run([hipair, "simulate", model_path, "--t-end", "0.05", "--no-pictures", "--out", out],
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    text = "\n".join(line for line in p.stdout.splitlines() if not line.startswith("wrote "))
    text = re.sub(r"[0-9.e+-]+ s CPU", "* s CPU", text)
    files = {}
    for name in ("trajectory.csv", "events.json", "events.txt"):
        path = os.path.join(out, name)
        files[name] = open(path, encoding="utf-8").read() if os.path.exists(path) else None
    return p.returncode, text, p.stderr.strip(), files


def event_shape(text):
    """events.txt without its numbers: the kinds, pairs and features in order."""
    return re.sub(r"-?[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?", "#", text or "")


def main(argv):
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    hipair, source_dir, work = argv[1], argv[2], argv[3]
    lengths = [int(d) for d in argv[4].split(",")] if len(argv) > 4 else [120, 300, 600, 1200]
    timeout = float(argv[5]) if len(argv) > 5 else 120
    if len(lengths) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    source = os.path.join(source_dir, "examples", "models", "escapement.json")
    os.makedirs(work, exist_ok=True)
    runs = {}
    for digits in ["x1"] + lengths:
        if digits == "x1":
            path = source
        else:
            path = os.path.join(work, "escapement-%d-digits.json" % digits)
            with open(path, "w", encoding="utf-8") as f:
                json.dump(model_with(source, digits), f, indent=1)
        runs[digits] = simulate(hipair, path, os.path.join(work, "out-%s" % digits), timeout)
    failures = []
    reference = runs[lengths[0]]
    x1 = runs["x1"]
    if x1 is None or x1[0] != 0:
        failures.append("x 1: %s" % ("timed out" if x1 is None else "exit %d: %s" % (x1[0], x1[2])))
    for digits in lengths:
        run = runs[digits]
        if run is None:
            failures.append("%d digits: timed out" % digits)
            continue
        if run[0] != 0:
            failures.append("%d digits: exit %d: %s" % (digits, run[0], run[2]))
            continue
        if digits != lengths[0]:
            if run[1] != reference[1]:
                failures.append("%d digits: stdout differs from %d digits'" % (digits, lengths[0]))
            for name, text in run[3].items():
                if text != reference[3][name]:
                    failures.append("%d digits: %s differs from %d digits'" % (digits, name, lengths[0]))
        if x1 is not None and event_shape(run[3]["events.txt"]) != event_shape(x1[3]["events.txt"]):
            failures.append("%d digits: the event sequence differs from x 1's" % digits)
    for f in failures:
        print("DIFFERENT: " + f)
    if not failures:
        events = (x1[3]["events.txt"] or "").count("\n")
        print("long-digit escapement: %s digits and x 1 agree (%d event lines)" % (",".join(map(str, lengths)), events))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
