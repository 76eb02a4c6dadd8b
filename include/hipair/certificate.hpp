// HIPAIR — certificates: claims about a model (interference, clearance, jamming, free passage)
// with witnesses that anyone can re-check with the small independent verifier `hipair-verify`
// (certify/), without trusting HIPAIR's C-space, kernels or analysis code.
//
// A certificate names the model by the SHA-256 of its file bytes, lists the exact parameter
// values used and every rounding the model reader performed, states one claim about a pair of
// parts and carries the witnesses of that claim. The JSON format is described in
// docs/certify.md; certify/certificate_format.hpp reads and writes it.
//
// Coordinates. A rotating part's angle theta (rad, counter-clockwise, 0 = as drawn in the
// model) is given in single-configuration claims by the half-angle tangent
// t = tan((theta - c)/2) with c = 0 or c = pi, so that cos and sin are rational and the posed
// geometry is exact; interval claims (jam, free passage) use angle intervals in rad with
// rational ends. A translating part's coordinate is its offset s (mm) along its direction.
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hipair {

/// The kinds of claims a certificate can carry.
enum class ClaimKind {
  interference,  ///< the pair overlaps at one exact configuration
  clearance,     ///< at one exact configuration the pair is at least `distance` apart
  jam,           ///< driving the driver monotonically cannot pass a driver position
  free_passage,  ///< along a motion path over a driver range the pair stays `distance` apart
  tolerance,     ///< for every parameter vector of a box, a driven pair's channel never closes
  planar_interference,  ///< a part free in the plane overlaps a fixed part at one exact pose (x, y, theta)
  planar_clearance      ///< at one exact pose the free part is at least `distance` from the fixed part
};

/// "interference", "clearance", "jam", "free_passage".
std::string to_string(ClaimKind kind);

/// The exact position of one moving part in a single-configuration claim.
struct ExactPosition {
  /// Rotation: t = tan((theta - c)/2), c = pi when `half_turn`, else 0. Translation: s (mm).
  Rational value;
  bool is_offset = false;   ///< a translation offset (JSON "offset") rather than a tangent ("tangent")
  bool half_turn = false;
  /// Optional (rotations): the angle (rad) the position stands for and a bound on
  /// |theta - angle| (an irrational tangent is rounded). Checked by the verifier.
  std::optional<Rational> angle;
  std::optional<Rational> angle_error;
};

/// The exact pose of a part free in the plane (motion "planar") in planar claims: body point p
/// goes to pivot + R(theta) (p - pivot) + (x, y), theta given by its half-angle tangent
/// t = tan((theta - c)/2) with c = 0, or c = pi when `half_turn` (so that cos and sin are
/// rational).
/// A pin-in-slot part (motion "pin_slot") is posed by its slide instead of (x, y): body point p
/// goes to pivot + R(theta) (p - pivot) + slide R(theta) d (d its direction).
struct PlanarPose {
  std::string part;   ///< the posed part (the other part of the pair is fixed, or placed by the configuration)
  Rational x, y;      ///< mm (planar parts)
  Rational tangent;
  bool half_turn = false;
  std::optional<Rational> slide;   ///< pin-slot parts: the slide s (mm); x and y unused
};

/// One boundary edge of a part, by index; `label` must equal the model edge's label.
struct EdgeReference {
  std::string part;
  std::size_t loop = 0;
  std::size_t edge = 0;
  std::string label;
};

/// Two edges of different parts whose boundaries cross. A crossing proves that the parts
/// overlap (a point of `edge` lies strictly inside the other part).
struct CrossingWitness {
  EdgeReference edge;
  EdgeReference across;
  /// Interval claims: the piece of `edge` that crosses `across` for every configuration of the
  /// piece: a fraction [u1, u2] of a segment (0 = source, 1 = target), or angles [a1, a2]
  /// (rad) from an arc's source in the arc's direction. Unused for single configurations
  /// (the verifier then computes the crossing exactly).
  std::optional<RationalInterval> along;
};

/// A piece of a jam wall: every configuration of the wall with its running coordinate in
/// `range` is blocked because `crossing` crosses there, or (format version 2, `point` set and
/// `crossing` unused) because the world point `point` lies strictly inside both parts for every
/// configuration of the piece: the witness of flush faces, whose boundaries meet only along
/// collinear edges and never cross (docs/certify.md, "Jam").
struct BlockedPiece {
  RationalInterval range;
  CrossingWitness crossing;
  std::optional<Point> point;
};

/// A box of configurations: driver coordinate in `driver`, follower coordinate in `follower`
/// (absent when the other part of the pair is fixed). Angles in rad, offsets in mm.
struct ConfigurationBox {
  RationalInterval driver;
  std::optional<RationalInterval> follower;
};

/// A feature of a part in a tolerance certificate: an edge (segment or arc) of the part's
/// loops as read, or, with `vertex`, the source vertex of that edge (edges oriented as read).
struct FeatureReference {
  EdgeReference edge;
  bool vertex = false;
};

/// One side of the follower's free channel in a tolerance certificate: the contact curve of
/// a feature of the driver and a feature of the follower (docs/certify.md "Tolerance").
struct ContactSidePair {
  FeatureReference driver;     ///< the feature of the driven part
  FeatureReference follower;   ///< the feature of the follower
};

/// A side's witness in one leaf: the side is the contact pair `pair` (index into
/// ToleranceClaim::sides); for every (parameters, driver) of the leaf its contact function has
/// exactly one root in the follower interval `bracket`, and at the leaf's centre that root
/// lies in `centre` (follower coordinates, rad or mm).
struct LeafSide {
  std::size_t pair = 0;
  RationalInterval bracket;
  RationalInterval centre;
};

/// A leaf of the branch-and-bound: a sub-box of the parameter box (deviations from nominal, one
/// interval per varied parameter, ToleranceClaim::varied order) times a driver interval, over
/// which the channel between the two sides is certified open (no_jam), or times a driver and a
/// follower interval over which the two parts are certified apart (no_interference: `follower`
/// set, `lower`/`upper` unused).
struct ToleranceLeaf {
  std::vector<RationalInterval> parameters;
  RationalInterval driver;
  std::optional<RationalInterval> follower;   ///< no_interference only
  LeafSide lower, upper;
  /// Optional witness of the open channel: the follower coordinate
  /// y*(p, d) = value + sum slopes_i (p_i - c_i) + slopes_k (d - d_c) (c, d_c: the leaf's
  /// centre; slopes per varied parameter, then the driver) lies strictly between the two
  /// sides over the whole leaf. Without it the play between the sides is enclosed instead.
  std::optional<Rational> witness;
  std::vector<Rational> witness_slopes;
  /// Optional, with a witness: the lower and upper sides' margins m > 0 of the second-order
  /// test. The verifier encloses each side's contact function at y* over the leaf in
  /// second-order Taylor form (value and gradient at the centre, Hessian over the leaf) and
  /// requires it to keep the sign of the bracket's channel-side end with at least this margin
  /// (docs/certify.md "Tolerance", check 6). Without them the first-order forms are used.
  std::vector<Rational> witness_margins;
};

/// A node of the subdivision tree in preorder: a split of the current region at `value` along
/// `dimension` (a varied parameter's name, "driver", or for no_interference "follower"; lower
/// part first), or a leaf (index
/// into ToleranceClaim::leaves) whose box must contain the region.
struct ToleranceTreeNode {
  bool leaf = false;
  std::size_t index = 0;
  std::string dimension;
  Rational value;
};

/// A tolerance certificate's claim (docs/certify.md "Tolerance").
struct ToleranceClaim {
  /// "no_jam": the channel never closes; "no_interference": the parts stay apart over
  /// range x follower_range (the operating configuration set).
  std::string property = "no_jam";
  std::string driver, follower;       ///< both rotating or translating parts of the pair
  RationalInterval range;             ///< driver range (rad or mm)
  std::optional<RationalInterval> follower_range;   ///< no_interference: follower range (rad or mm)
  Rational scale = 1;                 ///< the box is `scale` times each varied tolerance range
  std::vector<std::string> varied;    ///< varied parameters (the others stay nominal)
  std::vector<RationalInterval> box;  ///< per varied parameter: deviations from nominal
  std::vector<ContactSidePair> sides;   ///< no_jam only
  std::vector<ToleranceLeaf> leaves;
  std::vector<ToleranceTreeNode> tree;
};

/// The value of one model parameter used for the claim.
struct ParameterValue {
  std::string name;
  Rational value;           ///< the rational used (the model's nominal when not overridden)
  bool overridden = false;  ///< given through ReadOptions::parameter_values
};

/// A certificate: model identity, one claim about a pair of parts, its witnesses.
/// A jam's start: a configuration in its trap where the parts are apart (Certificate::start).
struct JamStart {
  Rational driver;
  std::optional<Rational> follower;   ///< absent when the pair's other part is fixed
};

struct Certificate {
  ClaimKind claim = ClaimKind::interference;
  std::string statement;   ///< the claim in words: certificate_statement() of the claim's data (checked)

  std::string model_name;
  /// The model file's name as certified, a label: the content hash identifies the model, so the
  /// verifier does not compare it with the name of the file it is given; it checks only that it
  /// is a bare file name (no directory, no control character, at most 255 bytes), as written.
  std::string model_file;
  std::string content_hash;
  std::vector<ParameterValue> parameters;   ///< every parameter of the model, in model order
  std::vector<Rounding> roundings;          ///< every rounding of the model reader

  std::string first;       ///< the pair's parts, by name
  std::string second;

  /// interference, clearance: the position of every moving part of the pair.
  std::map<std::string, ExactPosition> configuration;
  /// planar_interference, planar_clearance: the free part's pose (the other part is fixed or,
  /// against a pin-slot part, placed by `configuration`).
  std::optional<PlanarPose> pose;

  /// interference, planar_interference: a point strictly inside both parts (world, mm), or a crossing.
  std::optional<Point> witness_point;
  std::optional<CrossingWitness> witness_crossing;

  /// clearance, free_passage: certified lower bound of the distance between the parts (mm).
  Rational distance;

  /// jam, free_passage: the driven part and the other moving part of the pair ("" if fixed).
  std::string driver;
  std::string follower;

  /// free_passage: the driver range, the nominal path (driver, follower) as a polyline with
  /// rational vertices (empty when the follower is absent), and boxes covering the path.
  RationalInterval range;
  std::vector<std::pair<Rational, Rational>> path;
  std::vector<ConfigurationBox> boxes;

  /// jam: the driver moves in `direction` (+1 increasing, -1 decreasing) inside `trap`; the
  /// cut is the side of the trap at the far driver end, the walls its follower ends.
  /// A wall is empty when the follower's motion limit closes that side.
  int direction = +1;
  ConfigurationBox trap;
  std::vector<BlockedPiece> cut;          ///< range: follower (one piece, any range, for 1-D pairs)
  std::vector<BlockedPiece> lower_wall;   ///< range: driver; follower = trap.follower->lo
  std::vector<BlockedPiece> upper_wall;   ///< range: driver; follower = trap.follower->hi
  /// jam: a configuration inside the trap at which the parts are certainly apart (the driver's
  /// coordinate, and the follower's when it moves): the trap holds a configuration of the
  /// mechanism, so the claim is not empty (session 42; until then a trap wholly inside the
  /// parts' overlap verified: "cannot pass" of a motion that cannot start).
  std::optional<JamStart> start;

  /// tolerance: the parameter box, the driver range and the branch-and-bound leaves.
  std::optional<ToleranceClaim> tolerance;
};

/// What the producer needs besides the model.
struct CertifyContext {
  /// The parameter overrides the model was read with (ReadOptions::parameter_values).
  std::map<std::string, Rational> parameter_values;
};

/// Positions of the pair's moving parts for single-configuration claims: the angle of a
/// rotating part (rad, rounded to an exact half-angle tangent within 1e-15 rad and recorded)
/// or the offset of a translating part (mm).
using PartValues = std::map<std::string, Rational>;

/// An exact position from an angle (rad): the half-angle tangent rounded to a rational (the
/// chart centred at pi when |angle| > pi/2), with `angle` and its error bound recorded (a
/// label the verifier accepts only with an error of at most 10^-12 rad: an angle so large that
/// its reduction to a turn is coarser gets no label).
ExactPosition exact_position_from_angle(const Rational& angle);

/// Certifies that parts `first` and `second` overlap at `positions` (every moving part of the
/// pair; rotations by ExactPosition). Witness: a rational point strictly inside both (from the
/// exact overlap predicate), else a transversal crossing of two boundary edges, re-checked with
/// the verifier's own code. \returns nullopt when the parts do not overlap there (apart or only
/// touching). \throws ModelError for unknown parts or a position beyond the part's motion limits
/// (so does certify_clearance), GeometryError for parts that are not fixed-axis parts.
std::optional<Certificate> certify_interference(const Model& model, const std::string& first,
                                                const std::string& second,
                                                const std::map<std::string, ExactPosition>& positions,
                                                const CertifyContext& context = {});

/// Certifies that the pair is at least `distance` apart at `positions` (exactly the distance too, at any scale); when
/// absent, the certified lower bound found to 6 digits (rounded down, or up to the distance when that holds exactly).
/// \returns nullopt when the parts touch or overlap there, or the bound cannot be certified.
std::optional<Certificate> certify_clearance(const Model& model, const std::string& first,
                                             const std::string& second,
                                             const std::map<std::string, ExactPosition>& positions,
                                             std::optional<Rational> distance = std::nullopt,
                                             const CertifyContext& context = {});

/// Certifies that the planar part `pose.part` overlaps the fixed part `fixed` at the exact pose
/// (the 3-DOF counterpart of certify_interference): witness point or crossing, re-checked.
/// \returns nullopt when they do not overlap there. \throws ModelError for unknown parts,
/// GeometryError when `fixed` is not fixed or the posed part is not planar.
std::optional<Certificate> certify_planar_interference(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                       const CertifyContext& context = {});

/// Certifies that at the exact pose the planar part is at least `distance` from the fixed part
/// (absent: the distance found, as for certify_clearance).
/// \returns nullopt when the parts touch or overlap there, or the bound cannot be certified.
std::optional<Certificate> certify_planar_clearance(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                    std::optional<Rational> distance = std::nullopt,
                                                    const CertifyContext& context = {});

/// Certifies that the pin-in-slot part `pose.part` (pose.slide set) overlaps part `other` (fixed,
/// or rotating or translating to its position in `configuration`) at the exact pose: a planar
/// interference claim with the pin-slot pose, re-checked. \returns nullopt when they do not
/// overlap there. \throws ModelError for unknown parts, GeometryError for other motions.
std::optional<Certificate> certify_pin_slot_interference(const Model& model, const std::string& other, const PlanarPose& pose,
                                                         const std::map<std::string, ExactPosition>& configuration = {},
                                                         const CertifyContext& context = {});

/// Certifies that at the exact pin-slot pose the parts are at least `distance` apart (absent: the
/// largest certified bound found, rounded down to 6 significant digits). \returns nullopt when
/// they touch or overlap, or the bound cannot be certified.
std::optional<Certificate> certify_pin_slot_clearance(const Model& model, const std::string& other, const PlanarPose& pose,
                                                      const std::map<std::string, ExactPosition>& configuration = {},
                                                      std::optional<Rational> distance = std::nullopt,
                                                      const CertifyContext& context = {});

/// A motion path for free passage: the follower coordinate as a polyline of the driver
/// coordinate (rational vertices, rad or mm). Empty for a pair with a fixed part.
struct PassagePath {
  std::string driver;
  std::string follower;    ///< "" when the pair's other part is fixed
  RationalInterval range;  ///< driver range
  std::vector<std::pair<Rational, Rational>> polyline;
};

/// Options of the interval searches (free passage, jam).
struct IntervalSearchOptions {
  std::size_t max_boxes = 200000;   ///< give up beyond this many boxes / pieces
};

/// Certifies that along `path` the pair never overlaps and stays at least `distance` apart
/// (absent: half the smallest clearance sampled along the path, rounded down). The driver
/// range is covered by boxes, each certified with interval arithmetic and a Lipschitz bound.
/// \returns nullopt when the parts come closer than the distance (or touch) on the path.
std::optional<Certificate> certify_free_passage(const Model& model, const std::string& first,
                                                const std::string& second, const PassagePath& path,
                                                std::optional<Rational> distance = std::nullopt,
                                                const CertifyContext& context = {},
                                                const IntervalSearchOptions& options = {});

/// A jam to certify: the driver moving in `direction` cannot leave the trap box except by
/// passing the cut at its far driver end, and every configuration of the cut and of the
/// follower walls is blocked.
struct JamQuery {
  std::string driver;
  std::string follower;    ///< "" when the pair's other part is fixed
  int direction = +1;
  ConfigurationBox trap;
  /// A configuration in the trap known to be free (find_jam: where the search stood); certify_jam
  /// tries it first for the certificate's start, then a grid over the trap.
  std::optional<JamStart> start;
};

/// Certifies the jam described by `query` by covering the cut and the walls with pieces, each
/// blocked by a crossing feature pair (interval arithmetic). A wall at or beyond the follower's
/// motion limit, in the limits' own turn (verify::wall_closed_by_limit), needs no pieces.
/// The certificate's start is a configuration of the trap at which the parts are certainly
/// apart (verify::jam_start_failure): `query.start` when it is one, else the first of a grid over
/// the trap (driver: the near end, the middle, the quarters; follower: 31 values across the band).
/// \returns nullopt when some part of the cut or walls is not certainly blocked, or when no
/// configuration tried in the trap is certainly free.
std::optional<Certificate> certify_jam(const Model& model, const std::string& first,
                                       const std::string& second, const JamQuery& query,
                                       const CertifyContext& context = {},
                                       const IntervalSearchOptions& options = {});

/// Looks for the trap of a jam: starting from the driver at `start` with the follower at
/// `follower_start` (both rad or mm; the follower ignored for a pair with a fixed part), the
/// driver is moved in `direction` by steps of `step` up to `travel`; the follower's free
/// interval around its position is tracked with the exact overlap predicate. When it closes,
/// returns the trap box around the closing (for certify_jam); nullopt when it never closes.
std::optional<JamQuery> find_jam(const Model& model, const std::string& first,
                                 const std::string& second, const std::string& driver,
                                 const Rational& start, const Rational& follower_start,
                                 int direction, const Rational& step, const Rational& travel);

/// True when the pair's configurations recur every whole turn of the driver: it rotates without
/// angle limits and `other` is fixed. find_jam then searches a travel longer than
/// periodic_jam_travel() as that travel (a path of a whole turn meets every configuration).
bool periodic_jam_search(const Part& driver, const Part& other);
/// 710/113 rad: just over a whole turn (2 pi < 710/113 < 2 pi + 6e-7).
Rational periodic_jam_travel();

/// Certifies a trap find_jam found, searched with driver steps of `step`: the trap itself, or,
/// where its cut is too shallow to certify (the channel closes within a rounding of the step's
/// end: at the cut the parts overlap by next to nothing), the same trap with its far end moved
/// on by 1, 2, 4 or 8 further steps (its walls must then hold over the longer range).
/// \returns nullopt when none of them is certified.
std::optional<Certificate> certify_found_jam(const Model& model, const std::string& first,
                                             const std::string& second, const JamQuery& query,
                                             const Rational& step, const CertifyContext& context = {},
                                             const IntervalSearchOptions& options = {});

struct KinematicsResult;

/// A finding of an analysis with its certificate, or why it has none.
struct CertifiedFinding {
  std::string finding;                    ///< "interference of driver:wheel at the initial configuration", ...
  std::optional<Certificate> certificate;
  std::string note;                       ///< why there is no certificate
};

/// Certificates for the interference and jamming findings of a kinematic analysis
/// (include/hipair/kinematics.hpp): interference at the initial configuration of each pair
/// reported, and the jam (pair by pair: the driver against a fixed part, or driver and jammed
/// follower; the trap is searched around the reported jam position).
std::vector<CertifiedFinding> certify_kinematic_findings(const Model& model, const KinematicsResult& result,
                                                         const CertifyContext& context = {});

/// The certificate as JSON text (docs/certify.md).
std::string write_certificate(const Certificate& certificate);

/// Reads a certificate from JSON text. \throws ModelError (pointer into the certificate).
Certificate read_certificate(std::string_view json_text);

/// The outcome of checking a certificate.
struct VerificationResult {
  bool valid = false;    ///< the claim holds (hipair-verify exit 0)
  /// The evidence passes every check the verifier makes, but those checks do not prove the
  /// claim (hipair-verify exit 3): tolerance claims with property no_jam (the verifier checks
  /// that the named contact sides stay apart, not that they bound the follower's channel;
  /// docs/certify.md). `valid` is false then.
  bool unproven = false;
  std::string summary;   ///< valid or unproven: one line describing what was checked
  std::string reason;    ///< invalid: the exact reason
};

/// The claim in words: a function of the claim's data alone (names, numbers and the driver's
/// unit). Every producer writes it; the verifier regenerates it from the checked data and
/// rejects a certificate whose `statement` differs (session 36). The data must hold what the
/// claim needs (a planar claim's pose, a tolerance claim's section, the driver a part of `model`).
std::string certificate_statement(const Certificate& certificate, const Model& model);

/// Checks `certificate` against `model` with the verifier's own code (the code `hipair-verify`
/// runs): the model must have been read with the certificate's parameter values.
/// Does not check the content hash (the model text is not at hand; see verify_certificate_file).
VerificationResult check_certificate(const Certificate& certificate, const Model& model);

/// Checks `certificate` against the model file's text: its SHA-256, the model read with the
/// certificate's parameter values, then the claim (tolerance certificates need the text: the
/// verifier re-reads the parametric form of the geometry from it).
VerificationResult check_certificate_text(const Certificate& certificate, std::string_view model_text,
                                          const std::string& source_name = "<string>");

/// Everything `hipair-verify CERTIFICATE MODEL` does: reads the certificate, checks the model
/// file's SHA-256 against it, reads the model with the certificate's parameter values (which
/// must lie within their tolerances) and checks the claim. I/O failures are reported as
/// invalid with the reason.
VerificationResult verify_certificate_file(const std::filesystem::path& certificate,
                                           const std::filesystem::path& model);

}  // namespace hipair
