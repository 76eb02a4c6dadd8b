// HIPAIR — the correctly rounded double of an exact number, for every figure a report prints.
//
// Each function returns the double nearest the exact value (IEEE round to nearest, ties to
// even, subnormals and overflow to infinity included): the exact number is enclosed by outward
// MPFR/MPFI bounds (a real algebraic number's isolating interval refined as needed) until both
// ends of the enclosure round to the same double. A zero result carries the sign of the exact
// value (-0.0 for a negative number below the least subnormal); an exact 0 is +0.0.
// Real::approximate() (exact_real.hpp) is within one unit in the last place and is kept for the
// outputs that print it; these are for figures that must be right to the last digit whatever
// the scale (an angle's tangent of 10^-400, an interval that straddles 0).
#pragma once

#include "algebra/exact_real.hpp"

namespace hipair::cspace::algebra {

/// The double nearest the rational q (hipair::to_double, which is correctly rounded).
double nearest_double(const Rational& q);
/// The double nearest the real algebraic number r (refined on a copy).
double nearest_double(const Real& r);
/// The angle whose half-angle tangent is t, in degrees: 360 atan(t) / pi, correctly rounded.
double half_angle_degrees(const Rational& t);
/// The same for a real algebraic t (refined on a copy).
double half_angle_degrees(const Real& t);

}  // namespace hipair::cspace::algebra
