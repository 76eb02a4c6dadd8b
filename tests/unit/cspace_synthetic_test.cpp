// The C-space builder on synthetic curves with an exact synthetic overlap oracle: a disk
// obstacle in one chart, a channel around a cylinder (rotation x translation) and a diagonal
// channel around a torus (two rotations, four charts glued along seams, as for a Geneva pair).
#include "cspace/builder_impl.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <random>

namespace hipair::cspace {
namespace {

IntegerPolynomial2 polynomial(std::vector<std::vector<long>> rows) {
  IntegerPolynomial2 f;
  for (auto& row : rows) {
    f.coefficients.emplace_back();
    for (long c : row) f.coefficients.back().push_back(mpz_class(c));
  }
  return f;
}

ContactCurve curve(IntegerPolynomial2 f, std::string label) {
  ContactCurve c;
  c.polynomial = std::move(f);
  c.label = std::move(label);
  return c;
}

Overlap by_sign(int sign) { return sign < 0 ? Overlap::apart : sign == 0 ? Overlap::touching : Overlap::overlapping; }

ChartAxis axis(ChartAxis::Kind kind, bool half_turn, long lo, long hi) {
  return ChartAxis{kind, half_turn, Rational(lo), Rational(hi)};
}

// ---------------------------------------------------------------- a disk in one chart

CSpace disk_space() {
  // blocked where 4x^2 + 4y^2 < 1
  PairInput input;
  input.first_part = input.x_part = "a";
  input.second_part = input.y_part = "b";
  ChartInput chart;
  chart.x = axis(ChartAxis::Kind::translation, false, -1, 1);
  chart.y = axis(ChartAxis::Kind::translation, false, -1, 1);
  IntegerPolynomial2 f = polynomial({{-1, 0, 4}, {0}, {4}});
  chart.curves.push_back(curve(f, "disk"));
  chart.classify = [f](const ChartPoint& q) { return by_sign(-algebra::sign_at(f, q.x, q.y)); };
  input.charts.push_back(std::move(chart));
  return build_cspace(std::move(input), {});
}

TEST(CSpaceSynthetic, DiskObstacleCellsAndLocation) {
  CSpace space = disk_space();
  ASSERT_EQ(space.cells().size(), 2u);
  std::size_t blocked = space.cells()[0].kind == CellKind::blocked ? 0 : 1;
  EXPECT_EQ(space.cells()[blocked].kind, CellKind::blocked);
  EXPECT_EQ(space.cells()[1 - blocked].kind, CellKind::free);
  EXPECT_FALSE(space.cells()[blocked].wraps_x);
  // the circle is split at its vertical and horizontal tangents: 4 contact edges
  EXPECT_EQ(space.statistics().contact_edges, 4u);
  EXPECT_EQ(space.cells()[blocked].boundary.size(), 4u);
  Location centre = space.locate(hipair::ChartPoint{0, Rational(0), Rational(0)});
  EXPECT_EQ(centre.kind, Location::Kind::blocked);
  EXPECT_EQ(centre.cell, blocked);
  Location on = space.locate(hipair::ChartPoint{0, Rational(3, 10), Rational(2, 5)});   // 9/100 + 16/100 = 1/4
  EXPECT_EQ(on.kind, Location::Kind::edge);
  EXPECT_TRUE(space.edges()[on.edge].real);
  Location tangent = space.locate(hipair::ChartPoint{0, Rational(1, 2), Rational(0)});  // vertical tangent: a vertex
  EXPECT_EQ(tangent.kind, Location::Kind::vertex);
  Location outside = space.locate(hipair::ChartPoint{0, Rational(3, 4), Rational(3, 4)});
  EXPECT_EQ(outside.kind, Location::Kind::free);
  // just off the circle, closer than a double can tell
  Rational near = Rational(1, 2) - Rational(1, mpz_class("1000000000000000000000"));
  EXPECT_EQ(space.locate(hipair::ChartPoint{0, near, Rational(0)}).kind, Location::Kind::blocked);
  EXPECT_EQ(space.locate(hipair::ChartPoint{0, Rational(1, 2) + (Rational(1, 2) - near), Rational(0)}).kind,
            Location::Kind::free);
}

TEST(CSpaceSynthetic, DiskRandomPointsAgreeWithOracle) {
  CSpace space = disk_space();
  IntegerPolynomial2 f = polynomial({{-1, 0, 4}, {0}, {4}});
  std::mt19937_64 random(7);
  for (int i = 0; i < 2000; ++i) {
    Rational x(static_cast<long>(random() % 2001) - 1000, 1000), y(static_cast<long>(random() % 2001) - 1000, 1000);
    int sign = algebra::sign_at(f, x, y);
    Location location = space.locate(hipair::ChartPoint{0, x, y});
    if (sign < 0) EXPECT_EQ(location.kind, Location::Kind::blocked) << x << " " << y;
    if (sign > 0) EXPECT_EQ(location.kind, Location::Kind::free) << x << " " << y;
    if (sign == 0) EXPECT_TRUE(location.kind == Location::Kind::edge || location.kind == Location::Kind::vertex);
  }
}

TEST(CSpaceSynthetic, EdgeEvaluationIsCertified) {
  CSpace space = disk_space();
  int checked = 0;
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (edge.role != EdgeRole::contact || edge.vertical) continue;
    double a = space.vertices()[edge.source].x.approximate(), b = space.vertices()[edge.target].x.approximate();
    for (int k = 1; k < 10; ++k) {
      double x = a + (b - a) * k / 10;
      CertifiedValue v = space.evaluate(e, x);
      // exact: y^2 = 1/4 - x^2 on the branch whose sign the edge's extent shows
      Rational y2 = Rational(1, 4) - Rational(x) * Rational(x);
      Rational lo = Rational(v.value) - Rational(v.error), hi = Rational(v.value) + Rational(v.error);
      bool upper = edge.y_chart.lower > -1e-12;
      if (upper) {
        EXPECT_LE(lo * lo * (lo >= 0 ? 1 : 0), y2);
        EXPECT_GE(hi * hi, y2);
        EXPECT_GE(hi, 0);
      } else {
        EXPECT_LE(lo, 0);
        EXPECT_GE(lo * lo, y2);
      }
      EXPECT_LT(v.error, 1e-14);
      AlgebraicNumber exact = space.evaluate_exact(e, Rational(x));
      EXPECT_LE(Rational(exact.lower) - Rational(1, mpz_class(1) << 40), hi);
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(CSpaceSynthetic, FirstCrossingIsExact) {
  CSpace space = disk_space();
  // from (-9/10, 0) to (9/10, 0): enters the disk at x = -1/2, u = 2/9
  Crossing c = space.first_crossing(hipair::ChartPoint{0, Rational(-9, 10), Rational(0)}, Rational(9, 10), Rational(0));
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.parameter_lower, Rational(2, 9));
  EXPECT_EQ(c.parameter_upper, Rational(2, 9));
  // an irrational crossing: from (-9/10, 1/5) to (9/10, 1/5): x = -sqrt(21)/10
  Crossing d = space.first_crossing(hipair::ChartPoint{0, Rational(-9, 10), Rational(1, 5)}, Rational(9, 10), Rational(1, 5));
  ASSERT_TRUE(d.found);
  EXPECT_FALSE(d.grazing);
  ASSERT_NE(d.edge, no_index);
  EXPECT_TRUE(space.edges()[d.edge].real);
  // u = (9 - sqrt 21)/18 = 0.245...
  double u = (9 - std::sqrt(21.0)) / 18;
  EXPECT_LE(d.parameter_lower, Rational(u + 1e-12));
  EXPECT_GE(d.parameter_upper, Rational(u - 1e-12));
  EXPECT_LT(d.parameter_upper - d.parameter_lower, Rational(1, mpz_class(1) << 60));
  EXPECT_NE(d.cell_entered, d.cell_left);
  // a path that stays free
  Crossing none = space.first_crossing(hipair::ChartPoint{0, Rational(-9, 10), Rational(9, 10)}, Rational(9, 10), Rational(9, 10));
  EXPECT_FALSE(none.found);
  // a path that touches the disk tangentially at (0, 1/2)
  Crossing touch = space.first_crossing(hipair::ChartPoint{0, Rational(-9, 10), Rational(1, 2)}, Rational(9, 10), Rational(1, 2));
  ASSERT_TRUE(touch.found);
  EXPECT_EQ(touch.parameter_lower, Rational(1, 2));
}

// ---------------------------------------------------------------- cylinder: rotation x translation

TEST(CSpaceSynthetic, ChannelAroundACylinderIsOneCell) {
  // free where |y| < 1/2 (y translation), for every angle: charts around 0 and pi glued
  PairInput input;
  input.first_part = input.x_part = "rotor";
  input.second_part = input.y_part = "slider";
  for (bool half_turn : {false, true}) {
    ChartInput chart;
    chart.x_index = half_turn ? 1 : 0;
    chart.y_index = 0;
    chart.x = axis(ChartAxis::Kind::rotation, half_turn, -1, 1);
    chart.y = axis(ChartAxis::Kind::translation, false, -1, 1);
    IntegerPolynomial2 f = polynomial({{-1, 0, 4}});   // 4y^2 - 1
    chart.curves.push_back(curve(f, "rails"));
    chart.classify = [f](const ChartPoint& q) { return by_sign(algebra::sign_at(f, q.x, q.y)); };
    input.charts.push_back(std::move(chart));
  }
  CSpace space = build_cspace(std::move(input), {});
  int free = 0, blocked = 0;
  for (const auto& cell : space.cells()) {
    if (cell.kind == CellKind::free) {
      ++free;
      EXPECT_TRUE(cell.wraps_x);
      EXPECT_FALSE(cell.wraps_y);
    } else {
      ++blocked;
      EXPECT_TRUE(cell.wraps_x);
    }
  }
  EXPECT_EQ(free, 1);
  EXPECT_EQ(blocked, 2);
  // theta = pi (half turn), y = 0 is free; theta = pi/2 exactly on the seam too
  Location at_pi = space.locate(PartCoordinate{PartCoordinate::Kind::half_turn, 0},
                                PartCoordinate{PartCoordinate::Kind::offset, Rational(0)});
  EXPECT_EQ(at_pi.kind, Location::Kind::free);
  Location on_seam = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(1)},
                                  PartCoordinate{PartCoordinate::Kind::offset, Rational(1, 4)});
  EXPECT_EQ(on_seam.kind, Location::Kind::free);
  Location rail = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(3)},
                               PartCoordinate{PartCoordinate::Kind::offset, Rational(-1, 2)});
  EXPECT_EQ(rail.kind, Location::Kind::edge);
}

