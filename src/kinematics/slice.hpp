// Slices of a pair's C-space for kinematic analysis (internal).
//
// A slice fixes one part of a pair (the "other" part, e.g. the driver) at an exact rational
// chart value and returns the 1-D C-space of the remaining part (the "follower"): the exact
// contact points along the follower's axis (real algebraic numbers, with the feature pairs that
// touch there) and the class of every interval between them (free / blocked / touching).
//
// Two slicers implement the same interface:
// - the C-space slicer reads the built hipair::CSpace (its contact edges and cells);
// - the kernel slicer substitutes the driver value into the pair's contact polynomials and
//   classifies the intervals with the exact overlap oracle. It needs no arrangement, so it is
//   fast and is also the cross-check of the C-space slicer.
#pragma once

#include "algebra/exact_real.hpp"
#include "core/thread_switch.hpp"
#include "curves/contact_curves.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace hipair::kinematics_detail {

using cspace::ChartAxis;
using cspace::IntegerPolynomial2;
using cspace::algebra::Real;

/// A feature pair that can touch, identified across the charts of a pair.
struct ContactFeature {
  std::string label;             ///< "driver pin / wheel slot 2 wall"
  ContactKind kind = ContactKind::vertex_segment;
  /// The exact feature pair (the pair's first and second part's features), when the slicer has
  /// one for the label (the kernel slicer); part == no_index otherwise.
  FeatureIdentity first, second;
};

/// Interval classes of a slice.
enum class SliceKind : int { empty = -1, free = 0, blocked = 1, touching = 2 };

/// A contact point of a slice in one follower chart.
struct SlicePoint {
  Real value;                          ///< follower chart coordinate (t or mm), exact
  std::vector<std::size_t> features;   ///< indices into PairSlicer::features()
  /// Blocked on both sides, but the parts only touch at the point itself (decided exactly): a
  /// zero-clearance fit, the follower's whole free range there. Other points with the same
  /// class on both sides are curves through blocked (or free) space, not contacts, except the
  /// kernel slicer's undecided ones (SliceClassCounts::touching_undecided). A point blocked on
  /// both sides whose value is rational is held exact by the kernel slicer.
  bool touching = false;
  /// Blocked on both sides and its touching not decided (the kernel slicer counted it in
  /// SliceClassCounts::touching_undecided): a slice read off a wider one counts its own.
  bool undecided = false;
};

/// The slice of one follower chart over [covered_lo, covered_hi] (the whole chart unless a
/// window was asked for): points ascending, and the classes of the intervals between them
/// (kinds[i] is the interval before points[i], kinds.back() after the last).
struct ChartSlice {
  std::vector<SlicePoint> points;
  std::vector<SliceKind> kinds;
  Rational covered_lo, covered_hi;
};

/// A part of a follower chart to slice (chart coordinates).
struct ChartWindow {
  Rational lo, hi;
};

/// The 1-D C-spaces of one part of a pair, sliced at positions of the other part.
class PairSlicer {
 public:
  virtual ~PairSlicer() = default;

  /// "first:second" as the pair is declared in the model.
  const std::string& name() const { return name_; }
  std::size_t follower() const { return follower_; }   ///< model part index
  std::size_t other() const { return other_; }         ///< model part index
  bool other_moves() const { return other_moves_; }
  /// Charts of the follower axis and of the other part's axis (empty when it is fixed).
  const std::vector<ChartAxis>& follower_charts() const { return follower_charts_; }
  const std::vector<ChartAxis>& other_charts() const { return other_charts_; }
  const std::vector<ContactFeature>& features() const { return features_; }

  /// The slice of follower chart `follower_chart` with the other part at chart value `value`
  /// of its chart `other_chart` (both ignored when the other part is fixed).
  virtual ChartSlice slice(std::size_t other_chart, const Rational& value, std::size_t follower_chart,
                           const ChartWindow* window = nullptr) const = 0;

  /// The polynomial of `feature` in the chart pair, with variables ordered (other, follower):
  /// c[i][j] of other^i follower^j; nullptr when the feature has no curve in that chart pair.
  virtual const IntegerPolynomial2* polynomial(std::size_t other_chart, std::size_t follower_chart,
                                               std::size_t feature) const = 0;

 protected:
  std::string name_;
  std::size_t follower_ = 0, other_ = 0;
  bool other_moves_ = false;
  std::vector<ChartAxis> follower_charts_, other_charts_;
  /// mutable: a slicer may number features as it meets them (numbers never change)
  mutable std::vector<ContactFeature> features_;
};

