// Certified numeric geometry of the verifier (see interval_geometry.hpp). Every quantity is an
// MPFI enclosure; a decision is taken only when the enclosure makes it certain, otherwise the
// conservative answer is used (distance candidates kept, "may intersect" => distance 0).
// Bounds are exact rationals (the MPFR end points of the enclosures, converted exactly) and are
// compared exactly: nothing here is decided in double.
#include "certify/interval_geometry.hpp"

#include <mpfr.h>

#include <algorithm>
#include <optional>

namespace hipair::verify {
namespace {

using P = IntervalPoint;

Interval unary(int (*operation)(mpfi_ptr, mpfi_srcptr), const Interval& a) {
  Interval result;
  operation(result.get(), a.get());
  return result;
}
Interval sqr(const Interval& a) { return unary(mpfi_sqr, a); }
Interval absolute(const Interval& a) { return unary(mpfi_abs, a); }
Interval root(const Interval& a) {   // sqrt of the non-negative part of a
  if (mpfi_is_nonneg(a.get()) > 0) return unary(mpfi_sqrt, a);
  mpfr_t right;
  mpfr_init2(right, model_detail::interval_bits);
  mpfi_get_right(right, a.get());
  Interval clipped(Rational(0));
  if (mpfr_sgn(right) > 0) mpfi_put_fr(clipped.get(), right);
  mpfr_clear(right);
  return unary(mpfi_sqrt, clipped);
}
Interval hull(const Interval& a, const Interval& b) {
  Interval result(a);
  mpfi_put(result.get(), b.get());
  return result;
}
bool certainly_positive(const Interval& a) { return a.sign() > 0; }
// A lower bound of a distance (a non-negative quantity) enclosed by `a`: its exact lower end,
// or 0 when that is negative or the enclosure is unbounded or NaN.
Rational distance_lower(const Interval& a) {
  if (!a.is_bounded() || mpfr_sgn(&a.get()->left) <= 0) return Rational(0);
  return a.lower();
}
// True when every value of `a` is at least `bound` (exact comparison of the lower end).
bool certainly_at_least(const Interval& a, const Rational& bound) {
  return a.is_bounded() && mpfr_cmp_q(&a.get()->left, bound.get_mpq_t()) >= 0;
}
bool possibly_nonnegative(const Interval& a) { return a.sign() >= 0; }
// best = min(best, candidate); an absent best is +infinity.
void keep_smaller(std::optional<Rational>& best, const Rational& candidate) {
  if (!best || candidate < *best) best = candidate;
}

P operator-(const P& a, const P& b) { return P{a.x - b.x, a.y - b.y}; }
P operator+(const P& a, const P& b) { return P{a.x + b.x, a.y + b.y}; }
P scale(const Interval& k, const P& a) { return P{k * a.x, k * a.y}; }
Interval cross(const P& a, const P& b) { return a.x * b.y - a.y * b.x; }
Interval dot(const P& a, const P& b) { return a.x * b.x + a.y * b.y; }
Interval norm(const P& a) { return root(sqr(a.x) + sqr(a.y)); }
P exact(const Point& p) { return P{Interval(p.x), Interval(p.y)}; }

P apply(const IntervalMap& map, const P& pivot, const P& p) {   // p relative to the pivot
  return P{pivot.x + map.c * p.x - map.s * p.y + map.shift.x, pivot.y + map.s * p.x + map.c * p.y + map.shift.y};
}
P rotate(const IntervalMap& map, const P& v) { return P{map.c * v.x - map.s * v.y, map.s * v.x + map.c * v.y}; }

// Direction w (from an arc's centre) in the arc's sector: possibly (closed) or certainly (open).
bool possibly_in_sector(const IntervalEdge& arc, const P& w) {
  if (arc.full_circle) return true;
  bool first = possibly_nonnegative(cross(arc.from, w)), second = possibly_nonnegative(cross(w, arc.to));
  return arc.reflex ? (first || second) : (first && second);
}
bool certainly_in_open_sector(const IntervalEdge& arc, const P& w) {
  if (arc.full_circle) return true;
  bool first = certainly_positive(cross(arc.from, w)), second = certainly_positive(cross(w, arc.to));
  return arc.reflex ? (first || second) : (first && second);
}

// Lower bound of the distance from point p to edge e (absent: no candidate, +infinity).
void point_to_edge(const P& p, const IntervalEdge& e, std::optional<Rational>& best) {
  if (!e.full_circle) {
    keep_smaller(best, distance_lower(norm(p - e.source)));
    keep_smaller(best, distance_lower(norm(p - e.target)));
  }
  if (!e.arc) {
    P d = e.target - e.source;
    Interval u = dot(p - e.source, d) / dot(d, d);
    if (possibly_nonnegative(u) && possibly_nonnegative(Interval(Rational(1)) - u))
      keep_smaller(best, distance_lower(absolute(cross(d, p - e.source)) / norm(d)));
  } else if (possibly_in_sector(e, p - e.center)) {
    keep_smaller(best, distance_lower(absolute(norm(p - e.center) - e.radius)));
  }
}

// May the segment s and arc a have a common point?
bool segment_arc_may_meet(const IntervalEdge& s, const IntervalEdge& a) {
  P v = s.target - s.source, w = s.source - a.center;
  Interval qa = dot(v, v), qb = dot(v, w), discriminant = sqr(qb) - qa * (dot(w, w) - a.radius_squared);
  if (discriminant.sign() < 0) return false;
  Interval r = root(discriminant);
  for (const Interval& lambda : {(-qb - r) / qa, (-qb + r) / qa}) {
    bool on_segment = possibly_nonnegative(lambda) && possibly_nonnegative(Interval(Rational(1)) - lambda);
    if (on_segment && possibly_in_sector(a, w + scale(lambda, v))) return true;
  }
  return false;
}

bool arcs_may_meet(const IntervalEdge& e, const IntervalEdge& g) {
  P axis = g.center - e.center;
  Interval length2 = dot(axis, axis), length = root(length2);
  if (certainly_positive(length - e.radius - g.radius)) return false;          // apart
  if (certainly_positive(absolute(e.radius - g.radius) - length)) return false;  // nested
  if (!certainly_positive(length2)) return true;                                  // (nearly) concentric
  Interval k = (Interval(Rational(1)) + (e.radius_squared - g.radius_squared) / length2) / Interval(Rational(2));
  Interval offset = root(e.radius_squared - sqr(k) * length2) / length;
  P perpendicular{-axis.y, axis.x};
  for (const Interval& sign : {Interval(Rational(-1)), Interval(Rational(1))}) {
    P w = scale(k, axis) + scale(sign * offset, perpendicular);   // relative to e's centre
    if (possibly_in_sector(e, w) && possibly_in_sector(g, w - axis)) return true;
  }
  return false;
}

bool edges_may_meet(const IntervalEdge& e, const IntervalEdge& g) {
  if (!e.arc && !g.arc) {
    auto side = [](const IntervalEdge& line, const P& p) { return cross(line.target - line.source, p - line.source).sign(); };
    auto separates = [&](const IntervalEdge& line, const IntervalEdge& other) {
      int a = side(line, other.source), b = side(line, other.target);
      return a != 0 && a == b;
    };
    // Collinear or nearly parallel segments: their projections on either one's direction are
    // certainly disjoint (a separating line perpendicular to it).
    auto apart_along = [](const IntervalEdge& line, const IntervalEdge& other) {
      P d = line.target - line.source;
      Interval length2 = dot(d, d), u = dot(other.source - line.source, d), v = dot(other.target - line.source, d);
      return (u.sign() < 0 && v.sign() < 0) || (certainly_positive(u - length2) && certainly_positive(v - length2));
    };
    return !separates(e, g) && !separates(g, e) && !apart_along(e, g) && !apart_along(g, e);
  }
  if (!e.arc) return segment_arc_may_meet(e, g);
  if (!g.arc) return segment_arc_may_meet(g, e);
  return arcs_may_meet(e, g);
}

// Lower bound of the distance between edges e and g (0 when they may meet).
Rational edge_distance(const IntervalEdge& e, const IntervalEdge& g) {
  if (edges_may_meet(e, g)) return Rational(0);
  std::optional<Rational> best;
  if (!e.full_circle) {
    point_to_edge(e.source, g, best);
    point_to_edge(e.target, g, best);
  }
  if (!g.full_circle) {
    point_to_edge(g.source, e, best);
    point_to_edge(g.target, e, best);
  }
  // Interior points of both at a common normal.
  if (e.arc != g.arc) {
    const IntervalEdge& s = e.arc ? g : e;
    const IntervalEdge& a = e.arc ? e : g;
    P d = s.target - s.source, w = a.center - s.source;
    Interval u = dot(w, d) / dot(d, d);
    P normal{-d.y, d.x};
    if (possibly_nonnegative(u) && possibly_nonnegative(Interval(Rational(1)) - u) &&
        (possibly_in_sector(a, normal) || possibly_in_sector(a, scale(Interval(Rational(-1)), normal))))
      keep_smaller(best, distance_lower(absolute(absolute(cross(d, w)) / norm(d) - a.radius)));
  } else if (e.arc && g.arc) {
    P axis = g.center - e.center;
    Interval length = norm(axis);
    if (!certainly_positive(length)) {
      keep_smaller(best, distance_lower(absolute(e.radius - g.radius)));
    } else {
      for (int sign_e : {-1, 1})
        for (int sign_g : {-1, 1}) {
          Interval se{Rational(sign_e)}, sg{Rational(sign_g)};
          if (possibly_in_sector(e, scale(se, axis)) && possibly_in_sector(g, scale(sg, axis)))
            keep_smaller(best, distance_lower(absolute(length + sg * g.radius - se * e.radius)));
        }
    }
  }
  return best ? *best : Rational(0);   // no candidate (never: every pair has end points or normals)
}

Interval disc_gap(const P& c1, const Interval& r1, const P& c2, const Interval& r2) { return norm(c1 - c2) - r1 - r2; }

}  // namespace

namespace {
bool beyond_reduction(const Interval& angle) {
  if (!angle.is_bounded()) return true;
  for (mpfr_srcptr end : {&angle.get()->left, &angle.get()->right})
    if (mpfr_regular_p(end) && mpfr_get_exp(end) > 1100) return true;
  return false;
}
Interval unit_range() {
  Interval range(Rational(-1));
  mpfi_put_si(range.get(), 1);
  return range;
}
}  // namespace

Interval sin_of(const Interval& angle) {
  if (beyond_reduction(angle)) return unit_range();
  Interval result;
  mpfi_sin(result.get(), angle.get());
  return result;
}
Interval cos_of(const Interval& angle) {
  if (beyond_reduction(angle)) return unit_range();
  Interval result;
  mpfi_cos(result.get(), angle.get());
  return result;
}

IntervalMap to_interval_map(const ExactMap& map) { return IntervalMap{Interval(map.c), Interval(map.s), exact(map.shift)}; }

IntervalMap rotation_over(const RationalInterval& angle) {
  Interval theta(angle.lo);
  mpfi_put_q(theta.get(), const_cast<mpq_ptr>(angle.hi.get_mpq_t()));
  IntervalMap map;
  map.c = cos_of(theta);
  map.s = sin_of(theta);
  return map;
}

IntervalMap translation_over(const Point& direction, const RationalInterval& offset) {
  Interval s(offset.lo);
  mpfi_put_q(s.get(), const_cast<mpq_ptr>(offset.hi.get_mpq_t()));
  IntervalMap map;
  map.shift = scale(s, exact(direction));
  return map;
}

Point pose_pivot(const Part& part) {
  return part.motion.kind == Motion::Kind::rotation ? part.motion.pivot : Point{Rational(0), Rational(0)};
}

IntervalPart shape_of(const Part& part) {
  Point pivot = pose_pivot(part);
  auto relative = [&](const Point& p) { return P{Interval(Rational(p.x - pivot.x)), Interval(Rational(p.y - pivot.y))}; };
  IntervalPart shape{part.name, exact(pivot), {}, {}};
  constexpr std::size_t group_size = 8;
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    std::vector<IntervalEdge>& edges = shape.loops.emplace_back();
    for (const Edge& edge : part.loops[l].edges) {
      IntervalEdge e;
      e.arc = edge.is_arc();
      e.full_circle = edge.is_full_circle();
      e.ccw = edge.ccw;
      e.source = relative(edge.source);
      e.target = relative(edge.target);
      e.disc_center = scale(Interval(Rational(1, 2)), e.source + e.target);
      e.disc_radius = norm(e.target - e.source) / Interval(Rational(2));
      if (e.arc) {
        Point from = edge.ccw ? edge.source : edge.target, to = edge.ccw ? edge.target : edge.source;
        Point body_from{Rational(from.x - edge.center.x), Rational(from.y - edge.center.y)};
        Point body_to{Rational(to.x - edge.center.x), Rational(to.y - edge.center.y)};
        e.center = relative(edge.center);
        e.radius_squared = Interval(edge.radius_squared);
        e.radius = root(e.radius_squared);
        e.from = exact(body_from);
        e.to = exact(body_to);
        Rational turn = body_from.x * body_to.y - body_from.y * body_to.x;
        e.reflex = sgn(turn) < 0;
        Interval angle;
        mpfi_atan2(angle.get(), Interval(turn).get(), Interval(Rational(body_from.x * body_to.x + body_from.y * body_to.y)).get());
        Interval turn_twice = Interval::pi() * Interval(Rational(2));
        e.sweep = e.full_circle ? turn_twice : (e.reflex ? angle + turn_twice : angle);
        if (e.full_circle || e.reflex) {   // else the arc lies in the disc on its chord
          e.disc_center = e.center;
          e.disc_radius = e.radius;
        }
      }
      edges.push_back(std::move(e));
    }
    for (std::size_t first = 0; first < edges.size(); first += group_size) {
      std::size_t last = std::min(edges.size(), first + group_size);
      P sum{Interval(Rational(0)), Interval(Rational(0))};
      for (std::size_t i = first; i < last; ++i) sum = sum + edges[i].disc_center;
      P center = scale(Interval(Rational(1, long(last - first))), sum);
      Interval radius(Rational(0));
      for (std::size_t i = first; i < last; ++i)
        radius = hull(radius, norm(edges[i].disc_center - center) + edges[i].disc_radius);
      if (!radius.is_bounded()) throw Rejection{"the edges of part '" + part.name + "' cannot be bounded"};
      shape.groups.push_back({l, first, last, center, Interval(radius.upper())});
    }
  }
  return shape;
}

