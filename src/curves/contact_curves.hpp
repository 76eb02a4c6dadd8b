// Contract between the contact kernels (kernels/, src/curves/contact_curves.cpp) and the
// C-space builder (src/cspace/builder*.cpp). Internal: not part of the public API.
//
// Configuration space of a fixed-axis pair: one axis per moving part (x: first part of the
// pair, y: second part). A fixed part contributes no axis (the space is then 1-D).
//
// Chart coordinates. A rotation angle theta is carried by t = tan((theta - c)/2) with chart
// centre c = 0 (half_turn == false, covers |theta| <= pi/2 for t in [-1, 1]) or c = pi
// (half_turn == true). Then cos(theta - c) = (1-t^2)/(1+t^2), sin(theta - c) = 2t/(1+t^2)
// exactly, and rotating by pi negates both. A translation offset s (mm) is its own chart
// coordinate. Contact polynomials are cleared of the positive denominators (1+t^2), so
// their zero sets are the contact curves of the chart.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <gmpxx.h>

#include "algebra/polynomial.hpp"
#include "core/thread_switch.hpp"
#include "kernels/contact_table.hpp"
#include "kernels/interval.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <memory>
#include <utility>
#include <vector>

namespace hipair::cspace {

class BlockedCells;   // oracle/blocked_tester.hpp

/// The blocked-space cull's memo of the cell being visited (a part's posed cores and feature
/// boxes computed once per cell and shared by its tests, slots stamped with the cell): on by
/// default; off on this thread, every test computes the poses it reads afresh (tests compare
/// the selections; the values are the same functions of the cell's axis intervals).
struct CellPoseMemoTag {};
inline bool& cell_pose_memo_switch() { return thread_switch<CellPoseMemoTag>(); }

/// One chart axis of a pair's C-space.
struct ChartAxis {
  using Kind = AxisKind;    ///< the public axis kind (hipair/cspace.hpp)
  Kind kind = Kind::rotation;
  bool half_turn = false;   ///< rotation: chart centred at theta = pi instead of 0
  Rational lo;              ///< chart box in chart coordinates (t or s)
  Rational hi;
};

/// The charts covering a pair's C-space and how they glue (seams) — produced by
/// chart_layout(); a rotation without limits gets two charts t in [-1,1] around 0 and pi.
struct ChartLayout {
  std::vector<ChartAxis> x_charts;   ///< first moving part
  std::vector<ChartAxis> y_charts;   ///< second moving part (empty for a 1-D space)
};

/// A boundary feature of a part, in the model's loops.
struct FeatureRef {
  using Kind = FeatureKind;   ///< the public feature kind (hipair/cspace.hpp)
  std::size_t part = 0;
  std::size_t loop = 0;
  std::size_t edge = 0;   ///< for a vertex: the vertex is the source of this edge
  Kind kind = Kind::segment;
  friend bool operator==(const FeatureRef&, const FeatureRef&) = default;
};

/// How two features touch along a curve: the kernels' contact table (one spelling,
/// kernels/contact_table.hpp); the public spelling is ContactKind (same order).
using ContactType = kernels::ContactType;

/// The public spelling of a contact type.
ContactKind public_kind(ContactType type) noexcept;

/// A contact curve of a pair in one chart: the zero set of `polynomial` restricted to the
/// chart box contains every configuration where `first` touches `second` (a superset: the
/// validity range — contact point within both features — is an extra restriction that the
/// builder may use to clip; correctness of free/blocked never depends on it).
///
/// Degenerate case: when the two features touch at every configuration of the chart (e.g. a
/// shaft in a fixed bearing of the same radius, concentric with the pivot), `polynomial` is
/// identically zero (is_zero()); such a curve bounds no region and the builder may skip it.
struct ContactCurve;

/// One clause of a contact's validity: atoms[0] >= 0, or, with two atoms,
/// atoms[0] >= 0 || atoms[1] >= 0 (chart coordinates, same variables as the curve).
struct ValidityClause {
  std::vector<IntegerPolynomial2> atoms;
};

/// See the comment above the forward declaration.
struct ContactCurve {
  FeatureRef first;
  FeatureRef second;
  ContactType type = ContactType::vertex_segment;
  IntegerPolynomial2 polynomial;
  std::string label;  ///< "driver pin / wheel slot 2 wall" for people
  /// Added by the kernels: sign of `polynomial` on the locally blocked (penetrating) side near
  /// valid contact points: always -1 (0 is reserved for "unknown"). Squared forms, used when a
  /// product of radii or a radius times a segment length is irrational, also vanish on a
  /// spurious branch; their `validity` has a clause that excludes it.
  int blocked_sign = -1;
  /// Added by the kernels: the contact point lies within both features iff every clause
  /// holds (optional for the builder: clipping only; see ValidityClause).
  std::vector<ValidityClause> validity;
  /// Added by the kernels, vertex contacts only (optional for the builder: culling only):
  /// corner-entry atoms. Wherever one atom is < 0 and every validity clause holds strictly
  /// (some atom > 0), a configuration on the curve has the vertex strictly inside the other
  /// feature with one of the vertex's edge tangents pointing into the other part's material,
  /// so the parts' interiors overlap there: the curve lies in the interior of blocked space
  /// and bounds nothing (the argument at corner_entry_atoms in contact_curves.cpp).
  std::vector<IntegerPolynomial2> corner_entry;
};

/// A configuration of the pair in chart coordinates of a given chart.
struct ChartPoint {
  Rational x;
  Rational y;   ///< ignored for a 1-D space
};

/// Exact relation of two posed parts.
enum class Overlap {
  apart,       ///< closed parts disjoint
  touching,    ///< boundaries meet, interiors disjoint
  overlapping  ///< interiors intersect
};

/// Counts reported by --stats.
struct CurveStatistics {
  std::size_t feature_pairs_considered = 0;
  std::size_t feature_pairs_culled = 0;   ///< swept annuli/strips disjoint: can never touch
  std::size_t curves = 0;                 ///< non-trivial contact polynomials emitted
  std::size_t identically_zero = 0;       ///< added: degenerate curves emitted (contact everywhere)
  std::size_t reflex_vertices_skipped = 0;  ///< added: strictly reflex vertices never touch alone
  /// added: pairs whose every possible contact configuration in the chart is certified
  /// blocked (two inscribed disks of the parts overlap there); their curves would lie inside
  /// blocked space and bound no free region
  std::size_t feature_pairs_in_blocked_space = 0;
};

/// The moving parts of a pair in axis order: `x_part` moves along x, `y_part` along y (or
/// nullopt for a 1-D space). Parts with more than one degree of freedom are rejected with a
/// GeometryError (planar and pin_slot pairs are not fixed-axis pairs).
struct PairAxes {
  std::size_t first = 0;               ///< model part index of the pair's first part
  std::size_t second = 0;
  bool first_moves = false;            ///< first part has the x axis (else it is fixed)
  bool second_moves = false;           ///< second part has the next axis
  int dimension() const noexcept { return int(first_moves) + int(second_moves); }
};

PairAxes pair_axes(const Model& model, std::size_t first, std::size_t second);

/// Charts covering the pair's C-space: rotations without limits get two charts
/// (t in [-1,1] around 0 and around pi); rotations with limits get the charts their range
/// needs, clipped; translations get one chart [lo, hi] from the limits, or, without limits,
/// the offsets outside of which the parts can never touch (widened by a margin, so that the
/// chart edge lies in free space).
ChartLayout chart_layout(const Model& model, const PairAxes& axes);

/// All contact curves of the pair in the chart (x, y) (y ignored for a 1-D space).
/// Feature pairs that can never touch are culled before any exact work, and so are pairs that
/// can touch only at configurations certified blocked (inside the C-obstacle): every
/// configuration where the parts touch without overlapping lies on an emitted curve.
std::vector<ContactCurve> generate_contact_curves(const Model& model, const PairAxes& axes,
                                                  const ChartAxis& x, const ChartAxis& y,
                                                  CurveStatistics* statistics = nullptr);

/// Added by the kernels: options of curve generation (tests switch the blocked-space cull off).
struct CurveOptions {
  bool cull_blocked_space = true;
  /// The C-space builder's merged cull: the blocked test is the caller's grid of each chart
  /// box (BlockedCells, given to every generate() call), not the parts' inscribed disks,
  /// which are then not computed.
  bool blocked_grid = false;
  /// Translating polygon pairs without the blocked-space cull: the pairs of the reduced
  /// convolution by an angular walk and each curve written from the vertices (the same curves,
  /// in the same order, as the general path; false: the general path, for tests).
  bool polygon_front_end = true;
};

/// generate_contact_curves with options.
std::vector<ContactCurve> generate_contact_curves(const Model& model, const PairAxes& axes,
                                                  const ChartAxis& x, const ChartAxis& y,
                                                  CurveStatistics* statistics,
                                                  const CurveOptions& options);

/// Contact-curve generation for one pair with the per-part data (features, their bounding
/// disks, the parts' inscribed disks) computed once and shared by every chart or tile:
/// generate(x, y) equals generate_contact_curves(model, axes, x, y) curve for curve. The model
/// must outlive the generator. generate() is const and may run on several threads.
class CurveGenerator {
 public:
  CurveGenerator(const Model& model, const PairAxes& axes, const CurveOptions& options = {});
  ~CurveGenerator();
  CurveGenerator(const CurveGenerator&) = delete;
  CurveGenerator& operator=(const CurveGenerator&) = delete;
  /// `grid`: the chart box's certainly-blocked cells (required with CurveOptions::blocked_grid,
  /// else ignored): a feature pair is kept only if its features' posed boxes meet in a cell of
  /// the grid's finest depth that is not certainly blocked; the cells it tests stay known to
  /// the grid for the builder's windows.
  std::vector<ContactCurve> generate(const ChartAxis& x, const ChartAxis& y,
                                     CurveStatistics* statistics = nullptr, BlockedCells* grid = nullptr) const;

