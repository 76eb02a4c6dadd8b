// Tolerance analysis of assembly chains (ToleranceOptions::chain; docs/tolerance.md "Assembly
// chains"): driver -> pair 1 -> part -> pair 2 -> ... -> output.
//
// Oracles:
//   - generated lift chains (an eccentric cam under a lifter, each lifter's roller under the next
//     lifter's face, every face on toleranced shims): the output is linear in the parameters,
//     out = e sin(theta) - sum(shims - nominal) + const, so the linearised worst case and the
//     RSS band have closed forms, the certified band must contain the exact range, and every
//     Monte Carlo sample must lie in the certified band;
//   - a two-pair chain equals the composition of the two single-pair analyses;
//   - on the nonlinear cam -> follower -> lever chain (examples/models/cam-follower-lever.json),
//     every composed sensitivity equals central finite differences of exact recomputations (the
//     model rebuilt exactly at p +- h, the whole chain's motion recomputed by the exact
//     kinematic engine).
#include "tolerance_band_check.hpp"
#include "tolerance_chain_models.hpp"
#include "tolerance_chain_oracle.hpp"

#include "model/parametric/parametric.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

namespace hipair {
namespace {

using test_chain::LiftChain;
using test_chain::lift_chain;

// Rounding bound of a sum of `terms` doubles of magnitude at most `scale` (and of the
// distributions' ranges rounded to the nearest doubles): terms x 4 ulp(scale).
double rounding(std::size_t terms, double scale) {
  return 4.0 * static_cast<double>(terms + 1) * std::numeric_limits<double>::epsilon() * scale;
}

TEST(ToleranceChain, LinearLiftChainsGiveTheClosedFormWorstCaseAndRss) {
  std::mt19937 rng(12);
  for (int round = 0; round < 10; ++round) {
    std::size_t pairs = 1 + round % 4, shims = 1 + (round * 7) % 5;
    LiftChain chain = lift_chain(pairs, shims, rng);
    SCOPED_TRACE(std::to_string(pairs) + " pairs, " + std::to_string(shims) + " shims per lifter");
    ToleranceOptions options;
    options.driver = "cam";
    options.chain = true;
    options.positions = 36;
    options.monte_carlo = 30;
    options.threads = 2;
    ToleranceResult result = analyze_tolerances_text(chain.json, options);
    ASSERT_EQ(result.chain.size(), pairs);
    EXPECT_EQ(result.follower, "lifter" + std::to_string(pairs));
    ASSERT_EQ(result.parameters.size(), chain.parameters.size());
    std::size_t checked = 0;
    for (const VariationSample& s : result.samples) {
      if (!s.contact) continue;
      ++checked;
      double lower = 0, upper = 0, mean = 0, variance = 0, scale = std::fabs(s.nominal);
      for (std::size_t i = 0; i < chain.parameters.size(); ++i) {
        const test_chain::ChainParameter& p = chain.parameters[i];
        double sensitivity = p.name == "e" ? std::sin(s.driver) : -1.0;
        ASSERT_EQ(s.sensitivities.size(), chain.parameters.size());
        EXPECT_NEAR(s.sensitivities[i], sensitivity, rounding(8, 1.0)) << p.name;
        lower += std::min(sensitivity * p.lo, sensitivity * p.hi);
        upper += std::max(sensitivity * p.lo, sensitivity * p.hi);
        mean += sensitivity * p.mean;
        variance += sensitivity * sensitivity * p.sigma * p.sigma;
        scale += std::fabs(p.lo) + std::fabs(p.hi);
      }
      double bound = rounding(chain.parameters.size(), scale);
      EXPECT_NEAR(s.linear_lower - s.nominal, lower, bound);
      EXPECT_NEAR(s.linear_upper - s.nominal, upper, bound);
      EXPECT_NEAR(s.rss_lower - s.nominal, mean - 3 * std::sqrt(variance), bound);
      EXPECT_NEAR(s.rss_upper - s.nominal, mean + 3 * std::sqrt(variance), bound);
      // Linear: the exact range over the box is the worst case; the certified band holds it.
      EXPECT_LE(s.certified.lower, s.nominal + lower + bound);
      EXPECT_GE(s.certified.upper, s.nominal + upper - bound);
    }
    EXPECT_GE(checked, 30u);
    EXPECT_EQ(test_band::expect_certified_band_holds(result), checked);
    ASSERT_TRUE(result.monte_carlo);
    EXPECT_EQ(result.monte_carlo->evaluations, 30 * checked);
    // The sensitivity table: every shim -1, ranked by its contribution.
    ASSERT_FALSE(result.regions.empty());
    for (const ParameterContribution& c : result.regions.front().ranked)
      if (c.parameter != "e") EXPECT_NEAR(c.sensitivity, -1.0, rounding(8, 1.0)) << c.parameter;
  }
}

TEST(ToleranceChain, TwoPairChainEqualsTheCompositionOfItsPairs) {
  std::mt19937 rng(5);
  for (int round = 0; round < 3; ++round) {
    LiftChain chain = lift_chain(2, 2 + round, rng);
    ToleranceOptions options;
    options.positions = 36;
    options.threads = 2;
    options.driver = "cam";
    options.follower = "lifter1";
    ToleranceResult first = analyze_tolerances_text(chain.json, options);
    options.driver = "lifter1";
    options.follower = "lifter2";
    ToleranceResult second = analyze_tolerances_text(chain.json, options);
    options.driver = "cam";
    options.follower = "";
    options.chain = true;
    ToleranceResult composed = analyze_tolerances_text(chain.json, options);
    ASSERT_EQ(composed.samples.size(), first.samples.size());
    // The second pair's output moves with its driver one for one (d lifter2 / d lifter1 = 1): its
    // own sensitivities are the same at every position.
    const VariationSample* pair2 = nullptr;
    for (const VariationSample& s : second.samples)
      if (s.contact) pair2 = &s;
    ASSERT_NE(pair2, nullptr);
    std::size_t checked = 0;
    for (std::size_t k = 0; k < composed.samples.size(); ++k) {
      const VariationSample& c = composed.samples[k];
      const VariationSample& f = first.samples[k];
      EXPECT_EQ(c.driver, f.driver);
      if (!c.contact || !f.contact) continue;
      ++checked;
      double bound = rounding(composed.parameters.size(), 1.0 + std::fabs(c.nominal));
      for (std::size_t i = 0; i < composed.parameters.size(); ++i)
        EXPECT_NEAR(c.sensitivities[i], f.sensitivities[i] + pair2->sensitivities[i], bound) << composed.parameters[i].name;
      EXPECT_NEAR(c.linear_upper - c.nominal, (f.linear_upper - f.nominal) + (pair2->linear_upper - pair2->nominal), bound);
      EXPECT_NEAR(c.linear_lower - c.nominal, (f.linear_lower - f.nominal) + (pair2->linear_lower - pair2->nominal), bound);
      // Independent parameters: the variances add.
      double h1 = 0.5 * (f.rss_upper - f.rss_lower), h2 = 0.5 * (pair2->rss_upper - pair2->rss_lower);
      EXPECT_NEAR(0.5 * (c.rss_upper - c.rss_lower), std::sqrt(h1 * h1 + h2 * h2), bound);
    }
    EXPECT_GE(checked, 30u);
  }
}

// Every composed sensitivity of a toleranced parameter at three contact positions equals the
// central difference of exact recomputations of the chain's output. Step h (rational); the
// rebuilds' recorded roundings and the positions' doubles are below 1e-10, so a central
// difference is within h^2 |f'''| / 6 + 2e-10 / h of the derivative; |f'''| <= 6 on these
// chains' scale (mm, rad).
void expect_finite_differences(const std::string& text, const ToleranceResult& result, unsigned steps) {
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  Rational h(1, 10000);
  double bound = h.get_d() * h.get_d() + 2e-10 / h.get_d();
  std::size_t checked = 0, significant = 0;
  for (std::size_t k = 0; k < result.samples.size() && checked < 3; k += 5) {
    const VariationSample& s = result.samples[k];
    if (!s.contact) continue;
    ++checked;
    SCOPED_TRACE("driver " + std::to_string(s.driver));
    for (std::size_t i = 0; i < result.parameters.size(); ++i) {
      if (result.parameters[i].range.lo == result.parameters[i].range.hi) continue;
      SCOPED_TRACE(result.parameters[i].name);
      auto rebuilt = [&](const Rational& delta) {
        std::vector<Rational> d(result.parameters.size(), Rational(0));
        d[i] = delta;
        return test_chain::chain_output(model->exact_model(d), "cam", s.driver, result.follower,
                                        Rational(result.samples.front().driver), steps);
      };
      double difference = (rebuilt(h) - rebuilt(-h)) / (2 * h.get_d());
      EXPECT_NEAR(s.sensitivities[i], difference, bound);
      significant += std::fabs(s.sensitivities[i]) > 100 * bound;
    }
  }
  EXPECT_EQ(checked, 3u);
  EXPECT_GE(significant, 3u) << "the parameters move the output";
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ToleranceChain, ChainSensitivitiesEqualFiniteDifferencesOfExactRecomputations) {
  std::string text = read_text(std::filesystem::path(HIPAIR_EXAMPLES) / "cam-follower-lever.json");
  ToleranceOptions options;
  options.driver = "cam";
  options.chain = true;
  options.positions = 24;
  options.threads = 2;
  ToleranceResult result = analyze_tolerances_text(text, options);
  ASSERT_EQ(result.chain.size(), 2u);
  EXPECT_EQ(result.follower, "lever");
  expect_finite_differences(text, result, 24);
}

// A rotating part inside the chain: cam -> rocker (pivoted, held on the cam by a torque) ->
// lifter (on the rocker's roller). The certified composition converts the rocker's enclosure to
// its half-angle chart: every Monte Carlo sample in the certified band, sensitivities equal
// finite differences of exact recomputations.
TEST(ToleranceChain, RotatingIntermediatePartKeepsEveryMonteCarloSampleAndMatchesFiniteDifferences) {
  std::string text = R"({"hipair": 1, "name": "rocker-chain", "units": {"length": "mm", "angle": "rad"},
  "parameters": {"e": {"nominal": 5, "tolerance": 0.01}, "under": {"nominal": 20, "tolerance": 0.01},
                 "rr": {"nominal": 5, "tolerance": [-0.01, 0.02], "distribution": "uniform"},
                 "face": {"nominal": 40, "tolerance": 0.01}, "py": {"nominal": 23, "tolerance": 0.005}},
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": 20}}]},
    {"name": "rocker", "motion": {"rotation": {"pivot": [60, "py"], "limits": [-0.5, 0.5]}}, "initial": {"angle": 0},
     "loops": [{"start": [-20, "under"], "edges": [{"line_to": [65, "under"]}, {"line_to": [65, 26]}, {"line_to": [-20, 26]},
                {"line_to": [-20, "under"]}]},
               {"circle": {"center": [-10, 32.5], "radius": "rr"}}],
     "dynamics": {"moment_of_inertia": 500, "torque": 20}},
    {"name": "lifter", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}}, "initial": {"offset": -2.5},
     "loops": [{"start": [-30, "face"], "edges": [{"line_to": [10, "face"]}, {"line_to": [10, 50]}, {"line_to": [-30, 50]},
                {"line_to": [-30, "face"]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}],
  "pairs": [{"parts": ["cam", "rocker"]}, {"parts": ["rocker", "lifter"]}]})";
  ToleranceOptions options;
  options.driver = "cam";
  options.chain = true;
  options.positions = 36;
  options.monte_carlo = 40;
  options.threads = 2;
  ToleranceResult result = analyze_tolerances_text(text, options);
  ASSERT_EQ(result.chain.size(), 2u);
  EXPECT_EQ(result.follower, "lifter");
  EXPECT_TRUE(result.chain[0].follower_rotates);
  std::size_t contact = test_band::expect_certified_band_holds(result);
  EXPECT_GE(contact, 30u);
  ASSERT_TRUE(result.monte_carlo);
  EXPECT_EQ(result.monte_carlo->evaluations, 40 * contact);
  expect_finite_differences(text, result, 36);
  // Independently of the composition: the exact chain (the model rebuilt exactly at random
  // vectors of the box, its motion recomputed by the kernel-sliced engine) lies in the certified
  // band, up to the positions' doubles (1e-10, as above).
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> u(0, 1000);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<Rational> d(result.parameters.size(), Rational(0));
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Parameter& p = result.parameters[i];
      d[i] = p.range.lo - p.nominal + Rational(u(rng), 1000) * (p.range.hi - p.range.lo);
    }
    Model exact = model->exact_model(d);
    for (std::size_t k : {std::size_t{2}, std::size_t{13}, std::size_t{27}}) {
      const VariationSample& s = result.samples[k];
      ASSERT_TRUE(s.contact);
      double out = test_chain::chain_output(exact, "cam", s.driver, "lifter", Rational(result.samples.front().driver), 36);
      EXPECT_GE(out, s.certified.lower - 1e-10) << s.driver;
      EXPECT_LE(out, s.certified.upper + 1e-10) << s.driver;
    }
  }
}

TEST(ToleranceChain, RefusesWhatItDoesNotAnalyse) {
  std::mt19937 rng(1);
  LiftChain chain = lift_chain(2, 1, rng);
  ToleranceOptions options;
  options.chain = true;
  options.threshold = true;
  EXPECT_THROW(analyze_tolerances_text(chain.json, options), ModelError);
  options.threshold = false;
  options.follower = "nowhere";
  EXPECT_THROW(analyze_tolerances_text(chain.json, options), ModelError);
  options.follower = "";
  options.driver = "nowhere";
  EXPECT_THROW(analyze_tolerances_text(chain.json, options), ModelError);
}

}  // namespace
}  // namespace hipair
