// HIPAIR contact kernels — the world contact point and contact normal of a touching feature
// pair, written once for any number type T with division (exact rationals, certified
// intervals, double, AutoDiff scalars).
//
// The features are given in their parts' body coordinates, posed by homogeneous poses
// (kernels/pose.hpp). At a configuration where the pair touches (its contact function is
// zero and its validity holds) the formulas below give the exact contact point and a normal
// direction; elsewhere they stay continuous, so an interval enclosure of a configuration gives
// an enclosure of the point and the normal at every configuration in it.
//
// Contact point per contact type (a = the pair's first part, b = the second):
//   vertex of a on a segment or arc of b   the vertex, posed with a
//   segment or arc of a on a vertex of b   the vertex, posed with b
//   arc of a tangent to a segment of b     the foot of a's arc centre on b's line
//                                          Q1 + (dot(K - Q1, d) / |d|^2) d   (rational)
//   arc of a tangent to an arc of b        the intersection of the line of centres with the
//                                          radical axis, Ka + ((|D|^2 + ra^2 - rb^2) / (2 |D|^2)) D,
//                                          D = Kb - Ka (rational from squared radii only)
// Normal: the direction from a into b, i.e. the outward normal of a's material at the contact
// point (the direction in which a pushes b); not unit length (normalise with a square root:
// see unit()). It is the left normal of b's segment for a contact on a segment of b (material
// lies on the left of every edge), the right normal of a's segment, the radial direction of
// an arc (into the arc's material), and +-D for arcs (D for an external tangency, -D when one
// arc lies inside the other).
#pragma once

#include "kernels/contact.hpp"
#include "kernels/pose.hpp"

namespace hipair::kernels {

/// The kind of a boundary feature.
enum class FeatureShape { vertex, segment, arc };

/// A boundary feature in its part's body coordinates.
template <class T>
struct FeatureGeometry {
  FeatureShape shape = FeatureShape::segment;
  Vector<T> point{T(0), T(0)};   ///< vertex: the vertex; segment: its source
  Vector<T> target{T(0), T(0)};  ///< segment: its target
  Vector<T> center{T(0), T(0)};  ///< arc: its centre
  T radius_squared{0};           ///< arc
  bool convex = true;            ///< arc: material inside its circle (a counter-clockwise arc)
  ArcSector<T> sector;           ///< arc: its angular range (validity of the contact table)
};

/// Contact point and (not normalised) normal from the first part into the second, in world
/// coordinates.
template <class T>
struct ContactFrame {
  Vector<T> point{T(0), T(0)};
  Vector<T> normal{T(0), T(0)};
  bool defined = false;   ///< false for pairs without a contact of their own (vertex–vertex, ...)
};

/// World position of a body point under a homogeneous pose: pivot + shift + R (p - pivot).
template <class T>
Vector<T> world_point(const Pose<T>& pose, const Vector<T>& p) {
  Vector<T> base = pose.pivot + pose.shift;
  if (!pose.rotates) return base + (p - pose.pivot);
  Vector<T> r = rotated(pose.c, pose.s, p - pose.pivot);
  return base + Vector<T>{T(r.x / pose.w), T(r.y / pose.w)};
}

/// World direction of a body vector: R d (times w_pose, a positive factor: directions only).
template <class T>
Vector<T> world_direction_homogeneous(const Pose<T>& pose, const Vector<T>& d) {
  return rotate_homogeneous(pose, d);
}

/// The right normal (y, -x).
template <class T>
Vector<T> right_normal(const Vector<T>& a) {
  return Vector<T>{a.y, T(-a.x)};
}

/// The contact frame of feature `fa` of part a against feature `fb` of part b.
template <class T>
ContactFrame<T> contact_frame(const Pose<T>& a, const FeatureGeometry<T>& fa, const Pose<T>& b,
                              const FeatureGeometry<T>& fb) {
  ContactFrame<T> frame;
  using S = FeatureShape;
  if (fa.shape == S::vertex && fb.shape == S::segment) {
    frame.point = world_point(a, fa.point);
    frame.normal = left_normal(world_direction_homogeneous(b, fb.target - fb.point));
  } else if (fa.shape == S::segment && fb.shape == S::vertex) {
    frame.point = world_point(b, fb.point);
    frame.normal = right_normal(world_direction_homogeneous(a, fa.target - fa.point));
  } else if (fa.shape == S::vertex && fb.shape == S::arc) {
    frame.point = world_point(a, fa.point);
    Vector<T> outward = frame.point - world_point(b, fb.center);   // out of b's circle
    frame.normal = fb.convex ? -outward : outward;                  // into b's material
  } else if (fa.shape == S::arc && fb.shape == S::vertex) {
    frame.point = world_point(b, fb.point);
    Vector<T> outward = frame.point - world_point(a, fa.center);
    frame.normal = fa.convex ? outward : -outward;                  // out of a's material
  } else if (fa.shape == S::arc && fb.shape == S::arc) {
    Vector<T> ka = world_point(a, fa.center);
    Vector<T> d = world_point(b, fb.center) - ka;
    T d2 = dot(d, d);
    T along = T(T(d2 + fa.radius_squared - fb.radius_squared) / T(T(2) * d2));
    frame.point = ka + scaled(along, d);
    frame.normal = fa.convex && fb.convex ? d : -d;
  } else if (fa.shape == S::arc && fb.shape == S::segment) {
    Vector<T> q1 = world_point(b, fb.point);
    Vector<T> dir = world_point(b, fb.target) - q1;
    Vector<T> k = world_point(a, fa.center);
    T along = T(dot(k - q1, dir) / dot(dir, dir));
    frame.point = q1 + scaled(along, dir);
    frame.normal = left_normal(dir);
  } else if (fa.shape == S::segment && fb.shape == S::arc) {
    Vector<T> p1 = world_point(a, fa.point);
    Vector<T> dir = world_point(a, fa.target) - p1;
    Vector<T> k = world_point(b, fb.center);
    T along = T(dot(k - p1, dir) / dot(dir, dir));
    frame.point = p1 + scaled(along, dir);
    frame.normal = right_normal(dir);
  } else {
    return frame;
  }
  frame.defined = true;
  return frame;
}

/// The unit vector of `v` for number types with a square root found by `sqrt_of` (e.g. the
/// certified interval square root): v / sqrt(|v|^2).
template <class T, class Sqrt>
Vector<T> unit(const Vector<T>& v, Sqrt&& sqrt_of) {
  T length = sqrt_of(dot(v, v));
  return Vector<T>{T(v.x / length), T(v.y / length)};
}

}  // namespace hipair::kernels
