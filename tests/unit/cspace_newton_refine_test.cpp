// Session 63's two additions to CSpace::first_crossing's subdivision (src/cspace/cspace_queries.cpp):
// - the Newton proposal narrowed by steps from anchors inside it before its node is chosen
//   (CrossingRun::refine, MotionScanner::newton_from; switch cspace::newton_refine() in
//   src/cspace/crossing_shrink.hpp), and the left siblings up to its last anchor skipped as
//   certified free (CrossingRun::refined_free_before);
// - the second-order exclusion's nested (Horner) Taylor form, tried where the summed one fails
//   (MotionScanner::second_order_excludes; switch cspace::nested_taylor() in
//   src/cspace/angle_filter.hpp).
// The first only chooses which nodes holding the one curve's root are skipped, the second only
// adds certified exclusions: on generated motions over the example spaces — starts on a contact
// edge a few ulps or 1e-15 ... 1e-9 off it, along its tangent with a bend, or anywhere in a
// chart, at speeds 1e-12 ... 10 chart units (test::generated_motion) — every answer must be the
// one without them, field for field, and the refined queries must take fewer steps in all. The
// simulator's runs with each switch on and off: every state and event bit for bit.
#include "cspace/angle_filter.hpp"
#include "cspace/crossing_shrink.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation_side_by_side.hpp"
#include "test_seed.hpp"

#include <hipair/crossing_before.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

TEST(CSpaceNewtonRefine, AnswersAreThoseWithoutIt) {
  test::SwitchCounts counts;
  test::switch_answers_equal_on_examples<&cspace::newton_refine, &cspace::newton_refine_steps>(
      120, test::test_seed(6301), counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d, other %d; Newton steps from an anchor %zu\n", counts.motions,
              counts.crossing, counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.hits, 20u);
}

// The steps (stretches evaluated, CrossingQuery::step) each generated motion's query takes with
// the switch Flag on and off (seed `seed`, 120 motions per example space): the same answer, and
// the sums and per-motion comparisons of the steps.
struct StepCounts {
  long with_steps = 0, without_steps = 0;
  int motions = 0, fewer = 0, more = 0;
};
template <bool& (*Flag)()>
StepCounts steps_on_and_off(std::uint64_t seed) {
  StepCounts counts;
  const std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::mt19937_64 random(seed);
  for (const auto& space : spaces) {
    const std::vector<std::size_t> edges = test::real_edges(*space);
    for (int i = 0; i < 120; ++i) {
      std::optional<test::GeneratedMotion> motion = test::generated_motion(*space, edges, random);
      if (!motion) continue;
      auto run = [&](bool on, long& steps) -> std::string {
        test::FlagSwitch<Flag> flag(on);
        try {
          CrossingQuery query(*space, motion->path, CrossingOptions{});
          long n = 0;
          for (; !query.finished(); ++n) query.step();
          steps = n;
          return test::describe_crossing(*space, query.answer());
        } catch (const GeometryError& e) {
          steps = 0;
          return std::string("throws ") + e.what();
        }
      };
      long on = 0, off = 0;
      const std::string with = run(true, on), without = run(false, off);
      EXPECT_EQ(with, without) << space->first_part() << ":" << space->second_part() << " motion " << i;
      if (with != without) return counts;
      counts.with_steps += on;
      counts.without_steps += off;
      ++counts.motions;
      counts.fewer += on < off;
      counts.more += on > off;
    }
  }
  return counts;
}

// The refinement on and off: it exists to take fewer steps (a deeper node's left siblings are
// skipped as far as its last anchor proves free).
TEST(CSpaceNewtonRefine, RefinedQueriesTakeFewerSteps) {
  const StepCounts c = steps_on_and_off<&cspace::newton_refine>(test::test_seed(6302));
  ASSERT_FALSE(HasFailure());
  std::printf("motions %d: steps %ld with the refinement, %ld without; fewer in %d, more in %d\n", c.motions,
              c.with_steps, c.without_steps, c.fewer, c.more);
  EXPECT_GE(c.motions, 500);
  EXPECT_GT(c.fewer, 0);
  EXPECT_LT(c.with_steps, c.without_steps);
}

