// first_crossing's filtered ends (src/cspace/cspace_queries.cpp, CrossingRun::filtered_end;
// switch cspace::end_filter() in src/cspace/start_filter.hpp): once a stretch within the
// resolution may touch contact space, each end tried past it is located from the stretches'
// double pieces (widened by a double) where they meet no contact curve and their midpoint lies in
// a free or a blocked cell's face, else from the 160-bit pieces as before. Generated segments on
// the example and degenerate spaces (random, ending exactly on a curve, tangent to one, through a
// vertex, across a seam): every answer, every field (test::describe_crossing), equals the answer
// without the filter.
#include "cspace/start_filter.hpp"
#include "cspace_crossing_segments.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <string>

namespace hipair {
namespace {

TEST(CSpaceCrossingEndFilter, AnswersEqualTheAnswersWithoutTheFilter) {
  std::size_t examples = 0;
  const auto spaces = test::crossing_test_spaces(examples);
  std::mt19937_64 random(3301);
  std::array<std::size_t, test::segment_kinds> made{}, crossings{};
  std::size_t compared = 0, filtered = 0;
  for (int i = 0; i < 2400; ++i) {
    const std::size_t s = i < 1600 ? random() % examples : random() % spaces.size();   // the example spaces first
    const CSpace& space = *spaces[s];
    const auto kind = static_cast<test::SegmentKind>(random() % test::segment_kinds);
    MotionPath path;
    std::string what;
    if (!test::crossing_segment(space, kind, random, path, what)) continue;
    const std::size_t before = cspace::filtered_ends();
    auto [on, off] = test::on_and_off<&cspace::end_filter>(random, [&](bool) { return test::crossing_answer(space, path); });
    ASSERT_EQ(on, off) << "segment " << i << " on space " << s << ": " << what;
    filtered += cspace::filtered_ends() - before;
    ++compared;
    ++made[static_cast<int>(kind)];
    if (on.rfind("status 1 ", 0) == 0) ++crossings[static_cast<int>(kind)];
  }
  std::printf("end filter: %zu segments compared, %zu ends located by the filter;", compared, filtered);
  for (int k = 0; k < test::segment_kinds; ++k)
    std::printf(" %s %zu (%zu crossings)", test::segment_name(static_cast<test::SegmentKind>(k)), made[k], crossings[k]);
  std::printf("\n");
  EXPECT_GE(compared, 1000u);
  for (int k = 0; k < test::segment_kinds; ++k) EXPECT_GT(made[k], 50u) << test::segment_name(static_cast<test::SegmentKind>(k));
  EXPECT_GT(crossings[0] + crossings[1] + crossings[3], 200u);
  EXPECT_GT(filtered, 100u);
}

}  // namespace
}  // namespace hipair
