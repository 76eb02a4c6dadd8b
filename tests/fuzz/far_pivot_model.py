#!/usr/bin/env python3
"""Writes the ratchet with its wheel's pivot moved by an exact offset (docs/cspace.md, "A pivot far
from its part"; docs/performance.md, "Session 46 (pivot46)").

usage: far_pivot_model.py VARIANT OFFSET OUT
  VARIANT  pivot: only the wheel's pivot x becomes (0)+(OFFSET) (the teeth stay at the origin);
           wheel: the pivot and the wheel's centre (the pair apart);
           all:   every pivot and point of both parts (the whole mechanism translated)
  OFFSET   an exact literal of the model format: 1e50, 1e400

The model is examples/models/ratchet.json (next to this script's repository root); coordinates
are written as expressions "(x)+(OFFSET)", read exactly in rationals.
"""
import json
import os
import sys


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("pivot", "wheel", "all"):
        sys.exit(__doc__)
    variant, offset, out = sys.argv[1:]
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with open(os.path.join(root, "examples", "models", "ratchet.json")) as f:
        model = json.load(f)

    def moved(value):
        return "(%s)+(%s)" % (value, offset)

    wheel, pawl = model["parts"]
    wheel["motion"]["rotation"]["pivot"][0] = moved(wheel["motion"]["rotation"]["pivot"][0])
    if variant in ("wheel", "all"):
        centre = wheel["features"][0]["ratchet_wheel"]["center"]
        centre[0] = moved(centre[0])
    if variant == "all":
        pawl["motion"]["rotation"]["pivot"][0] = moved(pawl["motion"]["rotation"]["pivot"][0])
        loop = pawl["loops"][0]
        loop["start"][0] = moved(loop["start"][0])
        for edge in loop["edges"]:
            edge["line_to"][0] = moved(edge["line_to"][0])
    with open(out, "w") as f:
        json.dump(model, f, indent=1)


if __name__ == "__main__":
    main()
