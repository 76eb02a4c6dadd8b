// The step's crossing queries with a limit (src/simulation/crossing_limit.hpp, switch
// simulation::crossing_limits()): the free pairs' queries run side by side
// (src/simulation/crossing_sweep.hpp), once a crossing is found they stop past its u_upper
// (hipair/crossing_before.hpp), and a stopped query that might still be simultaneous is resumed
// to its end. The oracle is the same simulation with every query
// complete: the two run side by side, step for step (the switch set per step), on the example
// models with several free pairs and with one, at two accuracies, and every state (time,
// positions, velocities: bit patterns) and every event (kind, pair, features, time, impulse)
// must be equal.
#include "cspace_test_support.hpp"
#include "simulation/crossing_limit.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

using LimitSwitch = test::FlagSwitch<simulation::crossing_limits>;

std::string describe(const SimulationEvent& e) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s pair %zu t %a impulse %a", to_string(e.kind).c_str(), e.pair, e.time, e.impulse);
  std::string text = buffer;
  for (const std::string& f : e.features) text += " " + f;
  return text;
}

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
    Simulation limited = Simulation::create(model, options), complete = Simulation::create(model, options);
    while (limited.state().time < c.t_end) {
      {
        LimitSwitch on(true);
        limited.step();
      }
      {
        LimitSwitch off(false);
        complete.step();
      }
      ++steps;
      const SimulationState &a = limited.state(), &b = complete.state();
      const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy) + ", step " + std::to_string(steps);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.time), std::bit_cast<std::uint64_t>(b.time)) << where;
      ASSERT_EQ(a.position.size(), b.position.size()) << where;
      for (std::size_t i = 0; i < a.position.size(); ++i) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.position[i]), std::bit_cast<std::uint64_t>(b.position[i])) << where << " part " << i;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.velocity[i]), std::bit_cast<std::uint64_t>(b.velocity[i])) << where << " part " << i;
      }
      ASSERT_EQ(limited.events().size(), complete.events().size()) << where;
      for (std::size_t k = 0; k < limited.events().size(); ++k)
        ASSERT_EQ(describe(limited.events()[k]), describe(complete.events()[k])) << where << " event " << k;
    }
    events += limited.events().size();
  }
  const std::size_t limited_queries = simulation::limited_queries() - limited_before;
  const std::size_t requeried = simulation::requeried_limits() - requeried_before;
  std::printf("crossing limits: %zu steps, %zu events equal; %zu queries stopped at their limit, %zu of them resumed\n",
              steps, events, limited_queries, requeried);
  EXPECT_GT(limited_queries, 20u);
}

}  // namespace
}  // namespace hipair
