// A parameter shared by two pairs of an assembly chain (docs/tolerance.md "Assembly chains",
// the certified band): cam -> lifter1 -> lifter2, where one dimension d both raises lifter1's
// face (lifter1 sits d lower on the cam) and its roller within lifter1 (d higher): lifter2's
// position is out = e sin(theta) - f1, independent of d. Composing the pairs' enclosures
// independently counts d twice (|-1| + |+1| times its range); the chain bisects the box along d
// until the band is within the requested accuracy of the direct computation's exact range,
// e sin(theta) -+ (0.01 |sin(theta)| + 0.005) (linear in e and f1, so that range is exact).
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace hipair {
namespace {

const char* const kSharedChain = R"({"hipair": 1, "name": "shared-chain", "units": {"length": "mm", "angle": "rad"},
  "parameters": {"e": {"nominal": 5, "tolerance": 0.01}, "d": {"nominal": 0, "tolerance": 0.005},
                 "f1": {"nominal": 0, "tolerance": 0.005}},
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": 20}}]},
    {"name": "lifter1", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}}, "initial": {"offset": 0},
     "loops": [{"start": [-30, "20 + d + f1"], "edges": [{"line_to": [30, "20 + d + f1"]}, {"line_to": [30, 30]},
                {"line_to": [-30, 30]}, {"line_to": [-30, "20 + d + f1"]}]},
               {"circle": {"center": [0, "40 + d"], "radius": 5}}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}},
    {"name": "lifter2", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}}, "initial": {"offset": 0},
     "loops": [{"start": [-30, 45], "edges": [{"line_to": [30, 45]}, {"line_to": [30, 60]}, {"line_to": [-30, 60]},
                {"line_to": [-30, 45]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}],
  "pairs": [{"parts": ["cam", "lifter1"]}, {"parts": ["lifter1", "lifter2"]}]})";

// mean_value false: the interval composition alone (session 11's shared-parameter bisection,
// which these first two tests are about); the mean-value composition (session 22, the default)
// keeps d's effect through both pairs without it (the third test).
ToleranceResult analyse(double relative_accuracy, bool mean_value = false) {
  ToleranceOptions options;
  options.mean_value_chain = mean_value;
  options.driver = "cam";
  options.chain = true;
  options.positions = 36;
  options.threads = 2;
  options.relative_accuracy = relative_accuracy;
  return analyze_tolerances_text(kSharedChain, options);
}

// The direct computation's half-width at driver theta (exact: out is linear in e and f1).
double exact_half_width(double theta) { return 0.01 * std::fabs(std::sin(theta)) + 0.005; }

TEST(ToleranceChainShared, SharedParameterGetsTheBandOfTheDirectComputation) {
  ToleranceResult result = analyse(0.1);
  ASSERT_EQ(result.chain.size(), 2u);
  std::size_t d = 0;
  while (result.parameters[d].name != "d") ++d;
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++checked;
    SCOPED_TRACE("driver " + std::to_string(s.driver));
    double nominal = 5 * std::sin(s.driver), half = exact_half_width(s.driver);
    // positions are doubles and the box is rounded outwards: 1e-10 mm
    EXPECT_NEAR(s.nominal, nominal, 1e-10);
    EXPECT_NEAR(s.sensitivities[d], 0.0, 1e-9);   // d cancels to first order too
    EXPECT_LE(s.certified.lower, nominal - half + 1e-10);
    EXPECT_GE(s.certified.upper, nominal + half - 1e-10);
    // within the requested accuracy (10 % of the linearised width, + 1e-9) of the exact range
    EXPECT_LE(s.certified.upper - s.certified.lower, 1.1 * 2 * half + 1e-9 + 1e-10);
  }
  EXPECT_GE(checked, 30u);
  bool noted = false;
  for (const std::string& note : result.notes) noted = noted || note.find("several pairs") != std::string::npos;
  EXPECT_TRUE(noted);
}

// The control: when one composition over the whole box is accepted (accuracy 1000 %), the pairs'
// enclosures compose independently and d enters twice: the band is 2 x 2 x 0.005 wider than the
// exact range — what the bisection above removes.
TEST(ToleranceChainShared, WithoutBisectionTheSharedParameterCountsTwice) {
  ToleranceResult result = analyse(10.0);
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++checked;
    EXPECT_GE(s.certified.upper - s.certified.lower, 2 * exact_half_width(s.driver) + 0.0195) << s.driver;
  }
  EXPECT_GE(checked, 30u);
}

// The mean-value composition (default since session 22) over the whole box in one composition
// (accuracy 1000 %: no bisection): d's effects on the two pairs cancel through the chain rule,
// so the band holds the exact range and is within 10 % of it (+ 1e-9), where the interval
// composition above is 2 x 2 x 0.005 wider.
TEST(ToleranceChainShared, MeanValueCompositionCancelsTheSharedParameterWithoutBisection) {
  ToleranceResult result = analyse(10.0, true);
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++checked;
    SCOPED_TRACE("driver " + std::to_string(s.driver));
    double nominal = 5 * std::sin(s.driver), half = exact_half_width(s.driver);
    EXPECT_LE(s.certified.lower, nominal - half + 1e-10);
    EXPECT_GE(s.certified.upper, nominal + half - 1e-10);
    EXPECT_LE(s.certified.upper - s.certified.lower, 1.1 * 2 * half + 1e-9 + 1e-10);
  }
  EXPECT_GE(checked, 30u);
  for (const std::string& note : result.notes) EXPECT_EQ(note.find("several pairs"), std::string::npos) << note;
}

}  // namespace
}  // namespace hipair
