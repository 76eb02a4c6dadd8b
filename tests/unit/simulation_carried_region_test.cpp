// The carried region of first_crossing (src/cspace/carried_region.hpp; docs/simulation.md,
// "Session 44 (esc44)"): runs with the region and without it, side by side, every state and
// event bit for bit.
#include "cspace/carried_region.hpp"
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

TEST(SimulationCarriedRegion, RunsEqualTheRunsWithoutTheRegion) {
  struct Case {
    const char* model;
    double t_end, accuracy;
  };
  const Case cases[] = {{"examples/models/escapement.json", 0.5, 1e-3},
                        {"examples/models/escapement.json", 0.1, 1e-6},
                        {"tests/data/simulation/escapement-frictionless.json", 0.25, 1e-3},
                        {"examples/models/ratchet.json", 0.5, 1e-3},
                        {"examples/models/geneva-drive.json", 2.0, 1e-3},
                        {"examples/models/cam-follower.json", 0.5, 1e-4}};
  const std::size_t hits_before = cspace::carried_region_hits(), made_before = cspace::carried_regions_made();
  std::size_t steps = 0, events = 0;
  for (const Case& c : cases) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / c.model);
    SimulationOptions options;
    options.accuracy = c.accuracy;
    const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy);
    test::SideBySide run = test::run_side_by_side<cspace::carried_regions>(model, options, c.t_end, where);
    ASSERT_EQ(run.mismatch, "");
    steps += run.steps;
    events += run.events;
  }
  const std::size_t hits = cspace::carried_region_hits() - hits_before, made = cspace::carried_regions_made() - made_before;
  std::printf("carried region: %zu steps, %zu events equal; %zu regions made, %zu boxes inside one\n", steps, events, made,
              hits);
  EXPECT_GT(hits, 0u);
}

}  // namespace
}  // namespace hipair
