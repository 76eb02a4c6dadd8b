// Internal representation behind hipair::CSpace (CGAL-free). Shared by the builder
// (builder.cpp), the queries (builder_locate.cpp) and the accessors (cspace.cpp).
#pragma once

#include <hipair/cspace.hpp>

#include "cspace/cspace_access.hpp"
#include "cspace/half_turn_symmetry.hpp"

#include "algebra/exact_real.hpp"
#include "arrangement/arrangement.hpp"
#include "curves/algebraic_overlap.hpp"
#include "curves/contact_curves.hpp"

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace hipair::cspace {

/// The exact overlap oracle of one chart.
using Classifier = std::function<Overlap(const ChartPoint&)>;
/// The exact overlap relation at a chart point with algebraic (possibly irrational)
/// coordinates (curves/algebraic_overlap.hpp), or nullopt where it cannot decide (both
/// coordinates irrational; with arcs, a loop whose every vertex has one of the other part at its
/// height and at its abscissa).
using AlgebraicClassifier = std::function<std::optional<Overlap>(const algebra::Real&, const algebra::Real&)>;
/// The same at a point whose ordinate is a rational function of its abscissa (both coordinates
/// irrational: curves/algebraic_overlap.hpp, RadicalOrdinate).
using OrdinateClassifier = std::function<std::optional<Overlap>(const algebra::Real&, const RadicalOrdinate&)>;

/// The certified filter of the algebraic classifiers alone (curves/algebraic_overlap.hpp,
/// certainly_overlapping_over): true only where the parts certainly overlap at every point of
/// the box of x (its value or isolating interval) and [y_lower, y_upper]; false says nothing.
using OverlapFilter = std::function<bool(const algebra::Real& x, const Rational& y_lower, const Rational& y_upper)>;

/// Input of one chart: its axes, its contact curves and its oracle.
struct ChartInput {
  std::size_t x_index = 0;           ///< index of the x chart axis in the layout (seams glue
  std::size_t y_index = 0;           ///< charts that share the other axis)
  ChartAxis x;
  ChartAxis y;                       ///< ignored for a 1-D space
  std::vector<ContactCurve> curves;
  Classifier classify;
  /// Optional: the oracle at irrational zero-clearance points (empty: those stay undecided).
  AlgebraicClassifier classify_algebraic;
  /// Optional: the oracle at zero-clearance vertices with both coordinates irrational (empty:
  /// those stay undecided).
  OrdinateClassifier classify_ordinate;
  /// Optional: their certified filter alone, asked first at zero-clearance candidates (where it
  /// answers, the parts overlap there: no exact work; empty: the classifiers decide alone).
  OverlapFilter certainly_overlapping;
  /// Optional: the box's certainly-blocked cells (the merged cull's grid, whose cells the
  /// curve generator has already tested). Curve parts in blocked cells bound nothing and are
  /// not inserted (the curves' windows); its depth is the culling quadtree's.
  std::shared_ptr<BlockedCells> blocked_cells;
  /// Depth of the curve-culling quadtree over the box without a grid (0: 6).
  int cull_depth = 0;
};

/// A chart built by mapping an earlier chart of the same build (session 68, geneva68): the two
/// charts' boxes and axes are the same except one rotation axis, centred at 0 in `source` and
/// at pi in this chart (or the reverse), and that axis's part maps onto itself under the half
/// turn about its pivot exactly (half_turn_symmetry: `image`). The part placed at theta + pi is
/// then the part placed at theta as a set, its feature f lying where feature image(f) lies at
/// theta; at the same chart coordinates the two charts carry the same contact curves (the
/// same exact polynomials and validity), the curve of (g, f) here being source's curve of
/// (g, image(f)) (image is an involution), and the same overlap relation. The chart is the
/// source chart's arrangement, faces and contacts, its feature pairs read through the image:
/// no curves generated, culled, inserted or classified.
struct TwinChart {
  std::size_t source = no_index;   ///< the chart mapped (built before this one); no_index: built directly
  std::size_t part = 0;            ///< the symmetric part (model index: FeatureRef::part)
  std::vector<std::vector<HalfTurnImage>> image;   ///< per loop, per edge of `part`
  std::size_t x_index = 0, y_index = 0;   ///< this chart's layout indices and axes
  ChartAxis x, y;
};

/// Input of a pair's build (model-free, so that tests can feed synthetic curves).
struct PairInput {
  std::string first_part, second_part;   ///< names
  std::string x_part, y_part;            ///< names of the moving parts carrying the axes
  std::vector<std::string> part_names;   ///< model part names, for FeatureRef::part
  int dimension = 2;
  std::vector<ChartInput> charts;
  /// Instead of `charts`: chart `c` of `chart_count`, produced on demand (curves generated when
  /// the builder reaches it), so that only one chart's input curves are alive at a time.
  /// It adds to the `curve_statistics` and `seconds_curves` of the input it is given (the
  /// builder's own).
  std::size_t chart_count = 0;
  std::function<ChartInput(std::size_t, PairInput&)> make_chart;
  CurveStatistics curve_statistics;
  double seconds_curves = 0;
  bool complete = true;          ///< false: the charts are tiles of an operating region
  long length_unit_exponent = 0;   ///< lengths in units of 2^this mm (CSpace::length_unit_exponent)
  /// The model and the pair's axes (contact geometry queries); null for synthetic input.
  std::shared_ptr<const Model> model;
  PairAxes axes;
  std::size_t region_cells = 0;
  double seconds_region = 0;
  /// Per chart (empty, or one entry per chart): the charts built by mapping an earlier one
  /// (TwinChart; source no_index: built directly). Whole 2-D spaces with a model only.
  std::vector<TwinChart> twins;
};

/// What the oracle says of a face: outside the chart box (not classified), or the kind of
/// cell it belongs to.
enum class FaceKind { outside, free, blocked, touching };

/// One face (2-D) or interval (1-D) of a chart.
struct FaceData {
  FaceKind kind = FaceKind::outside;
  Rational sample_x, sample_y;    ///< strictly inside (2-D: once `sampled`; a cell's first face always is)
  bool sampled = false;
  std::size_t cell = no_index;
};

/// A non-vertical edge's exact evaluation data and its y at one interior rational abscissa.
struct EdgeData {
  std::size_t global = no_index;
  Rational sample_x;              ///< interior point (vertical edges: sample_y is rational)
  algebra::Real sample_y;
  /// vertical edges only (read only for them): the constant x. Unset elsewhere, so that the
  /// other edges construct no rationals for it.
  std::optional<algebra::Real> vertical_x;
  std::vector<std::size_t> curves;   ///< local curve indices
  /// Blocked on both sides, but the parts only touch along it (exact oracle at a rational
  /// point of the edge): a zero-clearance channel, EdgeRole::touching.
  bool touching = false;
};

struct ChartData {
  std::size_t x_index = 0, y_index = 0;   ///< indices into the layout's x and y charts
  ChartAxis x_axis, y_axis;
  raw::Box box;
  std::vector<std::size_t> curve_global;       ///< local curve -> feature pair index
  std::vector<IntegerPolynomial2> polynomials; ///< local curves (those that can be valid in the box)
  std::vector<std::vector<ValidityClause>> validity;   ///< per local curve
  /// per local curve: x-intervals outside which the curve certainly bounds nothing (empty: all)
  std::vector<std::vector<std::pair<Rational, Rational>>> windows;
  /// per local curve: the culling's surviving finest cells {x_lo, x_hi, y_lo, y_hi} (empty: no
  /// restriction), whose x-ranges are the windows; outside them the curve bounds nothing
  std::vector<std::vector<std::array<double, 4>>> cells;
  std::vector<algebra::IntervalPolynomial2> interval_polynomials;
  raw::Arrangement arrangement;                ///< 2-D topology (empty for 1-D)
  std::vector<FaceData> faces;
  std::vector<EdgeData> edges;
  std::vector<std::size_t> vertex_global;
  /// per vertex: an isolated touching configuration (blocked all around, the parts only
  /// touch there; exact oracle at the rational vertex)
  std::vector<char> touching_vertex;
  /// 1-D, per point on the chart's end (x_lo or x_hi) with blocked or free space on its inner
  /// side (a contact point on a seam or a motion limit): 1 the parts only touch there, 0 they
  /// overlap, 2 they are apart, -1 not decided (the exact oracle at the rational chart end); the
  /// seams are decided in `build` (session 29), point location at the chart's end answers it
  /// (session 32, hunt32b)
  std::vector<signed char> seam_relation;
  /// 1-D, per point: a contact point with free space on both sides where the parts touch (a
  /// grazing contact; the exact oracle at the rational point, session 30): point location
  /// answers the contact there, not the free cell it lies in
  std::vector<char> grazing_point;
  std::vector<Rational> rational_vertex_x;     ///< sorted: rational x of vertices (sampling avoids them)
  /// per vertex (2-D, set when the space is complete): certified doubles {x_lo, x_hi, y_hi} with
  /// x_lo <= x <= x_hi and y <= y_hi for the vertex's algebraic x and y (point location's
  /// vertex bounds, locate_prefilter.hpp); empty or of another size: not used
  std::vector<std::array<double, 3>> vertex_bounds;
  // 1-D: contact points (ascending) and the intervals between them (faces[i] is the interval
  // before point i; faces.back() after the last).
  std::vector<algebra::Real> points;
  std::vector<std::vector<std::size_t>> point_curves;
};

}  // namespace hipair::cspace

namespace hipair {

struct CSpace::Impl {
  std::string first_part, second_part, x_part, y_part;
  int dimension = 2;
  bool complete = true;   ///< false: only the operating region was built
  long length_unit_exponent = 0;   ///< CSpace::length_unit_exponent
  std::vector<cspace::ChartData> charts;
  std::vector<CSpaceChart> public_charts;
  std::vector<FeaturePair> feature_pairs;
  /// The public vertices. Their exact numbers (x, y, y_lower, y_upper, y_curve, y_branch,
  /// y_exact) of 2-D charts are copied from the raw arrangement's vertices when they are first
  /// read: all of them on the first vertex_numbers() (CSpace::vertices()), one vertex on the
  /// first vertex_number(index) (CSpace::vertex(id): the simulator reads a few vertices of a
  /// space; session 46). Nothing else reads them: a build whose vertices are never read makes no
  /// copy. A vertex's numbers are written once and never rewritten. Their topology (chart,
  /// edges, curves, flags) is written by the build.
  std::vector<CSpaceVertex> vertices;
  std::vector<CSpaceEdge> edges;
  /// The public cells. A cell's sample (sample_x, sample_y) is the sample of its first face (in
  /// chart, then face order: the face whose chart is sample_chart), taken by sample_face when
  /// the cells are first read (cell_samples(): CSpace::cells(), CSpace::cell(id)), not by the
  /// build: the build classifies most faces of a polygon pair without a sample. sample_face is
  /// deterministic (the same point whichever reader asks first; the arrangement is immutable
  /// after the build), so the samples are the ones the build took before. Everything else of a
  /// cell is written by the build.
  std::vector<CSpaceCell> cells;
  std::vector<std::pair<std::size_t, std::size_t>> edge_local;   ///< global edge -> (chart, local)
  std::vector<std::pair<std::size_t, std::size_t>> vertex_local;
  CSpaceStatistics statistics;
  /// The model and the pair's axes (contact_at, first_crossing's contact frames); null when
  /// the space was built from synthetic curves.
  std::shared_ptr<const Model> model;
  cspace::PairAxes axes;

