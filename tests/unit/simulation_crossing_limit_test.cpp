// The step's crossing queries with a limit (src/simulation/crossing_limit.hpp, switch
// simulation::crossing_limits()): the free pairs' queries run side by side
// (src/simulation/crossing_sweep.hpp), once a crossing is found they stop past its u_upper
// (hipair/crossing_before.hpp), and a stopped query that might still be simultaneous is resumed
// to its end. The oracle is the same simulation with every query
// complete: the two run side by side, step for step (the switch set per step), on the example
// models with several free pairs and with one, at two accuracies, and every state (time,
// positions, velocities: bit patterns) and every event (kind, pair, features, time, impulse)
// must be equal.
#include "simulation/crossing_limit.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

TEST(SimulationCrossingLimit, RunsEqualTheRunsWithCompleteQueries) {
  struct Case {
    const char* model;
    double t_end, accuracy;
  };
  const Case cases[] = {{"escapement.json", 0.5, 1e-3},    {"escapement.json", 0.25, 1e-6},
                        {"geneva-drive.json", 1.0, 1e-3}, {"geneva-drive.json", 0.5, 1e-6},
                        {"bouncing-bar.json", 0.5, 1e-3}, {"cam-drive.json", 0.5, 1e-3}};
  const std::size_t limited_before = simulation::limited_queries(), requeried_before = simulation::requeried_limits();
  std::size_t steps = 0, events = 0;
  for (const Case& c : cases) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.model);
    SimulationOptions options;
    options.accuracy = c.accuracy;
    const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy);
    test::SideBySide run = test::run_side_by_side<simulation::crossing_limits>(model, options, c.t_end, where);
    ASSERT_EQ(run.mismatch, "");
    ASSERT_EQ(run.error, "") << where;
    steps += run.steps;
    events += run.events;
  }
  const std::size_t limited_queries = simulation::limited_queries() - limited_before;
  const std::size_t requeried = simulation::requeried_limits() - requeried_before;
  std::printf("crossing limits: %zu steps, %zu events equal; %zu queries stopped at their limit, %zu of them resumed\n",
              steps, events, limited_queries, requeried);
  EXPECT_GT(limited_queries, 20u);
}

}  // namespace
}  // namespace hipair
