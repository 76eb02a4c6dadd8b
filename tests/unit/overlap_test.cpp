// Exact overlap predicate: hand cases with exact answers, including values a double cannot
// hold (2^53 + 1, 10^-30 offsets), tangencies, coincident edges, holes and zero clearance.
#include "oracle/overlap.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <initializer_list>
#include <random>

namespace hipair::cspace {
namespace {

Rational q(const char* text) { return Rational(text); }
// gmpxx does not canonicalise mpq_class(a, b): every fraction goes through this.
Rational frac(long numerator, long denominator) {
  Rational value(numerator, denominator);
  value.canonicalize();
  return value;
}

Point pt(const Rational& x, const Rational& y) { return Point{x, y}; }

Edge segment(const Point& a, const Point& b, std::string label = "") {
  Edge e;
  e.kind = Edge::Kind::segment;
  e.source = a;
  e.target = b;
  e.label = std::move(label);
  return e;
}

Edge arc(const Point& a, const Point& b, const Point& center, bool ccw) {
  Edge e;
  e.kind = Edge::Kind::arc;
  e.source = a;
  e.target = b;
  e.center = center;
  e.ccw = ccw;
  e.radius_squared = (a.x - center.x) * (a.x - center.x) + (a.y - center.y) * (a.y - center.y);
  return e;
}

// Polygon loop through the points in the given order (caller orients: ccw outer, cw hole).
Loop polygon(std::initializer_list<Point> points, bool hole = false) {
  Loop loop;
  std::vector<Point> p(points);
  for (std::size_t i = 0; i < p.size(); ++i) loop.edges.push_back(segment(p[i], p[(i + 1) % p.size()]));
  loop.is_hole = hole;
  return loop;
}

// Full circle through (cx + r, cy); ccw for material inside, cw for a hole.
Loop circle(const Rational& cx, const Rational& cy, const Rational& r, bool hole = false) {
  Loop loop;
  Point start = pt(cx + r, cy);
  loop.edges.push_back(arc(start, start, pt(cx, cy), !hole));
  loop.is_hole = hole;
  return loop;
}

Part part_of(std::initializer_list<Loop> loops, std::string name = "part") {
  Part part;
  part.name = std::move(name);
  part.loops = loops;
  return part;
}

Loop square(const Rational& x0, const Rational& y0, const Rational& size) {
  return polygon({pt(x0, y0), pt(x0 + size, y0), pt(x0 + size, y0 + size), pt(x0, y0 + size)});
}

RigidMap identity() { return RigidMap{}; }

RigidMap shift(const Rational& dx, const Rational& dy) {
  RigidMap map;
  map.offset = pt(dx, dy);
  return map;
}

Overlap relation(const Part& a, const RigidMap& ma, const Part& b, const RigidMap& mb) {
  return analyse_overlap(a, ma, b, mb).relation;
}

Overlap relation(const Part& a, const Part& b) { return relation(a, identity(), b, identity()); }

// Both orders must agree (the predicate is symmetric).
void expect_relation(const Part& a, const RigidMap& ma, const Part& b, const RigidMap& mb,
                     Overlap expected) {
  EXPECT_EQ(relation(a, ma, b, mb), expected);
  EXPECT_EQ(relation(b, mb, a, ma), expected);
  if (expected == Overlap::overlapping) {
    OverlapOptions options;
    options.want_witness = true;
    OverlapReport report = analyse_overlap(a, ma, b, mb, options);
    ASSERT_TRUE(report.witness.has_value());
    EXPECT_EQ(locate_point(a, ma, *report.witness), PointLocation::inside);
    EXPECT_EQ(locate_point(b, mb, *report.witness), PointLocation::inside);
  }
}

void expect_relation(const Part& a, const Part& b, Overlap expected) {
  expect_relation(a, identity(), b, identity(), expected);
}

const Rational tiny = Rational(1) / Rational(mpz_class("1000000000000000000000000000000"));  // 1e-30

TEST(Overlap, TangentCirclesExactlyTouch) {
  Part small = part_of({circle(0, 0, 1)});
  Part large = part_of({circle(3, 0, 2)});
  expect_relation(small, large, Overlap::touching);
  expect_relation(small, shift(tiny, 0), large, identity(), Overlap::overlapping);
  expect_relation(small, shift(-tiny, 0), large, identity(), Overlap::apart);
}

TEST(Overlap, TangentCirclesAtIrrationalDirection) {
  // centres (0,0) and (3,4) at distance 5 = 2 + 3; tangent point (6/5, 8/5)
  Part a = part_of({circle(0, 0, 2)});
  Part b = part_of({circle(3, 4, 3)});
  expect_relation(a, b, Overlap::touching);
  OverlapOptions options;
  options.want_touches = true;
  OverlapReport report = analyse_overlap(a, identity(), b, identity(), options);
  ASSERT_EQ(report.touches.size(), 1u);
  EXPECT_EQ(report.touches[0].point, pt(frac(6, 5), frac(8, 5)));
  EXPECT_EQ(relation(a, shift(tiny, tiny), b, identity()), Overlap::overlapping);
}

TEST(Overlap, CirclesCrossingAtIrrationalPoints) {
  Part a = part_of({circle(0, 0, 1)});
  Part b = part_of({circle(1, 1, 1)});  // crossing points (0,1) and (1,0): rational
  expect_relation(a, b, Overlap::overlapping);
  Part c = part_of({circle(frac(3, 2), 0, 1)});  // crossing at x = 3/4, y = +-sqrt(7)/4
  expect_relation(a, c, Overlap::overlapping);
}

TEST(Overlap, PinInHoleZeroClearanceTouches) {
  Part plate = part_of({square(-10, -10, 20), circle(0, 0, 3, true)});
  Part pin = part_of({circle(0, 0, 3)});
  expect_relation(pin, plate, Overlap::touching);
  // a hair of clearance: apart; a hair of interference: overlapping
  Part thinner = part_of({circle(0, 0, 3 - tiny)});
  Part thicker = part_of({circle(0, 0, 3 + tiny)});
  expect_relation(thinner, plate, Overlap::apart);
  expect_relation(thicker, plate, Overlap::overlapping);
}

TEST(Overlap, PinInsideHoleWithClearanceIsApart) {
  Part plate = part_of({square(-10, -10, 20), circle(0, 0, 3, true)});
  Part pin = part_of({circle(1, 0, 1)});
  expect_relation(pin, plate, Overlap::apart);
  // the same pin touching the hole wall from inside: (1,0)+(1)=2 ... move to x = 2: 2+1 = 3
  expect_relation(pin, shift(1, 0), plate, identity(), Overlap::touching);
  // pin in the plate's material, away from the hole: overlapping (containment, no crossing)
  expect_relation(pin, shift(6, 0), plate, identity(), Overlap::overlapping);
}

TEST(Overlap, ConcentricArcsOfDifferentRadii) {
  Part ring = part_of({circle(0, 0, 5), circle(0, 0, 4, true)});
  Part disk = part_of({circle(0, 0, 4)});
  expect_relation(disk, ring, Overlap::touching);
  Part big = part_of({circle(0, 0, 6)});
  expect_relation(big, ring, Overlap::overlapping);  // ring entirely inside the disk
  Part outside_ring = part_of({circle(0, 0, 7), circle(0, 0, 5, true)});
  expect_relation(outside_ring, ring, Overlap::touching);
}

TEST(Overlap, CollinearEdges) {
  Part left = part_of({square(0, 0, 1)});
  Part right = part_of({square(1, 0, 1)});
  expect_relation(left, right, Overlap::touching);
  Part shifted = part_of({square(1, frac(1, 2), 1)});
  expect_relation(left, shifted, Overlap::touching);
  expect_relation(left, shift(tiny, 0), right, identity(), Overlap::overlapping);
  expect_relation(left, shift(-tiny, 0), right, identity(), Overlap::apart);
  // same square twice: overlapping (common edges with material on the same side)
  expect_relation(left, left, Overlap::overlapping);
}

TEST(Overlap, VertexOnVertex) {
  Part a = part_of({square(0, 0, 1)});
  Part b = part_of({square(1, 1, 1)});
  expect_relation(a, b, Overlap::touching);
  expect_relation(a, shift(tiny, tiny), b, identity(), Overlap::overlapping);
  expect_relation(a, shift(tiny, -tiny), b, identity(), Overlap::apart);
  // a diamond whose vertex sits exactly on the square's corner from outside
  Part diamond = part_of({polygon({pt(1, 1), pt(3, 0), pt(5, 1), pt(3, 2)})});
  // corner angle of the diamond at (1,1) opens towards +x: overlaps the square near (1,1)?
  // The square occupies x <= 1 there; the diamond x >= 1: touching.
  expect_relation(a, diamond, Overlap::touching);
  Part spike = part_of({polygon({pt(1, 1), pt(0, 3), pt(-1, 3)})});  // spike from above-left
  expect_relation(a, spike, Overlap::touching);
  Part into = part_of({polygon({pt(1, 1), pt(0, 3), pt(0, frac(1, 2))})});  // enters the square
  expect_relation(a, into, Overlap::overlapping);
}

TEST(Overlap, VertexOnEdge) {
  Part base = part_of({square(0, 0, 4)});
  Part wedge = part_of({polygon({pt(2, 4), pt(3, 6), pt(1, 6)})});  // apex on the top edge
  expect_relation(base, wedge, Overlap::touching);
  expect_relation(base, identity(), wedge, shift(0, -tiny), Overlap::overlapping);
  expect_relation(base, identity(), wedge, shift(0, tiny), Overlap::apart);
}

TEST(Overlap, HugeCoordinatesBeyondDouble) {
  // 2^53 + 1 is not a double: a double filter would see the squares touching.
  Rational big(mpz_class("9007199254740993"));
  Rational big_minus_one(mpz_class("9007199254740992"));
  Part a = part_of({square(0, 0, big)});
  Part b = part_of({square(big, 0, 1)});
  expect_relation(a, b, Overlap::touching);
  Part c = part_of({square(big_minus_one, 0, 2)});  // overlaps by exactly 1
  expect_relation(a, c, Overlap::overlapping);
  Part d = part_of({square(big + 1, 0, 1)});
  expect_relation(a, d, Overlap::apart);
}

TEST(Overlap, ArcTangentToSegment) {
  Part floor_part = part_of({square(-5, -5, 5)});  // top edge y = 0 from x = -5 to 0
  Part wheel = part_of({circle(-2, 1, 1)});          // touches y = 0 at (-2, 0)
  expect_relation(floor_part, wheel, Overlap::touching);
  expect_relation(floor_part, identity(), wheel, shift(0, -tiny), Overlap::overlapping);
  // tangent exactly at the square's corner (0,0): circle centre (0, 1)
  Part corner_wheel = part_of({circle(0, 1, 1)});
  expect_relation(floor_part, corner_wheel, Overlap::touching);
  // circle with irrational radius (r^2 = 2) crossing the edge at irrational points
  // x = -2 +- sqrt(7)/2
  Loop irrational;
  Edge full;
  full.kind = Edge::Kind::arc;
  full.source = pt(-1, frac(3, 2));
  full.target = full.source;
  full.center = pt(-2, frac(1, 2));
  full.radius_squared = 2;
  full.ccw = true;
  irrational.edges.push_back(full);
  Part crossing = part_of({irrational});
  expect_relation(floor_part, crossing, Overlap::overlapping);
}

TEST(Overlap, NestedWithoutBoundaryContact) {
  Part outer = part_of({square(0, 0, 10)});
  Part inner = part_of({square(2, 2, 1)});
  expect_relation(outer, inner, Overlap::overlapping);
  Part frame = part_of({square(0, 0, 10), polygon({pt(1, 1), pt(1, 9), pt(9, 9), pt(9, 1)}, true)});
  expect_relation(frame, inner, Overlap::apart);  // inside the frame's hole
}

TEST(Overlap, RotatedPartsExactly) {
  // A unit square rotated by the rational half-angle tangent t = 1/2 (cos 3/5, sin 4/5)
  // about the origin; a square placed so that the rotated corner (3/5 - 4/5, 4/5 + 3/5)
  // = (-1/5, 7/5) touches its bottom edge.
  Part a = part_of({square(0, 0, 1)});
  RigidMap rotation;
  rotation.c = frac(3, 5);
  rotation.s = frac(4, 5);
  Part b = part_of({square(-1, frac(7, 5), 2)});
  expect_relation(a, rotation, b, identity(), Overlap::touching);
  expect_relation(a, rotation, b, shift(0, -tiny), Overlap::overlapping);
  expect_relation(a, rotation, b, shift(0, tiny), Overlap::apart);
}

TEST(Overlap, LocatePointRespectsHoles) {
  Part plate = part_of({square(-10, -10, 20), circle(0, 0, 3, true)});
  EXPECT_EQ(locate_point(plate, identity(), pt(0, 0)), PointLocation::outside);
  EXPECT_EQ(locate_point(plate, identity(), pt(3, 0)), PointLocation::boundary);
  EXPECT_EQ(locate_point(plate, identity(), pt(5, 0)), PointLocation::inside);
  EXPECT_EQ(locate_point(plate, identity(), pt(0, 3 + tiny)), PointLocation::inside);
  EXPECT_EQ(locate_point(plate, identity(), pt(0, 3 - tiny)), PointLocation::outside);
  EXPECT_EQ(locate_point(plate, identity(), pt(-10, 0)), PointLocation::boundary);
  EXPECT_EQ(locate_point(plate, identity(), pt(11, 0)), PointLocation::outside);
  // rays through vertices and tangent to the hole: points at the hole's top height
  EXPECT_EQ(locate_point(plate, identity(), pt(-5, 3)), PointLocation::inside);
  EXPECT_EQ(locate_point(plate, identity(), pt(-5, -10 + tiny)), PointLocation::inside);
}

// Random polygons: compare with a brute-force oracle on a fine rational grid of probe points
// (a probe strictly inside both proves overlap; a missing probe does not prove anything, so
// only the implication "grid witness => overlapping" is checked), and symmetry.
TEST(Overlap, RandomTrianglesConsistentWithProbes) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coordinate(-6, 6);
  auto random_triangle = [&]() {
    while (true) {
      Point a = pt(coordinate(rng), coordinate(rng));
      Point b = pt(coordinate(rng), coordinate(rng));
      Point c = pt(coordinate(rng), coordinate(rng));
      Rational orientation = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (sgn(orientation) > 0) return part_of({polygon({a, b, c})});
      if (sgn(orientation) < 0) return part_of({polygon({a, c, b})});
    }
  };
  int overlapping = 0, touching = 0, apart = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Part s = random_triangle();
    Part t = random_triangle();
    Overlap r = relation(s, t);
    EXPECT_EQ(r, relation(t, s));
    bool grid_witness = false;
    for (int i = -24; i <= 24 && !grid_witness; ++i)
      for (int j = -24; j <= 24 && !grid_witness; ++j) {
        Point p = pt(frac(i, 4) + frac(1, 7), frac(j, 4) + frac(1, 11));
        grid_witness = locate_point(s, identity(), p) == PointLocation::inside &&
                       locate_point(t, identity(), p) == PointLocation::inside;
      }
    if (grid_witness) EXPECT_EQ(r, Overlap::overlapping);
    if (r == Overlap::overlapping) ++overlapping;
    if (r == Overlap::touching) ++touching;
    if (r == Overlap::apart) ++apart;
  }
  EXPECT_GT(overlapping, 0);
  EXPECT_GT(touching, 0);  // integer grids make exact contacts common
  EXPECT_GT(apart, 0);
}

}  // namespace
}  // namespace hipair::cspace

