// The plain no-jam search (`hipair tolerance --certify`, without --certify-free-path) over the
// escapement's drops (session 68, escert68; src/tolerance/certificate.cpp, Producer::solve and
// drop_between).
//
// At a drop the tooth leaves the exit impulse face and the anchor's lower side falls from the
// tooth's vertex on that face to the pallet's corner on the wheel's root circle. The plain search
// used to name, over a leaf before the drop, the next piece's sides (the root circle below) with
// a witness midway between the root circle and the upper side: checks 1-6 pass it (they prove
// only the named sides apart), but that witness path runs through the tooth, and check 7 (the
// free follower path, the claim itself) left the certificate `unproven` — the escapement's whole
// turn as well as ranges across one drop. Now the plain search accepts a leaf of a piece next to
// a drop (a side whose nominal value jumps across a piece boundary by more than the channel is
// wide) only when check 7 proves its witness path over the leaf, as --certify-free-path does for
// every leaf; elsewhere (Geneva's continuous lock/drive switch) it is unchanged.
//
// - The old plain choice, kept as tests/data/certificates/escapement-plain-drop-0.3-0.45-base.json
//   (base68's producer, driver 0.3-0.45 rad): `unproven`, and its witness path at the centre of
//   its first leaf lies inside the wheel by the exact overlap predicate; the new plain
//   certificate of that range: `valid`, every leaf witnessed, its witness paths apart by the
//   exact overlap predicate at points and corners of every leaf; its mutations are not valid.
// - Generated (test_seed(68)) ranges across the drop of a random tooth at 1/2, 3/4 or 1 x the
//   tolerances, and (test_seed(6868)) escapements of 14 or 15 teeth (the anchor's distance
//   20 mm / cos(450 deg / N), its pallets 2.5 pitches apart) with the lift or lock moved: plain
//   `valid`, every leaf witnessed. (base68's plain producer, run through its hipair CLI on the
//   same ranges, scales and models: `unproven` at each of the six cases; not asserted here.)
#include <hipair/certificate.hpp>
#include <hipair/overlap.hpp>
#include <hipair/tolerance.hpp>

#include "certificate_test_support.hpp"
#include "rotation_pair_oracle.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"
#include "tolerance_certificate_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string escapement_path() { return (std::filesystem::path(HIPAIR_EXAMPLES) / "escapement.json").string(); }

// The plain search (no free_path_leaves) over [from, to] at `scale` x the tolerances.
ToleranceCertification plain_certificate(const std::string& model_text, const Rational& from, const Rational& to,
                                         const Rational& scale) {
  ToleranceOptions options = test::certify_over(from, to);
  options.certify_scale = scale;
  ToleranceResult result = analyze_tolerances_text(model_text, options);
  if (!result.certification) return {};
  return *result.certification;
}

// How many leaves of a certificate carry no witness path (check 7 cannot start on them).
std::size_t unwitnessed(const Certificate& c) { return test::leaves_without_witness(c).size(); }

// The tangent of half of `angle`, rounded to 1e-12: a rotation by a rational cosine and sine, so
// the exact predicate is evaluated within about 1e-12 rad of the witness pose, not on it (enough
// for `apart` away from contact and for the old witness's `overlapping` deep in the tooth).
Rational half_tangent(const Rational& angle) {
  const double t = std::tan(0.5 * angle.get_d());
  Rational q(mpz_class(static_cast<long>(std::llround(t * 1e12))), mpz_class("1000000000000"));
  q.canonicalize();
  return q;
}

// The exact relation of the wheel and the anchor at a point of `leaf` (every parameter and the
// driver at `pick` of its interval) with the anchor on the leaf's witness path.
PartRelation on_the_witness(const test::RotationPairOracle& oracle, const ToleranceClaim& t, const ToleranceLeaf& leaf,
                            const std::function<Rational(const RationalInterval&)>& pick) {
  const Model& m = oracle.model->nominal();
  std::vector<Rational> deviations(m.parameters.size(), Rational(0));
  Rational y = *leaf.witness, d;
  const std::size_t k = t.varied.size();
  for (std::size_t i = 0; i <= k; ++i) {
    const RationalInterval& span = i < k ? leaf.parameters[i] : leaf.driver;
    const Rational x = pick(span);
    y += leaf.witness_slopes[i] * (x - (span.lo + span.hi) / 2);
    if (i < k)
      deviations[static_cast<std::size_t>(m.find_parameter(t.varied[i]) - m.parameters.data())] = x;
    else
      d = x;
  }
  return oracle.relation(deviations, half_tangent(d), half_tangent(y));
}

