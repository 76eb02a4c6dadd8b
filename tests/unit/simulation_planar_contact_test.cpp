// Sustained contact and Coulomb friction of a part free in the plane (docs/simulation.md,
// "Sustained contact of a planar part"), against closed forms on generated cases: a block
// sliding on a floor with friction (deceleration mu_k g, stop at v^2 / (2 mu_k g)), a block
// under tilted gravity (an incline: sticks iff tan(alpha) <= mu_s, else slides with
// g (sin - mu_k cos)), the frictionless ladder (leaves the wall at 2/3 of its height), a rocking
// peg's energy (never gained with e <= 1), the thrown spinning peg of
// examples/models/peg-throw.json (runs to rest, every state exactly not blocked), the
// curvature terms of the held contacts (finite differences) and step-size independence.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"
#include "simulation/planar_bounds.hpp"
#include "simulation/friction.hpp"
#include "test_paths.hpp"

#include <cmath>
#include <iostream>
#include <cstdint>
#include <iomanip>
#include <optional>
#include <array>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

// A planar part "body" (a polygon in body coordinates, pivot = centre of mass at the origin)
// among the fixed part "base" (an L: a floor with top y = 0 for x in [0, 1000] and a wall with
// face x = 0 up to y = 1000; or a floor only).
struct Scene {
  std::vector<std::array<double, 2>> body;   // counter-clockwise
  bool wall = false;
  bool table = false;   // the floor ends at x = 0 (a table top for x in [-1000, 0], its side below)
  double mass = 0.01, inertia = 0.2, e = 0;
  double gx = 0, gy = -9810;
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;
  double mu_static = 0, mu_kinetic = 0;
  // exact decimals written as given (override gx, gy and the friction coefficients)
  std::string gravity_text, mu_text;

  std::string json() const {
    std::string base = table ? R"({ "start": [-1000, -500], "edges": [ { "line_to": [0, -500] }, { "line_to": [0, 0], "label": "side" },
          { "line_to": [-1000, 0], "label": "table" }, { "line_to": [-1000, -500] } ] })"
                       : wall ? R"({ "start": [-20, -20], "edges": [ { "line_to": [1000, -20] }, { "line_to": [1000, 0] },
          { "line_to": [0, 0], "label": "floor" }, { "line_to": [0, 1000], "label": "wall" }, { "line_to": [-20, 1000] },
          { "line_to": [-20, -20] } ] })"
                            : R"({ "start": [-1000, -20], "edges": [ { "line_to": [1000, -20] }, { "line_to": [1000, 0] },
          { "line_to": [-1000, 0], "label": "floor" }, { "line_to": [-1000, -20] } ] })";
    std::string edges;
    for (std::size_t i = 1; i <= body.size(); ++i) {
      const auto& p = body[i % body.size()];
      edges += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + num(p[0]) + ", " + num(p[1]) + "] }";
    }
    std::string friction = !mu_text.empty() ? R"(, "friction": { "static": )" + mu_text + R"(, "kinetic": )" + mu_text + " }"
                           : mu_static > 0 ? R"(, "friction": { "static": )" + num(mu_static) + R"(, "kinetic": )" +
                                               num(mu_kinetic) + " }"
                                         : "";
    return R"({ "hipair": 1, "name": "contact", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "base", "motion": "fixed", "loops": [ )" + base + R"( ] },
        { "name": "body", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(x) + R"(, "y": )" + num(y) + R"(, "angle": )" + num(angle) + R"( },
          "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(inertia) + R"( },
          "loops": [ { "start": [)" + num(body[0][0]) + ", " + num(body[0][1]) + R"(], "edges": [ )" + edges + R"( ] } ] } ],
      "pairs": [ { "parts": ["base", "body"], "restitution": )" + num(e) + friction + R"( } ],
      "simulation": { "gravity": [)" + (gravity_text.empty() ? num(gx) + ", " + num(gy) : gravity_text) + R"(], "velocities": { "body": { "x": )" + num(vx) +
           R"(, "y": )" + num(vy) + R"(, "angle": )" + num(omega) + R"( } } } })";
  }
  Model model() const { return read_model(json(), "<scene>"); }
};

