// Point location's filter (src/cspace/builder_locate.cpp, locate_2d; switch
// cspace::locate_filter() in src/cspace/angle_filter.hpp): an edge whose support is quadratic in
// y at the point's rational abscissa is placed above or below the point by a certified double
// enclosure of its root (quadratic_root_enclosure) or the exact sign of the quadratic at the
// point's ordinate (QuadraticOrdinate::compare), not by root isolation. Oracles: the exact
// algebraic numbers (nth_real_root, Real::compare) for the two pieces on generated quadratics,
// and point location with the filter off on the example spaces for the whole query.
#include "algebra/exact_real.hpp"
#include "cspace/angle_filter.hpp"
#include "cspace/builder_impl.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

using Switch = test::FlagSwitch<&cspace::locate_filter>;

Rational rational(long n, long d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

// a y^2 + b y + c = (k y - m)(l y - n) (rational roots m / k, n / l) or with a random integer
// perturbation of c (irrational roots), scaled by a power of two up to 2^400 (the enclosures'
// conversions and products far from 1).
TEST(CSpaceLocateFilter, QuadraticRootsAgreeWithTheExactAlgebraicNumbers) {
  std::mt19937_64 random(21);
  std::uniform_int_distribution<long> small(-2000, 2000), positive(1, 3000);
  std::size_t enclosed = 0, compared = 0, on_root = 0, cases = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    long k = positive(random), l = positive(random), m = small(random), n = small(random);
    if (random() % 2) k = -k;
    mpz_class a = mpz_class(k) * l, b = -(mpz_class(k) * n + mpz_class(l) * m), c = mpz_class(m) * n;
    bool perturbed = random() % 3 == 0;
    if (perturbed) c += small(random);
    mpz_class scale = mpz_class(1) << static_cast<unsigned>(random() % 400);
    a *= scale;
    b *= scale;
    c *= scale;
    if (sgn(b * b - 4 * a * c) <= 0) continue;
    ++cases;
    cspace::algebra::Polynomial p{c, b, a};
    for (int index = 0; index < 2; ++index) {
      cspace::algebra::Real root = cspace::algebra::nth_real_root(p, index);
      cspace::QuadraticOrdinate q;
      q.a = a;
      q.b = b;
      q.c = c;
      q.index = index;
      if (std::optional<cspace::algebra::Interval> y = cspace::quadratic_root_enclosure(a, b, c, index)) {
        ++enclosed;
        ASSERT_GE(root.compare(Rational(y->lo)), 0) << "trial " << trial << " index " << index;
        ASSERT_LE(root.compare(Rational(y->hi)), 0) << "trial " << trial << " index " << index;
        ASSERT_LE(y->lo, y->hi);
      }
      // values: both roots when rational, their doubles moved by -6..6 ulps, the midpoint,
      // random rationals near and far
      std::vector<Rational> values;
      if (!perturbed) {
        values.push_back(rational(m, k));
        values.push_back(rational(n, l));
      }
      for (int r = 0; r < 2; ++r) {
        double near = cspace::algebra::nth_real_root(p, r).approximate();
        for (int u = -6; u <= 6; ++u) {
          double v = near;
          for (int s = 0; s < std::abs(u); ++s) v = std::nextafter(v, u < 0 ? -INFINITY : INFINITY);
          values.push_back(Rational(v));
        }
      }
      Rational middle(mpz_class(-b), mpz_class(2 * a));
      middle.canonicalize();
      values.push_back(middle);
      values.push_back(rational(small(random), positive(random)));
      for (const Rational& v : values) {
        int exact = root.compare(v);
        ASSERT_EQ(q.compare(v), exact) << "trial " << trial << " index " << index << " v " << v;
        ++compared;
        on_root += exact == 0;
      }
    }
  }
  std::printf("cases %zu, enclosed roots %zu, compared values %zu (%zu on the root)\n", cases, enclosed, compared,
              on_root);
  EXPECT_GE(cases, 4000u);
  EXPECT_GE(enclosed, 2 * cases * 9 / 10);
  EXPECT_GE(on_root, 3000u);
}

std::string describe(const Location& l) {
  return std::to_string(static_cast<int>(l.kind)) + " cell " + std::to_string(static_cast<long>(l.cell)) + " edge " +
         std::to_string(static_cast<long>(l.edge)) + " vertex " + std::to_string(static_cast<long>(l.vertex)) +
         " chart " + std::to_string(static_cast<long>(l.chart));
}

