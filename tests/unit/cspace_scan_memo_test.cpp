// CSpace::first_crossing's per-space memo of its scanner's derived curve data (interval partials,
// validity clauses, carriers, chart sides; src/cspace/cspace_queries.cpp ScanMemo, switch
// cspace::scan_memo() in src/cspace/scan_memo.hpp): generated motions on the example spaces,
// the spaces' queries interleaved at random (several spaces in the memo at once, each memo
// filled in a different order) and the spaces freed and rebuilt in turn (the memo must not match
// a freed space's successor): every answer, every field (test::describe_crossing), equals the
// answer made without the memo (the scanner's data made anew by the call).
#include "cspace/scan_memo.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

// A motion on `space`: from a random point of a random chart, either toward a random point of a
// real edge and past it (kind 0, two thirds: a crossing from a free start), or in a random
// direction by 10^-3 ... 1 (kind 1);
// a cubic in u through both ends with a random bend.
MotionPath random_motion(const CSpace& space, std::mt19937_64& random, int& kind, std::size_t& chart_index) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const bool two = space.dimension() == 2;
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  kind = real_edges.empty() || random() % 3 == 0 ? 1 : 0;
  std::size_t c = random() % space.charts().size();
  double x1 = 0, y1 = 0;
  if (kind == 0) {
    const std::size_t e = real_edges[random() % real_edges.size()];
    const CSpaceEdge& edge = space.edges()[e];
    c = edge.chart;
    double x = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
    double y = 0;
    if (two) {
      try {
        y = space.evaluate(e, x).value;
      } catch (const GeometryError&) {
        kind = 1;
      }
    } else {
      x = edge.x_chart.lower;
    }
    x1 = x;
    y1 = y;
  }
  const CSpaceChart& chart = space.charts()[c];
  double x0 = chart.x_lo.get_d() + (chart.x_hi.get_d() - chart.x_lo.get_d()) * unit(random);
  double y0 = two ? chart.y_lo.get_d() + (chart.y_hi.get_d() - chart.y_lo.get_d()) * unit(random) : 0;
  if (kind == 0) {
    double past = 1 + 0.5 * unit(random);
    x1 = x0 + (x1 - x0) * past;
    y1 = y0 + (y1 - y0) * past;
  } else {
    double scale = std::pow(10.0, -3 + 3 * unit(random));
    x1 = x0 + sym(random) * scale;
    y1 = y0 + sym(random) * scale;
  }
  double qx0 = test::part_value(chart.x_kind, chart.x_half_turn, x0);
  double qx1 = test::part_value(chart.x_kind, chart.x_half_turn, x1);
  double qy0 = two ? test::part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
  double qy1 = two ? test::part_value(chart.y_kind, chart.y_half_turn, y1) : 0;
  double bend = (random() % 3 == 0) ? 0.0 : 0.3 * sym(random);
  double vx = qx1 - qx0, vy = qy1 - qy0;
  MotionPath path;
  path.x = test::axis_path(chart.x_kind, {qx0, vx * (1 - bend), vx * bend, 0});
  if (two) path.y = test::axis_path(chart.y_kind, {qy0, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
  chart_index = c;
  return path;
}

TEST(CSpaceScanMemo, AnswersEqualTheAnswersWithoutTheMemo) {
  std::mt19937_64 random(20261130);
  std::size_t compared = 0, crossings = 0, starts_free = 0;
  const std::size_t hits_before = cspace::scan_memo_hits();
  for (int round = 0; round < 2; ++round) {
    // each round builds the spaces anew (the memo must not match a freed space's successor)
    std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
    for (int query = 0; query < 1000; ++query) {
      std::size_t s = random() % spaces.size();
      const CSpace& space = *spaces[s];
      int kind = 0;
      std::size_t chart = 0;
      MotionPath path = random_motion(space, random, kind, chart);
      // with the memo and without it, in a random order
      auto [on, off] = test::on_and_off<&cspace::scan_memo>(random, [&](bool) { return test::crossing_answer(space, path); });
      ASSERT_EQ(on, off) << "round " << round << " query " << query << " space " << s << " (" << space.first_part() << ":"
                         << space.second_part() << ") kind " << kind << " chart " << chart;
      ++compared;
      if (on.rfind("status 1 ", 0) == 0) ++crossings;
      if (on.rfind("status 0 ", 0) == 0 || on.rfind("status 1 ", 0) == 0) ++starts_free;
    }
  }
  const std::size_t hits = cspace::scan_memo_hits() - hits_before;
  std::printf("scan memo: %zu motions compared, %zu from a free start, %zu crossings, %zu calls from a memo already made\n",
              compared, starts_free, crossings, hits);
  EXPECT_GT(starts_free, compared / 3);
  EXPECT_GT(crossings, compared / 6);
  EXPECT_GT(hits, compared / 2);
}

}  // namespace
}  // namespace hipair
