// Translating pairs bounded by segments AND arcs (pins, stadium slots, rounded rectangles, plates
// with round holes, stars), generated at random on a rational grid, including the fits
// designers make on purpose: a pin in a hole of exactly its radius, a pin in a slot of exactly
// its width, a stadium in a stadium-shaped pocket. Every C-space is checked against the exact
// overlap predicate (include/hipair/overlap.hpp) at random rational configurations, at every
// exact vertex of the space, and at rational points ON its real edges (the exact ordinate of the
// edge at a rational abscissa, where it is rational): point location must say free exactly where
// the parts are apart, blocked exactly where they overlap, and contact/touching exactly where
// they touch. Session 14 found with a narrower version of this test a triangle-against-circle
// pair that failed to build and a whole vertical line of wrong locations at a slot's tangent joint;
// this one, at 1e300 mm, a piece of the algebraic traits stretched past a circle's bottom point.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "random_rationals.hpp"

namespace hipair {
namespace {

Rational eighths(long n) {
  Rational r(n, 8);
  r.canonicalize();
  return r;
}

// Every number written into a model is a length: scaled by `length_scale` (exactly).
Rational length_scale(1);
std::string q(const Rational& r) { return "\"" + Rational(r * length_scale).get_str() + "\""; }
std::string at(const Rational& x, const Rational& y) { return "[" + q(x) + ", " + q(y) + "]"; }

// One loop as JSON, from a start point and a list of edges already written.
struct Loop {
  Rational x0, y0;
  std::vector<std::string> edges;
  void line(const Rational& x, const Rational& y) { edges.push_back("{ \"line_to\": " + at(x, y) + " }"); }
  void arc(const Rational& x, const Rational& y, const Rational& cx, const Rational& cy, bool ccw) {
    edges.push_back("{ \"arc_to\": " + at(x, y) + ", \"center\": " + at(cx, cy) + ", \"dir\": \"" + (ccw ? "ccw" : "cw") + "\" }");
  }
  std::string json() const {
    std::string s = "{ \"start\": " + at(x0, y0) + ", \"edges\": [";
    for (std::size_t i = 0; i < edges.size(); ++i) s += (i ? ", " : "") + edges[i];
    return s + "] }";
  }
};

std::string circle(const Rational& cx, const Rational& cy, const Rational& r) {
  return "{ \"circle\": { \"center\": " + at(cx, cy) + ", \"radius\": " + q(r) + " } }";
}

// A stadium (a slot's outline): the segment (x0, y) .. (x1, y) thickened by r.
std::string stadium(const Rational& x0, const Rational& x1, const Rational& y, const Rational& r) {
  Loop l{x0, y - r, {}};
  l.line(x1, y - r);
  l.arc(x1, y + r, x1, y, true);
  l.line(x0, y + r);
  l.arc(x0, y - r, x0, y, true);
  return l.json();
}

// A rectangle [x0, x1] x [y0, y1] with corners rounded by r (tangent joints everywhere).
std::string rounded_rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1,
                              const Rational& r) {
  Loop l{x0 + r, y0, {}};
  l.line(x1 - r, y0);
  l.arc(x1, y0 + r, x1 - r, y0 + r, true);
  l.line(x1, y1 - r);
  l.arc(x1 - r, y1, x1 - r, y1 - r, true);
  l.line(x0 + r, y1);
  l.arc(x0, y1 - r, x0 + r, y1 - r, true);
  l.line(x0, y0 + r);
  l.arc(x0 + r, y0, x0 + r, y0 + r, true);
  return l.json();
}

std::string square(const Rational& cx, const Rational& cy, const Rational& h) {
  Loop l{cx - h, cy - h, {}};
  l.line(cx + h, cy - h);
  l.line(cx + h, cy + h);
  l.line(cx - h, cy + h);
  l.line(cx - h, cy - h);
  return l.json();
}

std::string star(std::mt19937_64& random, int k, double radius) {
  Loop l;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * 3.141592653589793 * (i + 0.2 + 0.6 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (0.4 + 0.6 * static_cast<double>(random() % 1000) / 1000.0);
    Rational x = eighths(std::lround(8 * r * std::cos(angle))), y = eighths(std::lround(8 * r * std::sin(angle)));
    if (i == 0) {
      l.x0 = x;
      l.y0 = y;
    } else {
      l.line(x, y);
    }
  }
  l.line(l.x0, l.y0);
  return l.json();
}

// The pair: part "a" slides along x, part "b" along y, both within [-12, 12].
std::string pair_json(const std::string& a_loops, const std::string& b_loops) {
  const std::string limits = "[" + q(Rational(-12)) + ", " + q(Rational(12)) + "]";
  return R"({ "hipair": 1, "name": "translating arcs", "parts": [
    { "name": "a", "motion": { "translation": { "direction": [1, 0], "limits": )" + limits + R"( } }, "loops": [ )" +
         a_loops + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1], "limits": )" + limits + R"( } }, "loops": [ )" +
         b_loops + R"( ] } ] })";
}

