// The kernel slicer generates a chart pair's curves per strip of the other part's axis (on the
// strip's first slice) instead of the whole chart pair at once. A strip's blocked-space cull
// works on the strip's box, finer than the chart's, so it may drop curves whose every contact
// in the strip lies in certified blocked space — and nothing else. The test slices the example
// pairs (both parts as followers, every chart pair) at generated rational values of the other
// part — random ones, strip borders, chart ends — with and without windows, by the strip
// slicer and the whole-chart slicer, and checks that
//   - every point of the strip slice is a point of the whole-chart slice, with the same
//     features (canonical numbers: the same in both) and the same zero-clearance flag;
//   - every point the strip slice lacks has blocked space on both sides and is no
//     zero-clearance fit;
//   - the class of every interval is the class of each whole-chart interval inside it;
//   - the feature labels agree.
#include "kinematics/slice.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <random>
#include <string>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// A rational of the chart [lo, hi]: random with a 2^-20 grid, a strip border, or an end.
Rational chart_value(const ChartAxis& axis, std::mt19937_64& random, int which) {
  if (which == 0) return axis.lo;
  if (which == 1) return axis.hi;
  if (which < 6) {
    int cell = static_cast<int>(random() % 65);   // strip borders (64 strips a chart)
    return Rational(axis.lo + (axis.hi - axis.lo) * cell / 64);
  }
  Rational u(static_cast<long>(random() % (1u << 20)), 1L << 20);
  u.canonicalize();
  return Rational(axis.lo + (axis.hi - axis.lo) * u);
}

// Strip slice `b` against whole-chart slice `a` (the rules of the header comment).
void expect_same(const ChartSlice& a, const ChartSlice& b, const PairSlicer& whole, const PairSlicer& strips,
                 const std::string& where) {
  ASSERT_EQ(a.covered_lo, b.covered_lo) << where;
  ASSERT_EQ(a.covered_hi, b.covered_hi) << where;
  ASSERT_EQ(a.kinds.size(), a.points.size() + 1) << where;
  ASSERT_EQ(b.kinds.size(), b.points.size() + 1) << where;
  std::size_t j = 0;   // next point of b
  std::size_t interval_b = 0;
  for (std::size_t i = 0; i <= a.points.size(); ++i) {
    // interval i of a lies inside interval interval_b of b (empty intervals have no class)
    if (a.kinds[i] != SliceKind::empty && b.kinds[interval_b] != SliceKind::empty)
      EXPECT_EQ(a.kinds[i], b.kinds[interval_b]) << where << ": interval " << i;
    if (i == a.points.size()) break;
    const SlicePoint& p = a.points[i];
    if (j < b.points.size() && algebra::compare(b.points[j].value, p.value) == 0) {
      EXPECT_EQ(b.points[j].features, p.features) << where << ": point " << i;
      EXPECT_EQ(b.points[j].touching, p.touching) << where << ": point " << i;
      for (std::size_t f : p.features) {
        ASSERT_LT(f, whole.features().size());
        ASSERT_LT(f, strips.features().size());
        EXPECT_EQ(whole.features()[f].label, strips.features()[f].label);
        EXPECT_EQ(whole.features()[f].kind, strips.features()[f].kind);
        EXPECT_FALSE(strips.features()[f].label.empty());
      }
      ++j;
      ++interval_b;
      continue;
    }
    ASSERT_FALSE(j < b.points.size() && algebra::compare(b.points[j].value, p.value) < 0)
        << where << ": the strip slice has a point the whole-chart slice lacks";
    // dropped: a curve through certified blocked space
    EXPECT_EQ(a.kinds[i], SliceKind::blocked) << where << ": dropped point " << i;
    EXPECT_EQ(a.kinds[i + 1], SliceKind::blocked) << where << ": dropped point " << i;
    EXPECT_FALSE(p.touching) << where << ": dropped point " << i;
  }
  EXPECT_EQ(j, b.points.size()) << where;
}

struct StripCase {
  std::string file;
  int values;          // slices per chart pair and follower
  bool data = false;   // tests/data instead of examples/models
};

