// Kinematic analysis benchmarks (Google Benchmark), issue 14 item 5:
//   BM_AnalyzeExample/geneva, /ratchet   hipair::analyze_kinematics as `hipair analyze` runs it
//                                        (720 driver steps a turn, contact kernels), CPU time
//   BM_RefineRoots/0 and /1              the analysis' hot spot side by side: 200 roots of random
//                                        quartics refined to 2^-60 relative (as Real::approximate
//                                        does) by Real::refine_to (/0) and by the halving of
//                                        canonical rationals it replaced (/1, the peer); the
//                                        counter `ratio` of /1 is its thread CPU time over /0's
//   BM_CompareRoots/0 and /1             every ordered pair of 120 close roots (relative gaps down
//                                        to 2^-80, equal ones from other polynomials) compared by
//                                        algebra::compare (/0, with its double filter) and by the
//                                        unfiltered exact comparison it had before (/1, the peer:
//                                        refinement of copies by 2^-20, gcd and Sturm count)
#include "bench_paths.hpp"

#include "algebra/exact_real.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace hipair;
namespace algebra = hipair::cspace::algebra;

void BM_AnalyzeExample(benchmark::State& state) {
  const char* name = state.range(0) == 0 ? "geneva.json" : "ratchet.json";
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name);
  KinematicsOptions options;
  options.steps_per_cycle = 720;   // the CLI's default
  std::size_t samples = 0;
  for (auto _ : state) {
    KinematicsResult result = analyze_kinematics(model, options);
    samples = result.samples.size();
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(name);
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_AnalyzeExample)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// The halving refine_to did before (canonical midpoints, exact signs).
void halving_refine_to(algebra::Real& r, const Rational& width) {
  if (r.exact || r.upper - r.lower <= width) return;
  const int lower_sign = algebra::sign_at(r.polynomial, r.lower);
  while (r.upper - r.lower > width) {
    Rational middle = (r.lower + r.upper) / 2;
    int s = algebra::sign_at(r.polynomial, middle);
    if (s == 0) {
      r.lower = r.upper = middle;
      r.exact = true;
      return;
    }
    if (s == lower_sign)
      r.lower = middle;
    else
      r.upper = middle;
  }
}

std::vector<algebra::Real> quartic_roots() {
  gmp_randclass random(gmp_randinit_default);
  random.seed(14);
  std::vector<algebra::Real> roots;
  while (roots.size() < 200) {
    algebra::Polynomial p;
    for (int i = 0; i <= 4; ++i) p.push_back(random.get_z_bits(40) - (mpz_class(1) << 39));
    p = algebra::square_free_part(p);
    if (algebra::degree(p) < 1) continue;
    for (algebra::Real& root : algebra::real_roots(p, Rational(-4), Rational(4))) {
      root.lower.canonicalize();
      root.upper.canonicalize();
      roots.push_back(root);
    }
  }
  return roots;
}

double fast_seconds = 0;

double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Runs `work` once per iteration and records its mean thread CPU time: in `fast` for the
// measured code (peer = false), as the counter `ratio` (peer / measured) for its peer.
template <class Work>
void side_by_side(benchmark::State& state, bool peer, double& fast, Work work) {
  double seconds = 0;
  std::size_t rounds = 0;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    work();
    seconds += thread_cpu_seconds() - start;
    ++rounds;
  }
  double mean = seconds / static_cast<double>(rounds);
  if (!peer) fast = mean;
  if (peer && fast > 0) state.counters["ratio"] = mean / fast;
}

void BM_RefineRoots(benchmark::State& state) {
  const std::vector<algebra::Real> roots = quartic_roots();
  bool halving = state.range(0) == 1;
  side_by_side(state, halving, fast_seconds, [&] {
    for (const algebra::Real& root : roots) {
      algebra::Real copy = root;
      Rational width = (abs(copy.lower) + abs(copy.upper)) / Rational(mpz_class(1) << 60);
      if (halving)
        halving_refine_to(copy, width);
      else
        copy.refine_to(width);
      benchmark::DoNotOptimize(copy);
    }
  });
  state.SetLabel(halving ? "canonical halving (peer)" : "refine_to");
}
BENCHMARK(BM_RefineRoots)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// compare() as it was before its double filter (session 12).
int unfiltered_compare(const algebra::Real& a, const algebra::Real& b) {
  if (a.exact) return -b.compare(a.lower);
  if (b.exact) return a.compare(b.lower);
  if (a.upper <= b.lower) return -1;
  if (b.upper <= a.lower) return 1;
  {
    algebra::Real x = a, y = b;
    Rational width = std::max(Rational(x.upper - x.lower), Rational(y.upper - y.lower)) / 1048576;
    x.refine_to(width);
    y.refine_to(width);
    if (x.exact || y.exact) return unfiltered_compare(x, y);
    if (x.upper <= y.lower) return -1;
    if (y.upper <= x.lower) return 1;
  }
  algebra::Polynomial g = algebra::gcd(a.polynomial, b.polynomial);
  Rational lo = std::max(a.lower, b.lower), hi = std::min(a.upper, b.upper);
  if (algebra::degree(g) >= 1) {
    algebra::SturmSequence sturm(g);
    if (sturm.count(lo, hi) - (algebra::sign_at(g, hi) == 0 ? 1 : 0) > 0) return 0;
  }
  algebra::Real x = a, y = b;
  for (;;) {
    Rational width = std::max(Rational(x.upper - x.lower), Rational(y.upper - y.lower)) / 65536;
    x.refine_to(width);
    y.refine_to(width);
    if (x.exact || y.exact) return unfiltered_compare(x, y);
    if (x.upper <= y.lower) return -1;
    if (y.upper <= x.lower) return 1;
  }
}

std::vector<algebra::Real> close_roots() {
  gmp_randclass random(gmp_randinit_default);
  random.seed(1428);
  std::vector<algebra::Real> roots;
  for (int i = 0; roots.size() < 120; ++i) {
    mpz_class a = random.get_z_bits(30) + 2, b = random.get_z_bits(12) + 1;
    mpz_class scale = mpz_class(1) << (i * 9 % 81);
    // b x^2 - a, (b scale) x^2 - (a scale + a), and (x - 5) (b x^2 - a): close and equal roots
    for (const algebra::Polynomial& p :
         {algebra::Polynomial{-a, 0, b}, algebra::primitive_part(algebra::Polynomial{-(a * scale + a), 0, b * scale}),
          algebra::Polynomial{5 * a, -a, -5 * b, b}})
      for (algebra::Real& root : algebra::real_roots(p, Rational(0), Rational(a + 1, b) + 1))
        if (!root.exact) roots.push_back(root);
  }
  return roots;
}

double filtered_compare_seconds = 0;

void BM_CompareRoots(benchmark::State& state) {
  const std::vector<algebra::Real> roots = close_roots();
  bool unfiltered = state.range(0) == 1;
  side_by_side(state, unfiltered, filtered_compare_seconds, [&] {
    int sum = 0;
    for (const algebra::Real& x : roots)
      for (const algebra::Real& y : roots) sum += unfiltered ? unfiltered_compare(x, y) : algebra::compare(x, y);
    benchmark::DoNotOptimize(sum);
  });
  state.SetLabel(unfiltered ? "unfiltered exact compare (peer)" : "compare with double filter");
}
BENCHMARK(BM_CompareRoots)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