namespace {

// Edge e of `shape` (body frame) posed by `map`, in place.
void pose_edge(const IntervalPart& shape, const IntervalMap& map, IntervalEdge& e) {
  e.source = apply(map, shape.pivot, e.source);
  e.target = apply(map, shape.pivot, e.target);
  e.disc_center = apply(map, shape.pivot, e.disc_center);
  if (e.arc) {
    e.center = apply(map, shape.pivot, e.center);
    e.from = rotate(map, e.from);
    e.to = rotate(map, e.to);
  }
}

// The bound of boundary_distance_lower_bound over parts seen through `group_center(part, g)`
// (a group's posed disc centre) and `edge(part, loop, i)` (a posed edge), part 0 = a, 1 = b.
template <class GroupCenter, class Edge>
Rational distance_bound(const IntervalPart& a, const IntervalPart& b, const Rational& enough, std::string* closest,
                        GroupCenter&& group_center, Edge&& edge) {
  // The bound is min(enough, min over edge pairs of max(edge gap, group gap, edge distance)),
  // where each term is the exact lower end of an enclosure of the pair's distance (so the
  // maximum is one too). Its value does not depend on the order of the pairs, and pairs are
  // visited nearest first (by the lower end of their bounding discs' gap) so that the running
  // minimum `best` falls early: once a gap is at least `best`, so is every later term.
  Rational best = enough;
  struct Candidate {
    Rational gap;
    std::size_t first, second;
  };
  auto by_gap = [](const Candidate& p, const Candidate& q) { return p.gap < q.gap; };
  std::vector<P> centers_b;
  for (std::size_t n = 0; n < b.groups.size(); ++n) centers_b.push_back(group_center(1, n));
  std::vector<Candidate> groups;
  for (std::size_t m = 0; m < a.groups.size(); ++m) {
    P center_a = group_center(0, m);
    for (std::size_t n = 0; n < b.groups.size(); ++n) {
      Interval gap = disc_gap(center_a, a.groups[m].radius, centers_b[n], b.groups[n].radius);
      if (certainly_at_least(gap, best)) continue;
      groups.push_back({distance_lower(gap), m, n});
    }
  }
  std::stable_sort(groups.begin(), groups.end(), by_gap);
  std::vector<Candidate> edges;
  for (const Candidate& group : groups) {
    if (group.gap >= best) break;
    const auto &ga = a.groups[group.first], &gb = b.groups[group.second];
    edges.clear();
    for (std::size_t i = ga.first; i < ga.last; ++i)
      for (std::size_t j = gb.first; j < gb.last; ++j) {
        const IntervalEdge& e = edge(0, ga.loop, i);
        const IntervalEdge& g = edge(1, gb.loop, j);
        Interval gap = disc_gap(e.disc_center, e.disc_radius, g.disc_center, g.disc_radius);
        if (certainly_at_least(gap, best)) continue;
        edges.push_back({std::max(distance_lower(gap), group.gap), i, j});
      }
    std::stable_sort(edges.begin(), edges.end(), by_gap);
    for (const Candidate& pair : edges) {
      if (pair.gap >= best) break;
      Rational distance = std::max(edge_distance(edge(0, ga.loop, pair.first), edge(1, gb.loop, pair.second)), pair.gap);
      if (distance < best) {
        best = distance;
        if (closest)
          *closest = "loop " + std::to_string(ga.loop) + " edge " + std::to_string(pair.first) + " of '" + a.name +
                     "' and loop " + std::to_string(gb.loop) + " edge " + std::to_string(pair.second) + " of '" + b.name + "'";
      }
      if (sgn(best) <= 0) return Rational(0);
    }
  }
  return best;
}

}  // namespace

