// The follower's coordinate on one contact curve at a fixed driver coordinate, as a function of
// the parameters: value and partial derivatives (AutoDiff, implicit differentiation), certified
// enclosures over a box of parameters (interval jets, mean-value form, subdivision) and at a
// point of the box (interval bisection). Internal to src/tolerance/ (docs/tolerance.md).
#pragma once

#include "tolerance/contact_function.hpp"
#include "tolerance/edge_memo.hpp"
#include "tolerance/hessian_jet.hpp"
#include "tolerance/jet.hpp"

#include <hipair/cspace.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::tolerance_detail {

using Interval = kernels::Interval;
using IntervalJet = Jet<Interval>;
/// Second-order jets: a jet whose value and partial derivatives are interval jets (their
/// gradients: the second partial derivatives).
/// Jets whose value and partial derivatives are first-order Taylor models over a box
/// (taylor_model.hpp): the partial derivatives over the box keep the correlation between the
/// parameters that interval jets lose (docs/tolerance.md "Taylor-model partial derivatives").
using TaylorJet = Jet<TaylorModel1>;

/// A contact curve with one coordinate held: F(fixed, free; p) = 0 solved for `free`.
struct CurveSlice {
  FeatureIdentity first, second;       ///< the feature pair (parts index Model::parts)
  std::size_t fixed_part = 0;          ///< the part whose chart coordinate is held
  std::size_t free_part = 0;           ///< the part whose chart coordinate is solved for
  bool fixed_half_turn = false, free_half_turn = false;
  Rational fixed_value;                ///< chart coordinate of the held part (exact)
  /// Assembly chains (chain.cpp): the held part's chart coordinate ranges over this enclosure
  /// instead of the point `fixed_value` (a driver moved by an earlier pair of the chain); the
  /// enclosures then hold for every held coordinate in it.
  std::optional<kernels::Interval> fixed_range;
  /// With `fixed_range`: |dv/d fixed| x its width (chart units), added to the linearised width
  /// that sizes the root's bracket and the certified band's accuracy target.
  double fixed_spread = 0;
};

/// What a curve slice needs of the geometry: the two features' edges and both parts' axes.
template <class T>
struct PairGeometry {
  model_detail::EdgeValue<T> first, second;
  kernels::Vector<T> fixed_pivot, fixed_direction, free_pivot, free_direction;
};

/// A tolerance box of deviations (per parameter, [lo, hi]).
struct Box {
  std::vector<double> lo, hi;
};

/// The two halves of `box` split at the middle of dimension `i` (lower half first).
inline std::pair<Box, Box> halves(const Box& box, std::size_t i) {
  std::pair<Box, Box> result{box, box};
  double m = 0.5 * (box.lo[i] + box.hi[i]);
  result.first.hi[i] = m;
  result.second.lo[i] = m;
  return result;
}

/// What the solver needs of the model, with geometry caches.
class CurveSolver {
 public:
  explicit CurveSolver(std::shared_ptr<const model_detail::ParametricModel> model);

  std::size_t parameters() const { return n_; }
  const Model& nominal() const { return model_->nominal(); }
  const model_detail::ParametricModel& model() const { return *model_; }

  /// dv/dp_i (chart units) at the nominal parameters, at the curve point near `free_value`;
  /// also the refined free value (Newton in double); with `fixed_slope`, also dv/d fixed there
  /// (= -F_fixed / F_free, chart units). \throws NumericError when F_free = 0.
  std::vector<double> sensitivities(const CurveSlice& curve, double& free_value, double* fixed_slope = nullptr) const;

