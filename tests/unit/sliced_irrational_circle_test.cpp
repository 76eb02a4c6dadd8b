// 3-DOF pairs with a full circle of irrational radius (session 44; docs/cspace.md, "Scale and
// degenerate curves"): a disk of radius r = sqrt(a^2 + b^2) (not a rational square; the loop
// starts at the rational point centre + (a, b) of its circle, so the reader keeps r^2 exact) in a
// slot of half-width h. The slices keep the exact r^2 (SlicedSpace's direct slice; the text
// path refused such a circle). Generated cases: point location in (x, y, theta) equals the exact
// overlap predicate of the posed parts at random rational configurations, at offsets within
// 2^-40 mm of the disk's tangency to the slot's long sides (r between two dyadics), and at
// exact contacts (the disk's centre at the rational vector (+-a, +-b) from a corner of the
// plate's outline, outside it).
// A disk turning about its centre or about another pivot has no critical angle (its slices are
// translates of each other): a free configuration in the slot is connected to one at another
// angle, never to one outside the plate; the location is the same without the cell structure.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>

#include "core/exact_sqrt.hpp"
#include "sliced_model_support.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
std::string point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }

std::string rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return "{ \"start\": " + point(x0, y0) + ", \"edges\": [ { \"line_to\": " + point(x1, y0) + " }, { \"line_to\": " + point(x1, y1) +
         " }, { \"line_to\": " + point(x0, y1) + " }, { \"line_to\": " + point(x0, y0) + " } ] }";
}

struct Case {
  Rational a, b;            // the circle passes through centre + (a, b): r^2 = a^2 + b^2
  Rational half_width, half_length;
  Point centre, pivot;
  Model model;
};

Rational random_rational(Random& random, long lo, long hi, long den) {
  Rational r(lo * den + static_cast<long>(random() % static_cast<unsigned long>((hi - lo) * den + 1)), den);
  r.canonicalize();
  return r;
}

Case make_case(Random& random, bool about_pivot) {
  Case c;
  do {
    c.a = random_rational(random, 1, 3, 1 + static_cast<long>(random() % 4));
    c.b = random_rational(random, 1, 3, 1 + static_cast<long>(random() % 4));
  } while (rational_sqrt(Rational(c.a * c.a + c.b * c.b)).has_value());
  // the slot's half-width: the disk fits (h^2 > r^2) or not, by a margin
  c.half_width = random_rational(random, 1, 5, 4);
  c.half_length = random_rational(random, 8, 14, 3);
  c.centre = Point{random_rational(random, -1, 1, 5), random_rational(random, -1, 1, 7)};
  c.pivot = about_pivot ? c.centre : Point{Rational(c.centre.x + random_rational(random, 1, 2, 3)), c.centre.y};
  const Rational& h = c.half_width;
  const Rational& L = c.half_length;
  std::string fixed = rectangle(-30, -30, 30, 30) + ", " + rectangle(-L, -h, L, h);
  // a full circle through centre + (a, b), as `arc_to` its own start (r^2 kept exactly)
  const Point start{Rational(c.centre.x + c.a), Rational(c.centre.y + c.b)};
  std::string disk = "{ \"start\": " + point(start.x, start.y) + ", \"edges\": [ { \"arc_to\": " + point(start.x, start.y) +
                     ", \"center\": " + point(c.centre.x, c.centre.y) + ", \"dir\": \"ccw\" } ] }";
  c.model = read_model(R"({ "hipair": 1, "name": "disk in slot", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + fixed + R"( ] },
    { "name": "disk", "motion": { "planar": { "pivot": )" + point(c.pivot.x, c.pivot.y) + R"( } }, "loops": [ )" + disk + R"( ] } ] })");
  return c;
}

using sliced_models::rotation;

SlicedLocation::Kind oracle(const Model& model, const SlicedConfiguration& q) {
  const Part& a = model.parts[0];
  const Part& b = model.parts[1];
  auto [c, s] = rotation(q.angle);
  auto relation = part_overlap(a, Placement{}, b, placement_about(b.motion.pivot, c, s, Point{q.x, q.y})).relation;
  return relation == PartRelation::apart ? SlicedLocation::Kind::free
         : relation == PartRelation::touching ? SlicedLocation::Kind::contact
                                              : SlicedLocation::Kind::blocked;
}

// Where the disk's centre is at p (world) after the rotation of angle about the pivot: the offset.
SlicedConfiguration centre_at(const Case& c, const Point& p, const SlicedAngle& angle) {
  auto [cs, sn] = rotation(angle);
  Rational dx = c.centre.x - c.pivot.x, dy = c.centre.y - c.pivot.y;
  Point turned{Rational(c.pivot.x + cs * dx - sn * dy), Rational(c.pivot.y + sn * dx + cs * dy)};
  return SlicedConfiguration{Rational(p.x - turned.x), Rational(p.y - turned.y), angle};
}

