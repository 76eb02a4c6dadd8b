// sliced_apart certificates of pin-in-slot pairs (session 70, <hipair/sliced_apart.hpp>): a bar on
// a pin at the origin, sliding along itself by s in [-2, 2], cannot turn from 0 to 90 degrees past
// a post at about 45 degrees: its tip and its tail (the bar spans [-10, 10]) both meet the post,
// so the turn is walled on both sides. The post fixed (2-D: s, u), turning about its own centre
// (3-D: its angle, s, u) or sliding along x within [-1, 1] (3-D). Oracles: the exact overlap
// predicate at every blocked leaf's middle and at random exact poses inside blocked leaves, the
// ends apart; the other side: without the tail the bar turns the other way round (certified since
// session 71: a sliced_connected certificate, its steps apart by the exact oracle) and no apart
// certificate is produced, and the certificate of the walled bar is invalid for it. Mutated certificates rejected with their reasons. The format's work limits:
// a tree of more leaves or halvings than it states is refused before any proof is checked.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced_apart.hpp>
#include <hipair/sliced_certificate.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <optional>
#include <random>
#include <string>

#include "pin_slot_bar_post.hpp"
#include "random_rationals.hpp"
#include "sliced_apart_support.hpp"
#include "sliced_peg_in_hole.hpp"
#include "test_seed.hpp"

