// HIPAIR contact kernels — a model's boundary features as the kernels' body geometry.
//
// The one map from a feature of the public model (include/hipair/model.hpp; a feature named
// by the public FeatureKind / FeatureIdentity of include/hipair/cspace.hpp) to the kernels'
// FeatureGeometry (kernels/contact_geometry.hpp), in any number type T: a vertex is the
// source of its edge; a segment runs from the edge's source to its target; an arc keeps its
// centre, squared radius, side (material inside its circle when the arc runs counter-clockwise)
// and its counter-clockwise angular sector, the validity range of the contact table. The
// sector is decided in exact rationals and only then converted, so every consumer (curve
// generation, the adaptor's contact frames, the sliced contact frame, the planar simulator)
// reads the same exact sector in its own number type.
#pragma once

#include "kernels/contact_geometry.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <utility>

namespace hipair::kernels {

/// The counter-clockwise sector of an arc edge seen from its centre (body frame), exact: from
/// the source to the target of a counter-clockwise arc, from the target to the source of a
/// clockwise one; `large` when it spans more than a half turn; `full` for a full circle.
inline ArcSector<Rational> arc_sector(const Edge& edge) {
  ArcSector<Rational> sector;
  Vector<Rational> from_source{Rational(edge.source.x - edge.center.x), Rational(edge.source.y - edge.center.y)};
  Vector<Rational> from_target{Rational(edge.target.x - edge.center.x), Rational(edge.target.y - edge.center.y)};
  if (edge.is_full_circle()) {
    sector.full = true;
    sector.start = from_source;
    sector.end = std::move(from_source);
    return sector;
  }
  sector.start = edge.ccw ? std::move(from_source) : std::move(from_target);
  sector.end = edge.ccw ? std::move(from_target) : std::move(from_source);
  sector.large = sgn(sector.start.x * sector.end.y - sector.start.y * sector.end.x) < 0;
  return sector;
}

/// The body geometry of the feature of kind `kind` on `edge` (a vertex: the edge's source) in
/// number type T, `convert` taking the model's rationals to T.
template <class T, class Convert>
FeatureGeometry<T> feature_geometry(const Edge& edge, FeatureKind kind, Convert&& convert) {
  FeatureGeometry<T> f;
  auto vec = [&](const auto& p) { return Vector<T>{convert(p.x), convert(p.y)}; };
  switch (kind) {
    case FeatureKind::vertex:
      f.shape = FeatureShape::vertex;
      f.point = vec(edge.source);
      break;
    case FeatureKind::segment:
      f.shape = FeatureShape::segment;
      f.point = vec(edge.source);
      f.target = vec(edge.target);
      break;
    case FeatureKind::arc: {
      f.shape = FeatureShape::arc;
      f.center = vec(edge.center);
      f.radius_squared = convert(edge.radius_squared);
      f.convex = edge.ccw;
      ArcSector<Rational> sector = arc_sector(edge);
      f.sector.start = vec(sector.start);
      f.sector.end = vec(sector.end);
      f.sector.large = sector.large;
      f.sector.full = sector.full;
      break;
    }
  }
  return f;
}

/// The body geometry of feature `id` of `model` in number type T (feature_geometry of its edge).
template <class T, class Convert>
FeatureGeometry<T> feature_geometry(const Model& model, const FeatureIdentity& id, Convert&& convert) {
  const Edge& edge = model.parts.at(id.part).loops.at(id.loop).edges.at(id.edge);
  return feature_geometry<T>(edge, id.kind, convert);
}

}  // namespace hipair::kernels
