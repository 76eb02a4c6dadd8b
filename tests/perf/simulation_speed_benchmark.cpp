// Simulated seconds per CPU second of HIPAIR's simulator (issue 11's speed goal: >= 100x real
// time at 0.1 % accuracy; docs/performance.md, "Session 8: simulator speed").
//
// `hipair_simulation_speed [--benchmark_filter=...]`: the Geneva drive (examples/models/
// geneva-drive.json, driver at its prescribed 2 pi rad/s, 2 s = two drives and two dwells) and
// the escapement (examples/models/escapement.json, its own simulation section, 0.5 s) at
// accuracies 1e-3 (0.1 %), 1e-4, 1e-6 and 1e-9 (a run that stops with an error is reported as
// such). CPU time of the simulating thread for run_until alone (the C-space build is reported
// apart as setup_s). Counters: sim_s_per_cpu_s (the figure the goal is about), steps, events,
// setup_s. One translation unit without CGAL; not a ctest test.
//
// Session 13: also the Geneva pair driven by a motor torque (GenevaMotor: geneva-drive.json with
// its driver law replaced by inertia 1e5 kg mm^2, a constant torque of 100 N mm and an initial
// 2 pi rad/s), and every case twice in the same run, `carried:1` (first_crossing's carried
// double bounds, the default) and `carried:0` (the conversions from rationals as before,
// cspace::carried_bounds() off): the same answers, so the ratio is the speed-up.
#include "bench_paths.hpp"

#include "peer_timing.hpp"

#include "cspace/angle_filter.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace hipair {
namespace {

// The Geneva drive with a motor torque instead of its prescribed driver speed (see above).
Model geneva_motor() {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva-drive.json");
  nlohmann::json m = nlohmann::json::parse(in);
  m["simulation"].erase("drivers");
  m["simulation"]["velocities"] = {{"driver", "2*pi"}};
  for (auto& part : m["parts"])
    if (part["name"] == "driver") part["dynamics"] = {{"moment_of_inertia", 100000}, {"torque", 100}};
  return read_model(m.dump(), "geneva-motor");
}

void BM_Simulate(benchmark::State& state, const std::string& file, double t_end, double accuracy, bool carried) {
  Model model = file == "motor" ? geneva_motor() : read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
  cspace::carried_bounds() = carried;
  SimulationOptions options;
  options.accuracy = accuracy;
  double cpu = 0, setup = 0;
  std::size_t steps = 0, events = 0;
  for (auto _ : state) {
    double begin = bench::thread_cpu_seconds();
    Simulation s = Simulation::create(model, options);
    double start = bench::thread_cpu_seconds();
    setup = start - begin;
    try {
      s.run_until(t_end, [&](double) { ++steps; });
    } catch (const Error& error) {
      state.SkipWithError(error.what());
      return;
    }
    double elapsed = bench::thread_cpu_seconds() - start;
    cpu += elapsed;
    events = s.events().size();
    state.SetIterationTime(elapsed);
  }
  double runs = static_cast<double>(state.iterations());
  state.counters["sim_s_per_cpu_s"] = t_end * runs / cpu;
  state.counters["steps"] = static_cast<double>(steps) / runs;
  state.counters["events"] = static_cast<double>(events);
  state.counters["setup_s"] = setup;
  cspace::carried_bounds() = true;
}

void register_all() {
  struct Case {
    const char* name;
    const char* file;
    double t_end;
  };
  for (const Case& c : {Case{"Geneva", "geneva-drive.json", 2.0}, Case{"GenevaMotor", "motor", 2.0},
                        Case{"Escapement", "escapement.json", 0.5}})
    for (double accuracy : {1e-3, 1e-4, 1e-6, 1e-9})
      for (bool carried : {false, true}) {
        char name[96];
        std::snprintf(name, sizeof name, "BM_Simulate%s/accuracy:%.0e/carried:%d", c.name, accuracy, carried ? 1 : 0);
        benchmark::RegisterBenchmark(name, BM_Simulate, std::string(c.file), c.t_end, accuracy, carried)
            ->Iterations(1)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
      }
}

}  // namespace
}  // namespace hipair

int main(int argc, char** argv) {
  hipair::register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
