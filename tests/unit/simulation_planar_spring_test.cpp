// Springs and dampers on a part free in the plane (docs/simulation.md, "Springs on a planar
// part"), against closed forms on generated cases: a mass on a zero-length spring in the plane
// (x(t) = A + (x0 - A) cos wt + v0/w sin wt, period 2 pi sqrt(m/k)) with a torsional spring
// (period 2 pi sqrt(I/k_t)); a damped spring on a line (the underdamped closed form); a block
// pulled into a wall by a spring (first impact at acos((A - x_c)/R)/w, elastic impacts every
// 2 t*, never missed whatever the maximum step, energy kept); a spring attached off the centre
// (energy kept); the model section's validation.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"
#include "test_paths.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

// A square block of side a (pivot at its centre) and a fixed part: a wall x in [wall, wall + 10]
// (|y| <= 100), far away unless placed. A spring from the block's point `attach` (world, zero
// configuration) to the anchor; no gravity unless given. Units N, s, mm, kg.
struct SpringScene {
  double side = 4, mass = 0.01, inertia = 0.05;
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;
  double wall = 5000, e = 1;
  double k = 0.5, rest = 0, damping = 0;
  double attach[2] = {0, 0}, anchor[2] = {0, 0};
  double torsion = 0;   // torsional spring stiffness (N mm / rad), rest 0
  double g = 0;

