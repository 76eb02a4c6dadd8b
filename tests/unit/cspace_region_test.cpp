// Operating-region builds (CSpaceBuildOptions::operating_region): only the tiles reached from
// the initial configuration through configurations not certified blocked are built.
//  - inside the built tiles, exact point location agrees with the exact overlap oracle at
//    random rational configurations (the same contract as a whole build);
//  - the channel of the initial configuration is the same as in the whole build: a free cell
//    bounded by the same feature pairs, wrapping the same way;
//  - tiles not built are reported as outside, and the space says it is not complete.
#include "cspace/builder_impl.hpp"
#include "curves/contact_curves.hpp"
#include "oracle/blocked_tester.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/cspace_region.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <numbers>
#include <tuple>
#include <random>
#include <set>

namespace hipair {
namespace {

using test::axis_of;
using test::random_tile_point;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// The exact overlap oracle at a chart point of `space`.
cspace::Overlap oracle_at(const Model& model, const cspace::PairAxes& axes, const CSpace& space, const ChartPoint& q) {
  const CSpaceChart& chart = space.charts()[q.chart];
  return cspace::classify_overlap(model, axes, axis_of(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi),
                                  axis_of(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi),
                                  cspace::ChartPoint{q.x, q.y});
}

// The spur-gears example with z1 x z2 teeth.
Model gears(long z1, long z2) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.allow_out_of_tolerance = true;
  return read_model_file(example("spur-gears.json"), read);
}

CSpaceBuildOptions region_options() {
  CSpaceBuildOptions options;
  options.operating_region = true;
  return options;
}

// Exact point location at `count` random rational configurations of the built tiles against
// the exact oracle: free is apart, blocked is overlapping, nothing in a built tile is outside,
// and both kinds occur.
void expect_tiles_agree_with_oracle(const Model& model, const cspace::PairAxes& axes, const CSpace& space,
                                    unsigned seed, int count) {
  std::mt19937_64 random(seed);
  int free = 0, blocked = 0;
  for (int i = 0; i < count; ++i) {
    ChartPoint q = random_tile_point(space, random);
    Location location = space.locate(q);
    cspace::Overlap overlap = oracle_at(model, axes, space, q);
    EXPECT_NE(location.kind, Location::Kind::outside) << "a point of a built tile is outside";
    if (location.kind == Location::Kind::free) {
      EXPECT_EQ(overlap, cspace::Overlap::apart) << "tile " << q.chart << " at " << q.x << ", " << q.y;
      ++free;
    } else if (location.kind == Location::Kind::blocked) {
      EXPECT_EQ(overlap, cspace::Overlap::overlapping) << "tile " << q.chart << " at " << q.x << ", " << q.y;
      ++blocked;
    }
  }
  EXPECT_GT(free, 0);
  EXPECT_GT(blocked, 0);
}

PartCoordinate initial_coordinate(const Model& model, const std::string& part_name) {
  const Part& part = model.parts[*model.find_part(part_name)];
  if (part.motion.kind == Motion::Kind::translation) return {PartCoordinate::Kind::offset, part.initial.offset};
  // the examples' initial angles are 0: tan(0/2) = 0
  EXPECT_EQ(part.initial.angle, 0);
  return {PartCoordinate::Kind::half_angle_tangent, Rational(0)};
}

std::set<std::string> boundary_labels(const CSpace& space, std::size_t cell) {
  std::set<std::string> labels;
  for (std::size_t e : space.cells()[cell].boundary)
    for (std::size_t k : space.edges()[e].curves) labels.insert(space.feature_pairs()[k].label);
  return labels;
}

struct RegionCase {
  std::string file, first, second;
  unsigned tiles;
};

class CSpaceRegion : public ::testing::TestWithParam<RegionCase> {};

TEST_P(CSpaceRegion, AgreesWithOracleAndWholeBuild) {
  const RegionCase& c = GetParam();
  Model model = read_model_file(example(c.file));
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.region_tiles = c.tiles;
  CSpace region = CSpace::build(model, c.first, c.second, options);
  CSpace whole = CSpace::build(model, c.first, c.second);
  ASSERT_FALSE(region.complete());
  ASSERT_TRUE(whole.complete());
  EXPECT_GT(region.statistics().region_tiles, 0u);
  std::size_t all_tiles = whole.charts().size() * c.tiles * c.tiles;
  EXPECT_LT(region.charts().size(), all_tiles) << "the region should leave tiles out";

  // the initial configuration's channel
  PartCoordinate x = initial_coordinate(model, region.x_part());
  PartCoordinate y = initial_coordinate(model, region.y_part());
  // (on a tile seam or a spurious edge the location names the cell around it)
  Location in_region = region.locate(x, y);
  Location in_whole = whole.locate(x, y);
  ASSERT_NE(in_region.cell, no_index);
  ASSERT_NE(in_whole.cell, no_index);
  const CSpaceCell& region_cell = region.cells()[in_region.cell];
  const CSpaceCell& whole_cell = whole.cells()[in_whole.cell];
  ASSERT_EQ(region_cell.kind, CellKind::free);
  ASSERT_EQ(whole_cell.kind, CellKind::free);
  EXPECT_EQ(region_cell.wraps_x, whole_cell.wraps_x);
  EXPECT_EQ(region_cell.wraps_y, whole_cell.wraps_y);
  EXPECT_EQ(boundary_labels(region, in_region.cell), boundary_labels(whole, in_whole.cell));

  // random rational configurations in the built tiles against the exact oracle
  cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part(c.first), *model.find_part(c.second));
  std::mt19937_64 random(17);
  int free = 0, blocked = 0;
  for (int i = 0; i < 3000; ++i) {
    ChartPoint q = random_tile_point(region, random);
    std::size_t t = q.chart;
    const CSpaceChart& chart = region.charts()[t];
    Location location = region.locate(q);
    cspace::Overlap overlap = oracle_at(model, axes, region, q);
    if (location.kind == Location::Kind::free) {
      EXPECT_EQ(overlap, cspace::Overlap::apart) << c.file << " tile " << t << " at " << q.x << ", " << q.y;
      ++free;
    } else if (location.kind == Location::Kind::blocked) {
      EXPECT_EQ(overlap, cspace::Overlap::overlapping) << c.file << " tile " << t << " at " << q.x << ", " << q.y;
      ++blocked;
    } else {
      EXPECT_NE(location.kind, Location::Kind::outside) << "a point of a built tile is outside";
    }
    // the whole build says the same
    Location w = whole.locate(*whole.to_chart(
        {chart.x_kind == AxisKind::translation ? PartCoordinate::Kind::offset : PartCoordinate::Kind::half_angle_tangent,
         chart.x_half_turn ? Rational(sgn(q.x) == 0 ? Rational(0) : Rational(-1 / q.x)) : q.x},
        {chart.y_kind == AxisKind::translation ? PartCoordinate::Kind::offset : PartCoordinate::Kind::half_angle_tangent,
         chart.y_half_turn ? Rational(sgn(q.y) == 0 ? Rational(0) : Rational(-1 / q.y)) : q.y}));
    if ((location.kind == Location::Kind::free || location.kind == Location::Kind::blocked) &&
        (chart.x_kind == AxisKind::translation || !chart.x_half_turn || sgn(q.x) != 0) &&
        (chart.y_kind == AxisKind::translation || !chart.y_half_turn || sgn(q.y) != 0))
      EXPECT_EQ(w.kind, location.kind) << c.file << " tile " << t;
  }
  EXPECT_GT(free, 0);
  EXPECT_GT(blocked, 0);
}

INSTANTIATE_TEST_SUITE_P(Examples, CSpaceRegion,
                         ::testing::Values(RegionCase{"geneva.json", "driver", "wheel", 8},
                                           RegionCase{"cam-follower.json", "cam", "follower", 4},
                                           RegionCase{"ratchet.json", "wheel", "pawl", 8}),
                         [](const auto& info) {
                           std::string name = info.param.file.substr(0, info.param.file.find('.'));
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

TEST(CSpaceRegion, PointsOutsideTheRegionAreOutside) {
  Model model = read_model_file(example("geneva.json"));
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.region_tiles = 8;
  CSpace region = CSpace::build(model, "driver", "wheel", options);
  // driver at 0, wheel at 45 degrees: the pin would sit inside the wheel's locking arc, deep
  // in blocked space far from the channel (wheel dwells at multiples of 90 degrees there)
  Rational t45(41421356, 100000000);   // tan(22.5 deg), approximately
  Location location = region.locate({PartCoordinate::Kind::half_angle_tangent, Rational(0)},
                                    {PartCoordinate::Kind::half_angle_tangent, t45});
  EXPECT_TRUE(location.kind == Location::Kind::outside || location.kind == Location::Kind::blocked);
}


TEST(CSpaceRegion, FirstCrossingThroughTilesAgreesWithWholeBuild) {
  Model model = read_model_file(example("geneva.json"));
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.region_tiles = 8;
  CSpace region = CSpace::build(model, "driver", "wheel", options);
  CSpace whole = CSpace::build(model, "driver", "wheel");
  PartCoordinate zero{PartCoordinate::Kind::half_angle_tangent, Rational(0)};
  // straight paths in the chart around (0, 0) from the initial configuration, through several
  // tiles of the region build and inside one chart of the whole build
  const Rational targets[][2] = {{Rational(9, 10), Rational(0)},
                                 {Rational(-9, 10), Rational(0)},
                                 {Rational(1, 10), Rational(1, 10)},
                                 {Rational(9, 10), Rational(-1, 50)}};
  int found = 0;
  for (const auto& target : targets) {
    ChartPoint a = *region.to_chart(zero, zero);
    ChartPoint b = *whole.to_chart(zero, zero);
    Crossing in_region = region.first_crossing(a, target[0], target[1]);
    Crossing in_whole = whole.first_crossing(b, target[0], target[1]);
    ASSERT_EQ(in_region.found, in_whole.found) << target[0] << ", " << target[1];
    if (!in_whole.found) continue;
    ++found;
    // both isolate the same exact root: the intervals intersect
    EXPECT_LE(in_region.parameter_lower, in_whole.parameter_upper);
    EXPECT_LE(in_whole.parameter_lower, in_region.parameter_upper);
    auto labels = [](const CSpace& space, const Crossing& c) {
      std::set<std::string> out;
      if (c.edge != no_index)
        for (std::size_t k : space.edges()[c.edge].curves) out.insert(space.feature_pairs()[k].label);
      return out;
    };
    EXPECT_EQ(labels(region, in_region), labels(whole, in_whole));
  }
  EXPECT_GT(found, 0);
}

TEST(CSpaceRegion, GearChannelIsOneFreeCellAroundTheTorus) {
  // 6 x 6 teeth: the whole torus holds 36 tooth encounters, the channel the gears run in six
  Model model = gears(6, 6);
  CSpace region = CSpace::build(model, "pinion", "gear", region_options());
  ASSERT_FALSE(region.complete());
  PartCoordinate zero{PartCoordinate::Kind::half_angle_tangent, Rational(0)};
  Location start = region.locate(zero, zero);
  ASSERT_NE(start.cell, no_index);
  const CSpaceCell& channel = region.cells()[start.cell];
  EXPECT_EQ(channel.kind, CellKind::free);
  // equal gears: one pinion turn is one gear turn, the channel closes around both axes
  EXPECT_TRUE(channel.wraps_x);
  EXPECT_TRUE(channel.wraps_y);
  ASSERT_FALSE(channel.boundary.empty());
  for (std::size_t e : channel.boundary) {
    const CSpaceEdge& edge = region.edges()[e];
    if (edge.role != EdgeRole::contact) continue;
    for (std::size_t k : edge.curves)
      EXPECT_NE(region.feature_pairs()[k].label.find("tooth"), std::string::npos) << region.feature_pairs()[k].label;
  }
  // exact point location inside the tiles against the oracle
  cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("pinion"), *model.find_part("gear"));
  expect_tiles_agree_with_oracle(model, axes, region, 23, 400);
}

// The operating region's flood as it was built before session 30 (the reference): every fine
// cell decided by BlockedTester's sweep over every disk pair, breadth first from the seed's
// cell, across the rotation charts' glued ends; returns the flooded cells.
std::size_t reference_flood(const Model& model, unsigned tiles) {
  using cspace::ChartAxis;
  const cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("pinion"), *model.find_part("gear"));
  const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  const cspace::BlockedTester tester(model, axes);
  const std::size_t grid = tiles * std::max<std::size_t>(4, 512 / tiles);
  const std::size_t nx = layout.x_charts.size(), ny = layout.y_charts.size();
  auto lo_of = [](const ChartAxis& a) { return a.lo.get_d(); };
  auto hi_of = [](const ChartAxis& a) { return a.hi.get_d(); };
  auto cell = [&](const ChartAxis& a, std::size_t i) {
    const double lo = lo_of(a), width = (hi_of(a) - lo) / static_cast<double>(grid);
    const double l = i == 0 ? cspace::algebra::lower_double(a.lo) : lo + width * static_cast<double>(i);
    const double h = i + 1 == grid ? cspace::algebra::upper_double(a.hi) : lo + width * static_cast<double>(i + 1);
    return cspace::algebra::Interval{std::nextafter(l, -1e300), std::nextafter(h, 1e300)};
  };
  auto glued = [](const ChartAxis& a, const Rational& ta, const ChartAxis& b, const Rational& tb) {
    return a.half_turn == b.half_turn ? ta == tb : ta * tb == -1;
  };
  // the seed: both parts' initial angles, in the first chart pair holding them
  const double seed[2] = {model.parts[axes.first].initial.angle.get_d(), model.parts[axes.second].initial.angle.get_d()};
  std::vector<std::array<std::size_t, 3>> queue;
  std::vector<std::vector<char>> seen(nx * ny, std::vector<char>(grid * grid, 0));
  auto push = [&](std::size_t c, std::size_t i, std::size_t j) {
    char& mark = seen[c][i * grid + j];
    if (mark) return;
    mark = 1;
    if (tester.blocked(layout.x_charts[c / ny], layout.y_charts[c % ny], cell(layout.x_charts[c / ny], i),
                       cell(layout.y_charts[c % ny], j)))
      return;
    queue.push_back({c, i, j});
  };
  for (std::size_t ix = 0; ix < nx && queue.empty(); ++ix)
    for (std::size_t iy = 0; iy < ny && queue.empty(); ++iy) {
      double t[2];
      bool inside = true;
      for (int k = 0; k < 2; ++k) {
        const ChartAxis& a = k == 0 ? layout.x_charts[ix] : layout.y_charts[iy];
        const double local = std::remainder(seed[k] - (a.half_turn ? std::numbers::pi : 0.0), 2 * std::numbers::pi);
        t[k] = std::tan(0.5 * local);
        inside = inside && std::fabs(local) <= 0.5 * std::numbers::pi + 1e-12 && t[k] >= lo_of(a) && t[k] <= hi_of(a);
      }
      if (!inside) continue;
      auto index = [&](const ChartAxis& a, double v) {
        const double f = (v - lo_of(a)) / (hi_of(a) - lo_of(a)) * static_cast<double>(grid);
        return std::min<std::size_t>(grid - 1, static_cast<std::size_t>(std::max(0.0, f)));
      };
      push(ix * ny + iy, index(layout.x_charts[ix], t[0]), index(layout.y_charts[iy], t[1]));
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const auto [c, i, j] = queue[head];
    const std::size_t ix = c / ny, iy = c % ny;
    if (i > 0) push(c, i - 1, j);
    if (i + 1 < grid) push(c, i + 1, j);
    if (j > 0) push(c, i, j - 1);
    if (j + 1 < grid) push(c, i, j + 1);
    for (std::size_t o = 0; o < nx; ++o) {
      const ChartAxis &a = layout.x_charts[ix], &b = layout.x_charts[o];
      if (i + 1 == grid && glued(a, a.hi, b, b.lo)) push(o * ny + iy, 0, j);
      if (i == 0 && glued(b, b.hi, a, a.lo)) push(o * ny + iy, grid - 1, j);
    }
    for (std::size_t o = 0; o < ny; ++o) {
      const ChartAxis &a = layout.y_charts[iy], &b = layout.y_charts[o];
      if (j + 1 == grid && glued(a, a.hi, b, b.lo)) push(ix * ny + o, i, 0);
      if (j == 0 && glued(b, b.hi, a, a.lo)) push(ix * ny + o, i, grid - 1);
    }
  }
  return queue.size();
}

