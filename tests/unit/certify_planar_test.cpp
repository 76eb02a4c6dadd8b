// Planar certificates (a part free in the plane at an exact pose against a fixed part): at random
// rational poses of a peg in a hole and of arc-bounded parts, interference is certified exactly
// where the exact oracle says the parts overlap and clearance exactly where they are apart; each
// certificate verifies, survives the JSON round trip, and its mutations are rejected; the
// certified clearance never exceeds the distance of any two features (sliced features_near).
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "test_paths.hpp"
#include "random_rationals.hpp"

namespace hipair {
namespace {

using Random = std::mt19937_64;

std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
std::string point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }
std::string rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return R"({ "start": )" + point(x0, y0) + R"(, "edges": [ { "line_to": )" + point(x1, y0) + R"( }, { "line_to": )" +
         point(x1, y1) + R"( }, { "line_to": )" + point(x0, y1) + R"( }, { "line_to": )" + point(x0, y0) + " } ] }";
}
Model planar_model(const std::string& fixed_loops, const std::string& free_loops) {
  return read_model(R"({ "hipair": 1, "name": "planar", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + fixed_loops + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + free_loops + R"( ] } ] })");
}
Rational random_rational(Random& random, const Rational& lo, const Rational& hi, long den = 61) {
  return test_numbers::random_rational(random, lo, hi, den);
}
PartRelation relation(const Model& model, const PlanarPose& pose) {
  Rational c = -1, s = 0;
  if (!pose.half_turn) {
    Rational d = 1 + pose.tangent * pose.tangent;
    c = (1 - pose.tangent * pose.tangent) / d;
    s = 2 * pose.tangent / d;
  } else {
    Rational d = 1 + pose.tangent * pose.tangent;
    c = -(1 - pose.tangent * pose.tangent) / d;
    s = -2 * pose.tangent / d;
  }
  const Part& b = model.parts[1];
  return part_overlap(model.parts[0], Placement{}, b, placement_about(b.motion.pivot, c, s, Point{pose.x, pose.y})).relation;
}

void check_model(const Model& model, Random& random, int poses) {
  SlicedBuildOptions options;
  options.cell_structure = false;
  SlicedSpace space = SlicedSpace::build(model, "plate", "peg", options);
  int interference = 0, clearance = 0;
  for (int i = 0; i < poses; ++i) {
    // half of the poses near the hole's centre (mostly apart), half anywhere nearby
    Rational reach = i % 2 ? Rational(4) : Rational(1, 2), turn = i % 2 ? Rational(2) : Rational(1, 20);
    PlanarPose pose{"peg", random_rational(random, -reach, reach), random_rational(random, -reach, reach),
                    random_rational(random, -turn, turn, 17), i % 2 == 1 && random() % 5 == 0};
    PartRelation r = relation(model, pose);
    SCOPED_TRACE("pose x=" + pose.x.get_str() + " y=" + pose.y.get_str() + " t=" + pose.tangent.get_str() +
                 (pose.half_turn ? " (pi)" : ""));
    auto overlap = certify_planar_interference(model, "plate", pose);
    auto apart = certify_planar_clearance(model, "plate", pose);
    EXPECT_EQ(bool(overlap), r == PartRelation::overlapping);
    EXPECT_EQ(bool(apart), r == PartRelation::apart);
    if (overlap) {
      ++interference;
      Certificate read = read_certificate(write_certificate(*overlap));
      EXPECT_TRUE(check_certificate(read, model).valid);
      // the same witness at a pose moved far away: rejected
      Certificate moved = read;
      moved.pose->x += 100;
      EXPECT_FALSE(check_certificate(moved, model).valid);
      if (read.witness_point) {
        Certificate off = read;
        off.witness_point->x += 1000;
        VerificationResult v = check_certificate(off, model);
        EXPECT_FALSE(v.valid);
        EXPECT_NE(v.reason.find("is not strictly inside"), std::string::npos) << v.reason;
      }
    }
    if (apart) {
      ++clearance;
      Certificate read = read_certificate(write_certificate(*apart));
      ASSERT_TRUE(check_certificate(read, model).valid) << check_certificate(read, model).reason;
      EXPECT_GT(read.distance, 0);
      // no feature pair is nearer than the certified clearance
      auto near = space.features_near(SlicedConfiguration{pose.x, pose.y, SlicedAngle{pose.tangent, false}}, Rational(1000));
      if (!pose.half_turn)
        for (const auto& n : near) EXPECT_LE(read.distance, n.distance_upper) << n.pair.label;
      Certificate larger = read;
      larger.distance = read.distance * 2 + 1;
      VerificationResult v = check_certificate(larger, model);
      EXPECT_FALSE(v.valid);
      EXPECT_NE(v.reason.find("less than the claimed"), std::string::npos) << v.reason;
      Certificate fixed_posed = read;
      fixed_posed.pose->part = "plate";
      EXPECT_FALSE(check_certificate(fixed_posed, model).valid);
    }
  }
  EXPECT_GT(interference, poses / 10);
  EXPECT_GT(clearance, poses / 10);
}

