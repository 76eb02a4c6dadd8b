// The feature pair's contact constant made once per box geometry (session 69, chain69;
// contact_function.hpp contact_constant, CurveSolver::BoxGeometry): the solver's box-geometry memo
// is keyed by the features' edges, not their kinds, so an arc and the vertex at its source share
// one geometry while only the arc's contact function takes the constant (the arc's radius times
// the wall's length for the Geneva pin on a slot wall). On generated Geneva cases (the pin /
// slot 1 wall R curve, random driver positions, sub-boxes and held driver ranges, the chains'
// switches and the plain ones), a solver that has first enclosed the curve of the pin's vertex
// over the box (its geometry memoised) must enclose the pin's curve exactly as a fresh solver does
// (outcome, enclosure, sub-boxes, free side, bit for bit), and the vertex's curve after the pin's
// likewise. Mutant (the first version of the change, the constant made for the memo's first
// curve's kinds): the pin's curve after its vertex's throws "the feature pair has no contact of
// its own" — fails.
#include "model/parametric/parametric.hpp"
#include "tolerance/contact_function.hpp"
#include "tolerance/solver.hpp"
#include "tolerance_geneva_curve.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

namespace hipair {
namespace {

using tolerance_detail::CurveSlice;
using tolerance_detail::CurveSolver;
using tolerance_detail::Interval;

struct Outcome {
  bool certified = false;
  std::string error;
  Interval y;
  std::size_t boxes = 0;
  int side = 7;
};

Outcome enclose(const CurveSolver& solver, const CurveSlice& curve, const test::GenevaBoxCase& c) {
  Outcome out;
  try {
    out.y = solver.certified_range(curve, c.box, c.v, c.sensitivity, 0.1, 1e-9, out.boxes, &out.side);
    out.certified = true;
  } catch (const Error& e) {
    out.error = e.what();
  }
  return out;
}

void expect_same(const Outcome& a, const Outcome& b) {
  EXPECT_EQ(a.certified, b.certified);
  EXPECT_EQ(a.error, b.error);
  if (a.certified && b.certified) {
    EXPECT_EQ(a.y.lo, b.y.lo);
    EXPECT_EQ(a.y.hi, b.y.hi);
    EXPECT_EQ(a.boxes, b.boxes);
    EXPECT_EQ(a.side, b.side);
  }
}

TEST(ToleranceContactConstant, ArcAndItsSourceVertexSharingABoxGeometryEncloseAsFreshSolvers) {
  auto model = test::geneva_parametric();
  const Model& nominal = model->nominal();
  auto configured = [&](bool chain) { return chain ? test::chain_solver(model) : CurveSolver(model); };
  std::mt19937_64 random(test::test_seed(69));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t pins_certified = 0, trials = 0;
  for (int trial = 0; trial < 24; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const bool chain = trial % 2 == 0;
    CurveSolver probe = configured(chain);
    test::GenevaBoxCase c;
    if (!test::generate_geneva_box_case(probe, nominal, random, c)) continue;
    ++trials;
    CurveSlice pin = c.curve;
    if (trial % 4 < 2) {   // the driver over a held range about its position (the chains' slices)
      double v = c.v;
      pin = test::held_over(probe, pin, v, std::ldexp(1.0, -6 - static_cast<int>(unit(random) * 4)));
    }
    CurveSlice vertex = pin;
    vertex.first.kind = FeatureKind::vertex;   // the source vertex of the pin's edge: the same geometry
    const Outcome pin_fresh = enclose(configured(chain), pin, c);
    const Outcome vertex_fresh = enclose(configured(chain), vertex, c);
    EXPECT_TRUE(pin_fresh.certified || pin_fresh.error.find("no contact") == std::string::npos) << pin_fresh.error;
    pins_certified += pin_fresh.certified;
    {
      SCOPED_TRACE("the vertex's curve first");
      CurveSolver shared = configured(chain);
      expect_same(enclose(shared, vertex, c), vertex_fresh);
      expect_same(enclose(shared, pin, c), pin_fresh);
    }
    {
      SCOPED_TRACE("the pin's curve first");
      CurveSolver shared = configured(chain);
      expect_same(enclose(shared, pin, c), pin_fresh);
      expect_same(enclose(shared, vertex, c), vertex_fresh);
    }
  }
  EXPECT_GE(trials, 12u);
  EXPECT_GE(pins_certified, trials / 2) << "too few certified enclosures to compare";
}

// The split contact function (contact_constant, then the kernel with it) against the kernels
// called as before session 69 (the constant made inside, per call), on generated arc–arc pairs of
// every orientation and arc–segment pairs at random poses, in intervals: bit for bit.
TEST(ToleranceContactConstant, SplitContactFunctionIsTheKernelsBitForBit) {
  using V = kernels::Vector<Interval>;
  using E = model_detail::EdgeValue<Interval>;
  std::mt19937_64 random(test::test_seed(6900));
  std::uniform_real_distribution<double> u(-3.0, 3.0), r2(0.25, 9.0);
  auto point = [&] { return V{Interval::point(u(random)), Interval::point(u(random))}; };
  auto pose = [&](int kind) {
    V pivot = point();
    if (kind == 0) return kernels::rotation_pose_from_half_tangent(pivot, Interval::point(u(random) / 3), u(random) > 0);
    if (kind == 1) return kernels::translation_pose(V{Interval(1), Interval(0)}, Interval::point(u(random)));
    return kernels::fixed_pose<Interval>();
  };
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    E arc_a, arc_b, segment;
    arc_a.arc = arc_b.arc = true;
    arc_a.center = point();
    arc_b.center = point();
    arc_a.radius_squared = Interval::point(r2(random));
    arc_b.radius_squared = Interval::point(r2(random));
    arc_a.ccw = trial % 4 != 1;
    arc_b.ccw = trial % 4 != 2;
    segment.source = point();
    segment.target = point();
    FeatureIdentity fa{0, 0, 0, FeatureKind::arc}, fb{1, 0, 0, FeatureKind::arc}, fs{1, 0, 1, FeatureKind::segment};
    const kernels::Pose<Interval> a = pose(trial % 3), b = pose((trial / 3) % 3);
    using A = model_detail::Arithmetic<Interval>;
    const Interval ra = A::sqrt(arc_a.radius_squared), rb = A::sqrt(arc_b.radius_squared);
    auto same = [](const Interval& x, const Interval& y) { return x.lo == y.lo && x.hi == y.hi; };
    // arc–arc (both concave: no contact of its own, both forms throw)
    if (arc_a.ccw || arc_b.ccw) {
      Interval d = arc_a.ccw && arc_b.ccw ? ra + rb : ra - rb;
      kernels::Tangency t = arc_a.ccw && arc_b.ccw ? kernels::Tangency::external
                            : arc_a.ccw            ? kernels::Tangency::first_inside_second
                                                   : kernels::Tangency::second_inside_first;
      Interval reference = kernels::arc_arc(a, arc_a.center, b, arc_b.center, d * d, t);
      EXPECT_TRUE(same(tolerance_detail::contact_function(arc_a, fa, a, arc_b, fb, b,
                                                          tolerance_detail::contact_constant(arc_a, fa, arc_b, fb)),
                       reference));
      EXPECT_TRUE(same(tolerance_detail::contact_function(arc_a, fa, a, arc_b, fb, b), reference));
    } else {
      EXPECT_THROW(tolerance_detail::contact_function(arc_a, fa, a, arc_b, fb, b), GeometryError);
    }
    // arc–segment and segment–arc (a convex arc)
    if (arc_a.ccw) {
      V d = segment.target - segment.source;
      Interval product = ra * A::sqrt(kernels::dot(d, d));
      Interval reference = kernels::arc_segment(a, arc_a.center, product, b, segment.source, segment.target);
      EXPECT_TRUE(same(tolerance_detail::contact_function(arc_a, fa, a, segment, fs, b,
                                                          tolerance_detail::contact_constant(arc_a, fa, segment, fs)),
                       reference));
      Interval swapped = kernels::segment_arc(b, segment.source, segment.target, a, arc_a.center, product);
      EXPECT_TRUE(same(tolerance_detail::contact_function(segment, fs, b, arc_a, fa, a,
                                                          tolerance_detail::contact_constant(segment, fs, arc_a, fa)),
                       swapped));
    }
    // a vertex pair takes no constant
    FeatureIdentity fv{0, 0, 0, FeatureKind::vertex};
    EXPECT_FALSE(tolerance_detail::contact_constant(arc_a, fv, segment, fs).value.has_value());
  }
}

}  // namespace
}  // namespace hipair
