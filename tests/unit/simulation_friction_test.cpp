// Coulomb friction in the simulator (docs/simulation.md#friction), against closed forms on
// generated cases:
//  - a slider on a horizontal guide under a presser on a vertical guide pressed down by a
//    constant force P (normal force N = P): with a horizontal force F the slider sticks when
//    F <= mu_s N and slides with acceleration (F - mu_k N) / m above;
//  - the same slider launched at v1 with F = 0 stops after v1^2 / (2 mu_k N / m) in
//    v1 / (mu_k N / m) (a slip -> stick event located by the step's bisection);
//  - a drum turning on its axis braked by a shoe pressed radially with P: it sticks when its
//    torque T <= mu_s P R and accelerates with (T - mu_k P R) / I above;
//  - energy (kinetic + potential of the constant loads) never increases with friction, at
//    impacts (restitution 0..1) and while sliding;
//  - the frictional LCP on generated problems satisfies the Coulomb conditions.
// The model format's static/kinetic pair is tested with the bad-model corpus (tests/data/bad).
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include "simulation/friction.hpp"
#include "eigen_bits.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
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

std::size_t count(const Simulation& s, SimulationEvent::Kind kind) {
  std::size_t n = 0;
  for (const auto& e : s.events()) n += e.kind == kind;
  return n;
}

// The slider (part 0: a plate 200 mm wide, top face y = 10) translates along x with force F;
// the presser (part 1: a V tip at (0, 10 + drop)) translates along y, pressed down by P. No
// gravity. Units kg, mm, s, N.
std::string press_model(double ms, double mp, double F, double P, double mus, double muk, double v0 = 0,
                        double restitution = 0, double drop = 1e-3, double accuracy = 1e-10) {
  return R"({"hipair": 1, "name": "press", "parts": [
    {"name": "slider", "motion": {"translation": {"direction": [1, 0], "limits": [-80, 80]}},
     "dynamics": {"mass": )" + number(ms) + R"(, "force": [)" + number(F) + R"(, 0]},
     "loops": [{"start": [-100, 0], "edges": [{"line_to": [100, 0]}, {"line_to": [100, 10]},
                {"line_to": [-100, 10], "label": "slider top"}, {"line_to": [-100, 0]}]}]},
    {"name": "presser", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 20]}},
     "initial": {"offset": )" + number(drop) + R"(},
     "dynamics": {"mass": )" + number(mp) + R"(, "force": [0, )" + number(-P) + R"(]},
     "loops": [{"start": [0, 10], "edges": [{"line_to": [8, 14]}, {"line_to": [8, 20]}, {"line_to": [-8, 20]},
                {"line_to": [-8, 14]}, {"line_to": [0, 10]}]}]}],
    "pairs": [{"parts": ["slider", "presser"], "restitution": )" + number(restitution) +
         R"(, "friction": {"static": )" + number(mus) + R"(, "kinetic": )" + number(muk) + R"(}}],
    "simulation": {"accuracy": )" + number(accuracy) + R"(, "velocities": {"slider": )" + number(v0) + R"(}}})";
}

std::size_t count_kind(const std::vector<std::pair<std::string, double>>& log, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& [k, t] : log) n += k == kind;
  return n;
}

// Steps until the first impact has been handled; returns its index in the event log.
std::size_t step_past_impact(Simulation& s, double t_max) {
  while (s.state().time < t_max) {
    s.step();
    for (std::size_t i = 0; i < s.events().size(); ++i)
      if (s.events()[i].kind == SimulationEvent::Kind::impact) return i;
  }
  return s.events().size();
}