// Configurations: random; the centre within 2^-40 of tangency to the long sides (r between
// two dyadics); the centre at (+-a, +-b) or (+-b, +-a) from an outline corner (exact contact).
std::vector<SlicedConfiguration> configurations(Random& random, const Case& c) {
  std::vector<SlicedConfiguration> out;
  const Rational r2 = c.a * c.a + c.b * c.b;
  mpz_class scaled = mpz_class(r2.get_num() << 80) / r2.get_den(), root;
  mpz_sqrt(root.get_mpz_t(), scaled.get_mpz_t());
  const Rational below(root, mpz_class(1) << 40), above(mpz_class(root + 1), mpz_class(1) << 40);   // below < r < above
  const Rational& h = c.half_width;
  for (int k = 0; k < 60; ++k) {
    SlicedAngle angle = k % 6 == 0 ? SlicedAngle{0, true} : SlicedAngle{random_rational(random, -3, 3, 11), false};
    switch (k % 3) {
      case 0:
        out.push_back(SlicedConfiguration{random_rational(random, -20, 20, 13), random_rational(random, -8, 8, 13), angle});
        break;
      case 1: {
        // near tangency to y = h (from inside: centre y = h - above / h - below) or y = -h
        const Rational& d = random() % 2 ? below : above;
        Rational y = random() % 2 ? Rational(h - d) : Rational(-h + d);
        out.push_back(centre_at(c, Point{random_rational(random, -4, 4, 9), y}, angle));
        break;
      }
      default: {
        // at distance exactly r from a corner of the plate's outline, outside it: touching
        const int sx = random() % 2 ? 1 : -1, sy = random() % 2 ? 1 : -1;
        const bool swap = random() % 2;
        Rational vx = swap ? c.b : c.a, vy = swap ? c.a : c.b;
        out.push_back(centre_at(c, Point{Rational(sx * (30 + vx)), Rational(sy * (30 + vy))}, angle));
      }
    }
  }
  return out;
}

// Location against the oracle and connectivity, `instances` generated cases of one kind.
void check_cases(Random& random, bool about_pivot, int instances) {
  int counts[3] = {0, 0, 0};
  int fitting = 0;
  for (int instance = 0; instance < instances; ++instance) {
    const Case c = make_case(random, about_pivot);
    SCOPED_TRACE("instance " + std::to_string(instance) + ": r^2 = " + to_exact_string(Rational(c.a * c.a + c.b * c.b)) +
                 ", h = " + to_exact_string(c.half_width));
    const SlicedSpace space = SlicedSpace::build(c.model, "plate", "disk");
    // a disk turning about a point: the slices are translates of each other, no critical angle
    EXPECT_TRUE(space.critical_angles().empty());
    SlicedBuildOptions without;
    without.cell_structure = false;
    const SlicedSpace plain = SlicedSpace::build(c.model, "plate", "disk", without);
    for (const auto& q : configurations(random, c)) {
      SlicedLocation l = space.locate(q);
      ASSERT_EQ(static_cast<int>(l.kind), static_cast<int>(oracle(c.model, q)))
          << "(" << to_exact_string(q.x) << ", " << to_exact_string(q.y) << ", t = " << (q.angle.half_turn ? "pi" : to_exact_string(q.angle.t)) << ")";
      ASSERT_EQ(static_cast<int>(plain.locate(q).kind), static_cast<int>(l.kind));
      ++counts[static_cast<int>(l.kind)];
    }
    // inside the slot when the disk fits (h^2 > r^2: the centre on the slot's axis), at two
    // angles: one component; never the one outside the plate
    const bool fits = c.half_width * c.half_width > c.a * c.a + c.b * c.b;
    SlicedConfiguration in_slot = centre_at(c, Point{0, 0}, SlicedAngle{0, false});
    SlicedConfiguration in_slot_turned = centre_at(c, Point{Rational(1, 2), 0}, SlicedAngle{Rational(7, 3), false});
    SlicedConfiguration outside = centre_at(c, Point{40, 40}, SlicedAngle{Rational(1, 5), false});
    ASSERT_EQ(static_cast<int>(space.locate(outside).kind), static_cast<int>(SlicedLocation::Kind::free));
    if (fits) {
      ++fitting;
      EXPECT_TRUE(space.connected(in_slot, in_slot_turned));
      EXPECT_FALSE(space.connected(in_slot, outside));
    } else {
      EXPECT_EQ(static_cast<int>(space.locate(in_slot).kind), static_cast<int>(SlicedLocation::Kind::blocked));
    }
  }
  EXPECT_GT(counts[0], 6 * instances);   // coverage: most random offsets put the disk in the plate
  EXPECT_GT(counts[1], 8 * instances);
  EXPECT_GT(counts[2], 10 * instances);
  EXPECT_GT(fitting, 0);
  EXPECT_LT(fitting, instances);
}

TEST(SlicedIrrationalCircle, DiskAboutItsPivotLocatesAsTheOverlapPredicate) {
  Random random(4401);
  check_cases(random, true, 6);
}

TEST(SlicedIrrationalCircle, DiskOffItsPivotLocatesAsTheOverlapPredicate) {
  Random random(4402);
  check_cases(random, false, 4);
}

}  // namespace
}  // namespace hipair