  /// Certified enclosure of the root in `bracket` of F at the point deviations `point`
  /// (each exact as a double). Returns false when no certified sign change is found.
  bool certified_point_root(const CurveSlice& curve, const std::vector<double>& point, Interval bracket,
                            Interval& root) const;
  /// Same with the geometry already evaluated at the point.
  bool certified_point_root(const CurveSlice& curve, const std::vector<Interval>& parameters,
                            Interval bracket, Interval& root) const;
  /// Same with the curve's geometry already evaluated (point_geometry): the geometry does not
  /// depend on the held coordinate, so positions along one feature pair share it.
  /// `constant` (when given): the feature pair's contact_constant over `geometry`, made once
  /// (contact_function.hpp; the same root bit for bit).
  bool certified_point_root(const CurveSlice& curve, const PairGeometry<Interval>& geometry, Interval bracket,
                            Interval& root, const ContactConstant<Interval>* constant = nullptr) const;
  /// The sign of F at the free chart value `free` (the held coordinate `curve.fixed_value`, or
  /// `curve.fixed_range` when it ranges), the geometry evaluated (point_geometry): +1 or -1 when
  /// certain (-1: the features penetrate there), 0 for an exact zero, 2 when undecided.
  int point_sign(const CurveSlice& curve, const PairGeometry<Interval>& geometry, double free) const;
  /// The sign of the interval enclosure of the contact function over the free coordinates
  /// `free` (the held one as point_sign): +1 or -1 when certain over all of it, else 0 or 2.
  int range_sign(const CurveSlice& curve, const PairGeometry<Interval>& geometry, Interval free) const;
  /// The curve's geometry (both features, both axes) at parameter values (enclosures).
  PairGeometry<Interval> point_geometry(const CurveSlice& curve, const std::vector<Interval>& parameters) const {
    return geometry(curve, parameters);
  }
  /// Parameter values (enclosures) at point deviations.
  std::vector<Interval> point_parameters(const std::vector<double>& point) const;
  /// For measurements only (ToleranceOptions::fast_paths): false makes the jets of
  /// certified_range range over every parameter varying in the box, as before session 8.
  void set_compact_jets(bool compact) { compact_jets_ = compact; }
  /// For tests only: false tests every end sign of box_range with its own jet at the point,
  /// as before session 13, instead of the jet over the last bracket first.
  void set_reuse_y_jets(bool reuse) { reuse_y_jets_ = reuse; }
  /// Whether certified_range narrows its partial derivatives by their second-order form
  /// (default: yes). Assembly chains turn it off: their gear meshes exhaust the subdivision
  /// budget either way, and each second-order sub-box costs ~15 x a first-order one
  /// (docs/performance.md, session 20).
  void set_second_order(bool second_order) { second_order_ = second_order; }
  /// Whether certified_range narrows its partial derivatives over the box by their first-order
  /// Taylor models (TaylorJet), intersected with the interval jets' (default: no; assembly
  /// chains turn it on: docs/performance.md, session 21).
  void set_taylor_partials(bool taylor) { taylor_ = taylor; }
  /// The switches above, in the order compact jets, reused y jets, second order, Taylor partials
  /// (bit 0 .. 3): what a result of the solver depends on besides its arguments and model.
  unsigned switches() const {
    return (compact_jets_ ? 1u : 0u) | (reuse_y_jets_ ? 2u : 0u) | (second_order_ ? 4u : 0u) | (taylor_ ? 8u : 0u);
  }

  /// Certified enclosure of {v(p) : p in box} (the root near the nominal `free_value`, unique
  /// in a neighbourhood certified along the way), subdividing the box until the enclosure is
  /// within `accuracy` of the linearised width `linear_width` (absolute, chart units).
  /// Counts sub-boxes in `boxes`. \throws NumericError when it cannot certify.
  /// `free_side` (when given) receives the holder's free side where the certification proves it:
  /// each sub-box B_j's enclosure is certified with F_v of one sign s_j over B_j x the held range
  /// x its bracket y_j, which holds the root for every (p, t) there; +1 or -1 when every s_j is
  /// that sign (F_v has it at the root for every (p, t) of the box x the held range), else 0.
  Interval certified_range(const CurveSlice& curve, const Box& box, double free_value,
                           const std::vector<double>& sensitivity, double relative_accuracy,
                           double absolute_accuracy, std::size_t& boxes, int* free_side = nullptr) const;

  /// The root's partial derivatives over a region, for the mean-value composition of an
  /// assembly chain (chain.cpp; docs/tolerance.md "Assembly chains"): with F_v's sign certain
  /// over `box` x `y` (x the held range `curve.fixed_range`, when it ranges), F(p, t, .) has at
  /// most one root in `y` for every (p, t) there, and where it has one, v(p, t), the implicit
  /// function theorem gives dv/dp_i = -F_i/F_v and dv/dt = -F_t/F_v. `dp` (one per parameter)
  /// and `dt` (0 when the held coordinate is a point) enclose them over the region, chart units;
  /// the contact function's partials as in certified_range (interval jets, narrowed by the
  /// Taylor models when set_taylor_partials). A parameter varying in the box that the jets leave
  /// out (compact jets: no partial derivative at nominal) gets dp = 0 only when the geometry's
  /// partial derivatives with respect to it are exactly 0 over `whole` (a box containing `box`:
  /// interval jets over it, memoised per feature pair). `taylor` false: interval jets only
  /// (cheaper: no Taylor-model geometry). False when F_v's sign is not certain or such a
  /// parameter is not proven inert. `sign`, when given, receives F_v's sign over the region
  /// (+1 or -1) once it is certain.
  bool root_partials(const CurveSlice& curve, const Box& box, const Box& whole, const Interval& y,
                     std::vector<Interval>& dp, Interval& dt, bool taylor = true, int* sign = nullptr) const;

