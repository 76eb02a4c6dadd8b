// The blocked-space cull's per-cell pose memo (src/curves/contact_curves.cpp BlockedSpaceCuller,
// session 36): a part's posed cores and feature boxes computed once per visited cell, in one
// stamped set per part, instead of a map of per-interval caches allocated by every walk. Side
// by side with the plain cull (cell_pose_memo_switch() off: every test poses what it reads
// afresh) on generated spur-gear pairs: the same selections of whole chart pairs and of driver
// strips (CurveGenerator::select), the same pairs returned walk by walk by the lazily extended
// selections the kernel slicer uses (incremental_select, windows of the follower axis in random
// order), and the same curves from an operating-region tile's grid cull (the builder's path).
// Session 37: the memo keeps, per thread, the poses of the last four axis intervals per depth and
// part (while they fit its budget), across cells and cullers: the grid culls of generated pairs
// with the same axes (the same teeth, another backlash and centre distance) run one after the
// other on the same tiles, and the Geneva pair's whole chart pairs, side by side with the plain
// cull.
// Session 38: a shallow cell with a long inherited list of core pairs sweeps its own posed cores
// instead (core_sweep_switch()): the same selections and walks as the inherited lists' on
// generated pairs scaled exactly by 2^0, 2^-30 and 2^30.
#include "core/model_scale.hpp"
#include "curves/contact_curves.hpp"
#include "oracle/blocked_tester.hpp"
#include "chart_sub_axis.hpp"
#include "spur_gear_pairs.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using Pairs = std::vector<cspace::CurveGenerator::FeaturePair>;

// Runs f with a fast path's switch on, then off, and restores it (default: the memo's).
template <class F>
auto both_ways(F&& f, bool& memo = cspace::cell_pose_memo_switch()) {
  memo = true;
  auto on = f();
  memo = false;
  auto off = f();
  memo = true;
  return std::make_pair(on, off);
}

using test_charts::sub_axis;

// A generated spur-gear pair (6…11 × 6…11 teeth) with its axes and charts.
struct GearPair {
  std::string name;
  Model model;
  cspace::PairAxes axes;
  cspace::ChartLayout layout;
};
GearPair random_gear_pair(std::mt19937_64& random) {
  GearPair pair;
  const long z1 = 6 + static_cast<long>(random() % 6), z2 = 6 + static_cast<long>(random() % 6);
  pair.model = test_gears::spur_gear_pair(random, z1, z2, pair.name);
  pair.axes = cspace::pair_axes(pair.model, 0, 1);
  pair.layout = cspace::chart_layout(pair.model, pair.axes);
  return pair;
}

TEST(CullCellPoseMemo, SelectionsAndWalksAreThePlainCullsOnGeneratedGearPairs) {
  std::mt19937_64 random(3601);
  std::size_t kept = 0, walked = 0;
  for (int trial = 0; trial < 2; ++trial) {
    const GearPair pair = random_gear_pair(random);
    SCOPED_TRACE(pair.name);
    const cspace::ChartLayout& layout = pair.layout;
    ASSERT_EQ(pair.axes.dimension(), 2);
    cspace::CurveGenerator generator(pair.model, pair.axes);
    const cspace::ChartAxis& x = layout.x_charts[random() % layout.x_charts.size()];
    const cspace::ChartAxis& y = layout.y_charts[random() % layout.y_charts.size()];
    // a whole chart pair, and driver strips of 1 and 4 of 64 cells (either part the driver)
    std::vector<std::pair<cspace::ChartAxis, cspace::ChartAxis>> boxes{{x, y}};
    for (long width : {1L, 4L}) {
      long first = static_cast<long>(random() % static_cast<unsigned long>(64 - width + 1));
      boxes.emplace_back(sub_axis(x, first, width, 64), y);
      boxes.emplace_back(x, sub_axis(y, first, width, 64));
    }
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const auto& [bx, by] = boxes[b];
      auto [on, off] = both_ways([&] { return generator.select(bx, by); });
      EXPECT_EQ(on, off) << "box " << b;
      kept += on.size();
      if (b == 0) continue;
      // the strip's selection extended over follower windows (the other axis), in random order
      const int axis = b % 2 == 1 ? 1 : 0;
      const cspace::ChartAxis& follower = axis == 1 ? by : bx;
      std::vector<std::pair<double, double>> windows;
      for (int w = 0; w < 5; ++w) {
        long first = static_cast<long>(random() % 32), width = 1 + static_cast<long>(random() % 3);
        cspace::ChartAxis window = sub_axis(follower, first, std::min(width, 32 - first), 32);
        windows.emplace_back(cspace::algebra::lower_double(window.lo), cspace::algebra::upper_double(window.hi));
      }
      windows.emplace_back(cspace::algebra::lower_double(follower.lo), cspace::algebra::upper_double(follower.hi));
      auto [walks_on, walks_off] = both_ways([&] {
        std::unique_ptr<cspace::CurveGenerator::Selection> selection = generator.incremental_select(bx, by);
        std::vector<Pairs> added;
        for (const auto& window : windows) added.push_back(selection->extend(axis, {window}));
        return added;
      });
      EXPECT_EQ(walks_on, walks_off) << "box " << b;
      // after the whole axis, the walks kept select()'s pairs
      Pairs all;
      for (const Pairs& pairs : walks_on) all.insert(all.end(), pairs.begin(), pairs.end());
      std::sort(all.begin(), all.end());
      EXPECT_EQ(all, on) << "box " << b;
      walked += all.size();
    }
  }
  EXPECT_GT(kept, 0u);
  EXPECT_GT(walked, 0u);
}

