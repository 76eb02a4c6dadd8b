// first_crossing's per-thread memo of the stretches' filtered angle pieces
// (src/cspace/cspace_queries.cpp, memo_filtered_angle_ranges; switch cspace::angle_memo() in
// src/cspace/angle_memo.hpp). Oracle: the same queries with the memo off. Motions on the example
// spaces (the Geneva drive, the escapement's pairs, the cam), interleaved at random so that the
// memo holds thetas from other spaces and other motions: starts anywhere in a chart, on a real
// edge a few ulps (or 1e-15 ... 1e-3) off it, on a chart's side (the seams t = +-1, where an angle
// splits into two pieces), and at part angles near +-pi; each motion is followed by motions that
// share its angle path on one axis (the nudge's trials: the driver's angle fixed, the other axis
// moved), and by itself again (a hit on both axes).
#include "cspace/angle_memo.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

struct Tally {
  std::size_t compared = 0, hits = 0, shared_axis = 0;
};

void compare(const CSpace& space, const MotionPath& path, const std::string& what, std::mt19937_64& random, Tally& tally) {
  const std::size_t before = cspace::angle_memo_hits();
  auto [on, off] = test::on_and_off<&cspace::angle_memo>(random, [&](bool) { return test::crossing_answer(space, path); });
  ASSERT_EQ(on, off) << what;
  tally.hits += cspace::angle_memo_hits() - before;
  ++tally.compared;
}

TEST(CSpaceAngleMemo, AnswersEqualTheAnswersWithoutTheMemo) {
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::mt19937_64 random(2424);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  Tally tally;
  for (int i = 0; i < 1500; ++i) {
    const test::PartStart start = test::part_start(spaces, random, test::pick_start);
    const CSpace& space = *start.space;
    const std::size_t c = start.chart;
    const CSpaceChart& chart = space.charts()[c];
    const bool two = start.two;
    double qx0 = start.qx0;
    const double qy0 = start.qy0;
    if (random() % 8 == 0 && chart.x_kind == AxisKind::rotation)   // near +-pi: the angle's reduction
      qx0 = (random() % 2 ? 1 : -1) * std::nextafter(std::numbers::pi, static_cast<double>(random() % 2) * 8);
    const bool point = random() % 3 == 0;
    const double scale = std::pow(10.0, -4 + 4 * unit(random));
    const double vx = point ? 0 : sym(random) * scale, vy = point ? 0 : sym(random) * scale;
    const double bend = (point || random() % 3 == 0) ? 0.0 : 0.3 * sym(random);
    MotionPath path = test::bent_motion(chart, two, qx0, qy0, vx, vy, bend, point);
    std::ostringstream what;
    what.precision(17);
    what << space.first_part() << ":" << space.second_part() << " motion " << i << " chart " << c << " from " << qx0
         << ", " << qy0 << " by " << vx << ", " << vy << (point ? " (point)" : "");
    compare(space, path, what.str(), random, tally);
    ASSERT_FALSE(HasFatalFailure());
    // the same x path with y moved (as a nudge moves the driven wheel, not the driver), and the
    // motion itself again
    for (int k = 0; k < 3 && two; ++k) {
      MotionPath moved = path;
      double dy = std::ldexp(4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(qy0)), 3 * k);
      moved.y = test::axis_path(chart.y_kind, {qy0 + dy, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
      compare(space, moved, what.str() + " y moved by " + std::to_string(dy), random, tally);
      ASSERT_FALSE(HasFatalFailure());
      ++tally.shared_axis;
    }
    compare(space, path, what.str() + " again", random, tally);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("angle memo: %zu queries compared (%zu sharing an axis path), %zu stretches from the memo\n",
              tally.compared, tally.shared_axis, tally.hits);
  EXPECT_GT(tally.compared, 5000u);
  EXPECT_GT(tally.hits, tally.compared);   // the memo is used
}

}  // namespace
}  // namespace hipair
