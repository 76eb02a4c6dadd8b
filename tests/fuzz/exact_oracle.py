"""Exact and certified numbers for the certificate oracles (certificate_alterations.py,
motion_certificate_alterations.py; sessions 47-48): Python fractions and 80-digit decimals, no
code of the library or the verifier.  A decimal result is within 10^-75 of the true value; a
comparison closer than 10^-70 is left undecided (None) by its callers."""
import decimal, json, os, subprocess
from fractions import Fraction as F

decimal.getcontext().prec = 80
D = decimal.Decimal
MARGIN = D(10) ** -70


def dec(f):
    """a Fraction as an 80-digit Decimal"""
    return D(f.numerator) / D(f.denominator)


def atan(x):
    """atan of a Decimal x, |x| < 1 (halved twice: |x / (1 + sqrt(1 + x^2))| < 0.42, then the series)"""
    assert abs(x) < 1
    for _ in range(2):
        x = x / (1 + (1 + x * x).sqrt())
    total, power, k = D(0), x, 0
    while abs(power) > D(10) ** -78:
        total += power / (2 * k + 1) * (-1 if k % 2 else 1)
        power *= x * x
        k += 1
    return 4 * total


def two_atan(t):
    """2 atan(t) for a rational |t| < 1 as an 80-digit Decimal"""
    return 2 * atan(dec(t))


PI = 4 * (4 * atan(D(1) / 5) - atan(D(1) / 239))


def sin_cos(x):
    """(sin x, cos x) of a Decimal |x| < 4 by their series"""
    s, c, term, k = D(0), D(0), D(1), 0
    while k < 2 or abs(term) > D(10) ** -78:
        if k % 2 == 0:
            c += term * (-1 if k % 4 == 2 else 1)
        else:
            s += term * (-1 if k % 4 == 3 else 1)
        k += 1
        term = term * x / k
    return s, c


def compare(x, y):
    """-1, 0 or 1 for Decimals further apart than MARGIN; None when closer (undecided)"""
    if abs(x - y) < MARGIN:
        return None
    return -1 if x < y else 1


def decimal_text(v, digits):
    """v to `digits` significant digits, without trailing zeros; below 1e-21 or from 1e30 on with an
    exponent, as the library's to_decimal_string writes it ("3.67341e-40": session 29) — until
    session 65 (hunt65) this wrote 39 zeros there, so the oracle restated a tiny clearance claim
    unlike hipair and hipair-verify"""
    ctx = decimal.Context(prec=digits, rounding=decimal.ROUND_HALF_EVEN)
    d = ctx.divide(D(v.numerator), D(v.denominator))
    if d != 0 and not -20 <= d.adjusted() + 1 <= 30:
        sign, mantissa = ('-' if d < 0 else ''), ''.join(map(str, d.as_tuple().digits)).rstrip('0')
        return sign + mantissa[0] + ('.' + mantissa[1:] if len(mantissa) > 1 else '') + 'e%d' % d.adjusted()
    text = format(d, 'f')
    if '.' in text:
        text = text.rstrip('0').rstrip('.')
    return '0' if text in ('-0', '') else text


def claim_number(v):
    """a number as a certificate's statement writes it: 12 or 25 digits when exact, else p/q"""
    for digits in (12, 25):
        text = decimal_text(v, digits)
        if F(text) == v:
            return text
    return str(v)


def bisect(holds, good, bad, steps=60):
    """the last value for which holds() is true and the first for which it is not, 2^-steps apart"""
    for _ in range(steps):
        mid = (good + bad) / 2
        good, bad = (mid, bad) if holds(mid) else (good, mid)
    return good, bad


def rational_near(x, digits=40):
    """a Fraction within 10^-digits of the Decimal x"""
    return F(int((x * D(10) ** digits).to_integral_value()), 10 ** digits)


def altered_numbers(rng, text):
    """(what, value) alterations of an exact literal: sign, +-1/den, the last digit, x(1 + 10^-k)"""
    f = F(text)
    cands = [('sign', -f), ('+1/den', f + F(1, f.denominator)), ('-1/den', f - F(1, f.denominator))]
    if text[-1].isdigit():
        cands.append(('last digit', F(text[:-1] + str((int(text[-1]) + rng.choice([1, 9])) % 10))))
    k = rng.randrange(3, 20)
    cands.append(('x(1+1e-%d)' % k, f * (1 + F(1, 10 ** k))))
    return [(what, v) for what, v in cands if v != f]


def verdict_problems(code, text, true, counts, unproven_claims=False):
    """counts one verdict (exit code of a single run, its output) against the truth (True, False or
    None: undecided) in `counts`; returns the problems: a false certificate accepted, or an exit
    other than 0/1/3 or more than one line; with unproven_claims (a no_jam certificate, whose
    'unproven', exit 3, still asserts checks 1-6: the named sides apart over every leaf, false when
    the oracle's channel closes) exit 3 too"""
    problems = []
    if code not in (0, 1, 3) or len(text.splitlines()) != 1:
        problems.append('exit %d, %d lines' % (code, len(text.splitlines())))
    if true is None:
        counts['undecided'] += 1
    elif code == 0 and not true:
        problems.append('a FALSE certificate accepted')
    elif code == 3 and not true and unproven_claims:
        problems.append("a FALSE certificate's checks 1-6 passed (unproven)")
    elif code != 0 and true:
        counts['true rejected'] += 1
    elif true:
        counts['true accepted'] += 1
    else:
        counts['false rejected'] += 1
    return problems


