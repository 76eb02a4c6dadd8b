#include "algebra/nearest_double.hpp"

#include "core/mp_values.hpp"

#include <mpfi.h>
#include <mpfr.h>

#include <cmath>
#include <limits>
#include <utility>

namespace hipair::cspace::algebra {
namespace {

using Mpfr = MpfrValue;
using Mpfi = MpfiValue;

// A zero result with the exact value's sign (the rounding of a number below the least subnormal).
double signed_result(double rounded, int sign) {
  if (rounded != 0) return rounded;
  return sign < 0 ? -0.0 : 0.0;
}

// The doubles nearest the two ends of an MPFI enclosure (mpfr_get_d rounds correctly, the
// subnormal range and overflow included).
std::pair<double, double> nearest_ends(const mpfi_t x, mpfr_prec_t precision) {
  Mpfr end(precision);
  mpfi_get_left(end.v, x);
  const double a = mpfr_get_d(end.v, MPFR_RNDN);
  mpfi_get_right(end.v, x);
  return {a, mpfr_get_d(end.v, MPFR_RNDN)};
}

// A double as an exact rational; the infinities as +-2^1024 (the end of the last rounding cell).
Rational exact_double(double d) {
  if (std::isinf(d)) {
    Rational r(mpz_class(1) << 1024);
    return d < 0 ? Rational(-r) : r;
  }
  Rational r;
  mpq_set_d(r.get_mpq_t(), d);
  return r;
}

// 360 atan(x) / pi over [lo, hi], rounded to doubles at both ends.
std::pair<double, double> degrees_ends(const Rational& lo, const Rational& hi, mpfr_prec_t precision) {
  Mpfi x(precision), pi(precision);
  if (lo == hi)
    mpfi_set_q(x.v, lo.get_mpq_t());
  else
    mpfi_interv_q(x.v, lo.get_mpq_t(), hi.get_mpq_t());
  mpfi_atan(x.v, x.v);
  mpfi_const_pi(pi.v);
  mpfi_div(x.v, x.v, pi.v);
  mpfi_mul_ui(x.v, x.v, 360);
  return nearest_ends(x.v, precision);
}

// The sign of r, exactly, and r's enclosure narrowed to that side of 0 (r not 0). An isolating
// interval that contains 0 while r is not 0 has a polynomial not vanishing at 0 (0 would be a
// second root in it), so 0 is a valid end.
int sign_apart_from_zero(Real& r) {
  if (r.exact) return sgn(r.lower);
  if (sgn(r.lower) >= 0) return 1;
  if (sgn(r.upper) <= 0) return -1;
  const int s = r.compare(Rational(0));
  if (s > 0) r.lower = 0;
  if (s < 0) r.upper = 0;
  return s;
}

// Narrows r by 2^-32 of its width (or makes it exact).
void narrow(Real& r) {
  Rational width = r.upper - r.lower;
  mpq_div_2exp(width.get_mpq_t(), width.get_mpq_t(), 32);
  r.refine_to(width);
}

// Rounds far beyond any enclosure the callers' numbers need (an isolating interval narrowed by
// 2^-32 per round and 32 more bits of precision): a guard, not a limit reached in practice.
constexpr int max_rounds = 4096;

}  // namespace

double nearest_double(const Rational& q) { return to_double(q); }

double nearest_double(const Real& value) {
  if (value.exact) return nearest_double(value.lower);
  Real r = value;
  const int sign = sign_apart_from_zero(r);
  if (sign == 0) return 0.0;
  for (int round = 0;; ++round) {
    if (r.exact) return nearest_double(r.lower);
    const double a = nearest_double(r.lower), b = nearest_double(r.upper);
    if (a == b) return signed_result(a, sign);
    if (std::nextafter(a, std::numeric_limits<double>::infinity()) == b || round == max_rounds) {
      // one rounding boundary between the ends: the tie of a and b, placed exactly
      Rational tie = exact_double(a) + exact_double(b);
      mpq_div_2exp(tie.get_mpq_t(), tie.get_mpq_t(), 1);
      const int side = r.compare(tie);
      if (side == 0) return nearest_double(tie);   // ties to even
      return signed_result(side < 0 ? a : b, sign);
    }
    narrow(r);
  }
}

double half_angle_degrees(const Rational& t) {
  const int sign = sgn(t);
  if (sign == 0) return 0.0;
  for (mpfr_prec_t precision = 64;; precision *= 2) {
    // 360 atan(t) / pi is not a tie: a rational angle in degrees whose half-angle tangent is a
    // rational is 0 or +-90 (Niven), and those are doubles
    const auto [a, b] = degrees_ends(t, t, precision);
    if (a == b) return signed_result(a, sign);
  }
}

double half_angle_degrees(const Real& t) {
  if (t.exact) return half_angle_degrees(t.lower);
  Real r = t;
  const int sign = sign_apart_from_zero(r);
  if (sign == 0) return 0.0;
  mpfr_prec_t precision = 64;
  for (int round = 0;; ++round) {
    if (r.exact) return half_angle_degrees(r.lower);
    const auto [a, b] = degrees_ends(r.lower, r.upper, precision);
    // (a degree value that is a tie would be a rational angle with an algebraic half-angle tangent
    // of a degree beyond any contact polynomial's: the guard ends the loop regardless)
    if (a == b || round == max_rounds) return signed_result(a, sign);
    narrow(r);
    precision += 32;
  }
}

}  // namespace hipair::cspace::algebra
