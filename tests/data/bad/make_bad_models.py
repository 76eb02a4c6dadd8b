# Generates tests/data/bad/*.json and EXPECTED.txt (file<TAB>pointer<TAB>message fragment).
import json, os, copy
out = os.path.dirname(os.path.abspath(__file__))
os.makedirs(out, exist_ok=True)
square = {"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}
def base():
    return {"hipair": 1, "name": "bad", "parts": [{"name": "plate", "motion": "fixed", "loops": [copy.deepcopy(square)]}]}
def two_parts():
    m = base()
    m["parts"].append({"name": "arm", "motion": {"rotation": {"pivot": [30, 0]}},
                       "loops": [{"start": [20, 0], "edges": [{"line_to": [40, 0]}, {"line_to": [40, 2]}, {"line_to": [20, 2]}, {"line_to": [20, 0]}]}]})
    return m
cases = []  # (name, text-or-model, pointer, fragment, description)
def add(name, model, pointer, fragment, comment):
    cases.append((name, model, pointer, fragment, comment))
def part_loops(loops, model=None):
    m = model or base()
    m["parts"][0]["loops"] = loops
    return m

add("malformed_json", '{"hipair": 1, "name": "x",, "parts": []}', "", "malformed JSON at line 1", "two commas")
add("truncated_file", json.dumps(base(), indent=1)[:120], "", "unexpected end of file", "file cut short")
add("empty_file", "", "", "malformed JSON at line 1, column 1", "nothing at all")
add("trailing_garbage", json.dumps(base()) + " {", "", "malformed JSON", "a second value after the model")
add("infinity_literal", json.dumps(base()).replace('"start": [0, 0]', '"start": [0, Infinity]'), "", "malformed JSON", "Infinity is not JSON")
add("nan_literal", json.dumps(base()).replace('"start": [0, 0]', '"start": [NaN, 0]'), "", "malformed JSON", "NaN is not JSON")
add("huge_exponent", json.dumps(base()).replace('"start": [0, 0]', '"start": [0, 1e999999]'), "/parts/0/loops/0/start/1", "out of range", "exponent beyond the reader's limit, as a JSON number (named by its pointer)")
m = base(); m["parts"][0]["loops"][0]["start"] = [0, "1e-5000"]
add("huge_exponent_string", m, "/parts/0/loops/0/start/1", "out of range", "exponent beyond the reader's limit")
m = base(); m["parts"][0]["loops"][0]["start"] = ["nan", 0]
add("nan_string", m, "/parts/0/loops/0/start/0", "NaN and infinity are not allowed", "the string nan")
m = base(); m["parts"][0]["loops"][0]["start"] = [0, "-inf"]
add("infinity_string", m, "/parts/0/loops/0/start/1", "NaN and infinity are not allowed", "the string -inf")
add("root_not_object", "[1, 2, 3]", "", "must hold a JSON object", "an array at top level")
m = base(); m["colour"] = "red"
add("unknown_key_top", m, "/colour", "unknown key 'colour'", "unknown top-level key")
m = base(); m["parts"][0]["loops"][0]["edges"][1] = {"line_too": [10, 10]}
add("unknown_key_edge", m, "/parts/0/loops/0/edges/1/line_too", "unknown key 'line_too'", "misspelt edge kind")
m = base(); m["parts"][0]["name"] = 5
add("wrong_type_name", m, "/parts/0/name", "expected a string, found a number", "name is a number")
m = base(); m["parts"][0]["loops"][0]["start"] = "origin"
add("wrong_type_point", m, "/parts/0/loops/0/start", "expected a point [x, y]", "a point given as a word")
m = base(); m["parts"][0]["loops"][0]["start"] = [0, 0, 0]
add("point_three_coordinates", m, "/parts/0/loops/0/start", "expected 2 numbers, found 3", "3-D point")
m = base(); m["parts"][0]["loops"][0]["start"] = [0, True]
add("wrong_type_coordinate", m, "/parts/0/loops/0/start/1", "found a boolean", "boolean coordinate")
m = base(); m["hipair"] = 2
add("wrong_version", m, "/hipair", "unsupported format version", "format version 2")
m = base(); del m["parts"]
add("missing_parts", m, "", "missing required key 'parts'", "no parts")
m = base(); m["parts"] = []
add("empty_parts", m, "/parts", "at least one part", "empty parts array")
m = base(); m["units"] = {"length": "mm", "angle": "grad"}
add("bad_angle_unit", m, "/units/angle", "unsupported angle unit 'grad'", "grads")
m = base(); m["units"] = {"length": "inch"}
add("bad_length_unit", m, "/units/length", "unsupported length unit 'inch'", "inches")
add("duplicate_keys", '{"hipair": 1, "name": "bad", "parts": [{"name": "plate", "name": "plate2", "motion": "fixed", "loops": []}]}',
    "/parts/0/name", "duplicate key 'name'", "a key given twice")
m = base(); m["parameters"] = {"width": {"nominal": 10}}; m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["widht", 0]
add("unknown_parameter", m, "/parts/0/loops/0/edges/0/line_to/0", "unknown parameter 'widht'", "misspelt parameter")
m = base(); m["parameters"] = {"width": {"nominal": 10}}; m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["width-2", 0]
add("minus_inside_name", m, "/parts/0/loops/0/edges/0/line_to/0", "write 'a - b' with spaces", "width-2 is one name")
m = base(); m["parameters"] = {"a": {"nominal": "b + 1"}, "b": {"nominal": "2 * c"}, "c": {"nominal": "a / 3"}}
add("circular_parameters", m, "/parameters/a", "circular parameter references: a -> b -> c -> a", "a cycle of three")
m = base(); m["parameters"] = {"a": {"nominal": "a + 1"}}
add("self_referencing_parameter", m, "/parameters/a", "circular parameter references: a -> a", "a parameter defined by itself")
m = base(); m["parameters"] = {"2x": {"nominal": 1}}
add("invalid_parameter_name", m, "/parameters/2x", "invalid parameter name", "name starts with a digit")
m = base(); m["parameters"] = {"pi": {"nominal": 3}}
add("reserved_parameter_name", m, "/parameters/pi", "reserved word", "pi is a constant")
m = base(); m["parameters"] = {"r": {"nominal": 4}}; m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["10 / (r - 4)", 0]
add("division_by_zero", m, "/parts/0/loops/0/edges/0/line_to/0", "division by zero", "divides by a zero parameter difference")
m = base(); m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["sqrt(2 - 3)", 0]
add("sqrt_negative", m, "/parts/0/loops/0/edges/0/line_to/0", "square root of a negative number", "sqrt(-1)")
m = base(); m["units"] = {"angle": "deg"}; m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["10 * tan(90)", 0]
add("tan_undefined", m, "/parts/0/loops/0/edges/0/line_to/0", "tan is undefined", "tan of 90 degrees")
m = base(); m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["2 * (3 + 4", 0]
add("expression_syntax", m, "/parts/0/loops/0/edges/0/line_to/0", "expected ')'", "unbalanced parenthesis")
m = base(); m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["log(10)", 0]
add("unknown_function", m, "/parts/0/loops/0/edges/0/line_to/0", "unknown function 'log'", "no logarithms")
m = base(); m["parts"][0]["loops"][0]["edges"][0]["line_to"] = ["2^0.5", 0]
add("non_integer_exponent", m, "/parts/0/loops/0/edges/0/line_to/0", "must be an integer", "use sqrt instead")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "tolerance": [0.02, -0.01]}}
add("tolerance_lo_above_hi", m, "/parameters/gap/tolerance", "greater than the upper deviation", "asymmetric tolerance reversed")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "tolerance": -0.01}}
add("negative_tolerance", m, "/parameters/gap/tolerance", "must not be negative", "negative symmetric tolerance")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "range": [1.1, 1.2]}}
add("nominal_outside_range", m, "/parameters/gap/nominal", "lies outside its range", "range misses the nominal")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "tolerance": [0.01, 0.02]}}
add("nominal_outside_tolerance", m, "/parameters/gap/tolerance", "outside its tolerance", "deviations both positive")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "distribution": "uniform"}}
add("distribution_without_tolerance", m, "/parameters/gap/distribution", "needs a 'tolerance' or 'range'", "nothing to distribute")
m = base(); m["parameters"] = {"gap": {"nominal": 1, "tolerance": 0.1, "distribution": {"normal": {"sigma": 0}}}}
add("zero_sigma", m, "/parameters/gap/distribution/normal/sigma", "sigma must be positive", "degenerate normal")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 10]}]}])
add("open_loop", m, "/parts/0/loops/0", "open loop", "the last edge stops short")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 0]}]}])
add("zero_length_segment", m, "/parts/0/loops/0/edges/1", "zero-length segment", "a segment to where it already is")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"arc_to": [0, 10.001], "center": [0, 0], "dir": "ccw"}, {"line_to": [0, 0]}]}])
add("inconsistent_arc", m, "/parts/0/loops/0/edges/1", "inconsistent arc", "arc end 0.001 off its circle")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"arc_to": [0, 0], "center": [10, 0], "dir": "ccw"}]}])
add("zero_radius", m, "/parts/0/loops/0/edges/1", "zero radius", "arc ends at its own centre")
m = part_loops([{"circle": {"center": [5, 5], "radius": -3}}])
add("negative_radius", m, "/parts/0/loops/0/circle/radius", "must be positive", "circle of radius -3")
m = part_loops([{"circle": {"center": [5, 5], "radius": 0}}])
add("zero_radius_circle", m, "/parts/0/loops/0/circle/radius", "must be positive", "circle of radius 0")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 10]}, {"line_to": [10, 0]}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}])
add("bowtie", m, "/parts/0/loops/0/edges/2", "the loop intersects itself", "figure of eight polygon")
m = part_loops([copy.deepcopy(square), {"start": [5, 5], "edges": [{"line_to": [15, 5]}, {"line_to": [15, 15]}, {"line_to": [5, 15]}, {"line_to": [5, 5]}]}])
add("loops_cross", m, "/parts/0/loops/1/edges/3", "cross or touch", "two overlapping squares in one part")
m = part_loops([copy.deepcopy(square), {"start": [2, 2], "edges": [{"line_to": [10, 2]}, {"line_to": [10, 8]}, {"line_to": [2, 8]}, {"line_to": [2, 2]}]}])
add("hole_touches_outline", m, "/parts/0/loops/1/edges/0", "cross or touch", "a hole whose side lies on the outline")
m = part_loops([copy.deepcopy(square), {"circle": {"center": [5, 5], "radius": 5}}])
add("circle_tangent_to_outline", m, "/parts/0/loops/1/circle", "cross or touch", "inscribed circle touches all four sides")
m = part_loops([{"circle": {"center": [0, 0], "radius": 5}}, {"circle": {"center": [6, 0], "radius": 2}}])
add("circles_cross", m, "/parts/0/loops/1/circle", "cross or touch", "two circles of one part crossing")
m = part_loops([copy.deepcopy(square), {"start": [2, 2], "edges": [{"line_to": [8, 2]}, {"arc_to": [8, 8], "center": [8, 5], "dir": "ccw"},
                 {"line_to": [2, 8]}, {"line_to": [2, 2]}]}])
