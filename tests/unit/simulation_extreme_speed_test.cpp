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

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "simulation/whole_turns.hpp"
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

// geneva-drive.json's geometry (tests/unit/simulation_test.cpp, SimulationGeneva): crank 56.5 mm,
// centre distance 80 mm, pin centre free by 0.5 mm either side of the slot's axis
constexpr double geneva_centre = 80, geneva_crank = 56.5, geneva_half_clearance = 0.5,
                 geneva_lambda = geneva_crank / geneva_centre;

// In the drive (the pin in a slot, away from its ends: driver angle within pi / 4 - 0.02 of the
// centres' line), the wheel angle theta's excess over the closed form
// tan theta = -lambda sin psi / (1 - lambda cos psi) beyond the slot's play (rad); nullopt outside
// the drive.
std::optional<double> geneva_drive_excess(double phi, double theta) {
  const double psi = std::remainder(phi - std::numbers::pi, 2 * std::numbers::pi);
  if (!(std::abs(psi) < std::numbers::pi / 4 - 0.02)) return std::nullopt;
  const double lambda = geneva_lambda, crank = geneva_crank;
  const double expected = -std::atan(lambda * std::sin(psi) / (1 - lambda * std::cos(psi)));
  const double rho = std::hypot(geneva_centre - crank * std::cos(psi), crank * std::sin(psi));
  const double rel = std::remainder(theta - expected - std::numbers::pi / 4, std::numbers::pi / 2);
  return std::abs(rel) - std::asin(geneva_half_clearance / rho);
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
  const double turn = 2 * std::numbers::pi / speed;
  GenevaTurn out;
  while (s.state().time < turn) {
    s.step();
    EXPECT_TRUE(finite_state(s.state())) << "at " << text(speed) << " rad/s, t " << s.state().time;
    const double phi = s.state().position[0], theta = s.state().position[1];
    EXPECT_NEAR(phi, speed * s.state().time, 1e-12 * (1 + phi)) << "the driver's law at " << text(speed);
    if (const std::optional<double> excess = geneva_drive_excess(phi, theta)) {
      out.excess = std::max(out.excess, *excess);
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

// ------------------------------------------------------------------ long runs (session 61)
// A run of any length behaves as its first turns (session 61, geneva61; docs/simulation.md,
// "Session 61 (geneva61)"). geneva-drive.json at 10^6 rad/s jammed after 3012 driver turns
// ("a jammed contact change", t = 0.0189289 s): the driver's and the wheel's angles grew without
// bound and lost their bits within the turn. The simulator now takes whole turns out of them
// exactly (simulation/whole_turns.hpp). Two ways to reach many turns: start the mechanism at
// K whole turns (driver at 2 pi K, wheel at -pi K / 2: the state after K turns of the dwell; cheap),
// and run many turns from the start (every turn's events those of the first full turn, the
// closed form in every drive).

// pi to 40 digits, exact: 2 pi K within 10^-34 K (the simulator rounds it once to a double)
Rational pi_40() { return Rational("31415926535897932384626433832795028841971/10000000000000000000000000000000000000000"); }

Model geneva_after(double speed, long turns) {
  Model model = example_at("geneva-drive.json", "driver-speed", speed);
  for (Part& part : model.parts) {
    if (part.name == "driver") part.initial.angle = 2 * pi_40() * turns;
    if (part.name == "wheel") part.initial.angle = -pi_40() * turns / 2;
  }
  return model;
}

struct GenevaRun {
  std::vector<SimulationEvent> events;
  double excess = 0, dwell_speed = 0, law_error = 0;
  // the closed form's check reads the published angles (each rounded once, near 2 pi K and
  // -pi K / 2) and reduces them with the double 2 pi: an error of a few units in their last
  // place, times 1 + the closed form's largest slope lambda / (1 - lambda) for the driver's
  double reading = 0;
  std::size_t drive_states = 0, steps = 0;
};

// `count` driver turns of geneva-drive.json at `speed` rad/s from K = `turns` whole turns: the
// closed form's excess over the slot's play in every drive, the wheel's speed in every dwell, the
// driver's law (phi = phi0 + w t, in units of phi's own rounding)
GenevaRun geneva_run(double speed, long turns, double count) {
  Simulation s = Simulation::create(geneva_after(speed, turns));
  const double lambda = geneva_lambda;
  const double end = count * 2 * std::numbers::pi / speed;
  const double phi0 = s.state().position[0];
  GenevaRun out;
  out.reading = 4 * (1 + lambda / (1 - lambda)) * std::numeric_limits<double>::epsilon() *
                (std::abs(phi0) + std::abs(s.state().position[1]));
  while (s.state().time < end) {
    s.step();
    EXPECT_TRUE(finite_state(s.state()));
    const double phi = s.state().position[0], theta = s.state().position[1];
    // (the published angles are rounded once: half a unit in the last place of each)
    out.law_error = std::max(out.law_error, std::abs(phi - (phi0 + speed * s.state().time)) /
                                                (std::numeric_limits<double>::epsilon() * (1 + std::abs(phi))));
    if (const std::optional<double> excess = geneva_drive_excess(phi, theta)) {
      out.excess = std::max(out.excess, *excess);
      ++out.drive_states;
    }
    // the dwell, away from the lock's ends (psi within 0.13 turn of the drive's centre's opposite)
    if (std::abs(std::remainder(phi, 2 * std::numbers::pi)) < 0.8)
      out.dwell_speed = std::max(out.dwell_speed, std::abs(s.state().velocity[1]) / speed);
  }
  // (the last step goes past `end` by its own length: the events up to `end`)
  for (const SimulationEvent& e : s.events())
    if (e.time < end) out.events.push_back(e);
  out.steps = s.steps();
  return out;
}

// the events as lines "kind features driver-angle" (a failure's listing)
std::string listing(const std::vector<SimulationEvent>& events, double speed) {
  std::ostringstream out;
  out.precision(10);
  for (const SimulationEvent& e : events) {
    out << "\n  " << static_cast<int>(e.kind);
    for (const std::string& f : e.features) out << " [" << f << "]";
    out << " at " << e.time * speed;
  }
  return out.str();
}

// The events of driver turn j (driver angle w t - 2 pi j in [0, 2 pi)), with that angle in `angles`
std::vector<const SimulationEvent*> turn_events(const GenevaRun& run, double speed, long j, std::vector<double>& angles) {
  std::vector<const SimulationEvent*> out;
  angles.clear();
  for (const SimulationEvent& e : run.events) {
    const double a = e.time * speed - 2 * std::numbers::pi * static_cast<double>(j);
    if (a >= 0 && a < 2 * std::numbers::pi) {
      out.push_back(&e);
      angles.push_back(a);
    }
  }
  return out;
}

// The wheel's features of a label, renumbered by `shift` slots: the wheel turns a quarter per
// driver turn, so the driver meets slot n + 1 one turn after slot n
std::string wheel_shifted(const std::string& label, long shift) {
  std::string out = label;
  const std::size_t at = out.find("/ wheel");
  if (at == std::string::npos) return out;
  for (std::size_t i = at; i < out.size(); ++i)
    if (out[i] >= '1' && out[i] <= '4') out[i] = static_cast<char>('1' + (((out[i] - '1' + shift) % 4) + 4) % 4);
  return out;
}

// every full turn's events (kinds, feature pairs with the wheel's slots renumbered, driver angles
// within the turn) those of turn 1, the first full one (turn 0 starts with the wheel at rest in
// the middle of the lock's play, turn 1 where the lock left it)
void expect_turns_repeat(const GenevaRun& run, double speed, long full_turns, double angle_tolerance) {
  std::vector<double> first_angles, angles;
  const std::vector<const SimulationEvent*> first = turn_events(run, speed, 1, first_angles);
  ASSERT_GE(first.size(), 8u);
  for (long j = 2; j < full_turns; ++j) {
    SCOPED_TRACE("driver turn " + std::to_string(j));
    const std::vector<const SimulationEvent*> events = turn_events(run, speed, j, angles);
    ASSERT_EQ(events.size(), first.size());
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(events[i]->kind, first[i]->kind) << i;
      ASSERT_EQ(events[i]->features.size(), first[i]->features.size()) << i;
      for (std::size_t f = 0; f < first[i]->features.size(); ++f)
        EXPECT_EQ(wheel_shifted(events[i]->features[f], 1 - j), first[i]->features[f]) << i;
      EXPECT_NEAR(angles[i], first_angles[i], angle_tolerance) << i;
    }
  }
}

// From K whole turns the Geneva makes the events of the run from K = 0 over 4.5 turns and follows
// the closed form, at 2 pi rad/s and 10^6 rad/s (the time unit 2^-19 s): K = 3 10^5 and 10^6, and
// at 10^6 rad/s a seeded K up to 10^6; HIPAIR_LONG_RUNS=1 adds 10^3, 3 10^4 and 10^5 over 8.5 turns.
// Before session 61 (base61, 10^6 rad/s) the start at K = 3 10^5 added an impact at slot 2's corner
// in turn 1, K = 10^6 one at slot 4's in turn 3, K = 10^5 one in turn 7.
TEST(SimulationLongRun, GenevaFromManyWholeTurnsMakesTheEventsOfTheFirstTurns) {
  const double accuracy = 1e-9;
  const unsigned seed = static_cast<unsigned>(hipair::test::test_seed(61));
  RecordProperty("seed", static_cast<int>(seed % 1000000));
  std::mt19937 random(seed);
  const long drawn = 1 + static_cast<long>(random() % 1000000);
  const char* long_runs = std::getenv("HIPAIR_LONG_RUNS");
  const bool long_run = long_runs && *long_runs && *long_runs != '0';
  const double count = long_run ? 8.5 : 4.5;
  for (double speed : {2 * std::numbers::pi, 1e6}) {
    const GenevaRun reference = geneva_run(speed, 0, count);
    std::vector<long> starts = {300000, 1000000};
    if (speed > 1e3) starts.push_back(drawn);
    if (long_run) starts.insert(starts.end(), {1000, 30000, 100000});
    for (long turns : starts) {
      SCOPED_TRACE("driver speed " + text(speed) + " rad/s from " + std::to_string(turns) + " whole turns (seed " +
                   std::to_string(seed) + ")");
      const GenevaRun run = geneva_run(speed, turns, count);
      EXPECT_GE(run.drive_states, 10u);
      EXPECT_LE(run.excess, accuracy + run.reading);
      EXPECT_LE(run.dwell_speed, accuracy);
      EXPECT_LE(run.law_error, 2.0);
      const double angle_tolerance = accuracy * static_cast<double>(std::max(run.steps, reference.steps));
      ASSERT_EQ(run.events.size(), reference.events.size())
          << "run:" << listing(run.events, speed) << "\nreference:" << listing(reference.events, speed);
      for (std::size_t i = 0; i < run.events.size(); ++i) {
        EXPECT_EQ(run.events[i].kind, reference.events[i].kind) << i;
        EXPECT_EQ(run.events[i].features, reference.events[i].features) << i;
        EXPECT_NEAR(run.events[i].time * speed, reference.events[i].time * speed, angle_tolerance) << i;
      }
    }
  }
}

// Many turns from the start: every full turn repeats the first one's events, the closed form holds
// in every drive and the wheel rests in every dwell. CI runs 40 turns at 10^6 rad/s (five times
// past the bound at which whole turns are taken out, and the time restarted); HIPAIR_LONG_RUNS=1
// adds 3500 turns at 10^6 rad/s (past the 3012 turns at which the run jammed before session 61) and
// 10^3 turns at a seeded speed in 10^4 ... 10^12 rad/s (minutes each).
TEST(SimulationLongRun, GenevaRunForManyTurnsRepeatsItsFirstTurn) {
  const double accuracy = 1e-9;
  const unsigned seed = static_cast<unsigned>(hipair::test::test_seed(61));
  RecordProperty("seed", static_cast<int>(seed % 1000000));
  std::vector<std::pair<double, long>> cases = {{1e6, 40}};
  if (const char* long_runs = std::getenv("HIPAIR_LONG_RUNS"); long_runs && *long_runs && *long_runs != '0') {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> exponent(4, 12);
    cases.push_back({1e6, 3500});
    cases.push_back({std::pow(10.0, exponent(random)), 1000});
  }
  for (const auto& [speed, turns] : cases) {
    SCOPED_TRACE("driver speed " + text(speed) + " rad/s over " + std::to_string(turns) + " turns (seed " +
                 std::to_string(seed) + ")");
    const GenevaRun run = geneva_run(speed, 0, static_cast<double>(turns) + 0.5);
    EXPECT_GE(run.drive_states, 10u * static_cast<std::size_t>(turns));
    EXPECT_LE(run.excess, accuracy);
    EXPECT_LE(run.dwell_speed, accuracy);
    EXPECT_LE(run.law_error, 2.0);
    expect_turns_repeat(run, speed, turns, accuracy * static_cast<double>(run.steps));
  }
}

// cam-drive.json (a rotating cam and a translating follower): from K whole turns of the cam the
// follower makes the events of the run from K = 0 over two turns, at 150 rad/s (riding) and
// 220 rad/s (thrown off and struck again).
TEST(SimulationLongRun, CamFollowerFromManyWholeTurnsMakesTheEventsOfTheFirstTurns) {
  const double accuracy = 1e-9;
  for (double speed : {150.0, 220.0}) {
    auto run = [&](long turns) {
      Model model = example_at("cam-drive.json", "cam-speed", speed);
      for (Part& part : model.parts)
        if (part.name == "cam") part.initial.angle = 2 * pi_40() * turns;
      Simulation s = Simulation::create(model);
      s.run_until(2 * 2 * std::numbers::pi / speed);
      EXPECT_TRUE(finite_state(s.state()));
      return std::pair{s.events(), s.steps()};
    };
    const auto [reference, reference_steps] = run(0);
    for (long turns : {1000L, 100000L}) {
      SCOPED_TRACE("cam speed " + text(speed) + " rad/s from " + std::to_string(turns) + " whole turns");
      const auto [events, steps] = run(turns);
      const double angle_tolerance = accuracy * static_cast<double>(std::max(steps, reference_steps));
      ASSERT_EQ(events.size(), reference.size());
      for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(events[i].kind, reference[i].kind) << i;
        EXPECT_EQ(events[i].features, reference[i].features) << i;
        EXPECT_NEAR(events[i].time * speed, reference[i].time * speed, angle_tolerance) << i;
      }
    }
  }
}

// A gear pair (spur-gears.json with 6 and 8 teeth, backlash 0.1 mm; the pinion driven by its
// torque from rest, the gear damped): from K1 whole turns of the pinion and K2 of the gear (the
// same point of the pair's torus) the run makes the events of the run from (0, 0), and its
// published angles are those of that run plus the whole turns. The two runs' configurations
// differ only by the rounding of the start (2 pi K to a double: up to 6e-11 rad at K = 10^5), so
// the tolerance is that of the Geneva runs (accuracy per step). The C-space build makes this a few
// seconds per run (40 s for the test): it runs with HIPAIR_LONG_RUNS=1 only, at K = 10^3, 10^4, 10^5.
TEST(SimulationLongRun, GearPairFromManyWholeTurnsMakesTheEventsOfTheFirstTurns) {
  const char* long_runs = std::getenv("HIPAIR_LONG_RUNS");
  if (!long_runs || !*long_runs || *long_runs == '0') GTEST_SKIP() << "HIPAIR_LONG_RUNS=1 runs it (about a minute)";
  const double accuracy = 1e-9;
  auto run = [&](long pinion_turns, long gear_turns) {
    ReadOptions read;
    read.parameter_values["teeth-1"] = Rational(6);
    read.parameter_values["teeth-2"] = Rational(8);
    read.parameter_values["backlash"] = Rational(1, 10);
    read.parameter_values["center-distance"] = Rational(14);
    read.allow_out_of_tolerance = true;
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
    model.parts[0].initial.angle = 2 * pi_40() * pinion_turns;
    model.parts[1].initial.angle = 2 * pi_40() * gear_turns;
    SimulationOptions options;
    options.accuracy = accuracy;
    Simulation s = Simulation::create(model, options);
    s.run_until(0.1);
    EXPECT_TRUE(finite_state(s.state()));
    return s;
  };
  const Simulation reference = run(0, 0);
  ASSERT_GE(reference.events().size(), 3u);
  const std::vector<std::pair<long, long>> starts = {{10000, -7500}, {1000, 1000}, {100000, -75000}};
  for (const auto& [k1, k2] : starts) {
    SCOPED_TRACE("gear pair from " + std::to_string(k1) + " and " + std::to_string(k2) + " whole turns");
    const Simulation s = run(k1, k2);
    const double tolerance = accuracy * static_cast<double>(std::max(s.steps(), reference.steps()));
    ASSERT_EQ(s.events().size(), reference.events().size())
        << "run:" << listing(s.events(), 1) << "\nreference:" << listing(reference.events(), 1);
    for (std::size_t i = 0; i < s.events().size(); ++i) {
      EXPECT_EQ(s.events()[i].kind, reference.events()[i].kind) << i;
      EXPECT_EQ(s.events()[i].features, reference.events()[i].features) << i;
      EXPECT_NEAR(s.events()[i].time, reference.events()[i].time, tolerance) << i;
    }
    const double turns[2] = {static_cast<double>(k1), static_cast<double>(k2)};
    for (int p = 0; p < 2; ++p) {
      const double whole = 2 * std::numbers::pi * turns[p];
      EXPECT_NEAR(s.state().position[p] - whole, reference.state().position[p],
                  tolerance + 4 * std::numeric_limits<double>::epsilon() * std::abs(whole))
          << p;
      EXPECT_NEAR(s.state().velocity[p], reference.state().velocity[p], tolerance * (1 + std::abs(reference.state().velocity[p])))
          << p;
    }
  }
}


// ------------------------------------------------------------------ whole turns, exactly
// simulation/whole_turns.hpp against an oracle of its own: pi to 50 digits as a rational (an error
// of n 10^-50 in x - 2 pi n, far below half a unit in the last place of a residue of order 1 for
// n < 10^25) and exact rational arithmetic, each result rounded to the nearest double here.

// the double nearest to x, a tie to the even one (mpq_get_d truncates toward zero; a small x whose
// residue is x itself, 54 significant bits, is a tie)
double nearest(const Rational& x) {
  const double d = x.get_d();
  const double other = std::nextafter(d, sgn(x) >= 0 ? std::numeric_limits<double>::infinity()
                                                     : -std::numeric_limits<double>::infinity());
  const int c = cmp(abs(Rational(other) - x), abs(Rational(d) - x));
  if (c != 0) return c < 0 ? other : d;
  return (std::bit_cast<std::uint64_t>(d) & 1) == 0 ? d : other;
}

TEST(SimulationWholeTurns, ReduceMinusAndAddTurnsRoundOnceLikeTheRationalOracle) {
  const Rational pi("31415926535897932384626433832795028841971693993751/"
                    "10000000000000000000000000000000000000000000000000");
  const std::uint64_t seed = hipair::test::test_seed(61);
  RecordProperty("seed", static_cast<int>(seed % 1000000));
  std::mt19937_64 random(seed);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial) + " (seed " + std::to_string(seed) + ")");
    // x = +-m / 2^k: a 62-bit numerator, k so that |x| spreads over 2^-10 ... 2^80 rad
    const int exponent = static_cast<int>(random() % 91) - 10;
    Rational x(mpz_class(static_cast<unsigned long>(random() >> 2)));
    x /= Rational(mpz_class(1) << 62);
    if (exponent >= 0) x *= Rational(mpz_class(1) << exponent);
    else x /= Rational(mpz_class(1) << -exponent);
    if (random() % 2) x = -x;
    const simulation::ReducedAngle r = simulation::reduce_turns(x);
    ASSERT_EQ(r.turns.get_den(), 1) << "whole turns";
    const Rational residue = x - 2 * pi * r.turns;
    EXPECT_LE(abs(residue), pi + Rational(1, 1000000)) << "the nearest whole turn";
    EXPECT_EQ(r.angle, nearest(residue)) << "x - 2 pi n rounded once; x = " << x << ", n = " << r.turns;
    EXPECT_EQ(simulation::minus_turns(x, r.turns), r.angle);
    // another turn count: the residue by those turns, rounded once
    const Rational other = r.turns + Rational(static_cast<long>(random() % 7) - 3);
    EXPECT_EQ(simulation::minus_turns(x, other), nearest(x - 2 * pi * other));
    // back: r + 2 pi n rounded once (r the double)
    EXPECT_EQ(simulation::add_turns(r.angle, r.turns), nearest(Rational(r.angle) + 2 * pi * r.turns));
    ++checked;
  }
  EXPECT_EQ(checked, 400);
  // no turns: r itself; a non-finite r is its own sum (its rational aborted in GMP)
  EXPECT_EQ(simulation::add_turns(0.25, Rational(0)), 0.25);
  EXPECT_EQ(simulation::add_turns(std::numeric_limits<double>::infinity(), Rational(3)),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(simulation::add_turns(-std::numeric_limits<double>::infinity(), Rational(-5)),
            -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(simulation::add_turns(std::numeric_limits<double>::quiet_NaN(), Rational(2))));
  // exactly representable cases: 0 and the nearest turn of a small x
  EXPECT_EQ(simulation::reduce_turns(Rational(0)).turns, 0);
  EXPECT_EQ(simulation::reduce_turns(Rational(0)).angle, 0.0);
  EXPECT_EQ(simulation::reduce_turns(Rational(7)).turns, 1);   // 7 - 2 pi = 0.7168...
}

}  // namespace
}  // namespace hipair
