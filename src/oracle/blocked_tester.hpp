// Certainly-blocked C-space boxes of a fixed-axis pair (internal to the builder).
//
// A box of a chart is certainly blocked when, for every configuration in it, a disk of the
// first part's material and a disk of the second part's material overlap: the interiors of
// the parts overlap there. The builder culls contact curves in such boxes and stops the
// operating-region flood at them. The decision is certified: the disks are certified once at
// construction (exact centre strictly inside the part, radius a certified lower bound of the
// clearance) and blocked() computes in outward-rounded interval arithmetic (kernels/interval.hpp)
// from the chart coordinates (rational cos/sin of the half-angle tangent, no libm trigonometry).
// Lengths are in units of 2^exponent mm (an exact power-of-two scaling of the parts), so no
// double over- or underflows at any model scale.
#pragma once

#include "algebra/exact_real.hpp"
#include "curves/contact_curves.hpp"
#include "kernels/interval.hpp"

#include <hipair/model.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hipair::cspace {

/// BlockedTester's memo of certified part disks: a part's disks (and boundary points) depend
/// only on its loops' exact geometry, its pivot and the pair's scale exponent, so they are
/// certified once per process for each such key (the escapement's anchor, in three pairs,
/// once) and shared by every tester constructed later, on any thread. The disks are the same
/// as without the memo. On by default; tests turn it off to compare.
std::atomic<bool>& part_disk_memo();
/// Testers that took a part's disks from the memo (tests).
std::atomic<std::size_t>& part_disk_memo_hits();

class BlockedTester {
  friend struct BlockedTesterProbe;   // tests: the disk sweep against every pair
  struct PosedDisk {
    double x, y;
    double reach;         // lower bound of the radius over the whole interval (may be negative)
    double outer;         // upper bound of the radius plus the centre's movement and errors
    std::uint32_t index;  // of the certified disk in disks(part)
  };
  // Posed disks of one kind, sorted by the centre's x.
  struct PosedSet {
    std::vector<PosedDisk> disks;
    std::vector<double> xs;   // the centres' x, ascending
    double widest = 0;        // the largest reach
  };
  // One part's disks posed over one interval of its axis: its interior disks and its boundary
  // points (radius 0: they certify only against the other part's interior disks).
  struct Posed {
    bool usable = true;   // false: the interval admits no claim (nothing is blocked)
    PosedSet interior, boundary;
  };
  // The pose of one part over one interval of its axis, without its disks: the pose at a
  // middle value and bounds of how far a point moves from there (see pose_bound()).
  struct PoseBound {
    bool usable = true;             // false: the interval admits no claim (nothing is blocked)
    double c = 1, s = 0;            // a point of the enclosure of cos, sin at m
    double cs_error = 0;            // bound of |cos - c| + |sin - s|
    double cs_size = 1;             // bound of |c| + |s|
    double shift = 0;               // translations: m
    double angle = 0;               // bound of |theta - theta_m|
    double travel = 0;              // bound of the translation's travel from the middle
    double direction_error = 0;     // bound of the direction's enclosure width
  };

 public:
  /// The parts' posed disks per interval of their axes, kept between calls for the boxes of
  /// one chart (always with the same two chart axes): a part's posed disks depend only on its
  /// own axis interval, so a grid of boxes poses each part once per column or row instead of
  /// once per box. The answers are the same as without it. One cache per chart and thread.
  class Cache {
    friend class BlockedTester;
    // One part's pose over one axis interval and its disks posed with it so far (the
    // candidate lists' path: a disk of a column's or row's cells is posed once for them all).
    // slot[i]: -1 not yet posed, -2 not finite, otherwise its place in `disks`.
    struct Pose {
      PoseBound bound;
      std::vector<std::int32_t> slot;
      std::vector<PosedDisk> disks;
    };
    // keyed by the axis interval's ends (a hash of their bits: equal doubles, equal keys;
    // node-based, so entries stay in place while the tables grow)
    struct KeyHash {
      std::size_t operator()(const std::pair<double, double>& key) const noexcept;
    };
    static constexpr int cell_index_depths = 13;