TEST(CertifyPlanar, PegInAHoleAtRandomPoses) {
  Random random(31);
  Model model = planar_model(rectangle(-20, -20, 20, 20) + ", " + rectangle(-6, -6, 6, 6), rectangle(-5, -4, 5, 4));
  check_model(model, random, 60);
}

TEST(CertifyPlanar, PartsWithArcsAtRandomPoses) {
  Random random(32);
  std::string round_hole = R"({ "circle": { "center": [0, 0], "radius": 7 } })";
  std::string stadium = R"({ "start": [-3, -2], "edges": [ { "line_to": [3, -2] }, { "arc_to": [3, 2], "center": [3, 0], "dir": "ccw" },
      { "line_to": [-3, 2] }, { "arc_to": [-3, -2], "center": [-3, 0], "dir": "ccw" } ] })";
  Model model = planar_model(rectangle(-20, -20, 20, 20) + ", " + round_hole, stadium);
  check_model(model, random, 60);
}

TEST(CertifyPlanar, BadPairsAreRefused) {
  Model model = planar_model(rectangle(-20, -20, 20, 20) + ", " + rectangle(-6, -6, 6, 6), rectangle(-5, -4, 5, 4));
  EXPECT_THROW(certify_planar_clearance(model, "peg", PlanarPose{"plate", 0, 0, 0, false}), GeometryError);
  EXPECT_THROW(certify_planar_clearance(model, "nothing", PlanarPose{"peg", 0, 0, 0, false}), ModelError);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Pin-in-slot poses of the film advance's follower (slide s, tangent of psi) against the cam (a
// rotating part at a random tangent), the film (translating, a random offset) and the pin (fixed):
// interference certified exactly where the oracle says the parts overlap, clearance exactly
// where they are apart; each certificate survives the JSON round trip and verifies; mutations
// (the witness moved off, the clearance enlarged, the slide out of its limits, the other part's
// position dropped, the pose given to the other part) are rejected with their reasons.
TEST(CertifyPinSlot, FilmAdvanceFollowerAtRandomPoses) {
  const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  const Part& follower = model.parts[*model.find_part("follower")];
  Random random(41);
  int interference = 0, clearance = 0, beyond_angle_limits = 0;
  for (const std::string other : {"cam", "film", "pin"}) {
    const Part& part = model.parts[*model.find_part(other)];
    for (int i = 0; i < 30; ++i) {
      PlanarPose pose{"follower", 0, 0, random_rational(random, Rational(-7, 100), Rational(7, 100), 97), false};
      pose.slide = random_rational(random, -6, 6, 29);
      std::map<std::string, ExactPosition> configuration;
      PartCoordinate coordinate;
      if (other == "cam") {
        ExactPosition p;
        p.value = random_rational(random, -3, 3, 13);
        configuration[other] = p;
        coordinate.value = p.value;
      } else if (other == "film") {
        ExactPosition p;
        p.value = random_rational(random, -20, 5, 7);
        p.is_offset = true;
        configuration[other] = p;
        coordinate = PartCoordinate{PartCoordinate::Kind::offset, p.value};
      }
      SCOPED_TRACE(other + " s=" + pose.slide->get_str() + " t=" + pose.tangent.get_str());
      // a pose beyond the follower's angle limits (+-8 deg, |t| > tan(4 deg) = 0.0699268...; the
      // generated tangents -0.07 + 0.14 p/q with q <= 97 come no closer than 7e-5 to it) is refused by
      // both producers (an input error naming the follower, as for a fixed-axis part: session 32)
      if (abs(pose.tangent) > Rational(69927, 1000000)) {
        EXPECT_THROW(certify_pin_slot_interference(model, other, pose, configuration), ModelError);
        EXPECT_THROW(certify_pin_slot_clearance(model, other, pose, configuration), ModelError);
        ++beyond_angle_limits;
        continue;
      }
      PartRelation r = part_overlap(part, part_placement(part, coordinate), follower,
                                    pin_slot_placement(follower, *pose.slide, pose.tangent))
                           .relation;
      auto overlap = certify_pin_slot_interference(model, other, pose, configuration);
      auto apart = certify_pin_slot_clearance(model, other, pose, configuration);
      EXPECT_EQ(bool(overlap), r == PartRelation::overlapping);
      EXPECT_EQ(bool(apart), r == PartRelation::apart);
      auto expect_rejected = [&](const Certificate& c, const std::string& reason) {
        VerificationResult v = check_certificate(c, model);
        EXPECT_FALSE(v.valid);
        EXPECT_NE(v.reason.find(reason), std::string::npos) << v.reason;
      };
      for (const auto* certificate : {&overlap, &apart}) {
        if (!*certificate) continue;
        Certificate read = read_certificate(write_certificate(**certificate));
        ASSERT_TRUE(read.pose && read.pose->slide);
        VerificationResult v = check_certificate(read, model);
        ASSERT_TRUE(v.valid) << v.reason;
        Certificate out_of_limits = read;
        out_of_limits.pose->slide = Rational(13, 2);
        expect_rejected(out_of_limits, "outside its limits");
        Certificate turned_too_far = read;   // 2 atan(71/1000) = 8.12 deg, beyond the 8 deg limit
        turned_too_far.pose->tangent = Rational(71, 1000) * (sgn(read.pose->tangent) < 0 ? -1 : 1);
        expect_rejected(turned_too_far, "is not certainly within its limits");
        if (!configuration.empty()) {
          Certificate dropped = read;
          dropped.configuration.clear();
          expect_rejected(dropped, "gives no position for moving part");
        }
        Certificate swapped = read;
        swapped.pose->part = other;
        EXPECT_FALSE(check_certificate(swapped, model).valid);
      }
      if (overlap) {
        ++interference;
        Certificate read = read_certificate(write_certificate(*overlap));
        if (read.witness_point) {
          read.witness_point->x += 1000;
          expect_rejected(read, "is not strictly inside");
        }
      }
      if (apart) {
        ++clearance;
        Certificate read = read_certificate(write_certificate(*apart));
        EXPECT_GT(read.distance, 0);
        read.distance = read.distance * 2 + 1;
        expect_rejected(read, "less than the claimed");
      }
    }
  }
  EXPECT_GT(interference, 5);
  EXPECT_GT(clearance, 5);
  EXPECT_GT(beyond_angle_limits, 0);
  // bad requests: no slide, a planar-pose producer with a slide
  PlanarPose no_slide{"follower", 0, 0, 0, false};
  EXPECT_THROW(certify_pin_slot_clearance(model, "pin", no_slide), GeometryError);
  PlanarPose slid = no_slide;
  slid.slide = Rational(1);
  EXPECT_THROW(certify_planar_clearance(model, "pin", slid), GeometryError);
}

}  // namespace
}  // namespace hipair
