#!/usr/bin/env python3
"""A zero-backlash spur-gear pair from examples/models/spur-gears.json.

    zero_backlash_gears.py TEMPLATE Z1 Z2 OUT

Writes TEMPLATE with the pinion's and the gear's tooth counts Z1 and Z2, the backlash 0 and the
centre distance the sum of the pitch radii (module (Z1 + Z2) / 2), as the zero-backlash CLI
tests (tests/cli/run_gear_zero_backlash_tests.sh) and the sweep (tests/perf/gear_jam_sweep.sh)
use it.
"""
import json
import sys

template, z1, z2, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
with open(template) as f:
    model = json.load(f)
model['parameters']['teeth-1'] = {'nominal': z1}
model['parameters']['teeth-2'] = {'nominal': z2}
model['parameters']['backlash'] = {'nominal': 0}
model['parameters']['center-distance'] = {'nominal': 'module * (teeth-1 + teeth-2) / 2'}
with open(out, 'w') as f:
    json.dump(model, f, indent=1)