// The flood tests each fine cell on its block's candidate pairs (session 30): the same cells
// as the reference flood's sweep over every pair, on a sweep of gear pairs (tooth counts 6 to
// 17, unequal and equal, 4 to 16 tiles per axis). Only the tiles at the seed are built (a path
// of one configuration); the flooded cells are counted over the whole region.
TEST(CSpaceRegion, FloodedCellsAreTheSweepsOnGeneratedGearPairs) {
  for (auto [z1, z2, tiles] : std::vector<std::tuple<long, long, unsigned>>{
           {6, 7, 8}, {7, 13, 8}, {8, 9, 16}, {10, 10, 4}, {9, 14, 16}, {12, 17, 8}, {11, 11, 8}}) {
    Model model = gears(z1, z2);
    CSpaceBuildOptions options = region_options();
    options.region_tiles = tiles;
    const std::vector<std::array<double, 2>> path{std::array<double, 2>{
        model.parts[*model.find_part("pinion")].initial.angle.get_d(), model.parts[*model.find_part("gear")].initial.angle.get_d()}};
    CSpace along = build_operating_region_along(model, "pinion", "gear", path, options);
    const std::size_t expected = reference_flood(model, tiles);
    EXPECT_GT(expected, 100u) << z1 << " x " << z2;
    EXPECT_EQ(along.statistics().region_cells, expected) << z1 << " x " << z2 << ", " << tiles << " tiles";
  }
}

