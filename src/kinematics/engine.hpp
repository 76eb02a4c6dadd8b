// Quasi-static motion of a chain of fixed-axis parts driven by one of them, on exact slices of
// the pairs' C-spaces (internal; the public entry point is hipair::analyze_kinematics).
#pragma once

#include "kinematics/axis.hpp"
#include "kinematics/slice.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace hipair::kinematics_detail {

inline constexpr std::size_t none = static_cast<std::size_t>(-1);

/// A part of the chain: the driver (index 0) or a follower.
struct ChainPart {
  std::size_t part = 0;                  ///< model index
  AxisLine line;
  std::vector<std::size_t> constraints;  ///< slicers whose follower is this part
  FollowerLoad load;
};

/// The parts reached from the driver through pairs, in order, and one slicer per pair.
struct Chain {
  const Model* model = nullptr;
  std::vector<std::unique_ptr<PairSlicer>> slicers;
  std::vector<std::string> slicer_methods;
  std::vector<ChainPart> parts;                      ///< [0] is the driver
  std::vector<std::size_t> chain_index;              ///< model part -> chain index or none
  /// slicer -> (other part's axis piece -> slicer's other chart), for 2-D slicers
  std::vector<std::vector<std::size_t>> other_chart_of_piece;
  std::vector<std::string> unconnected;
  std::vector<std::string> warnings;
  /// Rates::acceleration is computed (false: left 0 — the analysis samples accelerations only
  /// when asked, and nothing else reads them; the velocity ratios are the same either way).
  bool accelerations = true;
};

/// The model's pairs (indices) the chain of `driver` slices: usable pairs (both parts
/// fixed-axis, not both fixed) with a moving part reached from the driver (build_chain's rule).
std::vector<std::size_t> chain_pairs(const Model& model, std::size_t driver);

/// Builds the chain of `driver` (model part index).
Chain build_chain(const Model& model, std::size_t driver, const std::vector<CSpace>& spaces,
                  SliceMethod method, const std::map<std::string, FollowerLoad>& loads);

/// State of one part at a driver position.
struct PartState {
  AxisPosition position;
  double unwrapped = 0;                   ///< coordinate including whole turns
  int side = 0;                           ///< in contact with the lower (-1) / upper (+1) end of its play
  std::vector<SliceContact> contacts;     ///< active contacts (sorted)
  Bound lower, upper;                     ///< ends of its free range
  SliceKind kind = SliceKind::free;
  bool pushed = false;                    ///< the previous position became blocked: it was pushed
  double push_distance = 0;
  std::vector<SliceContact> blocked_by;   ///< when pushed out of blocked space: the contacts bounding it
  /// On a zero-clearance channel (Breakpoint::channel): a free range of zero width; lower and
  /// upper are the channel point, `contacts` its contacts, `kind` touching, `side` 0.
  bool channel = false;
  /// At its spring's rest, exactly: `position` is then the rest itself (translation) or its
  /// half-angle tangent rounded (rotation: rest_position), so two states at rest are at the
  /// same position whatever their roundings.
  bool at_rest = false;
};

/// Velocity ratio and acceleration of chain part `k` with respect to the driver (double).
struct Rates {
  double ratio = 0;
  double acceleration = 0;
};

/// State of the whole chain.
struct ChainState {
  std::size_t driver_piece = 0;
  Rational driver_value;
  double driver_unwrapped = 0;
  std::vector<PartState> parts;           ///< chain order; parts[0] is the driver
  bool jammed = false;
  bool coarse = false;                    ///< jammed only because the step was too long to follow
  std::size_t jam_part = none;
  std::string jam_reason;
  std::vector<SliceContact> jam_contacts;
  /// rates(chain, *this) when step() computed them on the way (a state it completed), else
  /// empty: rates() then computes them.
  std::vector<Rates> known_rates;
};

/// Moves the chain from `state` to the driver at (piece, value, unwrapped). When `strict`, a
/// follower pushed further than a bounded velocity ratio allows stops the step (`coarse`): the
/// step may have tunnelled through a blocking point, and must be subdivided.
ChainState step(const Chain& chain, const ChainState& state, std::size_t piece, const Rational& value,
                double unwrapped, bool strict = true);

/// step(chain, state, piece, value, unwrapped, false), given `strict`: the strict step from the
/// same state to the same driver value, or nullptr. A strict step that was not stopped as too
/// coarse took every branch of the non-strict one (max_push only stops a step) on the same
/// slices, so it is that step and is returned (moved from); otherwise the step is taken.
ChainState non_strict_step(const Chain& chain, const ChainState& state, std::size_t piece, const Rational& value,
                           double unwrapped, ChainState* strict);

/// The initial state: every part at its initial configuration (rounded to rational chart
/// values), pushed out of blocked space if needed. `interference` receives the overlaps found.
/// Each part's slices are asked in windows around its initial position, widened until the
/// overlaps and the decision lie inside (the same answers as the whole axis's slices).
ChainState initial_state(const Chain& chain, std::size_t piece, const Rational& value, double unwrapped,
                         std::vector<Interference>& interference);
/// Per-thread switch of initial_state's windows (on by default; tests turn it off to compare
/// with the whole axis's slices), and the count of windows it widened on this thread (tests).
struct InitialWindowsTag;
inline bool& initial_windows_switch() { return thread_switch<InitialWindowsTag>(); }
inline std::size_t& initial_widenings() { return thread_counter<InitialWindowsTag>(); }

/// True when the contact situation of every part is the same.
bool same_contacts(const ChainState& a, const ChainState& b);

