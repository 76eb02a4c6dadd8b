// The verifier's motion-limit tests on exact values are exact (session 50, exact50b): an offset
// or a jam trap's driver span ending exactly on a limit that is not a dyadic rational (1/3 mm)
// is within the limits, a hair beyond it is not. Until then exact_map and check_jam compared
// outward-rounded enclosures of both rationals, which overlap when they are equal, and refused
// true claims the producer had accepted exactly (`hipair certify --claim interference --at
// slider=1/3` exited 3: "the certificate produced does not pass its own check").
// Generated: limits p/q (q odd, so never dyadic), a slider certified at each limit, and a jam
// whose trap spans the whole limits; oracle: the exact comparison with the limits.
#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace {

using namespace hipair;

std::string exact(const Rational& q) { return "\"" + to_exact_string(q) + "\""; }

// A fixed wall x in [2, 3] and a 2 x 1 slider (x in [-1, 1], y in [1, 2]) translating along x
// within [lo, hi].
Model slide_model(const Rational& lo, const Rational& hi) {
  std::string text = R"({ "hipair": 1, "name": "slide-limit", "units": { "length": "mm", "angle": "rad" }, "parts": [
    { "name": "wall", "motion": "fixed", "loops": [ { "start": [2, 0], "edges": [
      { "line_to": [3, 0] }, { "line_to": [3, 10] }, { "line_to": [2, 10] }, { "line_to": [2, 0] } ] } ] },
    { "name": "slider", "motion": { "translation": { "direction": [1, 0], "limits": [)" +
                     exact(lo) + ", " + exact(hi) + R"(] } }, "loops": [ { "start": [-1, 1], "edges": [
      { "line_to": [1, 1] }, { "line_to": [1, 2] }, { "line_to": [-1, 2] }, { "line_to": [-1, 1] } ] } ] } ] })";
  return read_model(text);
}

Certificate base_certificate(const Model& model, ClaimKind claim) {
  Certificate c;
  c.claim = claim;
  c.model_name = model.name;
  c.first = "wall";
  c.second = "slider";
  return c;
}

// The slider at offset s overlaps the wall: the witness point (5/2 + s/10, 3/2) lies in both for
// s in [1.7, 3] (limits below).
VerificationResult interference_at(const Model& model, const Rational& s) {
  Certificate c = base_certificate(model, ClaimKind::interference);
  c.configuration["slider"] = ExactPosition{s, true, false, {}, {}};
  c.witness_point = Point{Rational(Rational(5, 2) + s / 10), Rational(3, 2)};
  c.statement = certificate_statement(c, model);
  return check_certificate(c, model);
}

// Driving the slider forward from within [lo, hi], it cannot pass hi: its bottom edge crosses
// the wall's left side there (the piece [u - 1/8, u + 1/8] of the edge around its crossing u =
// (3 - hi) / 2), and at lo it is apart from the wall.
VerificationResult jam_over(const Model& model, const Rational& lo, const Rational& hi) {
  Certificate c = base_certificate(model, ClaimKind::jam);
  c.driver = "slider";
  c.direction = 1;
  c.trap = ConfigurationBox{RationalInterval{lo, hi}, std::nullopt};
  c.start = JamStart{lo, std::nullopt};
  Rational u = (3 - hi) / 2;
  c.cut.push_back(BlockedPiece{RationalInterval{Rational(0), Rational(0)},
                               CrossingWitness{EdgeReference{"slider", 0, 0, ""}, EdgeReference{"wall", 0, 3, ""},
                                               RationalInterval{Rational(u - Rational(1, 8)), Rational(u + Rational(1, 8))}}});
  c.statement = certificate_statement(c, model);
  return check_certificate(c, model);
}

TEST(CertifyExactLimits, OffsetsAndTrapSpansOnNonDyadicLimits) {
  std::mt19937 random(50);
  const Rational hair = Rational(1, 1) / Rational(mpz_class("1000000000000000000000000000000000000000"));   // 10^-39
  for (int trial = 0; trial < 12; ++trial) {
    // lo in (0, 1), hi in (1.7, 2.3), denominators odd (3 .. 99): never dyadic
    long q = 3 + 2 * long(random() % 49), r = 3 + 2 * long(random() % 49);
    Rational lo(1 + long(random() % (q - 1)), q), hi(Rational(17, 10) + Rational(1 + long(random() % (6 * r / 10)), r));
    lo.canonicalize();
    hi.canonicalize();
    Model model = slide_model(lo, hi);
    SCOPED_TRACE("limits [" + to_exact_string(lo) + ", " + to_exact_string(hi) + "]");
    // on the upper limit: a configuration (exactly as the producer decides it)
    VerificationResult at_limit = interference_at(model, hi);
    EXPECT_TRUE(at_limit.valid) << at_limit.reason;
    // a hair beyond it: not a configuration
    VerificationResult beyond = interference_at(model, hi + hair);
    EXPECT_FALSE(beyond.valid);
    EXPECT_NE(beyond.reason.find("outside its limits"), std::string::npos) << beyond.reason;
    // a trap spanning the whole limits
    VerificationResult jam = jam_over(model, lo, hi);
    EXPECT_TRUE(jam.valid) << jam.reason;
    VerificationResult wider = jam_over(model, lo - hair, hi);
    EXPECT_FALSE(wider.valid);
    EXPECT_NE(wider.reason.find("outside the driver's limits"), std::string::npos) << wider.reason;
  }
}

}  // namespace
