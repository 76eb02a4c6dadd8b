// HIPAIR contact kernels — exact squared distances of points and segments of the plane.
//
// For ordered fields only (exact rationals): the formulas compare and divide, so unlike
// vector.hpp they do not serve intervals or AutoDiff scalars. Used where a decision needs the
// exact gap between posed features: the 3-DOF feature-pair distances (src/sliced/nearby.cpp)
// and the pin-in-slot simulator's far test (src/simulation/pin_slot_simulation.cpp).
#pragma once

#include <algorithm>
#include <type_traits>
#include <utility>

namespace hipair::kernels {

// The functions take any point type with members x and y of one ordered field type (kernels'
// Vector<T>, hipair::Point), so callers pass their points without copying them.
template <class P>
using Coordinate = std::decay_t<decltype(std::declval<const P&>().x)>;

/// |p - q|^2.
template <class P>
Coordinate<P> squared_distance(const P& p, const P& q) {
  using T = Coordinate<P>;
  const T dx = p.x - q.x, dy = p.y - q.y;
  return T(dx * dx + dy * dy);
}

/// The squared distance from p to the closed segment [a, b] (a point when a == b).
template <class P>
Coordinate<P> point_segment_squared_distance(const P& p, const P& a, const P& b) {
  using T = Coordinate<P>;
  const T dx = b.x - a.x, dy = b.y - a.y, qx = p.x - a.x, qy = p.y - a.y;
  const T along = qx * dx + qy * dy;
  if (!(along > 0)) return T(qx * qx + qy * qy);   // before a (or a degenerate segment)
  const T length2 = dx * dx + dy * dy;
  if (!(along < length2)) return squared_distance(p, b);   // past b
  const T c = qx * dy - qy * dx;
  return T(c * c / length2);   // the foot lies inside: the line's distance
}

/// The sign of cross(b - a, c - a): +1 when c lies left of the directed line a -> b.
template <class P>
int orientation(const P& a, const P& b, const P& c) {
  using T = Coordinate<P>;
  const T value = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return value > 0 ? 1 : (value < 0 ? -1 : 0);
}

/// The squared distance between the closed segments [a, b] and [c, d]: 0 when they meet
/// (cross, touch or overlap), otherwise the least distance of an end point from the other
/// segment (two disjoint segments' nearest points include an end point; for collinear
/// segments too).
template <class P>
Coordinate<P> segment_segment_squared_distance(const P& a, const P& b, const P& c, const P& d) {
  using T = Coordinate<P>;
  if (orientation(a, b, c) * orientation(a, b, d) < 0 && orientation(c, d, a) * orientation(c, d, b) < 0)
    return T(0);   // a proper crossing (touching and overlapping pairs give 0 below)
  return std::min({point_segment_squared_distance(a, c, d), point_segment_squared_distance(b, c, d),
                   point_segment_squared_distance(c, a, b), point_segment_squared_distance(d, a, b)});
}

}  // namespace hipair::kernels
