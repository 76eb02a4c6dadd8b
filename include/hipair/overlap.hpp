// HIPAIR — the exact overlap predicate of two parts at exact placements: the oracle that
// classifies every C-space face, as a public door for the library's other layers (certificate
// producers, tools) and for users. Decisions are exact (GMP): placements are rational rigid
// maps, arcs keep rational centres and squared radii, irrational intersection points are only
// ever tested by exact sign computations.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <optional>

namespace hipair {

/// An exact rigid placement of a part: body point p goes to R p + offset in the world, with
/// R = [cos -sin; sin cos] and cos^2 + sin^2 = 1 (rational: a rotation through a rational
/// half-angle tangent).
struct Placement {
  Rational cos = 1;
  Rational sin = 0;
  Point offset{Rational(0), Rational(0)};
  /// The world position of body point p.
  Point apply(const Point& p) const;
};

/// The placement that turns a part by the rotation (cos, sin) about world point `pivot` and
/// then shifts it by `shift`: p -> pivot + R (p - pivot) + shift.
Placement placement_about(const Point& pivot, const Rational& cos, const Rational& sin, const Point& shift);

/// How two placed parts (closed regions bounded by their loops) relate.
enum class PartRelation {
  apart,       ///< closed parts disjoint
  touching,    ///< boundaries meet, interiors disjoint
  overlapping  ///< interiors intersect
};

/// The exact relation of two placed parts.
struct PartOverlap {
  PartRelation relation = PartRelation::apart;
  /// A rational world point strictly inside both parts, when asked for and the parts overlap
  /// (nullopt when the search for a rational one failed: the interiors may meet only in an
  /// irrational lens; see docs/cspace.md).
  std::optional<Point> witness;
};

/// The exact relation of `first` placed by `first_placement` and `second` placed by
/// `second_placement`; with `want_witness`, a rational interior point of both when they overlap.
/// \throws NumericError when a placement is not a rigid map (cos^2 + sin^2 != 1).
PartOverlap part_overlap(const Part& first, const Placement& first_placement, const Part& second,
                         const Placement& second_placement, bool want_witness = false);

}  // namespace hipair
