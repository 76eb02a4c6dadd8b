// HIPAIR — whether a held contact of a pin-slot part still lies on both its features (its
// edge-end decision; docs/simulation.md, "The pin-slot simulator's decisions, exact"). Internal
// to src/simulation. Decided at the pair's exact relative configuration: the other part's
// feature at its zero configuration, the pin-slot part's placed by p -> P + R(theta)(p - P) +
// (x, y) with the exact rotation of the configuration's half-angle tangent. A certified interval
// filter (kernels::Interval enclosing every exact input) decides first; where an interval holds 0
// the same predicates are evaluated in exact rationals. Until session 60 the test ran in doubles
// on the state's cos/sin (a contact point within rounding of an edge's end could go either way).
#pragma once

#include "kernels/contact_geometry.hpp"
#include "kernels/interval.hpp"

#include <hipair/rational.hpp>

#include <optional>

namespace hipair::simulation {

/// A placement p -> pivot + R (p - pivot) + shift in number type T (R = [[c, -s], [s, c]]).
template <class T>
struct ExtentPose {
  T c{1}, s{0};
  kernels::Vector<T> pivot{T(0), T(0)}, shift{T(0), T(0)};
  kernels::Vector<T> place(const kernels::Vector<T>& p) const {
    const T dx = p.x - pivot.x, dy = p.y - pivot.y;
    return {pivot.x + c * dx - s * dy + shift.x, pivot.y + s * dx + c * dy + shift.y};
  }
  // a world direction turned back into the body: R^T v
  kernels::Vector<T> unturn(const kernels::Vector<T>& v) const { return {c * v.x + s * v.y, -s * v.x + c * v.y}; }
};

namespace extent_detail {

// Kleene three-valued logic: nullopt = not decided by the number type.
using Maybe = std::optional<bool>;
inline Maybe non_negative(const Rational& v) { return sgn(v) >= 0; }
inline Maybe non_negative(const kernels::Interval& v) {
  if (v.lo >= 0) return true;
  if (v.hi < 0) return false;
  return std::nullopt;
}
inline Maybe both(Maybe a, Maybe b) {
  if ((a && !*a) || (b && !*b)) return false;
  if (a && b) return true;
  return std::nullopt;
}
inline Maybe either(Maybe a, Maybe b) {
  if ((a && *a) || (b && *b)) return true;
  if (a && b) return false;
  return std::nullopt;
}
using kernels::cross;
using kernels::dot;
template <class T>
kernels::Vector<T> minus(const kernels::Vector<T>& a, const kernels::Vector<T>& b) {
  return a - b;
}

// The body direction v lies in the closed sector (the planar simulator's in_sector, exact signs).
template <class T>
Maybe in_sector(const kernels::Vector<T>& v, const kernels::ArcSector<T>& sector) {
  if (sector.full) return true;
  const Maybe from = non_negative(T(cross(sector.start, v))), to = non_negative(T(cross(v, sector.end)));
  return sector.large ? either(from, to) : both(from, to);
}

// The foot of world point x on the placed segment (q1, q2) lies within it: 0 <= (x - q1).(q2 - q1) <= |q2 - q1|^2.
template <class T>
Maybe on_segment(const kernels::Vector<T>& x, const kernels::Vector<T>& q1, const kernels::Vector<T>& q2) {
  const kernels::Vector<T> d = minus(q2, q1);
  const T f = dot(minus(x, q1), d);
  return both(non_negative(f), non_negative(T(dot(d, d) - f)));
}

}  // namespace extent_detail

/// Whether the contact of `fixed` (placed by `pa`) and `free` (placed by `pb`) lies within both
/// features: a vertex's foot on the segment or its direction from the arc's centre in the arc's
/// sector; an arc's centre's foot on a segment within it and the foot's direction in the arc's
/// sector; two arcs' line of centres in both sectors (from the concave arc's centre towards the
/// convex one's when one is concave). nullopt when T (an interval) does not decide it.
template <class T>
std::optional<bool> contact_within(const ExtentPose<T>& pa, const kernels::FeatureGeometry<T>& fa,
                                   const ExtentPose<T>& pb, const kernels::FeatureGeometry<T>& fb) {
  using namespace extent_detail;
  using kernels::FeatureShape;
  using V = kernels::Vector<T>;
  auto in_arc = [](const V& world, const ExtentPose<T>& pk, const kernels::FeatureGeometry<T>& arc) {
    return in_sector(pk.unturn(world), arc.sector);
  };
  auto vertex_on = [&](const ExtentPose<T>& pv, const kernels::FeatureGeometry<T>& v, const ExtentPose<T>& po,
                       const kernels::FeatureGeometry<T>& other) -> Maybe {
    const V x = pv.place(v.point);
    if (other.shape == FeatureShape::segment) return on_segment(x, po.place(other.point), po.place(other.target));
    return in_arc(minus(x, po.place(other.center)), po, other);
  };
  auto segment_arc = [&](const ExtentPose<T>& ps, const kernels::FeatureGeometry<T>& seg, const ExtentPose<T>& pk,
                         const kernels::FeatureGeometry<T>& arc) -> Maybe {
    const V k = pk.place(arc.center), q1 = ps.place(seg.point), q2 = ps.place(seg.target);
    const V d = minus(q2, q1);
    const T l2 = dot(d, d), f = dot(minus(k, q1), d);   // the foot q1 + (f / l2) d
    const Maybe on = both(non_negative(f), non_negative(T(l2 - f)));
    if (on && !*on) return false;
    // the foot's direction from the centre, times l2 > 0: l2 (q1 - k) + f d
    const V q1k = minus(q1, k);
    const V foot{l2 * q1k.x + f * d.x, l2 * q1k.y + f * d.y};
    return both(on, in_arc(foot, pk, arc));
  };
  if (fa.shape == FeatureShape::vertex) return vertex_on(pa, fa, pb, fb);
  if (fb.shape == FeatureShape::vertex) return vertex_on(pb, fb, pa, fa);
  if (fa.shape == FeatureShape::segment) return segment_arc(pa, fa, pb, fb);
  if (fb.shape == FeatureShape::segment) return segment_arc(pb, fb, pa, fa);
  const V v = minus(pb.place(fb.center), pa.place(fa.center));
  const V back{T(0) - v.x, T(0) - v.y};
  if (fa.convex && fb.convex) return both(in_arc(v, pa, fa), in_arc(back, pb, fb));
  const V toward = fa.convex ? back : v;   // from the concave arc's centre towards the convex one's
  return both(in_arc(toward, pa, fa), in_arc(toward, pb, fb));
}

/// The interval enclosure of an exact feature geometry and pose (kernels::Interval::enclose).
inline kernels::FeatureGeometry<kernels::Interval> enclose(const kernels::FeatureGeometry<Rational>& f) {
  using kernels::Interval;
  auto v = [](const kernels::Vector<Rational>& p) {
    return kernels::Vector<Interval>{Interval::enclose(p.x), Interval::enclose(p.y)};
  };
  kernels::FeatureGeometry<Interval> out;
  out.shape = f.shape;
  out.point = v(f.point);
  out.target = v(f.target);
  out.center = v(f.center);
  out.radius_squared = Interval::enclose(f.radius_squared);
  out.convex = f.convex;
  out.sector.start = v(f.sector.start);
  out.sector.end = v(f.sector.end);
  out.sector.large = f.sector.large;
  out.sector.full = f.sector.full;
  return out;
}
inline ExtentPose<kernels::Interval> enclose(const ExtentPose<Rational>& p) {
  using kernels::Interval;
  ExtentPose<Interval> out;
  out.c = Interval::enclose(p.c);
  out.s = Interval::enclose(p.s);
  out.pivot = {Interval::enclose(p.pivot.x), Interval::enclose(p.pivot.y)};
  out.shift = {Interval::enclose(p.shift.x), Interval::enclose(p.shift.y)};
  return out;
}

/// contact_within decided: the interval filter (`filtered`: its enclosures, built once per
/// feature), then, only where it cannot decide, the exact rationals. `exact_used` (optional)
/// counts the fallbacks.
inline bool contact_within_certified(const ExtentPose<Rational>& pa, const kernels::FeatureGeometry<Rational>& fa,
                                     const kernels::FeatureGeometry<kernels::Interval>& ia,
                                     const ExtentPose<Rational>& pb, const kernels::FeatureGeometry<Rational>& fb,
                                     const kernels::FeatureGeometry<kernels::Interval>& ib,
                                     std::size_t* exact_used = nullptr) {
  if (const std::optional<bool> quick = contact_within(enclose(pa), ia, enclose(pb), ib)) return *quick;
  if (exact_used) ++*exact_used;
  return *contact_within(pa, fa, pb, fb);
}

}  // namespace hipair::simulation
