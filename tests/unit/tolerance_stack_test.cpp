// A 100-parameter tolerance chain on one pair (examples/models/cam-shim-stack.json and its
// generated smaller versions): an eccentric cam (e = 5 +- 0.01) under a flat follower whose face
// sits on n - 1 shims of 0.2 +- 0.002 mm. The lift is s = 20 + e sin(theta) - face - sum(shims -
// 0.2): linear, so the worst case is exactly (n - 1) 0.002 + 0.01 |sin theta| and every shim's
// sensitivity is -1.
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace hipair {
namespace {

std::string stack(int n) {
  std::string params = R"("e": {"nominal": 5, "tolerance": 0.01}, "face": {"nominal": 30})";
  std::string sum;
  for (int i = 1; i < n; ++i) {
    params += ", \"shim" + std::to_string(i) + R"(": {"nominal": "1/5", "tolerance": 0.002})";
    sum += (i > 1 ? " + shim" : "shim") + std::to_string(i);
  }
  std::string face = "face + (" + sum + ") - " + std::to_string(n - 1) + "/5";
  return R"({"hipair": 1, "name": "stack", "units": {"length": "mm", "angle": "rad"}, "parameters": {)" + params +
         R"(}, "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": 20}}]},
    {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}}, "initial": {"offset": -10},
     "loops": [{"start": [-40, ")" + face + R"("], "edges": [{"line_to": [40, ")" + face + R"("]},
       {"line_to": [40, ")" + face + R"( + 10"]}, {"line_to": [-40, ")" + face + R"( + 10"]}, {"line_to": [-40, ")" + face + R"("]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}],
  "pairs": [{"parts": ["cam", "follower"]}]})";
}

TEST(ToleranceStack, HundredParameterChainGivesTheClosedForm) {
  for (int n : {10, 100}) {
    ToleranceOptions options;
    options.driver = "cam";
    options.positions = 36;
    options.monte_carlo = 50;
    options.threads = 2;
    ToleranceResult result = analyze_tolerances_text(stack(n), options);
    ASSERT_EQ(result.parameters.size(), static_cast<std::size_t>(n + 1));   // e, face, n - 1 shims
    std::size_t checked = 0;
    for (const VariationSample& s : result.samples) {
      if (!s.contact) continue;
      double half = (n - 1) * 0.002 + 0.01 * std::fabs(std::sin(s.driver));
      EXPECT_NEAR(s.linear_upper - s.nominal, half, 1e-12) << n << " " << s.driver;
      EXPECT_NEAR(s.nominal - s.linear_lower, half, 1e-12) << n << " " << s.driver;
      EXPECT_LE(s.certified.lower, s.nominal - half + 1e-12);
      EXPECT_GE(s.certified.upper, s.nominal + half - 1e-12);
      ++checked;
    }
    EXPECT_GE(checked, 30u);
    for (const ParameterContribution& c : result.regions.front().ranked)
      if (c.parameter.rfind("shim", 0) == 0) EXPECT_NEAR(c.sensitivity, -1.0, 1e-12) << c.parameter;
    ASSERT_TRUE(result.monte_carlo);
    EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
    EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  }
}

}  // namespace
}  // namespace hipair
