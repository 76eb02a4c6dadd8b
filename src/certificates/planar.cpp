// Certificates for parts free in the plane at one exact pose (x, y, theta) against a fixed part:
// planar interference and planar clearance (docs/certify.md, "Planar pairs"). The witness is
// found with the exact overlap predicate (interference) or the verifier's certified distance
// bound (clearance), and every certificate is re-checked with the verifier's own code.
#include "certificates/producer.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

namespace hipair {
namespace {

using namespace certify_detail;

struct PlanarPair {
  const Part* fixed;
  const Part* free;
  verify::ExactMap map;   // the free part's pose as a rotation about the origin and a shift
};

PlanarPair planar_pair(const Model& model, const std::string& fixed, const PlanarPose& pose) {
  const Part& a = part_of(model, fixed);
  const Part& b = part_of(model, pose.part);
  if (a.motion.kind != Motion::Kind::fixed) throw GeometryError("planar certificate: part '" + a.name + "' must be fixed");
  if (b.motion.kind != Motion::Kind::planar)
    throw GeometryError("planar certificate: part '" + b.name + "' must be free in the plane (motion \"planar\")");
  if (b.motion.angle_limits || b.motion.translation_limits)
    throw GeometryError("planar certificate: part '" + b.name + "' has motion limits");
  Rational w = 1 + pose.tangent * pose.tangent;
  int sign = pose.half_turn ? -1 : 1;
  verify::ExactMap map;
  map.c = sign * (1 - pose.tangent * pose.tangent) / w;
  map.s = sign * 2 * pose.tangent / w;
  Point turned = map.rotate(b.motion.pivot);
  map.shift = Point{Rational(b.motion.pivot.x - turned.x + pose.x), Rational(b.motion.pivot.y - turned.y + pose.y)};
  return PlanarPair{&a, &b, map};
}

Placement placement_of(const verify::ExactMap& map) { return placement_about(map.pivot, map.c, map.s, map.shift); }

std::string pose_words(const PlanarPose& pose) {
  return "'" + pose.part + "' shifted by (" + to_decimal_string(pose.x) + ", " + to_decimal_string(pose.y) +
         ") mm and turned by 2 atan(" + to_exact_string(pose.tangent) + ")" + (pose.half_turn ? " + pi" : "") + " rad";
}

}  // namespace

std::optional<Certificate> certify_planar_interference(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                       const CertifyContext& context) {
  PlanarPair pair = planar_pair(model, fixed, pose);
  Certificate c = start_certificate(model, context, ClaimKind::planar_interference, fixed, pose.part);
  c.pose = pose;
  PartOverlap report = part_overlap(*pair.fixed, Placement{}, *pair.free, placement_of(pair.map), true);
  if (report.relation != PartRelation::overlapping) return std::nullopt;
  if (report.witness) {
    c.witness_point = report.witness;
  } else {   // a transversal crossing of two edges, found with the verifier's own predicate
    const Part &a = *pair.fixed, &b = *pair.free;
    verify::PlacedPart placed_a = verify::place(a, verify::ExactMap{}), placed_b = verify::place(b, pair.map);
    for (std::size_t i = 0; i < a.loops.size() && !c.witness_crossing; ++i)
      for (std::size_t j = 0; j < a.loops[i].edges.size() && !c.witness_crossing; ++j)
        for (std::size_t k = 0; k < b.loops.size() && !c.witness_crossing; ++k)
          for (std::size_t l = 0; l < b.loops[k].edges.size() && !c.witness_crossing; ++l)
            if (verify::edges_cross(placed_a.loops[i][j], placed_b.loops[k][l]))
              c.witness_crossing = CrossingWitness{{a.name, i, j, a.loops[i].edges[j].label},
                                                   {b.name, k, l, b.loops[k].edges[l].label}, std::nullopt};
    if (!c.witness_crossing) return std::nullopt;
  }
  c.statement = "Part '" + fixed + "' and " + pose_words(pose) + " overlap.";
  self_check(c, model);
  return c;
}

std::optional<Certificate> certify_planar_clearance(const Model& model, const std::string& fixed, const PlanarPose& pose,
                                                    std::optional<Rational> distance, const CertifyContext& context) {
  PlanarPair pair = planar_pair(model, fixed, pose);
  Certificate c = start_certificate(model, context, ClaimKind::planar_clearance, fixed, pose.part);
  c.pose = pose;
  const Part &a = *pair.fixed, &b = *pair.free;
  if (part_overlap(a, Placement{}, b, placement_of(pair.map)).relation != PartRelation::apart) return std::nullopt;
  // capped at the L1 distance of two boundary points (an upper bound of the distance)
  Point p = a.loops.at(0).edges.at(0).source, q = pair.map.apply(b.loops.at(0).edges.at(0).source);
  Rational cap = abs(p.x - q.x) + abs(p.y - q.y);
  if (distance && *distance > cap) return std::nullopt;
  Rational bound = verify::boundary_distance_lower_bound(verify::place_over(a, verify::IntervalMap{}),
                                                         verify::place_over(b, verify::to_interval_map(pair.map)), cap);
  if (sgn(bound) <= 0 || (distance && bound < *distance)) return std::nullopt;
  c.distance = distance ? *distance : round_down(bound, 6);
  c.statement = "Part '" + fixed + "' and " + pose_words(pose) + " are at least " + to_decimal_string(c.distance) +
                " mm apart.";
  self_check(c, model);
  return c;
}

}  // namespace hipair
