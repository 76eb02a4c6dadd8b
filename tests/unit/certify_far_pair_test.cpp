// The verifier's verdict on a clearance (planar too), jam or free-passage certificate does not
// depend on where the mechanism is drawn (issue 13): every such certificate of the corpus
// (tests/data/certificates: the valid ones and their mutations) is checked against its model and
// against the model with every point and turning pivot moved by a random far vector,
// (±10^k + a, ±10^k + b) for k = 30, 100, 400 (a, b random dyadic rationals): the same verdict,
// and a rejection for the same reason (the corpus's expected substring). These claims hold no
// world point (angles, offsets, planar x and y, a distance, edge references), so a translate of
// the model is the same claim.
//
// Before session 49 (scale49) the verifier posed a far pair where it lies: at 10^100 mm its
// 256-bit enclosures are about 10^23 mm wide, and every far jam was rejected ("the ends of the
// piece are not certainly on opposite sides of the other edge's line"), so analyze reported the
// ratchet's jam + 10^100 and + 10^400 not certified. Now a pair far from the origin for its size
// is checked moved to it (certify/check.cpp, pair_moved_to_origin).
#include "core/model_scale.hpp"
#include "io/atomic_file.hpp"
#include "test_paths.hpp"

#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace hipair {
namespace {

struct FarPairEntry {
  std::string certificate, model, expected;
};

// The corpus's entries (the claim kind is tested once the certificate is read), but the spur
// gears' (their free passage takes seconds per check).
std::vector<FarPairEntry> far_pair_entries() {
  std::ifstream list(std::filesystem::path(HIPAIR_TEST_DATA) / "certificates" / "EXPECTED.txt");
  std::vector<FarPairEntry> entries;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    for (std::size_t start = 0;;) {
      std::size_t bar = line.find('|', start);
      std::string field = line.substr(start, bar == std::string::npos ? std::string::npos : bar - start);
      field.erase(0, field.find_first_not_of(' '));
      field.erase(field.find_last_not_of(' ') + 1);
      fields.push_back(field);
      if (bar == std::string::npos) break;
      start = bar + 1;
    }
    if (fields.size() != 4 || fields[1].find("spur-gears") != std::string::npos) continue;
    entries.push_back(FarPairEntry{fields[0], fields[1], fields[2]});
  }
  return entries;
}

Rational far_pair_power10(unsigned exponent) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, exponent);
  return Rational(p);
}

TEST(CertifyFarPair, VerdictsOnClearanceJamAndFreePassageAreTheSameFarFromTheOrigin) {
  std::mt19937_64 random(49);
  // a dyadic offset (an integer up to 10^5 over 2^0 ... 2^10): a claim exactly at its limit (the
  // lever's clearance of 2 mm is the parts' distance) is decided by enclosures that are exact on
  // the model's dyadic coordinates; moved by a third, the moved copy's 256-bit enclosures give a
  // bound 2 - 10^-76 and reject it (the verifier's rule: an inconclusive enclosure rejects)
  auto random_rational = [&] {
    Rational r(static_cast<long>(random() % 200001) - 100000, 1L << (random() % 11));
    r.canonicalize();
    return r;
  };
  std::size_t checked = 0, valid = 0, rejected = 0;
  for (const FarPairEntry& entry : far_pair_entries()) {
    Certificate certificate;
    try {
      certificate = read_certificate(io::read_file(std::filesystem::path(HIPAIR_TEST_DATA) / "certificates" / entry.certificate));
    } catch (const Error&) {
      continue;   // a malformed mutation: rejected by the reader, wherever the model is
    }
    if (certificate.claim != ClaimKind::clearance && certificate.claim != ClaimKind::jam &&
        certificate.claim != ClaimKind::free_passage && certificate.claim != ClaimKind::planar_clearance)
      continue;
    Model model = read_model_file(std::filesystem::path(HIPAIR_SOURCE_DIR) / entry.model);
    VerificationResult at_origin = check_certificate(certificate, model);
    if (!at_origin.valid && at_origin.reason.find("rounding") != std::string::npos &&
        entry.expected.find("rounding") == std::string::npos)
      continue;   // a stale snapshot (certify_corpus_test.cpp says when)
    const bool expected_found = at_origin.reason.find(entry.expected) != std::string::npos;
    for (unsigned k : {30u, 100u, 400u}) {
      Rational sx = random() % 2 ? Rational(1) : Rational(-1), sy = random() % 2 ? Rational(1) : Rational(-1);
      Point by{sx * far_pair_power10(k) + random_rational(), sy * far_pair_power10(k) + random_rational()};
      Model far = translated_model(model, by);
      VerificationResult result = check_certificate(certificate, far);
      std::string what = entry.certificate + " moved by ~10^" + std::to_string(k);
      EXPECT_EQ(result.valid, at_origin.valid) << what << ": " << result.reason << " / at the origin: " << at_origin.reason;
      if (!at_origin.valid)
        EXPECT_EQ(result.reason.find(entry.expected) != std::string::npos, expected_found)
            << what << ": " << result.reason << " / at the origin: " << at_origin.reason;
      else
        EXPECT_EQ(result.summary, at_origin.summary) << what;
      ++checked;
      valid += result.valid;
      rejected += !result.valid;
    }
  }
  // 9 certificates valid at every k (the lever's clearance, free passage and jam, the ratchet's
  // jam, the cam follower's free passage, the peg's and the film advance's two planar
  // clearances, and m07, whose changed hash only the file check sees) and 35 mutations rejected
  EXPECT_GE(valid, 9u * 3u);
  EXPECT_GE(rejected, 35u * 3u);
  std::cout << "[ far pair ] " << checked << " far checks: " << valid << " valid, " << rejected << " rejected\n";
}

