// Runs that stop after they began, with their state (session 70, stop70; the CLI's side:
// tests/cli/run_simulate_stop_tests.sh):
//  - a part at its own motion limit (a translating part's "limits", not a contact) stops the run
//    with a SimulationLimit naming the part and the limit, the state published at the limit, at
//    the closed-form time. Until session 70: "cannot be moved off its contact (a jammed contact
//    change)", a NumericError naming no limit, the state that of the step before;
//  - a planar jam against a speed-profile driver (a prescribed driver, its velocity doubles) is
//    labelled approximate; base69's SimulationJam defaulted `exact` to true and the planar
//    simulator left it so (and called it a "constant-speed" driver);
//  - (session 71, jam71) a planar jam of a constant-speed driver and a speed profile in a model
//    timed in milliseconds: both drivers' shares in the model's time unit.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>
#include <hipair/simulation_stop.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "jam_test_support.hpp"
#include "simulation_planar_support.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

nlohmann::json example(const std::string& name) {
  std::ifstream in(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models" / name);
  return nlohmann::json::parse(in);
}

// cam-drive.json's eccentric cam (e = 8 mm) at a constant w rad/s, the follower's limits
// [-12, L] mm: riding the cam, its offset e sin(w t) reaches L at t* = asin(L / e) / w.
Model cam_to_limit(const std::string& limit, double w) {
  nlohmann::json j = example("cam-drive.json");
  EXPECT_EQ(j["parameters"]["eccentricity"]["nominal"], 8);
  j["parameters"]["cam-speed"]["nominal"] = w;
  for (nlohmann::json& part : j["parts"])
    if (part["name"] == "follower") part["motion"]["translation"]["limits"] = {-12, std::stod(limit)};
  return read_model(j.dump(), "cam-drive with a limit");
}

using test::pusher_into_wall_json;

using test::run_to_jam;

// Generated: limits L = 1.5 .. 6.5 mm (three decimals: printed as given), w = 20 .. 150 rad/s
// (below the critical 187 rad/s: the follower rides the cam). The stop at t* within the jam
// tests' tolerance (1e-9 of the 33 mm reach over the lift's rate e w cos(w t*)); the state
// published is the stop's (its time, the follower at L within that reach), the limit named.
TEST(SimulationStop, AFollowerLiftedToItsOwnMotionLimitStopsThereAtTheClosedFormTime) {
  const std::uint64_t seed = test::test_seed(7001);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  Lcg rng{seed};
  for (int trial = 0; trial < 4; ++trial) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << rng.uniform(1.5, 6.5);
    const std::string limit = text.str();
    const double L = std::stod(limit), w = rng.uniform(20, 150), e = 8;
    SCOPED_TRACE("L " + limit + " mm, w " + num(w) + " rad/s");
    const Model model = cam_to_limit(limit, w);
    Simulation sim = Simulation::create(model, SimulationOptions{});
    const double expected = std::asin(L / e) / w, tol = 1e-9 * 33 / (e * w * std::cos(w * expected));
    std::optional<double> stopped;
    std::string message, part, which;
    try {
      sim.run_until(2 * expected);
    } catch (const SimulationLimit& stop) {
      stopped = stop.time();
      message = stop.what();
      part = stop.part();
      which = stop.limit();
    }
    ASSERT_TRUE(stopped.has_value()) << "no stop at a limit by " << 2 * expected << " s (t = " << sim.state().time << " s)";
    EXPECT_NEAR(*stopped, expected, tol);
    std::cout << "  stopped at " << num(*stopped) << " s, closed form " << num(expected) << " s: "
              << (*stopped - expected) / tol << " of the tolerance\n";
    EXPECT_EQ(sim.state().time, *stopped);
    const std::size_t follower = *model.find_part("follower");
    EXPECT_NEAR(sim.state().position[follower], L, 1e-9 * 33);
    EXPECT_EQ(part, "follower");
    // (the limit's numbers are the doubles' default stream form: three decimals print as given)
    std::string shown = limit;
    while (shown.back() == '0') shown.pop_back();
    if (shown.back() == '.') shown.pop_back();
    EXPECT_EQ(which, "upper limit " + shown + " mm of [-12, " + shown + "]");
    EXPECT_NE(message.find("translating part 'follower' (/parts/1/motion) is at "), std::string::npos) << message;
    EXPECT_NE(message.find("a motion limit"), std::string::npos) << message;   // (the nudge's stop, or leaving the C-space at the limit)
    for (const SimulationEvent& ev : sim.events()) EXPECT_LE(ev.time, *stopped);
  }
}

