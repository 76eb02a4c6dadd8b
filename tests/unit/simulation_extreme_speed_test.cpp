// The fixed-axis simulator at extreme driver speeds (session 60, geneva60; docs/simulation.md,
// "Session 60 (geneva60)"). geneva-drive.json's wheel carries no spring, damper or load: its
// motion as a function of the driver angle phi = w t is the same at every driver speed w, so
// the run at 1 rad/s is the oracle of the run at any w, and the closed form
// tan(theta) = lambda sin(psi) / (1 - lambda cos(psi)) (within the slot's play) that of every
// state during the drive. Generated driver speeds over 1e-3 ... 1e300 rad/s (a seeded draw of
// mantissae and exponents): every run completes one driver turn with the events of the 1 rad/s
// run (kinds, feature pairs, driver angles) and finite states, or, beyond the doubles' range of
// the driver's centripetal acceleration, is refused at /simulation/drivers/0/speed before
// anything is built. The cam follower of cam-drive.json: its lift-off at the closed-form angle
// wherever the contact holds there, and every run ends at t_end or at the follower's travel
// limit (its C-space's border), never in a non-finite state.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "test_seed.hpp"

namespace hipair {
namespace {

Model example_at(const std::string& name, const std::string& parameter, double value) {
  ReadOptions options;
  options.parameter_values[parameter] = Rational(value);
  options.allow_out_of_tolerance = true;
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name, options);
}

std::string text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// The generated speeds: fixed ones at the ends and at the rescaling threshold 2^12 rad/s
// (simulation/time_rescale.hpp), and a seeded draw of one speed per `stride` decades of
// [10^low, 10^high) (mantissa log-uniform in [1, 10)).
std::vector<double> generated_speeds(unsigned seed, int low, int high, int stride, std::vector<double> fixed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> mantissa(0, 1);
  for (int decade = low; decade < high; decade += stride) {
    const int exponent = decade + static_cast<int>(random() % static_cast<unsigned>(stride));
    if (exponent >= high) continue;
    fixed.push_back(std::pow(10.0, exponent + mantissa(random)));
  }
  return fixed;
}

bool finite_state(const SimulationState& state) {
  for (double x : state.position)
    if (!std::isfinite(x)) return false;
  for (double x : state.velocity)
    if (!std::isfinite(x)) return false;
  return std::isfinite(state.time);
}

// One driver turn of geneva-drive.json at `speed` rad/s: the events and the largest excess of
// the wheel angle over the closed form's play during the drive (rad).
struct GenevaTurn {
  std::vector<SimulationEvent> events;
  double excess = 0;       // largest |theta - closed form| - play, over the drive's states
  double dwell_speed = 0;  // largest |wheel speed| / speed after the lock
  std::size_t drive_states = 0, steps = 0;
};

GenevaTurn geneva_turn(double speed) {
  Simulation s = Simulation::create(example_at("geneva-drive.json", "driver-speed", speed));
  // the model's geometry (tests/unit/simulation_test.cpp, SimulationGeneva): crank 56.5 mm,
  // centre distance 80 mm, pin centre free by 0.5 mm either side of the slot's axis
  const double centre = 80, crank = 56.5, half_clearance = 0.5, lambda = crank / centre;
  const double turn = 2 * std::numbers::pi / speed;
  GenevaTurn out;
  while (s.state().time < turn) {
    s.step();
    EXPECT_TRUE(finite_state(s.state())) << "at " << text(speed) << " rad/s, t " << s.state().time;
    const double phi = s.state().position[0], theta = s.state().position[1];
    EXPECT_NEAR(phi, speed * s.state().time, 1e-12 * (1 + phi)) << "the driver's law at " << text(speed);
    const double psi = std::remainder(phi - std::numbers::pi, 2 * std::numbers::pi);
    if (std::abs(psi) < std::numbers::pi / 4 - 0.02) {
      const double expected = -std::atan(lambda * std::sin(psi) / (1 - lambda * std::cos(psi)));
      const double rho = std::hypot(centre - crank * std::cos(psi), crank * std::sin(psi));
      const double rel = std::remainder(theta - expected - std::numbers::pi / 4, std::numbers::pi / 2);
      out.excess = std::max(out.excess, std::abs(rel) - std::asin(half_clearance / rho));
      ++out.drive_states;
    }
    if (phi > 0.87 * 2 * std::numbers::pi)
      out.dwell_speed = std::max(out.dwell_speed, std::abs(s.state().velocity[1]) / speed);
  }
  out.events = s.events();
  out.steps = s.steps();
  return out;
}

TEST(SimulationExtremeSpeed, GenevaAtAnyDriverSpeedFollowsTheClosedFormWithTheEventsOf1RadPerSecond) {
  const double accuracy = 1e-9;   // the model's simulation accuracy
  const GenevaTurn reference = geneva_turn(1.0);
  ASSERT_GE(reference.events.size(), 8u);
  ASSERT_GE(reference.drive_states, 10u);
  EXPECT_LE(reference.excess, accuracy);
  const unsigned seed = static_cast<unsigned>(hipair::test::test_seed(61));
  RecordProperty("seed", static_cast<int>(seed % 1000000));
  // the refusal bound: sqrt(1.8e308 / reach), reach 61 mm (the pin's rim) -> 1.7e153 rad/s
  const std::vector<double> speeds =
      generated_speeds(seed, -3, 153, 6, {1e-3, 4095.0, 4096.0, 4097.0, 1e6, 1e10, 1e50, 1e100, 1e153});
  for (double speed : speeds) {
    SCOPED_TRACE("driver speed " + text(speed) + " rad/s (seed " + std::to_string(seed) + ")");
    const GenevaTurn run = geneva_turn(speed);
    EXPECT_GE(run.drive_states, 10u);
    // the closed form within the slot's play, to the accuracy (as at 2 pi rad/s)
    EXPECT_LE(run.excess, accuracy);
    // locked during the dwell: the wheel at rest (relative to the driver's speed)
    EXPECT_LE(run.dwell_speed, accuracy);
    // the 1 rad/s run's events: kinds and feature pairs equal, driver angles w t to the
    // integration's global error (accuracy per step over the run's steps; the two runs'
    // internal speeds differ, so their steps do)
    const double angle_tolerance = accuracy * static_cast<double>(std::max(run.steps, reference.steps));
    ASSERT_EQ(run.events.size(), reference.events.size());
    for (std::size_t i = 0; i < run.events.size(); ++i) {
      EXPECT_EQ(run.events[i].kind, reference.events[i].kind) << i;
      EXPECT_EQ(run.events[i].features, reference.events[i].features) << i;
      EXPECT_NEAR(run.events[i].time * speed, reference.events[i].time, angle_tolerance) << i;
      // impacts: approach speed and impulse scale with the speed (no load on the wheel)
      if (run.events[i].kind == SimulationEvent::Kind::impact) {
        EXPECT_NEAR(run.events[i].normal_speed_before / speed, reference.events[i].normal_speed_before,
                    1e-6 * std::abs(reference.events[i].normal_speed_before) + angle_tolerance)
            << i;
        EXPECT_TRUE(std::isfinite(run.events[i].impulse)) << i;
      }
    }
  }
  // beyond the doubles' range of w^2 r: refused at the driver's speed before anything is built
  for (int exponent = 154; exponent <= 300; exponent += 1) {
    const double speed = (exponent % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent);
    try {
      Simulation::create(example_at("geneva-drive.json", "driver-speed", speed));
      ADD_FAILURE() << "not refused: " << text(speed) << " rad/s";
    } catch (const ModelError& e) {
      EXPECT_EQ(e.pointer(), "/simulation/drivers/0/speed") << e.what();
      EXPECT_NE(std::string(e.what()).find("beyond the doubles' range"), std::string::npos) << e.what();
    }
  }
}

// cam-drive.json: follower (m = 0.05 kg) on an eccentric cam (e = 8 mm) at w rad/s, spring
// 0.5 N/mm with rest -20 mm. Riding the cam, the follower lifts off where
// m e w^2 sin(phi) = k (e sin(phi) + 20) (tests/unit/simulation_test.cpp, SimulationCam), i.e.
// sin(phi_L) = k rest / (e (m w^2 - k)); where the contact only begins after phi_L (the cam
// strikes the follower when it is already decelerating), it lifts off at once. Above the
// critical speed the follower is thrown off; at high speed it flies past its travel limit
// (12 mm), the border of the pair's C-space: that ends the run with a GeometryError naming the
// pair. Every state up to there finite.
TEST(SimulationExtremeSpeed, CamFollowerLiftsOffAtTheClosedFormAtAnySpeed) {
  const double k = 500, m = 0.05, e = 8, rest = 20;   // internal units kg, mm, s
  const unsigned seed = static_cast<unsigned>(hipair::test::test_seed(61));
  RecordProperty("seed", static_cast<int>(seed % 1000000));
  const std::vector<double> speeds = generated_speeds(seed, 3, 153, 15, {191.0, 220.0, 5000.0, 1e8, 1e20, 2e153});
  for (double speed : speeds) {
    SCOPED_TRACE("cam speed " + text(speed) + " rad/s (seed " + std::to_string(seed) + ")");
    Simulation s = Simulation::create(example_at("cam-drive.json", "cam-speed", speed));
    const double turn = 2 * std::numbers::pi / speed;
    double contact_angle = std::numeric_limits<double>::quiet_NaN(), lift_angle = contact_angle;
    bool ended_at_border = false;
    try {
      while (s.state().time < turn) {
        const std::size_t before = s.events().size();
        s.step();
        ASSERT_TRUE(finite_state(s.state())) << "t " << s.state().time;
        for (std::size_t i = before; i < s.events().size(); ++i) {
          const SimulationEvent& event = s.events()[i];
          const double angle = event.time * speed;
          if (event.kind == SimulationEvent::Kind::contact && std::isnan(lift_angle)) contact_angle = angle;
          if (event.kind == SimulationEvent::Kind::lift_off && std::isnan(lift_angle)) lift_angle = angle;
        }
      }
    } catch (const GeometryError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find("pair (cam, follower) leaves its built C-space"), std::string::npos) << what;
      ended_at_border = true;
    }
    ASSERT_FALSE(std::isnan(contact_angle));
    ASSERT_FALSE(std::isnan(lift_angle));
    const double closed = std::asin(k * rest / (e * (m * speed * speed - k)));
    const double expected = std::max(closed, std::remainder(contact_angle, 2 * std::numbers::pi));
    EXPECT_NEAR(std::remainder(lift_angle, 2 * std::numbers::pi), expected, 1e-5)
        << "closed form " << closed << ", contact from " << contact_angle;
    if (speed > 1000) EXPECT_TRUE(ended_at_border);
  }
}

}  // namespace
}  // namespace hipair
