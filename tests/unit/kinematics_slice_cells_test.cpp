// The kernel slicer's binary searches (kinematics/slice_cells.hpp) against the linear scans they
// replace: the follower cells holding a value (two on an inner edge), the cells a window meets,
// and the first point of a slice at or above a rational (nullopt on a point), on generated edges
// (the slicer's 32 equal cells of random rational charts, and arbitrary ascending edges) and
// values on the edges, between them, outside, and a last bit beside them.
#include "kinematics/slice_cells.hpp"

#include "algebra/exact_real.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

using cspace::algebra::Real;

// The scans as kernel_slice.cpp wrote them (cells [edges[c], edges[c + 1]], closed).
std::uint32_t scan_holding(const std::vector<Rational>& edges, const Rational& s) {
  std::uint32_t bits = 0;
  for (std::size_t cell = 0; cell + 1 < edges.size(); ++cell)
    if (edges[cell] <= s && s <= edges[cell + 1]) bits |= std::uint32_t(1) << cell;
  return bits;
}

std::uint32_t scan_meeting(const std::vector<Rational>& edges, const Rational& lo, const Rational& hi) {
  std::uint32_t bits = 0;
  for (std::size_t cell = 0; cell + 1 < edges.size(); ++cell)
    if (edges[cell + 1] >= lo && edges[cell] <= hi) bits |= std::uint32_t(1) << cell;
  return bits;
}

Rational random_rational(std::mt19937_64& random) {
  Rational r(mpz_class(static_cast<long>(random() % 2000001) - 1000000), mpz_class(1 + random() % 100000));
  r.canonicalize();
  return r;
}

std::vector<std::vector<Rational>> generated_edges(std::mt19937_64& random) {
  std::vector<std::vector<Rational>> all;
  for (int n = 0; n < 300; ++n) {
    std::vector<Rational> edges;
    if (n % 2 == 0) {
      // the slicer's: lo + (hi - lo) cell / 32
      Rational lo = random_rational(random), hi = random_rational(random);
      if (hi == lo) hi += 1;
      if (hi < lo) std::swap(lo, hi);
      for (int cell = 0; cell <= 32; ++cell) edges.push_back(lo + (hi - lo) * cell / 32);
    } else {
      const std::size_t count = 2 + random() % 32;   // 1..32 cells
      while (edges.size() < count) edges.push_back(random_rational(random));
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      if (edges.size() < 2) edges.push_back(edges.back() + 1);
    }
    all.push_back(std::move(edges));
  }
  return all;
}

std::vector<Rational> probes(const std::vector<Rational>& edges, std::mt19937_64& random) {
  const Rational tiny(mpz_class(1), mpz_class(1) << 200);
  std::vector<Rational> values;
  for (const Rational& e : edges) {
    values.push_back(e);
    values.push_back(e + tiny);
    values.push_back(e - tiny);
  }
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) values.push_back((edges[i] + edges[i + 1]) / 2);
  values.push_back(edges.front() - 1);
  values.push_back(edges.back() + 1);
  for (int k = 0; k < 20; ++k) values.push_back(random_rational(random));
  return values;
}

TEST(KinematicsSliceCells, CellsHoldingAValueAreTheLinearScans) {
  std::mt19937_64 random(5);
  std::size_t on_edges = 0;
  for (const std::vector<Rational>& edges : generated_edges(random))
    for (const Rational& s : probes(edges, random)) {
      const std::uint32_t want = scan_holding(edges, s);
      ASSERT_EQ(slice_cells::cells_holding(edges, s), want) << s.get_str();
      if (want != 0 && (want & (want - 1)) != 0) ++on_edges;   // two cells: an inner edge
    }
  EXPECT_GT(on_edges, 3000u);
}

TEST(KinematicsSliceCells, CellsMeetingAWindowAreTheLinearScans) {
  std::mt19937_64 random(6);
  for (const std::vector<Rational>& edges : generated_edges(random)) {
    std::vector<Rational> values = probes(edges, random);
    for (int k = 0; k < 200; ++k) {
      Rational lo = values[random() % values.size()], hi = values[random() % values.size()];
      if (hi < lo) std::swap(lo, hi);
      ASSERT_EQ(slice_cells::cells_meeting(edges, lo, hi), scan_meeting(edges, lo, hi)) << lo.get_str() << " " << hi.get_str();
      ASSERT_EQ(slice_cells::cells_meeting(edges, lo, lo), scan_meeting(edges, lo, lo)) << lo.get_str();
    }
  }
}

struct Point {
  Real value;
};

TEST(KinematicsSliceCells, FirstPointNotBelowIsTheLinearScan) {
  std::mt19937_64 random(8);
  std::size_t equal = 0, irrational = 0;
  for (int n = 0; n < 400; ++n) {
    // ascending distinct points: rationals and square roots of generated rationals
    std::vector<Point> points;
    std::vector<Rational> values;
    const std::size_t count = random() % 12;
    for (std::size_t i = 0; i < count; ++i) {
      const Rational r = random_rational(random);
      if (random() % 2) {
        points.push_back({Real::from_rational(r)});
        values.push_back(r);
      } else {
        Rational q = abs(r) + Rational(1, 3);   // sqrt(q) irrational or not: both are exact numbers
        q.canonicalize();
        std::vector<Real> roots = cspace::algebra::real_roots({-q.get_num(), mpz_class(0), q.get_den()});
        points.push_back({roots.back()});
        ++irrational;
        values.push_back(q);   // a probe near it (q is not sqrt(q) unless 1)
      }
    }
    std::sort(points.begin(), points.end(),
              [](const Point& a, const Point& b) { return cspace::algebra::compare(a.value, b.value) < 0; });
    points.erase(std::unique(points.begin(), points.end(),
                             [](const Point& a, const Point& b) { return cspace::algebra::compare(a.value, b.value) == 0; }),
                 points.end());
    for (int k = 0; k < 20; ++k) values.push_back(random_rational(random));
    for (const Point& p : points) {
      values.push_back(p.value.lower);
      values.push_back(p.value.upper);
    }
    for (const Rational& bound : values) {
      // the scan: nullopt when a point equals the bound, else the first point above it
      std::optional<std::size_t> want = points.size();
      for (std::size_t i = 0; i < points.size(); ++i) {
        const int c = points[i].value.compare(bound);
        if (c == 0) {
          want = std::nullopt;
          break;
        }
        if (c > 0) {
          want = i;
          break;
        }
      }
      if (!want) ++equal;
      ASSERT_EQ(slice_cells::first_point_not_below(points, bound), want) << bound.get_str();
    }
  }
  EXPECT_GT(equal, 1000u);
  EXPECT_GT(irrational, 500u);
}

}  // namespace
}  // namespace hipair::kinematics_detail
