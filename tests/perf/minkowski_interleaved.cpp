// Interleaved timing of HIPAIR's C-space build and CGAL's minkowski_sum_2 on the benchmark's
// polygons (the same polygons as tests/perf/minkowski_peer_benchmark.cpp): `rounds` rounds of
// `batch` builds then `batch` sums, CPU time of this thread; prints the medians and their
// ratio. On a loaded machine the benchmark's `ratio` counter compares a build with a CGAL call
// timed up to a second earlier; here both are timed within each round (docs/performance.md,
// session 16). Not part of the CMake build (it has its own main); compile it against a build:
//   c++ -O3 -DNDEBUG -frounding-math -std=c++20 -DCGAL_USE_GMP -DCGAL_USE_GMPXX=1 -DCGAL_USE_MPFI \
//     -DCGAL_USE_MPFR -Isrc -Iinclude -I. -isystem /usr/include/eigen3 tests/perf/minkowski_interleaved.cpp \
//     -o minkowski_interleaved build/libhipair.a -lmpfi -lmpfr -lgmpxx -lgmp -lpthread
//   ./minkowski_interleaved N ROUNDS BATCH     (N as BM_MinkowskiHipair/N; e.g. 64 11 5)
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/minkowski_sum_2.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>
using namespace hipair;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;
using Points = std::vector<std::pair<Rational, Rational>>;
static double cpu() { timespec t{}; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
Points rational_polygon(int n, const Rational& radius, const Rational& cx, const Rational& cy) {
  Points points; constexpr double pi = 3.14159265358979323846; const long grid = n > 64 ? 16L * n : 64L;
  for (int k = -(n / 2) + 1; k < n - n / 2; ++k) {
    if (2 * k == n) break;
    Rational t(std::lround(std::tan(pi * k / n) * static_cast<double>(grid)), grid); t.canonicalize();
    Rational d = 1 + t * t;
    points.emplace_back(Rational(cx + radius * (1 - t * t) / d), Rational(cy + radius * 2 * t / d));
  }
  if (n % 2 == 0) points.emplace_back(Rational(cx - radius), cy);
  return points;
}
Points fixed_points(const std::vector<std::pair<std::string, std::string>>& text) {
  Points p; for (const auto& [x, y] : text) p.emplace_back(parse_rational(x), parse_rational(y)); return p;
}
std::pair<Points, Points> polygons(int n) {
  if (n == 0) return {fixed_points({{"0", "0"}, {"4", "0"}, {"1", "3"}}), fixed_points({{"10", "10"}, {"12", "10"}, {"12", "12"}, {"10", "12"}})};
  if (n == 1) return {fixed_points({{"0", "0"}, {"6", "0"}, {"6", "1"}, {"1", "1"}, {"1", "5"}, {"0", "5"}}), fixed_points({{"20", "-3"}, {"23.5", "-3"}, {"21", "1/7"}})};
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
    { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ )" + loop_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [ )" + loop_json(b) + R"( ] } ] })";
  return read_model(text);
}
Polygon cgal_polygon(const Points& points, bool negate) {
  Polygon polygon;
  for (const auto& [x, y] : points) { Rational px = negate ? Rational(-x) : x, py = negate ? Rational(-y) : y; polygon.push_back(Kernel::Point_2(Kernel::FT(px), Kernel::FT(py))); }
  if (polygon.is_clockwise_oriented()) polygon.reverse_orientation();
  return polygon;
}
__attribute__((noinline)) std::size_t run_cgal(const Points& a, const Points& b, int reps) {
  std::size_t s = 0;
  for (int i = 0; i < reps; ++i) s += CGAL::minkowski_sum_2(cgal_polygon(b, false), cgal_polygon(a, true)).outer_boundary().size();
  return s;
}
__attribute__((noinline)) std::size_t run_ours(const Model& model, CSpace& space, int reps) {
  for (int i = 0; i < reps; ++i) space = CSpace::build(model, "a", "b");
  return space.statistics().vertices;
}
int main(int argc, char** argv) {
  int n = std::atoi(argv[1]), rounds = std::atoi(argv[2]), batch = std::atoi(argv[3]);
  auto [a, b] = polygons(n);
  Model model = sliders(a, b);
  CSpace space;
  run_ours(model, space, 1); run_cgal(a, b, 1);   // warm-up
  std::vector<double> ours, theirs, ratios;
  for (int r = 0; r < rounds; ++r) {
    double t0 = cpu(); run_ours(model, space, batch); double t1 = cpu(); run_cgal(a, b, batch); double t2 = cpu();
    ours.push_back((t1 - t0) / batch); theirs.push_back((t2 - t1) / batch); ratios.push_back((t1 - t0) / (t2 - t1));
  }
  auto median = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
  std::printf("n=%d ours %.3f ms cgal %.3f ms ratio(medians) %.2f median-of-round-ratios %.2f min-ratio %.2f\n", n, 1e3 * median(ours),
              1e3 * median(theirs), median(ours) / median(theirs), median(ratios), *std::min_element(ratios.begin(), ratios.end()));
}
