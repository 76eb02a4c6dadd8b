// Translating polygon pairs (part A along x by s, part B along y by r): the blocked region
// is {(s, r) : s e_x - r e_y in interior(B + (-A))}, the Minkowski sum reflected in the s axis.
// The blocked faces of the C-space must make up exactly that polygon: the symmetric difference
// with CGAL's minkowski_sum_2 is empty. (Includes CGAL: its own translation unit.)
#include "cspace/builder_impl.hpp"
#include "cspace_minkowski_support.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <CGAL/Cartesian.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/minkowski_sum_2.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hipair {
namespace {

using namespace minkowski_support;

std::string polygon_json(const std::vector<std::pair<std::string, std::string>>& points) {
  auto quoted = [](const std::string& v) { return "\"" + v + "\""; };
  std::string text = "{ \"start\": [" + quoted(points[0].first) + ", " + quoted(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + quoted(p.first) + ", " + quoted(p.second) + "] }";
  }
  return text + "] }";
}

Model two_sliders(const std::vector<std::pair<std::string, std::string>>& a,
                  const std::vector<std::pair<std::string, std::string>>& b) {
  std::string text = R"({ "hipair": 1, "name": "sliders", "parts": [
    { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ )" +
                     polygon_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [ )" +
                     polygon_json(b) + R"( ] } ] })";
  return read_model(text);
}

Polygon to_polygon(const std::vector<std::pair<std::string, std::string>>& points, bool negate) {
  Polygon p;
  for (const auto& [x, y] : points) {
    Rational px = parse_rational(x), py = parse_rational(y);
    if (negate) {
      px = -px;
      py = -py;
    }
    p.push_back(Point2(CGAL::Gmpq(px.get_mpq_t()), CGAL::Gmpq(py.get_mpq_t())));
  }
  if (p.is_clockwise_oriented()) p.reverse_orientation();
  return p;
}

void expect_minkowski(const std::vector<std::pair<std::string, std::string>>& a,
                      const std::vector<std::pair<std::string, std::string>>& b) {
  Model model = two_sliders(a, b);
  CSpace space = CSpace::build(model, "a", "b");
  ASSERT_EQ(space.dimension(), 2);
  ASSERT_EQ(space.charts().size(), 1u);
  // M = B + (-A); the blocked region is M reflected in the s axis: (u, v) -> (u, -v)
  PolygonWithHoles sum = CGAL::minkowski_sum_2(to_polygon(b, false), to_polygon(a, true));
  Polygon reflected;
  for (auto it = sum.outer_boundary().vertices_begin(); it != sum.outer_boundary().vertices_end(); ++it)
    reflected.push_back(Point2(it->x(), -it->y()));
  reflected.reverse_orientation();
  PolygonWithHoles expected(reflected);
  for (auto hole = sum.holes_begin(); hole != sum.holes_end(); ++hole) {
    Polygon h;
    for (auto it = hole->vertices_begin(); it != hole->vertices_end(); ++it) h.push_back(Point2(it->x(), -it->y()));
    h.reverse_orientation();
    expected.add_hole(h);
  }
  PolygonSet difference = blocked_region(space);
  EXPECT_FALSE(difference.is_empty());
  difference.symmetric_difference(expected);
  EXPECT_TRUE(difference.is_empty()) << "blocked faces differ from the Minkowski sum";
  // and the free space is one cell around the sum, plus one per hole of the sum
  int free = 0;
  for (const auto& cell : space.cells()) free += cell.kind == CellKind::free;
  EXPECT_EQ(free, 1 + static_cast<int>(sum.number_of_holes()));
  // built on the circle–segment traits (lines only), every vertex exact
  EXPECT_EQ(space.statistics().circle_segment_charts, 1u);
  for (const auto& vertex : space.vertices()) EXPECT_TRUE(vertex.y_exact);
}

// A star-shaped polygon with k vertices at increasing angles around (cx, cy), on a 1/q grid
// (a double only places the test input; the reader checks that it is simple).
std::vector<std::pair<std::string, std::string>> random_star(std::mt19937_64& random, int k, double cx, double cy,
                                                             double radius, long q) {
  std::vector<std::pair<std::string, std::string>> points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * 3.141592653589793 * (i + 0.15 + 0.7 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (random() % 3 == 0 ? 1.0 : 0.35 + 0.65 * static_cast<double>(random() % 1000) / 1000.0);
    Rational x(static_cast<long>(std::lround(q * (cx + r * std::cos(angle)))), q);
    Rational y(static_cast<long>(std::lround(q * (cy + r * std::sin(angle)))), q);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x.get_str(), y.get_str());
  }
  return points;
}