/// Velocity ratios and accelerations of the chain parts (ChainState::known_rates when set).
std::vector<Rates> rates(const Chain& chain, const ChainState& state);
/// The same for chain part `k` when the parts before it are known.
Rates rate_of(const Chain& chain, const ChainState& state, std::size_t k, const std::vector<Rates>& known);

/// The slopes of a contact curve P(u, v) = 0 (c[i][j] of u^i v^j; u the other part's chart
/// coordinate, v the follower's) at the rational point (u, v), in part coordinates (rad through
/// the half-angle chart when the part rotates, mm otherwise): dY/dX and d^2Y/dX^2 as doubles,
/// each the double of the exact rational (mpq_get_d). `singular`: P_v = 0 there (no slope).
/// Without `second_derivative`, `second` is left 0 (not computed).
struct CurveSlopes {
  bool singular = false;
  double first = 0, second = 0;
};
/// Fraction-free: the partials and the chain rule on integer numerators and denominators,
/// one canonicalisation per result (rate_of's arithmetic).
CurveSlopes contact_slopes(const IntegerPolynomial2& polynomial, const Rational& u, const Rational& v,
                           bool other_rotates, bool part_rotates, bool second_derivative = true);
/// The same by rational arithmetic (kernels/implicit_curve.hpp), canonical at every operation:
/// the reference the tests compare contact_slopes with.
CurveSlopes contact_slopes_rational(const IntegerPolynomial2& polynomial, const Rational& u, const Rational& v,
                                    bool other_rotates, bool part_rotates);

/// Labels of contacts for reports.
ContactLabel label_of(const Chain& chain, const SliceContact& contact, std::size_t part);

/// Chain part `k`'s position as an AxisPosition from a coordinate (rad or mm), rounded (a
/// rotation's half-angle tangent to the grid 2^-bits).
AxisPosition position_of_coordinate(const AxisLine& line, const Rational& coordinate, int bits = 60);
/// position_of_coordinate with the exact number of half turns of the chart it lies in: the
/// coordinate is half_turns pi + 2 atan(t) up to the rounding of t (a rotation; 0 for a
/// translation), at any magnitude the reader accepts. The chart is chosen exactly (session 56:
/// core/angle_sign.hpp; a cyclic axis' chart about m pi holds [m pi - pi / 2, m pi + pi / 2)).
/// `beyond`: -1 (+1) when the coordinate lies below (above) the ends of a line, whose end it is
/// then clamped to; 0 otherwise.
struct LocatedCoordinate {
  AxisPosition position;
  mpz_class half_turns;
  int beyond = 0;
};
LocatedCoordinate locate_coordinate(const AxisLine& line, const Rational& coordinate, int bits = 60);

// A stretch of the driver's travel inside one chart: t runs from `from` to `to`. The sweep works
// in a frame whose origin is DriverPlan::reference half turns (exact, even: whole turns; 0 unless
// the start lies beyond 2^20 half turns), so that its doubles (the driver's unwrapped
// coordinate, its motion between two states, grid spacing) keep their precision at any angle
// the reader accepts; the results are shifted back by it at the end.
struct DriverSegment {
  std::size_t piece = 0;
  Rational from, to;
  long base_pi = 0;          // rotation: coordinate = (reference + base_pi) pi + 2 atan(t)
  double base = 0;           // base_pi * pi
};

// The end of the driver's travel: a coordinate (a range's end, a translation's limit), whole or
// part turns of a full rotation from the start, or the motion limit of a limited rotation.
struct DriverEnd {
  enum class Kind { coordinate, cycles, limit } kind = Kind::coordinate;
  Rational value;   // the coordinate (rad or mm) or the number of cycles
};

// The driver's travel planned exactly (session 56; before, in doubles: the start's turn by
// std::lround of start.get_d(), the end from start.get_d() + travel, the segments counted until
// the doubles' travel was reached within 1e-6, so beyond 2^53 rad the turns and the end were
// wrong, and a cam with limits near 10^17 deg ran for minutes): the start and the end located
// exactly (locate_coordinate: their charts and half turns, at any magnitude), the segments the
// charts from the one to the other.
struct DriverPlan {
  std::vector<DriverSegment> segments;
  mpz_class reference;        // half turns of the sweep's frame (even)
  mpz_class start_half_turns, end_half_turns;
  AxisPosition start, end;
  bool beyond = false;        // the end asked for lies beyond the driver's motion limit
};

/// Is m pi + 2 (atan(to) - atan(from)) <= n pi? Exact (by rationals: atan(to) - atan(from) lies in
/// (-pi, pi), and its side of +-pi / 2 is the sign of 1 + to from).
bool half_turns_at_most(const mpz_class& m, const Rational& from, const Rational& to, long n);
/// Plans the driver's travel from `start` (rad or mm) in `direction` to `end` (analyze.cpp).
/// Warns in `warnings` when the driver reaches its motion limit before the end.
DriverPlan plan_driver(const AxisLine& line, const Rational& start, int direction, const DriverEnd& end,
                       std::vector<std::string>& warnings);

/// A spring's rest as a position strictly inside the free range (low, high) that holds it
/// (`rest` strictly between them, decided before): the rest itself for a translation; for a
/// rotation its half-angle tangent rounded to 2^-60, 2^-120, ... until the rounded position lies
/// strictly between the range's ends (their doubles give their whole turns).
AxisPosition rest_position(const AxisLine& line, const Rational& rest, const Bound& low, double low_unwrapped,
                           const Bound& high, double high_unwrapped);
/// Pushes out of blocked space whose direction (the nearer end) certified enclosures did not
/// decide at 2^10 bits (taken downwards) on this thread: analyze warns when it is not 0.
struct UndecidedPushTag;
inline std::size_t& undecided_push_ties() { return thread_counter<UndecidedPushTag>(); }

}  // namespace hipair::kinematics_detail
