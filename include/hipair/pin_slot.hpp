// HIPAIR — C-spaces of pin-in-slot pairs: a part with motion "pin_slot" (rotation psi about
// its pivot, then a slide s along its direction turned with it) against a rotating driver, a
// translating part or a fixed part, as a stack of exact slices (docs/cspace.md, "Pin-in-slot
// pairs").
//
// Coordinates. (q, s, psi): q is the other part's coordinate (rotation angle phi, carried by a
// PartCoordinate: half-angle tangent or half turn; or translation offset, mm; none when it is
// fixed), s the slide (mm), psi the pin-slot part's angle, carried exactly by its half-angle
// tangent tau = tan(psi/2) (rational tau: an exact rational rotation).
//
// Structure. At a fixed rational tau the pin-slot part is a translating part (its geometry
// turned by psi about the pivot, sliding along the turned direction): the slice is the exact
// fixed-axis C-space of a rotating (or translating) part against a translating one, built by
// hipair::CSpace (2-D in (q, s); 1-D in s against a fixed part). The stack holds slices at
// rational tau across the part's angle limits. Across each gap between consecutive slices:
//  - connections: free cells of the two slices joined by an exact witness, a segment at
//    constant (q, s) from the lower slice's tau to the upper's that is free throughout
//    (certified by the exact 1-D C-space of the turning part at that (q, s));
//  - changes: consecutive slices whose free-cell structure (number of free cells, contact
//    feature pairs on their boundaries) differs. Each reported interval certainly contains a
//    change (both slices are exact); gaps between alike slices are not certified free of
//    changes (two changes can cancel). Changes are isolated by bisection of tau.
// Free-space groups are the classes of cells joined by witnessed connections: configurations
// in one group are certainly connected through free space; two groups are not claimed apart.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/rational.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

/// A configuration of a pin-in-slot pair.
struct PinSlotConfiguration {
  PartCoordinate other;   ///< the other part's coordinate (ignored when it is fixed)
  Rational slide;         ///< s, mm
  Rational tau;           ///< tan(psi/2)
};

/// Exact point location in a pin-in-slot C-space.
struct PinSlotLocation {
  enum class Kind { free, blocked, contact, outside };
  Kind kind = Kind::outside;
  /// When tau is the angle of a slice of the stack: that slice, and (free) the index of the
  /// free cell into PinSlotSlice::free_cells.
  std::size_t slice = no_index;
  std::size_t cell = no_index;
  /// Location in the exact slice at tau (built on demand when tau is not in the stack).
  Location in_slice;
};

/// A free cell of a slice of the stack.
struct PinSlotCell {
  std::size_t slice_cell = no_index;   ///< index into the slice CSpace's cells()
  std::string contacts;                ///< feature pairs on its boundary, sorted, "; "-separated
  std::size_t group = no_index;        ///< certainly-connected group (see header comment)
  PartCoordinate sample_other;         ///< a configuration strictly inside the cell
  Rational sample_slide;
};

/// One slice of the stack.
struct PinSlotSlice {
  Rational tau;                        ///< tan(psi/2)
  double degrees = 0;                  ///< psi, approximate, for display
  bool refinement = false;             ///< inserted by bisection to isolate a change
  std::vector<PinSlotCell> free_cells;
  std::size_t cells = 0;               ///< all cells of the slice (free, blocked, touching)
};

/// Free cells of slices `lower` and `lower` + 1 (the last and the first across the half turn)
/// joined by an exact witness, a segment free throughout:
///  - vertical: at (witness_other, witness_slide) from the lower slice's tau to the upper's;
///  - in a plane of constant slide: from (witness_other, lower tau) to (witness_other_upper,
///    upper tau), straight in the coordinates (the other part's half-angle tangent or offset,
///    tau), at witness_slide (certified on the exact 2-D C-space of the other part against the
///    slotted part turning about its pin at that slide).
struct PinSlotConnection {
  enum class Kind { vertical, plane };
  Kind kind = Kind::vertical;
  std::size_t lower = no_index;        ///< slice index
  std::size_t lower_cell = no_index;   ///< index into the lower slice's free_cells
  std::size_t upper_cell = no_index;
  PartCoordinate witness_other;
  PartCoordinate witness_other_upper;  ///< plane witnesses: the other end's coordinate
  Rational witness_slide;
};

