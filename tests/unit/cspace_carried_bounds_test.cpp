// CSpace::first_crossing's carried double bounds (src/cspace/angle_filter.hpp, carried_bounds()):
// the stretches' pieces, boxes and path values keep the doubles they were computed in instead
// of converting them back from their rationals. Every answer must be the one of the conversions
// (the switch off): on thousands of generated motions on the Geneva, escapement, cam and
// degenerate (zero-clearance, tangent circles, concentric arcs, coincident edges) spaces, with
// starts in free space, starts within a few units in the last place of a contact curve, motions
// along a curve's tangent (near-tangent passes), and starts on contact space.
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
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }
using Switch = test::FlagSwitch<&cspace::carried_bounds>;
using test::describe_crossing;
using test::axis_path;
using test::part_value;


struct Tally {
  std::map<int, int> status;
  int grazing = 0, near_starts = 0, motions = 0;
};

// The answer with the carried bounds and with the conversions; both or neither throw.
void compare(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally) {
  std::string with, without;
  MotionCrossing answer;
  {
    Switch on(true);
    try {
      answer = space.first_crossing(path);
      with = describe_crossing(space, answer);
    } catch (const Error& e) {
      with = std::string("error: ") + e.what();
    }
  }
  {
    Switch off(false);
    try {
      without = describe_crossing(space, space.first_crossing(path));
    } catch (const Error& e) {
      without = std::string("error: ") + e.what();
    }
  }
  ASSERT_EQ(with, without) << what;
  ++tally.motions;
  ++tally.status[static_cast<int>(answer.status)];
  tally.grazing += answer.grazing;
}

// Generated motions on one space: quintic-like paths (the simulator's step polynomials) from
// random chart points, and from points on the space's contact edges moved by a few ulps, along
// random directions and along the edge's tangent.
void generated_motions(const CSpace& space, int count, std::uint64_t seed, Tally& tally) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    double x0 = 0, y0 = 0, dx = 0, dy = 0;
    std::size_t c = random() % charts.size();
    bool near = !real_edges.empty() && random() % 2 == 0;
    bool tangent = false;
    if (near) {
      std::size_t e = real_edges[random() % real_edges.size()];
      const CSpaceEdge& edge = space.edges()[e];
      c = edge.chart;
      double xa = edge.x_chart.lower, xb = edge.x_chart.upper;
      double x = xa + (xb - xa) * (0.02 + 0.96 * unit(random));
      if (two) {
        try {
          CertifiedValue y = space.evaluate(e, x);
          x0 = x;
          y0 = y.value;
          // a few units in the last place off the curve, either way, or 1e-15 ... 1e-3 off it
          if (random() % 2 == 0) {
            int k = static_cast<int>(random() % 9) - 4;
            for (int j = 0; j < std::abs(k); ++j) y0 = std::nextafter(y0, k > 0 ? 1e300 : -1e300);
          } else {
            y0 += sym(random) * std::pow(10.0, -15 + 12 * unit(random));
          }
          tangent = random() % 2 == 0;
          if (tangent) {
            EdgeDerivatives d = space.derivatives(EdgeId(e), Rational(x));
            double slope = 0.5 * (d.dy.lower + d.dy.upper);
            if (!std::isfinite(slope)) tangent = false;
            dx = 1;
            dy = slope;
          }
        } catch (const GeometryError&) {
          near = false;
        }
      } else {
        x0 = edge.x_chart.lower;
        int k = static_cast<int>(random() % 9) - 4;
        for (int j = 0; j < std::abs(k); ++j) x0 = std::nextafter(x0, k > 0 ? 1e300 : -1e300);
      }
    }
    const CSpaceChart& chart = charts[c];
    if (!near) {
      x0 = chart.x_lo.get_d() + (chart.x_hi.get_d() - chart.x_lo.get_d()) * unit(random);
      if (two) y0 = chart.y_lo.get_d() + (chart.y_hi.get_d() - chart.y_lo.get_d()) * unit(random);
    }
    if (!tangent) {
      dx = sym(random);
      dy = sym(random);
    }
    if (near) ++tally.near_starts;
    // chart values to part coordinates; velocity in part units (d theta = 2 dt / (1 + t^2))
    double qx = part_value(chart.x_kind, chart.x_half_turn, x0);
    double qy = two ? part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
    // motions of 1e-6 ... 0.1 (chart units) from near a curve, 0.01 ... 1 from elsewhere
    double scale = near ? std::pow(10.0, -6 + 5 * unit(random)) : std::pow(10.0, -2 + 2 * unit(random));
    double vx = dx * scale * (chart.x_kind == AxisKind::rotation ? 2 / (1 + x0 * x0) : 1);
    double vy = dy * scale * (two && chart.y_kind == AxisKind::rotation ? 2 / (1 + y0 * y0) : 1);
    double curve = (random() % 3 == 0) ? 0.0 : scale * 0.3;
    MotionPath path;
    path.x = axis_path(chart.x_kind, {qx, vx, curve * sym(random), curve * 0.1 * sym(random)});
    if (two) path.y = axis_path(chart.y_kind, {qy, vy, curve * sym(random), curve * 0.1 * sym(random)});
    std::ostringstream what;
    what.precision(17);
    what << space.first_part() << ":" << space.second_part() << " motion " << i << " chart " << c << " at " << x0
         << ", " << y0 << " near " << near << " tangent " << tangent;
    compare(space, path, what.str(), tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CSpaceCarriedBounds, FirstCrossingsEqualTheConvertedBoundsOnGeneratedMotions) {
  Tally tally;
  test::on_example_spaces({{1500, 7}, {500, 11}, {400, 13}},
                          [&](const CSpace& space, const test::ExampleSamples& run) { generated_motions(space, run.samples, run.seed, tally); });
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d near %d crossing %d none %d in contact %d grazing %d\n", tally.motions, tally.near_starts,
              tally.status[1], tally.status[0], tally.status[2], tally.grazing);
  RecordProperty("motions", tally.motions);
  RecordProperty("crossings", tally.status[static_cast<int>(CrossingStatus::crossing)]);
  RecordProperty("free", tally.status[static_cast<int>(CrossingStatus::none)]);
  RecordProperty("starts_in_contact", tally.status[static_cast<int>(CrossingStatus::starts_in_contact)]);
  RecordProperty("grazing", tally.grazing);
  EXPECT_GE(tally.motions, 3000);
  EXPECT_GE(tally.near_starts, 1000);
  EXPECT_GE(tally.status[static_cast<int>(CrossingStatus::crossing)], 150);
  EXPECT_GE(tally.status[static_cast<int>(CrossingStatus::none)], 600);
  EXPECT_GE(tally.status[static_cast<int>(CrossingStatus::starts_in_contact)], 1000);
  EXPECT_GE(tally.grazing, 500);
}

TEST(CSpaceCarriedBounds, FirstCrossingsEqualTheConvertedBoundsOnDegenerateSpaces) {
  Tally tally;
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    generated_motions(*named.space, 150, 17, tally);
    ASSERT_FALSE(HasFatalFailure()) << named.file;
  }
  RecordProperty("motions", tally.motions);
  RecordProperty("grazing", tally.grazing);
  EXPECT_GE(tally.motions, 700);
  EXPECT_GE(tally.near_starts, 200);
}

}  // namespace
}  // namespace hipair
