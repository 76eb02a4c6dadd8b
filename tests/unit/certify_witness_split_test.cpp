// No-jam tolerance certificates whose every leaf carries a witness path (session 67, escert67).
//
// The producer used to accept a leaf whose two sides checks 1-6 prove apart from their slopes
// alone, without a witness follower path; check 7 (the free follower path, the claim itself)
// cannot start on such a leaf, so the certificate was `unproven` by construction. On the
// escapement (examples/models/escapement.json, the escape wheel driving the anchor) that happens
// at every drop: as the tooth leaves the exit impulse face the anchor's lower side falls from
// the tooth's vertex on that face to the pallet's corner on the wheel's root circle, and over a
// leaf straddling the drop neither pair's witness test passes, while the root circle's side
// (constant in the driver) and the upper side stay apart by their slopes. The producer now
// splits such a leaf along the driver (up to CertifyRequest::witness_splits times on a branch)
// until a witness passes (src/tolerance/certificate.cpp, Producer::solve).
//
// - Over driver [1/5, 9/20] rad (the whole turn's leaf 2 of session 66, 0.218-0.410 rad, and its
//   neighbours): `valid`, every leaf with a witness (before: `unproven`, "leaf 1 has no witness
//   path for the follower").
// - The committed fixture of that range verifies `valid`; its mutations are not: the witness of
//   the leaf over the drop removed (base67's form: `unproven`, "no witness path"), a leaf's driver
//   interval halved, the box widened, the scale raised, a witness moved into the wheel.
// - Generated (test_seed(67)): 0.095 or 0.1 rad across the drop of a random tooth (the wheel's
//   period is 2 pi / 15), the box at 1/2 or 3/4 x the tolerances, with --certify-free-path: every leaf
//   has a witness and the verifier's code (re-checking the written text) says `valid`. (base67's
//   producer, at the seed's three cases: a leaf without a witness in each, `unproven`.)
// - Generated (test_seed(6767)): escapements with the anchor's lift or lock moved by +-1/4 or
//   +-1/2 deg, across the drop of tooth 0: the same (base67: a leaf without a witness in each).
#include <hipair/certificate.hpp>
#include <hipair/tolerance.hpp>

#include "free_path_claim.hpp"
#include "certificate_test_support.hpp"
#include "test_seed.hpp"
#include "tolerance_certificate_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>

namespace hipair {
namespace {

using test::certify_over;

std::filesystem::path escapement() { return test::example_model("escapement.json"); }
std::string read_text(const std::filesystem::path& path) { return test::slurp(path.string()); }

// Every leaf of a certified no_jam certificate carries a witness path; the names of those
// that do not.
std::string leaves_without_witness(const ToleranceCertification& c) {
  std::string out;
  if (!c.certificate || !c.certificate->tolerance) return "no certificate";
  const auto& leaves = c.certificate->tolerance->leaves;
  for (std::size_t i : test::leaves_without_witness(*c.certificate))
    out += (out.empty() ? "" : ", ") + std::to_string(i) + " (driver " + std::to_string(leaves[i].driver.lo.get_d()) +
           " .. " + std::to_string(leaves[i].driver.hi.get_d()) + ")";
  return out;
}

TEST(CertifyWitnessSplit, TheEscapementsDropGetsAWitnessAndTheCertificateIsValid) {
  ToleranceResult result = analyze_tolerances(escapement(), certify_over(Rational(1, 5), Rational(9, 20)));
  ASSERT_TRUE(result.certification);
  const ToleranceCertification& c = *result.certification;
  ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
  EXPECT_EQ(leaves_without_witness(c), "");
  EXPECT_FALSE(c.unproven) << c.reason;   // the verifier's code on the written text
  std::cout << "[ witness split ] driver 0.2 .. 0.45: " << c.leaves << " leaves, " << c.attempts << " boxes\n";
}

TEST(CertifyWitnessSplit, TheEscapementFixtureIsValidAndItsMutationsAreNot) {
  std::filesystem::path fixture =
      std::filesystem::path(HIPAIR_TEST_DATA) / "certificates" / "escapement-tolerance-no-jam-0.2-0.45.json";
  const std::string model_text = read_text(escapement());
  VerificationResult v = verify_certificate_file(fixture, escapement());
  EXPECT_TRUE(v.valid) << v.summary << v.reason;
  EXPECT_FALSE(v.unproven) << v.summary;
  const Certificate base = read_certificate(read_text(fixture));
  ASSERT_TRUE(base.tolerance);
  const auto& leaves = base.tolerance->leaves;
  ASSERT_GE(leaves.size(), 3u);
  // The leaf over the drop (driver 0.40 rad, where the tooth leaves the exit impulse face).
  std::size_t drop = leaves.size();
  for (std::size_t i = 0; i < leaves.size(); ++i)
    if (leaves[i].driver.lo < Rational(2, 5) && leaves[i].driver.hi > Rational(2, 5)) drop = i;
  ASSERT_LT(drop, leaves.size());
  auto check = [&](const Certificate& c) { return check_certificate_text(c, model_text, "escapement.json"); };
  {
    // Base67's form: a leaf without a witness path. Checks 1-6 may pass it; check 7 cannot start.
    Certificate c = base;
    c.tolerance->leaves[drop].witness.reset();
    c.tolerance->leaves[drop].witness_slopes.clear();
    c.tolerance->leaves[drop].witness_margins.clear();
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid) << r.summary;
    if (r.unproven)
      EXPECT_NE(r.summary.find("has no witness path for the follower"), std::string::npos) << r.summary;
  }
  test::expect_box_and_coverage_mutations_rejected(base, drop, check);
  {
    // The witness of the leaf over the drop moved 0.3 rad down: the pallet inside the wheel.
    Certificate c = base;
    *c.tolerance->leaves[drop].witness -= Rational(3, 10);
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid) << r.summary;
  }
}

