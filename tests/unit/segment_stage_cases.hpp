// Generated cases of the segment stage's tests (cspace_segment_stage_test.cpp,
// translating_overlap_split_test.cpp): grid rationals, a random box on the grid, the
// instances' scales, lines as integer polynomials.
#pragma once

#include "random_rationals.hpp"

#include "algebra/polynomial.hpp"

#include <hipair/rational.hpp>

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

}  // namespace hipair::test_segment_stage