// Generated cases: sticks below mu_s N, slides with (F - mu_k N)/m above. The accelerations are
// compared to 1e-9 relative: the sliding motion is a quadratic polynomial in time, which the
// Dormand-Prince pair (order 5) integrates exactly up to round-off; the forces solve a 2x2
// system (round-off relative to the data's magnitudes).
TEST(SimulationFriction, SliderSticksBelowTheStaticLimitAndSlidesWithTheKineticAccelerationAbove) {
  std::mt19937 random(20261127);
  std::uniform_real_distribution<double> unit(0, 1);
  int sticks = 0, slides = 0;
  for (int trial = 0; trial < 12; ++trial) {
    double ms = 0.5 + unit(random), mp = 0.5 + unit(random), P = 0.5 + 5 * unit(random);
    double mus = 0.1 + 0.7 * unit(random), muk = mus * (0.5 + 0.5 * unit(random));
    bool stick = trial % 2 == 0;
    // clear of the limits by 5 %: below 0.95 mu_k N (a sliding slider decelerates and sticks),
    // above 1.05 mu_s N
    double F = stick ? muk * P * (0.05 + 0.9 * unit(random)) : mus * P * (1.05 + unit(random));
    Simulation s = Simulation::create(read_model(press_model(ms, mp, F, P, mus, muk)));
    std::size_t impact = step_past_impact(s, 0.01);
    ASSERT_LT(impact, s.events().size()) << trial;
    s.run_until(s.state().time + 0.02);
    std::vector<SimulationContact> contacts = s.contacts();
    ASSERT_EQ(contacts.size(), 1u) << trial;
    const SimulationContact& c = contacts[0];
    EXPECT_NEAR(c.normal_force, P, 1e-9 * P) << trial;
    if (stick) {
      ++sticks;
      EXPECT_TRUE(c.sticking) << trial;
      EXPECT_NEAR(std::abs(c.friction_force), F, 1e-9 * P) << trial;
      EXPECT_GE(count(s, SimulationEvent::Kind::stick), 1u) << trial;
      // at rest: below the simulator's tangential rest tolerance sqrt(accuracy) 1e-2 (1 + |v|)
      // (1 + sum |T|) = 1e-7 x 2 x 2 mm/s here (the stick rows hold it to round-off)
      double x = s.state().position[0];
      s.run_until(s.state().time + 0.05);
      EXPECT_LE(std::abs(s.state().velocity[0]), 4e-7) << trial;
      EXPECT_LE(std::abs(s.state().position[0] - x), 4e-7 * 0.05) << trial;
    } else {
      ++slides;
      EXPECT_FALSE(c.sticking) << trial;
      EXPECT_NEAR(std::abs(c.friction_force), muk * P, 1e-9 * P) << trial;
      EXPECT_EQ(count(s, SimulationEvent::Kind::stick), 0u) << trial;
      double t1 = s.state().time, v1 = s.state().velocity[0];
      s.run_until(t1 + 0.03);
      double a = (s.state().velocity[0] - v1) / (s.state().time - t1);
      double expected = (F - muk * P) * 1000 / ms;   // mm/s^2
      EXPECT_NEAR(a, expected, 1e-9 * (std::abs(expected) + F * 1000 / ms)) << trial;
    }
  }
  EXPECT_EQ(sticks, 6);
  EXPECT_EQ(slides, 6);
}

// A slider launched at v0 with no driving force stops after v1^2 / (2 mu_k N / m) in
// v1 / (mu_k N / m), v1 its speed just after the presser's landing (the impact's own tangential
// impulse changes it; its effect is measured, not modelled here). With N = m g this is the
// textbook v^2 / (2 mu_k g). The stop is a slip -> stick event located by bisection on the
// step's polynomial (2^-50 of a step): its time and position to 1e-9 relative.
TEST(SimulationFriction, ASlidingSliderStopsAtTheClosedFormDistanceAndTime) {
  std::mt19937 random(112026);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 8; ++trial) {
    double ms = 0.5 + unit(random), mp = 0.5 + unit(random);
    double mus = 0.1 + 0.7 * unit(random), muk = mus * (0.5 + 0.5 * unit(random));
    double g = 9.81, P = ms * g;   // N = m g
    double v0 = 20 + 200 * unit(random);   // mm/s
    double deceleration = muk * P * 1000 / ms;
    Simulation s = Simulation::create(read_model(press_model(ms, mp, 0, P, mus, muk, v0)));
    std::size_t impact = step_past_impact(s, 0.01);
    ASSERT_LT(impact, s.events().size()) << trial;
    double t1 = s.state().time, x1 = s.state().position[0], v1 = s.state().velocity[0];
    ASSERT_GT(v1, 0) << trial;
    EXPECT_LE(v1, v0) << trial;
    while (count(s, SimulationEvent::Kind::stick) == 0 && s.state().time < t1 + 2 * v1 / deceleration + 0.01) s.step();
    ASSERT_EQ(count(s, SimulationEvent::Kind::stick), 1u) << trial;
    double t_stop = 0;
    for (const auto& e : s.events())
      if (e.kind == SimulationEvent::Kind::stick) t_stop = e.time;
    double expected_time = v1 / deceleration, expected_distance = v1 * v1 / (2 * deceleration);
    EXPECT_NEAR(t_stop - t1, expected_time, 1e-9 * (1 + expected_time)) << trial;
    s.run_until(t_stop + 0.01);
    EXPECT_NEAR(s.state().position[0] - x1, expected_distance, 1e-9 * (1 + expected_distance)) << trial;
    EXPECT_LE(std::abs(s.state().velocity[0]), 4e-7) << trial;   // the rest tolerance, as above
  }
}

