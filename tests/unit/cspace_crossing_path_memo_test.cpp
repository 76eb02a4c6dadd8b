// CSpace::first_crossing's path-enclosure memo (src/cspace/cspace_queries.cpp,
// MotionScanner::path_enclosure; switch cspace::path_memo() in src/cspace/angle_filter.hpp): the
// scanner remembers the filtered enclosures of its path, rate and acceleration polynomials over
// the last few stretches' end doubles. It must give the same bits as evaluating them: on generated
// motions — quintics (the simulator's step paths) starting on a contact edge, a few ulps or
// 1e-15 ... 1e-9 off it, along its tangent with a random bend, or at a random chart point, at
// speeds 1e-12 ... 10 chart units — every answer with the memo is the one without it, field for
// field (in a random order of the two runs); the memo answers often (the second-order
// exclusion's repeated start rates, asked per curve here: cspace::second_order_shared() off),
// and never with the switch off.
#include "cspace/angle_filter.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path model_file(const char* dir, const std::string& name) { return std::filesystem::path(dir) / name; }

TEST(CSpaceCrossingPathMemo, AnswersAreThoseWithoutTheMemo) {
  // (the second-order exclusion's start rates asked of the path memo for every curve, as when
  // this test was written: with cspace::second_order_shared() they are kept with the start's
  // pieces and asked once — CSpaceSecondOrderShared.* compares that sharing on and off)
  test::FlagSwitch<&cspace::second_order_shared> per_curve(false);
  test::SwitchCounts counts;
  std::uint64_t seed = 40;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    test::switch_answers_equal<&cspace::path_memo, &cspace::path_memo_hits>(*space, 160, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  Model model = read_model_file(model_file(HIPAIR_TEST_DATA, "degenerate/zero-clearance.json"));
  for (const PairBuild& pair : CSpace::build_pairs(model)) {
    if (pair.status != PairBuild::Status::built) continue;
    test::switch_answers_equal<&cspace::path_memo, &cspace::path_memo_hits>(*pair.space, 100, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("motions %d: crossing %d, none %d, other %d; memo hits %zu\n", counts.motions, counts.crossing,
              counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 800);
  EXPECT_GE(counts.crossing, 60);
  EXPECT_GE(counts.none, 200);
  EXPECT_GE(counts.hits, 2000u);
}

}  // namespace
}  // namespace hipair
