// The escapement's driving-torque band (docs/simulation.md, "Escapement"): the frictionless
// escapement (tests/data/simulation/escapement-frictionless.json: examples/models/escapement.json
// without its pairs' friction 0.1, as the torque tables were measured) inside the band keeps a
// steady oscillation with one tooth per balance period; beyond it the escape wheel stops with the
// impulse pin held on the outside of a fork horn. And the three simulator defects that ended the
// frictionless runs at -612 ... -1200 N.mm (a jam or an endless step) before session 11.

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair {
namespace {

Model escapement(long torque) {
  ReadOptions options;
  options.parameter_values["drive-torque"] = Rational(torque);
  options.allow_out_of_tolerance = true;
  return read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "simulation" / "escapement-frictionless.json", options);
}

std::size_t part(const Model& model, const std::string& name) {
  for (std::size_t i = 0; i < model.parts.size(); ++i)
    if (model.parts[i].name == name) return i;
  ADD_FAILURE() << "no part " << name;
  return 0;
}

struct Record {
  std::vector<double> t, wheel, anchor, balance, balance_speed;
};

Record run(Simulation& s, const Model& model, double t_end) {
  Record r;
  std::size_t w = part(model, "escape-wheel"), a = part(model, "anchor"), b = part(model, "balance");
  auto keep = [&](double) {
    const SimulationState& st = s.state();
    r.t.push_back(st.time);
    r.wheel.push_back(st.position[w]);
    r.anchor.push_back(st.position[a]);
    r.balance.push_back(st.position[b]);
    r.balance_speed.push_back(st.velocity[b]);
  };
  keep(0);
  s.run_until(t_end, keep);
  return r;
}

constexpr double tooth = 2 * std::numbers::pi / 15;   // the escape wheel's 15 teeth

// A departing motion from a configuration a few ulps off a contact curve is certified: at
// -1200 N.mm the tooth-13 corner bounces off the entry locking face at t = 0.325776833828 s and
// leaves it at 0.845 rad/s; the nudged start lay within rounding of the face, the query's
// mean-value test took F at the start in doubles (an enclosure containing 0), reported a grazing
// crossing at u in [0, 2^-44] at every step, and the simulator struck the separating contact
// with impulse 0 forever (the joint-nudge branch's "did not finish in 50 min"). With a step cap
// the endless step is a NumericError ("more than max_steps"): this test failed so.
TEST(SimulationEscapementTorque, DepartureFromALockingFaceIsCertified) {
  Model model = escapement(-1200);
  SimulationOptions options;
  options.max_steps = 5000;   // the run takes about 300 steps
  Simulation s = Simulation::create(model, options);
  ASSERT_NO_THROW(s.run_until(0.4));
  EXPECT_LT(s.steps(), 1000u);
  EXPECT_DOUBLE_EQ(s.state().time, 0.4);
}

// Newton restitution acts on approach only: no impact leaves a contact approaching (w = G v+ +
// e min(G v-, 0) >= 0). A contact within the accuracy of closing that joins another pair's
// impact may already be separating; with w = G v+ + e G v- it was struck into approach at
// -e G v-: at -1200 N.mm, t = 0.3314 s, anchor/banking from +2.76 to -0.83 mm/s (failed so).
// The bound is the complementarity solver's tolerance, 1e-10 of the row's speeds.
TEST(SimulationEscapementTorque, NoImpactLeavesAContactApproaching) {
  Model model = escapement(-1200);
  Simulation s = Simulation::create(model);
  s.run_until(0.4);
  int impacts = 0;
  for (const SimulationEvent& e : s.events()) {
    if (e.kind != SimulationEvent::Kind::impact) continue;
    ++impacts;
    EXPECT_GE(e.normal_speed_after, -1e-10 * std::max(1.0, std::abs(e.normal_speed_before)))
        << "t " << e.time << " " << e.first_part << " / " << e.second_part << " before " << e.normal_speed_before;
  }
  EXPECT_GT(impacts, 20);
}

// A held contact that has left its edge when a step ends changes there as at a watched edge
// end. At -675 N.mm the impulse pin slides along fork slot wall R up to the corner of the fork
// R tip (t = 0.5543 s, steps shrinking to 1e-8 s); the step's watch did not cut there, the row
// failed after the step, and the pair was nudged along a zero direction: "pair (anchor, balance)
// cannot be moved off its contact" (failed so). Now: an edge end at the vertex, where the
// corner of the tip takes the contact over.
TEST(SimulationEscapementTorque, HeldContactPastItsEdgeEndsAtTheVertex) {
  Model model = escapement(-675);
  Simulation s = Simulation::create(model);
  ASSERT_NO_THROW(s.run_until(0.6));
  bool corner = false;
  for (const SimulationEvent& e : s.events())
    if (e.time > 0.5543 && e.time < 0.5544 && e.kind == SimulationEvent::Kind::contact)
      for (const std::string& f : e.features) corner = corner || f.find("corner of fork R tip") != std::string::npos;
  EXPECT_TRUE(corner);
}

// Inside the band (-500 ... -600 N.mm, docs/simulation.md): at -575 N.mm over 2.4 s (12
// periods) the balance keeps its period, the wheel advances one tooth per period and the
// amplitude is maintained. Bounds, from the quantities: every period of the last 1.2 s within
// 2.5 % of the natural period 0.2 s (the band's runs keep 0.2003-0.2026 s; the overdriven runs
// beyond it have periods of 0.209-0.24 s and reversals in place of 0.03 s); the wheel's advance
// within half a tooth of one tooth per period; the mean half-swing amplitude of the last two
// periods not below that of the two periods before by more than a fifth of the unfed decay (at
// -200 N.mm, which does not feed the balance, the amplitude falls 5.4 % per second, 2.2 % per
// two periods: bound 0.44 %).
TEST(SimulationEscapementTorque, RunsSteadilyInsideTheBand) {
  Model model = escapement(-575);
  Simulation s = Simulation::create(model);
  Record r = run(s, model, 2.4);
  ASSERT_DOUBLE_EQ(r.t.back(), 2.4);
  std::vector<double> reversal_t, reversal_q;
  for (std::size_t i = 1; i < r.t.size(); ++i)
    if (r.balance_speed[i] * r.balance_speed[i - 1] < 0) {
      reversal_t.push_back(r.t[i]);
      reversal_q.push_back(r.balance[i]);
    }
  ASSERT_GE(reversal_t.size(), 20u);
  for (std::size_t i = 2; i < reversal_t.size(); ++i) {
    if (reversal_t[i] < 1.2) continue;
    double period = reversal_t[i] - reversal_t[i - 2];
    EXPECT_NEAR(period, 0.2, 0.025 * 0.2) << "period ending at " << reversal_t[i];
  }
  double periods = (reversal_t.back() - reversal_t.front()) / 0.2;
  double teeth_between = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] == reversal_t.front()) teeth_between = r.wheel[i];
  teeth_between = (teeth_between - r.wheel[std::find(r.t.begin(), r.t.end(), reversal_t.back()) - r.t.begin()]) / tooth;
  EXPECT_NEAR(teeth_between, periods, 0.5);
  std::vector<double> amplitude;
  for (std::size_t i = 1; i < reversal_q.size(); ++i) amplitude.push_back(std::abs(reversal_q[i] - reversal_q[i - 1]) / 2);
  auto mean = [&](std::size_t from, std::size_t n) {
    double sum = 0;
    for (std::size_t i = from; i < from + n; ++i) sum += amplitude[i];
    return sum / static_cast<double>(n);
  };
  std::size_t n = amplitude.size();
  double last = mean(n - 4, 4), before = mean(n - 8, 4);
  EXPECT_GE(last, before * (1 - 0.0044)) << "last two periods " << last << " rad, two before " << before << " rad";
  EXPECT_GT(last, 0.9);
}

