// PEER comparison: the exact C-space of a translating polygon pair (part A slides along x,
// part B along y) built by HIPAIR, against CGAL's minkowski_sum_2 of B and -A on the same
// exact polygons (the blocked region is that sum reflected; tests/unit/cspace_minkowski_test.cpp
// checks the equality). HIPAIR does more (arrangement, face classification, cells, point
// location structure), so the ratio is an upper bound on the price of generality.
//   BM_MinkowskiHipair/n    HIPAIR C-space, counters peer_us (CGAL) and ratio (HIPAIR / CGAL)
//   BM_MinkowskiCgal/n      CGAL minkowski_sum_2 alone
// n = 0: triangle and square, n = 1: non-convex L and a triangle, n >= 3: two convex n-gons
// with rational vertices on circles (n = 256: the largest row).
#include "peer_timing.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/minkowski_sum_2.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace hipair;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;
using Points = std::vector<std::pair<Rational, Rational>>;

// Convex n-gon with rational vertices on the circle of radius `radius` about `centre`:
// (cos, sin) from rational half-angle tangents rounded to 1/64 (1/(16 n) above 64 vertices,
// so that neighbouring tangents stay distinct).
Points rational_polygon(int n, const Rational& radius, const Rational& cx, const Rational& cy) {
  Points points;
  constexpr double pi = 3.14159265358979323846;
  const long grid = n > 64 ? 16L * n : 64L;
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

Points fixed_points(const std::vector<std::pair<std::string, std::string>>& text) {
  Points points;
  for (const auto& [x, y] : text) points.emplace_back(parse_rational(x), parse_rational(y));
  return points;
}

std::pair<Points, Points> polygons(int n) {
  if (n == 0)
    return {fixed_points({{"0", "0"}, {"4", "0"}, {"1", "3"}}),
            fixed_points({{"10", "10"}, {"12", "10"}, {"12", "12"}, {"10", "12"}})};
  if (n == 1)
    return {fixed_points({{"0", "0"}, {"6", "0"}, {"6", "1"}, {"1", "1"}, {"1", "5"}, {"0", "5"}}),
            fixed_points({{"20", "-3"}, {"23.5", "-3"}, {"21", "1/7"}})};
  return {rational_polygon(n, 5, 0, 0), rational_polygon(n + 1, 3, 20, 7)};
}

std::string loop_json(const Points& points) {
  auto value = [](const Rational& q) { return "\"" + q.get_str() + "\""; };
  std::string text = "{ \"start\": [" + value(points[0].first) + ", " + value(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + value(p.first) + ", " + value(p.second) + "] }";
  }
  return text + "] }";
}

Model sliders(const Points& a, const Points& b) {
  std::string text = R"({ "hipair": 1, "name": "sliders", "parts": [
    { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ )" +
                     loop_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [ )" +
                     loop_json(b) + R"( ] } ] })";
  return read_model(text);
}

Polygon cgal_polygon(const Points& points, bool negate) {
  Polygon polygon;
  for (const auto& [x, y] : points) {
    Rational px = negate ? Rational(-x) : x, py = negate ? Rational(-y) : y;
    polygon.push_back(Kernel::Point_2(Kernel::FT(px), Kernel::FT(py)));
  }
  if (polygon.is_clockwise_oriented()) polygon.reverse_orientation();
  return polygon;
}

// A fresh CGAL call each time (no lazy-exact values shared between calls).
std::size_t cgal_sum(const Points& a, const Points& b) {
  auto sum = CGAL::minkowski_sum_2(cgal_polygon(b, false), cgal_polygon(a, true));
  return sum.outer_boundary().size();
}

void BM_MinkowskiHipair(benchmark::State& state) {
  auto [a, b] = polygons(static_cast<int>(state.range(0)));
  Model model = sliders(a, b);
  CSpace space;
  hipair::bench::run_with_peer(
      state,
      [&] {
        space = CSpace::build(model, "a", "b");
        benchmark::DoNotOptimize(space);
      },
      [&] { benchmark::DoNotOptimize(cgal_sum(a, b)); });
  state.counters["vertices"] = static_cast<double>(space.statistics().vertices);
  state.counters["polygon_vertices"] = static_cast<double>(a.size() + b.size());
}
BENCHMARK(BM_MinkowskiHipair)->Arg(0)->Arg(1)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

void BM_MinkowskiCgal(benchmark::State& state) {
  auto [a, b] = polygons(static_cast<int>(state.range(0)));
  std::size_t size = 0;
  for (auto _ : state) benchmark::DoNotOptimize(size = cgal_sum(a, b));
  state.counters["sum_vertices"] = static_cast<double>(size);
}
BENCHMARK(BM_MinkowskiCgal)->Arg(0)->Arg(1)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace
