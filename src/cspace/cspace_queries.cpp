// The adaptor's queries for simulation and tolerancing (CGAL-free): typed access, blocked
// sides, contacts with their world points and normals, certified derivatives of contact edges,
// the first crossing along a motion across charts and seams, 1-D slices and edge polylines.
//
// Contact points and normals come from kernels/contact_geometry.hpp (one formula per contact
// type, templated on the number type): exact rationals at rational configurations, certified
// intervals at the crossing of a motion. Every decision is exact (GMP) or certified (MPFI/MPFR
// with directed rounding, outward-rounded double intervals).
#include <hipair/cspace.hpp>
#include <hipair/cspace_slice.hpp>
#include <hipair/blocked_walk.hpp>
#include <hipair/contact_frame_doubles.hpp>
#include <hipair/contact_frame_exact.hpp>
#include <hipair/crossing_before.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/edge_slope.hpp>
#include <hipair/error.hpp>

#include "cspace/angle_filter.hpp"
#include "cspace/path_filter.hpp"
#include "cspace/angle_memo.hpp"
#include "cspace/builder_impl.hpp"
#include "cspace/crossing_shrink.hpp"
#include "cspace/dyadic.hpp"
#include "cspace/cspace_access.hpp"
#include "cspace/exact_bound.hpp"
#include "cspace/frame_memo.hpp"
#include "cspace/partial_terms.hpp"
#include "cspace/point_tangent.hpp"
#include "cspace/scan_memo.hpp"
#include "cspace/slopes_memo.hpp"
#include "cspace/start_filter.hpp"
#include "algebra/interval_shift.hpp"
#include "core/kept_per_thread.hpp"
#include "core/mp_values.hpp"
#include "curves/pose.hpp"
#include "kernels/contact_frame_rational.hpp"
#include "kernels/contact_geometry.hpp"
#include "kernels/model_features.hpp"
#include "kernels/implicit_curve.hpp"
#include "kernels/interval.hpp"

#include <mpfi.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace hipair {

namespace {

using cspace::ChartData;
using cspace::algebra::Real;
using KInterval = kernels::Interval;

const CSpace::Impl& checked(const CSpace& space) { return implementation(space); }

template <class Id>
std::size_t index_in(Id id, std::size_t size, const char* what) {
  if (!id.valid() || id.index() >= size) throw GeometryError(std::string("no ") + what + " " + std::to_string(id.value));
  return id.index();
}

CertifiedRange range_of(const Rational& lo, const Rational& hi) {
  return CertifiedRange{cspace::algebra::lower_double(lo), cspace::algebra::upper_double(hi)};
}

CertifiedRange range_of(const KInterval& i) { return CertifiedRange{i.lo, i.hi}; }

// The exact ordinate of a contact edge at a rational abscissa strictly inside its extent
// (cspace::edge_y_at: the edge's arc number's root of the fibre), and that number refined to
// 2^-64 (Real::refine_to: the first interval derivatives_of and exact_ordinate take).
struct EdgeOrdinate {
  std::size_t edge = 0;   // global
  Rational x;             // canonical
  Real y, y64;
};
// From the scan memo's last few of the space (an impact's new contact asks edge_coordinate_slope
// at the configuration's abscissa, and its first contact row places a tracker at the same one),
// or made (and remembered); the same values either way (scan_memo.hpp, ordinate_at_memo()).
std::shared_ptr<const EdgeOrdinate> edge_ordinate(const CSpace& space, std::size_t index, const Rational& x);

// ------------------------------------------------------------------ exact rational intervals

struct RInterval {
  Rational lo, hi;
  RInterval() = default;
  RInterval(int value) : lo(value), hi(value) {}  // NOLINT(google-explicit-constructor): kernels' T(int)
  RInterval(Rational low, Rational high) : lo(std::move(low)), hi(std::move(high)) {}
  static RInterval point(const Rational& r) { return {r, r}; }
  bool contains_zero() const { return sgn(lo) <= 0 && sgn(hi) >= 0; }
};

RInterval operator+(const RInterval& a, const RInterval& b) {
  return {Rational(a.lo + b.lo), Rational(a.hi + b.hi)};
}
RInterval operator-(const RInterval& a, const RInterval& b) {
  return {Rational(a.lo - b.hi), Rational(a.hi - b.lo)};
}
RInterval operator-(const RInterval& a) { return {Rational(-a.hi), Rational(-a.lo)}; }
RInterval operator*(const RInterval& a, const RInterval& b) {
  Rational p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}
// \pre b does not contain 0.
RInterval operator/(const RInterval& a, const RInterval& b) {
  RInterval inverse{Rational(1 / b.hi), Rational(1 / b.lo)};
  return a * inverse;
}

// p(X) for ascending rational coefficients over an interval, by Horner (certified enclosure).
RInterval horner(const std::vector<Rational>& p, const RInterval& x) {
  RInterval value = RInterval::point(Rational(0));
  for (std::size_t i = p.size(); i-- > 0;) value = value * x + RInterval::point(p[i]);
  return value;
}

// Tighter enclosure of a polynomial over [a, b] for the path: Horner around the midpoint.
RInterval evaluate_path(const std::vector<Rational>& p, const Rational& a, const Rational& b) {
  if (a == b) {
    Rational v(0);
    for (std::size_t i = p.size(); i-- > 0;) v = v * a + p[i];
    return RInterval::point(v);
  }
  Rational m = (a + b) / 2;
  // coefficients of p(m + h)
  std::vector<Rational> shifted = p;
  for (std::size_t i = 0; i + 1 < shifted.size(); ++i)
    for (std::size_t j = shifted.size() - 1; j > i; --j) shifted[j - 1] += m * shifted[j];
  Rational half = (b - a) / 2;
  return horner(shifted, RInterval{Rational(-half), half});
}

// The same enclosure in outward-rounded doubles, the filter in front of the exact one (a
// certified enclosure a few units in the last place wider): cspace::evaluate_path_filtered_d
// (path_filter.hpp).
using cspace::evaluate_path_filtered_d;

std::optional<RInterval> evaluate_path_filtered(const std::vector<KInterval>& p, const Rational& a, const Rational& b) {
  std::optional<KInterval> value = evaluate_path_filtered_d(p, KInterval::enclose(a), KInterval::enclose(b));
  if (!value) return std::nullopt;
  return RInterval{Rational(value->lo), Rational(value->hi)};
}

// ------------------------------------------------------------------ feature geometry

// The pair's features as the kernels' body geometry: kernels::feature_geometry (model_features.hpp).
using kernels::feature_geometry;

// The contact frame of feature pair `pair` at chart values (x, y) of chart `c`, in T.
template <class T, class Convert>
kernels::ContactFrame<T> frame_at(const CSpace::Impl& impl, std::size_t c, const FeaturePair& pair, const T& x,
                                  const T& y, Convert&& convert) {
  const ChartData& chart = impl.charts[c];
  cspace::PairPoses<T> poses =
      cspace::pair_poses<T>(*impl.model, impl.axes, chart.x_axis, chart.y_axis, x, y, convert);
  const kernels::Pose<T>& a = pair.first.part == impl.axes.first ? poses.first : poses.second;
  const kernels::Pose<T>& b = pair.second.part == impl.axes.first ? poses.first : poses.second;
  if constexpr (std::is_same_v<T, Rational>) {   // exact: concentric arcs have no frame (no division by 0)
    return kernels::contact_frame_rational(a, feature_geometry<T>(*impl.model, pair.first, convert), b,
                                           feature_geometry<T>(*impl.model, pair.second, convert));
  } else {
    return kernels::contact_frame(a, feature_geometry<T>(*impl.model, pair.first, convert), b,
                                  feature_geometry<T>(*impl.model, pair.second, convert));
  }
}

// The contact frame of feature pair `pair` at chart values (x, y) of chart `c`, in T, from the
// pair's body geometries `first` and `second` (feature_geometry of pair.first and pair.second).
template <class T, class Convert>
kernels::ContactFrame<T> frame_with(const CSpace::Impl& impl, std::size_t c, const FeaturePair& pair, const T& x,
                                    const T& y, Convert&& convert, const kernels::FeatureGeometry<T>& first,
                                    const kernels::FeatureGeometry<T>& second) {
  const ChartData& chart = impl.charts[c];
  cspace::PairPoses<T> poses =
      cspace::pair_poses<T>(*impl.model, impl.axes, chart.x_axis, chart.y_axis, x, y, convert);
  const kernels::Pose<T>& a = pair.first.part == impl.axes.first ? poses.first : poses.second;
  const kernels::Pose<T>& b = pair.second.part == impl.axes.first ? poses.first : poses.second;
  if constexpr (std::is_same_v<T, Rational>) {
    return kernels::contact_frame_rational(a, first, b, second);
  } else {
    return kernels::contact_frame(a, first, b, second);
  }
}

// frame_memo (cspace/frame_memo.hpp): per thread, per space, the enclosed body geometries of
// the feature pairs met so far.
// Also the double enclosures (KInterval::enclose) of the public charts' bounds x_lo, x_hi, y_lo,
// y_hi, for contact_frame_ranges' chart tests (made with the memo).
struct FrameMemo {
  std::weak_ptr<const CSpace::Impl> owner;
  std::vector<std::optional<std::array<kernels::FeatureGeometry<KInterval>, 2>>> pairs;
  std::vector<std::array<KInterval, 4>> bounds;
};

// The memo of `space` on this thread (found, or made).
FrameMemo& frame_memo_of(const CSpace& space) {
  thread_local std::vector<FrameMemo> memos;
  const std::shared_ptr<const CSpace::Impl>& owner = CSpaceAccess::shared(space);
  const CSpace::Impl& impl = *owner;
  auto same = [&](const FrameMemo& m) { return !m.owner.owner_before(owner) && !owner.owner_before(m.owner); };
  auto it = std::find_if(memos.begin(), memos.end(), [&](const FrameMemo& m) { return !m.owner.expired() && same(m); });
  if (it == memos.end()) {
    std::erase_if(memos, [](const FrameMemo& m) { return m.owner.expired(); });
    if (memos.size() >= 16) memos.erase(memos.begin());
    FrameMemo made{owner, {}, {}};
    for (const CSpaceChart& chart : impl.public_charts)
      made.bounds.push_back({KInterval::enclose(chart.x_lo), KInterval::enclose(chart.x_hi), KInterval::enclose(chart.y_lo),
                             KInterval::enclose(chart.y_hi)});
    memos.push_back(std::move(made));
    it = std::prev(memos.end());
  }
  return *it;
}

// The enclosed body geometries of feature pair `index` of `space` (from the memo, or made and
// remembered).
const std::array<kernels::FeatureGeometry<KInterval>, 2>& enclosed_geometries(const CSpace& space, std::size_t index) {
  FrameMemo& memo = frame_memo_of(space);
  const CSpace::Impl& impl = implementation(space);
  if (memo.pairs.size() < impl.feature_pairs.size()) memo.pairs.resize(impl.feature_pairs.size());
  std::optional<std::array<kernels::FeatureGeometry<KInterval>, 2>>& slot = memo.pairs[index];
  if (slot) {
    ++cspace::frame_memo_hits();
    return *slot;
  }
  auto enclose = [](const Rational& r) { return KInterval::enclose(r); };
  const FeaturePair& pair = impl.feature_pairs[index];
  slot = std::array<kernels::FeatureGeometry<KInterval>, 2>{feature_geometry<KInterval>(*impl.model, pair.first, enclose),
                                                            feature_geometry<KInterval>(*impl.model, pair.second, enclose)};
  return *slot;
}

std::array<CertifiedRange, 2> unit_normal(const kernels::Vector<KInterval>& n) {
  kernels::Vector<KInterval> u = kernels::unit(n, [](const KInterval& v) { return kernels::sqrt(v); });
  return {range_of(u.x), range_of(u.y)};
}

const Model& model_of(const CSpace::Impl& impl) {
  if (!impl.model) throw GeometryError("this C-space was built without a model: no contact geometry");
  return *impl.model;
}

// Every clause of a validity holds at a rational point (exact).
bool valid_at(const std::vector<cspace::ValidityClause>& validity, const Rational& x, const Rational& y) {
  for (const auto& clause : validity) {
    bool holds = false;
    for (const auto& atom : clause.atoms) holds = holds || cspace::algebra::sign_at(atom, x, y) >= 0;
    if (!holds) return false;
  }
  return true;
}

bool contact_location(const CSpace::Impl& impl, const Location& location) {
  if (location.kind == Location::Kind::touching) return true;
  if (location.kind == Location::Kind::edge) return impl.edges[location.edge].real;
  if (location.kind == Location::Kind::vertex) {
    for (std::size_t e : impl.vertices[location.vertex].edges)
      if (impl.edges[e].real) return true;
    return impl.dimension == 1 && location.cell == no_index;
  }
  return false;
}

// A contact from the kernels' exact frame (contact_at, exact_contact_frame): the point and the
// normal exact, canonical, with their enclosures.
Contact exact_contact(FeatureId feature, const kernels::ContactFrame<Rational>& frame) {
  Contact contact;
  contact.feature = feature;
  contact.exact = true;
  contact.point = {frame.point.x, frame.point.y};
  contact.normal_direction = {frame.normal.x, frame.normal.y};
  for (auto& r : contact.point) r.canonicalize();
  for (auto& r : contact.normal_direction) r.canonicalize();
  contact.point_range = {range_of(frame.point.x, frame.point.x), range_of(frame.point.y, frame.point.y)};
  contact.normal = unit_normal({KInterval::enclose(frame.normal.x), KInterval::enclose(frame.normal.y)});
  return contact;
}

}  // namespace

// ------------------------------------------------------------------ typed access

const CSpaceCell& CSpace::cell(CellId id) const {
  const Impl& impl = checked(*this);
  return impl.cell_samples()[index_in(id, impl.cells.size(), "cell")];
}
const CSpaceEdge& CSpace::edge(EdgeId id) const {
  const Impl& impl = checked(*this);
  return impl.edges[index_in(id, impl.edges.size(), "edge")];
}
const CSpaceVertex& CSpace::vertex(VertexId id) const {
  const Impl& impl = checked(*this);
  return impl.vertex_number(index_in(id, impl.vertices.size(), "vertex"));
}
const FeaturePair& CSpace::feature_pair(FeatureId id) const {
  const Impl& impl = checked(*this);
  return impl.feature_pairs[index_in(id, impl.feature_pairs.size(), "feature pair")];
}

BlockedSide CSpace::blocked_side(EdgeId id) const {
  const Impl& impl = checked(*this);
  const CSpaceEdge& e = edge(id);
  if (!e.real) return BlockedSide::none;
  auto blocked = [&](std::size_t c) { return c != no_index && impl.cells[c].kind == CellKind::blocked; };
  if (blocked(e.left_cell) && !blocked(e.right_cell)) return BlockedSide::left;
  if (blocked(e.right_cell) && !blocked(e.left_cell)) return BlockedSide::right;
  return BlockedSide::none;
}

// ------------------------------------------------------------------ contact_at

std::vector<Contact> CSpace::contact_at(const ChartPoint& input) const {
  const Impl& impl = checked(*this);
  const Model& model = model_of(impl);
  (void)model;
  if (input.chart >= impl.charts.size()) throw GeometryError("contact_at: no chart " + std::to_string(input.chart));
  ChartPoint q = input;
  q.x.canonicalize();
  q.y.canonicalize();
  if (impl.dimension == 1) q.y = 0;
  const ChartData& chart = impl.charts[q.chart];
  std::vector<Contact> contacts;
  for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
    if (cspace::algebra::sign_at(chart.polynomials[k], q.x, q.y) != 0) continue;
    if (!valid_at(chart.validity[k], q.x, q.y)) continue;
    FeatureId id(chart.curve_global[k]);
    if (std::any_of(contacts.begin(), contacts.end(), [&](const Contact& c) { return c.feature == id; })) continue;
    const FeaturePair& pair = impl.feature_pairs[id.index()];
    auto exact = [](const Rational& r) { return r; };
    kernels::ContactFrame<Rational> frame = frame_at<Rational>(impl, q.chart, pair, q.x, q.y, exact);
    if (!frame.defined) continue;
    contacts.push_back(exact_contact(id, frame));
  }
  return contacts;
}

std::vector<Contact> CSpace::contact_at(const PartCoordinate& x, const PartCoordinate& y) const {
  auto point = to_chart(x, y);
  if (!point) throw GeometryError("contact_at: the configuration is outside every chart");
  return contact_at(*point);
}

std::optional<Contact> CSpace::contact_frame(FeatureId feature, const PartCoordinate& x, const PartCoordinate& y) const {
  const Impl& impl = checked(*this);
  model_of(impl);
  std::size_t index = index_in(feature, impl.feature_pairs.size(), "feature pair");
  auto point = to_chart(x, y);
  if (!point) throw GeometryError("contact_frame: the configuration is outside every chart");
  if (impl.dimension == 1) point->y = 0;
  auto enclose = [](const Rational& r) { return KInterval::enclose(r); };
  kernels::ContactFrame<KInterval> frame;
  if (cspace::frame_memo()) {
    const std::array<kernels::FeatureGeometry<KInterval>, 2>& g = enclosed_geometries(*this, index);
    frame = frame_with<KInterval>(impl, point->chart, impl.feature_pairs[index], enclose(point->x), enclose(point->y),
                                  enclose, g[0], g[1]);
  } else {
    frame = frame_at<KInterval>(impl, point->chart, impl.feature_pairs[index], enclose(point->x), enclose(point->y),
                                enclose);
  }
  if (!frame.defined) return std::nullopt;
  Contact contact;
  contact.feature = feature;
  contact.point_range = {range_of(frame.point.x), range_of(frame.point.y)};
  contact.normal = unit_normal(frame.normal);
  return contact;
}

// (session 70, stop70: the fixed-axis jam test's exact rows; contact_at's rational frame at a
// configuration that need not be on the contact curve)
std::optional<Contact> exact_contact_frame(const CSpace& space, FeatureId feature, const PartCoordinate& x,
                                           const PartCoordinate& y) {
  const CSpace::Impl& impl = checked(space);
  model_of(impl);
  const std::size_t index = index_in(feature, impl.feature_pairs.size(), "feature pair");
  auto point = space.to_chart(x, y);
  if (!point) throw GeometryError("exact_contact_frame: the configuration is outside every chart");
  if (impl.dimension == 1) point->y = 0;
  auto exact = [](const Rational& r) { return r; };
  const kernels::ContactFrame<Rational> frame =
      frame_at<Rational>(impl, point->chart, impl.feature_pairs[index], point->x, point->y, exact);
  if (!frame.defined) return std::nullopt;
  return exact_contact(feature, frame);
}

// ------------------------------------------------------------------ contact_frame_ranges

std::size_t& contact_frame_ranges_fallbacks() { return thread_counter<struct ContactFrameRangesFallbacksTag>(); }

namespace {

// A chart value known by doubles: lo <= value <= hi, lo == hi when the value is that double
// (tight: otherwise lo and hi are adjacent doubles and the value lies strictly between them).
struct TightValue {
  double lo = 0, hi = 0;
  // KInterval::enclose of the exact value: [0, 0] for 0, [v, up(v)] / [down(v), v] for a
  // nonzero double v (enclose truncates toward zero and steps away even when exact), the
  // adjacent pair itself otherwise
  KInterval enclosure() const {
    if (lo != hi) return KInterval(lo, hi);
    if (lo == 0) return KInterval(0.0, 0.0);
    return lo > 0 ? KInterval(lo, kernels::interval_detail::up(lo)) : KInterval(kernels::interval_detail::down(lo), lo);
  }
};

enum class Decided { no, yes, unknown };

// value < bound, for `bound` enclosed by b (b.lo <= bound <= b.hi)
Decided below(const TightValue& v, const KInterval& b) {
  if (v.hi < b.lo) return Decided::yes;
  if (v.lo >= b.hi) return Decided::no;
  return Decided::unknown;
}
// value > bound
Decided above(const TightValue& v, const KInterval& b) {
  if (v.lo > b.hi) return Decided::yes;
  if (v.hi <= b.lo) return Decided::no;
  return Decided::unknown;
}

// chart_points' `convert` on a double coordinate: the chart value, nullopt where the chart
// cannot express it; `undecided` where the doubles do not answer as the rationals would (a kind
// its axis refuses: convert throws; -1/value beyond 2^+-500)
std::optional<TightValue> chart_value(const DoubleCoordinate& p, AxisKind kind, bool half_turn, bool& undecided) {
  if (kind == AxisKind::translation) {
    if (p.kind != PartCoordinate::Kind::offset) {
      undecided = true;
      return std::nullopt;
    }
    const double v = p.value == 0 ? 0.0 : p.value;   // -0 is the rational 0
    return TightValue{v, v};
  }
  if (p.kind == PartCoordinate::Kind::offset) {
    undecided = true;
    return std::nullopt;
  }
  if (p.kind == PartCoordinate::Kind::half_turn) {
    if (!half_turn) return std::nullopt;
    return TightValue{0.0, 0.0};
  }
  const double v = p.value == 0 ? 0.0 : p.value;
  if (!half_turn) return TightValue{v, v};
  if (v == 0) return std::nullopt;
  const double magnitude = std::abs(v);
  if (!(magnitude >= 0x1p-500 && magnitude <= 0x1p500)) {
    undecided = true;
    return std::nullopt;
  }
  // t = -1/v (tan((theta - pi)/2) = -cot(theta/2)); q its rounded quotient. The residual
  // q v + 1 = v (q - t) is a double (the error of a division without underflow), so fma gives it
  // exactly and its sign times v's is the sign of q - t.
  const double q = -1.0 / v;
  const double r = std::fma(q, v, 1.0);
  if (r == 0) return TightValue{q, q};
  const bool q_above = (r > 0) == (v > 0);
  if (q_above) return TightValue{kernels::interval_detail::down(q), q};
  return TightValue{q, kernels::interval_detail::up(q)};
}

}  // namespace

std::optional<FrameRanges> contact_frame_ranges(const CSpace& space, FeatureId feature, const DoubleCoordinate& x,
                                                const DoubleCoordinate& y) {
  const CSpace::Impl& impl = checked(space);
  auto exact_answer = [&]() -> std::optional<FrameRanges> {
    ++contact_frame_ranges_fallbacks();
    auto part = [](const DoubleCoordinate& d) {
      return PartCoordinate{d.kind, d.kind == PartCoordinate::Kind::half_turn ? Rational(0) : Rational(d.value)};
    };
    std::optional<Contact> c = space.contact_frame(feature, part(x), part(y));
    if (!c) return std::nullopt;
    return FrameRanges{c->point_range, c->normal};
  };
  if (!impl.model) return exact_answer();   // contact_frame's error
  if (!feature.valid() || feature.index() >= impl.feature_pairs.size()) return exact_answer();
  const std::size_t index = feature.index();
  FrameMemo& memo = frame_memo_of(space);
  // the first chart that holds the configuration (chart_points with first_only)
  std::optional<std::size_t> chart_index;
  TightValue cx, cy;
  for (std::size_t c = 0; c < impl.public_charts.size(); ++c) {
    const CSpaceChart& chart = impl.public_charts[c];
    const std::array<KInterval, 4>& b = memo.bounds[c];
    bool undecided = false;
    std::optional<TightValue> vx = chart_value(x, chart.x_kind, chart.x_half_turn, undecided);
    if (undecided) return exact_answer();
    if (!vx) continue;
    Decided out = below(*vx, b[0]);
    if (out == Decided::no) out = above(*vx, b[1]);
    if (out == Decided::unknown) return exact_answer();
    if (out == Decided::yes) continue;
    if (impl.dimension == 1) {
      chart_index = c;
      cx = *vx;
      cy = TightValue{0.0, 0.0};
      break;
    }
    std::optional<TightValue> vy = chart_value(y, chart.y_kind, chart.y_half_turn, undecided);
    if (undecided) return exact_answer();
    if (!vy) continue;
    out = below(*vy, b[2]);
    if (out == Decided::no) out = above(*vy, b[3]);
    if (out == Decided::unknown) return exact_answer();
    if (out == Decided::yes) continue;
    chart_index = c;
    cx = *vx;
    cy = *vy;
    break;
  }
  if (!chart_index) throw GeometryError("contact_frame: the configuration is outside every chart");
  auto enclose = [](const Rational& r) { return KInterval::enclose(r); };
  kernels::ContactFrame<KInterval> frame;
  if (cspace::frame_memo()) {
    const std::array<kernels::FeatureGeometry<KInterval>, 2>& g = enclosed_geometries(space, index);
    frame = frame_with<KInterval>(impl, *chart_index, impl.feature_pairs[index], cx.enclosure(), cy.enclosure(), enclose,
                                  g[0], g[1]);
  } else {
    frame = frame_at<KInterval>(impl, *chart_index, impl.feature_pairs[index], cx.enclosure(), cy.enclosure(), enclose);
  }
  if (!frame.defined) return std::nullopt;
  return FrameRanges{{range_of(frame.point.x), range_of(frame.point.y)}, unit_normal(frame.normal)};
}

// ------------------------------------------------------------------ derivatives

namespace {

// Partial derivative d^(dx+dy) F / dx^dx dy^dy at the rational x, as a polynomial in y.
std::vector<Rational> partial_in_y(const cspace::IntegerPolynomial2& f, const Rational& x, int dx, int dy) {
  std::vector<Rational> result;
  for (std::size_t i = 0; i < f.coefficients.size(); ++i) {
    if (static_cast<int>(i) < dx) continue;
    Rational x_factor(1);
    for (int d = 0; d < dx; ++d) x_factor *= static_cast<long>(i) - d;
    for (std::size_t p = 0; p + dx < i; ++p) x_factor *= x;
    const auto& row = f.coefficients[i];
    for (std::size_t j = 0; j < row.size(); ++j) {
      if (static_cast<int>(j) < dy || sgn(row[j]) == 0) continue;
      Rational c = x_factor * Rational(row[j]);
      for (int d = 0; d < dy; ++d) c *= static_cast<long>(j) - d;
      std::size_t power = j - static_cast<std::size_t>(dy);
      if (result.size() <= power) result.resize(power + 1, Rational(0));
      result[power] += c;
    }
  }
  return result;
}

// Slopes of a part coordinate (rad or mm) with respect to its chart coordinate.
kernels::Slopes<RInterval> coordinate_slopes(const cspace::ChartAxis& axis, const RInterval& t) {
  if (axis.kind == cspace::ChartAxis::Kind::translation)
    return {RInterval::point(Rational(1)), RInterval::point(Rational(0))};
  return kernels::half_angle_slopes(t);
}

}  // namespace

namespace {

// CSpace::derivatives (second_order) or edge_coordinate_slope (not: only coordinate_dy, by the
// same rational interval operations as the first components of kernels::implicit_slopes,
// half_angle_slopes and part_slopes, so the same bits; the same checks, so the same throws).
EdgeDerivatives derivatives_of(const CSpace& space, EdgeId id, const Rational& x_input, bool second_order) {
  const CSpace::Impl& impl = checked(space);
  std::size_t index = index_in(id, impl.edges.size(), "edge");
  if (impl.dimension != 2) throw GeometryError("derivatives: a 1-D C-space has no contact edges");
  auto [c, e] = impl.edge_local[index];
  const ChartData& chart = impl.charts[c];
  const cspace::raw::Edge& raw_edge = chart.arrangement.edges[e];
  if (raw_edge.vertical) throw GeometryError("derivatives: edge " + std::to_string(index) + " is vertical");
  Rational x = x_input;
  x.canonicalize();
  const cspace::raw::Vertex& low = chart.arrangement.vertices[raw_edge.min_vertex];
  const cspace::raw::Vertex& high = chart.arrangement.vertices[raw_edge.max_vertex];
  int cl = low.x.compare(x), ch = high.x.compare(x);
  if (cl > 0 || ch < 0) throw GeometryError("derivatives: abscissa outside the edge's extent");
  std::shared_ptr<const EdgeOrdinate> inside = cl == 0 || ch == 0 ? nullptr : edge_ordinate(space, index, x);
  const Real& y = cl == 0 ? low.y : ch == 0 ? high.y : inside->y;
  const cspace::IntegerPolynomial2& f = raw_edge.support;
  std::vector<Rational> fx = partial_in_y(f, x, 1, 0), fy = partial_in_y(f, x, 0, 1);
  std::vector<Rational> fxx, fxy, fyy;
  if (second_order) fxx = partial_in_y(f, x, 2, 0), fxy = partial_in_y(f, x, 1, 1), fyy = partial_in_y(f, x, 0, 2);
  EdgeDerivatives result;
  if (second_order) result.y = cspace::to_public(y);
  for (int bits = 64;; bits *= 2) {
    Real refined = inside && bits == 64 ? inside->y64 : y;
    if (!refined.exact) refined.refine_to(Rational(1, mpz_class(1) << bits));
    RInterval Y = refined.exact ? RInterval::point(refined.lower)
                                       : RInterval{refined.lower, refined.upper};
    RInterval Fy = horner(fy, Y);
    if (Fy.contains_zero()) {
      if (refined.exact || bits >= 2048)
        throw GeometryError("derivatives: the curve of edge " + std::to_string(index) +
                            " is singular or vertical at this abscissa (F_y = 0)");
      continue;
    }
    if (!second_order) {
      // the first components: chart y' = -(F_x / F_y); a rotating axis's d theta / dt = 2 / (1 + t^2)
      // (a translation's 1); dY/dX = Y' y' / X'
      auto first_slope = [](const cspace::ChartAxis& axis, const RInterval& t) {
        if (axis.kind == cspace::ChartAxis::Kind::translation) return RInterval::point(Rational(1));
        RInterval w = RInterval(RInterval(1) + t * t);
        return RInterval(RInterval(2) / w);
      };
      RInterval dy = RInterval(-(horner(fx, Y) / Fy));
      RInterval ratio = RInterval(first_slope(chart.y_axis, Y) * dy / first_slope(chart.x_axis, RInterval::point(x)));
      result.dy = range_of(dy.lo, dy.hi);
      result.coordinate_dy = range_of(ratio.lo, ratio.hi);
      return result;
    }
    kernels::Slopes<RInterval> chart_slopes =
        kernels::implicit_slopes(horner(fx, Y), Fy, horner(fxx, Y), horner(fxy, Y), horner(fyy, Y));
    kernels::Slopes<RInterval> part = kernels::part_slopes(
        chart_slopes, coordinate_slopes(chart.x_axis, RInterval::point(x)), coordinate_slopes(chart.y_axis, Y));
    const RInterval& dy = chart_slopes.first;
    const RInterval& d2y = chart_slopes.second;
    const RInterval& ratio = part.first;
    const RInterval& acceleration = part.second;
    result.dy = range_of(dy.lo, dy.hi);
    result.d2y = range_of(d2y.lo, d2y.hi);
    result.coordinate_dy = range_of(ratio.lo, ratio.hi);
    result.coordinate_d2y = range_of(acceleration.lo, acceleration.hi);
    return result;
  }
}

}  // namespace

EdgeDerivatives CSpace::derivatives(EdgeId id, const Rational& x_input) const {
  return derivatives_of(*this, id, x_input, true);
}

CertifiedRange edge_coordinate_slope(const CSpace& space, EdgeId id, const Rational& x) {
  return derivatives_of(space, id, x, false).coordinate_dy;
}

// ------------------------------------------------------------------ compare_ordinate

namespace {

// compare_ordinate's decision data for a vertex with an inexact ordinate: which polynomial
// changes sign across its isolating interval [y_lower, y_upper] (the fibre y_curve(x, .), or
// for a fibre of degree 2 its y-derivative; nothing: undecided), and that polynomial's sign at
// y_lower. A pure function of the vertex (exact signs at its algebraic x).
struct FibreSigns {
  enum class Decides : signed char { curve, derivative, nothing };
  Decides decides = Decides::nothing;
  int lower = 0;
};

// The y-derivative of a curve's integer polynomial.
cspace::IntegerPolynomial2 y_derivative(const cspace::IntegerPolynomial2& f) {
  cspace::IntegerPolynomial2 derivative;
  derivative.coefficients.resize(f.coefficients.size());
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 1; j < f.coefficients[i].size(); ++j)
      derivative.coefficients[i].push_back(f.coefficients[i][j] * static_cast<long>(j));
  return derivative;
}

FibreSigns fibre_signs_of(const cspace::raw::Vertex& vertex) {
  FibreSigns result;
  int lower = cspace::algebra::sign_at(vertex.y_curve, vertex.x, vertex.y_lower);
  int upper = cspace::algebra::sign_at(vertex.y_curve, vertex.x, vertex.y_upper);
  if (lower != 0 && upper != 0 && lower != upper) {
    result.decides = FibreSigns::Decides::curve;
    result.lower = lower;
  } else if (vertex.y_curve.degree_y() == 2) {
    const cspace::IntegerPolynomial2 derivative = y_derivative(vertex.y_curve);
    lower = cspace::algebra::sign_at(derivative, vertex.x, vertex.y_lower);
    upper = cspace::algebra::sign_at(derivative, vertex.x, vertex.y_upper);
    if (lower != 0 && upper != 0 && lower != upper) {
      result.decides = FibreSigns::Decides::derivative;
      result.lower = lower;
    }
  }
  return result;
}

// fibre_signs_of(vertex `index`) through the space's scan memo (defined below it).
FibreSigns fibre_signs(const CSpace& space, std::size_t index);

// What compare_ordinate has proved of a vertex's ordinate y_v from the ordinates it compared
// (per space and thread, in the scan memo): below < y_v < above, or y_v == equal. An ordinate at
// or below `below` (at or above `above`) is then decided by a rational comparison, without the
// exact sign of the fibre at the vertex's algebraic abscissa.
struct OrdinateBounds {
  std::optional<Rational> below, above, equal;
};
OrdinateBounds ordinate_bounds(const CSpace& space, std::size_t index);
// records compare_ordinate's answer `side` (the sign of y - y_v) for the ordinate y
void remember_ordinate(const CSpace& space, std::size_t index, const Rational& y, int side);
// The sign of the deciding polynomial D of `signs` (the fibre or its y-derivative) at (x_v, y),
// from exact signs at two rationals: x_v's isolating interval (x_lo, x_hi), narrowed once per
// vertex to 2^-100 and remembered in the scan memo, where D(., y)'s x-derivative is certified
// non-zero (outward-rounded double intervals) so that D(x_v, y) lies strictly between
// D(x_lo, y) and D(x_hi, y): their common sign, where they have one; nullopt otherwise (the
// exact sign at the algebraic x_v then decides). Switch cspace::ordinate_enclosure().
std::optional<int> enclosed_fibre_sign(const CSpace& space, std::size_t index, const FibreSigns& signs,
                                       const Rational& y);

}  // namespace

int CSpace::compare_ordinate(VertexId id, const Rational& y_input) const {
  const Impl& impl = checked(*this);
  std::size_t index = index_in(id, impl.vertices.size(), "vertex");
  if (impl.dimension != 2) throw GeometryError("compare_ordinate: a 1-D C-space has no ordinate");
  auto [c, v] = impl.vertex_local[index];
  const cspace::raw::Vertex& vertex = impl.charts[c].arrangement.vertices[v];
  Rational y = y_input;
  y.canonicalize();
  // Real::compare is the sign of (value - y)
  if (vertex.y_exact) return -vertex.y.compare(y);
  if (y < vertex.y_lower) return -1;
  if (y > vertex.y_upper) return 1;
  // the vertex's y is the only root of y_curve(x, .) in [y_lower, y_upper]: where y_curve
  // changes sign across the interval, the sign at y tells on which side of the root y lies.
  // Otherwise a double root of the fibre (the curve's vertical tangent meets another curve
  // there, as where a slot's side meets its round end): for a fibre of degree 2 in y,
  // a y0^2 + ... = a (y - y0)^2 and its y-derivative 2 a (y - y0) changes sign at y0 alone.
  // Which of the two decides, and its sign at y_lower, are the vertex's alone (fibre_signs,
  // remembered per space and thread).
  // Ordinates compared before bound the vertex's (ordinate_bounds): a rational comparison
  // decides where y lies beyond them.
  const OrdinateBounds known = ordinate_bounds(*this, index);
  if (known.equal) {
    ++cspace::ordinate_memo_hits();
    return y < *known.equal ? -1 : y > *known.equal ? 1 : 0;
  }
  if (known.below && y <= *known.below) {
    ++cspace::ordinate_memo_hits();
    return -1;
  }
  if (known.above && y >= *known.above) {
    ++cspace::ordinate_memo_hits();
    return 1;
  }
  const FibreSigns signs = fibre_signs(*this, index);
  if (signs.decides != FibreSigns::Decides::nothing) {
    // the certified double-interval sign first (a non-zero sign only; the exact one otherwise)
    if (const std::optional<int> enclosed = enclosed_fibre_sign(*this, index, signs, y)) {
      const int side = *enclosed == signs.lower ? -1 : 1;
      remember_ordinate(*this, index, y, side);
      return side;
    }
    const cspace::IntegerPolynomial2 derivative =
        signs.decides == FibreSigns::Decides::derivative ? y_derivative(vertex.y_curve) : cspace::IntegerPolynomial2{};
    int at = cspace::algebra::sign_at(signs.decides == FibreSigns::Decides::curve ? vertex.y_curve : derivative, vertex.x, y);
    const int side = at == 0 ? 0 : at == signs.lower ? -1 : 1;
    remember_ordinate(*this, index, y, side);
    return side;
  }
  throw GeometryError("compare_ordinate: the ordinate of vertex " + std::to_string(index) +
                      " is not a sign change of its curve's fibre (not decided)");
}

// ------------------------------------------------------------------ filtered derivatives

namespace {

// kernels::Interval with the equality polynomial_partials uses to skip zero coefficients.
struct TrackInterval : KInterval {
  TrackInterval() = default;
  TrackInterval(int value) : KInterval(value) {}                 // NOLINT(google-explicit-constructor)
  TrackInterval(const KInterval& value) : KInterval(value) {}    // NOLINT(google-explicit-constructor)
  friend bool operator==(const TrackInterval& a, const TrackInterval& b) { return a.lo == b.lo && a.hi == b.hi; }
};

// What a tracker keeps of its edge: the support polynomial in doubles (nearest, for Newton),
// in certified double intervals (the partials over boxes) and with a certified error bound (the
// signs of F), the abscissae strictly inside the edge's extent, and the chart's axis kinds.
struct TrackerData {
  std::vector<std::vector<double>> nearest;
  std::vector<std::vector<TrackInterval>> enclosed;
  cspace::algebra::IntervalPolynomial2 value;
  cspace::PartialTerms<double> nearest_terms;         // `nearest` and `enclosed`, their partials premultiplied
  cspace::PartialTerms<TrackInterval> enclosed_terms;  // (bit-for-bit polynomial_partials'; partial_terms.hpp)
  bool terms = false;                                 // cspace::partial_terms() when the tracker was placed
  double x_min = 0, x_max = 0;   // an abscissa in (x_min, x_max) is strictly inside the edge's extent
  bool x_rotation = false, y_rotation = false;
};

// Certified sign of F at a double point: -1, +1, or 0 when rounding cannot decide.
int certified_sign(const TrackerData& data, double x, double y) {
  double error = 0;
  double v = data.value.evaluate(x, y, &error);
  if (!std::isfinite(v) || !std::isfinite(error)) return 0;
  return v > error ? 1 : v < -error ? -1 : 0;
}

// Step 4 of slopes_from: the slopes on {x} x Y1, Y1 a certified bracket of the edge's root at x
// (a pure function of the tracker's data, x and Y1).
std::optional<EdgeSlopes> slopes_at(const TrackerData& data, double x, const KInterval& y1) {
  auto identity = [](const auto& v) { return v; };
  const TrackInterval X1(KInterval::point(x)), Y1(y1);
  kernels::Partials<TrackInterval> at =
      data.terms ? data.enclosed_terms.all(X1, Y1) : kernels::polynomial_partials(data.enclosed, X1, Y1, identity);
  if (at.fy.sign() == 2 || at.fy.sign() == 0) return std::nullopt;
  kernels::Slopes<TrackInterval> chart_slopes = kernels::implicit_slopes(at.fx, at.fy, at.fxx, at.fxy, at.fyy);
  auto axis_slopes = [](bool rotation, const TrackInterval& t) {
    return rotation ? kernels::half_angle_slopes(t) : kernels::offset_slopes<TrackInterval>();
  };
  kernels::Slopes<TrackInterval> part =
      kernels::part_slopes(chart_slopes, axis_slopes(data.x_rotation, X1), axis_slopes(data.y_rotation, Y1));
  for (const KInterval* v : {&chart_slopes.first, &chart_slopes.second, &part.first, &part.second})
    if (!std::isfinite(v->lo) || !std::isfinite(v->hi)) return std::nullopt;
  return EdgeSlopes{range_of(y1), range_of(chart_slopes.first), range_of(chart_slopes.second), range_of(part.first),
                    range_of(part.second)};
}

// The filter proper (track_derivatives): y, y', y'' at x from the certified point (x0, Y0) of
// the same edge, or nullopt. `memo` (slopes_memo.hpp): step 4's last answer, taken again for the
// same x and Y1 (bit patterns).
template <class Memo>
std::optional<EdgeSlopes> slopes_from(const TrackerData& data, double x, double x0, CertifiedRange y0, Memo* memo) {
  namespace detail = kernels::interval_detail;
  auto identity = [](const auto& v) { return v; };

  // 1. the ordinate by Newton's method in doubles from the last certified point
  double y = 0.5 * (y0.lower + y0.upper);
  for (int i = 0; i < 8; ++i) {
    double fy = data.terms ? data.nearest_terms.fy(x, y) : kernels::polynomial_partials(data.nearest, x, y, identity).fy;
    double error = 0;
    double step = data.value.evaluate(x, y, &error) / fy;
    if (!std::isfinite(step)) return std::nullopt;
    y -= step;
    if (std::abs(step) <= 1e-16 * std::max(1.0, std::abs(y))) break;
  }
  // 2. a certified enclosure Y1 of a root of F(x, .): opposite certified signs at its ends
  const double scale = std::max(1.0, std::abs(y));
  KInterval y1;
  bool bracketed = false;
  for (double delta = 4e-16 * scale; delta < 1e-7 * scale && !bracketed; delta *= 8) {
    double lo = y - delta, hi = y + delta;
    int s_lo = certified_sign(data, x, lo), s_hi = certified_sign(data, x, hi);
    if (s_lo != 0 && s_hi != 0 && s_lo != s_hi) {
      y1 = KInterval(lo, hi);
      bracketed = true;
    }
  }
  if (!bracketed) return std::nullopt;
  // 3. the root in Y1 is the edge's: on the box X x Y (X between the certified point x0 and
  // x), F_y excludes 0 (each fibre has at most one root in Y) and |y'| = |F_x / F_y| <= S, so
  // the edge's branch, in Y0 at x0, stays within S |x - x0| of Y0, inside Y, and meets the
  // fibre at x in its only root in Y, which lies in Y1 (within the edge's extent: no end between;
  // x = x0 too: Y0 and Y1 then hold the same root)
  const TrackInterval X(KInterval(std::min(x0, x), std::max(x0, x)));
  const double dx = detail::up(std::abs(x - x0));
  double margin = detail::up(std::abs(y1.hi - y0.lower) + std::abs(y0.upper - y1.lo));
  bool certified = false;
  for (int attempt = 0; attempt < 4 && !certified; ++attempt) {
    TrackInterval Y(KInterval(detail::down(std::min(y0.lower, y1.lo) - margin),
                              detail::up(std::max(y0.upper, y1.hi) + margin)));
    std::pair<TrackInterval, TrackInterval> box;   // F_x, F_y on X x Y
    if (data.terms) {
      box = data.enclosed_terms.first(X, Y);
    } else {
      kernels::Partials<TrackInterval> all = kernels::polynomial_partials(data.enclosed, X, Y, identity);
      box = {all.fx, all.fy};
    }
    if (box.second.sign() == 2 || box.second.sign() == 0) return std::nullopt;
    KInterval q = box.first / box.second;
    double slope = std::max(std::abs(q.lo), std::abs(q.hi));
    if (!std::isfinite(slope)) return std::nullopt;
    double reach = detail::up(detail::up(slope) * dx);
    certified = Y.lo < detail::down(y0.lower - reach) && detail::up(y0.upper + reach) < Y.hi &&
                Y.lo <= y1.lo && y1.hi <= Y.hi;
    margin = std::max(4 * margin, 2 * reach);
  }
  if (!certified) return std::nullopt;
  // 4. the slopes on {x} x Y1
  if (!memo || !cspace::slopes_memo()) return slopes_at(data, x, y1);
  const auto bx = std::bit_cast<std::uint64_t>(x), blo = std::bit_cast<std::uint64_t>(y1.lo),
             bhi = std::bit_cast<std::uint64_t>(y1.hi);
  if (memo->set && memo->x == bx && memo->y_lo == blo && memo->y_hi == bhi) {
    ++cspace::slopes_memo_hits();
    return memo->slopes;
  }
  memo->slopes = slopes_at(data, x, y1);
  memo->x = bx;
  memo->y_lo = blo;
  memo->y_hi = bhi;
  memo->set = true;
  return memo->slopes;
}

// A tracker's data for a non-vertical edge (a pure function of the edge and the switch
// cspace::partial_terms()).
std::shared_ptr<const TrackerData> tracker_data_of(const ChartData& chart, const cspace::raw::Edge& raw_edge) {
  auto data = std::make_shared<TrackerData>();
  const cspace::raw::Vertex& low = chart.arrangement.vertices[raw_edge.min_vertex];
  const cspace::raw::Vertex& high = chart.arrangement.vertices[raw_edge.max_vertex];
  // the ends' abscissae to about a unit in the last place (their isolating intervals may be
  // wide): abscissae strictly between are inside the edge's extent
  Real x_low = low.x, x_high = high.x;
  for (Real* end : {&x_low, &x_high})
    if (!end->exact) end->refine_to(Rational(1, mpz_class(1) << 60));
  data->x_min = x_low.upper_bound();
  data->x_max = x_high.lower_bound();
  const auto& f = raw_edge.support.coefficients;
  data->nearest.resize(f.size());
  data->enclosed.resize(f.size());
  // F / 2^shift throughout, as `value` encloses it (interval_shift.hpp: Newton's F / F_y and
  // the slopes' quotients of partials are the same at any common scale); shift 0 but for huge
  // coefficients
  const long shift = cspace::algebra::interval_shift(raw_edge.support);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (const mpz_class& coefficient : f[i]) {
      if (shift == 0) {
        data->nearest[i].push_back(coefficient.get_d());
        data->enclosed[i].push_back(KInterval::enclose(mpq_class(coefficient)));
      } else {
        data->nearest[i].push_back(cspace::algebra::nearest_shifted(coefficient, shift));
        const cspace::algebra::Interval scaled = cspace::algebra::enclose_shifted(coefficient, shift);
        data->enclosed[i].push_back(KInterval(scaled.lo, scaled.hi));
      }
    }
  {
    cspace::algebra::ScaledEnclosures scope;
    data->value = cspace::algebra::IntervalPolynomial2(raw_edge.support);
  }
  data->terms = cspace::partial_terms();
  if (data->terms) {
    auto identity = [](const auto& v) { return v; };
    data->nearest_terms = cspace::PartialTerms<double>(data->nearest, identity);
    data->enclosed_terms = cspace::PartialTerms<TrackInterval>(data->enclosed, identity);
  }
  data->x_rotation = chart.x_axis.kind != cspace::ChartAxis::Kind::translation;
  data->y_rotation = chart.y_axis.kind != cspace::ChartAxis::Kind::translation;
  return data;
}

// The scan memo's slot for edge `index`'s tracker data (a TrackerData, made on first placement;
// defined with ScanMemo below), or nullptr when the memo is switched off (scan_memo.hpp,
// tracker_memo()).
std::shared_ptr<std::shared_ptr<const void>> tracker_data_slot(const CSpace& space, std::size_t index);

// A certified enclosure of the edge's ordinate at x, exactly (the edge's arc number).
CertifiedRange exact_ordinate(const CSpace& space, std::size_t index, double x) {
  const std::shared_ptr<const EdgeOrdinate> at = edge_ordinate(space, index, Rational(x));
  const Real& y = at->y64;
  return y.exact ? range_of(y.lower, y.lower) : range_of(y.lower, y.upper);
}

}  // namespace

std::optional<EdgeSlopes> track_derivatives(const CSpace& space, EdgeId id, double x, EdgeTracker& tracker) {
  const CSpace::Impl& impl = checked(space);
  if (impl.dimension != 2 || !id.valid() || id.index() >= impl.edges.size() || !std::isfinite(x)) return std::nullopt;
  auto [c, e] = impl.edge_local[id.index()];
  const ChartData& chart = impl.charts[c];
  const cspace::raw::Edge& raw_edge = chart.arrangement.edges[e];
  if (raw_edge.vertical) return std::nullopt;

  if (tracker.space_ != &impl || tracker.edge_ != id || !tracker.data_) {
    // place the tracker: the edge's polynomial in doubles, and one exact point of the edge.
    // The polynomial's forms and the extent are the edge's alone: made once per edge on this
    // thread (the scan memo), the same values as made here
    std::shared_ptr<std::shared_ptr<const void>> slot = tracker_data_slot(space, id.index());
    std::shared_ptr<const TrackerData> made =
        slot && *slot ? std::static_pointer_cast<const TrackerData>(*slot) : nullptr;
    if (made && made->terms == cspace::partial_terms()) {
      ++cspace::tracker_memo_hits();
    } else {
      made = tracker_data_of(chart, raw_edge);
      if (slot) *slot = made;
    }
    if (!(x > made->x_min && x < made->x_max)) return std::nullopt;
    tracker.space_ = &impl;
    tracker.edge_ = id;
    tracker.x_ = x;
    tracker.y_ = exact_ordinate(space, id.index(), x);
    tracker.data_ = std::move(made);
    tracker.memo_ = EdgeTracker::Memo{};   // its answers were of the edge placed before
  }
  const TrackerData& data = *static_cast<const TrackerData*>(tracker.data_.get());
  if (!(x > data.x_min && x < data.x_max)) return std::nullopt;
  std::optional<EdgeSlopes> result = slopes_from(data, x, tracker.x_, tracker.y_, &tracker.memo_);
  if (!result && x != tracker.x_) {
    // a jump the a-priori box cannot bridge: one exact point of the edge at x, and the filter
    // from there
    tracker.x_ = x;
    tracker.y_ = exact_ordinate(space, id.index(), x);
    result = slopes_from(data, x, x, tracker.y_, &tracker.memo_);
  }
  if (result) {
    tracker.x_ = x;
    tracker.y_ = result->y;
  }
  return result;
}

// ------------------------------------------------------------------ slices and polylines

namespace {

// The real roots of every curve of a chart at the slice `value` (the chart's box open ends
// excluded), ascending and merged (one root per distinct value, with all its curves' features).
struct SliceRoot {
  Real at;
  std::vector<FeatureId> features;
};
std::vector<SliceRoot> slice_roots(const ChartData& chart, bool along_x, const Rational& value, const Rational& lower,
                                   const Rational& upper) {
  std::vector<SliceRoot> roots;
  for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
    cspace::algebra::Polynomial p = along_x ? cspace::algebra::substitute_x(chart.polynomials[k], value)
                                            : cspace::algebra::substitute_y(chart.polynomials[k], value);
    if (p.empty()) continue;   // the slice runs along the curve: located below
    for (Real& r : cspace::algebra::real_roots(p, lower, upper)) {
      if (r.compare(lower) == 0 || r.compare(upper) == 0) continue;
      FeatureId id(chart.curve_global[k]);
      auto it = std::find_if(roots.begin(), roots.end(),
                             [&](const SliceRoot& o) { return cspace::algebra::compare(o.at, r) == 0; });
      if (it == roots.end()) {
        roots.push_back(SliceRoot{std::move(r), {id}});
      } else if (std::find(it->features.begin(), it->features.end(), id) == it->features.end()) {
        it->features.push_back(id);
      }
    }
  }
  std::sort(roots.begin(), roots.end(),
            [](const SliceRoot& a, const SliceRoot& b) { return cspace::algebra::compare(a.at, b.at) < 0; });
  return roots;
}

}  // namespace

namespace {

// The interval of a slice holding the chart point (c; value along the fixed axis, t along the
// free one): its cell and kind by exact point location.
Slice::Interval slice_interval(const CSpace& space, const CSpace::Impl& impl, std::size_t c, SliceAxis axis,
                               const Rational& value, const Rational& t) {
  ChartPoint q = axis == SliceAxis::x ? ChartPoint{c, value, t} : ChartPoint{c, t, value};
  Location where = space.locate(q);
  Slice::Interval interval;
  interval.sample = t;
  interval.cell = CellId(where.cell);
  if (where.kind == Location::Kind::blocked) interval.kind = CellKind::blocked;
  else if (where.kind == Location::Kind::free) interval.kind = CellKind::free;
  else interval.kind = contact_location(impl, where) ? CellKind::touching : CellKind::free;
  if (where.kind == Location::Kind::touching) interval.kind = CellKind::touching;
  return interval;
}

}  // namespace

std::vector<Slice> CSpace::slice(SliceAxis axis, const Rational& value_input) const {
  const Impl& impl = checked(*this);
  if (impl.dimension != 2) throw GeometryError("slice: a 1-D C-space is its own slice (use cells and vertices)");
  Rational value = value_input;
  value.canonicalize();
  std::vector<Slice> slices;
  for (std::size_t c = 0; c < impl.charts.size(); ++c) {
    const CSpaceChart& box = impl.public_charts[c];
    bool along_x = axis == SliceAxis::x;
    const Rational& fixed_lo = along_x ? box.x_lo : box.y_lo;
    const Rational& fixed_hi = along_x ? box.x_hi : box.y_hi;
    if (value < fixed_lo || value > fixed_hi) continue;
    Slice s;
    s.chart = c;
    s.axis = axis;
    s.value = value;
    s.lower = along_x ? box.y_lo : box.x_lo;
    s.upper = along_x ? box.y_hi : box.x_hi;
    std::vector<SliceRoot> roots = slice_roots(impl.charts[c], along_x, value, s.lower, s.upper);
    Real previous = Real::from_rational(s.lower);
    std::vector<Slice::Interval> intervals;
    for (std::size_t i = 0; i <= roots.size(); ++i) {
      Real next = i < roots.size() ? roots[i].at : Real::from_rational(s.upper);
      intervals.push_back(slice_interval(*this, impl, c, axis, value, cspace::algebra::rational_between(previous, next)));
      previous = next;
    }
    // keep the boundaries between different cells only
    s.intervals.push_back(intervals[0]);
    for (std::size_t i = 0; i < roots.size(); ++i) {
      const Slice::Interval& before = s.intervals.back();
      const Slice::Interval& after = intervals[i + 1];
      if (before.cell == after.cell && before.kind == after.kind) continue;
      s.points.push_back(Slice::Point{cspace::to_public(roots[i].at), roots[i].features});
      s.intervals.push_back(after);
    }
    slices.push_back(std::move(s));
  }
  return slices;
}

std::optional<Slice> slice_near(const CSpace& space, std::size_t chart, SliceAxis axis, const Rational& value_input,
                                const Rational& at_input, std::size_t boundaries) {
  const CSpace::Impl& impl = checked(space);
  if (impl.dimension != 2) throw GeometryError("slice_near: a 1-D C-space is its own slice (use cells and vertices)");
  if (chart >= impl.charts.size()) throw GeometryError("slice_near: no chart " + std::to_string(chart));
  if (boundaries == 0) throw GeometryError("slice_near: at least one boundary on either side");
  Rational value = value_input, at = at_input;
  value.canonicalize();
  at.canonicalize();
  const CSpaceChart& box = impl.public_charts[chart];
  bool along_x = axis == SliceAxis::x;
  const Rational& fixed_lo = along_x ? box.x_lo : box.y_lo;
  const Rational& fixed_hi = along_x ? box.x_hi : box.y_hi;
  if (value < fixed_lo || value > fixed_hi) return std::nullopt;
  Slice s;
  s.chart = chart;
  s.axis = axis;
  s.value = value;
  s.lower = along_x ? box.y_lo : box.x_lo;
  s.upper = along_x ? box.y_hi : box.x_hi;
  if (at < s.lower || at > s.upper) return std::nullopt;
  std::vector<SliceRoot> roots = slice_roots(impl.charts[chart], along_x, value, s.lower, s.upper);
  // Sub-interval i lies between roots i - 1 and i (the box's ends beyond the first and last),
  // located lazily: only those from `at` outward to the `boundaries`-th cell change each way.
  std::size_t n = roots.size();
  std::vector<std::optional<Slice::Interval>> located(n + 1);
  auto interval = [&](std::size_t i) -> const Slice::Interval& {
    if (!located[i]) {
      Real below = i == 0 ? Real::from_rational(s.lower) : roots[i - 1].at;
      Real above = i == n ? Real::from_rational(s.upper) : roots[i].at;
      located[i] = slice_interval(space, impl, chart, axis, value, cspace::algebra::rational_between(below, above));
    }
    return *located[i];
  };
  auto differ = [&](std::size_t i) {   // a cell boundary at root i (between sub-intervals i and i + 1)
    const Slice::Interval &a = interval(i), &b = interval(i + 1);
    return !(a.cell == b.cell && a.kind == b.kind);
  };
  // Roots below `at`; `at` may lie on root `first` itself.
  std::size_t first = 0;
  while (first < n && roots[first].at.compare(at) < 0) ++first;
  bool on_root = first < n && roots[first].at.compare(at) == 0;
  std::vector<std::size_t> kept;   // cell boundaries (root indices), found outward from `at`
  for (std::size_t i = first; i-- > 0 && kept.size() < boundaries;)
    if (differ(i)) kept.push_back(i);
  std::reverse(kept.begin(), kept.end());
  if (on_root && differ(first)) kept.push_back(first);
  std::size_t found_up = 0;
  for (std::size_t i = on_root ? first + 1 : first; i < n && found_up < boundaries; ++i)
    if (differ(i)) {
      kept.push_back(i);
      ++found_up;
    }
  // Between consecutive boundaries every sub-interval has the boundary's upper cell and kind.
  s.intervals.push_back(interval(kept.empty() ? first : kept.front()));
  for (std::size_t i : kept) {
    s.points.push_back(Slice::Point{cspace::to_public(roots[i].at), roots[i].features});
    s.intervals.push_back(interval(i + 1));
  }
  return s;
}

std::vector<CSpaceFace> CSpace::faces(std::size_t chart_index) const {
  const Impl& impl = checked(*this);
  if (chart_index >= impl.charts.size()) throw GeometryError("faces: no chart " + std::to_string(chart_index));
  const ChartData& chart = impl.charts[chart_index];
  auto kind_of = [](cspace::FaceKind kind) {
    return kind == cspace::FaceKind::blocked    ? CellKind::blocked
           : kind == cspace::FaceKind::touching ? CellKind::touching
                                                : CellKind::free;
  };
  std::vector<CSpaceFace> result;
  if (impl.dimension == 1) {
    for (std::size_t i = 0; i < chart.faces.size(); ++i) {
      CSpaceFace face;
      face.chart = chart_index;
      face.classified = chart.faces[i].kind != cspace::FaceKind::outside;
      face.kind = kind_of(chart.faces[i].kind);
      if (face.classified) face.cell = CellId(chart.faces[i].cell);
      if (i > 0) face.lower = VertexId(chart.vertex_global[i - 1]);
      if (i < chart.points.size()) face.upper = VertexId(chart.vertex_global[i]);
      result.push_back(std::move(face));
    }
    return result;
  }
  const auto& arrangement = chart.arrangement;
  for (std::size_t f = 0; f < arrangement.faces.size(); ++f) {
    const cspace::raw::Face& raw_face = arrangement.faces[f];
    if (raw_face.unbounded) continue;
    CSpaceFace face;
    face.chart = chart_index;
    face.classified = chart.faces[f].kind != cspace::FaceKind::outside;
    face.kind = kind_of(chart.faces[f].kind);
    if (face.classified) face.cell = CellId(chart.faces[f].cell);
    for (std::size_t k = 0; k < raw_face.component_starts.size(); ++k) {
      std::size_t begin = raw_face.component_starts[k];
      std::size_t end = k + 1 < raw_face.component_starts.size() ? raw_face.component_starts[k + 1] : raw_face.boundary.size();
      std::vector<std::pair<EdgeId, bool>> cycle;
      for (std::size_t i = begin; i < end; ++i) {
        auto [e, forward] = raw_face.boundary[i];
        cycle.emplace_back(EdgeId(chart.edges[e].global), forward);
      }
      face.boundary.push_back(std::move(cycle));
    }
    result.push_back(std::move(face));
  }
  return result;
}

std::vector<std::vector<mpz_class>> CSpace::curve_polynomial(std::size_t chart_index, FeatureId feature) const {
  const Impl& impl = checked(*this);
  if (chart_index >= impl.charts.size()) throw GeometryError("curve_polynomial: no chart " + std::to_string(chart_index));
  index_in(feature, impl.feature_pairs.size(), "feature pair");
  const ChartData& chart = impl.charts[chart_index];
  for (std::size_t k = 0; k < chart.curve_global.size(); ++k)
    if (chart.curve_global[k] == feature.index()) return chart.polynomials[k].coefficients;
  return {};
}

EdgePolyline CSpace::edge_polyline(EdgeId id, std::size_t samples) const {
  const Impl& impl = checked(*this);
  std::size_t index = index_in(id, impl.edges.size(), "edge");
  if (impl.dimension != 2) throw GeometryError("edge_polyline: a 1-D C-space has no edges to draw");
  samples = std::max<std::size_t>(samples, 2);
  auto [c, e] = impl.edge_local[index];
  const ChartData& chart = impl.charts[c];
  const cspace::raw::Edge& raw_edge = chart.arrangement.edges[e];
  EdgePolyline line;
  auto add_error = [&](const Real& r, double value) {
    line.error = std::max({line.error, std::fabs(r.upper_bound() - value), std::fabs(value - r.lower_bound())});
  };
  // an end of the edge: the vertex when its y is an algebraic number (rational x); otherwise
  // the point of the edge at a rational abscissa within 2^-60 of the vertex, inside the edge
  auto vertex_point = [&](std::size_t v, bool low_end) {
    const cspace::raw::Vertex& vertex = chart.arrangement.vertices[v];
    Real x = vertex.x;
    x.refine_to(Rational(1, mpz_class(1) << 60));
    double px = x.approximate();
    add_error(x, px);
    if (vertex.y_exact) {
      Real y = vertex.y;
      y.refine_to(Rational(1, mpz_class(1) << 60));
      double py = y.approximate();
      add_error(y, py);
      return std::array<double, 2>{px, py};
    }
    // irrational x: the edge's point at the end of x's isolating interval that lies inside the
    // edge (when the edge is longer than that), else the vertex's certified y interval
    const cspace::raw::Vertex& other = chart.arrangement.vertices[low_end ? raw_edge.max_vertex : raw_edge.min_vertex];
    Rational inside = low_end ? x.upper : x.lower;
    bool fits = !raw_edge.vertical && !x.exact && (low_end ? other.x.compare(inside) > 0 : other.x.compare(inside) < 0);
    if (!fits) {
      Rational middle = (vertex.y_lower + vertex.y_upper) / 2;
      double py = middle.get_d();
      line.error = std::max({line.error, std::fabs(cspace::algebra::upper_double(vertex.y_upper) - py),
                             std::fabs(py - cspace::algebra::lower_double(vertex.y_lower))});
      return std::array<double, 2>{px, py};
    }
    Real y = cspace::edge_y_at(chart, e, inside);
    y.refine_to(Rational(1, mpz_class(1) << 60));
    double py = y.approximate();
    add_error(y, py);
    line.error = std::max(line.error, std::fabs(Rational(inside - Rational(px)).get_d()));
    return std::array<double, 2>{px, py};
  };
  line.points.push_back(vertex_point(raw_edge.min_vertex, true));
  if (!raw_edge.vertical) {
    const Real& lo = chart.arrangement.vertices[raw_edge.min_vertex].x;
    const Real& hi = chart.arrangement.vertices[raw_edge.max_vertex].x;
    double a = lo.upper_bound(), b = hi.lower_bound();
    for (std::size_t i = 1; i + 1 < samples && a < b; ++i) {
      double x = a + (b - a) * static_cast<double>(i) / static_cast<double>(samples - 1);
      if (!(x > a && x < b)) continue;
      CertifiedValue y = evaluate(index, x);
      line.points.push_back({x, y.value});
      line.error = std::max(line.error, y.error);
    }
  }
  line.points.push_back(vertex_point(raw_edge.max_vertex, false));
  return line;
}

// ------------------------------------------------------------------ first crossing along a motion