add("arc_crosses_segment", m, "/parts/0/loops/1/edges/1", "cross or touch", "a hole's arc bulges through the outline at (10, 5 +- sqrt 5)")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [9, 10]},
                 {"arc_to": [1, 10], "center": [5, 2], "dir": "cw"}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}])
add("arc_self_crossing", m, "/parts/0/loops/0/edges/5", "the loop intersects itself", "an arc of one loop sweeping out through its sides")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [10, 5]}, {"line_to": [0, 5]}, {"line_to": [0, 0]}]}])
add("spike", m, "/parts/0/loops/0/edges/2", "zero-area spike", "an edge running back along the previous one")
m = part_loops([{"start": [5, 0], "edges": [{"arc_to": [5, 0], "center": [0, 0], "dir": "ccw"}, {"line_to": [6, 0]}, {"line_to": [5, 0]}]}])
add("full_circle_inside_loop", m, "/parts/0/loops/0/edges/0", "must be a loop of its own", "circle as one edge of many")
m = part_loops([{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"arc_to": [0, 10], "center": [0, 0]}, {"line_to": [0, 0]}]}])
add("arc_without_direction", m, "/parts/0/loops/0/edges/1", "missing required key 'dir'", "ccw or cw must be said")
m = part_loops([{"start": [0, 0], "edges": []}])
add("loop_without_edges", m, "/parts/0/loops/0/edges", "at least one edge", "empty edge list")
m = base(); m["parts"][0]["loops"] = []
add("part_without_geometry", m, "/parts/0", "has no geometry", "no loops or features")
m = base(); m["parts"][0]["motion"] = {"translation": {"direction": [0, 0]}}
add("zero_motion_axis", m, "/parts/0/motion/translation/direction", "zero direction vector", "translation with no axis")
m = base(); m["parts"][0]["motion"] = "spinning"
add("unknown_motion", m, "/parts/0/motion", "unknown motion 'spinning'", "no such motion")
m = base(); m["parts"][0]["motion"] = {"rotation": {"pivot": [0, 0]}, "translation": {"direction": [1, 0]}}
add("two_motions", m, "/parts/0/motion", "exactly one of", "rotation and translation at once")
m = base(); m["parts"][0]["motion"] = {"rotation": {"pivot": [0, 0], "limits": [1, -1]}}
add("limits_reversed", m, "/parts/0/motion/rotation/limits", "must be less than the upper limit", "lower limit above upper")
m = base(); m["units"] = {"angle": "deg"}; m["parts"][0]["motion"] = {"rotation": {"pivot": [0, 0], "limits": [-30, 30]}}; m["parts"][0]["initial"] = {"angle": 45}
add("initial_outside_limits", m, "/parts/0/initial/angle", "outside the motion's angle limits", "starts beyond its stop")
m = base(); m["parts"][0]["motion"] = {"rotation": {"pivot": [0, 0]}}; m["parts"][0]["initial"] = {"offset": 2}
add("initial_key_not_used", m, "/parts/0/initial/offset", "unknown key 'offset'", "a rotation has no offset")
m = two_parts(); m["parts"][1]["name"] = "plate"
add("duplicate_part_names", m, "/parts/1/name", "duplicate part name 'plate'", "two parts called plate")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "lever"]}]
add("unknown_pair_part", m, "/pairs/0/parts/1", "unknown part 'lever'", "pair names a missing part")
m = two_parts(); m["pairs"] = [{"parts": ["arm", "arm"]}]
add("self_pair", m, "/pairs/0/parts", "cannot be paired with itself", "a part with itself")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"]}, {"parts": ["arm", "plate"]}]
add("duplicate_pair", m, "/pairs/1", "duplicate pair", "the same pair twice, reversed")
m = two_parts(); m["pairs"] = [{"parts": ["plate"]}]
add("pair_of_one", m, "/pairs/0/parts", "exactly 2 parts", "a pair of one part")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"], "restitution": 1.5}]
add("restitution_above_one", m, "/pairs/0/restitution", "restitution must lie in [0, 1]", "bouncier than elastic")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"], "friction": -0.1}]
add("negative_friction", m, "/pairs/0/friction", "friction must not be negative", "negative friction coefficient")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"], "friction": {"static": 0.2, "kinetic": 0.3}}]
add("kinetic_friction_above_static", json.dumps(m, indent=2), "/pairs/0/friction/kinetic", "kinetic friction must not exceed static friction", "sliding grips harder than sticking")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"], "friction": {"static": 0.2, "kinetic": -0.1}}]
add("negative_kinetic_friction", json.dumps(m, indent=2), "/pairs/0/friction/kinetic", "kinetic friction must not be negative", "negative kinetic coefficient")
m = two_parts(); m["pairs"] = [{"parts": ["plate", "arm"], "friction": {"static": 0.2}}]
add("friction_without_kinetic", json.dumps(m, indent=2), "/pairs/0/friction", "kinetic", "the object form names both coefficients")
m = two_parts(); m["parts"][1]["dynamics"] = {"mass": -1}
add("negative_mass", m, "/parts/1/dynamics/mass", "mass must not be negative", "negative mass")
m = two_parts(); m["parts"][1]["dynamics"] = {"moment_of_inertia": "-2"}
add("negative_inertia", m, "/parts/1/dynamics/moment_of_inertia", "moment of inertia must not be negative", "negative inertia")
m = two_parts(); m["parts"][1]["dynamics"] = {"torsional_spring": {"stiffness": -3}}
add("negative_stiffness", m, "/parts/1/dynamics/torsional_spring/stiffness", "stiffness must not be negative", "negative spring rate")
m = two_parts(); m["parts"][1]["dynamics"] = {"damping": -0.5}
add("negative_damping", m, "/parts/1/dynamics/damping", "damping must not be negative", "negative damping")
m = base()
m["parts"].append({"name": "slider", "motion": {"pin_slot": {"pivot": [30, 0], "direction": [1, 0]}},
                   "loops": [{"start": [20, 0], "edges": [{"line_to": [40, 0]}, {"line_to": [40, 2]}, {"line_to": [20, 2]}, {"line_to": [20, 0]}]}]})
