// The kernel slicer's shortcuts of session 13 must not change a single slice:
//   - a root's validity clauses are first evaluated on its isolating interval, and only an
//     undecided verdict refines it to 2^-24 and 2^-48 (interval evaluation is inclusion
//     isotone, so a verdict taken on the wider box is the one the narrower boxes give);
//   - an interval's class is read at the shared end of its points' isolating intervals when
//     they meet end to end, instead of at rational_between's sample (the class is constant
//     strictly between consecutive points: the premise of every slice, checked here).
// The test slices example pairs and generated gear pairs (random tooth counts) at generated
// values and windows — each query asked twice, and earlier queries asked again later — with a
// slicer that uses the shortcuts and one that does not, and requires identical slices: the same
// points (the same isolating intervals and polynomials, features, zero-clearance flags), the
// same interval classes, the same covered range.
//
// A short driver range (shorter than one grid step) draws its C-space path through the states
// on both sides of every event, not straight from the range's start to its end.
#include "algebra/real_filters.hpp"
#include "core/model_scale.hpp"
#include "kinematics/axis.hpp"
#include "kinematics/slice.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/error.hpp>
#include <hipair/kernel_slice.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

Rational chart_value(const ChartAxis& axis, std::mt19937_64& random) {
  Rational u(static_cast<long>(random() % (1u << 20)), 1L << 20);
  u.canonicalize();
  return Rational(axis.lo + (axis.hi - axis.lo) * u);
}

// What every comparison of two slices requires: the same covered range, classes, number of
// points, and per point the same features and zero-clearance flag.
void expect_same_structure(const ChartSlice& a, const ChartSlice& b, const std::string& where) {
  ASSERT_EQ(a.covered_lo, b.covered_lo) << where;
  ASSERT_EQ(a.covered_hi, b.covered_hi) << where;
  ASSERT_EQ(a.kinds, b.kinds) << where;
  ASSERT_EQ(a.points.size(), b.points.size()) << where;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].features, b.points[i].features) << where << ": point " << i;
    EXPECT_EQ(a.points[i].touching, b.points[i].touching) << where << ": point " << i;
  }
}

void expect_identical(const ChartSlice& a, const ChartSlice& b, const std::string& where) {
  expect_same_structure(a, b, where);
  if (::testing::Test::HasFatalFailure()) return;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const Real& x = a.points[i].value;
    const Real& y = b.points[i].value;
    EXPECT_EQ(x.exact, y.exact) << where << ": point " << i;
    EXPECT_EQ(x.lower, y.lower) << where << ": point " << i;
    EXPECT_EQ(x.upper, y.upper) << where << ": point " << i;
    EXPECT_TRUE(x.polynomial == y.polynomial) << where << ": point " << i;
  }
}

// The same slices as numbers: points equal exactly (algebra::compare), each a valid isolating
// interval (non-zero opposite signs of its polynomial at its ends); the isolating intervals may
// differ.
void expect_same_numbers(const ChartSlice& a, const ChartSlice& b, const std::string& where) {
  expect_same_structure(a, b, where);
  if (::testing::Test::HasFatalFailure()) return;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const Real& x = a.points[i].value;
    const Real& y = b.points[i].value;
    if (!y.exact) {
      int at_lower = algebra::sign_at(y.polynomial, y.lower), at_upper = algebra::sign_at(y.polynomial, y.upper);
      ASSERT_TRUE(y.lower < y.upper && at_lower != 0 && at_upper == -at_lower) << where << ": point " << i;
    }
    EXPECT_EQ(algebra::compare(x, y), 0) << where << ": point " << i;
  }
}

// The example spur gears with 7 + random() % spread_1 and 7 + random() % spread_2 teeth (in that
// order); `name` receives "gears Z1xZ2".
Model random_gear_pair(std::mt19937_64& random, long spread_1, long spread_2, std::string& name) {
  ReadOptions read;
  long z1 = 7 + static_cast<long>(random() % spread_1), z2 = 7 + static_cast<long>(random() % spread_2);
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.allow_out_of_tolerance = true;
  name = "gears " + std::to_string(z1) + "x" + std::to_string(z2);
  return read_model_file(example("spur-gears.json"), read);
}

// Test names from model file names: "cam-drive.json" -> cam_drive.
std::string model_param_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(0, info.param.find('.'));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

struct Query {
  std::size_t o = 0, f = 0;
  Rational value;
  std::optional<ChartWindow> window;
};