// Session 64: what the refinement achieves, counted where it succeeds (not where it is tried):
// proposals narrowed by a Newton step from an anchor (cspace::refine_narrowings), and left
// siblings skipped on the last anchor's proof alone (refined_free_before, where the stretch's
// own bound could not: cspace::refined_skips). Each must happen on generated motions, the
// anchor's skip alone switched off (cspace::refined_skip) must leave every answer as it was
// and take more steps. A refinement that never narrows, or a refined_free_before that never
// proves anything, fails here (the counts of attempts above do not see it).
TEST(CSpaceNewtonRefine, NarrowingsHappenOnGeneratedMotions) {
  test::SwitchCounts counts;
  test::switch_answers_equal_on_examples<&cspace::newton_refine, &cspace::refine_narrowings>(
      120, test::test_seed(6401), counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d, other %d; proposals narrowed %zu\n", counts.motions, counts.crossing,
              counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.hits, 20u);
}

TEST(CSpaceNewtonRefine, AnchorSkipsHappenAndLeaveTheAnswers) {
  test::SwitchCounts counts;
  test::switch_answers_equal_on_examples<&cspace::refined_skip, &cspace::refined_skipped_stretches>(
      120, test::test_seed(6402), counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d, other %d; stretches skipped on an anchor's proof %zu\n",
              counts.motions, counts.crossing, counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.hits, 10u);
}

TEST(CSpaceNewtonRefine, AnchorSkipsTakeFewerSteps) {
  const std::size_t before = cspace::refined_skips();
  const StepCounts c = steps_on_and_off<&cspace::refined_skip>(test::test_seed(6403));
  ASSERT_FALSE(HasFailure());
  std::printf("motions %d: steps %ld with the anchor's skips, %ld without; fewer in %d, more in %d; %zu skips\n",
              c.motions, c.with_steps, c.without_steps, c.fewer, c.more, cspace::refined_skips() - before);
  EXPECT_GE(c.motions, 500);
  EXPECT_GT(c.fewer, 0);
  EXPECT_EQ(c.more, 0);
  EXPECT_LT(c.with_steps, c.without_steps);
  EXPECT_GE(cspace::refined_skips() - before, static_cast<std::size_t>(c.fewer));
}

TEST(CSpaceNestedTaylor, AnswersAreThoseWithoutIt) {
  test::SwitchCounts counts;
  // (130 motions per space: the motions start near real edges drawn by number, and session 68's
  // mapped twin charts renumbered geneva-drive's edges; at 120 the draw had 39 crossings, base68's 41)
  test::switch_answers_equal_on_examples<&cspace::nested_taylor, &cspace::nested_taylor_exclusions>(
      130, test::test_seed(6303), counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d, other %d; nested-form exclusions %zu\n", counts.motions,
              counts.crossing, counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.hits, 1u);
}

TEST(CSpaceNewtonRefine, SimulationRunsEqualTheRunsWithoutIt) {
  const std::size_t before = cspace::newton_refine_steps();
  const std::size_t narrowed = cspace::refine_narrowings(), skipped = cspace::refined_skips();
  test::SideBySide runs = test::examples_side_by_side<cspace::newton_refine>(
      {{"escapement.json", 0.5, 1e-3}, {"geneva-drive.json", 2.0, 1e-3}, {"ratchet.json", 0.1, 1e-6}});
  ASSERT_FALSE(HasFailure());
  std::printf("Newton refinement: %zu steps, %zu events equal with the switch off; %zu Newton steps, %zu proposals "
              "narrowed, %zu anchor skips\n",
              runs.steps, runs.events, cspace::newton_refine_steps() - before, cspace::refine_narrowings() - narrowed,
              cspace::refined_skips() - skipped);
  EXPECT_GT(runs.events, 20u);
  EXPECT_GT(cspace::newton_refine_steps() - before, 0u);
  // (session 64) the runs' queries narrow proposals and skip siblings on an anchor's proof
  EXPECT_GT(cspace::refine_narrowings() - narrowed, 0u);
  EXPECT_GT(cspace::refined_skips() - skipped, 0u);
}

TEST(CSpaceNestedTaylor, SimulationRunsEqualTheRunsWithoutIt) {
  const std::size_t before = cspace::nested_taylor_exclusions();
  test::SideBySide runs = test::examples_side_by_side<cspace::nested_taylor>(
      {{"escapement.json", 0.5, 1e-3}, {"geneva-drive.json", 2.0, 1e-3}});
  ASSERT_FALSE(HasFailure());
  std::printf("nested Taylor form: %zu steps, %zu events equal with the switch off; %zu exclusions\n", runs.steps,
              runs.events, cspace::nested_taylor_exclusions() - before);
  EXPECT_GT(runs.events, 20u);
  EXPECT_GT(cspace::nested_taylor_exclusions() - before, 0u);
}

}  // namespace
}  // namespace hipair