TEST(CertifyPlainDrop, TheOldPlainChoiceMeetsTheToothAndTheNewOneIsValidAndFree) {
  const std::string model_text = test::slurp(escapement_path());
  test::RotationPairOracle oracle(escapement_path(), "escape-wheel", "anchor");
  // base68's plain certificate: its first leaf names the root circle below over 0.3-0.408 rad,
  // before the drop; its witness path at the leaf's centre is inside the wheel (the tooth).
  const Certificate old = test::corpus("escapement-plain-drop-0.3-0.45-base.json");
  ASSERT_TRUE(old.tolerance);
  VerificationResult v = check_certificate_text(old, model_text, "escapement.json");
  EXPECT_FALSE(v.valid) << v.summary;
  EXPECT_TRUE(v.unproven) << v.summary << v.reason;
  EXPECT_NE(v.summary.find("'tooth 3 face'"), std::string::npos) << v.summary;
  auto middle = [](const RationalInterval& r) -> Rational { return (r.lo + r.hi) / 2; };
  EXPECT_EQ(on_the_witness(oracle, *old.tolerance, old.tolerance->leaves.at(0), middle), PartRelation::overlapping);

  const ToleranceCertification c = plain_certificate(model_text, Rational(3, 10), Rational(9, 20), Rational(1));
  ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
  EXPECT_FALSE(c.unproven) << c.reason;   // the verifier's code on the written text: valid
  ASSERT_TRUE(c.certificate && c.certificate->tolerance);
  const ToleranceClaim& t = *c.certificate->tolerance;
  EXPECT_EQ(unwitnessed(*c.certificate), 0u);
  // The witness paths against the exact overlap predicate, at the centre and at 8 points
  // (corners and interior points by test_seed(68)) of every leaf.
  std::mt19937_64 random(test::test_seed(68));
  bool corner = false;
  auto somewhere = [&](const RationalInterval& r) -> Rational {
    const long n = corner ? 1000 * std::uniform_int_distribution<long>(0, 1)(random)
                          : std::uniform_int_distribution<long>(0, 1000)(random);
    return r.lo + (r.hi - r.lo) * Rational(n, 1000);
  };
  for (std::size_t i = 0; i < t.leaves.size(); ++i) {
    EXPECT_EQ(on_the_witness(oracle, t, t.leaves[i], middle), PartRelation::apart) << "leaf " << i;
    for (int point = 0; point < 8; ++point) {
      corner = point % 2 == 0;
      EXPECT_EQ(on_the_witness(oracle, t, t.leaves[i], somewhere), PartRelation::apart) << "leaf " << i << " point " << point;
    }
  }

  // Mutations of the new certificate: none is valid.
  auto verdict = [&](const Certificate& m) { return check_certificate_text(m, model_text, "escapement.json"); };
  std::size_t drop = t.leaves.size();   // the leaf holding driver 0.40 rad, where the tooth leaves the face
  for (std::size_t i = 0; i < t.leaves.size(); ++i)
    if (t.leaves[i].driver.lo <= Rational(2, 5) && t.leaves[i].driver.hi > Rational(2, 5)) drop = i;
  ASSERT_LT(drop, t.leaves.size());
  {
    // The old choice's witness in the new leaf over the drop: the anchor 0.1 rad lower, in the tooth.
    Certificate m = *c.certificate;
    *m.tolerance->leaves[drop].witness -= Rational(1, 10);
    EXPECT_FALSE(verdict(m).valid);
  }
  {
    Certificate m = *c.certificate;
    m.tolerance->leaves[drop].witness.reset();
    m.tolerance->leaves[drop].witness_slopes.clear();
    m.tolerance->leaves[drop].witness_margins.clear();
    VerificationResult r = verdict(m);
    EXPECT_FALSE(r.valid) << r.summary;
  }
  {
    Certificate m = *c.certificate;
    m.tolerance->scale = Rational(3, 2);
    EXPECT_FALSE(verdict(m).valid);
  }
  {
    Certificate m = *c.certificate;
    m.tolerance->range.hi = Rational(1, 2);   // past the last leaf: a coverage gap
    VerificationResult r = verdict(m);
    EXPECT_FALSE(r.valid || r.unproven) << r.summary;
  }
  std::cout << "[ plain drop ] 0.3 .. 0.45: " << t.leaves.size() << " leaves (base68: " << old.tolerance->leaves.size()
            << ", unproven)\n";
}