/// Options of the kernel slicer.
/// The feature-pair selections (CurveGenerator::select) of the strips generated so far, shared
/// by the kernel slicers of one analysis: a slicer whose pair is exactly congruent to one
/// already sliced (equal CurveGenerator::congruence_key: one pair a translate of the other)
/// reuses that pair's selection for the same chart box and forms only its own curves (the
/// idler train's meshes: 8 meshes, 2 congruence classes). Keys are compared in full (exact
/// strings, no hash decides). Thread safe.
///
/// Whole strips too (session 23): a strip's curves in chart coordinates (the contact
/// polynomials and validity clauses, integer polynomials made primitive) and the follower cells
/// where each may vanish depend on the pair only through its congruence key, so a congruent
/// pair's strip for the same chart pair, the same cells and the same follower takes that strip
/// as it is (its labels are its own: written from the strip's feature pairs and its own parts).
struct KernelStrip;   // kernel_slice.cpp
class SelectionMemo {
 public:
  using Selection = std::vector<std::pair<int, int>>;
  /// The selection stored under `key`, or nullptr.
  std::shared_ptr<const Selection> find(const std::string& key) const;
  /// Stores `selection` under `key` (the first one stored stays) and returns the stored one.
  std::shared_ptr<const Selection> add(const std::string& key, Selection selection);
  std::size_t hits() const;
  /// The strip stored under `key`, or nullptr.
  std::shared_ptr<const KernelStrip> find_strip(const std::string& key) const;
  /// Stores `strip` under `key` (the first one stored stays) and returns the stored one.
  std::shared_ptr<const KernelStrip> add_strip(const std::string& key, std::shared_ptr<const KernelStrip> strip);
  std::size_t strip_hits() const;
  /// Counts a slicer of a pair with congruence key `key` (each kernel slicer of the analysis
  /// once, when it is made); congruent(key): how many were counted. A slicer whose pair has no
  /// congruent partner culls its strips lazily (KernelSlicerOptions::lazy_cull) and shares none.
  void count_congruence(const std::string& key);
  std::size_t congruent(const std::string& key) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::size_t> congruence_counts_;
  std::map<std::string, std::shared_ptr<const Selection>> selections_;
  std::map<std::string, std::shared_ptr<const KernelStrip>> strips_;
  mutable std::size_t hits_ = 0, strip_hits_ = 0;
};

struct KernelSlicerOptions {
  /// Generate a chart pair's curves per strip of the other part's axis (1/64 of its chart) on
  /// the strip's first slice, with the generator's blocked-space cull on the strip's box; false:
  /// the whole chart pair on its first slice (the slicer before session 12; tests compare the
  /// two). The slices agree except for points inside certified blocked space (blocked on both
  /// sides, not touching), which a strip's finer cull may drop.
  bool strips = true;
  /// Decide a root's validity clauses at its isolating interval before refining it (the same
  /// verdict: interval evaluation is inclusion isotone); false: refine first (tests compare).
  bool validity_prefilter = true;
  /// Read an interval's class at the shared end of its two points' isolating intervals when they
  /// meet end to end, instead of refining both for rational_between's sample (the class is the
  /// same anywhere inside the interval); false: rational_between always (tests compare).
  bool shared_end_samples = true;
  /// Shared selections of congruent pairs (see SelectionMemo); nullptr: every slicer runs its
  /// own generator's cull.
  std::shared_ptr<SelectionMemo> selections;
  /// Carry an interval's class over from the previous slice of the same chart pair instead of
  /// asking the overlap oracle, when it is proven the same: the interval's sample s lies
  /// strictly inside an interval of the previous slice (exact comparisons), and no curve of the
  /// strips covering the driver interval between the two slices' values can vanish on the
  /// segment {driver in that interval} x {s} (certified interval enclosures, with the strips'
  /// cull cells). The segment then meets no contact configuration, so its class is constant.
  /// When the proof fails the oracle decides as before. false: the oracle always (tests compare).
  bool transfer_classes = true;
  /// Most curve enclosures one carried class's proof evaluates before the oracle decides
  /// instead; 0: from the pair (session 33), max(32, the edges of both parts) — the oracle
  /// poses every edge of both parts, a proof's enclosure costs a few dozen double operations,
  /// and a gear pair's sample meets a few hundred curves (a cap of 32 carried no gear class).
  /// Each enclosure is taken of the curve collapsed once per slice over the driver interval.
  std::size_t proof_curves = 0;
  /// Isolate the roots of a curve on a run of follower cells without Descartes when the
  /// enclosure of its follower derivative over (value, run) excludes zero: the curve is then
  /// strictly monotone there, so it has a root exactly when its signs at the run's ends differ
  /// (certified enclosures first, exact signs when they hold zero), and the run isolates it.
  /// The same roots with other isolating intervals (the engine reads nothing that depends on
  /// them: rational_near and truncated_double are functions of the number). false: Descartes
  /// on every run (tests compare).
  bool monotone_runs = true;
  /// Cull a strip's curves (the curve generator's blocked-space cull) only over the follower
  /// cells the slices ask for (their windows: the cells meeting the sliced range), extending
  /// the cull when a later slice asks for cells not culled yet (CurveGenerator::Selection: the
  /// same quadtree cells, walked part by part). A strip then holds the curves of the whole
  /// strip's selection that survive in a culled cell, so a slice holds the same points but
  /// those of curves certified blocked throughout the culled cells (points with blocked space
  /// on both sides, no zero-clearance fit), and a carried class is proven only at samples in
  /// cells culled in every strip of its proof. Not for pairs with a congruent partner in
  /// `selections` (those share whole strips). false: the whole follower chart on a strip's
  /// first slice (tests compare the two).
  bool lazy_cull = true;
};

