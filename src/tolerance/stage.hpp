// One pair of an assembly chain, analysed at driver positions given by the chain's nominal motion
// (chain.cpp; docs/tolerance.md "Assembly chains"): the pair's part of the single-pair analysis
// (analysis.cpp: the exact slice of the pair's nominal C-space at each position, the feature pair
// holding the follower, its parametric contact curve and sensitivities). Internal to
// src/tolerance/.
#pragma once

#include "tolerance/sampling.hpp"
#include "tolerance/solver.hpp"

#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hipair::tolerance_detail {

/// How the analysis reads the model: with the options' nominal overrides (the changed design).
inline ReadOptions design_read_options(const ToleranceOptions& options) {
  ReadOptions read;
  read.parameter_values = options.parameter_values;
  read.allow_out_of_tolerance = options.allow_out_of_tolerance;
  read.overrides_set_nominal = true;
  return read;
}

/// The parametric form a tolerance analysis runs on (session 54): `form` itself, or for a
/// mechanism drawn at an extreme scale (kinematic_decimal_exponent of its nominal model nonzero:
/// lengths outside about 1e-9 .. 1e9 mm with a translating part, 1e-9 .. 1e18 mm rotating only)
/// form.rescaled(E), the model divided exactly by 10^E: the analysis then runs in units of
/// 10^E mm, as `hipair analyze` does, and a model written at 10^E times an ordinary one is
/// analysed as that one (ToleranceResult::length_exponent). \throws ModelError as rescaled().
/// Tolerance certificates of such a model: for a pair whose parts both rotate, written at the
/// file's scale (session 56); refused by the analysis when a part translates.
std::shared_ptr<const model_detail::ParametricModel> analysed_form(model_detail::ParametricModel form,
                                                                    const ToleranceOptions& options);

/// The options' driver range in the unit of a form rescaled by 10^exponent: a translating
/// driver's mm divided by 10^exponent exactly, a rotating one's rad unchanged.
std::optional<std::pair<Rational, Rational>> range_in_unit(const ToleranceOptions& options, bool driver_rotates,
                                                           long exponent);

/// The pair's two parts at one position of the chain's nominal motion (part coordinates, rad or
/// mm, as KinematicSample::positions gives them).
struct StagePosition {
  double driver = 0, follower = 0;
  bool contact = false;   ///< the exact kinematic engine found the follower touching the driver
};

/// The follower at one position: the contact curve holding it (its fixed_value the driver's
/// exact chart coordinate) and dv/dp in chart units.
struct StageContact {
  bool contact = false;
  CurveSlice curve;
  std::string label;            ///< the feature pair's label
  double v = 0;                 ///< follower chart coordinate on the curve
  bool follower_half = false;   ///< the follower's chart is the half-turn one
  std::vector<double> s_chart;
};

struct StageAnalysis {
  ToleranceResult result;       ///< the pair's samples with linearised and RSS bands, regions
  std::vector<StageContact> contacts;   ///< per position
  std::shared_ptr<const CurveSolver> solver;
  std::vector<Distribution> distributions;
  Box box;                      ///< the tolerance box rounded outwards
};

/// Chart enclosure -> part coordinate enclosure (rad or mm), unwrapped near `near` (rotations).
kernels::Interval to_part(const kernels::Interval& chart, bool rotates, bool half, double near);
/// d part coordinate / d chart coordinate at chart value t.
double chart_slope(double t, bool rotates);

/// The linearised worst case and the mean -+ 3 sigma band of `sample` (about its nominal) from
/// the sensitivities `s` (part units per parameter). Returns the worst case's (lower, upper)
/// deviations.
std::pair<double, double> linear_bands(VariationSample& sample, const std::vector<double>& s,
                                       const std::vector<Distribution>& distributions);
/// Sample k joins the last region of `result` (same label and feature pair, consecutive) or
/// starts one; each parameter's contribution |s_i| x half its tolerance width is kept at its
/// largest over the region.
void extend_regions(ToleranceResult& result, std::size_t k, const std::string& label, const FeatureIdentity& first,
                    const FeatureIdentity& second, const std::vector<double>& s,
                    const std::vector<Distribution>& distributions, double half_width);
