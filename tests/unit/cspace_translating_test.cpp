// Translating pairs on the circle–segment arrangement (src/arrangement/circle_segment_traits.cpp):
// random rational parts bounded by segments and circular arcs (disks, rounded rectangles,
// squares with a bulge or a dent, star polygons), each part translating along its own axis;
// exact point location at thousands of random rational configurations per pair against the
// exact overlap oracle; every vertex exact; zero-clearance fits with arcs (a disk in a round
// hole and a rounded square in a rounded hole of exactly their size: one touching
// configuration; a disk in a stadium slot of exactly its diameter: a touching channel).
// The Minkowski-sum equality for polygons is in cspace_minkowski_test.cpp (CGAL there).
#include "algebra/exact_real.hpp"
#include "curves/contact_curves.hpp"
#include "random_rationals.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

using test_numbers::random_rational;

std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }
std::string point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }

// ---------------------------------------------------------------- shapes (loop JSON, ccw)

std::string disk(const Rational& cx, const Rational& cy, const Rational& r) {
  return R"({ "circle": { "center": )" + point(cx, cy) + R"(, "radius": )" + text(r) + " } }";
}

std::string rounded_rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1,
                              const Rational& r) {
  auto arc = [&](const Rational& px, const Rational& py, const Rational& cx, const Rational& cy) {
    return R"({ "arc_to": )" + point(px, py) + R"(, "center": )" + point(cx, cy) + R"(, "dir": "ccw" })";
  };
  return R"({ "start": )" + point(x0 + r, y0) + R"(, "edges": [ { "line_to": )" + point(x1 - r, y0) + " }, " +
         arc(x1, y0 + r, x1 - r, y0 + r) + R"(, { "line_to": )" + point(x1, y1 - r) + " }, " + arc(x1 - r, y1, x1 - r, y1 - r) +
         R"(, { "line_to": )" + point(x0 + r, y1) + " }, " + arc(x0, y1 - r, x0 + r, y1 - r) + R"(, { "line_to": )" +
         point(x0, y0 + r) + " }, " + arc(x0 + r, y0, x0 + r, y0 + r) + " ] }";
}

// The square [x0, x0 + 6t] x [y0, y0 + 6t] whose top side is replaced by an arc of radius 5t
// (a Pythagorean 3-4-5 chord, so the radius is rational): bulging out by t, or dented in by t.
std::string arched_square(const Rational& x0, const Rational& y0, const Rational& t, bool bulge) {
  Rational a = 6 * t;
  Rational cx = x0 + 3 * t, cy = bulge ? Rational(y0 + a - 4 * t) : Rational(y0 + a + 4 * t);
  return R"({ "start": )" + point(x0, y0) + R"(, "edges": [ { "line_to": )" + point(x0 + a, y0) + R"( }, { "line_to": )" +
         point(x0 + a, y0 + a) + R"( }, { "arc_to": )" + point(x0, y0 + a) + R"(, "center": )" + point(cx, cy) +
         R"(, "dir": ")" + (bulge ? "ccw" : "cw") + R"(" }, { "line_to": )" + point(x0, y0) + " } ] }";
}

// A star-shaped polygon around (cx, cy) with k vertices at increasing angles (rational
// coordinates on a 1/16 grid; a double only places the test input).
std::string star(Random& random, const Rational& cx, const Rational& cy, int k, double radius) {
  std::vector<std::pair<Rational, Rational>> points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * std::numbers::pi * (i + 0.15 + 0.7 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (0.5 + 0.5 * static_cast<double>(random() % 1000) / 1000.0);
    Rational x(static_cast<long>(std::lround(16 * r * std::cos(angle))), 16), y(static_cast<long>(std::lround(16 * r * std::sin(angle))), 16);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(cx + x, cy + y);
  }
  std::string loop = R"({ "start": )" + point(points[0].first, points[0].second) + R"(, "edges": [ )";
  for (int i = 1; i <= k; ++i)
    loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": )" + point(points[i % k].first, points[i % k].second) + " }";
  return loop + " ] }";
}

