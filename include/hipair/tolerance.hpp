// HIPAIR — kinematic tolerance analysis of a driven pair (docs/tolerance.md; the paper's
// section "Kinematic tolerance analysis").
//
// The nominal motion comes from the kinematic analysis and the nominal C-space (through its
// public adaptor: slices with their feature pairs). Along it, each contact curve is
// re-instantiated over the parametric model, so that the follower's position and its partial
// derivatives with respect to every parameter are known at every driver position:
//   - sensitivity tables per contact region (the paper's Table 1), ranked;
//   - the variation of the kinematic function: worst case (linearised, as the paper), root sum
//     of squares (statistical), and certified worst case (interval arithmetic over the whole
//     tolerance box, subdivided until within the requested accuracy: no linearisation error);
//   - contact zones (the paper's Figure 5), linearised and certified;
//   - Monte Carlo validation (seedable, reproducible, parallel), against both bands;
//   - the jamming threshold: the smallest uniform scaling of the tolerances at which the free
//     channel can close, confirmed by an exact C-space built at the worst-case parameters;
//   - contacts that appear or disappear under tolerance (a contact curve that does not bound the
//     nominal channel but does for some parameters in the box, or the reverse), found from
//     certified enclosures over the box and confirmed by an exact C-space at a witness vector.
// No CGAL types.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hipair {

