// C-space construction and query benchmarks (Google Benchmark).
//   BM_GenevaCSpaceCold        the Geneva build in a fresh process (cold CGAL caches): child CPU
//                              time of a forked single-thread build; runs first, skipped if
//                              something already built in this process
//   BM_CSpaceColdTraits/m/t    cold builds (forked) of Geneva, ratchet, escapement (m = 0, 1, 2) with
//                              the algebraic (t = 0) or the quadratic traits (t = 1)
//   BM_GenevaCSpace            the paper's Geneva pair, exact C-space (charts in parallel; real time)
//   BM_GenevaCSpaceSingleThread  the same on one thread
//   BM_SpurGearsCSpace/n       spur gear pair with n x n teeth on the full torus
//                              (examples/models/spur-gears.json); n = 4, 6, and with
//                              HIPAIR_BENCH_GEARS="8,10" in the environment also those
//   BM_EscapementCSpace        escape wheel and anchor: many arcs
//   BM_GenevaLocate            exact point location of random rational configurations
//   BM_GenevaFirstCrossing     certified first contact along random straight paths
//   BM_GenevaCurves            stage alone: contact-curve generation (all charts, with the merged
//                              cull's grid of each chart as the builder gives it)
//   BM_GenevaCgalStage         stage alone: CGAL clipping, insertion and export (all charts)
//   BM_ArrangementStage/m/t    the arrangement stage alone on the charts of model m (0 Geneva,
//                              1 ratchet, 2 escapement wheel:anchor) that the quadratic traits
//                              accepts: t = 0 CGAL's algebraic traits, t = 1 the filtered
//                              quadratic traits (side by side: the ratio is the figure)
// Peer comparisons: minkowski_peer_benchmark.cpp, overlap_peer_benchmark.cpp.
// Counters: vertices, edges, cells, curves of the built space.
#include "bench_paths.hpp"

#include "arrangement/circle_segment_traits.hpp"
#include "arrangement/quadratic_traits.hpp"
#include "cspace/builder_impl.hpp"
#include "oracle/blocked_tester.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <string>

