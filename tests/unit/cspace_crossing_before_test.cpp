// first_crossing_before (include/hipair/crossing_before.hpp): the first-crossing query stopped
// where its subdivision passes a limit u_stop. Generated motions on the example spaces (from a
// random chart point toward a real edge and past it, or in a random direction; cubics with a
// random bend), each asked once without a limit (the oracle: CSpace::first_crossing) and then
// with limits around its answer: 0, random ones, the answer's u_lower itself, just below it (by
// one and by 2^-6 of a resolution cell), its u_upper. Every answer that did not stop must equal
// the oracle's in every field (test::describe_crossing); a stopped one must be `none` from the
// same start cell with u_lower == u_upper == a, u_stop < a <= u_end, and the oracle's answer
// `none` or a bracket with u_lower >= a; a limit at or past the oracle's u_lower never stops.
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/crossing_before.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

TEST(CSpaceCrossingBefore, AnswersAreTheQuerysOrCertifiedStops) {
  std::mt19937_64 random(20261130);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::size_t asked = 0, stopped = 0, same = 0, crossings = 0, at_lower = 0;
  const Rational cell = Rational(1) / Rational(mpz_class(1) << CrossingOptions{}.resolution_bits);
  for (int query = 0; query < 600; ++query) {
    test::GeneratedQuery g;
    if (!test::random_query(spaces, random, g)) continue;
    const std::size_t s = g.s;
    const CSpace& space = *spaces[s];
    const MotionPath& path = g.path;
    const MotionCrossing& full = g.answer;
    const std::string oracle = test::describe_crossing(space, full);
    const bool bracket = full.status == CrossingStatus::crossing || full.status == CrossingStatus::outside_region;
    crossings += full.status == CrossingStatus::crossing;
    std::vector<Rational> limits{Rational(0)};
    for (int k = 0; k < 3; ++k) limits.push_back(Rational(std::uniform_real_distribution<double>(0, 1)(random)));
    if (bracket) {
      limits.push_back(full.u_lower);
      limits.push_back(full.u_lower - cell);
      limits.push_back(full.u_lower - cell / 64);
      limits.push_back(full.u_upper);
    }
    for (std::size_t l = 0; l < limits.size(); ++l) {
      Rational u_stop = limits[l];
      u_stop.canonicalize();
      const std::string where = "query " + std::to_string(query) + " space " + std::to_string(s) + " (" +
                                space.first_part() + ":" + space.second_part() + ") kind " + std::to_string(g.kind) +
                                " limit " + std::to_string(l) + " u_stop " + u_stop.get_str() + "; oracle " + oracle;
      CrossingBefore answer = first_crossing_before(space, path, CrossingOptions{}, u_stop);
      ++asked;
      if (!answer.stopped) {
        ASSERT_EQ(test::describe_crossing(space, answer.crossing), oracle) << where;
        ++same;
        continue;
      }
      ++stopped;
      const MotionCrossing& c = answer.crossing;
      ASSERT_EQ(c.status, CrossingStatus::none) << where;
      ASSERT_EQ(c.u_lower, c.u_upper) << where;
      ASSERT_GT(c.u_lower, u_stop) << where;
      ASSERT_LE(c.u_lower, path.u_end) << where;
      ASSERT_EQ(c.cell_left, full.cell_left) << where;
      ASSERT_NE(full.status, CrossingStatus::starts_in_contact) << where;
      if (bracket) {
        ASSERT_GE(full.u_lower, c.u_lower) << where;
        ASSERT_LT(u_stop, full.u_lower) << where;   // a limit at or past u_lower never stops
      }
      if (bracket && u_stop == full.u_lower) ++at_lower;
    }
  }
  std::printf("crossing before: %zu queries with a limit, %zu stopped, %zu the query's own answer (%zu crossings)\n", asked,
              stopped, same, crossings);
  EXPECT_GT(stopped, asked / 10);
  EXPECT_GT(same, asked / 3);
  EXPECT_GT(crossings, 100u);
  EXPECT_EQ(at_lower, 0u);
}

}  // namespace
}  // namespace hipair
