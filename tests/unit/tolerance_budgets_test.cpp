// Session 72 (tol72): the budgets that bound a tolerance result, as options and in tolerance.json.
//
// - ToleranceOptions::chain_failure_boxes (`--chain-split-budget`): where a chain's composition
//   over the whole tolerance box cannot be certified at a position, the box is bisected into at
//   most this many sub-boxes there (session 42's split, a constant 4 until session 72). Any
//   partition of the box is sound; a larger budget is not proved to bound more positions (the
//   budget changes which later passes run: review72 M6), so "every band bounded with budget 1
//   stays bounded and no wider with 4" below is a check of this window, not a property. On
//   gear-train.json over 0..0.53 rad at 120 per turn the default budget bisects the box at 3
//   positions; with a budget of 1 sub-box (no split) none is bisected (the later passes' far walks
//   bound them instead, with other bands). Both runs' bands hold the exact train (the model
//   rebuilt exactly at generated vectors and at the extreme corners of the positions whose band
//   the budget changed, its kinematics recomputed by the exact engine over the same range and
//   grid; each exact position allowed the rounding of the exact root to a double, 4 ulps:
//   test_band::visit_exact_values, session 73 — was a constant 1e-10 rad), the default's every
//   Monte Carlo value.
// - ToleranceResult::budgets, tolerance.json's `budgets`: the accuracy, a chain's sub-box budgets
//   and a certificate's leaf and witness-split budgets, as used (generated values).
#include "gear_train_models.hpp"
#include "test_paths.hpp"
#include "tolerance_band_check.hpp"
#include "test_seed.hpp"
#include "tolerance_certificate_support.hpp"

#include "model/parametric/parametric.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string example_text(const char* name) {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using test_band::bounded;

TEST(ToleranceBudgets, TheChainSplitBudgetTakesEffectAndEveryBandHoldsTheExactTrain) {
  const std::uint64_t seed = test::test_seed(72);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  const std::string text = example_text("gear-train.json");
  const std::pair<Rational, Rational> range(Rational(0), Rational(53, 100));
  ToleranceOptions options = test_gears::chain_options(range.second, 24, static_cast<unsigned>(seed % 100000));
  options.chain_failure_boxes = 1;
  ToleranceResult small = analyze_tolerances_text(text, options);
  options.chain_failure_boxes = 4;
  ToleranceResult large = analyze_tolerances_text(text, options);
  ASSERT_EQ(small.samples.size(), large.samples.size());
  std::size_t held = 0, bounded_small = 0, bounded_large = 0;
  for (std::size_t i = 0; i < large.samples.size(); ++i) {
    const VariationSample &a = small.samples[i], &b = large.samples[i];
    ASSERT_EQ(a.contact, b.contact);
    if (!b.contact) continue;
    ++held;
    bounded_small += bounded(a);
    bounded_large += bounded(b);
    if (bounded(a)) {   // bounded with the smaller budget: bounded, and inside that band, with the larger
      EXPECT_TRUE(bounded(b)) << "driver " << b.driver;
      EXPECT_GE(b.certified.lower, a.certified.lower) << "driver " << b.driver;
      EXPECT_LE(b.certified.upper, a.certified.upper) << "driver " << b.driver;
    }
  }
  EXPECT_EQ(held, 10u);
  EXPECT_EQ(bounded_large, held);
  EXPECT_LE(small.chain_budget_exhausted, held - bounded_small);
  EXPECT_EQ(large.chain_budget_exhausted, 0u);
  // The budget takes effect: with 1 sub-box no position's box is bisected for a failed composition
  // (those positions are bounded by the later passes' far walks instead, or not at all); with 4
  // some are (base72: the budget a constant 4, both runs bisect).
  auto bisected = [](const ToleranceResult& r) {
    bool said = false;
    for (const std::string& note : r.notes) said = said || note.find("bounded by bisecting the tolerance box") != std::string::npos;
    return said;
  };
  EXPECT_FALSE(bisected(small));
  EXPECT_TRUE(bisected(large));
  ASSERT_TRUE(large.monte_carlo.has_value());
  EXPECT_EQ(large.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(large.monte_carlo->not_certified, 0u);

  // The exact train, inside both runs' bands, at generated vectors of the box and at the corners
  // the linearisation moves furthest at the positions whose band the budget changed.
  std::vector<std::vector<Rational>> vectors;
  std::size_t changed = 0;
  for (std::size_t i = 0; i < large.samples.size(); ++i) {
    const VariationSample &a = small.samples[i], &b = large.samples[i];
    if (!b.contact || (bounded(a) && a.certified.lower == b.certified.lower && a.certified.upper == b.certified.upper))
      continue;
    ++changed;
    for (int way : {1, -1}) vectors.push_back(test_gears::linearised_corner(b, large.parameters, way));
  }
  EXPECT_GE(changed, 1u);
  std::mt19937 rng(static_cast<std::mt19937::result_type>(seed));
  for (int k = 0; k < 2; ++k) vectors.push_back(test_gears::random_deviations(large.parameters, rng));
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  for (std::size_t v = 0; v < vectors.size(); ++v) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = 120;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult exact = analyze_kinematics(model->exact_model(vectors[v]), k);
    for (const ToleranceResult* r : {&small, &large}) {
      const char* budget = r == &small ? "budget 1" : "budget 4";
      // the allowance: the exact engine's position is the exact root rounded to a double (review72 M4)
      test_band::visit_exact_values(exact, "gear-I", r->samples, [&](std::size_t i, double out, double ulp) {
        const VariationSample& sample = r->samples[i];
        ++checked;
        EXPECT_GE(out, sample.certified.lower - ulp) << budget << ", driver " << sample.driver << " vector " << v;
        EXPECT_LE(out, sample.certified.upper + ulp) << budget << ", driver " << sample.driver << " vector " << v;
      });
    }
  }
  EXPECT_EQ(checked, vectors.size() * (bounded_small + bounded_large));

  // tolerance.json records the budget each run used and the positions that exhausted it
  for (const ToleranceResult* r : {&small, &large}) {
    nlohmann::json j = nlohmann::json::parse(tolerance_json_report(*r));
    ASSERT_TRUE(j.contains("budgets"));
    EXPECT_EQ(j["budgets"]["chain_failure_boxes"].get<long>(), r == &small ? 1 : 4);
    EXPECT_EQ(j["budgets"]["chain_shared_boxes"].get<long>(), 128);
    EXPECT_EQ(j["budgets"]["chain_budget_exhausted_positions"].get<std::size_t>(), r->chain_budget_exhausted);
    EXPECT_EQ(j["budgets"]["monte_carlo_samples"].get<long>(), 24);
    EXPECT_FALSE(j["budgets"].contains("certify_witness_splits"));
  }
}