  /// Bounds the box-geometry memo and the Taylor-model edge memo at `entries` each (cleared
  /// when full; default BoxGeometryMemo::max_entries and TaylorEdgeMemo::max_entries). Their
  /// values are pure functions of their keys, so results are the same whatever the bound; an
  /// assembly chain (one solver per pair, each pair's sub-boxes at every position) sets a small
  /// one: docs/performance.md "Session 43 (tol43)". (The memos are shared state behind
  /// mutexes, hence const.)
  void limit_memos(std::size_t entries) const;

 private:
  template <class T>
  PairGeometry<T> geometry(const CurveSlice& curve, const std::vector<T>& parameters) const;
  /// The contact function at (fixed, free) over `geometry`; `constant` (when given) the feature
  /// pair's contact_constant over `geometry` (the same value bit for bit, made once: session 69).
  template <class T>
  T evaluate(const CurveSlice& curve, const PairGeometry<T>& geometry, const T& fixed, const T& free,
             const ContactConstant<T>* constant = nullptr) const;
  /// The feature pair's contact_constant over `geometry`, or nothing when it cannot be made (a
  /// square root T cannot take: evaluate then makes it, and throws, as before).
  /// Made for features of kinds `kinds` (the curve's own features otherwise).
  template <class T>
  std::optional<ContactConstant<T>> constant_of_pair(const CurveSlice& curve, const PairGeometry<T>& geometry,
                                                     const FeatureKind (&kinds)[2]) const;
  /// Per parameter: whether the curve's geometry (both features, both axes) has a non-zero
  /// partial derivative with respect to it at the nominal vector.
  std::vector<bool> dependencies(const CurveSlice& curve) const;
  bool box_range(const CurveSlice& curve, const Box& box, double free_value, const std::vector<double>& sensitivity,
                 double target, Interval& result, std::vector<double>& split_score, bool& taylor_used,
                 int& free_side) const;

