// Hand-overs in an assembly chain's certified band (handover.hpp; docs/tolerance.md "Assembly
// chains", step 4, "Hand-overs").
//
// The argument. At a driver position, for a parameter vector p of the box (and a driver value t
// of its range), the follower is held at y(t, p) by a contact that pushes it: a feature pair
// touching there whose free side is the side the follower is free to move to. Let sigma be
// the holder's free side (the sign of its F_v over box x range x its enclosure Y, which
// certified_range has made certain). Every feature pair j pushing on the same side blocks the
// follower on the -sigma side of its root v_j (its features would penetrate there), so
// y(t, p) is on the sigma side of every such root, in particular of the holder's: y is never
// on the -sigma side of Y. It is one of them (the one pushing it), so
//   y(t, p) = the sigma-most of v_j(t, p) over the pushing feature pairs j,
// and its enclosure over the box is the holder's, widened on its sigma side to the
// sigma-most end of the candidates' enclosures (each candidate's enclosure holds its roots;
// a candidate whose roots lie certainly on the -sigma side of Y's sigma end changes nothing).
// The candidates are sought in a window W beyond Y's sigma end (of width 2 |Y| plus the
// absolute accuracy). y(t, p) is continuous on the connected (range x box) and equals the
// nominal follower (inside Y) at the nominal vector, so its image is an interval holding a point
// of Y; a value where the follower can be held is a zero of some feature pair's contact function
// that pushes it, that feature pair's edges meeting there. So if no feature pair has a pushing
// zero in a leaf (E, E + h] of W (E at or beyond Y's sigma end), y never passes E: E bounds the
// envelope, whatever the candidates do further on. So:
//   1. Edges: every edge of each part posed over box x range x W (outward-rounded intervals);
//      an edge pair certainly apart there (the verifier's separation test on two posed edges,
//      certify/tolerance_support.hpp, or their bounding discs apart) cannot touch in W. The
//      feature pairs of the others (curve / curve, each end vertex / the other curve) are the
//      candidates, with the holder.
//   2. Exclusion from a leaf y, over box x t x y for each piece t of the driver's range (halved
//      up to three times where undecided): the two features certainly apart; F_v certainly of
//      sign -sigma (a contact blocking the follower from ahead, the channel's other side: not a
//      push); F certainly non-zero (F as a first-order Taylor model in the box's parameters,
//      t and v: its range, met with the interval enclosure); F_v of sign sigma (F monotone in
//      v) and F certainly positive at y's -sigma end or negative at its sigma end; a clause of
//      the pair's validity certainly false (the contact point off a feature: the vertex outside
//      the arc's angular range, ...; kernels/contact.hpp, closed conditions every touching
//      meets); or its root over box x t (CurveSolver::certified_range; the holder's over the
//      whole range: Y) on the -sigma side of y (up to y's -sigma end) or beyond it, with F_v of
//      one sign over their hull (F monotone there, its one zero in the root's enclosure).
//      Where the chain gives the driver as the previous pair's mean-value form (DriverForm,
//      session 28), a candidate that these tests leave possible over the pieces of T is tried
//      again with the driver as that form: its terms in the parameters the two parts depend on
//      as the Taylor models' linear part (correlated with the parts' geometry), the rest (the
//      earlier pairs' parameters, the form's value and remainder) one more variable, whose
//      range is halved as T's; the driver's interval there is the form's range met with T.
//      Both hold the driver at every vector of the box, so an exclusion by either is sound.
//   3. The walk: E from Y's sigma end; the leaf [E, E + h] (h from |W| / 8 halved up to four
//      times) with no candidate pushing in it ends the walk at E; where one may push in the
//      finest leaf, E moves to its far end. E is the envelope's sigma end.
//   4. If E reaches W's far end, y could leave W: unbounded.
// Assumption (stated in docs/tolerance.md): quasi-static pushing, the follower held by a
// contact at every vector of the box, its position continuous in (driver, parameters), as the
// chain's kinematics assumes at nominal.
#include "tolerance/handover.hpp"

#include "certify/tolerance_support.hpp"
#include "kernels/contact_geometry.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/contact_function.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <tuple>

