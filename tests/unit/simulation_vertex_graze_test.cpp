// A motion that passes exactly through a C-space vertex from free space into free space only
// grazes: no impulse (docs/simulation.md, "Session 41 (graze41)"). Two translating 10 mm squares
// without forces, the cart free along x, the slider along y, whose corners meet at t*: in C-space
// (cart offset a, slider offset b) the blocked region is the open rectangle 0 < a < 20,
// -20 < b < 0, and the motion is the line (a, b) = (vx (t - t*) + delta, vy (t - t*)). With
// delta = 0 and both velocities of one sign it passes through the rectangle's corner (0, 0)
// outside it on both sides; with delta > 0 it cuts the corner (a real impact), with delta < 0
// it passes it by (no event). Oracle: the pair's exact point location (CSpace::locate) on the
// exact line near the vertex. Before session 41, with both velocities positive, the simulator
// struck the edge the motion approaches with a full impulse at delta = 0.
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <random>
#include <string>

#include "simulation/vertex_graze.hpp"

namespace hipair {
namespace {

// n / 64, or with a delta of 2^-k: exact rational expressions of the model
std::string ratio(long n, long d) { return std::to_string(n) + "/" + std::to_string(d); }

nlohmann::json corners(long vx64, long vy64, long t64, int delta_sign, int delta_bits, double restitution) {
  auto square = [](int x, int y) {
    return nlohmann::json{{{"start", {x, y}},
                           {"edges", {{{"line_to", {x + 10, y}}}, {{"line_to", {x + 10, y + 10}}}, {{"line_to", {x, y + 10}}}, {{"line_to", {x, y}}}}}}};
  };
  auto part = [&](const char* name, int axis, const std::string& offset, int x, int y) {
    return nlohmann::json{{"name", name},
                          {"motion", {{"translation", {{"direction", {axis == 0 ? 1 : 0, axis}}, {"limits", {-50, 50}}}}}},
                          {"initial", {{"offset", offset}}},
                          {"dynamics", {{"mass", 1}}},
                          {"loops", square(x, y)}};
  };
  // offsets at t = 0: a0 = -vx t* + delta, b0 = -vy t*
  std::string a0 = ratio(-vx64 * t64, 4096);
  if (delta_sign != 0) a0 += (delta_sign > 0 ? " + 1/" : " - 1/") + std::to_string(1L << delta_bits);
  return {{"hipair", 1},
          {"name", "corners"},
          {"parts", {part("cart", 0, a0, 0, 0), part("slider", 1, ratio(-vy64 * t64, 4096), 10, 10)}},
          {"pairs", {{{"parts", {"cart", "slider"}}, {"restitution", restitution}}}},
          {"simulation", {{"velocities", {{"cart", ratio(vx64, 64)}, {"slider", ratio(vy64, 64)}}}}}};
}

// The oracle: whether the exact line enters blocked space near the vertex (points spaced a
// quarter of the time the line spends within delta of the vertex, 8 either side of t*).
bool line_enters_blocked(const CSpace& space, long vx64, long vy64, long t64, int delta_sign, int delta_bits) {
  const Rational vx(vx64, 64), vy(vy64, 64), t_star(t64, 64);
  Rational delta = delta_sign == 0 ? Rational(0) : Rational(delta_sign, 1L << delta_bits);
  delta.canonicalize();
  Rational tau = delta_sign == 0 ? Rational(1, 4096) : Rational(1, 1L << delta_bits) / (4 * abs(vx));
  for (int k = -8; k <= 8; ++k) {
    const Rational t = t_star + k * tau;
    PartCoordinate a{PartCoordinate::Kind::offset, Rational(vx * (t - t_star) + delta)};
    PartCoordinate b{PartCoordinate::Kind::offset, Rational(vy * (t - t_star))};
    if (space.locate(a, b).kind == Location::Kind::blocked) return true;
  }
  return false;
}

TEST(SimulationVertexGraze, CornersPassingThroughEachOtherGrazeCutOrMiss) {
  std::mt19937 random(41);
  auto pick = [&](long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(random); };
  const int deltas[][2] = {{0, 0}, {1, 10}, {-1, 10}, {1, 20}, {-1, 20}, {1, 30}, {-1, 30}};
  int grazes = 0, cuts = 0, misses = 0;
  for (int trial = 0; trial < 18; ++trial) {
    const long sign = trial % 2 == 0 ? 1 : -1;
    const long vx64 = sign * pick(64, 20 * 64), vy64 = sign * pick(64, 20 * 64), t64 = pick(7, 32);
    const double restitution = trial % 3 == 0 ? 1 : trial % 3 == 1 ? 0 : 0.5;
    SimulationOptions options;
    options.accuracy = (trial / 3) % 3 == 0 ? 1e-3 : (trial / 3) % 3 == 1 ? 1e-6 : 1e-9;
    options.max_steps = 3000;
    for (const auto& [delta_sign, delta_bits] : deltas) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << " v " << vx64 << "/64 " << vy64 << "/64 t* " << t64
                                        << "/64 delta " << delta_sign << " 2^-" << delta_bits << " e " << restitution
                                        << " accuracy " << options.accuracy);
      Simulation s = Simulation::create(read_model(corners(vx64, vy64, t64, delta_sign, delta_bits, restitution).dump(), "corners"), options);
      const bool enters = line_enters_blocked(*s.spaces().at(0), vx64, vy64, t64, delta_sign, delta_bits);
      // the oracle's answer where the exact geometry is plain: the corner is cut for delta > 0
      ASSERT_EQ(enters, delta_sign > 0);
      const double vx = vx64 / 64.0, vy = vy64 / 64.0, t_star = t64 / 64.0;
      while (s.state().time < 2 * t_star) {
        const double t = s.state().time;
        ASSERT_NO_THROW(s.step()) << "at t = " << t;
        ASSERT_GT(s.state().time, t);
      }
      if (enters) {
        // a real impact where the line enters the rectangle, with an impulse: moving up and right
        // it strikes the side a = 0 at t* - delta / vx, moving down and left the side b = 0 at t*
        ++cuts;
        ASSERT_FALSE(s.events().empty());
        EXPECT_EQ(s.events()[0].kind, SimulationEvent::Kind::impact);
        EXPECT_GT(s.events()[0].impulse, 0);
        EXPECT_NEAR(s.events()[0].time, sign > 0 ? t_star - std::ldexp(1.0, -delta_bits) / vx : t_star, 1e-6);
        continue;
      }
      if (delta_sign == 0) ++grazes;
      else ++misses;
      // a graze or a miss: touches without impulse at most, the velocities kept
      if (delta_sign != 0) EXPECT_TRUE(s.events().empty());
      EXPECT_LE(s.events().size(), 1u);
      for (const SimulationEvent& e : s.events()) {
        EXPECT_EQ(e.kind, SimulationEvent::Kind::impact);
        EXPECT_EQ(e.impulse, 0);
        EXPECT_EQ(e.tangential_impulse, 0);
        EXPECT_NEAR(e.time, t_star, 1e-9);
      }
      EXPECT_NEAR(s.state().velocity[0], vx, 1e-12 * std::abs(vx));
      EXPECT_NEAR(s.state().velocity[1], vy, 1e-12 * std::abs(vy));
    }
  }
  EXPECT_EQ(grazes, 18);
  EXPECT_EQ(cuts, 54);
  EXPECT_EQ(misses, 54);
}

