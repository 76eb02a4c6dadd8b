// sliced_connected certificates of pin-in-slot pairs (session 71, <hipair/sliced_certificate.hpp>):
// the steps (q, s, u) of a bar on a pin against a post, each move proved free by hipair-verify's
// own check. A bar without its tail turns the other way round past a fixed post (the other side
// of CertifyApartPinSlot's walled turn, now certified); a turning and a sliding post (3-D).
// Oracle: the exact overlap predicate (part_overlap, the tests' own) at every step and at random
// exact configurations along every move. Mutations: generated (a step moved to a configuration
// the oracle finds not apart is rejected) and each of the format's checks with its reason.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced_apart.hpp>
#include <hipair/sliced_certificate.hpp>

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <random>
#include <string>

#include "pin_slot_bar_post.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

namespace hipair {
namespace {

using namespace test::bar_post;

SlicedConnectedCertificate round_trip(const SlicedConnectedCertificate& c) {
  return read_sliced_connected_certificate(write_sliced_connected_certificate(c));
}

// Every step apart, and `samples` random exact configurations of every move (one coordinate
// between its ends') apart, by the exact oracle.
void expect_steps_apart(const SlicedConnectedCertificate& c, const Model& model, std::mt19937_64& random, int samples) {
  for (std::size_t i = 0; i < c.steps.size(); ++i) {
    const auto& p = c.steps[i];
    EXPECT_EQ(relation_at(model, p[0], p[1], p[2]), PartRelation::apart) << "step " << i;
    if (i + 1 == c.steps.size()) continue;
    const auto& q = c.steps[i + 1];
    // (u = 3 to u = -1, or back, at one s and q: one configuration, not a move)
    if (p[0] == q[0] && p[1] == q[1] && ((p[2] == 3 && q[2] == -1) || (p[2] == -1 && q[2] == 3))) continue;
    for (int k = 0; k < samples; ++k) {
      const Rational f = test_numbers::random_rational(random, Rational(0), Rational(1), 1009);
      Rational at[3];
      for (int axis = 0; axis < 3; ++axis) at[axis] = p[axis] + f * (q[axis] - p[axis]);
      EXPECT_EQ(relation_at(model, at[0], at[1], at[2]), PartRelation::apart) << "move " << i << " at " << f;
    }
  }
}

void expect_connected_rejected(const SlicedConnectedCertificate& c, const Model& model, const std::string& reason, bool restate = true) {
  SlicedConnectedCertificate m = c;
  if (restate) m.envelope.statement = sliced_connected_statement(m);
  VerificationResult v = check_sliced_connected(m, model);
  EXPECT_FALSE(v.valid) << "accepted; expected a rejection holding '" << reason << "'";
  EXPECT_NE(v.reason.find(reason), std::string::npos) << v.reason;
}

TEST(CertifyConnectedPinSlot, GeneratedShortBarsTurnTheOtherWayRoundPastAFixedPost) {
  std::mt19937_64 random(test::test_seed(7101));
  for (int trial = 0; trial < 4; ++trial) {
    // the post at 42 to 48 degrees, 4.7 to 6.4 mm from the pin (CertifyApartPinSlot's); the bar's
    // tail 1/4 to 1 mm long: it turns the other way round (-90, -180, -270 = 90 degrees)
    const Rational px = test_numbers::random_rational(random, Rational(7, 2), Rational(9, 2));
    const Rational py = px * test_numbers::random_rational(random, Rational(9, 10), Rational(11, 10));
    const Rational r = test_numbers::random_rational(random, Rational(1, 2), Rational(3, 4));
    const Rational w = test_numbers::random_rational(random, Rational(1, 2), Rational(3, 4));
    const Rational tail = -test_numbers::random_rational(random, Rational(1, 4), Rational(1));
    const Model model = bar_and_post(px, py, r, w, Post::fixed, tail);
    const Rational slide = test_numbers::random_rational(random, Rational(-1), Rational(1));
    const PlanarPose a = bar_pose(slide, 0), b = bar_pose(-slide, 1);
    SlicedConnectedResult result = certify_pin_slot_connected(model, "post", a, std::nullopt, b, std::nullopt);
    ASSERT_TRUE(result.certificate) << "post (" << px << ", " << py << ") r " << r << " w " << w << " tail " << tail << ": " << result.failure;
    const SlicedConnectedCertificate c = round_trip(*result.certificate);
    ASSERT_TRUE(c.pin_slot);
    VerificationResult v = check_sliced_connected(c, model);
    ASSERT_TRUE(v.valid) << v.reason;
    EXPECT_EQ(c.envelope.statement, "Part 'bar' moves from s=" + to_exact_string(slide) + ", t=0 to s=" + to_exact_string(Rational(-slide)) +
                                        ", t=1 without touching part 'post'.");
    expect_steps_apart(c, model, random, 4);
    // the steps pass u = -1 / 3 (the other way round): the direct quarter turn is walled
    bool seam = false;
    for (std::size_t i = 0; i + 1 < c.steps.size(); ++i) seam = seam || (c.steps[i][2] == 3 && c.steps[i + 1][2] == -1) || (c.steps[i][2] == -1 && c.steps[i + 1][2] == 3);
    EXPECT_TRUE(seam);
    // the walled bar (its tail reaching 10 mm): the same steps are invalid, no path is certified,
    // and its separation is (sliced_apart)
    const Model walled = bar_and_post(px, py, r, w, Post::fixed);
    EXPECT_FALSE(check_sliced_connected(c, walled).valid);
    if (trial == 0) {
      SlicedConnectedResult none = certify_pin_slot_connected(walled, "post", a, std::nullopt, b, std::nullopt, {}, 3000);
      EXPECT_FALSE(none.certificate) << "the walled bar certified connected";
      SlicedApartResult apart = certify_pin_slot_apart(walled, "post", a, std::nullopt, b, std::nullopt, {}, 20000);
      EXPECT_TRUE(apart.certificate) << apart.failure;
    }
  }
}

TEST(CertifyConnectedPinSlot, ATurningAndASlidingPostLetTheShortBarTurn) {
  // 3-D: the post turning about its own centre or sliding within [-1, 1] (one kind per run, by
  // the seed's parity), the short bar from 0 to 90 degrees with the post moving too
  const unsigned seed = test::test_seed(7102);
  std::mt19937_64 random(seed);
  for (Post kind : {seed % 2 ? Post::turning : Post::sliding}) {
    const Model model = bar_and_post(4, 4, Rational(1), Rational(3, 4), kind, Rational(-1, 2));
    const PlanarPose a = bar_pose(0, 0), b = bar_pose(1, 1);
    const Rational qa = kind == Post::turning ? Rational(1, 3) : Rational(-1, 2), qb = kind == Post::turning ? Rational(5, 2) : Rational(1);
    SlicedConnectedResult result = certify_pin_slot_connected(model, "post", a, post_position(kind, qa), b, post_position(kind, qb));
    ASSERT_TRUE(result.certificate) << result.failure;
    const SlicedConnectedCertificate c = round_trip(*result.certificate);
    VerificationResult v = check_sliced_connected(c, model);
    ASSERT_TRUE(v.valid) << v.reason;
    expect_steps_apart(c, model, random, 3);
    if (kind == Post::sliding) {
      SlicedConnectedCertificate m = c;
      m.steps.insert(m.steps.begin() + 1, {Rational(2), m.steps[0][1], m.steps[0][2]});   // the post beyond its limits and back
      m.steps.insert(m.steps.begin() + 2, m.steps[0]);
      expect_connected_rejected(m, model, "the offset of 'post' (q in [");
    }
    SlicedConnectedCertificate m = c;
    m.from_other.reset();
    m.to_other.reset();
    expect_connected_rejected(m, model, "the ends give no position of the moving part 'post'");
  }
}

TEST(CertifyConnectedPinSlot, MutatedCertificatesAreRejected) {
  std::mt19937_64 random(test::test_seed(7103));
  const Model model = bar_and_post(4, Rational(21, 5), Rational(3, 4), Rational(1, 2), Post::fixed, Rational(-1, 2));
  SlicedConnectedResult result = certify_pin_slot_connected(model, "post", bar_pose(0, 0), std::nullopt, bar_pose(0, 1), std::nullopt);
  ASSERT_TRUE(result.certificate) << result.failure;
  const SlicedConnectedCertificate c = round_trip(*result.certificate);
  ASSERT_TRUE(check_sliced_connected(c, model).valid);
  ASSERT_GE(c.steps.size(), 3u);
  // generated: a detour from a step along s or u to a random configuration and back (the moves
  // stay one coordinate each): rejected when the exact oracle finds the detour's end not apart
  int rejected = 0, kept = 0;
  for (int k = 0; k < 40; ++k) {
    SlicedConnectedCertificate m = c;
    const std::size_t i = std::size_t(random() % m.steps.size());
    const int axis = 1 + int(random() % 2);
    std::array<Rational, 3> away = m.steps[i];
    away[axis] = axis == 1 ? test_numbers::random_rational(random, Rational(-2), Rational(2))
                           : test_numbers::random_rational(random, Rational(-1), Rational(3));
    m.steps.insert(m.steps.begin() + long(i) + 1, {away, m.steps[i]});
    bool blocked = relation_at(model, away[0], away[1], away[2]) != PartRelation::apart;
    for (int j = 1; j < 8 && !blocked; ++j) {   // the detour's configurations at j/8 of it
      std::array<Rational, 3> at = m.steps[i];
      at[axis] += Rational(j, 8) * (away[axis] - at[axis]);
      blocked = relation_at(model, at[0], at[1], at[2]) != PartRelation::apart;
    }
    if (!blocked) {
      // (the detour may be free: then the verifier's verdict is checked against the oracle)
      if (check_sliced_connected(m, model).valid) ++kept, expect_steps_apart(m, model, random, 4);
      continue;
    }
    ++rejected;
    expect_connected_rejected(m, model, "move " + std::to_string(i));
  }
  EXPECT_GT(rejected, 0) << "no generated mutation reached a blocked configuration";
  // each of the format's checks
  SlicedConnectedCertificate m = c;
  for (auto& step : m.steps) step[0] = 1;   // q of a fixed post
  expect_connected_rejected(m, model, "for the fixed part 'post' (it is 0)");
  m = c;
  m.steps.insert(m.steps.begin() + 1, {Rational(0), Rational(1, 2), Rational(1, 4)});   // s and u at once
  expect_connected_rejected(m, model, "it changes two coordinates at once");
  m = c;
  m.steps.front()[1] = Rational(1, 3);
  expect_connected_rejected(m, model, "the steps start at");
  m = c;
  m.steps.back()[2] = Rational(1, 2);
  expect_connected_rejected(m, model, "the steps end at");
  m = c;
  m.steps.insert(m.steps.begin() + 1, {Rational(0), Rational(3), Rational(0)});   // beyond the slide's limits and back
  m.steps.insert(m.steps.begin() + 2, m.steps[0]);
  expect_connected_rejected(m, model, "the slide of 'bar' (s in [0, 3]) leaves its limits");
  m = c;
  m.steps.assign(1, c.steps.front());
  expect_connected_rejected(m, model, "the steps end at");
  m = c;
  m.steps.clear();
  expect_connected_rejected(m, model, "the steps have no configuration");
  m = c;
  m.from_other = m.to_other = ExactPosition{Rational(0), false, false, {}, {}};
  expect_connected_rejected(m, model, "part 'post' is fixed: the ends give no position of it");
  m = c;
  m.to = bar_pose(3, 1);
  expect_connected_rejected(m, model, "the end to: the slide of 'bar' (3) is outside its limits");
  m = c;
  m.envelope.statement = "Part 'bar' moves.";
  expect_connected_rejected(m, model, "the statement does not say", false);
  m = c;
  m.path.push_back(PlanarPose{"bar", 0, 0, 0, false, std::nullopt});
  expect_connected_rejected(m, model, "not a path of planar poses");
  // the reader: a pin-slot claim's witness is its steps
  std::string text = write_sliced_connected_certificate(c);
  const std::size_t at = text.find("\"steps\"");
  ASSERT_NE(at, std::string::npos);
  EXPECT_THROW(read_sliced_connected_certificate(std::string(text).replace(at, 7, "\"path\"")), ModelError);
  std::string one_other = text;
  one_other.insert(one_other.find("\"steps\""), "\"from_other\": {\"offset\": \"0\"},\n    ");
  EXPECT_THROW(read_sliced_connected_certificate(one_other), ModelError);
}

}  // namespace
}  // namespace hipair
