// C-space construction and query benchmarks (Google Benchmark).
//   BM_GenevaCSpace            the paper's Geneva pair, exact C-space (charts in parallel; real time)
//   BM_GenevaCSpaceSingleThread  the same on one thread
//   BM_SpurGearsCSpace/n       spur gear pair with n x n teeth on the full torus
//                              (examples/models/spur-gears.json); n = 4, 6, and with
//                              HIPAIR_BENCH_GEARS="8,10" in the environment also those
//   BM_EscapementCSpace        escape wheel and anchor: many arcs
//   BM_GenevaLocate            exact point location of random rational configurations
//   BM_GenevaFirstCrossing     certified first contact along random straight paths
// Peer comparisons: minkowski_peer_benchmark.cpp, overlap_peer_benchmark.cpp.
// Counters: vertices, edges, cells, curves of the built space.
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

namespace {

using namespace hipair;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

void report(benchmark::State& state, const CSpace& space) {
  const CSpaceStatistics& s = space.statistics();
  state.counters["vertices"] = static_cast<double>(s.vertices);
  state.counters["edges"] = static_cast<double>(s.edges);
  state.counters["cells"] = static_cast<double>(s.cells);
  state.counters["curves"] = static_cast<double>(s.curves);
}

void build(benchmark::State& state, const Model& model, const char* first, const char* second,
           unsigned threads = 0) {
  CSpace space;
  CSpaceBuildOptions options;
  options.threads = threads;
  for (auto _ : state) {
    space = CSpace::build(model, first, second, options);
    benchmark::DoNotOptimize(space);
  }
  report(state, space);
}

void BM_GenevaCSpace(benchmark::State& state) {
  Model model = read_model_file(example("geneva.json"));
  build(state, model, "driver", "wheel");
}
BENCHMARK(BM_GenevaCSpace)->Unit(benchmark::kMillisecond)->MinTime(3)->UseRealTime();

void BM_GenevaCSpaceSingleThread(benchmark::State& state) {
  Model model = read_model_file(example("geneva.json"));
  build(state, model, "driver", "wheel", 1);
}
BENCHMARK(BM_GenevaCSpaceSingleThread)->Unit(benchmark::kMillisecond)->MinTime(3);

void BM_SpurGearsCSpace(benchmark::State& state) {
  ReadOptions options;
  options.parameter_values["teeth-1"] = Rational(state.range(0));
  options.parameter_values["teeth-2"] = Rational(state.range(0));
  options.allow_out_of_tolerance = true;
  Model model = read_model_file(example("spur-gears.json"), options);
  build(state, model, "pinion", "gear", 1);
  state.counters["teeth"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_SpurGearsCSpace)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond)->Iterations(1);

// Larger gears take minutes each: only on request (HIPAIR_BENCH_GEARS="8,10").
const bool larger_gears_registered = [] {
  const char* list = std::getenv("HIPAIR_BENCH_GEARS");
  if (!list) return false;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ','))
    if (!item.empty())
      benchmark::RegisterBenchmark("BM_SpurGearsCSpace", BM_SpurGearsCSpace)
          ->Arg(std::stol(item))
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
  return true;
}();

void BM_EscapementCSpace(benchmark::State& state) {
  Model model = read_model_file(example("escapement.json"));
  build(state, model, "escape-wheel", "anchor", 1);
}
BENCHMARK(BM_EscapementCSpace)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_GenevaLocate(benchmark::State& state) {
  static const CSpace space = CSpace::build(read_model_file(example("geneva.json")), "driver", "wheel");
  std::mt19937_64 random(5);
  for (auto _ : state) {
    std::size_t c = random() % space.charts().size();
    ChartPoint q{c, Rational(static_cast<long>(random() % 200001) - 100000, 100000),
                 Rational(static_cast<long>(random() % 200001) - 100000, 100000)};
    q.x.canonicalize();
    q.y.canonicalize();
    benchmark::DoNotOptimize(space.locate(q));
  }
}
BENCHMARK(BM_GenevaLocate)->Unit(benchmark::kMicrosecond);

void BM_GenevaFirstCrossing(benchmark::State& state) {
  static const CSpace space = CSpace::build(read_model_file(example("geneva.json")), "driver", "wheel");
  std::mt19937_64 random(6);
  for (auto _ : state) {
    std::size_t c = random() % space.charts().size();
    auto value = [&] {
      Rational r(static_cast<long>(random() % 2001) - 1000, 1000);
      r.canonicalize();
      return r;
    };
    ChartPoint from{c, value(), value()};
    benchmark::DoNotOptimize(space.first_crossing(from, value(), value()));
  }
}
BENCHMARK(BM_GenevaFirstCrossing)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
