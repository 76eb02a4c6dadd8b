// Contact-curve solver over the parametric model (solver.hpp).
#include "tolerance/solver.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace hipair::tolerance_detail {

using model_detail::Arithmetic;
using model_detail::AutoDiff;

CurveSolver::CurveSolver(std::shared_ptr<const model_detail::ParametricModel> model)
    : model_(std::move(model)), n_(model_->parameter_count()), edges_(std::make_shared<TaylorEdgeMemo>(model_)) {
  std::vector<Jet<double>> deviations(n_);
  for (std::size_t i = 0; i < n_; ++i) deviations[i] = Jet<double>::variable(0.0, i, n_ + 1);
  autodiff_ = model_->parameter_values(deviations);
  // The jets' variable of a parameter whose tolerance range is far from 1 (a raw length of
  // 1e-300 mm: width 2^-1000) is its deviation in units of a power of two near that width
  // (session 65; the analysis of a model drawn at 1e-300 mm in units of 1e-300 mm reads such a
  // parameter times 1e300 in each length slot, so the second partial derivatives with respect to
  // the deviation are about 1e600: they overflowed the doubles and the second-order partials never
  // narrowed the band, 43 596 sub-boxes against 6 840 at 1 mm). Exact: a power of two scales a
  // deviation without rounding. Every ordinary range (widths 2^-100 .. 2^100) keeps unit 1.
  unit_.assign(n_, 1.0);
  for (std::size_t i = 0; i < n_; ++i) {
    const Parameter& parameter = model_->nominal().parameters[i];
    const Rational width = parameter.range.hi - parameter.range.lo;
    if (sgn(width) <= 0) continue;
    const long e = static_cast<long>(mpz_sizeinbase(width.get_num_mpz_t(), 2)) -
                   static_cast<long>(mpz_sizeinbase(width.get_den_mpz_t(), 2));
    if (std::labs(e) > 100 && std::labs(e) <= 1020) {
      unit_[i] = std::ldexp(1.0, static_cast<int>(e));
      scaled_units_ = true;
    }
  }
}

namespace {
// The constant c (exact in doubles) as each number type the solver evaluates.
template <class T>
T constant_of(double c);
template <>
Interval constant_of<Interval>(double c) { return Interval::point(c); }
template <>
IntervalJet constant_of<IntervalJet>(double c) { return IntervalJet(Interval::point(c)); }
template <>
HessianJet constant_of<HessianJet>(double c) { return HessianJet(Interval::point(c)); }
template <>
TaylorJet constant_of<TaylorJet>(double c) { return TaylorJet(TaylorModel1(Interval::point(c))); }
// The kind of the feature an edge is when it is not a vertex.
template <class T>
FeatureKind edge_kind(const model_detail::EdgeValue<T>& e) {
  return e.arc ? FeatureKind::arc : FeatureKind::segment;
}
// A box geometry's memoised contact constant as evaluate's argument for `curve` (nullptr: evaluate
// makes it). The geometry memo is keyed by the features' edges, not their kinds (a vertex is the
// source of its edge: an arc and its first vertex share the geometry), and the constant is made
// for the edges' own kinds (CurveSolver::constant_of_pair): a curve of other kinds (one with a
// vertex, which has no constant) makes its own.
template <class T>
const ContactConstant<T>* made(const std::optional<ContactConstant<T>>& c, const FeatureKind (&kinds)[2],
                               const CurveSlice& curve) {
  return c && curve.first.kind == kinds[0] && curve.second.kind == kinds[1] ? &*c : nullptr;
}
}  // namespace

Box CurveSolver::in_units(const Box& box) const {
  if (!scaled_units_) return box;
  Box u = box;
  for (std::size_t i = 0; i < n_; ++i) {
    u.lo[i] = box.lo[i] / unit_[i];   // exact: a power of two, within the doubles' normal range
    u.hi[i] = box.hi[i] / unit_[i];
  }
  return u;
}

template <class T>
std::vector<T> CurveSolver::values(std::vector<T> u) const {
  if (scaled_units_)
    for (std::size_t i = 0; i < n_; ++i)
      if (unit_[i] != 1.0) u[i] = T(u[i] * constant_of<T>(unit_[i]));
  return model_->parameter_values(u);
}

template <class T>
PairGeometry<T> CurveSolver::geometry(const CurveSlice& curve, const std::vector<T>& p) const {
  PairGeometry<T> g;
  g.first = model_->edge_value(curve.first.part, curve.first.loop, curve.first.edge, p);
  g.second = model_->edge_value(curve.second.part, curve.second.loop, curve.second.edge, p);
  model_->motion_value(curve.fixed_part, p, g.fixed_pivot, g.fixed_direction);
  model_->motion_value(curve.free_part, p, g.free_pivot, g.free_direction);
  return g;
}

template <class T>
std::optional<ContactConstant<T>> CurveSolver::constant_of_pair(const CurveSlice& curve, const PairGeometry<T>& g,
                                                                const FeatureKind (&kinds)[2]) const {
  // for the features of kinds `kinds` (the edges' own, not the curve's: see made())
  FeatureIdentity first = curve.first, second = curve.second;
  first.kind = kinds[0];
  second.kind = kinds[1];
  try {
    return contact_constant(g.first, first, g.second, second);
  } catch (const NumericError&) {
    return std::nullopt;   // evaluate makes it, and throws, at each evaluation as before
  }
}

