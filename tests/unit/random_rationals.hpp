// Generated integers and rationals for the tests of the machine-number fast cases
// (cspace_segment_stage_test.cpp, near_quotient_test.cpp) and random rationals in a range
// (cspace_irrational_fit_test.cpp), powers of ten.
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

// A random rational in [lo, hi] with a denominator up to `den` (not a decimal in general).
inline Rational random_rational(std::mt19937_64& random, const Rational& lo, const Rational& hi, long den = 97) {
  long q = 1 + static_cast<long>(random() % static_cast<unsigned long>(den));
  long p = static_cast<long>(random() % static_cast<unsigned long>(q + 1));
  Rational value = lo + canonical(p, q) * (hi - lo);
  value.canonicalize();
  return value;
}

// 10^e exactly (e of either sign; canonical).
inline Rational power_of_ten(long e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
  return e < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

}  // namespace hipair::test_numbers