/// A change of the free-cell structure between slices `lower` and `lower` + 1 (see header).
struct PinSlotChange {
  std::size_t lower = no_index;
  std::string description;             ///< "free cells 2 -> 1", "contacts of the free cells differ"
};

/// An exact critical value of tau = tan(psi/2): where the slice's structure may change (the
/// events of docs/cspace.md, "Critical values of pin-in-slot pairs"). Between two consecutive
/// critical values the slices are alike.
struct PinSlotCritical {
  AlgebraicNumber tau;     ///< (half_turn: unused)
  double degrees = 0;      ///< psi, approximate, for display
  /// psi = pi itself (tau infinite; a whole-turn stack only: between its last and first slices)
  bool half_turn = false;
};

/// A path through the free space of a pin-in-slot pair (PinSlotSpace::path): straight motions
/// between consecutive waypoints, each straight in (the other part's coordinate value: half-angle
/// tangent or offset, s, tau) -- or, `through_half_turn`, in (other, s, -1/tau), the short way
/// across psi = pi of a whole-turn stack -- and each certified free throughout by an exact
/// C-space of the pair (PinSlotSpace::motion_free). Motions are of three kinds only: at constant
/// tau (in a slice), at constant (other, s) (a turn of the pin-slot part: a witness segment),
/// or at constant s (a plane witness).
struct PinSlotPath {
  enum class Status {
    found,                ///< waypoints from the first configuration to the second
    not_free,             ///< an end is not a free configuration (or is outside the limits)
    not_shown_connected,  ///< the stack does not show the ends connected (different groups, or an
                          ///< end joined to no slice's cell): NOT a proof that they are apart
    not_found             ///< in one group, but the planner found no certified path (its budget)
  };
  Status status = Status::not_free;
  std::vector<PinSlotConfiguration> waypoints;
  std::vector<bool> through_half_turn;   ///< per motion (waypoints.size() - 1)
  std::size_t motions_checked = 0;       ///< motions certified or refused while planning
};
std::string_view to_string(PinSlotPath::Status status);

/// Options of a pin-in-slot build.
struct PinSlotBuildOptions {
  /// Slices across the angle limits (0: automatic, 16). At least 2.
  std::size_t slices = 0;
  /// Bisection steps to isolate each change (0: none).
  unsigned refine_steps = 3;
  /// Search witnesses of connections between consecutive slices.
  bool connections = true;
  /// Also try plane witnesses (constant slide) between cells no vertical witness joined: one
  /// 2-D C-space per slide tried (slower; the other part must move).
  bool plane_witnesses = false;
  /// Build the stack. false: nothing is built up front; slices are built on demand by slice()
  /// and locate() (slices(), connections(), changes() stay empty).
  bool stack = true;
  /// Compute the exact critical values of tau (when the class allows: see
  /// PinSlotSpace::critical_values_exact) and put a slice in every interval between them.
  bool critical_values = true;
  /// Decide a connection's witness segment free by a certified double-interval test of the two
  /// boundaries (segments only) before building its exact 1-D C-space; the connections are
  /// the same either way (false: always the exact space, for tests).
  bool witness_filter = true;
  /// Called with the stage under way ("slice 3 of 16", "connections 5 of 15").
  std::function<void(const std::string&)> progress;
  /// A pair whose lengths pass 2^1016 mm (a model drawn at 10^400 mm) is refused (its slices'
  /// coordinates would leave the doubles) unless this is set: it is then stacked on the model
  /// scaled by 2^-L (L brings its largest length near 64 mm; the same slices, changes and
  /// critical values), and every length-valued member and argument (slides, a translating other
  /// part's offsets, samples, witnesses, slice()) is in units of 2^L mm (length_unit_exponent()).
  /// `hipair cspace` sets it and writes mm.
  bool normalise_lengths = false;
};

struct PinSlotStatistics {
  std::size_t slices_built = 0;          ///< 2-D (or 1-D) slices, including refinements and queries
  /// Witness segments certified free (each by an exact 1-D C-space, or `witness_filtered` of
  /// them by the certified boundary test of PinSlotBuildOptions::witness_filter).
  std::size_t witness_spaces = 0;
  std::size_t plane_spaces = 0;          ///< 2-D C-spaces built for plane witnesses
  std::size_t witness_candidates = 0;    ///< candidate witness points tried
  std::size_t witness_filtered = 0;      ///< witness segments certified free without a 1-D C-space
  std::size_t critical_roots = 0;        ///< candidate roots of the critical-value events
  double seconds_critical = 0;
  double seconds_slices = 0;
  double seconds_connections = 0;
  double seconds_total = 0;
};

/// The stack-of-slices C-space of a pin-in-slot pair.
class PinSlotSpace {
 public:
  struct Impl;

  /// \throws ModelError for unknown part names; GeometryError when `pin_slot_part` has no
  /// pin_slot motion, the other part is planar or pin-slot too, or a slice cannot be built
  /// (the message names the pair and the slice).
  static PinSlotSpace build(const Model& model, std::string_view other_part, std::string_view pin_slot_part,
                            const PinSlotBuildOptions& options = {});

  const std::string& other_part() const;
  const std::string& pin_slot_part() const;
  /// What moves the other part: rotation, translation, or fixed (Motion::Kind).
  Motion::Kind other_kind() const;
  /// 3 (the other part moves) or 2 (it is fixed: slices are 1-D in s).
  int dimension() const;
  /// The rational half-angle tangents bounding the stack: its first and last slices (inside
  /// the angle limits, or, without limits, the whole turn but the half turn).
  const Rational& tau_lower() const;
  const Rational& tau_upper() const;
  /// L when the pair was stacked with its lengths in units of 2^L mm (PinSlotBuildOptions::
  /// normalise_lengths; a pair at 10^400 mm); 0 for every other pair (lengths in mm).
  long length_unit_exponent() const;

  /// The exact slice at tau: x = the other part's coordinate, y = s (1-D: x = s).
  std::shared_ptr<const CSpace> slice(const Rational& tau) const;

  const std::vector<PinSlotSlice>& slices() const;
  const std::vector<PinSlotConnection>& connections() const;
  const std::vector<PinSlotChange>& changes() const;
  std::size_t groups() const;

  /// Are the critical values exact and complete? True when they were asked for, the stack was
  /// built, the other part is fixed or translates, and every slide (and the other part's
  /// translation) has limits (the slice box is then fixed); parts as for 3-DOF pairs with arcs
  /// (arcs of rational radius; a segment facing a convex arc of rational length). Otherwise
  /// (a rotating driver, no limits) the stack is sampled as described above.
  bool critical_values_exact() const;
  /// The exact critical values inside (tau_lower, tau_upper), ascending (empty unless
  /// critical_values_exact()). Every interval between consecutive ones (and the stack's ends)
  /// holds a slice of the stack: two slices with no critical value between them are alike.
  /// A stack narrower than a whole turn is searched up to its angle limits (the end pieces
  /// between the limits and the end slices too, since session 55): slices are added between a
  /// limit and the value nearest it, so the stack is complete up to the limits; a value at a
  /// limit (psi = 0 only: tau rational) is listed, and that limit is the stack's end slice. A
  /// limit at or beyond the half turn (the quarter step the stack accepts) leaves the values
  /// incomplete (critical_values_exact() false).
  /// A whole-turn stack (no angle limits, or limits of a turn or more) is a cycle: the values
  /// across the half turn are found too (in the chart about it, u = -1/tau), slices are added
  /// beyond the first and last so that every interval between cyclically consecutive values
  /// holds one, and psi = pi itself, when critical, is listed last (half_turn).
  const std::vector<PinSlotCritical>& critical_values() const;

  /// Exact point location at any rational configuration.
  PinSlotLocation locate(const PinSlotConfiguration& configuration) const;

  /// Are two configurations certainly connected through free space (both free, and joined
  /// through witnessed segments and the stack's groups)? false means "not shown", not "apart".
  bool certainly_connected(const PinSlotConfiguration& a, const PinSlotConfiguration& b) const;

  const PinSlotStatistics& statistics() const;

  /// Is the straight motion from `a` to `b` (see PinSlotPath) certainly free throughout, ends
  /// included? Exact; decided for motions at constant tau, at constant (other, s), or (the other
  /// part moving) at constant s; false for any other motion (not certified), and for an end
  /// that is not free.
  bool motion_free(const PinSlotConfiguration& a, const PinSlotConfiguration& b, bool through_half_turn = false) const;

  /// A path through free space from `a` to `b` when certainly_connected(a, b) (the same
  /// witnessed connections and groups): the vertical segment from each end to the slice its
  /// group was found through, moves inside slice cells (a lazy roadmap on the cells' exact
  /// slices), and the connections' witness segments. Every motion is certified by
  /// motion_free before it is taken; "not found" is a status, never an uncertified path.
  PinSlotPath path(const PinSlotConfiguration& a, const PinSlotConfiguration& b) const;


 private:
  std::shared_ptr<Impl> impl_;
};

// ------------------------------------------------------------------ the work cycle

/// Options of a pin-in-slot work cycle (pin_slot_cycle).
struct PinSlotCycleOptions {
  std::string driver;     ///< rotating part driving the pin-slot part (empty: the one paired with it)
  std::string follower;   ///< the pin-slot part (empty: the model's only one)
  std::string target;     ///< translating part the follower pushes (empty: the one paired with it)
  std::size_t steps = 72; ///< driver samples per turn (>= 8)
  bool clockwise = false; ///< the driver's sense
  std::function<void(const std::string&)> progress;
};

/// What the follower does to the target at one sample.
enum class CyclePhase {
  clear,     ///< the target's free cell has no contact end: the follower does not hold it
  engaged,   ///< the target's free cell is bounded by a contact with the follower (e.g. a claw
             ///< inside a perforation): held but not moved
  pushing,   ///< the target had to move to stay free of the follower: it is pushed, in contact
  jammed     ///< no free target offset within the target's limits
};
std::string_view to_string(CyclePhase phase);

/// One sample of the cycle. The follower's pose is the middle of its largest free slide
/// interval over follower angles searched near the previous pose (a choice, not a law), and it
/// is certified free against the driver by exact point location; the target's offset is exact.
struct CycleSample {
  PartCoordinate driver;            ///< half-angle tangent (or half turn), exact
  double driver_degrees = 0;
  Rational slide, tau;              ///< follower pose, exact
  double psi_degrees = 0;
  double clearance = 0;             ///< length of the follower's free slide interval there (mm, approximate)
  bool follower_free = false;       ///< exact point location against the driver
  Rational target_offset;           ///< exact
  bool target_offset_exact = true;  ///< false: an irrational contact, the offset is the rational
                                    ///< end of its isolating interval on the free side
  CyclePhase phase = CyclePhase::clear;
  std::vector<std::string> contacts;   ///< feature pairs touching between follower and target
  /// engaged: the feature pairs whose contacts bound the target's free interval (they touch
  /// when the target moves to that end)
  std::vector<std::string> bounds;
  /// The driver–follower contacts that bound the follower's free slide interval at its pose
  /// (feature-pair labels of the interval's two end vertices in the exact 1-D slice of the
  /// follower against the driver; "slide limit" for an end at the slot's limit). The follower
  /// itself is posed inside the interval, clear of the driver.
  std::vector<std::string> driver_bounds;
};

/// A run of samples with one phase.
struct CycleRun {
  CyclePhase phase = CyclePhase::clear;
  std::size_t first = 0, last = 0;  ///< sample indices
  Rational target_moved;            ///< target offset change over the run (exact)
};

struct PinSlotCycle {
  std::string driver, follower, target;
  std::vector<CycleSample> samples;
  std::vector<CycleRun> runs;
  Rational advance;                 ///< target offset change over the whole cycle (exact)
  double seconds = 0;
};

/// The work cycle of a driver, a pin-slot follower and a translating target it pushes (the
/// film advance: the cam turns once; the claw enters a perforation, pulls the film, retracts).
/// Quasi-static: the target stays where it is unless the follower's new pose overlaps it, then
/// it moves to the nearest free offset (the contact). Exact at every sample: the follower's pose
/// is rational and located exactly against the driver; the target's free offsets are the exact
/// 1-D C-space of the target against the follower at that pose. Between samples nothing is
/// claimed: phase changes are located to the sample spacing.
/// \throws GeometryError when the parts are not such a chain (naming them), ModelError for
/// unknown names.
PinSlotCycle pin_slot_cycle(const Model& model, const PinSlotCycleOptions& options = {});

/// The rigid placement of the pin-slot part at (s, tau) (body point p -> pivot + R(psi)(p -
/// pivot) + s R(psi) d), and of the other part at its coordinate: exact, for the overlap oracle.
Placement pin_slot_placement(const Part& pin_slot_part, const Rational& slide, const Rational& tau);
Placement part_placement(const Part& part, const PartCoordinate& coordinate);

}  // namespace hipair