// ---------------------------------------------------------------- torus: two rotations

// Free where |theta - phi| < 2 atan(1/3): a diagonal channel that wraps around both angles,
// like the Geneva pair's. With t, s the chart coordinates, tan((theta - phi)/2) is
// (t - s)/(1 + t s) for charts with the same centre and -(1 + t s)/(t - s) otherwise.
CSpace torus_space() {
  PairInput input;
  input.first_part = input.x_part = "driver";
  input.second_part = input.y_part = "wheel";
  for (bool x_half : {false, true})
    for (bool y_half : {false, true}) {
      ChartInput chart;
      chart.x_index = x_half;
      chart.y_index = y_half;
      chart.x = axis(ChartAxis::Kind::rotation, x_half, -1, 1);
      chart.y = axis(ChartAxis::Kind::rotation, y_half, -1, 1);
      // same centre: 9 (t - s)^2 - (1 + t s)^2 < 0 is free; else (1 + ts)^2 * 9 - (t - s)^2 < 0
      IntegerPolynomial2 f = x_half == y_half ? polynomial({{-1, 0, 9}, {0, -20}, {9, 0, -1}})
                                              : polynomial({{9, 0, -1}, {0, 20}, {-1, 0, 9}});
      chart.curves.push_back(curve(f, "channel wall"));
      chart.classify = [f](const ChartPoint& q) { return by_sign(algebra::sign_at(f, q.x, q.y)); };
      input.charts.push_back(std::move(chart));
    }
  return build_cspace(std::move(input), {});
}

