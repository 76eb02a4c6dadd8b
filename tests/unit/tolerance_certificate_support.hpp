// Shared by the no-jam tolerance-certificate tests (certify_tolerance_test.cpp,
// certify_witness_split_test.cpp, certify_tolerance_witness_budget_test.cpp,
// certify_plain_drop_test.cpp, tolerance_threshold_bracket_test.cpp; session 71): an example model's
// path, the options certifying over a driver range, the leaves without a witness path, the
// certified outcome's checks every test started with, and a mutated certificate's rejection.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair::test {

/// examples/models/NAME
inline std::filesystem::path example_model(const std::string& name) {
  return std::filesystem::path(HIPAIR_EXAMPLES) / name;
}

/// A no-jam certificate over driver [from, to] at the declared tolerances, one thread; the
/// certified band coarse (relative accuracy 0.5: not what the certificate tests test).
inline ToleranceOptions certify_over(const Rational& from, const Rational& to) {
  ToleranceOptions options;
  options.range = std::make_pair(from, to);
  options.threads = 1;
  options.relative_accuracy = 0.5;
  options.certify = true;
  return options;
}

/// The indices of a no_jam certificate's leaves that carry no witness follower path.
inline std::vector<std::size_t> leaves_without_witness(const Certificate& c) {
  std::vector<std::size_t> out;
  if (!c.tolerance) return out;
  for (std::size_t i = 0; i < c.tolerance->leaves.size(); ++i)
    if (!c.tolerance->leaves[i].witness) out.push_back(i);
  return out;
}

/// `result`'s certification when its outcome is `certified` with a written tolerance certificate;
/// otherwise nullptr, the failure recorded with the outcome and its reason (the test then stops
/// at `ASSERT_TRUE` on the pointer).
inline const ToleranceCertification* certified_outcome(const ToleranceResult& result) {
  if (!result.certification) {
    ADD_FAILURE() << "no certification in the result";
    return nullptr;
  }
  const ToleranceCertification& c = *result.certification;
  if (c.outcome != ToleranceCertification::Outcome::certified) {
    ADD_FAILURE() << "not certified (outcome " << static_cast<int>(c.outcome) << "): " << c.reason;
    return nullptr;
  }
  if (!c.certificate || !c.certificate->tolerance) {
    ADD_FAILURE() << "certified without a tolerance certificate: " << c.reason;
    return nullptr;
  }
  return &c;
}

/// `c` written, read back and checked against `model_text` (the file `model_name`) by the
/// verifier's code: invalid (neither valid nor unproven), its reason containing `reason`.
inline void expect_rejected(const Certificate& c, const std::string& model_text, const std::string& model_name,
                            const std::string& reason, const std::string& what) {
  VerificationResult v = check_certificate_text(read_certificate(write_certificate(c)), model_text, model_name);
  EXPECT_FALSE(v.valid) << what;
  EXPECT_FALSE(v.unproven) << what;
  EXPECT_NE(v.reason.find(reason), std::string::npos) << what << ": " << v.reason;
}

}  // namespace hipair::test