class KernelSlicerStrips : public ::testing::TestWithParam<StripCase> {};

TEST_P(KernelSlicerStrips, SameSlicesAsTheWholeChartPairs) {
  Model model = read_model_file(GetParam().data ? std::filesystem::path(HIPAIR_TEST_DATA) / GetParam().file
                                                : example(GetParam().file));
  std::mt19937_64 random(20261128);
  std::size_t slices = 0, compared_points = 0;
  for (std::size_t pair = 0; pair < model.pairs.size(); ++pair) {
    for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second}) {
      std::unique_ptr<PairSlicer> whole, strips;
      try {
        whole = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{false});
        strips = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{true});
      } catch (const GeometryError&) {
        continue;   // a fixed follower, or not a fixed-axis pair
      }
      std::size_t other_count = std::max<std::size_t>(1, whole->other_charts().size());
      for (std::size_t o = 0; o < other_count; ++o)
        for (std::size_t f = 0; f < whole->follower_charts().size(); ++f)
          for (int k = 0; k < GetParam().values; ++k) {
            Rational value(0);
            if (whole->other_moves()) value = chart_value(whole->other_charts()[o], random, k);
            const ChartAxis& axis = whole->follower_charts()[f];
            std::optional<ChartWindow> window;
            if (k % 3 == 2) {
              Rational a = chart_value(axis, random, 7), b = chart_value(axis, random, 7);
              window = ChartWindow{std::min(a, b), std::max(a, b)};
            }
            ChartSlice a = whole->slice(o, value, f, window ? &*window : nullptr);
            ChartSlice b = strips->slice(o, value, f, window ? &*window : nullptr);
            std::string where = GetParam().file + " pair " + std::to_string(pair) + " follower " +
                                std::to_string(follower) + " charts " + std::to_string(o) + "," +
                                std::to_string(f) + " at " + value.get_str();
            expect_same(a, b, *whole, *strips, where);
            ++slices;
            compared_points += a.points.size();
            // the polynomials the engine differentiates: the same curve in both
            for (const SlicePoint& point : b.points)
              for (std::size_t feature : point.features) {
                const IntegerPolynomial2* p = whole->polynomial(o, f, feature);
                const IntegerPolynomial2* q = strips->polynomial(o, f, feature);
                ASSERT_NE(p, nullptr);
                ASSERT_NE(q, nullptr);
                EXPECT_EQ(p->coefficients, q->coefficients) << where;
              }
          }
    }
  }
  EXPECT_GT(slices, 0u);
  EXPECT_GT(compared_points, 0u);
}