m["simulation"] = {"springs": [{"parts": ["plate", "slider"], "points": [[0, 0], [30, 0]], "stiffness": 1}]}
add("spring_on_pin_slot_part", m, "/simulation/springs/0/parts/1", "is a pin-slot part", "a spring joins fixed, rotating, translating or planar parts only")
m = base()
m["parts"].append({"name": "pusher", "motion": {"planar": {"pivot": [30, 0]}}, "initial": {"x": 0, "y": 0},
                   "loops": [{"start": [20, 0], "edges": [{"line_to": [40, 0]}, {"line_to": [40, 2]}, {"line_to": [20, 2]}, {"line_to": [20, 0]}]}]})
m["simulation"] = {"drivers": [{"part": "pusher", "law": "speed_profile", "profile": [[0, {"x": 1}], [0.5, {"x": 2, "angle": 1}], [0.5, {"y": 3}]]}]}
add("planar_profile_time_not_increasing", m, "/simulation/drivers/0/profile/2/0", "profile times must increase strictly", "a planar driver's speed profile with two points at 0.5")
m = base(); m["parts"][0]["features"] = [{"sprocket": {"teeth": 12}}]
add("unknown_feature_template", m, "/parts/0/features/0/sprocket", "unknown feature template 'sprocket'", "no such template")
m = base(); m["parts"][0]["features"] = [{"circle": {"center": [50, 50], "radius": 2, "colour": "red"}}]
add("unknown_template_argument", m, "/parts/0/features/0/circle/colour", "unknown argument 'colour'", "template argument misspelt")
m = base(); m["parts"][0]["features"] = [{"circle": {"center": [50, 50]}}]
add("missing_template_argument", m, "/parts/0/features/0/circle", "needs argument 'radius'", "a circle without radius")
m = base(); m["parameters"] = {"p%d" % i: {"nominal": "p%d + 1" % (i + 1)} for i in range(250)}; m["parameters"]["p250"] = {"nominal": 1}
add("parameter_chain_too_deep", m, "/parameters/p200", "more than 200 levels deep", "250 parameters each defined by the next")
m = base(); m["parts"][0]["loops"] = [{"circle": {"center": {"polar": {"center": [0, 0], "radius": 1, "angle": "1e7"}}, "radius": 1}}]
add("angle_too_large", m, "/parts/0/loops/0/circle/center/polar/angle", "larger than 1000000 rad", "a polar angle of 10^7 rad")
m = base(); m["units"] = {"angle": "deg"}; m["parts"][0]["motion"] = {"rotation": {"pivot": [0, 0], "limits": ["-pi/4", "pi/4"]}}
add("ambiguous_pi_angle", m, "/parts/0/motion/rotation/limits/0", "ambiguous angle", "pi/4 in a degree file: 45 degrees or pi/4 degrees?")
nested = 0
for _ in range(80): nested = [nested]
m = base(); m["description"] = "deep"; 
add("nested_too_deeply", json.dumps(m)[:-1] + ', "extra": ' + json.dumps(nested) + "}", "/extra" + "/0" * 63, "nested too deeply", "80 levels of arrays")
add("invalid_utf8", b'{"hipair": 1, "name": "bad\xff\xfe", "parts": []}', "", "malformed JSON", "a name with invalid UTF-8 bytes")

expected = ["# file<TAB>JSON pointer of the error (- for the whole document)<TAB>fragment of the message<TAB>what is wrong"]
for name, model, pointer, fragment, comment in cases:
    path = os.path.join(out, name + ".json")
    if isinstance(model, bytes):
        open(path, "wb").write(model)
    elif isinstance(model, str):
        open(path, "w").write(model)
    else:
        open(path, "w").write(json.dumps(model, indent=2) + "\n")
    expected.append("\t".join([name + ".json", pointer or "-", fragment, comment]))
open(os.path.join(out, "EXPECTED.txt"), "w").write("\n".join(expected) + "\n")
print(len(cases), "bad models")
