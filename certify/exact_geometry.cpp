// Exact geometry of the verifier (see exact_geometry.hpp).
#include "certify/exact_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace hipair::verify {
namespace {

Point minus(const Point& a, const Point& b) { return Point{Rational(a.x - b.x), Rational(a.y - b.y)}; }
Point plus(const Point& a, const Point& b) { return Point{Rational(a.x + b.x), Rational(a.y + b.y)}; }
Point times(const Rational& k, const Point& a) { return Point{Rational(k * a.x), Rational(k * a.y)}; }
Rational cross(const Point& a, const Point& b) { return a.x * b.y - a.y * b.x; }
Rational dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }

// The intersections of the line p + lambda v with a circle of centre c: lambda = l0 +- l1 sqrt(D).
// `base` = p - c + l0 v, so a root's point relative to the centre is base +- l1 sqrt(D) v.
struct LineCircle {
  Rational discriminant, l0, l1;
  Point base, v;
  // Sign of cross(f, w + shift) where w is root `sigma`'s point relative to the centre.
  int cross_sign(int sigma, const Point& f, const Point& shift = {0, 0}) const {
    return sign_with_root(cross(f, plus(base, shift)), sigma * l1 * cross(f, v), discriminant);
  }
  int lambda_sign(int sigma, const Rational& minus_value = 0) const {
    return sign_with_root(l0 - minus_value, sigma * l1, discriminant);
  }
};

LineCircle line_circle(const Point& p, const Point& v, const Point& c, const Rational& r2) {
  Point w = minus(p, c);
  Rational a = dot(v, v), b = dot(v, w), cc = dot(w, w) - r2;
  LineCircle result{b * b - a * cc, -b / a, 1 / a, {0, 0}, v};
  result.base = plus(w, times(result.l0, v));
  return result;
}

// Is root `sigma` (point relative to the arc's centre: base + shift + ...) in the arc's sector?
bool root_in_sector(const LineCircle& line, int sigma, const PlacedEdge& arc, bool open, const Point& shift = {0, 0}) {
  int s1 = line.cross_sign(sigma, arc.from, shift);
  int s2 = -line.cross_sign(sigma, arc.to, shift);
  return in_sector(arc, s1, s2, open);
}

// Crossings of the ray p + lambda v (lambda > 0) with edge e; nullopt when the ray passes
// through an end point of e or touches it (then another direction is tried). Every test is an
// exact sign: no screen in floating point (a rounded screen far from a small edge drops
// crossings and flips the parity).
std::optional<int> ray_crossings(const PlacedEdge& e, const Point& p, const Point& v) {
  if (!e.arc) {
    Point a = minus(e.source, p), b = minus(e.target, p);
    int sa = sgn(cross(v, a)), sb = sgn(cross(v, b));   // sides of the ray's line
    if (sa == 0 && sb == 0) return std::nullopt;          // along the ray's line
    if (sa == sb) return 0;                               // both ends on one side
    if (sa == 0) return sgn(dot(a, v)) > 0 ? std::nullopt : std::optional<int>(0);   // the line through an end
    if (sb == 0) return sgn(dot(b, v)) > 0 ? std::nullopt : std::optional<int>(0);
    // The line crosses the segment's interior at p + lambda v with
    // lambda = cross(a, d) / cross(v, d), d = b - a; ahead iff lambda > 0.
    Point d = minus(b, a);
    return sgn(cross(a, d)) * sgn(cross(v, d)) > 0 ? 1 : 0;
  }
  // Exact screens: the ray's line misses the circle, or the circle lies wholly behind p.
  Point w = minus(e.center, p);
  Rational vv = dot(v, v), reach2 = e.radius_squared * vv;
  Rational across = cross(v, w), along = dot(v, w);
  if (cmp(Rational(across * across), reach2) > 0) return 0;
  if (sgn(along) < 0 && cmp(Rational(along * along), reach2) > 0) return 0;
  LineCircle line = line_circle(p, v, e.center, e.radius_squared);
  int d = sgn(line.discriminant);
  if (d < 0) return 0;
  if (d == 0) return (line.lambda_sign(1) > 0 && root_in_sector(line, 1, e, false)) ? std::nullopt : std::optional<int>(0);
  int count = 0;
  for (int sigma : {-1, 1}) {
    if (line.lambda_sign(sigma) <= 0) continue;
    int s1 = line.cross_sign(sigma, e.from), s2 = -line.cross_sign(sigma, e.to);
    if (!e.full_circle && (s1 == 0 || s2 == 0)) return std::nullopt;
    count += in_sector(e, s1, s2, true) ? 1 : 0;
  }
  return count;
}

