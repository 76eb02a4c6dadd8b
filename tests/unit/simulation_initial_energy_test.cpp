// A simulation whose initial state's energy is beyond the doubles is bad input (session 72,
// jam72; Issue 11): each simulator's create() refuses it with a ModelError at the pointer of the
// datum that puts it there (src/simulation/initial_energy.hpp) — no step of it can be computed.
// Until session 72 the run computed one step and stopped (exit 3) writing its initial state with
// "energy": null; base72's create() accepts every case below.
//
// Generated cases over the four simulators (the planar part ladder.json, several planar parts
// pushed-block.json, the pin-slot part of tests/data/simulation/pin-slot-cam.json, the fixed-axis
// translating follower of cam-drive.json): one datum — an initial velocity component, or gravity
// along x on the ladder (1 kg) — at 10^k. The oracle is the term's closed form in long double
// (m v^2 / 2, v^2 itself, m g x; x86's long double reaches 1e4932): k is drawn either where it is
// beyond the doubles' 1.8e308 by a factor 4 at least (refused at that datum's pointer), or
// within them by 1e6 at least (created). The ladder's velocity cases carry a distractor, gravity
// along y at 10^j with j > k where the velocity's term overflows: the largest velocity or load
// given (session 65's largest_motion_datum) is then gravity, whose term m g y stays finite — the
// refusal must name the velocity.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/pin_slot_simulation.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "simulation_planar_support.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <cfloat>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