/// Shares of the contributions, ranked (largest first), in every region.
void rank_regions(ToleranceResult& result);
/// One Monte Carlo vector's values along the path, counted against the bands.
struct MonteCarloOutcome {
  std::vector<double> value;   ///< part coordinate per driver position (NaN: not evaluated)
  std::size_t outside_certified = 0, outside_linear = 0, evaluations = 0;
  std::size_t not_certified = 0;   ///< positions without a certified value (not among evaluations)
  /// certified values whose enclosure meets the certified band's edge: neither inside nor outside
  std::size_t undecided_certified = 0;
  double excess = 0;           ///< largest excess beyond the linearised band
  /// The value at position k (certified enclosure `value`, part units): outside the certified
  /// band (its enclosure apart from the band), undecided against it (meeting an edge), or
  /// beyond the linearised band.
  void record(std::size_t k, const kernels::Interval& value, const VariationSample& sample);
  /// The value at position k (part units), against the linearised band only.
  void record_linear(std::size_t k, double value, const VariationSample& sample);
};
/// The outcomes into the summary and the samples' Monte Carlo envelopes (the first 12 curves
/// kept).
void merge_monte_carlo(const std::vector<MonteCarloOutcome>& outcomes, MonteCarloSummary& summary,
                       ToleranceResult& result);

/// task(0 .. count-1) on `threads` threads (0: hardware concurrency); each task writes its own
/// slot, so results do not depend on the number of threads.
void parallel_for(unsigned threads, std::size_t count, const std::function<void(std::size_t)>& task);
/// The same, with done(n) called on the calling thread as tasks finish (n tasks finished, never
/// decreasing; the last call says count), for a progress bar.
void parallel_for(unsigned threads, std::size_t count, const std::function<void(std::size_t)>& task,
                  const std::function<void(std::size_t)>& done);

/// Tests only (session 67): the certified band's per-position results of a chain analysis, kept
/// for a later analysis of the same model text with the same options and switches in the same
/// process (ChainPaths::band_memo): the kernel path and its C-space lookup, compared bit for bit
/// (tolerance_chain_kernel_test.cpp), compute the same bands from the same inputs. A position is
/// replayed only where every input of its band is the same bit for bit (chain.cpp certified():
/// each pair's contact curve, chart values, sensitivities and slopes there, the output's
/// sensitivities, each pair's tolerance box and solver switches); an analysis of another text,
/// other options or switches clears it first. Positions are computed and stored under `mutex`.
struct ChainBandMemo {
  /// What certified() computed at one position.
  struct Position {
    bool ok = false;                          ///< bounded
    double lower = 0, upper = 0;              ///< the band (when ok)
    std::vector<kernels::Interval> charts;    ///< each pair's certified chart enclosure (when ok)
    std::vector<std::size_t> boxes;           ///< each pair's sub-box count at the position
    std::size_t shared_boxes = 0, failure_boxes = 0;
    bool exhausted = false;                   ///< the failure split ran out of budget (session 72)
    bool extended = false;                    ///< a hand-over envelope widened
    std::string why;                          ///< why an envelope was not bounded
  };
  std::string run;   ///< the text, options and switches the positions belong to
  std::map<std::string, Position> positions;   ///< by the position's inputs, bit for bit
  std::size_t replayed = 0;                    ///< positions replayed (tests: not vacuous)
  std::mutex mutex;
};

/// How a chain finds each pair's nominal motion and touching feature pairs (chain.cpp).
struct ChainPaths {
  /// Chains whose parts all rotate without angle limits (gear trains): the whole model's
  /// kinematics sliced from the contact kernels (no C-space build) and, per pair, the touching
  /// feature pair named exactly by the kinematic engine at each position; a pair's C-space is
  /// built (and the pair analysed as before) only where that feature pair is not unique. False:
  /// every pair's C-space built (the path before session 13; tests compare the two).
  bool kernel_kinematics = true;
  /// Tests only, with kernel_kinematics: every pair analysed on its built C-space (analyze_stage)
  /// at the kernel kinematics' positions: the C-space lookup on the same nominal motion.
  bool cspace_lookup = false;
  /// Tests only: applied to each contact the kernel path looked up (stage, position), so that a
  /// test can check that a wrong lookup is caught.
  std::function<void(std::size_t, std::size_t, CurveSlice&)> mutate_lookup;
  /// Tests only: the Monte Carlo's parameter vector `index` (deviations, each in the tolerance
  /// box) instead of draw(seed, index), so that a test can place vectors at the box's corners.
  std::function<std::vector<double>(std::size_t)> monte_carlo_vector;
  /// Tests only: each Monte Carlo value (vector index, driver position, the output's certified
  /// enclosure in part units).
  std::function<void(std::size_t, std::size_t, const kernels::Interval&)> monte_carlo_value;
  /// Tests only: false skips the certified band and the Monte Carlo (the samples' certified
  /// fields not computed), for a test that compares only the nominal motion, the contacts, the
  /// sensitivities, the linearised bands and the regions, which are computed before them.
  bool certified_band = true;
  /// Tests only: the certified band's positions kept and replayed across analyses
  /// (ChainBandMemo); null: none.
  std::shared_ptr<ChainBandMemo> band_memo;
};