// vertex_pass itself at the rectangle's four corners, for lines through each in 120 directions
// (integer steps -5..5 each way; along the sides too), against the exact point location of the
// line's points 1/1000 of a step either side of the corner: ahead blocked -> enters; both free ->
// graze; otherwise (along a side: ahead on an edge) not decided.
TEST(SimulationVertexGraze, VertexPassAgreesWithPointLocation) {
  Model model = read_model(corners(64, 64, 16, 0, 0, 0).dump(), "corners");
  const CSpace space = CSpace::build(model, "cart", "slider");
  int counts[3] = {0, 0, 0};
  for (int ca : {0, 20})
    for (int cb : {0, -20})
      for (int dx = -5; dx <= 5; ++dx)
        for (int dy = -5; dy <= 5; ++dy) {
          if (dx == 0 && dy == 0) continue;
          SCOPED_TRACE(::testing::Message() << "corner " << ca << " " << cb << " direction " << dx << " " << dy);
          auto at = [&](const Rational& s) {
            return space.locate(PartCoordinate{PartCoordinate::Kind::offset, Rational(ca + dx * s)},
                                PartCoordinate{PartCoordinate::Kind::offset, Rational(cb + dy * s)})
                .kind;
          };
          const Location::Kind ahead = at(Rational(1, 1000)), behind = at(Rational(-1, 1000));
          simulation::VertexPass expected = ahead == Location::Kind::blocked ? simulation::VertexPass::enters
                                            : ahead == Location::Kind::free && behind == Location::Kind::free
                                                ? simulation::VertexPass::graze
                                                : simulation::VertexPass::unknown;
          // the line through the corner at u = 1/2, u in [0, 1]; the query's grazing bracket
          MotionPath path;
          path.x = AxisPath{AxisPath::Kind::offset, {Rational(ca) - Rational(dx, 2), Rational(dx)}};
          path.y = AxisPath{AxisPath::Kind::offset, {Rational(cb) - Rational(dy, 2), Rational(dy)}};
          MotionCrossing c;
          c.status = CrossingStatus::crossing;
          c.grazing = true;
          c.u_lower = Rational(1, 2) - Rational(1, 1L << 40);
          c.u_upper = Rational(1, 2) + Rational(1, 1L << 40);
          c.chart = space.to_chart(PartCoordinate{PartCoordinate::Kind::offset, Rational(ca)},
                                   PartCoordinate{PartCoordinate::Kind::offset, Rational(cb)})
                        ->chart;
          const simulation::VertexPass got = simulation::vertex_pass(space, c, path);
          EXPECT_EQ(static_cast<int>(got), static_cast<int>(expected));
          ++counts[static_cast<int>(got)];
          // not grazing (the query certified another cell): never decided here
          c.grazing = false;
          EXPECT_EQ(static_cast<int>(simulation::vertex_pass(space, c, path)), static_cast<int>(simulation::VertexPass::unknown));
        }
  // each corner of 120 directions: 25 strictly into the rectangle; 25 out of it, 10 along its two
  // sides and 10 coming along them (not decided); 50 through the corner from free to free
  EXPECT_EQ(counts[0], 4 * 45);
  EXPECT_EQ(counts[1], 4 * 50);
  EXPECT_EQ(counts[2], 4 * 25);
}

}  // namespace
}  // namespace hipair
