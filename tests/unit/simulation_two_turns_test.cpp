// The Geneva drive over two driver turns (tests/perf/simulation_peer_benchmark.cpp found that a
// run without a step limit skips the second drive; docs/performance.md, "Simulation against
// Box2D and MuJoCo"). The wheel must advance one quarter turn per driver turn, within the play
// of its locking arcs, and every drive must begin with the pin striking a slot wall.
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

namespace hipair {
namespace {

void expect_two_drives(const SimulationOptions& options) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva-drive.json");
  Simulation s = Simulation::create(model, options);
  s.run_until(2.0);   // straight to the end: no step is cut at one turn
  // the pin enters a slot once per turn (impacts on a slot wall at about 0.39 s and 1.39 s)
  int first_turn = 0, second_turn = 0;
  for (const SimulationEvent& e : s.events()) {
    if (e.kind != SimulationEvent::Kind::impact || e.features.empty()) continue;
    if (e.features.front().find("pin") == std::string::npos) continue;
    (e.time < 1 ? first_turn : second_turn) += 1;
  }
  EXPECT_GE(first_turn, 1);
  EXPECT_GE(second_turn, 1);
  // a quarter turn per driver turn; the locking arcs' play (0.683 mm at the arms) allows 0.02 rad
  EXPECT_NEAR(s.state().position[1], -std::numbers::pi, 0.02);
}

TEST(SimulationGenevaTwoTurns, WithAStepLimitEveryDriveHappens) {
  SimulationOptions options;
  options.max_step = 0.1;
  expect_two_drives(options);
}

// Fails today: a step in sustained contact (the wheel's corner on the driver's locking arc, from
// 0.856 s) spans more than a driver turn, its edge is tested for its end only at the step's end,
// which lies on the edge again one turn later, and the second drive is skipped without an event
// (the pin passes through the wheel). Enable when src/simulation/ bounds such steps.
TEST(SimulationGenevaTwoTurns, DISABLED_WithoutAStepLimitEveryDriveHappens) { expect_two_drives({}); }

}  // namespace
}  // namespace hipair
