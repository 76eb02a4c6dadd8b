// PEER comparison: HIPAIR's exact overlap predicate (classify_overlap: apart / touching /
// overlapping, exact rational poses from half-angle tangents) against Box2D's floating-point
// b2TestOverlap (GJK distance with the polygon skin) and b2CollidePolygons (SAT + clipping,
// contact manifold) on the same convex polygonal parts at the same configurations.
//   BM_OverlapHipair/n     n = 0: triangle and square; n >= 3: n-gon and (n-1)-gon
//   BM_OverlapBox2dTest/n, BM_OverlapBox2dCollide/n
// Counters of BM_OverlapHipair: peer_us (b2TestOverlap, per call), ratio (HIPAIR / Box2D),
// agree (fraction of configurations where Box2D's overlap answer equals HIPAIR's
// "overlapping"; Box2D counts the 0.01-unit polygon skin as contact, so a few touching or
// nearly touching configurations differ by design).
#include "peer_timing.hpp"
#include "polygon_models.hpp"

#include "curves/contact_curves.hpp"

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <box2d/b2_collision.h>
#include <box2d/b2_polygon_shape.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace hipair;
using perf::loop_json;
using perf::Points;
constexpr double pi = 3.14159265358979323846;

std::pair<Points, Points> polygons(int n) {
  if (n == 0)
    return {Points{{0, 0}, {4, 0}, {1, 3}}, Points{{6, -1}, {9, -1}, {9, 2}, {6, 2}}};
  return {perf::rational_polygon(n, 5, 2, 0, 64), perf::rational_polygon(n - 1, 4, 8, 1, 64)};
}

// Part a turns about (0, 0), part b about (pivot, 0): their swept disks overlap.
Model rotors(const Points& a, const Points& b, int pivot) {
  std::string text = R"({ "hipair": 1, "name": "rotors", "parts": [
    { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" +
                     loop_json(a) + R"( ] },
    { "name": "b", "motion": { "rotation": { "pivot": [)" + std::to_string(pivot) + R"(, 0] } }, "loops": [ )" +
                     loop_json(b) + R"( ] } ] })";
  return read_model(text);
}

struct Sample {
  std::size_t x_chart = 0, y_chart = 0;
  cspace::ChartPoint q;
  b2Transform a, b;
};

b2Transform transform(double angle, double px, double py) {
  b2Rot rotation(static_cast<float>(angle));
  double c = std::cos(angle), s = std::sin(angle);
  return b2Transform(b2Vec2(static_cast<float>(px - (c * px - s * py)), static_cast<float>(py - (s * px + c * py))),
                     rotation);
}

b2PolygonShape box2d_polygon(const Points& points) {
  std::vector<b2Vec2> vertices;
  for (const auto& [x, y] : points) vertices.emplace_back(static_cast<float>(x.get_d()), static_cast<float>(y.get_d()));
  b2PolygonShape shape;
  shape.Set(vertices.data(), static_cast<int32>(vertices.size()));
  return shape;
}

struct Setup {
  Model model;
  cspace::PairAxes axes;
  cspace::ChartLayout layout;
  Points a, b;
  int pivot = 9;   ///< x of part b's pivot
  b2PolygonShape shape_a, shape_b;
  std::vector<Sample> samples;

  explicit Setup(int n) {
    std::tie(a, b) = polygons(n);
    pivot = n == 0 ? 6 : 9;
    model = rotors(a, b, pivot);
    axes = cspace::pair_axes(model, 0, 1);
    layout = cspace::chart_layout(model, axes);
    shape_a = box2d_polygon(a);
    shape_b = box2d_polygon(b);
    std::mt19937_64 random(11);
    for (int i = 0; i < 512; ++i) {
      Sample s;
      s.x_chart = random() % layout.x_charts.size();
      s.y_chart = random() % layout.y_charts.size();
      s.q.x = Rational(static_cast<long>(random() % 2049) - 1024, 1024);
      s.q.y = Rational(static_cast<long>(random() % 2049) - 1024, 1024);
      s.q.x.canonicalize();
      s.q.y.canonicalize();
      const auto& xa = layout.x_charts[s.x_chart];
      const auto& ya = layout.y_charts[s.y_chart];
      s.a = transform(cspace::chart_to_coordinate(xa, s.q.x.get_d()), 0, 0);
      s.b = transform(cspace::chart_to_coordinate(ya, s.q.y.get_d()), pivot, 0);
      samples.push_back(s);
    }
  }

  cspace::Overlap exact(const Sample& s) const {
    return cspace::classify_overlap(model, axes, layout.x_charts[s.x_chart], layout.y_charts[s.y_chart], s.q);
  }
  bool test(const Sample& s) const { return b2TestOverlap(&shape_a, 0, &shape_b, 0, s.a, s.b); }
  int collide(const Sample& s) const {
    b2Manifold manifold;
    b2CollidePolygons(&manifold, &shape_a, s.a, &shape_b, s.b);
    return manifold.pointCount;
  }
};

void BM_OverlapHipair(benchmark::State& state) {
  Setup setup(static_cast<int>(state.range(0)));
  std::size_t i = 0, j = 0;
  hipair::bench::run_with_peer(
      state, [&] { benchmark::DoNotOptimize(setup.exact(setup.samples[i++ % setup.samples.size()])); },
      [&] { benchmark::DoNotOptimize(setup.test(setup.samples[j++ % setup.samples.size()])); });
  std::size_t agree = 0, overlapping = 0, touching = 0;
  for (const auto& s : setup.samples) {
    cspace::Overlap relation = setup.exact(s);
    overlapping += relation == cspace::Overlap::overlapping;
    touching += relation == cspace::Overlap::touching;
    agree += (relation == cspace::Overlap::overlapping) == setup.test(s);
  }
  state.counters["agree"] = static_cast<double>(agree) / static_cast<double>(setup.samples.size());
  state.counters["overlapping"] = static_cast<double>(overlapping) / static_cast<double>(setup.samples.size());
  state.counters["touching"] = static_cast<double>(touching);
}
BENCHMARK(BM_OverlapHipair)->Arg(0)->Arg(5)->Arg(8)->Unit(benchmark::kMicrosecond);

void BM_OverlapBox2dTest(benchmark::State& state) {
  Setup setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(setup.test(setup.samples[i++ % setup.samples.size()]));
}
BENCHMARK(BM_OverlapBox2dTest)->Arg(0)->Arg(5)->Arg(8)->Unit(benchmark::kMicrosecond);

void BM_OverlapBox2dCollide(benchmark::State& state) {
  Setup setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(setup.collide(setup.samples[i++ % setup.samples.size()]));
}
BENCHMARK(BM_OverlapBox2dCollide)->Arg(0)->Arg(5)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace
