// Session 46 (gear46): two exact shortcuts of the curve generator's and the blocked-space
// culler's bookkeeping, each compared with the route it replaces.
// - sort_index_pairs (src/curves/pair_sort.hpp): the culler's core-pair sweeps sort their pairs
//   by two counting passes instead of std::sort; on generated lists (short and long, sparse and
//   dense, with repeats, in sweep-like and random orders) the order is std::sort's, element for
//   element.
// - the swept-box memo (CurveGenerator::Data::swept_memo, src/curves/swept_box_memo.hpp): a
//   rotating part's broad-phase boxes remembered per axis interval; on generated spur-gear pairs
//   the tiles of an operating region (the builder's grid cull) give the same curves and the same
//   broad-phase counts with the memo as a generator with the memo off, over tiles that share a
//   column, a row, an interval's lower end only, an interval on the other part's axis and an
//   interval of the half-turn chart — the memo must have answered.
// - ClearanceBound::lower over a box, flattened (its interval operations inlined): bit for bit
//   the formula written out here with the kernels' interval operations, on boxes around and
//   inside generated spur gears' teeth.
#include "algebra/near_quotient.hpp"
#include "curves/contact_curves.hpp"
#include "curves/pair_sort.hpp"
#include "curves/swept_box_memo.hpp"
#include "oracle/blocked_tester.hpp"
#include "chart_sub_axis.hpp"
#include "spur_gear_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace hipair {
namespace {

TEST(PairSort, CountingPassesGiveStdSortsOrderOnGeneratedLists) {
  std::mt19937_64 random(4601);
  std::size_t long_lists = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t first_bound = 1 + random() % (trial % 4 == 0 ? 4 : 700);
    const std::size_t second_bound = 1 + random() % (trial % 5 == 0 ? 3 : 900);
    const std::size_t size = trial % 3 == 0 ? random() % 80 : random() % 20000;
    std::vector<std::pair<int, int>> pairs;
    if (trial % 2 == 0) {
      // distinct pairs emitted in a sweep-like order: ascending blocks of firsts interleaved
      for (std::size_t k = 0; k < size; ++k)
        pairs.emplace_back(static_cast<int>((k * 7 + random() % 3) % first_bound),
                           static_cast<int>((k / first_bound * 13 + random() % 5) % second_bound));
    } else {
      for (std::size_t k = 0; k < size; ++k)
        pairs.emplace_back(static_cast<int>(random() % first_bound), static_cast<int>(random() % second_bound));
    }
    std::vector<std::pair<int, int>> expected = pairs;
    std::sort(expected.begin(), expected.end());
    cspace::sort_index_pairs(pairs, first_bound, second_bound);
    ASSERT_EQ(pairs, expected) << "trial " << trial << ": " << size << " pairs of bounds " << first_bound << " x "
                               << second_bound;
    if (size >= 64 && size >= (first_bound + second_bound) / 2) ++long_lists;
  }
  EXPECT_GT(long_lists, 100u);   // the counting passes ran, not only std::sort
}

// The curves (labels, polynomial zero or not) and the broad phase's counts of one tile.
using TileCurves = std::tuple<std::vector<std::pair<std::string, bool>>, std::size_t, std::size_t, std::size_t, std::size_t>;
TileCurves tile_curves(const cspace::CurveGenerator& generator, const std::shared_ptr<cspace::BlockedTester>& tester,
                       const cspace::ChartAxis& tx, const cspace::ChartAxis& ty) {
  cspace::BlockedCells cells(tester, tx, ty, 2, 5);
  cspace::CurveStatistics stats;
  std::vector<std::pair<std::string, bool>> labels;
  for (const cspace::ContactCurve& curve : generator.generate(tx, ty, &stats, &cells))
    labels.emplace_back(curve.label, curve.polynomial.is_zero());
  return {labels, stats.feature_pairs_considered, stats.feature_pairs_culled, stats.feature_pairs_in_blocked_space,
          stats.curves};
}

using test_charts::sub_axis;

TEST(SweptBoxMemo, RegionTilesAreTheUnrememberedTilesOnGeneratedGearPairs) {
  std::mt19937_64 random(4602);
  std::size_t curves = 0, tiles = 0;
  const std::size_t hits_before = cspace::swept_box_memo_hits();
  for (int trial = 0; trial < 3; ++trial) {
    const long z1 = 6 + static_cast<long>(random() % 6), z2 = 6 + static_cast<long>(random() % 6);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
    ASSERT_TRUE(tester->usable());
    cspace::CurveOptions options;
    options.blocked_grid = true;
    // one generator remembers (its memo grows over the tiles), the other never does
    const cspace::CurveGenerator remembering(model, axes, options), plain(model, axes, options);
    // every chart pair's tiles: a column (same x interval, several y), a row, a double-width tile
    // from a column's lower end, the diagonal tile (x and y the same interval: the other part's
    // key), and the same tiles again in the next chart pair (the half-turn charts' intervals
    // are the same numbers)
    for (std::size_t cx = 0; cx < layout.x_charts.size(); ++cx)
      for (std::size_t cy = 0; cy < layout.y_charts.size(); ++cy) {
        const cspace::ChartAxis& x = layout.x_charts[cx];
        const cspace::ChartAxis& y = layout.y_charts[cy];
        const long column = static_cast<long>(random() % 16), row = static_cast<long>(random() % 16);
        std::vector<std::pair<cspace::ChartAxis, cspace::ChartAxis>> boxes;
        for (long j : {row, (row + 5) % 16, (row + 11) % 16}) boxes.emplace_back(sub_axis(x, column, 1, 16), sub_axis(y, j, 1, 16));
        for (long i : {(column + 3) % 16, (column + 9) % 16}) boxes.emplace_back(sub_axis(x, i, 1, 16), sub_axis(y, row, 1, 16));
        boxes.emplace_back(sub_axis(x, column / 2 * 2, 2, 16), sub_axis(y, row, 1, 16));
        boxes.emplace_back(sub_axis(x, column, 1, 16), sub_axis(y, column, 1, 16));
        boxes.emplace_back(sub_axis(x, 7, 2, 16), sub_axis(y, 7, 2, 16));   // where the teeth meet
        for (std::size_t b = 0; b < boxes.size(); ++b) {
          const auto& [tx, ty] = boxes[b];
          cspace::swept_box_memo_switch() = true;
          const TileCurves with = tile_curves(remembering, tester, tx, ty);
          cspace::swept_box_memo_switch() = false;
          const TileCurves without = tile_curves(plain, tester, tx, ty);
          cspace::swept_box_memo_switch() = true;
          EXPECT_EQ(with, without) << "charts " << cx << ", " << cy << " tile " << b;
          curves += std::get<0>(with).size();
          ++tiles;
        }
      }
  }
  EXPECT_GT(tiles, 30u);
  EXPECT_GT(curves, 0u);
  EXPECT_GT(cspace::swept_box_memo_hits() - hits_before, tiles / 2);   // the memo answered
}

// ClearanceBound::lower(box) as its comment states it: per edge, the smaller of the distances to
// its ends and to its line (segment) or circle (arc), minimised; 0 where a bound is not positive.
double clearance_as_stated(const Part& part, const kernels::Interval& cx, const kernels::Interval& cy) {
  using kernels::Interval;
  auto enclose = [](const Rational& q) { return cspace::algebra::enclose_kernel(q); };
  auto distance = [&](const Interval& px, const Interval& py) {
    const Interval dx = cx - px, dy = cy - py;
    return kernels::sqrt(dx * dx + dy * dy);
  };
  double best = std::numeric_limits<double>::infinity();
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      const Interval sx = enclose(edge.source.x), sy = enclose(edge.source.y);
      const Interval tx = enclose(edge.target.x), ty = enclose(edge.target.y);
      const double ends = std::min(distance(sx, sy).lo, distance(tx, ty).lo);
      double bound;
      if (edge.is_arc()) {
        const Interval radius = kernels::sqrt(enclose(edge.radius_squared));
        const Interval gap = distance(enclose(edge.center.x), enclose(edge.center.y)) - radius;
        bound = std::min(ends, std::max({0.0, gap.lo, (-gap).lo}));
      } else {
        const Interval ux = tx - sx, uy = ty - sy;
        const Interval cross = (cx - sx) * uy - (cy - sy) * ux;
        const Interval line = kernels::sqrt(cross * cross) / kernels::sqrt(ux * ux + uy * uy);
        bound = std::min(ends, line.lo);
      }
      if (!(bound > 0)) return 0;
      best = std::min(best, bound);
    }
  return std::isfinite(best) ? best : 0;
}

TEST(ClearanceBoundFlattened, BoxBoundsAreTheStatedFormulaOnGeneratedGears) {
  std::mt19937_64 random(4603);
  std::size_t positive = 0, boxes = 0;
  for (int trial = 0; trial < 3; ++trial) {
    const long z1 = 6 + static_cast<long>(random() % 20), z2 = 6 + static_cast<long>(random() % 20);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    SCOPED_TRACE(name);
    for (const Part& part : model.parts) {
      const cspace::ClearanceBound bound(part);
      // boxes around points pushed from each edge's ends towards the part's pivot and beyond
      for (const Loop& loop : part.loops)
        for (const Edge& edge : loop.edges) {
          const double px = edge.source.x.get_d(), py = edge.source.y.get_d();
          const double ox = part.motion.pivot.x.get_d(), oy = part.motion.pivot.y.get_d();
          for (double f : {0.001, 0.02, 0.1, 0.5, -0.05}) {
            const double x = px + f * (ox - px), y = py + f * (oy - py);
            const double w = (random() % 4) * 1e-3 * std::ldexp(1.0, -static_cast<int>(random() % 20));
            const kernels::Interval cx(x - w, x + w), cy(y - w * 0.5, y + w);
            const double flattened = bound.lower(cx, cy), stated = clearance_as_stated(part, cx, cy);
            ASSERT_EQ(std::bit_cast<std::uint64_t>(flattened), std::bit_cast<std::uint64_t>(stated))
                << part.name << " box [" << cx.lo << ", " << cx.hi << "] x [" << cy.lo << ", " << cy.hi << "]";
            positive += flattened > 0;
            ++boxes;
          }
        }
    }
  }
  EXPECT_GT(boxes, 1000u);
  EXPECT_GT(positive, boxes / 4);
}

}  // namespace
}  // namespace hipair