namespace {

constexpr mpfr_prec_t precision = 160;

// RAII for MPFI / MPFR values: core/mp_values.hpp.
using Mpfi = MpfiValue;
using Mpfr = MpfrValue;

Rational to_rational(const mpfr_t value) {
  Rational r;
  mpfr_get_q(r.get_mpq_t(), value);
  return r;
}

using cspace::ExactBound;
using cspace::Side;

// One axis's position over a stretch of the path in one chart system: a rotation chart
// centred at 0 or pi, or a translation; [lo, hi] in chart coordinates, exact.
struct AxisPiece {
  bool rotation = true;
  bool half_turn = false;
  ExactBound lo, hi;
  // lower_double(lo), upper_double(hi), set once (with_doubles) and carried along
  double dlo = 0, dhi = 0;
};

AxisPiece with_doubles(AxisPiece p) {
  p.dlo = cspace::algebra::lower_double(p.lo.rational());
  p.dhi = cspace::algebra::upper_double(p.hi.rational());
  return p;
}

// The pieces of filtered_angle_ranges' t-ranges: their bounds are the doubles themselves.
std::vector<AxisPiece> range_pieces(const cspace::AngleRanges& ranges) {
  std::vector<AxisPiece> pieces;
  pieces.reserve(ranges.size);
  for (std::size_t i = 0; i < ranges.size; ++i)
    pieces.push_back(AxisPiece{true, ranges.half_turn[i], ExactBound::of_double(ranges.lo[i]),
                               ExactBound::of_double(ranges.hi[i]), ranges.lo[i], ranges.hi[i]});
  return pieces;
}

// tan(angle / 2), rounded down or up; \pre |angle| < pi.
Rational tan_half(const mpfr_t angle, mpfr_rnd_t rounding, mpfr_prec_t bits) {
  Mpfr half(bits), t(bits);
  mpfr_div_2ui(half.v, angle, 1, MPFR_RNDN);   // exact
  mpfr_tan(t.v, half.v, rounding);
  return to_rational(t.v);
}

// pi and pi / 2 enclosed at `bits`, and the bounds of pi / 2 that angle_pieces compares with,
// made once per thread and precision (the same numbers on every call)
struct PiBounds {
  explicit PiBounds(mpfr_prec_t bits) : bits(bits), pi(bits), half_pi(bits), hp_lo(bits), hp_hi(bits), below(bits), neg_lo(bits) {
    mpfi_const_pi(pi.v);
    mpfi_div_2ui(half_pi.v, pi.v, 1);
    mpfi_get_left(hp_lo.v, half_pi.v);
    mpfi_get_right(hp_hi.v, half_pi.v);
    mpfr_neg(below.v, hp_hi.v, MPFR_RNDN);   // -pi/2 >= -hp_hi
    mpfr_neg(neg_lo.v, hp_lo.v, MPFR_RNDN);
  }
  mpfr_prec_t bits;
  Mpfi pi, half_pi;
  Mpfr hp_lo, hp_hi, below, neg_lo;
};
const PiBounds& pi_bounds(mpfr_prec_t bits) {
  thread_local std::vector<std::unique_ptr<PiBounds>> made;
  for (const auto& b : made)
    if (b->bits == bits) return *b;
  made.push_back(std::make_unique<PiBounds>(bits));
  return *made.back();
}

// The chart-coordinate pieces of an angle enclosure `theta` (width < 2): t = tan((theta - c)/2)
// in the charts centred at c = 0 and c = pi, clipped at the seams theta = +-pi/2 (where t = +-1
// exactly), so that the pieces cover every angle in `theta`. Computed with `bits` of precision
// and directed rounding: certified at any precision, tighter at more.
std::vector<AxisPiece> angle_pieces(const RInterval& theta, mpfr_prec_t bits) {
  const PiBounds& constants = pi_bounds(bits);
  const mpfi_t& pi = constants.pi.v;
  Mpfi angle(bits);
  mpfi_interv_q(angle.v, theta.lo.get_mpq_t(), theta.hi.get_mpq_t());
  // reduce by a whole number of turns: k = floor((mid + pi) / 2 pi) (none within [-3, 3]:
  // point_tangent.hpp)
  if (cspace::point_tangents() && cspace::zero_turns(theta.lo.get_mpq_t(), theta.hi.get_mpq_t())) {
    ++cspace::point_tangent_shortcuts();
  } else {
    Mpfr mid(bits), turn(bits), k(bits);
    Rational m = (theta.lo + theta.hi) / 2;
    mpfr_set_q(mid.v, m.get_mpq_t(), MPFR_RNDN);
    mpfr_const_pi(turn.v, MPFR_RNDN);
    mpfr_add(mid.v, mid.v, turn.v, MPFR_RNDN);
    mpfr_mul_2ui(turn.v, turn.v, 1, MPFR_RNDN);
    mpfr_div(k.v, mid.v, turn.v, MPFR_RNDN);
    mpfr_floor(k.v, k.v);
    mpz_class turns;
    mpfr_get_z(turns.get_mpz_t(), k.v, MPFR_RNDN);
    Mpfi full(bits);
    mpfi_mul_2ui(full.v, pi, 1);
    mpfi_mul_z(full.v, full.v, turns.get_mpz_t());
    mpfi_sub(angle.v, angle.v, full.v);
  }
  const Mpfr& hp_lo = constants.hp_lo;
  const Mpfr& hp_hi = constants.hp_hi;
  std::vector<AxisPiece> pieces;
  // tau = angle - centre, clipped to [-pi/2, pi/2]
  Mpfr lo(bits), hi(bits);   // tau's ends (each piece's)
  auto piece = [&](const mpfi_t tau, bool half_turn) {
    mpfi_get_left(lo.v, tau);
    mpfi_get_right(hi.v, tau);
    // certainly below -pi/2 or certainly above pi/2: not in this chart
    if (mpfr_cmp(hi.v, constants.below.v) < 0 || mpfr_cmp(lo.v, hp_hi.v) > 0) return;
    AxisPiece p;
    p.rotation = true;
    p.half_turn = half_turn;
    const Mpfr& neg_lo = constants.neg_lo;
    const bool clipped_lo = mpfr_cmp(lo.v, neg_lo.v) <= 0, clipped_hi = mpfr_cmp(hi.v, hp_lo.v) >= 0;
    if (!clipped_lo && !clipped_hi) {
      // both ends' tangents (a point's from one: point_tangent.hpp)
      Mpfr down(bits), up(bits);
      cspace::tan_half_bounds(down.v, up.v, lo.v, hi.v);
      p.lo = to_rational(down.v);
      p.hi = to_rational(up.v);
    } else {
      p.lo = clipped_lo ? Rational(-1) : tan_half(lo.v, MPFR_RNDD, bits);
      p.hi = clipped_hi ? Rational(1) : tan_half(hi.v, MPFR_RNDU, bits);
    }
    if (p.lo > p.hi) return;
    pieces.push_back(p);
  };
  piece(angle.v, false);
  Mpfi tau(bits);
  mpfi_sub(tau.v, angle.v, pi);
  piece(tau.v, true);
  mpfi_add(tau.v, angle.v, pi);
  piece(tau.v, true);
  return pieces;
}

// cspace::filtered_angle_ranges(theta) through the per-thread memo of angle_memo.hpp: a
// direct-mapped table keyed by the bit patterns of theta's ends; a hit is a copy of the ranges
// filtered_angle_ranges made for that same theta (a pure function of it).
std::optional<cspace::AngleRanges> memo_filtered_angle_ranges(const KInterval& theta) {
  if (!cspace::angle_memo()) return cspace::filtered_angle_ranges(theta);
  struct Entry {
    std::uint64_t lo = 0, hi = 0;
    bool used = false;
    std::optional<cspace::AngleRanges> ranges;
  };
  constexpr std::size_t size = 64;
  thread_local std::array<Entry, size> table;
  const auto lo = std::bit_cast<std::uint64_t>(theta.lo), hi = std::bit_cast<std::uint64_t>(theta.hi);
  std::uint64_t mix = (lo ^ (hi * 0x9E3779B97F4A7C15ull)) * 0xC2B2AE3D27D4EB4Full;
  Entry& entry = table[static_cast<std::size_t>(mix >> 58) % size];
  if (entry.used && entry.lo == lo && entry.hi == hi) {
    ++cspace::angle_memo_hits();
    return entry.ranges;
  }
  entry.ranges = cspace::filtered_angle_ranges(theta);
  entry.lo = lo;
  entry.hi = hi;
  entry.used = true;
  return entry.ranges;
}

// angle_pieces(theta, bits) through the same memo (angle_memo.hpp): the last few exact thetas
// and their pieces, compared exactly (the nudge's trials move the free part only, so a driven
// part's start angle recurs in every trial that falls back to the 160-bit pieces).
std::vector<AxisPiece> memo_angle_pieces(const RInterval& theta, mpfr_prec_t bits) {
  if (!cspace::angle_memo()) return angle_pieces(theta, bits);
  struct Entry {
    RInterval theta;
    mpfr_prec_t bits = 0;
    std::vector<AxisPiece> pieces;
  };
  constexpr std::size_t size = 8;
  thread_local std::array<Entry, size> table;
  thread_local std::size_t next = 0;
  for (const Entry& entry : table)
    if (entry.bits == bits && entry.theta.lo == theta.lo && entry.theta.hi == theta.hi) {
      ++cspace::angle_memo_hits();
      return entry.pieces;
    }
  Entry& entry = table[next];
  next = (next + 1) % size;
  entry.pieces = angle_pieces(theta, bits);
  entry.theta = theta;
  entry.bits = bits;
  return entry.pieces;
}

// angle_pieces(theta, 64)'s pieces through the double-interval filter (src/cspace/angle_filter.hpp);
// nullopt where the filter cannot decide: the caller takes angle_pieces.
std::optional<std::vector<AxisPiece>> angle_pieces_filtered(const RInterval& theta) {
  std::optional<cspace::AngleRanges> ranges = cspace::filtered_angle_ranges(
      KInterval(KInterval::enclose(theta.lo).lo, KInterval::enclose(theta.hi).hi));
  if (!ranges) return std::nullopt;
  return range_pieces(*ranges);
}

// The chart-coordinate pieces of a half-angle-tangent enclosure t0 (chart centred at 0): the
// part within [-1, 1], and the parts beyond the seams mapped to the chart centred at pi by
// t -> -1/t.
std::vector<AxisPiece> tangent_pieces(const RInterval& t) {
  std::vector<AxisPiece> pieces;
  Rational one(1), minus_one(-1);
  if (t.hi >= minus_one && t.lo <= one)
    pieces.push_back(AxisPiece{true, false, std::max(t.lo, minus_one), std::min(t.hi, one)});
  if (t.hi >= one) {
    Rational a = -1 / std::max(t.lo, one), b = -1 / t.hi;
    pieces.push_back(AxisPiece{true, true, a, b});
  }
  if (t.lo <= minus_one) {
    Rational a = -1 / t.lo, b = -1 / std::min(t.hi, minus_one);
    pieces.push_back(AxisPiece{true, true, a, b});
  }
  return pieces;
}

// A box of one chart where the path may be.
struct PieceBox {
  std::size_t chart = 0;
  ExactBound x_lo, x_hi, y_lo, y_hi;
  // lower_double(x_lo), upper_double(x_hi), ... (carried: lower_double of a maximum is the
  // maximum of the lower_doubles, upper_double of a minimum the minimum of the upper_doubles)
  double dx_lo = 0, dx_hi = 0, dy_lo = 0, dy_hi = 0;
};

// A contact curve of a chart that is not excluded over a box.
struct Possible {
  std::size_t chart, curve, piece;
};

// A box of one chart certified inside one face of its free cell `cell`: no curve of the chart
// vanishes on it (interval enclosure; the arrangement's edges and vertices lie on these curves),
// and a path that stayed in `cell` passed through it. A rational point in it and strictly inside
// the chart's box lies in that face's interior: point location answers free, `cell`, `chart`.
// Kept per thread and per space (a weak_ptr: a space freed and another built at its address is
// never matched), one per space.
struct StartAnchor {
  std::weak_ptr<const CSpace::Impl> owner;
  std::size_t chart = 0, cell = 0;
  Rational x_lo, x_hi, y_lo, y_hi;
};

std::vector<StartAnchor>& start_anchor_list() {
  thread_local std::vector<StartAnchor> list;
  return list;
}

bool same_owner(const std::weak_ptr<const CSpace::Impl>& a, const std::shared_ptr<const CSpace::Impl>& b) {
  return !a.owner_before(b) && !b.owner_before(a);
}

const StartAnchor* find_anchor(const std::shared_ptr<const CSpace::Impl>& owner) {
  if (!cspace::start_anchors()) return nullptr;
  for (const StartAnchor& anchor : start_anchor_list())
    if (!anchor.owner.expired() && same_owner(anchor.owner, owner)) return &anchor;
  return nullptr;
}

void remember_anchor(StartAnchor anchor, const std::shared_ptr<const CSpace::Impl>& owner) {
  std::vector<StartAnchor>& list = start_anchor_list();
  std::erase_if(list, [&](const StartAnchor& a) { return a.owner.expired() || same_owner(a.owner, owner); });
  if (list.size() >= 16) list.erase(list.begin());
  anchor.owner = owner;
  list.push_back(std::move(anchor));
}

// The anchor boxes (angle_filter.hpp, anchor_boxes): the boxes certified in a query's start cell
// (its located start's, its excluded stretches') with that cell, per thread, the last 16 per space
// (its owner).
struct AnchorBox : PieceBox {
  std::size_t cell = 0;
};
struct AnchorBoxes {
  std::weak_ptr<const CSpace::Impl> owner;
  std::vector<AnchorBox> boxes;
};

std::vector<AnchorBoxes>& anchor_box_list() {
  thread_local std::vector<AnchorBoxes> list;
  return list;
}

AnchorBoxes* find_anchor_boxes(const std::shared_ptr<const CSpace::Impl>& owner) {
  if (!cspace::anchor_boxes()) return nullptr;
  for (AnchorBoxes& entry : anchor_box_list())
    if (!entry.owner.expired() && same_owner(entry.owner, owner)) return &entry;
  return nullptr;
}

void remember_anchor_boxes(std::vector<AnchorBox>& boxes, const std::shared_ptr<const CSpace::Impl>& owner) {
  AnchorBoxes* entry = find_anchor_boxes(owner);
  if (!entry) {
    std::vector<AnchorBoxes>& list = anchor_box_list();
    std::erase_if(list, [](const AnchorBoxes& a) { return a.owner.expired(); });
    if (list.size() >= 16) list.erase(list.begin());
    list.push_back(AnchorBoxes{owner, {}});
    entry = &list.back();
  }
  // the 16 most recent, moved in (the older ones dropped first)
  std::vector<AnchorBox>& kept = entry->boxes;
  const std::size_t take = std::min<std::size_t>(boxes.size(), 16);
  const std::size_t keep = std::min(kept.size(), 16 - take);
  kept.erase(kept.begin(), kept.end() - static_cast<std::ptrdiff_t>(keep));
  kept.insert(kept.end(), std::make_move_iterator(boxes.end() - static_cast<std::ptrdiff_t>(take)),
              std::make_move_iterator(boxes.end()));
}

// The scanner's data derived from the space alone, filled on first use: per chart (sized by
// scan_memo_of), per local curve. Shared by the first_crossing calls of a space on one thread
// (scan_memo, cspace/scan_memo.hpp), or made for one call when the switch is off.
struct ScanMemo {
  std::weak_ptr<const CSpace::Impl> owner;
  // the curves of a chart that can bound a cell: those carried by an edge between different
  // cells (contact edges), with the edges' certified boxes, and those through an isolated vertex
  struct Carrier {
    double box[4];
    std::vector<std::size_t> curves;
  };
  struct ChartCarriers {
    bool ready = false;
    std::vector<Carrier> edges;
    std::vector<std::size_t> everywhere;
    // the other edges with a curve (spurious, inside one cell), for locate_inside's anchor boxes
    std::vector<Carrier> inner;
  };
  // A partial derivative D of a chart curve F, enclosed at F's scale: the interval polynomial
  // encloses D / 2^interval_shift(D), and evaluate multiplies by 2^(that shift - F's), so that it
  // encloses D / 2^interval_shift(F), as curve_enclosure(k) encloses F / 2^shift(F)
  // (algebra/interval_shift.hpp: the mean-value and Taylor forms add F and its derivatives).
  struct ScaledPartial {
    ScaledPartial(const cspace::IntegerPolynomial2& d, long f_shift)
        : polynomial(scaled(d)), exponent(cspace::algebra::interval_shift(d) - f_shift) {}
    static cspace::algebra::IntervalPolynomial2 scaled(const cspace::IntegerPolynomial2& d) {
      cspace::algebra::ScaledEnclosures scope;
      return cspace::algebra::IntervalPolynomial2(d);
    }
    cspace::algebra::Interval evaluate(cspace::algebra::Interval x, cspace::algebra::Interval y) const {
      const cspace::algebra::Interval value = polynomial.evaluate(x, y);
      return exponent == 0 ? value : cspace::algebra::scale_by_power_of_two(value, exponent);
    }
    cspace::algebra::IntervalPolynomial2 polynomial;
    long exponent = 0;   // 0 for every polynomial of ordinary size
  };
  struct Gradient {
    ScaledPartial fx, fy;
  };
  struct Hessian {
    ScaledPartial fxx, fxy, fyy;
  };
  using Clauses = std::vector<std::vector<cspace::algebra::IntervalPolynomial2>>;
  std::vector<ChartCarriers> carriers;
  // per chart: its curves' enclosures made under ScaledEnclosures where one of them has
  // coefficients beyond interval_coefficient_bits (empty: chart.interval_polynomials serve, the
  // same enclosures), and whether that was looked at (curve_enclosure)
  std::vector<std::vector<cspace::algebra::IntervalPolynomial2>> scaled_curves;
  std::vector<char> scaled_ready;
  std::vector<std::vector<std::optional<Gradient>>> gradients;
  std::vector<std::vector<std::optional<Hessian>>> hessians;
  std::vector<std::vector<std::optional<Clauses>>> validity;
  std::vector<std::array<double, 4>> chart_boxes;   // lower/upper doubles of the public charts' sides
  // per public chart: lower_double and upper_double of x_lo, x_hi, y_lo, y_hi (MotionScanner::side)
  std::vector<std::array<double, 8>> chart_sides;
  // per global vertex: compare_ordinate's fibre signs, once made
  std::vector<std::optional<FibreSigns>> fibre_signs;
  // per global vertex: the bounds compare_ordinate has proved on its ordinate (OrdinateBounds)
  std::vector<OrdinateBounds> ordinates;
  // per global vertex: compare_ordinate's filter data (enclosed_fibre_sign), once made
  struct FibreEnclosure {
    cspace::IntegerPolynomial2 decider;   // the fibre or its y-derivative
    Rational x_lo, x_hi;                  // x_lo < x_v < x_hi (narrowed); unused where x_v is rational
    cspace::algebra::Interval x;          // doubles around [x_lo, x_hi]
    bool exact = false;                   // x_v is rational (the exact sign is cheap)
  };
  std::vector<std::optional<FibreEnclosure>> fibre_enclosures;
  // per global edge: track_derivatives' placement data (a TrackerData), once made
  std::vector<std::shared_ptr<const void>> tracker_data;
  // the last few exact edge ordinates asked (edge_ordinate), newest last
  std::vector<std::shared_ptr<const EdgeOrdinate>> ordinates_at;
};

std::shared_ptr<ScanMemo> fresh_scan_memo(const CSpace::Impl& impl) {
  auto memo = std::make_shared<ScanMemo>();
  memo->carriers.resize(impl.charts.size());
  memo->scaled_curves.resize(impl.charts.size());
  memo->scaled_ready.assign(impl.charts.size(), 0);
  memo->gradients.resize(impl.charts.size());
  memo->hessians.resize(impl.charts.size());
  memo->validity.resize(impl.charts.size());
  for (const CSpaceChart& chart : impl.public_charts) {
    std::array<double, 8> sides{};
    const Rational* r[4] = {&chart.x_lo, &chart.x_hi, &chart.y_lo, &chart.y_hi};
    for (int k = 0; k < 4; ++k) {
      sides[2 * k] = cspace::algebra::lower_double(*r[k]);
      sides[2 * k + 1] = cspace::algebra::upper_double(*r[k]);
    }
    memo->chart_sides.push_back(sides);
  }
  for (const CSpaceChart& chart : impl.public_charts)
    memo->chart_boxes.push_back({cspace::algebra::lower_double(chart.x_lo), cspace::algebra::upper_double(chart.x_hi),
                                 cspace::algebra::lower_double(chart.y_lo), cspace::algebra::upper_double(chart.y_hi)});
  return memo;
}

// Curve k of chart c enclosed for the crossing queries: F / 2^interval_shift(F)
// (algebra/interval_shift.hpp) — the builder's chart.interval_polynomials[k] itself unless some
// curve of the chart has coefficients beyond interval_coefficient_bits (their enclosures
// unbounded: every curve "possibly vanished" everywhere), then the chart's curves made under
// ScaledEnclosures once per memo.
const cspace::algebra::IntervalPolynomial2& curve_enclosure(const CSpace::Impl& impl, ScanMemo& memo, std::size_t c,
                                                            std::size_t k) {
  std::vector<cspace::algebra::IntervalPolynomial2>& scaled = memo.scaled_curves[c];
  if (!memo.scaled_ready[c]) {
    memo.scaled_ready[c] = 1;
    const std::vector<cspace::IntegerPolynomial2>& curves = impl.charts[c].polynomials;
    if (std::any_of(curves.begin(), curves.end(),
                    [](const cspace::IntegerPolynomial2& f) { return cspace::algebra::interval_shift(f) > 0; })) {
      cspace::algebra::ScaledEnclosures scope;
      scaled.reserve(curves.size());
      for (const cspace::IntegerPolynomial2& f : curves) scaled.emplace_back(f);
    }
  }
  return scaled.empty() ? impl.charts[c].interval_polynomials[k] : scaled[k];
}

// The curves of chart c that can bound a cell (ScanMemo::carriers), made on first use.
const ScanMemo::ChartCarriers& chart_carriers(const CSpace::Impl& impl, ScanMemo& memo, std::size_t c) {
  ScanMemo::ChartCarriers& result = memo.carriers[c];
  if (result.ready) return result;
  result.ready = true;
  const ChartData& chart = impl.charts[c];
  for (std::size_t e = 0; e < chart.edges.size(); ++e) {
    const CSpaceEdge& edge = impl.edges[chart.edges[e].global];
    if (chart.edges[e].curves.empty()) continue;
    ScanMemo::Carrier carrier;
    std::copy(std::begin(chart.arrangement.edges[e].box), std::end(chart.arrangement.edges[e].box), carrier.box);
    carrier.curves = chart.edges[e].curves;
    (!edge.real && edge.left_cell == edge.right_cell ? result.inner : result.edges).push_back(std::move(carrier));
  }
  for (std::size_t v = 0; v < chart.arrangement.vertices.size(); ++v) {
    if (!chart.arrangement.vertices[v].isolated) continue;
    const CSpaceVertex& vertex = impl.vertices[chart.vertex_global[v]];
    for (std::size_t k = 0; k < chart.curve_global.size(); ++k)
      if (std::find(vertex.curves.begin(), vertex.curves.end(), chart.curve_global[k]) != vertex.curves.end())
        result.everywhere.push_back(k);
  }
  return result;
}

// The scan memo of the space `owner` on this thread (made on first use), or a fresh one when
// the switch is off. Held by shared_ptr: a scanner keeps its memo even if the list drops it.
std::shared_ptr<ScanMemo> scan_memo_of(const std::shared_ptr<const CSpace::Impl>& owner) {
  if (!cspace::scan_memo()) return fresh_scan_memo(*owner);
  thread_local std::vector<std::shared_ptr<ScanMemo>> memos;
  for (const std::shared_ptr<ScanMemo>& m : memos)
    if (!m->owner.expired() && !m->owner.owner_before(owner) && !owner.owner_before(m->owner)) {
      ++cspace::scan_memo_hits();
      return m;
    }
  std::erase_if(memos, [](const std::shared_ptr<ScanMemo>& m) { return m->owner.expired(); });
  if (memos.size() >= 16) memos.erase(memos.begin());
  std::shared_ptr<ScanMemo> memo = fresh_scan_memo(*owner);
  memo->owner = owner;
  memos.push_back(memo);
  return memo;
}

std::shared_ptr<std::shared_ptr<const void>> tracker_data_slot(const CSpace& space, std::size_t index) {
  if (!cspace::scan_memo() || !cspace::tracker_memo()) return nullptr;
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  if (memo->tracker_data.empty()) memo->tracker_data.resize(implementation(space).edges.size());
  // (the slot shares the memo's ownership: it stays valid however the thread's list changes)
  return std::shared_ptr<std::shared_ptr<const void>>(memo, &memo->tracker_data[index]);
}

std::shared_ptr<const EdgeOrdinate> edge_ordinate(const CSpace& space, std::size_t index, const Rational& x) {
  const CSpace::Impl& impl = implementation(space);
  auto make = [&] {
    auto [c, e] = impl.edge_local[index];
    auto made = std::make_shared<EdgeOrdinate>();
    made->edge = index;
    made->x = x;
    made->y = cspace::edge_y_at(impl.charts[c], e, x);
    made->y64 = made->y;
    if (!made->y64.exact) made->y64.refine_to(Rational(1, mpz_class(1) << 64));
    return made;
  };
  if (!cspace::scan_memo() || !cspace::ordinate_at_memo()) return make();
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  for (const std::shared_ptr<const EdgeOrdinate>& known : memo->ordinates_at)
    if (known->edge == index && known->x == x) {
      ++cspace::ordinate_at_memo_hits();
      return known;
    }
  std::shared_ptr<const EdgeOrdinate> made = make();
  if (memo->ordinates_at.size() >= 4) memo->ordinates_at.erase(memo->ordinates_at.begin());
  memo->ordinates_at.push_back(made);
  return made;
}

OrdinateBounds ordinate_bounds(const CSpace& space, std::size_t index) {
  if (!cspace::ordinate_memo()) return {};
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  if (memo->ordinates.empty()) return {};
  return memo->ordinates[index];
}

void remember_ordinate(const CSpace& space, std::size_t index, const Rational& y, int side) {
  if (!cspace::ordinate_memo()) return;
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  if (memo->ordinates.empty()) memo->ordinates.resize(implementation(space).vertices.size());
  OrdinateBounds& known = memo->ordinates[index];
  if (side == 0) known.equal = y;
  if (side < 0 && (!known.below || y > *known.below)) known.below = y;
  if (side > 0 && (!known.above || y < *known.above)) known.above = y;
}

FibreSigns fibre_signs(const CSpace& space, std::size_t index) {
  const CSpace::Impl& impl = implementation(space);
  auto [c, v] = impl.vertex_local[index];
  const cspace::raw::Vertex& vertex = impl.charts[c].arrangement.vertices[v];
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  if (memo->fibre_signs.empty()) memo->fibre_signs.resize(impl.vertices.size());
  std::optional<FibreSigns>& signs = memo->fibre_signs[index];
  if (!signs) signs = fibre_signs_of(vertex);
  return *signs;
}

// enclosed_fibre_sign's data for vertex `index`, made on first use
const ScanMemo::FibreEnclosure& fibre_enclosure(const CSpace::Impl& impl, ScanMemo& memo, std::size_t index,
                                                const FibreSigns& signs) {
  if (memo.fibre_enclosures.empty()) memo.fibre_enclosures.resize(impl.vertices.size());
  std::optional<ScanMemo::FibreEnclosure>& enclosure = memo.fibre_enclosures[index];
  if (!enclosure) {
    auto [c, v] = impl.vertex_local[index];
    const cspace::raw::Vertex& vertex = impl.charts[c].arrangement.vertices[v];
    ScanMemo::FibreEnclosure made;
    made.decider = signs.decides == FibreSigns::Decides::curve ? vertex.y_curve : y_derivative(vertex.y_curve);
    Real x = vertex.x;
    x.refine_to(Rational(mpz_class(1), mpz_class(1) << 100));
    made.exact = x.exact;
    made.x_lo = x.lower;
    made.x_hi = x.upper;
    made.x = {cspace::algebra::lower_double(x.lower), cspace::algebra::upper_double(x.upper)};
    enclosure = std::move(made);
  }
  return *enclosure;
}

std::optional<int> enclosed_fibre_sign(const CSpace& space, std::size_t index, const FibreSigns& signs,
                                       const Rational& y) {
  if (!cspace::ordinate_enclosure()) return std::nullopt;
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  const ScanMemo::FibreEnclosure& enclosure = fibre_enclosure(implementation(space), *memo, index, signs);
  if (enclosure.exact) return std::nullopt;
  // d^k D(x, y) for y = n / d (d > 0): D(., y)'s sign everywhere
  const cspace::algebra::Polynomial p = cspace::algebra::substitute_y(enclosure.decider, y);
  if (p.size() < 2) return std::nullopt;
  // p' over the doubles around [x_lo, x_hi], outward-rounded: p strictly monotone there where it
  // excludes zero (NaN fails both tests)
  cspace::algebra::Interval slope{0, 0};
  for (std::size_t i = p.size() - 1; i >= 1; --i)
    slope = slope * enclosure.x + cspace::algebra::enclose(mpz_class(p[i] * static_cast<unsigned long>(i)));
  if (!(slope.lo > 0) && !(slope.hi < 0)) return std::nullopt;
  const int lower = cspace::algebra::sign_at(p, enclosure.x_lo);
  if (lower == 0 || cspace::algebra::sign_at(p, enclosure.x_hi) != lower) return std::nullopt;
  ++cspace::ordinate_enclosure_decided();
  return lower;
}

class MotionScanner {
 public:
  // The scanner's scratch and per-path vectors, kept with its query's storage between queries
  // (CrossingRun::Kept): each is rewritten before it is read (the ends' memo counts its entries
  // from none, the path's enclosures are filled again, exclude and locate_inside reset theirs).
  struct Storage {
    std::array<std::pair<Rational, KInterval>, 4> ends{};
    std::vector<std::vector<KInterval>> enclosed, enclosed_rate, enclosed_acceleration;
    std::vector<char> candidate;
    std::vector<Possible> hull_possible;
    ChartPoint located;                  // locate_inside's point (the box's midpoint)
    Rational bound_lo, bound_hi;         // and the box's double bounds as rationals
    std::vector<std::size_t> charts;     // evaluate's charts of one pair of pieces (cleared per pair)
  };

