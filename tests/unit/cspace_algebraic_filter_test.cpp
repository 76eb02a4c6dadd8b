// The certified filter in front of the exact algebraic oracle (session 37,
// PairOverlap::certainly_overlapping, curves/contact_curves.hpp): at chart points with an
// irrational coordinate it may answer "overlapping" from interval poses of the whole box of
// the point's isolating intervals; it must never answer where the exact oracle
// (algebraic_overlap without the filter) says touching or apart, nor over any box that holds
// such a point.
//
// Generator: spur-gear pairs from examples/models/spur-gears.json (tests/unit/spur_gear_pairs.hpp)
// with 6 … 40 teeth, random rational backlash and centre offset, or zero backlash and zero offset
// (the teeth mesh at zero clearance: tangent contacts); session 37's test also scaled them by
// 2^±996, which the narrow-box test below does not (minutes per scaled pair at load 15). Points (session 38): a random small tile of a chart near the initial
// configuration (the meshing channel: its walls are touching points) or anywhere (mostly blocked
// space), the contact curves of a few feature pairs the generator keeps there (no blocked-space
// cull, so curves deep in blocked space too), a random rational abscissa and every real root of
// the curve over the tile, refined to a narrow box (as the builder's vertices are): points where
// two features touch, the parts overlapping elsewhere, only touching, or apart (a curve's
// spurious branch). Oracle: algebraic_overlap without a filter, exact.
#include "curves/algebraic_overlap.hpp"
#include "curves/contact_curves.hpp"
#include "algebra/near_quotient.hpp"
#include "spur_gear_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using cspace::ChartAxis;
using cspace::Overlap;
using Real = cspace::algebra::Real;

kernels::Interval box_of(const Real& r) {
  return r.exact ? cspace::algebra::enclose_kernel(r.lower)
                 : kernels::Interval(cspace::algebra::lower_double(r.lower), cspace::algebra::upper_double(r.upper));
}

// a random rational in [lo, hi] with a denominator up to 2^20
Rational between(std::mt19937_64& random, const Rational& lo, const Rational& hi) {
  Rational u(static_cast<long>(random() % (1u << 20)), 1L << 20);
  u.canonicalize();
  return Rational(lo + (hi - lo) * u);
}

struct Counts {
  std::size_t points = 0, decided = 0, overlapping = 0, touching = 0, apart = 0, boxes = 0;
};

// A tile of 1/64 of chart `axis` on each side: around chart coordinate 0 (the initial
// configuration: the meshing channel) when `near_seed`, else anywhere in the chart.
ChartAxis small_tile(std::mt19937_64& random, ChartAxis axis, bool near_seed) {
  const Rational width = Rational(axis.hi - axis.lo) / 64;
  if (near_seed)
    axis.lo = Rational(between(random, Rational(-width / 4), Rational(width / 4)) - width / 2);
  else
    axis.lo = between(random, axis.lo, Rational(axis.hi - width));
  axis.lo.canonicalize();
  axis.hi = Rational(axis.lo + width);
  return axis;
}

// The chart of `charts` holding coordinate 0 of a rotation (its axis through angle 0).
const ChartAxis& chart_at_zero(const std::vector<ChartAxis>& charts) {
  for (const ChartAxis& axis : charts)
    if (!axis.half_turn && axis.lo < 0 && axis.hi > 0) return axis;
  return charts.front();
}

// The points of the pair on a few curves of two tiles (one at the seed, one anywhere), each
// refined to a narrow box: the filter against the exact oracle at the point's box and, where
// the exact answer is not "overlapping", at wider boxes holding it.
void check_pair(const Model& model, std::mt19937_64& random, const std::string& name, Counts& counts) {
  const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  cspace::CurveOptions culled, whole;
  whole.cull_blocked_space = false;
  cspace::CurveGenerator generator(model, axes, culled), every_curve(model, axes, whole);
  const cspace::PairOverlap filter(model, axes);
  for (int tile = 0; tile < 2; ++tile) {
    const bool near_seed = tile == 0;
    const ChartAxis x = small_tile(random, near_seed ? chart_at_zero(layout.x_charts)
                                                     : layout.x_charts[random() % layout.x_charts.size()], near_seed);
    const ChartAxis y = small_tile(random, near_seed ? chart_at_zero(layout.y_charts)
                                                     : layout.y_charts[random() % layout.y_charts.size()], near_seed);
    // near the seed the curves the builder keeps (the channel's walls: touching points, and
    // spurious branches); elsewhere every feature pair's (mostly overlapping points)
    std::vector<cspace::ContactCurve> curves = (near_seed ? generator : every_curve).generate(x, y);
    std::shuffle(curves.begin(), curves.end(), random);
    if (curves.size() > 8) curves.resize(8);
    // the builder's vertex boxes: isolating intervals far narrower than the tile
    const Rational narrow = Rational(y.hi - y.lo) / Rational(mpz_class(1) << 40);
    for (const cspace::ContactCurve& curve : curves) {
      const Rational qx = between(random, x.lo, x.hi);
      const cspace::algebra::Polynomial p = cspace::algebra::substitute_x(curve.polynomial, qx);
      if (p.size() < 2) continue;
      for (Real qy : cspace::algebra::real_roots(p, y.lo, y.hi)) {
        cspace::algebra::refine_dyadically(qy, narrow);
        const Real rx = Real::from_rational(qx);
        const std::optional<Overlap> exact = cspace::algebraic_overlap(model, axes, x, y, rx, qy);
        if (!exact) continue;
        ++counts.points;
        const bool decided = filter.certainly_overlapping(x, y, box_of(rx), box_of(qy));
        if (*exact == Overlap::overlapping) {
          ++counts.overlapping;
          counts.decided += decided;
          // with the filter, the oracle's answer is the same
          if (decided) EXPECT_EQ(cspace::algebraic_overlap(model, axes, x, y, rx, qy, &filter), exact) << name;
          continue;
        }
        ++(*exact == Overlap::touching ? counts.touching : counts.apart);
        EXPECT_FALSE(decided) << name << ": the filter says overlapping where the parts are "
                              << (*exact == Overlap::touching ? "touching" : "apart") << " (x " << qx.get_str()
                              << ", y in [" << qy.lower.get_str() << ", " << qy.upper.get_str() << "])";
        // boxes about the point, up to 1/16 of the tile wide on each side
        for (int k = 0; k < 4; ++k) {
          const double wx = Rational(x.hi - x.lo).get_d() * std::ldexp(1.0, -4 - static_cast<int>(random() % 30));
          const double wy = Rational(y.hi - y.lo).get_d() * std::ldexp(1.0, -4 - static_cast<int>(random() % 30));
          kernels::Interval bx = box_of(rx), by = box_of(qy);
          bx = kernels::Interval(bx.lo - wx * (random() % 2), bx.hi + wx * (random() % 2));
          by = kernels::Interval(by.lo - wy * (random() % 2), by.hi + wy * (random() % 2));
          ++counts.boxes;
          EXPECT_FALSE(filter.certainly_overlapping(x, y, bx, by))
              << name << ": the filter says overlapping over a box that holds a point where the parts are "
              << (*exact == Overlap::touching ? "touching" : "apart");
        }
      }
    }
  }
}