template <class T>
T CurveSolver::evaluate(const CurveSlice& curve, const PairGeometry<T>& g, const T& fixed, const T& free,
                        const ContactConstant<T>* constant) const {
  const Model& m = nominal();
  kernels::Pose<T> fixed_pose =
      pose_of(m.parts[curve.fixed_part].motion, g.fixed_pivot, g.fixed_direction, fixed, curve.fixed_half_turn);
  kernels::Pose<T> free_pose =
      pose_of(m.parts[curve.free_part].motion, g.free_pivot, g.free_direction, free, curve.free_half_turn);
  const kernels::Pose<T>& a = curve.first.part == curve.fixed_part ? fixed_pose : free_pose;
  const kernels::Pose<T>& b = curve.second.part == curve.fixed_part ? fixed_pose : free_pose;
  if (constant) return contact_function(g.first, curve.first, a, g.second, curve.second, b, *constant);
  return contact_function(g.first, curve.first, a, g.second, curve.second, b);
}

std::vector<double> CurveSolver::sensitivities(const CurveSlice& curve, double& free_value, double* fixed_slope) const {
  using Dual = Jet<double>;
  Dual fixed = fixed_slope ? Dual::variable(curve.fixed_value.get_d(), n_ + 1, n_ + 2) : Dual(curve.fixed_value.get_d());
  Dual f;
  double fv = 0;
  PairGeometry<Dual> g = geometry(curve, autodiff_);
  for (int iteration = 0; iteration < 4; ++iteration) {
    f = evaluate<Dual>(curve, g, fixed, Dual::variable(free_value, n_, n_ + 1));
    fv = f.partial(n_);
    if (!(std::fabs(fv) > 0)) throw NumericError("the contact curve is singular here (F_y = 0)");
    double step = f.value / fv;
    free_value -= step;
    if (std::fabs(step) < 1e-15 * (1 + std::fabs(free_value))) break;
  }
  std::vector<double> s(n_);
  for (std::size_t i = 0; i < n_; ++i) s[i] = -f.partial(i) / fv;
  if (fixed_slope) *fixed_slope = -f.partial(n_ + 1) / fv;
  return s;
}

std::vector<Interval> CurveSolver::point_parameters(const std::vector<double>& point) const {
  std::vector<Interval> deviations(n_);
  for (std::size_t i = 0; i < n_; ++i) deviations[i] = Interval::point(point[i]);
  return model_->parameter_values(deviations);
}

bool CurveSolver::certified_point_root(const CurveSlice& curve, const std::vector<double>& point, Interval bracket,
                                       Interval& root) const {
  return certified_point_root(curve, point_parameters(point), bracket, root);
}

bool CurveSolver::certified_point_root(const CurveSlice& curve, const std::vector<Interval>& parameters,
                                       Interval bracket, Interval& root) const {
  return certified_point_root(curve, geometry(curve, parameters), bracket, root);
}

int CurveSolver::point_sign(const CurveSlice& curve, const PairGeometry<Interval>& geometry, double free) const {
  Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  return evaluate<Interval>(curve, geometry, fixed, Interval::point(free)).sign();
}

int CurveSolver::range_sign(const CurveSlice& curve, const PairGeometry<Interval>& geometry, Interval free) const {
  Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  return evaluate<Interval>(curve, geometry, fixed, free).sign();
}

bool CurveSolver::certified_point_root(const CurveSlice& curve, const PairGeometry<Interval>& geometry,
                                       Interval bracket, Interval& root, const ContactConstant<Interval>* constant) const {
  Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  auto sign_at = [&](double v) { return evaluate<Interval>(curve, geometry, fixed, Interval::point(v), constant).sign(); };
  double a = bracket.lo, b = bracket.hi;
  int sa = sign_at(a), sb = sign_at(b);
  if (sa == 2 || sb == 2 || sa == 0 || sb == 0 || sa == sb) return false;
  for (int i = 0; i < 64; ++i) {
    double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    int s = sign_at(m);
    if (s == 2 || s == 0) {
      // Too close to the root for a certain sign: narrow each end separately (a keeps the
      // sign sa, b the sign sb; points of uncertain sign count as the other side).
      double a2 = m, b2 = m;
      double lo = a, hi = m;
      for (int j = 0; j < 64 && 0.5 * (lo + hi) > lo && 0.5 * (lo + hi) < hi; ++j) {
        double c = 0.5 * (lo + hi);
        if (sign_at(c) == sa) lo = c; else hi = c;
      }
      a2 = lo;
      lo = m;
      hi = b;
      for (int j = 0; j < 64 && 0.5 * (lo + hi) > lo && 0.5 * (lo + hi) < hi; ++j) {
        double c = 0.5 * (lo + hi);
        if (sign_at(c) == sb) hi = c; else lo = c;
      }
      b2 = hi;
      a = a2;
      b = b2;
      break;
    }
    if (s == sa) a = m; else b = m;
  }
  root = Interval(a, b);
  return true;
}

std::vector<bool> CurveSolver::dependencies(const CurveSlice& curve) const {
  PairGeometry<Jet<double>> g = geometry(curve, autodiff_);
  std::vector<bool> depends(n_, false);
  auto mark = [&](const Jet<double>& x) {
    for (std::size_t i = 0; i < n_ && i < x.gradient.size(); ++i) depends[i] = depends[i] || x.gradient[i] != 0;
  };
  auto mark_vector = [&](const kernels::Vector<Jet<double>>& v) {
    mark(v.x);
    mark(v.y);
  };
  for (const model_detail::EdgeValue<Jet<double>>* e : {&g.first, &g.second}) {
    mark_vector(e->source);
    mark_vector(e->target);
    mark_vector(e->center);
    mark(e->radius_squared);
  }
  for (const kernels::Vector<Jet<double>>* v : {&g.fixed_pivot, &g.fixed_direction, &g.free_pivot, &g.free_direction})
    mark_vector(*v);
  return depends;
}

