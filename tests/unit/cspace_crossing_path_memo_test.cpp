// CSpace::first_crossing's path-enclosure memo (src/cspace/cspace_queries.cpp,
// MotionScanner::path_enclosure; switch cspace::path_memo() in src/cspace/angle_filter.hpp): the
// scanner remembers the filtered enclosures of its path, rate and acceleration polynomials over
// the last few stretches' end doubles. It must give the same bits as evaluating them: on generated
// motions — quintics (the simulator's step paths) starting on a contact edge, a few ulps or
// 1e-15 ... 1e-9 off it, along its tangent with a random bend, or at a random chart point, at
// speeds 1e-12 ... 10 chart units — every answer with the memo is the one without it, field for
// field (in a random order of the two runs); the memo answers often (the second-order
// exclusion's repeated start rates), and never with the switch off.
#include "cspace/angle_filter.hpp"
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
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path model_file(const char* dir, const std::string& name) { return std::filesystem::path(dir) / name; }

struct Counts {
  int motions = 0, crossing = 0, none = 0, other = 0;
  std::size_t hits = 0;
};

std::string answer_of(const CSpace& space, const MotionPath& path) {
  try {
    return test::describe_crossing(space, space.first_crossing(path));
  } catch (const Error& e) {
    return std::string("error: ") + e.what();
  }
}

// `count` generated motions on `space` (see the file comment), each asked with the memo on and off.
void compare_motions(const CSpace& space, int count, std::uint64_t seed, Counts& counts) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<std::size_t> edges = test::real_edges(space);
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    const double speed = std::pow(10.0, -12 + 13 * unit(random));
    std::size_t chart_index = 0;
    double x0 = 0, y0 = 0, sx = sym(random), sy = sym(random);
    if (!edges.empty() && random() % 4 != 0) {
      const CSpaceEdge& edge = space.edges()[edges[random() % edges.size()]];
      chart_index = edge.chart;
      x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
      if (two) {
        try {
          const std::size_t e = static_cast<std::size_t>(&edge - space.edges().data());
          y0 = space.evaluate(e, x0).value;
          EdgeDerivatives d = space.derivatives(EdgeId(e), Rational(x0));
          sx = 1;
          sy = 0.5 * (d.dy.lower + d.dy.upper);
        } catch (const GeometryError&) {
          continue;
        }
        if (!std::isfinite(sy)) continue;
        if (random() % 2 == 0) {
          int k = static_cast<int>(random() % 13) - 6;
          for (int j = 0; j < std::abs(k); ++j) y0 = std::nextafter(y0, k > 0 ? 1e300 : -1e300);
        } else {
          y0 += sym(random) * std::pow(10.0, -15 + 6 * unit(random));
        }
      }
      if (random() % 2 == 0) {
        sx = -sx;
        sy = -sy;
      }
    } else {
      ChartPoint p = test::random_tile_point(space, random);
      chart_index = p.chart;
      x0 = p.x.get_d();
      y0 = p.y.get_d();
    }
    const CSpaceChart& chart = space.charts()[chart_index];
    // a quintic in the part coordinates: the start, the velocity, and random higher terms
    auto axis = [&](AxisKind kind, bool half_turn, double start, double direction) {
      std::vector<double> c{test::part_value(kind, half_turn, start), direction * speed};
      for (int k = 2; k <= 5; ++k) c.push_back(random() % 3 == 0 ? 0.0 : sym(random) * speed * speed);
      return test::axis_path(kind, c);
    };
    MotionPath path;
    path.x = axis(chart.x_kind, chart.x_half_turn, x0, sx);
    if (two) path.y = axis(chart.y_kind, chart.y_half_turn, y0, sy);
    const std::size_t before = cspace::path_memo_hits();
    std::size_t on_hits = 0;
    auto [with, without] = test::on_and_off<&cspace::path_memo>(random, [&](bool on) {
      const std::size_t start = cspace::path_memo_hits();
      std::string answer = answer_of(space, path);
      if (on) on_hits = cspace::path_memo_hits() - start;
      else EXPECT_EQ(cspace::path_memo_hits(), start) << "the switch must turn the memo off";
      return answer;
    });
    ASSERT_EQ(with, without) << space.first_part() << ":" << space.second_part() << " motion " << i << " speed "
                             << speed << " from (" << x0 << ", " << y0 << ") in chart " << chart_index;
    ASSERT_EQ(cspace::path_memo_hits() - before, on_hits);
    ++counts.motions;
    counts.hits += on_hits;
    if (with.rfind("status 1 ", 0) == 0) ++counts.crossing;
    else if (with.rfind("status 0 ", 0) == 0) ++counts.none;
    else ++counts.other;
  }
}

TEST(CSpaceCrossingPathMemo, AnswersAreThoseWithoutTheMemo) {
  Counts counts;
  std::uint64_t seed = 40;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    compare_motions(*space, 160, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  Model model = read_model_file(model_file(HIPAIR_TEST_DATA, "degenerate/zero-clearance.json"));
  for (const PairBuild& pair : CSpace::build_pairs(model)) {
    if (pair.status != PairBuild::Status::built) continue;
    compare_motions(*pair.space, 100, ++seed, counts);
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
