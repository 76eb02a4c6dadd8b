// Exact rational directions from angles, through rational half-angle tangents.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>

#include <string>
#include <vector>

namespace hipair::model_detail {

/// Precision of every rounding the reader performs: values are rounded to the nearest
/// multiple of 10^-12 (mm, rad or unitless).
inline constexpr int rounding_decimals = 12;

/// Rounds a 256-bit value given as decimal text (or an MPFR value via the overload in the
/// .cpp) to the nearest multiple of 10^-12. Internal helper.
Rational round_to_grid(const Rational& value);

/// The simplest rational (smallest denominator) in the closed interval [lo, hi], lo <= hi.
Rational simplest_rational_between(const Rational& lo, const Rational& hi);

/// Rounds a half-angle tangent for an exact unit vector: the simplest rational within half a
/// grid step (5*10^-13) of `tangent`. Same error bound as the grid, but about half the digits
/// (continued-fraction convergents), which keeps every exact computation downstream small.
Rational round_half_tangent(const Rational& tangent);

/// An exact rational unit vector (cos a, sin a) for the angle `angle` (rad), built from the
/// half-angle tangent t = tan(a/2) (or of a - pi when |a| > pi/2, then negated), with t
/// rounded to a multiple of 10^-12 when it is not rational. When rounding happens, a Rounding
/// with the resulting angle error bound is appended to `roundings` under `pointer`.
/// Exact cases: angles that are integer multiples of pi/2 (given exactly as rationals only
/// when 0) — in practice only a = 0 is rational among them.
Point exact_unit_vector(const Rational& angle, const std::string& pointer,
                        const std::string& expression, std::vector<Rounding>& roundings);

/// Exact unit vector for an angle that is a rational multiple of pi: a = pi * turns_of_pi.
/// Multiples of pi/2 are exact with no rounding; others go through the half-angle tangent.
Point exact_unit_vector_pi(const Rational& multiple_of_pi, const std::string& pointer,
                           const std::string& expression, std::vector<Rounding>& roundings);

/// Exact point on the circle (center, radius) in direction `unit` (an exact unit vector).
inline Point point_on_circle(const Point& center, const Rational& radius, const Point& unit) {
  return Point{center.x + radius * unit.x, center.y + radius * unit.y};
}

/// Unit vector from a rational half-angle tangent t: ((1-t^2)/(1+t^2), 2t/(1+t^2)).
inline Point unit_from_half_tangent(const Rational& t) {
  Rational w = 1 + t * t;
  return Point{Rational((1 - t * t) / w), Rational(2 * t / w)};
}

}  // namespace hipair::model_detail
