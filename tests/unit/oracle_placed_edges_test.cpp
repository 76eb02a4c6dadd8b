// The exact oracle's placed edges (src/oracle/overlap.cpp: a segment's PlacedEdge carries no arc
// geometry; an arc's centre, radius and sector are placed only for arcs; the second part of a
// PairOverlap placed once at the identity without a throw-away PlacedPart) on generated pairs:
// random rational convex polygons (strictly convex, some with a vertex put exactly on an edge's
// line: collinear edges) and discs, at scales 10^-300 … 10^300, translated along a rational
// direction to positions where they overlap, are apart, and — for two polygons — exactly touch.
// Every answer of the three ways into the oracle (analyse_overlap with explicit maps in both
// orders: the lazily placed edges, by a map and at the identity; PairOverlap::classify: the
// second part placed once; classify_overlap) is compared with an independent exact oracle:
// separating axes over the polygons' edge normals, a disc's squared distance to a polygon, in
// rationals.
#include "curves/contact_curves.hpp"
#include "oracle/overlap.hpp"
#include "random_rationals.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::cspace {
namespace {

using Random = std::mt19937_64;
using Poly = std::vector<Point>;

Rational canonical(Rational r) {
  r.canonicalize();
  return r;
}

Rational random_rational(Random& random, long bound, long den = 997) {
  const long q = 1 + static_cast<long>(random() % static_cast<unsigned long>(den));
  const long p = static_cast<long>(random() % static_cast<unsigned long>(2 * bound * q + 1)) - bound * q;
  return canonical(Rational(p, q));
}

using test_numbers::power_of_ten;

std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }
std::string point_text(const Point& p) { return "[" + text(p.x) + ", " + text(p.y) + "]"; }

// A strictly convex polygon, ccw: points of the circle of radius r about c at the rational
// parameters u ((1 - u^2, 2u) / (1 + u^2), ascending u is ascending angle); with `collinear`,
// one edge's midpoint added as a vertex (two collinear edges).
Poly convex_polygon(Random& random, const Point& c, const Rational& r, bool collinear) {
  const int n = 3 + static_cast<int>(random() % 5);
  std::vector<Rational> us;
  while (static_cast<int>(us.size()) < n) {
    Rational u = random_rational(random, 4, 31);
    if (std::find(us.begin(), us.end(), u) == us.end()) us.push_back(u);
  }
  std::sort(us.begin(), us.end());
  Poly poly;
  for (const Rational& u : us) {
    const Rational w = 1 + u * u;
    poly.push_back(Point{canonical(c.x + r * (1 - u * u) / w), canonical(c.y + r * 2 * u / w)});
  }
  if (collinear) {
    const std::size_t i = random() % poly.size();
    const Point& a = poly[i];
    const Point& b = poly[(i + 1) % poly.size()];
    poly.insert(poly.begin() + static_cast<long>(i) + 1, Point{canonical((a.x + b.x) / 2), canonical((a.y + b.y) / 2)});
  }
  return poly;
}

std::string polygon_loop(const Poly& poly) {
  std::string loop = R"({ "start": )" + point_text(poly[0]) + R"(, "edges": [ )";
  for (std::size_t i = 1; i <= poly.size(); ++i)
    loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": )" + point_text(poly[i % poly.size()]) + " }";
  return loop + " ] }";
}

std::string disc_loop(const Point& c, const Rational& r) {
  return R"({ "circle": { "center": )" + point_text(c) + R"(, "radius": )" + text(r) + " } }";
}

// A body: a convex polygon or a disc.
struct Body {
  std::optional<Poly> polygon;
  Point centre;
  Rational radius;
  std::string loop() const { return polygon ? polygon_loop(*polygon) : disc_loop(centre, radius); }
};

Point shifted(const Point& p, const Point& d, const Rational& t) {
  return Point{canonical(p.x + t * d.x), canonical(p.y + t * d.y)};
}

