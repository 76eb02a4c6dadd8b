// certainly_blocked (include/hipair/blocked_walk.hpp, src/cspace/cspace_queries.cpp): walks of
// configurations as the simulator's nudge makes them (a start next to a contact edge, moved
// along a fixed direction by 4 ulps * 2^k), continued well past the edge into the free cell and
// beyond (a nudge stops at its first free trial; these do not, so that a walk certifying past
// its cell is seen). Every configuration the walk certifies blocked must be one first_crossing
// reports starts_in_contact from (the oracle: the exact point query), and the walks must
// certify many configurations from their last box, not only by the exact location.
#include "cspace/start_filter.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/blocked_walk.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

struct Tally {
  std::size_t trials = 0, certified = 0, chained = 0, free_after = 0;
  std::size_t compared = 0, compared_free = 0, compared_contact = 0;
};

// `count` walks on one 2-D space. The start: on a real edge moved a few ulps (or 1e-15 ... 1e-3)
// off it (two in three walks), or anywhere in a chart. The direction: one part alone (either),
// or both. The trials: the start and the start + 4 ulps * 2^k * direction, k = 0 ... 40.
// `constant`: each trial's point query (u_end = u_begin, as the nudge asks since session 29) is
// also checked against the same configuration as a constant path over [0, 1] (as the nudge asked
// before): the same status and start cell, and the same description where not free.
void walks(const CSpace& space, int count, std::uint64_t seed, const std::string& name, Tally& tally,
           bool constant = false) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  for (int i = 0; i < count; ++i) {
    std::size_t c = random() % charts.size();
    double x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
    double y0 = charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random);
    if (random() % 3 != 0 && !real_edges.empty()) {
      if (!test::onto_edge(space, real_edges[random() % real_edges.size()], random, c, x0, y0)) continue;
      test::move_off(y0, random);
    }
    const CSpaceChart& chart = charts[c];
    const double qx0 = test::part_value(chart.x_kind, chart.x_half_turn, x0);
    const double qy0 = test::part_value(chart.y_kind, chart.y_half_turn, y0);
    const int which = static_cast<int>(random() % 3);
    const double dx = which == 1 ? 0.0 : sym(random), dy = which == 0 ? 0.0 : sym(random);
    const double norm = std::max(std::abs(dx), std::abs(dy));
    if (norm == 0) continue;
    const double first = 4 * std::numeric_limits<double>::epsilon() * std::max({1.0, std::abs(qx0), std::abs(qy0)});
    BlockedWalk walk;
    bool seen_certified = false;
    for (int k = -1; k <= 40; ++k) {
      const double eps = k < 0 ? 0.0 : first * std::ldexp(1.0, k);
      const double qx = qx0 + eps * dx / norm, qy = qy0 + eps * dy / norm;
      MotionPath path = test::bent_motion(chart, true, qx, qy, 0, 0, 0, true);
      const std::size_t steps = cspace::blocked_walk_steps();
      const bool blocked = certainly_blocked(space, path, walk);
      const MotionCrossing answer = space.first_crossing(path);
      ++tally.trials;
      if (constant) {
        const MotionCrossing still = space.first_crossing(test::bent_motion(chart, true, qx, qy, 0, 0, 0, false));
        std::ostringstream what;
        what.precision(17);
        what << name << " " << space.first_part() << ":" << space.second_part() << " walk " << i << " trial " << k
             << " part values " << qx << ", " << qy << ": point " << test::describe_crossing(space, answer)
             << "; constant path " << test::describe_crossing(space, still);
        ASSERT_EQ(answer.status, still.status) << what.str();
        ASSERT_EQ(answer.cell_left.valid(), still.cell_left.valid()) << what.str();
        if (answer.cell_left.valid()) ASSERT_EQ(answer.cell_left.index(), still.cell_left.index()) << what.str();
        if (answer.status != CrossingStatus::none)
          ASSERT_EQ(test::describe_crossing(space, answer), test::describe_crossing(space, still)) << what.str();
        ++tally.compared;
        tally.compared_free += answer.status == CrossingStatus::none;
        tally.compared_contact += answer.status == CrossingStatus::starts_in_contact;
      }
      if (blocked) {
        std::ostringstream what;
        what.precision(17);
        what << name << " " << space.first_part() << ":" << space.second_part() << " walk " << i << " trial " << k
             << " chart " << c << " from " << x0 << ", " << y0 << " part values " << qx << ", " << qy << ": "
             << test::describe_crossing(space, answer);
        ASSERT_EQ(answer.status, CrossingStatus::starts_in_contact) << what.str();
        ++tally.certified;
        tally.chained += cspace::blocked_walk_steps() - steps;
        seen_certified = true;
      } else if (seen_certified && answer.status == CrossingStatus::none) {
        ++tally.free_after;   // the walk left its blocked cell into a free one
      }
    }
  }
}

