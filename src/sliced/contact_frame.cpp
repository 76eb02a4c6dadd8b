// The contact frame of a 3-DOF feature pair (include/hipair/sliced.hpp, sliced_contact_frame):
// the free part posed homogeneously at (x, y, t) and the fixed part at rest, handed to the
// contact kernels (kernels/contact_geometry.hpp). Exact rational arithmetic throughout.
#include <hipair/error.hpp>
#include <hipair/sliced.hpp>

#include "kernels/contact_frame_rational.hpp"
#include "kernels/contact_geometry.hpp"
#include "kernels/model_features.hpp"

namespace hipair {
namespace {

using V = kernels::Vector<Rational>;

V vec(const Point& p) { return V{p.x, p.y}; }

// The body geometry of a feature for the frame formulas (kernels/model_features.hpp).
kernels::FeatureGeometry<Rational> geometry_of(const Model& model, const FeatureIdentity& id) {
  return kernels::feature_geometry<Rational>(model, id, [](const Rational& r) { return r; });
}

}  // namespace

SlicedContactFrame sliced_contact_frame(const Model& model, const SlicedFeaturePair& pair,
                                        const SlicedConfiguration& configuration) {
  if (pair.fixed.part >= model.parts.size() || pair.free.part >= model.parts.size() ||
      model.parts[pair.fixed.part].motion.kind != Motion::Kind::fixed ||
      model.parts[pair.free.part].motion.kind != Motion::Kind::planar)
    throw GeometryError("sliced_contact_frame: the pair is not a fixed part and a planar part of the model");
  const Motion& motion = model.parts[pair.free.part].motion;
  Rational x = configuration.x, y = configuration.y, t = configuration.angle.t;
  for (Rational* r : {&x, &y, &t}) r->canonicalize();
  kernels::Pose<Rational> free_pose;
  if (configuration.angle.half_turn) {
    free_pose.c = Rational(-1);
    free_pose.s = Rational(0);
    free_pose.w = Rational(1);
    free_pose.pivot = vec(motion.pivot);
    free_pose.rotates = true;
  } else {
    free_pose = kernels::rotation_pose_from_half_tangent(vec(motion.pivot), t, false);
  }
  free_pose.shift = V{x, y};
  free_pose.translates = true;
  kernels::ContactFrame<Rational> frame =
      kernels::contact_frame_rational(kernels::fixed_pose<Rational>(), geometry_of(model, pair.fixed), free_pose,
                                      geometry_of(model, pair.free));
  SlicedContactFrame out;
  out.defined = frame.defined;
  if (frame.defined) {
    out.point = Point{frame.point.x, frame.point.y};
    out.normal = Point{frame.normal.x, frame.normal.y};
  }
  return out;
}

}  // namespace hipair