bool in_box(const PlacedEdge& e, const Point& p) {
  return !(p.x < e.box[0] || p.x > e.box[1] || p.y < e.box[2] || p.y > e.box[3]);
}

bool boxes_meet(const PlacedEdge& e, const PlacedEdge& g) {
  // Screen: the outward double boxes are disjoint only if the exact boxes are (a strict
  // inequality between outward bounds implies it between the exact bounds).
  const auto &f = e.outer, &h = g.outer;
  if (f[1] < h[0] || h[1] < f[0] || f[3] < h[2] || h[3] < f[2]) return false;
  return !(e.box[1] < g.box[0] || g.box[1] < e.box[0] || e.box[3] < g.box[2] || g.box[3] < e.box[2]);
}

// A double <= q (lower) or >= q (upper). mpq_get_d truncates towards zero (GMP's own rounding,
// whatever the FPU mode), so one step outwards bounds q; beyond the double range it gives
// +-infinity or +-DBL_MAX, and one step outwards still bounds q (nextafter(inf, -inf) is DBL_MAX,
// below any q that rounded to inf). Below the normal range GMP may flush to zero: truncation
// gives |d| < DBL_MIN only when |q| < DBL_MIN, so +-DBL_MIN bounds q there.
double outward(const Rational& q, bool upper) {
  constexpr double infinity = std::numeric_limits<double>::infinity(), tiny = std::numeric_limits<double>::min();
  double d = q.get_d();
  if (std::fabs(d) < tiny) return upper ? tiny : -tiny;
  return std::nextafter(d, upper ? infinity : -infinity);
}

bool on_edge(const PlacedEdge& e, const Point& p) {
  if (!in_box(e, p)) return false;
  if (!e.arc) {
    Point d = minus(e.target, e.source);
    return sgn(cross(d, minus(p, e.source))) == 0 && sgn(dot(minus(p, e.source), d)) >= 0 &&
           sgn(dot(minus(p, e.target), d)) <= 0;
  }
  Point w = minus(p, e.center);
  return cmp(dot(w, w), e.radius_squared) == 0 && in_sector(e, sgn(cross(e.from, w)), sgn(cross(w, e.to)), false);
}

// A rational upper bound of sqrt(q), q >= 0: sqrt(n/d) = sqrt(n d)/d <= (isqrt(n d) + 1)/d.
Rational sqrt_upper(Rational q) {
  q.canonicalize();
  mpz_class product = q.get_num() * q.get_den(), root;
  mpz_sqrt(root.get_mpz_t(), product.get_mpz_t());
  return Rational(root + 1, q.get_den());
}

// An exact box containing an arc: the box of its end points and of the circle's extreme points
// (centre +- r along the axes, with a rational upper bound of r) whose directions lie in the
// arc's closed sector. The box is only used to skip exact tests, so it may be larger than the
// arc's, never smaller: an extreme point moved outwards along its axis only widens the box.
std::array<Rational, 4> arc_box(const PlacedEdge& e) {
  Rational radius = sqrt_upper(e.radius_squared);
  std::array<Rational, 4> box{std::min(e.source.x, e.target.x), std::max(e.source.x, e.target.x),
                              std::min(e.source.y, e.target.y), std::max(e.source.y, e.target.y)};
  const Point axes[4] = {{Rational(-1), Rational(0)}, {Rational(1), Rational(0)}, {Rational(0), Rational(-1)},
                         {Rational(0), Rational(1)}};
  for (int k = 0; k < 4; ++k)
    if (in_sector(e, sgn(cross(e.from, axes[k])), sgn(cross(axes[k], e.to)), false)) {
      Rational extreme = (k < 2 ? e.center.x : e.center.y) + (k % 2 ? radius : Rational(-radius));
      box[k] = k % 2 ? std::max(box[k], extreme) : std::min(box[k], extreme);
    }
  return box;
}

}  // namespace

