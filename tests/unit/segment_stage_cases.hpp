// Generated cases of the segment stage's tests (cspace_segment_stage_test.cpp,
// translating_overlap_split_test.cpp): grid rationals, a random box on the grid, the
// instances' scales, lines as integer polynomials.
#pragma once

#include "random_rationals.hpp"

#include "algebra/exact_real.hpp"
#include "algebra/polynomial.hpp"
#include "arrangement/arrangement.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <random>

namespace hipair::test_segment_stage {

/// A non-dyadic grid value in [-range, range] (denominators 1, 3, 7, 2).
inline Rational grid_value(std::mt19937_64& random, long range) {
  static const long dens[] = {1, 3, 7, 2};
  const long den = dens[random() % 4];
  return test_numbers::canonical(static_cast<long>(random() % static_cast<unsigned long>(2 * range * den + 1)) - range * den, den);
}

/// Instance i's scale, in turn 2^-300, 2^-1, 1, 1, 2, 2^150, 2^198 (coefficients across the
/// segment filter's 2^400 limit).
inline Rational instance_scale(int instance) {
  static const int exponents[] = {-300, -1, 0, 0, 1, 150, 198};
  const int exponent = exponents[instance % 7];
  return exponent >= 0 ? test_numbers::canonical(mpz_class(1) << exponent, 1)
                       : test_numbers::canonical(1, mpz_class(1) << -exponent);
}

/// A random box on the grid (before scaling), wider and taller than 0.
struct GridBox {
  Rational x_lo, x_hi, y_lo, y_hi;
};
inline GridBox random_grid_box(std::mt19937_64& random) {
  GridBox b;
  b.x_lo = grid_value(random, 4);
  b.y_lo = grid_value(random, 4);
  b.x_hi = b.x_lo + 1 + grid_value(random, 3) * grid_value(random, 3);
  b.y_hi = b.y_lo + 1 + grid_value(random, 3) * grid_value(random, 3);
  if (b.x_hi <= b.x_lo) b.x_hi = b.x_lo + 2;
  if (b.y_hi <= b.y_lo) b.y_hi = b.y_lo + test_numbers::canonical(5, 3);
  return b;
}

/// k0 + kx x + ky y as an integer polynomial: the rationals times their denominators' lcm and
/// `factor`.
inline cspace::IntegerPolynomial2 integer_line(const Rational& k0, const Rational& kx, const Rational& ky, long factor) {
  mpz_class lcm = 1;
  for (const Rational* r : {&k0, &kx, &ky}) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), r->get_den_mpz_t());
  auto z = [&](const Rational& r) { return mpz_class(r.get_num() * (lcm / r.get_den()) * factor); };
  cspace::IntegerPolynomial2 f;
  f.coefficients = {{z(k0), z(ky)}, {z(kx), mpz_class(0)}};
  return f;
}

/// Two exports of one arrangement are the same, field by field: vertices (exact x and y,
/// isolated, faces below and above, incidences), edges (ends, vertical, box side, faces,
/// certified boxes, arc numbers, supports), faces (boundaries, components, isolated vertices).
/// Not `support_curve` (only the stage with carried supports sets it). Gtest failures.
inline void expect_same_arrangement(const cspace::raw::Arrangement& p, const cspace::raw::Arrangement& q) {
  ASSERT_EQ(p.vertices.size(), q.vertices.size());
  for (std::size_t v = 0; v < p.vertices.size(); ++v) {
    const cspace::raw::Vertex &a = p.vertices[v], &b = q.vertices[v];
    ASSERT_EQ(cspace::algebra::compare(a.x, b.x), 0) << "vertex " << v;
    ASSERT_EQ(cspace::algebra::compare(a.y, b.y), 0) << "vertex " << v;
    EXPECT_EQ(a.isolated, b.isolated) << "vertex " << v;
    EXPECT_EQ(a.face_below, b.face_below) << "vertex " << v;
    EXPECT_EQ(a.face_above, b.face_above) << "vertex " << v;
    ASSERT_EQ(a.around.size(), b.around.size()) << "vertex " << v;
    for (std::size_t i = 0; i < a.around.size(); ++i) {
      EXPECT_EQ(a.around[i].edge, b.around[i].edge) << "vertex " << v;
      EXPECT_EQ(a.around[i].direction, b.around[i].direction) << "vertex " << v;
      EXPECT_EQ(a.around[i].wedge_face, b.around[i].wedge_face) << "vertex " << v;
    }
  }
  ASSERT_EQ(p.edges.size(), q.edges.size());
  for (std::size_t e = 0; e < p.edges.size(); ++e) {
    const cspace::raw::Edge &a = p.edges[e], &b = q.edges[e];
    EXPECT_EQ(a.min_vertex, b.min_vertex) << "edge " << e;
    EXPECT_EQ(a.max_vertex, b.max_vertex) << "edge " << e;
    EXPECT_EQ(a.vertical, b.vertical) << "edge " << e;
    EXPECT_EQ(a.box_side, b.box_side) << "edge " << e;
    EXPECT_EQ(a.left_face, b.left_face) << "edge " << e;
    EXPECT_EQ(a.right_face, b.right_face) << "edge " << e;
    for (int i = 0; i < 4; ++i) EXPECT_EQ(a.box[i], b.box[i]) << "edge " << e;
    EXPECT_EQ(a.arc_numbers.between, b.arc_numbers.between) << "edge " << e;
    ASSERT_FALSE(a.support.coefficients.empty()) << "edge " << e;
    EXPECT_EQ(a.support.coefficients, b.support.coefficients) << "the support of edge " << e;
  }
  ASSERT_EQ(p.faces.size(), q.faces.size());
  EXPECT_EQ(p.unbounded_face, q.unbounded_face);
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    EXPECT_EQ(p.faces[f].unbounded, q.faces[f].unbounded) << "face " << f;
    EXPECT_EQ(p.faces[f].boundary, q.faces[f].boundary) << "face " << f;
    EXPECT_EQ(p.faces[f].component_starts, q.faces[f].component_starts) << "face " << f;
    EXPECT_EQ(p.faces[f].isolated_vertices, q.faces[f].isolated_vertices) << "face " << f;
  }
}

}  // namespace hipair::test_segment_stage
