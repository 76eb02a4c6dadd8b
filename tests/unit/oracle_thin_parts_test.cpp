// The exact overlap oracle with parts of very different extents (a peg 10^-300 mm thin and 2 mm
// long, src/oracle/overlap.cpp): point location against the closed form of a rotated
// rectangle, the relation against its construction, and an interior witness for every
// overlapping pose (main 9b844dd: none when the thin side is below about 2^-38 of the long one:
// the witness search halved from the part's size and stopped 600 halvings down).
#include "oracle/overlap.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace hipair::cspace {
namespace {

using Random = std::mt19937_64;

Rational canonical(Rational r) {
  r.canonicalize();
  return r;
}

Rational power10(int k) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(k < 0 ? -k : k));
  return k < 0 ? canonical(Rational(mpz_class(1), p)) : Rational(p);
}

Edge segment(const Point& a, const Point& b) {
  Edge e;
  e.kind = Edge::Kind::segment;
  e.source = a;
  e.target = b;
  return e;
}

Part polygon(const std::vector<Point>& p, const std::string& name) {
  Loop loop;
  for (std::size_t i = 0; i < p.size(); ++i) loop.edges.push_back(segment(p[i], p[(i + 1) % p.size()]));
  Part part;
  part.name = name;
  part.loops.push_back(loop);
  return part;
}

// A rectangle of half-sizes (h, w) centred at the origin (ccw).
Part rectangle(const Rational& h, const Rational& w) {
  return polygon({Point{Rational(-h), Rational(-w)}, Point{h, Rational(-w)}, Point{h, w}, Point{Rational(-h), w}}, "peg");
}

// The rigid map turning by the half-angle tangent t, then shifting by (x, y).
RigidMap pose(const Rational& t, const Rational& x, const Rational& y) {
  RigidMap map;
  Rational d = 1 + t * t;
  map.c = canonical((1 - t * t) / d);
  map.s = canonical(2 * t / d);
  map.offset = Point{x, y};
  return map;
}

// Closed form: where world point p lies for the rectangle (h, w) posed by `map`.
PointLocation closed_form(const Rational& h, const Rational& w, const RigidMap& map, const Point& p) {
  Rational dx = p.x - map.offset.x, dy = p.y - map.offset.y;
  Rational u = map.c * dx + map.s * dy, v = -map.s * dx + map.c * dy;  // body frame
  int a = cmp(abs(u), h), b = cmp(abs(v), w);
  if (a > 0 || b > 0) return PointLocation::outside;
  if (a == 0 || b == 0) return PointLocation::boundary;
  return PointLocation::inside;
}

Rational random_unit(Random& random, int bits) {  // a rational in [-1, 1] with 2^bits as denominator
  const unsigned long den = 1ul << bits;
  long k = static_cast<long>(random() % (2 * den + 1)) - static_cast<long>(den);
  return canonical(Rational(k, static_cast<long>(den)));
}

// Thin sides 10^-300, 10^-120, 10^-30, 2^-60 and (the ordinary path) 1/4 of a 2 mm long peg,
// the whole pair at scales 10^-300 … 10^300.
struct Case {
  int thin_exponent;  // the thin half-side is 10^thin_exponent (0: 1/4)
  int scale_exponent;
};
const Case cases[] = {{-300, 0}, {-120, 0}, {-30, 0}, {0, 0}, {-300, 300}, {-30, -300}, {-60, 30}, {0, -300}};

Rational thin_of(const Case& c) { return c.thin_exponent == 0 ? Rational(1, 4) : power10(c.thin_exponent); }