bool CurveSolver::box_range(const CurveSlice& curve, const Box& box, double free_value,
                            const std::vector<double>& sensitivity, double target, Interval& result,
                            std::vector<double>& split_score, bool& taylor_used, int& free_side) const {
  std::vector<double> center(n_);
  double spread = 0, shift = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    center[i] = 0.5 * (box.lo[i] + box.hi[i]);
    spread += std::fabs(sensitivity[i]) * (box.hi[i] - box.lo[i]);
    shift += sensitivity[i] * center[i];
  }
  spread += curve.fixed_spread;
  double slack = 1e-12 * (1 + std::fabs(free_value));
  std::shared_ptr<const BoxGeometry> memo = box_geometry(curve, box, center);
  const std::vector<std::size_t>& active = memo->active;
  std::size_t k = active.size();   // the free coordinate's index
  // A held coordinate ranging over an enclosure (assembly chains) enters in mean-value form too:
  // the root is taken at its midpoint t_c, and F_t over the box times (range - t_c) is added
  // (plain interval evaluation over the range would lose the dependence of the pose's sine and
  // cosine on it).
  CurveSlice at_mid = curve;
  std::optional<Interval> held_offset;
  if (curve.fixed_range) {
    double mid = curve.fixed_range->middle();
    at_mid.fixed_range = Interval::point(mid);
    held_offset = Interval::point(curve.fixed_range->lo) - Interval::point(mid);
    held_offset = kernels::hull(*held_offset, Interval::point(curve.fixed_range->hi) - Interval::point(mid));
  }
  Interval root;
  double w0 = spread + slack;
  bool found = false;
  // Where the linearised spread vanishes (a position where no parameter moves the follower to
  // first order: an eccentric cam at its dead centre) the root still moves to second order,
  // so the brackets keep growing up to `cap` rather than four or six times from the slack.
  const double cap = 1e-3 * (1 + std::fabs(free_value));
  for (int attempt = 0; (attempt < 4 || w0 <= cap) && !found; ++attempt, w0 *= 4)
    found = certified_point_root(at_mid, memo->at_center, Interval(free_value + shift - w0, free_value + shift + w0), root,
                                 made(memo->at_center_constant, memo->constant_kinds, curve));
  if (!found) return false;
  // Geometry over the box as interval jets (values and partial derivatives over the box), and
  // at its centre as intervals. F over the box at a fixed v is enclosed in mean-value form:
  // F(c, v) + sum_i F_i(B, v) (B_i - c_i), far tighter than plain interval evaluation.
  const PairGeometry<IntervalJet>& jet = memo->jet;
  const PairGeometry<Interval>& at_center = memo->at_center;
  Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  // the held coordinate is the jets' variable k + 1 when it ranges (its partial: F_t)
  IntervalJet fixed_jet = held_offset ? IntervalJet::variable(fixed, k + 1, k + 2) : IntervalJet(fixed);
  Interval fixed_at_mid = held_offset ? *at_mid.fixed_range : fixed;
  // F(c, v) + sum_i F_i (B_i - c_i) with the partials of `f`, a jet containing F_i(B, v).
  auto mean_value_sign = [&](double v, const IntervalJet& f) {
    Interval value = evaluate<Interval>(curve, at_center, fixed_at_mid, Interval::point(v), made(memo->at_center_constant, memo->constant_kinds, curve));
    for (std::size_t a = 0; a < k; ++a) {
      std::size_t i = active[a];
      value = value + f.partial(a) * Interval(box.lo[i] - center[i], box.hi[i] - center[i]);
    }
    if (held_offset) value = value + f.partial(k + 1) * *held_offset;
    return value.sign();
  };
  // The last jet over B x Y of `enclose`: its partials contain F_i(B, v) for every v in Y, so a
  // sign over the box at an end of a narrower Y' inside Y is tried with them first (a certain
  // sign there is certain); the jet at the point v only when that is undecided.
  // With the Taylor models (use_taylor), that jet's partials are narrowed to theirs
  // (taylor_partials) only when a sign needs them: a sign certain with the wider partials is the
  // same sign with the narrower ones (the mean-value sum is inclusion isotone), so the Taylor
  // models are evaluated once a sign is undecided without them or the bracket is certified
  // (enclose), never for a bracket whose end signs fail anyway; the answers are those of
  // narrowing first.
  std::optional<IntervalJet> over_y;
  Interval over_y_range;
  bool over_y_narrowed = true;   // over_y's partials are what enclose uses (narrowed when use_taylor)
  bool use_taylor = false;
  auto narrow_over_y = [&] {
    if (over_y_narrowed) return;
    taylor_partials(curve, *memo, fixed, held_offset, over_y_range, *over_y);
    over_y_narrowed = true;
  };
  auto sign_over_box = [&](double v) {
    if (reuse_y_jets_ && over_y && over_y_range.lo <= v && v <= over_y_range.hi) {
      int s = mean_value_sign(v, *over_y);
      if (s == 1 || s == -1) return s;
      if (!over_y_narrowed) {
        narrow_over_y();
        s = mean_value_sign(v, *over_y);
        if (s == 1 || s == -1) return s;
      }
    }
    return mean_value_sign(v, evaluate<IntervalJet>(curve, jet, fixed_jet, IntervalJet(Interval::point(v)), made(memo->jet_constant, memo->constant_kinds, curve)));
  };
  auto offset = [&](std::size_t i) {   // B_i - c_i, outward rounded
    return Interval::point(box.lo[i]) - Interval::point(center[i]);
  };
  auto upper_offset = [&](std::size_t i) { return Interval::point(box.hi[i]) - Interval::point(center[i]); };
  // The mean-value enclosure over B x Y when Y is certified to hold exactly one root for every
  // p in B (end signs opposite, F_v of one sign); false otherwise.
  bool use_second = false;
  auto enclose = [&](const Interval& y, Interval& out) {
    if (reuse_y_jets_) {
      // its partials serve the end signs of Y itself first
      over_y = evaluate<IntervalJet>(curve, jet, fixed_jet, IntervalJet::variable(y, k, held_offset ? k + 2 : k + 1),
                                     made(memo->jet_constant, memo->constant_kinds, curve));
      over_y_range = y;
      over_y_narrowed = !use_taylor;
    }
    int s_lo = sign_over_box(y.lo);
    int s_hi = sign_over_box(y.hi);
    if (s_lo == 2 || s_hi == 2 || s_lo == 0 || s_hi == 0 || s_lo == s_hi) return false;
    IntervalJet f;
    if (reuse_y_jets_) {
      narrow_over_y();
      f = *over_y;
    } else {
      f = evaluate<IntervalJet>(curve, jet, fixed_jet, IntervalJet::variable(y, k, held_offset ? k + 2 : k + 1),
                                made(memo->jet_constant, memo->constant_kinds, curve));
      if (use_taylor) taylor_partials(curve, *memo, fixed, held_offset, y, f);
    }
    if (use_second) tighten_partials(curve, *memo, box, center, fixed, held_offset, y, f);
    Interval fv = f.partial(k);
    int s = fv.sign();
    if (s != 1 && s != -1) return false;
    // (every certified bracket of this box holds its roots: all give the same sign)
    free_side = s;
    Interval enclosure = root;
    split_score.assign(n_, 0.0);
    for (std::size_t a = 0; a < k; ++a) {
      std::size_t i = active[a];
      Interval g = -(f.partial(a) / fv);
      enclosure = enclosure + g * kernels::hull(offset(i), upper_offset(i));
      split_score[i] = g.width() * (box.hi[i] - box.lo[i]);
    }
    if (held_offset) enclosure = enclosure + (-(f.partial(k + 1) / fv)) * *held_offset;
    out = Interval(std::max(enclosure.lo, y.lo), std::min(enclosure.hi, y.hi));
    return true;
  };
  // Taylor models from the start (assembly chains): when no bracket Y is certified with the
  // interval jets' partials (an end's sign over the box or F_v's sign undecided: a wide held
  // range, the chain's seventh gear mesh; docs/performance.md session 22), the same brackets
  // again with the partials narrowed by the Taylor models. Enclosures certified at first order
  // are as before.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      if (use_taylor || !taylor_ || !taylor_geometry(curve, *memo, box)) break;
      use_taylor = true;
      taylor_used = true;
    }
    double r = 0.75 * spread + slack;
    for (int attempt = 0; attempt < 6 || r <= cap; ++attempt, r *= 3) {
      Interval y(root.lo - r, root.hi + r);
      if (!enclose(y, result)) continue;
      // Contract: the enclosure itself (slightly widened) as the next Y gives tighter derivative
      // bounds; keep the last certified enclosure.
      for (int contraction = 0; contraction < 3; ++contraction) {
        double pad = 1e-3 * result.width() + slack;
        Interval narrower(result.lo - pad, result.hi + pad);
        if (!(narrower.width() < 0.9 * y.width())) break;
        Interval next;
        if (!enclose(narrower, next)) break;
        y = narrower;
        result = next;
      }
      // Taylor models (assembly chains; once the first-order contraction has settled, and only
      // when its enclosure is wider than `target`): the partial derivatives over B x Y narrowed to
      // the ranges of their first-order Taylor models, which keep the correlation between the
      // parameters that the interval jets lose; then contracted again.
      if (taylor_ && result.width() > target && taylor_geometry(curve, *memo, box)) {
        use_taylor = true;
        taylor_used = true;
        Interval next;
        if (enclose(y, next)) {
          result = Interval(std::max(result.lo, next.lo), std::min(result.hi, next.hi));
          for (int contraction = 0; contraction < 3; ++contraction) {
            double pad = 1e-3 * result.width() + slack;
            Interval narrower(result.lo - pad, result.hi + pad);
            if (!(narrower.width() < 0.9 * y.width())) break;
            if (!enclose(narrower, next)) break;
            y = narrower;
            result = Interval(std::max(result.lo, next.lo), std::min(result.hi, next.hi));
          }
        }
      }
      // Second order (once the first-order contraction has settled, and only when its enclosure is
      // wider than `target`, the accuracy certified_range asks for): the partial derivatives over
      // the box from their values at the centre and the second derivatives over the box, which
      // the box's width multiplies; each of a dozen wide parameters widens every first-order
      // partial (the dependency problem), far less so their second-order forms.
      // One contraction: a second pass would evaluate the checked, narrower Y again, the same
      // enclosure as the check's (already intersected), and stop for want of progress.
      if (memo->second_order && result.width() > target) {
        use_second = true;
        Interval next;
        if (enclose(y, next)) {
          Interval narrower_result(std::max(result.lo, next.lo), std::min(result.hi, next.hi));
          if (narrower_result.lo <= narrower_result.hi) {
            bool progress = narrower_result.width() < 0.9 * result.width();
            result = narrower_result;
            double pad = 1e-3 * result.width() + slack;
            Interval narrower(result.lo - pad, result.hi + pad);
            Interval check;
            // the narrower Y must hold the root for the box too
            if (progress && narrower.width() < 0.9 * y.width() && enclose(narrower, check))
              result = Interval(std::max(result.lo, check.lo), std::min(result.hi, check.hi));
          }
        }
      }
      return true;
    }
  }
  return false;
}