  /// `vertices`, every vertex's numbers written first if they are not yet (thread-safe).
  const std::vector<CSpaceVertex>& vertex_numbers() const {
    if (!numbers.all.load(std::memory_order_acquire)) write_vertex_numbers();
    return vertices;
  }
  /// `vertices[index]` (index < vertices.size()), its numbers written first if they are not yet
  /// (only its own; thread-safe).
  const CSpaceVertex& vertex_number(std::size_t index) const {
    if (!numbers.all.load(std::memory_order_acquire)) {
      const std::atomic<unsigned char>* written = numbers.written.load(std::memory_order_acquire);
      if (!written || !written[index].load(std::memory_order_acquire)) write_vertex_number(index);
    }
    return vertices[index];
  }
  /// `cells`, every cell's sample written first if it is not yet (thread-safe).
  const std::vector<CSpaceCell>& cell_samples() const {
    if (!samples.all.load(std::memory_order_acquire)) write_cell_samples();
    return cells;
  }
  /// The samples of every cell, from its first face's (builder.cpp).
  void write_cell_samples() const;
  /// The numbers of every 2-D chart's public vertices not yet written, from their raw vertices
  /// (builder.cpp).
  void write_vertex_numbers() const;
  /// The numbers of public vertex `index` if not yet written (builder.cpp).
  void write_vertex_number(std::size_t index) const;
  /// The numbers' state: `all` once every vertex is written (release after the writes);
  /// `written[i]` once vertex i is (the array made on the first one-vertex write). Writers hold
  /// `mutex`.
  struct Numbers {
    std::mutex mutex;
    std::atomic<bool> all{false};
    std::atomic<std::atomic<unsigned char>*> written{nullptr};
    Numbers() = default;
    Numbers(const Numbers&) = delete;
    Numbers& operator=(const Numbers&) = delete;
    ~Numbers() { delete[] written.load(); }
  };
  mutable Numbers numbers;
  /// The cells' samples' state: `all` once every cell's sample is written (release after the
  /// writes, under `mutex`).
  struct Samples {
    std::mutex mutex;
    std::atomic<bool> all{false};
  };
  mutable Samples samples;
};

}  // namespace hipair