def judged(verify, path, model, certificate, true, counts, unproven_claims=False):
    """writes the certificate to `path`, runs hipair-verify on it and counts its verdict against the
    truth (verdict_problems); returns (problems, exit code, output)"""
    json.dump(certificate, open(path, 'w'))
    r = subprocess.run([verify, path, model], capture_output=True, text=True, timeout=120)
    text = (r.stdout + r.stderr).strip()
    return verdict_problems(r.returncode, text, true, counts, unproven_claims), r.returncode, text


VERDICT_CODES = {'valid': 0, 'invalid': 1, 'unproven': 3}


class BatchVerifier:
    """Session 75 (verify75): checks queued certificates with one `hipair-verify --list` process per
    `size` of them instead of one process each (half of a single check's cost is the process's
    start).  add() writes the certificate to a file of its own (PREFIX-N.json) and queues it;
    flush() runs the verifier on the queue and hands each check its verdict as a single run would
    give it: then(exit code, verdict line), which returns whether to keep the file (a case with a
    problem; the others' files are removed).  The batch's output must be one line per certificate,
    in order, "PATH: valid|invalid|unproven: ...", and its exit status the worst verdict's (1 if any
    invalid, else 3 if any unproven, else 0; a finding otherwise); a missing or malformed line is
    passed on as exit -1 with the batch's output, so that the check reports it as a problem naming
    its case.  With VERIFY_BOTH_WAYS set (run_verify_batch_tests.sh) every certificate is also
    checked by a run of its own, whose exit status and output must be the batch's verdict."""

    def __init__(self, verify, size=250):
        self.verify, self.size, self.queue, self.findings, self.added = verify, size, [], 0, 0
        self.both_ways = bool(os.environ.get('VERIFY_BOTH_WAYS'))

    def add(self, prefix, model, certificate, then):
        path = '%s-%d.json' % (prefix, self.added)
        self.added += 1
        json.dump(certificate, open(path, 'w'))
        self.queue.append((path, model, then))
        if len(self.queue) >= self.size:
            self.flush()

    def flush(self):
        if not self.queue:
            return
        queue, self.queue = self.queue, []
        listing = queue[0][0] + '.list'
        with open(listing, 'w') as f:
            f.writelines('%s\t%s\n' % (path, model) for path, model, _ in queue)
        r = subprocess.run([self.verify, '--list', listing], capture_output=True, text=True, timeout=120 * len(queue))
        lines = r.stdout.split('\n')
        if lines and lines[-1] == '':
            lines.pop()
        codes = []
        for i, (path, model, then) in enumerate(queue):
            code, text = -1, 'batch exit %d, %d lines for %d certificates, stderr %r' % (
                r.returncode, len(lines), len(queue), r.stderr.strip()[:200])
            if len(lines) == len(queue) and lines[i].startswith(path + ': '):
                text = lines[i][len(path) + 2:]
                code = VERDICT_CODES.get(text.split(':', 1)[0], -1)
            codes.append(code)
            if self.both_ways:
                one = subprocess.run([self.verify, path, model], capture_output=True, text=True, timeout=120)
                if (one.returncode, (one.stdout + one.stderr).strip()) != (code, text):
                    print('%s: a single run says exit %d %r, the batch exit %d %r' % (
                        path, one.returncode, (one.stdout + one.stderr).strip()[:200], code, text[:200]), flush=True)
                    self.findings += 1
            if not then(code, text):
                os.remove(path)
        worst = 1 if 1 in codes else 3 if 3 in codes else 0
        if -1 not in codes and r.returncode != worst:
            print('hipair-verify --list %s: exit %d, the verdicts say %d' % (listing, r.returncode, worst), flush=True)
            self.findings += 1
        os.remove(listing)


def judged_certificate(verify, path, model, cert, label, truth, statement, alterations, counts, unproven_claims=False):
    """counts one produced certificate (true by the oracle, its statement restated alike) and queues
    every alteration of it on `verify` (a BatchVerifier), judged at its flush by verdict_problems;
    prints each finding (prefixed with label) and, with ALTERATIONS_VERBOSE set, every verdict;
    returns the number of findings found now (those of the alterations are added to
    verify.findings at the flush)"""
    findings = 0
    counts['base'] += 1
    if truth(cert) is not True:
        print('%s: the produced certificate is not true by the oracle (%s)' % (label, truth(cert)))
        findings += 1
    if statement(cert) != cert['statement']:
        print('%s: the oracle restates %r as %r' % (label, cert['statement'], statement(cert)))
        findings += 1
    for what, altered in alterations(cert):
        true = truth(altered)

        def then(code, text, what=what, true=true):
            problems = verdict_problems(code, text, true, counts, unproven_claims)
            if os.environ.get('ALTERATIONS_VERBOSE'):
                print('  %s: %s -> exit %d %s' % (what, true, code, text[:150]))
            if problems:
                verify.findings += 1
                print('%s %s: %s: %s' % (label, what, problems, text[:200]), flush=True)
            return bool(problems)
        verify.add(path[:-len('.json')] if path.endswith('.json') else path, model, altered, then)
    return findings
