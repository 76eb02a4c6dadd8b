#!/usr/bin/env python3
"""Outputs of a command on a model scaled exactly by 10^K against the unscaled model's (session 53).

usage: scaled_outputs.py HIPAIR SOURCE_DIR WORK COMMAND MODELS SCALES [TIMEOUT]
  COMMAND  analyze (report text, report.json, kinematics.csv), tolerance[=OPTIONS] (stdout, report
           files; OPTIONS: more options of the run, separated by spaces),
           simulate[=T] (--t-end T, default 0.05 time units, --no-pictures: stdout, trajectory.csv,
           events.json, events.txt) or sweep=NAME=A:B:N[@T] (simulate --sweep NAME=A:B:N --t-end T:
           stdout, sweep.json), cycle (analyze of a pin-in-slot mechanism: cycle.json) or cspace (--json: the pin-in-slot stacks, lengths times 10^K exactly)
  MODELS   comma-separated example names (examples/models/NAME.json)
  SCALES   comma-separated exponents K (e.g. -300,-30,30,400): the model is written by
           tests/fuzz/scale_model.py with every length times 1eK (exactly)

The oracle is the unscaled run: the scaled run must exit with the same code and, once the model's
name ("NAME-x1eK") and the run's own paths and timings are set aside, give the same outputs with
every length shown times 10^K exactly: a length the unscaled run prints as "12.500 mm" is
"12.500eK mm" when the analysis ran in units of 10^K mm (a power of ten chosen from the model,
core/model_scale.hpp kinematic_decimal_exponent) or "12.500 mm" when it ran as is (K = +-30 at
most: lengths within the doubles' range), report.json's "units"/"length" is "1eK mm" or "mm"
accordingly, and every other value (angles, events, verdicts, contact labels, closed forms,
counts) is identical. Refusals must give the same message. Exit 0 when every scale matches,
1 otherwise (the differences printed), 2 on usage errors.

simulate (session 53, scale53b): a model whose run is rescaled (src/cli/simulate.cpp
simulated_model) shows quantities in mm and N with the printed decimal's exponent moved by
j * K (j = 1: lengths, speeds, forces, impulses; 2: energies; 0: times, angles): every number of
the scaled run's text must be the unscaled run's digits with its exponent moved by 0, K or 2K
(its own text otherwise identical; the CPU time set aside); trajectory.csv and events.json hold
the same numbers in units of 10^K mm (identical), their headers and "units" naming those units.
"""
import json
import os
from fractions import Fraction
import re
import shutil
import subprocess
import sys


def run(hipair, args, cwd, timeout):
    try:
        done = subprocess.run([hipair] + args, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", "timeout"
    return done.returncode, done.stdout, done.stderr


def unit_free_text(text, k, name):
    """The text with the scaled model's name and the lengths' exponent taken out."""
    text = text.replace("%s-x1e%d" % (name, k), name)
    text = re.sub(r"(?<![\d.])1e%d ?mm\b" % k, "mm", text)   # a unit named: "1e400 mm", "_1e400mm"
    # a decimal followed by its exponent: "12.500e400" -> "12.500"; "rad/mm" ratios carry -K
    text = re.sub(r"(\d)e%d\b" % k, r"\1", text)
    text = re.sub(r"(\d)e%d\b" % -k, r"\1", text)
    return text


def plain_json(path, k, name):
    with open(path, encoding="utf-8") as f:
        return plain_json_data(json.load(f), k, name)


def plain_json_data(data, k, name):
    def clean(value):
        if isinstance(value, dict):   # keys naming the unit 10^K mm ("advance_1e400mm") as "advance_mm"
            return {re.sub(r"_1e%dmm\b" % k, "_mm", key): clean(v) for key, v in value.items()
                    if key not in ("seconds", "cpu_seconds") and not key.startswith("seconds_")}
        if isinstance(value, list):
            return [clean(v) for v in value]
        if isinstance(value, str):
            return unit_free_text(value, k, name)
        return value

    return clean(data)


def first_difference(a, b, where=""):
    if type(a) is not type(b):
        return "%s: %r vs %r" % (where or "/", a, b)
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return "%s/%s: only in one" % (where, key)
            found = first_difference(a[key], b[key], where + "/" + key)
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return "%s: %d vs %d entries" % (where, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, "%s/%d" % (where, i))
            if found:
                return found
        return None
    return None if a == b else "%s: %r vs %r" % (where or "/", a, b)


def text_difference(a, b):
    la, lb = a.splitlines(), b.splitlines()
    for i, (x, y) in enumerate(zip(la, lb)):
        if x != y:
            return "line %d: %r vs %r" % (i + 1, x, y)
    return None if len(la) == len(lb) else "%d vs %d lines" % (len(la), len(lb))


NUMBER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?)(?:e([+-]?\d+))?(?![\w.])")


