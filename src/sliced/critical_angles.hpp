// Critical angles of a polygonal part free in the plane against a fixed polygonal part
// (docs/cspace.md, "3-DOF pairs"): the rotations at which the free space of the translational
// slice changes its contact structure. Every candidate event is a polynomial in the half-angle
// tangent t (vertex–vertex contacts are a_i - p - R(t) u_j, with R's entries rational in t);
// its roots are isolated exactly, checked exactly against the features' extents, and dropped
// only when the event point is certified to lie inside blocked space (interval enclosure of the
// configuration and an interior witness point certified inside both parts). CGAL-free.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/geometry.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include "algebra/exact_real.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::sliced {

/// The polygonal geometry of the pair: the fixed part's vertices (world), the free part's
/// vertices relative to its pivot, and their edges (source, target) with material on the left.
struct PolygonalPair {
  std::vector<Point> a;                                   ///< fixed part vertices minus pivot
  std::vector<std::pair<std::size_t, std::size_t>> a_edges;
  std::vector<Point> u;                                   ///< free part vertices minus pivot
  std::vector<std::pair<std::size_t, std::size_t>> b_edges;
  Point pivot;
  const Part* fixed = nullptr;
  const Part* free = nullptr;
};

/// \throws GeometryError when a part has an arc.
PolygonalPair polygonal_pair(const Part& fixed, const Part& free);

/// A critical angle, exact.
struct Critical {
  bool half_turn = false;
  cspace::algebra::Real t;   ///< the half-angle tangent (half_turn: unused)
  std::vector<CriticalEvent> events;
};

struct CriticalStatistics {
  std::size_t polynomials = 0;
  std::size_t roots = 0;
  std::size_t irrelevant = 0;
  /// Certificate probes (a vertex or midpoint of one part tested inside the other at a root's
  /// enclosure) rejected by the certified double-interval test, without exact enclosures.
  std::size_t probes_filtered = 0;
  /// Roots whose event conditions were decided without forming them as polynomials (in
  /// certified double intervals, or exactly at a rational root: CurveFinder::verdict_at).
  std::size_t verdicts = 0;
  /// Witness searches of the exact overlap oracle at a root's enclosure (its mid configuration
  /// overlapping), those that found no witness (a sliver below the search's 2^-600 of the
  /// parts' size), and searches skipped because a configuration of the enclosure is exactly
  /// not overlapping (no witness could be certified there: Certifier::apart_in_enclosure).
  std::size_t witness_searches = 0;
  std::size_t witness_searches_failed = 0;
  std::size_t witness_searches_skipped = 0;
};

/// The critical angles, in counter-clockwise order from -pi (t ascending, the half turn last).
std::vector<Critical> critical_angles(const PolygonalPair& pair, CriticalStatistics& statistics);

/// The critical angles of a pair with circular arcs (docs/cspace.md, "Critical angles with
/// arcs"): arcs of rational radius; a segment facing a convex arc of the other part of rational
/// length. \throws GeometryError otherwise.
std::vector<Critical> critical_angles_with_arcs(const Part& fixed, const Part& free, CriticalStatistics& statistics);

/// The critical values of tau = tan(psi/2) of a pin-slot part (rotation psi about its pivot, then
/// the slide s in [s_lo, s_hi] along its turned direction d) against a fixed part (`q_range`
/// empty: the slice is the segment X = s R d of the translation plane) or a part translating
/// along f by q in `q_range` (the slice is the parallelogram X = s R d - q f, a linear image of
/// the 3-DOF slice): the events of critical_angles_with_arcs inside the window, those with the
/// window's edges, and (translating) where R d is parallel to f. Same input class as
/// critical_angles_with_arcs (polygonal parts included). With `tau_range`, only critical values
/// in it (and not the half turn) are found. `filters` (default): an event polynomial is formed
/// exactly only when certified double intervals over the range do not prove that it has no
/// root there meeting its conditions, and the exact overlap oracle's answers at rational
/// configurations are remembered; the result is the same as without (`filters` false: the
/// plain exact path, for tests). `statistics.polynomials` counts the polynomials formed.
/// `centre`: the point the part's curves turn about (the part about its pivot P is the part
/// about Q translated by (I - R)(P - Q): the same critical values); by default its first vertex
/// when its reach about P exceeds 2^20 times its reach about that vertex (a far pivot: about P
/// the curves cancel beyond the certified doubles), else P.
std::vector<Critical> pin_slot_critical_values(const Part& other, const Part& pin, const Rational& s_lo, const Rational& s_hi,
                                               const std::optional<std::pair<Rational, Rational>>& q_range,
                                               const std::optional<std::pair<Rational, Rational>>& tau_range,
                                               CriticalStatistics& statistics, bool filters = true,
                                               const std::optional<Point>& centre = std::nullopt);

/// An exact real (algebra) as the public AlgebraicNumber, and back.
AlgebraicNumber algebraic_of(const cspace::algebra::Real& r);
cspace::algebra::Real real_of(const AlgebraicNumber& a);

/// The exact factor k > 0 at which the critical angles of `fixed` against `free` are computed
/// (the parts times k about the origin have the same angles): 1 / the common measure of every
/// coordinate of both parts and the free part's pivot (gcd of numerators / lcm of denominators:
/// the scaled coordinates are integers), when the parts are all tiny or all huge (the largest
/// coordinate outside [2^-20, 2^40] mm) and the integers are shorter than the coordinates;
/// nullopt otherwise (ordinary models keep model units). `any_scale`: at any largest coordinate
/// (a pair normalised by a power of two from 10^400 mm lies near 64 mm, but its rationals carry
/// 5^400: SlicedBuildOptions::normalise_lengths).
std::optional<Rational> scale_free_factor(const Part& fixed, const Part& free, bool any_scale = false);

/// A length for nudges and steps that must follow the pair's scale: 1 (mm) for ordinary pairs
/// (the largest coordinate in [2^-20, 2^40] mm), otherwise the power of two 2^(e - 4) with 2^e
/// within a factor 2 of the largest coordinate (exact).
Rational length_unit(const Part& fixed, const Part& free);
/// length_unit's rule for a given largest coordinate (1 in [2^-20, 2^40] mm, else 2^(e - 4)).
Rational length_unit_of_largest(const Rational& largest);

/// The power of two 2^(e - 4) with 2^e within a factor 2 of the largest coordinate, at any
/// scale (length_unit without the ordinary range; 1 for a pair with no coordinate but 0).
Rational size_unit(const Part& fixed, const Part& free);

/// The part with every length multiplied by k > 0 about the origin (points, pivot, radii by k).
Part scaled_part(const Part& part, const Rational& k);

/// cos and sin of the rotation with half-angle tangent t (or the half turn), exact.
std::pair<Rational, Rational> rotation_of(const SlicedAngle& angle);

/// The rotation theta(u) = 2 atan(u), or pi + 2 atan(u) when `flip` (u = -1/t: the chart
/// about the half turn).
std::pair<Rational, Rational> rotation_at(const Rational& u, bool flip);

/// Does the free part at offset q keep its overlap relation for every theta(u), u in
/// [u_lo, u_hi] (see rotation_at)? Exact and conservative: true when no vertex–edge contact
/// line (extents ignored) passes through q for any such u.
bool steady_along(const PolygonalPair& pair, const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip);

}  // namespace hipair::sliced
