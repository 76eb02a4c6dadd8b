// sliced_connected certificates under hostile input (session 68, fuzzconn68), and far-off pairs.
// Hand-written forgeries, each refused with its reason in bounded time (or, when the claim is
// true, accepted without the work a forger asked for): a move that grazes the hole's side for its
// whole length (refused once its pieces reach 2^-(bits + 64) of the move, not after 40 000 of
// them), more moves than the certificate's budget of pieces (refused before any is checked),
// 100 000 repeated vertices and 100 000 chart changes at one pose (a move that stays at a pose is
// free where the moves around it are: not re-proved), rationals of 300 and 5 000 digits, a chart
// change that turns. And a peg/hole pair at offsets 10^6, 10^30 and 10^300 from the origin: certified
// as at the origin (the producer moves the pair there as the verifier does), the certificate
// verified on the model as given.
#include <hipair/certificate.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced_certificate.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sliced_peg_in_hole.hpp"
#include "random_rationals.hpp"

namespace hipair {
namespace {

PlanarPose pose(const Rational& x, const Rational& y, const Rational& t, bool half_turn = false) {
  return PlanarPose{"peg", x, y, t, half_turn, std::nullopt};
}

// A claim from `path`'s first vertex to its last, with its statement.
SlicedConnectedCertificate claim(const Model& model, std::vector<PlanarPose> path) {
  SlicedConnectedCertificate c;
  c.envelope.model_name = model.name;
  c.envelope.first = "plate";
  c.envelope.second = "peg";
  c.from = path.front();
  c.to = path.back();
  c.path = std::move(path);
  c.envelope.statement = sliced_connected_statement(c);
  return c;
}

void expect_rejected(const SlicedConnectedCertificate& c, const Model& model, const std::string& reason) {
  VerificationResult v = check_sliced_connected(c, model);
  EXPECT_FALSE(v.valid) << v.summary;
  EXPECT_NE(v.reason.find(reason), std::string::npos) << v.reason.substr(0, 600);
}

using test_numbers::power_of_ten;

// The 10 mm peg in a 12 mm hole of a 40 mm plate, both moved by (d, d) (the peg's pivot with it).
Model peg_in_hole_at(const Rational& d) {
  auto square = [&](const Rational& half) {
    auto at = [&](int sx, int sy) {
      const Rational x = d + sx * half, y = d + sy * half;
      return "[\"" + x.get_str() + "\", \"" + y.get_str() + "\"]";
    };
    return R"({ "start": )" + at(-1, -1) + R"(, "edges": [ { "line_to": )" + at(1, -1) + R"( }, { "line_to": )" + at(1, 1) +
           R"( }, { "line_to": )" + at(-1, 1) + R"( }, { "line_to": )" + at(-1, -1) + " } ] }";
  };
  return read_model(R"({ "hipair": 1, "name": "json", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + square(20) + ", " + square(6) + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [")" + d.get_str() + "\", \"" + d.get_str() + R"("] } }, "loops": [ )" +
                    square(5) + R"( ] } ] })");
}

TEST(CertifySlicedConnectedHostile, ForgedPathsAreRefusedOrAcceptedInBoundedWork) {
  const Model model = test::peg_in_hole("5", "6");   // 1 mm of clearance each side
  // grazing: the peg's right side on the hole's (x = 1) for the whole move
  expect_rejected(claim(model, {pose(1, Rational(-1, 2), 0), pose(1, Rational(1, 2), 0)}), model,
                  "move 0 (x=1, y=-1/2, t=0 to x=1, y=1/2, t=0): not proved free: its pieces reached 2^-320 of the move");
  // more moves than pieces in all: refused before any move is checked
  std::vector<PlanarPose> path(100002, pose(0, 0, 0));
  expect_rejected(claim(model, path), model, "the path has 100001 moves, more than the 100000 interval pieces");
  // 100 000 repeated vertices at a free pose: true, proved once (at the start)
  path.resize(100001);
  VerificationResult v = check_sliced_connected(claim(model, path), model);
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_NE(v.summary.find("(100000 moves, each proved free over 1 interval pieces in all)"), std::string::npos) << v.summary;
  // 100 000 chart changes at a quarter turn (t = 1 about 0 is t = -1 about pi), out of the hole
  path.clear();
  for (int k = 0; k < 100000; ++k) path.push_back(k % 2 ? pose(30, 0, -1, true) : pose(30, 0, 1));
  path.insert(path.begin(), pose(30, 0, 0));
  v = check_sliced_connected(claim(model, path), model);
  EXPECT_TRUE(v.valid) << v.reason;
  // a chart change that turns
  expect_rejected(claim(model, {pose(30, 0, 1), pose(30, 0, 1, true)}), model, "changes the chart (centre) and the angle at once");
  // 5000-digit rationals: a turn by a tangent of 10^-5000 in the hole, and out through the plate
  // to x = 10^5000
  const Rational tiny = 1 / power_of_ten(5000), huge = power_of_ten(5000);
  v = check_sliced_connected(claim(model, {pose(0, 0, 0), pose(0, 0, tiny), pose(0, 0, 0)}), model);
  EXPECT_TRUE(v.valid) << v.reason;
  // (longer than 2^1024 times the peg: refused near its start at 2^-(320 + 1024) of the move)
  expect_rejected(claim(model, {pose(0, 0, 0), pose(huge, 0, 0)}), model, "its pieces reached 2^-1344 of the move");
  // out through the plate to x = 10^300: the overlap found
  expect_rejected(claim(model, {pose(0, 0, 0), pose(power_of_ten(300), 0, 0)}), model, "the parts overlap");
  // a rotation by a tangent of 10^300 (almost a half turn) in the hole: the corners meet the plate
  expect_rejected(claim(model, {pose(0, 0, 0), pose(0, 0, power_of_ten(300))}), model, "the parts overlap");
}

TEST(CertifySlicedConnectedHostile, FarPairsAreCertifiedAsAtTheOrigin) {
  const PlanarPose flat = pose(0, 0, 0), slid = pose(Rational(9, 10), Rational(-9, 10), 0), turned = pose(Rational(1, 2), 0, Rational(1, 25));
  for (int exponent : {0, 6, 30, 300}) {
    const Model model = peg_in_hole_at(exponent ? power_of_ten(exponent) : Rational(0));
    for (const PlanarPose& to : {slid, turned}) {
      SlicedConnectedResult result = certify_sliced_connected(model, "plate", flat, to);
      ASSERT_TRUE(result.certificate) << "offset 10^" << exponent << ": " << result.failure;
      SlicedConnectedCertificate read = read_sliced_connected_certificate(write_sliced_connected_certificate(*result.certificate));
      VerificationResult v = check_sliced_connected(read, model);
      EXPECT_TRUE(v.valid) << "offset 10^" << exponent << ": " << v.reason;
      EXPECT_EQ(read.to.x, to.x);
      EXPECT_EQ(read.to.tangent, to.tangent);
    }
  }
}

}  // namespace
}  // namespace hipair