std::vector<std::array<double, 2>> box(double w, double h) {
  return {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
}

// A uniform w x h block (its moment of inertia m (w^2 + h^2) / 12) a gap above the floor.
Scene block_scene(double w, double h, double gap) {
  Scene scene;
  scene.body = box(w, h);
  scene.inertia = scene.mass * (w * w + h * h) / 12;
  scene.y = h / 2 + gap;
  return scene;
}

std::size_t count(const std::vector<SimulationEvent>& events, SimulationEvent::Kind kind) {
  std::size_t n = 0;
  for (const auto& e : events) n += e.kind == kind;
  return n;
}

// Steps until an event of `kind` appears (or t_end); the index of that event or npos.
std::size_t run_to(PlanarSimulation& s, SimulationEvent::Kind kind, double t_end, std::size_t from = 0) {
  for (;;) {
    for (std::size_t i = from; i < s.events().size(); ++i)
      if (s.events()[i].kind == kind) return i;
    if (s.state().time >= t_end || s.state().resting) return std::string::npos;
    from = s.events().size();
    s.step(t_end);
  }
}

// A held contact's force sign, exact (docs/simulation.md, "Session 63 (exact63)"): a block
// thrown into the corner of a floor and a wall (plastic, frictionless), held there with gravity
// g_x = -9810 mm/s^2 into the wall and g_y = sigma 2^-k 9810 along the floor's normal (k up to
// 80). Its floor contacts' forces are -m g_y: a pull (sigma = 1) lifts the block off the floor
// however small, a push (sigma = -1) holds it; the wall's contacts carry m |g_x| and never lift
// off. Before session 63 the planar simulators held a contact until its force fell below 10^-9
// of the loads (force_tolerance): pulls below that stayed held with a negative force. (Not at
// 2^-100 g, nor with no load at all: the landing's plastic impact leaves velocities of
// round-off's size whose velocity terms are in the rows exactly and decide the sign there — a
// push of 2^-100 g was lifted by them: the rows' doubles, docs/simulation.md.)
TEST(SimulationPlanarContact, BlockInACornerLiftsOffTheFloorExactlyWhenItsLoadPullsAway) {
  int cases = 0;
  for (const int k : {1, 20, 29, 33, 40, 52, 53, 64, 80})
    for (const int sigma : {1, -1}) {
      double w = 10, h = 4, gap = 1e-3;
      Scene scene = block_scene(w, h, gap);
      scene.wall = true;
      scene.x = w / 2 + gap;
      scene.vx = scene.vy = -100;
      scene.gx = -9810;
      scene.gy = sigma * std::ldexp(9810.0, -k);
      PlanarSimulation s = PlanarSimulation::create(scene.model());
      s.run_until(0.002);
      std::size_t floor_lifts = 0, wall_lifts = 0, floor_contacts = 0;
      for (const SimulationEvent& e : s.events()) {
        const bool floor = !e.features.empty() && e.features[0].find("floor") != std::string::npos;
        const bool wall = !e.features.empty() && e.features[0].find("wall") != std::string::npos;
        if (e.kind == SimulationEvent::Kind::lift_off) (floor ? floor_lifts : wall_lifts) += floor || wall;
        if (e.kind == SimulationEvent::Kind::contact && floor) ++floor_contacts;
      }
      ASSERT_GT(floor_contacts, 0u) << "k " << k << " sigma " << sigma;   // held on the floor after the landing
      EXPECT_EQ(wall_lifts, 0u) << "k " << k << " sigma " << sigma;
      if (sigma > 0) EXPECT_GT(floor_lifts, 0u) << "k " << k << ": a pull of 2^-" << k << " g stayed held";
      else EXPECT_EQ(floor_lifts, 0u) << "k " << k << " sigma " << sigma;
      ++cases;
    }
  EXPECT_EQ(cases, 18);
}

// A block w x h dropped flat from a gap of 10^-3 mm with horizontal speed v lands (plastic) at
// t_f = sqrt(2 gap / g) with normal speed v_n = g t_f; the impact's Coulomb impulse leaves
// v+ = v - mu_k v_n (it slides through the impact); then it decelerates at mu_k g and stops
// after v+^2 / (2 mu_k g), at t_f + v+ / (mu_k g), and sticks (mu_s >= mu_k: at rest).
TEST(SimulationPlanarContact, SlidingBlockDeceleratesAtMuGAndStopsAtTheClosedFormDistance) {
  Lcg rng{3};
  for (int c = 0; c < 6; ++c) {
    double w = 10, h = 4, gap = 1e-3, g = 9810;
    Scene scene = block_scene(w, h, gap);
    scene.vx = rng.uniform(50, 300);
    scene.mu_static = rng.uniform(0.2, 0.8);
    scene.mu_kinetic = scene.mu_static * rng.uniform(0.5, 1);
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    double tf = std::sqrt(2 * gap / g), vn = g * tf, mu = scene.mu_kinetic;
    double v_plus = scene.vx - mu * vn;
    double t_stop = tf + v_plus / (mu * g);
    double x_stop = scene.vx * tf + v_plus * v_plus / (2 * mu * g);
    // the landing
    std::size_t landing = run_to(s, SimulationEvent::Kind::impact, 1);
    ASSERT_NE(landing, std::string::npos) << c;
    double delta = s.chord_deviation();
    // the landing time is within delta / v_n of the path's (the chord's accuracy)
    double t_landing_tol = 2 * delta / vn + 1e-12;
    EXPECT_NEAR(s.events()[landing].time, tf, t_landing_tol) << c;
    // (the normal speed at the landing is within g times the landing time's tolerance)
    EXPECT_NEAR(s.state().vx, v_plus, 1e-9 * scene.vx + mu * g * t_landing_tol) << c;
    // along the tangent t = (-n_y, n_x) = (-1, 0): against the motion
    EXPECT_NEAR(s.events()[landing].tangential_impulse, scene.mass * mu * vn / 1000,
                scene.mass * mu * g * t_landing_tol / 1000 + 1e-9 * scene.mass * vn / 1000) << c;
    // sliding: the velocity falls linearly at mu_k g (a quadratic motion: the integrator is
    // exact up to round-off; the accuracy 1e-9 is asserted)
    double t_mid = tf + 0.5 * (t_stop - tf);
    s.run_until(t_mid);
    EXPECT_NEAR(s.state().vx, v_plus - mu * g * (s.state().time - tf), 1e-9 * scene.vx + mu * g * t_landing_tol) << c;
    EXPECT_NEAR(s.state().y, h / 2, delta) << c;
    EXPECT_NEAR(s.state().angle, 0.0, delta / w) << c;
    // the stop: a stick event, then rest
    std::size_t stick = run_to(s, SimulationEvent::Kind::stick, 1);
    ASSERT_NE(stick, std::string::npos) << c;
    EXPECT_NEAR(s.events()[stick].time, t_stop, 1e-9 * t_stop + t_landing_tol) << c;
    EXPECT_NEAR(s.state().x, x_stop, 1e-9 * x_stop + scene.vx * t_landing_tol + delta) << c;
    s.run_until(t_stop + 0.05);
    EXPECT_TRUE(s.state().resting) << c;
    EXPECT_NEAR(s.state().x, x_stop, 1e-9 * x_stop + scene.vx * t_landing_tol + delta) << c;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
  }
}

// Tilted gravity g = G (sin a, -cos a) on a flat floor is the incline of angle a. The block
// falls a gap of 10^-3 mm, lands, and sticks iff tan a <= mu_s (cases 5 % either side of the
// limit; since session 11 the landed block is in the exact rest class, docs/simulation.md, and
// the exact case at the limit is the next test); sliding, its speed along
// the floor grows at G (sin a - mu_k cos a).
TEST(SimulationPlanarContact, BlockOnAnInclineSticksIffTanAlphaIsAtMostMuStatic) {
  Lcg rng{17};
  for (int c = 0; c < 8; ++c) {
    double w = 10, h = 4, gap = 1e-3, G = 9810;
    Scene scene = block_scene(w, h, gap);
    scene.mu_static = rng.uniform(0.15, 0.6);
    scene.mu_kinetic = scene.mu_static * rng.uniform(0.5, 1);
    bool sticks = c % 2 == 0;
    double tan_a = scene.mu_static * (sticks ? 0.95 : 1.05);
    double a = std::atan(tan_a);
    scene.gx = G * std::sin(a);
    scene.gy = -G * std::cos(a);
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    std::size_t landing = run_to(s, SimulationEvent::Kind::impact, 1);
    ASSERT_NE(landing, std::string::npos) << c;
    double x_landing = s.state().x;
    double gt = scene.gx, gn = -scene.gy;   // along and into the floor (the model's doubles)
    if (sticks) {
      s.run_until(0.05);
      EXPECT_TRUE(s.state().resting) << c;
      EXPECT_NEAR(s.state().x, x_landing, s.chord_deviation()) << c;
      EXPECT_GE(count(s.events(), SimulationEvent::Kind::stick), 1u) << c;
      EXPECT_EQ(count(s.events(), SimulationEvent::Kind::slip), 0u) << c;
      // the friction force holds the tangential load: f = -m g_t (force unit N, mN internally)
      const SimulationEvent& rest = s.events().back();
      EXPECT_EQ(rest.kind, SimulationEvent::Kind::contact) << c;
      EXPECT_NEAR(rest.normal_force, scene.mass * gn / 1000, 1e-9 * scene.mass * G / 1000) << c;
      EXPECT_NEAR(std::abs(rest.friction_force), scene.mass * gt / 1000, 1e-9 * scene.mass * G / 1000) << c;
    } else {
      s.run_until(0.02);
      double t1 = s.state().time, v1 = s.state().vx;
      s.run_until(0.04);
      double t2 = s.state().time, v2 = s.state().vx;
      EXPECT_FALSE(s.state().resting) << c;
      EXPECT_NEAR((v2 - v1) / (t2 - t1), gt - scene.mu_kinetic * gn, 1e-9 * G) << c;
      EXPECT_EQ(count(s.events(), SimulationEvent::Kind::stick), 0u) << c;
    }
  }
}

// The incline at the limit, tan a = mu_s exactly, in rationals: gravity (mu G, -G) with mu = k/100
// and G an integer, written as exact decimals. At equality Coulomb's law sticks; mu_s lowered by
// 10^-14 (relative ~3e-14, far inside the floating-point solver's 1e-9 margin, which calls it
// stick) the block must slide; raised by 10^-14 it sticks. The decision is exact (the rest class,
// docs/simulation.md): the stick / slip event says so, and the slide is down the incline.
TEST(SimulationPlanarContact, BlockOnAnInclineAtExactlyTanAlphaEqualsMuIsDecidedExactly) {
  Lcg rng{41};
  for (int c = 0; c < 9; ++c) {
    const int k = 15 + static_cast<int>(rng.uniform(0, 45));   // mu = k / 100
    const long G = 9000 + static_cast<long>(rng.uniform(0, 1000));
    const int variant = c % 3;   // 0: equal, 1: mu lowered, 2: mu raised
    Scene scene = block_scene(10, 4, 1e-3);
    std::ostringstream gravity, mu;
    // mu G exactly: k G / 100 as a decimal
    gravity << (k * G) / 100 << "." << std::setw(2) << std::setfill('0') << (k * G) % 100 << ", -" << G;
    mu << "0." << std::setw(2) << std::setfill('0') << k << (variant == 0 ? "" : variant == 1 ? "" : "000000000001");
    std::string mu_text = mu.str();
    if (variant == 1) {   // k/100 - 10^-14
      std::ostringstream lowered;
      lowered << "0." << std::setw(2) << std::setfill('0') << k - 1 << "999999999999";
      mu_text = lowered.str();
    }
    scene.gravity_text = gravity.str();
    scene.mu_text = mu_text;
    scene.gx = static_cast<double>(k * G) / 100;
    scene.gy = -static_cast<double>(G);
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    ASSERT_NE(run_to(s, SimulationEvent::Kind::impact, 1), std::string::npos) << c;
    s.run_until(0.05);
    const SimulationEvent* decision = nullptr;
    for (const SimulationEvent& e : s.events())
      if (e.kind == SimulationEvent::Kind::stick || e.kind == SimulationEvent::Kind::slip) {
        decision = &e;
        break;
      }
    ASSERT_NE(decision, nullptr) << c << " mu " << mu_text << " g " << scene.gravity_text;
    EXPECT_TRUE(decision->exact_decision) << c;
    if (variant == 1) {
      // the floating-point decision alone (friction.hpp on the same block, translation only:
      // normal row (0, 1), tangent (-1, 0)) calls this case stick: the exact decision is needed
      std::vector<simulation::Friction> friction(1);
      friction[0].on = true;
      friction[0].T = Eigen::Vector2d(-1, 0);
      friction[0].mu_static = friction[0].mu_kinetic = std::stod(mu_text);
      simulation::FrictionalSolution fp = simulation::solve_frictional(
          Eigen::MatrixXd{{0.0, 1.0}}, Eigen::Vector2d(1 / scene.mass, 1 / scene.mass),
          Eigen::Vector2d(scene.gx, scene.gy), Eigen::VectorXd::Zero(1), friction);
      ASSERT_TRUE(fp.solved) << c;
      EXPECT_EQ(fp.state[0], simulation::stick) << c << " (the floating-point decision)";
      EXPECT_EQ(decision->kind, SimulationEvent::Kind::slip) << c << " mu " << mu_text;
      // down the incline (+x): the sliding direction along the tangent (-normal.y, normal.x)
      EXPECT_EQ(decision->slip_direction * -decision->normal[1], 1.0) << c;
      EXPECT_FALSE(s.state().resting) << c;
      EXPECT_EQ(count(s.events(), SimulationEvent::Kind::stick), 0u) << c;
    } else {
      EXPECT_EQ(decision->kind, SimulationEvent::Kind::stick) << c << " mu " << mu_text;
      EXPECT_TRUE(s.state().resting) << c;
      EXPECT_EQ(count(s.events(), SimulationEvent::Kind::slip), 0u) << c;
    }
  }
}

// The far test's certified sweep bound (planar_bounds.hpp) against Monte Carlo: straight motions
// in (x, y, w) between generated configurations, in both charts; points of a part within its reach
// sampled along the motion never move from their start farther than the bound D. The sampled
// distances are evaluated in double (relative error below 1e-14 of the coordinates' scale,
// hence the 1e-12 margin); sqrt_upper is checked exactly.
TEST(SimulationPlanarContact, SweepBoundOfAStraightMotionContainsEveryPointsPath) {
  Lcg rng{53};
  for (int c = 0; c < 200; ++c) {
    const bool half = c % 2 == 1;
    const double reach = rng.uniform(1, 50);
    const Rational reach_q = simulation::sqrt_upper(Rational(reach * reach));
    ASSERT_GE(reach_q * reach_q, Rational(reach * reach)) << c;
    ASSERT_LE(reach_q.get_d(), reach * (1 + 1e-11)) << c;
    SlicedConfiguration a, b;
    a.x = Rational(rng.uniform(-10, 10));
    a.y = Rational(rng.uniform(-10, 10));
    b.x = a.x + Rational(rng.uniform(-1, 1));
    b.y = a.y + Rational(rng.uniform(-1, 1));
    // the chart coordinate w, then t (t = w without the half turn, -1/w with it)
    double wa = rng.uniform(-1.5, 1.5), wb = wa + rng.uniform(-0.5, 0.5);
    if (half && (wa == 0 || wb == 0)) continue;
    a.angle.t = half ? Rational(-1) / Rational(wa) : Rational(wa);
    b.angle.t = half ? Rational(-1) / Rational(wb) : Rational(wb);
    std::optional<Rational> bound = simulation::motion_sweep_bound(a, b, half, reach_q);
    ASSERT_TRUE(bound.has_value()) << c;
    const double D = bound->get_d();
    const double px = rng.uniform(-1, 1), py = rng.uniform(-1, 1), r = reach * rng.uniform(0.2, 1) / std::hypot(px, py);
    const double bx = px * r, by = py * r;   // a body point at distance <= reach from the pivot
    auto world = [&](double u) {
      const double dx = Rational(b.x - a.x).get_d(), dy = Rational(b.y - a.y).get_d();
      double x = a.x.get_d() + u * dx, y = a.y.get_d() + u * dy;
      double w = wa + u * (wb - wa);
      double theta = (half ? std::numbers::pi : 0.0) + 2 * std::atan(w);
      return std::array<double, 2>{x + std::cos(theta) * bx - std::sin(theta) * by,
                                   y + std::sin(theta) * bx + std::cos(theta) * by};
    };
    const auto p0 = world(0);
    double farthest = 0;
    for (int i = 1; i <= 64; ++i) {
      const auto p = world(i / 64.0);
      farthest = std::max(farthest, std::hypot(p[0] - p0[0], p[1] - p0[1]));
    }
    EXPECT_LE(farthest, D * (1 + 1e-12)) << c;
  }
}

// The frictionless ladder: a thin rhombus (tips at +-l on its axis, the centre of mass midway)
// leaning at phi0 against a wall, its tips 10^-4 mm from the wall and the floor. It lands on
// the floor, meets the wall, and slides with both tips held until the wall's force vanishes.
// With both held, E = (m l^2 + I) phi'^2 / 2 + m g l sin(phi) is conserved and the wall force
// m x'' vanishes where sin(phi) = 2 E / (3 m g l): from rest, 2/3 of the initial height.
TEST(SimulationPlanarContact, FrictionlessLadderLeavesTheWallAtTwoThirdsOfItsHeight) {
  Lcg rng{29};
  for (int c = 0; c < 5; ++c) {
    Scene scene;
    double l = rng.uniform(30, 80), b = 1, g = 9810, gap = 1e-4;
    scene.wall = true;
    scene.body = {{-l, 0}, {0, -b}, {l, 0}, {0, b}};
    scene.inertia = scene.mass * rng.uniform(0.2, 0.4) * l * l;
    double phi0 = rng.uniform(0.7, 1.3);
    scene.angle = std::numbers::pi - phi0;   // the body's +x tip at the wall, -x tip on the floor
    scene.x = l * std::cos(phi0) + gap;
    scene.y = l * std::sin(phi0) + gap;
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    const double m = scene.mass, I = scene.inertia;
    // until both tips are held: the wall's contact event
    std::size_t held_wall = std::string::npos;
    for (std::size_t from = 0; held_wall == std::string::npos && s.state().time < 1;) {
      from = s.events().size();
      s.step(1);
      for (std::size_t i = from; i < s.events().size(); ++i)
        if (s.events()[i].kind == SimulationEvent::Kind::contact && s.events()[i].features[0].find("wall") != std::string::npos)
          held_wall = i;
    }
    ASSERT_NE(held_wall, std::string::npos) << c;
    auto phi_of = [](const PlanarState& st) { return std::numbers::pi - st.angle; };
    auto energy = [&](const PlanarState& st) {
      double rate = st.omega;   // phi' = -theta'
      return 0.5 * (m * l * l + I) * rate * rate + m * g * l * std::sin(phi_of(st));
    };
    double E = energy(s.state());
    double predicted = 2 * E / (3 * m * g * l);
    // the gaps perturb it: E differs from m g l sin(phi0) by less than the fall of both gaps
    EXPECT_NEAR(predicted, 2.0 / 3 * std::sin(phi0), 4 * gap / l) << c;
    // both held: the energy is conserved to the integration's accuracy (1e-9 per step)
    std::size_t lift = std::string::npos;
    double worst = 0;
    while (lift == std::string::npos && s.state().time < 1) {
      std::size_t from = s.events().size();
      s.step(1);
      for (std::size_t i = from; i < s.events().size(); ++i)
        if (s.events()[i].kind == SimulationEvent::Kind::lift_off) lift = i;
        else if (s.events()[i].kind == SimulationEvent::Kind::impact) ADD_FAILURE() << "impact at " << s.events()[i].time;
      if (lift == std::string::npos) worst = std::max(worst, std::abs(energy(s.state()) - E));
    }
    ASSERT_NE(lift, std::string::npos) << c;
    EXPECT_NE(s.events()[lift].features[0].find("wall"), std::string::npos) << c;
    // the integration's accuracy, 1e-9 relative per step (measured: 3e-10 in all)
    const double steps = static_cast<double>(s.steps());
    EXPECT_LE(worst, 1e-9 * steps * E) << c;
    // the wall's force vanished here: sin phi = 2E/(3mgl), to the energy's error (2/3 of the
    // above relative to sin phi0 <= 1) and the force threshold of a lift-off (1e-9 relative:
    // 1e-8); measured 1.6e-9
    EXPECT_NEAR(std::sin(phi_of(s.state())), predicted, 1e-9 * steps + 1e-8) << c;
    double top = s.state().y + l * std::sin(phi_of(s.state()));
    EXPECT_NEAR(top / (2 * l * std::sin(phi0)), 2.0 / 3, (4 * gap / l + 1e-9 * steps + 1e-8) / std::sin(phi0)) << c;
  }
}


// A square peg dropped spinning onto a corner: with e <= 1 (and friction or none) the energy
// (kinetic + gravity's potential) never grows: after every step it is at most the start's, up
// to the integration's error (accuracy 1e-9 relative per step and coordinate, times the energy
// scale m g (|y| + reach) + kinetic) and the held contacts' projection gap (m g 3/4 delta).
TEST(SimulationPlanarContact, RockingPegNeverGainsEnergy) {
  Lcg rng{43};
  std::size_t held_cases = 0, limited = 0;
  for (int c = 0; c < 8; ++c) {
    Scene scene;
    double side = 10, g = 9810;
    scene.body = box(side, side);
    scene.inertia = scene.mass * side * side / 6;
    scene.e = c < 2 ? static_cast<double>(c) : rng.uniform(0, 1);
    if (c % 2 == 1) {
      scene.mu_static = rng.uniform(0.1, 0.8);
      scene.mu_kinetic = scene.mu_static * rng.uniform(0.5, 1);
    }
    scene.angle = rng.uniform(0.2, 0.6);
    scene.y = side * 0.75 + rng.uniform(0.5, 5);
    scene.vx = rng.uniform(-40, 40);
    scene.omega = rng.uniform(-4, 4);
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    const double reach = side / std::sqrt(2.0);
    const double e0 = s.energy();
    double scale = (scene.mass * g * (scene.y + reach) +
                    0.5 * scene.mass * scene.vx * scene.vx + 0.5 * scene.inertia * scene.omega * scene.omega) / 1000;
    double previous = e0;
    while (s.state().time < 0.4 && !s.state().resting) {
      std::size_t before = s.steps();
      s.step(0.4);
      double now = s.energy();
      double tol = 1e-9 * static_cast<double>(s.steps() - before + 1) * scale +
                   scene.mass * g * s.chord_deviation() / 1000;
      EXPECT_LE(now, previous + tol) << c << " t = " << s.state().time << " gain " << now - previous << " tol " << tol;
      EXPECT_LE(now, e0 + 1e-9 * static_cast<double>(s.steps()) * scale + scene.mass * g * s.chord_deviation() / 1000) << c;
      previous = std::min(previous, now);
    }
    held_cases += count(s.events(), SimulationEvent::Kind::contact) > 0;
    limited += s.statistics().restitution_limited;
  }
  EXPECT_GE(held_cases, 4u);   // sustained contact was met in at least half of the cases
  std::cerr << limited << " frictional impacts had their restitution limited\n";
}

// The peg of examples/models/peg-throw.json (vx = -30 mm/s, omega = 3 rad/s into the hole,
// e = 0.5, friction 0.4/0.3), which stopped at 0.2068 s with "sustained contact not supported"
// before sustained contact existed: it runs to rest, and every recorded state's exact
// configuration is not blocked (exact point location in the pair's 3-DOF C-space).
TEST(SimulationPlanarContact, ThrownSpinningPegRunsToRestWithNoBlockedState) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/peg-throw.json");
  PlanarSimulation s = PlanarSimulation::create(model);
  SlicedSpace space = SlicedSpace::build(model, "cup", "peg", SlicedBuildOptions{false, {}});
  std::size_t checked = 0, touching = 0;
  while (s.state().time < 1 && !s.state().resting) {
    s.step(1);
    SlicedLocation where = space.locate(s.state().configuration);
    ASSERT_NE(where.kind, SlicedLocation::Kind::blocked) << "t = " << s.state().time;
    touching += where.kind == SlicedLocation::Kind::contact;
    ++checked;
  }
  EXPECT_TRUE(s.state().resting);
  EXPECT_LT(s.state().time, 0.5);
  EXPECT_GT(checked, 100u);
  EXPECT_GT(count(s.events(), SimulationEvent::Kind::contact), 0u);
  EXPECT_GT(count(s.events(), SimulationEvent::Kind::slip), 0u);
  EXPECT_GT(count(s.events(), SimulationEvent::Kind::stick), 0u);
  // resting on the hole's bottom: the peg's centre 5 mm above it (y = -10), flat
  EXPECT_NEAR(s.state().y, -5, 1e-6);
  EXPECT_NEAR(std::remainder(s.state().angle, std::numbers::pi / 2), 0, 1e-6);
  std::cerr << checked << " states located, " << touching << " touching\n";
}

