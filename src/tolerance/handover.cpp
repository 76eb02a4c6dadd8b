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
// absolute accuracy): y(t, p), a continuous function on the connected (range x box) equal to
// the nominal follower (inside Y) at the nominal vector, can only leave Y's sigma end through
// W; a position of W where the follower can be held is a zero of some feature pair's contact
// function, that feature pair's edges meeting there. So:
//   1. Edges: every edge of each part posed over box x range x W (outward-rounded intervals);
//      an edge pair certainly apart there (the verifier's separation test on two posed edges,
//      certify/tolerance_support.hpp, or their bounding discs apart) cannot touch in W. The
//      feature pairs of the others (curve / curve, each end vertex / the other curve) are the
//      candidates, with the holder.
//   2. Exclusion: a candidate's contact function certainly non-zero over box x range x a piece
//      of W, or its F_v certainly of sign -sigma there (a contact blocking the follower from
//      ahead, the channel's other side: not a push), has no pushing zero in that piece; a
//      candidate with none in any piece is excluded.
//   3. Enclosure: the others' roots enclosed over the box (CurveSolver::certified_range, from
//      the root Newton finds in the first piece left), and beyond that enclosure no pushing
//      zero in W (F_v of sign sigma over the enclosure and beyond: one zero; or the pieces
//      beyond tested as in 2); where it cannot be enclosed, the pieces of W bisected (six
//      times) and the sigma-most piece left is the candidate's end. Both sound.
//   4. The envelope reaches the sigma-most candidate end; if that comes within an eighth of
//      W's far end, y could leave W: unbounded.
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
#include <optional>
#include <set>
#include <tuple>

namespace hipair::tolerance_detail {

struct HandoverSearch::BoxParts {
  model_detail::PartGeometry<Interval> fixed, free;
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

model_detail::EdgeValue<IntervalJet> lift(const model_detail::EdgeValue<Interval>& e) {
  auto v = [](const V& p) { return kernels::Vector<IntervalJet>{IntervalJet(p.x), IntervalJet(p.y)}; };
  model_detail::EdgeValue<IntervalJet> out;
  out.arc = e.arc;
  out.ccw = e.ccw;
  out.source = v(e.source);
  out.target = v(e.target);
  out.center = v(e.center);
  out.radius_squared = IntervalJet(e.radius_squared);
  return out;
}

double end_of(const Interval& y, int sigma) { return sigma > 0 ? y.hi : y.lo; }
// The sigma-most of two values.
double further(double a, double b, int sigma) { return sigma > 0 ? std::max(a, b) : std::min(a, b); }

}  // namespace

HandoverSearch::HandoverSearch(std::shared_ptr<const CurveSolver> solver, std::size_t fixed_part, std::size_t free_part)
    : solver_(std::move(solver)), fixed_part_(fixed_part), free_part_(free_part) {}

// The two parts' geometry over the box, each number in mean-value form (its value at the box's
// centre plus its gradient over the box times the box's offsets: the spur gear's construction
// in plain interval arithmetic over the box overestimates by millimetres), intersected with
// the plain enclosure. Memoised per box (the positions composing over the same box share it).
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
  for (std::size_t i = 0; i < n; ++i)
    if (box.hi[i] > box.lo[i]) active.push_back(i);
  std::vector<Interval> whole(n), center(n), offsets;
  std::vector<IntervalJet> jets(n);
  for (std::size_t i = 0; i < n; ++i) {
    whole[i] = Interval(box.lo[i], box.hi[i]);
    double c = 0.5 * (box.lo[i] + box.hi[i]);
    center[i] = Interval::point(c);
    jets[i] = IntervalJet(box.hi[i] > box.lo[i] ? whole[i] : Interval::point(box.lo[i]));
  }
  for (std::size_t a = 0; a < active.size(); ++a) {
    std::size_t i = active[a];
    jets[i] = IntervalJet::variable(whole[i], a, active.size());
    offsets.push_back(Interval::point(box.lo[i]) - center[i] + Interval(0, box.hi[i] - box.lo[i]));
  }
  auto form = [&](const IntervalJet& over, const Interval& at, const Interval& plain) {
    Interval v = at;
    for (std::size_t a = 0; a < active.size(); ++a) v = v + over.partial(a) * offsets[a];
    Interval r(std::max(v.lo, plain.lo), std::min(v.hi, plain.hi));
    return r.lo <= r.hi ? r : plain;
  };
  auto vector = [&](const kernels::Vector<IntervalJet>& over, const V& at, const V& plain) {
    return V{form(over.x, at.x, plain.x), form(over.y, at.y, plain.y)};
  };
  auto part = [&](std::size_t k) {
    const model_detail::ParametricModel& model = solver_->model();
    model_detail::PartGeometry<Interval> plain = model.part_geometry(k, whole);
    model_detail::PartGeometry<Interval> at = model.part_geometry(k, center);
    model_detail::PartGeometry<IntervalJet> over = model.part_geometry(k, jets);
    for (std::size_t l = 0; l < plain.loops.size(); ++l)
      for (std::size_t e = 0; e < plain.loops[l].size(); ++e) {
        auto& p = plain.loops[l][e];
        const auto& a = at.loops[l][e];
        const auto& o = over.loops[l][e];
        p.source = vector(o.source, a.source, p.source);
        p.target = vector(o.target, a.target, p.target);
        p.center = vector(o.center, a.center, p.center);
        p.radius_squared = form(o.radius_squared, a.radius_squared, p.radius_squared);
      }
    plain.pivot = vector(over.pivot, at.pivot, plain.pivot);
    plain.direction = vector(over.direction, at.direction, plain.direction);
    return plain;
  };
  auto parts = std::make_shared<BoxParts>();
  parts->fixed = part(fixed_part_);
  parts->free = part(free_part_);
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
  if (memo_.size() >= 256) memo_.clear();
  return memo_.emplace(key, parts).first->second;
}