void CurveSolver::limit_memos(std::size_t entries) const {
  {
    std::lock_guard<std::mutex> lock(memo_->mutex);
    memo_->limit = entries;
    if (memo_->entries.size() >= entries) memo_->entries.clear();
  }
  edges_->set_limit(entries);
}

std::shared_ptr<const CurveSolver::BoxGeometry> CurveSolver::box_geometry(const CurveSlice& curve, const Box& box,
                                                                         const std::vector<double>& center) const {
  std::vector<double> key{static_cast<double>(curve.first.part),  static_cast<double>(curve.first.loop),
                          static_cast<double>(curve.first.edge),  static_cast<double>(curve.second.part),
                          static_cast<double>(curve.second.loop), static_cast<double>(curve.second.edge),
                          static_cast<double>(curve.fixed_part),  static_cast<double>(curve.free_part),
                          compact_jets_ ? 1.0 : 0.0};
  key.insert(key.end(), box.lo.begin(), box.lo.end());
  key.insert(key.end(), box.hi.begin(), box.hi.end());
  {
    std::lock_guard<std::mutex> lock(memo_->mutex);
    auto found = memo_->entries.find(key);
    if (found != memo_->entries.end()) return found->second;
  }
  auto g = std::make_shared<BoxGeometry>();
  // The jets' variables: the parameters varying in the box that the curve's geometry (its two
  // features and the two parts' axes) depends on, then the free coordinate. A varying parameter
  // left out (no partial derivative of any of those coordinates at nominal: one the two
  // features do not depend on) enters as its whole range, in plain interval arithmetic, both at
  // the "centre" and in the jets: the enclosures stay valid whatever it does, and are the same
  // as with it as a variable when the geometry does not depend on it. Fewer variables: shorter
  // gradients in every jet operation.
  std::vector<bool> depends = compact_jets_ ? dependencies(curve) : std::vector<bool>(n_, true);
  std::vector<std::size_t>& active = g->active;
  for (std::size_t i = 0; i < n_; ++i)
    if (box.hi[i] > box.lo[i] && depends[i]) active.push_back(i);
  std::size_t k = active.size();   // the free coordinate's index
  std::vector<Interval> center_deviations(n_);
  std::vector<IntervalJet> jets(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    bool varies = box.hi[i] > box.lo[i];
    center_deviations[i] = varies && !depends[i] ? Interval(box.lo[i], box.hi[i]) : Interval::point(center[i]);
    jets[i] = IntervalJet(varies ? Interval(box.lo[i], box.hi[i]) : Interval::point(box.lo[i]));
  }
  for (std::size_t a = 0; a < k; ++a)
    jets[active[a]] = IntervalJet::variable(Interval(box.lo[active[a]], box.hi[active[a]]), a, k + 1);
  if (second_order_) {
    std::vector<IntervalJet> at_center(n_);
    std::vector<HessianJet> jets2(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      at_center[i] = IntervalJet(center_deviations[i]);
      jets2[i] = HessianJet(jets[i]);
    }
    for (std::size_t a = 0; a < k; ++a) {
      std::size_t i = active[a];
      at_center[i] = IntervalJet::variable(Interval::point(center[i]), a, k + 1);
      jets2[i] = HessianJet::variable(Interval(box.lo[i], box.hi[i]), a, k + 1);
    }
    try {
      g->jet_at_center = geometry(curve, values(at_center));
      g->jet2 = geometry(curve, values(jets2));
      g->second_order = true;
    } catch (const NumericError&) {
      // a construction that is not twice differentiable over the box: first order only
    }
  }
  g->center_parameters = values(center_deviations);
  g->jet = geometry(curve, values(jets));
  g->at_center = geometry(curve, g->center_parameters);
  // the feature pair's contact constants (session 69), for the edges' own kinds
  g->constant_kinds[0] = edge_kind(g->jet.first);
  g->constant_kinds[1] = edge_kind(g->jet.second);
  g->jet_constant = constant_of_pair(curve, g->jet, g->constant_kinds);
  g->at_center_constant = constant_of_pair(curve, g->at_center, g->constant_kinds);
  if (g->second_order) {
    g->jet_at_center_constant = constant_of_pair(curve, g->jet_at_center, g->constant_kinds);
    g->jet2_constant = constant_of_pair(curve, g->jet2, g->constant_kinds);
  }
  std::lock_guard<std::mutex> lock(memo_->mutex);
  if (memo_->entries.size() >= memo_->limit) memo_->entries.clear();
  return memo_->entries.emplace(std::move(key), std::move(g)).first->second;
}