struct Case {
  std::string name, json;
};

std::vector<Case> cases() {
  std::mt19937_64 random(14014);
  auto coordinate = [&](int span) { return eighths(static_cast<long>(random() % (16 * span + 1)) - 8 * span); };
  auto radius = [&](int lo8, int hi8) { return eighths(lo8 + static_cast<long>(random() % (hi8 - lo8 + 1))); };
  std::vector<Case> out;
  // deliberate fits: zero clearance
  for (int i = 0; i < 3; ++i) {
    Rational r = radius(6, 20), cx = coordinate(2), cy = coordinate(2);
    // a plate (square) with a round hole of radius r, and a pin of radius r
    out.push_back({"pin in a hole of its radius " + std::to_string(i),
                   pair_json(square(cx, cy, r + 3) + ", " + circle(cx, cy, r), circle(Rational(0), Rational(0), r))});
    // a pin of radius r in a stadium slot of half-width r (the slot cut into a plate)
    Rational x0 = coordinate(2), len = radius(8, 40);
    out.push_back({"pin in a slot of its width " + std::to_string(i),
                   pair_json(square(x0 + len / 2, cy, len / 2 + r + 2) + ", " + stadium(x0, x0 + len, cy, r),
                             circle(coordinate(1), coordinate(1), r))});
    // a stadium in a stadium-shaped pocket of the same size
    out.push_back({"stadium in its pocket " + std::to_string(i),
                   pair_json(square(x0 + len / 2, cy, len / 2 + r + 2) + ", " + stadium(x0, x0 + len, cy, r),
                             stadium(Rational(0), len, Rational(0), r))});
  }
  // random shapes against each other
  for (int i = 0; i < 15; ++i) {
    auto shape = [&](int which) -> std::string {
      switch (which) {
        case 0: return circle(coordinate(2), coordinate(2), radius(4, 24));
        case 1: {
          Rational x0 = coordinate(2);
          return stadium(x0, x0 + radius(4, 32), coordinate(2), radius(3, 12));
        }
        case 2: {
          Rational x0 = coordinate(3), y0 = coordinate(3), r = radius(2, 8);
          return rounded_rectangle(x0, y0, x0 + 2 * r + radius(1, 24), y0 + 2 * r + radius(1, 24), r);
        }
        default: return star(random, 3 + static_cast<int>(random() % 5), 3);
      }
    };
    int first = static_cast<int>(random() % 4), second = static_cast<int>(random() % 3);   // b has an arc
    out.push_back({"random " + std::to_string(i), pair_json(shape(first), shape(second))});
  }
  return out;
}

enum class Seen { free, blocked, touching, contact, outside };

Seen seen(const CSpace& space, const Rational& x, const Rational& y) {
  Location l = space.locate(PartCoordinate{PartCoordinate::Kind::offset, x}, PartCoordinate{PartCoordinate::Kind::offset, y});
  auto of_cell = [&](std::size_t cell) {
    switch (space.cells()[cell].kind) {
      case CellKind::free: return Seen::free;
      case CellKind::blocked: return Seen::blocked;
      case CellKind::touching: return Seen::touching;
    }
    return Seen::outside;
  };
  switch (l.kind) {
    case Location::Kind::free: return Seen::free;
    case Location::Kind::blocked: return Seen::blocked;
    case Location::Kind::touching: return Seen::touching;
    case Location::Kind::outside: return Seen::outside;
    case Location::Kind::edge:
    case Location::Kind::vertex: return l.cell == no_index ? Seen::contact : of_cell(l.cell);
  }
  return Seen::outside;
}

