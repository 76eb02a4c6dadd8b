// Kinematic analysis of the example mechanisms against their closed forms: eccentric cam with
// a flat follower, Scotch yoke, ratchet (indexes one way, blocks the other) and spur gears
// (tooth ratio, backlash against centre distance, jamming).
#include "kinematics_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace {

using namespace hipair;
using test::mentions;
constexpr double pi = std::numbers::pi;

Model example(const std::string& name) { return read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + name); }

KinematicsOptions options_for(const std::string& driver, int direction = 1, unsigned steps = 120) {
  KinematicsOptions options;
  options.driver = driver;
  options.direction = direction;
  options.steps_per_cycle = steps;
  return options;
}

// Eccentric circular cam (radius R = 25, centre at e = 8 from the shaft along the cam's x axis)
// under a flat face at height R + s, held down by the follower's return spring: the face rests
// on the cam's top point, R + e sin(theta), so s(theta) = e sin(theta) = e cos(theta - 90 deg)
// (the s = R + e cos(theta) of a cam whose eccentricity points along the follower axis, with
// the offset measured from the face's zero position).
TEST(KinematicsMechanisms, EccentricCamWithFlatFollower) {
  Model model = example("cam-follower.json");
  KinematicsResult result = analyze_kinematics(model, options_for("cam"));
  ASSERT_FALSE(result.jam);
  ASSERT_EQ(result.followers, std::vector<std::string>{"follower"});
  EXPECT_EQ(result.loads[0].kind, FollowerLoad::Kind::spring);
  const double e = 8;
  // positions are exact algebraic numbers at rational driver positions, converted to double
  // (|s| <= 8: 2e-15); the driver angle is 2 atan(t) in double (a few 1e-16 rad, times e = 8)
  // and e sin(theta) is evaluated in double: 1e-13 covers these with a margin of ~10
  const double tolerance = 1e-13;
  ASSERT_GT(result.samples.size(), 100u);
  for (const KinematicSample& sample : result.samples) {
    EXPECT_NEAR(sample.positions[0], e * std::sin(sample.driver), tolerance) << "theta " << sample.driver;
    // velocity ratio -P_u / P_v from the exact partial derivatives of the contact polynomial at
    // rationals within 2^-60 of the contact, divided and mapped from chart to angle in double
    // (relative error ~1e-15 of |ratio| <= 8, the chart factor 2 / (1 + t^2) likewise)
    EXPECT_NEAR(sample.velocity_ratios[0], e * std::cos(sample.driver), 1e-12) << "theta " << sample.driver;
    ASSERT_EQ(sample.contacts[0].size(), 1u);
    EXPECT_TRUE(mentions(sample.contacts[0], "flat face"));
  }
}

// Scotch yoke: crank pin radius 5 at r = 30 in a slot of width 10.4 (clearance c = 0.2 each
// side). Pushed by the left wall: s = r cos(theta) - r + c; by the right wall: s = r cos(theta)
// - r - c. The yoke dwells where the crank reverses it while the pin crosses the slot.
TEST(KinematicsMechanisms, ScotchYokeIsHarmonicWithLostMotionAtReversal) {
  Model model = example("scotch-yoke.json");
  KinematicsOptions options = options_for("crank");
  KinematicsResult result = analyze_kinematics(model, options);
  ASSERT_FALSE(result.jam);
  // positions (|x| <= 60 mm) exact, converted to double; r cos(theta) in double: 1e-12
  const double r = 30, c = 0.2, tolerance = 1e-12;
  std::size_t checked = 0;
  for (const KinematicSample& sample : result.samples) {
    if (sample.contacts[0].empty()) continue;
    double expected = r * std::cos(sample.driver) - r + (mentions(sample.contacts[0], "wall L") ? c : -c);
    EXPECT_NEAR(sample.positions[0], expected, tolerance) << "theta " << sample.driver;
    ++checked;
  }
  EXPECT_GT(checked, 100u);
  // drives start exactly where the pin has crossed the clearance
  std::vector<const KinematicPiece*> drives;
  for (const KinematicPiece& piece : result.pieces)
    if (piece.moving) drives.push_back(&piece);
  ASSERT_EQ(drives.size(), 2u);
  // an event is located in a certified driver interval of width <= event_resolution; the
  // closed forms are evaluated in double (acos near 1 amplifies rounding by ~10: 1e-14)
  const double located = result.event_resolution + 1e-14;
  EXPECT_LT(result.event_resolution, 1e-12);
  EXPECT_NEAR(drives[0]->start.value(), std::acos(1 - c / r), located);
  EXPECT_NEAR(drives[1]->start.value(), pi + std::acos(1 - 2 * c / r), located);
  // the drive ends at the turning point theta = pi, where the pin leaves the wall: the pin's
  // distance from the wall grows only as r (theta - pi)^2 / 2, but it is decided exactly
  EXPECT_NEAR(drives[0]->end.value(), pi, located);
  // reversing mid-drive: the pin must cross 2c before the other wall moves the yoke
  ASSERT_FALSE(result.reversals.empty());
  for (const ReversalCheck& check : result.reversals) {
    ASSERT_TRUE(check.follower_moved);
    double theta = check.driver;
    double back = std::sin(theta) > 0 ? theta - std::acos(std::cos(theta) + 2 * c / r)
                                      : std::acos(std::cos(theta) - 2 * c / r) - (2 * pi - theta);
    // the moving point is bisected to 2^-46 in the chart variable (angle: 2^-45), the reversal
    // angle is a grid point; the closed form is evaluated in double
    EXPECT_NEAR(check.lost_motion, std::abs(back), std::ldexp(1.0, -44) + 1e-13) << "reversing at " << theta;
  }
}

