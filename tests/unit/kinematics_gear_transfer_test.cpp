// Session 33: a carried class's proof on gear pairs. The kernel slicer carries an interval's
// class over from the previous slice when no curve that may vanish at the sample vanishes on
// the segment {driver between the two slices} x {sample} (KernelSlicerOptions::transfer_classes).
// Its proof now evaluates each curve's enclosure collapsed once per slice over the driver
// interval (a polynomial in the follower coordinate), and may evaluate as many curves as the two
// parts have edges (KernelSlicerOptions::proof_curves; 32 before, which carried no class of a
// gear pair: a gear sample meets a few hundred curves).
//
// - Slices: generated spur-gear pairs (6 … 40 teeth each, backlash and centre distance varied
//   with --set-like parameter values) walked like the engine walks them — grid steps, the halving
//   of a bracket down to 2^-46, windows around the follower — by a
//   slicer with the new proof (automatic cap, and an unlimited one) and by an oracle-only slicer:
//   every slice identical (points, isolating intervals, polynomials, features, flags, classes).
//   The walks must carry most classes and meet classes that changed since the previous slice.
// - Analyses: generated gear pairs over short ranges (one ending exactly on an event of the
//   analysis) with and without carried classes (transfer_classes_switch): report.json and
//   kinematics.csv byte-identical.
#include "algebra/real_filters.hpp"
#include "kinematics/axis.hpp"
#include "kinematics/slice.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// The example's spur gears with z1 and z2 teeth, a random backlash and centre distance inside
// their tolerances; `name` says which.
Model gear_pair(std::mt19937_64& random, long z1, long z2, std::string& name) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  // backlash 0.1 +- 0.02, centre distance m (z1 + z2) / 2 + [-0.02, 0.02] (exact rationals)
  Rational backlash(static_cast<long>(80 + random() % 41), 1000);
  backlash.canonicalize();
  Rational offset(static_cast<long>(random() % 41) - 20, 1000);
  offset.canonicalize();
  read.parameter_values["backlash"] = backlash;
  read.parameter_values["center-distance"] = Rational(Rational(z1 + z2) + offset);
  read.allow_out_of_tolerance = true;
  name = "gears " + std::to_string(z1) + "x" + std::to_string(z2) + " backlash " + backlash.get_str() +
         " centre offset " + offset.get_str();
  return read_model_file(example("spur-gears.json"), read);
}

void expect_identical(const ChartSlice& a, const ChartSlice& b, const std::string& where) {
  ASSERT_EQ(a.covered_lo, b.covered_lo) << where;
  ASSERT_EQ(a.covered_hi, b.covered_hi) << where;
  ASSERT_EQ(a.kinds, b.kinds) << where;
  ASSERT_EQ(a.points.size(), b.points.size()) << where;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const SlicePoint& x = a.points[i];
    const SlicePoint& y = b.points[i];
    EXPECT_EQ(x.features, y.features) << where << ": point " << i;
    EXPECT_EQ(x.touching, y.touching) << where << ": point " << i;
    EXPECT_EQ(x.undecided, y.undecided) << where << ": point " << i;
    EXPECT_EQ(x.value.exact, y.value.exact) << where << ": point " << i;
    EXPECT_EQ(x.value.lower, y.value.lower) << where << ": point " << i;
    EXPECT_EQ(x.value.upper, y.value.upper) << where << ": point " << i;
    EXPECT_TRUE(x.value.polynomial == y.value.polynomial) << where << ": point " << i;
  }
}

struct Counts {
  std::size_t slices = 0, transferred = 0, classified = 0, changed = 0;
};