namespace hipair::cspace {

inline const CSpace::Impl& impl_of(const CSpace& space) { return implementation(space); }

/// How many public vertices' numbers this thread copied from raw vertices
/// (CSpace::Impl::write_vertex_numbers / write_vertex_number; tests: each vertex once, only the
/// ones read).
std::size_t& vertex_numbers_copied();

/// Builds the C-space from model-free input. \throws GeometryError, NumericError.
CSpace build_cspace(PairInput input, const CSpaceBuildOptions& options);

// ---------------------------------------------------------------- helpers shared by modules

/// Exact y of a non-vertical edge at rational x strictly inside its x-range.
algebra::Real edge_y_at(const ChartData& chart, std::size_t local_edge, const Rational& x);
/// The arc number (the index of the edge's root among the support's distinct real roots at x,
/// counted from below over the whole line) of a non-vertical edge at rational x.
int edge_arc_at(const ChartData& chart, std::size_t local_edge, const Rational& x);
/// A non-vertical edge whose support is quadratic in y at a rational x strictly inside the
/// edge's x-range, with two distinct real roots (b^2 - 4ac > 0 exactly): p(y) = a y^2 + b y + c
/// (the exact substitution), the edge's root `index` (0 or 1) and, where the double interval
/// filter separates the two roots, a certified enclosure `y` of the edge's ordinate. Point
/// location's filter (builder_locate.cpp): no root isolation for such edges.
struct QuadraticOrdinate {
  mpz_class a, b, c;
  int index = 0;
  bool enclosed = false;
  algebra::Interval y;
  /// The exact sign of (the edge's ordinate - v): -1, 0, +1.
  int compare(const Rational& v) const;
};
/// nullopt: a line, a vertical edge, a support not quadratic in y at x, a double or no real
/// root, an arc number other than 0 or 1 (the exact edge_y_at decides those).
std::optional<QuadraticOrdinate> quadratic_ordinate(const ChartData& chart, std::size_t local_edge, const Rational& x);
/// A certified double enclosure of the index-th (0 or 1, ascending) root of a y^2 + b y + c
/// with b^2 - 4ac > 0, separated from the other root's; nullopt where the double intervals
/// cannot separate them (or overflow).
std::optional<algebra::Interval> quadratic_root_enclosure(const mpz_class& a, const mpz_class& b, const mpz_class& c,
                                                          int index);
/// The culling quadtree (builder.cpp) keeps the rows in y of each curve's polynomials per row
/// of grid cells and evaluates the cells of a row from them (bound for bound the enclosures of
/// evaluating each cell alone: the same windows and cells). On by default; tests turn it off
/// to compare with the plain evaluation per cell.
std::atomic<bool>& culling_row_cache();
/// The culling quadtree leaves a cell the chart's grid has already answered blocked (the curve
/// generator's walk tests the even depths the quadtree does not) without evaluating its clauses
/// or children: every cell below it would be answered blocked (see CurveCuller::visit). The
/// same windows and cells. On by default; tests turn it off to compare.
std::atomic<bool>& culling_known_blocked();
/// The grids of a pair's boxes share their parts' poses where a part's axis and box side are
/// the same (SharedPoses; the operating-region flood's charts likewise). The same answers. On
/// by default; tests turn it off to compare.
std::atomic<bool>& shared_chart_poses();
/// The operating region's flood gathers each tile's disk pairs before its blocks' and gives a
/// kept tile's grid the list of the tile (or of the block holding it): the grid's cells without
/// a tested ancestor test those pairs instead of sweeping every disk (BlockedCells::enclose;
/// the same answers). On by default; tests turn it off to compare with the sweeps.
std::atomic<bool>& region_tile_lists();
/// A whole 2-D space's chart whose twin (the same chart with a half-turn-symmetric part's axis
/// centred at pi instead of 0) was built first is built by mapping it (TwinChart): the same
/// exact C-space, written through the twin's vertices and order. On by default; tests turn it
/// off to compare with the direct build.
std::atomic<bool>& mapped_twin_charts();
/// Queries (builder_locate.cpp).
Location locate_point(const CSpace::Impl& impl, const hipair::ChartPoint& q);
CertifiedValue evaluate_edge(const CSpace::Impl& impl, std::size_t edge, double x);
AlgebraicNumber evaluate_edge_exact(const CSpace::Impl& impl, std::size_t edge, const Rational& x);
Crossing first_crossing_in_chart(const CSpace::Impl& impl, const hipair::ChartPoint& from, const Rational& to_x,
                                 const Rational& to_y);
/// AlgebraicNumber from Real.
AlgebraicNumber to_public(const algebra::Real& r);
/// Converts a ChartAxis value interval (chart coordinates) to part coordinates, certified.
CertifiedRange to_coordinate_range(const ChartAxis& axis, double lo, double hi);

}  // namespace hipair::cspace
