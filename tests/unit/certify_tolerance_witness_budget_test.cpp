// The no-jam certificate producer's exhausted witness-split budget (session 70, tol70: escert67's
// and escert68's "not done").
//
// A leaf whose sides checks 1-6 prove apart from their slopes alone, without a witness follower
// path, is split (along the driver) instead of accepted, at most CertifyRequest::witness_splits
// times along a branch (session 67); beyond that budget the producer accepts it, and the
// certificate is `unproven` (check 7 cannot start on a leaf without a witness path) and names it.
// No model at hand needs more than 6 such splits, so the budget is lowered through the request's
// ToleranceOptions::certify_witness_splits (session 71; a tests-only global hook in session 70,
// `hipair tolerance --certify-witness-splits N` at the CLI: tests/cli/run_tolerance_witness_budget_tests.sh):
// on the escapement (the wheel driving the
// anchor) every range across a drop needs at least one split there (base67's producer, which
// never split, left the leaf over the drop without a witness at every such range it was run on).
//
// - Driver [1/5, 9/20] rad (the escapement's first drop at 0.40 rad) at budget 0: the producer's
//   outcome is a written certificate, `unproven`, its reason the verifier's "leaf N has no witness
//   path for the follower" for a leaf N that indeed has none; the written file read back and
//   checked by hipair-verify's code (verify_certificate_file) says the same (unproven, not valid;
//   hipair-verify's exit 3), and the text report says "WRITTEN, NOT PROVED" with that reason. At the
//   default budget the same range is `valid` with a witness on every leaf: the budget alone decides.
// - Generated (test_seed(70)): 2 ranges of 0.1 rad from 0.33 rad + a random tooth x 2 pi / 15 (across
//   that tooth's drop), budget 0, the box at 1/2 or 3/4 x the tolerances: the same.
#include <hipair/certificate.hpp>
#include <hipair/tolerance.hpp>

#include "test_seed.hpp"
#include "tolerance_certificate_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test::leaves_without_witness;

std::filesystem::path escapement() { return test::example_model("escapement.json"); }

ToleranceOptions certify_over(const Rational& from, const Rational& to, const Rational& scale, std::size_t splits) {
  ToleranceOptions options = test::certify_over(from, to);
  options.certify_scale = scale;
  options.certify_witness_splits = splits;
  return options;
}

// The leaf a "leaf N has no witness path for the follower" message names; -1 when none.
long named_leaf(const std::string& text) {
  const std::string tail = " has no witness path for the follower";
  std::size_t at = text.find(tail);
  if (at == std::string::npos) return -1;
  std::size_t start = text.rfind("leaf ", at);
  if (start == std::string::npos) return -1;
  return std::strtol(text.c_str() + start + 5, nullptr, 10);
}

// The exhausted path's outcome: a complete certificate, unproven, naming one of its leaves without
// a witness path, on the producer's side, in the written file and in the text report.
void expect_exhausted(const ToleranceResult& result, const std::string& file_name) {
  const ToleranceCertification* certified = test::certified_outcome(result);
  ASSERT_TRUE(certified);
  const ToleranceCertification& c = *certified;
  const std::vector<std::size_t> missing = leaves_without_witness(*c.certificate);
  ASSERT_FALSE(missing.empty()) << "the budget was not exhausted: every leaf has a witness";
  EXPECT_TRUE(c.unproven) << "a leaf without a witness path, yet not unproven";
  const long named = named_leaf(c.reason);
  EXPECT_NE(std::find(missing.begin(), missing.end(), static_cast<std::size_t>(named)), missing.end())
      << "the reason names leaf " << named << ": " << c.reason;
  EXPECT_EQ(c.leaves, c.certificate->tolerance->leaves.size());
  // The certificate as the CLI writes it, read back and checked by hipair-verify's code.
  const std::filesystem::path file = std::filesystem::temp_directory_path() / file_name;
  {
    std::ofstream out(file, std::ios::binary);
    out << write_certificate(*c.certificate);
  }
  const VerificationResult v = verify_certificate_file(file, escapement());
  std::filesystem::remove(file);
  EXPECT_FALSE(v.valid) << v.summary;
  EXPECT_TRUE(v.unproven) << v.summary << " " << v.reason;
  EXPECT_EQ(named_leaf(v.summary), named) << v.summary;
  const std::string report = tolerance_text_report(result);
  EXPECT_NE(report.find("WRITTEN, NOT PROVED: " + std::to_string(c.leaves) + " leaves"), std::string::npos) << report;
  EXPECT_NE(report.find(c.reason), std::string::npos) << report;
  std::cout << "[ witness budget ] " << c.leaves << " leaves, " << missing.size() << " without a witness; " << c.reason
            << "\n";
}

TEST(CertifyToleranceWitnessBudget, TheExhaustedBudgetWritesAnUnprovenCertificateNamingTheLeaf) {
  {
    SCOPED_TRACE("budget 0");
    expect_exhausted(analyze_tolerances(escapement(), certify_over(Rational(1, 5), Rational(9, 20), Rational(1), 0)),
                     "tol70-witness-budget-0.json");
  }
  // The default budget on the same range: valid, a witness on every leaf.
  ToleranceOptions options;
  EXPECT_EQ(options.certify_witness_splits, 6u);
  options = certify_over(Rational(1, 5), Rational(9, 20), Rational(1), options.certify_witness_splits);
  const ToleranceResult result = analyze_tolerances(escapement(), options);
  const ToleranceCertification* c = test::certified_outcome(result);
  ASSERT_TRUE(c);
  EXPECT_TRUE(leaves_without_witness(*c->certificate).empty());
  EXPECT_FALSE(c->unproven) << c->reason;
}

TEST(CertifyToleranceWitnessBudget, GeneratedRangesAcrossDropsExhaustSmallBudgets) {
  std::mt19937_64 random(test::test_seed(70));
  const Rational period(41887902, 100000000);   // a little below 2 pi / 15 (the ranges need not be exact)
  const Rational scales[] = {Rational(1, 2), Rational(3, 4)};
  for (int trial = 0; trial < 2; ++trial) {
    const int tooth = std::uniform_int_distribution<int>(1, 14)(random);
    const Rational from = Rational(33, 100) + period * tooth;
    const Rational to = from + Rational(1, 10);
    const Rational scale = scales[std::uniform_int_distribution<int>(0, 1)(random)];
    const std::size_t budget = 0;
    SCOPED_TRACE("trial " + std::to_string(trial) + ": driver " + to_exact_string(from) + " .. " + to_exact_string(to) +
                 " rad, scale " + to_exact_string(scale) + ", budget " + std::to_string(budget));
    expect_exhausted(analyze_tolerances(escapement(), certify_over(from, to, scale, budget)),
                     "tol70-witness-budget-" + std::to_string(trial) + ".json");
  }
}

}  // namespace
}  // namespace hipair
