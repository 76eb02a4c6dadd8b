// Test helper: spaces of two translating random star polygons (test_loops::grid_star), as the
// vertex-number tests generate them (cspace_vertex_numbers_test.cpp,
// cspace_vertex_number_lazy_test.cpp).
#pragma once

#include "polygon_loop_json.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <optional>
#include <random>

namespace hipair::test_loops {

/// The model of a translating along x and b along y.
inline Model slider_pair_model(const Points& a, const Points& b) { return read_model(sliders_json(a, b)); }

/// The space of a and b sliding, or nothing when the reader refused a polygon (rounding to the
/// grid made it degenerate: a repeated vertex, a self-touching boundary): not a test case.
inline std::optional<CSpace> star_slider_space(const Points& a, const Points& b) {
  try {
    return CSpace::build(slider_pair_model(a, b), "a", "b");
  } catch (const ModelError&) {
    return std::nullopt;
  }
}

/// The pair the threads tests read: a star of 7 vertices, radius 4 about the origin, and one of
/// 9, radius 5 about (1, -1), both on the 1/16 grid and drawn from `random` in that order; its
/// space, or nothing as star_slider_space.
inline std::optional<CSpace> random_star_slider_space(std::mt19937_64& random) {
  Points a = grid_star(random, 7, 0, 0, 4, 16, 1);
  Points b = grid_star(random, 9, 1, -1, 5, 16, 1);
  return star_slider_space(a, b);
}

/// Generated pair `instance` of the vertex-number tests: stars of 3..10 vertices (a about the
/// origin, radius 3..6; b about a random grid point in [-3, 3]^2, radius 2..6) on the grid 1,
/// 1/16 or 1/97 (by instance mod 3), times 2^-100 (instance mod 5 == 3), 2^100 (mod 5 == 4) or 1;
/// b is a itself when `equal`.
struct StarPair {
  Points a, b;
};

inline StarPair generated_star_pair(std::mt19937_64& random, int instance, bool equal) {
  const Rational tiny = Rational(1) / (mpz_class(1) << 100), huge = Rational(mpz_class(1) << 100);
  int ka = 3 + static_cast<int>(random() % 8), kb = 3 + static_cast<int>(random() % 8);
  long q = instance % 3 == 0 ? 1 : instance % 3 == 1 ? 16 : 97;
  Rational scale = instance % 5 == 3 ? tiny : instance % 5 == 4 ? huge : Rational(1);
  StarPair pair;
  pair.a = grid_star(random, ka, 0, 0, 3 + static_cast<double>(random() % 4), q, scale);
  if (equal) {
    pair.b = pair.a;
    return pair;
  }
  // drawn radius first, then y, then x: the order GCC evaluated the arguments of the tests'
  // former single call in, so the instances are the ones tested before
  const double radius = 2 + static_cast<double>(random() % 5);
  const double cy = static_cast<double>(random() % 7) - 3;
  const double cx = static_cast<double>(random() % 7) - 3;
  pair.b = grid_star(random, kb, cx, cy, radius, q, scale);
  return pair;
}

}  // namespace hipair::test_loops
