#include "model/template_geometry.hpp"

#include "core/model_scale.hpp"
#include "model/exact_trig.hpp"

#include <hipair/error.hpp>

namespace hipair::model_detail::template_geometry {
namespace {

mpz_class power_of_ten(unsigned exponent) {
  mpz_class result;
  mpz_ui_pow_ui(result.get_mpz_t(), 10, exponent);
  return result;
}

// floor(sqrt(q * 10^(2 digits))) as an integer.
mpz_class scaled_integer_sqrt(const Rational& q, unsigned digits) {
  mpz_class scale = power_of_ten(2 * digits);
  mpz_class numerator = q.get_num() * scale;
  mpz_class floor_value;
  mpz_fdiv_q(floor_value.get_mpz_t(), numerator.get_mpz_t(), q.get_den_mpz_t());
  mpz_class root;
  mpz_sqrt(root.get_mpz_t(), floor_value.get_mpz_t());
  return root;
}

// Decimal digits after the point: `absolute`, and for a tiny q (below about 2^-40, sqrt(q) below
// about 10^-6) enough more to keep `absolute` significant digits of sqrt(q) (about half of q's
// negative decimal exponent more; the size test is on the numbers' bit lengths, so it is exact).
unsigned digits_for(const Rational& q, unsigned absolute) {
  long bits = static_cast<long>(mpz_sizeinbase(q.get_den_mpz_t(), 2)) -
              static_cast<long>(mpz_sizeinbase(q.get_num_mpz_t(), 2));
  if (bits < 40) return absolute;
  return absolute + static_cast<unsigned>(bits * 0.30103 / 2) + 2;  // 10^-more <= sqrt(q) / 10
}

}  // namespace

Point add(const Point& a, const Point& b) { return Point{a.x + b.x, a.y + b.y}; }
Point subtract(const Point& a, const Point& b) { return Point{a.x - b.x, a.y - b.y}; }
Point scale(const Rational& k, const Point& a) { return Point{k * a.x, k * a.y}; }
Point rotate(const Point& p, const Point& unit) {
  return Point{p.x * unit.x - p.y * unit.y, p.x * unit.y + p.y * unit.x};
}
Point mirror(const Point& p) { return Point{p.x, -p.y}; }
Point perpendicular(const Point& p) { return Point{-p.y, p.x}; }
Rational squared_norm(const Point& a) { return a.x * a.x + a.y * a.y; }
Rational squared_distance(const Point& a, const Point& b) { return squared_norm(subtract(a, b)); }

namespace {
thread_local Rational length_scale(1);   // the template's unit of length (LengthScaleScope)
}  // namespace

// A squared length's root under a template's unit U != 1 is taken in units of U: U sqrt(q / U^2),
// as at 1 mm (session 53: 30 decimals of a 10^401 mm length were not 10^400 times those of a
// 11.5 mm one, and the escapement x 1e400 was another model than x 1's scaled).
Rational approximate_sqrt(const Rational& q) {
  if (q <= 0) return Rational(0);
  if (length_scale != 1) {
    const Rational unit = length_scale;
    length_scale = 1;
    Rational root = approximate_sqrt(Rational(q / (unit * unit)));
    length_scale = unit;
    return Rational(unit * root);
  }
  unsigned digits = digits_for(q, 30);
  Rational result(scaled_integer_sqrt(q, digits), power_of_ten(digits));
  result.canonicalize();
  return result;
}

Rational upper_sqrt(const Rational& q) {
  if (q <= 0) return Rational(0);
  if (length_scale != 1) {   // as approximate_sqrt: U upper_sqrt(q / U^2) >= sqrt(q)
    const Rational unit = length_scale;
    length_scale = 1;
    Rational root = upper_sqrt(Rational(q / (unit * unit)));
    length_scale = unit;
    return Rational(unit * root);
  }
  unsigned digits = digits_for(q, 15);
  Rational result(scaled_integer_sqrt(q, digits) + 1, power_of_ten(digits));
  result.canonicalize();
  return result;
}


double approximate(const Rational& q) { return q.get_d(); }

LengthScaleScope::LengthScaleScope(const Rational& largest) : previous_(length_scale) {
  static const Rational low(1, mpz_class(1) << 20), high(mpz_class(1) << 40);
  // a power of ten, 10^E with E a multiple of 10 (core/model_scale.hpp decimal_unit_exponent),
  // rather than `largest` itself (until session 53): a template scaled by 10^(10 j) from an
  // ordinary one is then constructed as that one, times 10^(10 j) exactly (the escapement x
  // 1e400's roundings were others, and its jam moved in the 12th digit)
  length_scale = largest > 0 && (largest < low || largest > high) ? power_of_ten_rational(decimal_unit_exponent(largest))
                                                                  : Rational(1);
}

LengthScaleScope::~LengthScaleScope() { length_scale = previous_; }

double approximate_length(const Rational& length) {
  if (length_scale == 1) return length.get_d();
  return Rational(length / length_scale).get_d();
}

double approximate_squared_length(const Rational& squared_length) {
  if (length_scale == 1) return squared_length.get_d();
  return Rational(squared_length / (length_scale * length_scale)).get_d();
}

Rational length_from(double value) { return Rational(Rational(value) * length_scale); }

const Rational& length_unit() { return length_scale; }

Rational round_length(const Rational& length) {
  if (length_scale == 1) return round_simplest(length);
  // as at 1 mm, in units of the template's unit (round_simplest's bound is at most rounding_bound())
  return Rational(length_scale * round_simplest(Rational(length / length_scale)));
}

Rational length_rounding_bound() { return Rational(rounding_bound() * length_scale); }

Point point_on_circle_near(const Point& center, const Rational& radius, const Point& near,
                           const std::string& pointer, const std::string& what,
                           std::vector<Rounding>& roundings) {
  Point relative = subtract(near, center);
  // Half-angle tangent of the polar angle: y / (r + x) away from the angle pi, and the
  // tangent of half the angle minus pi, -y / (r - x), near it (then the unit vector flips).
  bool flipped = relative.x < 0;
  Rational tangent = flipped ? Rational(-relative.y / (radius - relative.x))
                             : Rational(relative.y / (radius + relative.x));
  Rational rounded = round_half_tangent(tangent);
  Point unit = unit_from_half_tangent(rounded);
  if (flipped) unit = Point{-unit.x, -unit.y};
  // Moving t by at most b/2 turns the unit vector by at most b rad (the rounding bound b): the
  // point moves by at most radius * b.
  roundings.push_back(Rounding{pointer, what + " (exact point on its circle, half-angle tangent)",
                               rounded, Rational(radius * rounding_bound())});
  return point_on_circle(center, radius, unit);
}

bool circle_intersections(const Rational& r0, const Point& c1, const Rational& r1, Point& first,
                          Point& second) {
  Rational d2 = squared_norm(c1);
  if (d2 == 0) return false;
  Rational d = approximate_sqrt(d2);
  Rational along = (r0 * r0 - r1 * r1 + d2) / (2 * d);
  Rational h2 = r0 * r0 - along * along;
  if (h2 < 0) return false;
  Rational h = approximate_sqrt(h2);
  Point axis = scale(Rational(1 / d), c1);
  Point base = scale(along, axis);
  Point offset = scale(h, perpendicular(axis));
  first = add(base, offset);
  second = subtract(base, offset);
  return true;
}

LoopBuilder::LoopBuilder(const Point& start, std::string pointer)
    : start_(start), current_(start), pointer_(std::move(pointer)) {
  loop_.pointer = pointer_;
}

void LoopBuilder::line_to(const Point& target, const std::string& label) {
  if (target == current_)
    throw GeometryError("internal error in template " + pointer_ + ": zero-length edge '" +
                        label + "'");
  Edge edge;
  edge.kind = Edge::Kind::segment;
  edge.source = current_;
  edge.target = target;
  edge.pointer = pointer_;
  edge.label = label;
  loop_.edges.push_back(std::move(edge));
  current_ = target;
}

void LoopBuilder::arc_to(const Point& target, const Point& center, bool ccw,
                         const std::string& label) {
  Rational r2 = squared_distance(current_, center);
  if (r2 == 0 || squared_distance(target, center) != r2)
    throw GeometryError("internal error in template " + pointer_ + ": arc '" + label +
                        "' endpoints are not on one circle");
  Edge edge;
  edge.kind = Edge::Kind::arc;
  edge.source = current_;
  edge.target = target;
  edge.center = center;
  edge.ccw = ccw;
  edge.radius_squared = r2;
  edge.pointer = pointer_;
  edge.label = label;
  loop_.edges.push_back(std::move(edge));
  current_ = target;
}

Loop LoopBuilder::circle(const Point& center, const Rational& radius, const std::string& label,
                         const std::string& pointer) {
  Point start{center.x + radius, center.y};
  LoopBuilder builder(start, pointer);
  builder.arc_to(start, center, true, label);
  return builder.finish();
}

Loop LoopBuilder::finish() {
  if (!(current_ == start_) || loop_.edges.empty())
    throw GeometryError("internal error in template " + pointer_ + ": loop does not close");
  return std::move(loop_);
}

}  // namespace hipair::model_detail::template_geometry
