// An oracle of correctly rounded figures for the tests (issue 13, sessions 63-64), independent of
// MPFR/MPFI: round to nearest even on an exact rational in integers (the IEEE double grid, the
// subnormal spacing 2^-1074 and overflow included), atan by its alternating series (any
// argument, through atan x = pi/4 + atan((x - 1)/(x + 1)) and pi/2 - atan(1/x)) and pi between
// two 60-digit decimals. A bracket of a value is decided only when both of its ends round to
// the same double.
#pragma once

#include <hipair/rational.hpp>

#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

namespace hipair::test::rounding {

inline Rational power_of_two(long e) {
  Rational r(1);
  if (e >= 0)
    mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else
    mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  return r;
}

// floor(log2 q), q > 0
inline long floor_log2(const Rational& q) {
  long e = static_cast<long>(mpz_sizeinbase(q.get_num_mpz_t(), 2)) - static_cast<long>(mpz_sizeinbase(q.get_den_mpz_t(), 2));
  while (q < power_of_two(e)) --e;
  while (q >= power_of_two(e + 1)) ++e;
  return e;
}

// q rounded to the IEEE double grid (53 bits, subnormal spacing 2^-1074), ties to even, overflow
// to infinity; a zero keeps q's sign.
inline double oracle_round(const Rational& value) {
  const int sign = sgn(value);
  if (sign == 0) return 0.0;
  const Rational q = abs(value);
  const long e = std::max(floor_log2(q) - 52, -1074L);
  const Rational m = q / power_of_two(e);   // in [2^52, 2^53), or below on the subnormal grid
  mpz_class n = m.get_num() / m.get_den();
  const Rational fraction = m - Rational(n);
  if (fraction > Rational(1, 2) || (fraction == Rational(1, 2) && mpz_odd_p(n.get_mpz_t()))) n += 1;
  double d = 0;
  if (n == 0)
    d = 0.0;
  else if (e + static_cast<long>(mpz_sizeinbase(n.get_mpz_t(), 2)) > 1024)
    d = std::numeric_limits<double>::infinity();
  else
    d = std::ldexp(n.get_d(), static_cast<int>(e));   // n < 2^54: exact
  return sign < 0 ? -d : d;
}

inline bool same_double(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// pi between two rationals 10^-60 apart
inline const Rational& pi_lower() {
  static const Rational r("3141592653589793238462643383279502884197169399375105820974944/1000000000000000000000000000000000000000000000000000000000000");
  return r;
}
inline const Rational& pi_upper() {
  static const Rational r(pi_lower() + Rational(1, mpz_class("1000000000000000000000000000000000000000000000000000000000000")));
  return r;
}

// atan(x) between two rationals: for 0 < x <= 1/2 two partial sums of its alternating series
// (relative width below 2^-200); elsewhere by oddness, pi/4 + atan((x - 1)/(x + 1)) for
// 1/2 < x <= 2 and pi/2 - atan(1/x) above (the pi bracket adds 10^-60).
inline std::pair<Rational, Rational> atan_bracket(const Rational& x) {
  if (sgn(x) == 0) return {Rational(0), Rational(0)};
  if (sgn(x) < 0) {
    const auto [lo, hi] = atan_bracket(Rational(-x));
    return {Rational(-hi), Rational(-lo)};
  }
  if (x > 2) {
    const auto [lo, hi] = atan_bracket(Rational(1 / x));
    return {Rational(pi_lower() / 2 - hi), Rational(pi_upper() / 2 - lo)};
  }
  if (x > Rational(1, 2)) {
    const auto [lo, hi] = atan_bracket(Rational((x - 1) / (x + 1)));
    return {Rational(pi_lower() / 4 + lo), Rational(pi_upper() / 4 + hi)};
  }
  Rational sum = 0, power = x, term;
  const Rational x2 = x * x;
  for (long k = 0;; ++k) {
    term = power / (2 * k + 1);
    const Rational before = sum;
    sum += (k % 2 == 0) ? term : Rational(-term);
    if (term < x * power_of_two(-200)) return sum < before ? std::pair{sum, before} : std::pair{before, sum};
    power *= x2;
  }
}

// The expected degrees 360 atan(x) / pi of a half-angle tangent x in [xlo, xhi] (any signs,
// xlo <= xhi): the rounding of both ends of the bracket; nullopt when they differ.
inline std::optional<double> expected_degrees(const Rational& xlo, const Rational& xhi) {
  const Rational alo = atan_bracket(xlo).first, ahi = atan_bracket(xhi).second;
  const Rational lo = 360 * alo / (sgn(alo) >= 0 ? pi_upper() : pi_lower());
  const Rational hi = 360 * ahi / (sgn(ahi) >= 0 ? pi_lower() : pi_upper());
  const double a = oracle_round(lo), b = oracle_round(hi);
  if (!same_double(a, b)) return std::nullopt;
  if (a == 0) return sgn(xlo) < 0 ? -0.0 : 0.0;
  return a;
}

}  // namespace hipair::test::rounding
