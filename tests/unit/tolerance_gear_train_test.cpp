// Gear trains as assembly chains (docs/tolerance.md "Gear trains"; session 12): the generated
// trains of tests/unit/gear_train_models.hpp (the C++ form of examples/models/gear-train.py).
//
// Oracles: the examples written by gear-train.py (the generator must give the same model); the
// certified band against Monte Carlo (no sample may leave it) and against exact recomputations
// of the train at random vectors of the tolerance box (the model rebuilt exactly, the train's
// motion recomputed by the exact kinematic engine sliced from the contact kernels).
#include "gear_train_models.hpp"
#include "tolerance_chain_oracle.hpp"

#include "model/parametric/parametric.hpp"
#include "test_paths.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>

namespace hipair {
namespace {

nlohmann::json example(const char* name) {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / name);
  return nlohmann::json::parse(in);
}


TEST(GearTrainModels, GeneratedTrainsAreTheExamples) {
  for (auto [gears, name] : {std::pair(3u, "gear-train-3.json"), std::pair(9u, "gear-train.json")}) {
    SCOPED_TRACE(name);
    nlohmann::json generated = nlohmann::json::parse(test_gears::gear_train(gears));
    nlohmann::json file = example(name);
    EXPECT_EQ(generated["parameters"], file["parameters"]);
    EXPECT_EQ(generated["parts"], file["parts"]);
    EXPECT_EQ(generated["pairs"], file["pairs"]);
  }
}

// Two gears (25 toleranced parameters) over 0..0.3 rad: every Monte Carlo sample inside the
// certified band, and exact recomputations at random vectors inside it where it is bounded.
TEST(ToleranceChainGear, TwoGearTrainKeepsEveryMonteCarloSampleAndExactRecomputationInTheCertifiedBand) {
  std::string text = test_gears::gear_train(2);
  ToleranceOptions options = test_gears::chain_options(Rational(3, 10), 200, 5);
  ToleranceResult result = analyze_tolerances_text(text, options);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  std::size_t held = 0, bounded = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++held;
    if (!std::isfinite(s.certified.upper - s.certified.lower)) continue;
    ++bounded;
  }
  EXPECT_GT(held, 0u);
  RecordProperty("held", static_cast<int>(held));
  RecordProperty("bounded", static_cast<int>(bounded));
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::mt19937 rng(41);
  for (int trial = 0; trial < 2; ++trial) {
    Model exact = model->exact_model(test_gears::random_deviations(result.parameters, rng));
    for (std::size_t k = 0; k < result.samples.size(); k += 4) {
      const VariationSample& s = result.samples[k];
      if (!s.contact || !std::isfinite(s.certified.upper - s.certified.lower)) continue;
      double out = test_chain::chain_output(exact, "gear-A", s.driver, "gear-B", Rational(0), 120);
      EXPECT_GE(out, s.certified.lower - 1e-10) << s.driver;
      EXPECT_LE(out, s.certified.upper + 1e-10) << s.driver;
    }
  }
}

// Three gears (two meshes, 37 parameters; the idler's act on both meshes) over 0..0.2 rad: the
// second mesh's driver ranges over the first mesh's enclosure. The band is bounded wherever both
// meshes hold (session 11: unbounded at most positions of gear-train-3), and no Monte Carlo
// sample leaves it.
TEST(ToleranceChainGear, ThreeGearTrainBandIsBoundedAndKeepsEveryMonteCarloSample) {
  ToleranceOptions options = test_gears::chain_options(Rational(1, 5), 100, 9);
  ToleranceResult result = analyze_tolerances_text(test_gears::gear_train(3), options);
  ASSERT_EQ(result.chain.size(), 2u);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  std::size_t held = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++held;
    EXPECT_TRUE(std::isfinite(s.certified.upper - s.certified.lower)) << s.driver;
    EXPECT_LE(s.certified.lower, s.nominal) << s.driver;
    EXPECT_GE(s.certified.upper, s.nominal) << s.driver;
  }
  EXPECT_GE(held, 3u);
  EXPECT_EQ(result.monte_carlo->evaluations, result.monte_carlo->samples * held);
}

}  // namespace
}  // namespace hipair
