// Sustained contact and Coulomb friction between moving planar parts (docs/simulation.md,
// "Several planar parts", "Sustained contact between moving parts"), against closed forms on
// generated cases: two blocks stacked on the ground come to rest with contact forces equal to the
// weights above each contact; a block launched on a block that slides on a frictionless floor
// slides with relative deceleration mu_k g (1 + m_top / m_bottom), sticks at the closed-form time,
// both then move with the common velocity momentum gives, and the energy lost is the friction
// work 1/2 m_red v_rel^2; a horizontal force on the top block below the stick limit
// mu_s m_top g (m_top + m_bottom) / m_bottom moves both together at F / (m_top + m_bottom), above
// it the top slides with (F - mu_k m_top g) / m_top and the bottom follows at mu_k g m_top /
// m_bottom; the event sequence does not depend on the step size.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"
#include "test_paths.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

constexpr double g_mm = 9810;   // mm/s^2

std::string block(const std::string& name, double w, double h, double x, double y, double mass, const std::string& extra = "") {
  const std::string a = num(w / 2), b = num(h / 2);
  return R"({ "name": ")" + name + R"(", "motion": { "planar": { "pivot": [0, 0] } },
      "initial": { "x": )" + num(x) + R"(, "y": )" + num(y) + R"( },
      "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(mass * (w * w + h * h) / 12) + extra + R"( },
      "loops": [ { "start": [-)" + a + ", -" + b + R"(], "edges": [ { "line_to": [)" + a + ", -" + b + R"(], "label": ")" + name +
         R"( bottom" }, { "line_to": [)" + a + ", " + b + R"(] }, { "line_to": [-)" + a + ", " + b + R"(], "label": ")" + name +
         R"( top" }, { "line_to": [-)" + a + ", -" + b + R"(] } ] } ] })";
}

// The ground (top face y = 0, x in [-400, 400]), a lower block L (wl x hl, mass ml) dropped
// gap_l above it and an upper block U (wu < wl) dropped gap_u above L; L/U friction mu_s, mu_k;
// the ground frictionless or with mu_ground.
struct Stack {
  double wl = 30, hl = 8, ml = 0.02, wu = 12, hu = 6, mu = 0.01;
  double gap_l = 1e-3, gap_u = 2e-3, xu = 0;
  double vu = 0, fu = 0;   // U's initial velocity (mm/s) and a horizontal force on it (N)
  double mu_s = 0.5, mu_k = 0.4, mu_ground = 0;
  double accuracy = 1e-10;
  Model model() const {
    const std::string ground = R"({ "name": "ground", "motion": "fixed", "loops": [ { "start": [-400, -20], "edges": [
        { "line_to": [400, -20] }, { "line_to": [400, 0] }, { "line_to": [-400, 0], "label": "ground top" },
        { "line_to": [-400, -20] } ] } ] })";
    const double yl = hl / 2 + gap_l, yu = hl + gap_l + gap_u + hu / 2;
    const std::string force = fu != 0 ? R"(, "force": [)" + num(fu) + ", 0]" : "";
    std::string json = R"({ "hipair": 1, "name": "stack", "units": { "length": "mm", "angle": "rad" }, "parts": [ )" + ground +
                       ", " + block("L", wl, hl, 0, yl, ml) + ", " + block("U", wu, hu, xu, yu, mu, force) +
                       R"( ], "pairs": [ { "parts": ["ground", "L"], "restitution": 0)" +
                       (mu_ground > 0 ? R"(, "friction": )" + num(mu_ground) : "") +
                       R"( }, { "parts": ["L", "U"], "restitution": 0, "friction": { "static": )" + num(mu_s) +
                       R"(, "kinetic": )" + num(mu_k) + R"( } } ],
      "simulation": { "units": { "time": "s", "force": "N" }, "gravity": [0, -9810],
        "velocities": { "U": { "x": )" + num(vu) + R"( } }, "accuracy": )" + num(accuracy) + " } }";
    return read_model(json, "<stack>");
  }
};

std::size_t count(const std::vector<SimulationEvent>& events, SimulationEvent::Kind kind) {
  std::size_t n = 0;
  for (const SimulationEvent& e : events) n += e.kind == kind;
  return n;
}