IntervalPoint place_point(const IntervalPart& shape, const IntervalMap& map, const IntervalPoint& p) {
  return apply(map, shape.pivot, p);
}

IntervalPart place_over(const IntervalPart& shape, const IntervalMap& map) {
  IntervalPart placed = shape;
  for (auto& loop : placed.loops)
    for (IntervalEdge& e : loop) pose_edge(shape, map, e);
  for (auto& group : placed.groups) group.center = apply(map, shape.pivot, group.center);
  return placed;
}

Rational boundary_distance_lower_bound(const IntervalPart& a, const IntervalPart& b, const Rational& enough,
                                       std::string* closest) {
  const IntervalPart* parts[2] = {&a, &b};
  return distance_bound(
      a, b, enough, closest, [&](int part, std::size_t g) { return parts[part]->groups[g].center; },
      [&](int part, std::size_t loop, std::size_t i) -> const IntervalEdge& { return parts[part]->loops[loop][i]; });
}

Rational boundary_distance_lower_bound(const IntervalPart& shape_a, const IntervalMap& map_a, const IntervalPart& shape_b,
                                       const IntervalMap& map_b, const Rational& enough, std::string* closest) {
  // Edges are posed when first needed (most pairs are culled by their groups' discs).
  const IntervalPart* shapes[2] = {&shape_a, &shape_b};
  const IntervalMap* maps[2] = {&map_a, &map_b};
  std::vector<std::vector<std::optional<IntervalEdge>>> posed[2];
  for (int part = 0; part < 2; ++part)
    for (const auto& loop : shapes[part]->loops) posed[part].emplace_back(loop.size());
  return distance_bound(
      shape_a, shape_b, enough, closest,
      [&](int part, std::size_t g) { return apply(*maps[part], shapes[part]->pivot, shapes[part]->groups[g].center); },
      [&](int part, std::size_t loop, std::size_t i) -> const IntervalEdge& {
        std::optional<IntervalEdge>& e = posed[part][loop][i];
        if (!e) {
          e = shapes[part]->loops[loop][i];
          pose_edge(*shapes[part], *maps[part], *e);
        }
        return *e;
      });
}

