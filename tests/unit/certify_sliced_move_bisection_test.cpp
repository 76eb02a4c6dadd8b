// The verifier's one move bisection (session 72: verify::move_bisection_failure, shared by the
// planar sliced_connected claim's path moves and the pin-slot claim's steps): a move that grazes
// (the parts touch along it, so no piece is ever certainly apart) is refused at the depth limit
// with one reason for both claims, naming the moving coordinate and the piece. Generated: a bar
// on a pin at angle 0 slides (s) or its post slides (q) until the post's lower face lies on the
// bar's upper side; the same contact for a planar bar moved along x. Oracle: the exact overlap
// predicate (part_overlap, the test's own) says touching at the move's end and apart at its start,
// and the move up to just before the contact is certified valid.
#include <hipair/certificate.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced_certificate.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "pin_slot_bar_post.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

namespace hipair {
namespace {

using namespace test::bar_post;

// The rejection's reason (the claim restated for its altered ends).
std::string reason_of(SlicedConnectedCertificate c, const Model& model) {
  c.envelope.statement = sliced_connected_statement(c);
  VerificationResult v = check_sliced_connected(c, model);
  EXPECT_FALSE(v.valid) << "accepted: " << v.summary;
  return v.reason;
}

bool valid(SlicedConnectedCertificate c, const Model& model) {
  c.envelope.statement = sliced_connected_statement(c);
  VerificationResult v = check_sliced_connected(c, model);
  EXPECT_TRUE(v.valid) << v.reason;
  return v.valid;
}

void expect_grazing_reason(const std::string& reason, char letter) {
  EXPECT_NE(reason.find("move 0 ("), std::string::npos) << reason;
  EXPECT_NE(reason.find("not proved free: its pieces reached 2^-"), std::string::npos) << reason;
  EXPECT_NE(reason.find(std::string(" of the move near ") + letter + " in ["), std::string::npos) << reason;
  EXPECT_NE(reason.find("(narrower than the enclosures resolve: the parts come too close, or touch)"), std::string::npos) << reason;
}

TEST(CertifySlicedMoveBisection, GrazingMovesOfPinSlotAndPlanarClaimsAreRefusedWithOneReason) {
  std::mt19937_64 random(test::test_seed(7201));
  for (int trial = 0; trial < 4; ++trial) {
    // the bar (half width w, x in [-10, 10] at s = 0) and a square post of half side r whose lower
    // face is the line y = w, a gap g beyond the bar's tip
    const Rational w = test_numbers::random_rational(random, Rational(1, 2), Rational(3, 4));
    const Rational r = test_numbers::random_rational(random, Rational(1, 4), Rational(1, 2));
    const Rational g = test_numbers::random_rational(random, Rational(1, 10), Rational(9, 10));
    const Rational px = 10 + g + r, py = w + r;
    SCOPED_TRACE("w " + to_exact_string(w) + " r " + to_exact_string(r) + " g " + to_exact_string(g));
    for (Post kind : {Post::fixed, Post::sliding}) {
      const Model model = bar_and_post(px, py, r, w, kind);
      const bool sliding = kind == Post::sliding;
      // a valid certificate of a short move of the claw away from the post (the direct walk)
      SlicedConnectedResult result = certify_pin_slot_connected(model, "post", bar_pose(0, 0), post_position(kind, Rational(0)),
                                                                bar_pose(Rational(-1, 2), 0), post_position(kind, Rational(0)));
      ASSERT_TRUE(result.certificate) << result.failure;
      SlicedConnectedCertificate c = *result.certificate;
      // the move along s (fixed post: the bar out by g + d) or q (sliding post: in by g + d),
      // ending on the post's lower face: touching there (the oracle), apart at the start
      // (d at most (1 - g)/2: within the post's offset limits [-1, 1] and under its face, 2r wide)
      const Rational d = test_numbers::random_rational(random, Rational(1, 5), Rational(1)) * (1 - g) / 2;
      const Rational end = sliding ? Rational(-(g + d)) : Rational(g + d);
      const Rational q_end = sliding ? end : Rational(0), s_end = sliding ? Rational(0) : end;
      EXPECT_EQ(relation_at(model, 0, 0, 0), PartRelation::apart);
      EXPECT_EQ(relation_at(model, q_end, s_end, 0), PartRelation::touching);
      c.steps = {{Rational(0), Rational(0), Rational(0)}, {q_end, s_end, Rational(0)}};
      c.to = bar_pose(s_end, 0);
      if (sliding) c.to_other = post_position(kind, q_end);
      expect_grazing_reason(reason_of(c, model), sliding ? 'q' : 's');
      // up to half the gap: certified
      const Rational half = sliding ? Rational(-g / 2) : Rational(g / 2);
      c.steps[1] = {sliding ? half : Rational(0), sliding ? Rational(0) : half, Rational(0)};
      c.to = bar_pose(c.steps[1][1], 0);
      if (sliding) c.to_other = post_position(kind, half);
      EXPECT_TRUE(valid(c, model));
    }
    // the planar claim: a bar free in the plane (pivot at the origin) moved along x until its tip's
    // upper side runs under the fixed post's lower face (the same reason, named u: the move's
    // parameter)
    const Model planar = read_model(R"({ "hipair": 1, "name": "bar-post-planar", "parts": [
      { "name": "post", "motion": "fixed", "loops": [ )" + rectangle(px - r, py - r, px + r, py + r) + R"( ] },
      { "name": "bar", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + rectangle(-10, -w, 10, w) + R"( ] } ] })");
    SlicedConnectedCertificate p;
    p.envelope.model_name = planar.name;
    p.envelope.first = "post";
    p.envelope.second = "bar";
    p.from = PlanarPose{"bar", 0, 0, 0, false, std::nullopt};
    p.to = PlanarPose{"bar", g + 1, 0, 0, false, std::nullopt};
    p.path = {p.from, p.to};
    expect_grazing_reason(reason_of(p, planar), 'u');
  }
}

}  // namespace
}  // namespace hipair