namespace hipair::tolerance_detail {

struct HandoverSearch::BoxParts {
  // over the box: each number's first-order Taylor model's range met with its plain enclosure
  model_detail::PartGeometry<Interval> fixed, free;
  // over the box: first-order Taylor models (taylor_model.hpp) in the box's parameters that
  // either part depends on (`variables` of them, numbered 0 ..; a parameter whose coefficients
  // are exactly 0 in every number of both parts is left out)
  model_detail::PartGeometry<TaylorModel1> fixed_taylor, free_taylor;
  std::size_t variables = 0;
  std::vector<std::size_t> parameter_of;   // the box's parameter of each variable
  bool taylor = false;   // the Taylor models could follow the construction over the box
  // per loop and edge: an arc certainly of at most a half turn (decided in the part's frame,
  // where the box alone blurs it: a rigid motion does not change it)
  std::vector<std::vector<char>> fixed_minor, free_minor;
};

namespace {

using V = kernels::Vector<Interval>;

int sign_of(const Interval& x) { return x.lo > 0 ? 1 : x.hi < 0 ? -1 : 0; }

// An edge posed over a region: the verifier's separation form and a bounding disc.
struct Posed {
  verify::EdgeT<Interval> edge;
  V disc_center;
  Interval disc_radius;
};

// Whether an arc is certainly at most a half turn: its centre certainly on the side of its chord
// away from the arc (the arc runs on the chord's right when ccw).
bool minor_arc(const model_detail::EdgeValue<Interval>& e) {
  if (!e.arc) return true;
  V d = e.target - e.source, cs = e.center - e.source;
  return sign_of(d.x * cs.y - d.y * cs.x) == (e.ccw ? 1 : -1);
}

Posed pose_edge(const model_detail::EdgeValue<Interval>& e, const kernels::Pose<Interval>& pose, bool minor) {
  using A = model_detail::Arithmetic<Interval>;
  Posed q;
  q.edge.arc = e.arc;
  q.edge.ccw = e.ccw;
  q.edge.s = kernels::world_point(pose, e.source);
  q.edge.t = kernels::world_point(pose, e.target);
  auto half = [](const V& a, const V& b) { return V{(a.x + b.x) * Interval(0.5, 0.5), (a.y + b.y) * Interval(0.5, 0.5)}; };
  V d = q.edge.t - q.edge.s;
  Interval chord = A::sqrt(d.x * d.x + d.y * d.y) * Interval(0.5, 0.5);
  q.disc_center = half(q.edge.s, q.edge.t);   // a segment, or an arc of at most a half turn: its Thales disc
  q.disc_radius = chord;
  if (e.arc) {
    q.edge.c = kernels::world_point(pose, e.center);
    q.edge.r2 = e.radius_squared;
    q.edge.r = A::sqrt(e.radius_squared);
    if (!minor) {
      q.disc_center = q.edge.c;   // the whole circle's disc
      q.disc_radius = q.edge.r;
    }
  }
  return q;
}

// A vertex as a degenerate segment (its separation tests hold for it: a point strictly on one
// side of a line, inside a disc or beyond an arc's chord).
Posed point(const V& p) {
  Posed q;
  q.edge.s = q.edge.t = p;
  q.disc_center = p;
  q.disc_radius = Interval(0);
  return q;
}

bool apart(const Posed& a, const Posed& b) {
  V d = a.disc_center - b.disc_center;
  Interval r = a.disc_radius + b.disc_radius;
  if (sign_of(d.x * d.x + d.y * d.y - r * r) > 0) return true;
  return verify::separated(a.edge, b.edge, [](const Interval& x) { return sign_of(x); });
}

// A point as a constant jet (every partial derivative 0).
template <class S>
kernels::Vector<Jet<S>> lift(const kernels::Vector<S>& p) {
  return {Jet<S>(p.x), Jet<S>(p.y)};
}

template <class S>
model_detail::EdgeValue<Jet<S>> lift(const model_detail::EdgeValue<S>& e) {
  model_detail::EdgeValue<Jet<S>> out;
  out.arc = e.arc;
  out.ccw = e.ccw;
  out.source = lift(e.source);
  out.target = lift(e.target);
  out.center = lift(e.center);
  out.radius_squared = Jet<S>(e.radius_squared);
  return out;
}

// x met with y where they meet (both enclose the same quantity; x where they do not, which
// outward rounding alone cannot cause)
Interval met(const Interval& x, const Interval& y) {
  Interval both(std::max(x.lo, y.lo), std::min(x.hi, y.hi));
  return both.lo <= both.hi ? both : x;
}

// An arc's angular range for the kernels' validity (curves/pose.cpp arc_sector); an arc not
// certainly of at most a half turn gets none (`full`: no requirement, never an exclusion).
template <class N>
kernels::ArcSector<N> sector_of(const model_detail::EdgeValue<N>& e, bool minor) {
  kernels::ArcSector<N> s;
  if (!minor) {
    s.full = true;
    return s;
  }
  kernels::Vector<N> from_source = e.source - e.center, from_target = e.target - e.center;
  s.start = e.ccw ? from_source : from_target;
  s.end = e.ccw ? from_target : from_source;
  return s;
}

// The validity of a feature pair's contact (kernels/contact.hpp: the contact point on both
// features; closed conditions, so every touching of the two features satisfies them), with
// the same dispatch as contact_function. Empty (always valid) where it has none.
template <class N>
kernels::Validity<N> validity_of(const model_detail::EdgeValue<N>& ea, const FeatureIdentity& fa, const kernels::Pose<N>& a,
                                 bool minor_a, const model_detail::EdgeValue<N>& eb, const FeatureIdentity& fb,
                                 const kernels::Pose<N>& b, bool minor_b) {
  using K = FeatureKind;
  if (fa.kind == K::vertex && fb.kind == K::segment) return kernels::vertex_segment_validity(a, ea.source, b, eb.source, eb.target);
  if (fa.kind == K::segment && fb.kind == K::vertex) return kernels::segment_vertex_validity(a, ea.source, ea.target, b, eb.source);
  if (fa.kind == K::vertex && fb.kind == K::arc) return kernels::vertex_arc_validity(a, ea.source, b, eb.center, sector_of(eb, minor_b));
  if (fa.kind == K::arc && fb.kind == K::vertex) return kernels::arc_vertex_validity(a, ea.center, sector_of(ea, minor_a), b, eb.source);
  if (fa.kind == K::arc && fb.kind == K::arc && (ea.ccw || eb.ccw)) {
    kernels::Tangency tangency = ea.ccw && eb.ccw ? kernels::Tangency::external
                                 : ea.ccw         ? kernels::Tangency::first_inside_second
                                                  : kernels::Tangency::second_inside_first;
    return kernels::arc_arc_validity(a, ea.center, sector_of(ea, minor_a), ea.radius_squared, b, eb.center,
                                     sector_of(eb, minor_b), eb.radius_squared, tangency);
  }
  if (fa.kind == K::arc && fb.kind == K::segment && ea.ccw)
    return kernels::arc_segment_validity(a, ea.center, sector_of(ea, minor_a), b, eb.source, eb.target);
  if (fa.kind == K::segment && fb.kind == K::arc && eb.ccw)
    return kernels::segment_arc_validity(a, ea.source, ea.target, b, eb.center, sector_of(eb, minor_b));
  return {};
}

double end_of(const Interval& y, int sigma) { return sigma > 0 ? y.hi : y.lo; }

// How deep in envelope calls this thread is (1: the composition's own envelope; more: a walk it
// makes of its own, the driver's pieces, the bridge, the driver-monotone route), for step 7.
thread_local int envelope_depth = 0;
struct EnvelopeDepth {
  int level;
  EnvelopeDepth() : level(++envelope_depth) {}
  ~EnvelopeDepth() { --envelope_depth; }
  EnvelopeDepth(const EnvelopeDepth&) = delete;
  EnvelopeDepth& operator=(const EnvelopeDepth&) = delete;
};

}  // namespace

HandoverSearch::HandoverSearch(std::shared_ptr<const CurveSolver> solver, std::size_t fixed_part, std::size_t free_part)
    : solver_(std::move(solver)), fixed_part_(fixed_part), free_part_(free_part) {}

// The two parts' geometry over the box as first-order Taylor models (constant, linear part in
// the box's parameters, remainder: the spur gear's construction in plain interval arithmetic
// over the box overestimates by millimetres, and a mean-value form with interval gradients by
// tenths), and as intervals: the models' ranges met with the plain enclosures. Memoised per box
// (the positions composing over the same box share it).
std::shared_ptr<const HandoverSearch::BoxParts> HandoverSearch::box_parts(const Box& box) const {
  std::vector<double> key = box.lo;
  key.insert(key.end(), box.hi.begin(), box.hi.end());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = memo_.find(key);
    if (it != memo_.end()) return it->second;
  }
  const std::size_t n = box.lo.size();
  std::vector<std::size_t> active;
  std::vector<Interval> whole(n);
  std::vector<TaylorModel1> models(n);
  for (std::size_t i = 0; i < n; ++i) {
    whole[i] = Interval(box.lo[i], box.hi[i]);
    if (box.hi[i] > box.lo[i]) {
      models[i] = TaylorModel1::over(box.lo[i], box.hi[i], active.size());
      active.push_back(i);
    } else {
      models[i] = TaylorModel1(Interval::point(box.lo[i]));
    }
  }
  const model_detail::ParametricModel& model = solver_->model();
  auto parts = std::make_shared<BoxParts>();
  parts->fixed = model.part_geometry(fixed_part_, whole);
  parts->free = model.part_geometry(free_part_, whole);
  try {
    parts->fixed_taylor = model.part_geometry(fixed_part_, models);
    parts->free_taylor = model.part_geometry(free_part_, models);
    parts->taylor = true;
  } catch (const NumericError&) {
  }
  auto numbers = [](auto& g, auto&& visit) {
    for (auto& loop : g.loops)
      for (auto& e : loop) {
        for (auto* v : {&e.source, &e.target, &e.center}) {
          visit(v->x);
          visit(v->y);
        }
        visit(e.radius_squared);
      }
    for (auto* v : {&g.pivot, &g.direction}) {
      visit(v->x);
      visit(v->y);
    }
  };
  if (parts->taylor) {
    // the variables: the active parameters either part depends on over the box
    std::vector<char> used(active.size(), 0);
    auto mark = [&](const TaylorModel1& x) {
      for (std::size_t a = 0; a < x.coefficients.size(); ++a)
        if (!(x.coefficients[a].lo == 0.0 && x.coefficients[a].hi == 0.0)) used[a] = 1;
    };
    numbers(parts->fixed_taylor, mark);
    numbers(parts->free_taylor, mark);
    std::vector<std::size_t> keep;
    for (std::size_t a = 0; a < active.size(); ++a)
      if (used[a]) keep.push_back(a);
    parts->variables = keep.size();
    for (std::size_t a : keep) parts->parameter_of.push_back(active[a]);
    auto compact = [&](TaylorModel1& x) {
      std::vector<Interval> coefficients(keep.size(), Interval(0));
      for (std::size_t b = 0; b < keep.size(); ++b)
        if (keep[b] < x.coefficients.size()) coefficients[b] = x.coefficients[keep[b]];
      x.coefficients = std::move(coefficients);
    };
    numbers(parts->fixed_taylor, compact);
    numbers(parts->free_taylor, compact);
    // the intervals: the models' ranges met with the plain enclosures
    auto meet = [&](model_detail::PartGeometry<Interval>& plain, model_detail::PartGeometry<TaylorModel1>& taylor) {
      std::vector<Interval*> p;
      std::vector<const TaylorModel1*> t;
      numbers(plain, [&](Interval& x) { p.push_back(&x); });
      numbers(taylor, [&](TaylorModel1& x) { t.push_back(&x); });
      for (std::size_t i = 0; i < p.size(); ++i) {
        Interval r = t[i]->range();
        Interval both(std::max(r.lo, p[i]->lo), std::min(r.hi, p[i]->hi));
        if (both.lo <= both.hi) *p[i] = both;
      }
    };
    meet(parts->fixed, parts->fixed_taylor);
    meet(parts->free, parts->free_taylor);
  }
  auto minors = [](const model_detail::PartGeometry<Interval>& g) {
    std::vector<std::vector<char>> out;
    for (const auto& loop : g.loops) {
      out.emplace_back();
      for (const auto& e : loop) out.back().push_back(minor_arc(e) ? 1 : 0);
    }
    return out;
  };
  parts->fixed_minor = minors(parts->fixed);
  parts->free_minor = minors(parts->free);
  std::lock_guard<std::mutex> lock(mutex_);
  if (memo_.size() >= max_box_parts) memo_.clear();
  return memo_.emplace(key, parts).first->second;
}

