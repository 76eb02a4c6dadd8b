// The exact overlap relation at a chart point with an irrational coordinate
// (curves/algebraic_overlap.hpp), for parts bounded by segments (below) and by segments and
// arcs (CurvedRelation, further down).
//
// The parts are posed symbolically: every world vertex is a homogeneous point (X, Y, W) whose
// coordinates are polynomials in the chart coordinates (x, y) (kernels' poses over
// RationalPolynomial2: a rotation through the half-angle tangent t has W = 1 + t^2 > 0, a
// translation or a fixed part W = 1). Every predicate below is the sign of such a polynomial
// at the configuration, decided exactly by algebra::sign_at (the polynomial restricted to the
// rational coordinate, then its sign at the algebraic one: zero exactly when it shares the
// number's root, by gcd; otherwise certified by refining the isolating interval).
//
// The relation of two closed polygonal regions A and B (loops oriented with material on the
// left) is decided without intersection points:
//  1. an edge of A and an edge of B crossing properly (each edge's ends strictly on both sides
//     of the other's line) means the interiors meet;
//  2. every edge of B is cut at the vertices of A on its relative interior; a piece then meets
//     the boundary of A nowhere inside it, or lies on an edge of A: its midpoint strictly
//     inside A means overlap; on an edge of A running the same way (material on the same side)
//     means overlap; likewise every edge of A against B;
//  3. otherwise the interiors are disjoint: a component C of int A ∩ int B would have its
//     boundary in ∂A ∩ ∂B (a boundary point of C in ∂A is not in int B, by 2, so it is in ∂B;
//     likewise), which is finitely many points and shared pieces of edges; finitely many points
//     do not bound a bounded open set, so C borders a shared piece, with C on one side: material
//     of both on that side, which 2 finds. The parts touch when some vertex of one lies on the
//     other's boundary (every common point of two segments that do not cross properly is an
//     end of one of them on the other), else they are apart.
#include "curves/algebraic_overlap.hpp"
#include "algebra/ordinate.hpp"
#include "oracle/box_grid.hpp"
#include "oracle/filter_counts.hpp"

#include "algebra/near_quotient.hpp"
#include "algebra/polynomial.hpp"
#include "curves/pose.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace hipair::cspace {

namespace {

using algebra::Real;
using Poly = RationalPolynomial2;

// A homogeneous world point (X / W, Y / W) with W > 0 at every configuration.
using algebra::Interval;

// A homogeneous world point with certified enclosures of its coordinates at the configuration
// (x, y, w: filled in by SignAt::enclose before any test).
struct HPoint {
  Poly X, Y, W;
  Interval x{0, 0}, y{0, 0}, w{0, 0};
};

Interval operator-(Interval a, Interval b) { return a + Interval{-b.hi, -b.lo}; }
// the sign of an enclosed value, or 2 when the enclosure holds 0 (or a NaN bound)
int certain_sign(const Interval& v) { return v.lo > 0 ? 1 : v.hi < 0 ? -1 : 2; }

struct Segment {
  HPoint from, to;   // material on the left
};

// The exact sign of a polynomial in the chart coordinates at the point. A certified double
// filter first (session 34): the polynomial's integer numerators (over one positive
// denominator, which does not change the sign) evaluated by outward-rounded interval Horner
// over the point's box — the rational coordinate's enclosure and the algebraic one's isolating
// interval, refined once to width 2^-60 of its size; only when that interval holds 0 (or
// overflowed) is the polynomial normalised and its sign decided exactly by algebra::sign_at.
class SignAt {
 public:
  SignAt(const Real& x, const Real& y) : x_(narrowed(x)), y_(narrowed(y)), box_x_(box(x_)), box_y_(box(y_)) {}
  // at (x, (P(x) + √R(x)) / Q(x)), Q(x) != 0 of sign q, R(x) >= 0, the ordinate enclosed by
  // [lower, upper]
  SignAt(const Real& x, const RadicalOrdinate& y, int q)
      : x_(narrowed(x)), box_x_(box(x_)),
        box_y_{algebra::lower_double(y.lower), algebra::upper_double(y.upper)}, ordinate_(&y), q_(q) {}
  // the polynomial's numerators (a positive multiple of it) over the point's box
  Interval numerators(const Poly& p) const {
    Interval value{0, 0};
    for (int i = p.rows() - 1; i >= 0; --i) {
      Interval r{0, 0};
      for (int j = p.columns() - 1; j >= 0; --j) r = r * box_y_ + algebra::enclose(p.numerator(i, j));
      value = value * box_x_ + r;
    }
    return value;
  }
  // the polynomial's value at the point, enclosed (the numerators' values over the
  // denominator's enclosure; the whole line when that overflowed)
  Interval value(const Poly& poly) const {
    const Interval d = algebra::enclose(poly.denominator());
    const Interval n = numerators(poly);
    // n / d with d > 0: the hull of the end quotients, rounded outwards
    if (!(d.lo > 0)) return Interval{-__builtin_inf(), __builtin_inf()};
    const double q[4] = {n.lo / d.lo, n.lo / d.hi, n.hi / d.lo, n.hi / d.hi};
    double lo = q[0], hi = q[0];
    bool nan = false;
    for (double v : q) {
      nan = nan || v != v;
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    return nan ? Interval{-__builtin_inf(), __builtin_inf()}
               : Interval{algebra::interval_detail::down(lo), algebra::interval_detail::up(hi)};
  }
  // the point's enclosures
  void enclose(HPoint& h) const {
    h.x = value(h.X);
    h.y = value(h.Y);
    h.w = value(h.W);
  }
  int operator()(const Poly& p) const {
    if (p.is_zero()) return 0;
    const int filtered = certain_sign(numerators(p));
    if (filtered != 2) return filtered;
    IntegerPolynomial2 f = normalized_integer_polynomial(p);
    if (f.is_zero()) return 0;
    if (ordinate_) return algebra::sign_at(f, x_, *ordinate_, q_);   // Q^d f(x, (P + √R) / Q) at x, times sign(Q)^d
    if (y_.exact) return x_.exact ? algebra::sign_at(f, x_.lower, y_.lower) : algebra::sign_at(f, x_, y_.lower);
    return algebra::sign_at(f, x_.lower, y_);
  }

 private:
  static Real narrowed(const Real& r) {
    Real result = r;
    if (!result.exact) algebra::refine_dyadically(result, Rational(result.upper - result.lower) / Rational(mpz_class(1) << 60));
    return result;
  }
  static algebra::Interval box(const Real& r) {
    if (r.exact) return algebra::enclose(r.lower);
    return algebra::Interval{algebra::lower_double(r.lower), algebra::upper_double(r.upper)};
  }
  Real x_, y_;
  algebra::Interval box_x_, box_y_;
  const RadicalOrdinate* ordinate_ = nullptr;
  int q_ = 1;
};

class PolygonRelation {
 public:
  PolygonRelation(std::vector<Segment> a, std::vector<Segment> b, const SignAt& sign)
      : parts_{std::move(a), std::move(b)}, sign_(sign) {}