// Slices every chart pair of both followers of every pair of `model` at `values` generated
// queries each; returns the number of points compared.
// `plain_options` is the reference slicer's; with `same_intervals` the points must have the same
// isolating intervals, else the same numbers (exact comparison) with valid isolating intervals.
std::size_t compare_slicers(const Model& model, int values, std::uint64_t seed, const std::string& name,
                            const KernelSlicerOptions& plain_options = KernelSlicerOptions{true, false, false},
                            bool same_intervals = true, std::size_t* monotone_roots = nullptr,
                            SliceClassCounts* fast_counts = nullptr) {
  std::mt19937_64 random(seed);
  std::size_t compared = 0;
  for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
    for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second}) {
      std::unique_ptr<PairSlicer> plain, fast;
      try {
        plain = make_kernel_slicer(model, pair, follower, plain_options);
        fast = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{});
      } catch (const GeometryError&) {
        continue;   // a fixed follower, or not a fixed-axis pair
      }
      if (!plain->other_moves()) continue;
      std::vector<Query> asked;
      for (int k = 0; k < values; ++k) {
        Query q;
        if (!asked.empty() && k % 4 == 3) {
          q = asked[random() % asked.size()];   // asked again, after other slices
        } else {
          q.o = random() % plain->other_charts().size();
          q.f = random() % plain->follower_charts().size();
          q.value = chart_value(plain->other_charts()[q.o], random);
          const ChartAxis& axis = plain->follower_charts()[q.f];
          if (k % 3 != 0) {
            // windows like the engine's: narrow, around a point of the chart
            Rational centre = chart_value(axis, random);
            Rational half(static_cast<long>(1 + random() % 64), 1024);
            q.window = ChartWindow{centre - half, centre + half};
          }
          asked.push_back(q);
        }
        const ChartWindow* window = q.window ? &*q.window : nullptr;
        std::string where = name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) +
                            " charts " + std::to_string(q.o) + "," + std::to_string(q.f) + " at " + q.value.get_str();
        ChartSlice expected = plain->slice(q.o, q.value, q.f, window);
        ChartSlice first = fast->slice(q.o, q.value, q.f, window);
        ChartSlice second = fast->slice(q.o, q.value, q.f, window);   // asked again
        const auto expect = same_intervals ? expect_identical : expect_same_numbers;
        expect(expected, first, where);
        expect(expected, second, where + " (again)");
        compared += expected.points.size();
        if (::testing::Test::HasFailure()) return compared;
      }
      if (monotone_roots) *monotone_roots += kernel_slice_class_counts(*fast).monotone_roots;
      if (fast_counts) {
        const SliceClassCounts counts = kernel_slice_class_counts(*fast);
        fast_counts->monotone_roots += counts.monotone_roots;
        fast_counts->runs_rejected += counts.runs_rejected;
        fast_counts->runs_kept += counts.runs_kept;
      }
    }
  return compared;
}

class KinematicSliceFilters : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicSliceFilters, ValidityPrefilterGivesTheSlicesOfPlainSlicing) {
  Model model = read_model_file(example(GetParam()));
  EXPECT_GT(compare_slicers(model, 160, 20261128, GetParam()), 0u);
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicSliceFilters,
                         ::testing::Values("geneva.json", "ratchet.json", "escapement.json", "cam-follower.json",
                                           "cam-follower-lever.json", "cam-drive.json", "scotch-yoke.json"),
                         model_param_name);

// Generated spur-gear pairs: random tooth counts, the example's profile.
TEST(KinematicSliceFilters, GeneratedGearPairsGiveTheSlicesOfPlainSlicing) {
  std::mt19937_64 random(1313);
  std::size_t compared = 0;
  for (int trial = 0; trial < 3; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 8, 10, name);
    compared += compare_slicers(model, 60, random(), name);
    if (HasFailure()) return;
  }
  EXPECT_GT(compared, 0u);
}

// Session 40: the validity clauses are asked over a whole run of follower cells before its roots
// are sought (a run they certainly reject is dropped, one they certainly accept keeps its roots
// without valid()), and a monotone run's root is narrowed and its clauses asked before its
// square-free test. The slices must be the plain slicer's (no prefilter), interval for interval,
// on generated cases: the ratchet at zero nose clearance with random rational radii, the scotch
// yoke's pin in an exact slot of random rational width (zero clearance: tangent along the
// slot), and the ratchet and the Geneva drive scaled by 2^300 and 2^-300. Both verdicts must
// occur (runs dropped and runs kept), and monotone runs must isolate roots.
TEST(KinematicSliceFilters, RunVerdictsGiveThePlainSlicesAtZeroClearanceAndExtremeScales) {
  std::mt19937_64 random(4040);
  std::size_t compared = 0;
  SliceClassCounts counts;
  auto random_rational = [&](long lo, long hi) {
    Rational r(lo * 4096 + static_cast<long>(random() % static_cast<std::uint64_t>((hi - lo) * 4096 + 1)), 4096);
    r.canonicalize();
    return r;
  };
  for (int trial = 0; trial < 2; ++trial) {
    ReadOptions read;
    read.allow_out_of_tolerance = true;
    read.parameter_values["nose-clearance"] = Rational(0);
    read.parameter_values["tip-radius"] = random_rational(29, 31);
    read.parameter_values["root-radius"] = random_rational(23, 25);
    const Model ratchet = read_model_file(example("ratchet.json"), read);
    compared += compare_slicers(ratchet, 40, random(), "ratchet at zero clearance", KernelSlicerOptions{true, false, false},
                                true, nullptr, &counts);
    if (HasFailure()) return;
    ReadOptions yoke;
    yoke.allow_out_of_tolerance = true;
    const Rational pin = random_rational(3, 6);
    yoke.parameter_values["pin-radius"] = pin;
    yoke.parameter_values["slot-width"] = Rational(2 * pin);
    compared += compare_slicers(read_model_file(example("scotch-yoke.json"), yoke), 40, random(), "scotch yoke, exact slot",
                                KernelSlicerOptions{true, false, false}, true, nullptr, &counts);
    if (HasFailure()) return;
  }
  for (const char* name : {"ratchet.json", "geneva.json"})
    for (long shift : {300L, -300L}) {
      const Model scaled = scaled_model(read_model_file(example(name)), shift);
      compared += compare_slicers(scaled, 12, random(), std::string(name) + " scaled by 2^" + std::to_string(shift),
                                  KernelSlicerOptions{true, false, false}, true, nullptr, &counts);
      if (HasFailure()) return;
    }
  std::cout << "[ run verdicts ] " << compared << " points compared; runs dropped " << counts.runs_rejected << ", kept "
            << counts.runs_kept << "; monotone roots " << counts.monotone_roots << "\n";
  EXPECT_GT(compared, 0u);
  EXPECT_GT(counts.runs_rejected, 0u);
  EXPECT_GT(counts.runs_kept, 0u);
  EXPECT_GT(counts.monotone_roots, 0u);
}

