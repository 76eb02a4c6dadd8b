# Zero-clearance fits and tangencies beyond the Geneva, session 46 (hunt46): docs/certify.md
# "Session 46 (hunt46)". Variants of the examples at zero clearance — the ratchet's pawl nose
# (nose-clearance 0), the cam follower's stem in its guide (guide-clearance 0), the Scotch yoke's
# pin in a slot of exactly its diameter with a guide of zero clearance, the escapement's impulse
# pin in a fork slot of exactly its diameter, the lever resting on its stop (stop-gap 0). Every
# cell `cspace --json` writes is checked at its sample against the exact overlap predicate
# through certificates: a free cell's clearance and a blocked cell's interference are certified
# and hipair-verify accepts them; at a touching cell's sample neither is certified ("cannot
# certify", exit 1). Prints each disagreement and "findings N"; exit 1 when N > 0.
# usage: zero_clearance_hunt.py HIPAIR HIPAIR_VERIFY MODELS_DIR WORK_DIR
import json, subprocess, sys, os, math, fractions
hipair, verify, models, work = sys.argv[1:5]
variants = [
  ('ratchet', {'nose-clearance': '0'}),
  ('cam-follower', {'guide-clearance': '0'}),
  ('scotch-yoke', {'slot-width': '10', 'guide-clearance': '0'}),
  ('escapement', {'fork-slot-width': '2.4'}),
  ('lever-stop', {'stop-gap': '0'}),
]
def run(args, timeout=300):
    p = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout + p.stderr
findings = 0
for name, params in variants:
    t = json.load(open(f'{models}/{name}.json'))
    for k, v in params.items():
        t['parameters'][k] = {'nominal': v}
    m = f'{work}/{name}-zero.json'
    json.dump(t, open(m, 'w'), indent=1)
    out = f'{work}/{name}-zero-cs.json'
    code, text = run([hipair, 'cspace', m, '--json', out])
    if code != 0:
        print(name, 'cspace exit', code, text[-300:]); continue
    files = [out] if os.path.exists(out) else sorted(f'{work}/{f}' for f in os.listdir(work) if f.startswith(f'{name}-zero-cs-'))
    for f in files:
        c = json.load(open(f))
        pair = c['pair']
        xs = c['x_part']; ys = c.get('y_part')
        touching = sum(1 for e in c.get('edges', []) if e.get('role') == 'touching')
        print(f'{name} {pair}: {len(c["cells"])} cells, touching edges {touching}, kinds {[x["kind"] for x in c["cells"]]}')
        for i, cell in enumerate(c['cells']):
            s = cell.get('sample')
            if not s: continue
            ch = c['charts'][s['chart']]
            def coord(v, kind, half):
                q = fractions.Fraction(v)
                if kind == 'translation': return str(q.numerator) + '/' + str(q.denominator)
                return repr((math.pi if half else 0) + 2 * math.atan(float(q)))
            at = ['--at', f'{xs}={coord(s["x"], ch["x"]["kind"], ch["x"].get("chart_center") not in ("0", "-"))}']
            if ys and c['dimension'] == 2:
                at += ['--at', f'{ys}={coord(s["y"], ch["y"]["kind"], ch["y"].get("chart_center") not in ("0", "-"))}']
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
