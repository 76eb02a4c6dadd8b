// Certified enclosures of a contact curve's root over a parameter box (CurveSolver::
// certified_range) narrow their partial derivatives by the second-order form (session 20):
// F_a(box) in F_a(c) + sum_b F_ab(box) (x_b - c_b), with F_ab from nested interval jets. Checked
// on generated Geneva cases (pin / slot 1 wall R at random driver positions, random sub-boxes of
// 1/4 ... 64 x the tolerance box) against the first-order solver: the second-order enclosure
// certifies wherever the first-order one does, holds the root isolated independently at the
// box's corners and at random vectors, and is narrower in total.
//
// And an eccentric cam under a flat face placed at the cam's radius (as in
// examples/models/cam-follower.json): at the dead centres (sin theta = 0) no parameter moves the
// follower to first order (the radius moves both sides alike), so the root's bracket cannot
// be sized from the linearised spread; the certified band must still be bounded there (it was
// unbounded, and the Monte Carlo counted every sample there as outside it).
#include "model/parametric/parametric.hpp"
#include "tolerance/solver.hpp"
#include "tolerance_geneva_curve.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>

namespace hipair {
namespace {

using model_detail::ParametricModel;
using tolerance_detail::Box;
using tolerance_detail::CurveSolver;
using tolerance_detail::Interval;

TEST(ToleranceSecondOrder, EnclosuresHoldTheRootsAndAreNarrowerThanFirstOrder) {
  auto model = std::make_shared<const ParametricModel>(
      ParametricModel::read_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"));
  const Model& nominal = model->nominal();
  CurveSolver second(model), first(model);
  first.set_second_order(false);
  std::mt19937_64 random(20);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t cases = 0, narrower = 0, points = 0;
  double width_first = 0, width_second = 0;
  for (int trial = 0; trial < 150; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    test::GenevaBoxCase c;
    if (!test::generate_geneva_box_case(second, nominal, random, c)) continue;
    std::size_t boxes_first = 0, boxes_second = 0;
    Interval a, b;
    try {
      b = first.certified_range(c.curve, c.box, c.v, c.sensitivity, 0.1, 1e-9, boxes_first);
    } catch (const NumericError&) {
      continue;
    }
    ++cases;
    try {
      a = second.certified_range(c.curve, c.box, c.v, c.sensitivity, 0.1, 1e-9, boxes_second);
    } catch (const NumericError& e) {
      ADD_FAILURE() << "first order certified, second order did not: " << e.what();
      continue;
    }
    width_first += b.width();
    width_second += a.width();
    narrower += a.width() < b.width();
    // the root at the corners where the linearised root is least and greatest (each parameter
    // at the end its sensitivity points to: a linearisation misses the curvature there), at the
    // box's lower and upper corners and at random vectors, isolated independently
    for (int k = 0; k < 8; ++k) {
      const std::vector<double> point = test::box_probe(c, k, random);
      Interval r;
      Interval bracket = kernels::hull(a, b);
      if (!second.certified_point_root(c.curve, point, Interval(bracket.lo - bracket.width(), bracket.hi + bracket.width()), r))
        continue;
      ++points;
      EXPECT_GE(r.lo, a.lo) << "corner/point " << k;
      EXPECT_LE(r.hi, a.hi) << "corner/point " << k;
    }
  }
  EXPECT_GE(cases, 80u);
  EXPECT_GE(points, 400u);
  EXPECT_LT(width_second, 0.9 * width_first);
  std::printf("%zu cases: %zu narrower; total width %.6g (second order) against %.6g (first); %zu point roots inside\n",
              cases, narrower, width_second, width_first, points);
}

const char* eccentric_cam = R"({
  "hipair": 1, "name": "eccentric-cam-dead-centres",
  "units": {"length": "mm", "angle": "rad"},
  "parameters": {
    "R": {"nominal": 20, "tolerance": 0.03},
    "e": {"nominal": 5, "tolerance": [-0.01, 0.03], "distribution": "uniform"}
  },
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": "R"}}]},
    {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}},
     "initial": {"offset": 1},
     "loops": [{"start": [-40, "R"], "edges": [
        {"line_to": [40, "R"], "label": "face"}, {"line_to": [40, "R + 10"]},
        {"line_to": [-40, "R + 10"]}, {"line_to": [-40, "R"]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}
  ],
  "pairs": [{"parts": ["cam", "follower"]}]
})";

TEST(ToleranceSecondOrder, BandIsBoundedWhereNoParameterActsToFirstOrder) {
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 48;   // driver 0, pi and 2 pi among them: the dead centres
  options.monte_carlo = 100;
  options.seed = 5;
  ToleranceResult result = analyze_tolerances_text(eccentric_cam, options);
  std::size_t checked = 0, dead_centres = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    double sine = std::sin(s.driver);
    // the face is at the cam's radius, so s = e sin(theta) exactly whatever R is: its range over
    // e in [4.99, 5.03]; at the dead centres 0 for every parameter vector (R moves both sides)
    double lower = std::min(4.99 * sine, 5.03 * sine), upper = std::max(4.99 * sine, 5.03 * sine);
    ASSERT_TRUE(std::isfinite(s.certified.lower) && std::isfinite(s.certified.upper)) << "driver " << s.driver;
    EXPECT_LE(s.certified.lower, lower + 1e-12) << "driver " << s.driver;
    EXPECT_GE(s.certified.upper, upper - 1e-12) << "driver " << s.driver;
    EXPECT_LE((s.certified.upper - s.certified.lower) - (upper - lower), 0.11 * (upper - lower) + 1e-9) << "driver " << s.driver;
    ASSERT_TRUE(s.has_monte_carlo) << "driver " << s.driver;
    EXPECT_GE(s.monte_carlo_min, s.certified.lower);
    EXPECT_LE(s.monte_carlo_max, s.certified.upper);
    if (std::fabs(sine) < 1e-9) ++dead_centres;
    ++checked;
  }
  EXPECT_GE(checked, 40u);
  EXPECT_GE(dead_centres, 2u);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
}

}  // namespace
}  // namespace hipair
