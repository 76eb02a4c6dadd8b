// sliced_connected certificates (<hipair/sliced_certificate.hpp>): a planar part's two poses
// connected through free space, witnessed by a staircase of pure translations and rotations that
// hipair-verify's check proves free. Tested: the square peg that turns a quarter in a 14.15 mm
// hole (certified) but not in a 14.14 mm one (no certificate: the ends lie in different
// components); generated peg and hole sizes and poses, every certified move sampled with the
// exact overlap oracle; diagonal motions turned into staircases; mutations rejected with their
// reasons (an end moved, a rotation at the wrong offset, a move through the plate, a diagonal
// move, a chart change that turns, the statement, the other part posed, a narrower hole).
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>
#include <hipair/sliced_certificate.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "random_rationals.hpp"
#include "sliced_peg_in_hole.hpp"
#include "test_seed.hpp"

namespace hipair {
namespace {

using Random = std::mt19937_64;

using test_numbers::random_rational;

// Every move of the certificate is pure (or a chart change at one pose), and the exact oracle
// finds the parts apart at 9 poses along it.
void expect_moves_apart(const Model& model, const SlicedConnectedCertificate& c) {
  for (std::size_t i = 0; i + 1 < c.path.size(); ++i) {
    const PlanarPose &a = c.path[i], &b = c.path[i + 1];
    const bool same_xy = a.x == b.x && a.y == b.y;
    ASSERT_TRUE(same_xy || (a.tangent == b.tangent && a.half_turn == b.half_turn)) << "move " << i << " is diagonal";
    if (a.half_turn != b.half_turn) continue;
    for (int k = 0; k <= 8; ++k) {
      Rational u(k, 8);
      u.canonicalize();
      PlanarPose p = a;
      p.x = a.x + u * (b.x - a.x);
      p.y = a.y + u * (b.y - a.y);
      p.tangent = a.tangent + u * (b.tangent - a.tangent);
      ASSERT_EQ(test::relation_at_pose(model, p), PartRelation::apart) << "move " << i << " at u = " << u.get_str();
    }
  }
}

// The certificate verifies after the JSON round trip; returns the copy read back.
SlicedConnectedCertificate expect_valid(const Model& model, const SlicedConnectedResult& result) {
  EXPECT_TRUE(result.certificate) << result.failure;
  if (!result.certificate) return {};
  SlicedConnectedCertificate read = read_sliced_connected_certificate(write_sliced_connected_certificate(*result.certificate));
  VerificationResult v = check_sliced_connected(read, model);
  EXPECT_TRUE(v.valid) << v.reason;
  expect_moves_apart(model, read);
  return read;
}

void expect_rejected(const SlicedConnectedCertificate& c, const Model& model, const std::string& reason, bool restate = true) {
  SlicedConnectedCertificate mutated = c;
  if (restate) mutated.envelope.statement = sliced_connected_statement(mutated);
  VerificationResult v = check_sliced_connected(mutated, model);
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find(reason), std::string::npos) << v.reason;
}

PlanarPose pose(const Rational& x, const Rational& y, const Rational& t, bool half_turn = false) {
  return PlanarPose{"peg", x, y, t, half_turn, std::nullopt};
}

TEST(CertifySlicedConnected, TheSquarePegTurnsAQuarterOnlyInTheWiderHole) {
  // 10 mm square peg: its diagonal is 14.142 mm, so it turns in a 14.15 mm hole, not in a 14.14 one
  const Model wide = test::peg_in_hole("5", "7.075"), narrow = test::peg_in_hole("5", "7.07");
  const PlanarPose flat = pose(0, 0, 0), upright = pose(0, 0, 1);
  SlicedConnectedResult turned = certify_sliced_connected(wide, "plate", flat, upright);
  SlicedConnectedCertificate c = expect_valid(wide, turned);
  ASSERT_GE(c.path.size(), 2u);
  EXPECT_EQ(c.envelope.statement, "Part 'peg' moves from x=0, y=0, t=0 to x=0, y=0, t=1 without touching part 'plate'.");

  SlicedConnectedResult stuck = certify_sliced_connected(narrow, "plate", flat, upright);
  EXPECT_FALSE(stuck.certificate);
  EXPECT_NE(stuck.failure.find("different components"), std::string::npos) << stuck.failure;
  // the wide hole's certificate on the narrow hole: a rotation meets the plate
  {
    VerificationResult v = check_sliced_connected(c, narrow);
    EXPECT_FALSE(v.valid);
    EXPECT_NE(v.reason.find("move "), std::string::npos) << v.reason;
  }

  // mutations
  SlicedConnectedCertificate m = c;
  m.to.x = Rational(1, 10);
  expect_rejected(m, wide, "the path ends at");
  m = c;
  m.from.tangent = Rational(1, 100);
  expect_rejected(m, wide, "the path starts at");
  m = c;   // turned at an offset of 1 mm: the corners reach 8.07 mm, past the hole's side
  m.path = {flat, pose(1, 0, 0), pose(1, 0, 1), upright};
  expect_rejected(m, wide, "move 1 (x=1, y=0, t=0 to x=1, y=0, t=1): the parts overlap");
  m = c;   // straight out through the plate
  m.to = pose(30, 0, 0);
  m.path = {flat, m.to};
  expect_rejected(m, wide, "move 0 (x=0, y=0, t=0 to x=30, y=0, t=0): the parts overlap");
  m = c;   // a diagonal move
  m.to = pose(Rational(1, 10), 0, Rational(1, 100));
  m.path = {flat, m.to};
  expect_rejected(m, wide, "changes both the offset and the rotation");
  m = c;   // a chart change that also turns
  m.to = pose(0, 0, Rational(1, 2), true);
  m.path = {flat, pose(0, 0, Rational(1, 2)), m.to};
  expect_rejected(m, wide, "changes the chart (centre) and the angle at once");
  m = c;
  m.envelope.statement = "Part 'peg' moves anywhere.";
  expect_rejected(m, wide, "the statement does not say what the claim's data prove", false);
  m = c;
  m.from.part = m.to.part = "plate";
  expect_rejected(m, wide, "is not free in the plane", false);
  m = c;
  m.path.clear();
  expect_rejected(m, wide, "the path has no vertex");
  // a single vertex: the claim from a pose to itself, proved at the pose
  m = c;
  m.to = flat;
  m.path = {flat};
  m.envelope.statement = sliced_connected_statement(m);
  EXPECT_TRUE(check_sliced_connected(m, wide).valid);
  m.from = m.to = pose(3, 0, 0);   // the peg's side at x = 8, past the hole's 7.075
  m.path = {m.from};
  expect_rejected(m, wide, "at the start: the parts overlap");
}

TEST(CertifySlicedConnected, GeneratedPegsHolesAndPoses) {
  Random random(test::test_seed(6801));
  int certified = 0;
  for (int model_index = 0; model_index < 3; ++model_index) {
    const Rational s = random_rational(random, 3, 6, 8);
    // hole half-side h = s k, k in [1.03, 1.6]: the peg turns freely when k > sqrt 2
    const Rational k = random_rational(random, Rational(103, 100), Rational(160, 100), 20);
    const Rational h = s * k;
    const bool turns = k * k > 2;
    const Model model = test::peg_in_hole(to_exact_string(s), to_exact_string(h));
    SCOPED_TRACE("peg half-side " + s.get_str() + ", hole half-side " + h.get_str());
    for (int query = 0; query < 2; ++query) {
      // query 1: both ends at one rotation; the poses of a convex peg inside a convex hole at a
      // fixed rotation form a convex set, so the translation between them is free: connected
      const bool same_turn = query == 1;
      PlanarPose ends[2];
      for (PlanarPose& end : ends) {
        for (int attempt = 0; attempt < 200; ++attempt) {
          end = pose(random_rational(random, s - h, h - s, 16), random_rational(random, s - h, h - s, 16),
                     same_turn && &end == &ends[1] ? ends[0].tangent : random_rational(random, -1, 1, 24));
          if (test::relation_at_pose(model, end) == PartRelation::apart) break;
        }
        ASSERT_EQ(test::relation_at_pose(model, end), PartRelation::apart);
      }
      SCOPED_TRACE("from x=" + ends[0].x.get_str() + " y=" + ends[0].y.get_str() + " t=" + ends[0].tangent.get_str() +
                   " to x=" + ends[1].x.get_str() + " y=" + ends[1].y.get_str() + " t=" + ends[1].tangent.get_str());
      SlicedConnectedResult result = certify_sliced_connected(model, "plate", ends[0], ends[1]);
      if (turns) EXPECT_TRUE(result.certificate) << "the peg turns freely in this hole: " << result.failure;
      if (same_turn) EXPECT_TRUE(result.certificate) << "both ends at one rotation in the hole: " << result.failure;
      if (result.certificate) {
        ++certified;
        SlicedConnectedCertificate c = expect_valid(model, result);
        // moved end: refused
        c.to.y += 1;
        expect_rejected(c, model, "the path ends at");
      } else {
        EXPECT_TRUE(result.failure.find("different components") != std::string::npos ||
                    result.failure.find("found no path") != std::string::npos)
            << result.failure;
      }
    }
  }
  EXPECT_GE(certified, 1);
}

TEST(CertifySlicedConnected, DiagonalMotionsBecomeStaircasesProvedFree) {
  const Model wide = test::peg_in_hole("5", "7.075");
  SlicedPath path;
  path.status = SlicedPath::Status::found;
  // in the hole, x, y and the angle changing together; outside the plate, through the half turn
  path.waypoints = {SlicedConfiguration{Rational(-1, 5), 0, SlicedAngle{0, false}},
                    SlicedConfiguration{Rational(1, 5), Rational(1, 10), SlicedAngle{Rational(1, 20), false}}};
  path.through_half_turn = {false};
  SlicedConnectedCertificate c = expect_valid(wide, certify_sliced_path(wide, "plate", "peg", path));
  EXPECT_GE(c.path.size(), 3u);
  path.waypoints = {SlicedConfiguration{30, 0, SlicedAngle{0, true}}, SlicedConfiguration{28, 3, SlicedAngle{10, false}},
                    SlicedConfiguration{31, -2, SlicedAngle{-7, false}}};
  path.through_half_turn = {true, true};
  c = expect_valid(wide, certify_sliced_path(wide, "plate", "peg", path));
  EXPECT_TRUE(c.path.front().half_turn);
  // a proposal through the plate: no certificate
  path.waypoints = {SlicedConfiguration{0, 0, SlicedAngle{0, false}}, SlicedConfiguration{30, 0, SlicedAngle{Rational(1, 10), false}}};
  path.through_half_turn = {false};
  SlicedConnectedResult blocked = certify_sliced_path(wide, "plate", "peg", path);
  EXPECT_FALSE(blocked.certificate);
  EXPECT_FALSE(blocked.failure.empty());
}

TEST(CertifySlicedConnected, TheBarTurnsTheCornerOfAnLShapedCorridor) {
  const Model model = read_model(R"({ "hipair": 1, "name": "L", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [
      { "start": [-30, -30], "edges": [ { "line_to": [30, -30] }, { "line_to": [30, 30] }, { "line_to": [-30, 30] }, { "line_to": [-30, -30] } ] },
      { "start": [-20, 0], "edges": [ { "line_to": [4, 0] }, { "line_to": [4, 20] }, { "line_to": [0, 20] }, { "line_to": [0, 4] },
                                      { "line_to": [-20, 4] }, { "line_to": [-20, 0] } ] } ] },
    { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [
      { "start": [-3, -1], "edges": [ { "line_to": [3, -1] }, { "line_to": [3, 1] }, { "line_to": [-3, 1] }, { "line_to": [-3, -1] } ] } ] } ] })");
  SlicedConnectedCertificate c = expect_valid(model, certify_sliced_connected(model, "plate", pose(-10, 2, 0), pose(2, 12, 1)));
  EXPECT_GE(c.path.size(), 4u);
}

TEST(CertifySlicedConnected, BadPairsAreRefused) {
  const Model wide = test::peg_in_hole("5", "7.075");
  EXPECT_THROW(certify_sliced_connected(wide, "peg", PlanarPose{"plate", 0, 0, 0, false}, PlanarPose{"plate", 0, 0, 0, false}),
               GeometryError);
  EXPECT_THROW(certify_sliced_connected(wide, "nothing", pose(0, 0, 0), pose(0, 0, 1)), ModelError);
  // an end in the plate: not free
  SlicedConnectedResult r = certify_sliced_connected(wide, "plate", pose(0, 0, 0), pose(3, 0, 0));
  EXPECT_FALSE(r.certificate);
  EXPECT_NE(r.failure.find("not a free configuration"), std::string::npos) << r.failure;
}

}  // namespace
}  // namespace hipair
