// HIPAIR — the exact configuration space (C-space) of a fixed-axis pair of parts, as a
// CGAL-free cell structure: free and blocked cells, contact edges labelled with the feature
// pair that touches along them, contact-change vertices, exact point location, certified edge
// evaluation and a certified "first contact along a path" query.
//
// Coordinates. Each moving part contributes one axis: x for the pair's first moving part, y for
// the second. A rotation angle theta is carried in charts by t = tan((theta - c)/2) with chart
// centre c = 0 or c = pi, so that rational t gives an exact rational pose; a translation offset
// s (mm) is its own chart coordinate. A rotation without limits is covered by two charts that
// are glued along seams (theta = +-pi/2); cells are connected across seams, so a free channel
// that wraps around the torus (two rotations) or the cylinder (rotation x translation) is one
// cell. A pair with one fixed part has a 1-D C-space: cells are intervals, contacts are points.
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hipair {

/// Index value meaning "no such element".
inline constexpr std::size_t no_index = std::numeric_limits<std::size_t>::max();

/// An exact real algebraic number: `lower` when `exact`, otherwise the unique root of
/// `polynomial` (integer coefficients, ascending powers, square-free) in the open interval
/// (lower, upper).
struct AlgebraicNumber {
  std::vector<mpz_class> polynomial;
  Rational lower;
  Rational upper;
  bool exact = false;

  /// Nearest double (within one unit in the last place).
  double approximate() const;
  /// Exact text: "7/2", or "x^2 - 2 = 0, x in (1, 2)".
  std::string to_string(const std::string& variable = "x") const;
};

/// Closed interval of doubles that certainly contains the exact quantity.
struct CertifiedRange {
  double lower = 0;
  double upper = 0;
};

/// A double value with a certified bound: |exact - value| <= error.
struct CertifiedValue {
  double value = 0;
  double error = 0;
};

/// The kind of a C-space axis.
enum class AxisKind { rotation, translation };

/// One chart of the C-space: a box in chart coordinates.
struct CSpaceChart {
  AxisKind x_kind = AxisKind::rotation;
  AxisKind y_kind = AxisKind::rotation;   ///< meaningless for a 1-D space
  bool x_half_turn = false;               ///< rotation chart centred at theta = pi
  bool y_half_turn = false;
  Rational x_lo, x_hi, y_lo, y_hi;        ///< box in chart coordinates (t or mm)

  /// Chart x coordinate -> part coordinate (rad or mm), in double: theta = c + 2 atan(t).
  double x_to_coordinate(double chart_x) const;
  double y_to_coordinate(double chart_y) const;
};

/// How two features touch along a contact curve.
enum class ContactKind { vertex_segment, segment_vertex, vertex_arc, arc_vertex, arc_arc, arc_segment, segment_arc };

/// Short name of a contact kind: "vertex-segment", ...
std::string_view to_string(ContactKind kind);

// ------------------------------------------------------------------ typed ids (adaptor)

/// A strongly typed index into one of a CSpace's tables (cells(), edges(), vertices(),
/// feature_pairs()). Default-constructed ids are invalid (no_index).
template <class Tag>
struct Id {
  std::size_t value = no_index;
  constexpr Id() = default;
  constexpr explicit Id(std::size_t index) : value(index) {}
  constexpr bool valid() const noexcept { return value != no_index; }
  constexpr std::size_t index() const noexcept { return value; }
  friend constexpr bool operator==(Id, Id) = default;
  friend constexpr auto operator<=>(Id, Id) = default;
};
using CellId = Id<struct CellTag>;        ///< index into CSpace::cells()
using EdgeId = Id<struct EdgeTag>;        ///< index into CSpace::edges()
using VertexId = Id<struct VertexTag>;    ///< index into CSpace::vertices()
using FeatureId = Id<struct FeatureTag>;  ///< index into CSpace::feature_pairs()

/// The shape of a boundary feature.
enum class FeatureKind { vertex, segment, arc };

/// Which boundary feature of which part: the model's part index, the loop of the part, the
/// edge of the loop (for a vertex: the vertex is the source of that edge) and the kind.
struct FeatureIdentity {
  std::size_t part = no_index;   ///< index into Model::parts
  std::size_t loop = 0;
  std::size_t edge = 0;
  FeatureKind kind = FeatureKind::segment;
  friend bool operator==(const FeatureIdentity&, const FeatureIdentity&) = default;
};

/// The feature pair of a contact curve.
struct FeaturePair {
  std::string first_part;       ///< part names
  std::string second_part;
  std::string first_feature;    ///< edge label, or "loop 0 edge 3" / "vertex of loop 0 edge 3"
  std::string second_feature;
  ContactKind kind = ContactKind::vertex_segment;
  std::string label;            ///< "driver pin / wheel slot 2 wall" (a description for display)
  FeatureIdentity first;        ///< the first part's feature (exact identity)
  FeatureIdentity second;
  /// Sign of the pair's contact polynomial on the locally blocked (penetrating) side next to
  /// valid contact configurations: always -1 (docs/contact-kernels.md).
  int blocked_sign = -1;
};

/// Classes of C-space cells.
enum class CellKind {
  free,      ///< the parts are apart
  blocked,   ///< the parts overlap
  touching   ///< the parts touch throughout a 2-D region (degenerate: e.g. concentric arcs of
             ///< equal radius on parts turning about the same axis)
};

/// What an edge is.
enum class EdgeRole {
  contact,    ///< free on one side, blocked on the other: a real contact boundary
  spurious,   ///< lies on a contact curve but has the same class on both sides (the features
              ///< would touch outside their extent, or the curve passes through blocked space)
  seam,       ///< chart boundary glued to another chart (theta = +-pi/2), same class across
  limit,      ///< chart boundary at a motion limit or the end of a translation chart
  touching    ///< blocked on both sides, but the parts only touch along it (interiors disjoint,
              ///< decided by the exact overlap oracle): a zero-clearance channel, e.g. a pin in
              ///< a slot of exactly its diameter. `real`; it separates the cells on its sides.
};

/// A vertex of the C-space (per chart; a configuration on a seam appears once per chart).
struct CSpaceVertex {
  std::size_t chart = 0;
  AlgebraicNumber x;                   ///< chart coordinates, exact
  /// y exactly: the `y_branch`-th (0-based, ascending) distinct real root in y of
  /// y_curve(x, y) = 0 at this x; within the certified bounds [y_lower, y_upper], which isolate
  /// it among those roots. As a univariate algebraic number `y` when `y_exact` (x rational;
  /// or any vertex of a circle–segment chart, whose y_curve is y's minimal polynomial in y alone).
  /// A 1-D space has y = 0.
  std::vector<std::vector<mpz_class>> y_curve;
  int y_branch = 0;
  Rational y_lower, y_upper;
  bool y_exact = false;
  AlgebraicNumber y;
  std::vector<std::size_t> edges;      ///< incident edges
  std::vector<std::size_t> curves;     ///< feature pairs (contact curves) through the vertex
  bool contact_change = false;         ///< two or more distinct contact curves meet here
  bool on_chart_boundary = false;
  /// An isolated touching configuration: blocked space all around, but the parts only touch
  /// here (exact oracle), e.g. a square in a square hole of exactly its size. Vertices of real
  /// edges (contact or touching) are contact configurations anyway.
  bool touching = false;
};

/// An edge of the C-space: a piece of one or more contact curves (or of a chart boundary).
struct CSpaceEdge {
  std::size_t chart = 0;
  std::size_t source = no_index;       ///< vertex at the lexicographically smaller end
  std::size_t target = no_index;
  bool vertical = false;               ///< x constant along the edge
  std::vector<std::size_t> curves;     ///< feature pairs touching along the edge (overlaps: several)
  EdgeRole role = EdgeRole::spurious;
  std::size_t left_cell = no_index;    ///< cell on the left of source -> target (above, if not vertical)
  std::size_t right_cell = no_index;   ///< no_index: outside the C-space
  CertifiedRange x_chart, y_chart;     ///< certified extent in chart coordinates
  CertifiedRange x_coordinate, y_coordinate;   ///< certified extent in rad or mm

  /// The parts touch along it: free on one side and blocked on the other (contact edges, and
  /// seams/limits carrying a contact curve that separates classes), or a touching edge.
  bool real = false;
};

/// A cell: a connected component of free or of blocked space (across charts and seams).
struct CSpaceCell {
  CellKind kind = CellKind::free;
  std::vector<std::size_t> boundary;     ///< real edges bounding it
  std::vector<std::size_t> neighbours;   ///< cells across its real edges
  bool wraps_x = false;                  ///< a loop in the cell winds around the x rotation
  bool wraps_y = false;
  std::size_t faces = 0;                 ///< arrangement faces (or 1-D intervals) it consists of
  std::size_t sample_chart = 0;          ///< a configuration strictly inside the cell
  Rational sample_x, sample_y;
};

/// A configuration in the coordinates of one chart.
struct ChartPoint {
  std::size_t chart = 0;
  Rational x;
  Rational y;   ///< ignored for a 1-D space
};

/// A coordinate of one moving part, exact.
struct PartCoordinate {
  enum class Kind {
    half_angle_tangent,   ///< rotation: value = tan(theta/2)
    half_turn,            ///< rotation: theta = pi (value ignored)
    offset                ///< translation: value = s (mm)
  };
  Kind kind = Kind::half_angle_tangent;
  Rational value;
};

/// Result of exact point location; in a 1-D space every contact point is a `vertex`.
struct Location {
  /// `touching`: inside a touching cell. `edge` / `vertex`: on contact space; the parts touch
  /// there (`cell` no_index) on a real edge (free/blocked boundary or EdgeRole::touching), at its
  /// vertices, at CSpaceVertex::touching, and in 1-D between different cells, on a chart's end,
  /// or at a rational grazing point (free both sides, oracle: touching; not flagged touching);
  /// otherwise on a spurious piece (or an undecided irrational grazing point) inside `cell`.
  enum class Kind { free, blocked, edge, vertex, outside, touching };
  Kind kind = Kind::outside;
  std::size_t cell = no_index;     ///< free / blocked / touching (and edges or vertices inside one cell)
  std::size_t edge = no_index;     ///< on the relative interior of this edge
  std::size_t vertex = no_index;
  std::size_t chart = no_index;
};

/// First contact crossing along a straight path.
struct Crossing {
  bool found = false;
  Rational parameter_lower;        ///< the crossing is at u in [lower, upper] (equal when exact)
  Rational parameter_upper;
  std::size_t edge = no_index;     ///< the real edge crossed (no_index at a vertex)
  std::size_t vertex = no_index;   ///< when the path passes through a vertex
  std::size_t cell_left = no_index;     ///< cell just before the crossing
  std::size_t cell_entered = no_index;  ///< cell just after (same as cell_left for a grazing touch)
  bool grazing = false;            ///< the path touches contact space and returns to the same cell
};

// ------------------------------------------------------------------ adaptor queries
// (src/cspace/cspace_queries.cpp; contact mathematics in kernels/contact_geometry.hpp)

/// Which side of an edge (see CSpaceEdge::left_cell) is blocked space.
enum class BlockedSide { none, left, right };

/// A feature pair touching at a configuration: the world contact point and the contact normal
/// (unit, from the pair's first part into the second: the direction in which the first part
/// pushes the second; kernels/contact_geometry.hpp).
struct Contact {
  FeatureId feature;
  /// True when `point` and `normal_direction` are exact (the configuration is rational).
  bool exact = false;
  std::array<Rational, 2> point;              ///< world contact point (mm), when exact
  std::array<Rational, 2> normal_direction;   ///< normal, not normalised, when exact
  std::array<CertifiedRange, 2> point_range;  ///< certified enclosure of the point (always)
  std::array<CertifiedRange, 2> normal;       ///< certified enclosure of the unit normal
};

/// Derivatives of a contact edge's curve y(x) at an abscissa, by implicit differentiation of
/// the edge's exact polynomial F: y' = -F_x / F_y, y'' = -(F_xx + 2 F_xy y' + F_yy y'^2) / F_y.
struct EdgeDerivatives {
  AlgebraicNumber y;                  ///< the ordinate, exact
  CertifiedRange dy, d2y;             ///< in chart coordinates
  /// The same in part coordinates (rad or mm): d(y part)/d(x part) — for a driven pair the
  /// velocity ratio — and its derivative (the acceleration ratio).
  CertifiedRange coordinate_dy, coordinate_d2y;
};

/// The motion of one part along a path parameter u: a polynomial in u (ascending
/// coefficients) giving its angle (rad), its offset (mm), or the half-angle tangent
/// t = tan(theta/2) of its angle (a curve in chart coordinates, e.g. a gear ratio between
/// two tangents). Angles wrap around: the path continues across the theta = +-pi/2 seams.
struct AxisPath {
  enum class Kind { angle, offset, half_tangent };
  Kind kind = Kind::angle;
  std::vector<Rational> coefficients;   ///< empty: constant 0
};

/// A motion of the pair for u in [u_begin, u_end]: x for the space's x part, y for its y part
/// (ignored for a 1-D space).
struct MotionPath {
  AxisPath x;
  AxisPath y;
  Rational u_begin = 0;
  Rational u_end = 1;
};

/// Outcome of a first-crossing query along a motion.
enum class CrossingStatus {
  none,                ///< the motion stays in its starting free cell
  crossing,            ///< it reaches contact space at u in [u_lower, u_upper]
  starts_in_contact,   ///< it does not start in a free cell (contact or overlap at u_begin)
  outside_region       ///< it may leave the built space at u in [u_lower, u_upper] first
};

/// First contact along a motion (in the manner of Box2D's time-of-impact output).
struct MotionCrossing {
  CrossingStatus status = CrossingStatus::none;
  /// Certified bounds: the motion is in its starting free cell on [u_begin, u_lower) and
  /// reaches contact space (or leaves the built space) at some u in [u_lower, u_upper].
  Rational u_lower, u_upper;
  /// The motion comes within the resolution of a contact curve (a touch, or a pass closer than
  /// the resolution) but is not certified to enter another cell: reported, so that no contact
  /// is missed. False when the cell at u_upper is certified to differ from the start's.
  bool grazing = false;
  EdgeId edge;                          ///< a real edge crossed (when identified)
  std::vector<FeatureId> features;      ///< feature pairs that may touch there
  CellId cell_left;                     ///< the starting free cell
  CellId cell_entered;                  ///< the cell at u_upper (when certified)
  std::size_t chart = no_index;         ///< a chart holding the crossing
  std::array<CertifiedRange, 2> chart_point;   ///< chart coordinates of the crossing, certified
  std::array<CertifiedRange, 2> point;  ///< world contact point of features.front(), certified
  std::array<CertifiedRange, 2> normal; ///< its unit normal (first part into second), certified
};

/// Resolution of the first-crossing query: the bounds [u_lower, u_upper] are at most
/// (u_end - u_begin) / 2^resolution_bits wide.
struct CrossingOptions {
  unsigned resolution_bits = 44;
};

/// The axis of a slice: `x` fixes the chart abscissa, `y` the ordinate.
enum class SliceAxis { x, y };

/// A 1-D slice of one chart: the other coordinate's range cut into intervals of constant cell.
struct Slice {
  std::size_t chart = 0;
  SliceAxis axis = SliceAxis::x;
  Rational value;                       ///< the fixed coordinate
  Rational lower, upper;                ///< the chart box along the free coordinate
  /// Boundaries between consecutive intervals (exact), with the feature pairs whose curves
  /// pass there.
  struct Point {
    AlgebraicNumber at;
    std::vector<FeatureId> features;
  };
  struct Interval {
    CellId cell;
    CellKind kind = CellKind::free;
    Rational sample;                    ///< a coordinate strictly inside the interval
  };
  std::vector<Point> points;
  std::vector<Interval> intervals;      ///< intervals.size() == points.size() + 1
};

/// An edge sampled for drawing: points on the edge (chart coordinates), each within `error`
/// of the exact curve. Labelled approximate: the chords between them are not certified.
struct EdgePolyline {
  std::vector<std::array<double, 2>> points;
  double error = 0;
  bool approximate = true;
};

/// A face of one chart (2-D: a face of the chart's arrangement inside the chart box; 1-D: an
/// interval between consecutive contact points), for drawing and for walking the structure.
/// Cells are unions of faces across charts and seams.
struct CSpaceFace {
  std::size_t chart = 0;
  CellKind kind = CellKind::free;
  /// False for a face of an operating-region chart outside the built tiles' cells (not
  /// classified); `cell` is then invalid.
  bool classified = true;
  CellId cell;
  /// 2-D: the connected components of the face's boundary, each a cycle of edges in order with
  /// the face on the left: (edge, true) runs source -> target, (edge, false) target -> source.
  std::vector<std::vector<std::pair<EdgeId, bool>>> boundary;
  /// 1-D: the interval's end vertices, lower and upper (invalid: the chart box's end).
  VertexId lower, upper;
};

class CSpace;
/// The library's own access to a CSpace's internals (src/cspace/cspace_access.hpp; not part
/// of the API: consumers use the queries below).
struct CSpaceAccess;

/// The build of one pair by CSpace::build_pairs.
struct PairBuild {
  enum class Status { built, failed };
  std::string first_part, second_part;
  Status status = Status::failed;
  std::string error;                    ///< the failure's message (status failed)
  std::shared_ptr<const CSpace> space;   ///< the built space (status built)
};

/// Counts and times reported by --stats.
struct CSpaceStatistics {
  std::size_t feature_pairs_considered = 0;
  std::size_t feature_pairs_culled = 0;
  std::size_t curves = 0;
  std::size_t charts = 0;
  std::size_t pieces_inserted = 0;
  std::size_t vertices = 0;
  std::size_t edges = 0;
  std::size_t faces = 0;
  std::size_t cells = 0;
  std::size_t contact_edges = 0;
  std::size_t touching_edges = 0;      ///< zero-clearance channels (EdgeRole::touching)
  std::size_t touching_vertices = 0;   ///< isolated touching configurations
  /// Edges on two or more coincident contact curves between blocked faces with no rational
  /// point found (they stay spurious, unchecked by the oracle; see docs/cspace.md).
  std::size_t touching_undecided = 0;
  /// Charts (or tiles) whose curves are all lines and circles (translating pairs), built on
  /// CGAL's circle–segment traits instead of the algebraic ones; their vertices all have exact
  /// coordinates (CSpaceVertex::y_exact).
  std::size_t circle_segment_charts = 0;
  /// Charts (or tiles) whose curves all have degree <= 2 in y, built on the filtered quadratic
  /// traits (CSpaceBuildOptions::quadratic_traits) instead of CGAL's algebraic traits.
  std::size_t quadratic_charts = 0;
  std::size_t region_tiles = 0;       ///< operating region: tiles built (0: whole space built)
  std::size_t region_cells = 0;       ///< operating region: flooded quadtree cells
  double seconds_region = 0;          ///< operating region: flood over certified-blocked cells
  double seconds_curves = 0;          ///< contact-curve generation (kernels)
  double seconds_culling = 0;         ///< curve windows: validity and certainly-blocked quadtree
  double seconds_clipping = 0;        ///< CGAL curve analysis, x-monotone split, clipping
  double seconds_arrangement = 0;     ///< CGAL insertion
  double seconds_export = 0;          ///< topology export from CGAL
  double seconds_labelling = 0;       ///< feature pairs on edges
  double seconds_classification = 0;  ///< sample points + overlap oracle
  double seconds_cells = 0;           ///< seams, cells, adjacency
  double seconds_total = 0;
};

/// One report of a pair's C-space build (CSpaceBuildOptions::progress). A build reports, in
/// order: each chart (or operating-region tile) when its build starts (Stage::chart), the exact
/// classification of each 2-D chart's edges and vertices as it goes (Stage::classification,
/// from done = 0), and its end once the cells are formed (Stage::done).
struct CSpaceBuildProgress {
  enum class Stage { chart, classification, done };
  Stage stage = Stage::chart;
  std::string_view first_part, second_part;   ///< the pair (valid during the call only)
  std::size_t chart = 0;                      ///< chart or tile from 1 (chart, classification)
  std::size_t charts = 0;                     ///< the pair's charts or tiles
  bool tiles = false;                         ///< operating region: tiles, not whole charts
  std::size_t done = 0, total = 0;            ///< classification: the chart's edges and vertices decided
  std::size_t coefficient_bits = 0;           ///< classification: the chart's widest polynomial coefficient
  /// The pair's build done, in [0, 1], never decreasing: work units (the charts built, then
  /// each 2-D chart classified, then the cells), the current chart's classification counted by
  /// its share done/total; exactly 1 at Stage::done.
  double fraction = 0;
  /// The line stderr_progress() shows for this report: "hipair: A:B chart k/n" ("tile k/n"),
  /// "hipair: A:B classifying chart k/n: P%" (with the reason over 300 coefficient bits);
  /// empty at Stage::done.
  std::string text() const;
};

/// Receives a build's reports (CSpaceBuildProgress). build_all and build_pairs build pairs on
/// worker threads but call it under one lock: never concurrently, each pair's reports in order.
using CSpaceProgress = std::function<void(const CSpaceBuildProgress&)>;

/// The reporter `hipair` passes on a terminal: each report's text() on one stderr line redrawn
/// in place ("\r"), a line break after the last chart's line, classification lines at most
/// four a second, the line wiped at Stage::done. (Callers decide whether stderr is a terminal.)
CSpaceProgress stderr_progress();

/// Options of a C-space build.
struct CSpaceBuildOptions {
  bool keep_arrangements = false;      ///< keep the raw CGAL arrangements (see hipair/cgal/)
  bool aggregated_insertion = false;   ///< CGAL's aggregated (sweep) insertion instead of incremental
  unsigned threads = 0;                ///< build_all: worker threads (0: hardware concurrency)
  /// Called with the build's progress (CSpaceBuildProgress); empty: none. stderr_progress()
  /// is the terminal's reporter.
  CSpaceProgress progress;
  /// Build only the operating region instead of the whole space: the connected set of
  /// configurations not certified blocked that contains the seed (the free channel the
  /// mechanism works in, with a margin), covered by tiles of each chart. Everything inside the
  /// built tiles is exact; configurations outside them locate as `outside`; edges on the
  /// region's border have role `limit`. A gear pair with z1 and z2 teeth has O(z1 z2) contact
  /// curves on the whole torus but O(z1 + z2) along one channel. 2-D spaces only (a 1-D space
  /// is always built whole).
  bool operating_region = false;
  /// Tiles per chart axis in operating-region mode (2 to 128); 0: automatic, about one per 8
  /// boundary edges of the pair's two parts (4 to 128), so that a tile spans about a tooth.
  unsigned region_tiles = 0;
  /// Seed of the operating region: coordinates of the x and y parts (rad or mm). Empty: the
  /// model's initial configuration. It only selects the channel, so double is enough.
  std::optional<std::array<double, 2>> region_seed;
  /// Faces on the blocked side of a contact edge are classified from the contact's blocked
  /// side, the others by the exact overlap oracle at a sample point. true: the oracle also
  /// checks every face classified from a blocked side, and a disagreement is a GeometryError;
  /// every face's sample is also checked to lie inside its face (crossing parity of a vertical
  /// ray with the face's own boundary cycles, exact), independently of how it was found
  /// (for tests; slower).
  bool check_face_classification = false;
  /// A fixed-axis pair with a length coordinate (a translating part) whose lengths lie beyond
  /// about 7e305 mm (or, with arcs, all below about 9e-302 mm) has coordinates outside the
  /// doubles' range and is refused (a GeometryError) unless this is true: it is then built on
  /// the model scaled by an exact power of two 2^-L that brings its largest length near 2^6 mm
  /// (the same C-space, lengths in other units: contact is homogeneous in lengths), and
  /// CSpace::length_unit_exponent() is L: every length-valued member of the space (translation
  /// charts' boxes and coordinates, vertices, edges, samples, evaluate, edge_polyline, contact
  /// points, ChartPoint and PartCoordinate offsets given to its queries) is then in units of
  /// 2^L mm, exact values exactly (x mm = x' * 2^L), doubles finite. `hipair cspace` sets it
  /// and maps every exact number of its JSON back to mm (docs/cspace.md). Not with
  /// operating_region, nor for a pair far from the origin for its size (still refused);
  /// pin-slot and 3-DOF pairs are still refused.
  bool normalise_lengths = false;
  /// Translating polygon pairs take a dedicated front end (the reduced convolution's segments
  /// written from the vertices, each edge's line carried through CGAL from its input segment,
  /// no interval culling quadtree). false: the general path of every other pair. The C-space is
  /// the same either way (for tests that compare the two).
  bool polygon_front_end = true;
  /// The certified blocked-space cull (feature pairs whose contacts all lie in certainly
  /// blocked cells are never built, and curve parts there are not inserted). false: every
  /// feature pair that can touch is built and inserted whole; the C-space is the same, with
  /// more spurious edges (for tests that compare the two; slower).
  bool cull_blocked_space = true;
  /// Charts whose contact curves all have degree <= 2 in y take the filtered quadratic traits
  /// (exact, without CGAL's curve analysis; see docs/cspace.md) instead of CGAL's algebraic
  /// traits; charts it does not decide fall back to the algebraic traits. Not with
  /// keep_arrangements (the raw CGAL access is for algebraic-traits arrangements).
  bool quadratic_traits = true;
  /// The quadratic traits declines charts with a coefficient above this many bits (the
  /// algebraic traits takes them). Since its Descartes root isolation (docs/performance.md,
  /// session 10) the spur gears (247-653 bits) build on the quadratic traits in 0.52-0.95 of
  /// the algebraic traits' CPU time with the same C-spaces, so the default takes them (it was
  /// 200 in session 9, which kept them on the algebraic traits).
  std::size_t quadratic_max_coefficient_bits = 1024;
};

/// The exact C-space of one pair. Value semantics: copies share the immutable structure.
/// All queries are const and may be called from several threads at once.
class CSpace {
 public:
  struct Impl;

  /// Builds the C-space of the pair (first_part, second_part) of `model`.
  /// \throws ModelError for unknown part names, GeometryError for pairs that are not
  /// fixed-axis pairs (planar or pin-slot motion) or input CGAL cannot handle.
  static CSpace build(const Model& model, std::string_view first_part, std::string_view second_part,
                      const CSpaceBuildOptions& options = {});

  /// Builds every pair of `model.pairs` that is a fixed-axis pair with at least one moving
  /// part, in parallel. Pairs of other kinds are skipped.
  static std::vector<CSpace> build_all(const Model& model, const CSpaceBuildOptions& options = {});
  /// The same pairs, built in parallel, with a status per pair: every pair that builds is kept
  /// when others fail. build_all() is this, throwing the first failure after all have run.
  static std::vector<PairBuild> build_pairs(const Model& model, const CSpaceBuildOptions& options = {});

  /// 1 (one part fixed) or 2.
  int dimension() const;
  /// Pair's part names in axis order: x belongs to the first moving part.
  const std::string& first_part() const;
  const std::string& second_part() const;
  /// Names of the parts carrying the x and y axes ("" for none).
  const std::string& x_part() const;
  const std::string& y_part() const;

  const std::vector<CSpaceChart>& charts() const;
  const std::vector<FeaturePair>& feature_pairs() const;
  const std::vector<CSpaceVertex>& vertices() const;
  const std::vector<CSpaceEdge>& edges() const;
  const std::vector<CSpaceCell>& cells() const;
  const CSpaceStatistics& statistics() const;
  /// False when only the operating region was built (CSpaceBuildOptions::operating_region):
  /// cells touching the region's border may continue outside it.
  bool complete() const;
  /// 0, or L when the space was built on the model scaled by 2^-L
  /// (CSpaceBuildOptions::normalise_lengths): its length-valued members are in units of 2^L mm.
  long length_unit_exponent() const;

  /// The chart point of a configuration given per moving part (exact), choosing the chart
  /// whose box contains it; nullopt when outside every chart (beyond a motion limit).
  std::optional<ChartPoint> to_chart(const PartCoordinate& x, const PartCoordinate& y = {}) const;

  /// Exact point location: free cell, blocked cell, on an edge, at a vertex, or outside.
  /// \pre point.chart < charts().size().
  Location locate(const ChartPoint& point) const;
  /// Exact point location of a configuration per moving part.
  Location locate(const PartCoordinate& x, const PartCoordinate& y = {}) const;

  /// The edge's curve at chart abscissa x (the ordinate y(x); for a vertical edge, the edge's
  /// constant x), evaluated in double with a certified error bound.
  /// \pre x within the edge's x extent. \throws GeometryError otherwise.
  CertifiedValue evaluate(std::size_t edge, double x) const;
  /// The same, exact: the edge's ordinate at a rational abscissa as an algebraic number.
  AlgebraicNumber evaluate_exact(std::size_t edge, const Rational& x) const;

  /// The exact polynomial whose zero set contains the edge, in chart coordinates x, y.
  std::string edge_polynomial(std::size_t edge) const;
  /// Its integer coefficients: c[i][j] of x^i y^j.
  const std::vector<std::vector<mpz_class>>& edge_polynomial_coefficients(std::size_t edge) const;

  /// The first point where the straight path from `from` to (to_x, to_y) (coordinates of
  /// from's chart) enters contact space on a real edge (a contact edge, or a vertex of one).
  /// Exact: the path parameter u in [0, 1] is isolated by rational bounds; crossings of
  /// spurious edges are skipped; a path that starts in contact space reports u = 0. The path may
  /// run through several boxes with the same coordinates (the tiles of an operating region,
  /// the charts of a limited rotation); it may not cross to a chart with other coordinates
  /// (split it at the chart side). \throws GeometryError when the path leaves the built space.
  Crossing first_crossing(const ChartPoint& from, const Rational& to_x, const Rational& to_y = 0) const;

  // ---------------------------------------------------------------- adaptor queries
  // (typed ids; see the block "adaptor queries" above)

  const CSpaceCell& cell(CellId id) const;
  const CSpaceEdge& edge(EdgeId id) const;
  const CSpaceVertex& vertex(VertexId id) const;
  const FeaturePair& feature_pair(FeatureId id) const;
  /// Which side of the edge is blocked (none for spurious edges, seams and limits).
  BlockedSide blocked_side(EdgeId id) const;

  /// The feature pairs touching at a configuration (contact polynomial zero and contact valid,
  /// decided exactly), with exact contact points and normals.
  std::vector<Contact> contact_at(const ChartPoint& point) const;
  std::vector<Contact> contact_at(const PartCoordinate& x, const PartCoordinate& y = {}) const;
  /// The contact frame of feature pair `feature` at a configuration on or next to its contact
  /// curve: the kernels' contact point and normal (kernels/contact_geometry.hpp) evaluated there
  /// whether or not the features touch exactly (e.g. a state moved off contact space by a few
  /// rounding units). Certified enclosures of the point and unit normal for the configuration
  /// given; `exact` is false. nullopt where the frame is undefined (a degenerate configuration).
  /// \throws GeometryError when the configuration is outside every chart.
  std::optional<Contact> contact_frame(FeatureId feature, const PartCoordinate& x, const PartCoordinate& y = {}) const;

  /// y, y', y'' of a non-vertical edge at a rational abscissa within its x extent.
  /// \throws GeometryError for a vertical edge, an abscissa outside the edge, or a singular
  /// point of the curve (F_y = 0).
  EdgeDerivatives derivatives(EdgeId edge, const Rational& x) const;

  /// Exact comparison of a chart ordinate with the ordinate of a vertex (in the vertex's
  /// chart): the sign of y - (the vertex's exact y), -1, 0 or +1. With it a vertical edge (x
  /// constant) is ended exactly at its end vertices, as derivatives() ends the others.
  /// \throws GeometryError for a 1-D space, or where the vertex's y_curve does not change sign
  /// across the ends of its isolating interval [y_lower, y_upper] (a root of even multiplicity,
  /// a fibre vanishing there), which this comparison does not resolve.
  int compare_ordinate(VertexId vertex, const Rational& y) const;

  /// The first point where the motion reaches contact space (a real edge or vertex), across
  /// charts, seams and tiles. Never misses a crossing: every u it passes over is certified
  /// free by certified interval exclusion of every contact curve (with its validity), and the
  /// cells are decided by exact point location.
  MotionCrossing first_crossing(const MotionPath& path, const CrossingOptions& options = {}) const;

  /// The 1-D slices through every chart whose box contains `value` on `axis`.
  std::vector<Slice> slice(SliceAxis axis, const Rational& value) const;

  /// The edge sampled at `samples` (>= 2) abscissae for drawing (labelled approximate).
  EdgePolyline edge_polyline(EdgeId edge, std::size_t samples = 32) const;

  /// The faces of chart `chart` inside its box (2-D), or its intervals in ascending order (1-D).
  /// \throws GeometryError for a chart index out of range.
  std::vector<CSpaceFace> faces(std::size_t chart) const;

  /// The exact contact polynomial of feature pair `feature` in the coordinates of chart
  /// `chart` (c[i][j] of x^i y^j; 1-D: c[i][0] of x^i): its zero set holds every configuration
  /// of the chart where the pair touches. Empty when the pair's curve was culled from the chart
  /// (the features cannot touch inside its box).
  std::vector<std::vector<mpz_class>> curve_polynomial(std::size_t chart, FeatureId feature) const;

 private:
  std::shared_ptr<const Impl> impl_;
  friend struct CSpaceAccess;
};

}  // namespace hipair