/// Options of a tolerance analysis.
struct ToleranceOptions {
  /// Parameters whose nominal values are replaced before the analysis (`hipair tolerance --set`):
  /// the design as changed, each `tolerance` about the new nominal and a `range` where it is
  /// (ReadOptions::overrides_set_nominal). A value outside the parameter's tolerance range needs
  /// `allow_out_of_tolerance`. Tolerance certificates are not produced with overrides (they are
  /// checked against the model file as written, about its nominal values).
  std::map<std::string, Rational> parameter_values;
  bool allow_out_of_tolerance = false;
  std::string driver;                  ///< driven part ("" = the first moving part of the pair)
  std::string follower;                ///< "" = the other part of the driver's first pair
  /// Driver range (rad or mm); absent: one full turn from the initial angle.
  std::optional<std::pair<Rational, Rational>> range;
  /// Density of the driver positions (the kinematic analysis' grid, steps_per_cycle): a rotating
  /// driver gets `positions` per full turn (equal steps of at most 2 pi / positions over the
  /// range, so a quarter turn gets about a quarter of them), a translating driver `positions`
  /// equal steps along its range; at least 8. The range's start is a position too.
  std::size_t positions = 360;
  std::size_t monte_carlo = 0;         ///< Monte Carlo samples (0: none)
  std::uint64_t seed = 1;
  unsigned threads = 0;                ///< Monte Carlo, certified band, zones (0: hardware concurrency)
  bool threshold = false;              ///< search the jamming threshold
  /// With `threshold` and > 0: bracket the threshold by bisection of the scale until the
  /// bracket's relative width is at most this (docs/tolerance.md "The threshold, bracketed"):
  /// an exact jam witness at the upper end, confirmed by an exact C-space there.
  double threshold_bracket = 0;
  /// Parameters varied by the threshold search (empty: every toleranced parameter).
  std::vector<std::string> threshold_parameters;
  /// Certified band: subdivide the tolerance box until the certified enclosure is at most this
  /// much (relative) wider than the linearised worst case, or `absolute_accuracy` (part units).
  double relative_accuracy = 0.1;
  double absolute_accuracy = 1e-9;
  std::size_t zone_samples = 24;       ///< abscissae per contact edge for the contact zones
  std::function<void(double)> progress;   ///< fraction done, from the calling thread
  /// Produce a no-jam tolerance certificate (docs/certify.md "Tolerance"): for every parameter
  /// vector in `certify_scale` x the tolerance box of the varied parameters (those of the
  /// threshold search: `threshold_parameters`, or every toleranced one), over the driver range,
  /// the follower's channel never closes. Proved by interval branch-and-bound.
  bool certify = false;
  Rational certify_scale = 1;
  /// With `threshold`: the scale is `certify_scale` times the linearised jamming threshold found
  /// (rounded down to 4 significant digits).
  bool certify_relative_to_threshold = false;
  std::size_t certify_max_leaves = 20000;   ///< undecided beyond this many leaves
  /// Accept a leaf only when the verifier's check 7 also proves its witness path free over the
  /// leaf's box (else split it): certificates whose free path the verifier proves (`valid`)
  /// where the plain search writes `unproven` ones (docs/tolerance.md, session 17).
  bool certify_free_path = false;
  /// A leaf whose named sides checks 1-6 prove apart from their slopes alone, without a witness
  /// follower path (check 7 cannot start there), is split along the driver instead of accepted,
  /// at most this many times along a branch; beyond, it is accepted and the certificate is
  /// `unproven`, its reason naming that leaf (docs/tolerance.md, sessions 67 and 71).
  std::size_t certify_witness_splits = 6;
  /// Look for contacts that appear or disappear under tolerance (ToleranceResult::contact_changes).
  bool contact_changes = false;
  /// Exact C-spaces built to confirm them (one per change, the largest linearised first).
  std::size_t contact_change_confirmations = 4;
  /// For measurements only (tests/perf/tolerance_benchmark.cpp): false takes the paths of
  /// session 7 (interval jets over every parameter varying in the box; the contact curve's
  /// geometry evaluated again at every Monte Carlo position). Same results either way.
  bool fast_paths = true;
  /// Assembly chains: each pair's certified enclosure over a box narrows its partial
  /// derivatives over the box by first-order Taylor models of the parametric geometry
  /// (docs/tolerance.md "Taylor-model partial derivatives"). false: interval jets only, as
  /// before session 21 (for measurements and tests). Sound either way.
  bool taylor_partials = true;
  /// Assembly chains: the certified band's composition over a box is also done in mean-value
  /// form, the output at the box's centre plus its total derivatives over the box (the chain
  /// rule over each pair's -F_p/F_v and -F_t/F_v) times the box's half widths, intersected with
  /// the interval composition (docs/tolerance.md "Assembly chains", session 22). false: the
  /// interval composition only, as before (for measurements and tests). Sound either way.
  bool mean_value_chain = true;
  /// Assembly chain (docs/tolerance.md "Assembly chains"): analyse the output of the chain of
  /// pairs driver -> part -> ... -> `follower` (or the chain's last moving part) instead of one
  /// pair; the per-pair kinematic functions and sensitivities are composed by the chain rule.
  /// Not combined with `threshold`, `certify` or `contact_changes` (ModelError); no zones.
  bool chain = false;
  /// Assembly chains: follow, in each pair, the feature pair touching at the nominal position
  /// over the whole tolerance box, without the hand-over envelope (docs/tolerance.md
  /// "Hand-overs"). The band is then certified only under that assumption, which the result's
  /// notes state: another feature pair taking over inside the box (the next tooth pair of a gear
  /// mesh near a hand-over) is not enclosed. Off by default: the certified band encloses every
  /// feature pair that may hold the follower inside the box, and is unbounded where one cannot
  /// be enclosed or excluded (today: every gear mesh).
  bool chain_assume_nominal_holder = false;
  /// Assembly chains: where a position's composition over the tolerance box cannot be
  /// certified (a pair's root, its free side, or a hand-over candidate not decided over the
  /// driver range its predecessors give it), the box is bisected along the parameter that spreads
  /// the failing pair's follower most, into at most this many sub-boxes per position; beyond, the
  /// band there is unbounded (docs/tolerance.md, sessions 42 and 72; `--chain-split-budget`).
  /// Any partition of the box is sound: a larger budget can only bound more positions, at a cost
  /// paid only where a composition fails. 4 (the value of sessions 42-71) at least.
  std::size_t chain_failure_boxes = 4;
};

/// One pair of an assembly chain (ToleranceResult::chain).
struct ChainStage {
  std::string driver, follower;
  bool driver_rotates = true, follower_rotates = true;
  std::size_t contact_positions = 0;   ///< chain positions at which this pair holds its follower
  std::size_t certified_boxes = 0;     ///< sub-boxes of this pair's certified enclosures
};

/// One parameter's share of the variation in a contact region.
struct ParameterContribution {
  std::string parameter;
  double sensitivity = 0;     ///< d follower / d parameter at the region's largest contribution
  double contribution = 0;    ///< |sensitivity| x half the tolerance width (part units)
  double share = 0;           ///< contribution / sum of contributions (0..1)
};

/// A contact region of the nominal path: consecutive driver positions with one feature pair.
struct ContactRegion {
  std::string contact;        ///< "driver pin / wheel slot 1 wall R"
  FeatureIdentity first, second;
  double driver_start = 0, driver_end = 0;   ///< driver coordinate (rad or mm)
  std::size_t first_sample = 0, last_sample = 0;
  std::vector<ParameterContribution> ranked;   ///< largest first
  double linear_half_width = 0;                ///< max over the region (part units)
};

