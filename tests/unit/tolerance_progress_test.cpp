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
#include "polygon_loop_json.hpp"
#include "tolerance_chain_models.hpp"

#include "test_paths.hpp"

#include <hipair/certificate.hpp>
#include <hipair/cspace.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <map>
#include <sstream>
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

// A generated model: star polygons (polygon_loop_json.hpp) about (4i, 0), radii 2 to 3.5 (so
// neighbours reach into each other), each rotating about its centre or fixed; a pair between
// every two parts, of which the fixed-fixed ones are skipped by build_all.
std::string star_model(std::mt19937_64& random, const std::vector<bool>& rotating) {
  std::string parts, pairs;
  for (std::size_t i = 0; i < rotating.size(); ++i) {
    const int n = 4 + static_cast<int>(random() % 4);
    const std::string loop = test_loops::loop_json(test_loops::star(random, n, 4.0 * static_cast<double>(i), 0, 1.5, false));
    const std::string motion =
        rotating[i] ? R"({ "rotation": { "pivot": [)" + std::to_string(4 * i) + R"(, 0] } })" : std::string(R"("fixed")");
    parts += std::string(i ? ", " : "") + R"({ "name": "p)" + std::to_string(i) + R"(", "motion": )" + motion +
             R"(, "loops": [ )" + loop + " ] }";
    for (std::size_t j = 0; j < i; ++j)
      pairs += std::string(pairs.empty() ? "" : ", ") + R"({ "parts": ["p)" + std::to_string(j) + R"(", "p)" +
               std::to_string(i) + R"("] })";
  }
  return R"({ "hipair": 1, "name": "stars", "parts": [ )" + parts + R"( ], "pairs": [ )" + pairs + " ] }";
}

// A record of one report (CSpaceBuildProgress's views live during the call only).
struct Seen {
  CSpaceBuildProgress::Stage stage;
  std::size_t chart, charts, done, total;
  double fraction;
  std::string text;
};

// One pair's reports against an independent model of them: its charts in order (fraction
// (k - 1)/U, U = charts + (2-D: charts) + 1 work units, the text "hipair: A:B chart k/n"),
// then on 2-D spaces each chart's classification in order (done growing to its total, the
// fraction (n + k - 1 + done/total)/U), then one Stage::done with fraction exactly 1; every
// fraction in [0, 1] and none below the one before.
void expect_one_pairs_reports(const std::vector<Seen>& seen, const CSpace& space, const std::string& what) {
  using Stage = CSpaceBuildProgress::Stage;
  const std::size_t n = space.charts().size();
  const bool plane = space.dimension() == 2;
  const double units = static_cast<double>((plane ? 2 : 1) * n + 1);
  ASSERT_GE(seen.size(), n + 1) << what;
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(seen[k].stage, Stage::chart) << what << " #" << k;
    EXPECT_EQ(seen[k].chart, k + 1) << what << " #" << k;
    EXPECT_EQ(seen[k].charts, n) << what << " #" << k;
    EXPECT_EQ(seen[k].fraction, static_cast<double>(k) / units) << what << " #" << k;
    EXPECT_EQ(seen[k].text, "hipair: " + space.first_part() + ":" + space.second_part() + " chart " +
                                std::to_string(k + 1) + "/" + std::to_string(n))
        << what;
  }
  std::size_t chart = 0, done = 0;
  for (std::size_t i = n; i + 1 < seen.size(); ++i) {
    const Seen& r = seen[i];
    ASSERT_TRUE(plane) << what << ": a 1-D space classifies no chart";
    ASSERT_EQ(r.stage, Stage::classification) << what << " #" << i;
    EXPECT_EQ(r.charts, n) << what;
    if (r.chart != chart) {
      EXPECT_EQ(r.chart, chart + 1) << what << " #" << i;
      chart = r.chart;
      done = 0;
    }
    EXPECT_GE(r.done, done) << what << " #" << i;
    EXPECT_LE(r.done, r.total) << what << " #" << i;
    done = r.done;
    const double expected =
        (static_cast<double>(n + chart - 1) + static_cast<double>(r.done) / static_cast<double>(std::max<std::size_t>(r.total, 1))) / units;
    EXPECT_NEAR(r.fraction, expected, 1e-12) << what << " #" << i;
    EXPECT_EQ(r.text.rfind("hipair: " + space.first_part() + ":" + space.second_part() + " classifying chart " +
                               std::to_string(chart) + "/" + std::to_string(n) + ": ",
                           0),
              0u)
        << what << " #" << i;
  }
  EXPECT_EQ(seen.back().stage, Stage::done) << what;
  EXPECT_EQ(seen.back().fraction, 1.0) << what;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_GE(seen[i].fraction, 0.0) << what << " #" << i;
    EXPECT_LE(seen[i].fraction, 1.0) << what << " #" << i;
    if (i > 0) EXPECT_GE(seen[i].fraction, seen[i - 1].fraction) << what << " #" << i;
  }
}