TEST(ToleranceBudgets, GeneratedCertificateBudgetsAreRecordedInToleranceJson) {
  const std::uint64_t seed = test::test_seed(72);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  for (int round = 0; round < 2; ++round) {
    ToleranceOptions options = test::certify_over(Rational(1, 5), Rational(9, 20));
    options.certify_witness_splits = static_cast<std::size_t>(random() % 9);
    options.certify_max_leaves = 1000 + static_cast<std::size_t>(random() % 20000);
    options.relative_accuracy = 0.25 + 0.25 * static_cast<double>(random() % 4);
    ToleranceResult r = analyze_tolerances(test::example_model("escapement.json"), options);
    ASSERT_TRUE(r.certification.has_value());
    nlohmann::json j = nlohmann::json::parse(tolerance_json_report(r));
    ASSERT_TRUE(j.contains("budgets"));
    const nlohmann::json& b = j["budgets"];
    EXPECT_EQ(b["certify_witness_splits"].get<std::size_t>(), options.certify_witness_splits);
    EXPECT_EQ(b["certify_max_leaves"].get<std::size_t>(), options.certify_max_leaves);
    ASSERT_TRUE(b["certify_free_path"].is_boolean());
    EXPECT_FALSE(b["certify_free_path"].get<bool>());
    // one JSON type per key whatever the value: an accuracy of 1.0 is a number with a fraction
    EXPECT_TRUE(b["relative_accuracy"].is_number_float());
    EXPECT_TRUE(b["absolute_accuracy"].is_number_float());
    EXPECT_TRUE(b["certify_max_leaves"].is_number_integer());
    EXPECT_EQ(b["relative_accuracy"].get<double>(), options.relative_accuracy);
    EXPECT_EQ(b["absolute_accuracy"].get<double>(), options.absolute_accuracy);
    EXPECT_FALSE(b.contains("chain_failure_boxes"));   // a pair, not a chain
    EXPECT_EQ(j["certificate"]["leaves"].get<std::size_t>(), r.certification->leaves);
  }
}

}  // namespace
}  // namespace hipair
