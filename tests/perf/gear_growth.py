#!/usr/bin/env python3
"""Growth of every C-space build stage with the tooth count (issue 14: every stage <= n^1.1).

Builds the operating region of examples/models/spur-gears.json with n x n teeth (the same
module, pressure angle, backlash and tooth family for every n: only teeth-1 = teeth-2 = n
change) with one `hipair` binary, over a sweep of tooth counts, and measures each build stage:

  * time: `hipair cspace ... --stats` prints the builder's stage clocks (CSpaceStatistics: the
    region flood, curve generation, culling, clipping, insertion, export, labelling,
    classification, cells; wall seconds of the building thread) and the child's CPU seconds
    (wait4's rusage) give the whole process; "rest" = process CPU - the build's total (model
    reading, JSON writing, start-up).
  * instructions (with --callgrind): one callgrind run per n; each stage's instructions are the
    inclusive cost of the functions that make it (STAGES below, matched on callgrind_annotate's
    demangled names). These are the reliable figures on a shared machine.

Then fits, per stage, the exponent k of cost ~ c n^k by least squares on log cost against log n
(with the slope's standard error and the smallest and largest local exponent between neighbouring
tooth counts), and writes OUTDIR/growth.md (the tables), OUTDIR/growth.json (the figures) and
OUTDIR/growth.svg (log-log plot: each stage's points and fitted line, and the n^1.1 slope).
The JSON C-spaces of every n are kept in OUTDIR/json/ (compare two binaries' with cmp).

  python3 tests/perf/gear_growth.py HIPAIR OUTDIR [--teeth 10,14,20,28,40,56,80] [--callgrind]
                                                  [--runs R] [--fit-from N]
  python3 tests/perf/gear_growth.py --report OUTDIR [--fit-from N]   (tables and plot again)

Not a CTest test: a developer's tool (a callgrind sweep takes about ten minutes of CPU).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = os.path.join(HERE, "..", "..", "examples", "models", "spur-gears.json")

# Stage -> regular expressions on callgrind's (demangled) function names; a stage's instructions
# are the sum over its expressions of the largest inclusive cost of a function matching it (the
# function itself, not its lambdas or cold parts, which it includes), less the stages named in
# its "minus" list (what remains of a function once other stages are taken out of it). The
# functions are those holding the builder's stage clocks; "process" is the program's total.
STAGES = [
    ("reading", [r"^hipair::read_model_file\("], []),
    ("region flood", [r"^hipair::\(anonymous namespace\)::flood_region\("], []),
    ("curves", [r"^hipair::cspace::CurveGenerator::generate\(", r"^hipair::cspace::BlockedCells::BlockedCells\("], []),
    ("culling", [r"prepare_chart\("], []),
    ("clipping", [r"QuadraticBuilder::clip\(", r"^hipair::cspace::raw::group_curves\("], []),
    ("export", [r"QuadraticBuilder::export_topology\("], []),
    ("insertion", [r"^hipair::cspace::raw::build_quadratic_arrangement\("], ["clipping", "export"]),
    ("labelling", [r"label_edges\("], []),
    ("classification", [r"classify_faces\(", r"find_touching\("], []),
    ("cells, rest of build", [r"^hipair::cspace::build_cspace\("],
     ["curves", "culling", "clipping", "export", "insertion", "labelling", "classification"]),
    ("json", [r"write_space_json\("], []),
    ("process", [r"^PROGRAM TOTALS$"], []),
    ("setup, rest of process", [r"^PROGRAM TOTALS$"],
     ["reading", "region flood", "curves", "culling", "clipping", "export", "insertion", "labelling", "classification",
      "cells, rest of build", "json"]),
]
# The builder's clocks (stdout of --stats), stage -> the printed name
CLOCKS = ["region", "curves", "culling", "clipping", "arrangement", "export", "labelling", "classification", "cells",
          "total"]


def hipair_command(binary, n, json_path, stats):
    return [binary, "cspace", MODEL, "--set", "teeth-1=%d" % n, "--set", "teeth-2=%d" % n, "--allow-out-of-tolerance",
            "--region", "operating", "--json", json_path] + (["--stats"] if stats else [])


def run_timed(command):
    """stdout, exit code and the child's CPU seconds (user + system)."""
    child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    out = child.stdout.read()
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    return out, child.returncode, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0


