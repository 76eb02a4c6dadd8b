#!/usr/bin/env python3
"""Writes a model with every length multiplied exactly by a factor S (docs/model-format.md).

usage: scale_model.py MODEL FACTOR OUT [MODEL FACTOR OUT ...]
  FACTOR  an exact literal or expression of the model format: 1e300, 1e-300, 2^-700, 3/2

Every length is rewritten at its use site as the expression "(<as written>)*S", so it stays
exact (the reader evaluates it in rationals) and parameters keep their values: a parameter used
in a point is scaled with the point, an angle or a count never is. Lengths are: points (also a
polar point's centre and radius), radii, template length arguments (src/model/templates.cpp,
K::length and K::point), pivots, translation and pin-slot limits, initial offsets and x/y,
profile tolerance bands and their sigma. Dynamics keep the same motion in the scaled units
(mass and time unchanged, so a force scales by S): force, gravity, translational speeds, spring
points, rest lengths and centres of mass by S; torque, moment of inertia, torsional stiffness
and rotational damping by S^2; linear stiffness, linear damping, angles, rates of angles,
friction and restitution not at all. Directions, angles and counts are not scaled. JSON numbers
are kept as written (their text, never through a double).
"""
import json
import sys

LENGTH_ARGUMENTS = {
    "radius", "slot_width", "slot_inner_radius", "slot_outer_radius", "lock_center_radius",
    "lock_radius", "pin_radius", "pin_center_radius", "lock_outer_radius", "lock_inner_radius",
    "pitch_radius", "addendum", "dedendum", "tooth_thickness", "flank_radius", "tip_radius",
    "root_radius", "wheel_radius", "pallet_width", "fork_length", "fork_width",
    "fork_slot_width", "fork_slot_depth",
}
POINT_ARGUMENTS = {"center", "wheel_center"}


class Number(str):
    """A JSON number kept as its text."""


