// Hand cases of the verifier's own predicates: exact point location with holes, vertices and
// arcs; transversal crossings (and the tangencies and touches that are not); certified distance
// bounds; crossings that hold over an interval of rotations.
#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"

#include <gtest/gtest.h>

namespace {

using namespace hipair;
using namespace hipair::verify;

Point P(Rational x, Rational y) { return Point{x, y}; }

Edge segment(Point a, Point b) {
  Edge e;
  e.source = a;
  e.target = b;
  return e;
}
Edge arc(Point a, Point b, Point c, bool ccw) {
  Edge e;
  e.kind = Edge::Kind::arc;
  e.source = a;
  e.target = b;
  e.center = c;
  e.ccw = ccw;
  e.radius_squared = (a.x - c.x) * (a.x - c.x) + (a.y - c.y) * (a.y - c.y);
  return e;
}

// A 10 x 10 square (ccw) with a hole of radius 2 at (5, 5) (a full circle, cw).
Part square_with_hole() {
  Part part;
  part.name = "plate";
  part.loops.push_back(Loop{{segment(P(0, 0), P(10, 0)), segment(P(10, 0), P(10, 10)), segment(P(10, 10), P(0, 10)),
                             segment(P(0, 10), P(0, 0))},
                            false, ""});
  part.loops.push_back(Loop{{arc(P(7, 5), P(7, 5), P(5, 5), false)}, true, ""});
  return part;
}

TEST(CertifyGeometry, PointLocationWithHolesVerticesAndArcs) {
  PlacedPart plate = place(square_with_hole(), ExactMap{});
  EXPECT_EQ(locate(plate, P(1, 1)), 1);
  EXPECT_EQ(locate(plate, P(5, 5)), -1);             // in the hole
  EXPECT_EQ(locate(plate, P(5, 7)), 0);              // on the hole's circle
  EXPECT_EQ(locate(plate, P(0, 0)), 0);              // a vertex
  EXPECT_EQ(locate(plate, P(5, 10)), 0);             // on an edge
  EXPECT_EQ(locate(plate, P(11, 5)), -1);
  EXPECT_EQ(locate(plate, P(Rational(7, 1) + Rational(1, 1000000000), 5)), 1);   // just outside the hole
  EXPECT_EQ(locate(plate, P(Rational(7, 1) - Rational(1, 1000000000), 5)), -1);  // just inside it
  EXPECT_EQ(locate(plate, P(1, 5)), 1);              // the ray along y = 5 passes the hole's tangent points
  // Rotated a quarter turn about (0, 0): (-5, 5) is the hole's centre.
  PlacedPart turned = place(square_with_hole(), ExactMap{0, 1, P(0, 0), P(0, 0)});
  EXPECT_EQ(locate(turned, P(-5, 5)), -1);
  EXPECT_EQ(locate(turned, P(-1, 1)), 1);
  // A half disc: the ccw arc from (1, 0) to (-1, 0) about the origin and the diameter back.
  Part half;
  half.loops.push_back(Loop{{arc(P(1, 0), P(-1, 0), P(0, 0), true), segment(P(-1, 0), P(1, 0))}, false, ""});
  PlacedPart placed = place(half, ExactMap{});
  EXPECT_EQ(locate(placed, P(0, Rational(1, 2))), 1);
  EXPECT_EQ(locate(placed, P(0, Rational(-1, 2))), -1);
  EXPECT_EQ(locate(placed, P(Rational(3, 5), Rational(4, 5))), 0);   // on the arc
  EXPECT_EQ(locate(placed, P(Rational(3, 5), Rational(-4, 5))), -1);  // on the circle, outside the arc
}

TEST(CertifyGeometry, TransversalCrossingsOnly) {
  auto placed = [](const Edge& e) {
    Part part;
    part.loops.push_back(Loop{{e}, false, ""});
    return place(part, ExactMap{}).loops[0][0];
  };
  PlacedEdge horizontal = placed(segment(P(-2, 0), P(2, 0)));
  EXPECT_TRUE(edges_cross(horizontal, placed(segment(P(0, -1), P(0, 1)))));
  EXPECT_FALSE(edges_cross(horizontal, placed(segment(P(0, 0), P(0, 1)))));     // touches at an end point
  EXPECT_FALSE(edges_cross(horizontal, placed(segment(P(-1, 0), P(1, 0)))));    // collinear
  PlacedEdge upper = placed(arc(P(1, 0), P(-1, 0), P(0, 0), true));             // upper half circle
  EXPECT_TRUE(edges_cross(placed(segment(P(0, 0), P(0, 3))), upper));
  EXPECT_FALSE(edges_cross(placed(segment(P(0, 0), P(0, -3))), upper));         // crosses the circle off the arc
  EXPECT_FALSE(edges_cross(placed(segment(P(-3, 1), P(3, 1))), upper));         // tangent at (0, 1)
  EXPECT_TRUE(edges_cross(placed(segment(P(-3, Rational(99, 100)), P(3, Rational(99, 100)))), upper));
  EXPECT_TRUE(edges_cross(upper, placed(arc(P(1, 1), P(1, -1), P(1, 0), true))));   // circles through (1/2, ±sqrt(3)/2)
  EXPECT_FALSE(edges_cross(upper, placed(arc(P(2, 0), P(-2, 0), P(0, 0), true))));  // concentric
  EXPECT_FALSE(edges_cross(upper, placed(arc(P(0, 1), P(0, 3), P(0, 2), false))));  // externally tangent at (0, 1)
}

TEST(CertifyGeometry, DistanceBoundsAreCertifiedAndTight) {
  Part disc_a, disc_b;
  disc_a.name = "a";
  disc_b.name = "b";
  disc_a.loops.push_back(Loop{{arc(P(1, 0), P(1, 0), P(0, 0), true)}, false, ""});
  disc_b.loops.push_back(Loop{{arc(P(4, 0), P(4, 0), P(3, 0), true)}, false, ""});   // gap 1
  IntervalPart a = place_over(disc_a, IntervalMap{}), b = place_over(disc_b, IntervalMap{});
  Rational bound = boundary_distance_lower_bound(a, b, Rational(100));
  EXPECT_LE(bound, 1);
  EXPECT_GE(bound, Rational(999999999999, 1000000000000));
  EXPECT_EQ(boundary_distance_lower_bound(a, b, Rational(1, 2)), Rational(1, 2));   // capped
  // A square's corner at distance 1/2 from a segment.
  Part plate = square_with_hole(), bar;
  bar.name = "bar";
  bar.loops.push_back(Loop{{segment(P(11, -5), P(11, 5)), segment(P(11, 5), P(12, 5)), segment(P(12, 5), P(12, -5)),
                            segment(P(12, -5), P(11, -5))},
                           false, ""});
  Rational corner = boundary_distance_lower_bound(place_over(plate, IntervalMap{}), place_over(bar, IntervalMap{}), Rational(100));
  EXPECT_LE(corner, 1);
  EXPECT_GE(corner, Rational(999999999, 1000000000));
}

TEST(CertifyGeometry, CrossingsOverAnIntervalOfRotations) {
  // A lever (segment from the pivot at the origin to (10, 0)) turned by 0.3..0.4 rad crosses the
  // vertical segment x = 5, y in [0, 5]: its piece [0.4, 0.6] crosses for every angle.
  Part lever, wall;
  lever.name = "lever";
  lever.motion.kind = Motion::Kind::rotation;
  lever.loops.push_back(Loop{{segment(P(0, 0), P(10, 0))}, false, ""});
  wall.name = "wall";
  wall.loops.push_back(Loop{{segment(P(5, 0), P(5, 5))}, false, ""});
  IntervalEdge turned = place_over(lever, rotation_over({Rational(3, 10), Rational(4, 10)})).loops[0][0];
  IntervalEdge fixed = place_over(wall, IntervalMap{}).loops[0][0];
  std::string why;
  EXPECT_TRUE(crossing_certain(turned, {Rational(4, 10), Rational(6, 10)}, fixed, &why)) << why;
  EXPECT_FALSE(crossing_certain(turned, {Rational(6, 10), Rational(8, 10)}, fixed, &why));   // beyond the wall
  EXPECT_NE(why.find("opposite sides"), std::string::npos);
  // Turned by 1.2..1.3 rad the crossing with x = 5 lies above the wall's top.
  IntervalEdge steep = place_over(lever, rotation_over({Rational(12, 10), Rational(13, 10)})).loops[0][0];
  EXPECT_FALSE(crossing_certain(steep, {Rational(1, 2), Rational(1)}, fixed, &why));
}

}  // namespace