// A right triangle with legs 4t (along x) and 3t (along y) at (x0, y0): every side has a
// rational length (3-4-5), so arcs against its sides give lines with rational offsets.
std::string pythagorean_triangle(const Rational& x0, const Rational& y0, const Rational& t, bool flip) {
  Rational sx = flip ? Rational(-4 * t) : Rational(4 * t);
  return R"({ "start": )" + point(x0, y0) + R"(, "edges": [ { "line_to": )" + point(x0 + sx, y0) + R"( }, { "line_to": )" +
         point(x0, y0 + 3 * t) + R"( }, { "line_to": )" + point(x0, y0) + " } ] }";
}

// An L-shaped (non-convex, rectilinear) hexagon of arm widths u, v around (x0, y0).
std::string l_shape(const Rational& x0, const Rational& y0, const Rational& w, const Rational& h, const Rational& u,
                    const Rational& v) {
  return R"({ "start": )" + point(x0, y0) + R"(, "edges": [ { "line_to": )" + point(x0 + w, y0) + R"( }, { "line_to": )" +
         point(x0 + w, y0 + v) + R"( }, { "line_to": )" + point(x0 + u, y0 + v) + R"( }, { "line_to": )" + point(x0 + u, y0 + h) +
         R"( }, { "line_to": )" + point(x0, y0 + h) + R"( }, { "line_to": )" + point(x0, y0) + " } ] }";
}

// The stadium [0, L] x [-r, r] with round ends of radius r.
std::string stadium(const Rational& L, const Rational& r) {
  return R"({ "start": )" + point(0, -r) + R"(, "edges": [ { "line_to": )" + point(L, -r) + R"( }, { "arc_to": )" + point(L, r) +
         R"(, "center": )" + point(L, 0) + R"(, "dir": "ccw" }, { "line_to": )" + point(0, r) + R"( }, { "arc_to": )" + point(0, -r) +
         R"(, "center": )" + point(0, 0) + R"(, "dir": "ccw" } ] })";
}

