// A held contact that an impact separates lifts off at the impact (src/simulation/simulation.cpp
// handle_contacts; docs/simulation.md, "Session 64 (stick64)" and "Session 65 (stick65)").
// A block c (mass m_c, vertical translation) lands on the ground and rests there under gravity
// (a held, plastic contact); a striker s (mass m_s, horizontal translation, thrown at v) hits c's
// face of slope -1 from below-left. The impulse problem of the strike (restitution e) with the
// ground's held row: the closed form leaves the ground without impulse, P = (1 + e) v / (1/m_s +
// 1/m_c) on the strike, c leaving upwards at P / m_c, the striker at v - P / m_s — c lifts off the
// ground at the impact, and nothing strikes again at that instant (the impulse sqrt 2 P along the
// face's normal, the normal speed after -e times before). Before session 64 the projection after
// the impact put every held contact's normal speed back to 0 (c's upward speed taken away).
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace hipair {
namespace {

std::string struck_block(double m_s, double m_c, double v, double e) {
  return R"({"hipair": 1, "name": "struck-block", "parts": [
    {"name": "s", "motion": {"translation": {"direction": [1, 0], "limits": [-20, 40]}},
     "dynamics": {"mass": )" + std::to_string(m_s) + R"(},
     "loops": [{"start": [-35, -5], "edges": [{"line_to": [-5, -5]}, {"line_to": [-15, 5], "label": "striker face"},
                {"line_to": [-35, 5]}, {"line_to": [-35, -5]}]}]},
    {"name": "c", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 60]}}, "initial": {"offset": 0.5},
     "dynamics": {"mass": )" + std::to_string(m_c) + R"(},
     "loops": [{"start": [0, 0], "edges": [{"line_to": [20, 0], "label": "c bottom"}, {"line_to": [20, 20]},
                {"line_to": [-20, 20]}, {"line_to": [0, 0], "label": "c face"}]}]},
    {"name": "ground", "motion": "fixed",
     "loops": [{"start": [-5, -5], "edges": [{"line_to": [30, -5]}, {"line_to": [30, 0], "label": "ground top"},
                {"line_to": [-5, 0]}, {"line_to": [-5, -5]}]}]}],
    "pairs": [{"parts": ["s", "c"], "restitution": )" + std::to_string(e) + R"(},
              {"parts": ["c", "ground"], "restitution": 0}],
    "simulation": {"gravity": [0, -9810], "velocities": {"s": )" + std::to_string(v) + R"(}, "accuracy": 1e-10}})";
}

TEST(SimulationImpactLiftOff, AHeldContactTheImpactSeparatesLiftsOffAtTheImpact) {
  std::mt19937_64 rng(hipair::test::test_seed(0x11f70ffULL));
  std::uniform_real_distribution<double> unit(0, 1);
  int cases = 0;
  for (int c = 0; c < 6; ++c) {
    // (each value the number the model's text gives it: std::to_string's six decimals)
    auto as_written = [](double x) { return std::stod(std::to_string(x)); };
    const double m_s = as_written(0.05 + 0.5 * unit(rng)), m_c = as_written(0.05 + 0.5 * unit(rng));
    const double v = as_written(100 + 100 * unit(rng)), e = c == 0 ? 0.0 : c == 1 ? 1.0 : as_written(unit(rng));
    const std::string where = "case " + std::to_string(c) + ": m_s " + std::to_string(m_s) + " m_c " +
                              std::to_string(m_c) + " v " + std::to_string(v) + " e " + std::to_string(e);
    Simulation s = Simulation::create(read_model(struck_block(m_s, m_c, v, e)));
    // c lands (an impact and a held contact), then the strike
    std::size_t strike = 0;
    auto find_strike = [&] {
      for (std::size_t i = 0; i < s.events().size(); ++i)
        if (s.events()[i].kind == SimulationEvent::Kind::impact && s.events()[i].pair == 0) return i + 1;
      return std::size_t{0};
    };
    while ((strike = find_strike()) == 0 && s.state().time < 0.2) s.step();
    ASSERT_NE(strike, 0u) << where;
    const SimulationEvent hit = s.events()[strike - 1];
    // the striker's face reaches c's (at rest on the ground, offset 0) after 10 mm
    EXPECT_NEAR(hit.time, 10 / v, 1e-8) << where;
    const double P = (1 + e) * v / (1 / m_s + 1 / m_c);   // kg mm/s
    // the impulse along the face's normal (1, 1)/sqrt 2: sqrt 2 P (P on each coordinate), N s
    EXPECT_NEAR(hit.impulse, std::sqrt(2.0) * P * 1e-3, 1e-9 * P) << where;
    // Newton's law on the strike's normal speed (the ground's held row takes no impulse)
    EXPECT_NEAR(hit.normal_speed_after, -e * hit.normal_speed_before, 1e-9 * v) << where;
    EXPECT_LT(hit.normal_speed_before, 0) << where;
    // the ground contact lifts off at the strike, with no other impact at that instant
    int lift_offs = 0, impacts = 0;
    for (const SimulationEvent& event : s.events()) {
      if (event.time != hit.time) continue;
      lift_offs += event.kind == SimulationEvent::Kind::lift_off && event.pair == 1;
      impacts += event.kind == SimulationEvent::Kind::impact;
    }
    EXPECT_EQ(lift_offs, 1) << where;
    EXPECT_EQ(impacts, 1) << where;
    // (the state after the step is later than the strike: e = 0 keeps the striker on c's face,
    // lifting it; velocities are not compared there)
    // and c leaves the ground: after a further step it is above it
    const double t_hit = s.state().time;
    while (s.state().time < t_hit + 1e-3) s.step();
    EXPECT_GT(s.state().position[1], 0) << where;
    ++cases;
  }
  EXPECT_EQ(cases, 6);
}

}  // namespace
}  // namespace hipair
