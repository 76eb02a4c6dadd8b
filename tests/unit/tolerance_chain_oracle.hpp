// The assembly-chain tests' oracle (tolerance_chain_test.cpp, tolerance_chain_gear_test.cpp): the
// output part's position at one driver position, from the exact kinematic engine sliced from the
// contact kernels and the exact overlap oracle, independently of the C-spaces the analysis
// slices.
#pragma once

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace hipair::test_chain {

/// Part `output`'s position at driver position `theta` (the range's start is a sample).
inline double chain_output(const Model& model, const std::string& driver, double theta, const std::string& output) {
  KinematicsOptions k;
  k.driver = driver;
  k.range = std::make_pair(Rational(theta), Rational(theta) + Rational(1, 100));
  k.steps_per_cycle = 16;
  k.reversal = false;
  k.method = SliceMethod::kernels;
  KinematicsResult r = analyze_kinematics(model, k);
  std::size_t index = static_cast<std::size_t>(
      std::find(r.followers.begin(), r.followers.end(), output) - r.followers.begin());
  EXPECT_LT(index, r.followers.size());
  // The first sample is the range's start (its double within a few ulps).
  EXPECT_NEAR(r.samples.front().driver, theta, 4 * std::numeric_limits<double>::epsilon() * (1 + std::fabs(theta)));
  return r.samples.front().positions.at(index);
}

}  // namespace hipair::test_chain
