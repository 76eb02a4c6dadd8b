// A 1-DOF pair's crossing decided from its exact C-space along the motion (docs/simulation.md,
// "Session 75 (graze75)"). Generated pairs at exact zero clearance, one part moving (translating
// along x, or turning about the origin), the other fixed: a corner that meets a corner and goes on
// into blocked space (an impact: v -> -e v), a corner that only grazes a corner (free on both sides:
// no impulse, speed kept), a part sliding flush under another (a touching cell: no impulse; the
// simulator refuses to follow it). Oracle: the pair's exact point location (CSpace::locate) on
// both sides of the contact configuration s*, which the construction knows exactly. Before,
// corner on corner was struck whatever lay beyond (graze-slide: thrown back), and a rotating
// corner meeting a corner head-on stopped as "a jammed contact change" (hostile75 M1).
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "test_seed.hpp"

namespace hipair {
namespace {

using Json = nlohmann::json;

std::string text(const Rational& r) { return r.get_str(); }

Json loop(const std::vector<std::array<Rational, 2>>& points) {
  Json edges = Json::array();
  for (std::size_t k = 1; k <= points.size(); ++k) {
    const auto& p = points[k % points.size()];
    edges.push_back({{"line_to", {text(p[0]), text(p[1])}}});
  }
  return Json::array({{{"start", {text(points[0][0]), text(points[0][1])}}, {"edges", edges}}});
}

// the three constructions along x (a translating to +x from offset 0; mirrored for -x)
enum class Kind { enters, grazes, slides };

struct Case {
  Kind kind;
  Rational x0;        // where a's leading corner meets b's corner: s* = x0 - 1 (a's corner at x = 1)
  Rational speed;     // mm/s, its sign the direction
  double restitution;
};

Json translating(const Case& c) {
  const Rational one(1), two(2), zero(0);
  // a: the unit square, or (grazes) the triangle (0,0) (1,0) (1,1) whose corner (1,1) leads
  std::vector<std::array<Rational, 2>> a = c.kind == Kind::grazes
                                               ? std::vector<std::array<Rational, 2>>{{zero, zero}, {one, zero}, {one, one}}
                                               : std::vector<std::array<Rational, 2>>{{zero, zero}, {one, zero}, {one, one}, {zero, one}};
  const Rational& x = c.x0;
  std::vector<std::array<Rational, 2>> b;
  if (c.kind == Kind::enters) b = {{x, one}, {x + 2, zero}, {x + 2, two}};                        // a wedge: its corner into a's way
  else if (c.kind == Kind::grazes) b = {{x, one}, {x + 1, two}, {x - 1, two}};                    // apex down on a's apex line
  else b = {{x, one}, {x + 1, one}, {x + 1, two}, {x, two}};                                         // flush above a's top edge
  if (c.speed < 0) {
    // mirrored: a moves to -x, its leading corner at x = 0 meets b's at -x0 + 1 ... mirror every x
    for (auto& p : a) p[0] = one - p[0];
    for (auto& p : b) p[0] = one - p[0];
    std::reverse(a.begin(), a.end());   // counter-clockwise again
    std::reverse(b.begin(), b.end());
  }
  return {{"hipair", 1},
          {"name", "line-pass"},
          {"parts",
           {{{"name", "a"},
             {"motion", {{"translation", {{"direction", {1, 0}}, {"limits", {-20, 20}}}}}},
             {"dynamics", {{"mass", 1}}},
             {"loops", loop(a)}},
            {{"name", "b"}, {"motion", "fixed"}, {"loops", loop(b)}}}},
          {"pairs", {{{"parts", {"a", "b"}}, {"restitution", c.restitution}, {"friction", 0}}}},
          {"simulation", {{"velocities", {{"a", text(c.speed)}}}}}};
}

Location::Kind at(const CSpace& space, const Rational& s) {
  return space.locate(PartCoordinate{PartCoordinate::Kind::offset, s}).kind;
}

// runs to t_end; true when the simulator refused (NumericError) on the way
bool run(Simulation& s, double t_end) {
  while (s.state().time < t_end) {
    const double t = s.state().time;
    try {
      s.step();
    } catch (const NumericError& e) {
      EXPECT_NE(std::string(e.what()).find("touching cell"), std::string::npos) << e.what();
      return true;
    }
    EXPECT_GT(s.state().time, t);
  }
  return false;
}

TEST(SimulationLinePass, TranslatingCornersEnterGrazeOrSlideAsTheExactCSpaceSays) {
  std::mt19937_64 random(test::test_seed(75));
  auto pick = [&](long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(random); };
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 24; ++trial) {
    Case c;
    c.kind = static_cast<Kind>(trial % 3);
    c.x0 = Rational(pick(12, 40), 8);   // 1.5 ... 5 mm
    c.x0.canonicalize();
    c.speed = Rational(pick(8, 160), 8) * (trial % 2 == 0 ? 1 : -1);
    c.speed.canonicalize();
    c.restitution = (trial / 6) % 3 == 0 ? 0 : (trial / 6) % 3 == 1 ? 0.5 : 1;
    SimulationOptions options;
    options.accuracy = trial % 4 < 2 ? 1e-6 : 1e-9;
    options.max_steps = 2000;
    const double v = c.speed.get_d();
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " kind " << trial % 3 << " x0 " << c.x0.get_str() << " v "
                                      << c.speed.get_str() << " e " << c.restitution);
    Simulation s = Simulation::create(read_model(translating(c).dump(), "line-pass"), options);
    const CSpace& space = *s.spaces().at(0);
    // the contact configuration s* (a's leading corner on b's corner), and the oracle beyond it
    const Rational s_star = c.speed > 0 ? Rational(c.x0 - 1) : Rational(-(c.x0 - 1));
    const Rational step(c.speed > 0 ? 1 : -1, 1024);
    ASSERT_EQ(at(space, s_star - step), Location::Kind::free);
    ASSERT_EQ(at(space, Rational(0)), Location::Kind::free);
    const Location::Kind beyond = at(space, s_star + step);
    const Location::Kind expected = c.kind == Kind::enters   ? Location::Kind::blocked
                                    : c.kind == Kind::grazes ? Location::Kind::free
                                                             : Location::Kind::touching;
    ASSERT_EQ(beyond, expected);
    ++counts[trial % 3];
    const double t_star = Rational(s_star / c.speed).get_d();
    const bool refused = run(s, 1.5 * t_star);
    if (beyond == Location::Kind::blocked) {
      // an impact at t*, restitution applied
      ASSERT_FALSE(refused);
      ASSERT_FALSE(s.events().empty());
      EXPECT_EQ(s.events()[0].kind, SimulationEvent::Kind::impact);
      EXPECT_GT(s.events()[0].impulse, 0);
      EXPECT_NEAR(s.events()[0].time, t_star, 1e-6 * t_star);
      EXPECT_NEAR(s.state().velocity[0], -c.restitution * v, 1e-9 * std::abs(v));
      continue;
    }
    // free or touching beyond: no impulse, the speed kept
    EXPECT_EQ(refused, beyond == Location::Kind::touching);
    for (const SimulationEvent& e : s.events()) {
      EXPECT_EQ(e.impulse, 0);
      EXPECT_EQ(e.normal_speed_before, e.normal_speed_after);
    }
    EXPECT_NEAR(s.state().velocity[0], v, 1e-12 * std::abs(v));
  }
  EXPECT_EQ(counts[0] + counts[1] + counts[2], 24);
}