Body moved(const Body& body, const Point& d, const Rational& t) {
  Body out = body;
  if (out.polygon)
    for (Point& p : *out.polygon) p = shifted(p, d, t);
  else
    out.centre = shifted(out.centre, d, t);
  return out;
}

// Independent oracle, two convex polygons: the largest gap over the edge normals of both
// (separating axes; the normals' lengths do not change a gap's sign). > 0 apart, 0 touching,
// < 0 overlapping.
Rational largest_gap(const Poly& a, const Poly& b) {
  std::optional<Rational> best;
  for (const Poly* edges : {&a, &b})
    for (std::size_t i = 0; i < edges->size(); ++i) {
      const Point& p = (*edges)[i];
      const Point& q = (*edges)[(i + 1) % edges->size()];
      const Rational nx = q.y - p.y, ny = p.x - q.x;
      auto range = [&](const Poly& poly) {
        Rational lo = nx * poly[0].x + ny * poly[0].y, hi = lo;
        for (const Point& v : poly) {
          const Rational s = nx * v.x + ny * v.y;
          lo = std::min(lo, s);
          hi = std::max(hi, s);
        }
        return std::pair{lo, hi};
      };
      const auto [alo, ahi] = range(a);
      const auto [blo, bhi] = range(b);
      const Rational gap = std::max(Rational(blo - ahi), Rational(alo - bhi));
      if (!best || gap > *best) best = gap;
    }
  return *best;
}

// Squared distance from c to a convex ccw polygon (0 inside or on it).
Rational squared_distance(const Point& c, const Poly& poly) {
  bool inside = true;
  std::optional<Rational> best;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % poly.size()];
    const Rational ex = q.x - p.x, ey = q.y - p.y, fx = c.x - p.x, fy = c.y - p.y;
    if (ex * fy - ey * fx < 0) inside = false;
    const Rational along = ex * fx + ey * fy, length2 = ex * ex + ey * ey;
    Rational d2;
    if (along <= 0) {
      d2 = fx * fx + fy * fy;
    } else if (along >= length2) {
      const Rational gx = c.x - q.x, gy = c.y - q.y;
      d2 = gx * gx + gy * gy;
    } else {
      const Rational cross = ex * fy - ey * fx;
      d2 = cross * cross / length2;
    }
    if (!best || d2 < *best) best = d2;
  }
  return inside ? Rational(0) : *best;
}

Overlap sign_relation(int sign) {   // sign of (clearance): > 0 apart
  return sign > 0 ? Overlap::apart : sign == 0 ? Overlap::touching : Overlap::overlapping;
}

Overlap independent(const Body& a, const Body& b) {
  if (a.polygon && b.polygon) return sign_relation(sgn(largest_gap(*a.polygon, *b.polygon)));
  if (!a.polygon && !b.polygon) {
    const Rational dx = a.centre.x - b.centre.x, dy = a.centre.y - b.centre.y;
    const Rational d2 = dx * dx + dy * dy, r = a.radius + b.radius;
    return sign_relation(sgn(d2 - r * r));
  }
  const Body& disc = a.polygon ? b : a;
  const Body& poly = a.polygon ? a : b;
  return sign_relation(sgn(squared_distance(disc.centre, *poly.polygon) - disc.radius * disc.radius));
}

// Part a translating along d, part b fixed; chart coordinate t: a moved by t times the unit
// direction the model stores for d.
// (limits ±16 scale: a reach beyond about 10^300 mm needs them)
std::string pair_model(const Body& a, const Body& b, const Point& d, const Rational& scale) {
  return R"({ "hipair": 1, "name": "placed", "parts": [
    { "name": "a", "motion": { "translation": { "direction": )" +
         point_text(d) + R"(, "limits": [)" + text(Rational(-16 * scale)) + ", " + text(Rational(16 * scale)) +
         R"(] } }, "loops": [ )" + a.loop() + R"( ] },
    { "name": "b", "motion": "fixed", "loops": [ )" + b.loop() + R"( ] } ], "pairs": [ { "parts": ["a", "b"] } ] })";
}

