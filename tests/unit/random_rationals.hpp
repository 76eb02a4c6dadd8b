// Generated integers and rationals for the tests of the machine-number fast cases
// (cspace_segment_stage_test.cpp, near_quotient_test.cpp).
#pragma once

#include <hipair/rational.hpp>

#include <random>

namespace hipair::test_numbers {

// A random integer of exactly `bits` bits (bits >= 1), with a random sign when `signed_`.
inline mpz_class random_integer(std::mt19937_64& random, int bits, bool signed_) {
  mpz_class z = 1;
  for (int b = 1; b < bits; ++b) z = 2 * z + static_cast<long>(random() & 1);
  if (signed_ && (random() & 1)) z = -z;
  return z;
}

// num / den in canonical form.
inline Rational canonical(const mpz_class& num, const mpz_class& den) {
  Rational q(num, den);
  q.canonicalize();
  return q;
}

}  // namespace hipair::test_numbers