Point ExactMap::rotate(const Point& v) const { return Point{Rational(c * v.x - s * v.y), Rational(s * v.x + c * v.y)}; }
Point ExactMap::apply(const Point& p) const { return plus(plus(pivot, rotate(minus(p, pivot))), shift); }

PlacedPart place(const Part& part, const ExactMap& map) {
  PlacedPart placed{part.name, {}};
  for (const Loop& loop : part.loops) {
    std::vector<PlacedEdge>& edges = placed.loops.emplace_back();
    for (const Edge& edge : loop.edges) {
      PlacedEdge e;
      e.arc = edge.is_arc();
      e.full_circle = edge.is_full_circle();
      e.source = map.apply(edge.source);
      e.target = map.apply(edge.target);
      if (e.arc) {
        e.center = map.apply(edge.center);
        e.radius_squared = edge.radius_squared;
        e.from = minus(edge.ccw ? e.source : e.target, e.center);
        e.to = minus(edge.ccw ? e.target : e.source, e.center);
        e.reflex = sgn(cross(e.from, e.to)) < 0;
        e.box = arc_box(e);
      } else {
        e.box = {std::min(e.source.x, e.target.x), std::max(e.source.x, e.target.x), std::min(e.source.y, e.target.y),
                 std::max(e.source.y, e.target.y)};
      }
      for (int k = 0; k < 4; ++k) e.outer[k] = outward(e.box[k], k % 2 == 1);
      edges.push_back(std::move(e));
    }
  }
  return placed;
}

int sign_with_root(const Rational& a, const Rational& b, const Rational& d) {
  int sa = sgn(a), sb = sgn(b);
  if (sb == 0 || sgn(d) == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  int c = cmp(Rational(a * a), Rational(b * b * d));   // |a| vs |b| sqrt(d)
  return c > 0 ? sa : (c < 0 ? sb : 0);
}

bool in_sector(const PlacedEdge& arc, int s1, int s2, bool open) {
  if (arc.full_circle) return true;
  bool first = open ? s1 > 0 : s1 >= 0, second = open ? s2 > 0 : s2 >= 0;
  return arc.reflex ? (first || second) : (first && second);
}

int locate(const PlacedPart& part, const Point& p) {
  const double px = outward(p.x, false), px_high = outward(p.x, true);
  const double py_low = outward(p.y, false), py_high = outward(p.y, true);
  // p beyond the box of every edge (rounded outwards) lies outside the material, which its
  // boundary encloses (session 72: the nested tests of the connected producer's free boxes)
  double box[4] = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& loop : part.loops)
    for (const PlacedEdge& e : loop)
      box[0] = std::min(box[0], e.outer[0]), box[1] = std::max(box[1], e.outer[1]), box[2] = std::min(box[2], e.outer[2]),
      box[3] = std::max(box[3], e.outer[3]);
  if (px_high < box[0] || box[1] < px || py_high < box[2] || box[3] < py_low) return -1;
  for (const auto& loop : part.loops)
    for (const PlacedEdge& e : loop) {
      if (px_high < e.outer[0] || e.outer[1] < px || py_high < e.outer[2] || e.outer[3] < py_low) continue;   // p outside the box
      if (on_edge(e, p)) return 0;
    }
  // Ray casting: the parity of the crossings of a ray with the boundary is 1 inside the
  // material (loops nest as outer / hole / island ...). Directions hitting a vertex or a
  // tangency are skipped.
  // Screen: every ray points to +x and to +y or -y, so an edge whose box lies wholly below
  // p.x, or wholly on the far side of p.y, is never met (the outward double bounds of box and
  // p make each screen a strict exact inequality).
  for (int k = 0; k < 64; ++k) {
    Point v{Rational(7), Rational(2 * k - 63)};   // 64 distinct directions
    const bool up = 2 * k - 63 > 0;
    int count = 0;
    bool degenerate = false;
    for (const auto& loop : part.loops)
      for (const PlacedEdge& e : loop) {
        if (degenerate || e.outer[1] < px || (up ? e.outer[3] < py_low : e.outer[2] > py_high)) continue;
        std::optional<int> crossings = ray_crossings(e, p, v);
        if (!crossings) degenerate = true;
        else count += *crossings;
      }
    if (!degenerate) return count % 2 ? 1 : -1;
  }
  throw Rejection{"point location failed: every ray tried passes through a vertex of part '" + part.name + "'"};
}

