// HIPAIR — kinematic analysis of fixed-axis mechanisms from their configuration spaces.
//
// One part (the driver) is moved monotonically over a range; every other part connected to it
// through pairs moves only when it is pushed through contact (quasi-static motion): a follower
// keeps its position while it is free, and is pushed along the boundary of its free interval
// when that boundary reaches it. A load (return spring, constant torque or force) instead holds
// a follower against one side of its free play, which makes the motion unique.
//
// The motion is computed on exact slices of the pairs' C-spaces: at an exact rational driver
// position, each follower's 1-D C-space (free intervals bounded by contact points, which are
// real algebraic numbers labelled with the touching features). Contact changes are located by
// bisection on exact slices to a certified driver interval; positions of parts are exact
// algebraic numbers at those rational driver positions. Velocity ratios and accelerations come
// from the contact polynomials by implicit differentiation (approximate, double).
//
// Assemblies: parts are ordered by distance from the driver through the pairs; each follower's
// free interval is the intersection of the slices of all its pairs with parts placed before it
// (the driver, earlier followers, fixed parts). A follower squeezed to nothing, or one that
// would have to jump through blocked space, blocks the driver: the report names the contacts.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

/// A load that holds a follower against one side of its play.
struct FollowerLoad {
  enum class Kind {
    none,      ///< moved only when pushed (keeps its position while free)
    negative,  ///< pushed towards decreasing coordinate (clockwise torque, force along -axis)
    positive,  ///< pushed towards increasing coordinate
    spring     ///< pulled towards `rest` (rad or mm)
  };
  Kind kind = Kind::none;
  /// The spring's rest (rad or mm), exact as given (model or --load): the analysis compares the
  /// follower's exact position with it (a rotating follower's rest angle by certified
  /// enclosures of its position's angle, which no nonzero rational equals).
  Rational rest = 0;
  std::string source;   ///< where it comes from: "torsional spring (model)", "--load", ...
};

/// How the slices are computed.
enum class SliceMethod {
  automatic,   ///< C-space slices where a built C-space of the pair is given, else kernels
  cspace,      ///< only from given C-spaces (a pair without one is an error)
  kernels      ///< from the contact polynomials and the exact overlap oracle (no arrangement)
};

/// Options of a kinematic analysis.
struct KinematicsOptions {
  std::string driver;                 ///< driven part; "" = the first moving part of the first pair
  int direction = +1;                 ///< +1: driver coordinate increases (ccw, +); -1 decreases
  /// Driver range [start, end] in rad or mm (end < start allowed: then direction is -1). When
  /// absent: `cycles` full turns from the driver's initial configuration for a rotation, the
  /// travel from the initial offset to the limit in `direction` for a translation.
  std::optional<std::pair<Rational, Rational>> range;
  Rational cycles = 1;
  /// Loads by part name; they replace the loads read from the model's dynamics data.
  std::map<std::string, FollowerLoad> loads;
  bool model_loads = true;            ///< take loads from the model's dynamics data
  unsigned steps_per_cycle = 1440;    ///< grid of the driver for a full turn (or the range)
  int event_bits = 46;                ///< contact changes located to 2^-bits in chart coordinate
  bool reversal = true;               ///< measure lost motion when the driver reverses
  std::size_t reversal_points = 6;    ///< at most this many reversal checks
  bool accelerations = false;         ///< also sample accelerations
  /// Feature-label substrings of contacts the designer expects; any other contact is reported
  /// as unintended. Empty: corner (vertex) contacts and tip/root contacts are flagged.
  std::vector<std::string> expected_contacts;
  SliceMethod method = SliceMethod::automatic;
  /// Called with the fraction done (0..1), from the calling thread.
  std::function<void(double)> progress;
};

/// A contact between two features of a pair.
struct ContactLabel {
  std::string pair;      ///< "driver:wheel"
  std::string label;     ///< "driver pin / wheel slot 2 wall R"
  ContactKind kind = ContactKind::vertex_segment;
  bool limit = false;    ///< a motion limit of the part rather than a contact
  /// The feature pair's exact identity (the pair's first and second part, as the pair is
  /// declared) when the slicer knows one feature pair for the label (the kernel slicer always
  /// does); part == no_index otherwise and for limits. Not part of the comparison.
  FeatureIdentity first, second;
  friend bool operator==(const ContactLabel& a, const ContactLabel& b) {
    return a.pair == b.pair && a.label == b.label && a.limit == b.limit;
  }
};

/// A driver position located exactly: in the chart of the driver, the rational interval
/// [chart_lower, chart_upper] contains it; `coordinate` is the certified enclosure in the
/// driver's unwrapped coordinate (rad or mm).
struct DriverLocation {
  CertifiedRange coordinate;
  std::size_t chart = 0;
  Rational chart_lower, chart_upper;
  double value() const { return 0.5 * (coordinate.lower + coordinate.upper); }
};

/// What a follower is doing over a driver interval.
struct KinematicPiece {
  std::string part;
  DriverLocation start, end;
  enum class Mode { free, contact, touching } mode = Mode::free;
  int side = 0;                          ///< contact on the lower (-1) or upper (+1) side of its play
  std::vector<ContactLabel> contacts;
  double start_position = 0, end_position = 0;   ///< follower coordinate (unwrapped, rad or mm)
  double lowest_position = 0, highest_position = 0;   ///< range swept during the piece (grid samples and ends)
  bool moving = false;                   ///< drive (true) or dwell (false)
  /// Shorter than the events' resolution: its start and end are located to overlapping certified
  /// driver intervals (their exact chart intervals bound it); its positive length was decided
  /// exactly (session 51: a sample at another exact position than the spring's rest it leaves).
  bool unresolved_length = false;
  std::string equation;                  ///< exact closed form P(driver_t, follower_t) = 0 of the contact
};

