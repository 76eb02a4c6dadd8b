// Speed profiles for drivers of planar parts (docs/model-format.md, law "speed_profile" with
// planar velocities; docs/simulation.md, "Several planar parts"): the driver's pose is the
// integral of its piecewise-linear velocity at every step and every profile point is a step's
// end (generated profiles); a pusher accelerating from rest strikes a block at the closed-form
// time sqrt(2 d / a) and the block leaves at (1 + e) a t*; malformed profiles name their pointer.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

std::string square(const std::string& name, double side, double x, const std::string& dynamics) {
  const std::string h = num(side / 2);
  return R"({ "name": ")" + name + R"(", "motion": { "planar": { "pivot": [0, 0] } }, "initial": { "x": )" + num(x) +
         R"(, "y": 0 }, )" + dynamics + R"("loops": [ { "start": [-)" + h + ", -" + h + R"(], "edges": [ { "line_to": [)" + h +
         ", -" + h + R"(] }, { "line_to": [)" + h + ", " + h + R"(] }, { "line_to": [-)" + h + ", " + h +
         R"(] }, { "line_to": [-)" + h + ", -" + h + R"(] } ] } ] })";
}

Model pusher_model(const std::string& driver, double block_x, double e, const std::string& time_unit = "s") {
  const std::string parts = square("pusher", 10, 0, "") + ", " +
                            square("block", 6, block_x, R"("dynamics": { "mass": 0.02, "moment_of_inertia": 0.12 }, )");
  return read_model(R"({ "hipair": 1, "name": "profile pusher", "units": { "length": "mm", "angle": "rad" },
      "parts": [ )" + parts + R"( ], "pairs": [ { "parts": ["pusher", "block"], "restitution": )" + num(e) + R"( } ],
      "simulation": { "units": { "time": ")" + time_unit + R"(", "force": "N" }, "drivers": [ )" + driver +
                        R"( ], "accuracy": 1e-10 } })",
                    "<profile pusher>");
}

TEST(SimulationPlanarProfile, DriverPoseIsTheIntegralOfItsProfileAndEveryPointIsAStepEnd) {
  Lcg rng{1331};
  for (int c = 0; c < 8; ++c) {
    const int n = 2 + c % 5;
    std::vector<std::array<double, 4>> pts;   // t, vx, vy, omega
    std::string points;
    double t = 0;
    for (int i = 0; i < n; ++i) {
      if (i > 0) t += rng.uniform(0.01, 0.05);
      std::array<double, 4> p{t, rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-3, 3)};
      pts.push_back(p);
      points += std::string(i ? ", " : "") + "[" + num(p[0]) + R"(, { "x": )" + num(p[1]) + R"(, "y": )" + num(p[2]) +
                R"(, "angle": )" + num(p[3]) + " }]";
    }
    // the block far away: only the driver moves (and the pair is watched)
    Model model = pusher_model(R"({ "part": "pusher", "law": "speed_profile", "profile": [ )" + points + " ] }", 5000, 0);
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(model);
    const double t_end = t + 0.03;
    std::vector<double> step_ends;
    // the exact integral of the piecewise-linear velocity (constant after the last point)
    auto integral = [&](double at, int comp, double& speed) {
      double q = 0;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double t0 = pts[i][0];
        if (at <= t0) break;
        const double t1 = i + 1 < pts.size() ? std::min(pts[i + 1][0], at) : at;
        const double slope = i + 1 < pts.size() ? (pts[i + 1][comp] - pts[i][comp]) / (pts[i + 1][0] - t0) : 0;
        q += pts[i][comp] * (t1 - t0) + 0.5 * slope * (t1 - t0) * (t1 - t0);
        speed = pts[i][comp] + slope * (t1 - t0);
      }
      return q;
    };
    while (sim.state().time < t_end) {
      sim.step(t_end);
      const PlanarState& s = sim.state().states[0];
      step_ends.push_back(s.time);
      const double got[3] = {s.x, s.y, s.angle}, got_v[3] = {s.vx, s.vy, s.omega};
      for (int comp = 1; comp <= 3; ++comp) {
        double speed = pts[0][comp];
        const double q = integral(s.time, comp, speed);
        // round-off of the steps' sums: 1e-12 of the largest travel
        const double scale = (comp == 3 ? 3.0 : 100.0) * t_end;
        EXPECT_NEAR(got[comp - 1], q, 1e-12 * scale + 1e-13) << c << " comp " << comp << " t " << s.time;
        EXPECT_NEAR(got_v[comp - 1], speed, 1e-12 * (comp == 3 ? 3.0 : 100.0)) << c << " comp " << comp;
      }
    }
    for (const std::array<double, 4>& p : pts) {
      if (p[0] == 0) continue;
      bool ends = false;
      for (double e : step_ends) ends = ends || std::abs(e - p[0]) <= 1e-12 * p[0];
      EXPECT_TRUE(ends) << c << " profile point " << p[0] << " is not a step's end";
    }
  }
}

