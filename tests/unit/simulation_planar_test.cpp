// Parts free in the plane in the simulator (docs/simulation.md, "Parts free in the plane"),
// against closed forms on generated cases: a square peg dropped flat onto a floor (landing time
// sqrt(2h/g), rebound speed e v and height e^2 h, rest), dropped on a corner (the angular impulse
// of a vertex impact, dw = (r x J) / I), thrown through a slot (never missed: the same first
// contact for a huge and a small maximum step, and the closed-form time), energy of elastic
// bounces, exact point location of every state, and the model section's validation.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

// A square peg of side a (pivot at its centre) above a floor (top face y = 0, wide), or a wall
// with a slot; gravity (0, -g); restitution e.
struct Scene {
  double side = 10, mass = 0.01, inertia = 0.2, g = 9810, e = 0.5;
  double x = 0, y = 20, angle = 0, vx = 0, vy = 0, omega = 0;
  std::string fixed = "floor";   // "floor" or "slot"
  double slot_gap = 0;           // the slot's width (fixed = "slot")
  std::string extra_dynamics, extra_simulation;

  std::string json() const {
    std::string h = num(side / 2);
    std::string fixed_loops;
    if (fixed == "floor") {
      fixed_loops = R"({ "start": [-500, -20], "edges": [ { "line_to": [500, -20] }, { "line_to": [500, 0], "label": "floor right" },
          { "line_to": [-500, 0], "label": "floor top" }, { "line_to": [-500, -20] } ] })";
    } else {
      // a wall at x in [60, 61] with a slot |y| < gap/2, and a back wall at x in [200, 210]
      std::string g2 = num(slot_gap / 2);
      fixed_loops = R"({ "start": [60, )" + g2 + R"(], "edges": [ { "line_to": [61, )" + g2 + R"(] }, { "line_to": [61, 100] },
          { "line_to": [60, 100] }, { "line_to": [60, )" + g2 + R"(] } ] },
        { "start": [60, -100], "edges": [ { "line_to": [61, -100] }, { "line_to": [61, -)" + g2 + R"(] },
          { "line_to": [60, -)" + g2 + R"(] }, { "line_to": [60, -100] } ] },
        { "start": [200, -100], "edges": [ { "line_to": [210, -100] }, { "line_to": [210, 100] },
          { "line_to": [200, 100] }, { "line_to": [200, -100], "label": "back wall" } ] })";
    }
    return R"({ "hipair": 1, "name": "drop", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "base", "motion": "fixed", "loops": [ )" + fixed_loops + R"( ] },
        { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(x) + R"(, "y": )" + num(y) + R"(, "angle": )" + num(angle) + R"( },
          "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(inertia) + extra_dynamics + R"( },
          "loops": [ { "start": [-)" + h + ", -" + h + R"(], "edges": [ { "line_to": [)" + h + ", -" + h + R"(] },
            { "line_to": [)" + h + ", " + h + R"(] }, { "line_to": [-)" + h + ", " + h + R"(] }, { "line_to": [-)" + h +
           ", -" + h + R"(] } ] } ] } ],
      "pairs": [ { "parts": ["base", "peg"], "restitution": )" + num(e) + R"( } ],
      "simulation": { "gravity": [0, )" + num(-g) + R"(], "velocities": { "peg": { "x": )" + num(vx) + R"(, "y": )" +
           num(vy) + R"(, "angle": )" + num(omega) + R"( } })" + extra_simulation + R"( } })";
  }
  Model model() const { return read_model(json(), "<scene>"); }
};

// Steps until the number of impacts grows (or t_end).
const SimulationEvent* next_impact(PlanarSimulation& s, double t_end) {
  std::size_t before = s.events().size();
  while (s.state().time < t_end && s.events().size() == before) s.step(t_end);
  for (std::size_t i = before; i < s.events().size(); ++i)
    if (s.events()[i].kind == SimulationEvent::Kind::impact) return &s.events()[i];
  return nullptr;
}

// The state's configuration is not blocked (exact point location in the pair's 3-DOF C-space).
void expect_not_blocked(const Model& model, const PlanarState& state) {
  SlicedSpace space = SlicedSpace::build(model, "base", "peg", SlicedBuildOptions{false, {}});
  EXPECT_NE(space.locate(state.configuration).kind, SlicedLocation::Kind::blocked) << "t = " << state.time;
}

TEST(SimulationPlanar, FlatDropLandsAtSqrtTwoHOverGAndReboundsToESquaredH) {
  Lcg rng{11};
  for (int c = 0; c < 8; ++c) {
    Scene scene;
    double h = rng.uniform(2, 80);
    scene.side = rng.uniform(3, 12);
    scene.g = rng.uniform(1000, 20000);
    scene.e = rng.uniform(0.2, 0.9);
    scene.y = h + scene.side / 2;
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    const double v = std::sqrt(2 * scene.g * h), t1 = std::sqrt(2 * h / scene.g);
    // accuracy: a contact on a chord within delta of the path is found within delta / v of the
    // true time; the crossing bracket and the double evaluation add t1 2^-40
    const double tol_t = s.chord_deviation() / v + t1 * std::ldexp(1.0, -40);
    const SimulationEvent* hit = next_impact(s, 10);
    ASSERT_NE(hit, nullptr) << c;
    EXPECT_NEAR(hit->time, t1, tol_t) << c;
    ASSERT_EQ(hit->features.size(), 2u) << c;   // both bottom corners at once
    EXPECT_NEAR(hit->normal[1], 1.0, 1e-15);
    EXPECT_NEAR(s.state().vy, scene.e * v, scene.e * scene.g * tol_t + 1e-12 * v) << c;
    EXPECT_NEAR(s.state().vx, 0.0, 1e-9 * v);
    EXPECT_NEAR(s.state().omega, 0.0, 1e-9 * v / scene.side);
    expect_not_blocked(model, s.state());
    // the peak of the rebound: e^2 h above the floor
    double rise = s.state().vy / scene.g;
    s.run_until(hit->time + rise);
    EXPECT_NEAR(s.state().y - scene.side / 2, scene.e * scene.e * h,
                scene.e * scene.e * v * tol_t + s.chord_deviation() + 1e-12 * h)
        << c;
    // the second landing 2 e v / g later. Its error: the first landing's (tol_t); the rebound
    // speed, short by g tol_t (2 e tol_t of flight); the flight starting up to delta above the
    // floor (delta / (e v) more) and the second landing's own chord (delta / (e v)).
    const SimulationEvent* second = next_impact(s, 10);
    ASSERT_NE(second, nullptr);
    EXPECT_NEAR(second->time, t1 + 2 * scene.e * v / scene.g,
                (1 + 2 * scene.e) * tol_t + 2 * s.chord_deviation() / (scene.e * v) + t1 * std::ldexp(1.0, -40))
        << c;
    expect_not_blocked(model, s.state());
  }
}

TEST(SimulationPlanar, BouncesDieOutAndThePegRestsOnTheFloor) {
  Lcg rng{5};
  for (int c = 0; c < 4; ++c) {
    Scene scene;
    double h = rng.uniform(5, 50);
    scene.e = rng.uniform(0.3, 0.7);
    scene.y = h + scene.side / 2;
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    // the bounces form a geometric series: all of them within t1 (1 + e) / (1 - e)
    double t1 = std::sqrt(2 * h / scene.g), total = t1 * (1 + scene.e) / (1 - scene.e);
    s.run_until(total * 1.01 + 0.01);
    ASSERT_TRUE(s.state().resting) << c;
    EXPECT_EQ(s.events().back().kind, SimulationEvent::Kind::contact);
    EXPECT_NEAR(s.events().back().normal_force, scene.mass * scene.g / 1000, 1e-9 * scene.mass * scene.g / 1000);
    EXPECT_NEAR(s.state().y, scene.side / 2, s.chord_deviation());
    EXPECT_LE(s.events().back().time, total * (1 + 1e-6));
    EXPECT_EQ(s.state().vy, 0.0);
    expect_not_blocked(model, s.state());
    for (const SimulationEvent& e : s.events())
      if (e.kind == SimulationEvent::Kind::impact) EXPECT_LE(e.normal_speed_after, -0.0 + std::abs(e.normal_speed_before));
  }
}

TEST(SimulationPlanar, ElasticBouncesConserveEnergy) {
  Scene scene;
  scene.e = 1;
  scene.y = 30 + scene.side / 2;
  PlanarSimulation s = PlanarSimulation::create(scene.model());
  double e0 = s.energy();
  std::size_t impacts = 0;
  while (impacts < 20) {
    ASSERT_NE(next_impact(s, 100), nullptr);
    ++impacts;
    // each flight is in closed form and each impact elastic: the energy moves only by the
    // contact's position within the chord deviation (m g delta) and rounding
    EXPECT_NEAR(s.energy(), e0, impacts * (scene.mass * scene.g * s.chord_deviation() / 1000 + 1e-12 * std::abs(e0)));
  }
}

TEST(SimulationPlanar, CornerImpactGivesTheClosedFormAngularImpulse) {
  Lcg rng{23};
  for (int c = 0; c < 10; ++c) {
    Scene scene;
    scene.angle = rng.uniform(0.05, 1.5);   // no side parallel to the floor
    scene.e = rng.uniform(0, 1);
    scene.inertia = rng.uniform(0.05, 1);
    double h = rng.uniform(3, 40);
    // the lowest corner's height above the centre
    double half = scene.side / 2, lowest = 0, corner_x = 0;
    for (int sx : {-1, 1})
      for (int sy : {-1, 1}) {
        double y = std::sin(scene.angle) * sx * half + std::cos(scene.angle) * sy * half;
        if (y < lowest) {
          lowest = y;
          corner_x = std::cos(scene.angle) * sx * half - std::sin(scene.angle) * sy * half;
        }
      }
    scene.y = h - lowest;
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    const double v = std::sqrt(2 * scene.g * h), t1 = std::sqrt(2 * h / scene.g);
    const double tol_t = s.chord_deviation() / v + t1 * std::ldexp(1.0, -40);
    const SimulationEvent* hit = next_impact(s, 10);
    ASSERT_NE(hit, nullptr);
    EXPECT_NEAR(hit->time, t1, tol_t) << c;
    ASSERT_EQ(hit->features.size(), 1u) << c;
    EXPECT_NE(hit->features[0].find("vertex"), std::string::npos) << hit->features[0];
    EXPECT_NEAR(hit->point[0], corner_x, 1e-9) << c;
    // Newton's law at one vertex: J = (1 + e) m_eff v along n = (0, 1), r = corner - centre,
    // m_eff = 1 / (1/m + (r x n)^2 / I), dw = (r x J) / I, dvy = J / m
    double rxn = corner_x;   // r x n with n = (0, 1)
    double impulse = (1 + scene.e) * v / (1 / scene.mass + rxn * rxn / scene.inertia);
    double vtol = scene.g * tol_t / v + 1e-12;   // relative error of the approach speed
    EXPECT_NEAR(s.state().omega, impulse * rxn / scene.inertia, vtol * std::abs(impulse * rxn / scene.inertia) + 1e-12)
        << c;
    EXPECT_NEAR(s.state().vy, -v + impulse / scene.mass, vtol * v + 1e-12) << c;
    EXPECT_NEAR(hit->impulse, impulse / 1000, vtol * impulse / 1000) << c;   // N s
    EXPECT_NEAR(hit->normal_speed_after, -scene.e * hit->normal_speed_before, 1e-9 * v) << c;
    expect_not_blocked(model, s.state());
  }
}

// A peg thrown at 20 m/s through a slot 0.02 mm wider than it: with a maximum step of 1 s (the
// whole flight in one step) and of 10 us the first contact is the back wall at the closed-form
// time; offset beyond the clearance, it hits the slot's edge at its closed-form time.
TEST(SimulationPlanar, ThrownThroughASlotNeverMissedWhateverTheStep) {
  Lcg rng{3};
  for (int c = 0; c < 6; ++c) {
    Scene scene;
    scene.fixed = "slot";
    scene.side = 4;
    scene.slot_gap = 4.02;
    scene.g = 0;
    scene.e = 0.5;
    scene.x = rng.uniform(0, 40);
    scene.vx = rng.uniform(5000, 40000);
    bool through = c % 2 == 0;
    scene.y = through ? rng.uniform(-0.009, 0.009) : rng.uniform(0.011, 0.5) * (c % 4 == 1 ? 1 : -1);
    double expected = through ? (200 - 2 - scene.x) / scene.vx : (60 - 2 - scene.x) / scene.vx;
    std::string wall = through ? "back wall" : "";
    double first_time[2];
    for (int run = 0; run < 2; ++run) {
      SimulationOptions options;
      options.max_step = run == 0 ? 1.0 : 1e-5;
      PlanarSimulation s = PlanarSimulation::create(scene.model(), options);
      const SimulationEvent* hit = next_impact(s, 1);
      ASSERT_NE(hit, nullptr) << c << " run " << run;
      first_time[run] = hit->time;
      double tol_t = s.chord_deviation() / scene.vx + expected * std::ldexp(1.0, -40);
      EXPECT_NEAR(hit->time, expected, tol_t) << c << " run " << run;
      if (through) {
        // flat on the back wall: both right corners, and the rebound -e vx without a turn
        ASSERT_EQ(hit->features.size(), 2u);
        for (const std::string& f : hit->features) EXPECT_NE(f.find("back wall"), std::string::npos) << f;
        EXPECT_NEAR(s.state().vx, -scene.e * scene.vx, 1e-12 * scene.vx);
        EXPECT_NEAR(s.state().omega, 0.0, 1e-12 * scene.vx);
      }
    }
    EXPECT_NEAR(first_time[0], first_time[1], 2 * 1e-9 * 4 / scene.vx + expected * std::ldexp(1.0, -39)) << c;
  }
}

// A spinning peg thrown past a thin bar: the same first contact (time and features) for steps
// that cover the whole flight and for small ones.
TEST(SimulationPlanar, SpinningPegFirstContactIsStepIndependent) {
  Lcg rng{41};
  for (int c = 0; c < 5; ++c) {
    Scene scene;
    scene.fixed = "slot";
    scene.side = 4;
    scene.slot_gap = rng.uniform(4.5, 6);
    scene.g = rng.uniform(0, 9810);
    scene.x = 0;
    scene.y = rng.uniform(-1, 1);
    scene.vx = rng.uniform(2000, 8000);
    scene.omega = rng.uniform(-200, 200);
    std::vector<double> times, approach;
    std::vector<std::vector<std::string>> features;
    double delta = 0;
    for (double max_step : {10.0, 1e-4, 3e-5}) {
      SimulationOptions options;
      options.max_step = max_step;
      PlanarSimulation s = PlanarSimulation::create(scene.model(), options);
      delta = s.chord_deviation();
      const SimulationEvent* hit = next_impact(s, 1);
      ASSERT_NE(hit, nullptr);
      times.push_back(hit->time);
      approach.push_back(std::abs(hit->normal_speed_before));
      features.push_back(hit->features);
    }
    // each run's contact lies on a chord within delta of the path: within delta / (approach
    // speed along the normal) of the path's contact time, plus the crossing brackets
    for (std::size_t i = 1; i < times.size(); ++i) {
      EXPECT_EQ(features[i], features[0]) << c;
      double v = std::min(approach[i], approach[0]);
      ASSERT_GT(v, 0.0);
      EXPECT_NEAR(times[i], times[0], 2 * delta / v + times[0] * std::ldexp(1.0, -39)) << c;
    }
  }
}

TEST(SimulationPlanar, BadDynamicsAreRefusedWithTheirPointers) {
  auto refused = [](const std::string& json, const std::string& pointer) {
    try {
      Model model = read_model(json, "<scene>");
      PlanarSimulation::create(model);
      ADD_FAILURE() << "accepted: " << pointer;
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  };
  Scene scene;
  std::string good = scene.json();
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  refused(replace("\"mass\": 0.01", "\"mass\": 0"), "/parts/1");
  refused(replace("\"moment_of_inertia\": 0.20000000000000001", "\"torque\": 1"), "/parts/1");
  refused(replace("\"angle\": 0 } }", "\"angle\": 0, \"z\": 1 } }"), "/simulation/velocities/peg");
  // (friction on the pair, refused here before sustained contact existed, is supported since
  // session 10: tests/unit/simulation_planar_contact_test.cpp; a torsional spring, refused here
  // until session 12, is supported since: tests/unit/simulation_planar_spring_test.cpp. A
  // negative one is still refused, at its stiffness)
  refused(replace("\"moment_of_inertia\": 0.20000000000000001",
                  "\"moment_of_inertia\": 0.2, \"torsional_spring\": { \"stiffness\": -1, \"rest\": 0 }"),
          "/parts/1/dynamics/torsional_spring/stiffness");
  refused(replace("\"velocities\"", "\"centers_of_mass\": { \"peg\": [1, 0] }, \"velocities\""),
          "/simulation/centers_of_mass/peg");
  refused(replace("\"y\": 20", "\"y\": 4"), "/parts/1/initial");   // starts overlapping the floor
  scene.extra_dynamics = ", \"linear_spring\": { \"stiffness\": 1, \"rest\": 0 }";
  refused(scene.json(), "/parts/1/dynamics/linear_spring");
}

}  // namespace
}  // namespace hipair