  MotionScanner(const CSpace::Impl& impl, const MotionPath& path, std::shared_ptr<ScanMemo> memo, Storage& storage)
      : impl_(impl),
        path_(path),
        ends_(storage.ends),
        enclosed_(storage.enclosed),
        enclosed_rate_(storage.enclosed_rate),
        enclosed_acceleration_(storage.enclosed_acceleration),
        memo_(std::move(memo)),
        candidate_(storage.candidate),
        hull_possible_(storage.hull_possible),
        located_(storage.located),
        bound_lo_(storage.bound_lo),
        bound_hi_(storage.bound_hi),
        charts_(storage.charts) {
    auto check = [&](const AxisPath& axis, AxisKind kind, const char* which) {
      bool rotation = axis.kind != AxisPath::Kind::offset;
      if (rotation != (kind == AxisKind::rotation))
        throw GeometryError(std::string("first_crossing: the ") + which + " part " +
                            (kind == AxisKind::rotation ? "rotates (give an angle or a half-angle tangent)"
                                                        : "translates (give an offset)"));
    };
    check(path.x, impl.public_charts.at(0).x_kind, "x");
    if (impl.dimension == 2) check(path.y, impl.public_charts.at(0).y_kind, "y");
    enclosed_.resize(2);
    enclosed_rate_.resize(2);
    enclosed_acceleration_.resize(2);
    for (std::size_t k = 0; k < 2; ++k) {
      // the path's coefficients c_i (KInterval::enclose's doubles, dyadic.hpp) and its
      // derivatives' i c_i and i (i - 1) c_i enclosed (cspace::enclose_multiple: KInterval::enclose
      // of the exact product, from the double where c_i is one)
      const std::vector<Rational>& c = (k == 0 ? path.x : path.y).coefficients;
      std::vector<KInterval>& e = enclosed_[k];
      std::vector<KInterval>& d = enclosed_rate_[k];
      std::vector<KInterval>& dd = enclosed_acceleration_[k];
      e.clear();
      d.clear();
      dd.clear();
      for (const Rational& ci : c) e.push_back(cspace::enclose_exact(ci));
      for (std::size_t i = 1; i < c.size(); ++i) d.push_back(cspace::enclose_multiple(c[i], static_cast<long>(i)));
      for (std::size_t i = 2; i < c.size(); ++i) dd.push_back(cspace::enclose_multiple(c[i], static_cast<long>(i * (i - 1))));
    }
  }

  struct Evaluation {
    bool too_wide = false;
    bool covered = true;
    bool box_clear = false;   // `possible` empty from the boxes' enclosures alone (no mean-value form)
    std::vector<PieceBox> boxes;
    std::vector<Possible> possible;
    // where `possible` is one curve whose value at a and rate over [a, b] exclude 0 with
    // opposite signs: the u - a where the rate's bounds bring that value to 0, smaller and larger
    // (doubles, not certified: a proposal for the subdivision, see newton_shrink)
    bool newton = false;
    double newton_lo = 0, newton_hi = 0;
    // and the certified bounds behind it: newton_s_min <= |f(a)| <= newton_s_max and newton_r_min
    // <= |rate| <= newton_r_max over [a, b] (ends of outward-rounded enclosures), so f(u) != 0 for
    // (u - a) newton_r_max < newton_s_min, and f(u) has the sign opposite to f(a)'s for
    // (u - a) newton_r_min > newton_s_max
    double newton_s_min = 0, newton_s_max = 0, newton_r_min = 0, newton_r_max = 0;
    bool newton_positive = false;   // f(a) > 0 (else < 0)
    // the chart systems of the stretch's one piece per axis (rotation, half turn: x, then y)
    std::array<bool, 4> newton_systems{};
  };

  // `filtered_point` (a == b): the point through the stretches' filter, its angle pieces widened
  // by a double either way (see start_filter.hpp), instead of to the full precision.
  Evaluation evaluate(const Rational& a, const Rational& b, bool filtered_point = false) {
    Evaluation result;
    // a point of the path (a start, an end: located exactly) to the full precision; a stretch
    // through the filter
    const bool fine = a == b && !filtered_point;
    std::vector<AxisPiece> xs = pieces(path_.x, a, b, result.too_wide, fine);
    std::vector<AxisPiece> ys;
    if (impl_.dimension == 2) ys = pieces(path_.y, a, b, result.too_wide, fine);
    else ys = {AxisPiece{false, false, ExactBound(), ExactBound()}};
    if (result.too_wide) return result;
    if (filtered_point) {
      widen(path_.x, xs);
      if (impl_.dimension == 2) widen(path_.y, ys);
    }
    for (const AxisPiece& px : xs)
      for (const AxisPiece& py : ys) {
        std::vector<std::size_t>& charts = charts_;
        charts.clear();
        for (std::size_t c = 0; c < impl_.public_charts.size(); ++c) {
          const CSpaceChart& chart = impl_.public_charts[c];
          if (!same_system(chart.x_kind, chart.x_half_turn, px)) continue;
          if (px.hi < side(c, 0) || px.lo > side(c, 1)) continue;
          if (impl_.dimension == 2) {
            if (!same_system(chart.y_kind, chart.y_half_turn, py)) continue;
            if (py.hi < side(c, 2) || py.lo > side(c, 3)) continue;
          }
          charts.push_back(c);
        }
        if (!covers(charts, px, py)) result.covered = false;
        for (std::size_t c : charts) {
          const std::array<double, 4>& side = memo_->chart_boxes[c];
          PieceBox box{c, max_with(px.lo, this->side(c, 0)), min_with(px.hi, this->side(c, 1)), py.lo, py.hi,
                       std::max(px.dlo, side[0]), std::min(px.dhi, side[1]), py.dlo, py.dhi};
          if (impl_.dimension == 2) {
            box.y_lo = max_with(py.lo, this->side(c, 2));
            box.y_hi = min_with(py.hi, this->side(c, 3));
            box.dy_lo = std::max(py.dlo, side[2]);
            box.dy_hi = std::min(py.dhi, side[3]);
          }
          result.boxes.push_back(box);
          exclude(result.boxes.size() - 1, box, result.possible);
        }
      }
    // Where the boxes' natural enclosures cannot exclude a curve, try the mean-value form along
    // the path (one chart system on [a, b]: no seam crossed): f(u) = F(X(u), Y(u)) lies in
    // f(a) + [0, b - a] f'([a, b]) with f' = F_x X' + F_y Y'. It excludes a curve near which the
    // path passes transversally (or leaves it: a motion that starts next to a contact curve and
    // moves away) at a subdivision depth set by the distance, not by the resolution.
    result.box_clear = result.possible.empty();
    if (a < b && xs.size() == 1 && ys.size() == 1 && !result.possible.empty())
      mean_value_exclusion(a, b, xs.front(), ys.front(), result.possible, &result);
    return result;
  }

  // An angle's filtered pieces widened by one double either way, within the chart system's
  // [-1, 1] (the 160-bit pieces lie in it): the result holds the double box of the 160-bit
  // pieces of the same point (their width is far below a double's spacing, so that box sticks
  // out of the filtered piece by at most one double). Offsets and half-angle tangents are exact
  // rationals at a point: the filtered enclosure's doubles already hold theirs.
  static void widen(const AxisPath& axis, std::vector<AxisPiece>& pieces) {
    if (axis.kind != AxisPath::Kind::angle) return;
    const double inf = std::numeric_limits<double>::infinity();
    for (AxisPiece& p : pieces) {
      if (p.dlo > -1) {
        p.dlo = std::max(-1.0, std::nextafter(p.dlo, -inf));
        p.lo = ExactBound::of_double(p.dlo);
      }
      if (p.dhi < 1) {
        p.dhi = std::min(1.0, std::nextafter(p.dhi, inf));
        p.hi = ExactBound::of_double(p.dhi);
      }
    }
  }

  // Exact location of a rational point inside a box with no contact curve; inside `anchor`'s box
  // (and strictly inside the chart's), the anchor's face (see StartAnchor). Or next to one of
  // `boxes` (AnchorBox): where no cell-bounding curve vanishes on the hull of that box and this
  // one (exclude, as a stretch is excluded) the point is in that box's cell, and where no curve
  // at all vanishes on this box (the point on no edge, strictly inside the chart) it is inside a
  // face of that (free) cell: the location is that cell's, without the ray shooting.
  Location locate_inside(const PieceBox& box, const StartAnchor* anchor = nullptr, AnchorBoxes* boxes = nullptr) {
    // the box's midpoint (dyadic.hpp: by shifts where both ends are dyadic, as the filtered and
    // the MPFR pieces' bounds are)
    // (into the kept point, each coordinate written whole: nothing of an earlier point read)
    located_.chart = box.chart;
    Rational& x = located_.x;
    Rational& y = located_.y;
    cspace::midpoint_into(x, box.x_lo.rational(bound_lo_), box.x_hi.rational(bound_hi_));
    cspace::midpoint_into(y, box.y_lo.rational(bound_lo_), box.y_hi.rational(bound_hi_));
    const cspace::raw::Box& side = impl_.charts[box.chart].box;
    const bool inside_chart = x > side.x_lo && x < side.x_hi && (impl_.dimension == 1 || (y > side.y_lo && y < side.y_hi));
    auto free_in = [&](std::size_t cell) {
      Location location;
      location.kind = Location::Kind::free;
      location.cell = cell;
      location.chart = box.chart;
      return location;
    };
    if (anchor && anchor->chart == box.chart && x >= anchor->x_lo && x <= anchor->x_hi && y >= anchor->y_lo &&
        y <= anchor->y_hi && inside_chart) {
      ++cspace::anchored_starts();
      return free_in(anchor->cell);
    }
    if (boxes && inside_chart) {
      int tried = 0;
      int clear = 0;   // this box clear of every curve: 0 not checked, 1 yes, -1 no
      for (auto it = boxes->boxes.rbegin(); it != boxes->boxes.rend() && tried < 3 && clear >= 0; ++it) {
        const PieceBox& b = *it;
        if (b.chart != box.chart) continue;
        // near it (within its width, or within a millionth of its chart's width): the hull small
        auto near = [](double lo, double hi, double b_lo, double b_hi, double chart_width) {
          double reach = std::max(b_hi - b_lo, 1e-6 * chart_width);
          return lo >= b_lo - reach && hi <= b_hi + reach;
        };
        const std::array<double, 4>& chart_box = memo_->chart_boxes[box.chart];
        if (!near(box.dx_lo, box.dx_hi, b.dx_lo, b.dx_hi, chart_box[1] - chart_box[0]) ||
            (impl_.dimension == 2 && !near(box.dy_lo, box.dy_hi, b.dy_lo, b.dy_hi, chart_box[3] - chart_box[2])))
          continue;
        ++tried;
        // (exclude reads the hull's doubles only, unless the carried bounds are switched off)
        PieceBox hull{box.chart, box.x_lo, box.x_hi, box.y_lo, box.y_hi,
                      std::min(b.dx_lo, box.dx_lo), std::max(b.dx_hi, box.dx_hi),
                      std::min(b.dy_lo, box.dy_lo), std::max(b.dy_hi, box.dy_hi)};
        if (!cspace::carried_bounds()) {
          if (compare(b.x_lo, box.x_lo) < 0) hull.x_lo = b.x_lo;
          if (compare(b.x_hi, box.x_hi) > 0) hull.x_hi = b.x_hi;
          if (compare(b.y_lo, box.y_lo) < 0) hull.y_lo = b.y_lo;
          if (compare(b.y_hi, box.y_hi) > 0) hull.y_hi = b.y_hi;
        }
        hull_possible_.clear();
        exclude(0, hull, hull_possible_);
        if (!hull_possible_.empty()) continue;
        if (clear == 0) clear = on_no_edge(box) ? 1 : -1;
        if (clear < 0) break;
        ++cspace::box_anchored_starts();
        return free_in(it->cell);
      }
    }
    return cspace::locate_point(impl_, located_);
  }

  // The box (on which no cell-bounding curve vanishes: see locate_inside) meets no edge of its
  // chart: the curves of the other edges whose certified boxes it meets do not vanish on it (in
  // a 1-D space: no curve of the chart does).
  bool on_no_edge(const PieceBox& box) {
    if (impl_.dimension == 1 || !cspace::carried_bounds()) return clear_of_curves(box);
    const cspace::algebra::Interval x{box.dx_lo, box.dx_hi}, y{box.dy_lo, box.dy_hi};
    for (const Carrier& carrier : carriers(box.chart).inner) {
      if (x.hi < carrier.box[0] || x.lo > carrier.box[2] || y.hi < carrier.box[1] || y.lo > carrier.box[3]) continue;
      for (std::size_t k : carrier.curves) {
        cspace::algebra::Interval value = curve_enclosure(impl_, *memo_, box.chart, k).evaluate(x, y);
        if (!std::isfinite(value.lo) || !std::isfinite(value.hi) || value.contains_zero()) return false;
      }
    }
    return true;
  }

  // No curve of the box's chart (not only the cell-bounding ones) vanishes on it: the box lies
  // in one face.
  bool clear_of_curves(const PieceBox& box) const {
    cspace::algebra::Interval x{box.dx_lo, box.dx_hi}, y{box.dy_lo, box.dy_hi};
    if (!cspace::carried_bounds()) {
      x = {cspace::algebra::lower_double(box.x_lo.rational()), cspace::algebra::upper_double(box.x_hi.rational())};
      y = {cspace::algebra::lower_double(box.y_lo.rational()), cspace::algebra::upper_double(box.y_hi.rational())};
    }
    for (std::size_t k = 0; k < impl_.charts[box.chart].interval_polynomials.size(); ++k) {
      cspace::algebra::Interval value = curve_enclosure(impl_, *memo_, box.chart, k).evaluate(x, y);
      if (!std::isfinite(value.lo) || !std::isfinite(value.hi) || value.contains_zero()) return false;
    }
    return true;
  }

  // A StartAnchor from the last stretch of a motion that stayed in the free cell `cell`: its one
  // box, when no curve of the chart (not only the cell-bounding ones) vanishes on it.
  std::optional<StartAnchor> anchor_from(const Evaluation& last, std::size_t cell) const {
    if (!last.box_clear || last.boxes.size() != 1) return std::nullopt;
    const PieceBox& box = last.boxes.front();
    if (!clear_of_curves(box)) return std::nullopt;
    StartAnchor anchor;
    anchor.chart = box.chart;
    anchor.cell = cell;
    anchor.x_lo = box.x_lo.rational();
    anchor.x_hi = box.x_hi.rational();
    anchor.y_lo = box.y_lo.rational();
    anchor.y_hi = box.y_hi.rational();
    return anchor;
  }

 private:
  // public chart c's side k (0: x_lo, 1: x_hi, 2: y_lo, 3: y_hi) with its doubles
  Side side(std::size_t c, int k) const {
    const CSpaceChart& chart = impl_.public_charts[c];
    const Rational* r[4] = {&chart.x_lo, &chart.x_hi, &chart.y_lo, &chart.y_hi};
    const std::array<double, 8>& d = memo_->chart_sides[c];
    return Side{*r[k], d[2 * k], d[2 * k + 1]};
  }

  static bool same_system(AxisKind kind, bool half_turn, const AxisPiece& piece) {
    if ((kind == AxisKind::rotation) != piece.rotation) return false;
    return kind == AxisKind::translation || half_turn == piece.half_turn;
  }

  // The path's enclosure over [a, b]: `fine`, exact (rational Horner; a start or an end, whose
  // point is located exactly); else in certified double intervals (exact where they overflow).
  RInterval path_value(const AxisPath& axis, const Rational& a, const Rational& b, bool fine) const {
    if (!fine)
      if (std::optional<KInterval> value = filtered_value(enclosed_[&axis == &path_.x ? 0 : 1], a, b))
        return RInterval{Rational(value->lo), Rational(value->hi)};
    return evaluate_path(axis.coefficients, a, b);
  }

  // evaluate_path_filtered with the ends' enclosures memoised (a subdivision meets each end
  // several times: both axes, their derivatives, the neighbouring stretches)
  std::optional<KInterval> filtered_value(const std::vector<KInterval>& p, const Rational& a, const Rational& b) const {
    if (!cspace::carried_bounds()) {
      std::optional<RInterval> value = evaluate_path_filtered(p, a, b);
      if (!value) return std::nullopt;
      return KInterval(cspace::algebra::lower_double(value->lo), cspace::algebra::upper_double(value->hi));
    }
    return path_enclosure(p, enclosure(a), enclosure(b));
  }
  // evaluate_path_filtered_d(p, A, B), remembered when p is one of this scanner's own
  // polynomials (enclosed_, enclosed_rate_, enclosed_acceleration_: fixed once the scanner is
  // built). The value is a function of p and the doubles A.lo and B.hi alone, and the same
  // stretch asks it again and again (the second-order exclusion takes the path's rate and
  // acceleration at the stretch's start once for every curve it tries; a stretch's rate after
  // its pieces): the last four end pairs per polynomial, compared by bit pattern, return the
  // same bits. Other polynomials are evaluated. Switch cspace::path_memo() (on by default;
  // CSpaceCrossingPathMemo.* compares every answer with it off).
  std::optional<KInterval> path_enclosure(const std::vector<KInterval>& p, const KInterval& A, const KInterval& B) const {
    std::size_t slot = path_values_.size();
    if (cspace::path_memo())
      for (std::size_t axis = 0; axis < 2 && axis < enclosed_.size(); ++axis) {
        if (&p == &enclosed_[axis]) slot = axis;
        else if (&p == &enclosed_rate_[axis]) slot = 2 + axis;
        else if (&p == &enclosed_acceleration_[axis]) slot = 4 + axis;
      }
    if (slot == path_values_.size()) return evaluate_path_filtered_d(p, A, B);
    const std::uint64_t lo = std::bit_cast<std::uint64_t>(A.lo), hi = std::bit_cast<std::uint64_t>(B.hi);
    PathValues& memo = path_values_[slot];
    if (const PathValue* known = memo.find(lo, hi)) {
      ++cspace::path_memo_hits();
      return known->value;
    }
    // the other axis' polynomial of the same kind (x with y: the stretch asks both) evaluated
    // with it, in the two lanes of one pass (path_filter.hpp: the same bits), and remembered
    std::optional<KInterval> value;
    const std::size_t partner = slot ^ 1;
    const std::vector<KInterval>* other = partner < 2 ? &enclosed_[partner]
                                          : partner < 4 ? &enclosed_rate_[partner - 2]
                                                        : &enclosed_acceleration_[partner - 4];
    std::optional<KInterval> other_value;
    if (cspace::paired_paths() && impl_.dimension == 2 && enclosed_.size() == 2 && !p.empty() &&
        !path_values_[partner].find(lo, hi) && cspace::evaluate_path_filtered_pair(p, *other, A, B, value, other_value)) {
      ++cspace::paired_path_count();
      path_values_[partner].put(lo, hi, other_value);
    } else {
      value = evaluate_path_filtered_d(p, A, B);
    }
    memo.put(lo, hi, value);
    return value;
  }
  KInterval enclosure(const Rational& r) const {
    for (std::size_t i = 0; i < filled_ends_; ++i)
      if (ends_[i].first == r) return ends_[i].second;
    KInterval value = cspace::enclose_exact(r);   // KInterval::enclose's doubles (dyadic.hpp)
    // the slot's rational set in place (its limbs reused; no temporary pair copied and cleared)
    ends_[next_end_].first = r;
    ends_[next_end_].second = value;
    next_end_ = (next_end_ + 1) % ends_.size();
    filled_ends_ = std::min(filled_ends_ + 1, ends_.size());
    return value;
  }

