// The tolerance analysis's progress (ToleranceOptions::progress, src/tolerance/progress.hpp;
// docs/performance.md "Session 37 (tol37)"): every fraction passed on is larger than the one
// before, lies in [0, 1], and the last is 1; each stage fills its share from its own work units
// (the nominal sweep's travel, the positions, the zones' samples, the Monte Carlo's vectors).
// Oracle for the reporter: a plain model of the bar (the running maximum of each stage's
// mapped fraction), written here independently. Mutation (run and reverted): the reporter
// passing on a value not above the last shown -> StagedProgressOnlyGrowsAndEndsAtOne and both
// analyses' tests fail. TheNominalSweepsFractionOnlyGrows checks the kinematic sweep's own
// fractions (before the reporter's filter), forward and backward over several Geneva turns.
#include "core/progress_scope.hpp"
#include "tolerance/progress.hpp"
#include "tolerance_chain_models.hpp"

#include "test_paths.hpp"

#include <hipair/certificate.hpp>
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
#include <thread>
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

// StagedProgress::within(lo, hi): an inner step's fraction f shows as the stage's lo + f (hi - lo),
// clamped, and still only growing. Oracle: the plain model of the bar, as above.
TEST(ToleranceProgress, APartOfAStageMapsItsInnerFractions) {
  std::mt19937 rng(38);
  for (int trial = 0; trial < 1000; ++trial) {
    std::vector<double> bounds{0, std::uniform_real_distribution<>(0, 0.5)(rng), 1};
    std::vector<double> shown, expected;
    StagedProgress bar([&](double f) { shown.push_back(f); }, bounds);
    double oracle = -1;
    auto ask = [&](double value) {
      if (value > oracle) expected.push_back(oracle = value);
    };
    std::size_t stage = rng() % 2;
    bar.begin(stage);
    ask(bounds[stage]);
    for (int part = 0; part < 6; ++part) {
      double lo = std::uniform_real_distribution<>(0, 1)(rng), hi = std::uniform_real_distribution<>(lo, 1)(rng);
      std::function<void(double)> inner = bar.within(lo, hi);
      for (int call = 0; call < 10; ++call) {
        double f = std::uniform_real_distribution<>(-0.5, 1.5)(rng);
        if (call == 3) f = std::numeric_limits<double>::quiet_NaN();
        inner(f);
        double clamped = f > 0 ? std::min(f, 1.0) : 0.0;
        ask(bounds[stage] + (lo + clamped * (hi - lo)) * (bounds[stage + 1] - bounds[stage]));
      }
    }
    bar.finish();
    ask(1);
    expect_growing_to_one(shown, "trial " + std::to_string(trial));
    ASSERT_EQ(shown, expected) << "trial " << trial;
  }
  StagedProgress silent({}, {0, 1});
  EXPECT_FALSE(static_cast<bool>(silent.within(0.2, 0.4)));
}

// core/progress_scope.hpp: the innermost scope's hook receives what the work reports; an empty
// scope hides the outer one; a scope's end restores the one before; another thread sees none.
// Oracle: a stack of hooks kept here. Then a real build: CSpace::build reports its charts built,
// classified and its cells as strictly growing fractions ending at 1.
TEST(ToleranceProgress, AProgressScopeReachesTheCSpaceBuild) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::vector<double>> received(8);
    std::vector<int> stack;   // the oracle: hooks installed, -1 for an empty one
    std::vector<std::vector<double>> expected(8);
    std::function<void(int)> nest = [&](int depth) {
      int hook = rng() % 4 == 0 ? -1 : depth;
      ProgressScope scope(hook < 0 ? std::function<void(double)>{}
                                   : std::function<void(double)>([&, hook](double f) { received[static_cast<std::size_t>(hook)].push_back(f); }));
      stack.push_back(hook);
      for (int step = 0; step < 4; ++step) {
        if (depth < 7 && rng() % 3 == 0) nest(depth + 1);
        double f = std::uniform_real_distribution<>(0, 1)(rng);
        EXPECT_EQ(progress_wanted(), stack.back() >= 0);
        report_progress(f);
        if (stack.back() >= 0) expected[static_cast<std::size_t>(stack.back())].push_back(f);
        std::thread([f] {
          EXPECT_FALSE(progress_wanted());
          report_progress(f);   // no hook on this thread: nothing received
        }).join();
      }
      stack.pop_back();
    };
    nest(0);
    EXPECT_FALSE(progress_wanted());
    ASSERT_EQ(received, expected) << "trial " << trial;
  }
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json");
  std::vector<double> seen;
  {
    ProgressScope scope([&](double f) { seen.push_back(f); });
    CSpace space = CSpace::build(model, "driver", "wheel");
    // 2-D: each chart built, each chart classified, the cells
    ASSERT_EQ(seen.size(), 2 * space.charts().size() + 1);
  }
  expect_growing_to_one(seen, "geneva's C-space build");
  seen.clear();
  CSpace::build(model, "driver", "wheel");   // the scope has ended: nothing
  EXPECT_TRUE(seen.empty());
}