TEST(CSpaceSynthetic, DiagonalChannelAroundATorusIsOneCell) {
  CSpace space = torus_space();
  int free = 0;
  for (const auto& cell : space.cells())
    if (cell.kind == CellKind::free) {
      ++free;
      EXPECT_TRUE(cell.wraps_x);
      EXPECT_TRUE(cell.wraps_y);
      EXPECT_GT(cell.faces, 1u);
    }
  EXPECT_EQ(free, 1);
  EXPECT_EQ(space.cells().size(), 2u);
  // every chart shares the channel
  std::mt19937_64 random(11);
  for (int i = 0; i < 3000; ++i) {
    std::size_t c = random() % 4;
    Rational x(static_cast<long>(random() % 2001) - 1000, 1000), y(static_cast<long>(random() % 2001) - 1000, 1000);
    const CSpaceChart& chart = space.charts()[c];
    bool same = chart.x_half_turn == chart.y_half_turn;
    // exact sign of the chart's wall polynomial
    Rational d = x - y, p = 1 + x * y;
    Rational value = same ? Rational(9 * d * d - p * p) : Rational(9 * p * p - d * d);
    Location location = space.locate(hipair::ChartPoint{c, x, y});
    if (value < 0) EXPECT_EQ(location.kind, Location::Kind::free);
    if (value > 0) EXPECT_EQ(location.kind, Location::Kind::blocked);
    if (value == 0) EXPECT_TRUE(location.kind == Location::Kind::edge || location.kind == Location::Kind::vertex);
  }
}