TEST(SimulationPlanarProfile, AcceleratingPusherStrikesTheBlockAtTheClosedFormTimeAndSpeed) {
  Lcg rng{1332};
  for (int c = 0; c < 6; ++c) {
    const double a = rng.uniform(200, 5000);   // mm/s^2, from rest
    const double d = rng.uniform(1, 20);       // the gap
    const double e = rng.uniform(0.2, 1);
    const bool ms = c % 2 == 1;                // the same profile written in ms
    const double T = 1.0, unit = ms ? 1000 : 1;
    const std::string driver = R"({ "part": "pusher", "law": "speed_profile", "profile": [ [0, { "x": 0 }], [)" +
                               num(T * unit) + R"(, { "x": )" + num(a * T / unit) + " }] ] }";
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(pusher_model(driver, 5 + 3 + d, e, ms ? "ms" : "s"));
    const double t_star = std::sqrt(2 * d / a), v_star = a * t_star;
    while (sim.events().empty() && sim.state().time < 2 * t_star * unit) sim.step(2 * t_star * unit);
    ASSERT_EQ(sim.events().size(), 1u) << c;
    const SimulationEvent& hit = sim.events()[0];
    // within 2 delta / v* of the closed form (chords within delta of the path)
    EXPECT_NEAR(hit.time / unit, t_star, 2 * sim.chord_deviation() / v_star + 1e-12) << c;
    // the driver has infinite inertia: the block leaves at (1 + e) v(t_hit)
    const double v_hit = a * hit.time / unit;
    EXPECT_NEAR(sim.state().states[1].vx * unit, (1 + e) * v_hit, 1e-9 * v_hit) << c;
    EXPECT_NEAR(sim.state().states[0].vx * unit, v_hit, 1e-12 * v_hit) << c;
  }
}

TEST(SimulationPlanarProfile, BadPlanarProfilesNameTheirPointer) {
  auto expect_error = [](const std::string& driver, const std::string& pointer, const std::string& words) {
    try {
      pusher_model(driver, 20, 0);
      ADD_FAILURE() << "accepted " << driver;
    } catch (const ModelError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(pointer), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  const std::string head = R"({ "part": "pusher", "law": "speed_profile", )";
  expect_error(head + R"("profile": [[0, {"x": 1}], [0, {"x": 2}]] })", "/simulation/drivers/0/profile/1/0",
               "increase strictly");
  expect_error(head + R"("profile": [[0.5, {"x": 1}]] })", "/simulation/drivers/0/profile/0/0", "starts at time 0");
  expect_error(head + R"("profile": [[0, {"x": 1}, 3]] })", "/simulation/drivers/0/profile/0", "expected 2 items");
  expect_error(head + R"("profile": [[0, {"z": 1}]] })", "/simulation/drivers/0/profile/0/1", "z");
  expect_error(head + R"("profile": [[0, 1]] })", "/simulation/drivers/0/profile/0/1", "velocity");
  expect_error(head + R"("profile": [] })", "/simulation/drivers/0/profile", "at least one point");
  expect_error(head + R"("speed": {"x": 1}, "profile": [[0, {"x": 1}]] })", "/simulation/drivers/0/speed",
               "in \"profile\"");
  expect_error(R"({ "part": "pusher", "speed": {"x": 1}, "profile": [[0, {"x": 1}]] })", "/simulation/drivers/0/profile",
               "speed_profile");
  expect_error(R"({ "part": "pusher", "law": "cam" })", "/simulation/drivers/0/law", "unsupported motion law");
}

}  // namespace
}  // namespace hipair
