#!/usr/bin/env python3
"""Scale and translation sweep of the example models (issue 13; docs/cspace.md, "scales").

usage:
  scale_sweep.py write MODE K MODEL OUT
      MODE scale: every length times 10^K; translate: every coordinate (points, pivots, template
      centres, spring points, centres of mass) plus 10^K in x and y. JSON numbers are rewritten
      as exact decimal strings (Python's decimal module at 2 000 digits, so 10^400 + 12.5 and
      10^-300 * 12.5 are exact); a value written as an expression becomes "(expr)*(1eK)" or
      "(expr)+(1eK)" (read exactly by the model reader). Lengths, angles and counts follow
      tests/fuzz/scale_model.py; translation leaves lengths, offsets, limits and initial values
      alone (they are differences).
  scale_sweep.py run HIPAIR WORK TIMEOUT MODELS KS [COMMANDS]
      For each model (examples/models/NAME.json, comma-separated, or "all": every example but
      the gears), each mode and each K (comma-separated), write the model, run
      `HIPAIR cspace MODEL --json WORK/...` (and `analyze --quiet` when COMMANDS has analyze),
      each under TIMEOUT seconds, and print one line per run: model, mode, K, command, exit code,
      user seconds, and "same" / "cells (...)" / "DIFF (...)" / "-" comparing the output with
      K = 0's transformed (see compare): "same" every field; "cells" the same C-space (summary():
      cells, their kinds, wraps and neighbour counts, the feature pairs on real edges; 3-DOF:
      critical angles, free cells per slice, crossings, components; pin-slot: free cells per
      slice, changes, groups) cut into other edges or with other witnesses; "DIFF" otherwise.
  scale_sweep.py recompare WORK LOG
      The verdicts of a run's log again, from the outputs it kept in WORK.
  scale_sweep.py compare MODE K OUT0 OUTK
      Compares two `cspace --json` outputs of one pair: every key, list length, label, kind,
      index and boolean equal; every rational number either equal or (scale) equal times 10^K
      (chart coordinates of a rotation are angles, of a translation lengths); the text of exact
      polynomials is compared by its monomials only (their coefficients change with the unit),
      algebraic numbers given by a polynomial and an interval not at all (the same number has
      other defining texts). The sweep reports differences of /statistics
      (work counters: pairs culled, curves kept) apart, in brackets: they are not the C-space.
      Exit 0 when the same, 1 otherwise (first differences on stdout).
"""
import decimal
import fractions
import glob
import json
import os
import re
import resource
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scale_model  # noqa: E402  (the scaler of lengths)

decimal.getcontext().prec = 2000
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GEARS = {"gear-train", "gear-train-3", "spur-gears"}


def exact_text(d):
    """A Decimal as an exact JSON number text (no rounding: prec 2000 holds every result)."""
    d = d.normalize()
    text = format(d, "f") if abs(d.adjusted()) < 40 else format(d, "e")
    return text.replace("E", "e")


class DecimalScaler(scale_model.Scaler):
    def __init__(self, k):
        super().__init__("1e%d" % k)
        self.k = k

    def times(self, value, power=1):
        if power == 0:
            return value
        if isinstance(value, scale_model.Number):
            return scale_model.Number(exact_text(decimal.Decimal(str(value)).scaleb(self.k * power)))
        return super().times(value, power)


class Translator(DecimalScaler):
    """Adds 10^K to both coordinates of every point; lengths and everything else unchanged."""

    def times(self, value, power=1):
        return value

    def coordinate(self, value):
        if isinstance(value, scale_model.Number):
            exact = decimal.Decimal(str(value)) + decimal.Decimal(1).scaleb(self.k)
            if exact - decimal.Decimal(1).scaleb(self.k) != decimal.Decimal(str(value)):
                raise ValueError("inexact translation of %s" % value)
            return scale_model.Number(exact_text(exact))
        return "(%s)+(1e%d)" % (value, self.k)

    def point(self, point):
        if isinstance(point, list):
            return [self.coordinate(c) for c in point]
        if isinstance(point, dict) and "polar" in point:
            polar = dict(point["polar"])
            polar["center"] = self.point(polar["center"])
            return {**point, "polar": polar}
        raise ValueError("not a point: %r" % (point,))

    def feature(self, feature):
        out = {}
        for template, arguments in feature.items():
            out[template] = {key: (self.point(value) if key in scale_model.POINT_ARGUMENTS else value)
                             for key, value in arguments.items()}
        return out


