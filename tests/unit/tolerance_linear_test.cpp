// A mechanism whose output is linear in its parameters: an eccentric circular cam (radius R,
// centre e off its shaft) under a flat-faced follower held down by a force. The follower's
// lift is s = R + e sin(theta) - 30 exactly, so the worst case is tol_R + |sin theta| tol_e and
// the statistical band is mean +- 3 sqrt(sigma_R^2 + sin^2(theta) sigma_e^2): the analysis must
// give these closed forms (to rounding), and its certified band must contain and hug them.
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace hipair