def parse_stats(text):
    clocks = {}
    m = re.search(r"flooded in ([0-9.]+) ms", text)
    clocks["region"] = float(m.group(1)) / 1e3 if m else 0.0
    m = re.search(r"time \(ms\): (.*)", text)
    if not m:
        raise RuntimeError("no stage times in the --stats output")
    for item in m.group(1).split(","):
        name, value = item.strip().rsplit(" ", 1)
        clocks[name] = float(value) / 1e3
    counts = {}
    for key, pattern in (("curves", r"curves (\d+);"), ("vertices", r"vertices (\d+),"), ("tiles", r"region: (\d+) tiles"),
                         ("quadratic_charts", r"quadratic-traits arrangements \(degree <= 2 in y\): (\d+)"),
                         ("charts", r"\((?:\d)-D, (\d+) charts\)")):
        m = re.search(pattern, text)
        counts[key] = int(m.group(1)) if m else 0
    return clocks, counts


def inclusive_costs(callgrind_file):
    """function name -> inclusive Ir (callgrind_annotate --inclusive=yes), "PROGRAM TOTALS" too."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", callgrind_file],
                          capture_output=True, text=True, check=True).stdout
    costs = {}
    for line in text.splitlines():
        m = re.match(r"^\s*([0-9,]+)\s+(?:\([ 0-9.%]+\)\s+)?PROGRAM TOTALS", line)
        if m:
            costs["PROGRAM TOTALS"] = int(m.group(1).replace(",", ""))
            continue
        m = re.match(r"^\s*([0-9,]+)\s+(?:\([ 0-9.%]+\)\s+)?([^:\s]*):(.*?)(?:\s+\[[^\]]*\])?\s*$", line)
        if not m:
            continue
        value = int(m.group(1).replace(",", ""))
        name = m.group(3).strip()
        costs[name] = max(costs.get(name, 0), value)
    return costs


def stage_instructions(costs):
    result = {}
    for stage, patterns, minus in STAGES:
        total = 0
        for pattern in patterns:
            regex = re.compile(pattern)
            total += max([v for name, v in costs.items() if regex.search(name) and "[clone .cold]" not in name] or [0])
        total -= sum(result.get(m, 0) for m in minus)
        result[stage] = total
    return result


def fit(ns, values):
    """(exponent, its standard error, smallest and largest local exponent) of values ~ c n^k."""
    points = [(math.log(n), math.log(v)) for n, v in zip(ns, values) if v > 0]
    if len(points) < 2:
        return None
    mx = sum(x for x, _ in points) / len(points)
    my = sum(y for _, y in points) / len(points)
    sxx = sum((x - mx) ** 2 for x, _ in points)
    k = sum((x - mx) * (y - my) for x, y in points) / sxx
    c = my - k * mx
    residual = sum((y - c - k * x) ** 2 for x, y in points)
    error = math.sqrt(residual / (len(points) - 2) / sxx) if len(points) > 2 else 0.0
    local = [(b[1] - a[1]) / (b[0] - a[0]) for a, b in zip(points, points[1:])]
    return {"exponent": k, "stderr": error, "local_min": min(local), "local_max": max(local), "log_c": c}


def report(outdir, fit_from):
    with open(os.path.join(outdir, "growth.json")) as f:
        data = json.load(f)
    rows = sorted(data["runs"], key=lambda r: r["teeth"])
    rows = [r for r in rows if r["teeth"] >= fit_from]
    ns = [r["teeth"] for r in rows]
    lines = ["Tooth counts %s (n x n teeth, operating region, `cspace --json`)." % ", ".join(map(str, ns)), ""]
    series = {}
    have_ir = all("instructions" in r for r in rows)
    if have_ir:
        lines += ["Instructions per stage (M, callgrind inclusive) and the fitted exponent k (cost ~ n^k, least "
                  "squares on log-log; ± its standard error; [smallest, largest] exponent between neighbouring n):", ""]
        stages = [s for s, _, _ in STAGES]
        lines.append("| stage | " + " | ".join("n=%d" % n for n in ns) + " | k | local k |")
        lines.append("|---|" + "---|" * (len(ns) + 2))
        for stage in stages:
            values = [r["instructions"][stage] for r in rows]
            f = fit(ns, values)
            series["Ir " + stage] = (values, f)
            cells = " | ".join("%.1f" % (v / 1e6) for v in values)
            lines.append("| %s | %s | %s | %s |" % (
                stage, cells, "%.2f ± %.2f" % (f["exponent"], f["stderr"]) if f else "—",
                "[%.2f, %.2f]" % (f["local_min"], f["local_max"]) if f else "—"))
        lines.append("")
    lines += ["Stage clocks (s, the builder's wall clocks of `--stats`, median of the runs) and process CPU (s):", ""]
    names = CLOCKS + ["process CPU", "rest (CPU - total)"]
    lines.append("| stage | " + " | ".join("n=%d" % n for n in ns) + " | k | local k |")
    lines.append("|---|" + "---|" * (len(ns) + 2))
    for name in names:
        values = [r["seconds"][name] for r in rows]
        f = fit(ns, values)
        cells = " | ".join("%.3f" % v for v in values)
        lines.append("| %s | %s | %s | %s |" % (
            name, cells, "%.2f ± %.2f" % (f["exponent"], f["stderr"]) if f else "—",
            "[%.2f, %.2f]" % (f["local_min"], f["local_max"]) if f else "—"))
    lines += ["", "| n | tiles | curves | vertices | quadratic tiles | peak RSS MB |", "|---|---|---|---|---|---|"]
    for r in rows:
        c = r["counts"]
        lines.append("| %d | %d | %d | %d | %d | %.0f |" % (r["teeth"], c["tiles"], c["curves"], c["vertices"],
                                                          c["quadratic_charts"], r["max_rss_mb"]))
    with open(os.path.join(outdir, "growth.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    if series:
        write_svg(os.path.join(outdir, "growth.svg"), ns, series)
    print("\n".join(lines))


def write_svg(path, ns, series):
    width, height, left, right, top, bottom = 760, 520, 70, 190, 30, 50
    values = [v for vs, _ in series.values() for v in vs if v > 0]
    lo_y, hi_y = math.floor(math.log10(min(values))), math.ceil(math.log10(max(values)))
    lo_x, hi_x = math.log10(min(ns) / 1.15), math.log10(max(ns) * 1.15)

    def X(n):
        return left + (math.log10(n) - lo_x) / (hi_x - lo_x) * (width - left - right)

    def Y(v):
        return top + (hi_y - math.log10(v)) / (hi_y - lo_y) * (height - top - bottom)

    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
               "#17becf", "#000000", "#aa3377", "#66aa00"]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">'
           % (width, height), '<rect width="100%" height="100%" fill="white"/>']
    for d in range(lo_y, hi_y + 1):
        out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="#ddd"/>' % (left, width - right, Y(10 ** d), Y(10 ** d)))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%s</text>' % (left - 5, Y(10 ** d) + 4,
                                                                         "%g M" % (10 ** d / 1e6)))
    for n in ns:
        out.append('<line x1="%.1f" x2="%.1f" y1="%d" y2="%d" stroke="#eee"/>' % (X(n), X(n), top, height - bottom))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%d</text>' % (X(n), height - bottom + 15, n))
    out.append('<text x="%d" y="%d" text-anchor="middle">teeth n (n x n, log scale)</text>' %
               ((left + width - right) / 2, height - 12))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">instructions (callgrind, log '
               'scale)</text>' % ((top + height - bottom) / 2, (top + height - bottom) / 2))
    for i, (name, (vs, f)) in enumerate(series.items()):
        colour = colours[i % len(colours)]
        pts = [(X(n), Y(v)) for n, v in zip(ns, vs) if v > 0]
        for x, y in pts:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (x, y, colour))
        if f:
            a, b = ns[0], ns[-1]
            ya, yb = math.exp(f["log_c"] + f["exponent"] * math.log(a)), math.exp(f["log_c"] + f["exponent"] * math.log(b))
            out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="%s" stroke-width="1.5"/>' %
                       (X(a), Y(ya), X(b), Y(yb), colour))
        label = name[3:] + (" n^%.2f" % f["exponent"] if f else "")
        out.append('<text x="%d" y="%d" fill="%s">%s</text>' % (width - right + 10, top + 14 * i + 10, colour, label))
    # the goal's slope n^1.1 through the process's first point
    vs, _ = series["Ir process"]
    a, b = ns[0], ns[-1]
    out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="black" stroke-dasharray="6 4"/>' %
               (X(a), Y(vs[0]), X(b), Y(vs[0] * (b / a) ** 1.1)))
    out.append('<text x="%d" y="%d">--- n^1.1 (goal slope)</text>' % (width - right + 10, top + 14 * len(series) + 14))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binary", nargs="?")
    parser.add_argument("outdir")
    parser.add_argument("--teeth", default="10,14,20,28,40,56,80")
    parser.add_argument("--callgrind", action="store_true")
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--fit-from", type=int, default=0)
    parser.add_argument("--report", action="store_true")
    args = parser.parse_args()
    if args.report:
        report(args.binary or args.outdir, args.fit_from)   # (--report OUTDIR: the one positional)
        return 0
    if not args.binary:
        parser.error("HIPAIR binary needed")
    os.makedirs(os.path.join(args.outdir, "json"), exist_ok=True)
    runs = []
    for n in [int(t) for t in args.teeth.split(",")]:
        timed = []
        for _ in range(args.runs):
            scratch = os.path.join(args.outdir, "stats-%d.json" % n)
            out, code, cpu, rss = run_timed(hipair_command(args.binary, n, scratch, True))
            if code != 0:
                print("hipair failed for n = %d (exit %d)" % (n, code), file=sys.stderr)
                return 1
            os.remove(scratch)
            clocks, counts = parse_stats(out)
            clocks["process CPU"] = cpu
            clocks["rest (CPU - total)"] = max(cpu - clocks["total"], 0.0)
            timed.append((clocks, counts, rss))
        seconds = {k: sorted(t[0][k] for t in timed)[len(timed) // 2] for k in timed[0][0]}
        row = {"teeth": n, "seconds": seconds, "counts": timed[0][1], "max_rss_mb": max(t[2] for t in timed)}
        json_path = os.path.join(args.outdir, "json", "gears-%d.json" % n)
        if args.callgrind:
            cg = os.path.join(args.outdir, "callgrind.%d.out" % n)
            subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg] +
                           hipair_command(args.binary, n, json_path, False),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            row["instructions"] = stage_instructions(inclusive_costs(cg))
        else:
            subprocess.run(hipair_command(args.binary, n, json_path, False), stdout=subprocess.DEVNULL, check=True)
        runs.append(row)
        print("n = %d: %.2f s CPU%s" % (n, seconds["process CPU"], ", %.0f M instructions" %
                                         (row["instructions"]["process"] / 1e6) if "instructions" in row else ""),
              file=sys.stderr, flush=True)
        with open(os.path.join(args.outdir, "growth.json"), "w") as f:
            json.dump({"binary": args.binary, "runs": runs, "time": time.strftime("%Y-%m-%d %H:%M:%S")}, f, indent=1)
    report(args.outdir, args.fit_from)
    return 0


if __name__ == "__main__":
    sys.exit(main())
