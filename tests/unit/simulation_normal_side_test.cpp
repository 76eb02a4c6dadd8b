// The side of a new contact's C-space normal from the slope's certified double enclosure
// (src/simulation/normal_side.hpp, switch simulation::normal_filter()): certified_side against
// the exact signs of G_y - s G_x at the enclosure's ends in rationals, on generated slopes and
// normals of every scale, with near-ties placed within a few ulps of dot = 0; and the simulator's
// runs with the filter against the runs without it (the exact slope's midpoint, as before), side
// by side, bit for bit, on the escapement (its impacts on the locking faces, the pin in the fork,
// the banking) with friction and without, and the ratchet and the Geneva drive with a motor.
#include "simulation/normal_side.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

int exact_sign(double s, double gx, double gy) {
  Rational dot = Rational(gy) - Rational(s) * Rational(gx);
  return sgn(dot);
}

TEST(SimulationNormalSide, CertifiedSideIsTheExactSignOverTheEnclosure) {
  std::mt19937_64 random(20261202);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::size_t decided = 0, near = 0, undecided_near = 0, wrong = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const int scale = static_cast<int>(random() % 81) - 40;
    double gx = std::ldexp(unit(random), scale), gy = std::ldexp(unit(random), static_cast<int>(random() % 81) - 40);
    double lo = std::ldexp(unit(random), static_cast<int>(random() % 41) - 20);
    double hi = lo;
    const int kind = trial % 5;
    if (kind == 0) {
      // a tie placed within a few ulps: gy = lo gx rounded, then moved by 0..4 ulps either way
      gy = lo * gx;
      for (int k = 0, n = static_cast<int>(random() % 5); k < n; ++k)
        gy = std::nextafter(gy, random() % 2 ? -1e300 : 1e300);
      ++near;
    } else if (kind == 1) {
      // the tie inside a few-ulp enclosure
      gy = lo * gx;
      ++near;
    }
    for (int k = 0, n = static_cast<int>(random() % 8); k < n; ++k) hi = std::nextafter(hi, 1e300);
    if (kind == 2) hi = lo + std::abs(lo) * 1e-3;
    if (kind == 4) {
      // a wide enclosure with the tie inside it, or just outside either end
      hi = lo + std::abs(lo) * 1e-3;
      gy = (lo + (hi - lo) * std::uniform_real_distribution<double>(-0.1, 1.1)(random)) * gx;
    }
    if (kind == 3 && trial % 50 == 3) gx = 0;
    const int side = simulation::certified_side(lo, hi, gx, gy);
    if (side == 0) {
      undecided_near += kind <= 1;
      continue;
    }
    ++decided;
    const std::string where = "lo " + test::bits_of(lo) + " hi " + test::bits_of(hi) + " gx " + test::bits_of(gx) +
                              " gy " + test::bits_of(gy);
    // at both ends and in between (affine: the ends decide; a midpoint checked as well)
    const bool right = exact_sign(lo, gx, gy) == side && exact_sign(hi, gx, gy) == side &&
                       sgn(Rational(gy) - (Rational(lo) + Rational(hi)) / 2 * Rational(gx)) == side;
    if (!right && ++wrong <= 3) ADD_FAILURE() << "side " << side << " is not the exact sign: " << where;
  }
  EXPECT_EQ(wrong, 0u) << "wrong sides";
  // never decided: an empty, reversed or non-finite enclosure
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(simulation::certified_side(1, 0, 1, 5), 0);
  EXPECT_EQ(simulation::certified_side(-inf, 0, 1, 5), 0);
  EXPECT_EQ(simulation::certified_side(nan, 0, 1, 5), 0);
  EXPECT_EQ(simulation::certified_side(0, 1, inf, 5), 0);
  EXPECT_EQ(simulation::certified_side(0, 1, 1, nan), 0);
  EXPECT_EQ(simulation::certified_side(0, 1e300, 1e300, 1), 0);   // the product overflows
  std::printf("%zu of 200000 decided; %zu near-ties generated, %zu of them left to the exact slope\n", decided, near,
              undecided_near);
  EXPECT_GT(decided, 80000u);
  EXPECT_GT(undecided_near, 1000u);
}

TEST(SimulationNormalSide, RunsEqualTheRunsWithoutIt) {
  const std::size_t decided_before = simulation::normal_filter_decided();
  const test::SideBySide total = test::runs_side_by_side<simulation::normal_filter>(
      HIPAIR_SOURCE_DIR,
      {{"examples/models/escapement.json", 0.5, 1e-3},
       {"examples/models/escapement.json", 0.2, 1e-6},
       {"tests/data/simulation/escapement-frictionless.json", 0.25, 1e-3},
       {"examples/models/ratchet.json", 0.5, 1e-3},
       {"examples/models/geneva-drive.json", 1.0, 1e-3},
       {"examples/models/cam-follower.json", 0.5, 1e-4}},
      std::numeric_limits<std::size_t>::max(), true);
  const std::size_t steps = total.steps, events = total.events;
  const std::size_t decided = simulation::normal_filter_decided() - decided_before;
  std::printf("normal filter: %zu steps, %zu events equal; %zu new contacts oriented by the filter\n", steps, events,
              decided);
  EXPECT_GT(decided, 20u);
}

}  // namespace
}  // namespace hipair