namespace {

using namespace hipair;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// True once this process has built a C-space: CGAL's algebraic kernel keeps global caches of
// curve analyses, so later builds of the same curves are warm.
bool built_in_process = false;

// Mean stage times of the builds (ms), as printed by --stats.
struct StageTimes {
  double curves = 0, culling = 0, clipping = 0, arrangement = 0, export_ = 0, labelling = 0, classification = 0,
         cells = 0;
  void add(const CSpaceStatistics& s) {
    curves += s.seconds_curves;
    culling += s.seconds_culling;
    clipping += s.seconds_clipping;
    arrangement += s.seconds_arrangement;
    export_ += s.seconds_export;
    labelling += s.seconds_labelling;
    classification += s.seconds_classification;
    cells += s.seconds_cells;
  }
};

void report(benchmark::State& state, const CSpace& space, const StageTimes& times) {
  const CSpaceStatistics& s = space.statistics();
  state.counters["vertices"] = static_cast<double>(s.vertices);
  state.counters["edges"] = static_cast<double>(s.edges);
  state.counters["cells"] = static_cast<double>(s.cells);
  state.counters["curves"] = static_cast<double>(s.curves);
  const double per = 1e3 / static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["ms_curves"] = times.curves * per;
  state.counters["ms_culling"] = times.culling * per;
  state.counters["ms_clipping"] = times.clipping * per;
  state.counters["ms_arrangement"] = times.arrangement * per;
  state.counters["ms_export"] = times.export_ * per;
  state.counters["ms_labelling"] = times.labelling * per;
  state.counters["ms_classify_cells"] = (times.classification + times.cells) * per;
}

void build(benchmark::State& state, const Model& model, const char* first, const char* second,
           unsigned threads = 0) {
  CSpace space;
  CSpaceBuildOptions options;
  options.threads = threads;
  StageTimes times;
  built_in_process = true;
  for (auto _ : state) {
    space = CSpace::build(model, first, second, options);
    benchmark::DoNotOptimize(space);
    times.add(space.statistics());
  }
  report(state, space, times);
}

// The Geneva build as a fresh process sees it (cold CGAL caches): each iteration forks, the
// child builds once on one thread and exits; the time is the child's CPU time (user + system,
// from wait4), and the counters are its stage times (ms, wall clock of the child).
// Must run before anything else builds in this process (it is registered first).
void cold_build(benchmark::State& state, const char* file, const char* first, const char* second, bool quadratic) {
  if (built_in_process) {
    state.SkipWithError("CGAL caches are already warm: run with --benchmark_filter=Cold");
    return;
  }
  Model model = read_model_file(example(file));
  StageTimes times;
  std::size_t vertices = 0;
  for (auto _ : state) {
    int channel[2];
    if (pipe(channel) != 0) {
      state.SkipWithError("pipe failed");
      return;
    }
    pid_t child = fork();
    if (child == 0) {
      close(channel[0]);
      CSpaceBuildOptions options;
      options.threads = 1;
      options.quadratic_traits = quadratic;
      CSpace space = CSpace::build(model, first, second, options);
      const CSpaceStatistics& s = space.statistics();
      double values[9] = {s.seconds_curves, s.seconds_culling, s.seconds_clipping, s.seconds_arrangement,
                          s.seconds_export, s.seconds_labelling, s.seconds_classification, s.seconds_cells,
                          static_cast<double>(s.vertices)};
      ssize_t written = write(channel[1], values, sizeof values);
      _exit(written == static_cast<ssize_t>(sizeof values) ? 0 : 1);
    }
    close(channel[1]);
    double values[9] = {};
    ssize_t got = read(channel[0], values, sizeof values);
    close(channel[0]);
    int status = 0;
    rusage usage{};
    wait4(child, &status, 0, &usage);
    if (got != static_cast<ssize_t>(sizeof values) || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      state.SkipWithError("the child build failed");
      return;
    }
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    state.SetIterationTime(seconds(usage.ru_utime) + seconds(usage.ru_stime));
    CSpaceStatistics s;
    s.seconds_curves = values[0];
    s.seconds_culling = values[1];
    s.seconds_clipping = values[2];
    s.seconds_arrangement = values[3];
    s.seconds_export = values[4];
    s.seconds_labelling = values[5];
    s.seconds_classification = values[6];
    s.seconds_cells = values[7];
    times.add(s);
    vertices = static_cast<std::size_t>(values[8]);
  }
  const double per = 1e3 / static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["ms_curves"] = times.curves * per;
  state.counters["ms_culling"] = times.culling * per;
  state.counters["ms_clipping"] = times.clipping * per;
  state.counters["ms_arrangement"] = times.arrangement * per;
  state.counters["ms_export"] = times.export_ * per;
  state.counters["ms_labelling"] = times.labelling * per;
  state.counters["ms_classify_cells"] = (times.classification + times.cells) * per;
}
void BM_GenevaCSpaceCold(benchmark::State& state) { cold_build(state, "geneva.json", "driver", "wheel", true); }
BENCHMARK(BM_GenevaCSpaceCold)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(5);

// The same cold build of Geneva (0), the ratchet (1) and the escapement's wheel and anchor (2)
// with CGAL's algebraic traits (t = 0) and with the filtered quadratic traits (t = 1), side by
// side (CPU time of the child; counters: its stage times).
void BM_CSpaceColdTraits(benchmark::State& state) {
  static const char* const cases[3][3] = {
      {"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"}, {"escapement.json", "escape-wheel", "anchor"}};
  const auto* c = cases[state.range(0)];
  cold_build(state, c[0], c[1], c[2], state.range(1) == 1);
}
BENCHMARK(BM_CSpaceColdTraits)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);

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

