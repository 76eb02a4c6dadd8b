// The second-order exclusion's shared parts (src/cspace/cspace_queries.cpp,
// MotionScanner::second_order_excludes; switch cspace::second_order_shared() in
// src/cspace/angle_filter.hpp): the start's rates X'(a), Y'(a), kept with the start's pieces, and
// the stretch's X'', Y'', computed once for all the curves tried over a stretch. They must give
// the same answers as computing them for each curve: on generated motions (quintics starting on
// a contact edge, a few ulps or 1e-15 ... 1e-9 off it, along its tangent with a bend, or at a
// random chart point) every answer with the switch on is the one with it off, field for field
// (in a random order of the two runs), the shared parts are taken again often, and never with
// the switch off; simulation runs side by side (escapement, ratchet) step for step.
#include "cspace/angle_filter.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation_side_by_side.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

TEST(CSpaceSecondOrderShared, AnswersAreThoseComputedPerCurve) {
  test::SwitchCounts counts;
  test::switch_answers_equal_on_examples<&cspace::second_order_shared, &cspace::second_order_shared_hits>(120, 4900,
                                                                                                          counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d; shared parts taken again %zu times\n", counts.motions,
              counts.crossing, counts.none, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.hits, 200u);
}

TEST(CSpaceSecondOrderShared, SimulationRunsEqualTheRunsWithoutIt) {
  const std::size_t before = cspace::second_order_shared_hits();
  test::SideBySide runs = test::examples_side_by_side<cspace::second_order_shared>(
      {{"escapement.json", 0.3, 1e-3}, {"ratchet.json", 0.1, 1e-6}});
  ASSERT_FALSE(HasFailure());
  std::printf("second-order sharing: %zu steps, %zu events equal with the switch off; %zu taken again\n", runs.steps,
              runs.events, cspace::second_order_shared_hits() - before);
  EXPECT_GT(runs.events, 20u);
  EXPECT_GT(cspace::second_order_shared_hits() - before, 0u);
}

}  // namespace
}  // namespace hipair