// CSpaceBuildOptions::progress (the one progress channel into the builder): on generated star
// pairs (1-D and 2-D spaces) a single build's reports follow the model above; build_all on
// generated three- and four-part models (several pairs on two worker threads) calls the
// callback never concurrently (a counter of calls inside it, each call sleeping a little to
// widen the window), and each pair's reports, taken apart by pair, follow the same model.
// Mutations (run and reverted): the chart's work unit left uncounted -> the fractions differ;
// the lock in build_each removed -> "called concurrently".
TEST(ToleranceProgress, TheBuildOptionsCallbackReportsEachPairGrowingToOne) {
  std::mt19937_64 random(39);
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<bool> rotating = trial % 3 == 0 ? std::vector<bool>{true, false} : std::vector<bool>{true, true};
    Model model = read_model(star_model(random, rotating));
    std::vector<Seen> seen;
    CSpaceBuildOptions options;
    options.progress = [&](const CSpaceBuildProgress& r) {
      seen.push_back({r.stage, r.chart, r.charts, r.done, r.total, r.fraction, r.text()});
    };
    CSpace space = CSpace::build(model, "p0", "p1", options);
    expect_one_pairs_reports(seen, space, "trial " + std::to_string(trial));
  }
  for (int trial = 0; trial < 3; ++trial) {
    const std::vector<bool> rotating =
        trial == 0 ? std::vector<bool>{true, true, true} : std::vector<bool>{true, false, true, trial == 2};
    Model model = read_model(star_model(random, rotating));
    std::map<std::pair<std::string, std::string>, std::vector<Seen>> seen;
    std::atomic<int> inside{0};
    std::atomic<int> overlaps{0};
    CSpaceBuildOptions options;
    options.threads = 2;
    options.progress = [&](const CSpaceBuildProgress& r) {
      if (inside.fetch_add(1) != 0) ++overlaps;
      seen[{std::string(r.first_part), std::string(r.second_part)}].push_back(
          {r.stage, r.chart, r.charts, r.done, r.total, r.fraction, r.text()});
      if (r.stage != CSpaceBuildProgress::Stage::classification) std::this_thread::sleep_for(std::chrono::milliseconds(2));
      inside.fetch_sub(1);
    };
    std::vector<CSpace> spaces = CSpace::build_all(model, options);
    EXPECT_EQ(overlaps.load(), 0) << "trial " << trial << ": called concurrently";
    ASSERT_GE(spaces.size(), 2u);
    EXPECT_EQ(seen.size(), spaces.size());
    for (const CSpace& space : spaces)
      expect_one_pairs_reports(seen[{space.first_part(), space.second_part()}], space,
                               "build_all trial " + std::to_string(trial) + " " + space.first_part() + ":" +
                                   space.second_part());
  }
}

// stderr_progress(), the reporter the CLI passes on a terminal: for Geneva's pair it writes
// every chart's line redrawn in place, a line break after the last, the first classification
// line (at once: the reporter shows one at most every 250 ms), and wipes its widest line at the
// end: the bytes `hipair cspace` wrote on a terminal before session 39. Mutation (run and
// reverted): the line break after the last chart dropped -> fails.
TEST(ToleranceProgress, TheTerminalReporterWritesTheBuildsLines) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json");
  std::ostringstream captured;
  std::streambuf* old = std::cerr.rdbuf(captured.rdbuf());
  CSpaceBuildOptions options;
  options.progress = stderr_progress();
  CSpace space = CSpace::build(model, "driver", "wheel", options);
  std::cerr.rdbuf(old);
  const std::string out = captured.str();
  const std::size_t n = space.charts().size();
  std::string charts;
  for (std::size_t k = 1; k <= n; ++k) charts += "\rhipair: driver:wheel chart " + std::to_string(k) + "/" + std::to_string(n);
  charts += "\n\rhipair: driver:wheel classifying chart 1/" + std::to_string(n) + ": 0%";
  ASSERT_EQ(out.substr(0, charts.size()), charts);
  // the end: the widest line shown wiped
  const std::size_t wipe = out.rfind('\r', out.size() - 2);
  ASSERT_NE(wipe, std::string::npos);
  const std::string tail = out.substr(wipe);
  EXPECT_EQ(tail, "\r" + std::string(tail.size() - 2, ' ') + "\r");
  EXPECT_GE(tail.size() - 2, std::string("hipair: driver:wheel classifying chart 1/4: 0%").size());
}

// A report's line names the pair as every console line does: names of up to 200 bytes whole,
// longer ones cut to their first 200 bytes and their length (core/console_text.hpp), so a line
// stays short whatever the model's names (generated names of 0 to 10^5 bytes, every stage).
TEST(ToleranceProgress, AReportsLineCutsLongPartNames) {
  std::mt19937_64 rng(40);
  std::uniform_int_distribution<int> letter('a', 'z');
  const std::size_t lengths[] = {0, 1, 199, 200, 201, 1000, 100000};
  for (int trial = 0; trial < 40; ++trial) {
    std::string first(lengths[rng() % 7], 'x'), second(lengths[rng() % 7], 'y');
    for (char& c : first) c = static_cast<char>(letter(rng));
    for (char& c : second) c = static_cast<char>(letter(rng));
    for (auto stage : {CSpaceBuildProgress::Stage::chart, CSpaceBuildProgress::Stage::classification}) {
      CSpaceBuildProgress report;
      report.stage = stage;
      report.first_part = first;
      report.second_part = second;
      report.chart = 1;
      report.charts = 4;
      report.total = 10;
      report.coefficient_bits = 400;
      const std::string line = report.text();
      SCOPED_TRACE(std::to_string(first.size()) + " / " + std::to_string(second.size()));
      // "hipair: " + two names of at most 200 bytes + "... (N characters)" each + the stage's words
      EXPECT_LE(line.size(), 8 + 2 * (200 + 30) + 150u);
      EXPECT_EQ(line.compare(0, 8, "hipair: "), 0);
      EXPECT_EQ(line.compare(8, std::min<std::size_t>(first.size(), 200), first, 0, 200), 0);
      const std::string second_shown = second.substr(0, 200);   // (whole when it has at most 200 bytes)
      EXPECT_NE(line.find(":" + second_shown), std::string::npos);
      if (first.size() <= 200 && second.size() <= 200)
        EXPECT_EQ(line.find("characters)"), std::string::npos) << "short names are shown whole";
      else
        EXPECT_NE(line.find("characters)"), std::string::npos) << "a cut name says its length";
    }
  }
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
