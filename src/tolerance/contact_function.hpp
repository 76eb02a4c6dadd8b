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

#include <optional>

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

/// What the contact function of a feature pair reads of its two edges alone, whatever the
/// poses: the kernels' exact tangent distance (arc–arc: (ra + rb)^2 or (ra - rb)^2) or radius
/// times length (arc–segment: r |d|), made from the edges' squared radii and end points; absent
/// for the other pairs (their kernels take the edges as they are). Session 69 (chain69): a caller
/// that evaluates one feature pair over one geometry at many poses (CurveSolver: the brackets of
/// a box) makes it once (contact_constant) and passes it to every evaluation; the result is the
/// contact function's bit for bit, the same operations on the same operands.
template <class T>
struct ContactConstant {
  std::optional<T> value;   ///< present when the pair's kernel takes it (arc–arc, arc–segment)
};

/// The feature pair's ContactConstant (see there). \throws NumericError as the contact function
/// would (a square root T cannot take); GeometryError is left to the contact function.
template <class T>
ContactConstant<T> contact_constant(const model_detail::EdgeValue<T>& ea, const FeatureIdentity& fa,
                                    const model_detail::EdgeValue<T>& eb, const FeatureIdentity& fb) {
  using A = model_detail::Arithmetic<T>;
  using K = FeatureKind;
  ContactConstant<T> c;
  if (fa.kind == K::arc && fb.kind == K::arc) {
    T ra = A::sqrt(ea.radius_squared), rb = A::sqrt(eb.radius_squared);
    if (!ea.ccw && !eb.ccw) return c;   // no contact of its own (the contact function throws)
    T d = ea.ccw && eb.ccw ? T(ra + rb) : T(ra - rb);
    c.value.emplace(d * d);
  } else if (fa.kind == K::arc && fb.kind == K::segment && ea.ccw) {
    kernels::Vector<T> d = eb.target - eb.source;
    c.value.emplace(A::sqrt(ea.radius_squared) * A::sqrt(kernels::dot(d, d)));
  } else if (fa.kind == K::segment && fb.kind == K::arc && eb.ccw) {
    kernels::Vector<T> d = ea.target - ea.source;
    c.value.emplace(A::sqrt(eb.radius_squared) * A::sqrt(kernels::dot(d, d)));
  }
  return c;
}

/// The contact function of the feature pair (fa of part a, fb of part b) at poses a, b, with the
/// pair's ContactConstant already made (contact_constant(ea, fa, eb, fb), bit for bit).
/// \throws GeometryError for a feature pair without a contact of its own.
template <class T>
T contact_function(const model_detail::EdgeValue<T>& ea, const FeatureIdentity& fa, const kernels::Pose<T>& a,
                   const model_detail::EdgeValue<T>& eb, const FeatureIdentity& fb, const kernels::Pose<T>& b,
                   const ContactConstant<T>& constant) {
  using K = FeatureKind;
  if (fa.kind == K::vertex && fb.kind == K::segment) return kernels::vertex_segment(a, ea.source, b, eb.source, eb.target);
  if (fa.kind == K::segment && fb.kind == K::vertex) return kernels::segment_vertex(a, ea.source, ea.target, b, eb.source);
  if (fa.kind == K::vertex && fb.kind == K::arc)
    return kernels::vertex_arc(a, ea.source, b, eb.center, eb.radius_squared, eb.ccw);
  if (fa.kind == K::arc && fb.kind == K::vertex)
    return kernels::arc_vertex(a, ea.center, ea.radius_squared, ea.ccw, b, eb.source);
  if (fa.kind == K::arc && fb.kind == K::arc && constant.value) {
    if (ea.ccw && eb.ccw) return kernels::arc_arc(a, ea.center, b, eb.center, *constant.value, kernels::Tangency::external);
    if (ea.ccw && !eb.ccw)
      return kernels::arc_arc(a, ea.center, b, eb.center, *constant.value, kernels::Tangency::first_inside_second);
    if (!ea.ccw && eb.ccw)
      return kernels::arc_arc(a, ea.center, b, eb.center, *constant.value, kernels::Tangency::second_inside_first);
  }
  if (fa.kind == K::arc && fb.kind == K::segment && ea.ccw && constant.value)
    return kernels::arc_segment(a, ea.center, *constant.value, b, eb.source, eb.target);
  if (fa.kind == K::segment && fb.kind == K::arc && eb.ccw && constant.value)
    return kernels::segment_arc(a, ea.source, ea.target, b, eb.center, *constant.value);
  throw GeometryError("the feature pair has no contact of its own");
}

/// The contact function of the feature pair (fa of part a, fb of part b) at poses a, b.
/// \throws GeometryError for a feature pair without a contact of its own.
template <class T>
T contact_function(const model_detail::EdgeValue<T>& ea, const FeatureIdentity& fa, const kernels::Pose<T>& a,
                   const model_detail::EdgeValue<T>& eb, const FeatureIdentity& fb, const kernels::Pose<T>& b) {
  return contact_function(ea, fa, a, eb, fb, b, contact_constant(ea, fa, eb, fb));
}

/// The same with the features looked up in whole part geometries.
template <class T>
T contact_function(const Geometry<T>& ga, const FeatureIdentity& fa, const kernels::Pose<T>& a,
                   const Geometry<T>& gb, const FeatureIdentity& fb, const kernels::Pose<T>& b) {
  return contact_function(ga.loops.at(fa.loop).at(fa.edge), fa, a, gb.loops.at(fb.loop).at(fb.edge), fb, b);
}

}  // namespace hipair::tolerance_detail