TEST(CullCoreSweep, SelectionsAndWalksAreTheInheritedListsCullsOnGeneratedScaledGearPairs) {
  std::mt19937_64 random(3801);
  std::size_t kept = 0, sweeps = 0, selections = 0;
  for (long shift : {0L, 30L, -30L}) {
    GearPair pair = random_gear_pair(random);
    pair.model = scaled_model(pair.model, shift);
    pair.axes = cspace::pair_axes(pair.model, 0, 1);
    pair.layout = cspace::chart_layout(pair.model, pair.axes);
    SCOPED_TRACE(pair.name + " / 2^" + std::to_string(shift));
    ASSERT_EQ(pair.axes.dimension(), 2);
    cspace::CurveGenerator generator(pair.model, pair.axes);
    const cspace::ChartAxis& x = pair.layout.x_charts[random() % pair.layout.x_charts.size()];
    const cspace::ChartAxis& y = pair.layout.y_charts[random() % pair.layout.y_charts.size()];
    // a whole chart pair and a driver strip of 2 of 64 cells
    const long first = static_cast<long>(random() % 63);
    const int axis = static_cast<int>(random() % 2);   // the follower's axis of the strip
    const cspace::ChartAxis sx = axis == 1 ? sub_axis(x, first, 2, 64) : x;
    const cspace::ChartAxis sy = axis == 1 ? y : sub_axis(y, first, 2, 64);
    const std::size_t before = cspace::core_sweeps();
    auto [on, off] = both_ways([&] { return std::make_pair(generator.select(x, y), generator.select(sx, sy)); },
                               cspace::core_sweep_switch());
    EXPECT_EQ(on.first, off.first);
    EXPECT_EQ(on.second, off.second);
    kept += on.first.size() + on.second.size();
    // the strip's selection extended over random follower windows, then the whole axis
    const cspace::ChartAxis& follower = axis == 1 ? sy : sx;
    std::vector<std::pair<double, double>> windows;
    for (int w = 0; w < 3; ++w) {
      cspace::ChartAxis window = sub_axis(follower, static_cast<long>(random() % 16), 1, 16);
      windows.emplace_back(cspace::algebra::lower_double(window.lo), cspace::algebra::upper_double(window.hi));
    }
    windows.emplace_back(cspace::algebra::lower_double(follower.lo), cspace::algebra::upper_double(follower.hi));
    auto [walks_on, walks_off] = both_ways(
        [&] {
          std::unique_ptr<cspace::CurveGenerator::Selection> selection = generator.incremental_select(sx, sy);
          std::vector<Pairs> added;
          for (const auto& window : windows) added.push_back(selection->extend(axis, {window}));
          return added;
        },
        cspace::core_sweep_switch());
    EXPECT_EQ(walks_on, walks_off);
    sweeps += cspace::core_sweeps() - before;
    ++selections;
  }
  EXPECT_GT(kept, 0u);
  // the sweep ran in every generated case (else the comparison tests nothing)
  EXPECT_GE(sweeps, selections);
}

TEST(CullCellPoseMemo, TileGridCullsAreThePlainCullsOnGeneratedGearPairs) {
  std::mt19937_64 random(3602);
  std::size_t curves = 0;
  for (int trial = 0; trial < 2; ++trial) {
    const GearPair pair = random_gear_pair(random);
    SCOPED_TRACE(pair.name);
    const cspace::ChartLayout& layout = pair.layout;
    auto tester = std::make_shared<cspace::BlockedTester>(pair.model, pair.axes);
    ASSERT_TRUE(tester->usable());
    cspace::CurveOptions options;
    options.blocked_grid = true;
    cspace::CurveGenerator generator(pair.model, pair.axes, options);
    // tiles of 1/16 of a chart pair near the line where the teeth meet (x = y = 0 in the charts
    // centred on the mesh) and elsewhere
    for (int tile = 0; tile < 3; ++tile) {
      const cspace::ChartAxis& x = layout.x_charts[random() % layout.x_charts.size()];
      const cspace::ChartAxis& y = layout.y_charts[random() % layout.y_charts.size()];
      long i = tile == 0 ? 8 : static_cast<long>(random() % 16), j = tile == 0 ? 8 : static_cast<long>(random() % 16);
      cspace::ChartAxis tx = sub_axis(x, i, 1, 16), ty = sub_axis(y, j, 1, 16);
      auto [on, off] = both_ways([&] {
        cspace::BlockedCells cells(tester, tx, ty, 2, 5);
        std::vector<std::pair<std::string, std::string>> labels;
        for (const cspace::ContactCurve& curve : generator.generate(tx, ty, nullptr, &cells))
          labels.emplace_back(curve.label, curve.polynomial.is_zero() ? "0" : "f");
        return labels;
      });
      EXPECT_EQ(on, off) << "tile " << tile;
      curves += on.size();
    }
  }
  EXPECT_GT(curves, 0u);
}

