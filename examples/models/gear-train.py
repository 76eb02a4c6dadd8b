# Generates examples/models/gear-train.json (9 gears: python3 gear-train.py 9 gear-train) and gear-train-3.json (python3 gear-train.py 3 gear-train-3).
import json, sys
def train(gears, name):
    params = {"module": {"nominal": 2, "tolerance": 0.002}}
    parts, pairs = [], []
    for k in range(gears):
        g = chr(ord('A') + k)
        z = 10 if k % 2 == 0 else 12
        phase = "0" if k == 0 else ("pi + pi / 12" if k % 2 else "pi")
        P = lambda s: f"{g}-{s}"
        params[P("teeth")] = {"nominal": z}
        params[P("pivot-x")] = {"nominal": 22 * k, "tolerance": 0.01}
        params[P("pivot-y")] = {"nominal": 0, "tolerance": 0.01}
        params[P("runout-x")] = {"nominal": 0, "tolerance": 0.005}
        params[P("runout-y")] = {"nominal": 0, "tolerance": 0.005}
        params[P("pitch-radius")] = {"nominal": f"module * {P('teeth')} / 2", "tolerance": 0.005}
        params[P("addendum")] = {"nominal": "module", "tolerance": 0.01}
        params[P("dedendum")] = {"nominal": "1.25 * module", "tolerance": 0.01}
        params[P("thinning")] = {"nominal": 0.1, "tolerance": 0.01}
        params[P("flank-radius")] = {"nominal": 4, "tolerance": 0.02}
        params[P("pressure-angle")] = {"nominal": "20 deg", "tolerance": 0.002, "angle": True}
        params[P("phase")] = {"nominal": phase, "tolerance": 0.001, "angle": True}
        part = {"name": f"gear-{g}", "motion": {"rotation": {"pivot": [P("pivot-x"), P("pivot-y")]}},
                "initial": {"angle": 0},
                "features": [{"spur_gear": {"center": [f"{P('pivot-x')} + {P('runout-x')}", f"{P('pivot-y')} + {P('runout-y')}"],
                   "teeth": P("teeth"), "pitch_radius": P("pitch-radius"), "addendum": P("addendum"),
                   "dedendum": P("dedendum"), "tooth_thickness": f"pi * module / 2 - {P('thinning')}",
                   "flank_radius": P("flank-radius"), "pressure_angle": P("pressure-angle"), "phase": P("phase")}}]}
        parts.append(part)
        if k > 0: pairs.append({"parts": [f"gear-{chr(ord('A') + k - 1)}", f"gear-{g}"]})
    toleranced = sum(1 for p in params.values() if "tolerance" in p)
    return {"hipair": 1, "name": name,
            "description": f"An idler gear train of {gears} spur gears in a row ({gears - 1} meshes), teeth 10 and 12 alternating, module 2 mm (toleranced, shared by every gear), 20 degree pressure angle, each flank one circular arc (flank_radius). Per gear: bearing position, runout of the gear on its shaft, pitch radius, addendum, dedendum, tooth thinning (half the backlash), flank radius, pressure angle and the teeth's angular phase on the shaft are toleranced ({toleranced} toleranced parameters). Gear A drives; over a turn of A the last gear turns z_A / z_last turns the same way (an even number of meshes).",
            "units": {"length": "mm", "angle": "rad"}, "parameters": params, "parts": parts, "pairs": pairs}
n = int(sys.argv[1])
print(json.dumps(train(n, sys.argv[2]), indent=1))