// A rational near v / scale on a 1/denominator grid, times scale (exact; v a double length).
Rational near_scaled(double v, double scale_as_double, const Rational& scale, long denominator) {
  Rational r(std::lround(static_cast<double>(denominator) * (v / scale_as_double)), denominator);
  r.canonicalize();
  return r * scale;
}

using test_numbers::power_of_ten;

class CSpaceTranslatingArcs : public testing::TestWithParam<int> {};

TEST_P(CSpaceTranslatingArcs, PointLocationEqualsTheExactOverlapPredicate) {
  const Rational s = power_of_ten(GetParam());
  const double sd = std::pow(10.0, GetParam());
  length_scale = s;
  std::mt19937_64 random(2026);
  int checked = 0, on_edges = 0, touching = 0, ordinates = 0;
  const std::vector<Case> all = cases();
  length_scale = 1;
  for (const Case& c : all) {
    SCOPED_TRACE(c.name);
    Model model = read_model(c.json);
    CSpace space = [&] {
      try {
        return CSpace::build(model, "a", "b");
      } catch (const Error& e) {
        ADD_FAILURE() << "build: " << e.what() << "\n" << c.json;
        throw;
      }
    }();
    std::vector<std::pair<Rational, Rational>> points;
    for (int i = 0; i < 400; ++i) {
      Rational x(static_cast<long>(random() % 385) - 192, 16), y(static_cast<long>(random() % 385) - 192, 16);
      x.canonicalize();
      y.canonicalize();
      points.emplace_back(x * s, y * s);
    }
    for (const CSpaceVertex& v : space.vertices())
      if (v.x.exact && v.y_exact && v.y.exact) points.emplace_back(v.x.lower, v.y.lower);
    // rational points on real edges: the midpoint abscissa of the edge's certified extent,
    // rounded to a short rational, where the edge's exact ordinate there is rational
    const std::size_t first_edge_point = points.size();
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.real || edge.vertical) continue;
      for (int k = 1; k <= 3; ++k) {
        double lo = edge.x_chart.lower, hi = edge.x_chart.upper;
        Rational x = near_scaled(lo + (hi - lo) * k / 4, sd, s, 1024);
        if (!(Rational(lo) < x && x < Rational(hi))) continue;
        try {
          AlgebraicNumber y = space.evaluate_exact(e, x);
          if (y.exact) points.emplace_back(x, y.lower);
        } catch (const GeometryError&) {
          // x outside the edge's exact extent (the certified one is wider): no point
        }
      }
    }
    // points on vertical edges (a vertex of a part against a vertical side, and where a slot's
    // side meets its round end tangentially): the edge's constant rational x, y across the edge
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.vertical) continue;
      const auto& f = space.edge_polynomial_coefficients(e);   // f[i][j]: x^i y^j; c0 + c1 x
      if (f.size() != 2 || f[1].empty() || f[1][0] == 0) continue;
      Rational x(mpz_class(-f[0][0]), f[1][0]);
      x.canonicalize();
      for (int k = 0; k <= 8; ++k) {
        points.emplace_back(x, near_scaled(edge.y_chart.lower + (edge.y_chart.upper - edge.y_chart.lower) * k / 8, sd, s, 64));
      }
    }
    int wrong = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto& [x, y] = points[i];
      Seen got;
      try {
        got = seen(space, x, y);
      } catch (const Error& e) {
        if (++wrong <= 3) ADD_FAILURE() << "locate (" << x << ", " << y << "): " << e.what();
        continue;
      }
      if (got == Seen::outside) continue;
      Placement pa, pb;
      pa.offset = Point{x, Rational(0)};
      pb.offset = Point{Rational(0), y};
      const PartRelation relation = part_overlap(model.parts[0], pa, model.parts[1], pb).relation;
      const bool agrees = relation == PartRelation::apart         ? got == Seen::free
                          : relation == PartRelation::overlapping ? got == Seen::blocked
                                                                  : got == Seen::contact || got == Seen::touching;
      if (!agrees && ++wrong <= 3)
        ADD_FAILURE() << "at (" << x << ", " << y << "): located " << static_cast<int>(got) << ", the parts are "
                      << (relation == PartRelation::apart ? "apart" : relation == PartRelation::overlapping ? "overlapping" : "touching");
      ++checked;
      on_edges += i >= first_edge_point;
      touching += relation == PartRelation::touching;
    }
    EXPECT_EQ(wrong, 0) << c.json;
    // the ordinate of every vertex compares with rationals below, above and far off it, also
    // where it is a double root of its curve's fibre (a tangent joint)
    for (std::size_t v = 0; v < space.vertices().size(); ++v) {
      const CSpaceVertex& vertex = space.vertices()[v];
      if (vertex.y_exact) continue;
      try {
        EXPECT_EQ(space.compare_ordinate(VertexId(v), vertex.y_lower - 1), -1);
        EXPECT_EQ(space.compare_ordinate(VertexId(v), vertex.y_upper + 1), 1);
        if (vertex.y_lower < vertex.y_upper) {
          const int low = space.compare_ordinate(VertexId(v), vertex.y_lower);
          const int high = space.compare_ordinate(VertexId(v), vertex.y_upper);
          EXPECT_TRUE(low <= 0 && high >= 0 && low < high) << "vertex " << v;
        }
        ++ordinates;
      } catch (const Error& e) {
        ADD_FAILURE() << "compare_ordinate, vertex " << v << ": " << e.what();
      }
    }
  }
  std::cout << checked << " configurations checked, " << on_edges << " on edges, " << touching
            << " where the parts touch\n";
  EXPECT_GT(checked, 10000);
  EXPECT_GT(ordinates, 20);
  EXPECT_GT(on_edges, 100);
  EXPECT_GT(touching, 200);
}