  // The chart pieces of the path over [a, b]; `fine`: the exact path and 160-bit tangents,
  // else the filtered path and 64-bit tangents (certified either way).
  std::vector<AxisPiece> pieces(const AxisPath& axis, const Rational& a, const Rational& b, bool& too_wide,
                                bool fine) const {
    if (!fine && axis.kind == AxisPath::Kind::angle && cspace::carried_bounds())
      if (std::optional<KInterval> value = filtered_value(enclosed_[&axis == &path_.x ? 0 : 1], a, b)) {
        // as below, without the rationals: Rational(d)'s enclosure is [d, d] widened by the
        // one double away from 0 on its far side (kernels::Interval::enclose)
        if (!(value->hi - value->lo < 1.5) && Rational(value->hi) - Rational(value->lo) >= 2) {
          too_wide = true;
          return {};
        }
        using kernels::interval_detail::down;
        using kernels::interval_detail::up;
        KInterval theta(value->lo < 0 ? down(value->lo) : value->lo, value->hi > 0 ? up(value->hi) : value->hi);
        if (std::optional<cspace::AngleRanges> ranges = memo_filtered_angle_ranges(theta)) return range_pieces(*ranges);
        std::vector<AxisPiece> result = angle_pieces(RInterval{Rational(value->lo), Rational(value->hi)}, 64);
        for (AxisPiece& p : result) p = with_doubles(std::move(p));
        return result;
      }
    RInterval value = path_value(axis, a, b, fine);
    std::vector<AxisPiece> result;
    switch (axis.kind) {
      case AxisPath::Kind::offset: result = {AxisPiece{false, false, value.lo, value.hi}}; break;
      case AxisPath::Kind::half_tangent: result = tangent_pieces(value); break;
      case AxisPath::Kind::angle:
        if (value.hi - value.lo >= 2) {
          too_wide = true;
          return {};
        }
        if (!fine)
          if (std::optional<std::vector<AxisPiece>> filtered = angle_pieces_filtered(value)) {
            result = std::move(*filtered);
            break;
          }
        result = memo_angle_pieces(value, fine ? precision : 64);
        break;
    }
    for (AxisPiece& p : result) p = with_doubles(std::move(p));
    return result;
  }

  using DInterval = cspace::algebra::Interval;
  static DInterval enclose_range(const Rational& lo, const Rational& hi) {
    return DInterval{cspace::algebra::lower_double(lo), cspace::algebra::upper_double(hi)};
  }
  static DInterval negate(DInterval v) { return DInterval{-v.hi, -v.lo}; }

  // Enclosure of d(chart coordinate)/du over [a, b] on the piece `piece` (one system).
  DInterval chart_derivative(const AxisPath& axis, const Rational& a, const Rational& b, const AxisPiece& piece) const {
    const std::vector<KInterval>& d = enclosed_rate_[&axis == &path_.x ? 0 : 1];
    DInterval rate{0, 0};
    if (!d.empty()) {
      if (std::optional<KInterval> dv = filtered_value(d, a, b)) {
        rate = DInterval{dv->lo, dv->hi};
      } else {
        std::vector<Rational> exact;
        for (std::size_t i = 1; i < axis.coefficients.size(); ++i)
          exact.push_back(axis.coefficients[i] * static_cast<long>(i));
        RInterval v = evaluate_path(exact, a, b);
        rate = enclose_range(v.lo, v.hi);
      }
    }
    DInterval x = cspace::carried_bounds() ? DInterval{piece.dlo, piece.dhi} : enclose_range(piece.lo.rational(), piece.hi.rational());
    switch (axis.kind) {
      case AxisPath::Kind::offset: return rate;
      case AxisPath::Kind::angle:   // t = tan((theta - c) / 2): dt/du = (1 + t^2) / 2 theta'
        return (DInterval{1, 1} + x * x) * DInterval{0.5, 0.5} * rate;
      case AxisPath::Kind::half_tangent:   // t itself, or -1/t beyond the seam: d(-1/t) = t' (-1/t)^2
        return piece.half_turn ? rate * (x * x) : rate;
    }
    return rate;
  }

  // The partial derivatives d/dx and d/dy of f (exact integer coefficients).
  static std::pair<cspace::IntegerPolynomial2, cspace::IntegerPolynomial2> partials(const cspace::IntegerPolynomial2& f) {
    cspace::IntegerPolynomial2 fx, fy;
    for (std::size_t i = 0; i < f.coefficients.size(); ++i)
      for (std::size_t j = 0; j < f.coefficients[i].size(); ++j) {
        if (sgn(f.coefficients[i][j]) == 0) continue;
        if (i > 0) {
          if (fx.coefficients.size() < i) fx.coefficients.resize(i);
          if (fx.coefficients[i - 1].size() <= j) fx.coefficients[i - 1].resize(j + 1);
          fx.coefficients[i - 1][j] = f.coefficients[i][j] * static_cast<long>(i);
        }
        if (j > 0) {
          if (fy.coefficients.size() <= i) fy.coefficients.resize(i + 1);
          if (fy.coefficients[i].size() < j) fy.coefficients[i].resize(j);
          fy.coefficients[i][j - 1] = f.coefficients[i][j] * static_cast<long>(j);
        }
      }
    return {std::move(fx), std::move(fy)};
  }

  using Gradient = ScanMemo::Gradient;
  const Gradient& gradient(std::size_t chart, std::size_t k) {
    std::vector<std::optional<Gradient>>& memo = memo_->gradients[chart];
    if (memo.empty()) memo.resize(impl_.charts[chart].polynomials.size());
    if (memo[k]) return *memo[k];
    const cspace::IntegerPolynomial2& f = impl_.charts[chart].polynomials[k];
    const long shift = cspace::algebra::interval_shift(f);
    auto [fx, fy] = partials(f);
    memo[k] = Gradient{ScanMemo::ScaledPartial(fx, shift), ScanMemo::ScaledPartial(fy, shift)};
    return *memo[k];
  }

  // The second partial derivatives F_xx, F_xy, F_yy of a local curve (memoised like gradient()).
  using Hessian = ScanMemo::Hessian;
  const Hessian& hessian(std::size_t chart, std::size_t k) {
    std::vector<std::optional<Hessian>>& memo = memo_->hessians[chart];
    if (memo.empty()) memo.resize(impl_.charts[chart].polynomials.size());
    if (memo[k]) return *memo[k];
    const cspace::IntegerPolynomial2& f = impl_.charts[chart].polynomials[k];
    const long shift = cspace::algebra::interval_shift(f);
    auto [fx, fy] = partials(f);
    auto [fxx, fxy] = partials(fx);
    cspace::IntegerPolynomial2 fyy = partials(fy).second;
    memo[k] = Hessian{ScanMemo::ScaledPartial(fxx, shift), ScanMemo::ScaledPartial(fxy, shift), ScanMemo::ScaledPartial(fyy, shift)};
    return *memo[k];
  }

  // Enclosure of d^2(chart coordinate)/du^2 over [a, b] on the piece `piece` (one system), from
  // the piece's coordinate enclosure `x` and its first derivative's enclosure `dx` over [a, b]:
  //   offset:                X'' = p''
  //   angle, t = tan((theta - c)/2):  t'' = t t' theta' + (1 + t^2)/2 theta''
  //   half-tangent t:        t'' = p'';  beyond the seam s = -1/t: s' = t' s^2, s'' = t'' s^2 + 2 t'^2 s^3
  DInterval chart_acceleration(const AxisPath& axis, const Rational& a, const Rational& b, const AxisPiece& piece,
                               const DInterval& x, const DInterval& dx) const {
    const std::size_t i = &axis == &path_.x ? 0 : 1;
    auto enclosed = [&](const std::vector<KInterval>& p) -> std::optional<DInterval> {
      if (p.empty()) return DInterval{0, 0};
      std::optional<KInterval> v = path_enclosure(p, enclosure(a), enclosure(b));
      if (!v) return std::nullopt;
      return DInterval{v->lo, v->hi};
    };
    std::optional<DInterval> acceleration = enclosed(enclosed_acceleration_[i]);
    if (!acceleration) return everything();
    switch (axis.kind) {
      case AxisPath::Kind::offset: return *acceleration;
      case AxisPath::Kind::angle: {
        std::optional<DInterval> rate = enclosed(enclosed_rate_[i]);
        if (!rate) return everything();
        return x * dx * *rate + (DInterval{1, 1} + x * x) * DInterval{0.5, 0.5} * *acceleration;
      }
      case AxisPath::Kind::half_tangent: {
        if (!piece.half_turn) return *acceleration;
        std::optional<DInterval> rate = enclosed(enclosed_rate_[i]);
        if (!rate) return everything();
        DInterval x2 = x * x;
        return *acceleration * x2 + DInterval{2, 2} * (*rate * *rate) * (x2 * x);
      }
    }
    return everything();
  }
  static DInterval everything() {
    return DInterval{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }

  // The mean-value exclusion (see evaluate): drops from `possible` every curve whose
  // f(a) + [0, b - a] (F_x X' + F_y Y') over the path's enclosure on [a, b] excludes zero.
  void mean_value_exclusion(const Rational& a, const Rational& b, const AxisPiece& px, const AxisPiece& py,
                            std::vector<Possible>& possible, Evaluation* proposal = nullptr) {
    // the path's pieces at a (the subdivision visits [a, m] right after [a, b]: kept for the
    // last a), through the filter (the exact ones only where exact_start_value needs them)
    if (!start_ || start_->a != a) {
      StartPieces at;
      at.a = a;
      at.x = pieces(path_.x, a, a, at.wide, false);
      if (impl_.dimension == 2) at.y = pieces(path_.y, a, a, at.wide, false);
      else at.y = {AxisPiece{false, false, ExactBound(), ExactBound()}};
      start_ = std::move(at);
    }
    if (start_->wide) return;
    const std::vector<AxisPiece>& xa = start_->x;
    const std::vector<AxisPiece>& ya = start_->y;
    auto same = [](const AxisPiece& p, const AxisPiece& q) { return p.rotation == q.rotation && p.half_turn == q.half_turn; };
    auto sx = std::find_if(xa.begin(), xa.end(), [&](const AxisPiece& p) { return same(p, px); });
    auto sy = std::find_if(ya.begin(), ya.end(), [&](const AxisPiece& p) { return same(p, py); });
    if (sx == xa.end() || sy == ya.end()) return;
    const bool carried = cspace::carried_bounds();
    DInterval x_at = carried ? DInterval{sx->dlo, sx->dhi} : enclose_range(sx->lo.rational(), sx->hi.rational());
    DInterval y_at = carried ? DInterval{sy->dlo, sy->dhi} : enclose_range(sy->lo.rational(), sy->hi.rational());
    DInterval x = carried ? DInterval{px.dlo, px.dhi} : enclose_range(px.lo.rational(), px.hi.rational());
    DInterval y = carried ? DInterval{py.dlo, py.dhi} : enclose_range(py.lo.rational(), py.hi.rational());
    DInterval dx = chart_derivative(path_.x, a, b, px);
    DInterval dy = impl_.dimension == 2 ? chart_derivative(path_.y, a, b, py) : DInterval{0, 0};
    thread_local Rational width;   // b - a (its limbs reused)
    cspace::sum_into(width, b, a, -1);
    DInterval h{0, cspace::algebra::upper_double(width)};
    std::vector<Possible> kept;
    // what second_order_excludes takes for every curve alike: the start's rates (per start
    // piece, kept with the start) and the stretch's accelerations (this call's)
    SecondOrderShared shared{static_cast<std::size_t>(sx - xa.begin()), static_cast<std::size_t>(sy - ya.begin())};
    bool newton = false;
    double newton_lo = 0, newton_hi = 0, newton_s_min = 0, newton_s_max = 0, newton_r_min = 0, newton_r_max = 0;
    bool newton_positive = false;
    for (const Possible& p : possible) {
      const Gradient& g = gradient(p.chart, p.curve);
      DInterval start = curve_enclosure(impl_, *memo_, p.chart, p.curve).evaluate(x_at, y_at);
      // a start within rounding of the curve (a motion leaving a contact from a configuration a
      // few ulps off it): the double enclosure contains 0 at any depth, so take F over the
      // start's exact (160-bit) box in rational intervals, cached per start and curve
      if (start.contains_zero()) start = exact_start_value(p.chart, p.curve, px, py);
      if (start.contains_zero()) {
        kept.push_back(p);
        continue;
      }
      const DInterval fx = g.fx.evaluate(x, y), fy = g.fy.evaluate(x, y);
      DInterval rate = fx * dx + fy * dy;
      DInterval value = start + h * rate;
      // (a non-finite bound, from overflow, proves nothing)
      if (std::isfinite(value.lo) && std::isfinite(value.hi) && !value.contains_zero()) continue;
      if (second_order_excludes(p, a, b, start, x_at, y_at, sx, sy, x, y, dx, dy, fx, fy, px, py, h, shared)) continue;
      kept.push_back(p);
      // f moves toward 0 at a rate within `rate` (one sign): f(a + t) = 0 needs
      // t >= |f(a)|min / |rate|max, and happens by t = |f(a)|max / |rate|min if in [a, b]
      bool toward = (start.lo > 0 && rate.hi < 0) || (start.hi < 0 && rate.lo > 0);
      if (toward && std::isfinite(start.lo) && std::isfinite(start.hi) && std::isfinite(rate.lo) &&
          std::isfinite(rate.hi) && kept.size() == 1) {
        double s_min = start.lo > 0 ? start.lo : -start.hi, s_max = start.lo > 0 ? start.hi : -start.lo;
        double r_min = rate.lo > 0 ? rate.lo : -rate.hi, r_max = rate.lo > 0 ? rate.hi : -rate.lo;
        newton = true;
        newton_lo = s_min / r_max;
        newton_hi = s_max / r_min;
        newton_s_min = s_min;
        newton_s_max = s_max;
        newton_r_min = r_min;
        newton_r_max = r_max;
        newton_positive = start.lo > 0;
      }
    }
    possible.swap(kept);
    if (proposal && newton && possible.size() == 1) {
      proposal->newton = true;
      proposal->newton_positive = newton_positive;
      proposal->newton_systems = {px.rotation, px.half_turn, py.rotation, py.half_turn};
      proposal->newton_lo = newton_lo;
      proposal->newton_hi = newton_hi;
      proposal->newton_s_min = newton_s_min;
      proposal->newton_s_max = newton_s_max;
      proposal->newton_r_min = newton_r_min;
      proposal->newton_r_max = newton_r_max;
    }
  }

public:
  // The Newton proposal's bounds again from an anchor inside the stretch (CrossingRun::shrink,
  // cspace::newton_refine()): for the one curve p left over a stretch [a, b] (`at`) whose value at a and
  // rate over [a, b] exclude 0 with opposite signs (so its only root r in [a, b] lies past
  // `anchor` and before `end`, both in [a, b]), f(anchor) and the rate over the box of
  // [anchor, end] on the systems of the stretch's pieces: by the mean value theorem 0 = f(r) =
  // f(anchor) + (r - anchor) f'(xi) with xi in [anchor, end], so r - anchor lies in
  // [s_min / r_max, s_max / r_min] of these enclosures. Set only where f(anchor) has the sign
  // `positive` and the rate the other one (both certified, finite); nothing is decided by it.
  struct NewtonBounds {
    double s_min = 0, s_max = 0, r_min = 0, r_max = 0;
  };
  std::optional<NewtonBounds> newton_from(const Rational& anchor, const Rational& end, const Evaluation& at) {
    if (!at.newton || at.possible.size() != 1) return std::nullopt;
    const Possible& p = at.possible.front();
    const bool positive = at.newton_positive;
    bool wide = false;
    const bool planar = impl_.dimension == 2;
    const AxisPiece flat{false, false, ExactBound(), ExactBound()};
    std::vector<AxisPiece> xa = pieces(path_.x, anchor, anchor, wide, false);
    std::vector<AxisPiece> xs = pieces(path_.x, anchor, end, wide, false);
    std::vector<AxisPiece> ya = planar ? pieces(path_.y, anchor, anchor, wide, false) : std::vector<AxisPiece>{flat};
    std::vector<AxisPiece> ys = planar ? pieces(path_.y, anchor, end, wide, false) : std::vector<AxisPiece>{flat};
    if (wide || xa.size() != 1 || xs.size() != 1 || ya.size() != 1 || ys.size() != 1) return std::nullopt;
    auto same = [&](const AxisPiece& u, int k) {
      return u.rotation == at.newton_systems[k] && u.half_turn == at.newton_systems[k + 1];
    };
    if (!same(xa[0], 0) || !same(xs[0], 0) || !same(ya[0], 2) || !same(ys[0], 2)) return std::nullopt;
    const bool carried = cspace::carried_bounds();
    auto box = [&](const AxisPiece& q) {
      return carried ? DInterval{q.dlo, q.dhi} : enclose_range(q.lo.rational(), q.hi.rational());
    };
    DInterval start = curve_enclosure(impl_, *memo_, p.chart, p.curve).evaluate(box(xa[0]), box(ya[0]));
    const Gradient& g = gradient(p.chart, p.curve);
    const DInterval x = box(xs[0]), y = box(ys[0]);
    DInterval dx = chart_derivative(path_.x, anchor, end, xs[0]);
    DInterval dy = planar ? chart_derivative(path_.y, anchor, end, ys[0]) : DInterval{0, 0};
    DInterval rate = g.fx.evaluate(x, y) * dx + g.fy.evaluate(x, y) * dy;
    for (double v : {start.lo, start.hi, rate.lo, rate.hi})
      if (!std::isfinite(v)) return std::nullopt;
    bool toward = positive ? (start.lo > 0 && rate.hi < 0) : (start.hi < 0 && rate.lo > 0);
    if (!toward) return std::nullopt;
    NewtonBounds out;
    out.s_min = positive ? start.lo : -start.hi;
    out.s_max = positive ? start.hi : -start.lo;
    out.r_min = positive ? -rate.hi : rate.lo;
    out.r_max = positive ? -rate.lo : rate.hi;
    return out;
  }

 private:
  // The second-order (Taylor) exclusion, tried where the mean-value form fails: a motion that
  // starts next to a contact curve and slides along it (a sustained contact just released, the
  // Geneva wheel's locking arc on the driver's disc) has f'(a) near 0 while the enclosure of
  // F_x X' + F_y Y' over the stretch's box is as wide as |Hessian| |X'|^2 (b - a): only stretches of
  // about sqrt(f(a) / |Hessian|) were excluded, thousands of them. Taylor with the Lagrange
  // remainder: for u in [a, b], f(u) = f(a) + f'(a) (u - a) + f''(xi) (u - a)^2 / 2 with xi in
  // [a, b], so f([a, b]) lies in f(a) + [0, h] f'(a) + [0, h^2 / 2] f''([a, b]), f'(a) at the point
  // (the start pieces), f'' = F_xx X'^2 + 2 F_xy X' Y' + F_yy Y'^2 + F_x X'' + F_y Y'' over the
  // stretch's box (one chart system on [a, b], as the mean-value form). Certified like it.
  //
  // `fx`, `fy`: F_x, F_y over the stretch's box (the mean-value form's). `shared`: the start's
  // rates X'(a), Y'(a) on its pieces `sx`, `sy` and the stretch's X'', Y'' over [a, b] are the
  // same for every curve tried: computed on the first curve and taken again for the others (the
  // rates kept with the start pieces, for the next stretch from the same a) — pure functions of
  // a, b, the pieces and the path, the same bits (switch cspace::second_order_shared(); off:
  // computed for each curve as before).
  struct SecondOrderShared {
    std::size_t sx = 0, sy = 0;   // the start pieces' indices in start_->x, start_->y
    std::optional<DInterval> ddx, ddy;
  };
  bool second_order_excludes(const Possible& p, const Rational& a, const Rational& b, const DInterval& start,
                             const DInterval& x_at, const DInterval& y_at, std::vector<AxisPiece>::const_iterator sx,
                             std::vector<AxisPiece>::const_iterator sy, const DInterval& x, const DInterval& y,
                             const DInterval& dx, const DInterval& dy, const DInterval& fx, const DInterval& fy,
                             const AxisPiece& px, const AxisPiece& py, const DInterval& h, SecondOrderShared& shared) {
    if (!cspace::second_order()) return false;
    const Gradient& g = gradient(p.chart, p.curve);
    const Hessian& hs = hessian(p.chart, p.curve);
    const bool planar = impl_.dimension == 2;
    const bool keep = cspace::second_order_shared();
    // X'(a) on start piece i of an axis, kept with the start (index by the piece's place)
    auto start_rate = [&](const AxisPath& axis, std::vector<std::optional<DInterval>>& rates, std::size_t i,
                          const AxisPiece& piece) {
      if (!keep) return chart_derivative(axis, a, a, piece);
      if (rates.size() <= i) rates.resize(i + 1);
      if (!rates[i]) rates[i] = chart_derivative(axis, a, a, piece);
      else ++cspace::second_order_shared_hits();
      return *rates[i];
    };
    DInterval dx_at = start_rate(path_.x, start_->rate_x, shared.sx, *sx);
    DInterval dy_at = planar ? start_rate(path_.y, start_->rate_y, shared.sy, *sy) : DInterval{0, 0};
    DInterval rate_at = g.fx.evaluate(x_at, y_at) * dx_at + g.fy.evaluate(x_at, y_at) * dy_at;
    if (!keep || !shared.ddx) {
      shared.ddx = chart_acceleration(path_.x, a, b, px, x, dx);
      shared.ddy = planar ? chart_acceleration(path_.y, a, b, py, y, dy) : DInterval{0, 0};
    } else {
      ++cspace::second_order_shared_hits();
    }
    const DInterval ddx = *shared.ddx, ddy = *shared.ddy;
    DInterval curvature = hs.fxx.evaluate(x, y) * (dx * dx) + fx * ddx;
    if (planar)
      curvature = curvature + DInterval{2, 2} * hs.fxy.evaluate(x, y) * (dx * dy) + hs.fyy.evaluate(x, y) * (dy * dy) +
                  fy * ddy;
    DInterval half_square = DInterval{0, 0.5} * (h * h);
    DInterval value = start + h * rate_at + half_square * curvature;
    if (std::isfinite(value.lo) && std::isfinite(value.hi) && !value.contains_zero()) {
      ++cspace::second_order_exclusions();
      return true;
    }
    // The same Taylor form nested (cspace::nested_taylor()): for t = u - a in [0, h],
    // f(a) + t (f'(a) + (t / 2) f''(xi)) with t / 2 in [0, h / 2], enclosed as
    // start + h (rate_at + [0, h / 2] curvature). The first factor t and the t in t / 2 are the
    // same number, taken here independently: still an enclosure, and within subdistributivity
    // (h (r + s c) is in h r + h s c) no wider than the sum above in exact interval arithmetic.
    // Where the sum fails because h r's lower end 0 and (h^2 / 2) c's negative lower end are
    // taken at different t (a motion leaving a curve: f(a) > 0 tiny, f'(a) > 0, c < 0), the
    // nested form keeps f >= f(a) > 0 on every t with f'(a) + t c / 2 > 0: stretches up to
    // 2 f'(a) / |c| instead of sqrt(2 f(a) / |c|). Tried only where the sum fails (its
    // exclusions all kept: a stretch excluded before is excluded now).
    if (!cspace::nested_taylor()) return false;
    DInterval half_h = DInterval{0, 0.5} * h;
    DInterval nested = start + h * (rate_at + half_h * curvature);
    if (!std::isfinite(nested.lo) || !std::isfinite(nested.hi) || nested.contains_zero()) return false;
    ++cspace::second_order_exclusions();
    ++cspace::nested_taylor_exclusions();
    return true;
  }

  // F of local curve `curve` of `chart` over the start's rational box, enclosed in doubles
  // (outward): certified, and free of zero whenever the start lies off the curve by more than
  // the box's width (2^-160 relative), however close.
  // `px`, `py`: the systems of the stretch's pieces; the start's exact pieces are computed on
  // first use (a start not in those systems: the whole line, nothing proved).
  DInterval exact_start_value(std::size_t chart, std::size_t curve, const AxisPiece& px, const AxisPiece& py) {
    auto key = std::make_pair(chart, curve);
    auto it = start_->exact.find(key);
    if (it != start_->exact.end()) return it->second;
    if (!start_->fine_ready) {
      start_->fine_ready = true;
      start_->fine_x = pieces(path_.x, start_->a, start_->a, start_->fine_wide, true);
      if (impl_.dimension == 2) start_->fine_y = pieces(path_.y, start_->a, start_->a, start_->fine_wide, true);
      else start_->fine_y = {AxisPiece{false, false, ExactBound(), ExactBound()}};
    }
    const DInterval everything{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    auto same = [](const AxisPiece& p, const AxisPiece& q) { return p.rotation == q.rotation && p.half_turn == q.half_turn; };
    auto sx = std::find_if(start_->fine_x.begin(), start_->fine_x.end(), [&](const AxisPiece& p) { return same(p, px); });
    auto sy = std::find_if(start_->fine_y.begin(), start_->fine_y.end(), [&](const AxisPiece& p) { return same(p, py); });
    if (start_->fine_wide || sx == start_->fine_x.end() || sy == start_->fine_y.end()) return everything;
    const AxisPiece& x = *sx;
    const AxisPiece& y = *sy;
    const cspace::IntegerPolynomial2& f = impl_.charts[chart].polynomials[curve];
    RInterval X{x.lo.rational(), x.hi.rational()}, Y{y.lo.rational(), y.hi.rational()}, value = RInterval::point(Rational(0));
    for (std::size_t i = f.coefficients.size(); i-- > 0;) {
      RInterval row = RInterval::point(Rational(0));
      for (std::size_t j = f.coefficients[i].size(); j-- > 0;)
        row = row * Y + RInterval::point(Rational(f.coefficients[i][j]));
      value = value * X + row;
    }
    // at the scale of the double enclosures it is added to (F / 2^shift, interval_shift.hpp)
    if (const long shift = cspace::algebra::interval_shift(f); shift > 0) {
      mpq_div_2exp(value.lo.get_mpq_t(), value.lo.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
      mpq_div_2exp(value.hi.get_mpq_t(), value.hi.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
    }
    DInterval result{cspace::algebra::lower_double(value.lo), cspace::algebra::upper_double(value.hi)};
    start_->exact.emplace(key, result);
    return result;
  }

  // Do the boxes of `charts` (same system) cover px x py? Grid of the boxes' sides.
  bool covers(const std::vector<std::size_t>& charts, const AxisPiece& px, const AxisPiece& py) const {
    // one box holding px x py covers it (every grid cell below lies in it)
    if (cspace::carried_bounds())
      for (std::size_t c : charts)
        if (px.lo >= side(c, 0) && px.hi <= side(c, 1) &&
            (impl_.dimension == 1 || (py.lo >= side(c, 2) && py.hi <= side(c, 3))))
          return true;
    auto cells = [](std::vector<Rational> cuts) {
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      if (cuts.size() == 1) return cuts;
      std::vector<Rational> middles;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) middles.push_back((cuts[i] + cuts[i + 1]) / 2);
      return middles;
    };
    std::vector<Rational> xcuts{px.lo.rational(), px.hi.rational()}, ycuts{py.lo.rational(), py.hi.rational()};
    for (std::size_t c : charts) {
      const CSpaceChart& chart = impl_.public_charts[c];
      for (const Rational& v : {chart.x_lo, chart.x_hi})
        if (v > px.lo && v < px.hi) xcuts.push_back(v);
      if (impl_.dimension == 2)
        for (const Rational& v : {chart.y_lo, chart.y_hi})
          if (v > py.lo && v < py.hi) ycuts.push_back(v);
    }
    for (const Rational& mx : cells(xcuts))
      for (const Rational& my : cells(ycuts)) {
        bool inside = false;
        for (std::size_t c : charts) {
          const CSpaceChart& chart = impl_.public_charts[c];
          if (mx < chart.x_lo || mx > chart.x_hi) continue;
          if (impl_.dimension == 2 && (my < chart.y_lo || my > chart.y_hi)) continue;
          inside = true;
          break;
        }
        if (!inside) return false;
      }
    return true;
  }

  // The curves of a chart that can bound the start cell: those carried by an edge between
  // different cells (contact edges), with the edges' certified boxes, and those through an
  // isolated vertex (tested everywhere). A first crossing lies on such an edge or vertex.
  using Carrier = ScanMemo::Carrier;
  using ChartCarriers = ScanMemo::ChartCarriers;

  const ChartCarriers& carriers(std::size_t c) { return chart_carriers(impl_, *memo_, c); }

  // Curves of the box's chart that may vanish (validly) in the box, on a contact edge's box.
  void exclude(std::size_t piece, const PieceBox& box, std::vector<Possible>& possible) {
    const ChartData& chart = impl_.charts[box.chart];
    cspace::algebra::Interval x{box.dx_lo, box.dx_hi}, y{box.dy_lo, box.dy_hi};
    if (!cspace::carried_bounds()) {
      x = {cspace::algebra::lower_double(box.x_lo.rational()), cspace::algebra::upper_double(box.x_hi.rational())};
      y = {cspace::algebra::lower_double(box.y_lo.rational()), cspace::algebra::upper_double(box.y_hi.rational())};
    }
    std::vector<char>& candidate = candidate_;
    candidate.assign(chart.polynomials.size(), impl_.dimension == 1 ? 1 : 0);
    if (impl_.dimension == 2) {
      const ChartCarriers& known = carriers(box.chart);
      for (std::size_t k : known.everywhere) candidate[k] = 1;
      for (const Carrier& carrier : known.edges) {
        if (x.hi < carrier.box[0] || x.lo > carrier.box[2] || y.hi < carrier.box[1] || y.lo > carrier.box[3]) continue;
        for (std::size_t k : carrier.curves) candidate[k] = 1;
      }
    }
    for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
      if (!candidate[k]) continue;
      if (!curve_enclosure(impl_, *memo_, box.chart, k).evaluate(x, y).contains_zero()) continue;
      const auto& clauses = validity(box.chart, k);
      bool invalid = false;
      for (const auto& clause : clauses) {
        bool all_negative = true;
        for (const auto& atom : clause) all_negative = all_negative && atom.evaluate(x, y).hi < 0;
        if (all_negative) {
          invalid = true;
          break;
        }
      }
      if (!invalid) possible.push_back(Possible{box.chart, k, piece});
    }
  }

  const std::vector<std::vector<cspace::algebra::IntervalPolynomial2>>& validity(std::size_t chart, std::size_t k) {
    std::vector<std::optional<Clauses>>& memo = memo_->validity[chart];
    if (memo.empty()) memo.resize(impl_.charts[chart].polynomials.size());
    if (memo[k]) return *memo[k];
    Clauses clauses;
    cspace::algebra::ScaledEnclosures scope;   // (signs only: each atom at its own scale)
    for (const auto& clause : impl_.charts[chart].validity[k]) {
      clauses.emplace_back();
      for (const auto& atom : clause.atoms) clauses.back().emplace_back(atom);
    }
    memo[k] = std::move(clauses);
    return *memo[k];
  }

  const CSpace::Impl& impl_;
  const MotionPath& path_;
  std::array<std::pair<Rational, KInterval>, 4>& ends_;   // enclosure()'s memo
  mutable std::size_t next_end_ = 0, filled_ends_ = 0;
  struct PathValue {
    std::uint64_t lo = 0, hi = 0;   // A.lo, B.hi's bit patterns
    std::optional<KInterval> value;
  };
  struct PathValues {
    std::array<PathValue, 4> entries{};
    std::size_t next = 0, filled = 0;
    const PathValue* find(std::uint64_t lo, std::uint64_t hi) const {
      for (std::size_t i = 0; i < filled; ++i)
        if (entries[i].lo == lo && entries[i].hi == hi) return &entries[i];
      return nullptr;
    }
    void put(std::uint64_t lo, std::uint64_t hi, const std::optional<KInterval>& value) {
      entries[next] = PathValue{lo, hi, value};
      next = (next + 1) % entries.size();
      filled = std::min(filled + 1, entries.size());
    }
  };
  // path_enclosure()'s memo: x, y; their rates; their accelerations
  mutable std::array<PathValues, 6> path_values_{};
  struct StartPieces {
    Rational a;
    std::vector<AxisPiece> x, y;
    bool wide = false;
    std::map<std::pair<std::size_t, std::size_t>, cspace::algebra::Interval> exact;   // exact_start_value
    std::vector<std::optional<cspace::algebra::Interval>> rate_x, rate_y;   // second_order_excludes' X'(a), Y'(a) per piece
    // the exact (160-bit) pieces at a, computed on first use by exact_start_value
    bool fine_ready = false, fine_wide = false;
    std::vector<AxisPiece> fine_x, fine_y;
  };
  std::optional<StartPieces> start_;
  // per axis (x, y): the path's coefficients and those of its first and second derivatives,
  // enclosed in doubles
  std::vector<std::vector<KInterval>>&enclosed_, &enclosed_rate_, &enclosed_acceleration_;
  // per chart, per local curve: memos filled on first use, shared by the space's queries
  using Clauses = ScanMemo::Clauses;
  std::shared_ptr<ScanMemo> memo_;
  std::vector<char>& candidate_;   // exclude()'s scratch
  std::vector<Possible>& hull_possible_;   // locate_inside's
  ChartPoint& located_;                     // locate_inside's
  Rational &bound_lo_, &bound_hi_;          // locate_inside's
  std::vector<std::size_t>& charts_;        // evaluate's (kept: Storage::charts)
};

}  // namespace

namespace {

using cspace::StretchStack;

// CSpace::first_crossing's query as an object taking one step at a time (CrossingQuery,
// crossing_before.hpp): the start's point query, then one stretch of the subdivision per step.
// run() to the end takes the uninterrupted query's steps in its order; stopping between steps
// leaves the stretches still to evaluate on the stack, in path order, so that resuming goes on
// with exactly the steps the uninterrupted query would take next.
class CrossingRun {
 public:
  using Impl = CSpace::Impl;