// Ratchet: counter-clockwise the pawl rides up each tooth back and snaps into the next gap
// (12 teeth: 12 snaps per turn); clockwise the tooth face locks against the pawl nose.
TEST(KinematicsMechanisms, RatchetIndexesOneWayAndBlocksTheOther) {
  Model model = example("ratchet.json");
  KinematicsResult forward = analyze_kinematics(model, options_for("wheel", +1));
  ASSERT_FALSE(forward.jam) << forward.jam->description;
  std::size_t snaps = std::count_if(forward.events.begin(), forward.events.end(),
                                    [](const KinematicEvent& e) { return e.kind == KinematicEvent::Kind::drop; });
  EXPECT_EQ(snaps, 12u);
  for (const KinematicSample& sample : forward.samples) EXPECT_FALSE(sample.contacts[0].empty());   // spring holds it

  KinematicsResult backward = analyze_kinematics(model, options_for("wheel", -1));
  ASSERT_TRUE(backward.jam);
  EXPECT_LT(backward.reached, 0.0);
  EXPECT_GT(backward.reached, -2 * pi / 12);   // within one tooth
  EXPECT_TRUE(mentions(backward.jam->before, "tooth"));
  EXPECT_TRUE(mentions(backward.jam->before, "pawl nose"));
  std::string report = kinematics_text_report(backward);
  EXPECT_NE(report.find("BLOCKED"), std::string::npos);
  EXPECT_NE(report.find("pawl nose"), std::string::npos);
}

// 10:20 spur gears, module 2, circular-arc flanks through the pitch point (radius r sin 20 deg),
// 0.1 mm thinner than half the pitch (backlash). Few teeth keep the tests fast: the slices of a
// gear pair carry a contact curve for every pair of flanks that can meet.
constexpr int pinion_teeth = 10, gear_teeth = 20;

std::string gear_model(const std::string& centre_distance, const std::string& runout = "0") {
  return R"({ "hipair": 1, "name": "spur-gears", "units": { "length": "mm", "angle": "deg" },
    "parameters": { "center-distance": { "nominal": )" + centre_distance + R"( }, "runout": { "nominal": )" + runout + R"( } },
    "parts": [
      { "name": "pinion", "motion": { "rotation": { "pivot": [0, 0] } },
        "features": [ { "spur_gear": { "center": [0, 0], "teeth": 10, "pitch_radius": 10, "addendum": 2,
                        "dedendum": 2.5, "tooth_thickness": 3.04, "flank_radius": 3.42 } } ] },
      { "name": "gear", "motion": { "rotation": { "pivot": ["center-distance", "runout"] } },
        "features": [ { "spur_gear": { "center": ["center-distance", 0], "teeth": 20, "pitch_radius": 20,
                        "addendum": 2, "dedendum": 2.5, "tooth_thickness": 3.04, "flank_radius": 6.84,
                        "phase": 9 } } ] } ],
    "pairs": [ { "parts": ["pinion", "gear"] } ] })";
}