HandoverEnvelope HandoverSearch::envelope(const CurveSlice& curve, const Box& box, const Interval& holder,
                                          double relative_accuracy, double absolute_accuracy, std::size_t& boxes) const {
  HandoverEnvelope out;
  out.chart = holder;
  if (disabled_) {
    out.bounded = true;
    return out;
  }
  const Model& m = solver_->nominal();
  std::shared_ptr<const BoxParts> parts = box_parts(box);
  const Interval fixed = curve.fixed_range ? *curve.fixed_range : Interval::enclose(curve.fixed_value);
  const Motion& fixed_motion = m.parts[fixed_part_].motion;
  const Motion& free_motion = m.parts[free_part_].motion;
  auto geometry_of = [&](std::size_t part) -> const model_detail::PartGeometry<Interval>& {
    return part == fixed_part_ ? parts->fixed : parts->free;
  };
  // F and F_v of a feature pair over box x range x y (F_v: the jet's one partial).
  auto contact = [&](const FeatureIdentity& first, const FeatureIdentity& second, const Interval& y) {
    auto pose = [&](std::size_t part, const IntervalJet& chart) {
      const model_detail::PartGeometry<Interval>& g = geometry_of(part);
      kernels::Vector<IntervalJet> pivot{IntervalJet(g.pivot.x), IntervalJet(g.pivot.y)};
      kernels::Vector<IntervalJet> direction{IntervalJet(g.direction.x), IntervalJet(g.direction.y)};
      bool half = part == fixed_part_ ? curve.fixed_half_turn : curve.free_half_turn;
      return pose_of(part == fixed_part_ ? fixed_motion : free_motion, pivot, direction, chart, half);
    };
    IntervalJet t(fixed), v = IntervalJet::variable(y, 0, 1);
    auto a = pose(first.part, first.part == fixed_part_ ? t : v);
    auto b = pose(second.part, second.part == fixed_part_ ? t : v);
    return contact_function(lift(geometry_of(first.part).loops.at(first.loop).at(first.edge)), first, a,
                            lift(geometry_of(second.part).loops.at(second.loop).at(second.edge)), second, b);
  };
  // 0. The holder's free side.
  int sigma = 0;
  try {
    sigma = sign_of(contact(curve.first, curve.second, holder).partial(0));
  } catch (const Error&) {
  }
  if (sigma == 0) {
    out.why = "the holding feature pair's free side is not certain over the box";
    return out;
  }
  const double reach = 2 * holder.width() + absolute_accuracy + 1e-12 * (1 + std::fabs(holder.middle()));
  const double start = end_of(holder, sigma);
  const Interval window = sigma > 0 ? Interval(start, start + reach) : Interval(start - reach, start);
  // 1. The edges over box x range x window.
  auto pose_part = [&](std::size_t part, const Interval& chart) {
    const model_detail::PartGeometry<Interval>& g = geometry_of(part);
    bool half = part == fixed_part_ ? curve.fixed_half_turn : curve.free_half_turn;
    kernels::Pose<Interval> pose = pose_of(m.parts[part].motion, g.pivot, g.direction, chart, half);
    const auto& minor = part == fixed_part_ ? parts->fixed_minor : parts->free_minor;
    std::vector<std::vector<Posed>> loops;
    for (std::size_t l = 0; l < g.loops.size(); ++l) {
      loops.emplace_back();
      for (std::size_t e = 0; e < g.loops[l].size(); ++e) loops.back().push_back(pose_edge(g.loops[l][e], pose, minor[l][e]));
    }
    return loops;
  };
  const std::size_t first_part = curve.first.part, second_part = curve.second.part;
  auto first_edges = pose_part(first_part, first_part == fixed_part_ ? fixed : window);
  auto second_edges = pose_part(second_part, second_part == fixed_part_ ? fixed : window);
  using Key = std::tuple<std::size_t, std::size_t, int, std::size_t, std::size_t, int>;
  std::set<Key> keys;
  auto kind = [](const model_detail::EdgeValue<Interval>& e) { return e.arc ? FeatureKind::arc : FeatureKind::segment; };
  for (std::size_t la = 0; la < first_edges.size(); ++la)
    for (std::size_t ea = 0; ea < first_edges[la].size(); ++ea)
      for (std::size_t lb = 0; lb < second_edges.size(); ++lb)
        for (std::size_t eb = 0; eb < second_edges[lb].size(); ++eb) {
          if (apart(first_edges[la][ea], second_edges[lb][eb])) continue;
          std::size_t na = (ea + 1) % first_edges[la].size(), nb = (eb + 1) % second_edges[lb].size();
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
  auto identity = [](std::size_t part, std::size_t loop, std::size_t edge, int k) {
    FeatureIdentity f;
    f.part = part;
    f.loop = loop;
    f.edge = edge;
    f.kind = static_cast<FeatureKind>(k);
    return f;
  };
  // 2. Whether a candidate may push the follower somewhere in y.
  // The candidate's two features (an edge, or a vertex: its edge's source) posed with the
  // follower over y: certainly apart, they do not touch there.
  auto features_apart = [&](const CurveSlice& c, const Interval& y) {
    auto posed = [&](const FeatureIdentity& f) {
      const model_detail::PartGeometry<Interval>& g = geometry_of(f.part);
      bool half = f.part == fixed_part_ ? curve.fixed_half_turn : curve.free_half_turn;
      kernels::Pose<Interval> pose = pose_of(m.parts[f.part].motion, g.pivot, g.direction, f.part == fixed_part_ ? fixed : y, half);
      const auto& e = g.loops.at(f.loop).at(f.edge);
      if (f.kind == FeatureKind::vertex) return point(kernels::world_point(pose, e.source));
      const auto& minor = f.part == fixed_part_ ? parts->fixed_minor : parts->free_minor;
      return pose_edge(e, pose, minor[f.loop][f.edge]);
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
      auto minor = [&](const FeatureIdentity& f) {
        return (f.part == fixed_part_ ? parts->fixed_minor : parts->free_minor)[f.loop][f.edge] != 0;
      };
      if (off_arc(a, minor(c.first)) || off_arc(b, minor(c.second))) return true;
    }
    return false;
  };
  auto may_push = [&](const CurveSlice& c, const Interval& y) {
    if (features_apart(c, y)) return false;
    IntervalJet f = contact(c.first, c.second, y);
    return sign_of(f.value) == 0 && sign_of(f.partial(0)) != -sigma;
  };
  // The sigma end of the sigma-most piece of y (bisected `depth` times) where it may push.
  auto furthest = [&](const CurveSlice& c, const Interval& y, int depth, auto& self) -> std::optional<double> {
    if (!may_push(c, y)) return std::nullopt;
    if (depth == 0) return end_of(y, sigma);
    double mid = y.middle();
    Interval near_half(y.lo, mid), far_half(mid, y.hi);
    if (sigma < 0) std::swap(near_half, far_half);
    if (auto r = self(c, far_half, depth - 1, self)) return r;
    return self(c, near_half, depth - 1, self);
  };
  constexpr int pieces = 8;
  auto piece = [&](int k) {
    double a = window.lo + window.width() * k / pieces, b = k + 1 == pieces ? window.hi : window.lo + window.width() * (k + 1) / pieces;
    return Interval(a, std::max(a, b));
  };
  double envelope_end = start;
  std::string furthest_label;   // the candidate reaching furthest
  for (const Key& key : keys) {
    CurveSlice c = curve;
    c.first = identity(first_part, std::get<0>(key), std::get<1>(key), std::get<2>(key));
    c.second = identity(second_part, std::get<3>(key), std::get<4>(key), std::get<5>(key));
    bool is_holder = c.first == curve.first && c.second == curve.second;
    ++out.candidates;
    std::optional<int> first_piece;
    try {
      for (int k = 0; k < pieces && !first_piece; ++k)
        if (may_push(c, piece(k))) first_piece = k;
    } catch (const GeometryError&) {
      // no contact of its own (a concave arc on a segment, two vertices): its touchings are its
      // vertex candidates'
      ++out.excluded;
      continue;
    }
    if (!first_piece) {
      ++out.excluded;
      continue;
    }
    // 3. Enclosed: its root over the box, then nothing pushing beyond.
    std::optional<Interval> root;
    if (is_holder) {
      root = holder;
    } else {
      try {
        double v = piece(*first_piece).middle();
        CurveSlice at = c;
        std::vector<double> s = solver_->sensitivities(at, v);
        root = solver_->certified_range(c, box, v, s, relative_accuracy, absolute_accuracy, boxes);
      } catch (const Error&) {
      }
    }
    // (a root Newton found beyond the window is of no use: the window's pieces decide)
    if (root && !is_holder && (sigma > 0 ? end_of(*root, sigma) >= window.hi : end_of(*root, sigma) <= window.lo)) root.reset();
    std::optional<double> end;
    if (root) {
      double root_end = end_of(*root, sigma);
      {
        Interval beyond = sigma > 0 ? Interval(std::max(root_end, window.lo), window.hi) : Interval(window.lo, std::min(root_end, window.hi));
        Interval through = kernels::hull(*root, beyond);
        if (sign_of(contact(c.first, c.second, through).partial(0)) == sigma) {
          end = root_end;   // monotone over the root's enclosure and beyond: its only zero
        } else {
          std::optional<double> r = furthest(c, beyond, 6, furthest);
          end = r ? further(*r, root_end, sigma) : root_end;
        }
      }
    } else {
      std::optional<double> r = furthest(c, window, 6, furthest);
      end = r ? *r : start;
    }
    if (sigma > 0 ? *end > start : *end < start) out.extended = true;
    if (further(envelope_end, *end, sigma) != envelope_end || furthest_label.empty()) {
      auto name = [&](const FeatureIdentity& f) {
        const Part& part = m.parts[f.part];
        std::string edge = part.loops.at(f.loop).edges.at(f.edge).label;
        if (edge.empty()) edge = "loop " + std::to_string(f.loop) + " edge " + std::to_string(f.edge);
        return part.name + " " + (f.kind == FeatureKind::vertex ? "vertex of " : "") + edge;
      };
      furthest_label = name(c.first) + " / " + name(c.second) + (root ? "" : " (not enclosed)");
    }
    envelope_end = further(envelope_end, *end, sigma);
  }
  // 4. The envelope, unless it may reach the window's far end.
  double margin = reach / 8;
  if (sigma > 0 ? envelope_end > window.hi - margin : envelope_end < window.lo + margin) {
    out.why = "a feature pair other than the holding one may hold the follower further than the search reaches (" +
              furthest_label + ")";
    return out;
  }
  out.chart = sigma > 0 ? Interval(holder.lo, std::max(holder.hi, envelope_end))
                        : Interval(std::min(holder.lo, envelope_end), holder.hi);
  out.bounded = true;
  return out;
}

}  // namespace hipair::tolerance_detail