void CurveSolver::tighten_partials(const CurveSlice& curve, const BoxGeometry& memo, const Box& box,
                                   const std::vector<double>& center, const Interval& fixed,
                                   const std::optional<Interval>& held_offset, const Interval& y, IntervalJet& f) const {
  try {
    tighten_partials_or_throw(curve, memo, box, center, fixed, held_offset, y, f);
  } catch (const NumericError&) {
    // not twice differentiable over this region: the first-order partials stand
  }
}

void CurveSolver::tighten_partials_or_throw(const CurveSlice& curve, const BoxGeometry& memo, const Box& box,
                                            const std::vector<double>& center, const Interval& fixed,
                                            const std::optional<Interval>& held_offset, const Interval& y,
                                            IntervalJet& f) const {
  const std::vector<std::size_t>& active = memo.active;
  std::size_t k = active.size();
  std::size_t size = held_offset ? k + 2 : k + 1;
  double yc = y.middle();
  double tc = held_offset ? fixed.middle() : 0.0;
  // first order at the centre (c, y_c, t_c)
  IntervalJet fixed_c = held_offset ? IntervalJet::variable(Interval::point(tc), k + 1, size) : IntervalJet(fixed);
  IntervalJet fc = evaluate<IntervalJet>(curve, memo.jet_at_center, fixed_c, IntervalJet::variable(Interval::point(yc), k, size),
                                         made(memo.jet_at_center_constant, memo.constant_kinds, curve));
  // second order over the box
  HessianJet fixed2 = held_offset ? HessianJet::variable(fixed, k + 1, size) : HessianJet(fixed);
  HessianJet f2 = evaluate<HessianJet>(curve, memo.jet2, fixed2, HessianJet::variable(y, k, size), made(memo.jet2_constant, memo.constant_kinds, curve));
  std::vector<Interval> offsets(size);
  for (std::size_t a = 0; a < k; ++a) {
    std::size_t i = active[a];
    offsets[a] = kernels::hull(Interval::point(box.lo[i]) - Interval::point(center[i]),
                               Interval::point(box.hi[i]) - Interval::point(center[i]));
  }
  offsets[k] = kernels::hull(Interval::point(y.lo) - Interval::point(yc), Interval::point(y.hi) - Interval::point(yc));
  if (held_offset) offsets[k + 1] = kernels::hull(Interval::point(fixed.lo) - Interval::point(tc), Interval::point(fixed.hi) - Interval::point(tc));
  if (f.gradient.size() < size) f.gradient.resize(size, Interval(0));
  for (std::size_t a = 0; a < size; ++a) {
    Interval t = fc.partial(a);
    for (std::size_t b = 0; b < size; ++b) t = t + f2.second(a, b) * offsets[b];
    Interval& current = f.gradient[a];
    Interval narrower(std::max(current.lo, t.lo), std::min(current.hi, t.hi));
    if (narrower.lo <= narrower.hi) current = narrower;
  }
}