Rational point_boundary_distance_lower_bound(const IntervalPart& shape, const IntervalMap& map, const Point& p,
                                             const Rational& enough) {
  // The point taken into the shape's frame by the inverse maps, v = R^T (p - pivot - shift), an
  // enclosure of its preimages over every pose; its distance from the shape's (unposed) edges is
  // the distance sought (the maps are rigid). Posing the edges instead enclosed each edge's ends
  // separately: a segment translated over [lo, hi] got a direction 2 (hi - lo) wide, and a point
  // 10^-20 inside a slider over a range of 1 mm was not certainly off its boundary.
  std::optional<Rational> best = enough;
  P d = exact(p) - shape.pivot - map.shift;
  P v{map.c * d.x + map.s * d.y, map.c * d.y - map.s * d.x};
  for (const auto& loop : shape.loops)
    for (const IntervalEdge& e : loop) point_to_edge(v, e, best);
  return *best;
}

Rational reach(const IntervalPart& shape) {
  Rational best(0);
  for (const auto& loop : shape.loops)
    for (const IntervalEdge& edge : loop) {
      Interval distance = edge.arc ? norm(edge.center) + edge.radius : norm(edge.source);
      if (!distance.is_bounded()) throw Rejection{"the reach of part '" + shape.name + "' cannot be bounded"};
      Rational bound = distance.upper();
      // An arc lies in its disc (disc_center, disc_radius): the disc on its chord for an arc of at
      // most a half turn (decided exactly, shape_of), else its circle. The circle's bound |c| + r
      // alone made an arc of radius 10^10 on a 60 mm lever reach 2·10^10 mm: a free-passage
      // certificate's boxes shrank by that factor (session 45: `certify --claim free` over 0.001
      // rad took 38 s CPU and declined; 10^8: more than 100 s). Both bounds hold; the smaller is
      // taken (a segment keeps |source|: its neighbours' sources cover its target).
      if (edge.arc) {
        Interval disc = norm(edge.disc_center) + edge.disc_radius;
        if (disc.is_bounded() && disc.upper() < bound) bound = disc.upper();
      }
      best = std::max(best, bound);
    }
  return best;
}

