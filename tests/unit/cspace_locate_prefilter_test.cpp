// Point location's vertex prefilter (src/cspace/builder_locate.cpp, locate_2d; switch
// cspace::locate_exact_prefilter() in src/cspace/locate_prefilter.hpp): a vertex is passed over by
// exact comparisons of its rational bounds with the point, not by their double conversions. The
// oracle: the same location with the double prefilter (the switch off), on points placed where
// the prefilter decides: exactly on the vertices' rational bounds (x's isolating interval's
// ends, y_lower, y_upper), on the rational vertices themselves, a few ulps around the vertices,
// and at random in their charts.
#include "cspace/locate_prefilter.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Switch = test::FlagSwitch<&cspace::locate_exact_prefilter>;

std::string describe(const Location& l) {
  return std::to_string(static_cast<int>(l.kind)) + " cell " + std::to_string(static_cast<long>(l.cell)) + " edge " +
         std::to_string(static_cast<long>(l.edge)) + " vertex " + std::to_string(static_cast<long>(l.vertex)) +
         " chart " + std::to_string(static_cast<long>(l.chart));
}

std::string locate(const CSpace& space, const ChartPoint& p, bool exact_prefilter) {
  Switch use(exact_prefilter);
  try {
    return describe(space.locate(p));
  } catch (const Error& e) {
    return std::string("error: ") + e.what();
  }
}

double ulps(double v, int n) {
  for (int s = 0; s < std::abs(n); ++s) v = std::nextafter(v, n < 0 ? -INFINITY : INFINITY);
  return v;
}

TEST(CSpaceLocateFilterVertices, LocationsEqualTheDoublePrefilters) {
  std::vector<std::unique_ptr<CSpace>> owned = test::example_spaces();
  std::mt19937_64 random(2222);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t points = 0, at_vertex = 0, spaces = 0;
  for (const auto& space_owner : owned) {
    const CSpace& space = *space_owner;
    if (space.dimension() != 2) continue;
    ++spaces;
    auto check = [&](std::size_t chart, const Rational& x, const Rational& y) {
      ChartPoint p{chart, x, y};
      std::string with = locate(space, p, true);
      std::string without = locate(space, p, false);
      ASSERT_EQ(with, without) << "chart " << chart << " x " << x << " y " << y;
      ++points;
      at_vertex += with.rfind("3 ", 0) == 0;
    };
    for (const CSpaceVertex& vertex : space.vertices()) {
      const CSpaceChart& chart = space.charts()[vertex.chart];
      const double x0 = vertex.x.approximate(), y0 = vertex.y_exact ? vertex.y.approximate()
                                                                     : Rational((vertex.y_lower + vertex.y_upper) / 2).get_d();
      Rational x_mid = (vertex.x.lower + vertex.x.upper) / 2;
      x_mid.canonicalize();
      std::vector<Rational> xs{vertex.x.lower, vertex.x.upper, x_mid};
      for (int k = -3; k <= 3; ++k) xs.push_back(Rational(ulps(x0, k)));
      std::vector<Rational> ys{vertex.y_lower, vertex.y_upper};
      if (vertex.y_exact && vertex.y.exact) ys.push_back(vertex.y.lower);
      for (int k = -3; k <= 3; ++k) ys.push_back(Rational(ulps(y0, k)));
      ys.push_back(chart.y_lo + (chart.y_hi - chart.y_lo) * Rational(unit(random)));
      if (vertex.x.exact && vertex.y_exact && vertex.y.exact) {
        check(vertex.chart, vertex.x.lower, vertex.y.lower);   // the vertex itself
        ASSERT_FALSE(HasFatalFailure());
      }
      // every pair of a random third of them (the bounds' own pairs always)
      for (std::size_t i = 0; i < xs.size(); ++i)
        for (std::size_t j = 0; j < ys.size(); ++j) {
          if (i >= 2 && j >= 3 && random() % 3 != 0) continue;
          check(vertex.chart, xs[i], ys[j]);
          ASSERT_FALSE(HasFatalFailure());
        }
    }
    for (int i = 0; i < 2000; ++i) {   // at random in a random chart
      std::size_t c = random() % space.charts().size();
      const CSpaceChart& chart = space.charts()[c];
      check(c, chart.x_lo + (chart.x_hi - chart.x_lo) * Rational(unit(random)),
            chart.y_lo + (chart.y_hi - chart.y_lo) * Rational(unit(random)));
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  std::printf("spaces %zu, points %zu (%zu on a vertex)\n", spaces, points, at_vertex);
  EXPECT_GE(spaces, 4u);
  EXPECT_GE(points, 20000u);
  EXPECT_GE(at_vertex, 20u);
}

}  // namespace
}  // namespace hipair
