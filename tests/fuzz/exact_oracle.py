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


def judged(verify, path, model, certificate, true, counts, unproven_claims=False):
    """writes the certificate to `path`, runs hipair-verify on it and counts its verdict against the
    truth (True, False or None: undecided) in `counts`; returns (problems, exit code, output): a
    false certificate accepted, or an exit other than 0/1/3 or more than one line, is a problem;
    with unproven_claims (a no_jam certificate, whose 'unproven', exit 3, still asserts checks 1-6:
    the named sides apart over every leaf, false when the oracle's channel closes) exit 3 too"""
    json.dump(certificate, open(path, 'w'))
    r = subprocess.run([verify, path, model], capture_output=True, text=True, timeout=120)
    text = (r.stdout + r.stderr).strip()
    problems = []
    if r.returncode not in (0, 1, 3) or len(text.splitlines()) != 1:
        problems.append('exit %d, %d lines' % (r.returncode, len(text.splitlines())))
    if true is None:
        counts['undecided'] += 1
    elif r.returncode == 0 and not true:
        problems.append('a FALSE certificate accepted')
    elif r.returncode == 3 and not true and unproven_claims:
        problems.append("a FALSE certificate's checks 1-6 passed (unproven)")
    elif r.returncode != 0 and true:
        counts['true rejected'] += 1
    elif true:
        counts['true accepted'] += 1
    else:
        counts['false rejected'] += 1
    return problems, r.returncode, text


def judged_certificate(verify, path, model, cert, label, truth, statement, alterations, counts, unproven_claims=False):
    """counts one produced certificate (true by the oracle, its statement restated alike) and every
    alteration of it judged by judged(); prints each finding (prefixed with label) and, with
    ALTERATIONS_VERBOSE set, every verdict; returns the number of findings"""
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
        problems, code, text = judged(verify, path, model, altered, true, counts, unproven_claims)
        if os.environ.get('ALTERATIONS_VERBOSE'):
            print('  %s: %s -> exit %d %s' % (what, true, code, text[:150]))
        if problems:
            findings += 1
            print('%s %s: %s: %s' % (label, what, problems, text[:200]), flush=True)
    return findings