// Session 26: a slice's interval classes carried over from the previous slice of the same chart
// pair (KernelSlicerOptions::transfer_classes) must be the overlap oracle's. Walks of the
// driver with steps from 10^-7 to 1/10 of its chart (the engine's grid steps, bisections and
// jumps), windows like the engine's and whole charts, charts switched now and then: every
// slice of the transferring slicer equals the oracle-only slicer's. The walks must include
// intervals whose class differs from the previous slice's class at the same follower value
// (the cases a proof that misses a curve gets wrong) and many transferred classes.
struct TransferCounts {
  std::size_t slices = 0, transferred = 0, classified = 0, changed = 0;
};

TransferCounts compare_transfers(const Model& model, int walks, int steps, std::uint64_t seed, const std::string& name) {
  std::mt19937_64 random(seed);
  TransferCounts counts;
  for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
    for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second}) {
      std::unique_ptr<PairSlicer> plain, fast;
      try {
        KernelSlicerOptions oracle_only;
        oracle_only.transfer_classes = false;
        plain = make_kernel_slicer(model, pair, follower, oracle_only);
        fast = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{});
      } catch (const GeometryError&) {
        continue;   // a fixed follower, or not a fixed-axis pair
      }
      if (!plain->other_moves()) continue;
      for (int walk = 0; walk < walks; ++walk) {
        std::size_t o = random() % plain->other_charts().size(), f = random() % plain->follower_charts().size();
        const ChartAxis& other_axis = plain->other_charts()[o];
        Rational u = chart_value(other_axis, random);
        Rational centre = chart_value(plain->follower_charts()[f], random);
        std::optional<ChartSlice> last;   // the oracle's previous slice of chart pair (o, f)
        for (int k = 0; k < steps; ++k) {
          if (random() % 16 == 0) {   // another follower chart: the memo of (o, f) waits
            f = random() % plain->follower_charts().size();
            centre = chart_value(plain->follower_charts()[f], random);
            last.reset();
          }
          static const long scales[] = {10000000, 1000000, 100000, 10000, 1000, 100, 10};
          Rational delta(static_cast<long>(random() % 1000) - 500, 500L * scales[random() % 7]);
          delta.canonicalize();
          u = std::clamp(Rational(u + delta * (other_axis.hi - other_axis.lo)), other_axis.lo, other_axis.hi);
          const ChartAxis& axis = plain->follower_charts()[f];
          centre = std::clamp(Rational(centre + delta * (axis.hi - axis.lo) / 4), axis.lo, axis.hi);
          std::optional<ChartWindow> window;
          if (random() % 4 != 0) {
            Rational half(static_cast<long>(1 + random() % 64), 1024);
            window = ChartWindow{centre - half, centre + half};
          }
          const ChartWindow* w = window ? &*window : nullptr;
          std::string where = name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) +
                              " charts " + std::to_string(o) + "," + std::to_string(f) + " at " + u.get_str();
          ChartSlice expected = plain->slice(o, u, f, w);
          ChartSlice got = fast->slice(o, u, f, w);
          expect_identical(expected, got, where);
          if (::testing::Test::HasFailure()) return counts;
          ++counts.slices;
          // intervals whose class differs from the previous slice's at the same follower value
          if (last)
            for (std::size_t i = 0; i <= expected.points.size(); ++i) {
              if (expected.kinds[i] == SliceKind::empty) continue;
              Real a = i == 0 ? Real::from_rational(expected.covered_lo) : expected.points[i - 1].value;
              Real b = i == expected.points.size() ? Real::from_rational(expected.covered_hi) : expected.points[i].value;
              Rational s = algebra::rational_between(a, b);
              if (!(last->covered_lo < s && s < last->covered_hi)) continue;
              std::size_t j = 0;
              while (j < last->points.size() && last->points[j].value.compare(s) < 0) ++j;
              if (j < last->points.size() && last->points[j].value.compare(s) == 0) continue;
              if (last->kinds[j] != expected.kinds[i]) ++counts.changed;
            }
          last = std::move(expected);
        }
      }
      SliceClassCounts used = kernel_slice_class_counts(*fast);
      counts.transferred += used.transferred;
      counts.classified += used.classified;
      EXPECT_EQ(kernel_slice_class_counts(*plain).transferred, 0u);
    }
  return counts;
}

