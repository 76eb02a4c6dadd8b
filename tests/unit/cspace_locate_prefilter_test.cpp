// Point location's vertex prefilter (src/cspace/builder_locate.cpp, locate_2d; switch
// cspace::locate_exact_prefilter() in src/cspace/locate_prefilter.hpp): a vertex is passed over by
// exact comparisons of its rational bounds with the point, not by their double conversions. The
// oracle: the same location with the double prefilter (the switch off), on points placed where
// the prefilter decides: exactly on the vertices' rational bounds (x's isolating interval's
// ends, y_lower, y_upper), on the rational vertices themselves, a few ulps around the vertices,
// and at random in their charts.
#include "algebra/exact_real.hpp"
#include "cspace/locate_prefilter.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string describe(const Location& l) {
  return std::to_string(static_cast<int>(l.kind)) + " cell " + std::to_string(static_cast<long>(l.cell)) + " edge " +
         std::to_string(static_cast<long>(l.edge)) + " vertex " + std::to_string(static_cast<long>(l.vertex)) +
         " chart " + std::to_string(static_cast<long>(l.chart));
}

template <bool& (*Flag)()>
std::string locate(const CSpace& space, const ChartPoint& p, bool on) {
  test::FlagSwitch<Flag> use(on);
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

// The points of both tests, per 2-D example space: each vertex's rational bounds (x's isolating
// interval's ends, y_lower, y_upper), the rational vertex itself, a few ulps around it, and for
// the vertex bounds also their certified doubles (x_lo, x_hi, y_hi, where that filter decides)
// and a few ulps around those; the chart's sides (its seams with the neighbouring charts); and
// points at random in the charts. `check(chart, x, y)` compares the two locations.
using Check = std::function<void(std::size_t, const Rational&, const Rational&)>;
void for_each_point(const CSpace& space, std::mt19937_64& random, bool with_bounds, const Check& check) {
  std::uniform_real_distribution<double> unit(0, 1);
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
    if (with_bounds) {
      // the certified doubles ChartData::vertex_bounds holds, and an ulp either side
      for (double b : {cspace::algebra::lower_double(vertex.x.lower), cspace::algebra::upper_double(vertex.x.upper)})
        for (int k = -1; k <= 1; ++k) xs.push_back(Rational(ulps(b, k)));
      for (int k = -1; k <= 1; ++k) ys.push_back(Rational(ulps(cspace::algebra::upper_double(vertex.y_upper), k)));
    }
    if (vertex.x.exact && vertex.y_exact && vertex.y.exact) check(vertex.chart, vertex.x.lower, vertex.y.lower);   // the vertex itself
    // every pair of a random third of them (the bounds' own pairs always)
    for (std::size_t i = 0; i < xs.size(); ++i)
      for (std::size_t j = 0; j < ys.size(); ++j) {
        if (i >= 2 && j >= 3 && random() % 3 != 0) continue;
        check(vertex.chart, xs[i], ys[j]);
      }
  }
  if (with_bounds)
    for (std::size_t c = 0; c < space.charts().size(); ++c) {   // on the chart's sides (its seams)
      const CSpaceChart& chart = space.charts()[c];
      for (int i = 0; i < 100; ++i) {
        Rational along_x = chart.x_lo + (chart.x_hi - chart.x_lo) * Rational(unit(random));
        Rational along_y = chart.y_lo + (chart.y_hi - chart.y_lo) * Rational(unit(random));
        check(c, i % 2 ? chart.x_lo : chart.x_hi, along_y);
        check(c, along_x, i % 2 ? chart.y_lo : chart.y_hi);
      }
    }
  for (int i = 0; i < 2000; ++i) {   // at random in a random chart
    std::size_t c = random() % space.charts().size();
    const CSpaceChart& chart = space.charts()[c];
    check(c, chart.x_lo + (chart.x_hi - chart.x_lo) * Rational(unit(random)),
          chart.y_lo + (chart.y_hi - chart.y_lo) * Rational(unit(random)));
  }
}

struct Counts {
  std::size_t points = 0, at_vertex = 0, spaces = 0;
};

// Every point of for_each_point located twice, with `flag` on and off; every answer equal.
template <bool& (*Flag)()>
Counts compare_locations(std::uint64_t seed, bool with_bounds) {
  std::vector<std::unique_ptr<CSpace>> owned = test::example_spaces();
  std::mt19937_64 random(seed);
  Counts counts;
  for (const auto& space_owner : owned) {
    const CSpace& space = *space_owner;
    if (space.dimension() != 2) continue;
    ++counts.spaces;
    bool failed = false;
    for_each_point(space, random, with_bounds, [&](std::size_t chart, const Rational& x, const Rational& y) {
      if (failed) return;
      ChartPoint p{chart, x, y};
      std::string with = locate<Flag>(space, p, true);
      std::string without = locate<Flag>(space, p, false);
      EXPECT_EQ(with, without) << "chart " << chart << " x " << x << " y " << y;
      failed = with != without;
      ++counts.points;
      counts.at_vertex += with.rfind("3 ", 0) == 0;
    });
    if (failed) break;
  }
  std::printf("spaces %zu, points %zu (%zu on a vertex)\n", counts.spaces, counts.points, counts.at_vertex);
  return counts;
}

TEST(CSpaceLocateFilterVertices, LocationsEqualTheDoublePrefilters) {
  Counts counts = compare_locations<&cspace::locate_exact_prefilter>(2222, false);
  EXPECT_GE(counts.spaces, 4u);
  EXPECT_GE(counts.points, 20000u);
  EXPECT_GE(counts.at_vertex, 20u);
}

// The vertex bounds (ChartData::vertex_bounds, switch cspace::locate_vertex_bounds()): the same
// locations as the exact comparisons alone, on the points above plus the bounds' own doubles
// and the charts' sides.
TEST(CSpaceLocateVertexBounds, LocationsEqualTheExactComparisons) {
  Counts counts = compare_locations<&cspace::locate_vertex_bounds>(2424, true);
  EXPECT_GE(counts.spaces, 4u);
  EXPECT_GE(counts.points, 30000u);
  EXPECT_GE(counts.at_vertex, 20u);
}

}  // namespace
}  // namespace hipair