/// The follower at one driver position.
struct VariationSample {
  double driver = 0;
  bool contact = false;
  std::size_t region = no_index;       ///< index into ToleranceResult::regions
  double nominal = 0;                  ///< follower coordinate (rad or mm)
  double linear_lower = 0, linear_upper = 0;   ///< worst case, linearised (absolute)
  double rss_lower = 0, rss_upper = 0;         ///< mean -+ 3 sigma (absolute)
  CertifiedRange certified;            ///< certified worst case (absolute)
  double play = -1;                    ///< nominal width of the free channel (-1: unbounded)
  bool has_monte_carlo = false;
  double monte_carlo_min = 0, monte_carlo_max = 0;
  /// In contact: d follower / d parameter (part units per parameter unit, Model::parameters
  /// order) at the nominal parameters; for an assembly chain, composed by the chain rule.
  std::vector<double> sensitivities;
};

/// A contact zone: a contact edge of the nominal C-space between its bounds over the box.
struct ContactZone {
  std::string contact;
  std::size_t edge = no_index;         ///< edge id in the nominal C-space
  bool x_rotates = true, y_rotates = true;   ///< rad (true) or mm
  std::vector<double> x;               ///< x part coordinate (rad or mm)
  std::vector<double> nominal;         ///< y part coordinate
  std::vector<double> linear_lower, linear_upper;
  std::vector<double> certified_lower, certified_upper;
};

struct MonteCarloSummary {
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  std::size_t evaluations = 0;         ///< follower positions computed (certified each)
  /// Certified values outside the certified band: a defect of the band, must be 0.
  std::size_t outside_certified = 0;
  /// Positions where no value could be certified (no certain sign change of the follower's
  /// contact function found, even by the wider search): the Monte Carlo's own failure, not a
  /// value outside the band; not among `evaluations` (docs/tolerance.md "Monte Carlo").
  std::size_t not_certified = 0;
  /// Certified values whose enclosure meets an edge of the certified band (session 63): neither
  /// certainly inside nor certainly outside it, counted on their own (among `evaluations`), never
  /// as inside or outside. The root's enclosure is first narrowed at the edge by the contact
  /// function's certain sign there.
  std::size_t undecided_certified = 0;
  std::size_t outside_linear = 0;      ///< positions beyond the linearised band
  double linearisation_error = 0;      ///< largest excess beyond the linearised band (part units)
  double seconds = 0;
  double cpu_seconds = 0;              ///< CPU time of all threads over the Monte Carlo
};

struct JammingThreshold {
  bool found = false;
  double scale = 0;                    ///< linearised: tolerances x scale close the channel
  double driver = 0;                   ///< where (driver coordinate)
  std::string lower_contact, upper_contact;   ///< the channel's two sides there
  double nominal_play = 0;
  double certified_open_scale = 0;     ///< certified: at tolerances x this, never closed there
  double confirmed_scale = 0;          ///< the exact build's scale
  std::vector<std::pair<std::string, Rational>> worst_values;   ///< parameter values, exact
  bool confirmed = false;              ///< the exact C-space shows the closed channel
  std::string evidence;                ///< what the exact build shows
  /// With ToleranceOptions::threshold_bracket: the corner search over the driver range found
  /// no jam at tolerances x `bracket_below` and an exact jam witness at x `bracket_above` (the
  /// varied parameters at `bracket_values`, the driver at `bracket_driver`; the upper side's
  /// root in `bracket_upper`, below the lower side's in `bracket_lower`: certain sign changes).
  /// `bracket_below` is not a proof; a no-jam certificate at that scale is (`--certify`).
  bool bracketed = false;
  Rational bracket_below, bracket_above, bracket_driver;
  std::vector<std::pair<std::string, Rational>> bracket_values;
  RationalInterval bracket_lower, bracket_upper;
  double bracket_play_below = 0;       ///< narrowest corner channel at `bracket_below` (approximate)
  std::size_t bracket_steps = 0;
  bool bracket_confirmed = false;      ///< the exact C-space at the witness shows the closed channel
  std::string bracket_evidence;
};

