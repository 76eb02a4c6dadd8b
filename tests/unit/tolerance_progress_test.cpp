// The tolerance analysis's progress (ToleranceOptions::progress, src/tolerance/progress.hpp;
// docs/performance.md "Session 37 (tol37)"): every fraction passed on is larger than the one
// before, lies in [0, 1], and the last is 1; each stage fills its share from its own work units
// (the nominal sweep's travel, the positions, the zones' samples, the Monte Carlo's vectors).
// Oracle for the reporter: a plain model of the bar (the running maximum of each stage's
// mapped fraction), written here independently. Mutation (run and reverted): the reporter
// passing on a value not above the last shown -> StagedProgressOnlyGrowsAndEndsAtOne and both
// analyses' tests fail. TheNominalSweepsFractionOnlyGrows checks the kinematic sweep's own
// fractions (before the reporter's filter), forward and backward over several Geneva turns.
#include "tolerance/progress.hpp"
#include "tolerance_chain_models.hpp"

#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace hipair {
namespace {

using tolerance_detail::StagedProgress;

// Every fraction in [0, 1], each larger than the one before, the last one 1.
void expect_growing_to_one(const std::vector<double>& shown, const std::string& what) {
  ASSERT_FALSE(shown.empty()) << what;
  for (std::size_t i = 0; i < shown.size(); ++i) {
    EXPECT_GE(shown[i], 0.0) << what << " #" << i;
    EXPECT_LE(shown[i], 1.0) << what << " #" << i;
    if (i > 0) EXPECT_GT(shown[i], shown[i - 1]) << what << " #" << i;
  }
  EXPECT_EQ(shown.back(), 1.0) << what;
}

std::size_t count_within(const std::vector<double>& shown, double lo, double hi) {
  return static_cast<std::size_t>(
      std::count_if(shown.begin(), shown.end(), [&](double f) { return f > lo && f < hi; }));
}

TEST(ToleranceProgress, StagedProgressOnlyGrowsAndEndsAtOne) {
  std::mt19937 rng(37);
  for (int trial = 0; trial < 2000; ++trial) {
    // random stage bounds, some stages empty
    std::size_t stages = 1 + rng() % 8;
    std::vector<double> bounds{0};
    for (std::size_t k = 0; k < stages; ++k)
      bounds.push_back(rng() % 4 == 0 ? bounds.back() : bounds.back() + std::uniform_real_distribution<>(0, 1)(rng));
    for (double& b : bounds) b /= std::max(bounds.back(), 1e-300);
    bounds.back() = 1;
    std::vector<double> shown;
    StagedProgress bar([&](double f) { shown.push_back(f); }, bounds);
    double oracle = -1;   // the plain model: the running maximum of what was asked
    std::vector<double> expected;
    auto ask = [&](double value) {
      if (value > oracle) {
        oracle = value;
        expected.push_back(value);
      }
    };
    std::size_t stage = 0;
    auto mapped = [&](double f) { return bounds[stage] + f * (bounds[stage + 1] - bounds[stage]); };
    bar.begin(0);
    ask(bounds[0]);
    for (int call = 0; call < 60; ++call) {
      int what = static_cast<int>(rng() % 10);
      if (what == 0 && stage + 1 < stages) {
        ++stage;
        bar.begin(stage);
        ask(bounds[stage]);
      } else if (what == 1) {
        bar.begin(rng() % (stage + 1));   // the stage again or an earlier one: nothing moves back
        break;
      } else {
        std::size_t total = rng() % 50;
        std::size_t done = total == 0 ? 0 : rng() % (total + 5);   // sometimes beyond the total
        bar.units(done, total);
        double f = total == 0 ? 1.0 : std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
        ask(mapped(f));
      }
      if (what == 2) {
        bar.fraction(std::numeric_limits<double>::quiet_NaN());
        ask(mapped(0));
        bar.fraction(-3);
        bar.fraction(7);
        ask(mapped(1));
      }
    }
    bar.finish();
    ask(1.0);
    expect_growing_to_one(shown, "trial " + std::to_string(trial));
    ASSERT_EQ(shown, expected) << "trial " << trial;
  }
  // no sink: silent, and nothing throws
  StagedProgress silent({}, {0, 0.5, 1});
  EXPECT_FALSE(silent.active());
  EXPECT_FALSE(static_cast<bool>(silent.within()));
  silent.begin(1);
  silent.units(3, 4);
  silent.finish();
}

TEST(ToleranceProgress, APairsStagesEachReportInnerProgress) {
  for (unsigned threads : {1u, 2u}) {
    ToleranceOptions options;
    options.range = std::make_pair(Rational(12, 5), Rational(4));   // Geneva: the pin in slot 1
    options.positions = 90;
    options.relative_accuracy = 0.5;
    options.monte_carlo = 20;
    options.seed = 3;
    options.threads = threads;
    std::vector<double> shown;
    options.progress = [&](double f) { shown.push_back(f); };
    analyze_tolerances(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json", options);
    std::string what = "geneva, " + std::to_string(threads) + " thread(s)";
    expect_growing_to_one(shown, what);
    // on more threads the calling thread reports what has finished when it finishes a task of
    // its own, and every 100 ms while it waits: how many of these fall inside a short stage
    // depends on the scheduling
    if (threads > 1) continue;
    EXPECT_GE(count_within(shown, 0.02, 0.2), 5u) << what << ": the nominal sweep";
    EXPECT_GE(count_within(shown, 0.3, 0.45), 3u) << what << ": the certified band";
    EXPECT_GE(count_within(shown, 0.45, 0.55), 3u) << what << ": the zones";
  }
}

TEST(ToleranceProgress, AChainsStagesEachReportInnerProgress) {
  std::mt19937 rng(5);
  test_chain::LiftChain chain = test_chain::lift_chain(2, 2, rng);
  std::vector<double> shown;
  ToleranceOptions options;
  options.progress = [&](double f) { shown.push_back(f); };
  options.driver = "cam";
  options.chain = true;
  std::tie(options.positions, options.monte_carlo, options.threads) = std::tuple(std::size_t{36}, std::size_t{10}, 1u);
  analyze_tolerances_text(chain.json, options);
  expect_growing_to_one(shown, "lift chain");
  EXPECT_GE(count_within(shown, 0.05, 0.2), 5u) << "the chain's kinematics";
  EXPECT_GE(count_within(shown, 0.4, 0.6), 5u) << "the certified band";
  EXPECT_GE(count_within(shown, 0.6, 1.0), 5u) << "the Monte Carlo";
}

TEST(ToleranceProgress, TheNominalSweepsFractionOnlyGrows) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json");
  for (auto range : {std::make_pair(Rational(11, 5), Rational(30)), std::make_pair(Rational(30), Rational(11, 5))}) {
    KinematicsOptions k;
    k.range = range;
    k.steps_per_cycle = 36;
    k.reversal = false;
    k.method = SliceMethod::cspace;
    std::vector<double> seen;
    k.progress = [&](double f) { seen.push_back(f); };
    analyze_kinematics(model, k, {CSpace::build(model, "driver", "wheel")});
    ASSERT_GE(seen.size(), 10u);
    for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]) << "#" << i;
    EXPECT_EQ(seen.back(), 1.0);
  }
}

}  // namespace
}  // namespace hipair
