// Interleaved timing of HIPAIR's C-space build and CGAL's minkowski_sum_2 on the benchmark's
// polygons (the same polygons as tests/perf/minkowski_peer_benchmark.cpp): `rounds` rounds of
// `batch` builds then `batch` sums, CPU time of this thread; prints the medians and their
// ratio. On a loaded machine the benchmark's `ratio` counter compares a build with a CGAL call
// timed up to a second earlier; here both are timed within each round (docs/performance.md,
// session 16). Not part of the CMake build (it has its own main); compile it against a build:
//   c++ -O3 -DNDEBUG -frounding-math -std=c++20 -DCGAL_USE_GMP -DCGAL_USE_GMPXX=1 -DCGAL_USE_MPFI \
//     -DCGAL_USE_MPFR -Isrc -Iinclude -I. -isystem /usr/include/eigen3 tests/perf/minkowski_interleaved.cpp \
//     -o minkowski_interleaved build/libhipair.a -lmpfi -lmpfr -lgmpxx -lgmp -lpthread
//   ./minkowski_interleaved N ROUNDS BATCH [locate] [pool]    (N as BM_MinkowskiHipair/N; e.g. 64 11 5;
//                                                              or N/M: a convex N-gon and M-gon, e.g. 12/12)
// `pool`: GMP's memory functions are the command line's (hipair::use_throwing_gmp_allocation,
// src/cli/main.cpp: a per-thread pool of small limb blocks), installed before anything is
// made, so both sides' GMP numbers (ours and CGAL's) come from it; add -ljemalloc to the link
// as well to measure both sides as the `hipair` program runs (session 70, mink70).
// What "ours" times: CSpace::build (eager: every cell classified, the blocked region's boundary
// edges, vertices, samples and labels all built; everything `hipair cspace --json` writes is
// read from it without further computation, except the public vertices' exact numbers, copied
// from the arrangement's vertices on the first vertices() / vertex() call since session 43:
// trans43 measured build + that first read separately) and the destruction of the previous space; with
// `locate`, also one exact point location at the chart's centre after each build (a user's
// first query). "cgal": minkowski_sum_2 of the two exact polygons, their construction included.
// The allocator is the one linked (glibc's malloc unless -ljemalloc is added to the command
// above; the hipair command line links jemalloc): the same for both sides in one process.
#include "polygon_models.hpp"

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
using perf::Points;
static double cpu() { timespec t{}; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
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
__attribute__((noinline)) std::size_t run_ours(const Model& model, CSpace& space, int reps, bool locate) {
  std::size_t located = 0;
  for (int i = 0; i < reps; ++i) {
    space = CSpace::build(model, "a", "b");
    if (locate) {
      const CSpaceChart& chart = space.charts().front();
      Rational x = (chart.x_lo + chart.x_hi) / 2, y = (chart.y_lo + chart.y_hi) / 2;
      located += static_cast<std::size_t>(space.locate(ChartPoint{0, x, y}).kind);
    }
  }
  return space.statistics().vertices + located;
}
int main(int argc, char** argv) {
  const std::string pair = argv[1];
  const std::size_t slash = pair.find('/');
  int n = std::atoi(argv[1]), rounds = std::atoi(argv[2]), batch = std::atoi(argv[3]);
  bool locate = false, pool = false;
  for (int i = 4; i < argc; ++i) {
    locate = locate || std::string(argv[i]) == "locate";
    pool = pool || std::string(argv[i]) == "pool";
  }
  if (pool) use_throwing_gmp_allocation();
  auto [a, b] = slash == std::string::npos ? perf::minkowski_polygons(n) : perf::minkowski_polygons(n, std::atoi(pair.c_str() + slash + 1));
  Model model = perf::sliders(a, b);
  CSpace space;
  run_ours(model, space, 1, locate); run_cgal(a, b, 1);   // warm-up
  std::vector<double> ours, theirs, ratios;
  for (int r = 0; r < rounds; ++r) {
    double t0 = cpu(); run_ours(model, space, batch, locate); double t1 = cpu(); run_cgal(a, b, batch); double t2 = cpu();
    ours.push_back((t1 - t0) / batch); theirs.push_back((t2 - t1) / batch); ratios.push_back((t1 - t0) / (t2 - t1));
  }
  auto median = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
  std::printf("n=%s%s%s ours %.3f ms cgal %.3f ms ratio(medians) %.2f median-of-round-ratios %.2f min-ratio %.2f\n", pair.c_str(), locate ? " (+locate)" : "", pool ? " (gmp pool)" : "", 1e3 * median(ours),
              1e3 * median(theirs), median(ours) / median(theirs), median(ratios), *std::min_element(ratios.begin(), ratios.end()));
}
