// Check 7 of the no_jam tolerance verifier (certify/free_path_check.cpp) near an arc's end
// (session 66, tcert66): a vertex crossing an arc's circle a distance 2^-k beyond the arc's end.
// That is the spur gears' case: the pinion's base-circle vertex passes 0.05 mm beyond the corner
// of the gear's tooth tip arc (1.4 mm long), where it lies only 0.0012 mm beyond the arc's chord,
// and check 7 left it undecided (the whole-turn certificate `unproven`). The radial lines through
// the arc's ends decide it (`beyond_arc_ends`).
//
// Generated family: a "block" (a sector of a circle of radius rho about its pivot: the radial
// segment, a short arc of sweep 2 atan(tau), the radial segment back) held still, and an "arm"
// (a triangle whose tip is the start vertex of its first edge) turning about a far pivot (R mm
// below its tip) so that the tip crosses the block's circle nearly radially, at the distance
// `gap` (a toleranced parameter, +-1/4 of its value) from the line through the arc's end: beyond
// the end (gap = 2^-k: the arm never meets the block) or within the arc (gap = -2^-k: the tip runs
// into the block). Mirrored, the crossing is at the arc's other end (the arc's target). Oracle:
// the exact overlap predicate at exact parameter values and rational rotations (the exact model
// rebuilt by ParametricModel::exact_model). Check 7 must prove every free case (before session 66
// it ran out of its bisections on them: the chord's margin is 2^-k times half the sweep) and no
// case where the predicate finds the parts overlapping.
#include "certify/tolerance_check.hpp"

#include <hipair/certificate.hpp>
#include <hipair/overlap.hpp>

#include "model/parametric/parametric.hpp"
#include "certificate_test_support.hpp"
#include "free_path_claim.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

