// Model-level entry points of the C-space builder: wires the contact kernels
// (generate_contact_curves, classify_overlap) into the model-free build, and builds all pairs
// of a model in parallel.
#include <hipair/cspace.hpp>
#include <hipair/cspace_region.hpp>
#include <hipair/error.hpp>

#include "cspace/builder_impl.hpp"
#include "cspace/translated_boxes.hpp"
#include "oracle/blocked_tester.hpp"
#include "curves/contact_curves.hpp"
#include "curves/algebraic_overlap.hpp"
#include "core/model_equal.hpp"
#include "core/model_scale.hpp"
#include "kernels/interval.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <memory>
#include <optional>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <tuple>
#include <unordered_map>

namespace hipair {
namespace {

using Clock = std::chrono::steady_clock;

std::size_t part_index(const Model& model, std::string_view name) {
  auto index = model.find_part(name);
  if (!index) throw ModelError("/parts", "no part called '" + std::string(name) + "'");
  return *index;
}

// ---------------------------------------------------------------- operating region
//
// The connected set of quadtree cells, not certified blocked, that contains the seed: a flood
// over a fine grid of every chart, crossing seams where charts meet. A cell outside it is
// either certified blocked or separated from the seed by certified-blocked cells, so the free
// channel of the seed lies inside the flooded cells. Tiles (coarse boxes of a chart) holding
// a flooded cell are built exactly; the others are not built.

using RegionPath = std::vector<std::array<double, 2>>;

// The disk pairs that can certify a box inside [x] x [y] (BlockedTester::blocked's `narrowed`
// list of that box), which encloses a tile: the tile's grid tests its cells on them
// (BlockedCells::enclose) instead of sweeping every disk.
struct TileList {
  cspace::algebra::Interval x, y;
  std::shared_ptr<const std::vector<cspace::BlockedTester::DiskPair>> pairs;
};

struct RegionTiles {
  std::size_t tiles = 0;                 // per chart axis
  std::vector<std::vector<char>> kept;   // per chart (x index * y charts + y index): tiles x * tiles + y
  std::vector<std::vector<TileList>> lists;   // the same layout; no pairs: none made
  std::size_t cells = 0;                 // flooded cells
};

// Chart coordinate of a part coordinate (rad or mm) for a chart axis, or nullopt.
std::optional<double> chart_coordinate(const cspace::ChartAxis& axis, double value) {
  if (axis.kind == cspace::ChartAxis::Kind::translation) return value;
  double local = std::remainder(value - (axis.half_turn ? std::numbers::pi : 0.0), 2 * std::numbers::pi);
  if (std::fabs(local) > 0.5 * std::numbers::pi + 1e-12) return std::nullopt;
  return std::tan(0.5 * local);
}

RegionTiles flood_region(const Model& model, const cspace::PairAxes& axes, const cspace::ChartLayout& layout,
                         const cspace::BlockedTester& tester, const CSpaceBuildOptions& options,
                         const RegionPath* path) {
  using cspace::ChartAxis;
  RegionTiles region;
  unsigned tiles = options.region_tiles;
  if (tiles == 0) {
    std::size_t edges = 0;
    for (std::size_t part : {axes.first, axes.second})
      for (const Loop& loop : model.parts[part].loops) edges += loop.edges.size();
    tiles = 4;
    while (tiles < 128 && tiles * 8 < edges) tiles *= 2;
  }
  tiles = std::clamp(tiles, 2u, 128u);
  region.tiles = tiles;
  const std::size_t sub = std::max<std::size_t>(4, 512 / tiles);   // fine cells per tile side
  const std::size_t grid = tiles * sub;
  const std::size_t nx = layout.x_charts.size(), ny = layout.y_charts.size();
  auto chart_of = [&](std::size_t ix, std::size_t iy) { return ix * ny + iy; };
  region.kept.assign(nx * ny, std::vector<char>(static_cast<std::size_t>(tiles) * tiles, 0));

  // seed
  std::array<double, 2> seed{};
  if (options.region_seed) {
    seed = *options.region_seed;
  } else {
    const Part& a = model.parts[axes.first];
    const Part& b = model.parts[axes.second];
    seed[0] = (a.motion.kind == Motion::Kind::rotation ? a.initial.angle : a.initial.offset).get_d();
    seed[1] = (b.motion.kind == Motion::Kind::rotation ? b.initial.angle : b.initial.offset).get_d();
  }
  auto lo_of = [](const ChartAxis& axis) { return axis.lo.get_d(); };
  auto hi_of = [](const ChartAxis& axis) { return axis.hi.get_d(); };
  auto index_in = [&](const ChartAxis& axis, double t) {
    double f = (t - lo_of(axis)) / (hi_of(axis) - lo_of(axis)) * static_cast<double>(grid);
    return std::min<std::size_t>(grid - 1, static_cast<std::size_t>(std::max(0.0, f)));
  };
  std::optional<std::array<std::size_t, 3>> start;
  for (std::size_t ix = 0; ix < nx && !start; ++ix)
    for (std::size_t iy = 0; iy < ny && !start; ++iy) {
      auto tx = chart_coordinate(layout.x_charts[ix], seed[0]);
      auto ty = chart_coordinate(layout.y_charts[iy], seed[1]);
      if (!tx || !ty) continue;
      if (*tx < lo_of(layout.x_charts[ix]) || *tx > hi_of(layout.x_charts[ix])) continue;
      if (*ty < lo_of(layout.y_charts[iy]) || *ty > hi_of(layout.y_charts[iy])) continue;
      start = std::array<std::size_t, 3>{chart_of(ix, iy), index_in(layout.x_charts[ix], *tx),
                                         index_in(layout.y_charts[iy], *ty)};
    }
  if (!start)
    throw GeometryError("operating region of '" + model.parts[axes.first].name + "' and '" +
                        model.parts[axes.second].name + "': the seed configuration is outside the motion limits");

  auto cell_interval = [&](const ChartAxis& axis, std::size_t i) {
    double lo = lo_of(axis), width = (hi_of(axis) - lo) / static_cast<double>(grid);
    // one ulp-scale margin outward: the blocked test must see a superset of the cell
    double a = i == 0 ? cspace::algebra::lower_double(axis.lo) : lo + width * static_cast<double>(i);
    double b = i + 1 == grid ? cspace::algebra::upper_double(axis.hi) : lo + width * static_cast<double>(i + 1);
    return cspace::algebra::Interval{std::nextafter(a, -1e300), std::nextafter(b, 1e300)};
  };
  // neighbours across chart boundaries: glued chart along x (same y chart) and along y
  auto glued = [](const ChartAxis& a, const Rational& ta, const ChartAxis& b, const Rational& tb) {
    if (a.kind != ChartAxis::Kind::rotation || b.kind != ChartAxis::Kind::rotation) return false;
    if (a.half_turn == b.half_turn) return ta == tb;
    return ta * tb == -1;
  };
  std::vector<std::vector<char>> seen(nx * ny, std::vector<char>(grid * grid, 0));
  std::vector<std::array<std::size_t, 3>> queue;
  std::vector<cspace::BlockedTester::Cache> caches(nx * ny);   // per chart: its axes are fixed
  // a part's poses depend only on its own axis (BlockedTester::axis_of) and interval: the charts
  // with the same axis for a part share that part's poses (the cells' intervals are the same
  // doubles there), as the same computation gives the same poses
  for (std::size_t c = 0; c < nx * ny && cspace::shared_chart_poses().load(std::memory_order_relaxed); ++c)
    for (int k = 0; k < 2; ++k) {
      const int use = tester.axis_of(k);
      const std::size_t first = use == 0 ? (c / ny) * ny : use == 1 ? c % ny : 0;   // the first chart with that axis
      if (first != c) caches[c].share(k, caches[first].part(k));
    }
  // The disk pairs that can certify a cell, gathered once per block of block_side x block_side
  // cells (BlockedTester::blocked's `narrowed` list of the block's box, which contains each of
  // its cells' boxes: the cells' ends are monotone in the index). A cell is then tested on its
  // block's list only, with the same answer as the sweep over every disk (the list holds every
  // pair that can certify a box inside the block; BlockedTester::blocked). A block certified
  // blocked as a whole leaves no list: its cells are tested by the sweep, as before (a cell's
  // own test is what decides it, so the flood is the same cell for cell).
  // Where a tile is larger than a block (sub > block_side), the tile's box is gathered first,
  // once, and its blocks are tested on the tile's list (the list holds every pair that can
  // certify a box inside the tile, so the blocks' lists are the sweep's; the same reasoning
  // one level up). The kept tiles' lists (the tile's, or where a block holds the tile, the
  // block's) go to the tiles' grids (RegionTiles::lists).
  constexpr std::size_t block_side = 8;
  struct Block {
    bool listed = false;
    std::vector<cspace::BlockedTester::DiskPair> pairs;
  };
  // the union of the cells [i_first, i_last] x [j_first, j_last] of chart c
  auto box_of = [&](std::size_t c, std::size_t i_first, std::size_t i_last, std::size_t j_first, std::size_t j_last) {
    const ChartAxis& x = layout.x_charts[c / ny];
    const ChartAxis& y = layout.y_charts[c % ny];
    return std::array<cspace::algebra::Interval, 2>{
        cspace::algebra::Interval{cell_interval(x, i_first).lo, cell_interval(x, i_last).hi},
        cspace::algebra::Interval{cell_interval(y, j_first).lo, cell_interval(y, j_last).hi}};
  };
  const std::size_t blocks = (grid + block_side - 1) / block_side;
  std::vector<std::unordered_map<std::size_t, Block>> block_lists(nx * ny);
  const bool lists = cspace::region_tile_lists().load(std::memory_order_relaxed);
  const bool tile_level = lists && sub > block_side;
  std::vector<std::unordered_map<std::size_t, Block>> tile_lists(nx * ny);
  // tile (ti, tj) of chart c: tested and listed on first use
  auto tile_block = [&](std::size_t c, std::size_t ti, std::size_t tj) -> Block& {
    auto [it, inserted] = tile_lists[c].try_emplace(ti * tiles + tj);
    Block& tile = it->second;
    if (inserted) {
      const auto [bx, by] = box_of(c, ti * sub, (ti + 1) * sub - 1, tj * sub, (tj + 1) * sub - 1);
      tile.listed = !tester.blocked(layout.x_charts[c / ny], layout.y_charts[c % ny], bx, by, caches[c], nullptr,
                                    &tile.pairs);
      if (!tile.listed) tile.pairs.clear();
    }
    return tile;
  };
  auto blocked = [&](std::size_t c, std::size_t i, std::size_t j) {
    const ChartAxis& x = layout.x_charts[c / ny];
    const ChartAxis& y = layout.y_charts[c % ny];
    const std::size_t bi = i / block_side, bj = j / block_side;
    auto [it, inserted] = block_lists[c].try_emplace(bi * blocks + bj);
    Block& block = it->second;
    if (inserted) {
      const std::size_t i_first = bi * block_side, j_first = bj * block_side;
      const std::size_t i_last = std::min(grid, (bi + 1) * block_side) - 1;
      const std::size_t j_last = std::min(grid, (bj + 1) * block_side) - 1;
      const auto [bx, by] = box_of(c, i_first, i_last, j_first, j_last);
      // the block's tile's list, when the block lies in one tile that is not blocked whole
      const std::vector<cspace::BlockedTester::DiskPair>* above = nullptr;
      if (tile_level && i_first / sub == i_last / sub && j_first / sub == j_last / sub)
        if (Block& tile = tile_block(c, i_first / sub, j_first / sub); tile.listed) above = &tile.pairs;
      block.listed = !tester.blocked(x, y, bx, by, caches[c], above, &block.pairs);
      if (!block.listed) block.pairs.clear();
    }
    if (!block.listed) return tester.blocked(x, y, cell_interval(x, i), cell_interval(y, j), caches[c]);
    return tester.blocked(x, y, cell_interval(x, i), cell_interval(y, j), caches[c], &block.pairs, nullptr);
  };
  auto push = [&](std::size_t c, std::size_t i, std::size_t j) {
    char& mark = seen[c][i * grid + j];
    if (mark) return;
    mark = 1;
    if (blocked(c, i, j)) return;
    mark = 2;
    queue.push_back({c, i, j});
  };
  push((*start)[0], (*start)[1], (*start)[2]);
  if (queue.empty())
    throw GeometryError("operating region of '" + model.parts[axes.first].name + "' and '" +
                        model.parts[axes.second].name + "': the parts certainly overlap at the seed configuration");
  for (std::size_t head = 0; head < queue.size(); ++head) {
    auto [c, i, j] = queue[head];
    std::size_t ix = c / ny, iy = c % ny;
    region.kept[c][(i / sub) * tiles + j / sub] = 1;
    if (i > 0) push(c, i - 1, j);
    if (i + 1 < grid) push(c, i + 1, j);
    if (j > 0) push(c, i, j - 1);
    if (j + 1 < grid) push(c, i, j + 1);
    for (std::size_t other = 0; other < nx; ++other) {
      const ChartAxis& a = layout.x_charts[ix];
      const ChartAxis& b = layout.x_charts[other];
      if (i + 1 == grid && glued(a, a.hi, b, b.lo)) push(chart_of(other, iy), 0, j);
      if (i == 0 && glued(b, b.hi, a, a.lo)) push(chart_of(other, iy), grid - 1, j);
    }
    for (std::size_t other = 0; other < ny; ++other) {
      const ChartAxis& a = layout.y_charts[iy];
      const ChartAxis& b = layout.y_charts[other];
      if (j + 1 == grid && glued(a, a.hi, b, b.lo)) push(chart_of(ix, other), i, 0);
      if (j == 0 && glued(b, b.hi, a, a.lo)) push(chart_of(ix, other), i, grid - 1);
    }
  }
  region.cells = queue.size();
  // the kept tiles' lists: the tile's own, or the list of the block holding the whole tile
  // (a block holding several tiles: they share it)
  using Pairs = std::vector<cspace::BlockedTester::DiskPair>;
  region.lists.assign(nx * ny, std::vector<TileList>(static_cast<std::size_t>(tiles) * tiles));
  for (std::size_t c = 0; c < nx * ny && lists; ++c) {
    std::unordered_map<std::size_t, std::shared_ptr<const Pairs>> shared;   // per block
    for (std::size_t ti = 0; ti < tiles; ++ti)
      for (std::size_t tj = 0; tj < tiles; ++tj) {
        const std::size_t t = ti * tiles + tj;
        if (!region.kept[c][t]) continue;
        const std::size_t i_first = ti * sub, i_last = (ti + 1) * sub - 1;
        const std::size_t j_first = tj * sub, j_last = (tj + 1) * sub - 1;
        TileList& list = region.lists[c][t];
        if (tile_level) {
          const auto found = tile_lists[c].find(t);
          if (found == tile_lists[c].end() || !found->second.listed) continue;
          const auto box = box_of(c, i_first, i_last, j_first, j_last);
          list.x = box[0];
          list.y = box[1];
          list.pairs = std::make_shared<const Pairs>(std::move(found->second.pairs));
          continue;
        }
        const std::size_t bi = i_first / block_side, bj = j_first / block_side;
        if (i_last / block_side != bi || j_last / block_side != bj) continue;
        const auto found = block_lists[c].find(bi * blocks + bj);
        if (found == block_lists[c].end() || !found->second.listed) continue;
        const auto box = box_of(c, bi * block_side, std::min(grid, (bi + 1) * block_side) - 1, bj * block_side,
                                std::min(grid, (bj + 1) * block_side) - 1);
        list.x = box[0];
        list.y = box[1];
        std::shared_ptr<const Pairs>& pairs = shared[bi * blocks + bj];
        if (!pairs) pairs = std::make_shared<const Pairs>(found->second.pairs);
        list.pairs = pairs;
      }
  }
  if (path && !path->empty()) {
    // only the flooded tiles the path runs through, with a margin of one tile in its chart
    std::vector<std::vector<char>> near(nx * ny, std::vector<char>(static_cast<std::size_t>(tiles) * tiles, 0));
    for (const std::array<double, 2>& point : *path)
      for (std::size_t ix = 0; ix < nx; ++ix)
        for (std::size_t iy = 0; iy < ny; ++iy) {
          auto tx = chart_coordinate(layout.x_charts[ix], point[0]);
          auto ty = chart_coordinate(layout.y_charts[iy], point[1]);
          if (!tx || !ty) continue;
          if (*tx < lo_of(layout.x_charts[ix]) || *tx > hi_of(layout.x_charts[ix])) continue;
          if (*ty < lo_of(layout.y_charts[iy]) || *ty > hi_of(layout.y_charts[iy])) continue;
          std::size_t i = index_in(layout.x_charts[ix], *tx) / sub, j = index_in(layout.y_charts[iy], *ty) / sub;
          for (std::size_t a = i > 0 ? i - 1 : 0; a <= std::min<std::size_t>(i + 1, tiles - 1); ++a)
            for (std::size_t b = j > 0 ? j - 1 : 0; b <= std::min<std::size_t>(j + 1, tiles - 1); ++b)
              near[chart_of(ix, iy)][a * tiles + b] = 1;
        }
    std::size_t kept = 0;
    std::vector<std::vector<char>> restricted = region.kept;
    for (std::size_t c = 0; c < restricted.size(); ++c)
      for (std::size_t t = 0; t < restricted[c].size(); ++t) kept += (restricted[c][t] = restricted[c][t] && near[c][t]);
    if (kept > 0) region.kept = std::move(restricted);   // a path outside the flood: the whole region
  }
  return region;
}

}  // namespace

std::atomic<bool>& cspace::region_tile_lists() {
  static std::atomic<bool> on{true};
  return on;
}

std::atomic<bool>& cspace::shared_chart_poses() {
  static std::atomic<bool> on{true};
  return on;
}

namespace {

// The sub-axis of tile k of `tiles` of a chart axis.
cspace::ChartAxis tile_axis(const cspace::ChartAxis& axis, std::size_t k, std::size_t tiles) {
  cspace::ChartAxis tile = axis;
  Rational width = (axis.hi - axis.lo) / Rational(static_cast<long>(tiles));
  width.canonicalize();
  tile.lo = k == 0 ? axis.lo : axis.lo + width * Rational(static_cast<long>(k));
  tile.hi = k + 1 == tiles ? axis.hi : axis.lo + width * Rational(static_cast<long>(k + 1));
  tile.lo.canonicalize();
  tile.hi.canonicalize();
  return tile;
}

CSpace build_pair_as_is(const Model& model, std::size_t first, std::size_t second, const CSpaceBuildOptions& options,
                        const RegionPath* path, const Model* kept = nullptr, long length_unit_exponent = 0);

// The copy of the model that a built space keeps (its contact geometry queries read it). A
// space only reads its model, so an equal copy still held by a live space built on this thread
// is shared instead of copied again (same_model: every field, exactly): repeated builds of one
// model, and the pairs of one model that build_all gives a worker thread, keep one copy. The
// thread keeps only a weak reference: the copy is destroyed with the last space that holds it.
std::shared_ptr<const Model> model_copy(const Model& model) {
  thread_local std::weak_ptr<const Model> last;
  if (std::shared_ptr<const Model> held = last.lock(); held && same_model(*held, model)) return held;
  auto copy = std::make_shared<const Model>(model);
  last = copy;
  return copy;
}

CSpace build_pair(const Model& model, std::size_t first, std::size_t second, const CSpaceBuildOptions& options,
                  const RegionPath* path = nullptr) {
  // see core/model_scale.hpp: a rotation pair far outside the doubles' comfortable range is
  // built on an exactly rescaled copy (the same C-space)
  //
  // a pair far from the origin for its size (a mechanism at 10^400 mm) is first moved to the
  // origin by one exact vector (core/model_scale.hpp: the same C-space in every chart); the
  // space keeps the model as given, so contact points and normals stay in its coordinates
  if (std::optional<Point> by = normalising_translation(model, {first, second})) {
    Model moved = translated_model(model, *by);
    long shift = normalising_shift(moved, {first, second});
    if (shift == 0) require_length_coordinates_in_range(moved, {first, second});
    if (shift == 0) return build_pair_as_is(moved, first, second, options, path, &model);
    Model scaled = scaled_model(moved, shift);
    return build_pair_as_is(scaled, first, second, options, path, &model);
  }
  long shift = normalising_shift(model, {first, second});
  // lengths as coordinates beyond the doubles' range: built, when asked, on the copy scaled
  // by 2^-L, and that copy is the space's model (its lengths, also contact points, in units
  // of 2^L mm: CSpace::length_unit_exponent); refused otherwise (a clear error, not a crash)
  if (shift == 0 && options.normalise_lengths && !options.operating_region)
    if (long unit = length_coordinate_shift(model, {first, second}); unit != 0) {
      Model scaled = scaled_model(model, unit);
      return build_pair_as_is(scaled, first, second, options, path, nullptr, unit);
    }
  if (shift == 0) require_length_coordinates_in_range(model, {first, second});
  if (shift == 0) return build_pair_as_is(model, first, second, options, path);
  // the scaled copy lives through the build (the charts' overlap oracles read it); the built
  // space keeps the model as given (as a moved pair does, above), so contact points and frames
  // are in its mm, not in the copy's units 2^shift mm
  Model scaled = scaled_model(model, shift);
  return build_pair_as_is(scaled, first, second, options, path, &model);
}

CSpace build_pair_as_is(const Model& model, std::size_t first, std::size_t second, const CSpaceBuildOptions& options,
                        const RegionPath* path, const Model* kept, long length_unit_exponent) {
  using namespace cspace;
  PairAxes axes = pair_axes(model, first, second);
  if (axes.dimension() == 0)
    throw GeometryError("parts '" + model.parts[first].name + "' and '" + model.parts[second].name +
                        "' are both fixed: their C-space is a single configuration");
  ChartLayout layout = chart_layout(model, axes);
  PairInput input;
  input.first_part = model.parts[first].name;
  input.second_part = model.parts[second].name;
  std::size_t x_mover = axes.first_moves ? axes.first : axes.second;
  input.x_part = model.parts[x_mover].name;
  input.y_part = axes.dimension() == 2 ? model.parts[axes.second].name : std::string();
  for (const auto& part : model.parts) input.part_names.push_back(part.name);
  input.dimension = axes.dimension();
  input.length_unit_exponent = length_unit_exponent;
  input.model = model_copy(kept ? *kept : model);
  input.axes = axes;
  // (the layout's list read in place; a 1-D space's one zero-width axis stands for it)
  std::vector<ChartAxis> zero_axis;
  if (input.dimension == 1) zero_axis = {ChartAxis{ChartAxis::Kind::translation, false, Rational(0), Rational(0)}};
  const std::vector<ChartAxis>& y_charts = input.dimension == 1 ? zero_axis : layout.y_charts;
  // Translating polygon pairs: their contact curves are the segments of the parts' reduced
  // convolution once the curve generator's exact corner test has dropped every vertex–segment
  // pair whose curve lies in blocked space throughout; CGAL's circle–segment arrangement
  // takes them whole (as minkowski_sum_2 does) at a fraction of the cost of the certified
  // blocked-space culls (posed disks, quadtrees: before, more than everything else of such a
  // pair). Neither cull runs for them; the C-space is the same (docs/performance.md).
  bool polygon_translation = input.dimension == 2;
  for (const auto& axis : layout.x_charts)
    if (axis.kind != ChartAxis::Kind::translation) polygon_translation = false;
  for (const auto& axis : y_charts)
    if (axis.kind != ChartAxis::Kind::translation) polygon_translation = false;
  for (std::size_t part : {first, second})
    for (const Loop& loop : model.parts[part].loops)
      for (const Edge& edge : loop.edges)
        if (edge.is_arc()) polygon_translation = false;
  std::shared_ptr<cspace::BlockedTester> tester;
  if (!polygon_translation || (options.operating_region && input.dimension == 2))
    tester = std::make_shared<cspace::BlockedTester>(model, axes);
  // the boxes to build: whole charts, or the tiles of the operating region
  struct BoxToBuild {
    std::size_t x_index, y_index;
    ChartAxis x, y;
    TileList list;   // an operating-region tile's: the flood's list of a box holding it
  };
  std::vector<BoxToBuild> boxes;
  int cull_depth = 0;
  if (options.operating_region && input.dimension == 2) {
    if (!tester->usable())
      throw GeometryError("operating region of '" + input.first_part + "' and '" + input.second_part +
                          "': a part has no interior disks to certify blocked space");
    auto region_start = Clock::now();
    RegionTiles region = flood_region(model, axes, layout, *tester, options, path);
    input.seconds_region = std::chrono::duration<double>(Clock::now() - region_start).count();
    input.region_cells = region.cells;
    input.complete = false;
    std::size_t tiles = region.tiles;
    for (std::size_t ix = 0; ix < layout.x_charts.size(); ++ix)
      for (std::size_t iy = 0; iy < y_charts.size(); ++iy)
        for (std::size_t tx = 0; tx < tiles; ++tx)
          for (std::size_t ty = 0; ty < tiles; ++ty)
            if (region.kept[ix * y_charts.size() + iy][tx * tiles + ty])
              boxes.push_back({ix * tiles + tx, iy * tiles + ty, tile_axis(layout.x_charts[ix], tx, tiles),
                               tile_axis(y_charts[iy], ty, tiles), region.lists[ix * y_charts.size() + iy][tx * tiles + ty]});
    // the culling quadtree keeps the resolution of a whole chart's
    cull_depth = 3;
    while ((std::size_t{1} << cull_depth) * tiles < 512 && cull_depth < 9) ++cull_depth;
    // a region that is most of a finely tiled space (free space that is not a narrow channel)
    // is built whole: thousands of tiles would only add seams and repeated curve analyses
    std::size_t all_tiles = layout.x_charts.size() * y_charts.size() * tiles * tiles;
    if (tiles >= 32 && 2 * boxes.size() > all_tiles) {
      boxes.clear();
      input.complete = true;
      cull_depth = 0;
    }
  }
  if (boxes.empty()) {
    for (std::size_t ix = 0; ix < layout.x_charts.size(); ++ix)
      for (std::size_t iy = 0; iy < y_charts.size(); ++iy)
        boxes.push_back({ix, iy, layout.x_charts[ix], y_charts[iy], {}});
  }
  // the charts mapped from their half-turn twin (TwinChart): whole 2-D spaces, a part whose half
  // turn about its pivot maps it onto itself exactly, the chart with its axis at pi mapped from
  // the one at 0 (or the reverse: the first built) with every other axis and the box the same;
  // a mapped chart may be mapped again across the other part's half turn (both parts symmetric)
  if (input.dimension == 2 && input.complete && !options.keep_arrangements &&
      cspace::mapped_twin_charts().load(std::memory_order_relaxed)) {
    const std::size_t axis_part[2] = {axes.first, axes.second};
    std::optional<std::vector<std::vector<HalfTurnImage>>> image[2];
    for (int a = 0; a < 2; ++a)
      if (model.parts[axis_part[a]].motion.kind == Motion::Kind::rotation) image[a] = half_turn_symmetry(model.parts[axis_part[a]]);
    if (image[0] || image[1]) {
      input.twins.resize(boxes.size());
      auto same = [](const ChartAxis& p, const ChartAxis& q) {
        return p.kind == q.kind && p.half_turn == q.half_turn && p.lo == q.lo && p.hi == q.hi;
      };
      auto twin = [](const ChartAxis& p, const ChartAxis& q) {
        return p.kind == ChartAxis::Kind::rotation && q.kind == p.kind && p.half_turn != q.half_turn && p.lo == q.lo &&
               p.hi == q.hi;
      };
      for (std::size_t c = 0; c < boxes.size(); ++c)
        for (std::size_t s = 0; s < c && input.twins[c].source == no_index; ++s) {
          for (int a = 0; a < 2 && input.twins[c].source == no_index; ++a) {
            const bool x = a == 0;
            if (!image[a] || !(x ? twin(boxes[s].x, boxes[c].x) && same(boxes[s].y, boxes[c].y)
                                 : twin(boxes[s].y, boxes[c].y) && same(boxes[s].x, boxes[c].x)))
              continue;
            TwinChart& t = input.twins[c];
            t.source = s;
            t.part = axis_part[a];
            t.image = *image[a];
            t.x_index = boxes[c].x_index;
            t.y_index = boxes[c].y_index;
            t.x = boxes[c].x;
            t.y = boxes[c].y;
          }
        }
    }
  }
  auto generator_start = Clock::now();
  CurveOptions curve_options;
  curve_options.cull_blocked_space = !polygon_translation && options.cull_blocked_space;
  curve_options.polygon_front_end = options.polygon_front_end;
  // One merged blocked-space cull: each box's grid of certainly-blocked cells (the tester's,
  // memoised) culls feature pairs before their exact polynomials are formed and then gives the
  // kept curves their windows (prepare_chart); 2-D grids have the culling quadtree's depth,
  // 1-D ones the generator's former depth.
  curve_options.blocked_grid = curve_options.cull_blocked_space;
  const int grid_depth = input.dimension == 2 ? (cull_depth > 0 ? cull_depth : 9) : 10;
  CurveGenerator generator(model, axes, curve_options);
  // the pair's oracle (both parts' enclosures prepared once): the rational points' exact
  // relation and the algebraic oracle's certified filter. Session 75 (poly75): prepared when
  // a classifier first asks (a translating polygon pair's faces are mostly decided by the
  // contact curves' blocked sides; its preparation was 3.3 % of a triangle + square build),
  // and a translating polygon pair's chart points where the parts' moved bounding boxes are
  // strictly apart are answered `apart` exactly without it (TranslatedBoxes: the free face's
  // sample, usually). Every other answer is the same oracle's.
  struct LazyOverlap {
    LazyOverlap(const Model& m, const PairAxes& a, bool polygons) : model(m), axes(a) {
      if (polygons) boxes.emplace(m, a);
    }
    const Model& model;
    PairAxes axes;
    std::optional<cspace::TranslatedBoxes> boxes;
    std::once_flag once;
    std::unique_ptr<const PairOverlap> made;
    const PairOverlap& get() {
      std::call_once(once, [this] { made = std::make_unique<const PairOverlap>(model, axes); });
      return *made;
    }
  };
  auto overlap = std::make_shared<LazyOverlap>(model, axes, polygon_translation);
  input.seconds_curves += std::chrono::duration<double>(Clock::now() - generator_start).count();
  // each box's curves are generated when the builder reaches it (PairInput::make_chart):
  // the boxes are built one at a time, with one box's curves alive
  input.chart_count = boxes.size();
  // the parts' poses shared between boxes with an axis in common (the charts made one at a
  // time on this thread; the answers are those of a cache per grid)
  cspace::SharedPoses shared_poses;
  const bool share_poses = cspace::shared_chart_poses().load(std::memory_order_relaxed);
  // a whole space's few grids keep their blocked-cell tables whole (flat per depth: the cheaper
  // look-up), an operating region's many tiles the sparse blocks (chosen by the tables' bytes
  // over the boxes; the answers are the same either way)
  const bool whole_tables = BlockedCells::whole_tables_fit(boxes.size(), input.dimension);
  input.make_chart = [&](std::size_t c, PairInput& building) {
    const BoxToBuild& box = boxes[c];
    ChartInput chart;
    chart.x_index = box.x_index;
    chart.y_index = box.y_index;
    chart.x = box.x;
    chart.y = box.y;
    chart.cull_depth = cull_depth;
    auto start = Clock::now();
    std::shared_ptr<BlockedCells> cells;
    if (curve_options.blocked_grid)
      cells = std::make_shared<BlockedCells>(tester, chart.x, chart.y, building.dimension, grid_depth,
                                             share_poses ? &shared_poses : nullptr, whole_tables);
    // (a tile: its cells test the flood's list of a box holding it, when the box holds the grid's)
    if (cells && box.list.pairs) cells->enclose(box.list.x, box.list.y, box.list.pairs);
    std::vector<ContactCurve> curves = generator.generate(chart.x, chart.y, &building.curve_statistics, cells.get());
    // the tester's posed disks (per axis interval) stay for the builder's cull of the same box
    // (prepare_chart, right after this): the boxes are built one at a time and the builder
    // releases the grid after culling, so one box's poses are alive at a time (the answers
    // do not depend on the cache)
    building.seconds_curves += std::chrono::duration<double>(Clock::now() - start).count();
    for (auto& curve : curves)
      if (!curve.polynomial.is_zero()) chart.curves.push_back(std::move(curve));
    // the three classifiers share one copy of the chart's axes (each capturing its own copy
    // made six copies and, as std::function moved them, six more rationals per axis)
    struct Axes {
      ChartAxis x, y;
    };
    auto chart_axes = std::make_shared<Axes>();
    chart_axes->x = chart.x;
    chart_axes->y = chart.y;
    chart.classify = [chart_axes, overlap](const cspace::ChartPoint& q) {
      if (overlap->boxes && overlap->boxes->apart(q)) return Overlap::apart;
      return overlap->get().classify(chart_axes->x, chart_axes->y, q);
    };
    chart.classify_algebraic = [&model, axes, chart_axes, overlap](const algebra::Real& qx, const algebra::Real& qy) {
      return algebraic_overlap(model, axes, chart_axes->x, chart_axes->y, qx, qy, &overlap->get());
    };
    chart.classify_ordinate = [&model, axes, chart_axes, overlap](const algebra::Real& qx, const RadicalOrdinate& qy) {
      return algebraic_overlap(model, axes, chart_axes->x, chart_axes->y, qx, qy, &overlap->get());
    };
    chart.certainly_overlapping = [axes, chart_axes, overlap](const algebra::Real& qx, const Rational& y_lower,
                                                              const Rational& y_upper) {
      return certainly_overlapping_over(axes, chart_axes->x, chart_axes->y, qx, y_lower, y_upper, &overlap->get());
    };
    if (building.dimension == 2 && cells && cells->usable()) chart.blocked_cells = std::move(cells);
    return chart;
  };
  return build_cspace(std::move(input), options);
}

}  // namespace

CSpace CSpace::build(const Model& model, std::string_view first_part, std::string_view second_part,
                     const CSpaceBuildOptions& options) {
  std::size_t first = part_index(model, first_part), second = part_index(model, second_part);
  if (first == second) throw ModelError("/pairs", "a pair needs two different parts");
  return build_pair(model, first, second, options);
}

CSpace build_operating_region_along(const Model& model, std::string_view first_part, std::string_view second_part,
                                    const std::vector<std::array<double, 2>>& path, CSpaceBuildOptions options) {
  std::size_t first = part_index(model, first_part), second = part_index(model, second_part);
  if (first == second) throw ModelError("/pairs", "a pair needs two different parts");
  options.operating_region = true;
  if (!options.region_seed && !path.empty()) options.region_seed = path.front();
  return build_pair(model, first, second, options, &path);
}

namespace {

// Builds every fixed-axis pair with a moving part on worker threads; a pair's failure is kept
// as its exception and never stops the other pairs.
struct PairOutcome {
  std::size_t first = 0, second = 0;
  CSpace space;
  std::exception_ptr error;
};

std::vector<PairOutcome> build_each(const Model& model, const CSpaceBuildOptions& given) {
  // the pairs' reports reach the caller's callback one at a time (CSpaceProgress)
  CSpaceBuildOptions options = given;
  std::mutex reporting;
  if (given.progress)
    options.progress = [&reporting, &given](const CSpaceBuildProgress& report) {
      std::lock_guard<std::mutex> lock(reporting);
      given.progress(report);
    };
  std::vector<PairOutcome> outcomes;
  for (const auto& pair : model.pairs) {
    int first = model.parts[pair.first].motion.degrees_of_freedom();
    int second = model.parts[pair.second].motion.degrees_of_freedom();
    if (first > 1 || second > 1 || first + second == 0) continue;
    outcomes.push_back(PairOutcome{pair.first, pair.second, CSpace{}, nullptr});
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < outcomes.size(); i = next++) {
      try {
        outcomes[i].space = build_pair(model, outcomes[i].first, outcomes[i].second, options);
      } catch (...) {
        outcomes[i].error = std::current_exception();
      }
    }
  };
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  // CGAL's algebraic kernel caches are per thread: kept arrangements must stay on this thread
  if (options.keep_arrangements) threads = 1;
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, outcomes.size()));
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < threads; ++t) workers.emplace_back(work);
    for (auto& worker : workers) worker.join();
  }
  return outcomes;
}

}  // namespace

std::vector<CSpace> CSpace::build_all(const Model& model, const CSpaceBuildOptions& options) {
  std::vector<PairOutcome> outcomes = build_each(model, options);
  std::vector<CSpace> spaces;
  for (auto& outcome : outcomes) {
    if (outcome.error) std::rethrow_exception(outcome.error);
    spaces.push_back(std::move(outcome.space));
  }
  return spaces;
}

std::vector<PairBuild> CSpace::build_pairs(const Model& model, const CSpaceBuildOptions& options) {
  std::vector<PairOutcome> outcomes = build_each(model, options);
  std::vector<PairBuild> builds;
  for (auto& outcome : outcomes) {
    PairBuild build;
    build.first_part = model.parts[outcome.first].name;
    build.second_part = model.parts[outcome.second].name;
    if (outcome.error) {
      build.status = PairBuild::Status::failed;
      try {
        std::rethrow_exception(outcome.error);
      } catch (const std::exception& e) {
        build.error = e.what();
      } catch (...) {
        build.error = "unknown error";
      }
    } else {
      build.status = PairBuild::Status::built;
      build.space = std::make_shared<const CSpace>(std::move(outcome.space));
    }
    builds.push_back(std::move(build));
  }
  return builds;
}

}  // namespace hipair
