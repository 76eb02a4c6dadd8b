// Stick/slip inside a step against closed forms (docs/simulation.md, "Session 42 (graze42)"):
//  - a block on an incline of angle theta (exact Pythagorean cosines): the block slides on a
//    guide along the incline, the normal load is a presser of the same mass on a guide normal to
//    it, gravity vertical, so along the incline m a = m g sin(theta) -+ mu_k m g cos(theta) and
//    N = m g cos(theta) — the textbook block. Launched down with mu_k > tan(theta) it stops at
//    t = v1 / (g (mu_k cos - sin)) and stays; launched up with mu_s > tan(theta) > mu_k it stops
//    at v1 / (g (sin + mu_k cos)) and stays (static friction holds what kinetic could not);
//    launched up with tan(theta) > mu_s it stops at the same time and slides back down with
//    g (sin - mu_k cos) (a slip reversal, not a stick);
//  - a block pushed by a force F between the kinetic and static thresholds (mu_k N < F < mu_s N)
//    launched against F: it stops at m v1 / (F + mu_k N) and stays; launched along F it keeps
//    sliding with (F - mu_k N) / m.
// The zero crossing of the tangential velocity lies inside a step: it is located by the step's
// bisection (2^-50 of a step), and the next step's problem decides stick or slip.
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