std::string locate(const CSpace& space, const ChartPoint& p, bool filter) {
  Switch use(filter);
  try {
    return describe(space.locate(p));
  } catch (const Error& e) {
    return std::string("error: ") + e.what();
  }
}

// Points near and on the edges of the example spaces (the Geneva drive, the escapement's pairs;
// the cam's is 1-D): at a random abscissa inside a random edge's extent (also at doubles a few
// ulps inside its ends), the edge's ordinate rounded to a double and moved by -8..8 ulps, or by
// 10^-15..10^-3 of the chart up or down, or a random ordinate in the chart; also the rational
// vertices and the cells' sample points. Each location with the filter on equals the exact one.
TEST(CSpaceLocateFilter, PointsNearAndOnEdgesAreLocatedAsExactly) {
  std::vector<std::unique_ptr<CSpace>> owned = test::example_spaces();
  std::mt19937_64 random(2111);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t points = 0, on_contact = 0, spaces = 0;
  std::size_t filtered_before = cspace::locate_filter_edges();
  for (const auto& space_owner : owned) {
    const CSpace& space = *space_owner;
    if (space.dimension() != 2) continue;
    ++spaces;
    const auto& edges = space.edges();
    auto check = [&](const ChartPoint& p) {
      std::string with = locate(space, p, true);
      std::string without = locate(space, p, false);
      ASSERT_EQ(with, without) << "chart " << p.chart << " x " << p.x << " y " << p.y;
      ++points;
      on_contact += with.rfind("2 ", 0) == 0 || with.rfind("3 ", 0) == 0;
    };
    for (int i = 0; i < 9000; ++i) {
      const CSpaceEdge& edge = edges[random() % edges.size()];
      if (edge.vertical) continue;
      const CSpaceChart& chart = space.charts()[edge.chart];
      double x_lo = edge.x_chart.lower, x_hi = edge.x_chart.upper;
      double x = x_lo + (x_hi - x_lo) * unit(random);
      if (random() % 8 == 0) {   // a few ulps inside an end
        x = random() % 2 ? x_lo : x_hi;
        for (int s = 0, n = 1 + static_cast<int>(random() % 6); s < n; ++s)
          x = std::nextafter(x, x == x_lo ? INFINITY : -INFINITY);
      }
      std::size_t e = static_cast<std::size_t>(&edge - edges.data());
      double y;
      try {
        y = space.evaluate(e, x).value;
      } catch (const GeometryError&) {
        continue;   // outside the edge's exact extent
      }
      double height = Rational(chart.y_hi - chart.y_lo).get_d();
      switch (random() % 4) {
        case 0:
        case 1: {
          int ulps = static_cast<int>(random() % 17) - 8;
          for (int s = 0; s < std::abs(ulps); ++s) y = std::nextafter(y, ulps < 0 ? -INFINITY : INFINITY);
          break;
        }
        case 2:
          y += (random() % 2 ? 1 : -1) * height * std::pow(10.0, -15 + 12 * unit(random));
          break;
        default:
          y = chart.y_lo.get_d() + height * unit(random);
      }
      check(ChartPoint{edge.chart, Rational(x), Rational(y)});
      ASSERT_FALSE(HasFatalFailure());
    }
    // on contact space exactly: rational vertices, and the cells' samples (inside)
    for (std::size_t v = 0; v < space.vertices().size(); ++v) {
      const CSpaceVertex& vertex = space.vertices()[v];
      if (!vertex.x.exact || !vertex.y_exact || !vertex.y.exact) continue;
      check(ChartPoint{vertex.chart, vertex.x.lower, vertex.y.lower});
      ASSERT_FALSE(HasFatalFailure());
    }
    for (const CSpaceCell& cell : space.cells()) {
      check(ChartPoint{cell.sample_chart, cell.sample_x, cell.sample_y});
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  std::size_t filtered = cspace::locate_filter_edges() - filtered_before;
  std::printf("spaces %zu, points %zu (%zu on contact space), edges placed by the filter %zu\n", spaces, points,
              on_contact, filtered);
  EXPECT_GE(spaces, 4u);
  EXPECT_GE(points, 20000u);
  EXPECT_GE(filtered, 20000u);   // the filter is used
  EXPECT_GE(on_contact, 50u);
}

}  // namespace
}  // namespace hipair