  CrossingRun(const CSpace& space, const MotionPath& input, const CrossingOptions& options)
      : impl(checked(space)),
        kept(Kept::take()),
        path(canonical(kept->path, input)),
        owner(CSpaceAccess::shared(space)),
        scanner(impl, path, scan_memo_of(owner), kept->scanner),
        options(options) {}

  // its start's box and the stretches it excluded are left as anchor boxes (finished or stopped)
  ~CrossingRun() {
    if (excluded_boxes.empty()) return;
    try {
      remember_anchor_boxes(excluded_boxes, owner);
    } catch (...) {   // (memory) the boxes are an optimisation: none is left
    }
  }
  CrossingRun(const CrossingRun&) = delete;
  CrossingRun& operator=(const CrossingRun&) = delete;

  bool finished() const { return done; }

  const Rational& next() const { return done ? result.u_lower : started ? stack.back().first : path.u_begin; }

  void step() {
    if (done) return;
    if (!started) {
      started = true;
      start();
      if (done) return;
      // ---- subdivision: intervals in path order, excluded ones certified in the starting cell
      resolution = (path.u_end - path.u_begin) / Rational(mpz_class(1) << options.resolution_bits);
      resolution.canonicalize();
      resolution_d = resolution.get_d();
      stack.emplace_back(path.u_begin, path.u_end);
    } else {
      // copied into kept rationals (their limbs reused) before the stretch pushes onto its slot
      stretch_a = stack.back().first;
      stretch_b = stack.back().second;
      stack.pop_back();
      stretch(stretch_a, stretch_b);
      if (done) return;
    }
    settle();
  }

  // steps until the answer is known or, after the start, the next stretch starts past *stop
  void run(const Rational* stop) {
    while (!done) {
      if (started && stop && next() > *stop) return;
      step();
    }
  }

  // finished: the query's answer; stopped: none at the next stretch's start
  MotionCrossing answer() const {
    MotionCrossing copy = result;
    if (!done) copy.u_lower = copy.u_upper = next();
    return copy;
  }

  MotionCrossing take_answer() && {
    if (!done) result.u_lower = result.u_upper = next();
    return std::move(result);
  }

 private:
  // `input` canonical in `path` (a kept path: copied into its rationals, their limbs reused)
  static MotionPath& canonical(MotionPath& path, const MotionPath& input) {
    path = input;
    // (a value already canonical is left as mpq_canonicalize leaves it, without its gcd: the
    // simulator's coefficients are doubles, an odd numerator over a power of two or over 1)
    auto canonicalize = [](Rational& r) {
      mpz_srcptr den = mpq_denref(r.get_mpq_t());
      if (mpz_cmp_ui(den, 1) == 0) return;
      if (mpz_sgn(den) > 0 && mpz_popcount(den) == 1 && mpz_odd_p(mpq_numref(r.get_mpq_t()))) return;
      r.canonicalize();
    };
    for (auto* axis : {&path.x, &path.y})
      for (auto& c : axis->coefficients) canonicalize(c);
    canonicalize(path.u_begin);
    canonicalize(path.u_end);
    if (path.u_end < path.u_begin) throw GeometryError("first_crossing: u_end < u_begin");
    return path;
  }

  // The query's working storage that outlives it on its thread (exact_bound.hpp, kept_runs):
  // its canonical path, its stack's slots and the rationals its steps write before they read
  // them; a taken one's stack is emptied, its path and rationals are overwritten before use.
  struct Kept {
    MotionPath path;
    StretchStack stack;
    Rational resolution;
    Rational stretch_a, stretch_b;   // the stretch being evaluated (step())
    Rational skip_bound;              // free_before's product
    MotionScanner::Storage scanner;
    static void dispose(Kept* p) { delete p; }
    using Pool = KeptPerThread<Kept, 8>;
    struct Back {
      void operator()(Kept* p) const noexcept {
        if (!cspace::kept_runs() || !Pool::keep(p)) dispose(p);
      }
    };
    static std::unique_ptr<Kept, Back> take() {
      Kept* p = cspace::kept_runs() ? Pool::take() : nullptr;
      if (!p) return std::unique_ptr<Kept, Back>(new Kept);
      ++cspace::kept_run_reuses();
      p->stack.clear();
      return std::unique_ptr<Kept, Back>(p);
    }
  };

  // a real edge of `possible` curves near the crossing, its feature pairs, chart point and frame
  // (not in a StatusOnlyCrossings scope: its caller reads none of them)
  void describe(const MotionScanner::Evaluation& at, std::size_t entered) {
    if (status_only_crossings()) {
      ++skipped_descriptions();
      return;
    }
    for (const Possible& p : at.possible) {
      FeatureId id(impl.charts[p.chart].curve_global[p.curve]);
      if (std::find(result.features.begin(), result.features.end(), id) == result.features.end())
        result.features.push_back(id);
    }
    if (at.possible.empty()) return;
    const Possible& first = at.possible.front();
    const PieceBox& box = at.boxes[first.piece];
    result.chart = box.chart;
    result.chart_point = {range_of(box.x_lo.rational(), box.x_hi.rational()), range_of(box.y_lo.rational(), box.y_hi.rational())};
    // the real edge crossed: among the real edges of the charts met whose certified boxes meet
    // the bracket's, prefer one between the start cell and the cell entered carrying a
    // possible curve, then one between the two cells, then one carrying a possible curve
    int best = 0;
    if (result.edge.valid()) best = 3;   // known exactly
    for (std::size_t i = 0; i < at.boxes.size() && best < 3; ++i) {
      const PieceBox& piece = at.boxes[i];
      const ChartData& chart = impl.charts[piece.chart];
      double bx[4] = {cspace::algebra::lower_double(piece.x_lo.rational()), cspace::algebra::lower_double(piece.y_lo.rational()),
                      cspace::algebra::upper_double(piece.x_hi.rational()), cspace::algebra::upper_double(piece.y_hi.rational())};
      for (std::size_t e = 0; e < chart.edges.size() && best < 3; ++e) {
        const CSpaceEdge& edge = impl.edges[chart.edges[e].global];
        if (!edge.real) continue;
        if (impl.dimension == 2) {
          const auto& raw_box = chart.arrangement.edges[e].box;
          if (bx[2] < raw_box[0] || bx[0] > raw_box[2] || bx[3] < raw_box[1] || bx[1] > raw_box[3]) continue;
        }
        const auto& curves = chart.edges[e].curves;
        bool carries = std::any_of(at.possible.begin(), at.possible.end(), [&](const Possible& p) {
          return p.chart == piece.chart && std::find(curves.begin(), curves.end(), p.curve) != curves.end();
        });
        bool separates = entered != no_index &&
                         ((edge.left_cell == result.cell_left.index() && edge.right_cell == entered) ||
                          (edge.right_cell == result.cell_left.index() && edge.left_cell == entered));
        int score = separates && carries ? 3 : separates ? 2 : carries ? 1 : 0;
        if (score > best) {
          best = score;
          result.edge = EdgeId(chart.edges[e].global);
        }
      }
    }
    if (impl.model && !result.features.empty()) {
      auto enclose = [](const Rational& r) { return KInterval::enclose(r); };
      KInterval x(cspace::algebra::lower_double(box.x_lo.rational()), cspace::algebra::upper_double(box.x_hi.rational()));
      KInterval y(cspace::algebra::lower_double(box.y_lo.rational()), cspace::algebra::upper_double(box.y_hi.rational()));
      kernels::ContactFrame<KInterval> frame =
          frame_at<KInterval>(impl, box.chart, impl.feature_pairs[result.features.front().index()], x, y, enclose);
      if (frame.defined) {
        result.point = {range_of(frame.point.x), range_of(frame.point.y)};
        result.normal = unit_normal(frame.normal);
      }
    }
  }

  // ---- the start
  void start() {
    result.u_lower = result.u_upper = path.u_begin;
    Location where;
    bool located = false;
    // the filtered start (start_filter.hpp): a rotating axis's start through the double filter,
    // located there when its boxes are covered, meet no contact curve and their front midpoint
    // lies inside a free or a blocked cell's face; otherwise the 160-bit start below, as without
    // the filter
    if (cspace::start_filter() &&
        (path.x.kind == AxisPath::Kind::angle || (impl.dimension == 2 && path.y.kind == AxisPath::Kind::angle))) {
      MotionScanner::Evaluation quick = scanner.evaluate(path.u_begin, path.u_begin, true);
      if (!quick.too_wide && quick.covered && !quick.boxes.empty() && quick.possible.empty()) {
        Location there = scanner.locate_inside(quick.boxes.front(), find_anchor(owner), find_anchor_boxes(owner));
        if (there.kind == Location::Kind::free || there.kind == Location::Kind::blocked) {
          ++cspace::filtered_starts();
          if (there.kind == Location::Kind::blocked) {
            // in a blocked cell: the 160-bit start's answer (its boxes meet no curve either, so
            // describe adds nothing to it)
            result.status = CrossingStatus::starts_in_contact;
            result.cell_left = CellId(there.cell);
            if (there.edge != no_index) result.edge = EdgeId(there.edge);
            done = true;
            return;
          }
          where = there;
          located = true;
          remember_start_box(quick.boxes.front(), there.cell);
        }
      }
    }
    if (!located) {
      MotionScanner::Evaluation start = scanner.evaluate(path.u_begin, path.u_begin);
      if (!start.covered || start.boxes.empty()) {
        result.status = CrossingStatus::outside_region;
        done = true;
        return;
      }
      bool point_exact = std::all_of(start.boxes.begin(), start.boxes.end(), [](const PieceBox& b) {
        return b.x_lo == b.x_hi && b.y_lo == b.y_hi;
      });
      if (start.possible.empty() || point_exact) {
        where = scanner.locate_inside(start.boxes.front(), find_anchor(owner), find_anchor_boxes(owner));
      } else {
        // an irrational start within the resolution of a contact curve: in contact, conservatively
        result.status = CrossingStatus::starts_in_contact;
        result.grazing = true;
        describe(start, no_index);
        done = true;
        return;
      }
      if (where.kind != Location::Kind::free || contact_location(impl, where)) {
        result.status = CrossingStatus::starts_in_contact;
        result.cell_left = CellId(where.cell);
        if (where.edge != no_index) result.edge = EdgeId(where.edge);
        describe(start, no_index);
        done = true;
        return;
      }
      if (start.possible.empty()) remember_start_box(start.boxes.front(), where.cell);
    }
    result.cell_left = CellId(where.cell);
  }

  // a located free start's box, on which no cell-bounding curve vanishes: in the start cell
  void remember_start_box(const PieceBox& box, std::size_t cell) {
    if (cspace::anchor_boxes()) excluded_boxes.push_back(AnchorBox{box, cell});
  }

  // empty stretches dropped; at an empty stack the motion stays in its start cell to u_end
  void settle() {
    while (!stack.empty() && stack.back().first == stack.back().second) stack.pop_back();
    if (!stack.empty()) return;
    done = true;
    result.u_lower = result.u_upper = path.u_end;
    if (last && cspace::start_anchors())
      if (std::optional<StartAnchor> anchor = scanner.anchor_from(*last, result.cell_left.index()))
        remember_anchor(std::move(*anchor), owner);
  }

  void split(const Rational& a, const Rational& b) {
    Rational& m = scratch().m;
    cspace::midpoint_into(m, a, b);
    stack.emplace_back(m, b);
    stack.emplace_back(a, m);
  }