bool edges_cross(const PlacedEdge& e, const PlacedEdge& g) {
  // edges whose boxes (rounded outwards) are apart do not meet (session 72: most pairs of edges
  // of two parts are far apart; their exact tests were most of the connected producer's time)
  if (!boxes_meet(e, g)) return false;
  if (!e.arc && !g.arc) {
    auto orient = [](const Point& a, const Point& b, const Point& c) { return sgn(cross(minus(b, a), minus(c, a))); };
    return orient(e.source, e.target, g.source) * orient(e.source, e.target, g.target) < 0 &&
           orient(g.source, g.target, e.source) * orient(g.source, g.target, e.target) < 0;
  }
  if (!e.arc || !g.arc) {
    const PlacedEdge& segment = e.arc ? g : e;
    const PlacedEdge& arc = e.arc ? e : g;
    LineCircle line = line_circle(segment.source, minus(segment.target, segment.source), arc.center, arc.radius_squared);
    if (sgn(line.discriminant) <= 0) return false;   // no crossing, or a tangency (not transversal)
    for (int sigma : {-1, 1})
      if (line.lambda_sign(sigma) > 0 && line.lambda_sign(sigma, 1) < 0 && root_in_sector(line, sigma, arc, true))
        return true;
    return false;
  }
  Point axis = minus(g.center, e.center);
  Rational length2 = dot(axis, axis);
  if (sgn(length2) == 0) return false;   // concentric circles never cross transversally
  // The common points lie on the radical line c1 + k axis + lambda perp(axis).
  Rational k = (1 + (e.radius_squared - g.radius_squared) / length2) / 2;
  LineCircle line = line_circle(plus(e.center, times(k, axis)), Point{Rational(-axis.y), axis.x}, e.center,
                                e.radius_squared);
  if (sgn(line.discriminant) <= 0) return false;
  Point shift = minus(e.center, g.center);   // from e's centre to g's centre frame
  for (int sigma : {-1, 1})
    if (root_in_sector(line, sigma, e, true) && root_in_sector(line, sigma, g, true, shift)) return true;
  return false;
}

