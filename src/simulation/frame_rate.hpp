// HIPAIR — the contact frame of a fixed-axis feature pair and its exact rate along a motion
// (docs/simulation.md, "The tangent's drift, exact (session 59)").
//
// The kernels' contact frame (kernels/contact_geometry.hpp) evaluated in dual numbers
// (kernels/dual.hpp): each moving part of the pair posed by its coordinate q and rate q' (a
// rotation about its pivot by Dual(cos q, -sin q q'), Dual(sin q, cos q q'); a translation by
// the offset Dual(q, q') along its direction; a fixed part by the identity) gives the world
// contact point c, its rate c', the not normalised normal N and its rate N', by the chain rule
// through the same formulas the adaptor's CSpace::contact_frame evaluates in certified
// intervals. The unit normal n = N / |N| and its rate n' = (N' - n (n . N')) / |N|.
#pragma once

#include "kernels/contact_geometry.hpp"
#include "kernels/dual.hpp"
#include "kernels/model_features.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::simulation {

/// A contact frame and its rate (world coordinates, per time unit of the rates given).
struct FrameRate {
  bool defined = false;    ///< false where the kernels' frame is undefined or not finite
  double point[2] = {0, 0}, point_rate[2] = {0, 0};
  double normal[2] = {0, 0}, normal_rate[2] = {0, 0};   ///< unit normal (first part into second)
};

/// The pose of `part` at coordinate q with rate v, in dual numbers (a fixed part: the identity).
inline kernels::Pose<kernels::Dual> dual_pose(const Part& part, double q, double v) {
  using kernels::Dual;
  const auto d = [](const Rational& r) { return Dual(r.get_d()); };
  switch (part.motion.kind) {
    case Motion::Kind::rotation: {
      const double c = std::cos(q), s = std::sin(q);
      return kernels::rotation_pose_from_cos_sin(kernels::Vector<Dual>{d(part.motion.pivot.x), d(part.motion.pivot.y)},
                                                 Dual(c, -s * v), Dual(s, c * v));
    }
    case Motion::Kind::translation:
      return kernels::translation_pose(kernels::Vector<Dual>{d(part.motion.direction.x), d(part.motion.direction.y)},
                                       Dual(q, v));
    default:
      return kernels::fixed_pose<Dual>();
  }
}

/// The body geometries of a feature pair's two features in dual numbers (constants).
using DualFeatures = std::array<kernels::FeatureGeometry<kernels::Dual>, 2>;
inline DualFeatures dual_features(const Model& model, const FeaturePair& pair) {
  const auto d = [](const Rational& r) { return kernels::Dual(r.get_d()); };
  return {kernels::feature_geometry<kernels::Dual>(model, pair.first, d),
          kernels::feature_geometry<kernels::Dual>(model, pair.second, d)};
}

/// The frame and its rate from the kernels' frame in dual numbers (the unit normal and its rate).
inline FrameRate frame_rate(const kernels::ContactFrame<kernels::Dual>& frame) {
  FrameRate out;
  if (!frame.defined) return out;
  out.defined = true;
  const double length = std::hypot(frame.normal.x.v, frame.normal.y.v);
  if (!(length > 0) || !std::isfinite(length)) return out;
  const double nx = frame.normal.x.v / length, ny = frame.normal.y.v / length;
  const double along = nx * frame.normal.x.d + ny * frame.normal.y.d;
  out.point[0] = frame.point.x.v;
  out.point[1] = frame.point.y.v;
  out.point_rate[0] = frame.point.x.d;
  out.point_rate[1] = frame.point.y.d;
  out.normal[0] = nx;
  out.normal[1] = ny;
  out.normal_rate[0] = (frame.normal.x.d - nx * along) / length;
  out.normal_rate[1] = (frame.normal.y.d - ny * along) / length;
  for (double value : {out.point[0], out.point[1], out.point_rate[0], out.point_rate[1], out.normal_rate[0],
                       out.normal_rate[1]})
    if (!std::isfinite(value)) return FrameRate{};
  return out;
}

