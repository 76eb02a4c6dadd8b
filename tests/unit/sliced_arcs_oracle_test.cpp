// 3-DOF pairs with arcs and zero-clearance fits (a stadium in a stadium-shaped pocket of its own
// size, a rounded rectangle against a plate with a round hole, a star against a round pin):
// exact point location in (x, y, theta) against the exact overlap predicate, at random rational
// configurations and on every vertical edge of the slices at the angles 0 and a random one (the
// lines where a vertex meets a side, or a side meets a round end tangentially).
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string q(const Rational& r) { return "\"" + r.get_str() + "\""; }
std::string at(const Rational& x, const Rational& y) { return "[" + q(x) + ", " + q(y) + "]"; }

std::string stadium(const Rational& x0, const Rational& x1, const Rational& y, const Rational& r) {
  return "{ \"start\": " + at(x0, y - r) + ", \"edges\": [ { \"line_to\": " + at(x1, y - r) + " }, { \"arc_to\": " +
         at(x1, y + r) + ", \"center\": " + at(x1, y) + ", \"dir\": \"ccw\" }, { \"line_to\": " + at(x0, y + r) +
         " }, { \"arc_to\": " + at(x0, y - r) + ", \"center\": " + at(x0, y) + ", \"dir\": \"ccw\" } ] }";
}

std::string square(const Rational& h) {
  return "{ \"start\": " + at(-h, -h) + ", \"edges\": [ { \"line_to\": " + at(h, -h) + " }, { \"line_to\": " + at(h, h) +
         " }, { \"line_to\": " + at(-h, h) + " }, { \"line_to\": " + at(-h, -h) + " } ] }";
}

std::string circle(const Rational& cx, const Rational& cy, const Rational& r) {
  return "{ \"circle\": { \"center\": " + at(cx, cy) + ", \"radius\": " + q(r) + " } }";
}

std::string triangle() {
  return "{ \"start\": [\"-3/2\", \"-1\"], \"edges\": [ { \"line_to\": [\"2\", \"-1/2\"] }, { \"line_to\": [\"-1/4\", \"7/4\"] }, "
         "{ \"line_to\": [\"-3/2\", \"-1\"] } ] }";
}

std::string model(const std::string& fixed_loops, const std::string& free_loops) {
  return R"({ "hipair": 1, "name": "sliced arcs", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + fixed_loops + R"( ] },
    { "name": "part", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + free_loops + R"( ] } ] })";
}

Rational rational(std::mt19937_64& random, long span, long denominator) {
  Rational r(static_cast<long>(random() % (2 * span * denominator + 1)) - span * denominator, denominator);
  r.canonicalize();
  return r;
}

TEST(SlicedArcsOracle, PointLocationEqualsTheExactOverlapPredicate) {
  const Rational r(3, 2), len(4);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"stadium in its own pocket", model(square(Rational(8)) + ", " + stadium(-len / 2, len / 2, 0, r), stadium(-len / 2, len / 2, 0, r))},
      {"stadium against a round pin", model(circle(Rational(1), Rational(1, 2), Rational(1)), stadium(-len / 2, len / 2, 0, r))},
      {"triangle in a round hole", model(square(Rational(6)) + ", " + circle(Rational(0), Rational(0), Rational(5, 2)), triangle())},
  };
  std::mt19937_64 random(31);
  int checked = 0, contacts = 0;
  for (const auto& [name, json] : cases) {
    SCOPED_TRACE(name);
    const Model m = read_model(json);
    const SlicedSpace space = SlicedSpace::build(m, "plate", "part");
    const Part& plate = m.parts[0];
    const Part& part = m.parts[1];
    std::vector<SlicedConfiguration> points;
    for (int i = 0; i < 1500; ++i)
      points.push_back(SlicedConfiguration{rational(random, 6, 8), rational(random, 6, 8),
                                           random() % 29 == 0 ? SlicedAngle{0, true} : SlicedAngle{rational(random, 3, 16), false}});
    for (const SlicedAngle& angle : {SlicedAngle{0, false}, SlicedAngle{Rational(1, 3), false}, SlicedAngle{0, true}}) {
      const std::shared_ptr<const CSpace> slice = space.slice(angle);
      for (std::size_t e = 0; e < slice->edges().size(); ++e) {
        const CSpaceEdge& edge = slice->edges()[e];
        if (!edge.vertical) continue;
        const auto& f = slice->edge_polynomial_coefficients(e);
        if (f.size() != 2 || f[1].empty() || f[1][0] == 0) continue;
        Rational x(mpz_class(-f[0][0]), f[1][0]);
        x.canonicalize();
        for (int k = 0; k <= 8; ++k) {
          Rational y(std::lround(256 * (edge.y_chart.lower + (edge.y_chart.upper - edge.y_chart.lower) * k / 8)), 256);
          y.canonicalize();
          points.push_back(SlicedConfiguration{x, y, angle});
        }
      }
      for (const CSpaceVertex& v : slice->vertices())
        if (v.x.exact && v.y_exact && v.y.exact) points.push_back(SlicedConfiguration{v.x.lower, v.y.lower, angle});
    }
    int wrong = 0;
    for (const SlicedConfiguration& c : points) {
      SlicedLocation l;
      try {
        l = space.locate(c);
      } catch (const Error& e) {
        if (++wrong <= 3) ADD_FAILURE() << "locate (" << c.x << ", " << c.y << ", t " << c.angle.t << "): " << e.what();
        continue;
      }
      Rational cs(-1), sn(0);
      if (!c.angle.half_turn) {
        const Rational d = 1 + c.angle.t * c.angle.t;
        cs = (1 - c.angle.t * c.angle.t) / d;
        sn = 2 * c.angle.t / d;
      }
      const PartRelation relation =
          part_overlap(plate, Placement{}, part, placement_about(part.motion.pivot, cs, sn, Point{c.x, c.y})).relation;
      const bool agrees = relation == PartRelation::apart         ? l.kind == SlicedLocation::Kind::free
                          : relation == PartRelation::overlapping ? l.kind == SlicedLocation::Kind::blocked
                                                                  : l.kind == SlicedLocation::Kind::contact;
      if (!agrees && ++wrong <= 3)
        ADD_FAILURE() << "at (" << c.x << ", " << c.y << ", t " << (c.angle.half_turn ? std::string("half turn") : c.angle.t.get_str())
                      << "): located " << static_cast<int>(l.kind) << ", the parts are "
                      << (relation == PartRelation::apart ? "apart" : relation == PartRelation::overlapping ? "overlapping" : "touching");
      ++checked;
      contacts += relation == PartRelation::touching;
    }
    EXPECT_EQ(wrong, 0);
  }
  std::cout << checked << " configurations, " << contacts << " touching\n";
  EXPECT_GT(checked, 4500);
  EXPECT_GT(contacts, 50);
}

}  // namespace
}  // namespace hipair