  Overlap run() {
    for (const Segment& ea : parts_[0])
      for (const Segment& eb : parts_[1])
        if (cross_properly(ea, eb)) return Overlap::overlapping;
    for (int side = 0; side < 2; ++side)
      for (const Segment& edge : parts_[side])
        if (pieces_overlap(edge, side)) return Overlap::overlapping;
    return touching_ ? Overlap::touching : Overlap::apart;
  }

 private:
  // sign of the orientation of (p, q, r): the 3 x 3 determinant of the homogeneous rows, whose
  // sign is the orientation's (every W > 0)
  int orientation(const HPoint& p, const HPoint& q, const HPoint& r) const {
    const int filtered = certain_sign(p.x * (q.y * r.w - r.y * q.w) - p.y * (q.x * r.w - r.x * q.w) + p.w * (q.x * r.y - r.x * q.y));
    if (filtered != 2) return filtered;
    Poly det = p.X * (q.Y * r.W - r.Y * q.W) - p.Y * (q.X * r.W - r.X * q.W) + p.W * (q.X * r.Y - r.X * q.Y);
    return sign_(det);
  }
  // sign of (p - q) . (s - r)
  int along(const HPoint& p, const HPoint& q, const HPoint& r, const HPoint& s) const {
    const int filtered = certain_sign((p.x * q.w - q.x * p.w) * (s.x * r.w - r.x * s.w) + (p.y * q.w - q.y * p.w) * (s.y * r.w - r.y * s.w));
    if (filtered != 2) return filtered;
    Poly dx = p.X * q.W - q.X * p.W, dy = p.Y * q.W - q.Y * p.W;
    Poly ex = s.X * r.W - r.X * s.W, ey = s.Y * r.W - r.Y * s.W;
    return sign_(dx * ex + dy * ey);
  }
  // sign of p.y - q.y
  int compare_y(const HPoint& p, const HPoint& q) const {
    const int filtered = certain_sign(p.y * q.w - q.y * p.w);
    return filtered != 2 ? filtered : sign_(p.Y * q.W - q.Y * p.W);
  }
  static HPoint midpoint(const HPoint& p, const HPoint& q) {
    return HPoint{p.X * q.W + q.X * p.W, p.Y * q.W + q.Y * p.W, Poly(2) * p.W * q.W,
                  p.x * q.w + q.x * p.w, p.y * q.w + q.y * p.w, Interval{2, 2} * p.w * q.w};
  }
  // p on the closed segment
  bool on_segment(const HPoint& p, const Segment& e) const {
    return orientation(e.from, e.to, p) == 0 && along(p, e.from, e.from, e.to) >= 0 && along(p, e.to, e.to, e.from) >= 0;
  }
  // p on the open segment
  bool inside_segment(const HPoint& p, const Segment& e) const {
    return orientation(e.from, e.to, p) == 0 && along(p, e.from, e.from, e.to) > 0 && along(p, e.to, e.to, e.from) > 0;
  }

  bool cross_properly(const Segment& a, const Segment& b) const {
    int o1 = orientation(a.from, a.to, b.from), o2 = orientation(a.from, a.to, b.to);
    if (o1 * o2 >= 0) return false;
    int o3 = orientation(b.from, b.to, a.from), o4 = orientation(b.from, b.to, a.to);
    return o3 * o4 < 0;
  }

  // Edge `edge` of part `side` cut at the other part's vertices on it: does a piece lie in the
  // other part's interior, or on an edge of it with material on the same side?
  bool pieces_overlap(const Segment& edge, int side) {
    const std::vector<Segment>& other = parts_[1 - side];
    std::vector<HPoint> cuts{edge.from};
    for (const Segment& e : other) {
      if (on_segment(e.from, edge)) touching_ = true;
      if (inside_segment(e.from, edge)) cuts.push_back(e.from);
    }
    // along the edge from its source (distinct points: vertices of a loop are distinct)
    std::sort(cuts.begin() + 1, cuts.end(),
              [&](const HPoint& p, const HPoint& q) { return along(q, p, edge.from, edge.to) > 0; });
    cuts.push_back(edge.to);
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      HPoint m = midpoint(cuts[i], cuts[i + 1]);
      int crossings = 0;
      for (const Segment& e : other) {
        if (on_segment(m, e)) {
          // the piece lies on e (it meets the other boundary nowhere else): overlap iff the
          // materials (on the left of both) are on the same side
          if (along(edge.to, edge.from, e.from, e.to) > 0) return true;
          crossings = -1;
          break;
        }
        const bool from_above = compare_y(e.from, m) > 0, to_above = compare_y(e.to, m) > 0;
        if (from_above == to_above) continue;
        // m is left of the upward crossing point's abscissa iff orientation and rise agree
        if ((orientation(e.from, e.to, m) > 0) == (compare_y(e.to, e.from) > 0)) ++crossings;
      }
      if (crossings > 0 && crossings % 2 == 1) return true;
    }
    return false;
  }

  std::array<std::vector<Segment>, 2> parts_;
  const SignAt& sign_;
  bool touching_ = false;
};

Poly constant(const Rational& value) { return Poly(value); }

// W world = w (pivot + shift) + [c -s; s c] (p - pivot)
HPoint place(const kernels::Pose<Poly>& pose, const Point& p) {
  Poly dx = constant(p.x) - pose.pivot.x, dy = constant(p.y) - pose.pivot.y;
  return HPoint{pose.w * (pose.pivot.x + pose.shift.x) + pose.c * dx - pose.s * dy,
                pose.w * (pose.pivot.y + pose.shift.y) + pose.s * dx + pose.c * dy, pose.w};
}

// The part's loops as world segments at the symbolic pose.
std::vector<Segment> posed_segments(const Part& part, const kernels::Pose<Poly>& pose) {
  std::vector<Segment> result;
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) result.push_back(Segment{place(pose, edge.source), place(pose, edge.target)});
  return result;
}

