# Zero-clearance fits and tangencies beyond the Geneva, session 46 (hunt46): docs/certify.md
# "Session 46 (hunt46)". Variants of the examples at zero clearance — the ratchet's pawl nose
# (nose-clearance 0), the cam follower's stem in its guide (guide-clearance 0), the Scotch yoke's
# pin in a slot of exactly its diameter with a guide of zero clearance, the escapement's impulse
# pin in a fork slot of exactly its diameter, the lever resting on its stop (stop-gap 0). Every
# cell `cspace --json` writes is checked at its sample against the exact overlap predicate
# through certificates: a free cell's clearance and a blocked cell's interference are certified
# and hipair-verify accepts them; at a touching cell's sample neither is certified ("cannot
# certify", exit 1). Prints each disagreement and "findings N"; exit 1 when N > 0.
#
# Session 62 (hunt62): `--case NAME:KEY=VALUE,...` replaces the variants by the given ones (a value
# is written as the parameter's nominal), `--gears Z1xZ2@BACKLASH,...` adds spur-gears.json pairs
# at the exact centre distance m (Z1 + Z2) / 2 (the tight fit; BACKLASH 0 or tiny), and
# `--region operating` builds only the operating region. A sample's angle is handed to
# `certify --at` with 40 significant digits (the sample's tangent, 2 atan t, in decimals): a
# double's 17 digits leave a sample outside a cell 10^-15 rad wide.
# usage: zero_clearance_hunt.py HIPAIR HIPAIR_VERIFY MODELS_DIR WORK_DIR [--case ...] [--gears ...] [--region operating]
import json, subprocess, sys, os, fractions, decimal
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_oracle import D, PI, atan

hipair, verify, models, work = sys.argv[1:5]
variants = [
  ('ratchet', {'nose-clearance': '0'}),
  ('cam-follower', {'guide-clearance': '0'}),
  ('scotch-yoke', {'slot-width': '10', 'guide-clearance': '0'}),
  ('escapement', {'fork-slot-width': '2.4'}),
  ('lever-stop', {'stop-gap': '0'}),
]
region = []
options = sys.argv[5:]
chosen = None
while options:
  flag, value = options[0], options[1]
  options = options[2:]
  if flag == '--case':
    name, _, settings = value.partition(':')
    chosen = (chosen or []) + [(name, dict(s.split('=', 1) for s in settings.split(',') if s))]
  elif flag == '--gears':
    for pair in value.split(','):
      teeth, _, backlash = pair.partition('@')
      z1, z2 = teeth.split('x')
      chosen = (chosen or []) + [('spur-gears', {'teeth-1': z1, 'teeth-2': z2, 'backlash': backlash or '0',
                                                 'center-distance': 'module * (teeth-1 + teeth-2) / 2'})]
  elif flag == '--region':
    region = ['--region', value]
  else:
    sys.exit('unknown option ' + flag)
if chosen is not None:
  variants = chosen
os.makedirs(work, exist_ok=True)

def run(args, timeout=300):
  try:
    p = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
  except subprocess.TimeoutExpired:
    return 'timeout', ''
  return p.returncode, p.stdout + p.stderr

def two_atan(t):
  """2 atan(t) for any rational t as a Decimal (80 digits)"""
  if abs(t) < 1:
    return 2 * atan(D(t.numerator) / D(t.denominator))
  if abs(t) == 1:
    return PI / 2 * (1 if t > 0 else -1)
  return (PI if t > 0 else -PI) - 2 * atan(D(t.denominator) / D(t.numerator))

def coordinate(value, axis):
  q = fractions.Fraction(value)
  if axis['kind'] == 'translation':
    return f'{q.numerator}/{q.denominator}'
  half = axis.get('chart_center') not in (None, '0', '-')
  with decimal.localcontext() as context:
    context.prec = 40
    return str(+((PI if half else 0) + two_atan(q)))

findings = 0
for name, params in variants:
  t = json.load(open(f'{models}/{name}.json'))
  for k, v in params.items():
    t['parameters'][k] = {'nominal': v}
  tag = name + ''.join(f'-{v}' for k, v in params.items() if k != 'center-distance')
  m = f'{work}/{tag}.json'
  json.dump(t, open(m, 'w'), indent=1)
  out = f'{work}/{tag}-cs.json'
  code, text = run([hipair, 'cspace', m, '--json', out, *region])
  if code != 0:
    if code != 3 or 'overlap at the seed' not in text:
      findings += 1
      print(tag, 'FINDING: cspace exit', code, text[-300:])
    else:
      print(tag, 'cspace exit 3 (the start overlaps):', text.strip()[-160:])
    continue
  files = [out] if os.path.exists(out) else sorted(f'{work}/{f}' for f in os.listdir(work) if f.startswith(f'{tag}-cs-'))
  for f in files:
    c = json.load(open(f))
    pair = c['pair']
    xs = c['x_part']; ys = c.get('y_part')
    touching = sum(1 for e in c.get('edges', []) if e.get('role') == 'touching')
    kinds = [x['kind'] for x in c['cells']]
    print(f'{tag} {pair}: {len(c["cells"])} cells, touching edges {touching}, kinds ' +
          ', '.join(f'{k} {kinds.count(k)}' for k in sorted(set(kinds))))
    for i, cell in enumerate(c['cells']):
      s = cell.get('sample')
      if not s: continue
      ch = c['charts'][s['chart']]
      at = ['--at', f'{xs}={coordinate(s["x"], ch["x"])}']
      if ys and c['dimension'] == 2:
        at += ['--at', f'{ys}={coordinate(s["y"], ch["y"])}']
      claim = {'free': 'clearance', 'blocked': 'interference'}.get(cell['kind'])
      if cell['kind'] == 'touching':
        # the parts touch there: neither apart nor overlapping may be certified
        for wrong in ('clearance', 'interference'):
          cert = f'{work}/cert.json'
          code, text = run([hipair, 'certify', m, '--claim', wrong, '--pair', f'{pair[0]}:{pair[1]}', *at, '--out', cert])
          if code != 1 or 'cannot certify' not in text:
            findings += 1
            print(f'  FINDING: touching cell {i} sample {s} {at}: certify {wrong} exit {code}: {text.strip()[-200:]}')
        continue
      if not claim: continue
      cert = f'{work}/cert.json'
      if os.path.exists(cert): os.remove(cert)
      code, text = run([hipair, 'certify', m, '--claim', claim, '--pair', f'{pair[0]}:{pair[1]}', *at, '--out', cert])
      ok = code == 0 and run([verify, cert, m])[0] == 0
      if not ok:
        findings += 1
        print(f'  FINDING? cell {i} {cell["kind"]} sample {s} {at}: certify {claim} exit {code}: {text.strip()[-200:]}')
print('findings', findings)
sys.exit(1 if findings else 0)
