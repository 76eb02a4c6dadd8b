// A part far from its pivot (issue 13, session 65): the crossings find their steady samples by
// the turn about the part's own centre Q (ranges not narrowed by the lever) and certify each
// link's published chord about the pivot P once. The zero-clearance 12 x 3 peg below a wall
// with a 3 mm slot (tests/fuzz/sliced_oracle_hunt.py's peg_in_slot(3, 3): it cannot pass, 3
// components) pivoted 10^30 mm away had 4 components in slice64's variant of this (the nudges of
// the samples in the unit of the pair about P, 2^95 mm: the upper chamber's sample, touching the
// slot's corners at 90 degrees, was never moved off them, and the chamber's cells were not
// linked across +-90 degrees); the integ code linked it across -90 but not +90 degrees (47
// connections for 48). Checked against the same pair pivoted at Q: the components, the critical
// angles, and across every critical angle the same connections (by the cells' contacts); every
// witness free by the exact overlap predicate (part_overlap), in the cells its connection names,
// and the chord between the two witnesses free at 17 rational points by the predicate and
// certified by motion_free. (The peg 10^-9 wider, and the far pivots 10^6, 10^400 mm and off
// the axis: tests/fuzz/sliced_oracle_hunt.py's full run.)
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include "sliced_model_support.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

std::string lit(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }

std::string loop(const std::vector<std::pair<Rational, Rational>>& points) {
  std::string s = R"({ "start": [)" + lit(points[0].first) + "," + lit(points[0].second) + R"(], "edges": [)";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    s += std::string(i > 1 ? ", " : "") + R"({ "line_to": [)" + lit(p.first) + "," + lit(p.second) + "] }";
  }
  return s + "] }";
}

std::vector<std::pair<Rational, Rational>> box(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// The 12 x p peg (centre (0, -11)) below a wall with a 3 mm slot between two chambers.
Model peg_in_slot(const Rational& p, const Point& pivot) {
  const Rational w2(3, 2);
  const std::vector<std::pair<Rational, Rational>> inner = {
      {-10, -20}, {10, -20}, {10, -2}, {w2, -2}, {w2, 2}, {10, 2}, {10, 20}, {-10, 20}, {-10, 2}, {-w2, 2}, {-w2, -2}, {-10, -2}};
  return read_model(R"({ "hipair": 1, "name": "far-pivot", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + loop(box(-15, -25, 15, 25)) + ", " + loop(inner) + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [)" + lit(pivot.x) + "," + lit(pivot.y) + R"(] } }, "loops": [ )" +
                    loop(box(-6, Rational(-11 - p / 2), 6, Rational(-11 + p / 2))) + R"( ] } ] })");
}

using sliced_models::rotation;

bool apart(const Model& model, const SlicedConfiguration& q) {
  const auto [c, s] = rotation(q.angle);
  const Part& peg = model.parts[1];
  return part_overlap(model.parts[0], Placement{}, peg, placement_about(peg.motion.pivot, c, s, Point{q.x, q.y})).relation ==
         PartRelation::apart;
}

// Every crossing's connections as pairs of the cells' contacts.
std::vector<std::set<std::pair<std::string, std::string>>> links_by_contacts(const SlicedSpace& space) {
  std::vector<std::set<std::pair<std::string, std::string>>> out;
  for (const SlicedCrossing& crossing : space.crossings()) {
    out.emplace_back();
    for (const SlicedConnection& link : crossing.connections)
      out.back().emplace(space.intervals()[crossing.left_interval].free_cells[link.left_cell].contacts,
                         space.intervals()[crossing.right_interval].free_cells[link.right_cell].contacts);
  }
  return out;
}

void expect_as_about_the_centre(const Rational& p, std::size_t components, const std::string& what) {
  const Point centre{Rational(0), Rational(-11)};
  const SlicedSpace near = SlicedSpace::build(peg_in_slot(p, centre), "plate", "peg");
  ASSERT_EQ(near.components(), components) << what;
  const auto expected = links_by_contacts(near);
  const Point pivot{Rational(mpz_class("1000000000000000000000000000000")), centre.y};
  SCOPED_TRACE(what + ", pivot at x = 10^30");
  const Model model = peg_in_slot(p, pivot);
  const SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
  EXPECT_EQ(space.components(), components);
  ASSERT_EQ(space.critical_angles().size(), near.critical_angles().size());
  for (std::size_t k = 0; k < near.critical_angles().size(); ++k) {
    const CriticalAngle &a = space.critical_angles()[k], &b = near.critical_angles()[k];
    EXPECT_EQ(a.half_turn, b.half_turn);
    if (a.half_turn) continue;
    // the same root: the same polynomial (or rational) and overlapping isolating intervals
    EXPECT_EQ(a.t.exact, b.t.exact) << "critical angle " << k;
    EXPECT_EQ(a.t.polynomial, b.t.polynomial) << "critical angle " << k;
    const Rational &a_hi = a.t.exact ? a.t.lower : a.t.upper, &b_hi = b.t.exact ? b.t.lower : b.t.upper;
    EXPECT_TRUE(a.t.lower <= b_hi && b.t.lower <= a_hi) << "critical angle " << k;
  }
  const auto got = links_by_contacts(space);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got[k], expected[k]) << "crossing of critical angle " << k;
  for (const SlicedCrossing& crossing : space.crossings())
    for (const SlicedConnection& link : crossing.connections) {
      SCOPED_TRACE("crossing " + std::to_string(crossing.critical));
      const SlicedLocation a = space.locate(link.left_witness), b = space.locate(link.right_witness);
      ASSERT_EQ(a.kind, SlicedLocation::Kind::free);
      ASSERT_EQ(b.kind, SlicedLocation::Kind::free);
      EXPECT_EQ(a.interval, crossing.left_interval);
      EXPECT_EQ(a.cell, link.left_cell);
      EXPECT_EQ(b.interval, crossing.right_interval);
      EXPECT_EQ(b.cell, link.right_cell);
      // the chord of the chart (offset and chart coordinate linear) at 17 points, by the predicate
      auto chart = [&](const SlicedAngle& angle) {
        if (!link.through_half_turn) return angle.t;
        return angle.half_turn ? Rational(0) : Rational(-1 / angle.t);
      };
      const Rational u0 = chart(link.left_witness.angle), u1 = chart(link.right_witness.angle);
      for (int k = 0; k <= 16; ++k) {
        const Rational f(k, 16);
        const Rational u = u0 + (u1 - u0) * f;
        SlicedAngle angle{u, false};
        if (link.through_half_turn) angle = sgn(u) == 0 ? SlicedAngle{Rational(0), true} : SlicedAngle{Rational(-1 / u), false};
        const SlicedConfiguration q{Rational(link.left_witness.x + (link.right_witness.x - link.left_witness.x) * f),
                                    Rational(link.left_witness.y + (link.right_witness.y - link.left_witness.y) * f), angle};
        ASSERT_TRUE(apart(model, q)) << "chord point " << k;
      }
      EXPECT_TRUE(space.motion_free(SlicedMotion{link.left_witness, link.right_witness, link.through_half_turn, {}}));
    }
}

TEST(SlicedFarPivot, AZeroClearancePegInTheSlotFarFromItsPivotHasTheCrossingsOfItsCentre) {
  expect_as_about_the_centre(Rational(3), 3, "the peg as wide as the slot");
}

}  // namespace
}  // namespace hipair
