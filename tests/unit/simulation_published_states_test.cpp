// Session 74 (jam74; Issue 11, review73 H1): no state a planar simulation publishes has two
// parts of a model pair overlapping — decided exactly (part_overlap on the state's exact
// configurations, published_overlap.hpp), at every step's end, every event's state and a stop's.
// A guard (passes on base74 too): until session 74 a block carried off plastically drifted into
// its pusher (~3e-15 mm/s, ~1e-30 rad/s; docs/simulation.md Session 74) and the back-off's trial
// states were blocked, but the published states were free by rounding luck (relative x 8 + 3.6e-15).
#include <hipair/model.hpp>
#include <hipair/pin_slot_simulation.hpp>
#include <hipair/simulation.hpp>
#include <hipair/simulation_stop.hpp>

#include <gtest/gtest.h>

#include "published_overlap.hpp"
#include "test_paths.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace hipair {
namespace {

Model example(const std::string& name) {
  const std::filesystem::path path = std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models" / (name + ".json");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return read_model(text.str(), path.string());
}

// Runs `sim` to t_end step by step, checking every published state; a stop (a jam, a refusal)
// ends the run with its state checked too.
template <class Sim>
test::PublishedOverlapCheck checked_run(Sim& sim, double t_end) {
  test::PublishedOverlapCheck check;
  check(sim);
  try {
    sim.run_until(t_end, [&](double) { check(sim); });
  } catch (const SimulationJam&) {
    check(sim);
  }
  return check;
}

struct Example {
  const char* name;
  double t_end;   // the model's time unit: a short run (a second or so of CPU here)
};

// every planar example (one planar part: PlanarSimulation; several: PlanarSystemSimulation)
TEST(SimulationPublishedStates, NoPlanarExampleEverPublishesOverlappingParts) {
  const Example examples[] = {{"disc-incline", 0.5},  {"friction-slide", 0.3}, {"incline-limit", 0.5},
                              {"ladder", 0.05},       {"peg-drop", 0.5},       {"peg-throw", 0.2},
                              {"pushed-block", 0.5},  {"pusher-blocks", 0.12}, {"spring-block", 0.2},
                              {"stacked-blocks", 0.5}, {"wheel-socket", 0.5}};
  for (const Example& e : examples) {
    SCOPED_TRACE(e.name);
    const Model model = example(e.name);
    std::size_t planar = 0;
    for (const Part& p : model.parts) planar += p.motion.kind == Motion::Kind::planar;
    test::PublishedOverlapCheck check;
    if (planar == 1) {
      PlanarSimulation sim = PlanarSimulation::create(model, SimulationOptions{});
      check = checked_run(sim, e.t_end);
    } else {
      PlanarSystemSimulation sim = PlanarSystemSimulation::create(model, SimulationOptions{});
      check = checked_run(sim, e.t_end);
    }
    EXPECT_EQ(check.bad, 0u) << check.bad << " of " << check.checked << " states overlap; the first at " << check.first_bad;
    ::testing::Test::RecordProperty(std::string(e.name) + "_states", static_cast<int>(check.checked));
  }
}

// Session 75 (jam75; review74 M2): the fixed-axis simulator's examples (rotating and translating
// parts: Simulation) and the pin-slot one (film-advance: PinSlotSimulation), every step's state,
// every model pair, exact (published_overlap.hpp: a fixed-axis state's angle placed by its
// half-angle tangent at 300 bits; a pin-slot state by its exact pair configurations).
TEST(SimulationPublishedStates, NoFixedAxisOrPinSlotExampleEverPublishesOverlappingParts) {
  const Example examples[] = {{"escapement", 0.05},   {"geneva-drive", 0.2},  {"cam-drive", 0.05},
                              {"cam-follower", 0.05}, {"cam-shim-stack", 0.05}, {"ratchet", 0.1},
                              {"lever-stop", 0.1},    {"scotch-yoke", 0.05},  {"bouncing-bar", 0.2},
                              {"spur-gears", 0.02},   {"two-pin-wedge", 0.1}, {"film-advance", 0.1}};
  for (const Example& e : examples) {
    SCOPED_TRACE(e.name);
    const Model model = example(e.name);
    bool pin_slot = false;
    for (const Part& p : model.parts) pin_slot = pin_slot || p.motion.kind == Motion::Kind::pin_slot;
    test::PublishedOverlapCheck check;
    if (pin_slot) {
      PinSlotSimulation sim = PinSlotSimulation::create(model, SimulationOptions{});
      check = checked_run(sim, e.t_end);
    } else {
      Simulation sim = Simulation::create(model, SimulationOptions{});
      check = checked_run(sim, e.t_end);
    }
    EXPECT_EQ(check.bad, 0u) << check.bad << " of " << check.checked << " states overlap; the first at " << check.first_bad;
    ::testing::Test::RecordProperty(std::string(e.name) + "_states", static_cast<int>(check.checked));
  }
}

}  // namespace
}  // namespace hipair