namespace hipair {
namespace {

using planar_test::Lcg;

nlohmann::json load(const std::string& relative) {
  std::ifstream in(std::filesystem::path(HIPAIR_SOURCE_DIR) / relative);
  return nlohmann::json::parse(in);
}

// The pointer of the ModelError create() throws, or nullopt where it creates the simulation.
template <class Sim>
std::optional<std::string> refusal(const nlohmann::json& j, std::string* message) {
  const Model model = read_model(j.dump(), "initial energy");
  try {
    Sim sim = Sim::create(model, SimulationOptions{});
    EXPECT_TRUE(std::isfinite(sim.energy()));
    return std::nullopt;
  } catch (const ModelError& e) {
    *message = e.what();
    return e.pointer();
  }
}

struct Case {
  nlohmann::json model;
  std::string pointer;   // the datum
  long double term;      // the oracle: the term's magnitude (internal units: s, kg, mm)
  std::function<std::optional<std::string>(const nlohmann::json&, std::string*)> create;
};

TEST(SimulationInitialEnergy, AnInitialStateBeyondTheDoublesIsRefusedAtItsDatum) {
  const std::uint64_t seed = test::test_seed(7201);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  Lcg rng{seed};
  const nlohmann::json ladder = load("examples/models/ladder.json"), pushed = load("examples/models/pushed-block.json"),
                       pin_slot = load("tests/data/simulation/pin-slot-cam.json"),
                       cam = load("examples/models/cam-drive.json");
  ASSERT_EQ(ladder["parts"][1]["dynamics"]["mass"], 0.05);
  ASSERT_EQ(pushed["parts"][2]["dynamics"]["mass"], 0.02);
  ASSERT_EQ(pin_slot["parts"][1]["dynamics"]["mass"], 0.01);
  ASSERT_EQ(cam["parts"][1]["dynamics"]["mass"], 0.05);
  const long double ladder_x = ladder["parts"][1]["initial"]["x"].get<double>();
  int refused = 0, created = 0, distracted = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const bool overflow = trial % 2 == 0;
    // 10^k: overflowing (the term >= 1e318) or not (<= 1e302)
    const double k = overflow ? rng.uniform(160, 300) : rng.uniform(1, 150);
    const double sign = rng.uniform(0, 1) < 0.5 ? 1 : -1;
    const double value = sign * std::pow(10.0, k);
    const long double v = value;
    Case c;
    switch (trial / 2 % 6) {
      case 0:
      case 1: {   // the ladder's velocity component, a distractor along y
        static const char* keys[] = {"x", "y", "angle"};
        const std::string key = keys[static_cast<int>(rng.uniform(0, 3) - 1e-9)];
        c.model = ladder;
        c.model["simulation"]["velocities"]["ladder"][key] = value;
        c.pointer = "/simulation/velocities/ladder/" + key;
        // (v^2 itself is formed first: vx vx + vy vy, omega omega)
        c.term = std::max(v * v, 0.5L * (key == "angle" ? 20.841667L : 0.05L) * v * v);
        if (overflow) {
          // gravity along y at 10^j, j in (k, 300]: its m g y (y = 44.56 mm) stays below 1e300
          const double j = rng.uniform(k + 0.5, 300.5);
          c.model["simulation"]["gravity"][1] = -std::pow(10.0, j);
          ++distracted;
        }
        c.create = refusal<PlanarSimulation>;
        break;
      }
      case 2: {   // gravity along x on the ladder made 1 kg: m g x = 22.68 g (m g itself within the
                  // doubles: the reader's load check, which refuses m g beyond them, is not reached)
        const double b = overflow ? rng.uniform(307.5, 308.2) : rng.uniform(200, 300);
        const double g = sign * std::pow(10.0, b);
        c.model = ladder;
        c.model["parts"][1]["dynamics"]["mass"] = 1;
        c.model["simulation"]["gravity"][0] = g;
        c.pointer = "/simulation/gravity/0";
        c.term = std::abs(static_cast<long double>(g)) * ladder_x;
        c.create = refusal<PlanarSimulation>;
        break;
      }
      case 3: {   // the pushed block among several planar parts
        c.model = pushed;
        c.model["simulation"]["velocities"]["block"] = {{"x", value}};
        c.pointer = "/simulation/velocities/block/x";
        c.term = std::max(v * v, 0.5L * 0.02L * v * v);
        c.create = refusal<PlanarSystemSimulation>;
        break;
      }
      case 4: {   // the pin-slot follower's slide
        c.model = pin_slot;
        c.model["simulation"]["velocities"] = {{"follower", {{"slide", value}}}};
        c.pointer = "/simulation/velocities/follower/slide";
        c.term = std::max(v * v, 0.5L * 0.01L * v * v);
        c.create = refusal<PinSlotSimulation>;
        break;
      }
      default: {   // the fixed-axis translating follower
        c.model = cam;
        c.model["simulation"]["velocities"] = {{"follower", value}};
        c.pointer = "/simulation/velocities/follower";
        c.term = std::max(v * v, 0.5L * 0.05L * v * v);
        c.create = refusal<Simulation>;
        break;
      }
    }
    SCOPED_TRACE("trial " + std::to_string(trial) + ": " + c.pointer + ", term " + std::to_string(std::log10(c.term)));
    // the oracle's margins (far beyond the doubles' rounding): beyond the doubles by a factor 4, or
    // within them by 1e6
    const bool beyond = c.term > 4.0L * static_cast<long double>(DBL_MAX);
    ASSERT_TRUE(beyond || c.term < 1e-6L * static_cast<long double>(DBL_MAX)) << "a case within the margin";
    ASSERT_EQ(beyond, overflow);
    std::string message;
    const std::optional<std::string> pointer = c.create(c.model, &message);
    if (beyond) {
      ASSERT_TRUE(pointer.has_value()) << "created";
      EXPECT_EQ(*pointer, c.pointer) << message;
      EXPECT_EQ(message.rfind(c.pointer + ": the initial state's energy is not finite", 0), 0u) << message;
      EXPECT_NE(message.find("nothing was run or written"), std::string::npos) << message;
      // (session 73, jam73: what cannot be computed is the energy, not every step)
      EXPECT_NE(message.find("so the energy the run publishes with every state and checks at every step's end cannot be "
                             "computed"),
                std::string::npos)
          << message;
      ++refused;
    } else {
      EXPECT_FALSE(pointer.has_value()) << message;
      ++created;
    }
  }
  EXPECT_EQ(refused, 12);
  EXPECT_EQ(created, 12);
  EXPECT_GE(distracted, 2);
}

}  // namespace
}  // namespace hipair