// Once a pinion flank pushes a gear flank, the mesh repeats every pinion tooth pitch with the
// gear one gear tooth pitch further: over two whole mesh cycles the gear turns exactly
// -(10/20) of the pinion's travel.
TEST(KinematicsMechanisms, SpurGearsTurnAtTheToothRatio) {
  Model model = read_model(gear_model("30"));
  KinematicsOptions options = options_for("pinion");
  const double pitch = 2 * pi / pinion_teeth;
  // 90 deg on a grid of 3 deg (120 steps per turn): grid points two pitches (72 deg) apart
  options.steps_per_cycle = 120;
  options.range = std::make_pair(Rational(0), Rational(pi / 2));
  options.reversal = false;
  KinematicsResult result = analyze_kinematics(model, options);
  ASSERT_FALSE(result.jam) << result.jam->description;
  double rounding = 0;   // largest rounding bound of the model (template tooth placement)
  for (const Rounding& r : model.roundings) rounding = std::max(rounding, r.bound.get_d());
  ASSERT_GT(rounding, 0.0);
  ASSERT_LT(rounding, 1e-9);
  const double tolerance = 3 * rounding + 1e-14;
  double first_contact = 1e9;
  for (const KinematicEvent& event : result.events) first_contact = std::min(first_contact, event.at.value());
  ASSERT_LT(first_contact, 0.05);
  const std::vector<KinematicSample>& samples = result.samples;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].driver < first_contact + 0.01) continue;
    // the sample nearest to two pitches later (grid points are rational half-tangents rounded
    // to 2^-32, so the two drivers differ from exactly two pitches by a few 1e-10 rad)
    std::size_t j = i;
    while (j + 1 < samples.size() && samples[j].driver < samples[i].driver + 2 * pitch - 1e-6) ++j;
    if (std::abs(samples[j].driver - samples[i].driver - 2 * pitch) > 1e-6) continue;
    double mismatch = samples[j].driver - samples[i].driver - 2 * pitch;
    double turned = samples[j].positions[0] - samples[i].positions[0];
    // periodicity: g(d + 2 pitch) = g(d) - 2 * 2 pi / 20, exact up to the model's roundings:
    // every tooth is placed through a rounded half-angle tangent and rounded points (bound B
    // each, rad or mm; levers >= 1 mm). Two configurations, each fixed by one pinion tooth
    // (seen by the gear at ratio 1/2) and one gear tooth: 3 B. The grid mismatch (~1e-10 rad)
    // is corrected to first order with the velocity ratio at j (second order ~1e-20); double
    // rounding of positions and driver angles ~1e-15.
    double corrected = turned - samples[j].velocity_ratios[0] * mismatch;
    EXPECT_NEAR(corrected, -2 * 2 * pi / gear_teeth, tolerance) << "from driver " << samples[i].driver;
    EXPECT_NEAR(corrected / (2 * pitch), -double(pinion_teeth) / gear_teeth, tolerance / (2 * pitch));
    ++checked;
  }
  EXPECT_GE(checked, 5u);
}

TEST(KinematicsMechanisms, GearBacklashGrowsWithCentreDistance) {
  double previous = 0;
  for (const char* distance : {"29.9", "30", "30.3"}) {
    Model model = read_model(gear_model(distance));
    KinematicsOptions options = options_for("pinion", 1, 60);   // play sampled every 6 deg
    options.range = std::make_pair(Rational(0), Rational(pi / pinion_teeth * 2));   // one pinion tooth pitch
    options.reversal = false;
    KinematicsResult result = analyze_kinematics(model, options);
    ASSERT_FALSE(result.jam) << distance;
    ASSERT_EQ(result.play.size(), 1u);
    EXPECT_FALSE(result.play[0].unbounded);
    EXPECT_GT(result.play[0].minimum, previous) << "centre distance " << distance;
    previous = result.play[0].minimum;
  }
}

TEST(KinematicsMechanisms, GearsJamWhereTheCentreDistanceShrinks) {
  // the gear turns about a pivot 0.5 mm off its centre: the mesh tightens as it turns until a
  // gear tooth is squeezed between two pinion teeth (about 61 deg of pinion travel)
  Model model = read_model(gear_model("30", "0.5"));
  KinematicsOptions options = options_for("pinion", 1, 90);
  options.range = std::make_pair(Rational(0), Rational(3, 2));
  options.reversal = false;
  KinematicsResult result = analyze_kinematics(model, options);
  ASSERT_TRUE(result.jam);
  EXPECT_TRUE(result.initial_interference.empty());
  EXPECT_GT(result.reached, 0.9);
  EXPECT_LT(result.reached, 1.2);
  // both contacts that close the gear's play are named: the pushing flank and the opposite one
  EXPECT_TRUE(mentions(result.jam->before, "flank L"));
  EXPECT_TRUE(mentions(result.jam->before, "flank R"));
  // the play shrinks to (almost) nothing before the jam
  EXPECT_LT(result.samples.back().play[0], result.samples.front().play[0] / 10);
  std::string report = kinematics_text_report(result);
  EXPECT_NE(report.find("BLOCKED"), std::string::npos);
  EXPECT_NE(report.find("Blocking contacts: pinion tooth"), std::string::npos);
}

// A centre distance so small that the pinion's tips reach into the gear's root circle (tip
// radius 12 + gear root radius 17.5 = 29.5): the gears overlap at the initial angles.
TEST(KinematicsMechanisms, GearsThatCannotBeAssembledAreReported) {
  Model model = read_model(gear_model("29.5"));
  KinematicsOptions options = options_for("pinion");
  options.range = std::make_pair(Rational(0), Rational(1, 2));
  KinematicsResult result = analyze_kinematics(model, options);
  EXPECT_FALSE(result.initial_interference.empty());
  ASSERT_TRUE(result.jam);
  EXPECT_EQ(result.reached, 0.0);
  EXPECT_NE(kinematics_text_report(result).find("INTERFERENCE"), std::string::npos);
}

}  // namespace