def numbers_moved(base, scaled, k, shifts=None):
    """The first difference between the unscaled text and the scaled one, where every number of the
    scaled one may be the unscaled one's digits with its exponent moved by 0, k or 2k (or by one
    of `shifts`)."""
    shifts = shifts or (0, k, 2 * k)
    parts0, parts1 = NUMBER.split(base), NUMBER.split(scaled)
    if len(parts0) != len(parts1):
        return "%d vs %d numbers" % (len(parts0) // 3, len(parts1) // 3)
    for i in range(0, len(parts0), 3):
        if parts0[i] != parts1[i]:
            return "text %r vs %r" % (parts0[i][:80], parts1[i][:80])
        if i + 1 < len(parts0):
            m0, e0, m1, e1 = parts0[i + 1], parts0[i + 2], parts1[i + 1], parts1[i + 2]
            shift = int(e1 or 0) - int(e0 or 0)
            if m0 != m1 or shift not in shifts:
                return "number %s%s vs %s%s" % (m0, "e" + e0 if e0 else "", m1, "e" + e1 if e1 else "")
    return None


def simulate_text(text, k, name):
    text = text.replace("%s-x1e%d" % (name, k), name)
    text = re.sub(r"_1e%dmm(_per_[a-z]+)?" % k, "", text)   # trajectory.csv's columns in units of 10^K mm
    return re.sub(r"[0-9.e+-]+ s CPU", "@ s CPU", text)


def compare_dirs(base, scaled, streams, file_difference):
    """The first difference between the unscaled run `base` and a scaled run, or None: each run is
    (exit code, stdout, stderr, output folder); `streams(a, b)` compares the unscaled and the
    scaled stdout (then stderr) once the runs' own folders are named alike, and
    `file_difference(file, a, b)` the two copies of each file of the folders (None: the same)."""
    (rc0, out0, err0, dir0), (rc1, out1, err1, dir1) = base, scaled
    if rc1 is None:
        return "timed out"
    if rc0 != rc1:
        return "exit %s vs %s (%s)" % (rc0, rc1, (err1 or err0).strip()[:300])
    # the run's own directory is named in "wrote ..." lines
    found = streams(out0.replace(dir0, "@OUT@"), out1.replace(dir1, "@OUT@")) or \
        streams(err0.replace(dir0, "@OUT@"), err1.replace(dir1, "@OUT@"))
    if found:
        return "stdout/stderr " + found
    files0 = sorted(os.listdir(dir0)) if os.path.isdir(dir0) else []
    files1 = sorted(os.listdir(dir1)) if os.path.isdir(dir1) else []
    if files0 != files1:
        return "files %s vs %s" % (files0, files1)
    for file in files0:
        found = file_difference(file, os.path.join(dir0, file), os.path.join(dir1, file))
        if found:
            return "%s %s" % (file, found)
    return None


def read_text(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def compare_simulate(base, scaled, k, name):
    def streams(a, b):
        return numbers_moved(simulate_text(a, 0, name), simulate_text(b, k, name), k)

    def file_difference(file, a, b):
        ta, tb = read_text(a), read_text(b)
        if file == "events.json":
            ja, jb = json.loads(ta), json.loads(tb)
            found = None
            units = jb.get("units", {})
            if "1e%d mm" % k == units.get("length"):   # run in units of 10^K mm: named so
                force = ja["units"]["force"]
                if units.get("force") != "1e%d %s" % (k, force) or units.pop("energy", None) != "1e%d %s·mm" % (2 * k, force):
                    found = "units %r" % units
                units["force"], units["length"] = force, "mm"
            ja["model"] = jb["model"] = name
            if "chord_deviation_1e%dmm" % k in jb:   # a planar run's chord deviation in units of 10^K mm
                jb["chord_deviation_mm"] = jb.pop("chord_deviation_1e%dmm" % k)
            return found or first_difference(ja, jb)
        if file == "events.txt":
            return numbers_moved(ta, tb, k)
        return text_difference(simulate_text(ta, 0, name), simulate_text(tb, k, name))

    return compare_dirs(base, scaled, streams, file_difference)


def tolerance_text(text, k, name):
    """The scaled tolerance run's text with the model's name and its CSV columns' unit taken out
    ("nominal_1e400mm": a translating part's coordinates in units of 10^K mm)."""
    text = text.replace("%s-x1e%d" % (name, k), name)
    return re.sub(r"_1e%dmm\b" % k, "", text)


def unit_named(data, key, k):
    """data[key] when it names the unit 10^K mm ("1e400 mm") turned into "mm"; an error text when
    it names another power of ten."""
    value = data.get(key)
    if isinstance(value, str) and value.startswith("1e") and value.endswith(" mm"):
        if value != "1e%d mm" % k:
            return "%s %r" % (key, value)
        data[key] = "mm"
    return None


def certificate_margins(a, b, k):
    """A tolerance certificate's leaves' second-order margins (values of contact functions, of
    degree 2 or 4 in lengths: session 56) in the scaled run's certificate are the unscaled one's
    times 10^2K or 10^4K exactly; set equal once checked (None), else the difference."""
    leaves_a = a.get("tolerance", {}).get("leaves", []) if isinstance(a.get("tolerance"), dict) else []
    leaves_b = b.get("tolerance", {}).get("leaves", []) if isinstance(b.get("tolerance"), dict) else []
    for i, (la, lb) in enumerate(zip(leaves_a, leaves_b)):
        ma = la.get("witness", {}).get("second_order_margins")
        mb = lb.get("witness", {}).get("second_order_margins")
        if ma is None or mb is None or len(ma) != len(mb):
            continue   # left to the comparison of the whole
        for x, y in zip(ma, mb):
            if Fraction(y) not in (Fraction(x) * Fraction(10) ** (2 * k), Fraction(x) * Fraction(10) ** (4 * k)):
                return "leaf %d: second-order margin %s vs %s" % (i, x, y[:40])
        lb["witness"]["second_order_margins"] = ma
    return None


def compare_tolerance(base, scaled, k, name):
    """`hipair tolerance` (session 54, scale54): a mechanism at 10^K is analysed on its copy divided
    by 10^E (E = K for a model scaled from an ordinary one), so the scaled run's text is the
    unscaled one with each number the same digits, its exponent moved by 0 (angles, shares,
    counts) or K (lengths: a translating part's coordinates, bands, plays, sensitivities and
    contributions of a translating follower); tolerance.json, variation.csv and sensitivity.csv
    hold the same numbers in units of 10^K mm, their "length_unit" / "follower_unit" and column
    names naming that unit."""
    dir0, dir1 = base[3], scaled[3]

    def timeless(text):   # the Monte Carlo's and the certificate's times ("... in 2.41 s")
        return re.sub(r"\bin [0-9.]+ s\b", "in @ s", text)

    def streams(a, b):
        return numbers_moved(timeless(a), tolerance_text(timeless(b), k, name), k, (0, k))

    def file_difference(file, a, b):
        ta, tb = timeless(read_text(a)), timeless(read_text(b))
        if file.endswith(".json"):
            ja, jb = json.loads(ta), json.loads(tb)
            found = unit_named(jb, "follower_unit", k)
            if not found and "length_unit" in jb:   # named only when the run is in units of 10^K mm
                unit = jb.pop("length_unit")
                if "length_unit" in ja or unit != "1e%d mm" % k:
                    found = "length_unit %r" % unit
            ja["model"] = jb["model"] = name
            found = found or certificate_margins(ja, jb, k)
            return found or first_difference(plain_json_data(ja, 0, name), plain_json_data(jb, k, name))
        if file.endswith(".csv"):
            return text_difference(ta, tolerance_text(tb, k, name))
        if file.endswith(".txt"):
            return numbers_moved(ta.replace(dir0, "@OUT@"), tolerance_text(tb.replace(dir1, "@OUT@"), k, name), k, (0, k))
        return None   # pictures: the same doubles, their axis labels naming the unit

    return compare_dirs(base, scaled, streams, file_difference)


def sweep_text(text, k, name):
    """A sweep's stdout with the model's name and the CPU-time column (cpu_s) set aside."""
    text = text.replace("%s-x1e%d" % (name, k), name)
    lines = text.splitlines()
    column = None
    for i, line in enumerate(lines):
        cells = line.split("\t")
        if column is None and "cpu_s" in cells:
            column = cells.index("cpu_s")
        elif column is not None and len(cells) > column:
            cells[column] = "@"
            lines[i] = "\t".join(cells)
    return "\n".join(lines)


def compare_sweep(base, scaled, k, name):
    """`hipair simulate --sweep` (session 54, scale54): each run of a mechanism at 10^K simulated
    on its rescaled copy as the unscaled run is: the same rows (status, verdict, steps, events,
    swings), a translating part's advance shown in mm (the digits, exponent moved by K); sweep.json
    the same numbers in units of 10^K mm ("units" naming them), CPU times set aside."""
    def streams(a, b):
        return numbers_moved(sweep_text(a, 0, name), sweep_text(b, k, name), k, (0, k))

    def file_difference(file, a, b):
        ja, jb = json.loads(read_text(a)), json.loads(read_text(b))
        units = jb.pop("units", None)
        if units != {"length": "1e%d mm" % k} and (units is not None or "units" in ja):
            return "units %r" % units
        ja["model"] = jb["model"] = name
        return first_difference(plain_json_data(ja, 0, name), plain_json_data(jb, k, name))

    return compare_dirs(base, scaled, streams, file_difference)


def exact_scaled(a, b, k, where):
    """The first difference between the unscaled pin-slot stack `a` and the scaled one `b`: every
    "offset" and "slide" (an exact rational in mm) of b is a's times 10^K exactly, everything else
    (tau, angles, cells, contacts, groups, critical values) identical."""
    if isinstance(a, dict) and isinstance(b, dict):
        if sorted(a) != sorted(b):
            return "%s: keys %s vs %s" % (where or "/", sorted(a), sorted(b))
        for key in sorted(a):
            if key in ("offset", "slide") and isinstance(a[key], str):
                if Fraction(b[key]) != Fraction(a[key]) * Fraction(10) ** k:
                    return "%s/%s: %s vs %s" % (where, key, a[key][:40], b[key][:40])
                continue
            found = exact_scaled(a[key], b[key], k, where + "/" + key)
            if found:
                return found
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return "%s: %d vs %d entries" % (where, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            found = exact_scaled(x, y, k, "%s/%d" % (where, i))
            if found:
                return found
        return None
    return None if a == b else "%s: %r vs %r" % (where or "/", a, b)


def compare_cspace(base, scaled, k, name):
    """`hipair cspace --json` of a mechanism with pin-in-slot pairs (session 54, scale54): each
    pin-slot stack of the scaled model is the unscaled one's, its lengths (samples' and witnesses'
    offsets and slides, exact) times 10^K exactly (exact_scaled); the other pairs' files are left
    to tests/fuzz/scaled_cli.sh (their exact curves are the scaled model's)."""
    stacks = []

    def file_difference(file, a, b):
        ja, jb = json.loads(read_text(a)), json.loads(read_text(b))
        if ja.get("kind") != "pin_slot":
            return None
        stacks.append(file)
        return exact_scaled(ja, jb, k, "")

    found = compare_dirs(base, scaled, lambda a, b: None, file_difference)
    return found or (None if stacks else "no pin-slot stack written")


def command_args(command, model, out):
    if command == "cspace":
        os.makedirs(out, exist_ok=True)
        return ["cspace", model, "--json", os.path.join(out, "cspace.json")]
    if command.startswith("sweep="):
        spec, _, t_end = command[len("sweep="):].partition("@")
        return ["simulate", model, "--t-end", t_end or "0.05", "--sweep", spec, "--jobs", "1",
                "--allow-out-of-tolerance", "--out", out]
    if command.startswith("simulate"):
        t_end = command.split("=", 1)[1] if "=" in command else "0.05"
        return ["simulate", model, "--t-end", t_end, "--no-pictures", "--out", out]
    if command == "analyze":
        return ["analyze", model, "--quiet", "--no-pictures", "--out", out]
    if command == "cycle":   # a pin-in-slot mechanism's work cycle (analyze takes no --no-pictures there)
        return ["analyze", model, "--quiet", "--out", out]
    if command == "tolerance" or command.startswith("tolerance="):   # tolerance=OPTIONS: more options
        extra = command.split("=", 1)[1].split() if "=" in command else []
        return ["tolerance", model, "--quiet"] + extra + ["--out", out]
    raise SystemExit("scaled_outputs: unknown command " + command)


def compare_run(base, scaled, k, name):
    """The first difference between the unscaled run `base` and the run at 10^k, or None."""
    def streams(a, b):
        return text_difference(a, unit_free_text(b, k, name))

    def file_difference(file, a, b):
        if file.endswith(".json"):
            ja, jb = plain_json(a, 0, name), plain_json(b, k, name)
            if "units" not in ja and jb.get("units") == {"length": "mm"}:   # named only in units of 10^K mm
                del jb["units"]
            return first_difference(ja, jb)
        if file.endswith(".csv") or file.endswith(".txt"):
            return text_difference(read_text(a), unit_free_text(read_text(b), k, name))
        return None   # pictures: their numbers are the same doubles, their labels name the unit

    return compare_dirs(base, scaled, streams, file_difference)


def main(argv):
    if len(argv) < 7:
        sys.stderr.write(__doc__)
        return 2
    hipair, source, work, command, models, scales = argv[1:7]
    timeout = float(argv[7]) if len(argv) > 7 else 120
    hipair = os.path.abspath(hipair)
    work = os.path.abspath(work)
    os.makedirs(work, exist_ok=True)
    failures = 0
    for name in models.split(","):
        model = os.path.join(source, "examples", "models", name + ".json")
        runs = {}
        for k in [0] + [int(s) for s in scales.split(",")]:
            path = model
            if k != 0:
                path = os.path.join(work, "%s@1e%d.json" % (name, k))
                subprocess.run([sys.executable, os.path.join(source, "tests", "fuzz", "scale_model.py"), model,
                                "1e%d" % k, path], check=True)
            out = os.path.join(work, "out", "%s@%d" % (name, k))
            shutil.rmtree(out, ignore_errors=True)
            os.makedirs(os.path.dirname(out), exist_ok=True)
            rc, stdout, stderr = run(hipair, command_args(command, path, out), work, timeout)
            runs[k] = (rc, stdout, stderr, out)
            if k == 0:
                print("%s %s: exit %s" % (command, name, rc))
                continue
            compare = (compare_simulate if command.startswith("simulate") else compare_sweep if command.startswith("sweep=")
                       else compare_tolerance if command.split("=")[0] == "tolerance" else compare_cspace if command == "cspace"
                       else compare_run)
            found = compare(runs[0], runs[k], k, name)
            print("  x1e%d: %s" % (k, "same" if found is None else "DIFFERENT: " + found))
            failures += found is not None
    print("scaled_outputs: %d difference%s" % (failures, "" if failures == 1 else "s"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