def write_model(mode, k, source, out):
    with open(source, encoding="utf-8") as f:
        model = json.load(f, parse_float=scale_model.Number, parse_int=scale_model.Number)
    transformer = DecimalScaler(k) if mode == "scale" else Translator(k)
    model = transformer.model(model)
    text = scale_model.dump(model) + "\n"
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)


# ---- comparison -------------------------------------------------------------------------------
RATIONAL = re.compile(r"^-?\d+(/\d+)?$")
DECIMAL = re.compile(r"^-?\d+(\.\d+)?(e[-+]?\d+)?$")
VOLATILE = re.compile(r"(^|_)(ms|time|times|seconds|wall)($|_)")


def shape(text):
    """An exact polynomial's or algebraic number's text without its numbers: its monomials."""
    terms = re.split(r" [-+] |^-", text)
    monomials = []
    for t in terms:
        t = re.sub(r"^[\d/]+\*", "", t.strip())
        if t:
            monomials.append("1" if re.fullmatch(r"[\d/]+", t) else t)
    return sorted(monomials)


def summary(d):
    """What the C-space is, without how it is cut: a fixed-axis pair's cells (kind, wraps,
    number of neighbours) and the feature pairs on its real edges; a 3-DOF pair's critical
    angles, free cells per slice, crossings and components; a pin-slot pair's slices' free
    cells, changes and groups (its connections are witnessed, not complete: not compared)."""
    if d.get("kind") == "pin_slot":
        count = lambda v: v if isinstance(v, int) else len(v)  # noqa: E731
        return ("pin_slot", tuple(count(s["free_cells"]) for s in d["slices"]), count(d["changes"]),
                count(d["groups"]))
    if "critical_angles" in d:
        return ("sliced", len(d["critical_angles"]), d["components"],
                tuple(len(s["free_cells"]) for s in d["slices"]), len(d["crossings"]))
    labels = sorted({d["feature_pairs"][i]["label"] for e in d.get("edges", []) if e.get("real")
                     for i in e.get("feature_pairs", [])})
    if "edges" not in d:  # 1-D: the cells' ends
        labels = sorted({d["feature_pairs"][i]["label"] for v in d.get("vertices", [])
                         for i in v.get("curves", []) if isinstance(i, int)})
    cells = sorted((c["kind"], c["wraps_x"], c["wraps_y"], len(c["neighbours"])) for c in d["cells"])
    return ("pair", cells, labels)


def compare_values(a, b, path, mode, k, lengths, out):
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            out.append("%s: keys %s vs %s" % (path, sorted(a), sorted(b)))
            return
        for key in a:
            if VOLATILE.search(key):
                continue
            sub_lengths = lengths
            if key in ("x", "y") and isinstance(a[key], dict) and "kind" in a[key]:
                sub_lengths = a[key]["kind"] != "rotation"
            compare_values(a[key], b[key], path + "/" + key, mode, k, sub_lengths, out)
        return
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append("%s: %d vs %d elements" % (path, len(a), len(b)))
            return
        for i, (x, y) in enumerate(zip(a, b)):
            compare_values(x, y, "%s/%d" % (path, i), mode, k, lengths, out)
        return
    if isinstance(a, str) and isinstance(b, str) and RATIONAL.match(a) and RATIONAL.match(b):
        if a == b:
            return
        if mode == "scale" and lengths is not False:
            if fractions.Fraction(b) == fractions.Fraction(a) * fractions.Fraction(10) ** k:
                return
        if lengths is None:  # a coordinate of unknown kind: equal or scaled both pass
            return
        out.append("%s: %s vs %s" % (path, a[:40], b[:40]))
        return
    if isinstance(a, str) and isinstance(b, str):
        if a == b or shape(a) == shape(b):
            return
        if all(" in (" in t or t.startswith("real root number") for t in (a, b)):
            return  # an algebraic number by its polynomial and interval: other polynomials, other texts
        out.append("%s: %r vs %r" % (path, a[:60], b[:60]))
        return
    if isinstance(a, float) and isinstance(b, float):
        return  # doubles are approximate pictures of exact values
    if isinstance(a, (int, float)) and not isinstance(a, bool) and isinstance(b, str) and DECIMAL.match(b):
        return  # so is a double of a space built in units of 2^L mm, written as a decimal string
    if a != b:
        out.append("%s: %r vs %r" % (path, a, b))


def compare_files(mode, k, file0, filek, summaries=None):
    with open(file0) as f:
        a = json.load(f)
    with open(filek) as f:
        b = json.load(f)
    out = []
    compare_values(a, b, "", mode, k, None, out)
    if summaries is not None:
        summaries.append(summary(a) == summary(b))
    return out


