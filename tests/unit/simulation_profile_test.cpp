// Speed-profile drivers (docs/model-format.md#simulation, law "speed_profile"): a driver whose
// speed is piecewise linear in time follows the integral of its profile exactly (steps end at
// the profile's points, and within a step the driver's motion is its segment's quadratic), and
// the profile's errors name their JSON pointers.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// A driven slider (part 0) and a free pendulum-less bar (part 1) far from it, with a torsional
// spring (so that the integration has work to do); the pair never touches.
std::string profile_model(const std::vector<std::pair<double, double>>& profile, const std::string& time_unit = "s") {
  std::string points;
  for (const auto& [t, v] : profile) points += (points.empty() ? "" : ", ") + ("[" + number(t) + ", " + number(v) + "]");
  return R"({"hipair": 1, "name": "profile", "parts": [
    {"name": "slider", "motion": {"translation": {"direction": [1, 0], "limits": [-400, 400]}},
     "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 0]}]}]},
    {"name": "bar", "motion": {"rotation": {"pivot": [0, 500]}},
     "dynamics": {"moment_of_inertia": 10, "torsional_spring": {"stiffness": 0.5}},
     "loops": [{"start": [-5, 499], "edges": [{"line_to": [5, 499]}, {"line_to": [5, 501]}, {"line_to": [-5, 501]},
                {"line_to": [-5, 499]}]}]}],
    "simulation": {"units": {"time": ")" + time_unit + R"("}, "velocities": {"bar": 1},
      "drivers": [{"part": "slider", "law": "speed_profile", "profile": [)" + points + R"(]}]}})";
}

// The integral of a piecewise-linear speed profile (trapezoids), the last speed held.
double integral(const std::vector<std::pair<double, double>>& profile, double t) {
  double q = 0;
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    auto [t0, v0] = profile[i];
    auto [t1, v1] = profile[i + 1];
    if (t <= t0) return q;
    double end = std::min(t, t1), a = (v1 - v0) / (t1 - t0);
    q += v0 * (end - t0) + 0.5 * a * (end - t0) * (end - t0);
    if (t <= t1) return q;
  }
  return q + profile.back().second * (t - profile.back().first);
}

double speed(const std::vector<std::pair<double, double>>& profile, double t) {
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    auto [t0, v0] = profile[i];
    auto [t1, v1] = profile[i + 1];
    if (t < t1) return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
  }
  return profile.back().second;
}

// Generated profiles of 2..6 points (times increasing from 0, speeds in [-100, 100] mm/s): at
// every recorded state (each step) and at sampled times the driver's position equals the
// integral of its profile, its velocity the profile's speed, to round-off (1e-12 of the
// position's scale: both are a few floating-point operations on the same data).
TEST(SimulationSpeedProfile, DriverFollowsTheIntegralOfItsProfile) {
  std::mt19937 random(4242);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<std::pair<double, double>> profile{{0, 200 * unit(random) - 100}};
    int points = 2 + trial % 5;
    for (int i = 1; i < points; ++i) profile.emplace_back(profile.back().first + 0.02 + 0.1 * unit(random), 200 * unit(random) - 100);
    Simulation s = Simulation::create(read_model(profile_model(profile)));
    double end = profile.back().first + 0.1;
    int checked = 0;
    std::vector<double> breakpoints_hit;
    while (s.state().time < end) {
      s.step();
      double t = s.state().time, q = s.state().position[0], v = s.state().velocity[0];
      double scale = 1 + 100 * end;
      ASSERT_NEAR(q, integral(profile, t), 1e-12 * scale) << "trial " << trial << " t " << t;
      ASSERT_NEAR(v, speed(profile, t), 1e-12 * 100) << "trial " << trial << " t " << t;
      ++checked;
      // the reader converts the file's exact decimal times to doubles by truncation
      // (mpq_get_d): within one unit in the last place of the test's doubles
      for (const auto& [tp, vp] : profile)
        if (tp > 0 && std::abs(t - tp) <= 2 * std::numeric_limits<double>::epsilon() * tp) breakpoints_hit.push_back(t);
    }
    // every profile point after 0 is a step's end exactly
    EXPECT_EQ(breakpoints_hit.size(), profile.size() - 1) << trial;
    EXPECT_GT(checked, 0);
  }
}

// The same profile written in ms: identical motion in the file's units.
TEST(SimulationSpeedProfile, ProfileTimesAreInTheFilesTimeUnit) {
  std::vector<std::pair<double, double>> seconds{{0, 0}, {0.1, 50}, {0.2, -30}};
  std::vector<std::pair<double, double>> millis{{0, 0}, {100, 0.05}, {200, -0.03}};
  Simulation a = Simulation::create(read_model(profile_model(seconds)));
  Simulation b = Simulation::create(read_model(profile_model(millis, "ms")));
  a.run_until(0.25);
  b.run_until(250);
  EXPECT_NEAR(a.state().position[0], integral(seconds, 0.25), 1e-12 * 10);
  EXPECT_NEAR(b.state().position[0], a.state().position[0], 1e-12 * 10);
}

void expect_profile_error(const std::string& driver, const std::string& pointer, const std::string& words) {
  std::string text = R"({"hipair": 1, "name": "m", "parts": [
    {"name": "slider", "motion": {"translation": {"direction": [1, 0]}},
     "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 0]}]}]}],
    "simulation": {"drivers": [)" + driver + "]}}";
  try {
    read_model(text);
    FAIL() << "accepted: " << driver;
  } catch (const ModelError& error) {
    std::string message = error.what();
    EXPECT_NE(message.find(pointer), std::string::npos) << message;
    EXPECT_NE(message.find(words), std::string::npos) << message;
  }
}

TEST(SimulationSpeedProfile, BadProfilesNameTheirPointer) {
  expect_profile_error(R"({"part": "slider", "law": "speed_profile", "profile": [[0, 1], [0, 2]]})",
                       "/simulation/drivers/0/profile/1/0", "increase strictly");
  expect_profile_error(R"({"part": "slider", "law": "speed_profile", "profile": [[0.5, 1]]})",
                       "/simulation/drivers/0/profile/0/0", "starts at time 0");
  expect_profile_error(R"({"part": "slider", "law": "speed_profile", "profile": [[0, 1, 2]]})",
                       "/simulation/drivers/0/profile/0", "[time, speed]");
  expect_profile_error(R"({"part": "slider", "law": "speed_profile", "profile": []})",
                       "/simulation/drivers/0/profile", "at least one point");
  expect_profile_error(R"({"part": "slider", "law": "speed_profile", "speed": 1, "profile": [[0, 1]]})",
                       "/simulation/drivers/0/speed", "in \"profile\"");
  expect_profile_error(R"({"part": "slider", "speed": 1, "profile": [[0, 1]]})", "/simulation/drivers/0/profile",
                       "speed_profile");
  expect_profile_error(R"({"part": "slider", "law": "speed_profile"})", "/simulation/drivers/0",
                       "missing required key 'profile'");
}

}  // namespace
}  // namespace hipair