// Step-size independence of the stick/slip events: a slider launched at 150 mm/s against a
// constant force below mu_k N (it slides, stops and sticks) with the largest step h, h/2 and 2h gives the same event sequence,
// and event times that agree to the stated accuracy (1e-9 s: bisection to 2^-50 of a step on
// an exactly integrated quadratic).
TEST(SimulationFriction, StickSlipEventsDoNotDependOnTheStepSize) {
  std::vector<std::vector<std::pair<std::string, double>>> logs;
  for (double h : {2e-3, 1e-3, 5e-4}) {
    SimulationOptions options;
    options.max_step = h;
    Simulation s = Simulation::create(read_model(press_model(0.7, 0.9, -0.4, 3.0, 0.5, 0.3, 150)), options);
    s.run_until(0.2);
    std::vector<std::pair<std::string, double>> log;
    for (const auto& e : s.events()) log.emplace_back(to_string(e.kind), e.time);
    logs.push_back(log);
  }
  ASSERT_GE(count_kind(logs[0], "stick"), 1u);
  for (std::size_t k = 1; k < logs.size(); ++k) {
    ASSERT_EQ(logs[k].size(), logs[0].size());
    for (std::size_t i = 0; i < logs[0].size(); ++i) {
      EXPECT_EQ(logs[k][i].first, logs[0][i].first) << i;
      EXPECT_NEAR(logs[k][i].second, logs[0][i].second, 1e-9) << logs[0][i].first;
    }
  }
}

// The adaptor's contact_frame: at a configuration on the contact curve its enclosures contain
// contact_at's exact point and normal; next to the curve (a state moved off contact space),
// where contact_at finds nothing, it still gives the frame (the presser's tip and the slider
// top's normal, here exact: (x, 10 + offset) and (0, 1) up to the sign of the feature order).
TEST(SimulationFriction, ContactFrameAgreesWithContactAtAndWorksNextToTheCurve) {
  Simulation s = Simulation::create(read_model(press_model(1, 1, 0, 1, 0.5, 0.5)));
  const CSpace& space = *s.spaces().at(0);
  auto offset = [](double v) {
    PartCoordinate c;
    c.kind = PartCoordinate::Kind::offset;
    c.value = Rational(v);
    return c;
  };
  bool slider_is_x = space.x_part() == "slider";
  for (double x : {-30.0, 0.0, 12.5, 47.0}) {
    PartCoordinate sx = offset(x), py = offset(0);
    std::vector<Contact> on = slider_is_x ? space.contact_at(sx, py) : space.contact_at(py, sx);
    ASSERT_EQ(on.size(), 1u) << x;
    std::optional<Contact> frame = slider_is_x ? space.contact_frame(on[0].feature, sx, py)
                                               : space.contact_frame(on[0].feature, py, sx);
    ASSERT_TRUE(frame.has_value());
    for (int k = 0; k < 2; ++k) {
      double p = on[0].point[k].get_d();
      EXPECT_LE(frame->point_range[k].lower, p);
      EXPECT_GE(frame->point_range[k].upper, p);
    }
    PartCoordinate near = offset(1e-9);
    EXPECT_TRUE((slider_is_x ? space.contact_at(sx, near) : space.contact_at(near, sx)).empty());
    std::optional<Contact> off = slider_is_x ? space.contact_frame(on[0].feature, sx, near)
                                             : space.contact_frame(on[0].feature, near, sx);
    ASSERT_TRUE(off.has_value());
    EXPECT_LE(off->point_range[1].lower, 10 + 1e-9);
    EXPECT_GE(off->point_range[1].upper, 10 + 1e-9);
    EXPECT_LE(off->normal[0].lower, 0.0);
    EXPECT_GE(off->normal[0].upper, 0.0);
    EXPECT_NEAR(std::abs(0.5 * (off->normal[1].lower + off->normal[1].upper)), 1.0, 1e-15);
  }
}

