// Kernel slicer benchmarks (Google Benchmark), issue 14 item 5 (initial_state's fixed cost):
//   BM_GearsFirstSlice/0   the first slice of the 18 x 27 spur gears (examples/models) at the
//                          pinion's initial angle by a fresh kernel slicer that generates the
//                          chart pair's curves per strip of the pinion's axis (the default);
//                          the counter `ratio` is its CPU time over the peer's: the same slice
//                          by a slicer generating the whole chart pair (the slicer before
//                          session 12), measured in the same process
//   BM_GearsShortAnalyze   hipair::analyze_kinematics of the gears over the driver range
//                          0:0.005 rad (`hipair analyze --range 0:0.005`): initial_state's cost
#include "bench_paths.hpp"

#include "kinematics/slice.hpp"
#include "peer_timing.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>

namespace {

using namespace hipair;
using namespace hipair::kinematics_detail;

Model gears() { return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json"); }

void first_slice(const Model& model, bool strips) {
  std::size_t follower = model.pairs[0].second;
  auto slicer = make_kernel_slicer(model, 0, follower, KernelSlicerOptions{strips});
  ChartSlice slice = slicer->slice(0, Rational(0), 0);
  benchmark::DoNotOptimize(slice);
}

void BM_GearsFirstSlice(benchmark::State& state) {
  Model model = gears();
  double start = bench::thread_cpu_seconds();
  first_slice(model, false);
  double peer = bench::thread_cpu_seconds() - start;
  start = bench::thread_cpu_seconds();
  for (auto _ : state) first_slice(model, true);
  double ours = (bench::thread_cpu_seconds() - start) / static_cast<double>(state.iterations());
  state.counters["peer_ms"] = peer * 1e3;
  state.counters["ratio"] = ours / peer;
}
BENCHMARK(BM_GearsFirstSlice)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_GearsShortAnalyze(benchmark::State& state) {
  Model model = gears();
  KinematicsOptions options;
  options.steps_per_cycle = 720;   // the CLI's default
  options.range = std::make_pair(Rational(0), Rational(1, 200));
  for (auto _ : state) {
    KinematicsResult result = analyze_kinematics(model, options);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_GearsShortAnalyze)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