   public:
    /// One part's poses: they depend only on the part, its chart axis (kind and chart centre)
    /// and the axis interval, so the grids of several boxes with the same axis and the same
    /// box side (a pair's charts with one axis in common, the operating-region tiles of one
    /// column) can share one (SharedPoses). Made by the cache; opaque outside the tester.
    class Part {
      friend class BlockedTester;
      std::unordered_map<std::pair<double, double>, Posed, KeyHash> posed;
      std::unordered_map<std::pair<double, double>, Pose, KeyHash> bounds;
      // The entries of `bounds` found for the cells of a grid (BlockedCells), per depth and
      // column or row index (a cell's sides are pure functions of the grid box's side, its
      // depth and index, so an index names one key): a grid's look-up of a pose it has seen is
      // an array read, not a hash. Depths to cell_index_depths - 1 only; null: not yet found.
      std::vector<Pose*> by_cell[cell_index_depths];
    };
    Cache() : parts_{std::make_shared<Part>(), std::make_shared<Part>()} {}
    /// Part k's poses: this cache's own, or ones shared with other caches (share()).
    const std::shared_ptr<Part>& part(int k) const { return parts_[k]; }
    /// Takes `part` as part k's poses (shared with the caches that hold it). Sound only between
    /// grids whose part k has the same chart axis and the same box side (SharedPoses checks).
    void share(int k, std::shared_ptr<Part> part) { parts_[k] = std::move(part); }

   private:
    std::shared_ptr<Part> parts_[2];
  };

  /// A cell of a BlockedCells grid (its depth and indices), given with the cell's box so that
  /// the cache finds the parts' poses by index (the same entries as by the box's ends).
  struct GridCell {
    int depth;
    long i, j;
  };

  /// A pair of certified disks, indices into disks(0) and disks(1).
  struct DiskPair {
    std::uint32_t first, second;
  };

  BlockedTester(const Model& model, const PairAxes& axes);
  /// False when either part got no certified disk (then nothing is ever blocked).
  bool usable() const { return interior_disks_[0] > 0 && interior_disks_[1] > 0; }
  /// The chart axis part k's pose depends on: 0 the chart's x axis, 1 its y axis, -1 none (a
  /// fixed part). The first moving part carries x, the second y.
  int axis_of(int k) const { return !moves_[k] ? -1 : (k == 0 || !moves_[0]) ? 0 : 1; }
  /// True only if the parts' interiors overlap at every configuration of the box [x] x [y]
  /// (chart x carries the first moving part, chart y the second, if any). Certified.
  bool blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
               const algebra::Interval& y) const;
  /// The same answer, with the posed disks kept in `cache` (see Cache; the same chart axes
  /// at every call with one cache).
  bool blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
               const algebra::Interval& y, Cache& cache) const;

  /// The same answer again, from a list of candidate pairs instead of a sweep over all disks:
  /// `candidates` (null: every pair) must hold every pair of disks that can certify the box,
  /// as the `narrowed` list of any box containing it does. When the box is not blocked and
  /// `narrowed` is given, it receives the pairs that can certify some box inside this one
  /// (the posed centres closer than the sum of both disks' radii plus both movement bounds
  /// over this box: a pair certifying a sub-box is closer than the radii at every
  /// configuration of the sub-box, and each posed centre is within its movement bound of the
  /// true one). The answer does not depend on the candidates given (any pair certifying the
  /// box is among them, and the same certified test decides each pair), so it is the answer
  /// of the sweep; only the work differs.
  bool blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
               const algebra::Interval& y, Cache& cache, const std::vector<DiskPair>* candidates,
               std::vector<DiskPair>* narrowed, const GridCell* cell = nullptr) const;

  /// A disk of a part's material in the tester's unit, certified once at construction (exact
  /// centre strictly inside the part, radius a certified lower bound of its clearance).
  struct CertifiedCore {
    kernels::Interval x, y;     // centre enclosure (a point: the centre is a double)
    kernels::Interval rx, ry;   // centre minus the part's pivot (rotating parts)
    double r = 0;               // radius, rounded down
    double rho = 0;             // upper bound of the distance from the pivot (rotating parts)
    double cx = 0, cy = 0;      // the centre (exact doubles)
    double rx_m = 0, ry_m = 0;  // points of rx, ry
    double r_error = 0;         // bound of |rx - rx_m| and |ry - ry_m|
    double magnitude = 0;       // bound of |rx| + |ry|
    double centre_error = 0;    // bound of |centre - (cx, cy)| per coordinate (boundary points)
  };

  const std::vector<CertifiedCore>& disks(int part) const { return disks_[part]; }

 private:
  bool pose_part(int k, const ChartAxis& axis, const algebra::Interval& range, Posed& out) const;
  PoseBound pose_bound(int k, const ChartAxis& axis, const algebra::Interval& range) const;
  bool pose_disk(int k, const PoseBound& pose, std::uint32_t index, PosedDisk& out) const;
  template <class F>
  bool each_part(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                 const algebra::Interval& y, F&& f) const;
  // the parts' cached posed disks (or pose bounds) over the box; false: nothing is blocked
  bool posed_parts(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                   const algebra::Interval& y, Cache& cache, const Posed* out[2]) const;
  bool pose_bounds(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                   const algebra::Interval& y, Cache& cache, Cache::Pose* out[2], const GridCell* cell) const;
  // disk `index` of part k posed with `pose` (pose_disk's answer, kept in the pose); null when
  // not finite
  const PosedDisk* posed_disk(int k, Cache::Pose& pose, std::uint32_t index) const;
  const PosedDisk* pose_new_disk(int k, Cache::Pose& pose, std::uint32_t index) const;
  static bool overlapping(const Posed& first, const Posed& second);
  static bool overlapping(const PosedSet& first, const PosedSet& second);
  static bool gather(const Posed& first, const Posed& second, std::vector<DiskPair>& out);
  static bool gather(const PosedSet& first, const PosedSet& second, std::vector<DiskPair>& out);

  PairAxes axes_;
  long exponent_;                        // lengths in units of 2^exponent_ mm
  Motion::Kind motion_[2] = {};
  bool moves_[2] = {};
  kernels::Interval pivot_[2][2];        // the parts' pivots in that unit
  kernels::Interval direction_[2][2];    // translation directions (unit vectors, enclosed)
  double direction_length_[2] = {};      // upper bound of |direction|
  double pivot_m_[2][2] = {};            // points of the pivots' enclosures
  double pivot_error_[2] = {};           // bound of their error
  double pivot_magnitude_[2] = {};       // max |pivot_m| coordinate
  std::vector<CertifiedCore> disks_[2];
  std::size_t interior_disks_[2] = {};   // disks of positive radius (the rest: boundary points)
};

/// The certainly-blocked cells of one chart box (a whole chart or an operating-region tile):
/// the one grid of the merged blocked-space cull. Depth 0 is the box (its rational ends
/// enclosed outward in doubles), a cell of depth d + 1 is a quarter of one of depth d (a half
/// for a 1-D space), so cell (d, i, j) covers [cell_x(d, i)] x [cell_y(d, j)] and the cells of
/// one depth tile the box. `depth()` is the builder's finest depth (its windows); the curve
/// generator may go deeper (any depth up to 24 is a cell). The curve generator asks it which feature pairs can touch outside
/// certified blocked space (before any exact polynomial is formed), and the builder which
/// parts of each kept curve can bound free space (its windows); every cell is tested once
/// (memoised, with the posed disks of the tester's cache), and a cell inside a blocked cell
/// is blocked without a test. Certified as BlockedTester::blocked. One instance per box and
/// thread.
class BlockedCells;

/// The parts' poses shared between the grids (BlockedCells) of one tester's boxes, built one
/// after the other: a part's poses depend only on its chart axis and the axis interval (not on
/// the other part's), so two boxes with the same axis for that part and the same box side on
/// it — a pair's charts with one axis in common (Geneva: each of the four charts shares its x
/// axis with one chart and its y axis with another), the operating-region tiles of one column —
/// pose each cell's column or row once for both instead of once per box. The answers are the
/// same as with a cache per grid (a pose is the same computation whichever grid made it).
/// Keeps the poses of the `kept` most recently used axes per part (the rest are freed when no
/// grid holds them). One pool per tester and thread.
class SharedPoses {
 public:
  explicit SharedPoses(std::size_t kept = 2) : kept_(kept) {}
  /// Poses found in another grid's part (tests, statistics).
  std::size_t reused() const { return reused_; }

 private:
  friend class BlockedCells;
  // part k's poses for a grid of `tester` whose part k has axis `use` (BlockedTester::axis_of)
  // of the given kind and centre and box side [lo, hi]
  std::shared_ptr<BlockedTester::Cache::Part> part(const std::shared_ptr<const BlockedTester>& tester, int k, int use,
                                                   const ChartAxis& axis, double lo, double hi);
  struct Entry {
    std::shared_ptr<const BlockedTester> tester;   // (held: an entry never outlives its tester)
    int k, use;
    ChartAxis::Kind kind;
    bool half_turn;
    double lo, hi;
    std::shared_ptr<BlockedTester::Cache::Part> part;
  };
  std::size_t kept_;
  std::vector<Entry> entries_;   // least recently used first
  std::size_t reused_ = 0;
};

