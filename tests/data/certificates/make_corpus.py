#!/usr/bin/env python3
"""Writes the mutation corpus of HIPAIR certificates (see README.md in this folder).

usage: make_corpus.py [--dir DIR] [--source SOURCE_DIR]

The valid base certificates in DIR (default: this folder) are produced with `hipair certify`
(make_bases.sh). Each mutation changes one thing and names the reason the verifier must give (a
substring of its message). DIR/EXPECTED.txt lists: certificate, model (relative to the
repository, or absolute), expected reason ("valid" for the base certificates; "unproven" for the
no_jam tolerance bases, which hipair-verify answers with exit 3).
"""
import argparse
import copy
from fractions import Fraction
import json
import os

parser = argparse.ArgumentParser()
parser.add_argument("--dir", default=os.path.dirname(os.path.abspath(__file__)))
parser.add_argument("--source", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../.."))
arguments = parser.parse_args()
HERE = os.path.abspath(arguments.dir)
SOURCE = os.path.abspath(arguments.source)
MODELS = "examples/models/"


def load(name):
    with open(os.path.join(HERE, name)) as f:
        return json.load(f)


def save(name, certificate):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(certificate, f, indent=1)
        f.write("\n")


expected = []
bases = [
    ("lever-interference.json", "lever-stop.json"),
    ("lever-clearance.json", "lever-stop.json"),
    ("lever-free.json", "lever-stop.json"),
    ("lever-jam.json", "lever-stop.json"),
    ("ratchet-jam.json", "ratchet.json"),
    ("geneva-interference.json", "geneva.json"),
    ("follower-guide-free.json", "cam-follower.json"),
    ("peg-planar-clearance.json", "peg-in-hole.json"),
    ("peg-planar-interference.json", "peg-in-hole.json"),
    ("film-cam-clearance.json", "film-advance.json"),
    ("film-pin-clearance.json", "film-advance.json"),
    ("film-claw-interference.json", "film-advance.json"),
    ("geneva-tolerance-no-jam.json", "geneva.json"),
    ("geneva-tolerance-no-interference.json", "geneva.json"),
    ("geneva-tolerance-no-jam-0.9-threshold.json", "geneva.json"),
    ("geneva-tolerance-no-jam-4x-free-path.json", "geneva.json"),
    ("spur-clearance.json", "spur-gears.json"),
    ("spur-interference.json", "spur-gears.json"),
    ("spur-free.json", "spur-gears.json"),
]
# The no_jam bases whose free follower path check 7 proves (docs/certify.md "Tolerance"): the
# 2 x certificate and the 4 x one produced with --certify-free-path. The 0.9 x one passes checks
# 1-6, but its witness path meets the pin near the lock/drive switch (session 17): "unproven"
# (hipair-verify exit 3).
PROVED_NO_JAM = {"geneva-tolerance-no-jam.json", "geneva-tolerance-no-jam-4x-free-path.json"}


def base_verdict(name):
    """A no_jam tolerance certificate whose evidence passes checks 1-6 is "valid" when check 7
    proves a free follower path across its range, else "unproven" (hipair-verify exit 3)."""
    c = load(name)
    if c.get("claim") == "tolerance" and c.get("tolerance", {}).get("property") == "no_jam":
        return "valid" if name in PROVED_NO_JAM else "unproven"
    return "valid"


for name, model in bases:
    expected.append((name, MODELS + model, base_verdict(name), name))


def mutate(base, model, name, reason, change, model_path=None):
    certificate = copy.deepcopy(load(base))
    change(certificate)
    save(name, certificate)
    expected.append((name, model_path or MODELS + model, reason, base))


def set_path(keys, value):
    def change(c):
        target = c
        for key in keys[:-1]:
            target = target[key]
        target[keys[-1]] = value
    return change


# Perturbed witnesses.
mutate("lever-interference.json", "lever-stop.json", "m01-point-outside.json",
       "is not strictly inside part 'lever' (it lies outside)", set_path(["interference", "point"], ["1000", "1000"]))
mutate("lever-interference.json", "lever-stop.json", "m02-point-on-boundary.json",
       "is not strictly inside part 'stop' (it lies on its boundary)", set_path(["interference", "point"], ["20", "10"]))
mutate("geneva-interference.json", "geneva.json", "m03-point-moved.json", "is not strictly inside part",
       set_path(["interference", "point"], ["-100", "-100"]))
mutate("lever-interference.json", "lever-stop.json", "m04-tangent-off-angle.json", "is not within",
       set_path(["interference", "configuration", "lever", "tangent"], "27/100"))
mutate("lever-interference.json", "lever-stop.json", "m05-missing-position.json",
       "gives no position for moving part 'lever'", set_path(["interference", "configuration"], {}))
mutate("lever-clearance.json", "lever-stop.json", "m06-clearance-too-large.json", "less than the claimed",
       set_path(["clearance", "distance"], "21/10"))

# The model edited after certification, or the certificate naming another model.
mutate("lever-clearance.json", "lever-stop.json", "m07-hash-changed.json", "model hash mismatch",
       set_path(["model", "content_hash"], "0" * 64))
with open(os.path.join(SOURCE, "examples/models/lever-stop.json")) as f:
    edited = f.read().replace('"stop-gap":     { "nominal": 2,', '"stop-gap":     { "nominal": 2.5,')
assert '"nominal": 2.5' in edited
with open(os.path.join(HERE, "lever-stop-edited.json"), "w") as f:
    f.write(edited)
mutate("lever-clearance.json", "lever-stop.json", "m08-model-edited.json", "model hash mismatch", lambda c: None,
       model_path=os.path.relpath(os.path.join(HERE, "lever-stop-edited.json"), SOURCE)
       if HERE.startswith(SOURCE) else os.path.join(HERE, "lever-stop-edited.json"))

# Parameters and roundings.
mutate("lever-clearance.json", "lever-stop.json", "m09-parameter-outside-tolerance.json",
       "parameter outside its tolerance", set_path(["model", "parameters", "lever-length"], {"value": "61", "overridden": True}))
mutate("lever-clearance.json", "lever-stop.json", "m10-parameter-not-nominal.json", "is not the model's nominal",
       set_path(["model", "parameters", "lever-length"], {"value": "6001/100", "overridden": False}))
mutate("lever-clearance.json", "lever-stop.json", "m11-parameter-missing.json", "gives no value for parameter 'stop-gap'",
       lambda c: c["model"]["parameters"].pop("stop-gap"))
mutate("lever-clearance.json", "lever-stop.json", "m12-rounding-changed.json", "rounding 0 differs",
       lambda c: c["model"]["roundings"][0].__setitem__("value", "-1/2"))

# Interval covers with gaps, and claims beyond what the boxes show.
mutate("lever-free.json", "lever-stop.json", "m13-free-box-removed.json", "gap in the boxes' cover",
       lambda c: c["free_passage"]["boxes"].pop(2))
mutate("lever-free.json", "lever-stop.json", "m14-free-range-extended.json", "at its end",
       set_path(["free_passage", "range"], ["-1/2", "3/100"]))
mutate("lever-free.json", "lever-stop.json", "m15-free-distance-too-large.json",
       "less than the claimed clearance plus the motion", set_path(["free_passage", "distance"], "3"))
mutate("follower-guide-free.json", "cam-follower.json", "m16-free-beyond-limits.json", "outside the driver's limits",
       lambda c: (c["free_passage"].__setitem__("range", ["-2", "20"]),
                  c["free_passage"]["boxes"].append({"driver": ["3", "20"]})))
mutate("ratchet-jam.json", "ratchet.json", "m17-jam-cut-gap.json", "gap in the cover of the cut",
       lambda c: c["jam"]["cut"][0]["range"].__setitem__(1, "0"))
mutate("ratchet-jam.json", "ratchet.json", "m18-jam-wall-gap.json", "gap in the cover of the lower wall",
       lambda c: c["jam"]["lower_wall"].pop(1))
mutate("ratchet-jam.json", "ratchet.json", "m19-jam-trap-widened.json", "gap in the cover of the cut",
       lambda c: c["jam"]["trap"].__setitem__("follower", ["-7/500", "1/100"]))

# Claimed feature pairs that do not block.
mutate("lever-jam.json", "lever-stop.json", "m20-jam-pair-not-blocking.json", "does not block",
       set_path(["jam", "cut", 0, "crossing", "across"], {"part": "stop", "loop": 0, "edge": 2, "label": ""}))
mutate("lever-jam.json", "lever-stop.json", "m21-jam-piece-moved.json", "does not block",
       set_path(["jam", "cut", 0, "crossing", "along"], ["1/2", "6/10"]))
mutate("lever-jam.json", "lever-stop.json", "m22-jam-before-contact.json", "does not block",
       set_path(["jam", "trap", "driver"], ["0", "1/100"]))
mutate("ratchet-jam.json", "ratchet.json", "m23-jam-wall-pair-elsewhere.json", "does not block",
       set_path(["jam", "lower_wall", 0, "crossing", "across"], {"part": "pawl", "loop": 0, "edge": 3, "label": "hub end"}))
mutate("lever-jam.json", "lever-stop.json", "m24-jam-beyond-limits.json", "outside the driver's limits",
       set_path(["jam", "trap", "driver"], ["3", "31/10"]))

# References and syntax.
mutate("lever-jam.json", "lever-stop.json", "m25-label-mismatch.json", "is labelled 'upper side' in the model",
       set_path(["jam", "cut", 0, "crossing", "edge", "label"], "lower side"))
mutate("lever-jam.json", "lever-stop.json", "m26-edge-out-of-range.json", "has no loop 0 edge 9",
       set_path(["jam", "cut", 0, "crossing", "edge", "edge"], 9))
mutate("lever-clearance.json", "lever-stop.json", "m27-unknown-key.json", "malformed certificate: /clearance/note: unknown key 'note'",
       set_path(["clearance", "note"], "x"))
mutate("lever-clearance.json", "lever-stop.json", "m28-unknown-part.json", "the model has no part 'leverr'",
       set_path(["pair"], ["leverr", "stop"]))
mutate("lever-clearance.json", "lever-stop.json", "m29-not-a-rational.json", "not an exact rational",
       set_path(["clearance", "distance"], "two"))

# Session 36 (hunt36): the statement must be the claim's; model.file a bare file name; a jam
# trap's follower range must meet the follower's limits (the pawl's are [-20, 10] degrees).
mutate("lever-clearance.json", "lever-stop.json", "m30-statement-changed.json",
       "the statement does not say what the claim's data prove",
       set_path(["statement"], "Parts 'lever' and 'stop' are at least 3 mm apart with lever at 0 rad."))
mutate("lever-clearance.json", "lever-stop.json", "m31-model-file-a-path.json", "model.file must be a bare file name",
       set_path(["model", "file"], "../examples/models/lever-stop.json"))
mutate("ratchet-jam.json", "ratchet.json", "m32-jam-trap-follower-outside-limits.json",
       "lies outside the follower's limits", set_path(["jam", "trap", "follower"], ["1", "11/10"]))

# Session 42 (hunt42): what the statement prints must be what the data prove. A jam needs a free
# start in its trap (else "cannot pass" is said of a motion that cannot start); an angle label is
# a label only within 10^-12 rad (the statement prints it, not the tangent); a configuration may
# give positions only to the claim's parts (the statement prints every one). Each statement is the
# one of the mutated data, so only the new checks can reject them (main 9b844dd accepts m36-m38).
mutate("ratchet-jam.json", "ratchet.json", "m33-jam-start-dropped.json", "/jam: missing key 'start'",
       lambda c: c["jam"].pop("start"))
mutate("ratchet-jam.json", "ratchet.json", "m34-jam-start-outside-trap.json", "is not in the trap's driver range",
       lambda c: c["jam"]["start"].__setitem__("driver", str(Fraction(c["jam"]["trap"]["driver"][1]) + 1)))
mutate("ratchet-jam.json", "ratchet.json", "m35-jam-start-on-a-wall.json", "not certainly apart at the trap's start",
       lambda c: c["jam"]["start"].__setitem__("follower", c["jam"]["trap"]["follower"][0]))
mutate("lever-interference.json", "lever-stop.json", "m36-angle-label-a-radian-off.json", "the angle error of 'lever'",
       lambda c: (c["interference"]["configuration"]["lever"].update({"angle": "0", "angle_error": "1"}),
                  c.__setitem__("statement", "Parts 'lever' and 'stop' overlap with lever at 0 rad.")))
mutate("lever-clearance.json", "lever-stop.json", "m37-angle-label-half-a-radian-off.json", "the angle error of 'lever'",
       lambda c: (c["clearance"]["configuration"]["lever"].update({"angle": "1/2", "angle_error": "1"}),
                  c.__setitem__("statement", "Parts 'lever' and 'stop' are at least 2 mm apart with lever at 0.5 rad.")))
mutate("lever-clearance.json", "lever-stop.json", "m38-configuration-ghost-part.json",
       "the configuration gives a position for 'ghost'",
       lambda c: (c["clearance"]["configuration"].__setitem__("ghost", {"offset": "5"}),
                  c.__setitem__("statement", "Parts 'lever' and 'stop' are at least 2 mm apart with ghost at 5 mm, lever at 0 rad.")))

# Planar claims (a part free in the plane at an exact pose).
mutate("peg-planar-clearance.json", "peg-in-hole.json", "p01-planar-pose-moved.json", "less than the claimed",
       set_path(["planar_clearance", "pose", "x"], "3/2"))
mutate("peg-planar-clearance.json", "peg-in-hole.json", "p02-planar-clearance-too-large.json", "less than the claimed",
       set_path(["planar_clearance", "distance"], "11/10"))
mutate("peg-planar-interference.json", "peg-in-hole.json", "p03-planar-point-outside.json",
       "is not strictly inside part 'peg' (it lies outside)", set_path(["planar_interference", "point"], ["-8", "-8"]))
mutate("peg-planar-interference.json", "peg-in-hole.json", "p04-planar-pose-centred.json", "is not strictly inside part",
       set_path(["planar_interference", "pose", "x"], "0"))
mutate("peg-planar-interference.json", "peg-in-hole.json", "p05-planar-part-not-planar.json",
       "is not free in the plane", set_path(["planar_interference", "pose", "part"], "plate"))
mutate("peg-planar-clearance.json", "peg-in-hole.json", "p06-planar-pose-incomplete.json", "missing key 'y'",
       lambda c: c["planar_clearance"]["pose"].pop("y"))

# Pin-in-slot claims (the film advance's follower at an exact slide and angle, the other part
# fixed, turned or shifted to its position in the configuration).
mutate("film-pin-clearance.json", "film-advance.json", "s01-pin-slot-angle-beyond-limits.json",
       "the angle of 'follower' (2 atan(701/10000) rad) is not certainly within its limits",
       set_path(["planar_clearance", "pose", "tangent"], "701/10000"))
mutate("film-pin-clearance.json", "film-advance.json", "s02-pin-slot-slide-beyond-limits.json",
       "the slide of 'follower' (61/10) is outside its limits", set_path(["planar_clearance", "pose", "slide"], "61/10"))
mutate("film-cam-clearance.json", "film-advance.json", "s03-pin-slot-clearance-too-large.json", "less than the claimed",
       set_path(["planar_clearance", "distance"], "1/4"))
mutate("film-cam-clearance.json", "film-advance.json", "s04-pin-slot-cam-tangent-off-angle.json", "is not within",
       lambda c: c["planar_clearance"]["configuration"]["cam"].__setitem__("tangent", "0"))
mutate("film-claw-interference.json", "film-advance.json", "s05-pin-slot-film-position-dropped.json",
       "gives no position for moving part 'film'", set_path(["planar_interference", "configuration"], {}))
mutate("film-claw-interference.json", "film-advance.json", "s06-pin-slot-film-moved.json", "is not strictly inside part 'film'",
       set_path(["planar_interference", "configuration", "film", "offset"], "2"))
mutate("film-claw-interference.json", "film-advance.json", "s07-pin-slot-claw-swung-out.json", "is not strictly inside part 'follower'",
       set_path(["planar_interference", "pose", "tangent"], "-1/20"))
mutate("film-cam-clearance.json", "film-advance.json", "s08-pin-slot-pose-on-the-cam.json", "has no pin_slot motion",
       set_path(["planar_clearance", "pose", "part"], "cam"))
# Tolerance certificates (`hipair tolerance --certify` / `--certify-interference`): the parameter
# box times the driver range (times the follower range) must be covered by leaves that each hold.
def fraction(text):
    from fractions import Fraction
    return Fraction(text)


def rational(value):
    return f"{value.numerator}/{value.denominator}" if value.denominator != 1 else str(value.numerator)


def halve_driver(leaf):
    def change(c):
        d = c["tolerance"]["leaves"][leaf]["driver"]
        d[1] = rational((fraction(d[0]) + fraction(d[1])) / 2)
    return change


def nearest_double_box_end(c):
    # A box end replaced by its nearest double (half an ulp away from the exact tolerance).
    end = fraction(c["tolerance"]["box"][0][1])
    from fractions import Fraction
    moved = Fraction(float(end))
    assert moved != end
    c["tolerance"]["box"][0][1] = rational(moved)


def witness_onto_lower_side(c):
    for leaf in c["tolerance"]["leaves"]:
        if "witness" in leaf:
            centre = leaf["lower"]["centre"]
            leaf["witness"]["value"] = rational((fraction(centre[0]) + fraction(centre[1])) / 2)
            return
    raise AssertionError("no leaf with a witness")


def witness_slopes_reversed(c):
    for leaf in c["tolerance"]["leaves"]:
        if "witness" in leaf:
            leaf["witness"]["slopes"] = [rational(-3 * fraction(a) - 1) for a in leaf["witness"]["slopes"]]
            return
    raise AssertionError("no leaf with a witness")


def upper_bracket_moved(c):
    side = c["tolerance"]["leaves"][0]["upper"]
    lo, hi = fraction(side["bracket"][0]), fraction(side["bracket"][1])
    shift = 2 * (hi - lo)
    side["bracket"] = [rational(lo + shift), rational(hi + shift)]
    width = fraction(side["centre"][1]) - fraction(side["centre"][0])
    side["centre"] = [rational(lo + shift), rational(lo + shift + width)]


def lower_centre_moved(c):
    side = c["tolerance"]["leaves"][0]["lower"]
    width = fraction(side["centre"][1]) - fraction(side["centre"][0])
    lo = fraction(side["bracket"][0])
    side["centre"] = [side["bracket"][0], rational(lo + width)]


def extend_range(c):
    r = c["tolerance"]["range"]
    r[1] = rational(fraction(r[1]) + fraction("1/100"))


def follower_moved(value):
    def change(c):
        c["tolerance"]["follower_range"] = [value, value]
        for leaf in c["tolerance"]["leaves"]:
            leaf["follower"] = [value, value]
    return change


NOJAM, NOINT = "geneva-tolerance-no-jam.json", "geneva-tolerance-no-interference.json"
mutate(NOJAM, "geneva.json", "t01-nojam-leaf-driver-halved.json", "coverage gap", halve_driver(0))
mutate(NOJAM, "geneva.json", "t02-nojam-range-extended.json", "coverage gap", extend_range)
mutate(NOJAM, "geneva.json", "t03-nojam-tree-node-dropped.json", "ends early", lambda c: c["tolerance"]["tree"].pop())
mutate(NOJAM, "geneva.json", "t04-nojam-box-widened.json", "wrong parameter box",
       lambda c: c["tolerance"]["box"][3].__setitem__(1, rational(2 * fraction(c["tolerance"]["box"][3][1]))))
mutate(NOJAM, "geneva.json", "t05-nojam-scale-raised.json", "wrong parameter box", set_path(["tolerance", "scale"], "3"))
mutate(NOJAM, "geneva.json", "t06-nojam-box-end-nearest-double.json", "wrong parameter box", nearest_double_box_end)
mutate(NOJAM, "geneva.json", "t07-nojam-varied-twice.json", "varied twice",
       lambda c: c["tolerance"]["varied"].__setitem__(0, c["tolerance"]["varied"][1]))
mutate(NOJAM, "geneva.json", "t08-nojam-side-label.json", "labelled",
       lambda c: c["tolerance"]["sides"][0]["follower"].__setitem__("label", c["tolerance"]["sides"][0]["follower"]["label"] + "x"))
mutate(NOJAM, "geneva.json", "t09-nojam-witness-on-lower-side.json", "witness", witness_onto_lower_side)
mutate(NOJAM, "geneva.json", "t10-nojam-witness-slopes.json", "witness", witness_slopes_reversed)
mutate(NOJAM, "geneva.json", "t11-nojam-upper-bracket-moved.json", "leaf 0", upper_bracket_moved)
mutate(NOJAM, "geneva.json", "t12-nojam-lower-centre-moved.json", "at the leaf's centre", lower_centre_moved)
mutate(NOINT, "geneva.json", "t13-nointerference-leaf-driver-halved.json", "coverage gap", halve_driver(0))
mutate(NOINT, "geneva.json", "t14-nointerference-follower-widened.json", "coverage gap",
       set_path(["tolerance", "follower_range"], ["-1/1000", "1/1000"]))
mutate(NOINT, "geneva.json", "t15-nointerference-leaf-follower-dropped.json", "missing key 'lower'",
       lambda c: c["tolerance"]["leaves"][0].pop("follower"))
mutate(NOINT, "geneva.json", "t16-nointerference-scale-raised.json", "wrong parameter box",
       set_path(["tolerance", "scale"], "2"))
mutate(NOINT, "geneva.json", "t17-nointerference-wheel-turned-into-the-lock.json", "may interfere",
       follower_moved("3/10"))
mutate(NOINT, "geneva.json", "t18-nointerference-box-end-nearest-double.json", "wrong parameter box",
       nearest_double_box_end)

# The second-order witness test (0.9 x the jamming threshold): the leaves' margins are claims the
# verifier re-derives from its own Taylor enclosures.
SECOND = "geneva-tolerance-no-jam-0.9-threshold.json"


def second_order_leaf(c):
    for index, leaf in enumerate(c["tolerance"]["leaves"]):
        if "second_order_margins" in leaf.get("witness", {}):
            return index, leaf
    raise AssertionError("no second-order leaf")


def margin_raised(c):
    _, leaf = second_order_leaf(c)
    leaf["witness"]["second_order_margins"][0] = rational(100 * fraction(leaf["witness"]["second_order_margins"][0]))


def margin_zero(c):
    _, leaf = second_order_leaf(c)
    leaf["witness"]["second_order_margins"][1] = "0"


def margins_dropped(c):
    # Without its margins the leaf falls back to the first-order forms, which do not hold there.
    _, leaf = second_order_leaf(c)
    del leaf["witness"]["second_order_margins"]


def driver_slope_flipped(c):
    # The witness path's derivative in the driver angle with its sign flipped (scaled up, so the
    # path leaves the channel within the leaf).
    _, leaf = second_order_leaf(c)
    slopes = leaf["witness"]["slopes"]
    slopes[-1] = rational(-fraction(slopes[-1]) - 1)


def leaf_driver_widened(c):
    # A leaf's driver interval widened to the whole range: the box is still covered, but the
    # leaf no longer holds over it.
    index, leaf = second_order_leaf(c)
    leaf["driver"] = list(c["tolerance"]["range"])


def tolerance_changed(c):
    # A consistent claim at a larger scale (box = scale x tolerances): the leaves do not cover it.
    t = c["tolerance"]
    old, new = fraction(t["scale"]), fraction(t["scale"]) * fraction("21/20")
    t["scale"] = rational(new)
    t["box"] = [[rational(fraction(lo) * new / old), rational(fraction(hi) * new / old)] for lo, hi in t["box"]]


def range_shifted(c):
    r = c["tolerance"]["range"]
    c["tolerance"]["range"] = [rational(fraction(r[0]) + fraction("1/100")), rational(fraction(r[1]) + fraction("1/100"))]


mutate(SECOND, "geneva.json", "t19-nojam-second-order-margin-raised.json", "second-order form", margin_raised)
mutate(SECOND, "geneva.json", "t20-nojam-second-order-margin-zero.json", "is not positive", margin_zero)
mutate(SECOND, "geneva.json", "t21-nojam-second-order-margins-dropped.json", "the witness is not certainly", margins_dropped)
mutate(SECOND, "geneva.json", "t22-nojam-second-order-driver-slope-flipped.json", "is not certainly inside the lower side's bracket", driver_slope_flipped)
mutate(SECOND, "geneva.json", "t23-nojam-second-order-leaf-driver-widened.json", "does not certainly change sign across the bracket", leaf_driver_widened)
mutate(SECOND, "geneva.json", "t24-nojam-second-order-tolerance-changed.json", "coverage gap", tolerance_changed)
mutate(SECOND, "geneva.json", "t25-nojam-second-order-scale-only-changed.json", "wrong parameter box",
       set_path(["tolerance", "scale"], "8"))
mutate(SECOND, "geneva.json", "t26-nojam-second-order-range-shifted.json", "coverage gap", range_shifted)

# Gear pairs (session 45): the spur gears' involute flanks are arcs only, the parts' pivots lie
# inside one part each ((0, 0) the pinion's, (45, 0) the gear's).
mutate("spur-interference.json", "spur-gears.json", "g01-gear-point-at-pinion-pivot.json",
       "is not strictly inside part 'gear' (it lies outside)", set_path(["interference", "point"], ["0", "0"]))
mutate("spur-interference.json", "spur-gears.json", "g02-gear-point-at-gear-pivot.json",
       "is not strictly inside part 'pinion' (it lies outside)", set_path(["interference", "point"], ["45", "0"]))
mutate("spur-interference.json", "spur-gears.json", "g03-gear-tangent-off-angle.json", "is not within",
       set_path(["interference", "configuration", "pinion", "tangent"], "0"))
mutate("spur-clearance.json", "spur-gears.json", "g04-gear-clearance-too-large.json", "less than the claimed",
       set_path(["clearance", "distance"], "258886/5000000"))
mutate("spur-clearance.json", "spur-gears.json", "g05-gear-clearance-at-overlap.json", "less than the claimed",
       lambda c: c["clearance"]["configuration"].__setitem__(
           "pinion", copy.deepcopy(load("spur-interference.json")["interference"]["configuration"]["pinion"])))
mutate("spur-free.json", "spur-gears.json", "g06-gear-free-box-removed.json", "gap in the boxes' cover",
       lambda c: c["free_passage"]["boxes"].pop(len(c["free_passage"]["boxes"]) // 2))
mutate("spur-free.json", "spur-gears.json", "g07-gear-free-range-extended.json", "at its end",
       lambda c: (c["free_passage"].__setitem__("range", ["0", "1/10"]),
                  c["free_passage"].__setitem__("path", [["0", "0"], ["1/10", "-1/15"]])))
mutate("spur-free.json", "spur-gears.json", "g08-gear-free-distance-too-large.json",
       "less than the claimed clearance plus the motion", set_path(["free_passage", "distance"], "1/10"))

with open(os.path.join(HERE, "EXPECTED.txt"), "w") as f:
    f.write("# certificate | model (relative to the repository) | expected: valid, unproven (exit 3), or a substring of the reason | base\n")
    for name, model, reason, base in expected:
        f.write(f"{name} | {model} | {reason} | {base}\n")
print(f"{len(expected)} certificates ({len(expected) - len(bases)} mutations)")