namespace hipair {
namespace {

std::string text(const Rational& r) { return to_exact_string(r); }

struct Case {
  int k = 4;
  bool free = true;       // the tip passes beyond the arc's end (else through the arc)
  bool mirrored = false;  // the crossing at the arc's target (else at its source)
  Rational tau, rho, R;
};

// The model of a case as JSON (lengths in mm, angles in rad).
std::string model_json(const Case& c) {
  Rational eps(1);
  for (int i = 0; i < c.k; ++i) eps /= 2;
  Rational gap = c.free ? eps : -eps;
  Rational m = c.mirrored ? -1 : 1;
  Rational d = 1 + c.tau * c.tau;
  Rational tx = c.rho * (1 - c.tau * c.tau) / d, ty = c.rho * 2 * c.tau / d;
  Rational x0 = c.rho + 32 * eps;   // the tip 32 eps outside the circle at the range's start
  auto pt = [&](const std::string& x, const std::string& y) { return "[\"" + x + "\", \"" + y + "\"]"; };
  auto y = [&](const std::string& base) { return c.mirrored ? "-(" + base + ")" : base; };
  std::ostringstream o;
  o << "{\"hipair\": 1, \"name\": \"arc-end\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"},\n"
    << " \"parameters\": {\"gap\": {\"nominal\": \"" << text(gap) << "\", \"tolerance\": \"" << text(eps / 4) << "\"}},\n"
    << " \"parts\": [\n";
  // The arm: tip at (x0, -gap) (mirrored: +gap), pivot R below (above) it.
  std::string tip_y = y("-gap"), base_y = y("-gap - 2");
  std::string left = pt(text(x0 - Rational(1, 2)), base_y), right = pt(text(x0 + Rational(1, 2)), base_y);
  o << "  {\"name\": \"arm\", \"motion\": {\"rotation\": {\"pivot\": " << pt(text(x0), y("-gap - " + text(c.R)))
    << "}},\n   \"loops\": [{\"start\": " << pt(text(x0), tip_y) << ", \"edges\": [\n"
    << "     {\"line_to\": " << (c.mirrored ? right : left) << ", \"label\": \"tip side\"},\n"
    << "     {\"line_to\": " << (c.mirrored ? left : right) << "},\n"
    << "     {\"line_to\": " << pt(text(x0), tip_y) << "}]}]},\n";
  // The block: the sector from angle 0 to the sweep (mirrored: from minus the sweep to 0), ccw.
  std::string s = pt(text(c.rho), "0"), t = pt(text(tx), text(m * ty));
  o << "  {\"name\": \"block\", \"motion\": {\"rotation\": {\"pivot\": [0, 0]}},\n"
    << "   \"loops\": [{\"start\": [0, 0], \"edges\": [\n"
    << "     {\"line_to\": " << (c.mirrored ? t : s) << "},\n"
    << "     {\"arc_to\": " << (c.mirrored ? s : t) << ", \"center\": [0, 0], \"dir\": \"ccw\", \"label\": \"tip arc\"},\n"
    << "     {\"line_to\": [0, 0]}]}]}\n ]}\n";
  return o.str();
}

Placement rotation(const Point& pivot, const Rational& t) {
  Rational d = 1 + t * t;
  return placement_about(pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
}

TEST(CertifyArcEnd, AVertexPastAnArcsEndAtTwoToTheMinusKIsDecidedAsTheExactOverlapPredicate) {
  std::mt19937_64 random(test::test_seed(66));
  const Rational taus[] = {Rational(1, 16), Rational(1, 40), Rational(1, 64), Rational(1, 128)};
  const Rational rhos[] = {Rational(5), Rational(10), Rational(29)};
  const Rational Rs[] = {Rational(64), Rational(128)};
  std::size_t proved = 0, overlapping_seen = 0;
  for (int trial = 0; trial < 16; ++trial) {
    Case c;
    c.k = std::uniform_int_distribution<int>(6, 30)(random);
    c.free = trial % 4 != 3;
    c.mirrored = trial % 2 == 1;
    c.tau = taus[std::uniform_int_distribution<int>(0, 3)(random)];
    c.rho = rhos[std::uniform_int_distribution<int>(0, 2)(random)];
    c.R = Rs[std::uniform_int_distribution<int>(0, 1)(random)];
    std::string json = model_json(c);
    SCOPED_TRACE("trial " + std::to_string(trial) + ": k " + std::to_string(c.k) + (c.free ? " free" : " through the arc") +
                 (c.mirrored ? ", at the arc's target" : ", at the arc's source") + ", tau " + text(c.tau) + ", rho " +
                 text(c.rho) + ", R " + text(c.R) + "\n" + json);
    std::shared_ptr<const model_detail::ParametricModel> model;
    ASSERT_NO_THROW(model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(json)));
    const Model& m = model->nominal();
    Rational eps(1);
    for (int i = 0; i < c.k; ++i) eps /= 2;
    // The arm turns by 64 eps / R (the tip 64 eps to the left); mirrored it turns the other way.
    Rational turn = 64 * eps / c.R;
    // A named side (checks 1-6 are not run here: check 7 never trusts it).
    ContactSidePair side;
    side.driver = FeatureReference{EdgeReference{"arm", 0, 0, "tip side"}, true};
    side.follower = FeatureReference{EdgeReference{"block", 0, 1, "tip arc"}, false};
    const ToleranceClaim t = test::one_leaf_no_jam_claim(
        "arm", "block", c.mirrored ? RationalInterval{-turn, Rational(0)} : RationalInterval{Rational(0), turn}, {"gap"},
        {{-eps / 4, eps / 4}}, side);
    const std::string failure = test::free_path_failure(model, t, 2);
    bool ok = failure.empty();
    proved += ok;
    // The oracle along the range: the arm at rational half-angle tangents from 0 to turn / 2
    // (tan(x / 2) >= x / 2: inside the range), the gap at its ends and its nominal value.
    bool overlap = false;
    std::size_t gap = static_cast<std::size_t>(m.find_parameter("gap") - m.parameters.data());
    for (int g = -1; g <= 1; ++g) {
      std::vector<Rational> deviations(m.parameters.size(), Rational(0));
      deviations[gap] = eps / 4 * g;
      Model exact = model->exact_model(deviations);
      const Part& arm = exact.parts[*exact.find_part("arm")];
      const Part& block = exact.parts[*exact.find_part("block")];
      for (int j = 0; j <= 32; ++j) {
        Rational td = turn / 2 * Rational(j, 32) * (c.mirrored ? -1 : 1);
        PartRelation r = part_overlap(arm, rotation(arm.motion.pivot, td), block, rotation(block.motion.pivot, Rational(0))).relation;
        if (ok) EXPECT_EQ(r, PartRelation::apart) << "gap deviation " << g << "/4 eps, sample " << j;
        if (c.free) EXPECT_EQ(r, PartRelation::apart) << "the generator's free case is not free: sample " << j;
        overlap = overlap || r == PartRelation::overlapping;
      }
    }
    overlapping_seen += overlap;
    if (c.free) EXPECT_TRUE(ok) << "not proved: " << failure;
    else EXPECT_TRUE(overlap) << "the generator's case through the arc does not overlap";
    if (overlap) EXPECT_FALSE(ok);
  }
  std::cout << "[ arc end ] " << proved << " proved, " << overlapping_seen << " seen overlapping (of 16)\n";
  EXPECT_EQ(proved, 12u);
  EXPECT_EQ(overlapping_seen, 4u);
}


// The spur gears' no-jam certificate over the pinion's first 0.25 rad (`hipair tolerance
// examples/models/spur-gears.json --range 0:0.25 --certify`, 4 leaves): check 7 met the pinion's
// base-circle vertex of 'tooth 2 flank R lower' passing 0.05 mm beyond the corner of the gear's
// 'tooth 27 tip' arc and stopped after its 48 bisections: `unproven` before session 66, `valid`
// now. Mutations are rejected: a leaf's driver interval halved (coverage gap), the box widened
// and the scale raised (wrong parameter box), the witness moved by a tooth's play (0.1 rad: the
// gear's teeth meet the pinion's).

TEST(CertifyArcEnd, TheSpurGearsNoJamCertificateIsValidAndItsMutationsAreNot) {
  std::filesystem::path model = std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json";
  std::filesystem::path fixture =
      std::filesystem::path(HIPAIR_TEST_DATA) / "certificates" / "spur-gears-tolerance-no-jam-0-0.25.json";
  const std::string model_text = test::slurp(model.string());
  VerificationResult v = verify_certificate_file(fixture, model);
  EXPECT_TRUE(v.valid) << v.summary << v.reason;
  EXPECT_FALSE(v.unproven) << v.summary;
  const Certificate base = read_certificate(test::slurp(fixture.string()));
  ASSERT_TRUE(base.tolerance);
  ASSERT_EQ(base.tolerance->leaves.size(), 4u);
  auto check = [&](const Certificate& c) { return check_certificate_text(c, model_text, "spur-gears.json"); };
  test::expect_box_and_coverage_mutations_rejected(base, 1, check);
  {
    Certificate c = base;
    *c.tolerance->leaves[0].witness += Rational(1, 10);
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid) << r.summary;
  }
}

}  // namespace
}  // namespace hipair