// A drum (radius R, moment of inertia I, torque T) braked by a shoe pressed radially onto its
// top with P: the contact point is a point of the drum's circle (vertex-arc contact; its
// tangential Jacobian is the radius). Sticks when |T| <= mu_s P R, else turns with
// (T - mu_k P R) / I.
std::string drum_model(double I, double T, double mb, double P, double mus, double muk) {
  return R"({"hipair": 1, "name": "drum", "parts": [
    {"name": "drum", "motion": {"rotation": {"pivot": [0, 0]}},
     "dynamics": {"moment_of_inertia": )" + number(I) + R"(, "torque": )" + number(T) + R"(},
     "loops": [{"circle": {"center": [0, 0], "radius": 20}, "label": "drum rim"}]},
    {"name": "shoe", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 20]}},
     "initial": {"offset": 0.001},
     "dynamics": {"mass": )" + number(mb) + R"(, "force": [0, )" + number(-P) + R"(]},
     "loops": [{"start": [0, 20], "edges": [{"line_to": [6, 26]}, {"line_to": [6, 30]}, {"line_to": [-6, 30]},
                {"line_to": [-6, 26]}, {"line_to": [0, 20]}]}]}],
    "pairs": [{"parts": ["drum", "shoe"], "friction": {"static": )" + number(mus) + R"(, "kinetic": )" +
         number(muk) + R"(}}],
    "simulation": {"accuracy": 1e-10}})";
}

TEST(SimulationFriction, BrakedDrumSticksBelowTheStaticTorqueAndTurnsWithTheKineticAccelerationAbove) {
  std::mt19937 random(27112026);
  std::uniform_real_distribution<double> unit(0, 1);
  const double R = 20;
  for (int trial = 0; trial < 6; ++trial) {
    double I = 50 + 500 * unit(random), mb = 0.5 + unit(random), P = 0.5 + 5 * unit(random);
    double mus = 0.1 + 0.7 * unit(random), muk = mus * (0.5 + 0.5 * unit(random));
    bool stick = trial % 2 == 0;
    double T = stick ? muk * P * R * (0.05 + 0.9 * unit(random)) : mus * P * R * (1.05 + unit(random));
    Simulation s = Simulation::create(read_model(drum_model(I, T, mb, P, mus, muk)));
    std::size_t impact = step_past_impact(s, 0.01);
    ASSERT_LT(impact, s.events().size()) << trial;
    s.run_until(s.state().time + 0.02);
    std::vector<SimulationContact> contacts = s.contacts();
    ASSERT_EQ(contacts.size(), 1u) << trial;
    EXPECT_NEAR(contacts[0].normal_force, P, 1e-9 * P) << trial;
    if (stick) {
      EXPECT_TRUE(contacts[0].sticking) << trial;
      // friction force times the radius balances the torque
      EXPECT_NEAR(std::abs(contacts[0].friction_force) * R, T, 1e-9 * P * R) << trial;
      // the rest tolerance of the contact, with sum |T| = R
      EXPECT_LE(std::abs(s.state().velocity[0]), 1e-7 * 2 * (1 + R)) << trial;
    } else {
      EXPECT_FALSE(contacts[0].sticking) << trial;
      double t1 = s.state().time, w1 = s.state().velocity[0];
      s.run_until(t1 + 0.02);
      double alpha = (s.state().velocity[0] - w1) / (s.state().time - t1);
      double expected = (T - muk * P * R) * 1000 / I;
      EXPECT_NEAR(alpha, expected, 1e-9 * (T * 1000 / I)) << trial;
    }
  }
}