std::string two_sliders(const std::string& a_loops, const std::string& b_loops, const std::string& a_direction = "[1, 0]",
                        const std::string& b_direction = "[0, 1]") {
  return R"({ "hipair": 1, "name": "sliders", "parts": [
    { "name": "a", "motion": { "translation": { "direction": )" +
         a_direction + R"( } }, "loops": [ )" + a_loops + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": )" +
         b_direction + R"( } }, "loops": [ )" + b_loops + R"( ] } ], "pairs": [ { "parts": ["a", "b"] } ] })";
}

// ---------------------------------------------------------------- checks

cspace::Overlap oracle(const Model& model, const CSpace& space, const ChartPoint& q) {
  std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
  cspace::PairAxes axes = cspace::pair_axes(model, first, second);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  std::size_t y_count = layout.y_charts.size();
  return cspace::classify_overlap(model, axes, layout.x_charts[q.chart / y_count], layout.y_charts[q.chart % y_count],
                                  cspace::ChartPoint{q.x, q.y});
}

bool real_location(const CSpace& space, const Location& location) {
  if (location.cell != no_index) return false;
  if (location.kind == Location::Kind::edge) return space.edges()[location.edge].real;
  if (location.kind == Location::Kind::vertex) {
    const CSpaceVertex& vertex = space.vertices()[location.vertex];
    bool real = vertex.touching;
    for (std::size_t e : vertex.edges) real = real || space.edges()[e].real;
    return real;
  }
  return false;
}

struct Counts {
  int free = 0, blocked = 0, contact = 0;
};

// Point location equals the oracle at random rational configurations (a quarter of them on a
// 1/64 grid of the chart, which hits contact edges and vertices now and then).
Counts agree_with_oracle(const Model& model, const CSpace& space, Random& random, int samples) {
  Counts counts;
  for (int i = 0; i < samples; ++i) {
    std::size_t c = random() % space.charts().size();
    const CSpaceChart& chart = space.charts()[c];
    auto pick = [&](const Rational& lo, const Rational& hi) {
      if (random() % 4 == 0) {
        Rational u(static_cast<long>(random() % 65), 64);
        u.canonicalize();
        Rational v = lo + u * (hi - lo);
        v.canonicalize();
        return v;
      }
      return random_rational(random, lo, hi, 1000003);
    };
    ChartPoint q{c, pick(chart.x_lo, chart.x_hi), pick(chart.y_lo, chart.y_hi)};
    Location location = space.locate(q);
    cspace::Overlap truth = oracle(model, space, q);
    std::string where = "chart " + std::to_string(c) + " at " + q.x.get_str() + ", " + q.y.get_str();
    switch (location.kind) {
      case Location::Kind::free:
        EXPECT_EQ(truth, cspace::Overlap::apart) << where;
        ++counts.free;
        break;
      case Location::Kind::blocked:
        EXPECT_EQ(truth, cspace::Overlap::overlapping) << where;
        ++counts.blocked;
        break;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        ++counts.contact;
        if (real_location(space, location)) {
          EXPECT_EQ(truth, cspace::Overlap::touching) << where;
        } else if (location.cell != no_index) {
          // a spurious piece inside one cell: the cell's class (or a touch the cell hides:
          // never, the spurious curves of translating pairs bound nothing)
          bool free = space.cells()[location.cell].kind == CellKind::free;
          EXPECT_EQ(truth, free ? cspace::Overlap::apart : cspace::Overlap::overlapping) << where;
        }
        break;
      default:
        ADD_FAILURE() << "outside the built space " << where;
    }
  }
  return counts;
}

// Every vertex of a circle–segment chart is exact: y a univariate algebraic number within its
// bounds; at a rational abscissa, the vertex lies exactly on the polynomial of each incident
// contact edge.
void expect_exact_vertices(const CSpace& space) {
  for (std::size_t v = 0; v < space.vertices().size(); ++v) {
    const CSpaceVertex& vertex = space.vertices()[v];
    ASSERT_TRUE(vertex.y_exact) << "vertex " << v;
    cspace::algebra::Real y{vertex.y.polynomial, vertex.y.lower, vertex.y.upper, vertex.y.exact};
    EXPECT_LE(vertex.y_lower, vertex.y.lower);
    EXPECT_GE(vertex.y_upper, vertex.y.upper);
    if (!vertex.x.exact) continue;
    for (std::size_t e : vertex.edges) {
      cspace::IntegerPolynomial2 f{space.edge_polynomial_coefficients(e)};
      EXPECT_TRUE(cspace::algebra::vanishes_at(f, vertex.x.lower, y)) << "vertex " << v << " edge " << e;
    }
  }
}

// ---------------------------------------------------------------- random arc-bounded pairs

std::string random_shape(Random& random, int kind, const Rational& cx, const Rational& cy) {
  switch (kind) {
    case 0: return disk(cx, cy, random_rational(random, Rational(1, 2), Rational(4)));
    case 1: {
      Rational w = random_rational(random, Rational(2), Rational(6)), h = random_rational(random, Rational(2), Rational(6));
      Rational r = random_rational(random, Rational(1, 10), std::min(w, h) / 2 - Rational(1, 20));
      return rounded_rectangle(cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2, r);
    }
    case 2: {
      Rational t = random_rational(random, Rational(1, 4), Rational(1));
      return arched_square(cx - 3 * t, cy - 3 * t, t, random() % 2 == 0);
    }
    case 3: {
      Rational t = random_rational(random, Rational(1, 4), Rational(1));
      return pythagorean_triangle(cx - 2 * t, cy - t, t, random() % 2 == 0);
    }
    default: {
      Rational w = random_rational(random, Rational(2), Rational(5)), h = random_rational(random, Rational(2), Rational(5));
      return l_shape(cx - w / 2, cy - h / 2, w, h, random_rational(random, w / 5, w * 4 / 5),
                     random_rational(random, h / 5, h * 4 / 5));
    }
  }
}

TEST(CSpaceTranslating, ArcBoundedPartsAgreeWithTheExactOracle) {
  Random random(1313);
  Counts total;
  for (int instance = 0; instance < 12; ++instance) {
    // a: any shape whose sides have rational lengths; b has an arc (disk, rounded, arched)
    int kind_a = static_cast<int>(random() % 5), kind_b = instance % 3;
    std::string a = random_shape(random, kind_a, random_rational(random, Rational(-3), Rational(3)),
                                 random_rational(random, Rational(-3), Rational(3)));
    std::string b = random_shape(random, kind_b, random_rational(random, Rational(-3), Rational(3)),
                                 random_rational(random, Rational(-3), Rational(3)));
    // directions: the axes, or an orthogonal rational pair (circles stay circles in (s, r))
    bool turned = instance % 4 == 3;
    Model model = read_model(turned ? two_sliders(a, b, "[3, 4]", "[-4, 3]") : two_sliders(a, b));
    SCOPED_TRACE("instance " + std::to_string(instance) + ": " + a + " / " + b);
    CSpace space = CSpace::build(model, "a", "b");
    ASSERT_EQ(space.dimension(), 2);
    EXPECT_EQ(space.statistics().circle_segment_charts, space.charts().size());
    expect_exact_vertices(space);
    Counts counts = agree_with_oracle(model, space, random, 1500);
    total.free += counts.free;
    total.blocked += counts.blocked;
    total.contact += counts.contact;
    EXPECT_GT(counts.free, 0);
    EXPECT_GT(counts.blocked, 0);
  }
  EXPECT_GT(total.contact, 0);
}

TEST(CSpaceTranslating, ObliqueDirectionsAndIrrationalRadiiUseTheAlgebraicStage) {
  // non-orthogonal directions turn circles into ellipses in (s, r), and an arc of irrational
  // radius or a segment of irrational length against an arc makes squared contact polynomials
  // (two parallel lines at an irrational distance): these go to the algebraic traits, same answers
  Random random(77);
  std::string square = R"({ "start": [0, 0], "edges": [ { "line_to": [2, 0] }, { "line_to": [2, 2] }, { "line_to": [0, 2] }, { "line_to": [0, 0] } ] })";
  {
    Model model = read_model(two_sliders(disk(5, 1, 1), square, "[1, 0]", "[1, 1]"));
    CSpace space = CSpace::build(model, "a", "b");
    EXPECT_EQ(space.statistics().circle_segment_charts, 0u);
    agree_with_oracle(model, space, random, 400);
  }
  {
    // radius sqrt(2): the arc from (1, 0) to (-1, 2) about (0, 1)
    std::string lens = R"({ "start": [1, 0], "edges": [ { "arc_to": [1, 2], "center": [0, 1], "dir": "ccw" }, { "line_to": [1, 0] } ] })";
    Model model = read_model(two_sliders(lens, square));
    CSpace space = CSpace::build(model, "a", "b");
    EXPECT_EQ(space.statistics().circle_segment_charts, 0u);
    agree_with_oracle(model, space, random, 400);
    // a disk against a star polygon (sides of irrational length)
    Model star_disk = read_model(two_sliders(star(random, 0, 0, 7, 3.0), disk(1, 5, 2)));
    CSpace star_space = CSpace::build(star_disk, "a", "b");
    EXPECT_EQ(star_space.statistics().circle_segment_charts, 0u);
    agree_with_oracle(star_disk, star_space, random, 400);
    // the same pair of polygons is a circle–segment pair
    Model polygons = read_model(two_sliders(square, square, "[1, 0]", "[1, 1]"));
    EXPECT_EQ(CSpace::build(polygons, "a", "b").statistics().circle_segment_charts, 1u);
  }
}

TEST(CSpaceTranslating, AnyScaleFrom1eMinus120To1e120GivesTheSameCells) {
  // a disk against a square with an arc side, every length times 10^e: the same cells, and
  // point location agrees with the oracle at every scale
  Random random(58);
  std::size_t cells = 0;
  for (int e = -120; e <= 120; e += 40) {
    mpz_class power;
    mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(e)));
    Rational u = e >= 0 ? Rational(power) : Rational(1) / Rational(power);
    u.canonicalize();
    SCOPED_TRACE("scale 1e" + std::to_string(e));
    Model model = read_model(two_sliders(disk(u / 3, u * 2 / 7, u * 3 / 2), arched_square(0, 0, u / 2, false)));
    CSpace space = CSpace::build(model, "a", "b");
    EXPECT_EQ(space.statistics().circle_segment_charts, 1u);
    if (cells == 0) cells = space.cells().size();
    EXPECT_EQ(space.cells().size(), cells);
    Counts counts = agree_with_oracle(model, space, random, 200);
    EXPECT_GT(counts.free, 0);
    // (the chart box is wider than the parts by a fixed margin, so random samples may miss
    // the blocked region at small scales): the disk's centre inside the square is blocked
    ChartPoint inside{0, u * 3 / 2 - u / 3, 0};
    inside.x.canonicalize();
    EXPECT_EQ(space.locate(inside).kind, Location::Kind::blocked);
    EXPECT_EQ(oracle(model, space, inside), cspace::Overlap::overlapping);
  }
}