TEST(OracleThinParts, LocationOnAndAroundAThinRotatedPegIsTheClosedForms) {
  Random random(4242);
  std::size_t checked = 0, inside = 0, boundary = 0;
  for (const Case& c : cases) {
    const Rational s = power10(c.scale_exponent), h = s, w = canonical(thin_of(c) * s);
    const Part peg = rectangle(h, w);
    for (int trial = 0; trial < 12; ++trial) {
      const RigidMap map = pose(random_unit(random, 20), canonical(random_unit(random, 10) * s), canonical(random_unit(random, 10) * s));
      for (int k = 0; k < 40; ++k) {
        // body points at (a h, b w) with a, b in [-5/4, 5/4] (exactly on the sides when |a| or |b| is 1)
        Rational a = canonical(random_unit(random, 3) * Rational(5, 4)), b = canonical(random_unit(random, 3) * Rational(5, 4));
        if (k % 5 == 0) b = (k % 10 == 0) ? Rational(1) : Rational(-1);
        Rational u = a * h, v = b * w;
        Point p{canonical(map.c * u - map.s * v + map.offset.x), canonical(map.s * u + map.c * v + map.offset.y)};
        const PointLocation expected = closed_form(h, w, map, p);
        ASSERT_EQ(static_cast<int>(locate_point(peg, map, p)), static_cast<int>(expected))
            << "thin 10^" << c.thin_exponent << " scale 10^" << c.scale_exponent << " body (" << a << ", " << b << ")";
        ++checked;
        inside += expected == PointLocation::inside;
        boundary += expected == PointLocation::boundary;
      }
    }
  }
  EXPECT_GT(inside, checked / 10);
  EXPECT_GT(boundary, checked / 10);
}

// The peg across a plate's edge (its end strictly inside the plate), beside it at a gap of its
// thin side, and exactly touching it: the relation of the construction, the same in both
// orders, and an interior witness inside both parts whenever they overlap.
TEST(OracleThinParts, AThinPegAgainstAPlateHasItsConstructedRelationAndAWitness) {
  Random random(4343);
  std::size_t witnesses = 0;
  for (const Case& c : cases) {
    const Rational s = power10(c.scale_exponent), h = s, w = canonical(thin_of(c) * s);
    const Part peg = rectangle(h, w);
    // the plate: x <= 0, a 10 s square
    const Rational ten = canonical(10 * s);
    const Part plate = polygon({Point{Rational(-ten), Rational(-ten)}, Point{Rational(0), Rational(-ten)}, Point{Rational(0), ten},
                                Point{Rational(-ten), ten}},
                               "plate");
    for (int trial = 0; trial < 6; ++trial) {
      // the peg turned by t (|t| <= 1/2: its direction within 53 degrees of +x), its centre on
      // the x axis at x0 so that its left end's lower-most corner reaches depth e into the plate
      const Rational t = canonical(random_unit(random, 16) / 2);
      RigidMap unit = pose(t, Rational(0), Rational(0));
      // the left-most x of the posed peg (centre at the origin): -h |c| - w |s|
      const Rational reach = canonical(h * abs(unit.c) + w * abs(unit.s));
      for (int kind = 0; kind < 3; ++kind) {
        // kind 0: overlapping by a quarter of the thin side; 1: apart by it; 2: touching
        const Rational depth = kind == 0 ? canonical(w / 4) : kind == 1 ? canonical(-w / 4) : Rational(0);
        const RigidMap map = pose(t, canonical(reach - depth), canonical(random_unit(random, 8) * s));
        const Overlap expected = kind == 0 ? Overlap::overlapping : kind == 1 ? Overlap::apart : Overlap::touching;
        OverlapOptions options;
        options.want_witness = true;
        OverlapReport one = analyse_overlap(plate, RigidMap{}, peg, map, options);
        OverlapReport two = analyse_overlap(peg, map, plate, RigidMap{}, options);
        const std::string where = "thin 10^" + std::to_string(c.thin_exponent) + " scale 10^" + std::to_string(c.scale_exponent) +
                                  " t " + t.get_str() + " kind " + std::to_string(kind);
        EXPECT_EQ(static_cast<int>(one.relation), static_cast<int>(expected)) << where;
        EXPECT_EQ(static_cast<int>(two.relation), static_cast<int>(expected)) << where;
        if (expected != Overlap::overlapping) continue;
        for (const OverlapReport* report : {&one, &two}) {
          EXPECT_TRUE(report->witness.has_value()) << where << ": no interior witness";
          if (!report->witness) continue;
          EXPECT_EQ(static_cast<int>(locate_point(plate, RigidMap{}, *report->witness)), static_cast<int>(PointLocation::inside)) << where;
          EXPECT_EQ(static_cast<int>(closed_form(h, w, map, *report->witness)), static_cast<int>(PointLocation::inside)) << where;
          ++witnesses;
        }
      }
    }
  }
  EXPECT_EQ(witnesses, 2 * 6 * std::size(cases));
}

}  // namespace
}  // namespace hipair::cspace