bool CurveSolver::taylor_geometry(const CurveSlice& curve, const BoxGeometry& memo, const Box& box) const {
  std::call_once(memo.taylor_once, [&] {
    // geometry(curve, model_->parameter_values(taylor_deviations(box, memo.active))), each edge
    // and axis through the edge memo (edge_memo.hpp: the same values, bit for bit); the
    // parameter values are made only when one of them is not in the memo
    std::optional<std::vector<TaylorJet>> values;
    auto parameters = [&]() -> const std::vector<TaylorJet>& {
      if (!values) values = this->values(taylor_deviations(box, memo.active));
      return *values;
    };
    try {
      PairGeometry<TaylorJet> g;
      g.first = edges_->edge(curve.first, box, memo.active, parameters);
      g.second = edges_->edge(curve.second, box, memo.active, parameters);
      edges_->motion(curve.fixed_part, box, memo.active, parameters, g.fixed_pivot, g.fixed_direction);
      edges_->motion(curve.free_part, box, memo.active, parameters, g.free_pivot, g.free_direction);
      memo.taylor = std::move(g);
      memo.has_taylor = true;
      memo.taylor_constant = constant_of_pair(curve, memo.taylor, memo.constant_kinds);
    } catch (const NumericError&) {
      // a construction the Taylor models cannot follow over this box (a square root or atan2
      // whose argument's range reaches its singularity, an undecided |x|): interval jets only
    }
  });
  return memo.has_taylor;
}

void CurveSolver::taylor_partials(const CurveSlice& curve, const BoxGeometry& memo, const Interval& fixed,
                                  const std::optional<Interval>& held_offset, const Interval& y, IntervalJet& f) const {
  std::size_t k = memo.active.size();
  std::size_t size = held_offset ? k + 2 : k + 1;
  try {
    TaylorJet fixed_t = held_offset ? TaylorJet::variable(TaylorModel1::over(fixed.lo, fixed.hi, k + 1), k + 1, size)
                                    : TaylorJet(TaylorModel1(fixed));
    TaylorJet ft = evaluate<TaylorJet>(curve, memo.taylor, fixed_t,
                                       TaylorJet::variable(TaylorModel1::over(y.lo, y.hi, k), k, size),
                                       made(memo.taylor_constant, memo.constant_kinds, curve));
    if (f.gradient.size() < size) f.gradient.resize(size, Interval(0));
    for (std::size_t a = 0; a < size; ++a) {
      Interval t = ft.partial(a).range();
      Interval& current = f.gradient[a];
      Interval narrower(std::max(current.lo, t.lo), std::min(current.hi, t.hi));
      if (narrower.lo <= narrower.hi) current = narrower;
    }
  } catch (const NumericError&) {
    // the Taylor models cannot follow the contact function over this region: the interval
    // jets' partials stand
  }
}