namespace {

// The key of an envelope's call (EnvelopeMemo): every argument, doubles by their bits.
EnvelopeMemo::Key envelope_key(const HandoverSearch* search, const CurveSlice& curve, const Box& box,
                               const Interval& holder, double relative_accuracy, double absolute_accuracy, int side,
                               const DriverForm* driver, bool monotone, double nominal_free) {
  std::vector<std::uint64_t> bits;
  bits.reserve(24 + 2 * box.lo.size() + (driver ? 2 * driver->gradient.size() : 0));
  auto number = [&bits](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    bits.push_back(b);
  };
  auto whole = [&bits](std::uint64_t x) { bits.push_back(x); };
  for (const FeatureIdentity* f : {&curve.first, &curve.second}) {
    whole(f->part);
    whole(f->loop);
    whole(f->edge);
    whole(static_cast<std::uint64_t>(f->kind));
  }
  whole(curve.fixed_part);
  whole(curve.free_part);
  whole(curve.fixed_half_turn);
  whole(curve.free_half_turn);
  whole(curve.fixed_range.has_value());
  if (curve.fixed_range) {
    number(curve.fixed_range->lo);
    number(curve.fixed_range->hi);
  }
  number(curve.fixed_spread);
  whole(box.lo.size());
  for (double x : box.lo) number(x);
  for (double x : box.hi) number(x);
  number(holder.lo);
  number(holder.hi);
  number(relative_accuracy);
  number(absolute_accuracy);
  whole(static_cast<std::uint64_t>(static_cast<std::int64_t>(side)));
  whole(monotone);
  number(nominal_free);
  whole(driver != nullptr);
  if (driver) {
    number(driver->value.lo);
    number(driver->value.hi);
    whole(driver->gradient.size());
    for (const Interval& g : driver->gradient) {
      number(g.lo);
      number(g.hi);
    }
  }
  return {search, std::move(bits), curve.fixed_value};
}

}  // namespace

// Steps 0-6 (walk_steps) and step 7 (driver_pieces), the former replayed from this position's
// EnvelopeMemo in the pass of the driver's pieces where the far walk's pass walked the same call.
HandoverEnvelope HandoverSearch::envelope(const CurveSlice& curve, const Box& box,
                                          const Interval& holder, double relative_accuracy,
                                          double absolute_accuracy, std::size_t& boxes, int side,
                                          const DriverForm* driver, bool monotone, double nominal_free) const {
  const EnvelopeDepth depth;
  if (disabled_) {
    HandoverEnvelope out;
    out.chart = holder;
    out.bounded = true;
    return out;
  }
  EnvelopeMemo* memo =
      depth.level == 1 && FarWalk::on() && handover_far_reuse() != 0 ? EnvelopeMemo::Scope::current() : nullptr;
  std::optional<EnvelopeMemo::Key> key;
  const EnvelopeMemo::Entry* walked = nullptr;
  if (memo) {
    key = envelope_key(this, curve, box, holder, relative_accuracy, absolute_accuracy, side, driver, monotone,
                       nominal_free);
    walked = memo->find(*key);
  }
  EnvelopeMemo::Entry made;
  if (walked) {
    boxes += walked->boxes;
    handover_envelopes_reused().fetch_add(1, std::memory_order_relaxed);
  } else {
    const std::size_t before = boxes;
    made.result = walk_steps(curve, box, holder, relative_accuracy, absolute_accuracy, boxes, side, driver, monotone,
                             nominal_free, made);
    made.boxes = boxes - before;
    walked = memo ? memo->store(std::move(*key), std::move(made)) : &made;
  }
  const HandoverEnvelope& out = walked->result;
  // 7. (driver_pieces) only while a FarWalk and a DriverPieces live (chain.cpp: a position unbounded
  // even with the far walk, composed once more), and only in the composition's own envelope (not in
  // the pieces', the bridge's or the route's walks: `depth`).
  if (!FarWalk::on() || !DriverPieces::on() || depth.level != 1 || handover_driver_pieces() <= 1) return out;
  // 7b. (session 55) An envelope bounded only widened, over a box and driver's range where step 7
  // applies: the walk over box x T sees every candidate's zeros over the whole of T, independently
  // of the follower's (the holder's enclosure Y over box x T spans T's sweep too), and where T's
  // sweep is wide those zero sets overlap into a wall the walk passes leaf by leaf (gear-train.json
  // at 1.7279 rad, mesh F:G: widened 0.325 chart units, 27 deg of gear G, beyond Y, while the exact
  // train over the box stays inside Y; docs/tolerance.md "The driver's range walked in pieces"). The
  // pieces' walk bounds the same follower over the same box x T (step 7's argument needs only the
  // box holding the nominal vector and T the nominal driver), so both ends bound it and the
  // envelope is their meet: the nearer sigma end.
  if (out.bounded) {
    if (!walked->widened || handover_widened_pieces() == 0 || (out.side != 1 && out.side != -1)) return out;
    const int sigma = out.side;
    std::optional<double> edge =
        driver_pieces(curve, box, holder, sigma, relative_accuracy, absolute_accuracy, boxes, nominal_free);
    if (!edge) return out;
    const double reached = end_of(out.chart, sigma), holder_end = end_of(holder, sigma);
    const double pieces_end = sigma > 0 ? std::max(holder_end, *edge) : std::min(holder_end, *edge);
    if (!(sigma > 0 ? pieces_end < reached : pieces_end > reached)) return out;
    HandoverEnvelope narrowed = out;
    narrowed.extended = pieces_end != holder_end;
    narrowed.chart = sigma > 0 ? Interval(out.chart.lo, pieces_end) : Interval(pieces_end, out.chart.hi);
    return narrowed;
  }
  if (!walked->pieces) return out;
  std::optional<double> edge =
      driver_pieces(curve, box, holder, walked->sigma, relative_accuracy, absolute_accuracy, boxes, nominal_free);
  if (!edge) return out;
  // bounded to the pieces' sigma-most end (walk_steps' bounded_to)
  const int sigma = walked->sigma;
  HandoverEnvelope pieces = out;
  pieces.why.clear();
  pieces.extended = *edge != end_of(holder, sigma);
  pieces.side = sigma;
  pieces.chart = sigma > 0 ? Interval(holder.lo, std::max(holder.hi, *edge)) : Interval(std::min(holder.lo, *edge), holder.hi);
  pieces.bounded = true;
  return pieces;
}

