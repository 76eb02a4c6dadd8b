// The contact function of one feature pair of a fixed-axis pair, re-instantiated over the
// parametric model for any number type T with a square root (double, certified intervals,
// AutoDiff scalars, the interval jets of jet.hpp): F(x, y; p), whose zero set near a valid
// contact is the pair's contact curve at the parameter vector p (docs/tolerance.md).
//
// The kernels are the ones the C-space is built from (kernels/contact.hpp), in their unsquared
// forms: where the exact builder must square away the irrational product r |d| (or ra rb), T
// has a square root. Same zero set near valid contacts and the same sign convention (negative
// where the features penetrate), so F_y != 0 there and implicit differentiation applies.
#pragma once

#include "kernels/contact.hpp"
#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

namespace hipair::tolerance_detail {

template <class T>
using Geometry = model_detail::PartGeometry<T>;

/// The world-frame pose of a part at a chart coordinate: rotation (half-angle tangent in the
/// chart centred at 0 or pi), translation (offset), or fixed.
template <class T>
kernels::Pose<T> pose_of(const Motion& motion, const kernels::Vector<T>& pivot, const kernels::Vector<T>& direction,
                         const T& chart, bool half_turn) {
  switch (motion.kind) {
    case Motion::Kind::rotation: return kernels::rotation_pose_from_half_tangent(pivot, chart, half_turn);
    case Motion::Kind::translation: return kernels::translation_pose(direction, chart);
    default: return kernels::fixed_pose<T>();
  }
}

template <class T>
kernels::Pose<T> pose_of(const Motion& motion, const Geometry<T>& geometry, const T& chart, bool half_turn) {
  return pose_of(motion, geometry.pivot, geometry.direction, chart, half_turn);
}

/// The contact function of the feature pair (fa of part a, fb of part b) at poses a, b.
/// \throws GeometryError for a feature pair without a contact of its own.
template <class T>
T contact_function(const model_detail::EdgeValue<T>& ea, const FeatureIdentity& fa, const kernels::Pose<T>& a,
                   const model_detail::EdgeValue<T>& eb, const FeatureIdentity& fb, const kernels::Pose<T>& b) {
  using A = model_detail::Arithmetic<T>;
  using K = FeatureKind;
  if (fa.kind == K::vertex && fb.kind == K::segment) return kernels::vertex_segment(a, ea.source, b, eb.source, eb.target);
  if (fa.kind == K::segment && fb.kind == K::vertex) return kernels::segment_vertex(a, ea.source, ea.target, b, eb.source);
  if (fa.kind == K::vertex && fb.kind == K::arc)
    return kernels::vertex_arc(a, ea.source, b, eb.center, eb.radius_squared, eb.ccw);
  if (fa.kind == K::arc && fb.kind == K::vertex)
    return kernels::arc_vertex(a, ea.center, ea.radius_squared, ea.ccw, b, eb.source);
  if (fa.kind == K::arc && fb.kind == K::arc) {
    T ra = A::sqrt(ea.radius_squared), rb = A::sqrt(eb.radius_squared);
    if (ea.ccw && eb.ccw) {
      T d = T(ra + rb);
      return kernels::arc_arc(a, ea.center, b, eb.center, T(d * d), kernels::Tangency::external);
    }
    T d = T(ra - rb);
    if (ea.ccw && !eb.ccw)
      return kernels::arc_arc(a, ea.center, b, eb.center, T(d * d), kernels::Tangency::first_inside_second);
    if (!ea.ccw && eb.ccw)
      return kernels::arc_arc(a, ea.center, b, eb.center, T(d * d), kernels::Tangency::second_inside_first);
  }
  if (fa.kind == K::arc && fb.kind == K::segment && ea.ccw) {
    kernels::Vector<T> d = eb.target - eb.source;
    T product = T(A::sqrt(ea.radius_squared) * A::sqrt(kernels::dot(d, d)));
    return kernels::arc_segment(a, ea.center, product, b, eb.source, eb.target);
  }
  if (fa.kind == K::segment && fb.kind == K::arc && eb.ccw) {
    kernels::Vector<T> d = ea.target - ea.source;
    T product = T(A::sqrt(eb.radius_squared) * A::sqrt(kernels::dot(d, d)));
    return kernels::segment_arc(a, ea.source, ea.target, b, eb.center, product);
  }
  throw GeometryError("the feature pair has no contact of its own");
}

/// The same with the features looked up in whole part geometries.
template <class T>
T contact_function(const Geometry<T>& ga, const FeatureIdentity& fa, const kernels::Pose<T>& a,
                   const Geometry<T>& gb, const FeatureIdentity& fb, const kernels::Pose<T>& b) {
  return contact_function(ga.loops.at(fa.loop).at(fa.edge), fa, a, gb.loops.at(fb.loop).at(fb.edge), fb, b);
}

}  // namespace hipair::tolerance_detail
