// The model's own frequency (`own_frequency`, docs/simulation.md "Stiff inputs"), which `simulate`
// compares with its step budget before a run, against the period the simulator itself integrates:
// generated bars on a torsional spring and on a spring between a point of the bar and the frame
// (tangential, unstretched: small oscillations of stiffness k·r²), oscillating freely well clear
// of a fixed tooth. The measured period (velocity sign changes, interpolated between steps) must
// be 2π/ω.
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

// A bar (inertia I about the origin) with a small initial speed; `spring` is its dynamics' spring
// entry (or empty) and `coupling` the simulation's springs entry (or empty).
std::string bar_model(const std::string& inertia, const std::string& spring, const std::string& coupling) {
  std::ostringstream m;
  m << R"({ "hipair": 1, "name": "spring-bar",
    "parts": [
      { "name": "frame", "motion": "fixed",
        "loops": [ { "start": [40, 20], "edges": [
          { "line_to": [41, 20] }, { "line_to": [41, 30] }, { "line_to": [40, 30] }, { "line_to": [40, 20] } ] } ] },
      { "name": "bar", "motion": { "rotation": { "pivot": [0, 0] } },
        "dynamics": { "moment_of_inertia": )"
    << inertia << (spring.empty() ? "" : ", " + spring) << R"( },
        "loops": [ { "start": [0, -1], "edges": [
          { "line_to": [30, -1] }, { "line_to": [30, 1] }, { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] }
    ],
    "pairs": [ { "parts": ["frame", "bar"] } ],
    "simulation": { "velocities": { "bar": 0.01 }, "accuracy": 1e-10)"
    << (coupling.empty() ? "" : ", \"springs\": [ " + coupling + " ]") << " } }";
  return m.str();
}

// The period of the bar's oscillation: twice the mean interval between the velocity's sign
// changes over `half_periods` of them.
double measured_period(const Model& model, int half_periods) {
  Simulation s = Simulation::create(model);
  std::vector<double> changes;
  double t0 = s.state().time, v0 = s.state().velocity[1];
  while (static_cast<int>(changes.size()) <= half_periods) {
    s.step();
    double t1 = s.state().time, v1 = s.state().velocity[1];
    if ((v0 > 0) != (v1 > 0)) changes.push_back(t0 + (t1 - t0) * v0 / (v0 - v1));
    t0 = t1;
    v0 = v1;
    if (t1 > 1e3) break;
  }
  EXPECT_TRUE(s.events().empty());   // never near the tooth
  if (changes.size() < 2) return 0;
  return 2 * (changes.back() - changes.front()) / static_cast<double>(changes.size() - 1);
}

std::string decimal(std::mt19937_64& rng, int lo, int hi) {
  std::uniform_int_distribution<int> d(lo, hi);
  std::ostringstream s;
  s << d(rng) << "." << std::uniform_int_distribution<int>(100, 999)(rng);
  return s.str();
}

TEST(SimulationOwnFrequency, SpringsPeriodIsTheSimulatedOne) {
  std::mt19937_64 rng(38);
  for (int round = 0; round < 6; ++round) {
    const std::string k = decimal(rng, 0, 40), inertia = decimal(rng, 20, 400);
    const bool torsional = round % 2 == 0;
    std::string model_text;
    double omega_sq = 0;
    if (torsional) {
      model_text = bar_model(inertia, R"("torsional_spring": { "stiffness": )" + k + R"(, "rest": 0 })", "");
      omega_sq = std::stod(k) * 1000 / std::stod(inertia);
    } else {
      // a spring from the bar's point (r, 0) to the frame's point (r, -20), unstretched: tangential
      const std::string r = decimal(rng, 5, 25);
      model_text = bar_model(inertia, "", R"({ "parts": ["bar", "frame"], "points": [[)" + r + R"(, 0], [)" + r +
                                              R"(, -20]], "stiffness": )" + k + R"(, "rest_length": 20 })");
      omega_sq = std::stod(k) * 1000 * std::stod(r) * std::stod(r) / std::stod(inertia);
    }
    SCOPED_TRACE(model_text);
    const Model model = read_model(model_text);
    const OwnFrequency f = own_frequency(model);
    EXPECT_NEAR(f.omega, std::sqrt(omega_sq), 1e-12 * std::sqrt(omega_sq));
    EXPECT_EQ(f.pointer, torsional ? "/parts/1/dynamics/torsional_spring" : "/simulation/springs/0");
    const double period = measured_period(model, 4);
    EXPECT_NEAR(period, 2 * std::numbers::pi / f.omega, 2e-3 * period);
  }
}

// A part with no spring, a driver, or a fixed part: no own frequency (nothing to refuse).
TEST(SimulationOwnFrequency, NoSpringNoFrequency) {
  const Model model = read_model(bar_model("100", "", ""));
  const OwnFrequency f = own_frequency(model);
  EXPECT_EQ(f.omega, 0);
  EXPECT_TRUE(f.pointer.empty());
}

}  // namespace
}  // namespace hipair