TEST(CSpaceSynthetic, OneDimensionalCircleWrapsAcrossTheSeam) {
  // a rotating part against a fixed one: blocked where t in (1/4, 1/2) in chart 0, else free
  PairInput input;
  input.first_part = input.x_part = "rotor";
  input.second_part = "frame";
  input.dimension = 1;
  for (bool half_turn : {false, true}) {
    ChartInput chart;
    chart.x_index = half_turn;
    chart.x = axis(ChartAxis::Kind::rotation, half_turn, -1, 1);
    IntegerPolynomial2 f = polynomial({{1}, {-6}, {8}});   // 8x^2 - 6x + 1 = (4x - 1)(2x - 1)
    if (!half_turn) chart.curves.push_back(curve(f, "stop"));
    chart.classify = [f, half_turn](const ChartPoint& q) {
      if (half_turn) return Overlap::apart;
      return by_sign(-algebra::sign_at(algebra::univariate_x(f), q.x));
    };
    input.charts.push_back(std::move(chart));
  }
  CSpace space = build_cspace(std::move(input), {});
  ASSERT_EQ(space.dimension(), 1);
  ASSERT_EQ(space.cells().size(), 2u);
  std::size_t free = space.cells()[0].kind == CellKind::free ? 0 : 1;
  // the free arc runs through theta = pi across both seams but is no full turn
  EXPECT_FALSE(space.cells()[free].wraps_x);
  EXPECT_EQ(space.cells()[free].faces, 3u);
  EXPECT_FALSE(space.cells()[1 - free].wraps_x);
  EXPECT_EQ(space.vertices().size(), 2u);
  EXPECT_EQ(space.locate(hipair::ChartPoint{0, Rational(1, 3)}).kind, Location::Kind::blocked);
  EXPECT_EQ(space.locate(hipair::ChartPoint{0, Rational(1, 4)}).kind, Location::Kind::vertex);
  EXPECT_EQ(space.locate(hipair::ChartPoint{1, Rational(0)}).kind, Location::Kind::free);
  Crossing c = space.first_crossing(hipair::ChartPoint{0, Rational(-1)}, Rational(1));
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.parameter_lower, Rational(5, 8));   // x = -1 + 2u = 1/4
}

}  // namespace
}  // namespace hipair::cspace
