// Certificates for parts free in the plane at one exact pose (x, y, theta) against a fixed part:
// planar interference and planar clearance (docs/certify.md, "Planar pairs"). The witness is
// found with the exact overlap predicate (interference) or the verifier's certified distance
// bound (clearance), and every certificate is re-checked with the verifier's own code.
#include "certificates/producer.hpp"
#include "certify/planar_check.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

namespace hipair {
namespace {

using namespace certify_detail;

struct PlanarPair {
  const Part* fixed;
  const Part* free;
  verify::ExactMap map;         // the free part's pose as a rotation about the origin and a shift
  verify::ExactMap fixed_map;   // the other part's (identity when fixed)
};

// A planar part against a fixed part, or (pose.slide) a pin-slot part against a fixed, rotating
// or translating part placed by `configuration`.
PlanarPair planar_pair(const Model& model, const std::string& fixed, const PlanarPose& pose,
                       const std::map<std::string, ExactPosition>& configuration) {
  const Part& a = part_of(model, fixed);
  const Part& b = part_of(model, pose.part);
  verify::ExactMap fixed_map;
  if (pose.slide) {
    if (b.motion.kind != Motion::Kind::pin_slot)
      throw GeometryError("pin-slot certificate: part '" + b.name + "' has no pin_slot motion");
    if (a.motion.kind == Motion::Kind::planar || a.motion.kind == Motion::Kind::pin_slot)
      throw GeometryError("pin-slot certificate: part '" + a.name + "' must be fixed, rotate or translate");
    // a pose beyond the motion limits is an input error naming the part and its limits, as a
    // fixed-axis part's position (single.cpp, require_within_limits; session 32, hunt32b)
    const auto& slide_limits = b.motion.translation_limits;
    if (slide_limits && (*pose.slide < slide_limits->lo || *pose.slide > slide_limits->hi))
      throw ModelError(b.pointer, "the slide of '" + b.name + "' (" + to_decimal_string(*pose.slide) +
                                      " mm) is outside its motion limits [" + to_decimal_string(slide_limits->lo) + ", " +
                                      to_decimal_string(slide_limits->hi) + "] mm");
    if (!verify::certainly_within(b.motion.angle_limits, verify::angle_of_tangent(pose.tangent, pose.half_turn), true))
      throw ModelError(b.pointer, "the angle of '" + b.name + "' (2 atan(" + to_exact_string(pose.tangent) + ")" +
                                      (pose.half_turn ? " + pi" : "") + " rad) is not certainly within its motion limits [" +
                                      to_decimal_string(b.motion.angle_limits->lo) + ", " +
                                      to_decimal_string(b.motion.angle_limits->hi) + "] rad");
    try {
      fixed_map = verify::exact_map(a, configuration);
    } catch (const verify::Rejection& r) {
      throw GeometryError("pin-slot certificate: " + r.reason);
    }
  } else {
    if (a.motion.kind != Motion::Kind::fixed) throw GeometryError("planar certificate: part '" + a.name + "' must be fixed");
    if (b.motion.kind != Motion::Kind::planar)
      throw GeometryError("planar certificate: part '" + b.name + "' must be free in the plane (motion \"planar\")");
    if (b.motion.angle_limits || b.motion.translation_limits)
      throw GeometryError("planar certificate: part '" + b.name + "' has motion limits");
  }
  Rational w = 1 + pose.tangent * pose.tangent;
  int sign = pose.half_turn ? -1 : 1;
  verify::ExactMap map;
  map.c = sign * (1 - pose.tangent * pose.tangent) / w;
  map.s = sign * 2 * pose.tangent / w;
  Point turned = map.rotate(b.motion.pivot);
  Point shift{pose.x, pose.y};
  if (pose.slide) {
    Point d = map.rotate(b.motion.direction);
    shift = Point{Rational(*pose.slide * d.x), Rational(*pose.slide * d.y)};
  }
  map.shift = Point{Rational(b.motion.pivot.x - turned.x + shift.x), Rational(b.motion.pivot.y - turned.y + shift.y)};
  return PlanarPair{&a, &b, map, fixed_map};
}

Placement placement_of(const verify::ExactMap& map) { return placement_about(map.pivot, map.c, map.s, map.shift); }

std::optional<Certificate> interference(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                        const std::map<std::string, ExactPosition>& configuration, const CertifyContext& context) {
  PlanarPair pair = planar_pair(model, fixed, pose, configuration);
  Certificate c = start_certificate(model, context, ClaimKind::planar_interference, fixed, pose.part);
  c.pose = pose;
  c.configuration = configuration;
  PartOverlap report = part_overlap(*pair.fixed, placement_of(pair.fixed_map), *pair.free, placement_of(pair.map), true);
  if (report.relation != PartRelation::overlapping) return std::nullopt;
  if (report.witness) {
    c.witness_point = report.witness;
  } else {   // a transversal crossing of two edges, found with the verifier's own predicate
    const Part &a = *pair.fixed, &b = *pair.free;
    verify::PlacedPart placed_a = verify::place(a, pair.fixed_map), placed_b = verify::place(b, pair.map);
    for (std::size_t i = 0; i < a.loops.size() && !c.witness_crossing; ++i)
      for (std::size_t j = 0; j < a.loops[i].edges.size() && !c.witness_crossing; ++j)
        for (std::size_t k = 0; k < b.loops.size() && !c.witness_crossing; ++k)
          for (std::size_t l = 0; l < b.loops[k].edges.size() && !c.witness_crossing; ++l)
            if (verify::edges_cross(placed_a.loops[i][j], placed_b.loops[k][l]))
              c.witness_crossing = CrossingWitness{{a.name, i, j, a.loops[i].edges[j].label},
                                                   {b.name, k, l, b.loops[k].edges[l].label}, std::nullopt};
    if (!c.witness_crossing) return std::nullopt;
  }
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}

std::optional<Certificate> clearance(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                     const std::map<std::string, ExactPosition>& configuration, std::optional<Rational> distance,
                                     const CertifyContext& context) {
  PlanarPair pair = planar_pair(model, fixed, pose, configuration);
  Certificate c = start_certificate(model, context, ClaimKind::planar_clearance, fixed, pose.part);
  c.pose = pose;
  c.configuration = configuration;
  const Part &a = *pair.fixed, &b = *pair.free;
  if (part_overlap(a, placement_of(pair.fixed_map), b, placement_of(pair.map)).relation != PartRelation::apart) return std::nullopt;
  // capped at the L1 distance of two boundary points (an upper bound of the distance)
  Point p = pair.fixed_map.apply(a.loops.at(0).edges.at(0).source), q = pair.map.apply(b.loops.at(0).edges.at(0).source);
  Rational cap = abs(p.x - q.x) + abs(p.y - q.y);
  if (distance && *distance > cap) return std::nullopt;
  Rational bound = verify::boundary_distance_lower_bound(verify::shape_of(a), verify::to_interval_map(pair.fixed_map), verify::shape_of(b), verify::to_interval_map(pair.map), cap);
  std::optional<Rational> claimed = claimed_clearance(bound, distance, a, pair.fixed_map, b, pair.map, cap);
  if (!claimed) return std::nullopt;
  c.distance = *claimed;
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}

}  // namespace

std::optional<Certificate> certify_planar_interference(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                       const CertifyContext& context) {
  if (pose.slide) throw GeometryError("planar certificate: the pose of '" + pose.part + "' has a slide (a pin-slot pose)");
  return interference(model, fixed, pose, {}, context);
}

std::optional<Certificate> certify_planar_clearance(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                    std::optional<Rational> distance, const CertifyContext& context) {
  if (pose.slide) throw GeometryError("planar certificate: the pose of '" + pose.part + "' has a slide (a pin-slot pose)");
  return clearance(model, fixed, pose, {}, distance, context);
}

std::optional<Certificate> certify_pin_slot_interference(const Model& model, const std::string& other, const PlanarPose& pose,
                                                         const std::map<std::string, ExactPosition>& configuration,
                                                         const CertifyContext& context) {
  if (!pose.slide) throw GeometryError("pin-slot certificate: the pose of '" + pose.part + "' needs a slide");
  return interference(model, other, pose, configuration, context);
}

std::optional<Certificate> certify_pin_slot_clearance(const Model& model, const std::string& other, const PlanarPose& pose,
                                                      const std::map<std::string, ExactPosition>& configuration,
                                                      std::optional<Rational> distance, const CertifyContext& context) {
  if (!pose.slide) throw GeometryError("pin-slot certificate: the pose of '" + pose.part + "' needs a slide");
  return clearance(model, other, pose, configuration, distance, context);
}

}  // namespace hipair