// Engine-like walks of the pinion (the other part) with the gear as follower: grid steps of
// 2 pi / 1440 in angle (chart steps of about 1/2000), a bracket halved towards 2^-46 now and
// then, windows of about 0.06 rad around the follower's expected position, against an
// oracle-only slicer.
Counts walk(const Model& model, std::size_t proof_curves, int walks, int steps, std::uint64_t seed,
            const std::string& name) {
  std::mt19937_64 random(seed);
  Counts counts;
  // the two slicers share their strips (one generator run per strip: the same curves)
  KernelSlicerOptions oracle_only;
  oracle_only.transfer_classes = false;
  oracle_only.selections = std::make_shared<SelectionMemo>();
  KernelSlicerOptions carried;
  carried.proof_curves = proof_curves;
  carried.selections = oracle_only.selections;
  const std::size_t follower = model.pairs[0].second;   // the gear
  std::unique_ptr<PairSlicer> plain = make_kernel_slicer(model, 0, follower, oracle_only);
  std::unique_ptr<PairSlicer> fast = make_kernel_slicer(model, 0, follower, carried);
  for (int w = 0; w < walks; ++w) {
    const std::size_t o = random() % plain->other_charts().size(), f = random() % plain->follower_charts().size();
    const ChartAxis& other_axis = plain->other_charts()[o];
    const ChartAxis& axis = plain->follower_charts()[f];
    Rational u(static_cast<long>(random() % (1u << 16)), 1L << 16);
    u.canonicalize();
    u = Rational(other_axis.lo + (other_axis.hi - other_axis.lo) * u);
    Rational centre(static_cast<long>(random() % (1u << 16)), 1L << 16);
    centre.canonicalize();
    centre = Rational(axis.lo + (axis.hi - axis.lo) * centre);
    std::optional<ChartSlice> last;
    for (int k = 0; k < steps; ++k) {
      Rational step(1, 2000);
      if (random() % 5 == 0) step = Rational(1, mpz_class(1) << static_cast<unsigned>(12 + random() % 35));   // a halving
      if (random() % 2) step = -step;
      u = std::clamp(Rational(u + step), other_axis.lo, other_axis.hi);
      centre = std::clamp(Rational(centre - step * 2 / 3), axis.lo, axis.hi);   // the gear turns back at 2/3
      // the engine's first window: about 0.06 rad of a half-angle chart near its middle
      const Rational half(3, 100);
      const ChartWindow window{centre - half, centre + half};
      const ChartWindow* wp = &window;
      const std::string where = name + " charts " + std::to_string(o) + "," + std::to_string(f) + " at " + u.get_str();
      ChartSlice expected = plain->slice(o, u, f, wp);
      ChartSlice got = fast->slice(o, u, f, wp);
      expect_identical(expected, got, where);
      if (::testing::Test::HasFailure()) return counts;
      ++counts.slices;
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
  counts.transferred = used.transferred;
  counts.classified = used.classified;
  EXPECT_EQ(kernel_slice_class_counts(*plain).transferred, 0u);
  return counts;
}

TEST(KinematicGearTransfer, CarriedClassesAreTheOraclesOnGeneratedGearPairs) {
  std::mt19937_64 random(33001);
  Counts all;
  // tooth counts from 6 to 40 (small and large pairs, equal and co-prime counts)
  const std::vector<std::pair<long, long>> teeth = {{6, 40}, {18, 27}, {13, 7}};
  for (auto [z1, z2] : teeth) {
    std::string name;
    Model model = gear_pair(random, z1, z2, name);
    Counts counts = walk(model, 0, 1, 16, random(), name);
    if (HasFailure()) return;
    all.slices += counts.slices;
    all.transferred += counts.transferred;
    all.classified += counts.classified;
    all.changed += counts.changed;
  }
  EXPECT_GT(all.transferred, all.classified) << "transferred " << all.transferred << ", oracle " << all.classified;
  EXPECT_GT(all.changed, 0u) << "no interval changed its class between consecutive slices";
  std::cout << "gears: " << all.slices << " slices, " << all.transferred << " carried over, " << all.classified
            << " by the oracle, " << all.changed << " changed\n";
}

TEST(KinematicGearTransfer, UnlimitedProofsCarryTheOraclesClasses) {
  std::mt19937_64 random(33002);
  std::string name;
  Model model = gear_pair(random, 7 + static_cast<long>(random() % 34), 7 + static_cast<long>(random() % 34), name);
  Counts counts = walk(model, static_cast<std::size_t>(-1), 1, 16, random(), name);
  if (HasFailure()) return;
  EXPECT_GT(counts.transferred, 0u);
  std::cout << name << ": " << counts.slices << " slices, " << counts.transferred << " carried over, "
            << counts.classified << " by the oracle, " << counts.changed << " changed\n";
}

// Whole analyses with and without carried classes: byte-identical.
std::pair<std::string, std::string> outputs(const Model& model, const KinematicsOptions& options, bool transfer) {
  transfer_classes_switch() = transfer;
  KinematicsResult result = analyze_kinematics(model, options);
  transfer_classes_switch() = true;
  result.seconds = 0;
  return {kinematics_json_report(result), kinematics_csv(result)};
}

TEST(KinematicGearTransfer, AnalysesAreTheSameWithoutCarriedClasses) {
  std::mt19937_64 random(33003);
  int ending_on_events = 0;
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    Model model = gear_pair(random, 6 + static_cast<long>(random() % 20), 6 + static_cast<long>(random() % 20), name);
    KinematicsOptions options;
    double start = static_cast<double>(random() % 1000) / 1000;
    options.range = std::make_pair(Rational(start), Rational(start + 0.2));
    options.steps_per_cycle = 720;
    auto with = outputs(model, options, true);
    auto without = outputs(model, options, false);
    EXPECT_FALSE(with.first.empty());
    EXPECT_TRUE(with.first == without.first) << name << ": report.json differs";
    EXPECT_TRUE(with.second == without.second) << name << ": kinematics.csv differs";
    // a range ending on the first event (at the double below its certified driver angle):
    // the last grid step brackets the event itself
    const KinematicsResult located = analyze_kinematics(model, options);
    if (located.events.empty()) continue;
    ++ending_on_events;
    options.range = std::make_pair(Rational(start), Rational(located.events.front().at.coordinate.lower));
    auto ending = outputs(model, options, true);
    auto ending_without = outputs(model, options, false);
    EXPECT_TRUE(ending.first == ending_without.first) << name << ": report.json differs (range ending on an event)";
    EXPECT_TRUE(ending.second == ending_without.second) << name << ": kinematics.csv differs (range ending on an event)";
  }
  EXPECT_GT(ending_on_events, 0) << "no analysis had an event to end a range on";
}

}  // namespace
}  // namespace hipair::kinematics_detail
