// first_crossing's anchor boxes (src/cspace/cspace_queries.cpp, MotionScanner::locate_inside;
// switch cspace::anchor_boxes() in src/cspace/angle_filter.hpp): a start next to a box that an
// earlier query on the space certified in its start cell (its start's box, an excluded
// stretch's) is located in that cell when no cell-bounding curve vanishes on the hull of both
// boxes and no edge meets the start's box, without the ray shooting. Chains of queries as the
// simulator asks them (each motion starting where the last one ended or was cut, in doubles, or
// a few ulps off it; point paths as the nudge asks; segments of every generated kind: random,
// ending on a curve, tangent, through a vertex, across a seam): every answer, every field
// (test::describe_crossing), equals the answer without the boxes.
#include "cspace/angle_filter.hpp"
#include "cspace_crossing_segments.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace hipair {
namespace {

// an axis's value at u, in doubles (as the simulator's state)
double value_at(const AxisPath& axis, double u) {
  double v = 0;
  for (std::size_t i = axis.coefficients.size(); i-- > 0;) v = v * u + axis.coefficients[i].get_d();
  return v;
}

TEST(CSpaceCrossingAnchorBoxes, ChainedAnswersEqualTheAnswersWithoutThem) {
  std::size_t examples = 0;
  const auto spaces = test::crossing_test_spaces(examples);
  std::mt19937_64 random(3303);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::size_t compared = 0, points = 0, anchored = 0, crossings = 0, free_starts = 0;
  for (int chain = 0; chain < 220; ++chain) {
    const std::size_t s = chain < 150 ? random() % examples : random() % spaces.size();
    const CSpace& space = *spaces[s];
    const bool two = space.dimension() == 2;
    MotionPath path;
    std::string what;
    if (!test::crossing_segment(space, static_cast<test::SegmentKind>(random() % test::segment_kinds), random, path, what))
      continue;
    for (int link = 0; link < 12; ++link) {
      const std::size_t before = cspace::box_anchored_starts();
      auto [on, off] = test::on_and_off<&cspace::anchor_boxes>(random, [&](bool) { return test::crossing_answer(space, path); });
      ASSERT_EQ(on, off) << "chain " << chain << " link " << link << " on space " << s << ": " << what;
      anchored += cspace::box_anchored_starts() - before;
      ++compared;
      if (path.u_begin == path.u_end) ++points;
      if (on.rfind("status 1 ", 0) == 0) ++crossings;
      if (on.rfind("status 0 ", 0) == 0 || on.rfind("status 1 ", 0) == 0) ++free_starts;
      // the next query: from where this one ends (u_end, or a cut inside), in doubles, sometimes
      // a few ulps off; a point path (the nudge's) one time in four, else a motion from there
      // (a crossing's step is cut before it: the next start is free)
      double u = path.u_begin == path.u_end ? 0.0 : random() % 2 == 0 ? 1.0 : unit(random);
      if (on.rfind("status 1 ", 0) == 0) {
        const MotionCrossing answer = space.first_crossing(path);
        u = answer.u_lower.get_d() * (random() % 2 == 0 ? 1 - std::pow(10.0, -8 * unit(random)) : unit(random));
      }
      double qx = value_at(path.x, u), qy = two ? value_at(path.y, u) : 0;
      if (random() % 3 == 0) test::move_off(two && random() % 2 == 0 ? qy : qx, random);
      const bool point = random() % 4 == 0;
      const double scale = std::pow(10.0, -5 + 4.5 * unit(random));
      const double vx = point ? 0 : sym(random) * scale, vy = point || !two ? 0 : sym(random) * scale;
      const double bend = random() % 2 == 0 ? 0.0 : 0.3 * sym(random);
      MotionPath next;
      next.x = path.x;
      next.y = path.y;
      auto set = [&](AxisPath& axis, double q0, double v) {
        axis.coefficients = {Rational(q0), Rational(v * (1 - bend)), Rational(v * bend)};
      };
      set(next.x, qx, vx);
      if (two) set(next.y, qy, vy);
      if (point) next.u_end = next.u_begin;
      path = next;
      what = "chained";
    }
  }
  std::printf("anchor boxes: %zu queries compared (%zu point paths, %zu free starts, %zu crossings), %zu starts located by a box\n",
              compared, points, free_starts, crossings, anchored);
  EXPECT_GE(compared, 1500u);
  EXPECT_GT(anchored, free_starts / 10);
  EXPECT_GT(crossings, 50u);
}

}  // namespace
}  // namespace hipair
