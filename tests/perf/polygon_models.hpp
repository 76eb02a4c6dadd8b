// Exact polygon pairs of the peer benchmarks (minkowski_peer_benchmark.cpp,
// minkowski_interleaved.cpp, overlap_peer_benchmark.cpp): convex n-gons with rational vertices
// on circles, the Minkowski benchmark's pairs, and the models that carry them.
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace hipair::perf {

using Points = std::vector<std::pair<Rational, Rational>>;

/// Convex n-gon with rational vertices on the circle of radius `radius` about (cx, cy):
/// (cos, sin) from rational half-angle tangents rounded to 1/grid; grid 0 means 1/64, or
/// 1/(16 n) above 64 vertices (so that neighbouring tangents stay distinct).
inline Points rational_polygon(int n, const Rational& radius, const Rational& cx, const Rational& cy, long grid = 0) {
  Points points;
  constexpr double pi = 3.14159265358979323846;
  if (grid == 0) grid = n > 64 ? 16L * n : 64L;
  for (int k = -(n / 2) + 1; k < n - n / 2; ++k) {
    if (2 * k == n) break;
    Rational t(std::lround(std::tan(pi * k / n) * static_cast<double>(grid)), grid);
    t.canonicalize();
    Rational d = 1 + t * t;
    points.emplace_back(Rational(cx + radius * (1 - t * t) / d), Rational(cy + radius * 2 * t / d));
  }
  if (n % 2 == 0) points.emplace_back(Rational(cx - radius), cy);
  return points;
}

inline Points fixed_points(const std::vector<std::pair<std::string, std::string>>& text) {
  Points points;
  for (const auto& [x, y] : text) points.emplace_back(parse_rational(x), parse_rational(y));
  return points;
}

/// The Minkowski benchmark's pair n: 0 a triangle and a square, 1 a non-convex L and a
/// triangle, n >= 3 a convex n-gon and (n+1)-gon.
inline std::pair<Points, Points> minkowski_polygons(int n) {
  if (n == 0)
    return {fixed_points({{"0", "0"}, {"4", "0"}, {"1", "3"}}),
            fixed_points({{"10", "10"}, {"12", "10"}, {"12", "12"}, {"10", "12"}})};
  if (n == 1)
    return {fixed_points({{"0", "0"}, {"6", "0"}, {"6", "1"}, {"1", "1"}, {"1", "5"}, {"0", "5"}}),
            fixed_points({{"20", "-3"}, {"23.5", "-3"}, {"21", "1/7"}})};
  return {rational_polygon(n, 5, 0, 0), rational_polygon(n + 1, 3, 20, 7)};
}

/// A convex n-gon and m-gon placed as minkowski_polygons' (n >= 3, m >= 3); with n = m every
/// edge of one has a parallel edge in the other (collinear convolution segments).
inline std::pair<Points, Points> minkowski_polygons(int n, int m) {
  return {rational_polygon(n, 5, 0, 0), rational_polygon(m, 3, 20, 7)};
}

/// A model loop of straight edges through `points`.
inline std::string loop_json(const Points& points) {
  auto value = [](const Rational& q) { return "\"" + q.get_str() + "\""; };
  std::string text = "{ \"start\": [" + value(points[0].first) + ", " + value(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + value(p.first) + ", " + value(p.second) + "] }";
  }
  return text + "] }";
}

/// Part a slides along x, part b along y.
inline Model sliders(const Points& a, const Points& b) {
  std::string text = R"({ "hipair": 1, "name": "sliders", "parts": [
    { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ )" +
                     loop_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [ )" +
                     loop_json(b) + R"( ] } ] })";
  return read_model(text);
}

}  // namespace hipair::perf
