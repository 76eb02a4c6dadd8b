// The engine's reading ahead (session 29): a follower's update slices first the window its old
// free range needs, and reads the narrower windows it asks before that one off that slice
// (restrict_chart_slice, ChartSliceMemo).
//
// - A slice read off a wider one must be the slicer's own slice of the narrower window: the same
//   points as numbers (exact comparison), features, zero-clearance and undecided flags, classes
//   and covered range; or nothing, when it cannot be read (a point on an end of the narrower
//   range, a range the wider slice does not cover). Generated on the example pairs and on
//   generated gear pairs, at random driver values and at the driver values of the analysis'
//   events, with random wide windows (and whole charts) and narrow windows inside them, at
//   their edges, at exact points and beyond them.
// - Whole analyses with and without the reading ahead (window_reading_switch) must give
//   byte-identical reports and samples, on the examples and on generated gear pairs over short
//   ranges; and the reading ahead must have been used.
#include "algebra/real_filters.hpp"
#include "kinematics/axis.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

Rational fraction_of(const Rational& lo, const Rational& hi, std::uint64_t numerator, long bits) {
  Rational u(static_cast<long>(numerator % (1ul << bits)), 1L << bits);
  u.canonicalize();
  return Rational(lo + (hi - lo) * u);
}

struct ReadCounts {
  std::size_t read = 0, refused = 0, points = 0, at_points = 0;
};

// `read` must be `direct` (the slicer's slice of the same window) as numbers.
void expect_same_slice(const ChartSlice& direct, const ChartSlice& read, const std::string& where) {
  ASSERT_EQ(direct.covered_lo, read.covered_lo) << where;
  ASSERT_EQ(direct.covered_hi, read.covered_hi) << where;
  ASSERT_EQ(direct.kinds, read.kinds) << where;
  ASSERT_EQ(direct.points.size(), read.points.size()) << where;
  for (std::size_t i = 0; i < direct.points.size(); ++i) {
    EXPECT_EQ(algebra::compare(direct.points[i].value, read.points[i].value), 0) << where << ": point " << i;
    EXPECT_EQ(direct.points[i].value.exact, read.points[i].value.exact) << where << ": point " << i;
    EXPECT_EQ(direct.points[i].features, read.points[i].features) << where << ": point " << i;
    EXPECT_EQ(direct.points[i].touching, read.points[i].touching) << where << ": point " << i;
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

std::string model_param_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(0, info.param.find('.'));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

Model random_gear_pair(std::mt19937_64& random, std::string& name) {
  ReadOptions read;
  long z1 = 7 + static_cast<long>(random() % 10), z2 = 7 + static_cast<long>(random() % 10);
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.allow_out_of_tolerance = true;
  name = "gears " + std::to_string(z1) + "x" + std::to_string(z2);
  return read_model_file(example("spur-gears.json"), read);
}

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
  for (int trial = 0; trial < 3; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, name);
    ReadCounts counts = compare_reads(model, 12, {}, random(), name);
    if (HasFailure()) return;
    total.read += counts.read;
    total.points += counts.points;
  }
  EXPECT_GT(total.read, 100u);
  EXPECT_GT(total.points, total.read);
  std::cout << "gears: " << total.read << " narrow slices read (" << total.points << " points)\n";
}

// Whole analyses with and without the reading ahead.
std::pair<std::string, std::string> analysis_outputs(const Model& model, const KinematicsOptions& options, bool reading) {
  window_reading_switch() = reading;
  KinematicsResult result = analyze_kinematics(model, options);
  window_reading_switch() = true;
  result.seconds = 0;
  return {kinematics_json_report(result), kinematics_csv(result)};
}

class KinematicWindowReadingAnalyses : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicWindowReadingAnalyses, ReportsAreTheSameWithoutReadingAhead) {
  Model model = read_model_file(example(GetParam()));
  KinematicsOptions options;
  options.accelerations = true;
  const std::size_t reads_before = window_reads();
  auto with = analysis_outputs(model, options, true);
  const std::size_t reads = window_reads() - reads_before;
  auto without = analysis_outputs(model, options, false);
  EXPECT_FALSE(with.first.empty());
  EXPECT_TRUE(with.first == without.first) << GetParam() << ": report.json differs";
  EXPECT_TRUE(with.second == without.second) << GetParam() << ": kinematics.csv differs";
  std::cout << GetParam() << ": " << reads << " chart slices read off wider ones\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicWindowReadingAnalyses, ::testing::ValuesIn(reading_examples),
                         model_param_name);

// The reading ahead is used: on the ratchet most updates read narrower windows off a wider slice.
TEST(KinematicWindowReadingAnalyses, TheRatchetReadsAhead) {
  Model model = read_model_file(example("ratchet.json"));
  KinematicsOptions options;
  options.reversal = false;
  const std::size_t reads_before = window_reads();
  analyze_kinematics(model, options);
  EXPECT_GT(window_reads() - reads_before, 2000u);
}

TEST(KinematicWindowReadingAnalyses, GeneratedGearPairsOverShortRanges) {
  std::mt19937_64 random(2930);
  for (int trial = 0; trial < 3; ++trial) {
    std::string name;
    Model model = random_gear_pair(random, name);
    KinematicsOptions options;
    double start = static_cast<double>(random() % 1000) / 1000;
    options.range = std::make_pair(Rational(start), Rational(start + 0.25));
    options.steps_per_cycle = 360;
    auto with = analysis_outputs(model, options, true);
    auto without = analysis_outputs(model, options, false);
    EXPECT_TRUE(with.first == without.first) << name << ": report.json differs";
    EXPECT_TRUE(with.second == without.second) << name << ": kinematics.csv differs";
  }
}

}  // namespace
}  // namespace hipair::kinematics_detail
