// The verifier's certified numeric geometry (MPFI, 256 bits): parts posed over sets of poses
// (an angle or offset interval), lower bounds of the distance between two posed boundaries, and
// crossings of two edges that hold for every pose of a set.
#pragma once

#include "certify/exact_geometry.hpp"
#include "model/interval.hpp"

#include <hipair/model.hpp>

#include <string>
#include <vector>

namespace hipair::verify {

using model_detail::Interval;

struct IntervalPoint {
  Interval x, y;
};

/// A set of rigid maps p -> pivot + R (p - pivot) + shift with R = [c -s; s c], c, s and shift
/// ranging over intervals; `pivot` is the part's rotation pivot (see shape_of).
struct IntervalMap {
  Interval c{Rational(1)}, s{Rational(0)};
  IntervalPoint shift{Interval(Rational(0)), Interval(Rational(0))};
};

/// MPFI sine and cosine of an angle enclosure (rad), or [-1, 1] when it is unbounded or an end
/// lies beyond 2^1100 in magnitude: a valid enclosure either way. MPFR reduces the argument
/// exactly, in time growing with its exponent: a forged certificate's angle "1e100000" kept the
/// verifier busy for minutes (session 35, hunt35); no model angle comes near 2^1100.
Interval sin_of(const Interval& angle);
Interval cos_of(const Interval& angle);

IntervalMap to_interval_map(const ExactMap& map);
/// All rotations (about the part's pivot) by angles in `angle` (rad).
IntervalMap rotation_over(const RationalInterval& angle);
/// All translations by offsets in `offset` along the unit vector `direction`.
IntervalMap translation_over(const Point& direction, const RationalInterval& offset);

/// An edge posed by an IntervalMap (arcs: ccw sector from `from` to `to`, see PlacedEdge), with
/// a bounding disc (`disc_center`, `disc_radius`) used to skip far pairs.
struct IntervalEdge {
  bool arc = false, full_circle = false, reflex = false, ccw = true;
  IntervalPoint source, target, center, from, to, disc_center;
  Interval radius_squared, radius, sweep, disc_radius;
};

/// A part's edges, either in its body frame relative to its pivot (a shape) or posed; `groups`
/// bound runs of consecutive edges of a loop (culling).
struct IntervalPart {
  std::string name;
  IntervalPoint pivot;
  std::vector<std::vector<IntervalEdge>> loops;
  struct Group {
    std::size_t loop, first, last;
    IntervalPoint center;
    Interval radius;
  };
  std::vector<Group> groups;
};

/// The rotation pivot of a part (the origin for parts that do not rotate).
Point pose_pivot(const Part& part);

/// The part's geometry relative to its pose pivot, with every pose-independent quantity (radii,
/// sweeps, bounding discs) computed once.
IntervalPart shape_of(const Part& part);

/// The shape posed by every map of `map` (rotations about the shape's pivot).
IntervalPart place_over(const IntervalPart& shape, const IntervalMap& map);
/// A point of the shape (body frame, relative to its pivot) posed by `map`.
IntervalPoint place_point(const IntervalPart& shape, const IntervalMap& map, const IntervalPoint& p);
inline IntervalPart place_over(const Part& part, const IntervalMap& map) { return place_over(shape_of(part), map); }

/// A certified lower bound of the distance between the boundaries of the two posed parts,
/// for every pose of their maps, capped at `enough` (pairs farther than `enough` are skipped):
/// min(enough, min over edge pairs of the largest of three certified lower bounds of the
/// pair's distance: its edges' disc gap, its groups' disc gap, its enclosed distance). The
/// value does not depend on the order in which pairs are tried (nearest discs first).
/// `closest` (optional) names the edge pair that gave the bound.
Rational boundary_distance_lower_bound(const IntervalPart& a, const IntervalPart& b, const Rational& enough,
                                       std::string* closest = nullptr);
/// The same bound for the shapes posed by `map_a` and `map_b` (equal to the bound of the
/// place_over parts), posing only the edges whose groups' discs come near.
Rational boundary_distance_lower_bound(const IntervalPart& shape_a, const IntervalMap& map_a, const IntervalPart& shape_b,
                                       const IntervalMap& map_b, const Rational& enough, std::string* closest = nullptr);

/// A certified lower bound of the distance from the exact point `p` to the boundary of the
/// shape posed by every map of `map`, capped at `enough` (0 when they may meet).
Rational point_boundary_distance_lower_bound(const IntervalPart& shape, const IntervalMap& map, const Point& p,
                                             const Rational& enough);

/// An upper bound of the distance of every point of a shape from its pivot.
Rational reach(const IntervalPart& shape);

/// The point of edge e at parameter u (segment fraction, or arc angle from the source in the
/// arc's direction), for every pose and every u in the interval.
IntervalPoint point_on(const IntervalEdge& e, const Interval& u);

/// The side function of edge g's line (cross product with its direction) or circle
/// (power of the point), whose sign tells on which side of g's support p lies.
Interval side_of(const IntervalEdge& g, const IntervalPoint& p);

/// True when, for every pose, the piece `along` of edge e (segment fraction, or arc angles from
/// the source in the arc's direction) crosses edge g: its ends lie strictly on opposite sides
/// of g's line or circle and the whole piece lies strictly within g's extent. Then a point of
/// e's part lies strictly inside g's part. `why` receives the first condition that failed.
bool crossing_certain(const IntervalEdge& e, const RationalInterval& along, const IntervalEdge& g, std::string* why);

}  // namespace hipair::verify