// Beyond the band the escapement stops (-1000 N.mm; -900 ... -1500 alike): the wheel advances
// about two teeth and stands, the anchor rests on its banking at +9 deg and the impulse pin is
// held on the outside of fork horn R (the upper boundary of the right lobe of the
// anchor/balance C-space, docs/simulation.md): the balance, pressed there by its spring, cannot
// re-enter the fork slot.
TEST(SimulationEscapementTorque, StopsOnTheForkHornBeyondTheBand) {
  Model model = escapement(-1000);
  Simulation s = Simulation::create(model);
  Record r = run(s, model, 1.0);
  ASSERT_DOUBLE_EQ(r.t.back(), 1.0);
  double teeth = (r.wheel.front() - r.wheel.back()) / tooth;
  EXPECT_LT(teeth, 3.0);
  EXPECT_GT(teeth, 1.0);
  // the last quarter: nothing moves (the sweep's rest rule would call it stopped)
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] >= 0.75) {
      EXPECT_NEAR(r.wheel[i], r.wheel.back(), 1e-6);
      EXPECT_NEAR(r.balance[i], r.balance.back(), 1e-3);
    }
  EXPECT_NEAR(r.anchor.back(), 9 * std::numbers::pi / 180, 1e-3);
  bool on_horn = false;
  for (const SimulationContact& c : s.contacts())
    for (const std::string& f : c.features) on_horn = on_horn || f.find("fork R outer") != std::string::npos;
  EXPECT_TRUE(on_horn);
}

}  // namespace
}  // namespace hipair
