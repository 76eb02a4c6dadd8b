// A mechanism drawn far from the origin (issue 13: every coordinate plus 10^k, k up to 400) has
// the same C-space as at the origin: configurations (angles about pivots that move with their
// parts, translation offsets, planar x, y, theta) are displacements. Generated pairs (random
// rational stars: two turning about their pivots, a turning one against a fixed one, two
// translating ones, a planar one in a fixed frame) are built at the origin and moved by
// (10^k + a, -10^k + b) with random rationals a, b; the moved pair's C-space must equal the
// original's exactly: the same feature pairs, cells (kinds, wraps, neighbours), edges (ends,
// roles, curves, cells) and vertices (x exactly, y's certified bounds holding the same root),
// the same exact point location at random configurations, and contact points moved by the same vector (the space keeps the
// model as given). 3-DOF pairs: the same critical angles (exactly), intervals, free cells,
// components and locations.
//
// On 147b396 the rotating pairs were rescaled as a whole (a 10 mm part at 10^100 mm became a
// 10^-98 mm part at 64 mm: the double filters see nothing, more curves are kept, the edges
// split differently; the escapement took over 120 s), the translating and 3-DOF pairs at
// 10^400 were refused ("beyond 2^1016 mm"): 84 failures here. core/model_scale.hpp
// normalising_translation now moves such a pair to the origin before building.
#include "algebra/exact_real.hpp"
#include "cspace_topology_compare.hpp"
#include "polygon_loop_json.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using Points = std::vector<std::pair<Rational, Rational>>;

Rational power10(int exponent) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(exponent)));
  return exponent >= 0 ? Rational(p) : Rational(mpz_class(1), p);
}

std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }

struct Offset {
  Rational x = 0, y = 0;
};

std::string point_json(const Rational& x, const Rational& y, const Offset& by) {
  Rational px = x + by.x, py = y + by.y;
  px.canonicalize();
  py.canonicalize();
  return "[" + text(px) + ", " + text(py) + "]";
}

std::string polygon_loop(const Points& points, const Offset& by) {
  return test_loops::loop_json(test_loops::moved(points, by.x, by.y));
}

// A star-shaped polygon of k vertices around (cx, cy) on a 1/8 grid (counter-clockwise).
Points random_star(std::mt19937_64& random, int k, double cx, double cy, double radius) {
  return test_loops::grid_star(random, k, cx, cy, radius, 8, 1, 0.4, 0.6);
}

// A square frame [-h, h]^2 with a square hole [-g, g]^2 (the hole clockwise).
std::string frame_loops(const Rational& h, const Rational& g, const Offset& by) {
  Points outer = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  Points hole = {{-g, -g}, {-g, g}, {g, g}, {g, -g}};
  return polygon_loop(outer, by) + ", " + polygon_loop(hole, by);
}

enum class Kind { two_rotating, rotating_fixed, two_translating, planar };

struct Case {
  Kind kind;
  Points a, b;
};

std::string model_json(const Case& c, const Offset& by) {
  const std::string head = R"({ "hipair": 1, "name": "moved", "units": { "length": "mm", "angle": "rad" }, "parts": [ )";
  switch (c.kind) {
    case Kind::two_rotating:
      return head + R"({ "name": "a", "motion": { "rotation": { "pivot": )" + point_json(-6, 0, by) +
             R"( } }, "loops": [ )" + polygon_loop(c.a, by) + R"( ] },
        { "name": "b", "motion": { "rotation": { "pivot": )" + point_json(6, 0, by) + R"( } }, "loops": [ )" +
             polygon_loop(c.b, by) + " ] } ] }";
    case Kind::rotating_fixed:
      return head + R"({ "name": "a", "motion": { "rotation": { "pivot": )" + point_json(-6, 0, by) +
             R"( } }, "loops": [ )" + polygon_loop(c.a, by) + R"( ] },
        { "name": "b", "motion": "fixed", "loops": [ )" + polygon_loop(c.b, by) + " ] } ] }";
    case Kind::two_translating:
      return head + R"({ "name": "a", "motion": { "translation": { "direction": [1, 0], "limits": [-20, 20] } }, "loops": [ )" +
             polygon_loop(c.a, by) + R"( ] },
        { "name": "b", "motion": { "translation": { "direction": [3, 4], "limits": [-20, 20] } }, "loops": [ )" +
             polygon_loop(c.b, by) + " ] } ] }";
    case Kind::planar:
      return head + R"({ "name": "frame", "motion": "fixed", "loops": [ )" + frame_loops(12, 8, by) + R"( ] },
        { "name": "b", "motion": { "planar": { "pivot": )" + point_json(0, 0, by) + R"( } }, "loops": [ )" +
             polygon_loop(c.b, by) + " ] } ] }";
  }
  return {};
}

