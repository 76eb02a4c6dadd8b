// Grazing contacts of 3-DOF pairs (hipair/sliced.hpp), session 52 (hunt52): motions whose only
// contact is one isolated touch, which dense sampling (SlicedQueries.*) cannot see. Generated
// pairs, each with a closed-form first contact:
// - two convex polygons on either side of a common supporting line n·x = c (n a rational unit
//   normal), the free one (turned by a rational half-angle tangent) translated along the line:
//   the parts meet only when their two extreme vertices coincide, at u* (vertex–vertex);
// - a disc off the free part's pivot grazing a fixed convex polygon's extreme vertex the same
//   way (vertex–arc, a double root in u), and grazing a fixed disc (arc–arc: the centres'
//   distance is R + r only at u*);
// - the same motions ending exactly at the touch (u* = 1) and starting there (u* = 0);
// - point location where a vertex of the free part (turned by a rational tangent) lies exactly
//   inside an edge of the fixed part, for non-convex star pairs: contact or blocked, as the exact
//   overlap predicate says.
// Oracles: u* exactly (first_crossing's u compared exactly), the exact overlap predicate at u*
// (touching), at rational u either side (apart) and at `before`; point location at the touch
// (contact) and beside it (free).
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>

#include "polygon_loop_json.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

std::string quoted(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
std::string json_point(const Point& p) { return "[" + quoted(p.x) + ", " + quoted(p.y) + "]"; }

std::string polygon_loop(const std::vector<Point>& p) {
  test_loops::Points points;
  for (const Point& v : p) points.emplace_back(v.x, v.y);
  return test_loops::loop_json(points);
}
std::string disc_loop(const Point& c, const Rational& r) {
  return R"({ "circle": { "center": )" + json_point(c) + R"(, "radius": )" + quoted(r) + " } }";
}
Model grazing_model(const std::string& fixed_loop, const std::string& free_loop) {
  return read_model(R"({ "hipair": 1, "name": "grazing", "parts": [
    { "name": "fixed", "motion": "fixed", "loops": [ )" + fixed_loop + R"( ] },
    { "name": "free", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + free_loop + R"( ] } ] })");
}

Rational ratio(Random& random, long lo, long hi, long den) {
  Rational r(lo * den + static_cast<long>(random() % static_cast<unsigned long>((hi - lo) * den + 1)), den);
  r.canonicalize();
  return r;
}

// A convex polygon (counter-clockwise, no three vertices collinear) about (cx, cy): the hull of
// k points at radius ~radius on a grid of 1/8.
std::vector<Point> convex_polygon(Random& random, int k, double cx, double cy, double radius) {
  std::vector<std::pair<long, long>> grid;
  for (int i = 0; i < k; ++i) {
    double a = 2 * std::numbers::pi * (i + 0.8 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (0.7 + 0.3 * static_cast<double>(random() % 1000) / 1000.0);
    grid.emplace_back(std::lround(8 * (cx + r * std::cos(a))), std::lround(8 * (cy + r * std::sin(a))));
  }
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  auto cross = [](auto o, auto a, auto b) {
    return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
  };
  std::vector<std::pair<long, long>> hull(2 * grid.size());
  std::size_t h = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {   // Andrew's monotone chain, strict turns only
    while (h >= 2 && cross(hull[h - 2], hull[h - 1], grid[i]) <= 0) --h;
    hull[h++] = grid[i];
  }
  for (std::size_t i = grid.size() - 1, lower = h + 1; i-- > 0;) {
    while (h >= lower && cross(hull[h - 2], hull[h - 1], grid[i]) <= 0) --h;
    hull[h++] = grid[i];
  }
  std::vector<Point> out;
  for (std::size_t i = 0; i + 1 < h; ++i) out.push_back(Point{Rational(hull[i].first, 8), Rational(hull[i].second, 8)});
  for (Point& p : out) {
    p.x.canonicalize();
    p.y.canonicalize();
  }
  return out;
}

struct Rotation {
  Rational cos, sin;
  Point apply(const Point& p) const { return Point{cos * p.x - sin * p.y, sin * p.x + cos * p.y}; }
};
Rotation rotation_of(const Rational& t) {
  Rational d = 1 + t * t;
  return Rotation{(1 - t * t) / d, 2 * t / d};
}
Rational dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }

// The unique vertex of `p` with the largest (sign +1) or least (sign -1) n·v, or none when two tie.
std::optional<Point> extreme_vertex(const std::vector<Point>& p, const Point& n, int sign) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (sign * cmp(dot(n, p[i]), dot(n, p[best])) > 0) best = i;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (i != best && dot(n, p[i]) == dot(n, p[best])) return std::nullopt;
  return p[best];
}

PartRelation relation_at(const Model& model, const Rotation& rotation, const Point& shift) {
  return part_overlap(model.parts[0], Placement{}, model.parts[1], placement_about(Point{0, 0}, rotation.cos, rotation.sin, shift))
      .relation;
}

// a == u exactly: a rational a is u; otherwise u is a root of a's polynomial (coefficients from
// the constant up) inside its isolating interval.
bool equals(const AlgebraicNumber& a, const Rational& u) {
  if (a.exact) return a.lower == u;
  Rational value = 0;
  for (std::size_t i = a.polynomial.size(); i-- > 0;) value = value * u + Rational(a.polynomial[i]);
  return a.lower <= u && u <= a.upper && value == 0;
}

// One grazing motion: the free part at half-angle tangent t translated from `touch` - u* L d to
// `touch` + (1 - u*) L d; apart everywhere but at u*, where the parts touch.
struct Grazing {
  Rational t;
  Point touch, d;
  Rational u_star, length;
  Point at(const Rational& u) const {
    Rational k = (u - u_star) * length;
    return Point{touch.x + k * d.x, touch.y + k * d.y};
  }
};

struct Tally {
  int crossings = 0, ends = 0, starts = 0;
};

void expect_grazing_found(const Model& model, const SlicedSpace& space, const Grazing& g, Tally& tally) {
  Rotation rotation = rotation_of(g.t);
  // the construction's own check: touching at u*, apart at rational u either side
  ASSERT_EQ(relation_at(model, rotation, g.at(g.u_star)), PartRelation::touching);
  Rational eps(1, 1 << 20);
  if (g.u_star > 0) ASSERT_EQ(relation_at(model, rotation, g.at(g.u_star - eps)), PartRelation::apart);
  if (g.u_star < 1) ASSERT_EQ(relation_at(model, rotation, g.at(g.u_star + eps)), PartRelation::apart);

  SlicedAngle angle{g.t, false};
  Point touch = g.at(g.u_star);
  EXPECT_EQ(space.locate(SlicedConfiguration{touch.x, touch.y, angle}).kind, SlicedLocation::Kind::contact)
      << "the grazing touch is not located as a contact";
  Point beside = g.at(g.u_star == 1 ? Rational(g.u_star - eps) : Rational(g.u_star + eps));
  EXPECT_EQ(space.locate(SlicedConfiguration{beside.x, beside.y, angle}).kind, SlicedLocation::Kind::free);

  SlicedMotion motion;
  Point from = g.at(0), to = g.at(1);
  motion.from = SlicedConfiguration{from.x, from.y, angle};
  motion.to = SlicedConfiguration{to.x, to.y, angle};
  SlicedMotionCrossing crossing = space.first_crossing(motion);
  if (g.u_star == 0) {
    EXPECT_EQ(crossing.status, CrossingStatus::starts_in_contact);
    ++tally.starts;
    return;
  }
  ASSERT_EQ(crossing.status, CrossingStatus::crossing)
      << "a grazing touch at u* = " << g.u_star.get_str() << " missed (status " << static_cast<int>(crossing.status) << ")";
  EXPECT_TRUE(equals(crossing.u, g.u_star)) << "first contact at [" << crossing.u_lower.get_str() << ", " << crossing.u_upper.get_str()
                                    << "], not at u* = " << g.u_star.get_str();
  EXPECT_LE(crossing.u_lower, g.u_star);
  EXPECT_GE(crossing.u_upper, g.u_star);
  EXPECT_FALSE(crossing.features.empty());
  EXPECT_EQ(relation_at(model, rotation, Point{crossing.before.x, crossing.before.y}), PartRelation::apart);
  ++(g.u_star == 1 ? tally.ends : tally.crossings);
}

Rational random_u_star(Random& random, int k) {
  if (k % 7 == 5) return 1;   // the motion ends exactly at the touch
  if (k % 7 == 6) return 0;   // it starts there
  return ratio(random, 0, 1, 97) / 2 + Rational(1, 4);
}

// A rational unit normal from a rational slope m: ((1 - m^2), 2m) / (1 + m^2).
Point unit_normal(Random& random) {
  Rational m = ratio(random, -3, 3, 13);
  Rational d = 1 + m * m;
  Point n{(1 - m * m) / d, 2 * m / d};
  if (random() % 2) n = Point{-n.x, -n.y};
  return n;
}

// The grazing motion at half-angle tangent t through `touch` along the line normal to n (the
// k-th of its instance: u* inside, at the end or at the start), checked.
void graze_along(const Model& model, const SlicedSpace& space, const Rational& t, const Point& touch, const Point& n,
                 Random& random, int k, Tally& tally) {
  Grazing g{t, touch, Point{-n.y, n.x}, random_u_star(random, k), ratio(random, 2, 20, 7)};
  expect_grazing_found(model, space, g, tally);
}

void expect_every_kind(const Tally& tally) {
  EXPECT_GT(tally.crossings, 20);
  EXPECT_GT(tally.ends, 2);
  EXPECT_GT(tally.starts, 2);
}

TEST(SlicedGrazing, ConvexPolygonsPassingVertexToVertexTouchOnceAtTheClosedFormParameter) {
  Random random(5201);
  Tally tally;
  for (int instance = 0; instance < 4; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    std::vector<Point> a = convex_polygon(random, 5 + static_cast<int>(random() % 4), 0, 0, 6);
    std::vector<Point> b = convex_polygon(random, 3 + static_cast<int>(random() % 4), 1, 0, 3);
    if (a.size() < 3 || b.size() < 3) continue;
    Model model = grazing_model(polygon_loop(a), polygon_loop(b));
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    for (int k = 0; k < 14; ++k) {
      SCOPED_TRACE("motion " + std::to_string(k));
      Rational t = k % 4 == 0 ? Rational(0) : ratio(random, -2, 2, 23);
      Rotation rotation = rotation_of(t);
      std::vector<Point> turned;
      for (const Point& q : b) turned.push_back(rotation.apply(q));
      Point n = unit_normal(random);
      std::optional<Point> p = extreme_vertex(a, n, +1), q = extreme_vertex(turned, n, -1);
      if (!p || !q) continue;
      graze_along(model, space, t, Point{p->x - q->x, p->y - q->y}, n, random, k, tally);
    }
  }
  expect_every_kind(tally);
}

TEST(SlicedGrazing, AnOffPivotDiscGrazingAVertexOrADiscTouchesOnceAtTheClosedFormParameter) {
  Random random(5202);
  Tally tally;
  for (int instance = 0; instance < 4; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    bool round_fixed = instance % 2 == 1;
    Rational fixed_radius = ratio(random, 2, 6, 4);
    std::vector<Point> a = convex_polygon(random, 5 + static_cast<int>(random() % 4), 0, 0, 6);
    Point centre{ratio(random, -3, 3, 8), ratio(random, -3, 3, 8)};   // the disc's centre, off the pivot
    Rational r = ratio(random, 1, 3, 8);
    Model model = grazing_model(round_fixed ? disc_loop(Point{0, 0}, fixed_radius) : polygon_loop(a), disc_loop(centre, r));
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    for (int k = 0; k < 14; ++k) {
      SCOPED_TRACE("motion " + std::to_string(k));
      Rational t = ratio(random, -2, 2, 19);
      Point n = unit_normal(random);
      Point p{n.x * fixed_radius, n.y * fixed_radius};   // the fixed disc's point facing n
      if (!round_fixed) {
        std::optional<Point> v = extreme_vertex(a, n, +1);
        if (!v) continue;
        p = *v;
      }
      // the disc's centre at p + r n at the touch: shift = p + r n - R centre
      Point turned = rotation_of(t).apply(centre);
      graze_along(model, space, t, Point{p.x + r * n.x - turned.x, p.y + r * n.y - turned.y}, n, random, k, tally);
    }
  }
  expect_every_kind(tally);
}

TEST(SlicedGrazing, AVertexExactlyInsideAnEdgeLocatesAsTheOverlapPredicate) {
  Random random(5203);
  int touching = 0, overlapping = 0;
  for (int instance = 0; instance < 3; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    test_loops::Points a = test_loops::grid_star(random, 6 + static_cast<int>(random() % 4), 0, 0, 6, 8, 1);
    test_loops::Points b = test_loops::grid_star(random, 4 + static_cast<int>(random() % 4), 1, 0, 3, 8, 1);
    Model model;
    try {
      model = grazing_model(test_loops::loop_json(a), test_loops::loop_json(b));
    } catch (const ModelError&) {
      continue;   // rounding to the grid made a polygon not simple: not a case
    }
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    for (int k = 0; k < 120; ++k) {
      Rational t = k % 10 == 0 ? Rational(0) : ratio(random, -3, 3, 29);
      Rotation rotation = rotation_of(t);
      const auto& e0 = a[random() % a.size()];
      std::size_t next = 0;
      while (a[next] != e0) ++next;
      const auto& e1 = a[(next + 1) % a.size()];
      const auto& v = b[random() % b.size()];
      Rational along = ratio(random, 0, 1, 31) * Rational(9, 10) + Rational(1, 20);   // strictly inside the edge
      Point on{e0.first + along * (e1.first - e0.first), e0.second + along * (e1.second - e0.second)};
      Point turned = rotation.apply(Point{v.first, v.second});
      Point shift{on.x - turned.x, on.y - turned.y};
      PartRelation relation = relation_at(model, rotation, shift);
      ASSERT_NE(relation, PartRelation::apart);
      SlicedLocation::Kind expected =
          relation == PartRelation::touching ? SlicedLocation::Kind::contact : SlicedLocation::Kind::blocked;
      EXPECT_EQ(space.locate(SlicedConfiguration{shift.x, shift.y, SlicedAngle{t, false}}).kind, expected)
          << "vertex (" << v.first << ", " << v.second << ") at " << along << " of the edge from (" << e0.first << ", "
          << e0.second << "), t = " << t;
      ++(relation == PartRelation::touching ? touching : overlapping);
    }
  }
  EXPECT_GT(touching, 20);
  EXPECT_GT(overlapping, 20);
}

}  // namespace
}  // namespace hipair