TEST(SimulationPlanarStack, StackedBlocksRestWithContactForcesEqualToTheWeightsAbove) {
  Lcg rng{1301};
  for (int c = 0; c < 6; ++c) {
    Stack s;
    s.wl = rng.uniform(16, 40);
    s.hl = rng.uniform(3, 10);
    s.ml = rng.uniform(0.005, 0.08);
    s.wu = rng.uniform(4, s.wl - 4);
    s.hu = rng.uniform(2, 10);
    s.mu = rng.uniform(0.005, 0.08);
    s.xu = rng.uniform(-1, 1) * (s.wl - s.wu) / 2 * 0.8;
    s.mu_s = rng.uniform(0.2, 0.8);
    s.mu_k = s.mu_s * rng.uniform(0.5, 1);
    s.mu_ground = c % 2 ? rng.uniform(0.2, 0.8) : 0;
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(s.model());
    sim.run_until(0.01);
    const std::vector<SimulationEvent>& ev = sim.events();
    ASSERT_TRUE(sim.state().states[0].resting) << c;
    // the lower block lands first, at sqrt(2 gap / g), the upper one at sqrt(2 (gap_l + gap_u) / g)
    ASSERT_GE(ev.size(), 2u);
    EXPECT_EQ(ev[0].kind, SimulationEvent::Kind::impact);
    EXPECT_EQ(ev[0].second_part, "L");
    const double landing_speed = std::sqrt(2 * g_mm * s.gap_l);
    EXPECT_NEAR(ev[0].time, std::sqrt(2 * s.gap_l / g_mm), 2 * sim.chord_deviation() / landing_speed + 1e-12) << c;
    double normal_ground = -1, normal_top = -1, friction_top = 1;
    std::size_t rests = 0;
    for (const SimulationEvent& e : ev) {
      EXPECT_NE(e.kind, SimulationEvent::Kind::lift_off) << c;
      if (e.kind != SimulationEvent::Kind::contact || e.normal_force == 0) continue;
      ++rests;
      if (e.first_part == "ground") normal_ground = e.normal_force;
      if (e.first_part == "L") {
        normal_top = e.normal_force;
        friction_top = e.friction_force;
      }
    }
    EXPECT_EQ(rests, 2u) << c;
    // N = weights (kg x m/s^2), to the contact LCP's 1e-9 relative
    const double w_upper = s.mu * g_mm / 1000, w_both = (s.ml + s.mu) * g_mm / 1000;
    EXPECT_NEAR(normal_top, w_upper, 1e-9 * w_both) << c;
    EXPECT_NEAR(normal_ground, w_both, 1e-9 * w_both) << c;
    EXPECT_NEAR(friction_top, 0.0, 1e-9 * w_both) << c;
    // at rest on the faces: centres at h/2 (+ the hold gap, 3/4 delta) above their supports
    const PlanarState &l = sim.state().states[0], &u = sim.state().states[1];
    EXPECT_NEAR(l.y, s.hl / 2, sim.chord_deviation()) << c;
    EXPECT_NEAR(u.y, s.hl + s.hu / 2, 2 * sim.chord_deviation()) << c;
    EXPECT_NEAR(u.x, s.xu, 1e-9) << c;
    EXPECT_NEAR(u.angle, 0.0, 1e-12) << c;
  }
}

// Velocities of L and U just after U's landing impact, and that impact's time.
struct Landing {
  double time = 0, vl = 0, vu = 0, energy = 0;
};

Landing run_to_landing(PlanarSystemSimulation& sim) {
  while (sim.state().time < 0.1) {
    std::size_t before = sim.events().size();
    sim.step(0.1);
    for (std::size_t i = before; i < sim.events().size(); ++i) {
      const SimulationEvent& e = sim.events()[i];
      if (e.kind == SimulationEvent::Kind::impact && e.second_part == "U")
        return {e.time, sim.state().states[0].vx, sim.state().states[1].vx, sim.energy()};
    }
  }
  ADD_FAILURE() << "U never landed";
  return {};
}