namespace hipair {
namespace {

using namespace test::bar_post;

// Every blocked leaf's middle and `samples` random exact poses of it overlap (the exact oracle);
// returns the number of blocked leaves.
std::size_t check_blocked_leaves(const SlicedApartCertificate& c, const Model& model, std::mt19937_64& random, int samples) {
  std::size_t blocked = 0;
  EXPECT_TRUE(test::walk_apart_tree(c, [&](const test::ApartLeaf& b) {
    if (!b.blocked) return;
    ++blocked;
    EXPECT_EQ(relation_at(model, (b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2), PartRelation::overlapping)
        << "blocked leaf " << blocked;
    for (int k = 0; k < samples; ++k) {
      Rational at[3];
      for (int axis = 0; axis < 3; ++axis)
        at[axis] = b.lo[axis] == b.hi[axis] ? b.lo[axis] : test_numbers::random_rational(random, b.lo[axis], b.hi[axis], 1009);
      EXPECT_EQ(relation_at(model, at[0], at[1], at[2]), PartRelation::overlapping) << "blocked leaf " << blocked << " sample " << k;
    }
  }));
  return blocked;
}

using test::expect_apart_rejected;

TEST(CertifyApartPinSlot, GeneratedBarsCannotTurnPastAFixedPost) {
  std::mt19937_64 random(test::test_seed(7001));
  for (int trial = 0; trial < 3; ++trial) {
    // the post at 42 to 48 degrees, 4.7 to 6.4 mm from the pin; post and bar 1 to 1.5 mm wide
    const Rational px = test_numbers::random_rational(random, Rational(7, 2), Rational(9, 2));
    const Rational py = px * test_numbers::random_rational(random, Rational(9, 10), Rational(11, 10));
    const Rational r = test_numbers::random_rational(random, Rational(1, 2), Rational(3, 4));
    const Rational w = test_numbers::random_rational(random, Rational(1, 2), Rational(3, 4));
    const Model model = bar_and_post(px, py, r, w, Post::fixed);
    const Rational slide = test_numbers::random_rational(random, Rational(-2), Rational(2));
    const PlanarPose a = bar_pose(slide, 0), b = bar_pose(-slide, 1);   // 0 and 90 degrees
    SlicedApartResult result = certify_pin_slot_apart(model, "post", a, std::nullopt, b, std::nullopt, {}, 20000);
    ASSERT_TRUE(result.certificate) << "post (" << px << ", " << py << ") r " << r << " w " << w << ": " << result.failure;
    const SlicedApartCertificate c = read_sliced_apart_certificate(write_sliced_apart_certificate(*result.certificate));
    ASSERT_TRUE(c.pin_slot);
    VerificationResult v = check_sliced_apart(c, model);
    ASSERT_TRUE(v.valid) << v.reason;
    EXPECT_EQ(c.envelope.statement, "Part 'bar' cannot move from s=" + to_exact_string(slide) + ", t=0 to s=" +
                                        to_exact_string(Rational(-slide)) + ", t=1 without touching part 'post'.");
    EXPECT_EQ(relation_at(model, 0, slide, 0), PartRelation::apart);
    EXPECT_EQ(relation_at(model, 0, -slide, 1), PartRelation::apart);
    EXPECT_EQ(check_blocked_leaves(c, model, random, 2), c.proofs.size());
    // the other side: without its tail the bar turns the other way round (-90, -180, -270 =
    // 90 degrees), certified (session 71: sliced_connected's steps, checked by the verifier and
    // by the exact oracle at each step); no apart certificate, and the walled bar's is invalid for it
    const Model short_bar = bar_and_post(px, py, r, w, Post::fixed, Rational(-1, 2));
    SlicedConnectedResult turns = certify_pin_slot_connected(short_bar, "post", bar_pose(0, 0), std::nullopt, bar_pose(0, 1), std::nullopt);
    ASSERT_TRUE(turns.certificate) << turns.failure;
    EXPECT_TRUE(check_sliced_connected(*turns.certificate, short_bar).valid);
    for (const auto& step : turns.certificate->steps) EXPECT_EQ(relation_at(short_bar, step[0], step[1], step[2]), PartRelation::apart);
    EXPECT_FALSE(check_sliced_apart(c, short_bar).valid);
    SlicedApartResult around = certify_pin_slot_apart(short_bar, "post", bar_pose(0, 0), std::nullopt, bar_pose(0, 1), std::nullopt, {}, 3000);
    EXPECT_FALSE(around.certificate) << "the short bar certified apart";
  }
}

TEST(CertifyApartPinSlot, ATurningAndASlidingPostWallTheTurnAtEveryPosition) {
  // the post turning about its own centre (its angle the full turn) or sliding within [-1, 1]: the
  // bar at 45 degrees passes through the post's centre region at every position
  // (one kind per run, by the seed's parity: each is a 3-D search of tens of seconds)
  const unsigned seed = test::test_seed(7002);
  std::mt19937_64 random(seed);
  for (Post kind : {seed % 2 ? Post::turning : Post::sliding}) {
    const Model model = bar_and_post(4, 4, Rational(1), Rational(3, 4), kind);
    const PlanarPose a = bar_pose(0, 0), b = bar_pose(1, 1);
    const Rational qa = kind == Post::turning ? Rational(1, 3) : Rational(-1, 2), qb = kind == Post::turning ? Rational(5, 2) : Rational(1);
    SlicedApartResult result = certify_pin_slot_apart(model, "post", a, post_position(kind, qa), b, post_position(kind, qb), {}, 20000);
    ASSERT_TRUE(result.certificate) << result.failure;
    const SlicedApartCertificate c = read_sliced_apart_certificate(write_sliced_apart_certificate(*result.certificate));
    VerificationResult v = check_sliced_apart(c, model);
    ASSERT_TRUE(v.valid) << v.reason;
    EXPECT_EQ(c.other_full_turn, kind == Post::turning);
    EXPECT_EQ(check_blocked_leaves(c, model, random, 1), c.proofs.size());
    // the other part's positions are part of the claim
    SlicedApartCertificate m = c;
    m.a_other.reset();
    expect_apart_rejected(m, model, "");
    if (kind == Post::sliding) {
      m = c;
      m.a_other->value = 3;   // beyond the post's limits
      expect_apart_rejected(m, model, "the end a: the offset of 'post' is outside its limits");
      // the offset's faces need no wall only where they are the post's limits
      m = c;
      m.x = RationalInterval{Rational(-1, 2), Rational(3, 2)};
      EXPECT_FALSE(check_sliced_apart([&] { m.envelope.statement = sliced_apart_statement(m); return m; }(), model).valid);
    }
  }
}

TEST(CertifyApartPinSlot, MutatedCertificatesAreRejected) {
  const Model model = bar_and_post(4, Rational(21, 5), Rational(3, 4), Rational(1, 2), Post::fixed);
  SlicedApartResult result = certify_pin_slot_apart(model, "post", bar_pose(0, 0), std::nullopt, bar_pose(0, 1), std::nullopt);
  ASSERT_TRUE(result.certificate) << result.failure;
  const SlicedApartCertificate c = read_sliced_apart_certificate(write_sliced_apart_certificate(*result.certificate));
  ASSERT_TRUE(check_sliced_apart(c, model).valid);
  SlicedApartCertificate m = c;
  m.b = bar_pose(0, Rational(1, 50));   // a few degrees from a: one component
  expect_apart_rejected(m, model, "a and b lie in one component");
  m = c;
  m.y = RationalInterval{Rational(-1), Rational(2)};   // the slide's lower face inside the limits: walls needed there
  expect_apart_rejected(m, model, "");
  m = c;
  m.b = bar_pose(3, 1);   // beyond the slide's limits
  expect_apart_rejected(m, model, "the end b: the slide of 'bar' (3) is outside its limits");
  m = c;
  m.tree = "q" + c.tree;   // the fixed post has no coordinate to halve
  expect_apart_rejected(m, model, "halves q, an axis of one value");
  m = c;
  m.tree[0] = 'x';
  expect_apart_rejected(m, model, "is not q, s, u, o or b");
  m = c;
  for (SlicedApartProof& p : m.proofs)
    if (p.kind == SlicedApartProof::Kind::cross) {
      p.along = RationalInterval{Rational(0), Rational(1, 1000000)};
      break;
    }
  expect_apart_rejected(m, model, "the crossing does not hold over the box");
  m = c;
  m.a_other = m.b_other = ExactPosition{Rational(0), false, false, {}, {}};
  m.x = RationalInterval{Rational(-1), Rational(1)};
  expect_apart_rejected(m, model, "part 'post' is fixed: the ends give no position of it");
  m = c;
  m.envelope.statement = "Part 'bar' cannot turn.";
  expect_apart_rejected(m, model, "the statement does not say", false);
  // a planar part's poses in a pin-slot pair
  m = c;
  m.pin_slot = false;
  m.a.slide.reset();
  m.b.slide.reset();
  expect_apart_rejected(m, model, "");
}

TEST(CertifyApartPinSlot, TreesBeyondTheFormatsLimitsAreRefusedBeforeTheirProofs) {
  // the format states its limits: 100 000 leaves, 160 halvings, 10^7 box tests of the adjacency
  const Model model = test::peg_in_hole("5", "6");
  SlicedApartCertificate m;
  m.envelope.first = "plate";
  m.envelope.second = "peg";
  m.a = PlanarPose{"peg", 0, 0, 0, false, std::nullopt};
  m.b = PlanarPose{"peg", 0, 0, 1, false, std::nullopt};
  m.x = m.y = RationalInterval{Rational(-7, 2), Rational(7, 2)};
  // (the envelope naming the model: a planar clearance certificate's, not a produced apart
  // certificate's, whose search cost most of this test's time before session 73; the verifier
  // reads the envelope's model and parts only, the statement after every proof)
  std::optional<Certificate> envelope = certify_planar_clearance(model, "plate", m.a, std::nullopt);
  ASSERT_TRUE(envelope);
  m.envelope = *envelope;
  // a point proof that fails wherever it is checked: (0, 0) relative to the peg's pivot is in the
  // peg and in the hole, not in the plate (so a proof checked before a limit is refused changes
  // the reason)
  SlicedApartProof unprovable;
  unprovable.kind = SlicedApartProof::Kind::point;
  // 2^17 leaves (131 072) in a balanced tree
  std::function<std::string(int)> balanced = [&](int k) -> std::string { return k == 0 ? "o" : "xyu"[k % 3] + balanced(k - 1) + balanced(k - 1); };
  m.tree = balanced(17);
  m.proofs.clear();
  auto started = std::chrono::steady_clock::now();
  expect_apart_rejected(m, model, "the tree has more than 100000 leaves (the format's limit)");
  // 161 halvings down to the lowest corner
  m.tree.clear();
  for (int k = 0; k < 161; ++k) m.tree += "xyu"[k % 3];
  m.tree += std::string(162, 'o');
  expect_apart_rejected(m, model, "the tree is deeper than 160 halvings");
  // 2^13 u-slabs left of x = 0 meeting 2^13 y-slabs right of it: 6.7 * 10^7 pairs of meeting open
  // leaves (16 386 leaves, within the leaf limit), refused by the adjacency's budget
  std::function<std::string(char, int)> slabs = [&](char axis, int k) -> std::string {
    return k == 0 ? std::string("o") : axis + slabs(axis, k - 1) + slabs(axis, k - 1);
  };
  m.tree = "x" + ("x" + std::string("b") + ("y" + ("y" + std::string("b") + slabs('u', 13)) + "b")) +
           ("x" + ("y" + ("y" + std::string("b") + slabs('y', 13)) + "b") + "b");
  m.proofs.assign(6, unprovable);
  expect_apart_rejected(m, model, "the open leaves' adjacency needs more than 10000000 box tests");
  // a peg of 302 edges (a zigzag bottom) and 2^15 leaves, all blocked by point proofs but the 16
  // holding a or b: 32 752 point proofs x 311 edges, refused before any is checked
  {
    std::string zigzag = R"({ "start": [-3, 1], "edges": [ )";
    for (int i = 0; i <= 300; ++i)
      zigzag += R"({ "line_to": [)" + n(Rational(-3) + Rational(6 * i, 300)) + "," + n(Rational(-1) - Rational(i % 2, 100)) + "] }, ";
    zigzag += R"({ "line_to": [3, 1] }, { "line_to": [-3, 1] } ] })";
    const std::string plate = rectangle(-20, -20, 20, 20) + ", " + rectangle(-6, -6, 6, 6);
    const Model comb = read_model(R"({ "hipair": 1, "name": "comb", "parts": [
      { "name": "plate", "motion": "fixed", "loops": [ )" + plate + R"( ] },
      { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + zigzag + " ] } ] }");
    SlicedApartCertificate f = m;
    // (an envelope naming the comb model: a planar clearance certificate's)
    std::optional<Certificate> clearance = certify_planar_clearance(comb, "plate", f.a, std::nullopt);
    ASSERT_TRUE(clearance);
    f.envelope = *clearance;
    f.tree.clear();
    f.proofs.clear();
    std::size_t open = 0;
    std::function<void(int, Rational*, Rational*)> build = [&](int k, Rational* lo, Rational* hi) {
      if (k == 15) {
        auto holds = [&](const Rational& u) { return lo[0] <= 0 && hi[0] >= 0 && lo[1] <= 0 && hi[1] >= 0 && lo[2] <= u && hi[2] >= u; };
        if (holds(0) || holds(1)) {
          f.tree += 'o';
          ++open;
        } else {
          f.tree += 'b';
          f.proofs.push_back(unprovable);
        }
        return;
      }
      const int axis = k % 3;
      f.tree += "xyu"[axis];
      const Rational middle = (lo[axis] + hi[axis]) / 2, saved_hi = hi[axis], saved_lo = lo[axis];
      hi[axis] = middle;
      build(k + 1, lo, hi);
      hi[axis] = saved_hi;
      lo[axis] = middle;
      build(k + 1, lo, hi);
      lo[axis] = saved_lo;
    };
    Rational lo[3] = {Rational(-7, 2), Rational(-7, 2), Rational(-1)}, hi[3] = {Rational(7, 2), Rational(7, 2), Rational(3)};
    build(0, lo, hi);
    EXPECT_EQ(open, 16u);
    expect_apart_rejected(f, comb, "point proofs need more than 4000000 edge tests (311 edges; the format's limit)");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_LT(seconds, 120.0);   // (a loose bound on a loaded machine: about 5 s when idle)
}

}  // namespace
}  // namespace hipair
