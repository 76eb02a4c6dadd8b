// The certified enclosures of the contact zones and the band (CurveSolver::certified_range)
// test the end signs of each bracket Y with the jet over Y first (session 13): its partial
// derivatives contain those at every point of Y, so a certain sign there is certain. Checked
// on generated Geneva cases (pin / slot 1 wall R at random driver positions, random sub-boxes
// of 1/4 ... 64 x the tolerance box): the enclosure lies inside the former path's (each end sign
// with its own jet at the point) and, on these cases, equals it bit for bit with the same
// number of sub-boxes (an end sign that only the new test certifies would make it tighter: none
// here; a remainder dropped from the new sign test made 2 of 149 differ); and it contains the
// certified root at random parameter vectors of the box (an independent isolation at a point).
#include "model/parametric/parametric.hpp"
#include "tolerance/solver.hpp"
#include "tolerance_geneva_curve.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace hipair {
namespace {

using model_detail::ParametricModel;
using tolerance_detail::Box;
using tolerance_detail::CurveSolver;

TEST(ToleranceZoneReuse, JetOverTheBracketGivesTheFormerEnclosuresOrTighterAndHoldsTheRoots) {
  auto model = std::make_shared<const ParametricModel>(
      ParametricModel::read_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"));
  const Model& nominal = model->nominal();
  CurveSolver reuse(model), former(model);
  former.set_reuse_y_jets(false);
  // first order on both: this compares the end-sign tests (the second-order narrowing after them
  // is tested in tolerance_second_order_test.cpp)
  reuse.set_second_order(false);
  former.set_second_order(false);
  std::size_t n = nominal.parameters.size();
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t cases = 0, identical = 0, tighter = 0, points = 0;
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    test::GenevaBoxCase c;
    if (!test::generate_geneva_box_case(reuse, nominal, random, c)) continue;
    const tolerance_detail::CurveSlice& curve = c.curve;
    const Box& box = c.box;
    double v = c.v;
    const std::vector<double>& s = c.sensitivity;
    std::size_t boxes_new = 0, boxes_old = 0;
    tolerance_detail::Interval a, b;
    bool ok_new = true, ok_old = true;
    try {
      a = reuse.certified_range(curve, box, v, s, 0.1, 1e-9, boxes_new);
    } catch (const NumericError&) {
      ok_new = false;
    }
    try {
      b = former.certified_range(curve, box, v, s, 0.1, 1e-9, boxes_old);
    } catch (const NumericError&) {
      ok_old = false;
    }
    if (!ok_old) continue;
    ++cases;
    ASSERT_TRUE(ok_new) << "the former path certified, the new one did not";
    EXPECT_GE(a.lo, b.lo);
    EXPECT_LE(a.hi, b.hi);
    if (a.lo == b.lo && a.hi == b.hi && boxes_new == boxes_old) ++identical;
    else ++tighter;
    for (int k = 0; k < 4; ++k) {
      std::vector<double> point(n);
      for (std::size_t i = 0; i < n; ++i) point[i] = box.lo[i] + (box.hi[i] - box.lo[i]) * (k < 2 ? double(k) : unit(random));
      tolerance_detail::Interval r;
      if (!reuse.certified_point_root(curve, point, tolerance_detail::Interval(a.lo - a.width(), a.hi + a.width()), r)) continue;
      ++points;
      EXPECT_GE(r.lo, a.lo);
      EXPECT_LE(r.hi, a.hi);
    }
  }
  EXPECT_GE(cases, 100u);
  EXPECT_GE(points, 200u);
  EXPECT_EQ(identical, cases) << tighter << " of " << cases << " differ";
  std::printf("%zu cases: %zu identical, %zu tighter; %zu point roots inside\n", cases, identical, tighter, points);
}

}  // namespace
}  // namespace hipair