// The examples the class-transfer and monotone-run tests slice.
const std::vector<std::string> walk_examples = {"geneva.json",        "ratchet.json",     "escapement.json",
                                                "cam-follower.json",  "cam-follower-lever.json", "cam-drive.json",
                                                "scotch-yoke.json",   "two-pin-wedge.json", "lift-chain.json"};

class KinematicClassTransfer : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicClassTransfer, CarriedClassesAreTheOraclesOnDriverWalks) {
  Model model = read_model_file(example(GetParam()));
  TransferCounts counts = compare_transfers(model, 6, 60, 20261130, GetParam());
  if (HasFailure()) return;
  EXPECT_GT(counts.slices, 0u);
  EXPECT_GT(counts.transferred, counts.classified / 4) << "transferred " << counts.transferred << ", oracle " << counts.classified;
  EXPECT_GT(counts.changed, 0u) << "no interval changed its class between consecutive slices";
  std::cout << GetParam() << ": " << counts.slices << " slices, " << counts.transferred << " classes carried over, "
            << counts.classified << " by the oracle, " << counts.changed << " intervals whose class changed since the previous slice\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicClassTransfer,
                         ::testing::ValuesIn(walk_examples),
                         model_param_name);

// Generated spur-gear pairs (random tooth counts): many curves per strip, neighbouring teeth's
// curves close to the active one.
TEST(KinematicClassTransfer, GeneratedGearPairsCarryTheOraclesClasses) {
  std::mt19937_64 random(2611);
  TransferCounts counts;
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 6, 6, name);
    TransferCounts one = compare_transfers(model, 2, 30, random(), name);
    if (HasFailure()) return;
    counts.slices += one.slices;
    counts.transferred += one.transferred;
    counts.classified += one.classified;
    counts.changed += one.changed;
  }
  EXPECT_GT(counts.transferred, 0u);
  EXPECT_GT(counts.changed, 0u);
  std::cout << "gears: " << counts.slices << " slices, " << counts.transferred << " carried over, " << counts.classified
            << " by the oracle, " << counts.changed << " changed\n";
}

// Session 27: a curve's root on a run of follower cells where the curve is certified monotone
// (KernelSlicerOptions::monotone_runs) is isolated by the run itself, from the signs at its ends,
// without Descartes. The slices must hold the same points as numbers as Descartes' (the same
// features, flags and classes), on the example pairs and generated gear pairs at generated
// values and windows; the isolating intervals differ, so they are only checked to isolate.
KernelSlicerOptions descartes_only() {
  KernelSlicerOptions options;
  options.monotone_runs = false;
  return options;
}

class KinematicMonotoneRuns : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicMonotoneRuns, SlicesHoldDescartesRootsAsNumbers) {
  Model model = read_model_file(example(GetParam()));
  std::size_t monotone = 0;
  std::size_t compared = compare_slicers(model, 160, 20261130, GetParam(), descartes_only(), false, &monotone);
  if (HasFailure()) return;
  EXPECT_GT(compared, 0u);
  EXPECT_GT(monotone, compared / 10) << "the monotone runs isolated few roots";
  std::cout << GetParam() << ": " << compared << " points compared, " << monotone << " isolated by monotone runs\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicMonotoneRuns,
                         ::testing::ValuesIn(walk_examples),
                         model_param_name);

TEST(KinematicMonotoneRuns, GeneratedGearPairsHoldDescartesRootsAsNumbers) {
  std::mt19937_64 random(2711);
  std::size_t compared = 0, monotone = 0;
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 8, 10, name);
    compared += compare_slicers(model, 30, random(), name, descartes_only(), false, &monotone);
    if (HasFailure()) return;
  }
  EXPECT_GT(compared, 0u);
  EXPECT_GT(monotone, compared / 10);
  std::cout << "gears: " << compared << " points compared, " << monotone << " isolated by monotone runs\n";
}

// Whole analyses with and without monotone runs: the report and the samples byte-identical (the
// engine reads no isolating interval: positions and rates are taken at canonical
// approximations), on the examples and on generated gear pairs over a short range.
// `fast_path` is a per-thread switch (on by default), turned to `on` for this analysis.
std::pair<std::string, std::string> analysis_outputs(const Model& model, const KinematicsOptions& options,
                                                     bool& (*fast_path)(), bool on) {
  fast_path() = on;
  KinematicsResult result = analyze_kinematics(model, options);
  fast_path() = true;
  result.seconds = 0;
  return {kinematics_json_report(result), kinematics_csv(result)};
}