Case random_case(std::mt19937_64& random, Kind kind) {
  Case c{kind, {}, {}};
  switch (kind) {
    case Kind::two_rotating:
      c.a = random_star(random, 4 + static_cast<int>(random() % 2), -6, 0, 7);
      c.b = random_star(random, 4 + static_cast<int>(random() % 2), 6, 0, 7);
      break;
    case Kind::rotating_fixed:
      c.a = random_star(random, 4 + static_cast<int>(random() % 3), -6, 0, 9);
      c.b = random_star(random, 4 + static_cast<int>(random() % 3), 4, 0, 4);
      break;
    case Kind::two_translating:
      c.a = random_star(random, 4 + static_cast<int>(random() % 4), -3, 0, 5);
      c.b = random_star(random, 4 + static_cast<int>(random() % 4), 3, 0, 5);
      break;
    case Kind::planar:
      c.b = random_star(random, 3 + static_cast<int>(random() % 2), 0, 0, 4);
      break;
  }
  return c;
}

cspace::algebra::Real real_of(const AlgebraicNumber& a) {
  cspace::algebra::Real r;
  r.exact = a.exact;
  r.lower = a.lower;
  r.upper = a.upper;
  r.polynomial = a.polynomial;
  return r;
}

bool same_number(const AlgebraicNumber& a, const AlgebraicNumber& b) {
  return cspace::algebra::compare(real_of(a), real_of(b)) == 0;
}

// Every field of the C-space that does not depend on where the mechanism is drawn.
void expect_same_space(const CSpace& at_origin, const CSpace& moved, const std::string& what) {
  ASSERT_NO_FATAL_FAILURE(hipair::test::expect_same_topology(at_origin, moved, what));
  for (std::size_t i = 0; i < at_origin.feature_pairs().size(); ++i)
    EXPECT_EQ(at_origin.feature_pairs()[i].label, moved.feature_pairs()[i].label) << what << " feature pair " << i;
  for (std::size_t i = 0; i < at_origin.vertices().size(); ++i) {
    const CSpaceVertex& p = at_origin.vertices()[i];
    const CSpaceVertex& q = moved.vertices()[i];
    EXPECT_TRUE(same_number(p.x, q.x)) << what << " vertex " << i << ": " << p.x.to_string() << " vs " << q.x.to_string();
    // y: the same root (each vertex's certified bounds isolate it; the bounds of one hold the other's)
    EXPECT_TRUE(p.y_lower <= q.y_upper && q.y_lower <= p.y_upper) << what << " vertex " << i;
  }
}

Rational random_rational(std::mt19937_64& random, long range, long denominator) {
  Rational r(static_cast<long>(random() % (2 * range * denominator + 1)) - range * denominator, denominator);
  r.canonicalize();
  return r;
}