// Energy (kinetic plus the potential of the constant loads) never increases with friction:
// generated presses with restitution 0..1, drops of 0.05..0.5 mm (impacts with tangential
// impulses), sliding and sticking. Tolerance per recorded state: 1e-8 of the run's energy scale
// (the integration's relative accuracy 1e-10 times 100 for the round-off of sums of terms of
// that scale).
TEST(SimulationFriction, EnergyNeverIncreases) {
  std::mt19937 random(5150);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 10; ++trial) {
    double ms = 0.5 + unit(random), mp = 0.5 + unit(random), P = 2 + 5 * unit(random);
    double mus = 0.1 + 0.7 * unit(random), muk = mus * (0.5 + 0.5 * unit(random));
    double F = mus * P * 2 * unit(random), v0 = 300 * (unit(random) - 0.5);
    double e = unit(random), drop = 0.05 + 0.45 * unit(random);
    Simulation s = Simulation::create(read_model(press_model(ms, mp, F, P, mus, muk, v0, e, drop)));
    double previous = s.energy();
    double scale = std::abs(previous) + 0.5 * ms * v0 * v0 / 1000 + (P + F) * 100;
    std::size_t impacts_with_friction = 0;
    while (s.state().time < 0.05) {
      s.step();
      double now = s.energy();
      ASSERT_LE(now, previous + 1e-8 * scale) << "trial " << trial << " t " << s.state().time;
      previous = now;
    }
    for (const auto& ev : s.events())
      impacts_with_friction += ev.kind == SimulationEvent::Kind::impact && ev.tangential_impulse != 0;
    EXPECT_GE(count(s, SimulationEvent::Kind::impact), 1u) << trial;
    if (v0 != 0) {
      std::string log;
      for (const auto& ev : s.events())
        log += to_string(ev.kind) + " t " + number(ev.time) + " J " + number(ev.impulse) + " Jt " +
               number(ev.tangential_impulse) + "; ";
      EXPECT_GE(impacts_with_friction, 1u) << trial << " v0 " << v0 << " F " << F << " e " << e << ": " << log;
    }
  }
}

// The coupled case: a bar turning on its pivot strikes the inclined underside of a block
// sliding on a horizontal guide. Both coordinates move the contact point along the normal and the
// tangent (G M^-1 T^T != 0), where Newton restitution with Coulomb friction is not guaranteed to
// dissipate. Generated cases (restitution 0..1, mu_s 0..1.5, relative sliding either way): the
// kinetic energy after every step is not above its value before, to 1e-9 relative (round-off of
// the impulse problem's solve on data of that scale).
std::string bar_block_model(double I, double w0, double mb, double vb, double e, double mus, double muk) {
  return R"({"hipair": 1, "name": "bar-block", "parts": [
    {"name": "bar", "motion": {"rotation": {"pivot": [0, 0]}},
     "dynamics": {"moment_of_inertia": )" + number(I) + R"(},
     "loops": [{"start": [0, -2], "edges": [{"line_to": [40, -2]}, {"line_to": [40, 2]}, {"line_to": [0, 2]},
                {"line_to": [0, -2]}]}]},
    {"name": "block", "motion": {"translation": {"direction": [1, 0], "limits": [-300, 300]}},
     "dynamics": {"mass": )" + number(mb) + R"(},
     "loops": [{"start": [25, 8], "edges": [{"line_to": [55, 14], "label": "block underside"}, {"line_to": [55, 30]},
                {"line_to": [25, 30]}, {"line_to": [25, 8]}]}]}],
    "pairs": [{"parts": ["bar", "block"], "restitution": )" + number(e) +
         R"(, "friction": {"static": )" + number(mus) + R"(, "kinetic": )" + number(muk) + R"(}}],
    "simulation": {"accuracy": 1e-10, "velocities": {"bar": )" + number(w0) + R"(, "block": )" + number(vb) + R"(}}})";
}

