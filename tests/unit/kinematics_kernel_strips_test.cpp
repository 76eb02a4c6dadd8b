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
#include "kinematics/engine.hpp"
#include "kinematics/slice.hpp"
#include "test_paths.hpp"
#include "spur_gear_pairs.hpp"
#include "chain_states.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
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

// The polynomials the engine differentiates: the same curve in both slicers for every feature
// of `slice`'s points.
void expect_same_polynomials(const ChartSlice& slice, const PairSlicer& whole, const PairSlicer& strips, std::size_t o,
                             std::size_t f, const std::string& where) {
  for (const SlicePoint& point : slice.points)
    for (std::size_t feature : point.features) {
      const IntegerPolynomial2* p = whole.polynomial(o, f, feature);
      const IntegerPolynomial2* q = strips.polynomial(o, f, feature);
      ASSERT_NE(p, nullptr) << where;
      ASSERT_NE(q, nullptr) << where;
      EXPECT_EQ(p->coefficients, q->coefficients) << where;
    }
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
            expect_same_polynomials(b, *whole, *strips, o, f, where);
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

// Lazily culled strips (KernelSlicerOptions::lazy_cull, session 34): a strip's blocked-space cull
// runs only over the follower cells the slices ask for, and is extended when a later slice asks
// for more. Engine-like walks — driver steps from grid steps to jumps of a few strips, windows
// of 1/64 to 1/4 of the follower chart moving against the driver, now and then a whole-chart
// slice, a jump to another place — by a lazily culling slicer and one culling every strip
// whole (today's), both carrying classes, compared slice for slice by the strip test's rules
// (every lazy point is a point of the whole strips' slice with the same features and flag, a
// point it lacks has blocked space on both sides and is no zero-clearance fit, the classes
// agree, the polynomials agree).
struct LazyCounts {
  std::size_t slices = 0, points = 0, lazy_cells = 0, whole_cells = 0;
};

void lazy_walks(const Model& model, std::size_t pair, std::size_t follower, int walks, int steps, std::uint64_t seed,
                const std::string& name, LazyCounts& counts) {
  std::mt19937_64 random(seed);
  std::unique_ptr<PairSlicer> lazy;
  try {
    lazy = make_kernel_slicer(model, pair, follower, KernelSlicerOptions{});
  } catch (const GeometryError&) {
    return;   // a fixed follower, or not a fixed-axis pair
  }
  if (!lazy->other_moves()) return;   // (a fixed other part: one strip, culled whole)
  KernelSlicerOptions whole_strips;
  whole_strips.lazy_cull = false;
  const std::unique_ptr<PairSlicer> whole = make_kernel_slicer(model, pair, follower, whole_strips);
  for (int w = 0; w < walks; ++w) {
    const std::size_t o = random() % whole->other_charts().size(), f = random() % whole->follower_charts().size();
    const ChartAxis& other_axis = whole->other_charts()[o];
    const ChartAxis& axis = whole->follower_charts()[f];
    Rational u = chart_value(other_axis, random, 2 + static_cast<int>(random() % 8));
    Rational centre = chart_value(axis, random, 7);
    // the follower's turn against the driver's in chart units
    static const Rational ratios[] = {Rational(2, 3), Rational(3, 2), Rational(1), Rational(-1, 2)};
    const Rational ratio = ratios[random() % 4];
    for (int k = 0; k < steps; ++k) {
      static const long steps_per_chart[] = {2000, 2000, 400, 100, 40, 16};
      Rational step = Rational(other_axis.hi - other_axis.lo) / steps_per_chart[random() % 6];
      if (random() % 2) step = -step;
      u = std::clamp(Rational(u + step), other_axis.lo, other_axis.hi);
      centre = std::clamp(Rational(centre - step * ratio), axis.lo, axis.hi);
      static const long windows_per_chart[] = {128, 64, 32, 16, 8};
      const Rational half = Rational(axis.hi - axis.lo) / windows_per_chart[random() % 5];
      std::optional<ChartWindow> window;
      if (random() % 12 != 0) window = ChartWindow{centre - half, centre + half};
      const std::string where = name + " pair " + std::to_string(pair) + " follower " + std::to_string(follower) +
                                " charts " + std::to_string(o) + "," + std::to_string(f) + " walk " + std::to_string(w) +
                                " step " + std::to_string(k) + " at " + u.get_str() +
                                (window ? " window " + window->lo.get_str() + ":" + window->hi.get_str() : " whole");
      ChartSlice a = whole->slice(o, u, f, window ? &*window : nullptr);
      ChartSlice b = lazy->slice(o, u, f, window ? &*window : nullptr);
      expect_same(a, b, *whole, *lazy, where);
      if (::testing::Test::HasFailure()) return;
      ++counts.slices;
      counts.points += a.points.size();
      expect_same_polynomials(b, *whole, *lazy, o, f, where);
    }
  }
  counts.lazy_cells += kernel_slice_class_counts(*lazy).strip_cells_culled;
  counts.whole_cells += kernel_slice_class_counts(*whole).strip_cells_culled;
}

TEST(KernelSlicerLazyCull, SameSlicesAsWholeStripsOnExamples) {
  LazyCounts counts;
  for (const char* file : {"geneva.json", "ratchet.json", "escapement.json", "scotch-yoke.json"}) {
    Model model = read_model_file(example(file));
    for (std::size_t pair = 0; pair < model.pairs.size(); ++pair)
      for (std::size_t follower : {model.pairs[pair].first, model.pairs[pair].second})
        lazy_walks(model, pair, follower, 3, 25, 34000 + pair, file, counts);
  }
  EXPECT_GT(counts.points, 0u);
  // the walks' windows leave cells unculled
  EXPECT_LT(counts.lazy_cells, counts.whole_cells);
}

// A generated spur-gear pair of 6…14 × 6…(5 + z2_span) teeth (the example's profile, random
// backlash and centre distance inside their tolerances); its name in `name`.
Model drawn_gear_pair(std::mt19937_64& random, long z2_span, std::string& name) {
  const long z1 = 6 + static_cast<long>(random() % 9), z2 = 6 + static_cast<long>(random() % z2_span);
  return test_gears::spur_gear_pair(random, z1, z2, name);
}

// Generated spur-gear pairs (the example's profile, random tooth counts, backlash and centre
// distance inside their tolerances), both gears as followers.
TEST(KernelSlicerLazyCull, SameSlicesAsWholeStripsOnGeneratedGearPairs) {
  std::mt19937_64 random(34001);
  LazyCounts counts;
  for (int g = 0; g < 2; ++g) {
    std::string name;
    Model model = drawn_gear_pair(random, 12, name);
    lazy_walks(model, 0, model.pairs[0].second, 2, 20, 34100 + static_cast<std::uint64_t>(g), name, counts);
    lazy_walks(model, 0, model.pairs[0].first, 1, 20, 34200 + static_cast<std::uint64_t>(g), name, counts);
  }
  EXPECT_GT(counts.points, 0u);
  EXPECT_LT(counts.lazy_cells, counts.whole_cells);
}

// The engine's initial state from windows (session 35): initial_state slices each part's pairs in
// the windows update_windowed asks (0.06 rad, 4 x, 16 x, ... then the whole axis) around the
// initial position, widened while an overlap found or the decision reaches a window edge, so
// that the first strips' blocked-space cull runs over the cells near the start instead of the
// whole follower axis. Against the whole axis's slices (initial_windows_switch off), on chains
// of their own: generated spur-gear pairs (both gears as drivers) and example mechanisms, the
// driver at random chart values and strip borders, the followers at random initial angles (most
// overlapping the driver: interference found, bounded by contacts a window may cut off, and
// the follower pushed out): the same state field for field, the same interference (pairs and
// descriptions), and the same states over a few steps from it (the lazily culled strips then
// extended by the steps' windows).
struct InitialCounts {
  std::size_t cases = 0, overlapping = 0, widened = 0, lazy_cells = 0, whole_cells = 0;
};

void compare_initial_states(Model& model, std::size_t driver, int cases, std::uint64_t seed, const std::string& name,
                            InitialCounts& counts) {
  std::mt19937_64 random(seed);
  Chain windows = build_chain(model, driver, {}, SliceMethod::kernels, {});
  Chain whole = build_chain(model, driver, {}, SliceMethod::kernels, {});
  const AxisLine& line = windows.parts[0].line;
  if (!line.rotation) return;
  std::vector<Rational> model_angles;
  for (const Part& part : model.parts) model_angles.push_back(part.initial.angle);
  for (int c = 0; c < cases; ++c) {
    // the followers' initial angles (read by initial_state from the model): the model's own with
    // the driver at 0 in the first case, else random
    for (std::size_t k = 1; k < windows.parts.size(); ++k) {
      Part& part = model.parts[windows.parts[k].part];
      if (part.motion.kind != Motion::Kind::rotation) continue;
      Rational angle(static_cast<long>(random() % 6283) - 3141, 1000);
      angle.canonicalize();
      part.initial.angle = c == 0 ? model_angles[windows.parts[k].part] : angle;
    }
    const std::size_t piece = c == 0 ? 0 : random() % line.pieces.size();
    const Rational value = c == 0 ? Rational(std::clamp(Rational(0), line.pieces[0].lo, line.pieces[0].hi))
                                  : chart_value(line.pieces[piece], random, 2 + static_cast<int>(random() % 8));
    const double unwrapped = line.coordinate(piece, value.get_d());
    const std::string where = name + " case " + std::to_string(c) + " driver at " + value.get_str();
    std::vector<Interference> found_windows, found_whole;
    const std::size_t widenings = initial_widenings();
    ChainState a = initial_state(windows, piece, value, unwrapped, found_windows);
    counts.widened += initial_widenings() - widenings;
    initial_windows_switch() = false;
    ChainState b = initial_state(whole, piece, value, unwrapped, found_whole);
    initial_windows_switch() = true;
    test_chain::expect_same_state(a, b, where, false);
    ASSERT_EQ(found_windows.size(), found_whole.size()) << where;
    for (std::size_t i = 0; i < found_whole.size(); ++i) {
      EXPECT_EQ(found_windows[i].pair, found_whole[i].pair) << where;
      EXPECT_EQ(found_windows[i].description, found_whole[i].description) << where;
    }
    if (::testing::Test::HasFailure()) return;
    ++counts.cases;
    counts.overlapping += !found_whole.empty();
    // a few steps on (grid steps and halvings of them)
    Rational u = value;
    double theta = unwrapped;
    for (int s = 0; s < 3 && !a.jammed; ++s) {
      const double ahead = (s == 1 ? 0.5 : 1.0) * 2 * std::acos(-1.0) / 360;
      const double to = std::min(theta + ahead, line.coordinate(piece, line.pieces[piece].hi.get_d()));
      if (!(to > theta)) break;
      Rational t(std::tan((to - line.coordinate(piece, 0.0)) / 2));
      if (t <= u || t > line.pieces[piece].hi) break;
      a = step(windows, a, piece, t, to);
      b = step(whole, b, piece, t, to);
      test_chain::expect_same_state(a, b, where + " step " + std::to_string(s), false);
      if (::testing::Test::HasFailure()) return;
      u = t;
      theta = to;
    }
  }
  for (const auto& slicer : windows.slicers) counts.lazy_cells += kernel_slice_class_counts(*slicer).strip_cells_culled;
  for (const auto& slicer : whole.slicers) counts.whole_cells += kernel_slice_class_counts(*slicer).strip_cells_culled;
}

TEST(KernelSlicerLazyCull, InitialStatesFromWindowsAreTheWholeAxissOnGeneratedGearPairs) {
  std::mt19937_64 random(35001);
  InitialCounts counts;
  for (int g = 0; g < 2; ++g) {
    std::string name;
    Model model = drawn_gear_pair(random, 11, name);
    const std::size_t driver = g == 0 ? model.pairs[0].first : model.pairs[0].second;
    compare_initial_states(model, driver, 5, random(), name, counts);
    if (HasFailure()) return;
  }
  std::cout << "gears: " << counts.cases << " initial states, " << counts.overlapping << " overlapping, " << counts.widened
            << " windows widened, " << counts.lazy_cells << " strip cells culled (whole axis: " << counts.whole_cells << ")\n";
  EXPECT_EQ(counts.cases, 10u);
  EXPECT_GT(counts.overlapping, 2u);
  EXPECT_LT(counts.overlapping, counts.cases);
  EXPECT_GT(counts.widened, 0u);
  EXPECT_LT(counts.lazy_cells, counts.whole_cells);
}

TEST(KernelSlicerLazyCull, InitialStatesFromWindowsAreTheWholeAxissOnExamples) {
  InitialCounts counts;
  std::uint64_t seed = 35100;
  for (const char* file : {"geneva.json", "ratchet.json", "escapement.json"}) {
    Model model = read_model_file(example(file));
    std::size_t driver = model.pairs.front().first;
    for (std::size_t candidate : {model.pairs.front().first, model.pairs.front().second})
      if (model.parts[candidate].motion.kind == Motion::Kind::rotation) {
        driver = candidate;
        break;
      }
    compare_initial_states(model, driver, 6, ++seed, file, counts);
    if (HasFailure()) return;
  }
  std::cout << "examples: " << counts.cases << " initial states, " << counts.overlapping << " overlapping, "
            << counts.widened << " windows widened\n";
  EXPECT_GT(counts.cases, 12u);
  EXPECT_GT(counts.overlapping, 0u);
  EXPECT_GT(counts.widened, 0u);
}

}  // namespace
}  // namespace hipair::kinematics_detail