// The same event sequence (kinds and feature pairs, in order) whatever the largest step, and
// event times within the stated accuracies (the chord's delta over the slowest approach speed of
// the run's impacts, plus 10^-7 s for the integration over the run): the ladder, the sliding
// block and the thrown spinning peg (examples/models/peg-throw.json: 76 events, impacts down
// to 0.013 mm/s) for largest steps 2h, h, h/2.
TEST(SimulationPlanarContact, EventSequenceDoesNotDependOnTheStepSize) {
  std::vector<Scene> scenes;
  {
    Scene ladder;
    double l = 50, b = 1, phi0 = 1.1, gap = 1e-4;
    ladder.wall = true;
    ladder.body = {{-l, 0}, {0, -b}, {l, 0}, {0, b}};
    ladder.inertia = ladder.mass * l * l / 3;
    ladder.angle = std::numbers::pi - phi0;
    ladder.x = l * std::cos(phi0) + gap;
    ladder.y = l * std::sin(phi0) + gap;
    scenes.push_back(ladder);
    Scene block;
    block.body = box(10, 4);
    block.y = 2 + 1e-3;
    block.vx = 120;
    block.mu_static = 0.5;
    block.mu_kinetic = 0.4;
    scenes.push_back(block);
  }
  Model thrown = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/peg-throw.json");
  for (std::size_t c = 0; c <= scenes.size(); ++c) {
    std::vector<std::vector<SimulationEvent>> runs;
    double delta = 0, slowest = std::numeric_limits<double>::infinity();
    for (double max_step : {2e-3, 1e-3, 5e-4}) {
      SimulationOptions options;
      options.max_step = max_step;
      PlanarSimulation s = PlanarSimulation::create(c < scenes.size() ? scenes[c].model() : thrown, options);
      delta = s.chord_deviation();
      s.run_until(c == 0 ? 0.12 : c == 1 ? 0.1 : 0.4);
      runs.push_back(s.events());
      for (const SimulationEvent& e : s.events())
        if (e.kind == SimulationEvent::Kind::impact) slowest = std::min(slowest, std::abs(e.normal_speed_before));
    }
    ASSERT_GE(runs[0].size(), 4u) << c;
    for (std::size_t r = 1; r < runs.size(); ++r) {
      ASSERT_EQ(runs[r].size(), runs[0].size()) << c << " run " << r;
      for (std::size_t i = 0; i < runs[0].size(); ++i) {
        EXPECT_EQ(runs[r][i].kind, runs[0][i].kind) << c << " event " << i;
        EXPECT_EQ(runs[r][i].features, runs[0][i].features) << c << " event " << i;
        EXPECT_NEAR(runs[r][i].time, runs[0][i].time, 2 * delta / slowest + 1e-7) << c << " event " << i;
      }
    }
  }
}