// The example's analysis (with accelerations) with and without the fast path: byte-identical.
void expect_same_analyses(const std::string& file, bool& (*fast_path)()) {
  Model model = read_model_file(example(file));
  KinematicsOptions options;
  options.accelerations = true;
  auto with = analysis_outputs(model, options, fast_path, true);
  auto without = analysis_outputs(model, options, fast_path, false);
  EXPECT_FALSE(with.first.empty());
  EXPECT_TRUE(with.first == without.first) << file << ": report.json differs";
  EXPECT_TRUE(with.second == without.second) << file << ": kinematics.csv differs";
}

// Three generated gear pairs over a quarter radian from a random start, with and without the
// fast path: byte-identical.
void expect_same_short_gear_analyses(std::uint64_t seed, bool& (*fast_path)()) {
  std::mt19937_64 random(seed);
  for (int trial = 0; trial < 3; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 10, 10, name);
    KinematicsOptions options;
    double start = static_cast<double>(random() % 1000) / 1000;
    options.range = std::make_pair(Rational(start), Rational(start + 0.25));
    options.steps_per_cycle = 360;
    auto with = analysis_outputs(model, options, fast_path, true);
    auto without = analysis_outputs(model, options, fast_path, false);
    EXPECT_TRUE(with.first == without.first) << name << ": report.json differs";
    EXPECT_TRUE(with.second == without.second) << name << ": kinematics.csv differs";
  }
}

class KinematicMonotoneAnalyses : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicMonotoneAnalyses, ReportsAreTheSameWithoutMonotoneRuns) {
  expect_same_analyses(GetParam(), monotone_runs_switch);
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicMonotoneAnalyses,
                         ::testing::Values("geneva.json", "ratchet.json", "cam-follower.json", "cam-drive.json",
                                           "scotch-yoke.json", "two-pin-wedge.json", "lift-chain.json"),
                         model_param_name);

TEST(KinematicMonotoneAnalyses, GeneratedGearPairsOverShortRanges) {
  expect_same_short_gear_analyses(2712, monotone_runs_switch);
}

// The engine's reading ahead (session 29): a follower's update slices first the window its old
// free range needs, and reads the narrower windows it asks before that one off that slice
// (restrict_chart_slice, ChartSliceMemo).
// - A slice read off a wider one must be the slicer's own slice of the narrower window: the same
//   points as numbers (exact comparison), features, zero-clearance and undecided flags, classes
//   and covered range; or nothing, when it cannot be read (a point on an end of the narrower
//   range, a range the wider slice does not cover). Generated on the example pairs and on
//   generated gear pairs, at random driver values and at the driver values of the analysis'
//   events, with random wide windows (and whole charts) and narrow windows inside them, at
//   their edges, at exact points and isolating-interval ends, and beyond them.
// - Whole analyses with and without the reading ahead (window_reading_switch) must give
//   byte-identical reports and samples, on the examples and on generated gear pairs over short
//   ranges; and the reading ahead must have been used.

Rational fraction_of(const Rational& lo, const Rational& hi, std::uint64_t numerator, long bits) {
  Rational u(static_cast<long>(numerator % (1ul << bits)), 1L << bits);
  u.canonicalize();
  return Rational(lo + (hi - lo) * u);
}

struct ReadCounts {
  std::size_t read = 0, refused = 0, points = 0, at_points = 0;
};

// `read` must be `direct` (the slicer's slice of the same window) as numbers, with the same
// exactness and undecided flags.
void expect_same_slice(const ChartSlice& direct, const ChartSlice& read, const std::string& where) {
  expect_same_structure(direct, read, where);
  if (::testing::Test::HasFatalFailure()) return;
  for (std::size_t i = 0; i < direct.points.size(); ++i) {
    EXPECT_EQ(algebra::compare(direct.points[i].value, read.points[i].value), 0) << where << ": point " << i;
    EXPECT_EQ(direct.points[i].value.exact, read.points[i].value.exact) << where << ": point " << i;
    EXPECT_EQ(direct.points[i].undecided, read.points[i].undecided) << where << ": point " << i;
  }
}

// Narrow windows of `wide` (over `range`, the wide slice's covered range) for a test: random
// ones inside, ones sharing an end with the range, ones ending at an exact point or at a point's
// isolating interval's end, and ones reaching beyond the range.
std::vector<ChartWindow> narrow_windows(const ChartSlice& wide, std::mt19937_64& random) {
  const Rational &lo = wide.covered_lo, &hi = wide.covered_hi;
  std::vector<ChartWindow> out;
  for (int k = 0; k < 6; ++k) {
    Rational a = fraction_of(lo, hi, random(), 20), b = fraction_of(lo, hi, random(), 20);
    if (b < a) std::swap(a, b);
    out.push_back(ChartWindow{a, b});
  }
  out.push_back(ChartWindow{lo, fraction_of(lo, hi, random(), 10)});
  out.push_back(ChartWindow{fraction_of(lo, hi, random(), 10), hi});
  out.push_back(ChartWindow{lo, hi});
  Rational width = hi - lo;
  out.push_back(ChartWindow{lo - width / 8, fraction_of(lo, hi, random(), 10)});
  out.push_back(ChartWindow{fraction_of(lo, hi, random(), 10), hi + width / 8});
  for (const SlicePoint& point : wide.points) {
    if (random() % 3 != 0) continue;
    // ends at the point itself when it is exact, else at its isolating interval's ends
    const Rational& at = point.value.exact ? point.value.lower : (random() % 2 ? point.value.lower : point.value.upper);
    out.push_back(ChartWindow{at, std::max(at, fraction_of(lo, hi, random(), 16))});
    out.push_back(ChartWindow{std::min(at, fraction_of(lo, hi, random(), 16)), at});
  }
  return out;
}