/// The frame of feature pair `pair` of `model` (its geometries `g`: dual_features) with the
/// pair's first part at (q1, v1) and its second at (q2, v2) (ignored for a fixed part) and its rate.
inline FrameRate frame_rate(const Model& model, const FeaturePair& pair, const DualFeatures& g, double q1, double v1,
                            double q2, double v2) {
  return frame_rate(kernels::contact_frame(dual_pose(model.parts.at(pair.first.part), q1, v1), g[0],
                                           dual_pose(model.parts.at(pair.second.part), q2, v2), g[1]));
}

/// frame_rate with the pair's geometries made here.
inline FrameRate frame_rate(const Model& model, const FeaturePair& pair, double q1, double v1, double q2, double v2) {
  return frame_rate(model, pair, dual_features(model, pair), q1, v1, q2, v2);
}

/// The drift T' v of a contact's tangent row T (the fixed-axis simulator's friction_of: T[d] =
/// s_d t . J_d(c), c the mean of the feature pairs' contact points, n the unit normal of the
/// first defined one, t = (-n_y, n_x), s_d = -1 for the first part's coordinate and +1 for the
/// second's, J_d(c) the velocity of point c of coordinate d's part per unit speed: (-(c_y - p_y),
/// c_x - p_x) for a rotation about pivot p, the direction for a translation) along the velocities:
///   T' v = sum_d v_d s_d (t' . J_d + t . J_d'),  t' = (-n'_y, n'_x),  J_d' = (-c'_y, c'_x) or 0,
/// exact (the chain rule through the kernels' frame). `coordinate(part)` gives a part's (q, v),
/// nullopt for a part without a coordinate (fixed); `geometry(pair)` gives a feature pair's
/// dual_features (e.g. remembered). 0 where no feature pair has a frame.
template <class Coordinate, class Geometry>
double tangent_drift(const Model& model, const std::vector<const FeaturePair*>& pairs, Coordinate&& coordinate,
                     Geometry&& geometry) {
  double c[2] = {0, 0}, dc[2] = {0, 0}, n[2] = {0, 0}, dn[2] = {0, 0};
  std::size_t first = 0, second = 0;
  int count = 0;
  for (const FeaturePair* fp : pairs) {
    const std::optional<std::pair<double, double>> a = coordinate(fp->first.part), b = coordinate(fp->second.part);
    const FrameRate r = frame_rate(model, *fp, geometry(*fp), a ? a->first : 0.0, a ? a->second : 0.0,
                                   b ? b->first : 0.0, b ? b->second : 0.0);
    if (!r.defined) continue;
    if (count == 0) {
      n[0] = r.normal[0];
      n[1] = r.normal[1];
      dn[0] = r.normal_rate[0];
      dn[1] = r.normal_rate[1];
      first = fp->first.part;
      second = fp->second.part;
    }
    for (int i = 0; i < 2; ++i) {
      c[i] += r.point[i];
      dc[i] += r.point_rate[i];
    }
    ++count;
  }
  if (count == 0) return 0;
  for (int i = 0; i < 2; ++i) {
    c[i] /= count;
    dc[i] /= count;
  }
  double drift = 0;
  const auto add = [&](std::size_t part, double sign) {
    const std::optional<std::pair<double, double>> qv = coordinate(part);
    if (!qv) return;
    const Motion& motion = model.parts.at(part).motion;
    double J[2], dJ[2] = {0, 0};
    if (motion.kind == Motion::Kind::rotation) {
      J[0] = -(c[1] - motion.pivot.y.get_d());
      J[1] = c[0] - motion.pivot.x.get_d();
      dJ[0] = -dc[1];
      dJ[1] = dc[0];
    } else {
      J[0] = motion.direction.x.get_d();
      J[1] = motion.direction.y.get_d();
    }
    drift += qv->second * sign * (-dn[1] * J[0] + dn[0] * J[1] - n[1] * dJ[0] + n[0] * dJ[1]);
  };
  add(first, -1);
  add(second, +1);
  return std::isfinite(drift) ? drift : 0.0;
}


/// tangent_drift with each feature pair's geometries made when needed.
template <class Coordinate>
double tangent_drift(const Model& model, const std::vector<const FeaturePair*>& pairs, Coordinate&& coordinate) {
  return tangent_drift(model, pairs, coordinate, [&](const FeaturePair& pair) { return dual_features(model, pair); });
}

}  // namespace hipair::simulation
