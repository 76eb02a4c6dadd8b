// The doubles around a rational whose numerator and denominator fit 53 bits, by one division
// and one fma instead of GMP's mpq_get_d (a long division of limbs and a normalisation) and an
// exact comparison of the rational with the double (docs/performance.md, session 32).
//
// Why it is exact. Let q = n / d with integers 0 < |n| < 2^53, 0 < d < 2^53 (both exact
// doubles) and h = fl(n / d), the division's result in the current rounding mode: h is one of
// the two doubles around q (IEEE division is correctly rounded in every mode), so
// |q - h| < ulp(h), and h is normal (2^-53 < |q| < 2^53). Then
//   - |h| <= 2^53, and |h| = 2^53 only when d = 1 and h = n (q is exact): otherwise |q| < 2^52
//     and ulp(h) <= 1, so n (an integer) and h d (h a multiple of ulp(h), d an integer) are
//     multiples of ulp(h), and so is n - h d;
//   - |n - h d| = d |q - h| < d ulp(h) < 2^53 ulp(h).
// So n - h d is a multiple of ulp(h) >= 2^-105 below 2^53 of them: a double, which
// fma(h, d, -n) returns exactly (one rounding of an exact double changes nothing; no
// underflow). Its sign is the sign of h - q (d > 0): zero when q = h, positive when h lies above
// q, negative below. The largest double <= q and the smallest >= q follow with one step of the
// representation (kernels' up/down, std::nextafter's value on finite non-zero doubles). Nothing
// depends on the rounding mode; the bounds are the ones lower_double / upper_double and
// kernels::Interval::enclose compute through GMP, bit for bit (tests/unit/near_quotient_test.cpp
// checks both on generated rationals).
#pragma once

#include "kernels/interval.hpp"

#include <gmp.h>
#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <utility>

namespace hipair::cspace::algebra {

namespace near_quotient_detail {
static_assert(GMP_LIMB_BITS == 64, "the fast case reads one 64-bit limb");
inline constexpr mp_limb_t two_53 = mp_limb_t{1} << 53;
}  // namespace near_quotient_detail

/// The doubles around num / den, when 0 < den < 2^53 and |num| < 2^53: true, and `lower` the
/// largest double <= num / den, `upper` the smallest double >= num / den (equal when the
/// quotient is a double; both 0 when num = 0). False, and nothing written, otherwise (the caller
/// takes the GMP path).
inline bool enclose_rational(mpz_srcptr num, mpz_srcptr den, double& lower, double& upper) {
  using near_quotient_detail::two_53;
  if (den->_mp_size != 1 || den->_mp_d[0] >= two_53) return false;
  const int num_size = num->_mp_size;
  if (num_size == 0) {
    lower = upper = 0.0;
    return true;
  }
  if (num_size > 1 || num_size < -1 || num->_mp_d[0] >= two_53) return false;
  const auto magnitude = static_cast<std::int64_t>(num->_mp_d[0]);
  const double n = static_cast<double>(num_size > 0 ? magnitude : -magnitude);   // exact
  const double d = static_cast<double>(static_cast<std::int64_t>(den->_mp_d[0]));   // exact
  const double h = n / d;
  const double excess = std::fma(h, d, -n);   // h d - n, exact: its sign is that of h - q
  lower = excess > 0 ? kernels::interval_detail::down(h) : h;
  upper = excess < 0 ? kernels::interval_detail::up(h) : h;
  return true;
}

/// enclose_rational of a rational's numerator and denominator.
inline bool enclose_rational(const mpq_class& q, double& lower, double& upper) {
  return enclose_rational(q.get_num_mpz_t(), q.get_den_mpz_t(), lower, upper);
}

/// kernels::Interval::enclose(q), bit for bit: the truncation toward zero (mpq_get_d) and the
/// next double away from zero, through enclose_rational where it applies. For q > 0 the
/// truncation is the largest double <= q, for q < 0 the smallest >= q.
inline kernels::Interval enclose_kernel(const mpq_class& q) {
  double lower, upper;
  if (!enclose_rational(q, lower, upper)) return kernels::Interval::enclose(q);
  if (upper > 0) return kernels::Interval(lower, kernels::interval_detail::up(lower));   // q > 0: lower > 0
  if (lower < 0) return kernels::Interval(kernels::interval_detail::down(upper), upper);
  return kernels::Interval(0.0, 0.0);
}

}  // namespace hipair::cspace::algebra