HandoverEnvelope HandoverSearch::walk_steps(const CurveSlice& curve, const Box& box, const Interval& holder,
                                            double relative_accuracy, double absolute_accuracy, std::size_t& boxes,
                                            int side, const DriverForm* driver, bool monotone, double nominal_free,
                                            EnvelopeMemo::Entry& entry) const {
  HandoverEnvelope out;
  out.chart = holder;
  const Model& m = solver_->nominal();
  std::shared_ptr<const BoxParts> parts = box_parts(box);
  const Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  auto half = [&](std::size_t part) { return part == fixed_part_ ? curve.fixed_half_turn : curve.free_half_turn; };
  auto geometry_of = [&](std::size_t part) -> const model_detail::PartGeometry<Interval>& {
    return part == fixed_part_ ? parts->fixed : parts->free;
  };
  auto minor_of = [&](const FeatureIdentity& f) {
    return (f.part == fixed_part_ ? parts->fixed_minor : parts->free_minor)[f.loop][f.edge] != 0;
  };
  auto centre = [](const Interval& x) {
    double c = x.middle();
    return c >= x.lo && c <= x.hi ? c : x.lo;
  };
  auto edge_of = [](const auto& g, const FeatureIdentity& f) -> const auto& { return g.loops.at(f.loop).at(f.edge); };
  // The candidate's two parts posed over box x t x y: as intervals with the follower's chart
  // coordinate an interval jet (F_v), and as Taylor models in the box's variables, t (variable
  // k) and v (variable k + 1).
  const std::size_t k = parts->variables;
  // (partials: 1, F's partial in v alone; 2, in v (0) and the driver's chart t (1))
  auto jet_pose = [&](std::size_t part, const Interval& t, const Interval& y, std::size_t partials) {
    const model_detail::PartGeometry<Interval>& g = geometry_of(part);
    IntervalJet chart = part != fixed_part_ ? IntervalJet::variable(y, 0, partials)
                        : partials == 2     ? IntervalJet::variable(t, 1, 2)
                                            : IntervalJet(t);
    return pose_of(m.parts[part].motion, lift(g.pivot), lift(g.direction), chart, half(part));
  };
  auto taylor_geometry = [&](std::size_t part) -> const model_detail::PartGeometry<TaylorModel1>& {
    return part == fixed_part_ ? parts->fixed_taylor : parts->free_taylor;
  };
  // The driver over a piece: its chart range (t) and its Taylor model (variable k, or the
  // driver's form: DriverForm, split_driver). A piece is a part of the driver's range T, or
  // with the form a part of its lumped term; `none`: the form's range misses T there (no
  // parameter vector of the box drives the pair from that piece).
  struct Driver {
    Interval t;
    TaylorModel1 model;
    bool none = false;
  };
  std::optional<DriverSplit> split;
  if (driver && parts->taylor && curve.fixed_range) {
    split = split_driver(*driver, box, parts->parameter_of);
    bool finite = std::isfinite(split->lumped.lo) && std::isfinite(split->lumped.hi);
    for (const Interval& a : split->coefficients) finite = finite && std::isfinite(a.lo) && std::isfinite(a.hi);
    if (!finite) split.reset();
  }
  auto plain_driver = [&](const Interval& t) { return Driver{t, TaylorModel1::over(t.lo, t.hi, k)}; };
  // `form`: the piece is one of the form's lumped term (else of T)
  auto driver_over = [&](const Interval& piece, bool form) {
    Driver d = plain_driver(piece);
    if (!form) return d;
    d.model = d.model + TaylorModel1(Interval(0), split->coefficients, Interval(0));
    Interval r = d.model.range();
    d.t = Interval(std::max(r.lo, fixed.lo), std::min(r.hi, fixed.hi));
    d.none = !(d.t.lo <= d.t.hi);
    return d;
  };
  auto taylor_pose = [&](std::size_t part, const Driver& t, const Interval& y) {
    const model_detail::PartGeometry<TaylorModel1>& g = taylor_geometry(part);
    TaylorModel1 chart = part == fixed_part_ ? t.model : TaylorModel1::over(y.lo, y.hi, k + 1);
    return pose_of(m.parts[part].motion, g.pivot, g.direction, chart, half(part));
  };
  // F of a feature pair over box x t x y (interval jets) and its partial derivatives there, in v
  // and (partials 2) in the driver's chart t. Where a partial's sign is not certain, it is met
  // with the same partial as a Taylor-model jet (session 48: the parts' first-order Taylor
  // models, t as in taylor_pose, v variable k + 1): over a 100-parameter box the interval jet
  // loses the parameters' correlation (a gear's module moves every flank of it together), and
  // the holder's free side, a candidate's F_v or F_t are then not certain where the Taylor
  // model's are.
  struct Partials {
    Interval f, f_v, f_t;
  };
  auto partials_of = [&](const CurveSlice& c, const Driver& t, const Interval& y, std::size_t partials) {
    IntervalJet plain = contact_function(lift(edge_of(geometry_of(c.first.part), c.first)), c.first,
                                         jet_pose(c.first.part, t.t, y, partials), lift(edge_of(geometry_of(c.second.part), c.second)),
                                         c.second, jet_pose(c.second.part, t.t, y, partials));
    Partials out{plain.value, plain.partial(0), plain.partial(1)};
    const bool undecided = sign_of(out.f_v) == 0 || (partials == 2 && sign_of(out.f_t) == 0);
    if (!undecided || !parts->taylor || handover_taylor_partials() == 0) return out;
    auto pose = [&](std::size_t part) {
      const model_detail::PartGeometry<TaylorModel1>& g = taylor_geometry(part);
      TaylorJet chart = part != fixed_part_ ? TaylorJet::variable(TaylorModel1::over(y.lo, y.hi, k + 1), 0, partials)
                        : partials == 2     ? TaylorJet::variable(t.model, 1, 2)
                                            : TaylorJet(t.model);
      return pose_of(m.parts[part].motion, lift(g.pivot), lift(g.direction), chart, half(part));
    };
    try {
      TaylorJet f = contact_function(lift(edge_of(taylor_geometry(c.first.part), c.first)), c.first, pose(c.first.part),
                                     lift(edge_of(taylor_geometry(c.second.part), c.second)), c.second, pose(c.second.part));
      out.f_v = met(out.f_v, f.partial(0).range());
      if (partials == 2) out.f_t = met(out.f_t, f.partial(1).range());
    } catch (const NumericError&) {
    }
    return out;
  };
  // F of a feature pair over box x t x y (its Taylor model's range met with the interval
  // enclosure) and F_v there.
  struct Value {
    Interval f, f_v;
  };
  auto contact = [&](const CurveSlice& c, const Driver& t, const Interval& y) {
    Partials plain = partials_of(c, t, y, 1);
    Value out{plain.f, plain.f_v};
    if (!parts->taylor) return out;
    try {
      out.f = met(out.f, contact_function(taylor_geometry(c.first.part), c.first, taylor_pose(c.first.part, t, y),
                                          taylor_geometry(c.second.part), c.second, taylor_pose(c.second.part, t, y))
                             .range());
    } catch (const NumericError&) {
    }
    return out;
  };
  // Whether the feature pair's contact point certainly lies off one of its features over
  // box x t x y (a clause of its validity certainly false: e.g. the vertex outside the arc's
  // angular range), so that no zero of F there is a touching of the features.
  auto off_features = [&](const CurveSlice& c, const Driver& t, const Interval& y) {
    auto false_clause = [&](const auto& validity, auto&& range) {
      for (const auto& clause : validity.clauses) {
        bool all = true;
        for (int j = 0; j < clause.count && all; ++j) all = sign_of(range(clause.atoms[static_cast<std::size_t>(j)])) < 0;
        if (all) return true;
      }
      return false;
    };
    auto pose = [&](std::size_t part) {
      return pose_of(m.parts[part].motion, geometry_of(part).pivot, geometry_of(part).direction,
                     part == fixed_part_ ? t.t : y, half(part));
    };
    if (false_clause(validity_of(edge_of(geometry_of(c.first.part), c.first), c.first, pose(c.first.part), minor_of(c.first),
                                 edge_of(geometry_of(c.second.part), c.second), c.second, pose(c.second.part), minor_of(c.second)),
                     [](const Interval& x) { return x; }))
      return true;
    if (!parts->taylor) return false;
    try {
      return false_clause(validity_of(edge_of(taylor_geometry(c.first.part), c.first), c.first, taylor_pose(c.first.part, t, y),
                                      minor_of(c.first), edge_of(taylor_geometry(c.second.part), c.second), c.second,
                                      taylor_pose(c.second.part, t, y), minor_of(c.second)),
                          [](const TaylorModel1& x) { return x.range(); });
    } catch (const NumericError&) {
      return false;
    }
  };
  // 0. The holder's free side: F_v's sign over box x T x Y, certain over each piece of T x Y
  // (each halved up to three times where undecided) and the same on all.
  auto slope_sign = [&](const Interval& t, const Interval& y, int depth, auto& self) -> int {
    int s = sign_of(partials_of(curve, plain_driver(t), y, 1).f_v);
    if (s != 0 || depth == 0) return s;
    double tm = centre(t), ym = centre(y);
    std::vector<Interval> ts{t}, ys{y};
    if (tm > t.lo && tm < t.hi) ts = {Interval(t.lo, tm), Interval(tm, t.hi)};
    if (ym > y.lo && ym < y.hi) ys = {Interval(y.lo, ym), Interval(ym, y.hi)};
    if (ts.size() == 1 && ys.size() == 1) return 0;
    int common = 2;
    for (const Interval& a : ts)
      for (const Interval& b : ys) {
        int piece = self(a, b, depth - 1, self);
        if (piece == 0 || (common != 2 && piece != common)) return 0;
        common = piece;
      }
    return common;
  };
  int sigma = side == 1 || side == -1 ? side : 0;   // the caller's proof, or ours
  if (sigma == 0) {
    try {
      sigma = slope_sign(fixed, holder, 3, slope_sign);
    } catch (const Error&) {
    }
  }
  if (sigma == 0) {
    out.why = "the holding feature pair's free side is not certain over the box";
    return out;
  }
  const double reach = 2 * holder.width() + absolute_accuracy + 1e-12 * (1 + std::fabs(holder.middle()));
  const double start = end_of(holder, sigma);
  // 0b. The anchor of a box away from the nominal vector (session 47, tol47c). The walk (3.)
  // needs one point of box x T where the follower is within the walk's start: a free leaf
  // (E, E + h] only says that y stays on one side of it over the connected box x T. With the
  // nominal vector in the box, the nominal configuration is that point (its follower at the
  // holder's root, in Y). A sub-box of the shared-parameter bisection, or a failure-split half
  // of an asymmetric box, need not hold it: its follower may be held by another feature pair
  // over the whole sub-box, entirely beyond a free leaf (tests/unit/
  // tolerance_chain_sub_box_anchor_test.cpp). There the bridge A x T_A is walked: A the box
  // from the nominal vector to the sub-box's point p_c nearest to it, T_A the hull of the
  // nominal driver and T; it holds the nominal configuration (its own anchor) and the point
  // q = (p_c, t(p_c)) (t(p_c) in T the actual driver at p_c: a point of box x T, and of the
  // graph of the actual driver over the box, which is what the walk sees where it uses the
  // driver's form), so the bridge's envelope end E_S bounds y(q). Then (after the walk)
  // E_S <= E anchors the walk; else the slab (E, E_S] must be free of every candidate over
  // box x T (y(q) is not in it, so y(q) <= E); else the walk goes on from E_S. No bridge (no
  // nominal root given, or its walk not bounded on the same side): no envelope.
  bool away = false;
  for (std::size_t q = 0; q < box.lo.size(); ++q) away = away || !(box.lo[q] <= 0.0 && 0.0 <= box.hi[q]);
  std::optional<double> bridge;
  if (away && handover_sub_box_anchor() != 0) {
    if (std::isfinite(nominal_free)) {
      try {
        CurveSlice at_nominal = curve;
        at_nominal.fixed_range.reset();
        double v = nominal_free, slope = 0;
        std::vector<double> s = solver_->sensitivities(at_nominal, v, &slope);
        Box a{box.lo, box.hi};
        for (std::size_t q = 0; q < box.lo.size(); ++q) {
          double c = std::min(std::max(0.0, box.lo[q]), box.hi[q]);
          a.lo[q] = std::min(0.0, c);
          a.hi[q] = std::max(0.0, c);
        }
        CurveSlice along = curve;
        double guess = v;
        if (curve.fixed_range) {
          const double t_nom = curve.fixed_value.get_d();
          along.fixed_range = kernels::hull(Interval::enclose(curve.fixed_value), fixed);
          along.fixed_spread = std::fabs(slope) * along.fixed_range->width();
          guess = v + slope * (centre(*along.fixed_range) - t_nom);
        }
        // (the bridge's sub-boxes not counted in `boxes`: the report's count stays the band's)
        std::size_t bridge_boxes = 0;
        Interval y_a = solver_->certified_range(along, a, guess, s, relative_accuracy, absolute_accuracy, bridge_boxes);
        HandoverEnvelope e = envelope(along, a, y_a, relative_accuracy, absolute_accuracy, bridge_boxes, 0, nullptr,
                                      monotone, nominal_free);
        if (e.bounded && e.side == sigma) bridge = end_of(e.chart, sigma);
      } catch (const Error&) {
      }
    }
    if (!bridge) {
      out.why = "the follower's position over a sub-box away from the nominal vector is not anchored (the walk from "
                "the nominal vector to it is not bounded)";
      return out;
    }
  }
  // the window reaches beyond the bridge's end (the walk may have to go on from there)
  const double far = bridge && (sigma > 0 ? *bridge + reach > start + reach : *bridge - reach < start - reach)
                         ? (sigma > 0 ? *bridge + reach : *bridge - reach)
                         : (sigma > 0 ? start + reach : start - reach);
  const Interval window = sigma > 0 ? Interval(start, far) : Interval(far, start);
  // 1. The edges over box x range x window.
  auto pose_part = [&](std::size_t part, const Interval& chart) {
    const model_detail::PartGeometry<Interval>& g = geometry_of(part);
    kernels::Pose<Interval> pose = pose_of(m.parts[part].motion, g.pivot, g.direction, chart, half(part));
    const auto& minor = part == fixed_part_ ? parts->fixed_minor : parts->free_minor;
    std::vector<std::vector<Posed>> loops;
    for (std::size_t l = 0; l < g.loops.size(); ++l) {
      loops.emplace_back();
      for (std::size_t e = 0; e < g.loops[l].size(); ++e) loops.back().push_back(pose_edge(g.loops[l][e], pose, minor[l][e]));
    }
    return loops;
  };
  const std::size_t first_part = curve.first.part, second_part = curve.second.part;
  // The feature pairs whose edges are not certainly apart with the follower over `range`.
  auto enumerate = [&](const Interval& range) {
    auto first_edges = pose_part(first_part, first_part == fixed_part_ ? fixed : range);
    auto second_edges = pose_part(second_part, second_part == fixed_part_ ? fixed : range);
    using Key = std::tuple<std::size_t, std::size_t, int, std::size_t, std::size_t, int>;
    std::set<Key> keys;
    auto kind = [](const model_detail::EdgeValue<Interval>& e) {
      return e.arc ? FeatureKind::arc : FeatureKind::segment;
    };
    for (std::size_t la = 0; la < first_edges.size(); ++la)
      for (std::size_t ea = 0; ea < first_edges[la].size(); ++ea)
        for (std::size_t lb = 0; lb < second_edges.size(); ++lb)
          for (std::size_t eb = 0; eb < second_edges[lb].size(); ++eb) {
            if (apart(first_edges[la][ea], second_edges[lb][eb])) continue;
            std::size_t na = (ea + 1) % first_edges[la].size(),
                        nb = (eb + 1) % second_edges[lb].size();
            int ka = static_cast<int>(kind(geometry_of(first_part).loops[la][ea]));
            int kb = static_cast<int>(kind(geometry_of(second_part).loops[lb][eb]));
            constexpr int vertex = static_cast<int>(FeatureKind::vertex);
            const Posed& a = first_edges[la][ea];
            const Posed& b = second_edges[lb][eb];
            keys.insert({la, ea, ka, lb, eb, kb});
            if (!apart(point(a.edge.s), b)) keys.insert({la, ea, vertex, lb, eb, kb});
            if (!apart(point(a.edge.t), b)) keys.insert({la, na, vertex, lb, eb, kb});
            if (!apart(a, point(b.edge.s))) keys.insert({la, ea, ka, lb, eb, vertex});
            if (!apart(a, point(b.edge.t))) keys.insert({la, ea, ka, lb, nb, vertex});
          }
    auto identity = [](std::size_t part, std::size_t loop, std::size_t edge, int kind) {
      FeatureIdentity f;
      f.part = part;
      f.loop = loop;
      f.edge = edge;
      f.kind = static_cast<FeatureKind>(kind);
      return f;
    };
    std::vector<CurveSlice> found;
    for (const Key& key : keys) {
      CurveSlice c = curve;
      c.first = identity(first_part, std::get<0>(key), std::get<1>(key), std::get<2>(key));
      c.second = identity(second_part, std::get<3>(key), std::get<4>(key), std::get<5>(key));
      found.push_back(c);
    }
    return found;
  };
  std::vector<CurveSlice> candidates = enumerate(window);
  out.candidates = candidates.size();
  // 2. Whether a candidate may push the follower somewhere in y.
  // The candidate's two features (an edge, or a vertex: its edge's source) posed with the
  // follower over y: certainly apart, they do not touch there.
  auto features_apart = [&](const CurveSlice& c, const Interval& y) {
    auto posed = [&](const FeatureIdentity& f) {
      const model_detail::PartGeometry<Interval>& g = geometry_of(f.part);
      kernels::Pose<Interval> pose = pose_of(m.parts[f.part].motion, g.pivot, g.direction, f.part == fixed_part_ ? fixed : y, half(f.part));
      const auto& e = g.loops.at(f.loop).at(f.edge);
      if (f.kind == FeatureKind::vertex) return point(kernels::world_point(pose, e.source));
      return pose_edge(e, pose, minor_of(f));
    };
    Posed a = posed(c.first), b = posed(c.second);
    if (apart(a, b)) return true;
    // Two arcs touch, interior to interior, where their circles are tangent: at c_a -+ r_a u
    // (u the unit vector between the centres). Neither point on arc a (both certainly beyond
    // its chord, a minor arc), or neither on arc b: no such touching (an end vertex's
    // touching is its vertex candidate's).
    if (c.first.kind == FeatureKind::arc && c.second.kind == FeatureKind::arc) {
      using A = model_detail::Arithmetic<Interval>;
      V d = b.edge.c - a.edge.c;
      Interval length = A::sqrt(d.x * d.x + d.y * d.y);
      if (!(length.lo > 0)) return false;
      V u{d.x / length, d.y / length};
      auto off_arc = [&](const Posed& e, bool minor) {
        if (!minor) return false;
        int arc_side = e.edge.ccw ? -1 : 1;
        V chord = e.edge.t - e.edge.s;
        for (int k : {1, -1}) {
          V q{e.edge.c.x + Interval(k) * e.edge.r * u.x - e.edge.s.x, e.edge.c.y + Interval(k) * e.edge.r * u.y - e.edge.s.y};
          if (sign_of(chord.x * q.y - chord.y * q.x) != -arc_side) return false;
        }
        return true;
      };
      if (off_arc(a, minor_of(c.first)) || off_arc(b, minor_of(c.second))) return true;
    }
    return false;
  };
  auto is_holder = [&](const CurveSlice& c) { return c.first == curve.first && c.second == curve.second; };
  // A candidate's root over box x t (t a piece of T; CurveSolver::certified_range about the
  // root Newton finds at nominal next to the first leaf that asks, moved along the driver by
  // its slope; the holder's over T: Y), computed once per piece: for every (p, t) there, F has
  // a zero in it.
  struct Nominal {
    bool tried = false, found = false;
    double v = 0, slope = 0;
    std::vector<double> s;
  };
  std::vector<Nominal> nominals(candidates.size());
  std::map<std::tuple<std::size_t, double, double>, std::optional<Interval>> roots;
  const double t_nominal = curve.fixed_value.get_d();
  auto root_of = [&](std::size_t i, const Interval& cut, bool form, const Interval& t, const Interval& y) -> std::optional<Interval> {
    const CurveSlice& c = candidates[i];
    const Interval& whole = form ? split->lumped : fixed;
    if (is_holder(c) && cut.lo == whole.lo && cut.hi == whole.hi) return holder;
    auto key = std::make_tuple(i, t.lo, t.hi);
    auto it = roots.find(key);
    if (it != roots.end()) return it->second;
    std::optional<Interval>& root = roots[key];
    Nominal& n = nominals[i];
    if (!n.tried) {
      n.tried = true;
      try {
        n.v = y.middle();
        n.s = solver_->sensitivities(c, n.v, &n.slope);
        n.found = true;
      } catch (const Error&) {
      }
    }
    if (!n.found) return root;
    CurveSlice piece = c;
    if (curve.fixed_range) {
      piece.fixed_range = t;
      piece.fixed_spread = std::fabs(n.slope) * t.width();
    }
    try {
      root = solver_->certified_range(piece, box, n.v + n.slope * (centre(t) - t_nominal), n.s, relative_accuracy,
                                      absolute_accuracy, boxes);
    } catch (const Error&) {
    }
    return root;
  };
  // Over box x t x y (t a piece of T, or of the form's lumped term).
  auto may_push_over = [&](std::size_t i, const Interval& piece, bool form, const Interval& y) {
    const CurveSlice& c = candidates[i];
    const Driver t = driver_over(piece, form);
    if (t.none) return false;
    Value f = contact(c, t, y);
    int slope = sign_of(f.f_v);
    if (slope == -sigma || sign_of(f.f) != 0) return false;
    // F monotone along y for each (p, t), increasing towards the sigma side: a zero in y only
    // where F <= 0 at y's -sigma end and >= 0 at its sigma end
    if (slope == sigma &&
        monotone_without_zero(sigma, y, [&](double v) { return sign_of(contact(c, t, Interval::point(v)).f); }))
      return false;
    if (off_features(c, t, y)) return false;
    // Its root R over the box on the -sigma side of y (touching y's -sigma end at most: a zero
    // there is the follower's position the walk has reached) or beyond y's sigma end, and F_v
    // of one sign over their hull: F is monotone there for each (p, t), its one zero in R.
    if (std::optional<Interval> r = root_of(i, piece, form, t.t, y)) {
      bool before = sigma > 0 ? r->hi <= y.lo : r->lo >= y.hi;
      bool after = sigma > 0 ? r->lo > y.hi : r->hi < y.lo;
      if ((before || after) && sign_of(contact(c, t, kernels::hull(*r, y)).f_v) != 0) return false;
    }
    return true;
  };
  // Over box x T x y: T (or the driver form's lumped term) halved where a piece is undecided,
  // at most `t_levels` times.
  constexpr int t_levels = 3;
  auto may_push_in = [&](std::size_t i, const Interval& t, bool form, const Interval& y, int level, auto& self) -> bool {
    if (!may_push_over(i, t, form, y)) return false;
    double mid = t.middle();
    if (level >= t_levels || !(mid > t.lo && mid < t.hi)) return true;
    return self(i, Interval(t.lo, mid), form, y, level + 1, self) || self(i, Interval(mid, t.hi), form, y, level + 1, self);
  };
  // Excluded by either driver (both hold the actual driver for every vector of the box): first
  // the interval T, then the form's pieces where T's pieces left the candidate possible.
  auto may_push = [&](std::size_t i, const Interval& y) {
    try {
      if (features_apart(candidates[i], y)) return false;
      if (!may_push_in(i, fixed, false, y, 0, may_push_in)) return false;
      return !split || may_push_in(i, split->lumped, true, y, 0, may_push_in);
    } catch (const GeometryError&) {
      // no contact of its own (a concave arc on a segment, two vertices): its touchings are its
      // vertex candidates'
      return false;
    }
  };
  // 3. The walk: from Y's sigma end E, a leaf [E, E + h] of W (sigma-wards) where no candidate
  // may push bounds the follower at E; a leaf where one may (at the finest size) moves E to its
  // far end.
  constexpr int levels = 4;   // a leaf is W / 8 halved at most this many times
  WindowWalk walk = walk_window(start, window, sigma, reach / 8, levels, candidates.size(), may_push);
  // 0b. (above) A box away from the nominal vector: the walk's free leaf anchored by the
  // bridge's end E_S, by the slab (E, E_S] free over box x T, or the walk goes on from E_S.
  if (bridge && walk.bounded && (sigma > 0 ? walk.edge < *bridge : walk.edge > *bridge)) {
    auto free_over = [&](const Interval& y, int depth, auto& self) -> bool {
      bool none = true;
      for (std::size_t i = 0; i < candidates.size() && none; ++i) none = !may_push(i, y);
      if (none) return true;
      double mid = y.middle();
      if (depth == 0 || !(mid > y.lo && mid < y.hi)) return false;
      return self(Interval(y.lo, mid), depth - 1, self) && self(Interval(mid, y.hi), depth - 1, self);
    };
    // in pieces of the walk's coarse leaf (reach / 8), each halved up to `levels` times
    bool slab = true;
    const double coarse = reach / 8;
    for (double from = walk.edge; slab && (sigma > 0 ? from < *bridge : from > *bridge);) {
      double to = sigma > 0 ? std::min(from + coarse, *bridge) : std::max(from - coarse, *bridge);
      if (to == from) break;
      slab = free_over(sigma > 0 ? Interval(from, to) : Interval(to, from), levels, free_over);
      from = to;
    }
    if (!slab) walk = walk_window(*bridge, window, sigma, coarse, levels, candidates.size(), may_push);
  }
  const double edge_reached = walk.edge;
  // The envelope that ends at `edge` on the holder's sigma side (the walk's end or the driver-monotone
  // route's).
  auto bounded_to = [&](double edge) {
    out.extended = edge != start;
    out.side = sigma;
    // 7b. (the pieces) whether they may narrow a widened envelope here
    entry.sigma = sigma;
    entry.widened = out.extended && curve.fixed_range && fixed.lo < fixed.hi && !away && std::isfinite(nominal_free);
    out.chart = sigma > 0 ? Interval(holder.lo, std::max(holder.hi, edge))
                          : Interval(std::min(holder.lo, edge), holder.hi);
    out.bounded = true;
    return out;
  };
  const std::size_t last = walk.last;
  const bool bounded = walk.bounded;
  const std::vector<char>& occupying = walk.occupying;
  out.occupying = static_cast<std::size_t>(std::count(occupying.begin(), occupying.end(), 1));
  // 5. The driver-monotone route (session 47), where the walk over box x T is not bounded and
  // the box holds the nominal vector (p = 0). Let s_t be the sign of the holder's F_t over
  // box x T x Y (certain, else no route) and T_e the end of T where the follower is furthest
  // sigma-wards if it moves as the holder does (T.hi when s_t < 0, else T.lo). M: the window's
  // far end.
  //   (a) Every feature pair whose edges may meet with the follower in [Y, M) (sigma-wards from
  //       Y's -sigma end) is, over box x T x each leaf there, either unable to push (features
  //       apart, F_v certainly -sigma, F certainly non-zero, a validity clause certainly false,
  //       F monotone without a zero) or of F_t certainly of sign s_t. Under the chain's
  //       assumption (the follower at the sigma-most root of the pushing feature pairs,
  //       continuous in t), each pushing root then moves with t in the holder's sense
  //       (dv/dt = -F_t/F_v, F_v of sign sigma), so does their sigma-most one: for each p, y(p, .)
  //       is monotone, sigma-wards towards T_e, on every t-interval where y stays in [Y, M).
  //   (b) The walk over {0} x hull(t_nominal, T_e) (a connected set holding the nominal vector,
  //       where the follower is at its holder, in Y) bounds y there by E_2.
  //   (c) The walk over box x {T_e}, started at E_2 (the point (0, T_e), in both sets, has its
  //       follower within E_2), bounds y(p, T_e) by E_1 for every p of the box; E_1 < M.
  //   Then for every p and t of T: y(p, t) is within E_1 (if y(p, t) were beyond it, take the
  //   last t' between t and T_e where y reaches M, or t itself: on (t', T_e] y stays in [Y, M),
  //   so it moves monotonically towards T_e, and by continuity y(p, t') <= y(p, T_e) <= E_1,
  //   against the choice of t'). So E_1 bounds the envelope over the whole box x T. The walks
  //   (b) and (c) see a point driver or a point box: far thinner than box x T.
  if (!bounded && monotone && curve.fixed_range && fixed.lo < fixed.hi &&
      handover_monotone_driver() != 0 && !disabled_) {
    bool nominal_inside = true;
    for (std::size_t q = 0; q < box.lo.size(); ++q)
      nominal_inside = nominal_inside && box.lo[q] <= 0.0 && 0.0 <= box.hi[q];
    int s_t = 0;
    if (nominal_inside) {
      try {
        s_t = sign_of(partials_of(curve, plain_driver(fixed), holder, 2).f_t);
      } catch (const Error&) {
      }
    }
    Interval region = sigma > 0 ? Interval(holder.lo, window.hi) : Interval(window.lo, holder.hi);
    double edge = start;
    bool route = s_t != 0;
    if (route) {
      // (b) and (c)
      const double t_end = s_t < 0 ? fixed.hi : fixed.lo;
      CurveSlice along = curve;
      along.fixed_range =
          kernels::hull(Interval::enclose(curve.fixed_value), Interval::point(t_end));
      Box nominal_box{std::vector<double>(box.lo.size(), 0.0),
                      std::vector<double>(box.lo.size(), 0.0)};
      HandoverEnvelope e2 = envelope(along, nominal_box, holder, relative_accuracy,
                                     absolute_accuracy, boxes, sigma, nullptr, false);
      route = e2.bounded;
      if (route) {
        double anchor = end_of(e2.chart, sigma);
        CurveSlice at_end = curve;
        at_end.fixed_range = Interval::point(t_end);
        Interval from = sigma > 0 ? Interval(holder.lo, std::max(holder.hi, anchor))
                                  : Interval(std::min(holder.lo, anchor), holder.hi);
        HandoverEnvelope e1 = envelope(at_end, box, from, relative_accuracy, absolute_accuracy,
                                       boxes, sigma, nullptr, false);
        route = e1.bounded;
        edge = end_of(e1.chart, sigma);
        route = route && (sigma > 0 ? edge < region.hi : edge > region.lo);
        // M: any value beyond E_1 will do; the nearer, the fewer feature pairs (a) must settle
        // (a tooth space further on, the teeth's geometry is another)
        if (route) {
          double margin = reach / 128;
          region = sigma > 0 ? Interval(holder.lo, std::min(region.hi, edge + margin))
                             : Interval(std::max(region.lo, edge - margin), holder.hi);
          route = sigma > 0 ? edge < region.hi : edge > region.lo;
        }
      }
    }
    if (route) {
      // (a), over box x T x [Y, M): a leaf not settled is halved along t or y, whichever moves F
      // more over it (|F_t| |t| against |F_v| |y|), up to `depth` times
      struct Settled {
        bool done = false;
        double t_share = 0, y_share = 0;
      };
      auto settled = [&](const CurveSlice& c, const Interval& t, const Interval& y) {
        Settled out;
        const Driver d = plain_driver(t);
        Value f = contact(c, d, y);
        int slope = sign_of(f.f_v);
        out.done = slope == -sigma || sign_of(f.f) != 0 ||
                   (slope == sigma &&
                    monotone_without_zero(
                        sigma, y,
                        [&](double v) { return sign_of(contact(c, d, Interval::point(v)).f); })) ||
                   off_features(c, d, y);
        if (out.done) return out;
        Interval f_t = partials_of(c, d, y, 2).f_t;
        out.done = sign_of(f_t) == s_t;
        auto magnitude = [](const Interval& x) {
          return std::max(std::fabs(x.lo), std::fabs(x.hi));
        };
        out.t_share = magnitude(f_t) * t.width();
        out.y_share = magnitude(f.f_v) * y.width();
        return out;
      };
      auto certify = [&](const CurveSlice& c, const Interval& t, const Interval& y, int depth,
                         auto& self) -> bool {
        Settled here;
        try {
          if (features_apart(c, y)) return true;
          here = settled(c, t, y);
          if (here.done) return true;
        } catch (const GeometryError&) {
          return true;  // no contact of its own (its touchings are its vertex candidates')
        } catch (const Error&) {
        }
        if (depth == 0) return false;
        double ym = y.middle(), tm = t.middle();
        bool can_y = ym > y.lo && ym<y.hi, can_t = tm> t.lo && tm < t.hi;
        if (can_t && (!can_y || here.t_share >= here.y_share))
          return self(c, Interval(t.lo, tm), y, depth - 1, self) &&
                 self(c, Interval(tm, t.hi), y, depth - 1, self);
        if (can_y)
          return self(c, t, Interval(y.lo, ym), depth - 1, self) &&
                 self(c, t, Interval(ym, y.hi), depth - 1, self);
        return false;
      };
      // T' from T_e's end: the whole of T, else T less its last 1/16, 1/8, 1/4 or 1/2 (the part
      // furthest from T_e), where the rest T'' is walked over box x T'' from E_1 (its follower
      // at t = T'' 's end in T' is within E_1 for every p: a point of the connected box x T''
      // whose follower is within the walk's start)
      const std::vector<CurveSlice> settling = enumerate(region);
      auto certified_over = [&](const Interval& t) {
        for (const CurveSlice& c : settling)
          if (!certify(c, t, region, 12, certify)) {
            return false;
          }
        return true;
      };
      route = false;
      const bool at_lo = s_t > 0;  // T_e = T.lo
      for (int j : {0, 4, 3, 2, 1}) {
        double cut = j == 0 ? (at_lo ? fixed.hi : fixed.lo)
                            : (at_lo ? fixed.hi - std::ldexp(fixed.width(), -j)
                                     : fixed.lo + std::ldexp(fixed.width(), -j));
        if (!(cut > fixed.lo && cut < fixed.hi) && j != 0) continue;
        Interval near = at_lo ? Interval(fixed.lo, cut) : Interval(cut, fixed.hi);
        if (!certified_over(near)) continue;
        if (j == 0) {
          route = true;
          break;
        }
        CurveSlice rest = curve;
        rest.fixed_range = at_lo ? Interval(cut, fixed.hi) : Interval(fixed.lo, cut);
        Interval from = sigma > 0 ? Interval(holder.lo, std::max(holder.hi, edge))
                                  : Interval(std::min(holder.lo, edge), holder.hi);
        HandoverEnvelope e3 = envelope(rest, box, from, relative_accuracy, absolute_accuracy, boxes,
                                       sigma, nullptr, false);
        if (e3.bounded) {
          edge = end_of(e3.chart, sigma);
          route = true;
        }
        break;
      }
    }
    if (route) return bounded_to(edge);
  }
  // 6. The walk carried on beyond the window (session 49), where neither the walk over the
  // window nor the driver-monotone route bounded the envelope (the walk stopped a leaf short of
  // the window's far end, every leaf it passed possibly pushed in): a candidate that really takes
  // over inside the box (a tooth pair handing over) may hold the follower further than the window
  // reaches, and the honest envelope then covers both holders. The walk goes on from where it
  // stopped over `handover_far_windows()` - 1 more windows' widths, the candidates enumerated
  // over the whole of it (their edges posed over the wider range), its leaves from the coarse
  // size again: a free leaf there bounds y as in 3. (the walk is one walk from Y's sigma end,
  // its leaves consecutive). Only while a FarWalk lives (chain.cpp: a position whose band is
  // unbounded without it, composed again), so that every band bounded without it stays as it was.
  std::size_t stuck = last;
  if (!bounded && handover_far_windows() > 1 && FarWalk::on()) {
    const double further = static_cast<double>(handover_far_windows() - 1) * reach;
    const Interval wide = sigma > 0 ? Interval(window.lo, window.hi + further) : Interval(window.lo - further, window.hi);
    candidates = enumerate(wide);
    nominals.assign(candidates.size(), Nominal{});
    roots.clear();
    WindowWalk more = walk_window(walk.edge, wide, sigma, reach / 8, levels, candidates.size(), may_push);
    if (more.bounded) return bounded_to(more.edge);
    stuck = more.last;
  }
  // 7. (driver_pieces) where the envelope is still not bounded: whether it applies here
  entry.sigma = sigma;
  entry.pieces = !bounded && curve.fixed_range && fixed.lo < fixed.hi && !away && std::isfinite(nominal_free);
  if (!bounded) {
    auto name = [&](const FeatureIdentity& f) {
      const Part& part = m.parts[f.part];
      std::string edge = part.loops.at(f.loop).edges.at(f.edge).label;
      if (edge.empty()) edge = "loop " + std::to_string(f.loop) + " edge " + std::to_string(f.edge);
      return part.name + " " + (f.kind == FeatureKind::vertex ? "vertex of " : "") + edge;
    };
    const CurveSlice& c = candidates[std::min(stuck, candidates.size() - 1)];
    out.why = "a feature pair other than the holding one may hold the follower further than the search reaches (" +
              name(c.first) + " / " + name(c.second) + ")";
    return out;
  }
  return bounded_to(edge_reached);
}

