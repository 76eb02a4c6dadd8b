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
#include <limits>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

TEST(SimulationCrossingLimit, RunsEqualTheRunsWithCompleteQueries) {
  const std::size_t limited_before = simulation::limited_queries(), requeried_before = simulation::requeried_limits();
  const test::SideBySide total =
      test::runs_side_by_side<simulation::crossing_limits>(HIPAIR_EXAMPLES,
                                                           {{"escapement.json", 0.5, 1e-3},
                                                            {"escapement.json", 0.25, 1e-6},
                                                            {"geneva-drive.json", 1.0, 1e-3},
                                                            {"geneva-drive.json", 0.5, 1e-6},
                                                            {"bouncing-bar.json", 0.5, 1e-3},
                                                            {"cam-drive.json", 0.5, 1e-3}},
                                                           std::numeric_limits<std::size_t>::max());
  const std::size_t steps = total.steps, events = total.events;
  const std::size_t limited_queries = simulation::limited_queries() - limited_before;
  const std::size_t requeried = simulation::requeried_limits() - requeried_before;
  std::printf("crossing limits: %zu steps, %zu events equal; %zu queries stopped at their limit, %zu of them resumed\n",
              steps, events, limited_queries, requeried);
  EXPECT_GT(limited_queries, 20u);
}

}  // namespace
}  // namespace hipair
