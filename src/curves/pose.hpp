// Poses of a pair's parts at chart coordinates, for any kernel number type, and the exact
// relative placement of one part in the other's body frame.
#pragma once

#include "curves/contact_curves.hpp"
#include "kernels/pose.hpp"

#include "kernels/contact.hpp"
#include "kernels/contact_geometry.hpp"
#include "kernels/model_features.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <optional>
#include <string>
#include <vector>

namespace hipair::cspace {

/// Degrees of freedom of a motion (0 fixed, 1 rotation/translation, 2 pin_slot, 3 planar).
int motion_degrees_of_freedom(const Motion& motion) noexcept;

/// Converts a model point with `convert` (Rational -> T).
template <class T, class Convert>
kernels::Vector<T> to_vector(const Point& p, Convert&& convert) {
  return kernels::Vector<T>{convert(p.x), convert(p.y)};
}

/// Pose of `part` at chart value `value` of chart `axis` (ignored when `moves` is false).
template <class T, class Convert>
kernels::Pose<T> part_pose(const Part& part, bool moves, const ChartAxis& axis, const T& value,
                           Convert&& convert) {
  if (!moves) return kernels::fixed_pose<T>();
  switch (part.motion.kind) {
    case Motion::Kind::rotation:
      return kernels::rotation_pose_from_half_tangent(to_vector<T>(part.motion.pivot, convert),
                                                      value, axis.half_turn);
    case Motion::Kind::translation:
      return kernels::translation_pose(to_vector<T>(part.motion.direction, convert), value);
    default:
      throw GeometryError("part '" + part.name + "' is not a fixed-axis part");
  }
}

/// The two parts' poses at a chart point of the pair, in any number type.
template <class T>
struct PairPoses {
  kernels::Pose<T> first;
  kernels::Pose<T> second;
};

/// Poses of the pair's parts when the chart coordinates are `x_value`, `y_value` (T).
template <class T, class Convert>
PairPoses<T> pair_poses(const Model& model, const PairAxes& axes, const ChartAxis& x,
                        const ChartAxis& y, const T& x_value, const T& y_value,
                        Convert&& convert) {
  PairPoses<T> poses{part_pose(model.parts.at(axes.first), axes.first_moves, x, x_value, convert),
                     kernels::fixed_pose<T>()};
  const ChartAxis& second_axis = axes.first_moves ? y : x;
  const T& second_value = axes.first_moves ? y_value : x_value;
  poses.second = part_pose(model.parts.at(axes.second), axes.second_moves, second_axis,
                           second_value, convert);
  return poses;
}

/// An exact rigid map p -> R p + offset, R = [c -s; s c] with c^2 + s^2 = 1 (rational).
struct RigidMap {
  Rational c = 1;
  Rational s = 0;
  Point offset{Rational(0), Rational(0)};
  Point apply(const Point& p) const {
    return Point{Rational(c * p.x - s * p.y + offset.x), Rational(s * p.x + c * p.y + offset.y)};
  }
  Point rotate(const Point& v) const {
    return Point{Rational(c * v.x - s * v.y), Rational(s * v.x + c * v.y)};
  }
};

/// Exact map from the first part's body frame to the second part's body frame at chart
/// point q (rational chart coordinates give a rational map).
RigidMap relative_map(const Model& model, const PairAxes& axes, const ChartAxis& x,
                      const ChartAxis& y, const ChartPoint& q);

/// Exact world map of one part at a chart value (identity for a part that does not move).
RigidMap world_map(const Part& part, bool moves, const ChartAxis& axis, const Rational& value);

// ------------------------------------------------------------------ features of a part

/// A boundary feature of a part with its exact body-frame geometry.
struct BodyFeature {
  FeatureRef ref;
  const Edge* edge = nullptr;  ///< segment/arc: the edge; vertex: the edge it starts
  std::string label;           ///< "slot 2 wall", "corner of slot 2 wall and slot 2 bottom"
  /// Vertex: the vertex; segment/arc: its start. Its edge's source (not a copy: a feature holds
  /// no exact number of its own, session 57).
  const Point& point() const { return edge->source; }
};

/// The features of part `part_index` that can take part in a contact: every segment and arc,
/// and every vertex except those of full circles and strictly reflex vertices (interior
/// angle > pi: such a vertex can never be the only contact point of a non-overlapping
/// configuration, see docs/contact-kernels.md). `reflex_skipped` counts the latter.
/// `labels` false: every label is left empty (feature_label gives it when needed).
std::vector<BodyFeature> part_features(const Model& model, std::size_t part_index,
                                       std::size_t* reflex_skipped = nullptr, bool labels = true);

/// The label part_features gives the feature `ref` of `model`.
std::string feature_label(const Model& model, const FeatureRef& ref);

/// How two features touch, for people: "vertex on segment", "arc tangent to arc", ...
const char* contact_word(ContactType type);

/// A contact curve's label for people, "driver pin / wheel slot 2 wall (vertex on segment)":
/// the parts' names and feature_label of each feature (`first.part`, `second.part` index
/// model.parts), and how they touch (the curve generator's labels, and a kernel slicer's for a
/// strip a congruent pair generated).
std::string curve_label(const Model& model, const FeatureRef& first, const FeatureRef& second, ContactType type);

/// The feature's exact body geometry for the kernels' contact table and contact frames
/// (kernels/contact_table.hpp, kernels/contact_geometry.hpp).
kernels::FeatureGeometry<Rational> feature_geometry(const BodyFeature& feature);

/// The counter-clockwise sector of an arc edge, and the body geometry of a model feature in any
/// number type: the kernels' one map from a model feature to FeatureGeometry
/// (kernels/model_features.hpp), used by curve generation and the adaptor's contact frames.
using kernels::arc_sector;
using kernels::feature_geometry;

/// Exact square root of a non-negative rational when it is rational.
std::optional<Rational> exact_square_root(const Rational& value);

/// Tangent (direction of travel, not normalised) of an edge at a point on it.
Point edge_tangent(const Edge& edge, const Point& at);
/// edge_tangent(edge, at) scaled by a positive integer into integers (the same direction: every
/// sign of a cross or dot product of such tangents is the rationals'), written into `out`'s
/// storage; a straight edge's without rational temporaries.
void scaled_tangent(const Edge& edge, const Point& at, kernels::Vector<mpz_class>& out);

/// True when the direction `v` (from the arc's centre) lies in the closed sector.
bool sector_contains(const kernels::ArcSector<Rational>& sector, const Point& v);

/// Exact vector difference a - b.
inline Point difference(const Point& a, const Point& b) {
  return Point{Rational(a.x - b.x), Rational(a.y - b.y)};
}
inline Rational cross(const Point& a, const Point& b) { return a.x * b.y - a.y * b.x; }
inline Rational dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }

/// Conversion of exact model data to kernel vectors of rationals.
inline kernels::Vector<Rational> to_kernel(const Point& p) { return {p.x, p.y}; }

}  // namespace hipair::cspace
