// BlockedCells' per-depth tables made sparsely (session 72, tile72): a depth's cells are cut
// into blocks, and a block is made only when a cell in it is first asked. The grids are asked
// cells the way the culls ask them (a curve's walk of neighbouring leaves and their ancestors,
// with jumps), in random order at depths past the tables' (the map); every answer is compared
// with a reference of the same meaning on BlockedTester's plain sweep (a cell asked before gives
// its first answer, a cell inside an asked blocked cell is blocked, any other is the tester's
// answer), and the tables' bytes with the blocks the asked cells lie in, counted independently.
// Session 73 (tile73): the same cells asked of a grid with whole tables (the depths of at most
// 2^16 cells one flat table each, chosen for a whole space's few grids; deeper tabled depths
// sparse) in the same order: the same answers, the same tester calls, its tables
// whole_table_bytes() and the sparse blocks of its deeper tabled depths.
#include "curves/contact_curves.hpp"
#include "oracle/blocked_tester.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>

namespace hipair {
namespace {

Model gear_pair(int z1, int z2) {
  ReadOptions read;
  read.parameter_values["module"] = Rational(1);
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.parameter_values["backlash"] = Rational(1, 10);
  read.allow_out_of_tolerance = true;
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
}

struct Seen {
  int blocked = 0, free = 0, grids = 0;
  std::size_t largest_bytes = 0;
};

// One grid of `dimension` over x (and y) with finest depth `grid_depth`; `walks` walks of
// neighbouring leaves at `leaf_depth`, each leaf asked at three random depths.
void expect_sparse_grid(const std::shared_ptr<const cspace::BlockedTester>& tester, const cspace::ChartAxis& x,
                        const cspace::ChartAxis& y, int dimension, int grid_depth, int leaf_depth, int walks,
                        std::mt19937_64& random, Seen& seen) {
  cspace::BlockedCells grid(tester, x, y, dimension, grid_depth);
  ASSERT_EQ(grid.table_bytes(), 0u);
  ASSERT_FALSE(grid.whole_tables());
  // the same grid with whole tables, asked the same cells in the same order
  cspace::BlockedCells whole(tester, x, y, dimension, grid_depth, nullptr, true);
  ASSERT_TRUE(whole.whole_tables());
  ASSERT_EQ(whole.table_bytes(), cspace::BlockedCells::whole_table_bytes(dimension));
  std::map<std::tuple<int, long, long>, bool> reference;
  std::size_t reference_tests = 0;   // cells the reference had to ask the tester (no blocked ancestor asked)
  auto expected = [&](int depth, long i, long j) {
    auto it = reference.find({depth, i, j});
    if (it != reference.end()) return it->second;
    bool result = false;
    for (int up = 1; up <= depth && !result; ++up) {
      auto parent = reference.find({depth - up, i >> up, dimension == 2 ? j >> up : 0});
      result = parent != reference.end() && parent->second;
    }
    if (!result) {
      ++reference_tests;
      result = tester->blocked(x, y, grid.cell_x(depth, i), grid.cell_y(depth, j));
    }
    reference.emplace(std::make_tuple(depth, i, j), result);
    return result;
  };
  // the blocks the asked cells of the tabled depths lie in, and the depths asked, counted here
  // from the layout's definition: a depth d (d * dimension <= 18) of at most 2^w cells is one
  // block, a deeper one cut into squares of side 2^b (1-D: runs of 2^(2b))
  constexpr int b = cspace::BlockedCells::table_block_log2, w = cspace::BlockedCells::whole_table_log2;
  auto side_log2 = [&](int depth) { return depth * dimension <= w ? depth : dimension == 2 ? b : 2 * b; };
  std::set<std::tuple<int, long, long>> blocks;
  std::set<int> depths;
  const long leaves = 1L << leaf_depth;
  long li = static_cast<long>(random() % static_cast<std::uint64_t>(leaves));
  long lj = dimension == 2 ? static_cast<long>(random() % static_cast<std::uint64_t>(leaves)) : 0;
  for (int w = 0; w < walks; ++w) {
    // a step to a neighbour (a curve crossing cells), now and then a jump
    if (random() % 16 == 0) {
      li = static_cast<long>(random() % static_cast<std::uint64_t>(leaves));
      if (dimension == 2) lj = static_cast<long>(random() % static_cast<std::uint64_t>(leaves));
    } else {
      li = std::clamp(li + static_cast<long>(random() % 3) - 1, 0L, leaves - 1);
      if (dimension == 2) lj = std::clamp(lj + static_cast<long>(random() % 3) - 1, 0L, leaves - 1);
    }
    for (int asks = 0; asks < 3; ++asks) {
      const int depth = static_cast<int>(random() % static_cast<std::uint64_t>(leaf_depth + 1));
      const long i = li >> (leaf_depth - depth), j = dimension == 2 ? lj >> (leaf_depth - depth) : 0;
      const bool want = expected(depth, i, j);
      ASSERT_EQ(grid.blocked(depth, i, j), want) << "cell (" << depth << ", " << i << ", " << j << ")";
      ASSERT_EQ(whole.blocked(depth, i, j), want) << "whole tables: cell (" << depth << ", " << i << ", " << j << ")";
      ASSERT_EQ(whole.known_blocked(depth, i, j), want) << "whole tables: cell (" << depth << ", " << i << ", " << j << ")";
      ++(want ? seen.blocked : seen.free);
      if (depth * dimension <= 18) {
        depths.insert(depth);
        const int s = side_log2(depth);
        blocks.insert({depth, i >> s, j >> s});
      }
    }
  }
  // the grid tested exactly the cells without an asked blocked ancestor (it read every ancestor)
  EXPECT_EQ(grid.tests(), reference_tests);
  EXPECT_EQ(whole.tests(), reference_tests);
  std::size_t bytes = 0;
  for (int depth : depths)   // a directory of blocks for each depth cut into blocks
    if (depth * dimension > w) bytes += (std::size_t{1} << ((depth - side_log2(depth)) * dimension)) * sizeof(std::int32_t*);
  for (const auto& [depth, bi, bj] : blocks) bytes += (std::size_t{1} << (side_log2(depth) * dimension)) * sizeof(std::int32_t);
  EXPECT_EQ(grid.table_bytes(), bytes) << blocks.size() << " blocks over " << depths.size() << " depths";
  // (the whole tables, then the directories and blocks of the deeper tabled depths asked)
  std::size_t whole_bytes = cspace::BlockedCells::whole_table_bytes(dimension);
  for (int depth : depths)
    if (depth * dimension > cspace::BlockedCells::whole_cells_log2 && depth * dimension > w)
      whole_bytes += (std::size_t{1} << ((depth - side_log2(depth)) * dimension)) * sizeof(std::int32_t*);
  for (const auto& [depth, bi, bj] : blocks)
    if (depth * dimension > cspace::BlockedCells::whole_cells_log2)
      whole_bytes += (std::size_t{1} << (side_log2(depth) * dimension)) * sizeof(std::int32_t);
  EXPECT_EQ(whole.table_bytes(), whole_bytes);
  ++seen.grids;
  seen.largest_bytes = std::max(seen.largest_bytes, grid.table_bytes());
}

TEST(BlockedCellsSparse, TablesHoldOnlyTheAskedBlocksAndAnswerAsTheSweep) {
  std::mt19937_64 random(test::test_seed(7201));
  Seen seen;
  // 2-D: spur gears of several tooth counts (the operating-region grids of depth 9) and Geneva
  for (const auto& [z1, z2] : std::vector<std::pair<int, int>>{{12, 13}, {24, 31}, {40, 40}}) {
    SCOPED_TRACE("gears " + std::to_string(z1) + " x " + std::to_string(z2));
    const Model model = gear_pair(z1, z2);
    const cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("pinion"), *model.find_part("gear"));
    ASSERT_EQ(axes.dimension(), 2);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    auto tester = std::make_shared<const cspace::BlockedTester>(model, axes);
    ASSERT_TRUE(tester->usable());
    for (int g = 0; g < 2; ++g)
      expect_sparse_grid(tester, layout.x_charts[random() % layout.x_charts.size()],
                         layout.y_charts[random() % layout.y_charts.size()], 2, 9, 11, 900, random, seen);
  }
  const std::filesystem::path geneva = std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json";
  if (std::filesystem::exists(geneva)) {
    SCOPED_TRACE("geneva");
    const Model model = read_model_file(geneva);
    const cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("driver"), *model.find_part("wheel"));
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    auto tester = std::make_shared<const cspace::BlockedTester>(model, axes);
    ASSERT_TRUE(tester->usable());
    for (std::size_t c = 0; c < layout.x_charts.size() && c < 2; ++c)
      expect_sparse_grid(tester, layout.x_charts[c], layout.y_charts[c % layout.y_charts.size()], 2, 9, 11, 900, random,
                         seen);
  }
  // 1-D: a lever and its stop, depths to 20 (tables to 18, then the map)
  const std::filesystem::path lever = std::filesystem::path(HIPAIR_EXAMPLES) / "lever-stop.json";
  if (std::filesystem::exists(lever)) {
    SCOPED_TRACE("lever-stop");
    const Model model = read_model_file(lever);
    const cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("lever"), *model.find_part("stop"));
    ASSERT_EQ(axes.dimension(), 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    auto tester = std::make_shared<const cspace::BlockedTester>(model, axes);
    ASSERT_TRUE(tester->usable());
    const cspace::ChartAxis y{cspace::ChartAxis::Kind::translation, false, Rational(0), Rational(0)};
    for (const cspace::ChartAxis& x : layout.x_charts) expect_sparse_grid(tester, x, y, 1, 10, 20, 900, random, seen);
  }
  // both answers occur often; a grid's tables stay far below the dense table's 1 MB of depth 9
  EXPECT_GE(seen.grids, 8);
  EXPECT_GT(seen.blocked, 1000);
  EXPECT_GT(seen.free, 1000);
  EXPECT_LT(seen.largest_bytes, std::size_t{1} << 19);
}

// The builder's choice (by size): whole tables for a whole space's few grids, sparse blocks for an
// operating region's many tiles; the bytes are the flat tables of depths 0 ... 8 (2-D), 0 ... 16 (1-D).
TEST(BlockedCellsSparse, WholeTablesChosenForFewGridsOnly) {
  EXPECT_EQ(cspace::BlockedCells::whole_table_bytes(2), ((std::size_t{1} << 18) - 1) / 3 * 4);
  EXPECT_EQ(cspace::BlockedCells::whole_table_bytes(1), ((std::size_t{1} << 17) - 1) * 4);
  EXPECT_TRUE(cspace::BlockedCells::whole_tables_fit(4, 2));    // Geneva's four charts
  EXPECT_TRUE(cspace::BlockedCells::whole_tables_fit(2, 1));
  EXPECT_FALSE(cspace::BlockedCells::whole_tables_fit(192, 2)); // the fewest tiles of a region
  EXPECT_FALSE(cspace::BlockedCells::whole_tables_fit(768, 2));
  EXPECT_FALSE(cspace::BlockedCells::whole_tables_fit(1, 0));
}

}  // namespace
}  // namespace hipair
