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
#include "polygon_models.hpp"

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
using perf::minkowski_polygons;
using perf::Points;
using perf::sliders;


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
  auto [a, b] = minkowski_polygons(static_cast<int>(state.range(0)));
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
  auto [a, b] = minkowski_polygons(static_cast<int>(state.range(0)));
  std::size_t size = 0;
  for (auto _ : state) benchmark::DoNotOptimize(size = cgal_sum(a, b));
  state.counters["sum_vertices"] = static_cast<double>(size);
}
BENCHMARK(BM_MinkowskiCgal)->Arg(0)->Arg(1)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace
