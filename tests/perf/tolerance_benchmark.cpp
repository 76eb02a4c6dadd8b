// Tolerance analysis performance (issue 12's goals; docs/performance.md "Tolerance analysis"):
// the Geneva pair's 26-parameter contact zones (goal <= 100 ms), Monte Carlo kinematic
// functions per second on 2 cores (goal >= 200, each at >= 360 driver positions), the certified
// band. Each benchmark runs the whole analysis once per iteration (the nominal C-space build
// included) and reports the phases' CPU times as counters; `/former` takes the paths of
// session 7 (ToleranceOptions::fast_paths = false) in the same run, for the ratio.
// One translation unit without CGAL. Not a ctest test.
#include "bench_paths.hpp"

#include <hipair/tolerance.hpp>

#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <string>

namespace {

void run(benchmark::State& state, bool fast, std::size_t positions, std::size_t samples) {
  hipair::ToleranceOptions options;
  options.positions = positions;
  options.monte_carlo = samples;
  options.seed = 7;
  options.threads = 2;
  options.fast_paths = fast;
  hipair::ToleranceResult result;
  for (auto _ : state) {
    result = hipair::analyze_tolerances(std::string(HIPAIR_EXAMPLES) + "/geneva.json", options);
    benchmark::DoNotOptimize(result.samples.data());
  }
  std::size_t contact = 0;
  for (const hipair::VariationSample& s : result.samples) contact += s.contact;
  state.counters["positions"] = static_cast<double>(result.samples.size());
  state.counters["contact_positions"] = static_cast<double>(contact);
  state.counters["zones_cpu_ms"] = 1e3 * result.cpu_seconds_zones;
  state.counters["zones_wall_ms"] = 1e3 * result.seconds_zones;
  state.counters["certified_cpu_ms"] = 1e3 * result.cpu_seconds_certified;
  state.counters["boxes"] = static_cast<double>(result.certified_boxes);
  if (result.monte_carlo) {
    const hipair::MonteCarloSummary& mc = *result.monte_carlo;
    state.counters["mc_functions_per_wall_s"] = static_cast<double>(mc.samples) / mc.seconds;
    // on 2 cores: twice the single-core rate the CPU time gives (the machine is shared)
    state.counters["mc_functions_per_s_2cores_cpu"] = 2 * static_cast<double>(mc.samples) / mc.cpu_seconds;
    state.counters["mc_outside_certified"] = static_cast<double>(mc.outside_certified);
    state.counters["mc_not_certified"] = static_cast<double>(mc.not_certified);
  }
}

void BM_GenevaTolerance_Fast(benchmark::State& state) {
  run(state, true, static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
}
void BM_GenevaTolerance_Former(benchmark::State& state) {
  run(state, false, static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
}

BENCHMARK(BM_GenevaTolerance_Former)->Args({360, 400})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_GenevaTolerance_Fast)->Args({360, 400})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_GenevaTolerance_Former)->Args({1440, 200})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_GenevaTolerance_Fast)->Args({1440, 200})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// Growth with the parameter count on one pair: examples/models/cam-shim-stack.json (an eccentric
// cam under a face on 99 toleranced shims: 101 parameters, 100 toleranced) cut to its first
// n - 1 shims by setting the others' tolerances to 0 (fixed at nominal).
void BM_ShimStack(benchmark::State& state) {
  int toleranced = static_cast<int>(state.range(0));   // e and toleranced - 1 shims
  std::ifstream file(std::string(HIPAIR_EXAMPLES) + "/cam-shim-stack.json");
  std::stringstream text;
  text << file.rdbuf();
  std::string model = text.str();
  for (int i = toleranced; i < 100; ++i) {
    std::string from = "\"shim" + std::to_string(i) + "\": {\n   \"nominal\": \"1/5\",\n   \"tolerance\": 0.002";
    std::size_t at = model.find(from);
    if (at == std::string::npos) {
      state.SkipWithError("unexpected layout of cam-shim-stack.json");
      return;
    }
    model.replace(at, from.size(), "\"shim" + std::to_string(i) + "\": {\n   \"nominal\": \"1/5\",\n   \"tolerance\": 0");
  }
  hipair::ToleranceOptions options;
  options.driver = "cam";
  options.positions = 360;
  options.threads = 1;
  hipair::ToleranceResult result;
  for (auto _ : state) {
    result = hipair::analyze_tolerances_text(model, options);
    benchmark::DoNotOptimize(result.samples.data());
  }
  state.counters["toleranced"] = toleranced;
  state.counters["certified_cpu_ms"] = 1e3 * result.cpu_seconds_certified;
  state.counters["zones_cpu_ms"] = 1e3 * result.cpu_seconds_zones;
}
BENCHMARK(BM_ShimStack)->Arg(10)->Arg(25)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
