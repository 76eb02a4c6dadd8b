// The crossings' witnesses of a part far from its pivot (issue 13, session 64): the motion
// certified between a connection's two witnesses is the turn of the part about its own centre
// Q (SlicedConnection::turn_centre), certified by the first-contact query of the part pivoted
// at Q, whose numbers are of the part's size (until session 64 the chord of the chart about the
// far pivot P, whose polynomials carried |Q - P|). Checked for the square peg in the hole of
// side 12 pivoted 10^6 and 10^30 mm away and the 12 x 2 peg in the 3 mm slot 10^30 mm away: every witness
// free and in the cells the connection names; the right witness the end of the turn from the
// left one, exactly; the turn free at 17 rational angles by the exact overlap predicate
// (part_overlap) and certified free as the pure rotation at one offset by the space of the same
// parts pivoted at Q (motion_free); the components and critical angles of the pivot at Q.
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

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

Model pair_model(const std::string& plate, const std::string& peg, const Point& pivot) {
  return read_model(R"({ "hipair": 1, "name": "far-turn", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + plate + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [)" + lit(pivot.x) + "," + lit(pivot.y) + R"(] } }, "loops": [ )" +
                    peg + R"( ] } ] })");
}

// The square peg of side 10 in a plate [-20, 20]^2 with a hole of side 12 (5 components).
Model peg_in_hole(const Point& pivot) {
  return pair_model(loop(box(-20, -20, 20, 20)) + ", " + loop(box(-6, -6, 6, 6)), loop(box(-5, -5, 5, 5)), pivot);
}

// The 12 x 2 peg below a wall with a 3 mm slot between two chambers (tests/fuzz/sliced_oracle_hunt.py's
// peg_in_slot(2, 3): 2 components).
Model peg_in_slot(const Point& pivot) {
  const Rational w2(3, 2);
  const std::vector<std::pair<Rational, Rational>> inner = {
      {-10, -20}, {10, -20}, {10, -2}, {w2, -2}, {w2, 2}, {10, 2}, {10, 20}, {-10, 20}, {-10, 2}, {-w2, 2}, {-w2, -2}, {-10, -2}};
  return pair_model(loop(box(-15, -25, 15, 25)) + ", " + loop(inner), loop(box(-6, -12, 6, -10)), pivot);
}

std::pair<Rational, Rational> rotation(const SlicedAngle& a) {
  if (a.half_turn) return {Rational(-1), Rational(0)};
  const Rational d = 1 + a.t * a.t;
  return {Rational((1 - a.t * a.t) / d), Rational(2 * a.t / d)};
}

bool apart(const Model& model, const SlicedConfiguration& q) {
  const auto [c, s] = rotation(q.angle);
  const Part& peg = model.parts[1];
  return part_overlap(model.parts[0], Placement{}, peg, placement_about(peg.motion.pivot, c, s, Point{q.x, q.y})).relation ==
         PartRelation::apart;
}

// The configuration about P of the turn about Q from `from` to the angle `to`.
SlicedConfiguration turned(const SlicedConfiguration& from, const SlicedAngle& to, const Point& q, const Point& p) {
  const auto [c0, s0] = rotation(from.angle);
  const auto [c1, s1] = rotation(to);
  const Rational vx = q.x - p.x, vy = q.y - p.y;
  SlicedConfiguration out{Rational(from.x + (c0 - c1) * vx - (s0 - s1) * vy), Rational(from.y + (s0 - s1) * vx + (c0 - c1) * vy), to};
  out.x.canonicalize();
  out.y.canonicalize();
  return out;
}