// Scale 1, and the same pairs at 1e-300 mm and 1e300 mm (every length multiplied exactly).
INSTANTIATE_TEST_SUITE_P(Scales, CSpaceTranslatingArcs, testing::Values(0, -300, 300),
                         [](const testing::TestParamInfo<int>& info) {
                           return info.param == 0 ? std::string("Scale1")
                                                  : "Scale1e" + std::string(info.param < 0 ? "Minus" : "") + std::to_string(std::abs(info.param));
                         });

// Rotating parts with arcs: a cam (a stadium or a rounded rectangle turning about a pivot)
// against a translating follower with a round or flat end, and two rotating parts (a lever
// against a lever or a pin wheel). Checked as above, with rotations at rational half-angle
// tangents (exact rational rotations): random ones, the abscissae of every vertical edge
// (the angles where a vertex meets a flank, or a tangent joint), at the vertices and on the
// real edges.
std::string rotating_pair_json(const std::string& a_loops, const std::string& a_pivot, const std::string& b_motion,
                               const std::string& b_loops) {
  return R"({ "hipair": 1, "name": "rotating arcs", "parts": [
    { "name": "a", "motion": { "rotation": { "pivot": )" + a_pivot + R"( } }, "loops": [ )" + a_loops + R"( ] },
    { "name": "b", "motion": )" + b_motion + R"(, "loops": [ )" + b_loops + R"( ] } ] })";
}

Placement turned(const Point& pivot, const Rational& t) {
  const Rational d = 1 + t * t;
  return placement_about(pivot, Rational((1 - t * t) / d), Rational(2 * t / d), Point{Rational(0), Rational(0)});
}

class CSpaceRotatingArcs : public testing::TestWithParam<int> {};