// Ranges of 0.12 or 0.15 rad from 0.30, 0.31 or 0.32 rad + a random tooth x the wheel's period
// (2 pi / 15, a little below), across that tooth's drop (at 0.40 rad + tooth x the period).
TEST(CertifyPlainDrop, GeneratedRangesAcrossTheDropsAreValidWithThePlainSearch) {
  std::mt19937_64 random(test::test_seed(68));
  const std::string model_text = test::slurp(escapement_path());
  const Rational period(41887902, 100000000);
  const Rational scales[] = {Rational(1, 2), Rational(3, 4), Rational(1)};
  for (int trial = 0; trial < 3; ++trial) {
    const int tooth = std::uniform_int_distribution<int>(1, 14)(random);
    const Rational from = Rational(30 + std::uniform_int_distribution<int>(0, 2)(random), 100) + period * tooth;
    const Rational to = from + Rational(std::uniform_int_distribution<int>(0, 1)(random) ? 15 : 12, 100);
    const Rational scale = scales[std::uniform_int_distribution<int>(0, 2)(random)];
    const std::string what = "driver " + std::to_string(from.get_d()) + ":" + std::to_string(to.get_d()) + " rad, scale " +
                             to_exact_string(scale);
    SCOPED_TRACE(what);
    const ToleranceCertification c = plain_certificate(model_text, from, to, scale);
    ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
    ASSERT_TRUE(c.certificate && c.certificate->tolerance);
    EXPECT_EQ(unwitnessed(*c.certificate), 0u);
    EXPECT_FALSE(c.unproven) << c.reason;
    std::cout << "[ plain drop ] " << what << ": " << c.leaves << " leaves, " << c.attempts << " boxes\n";
  }
}

// Escapements of 14 or 15 teeth, the anchor 20 mm / cos(450 deg / N) from the wheel (its
// pallets 2.5 pitches apart, as the file's 23.094 mm for 15), the lift or the lock moved by
// +-1/4 or +-1/2 deg; driver 0.30-0.50 rad, over the first exit drop (0.40 rad for 15 teeth,
// 0.43 for 14), at 1/2 x the tolerances. (16 teeth so drawn jam there: the channel closes at
// 0.39 rad at the box's worst corner.)
TEST(CertifyPlainDrop, GeneratedEscapementGeometriesAreValidWithThePlainSearch) {
  std::mt19937_64 random(test::test_seed(6868));
  const std::string text = test::slurp(escapement_path());
  const char* offsets[] = {"- 0.5", "- 0.25", "+ 0.25", "+ 0.5"};
  std::vector<int> cases(16);   // teeth 14 + (c & 1), the lift when c & 2, offset c >> 2: three distinct
  for (int c = 0; c < 16; ++c) cases[static_cast<std::size_t>(c)] = c;
  std::shuffle(cases.begin(), cases.end(), random);
  for (int trial = 0; trial < 3; ++trial) {
    const int draw = cases[static_cast<std::size_t>(trial)];
    const int teeth = 14 + (draw & 1);
    const bool lift = (draw & 2) != 0;
    const std::string offset = offsets[draw >> 2];
    std::string model = text;
    auto replace = [&](const std::string& from, const std::string& to) {
      const std::size_t at = model.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      model.replace(at, from.size(), to);
    };
    replace("\"wheel-teeth\": { \"nominal\": 15 }", "\"wheel-teeth\": { \"nominal\": " + std::to_string(teeth) + " }");
    char distance[32];
    std::snprintf(distance, sizeof distance, "%.4f", 20 / std::cos(450.0 / teeth * 3.14159265358979323846 / 180));
    replace("\"nominal\": 23.094,", std::string("\"nominal\": ") + distance + ",");
    if (lift)
      replace("\"lift\": { \"nominal\": 6,", "\"lift\": { \"nominal\": \"6 " + offset + "\",");
    else
      replace("\"lock\": { \"nominal\": 2,", "\"lock\": { \"nominal\": \"2 " + offset + "\",");
    const std::string what =
        std::to_string(teeth) + " teeth, " + (lift ? "lift 6 " : "lock 2 ") + offset + " deg";
    SCOPED_TRACE(what);
    const ToleranceCertification c = plain_certificate(model, Rational(3, 10), Rational(1, 2), Rational(1, 2));
    ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
    ASSERT_TRUE(c.certificate && c.certificate->tolerance);
    EXPECT_EQ(unwitnessed(*c.certificate), 0u);
    EXPECT_FALSE(c.unproven) << c.reason;
    std::cout << "[ plain drop ] " << what << ": " << c.leaves << " leaves, " << c.attempts << " boxes\n";
  }
}

}  // namespace
}  // namespace hipair