// Session 38: replaces session 37's disabled test (254 s; roots at their wide isolating
// intervals, where the filter decided nothing). A mutant of the filter answering "overlapping"
// unless the edges are certainly disjoint, posing only the box's centre (the margin dropped),
// or taking a certain crossing's "disjoint" for "overlapping" fails it.
TEST(AlgebraicOverlapFilter, DecidesOnlyWhereTheExactOracleSaysOverlappingAtNarrowBoxesOfGeneratedGearPairs) {
  std::mt19937_64 random(38);
  Counts counts;
  for (int trial = 0; trial < 8; ++trial) {
    const long z1 = 6 + static_cast<long>(random() % 35), z2 = 6 + static_cast<long>(random() % 35);
    std::string name;
    Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    if (trial % 2 == 0) {   // zero clearance: no backlash, the nominal centre distance
      ReadOptions read;
      read.parameter_values["teeth-1"] = Rational(z1);
      read.parameter_values["teeth-2"] = Rational(z2);
      read.parameter_values["backlash"] = Rational(0);
      read.parameter_values["center-distance"] = Rational(z1 + z2);
      read.allow_out_of_tolerance = true;
      model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
      name = "gears " + std::to_string(z1) + "x" + std::to_string(z2) + " at zero clearance";
    }
    check_pair(model, random, name, counts);
  }
  std::cout << "points " << counts.points << " (overlapping " << counts.overlapping << ", decided by the filter "
            << counts.decided << "; touching " << counts.touching << ", apart " << counts.apart << "), boxes "
            << counts.boxes << "\n";
  // the generator reaches points that are not overlapping, and at narrow boxes the filter
  // decides at least three quarters of the overlapping ones
  EXPECT_GT(counts.touching + counts.apart, 0u);
  EXPECT_GT(counts.overlapping, 20u);
  EXPECT_GE(4 * counts.decided, 3 * counts.overlapping);
}

// The region builds with the filter and without it (algebraic_filter_switch off): the same
// C-space, and the filter answered some of the oracle's calls.
TEST(AlgebraicOverlapFilter, RegionBuildsAreTheSameWithoutIt) {
  std::mt19937_64 random(3707);
  for (const auto& [z1, z2] : {std::pair{6L, 7L}, std::pair{9L, 8L}}) {
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    CSpaceBuildOptions options;
    options.operating_region = true;
    const auto before = cspace::overlap_filter_counts();
    const CSpace with = CSpace::build(model, model.parts[0].name, model.parts[1].name, options);
    const auto after = cspace::overlap_filter_counts();
    cspace::algebraic_filter_switch() = false;
    const CSpace without = CSpace::build(model, model.parts[0].name, model.parts[1].name, options);
    cspace::algebraic_filter_switch() = true;
    EXPECT_EQ(cspace::overlap_filter_counts(), after) << name << ": switched off, the filter was still asked";
    EXPECT_GT(after[1], before[1]) << name << ": the filter decided nothing";
    EXPECT_EQ(with.statistics().touching_vertices, without.statistics().touching_vertices) << name;
    EXPECT_EQ(with.statistics().touching_edges, without.statistics().touching_edges) << name;
    EXPECT_EQ(with.statistics().touching_undecided, without.statistics().touching_undecided) << name;
    ASSERT_EQ(with.vertices().size(), without.vertices().size()) << name;
    ASSERT_EQ(with.edges().size(), without.edges().size()) << name;
    for (std::size_t e = 0; e < with.edges().size(); ++e)
      EXPECT_EQ(with.edges()[e].role, without.edges()[e].role) << name << ": edge " << e;
    ASSERT_EQ(with.cells().size(), without.cells().size()) << name;
    for (std::size_t c = 0; c < with.cells().size(); ++c)
      EXPECT_EQ(with.cells()[c].kind, without.cells()[c].kind) << name << ": cell " << c;
  }
}

}  // namespace
}  // namespace hipair