  /// What box_range needs of the geometry over one box: it depends on the two features, the
  /// two parts and the box only, not on the held coordinate, so the positions of a zone or of
  /// the certified band along one feature pair share it (profiled: re-evaluating it, with MPFR
  /// trigonometry for angle parameters, was over half of the zones' CPU time).
  struct BoxGeometry {
    std::vector<std::size_t> active;   ///< the jets' variables (parameter indices)
    std::vector<Interval> center_parameters;
    PairGeometry<IntervalJet> jet;     ///< over the box, gradients over `active`
    PairGeometry<Interval> at_center;
    /// For the second-order partials (second_order_): the geometry at the centre with its
    /// gradient over `active`, and over the box with gradients and second derivatives.
    PairGeometry<IntervalJet> jet_at_center;
    PairGeometry<HessianJet> jet2;
    bool second_order = false;   ///< jet_at_center and jet2 hold
    /// The feature pair's contact_constant over each geometry above (session 69 (chain69): made
    /// once per box rather than at every bracket; absent when it cannot be made), for the
    /// features of kinds `constant_kinds` (the edges' own: the memo's key has no kinds, an arc
    /// and the vertex at its source sharing it).
    FeatureKind constant_kinds[2] = {FeatureKind::vertex, FeatureKind::vertex};
    std::optional<ContactConstant<IntervalJet>> jet_constant, jet_at_center_constant;
    std::optional<ContactConstant<Interval>> at_center_constant;
    std::optional<ContactConstant<HessianJet>> jet2_constant;
    /// For the Taylor-model partials (taylor_): the geometry over the box as jets of Taylor
    /// models in the box's active parameters (variables 0..k-1; the free coordinate is k, the
    /// held one k + 1).
    /// Filled on first use (taylor_geometry), once, by whichever thread needs it first.
    mutable std::once_flag taylor_once;
    mutable PairGeometry<TaylorJet> taylor;
    mutable bool has_taylor = false;   ///< `taylor` holds
    mutable std::optional<ContactConstant<TaylorJet>> taylor_constant;   ///< over `taylor`
  };
  /// The Taylor-model geometry of `memo`'s box (computed on first use); false when the Taylor
  /// models cannot follow the construction over the box.
  bool taylor_geometry(const CurveSlice& curve, const BoxGeometry& memo, const Box& box) const;
  std::shared_ptr<const BoxGeometry> box_geometry(const CurveSlice& curve, const Box& box,
                                                  const std::vector<double>& center) const;
  /// The memo of box_geometry, shared by the threads of the band and the zones (a pure
  /// function of its key, so results are the same with or without it). Bounded: cleared when
  /// it holds `max_entries`.
  struct BoxGeometryMemo {
    static constexpr std::size_t max_entries = 20000;
    std::size_t limit = max_entries;   ///< cleared when it holds this many (limit_memos)
    std::mutex mutex;
    std::map<std::vector<double>, std::shared_ptr<const BoxGeometry>> entries;
  };
  /// Narrows the partial derivatives in `f` (a jet over the box x y x the held range) by their
  /// second-order form: F_a(c, y_c, t_c) + sum_b F_ab(box, y, range) (x_b - c_b).
  void tighten_partials(const CurveSlice& curve, const BoxGeometry& memo, const Box& box,
                        const std::vector<double>& center, const Interval& fixed,
                        const std::optional<Interval>& held_offset, const Interval& y, IntervalJet& f) const;
  void tighten_partials_or_throw(const CurveSlice& curve, const BoxGeometry& memo, const Box& box,
                                 const std::vector<double>& center, const Interval& fixed,
                                 const std::optional<Interval>& held_offset, const Interval& y, IntervalJet& f) const;
  /// Narrows the partial derivatives in `f` (a jet over the box x y x the held range) to the
  /// ranges of their Taylor models over the same region, where those are narrower.
  void taylor_partials(const CurveSlice& curve, const BoxGeometry& memo, const Interval& fixed,
                       const std::optional<Interval>& held_offset, const Interval& y, IntervalJet& f) const;
  std::shared_ptr<BoxGeometryMemo> memo_ = std::make_shared<BoxGeometryMemo>();
  /// Per feature pair and box (root_partials' `whole`): the parameters whose partial
  /// derivatives of the curve's geometry are exactly 0 over the box (interval jets).
  std::vector<bool> inert(const CurveSlice& curve, const Box& whole) const;
  struct InertMemo {
    std::mutex mutex;
    std::map<std::vector<double>, std::vector<bool>> entries;
  };
  std::shared_ptr<InertMemo> inert_ = std::make_shared<InertMemo>();

  /// The box in the jets' units: each deviation divided by unit_ (exactly).
  Box in_units(const Box& box) const;
  /// Parameter values at deviations given in the jets' units (each multiplied by unit_).
  template <class T>
  std::vector<T> values(std::vector<T> deviations_in_units) const;

  std::shared_ptr<const model_detail::ParametricModel> model_;
  std::size_t n_ = 0;
  /// Per parameter, the unit of its jet variable (a power of two; 1 unless its tolerance range
  /// lies outside 2^-100 .. 2^100): certified_range and root_partials work on deviations in
  /// these units, so that partial derivatives stay within the doubles at every scale.
  std::vector<double> unit_;
  bool scaled_units_ = false;
  /// Nominal parameter values with their gradient over (p, v). A jet of doubles rather than
  /// Eigen's AutoDiffScalar: the kernels mix constants (no gradient) into nested expressions,
  /// which AutoDiffScalar's dynamic-size gradients do not reconcile.
  std::vector<Jet<double>> autodiff_;
  /// The Taylor-model edges and axes over boxes (taylor_geometry), shared by the threads.
  std::shared_ptr<TaylorEdgeMemo> edges_;
  bool compact_jets_ = true;
  bool reuse_y_jets_ = true;
  bool second_order_ = true;
  bool taylor_ = false;
};

/// Half-angle tangent chart value -> part coordinate (rad), certified: c + 2 atan(t).
Interval chart_to_angle(const Interval& t, bool half_turn);

}  // namespace hipair::tolerance_detail
