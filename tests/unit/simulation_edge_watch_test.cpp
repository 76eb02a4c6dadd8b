// The edge watch's stall exit (src/simulation/edge_watch.hpp, switch
// simulation::watch_stall_exit()): the scan returns at its fixed point the u it would return
// after its 100 000 iterations. Generated quintic paths and extents (crossings of an end at
// every slope, grazes that pass an end by about tol, paths that stay inside, starts outside,
// NaN) against the scan without the exit, bit for bit; and the simulator's runs with the exit
// against the runs without it, side by side, every state and event bit for bit.
#include "simulation/edge_watch.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

// A quintic through (q0, h v0, h^2 a0) and (q1, h v1, h^2 a1), as the simulator's step path.
std::array<double, 6> hermite(double q0, double v0, double a0, double q1, double v1, double a1, double h) {
  double c0 = q0, c1 = h * v0, c2 = h * h * a0 / 2;
  double A = q1 - (c0 + c1 + c2), B = h * v1 - (c1 + 2 * c2), C = h * h * a1 - 2 * c2;
  return {c0, c1, c2, 10 * A - 4 * B + C / 2, -15 * A + 7 * B - C, 6 * A - 3 * B + C / 2};
}

TEST(SimulationEdgeWatch, StallExitReturnsTheScansAnswer) {
  std::mt19937_64 random(20261202);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  const std::size_t stalls_before = simulation::watch_stalls();
  std::size_t differ = 0, crossings = 0, ones = 0, limits = 0;
  std::string first;
  const int trials = 3000;
  for (int trial = 0; trial < trials; ++trial) {
    const double scale = std::ldexp(1.0, static_cast<int>(random() % 21) - 10);
    const double q0 = scale * unit(random), h = std::ldexp(positive(random), -static_cast<int>(random() % 12));
    const double v0 = scale * unit(random) * 10, v1 = v0 * (1 + 0.5 * unit(random));
    const double q1 = q0 + h * 0.5 * (v0 + v1) * (1 + 1e-3 * unit(random));
    const std::array<double, 6> c = hermite(q0, v0, scale * unit(random), q1, v1, scale * unit(random), h);
    double slope = 0;
    for (int i = 1; i < 6; ++i) slope += i * std::abs(c[i]);
    const double at = simulation::watch_poly(c, positive(random));
    const double unit_length = scale;
    double A, B;
    const int kind = trial % 6;
    const double width = scale * (1 + positive(random));
    double tol;
    if (kind <= 2) {
      // an end the path passes (the lower or the upper one), placed at the path's value at a
      // random u: the scan creeps up to it (the graze the escapement met), or steps past it
      const bool lower = c[1] > 0 ? kind != 0 : kind == 0;
      A = lower ? at : at - width;
      B = lower ? at + width : at;
      if (lower && !(q0 > A)) A = q0 - width, B = at;   // keep the start inside
      if (!lower && !(q0 < B)) A = at, B = q0 + width;
    } else if (kind == 3) {
      // both ends far away: the path stays inside
      A = std::min(q0, q1) - 4 * width - slope;
      B = std::max(q0, q1) + 4 * width + slope;
    } else if (kind == 4) {
      // an end within a few tol of the start, or the start outside
      A = q0 - std::ldexp(unit(random), -40) * scale;
      B = q0 + width;
    } else {
      // the end exactly where the path is at u (within rounding), shifted by 0 .. 3 tol
      A = at;
      B = at + width;
    }
    tol = 1e-12 * (unit_length + std::abs(A) + std::abs(B));
    if (kind == 5) A -= tol * static_cast<double>(random() % 4);
    if (trial % 500 == 499) A = std::numeric_limits<double>::quiet_NaN();
    const int max_iterations = trial % 7 == 0 ? 1000 : trial % 10 == 0 ? 100000 : 20000;
    double on, off;
    {
      test::FlagSwitch<simulation::watch_stall_exit> flag(true);
      on = simulation::watch_scan(c, A, B, tol, slope, max_iterations);
    }
    {
      test::FlagSwitch<simulation::watch_stall_exit> flag(false);
      off = simulation::watch_scan(c, A, B, tol, slope, max_iterations);
    }
    if (std::bit_cast<std::uint64_t>(on) != std::bit_cast<std::uint64_t>(off)) {
      if (differ++ == 0) {
        char text[160];
        std::snprintf(text, sizeof text, "trial %d: %a against %a", trial, on, off);
        first = text;
      }
    }
    if (off == 1) ++ones;
    else if (std::isfinite(off)) {
      double q = simulation::watch_poly(c, off);
      if (std::min(q - A, B - q) < -tol) ++crossings;
      else ++limits;
    }
  }
  const std::size_t stalls = simulation::watch_stalls() - stalls_before;
  std::printf("edge watch: %d scans equal (%zu past an end, %zu to 1, %zu stopped in place); %zu stall exits\n", trials,
              crossings, ones, limits, stalls);
  EXPECT_EQ(differ, 0u) << first;
  // the generated cases reach every answer, and the exit
  EXPECT_GT(crossings, 100u);
  EXPECT_GT(ones, 100u);
  EXPECT_GT(limits, 100u);
  EXPECT_GT(stalls, 100u);
}

TEST(SimulationEdgeWatch, RunsEqualTheRunsWithoutTheExit) {
  const std::size_t stalls_before = simulation::watch_stalls();
  const test::SideBySide total = test::runs_side_by_side<simulation::watch_stall_exit>(
      HIPAIR_SOURCE_DIR,
      {{"examples/models/escapement.json", 0.5, 1e-3},
       {"examples/models/escapement.json", 0.1, 1e-6},
       {"tests/data/simulation/escapement-frictionless.json", 0.25, 1e-3},
       {"examples/models/ratchet.json", 0.5, 1e-3},
       {"examples/models/geneva-drive.json", 2.0, 1e-3},
       {"examples/models/cam-follower.json", 0.5, 1e-4}},
      std::numeric_limits<std::size_t>::max(), true);
  const std::size_t steps = total.steps, events = total.events;
  const std::size_t stalls = simulation::watch_stalls() - stalls_before;
  std::printf("edge watch: %zu steps, %zu events equal; %zu scans left at their fixed point\n", steps, events, stalls);
  EXPECT_GE(stalls, 6u);
}

}  // namespace
}  // namespace hipair