INSTANTIATE_TEST_SUITE_P(Examples, KernelSlicerStrips,
                         ::testing::Values(StripCase{"geneva.json", 60}, StripCase{"ratchet.json", 60},
                                           StripCase{"escapement.json", 30}, StripCase{"cam-follower.json", 40},
                                           StripCase{"scotch-yoke.json", 40}, StripCase{"lever-stop.json", 40},
                                           StripCase{"zero-clearance/scotch-yoke-exact-fit.json", 40, true}),
                         [](const auto& info) {
                           std::string name = info.param.file.substr(info.param.file.find('/') + 1);
                           name = name.substr(0, name.find('.'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// A value on the border of two cells, sliced first (a chart's first strip, or next to one): the
// slicer generates one strip holding both cells instead of a strip per cell (session 33). Fresh
// strip slicers at generated border values — then at values inside the two cells and beyond,
// whose strips are laid out after the merged one — against the whole-chart slices.
void border_first_slices(const Model& model, std::size_t pair, std::size_t follower, int borders, std::uint64_t seed,
                         const std::string& name, std::size_t& compared_points) {
  std::mt19937_64 random(seed);
  std::unique_ptr<PairSlicer> whole;
  try {
    whole = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{false});
  } catch (const GeometryError&) {
    return;   // a fixed follower, or not a fixed-axis pair
  }
  if (!whole->other_moves()) return;
  for (std::size_t o = 0; o < whole->other_charts().size(); ++o)
    for (std::size_t f = 0; f < whole->follower_charts().size(); ++f)
      for (int k = 0; k < borders; ++k) {
        const ChartAxis& axis = whole->other_charts()[o];
        // a border inside the chart (1..63), the first and last among them
        const int cell = k == 0 ? 1 : k == 1 ? 63 : 1 + static_cast<int>(random() % 63);
        auto at = [&](const Rational& cells) { return Rational(axis.lo + (axis.hi - axis.lo) * cells / 64); };
        auto strips = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{true});
        // the border first, then inside the cells on both sides, then a cell further on
        // each side, a window on some
        std::vector<Rational> values{at(Rational(cell)), at(Rational(2 * cell - 1, 2)), at(Rational(2 * cell + 1, 2)),
                                     at(Rational(std::max(0, cell - 3))), at(Rational(std::min(64, cell + 3))),
                                     at(Rational(cell + 1))};
        for (std::size_t v = 0; v < values.size(); ++v) {
          std::optional<ChartWindow> window;
          if (v % 3 == 2) {
            Rational a = chart_value(whole->follower_charts()[f], random, 7),
                     b = chart_value(whole->follower_charts()[f], random, 7);
            window = ChartWindow{std::min(a, b), std::max(a, b)};
          }
          ChartSlice a = whole->slice(o, values[v], f, window ? &*window : nullptr);
          ChartSlice b = strips->slice(o, values[v], f, window ? &*window : nullptr);
          expect_same(a, b, *whole, *strips,
                      name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) + " charts " +
                          std::to_string(o) + "," + std::to_string(f) + " border " + std::to_string(cell) + " at " +
                          values[v].get_str());
          compared_points += a.points.size();
        }
      }
}

TEST_P(KernelSlicerStrips, BorderValueSlicedFirstSameSlicesAsTheWholeChartPairs) {
  Model model = read_model_file(GetParam().data ? std::filesystem::path(HIPAIR_TEST_DATA) / GetParam().file
                                                : example(GetParam().file));
  std::size_t compared_points = 0;
  for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
    for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second})
      border_first_slices(model, pair, follower, std::max(3, GetParam().values / 10), 20261201 + pair, GetParam().file,
                          compared_points);
  SUCCEED() << compared_points << " points compared";
}

// The example's spur-gear profile with 8 x 12 teeth.
Model small_gear_pair() {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(8);
  read.parameter_values["teeth-2"] = Rational(12);
  read.allow_out_of_tolerance = true;
  return read_model_file(example("spur-gears.json"), read);
}

TEST(KernelSlicerStrips, SmallGearPairBorderValueSlicedFirst) {
  Model model = small_gear_pair();
  std::size_t compared_points = 0;
  border_first_slices(model, 0, model.pairs[0].second, 4, 33, "gears 8x12", compared_points);
  EXPECT_GT(compared_points, 0u);
}

// A small spur-gear pair (the example's profile with 8 x 12 teeth): every strip of the pinion's
// charts is visited by a sweep of slices, the case the analysis of gears meets.
TEST(KernelSlicerStrips, SmallGearPairSameSlicesAsTheWholeChartPairs) {
  Model model = small_gear_pair();
  std::mt19937_64 random(7);
  std::size_t follower = model.pairs[0].second;
  auto whole = make_kernel_slicer(model, 0, follower, KernelSlicerOptions{false});
  auto strips = make_kernel_slicer(model, 0, follower, KernelSlicerOptions{true});
  std::size_t compared_points = 0;
  for (std::size_t o = 0; o < whole->other_charts().size(); ++o)
    for (std::size_t f = 0; f < whole->follower_charts().size(); ++f)
      for (int k = 0; k < 12; ++k) {
        Rational value = chart_value(whole->other_charts()[o], random, k);
        ChartSlice a = whole->slice(o, value, f);
        ChartSlice b = strips->slice(o, value, f);
        expect_same(a, b, *whole, *strips, "gears 8x12 charts " + std::to_string(o) + "," + std::to_string(f) +
                                               " at " + value.get_str());
        compared_points += a.points.size();
      }
  EXPECT_GT(compared_points, 0u);
}

}  // namespace
}  // namespace hipair::kinematics_detail
