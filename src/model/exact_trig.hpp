// Exact rational directions from angles, through rational half-angle tangents.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>

#include <string>
#include <vector>

namespace hipair::model_detail {

/// The rounding bound b of every rounding the reader performs (docs/model-format.md
/// "Exactness and rounding"): a value that cannot be exact is replaced by the simplest rational
/// (smallest denominator) within b of it (mm, rad or unitless). The model's `"rounding"` key
/// chooses it, a command line's `--rounding` overrides that; 10^-12 by default.
Rational default_rounding_bound();

/// The bound in force on this thread: the innermost RoundingBoundScope's, else the default.
const Rational& rounding_bound();
/// True when the innermost RoundingBoundScope overrides the model's own "rounding" key.
bool rounding_bound_overrides_model();

/// Sets the thread's rounding bound for its lifetime (the reader, the parametric model, a
/// command's `--rounding` with `overrides_model`), and restores the previous one when it ends.
/// \pre bound > 0.
class RoundingBoundScope {
 public:
  explicit RoundingBoundScope(const Rational& bound, bool overrides_model = false);
  ~RoundingBoundScope();
  RoundingBoundScope(const RoundingBoundScope&) = delete;
  RoundingBoundScope& operator=(const RoundingBoundScope&) = delete;

 private:
  RoundingBoundScope* previous_;
  Rational bound_;
  bool overrides_model_;
  friend const Rational& rounding_bound();
  friend bool rounding_bound_overrides_model();
};

/// The smallest and the largest rounding bound a model may ask for: 1e-30 (far above the
/// 256-bit evaluations' error) and 1e-3 (already coarse geometry).
Rational smallest_rounding_bound();
Rational largest_rounding_bound();

/// The simplest rational within half the rounding bound of `value` (for values known to far
/// better than b/2, such as 10^-30 square roots: the result is then within b of the exact one).
Rational round_simplest(const Rational& value);

/// The simplest rational (smallest denominator, and among those the smallest numerator in
/// magnitude) in the closed interval [lo, hi], lo <= hi: the continued-fraction (Stern–Brocot)
/// descent. Exact: the result lies in [lo, hi] and no rational with a smaller denominator does.
Rational simplest_rational_between(const Rational& lo, const Rational& hi);

/// Rounds a half-angle tangent for an exact unit vector: the simplest rational within half the
/// rounding bound of `tangent` (so the angle moves by at most the bound, |dθ/dt| <= 2): small
/// denominators p/q give unit vectors ((q²−p²), 2pq)/(q²+p²) with small coefficients.
Rational round_half_tangent(const Rational& tangent);

/// An exact rational unit vector (cos a, sin a) for the angle `angle` (rad), built from the
/// half-angle tangent t = tan(a/2) (or of a - pi when |a| > pi/2, then negated), with t
/// rounded (round_half_tangent) when it is not rational. When rounding happens, a Rounding
/// with the resulting angle error bound is appended to `roundings` under `pointer`.
/// Exact cases: angles that are integer multiples of pi/2 (given exactly as rationals only
/// when 0) — in practice only a = 0 is rational among them.
Point exact_unit_vector(const Rational& angle, const std::string& pointer,
                        const std::string& expression, std::vector<Rounding>& roundings);

/// Exact unit vector for an angle that is a rational multiple of pi: a = pi * turns_of_pi.
/// Multiples of pi/2 are exact with no rounding; others go through the half-angle tangent.
Point exact_unit_vector_pi(const Rational& multiple_of_pi, const std::string& pointer,
                           const std::string& expression, std::vector<Rounding>& roundings);

/// Exact unit vector for the angle phase + pi * multiple_of_pi with ONE rounding: the half-angle
/// tangent of the whole angle is rounded (within the bound b, recorded under `pointer`), so the
/// direction is within b of the exact angle and its coordinates have the size of one rounded
/// tangent, where rotating by exact_unit_vector(phase) after exact_unit_vector_pi(multiple)
/// would make two roundings (2b) and square the denominators. Exact without a rounding when
/// phase is 0 and the multiple is one of pi/2 (exact_unit_vector_pi). A phase whose own
/// direction is exact (a quarter turn) turns the rounded u(pi multiple) exactly instead (also
/// one rounding; the rationals of the former two-step construction).
Point exact_unit_vector_sum(const Rational& phase, const Rational& multiple_of_pi, const std::string& pointer,
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