// Slices each moving-other pair of `model` at `values` random driver values and at `extra`
// values, in wide windows, and compares every narrow window read off a wide slice with the
// slicer's own slice of it.
ReadCounts compare_reads(const Model& model, int values, const std::vector<Rational>& extra, std::uint64_t seed,
                         const std::string& name) {
  std::mt19937_64 random(seed);
  ReadCounts counts;
  for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
    for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second}) {
      std::unique_ptr<PairSlicer> slicer;
      try {
        slicer = make_kernel_slicer(model, pair, follower);
      } catch (const GeometryError&) {
        continue;   // a fixed follower, or not a fixed-axis pair
      }
      if (!slicer->other_moves()) continue;
      std::vector<std::pair<std::size_t, Rational>> driver_values;
      for (int k = 0; k < values; ++k) {
        std::size_t o = random() % slicer->other_charts().size();
        const ChartAxis& axis = slicer->other_charts()[o];
        driver_values.emplace_back(o, fraction_of(axis.lo, axis.hi, random(), 24));
      }
      for (const Rational& value : extra)
        for (std::size_t o = 0; o < slicer->other_charts().size(); ++o)
          if (slicer->other_charts()[o].lo <= value && value <= slicer->other_charts()[o].hi) driver_values.emplace_back(o, value);
      for (const auto& [o, value] : driver_values) {
        std::size_t f = random() % slicer->follower_charts().size();
        const ChartAxis& chart = slicer->follower_charts()[f];
        std::optional<ChartWindow> wide_window;
        if (random() % 4 != 0) {
          Rational centre = fraction_of(chart.lo, chart.hi, random(), 20);
          Rational half = (chart.hi - chart.lo) * Rational(static_cast<long>(1 + random() % 64), 256);
          wide_window = ChartWindow{centre - half, centre + half};
        }
        std::string where = name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) + " charts " +
                            std::to_string(o) + "," + std::to_string(f) + " at " + value.get_str();
        ChartSlice wide = slicer->slice(o, value, f, wide_window ? &*wide_window : nullptr);
        for (const ChartWindow& narrow : narrow_windows(wide, random)) {
          std::optional<ChartSlice> read = restrict_chart_slice(wide, chart, &narrow);
          Rational lo = std::max(narrow.lo, chart.lo), hi = std::min(narrow.hi, chart.hi);
          bool inside = wide.covered_lo <= lo && hi <= wide.covered_hi && lo < hi;
          bool at_point = std::any_of(wide.points.begin(), wide.points.end(), [&](const SlicePoint& p) {
            return inside && (algebra::compare_filtered(p.value, lo) == 0 || algebra::compare_filtered(p.value, hi) == 0);
          });
          counts.at_points += at_point;
          std::string case_name = where + " window " + narrow.lo.get_str() + " .. " + narrow.hi.get_str();
          // read exactly when the narrower range lies inside and no point lies on its ends
          EXPECT_EQ(read.has_value(), inside && !at_point) << case_name;
          if (!read) {
            ++counts.refused;
            continue;
          }
          ++counts.read;
          counts.points += read->points.size();
          expect_same_slice(slicer->slice(o, value, f, &narrow), *read, case_name);
          if (::testing::Test::HasFailure()) return counts;
        }
      }
    }
  return counts;
}

// The driver chart values of an analysis' events (both ends of each located interval).
std::vector<Rational> event_values(const Model& model) {
  KinematicsOptions options;
  options.reversal = false;
  KinematicsResult result = analyze_kinematics(model, options);
  std::vector<Rational> out;
  for (const KinematicEvent& event : result.events) {
    out.push_back(event.at.chart_lower);
    out.push_back(event.at.chart_upper);
  }
  if (out.size() > 24) out.resize(24);
  return out;
}

const std::vector<std::string> reading_examples = {
    "geneva.json",       "ratchet.json",          "escapement.json",  "cam-follower.json",   "cam-follower-lever.json",
    "cam-drive.json",    "scotch-yoke.json",      "two-pin-wedge.json", "lift-chain.json",   "cam-shim-stack.json",
    "geneva-drive.json", "geneva-template.json"};