// The labels of the curves a grid cull keeps in the tile (tx, ty) of a pair.
std::vector<std::pair<std::string, std::string>> grid_culled_labels(const Model& model, const cspace::PairAxes& axes,
                                                                    const cspace::ChartAxis& tx,
                                                                    const cspace::ChartAxis& ty, int depth) {
  auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
  EXPECT_TRUE(tester->usable());
  cspace::CurveOptions options;
  options.blocked_grid = true;
  cspace::CurveGenerator generator(model, axes, options);
  cspace::BlockedCells cells(tester, tx, ty, 2, depth);
  std::vector<std::pair<std::string, std::string>> labels;
  for (const cspace::ContactCurve& curve : generator.generate(tx, ty, nullptr, &cells))
    labels.emplace_back(curve.label, curve.polynomial.is_zero() ? "0" : "f");
  return labels;
}

TEST(CullCellPoseMemo, PosesKeptAcrossCellsAndCullersAreThePlainCulls) {
  std::mt19937_64 random(3701);
  std::size_t curves = 0, tiles = 0;
  for (int trial = 0; trial < 2; ++trial) {
    // two pairs with the same teeth: the same charts, other shapes and centre distances
    const long z1 = 6 + static_cast<long>(random() % 3), z2 = 6 + static_cast<long>(random() % 3);
    GearPair pairs[2];
    for (GearPair& pair : pairs) {
      pair.model = test_gears::spur_gear_pair(random, z1, z2, pair.name);
      pair.axes = cspace::pair_axes(pair.model, 0, 1);
      pair.layout = cspace::chart_layout(pair.model, pair.axes);
    }
    SCOPED_TRACE(pairs[0].name + " then " + pairs[1].name);
    ASSERT_EQ(pairs[0].layout.x_charts.size(), pairs[1].layout.x_charts.size());
    ASSERT_EQ(pairs[0].layout.y_charts.size(), pairs[1].layout.y_charts.size());
    // tiles of 1/16 and 1/4 of a chart pair, the same for both pairs, both pairs culled on each
    // tile in turn (the second reads the memo after the first, on the same axis intervals)
    for (int tile = 0; tile < 4; ++tile) {
      const std::size_t cx = random() % pairs[0].layout.x_charts.size();
      const std::size_t cy = random() % pairs[0].layout.y_charts.size();
      ASSERT_EQ(pairs[0].layout.x_charts[cx].lo, pairs[1].layout.x_charts[cx].lo);
      ASSERT_EQ(pairs[0].layout.y_charts[cy].hi, pairs[1].layout.y_charts[cy].hi);
      const long cells = tile % 2 == 0 ? 16 : 4;
      const long i = tile == 0 ? 8 : static_cast<long>(random() % cells);
      const long j = tile == 0 ? 8 : static_cast<long>(random() % cells);
      const int depth = 4 + tile % 3;
      auto [on, off] = both_ways([&] {
        std::vector<std::vector<std::pair<std::string, std::string>>> labels;
        for (int repeat = 0; repeat < 2; ++repeat)
          for (const GearPair& pair : pairs)
            labels.push_back(grid_culled_labels(pair.model, pair.axes,
                                                sub_axis(pair.layout.x_charts[cx], i, 1, cells),
                                                sub_axis(pair.layout.y_charts[cy], j, 1, cells), depth));
        return labels;
      });
      EXPECT_EQ(on, off) << "tile " << tile;
      for (const auto& labels : on) curves += labels.size();
      ++tiles;
    }
  }
  // the Geneva pair's chart pairs, as its C-space build culls them (the case the memo is for)
  const Model geneva = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json");
  const cspace::PairAxes axes = cspace::pair_axes(geneva, 0, 1);
  const cspace::ChartLayout layout = cspace::chart_layout(geneva, axes);
  for (const cspace::ChartAxis& x : layout.x_charts)
    for (const cspace::ChartAxis& y : layout.y_charts) {
      auto [on, off] = both_ways([&] { return grid_culled_labels(geneva, axes, x, y, 6); });
      EXPECT_EQ(on, off);
      curves += on.size();
      ++tiles;
    }
  EXPECT_GT(curves, 0u);
  EXPECT_GT(tiles, 8u);
}

}  // namespace
}  // namespace hipair