/// A contact that appears or disappears for some parameter vector of the tolerance box
/// (docs/tolerance.md "Contacts that appear or disappear").
struct ContactChange {
  /// appears: `contact` bounds no side of the nominal channel anywhere along the path, but at
  /// `witness` it overtakes the nominal side `other` and bounds the channel. disappears: the
  /// nominal side `contact` is overtaken by `other` at every driver position where it bounds
  /// the nominal channel, so at `witness` it bounds the channel nowhere along the path.
  enum class Kind { appears, disappears } kind = Kind::appears;
  std::string contact, other;          ///< feature pair labels
  bool lower_side = true;              ///< the channel's side concerned (lower: below the follower)
  double driver_first = 0, driver_last = 0;   ///< driver positions (rad or mm) where it can happen
  std::size_t positions = 0;           ///< how many analysed positions
  double driver = 0;                   ///< the witness position (largest linearised overshoot)
  double overshoot = 0;                ///< linearised: how far past `other` at the witness (part units)
  /// Certified at the witness vector and position: both roots isolated by interval bisection,
  /// in reversed order (true), or only the linearised model predicts it (false).
  bool certified_at_witness = false;
  std::vector<std::pair<std::string, Rational>> witness;   ///< toleranced parameters' values (exact)
  bool confirmed = false;              ///< the exact C-space at `witness` shows it
  std::size_t confirmed_positions = 0; ///< analysed positions at which the exact slices show it
  std::string evidence;
};

/// The search for contacts that appear or disappear (ToleranceOptions::contact_changes).
struct ContactChangeCheck {
  std::size_t positions = 0;           ///< driver positions with a channel checked
  std::size_t candidates = 0;          ///< (position, contact curve beyond a side) pairs examined
  std::size_t excluded = 0;            ///< certified: cannot reach the side over the whole box there
  std::size_t possible = 0;            ///< enclosures overlap: the linearised worst corner tried
  std::size_t undecided = 0;           ///< an enclosure could not be computed
  std::size_t switch_shifts = 0;       ///< overtaken by a pair bounding the channel elsewhere on the path
  std::vector<ContactChange> changes;
  double seconds = 0;
};

/// The outcome of the tolerance certificate's branch-and-bound.
struct ToleranceCertification {
  /// certified: `certificate` holds the certificate; its evidence passed the verifier's code
  /// (re-checked from its JSON text): the named contact sides stay apart. The claim "no jam" is
  /// proved when the verifier's check 7 also proves a free follower path across the range
  /// (verdict "valid"); otherwise `unproven` below is true and `reason` says what was not proved.
  /// jams: at a parameter vector of the box the two sides of the channel certainly cross
  /// (`reason` names it); undecided: neither (budget exhausted, a side not isolated, ...).
  /// interferes (no_interference certificates): at `witness` the exact model's parts overlap.
  enum class Outcome { certified, jams, undecided, interferes } outcome = Outcome::undecided;
  std::optional<Certificate> certificate;
  std::string reason;
  /// interferes: an exact witness — deviations of the varied parameters (exact rationals; the
  /// others nominal), the driver's and the follower's exact positions (rotation: tangent of the
  /// half angle; translation: offset), at which the exact model (ParametricModel::exact_model,
  /// the reader's own steps) has the two parts' interiors overlapping (exact predicate).
  std::vector<std::pair<std::string, Rational>> witness_parameters;
  std::optional<ExactPosition> witness_driver, witness_follower;
  /// jams: the driver coordinate (rad or mm, exact) at which, with the parameters at
  /// `witness_parameters`, the channel's upper side (its root certified in `witness_upper` by a
  /// certain sign change of its contact function) lies below the lower side (`witness_lower`).
  std::optional<Rational> witness_coordinate;
  std::optional<RationalInterval> witness_lower, witness_upper;
  Rational scale;
  std::size_t leaves = 0, attempts = 0;
  std::size_t second_order_leaves = 0;   ///< leaves proved by the second-order witness test
  double seconds_produce = 0, seconds_verify = 0;
  /// certified: the verifier's verdict on the certificate is "unproven" (check 7 did not prove a
  /// free follower path), not "valid".
  bool unproven = false;
};

