// The content (gcd of the coefficients) of a univariate or bivariate integer polynomial, the
// smallest coefficient first.
#pragma once

#include <gmpxx.h>

#include <cstddef>
#include <limits>

namespace hipair::cspace::algebra {

/// The gcd of the integers for_each visits (each visit calls its argument with an mpz_srcptr),
/// >= 0, 0 when every one is zero. The smallest non-zero one in bits is taken first, so that
/// every gcd after it has one small operand (GMP reduces the larger modulo the smaller before
/// its Lehmer steps) and, once the gcd is 1, the rest is skipped. A gcd of a set does not
/// depend on the order its members are taken in: the value is the plain left-to-right one.
template <class ForEach>
mpz_class smallest_first_content(ForEach for_each) {
  mpz_srcptr smallest = nullptr;
  std::size_t smallest_bits = std::numeric_limits<std::size_t>::max();
  for_each([&](mpz_srcptr v) {
    if (mpz_sgn(v) == 0) return;
    const std::size_t bits = mpz_sizeinbase(v, 2);
    if (bits < smallest_bits) {
      smallest_bits = bits;
      smallest = v;
    }
  });
  mpz_class g;
  if (smallest == nullptr) return g;
  mpz_abs(g.get_mpz_t(), smallest);
  bool one = smallest_bits == 1;
  for_each([&](mpz_srcptr v) {
    if (one || v == smallest || mpz_sgn(v) == 0) return;
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v);
    one = mpz_cmp_ui(g.get_mpz_t(), 1) == 0;
  });
  return g;
}

}  // namespace hipair::cspace::algebra