// `count` walks on each 2-D example space, seeds from `seed` on.
void example_walks(int count, std::uint64_t seed, Tally& tally, bool constant) {
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const auto& space : spaces) {
    if (space->dimension() != 2) continue;
    walks(*space, count, seed++, "example", tally, constant);
    ASSERT_FALSE(::testing::Test::HasFatalFailure());
  }
}

TEST(CSpaceBlockedWalk, CertifiedConfigurationsStartInContact) {
  Tally tally;
  example_walks(150, 251, tally, false);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("blocked walks: %zu trials, %zu certified blocked (%zu from the last box), %zu free after a certified one\n",
              tally.trials, tally.certified, tally.chained, tally.free_after);
  EXPECT_GT(tally.certified, tally.trials / 10);
  EXPECT_GT(tally.chained, tally.certified / 2);
  EXPECT_GT(tally.free_after, 100u);
}

// The nudge's free test (simulation's nudge_free) asks a configuration as a point (u_end =
// u_begin): the start's exact location answers. Before, it asked a constant path over [0, 1],
// whose query also evaluated the stretch [0, 1] of a motion that does not move. On the walks'
// configurations (next to contact edges, a few ulps to 1e-3 off them, stepped by 4 ulps * 2^k
// along a direction, into and past the free cell; and anywhere in a chart): both answers are
// the same.
TEST(CSpaceBlockedWalk, PointQueriesAnswerAsConstantPaths) {
  Tally tally;
  example_walks(40, 907, tally, true);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("point queries against constant paths: %zu compared, %zu free, %zu starting in contact\n", tally.compared,
              tally.compared_free, tally.compared_contact);
  EXPECT_GT(tally.compared, 2000u);
  EXPECT_GT(tally.compared_free, tally.compared / 4);
  EXPECT_GT(tally.compared_contact, tally.compared / 10);
}

// The switch off: nothing is certified.
TEST(CSpaceBlockedWalk, SwitchedOffCertifiesNothing) {
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  test::FlagSwitch<&cspace::blocked_walks> off(false);
  const CSpace& space = *spaces.front();
  for (std::size_t e : test::real_edges(space)) {
    const CSpaceEdge& edge = space.edges()[e];
    if (edge.vertical) continue;
    const CSpaceChart& chart = space.charts()[edge.chart];
    double x = 0.5 * (edge.x_chart.lower + edge.x_chart.upper);
    double y = space.evaluate(e, x).value;
    BlockedWalk walk;
    for (double dy : {-1e-6, 1e-6}) {
      MotionPath path = test::bent_motion(chart, true, test::part_value(chart.x_kind, chart.x_half_turn, x),
                                          test::part_value(chart.y_kind, chart.y_half_turn, y + dy), 0, 0, 0, true);
      EXPECT_FALSE(certainly_blocked(space, path, walk));
    }
  }
}

}  // namespace
}  // namespace hipair