TEST(CSpaceTranslation, FixedAxisPairsFarFromTheOriginHaveTheSameCSpace) {
  std::mt19937_64 random(4747);
  const std::vector<int> exponents = {30, 100, 400};
  std::size_t cases = 0, located = 0, contacts = 0;
  for (Kind kind : {Kind::rotating_fixed, Kind::two_translating, Kind::two_rotating}) {
    const int rounds = kind == Kind::two_rotating ? 2 : 3;
    for (int round = 0; round < rounds; ++round) {
      Case c = random_case(random, kind);
      Model origin = read_model(model_json(c, Offset{}));
      CSpace base = CSpace::build(origin, "a", "b");
      EXPECT_GT(base.feature_pairs().size(), 0u) << "the generated parts never touch";
      for (int k : exponents) {
        Offset by{power10(k) + random_rational(random, 50, 3), -power10(k) + random_rational(random, 50, 7)};
        by.x.canonicalize();
        by.y.canonicalize();
        const std::string what = "kind " + std::to_string(static_cast<int>(kind)) + " round " + std::to_string(round) +
                                 " at 10^" + std::to_string(k);
        Model moved_model = read_model(model_json(c, by));
        CSpace moved;
        try {
          moved = CSpace::build(moved_model, "a", "b");
        } catch (const Error& e) {
          ADD_FAILURE() << what << ": " << e.what();
          continue;
        }
        ++cases;
        expect_same_space(base, moved, what);
        // exact point location at random chart points
        for (int i = 0; i < 12; ++i) {
          ChartPoint q{0, random_rational(random, 1, 97), base.dimension() == 2 ? random_rational(random, 1, 89) : Rational(0)};
          if (kind == Kind::two_translating) {
            q.x *= 20;
            q.y *= 20;
            q.x.canonicalize();
            q.y.canonicalize();
          }
          Location l0 = base.locate(q);
          Location l1 = moved.locate(q);
          EXPECT_EQ(l0.kind, l1.kind) << what << " at " << q.x << ", " << q.y;
          ++located;
        }
        // contact points: those of the moved space are the origin's moved by the same vector
        for (const CSpaceVertex& v : base.vertices()) {
          if (!v.x.exact || !v.y_exact || !v.y.exact) continue;
          ChartPoint q{v.chart, v.x.lower, v.y.lower};
          std::vector<Contact> c0 = base.contact_at(q), c1 = moved.contact_at(q);
          ASSERT_EQ(c0.size(), c1.size()) << what;
          for (std::size_t j = 0; j < c0.size(); ++j) {
            EXPECT_EQ(Rational(c0[j].point[0] + by.x), c1[j].point[0]) << what;
            EXPECT_EQ(Rational(c0[j].point[1] + by.y), c1[j].point[1]) << what;
            ++contacts;
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 24u);
  EXPECT_GT(located, 200u);
  EXPECT_GT(contacts, 20u);
}

TEST(CSpaceTranslation, PlanarPairsFarFromTheOriginHaveTheSameSlicedSpace) {
  std::mt19937_64 random(4748);
  std::size_t cases = 0;
  for (int round = 0; round < 2; ++round) {
    Case c = random_case(random, Kind::planar);
    Model origin = read_model(model_json(c, Offset{}));
    SlicedSpace base = SlicedSpace::build(origin, "frame", "b");
    for (int k : {100, 400}) {
      Offset by{power10(k) + random_rational(random, 50, 3), power10(k) + random_rational(random, 50, 5)};
      by.x.canonicalize();
      by.y.canonicalize();
      const std::string what = "round " + std::to_string(round) + " at 10^" + std::to_string(k);
      SlicedSpace moved;
      try {
        moved = SlicedSpace::build(read_model(model_json(c, by)), "frame", "b");
      } catch (const Error& e) {
        ADD_FAILURE() << what << ": " << e.what();
        continue;
      }
      ++cases;
      ASSERT_EQ(base.critical_angles().size(), moved.critical_angles().size()) << what;
      for (std::size_t i = 0; i < base.critical_angles().size(); ++i) {
        EXPECT_EQ(base.critical_angles()[i].half_turn, moved.critical_angles()[i].half_turn) << what;
        if (!base.critical_angles()[i].half_turn)
          EXPECT_TRUE(same_number(base.critical_angles()[i].t, moved.critical_angles()[i].t)) << what << " angle " << i;
      }
      ASSERT_EQ(base.intervals().size(), moved.intervals().size()) << what;
      for (std::size_t i = 0; i < base.intervals().size(); ++i)
        EXPECT_EQ(base.intervals()[i].free_cells.size(), moved.intervals()[i].free_cells.size()) << what;
      EXPECT_EQ(base.crossings().size(), moved.crossings().size()) << what;
      EXPECT_EQ(base.components(), moved.components()) << what;
      EXPECT_EQ(base.bound(), moved.bound()) << what;
      EXPECT_EQ(base.length_unit(), moved.length_unit()) << what;
      for (int i = 0; i < 12; ++i) {
        SlicedConfiguration q;
        q.x = random_rational(random, 4, 13);
        q.y = random_rational(random, 4, 11);
        q.angle.t = random_rational(random, 2, 17);
        SlicedLocation l0 = base.locate(q), l1 = moved.locate(q);
        EXPECT_EQ(l0.kind, l1.kind) << what;
        EXPECT_EQ(base.component_of(q), moved.component_of(q)) << what;
      }
    }
  }
  EXPECT_EQ(cases, 4u);
}

}  // namespace
}  // namespace hipair