class KinematicWindowReading : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicWindowReading, NarrowWindowsReadOffAWideSliceAreTheSlicersOwn) {
  Model model = read_model_file(example(GetParam()));
  ReadCounts counts = compare_reads(model, 24, event_values(model), 20261130, GetParam());
  if (HasFailure()) return;
  EXPECT_GT(counts.read, 100u);
  EXPECT_GT(counts.refused, 10u);
  std::cout << GetParam() << ": " << counts.read << " narrow slices read (" << counts.points << " points), "
            << counts.refused << " refused (" << counts.at_points << " with a point on an end)\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicWindowReading, ::testing::ValuesIn(reading_examples), model_param_name);

TEST(KinematicWindowReading, GeneratedGearPairsReadTheSlicersOwnSlices) {
  std::mt19937_64 random(2929);
  ReadCounts total;
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 6, 6, name);
    ReadCounts counts = compare_reads(model, 4, {}, random(), name);
    if (HasFailure()) return;
    total.read += counts.read;
    total.points += counts.points;
  }
  EXPECT_GT(total.read, 50u);
  EXPECT_GT(total.points, total.read);
  std::cout << "gears: " << total.read << " narrow slices read (" << total.points << " points)\n";
}

// Whole analyses with and without the reading ahead, and the reading ahead used (on the ratchet
// most updates read narrower windows off a wider slice).
class KinematicWindowReadingAnalyses : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicWindowReadingAnalyses, ReportsAreTheSameWithoutReadingAhead) {
  const std::size_t reads_before = window_reads();
  expect_same_analyses(GetParam(), window_reading_switch);
  std::cout << GetParam() << ": " << window_reads() - reads_before << " chart slices read off wider ones\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicWindowReadingAnalyses, ::testing::ValuesIn(reading_examples),
                         model_param_name);

TEST(KinematicWindowReadingAnalyses, TheRatchetReadsAhead) {
  Model model = read_model_file(example("ratchet.json"));
  KinematicsOptions options;
  options.reversal = false;
  const std::size_t reads_before = window_reads();
  analyze_kinematics(model, options);
  EXPECT_GT(window_reads() - reads_before, 2000u);
}

TEST(KinematicWindowReadingAnalyses, GeneratedGearPairsOverShortRanges) {
  expect_same_short_gear_analyses(2930, window_reading_switch);
}

// Geneva over a range shorter than one grid step around the wheel's first contact start: the
// path of the pair runs through the event (the wheel dwells up to it, then turns), so besides
// the range's two ends it has the states on both sides of the event, and the wheel's
// coordinate is unchanged up to the event.
TEST(AnalyzeShortRange, PathPassesThroughTheEventsOfARangeShorterThanAGridStep) {
  Model model = read_model_file(example("geneva.json"));
  KinematicsOptions full;
  full.reversal = false;
  KinematicsResult whole = analyze_kinematics(model, full);
  const KinematicEvent* start = nullptr;
  for (const KinematicEvent& event : whole.events)
    if (event.kind == KinematicEvent::Kind::contact_start) {
      start = &event;
      break;
    }
  ASSERT_NE(start, nullptr);
  double at = 0.5 * (start->at.coordinate.lower + start->at.coordinate.upper);
  double step = 2 * std::numbers::pi / full.steps_per_cycle;
  KinematicsOptions options = full;
  Rational lo(at - step / 4), hi(at + step / 4);
  options.range = std::make_pair(lo, hi);
  KinematicsResult result = analyze_kinematics(model, options);
  ASSERT_FALSE(result.paths.empty());
  const PairPath& path = result.paths.front();
  ASSERT_GE(path.points.size(), 4u) << "the path has only the range's ends";
  ASSERT_FALSE(result.events.empty());
  // before the event the wheel dwells: the first points share the wheel's coordinate; after it,
  // the wheel turns
  bool driver_is_x = path.x_part == result.driver;
  auto driver = [&](const PathPoint& p) { return driver_is_x ? p.x : p.y; };
  auto wheel = [&](const PathPoint& p) { return driver_is_x ? p.y : p.x; };
  EXPECT_EQ(wheel(path.points[0]), wheel(path.points[1]));
  EXPECT_NE(wheel(path.points.front()), wheel(path.points.back()));
  EXPECT_NE(driver(path.points[1]), driver(path.points[0]));
  EXPECT_FALSE(path.points[0].contact);
  EXPECT_TRUE(path.points.back().contact);
}