std::vector<bool> CurveSolver::inert(const CurveSlice& curve, const Box& whole) const {
  std::vector<double> key{static_cast<double>(curve.first.part),  static_cast<double>(curve.first.loop),
                          static_cast<double>(curve.first.edge),  static_cast<double>(curve.second.part),
                          static_cast<double>(curve.second.loop), static_cast<double>(curve.second.edge),
                          static_cast<double>(curve.fixed_part),  static_cast<double>(curve.free_part)};
  key.insert(key.end(), whole.lo.begin(), whole.lo.end());
  key.insert(key.end(), whole.hi.begin(), whole.hi.end());
  {
    std::lock_guard<std::mutex> lock(inert_->mutex);
    auto found = inert_->entries.find(key);
    if (found != inert_->entries.end()) return found->second;
  }
  // The parameters varying over `whole` that the geometry has no partial derivative with respect
  // to at nominal are the candidates; the geometry as interval jets over `whole` in them (the
  // others at their ranges): a partial that is exactly 0 there (exact zeros stay exact through
  // the jets' operations, jet.hpp) is 0 over the whole box.
  std::vector<bool> depends = dependencies(curve);
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < n_; ++i)
    if (whole.hi[i] > whole.lo[i] && !depends[i]) candidates.push_back(i);
  std::vector<bool> result(n_, false);
  if (!candidates.empty()) {
    std::vector<IntervalJet> jets(n_);
    for (std::size_t i = 0; i < n_; ++i) jets[i] = IntervalJet(Interval(whole.lo[i], whole.hi[i]));
    for (std::size_t a = 0; a < candidates.size(); ++a)
      jets[candidates[a]] = IntervalJet::variable(Interval(whole.lo[candidates[a]], whole.hi[candidates[a]]), a, candidates.size());
    std::vector<bool> zero(candidates.size(), true);
    try {
      PairGeometry<IntervalJet> g = geometry(curve, values(jets));
      auto mark = [&](const IntervalJet& x) {
        for (std::size_t a = 0; a < candidates.size(); ++a) {
          Interval d = x.partial(a);
          if (!(d.lo == 0.0 && d.hi == 0.0)) zero[a] = false;
        }
      };
      auto mark_vector = [&](const kernels::Vector<IntervalJet>& v) {
        mark(v.x);
        mark(v.y);
      };
      for (const model_detail::EdgeValue<IntervalJet>* e : {&g.first, &g.second}) {
        mark_vector(e->source);
        mark_vector(e->target);
        mark_vector(e->center);
        mark(e->radius_squared);
      }
      for (const kernels::Vector<IntervalJet>* v : {&g.fixed_pivot, &g.fixed_direction, &g.free_pivot, &g.free_direction})
        mark_vector(*v);
    } catch (const NumericError&) {
      zero.assign(candidates.size(), false);   // not evaluable over the box: nothing proven
    }
    for (std::size_t a = 0; a < candidates.size(); ++a) result[candidates[a]] = zero[a];
  }
  std::lock_guard<std::mutex> lock(inert_->mutex);
  if (inert_->entries.size() >= BoxGeometryMemo::max_entries) inert_->entries.clear();
  return inert_->entries.emplace(std::move(key), std::move(result)).first->second;
}

bool CurveSolver::root_partials(const CurveSlice& curve, const Box& box_in, const Box& whole_in, const Interval& y,
                                std::vector<Interval>& dp, Interval& dt, bool taylor, int* sign) const {
  const Box box = in_units(box_in), whole = in_units(whole_in);   // the jets' units (unit_)
  std::vector<double> center(n_);
  for (std::size_t i = 0; i < n_; ++i) center[i] = 0.5 * (box.lo[i] + box.hi[i]);
  std::shared_ptr<const BoxGeometry> memo = box_geometry(curve, box, center);
  const std::vector<std::size_t>& active = memo->active;
  std::size_t k = active.size();   // the free coordinate's index; the held one's k + 1
  // every parameter varying in the box: a jet variable, or proven inert over `whole`
  std::vector<bool> in_jets(n_, false);
  for (std::size_t i : active) in_jets[i] = true;
  std::vector<bool> proven;
  for (std::size_t i = 0; i < n_; ++i) {
    if (!(box.hi[i] > box.lo[i]) || in_jets[i]) continue;
    if (proven.empty()) proven = inert(curve, whole);
    if (!proven[i] || box.lo[i] < whole.lo[i] || box.hi[i] > whole.hi[i]) return false;
  }
  std::optional<Interval> held;
  if (curve.fixed_range) held = *curve.fixed_range;
  Interval fixed = held ? *held : Interval::enclose(curve.fixed_value);
  std::size_t size = held ? k + 2 : k + 1;
  IntervalJet fixed_jet = held ? IntervalJet::variable(fixed, k + 1, size) : IntervalJet(fixed);
  IntervalJet f;
  try {
    f = evaluate<IntervalJet>(curve, memo->jet, fixed_jet, IntervalJet::variable(y, k, size), made(memo->jet_constant, memo->constant_kinds, curve));
  } catch (const NumericError&) {
    return false;
  }
  std::optional<TaylorJet> ft;
  if (taylor && taylor_ && taylor_geometry(curve, *memo, box)) {
    try {
      TaylorJet fixed_t = held ? TaylorJet::variable(TaylorModel1::over(fixed.lo, fixed.hi, k + 1), k + 1, size)
                               : TaylorJet(TaylorModel1(fixed));
      ft = evaluate<TaylorJet>(curve, memo->taylor, fixed_t, TaylorJet::variable(TaylorModel1::over(y.lo, y.hi, k), k, size),
                               made(memo->taylor_constant, memo->constant_kinds, curve));
      if (f.gradient.size() < size) f.gradient.resize(size, Interval(0));
      for (std::size_t a = 0; a < size; ++a) {
        Interval t = ft->partial(a).range();
        Interval& current = f.gradient[a];
        Interval narrower(std::max(current.lo, t.lo), std::min(current.hi, t.hi));
        if (narrower.lo <= narrower.hi) current = narrower;
      }
    } catch (const NumericError&) {
      ft.reset();   // the Taylor models cannot follow the contact function here: interval jets
    }
  }
  Interval fv = f.partial(k);
  int s = fv.sign();
  if (s != 1 && s != -1) return false;   // no implicit function certified over the region
  if (sign) *sign = s;
  // -F_a/F_v, and where the Taylor models hold, also as a quotient of Taylor models (which keeps
  // the correlation of F_a and F_v over the region), intersected
  auto ratio = [&](std::size_t a) {
    Interval r = -(f.partial(a) / fv);
    if (ft) {
      try {
        Interval q = (-(ft->partial(a) / ft->partial(k))).range();
        Interval narrower(std::max(r.lo, q.lo), std::min(r.hi, q.hi));
        if (narrower.lo <= narrower.hi) r = narrower;
      } catch (const NumericError&) {
        // F_v's Taylor model reaches 0 somewhere: the interval quotient stands
      }
    }
    return r;
  };
  dp.assign(n_, Interval(0));
  for (std::size_t a = 0; a < k; ++a) {
    dp[active[a]] = ratio(a);
    // per deviation (the interval quotient rounds outwards: only for a unit other than 1)
    if (unit_[active[a]] != 1.0) dp[active[a]] = dp[active[a]] / Interval::point(unit_[active[a]]);
  }
  dt = held ? ratio(k + 1) : Interval(0);
  for (const Interval& d : dp)
    if (!std::isfinite(d.lo) || !std::isfinite(d.hi)) return false;
  return std::isfinite(dt.lo) && std::isfinite(dt.hi);
}

