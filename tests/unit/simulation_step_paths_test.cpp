// The simulator's step paths written into kept AxisPaths (src/simulation/step_paths.hpp,
// docs/performance.md "esc50c"): a kept path, rewritten by a sequence of generated quintics of
// every length (trailing zeros, constants, zero), rotations and offsets, and cleared, holds
// exactly what a fresh path written the same way holds — nothing of a longer or different path
// before it leaks into the next.

#include "simulation/step_paths.hpp"

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <array>
#include <random>

namespace hipair {
namespace {

std::array<double, 6> random_quintic(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> length(0, 6);
  std::uniform_real_distribution<double> value(-3, 3);
  std::array<double, 6> c{};
  const int n = length(rng);
  for (int i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = rng() % 5 == 0 ? 0.0 : value(rng);
  return c;
}

TEST(SimulationStepPaths, KeptPathsEqualFreshOnes) {
  std::mt19937_64 rng(5050);
  AxisPath kept;
  int shorter = 0, cleared = 0;
  std::size_t previous = 0;
  for (int i = 0; i < 2000; ++i) {
    AxisPath fresh;
    if (rng() % 8 == 0) {
      simulation::clear_axis_path(kept);
      ++cleared;
    } else {
      const std::array<double, 6> c = random_quintic(rng);
      const bool rotation = rng() % 2 == 0;
      simulation::assign_axis_path(kept, c, rotation);
      simulation::assign_axis_path(fresh, c, rotation);
      // the fresh path's own oracle: the coefficients up to the last nonzero one (at least one)
      std::size_t count = 1;
      for (std::size_t k = 0; k < 6; ++k)
        if (c[k] != 0) count = k + 1;
      ASSERT_EQ(fresh.coefficients.size(), count);
      for (std::size_t k = 0; k < count; ++k) ASSERT_EQ(fresh.coefficients[k], Rational(c[k]));
      ASSERT_EQ(fresh.kind, rotation ? AxisPath::Kind::angle : AxisPath::Kind::offset);
    }
    shorter += kept.coefficients.size() < previous;
    previous = kept.coefficients.size();
    ASSERT_EQ(kept.kind, fresh.kind) << "path " << i;
    ASSERT_EQ(kept.coefficients, fresh.coefficients) << "path " << i;
  }
  EXPECT_GT(shorter, 400);   // a shorter path after a longer one, often
  EXPECT_GT(cleared, 150);
}

}  // namespace
}  // namespace hipair
