// Test helper: a polygon (exact rational vertices) as a model loop of line_to edges.
#pragma once

#include <hipair/rational.hpp>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair::test_loops {

using Points = std::vector<std::pair<Rational, Rational>>;

inline std::string text(const Rational& q) { return "\"" + q.get_str() + "\""; }

inline std::string loop_json(const Points& points) {
  std::string out = "{ \"start\": [" + text(points[0].first) + ", " + text(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    out += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + text(p.first) + ", " + text(p.second) + "] }";
  }
  return out + "] }";
}

// A star-shaped polygon about (cx, cy): n vertices at increasing angles (36 degrees apart at
// least, so rounding to the 1/8 grid keeps their order), radii in [2, 2 + spread] (spread 0:
// convex, on a circle up to rounding); with `collinear`, the exact midpoint of edge 0 added as a
// vertex (a straight vertex between collinear edges).
inline Points star(std::mt19937_64& random, int n, double cx, double cy, double spread, bool collinear) {
  Points points;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < n; ++k) {
    double angle = 2 * pi * (k + 0.3 * (static_cast<double>(random() % 1000) / 1000.0)) / n;
    double radius = 2 + spread * static_cast<double>(random() % 1000) / 1000.0;
    Rational x(static_cast<long>(std::lround((cx + radius * std::cos(angle)) * 8)), 8);
    Rational y(static_cast<long>(std::lround((cy + radius * std::sin(angle)) * 8)), 8);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x, y);
  }
  if (collinear) {
    Rational mx = (points[0].first + points[1].first) / 2, my = (points[0].second + points[1].second) / 2;
    points.insert(points.begin() + 1, {mx, my});
  }
  return points;
}

// A star-shaped polygon with k vertices around (cx, cy) on a 1/q grid, times scale (a double only
// places the test input; the reader checks that it is simple); one vertex in three at the full
// radius, the others at `inner` ... `inner` + `span` of it (0.35-1 by default).
inline Points grid_star(std::mt19937_64& random, int k, double cx, double cy, double radius, long q, const Rational& scale,
                        double inner = 0.35, double span = 0.65) {
  Points points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * 3.141592653589793 * (i + 0.15 + 0.7 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (random() % 3 == 0 ? 1.0 : inner + span * static_cast<double>(random() % 1000) / 1000.0);
    Rational x(static_cast<long>(std::lround(q * (cx + r * std::cos(angle)))), q);
    Rational y(static_cast<long>(std::lround(q * (cy + r * std::sin(angle)))), q);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x * scale, y * scale);
  }
  return points;
}

// The polygon's vertices times s, or moved by (dx, dy) (exact, canonical).
inline Points scaled(const Points& points, const Rational& s) {
  Points out;
  for (const auto& [x, y] : points) out.emplace_back(x * s, y * s);
  return out;
}

inline Points moved(const Points& points, const Rational& dx, const Rational& dy) {
  Points out;
  for (const auto& [x, y] : points) out.emplace_back(x + dx, y + dy);
  return out;
}

// The model text of two translating polygons: a moves along da, b along db.
inline std::string sliders_json(const Points& a, const Points& b, const std::string& da = "[1, 0]",
                                const std::string& db = "[0, 1]") {
  return R"({ "hipair": 1, "name": "sliders", "parts": [
    { "name": "a", "motion": { "translation": { "direction": )" + da + R"( } }, "loops": [ )" + loop_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": )" + db + R"( } }, "loops": [ )" + loop_json(b) + R"( ] } ] })";
}

}  // namespace hipair::test_loops
