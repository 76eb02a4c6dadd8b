// A mechanism whose output is linear in its parameters: an eccentric circular cam (radius R,
// centre e off its shaft) under a flat-faced follower held down by a force. The follower's
// lift is s = R + e sin(theta) - 30 exactly, so the worst case is tol_R + |sin theta| tol_e and
// the statistical band is mean +- 3 sqrt(sigma_R^2 + sin^2(theta) sigma_e^2): the analysis must
// give these closed forms (to rounding), and its certified band must contain and hug them.
#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace hipair {
namespace {

const char* eccentric_cam = R"({
  "hipair": 1, "name": "eccentric-cam",
  "units": {"length": "mm", "angle": "rad"},
  "parameters": {
    "R": {"nominal": 20, "tolerance": 0.03, "distribution": {"normal": {"sigma": 0.01}}},
    "e": {"nominal": 5, "tolerance": [-0.01, 0.03], "distribution": "uniform"},
    "face": {"nominal": 30}
  },
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": "R"}}]},
    {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}},
     "initial": {"offset": -10},
     "loops": [{"start": [-40, "face"], "edges": [
        {"line_to": [40, "face"], "label": "face"}, {"line_to": [40, "face + 10"]},
        {"line_to": [-40, "face + 10"]}, {"line_to": [-40, "face"]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}
  ],
  "pairs": [{"parts": ["cam", "follower"]}]
})";

TEST(ToleranceLinear, EccentricCamGivesTheClosedFormWorstCaseAndRss) {
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 48;
  options.relative_accuracy = 0.01;
  ToleranceResult result = analyze_tolerances_text(eccentric_cam, options);
  ASSERT_EQ(result.follower, "follower");
  double sigma_r = 0.01, sigma_e = 0.04 / std::sqrt(12.0), mean_e = 0.01;   // uniform on [-0.01, 0.03]
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    double sine = std::sin(s.driver);
    EXPECT_NEAR(s.nominal, 20 + 5 * sine - 30, 1e-9) << "driver " << s.driver;
    // worst case: R in [-0.03, 0.03], e in [-0.01, 0.03] times sin
    double lower = -0.03 + std::min(-0.01 * sine, 0.03 * sine);
    double upper = 0.03 + std::max(-0.01 * sine, 0.03 * sine);
    EXPECT_NEAR(s.linear_lower - s.nominal, lower, 1e-12);
    EXPECT_NEAR(s.linear_upper - s.nominal, upper, 1e-12);
    double mean = mean_e * sine, sigma = std::sqrt(sigma_r * sigma_r + sine * sine * sigma_e * sigma_e);
    EXPECT_NEAR(s.rss_lower - s.nominal, mean - 3 * sigma, 1e-12);
    EXPECT_NEAR(s.rss_upper - s.nominal, mean + 3 * sigma, 1e-12);
    // certified: contains the exact worst case (which is the linear one) and is within 1 %
    EXPECT_LE(s.certified.lower, s.nominal + lower + 1e-12);
    EXPECT_GE(s.certified.upper, s.nominal + upper - 1e-12);
    EXPECT_LE((s.certified.upper - s.certified.lower) - (upper - lower), 0.011 * (upper - lower) + 1e-9);
    ++checked;
  }
  EXPECT_GE(checked, 40u);
  // one contact region: cam circle on the face; R dominates where sin is small
  ASSERT_FALSE(result.regions.empty());
  EXPECT_EQ(result.regions.front().ranked.front().parameter, "R");
  EXPECT_NEAR(result.regions.front().ranked.front().sensitivity, 1.0, 1e-9);
}


// Correlated parameters: the cam's radius "Rc" is derived from "R" (nominal "R + 1") and has its
// own tolerance. The lift is s = R + 1 + dRc + e sin(theta) - 30, so R's variation must reach the
// follower through Rc: sensitivity 1 to both, worst case tol_R + tol_Rc + |sin| tol_e, and a Monte
// Carlo envelope wider than Rc's and e's own variation alone could make it.
TEST(ToleranceLinear, DerivedParameterVariesWithItsExpression) {
  std::string model = eccentric_cam;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::size_t at = model.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    model.replace(at, from.size(), to);
  };
  replace(R"("face": {"nominal": 30})", R"("face": {"nominal": 30}, "Rc": {"nominal": "R + 1", "tolerance": 0.01, "distribution": "uniform"})");
  replace(R"("radius": "R")", R"("radius": "Rc")");
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 24;
  options.monte_carlo = 200;
  options.seed = 3;
  ToleranceResult result = analyze_tolerances_text(model, options);
  std::size_t checked = 0;
  double widest_excess = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    double sine = std::sin(s.driver);
    EXPECT_NEAR(s.nominal, 21 + 5 * sine - 30, 1e-9);
    double lower = -0.03 - 0.01 + std::min(-0.01 * sine, 0.03 * sine);
    double upper = 0.03 + 0.01 + std::max(-0.01 * sine, 0.03 * sine);
    EXPECT_NEAR(s.linear_lower - s.nominal, lower, 1e-12);
    EXPECT_NEAR(s.linear_upper - s.nominal, upper, 1e-12);
    ASSERT_TRUE(s.has_monte_carlo);
    EXPECT_GE(s.monte_carlo_min, s.certified.lower);
    EXPECT_LE(s.monte_carlo_max, s.certified.upper);
    // Without R's variation the lift could move by at most 0.02 + 0.04 |sin| in all.
    widest_excess = std::max(widest_excess, (s.monte_carlo_max - s.monte_carlo_min) - (0.02 + 0.04 * std::fabs(sine)));
    ++checked;
  }
  EXPECT_GE(checked, 20u);
  EXPECT_GT(widest_excess, 0.01);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  ASSERT_FALSE(result.regions.empty());
  for (const ParameterContribution& c : result.regions.front().ranked)
    if (c.parameter == "R" || c.parameter == "Rc") EXPECT_NEAR(c.sensitivity, 1.0, 1e-9) << c.parameter;
}


// The threshold search varies the named parameters only when asked (--vary); each must exist and
// have a tolerance, else one message naming it.
TEST(ToleranceLinear, ThresholdParametersMustBeToleranced) {
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 12;
  options.threshold = true;
  for (const char* name : {"face", "nope"}) {
    options.threshold_parameters = {name};
    try {
      analyze_tolerances_text(eccentric_cam, options);
      ADD_FAILURE() << name << " accepted";
    } catch (const ModelError& error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
    }
  }
  options.threshold_parameters = {"R"};
  ToleranceResult result = analyze_tolerances_text(eccentric_cam, options);
  ASSERT_TRUE(result.threshold.has_value());
  EXPECT_FALSE(result.threshold->found);   // the follower is held by a force: no bounded channel
}

}  // namespace
}  // namespace hipair