TEST(SimulationFriction, CoupledImpactsNeverCreateEnergy) {
  std::mt19937 random(31337);
  std::uniform_real_distribution<double> unit(0, 1);
  int struck = 0, with_friction = 0;
  for (int trial = 0; trial < 20; ++trial) {
    double I = 50 + 450 * unit(random), w0 = 2 + 8 * unit(random), mb = 0.1 + 2 * unit(random);
    double vb = 200 * (unit(random) - 0.5), e = unit(random), mus = 1.5 * unit(random), muk = mus * (0.5 + 0.5 * unit(random));
    Simulation s = Simulation::create(read_model(bar_block_model(I, w0, mb, vb, e, mus, muk)));
    double previous = s.energy(), start = previous;
    while (s.state().time < 0.15) {
      s.step();
      double now = s.energy();
      ASSERT_LE(now, previous + 1e-9 * start) << "trial " << trial << " t " << s.state().time;
      previous = now;
    }
    struck += count(s, SimulationEvent::Kind::impact) > 0;
    for (const auto& ev : s.events()) with_friction += ev.kind == SimulationEvent::Kind::impact && ev.tangential_impulse != 0;
  }
  EXPECT_GE(struck, 10);
  EXPECT_GE(with_friction, 5);
}

// A contact with friction 0 is frictionless: the same trajectory, bit for bit, as the pair
// without a "friction" key (and the escapement's pinned hash in simulation_test runs with its
// friction set to 0).
TEST(SimulationFriction, ZeroFrictionIsTheFrictionlessTrajectory) {
  std::string with = press_model(0.3, 0.2, 1.0, 2.0, 0, 0, 50, 0.5, 1.0);
  std::string without = with;
  without.replace(without.find(R"(, "friction")"), std::string(R"(, "friction": {"static": 0, "kinetic": 0})").size(), "");
  ASSERT_EQ(without.find("friction"), std::string::npos);
  Simulation a = Simulation::create(read_model(with));
  Simulation b = Simulation::create(read_model(without));
  a.run_until(0.05);
  b.run_until(0.05);
  EXPECT_EQ(a.events().size(), b.events().size());
  EXPECT_EQ(a.state().position, b.state().position);
  EXPECT_EQ(a.state().velocity, b.state().velocity);
}

// The frictional LCP on generated problems (3 coordinates, 1..3 contacts with random normal and
// tangent rows, masses and loads): a solution is found, and it satisfies lambda >= 0, w >= 0,
// lambda w = 0, |f| <= mu_s N when sticking (T x = 0), f = -sign mu_k N when sliding with
// sign T x >= 0.
TEST(SimulationFriction, FrictionalLcpSatisfiesTheCoulombConditionsOnGeneratedProblems) {
  std::mt19937 random(77);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int solved = 0, total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Index n = 3, m = 1 + trial % 3;
    Eigen::MatrixXd G(m, n);
    std::vector<simulation::Friction> friction(static_cast<std::size_t>(m));
    for (Eigen::Index k = 0; k < m; ++k) {
      G.row(k) = Eigen::RowVectorXd::Random(n);
      auto& c = friction[static_cast<std::size_t>(k)];
      c.on = true;
      c.T = Eigen::VectorXd::Random(n);
      c.s = 0.5 + std::abs(uniform(random));
      c.mu_static = 0.1 + 0.5 * std::abs(uniform(random));
      c.mu_kinetic = c.mu_static * (0.5 + 0.5 * std::abs(uniform(random)));
    }
    Eigen::VectorXd minv(n), a0(n), h = Eigen::VectorXd::Zero(m);
    for (Eigen::Index i = 0; i < n; ++i) {
      minv(i) = 0.5 + std::abs(uniform(random));
      a0(i) = uniform(random);
    }
    ++total;
    simulation::FrictionalSolution s = simulation::solve_frictional(G, minv, a0, h, friction);
    if (!s.solved) continue;   // possible for mu large against coupled rows (Painleve); counted
    ++solved;
    for (Eigen::Index k = 0; k < m; ++k) {
      const auto& c = friction[static_cast<std::size_t>(k)];
      double tol = 1e-8;
      EXPECT_GE(s.lambda(k), -tol);
      EXPECT_GE(s.w(k), -tol);
      EXPECT_LE(std::abs(s.lambda(k) * s.w(k)), tol);
      double N = s.lambda(k) / c.s, vt = c.T.dot(s.x);
      int st = s.state[static_cast<std::size_t>(k)];
      if (st == simulation::stick) {
        EXPECT_LE(std::abs(s.f(k)), c.mu_static * N + tol);
        EXPECT_NEAR(vt, 0, tol);
      } else {
        EXPECT_NEAR(s.f(k), -st * c.mu_kinetic * N, tol);
        EXPECT_GE(st * vt, -tol);
      }
    }
  }
  // with friction coefficients below 0.6 and well-conditioned rows nearly all are consistent
  EXPECT_GE(solved, total * 9 / 10);
}


