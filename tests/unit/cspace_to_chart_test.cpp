// CSpace::to_chart stops at the first chart that holds the configuration (src/cspace/cspace.cpp,
// chart_points' first_only). Oracle: the definition, written here from the public charts — the
// configuration's chart coordinates (t itself, or -1/t on a half-turn chart; the half turn is 0
// there and in no other chart; an offset itself) in the first chart, in chart order, whose closed
// box holds them. Generated configurations on the example spaces and the sliding pairs' spaces:
// random coordinates, the charts' sides exactly (where neighbouring charts share a point), 0, ±1,
// a few ulps off the sides, the half turn; every answer (chart, x, y exactly, or none) must equal
// the oracle's.
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::optional<Rational> convert(const PartCoordinate& p, AxisKind kind, bool half_turn) {
  if (kind == AxisKind::translation) return p.value;
  if (p.kind == PartCoordinate::Kind::half_turn) return half_turn ? std::optional<Rational>(Rational(0)) : std::nullopt;
  if (!half_turn) return p.value;
  if (sgn(p.value) == 0) return std::nullopt;
  Rational t = -1 / p.value;
  t.canonicalize();
  return t;
}

std::string oracle(const CSpace& space, const PartCoordinate& x, const PartCoordinate& y) {
  for (std::size_t c = 0; c < space.charts().size(); ++c) {
    const CSpaceChart& chart = space.charts()[c];
    std::optional<Rational> cx = convert(x, chart.x_kind, chart.x_half_turn);
    if (!cx || *cx < chart.x_lo || *cx > chart.x_hi) continue;
    if (space.dimension() == 1) return std::to_string(c) + " " + cx->get_str() + " 0";
    std::optional<Rational> cy = convert(y, chart.y_kind, chart.y_half_turn);
    if (!cy || *cy < chart.y_lo || *cy > chart.y_hi) continue;
    return std::to_string(c) + " " + cx->get_str() + " " + cy->get_str();
  }
  return "none";
}

std::string answer(const CSpace& space, const PartCoordinate& x, const PartCoordinate& y) {
  std::optional<ChartPoint> p = space.to_chart(x, y);
  if (!p) return "none";
  Rational px = p->x, py = space.dimension() == 1 ? Rational(0) : p->y;
  px.canonicalize();
  py.canonicalize();
  return std::to_string(p->chart) + " " + px.get_str() + " " + py.get_str();
}

TEST(CSpaceToChart, FirstChartHoldingTheConfiguration) {
  std::mt19937_64 random(20261130);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const test::SlidingPair& pair : test::sliding_pairs)
    spaces.push_back(std::make_unique<CSpace>(
        CSpace::build(read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / pair.file), pair.first, pair.second)));
  std::size_t compared = 0, none = 0, later_chart = 0;
  std::uniform_real_distribution<double> sym(-3, 3);
  for (std::size_t s = 0; s < spaces.size(); ++s) {
    const CSpace& space = *spaces[s];
    const CSpaceChart& first = space.charts().front();
    // candidate values per axis: the charts' sides and their images, 0, ±1, random, ulps off
    auto values = [&](bool x_axis) {
      std::vector<Rational> v{Rational(0), Rational(1), Rational(-1)};
      for (const CSpaceChart& chart : space.charts())
        for (const Rational& side : x_axis ? std::vector<Rational>{chart.x_lo, chart.x_hi} : std::vector<Rational>{chart.y_lo, chart.y_hi}) {
          v.push_back(side);
          if (sgn(side) != 0) v.push_back(Rational(-1 / side));
          double d = side.get_d();
          v.push_back(Rational(std::nextafter(d, 1e300)));
          v.push_back(Rational(std::nextafter(d, -1e300)));
        }
      for (int k = 0; k < 20; ++k) v.push_back(Rational(sym(random)));
      return v;
    };
    auto coordinate = [](AxisKind kind, const Rational& value, bool half) {
      if (kind == AxisKind::translation) return PartCoordinate{PartCoordinate::Kind::offset, value};
      if (half) return PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)};
      return PartCoordinate{PartCoordinate::Kind::half_angle_tangent, value};
    };
    std::vector<Rational> xs = values(true), ys = values(false);
    for (std::size_t i = 0; i < xs.size(); ++i)
      for (std::size_t j = 0; j < (space.dimension() == 2 ? ys.size() : 1); ++j)
        for (int half = 0; half < 4; ++half) {
          PartCoordinate x = coordinate(first.x_kind, xs[i], half & 1);
          PartCoordinate y = space.dimension() == 2 ? coordinate(first.y_kind, ys[j], half & 2) : PartCoordinate{};
          std::string expected = oracle(space, x, y), got = answer(space, x, y);
          ASSERT_EQ(got, expected) << "space " << s << " (" << space.first_part() << ":" << space.second_part() << ") x "
                                   << xs[i] << " y " << (space.dimension() == 2 ? ys[j] : Rational(0)) << " half " << half;
          ++compared;
          none += expected == "none";
          later_chart += expected != "none" && expected.rfind("0 ", 0) != 0;
        }
  }
  std::printf("to_chart: %zu configurations, %zu in no chart, %zu first held by a later chart\n", compared, none, later_chart);
  EXPECT_GT(compared, 10000u);
  EXPECT_GT(later_chart, compared / 4);
}

}  // namespace
}  // namespace hipair