def verdict_of(work, name, mode, k):
    """The comparison of one run's outputs with K = 0's (see the usage)."""
    base = os.path.join(work, "%s.0.cspace" % name)
    stem = os.path.join(work, "%s.%s.%d.cspace" % (name, mode, k))
    files0 = sorted(glob.glob(base + "*.json"))
    filesk = sorted(glob.glob(stem + "*.json"))
    if [f[len(base):] for f in files0] != [f[len(stem):] for f in filesk]:
        return "DIFF (files)"
    diffs, summaries = [], []
    for f0, fk in zip(files0, filesk):
        diffs += compare_files(mode, k, f0, fk, summaries)
    stats = [d for d in diffs if d.startswith("/statistics/")]
    diffs = [d for d in diffs if not d.startswith("/statistics/")]
    if not diffs:
        verdict = "same"
    elif all(summaries):  # the same cells, cut into other edges
        verdict = "cells (%d: %s)" % (len(diffs), diffs[0][:150])
    else:
        verdict = "DIFF (%d: %s)" % (len(diffs), diffs[0][:150])
    if stats:  # work counters (pairs culled, curves kept): not the C-space
        verdict += " [stats: %s]" % stats[0][len("/statistics/"):][:60]
    return verdict


def recompare(work, log):
    """The sweep's log again, each verdict recomputed from the outputs kept in WORK."""
    with open(log) as f:
        for line in f:
            fields = line.split()
            if len(fields) >= 6 and fields[3] == "cspace" and fields[4] == "rc=0" and fields[2] != "0":
                head = line[:line.index("user=") + len("user=") + 8]
                print(head + verdict_of(work, fields[0], fields[1], int(fields[2])))
            else:
                print(line, end="")


# ---- the sweep --------------------------------------------------------------------------------
def run_one(argv, timeout):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        proc = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              timeout=timeout)
        code, err = proc.returncode, proc.stderr.decode(errors="replace").strip()
    except subprocess.TimeoutExpired:
        code, err = "TIMEOUT", ""
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return code, after.ru_utime - before.ru_utime, err


def sweep(hipair, work, timeout, models, ks, commands):
    os.makedirs(work, exist_ok=True)
    if models == "all":
        models = sorted(os.path.basename(p)[:-5] for p in glob.glob(os.path.join(ROOT, "examples/models/*.json")))
        models = [m for m in models if m not in GEARS]
    else:
        models = models.split(",")
    ks = [int(k) for k in ks.split(",")]
    if 0 not in ks:
        ks = [0] + ks
    ks.sort(key=lambda k: k != 0)
    failures = 0
    for name in models:
        source = os.path.join(ROOT, "examples/models", name + ".json")
        for mode in ("scale", "translate"):
            for k in ks:
                if k == 0 and mode == "translate":
                    continue
                tag = "%s.%s.%d" % (name, mode, k) if k else "%s.0" % name
                model = os.path.join(work, tag + ".model.json")
                write_model(mode, k, source, model)
                stem = os.path.join(work, tag + ".cspace")
                for f in glob.glob(stem + "*.json"):
                    os.remove(f)
                code, user, err = run_one([hipair, "cspace", model, "--json", stem + ".json"], timeout)
                verdict = verdict_of(work, name, mode, k) if k and code == 0 else "-"
                if verdict.startswith("DIFF") or code not in (0,):
                    failures += 1
                print("%-20s %-9s %5d cspace  rc=%-7s user=%7.2f %s%s" % (
                    name, mode, k, code, user, verdict,
                    (" | " + err.splitlines()[-1][:140]) if err and code != 0 else ""), flush=True)
                if "analyze" in commands:
                    code, user, err = run_one([hipair, "analyze", model, "--quiet", "--no-pictures"], timeout)
                    print("%-20s %-9s %5d analyze rc=%-7s user=%7.2f%s" % (
                        name, mode, k, code, user,
                        (" | " + err.splitlines()[-1][:140]) if err and code != 0 else ""), flush=True)
    return 1 if failures else 0


def main(argv):
    if len(argv) >= 6 and argv[1] == "write":
        write_model(argv[2], int(argv[3]), argv[4], argv[5])
        return 0
    if len(argv) >= 7 and argv[1] == "run":
        return sweep(argv[2], argv[3], float(argv[4]), argv[5], argv[6],
                     argv[7] if len(argv) > 7 else "cspace")
    if len(argv) == 4 and argv[1] == "recompare":
        recompare(argv[2], argv[3])
        return 0
    if len(argv) == 6 and argv[1] == "compare":
        diffs = compare_files(argv[2], int(argv[3]), argv[4], argv[5])
        for d in diffs[:20]:
            print(d)
        return 1 if diffs else 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