namespace hipair {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

std::size_t count(const Simulation& s, SimulationEvent::Kind kind, double after) {
  std::size_t n = 0;
  for (const auto& e : s.events()) n += e.kind == kind && e.time > after;
  return n;
}

// Steps until the first impact (the presser's landing) has been handled.
bool step_past_impact(Simulation& s, double t_max) {
  while (s.state().time < t_max) {
    s.step();
    for (const auto& e : s.events())
      if (e.kind == SimulationEvent::Kind::impact) return true;
  }
  return false;
}

struct Triple {
  int c, s, k;   // cos = c / k, sin = s / k
};

// The incline: local coordinates (a along the incline, downwards; b along its normal) to world
// (a c + b s, -a s + b c) / k; local values are multiples of k, so the world's are integers.
std::string incline_model(const Triple& t, double m, double mus, double muk, double v0) {
  auto at = [&](int a, int b) {
    return "[" + std::to_string((a * t.c + b * t.s) / t.k) + ", " + std::to_string((-a * t.s + b * t.c) / t.k) + "]";
  };
  const int k = t.k;
  return R"({"hipair": 1, "name": "incline", "parts": [
    {"name": "block", "motion": {"translation": {"direction": [)" + std::to_string(t.c) + ", " + std::to_string(-t.s) +
         R"(], "limits": [-400, 400]}},
     "dynamics": {"mass": )" + number(m) + R"(},
     "loops": [{"start": )" + at(-20 * k, 0) + R"(, "edges": [{"line_to": )" + at(20 * k, 0) + R"(}, {"line_to": )" +
         at(20 * k, k) + R"(}, {"line_to": )" + at(-20 * k, k) + R"(, "label": "block face"}, {"line_to": )" + at(-20 * k, 0) +
         R"(}]}]},
    {"name": "presser", "motion": {"translation": {"direction": [)" + std::to_string(t.s) + ", " + std::to_string(t.c) +
         R"(], "limits": [-5, 20]}},
     "initial": {"offset": 0.001},
     "dynamics": {"mass": )" + number(m) + R"(},
     "loops": [{"start": )" + at(0, k) + R"(, "edges": [{"line_to": )" + at(k, 2 * k) + R"(}, {"line_to": )" + at(k, 3 * k) +
         R"(}, {"line_to": )" + at(-k, 3 * k) + R"(}, {"line_to": )" + at(-k, 2 * k) + R"(}, {"line_to": )" + at(0, k) +
         R"(}]}]}],
    "pairs": [{"parts": ["block", "presser"], "restitution": 0, "friction": {"static": )" + number(mus) +
         R"(, "kinetic": )" + number(muk) + R"(}}],
    "simulation": {"accuracy": 1e-10, "gravity": [0, -9810], "velocities": {"block": )" + number(v0) + R"(}}})";
}

// the first event of `kind` after the landing (its own slip event has the landing's time)
double stick_or_slip_time(const Simulation& s, SimulationEvent::Kind kind, double t1) {
  for (const SimulationEvent& e : s.events())
    if (e.kind == kind && e.time > t1) return e.time;
  return std::nan("");
}

TEST(SimulationFrictionIncline, BlockStopsAtTheClosedFormTimeThenStaysOrSlidesBack) {
  const Triple triples[] = {{4, 3, 5}, {12, 5, 13}, {15, 8, 17}, {24, 7, 25}};
  std::mt19937 random(2042);
  std::uniform_real_distribution<double> unit(0, 1);
  const double g = 9810;   // mm/s^2
  int stays = 0, back = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Triple& t = triples[trial % 4];
    const double cs = double(t.c) / t.k, sn = double(t.s) / t.k, tan_theta = sn / cs;
    const int scenario = trial % 3;   // 0 down and stays, 1 up and stays, 2 up and back
    double mus, muk, v0;
    const double m = 0.5 + unit(random);
    if (scenario == 0) {
      muk = tan_theta * (1.2 + 0.5 * unit(random));
      mus = muk * (1 + 0.3 * unit(random));
      v0 = 40 + 150 * unit(random);
    } else if (scenario == 1) {
      muk = tan_theta * (0.3 + 0.5 * unit(random));
      mus = tan_theta * (1.15 + 0.5 * unit(random));
      v0 = -(40 + 150 * unit(random));
    } else {
      muk = tan_theta * (0.2 + 0.4 * unit(random));
      mus = tan_theta * (0.65 + 0.25 * unit(random));
      v0 = -(40 + 150 * unit(random));
    }
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " scenario " << scenario << " tan " << tan_theta << " mus " << mus
                                      << " muk " << muk << " v0 " << v0);
    Simulation s = Simulation::create(read_model(incline_model(t, m, mus, muk, v0), "incline"));
    ASSERT_TRUE(step_past_impact(s, 0.01));
    const double t1 = s.state().time, v1 = s.state().velocity[0];
    ASSERT_GT(v1 * v0, 0);
    // decelerating: down, friction up the incline; up, gravity and friction both down
    const double deceleration = scenario == 0 ? g * (muk * cs - sn) : g * (sn + muk * cs);
    const double expected_stop = std::abs(v1) / deceleration;
    const SimulationEvent::Kind change = scenario == 2 ? SimulationEvent::Kind::slip : SimulationEvent::Kind::stick;
    while (std::isnan(stick_or_slip_time(s, change, t1)) && s.state().time < t1 + 2 * expected_stop + 0.01) s.step();
    const double t_stop = stick_or_slip_time(s, change, t1);
    ASSERT_FALSE(std::isnan(t_stop));
    EXPECT_NEAR(t_stop - t1, expected_stop, 1e-9 * (1 + expected_stop));
    if (scenario < 2) {
      ++stays;
      // at rest from there on, no further state change (the static limit holds the block)
      const double x = s.state().position[0];
      s.run_until(t_stop + 0.1);
      EXPECT_EQ(count(s, SimulationEvent::Kind::slip, t1), 0u);
      EXPECT_LE(std::abs(s.state().velocity[0]), 1e-6);
      EXPECT_LE(std::abs(s.state().position[0] - x), 1e-6);
      ASSERT_EQ(s.contacts().size(), 1u);
      EXPECT_TRUE(s.contacts()[0].sticking);
      // the friction force holds the weight's component along the incline: m g sin (N), below
      // mu_s m g cos
      EXPECT_NEAR(std::abs(s.contacts()[0].friction_force), m * g * sn / 1000, 1e-9 * m * g / 1000);
    } else {
      ++back;
      // no stick at the reversal; down the incline with g (sin - mu_k cos)
      EXPECT_EQ(count(s, SimulationEvent::Kind::stick, t1), 0u);
      s.run_until(t_stop + 0.01);
      const double ta = s.state().time, va = s.state().velocity[0];
      s.run_until(ta + 0.02);
      const double a = (s.state().velocity[0] - va) / (s.state().time - ta);
      const double expected = g * (sn - muk * cs);
      EXPECT_GT(va, 0);
      EXPECT_NEAR(a, expected, 1e-9 * g);
    }
  }
  EXPECT_EQ(stays, 8);
  EXPECT_EQ(back, 4);
}

// The horizontal press of simulation_friction_test.cpp with a force between the thresholds.
std::string press_model(double ms, double mp, double F, double P, double mus, double muk, double v0) {
  return R"({"hipair": 1, "name": "press", "parts": [
    {"name": "slider", "motion": {"translation": {"direction": [1, 0], "limits": [-80, 80]}},
     "dynamics": {"mass": )" + number(ms) + R"(, "force": [)" + number(F) + R"(, 0]},
     "loops": [{"start": [-100, 0], "edges": [{"line_to": [100, 0]}, {"line_to": [100, 10]},
                {"line_to": [-100, 10], "label": "slider top"}, {"line_to": [-100, 0]}]}]},
    {"name": "presser", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 20]}},
     "initial": {"offset": 0.001},
     "dynamics": {"mass": )" + number(mp) + R"(, "force": [0, )" + number(-P) + R"(]},
     "loops": [{"start": [0, 10], "edges": [{"line_to": [8, 14]}, {"line_to": [8, 20]}, {"line_to": [-8, 20]},
                {"line_to": [-8, 14]}, {"line_to": [0, 10]}]}]}],
    "pairs": [{"parts": ["slider", "presser"], "restitution": 0, "friction": {"static": )" + number(mus) +
         R"(, "kinetic": )" + number(muk) + R"(}}],
    "simulation": {"accuracy": 1e-10, "velocities": {"slider": )" + number(v0) + R"(}}})";
}

TEST(SimulationFrictionIncline, ForceBetweenTheThresholdsStopsABlockLaunchedAgainstIt) {
  std::mt19937 random(4242);
  std::uniform_real_distribution<double> unit(0, 1);
  int against = 0, along = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const double ms = 0.5 + unit(random), mp = 0.5 + unit(random), P = 1 + 4 * unit(random);
    const double muk = 0.1 + 0.4 * unit(random), mus = muk * (1.5 + unit(random));
    // clear of both thresholds by 10 % of the gap between them
    const double F = P * (muk + (mus - muk) * (0.1 + 0.8 * unit(random)));
    const bool launched_against = trial % 2 == 0;
    const double v0 = (launched_against ? -1 : 1) * (30 + 150 * unit(random));
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " F " << F << " P " << P << " mus " << mus << " muk " << muk
                                      << " v0 " << v0);
    Simulation s = Simulation::create(read_model(press_model(ms, mp, F, P, mus, muk, v0), "press"));
    ASSERT_TRUE(step_past_impact(s, 0.01));
    const double t1 = s.state().time, v1 = s.state().velocity[0];
    ASSERT_GT(v1 * v0, 0);
    if (launched_against) {
      ++against;
      const double deceleration = (F + muk * P) * 1000 / ms;   // mm/s^2
      const double expected_stop = std::abs(v1) / deceleration;
      while (std::isnan(stick_or_slip_time(s, SimulationEvent::Kind::stick, t1)) &&
             s.state().time < t1 + 2 * expected_stop + 0.01)
        s.step();
      const double t_stop = stick_or_slip_time(s, SimulationEvent::Kind::stick, t1);
      ASSERT_FALSE(std::isnan(t_stop));
      EXPECT_NEAR(t_stop - t1, expected_stop, 1e-9 * (1 + expected_stop));
      const double x = s.state().position[0];
      s.run_until(t_stop + 0.1);
      EXPECT_EQ(count(s, SimulationEvent::Kind::slip, t1), 0u);
      EXPECT_LE(std::abs(s.state().velocity[0]), 1e-6);
      EXPECT_LE(std::abs(s.state().position[0] - x), 1e-6);
      ASSERT_EQ(s.contacts().size(), 1u);
      EXPECT_TRUE(s.contacts()[0].sticking);
      EXPECT_NEAR(std::abs(s.contacts()[0].friction_force), F, 1e-9 * P);
    } else {
      ++along;
      s.run_until(t1 + 0.01);
      const double ta = s.state().time, va = s.state().velocity[0];
      s.run_until(ta + 0.03);
      EXPECT_EQ(count(s, SimulationEvent::Kind::stick, t1), 0u);
      const double a = (s.state().velocity[0] - va) / (s.state().time - ta);
      const double expected = (F - muk * P) * 1000 / ms;
      EXPECT_NEAR(a, expected, 1e-9 * (F + muk * P) * 1000 / ms);
    }
  }
  EXPECT_EQ(against, 4);
  EXPECT_EQ(along, 4);
}

}  // namespace
}  // namespace hipair