Interval CurveSolver::certified_range(const CurveSlice& curve, const Box& box, double free_value,
                                      const std::vector<double>& sensitivity, double relative_accuracy,
                                      double absolute_accuracy, std::size_t& boxes, int* free_side) const {
  // Once a box has needed the Taylor-model partials, subdivision gains little (gear-train-3: the
  // widest band +-1.235 deg with 16 sub-boxes per enclosure as with 256, the total width 2 %
  // more) and each sub-box costs more: then 16 (docs/performance.md, session 21). Enclosures that
  // never need them (first order meets the accuracy, or the Taylor models cannot follow the
  // construction) keep 256.
  bool taylor_used = false;
  // in the jets' units (unit_): the box divided, the sensitivities multiplied, exactly
  std::vector<double> sensitivity_in_units = sensitivity;
  for (std::size_t i = 0; i < n_; ++i) sensitivity_in_units[i] *= unit_[i];
  const std::vector<double>& sensitivity_u = sensitivity_in_units;
  std::vector<Box> pending{in_units(box)};
  bool have = false;
  Interval hull_of_all;
  std::size_t used = 0;
  int common_side = 2;   // the sub-boxes' F_v signs so far (2: none yet, 0: not all the same)
  while (!pending.empty()) {
    Box b = std::move(pending.back());
    pending.pop_back();
    ++used;
    Interval range;
    std::vector<double> score;
    double linear = 0;
    for (std::size_t i = 0; i < n_; ++i) linear += std::fabs(sensitivity_u[i]) * (b.hi[i] - b.lo[i]);
    linear += curve.fixed_spread;
    double target = linear * (1 + relative_accuracy) + absolute_accuracy;
    int side = 0;
    bool ok = box_range(curve, b, free_value, sensitivity_u, target, range, score, taylor_used, side);
    bool accurate = ok && range.width() <= target;
    const std::size_t max_boxes = taylor_used ? 16 : 256;
    if (!accurate && used + pending.size() + 2 <= max_boxes) {
      std::size_t split = 0;
      double best = -1;
      for (std::size_t i = 0; i < n_; ++i) {
        double s = ok ? score[i] : std::fabs(sensitivity_u[i]) * (b.hi[i] - b.lo[i]);
        if (b.hi[i] > b.lo[i] && s > best) {
          best = s;
          split = i;
        }
      }
      if (best > 0) {
        auto [left, right] = halves(b, split);
        pending.push_back(std::move(left));
        pending.push_back(std::move(right));
        continue;
      }
    }
    if (!ok) throw NumericError("cannot certify the contact curve over the tolerance box (the curve may be singular or the contact may change inside it)");
    hull_of_all = have ? kernels::hull(hull_of_all, range) : range;
    have = true;
    common_side = common_side == 2 || common_side == side ? side : 0;
  }
  boxes += used;
  if (free_side) *free_side = common_side == 2 ? 0 : common_side;
  return hull_of_all;
}

Interval chart_to_angle(const Interval& t, bool half_turn) {
  Interval a = model_detail::number_detail::through_mpfi(t, [](mpfi_ptr r, mpfi_srcptr x) { mpfi_atan(r, x); });
  Interval theta = Interval(2) * a;
  if (half_turn) theta = theta + Arithmetic<Interval>::pi();
  return theta;
}

}  // namespace hipair::tolerance_detail