class BlockedCells {
 public:
  /// `tester` may be null or unusable: then no cell is blocked. `depth`: the finest depth.
  /// `shared`: the parts' poses are taken from (and left in) the pool, shared with the other
  /// grids of the same tester that have the same axis and box side for a part (2-D grids; a
  /// 1-D grid keeps its own). `whole_tables`: every depth of at most 2^whole_cells_log2 cells
  /// is one flat table, made at the grid's construction (whole_table_bytes(), zeroed; see the
  /// private part), the deeper tabled depths sparse blocks as without. The answers are the same
  /// either way.
  BlockedCells(std::shared_ptr<const BlockedTester> tester, const ChartAxis& x, const ChartAxis& y, int dimension,
               int depth, SharedPoses* shared = nullptr, bool whole_tables = false);
  /// Whole tables: the depths of at most 2^whole_cells_log2 cells (2-D to depth 8, 1-D to 16).
  /// (Not depth 9 of a 2-D grid: its 1 MB table, touched here and there, took 460 page faults
  /// more per Geneva build than its sparse blocks, for 0.6 M instructions fewer.)
  static constexpr int whole_cells_log2 = 16;
  /// Bytes of the whole tables of a grid of `dimension` (2-D 0.33 MB, 1-D 0.5 MB; none below 1-D).
  static constexpr std::size_t whole_table_bytes(int dimension) {
    if (dimension < 1) return 0;
    std::size_t bytes = 0;
    for (int d = 0; d * dimension <= whole_cells_log2; ++d) bytes += (std::size_t{1} << (d * dimension)) * sizeof(std::int32_t);
    return bytes;
  }
  /// Whole tables suit a build of `grids` grids of `dimension` when their tables together take
  /// at most this many bytes (a whole space's few charts: Geneva's four 1.3 MB; an operating
  /// region's hundreds of tiles keep the sparse blocks). Chosen by size only: the entries,
  /// hence the answers, are the same either way.
  static constexpr std::size_t whole_tables_budget = std::size_t{4} << 20;
  static constexpr bool whole_tables_fit(std::size_t grids, int dimension) {
    return dimension >= 1 && grids * whole_table_bytes(dimension) <= whole_tables_budget;
  }
  /// The grid's tables are whole (the constructor's `whole_tables`).
  bool whole_tables() const { return whole_ != nullptr; }
  int depth() const { return depth_; }
  int dimension() const { return dimension_; }
  /// False: nothing is ever blocked (no usable tester).
  bool usable() const { return tester_ != nullptr; }
  algebra::Interval cell_x(int depth, long i) const {
    if (depth <= sides_depth_ && i >= 0 && i < (1L << depth)) return sides_[0][(std::size_t{1} << depth) - 1 + static_cast<std::size_t>(i)];
    return side_x(depth, i);
  }
  algebra::Interval cell_y(int depth, long j) const {   ///< a point (0) for a 1-D space
    if (dimension_ != 2) return y_;
    if (depth <= sides_depth_ && j >= 0 && j < (1L << depth)) return sides_[1][(std::size_t{1} << depth) - 1 + static_cast<std::size_t>(j)];
    return side_y(depth, j);
  }
  /// Every configuration of cell (depth, i, j) is certainly blocked.
  bool blocked(int depth, long i, long j);
  /// The cell was answered blocked already (no test, no look-up of its ancestors).
  bool known_blocked(int depth, long i, long j) const { return tester_ && known(depth, i, j) == is_blocked; }
  /// Tester calls made (each cell at most once).
  std::size_t tests() const { return tests_; }
  /// Bytes of the per-depth tables made so far (directories and blocks of the tabled depths).
  /// A grid with whole tables counts them whole, as allocated (calloc'ed): only the pages its
  /// cells touch are resident (faulted in), which may be much less.
  std::size_t table_bytes() const;
  /// Cell (depth, ·, ·) of this grid is kept in a per-depth table (whole or sparse blocks: a
  /// look-up by index), not in the map of the deeper cells.
  bool tabled(int depth) const { return dimension_ >= 1 && depth * dimension_ <= dense_cells_log2; }
  /// The tables' blocks: a depth of at most 2^whole_table_log2 cells is one block; a deeper
  /// one is cut into 2-D squares of 2^table_block_log2 cells a side, 1-D runs of
  /// 2^(2 table_block_log2) cells (see the private part).
  static constexpr int table_block_log2 = 4, whole_table_log2 = 12;
  /// log2 of the side (2-D) or length (1-D) of a block of a tabled depth of a grid of `dimension`.
  static constexpr int block_side_log2(int dimension, int depth) {
    return depth * dimension <= whole_table_log2 ? depth : dimension == 2 ? table_block_log2 : 2 * table_block_log2;
  }
  /// Candidate pairs tested over all calls (the work of the tests).
  std::size_t pairs_tested() const { return pairs_tested_; }
  /// Frees the tester's posed disks (kept for the next cells); the known cells and their
  /// candidate lists stay.
  void release_cache() { cache_ = BlockedTester::Cache{}; }
  /// Gives the grid the candidate list of an enclosing box [x] x [y] (the `narrowed` list of
  /// BlockedTester::blocked over that box: every pair of disks that can certify a box inside
  /// it): a cell with no tested ancestor then tests only those pairs instead of sweeping every
  /// disk (an operating-region tile gets the list the flood made for its tile or block). The
  /// answers are the sweep's (BlockedTester::blocked's answer does not depend on the
  /// candidates given). Kept only when the grid's box lies inside [x] x [y] (2-D grids);
  /// returns whether it was kept.
  bool enclose(const algebra::Interval& x, const algebra::Interval& y,
               std::shared_ptr<const std::vector<BlockedTester::DiskPair>> pairs);