  // The Newton proposal (see crossing_shrink.hpp). The subdivision's stretches are the nodes
  // of the binary tree over [u_begin, u_end] whose leaves are the resolution's cells; a stretch
  // of n = 2^m cells that would be halved goes straight to the smallest node [c_lo, c_hi] of
  // its subtree holding the root's proposed bounds (widened by a cell either way, and inside
  // [a, b]), when that node has at most half the cells: the nodes between are skipped (the
  // curve vanishes inside each, so the halving would not have excluded them, only halved them),
  // their siblings are evaluated in path order as the halving would (excluded or subdivided).
  // The stretches evaluated are the halving's minus those nodes: the same answer (see
  // crossing_shrink.hpp).
  void shrink(const Rational& a, const Rational& b, const MotionScanner::Evaluation& at) {
    refined_anchor = -1;
    if (cspace::newton_shrink() && at.newton) {
      Rational& cells = scratch().c;
      cspace::sum_into(cells, b, a, -1);
      mpq_div(cells.get_mpq_t(), cells.get_mpq_t(), resolution.get_mpq_t());   // canonical
      if (cells.get_den() == 1 && cells.get_num() > 2 && cells.get_num().fits_slong_p()) {
        const long n = cells.get_num().get_si();
        double lo = std::floor(at.newton_lo / resolution_d * (1 - 0x1p-48)) - 1;
        double hi = std::ceil(at.newton_hi / resolution_d * (1 + 0x1p-48)) + 1;
        // only where the widened bounds lie inside [a, b] (not clipped): then the curve
        // vanishes inside every node between [a, b] and the node proposed
        if ((n & (n - 1)) == 0 && lo >= 0 && hi <= static_cast<double>(n)) {
          long k_lo = static_cast<long>(lo), k_hi = static_cast<long>(hi);
          if (cspace::newton_refine()) refine(a, at, k_lo, k_hi);
          // the widening by a cell dropped where the certified bounds allow it: the curve
          // certainly nonzero up to cell k_lo + 1, certainly past its sign change from k_hi - 1
          // (so a sign change, which no stretch's exclusion can pass, lies between)
          if (cspace::skip_left() && k_lo + 2 < k_hi) {
            if (free_before(cells_of(k_lo + 1), at)) ++k_lo;
            if (past_change(cells_of(k_hi - 1), at)) --k_hi;
          }
          if (k_lo < k_hi) {
            // the smallest node holding cells k_lo ... k_hi - 1: 2^j cells from k_lo's multiple
            unsigned long diff = static_cast<unsigned long>(k_lo ^ (k_hi - 1));
            int j = 0;
            while (j < 63 && (diff >> j) != 0) ++j;
            long size = 1L << j, first = (k_lo >> j) << j;
            if (2 * size <= n) {
              // the path from [a, b] down to the node: the siblings left of it are the
              // stretches the halving evaluates (and excludes) before reaching it, those right
              // of it the ones it would evaluate after; pushed so that they pop in path order
              ++cspace::newton_steps();
              // a + k resolution (dyadic.hpp: by shifts where both are dyadic)
              auto at_cell = [&](long k) -> const Rational& {
                cspace::sum_multiple_into(scratch().u, a, resolution, k);
                return scratch().u;
              };
              std::vector<std::pair<long, long>> left;
              long lo = 0, length = n;
              while (length > size) {
                long half = length / 2;
                if (first < lo + half) {
                  scratch().v = at_cell(lo + half);
                  stack.emplace_back(scratch().v, at_cell(lo + length));
                } else {
                  left.emplace_back(lo, lo + half);
                  lo += half;
                }
                length = half;
              }
              scratch().v = at_cell(first);
              stack.emplace_back(scratch().v, at_cell(first + size));
              // the siblings left of the node, [a, a + first cells), certified free when the
              // curve's mean-value bound keeps it off 0 there (crossing_shrink.hpp, skip_left)
              if (!left.empty() && cspace::skip_left()) {
                bool skip = free_before(cells_of(first), at);
                if (!skip && cspace::refined_skip() && refined_free_before(first)) {
                  skip = true;
                  ++cspace::refined_skips();
                  cspace::refined_skipped_stretches() += left.size();
                }
                if (skip) {
                  cspace::skipped_left() += left.size();
                  return;
                }
              }
              for (auto it = left.rbegin(); it != left.rend(); ++it) {
                scratch().v = at_cell(it->first);
                stack.emplace_back(scratch().v, at_cell(it->second));
              }
              return;
            }
          }
        }
      }
    }
    // a halving whose first half the curve's certified bound keeps free: only the second half
    if (cspace::newton_shrink() && at.newton && cspace::skip_left()) {
      Rational& m = scratch().m;
      cspace::midpoint_into(m, a, b);
      cspace::sum_into(scratch().w, m, a, -1);
      if (free_before(scratch().w, at)) {
        ++cspace::skipped_left();
        stack.emplace_back(m, b);
        return;
      }
    }
    split(a, b);
  }

  // The proposal's cells [k_lo, k_hi) of [a, b] (the root of the one curve left certainly
  // inside) narrowed by Newton steps from anchors inside it (MotionScanner::newton_from,
  // cspace::newton_refine()): from the anchor a + k_lo cells, before the root, and the rate
  // over [a + k_lo, a + k_hi] cells, which holds it, the root lies s_min / r_max ... s_max / r_min
  // past the anchor; widened by a cell either way (and the relative 2^-48 the doubles' rounding
  // needs, as the first proposal) and kept only inside [k_lo, k_hi]. The bounds only choose the
  // node to go to: each narrowing keeps the root inside, so the nodes skipped hold it (the
  // halving would only have halved them) as without it. At most four steps, while each takes
  // off at least a quarter of the span and the span is wider than four cells.
  // The last anchor's cell and bounds are kept (refined_anchor, refined_bounds) for
  // refined_free_before.
  void refine(const Rational& a, const MotionScanner::Evaluation& at, long& k_lo, long& k_hi) {
    refined_anchor = -1;
    thread_local Rational anchor, end;
    for (int step = 0; step < 4 && k_hi - k_lo > 4; ++step) {
      cspace::sum_multiple_into(anchor, a, resolution, k_lo);
      cspace::sum_multiple_into(end, a, resolution, k_hi);
      std::optional<MotionScanner::NewtonBounds> bounds = scanner.newton_from(anchor, end, at);
      ++cspace::newton_refine_steps();
      if (!bounds) return;
      refined_anchor = k_lo;
      refined_bounds = *bounds;
      double lo = std::floor(bounds->s_min / bounds->r_max / resolution_d * (1 - 0x1p-48)) - 1;
      double hi = std::ceil(bounds->s_max / bounds->r_min / resolution_d * (1 + 0x1p-48)) + 1;
      const double span = static_cast<double>(k_hi - k_lo);
      if (!(lo < span) || !(hi >= 0)) return;   // (NaN, or outside: nothing narrowed)
      long new_lo = lo > 0 ? k_lo + static_cast<long>(lo) : k_lo;
      long new_hi = hi < span ? k_lo + static_cast<long>(hi) : k_hi;
      if (new_lo >= new_hi) return;
      if (new_lo > k_lo || new_hi < k_hi) ++cspace::refine_narrowings();
      bool enough = 4 * (new_hi - new_lo) <= 3 * (k_hi - k_lo);
      k_lo = new_lo;
      k_hi = new_hi;
      if (!enough) return;
    }
  }

  // Whether the one curve left over [a, b] (as free_before) certainly does not vanish on
  // [a, a + k cells], from refine's last anchor a + j cells: f has one sign of rate over
  // [a, b] (monotone there) and f(a + j cells) the sign of f(a), so f != 0 on [a, a + j cells];
  // past it f(u) lies in f(anchor) + (u - anchor) rate over the anchor's box [anchor, end],
  // which holds [anchor, a + k cells] where k is below refine's final k_lo (as free_before:
  // exact, (k - j) cells r_max < s_min in rationals).
  bool refined_free_before(long k) {
    if (refined_anchor < 0) return false;
    if (k <= refined_anchor) return true;
    return cspace::compare_product(cells_of(k - refined_anchor), refined_bounds.r_max, refined_bounds.s_min, skip_bound) < 0;
  }

  // Whether the one curve left over the stretch [a, b] just evaluated (`at`: every other curve
  // excluded on [a, b], this one's f(a) and rate over [a, b] of opposite signs) certainly does
  // not vanish on [a, a + offset] (offset <= b - a): f(u) lies in f(a) + (u - a) rate (the
  // mean-value form over the stretch's box, one chart system), so |f(u)| >= s_min - (u - a) r_max
  // > 0 there. Exact: offset * r_max < s_min in rationals (the doubles are the enclosures' ends).
  bool free_before(const Rational& offset, const MotionScanner::Evaluation& at) {
    if (!(at.newton_s_min > 0) || !std::isfinite(at.newton_r_max) || !(at.newton_r_max >= 0)) return false;
    // (dyadic.hpp: the product's certified double enclosure first, then the exact product)
    return cspace::compare_product(offset, at.newton_r_max, at.newton_s_min, skip_bound) < 0;
  }

  // Whether that curve's value certainly has the sign opposite to f(a)'s at a + offset (offset
  // <= b - a): f(u) - f(a) lies in (u - a) rate, of the other sign and at least (u - a) r_min in
  // magnitude, so past s_max >= |f(a)| it has changed sign. Exact: offset * r_min > s_max.
  bool past_change(const Rational& offset, const MotionScanner::Evaluation& at) {
    if (!(at.newton_r_min > 0) || !std::isfinite(at.newton_s_max) || !(at.newton_s_max > 0)) return false;
    return cspace::compare_product(offset, at.newton_r_min, at.newton_s_max, skip_bound) > 0;
  }

  // k resolutions (dyadic.hpp), in a kept rational
  const Rational& cells_of(long k) {
    cspace::sum_multiple_into(scratch().k, scratch().zero, resolution, k);
    return scratch().k;
  }

  // one stretch [a, b] of the subdivision: excluded, split, or the answer
  void stretch(const Rational& a, const Rational& b) {
    MotionScanner::Evaluation at = scanner.evaluate(a, b);
    cspace::sum_into(scratch().w, b, a, -1);
    bool wide = scratch().w > resolution;
    if (at.too_wide) {
      split(a, b);
      return;
    }
    if (!at.covered) {
      if (wide) {
        split(a, b);
        return;
      }
      result.status = CrossingStatus::outside_region;
      result.u_lower = a;
      result.u_upper = b;
      done = true;
      return;
    }
    if (at.possible.empty()) {
      // in the start cell (the stretches before it excluded or certified free): an anchor box
      if (cspace::anchor_boxes() && at.box_clear && at.boxes.size() == 1 && excluded_boxes.size() < 64)
        excluded_boxes.push_back(AnchorBox{at.boxes.front(), result.cell_left.index()});
      if (b == path.u_end) last = std::move(at);
      return;
    }
    if (wide) {
      shrink(a, b, at);
      return;
    }
    // a stretch within the resolution that may touch contact space: decide where the motion
    // is after it. A rational configuration (offset and half-tangent motions) is located
    // exactly, any other one when no contact curve meets its enclosure; the end moves forward
    // in doubling steps (at most 2^24 resolutions) until it is certainly outside the start
    // cell, and the bracket grows to it: the motion is in the start cell at u_lower and no
    // longer in it at u_upper, so its first contact lies between. If no such end is found,
    // the tiny stretch is reported as a possible touch (grazing).
    result.status = CrossingStatus::crossing;
    result.u_lower = a;
    result.u_upper = b;
    std::size_t entered = no_index;
    bool left_start = false;
    Rational reach = b - a;
    Rational end_u = b;
    for (int attempt = 0; attempt < 24; ++attempt) {
      // the end through the double filter first (start_filter.hpp, end_filter): a location in a
      // free or a blocked cell's face there is the 160-bit end's; otherwise the 160-bit end
      std::optional<Location> location = filtered_end(end_u);
      bool located = location.has_value();
      if (!located) {
        MotionScanner::Evaluation end = scanner.evaluate(end_u, end_u);
        if (!end.covered || end.boxes.empty()) break;
        bool exact_point = std::all_of(end.boxes.begin(), end.boxes.end(), [](const PieceBox& box) {
          return box.x_lo == box.x_hi && box.y_lo == box.y_hi;
        });
        if (exact_point || end.possible.empty()) {
          location = scanner.locate_inside(end.boxes.front());
          located = true;
        }
      }
      if (located) {
        const Location& there = *location;
        if (there.kind != Location::Kind::free || there.cell != result.cell_left.index()) {
          left_start = true;
          result.u_upper = end_u;
          if (there.kind == Location::Kind::blocked || there.kind == Location::Kind::free) {
            entered = there.cell;
            result.cell_entered = CellId(there.cell);
          } else if (there.edge != no_index && impl.edges[there.edge].real) {
            result.edge = EdgeId(there.edge);   // exactly on a contact edge at u_upper
          }
          break;
        }
      }
      reach *= 2;
      end_u = b + reach;
      if (end_u > path.u_end) break;
    }
    result.grazing = !left_start;
    if (left_start && result.u_upper != b) {
      MotionScanner::Evaluation bracket = scanner.evaluate(a, result.u_upper);
      describe(bracket.possible.empty() ? at : bracket, entered);
    } else {
      describe(at, entered);
    }
    result.u_upper.canonicalize();
    done = true;
  }

  // The location of the path's point at u through the double filter (end_filter, as the
  // filtered start): set only where it lies in a free or a blocked cell's face, a box of the
  // filtered pieces covered by the charts and free of every contact curve around it.
  std::optional<Location> filtered_end(const Rational& u) {
    if (!cspace::end_filter() ||
        !(path.x.kind == AxisPath::Kind::angle || (impl.dimension == 2 && path.y.kind == AxisPath::Kind::angle)))
      return std::nullopt;
    MotionScanner::Evaluation quick = scanner.evaluate(u, u, true);
    if (quick.too_wide || !quick.covered || quick.boxes.empty() || !quick.possible.empty()) return std::nullopt;
    Location there = scanner.locate_inside(quick.boxes.front());
    if (there.kind != Location::Kind::free && there.kind != Location::Kind::blocked) return std::nullopt;
    ++cspace::filtered_ends();
    return there;
  }

  const Impl& impl;
  std::unique_ptr<Kept, Kept::Back> kept;
  MotionPath& path;
  std::shared_ptr<const Impl> owner;
  MotionScanner scanner;
  CrossingOptions options;
  MotionCrossing result;
  bool started = false, done = false;
  Rational& resolution = kept->resolution;
  double resolution_d = 0;
  StretchStack& stack = kept->stack;
  Rational& stretch_a = kept->stretch_a;
  Rational& stretch_b = kept->stretch_b;
  Rational& skip_bound = kept->skip_bound;
  // the rationals a step works in (midpoints, cells, widths), per thread: kept between steps and
  // queries so that their limbs are reused, and never held across a step (the sweep's queries
  // take their steps one at a time on a thread)
  struct Scratch {
    Rational m, u, v, w, k, c;
    const Rational zero{0};
  };
  static Scratch& scratch() {
    thread_local Scratch kept;
    return kept;
  }
  long refined_anchor = -1;                         // refine's last anchor (cells of the stretch) or -1
  MotionScanner::NewtonBounds refined_bounds;       // and its bounds
  std::optional<MotionScanner::Evaluation> last;   // the excluded stretch ending at u_end
  std::vector<AnchorBox> excluded_boxes;           // the anchor boxes it leaves (its start's, its excluded stretches')
};

}  // namespace

namespace {
thread_local bool status_only_now = false;
}
StatusOnlyCrossings::StatusOnlyCrossings() : previous_(status_only_now) { status_only_now = true; }
StatusOnlyCrossings::~StatusOnlyCrossings() { status_only_now = previous_; }
bool status_only_crossings() { return status_only_now; }
std::size_t& skipped_descriptions() { return thread_counter<struct SkippedDescriptionsTag>(); }

// A query's state is one block of a few kilobytes (the scanner's memos inline), made and freed
// for each query: above the C library's per-thread cache of small blocks, so each one went through
// its general allocator (≈ 5 000 instructions a query in glibc, with a consolidation of its fast
// bins). The last few freed blocks are kept per thread and handed to the next queries instead.
// The blocks are the global operator new's; one freed on another thread joins that thread's
// blocks; a thread's blocks are released at its exit (a block freed after that goes to the
// global operator delete).
struct CrossingQuery::State : CrossingRun {
  using CrossingRun::CrossingRun;

  static void* operator new(std::size_t size) {
    if (size == sizeof(State) && cspace::kept_runs())
      if (Block* kept = Blocks::take()) {
        ++cspace::kept_block_reuses();
        return kept;
      }
    return ::operator new(size);
  }
  static void operator delete(void* p, std::size_t size) noexcept {
    if (size == sizeof(State) && cspace::kept_runs() && Blocks::keep(static_cast<Block*>(p))) return;
    ::operator delete(p);
  }

 private:
  // a freed block's memory (no object lives in it while kept)
  struct Block {
    static void dispose(Block* p) { ::operator delete(p); }
  };
  using Blocks = KeptPerThread<Block, 4>;
};

CrossingQuery::CrossingQuery(const CSpace& space, const MotionPath& path, const CrossingOptions& options)
    : state_(std::make_unique<State>(space, path, options)) {}
CrossingQuery::CrossingQuery(CrossingQuery&&) noexcept = default;
CrossingQuery& CrossingQuery::operator=(CrossingQuery&&) noexcept = default;
CrossingQuery::~CrossingQuery() = default;
bool CrossingQuery::finished() const { return state_->finished(); }
const Rational& CrossingQuery::next() const { return state_->next(); }
void CrossingQuery::step() { state_->step(); }
void CrossingQuery::run(const Rational* stop) { state_->run(stop); }
MotionCrossing CrossingQuery::answer() const { return state_->answer(); }

MotionCrossing CSpace::first_crossing(const MotionPath& path, const CrossingOptions& options) const {
  CrossingRun query(*this, path, options);
  query.run(nullptr);
  return std::move(query).take_answer();
}

CrossingBefore first_crossing_before(const CSpace& space, const MotionPath& path, const CrossingOptions& options,
                                     const Rational& u_stop) {
  CrossingBefore answer;
  Rational stop = u_stop;
  stop.canonicalize();
  CrossingRun query(space, path, options);
  query.run(&stop);
  answer.stopped = !query.finished();
  answer.crossing = std::move(query).take_answer();
  return answer;
}

// ------------------------------------------------------------------ blocked walks

namespace {

// One axis of a configuration for certainly_blocked: the double enclosure of its chart
// coordinate t at u = u_begin (the certified angle filter on the exact path angle), when it lies
// in one chart system; nullopt otherwise (an axis that does not rotate, an angle near a seam,
// the filter undecided).
struct WalkAxis {
  bool half_turn = false;
  cspace::algebra::Interval t;
};

template <class Memo>
std::optional<WalkAxis> walk_axis(const AxisPath& axis, const Rational& u, Memo& memo) {
  if (axis.kind != AxisPath::Kind::angle) return std::nullopt;
  // the exact angle at u (at u = 0 the constant coefficient itself, not a copy)
  Rational value(0);
  const Rational* theta = &value;
  if (sgn(u) == 0) {
    if (!axis.coefficients.empty()) theta = &axis.coefficients.front();
  } else {
    for (std::size_t i = axis.coefficients.size(); i-- > 0;) value = value * u + axis.coefficients[i];
  }
  if (memo.set && memo.theta == *theta) return WalkAxis{memo.half_turn, {memo.lo, memo.hi}};
  std::optional<cspace::AngleRanges> ranges = cspace::filtered_angle_ranges(KInterval::enclose(*theta));
  if (!ranges || ranges->size != 1) return std::nullopt;
  memo.set = true;
  memo.half_turn = ranges->half_turn[0];
  memo.theta = *theta;
  memo.lo = ranges->lo[0];
  memo.hi = ranges->hi[0];
  return WalkAxis{memo.half_turn, {memo.lo, memo.hi}};
}

// No curve of chart c that can bound a cell (the scanner's carriers: those of the edges whose
// certified boxes meet x * y, and those through an isolated vertex) vanishes on x * y
// (outward-rounded interval evaluation).
bool no_boundary_on(const CSpace::Impl& impl, ScanMemo& memo, std::size_t c, const cspace::algebra::Interval& x,
                    const cspace::algebra::Interval& y) {
  auto vanishes = [&](std::size_t k) {
    cspace::algebra::Interval value = curve_enclosure(impl, memo, c, k).evaluate(x, y);
    return !std::isfinite(value.lo) || !std::isfinite(value.hi) || value.contains_zero();
  };
  const ScanMemo::ChartCarriers& known = chart_carriers(impl, memo, c);
  for (std::size_t k : known.everywhere)
    if (vanishes(k)) return false;
  for (const ScanMemo::Carrier& carrier : known.edges) {
    if (x.hi < carrier.box[0] || x.lo > carrier.box[2] || y.hi < carrier.box[1] || y.lo > carrier.box[3]) continue;
    for (std::size_t k : carrier.curves)
      if (vanishes(k)) return false;
  }
  return true;
}

}  // namespace

// See blocked_walk.hpp for the proof. Every point of contact space or of a boundary between
// two cells in the chart (a real edge, an edge between different cells, a vertex of one, an
// isolated vertex) lies on a curve that the scanner's carriers test where that point can be
// (the edge's certified box; an isolated vertex's curves everywhere): where none of them vanishes
// on the hull H, H meets no such point, and H (connected, strictly inside the chart) lies in
// one cell: the last box's. That is the test first_crossing's own exclusion makes (exclude).
bool certainly_blocked(const CSpace& space, const MotionPath& point, BlockedWalk& walk) {
  const CSpace::Impl& impl = checked(space);
  if (!cspace::blocked_walks() || walk.spent_) return false;
  walk.spent_ = true;   // until this call certifies the configuration
  if (impl.dimension != 2 || !impl.complete) return false;
  std::optional<WalkAxis> px = walk_axis(point.x, point.u_begin, walk.axes_[0]);
  if (!px) return false;
  std::optional<WalkAxis> py = walk_axis(point.y, point.u_begin, walk.axes_[1]);
  if (!py) return false;
  std::shared_ptr<ScanMemo> memo = scan_memo_of(CSpaceAccess::shared(space));
  if (walk.space_) {
    // the walk's next configuration: certified from the last box, or the walk ends
    const CSpaceChart& system = impl.public_charts[walk.chart_];
    if (walk.space_ != &impl || px->half_turn != system.x_half_turn || py->half_turn != system.y_half_turn) return false;
    if (!(px->t.lo > walk.side_[0] && px->t.hi < walk.side_[1] && py->t.lo > walk.side_[2] && py->t.hi < walk.side_[3]))
      return false;
    cspace::algebra::Interval x{std::min(walk.box_[0], px->t.lo), std::max(walk.box_[1], px->t.hi)};
    cspace::algebra::Interval y{std::min(walk.box_[2], py->t.lo), std::max(walk.box_[3], py->t.hi)};
    if (!no_boundary_on(impl, *memo, walk.chart_, x, y)) return false;
    ++cspace::blocked_walk_steps();
  } else {
    // the walk's first configuration: in the chart that holds its box strictly inside, where no
    // carrier vanishes on the box, located exactly (its rational midpoint)
    std::size_t chart = no_index;
    std::array<double, 4> side{};
    for (std::size_t c = 0; c < impl.charts.size() && chart == no_index; ++c) {
      const CSpaceChart& system = impl.public_charts[c];
      if (system.x_kind != AxisKind::rotation || system.y_kind != AxisKind::rotation ||
          system.x_half_turn != px->half_turn || system.y_half_turn != py->half_turn)
        continue;
      // the sides rounded inward: a double beyond one is beyond the side
      const cspace::raw::Box& box = impl.charts[c].box;
      side = {cspace::algebra::upper_double(box.x_lo), cspace::algebra::lower_double(box.x_hi),
              cspace::algebra::upper_double(box.y_lo), cspace::algebra::lower_double(box.y_hi)};
      if (px->t.lo > side[0] && px->t.hi < side[1] && py->t.lo > side[2] && py->t.hi < side[3]) chart = c;
    }
    if (chart == no_index || !no_boundary_on(impl, *memo, chart, px->t, py->t)) return false;
    Rational x = (Rational(px->t.lo) + Rational(px->t.hi)) / 2, y = (Rational(py->t.lo) + Rational(py->t.hi)) / 2;
    x.canonicalize();
    y.canonicalize();
    if (cspace::locate_point(impl, ChartPoint{chart, x, y}).kind != Location::Kind::blocked) return false;
    walk.space_ = &impl;
    walk.chart_ = chart;
    walk.side_ = side;
  }
  walk.box_ = {px->t.lo, px->t.hi, py->t.lo, py->t.hi};
  walk.spent_ = false;
  return true;
}

}  // namespace hipair
