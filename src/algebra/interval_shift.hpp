// HIPAIR — the power of two by which an integer polynomial's certified double evaluation
// (IntervalPolynomial2) is scaled, so that its coefficients stay within the doubles' range.
//
// A contact curve's integer coefficients grow with the model's rationals: the escapement written
// at x 1 with its banking pins' centres as 300-digit decimals (960-bit numerators) has curves with
// 1 061-bit coefficients. Enclosed as they are, those are [DBL_MAX, inf]: every evaluation
// contains 0, so no curve was ever excluded near them and every point query of the pair answered
// "in contact (grazing)" at any configuration (session 55). A positive multiple of f has f's zero
// set and f's signs, so IntervalPolynomial2(f) made under ScaledEnclosures (the crossing queries'
// polynomials, cspace_queries.cpp) encloses f / 2^s instead, s = interval_shift(f):
// 0 while every coefficient has at most `interval_coefficient_bits` bits (every polynomial of
// ordinary size: enclosed exactly as before), else the largest bit length less that many, which
// leaves 2^123 of headroom below DBL_MAX for the sums of the Horner evaluation over the charts'
// boxes. Whoever combines the values of several polynomials (F with its partial derivatives in
// the mean-value form, F over an exact box, a Newton step F / F_y) must scale them alike: the
// partials by their own shift and then by 2^(their shift - F's) (scale_by_power_of_two).
#pragma once

#include "algebra/exact_real.hpp"

#include <gmpxx.h>

namespace hipair::cspace::algebra {

/// Whether IntervalPolynomial2's constructor scales by interval_shift on this thread: off unless
/// a ScaledEnclosures scope is open. (The C-space builder's filters — the curve culler, the label
/// filter, the arrangement's vertex certificates — keep their unscaled enclosures, unbounded for
/// coefficients beyond 2^1024: scaled, the rotation-translation pairs x 10^-400 of
/// CSpaceScale.RotationTranslationPairsBeyondTheDoublesLocateAsAtScaleOne located wrongly, the
/// culler's grid cells not nesting where their width underflows; docs/simulation.md, session 55.)
bool& interval_scaling();

/// Scaled enclosures while in scope.
class ScaledEnclosures {
 public:
  ScaledEnclosures() : was_(interval_scaling()) { interval_scaling() = true; }
  ~ScaledEnclosures() { interval_scaling() = was_; }
  ScaledEnclosures(const ScaledEnclosures&) = delete;
  ScaledEnclosures& operator=(const ScaledEnclosures&) = delete;

 private:
  bool was_;
};

/// Coefficients of at most this many bits are enclosed unscaled.
inline constexpr long interval_coefficient_bits = 900;

/// The exponent s >= 0 with which IntervalPolynomial2(f) encloses f / 2^s under ScaledEnclosures.
long interval_shift(const IntegerPolynomial2& f);

/// z / 2^shift enclosed outward in doubles: enclose(z) for shift 0. A quotient below the least
/// normal double in magnitude is enclosed by [0, DBL_MIN] (or [-DBL_MIN, 0]); one beyond the
/// doubles' range by [DBL_MAX, inf] (or [-inf, -DBL_MAX]).
Interval enclose_shifted(const mpz_class& z, long shift);

/// The double nearest below z / 2^shift in magnitude (z.get_d() for shift 0): z truncated toward
/// zero to 53 bits and scaled; NaN where the quotient is below the least normal double (it cannot
/// be carried with a relative error of one rounding: IntervalPolynomial2's double evaluation then
/// gives NaN, which its callers read as "not decided").
double nearest_shifted(const mpz_class& z, long shift);

/// The interval v * 2^exponent, outward: exact in the normal range, widened to 0 and the least
/// normal double where it underflows, to DBL_MAX where a finite bound overflows.
Interval scale_by_power_of_two(Interval v, long exponent);

}  // namespace hipair::cspace::algebra