// 7. The driver's range walked in pieces (session 52; envelope), where neither the walk over
// box x T, the driver-monotone route nor the far walk bounded the envelope, the box holds the nominal vector
// and T the nominal driver t_n: where T is wider than the teeth's pitch, the next tooth pair
// really may hold the follower inside box x T and its zeros over the whole of T sweep every
// leaf. T is split into n equal pieces T_0 .. T_n-1 (adjacent pieces share their double end
// t_b), and the pieces are walked outward from the one holding t_n, each over box x T_j alone
// (an interval driver: the driver's form holds the actual driver on its graph over the box,
// which a piece of T does not leave connected):
//   - the piece T_c holding t_n: the nominal configuration (0, t_n) lies in box x T_c, its
//     follower at the holder's root, in Y_c (the holder's enclosure over box x T_c): the walk
//     from Y_c's sigma end is anchored as in 3., and ends at E_c;
//   - a piece T_j next to an already walked T_i (outward): every point (p, t_b) of box x {t_b}
//     lies in box x T_i, so y(p, t_b) is within E_i; the walk over box x T_j started at the
//     sigma end of hull(Y_j, E_i) has that anchor, and ends at E_j.
// For every p and t of T, y(p, t) lies in some piece's envelope [Y_j's -sigma end, E_j], so the
// envelope is the holder's enclosure Y widened to the sigma-most E_j (its -sigma end stays Y's:
// the follower is never on the -sigma side of the holder's root). Each piece's competitor zeros
// sweep a fraction of the window. n = 4, 8, ... up to handover_driver_pieces(); a piece not
// bounded ends that n. Called only while a FarWalk and a DriverPieces live, in the composition's
// own envelope, where steps 0-6 left it unbounded over a box holding the nominal vector.
std::optional<double> HandoverSearch::driver_pieces(const CurveSlice& curve, const Box& box, const Interval& holder,
                                                    int sigma, double relative_accuracy, double absolute_accuracy,
                                                    std::size_t& boxes, double nominal_free) const {
  const Interval fixed = *curve.fixed_range;
  auto centre = [](const Interval& x) {
    double c = x.middle();
    return c >= x.lo && c <= x.hi ? c : x.lo;
  };
  const double t_n = curve.fixed_value.get_d();
  std::vector<double> s;
  double slope = 0;
  bool anchored = t_n >= fixed.lo && t_n <= fixed.hi;
  if (anchored) {
    try {
      CurveSlice at_nominal = curve;
      at_nominal.fixed_range.reset();
      double v = nominal_free;
      s = solver_->sensitivities(at_nominal, v, &slope);
    } catch (const Error&) {
      anchored = false;
    }
  }
  for (int n = 4; anchored && n <= handover_driver_pieces(); n *= 2) {
    std::vector<double> ends(static_cast<std::size_t>(n) + 1);
    for (int j = 0; j <= n; ++j)
      ends[static_cast<std::size_t>(j)] =
          j == n ? fixed.hi : std::max(fixed.lo, fixed.lo + fixed.width() * static_cast<double>(j) / static_cast<double>(n));
    for (std::size_t j = 1; j < ends.size(); ++j) ends[j] = std::max(ends[j], ends[j - 1]);
    std::size_t c = 0;
    while (c + 1 < static_cast<std::size_t>(n) && !(t_n <= ends[c + 1])) ++c;
    // the walk over box x T_j from the sigma end of hull(Y_j, previous): its envelope's sigma end
    auto piece_walk = [&](std::size_t j, std::optional<double> previous) -> std::optional<double> {
      CurveSlice piece = curve;
      piece.fixed_range = Interval(ends[j], ends[j + 1]);
      piece.fixed_spread = std::fabs(slope) * piece.fixed_range->width();
      // Y_j: certified about the nominal root moved along the driver, as Y is, and met with Y
      // (which holds the holder's root over box x T, so over box x T_j); Y itself where the two
      // do not meet, or where T_c's would not hold the nominal follower (the anchor of T_c)
      Interval y = holder;
      try {
        Interval own = solver_->certified_range(piece, box, nominal_free + slope * (centre(*piece.fixed_range) - t_n), s,
                                                relative_accuracy, absolute_accuracy, boxes);
        Interval both(std::max(own.lo, holder.lo), std::min(own.hi, holder.hi));
        if (both.lo <= both.hi && (previous || (both.lo < nominal_free && nominal_free < both.hi))) y = both;
      } catch (const Error&) {
      }
      if (previous) y = kernels::hull(y, Interval::point(*previous));
      try {
        HandoverEnvelope e = envelope(piece, box, y, relative_accuracy, absolute_accuracy, boxes, sigma, nullptr,
                                      false, nominal_free);
        if (e.bounded && e.side == sigma) return end_of(e.chart, sigma);
      } catch (const Error&) {
      }
      return std::nullopt;
    };
    std::optional<double> centre_edge = piece_walk(c, std::nullopt);
    if (!centre_edge) continue;
    double reached = *centre_edge;
    bool all = true;
    for (int direction : {1, -1}) {
      std::optional<double> previous = centre_edge;
      for (std::size_t j = c; all;) {
        if (direction > 0 ? j + 1 >= static_cast<std::size_t>(n) : j == 0) break;
        j = direction > 0 ? j + 1 : j - 1;
        previous = piece_walk(j, previous);
        if (!previous) {
          all = false;
          break;
        }
        reached = sigma > 0 ? std::max(reached, *previous) : std::min(reached, *previous);
      }
    }
    if (all) return reached;
  }
  return std::nullopt;
}

int& handover_monotone_driver() {
  static int on = 1;
  return on;
}

int& handover_sub_box_anchor() {
  static int on = 1;
  return on;
}

int& handover_far_windows() {
  static int windows = 2;
  return windows;
}

int& handover_driver_pieces() {
  static int pieces = 16;
  return pieces;
}

int& handover_taylor_partials() {
  static int on = 1;
  return on;
}

int& handover_widened_pieces() {
  static int on = 1;
  return on;
}

int& handover_far_reuse() {
  static int on = 1;
  return on;
}

std::atomic<std::size_t>& handover_envelopes_reused() {
  static std::atomic<std::size_t> count{0};
  return count;
}

}  // namespace hipair::tolerance_detail
