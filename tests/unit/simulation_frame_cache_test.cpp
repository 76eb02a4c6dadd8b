// friction_of's contact frames remembered within a step (src/simulation/frame_cache.hpp, switch
// simulation::frame_cache()). The oracle is the same simulation with every frame computed anew:
// the two run side by side, step for step (tests/unit/simulation_side_by_side.hpp), and every
// state (time, positions, velocities: bit patterns) and every event (every field) must be
// equal — on the example models with frictional pairs (the escapement at two accuracies, the
// ratchet driven either way, a cam with a follower in a guide, a scotch yoke) and on generated
// initial states of the escapement and the ratchet (random angles and velocities, random
// driving torques), where the cache must also have answered.
#include "simulation/frame_cache.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

Model example(const std::string& name) { return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name); }

TEST(SimulationFrameCache, ExampleRunsEqualTheRunsWithoutIt) {
  struct Case {
    const char* model;
    double t_end, accuracy, torque;   // torque: the first part's, NaN: the model's
    std::size_t max_steps;
  };
  const double keep = std::nan("");
  const Case cases[] = {{"escapement.json", 0.5, 1e-3, keep, 100000},  {"escapement.json", 0.1, 1e-6, keep, 100000},
                        {"ratchet.json", 0.05, 0, -20, 3000},          {"ratchet.json", 0.2, 1e-6, keep, 3000},
                        {"cam-follower.json", 0.3, 1e-6, keep, 3000}, {"scotch-yoke.json", 0.3, 1e-6, keep, 3000}};
  const std::size_t hits_before = simulation::frame_cache_hits(), misses_before = simulation::frame_cache_misses();
  std::size_t steps = 0, events = 0;
  for (const Case& c : cases) {
    Model model = example(c.model);
    if (!std::isnan(c.torque)) model.parts[0].dynamics->torque = Rational(c.torque);
    SimulationOptions options;
    options.accuracy = c.accuracy;
    const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy);
    test::SideBySide run = test::run_side_by_side<simulation::frame_cache>(model, options, c.t_end, where, c.max_steps);
    ASSERT_EQ(run.mismatch, "");
    ASSERT_EQ(run.error, "") << where;
    steps += run.steps;
    events += run.events;
  }
  const std::size_t hits = simulation::frame_cache_hits() - hits_before;
  const std::size_t misses = simulation::frame_cache_misses() - misses_before;
  std::printf("frame cache: %zu steps, %zu events equal; %zu frames remembered, %zu computed\n", steps, events, hits,
              misses);
  EXPECT_GT(hits, 1000u);
}

// Random initial states: the first part's angle uniform over a turn, the others' within their
// motion (the escapement's anchor and balance by up to 0.2 rad, the ratchet's pawl within its
// limits), velocities up to +-10 rad/s, the
// first part's torque in [-2000, 2000] N mm (escapement) or [-50, 50] N mm (ratchet). States that
// are not free are refused by both runs alike (Simulation::create's message, compared).
TEST(SimulationFrameCache, GeneratedInitialStatesRunEqual) {
  std::mt19937_64 random(20261201);
  std::uniform_real_distribution<double> unit(-1, 1);
  const std::size_t hits_before = simulation::frame_cache_hits();
  int ran = 0, refused = 0;
  std::size_t events = 0;
  for (int trial = 0; trial < 36; ++trial) {
    const bool escapement = trial % 3 == 0;
    Model model = example(escapement ? "escapement.json" : "ratchet.json");
    SimulationSpec spec = model.simulation.value_or(SimulationSpec{});
    spec.velocities.clear();
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      Part& part = model.parts[p];
      if (part.motion.kind != Motion::Kind::rotation) continue;
      // the ratchet's pawl within its limits (-20, 10 degrees)
      const double spread = p == 0 ? std::numbers::pi : escapement ? 0.2 : 0.15;
      const double centre = escapement || p == 0 ? 0.0 : -0.1;
      part.initial.angle = Rational(centre + spread * unit(random));
      SimulationSpec::Velocity v;
      v.part = p;
      v.value = Rational(10 * unit(random));
      spec.velocities.push_back(v);
    }
    model.parts[0].dynamics->torque = Rational((escapement ? 2000 : 50) * unit(random));
    model.simulation = spec;
    SimulationOptions options;
    const int level = (trial / 3 + trial) % 3;
    options.accuracy = level == 0 ? 1e-3 : level == 1 ? 1e-6 : 1e-9;
    const std::string where = std::string(escapement ? "escapement" : "ratchet") + " trial " + std::to_string(trial);
    test::SideBySide run = test::run_side_by_side<simulation::frame_cache>(model, options, 0.05, where, 300);
    ASSERT_EQ(run.mismatch, "");
    if (run.steps == 0) {
      ++refused;
      continue;
    }
    ++ran;
    events += run.events;
  }
  std::printf("frame cache, generated states: %d runs equal (%zu events), %d initial states refused alike\n", ran, events,
              refused);
  EXPECT_GE(ran, 10);
  EXPECT_GT(simulation::frame_cache_hits() - hits_before, 100u);
}

}  // namespace
}  // namespace hipair
