// Kinematic analysis of the escapement (examples/models/escapement.json) driven clockwise, as
// its model torque turns the escape wheel. After the entry pallet lifts the anchor and the
// tooth drops off it (driver +0.835 deg), the wheel turns freely until tooth 2 reaches the
// radius of the exit pallet's locking face (driver -0.835 deg: the mirror of the drop, since the
// tooth tips at +a and -a are mirror images and the pallets are symmetric). The locking face is
// concentric with the anchor pivot, so the tooth cannot turn the anchor: the wheel locks. The
// driver must stop there, blamed on the anchor (the lock), not on the balance: an engine that
// pushes the anchor through the wall of blocked C-space moves the fork by 1.87 deg in a zero
// driver step and then reports a fictitious squeeze of the balance between the slot walls.
#include <hipair/certificate.hpp>
#include "kinematics_test_support.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

namespace {

using namespace hipair;
using test::mentions;
using test::example_text;
constexpr double pi = std::numbers::pi;
constexpr double degree = pi / 180;

// `ten_thousandths` ten-thousandths of a degree, in rad, through a rational pi bound
// (the certify API rounds the half-angle tangent exactly and records the error)
Rational angle_of(long ten_thousandths) {
  return Rational(ten_thousandths, 10000) * Rational(pi / 180);
}

bool overlap(const Model& model, long wheel, long anchor) {
  std::map<std::string, ExactPosition> at{{"escape-wheel", exact_position_from_angle(angle_of(wheel))},
                                          {"anchor", exact_position_from_angle(angle_of(anchor))}};
  return certify_interference(model, "escape-wheel", "anchor", at).has_value();
}

// The lock is a vertical wall of the wheel:anchor C-space: between wheel -0.8353 and -0.8354
// deg every anchor angle from -13 deg to -2.1 deg (the exit pallet in the wheel's path) becomes
// blocked at once, while -1.9 deg (the exit impulse face) stays free. Certified overlaps.
TEST(KinematicsEscapement, ExitLockingFaceIsAWallOfTheCSpace) {
  Model model = read_model(example_text("escapement.json"));
  for (long anchor : {-130000L, -80000L, -38710L, -21000L}) {
    EXPECT_FALSE(overlap(model, -8353, anchor)) << anchor;
    EXPECT_TRUE(overlap(model, -8354, anchor)) << anchor;
  }
  EXPECT_FALSE(overlap(model, -8354, -19000));
}

TEST(KinematicsEscapement, ClockwiseRunLocksOnTheExitPalletNotOnTheBalance) {
  Model model = read_model(example_text("escapement.json"));
  KinematicsOptions options;
  options.driver = "escape-wheel";
  options.direction = -1;
  options.steps_per_cycle = 720;
  options.reversal = false;
  KinematicsResult result = analyze_kinematics(model, options);
  ASSERT_TRUE(result.jam.has_value());
  const KinematicEvent& jam = *result.jam;
  // where: the mirror of the drop off the entry pallet (certified width 2^-46 of the chart)
  EXPECT_NEAR(jam.at.value() / degree, -0.8353738296657, 1e-9);
  double drop = 0;
  for (const KinematicEvent& event : result.events)
    if (event.part == "anchor" && event.kind == KinematicEvent::Kind::contact_end) drop = event.at.value();
  EXPECT_NEAR(drop / degree, 0.8353738296657, 1e-9);
  // who: the anchor, which cannot be turned by a tooth on its locking face (it would have to jump)
  EXPECT_EQ(jam.part, "anchor") << jam.description;
  EXPECT_NE(jam.description.find("would have to jump"), std::string::npos) << jam.description;
  // a jump is told from a contact change by a threshold: the reason says so (session 49)
  EXPECT_NE(jam.description.find("a jump by threshold, approximate"), std::string::npos) << jam.description;
  // the wall it ran into is named first: the tip of tooth 2 on the exit pallet's locking face
  ASSERT_FALSE(jam.before.empty());
  EXPECT_EQ(jam.before.front().label,
            "escape-wheel corner of tooth 2 face and tooth 2 back / anchor exit locking face (vertex on arc)");
  EXPECT_EQ(jam.before.front().pair, "escape-wheel:anchor");
  EXPECT_FALSE(mentions(jam.before, "fork slot")) << jam.description;
  // nothing moved during the drop: the anchor stays at -3.871 deg, the balance at 18.738 deg
  const KinematicSample* first = nullptr;
  std::size_t inside = 0;
  for (const KinematicSample& sample : result.samples) {
    if (!(std::abs(sample.driver) < 0.83 * degree)) continue;
    ++inside;
    if (!first) first = &sample;
    EXPECT_EQ(sample.positions, first->positions) << sample.driver / degree;
  }
  EXPECT_GE(inside, 3u);
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->positions[0] / degree, -3.871033029, 1e-8);
  EXPECT_NEAR(first->positions[1] / degree, 18.738133799, 1e-8);
}

}  // namespace