// The threshold search (certified scales, exact C-spaces, the bracket's bisection and its
// witness' C-space) and the certificate's branch-and-bound report inside their stages; the
// pair's C-space build inside the first. The certificate's share: the leaves' exact share of the
// region (box x range, an independent sum over the certificate's leaves in rationals) is 1, and
// the last inner fraction shown before the end is the producer's 0.95 of its stage.
TEST(ToleranceProgress, TheCSpaceThresholdAndCertificateReportInnerProgress) {
  ToleranceOptions options;
  options.range = std::make_pair(Rational(11, 5), Rational(23, 10));   // Geneva: the pin's entry
  options.positions = 720;
  options.relative_accuracy = 0.5;
  options.threshold = true;
  options.threshold_bracket = 1e-2;   // (a few bisection steps: the test stays fast)
  options.certify = true;             // at the declared tolerances (a few leaves)
  options.threads = 1;
  std::vector<double> shown;
  options.progress = [&](double f) { shown.push_back(f); };
  ToleranceResult result = analyze_tolerances(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json", options);
  expect_growing_to_one(shown, "geneva, threshold and certificate");
  EXPECT_GE(count_within(shown, 0.0, 0.02), 3u) << "the pair's C-space build";
  const double t = 0.85, w = 0.05;   // the threshold's stage
  EXPECT_GE(count_within(shown, t + 0.1 * w, t + 0.6 * w), 3u) << "the exact C-spaces";
  EXPECT_GE(count_within(shown, t + 0.6 * w, t + 0.8 * w), 3u) << "the bracket's bisection";
  EXPECT_GE(count_within(shown, t + 0.8 * w, t + w), 2u) << "the witness' C-space";
  ASSERT_TRUE(result.threshold && result.threshold->bracketed);
  ASSERT_TRUE(result.certification);
  ASSERT_EQ(result.certification->outcome, ToleranceCertification::Outcome::certified) << result.certification->reason;
  const ToleranceClaim& claim = *result.certification->certificate->tolerance;
  EXPECT_GE(count_within(shown, 0.95, 0.95 + 0.1 * w), 5u) << "the corner search";
  EXPECT_GE(count_within(shown, 0.95 + 0.1 * w, 1.0), std::min<std::size_t>(20, claim.leaves.size()))
      << "the branch-and-bound's leaves";
  Rational share = 0;
  for (const ToleranceLeaf& leaf : claim.leaves) {
    Rational v = (leaf.driver.hi - leaf.driver.lo) / (claim.range.hi - claim.range.lo);
    for (std::size_t i = 0; i < claim.box.size(); ++i)
      v *= (leaf.parameters[i].hi - leaf.parameters[i].lo) / (claim.box[i].hi - claim.box[i].lo);
    share += v;
  }
  EXPECT_EQ(share, Rational(1)) << "the leaves cover the region once";
  ASSERT_GE(shown.size(), 2u);
  EXPECT_NEAR(shown[shown.size() - 2], 0.95 + 0.95 * w, 1e-9) << "the leaves' share shown";
}

}  // namespace
}  // namespace hipair