TEST(CertifyWitnessSplit, GeneratedRangesAcrossTheDropsGetAWitnessOnEveryLeaf) {
  std::mt19937_64 random(test::test_seed(67));
  // The wheel's period 2 pi / 15, as a rational a little below it (the ranges need not be exact).
  const Rational period(41887902, 100000000);
  const Rational scales[] = {Rational(1, 2), Rational(3, 4)};
  for (int trial = 0; trial < 3; ++trial) {
    // 0.095 or 0.1 rad from 0.33 rad + tooth x the period, across the drop of that tooth (at 0.40
    // rad + tooth x the period): base67 left the leaf over the drop without a witness there.
    int tooth = std::uniform_int_distribution<int>(1, 14)(random);
    Rational from = Rational(33, 100) + period * tooth;
    Rational to = from + (std::uniform_int_distribution<int>(0, 1)(random) ? Rational(1, 10) : Rational(95, 1000));
    Rational scale = scales[std::uniform_int_distribution<int>(0, 1)(random)];
    SCOPED_TRACE("trial " + std::to_string(trial) + ": driver " + to_exact_string(from) + " .. " + to_exact_string(to) +
                 " rad, scale " + to_exact_string(scale));
    ToleranceOptions options = certify_over(from, to);
    options.certify_scale = scale;
    options.certify_free_path = true;
    ToleranceResult result = analyze_tolerances(escapement(), options);
    ASSERT_TRUE(result.certification);
    const ToleranceCertification& c = *result.certification;
    ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
    EXPECT_EQ(leaves_without_witness(c), "");
    EXPECT_FALSE(c.unproven) << c.reason;   // the verifier's code on the written text
    std::cout << "[ witness split ] driver " << from.get_d() << " .. " << to.get_d() << ", scale " << scale.get_d() << ": "
              << c.leaves << " leaves, " << c.attempts << " boxes\n";
  }
}

// The same across the drop of tooth 0 (driver 0.33-0.43 rad) of generated escapements: the anchor's
// lift or lock angle moved by -1/2, -1/4, +1/4 or +1/2 deg from its nominal (6 and 2 deg), the box
// at 1/2 x the tolerances, --certify-free-path. base67's producer leaves the leaf over the drop
// without a witness at each of these eight geometries (`unproven`, "leaf 1 has no witness path").
TEST(CertifyWitnessSplit, GeneratedEscapementGeometriesGetAWitnessOnEveryLeaf) {
  std::mt19937_64 random(test::test_seed(6767));
  const std::string text = read_text(escapement());
  const char* offsets[] = {"-0.5", "-0.25", "+0.25", "+0.5"};
  for (int trial = 0; trial < 3; ++trial) {
    bool lift = std::uniform_int_distribution<int>(0, 1)(random) == 1;
    std::string offset = offsets[std::uniform_int_distribution<int>(0, 3)(random)];
    std::string key = lift ? "\"lift\": { \"nominal\": 6," : "\"lock\": { \"nominal\": 2,";
    std::string value = std::string(lift ? "6" : "2") + " " + offset.substr(0, 1) + " " + offset.substr(1);
    std::string replacement = std::string(lift ? "\"lift\"" : "\"lock\"") + ": { \"nominal\": \"" + value + "\",";
    std::string model = text;
    std::size_t at = model.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    model.replace(at, key.size(), replacement);
    SCOPED_TRACE("trial " + std::to_string(trial) + ": " + replacement);
    ToleranceOptions options = certify_over(Rational(33, 100), Rational(43, 100));
    options.certify_scale = Rational(1, 2);
    options.certify_free_path = true;
    ToleranceResult result = analyze_tolerances_text(model, options);
    ASSERT_TRUE(result.certification);
    const ToleranceCertification& c = *result.certification;
    ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
    EXPECT_EQ(leaves_without_witness(c), "");
    EXPECT_FALSE(c.unproven) << c.reason;
    std::cout << "[ witness split ] " << replacement << ": " << c.leaves << " leaves, " << c.attempts << " boxes\n";
  }
}

}  // namespace
}  // namespace hipair