TEST(SimulationPlanarStack, BlockSlidesOnAMovingBlockAndSticksAtTheClosedFormTimeLosingTheFrictionWork) {
  Lcg rng{1302};
  for (int c = 0; c < 6; ++c) {
    Stack s;
    s.wl = 300;   // long: the upper block stays on it
    s.hl = rng.uniform(3, 10);
    s.ml = rng.uniform(0.005, 0.08);
    s.wu = rng.uniform(4, 20);
    s.hu = rng.uniform(2, 10);
    s.mu = rng.uniform(0.005, 0.08);
    s.xu = -100;
    s.vu = rng.uniform(50, 400) * (c % 2 ? -1 : 1);
    s.xu = s.vu > 0 ? -100 : 100;
    s.mu_s = rng.uniform(0.2, 0.8);
    s.mu_k = s.mu_s * rng.uniform(0.5, 1);
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(s.model());
    const Landing land = run_to_landing(sim);
    const double vrel = land.vu - land.vl;
    ASSERT_GT(std::abs(vrel), 0.5 * std::abs(s.vu)) << c;
    // momentum along x is kept (the floor is frictionless): the common velocity after sticking
    const double common = (s.mu * land.vu + s.ml * land.vl) / (s.mu + s.ml);
    const double a_rel = s.mu_k * g_mm * (1 + s.mu / s.ml);
    const double t_stick = land.time + std::abs(vrel) / a_rel;
    // half way: U decelerates at mu_k g, L accelerates at mu_k g m_U / m_L
    const double t_half = 0.5 * (land.time + t_stick);
    sim.run_until(t_half);
    const double dt = sim.state().time - land.time, sgn_rel = vrel > 0 ? 1.0 : -1.0;
    const double tol_v = 1e-9 * std::abs(s.vu);
    EXPECT_NEAR(sim.state().states[1].vx, land.vu - sgn_rel * s.mu_k * g_mm * dt, tol_v) << c;
    EXPECT_NEAR(sim.state().states[0].vx, land.vl + sgn_rel * s.mu_k * g_mm * s.mu / s.ml * dt, tol_v) << c;
    EXPECT_EQ(count(sim.events(), SimulationEvent::Kind::stick), 0u) << c;
    sim.run_until(t_stick + 0.01);
    // both corners of the upper block's face stick at one instant (one event each)
    std::size_t sticks = 0;
    double stick_time = -1;
    for (const SimulationEvent& e : sim.events())
      if (e.kind == SimulationEvent::Kind::stick) {
        if (e.time != stick_time) ++sticks;
        stick_time = e.time;
        EXPECT_EQ(e.first_part, "L");
        EXPECT_FALSE(e.exact_decision);   // decided in floating point, labelled so
      }
    ASSERT_EQ(sticks, 1u) << c;
    EXPECT_EQ(count(sim.events(), SimulationEvent::Kind::lift_off), 0u) << c;
    // located by bisection to 2^-50 of its step; the slide is a quadratic motion (exact for the
    // integrator up to round-off)
    EXPECT_NEAR(stick_time, t_stick, 1e-9 * t_stick) << c;
    EXPECT_NEAR(sim.state().states[0].vx, common, tol_v) << c;
    EXPECT_NEAR(sim.state().states[1].vx, common, tol_v) << c;
    // energy lost between the landing and the stick = friction work = 1/2 m_red v_rel^2 (N mm)
    const double m_red = s.mu * s.ml / (s.mu + s.ml);
    const double lost = land.energy - sim.energy();
    // (plus the weights times 2 delta: the landing state lies within 2 delta of the hold gap)
    EXPECT_NEAR(lost, 0.5 * m_red * vrel * vrel / 1000,
                1e-8 * 0.5 * s.mu * s.vu * s.vu / 1000 + (s.ml + s.mu) * g_mm * 2 * sim.chord_deviation() / 1000)
        << c;
  }
}

TEST(SimulationPlanarStack, ForceOnTheTopBlockBelowTheStickLimitMovesBothAboveItTheTopSlides) {
  Lcg rng{1303};
  for (int c = 0; c < 8; ++c) {
    Stack s;
    s.wl = 200;
    s.hl = rng.uniform(3, 10);
    s.ml = rng.uniform(0.005, 0.08);
    s.wu = rng.uniform(4, 20);
    s.hu = rng.uniform(2, 10);
    s.mu = rng.uniform(0.005, 0.08);
    s.mu = s.ml * rng.uniform(0.25, 2);
    s.mu_s = rng.uniform(0.2, 0.8);
    // mu_k = mu_s: the upper block lands with the small horizontal speed the force gave it in
    // its fall (gaps 5e-5 mm) and, below the limit, its slide decelerates (F / m_U - mu_k g
    // (1 + m_U / m_L) < 0) and sticks within a few ms; with mu_k < 0.9 mu_s a slide started at
    // the landing would go on for good, as Coulomb's law says
    s.mu_k = s.mu_s;
    s.gap_l = s.gap_u = 5e-5;
    const bool sticks = c % 2 == 0;
    // the friction needed to carry L along: F m_L / (m_L + m_U); its limit mu_s m_U g
    const double limit = s.mu_s * s.mu * g_mm / 1000 * (s.ml + s.mu) / s.ml;   // N
    const double F = limit * (sticks ? 0.9 : 1.1);
    s.fu = F;
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(s.model());
    sim.run_until(0.03);
    const std::size_t events = sim.events().size();
    const double t1 = sim.state().time, vl1 = sim.state().states[0].vx, vu1 = sim.state().states[1].vx;
    sim.run_until(0.05);
    EXPECT_EQ(sim.events().size(), events) << c;   // settled: no change of state in between
    const double dt = sim.state().time - t1;
    const double al = (sim.state().states[0].vx - vl1) / dt, au = (sim.state().states[1].vx - vu1) / dt;
    const double Fm = F * 1000;   // mN = kg mm/s^2
    const double scale = Fm / s.mu;
    if (sticks) {
      EXPECT_NEAR(au, Fm / (s.mu + s.ml), 1e-8 * scale) << c;
      EXPECT_NEAR(al, Fm / (s.mu + s.ml), 1e-8 * scale) << c;
      EXPECT_NEAR(sim.state().states[1].vx, sim.state().states[0].vx, 1e-9 * scale * 0.05) << c;
    } else {
      EXPECT_NEAR(au, Fm / s.mu - s.mu_k * g_mm, 1e-8 * scale) << c;
      EXPECT_NEAR(al, s.mu_k * g_mm * s.mu / s.ml, 1e-8 * scale) << c;
    }
  }
}