void expect_turns_free(Model (*make)(const Point&), const Point& centre, std::size_t components, const std::string& what,
                       const std::vector<const char*>& pivots) {
  const SlicedSpace near = SlicedSpace::build(make(centre), "plate", "peg");
  ASSERT_EQ(near.components(), components) << what;
  for (const char* far : pivots) {
    SCOPED_TRACE(what + ", pivot at x = " + far);
    const Point pivot{Rational(mpz_class(far)), centre.y};
    const Model model = make(pivot);
    const SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
    EXPECT_EQ(space.components(), components);
    EXPECT_EQ(space.critical_angles().size(), near.critical_angles().size());
    std::size_t turns = 0;
    for (const SlicedCrossing& crossing : space.crossings())
      for (const SlicedConnection& link : crossing.connections) {
        ASSERT_TRUE(link.turn_centre.has_value());
        const Point& q = *link.turn_centre;
        EXPECT_EQ(q.x, centre.x);
        EXPECT_EQ(q.y, centre.y);
        const SlicedLocation a = space.locate(link.left_witness), b = space.locate(link.right_witness);
        ASSERT_EQ(a.kind, SlicedLocation::Kind::free);
        ASSERT_EQ(b.kind, SlicedLocation::Kind::free);
        EXPECT_EQ(a.interval, crossing.left_interval);
        EXPECT_EQ(a.cell, link.left_cell);
        EXPECT_EQ(b.interval, crossing.right_interval);
        EXPECT_EQ(b.cell, link.right_cell);
        const SlicedConfiguration end = turned(link.left_witness, link.right_witness.angle, q, pivot);
        EXPECT_EQ(end.x, link.right_witness.x);
        EXPECT_EQ(end.y, link.right_witness.y);
        // the chart's half-angle tangent (about pi: -1/t) at 33 rational points, by the oracle
        auto chart = [&](const SlicedAngle& angle) {
          if (!link.through_half_turn) return angle.t;
          return angle.half_turn ? Rational(0) : Rational(-1 / angle.t);
        };
        const Rational u0 = chart(link.left_witness.angle), u1 = chart(link.right_witness.angle);
        for (int k = 0; k <= 16; ++k) {
          const Rational u = u0 + (u1 - u0) * Rational(k, 16);
          SlicedAngle angle{u, false};
          if (link.through_half_turn) angle = sgn(u) == 0 ? SlicedAngle{Rational(0), true} : SlicedAngle{Rational(-1 / u), false};
          ASSERT_TRUE(apart(model, turned(link.left_witness, angle, q, pivot))) << "turn point " << k;
        }
        // certified: the pure rotation at the offset about Q, in the space pivoted at Q
        SlicedConfiguration from = turned(link.left_witness, SlicedAngle{Rational(0), false}, q, pivot);
        from.angle = link.left_witness.angle;
        SlicedConfiguration to = from;
        to.angle = link.right_witness.angle;
        EXPECT_TRUE(near.motion_free(SlicedMotion{from, to, link.through_half_turn, {}}));
        ++turns;
      }
    EXPECT_GE(turns, near.critical_angles().size());
  }
}

TEST(SlicedFarTurn, WitnessesTurnAboutThePartsOwnCentreFreely) {
  expect_turns_free(peg_in_hole, Point{0, 0}, 5, "peg in the hole of side 12", {"1000000", "1000000000000000000000000000000"});
  expect_turns_free(peg_in_slot, Point{0, -11}, 2, "peg in the 3 mm slot", {"1000000000000000000000000000000"});
}

TEST(SlicedFarTurn, APivotOnThePartKeepsThePureRotation) {
  const SlicedSpace space = SlicedSpace::build(peg_in_hole(Point{1, 2}), "plate", "peg");
  std::size_t links = 0;
  for (const SlicedCrossing& crossing : space.crossings())
    for (const SlicedConnection& link : crossing.connections) {
      EXPECT_FALSE(link.turn_centre.has_value());
      EXPECT_EQ(link.left_witness.x, link.right_witness.x);
      EXPECT_EQ(link.left_witness.y, link.right_witness.y);
      ++links;
    }
  EXPECT_GT(links, 12u);
}

}  // namespace
}  // namespace hipair