// The enumeration's kept storage (session 60: BilateralWork, LcpWork and the candidate solution
// reused across the stick/slip assignments, LcpWork across LCPs) gives the doubles of fresh
// objects: solve_frictional against the per-assignment fresh form it replaced (below, as it was),
// and solve_lcp's work form, reused over a run of problems of changing sizes, against its value
// form — bit for bit, on generated problems (1..4 contacts, with and without the frictionless
// fallback of undetermined multipliers, sticking pairs of equal rows among them).
simulation::FrictionalSolution fresh_frictional(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv,
                                                const Eigen::VectorXd& a0, const Eigen::VectorXd& h,
                                                const std::vector<simulation::Friction>& friction,
                                                bool undetermined_plain) {
  using namespace simulation;
  const std::size_t m = friction.size();
  std::vector<std::size_t> open;
  std::vector<int> state(m, frictionless);
  for (std::size_t k = 0; k < m; ++k) {
    if (!friction[k].on) continue;
    if (friction[k].decided) state[k] = friction[k].state;
    else open.push_back(k);
  }
  FrictionalSolution best;
  std::optional<LcpSolution> plain;
  Eigen::MatrixXd Af;
  Eigen::VectorXd bf;
  std::size_t combinations = 1;
  for (std::size_t i = 0; i < open.size(); ++i) combinations *= 3;
  std::vector<std::size_t> order(combinations);
  auto slips = [&](std::size_t code) {
    int count = 0;
    for (std::size_t i = 0; i < open.size(); ++i, code /= 3) count += code % 3 != 0;
    return count;
  };
  for (std::size_t c = 0; c < combinations; ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return slips(a) < slips(b); });
  for (std::size_t code : order) {
    std::size_t rest = code;
    for (std::size_t i = 0; i < open.size(); ++i, rest /= 3) {
      static constexpr int digit_state[3] = {stick, slip_positive, slip_negative};
      state[open[i]] = digit_state[rest % 3];
    }
    Reduced r = reduce(G, minv, a0, friction, state);
    Eigen::MatrixXd A = G * r.B;
    Eigen::VectorXd b = G * r.x0 + h;
    LcpSolution lcp = solve_lcp(A, b);
    FrictionalSolution s;
    s.state = state;
    if (lcp.solved) {
      s.lambda = lcp.lambda;
      s.tolerance = lcp.tolerance;
      complete(s, r, G, h, friction);
      if (coulomb_satisfied(s, friction)) {
        s.solved = true;
        return s;
      }
    }
    if (!undetermined_plain || r.sticking.empty()) continue;
    if (!plain) {
      Af = G * minv.asDiagonal() * G.transpose();
      bf = G * a0 + h;
      plain = solve_lcp(Af, bf);
    }
    if (!plain->solved || !undetermined(A, Af)) continue;
    const double tolerance = 10 * std::max(plain->tolerance, lcp_tolerance(A, b));
    if (!lcp_satisfied(A, b, plain->lambda, tolerance)) continue;
    s.lambda = plain->lambda;
    s.tolerance = tolerance;
    complete(s, r, G, h, friction);
    if (!coulomb_satisfied(s, friction)) continue;
    s.solved = true;
    return s;
  }
  return best;
}

