// Kinematic analysis of an assembly of three moving parts in a chain (cam -> follower -> lever,
// examples/models/cam-follower-lever.json): each part's position through the chain against its
// closed form, and a jam caused by the last part of the chain stopping the driver.
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

// Geometry of the example: cam circle radius 25 centred 8 from the shaft; the follower's flat
// face rests on it (held down by its spring), so its offset is s = 8 sin(theta). The stem tip is
// a circle of radius 5 centred at (0, 80 + s); the lever turns about (60, 95), its underside 5
// below the pivot, pressed onto the tip by a counter-clockwise torque. Tangency of the tip
// circle and the underside line: -60 sin(a) + (15 - s) cos(a) = 10.
double lever_angle(double s) {
  double b = 15 - s, r = std::hypot(60.0, b);
  return std::acos(10 / r) - std::atan2(60.0, b);
}

// the follower offset at which the lever reaches angle a
double offset_at_lever_angle(double a) { return 15 - (10 + 60 * std::sin(a)) / std::cos(a); }

KinematicsOptions cam_options() {
  KinematicsOptions options;
  options.driver = "cam";
  options.steps_per_cycle = 240;
  return options;
}

TEST(KinematicsAssembly, EachPartFollowsTheChainClosedForm) {
  Model model = read_model(example_text("cam-follower-lever.json"));
  KinematicsResult result = analyze_kinematics(model, cam_options());
  ASSERT_FALSE(result.jam) << result.jam->description;
  EXPECT_TRUE(result.initial_interference.empty());
  ASSERT_EQ(result.followers, (std::vector<std::string>{"follower", "lever"}));
  ASSERT_GT(result.samples.size(), 200u);
  // positions are exact algebraic numbers at rational driver positions, converted to double;
  // the closed forms are evaluated in double from the double driver angle (errors ~1e-15 in s,
  // amplified by ds/dtheta <= 8 and da/ds ~ 1/60): 1e-12 leaves a margin of ~100
  for (const KinematicSample& sample : result.samples) {
    double s = 8 * std::sin(sample.driver);
    EXPECT_NEAR(sample.positions[0], s, 1e-12) << "cam " << sample.driver;
    EXPECT_NEAR(sample.positions[1], lever_angle(s), 1e-12) << "cam " << sample.driver;
    ASSERT_EQ(sample.contacts[1].size(), 1u);
    EXPECT_TRUE(mentions(sample.contacts[1], "stem tip"));
  }
  // the lever sweeps between its angles at the follower's extremes
  double lowest = 1e9, highest = -1e9;
  for (const KinematicPiece& piece : result.pieces)
    if (piece.part == "lever") {
      lowest = std::min(lowest, piece.lowest_position);
      highest = std::max(highest, piece.highest_position);
    }
  EXPECT_NEAR(lowest, lever_angle(8), 1e-12);    // sampled at theta = 90 deg exactly on the grid
  EXPECT_NEAR(highest, lever_angle(-8), 1e-12);  // theta = 270 deg
  EXPECT_TRUE(std::none_of(result.contacts.begin(), result.contacts.end(), [](const ContactUse& u) { return u.unintended; }));
}

// Raising the lever's lower limit to -2 deg: when the follower rises far enough the lever is
// caught between the stem tip and its limit, and the whole chain, back to the cam, is blocked.
TEST(KinematicsAssembly, TheLastPartOfTheChainBlocksTheDriver) {
  std::string text = example_text("cam-follower-lever.json");
  const std::string nominal = "\"nominal\": -30,";
  ASSERT_NE(text.find(nominal), std::string::npos);
  text.replace(text.find(nominal), nominal.size(), "\"nominal\": -2,");
  Model model = read_model(text);
  KinematicsResult result = analyze_kinematics(model, cam_options());
  ASSERT_TRUE(result.jam);
  EXPECT_EQ(result.jam->part, "lever");
  EXPECT_TRUE(mentions(result.jam->before, "stem tip"));
  EXPECT_TRUE(std::any_of(result.jam->before.begin(), result.jam->before.end(), [](const ContactLabel& c) { return c.limit; }));
  // closed form: s* = offset_at_lever_angle(-2 deg), theta* = asin(s* / 8). The limit the
  // analysis uses is -2 deg rounded by the model (bound B rad), then its chart edge t = tan(a/2)
  // rounded outward to the 1e-12 grid plus one step (src/curves/contact_curves.cpp: up to 2e-12
  // in t, 4e-12 in angle): at most 5 B in the lever angle. That moves s* by up to 60 * 5 B
  // (ds/da ~ 60 mm/rad) and theta* by that over ds/dtheta = 8 cos(theta*); plus the certified
  // event width.
  double bound = 0;
  for (const Rounding& r : model.roundings) bound = std::max(bound, r.bound.get_d());
  double limit = -2 * pi / 180;
  double s_star = offset_at_lever_angle(limit);
  double theta_star = std::asin(s_star / 8);
  double tolerance = result.event_resolution + 61 * 5 * bound / (8 * std::cos(theta_star)) + 1e-13;
  EXPECT_LT(tolerance, 1e-9);
  EXPECT_NEAR(result.reached, theta_star, tolerance);
  EXPECT_NEAR(result.jam->at.value(), theta_star, tolerance);
  std::string report = kinematics_text_report(result);
  EXPECT_NE(report.find("BLOCKED"), std::string::npos);
  EXPECT_NE(report.find("motion limit of lever"), std::string::npos);
}

}  // namespace