// build_operating_region_along (the picture `hipair analyze` draws of a large pair): of the
// flooded region only the tiles a path runs through are built, and each of them is built as in
// the whole region: the same tile boxes, the same contact edges (feature pairs) in each, every
// path configuration inside the built tiles, and point location agreeing with the oracle.
TEST(CSpaceRegion, AlongAPathBuildsTheRegionsTilesItRunsThrough) {
  // 6 x 12 teeth: one pinion turn is half a gear turn, the channel closes after two pinion
  // turns; the path is the first half turn of the pinion
  Model model = gears(6, 12);
  CSpace region = CSpace::build(model, "pinion", "gear", region_options());
  // the gears' centre line: gear angle = -pinion angle / 2 (the initial phases are on it)
  std::vector<std::array<double, 2>> path;
  for (int k = 0; k <= 180; ++k) {
    double t = std::numbers::pi * k / 180;
    path.push_back({t, -t / 2});
  }
  CSpace along = build_operating_region_along(model, "pinion", "gear", path);
  ASSERT_FALSE(along.complete());
  ASSERT_FALSE(region.complete());
  EXPECT_EQ(along.statistics().region_tiles, along.charts().size());
  EXPECT_LT(along.statistics().region_tiles, region.statistics().region_tiles);
  EXPECT_GT(along.statistics().region_tiles, 0u);
  // tile boxes of the along-build, and the contact edges' feature pairs in each
  using Box = std::tuple<AxisKind, bool, Rational, Rational, AxisKind, bool, Rational, Rational>;
  auto box_of = [](const CSpaceChart& c) {
    return Box{c.x_kind, c.x_half_turn, c.x_lo, c.x_hi, c.y_kind, c.y_half_turn, c.y_lo, c.y_hi};
  };
  auto contact_edges = [](const CSpace& space) {
    std::map<Box, std::multiset<std::string>> edges;
    for (const CSpaceEdge& edge : space.edges()) {
      if (edge.role != EdgeRole::contact && edge.role != EdgeRole::touching) continue;
      std::string labels;
      for (std::size_t k : edge.curves) labels += space.feature_pairs()[k].label + ";";
      const CSpaceChart& c = space.charts()[edge.chart];
      edges[Box{c.x_kind, c.x_half_turn, c.x_lo, c.x_hi, c.y_kind, c.y_half_turn, c.y_lo, c.y_hi}].insert(labels);
    }
    return edges;
  };
  std::set<Box> region_boxes;
  for (const CSpaceChart& chart : region.charts()) region_boxes.insert(box_of(chart));
  for (const CSpaceChart& chart : along.charts()) EXPECT_TRUE(region_boxes.count(box_of(chart))) << "a tile outside the region";
  auto in_along = contact_edges(along), in_region = contact_edges(region);
  std::size_t compared = 0;
  for (const CSpaceChart& chart : along.charts()) {
    Box box = box_of(chart);
    EXPECT_EQ(in_along[box], in_region[box]) << "tile " << chart.x_lo << ".." << chart.x_hi << " x " << chart.y_lo
                                             << ".." << chart.y_hi;
    compared += in_along[box].size();
  }
  EXPECT_GT(compared, 20u);
  // every configuration of the path lies in a built tile
  for (const auto& point : path) {
    // (a rational near the path's angle: the tile margin covers the difference)
    auto exact = [](double angle) {
      if (std::fabs(std::remainder(angle, 2 * std::numbers::pi)) > 3.1415)
        return PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)};
      return PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(std::tan(angle / 2))};
    };
    Location location = along.locate(exact(point[0]), exact(point[1]));
    EXPECT_NE(location.kind, Location::Kind::outside) << point[0] << ", " << point[1];
  }
  // exact point location inside the built tiles against the oracle
  cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("pinion"), *model.find_part("gear"));
  expect_tiles_agree_with_oracle(model, axes, along, 29, 300);
}