TEST(CSpaceMinkowski, RandomRationalPolygonsEqualTheMinkowskiSum) {
  std::mt19937_64 random(2026);
  int compared = 0;
  for (int instance = 0; instance < 24; ++instance) {
    int ka = 3 + static_cast<int>(random() % 8), kb = 3 + static_cast<int>(random() % 8);
    long q = instance % 3 == 0 ? 1 : instance % 3 == 1 ? 16 : 97;
    auto a = random_star(random, ka, 0, 0, 3 + static_cast<double>(random() % 4), q);
    auto b = random_star(random, kb, static_cast<double>(random() % 7) - 3, static_cast<double>(random() % 7) - 3,
                         2 + static_cast<double>(random() % 5), q);
    SCOPED_TRACE("instance " + std::to_string(instance));
    try {
      expect_minkowski(a, b);
      ++compared;
    } catch (const ModelError&) {
      // rounding made a polygon degenerate (repeated vertex, self-touching): not a test case
    }
  }
  EXPECT_GE(compared, 20);
}

// A convex polygon with k vertices on the circle of rational radius `radius` about (cx, cy),
// placed as the Minkowski benchmark's (tests/perf/polygon_models.hpp): (cos, sin) from the
// half-angle tangents tan(pi i / k) rounded to 1/grid (a double only places the test input),
// here turned by the rational tangent `turn`. Two such polygons with the same k, grid and turn
// have pairwise parallel edges: every convolution segment overlaps another one.
std::vector<std::pair<std::string, std::string>> rational_circle_polygon(int k, const Rational& radius, const Rational& cx,
                                                                         const Rational& cy, long grid, const Rational& turn) {
  const Rational turn_d = 1 + turn * turn, turn_c = (1 - turn * turn) / turn_d, turn_s = 2 * turn / turn_d;
  std::vector<std::pair<std::string, std::string>> points;
  auto add = [&](const Rational& c, const Rational& s) {
    Rational x = cx + radius * (c * turn_c - s * turn_s), y = cy + radius * (c * turn_s + s * turn_c);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x.get_str(), y.get_str());
  };
  for (int i = -(k / 2) + 1; i < k - k / 2; ++i) {
    if (2 * i == k) break;
    Rational t(std::lround(std::tan(3.141592653589793 * i / k) * static_cast<double>(grid)), grid);
    t.canonicalize();
    const Rational d = 1 + t * t;
    add((1 - t * t) / d, 2 * t / d);
  }
  if (k % 2 == 0) add(Rational(-1), Rational(0));
  return points;
}

// The benchmark's pair family generated: convex k-gons and m-gons on circles (m = k on every
// other instance: all edges pairwise parallel, the 12-gon + 12-gon and 40-gon + 40-gon rows of
// docs/performance.md's session 56 are of this kind), rational radii and centres, turned by
// random rational tangents; the blocked region equals CGAL's Minkowski sum exactly.
TEST(CSpaceMinkowski, GeneratedConvexCirclePolygonPairsEqualTheMinkowskiSum) {
  std::mt19937_64 random(5656);
  int compared = 0, parallel = 0;
  for (int instance = 0; instance < 14; ++instance) {
    const int k = 3 + static_cast<int>(random() % 14);
    const int m = instance % 2 == 0 ? k : 3 + static_cast<int>(random() % 14);
    const long grid = instance % 3 == 0 ? 8 : instance % 3 == 1 ? 64 : 97;
    const Rational turn_a(static_cast<long>(random() % 9) - 4, 7), turn_b = instance % 2 == 0 ? turn_a : Rational(static_cast<long>(random() % 9) - 4, 5);
    const Rational ra(3 + static_cast<long>(random() % 40), 1 + static_cast<long>(random() % 7));
    const Rational rb(2 + static_cast<long>(random() % 30), 1 + static_cast<long>(random() % 5));
    const Rational bx(static_cast<long>(random() % 41) - 20, 3), by(static_cast<long>(random() % 41) - 20, 7);
    auto a = rational_circle_polygon(k, ra, Rational(0), Rational(0), grid, turn_a);
    auto b = rational_circle_polygon(m, rb, bx, by, grid, turn_b);
    SCOPED_TRACE("instance " + std::to_string(instance) + ": " + std::to_string(k) + "-gon and " + std::to_string(m) + "-gon");
    try {
      expect_minkowski(a, b);
      ++compared;
      parallel += k == m;
    } catch (const ModelError&) {
      // rounding repeated a vertex (a coarse grid, many vertices): not a test case
    }
  }
  EXPECT_GE(compared, 11);
  EXPECT_GE(parallel, 5);
}

