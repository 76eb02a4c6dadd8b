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

struct SharedCounts {
  int motions = 0, crossing = 0, none = 0;
  std::size_t hits = 0;
};

void compare_shared(const CSpace& space, int count, std::uint64_t seed, SharedCounts& counts) {
  std::mt19937_64 random(seed);
  const std::vector<std::size_t> edges = test::real_edges(space);
  for (int i = 0; i < count; ++i) {
    std::optional<test::GeneratedMotion> motion = test::generated_motion(space, edges, random);
    if (!motion) continue;
    std::size_t on_hits = 0;
    auto [with, without] = test::on_and_off<&cspace::second_order_shared>(random, [&](bool on) {
      const std::size_t start = cspace::second_order_shared_hits();
      std::string answer = test::crossing_answer(space, motion->path);
      if (on) on_hits = cspace::second_order_shared_hits() - start;
      else EXPECT_EQ(cspace::second_order_shared_hits(), start) << "the switch must turn the sharing off";
      return answer;
    });
    ASSERT_EQ(with, without) << space.first_part() << ":" << space.second_part() << " motion " << i << " speed "
                             << motion->speed << " from (" << motion->x0 << ", " << motion->y0 << ") in chart "
                             << motion->chart;
    ++counts.motions;
    counts.hits += on_hits;
    if (with.rfind("status 1 ", 0) == 0) ++counts.crossing;
    else if (with.rfind("status 0 ", 0) == 0) ++counts.none;
  }
}

TEST(CSpaceSecondOrderShared, AnswersAreThoseComputedPerCurve) {
  SharedCounts counts;
  std::uint64_t seed = 4900;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    compare_shared(*space, 120, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("motions %d: crossing %d, none %d; shared parts taken again %zu times\n", counts.motions,
              counts.crossing, counts.none, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.hits, 200u);
}

TEST(CSpaceSecondOrderShared, SimulationRunsEqualTheRunsWithoutIt) {
  struct Case {
    const char* model;
    double t_end, accuracy;
  };
  const Case cases[] = {{"escapement.json", 0.3, 1e-3}, {"ratchet.json", 0.1, 1e-6}};
  std::size_t steps = 0, events = 0;
  const std::size_t before = cspace::second_order_shared_hits();
  for (const Case& c : cases) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.model);
    SimulationOptions options;
    options.accuracy = c.accuracy;
    const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy);
    test::SideBySide runs = test::run_side_by_side<cspace::second_order_shared>(model, options, c.t_end, where, 100000);
    ASSERT_EQ(runs.mismatch, "");
    ASSERT_EQ(runs.error, "") << where;
    steps += runs.steps;
    events += runs.events;
  }
  std::printf("second-order sharing: %zu steps, %zu events equal with the switch off; %zu taken again\n", steps,
              events, cspace::second_order_shared_hits() - before);
  EXPECT_GT(events, 20u);
  EXPECT_GT(cspace::second_order_shared_hits() - before, 0u);
}

}  // namespace
}  // namespace hipair