// The flood's lists given to the tiles' grids (cspace::region_tile_lists(): a tile's or its
// block's disk pairs, BlockedCells::enclose) build the space the grids' own sweeps build: on
// gear pairs with 8 and 16 tiles per axis (a tile of 64 or 32 fine cells: the tile's list, made
// before its blocks'), 64 (a tile is a block) and 128 (a block holds 2 x 2 tiles), the tiles a
// short path of the centre line runs through, built with the lists and without: the same
// flooded cells, tiles, kept curves, windows and surviving cells, and point location in the
// tiles agreeing with the exact oracle.
TEST(CSpaceRegion, TileGridsOnTheFloodsListsBuildTheSweepsSpace) {
  std::size_t windows = 0;
  for (auto [z1, z2, tiles] : std::vector<std::tuple<long, long, unsigned>>{{6, 7, 8}, {8, 9, 16}, {7, 10, 64}, {5, 6, 128}}) {
    SCOPED_TRACE(std::to_string(z1) + " x " + std::to_string(z2) + ", " + std::to_string(tiles) + " tiles");
    Model model = gears(z1, z2);
    CSpaceBuildOptions options = region_options();
    options.region_tiles = tiles;
    const double start = model.parts[*model.find_part("pinion")].initial.angle.get_d();
    const double ratio = static_cast<double>(z1) / static_cast<double>(z2);
    std::vector<std::array<double, 2>> path;
    for (int k = 0; k <= 6; ++k) path.push_back({start + 0.05 * k, -ratio * (start + 0.05 * k)});
    std::optional<CSpace> swept;
    cspace::region_tile_lists().store(false);
    try {
      swept.emplace(build_operating_region_along(model, "pinion", "gear", path, options));
    } catch (...) {
      cspace::region_tile_lists().store(true);
      throw;
    }
    cspace::region_tile_lists().store(true);
    const CSpace listed = build_operating_region_along(model, "pinion", "gear", path, options);
    EXPECT_EQ(listed.statistics().region_cells, swept->statistics().region_cells);
    const auto& a = cspace::impl_of(listed);
    const auto& b = cspace::impl_of(*swept);
    ASSERT_EQ(a.charts.size(), b.charts.size());
    EXPECT_GT(a.charts.size(), 1u);
    for (std::size_t c = 0; c < a.charts.size(); ++c) {
      EXPECT_EQ(a.charts[c].box.x_lo, b.charts[c].box.x_lo) << "tile " << c;
      EXPECT_EQ(a.charts[c].box.y_lo, b.charts[c].box.y_lo) << "tile " << c;
      EXPECT_EQ(a.charts[c].curve_global, b.charts[c].curve_global) << "tile " << c;
      EXPECT_EQ(a.charts[c].windows, b.charts[c].windows) << "tile " << c;
      EXPECT_EQ(a.charts[c].cells, b.charts[c].cells) << "tile " << c;
      for (const auto& w : a.charts[c].windows) windows += w.size();
    }
    EXPECT_EQ(listed.vertices().size(), swept->vertices().size());
    EXPECT_EQ(listed.edges().size(), swept->edges().size());
    cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("pinion"), *model.find_part("gear"));
    expect_tiles_agree_with_oracle(model, axes, listed, static_cast<unsigned>(z1 * 100 + z2), 300);
  }
  EXPECT_GT(windows, 100u);
}

}  // namespace
}  // namespace hipair