// The certificate's text without the model's identity (name, file, content hash).
std::string far_pair_claim_text(Certificate certificate) {
  certificate.content_hash.clear();
  certificate.model_file.clear();
  certificate.model_name.clear();
  return write_certificate(certificate);
}

// The producer certifies a far pair's clearance, free passage and jam as at the origin: the lever
// against its stop (clearance at the initial configuration, free passage over [0, 0.04] rad, the
// jam driving forward) and the ratchet's jam driving backward, each moved by (±10^k + a, ±10^k + b),
// k = 30, 100, 400: the same certificate but for the model's identity, valid on the far model.
// Before session 49 (scale49) the producer searched on the far model's enclosures: `hipair
// certify` refused the lever's clearance and jam + 10^100 ("cannot certify").
TEST(CertifyFarPair, CertificatesOfAFarPairAreTheOnesAtTheOriginAndVerifyThere) {
  namespace fs = std::filesystem;
  std::mt19937_64 random(4901);
  const Model lever = read_model_file(fs::path(HIPAIR_EXAMPLES) / "lever-stop.json");
  const Model ratchet = read_model_file(fs::path(HIPAIR_EXAMPLES) / "ratchet.json");
  using Produce = std::function<std::optional<Certificate>(const Model&)>;
  const std::vector<std::tuple<std::string, const Model*, Produce>> claims{
      {"lever clearance", &lever,
       [](const Model& m) {
         std::map<std::string, ExactPosition> at{{"lever", ExactPosition{Rational(0)}}};
         return certify_clearance(m, "lever", "stop", at, std::nullopt);
       }},
      {"lever free passage", &lever,
       [](const Model& m) {
         return certify_free_passage(m, "lever", "stop", PassagePath{"lever", "", {Rational(0), Rational(1, 25)}, {}},
                                     std::nullopt);
       }},
      {"lever jam", &lever,
       [](const Model& m) -> std::optional<Certificate> {
         auto query = find_jam(m, "lever", "stop", "lever", 0, 0, +1, Rational(1, 500), Rational(2));
         return query ? certify_jam(m, "lever", "stop", *query) : std::nullopt;
       }},
      {"ratchet jam", &ratchet, [](const Model& m) -> std::optional<Certificate> {
         auto query = find_jam(m, "wheel", "pawl", "wheel", 0, 0, -1, Rational(1, 500), Rational(1));
         return query ? certify_jam(m, "wheel", "pawl", *query) : std::nullopt;
       }}};
  std::size_t compared = 0;
  for (const auto& [what, model, produce] : claims) {
    std::optional<Certificate> expected = produce(*model);
    ASSERT_TRUE(expected) << what;
    for (unsigned k : {30u, 100u, 400u}) {
      Rational sx = random() % 2 ? Rational(1) : Rational(-1), sy = random() % 2 ? Rational(1) : Rational(-1);
      Point by{sx * far_pair_power10(k) + Rational(static_cast<long>(random() % 2001) - 1000, 8),
               sy * far_pair_power10(k) + Rational(static_cast<long>(random() % 2001) - 1000, 16)};
      Model far = translated_model(*model, by);
      std::string where = what + " moved by ~10^" + std::to_string(k);
      std::optional<Certificate> got = produce(far);
      if (!got) {
        ADD_FAILURE() << where << ": not certified";
        continue;
      }
      EXPECT_EQ(far_pair_claim_text(*got), far_pair_claim_text(*expected)) << where;
      VerificationResult check = check_certificate(*got, far);
      EXPECT_TRUE(check.valid) << where << ": " << check.reason;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 12u);
}

}  // namespace
}  // namespace hipair