 private:
  // A tested cell's entry: 0 not tested, 1 blocked, 2 not blocked, 3 + k not blocked with
  // list k (above the finest depth anyone tests): the disk pairs that can certify a cell
  // inside it (BlockedTester::blocked with `narrowed`): the cells below test only those pairs
  // (the disk sweep bucketed by cell).
  static constexpr std::int32_t untested = 0, is_blocked = 1, not_blocked = 2, first_list = 3;
  // (Whole tables: every depth of at most 2^whole_cells_log2 cells is one flat table,
  // flat_[depth], all made at construction in one allocation, so whole_depth_ is the deepest of
  // them; the deeper tabled depths (2-D depth 9, 1-D 17 and 18) are cut into blocks as below.)
  // Cells of the depths with at most 2^18 cells (2-D: to depth 9; 1-D: to depth 18) are kept
  // in tables per depth, one entry per cell, made sparsely: a depth's cells are cut into blocks
  // (block_side_log2: a depth of at most 2^12 cells is one block; deeper, 2-D squares of 16 x 16
  // cells, 1-D runs of 256), a depth's directory of blocks made when a cell of that depth is
  // first asked, its blocks pointing to one shared block of zeros (every cell `untested`, only
  // read) until a cell in the block is first written, when the block is made (a cell's and its
  // ancestors' look-ups are plain reads; a grid allocates only the blocks its culls touch: the
  // dense table of session 56 was 1 MB at depth 9 for every grid, one per operating-region
  // tile); deeper cells (or indices outside the box) in a map keyed by (depth, i, j). The
  // entries, hence the answers, are the same either way.
  static constexpr int dense_cells_log2 = 18;
  bool dense(int depth, long i, long j) const {
    const long count = 1L << depth;
    return dimension_ >= 1 && depth * dimension_ <= dense_cells_log2 && i >= 0 && i < count &&
           (dimension_ == 2 ? j >= 0 && j < count : j == 0);
  }
  // The tabled depths of at most 2^whole_table_log2 cells (2-D: to depth 6; 1-D: to depth 12)
  // are one block each, flat_[depth] (index (i << depth) | j; 1-D: i); deeper ones are read
  // through directory_[depth]: block ((i >> b) << (depth - b)) | (j >> b), place in the block
  // ((i & m) << b) | (j & m) with b = table_block_log2, m = 2^b - 1 (1-D: block i >> 2b, place
  // i & (2^2b - 1)). Never null: until a cell of a depth is first written, flat_ points to the
  // shared zeros and directory_ to a shared directory of them (own_directory_ then).
  int whole_depth_ = 0;
  // the whole tables, one zeroed allocation (calloc: fresh pages come zeroed, and only the pages
  // a grid touches are ever faulted in)
  struct FreeTables {
    void operator()(std::int32_t* tables) const noexcept { std::free(tables); }
  };
  std::unique_ptr<std::int32_t[], FreeTables> whole_;
  std::int32_t* flat_[dense_cells_log2 + 1];
  std::int32_t* const* directory_[dense_cells_log2 + 1];
  std::unique_ptr<std::int32_t*[]> own_directory_[dense_cells_log2 + 1];
  std::int32_t deep_entry_2d(int depth, long i, long j) const {
    constexpr int b = table_block_log2;
    constexpr long m = (1L << b) - 1;
    return directory_[depth][static_cast<std::size_t>(((i >> b) << (depth - b)) | (j >> b))]
                        [static_cast<std::size_t>(((i & m) << b) | (j & m))];
  }
  std::int32_t deep_entry_1d(int depth, long i) const {
    constexpr int b = 2 * table_block_log2;
    return directory_[depth][static_cast<std::size_t>(i >> b)][static_cast<std::size_t>(i & ((1L << b) - 1))];
  }
  // a dense cell's entry (the shared zeros, `untested`, when its block was never written): no test
  std::int32_t dense_entry(int depth, long i, long j) const {
    if (depth <= whole_depth_) return flat_[depth][static_cast<std::size_t>(dimension_ == 2 ? (i << depth) | j : i)];
    return dimension_ == 2 ? deep_entry_2d(depth, i, j) : deep_entry_1d(depth, i);
  }
  // a dense cell's entry to write, made (with its depth's directory and its block) on first use
  std::int32_t& dense_slot(int depth, long i, long j) {
    if (depth <= whole_depth_) {
      std::int32_t* table = flat_[depth];
      if (table != zero_entries_) [[likely]]
        return table[static_cast<std::size_t>(dimension_ == 2 ? (i << depth) | j : i)];
    } else if (dimension_ == 2) {
      constexpr int b = table_block_log2;
      constexpr long m = (1L << b) - 1;
      std::int32_t* block = directory_[depth][static_cast<std::size_t>(((i >> b) << (depth - b)) | (j >> b))];
      if (block != zero_entries_) [[likely]]
        return block[static_cast<std::size_t>(((i & m) << b) | (j & m))];
    }
    return make_slot(depth, i, j);
  }
  std::int32_t& make_slot(int depth, long i, long j);
  static const std::int32_t zero_entries_[];              // the shared zeros (only read)
  static std::int32_t* zero_block() { return const_cast<std::int32_t*>(zero_entries_); }
  static std::int32_t* const* zero_directory();
  // the cell's entry (a tabled cell read in place; the deeper ones from the map)
  std::int32_t known(int depth, long i, long j) const {
    return dense(depth, i, j) ? dense_entry(depth, i, j) : known_deep(depth, i, j);
  }
  std::int32_t known_deep(int depth, long i, long j) const;
  void remember(int depth, long i, long j, std::int32_t entry);   // (a cell's first answer)
  std::shared_ptr<const BlockedTester> tester_;
  ChartAxis x_axis_, y_axis_;
  int dimension_;
  int depth_;
  algebra::Interval x_, y_;
  // The cells' sides (cell_x, cell_y) of the depths to sides_depth_ (-1: none), tabulated at the
  // construction of a grid with whole tables (a whole space's few grids, whose culls ask each
  // side many times: 2^(d+1) - 1 entries to depth d, depth d's side k at 2^d - 1 + k): the
  // values of side_x and side_y, which compute the others.
  int sides_depth_ = -1;
  std::vector<algebra::Interval> sides_[2];
  algebra::Interval side_x(int depth, long i) const;
  algebra::Interval side_y(int depth, long j) const;
  BlockedTester::Cache cache_;
  // The blocks (zeroed: every entry `untested`, which is 0) are owned by `blocks_` and never
  // move, so an entry's address stays valid while the grid lives.
  std::vector<std::unique_ptr<std::int32_t[]>> blocks_;
  std::size_t block_bytes_ = 0;
  std::unordered_map<long, std::int32_t> known_;   // the other cells
  std::vector<std::vector<BlockedTester::DiskPair>> lists_;
  // the enclosing box's list (enclose()): the candidates of a cell with no listed ancestor
  std::shared_ptr<const std::vector<BlockedTester::DiskPair>> enclosing_;
  std::size_t tests_ = 0;
  std::size_t pairs_tested_ = 0;
};

}  // namespace hipair::cspace
