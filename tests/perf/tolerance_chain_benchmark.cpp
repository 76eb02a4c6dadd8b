// Tolerance analysis of assembly chains (docs/performance.md "Issue 12, session 10: chains"):
// generated lift chains (tests/unit/tolerance_chain_models.hpp: an eccentric cam under a chain of
// lifters, each lifter's face on toleranced shims) with `pairs` pairs and `per_pair` toleranced
// shims per pair (plus the cam's eccentricity), analysed over one turn at 360 positions on one
// thread (no Monte Carlo). The paper claims time grows as pairs x parameters per pair; the
// counters give the CPU time of the whole analysis and of its certified band.
// Gear trains (BM_GearTrain; docs/performance.md "Issue 12, session 12: gear trains"): the idler
// trains of examples/models/gear-train.py (tests/unit/gear_train_models.hpp), `gears` gears of
// `z` and `z` + 2 teeth alternating (11 toleranced parameters per gear + the module), over
// 0..0.1 rad of the first gear at 120 positions per turn, one thread, one iteration each. Third
// argument: 1 the kernel path (session 13: kinematics sliced from the contact kernels, the touching
// feature pair named by the exact engine, no C-space built), 0 its peer, every mesh's exact
// C-space built (the path before session 13: seconds per mesh). 9 gears of 10/12 teeth are
// examples/models/gear-train.json (100 toleranced parameters).
#include "gear_train_models.hpp"
#include "tolerance_chain_models.hpp"

#include "tolerance/stage.hpp"

#include <hipair/tolerance.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>

namespace {

double process_cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The analysis of `model` once per iteration; `cpu`: the last one's process CPU seconds.
hipair::ToleranceResult measure(benchmark::State& state, const std::string& model, const hipair::ToleranceOptions& options,
                                double& cpu, const hipair::tolerance_detail::ChainPaths* paths = nullptr) {
  hipair::ToleranceResult result;
  for (auto _ : state) {
    double c0 = process_cpu();
    result = paths ? hipair::tolerance_detail::analyze_chain(model, options, *paths)
                   : hipair::analyze_tolerances_text(model, options);
    cpu = process_cpu() - c0;
    benchmark::DoNotOptimize(result.samples.data());
  }
  return result;
}

// `pairs` pairs with `per_pair` shims each; chain = false: the peer, the single-pair analysis of
// one pair carrying the same number of shims (pairs = 1, per_pair = their total).
void run(benchmark::State& state, std::size_t pairs, std::size_t per_pair, bool chain) {
  std::mt19937 rng(1);
  std::string model = hipair::test_chain::lift_chain(pairs, per_pair, rng, false).json;
  hipair::ToleranceOptions options;
  options.driver = "cam";
  options.chain = chain;
  options.positions = 360;
  options.threads = 1;
  double cpu = 0;
  hipair::ToleranceResult result = measure(state, model, options, cpu);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["toleranced"] = static_cast<double>(pairs * per_pair + 1);
  state.counters["cpu_ms"] = 1e3 * cpu;
  state.counters["certified_cpu_ms"] = 1e3 * result.cpu_seconds_certified;
}

void BM_LiftChain(benchmark::State& state) {
  run(state, static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)), true);
}

void BM_OnePairPeer(benchmark::State& state) { run(state, 1, static_cast<std::size_t>(state.range(0)), false); }

void BM_GearTrain(benchmark::State& state) {
  auto gears = static_cast<unsigned>(state.range(0));
  auto z = static_cast<unsigned>(state.range(1));
  std::string model = hipair::test_gears::gear_train(gears, z, z + 2);
  hipair::ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = std::pair(hipair::Rational(0), hipair::Rational(1, 10));
  options.positions = 120;
  options.threads = 1;
  hipair::tolerance_detail::ChainPaths paths;
  paths.kernel_kinematics = state.range(2) != 0;
  double cpu = 0;
  hipair::ToleranceResult result = measure(state, model, options, cpu, &paths);
  std::size_t bounded = 0, held = 0;
  for (const hipair::VariationSample& s : result.samples)
    if (s.contact) {
      ++held;
      bounded += std::isfinite(s.certified.upper - s.certified.lower) ? 1 : 0;
    }
  state.counters["meshes"] = gears - 1;
  state.counters["toleranced"] = 11.0 * gears + 1;   // 11 per gear + the module (gear-train.json: 100)
  state.counters["kernel"] = static_cast<double>(state.range(2));
  state.counters["cpu_ms"] = 1e3 * cpu;
  state.counters["certified_cpu_ms"] = 1e3 * result.cpu_seconds_certified;
  state.counters["held"] = static_cast<double>(held);
  state.counters["bounded"] = static_cast<double>(bounded);
}

BENCHMARK(BM_GearTrain)
    ->ArgsProduct({{2, 3, 4, 5, 6, 7, 8, 9}, {10}, {1}})
    ->Args({2, 20, 1})
    ->Args({2, 10, 0})
    ->Args({3, 10, 0})
    ->Args({2, 20, 0})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_LiftChain)
    ->ArgsProduct({{1, 2, 3, 4, 5}, {5, 10, 20}})
    ->Args({4, 25})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OnePairPeer)->Arg(5)->Arg(20)->Arg(50)->Arg(100)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
