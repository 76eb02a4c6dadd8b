// Session 42 (tol42): the chain's certified band where a composition over the whole tolerance
// box cannot be certified (src/tolerance/chain.cpp certified(): the box bisected along the
// parameter that spreads the failing pair's follower most, the band the hull of the halves';
// docs/tolerance.md "Assembly chains", step 4, "Where a composition fails").
//
// gear-train.json (8 meshes, 100 parameters) over 0..0.53 rad at 120 positions per turn: on main
// 9b844dd 3 of its 10 held positions are unbounded (the last mesh's hand-over envelope cannot
// exclude a neighbouring tooth with its driver ranging over the whole box's composition). With
// the split the band is bounded at more of them, and wherever it is bounded it must hold
//   - the exact train (the model rebuilt exactly at the vector, its kinematics recomputed by the
//     kernel-sliced exact engine over the same range and grid: the same start, so the same
//     assembly) at the corners of the box that the linearisation moves furthest either way at
//     each held position (the band's edges are nearest there), and at random rational vectors;
//   - every Monte Carlo value (the chain's own certified values at sampled vectors).
// A band computed over a part of the box only (a mutant keeping one half of a split) is left by
// the exact train at the corners in the other half.
#include "gear_train_models.hpp"
#include "test_paths.hpp"

#include "model/parametric/parametric.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string example_text(const char* name) {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ChainFailureSplit, GearTrainBandBoundedBySplittingTheBoxHoldsTheExactTrainAtItsExtremeCorners) {
  const std::string text = example_text("gear-train.json");
  const std::pair<Rational, Rational> range(Rational(0), Rational(53, 100));
  ToleranceOptions options = test_gears::chain_options(range.second, 50, 42);
  ToleranceResult r = analyze_tolerances_text(text, options);
  ASSERT_EQ(r.chain.size(), 8u);
  ASSERT_TRUE(r.monte_carlo.has_value());
  std::size_t held = 0, bounded = 0;
  for (const VariationSample& sample : r.samples) {
    if (!sample.contact) continue;
    ++held;
    if (!std::isfinite(sample.certified.upper - sample.certified.lower)) continue;
    ++bounded;
    EXPECT_LE(sample.certified.lower, sample.nominal);
    EXPECT_GE(sample.certified.upper, sample.nominal);
  }
  EXPECT_EQ(held, 10u);
  // main 9b844dd: 7 of 10 (unbounded at 0.434, 0.482 and 0.53 rad)
  EXPECT_GE(bounded, 9u);
  EXPECT_EQ(r.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(r.monte_carlo->not_certified, 0u);

  // The vectors: per held position the corners the linearisation moves furthest up and down
  // (each deviation at the end its sensitivity's sign points to), without repeats, and random
  // rational vectors of the box.
  std::set<std::vector<Rational>> corners;
  for (const VariationSample& sample : r.samples) {
    if (!sample.contact || !std::isfinite(sample.certified.upper - sample.certified.lower)) continue;
    for (int way : {1, -1}) corners.insert(test_gears::linearised_corner(sample, r.parameters, way));
  }
  std::vector<std::vector<Rational>> vectors(corners.begin(), corners.end());
  std::mt19937 rng(4242);
  for (int k = 0; k < 2; ++k) vectors.push_back(test_gears::random_deviations(r.parameters, rng));

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  double closest = std::numeric_limits<double>::infinity();   // the exact train's least distance to a band's edge
  for (std::size_t v = 0; v < vectors.size(); ++v) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = 120;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult exact = analyze_kinematics(model->exact_model(vectors[v]), k);
    std::size_t output = static_cast<std::size_t>(
        std::find(exact.followers.begin(), exact.followers.end(), "gear-I") - exact.followers.begin());
    ASSERT_LT(output, exact.followers.size());
    for (const VariationSample& sample : r.samples) {
      if (!sample.contact || !std::isfinite(sample.certified.upper - sample.certified.lower)) continue;
      auto at = std::find_if(exact.samples.begin(), exact.samples.end(),
                             [&](const KinematicSample& e) { return e.driver == sample.driver; });
      ASSERT_NE(at, exact.samples.end()) << "driver " << sample.driver;
      double out = at->positions.at(output);
      ++checked;
      closest = std::min({closest, out - sample.certified.lower, sample.certified.upper - out});
      EXPECT_GE(out, sample.certified.lower - 1e-10) << "driver " << sample.driver << " vector " << v;
      EXPECT_LE(out, sample.certified.upper + 1e-10) << "driver " << sample.driver << " vector " << v;
    }
  }
  EXPECT_EQ(checked, vectors.size() * bounded);
  std::printf("gear-train.json over 0..0.53 rad: %zu of %zu held positions bounded; %zu exact values (%zu vectors) "
              "inside, nearest %.3g rad from an edge\n",
              bounded, held, checked, vectors.size(), closest);
}

}  // namespace
}  // namespace hipair
