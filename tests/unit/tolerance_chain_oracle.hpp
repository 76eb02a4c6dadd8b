// The assembly-chain tests' oracle (tolerance_chain_test.cpp, tolerance_chain_gear_test.cpp,
// tolerance_chain_handover_test.cpp, tolerance_chain_monte_carlo_test.cpp): the output part's
// position at one driver position, from the exact kinematic engine sliced from the contact
// kernels and the exact overlap oracle, independently of the C-spaces the analysis slices.
#pragma once

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace hipair::test_chain {

/// One sample of the exact train: the driver, the output part's position, and every follower's
/// touching feature pairs ("pair: label", motion limits left out).
struct TrainSample {
  double driver = 0, output = 0;
  std::set<std::string> touching;
};

/// The exact engine driving `driver` over `range` on a grid of `steps` per turn, as the
/// analysis' kinematics samples it.
inline std::vector<TrainSample> chain_path(const Model& model, const std::string& driver,
                                           const std::pair<Rational, Rational>& range, const std::string& output,
                                           unsigned steps) {
  KinematicsOptions k;
  k.driver = driver;
  k.range = range;
  k.steps_per_cycle = steps;
  k.reversal = false;
  k.method = SliceMethod::kernels;
  KinematicsResult r = analyze_kinematics(model, k);
  std::size_t index = static_cast<std::size_t>(
      std::find(r.followers.begin(), r.followers.end(), output) - r.followers.begin());
  EXPECT_LT(index, r.followers.size());
  std::vector<TrainSample> path;
  for (const KinematicSample& sample : r.samples) {
    TrainSample t;
    t.driver = sample.driver;
    t.output = index < r.followers.size() ? sample.positions.at(index) : std::nan("");
    for (const std::vector<ContactLabel>& contacts : sample.contacts)
      for (const ContactLabel& c : contacts)
        if (!c.limit) t.touching.insert(c.pair + ": " + c.label);
    path.push_back(std::move(t));
  }
  return path;
}

/// Part `output`'s position at driver position `theta`, the train followed from the driver's
/// position `from` (the analysed range's start) as the analysis does: the exact engine over
/// [from, theta] on a grid of `steps` per turn (the range's end is its last sample). Started at
/// `theta` itself, a train far from the range's start can mesh another tooth than the one the
/// analysed motion reaches there.
inline double chain_output(const Model& model, const std::string& driver, double theta, const std::string& output,
                           const Rational& from, unsigned steps = 360) {
  bool at_start = Rational(theta) == from;
  auto path = chain_path(model, driver, std::make_pair(from, at_start ? from + Rational(1, 100) : Rational(theta)),
                         output, steps);
  const TrainSample& sample = at_start ? path.front() : path.back();
  // The range's end (or start) is a sample (its double within a few ulps).
  EXPECT_NEAR(sample.driver, theta, 4 * std::numeric_limits<double>::epsilon() * (1 + std::fabs(theta)));
  return sample.output;
}

}  // namespace hipair::test_chain