// A frictionless block w x h sliding at v off the end of a table (top y = 0 for x <= 0): its
// leading corner reaches the table's end at t = (-w/2 - x0) / v exactly (it slides at constant
// speed: `edge-end`), the table's corner then holds the block's bottom (a fixed vertex on a
// segment of the part, the other kind of held contact), the trailing corner lifts off when the
// centre of mass passes over the table's corner, t = -x0 / v, and the block tips over the corner
// and leaves it. Energy is conserved after the landing (frictionless; the integration's
// accuracy), and every state is exactly not blocked.
TEST(SimulationPlanarContact, BlockSlidingOffATableEndsItsEdgeAndTipsOverTheCorner) {
  Lcg rng{59};
  for (int c = 0; c < 3; ++c) {
    double w = 10, h = 4, gap = 1e-3;
    Scene scene = block_scene(w, h, gap);
    scene.table = true;
    scene.x = -rng.uniform(20, 40);
    scene.vx = rng.uniform(60, 200);
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    SlicedSpace space = SlicedSpace::build(model, "base", "body", SlicedBuildOptions{false, {}});
    double t_edge = (-w / 2 - scene.x) / scene.vx, t_lift = -scene.x / scene.vx;
    double e_landed = 0;
    double worst = 0;
    std::size_t edge = std::string::npos, lift = std::string::npos, corner = std::string::npos;
    while (s.state().time < t_lift + 0.1) {
      std::size_t from = s.events().size();
      s.step(t_lift + 0.1);
      ASSERT_NE(space.locate(s.state().configuration).kind, SlicedLocation::Kind::blocked) << c << " t = " << s.state().time;
      if (e_landed == 0 && !s.events().empty()) e_landed = s.energy();
      else if (e_landed != 0) worst = std::max(worst, std::abs(s.energy() - e_landed));
      for (std::size_t i = from; i < s.events().size(); ++i) {
        const SimulationEvent& e = s.events()[i];
        if (e.kind == SimulationEvent::Kind::edge_end && edge == std::string::npos) edge = i;
        if (e.kind == SimulationEvent::Kind::lift_off && lift == std::string::npos) lift = i;
        if (e.kind == SimulationEvent::Kind::contact && e.features[0].find("base vertex") == 0 && corner == std::string::npos)
          corner = i;
      }
    }
    ASSERT_NE(edge, std::string::npos) << c;
    ASSERT_NE(corner, std::string::npos) << c;
    ASSERT_NE(lift, std::string::npos) << c;
    EXPECT_LT(edge, corner) << c;
    EXPECT_LT(corner, lift) << c;
    // the foot parameter's bisection (2^-50 of a step) and the integration (1e-9)
    EXPECT_NEAR(s.events()[edge].time, t_edge, 1e-9 * t_edge + 1e-12) << c;
    // the trailing corner's force reaches the lift-off threshold (1e-9 m g per held contact)
    // within 3e-9 w of the corner
    EXPECT_NEAR(s.events()[lift].time, t_lift, 1e-9 * t_lift + 3e-9 * w / scene.vx) << c;
    EXPECT_NE(s.events()[lift].features[0].find("base segment"), std::string::npos) << c;   // the table top's contact
    EXPECT_LE(worst, 1e-9 * static_cast<double>(s.steps()) * e_landed) << c;
  }
}


