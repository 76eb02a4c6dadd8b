// The cut search's probes hand their held rows to their accelerations (src/simulation/
// probe_rows.hpp, switch simulation::probe_rows(); session 75). The rows a probe makes at a state
// must be the bits the accelerations would make again at that state — true only because
// track_derivatives answers as a function of the state, whatever its tracker's history (before
// session 75 the escapement's outputs moved from t = 0.32 s on when the rows were handed over:
// docs/performance.md, "Session 74 (speed74)"). Oracle: whole simulations side by side with the
// switch on and off (tests/unit/simulation_side_by_side.hpp): every state and event bit for bit,
// on the escapement (two accuracies), the Geneva drive, the ratchet, the cam with its follower and
// the scotch yoke.
#include "simulation/probe_rows.hpp"
#include "simulation_side_by_side.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace hipair {
namespace {

TEST(SimulationProbeRows, RunsEqualTheRunsThatRemakeTheRows) {
  const test::SideBySide runs = test::examples_side_by_side<simulation::probe_rows>(
      {{"escapement.json", 0.5, 1e-3},
       {"escapement.json", 0.1, 1e-6},
       {"geneva-drive.json", 2, 1e-3},
       {"ratchet.json", 0.2, 1e-6},
       {"cam-follower.json", 0.3, 1e-6},
       {"scotch-yoke.json", 0.3, 1e-6}},
      3000);
  std::printf("probe rows: %zu steps, %zu events equal\n", runs.steps, runs.events);
  EXPECT_GT(runs.events, 100u);
}

}  // namespace
}  // namespace hipair
