// The holder's free side as CurveSolver::certified_range proves it (session 51, tol51; the
// `free_side` argument; docs/tolerance.md "Hand-overs"). Each sub-box's enclosure is certified
// with F_v of one sign over the sub-box x the held range x its bracket, which holds the root for
// every (p, t) there; the common sign is F_v's sign at the root for every parameter vector of the
// box and every driver value of the held range, which is what the hand-over envelope needs of its
// holder (chain.cpp passes it where the mean-value step did not prove it; the envelope's own test
// over the rectangle box x T x Y often fails where T is wide: gear-train.json's H:I mesh).
// Checked on generated Geneva cases (pin / slot 1 wall R, random driver positions and sub-boxes)
// with the driver ranging over a random held range T: at the box's corners and random vectors of
// the box, each at a random driver value of T, the root isolated independently and the sign of F
// just above and just below it (point evaluation: the finite-difference sign of F_v at a simple
// root) must be the side given. Mutant (run and reverted): the side negated — fails (see
// docs/performance.md "Session 51 (tol51)").
#include "model/parametric/parametric.hpp"
#include "tolerance/solver.hpp"
#include "tolerance_geneva_curve.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

namespace hipair {
namespace {

using tolerance_detail::CurveSlice;
using tolerance_detail::CurveSolver;
using tolerance_detail::Interval;

TEST(ToleranceFreeSide, ProvenSideIsTheSignOfFvAtTheRootOverTheBoxAndTheHeldRange) {
  auto model = test::geneva_parametric();
  const Model& nominal = model->nominal();
  const CurveSolver solver = test::chain_solver(model);
  std::mt19937_64 random(51);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t decided = 0, undecided = 0, points = 0, wide = 0;
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    test::GenevaBoxCase c;
    if (!test::generate_geneva_box_case(solver, nominal, random, c)) continue;
    // the driver over a held range T about its position, 1/512 .. 1/16 of a chart unit wide
    // (dyadic ends: exact as doubles and as rationals)
    const double half = std::ldexp(1.0, -5 - static_cast<int>(unit(random) * 5));
    const CurveSlice held = test::held_over(solver, c.curve, c.v, half);
    std::size_t boxes = 0;
    int side = 7;
    Interval y;
    try {
      y = solver.certified_range(held, c.box, c.v, c.sensitivity, 0.1, 1e-9, boxes, &side);
    } catch (const NumericError&) {
      continue;
    }
    ASSERT_TRUE(side == 1 || side == -1 || side == 0) << side;
    if (side == 0) {
      ++undecided;
      continue;
    }
    ++decided;
    wide += half >= 1.0 / 64;
    for (int k = 0; k < 10; ++k) {
      const std::vector<double> point = test::box_probe(c, k, random);
      const Interval& t = *held.fixed_range;
      double u = k < 2 ? double(k) : unit(random);
      CurveSlice at_t = c.curve;
      at_t.fixed_value = Rational(t.lo + (t.hi - t.lo) * u);
      Interval r;
      if (!solver.certified_point_root(at_t, point, Interval(y.lo - y.width(), y.hi + y.width()), r)) continue;
      EXPECT_GE(r.lo, y.lo) << "point " << k;
      EXPECT_LE(r.hi, y.hi) << "point " << k;
      const auto geometry = solver.point_geometry(at_t, solver.point_parameters(point));
      const double step = std::max(1e-9, 4 * r.width());
      const int above = solver.point_sign(at_t, geometry, r.hi + step);
      const int below = solver.point_sign(at_t, geometry, r.lo - step);
      if (std::abs(above) != 1 || std::abs(below) != 1) continue;   // undecided in the roundings
      ++points;
      EXPECT_EQ(above, side) << "point " << k << ": F above the root";
      EXPECT_EQ(below, -side) << "point " << k << ": F below the root";
    }
  }
  EXPECT_GE(decided, 20u);
  EXPECT_GE(wide, 5u);
  EXPECT_GE(points, 150u);
  std::printf("%zu enclosures with the side proven (%zu with T 1/32 wide or more), %zu not; %zu roots checked\n",
              decided, wide, undecided, points);
}

}  // namespace
}  // namespace hipair