// Session 61 (tol61b): the public windowed slice (hipair::KernelSlicer::slice with window_lo,
// window_hi; tolerance --contact-changes relies on it) gives exactly the whole slice's answer
// inside the window. Generated: random spur gear pairs and the cam examples, random driver and
// follower chart values, windows with ends drawn from chart values, the chart's ends and beyond,
// the whole slice's exact points and its points' isolating bounds (next to points). Oracle: the
// whole chart's slice on the same slicer, restricted to the window clipped to the chart: the
// same points (exactly equal numbers, features, may_touch) and the same classes between them,
// `outside` for the empty piece at a point on a window end.
TEST(KernelSlicerWindows, WindowedSlicesAreTheWholeSlicesInside) {
  const std::uint64_t seed = test::test_seed(61);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  std::vector<std::pair<std::string, Model>> models;
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, 6, 6, name);
    models.emplace_back(name, std::move(model));
  }
  for (const char* file : {"cam-follower.json", "cam-drive.json"}) models.emplace_back(file, read_model_file(example(file)));
  auto to_real = [](const AlgebraicNumber& a) {
    algebra::Real r;
    r.polynomial = a.polynomial;
    r.lower = a.lower;
    r.upper = a.upper;
    r.exact = a.exact;
    return r;
  };
  std::size_t windows = 0, points = 0, at_ends = 0;
  for (const auto& [name, model] : models)
    for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
      for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second}) {
        const std::size_t other = follower == model.pairs[pair].first ? model.pairs[pair].second : model.pairs[pair].first;
        std::unique_ptr<PairSlicer> charts;
        try {
          charts = make_kernel_slicer(model, pair, follower);
        } catch (const GeometryError&) {
          continue;   // a fixed follower, or not a fixed-axis pair
        }
        if (!charts->other_moves()) continue;
        KernelSlicer slicer(model, other, follower);
        for (int position = 0; position < 4; ++position) {
          const ChartAxis& o_axis = charts->other_charts()[random() % charts->other_charts().size()];
          const ChartAxis& f_axis = charts->follower_charts()[random() % charts->follower_charts().size()];
          const Rational o_t = chart_value(o_axis, random), f_t = chart_value(f_axis, random);
          const std::string where = name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) +
                                    " at " + o_t.get_str() + (o_axis.half_turn ? " (half)" : "") + ", " + f_t.get_str() +
                                    (f_axis.half_turn ? " (half)" : "");
          std::optional<KernelSlice> whole = slicer.slice(o_t, o_axis.half_turn, f_t, f_axis.half_turn);
          ASSERT_TRUE(whole.has_value()) << where;
          ASSERT_EQ(whole->kinds.size(), whole->points.size() + 1) << where;
          std::vector<algebra::Real> reals;
          for (const KernelSlice::Point& p : whole->points) reals.push_back(to_real(p.at));
          // window ends: chart values, the chart's ends and beyond, exact points, isolating bounds
          std::vector<Rational> ends{f_axis.lo, f_axis.hi, Rational(f_axis.lo - 1), Rational(f_axis.hi + 1)};
          for (int k = 0; k < 4; ++k) ends.push_back(chart_value(f_axis, random));
          std::vector<Rational> exact_points;
          for (const algebra::Real& r : reals) {
            ends.push_back(r.lower);
            if (!r.exact) ends.push_back(r.upper);
            else exact_points.push_back(r.lower);
          }
          for (int w = 0; w < 10; ++w) {
            Rational lo = ends[random() % ends.size()], hi = ends[random() % ends.size()];
            if (w % 3 == 0 && !exact_points.empty()) lo = exact_points[random() % exact_points.size()];   // a point on an end
            if (hi < lo) std::swap(lo, hi);
            const Rational clip_lo = std::max(lo, f_axis.lo), clip_hi = std::min(hi, f_axis.hi);
            if (!(lo < hi) || !(clip_lo < clip_hi)) continue;
            const std::string case_name = where + " window " + lo.get_str() + " .. " + hi.get_str();
            std::optional<KernelSlice> part = slicer.slice(o_t, o_axis.half_turn, f_t, f_axis.half_turn, lo, hi);
            ASSERT_TRUE(part.has_value()) << case_name;
            // the whole slice's points in [clip_lo, clip_hi]: indices [first, last)
            std::size_t first = 0, last = 0;
            while (first < reals.size() && reals[first].compare(clip_lo) < 0) ++first;
            last = first;
            while (last < reals.size() && reals[last].compare(clip_hi) <= 0) ++last;
            ASSERT_EQ(part->points.size(), last - first) << case_name;
            ASSERT_EQ(part->kinds.size(), part->points.size() + 1) << case_name;
            for (std::size_t i = 0; i < part->points.size(); ++i) {
              const KernelSlice::Point &got = part->points[i], &want = whole->points[first + i];
              EXPECT_EQ(algebra::compare(to_real(got.at), reals[first + i]), 0) << case_name << ": point " << i;
              EXPECT_EQ(got.may_touch, want.may_touch) << case_name << ": point " << i;
              EXPECT_TRUE(got.features == want.features) << case_name << ": point " << i;
              // the class after the point (up to the next point, or to the window's end)
              const bool at_end = i + 1 == part->points.size() && reals[first + i].compare(clip_hi) == 0;
              EXPECT_EQ(part->kinds[i + 1], at_end ? KernelSlice::Kind::outside : whole->kinds[first + i + 1])
                  << case_name << ": after point " << i;
              at_ends += at_end;
            }
            const bool at_start = !part->points.empty() && reals[first].compare(clip_lo) == 0;
            EXPECT_EQ(part->kinds.front(), at_start ? KernelSlice::Kind::outside : whole->kinds[first])
                << case_name << ": before the first point";
            at_ends += at_start;
            ++windows;
            points += part->points.size();
            if (HasFailure()) return;
          }
        }
      }
  EXPECT_GT(windows, 100u);
  EXPECT_GT(points, windows);
  EXPECT_GT(at_ends, 5u);
  std::cout << windows << " windows, " << points << " points, " << at_ends << " on a window end\n";
}

}  // namespace
}  // namespace hipair::kinematics_detail