// ============================================================================ parts with arcs
//
// Both parts are scaled by the positive common weight W = w1 w2 (a similarity of the scene at
// the configuration, so the relation is unchanged): every point is a pair of polynomials
// (W x, W y), an arc's squared radius r^2 W^2. The relation follows the rational oracle's
// argument (src/oracle/overlap.cpp) without ever forming an irrational point:
//  1. two edges crossing transversally at a point interior to both means overlap: segments
//     crossing properly; a line or circle cutting a circle (discriminant > 0) at a point inside
//     the segment and the arc's open sector, each such point of the form a + b sqrt(K) with
//     polynomial a, b, K, its tests signs of u + v sqrt(K) (sign_with_root);
//  2. at every other common point of the boundaries — a vertex of one part on the other's
//     boundary, a tangency of the interiors of two edges (discriminant 0) — the boundary germs
//     of both parts (tangent direction, then signed curvature 0 or +-1/r) are sorted around
//     the point; overlap iff some sector between consecutive germs is material of both (a
//     germ tied with the other part's germ is a shared piece: the empty sector between them
//     is skipped, the one beside decides whether the materials are on the same side). Only
//     directions are needed: at a tangency of two arcs the point's direction from each centre
//     is a polynomial multiple of the centres' difference;
//  3. a loop with no common point lies in the other part's interior or outside it: one of
//     its vertices is located by ray parity (a vertex of the other part at the ray's height:
//     the next vertex; none usable: undecided);
//  4. otherwise the interiors are disjoint (no boundary piece of one is inside the other, by
//     2 and 3, and a component of the interiors' intersection bounded by common points and
//     shared pieces only would show at a shared piece's end, by 2); touching iff a common point.

struct V2 {
  Poly x, y;
};
V2 operator-(const V2& a, const V2& b) { return V2{a.x - b.x, a.y - b.y}; }
V2 scaled(const Poly& k, const V2& a) { return V2{k * a.x, k * a.y}; }
V2 negated(const V2& a) { return V2{-a.x, -a.y}; }
V2 left_perpendicular(const V2& a) { return V2{-a.y, a.x}; }
Poly cross(const V2& a, const V2& b) { return a.x * b.y - a.y * b.x; }
Poly dot(const V2& a, const V2& b) { return a.x * b.x + a.y * b.y; }

// A certified axis-parallel box (the broad phase): two features whose boxes are apart cannot
// meet. A NaN bound never separates (every comparison with it is false).
struct Box {
  Interval x{0, 0}, y{0, 0};
};
bool apart(const Box& a, const Box& b) {
  return a.x.hi < b.x.lo || b.x.hi < a.x.lo || a.y.hi < b.y.lo || b.y.hi < a.y.lo;
}
// the smaller lower bound, the larger upper one (-inf, +inf when either is NaN)
double lower(double a, double b) { return a != a || b != b ? -__builtin_inf() : a < b ? a : b; }
double upper(double a, double b) { return a != a || b != b ? __builtin_inf() : a > b ? a : b; }
Box hull(const Box& a, const Box& b) {
  return Box{Interval{lower(a.x.lo, b.x.lo), upper(a.x.hi, b.x.hi)}, Interval{lower(a.y.lo, b.y.lo), upper(a.y.hi, b.y.hi)}};
}
// the box of the point (x, y) turned by -90 degrees, (y, -x)
Box turned_box(const Box& b) { return Box{b.y, Interval{-b.x.hi, -b.x.lo}}; }
// enclosed vectors: the interval shadows of V2's cross and dot products
Box operator-(const Box& a, const Box& b) { return Box{a.x - b.x, a.y - b.y}; }
Interval cross(const Box& a, const Box& b) { return a.x * b.y - a.y * b.x; }
Interval dot(const Box& a, const Box& b) { return a.x * b.x + a.y * b.y; }
Interval exactly(double v) { return Interval{v, v}; }
Interval operator-(Interval a) { return Interval{-a.hi, -a.lo}; }
// an enclosure of the square root of a value enclosed by v (its non-negative part)
Interval root(const Interval& v) {
  using algebra::interval_detail::down;
  using algebra::interval_detail::up;
  const double lo = v.lo > 0 ? down(std::sqrt(v.lo)) : 0;
  return Interval{lo > 0 ? lo : 0, v.hi >= 0 ? up(std::sqrt(v.hi)) : 0};
}
// a sign certain from an enclosure: -1, 0 only for [0, 0], +1, or 2 (uncertain)
int known_sign(const Interval& v) { return v.lo == 0 && v.hi == 0 ? 0 : certain_sign(v); }

struct CurvedEdge {
  bool arc = false;
  bool ccw = true;
  bool full = false;
  V2 from, to, center;
  Poly radius_squared;
  std::size_t loop = 0;
  Box from_box, box;   // enclosures of the source vertex and of the whole edge
  // an arc's enclosures: its centre, its squared radius, and the directions from the centre
  // to the ends of its counter-clockwise sector, start and end, with the sign of their cross
  // product (2: uncertain)
  Box to_box, center_box, start, end;
  Interval radius_squared_box{0, 0};
  int turn = 2;
  const Edge* source = nullptr;   // the model's edge, posed as polynomials only when needed
  bool posed = false;
};

// A part's symbolic pose scaled by the other part's weight (points are W (x, y), W = w1 w2).
struct ScaledPose {
  const kernels::Pose<Poly>* pose = nullptr;
  const Poly* other_w = nullptr;
};

// A boundary germ at a common point: its tangent direction, signed curvature (sign, r^2),
// whether the part's boundary leaves the point along it (material on its left) or arrives.
struct Germ {
  int part = 0;
  bool outgoing = true;
  V2 direction;
  int curvature = 0;   // 0 straight, +1 turning left (1/r), -1 turning right
  Poly radius_squared;
};

