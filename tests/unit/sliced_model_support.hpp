// Shared by the 3-DOF (sliced) tests: model text for polygons, rectangles, circles and stadiums
// with exact rational coordinates, a fixed part against a planar part, the square peg in a square
// hole, random rationals and star-shaped polygons on a 1/8 grid, and the exact overlap oracle at a
// configuration (x, y, t = tan(theta/2) or the half turn), the rotation of a slice's angle and a
// vertex-vertex contact's offset.
#pragma once

#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include "random_rationals.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair::sliced_models {

using Random = std::mt19937_64;

inline std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
inline std::string point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }

inline std::string polygon(const std::vector<std::pair<Rational, Rational>>& p) {
  std::string loop = R"({ "start": )" + point(p[0].first, p[0].second) + R"(, "edges": [ )";
  for (std::size_t i = 1; i <= p.size(); ++i)
    loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": )" + point(p[i % p.size()].first, p[i % p.size()].second) + " }";
  return loop + " ] }";
}

inline std::string rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

inline std::string circle(const Rational& x, const Rational& y, const Rational& r) {
  return R"({ "circle": { "center": )" + point(x, y) + R"(, "radius": )" + text(r) + " } }";
}

// A stadium (a slot with round ends): centres (-l, 0), (l, 0), radius r.
inline std::string stadium(const Rational& l, const Rational& r) {
  return R"({ "start": )" + point(-l, -r) + R"(, "edges": [ { "line_to": )" + point(l, -r) + R"( }, { "arc_to": )" +
         point(l, r) + R"(, "center": )" + point(l, 0) + R"(, "dir": "ccw" }, { "line_to": )" + point(-l, r) +
         R"( }, { "arc_to": )" + point(-l, -r) + R"(, "center": )" + point(-l, 0) + R"(, "dir": "ccw" } ] })";
}

// A fixed part ("fixed") against a planar part ("free") turning about `pivot`.
inline Model pair_model(const std::string& fixed_loops, const std::string& free_loops, const Point& pivot = {0, 0}) {
  return read_model(R"({ "hipair": 1, "name": "three-dof", "parts": [
    { "name": "fixed", "motion": "fixed", "loops": [ )" + fixed_loops + R"( ] },
    { "name": "free", "motion": { "planar": { "pivot": )" + point(pivot.x, pivot.y) + R"( } }, "loops": [ )" +
                    free_loops + R"( ] } ] })");
}

// A square plate [-20, 20]^2 with a square hole of side h, and a square peg of side s.
inline Model peg_in_hole(const Rational& s, const Rational& h) {
  return pair_model(rectangle(-20, -20, 20, 20) + ", " + rectangle(-h / 2, -h / 2, h / 2, h / 2),
                    rectangle(-s / 2, -s / 2, s / 2, s / 2));
}

using test_numbers::random_rational;   // lo + (p / q) (hi - lo), q in 1..den (97), p in 0..q

// A star-shaped polygon with k vertices around (cx, cy) on a 1/8 grid (doubles only place input).
inline std::vector<std::pair<Rational, Rational>> star(Random& random, int k, double cx, double cy, double radius) {
  std::vector<std::pair<Rational, Rational>> points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * std::numbers::pi * (i + 0.15 + 0.7 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (0.45 + 0.55 * static_cast<double>(random() % 1000) / 1000.0);
    Rational x(static_cast<long>(std::lround(8 * (cx + r * std::cos(angle)))), 8);
    Rational y(static_cast<long>(std::lround(8 * (cy + r * std::sin(angle)))), 8);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x, y);
  }
  return points;
}

// cos and sin of a slice's angle, exactly: (1 - t^2, 2t) / (1 + t^2) of its half-angle tangent t,
// (-1, 0) at the half turn.
inline std::pair<Rational, Rational> rotation(const SlicedAngle& angle) {
  if (angle.half_turn) return {Rational(-1), Rational(0)};
  const Rational d = 1 + angle.t * angle.t;
  return {Rational((1 - angle.t * angle.t) / d), Rational(2 * angle.t / d)};
}

// The offset (x, y) at which vertex b of the planar part, turned by (c, s) about its pivot, meets
// vertex a of the fixed part: a - pivot - R (b - pivot).
inline std::pair<Rational, Rational> vertex_vertex_offset(const Point& a, const Point& b, const Point& pivot,
                                                          const Rational& c, const Rational& s) {
  const Rational bx = b.x - pivot.x, by = b.y - pivot.y;
  return {Rational(a.x - pivot.x - (c * bx - s * by)), Rational(a.y - pivot.y - (s * bx + c * by))};
}

// The exact overlap oracle: part 0 fixed, part 1 turned about its pivot to q's angle and moved by
// (q.x, q.y).
inline PartRelation relation_at(const Model& model, const SlicedConfiguration& q) {
  const Part& a = model.parts[0];
  const Part& b = model.parts[1];
  const auto [c, s] = rotation(q.angle);
  return part_overlap(a, Placement{}, b, placement_about(b.motion.pivot, c, s, Point{q.x, q.y})).relation;
}

// The same as a location kind: apart = free, touching = contact, overlapping = blocked.
inline SlicedLocation::Kind kind_at(const Model& model, const SlicedConfiguration& q) {
  const PartRelation relation = relation_at(model, q);
  return relation == PartRelation::apart      ? SlicedLocation::Kind::free
         : relation == PartRelation::touching ? SlicedLocation::Kind::contact
                                              : SlicedLocation::Kind::blocked;
}

}  // namespace hipair::sliced_models