struct Ways {
  Overlap explicit_ab, explicit_ba, prepared, classified;
};

Ways ask(const Model& model, const PairOverlap& prepared, const Point& d, const Rational& t) {
  RigidMap by_t;
  by_t.offset = Point{canonical(t * d.x), canonical(t * d.y)};
  const Part& a = model.parts.at(0);
  const Part& b = model.parts.at(1);
  const PairAxes axes = pair_axes(model, 0, 1);
  const ChartLayout layout = chart_layout(model, axes);
  const ChartAxis* x = &layout.x_charts.front();
  for (const ChartAxis& axis : layout.x_charts)
    if (axis.lo <= t && t <= axis.hi) x = &axis;
  const ChartAxis y;
  const ChartPoint q{t, Rational(0)};
  return Ways{analyse_overlap(a, by_t, b, RigidMap{}).relation, analyse_overlap(b, RigidMap{}, a, by_t).relation,
              prepared.classify(*x, y, q), classify_overlap(model, axes, *x, y, q)};
}

std::string describe(Overlap o) {
  return o == Overlap::apart ? "apart" : o == Overlap::touching ? "touching" : "overlapping";
}

// A hand case fixes the chart's convention (a moved by t along the unit direction).
TEST(OraclePlacedEdges, TheChartCoordinateMovesTheFirstPartByItsDirection) {
  Body a{Poly{{Rational(0), Rational(0)}, {Rational(1), Rational(0)}, {Rational(1), Rational(1)}, {Rational(0), Rational(1)}}, {}, {}};
  Body b{Poly{{Rational(7), Rational(8)}, {Rational(8), Rational(8)}, {Rational(8), Rational(9)}, {Rational(7), Rational(9)}}, {}, {}};
  // offset t in mm along the unit direction (3/5, 4/5): at t = 10, a is [6, 7] x [8, 9]
  const Model model = read_model(pair_model(a, b, Point{Rational(3), Rational(4)}, Rational(1)));
  const Point d{canonical(Rational(3, 5)), canonical(Rational(4, 5))};
  ASSERT_EQ(model.parts.at(0).motion.direction, d);
  const PairOverlap prepared(model, pair_axes(model, 0, 1));
  for (const auto& [t, expected] : std::vector<std::pair<Rational, Overlap>>{
           {Rational(10), Overlap::touching}, {Rational(11), Overlap::overlapping},
           {canonical(Rational(45, 4)), Overlap::touching}, {Rational(5), Overlap::apart}, {canonical(Rational(25, 2)), Overlap::apart}}) {
    const Ways w = ask(model, prepared, d, t);
    EXPECT_EQ(independent(moved(a, d, t), b), expected);
    EXPECT_EQ(w.prepared, expected) << t;
    EXPECT_EQ(w.classified, expected) << t;
    EXPECT_EQ(w.explicit_ab, expected) << t;
    EXPECT_EQ(w.explicit_ba, expected) << t;
  }
}