namespace hipair::cspace {
namespace {

// The certified interval filter never changes an answer: compare with the exact-only path on
// the Geneva pair at random chart points and on points of its contact curves' neighbourhood.
TEST(Overlap, IntervalFilterAgreesWithExactPath) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/geneva.json");
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coordinate(-1000, 1000);
  OverlapOptions exact;
  exact.exact_only = true;
  int counts[3] = {0, 0, 0};
  for (const ChartAxis& x : layout.x_charts)
    for (const ChartAxis& y : layout.y_charts)
      for (int trial = 0; trial < 150; ++trial) {
        ChartPoint q{frac(coordinate(rng), 1000), frac(coordinate(rng), 1000)};
        Overlap fast = classify_overlap(model, axes, x, y, q);
        EXPECT_EQ(fast, analyse_overlap(model, axes, x, y, q, exact).relation);
        ++counts[static_cast<int>(fast)];
      }
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[2], 0);
}

}  // namespace
}  // namespace hipair::cspace

namespace hipair::cspace {
namespace {

// The witness search locates its candidate points by the certified interval ray cast first
// (exact only when an interval decision is uncertain). Generated cases: random grid triangles,
// squares with round holes and disks, posed by random rational rotations and offsets, many of
// them touching (zero clearance on the integer grid), tangent (a disk on a square's side) or
// overlapping by a sliver; the relation and the witness must equal the exact-only path's, and
// every witness must be located strictly inside both parts by the exact predicate.
TEST(Overlap, FilteredWitnessSearchEqualsExactPath) {
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> coordinate(-4, 4), tangent(-3, 3), sliver(-2, 2);
  auto random_part = [&](int kind) {
    if (kind == 0)
      while (true) {
        Point a = pt(coordinate(rng), coordinate(rng)), b = pt(coordinate(rng), coordinate(rng)),
              c = pt(coordinate(rng), coordinate(rng));
        int o = sgn(Rational((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)));
        if (o > 0) return part_of({polygon({a, b, c})});
        if (o < 0) return part_of({polygon({a, c, b})});
      }
    if (kind == 1) return part_of({square(-3, -3, 6), circle(0, 0, 1, true)});
    return part_of({circle(coordinate(rng), coordinate(rng), Rational(1 + (coordinate(rng) + 4) % 3))});
  };
  auto random_map = [&](bool grid) {
    RigidMap map;
    if (grid) {   // no rotation, integer offsets (exact contacts on the grid are common) moved
                  // by a sliver 2^-30 or not: overlaps 2^-30 deep, gaps of 2^-30, contacts
      map.offset = pt(Rational(coordinate(rng)) + Rational(sliver(rng), 1 << 30), Rational(coordinate(rng)) + Rational(sliver(rng), 1 << 30));
      return map;
    }
    int t = tangent(rng);   // rational rotation by half-angle tangent t / 4 (identity for 0)
    Rational u(t, 4), d = 1 + u * u;
    map.c = Rational((1 - u * u) / d);
    map.s = Rational(2 * u / d);
    // integer offsets (exact contacts on the grid) or an offset by a sliver 2^-30
    map.offset = pt(Rational(coordinate(rng)) + Rational(sliver(rng), 1 << 30), Rational(coordinate(rng)));
    return map;
  };
  int counts[3] = {0, 0, 0}, witnesses = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Part a = random_part(trial % 3), b = random_part((trial / 3) % 3);
    RigidMap ma = trial % 2 ? identity() : random_map(false), mb = random_map(trial % 4 != 0);
    OverlapOptions filtered, exact;
    filtered.want_witness = exact.want_witness = true;
    exact.exact_only = true;
    OverlapReport fast = analyse_overlap(a, ma, b, mb, filtered);
    OverlapReport slow = analyse_overlap(a, ma, b, mb, exact);
    ASSERT_EQ(fast.relation, slow.relation) << "trial " << trial;
    ASSERT_EQ(fast.witness.has_value(), slow.witness.has_value()) << "trial " << trial;
    ++counts[static_cast<int>(fast.relation)];
    if (!fast.witness) continue;
    ++witnesses;
    EXPECT_EQ(fast.witness->x, slow.witness->x) << "trial " << trial;
    EXPECT_EQ(fast.witness->y, slow.witness->y) << "trial " << trial;
    EXPECT_EQ(locate_point(a, ma, *fast.witness), PointLocation::inside);
    EXPECT_EQ(locate_point(b, mb, *fast.witness), PointLocation::inside);
  }
  EXPECT_GT(counts[static_cast<int>(Overlap::apart)], 0);
  EXPECT_GT(counts[static_cast<int>(Overlap::touching)], 0);
  EXPECT_GT(witnesses, 50);
}

}  // namespace
}  // namespace hipair::cspace