/// Entries of each chain pair's box-geometry and Taylor-model edge memos (CurveSolver::limit_memos;
/// 1000 unless changed). The memos hold pure functions of their keys, so every value gives the
/// same bands (tests/unit/tolerance_chain_memo_test.cpp sets it to compare); read when a chain
/// analysis starts.
std::size_t& chain_memo_entries();

/// The case split at a chain's last widened pair (chain.cpp compose_over, docs/tolerance.md
/// "Assembly chains", "The case split at a widened mesh"; session 45): 1 (on) unless changed; 0
/// gives the composition without it (tests compare the two).
int& chain_case_split();

/// Where the whole box composes only through a widened hand-over envelope, beyond the
/// linearised width: its halves composed too and the band the meet of both (chain.cpp; session
/// 48): 1 (on) unless changed; 0 accepts the whole box's band as before (tests compare the two).
int& chain_widened_split();

/// Session 73: in the passes that compose a failed position again (the far walk's and the driver
/// pieces', chain.cpp certified()), each pair's enclosure over box x T narrowed to the hull of its
/// driver range's pieces' where that hull lies inside it (chain.cpp compose_once, held_pieces): 2
/// (tried at every pair) unless changed; 0 keeps the whole-T enclosure alone, as before session 73;
/// 1 skips it where the whole-T enclosure already meets certified_range's accuracy target (session
/// 74's default; session 75 measured no CPU saved by the skip and bands it gave up, and made 2 the
/// default again; tests compare the three).
int& chain_driver_piece_meet();

/// Session 74: how many pair enclosures the driver-piece meet above has narrowed (the hull
/// strictly inside the whole-T enclosure), over the process (tests read differences).
std::atomic<std::size_t>& chain_driver_piece_meets();

/// A position's plain compositions (no far walk, no driver pieces) of its sub-boxes kept for its
/// later passes, the far walk's and the driver pieces' (chain.cpp certified(); session 53), whose
/// first step per sub-box is the same plain composition: 1 (on) unless changed; 0 composes them
/// again (tests compare the two: the same bands, notes and sub-box counts).
int& chain_plain_reuse();

/// The case split's two cases resume from the state the composition recorded at the widened pair
/// (chain.cpp compose_once, Prefix; session 67) instead of computing pairs 0 .. that pair again,
/// exactly as the composition did: 1 (on) unless changed; 0 computes them again (tests compare
/// the two: the same bands, notes and sub-box counts).
int& chain_case_resume();
/// Tests only: the case split's cases resumed so (chain_case_resume), summed over every chain
/// analysis since the program started.
std::atomic<std::size_t>& chain_cases_resumed();

/// Tests only: compose_over calls the certified band's passes have made (the plain ones not
/// replayed, and the far walk's), summed over every chain analysis since the program started.
std::atomic<std::size_t>& chain_compositions_made();

/// The analysis of an assembly chain (ToleranceOptions::chain; chain.cpp). With `exponents`, for
/// a chain analysed at an extreme scale (ToleranceResult::length_exponent not 0), its parameters'
/// scale exponents (model_detail::parameter_scale_exponents of the analysed form every pair ran
/// on), else left empty: the form the chain read, not read again (session 70).
ToleranceResult analyze_chain(std::string_view text, const ToleranceOptions& options, const ChainPaths& paths = {},
                              std::vector<long>* exponents = nullptr);

/// The pair (options.driver, options.follower) of the model `text` at `path`; `space`, when
/// given, is the pair's nominal C-space (built by the caller for the same model text), not built
/// again. \throws ModelError, GeometryError.
StageAnalysis analyze_stage(std::string_view text, const ToleranceOptions& options,
                            const std::vector<StagePosition>& path, const CSpace* space = nullptr);
/// analyze_stage on `model`, the parametric form of `text` read with design_read_options(options)
/// (the chain's, recorded once for all its pairs): the model not read again.
StageAnalysis analyze_stage(std::string_view text, std::shared_ptr<const model_detail::ParametricModel> model,
                            const ToleranceOptions& options, const std::vector<StagePosition>& path,
                            const CSpace* space = nullptr);

}  // namespace hipair::tolerance_detail