TEST_P(CSpaceRotatingArcs, PointLocationEqualsTheExactOverlapPredicate) {
  const Rational s = power_of_ten(GetParam());
  const double sd = std::pow(10.0, GetParam());
  struct ScaleGuard {
    explicit ScaleGuard(const Rational& scale) { length_scale = scale; }
    ~ScaleGuard() { length_scale = 1; }
  } guard(s);   // every length written into the models below is scaled by s
  std::mt19937_64 random(1414);
  auto coordinate = [&](int span) { return eighths(static_cast<long>(random() % (16 * span + 1)) - 8 * span); };
  auto radius = [&](int lo8, int hi8) { return eighths(lo8 + static_cast<long>(random() % (hi8 - lo8 + 1))); };
  int checked = 0, touching = 0;
  // far from 1 mm the rotation-translation charts take the general algebraic traits (about 100x
  // slower): three instances there (two translating followers, one rotating lever)
  const int instances = GetParam() == 0 ? 12 : 3;
  for (int instance = 0; instance < instances; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    // part a: a cam about (0, 0): a stadium through the pivot or a rounded rectangle around it
    Rational r = radius(4, 12), len = radius(16, 40);
    std::string cam = instance % 2 == 0 ? stadium(Rational(0), len, Rational(0), r)
                                        : rounded_rectangle(-r - 1, -r - 1, len, r + 1, radius(2, 7));
    const bool translating = instance % 3 != 2;
    std::string b_motion, b_loops;
    Point b_pivot{Rational(0), Rational(0)};
    if (translating) {
      // a follower sliding along y at x = c, its lower end a round nose or a flat
      Rational c = coordinate(3), nose = radius(4, 16);
      b_motion = R"({ "translation": { "direction": [0, 1], "limits": [)" + q(Rational(-20)) + ", " + q(Rational(20)) + "] } }";
      b_loops = instance % 2 == 0 ? circle(c, nose + len + 2, nose) : square(c, len + 2 + nose, nose);
    } else {
      Rational px = len + radius(8, 24), py = coordinate(1);
      b_pivot = Point{px * s, py * s};
      b_motion = R"({ "rotation": { "pivot": )" + at(px, py) + " } }";
      b_loops = stadium(px - len, px, py, r) + ", " + circle(px - len / 2, py + r + 2, radius(4, 10));
    }
    Model model = read_model(rotating_pair_json(cam, "[0, 0]", b_motion, b_loops));
    CSpace space = CSpace::build(model, "a", "b");
    auto second = [&](const Rational& v) {
      return translating ? PartCoordinate{PartCoordinate::Kind::offset, v} : PartCoordinate{PartCoordinate::Kind::half_angle_tangent, v};
    };
    std::vector<std::pair<Rational, Rational>> points;   // (tangent of a, coordinate of b)
    for (int i = 0; i < 600; ++i) {
      Rational t(static_cast<long>(random() % 801) - 400, 100), v(static_cast<long>(random() % 641) - 320, translating ? 16 : 100);
      t.canonicalize();
      v.canonicalize();
      points.emplace_back(t, translating ? Rational(v * s) : v);
    }
    // vertical edges of chart 0 (whose coordinates are the half-angle tangent and the offset or
    // the other tangent): their constant abscissa, ordinates across the edge
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.vertical || edge.chart != 0) continue;
      const auto& f = space.edge_polynomial_coefficients(e);
      if (f.size() != 2 || f[1].empty() || f[1][0] == 0) continue;
      Rational x(mpz_class(-f[0][0]), f[1][0]);
      x.canonicalize();
      for (int k = 0; k <= 8; ++k) {
        const double y = edge.y_chart.lower + (edge.y_chart.upper - edge.y_chart.lower) * k / 8;
        points.emplace_back(x, translating ? near_scaled(y, sd, s, 256) : near_scaled(y, 1, Rational(1), 256));
      }
    }
    int wrong = 0;
    for (const auto& [t, v] : points) {
      // chart 0 coordinates are the tangent and the offset (or the other tangent) themselves
      Location l;
      try {
        l = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t}, second(v));
      } catch (const Error& e) {
        if (++wrong <= 3) ADD_FAILURE() << "locate (" << t << ", " << v << "): " << e.what();
        continue;
      }
      if (l.kind == Location::Kind::outside) continue;
      Seen got = l.kind == Location::Kind::free      ? Seen::free
                 : l.kind == Location::Kind::blocked ? Seen::blocked
                 : l.kind == Location::Kind::touching
                     ? Seen::touching
                     : (l.cell == no_index ? Seen::contact
                                           : (space.cells()[l.cell].kind == CellKind::free ? Seen::free : Seen::blocked));
      Placement pa = turned(Point{Rational(0), Rational(0)}, t);
      Placement pb = translating ? Placement{} : turned(b_pivot, v);
      if (translating) pb.offset = Point{Rational(0), v};
      const PartRelation relation = part_overlap(model.parts[0], pa, model.parts[1], pb).relation;
      const bool agrees = relation == PartRelation::apart         ? got == Seen::free
                          : relation == PartRelation::overlapping ? got == Seen::blocked
                                                                  : got == Seen::contact || got == Seen::touching;
      if (!agrees && ++wrong <= 3)
        ADD_FAILURE() << "at (" << t << ", " << v << "): located " << static_cast<int>(got) << ", the parts are "
                      << (relation == PartRelation::apart ? "apart" : relation == PartRelation::overlapping ? "overlapping" : "touching");
      ++checked;
      touching += relation == PartRelation::touching;
    }
    EXPECT_EQ(wrong, 0);
  }
  std::cout << checked << " rotating configurations checked, " << touching << " where the parts touch\n";
  EXPECT_GT(checked, 500 * instances);
}