using test::same_bits;

TEST(SimulationFriction, KeptStorageGivesTheFreshObjectsDoubles) {
  std::mt19937 random(6060);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int solved = 0, undetermined_taken = 0;
  simulation::LcpWork work;   // one work form reused over every LCP below
  simulation::LcpSolution kept;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Index n = 2 + trial % 3, m = 1 + (trial / 3) % 4;
    Eigen::MatrixXd G(m, n);
    std::vector<simulation::Friction> friction(static_cast<std::size_t>(m));
    for (Eigen::Index k = 0; k < m; ++k) {
      for (Eigen::Index i = 0; i < n; ++i) G(k, i) = uniform(random);
      // a wedge now and then: a row repeated (its multipliers left open by the sticking rows)
      if (k > 0 && trial % 5 == 0) G.row(k) = G.row(k - 1);
      auto& c = friction[static_cast<std::size_t>(k)];
      c.on = trial % 7 != 0 || k % 2 == 0;
      c.T = Eigen::VectorXd(n);
      for (Eigen::Index i = 0; i < n; ++i) c.T(i) = uniform(random);
      c.s = 0.5 + std::abs(uniform(random));
      c.mu_static = 0.1 + 0.8 * std::abs(uniform(random));
      c.mu_kinetic = c.mu_static * (0.5 + 0.5 * std::abs(uniform(random)));
      c.decided = trial % 4 == 1 && k == 0;
      c.state = c.decided ? (uniform(random) > 0 ? simulation::slip_positive : simulation::slip_negative) : 0;
    }
    Eigen::VectorXd minv(n), a0(n), h(m);
    for (Eigen::Index i = 0; i < n; ++i) {
      minv(i) = 0.5 + std::abs(uniform(random));
      a0(i) = uniform(random);
    }
    for (Eigen::Index k = 0; k < m; ++k) h(k) = 0.3 * uniform(random);
    const bool plain = trial % 2 == 0;
    const simulation::FrictionalSolution a = simulation::solve_frictional(G, minv, a0, h, friction, {}, plain);
    const simulation::FrictionalSolution b = fresh_frictional(G, minv, a0, h, friction, plain);
    ASSERT_EQ(a.solved, b.solved) << "trial " << trial;
    EXPECT_EQ(a.state, b.state) << "trial " << trial;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.tolerance), std::bit_cast<std::uint64_t>(b.tolerance)) << "trial " << trial;
    EXPECT_TRUE(same_bits(a.lambda, b.lambda)) << "trial " << trial;
    EXPECT_TRUE(same_bits(a.w, b.w)) << "trial " << trial;
    EXPECT_TRUE(same_bits(a.x, b.x)) << "trial " << trial;
    EXPECT_TRUE(same_bits(a.f, b.f)) << "trial " << trial;
    solved += a.solved;
    if (a.solved && plain && trial % 5 == 0) ++undetermined_taken;
    // the LCP of the frictionless rows through the reused work form and the value form
    const Eigen::MatrixXd A = G * minv.asDiagonal() * G.transpose();
    const Eigen::VectorXd bl = G * a0 + h;
    simulation::solve_lcp(A, bl, work, kept);
    const simulation::LcpSolution fresh = simulation::solve_lcp(A, bl);
    ASSERT_EQ(kept.solved, fresh.solved) << "trial " << trial;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(kept.tolerance), std::bit_cast<std::uint64_t>(fresh.tolerance));
    EXPECT_TRUE(same_bits(kept.lambda, fresh.lambda)) << "trial " << trial;
    EXPECT_TRUE(same_bits(kept.w, fresh.w)) << "trial " << trial;
  }
  // the comparison is not vacuous: most problems are solved, wedges among them
  EXPECT_GE(solved, 300);
  EXPECT_GE(undetermined_taken, 10);
}

}  // namespace
}  // namespace hipair
