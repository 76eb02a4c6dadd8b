// Exact construction helpers shared by the feature templates: rational rotations, exact
// points on circles near irrational intersections, and a loop builder that checks every arc
// endpoint exactly. Internal to src/model/templates*.cpp.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <string>
#include <vector>

namespace hipair::model_detail::template_geometry {

/// a + b.
Point add(const Point& a, const Point& b);
/// a - b.
Point subtract(const Point& a, const Point& b);
/// k * a.
Point scale(const Rational& k, const Point& a);
/// Rotates `p` about the origin by the exact rational unit vector `unit` (complex product).
Point rotate(const Point& p, const Point& unit);
/// Mirror image in the x axis: (x, -y).
Point mirror(const Point& p);
/// Rotation by +90 degrees: (-y, x).
Point perpendicular(const Point& p);
/// |a - b|^2, exact.
Rational squared_distance(const Point& a, const Point& b);
/// |a|^2, exact.
Rational squared_norm(const Point& a);

/// sqrt(q) for q >= 0 to within 10^-30 (truncated), and to 30 significant digits when
/// sqrt(q) < 1 (parts drawn at 10^-300 mm), as a rational. For constructions whose results are
/// rounded afterwards (round_simplest, point_on_circle_near); never for decisions. q is a squared
/// length: under a template's unit U != 1 (LengthScaleScope) the root is U sqrt(q / U^2), taken
/// as above (exactly covariant with a template scaled by a power of ten).
Rational approximate_sqrt(const Rational& q);
/// A rational >= sqrt(q), within 10^-15 of it (and within 10^-15 of it relatively when
/// sqrt(q) < 1): for error bounds (q a squared length, in units of U as approximate_sqrt).
Rational upper_sqrt(const Rational& q);
/// Nearest double of a dimensionless value or an angle, as a plain number for constructions and
/// coarse validity messages.
double approximate(const Rational& q);

/// A template's unit of length U: 1 (mm) for templates whose largest length argument lies in
/// [2^-20, 2^40] mm, else the power of ten 10^E (E a multiple of 10) that brings that largest
/// length within [1e-4, 1e6) (core/model_scale.hpp decimal_unit_exponent; until session 53 the
/// largest length itself), so that a part drawn at 10^-300 or
/// 10^400 mm is constructed as at unit size: lengths in doubles are taken in units of U (squares
/// of 10^-300 are 0 in double, 10^400 is infinite), and lengths are rounded relative to U
/// (round_length), which keeps the construction exactly covariant with the part's scale and the
/// rationals as small as at 1 mm. Set by expand_template for the template's expansion.
class LengthScaleScope {
 public:
  /// The unit for a template whose largest length argument is `largest` (> 0; 0: none).
  explicit LengthScaleScope(const Rational& largest);
  ~LengthScaleScope();
  LengthScaleScope(const LengthScaleScope&) = delete;
  LengthScaleScope& operator=(const LengthScaleScope&) = delete;

 private:
  Rational previous_;
};

/// The template's unit of length U (1 outside expand_template).
const Rational& length_unit();

/// A constructed length rounded to a rational: the simplest within half the rounding bound b of
/// `length` (round_simplest) when U = 1, else U times the simplest within b/2 of length / U (a
/// bound of b U mm).
Rational round_length(const Rational& length);
/// The bound of round_length, mm.
Rational length_rounding_bound();

/// The nearest double of length / U.
double approximate_length(const Rational& length);
/// The nearest double of a squared length / U^2.
double approximate_squared_length(const Rational& squared_length);
/// The exact length of a double in units of U: Rational(value) * U.
Rational length_from(double value);

/// An exact rational point on the circle of radius `radius` about `center` whose polar angle
/// is within the rounding bound b (rad) of the polar angle of `near` (a point on or very near
/// that circle, typically an irrational intersection computed to ~10^-30). Built from the
/// half-angle tangent (round_half_tangent); records a Rounding (pointer, `what`) with the bound
/// b * radius (mm) on the displacement from the ideal point.
Point point_on_circle_near(const Point& center, const Rational& radius, const Point& near,
                           const std::string& pointer, const std::string& what,
                           std::vector<Rounding>& roundings);

/// Intersections of the circle (origin, r0) with the circle (c1, r1), approximately
/// (to ~10^-25), or false when they do not meet. `first` is on the left of the line from the
/// origin to c1, `second` on the right.
bool circle_intersections(const Rational& r0, const Point& c1, const Rational& r1, Point& first,
                          Point& second);

/// Builds one loop edge by edge; each arc's endpoints are checked to be exactly equidistant
/// from its centre (an internal error otherwise: the template code is wrong).
class LoopBuilder {
 public:
  LoopBuilder(const Point& start, std::string pointer);
  void line_to(const Point& target, const std::string& label);
  void arc_to(const Point& target, const Point& center, bool ccw, const std::string& label);
  /// Full circle loop.
  static Loop circle(const Point& center, const Rational& radius, const std::string& label,
                     const std::string& pointer);
  /// The loop; its last edge must end at the start. \throws GeometryError otherwise.
  Loop finish();
  const Point& current() const { return current_; }

 private:
  Loop loop_;
  Point start_;
  Point current_;
  std::string pointer_;
};

}  // namespace hipair::model_detail::template_geometry
