// Kinematic analysis benchmarks (Google Benchmark), issue 14 item 5:
//   BM_AnalyzeExample/geneva, /ratchet   hipair::analyze_kinematics as `hipair analyze` runs it
//                                        (720 driver steps a turn, contact kernels), CPU time
//   BM_RefineRoots/0 and /1              the analysis' hot spot side by side: 200 roots of random
//                                        quartics refined to 2^-60 relative (as Real::approximate
//                                        does) by Real::refine_to (/0) and by the halving of
//                                        canonical rationals it replaced (/1, the peer); the
//                                        counter `ratio` of /1 is its thread CPU time over /0's
#include "algebra/exact_real.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

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

void BM_RefineRoots(benchmark::State& state) {
  const std::vector<algebra::Real> roots = quartic_roots();
  bool halving = state.range(0) == 1;
  double seconds = 0;
  std::size_t rounds = 0;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    for (const algebra::Real& root : roots) {
      algebra::Real copy = root;
      Rational width = (abs(copy.lower) + abs(copy.upper)) / Rational(mpz_class(1) << 60);
      if (halving)
        halving_refine_to(copy, width);
      else
        copy.refine_to(width);
      benchmark::DoNotOptimize(copy);
    }
    seconds += thread_cpu_seconds() - start;
    ++rounds;
  }
  double mean = seconds / static_cast<double>(rounds);
  if (!halving) fast_seconds = mean;
  if (halving && fast_seconds > 0) state.counters["ratio"] = mean / fast_seconds;
  state.SetLabel(halving ? "canonical halving (peer)" : "refine_to");
}
BENCHMARK(BM_RefineRoots)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