TEST(OraclePlacedEdges, GeneratedPolygonsAndDiscsAtExtremeScalesEqualAnIndependentOracle) {
  Random random(39013);
  int checked = 0, touching = 0, overlapping = 0, apart = 0, with_disc = 0;
  for (int k : {-300, -30, 0, 30, 300}) {
    const Rational scale = power_of_ten(k);
    for (int round = 0; round < 8; ++round) {
      auto body = [&](bool disc) {
        const Point c{canonical(scale * random_rational(random, 3)), canonical(scale * random_rational(random, 3))};
        Body out{std::nullopt, c, canonical(scale * (1 + random_rational(random, 1, 7) / 2))};   // [1/2, 3/2] scale
        if (!disc) out.polygon = convex_polygon(random, c, out.radius, random() % 3 == 0);
        return out;
      };
      const int kinds = round % 4;   // 0, 1: two polygons; 2: disc a; 3: disc b
      const Body a = body(kinds == 2), b = body(kinds == 3);
      // a's path passes b: at t = scale a's centre is b's, turned by a small random offset
      Point d{canonical((b.centre.x - a.centre.x) / scale + random_rational(random, 1, 5) / 64),
              canonical((b.centre.y - a.centre.y) / scale + random_rational(random, 1, 5) / 64)};
      if (sgn(d.x) == 0 && sgn(d.y) == 0) d.x = 1;
      const Model model = read_model(pair_model(a, b, d, scale));
      d = model.parts.at(0).motion.direction;   // the exact unit direction the model keeps
      const PairOverlap prepared(model, pair_axes(model, 0, 1));
      // positions: random ones, and (two polygons) every root of a gap's linear piece that is
      // a touching position, with points between and beyond them
      std::vector<Rational> ts;
      for (int i = 0; i < 6; ++i) ts.push_back(canonical((1 + random_rational(random, 2)) * scale));
      if (a.polygon && b.polygon) {
        std::vector<Rational> touch;
        for (const Poly* edges : {&*a.polygon, &*b.polygon})
          for (std::size_t i = 0; i < edges->size(); ++i) {
            const Point& p = (*edges)[i];
            const Point& q = (*edges)[(i + 1) % edges->size()];
            const Rational nx = q.y - p.y, ny = p.x - q.x, nd = nx * d.x + ny * d.y;
            if (sgn(nd) == 0) continue;
            // a's support values move by t (n.d): each gap piece (b's least minus a's most,
            // a's least minus b's most) vanishes once
            Rational alo = nx * a.polygon->front().x + ny * a.polygon->front().y, ahi = alo;
            Rational blo = nx * b.polygon->front().x + ny * b.polygon->front().y, bhi = blo;
            for (const Point& u : *a.polygon) {
              alo = std::min(alo, Rational(nx * u.x + ny * u.y));
              ahi = std::max(ahi, Rational(nx * u.x + ny * u.y));
            }
            for (const Point& v : *b.polygon) {
              blo = std::min(blo, Rational(nx * v.x + ny * v.y));
              bhi = std::max(bhi, Rational(nx * v.x + ny * v.y));
            }
            for (const Rational& t : {canonical((blo - ahi) / nd), canonical((bhi - alo) / nd)})
              if (std::find(touch.begin(), touch.end(), t) == touch.end() &&
                  sgn(largest_gap(*moved(a, d, t).polygon, *b.polygon)) == 0)
                touch.push_back(t);
          }
        std::sort(touch.begin(), touch.end());
        ASSERT_FALSE(touch.empty());
        for (const Rational& t : touch) ts.push_back(t);
        ts.push_back(canonical((touch.front() + touch.back()) / 2));
        ts.push_back(canonical(touch.front() - scale));
        ts.push_back(canonical(touch.back() + scale));
      } else {
        ts.push_back(scale);   // the centres' offset only
        ++with_disc;
      }
      for (const Rational& t : ts) {
        const Overlap expected = independent(moved(a, d, t), b);
        const Ways w = ask(model, prepared, d, t);
        const std::string where = "scale 10^" + std::to_string(k) + " round " + std::to_string(round) + " t " + t.get_str() +
                                  " expected " + describe(expected);
        ASSERT_EQ(w.prepared, expected) << where;
        ASSERT_EQ(w.classified, expected) << where;
        ASSERT_EQ(w.explicit_ab, expected) << where;
        ASSERT_EQ(w.explicit_ba, expected) << where;
        ++checked;
        (expected == Overlap::touching ? touching : expected == Overlap::apart ? apart : overlapping)++;
      }
    }
  }
  EXPECT_GT(touching, 20);
  EXPECT_GT(apart, 20);
  EXPECT_GT(overlapping, 20);
  EXPECT_GT(with_disc, 10);
  std::printf("placed edges: %d positions (%d touching, %d apart, %d overlapping), %d pairs with a disc\n", checked, touching,
              apart, overlapping, with_disc);
}

}  // namespace
}  // namespace hipair::cspace