class CurvedRelation {
 public:
  CurvedRelation(std::array<std::vector<std::vector<CurvedEdge>>, 2> loops, std::array<ScaledPose, 2> poses, const SignAt& sign)
      : loops_(std::move(loops)), poses_(poses), sign_(sign) {
    for (int side = 0; side < 2; ++side) {
      common_[side].assign(loops_[side].size(), false);
      const kernels::Pose<Poly>& pose = *poses_[side].pose;
      const Interval c = sign_.value(pose.c), s = sign_.value(pose.s), w = sign_.value(pose.w), ow = sign_.value(*poses_[side].other_w);
      const Box pivot{sign_.value(pose.pivot.x), sign_.value(pose.pivot.y)}, shift{sign_.value(pose.shift.x), sign_.value(pose.shift.y)};
      // the interval shadow of place() times the other weight
      auto at = [&](const Point& p) {
        const Interval dx = algebra::enclose(p.x) - pivot.x, dy = algebra::enclose(p.y) - pivot.y;
        return Box{(w * (pivot.x + shift.x) + c * dx - s * dy) * ow, (w * (pivot.y + shift.y) + s * dx + c * dy) * ow};
      };
      const Interval weight = w * ow;
      for (auto& loop : loops_[side])
        for (CurvedEdge& e : loop) {
          e.from_box = at(e.source->source);
          e.to_box = at(e.source->target);
          if (e.arc) {
            e.center_box = at(e.source->center);
            e.radius_squared_box = algebra::enclose(e.source->radius_squared) * weight * weight;
          }
          bound(e);
        }
    }
    // Session 74 (growth74): the pairs of edges whose boxes meet (`near_`), found through a grid
    // of the second part's boxes (BoxGrid) instead of testing every pair: every loop below
    // skipped the other pairs at once (interiors_meet and maybe_on_edge are 0 on apart boxes),
    // so the same pairs are visited in the same order (the first part's edges in boundary
    // order, each one's partners ascending), at a cost that follows the edges near the other
    // part, not the product of the parts' sizes (n^2 per call on an n-tooth gear pair).
    for (int side = 0; side < 2; ++side)
      for (auto& loop : loops_[side])
        for (CurvedEdge& e : loop) flat_[side].push_back(&e);
    std::vector<BoxGrid::Bounds> boxes;
    boxes.reserve(flat_[1].size());
    for (const CurvedEdge* b : flat_[1]) boxes.push_back(BoxGrid::Bounds{b->box.x.lo, b->box.x.hi, b->box.y.lo, b->box.y.hi});
    // (set_lazy_placement(false): every pair tested, as before; tests compare the two)
    const bool gridded = lazy_placement();
    const BoxGrid grid = gridded ? BoxGrid(boxes) : BoxGrid();
    near_[0].resize(flat_[0].size());
    near_[1].resize(flat_[1].size());
    std::vector<std::size_t> listed;
    for (std::size_t i = 0; i < flat_[0].size(); ++i) {
      CurvedEdge& a = *flat_[0][i];
      if (gridded) {
        grid.query(BoxGrid::Bounds{a.box.x.lo, a.box.x.hi, a.box.y.lo, a.box.y.hi}, listed);
      } else {
        listed.resize(flat_[1].size());
        std::iota(listed.begin(), listed.end(), std::size_t{0});
      }
      for (std::size_t j : listed) {
        CurvedEdge& b = *flat_[1][j];
        if (apart(a.box, b.box)) continue;
        near_[0][i].push_back(j);
        near_[1][j].push_back(i);
        // the polynomials of every edge whose box meets one of the other part's
        pose(0, a);
        pose(1, b);
      }
    }
  }

  std::optional<Overlap> run() {
    // two interiors certainly crossing (the double filter alone): overlapping
    for (std::size_t i = 0; i < flat_[0].size(); ++i)
      for (std::size_t j : near_[0][i])
        if (interiors_meet(*flat_[0][i], *flat_[1][j]) == 1) return Overlap::overlapping;
    for (int side = 0; side < 2; ++side)
      for (std::size_t l = 0, at = 0; l < loops_[side].size(); ++l)
        for (std::size_t k = 0; k < loops_[side][l].size(); ++k, ++at)
          if (vertex_overlaps(side, l, k, at)) return Overlap::overlapping;
    for (std::size_t i = 0; i < flat_[0].size(); ++i)
      for (std::size_t j : near_[0][i]) {
        const CurvedEdge& a = *flat_[0][i];
        const CurvedEdge& b = *flat_[1][j];
        if (const int meet = interiors_meet(a, b); meet == 1 || (meet == 2 && interiors_overlap(a, b))) return Overlap::overlapping;
      }
    for (int side = 0; side < 2; ++side)
      for (std::size_t l = 0; l < loops_[side].size(); ++l) {
        if (common_[side][l]) continue;
        std::optional<bool> inside = loop_inside(loops_[side][l], 1 - side);
        if (!inside) return std::nullopt;
        if (*inside) return Overlap::overlapping;
      }
    return touching_ ? Overlap::touching : Overlap::apart;
  }

 private:
  int sign(const Poly& p) const { return sign_(p); }
  // the edge's points as polynomials, once
  void pose(int side, CurvedEdge& e) const {
    if (e.posed) return;
    e.posed = true;
    const kernels::Pose<Poly>& pose = *poses_[side].pose;
    const Poly& other_w = *poses_[side].other_w;
    auto at = [&](const Point& p) {
      HPoint h = place(pose, p);
      return V2{h.X * other_w, h.Y * other_w};
    };
    e.from = at(e.source->source);
    e.to = at(e.source->target);
    if (e.arc) {
      e.center = at(e.source->center);
      const Poly w = pose.w * other_w;
      e.radius_squared = constant(e.source->radius_squared) * w * w;
    }
  }

  // The edge's certified boxes: a segment's is its ends' hull; an arc's adds each extreme of
  // its circle (centre +- radius along an axis) whose direction from the centre is not
  // certainly outside the arc's sector.
  void bound(CurvedEdge& e) const {
    using algebra::interval_detail::down;
    using algebra::interval_detail::up;
    e.box = hull(e.from_box, e.to_box);
    if (!e.arc) return;
    const Box& c = e.center_box;
    const double r = root(e.radius_squared_box).hi;   // an upper bound of the radius
    e.start = (e.ccw ? e.from_box : e.to_box) - c;
    e.end = (e.ccw ? e.to_box : e.from_box) - c;
    e.turn = e.full ? 2 : certain_sign(cross(e.start, e.end));
    // each extreme of the circle unless its direction is certainly outside the closed sector
    auto reaches = [&](double dx, double dy) { return in_sector(e, Box{exactly(dx), exactly(dy)}) != 0; };
    if (reaches(1, 0)) e.box.x.hi = upper(e.box.x.hi, up(c.x.hi + r));
    if (reaches(-1, 0)) e.box.x.lo = lower(e.box.x.lo, down(c.x.lo - r));
    if (reaches(0, 1)) e.box.y.hi = upper(e.box.y.hi, up(c.y.hi + r));
    if (reaches(0, -1)) e.box.y.lo = lower(e.box.y.lo, down(c.y.lo - r));
  }

  // The certified double filter of the predicates below (their interval shadows over the
  // enclosures): 1 or 0 when certain, 2 when the exact predicate must decide.
  //
  // Is the enclosed direction v strictly inside the arc's sector (1), certainly outside its
  // closed sector (0)? Sweep < 180 degrees: inside iff cross(start, v) > 0 and cross(v, end) >
  // 0; sweep > 180: inside iff cross(start, v) > 0 or cross(v, end) > 0, outside the closed
  // sector iff both are < 0 (v strictly inside the complementary sector); a full circle holds
  // every direction but its start's; a sweep near 0, 180 or 360 degrees is uncertain.
  static int in_sector(const CurvedEdge& e, const Box& v) {
    const int a = certain_sign(cross(e.start, v)), b = certain_sign(cross(v, e.end));
    if (e.full) return a == 1 || a == -1 ? 1 : 2;
    if (e.turn == 1) return a == 1 && b == 1 ? 1 : a == -1 || b == -1 ? 0 : 2;
    if (e.turn == -1) return a == 1 || b == 1 ? 1 : a == -1 && b == -1 ? 0 : 2;
    return 2;
  }
  // is the enclosed point p certainly off edge e (0), or uncertain (2)?
  static int maybe_on_edge(const Box& p, const CurvedEdge& e) {
    if (apart(p, e.box)) return 0;
    const Box v = e.arc ? p - e.center_box : Box{};
    const int off = e.arc ? certain_sign(dot(v, v) - e.radius_squared_box) : certain_sign(cross(e.to_box - e.from_box, p - e.from_box));
    return off == 1 || off == -1 ? 0 : 2;
  }
  // Do the interiors of a and b certainly cross (1), certainly have no common point (0)?
  static int interiors_meet(const CurvedEdge& a, const CurvedEdge& b) {
    if (apart(a.box, b.box)) return 0;
    if (!a.arc && !b.arc) {
      const Box da = a.to_box - a.from_box, db = b.to_box - b.from_box;
      const int o1 = known_sign(cross(da, b.from_box - a.from_box)), o2 = known_sign(cross(da, b.to_box - a.from_box));
      const int o3 = known_sign(cross(db, a.from_box - b.from_box)), o4 = known_sign(cross(db, a.to_box - b.from_box));
      auto separated = [](int p, int q) { return (p == 1 && q == 1) || (p == -1 && q == -1); };
      if (separated(o1, o2) || separated(o3, o4)) return 0;
      return o1 * o2 == -1 && o3 * o4 == -1 ? 1 : 2;
    }
    if (!a.arc || !b.arc) {
      const CurvedEdge& s = a.arc ? b : a;
      const CurvedEdge& c = a.arc ? a : b;
      // s.from + u d on the circle: a u^2 + 2 b u + q = 0, disc = b^2 - a q
      const Box d = s.to_box - s.from_box, f = s.from_box - c.center_box;
      const Interval qa = dot(d, d), qb = dot(d, f), qq = dot(f, f) - c.radius_squared_box;
      const Interval disc = qb * qb - qa * qq;
      const int sd = certain_sign(disc);
      if (sd == -1) return 0;
      // both ends strictly inside the disk: the segment is inside it
      if (certain_sign(qq) == -1 && certain_sign(dot(s.to_box - c.center_box, s.to_box - c.center_box) - c.radius_squared_box) == -1)
        return 0;
      if (sd != 1 || !(qa.lo > 0)) return 2;
      // u = (-b +- sqrt(disc)) / a, the point's direction from the centre f + u d
      int result = 0;
      for (const double pm : {1.0, -1.0}) {
        const Interval uu = (-qb + exactly(pm) * root(disc)) *
                            Interval{algebra::interval_detail::down(1 / qa.hi), algebra::interval_detail::up(1 / qa.lo)};
        const int inside = uu.lo > 0 && uu.hi < 1 ? 1 : uu.hi < 0 || uu.lo > 1 ? 0 : 2;
        const int on_arc = inside == 0 ? 0 : in_sector(c, Box{f.x + uu * d.x, f.y + uu * d.y});
        if (inside == 1 && on_arc == 1) return 1;
        if (inside != 0 && on_arc != 0) result = 2;
      }
      return result;
    }
    const Box e = b.center_box - a.center_box;
    const Interval d2 = dot(e, e), ra = root(a.radius_squared_box), rb = root(b.radius_squared_box);
    const Interval outer = d2 - (ra + rb) * (ra + rb), inner = d2 - (ra - rb) * (ra - rb);
    if (certain_sign(outer) == 1 || certain_sign(inner) == -1) return 0;
    if (certain_sign(outer) != -1 || certain_sign(inner) != 1) return 2;
    // the circles cross at (l e +- sqrt(k) n) / d^2 from a's centre, ((l - d^2) e +- sqrt(k) n)
    // / d^2 from b's, n = e turned left, l = (d^2 + ra^2 - rb^2) / 2, k = ra^2 d^2 - l^2
    const Interval l = (d2 + a.radius_squared_box - b.radius_squared_box) * exactly(0.5);
    const Interval rk = root(a.radius_squared_box * d2 - l * l), lb = l - d2;
    int result = 0;
    for (const double pm : {1.0, -1.0}) {
      const Interval nx = exactly(-pm) * e.y * rk, ny = exactly(pm) * e.x * rk;
      const int on_a = in_sector(a, Box{l * e.x + nx, l * e.y + ny});
      const int on_b = on_a == 0 ? 0 : in_sector(b, Box{lb * e.x + nx, lb * e.y + ny});
      if (on_a == 1 && on_b == 1) return 1;
      if (on_a != 0 && on_b != 0) result = 2;
    }
    return result;
  }
  // sign of u + v sqrt(w), w >= 0 at the point
  int sign_with_root(const Poly& u, const Poly& v, const Poly& w) const {
    const int su = sign(u), sv = sign(v);
    if (sv == 0 || sign(w) == 0) return su;
    if (su == 0) return sv;
    if (su == sv) return su;
    const int c = sign(u * u - v * v * w);
    return c > 0 ? su : c < 0 ? sv : 0;
  }
  bool same_point(const V2& p, const V2& q) const { return sign(p.x - q.x) == 0 && sign(p.y - q.y) == 0; }
  bool same_direction(const V2& a, const V2& b) const { return sign(cross(a, b)) == 0 && sign(dot(a, b)) > 0; }

  // Is the direction a + b sqrt(k) (b, k may be zero) strictly inside the arc's sector, or on
  // its closed sector (`closed`)? The sector runs counter-clockwise from `start` to `end`.
  bool in_sector(const CurvedEdge& e, const V2& a, const V2& b, const Poly& k, bool closed) const {
    const V2 start = e.ccw ? e.from - e.center : e.to - e.center, end = e.ccw ? e.to - e.center : e.from - e.center;
    auto cross_sign = [&](const V2& s, bool s_first) {   // sign of cross(s, v) or cross(v, s)
      Poly u = cross(s, a), v = cross(s, b);
      return s_first ? sign_with_root(u, v, k) : -sign_with_root(u, v, k);
    };
    auto along = [&](const V2& s) {   // v in the direction of s
      return cross_sign(s, true) == 0 && sign_with_root(dot(s, a), dot(s, b), k) > 0;
    };
    if (e.full) return closed || !along(start);
    if (closed && (along(start) || along(end))) return true;
    const int turn = sign(cross(start, end));
    if (turn > 0) return cross_sign(start, true) > 0 && cross_sign(end, false) > 0;
    if (turn == 0) return cross_sign(start, true) > 0;
    return !(cross_sign(end, true) >= 0 && cross_sign(start, false) >= 0);
  }
  bool in_sector(const CurvedEdge& e, const V2& a, bool closed) const { return in_sector(e, a, V2{Poly(0), Poly(0)}, Poly(0), closed); }

  // p on the edge (closed), or on its relative interior (`open`)
  bool on_edge(const V2& p, const CurvedEdge& e, bool open) const {
    if (!e.arc) {
      const V2 d = e.to - e.from, f = p - e.from;
      if (sign(cross(d, f)) != 0) return false;
      const int s0 = sign(dot(f, d)), s1 = sign(dot(d, d) - dot(f, d));
      return open ? s0 > 0 && s1 > 0 : s0 >= 0 && s1 >= 0;
    }
    const V2 v = p - e.center;
    if (sign(dot(v, v) - e.radius_squared) != 0) return false;
    if (open && (same_point(p, e.from) || same_point(p, e.to))) return false;
    return in_sector(e, v, true);
  }

  // the germs of edge e leaving (outgoing) or arriving at a point, `radial` the point's
  // direction from an arc's centre (a positive multiple)
  Germ germ(int part, const CurvedEdge& e, bool outgoing, const V2& radial) const {
    Germ g;
    g.part = part;
    g.outgoing = outgoing;
    if (!e.arc) {
      g.direction = outgoing ? e.to - e.from : e.from - e.to;
      return g;
    }
    const V2 travel = e.ccw ? left_perpendicular(radial) : negated(left_perpendicular(radial));
    g.direction = outgoing ? travel : negated(travel);
    g.curvature = (e.ccw == outgoing) ? 1 : -1;
    g.radius_squared = e.radius_squared;
    return g;
  }

  // cyclic order of germs around the point: by direction's angle, then by signed curvature
  // (turning more to the left is further counter-clockwise); 0 when they coincide
  int compare(const Germ& g, const Germ& h) const {
    auto half = [&](const V2& d) {
      const int sy = sign(d.y);
      return sy > 0 || (sy == 0 && sign(d.x) > 0) ? 0 : 1;
    };
    const int hg = half(g.direction), hh = half(h.direction);
    if (hg != hh) return hg < hh ? -1 : 1;
    const int c = sign(cross(g.direction, h.direction));
    if (c != 0) return c > 0 ? -1 : 1;
    if (g.curvature != h.curvature) return g.curvature < h.curvature ? -1 : 1;
    if (g.curvature == 0) return 0;
    // same turn: 1/r larger (r^2 smaller) turns more
    const int r = sign(g.radius_squared - h.radius_squared);
    return g.curvature > 0 ? -r : r;
  }

  // Is some sector between consecutive germs material of both parts?
  bool germs_overlap(std::vector<Germ> germs) const {
    std::sort(germs.begin(), germs.end(), [&](const Germ& g, const Germ& h) { return compare(g, h) < 0; });
    const std::size_t n = germs.size();
    for (std::size_t j = 0; j < n; ++j) {
      if (compare(germs[j], germs[(j + 1) % n]) == 0) continue;   // empty sector
      bool both = true;
      for (int part = 0; part < 2 && both; ++part) {
        bool material = false;
        for (std::size_t step = 1; step <= n; ++step) {
          const Germ& next = germs[(j + step) % n];
          if (next.part != part) continue;
          material = !next.outgoing;
          break;
        }
        both = material;
      }
      if (both) return true;
    }
    return false;
  }

  // the germs of part `side` at a point on edge e (a vertex of it when equal to an end)
  void edge_germs(int side, const CurvedEdge& e, const V2& p, std::vector<Germ>& germs) const {
    const bool at_from = same_point(p, e.from), at_to = same_point(p, e.to);
    const V2 radial = e.arc ? p - e.center : V2{};
    if (at_from || !at_to) germs.push_back(germ(side, e, true, radial));
    if (at_to || !at_from) germs.push_back(germ(side, e, false, radial));
  }

  // vertex k of loop l of part `side` (the source of edge k) on the other part's boundary:
  // do the parts overlap near it?
  // (`at`: the edge's place in flat_[side]; the other part's edges that may hold the vertex are
  // among those whose boxes meet its edge's, near_[side][at]: the vertex's box lies in its
  // edge's box, and maybe_on_edge is 0 on apart boxes; they are visited in boundary order)
  bool vertex_overlaps(int side, std::size_t l, std::size_t k, std::size_t at) {
    const std::vector<CurvedEdge>& loop = loops_[side][l];
    const V2& p = loop[k].from;
    std::vector<Germ> germs;
    for (std::size_t j : near_[side][at]) {
      const CurvedEdge& e = *flat_[1 - side][j];
      if (maybe_on_edge(loop[k].from_box, e) != 0 && on_edge(p, e, false)) {
        edge_germs(1 - side, e, p, germs);
        common_[1 - side][e.loop] = true;
      }
    }
    if (germs.empty()) return false;
    common_[side][l] = true;
    touching_ = true;
    const CurvedEdge& in = loop[(k + loop.size() - 1) % loop.size()];
    germs.push_back(germ(side, loop[k], true, loop[k].arc ? p - loop[k].center : V2{}));
    germs.push_back(germ(side, in, false, in.arc ? p - in.center : V2{}));
    return germs_overlap(std::move(germs));
  }

  // a tangency of the interiors of a and b at a point whose direction from each arc's centre is
  // radial_a, radial_b: the four germs
  bool tangency_overlaps(const CurvedEdge& a, const V2& radial_a, const CurvedEdge& b, const V2& radial_b) {
    common_[0][a.loop] = true;
    common_[1][b.loop] = true;
    touching_ = true;
    std::vector<Germ> germs{germ(0, a, true, radial_a), germ(0, a, false, radial_a), germ(1, b, true, radial_b),
                            germ(1, b, false, radial_b)};
    return germs_overlap(std::move(germs));
  }

  // the interiors of segment s (part side_s) and arc c: crossing (overlap) or tangent
  bool segment_arc(const CurvedEdge& s, const CurvedEdge& c, bool segment_first) {
    // s.from + u d on the circle: a u^2 + 2 b u + q = 0
    const V2 d = s.to - s.from, f = s.from - c.center;
    const Poly a = dot(d, d), b = dot(d, f), q = dot(f, f) - c.radius_squared;
    const Poly disc = b * b - a * q;
    const int sd = sign(disc);
    if (sd < 0) return false;
    // u = (-b +- sqrt(disc)) / a; the point's direction from the centre a f + (-b +- sqrt) d
    const V2 base = scaled(a, f) - scaled(b, d);
    if (sd > 0) {
      for (const Poly& pm : {Poly(1), Poly(-1)}) {
        const bool inside_segment = sign_with_root(-b, pm, disc) > 0 && sign_with_root(-b - a, pm, disc) < 0;
        if (inside_segment && in_sector(c, base, scaled(pm, d), disc, false)) return true;
      }
      return false;
    }
    if (!(sign(-b) > 0 && sign(-b - a) < 0) || !in_sector(c, base, false)) return false;
    return segment_first ? tangency_overlaps(s, V2{}, c, base) : tangency_overlaps(c, base, s, V2{});
  }

  bool arc_arc(const CurvedEdge& a, const CurvedEdge& b) {
    const V2 e = b.center - a.center;
    const Poly d2 = dot(e, e);
    if (sign(d2) == 0) return false;   // concentric: disjoint or the same circle (vertices decide)
    const Poly base = d2 - a.radius_squared - b.radius_squared, product = a.radius_squared * b.radius_squared;
    const int outer = sign_with_root(base, Poly(-2), product);   // d^2 - (r1 + r2)^2
    const int inner = sign_with_root(base, Poly(2), product);    // d^2 - (r1 - r2)^2
    if (outer > 0 || inner < 0) return false;
    const Poly l = (d2 + a.radius_squared - b.radius_squared) * Poly(Rational(1, 2));
    const V2 from_a = scaled(l, e), from_b = scaled(l - d2, e);
    if (outer < 0 && inner > 0) {
      const Poly k = a.radius_squared * d2 - l * l;
      const V2 n = left_perpendicular(e);
      for (const Poly& pm : {Poly(1), Poly(-1)})
        if (in_sector(a, from_a, scaled(pm, n), k, false) && in_sector(b, from_b, scaled(pm, n), k, false)) return true;
      return false;
    }
    if (!in_sector(a, from_a, false) || !in_sector(b, from_b, false)) return false;
    return tangency_overlaps(a, from_a, b, from_b);
  }

  // a (part 0) and b (part 1) meeting at a point interior to both: crossing, or overlapping
  // near a tangency
  bool interiors_overlap(const CurvedEdge& a, const CurvedEdge& b) {
    if (!a.arc && !b.arc) {
      const int o1 = sign(cross(a.to - a.from, b.from - a.from)), o2 = sign(cross(a.to - a.from, b.to - a.from));
      if (o1 * o2 >= 0) return false;
      const int o3 = sign(cross(b.to - b.from, a.from - b.from)), o4 = sign(cross(b.to - b.from, a.to - b.from));
      return o3 * o4 < 0;
    }
    if (!a.arc) return segment_arc(a, b, true);
    if (!b.arc) return segment_arc(b, a, false);
    return arc_arc(a, b);
  }

  // Does the loop (no common point with part `other`'s boundary) lie in that part's interior?
  // Ray parity from one of its vertices to +x, or else to +y (the scene turned by -90 degrees,
  // which keeps orientations); nullopt when every vertex has a vertex of the other part at its
  // height and at its abscissa.
  std::optional<bool> loop_inside(std::vector<CurvedEdge>& loop, int other) {
    for (CurvedEdge& e : loop) pose(1 - other, e);
    for (auto& l : loops_[other])
      for (CurvedEdge& e : l) pose(other, e);
    for (const bool turned : {false, true}) {
      auto turn = [turned](const V2& v) { return turned ? V2{v.y, -v.x} : v; };
      std::vector<CurvedEdge> edges;
      for (const auto& l : loops_[other])
        for (const CurvedEdge& e : l) {
          CurvedEdge t = e;
          t.from = turn(e.from);
          t.to = turn(e.to);
          if (e.arc) t.center = turn(e.center);
          if (turned) t.box = turned_box(e.box);
          edges.push_back(std::move(t));
        }
      for (const CurvedEdge& start : loop)
        if (std::optional<int> crossings = ray_crossings(turn(start.from), turned ? turned_box(start.from_box) : start.from_box, edges))
          return *crossings % 2 == 1;
    }
    return std::nullopt;
  }

  // The crossings of the ray from p to +x with the edges; nullopt when the ray's line passes
  // through a vertex or touches a circle.
  // Edges whose boxes lie certainly above, below or left of p's are skipped: the ray meets
  // none of their points.
  std::optional<int> ray_crossings(const V2& p, const Box& p_box, const std::vector<CurvedEdge>& edges) const {
    int crossings = 0;
    for (const CurvedEdge& e : edges) {
      if (e.box.y.hi < p_box.y.lo || p_box.y.hi < e.box.y.lo || e.box.x.hi < p_box.x.lo) continue;
      const int from_side = sign(e.from.y - p.y), to_side = sign(e.to.y - p.y);
      if (from_side == 0 || to_side == 0) return std::nullopt;
      if (!e.arc) {
        if (from_side == to_side) continue;
        // p left of the crossing's abscissa iff orientation and rise agree
        if ((sign(cross(e.to - e.from, p - e.from)) > 0) == (to_side > from_side)) ++crossings;
        continue;
      }
      const Poly dy = p.y - e.center.y, h = e.radius_squared - dy * dy;
      const int sh = sign(h);
      if (sh < 0) continue;
      if (sh == 0) return std::nullopt;   // the ray's line tangent to the circle
      // the circle's points (cx +- sqrt(h), py): right of p, on the arc (not at its ends)
      for (const Poly& pm : {Poly(1), Poly(-1)})
        if (sign_with_root(e.center.x - p.x, pm, h) > 0 && in_sector(e, V2{Poly(0), dy}, V2{pm, Poly(0)}, h, true))
          ++crossings;
    }
    return crossings;
  }

  std::array<std::vector<std::vector<CurvedEdge>>, 2> loops_;
  std::array<ScaledPose, 2> poses_;
  const SignAt& sign_;
  std::array<std::vector<bool>, 2> common_;
  bool touching_ = false;
  // each part's edges in boundary order (pointers into loops_, which no longer changes), and per
  // edge the other part's edges (their places in its flat_) whose boxes meet its box, ascending
  std::array<std::vector<CurvedEdge*>, 2> flat_;
  std::array<std::vector<std::vector<std::size_t>>, 2> near_;
};

// The part's loops, edges not yet posed (CurvedRelation poses them as needed).
std::vector<std::vector<CurvedEdge>> part_loops(const Part& part) {
  std::vector<std::vector<CurvedEdge>> loops;
  for (const Loop& loop : part.loops) {
    std::vector<CurvedEdge> edges;
    for (const Edge& edge : loop.edges) {
      CurvedEdge e;
      e.arc = edge.is_arc();
      e.loop = loops.size();
      e.source = &edge;
      if (e.arc) {
        e.ccw = edge.ccw;
        e.full = edge.is_full_circle();
      }
      edges.push_back(std::move(e));
    }
    loops.push_back(std::move(edges));
  }
  return loops;
}

bool has_arc(const Part& part) {
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges)
      if (edge.is_arc()) return true;
  return false;
}

}  // namespace

namespace {

// The relation of the pair posed in the chart at the point whose signs `sign` decides.
std::optional<Overlap> relation_at(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                   const ChartAxis& y_axis, const SignAt& sign) {
  const Part& first = model.parts.at(axes.first);
  const Part& second = model.parts.at(axes.second);
  PairPoses<Poly> poses = pair_poses(model, axes, x_axis, y_axis, Poly::variable(0), Poly::variable(1), constant);
  if (has_arc(first) || has_arc(second))
    return CurvedRelation({part_loops(first), part_loops(second)},
                          {ScaledPose{&poses.first, &poses.second.w}, ScaledPose{&poses.second, &poses.first.w}}, sign)
        .run();
  std::vector<Segment> a = posed_segments(first, poses.first), b = posed_segments(second, poses.second);
  for (auto* part : {&a, &b})
    for (Segment& segment : *part) {
      sign.enclose(segment.from);
      sign.enclose(segment.to);
    }
  return PolygonRelation(std::move(a), std::move(b), sign).run();
}

// The certified double box of a real algebraic number: its value's enclosure, or its isolating
// interval's.
kernels::Interval kernel_box(const Real& r) {
  return r.exact ? algebra::enclose_kernel(r.lower)
                 : kernels::Interval(algebra::lower_double(r.lower), algebra::upper_double(r.upper));
}

}  // namespace

std::optional<Overlap> algebraic_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                         const ChartAxis& y_axis, const Real& x, const Real& y,
                                         const PairOverlap* filter) {
  const Real y_used = axes.dimension() < 2 ? Real::from_rational(Rational(0)) : y;
  if (!x.exact && !y_used.exact) return std::nullopt;
  if (filter && algebraic_filter_switch() && filter->certainly_overlapping(x_axis, y_axis, kernel_box(x), kernel_box(y_used))) return Overlap::overlapping;
  return relation_at(model, axes, x_axis, y_axis, SignAt(x, y_used));
}

bool certainly_overlapping_over(const PairAxes& axes, const ChartAxis& x_axis, const ChartAxis& y_axis, const Real& x,
                                const Rational& y_lower, const Rational& y_upper, const PairOverlap* filter) {
  if (!filter || !algebraic_filter_switch()) return false;
  const kernels::Interval y = axes.dimension() < 2 ? kernel_box(Real::from_rational(Rational(0)))
                                                  : kernels::Interval(algebra::lower_double(y_lower), algebra::upper_double(y_upper));
  return filter->certainly_overlapping(x_axis, y_axis, kernel_box(x), y);
}

std::optional<Overlap> algebraic_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                         const ChartAxis& y_axis, const Real& x, const RadicalOrdinate& y,
                                         const PairOverlap* filter) {
  if (axes.dimension() < 2 || y.lower > y.upper) return std::nullopt;
  const int q = algebra::sign_at(y.denominator, x);
  if (q == 0 || (!y.radicand.empty() && algebra::sign_at(y.radicand, x) < 0)) return std::nullopt;
  // lower <= y <= upper: the signs of den y - num at y for each bound num / den (den > 0)
  auto side = [&](const Rational& r) {
    IntegerPolynomial2 f;
    f.coefficients = {{-r.get_num(), r.get_den()}};
    return algebra::sign_at(f, x, y, q);
  };
  if (side(y.lower) < 0 || side(y.upper) > 0) return std::nullopt;
  if (filter && algebraic_filter_switch() && filter->certainly_overlapping(
                    x_axis, y_axis, kernel_box(x),
                    kernels::Interval(algebra::lower_double(y.lower), algebra::upper_double(y.upper))))
    return Overlap::overlapping;
  return relation_at(model, axes, x_axis, y_axis, SignAt(x, y, q));
}

}  // namespace hipair::cspace
