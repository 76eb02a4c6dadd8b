#!/usr/bin/env python3
"""Outputs of a command on a model scaled exactly by 10^K against the unscaled model's (session 53).

usage: scaled_outputs.py HIPAIR SOURCE_DIR WORK COMMAND MODELS SCALES [TIMEOUT]
  COMMAND  analyze (report text, report.json, kinematics.csv), tolerance (stdout, report files) or
           simulate[=T] (--t-end T, default 0.05 time units, --no-pictures: stdout, trajectory.csv,
           events.json, events.txt)
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
        data = json.load(f)

    def clean(value):
        if isinstance(value, dict):
            return {key: clean(v) for key, v in value.items() if key not in ("seconds", "cpu_seconds")}
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


def numbers_moved(base, scaled, k):
    """The first difference between the unscaled text and the scaled one, where every number of the
    scaled one may be the unscaled one's digits with its exponent moved by 0, k or 2k."""
    parts0, parts1 = NUMBER.split(base), NUMBER.split(scaled)
    if len(parts0) != len(parts1):
        return "%d vs %d numbers" % (len(parts0) // 3, len(parts1) // 3)
    for i in range(0, len(parts0), 3):
        if parts0[i] != parts1[i]:
            return "text %r vs %r" % (parts0[i][:80], parts1[i][:80])
        if i + 1 < len(parts0):
            m0, e0, m1, e1 = parts0[i + 1], parts0[i + 2], parts1[i + 1], parts1[i + 2]
            shift = int(e1 or 0) - int(e0 or 0)
            if m0 != m1 or shift not in (0, k, 2 * k):
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


def command_args(command, model, out):
    if command.startswith("simulate"):
        t_end = command.split("=", 1)[1] if "=" in command else "0.05"
        return ["simulate", model, "--t-end", t_end, "--no-pictures", "--out", out]
    if command == "analyze":
        return ["analyze", model, "--quiet", "--no-pictures", "--out", out]
    if command == "tolerance":
        return ["tolerance", model, "--quiet", "--out", out]
    raise SystemExit("scaled_outputs: unknown command " + command)


def compare_run(base, scaled, k, name):
    """The first difference between the unscaled run `base` and the run at 10^k, or None."""
    def streams(a, b):
        return text_difference(a, unit_free_text(b, k, name))

    def file_difference(file, a, b):
        if file.endswith(".json"):
            return first_difference(plain_json(a, 0, name), plain_json(b, k, name))
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
            found = (compare_simulate if command.startswith("simulate") else compare_run)(runs[0], runs[k], k, name)
            print("  x1e%d: %s" % (k, "same" if found is None else "DIFFERENT: " + found))
            failures += found is not None
    print("scaled_outputs: %d difference%s" % (failures, "" if failures == 1 else "s"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