INSTANTIATE_TEST_SUITE_P(Scales, CSpaceRotatingArcs, testing::Values(0, -300, 300),
                         [](const testing::TestParamInfo<int>& info) {
                           return info.param == 0 ? std::string("Scale1")
                                                  : "Scale1e" + std::string(info.param < 0 ? "Minus" : "") + std::to_string(std::abs(info.param));
                         });


// A lever (a stadium about the origin) at -90 degrees and a second lever at +90 degrees whose pin
// touches the first one's straight side: the configuration (t, u) = (-1, 1) is a corner of chart
// 0 and of three other charts, and the contact curve meets chart 0 only at that corner. Point
// location said "blocked" (chart 0's corner lies in a blocked wedge); on a chart's boundary it
// asks every chart holding the configuration now (seed 11 of the rotating test found it).
TEST(CSpaceRotatingArcs, ContactThroughAChartCornerIsContact) {
  const Model model = read_model(R"json({ "hipair": 1, "name": "rotating arcs", "parts": [
    { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ { "start": ["0", "-3/2"], "edges": [{ "line_to": ["17/4", "-3/2"] }, { "arc_to": ["17/4", "3/2"], "center": ["17/4", "0"], "dir": "ccw" }, { "line_to": ["0", "3/2"] }, { "arc_to": ["0", "-3/2"], "center": ["0", "0"], "dir": "ccw" }] } ] },
    { "name": "b", "motion": { "rotation": { "pivot": ["45/8", "1/8"] } }, "loops": [ { "start": ["11/8", "-11/8"], "edges": [{ "line_to": ["45/8", "-11/8"] }, { "arc_to": ["45/8", "13/8"], "center": ["45/8", "1/8"], "dir": "ccw" }, { "line_to": ["11/8", "13/8"] }, { "arc_to": ["11/8", "-11/8"], "center": ["11/8", "1/8"], "dir": "ccw" }] }, { "circle": { "center": ["7/2", "29/8"], "radius": "5/8" } } ] } ] })json");
  const CSpace space = CSpace::build(model, "a", "b");
  const PartCoordinate t{PartCoordinate::Kind::half_angle_tangent, Rational(-1)};
  const PartCoordinate u{PartCoordinate::Kind::half_angle_tangent, Rational(1)};
  Placement pa = turned(Point{Rational(0), Rational(0)}, Rational(-1));
  Placement pb = turned(model.parts[1].motion.pivot, Rational(1));
  ASSERT_EQ(part_overlap(model.parts[0], pa, model.parts[1], pb).relation, PartRelation::touching);
  const Location l = space.locate(t, u);
  EXPECT_TRUE((l.kind == Location::Kind::edge || l.kind == Location::Kind::vertex) && l.cell == no_index)
      << "kind " << static_cast<int>(l.kind) << ", cell " << l.cell;
  // the same through chart 0's own coordinates (its corner)
  const Location c = space.locate(ChartPoint{0, Rational(-1), Rational(1)});
  EXPECT_TRUE((c.kind == Location::Kind::edge || c.kind == Location::Kind::vertex) && c.cell == no_index)
      << "kind " << static_cast<int>(c.kind) << ", cell " << c.cell;
}

}  // namespace
}  // namespace hipair