/// Everything the tolerance analysis found.
struct ToleranceResult {
  std::string model_name;
  /// The lengths of the result (a translating part's coordinates, bands, plays and sensitivities
  /// of a translating follower, its zones) are in units of 10^length_exponent mm: nonzero for a
  /// mechanism drawn at an extreme scale, analysed on the model divided exactly by 10^E (session
  /// 54; 0, mm, for every ordinary model). The reports show them in mm.
  long length_exponent = 0;
  std::string driver, follower;
  bool driver_rotates = true, follower_rotates = true;
  std::vector<Parameter> parameters;
  std::vector<double> sigma;            ///< per parameter, as used (0: untoleranced)
  std::vector<double> mean_shift;       ///< per parameter: mean deviation of its distribution
  std::vector<ContactRegion> regions;
  std::vector<VariationSample> samples;
  std::vector<ContactZone> zones;
  std::optional<MonteCarloSummary> monte_carlo;
  std::vector<std::vector<double>> monte_carlo_curves;   ///< a few sampled kinematic functions
  std::optional<JammingThreshold> threshold;
  double certified_excess = 0;          ///< largest (certified - linearised) width, part units
  std::size_t certified_boxes = 0;      ///< sub-boxes used by the certified bands
  double seconds_sensitivity = 0, seconds_certified = 0, seconds_zones = 0, seconds_threshold = 0;
  /// CPU time of the process (all threads) during the certified band and the zones.
  double cpu_seconds_certified = 0, cpu_seconds_zones = 0;
  std::optional<ToleranceCertification> certification;   ///< with ToleranceOptions::certify
  std::optional<ContactChangeCheck> contact_changes;     ///< with ToleranceOptions::contact_changes
  /// With ToleranceOptions::chain: the pairs from the driver to the output part (`follower`), in
  /// order; the samples, regions (one per tuple of the pairs' contacts) and bands are the output's.
  std::vector<ChainStage> chain;
  std::vector<std::string> notes;
  /// The budgets and options that bound the result, as used (tolerance.json's `budgets`,
  /// session 72): name and value, e.g. the certified band's relative accuracy, a chain's sub-box
  /// budgets, a certificate's leaf and witness-split budgets.
  std::vector<std::pair<std::string, double>> budgets;
  /// Assembly chains: held positions whose band is unbounded after the failure split used its
  /// whole budget (`ToleranceOptions::chain_failure_boxes`): a larger budget may bound them.
  std::size_t chain_budget_exhausted = 0;
};

/// What a "never interferes" tolerance certificate claims (docs/certify.md "Tolerance", property
/// no_interference): for every vector of the varied parameters within `scale` x their tolerance
/// ranges (the others nominal, derived ones following their expressions), every driver
/// coordinate in `driver_range` and every follower coordinate in `follower_range` (rad or mm:
/// the operating configuration set), the two parts are apart (closed parts disjoint).
struct InterferenceCertifyOptions {
  std::string driver, follower;               ///< part names (each rotating or translating)
  RationalInterval driver_range, follower_range;
  Rational scale = 1;
  std::vector<std::string> vary;              ///< varied parameters; empty: every toleranced one
  std::size_t max_leaves = 20000;             ///< undecided beyond this many leaves
};

/// Interval branch-and-bound over parameters x driver x follower; a certificate returned has been
/// re-checked by the verifier's code from its JSON text. Outcome `interferes` comes with an exact
/// witness. \throws ModelError (unknown parts or parameters, bad ranges), IoError.
ToleranceCertification certify_no_interference(const std::filesystem::path& model_file,
                                               const InterferenceCertifyOptions& options);
ToleranceCertification certify_no_interference_text(std::string_view json_text, const InterferenceCertifyOptions& options,
                                                    const std::string& source_name = "<string>");

/// Runs the analysis of `model_file`. \throws ModelError, GeometryError, IoError.
ToleranceResult analyze_tolerances(const std::filesystem::path& model_file, const ToleranceOptions& options = {});
ToleranceResult analyze_tolerances_text(std::string_view json_text, const ToleranceOptions& options = {});

std::string tolerance_text_report(const ToleranceResult& result);
std::string tolerance_json_report(const ToleranceResult& result);
/// Per driver position: nominal, linearised, RSS, certified and Monte Carlo bounds.
std::string tolerance_csv(const ToleranceResult& result);
/// Sensitivity tables as CSV: region, parameter, sensitivity, contribution, share.
std::string tolerance_sensitivity_csv(const ToleranceResult& result);
/// The kinematic function's variation band (deviation from nominal) with the Monte Carlo envelope.
std::string tolerance_band_svg(const ToleranceResult& result);
/// The contact-zone detail (Figure 5): one zone's bounds about its nominal curve.
std::string tolerance_zone_svg(const ToleranceResult& result);

}  // namespace hipair