// Stages of the Geneva build that can run alone: contact-curve generation for every chart,
// and the CGAL stage (curve analysis, clipping, insertion, export) on the charts' curves and
// windows as the builder passed them.
void BM_GenevaCurves(benchmark::State& state) {
  Model model = read_model_file(example("geneva.json"));
  built_in_process = true;   // (no CGAL here, but keep the cold figure honest)
  auto axes = cspace::pair_axes(model, 0, 1);
  auto layout = cspace::chart_layout(model, axes);
  std::size_t curves = 0, tests = 0;
  // as the builder does: per-pair data once, and the merged cull's grid of each chart (the
  // generator's part of the cull: the grid's blocked tests made before any polynomial)
  cspace::CurveOptions options;
  options.blocked_grid = true;
  auto tester = std::make_shared<const cspace::BlockedTester>(model, axes);
  for (auto _ : state) {
    curves = tests = 0;
    cspace::CurveGenerator generator(model, axes, options);
    for (const auto& x : layout.x_charts)
      for (const auto& y : layout.y_charts) {
        cspace::BlockedCells grid(tester, x, y, 2, 9);
        curves += generator.generate(x, y, nullptr, &grid).size();
        tests += grid.tests();
      }
  }
  state.counters["curves"] = static_cast<double>(curves);
  state.counters["blocked_tests"] = static_cast<double>(tests);
}
BENCHMARK(BM_GenevaCurves)->Unit(benchmark::kMillisecond);

void BM_GenevaCgalStage(benchmark::State& state) {
  built_in_process = true;
  static const CSpace space = CSpace::build(read_model_file(example("geneva.json")), "driver", "wheel");
  const auto& charts = cspace::impl_of(space).charts;
  double clipping = 0, insertion = 0, export_ = 0;
  std::size_t vertices = 0;
  for (auto _ : state) {
    vertices = 0;
    for (const auto& chart : charts) {
      auto arrangement = cspace::raw::build_arrangement(chart.box, chart.polynomials, chart.validity, chart.windows, {});
      clipping += arrangement.times.curves_seconds;
      insertion += arrangement.times.insertion_seconds;
      export_ += arrangement.times.export_seconds;
      vertices += arrangement.vertices.size();
    }
  }
  const double per = 1e3 / static_cast<double>(state.iterations());
  state.counters["ms_clipping"] = clipping * per;
  state.counters["ms_arrangement"] = insertion * per;
  state.counters["ms_export"] = export_ * per;
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_GenevaCgalStage)->Unit(benchmark::kMillisecond);

struct StageCase {
  const char* file;
  const char* first;
  const char* second;
};
const StageCase stage_cases[] = {
    {"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"}, {"escapement.json", "escape-wheel", "anchor"}};

void BM_ArrangementStage(benchmark::State& state) {
  built_in_process = true;
  const auto which = static_cast<std::size_t>(state.range(0));
  const bool quadratic = state.range(1) == 1;
  static std::map<std::size_t, CSpace> spaces;
  if (!spaces.count(which)) {
    CSpaceBuildOptions options;
    options.quadratic_traits = false;
    const StageCase& c = stage_cases[which];
    spaces.emplace(which, CSpace::build(read_model_file(example(c.file)), c.first, c.second, options));
  }
  std::vector<const cspace::ChartData*> charts;   // those the quadratic traits accepts
  for (const auto& chart : cspace::impl_of(spaces.at(which)).charts)
    if (!cspace::raw::circle_segment_applies(chart.polynomials, chart.validity) &&
        cspace::raw::build_quadratic_arrangement(chart.box, chart.polynomials, chart.validity, chart.windows, {}))
      charts.push_back(&chart);
  double clipping = 0, insertion = 0, export_ = 0;
  std::size_t vertices = 0;
  for (auto _ : state) {
    vertices = 0;
    for (const auto* chart : charts) {
      auto arrangement =
          quadratic ? *cspace::raw::build_quadratic_arrangement(chart->box, chart->polynomials, chart->validity,
                                                                chart->windows, {})
                    : cspace::raw::build_arrangement(chart->box, chart->polynomials, chart->validity, chart->windows, {});
      clipping += arrangement.times.curves_seconds;
      insertion += arrangement.times.insertion_seconds;
      export_ += arrangement.times.export_seconds;
      vertices += arrangement.vertices.size();
    }
  }
  const double per = 1e3 / static_cast<double>(state.iterations());
  state.counters["charts"] = static_cast<double>(charts.size());
  state.counters["ms_clipping"] = clipping * per;
  state.counters["ms_arrangement"] = insertion * per;
  state.counters["ms_export"] = export_ * per;
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_ArrangementStage)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_GenevaLocate(benchmark::State& state) {
  built_in_process = true;
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
  built_in_process = true;
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