IntervalPoint point_on(const IntervalEdge& e, const Interval& u) {
  if (!e.arc) return e.source + scale(u, e.target - e.source);
  Interval c = cos_of(u), s = sin_of(u);
  if (!e.ccw) s = -s;
  P w = e.source - e.center;
  return e.center + P{c * w.x - s * w.y, s * w.x + c * w.y};
}

Interval side_of(const IntervalEdge& g, const IntervalPoint& p) {
  if (!g.arc) return cross(g.target - g.source, p - g.source);
  return dot(p - g.center, p - g.center) - g.radius_squared;
}

bool crossing_certain(const IntervalEdge& e, const RationalInterval& along, const IntervalEdge& g, std::string* why) {
  auto no = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (sgn(along.lo) < 0 || along.lo >= along.hi) return no("the piece 'along' must satisfy 0 <= lo < hi");
  if (!e.arc && along.hi > 1) return no("a segment piece 'along' must lie in [0, 1]");
  if (e.arc && (e.sweep - Interval(along.hi)).sign() <= 0)
    return no("the arc piece 'along' is not certainly within the arc's angle");
  int start = side_of(g, point_on(e, Interval(along.lo))).sign(), end = side_of(g, point_on(e, Interval(along.hi))).sign();
  if (start == 0 || end == 0 || start == end)
    return no("the ends of the piece are not certainly on opposite sides of the other edge's " +
              std::string(g.arc ? "circle" : "line"));
  Interval piece(along.lo);
  mpfi_put_q(piece.get(), const_cast<mpq_ptr>(along.hi.get_mpq_t()));
  P q = point_on(e, piece);
  bool within = g.arc ? certainly_in_open_sector(g, q - g.center)
                      : certainly_positive(dot(q - g.source, g.target - g.source)) &&
                            certainly_positive(dot(q - g.target, g.source - g.target));
  return within ? true : no("the piece does not certainly stay within the other edge's extent");
}

}  // namespace hipair::verify
