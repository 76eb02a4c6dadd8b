// Growth with the tooth count, and assemblies built in parallel (Google Benchmark).
//   BM_SpurGearsOperatingRegion/n   spur gear pair with n x n teeth (examples/models/spur-gears.json
//                                   with teeth-1 = teeth-2 = n), the exact C-space of the channel
//                                   the gears run in (CSpaceBuildOptions::operating_region). The
//                                   whole torus holds n^2 tooth encounters; the channel about n.
//   BM_EscapementAllPairs/threads   CSpace::build_all on the escapement's pairs, 1 or 2 threads.
//   BM_GearPairCliCold/k            issue 14's slow gear pairs (session 65, perf65) as a user runs
//                                   them: the `hipair` program in a fresh process (forked and
//                                   exec'd), the child's CPU time (user + system, wait4).
//                                   k = 0: `cspace --region operating`, 19 x 40 teeth at zero
//                                   backlash (its start overlaps: refused; base65 built the whole
//                                   channel first, 38 s); 1: the same pair at the model's backlash
//                                   0.1 mm (coprime tooth counts: the channel meets all 760 tooth
//                                   pairs, 8 058 tiles); 2: `analyze --no-pictures`, 39 x 31 teeth
//                                   at zero backlash (a full turn of the pinion).
// CPU time of the building thread is what Google Benchmark reports for the gears (single thread).
#include "bench_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

void BM_GearPairCliCold(benchmark::State& state) {
  const std::string model = example("spur-gears.json").string();
  char directory[] = "/tmp/hipair-gear-bench-XXXXXX";
  if (mkdtemp(directory) == nullptr) {
    state.SkipWithError("mkdtemp failed");
    return;
  }
  std::vector<std::string> args{HIPAIR_CLI};
  switch (state.range(0)) {
    case 0:
      args.insert(args.end(), {"cspace", model, "--set", "teeth-1=19", "--set", "teeth-2=40", "--set", "backlash=0",
                               "--allow-out-of-tolerance", "--region", "operating"});
      break;
    case 1:
      args.insert(args.end(), {"cspace", model, "--set", "teeth-1=19", "--set", "teeth-2=40", "--allow-out-of-tolerance",
                               "--region", "operating", "--json", std::string(directory) + "/region.json"});
      break;
    default:
      args.insert(args.end(), {"analyze", model, "--set", "teeth-1=39", "--set", "teeth-2=31", "--set", "backlash=0",
                               "--allow-out-of-tolerance", "--no-pictures", "--quiet", "--out", std::string(directory) + "/a"});
      break;
  }
  const int expected = state.range(0) == 0 ? 3 : 0;   // the overlapping start is refused (exit 3)
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  for (auto _ : state) {
    pid_t child = fork();
    if (child == 0) {
      // the program's own output is not the benchmark's
      if (freopen("/dev/null", "w", stdout) == nullptr || freopen("/dev/null", "w", stderr) == nullptr) _exit(127);
      execv(argv[0], argv.data());
      _exit(127);
    }
    int status = 0;
    rusage usage{};
    wait4(child, &status, 0, &usage);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != expected) {
      state.SkipWithError("the hipair run did not end as expected");
      break;
    }
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    state.SetIterationTime(seconds(usage.ru_utime) + seconds(usage.ru_stime));
    state.counters["max_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
  }
  std::filesystem::remove_all(directory);
}
BENCHMARK(BM_GearPairCliCold)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1);

}  // namespace