// The shortcuts of translating polygon pairs checked by the exact oracle on random pairs:
// check_face_classification has the oracle confirm every face decided by a contact edge's
// blocked side or by propagation across curve-free edges, and every one-contact edge between
// blocked faces that the zero-clearance search no longer sends to the oracle (the blocked
// region itself is compared with CGAL's sum by RandomRationalPolygonsEqualTheMinkowskiSum).
TEST(CSpaceMinkowski, RandomRationalPolygonsShortcutsAgreeWithTheOracle) {
  std::mt19937_64 random(77);
  int built = 0;
  for (int instance = 0; instance < 16; ++instance) {
    int ka = 3 + static_cast<int>(random() % 8), kb = 3 + static_cast<int>(random() % 8);
    long q = instance % 2 == 0 ? 1 : 16;
    auto a = random_star(random, ka, 0, 0, 3 + static_cast<double>(random() % 4), q);
    auto b = random_star(random, kb, static_cast<double>(random() % 7) - 3, static_cast<double>(random() % 7) - 3,
                         2 + static_cast<double>(random() % 5), q);
    SCOPED_TRACE("instance " + std::to_string(instance));
    try {
      Model model = two_sliders(a, b);
      CSpaceBuildOptions options;
      options.check_face_classification = true;
      CSpace space = CSpace::build(model, "a", "b", options);
      std::size_t contact = 0;
      for (const auto& edge : space.edges()) contact += edge.role == EdgeRole::contact ? 1 : 0;
      EXPECT_GT(contact, 0u);
      ++built;
    } catch (const ModelError&) {
      // rounding made a polygon degenerate (repeated vertex, self-touching): not a test case
    }
  }
  EXPECT_GE(built, 12);
}

// Session 72 (poly72): rectilinear pairs, where every edge of one polygon is parallel to edges of
// the other, so that contact segments of several vertex–edge pairs lie on one line and overlap
// (the segment stage splits them before CGAL's sweep: split_overlaps). Random histogram
// polygons (columns of random integer heights on a unit grid: collinear runs where heights
// repeat), scaled by random rationals and placed at random rational offsets; the blocked region
// equals CGAL's Minkowski sum exactly.
TEST(CSpaceMinkowski, RectilinearPolygonPairsWithOverlappingContactsEqualTheMinkowskiSum) {
  std::mt19937_64 random(test::test_seed(7273));
  auto histogram = [&](int columns, const Rational& scale, const Rational& dx, const Rational& dy) {
    std::vector<long> h(static_cast<std::size_t>(columns));
    for (long& v : h) v = 1 + static_cast<long>(random() % 3);
    std::vector<std::pair<Rational, Rational>> corners = {{0, 0}, {columns, 0}, {columns, h.back()}};
    for (int i = columns - 1; i >= 1; --i)
      if (h[i] != h[i - 1]) {
        corners.emplace_back(i, h[i]);
        corners.emplace_back(i, h[i - 1]);
      }
    corners.emplace_back(0, h.front());
    std::vector<std::pair<std::string, std::string>> points;
    for (const auto& [x, y] : corners)
      points.emplace_back(Rational(x * scale + dx).get_str(), Rational(y * scale + dy).get_str());
    return points;
  };
  auto small_rational = [&](long range, long den) {
    Rational q(static_cast<long>(random() % static_cast<unsigned long>(2 * range + 1)) - range, den);
    q.canonicalize();
    return q;
  };
  int compared = 0;
  for (int instance = 0; instance < 16; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const long den = instance % 2 == 0 ? 1 : 3 + static_cast<long>(random() % 5);
    Rational sa(1 + static_cast<long>(random() % 4), den), sb(1 + static_cast<long>(random() % 4), den);
    sa.canonicalize();
    sb.canonicalize();
    auto a = histogram(1 + static_cast<int>(random() % 4), sa, small_rational(3, den), small_rational(3, den));
    auto b = histogram(1 + static_cast<int>(random() % 4), sb, small_rational(6, 7), small_rational(6, 7));
    expect_minkowski(a, b);
    ++compared;
  }
  EXPECT_EQ(compared, 16);
}

TEST(CSpaceMinkowski, TriangleAndSquare) {
  expect_minkowski({{"0", "0"}, {"4", "0"}, {"1", "3"}}, {{"10", "10"}, {"12", "10"}, {"12", "12"}, {"10", "12"}});
}

TEST(CSpaceMinkowski, NonConvexLAndRationalTriangle) {
  expect_minkowski({{"0", "0"}, {"6", "0"}, {"6", "1"}, {"1", "1"}, {"1", "5"}, {"0", "5"}},
                   {{"20", "-3"}, {"23.5", "-3"}, {"21", "1/7"}});
}

TEST(CSpaceMinkowski, CollinearAndParallelEdges) {
  // squares of equal height: parallel edges slide along each other (overlapping contact curves)
  expect_minkowski({{"0", "0"}, {"2", "0"}, {"2", "2"}, {"0", "2"}}, {{"5", "0"}, {"7", "0"}, {"7", "2"}, {"5", "2"}});
}

}  // namespace
}  // namespace hipair