// pusher-blocks.json's pusher carrying the 6 mm block into a wall at x = W (the jam tests'
// model), its driver a speed profile at the constant V: the jam at t* = (W - 6 + 35) / V as with
// a constant-speed driver, but found on the profile's velocity doubles: approximate, and said so.
TEST(SimulationStop, APlanarJamAgainstASpeedProfileIsLabelledApproximate) {
  const std::uint64_t seed = test::test_seed(7002);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  Lcg rng{seed};
  for (int trial = 0; trial < 3; ++trial) {
    const double v = rng.uniform(20, 400), wall = rng.uniform(50, 80);
    SCOPED_TRACE("V " + num(v) + " mm/s, wall " + num(wall) + " mm");
    nlohmann::json j = pusher_into_wall_json(wall);
    j["simulation"]["drivers"] = nlohmann::json::array(
        {{{"part", "pusher"}, {"law", "speed_profile"}, {"profile", {{0, {{"x", v}}}, {1000, {{"x", v}}}}}}});
    const Model model = read_model(j.dump(), "pusher into a wall, profile");
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(model, SimulationOptions{});
    const double expected = (wall - 6 + 35) / v, tol = 1e-10 * 100 / v;
    const auto [jam, message, exact] = run_to_jam(sim, 2 * expected);
    ASSERT_TRUE(jam.has_value()) << "no jam by " << 2 * expected << " s (t = " << sim.state().time << " s)";
    EXPECT_NEAR(*jam, expected, tol);
    EXPECT_FALSE(exact);
    EXPECT_NE(message.find("the prescribed driver 'pusher' jams 'block' (a jam)"), std::string::npos) << message;
    EXPECT_NE(message.find("(approximate (found exactly on the exact contact normals and the prescribed drivers' "
                           "velocity doubles)"),
              std::string::npos)
        << message;
  }
}

// Session 71 (jam71; stop70's review, M1): a planar jam in a model whose time unit is the
// millisecond, with one constant-speed driver and one speed profile. pusher-blocks.json's pusher
// (constant V mm/ms) carries the 6 mm block into the wall, the wall now planar and driven away by
// a speed profile at the constant U = r V mm/ms (r 0.1 .. 0.8): the block meets the receding wall
// and the pusher cannot give way — a jam at t* = (W - 6 + 35) / (V - U) ms (the pusher's face at
// -35 + V t, the block's right face 6 mm ahead, the wall's face at W + U t). The locking LP must
// take both drivers' shares in one time unit: base70 took the profile's velocity double per
// internal time unit (seconds: U / 0.001 = 1000 U mm/s) next to the pusher's V mm/ms, found the
// wall receding faster than the pusher closes (1000 U > V) and no jam — the run ended with the
// impact problem's error instead. The verdict: approximate (the profile's velocity doubles), the
// drivers "prescribed".
TEST(SimulationStop, APlanarJamOfAConstantAndAProfileDriverInMillisecondsTakesBothInOneTimeUnit) {
  const std::uint64_t seed = test::test_seed(7103);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  Lcg rng{seed};
  for (int trial = 0; trial < 3; ++trial) {
    const double v = rng.uniform(0.05, 0.4), u = v * rng.uniform(0.1, 0.8), wall = rng.uniform(50, 80);
    SCOPED_TRACE("V " + num(v) + " mm/ms, U " + num(u) + " mm/ms, wall " + num(wall) + " mm");
    nlohmann::json j = pusher_into_wall_json(wall);
    j["parts"][0]["motion"] = {{"planar", {{"pivot", {0, 0}}}}};
    j["parts"][0]["initial"] = {{"x", 0}, {"y", 0}};
    j["simulation"]["units"]["time"] = "ms";
    j["simulation"]["drivers"] = nlohmann::json::array(
        {{{"part", "pusher"}, {"speed", {{"x", v}}}},
         {{"part", "wall"}, {"law", "speed_profile"}, {"profile", {{0, {{"x", u}}}, {1e6, {{"x", u}}}}}}});
    const Model model = read_model(j.dump(), "pusher into a receding wall, ms");
    PlanarSystemSimulation sim = PlanarSystemSimulation::create(model, SimulationOptions{});
    // (the tolerance: 1e-6 mm of gap, 10^3 x the model's accuracy 1e-10 over the 100 mm travel as
    // in run_simulate_jam_tests.sh, over the closing speed V - U: the wall's frame, in which the
    // pair's C-space is built, moves, and the contact is found up to ~1e-6 mm early — seeds 1..4:
    // at most 0.09 of it)
    const double expected = (wall - 6 + 35) / (v - u), tol = 1e3 * 1e-10 * 100 / (v - u);
    const auto [jam, message, exact] = run_to_jam(sim, 2 * expected);
    ASSERT_TRUE(jam.has_value()) << "no jam by " << 2 * expected << " ms (t = " << sim.state().time << " ms)";
    EXPECT_NEAR(*jam, expected, tol);
    std::cout << "  jam at " << num(*jam) << " ms, closed form " << num(expected) << " ms: " << (*jam - expected) / tol
              << " of the tolerance\n";
    EXPECT_FALSE(exact);
    // (both drivers close the lock, in either order: "the prescribed drivers 'pusher' and 'wall' jam 'block'")
    const bool named = message.find("the prescribed drivers 'pusher' and 'wall' jam 'block' (a jam)") != std::string::npos ||
                       message.find("the prescribed drivers 'wall' and 'pusher' jam 'block' (a jam)") != std::string::npos;
    EXPECT_TRUE(named) << message;
    EXPECT_NE(message.find("(wall face)"), std::string::npos) << message;
    EXPECT_NE(message.find("(pusher face)"), std::string::npos) << message;
    EXPECT_NE(message.find("(approximate (found exactly on the exact contact normals and the prescribed drivers' "
                           "velocity doubles)"),
              std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace hipair
