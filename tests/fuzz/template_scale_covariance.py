#!/usr/bin/env python3
"""Models built from feature templates and expressions with pi, scaled exactly by factors from
1e-300 to 1e400 (tests/fuzz/scale_model.py), must read and give the C-space of the model at
1 mm (docs/model-format.md "Exactness and rounding"):

- `hipair validate` succeeds at every scale (before session 19: the escapement, the spur gears
  and the Geneva template were refused at 1e-300 or 1e400 with false geometric reasons, "the
  locking arcs cut into the slot walls", "the tip circle lies inside the base circle", because
  their roundings and constructions were absolute: 1e-12 mm rounds a 1e-300 mm length to 0,
  and 1e400 is infinite in double);
- every pair's C-space has the same cells (kinds, wrapping, neighbour kinds), the same number
  of contact edges and the same multiset of contact feature-pair labels as at 1 mm (rotating
  pairs' C-spaces do not depend on the unit; the roundings' own choices may differ by their
  bounds, which moves no contact across a cell: a stricter comparison would need the
  roundings to be identical);
- between two scales below 2^-20 mm (1e-300 and 1e-30) the C-spaces are identical as exact
  objects (tests/perf/compare_cspace_json.py: chains, polynomials, vertices): every rounding is
  then relative to the value (expressions, in units of a power of ten) or to the template's
  largest length, so the geometry is exactly proportional.

usage: template_scale_covariance.py HIPAIR SOURCE_DIR WORK_DIR
exit 0 when every check holds, 1 otherwise.
"""
import collections
import json
import os
import subprocess
import sys

# (model, extra cspace options): the spur gears as a 6 x 6 pair (one chart pair takes 1 s).
MODELS = [
    ("escapement", []),
    ("geneva-template", []),
    ("ratchet", []),
    ("geneva", []),
    ("spur-gears", ["--region", "operating", "--set", "teeth-1=6", "--set", "teeth-2=6",
                    "--allow-out-of-tolerance"]),
]
SCALES = ["1e-300", "1e-30", "1e30", "1e400"]
EXACT_PAIR = ("1e-300", "1e-30")


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=600)
    return result.returncode, result.stdout, result.stderr


def pair_files(out_json):
    """The per-pair JSON files of one `cspace --json OUT` run (OUT itself for one pair)."""
    if os.path.exists(out_json):
        return {"": out_json}
    stem = out_json[: -len(".json")]
    directory = os.path.dirname(out_json)
    files = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if path.startswith(stem + "-") and name.endswith(".json"):
            files[path[len(stem) + 1: -len(".json")]] = path
    return files


def structure(path):
    data = json.load(open(path))
    cells = data["cells"]
    kinds = [c["kind"] for c in cells]
    cell_keys = sorted(
        (c["kind"], c.get("wraps_x"), c.get("wraps_y"), tuple(sorted(kinds[n] for n in c.get("neighbours", []))))
        for c in cells)
    labels = collections.Counter()
    contact = 0
    for edge in data.get("edges", []):
        if edge["role"] != "contact":
            continue
        contact += 1
        labels[tuple(sorted(data["feature_pairs"][i]["label"] for i in edge["feature_pairs"]))] += 1
    if data.get("dimension") == 1:
        contact = len(data.get("vertices", []))
    return {"cells": cell_keys, "contact edges": contact, "contact labels": labels}


def main():
    hipair, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(work, exist_ok=True)
    failures = 0

    def fail(message):
        nonlocal failures
        failures += 1
        print("FAIL " + message)

    for name, options in MODELS:
        model = os.path.join(source, "examples", "models", name + ".json")
        outputs = {}
        for scale in ["1"] + SCALES:
            if scale == "1":
                scaled = model
            else:
                scaled = os.path.join(work, "%s@%s.json" % (name, scale))
                subprocess.run([sys.executable, os.path.join(source, "tests", "fuzz", "scale_model.py"), model, scale,
                                scaled], check=True, capture_output=True)
                rc, _, err = run([hipair, "validate", scaled])
                if rc != 0:
                    fail("validate %s@%s: %s" % (name, scale, err.strip()[:300]))
                    continue
            directory = os.path.join(work, "%s@%s" % (name, scale))
            os.makedirs(directory, exist_ok=True)
            out = os.path.join(directory, "cspace.json")
            rc, _, err = run([hipair, "cspace", scaled, "--json", out] + options)
            if rc != 0:
                fail("cspace %s@%s: %s" % (name, scale, err.strip()[:300]))
                continue
            outputs[scale] = pair_files(out)
        if "1" not in outputs:
            continue
        reference = {pair: structure(path) for pair, path in outputs["1"].items()}
        for scale in SCALES:
            if scale not in outputs:
                continue
            if sorted(outputs[scale]) != sorted(reference):
                fail("%s@%s: pairs %s, at 1 mm %s" % (name, scale, sorted(outputs[scale]), sorted(reference)))
                continue
            for pair, path in outputs[scale].items():
                got = structure(path)
                for key in reference[pair]:
                    if got[key] != reference[pair][key]:
                        fail("%s@%s pair %s: %s differ from 1 mm" % (name, scale, pair or "(one)", key))
            print("ok %s@%s: %d pair(s) as at 1 mm" % (name, scale, len(reference)))
        a, b = EXACT_PAIR
        if a in outputs and b in outputs:
            for pair in outputs[a]:
                rc, out, _ = run([sys.executable, os.path.join(source, "tests", "perf", "compare_cspace_json.py"),
                                  outputs[a][pair], outputs[b][pair]])
                if rc != 0:
                    fail("%s pair %s: %s and %s not identical C-spaces: %s" % (name, pair or "(one)", a, b,
                                                                                out.strip()[:300]))
            print("ok %s: %s and %s identical" % (name, a, b))
    print("template_scale_covariance: %d failure(s)" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
