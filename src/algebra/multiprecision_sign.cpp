// Session 40 (scale40): the multi-precision interval filter of sign_at(Polynomial, Real).
#include "algebra/multiprecision_sign.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cstddef>
#include <utility>

namespace hipair::cspace::algebra {

namespace {

// An MPFR number owned for the scope.
struct Mp {
  mpfr_t v;
  explicit Mp(long bits) { mpfr_init2(v, static_cast<mpfr_prec_t>(bits)); }
  ~Mp() { mpfr_clear(v); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  void widen(long bits) { mpfr_prec_round(v, static_cast<mpfr_prec_t>(bits), MPFR_RNDN); }  // exact when growing
};

// The working numbers of one evaluation, at one precision.
struct Scratch {
  Mp lo, hi, t1, t2, t3, t4;
  explicit Scratch(long bits) : lo(bits), hi(bits), t1(bits), t2(bits), t3(bits), t4(bits) {}
  void widen(long bits) {
    for (Mp* m : {&lo, &hi, &t1, &t2, &t3, &t4}) mpfr_set_prec(m->v, static_cast<mpfr_prec_t>(bits));
  }
};

// -1 / +1 when the enclosure [lo, hi] excludes zero, 0 when it does not.
int enclosure_sign(const Scratch& s) {
  if (mpfr_sgn(s.lo.v) > 0) return 1;
  if (mpfr_sgn(s.hi.v) < 0) return -1;
  return 0;
}

// [s.lo, s.hi] encloses p(x) at the MPFR number x (Horner, each bound rounded outwards).
void enclose_at_point(const Polynomial& p, mpfr_srcptr x, Scratch& s) {
  mpfr_set_z(s.lo.v, p.back().get_mpz_t(), MPFR_RNDD);
  mpfr_set_z(s.hi.v, p.back().get_mpz_t(), MPFR_RNDU);
  const bool negative = mpfr_sgn(x) < 0;
  for (std::size_t k = p.size() - 1; k-- > 0;) {
    // v in [lo, hi]: v x in [lo x, hi x] when x >= 0, [hi x, lo x] when x < 0
    mpfr_mul(s.t1.v, negative ? s.hi.v : s.lo.v, x, MPFR_RNDD);
    mpfr_mul(s.t2.v, negative ? s.lo.v : s.hi.v, x, MPFR_RNDU);
    mpfr_add_z(s.lo.v, s.t1.v, p[k].get_mpz_t(), MPFR_RNDD);
    mpfr_add_z(s.hi.v, s.t2.v, p[k].get_mpz_t(), MPFR_RNDU);
  }
}

// out = the least (rounding down) or the greatest (rounding up) of the four end products of
// [lo, hi] [a, b], each rounded that way; t is scratch.
void extreme_product(mpfr_ptr out, mpfr_ptr t, mpfr_srcptr lo, mpfr_srcptr hi, mpfr_srcptr a, mpfr_srcptr b,
                     mpfr_rnd_t rounding) {
  const bool least = rounding == MPFR_RNDD;
  mpfr_mul(out, lo, a, rounding);
  for (auto [x, y] : {std::pair{lo, b}, std::pair{hi, a}, std::pair{hi, b}}) {
    mpfr_mul(t, x, y, rounding);
    if (least ? mpfr_less_p(t, out) : mpfr_greater_p(t, out)) mpfr_swap(out, t);
  }
}

// [s.lo, s.hi] encloses p over [a, b] (a <= b; interval Horner, each bound rounded outwards).
void enclose_over(const Polynomial& p, mpfr_srcptr a, mpfr_srcptr b, Scratch& s) {
  mpfr_set_z(s.lo.v, p.back().get_mpz_t(), MPFR_RNDD);
  mpfr_set_z(s.hi.v, p.back().get_mpz_t(), MPFR_RNDU);
  for (std::size_t k = p.size() - 1; k-- > 0;) {
    extreme_product(s.t1.v, s.t2.v, s.lo.v, s.hi.v, a, b, MPFR_RNDD);
    extreme_product(s.t3.v, s.t4.v, s.lo.v, s.hi.v, a, b, MPFR_RNDU);
    mpfr_add_z(s.lo.v, s.t1.v, p[k].get_mpz_t(), MPFR_RNDD);
    mpfr_add_z(s.hi.v, s.t3.v, p[k].get_mpz_t(), MPFR_RNDU);
  }
}

long coefficient_bits(const Polynomial& p) {
  std::size_t bits = 0;
  for (const mpz_class& c : p) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  return static_cast<long>(bits);
}

Rational to_rational(mpfr_srcptr v) {
  mpz_class mantissa;
  const mpfr_exp_t e = mpfr_get_z_2exp(mantissa.get_mpz_t(), v);
  Rational r(mantissa);
  if (e > 0) mpz_mul_2exp(r.get_num_mpz_t(), r.get_num_mpz_t(), static_cast<mp_bitcnt_t>(e));
  if (e < 0) mpz_mul_2exp(r.get_den_mpz_t(), r.get_den_mpz_t(), static_cast<mp_bitcnt_t>(-e));
  r.canonicalize();
  return r;
}

}  // namespace

MultiprecisionEnclosure multiprecision_enclosure_over(const Polynomial& p, const Rational& a, const Rational& b, long bits) {
  Scratch s(bits);
  Mp lo(bits), hi(bits);
  mpfr_set_q(lo.v, a.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(hi.v, b.get_mpq_t(), MPFR_RNDU);
  enclose_over(p, lo.v, hi.v, s);
  return {a, to_rational(s.lo.v), to_rational(s.hi.v)};
}

MultiprecisionEnclosure multiprecision_enclosure_at_point(const Polynomial& p, const Rational& x, long bits) {
  Scratch s(bits);
  Mp point(bits);
  mpfr_set_q(point.v, x.get_mpq_t(), MPFR_RNDN);
  enclose_at_point(p, point.v, s);
  return {to_rational(point.v), to_rational(s.lo.v), to_rational(s.hi.v)};
}

MultiprecisionBits multiprecision_sign_bits(const Polynomial& p, const Real& u) {
  const long bits = std::max(coefficient_bits(p), coefficient_bits(u.polynomial));
  // rounding errors are relative to the terms: a start of 192 bits decides values down to about
  // 10^-40 of their terms; the cap allows cancellation well beyond the coefficients' width
  return {bits, 192, std::max(4 * bits + 512, 1024L)};
}

std::optional<int> multiprecision_sign(const Polynomial& p, const Real& u, long start_bits, long max_bits) {
  if (p.empty() || u.exact || u.polynomial.size() < 2) return std::nullopt;
  if (p.size() == 1) return sgn(p[0]);
  const Polynomial& q = u.polynomial;
  long bits = start_bits;
  Scratch s(bits);
  // [a, b] encloses the bracket (left, right) holding u: an end is u's rational end (enclosed
  // outwards) until a midpoint replaces it
  Mp a(bits), b(bits), m(bits);
  mpfr_set_q(a.v, u.lower.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(b.v, u.upper.get_mpq_t(), MPFR_RNDU);
  bool left_rational = true, right_rational = true;
  int low_sign = 0;   // q's sign at u.lower, when the first halving needs it
  for (;;) {
    for (;;) {
      enclose_over(p, a.v, b.v, s);
      if (const int sign = enclosure_sign(s)) return sign;
      if (low_sign == 0) {
        // non-zero, the opposite of q's sign at u.upper: the sign of q over the enclosure of
        // u.lower when it excludes zero, exactly otherwise
        mpfr_set_q(m.v, u.lower.get_mpq_t(), MPFR_RNDU);
        enclose_over(q, a.v, m.v, s);
        low_sign = enclosure_sign(s);
        if (low_sign == 0) low_sign = sign_at(q, u.lower);
      }
      // halve the bracket 16 times (as far as this precision allows), then enclose p again
      int halvings = 0;
      for (; halvings < 16; ++halvings) {
        mpfr_add(m.v, a.v, b.v, MPFR_RNDN);
        mpfr_div_2ui(m.v, m.v, 1, MPFR_RNDN);
        const bool inside = (left_rational ? mpfr_cmp_q(m.v, u.lower.get_mpq_t()) > 0 : mpfr_cmp(m.v, a.v) > 0) &&
                            (right_rational ? mpfr_cmp_q(m.v, u.upper.get_mpq_t()) < 0 : mpfr_cmp(m.v, b.v) < 0);
        if (!inside) break;
        enclose_at_point(q, m.v, s);
        const int sign = enclosure_sign(s);
        if (sign == 0) break;   // m at (or too near) u: a point sign this precision cannot give
        if (sign == low_sign) {
          mpfr_set(a.v, m.v, MPFR_RNDN);   // exact: same precision
          left_rational = false;
        } else {
          mpfr_set(b.v, m.v, MPFR_RNDN);
          right_rational = false;
        }
      }
      if (halvings < 16) break;   // this precision's floor: enclose once more, then widen
    }
    enclose_over(p, a.v, b.v, s);
    if (const int sign = enclosure_sign(s)) return sign;
    if (2 * bits > max_bits) return std::nullopt;
    bits *= 2;
    // a rational end enclosed afresh at the new precision (u's interval may be far narrower than
    // the old precision's ulp); a midpoint is kept exactly
    a.widen(bits);
    b.widen(bits);
    if (left_rational) mpfr_set_q(a.v, u.lower.get_mpq_t(), MPFR_RNDD);
    if (right_rational) mpfr_set_q(b.v, u.upper.get_mpq_t(), MPFR_RNDU);
    mpfr_set_prec(m.v, static_cast<mpfr_prec_t>(bits));
    s.widen(bits);
  }
}

}  // namespace hipair::cspace::algebra