// ---------------------------------------------------------------- zero clearance with arcs

// A plate (translating along y, limits [-1, 1]) with a hole; a peg (translating along x,
// limits [h - 1, h + 1]) that fits the hole exactly at offsets (-h ... ): peg at s = h, plate at
// r = 0 puts the peg's shape exactly on the hole.
std::string peg_in_plate(const std::string& peg, const std::string& hole, const Rational& h) {
  std::string plate = R"({ "start": [-20, -20], "edges": [ { "line_to": [20, -20] }, { "line_to": [20, 20] }, { "line_to": [-20, 20] }, { "line_to": [-20, -20] } ] }, )" + hole;
  return R"({ "hipair": 1, "name": "peg", "parts": [
    { "name": "peg", "motion": { "translation": { "direction": [1, 0], "limits": [)" +
         text(h - 1) + ", " + text(h + 1) + R"(] } }, "loops": [ )" + peg + R"( ] },
    { "name": "plate", "motion": { "translation": { "direction": [0, 1], "limits": [-1, 1] } }, "loops": [ )" + plate +
         R"( ] } ], "pairs": [ { "parts": ["peg", "plate"] } ] })";
}

void expect_single_touching_fit(const Model& model, const Rational& h, Random& random) {
  CSpace space = CSpace::build(model, "peg", "plate");
  ASSERT_EQ(space.charts().size(), 1u);
  EXPECT_EQ(space.statistics().circle_segment_charts, 1u);
  EXPECT_EQ(space.statistics().touching_vertices, 1u);
  ChartPoint fit{0, h, 0};
  EXPECT_EQ(oracle(model, space, fit), cspace::Overlap::touching);
  Location location = space.locate(fit);
  ASSERT_EQ(location.kind, Location::Kind::vertex);
  EXPECT_TRUE(space.vertices()[location.vertex].touching);
  EXPECT_EQ(location.cell, no_index);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      if (dx == 0 && dy == 0) continue;
      ChartPoint q{0, h + Rational(dx, 1000000), Rational(dy, 1000000)};
      q.x.canonicalize();
      Location near = space.locate(q);
      EXPECT_EQ(oracle(model, space, q), cspace::Overlap::overlapping);
      EXPECT_TRUE(near.kind == Location::Kind::blocked ||
                  (near.cell != no_index && space.cells()[near.cell].kind == CellKind::blocked))
          << dx << " " << dy;
    }
  for (const auto& cell : space.cells()) EXPECT_NE(cell.kind, CellKind::free);
  agree_with_oracle(model, space, random, 300);
}

TEST(CSpaceTranslating, DiskInARoundHoleOfExactlyItsRadiusTouchesAtOneConfiguration) {
  Random random(55);
  for (int instance = 0; instance < 6; ++instance) {
    Rational r = random_rational(random, Rational(1, 3), Rational(5)), h = random_rational(random, Rational(-5), Rational(5));
    Rational cx = random_rational(random, Rational(-4), Rational(4)), cy = random_rational(random, Rational(-4), Rational(4));
    SCOPED_TRACE("r " + r.get_str() + " h " + h.get_str());
    // the peg's disk at (cx - h, cy): at s = h it lies on the hole (cx, cy)
    Model model = read_model(peg_in_plate(disk(cx - h, cy, r), disk(cx, cy, r), h));
    expect_single_touching_fit(model, h, random);
  }
}

TEST(CSpaceTranslating, RoundedSquareInARoundedHoleOfExactlyItsSizeTouchesAtOneConfiguration) {
  Random random(56);
  for (int instance = 0; instance < 6; ++instance) {
    Rational w = random_rational(random, Rational(1), Rational(6)), h = random_rational(random, Rational(-5), Rational(5));
    Rational r = random_rational(random, Rational(1, 10), w / 2 - Rational(1, 20));
    SCOPED_TRACE("w " + w.get_str() + " r " + r.get_str() + " h " + h.get_str());
    Model model = read_model(peg_in_plate(rounded_rectangle(-h - w / 2, -w / 2, -h + w / 2, w / 2, r),
                                          rounded_rectangle(-w / 2, -w / 2, w / 2, w / 2, r), h));
    expect_single_touching_fit(model, h, random);
  }
}

TEST(CSpaceTranslating, DiskInAStadiumSlotOfExactlyItsDiameterRunsOnATouchingChannel) {
  Random random(57);
  for (int instance = 0; instance < 6; ++instance) {
    Rational r = random_rational(random, Rational(1, 3), Rational(3)), L = random_rational(random, Rational(1), Rational(6));
    SCOPED_TRACE("r " + r.get_str() + " L " + L.get_str());
    // the slot: the stadium [0, L] x [-r, r] with round ends of radius r; the disk at the origin
    std::string slot = stadium(L, r);
    std::string plate = R"({ "start": [-20, -20], "edges": [ { "line_to": [20, -20] }, { "line_to": [20, 20] }, { "line_to": [-20, 20] }, { "line_to": [-20, -20] } ] }, )" + slot;
    Model model = read_model(R"({ "hipair": 1, "name": "slot", "parts": [
      { "name": "pin", "motion": { "translation": { "direction": [1, 0], "limits": [-1, )" + text(L + 1) + R"(] } }, "loops": [ )" +
                             disk(0, 0, r) + R"( ] },
      { "name": "plate", "motion": { "translation": { "direction": [0, 1], "limits": [-1, 1] } }, "loops": [ )" + plate +
                             R"( ] } ], "pairs": [ { "parts": ["pin", "plate"] } ] })");
    CSpace space = CSpace::build(model, "pin", "plate");
    EXPECT_EQ(space.statistics().circle_segment_charts, 1u);
    EXPECT_GT(space.statistics().touching_edges, 0u);
    for (int k = 0; k <= 8; ++k) {
      Rational s = L * Rational(k, 8);
      s.canonicalize();
      ChartPoint q{0, s, 0};
      EXPECT_EQ(oracle(model, space, q), cspace::Overlap::touching);
      EXPECT_TRUE(real_location(space, space.locate(q))) << s;
    }
    agree_with_oracle(model, space, random, 300);
  }
}

}  // namespace
}  // namespace hipair
