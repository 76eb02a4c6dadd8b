// HIPAIR — sliced configuration spaces of 3-DOF pairs: a part free in the plane (motion
// "planar": x, y and theta about its pivot) against a fixed part (Sacks & Bajaj's slicing).
//
// Coordinates. A configuration (x, y, theta) places the free part's body point q at
// pivot + R(theta) (q - pivot) + (x, y). theta is carried exactly by its half-angle tangent
// t = tan(theta/2) (rational t: an exact rational rotation) or is the half turn theta = pi.
//
// Structure. At a fixed rational rotation the slice is the C-space of a translating pair,
// built exactly by the circle–segment arrangement stage and served by hipair::CSpace. The
// critical angles (polygonal parts, and parts with arcs of rational radius: docs/cspace.md,
// "Critical angles with arcs"), where the free space of the slice changes its contact
// structure, are exact algebraic numbers in t; between two consecutive critical angles the
// slices are alike, one rational representative each; across each critical angle the free
// cells of the two neighbouring intervals that connect are listed. Point location is exact
// at every rational configuration; connectivity uses the cell structure (see docs/cspace.md,
// "3-DOF pairs").
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hipair {

/// An exact rotation angle: tan(theta/2) = t, or the half turn.
struct SlicedAngle {
  Rational t;
  bool half_turn = false;   ///< theta = pi (t ignored)
  /// The angle in radians (double, for display): 2 atan(t), or pi.
  double radians() const;
  /// The angle in degrees, correctly rounded: the double nearest 360 atan(t) / pi (MPFR, the
  /// exact t; 0 for t = 0 and the exact sign below the least subnormal), or 180 for the half
  /// turn. Every published figure of a sliced pair (JSON `degrees`, SVG labels) is this.
  double degrees() const;
};

/// The double nearest an exact (algebraic) number, correctly rounded (round to nearest, ties to
/// even; the isolating interval refined on a copy until both ends round alike); the sliced
/// JSON's `t.decimal`. AlgebraicNumber::approximate() is within one unit in the last place.
double nearest_double(const AlgebraicNumber& number);

/// A configuration of the free part relative to the fixed part.
struct SlicedConfiguration {
  Rational x, y;            ///< mm; units of 2^L mm in a normalised space (SlicedSpace::length_unit_exponent)
  SlicedAngle angle;
};

/// What a critical angle is (several may coincide).
enum class CriticalEvent {
  antiparallel_edges,   ///< an edge of the free part is antiparallel to an edge of the fixed
                        ///< part: edge–edge contact, vertex–edge contacts change
  vertex_on_contact,    ///< a vertex–vertex contact lies on another vertex–edge contact
  three_contacts        ///< three vertex–edge contacts are concurrent
};

/// A critical angle: the half-angle tangent t is the unique root of `t_polynomial` in its
/// isolating interval (AlgebraicNumber), or the half turn.
struct CriticalAngle {
  AlgebraicNumber t;
  bool half_turn = false;
  std::vector<CriticalEvent> events;   ///< kinds of event found there (distinct)
  double degrees = 0;                  ///< 360 atan(t) / pi (180 at the half turn), correctly rounded
};

/// Result of exact point location in (x, y, theta).
struct SlicedLocation {
  enum class Kind { free, blocked, contact };
  Kind kind = Kind::free;
  /// The free cell of the interval holding the angle (when free and the angle is not
  /// critical): an index into SlicedSpace::intervals()[interval].free_cells.
  std::size_t interval = no_index;
  std::size_t cell = no_index;
};

/// Free cells connected across a critical angle: left is a free cell of the interval before
/// the critical angle (counter-clockwise order), right one of the interval after it.
struct SlicedConnection {
  std::size_t left_cell = no_index;
  std::size_t right_cell = no_index;
  /// A witness of the connection: a configuration at an angle inside the left interval and one
  /// inside the right interval; the straight motion between them (through the half turn when
  /// `through_half_turn`) is certified free. For a part near its pivot both have the same offset
  /// (x, y) (a pure rotation: no vertex–edge contact line passes the offset); for a part far from
  /// its pivot (lever above 1) the offsets differ: the ends of the chord of a turn about the
  /// part's own centre, certified by the exact first-contact query (docs/cspace.md, "A pivot far
  /// from the free part").
  SlicedConfiguration left_witness, right_witness;
  bool through_half_turn = false;
};

/// One open interval of angles between two consecutive critical angles.
struct SlicedInterval {
  std::size_t lower_critical = no_index;   ///< index into critical_angles() (no_index: none at all)
  std::size_t upper_critical = no_index;
  SlicedAngle representative;              ///< a rational angle inside
  /// Free cells of the representative slice: each the slice's CSpace cell index, and the
  /// contact features on its boundary ("a loop 0 edge 3 / b vertex of loop 0 edge 1; ...").
  struct Cell {
    std::size_t slice_cell = no_index;
    std::string contacts;
    std::size_t component = no_index;      ///< connected component of the 3-D free space
  };
  std::vector<Cell> free_cells;
};

/// What happens across one critical angle.
struct SlicedCrossing {
  std::size_t critical = no_index;         ///< index into critical_angles()
  std::size_t left_interval = no_index, right_interval = no_index;
  std::vector<SlicedConnection> connections;
  /// Free cells of the left interval ending at the critical angle (no continuation found), and
  /// of the right interval starting there.
  std::vector<std::size_t> ending, starting;
};

/// A straight motion in (x, y, w): x and y the shift, w the half-angle tangent of the angle in
/// the chart centred at 0 (w = tan(theta/2)) or, `through_half_turn`, at the half turn
/// (w = tan((theta - pi)/2) = -1/t); all three are linear in the motion parameter u in [0, 1].
/// \pre without `through_half_turn` neither end is the half turn; with it neither end is at
/// theta = 0 (GeometryError otherwise).
struct SlicedMotion {
  SlicedConfiguration from, to;
  bool through_half_turn = false;
  /// Feature pairs (fixed feature, free feature) that first_crossing does not test: a
  /// simulation's held contacts, whose own contact surface the motion follows (their touch is
  /// the caller's business); every other feature pair is tested as always.
  std::vector<std::pair<FeatureIdentity, FeatureIdentity>> ignored;
};

/// A feature pair of a 3-DOF pair: a feature of the fixed part and one of the free part
/// (FeatureIdentity::part indexes the model's parts).
struct SlicedFeaturePair {
  FeatureIdentity fixed;
  FeatureIdentity free;
  std::string label;   ///< "plate segment loop 1 edge 2 / peg vertex of loop 0 edge 3"
};

/// The first contact along a straight motion, exact: the least u in [0, 1] at which the parts
/// touch (the closed parts meet), an algebraic number, with certified rational bounds.
struct SlicedMotionCrossing {
  /// none (free on all of [0, 1], ends included), crossing, or starts_in_contact (the parts are
  /// not apart at u = 0).
  CrossingStatus status = CrossingStatus::none;
  AlgebraicNumber u;                ///< exact (status crossing)
  Rational u_lower, u_upper;        ///< u_lower <= u <= u_upper, at most 2^-resolution_bits apart
  std::vector<SlicedFeaturePair> features;   ///< every feature pair touching at u
  SlicedConfiguration before;       ///< a rational configuration of the motion at u_lower (free)
};

/// A feature pair whose contact surface passes near a configuration: in the slice through the
/// configuration, the distance of (x, y) from the pair's contact curve is the world distance
/// of the two features there; certified bounds of it.
struct SlicedNearFeature {
  SlicedFeaturePair pair;
  Rational distance_lower;   ///< certified: distance_lower <= distance <= distance_upper
  Rational distance_upper;
  bool exact = false;        ///< the comparison with the query's distance was decided exactly
};

/// The contact frame of a 3-DOF feature pair at a configuration, from the contact kernels
/// (kernels/contact_geometry.hpp), exact: the contact point (world, mm) and a normal from the
/// fixed part into the free part (the direction the fixed part pushes; not unit length). Where
/// the pair touches these are the contact's point and normal; elsewhere the formulas are
/// continuous in the configuration. `defined` is false for pairs without a contact of their own
/// (vertex–vertex).
struct SlicedContactFrame {
  Point point;
  Point normal;
  bool defined = false;
};

/// The contact frame of `pair` (a feature of the fixed part, one of the planar part) with the
/// planar part at `configuration` (src/sliced/contact_frame.cpp). \throws GeometryError when
/// the pair's parts are not a fixed part and a planar part of `model`.
SlicedContactFrame sliced_contact_frame(const Model& model, const SlicedFeaturePair& pair,
                                        const SlicedConfiguration& configuration);

/// A path through free space: straight motions (SlicedMotion) between consecutive waypoints,
/// each certified free by first_crossing (status none).
struct SlicedPath {
  enum class Status {
    found,           ///< waypoints from the first configuration to the second
    not_free,        ///< an end is not a free configuration
    not_connected,   ///< the ends lie in different components of the free space
    not_found        ///< connected, but the planner found no certified path (within its budget)
  };
  Status status = Status::not_free;
  std::vector<SlicedConfiguration> waypoints;
  std::vector<bool> through_half_turn;   ///< per motion (waypoints.size() - 1)
  std::size_t motions_checked = 0;       ///< straight motions certified or refused while planning
};

/// Options of a sliced build.
struct SlicedBuildOptions {
  /// Compute critical angles and the cell structure (polygonal parts, a round free part, or
  /// arcs of rational radius with every segment facing a convex arc of rational length). Off:
  /// slices and point location only (any arcs).
  bool cell_structure = true;
  /// Called with a short description of the stage under way ("critical angles", "slice 3 of
  /// 12", "crossing 5 of 12"), for a progress line; may be empty.
  std::function<void(const std::string&)> progress;
  /// A pair whose lengths pass 2^1016 mm (a model drawn at 10^400 mm; the slices' coordinates
  /// would leave the doubles) is refused (GeometryError) unless this is set: it is then sliced
  /// on the model scaled by 2^-L (L brings its largest length near 64 mm; the same critical
  /// angles, cells, crossings and components), and every length-valued member and argument of
  /// the space is in units of 2^L mm (length_unit_exponent(): configurations' x and y, witnesses,
  /// bound(), length_unit(), slice(), distances, paths). `hipair cspace` sets it and writes mm.
  bool normalise_lengths = false;
};

/// Counts and times of a sliced build.
struct SlicedStatistics {
  std::size_t candidate_polynomials = 0;   ///< event polynomials whose roots were isolated
  std::size_t candidate_roots = 0;         ///< roots inside the features' extents
  std::size_t irrelevant_roots = 0;        ///< certified inside blocked space: no change
  std::size_t slices_built = 0;
  double seconds_critical = 0;
  double seconds_slices = 0;
  double seconds_total = 0;
};

/// The sliced 3-D C-space of a free (planar) part against a fixed part.
class SlicedSpace {
 public:
  struct Impl;

  /// \throws ModelError for unknown part names; GeometryError when `fixed_part` is not fixed,
  /// `free_part` is not planar, or (with the cell structure) an arc has an irrational radius or a
  /// segment of irrational length faces a convex arc — except when the free part is a disc or
  /// concentric rings (full circles with one centre): its slices are translates of one another,
  /// there is no critical angle, and the fixed part may have any arcs.
  static SlicedSpace build(const Model& model, std::string_view fixed_part, std::string_view free_part,
                           const SlicedBuildOptions& options = {});

  const std::string& fixed_part() const;
  const std::string& free_part() const;

  /// The slice at an exact rotation: the translating C-space in (x, y), built on demand and
  /// cached. Its x axis is x, its y axis is y (chart coordinates = mm).
  std::shared_ptr<const CSpace> slice(const SlicedAngle& angle) const;
  /// The chart box of every slice: [-bound, bound]^2; outside it the parts are apart.
  const Rational& bound() const;
  /// The length that steps and nudges follow (exact, a power of two): 1 mm for ordinary pairs
  /// (every coordinate within [2^-20, 2^40] mm), the pair's own scale for a pair drawn tiny or
  /// huge (2^(e - 4) with 2^e within a factor 2 of its largest coordinate).
  const Rational& length_unit() const;
  /// L when the pair was sliced with its lengths in units of 2^L mm (SlicedBuildOptions::
  /// normalise_lengths; a pair at 10^400 mm); 0 for every other pair (lengths in mm).
  long length_unit_exponent() const;

  /// Exact point location (any rational configuration; inside a free cell of the structure
  /// when the cell structure was built and the angle is not critical).
  SlicedLocation locate(const SlicedConfiguration& configuration) const;

  /// Critical angles in counter-clockwise order from theta = -pi (t = -infinity) to pi.
  const std::vector<CriticalAngle>& critical_angles() const;
  /// Intervals between consecutive critical angles (interval i lies after critical angle i;
  /// the last wraps around theta = pi when pi is not critical).
  const std::vector<SlicedInterval>& intervals() const;
  const std::vector<SlicedCrossing>& crossings() const;
  /// Number of connected components of the free space.
  std::size_t components() const;

  /// Are two free configurations connected through free space? false when either is not free.
  bool connected(const SlicedConfiguration& a, const SlicedConfiguration& b) const;
  /// The 3-D free component of a free configuration (no_index when not free).
  std::size_t component_of(const SlicedConfiguration& configuration) const;

  const SlicedStatistics& statistics() const;

  // ---------------------------------------------------------------- queries (3-D)

  /// The first contact along a straight motion (exact; arcs supported). Never misses a touch:
  /// the parts are apart on [0, u) (see src/sliced/motion.hpp for why).
  SlicedMotionCrossing first_crossing(const SlicedMotion& motion, const CrossingOptions& options = {}) const;
  /// Is the whole closed motion free (apart at every u in [0, 1])? Exact.
  bool motion_free(const SlicedMotion& motion) const;

  /// The feature pairs (vertex–edge, vertex–arc, segment–arc, arc–arc: the contact surfaces of
  /// the 3-DOF C-space) whose features may lie within `distance` (space units) of each other at the
  /// configuration: every pair whose certified distance lower bound is <= `distance`, nearest
  /// first. \pre distance >= 0.
  std::vector<SlicedNearFeature> features_near(const SlicedConfiguration& configuration,
                                               const Rational& distance) const;

  /// A path through free space from `a` to `b` (needs the cell structure): waypoints whose
  /// straight motions are each certified free.
  SlicedPath path(const SlicedConfiguration& a, const SlicedConfiguration& b) const;

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace hipair