TEST(SimulationPlanarStack, EventSequenceDoesNotDependOnTheStepSize) {
  Stack s;
  s.wl = 300;
  s.xu = -100;
  s.vu = 200;
  std::vector<std::vector<SimulationEvent>> runs;
  double delta = 0;
  for (double h : {2e-3, 1e-3, 5e-4}) {
    SimulationOptions o;
    o.max_step = h;
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(s.model(), o);
    sim.run_until(0.1);
    runs.push_back(sim.events());
    delta = sim.chord_deviation();
  }
  const double landing_speed = std::sqrt(2 * g_mm * s.gap_l);   // the slowest approach
  for (std::size_t r = 1; r < runs.size(); ++r) {
    ASSERT_EQ(runs[r].size(), runs[0].size()) << r;
    for (std::size_t i = 0; i < runs[0].size(); ++i) {
      EXPECT_EQ(runs[r][i].kind, runs[0][i].kind) << r << " " << i;
      EXPECT_EQ(runs[r][i].features, runs[0][i].features) << r << " " << i;
      EXPECT_NEAR(runs[r][i].time, runs[0][i].time, 2 * delta / landing_speed + 1e-9) << r << " " << i;
    }
  }
  EXPECT_EQ(count(runs[0], SimulationEvent::Kind::stick), 2u);   // both corners, at one instant
}

// examples/models/pushed-block.json: the pusher (profile 0 -> 50 mm/s in 0.1 s, 50 to 0.3 s, 0 at
// 0.4 s) meets the block 1 mm ahead at sqrt(2 mm / 500 mm/s^2); the block then slides on the
// ground with N = m g and friction mu_k m g in total, and rests 15 mm further (the profile's
// integral) at the hold gap from the pusher's face, sticking when the pusher stops.
TEST(SimulationPlanarStack, PushedBlockExampleFollowsItsProfileWithTheClosedFormForces) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/pushed-block.json");
  PlanarSystemSimulation sim = PlanarSystemSimulation::create(model);
  sim.run_until(0.6);
  const double m = 0.02, mu_k = 0.3, w = m * g_mm / 1000;   // N
  const double t_meet = std::sqrt(2 * 1.0 / 500);
  double normal = 0, friction = 0, slip_time = -1, stick_time = -1, meet = -1;
  for (const SimulationEvent& e : sim.events()) {
    if (e.kind == SimulationEvent::Kind::impact && e.first_part == "pusher" && meet < 0) meet = e.time;
    if (e.kind == SimulationEvent::Kind::slip && e.first_part == "ground") {
      if (slip_time < 0) slip_time = e.time;
      if (e.time == slip_time) {
        normal += e.normal_force;
        friction += e.friction_force;
      }
    }
    if (e.kind == SimulationEvent::Kind::stick && e.first_part == "ground" && e.time > 0.2) stick_time = e.time;
  }
  EXPECT_NEAR(meet, t_meet, 2 * sim.chord_deviation() / (500 * t_meet) + 1e-12);
  EXPECT_EQ(slip_time, meet);
  EXPECT_NEAR(normal, w, 1e-9 * w);
  EXPECT_NEAR(friction, mu_k * w, 1e-9 * w);
  EXPECT_NEAR(stick_time, 0.4, 1e-12);
  const PlanarState &pusher = sim.state().states[0], &block = sim.state().states[1];
  EXPECT_NEAR(pusher.x, -20 + 15, 1e-12 * 15);
  EXPECT_NEAR(block.x - 5 - (pusher.x + 5), 0.0, sim.chord_deviation());   // faces at the hold gap
  EXPECT_GE(block.x - 5 - (pusher.x + 5), 0.0);
  EXPECT_NEAR(block.vx, 0.0, 1e-9);
}

}  // namespace
}  // namespace hipair
