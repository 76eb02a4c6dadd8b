// The C-space builder's cost guard for charts of two rotating parts (internal; session 75).
//
// A chart's arrangement (CGAL's curve analysis, the quadratic traits' algebraic comparisons)
// costs about the square of its contact curves' coefficient bits per curve, and the builder's
// double filters (the culler's enclosures) stop excluding curves once coefficients pass the
// doubles' range: every curve then reaches the arrangement. Coefficient bits of two rotating
// parts do not grow with the model's scale (a contact equation is homogeneous in lengths, and
// the primitive polynomial is the same at any unit), only with how finely coordinates are
// written relative to one another: geneva-template.json has 457-bit curves; with the wheel's
// centre moved from y = 0 to 1e-100 mm 1 061 bits (5 s), 1e-200 1 726 (21 s), 1e-300 2 390,
// 1e-400 3 055 (over 282 s: hostile74 H1) and 1e-1000 7 041. Every bundled example stays below
// 460 bits (the spur gears' 365; the translating and 1-D pairs are not concerned: a banking pin
// centre written with 1 200 digits is a univariate problem, built in 0.2 s).
#pragma once

#include "algebra/polynomial.hpp"

#include <cstddef>

namespace hipair::cspace {

/// The largest coefficient bit length (of the primitive polynomial) a contact curve of a chart
/// whose axes are both angles may have for the chart to be built (about 1e-280 mm offsets among
/// 100 mm coordinates; 4.5 times the largest of the examples).
inline constexpr std::size_t max_rotation_curve_bits = 2048;

/// The bit length of the largest coefficient of f divided by the gcd of its coefficients
/// (within one: the quotient's bits are those of the coefficient less those of the gcd, or
/// one more), 0 for the zero polynomial.
std::size_t primitive_coefficient_bits(const IntegerPolynomial2& f);

}  // namespace hipair::cspace
