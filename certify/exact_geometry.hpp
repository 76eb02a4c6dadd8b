// The verifier's exact geometry: parts posed by exact rational rigid maps, exact point
// location in a region bounded by segments and circular arcs, and exact transversal crossings
// of two boundary edges. Irrational intersection points lie in Q(sqrt(D)); they are only used
// through exact signs of a + b sqrt(D).
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hipair::verify {

/// A claim that does not hold, with the exact reason (the verifier's only failure mode).
struct Rejection {
  std::string reason;
};

/// p -> pivot + R (p - pivot) + shift with R = [c -s; s c], c^2 + s^2 = 1.
struct ExactMap {
  Rational c = 1, s = 0;
  Point pivot{Rational(0), Rational(0)};
  Point shift{Rational(0), Rational(0)};
  Point apply(const Point& p) const;
  Point rotate(const Point& v) const;
};

/// An edge posed in the world. Arcs also carry their counter-clockwise sector: the directions
/// `from` -> `to` from the centre (source/target for ccw arcs, swapped for cw arcs).
struct PlacedEdge {
  bool arc = false;
  bool full_circle = false;
  bool reflex = false;   ///< the sector spans more than a half turn
  Point source, target, center, from, to;
  Rational radius_squared;
  /// An exact box containing the edge (x0, x1, y0, y1; an arc's box is that of its end points
  /// and of the circle's axis-extreme points within its sector, with a rational upper bound of
  /// the radius): only used to skip exact tests that cannot succeed.
  /// Every comparison with it is exact.
  std::array<Rational, 4> box{};
  /// `box` rounded outwards to doubles (a screen before the exact comparisons).
  std::array<double, 4> outer{};
};

/// A part posed in the world: its edges loop by loop.
struct PlacedPart {
  std::string name;
  std::vector<std::vector<PlacedEdge>> loops;
};

PlacedPart place(const Part& part, const ExactMap& map);

/// Sign of a + b sqrt(d), d >= 0.
int sign_with_root(const Rational& a, const Rational& b, const Rational& d);

/// True when the direction with cross signs s1 = sign(from x v), s2 = sign(v x to) lies in the
/// arc's sector (open: not at an end; a full circle contains every direction).
bool in_sector(const PlacedEdge& arc, int s1, int s2, bool open);

/// Where `p` lies: +1 strictly inside the part's material, 0 on its boundary, -1 outside.
/// \throws Rejection if no ray from p avoids every vertex and tangency (never seen in practice).
int locate(const PlacedPart& part, const Point& p);

/// True when edges e and g cross transversally at a point interior to both (which proves that
/// their parts overlap, by the model reader's invariant that a part's edges meet only at
/// shared vertices).
bool edges_cross(const PlacedEdge& e, const PlacedEdge& g);

/// Is the distance between the boundaries of the posed parts at least `d` (> 0)? Decided
/// exactly: a pair of edges is at least d apart when the edges do not cross and each candidate
/// for their closest points is: an end point against the other edge; the foot of an arc's centre
/// on a segment against the arc's points on that perpendicular; concentric arcs along a shared
/// direction; two arcs' points on their centre line (a sum of three square roots, signed by
/// squaring). For clearance claims at the exact distance, where the MPFI bound falls a hair
/// short (session 41, hunt41).
bool boundary_distance_at_least(const PlacedPart& a, const PlacedPart& b, const Rational& d);

/// Evidence that two posed parts overlap: a transversal crossing of two edges, or a loop's
/// first vertex strictly inside the other part. Empty string when none was found.
std::string overlap_evidence(const PlacedPart& a, const PlacedPart& b);

}  // namespace hipair::verify
