#!/usr/bin/env python3
"""The driver's travel planned exactly at any magnitude, through the CLI (session 56, kin56).

usage: driver_plan_cli.py HIPAIR SOURCE_DIR WORK [SEED]

1. A translating driver (the cam follower's follower, --driver follower) over random ranges
   (ends inside, on and beyond its limits [-12, 12] mm) of the model scaled exactly by 10^400
   and 10^-300 (tests/fuzz/scale_model.py) against the same ranges of the unscaled model: the
   same exit code and report text once the lengths' exponent is taken out
   (scaled_outputs.unit_free_text); until session 56 the plan's doubles overflowed or underflowed
   past the CLI's rescaling for a library caller, and a range whose length rounded to 0 in
   double precision was refused.
2. The cam follower with its cam's limits near 10^17 deg ([1e17, 1e17 + 200] deg, initial angle
   1e17 + 10 deg): within 60 s (until session 56: more than 300 s, its driver's motion lost in
   doubles of 0.25 rad), one drive piece on the same contact as the cam at [280, 480] deg, and
   the driver completes its range.
Exit 0 when all agree, 1 otherwise (the differences printed).
"""
import os
import random
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scaled_outputs import run, unit_free_text  # noqa: E402


def main(argv):
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    hipair, source, work = argv[1:4]
    rng = random.Random(int(argv[4]) if len(argv) > 4 else 5656)
    os.makedirs(work, exist_ok=True)
    model = os.path.join(source, "examples", "models", "cam-follower.json")
    failures = []

    # 1. translating driver at 10^400 and 10^-300
    for k in (400, -300):
        scaled = os.path.join(work, "cam-follower-x1e%d.json" % k)
        subprocess.run([sys.executable, os.path.join(source, "tests", "fuzz", "scale_model.py"), model, "1e%d" % k, scaled],
                       check=True)
        ends = ["-12", "12", "0", "-13.25", "12.5"] + ["%d.%03d" % (rng.randint(-14, 13), rng.randint(0, 999)) for _ in range(4)]
        for _ in range(3):
            a, b = rng.sample(ends, 2)
            common = ["analyze", "--driver", "follower", "--quiet", "--no-pictures", "--steps", "64", "--no-reversal"]
            code1, out1, err1 = run(hipair, common + [model, "--range", "%s:%s" % (a, b)], work, 120)
            code2, out2, err2 = run(hipair, common + [scaled, "--range", "%se%d:%se%d" % (a, k, b, k)], work, 120)
            where = "x1e%d --range %s:%s" % (k, a, b)
            if code1 is None or code2 is None:
                failures.append("%s: timed out" % where)
                continue
            if code1 != code2:
                failures.append("%s: exit %s at x1, %s scaled: %s / %s" % (where, code1, code2, err1[:300], err2[:300]))
                continue
            texts = [unit_free_text(t, k, "cam-follower") for t in (out1 + err1, out2 + err2)]
            # the run's time and the scaled file's path set aside
            texts = [re.sub(r"cam-follower(-x1e-?\d+)?\.json", "MODEL", t) for t in texts]
            texts = [re.sub(r"\d+(\.\d+)? s\b", "T s", t) for t in texts]
            if texts[0] != texts[1]:
                import difflib
                diff = "\n".join(list(difflib.unified_diff(texts[0].splitlines(), texts[1].splitlines(), lineterm=""))[:20])
                failures.append("%s: the reports differ:\n%s" % (where, diff))

    # 2. the cam's limits near 10^17 deg
    text = open(model, encoding="utf-8").read()
    plain = '"motion": { "rotation": { "pivot": [0, 0] } },\n      "initial": { "angle": 0 }'
    if plain not in text:
        failures.append("cam-follower.json: the cam's motion is not as this test expects")
    else:
        reports = []
        for lo, hi, initial in (("280", "480", "290"), ("1e17", "1e17 + 200", "1e17 + 10")):
            path = os.path.join(work, "cam-limits-%s.json" % lo)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text.replace(plain, '"motion": { "rotation": { "pivot": [0, 0], "limits": ["%s", "%s"] } },\n'
                                            '      "initial": { "angle": "%s" }' % (lo, hi, initial)))
            code, out, err = run(hipair, ["analyze", path, "--quiet", "--no-pictures"], work, 60)
            if code != 0:
                failures.append("cam limits [%s, %s] deg: exit %s: %s" % (lo, hi, code, err[:300] or "timeout"))
                continue
            pieces = re.findall(r"^  (drive|dwell) .*?(held .*|free.*)$", out, re.M)
            blocking = re.findall(r"^Blocking: .*$", out, re.M)
            reports.append((pieces, blocking))
        if len(reports) == 2 and reports[0] != reports[1]:
            failures.append("cam limits near 1e17 deg: %s, at [280, 480] deg: %s" % (reports[1], reports[0]))
        if len(reports) == 2 and not reports[0][0]:
            failures.append("cam limits [280, 480] deg: no piece found in the report")

    for failure in failures:
        print("FAIL " + failure)
    print("driver_plan_cli: %d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
