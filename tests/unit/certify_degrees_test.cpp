// `hipair certify --at PART=ANGLEdeg` at whole quarter turns (cli::exact_position_from_degrees):
// a peg touching a block at exactly 90°, 180°, 270° or 0° (plus any whole number of turns, up to
// 10^60 of them) is placed exactly — half-angle tangent 0 or ±1, 180° as the half-turn chart's 0
// — and so found touching: neither interference nor clearance is certified. Until session 32
// the angle went through the rounded radians (10^-18 rad off) and such a peg was certified
// interfering. Generated cases: random rational pegs and blocks, scaled by 10^k for k in
// [-300, 300] (exact), the block touching, 10^-20 of the scale away, or 10^-20 into the peg;
// the oracle is the library's exact overlap predicate on the peg placed by the closed-form
// quarter-turn rotation (cos, sin in {0, ±1}). Any other angle is placed as before
// (degrees_to_radians, then exact_position_from_angle), and a position beyond the part's
// motion limits is an input error naming the part and its limits.
#include "cli/angles.hpp"
#include "random_rationals.hpp"

#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>

namespace {

using namespace hipair;

std::string lit(const Rational& v) { return "\"" + to_exact_string(v) + "\""; }
std::string json_point(const Rational& x, const Rational& y) { return "[" + lit(x) + ", " + lit(y) + "]"; }

// A closed polygon loop from its corners.
std::string polygon(const std::vector<std::array<Rational, 2>>& corners) {
  std::string text = "{ \"start\": " + json_point(corners[0][0], corners[0][1]) + ", \"edges\": [";
  for (std::size_t i = 1; i <= corners.size(); ++i) {
    const auto& c = corners[i % corners.size()];
    text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": " + json_point(c[0], c[1]) + " }";
  }
  return text + "] }";
}

struct Case {
  Rational length, half_width, block_half, block_depth, gap;   // all scaled already
  int quarter = 0;                                              // the block faces the peg turned by quarter x 90°
  std::string limits;                                           // the peg's "limits" entry ("" for none)
};

// The peg [0, L] x [-h, h] turning about the origin; the block's face at distance L + gap from
// the pivot along the quarter turn's direction u, across [-H, H] along v = u turned by 90°.
std::string model_text(const Case& c) {
  static const int cosines[4] = {1, 0, -1, 0}, sines[4] = {0, 1, 0, -1};
  Rational ux = cosines[c.quarter], uy = sines[c.quarter], vx = -uy, vy = ux;
  auto at = [&](const Rational& along, const Rational& across) -> std::array<Rational, 2> {
    return {Rational(along * ux + across * vx), Rational(along * uy + across * vy)};
  };
  Rational near = c.length + c.gap, far = near + c.block_depth;
  std::string peg = polygon({{Rational(0), Rational(-c.half_width)}, {c.length, Rational(-c.half_width)},
                             {c.length, c.half_width}, {Rational(0), c.half_width}});
  std::string block = polygon({at(near, -c.block_half), at(far, -c.block_half), at(far, c.block_half), at(near, c.block_half)});
  return "{ \"hipair\": 1, \"name\": \"quarter-turns\", \"parts\": [\n"
         "  { \"name\": \"peg\", \"motion\": { \"rotation\": { \"pivot\": [0, 0]" +
         (c.limits.empty() ? std::string() : ", \"limits\": " + c.limits) + " } }, \"loops\": [" + peg +
         "] },\n"
         "  { \"name\": \"block\", \"motion\": \"fixed\", \"loops\": [" +
         block + "] } ] }";
}

using test_numbers::power_of_ten;

TEST(CertifyDegrees, QuarterTurnsAreExactAndTouchingIsTouching) {
  std::mt19937_64 random(32);
  auto fraction = [&](int lo, int hi) {
    return Rational(std::uniform_int_distribution<int>(lo, hi)(random), std::uniform_int_distribution<int>(1, 97)(random));
  };
  static const int cosines[4] = {1, 0, -1, 0}, sines[4] = {0, 1, 0, -1};
  int touching = 0, interference = 0, clearance = 0;
  for (int n = 0; n < 240; ++n) {
    int k = std::uniform_int_distribution<int>(-300, 300)(random);
    if (n < 8) k = n % 2 ? 300 : -300;
    Rational scale = power_of_ten(k);
    Case c;
    c.quarter = n % 4;
    c.length = fraction(100, 5000) * scale;
    c.half_width = fraction(1, 90) * scale;
    c.block_half = fraction(1, 900) * scale;
    c.block_depth = fraction(1, 900) * scale;
    int side = (n / 4) % 3;   // 0: touching, 1: apart by 10^-20 of the scale, 2: overlapping by it
    Rational delta = scale * power_of_ten(-20);
    c.gap = side == 0 ? Rational(0) : side == 1 ? delta : Rational(-delta);
    // the quarter turn plus whole turns: a few, a million, or 10^60
    Rational turns = n % 5 == 0 ? power_of_ten(60) * (n % 2 ? 1 : -1) : Rational(std::uniform_int_distribution<int>(-1000000, 1000000)(random));
    Rational degrees = Rational(90 * c.quarter) + 360 * turns;
    std::string what = "case " + std::to_string(n) + ": " + to_exact_string(degrees) + " deg, scale 1e" + std::to_string(k) +
                       ", gap " + to_exact_string(c.gap);

    ExactPosition position = cli::exact_position_from_degrees(degrees);
    ASSERT_FALSE(position.angle) << what << ": nothing is rounded, no angle is recorded";
    ASSERT_FALSE(position.is_offset) << what;
    const Rational expected_tangent[4] = {Rational(0), Rational(1), Rational(0), Rational(-1)};
    ASSERT_EQ(position.value, expected_tangent[c.quarter]) << what;
    ASSERT_EQ(position.half_turn, c.quarter == 2) << what;
    // the position's rotation is the closed form's (cos, sin)
    Rational t = position.value, w = 1 + t * t;
    int sign = position.half_turn ? -1 : 1;
    ASSERT_EQ(Rational(sign * (1 - t * t) / w), Rational(cosines[c.quarter])) << what;
    ASSERT_EQ(Rational(sign * 2 * t / w), Rational(sines[c.quarter])) << what;

    Model model = read_model(model_text(c));
    const Part& peg = model.parts[0];
    const Part& block = model.parts[1];
    Placement turned = placement_about(Point{Rational(0), Rational(0)}, Rational(cosines[c.quarter]), Rational(sines[c.quarter]),
                                       Point{Rational(0), Rational(0)});
    PartRelation oracle = part_overlap(peg, turned, block, Placement{}).relation;
    const PartRelation expected[3] = {PartRelation::touching, PartRelation::apart, PartRelation::overlapping};
    ASSERT_EQ(oracle, expected[side]) << what << ": the closed form";

    std::map<std::string, ExactPosition> at{{"peg", position}};
    std::optional<Certificate> overlap = certify_interference(model, "peg", "block", at, CertifyContext{});
    std::optional<Certificate> apart = certify_clearance(model, "peg", "block", at, std::nullopt, CertifyContext{});
    EXPECT_EQ(overlap.has_value(), oracle == PartRelation::overlapping) << what << ": interference certified wrongly";
    EXPECT_EQ(apart.has_value(), oracle == PartRelation::apart) << what << ": clearance certified wrongly";
    for (const std::optional<Certificate>* certificate : {&overlap, &apart})
      if (*certificate) {
        VerificationResult result = check_certificate(**certificate, model);
        EXPECT_TRUE(result.valid) << what << ": " << result.reason;
      }
    if (overlap) {
      // the statement names the exact position: "2 atan(0) + pi rad" for the half turn
      const std::string words[4] = {"peg at 2 atan(0) rad", "peg at 2 atan(1) rad", "peg at 2 atan(0) + pi rad", "peg at 2 atan(-1) rad"};
      EXPECT_NE(overlap->statement.find(words[c.quarter]), std::string::npos) << what << ": " << overlap->statement;
    }
    touching += oracle == PartRelation::touching;
    interference += overlap.has_value();
    clearance += apart.has_value();
  }
  EXPECT_EQ(touching, 80);
  EXPECT_EQ(interference, 80);
  EXPECT_EQ(clearance, 80);
}

// Any other angle is placed as before: converted to the 10^-18 rad grid, the tangent rounded,
// the rational angle and the bound recorded.
TEST(CertifyDegrees, OtherAnglesArePlacedAsBefore) {
  std::mt19937_64 random(3232);
  for (int n = 0; n < 400; ++n) {
    Rational degrees(std::uniform_int_distribution<long>(-1000000, 1000000)(random), std::uniform_int_distribution<long>(1, 1000)(random));
    if (n < 4) degrees = Rational(90 * n) + Rational(1, 1000000000);   // just beside a quarter turn
    Rational quarters = degrees / 90;
    if (quarters.get_den() == 1) continue;
    ExactPosition now = cli::exact_position_from_degrees(degrees);
    ExactPosition before = exact_position_from_angle(cli::degrees_to_radians(degrees));
    EXPECT_EQ(now.value, before.value) << to_exact_string(degrees);
    EXPECT_EQ(now.half_turn, before.half_turn) << to_exact_string(degrees);
    ASSERT_TRUE(now.angle && before.angle) << to_exact_string(degrees);
    EXPECT_EQ(*now.angle, cli::degrees_to_radians(degrees)) << to_exact_string(degrees) << ": labelled as the rational used";
    EXPECT_EQ(*now.angle_error, *before.angle_error) << to_exact_string(degrees);
  }
  // and the option text: "ANGLEdeg" or rad
  EXPECT_EQ(cli::exact_position_from_text("90deg", "--at").value, Rational(1));
  EXPECT_TRUE(cli::exact_position_from_text("-180deg", "--at").half_turn);
  EXPECT_EQ(cli::exact_position_from_text("0.5", "--at").angle, Rational(1, 2));
  EXPECT_THROW(cli::exact_position_from_text("ninety deg", "--at"), ModelError);
  // how a rounded angle was taken: its exact decimal on the 10^-18 rad grid; nothing for exact ones
  EXPECT_EQ(cli::angle_label("45deg", cli::exact_position_from_text("45deg", "--at")), "45deg is taken as 0.785398163397448309 rad");
  EXPECT_EQ(cli::angle_label("-400deg", cli::exact_position_from_text("-400deg", "--at")), "-400deg is taken as -6.981317007977318308 rad");
  EXPECT_EQ(cli::angle_label("1e-30deg", cli::exact_position_from_text("1e-30deg", "--at")), "1e-30deg is taken as 0 rad");
  EXPECT_EQ(cli::angle_label("90deg", cli::exact_position_from_text("90deg", "--at")), "");
  EXPECT_EQ(cli::angle_label("0.5", cli::exact_position_from_text("0.5", "--at")), "");
}

// A position beyond the part's motion limits: an input error naming the part and its limits
// (it reached the certificate's self-check before session 32: "does not pass its own check").
TEST(CertifyDegrees, PositionBeyondTheLimitsIsAnInputError) {
  Case c;
  c.length = 10;
  c.half_width = 1;
  c.block_half = 1;
  c.block_depth = 1;
  c.gap = -1;
  c.quarter = 2;
  c.limits = "[0, 1]";
  Model model = read_model(model_text(c));
  for (const char* degrees : {"180", "-90", "1e30"}) {
    std::map<std::string, ExactPosition> at{{"peg", cli::exact_position_from_degrees(parse_rational(degrees))}};
    for (int claim = 0; claim < 2; ++claim) {
      try {
        if (claim == 0) certify_interference(model, "peg", "block", at, CertifyContext{});
        else certify_clearance(model, "peg", "block", at, std::nullopt, CertifyContext{});
        ADD_FAILURE() << degrees << " deg: a position beyond the limits was accepted";
      } catch (const ModelError& error) {
        std::string message = error.what();
        EXPECT_NE(message.find("the angle of 'peg'"), std::string::npos) << message;
        EXPECT_NE(message.find("its motion limits [0, 1] rad"), std::string::npos) << message;
      }
    }
  }
  // within the limits (0 lies on the lower limit exactly): decided, no error
  std::map<std::string, ExactPosition> at{{"peg", cli::exact_position_from_degrees(Rational(0))}};
  EXPECT_NO_THROW(certify_clearance(model, "peg", "block", at, std::nullopt, CertifyContext{}));
}

}  // namespace