// SlicedMotion::ignored: the peg of peg-drop.json lowered flat onto the hole's bottom first
// touches it with both bottom corners at once (exact); ignoring one corner's pair leaves the
// other at the same exact parameter; ignoring both leaves no contact on the motion (the chord
// then passes through the bottom: ignoring a pair is the caller's business).
TEST(SimulationPlanarContact, FirstCrossingSkipsTheIgnoredFeaturePairsOnly) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/peg-drop.json");
  SlicedSpace space = SlicedSpace::build(model, "cup", "peg", SlicedBuildOptions{false, {}});
  SlicedMotion down{SlicedConfiguration{0, 10, SlicedAngle{0, false}}, SlicedConfiguration{0, -8, SlicedAngle{0, false}}, false, {}};
  SlicedMotionCrossing both = space.first_crossing(down);
  ASSERT_EQ(both.status, CrossingStatus::crossing);
  ASSERT_EQ(both.features.size(), 2u);
  EXPECT_EQ(both.u_lower, Rational(5, 6));   // the centre at y = -5: 15 of 18 mm down, exactly
  SlicedMotion one = down;
  one.ignored.emplace_back(both.features[0].fixed, both.features[0].free);
  SlicedMotionCrossing other = space.first_crossing(one);
  ASSERT_EQ(other.status, CrossingStatus::crossing);
  ASSERT_EQ(other.features.size(), 1u);
  EXPECT_EQ(other.features[0].label, both.features[1].label);
  EXPECT_EQ(other.u_lower, both.u_lower);
  SlicedMotion none = one;
  none.ignored.emplace_back(both.features[1].fixed, both.features[1].free);
  EXPECT_EQ(space.first_crossing(none).status, CrossingStatus::none);
}

}  // namespace
}  // namespace hipair