def dump(value):
    if isinstance(value, Number):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(dump(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(json.dumps(k, ensure_ascii=False) + ": " + dump(v)
                               for k, v in value.items()) + "}"
    raise TypeError(type(value))


class Scaler:
    def __init__(self, factor):
        self.factor = factor

    def times(self, value, power=1):
        """The value (a number or an expression) times S^power, as an expression."""
        if power == 0:
            return value
        if not isinstance(value, str):  # a Number is a str
            raise ValueError("not a number: %r" % (value,))
        factor = "(%s)" % self.factor if power == 1 else "(%s)^%d" % (self.factor, power)
        return "(%s)*%s" % (value, factor)

    def point(self, point):
        if isinstance(point, list):
            return [self.times(c) for c in point]
        if isinstance(point, dict) and "polar" in point:
            polar = dict(point["polar"])
            polar["center"] = self.point(polar["center"])
            polar["radius"] = self.times(polar["radius"])
            return {**point, "polar": polar}
        raise ValueError("not a point: %r" % (point,))

    def loop(self, loop):
        loop = dict(loop)
        if "start" in loop:
            loop["start"] = self.point(loop["start"])
        if "circle" in loop:
            circle = dict(loop["circle"])
            circle["center"] = self.point(circle["center"])
            circle["radius"] = self.times(circle["radius"])
            loop["circle"] = circle
        edges = []
        for edge in loop.get("edges", []):
            edge = dict(edge)
            for key in ("line_to", "arc_to", "center"):
                if key in edge:
                    edge[key] = self.point(edge[key])
            edges.append(edge)
        if "edges" in loop:
            loop["edges"] = edges
        return loop

    def feature(self, feature):
        out = {}
        for template, arguments in feature.items():
            scaled = {}
            for key, value in arguments.items():
                if key in POINT_ARGUMENTS:
                    scaled[key] = self.point(value)
                elif key in LENGTH_ARGUMENTS:
                    scaled[key] = self.times(value)
                else:
                    scaled[key] = value
            out[template] = scaled
        return out

    def motion(self, motion):
        if not isinstance(motion, dict):
            return motion
        out = {}
        for kind, spec in motion.items():
            spec = dict(spec)
            if "pivot" in spec:
                spec["pivot"] = self.point(spec["pivot"])
            if "limits" in spec and kind in ("translation", "pin_slot"):
                spec["limits"] = [self.times(v) for v in spec["limits"]]
            out[kind] = spec
        return out

    def part(self, part):
        part = dict(part)
        kind = motion_kind(part)
        part["motion"] = self.motion(part["motion"])
        if "initial" in part:
            part["initial"] = {k: (v if k == "angle" else self.times(v))
                               for k, v in part["initial"].items()}
        if "loops" in part:
            part["loops"] = [self.loop(loop) for loop in part["loops"]]
        if "features" in part:
            part["features"] = [self.feature(f) for f in part["features"]]
        if "profile_tolerances" in part:
            bands = []
            for band in part["profile_tolerances"]:
                band = dict(band)
                band["tolerance"] = self.times(band["tolerance"])
                if isinstance(band.get("distribution"), dict) and "normal" in band["distribution"]:
                    normal = dict(band["distribution"]["normal"])
                    normal["sigma"] = self.times(normal["sigma"])
                    band["distribution"] = {**band["distribution"], "normal": normal}
                bands.append(band)
            part["profile_tolerances"] = bands
        if "dynamics" in part:
            d = dict(part["dynamics"])
            if "moment_of_inertia" in d:
                d["moment_of_inertia"] = self.times(d["moment_of_inertia"], 2)
            if "torque" in d:
                d["torque"] = self.times(d["torque"], 2)
            if "force" in d:
                d["force"] = [self.times(v) for v in d["force"]]
            if "damping" in d and kind == "rotation":
                d["damping"] = self.times(d["damping"], 2)
            if "torsional_spring" in d:
                spring = dict(d["torsional_spring"])
                spring["stiffness"] = self.times(spring["stiffness"], 2)
                d["torsional_spring"] = spring
            if "linear_spring" in d:
                spring = dict(d["linear_spring"])
                if "rest" in spring:
                    spring["rest"] = self.times(spring["rest"])
                d["linear_spring"] = spring
            part["dynamics"] = d
        return part

    def rate(self, kind, value):
        """A velocity of a part of motion `kind`: mm per time unit scales, an angle rate not."""
        if isinstance(value, dict):  # planar: x, y, angle
            return {k: (v if k == "angle" else self.times(v)) for k, v in value.items()}
        return self.times(value) if kind == "translation" else value

    def simulation(self, simulation, kinds):
        s = dict(simulation)
        if "gravity" in s:
            s["gravity"] = [self.times(v) for v in s["gravity"]]
        if "velocities" in s:
            s["velocities"] = {p: self.rate(kinds.get(p), v) for p, v in s["velocities"].items()}
        if "drivers" in s:
            drivers = []
            for driver in s["drivers"]:
                driver = dict(driver)
                kind = kinds.get(driver.get("part"))
                if "speed" in driver:
                    driver["speed"] = self.rate(kind, driver["speed"])
                if "profile" in driver:
                    driver["profile"] = [[t, self.rate(kind, v)] for t, v in driver["profile"]]
                drivers.append(driver)
            s["drivers"] = drivers
        if "springs" in s:
            springs = []
            for spring in s["springs"]:
                spring = dict(spring)
                spring["points"] = [self.point(p) for p in spring["points"]]
                if "rest_length" in spring:
                    spring["rest_length"] = self.times(spring["rest_length"])
                springs.append(spring)
            s["springs"] = springs
        if "centers_of_mass" in s:
            s["centers_of_mass"] = {p: self.point(v) for p, v in s["centers_of_mass"].items()}
        return s

    def model(self, model):
        model = dict(model)
        kinds = {p.get("name"): motion_kind(p) for p in model.get("parts", [])}
        model["parts"] = [self.part(p) for p in model["parts"]]
        if "simulation" in model:
            model["simulation"] = self.simulation(model["simulation"], kinds)
        return model


def motion_kind(part):
    motion = part.get("motion")
    if isinstance(motion, str):
        return motion
    if isinstance(motion, dict) and len(motion) == 1:
        return next(iter(motion))
    return None


def scale_one(source, factor, out):
    with open(source, encoding="utf-8") as f:
        model = json.load(f, parse_float=Number, parse_int=Number)
    scaled = Scaler(factor).model(model)
    if "name" in scaled:
        scaled["name"] = "%s-x%s" % (scaled["name"], factor)
    text = dump(scaled) + "\n"  # the whole text before the file is opened: none half-written
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    # MODEL FACTOR OUT, or several such triples in one process (tests/fuzz/scaled_cli.sh writes
    # all its models at once: one interpreter start rather than one per model and scale). A
    # triple that fails is reported on stderr and writes no file; the others are still written.
    if len(argv) < 4 or (len(argv) - 1) % 3:
        sys.stderr.write(__doc__)
        return 2
    failed = 0
    for i in range(1, len(argv), 3):
        try:
            scale_one(argv[i], argv[i + 1], argv[i + 2])
        except Exception as error:  # noqa: BLE001 -- reported per model, the next one still written
            sys.stderr.write("scale_model: %s at %s: %s\n" % (argv[i], argv[i + 1], error))
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
