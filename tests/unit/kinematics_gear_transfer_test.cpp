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
//   The walks must carry many classes and meet classes that changed since the previous slice.
// - Analyses: generated gear pairs over short ranges (one ending exactly on an event of the
//   analysis) with and without carried classes (transfer_classes_switch): report.json and
//   kinematics.csv byte-identical.
#include "algebra/real_filters.hpp"
#include "kinematics/axis.hpp"
#include "kinematics/slice.hpp"
#include "kinematics/slice_cells.hpp"
#include "test_paths.hpp"
#include "spur_gear_pairs.hpp"

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
  return test_gears::spur_gear_pair(random, z1, z2, name);
}

// Two slice points are the same: the same number with the same isolating interval and
// polynomial, the same features and flags.
bool same_point(const SlicePoint& x, const SlicePoint& y) {
  return x.features == y.features && x.touching == y.touching && x.undecided == y.undecided &&
         x.value.exact == y.value.exact && x.value.lower == y.value.lower && x.value.upper == y.value.upper &&
         x.value.polynomial == y.value.polynomial;
}

void expect_identical(const ChartSlice& expected, const ChartSlice& got, const std::string& where) {
  ASSERT_TRUE(expected.covered_lo == got.covered_lo && expected.covered_hi == got.covered_hi) << where << ": covered range";
  ASSERT_TRUE(expected.kinds == got.kinds) << where << ": classes";
  ASSERT_EQ(expected.points.size(), got.points.size()) << where;
  for (std::size_t i = 0; i < got.points.size(); ++i)
    EXPECT_TRUE(same_point(expected.points[i], got.points[i])) << where << ": point " << i;
}

// The intervals of `now` whose class differs from the class `before` (the previous slice) had
// at the same follower value (a sample strictly inside the interval, inside `before`'s range).
std::size_t changed_classes(const ChartSlice& before, const ChartSlice& now) {
  std::size_t changed = 0;
  for (std::size_t i = 0; i < now.kinds.size(); ++i) {
    if (now.kinds[i] == SliceKind::empty) continue;
    const Real low = i > 0 ? now.points[i - 1].value : Real::from_rational(now.covered_lo);
    const Real high = i < now.points.size() ? now.points[i].value : Real::from_rational(now.covered_hi);
    const Rational sample = algebra::rational_between(low, high);
    if (sample <= before.covered_lo || sample >= before.covered_hi) continue;
    // the interval of `before` holding the sample (none when the sample is one of its points)
    if (const std::optional<std::size_t> at = slice_cells::first_point_not_below(before.points, sample))
      changed += before.kinds[*at] != now.kinds[i] ? 1 : 0;
  }
  return changed;
}

struct Counts {
  std::size_t slices = 0, transferred = 0, classified = 0, changed = 0;
};

// Engine-like walks of the pinion (the other part) with the gear as follower: grid steps of
// 2 pi / 1440 in angle (chart steps of about 1/2000), longer jumps, a bracket halved towards
// 2^-46 now and then, windows of about 0.06 rad around the follower's expected position, against an
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
      // a grid step, a halving's step, or a longer jump (up to about three cull cells: classes
      // change under it, the cases a proof that misses a curve gets wrong)
      static const long denominators[] = {2000, 2000, 2000, 400, 100, 40};
      Rational step(1, denominators[random() % 6]);
      if (random() % 5 == 0) step = Rational(1, mpz_class(1) << static_cast<unsigned>(12 + random() % 35));   // a halving
      if (random() % 2) step = -step;
      u = std::clamp(Rational(u + step), other_axis.lo, other_axis.hi);
      centre = std::clamp(Rational(centre - step * 2 / 3), axis.lo, axis.hi);   // the gear turns back at 2/3
      // the engine's first window (about 0.06 rad of a half-angle chart near its middle), or one
      // four times wider (the engine's next): a gear's free ranges are a fraction of a degree
      // wide, one per tooth pitch, and the wider window holds several
      const Rational half = random() % 2 ? Rational(3, 100) : Rational(3, 25);
      const ChartWindow window{centre - half, centre + half};
      const ChartWindow* wp = &window;
      const std::string where = name + " charts " + std::to_string(o) + "," + std::to_string(f) + " at " + u.get_str();
      ChartSlice expected = plain->slice(o, u, f, wp);
      ChartSlice got = fast->slice(o, u, f, wp);
      expect_identical(expected, got, where);
      if (::testing::Test::HasFailure()) return counts;
      ++counts.slices;
      if (last) counts.changed += changed_classes(*last, expected);
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
  // tooth counts from 6 to 40: a small pinion on a large gear, the example pair, a pinion larger
  // than its gear
  const std::vector<std::pair<long, long>> teeth = {{6, 40}, {18, 27}, {13, 7}};
  for (auto [z1, z2] : teeth) {
    std::string name;
    Model model = gear_pair(random, z1, z2, name);
    Counts counts = walk(model, 0, 1, 24, random(), name);
    if (HasFailure()) return;
    all.slices += counts.slices;
    all.transferred += counts.transferred;
    all.classified += counts.classified;
    all.changed += counts.changed;
  }
  // a cap of 32 carried no class of the 18x27 analysis; the first slice of a walk and a wider
  // window than the previous one's leave classes to the oracle
  EXPECT_GT(all.transferred, all.classified / 4) << "transferred " << all.transferred << ", oracle " << all.classified;
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
    const auto event = std::find_if(located.events.begin(), located.events.end(), [&](const KinematicEvent& e) {
      return e.at.coordinate.lower > start + 1e-6;   // not an event at the range's start
    });
    if (event == located.events.end()) continue;
    ++ending_on_events;
    options.range = std::make_pair(Rational(start), Rational(event->at.coordinate.lower));
    auto ending = outputs(model, options, true);
    auto ending_without = outputs(model, options, false);
    EXPECT_TRUE(ending.first == ending_without.first) << name << ": report.json differs (range ending on an event)";
    EXPECT_TRUE(ending.second == ending_without.second) << name << ": kinematics.csv differs (range ending on an event)";
  }
  EXPECT_GT(ending_on_events, 0) << "no analysis had an event to end a range on";
}

}  // namespace
}  // namespace hipair::kinematics_detail
