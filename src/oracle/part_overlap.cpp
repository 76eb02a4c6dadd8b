// The public door to the exact overlap oracle (include/hipair/overlap.hpp): placements become
// the oracle's rigid maps, the oracle's report its public relation.
#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

#include "oracle/overlap.hpp"

namespace hipair {

Point Placement::apply(const Point& p) const {
  return Point{Rational(cos * p.x - sin * p.y + offset.x), Rational(sin * p.x + cos * p.y + offset.y)};
}

Placement placement_about(const Point& pivot, const Rational& cos, const Rational& sin, const Point& shift) {
  Placement placement;
  placement.cos = cos;
  placement.sin = sin;
  Point rotated{Rational(cos * pivot.x - sin * pivot.y), Rational(sin * pivot.x + cos * pivot.y)};
  placement.offset = Point{Rational(pivot.x - rotated.x + shift.x), Rational(pivot.y - rotated.y + shift.y)};
  return placement;
}

namespace {

// Rationals built from (numerator, denominator) need not be canonical, and GMP's rational
// arithmetic and comparisons assume canonical operands (Rational(12, 2) as an offset gave
// "overlapping" where the parts touch): the door canonicalises what it is given.
cspace::RigidMap rigid_of(const Placement& placement, const char* which) {
  cspace::RigidMap map;
  map.c = placement.cos;
  map.s = placement.sin;
  map.offset = placement.offset;
  for (Rational* value : {&map.c, &map.s, &map.offset.x, &map.offset.y}) value->canonicalize();
  if (map.c * map.c + map.s * map.s != 1)
    throw NumericError(std::string("part_overlap: the ") + which + " placement is not rigid (cos^2 + sin^2 != 1)");
  return map;
}

}  // namespace

PartOverlap part_overlap(const Part& first, const Placement& first_placement, const Part& second,
                         const Placement& second_placement, bool want_witness) {
  cspace::OverlapOptions options;
  options.want_witness = want_witness;
  cspace::OverlapReport report = cspace::analyse_overlap(first, rigid_of(first_placement, "first"), second,
                                                         rigid_of(second_placement, "second"), options);
  PartOverlap result;
  switch (report.relation) {
    case cspace::Overlap::apart: result.relation = PartRelation::apart; break;
    case cspace::Overlap::touching: result.relation = PartRelation::touching; break;
    case cspace::Overlap::overlapping: result.relation = PartRelation::overlapping; break;
  }
  result.witness = std::move(report.witness);
  return result;
}

}  // namespace hipair