/// A change of contact of a follower, or a stop.
struct KinematicEvent {
  enum class Kind { contact_start, contact_end, contact_change, drop, jam, limit, end_of_range };
  Kind kind = Kind::contact_start;
  std::string part;
  DriverLocation at;
  std::vector<ContactLabel> before, after;
  double position = 0;                   ///< follower coordinate at the event
  std::string description;               ///< for people
};

/// One driver grid sample of the whole mechanism.
struct KinematicSample {
  double driver = 0;                     ///< unwrapped rad or mm
  std::vector<double> positions;         ///< per follower (KinematicsResult::followers order)
  std::vector<double> velocity_ratios;   ///< d follower / d driver (rad/rad, mm/rad, ...)
  std::vector<double> accelerations;     ///< d2 follower / d driver2 (empty unless requested)
  std::vector<double> play;              ///< width of the free interval holding the follower
  std::vector<std::vector<ContactLabel>> contacts;   ///< active contacts per follower
};

/// Lost motion when the driver reverses at a point of the path.
struct ReversalCheck {
  std::string part;
  double driver = 0;           ///< where the driver reverses
  double lost_motion = 0;      ///< driver travel back before the follower moves (rad or mm)
  bool follower_moved = false; ///< false: it did not move within one cycle back
};

/// Smallest and largest play of a follower along the path.
struct PlaySummary {
  std::string part;
  /// Smallest and largest width over the samples where the follower is held on both sides (0 on
  /// a zero-clearance fit); NaN (JSON null) when it is held on both sides at no sample.
  double minimum = 0, at_minimum = 0;
  double maximum = 0, at_maximum = 0;
  bool unbounded = false;      ///< somewhere the follower has no contact on one side
};

/// A contact engaged along the path, with the driver intervals over which it is active.
struct ContactUse {
  std::string part;
  ContactLabel contact;
  std::vector<std::pair<double, double>> intervals;   ///< driver coordinate
  bool unintended = false;
  std::string reason;
};

/// Interference (overlap) of a pair at the initial configuration.
struct Interference {
  std::string pair;
  std::string description;
};

/// A point of a pair's motion path in its C-space (part coordinates: rad or mm, wrapped to
/// the C-space's own range for rotations).
struct PathPoint {
  double x = 0, y = 0;
  bool contact = false;
};

/// The motion path of one pair in its C-space (x, y as the C-space's axes).
struct PairPath {
  std::string pair;
  std::string x_part, y_part;            ///< y_part "" for a 1-D pair
  std::vector<PathPoint> points;
};

/// Everything the analysis found.
struct KinematicsResult {
  std::string model_name;
  std::string driver;
  bool driver_rotates = true;
  int direction = +1;
  double start = 0, end = 0;             ///< requested driver range (unwrapped)
  double reached = 0;                    ///< where the driver stopped (== end unless blocked)
  std::vector<std::string> followers;    ///< parts moved through contact, in chain order
  std::vector<bool> follower_rotates;
  std::vector<FollowerLoad> loads;       ///< per follower
  std::vector<std::string> unconnected;  ///< moving parts not connected to the driver
  std::vector<std::string> slice_methods;   ///< per pair used: "kernels" or "cspace"
  std::vector<KinematicSample> samples;
  std::vector<KinematicPiece> pieces;
  std::vector<KinematicEvent> events;
  std::optional<KinematicEvent> jam;     ///< the driver could not proceed
  std::vector<Interference> initial_interference;
  std::vector<ContactUse> contacts;
  std::vector<PlaySummary> play;
  std::vector<ReversalCheck> reversals;
  std::vector<PairPath> paths;
  std::vector<std::string> warnings;
  double event_resolution = 0;           ///< largest certified width of a located event (driver units)
  double seconds = 0;
};

/// Blocked space of a two-part C-space sampled on columns of the x axis, for pictures (each
/// column is an exact slice; the picture is as accurate as its column spacing).
struct CSpaceRaster {
  std::string pair, x_part, y_part;
  bool x_rotates = true, y_rotates = true;
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;   ///< axis ranges (rad or mm)
  double column_width = 0;
  std::vector<double> x;                           ///< column centres
  std::vector<std::vector<std::pair<double, double>>> blocked;   ///< per column: blocked y ranges
};

/// Samples the C-space of the pair (first, second) of `model` (both must move).
/// \throws ModelError for unknown parts or pairs, GeometryError for other motions.
CSpaceRaster sample_cspace(const Model& model, std::string_view first, std::string_view second,
                           std::size_t columns = 360);

/// Loads read from the model's dynamics data (springs, torques, forces), by part name.
std::map<std::string, FollowerLoad> model_loads(const Model& model);

/// Runs the analysis. `spaces` may hold built C-spaces of some pairs (used per
/// `options.method`). \throws ModelError for unknown parts, GeometryError for pairs that are
/// not fixed-axis pairs, NumericError for ranges that cannot be handled.
KinematicsResult analyze_kinematics(const Model& model, const KinematicsOptions& options = {},
                                    const std::vector<CSpace>& spaces = {});

/// The report for mechanism designers (plain text, no C-space vocabulary needed).
std::string kinematics_text_report(const KinematicsResult& result);
/// The report as JSON (report.json).
std::string kinematics_json_report(const KinematicsResult& result);
/// The samples as CSV: driver, each follower's position, velocity ratio, play, contacts.
std::string kinematics_csv(const KinematicsResult& result);

}  // namespace hipair
