// CSpace::first_crossing's filtered start (src/cspace/cspace_queries.cpp, switch
// cspace::start_filter() in src/cspace/start_filter.hpp): a rotating axis's start located from
// the double-filtered pieces (widened by a double) where they meet no contact curve and their
// midpoint lies in a free or a blocked cell's face, else from the 160-bit pieces as before. Generated motions and point paths on the example spaces and the
// degenerate ones, with starts anywhere, a few ulps (or 1e-15 ... 1e-3) off a real edge on
// either side, and on a chart's side: every answer, every field (test::describe_crossing),
// equals the answer without the filter.
#include "cspace/angle_filter.hpp"
#include "cspace/start_filter.hpp"
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
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

struct Tally {
  std::size_t compared = 0, free_starts = 0, contact_starts = 0, filtered = 0;
};

void compare(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally, std::mt19937_64& random) {
  const std::size_t before = cspace::filtered_starts();
  auto [on, off] = test::on_and_off<&cspace::start_filter>(random, [&](bool) { return test::crossing_answer(space, path); });
  ASSERT_EQ(on, off) << what;
  tally.filtered += cspace::filtered_starts() - before;
  ++tally.compared;
  if (on.rfind("status 0 ", 0) == 0 || on.rfind("status 1 ", 0) == 0) ++tally.free_starts;
  if (on.rfind("status 2 ", 0) == 0) ++tally.contact_starts;
}

// Motions on one space. The start (chart values): kind 0 anywhere in a chart; kind 1 on a real
// edge moved a few ulps (or 1e-15 ... 1e-3) off it; kind 2 on a chart's side (x or y at a side's
// double). The end: 10^-4 ... 1 away in a random direction (the motion a cubic with a random
// bend), or the start itself (a point path, as the simulator's nudge asks).
void generated(const CSpace& space, int count, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    int kind = static_cast<int>(random() % 3);
    if (kind == 1 && real_edges.empty()) kind = 0;
    std::size_t c = random() % charts.size();
    double x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
    double y0 = two ? charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random) : 0;
    if (kind == 1) {
      std::size_t e = real_edges[random() % real_edges.size()];
      const CSpaceEdge& edge = space.edges()[e];
      c = edge.chart;
      x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
      y0 = 0;
      if (two) {
        try {
          y0 = space.evaluate(e, x0).value;
        } catch (const GeometryError&) {
          continue;
        }
      } else {
        x0 = edge.x_chart.lower;
      }
      test::move_off(two && random() % 2 == 0 ? y0 : x0, random);
    } else if (kind == 2) {
      test::to_chart_side(charts[c], two, x0, y0, random);
    }
    const CSpaceChart& chart = charts[c];
    bool point = random() % 3 == 0;
    double scale = std::pow(10.0, -4 + 4 * unit(random));
    double x1 = point ? x0 : x0 + sym(random) * scale, y1 = point ? y0 : y0 + sym(random) * scale;
    double qx0 = test::part_value(chart.x_kind, chart.x_half_turn, x0);
    double qx1 = test::part_value(chart.x_kind, chart.x_half_turn, x1);
    double qy0 = two ? test::part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
    double qy1 = two ? test::part_value(chart.y_kind, chart.y_half_turn, y1) : 0;
    double bend = (point || random() % 3 == 0) ? 0.0 : 0.3 * sym(random);
    double vx = qx1 - qx0, vy = qy1 - qy0;
    MotionPath path = test::bent_motion(chart, two, qx0, qy0, vx, vy, bend, point);
    std::ostringstream what;
    what.precision(17);
    what << name << " " << space.first_part() << ":" << space.second_part() << " motion " << i << " kind " << kind
         << " chart " << c << " from " << x0 << ", " << y0 << " to " << x1 << ", " << y1 << (point ? " (point)" : "");
    compare(space, path, what.str(), tally, random);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CSpaceStartFilter, AnswersEqualTheAnswersWithoutTheFilter) {
  Tally tally;
  std::uint64_t seed = 61;
  {
    std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
    for (const auto& space : spaces) {
      generated(*space, 600, seed++, "example", tally);
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    generated(*named.space, 150, seed++, named.file, tally);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("start filter: %zu motions compared, %zu free starts (%zu located by the filter), %zu in contact\n",
              tally.compared, tally.free_starts, tally.filtered, tally.contact_starts);
  EXPECT_GT(tally.free_starts, tally.compared / 3);
  EXPECT_GT(tally.contact_starts, tally.compared / 10);
  EXPECT_GT(tally.filtered, tally.free_starts / 2);
}

}  // namespace
}  // namespace hipair