  /// A feature pair: indices into the two parts' feature lists (boundary order).
  using FeaturePair = std::pair<int, int>;

  /// generate(x, y) in two steps (the general path, no grid; not the polygon front end): the
  /// feature pairs it keeps after the broad phase and the blocked-space cull, ascending, and
  /// their curves. generate_selected(x, y, select(x, y)) == generate(x, y), curve for curve.
  std::vector<FeaturePair> select(const ChartAxis& x, const ChartAxis& y) const;
  std::vector<ContactCurve> generate_selected(const ChartAxis& x, const ChartAxis& y,
                                              const std::vector<FeaturePair>& selected) const;

  /// select(x, y) part by part of the chart box (the general path, no grid): the broad phase
  /// once, then the blocked-space cull's quadtree walked over the cells whose interval on one
  /// axis meets given ranges. Each cell is taken from the root by the same halvings and tested
  /// as select() tests it, so the pairs kept so far are select()'s with a surviving finest cell
  /// among the cells walked, and once the ranges walked cover the axis they are select()'s.
  /// Not thread safe; the generator must outlive it.
  class Selection {
   public:
    ~Selection();
    Selection(const Selection&) = delete;
    Selection& operator=(const Selection&) = delete;
    /// Walks the cells whose interval on `axis` (0: x, 1: y) meets one of `ranges` (closed,
    /// doubles); returns the pairs kept by this walk and not before, ascending.
    std::vector<FeaturePair> extend(int axis, const std::vector<std::pair<double, double>>& ranges);

   private:
    friend class CurveGenerator;
    Selection();
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
  std::unique_ptr<Selection> incremental_select(const ChartAxis& x, const ChartAxis& y) const;

  /// An exact description of what select() depends on: the options, the axes' motion flags and
  /// both parts' motions and boundaries (kinds, orientation, rational coordinates) translated
  /// so that the first part's first vertex is the origin; not names, labels or part indices.
  /// Two generators with equal keys have exactly congruent pairs (one a translate of the
  /// other, features in the same order), so a selection one certifies for a chart box (a pair
  /// left out has no contact outside certified blocked space there) holds for the other: the
  /// blocked-space statement is about exact configurations, which the translation maps one to
  /// one. (The double roundings of the two culls may differ; either selection is certified.)
  /// Empty when the generator takes the polygon front end (select() is not available).
  std::string congruence_key() const;

 private:
  std::vector<ContactCurve> generate_impl(const ChartAxis& x, const ChartAxis& y, CurveStatistics* statistics,
                                          BlockedCells* grid, const std::vector<FeaturePair>* selected_in,
                                          std::vector<FeaturePair>* selected_out,
                                          std::vector<FeaturePair>* candidates_out) const;
  struct Data;
  std::unique_ptr<Data> data_;
};

/// The blocked-space cull without a grid reads the parts' inscribed disks: they are computed
/// once per part and shared by every generator of a part with the same loops (exact geometry:
/// the gears of a train each mesh with two neighbours), in a bounded memo (session 34). For
/// tests: how many parts' disks were computed so far (memo misses), and the memo emptied (the
/// disks are a pure function of the loops: no result depends on it).
std::size_t inscribed_disk_parts_computed();
void clear_inscribed_disk_memo();

/// Exact relation of the two parts posed at chart point `q` of chart (x, y): the oracle.
Overlap classify_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                         const ChartAxis& y, const ChartPoint& q);

/// The overlap oracle of one pair of a model (implemented in src/oracle/overlap.cpp) with the
/// pose-independent work done once: the enclosures of both parts' body coordinates, and the
/// second part's whole placement (the analysis works in its body frame). `model` must outlive it
/// and stay unchanged. Thread safe: its queries only read the prepared data.
class PairOverlap {
 public:
  PairOverlap(const Model& model, const PairAxes& axes);
  ~PairOverlap();
  PairOverlap(const PairOverlap&) = delete;
  PairOverlap& operator=(const PairOverlap&) = delete;

  /// classify_overlap(model, axes, x, y, q): the same answer at every chart point (the same
  /// computation, on the prepared inputs).
  Overlap classify(const ChartAxis& x, const ChartAxis& y, const ChartPoint& q) const;

  /// The certified filter in front of the exact oracles at points that are not rational
  /// (session 37; curves/algebraic_overlap.hpp's `filter` arguments): true when the parts
  /// certainly overlap at every chart point of the box qx × qy (qy ignored for a 1-D pair) —
  /// some edge of each crosses the other transversally at a point interior to both, by the
  /// oracle's own interval tests over the box's poses: outward-rounded enclosures of the world
  /// maps over the whole box are the proved margin. False when it cannot tell (it never claims
  /// "touching" or "apart"); then the exact oracle must decide.
  bool certainly_overlapping(const ChartAxis& x, const ChartAxis& y, const kernels::Interval& qx,
                             const kernels::Interval& qy) const;

 private:
  struct Data;
  const Model& model_;
  PairAxes axes_;
  std::unique_ptr<const Data> data_;
};

/// Certified lower bounds of the distance from a point to the boundary of a part (every edge):
/// the edges' coordinates are enclosed once. Shared by the contact-curve generator's inscribed
/// disks and the builder's blocked-cell tester.
class ClearanceBound {
 public:
  explicit ClearanceBound(const Part& part);
  /// A lower bound (>= 0) of the distance from every point of the box [x] x [y] to the boundary.
  /// Weak (min of the distances to the edges' lines / circles and their ends).
  double lower(const kernels::Interval& x, const kernels::Interval& y) const;
  /// Sharper, for an exact point: the distance to each edge's nearest point proper (the foot
  /// on a segment, the arc's sector), where that is decided by an interval filter with an
  /// exact fallback.
  double lower(const Rational& x, const Rational& y) const;

 private:
  struct EdgeBox {
    bool arc = false;
    const Edge* edge = nullptr;
    kernels::Interval sx, sy, tx, ty, kx, ky, radius, length;
    kernels::Interval start_x, start_y, end_x, end_y;   // arcs: sector directions
    bool large = false, full = false;
  };
  std::vector<EdgeBox> edges_;
};

/// A disk in a part's material, certified: the exact centre (px, py) lies strictly inside the
/// part (exact location) and the radius is a certified lower bound of its distance to the
/// boundary; nullopt when that cannot be proven (centre outside, on or too near the boundary).
struct CertifiedDisk {
  kernels::Interval x;   // enclosure of the centre
  kernels::Interval y;
  double radius = 0;     // > 0, rounded down
};
std::optional<CertifiedDisk> certify_disk(const Part& part, const ClearanceBound& bound,
                                          const Rational& px, const Rational& py);

/// Certified enclosure of (cos, sin) of the part angle theta = c + 2 atan(t) over the chart
/// interval t (c = pi for half-turn charts): cos = (1 - t^2)/(1 + t^2), sin = 2t/(1 + t^2),
/// negated for half turns. No libm trigonometry.
std::pair<kernels::Interval, kernels::Interval> rotation_enclosure(bool half_turn, const kernels::Interval& t);

/// Converts a chart coordinate to the part coordinate (angle in rad / offset in mm), in
/// double, for drawing and reports: theta = c + 2 atan(t).
double chart_to_coordinate(const ChartAxis& axis, double chart_value);

struct BodyFeature;   // curves/pose.hpp

/// Certified enclosure of unit . p (unit exact): on the axes +-(1, 0), +-(0, 1) the coordinate's
/// enclosure, negated on the negative ones (Interval::enclose is symmetric under negation), else
/// the enclosure of the exact rational dot product.
kernels::Interval enclose_dot(const Point& unit, const Point& p);
/// Certified [lo, hi] of unit . p over the points of a feature (the curve generator's swept
/// ranges and chart extents).
kernels::Interval projection_range(const BodyFeature& feature, const Point& unit);

/// A vertex's or segment's ranges on (1, 0) and (0, 1), each of its points enclosed once.
struct AxisRanges {
  kernels::Interval x, y;
};
AxisRanges axis_ranges(const BodyFeature& feature);
/// The range on the axis unit +-(1, 0) or +-(0, 1) from axis_ranges: the same interval as
/// projection_range(feature, unit).
kernels::Interval axis_projection(const AxisRanges& ranges, const Point& unit);

}  // namespace hipair::cspace
