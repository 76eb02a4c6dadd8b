// Growth with the tooth count, and assemblies built in parallel (Google Benchmark).
//   BM_SpurGearsOperatingRegion/n   spur gear pair with n x n teeth (examples/models/spur-gears.json
//                                   with teeth-1 = teeth-2 = n), the exact C-space of the channel
//                                   the gears run in (CSpaceBuildOptions::operating_region). The
//                                   whole torus holds n^2 tooth encounters; the channel about n.
//   BM_EscapementAllPairs/threads   CSpace::build_all on the escapement's pairs, 1 or 2 threads.
// CPU time of the building thread is what Google Benchmark reports for the gears (single thread).
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>

namespace {

using namespace hipair;

std::filesystem::path example(const std::string& name) {
  return std::filesystem::path(HIPAIR_EXAMPLES) / name;
}

void BM_SpurGearsOperatingRegion(benchmark::State& state) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(state.range(0));
  read.parameter_values["teeth-2"] = Rational(state.range(0));
  read.allow_out_of_tolerance = true;
  Model model = read_model_file(example("spur-gears.json"), read);
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.threads = 1;
  CSpace space;
  for (auto _ : state) {
    space = CSpace::build(model, "pinion", "gear", options);
    benchmark::DoNotOptimize(space);
  }
  const CSpaceStatistics& s = space.statistics();
  state.counters["teeth"] = static_cast<double>(state.range(0));
  state.counters["tiles"] = static_cast<double>(s.region_tiles);
  state.counters["curves"] = static_cast<double>(s.curves);
  state.counters["contact_edges"] = static_cast<double>(s.contact_edges);
  state.counters["cells"] = static_cast<double>(s.cells);
}
BENCHMARK(BM_SpurGearsOperatingRegion)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_EscapementAllPairs(benchmark::State& state) {
  Model model = read_model_file(example("escapement.json"));
  CSpaceBuildOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  std::size_t pairs = 0;
  for (auto _ : state) {
    auto spaces = CSpace::build_all(model, options);
    pairs = spaces.size();
    benchmark::DoNotOptimize(spaces);
  }
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_EscapementAllPairs)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();

}  // namespace