  std::string json() const {
    std::string h = num(side / 2), w0 = num(wall), w1 = num(wall + 10);
    std::string torsional = torsion > 0 ? R"(, "torsional_spring": { "stiffness": )" + num(torsion) + R"(, "rest": 0 })" : "";
    return R"({ "hipair": 1, "name": "spring", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "wall", "motion": "fixed", "loops": [ { "start": [)" + w0 + R"(, -100], "edges": [
          { "line_to": [)" + w1 + R"(, -100] }, { "line_to": [)" + w1 + R"(, 100] }, { "line_to": [)" + w0 + R"(, 100] },
          { "line_to": [)" + w0 + R"(, -100], "label": "wall face" } ] } ] },
        { "name": "block", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(x) + R"(, "y": )" + num(y) + R"(, "angle": )" + num(angle) + R"( },
          "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(inertia) + torsional + R"( },
          "loops": [ { "start": [-)" + h + ", -" + h + R"(], "edges": [ { "line_to": [)" + h + ", -" + h + R"(] },
            { "line_to": [)" + h + ", " + h + R"(] }, { "line_to": [-)" + h + ", " + h + R"(] }, { "line_to": [-)" + h +
           ", -" + h + R"(] } ] } ] } ],
      "pairs": [ { "parts": ["wall", "block"], "restitution": )" + num(e) + R"( } ],
      "simulation": { "gravity": [0, )" + num(-g) + R"(],
        "velocities": { "block": { "x": )" + num(vx) + R"(, "y": )" + num(vy) + R"(, "angle": )" + num(omega) + R"( } },
        "springs": [ { "parts": ["block", "wall"], "points": [[)" + num(attach[0]) + ", " + num(attach[1]) + "], [" +
           num(anchor[0]) + ", " + num(anchor[1]) + R"(]], "stiffness": )" + num(k) + R"(, "rest_length": )" + num(rest) +
           R"(, "damping": )" + num(damping) + R"( } ],
        "accuracy": 1e-10 } })";
  }
  Model model() const { return read_model(json(), "<spring scene>"); }
};

// The integration's stated accuracy over a run: each accepted step's error is held below
// eps (1 + |y| + h |y'|) per state component (Dormand–Prince with error control, internal units
// mm and mm/s); the oscillator's flow does not amplify errors (it is a rotation in the energy
// norm), so after n steps a position is within n eps (1 + 2 (R + R w)) (1 + 1/w) of the closed
// form, R the amplitude.
double integration_bound(std::size_t steps, double eps, double amplitude, double w) {
  return static_cast<double>(steps + 1) * eps * (1 + 2 * (amplitude + amplitude * w)) * (1 + 1 / w);
}

TEST(SimulationPlanarSpring, MassOnASpringHasPeriodTwoPiSqrtMOverKAndATorsionalSpringTwoPiSqrtIOverK) {
  Lcg rng{23};
  for (int c = 0; c < 6; ++c) {
    SpringScene scene;
    scene.mass = rng.uniform(0.005, 0.05);
    scene.inertia = rng.uniform(0.02, 0.2);
    scene.k = rng.uniform(0.1, 2);
    scene.torsion = rng.uniform(1, 20);
    scene.anchor[0] = rng.uniform(-20, 20);
    scene.anchor[1] = rng.uniform(-20, 20);
    scene.x = rng.uniform(-40, 40);
    scene.y = rng.uniform(-40, 40);
    scene.angle = rng.uniform(-0.5, 0.5);
    scene.vx = rng.uniform(-2000, 2000);
    scene.vy = rng.uniform(-2000, 2000);
    scene.omega = rng.uniform(-20, 20);
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    // internal units: k N/mm = 1000 k kg/s^2, k_t N mm/rad = 1000 k_t kg mm^2/s^2
    const double w = std::sqrt(1000 * scene.k / scene.mass), wt = std::sqrt(1000 * scene.torsion / scene.inertia);
    const double period = 2 * std::numbers::pi * std::sqrt(scene.mass / (1000 * scene.k));
    const double X0 = scene.x - scene.anchor[0], Y0 = scene.y - scene.anchor[1];
    const double R = std::hypot(X0, Y0) + std::hypot(scene.vx, scene.vy) / w;
    const double Rt = std::abs(scene.angle) + std::abs(scene.omega) / wt;
    for (int j = 1; j <= 16; ++j) {
      const double t = j * period / 8;
      s.run_until(t);
      ASSERT_DOUBLE_EQ(s.state().time, t);
      const double ex = scene.anchor[0] + X0 * std::cos(w * t) + scene.vx / w * std::sin(w * t);
      const double ey = scene.anchor[1] + Y0 * std::cos(w * t) + scene.vy / w * std::sin(w * t);
      const double eth = scene.angle * std::cos(wt * t) + scene.omega / wt * std::sin(wt * t);
      const double tol = integration_bound(s.steps(), 1e-10, R, w);
      EXPECT_NEAR(s.state().x, ex, tol) << c << " t = " << t;
      EXPECT_NEAR(s.state().y, ey, tol) << c << " t = " << t;
      EXPECT_NEAR(s.state().angle, eth, integration_bound(s.steps(), 1e-10, Rt, wt)) << c << " t = " << t;
      if (j % 8 == 0) {   // a whole period: back where it started (2 pi sqrt(m/k))
        EXPECT_NEAR(s.state().x, scene.x, tol) << c;
        EXPECT_NEAR(s.state().vx, scene.vx, tol * w) << c;
      }
    }
    EXPECT_TRUE(s.events().empty()) << c;   // the wall is far away
  }
}

TEST(SimulationPlanarSpring, DamperAlongTheLineDecaysAtTheUnderdampedClosedForm) {
  Lcg rng{31};
  for (int c = 0; c < 5; ++c) {
    SpringScene scene;
    scene.mass = rng.uniform(0.005, 0.05);
    scene.k = rng.uniform(0.1, 2);
    const double w = std::sqrt(1000 * scene.k / scene.mass);
    const double zeta = rng.uniform(0.02, 0.5);
    // internal damping 1000 c kg/s = 2 zeta w m
    scene.damping = 2 * zeta * w * scene.mass / 1000;
    scene.anchor[0] = rng.uniform(-20, 20);
    scene.x = scene.anchor[0] + rng.uniform(5, 40) * (c % 2 == 0 ? 1 : -1);
    scene.vx = rng.uniform(-500, 500);
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    // the damping as read (the model holds it as a shortest decimal of the double)
    const double gamma = 1000 * scene.damping / (2 * scene.mass), wd = std::sqrt(w * w - gamma * gamma);
    const double X0 = scene.x - scene.anchor[0], V0 = scene.vx;
    const double R = std::abs(X0) + std::abs(V0) / wd;
    double energy = s.energy();
    for (int j = 1; j <= 24; ++j) {
      const double t = j * (2 * std::numbers::pi / wd) / 8;
      s.run_until(t);
      const double ex = scene.anchor[0] + std::exp(-gamma * t) * (X0 * std::cos(wd * t) + (V0 + gamma * X0) / wd * std::sin(wd * t));
      EXPECT_NEAR(s.state().x, ex, integration_bound(s.steps(), 1e-10, R, wd)) << c << " t = " << t;
      EXPECT_NEAR(s.state().y, 0.0, 1e-9) << c;   // the force stays on the line
      // the damper only takes energy out (to the integration's accuracy on the energy scale)
      const double e_now = s.energy();
      EXPECT_LE(e_now, energy + 1e-9 * (std::abs(energy) + 1e-12)) << c << " t = " << t;
      energy = e_now;
    }
  }
}

TEST(SimulationPlanarSpring, SpringPullsTheBlockIntoAWallAtTheClosedFormTimesWhateverTheStep) {
  Lcg rng{47};
  for (int c = 0; c < 4; ++c) {
    SpringScene scene;
    scene.side = rng.uniform(2, 8);
    scene.mass = rng.uniform(0.005, 0.05);
    scene.inertia = scene.mass * scene.side * scene.side / 6;
    scene.k = rng.uniform(0.1, 2);
    scene.wall = rng.uniform(10, 30);
    scene.anchor[0] = scene.wall + rng.uniform(5, 30);   // behind the wall: the spring pulls the block into it
    scene.x = rng.uniform(-40, 0);
    const double w = std::sqrt(1000 * scene.k / scene.mass);
    const double A = scene.anchor[0], R = A - scene.x, xc = scene.wall - scene.side / 2;
    const double t_star = std::acos((A - xc) / R) / w, v_star = w * std::sqrt(R * R - (A - xc) * (A - xc));
    for (double max_step : {0.0, t_star / 40}) {
      Model model = scene.model();
      SimulationOptions options;
      options.max_step = max_step;
      PlanarSimulation s = PlanarSimulation::create(model, options);
      const double energy = s.energy();
      int impacts = 0;
      while (impacts < 12 && s.state().time < 100 * t_star) {
        std::size_t before = s.events().size();
        s.step(100 * t_star);
        for (std::size_t i = before; i < s.events().size(); ++i) {
          const SimulationEvent& hit = s.events()[i];
          ASSERT_EQ(hit.kind, SimulationEvent::Kind::impact) << c;
          ASSERT_EQ(hit.features.size(), 2u) << c;   // both right corners on the wall face at once
          // elastic impacts every 2 t*: the contact on a chord within delta of the path is found
          // within delta / v* of the true time, the state within the integration's accuracy
          const double expected = (2 * impacts + 1) * t_star;
          const double tol = (impacts + 1) * (s.chord_deviation() + integration_bound(s.steps(), 1e-10, R, w)) / v_star +
                             expected * std::ldexp(1.0, -40);
          EXPECT_NEAR(hit.time, expected, tol) << c << " impact " << impacts << " max step " << max_step;
          EXPECT_NEAR(-hit.normal_speed_before, v_star, w * w * tol * (impacts + 1) + 1e-9 * v_star) << c;
          ++impacts;
        }
      }
      EXPECT_EQ(impacts, 12) << c;
      EXPECT_NEAR(s.energy(), energy,
                  integration_bound(s.steps(), 1e-10, R, w) * 1000 * scene.k * R / 1000 + 1e-9 * energy)
          << c;
    }
  }
}

TEST(SimulationPlanarSpring, SpringOffTheCentreKeepsTheEnergyAndTurnsThePart) {
  Lcg rng{59};
  for (int c = 0; c < 4; ++c) {
    SpringScene scene;
    scene.side = 10;
    scene.mass = 0.01;
    scene.inertia = rng.uniform(0.1, 0.3);
    scene.k = rng.uniform(0.2, 1);
    scene.rest = rng.uniform(5, 20);
    scene.attach[0] = rng.uniform(-5, 5);
    scene.attach[1] = 5;   // the top edge
    scene.anchor[0] = rng.uniform(-10, 10);
    scene.anchor[1] = rng.uniform(30, 60);
    scene.g = 9810;
    scene.x = rng.uniform(-10, 10);
    Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    const double energy = s.energy();
    double turned = 0;
    for (int j = 1; j <= 20; ++j) {
      s.run_until(j * 0.005);
      turned = std::max(turned, std::abs(s.state().angle));
      // energy: kinetic + spring + gravity, conserved to the integration's accuracy (state error
      // bound times the energy's gradient m v + k L + m g + I omega, internal units / 1000)
      const double L = 100, V = 5000;
      const double grad = (scene.mass * V + 1000 * scene.k * L + scene.mass * 9810 + scene.inertia * 100) / 1000;
      EXPECT_NEAR(s.energy(), energy, integration_bound(s.steps(), 1e-10, L, 1) * grad) << c << " j " << j;
    }
    if (scene.attach[0] != 0) EXPECT_GT(turned, 0.0) << c;   // off the centre: the spring turns it
  }
}

// examples/models/spring-block.json: a block hung on a damped spring at its corner swings into
// the post twice in 0.6 s; every state is exactly not blocked, every impact is on the post's
// face, and the energy (damper, restitution 0.7) ends below its start.
TEST(SimulationPlanarSpring, SpringBlockExampleSwingsIntoThePostAndIsNeverBlocked) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/spring-block.json");
  PlanarSimulation s = PlanarSimulation::create(model);
  SlicedSpace space = SlicedSpace::build(model, "frame", "block", SlicedBuildOptions{false, {}});
  const double energy = s.energy();
  while (s.state().time < 0.6) {
    s.step(0.6);
    EXPECT_NE(space.locate(s.state().configuration).kind, SlicedLocation::Kind::blocked) << s.state().time;
  }
  ASSERT_EQ(s.events().size(), 2u);
  for (const SimulationEvent& e : s.events()) {
    EXPECT_EQ(e.kind, SimulationEvent::Kind::impact);
    ASSERT_FALSE(e.features.empty());
    EXPECT_NE(e.features[0].find("post face"), std::string::npos) << e.features[0];
    EXPECT_NEAR(e.normal_speed_after, -0.7 * e.normal_speed_before, 1e-9 * std::abs(e.normal_speed_before));
  }
  EXPECT_LT(s.energy(), energy);
}

TEST(SimulationPlanarSpring, SpringsOfPlanarPartsAreValidatedWithTheirPointers) {
  // a spring on a pin-slot part is refused by the reader at the part's name in "parts"
  const std::string pin_slot = R"({ "hipair": 1, "name": "p", "units": { "length": "mm", "angle": "rad" },
    "parts": [ { "name": "f", "motion": "fixed", "loops": [ { "circle": { "center": [100, 0], "radius": 1 } } ] },
      { "name": "s", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0] } },
        "loops": [ { "circle": { "center": [0, 0], "radius": 1 } } ] } ],
    "simulation": { "springs": [ { "parts": ["f", "s"], "points": [[0, 0], [1, 0]], "stiffness": 1 } ] } })";
  try {
    read_model(pin_slot, "<pin slot>");
    ADD_FAILURE() << "accepted a spring on a pin-slot part";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/simulation/springs/0/parts/1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pin-slot"), std::string::npos) << e.what();
  }
  // a planar part takes springs between points and a torsional spring
  SpringScene scene;
  scene.torsion = 2;
  EXPECT_NO_THROW(PlanarSimulation::create(scene.model()));
  // a planar part's driver is a velocity object (a number: refused at its speed), and among
  // fixed parts only it would jam: PlanarSimulation refuses it at the driver
  std::string driven = scene.json();
  driven.replace(driven.find("\"velocities\""), 0, R"("drivers": [ { "part": "block", "speed": 1 } ], )");
  try {
    read_model(driven, "<driven>");
    ADD_FAILURE() << "accepted a planar driver's number speed";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/simulation/drivers/0/speed"), std::string::npos) << e.what();
  }
  driven = scene.json();
  driven.replace(driven.find("\"velocities\""), 0, R"("drivers": [ { "part": "block", "speed": { "x": 1 } } ], )");
  try {
    read_model(driven, "<driven>");   // the block is also given a velocity: refused there
    ADD_FAILURE() << "accepted a velocity for a driven planar part";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/simulation/velocities/block"), std::string::npos) << e.what();
  }
  std::size_t v = driven.find(", \"velocities\""), v_end = driven.find("} },", v);
  driven.erase(v + 2, v_end + 4 - (v + 2));
  try {
    PlanarSimulation::create(read_model(driven, "<driven>"));
    ADD_FAILURE() << "accepted a driven planar part among fixed parts";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/simulation/drivers/0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hipair
