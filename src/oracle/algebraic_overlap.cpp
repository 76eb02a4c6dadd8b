// The exact overlap relation at a chart point with an irrational coordinate
// (curves/algebraic_overlap.hpp), for parts bounded by segments.
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

#include "algebra/polynomial.hpp"
#include "curves/pose.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace hipair::cspace {

namespace {

using algebra::Real;
using Poly = RationalPolynomial2;

// A homogeneous world point (X / W, Y / W) with W > 0 at every configuration.
struct HPoint {
  Poly X, Y, W;
};

struct Segment {
  HPoint from, to;   // material on the left
};

class SignAt {
 public:
  SignAt(const Real& x, const Real& y) : x_(x), y_(y) {}
  int operator()(const Poly& p) const {
    if (p.is_zero()) return 0;
    IntegerPolynomial2 f = normalized_integer_polynomial(p);
    if (f.is_zero()) return 0;
    if (y_.exact) return x_.exact ? algebra::sign_at(f, x_.lower, y_.lower) : algebra::sign_at(f, x_, y_.lower);
    return algebra::sign_at(f, x_.lower, y_);
  }

 private:
  const Real& x_;
  const Real& y_;
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
    Poly det = p.X * (q.Y * r.W - r.Y * q.W) - p.Y * (q.X * r.W - r.X * q.W) + p.W * (q.X * r.Y - r.X * q.Y);
    return sign_(det);
  }
  // sign of (p - q) . (s - r)
  int along(const HPoint& p, const HPoint& q, const HPoint& r, const HPoint& s) const {
    Poly dx = p.X * q.W - q.X * p.W, dy = p.Y * q.W - q.Y * p.W;
    Poly ex = s.X * r.W - r.X * s.W, ey = s.Y * r.W - r.Y * s.W;
    return sign_(dx * ex + dy * ey);
  }
  // sign of p.y - q.y
  int compare_y(const HPoint& p, const HPoint& q) const { return sign_(p.Y * q.W - q.Y * p.W); }
  static HPoint midpoint(const HPoint& p, const HPoint& q) {
    return HPoint{p.X * q.W + q.X * p.W, p.Y * q.W + q.Y * p.W, Poly(2) * p.W * q.W};
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

// The part's loops as world segments at the symbolic pose (nullopt: an arc).
std::optional<std::vector<Segment>> posed_segments(const Part& part, const kernels::Pose<Poly>& pose) {
  std::vector<Segment> result;
  auto place = [&](const Point& p) {
    // W world = w (pivot + shift) + [c -s; s c] (p - pivot)
    Poly dx = constant(p.x) - pose.pivot.x, dy = constant(p.y) - pose.pivot.y;
    return HPoint{pose.w * (pose.pivot.x + pose.shift.x) + pose.c * dx - pose.s * dy,
                  pose.w * (pose.pivot.y + pose.shift.y) + pose.s * dx + pose.c * dy, pose.w};
  };
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      if (edge.is_arc()) return std::nullopt;
      result.push_back(Segment{place(edge.source), place(edge.target)});
    }
  return result;
}

}  // namespace

std::optional<Overlap> algebraic_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                         const ChartAxis& y_axis, const Real& x, const Real& y) {
  const Real y_used = axes.dimension() < 2 ? Real::from_rational(Rational(0)) : y;
  if (!x.exact && !y_used.exact) return std::nullopt;
  for (std::size_t index : {axes.first, axes.second})
    for (const Loop& loop : model.parts.at(index).loops)
      for (const Edge& edge : loop.edges)
        if (edge.is_arc()) return std::nullopt;
  PairPoses<Poly> poses = pair_poses(model, axes, x_axis, y_axis, Poly::variable(0), Poly::variable(1), constant);
  auto first = posed_segments(model.parts.at(axes.first), poses.first);
  auto second = posed_segments(model.parts.at(axes.second), poses.second);
  if (!first || !second) return std::nullopt;
  SignAt sign(x, y_used);
  return PolygonRelation(std::move(*first), std::move(*second), sign).run();
}

}  // namespace hipair::cspace