namespace {

// sqrt(A) >= sqrt(B) + d (A, B >= 0, d > 0): A >= B + d^2 + 2 d sqrt(B).
bool root_exceeds(const Rational& A, const Rational& B, const Rational& d) {
  return sign_with_root(Rational(A - B - d * d), Rational(-2 * d), B) >= 0;
}

// |sqrt(A) - sqrt(B)| >= d
bool roots_apart(const Rational& A, const Rational& B, const Rational& d) {
  return root_exceeds(A, B, d) || root_exceeds(B, A, d);
}

// sqrt(A) + sqrt(B) >= d: true when B >= d^2, else A >= d^2 + B - 2 d sqrt(B).
bool roots_reach(const Rational& A, const Rational& B, const Rational& d) {
  return cmp(B, Rational(d * d)) >= 0 || sign_with_root(Rational(A - d * d - B), Rational(2 * d), B) >= 0;
}

// Sign of (p + q sqrt(A)) + sqrt(B) (r + s sqrt(A)), A, B >= 0: the two parts' signs, or, when
// they differ, the sign of the difference of their squares (again of the form x + y sqrt(A)).
int sign_of_pair(const Rational& p, const Rational& q, const Rational& r, const Rational& s, const Rational& A,
                 const Rational& B) {
  int su = sign_with_root(p, q, A), sw = sgn(B) == 0 ? 0 : sign_with_root(r, s, A);
  if (sw == 0 || su == sw) return su;
  if (su == 0) return sw;
  int t = sign_with_root(Rational(p * p + q * q * A - B * r * r - B * s * s * A), Rational(2 * p * q - 2 * B * r * s), A);
  return t > 0 ? su : (t < 0 ? sw : 0);
}

// Sign of a + b sqrt(A) + c sqrt(B) + e sqrt(C) (A, B, C >= 0): P = a + b sqrt(A) + c sqrt(B)
// against e sqrt(C), their squares compared when the signs differ.
int sign_of_roots(const Rational& a, const Rational& b, const Rational& A, const Rational& c, const Rational& B,
                  const Rational& e, const Rational& C) {
  int sp = sign_of_pair(a, b, c, 0, A, B), se = sgn(C) == 0 ? 0 : sgn(e);
  if (se == 0 || sp == se) return sp;
  if (sp == 0) return se;
  // P^2 - e^2 C = (a^2 + b^2 A + c^2 B - e^2 C + 2ab sqrt(A)) + sqrt(B) (2ac + 2bc sqrt(A))
  int t = sign_of_pair(Rational(a * a + b * b * A + c * c * B - e * e * C), Rational(2 * a * b), Rational(2 * a * c),
                       Rational(2 * b * c), A, B);
  return t > 0 ? sp : (t < 0 ? se : 0);
}

// Is the point's distance from the segment [a, b] at least d? (a zero-length segment is a point)
bool point_segment_apart(const Point& p, const Point& a, const Point& b, const Rational& d2) {
  Point v = minus(b, a), w = minus(p, a);
  Rational vv = dot(v, v), along = dot(w, v);
  if (sgn(vv) == 0 || sgn(along) <= 0) return cmp(dot(w, w), d2) >= 0;
  if (cmp(along, vv) >= 0) {
    Point u = minus(p, b);
    return cmp(dot(u, u), d2) >= 0;
  }
  Rational across = cross(v, w);
  return cmp(Rational(across * across), Rational(d2 * vv)) >= 0;
}

// Is the point's distance from the arc at least d? Its nearest point on the circle when its
// direction from the centre lies in the closed sector, else the nearer end.
bool point_arc_apart(const Point& p, const PlacedEdge& arc, const Rational& d) {
  Point w = minus(p, arc.center);
  Rational ww = dot(w, w), d2 = d * d;
  if (sgn(ww) == 0) return cmp(arc.radius_squared, d2) >= 0;
  if (in_sector(arc, sgn(cross(arc.from, w)), sgn(cross(w, arc.to)), false)) return roots_apart(ww, arc.radius_squared, d);
  Point s = minus(p, arc.source), t = minus(p, arc.target);
  return cmp(dot(s, s), d2) >= 0 && cmp(dot(t, t), d2) >= 0;
}

bool point_edge_apart(const Point& p, const PlacedEdge& e, const Rational& d) {
  return e.arc ? point_arc_apart(p, e, d) : point_segment_apart(p, e.source, e.target, d * d);
}

bool direction_in(const PlacedEdge& arc, const Point& u) {
  return in_sector(arc, sgn(cross(arc.from, u)), sgn(cross(u, arc.to)), false);
}

// The boxes' gap along x or y is at least d: the edges are at least d apart.
bool boxes_apart(const PlacedEdge& e, const PlacedEdge& g, const Rational& d) {
  return cmp(Rational(g.box[0] - e.box[1]), d) >= 0 || cmp(Rational(e.box[0] - g.box[1]), d) >= 0 ||
         cmp(Rational(g.box[2] - e.box[3]), d) >= 0 || cmp(Rational(e.box[2] - g.box[3]), d) >= 0;
}

bool edges_apart(const PlacedEdge& e, const PlacedEdge& g, const Rational& d) {
  if (boxes_apart(e, g, d)) return true;
  if (edges_cross(e, g)) return false;
  for (const Point* p : {&e.source, &e.target})
    if (!point_edge_apart(*p, g, d)) return false;
  for (const Point* p : {&g.source, &g.target})
    if (!point_edge_apart(*p, e, d)) return false;
  if (!e.arc && !g.arc) return true;   // two segments: the closest points include an end
  if (!e.arc || !g.arc) {
    // the segment's point nearest the arc's centre, against the arc's points on that perpendicular
    const PlacedEdge& segment = e.arc ? g : e;
    const PlacedEdge& arc = e.arc ? e : g;
    Point v = minus(segment.target, segment.source);
    Rational vv = dot(v, v);
    if (sgn(vv) == 0) return true;
    Rational lambda = dot(minus(arc.center, segment.source), v) / vv;
    if (sgn(lambda) <= 0 || cmp(lambda, Rational(1)) >= 0) return true;
    Point n = minus(plus(segment.source, times(lambda, v)), arc.center);
    Rational nn = dot(n, n);
    if (sgn(nn) == 0) {   // the segment passes through the centre: both normals are at distance r
      Point normal{Rational(-v.y), v.x};
      if (direction_in(arc, normal) || direction_in(arc, times(Rational(-1), normal)))
        return cmp(arc.radius_squared, Rational(d * d)) >= 0;
      return true;
    }
    if (direction_in(arc, n) && !roots_apart(nn, arc.radius_squared, d)) return false;
    if (direction_in(arc, times(Rational(-1), n)) && !roots_reach(nn, arc.radius_squared, d)) return false;
    return true;
  }
  Point axis = minus(g.center, e.center);
  if (sgn(dot(axis, axis)) == 0) {
    // concentric: |r1 - r2| along a direction of both sectors, else the ends (checked above)
    if (direction_in(e, g.from) || direction_in(g, e.from) || direction_in(e, g.to) || direction_in(g, e.to))
      return roots_apart(e.radius_squared, g.radius_squared, d);
    return true;
  }
  // the points on the centre line c1 + s1 r1 u, c2 + s2 r2 u (u = axis / L, each in its arc):
  // their gap L + s2 r2 - s1 r1 is at least d in absolute value (three square roots)
  const Rational L2 = dot(axis, axis);
  for (int s1 : {-1, 1})
    for (int s2 : {-1, 1}) {
      if (!direction_in(e, times(Rational(s1), axis)) || !direction_in(g, times(Rational(s2), axis))) continue;
      bool above = sign_of_roots(Rational(-d), 1, L2, Rational(s2), g.radius_squared, Rational(-s1), e.radius_squared) >= 0;
      bool below = sign_of_roots(Rational(-d), -1, L2, Rational(-s2), g.radius_squared, Rational(s1), e.radius_squared) >= 0;
      if (!above && !below) return false;
    }
  return true;
}

}  // namespace