/// Per-thread switch of KernelSlicerOptions::monotone_runs for the slicers constructed on this
/// thread (on by default; tests turn it off to compare whole analyses with and without it).
struct MonotoneRunsTag;
inline bool& monotone_runs_switch() { return thread_switch<MonotoneRunsTag>(); }
/// Per-thread switch of KernelSlicerOptions::transfer_classes for the slicers constructed on
/// this thread (on by default; tests turn it off to compare whole analyses with the oracle's).
struct TransferClassesTag;
inline bool& transfer_classes_switch() { return thread_switch<TransferClassesTag>(); }

/// How a kernel slicer decided its interval classes so far: by the overlap oracle, or carried
/// over from the previous slice (KernelSlicerOptions::transfer_classes). For tests.
struct SliceClassCounts {
  std::size_t classified = 0, transferred = 0;
  std::size_t monotone_roots = 0;   ///< roots isolated by a monotone run (KernelSlicerOptions::monotone_runs)
  /// Slice points with blocked space on both sides whose touching was not decided: an irrational
  /// root of two or more contacts, or of one contact whose polynomial keeps its sign there (the
  /// point is reported blocked, SlicePoint::touching false; the analysis warns).
  std::size_t touching_undecided = 0;
  /// Follower cells whose blocked-space cull the slicer's strips ran, summed over its strips
  /// (a strip culled whole counts all of its chart's cells; KernelSlicerOptions::lazy_cull).
  std::size_t strip_cells_culled = 0;
  /// Runs of follower cells whose roots the validity clauses decided before any was sought
  /// (KernelSlicerOptions::validity_prefilter, over the whole run): all rejected, all kept.
  std::size_t runs_rejected = 0, runs_kept = 0;
};
/// Zero counts for a slicer that is not a kernel slicer.
SliceClassCounts kernel_slice_class_counts(const PairSlicer& slicer);
/// Adds `delta` (of either sign) to a kernel slicer's SliceClassCounts::touching_undecided (no
/// effect on another slicer): a slice read off a wider one instead of being taken counts its
/// undecided points as the slicer would have, and a wider slice taken only to be read off does
/// not count its own (kinematics_detail::ChartSliceMemo).
void add_touching_undecided(const PairSlicer& slicer, long delta);

/// Slicer on the pair's contact kernels and the exact overlap oracle.
/// `pair` indexes model.pairs; `follower` is one of its parts (it must move). Features are
/// numbered canonically: (feature of the pair's first part, feature of its second part), each in
/// the order of its part's boundary (loop, edge, the vertex before the edge's curve), so the
/// numbers do not depend on which slices were taken first; features() holds an entry (empty
/// label) for every number below the largest met.
/// \throws GeometryError for pairs that are not fixed-axis pairs.
std::unique_ptr<PairSlicer> make_kernel_slicer(const Model& model, std::size_t pair,
                                               std::size_t follower, const KernelSlicerOptions& options = {});

/// Slicer on a built C-space of the same pair (src/cspace/slice.cpp). Falls back to nothing:
/// \throws GeometryError when the C-space cannot be sliced along the requested axis.
std::unique_ptr<PairSlicer> make_cspace_slicer(const Model& model, const CSpace& space,
                                               std::size_t pair, std::size_t follower);

/// Transposes a bivariate polynomial (swaps x and y).
IntegerPolynomial2 transposed(const IntegerPolynomial2& polynomial);

}  // namespace hipair::kinematics_detail
