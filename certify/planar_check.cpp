// Planar claims (see planar_check.hpp).
#include "certify/planar_check.hpp"
#include "certify/sliced_connected.hpp"

#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"
#include "certify/tolerance_support.hpp"

namespace hipair::verify {
namespace {

// exact up to 60 characters, else 25 digits marked rounded (a forged x = 1e100000 printed a
// 100 KB line until session 36, as the tolerance messages did until session 35)
std::string text(const Rational& r) { return fraction_or_rounded(r); }

// p -> pivot + R (p - pivot) + (x, y) as a rotation about the origin: R p + (pivot - R pivot + (x, y))
// (the interval posing rotates a planar part's shape about the origin, see pose_pivot); a
// pin-slot part's shift is slide R d.

std::string pose_text(const PlanarPose& pose) {
  return "'" + pose.part + "' at " + (pose.slide ? "s=" + text(*pose.slide) : "x=" + text(pose.x) + ", y=" + text(pose.y)) +
         (pose.half_turn ? ", t(pi)=" : ", t=") + text(pose.tangent);
}

const Edge& edge_of(const Part& part, const EdgeReference& reference) {
  if (reference.loop >= part.loops.size() || reference.edge >= part.loops[reference.loop].edges.size())
    reject("part '" + part.name + "' has no loop " + std::to_string(reference.loop) + " edge " + std::to_string(reference.edge));
  const Edge& edge = part.loops[reference.loop].edges[reference.edge];
  if (edge.label != reference.label)
    reject("loop " + std::to_string(reference.loop) + " edge " + std::to_string(reference.edge) + " of '" + part.name +
           "' is labelled '" + edge.label + "' in the model, not '" + reference.label + "'");
  return edge;
}

}  // namespace

ExactMap planar_pose_map(const Part& part, const PlanarPose& pose) {
  Rational w = 1 + pose.tangent * pose.tangent;
  int sign = pose.half_turn ? -1 : 1;
  ExactMap map;
  map.c = sign * (1 - pose.tangent * pose.tangent) / w;
  map.s = sign * 2 * pose.tangent / w;
  const Point& p = part.motion.pivot;
  Point turned = map.rotate(p);
  Point shift{pose.x, pose.y};
  if (pose.slide) {
    Point d = map.rotate(part.motion.direction);
    shift = Point{Rational(*pose.slide * d.x), Rational(*pose.slide * d.y)};
  }
  map.shift = Point{Rational(p.x - turned.x + shift.x), Rational(p.y - turned.y + shift.y)};
  return map;
}

std::string check_planar(const Certificate& c, const Model& model) {
  if (!c.pose) reject("a planar claim needs the free part's pose");
  const PlanarPose& pose = *c.pose;
  if (pose.part != c.first && pose.part != c.second) reject("the posed part '" + pose.part + "' is not a part of the pair");
  const Part& free = part_named(model, pose.part);
  const Part& fixed = part_named(model, pose.part == c.first ? c.second : c.first);
  ExactMap fixed_map;
  if (pose.slide) {
    // a pin-in-slot part: its slide within its limits (exact), its angle certainly within its
    // angle limits (MPFI enclosure of 2 atan t), the other part fixed or at its configured position
    if (free.motion.kind != Motion::Kind::pin_slot) reject("part '" + free.name + "' has no pin_slot motion (a pose with a slide)");
    const auto& limits = free.motion.translation_limits;
    if (limits && (*pose.slide < limits->lo || *pose.slide > limits->hi))
      reject("the slide of '" + free.name + "' (" + text(*pose.slide) + ") is outside its limits");
    if (!certainly_within(free.motion.angle_limits, angle_of_tangent(pose.tangent, pose.half_turn), true))
      reject("the angle of '" + free.name + "' (2 atan(" + text(pose.tangent) + ")" + (pose.half_turn ? " + pi" : "") +
             " rad) is not certainly within its limits [" + to_decimal_string(free.motion.angle_limits->lo) + ", " +
             to_decimal_string(free.motion.angle_limits->hi) + "] rad");
    if (fixed.motion.kind == Motion::Kind::planar || fixed.motion.kind == Motion::Kind::pin_slot)
      reject("part '" + fixed.name + "' must be fixed, rotate or translate");
    check_configuration_parts(c.configuration, {fixed.name});
    fixed_map = exact_map(fixed, c.configuration);
  } else {
    if (free.motion.kind != Motion::Kind::planar) reject("part '" + free.name + "' is not free in the plane (motion \"planar\")");
    if (fixed.motion.kind != Motion::Kind::fixed) reject("part '" + fixed.name + "' is not fixed");
    if (free.motion.angle_limits || free.motion.translation_limits)
      reject("part '" + free.name + "' has motion limits (planar claims cover parts without limits)");
    if (!c.configuration.empty()) reject("a planar claim against a fixed part has no configuration");
  }
  const ExactMap map = planar_pose_map(free, pose);
  const PlacedPart placed_fixed = place(fixed, fixed_map), placed_free = place(free, map);
  const std::string where = pose_text(pose);
  if (c.claim == ClaimKind::planar_interference) {
    if (c.witness_point) {
      for (const PlacedPart* part : {&placed_fixed, &placed_free}) {
        int at = locate(*part, *c.witness_point);
        if (at <= 0)
          reject("the witness point (" + text(c.witness_point->x) + ", " + text(c.witness_point->y) +
                 ") is not strictly inside part '" + part->name + "' (it lies " + (at == 0 ? "on its boundary" : "outside") + ")");
      }
      return "parts '" + fixed.name + "' and " + where + " overlap (a witness point lies strictly inside both)";
    }
    if (!c.witness_crossing) reject("an interference claim needs a witness");
    const CrossingWitness& w = *c.witness_crossing;
    bool edge_free = w.edge.part == free.name;
    if (!((edge_free && w.across.part == fixed.name) || (w.edge.part == fixed.name && w.across.part == free.name)))
      reject("a crossing must name one edge of each part of the pair ('" + fixed.name + "', '" + free.name + "')");
    edge_of(edge_free ? free : fixed, w.edge);
    edge_of(edge_free ? fixed : free, w.across);
    const PlacedPart& first = edge_free ? placed_free : placed_fixed;
    const PlacedPart& second = edge_free ? placed_fixed : placed_free;
    if (!edges_cross(first.loops[w.edge.loop][w.edge.edge], second.loops[w.across.loop][w.across.edge]))
      reject("the edges loop " + std::to_string(w.edge.loop) + " edge " + std::to_string(w.edge.edge) + " of '" + w.edge.part +
             "' and loop " + std::to_string(w.across.loop) + " edge " + std::to_string(w.across.edge) + " of '" + w.across.part +
             "' do not cross transversally with " + where);
    return "parts '" + fixed.name + "' and " + where + " overlap (two edges cross)";
  }
  if (sgn(c.distance) <= 0) reject("the claimed clearance must be positive");
  std::string closest;
  Rational bound = boundary_distance_lower_bound(shape_of(fixed), to_interval_map(fixed_map), shape_of(free), to_interval_map(map),
                                                 c.distance, &closest);
  // the MPFI bound falls a hair short of an exact distance: decide it exactly (hunt41)
  if (bound < c.distance && !boundary_distance_at_least(placed_fixed, placed_free, c.distance)) {
    auto [found, claimed] = show_apart(bound, c.distance);
    reject("with " + where + " the certified distance lower bound of " + closest + " is " + found +
           ", less than the claimed " + claimed);
  }
  for (int side = 0; side < 2; ++side) {
    const PlacedPart& inner = side ? placed_free : placed_fixed;
    const PlacedPart& outer = side ? placed_fixed : placed_free;
    for (std::size_t i = 0; i < inner.loops.size(); ++i)
      if (!inner.loops[i].empty() && locate(outer, inner.loops[i][0].source) >= 0)
        reject("with " + where + ": loop " + std::to_string(i) + " of '" + inner.name + "' lies inside '" + outer.name +
               "' (the parts overlap)");
  }
  return "parts '" + fixed.name + "' and " + where + " are at least " + text(c.distance) + " mm apart";
}

}  // namespace hipair::verify