bool boundary_distance_at_least(const PlacedPart& a, const PlacedPart& b, const Rational& d) {
  for (const auto& loop : a.loops)
    for (const PlacedEdge& e : loop)
      for (const auto& other : b.loops)
        for (const PlacedEdge& g : other)
          if (!edges_apart(e, g, d)) return false;
  return true;
}

std::string overlap_evidence(const PlacedPart& a, const PlacedPart& b) {
  for (std::size_t i = 0; i < a.loops.size(); ++i)
    for (std::size_t j = 0; j < a.loops[i].size(); ++j) {
      for (std::size_t k = 0; k < b.loops.size(); ++k)
        for (std::size_t l = 0; l < b.loops[k].size(); ++l) {
          if (!boxes_meet(a.loops[i][j], b.loops[k][l])) continue;
          if (edges_cross(a.loops[i][j], b.loops[k][l]))
            return "loop " + std::to_string(i) + " edge " + std::to_string(j) + " of '" + a.name + "' crosses loop " +
                   std::to_string(k) + " edge " + std::to_string(l) + " of '" + b.name + "'";
        }
    }
  for (int side = 0; side < 2; ++side) {
    const PlacedPart& inner = side ? b : a;
    const PlacedPart& outer = side ? a : b;
    for (std::size_t i = 0; i < inner.loops.size(); ++i)
      if (!inner.loops[i].empty() && locate(outer, inner.loops[i][0].source) > 0)
        return "a vertex of loop " + std::to_string(i) + " of '" + inner.name + "' lies inside '" + outer.name + "'";
  }
  return "";
}

}  // namespace hipair::verify