// The bar [0, L] x [-1, 0] turning about the origin: its far corner (L, -1) sweeps the circle of
// radius sqrt(L^2 + 1) through the fixed square [L, L + 1] x [1, 2]'s corner (L, 1), which lies
// outside the square's sweep on both sides (graze); a rotating triangle's corner landing exactly
// on a fixed corner and going on into blocked space (hostile75 M1, sim-rf8) is an impact.
TEST(SimulationLinePass, RotatingCornerGrazesOrStrikesACorner) {
  std::mt19937_64 random(test::test_seed(7575));
  auto pick = [&](long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(random); };
  for (int trial = 0; trial < 8; ++trial) {
    const long L = pick(3, 12);
    const Rational w(pick(8, 32), 8);   // rad/s
    const Rational one(1), zero(0), bar(L);
    Json model = {{"hipair", 1},
                  {"name", "turn"},
                  {"parts",
                   {{{"name", "a"},
                     {"motion", {{"rotation", {{"pivot", {0, 0}}}}}},
                     {"dynamics", {{"moment_of_inertia", 1}}},
                     {"loops", loop({{zero, -one}, {bar, -one}, {bar, zero}, {zero, zero}})}},
                    {{"name", "b"}, {"motion", "fixed"}, {"loops", loop({{bar, one}, {bar + 1, one}, {bar + 1, 2}, {bar, 2}})}}}},
                  {"pairs", {{{"parts", {"a", "b"}}, {"restitution", 0.5}, {"friction", 0}}}},
                  {"simulation", {{"velocities", {{"a", text(w)}}}}}};
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " L " << L << " w " << w.get_str());
    SimulationOptions options;
    options.accuracy = trial % 2 ? 1e-6 : 1e-9;
    Simulation s = Simulation::create(read_model(model.dump(), "turn"), options);
    const CSpace& space = *s.spaces().at(0);
    // theta* = 2 atan(1/L): tan(theta*/2) = 1/L exactly; the oracle on both sides
    const Rational tan_star(1, L), d(1, 1L << 20);
    auto kind = [&](const Rational& t) {
      return space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t}).kind;
    };
    ASSERT_EQ(kind(tan_star - d), Location::Kind::free);
    ASSERT_EQ(kind(tan_star + d), Location::Kind::free);
    const double t_star = 2 * std::atan(1.0 / L) / w.get_d();
    EXPECT_FALSE(run(s, 2 * t_star));
    for (const SimulationEvent& e : s.events()) {
      EXPECT_EQ(e.impulse, 0);
      EXPECT_EQ(e.normal_speed_before, e.normal_speed_after);
    }
    EXPECT_NEAR(s.state().velocity[0], w.get_d(), 1e-12 * w.get_d());
  }
  // sim-rf8: the triangle (-2,-1) (0,-1) (-2,1) about (-2,1) turning back at -25 rad/s reaches
  // -3 pi/2, where its corner (-2,-1) lands on b's corner (0,1); beyond (smaller angles) blocked
  const Json rf8 = Json::parse(R"({"hipair": 1, "name": "cvx-rf-8", "units": {"length": "mm", "angle": "rad"}, "parts": [{"name": "a", "motion": {"rotation": {"pivot": ["-2", "1"]}}, "loops": [{"start": ["-2", "-1"], "edges": [{"line_to": ["0", "-1"]}, {"line_to": ["-2", "1"]}, {"line_to": ["-2", "-1"]}]}], "dynamics": {"moment_of_inertia": 1}}, {"name": "b", "motion": "fixed", "loops": [{"start": ["0", "1"], "edges": [{"line_to": ["3", "-1"]}, {"line_to": ["4", "2"]}, {"line_to": ["0", "1"]}]}, {"start": ["-1", "4"], "edges": [{"line_to": ["1", "4"]}, {"line_to": ["1", "5"]}, {"line_to": ["-1", "4"]}]}]}], "pairs": [{"parts": ["a", "b"], "restitution": 0.5, "friction": 0}], "simulation": {"units": {"time": "s", "force": "N"}, "velocities": {"a": 50}}})");
  SimulationOptions rf8_options;
  rf8_options.max_step = 0.01;
  Simulation s = Simulation::create(read_model(rf8.dump(), "rf8"), rf8_options);
  const CSpace& space = *s.spaces().at(0);
  auto kind = [&](const Rational& t) {
    return space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t}).kind;
  };
  // theta = pi/2 (tan 1): free on the larger side, blocked on the smaller
  ASSERT_EQ(kind(Rational(1) + Rational(1, 1 << 20)), Location::Kind::free);
  ASSERT_EQ(kind(Rational(1) - Rational(1, 1 << 20)), Location::Kind::blocked);
  EXPECT_FALSE(run(s, 0.3));
  ASSERT_GE(s.events().size(), 2u);
  const SimulationEvent& e = s.events()[1];
  EXPECT_EQ(e.kind, SimulationEvent::Kind::impact);
  EXPECT_GT(e.impulse, 0);
  EXPECT_NEAR(e.normal_speed_after, -0.5 * e.normal_speed_before, 1e-9 * std::abs(e.normal_speed_before));
  EXPECT_NEAR(s.state().velocity[0], 12.5, 1e-9);
}

}  // namespace
}  // namespace hipair
