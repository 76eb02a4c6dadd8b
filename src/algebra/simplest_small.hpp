// simplest_between's descent in machine integers, for ends whose numerators and denominators
// are below 2^62 in magnitude (every sample between the small translating pairs' vertices;
// docs/performance.md, session 32). The same steps as the GMP descent in exact_real.cpp, on
// __int128 so that no product can overflow: the ends stay below 2^62 through the descent (each
// step's four integers are earlier ones or remainders smaller than them), a quotient times an
// end is below 2^124, and the answer lies in the Stern–Brocot tree above the mediant of the ends
// (its numerator at most |a| + |c|, its denominator at most b + d: below 2^63), so each
// composed numerator and denominator fits a long. tests/unit/near_quotient_test.cpp compares it
// with the GMP descent on generated intervals.
#pragma once

#include <hipair/rational.hpp>

#include <gmp.h>

#include <cstdint>

namespace hipair::cspace::algebra {

namespace simplest_small_detail {
using Wide = __int128;
inline constexpr mp_limb_t limit = mp_limb_t{1} << 62;
static_assert(GMP_LIMB_BITS == 64, "reads one 64-bit limb");

// z as a Wide when |z| < 2^62
inline bool small(mpz_srcptr z, Wide& out) {
  const int size = z->_mp_size;
  if (size == 0) {
    out = 0;
    return true;
  }
  if (size > 1 || size < -1 || z->_mp_d[0] >= limit) return false;
  out = static_cast<Wide>(z->_mp_d[0]);
  if (size < 0) out = -out;
  return true;
}

// floor(a / b) and a - floor(a / b) b, b > 0
inline void floor_divide(Wide a, Wide b, Wide& f, Wide& r) {
  f = a / b;
  r = a - f * b;
  if (r < 0) {
    f -= 1;
    r += b;
  }
}
}  // namespace simplest_small_detail

/// simplest_between(lo, hi) (exact_real.hpp) when lo < hi and every numerator and denominator
/// is below 2^62 in magnitude: true and the answer in `out` (canonical, as the GMP descent
/// writes it); false and `out` untouched otherwise.
inline bool simplest_between_small(const Rational& lo, const Rational& hi, Rational& out) {
  using namespace simplest_small_detail;
  Wide a, b, c, d;
  if (!small(lo.get_num_mpz_t(), a) || !small(lo.get_den_mpz_t(), b) || !small(hi.get_num_mpz_t(), c) ||
      !small(hi.get_den_mpz_t(), d) || b <= 0 || d <= 0)
    return false;
  Wide quotients[160];   // a descent on integers below 2^62 takes fewer than 92 steps (Fibonacci)
  int count = 0;
  Wide last = 0, f = 0, r = 0;
  for (bool top = true;; top = false) {
    floor_divide(a, b, f, r);   // a = f b + r, 0 <= r < b
    if ((f + 1) * d < c) {      // f + 1 < c / d
      if (top) {
        // an integer lies inside; the one of smallest magnitude
        if (a < 0 && c > 0) {
          mpq_set_ui(out.get_mpq_t(), 0, 1);
          return true;
        }
        if (c <= 0) {
          Wide ceil_hi, rest;
          floor_divide(c, d, ceil_hi, rest);
          if (rest != 0) ceil_hi += 1;
          ceil_hi -= 1;
          if (ceil_hi * b > a) {   // ceil(c / d) - 1 > lo
            mpq_set_si(out.get_mpq_t(), static_cast<long>(ceil_hi), 1);
            return true;
          }
        }
        mpq_set_si(out.get_mpq_t(), static_cast<long>(f + 1), 1);
        return true;
      }
      last = f + 1;
      break;
    }
    if (count == 160) return false;   // not reached (see above); the GMP descent then
    quotients[count++] = f;
    c -= f * d;   // in (0, d]
    if (r == 0) {
      last = d / c + 1;   // floor, both positive
      break;
    }
    // next interval: (d / (c - f d), b / r)
    const Wide next_a = d, next_b = c, next_c = b, next_d = r;
    a = next_a;
    b = next_b;
    c = next_c;
    d = next_d;
  }
  Wide n = last, m = 1;   // the value n / m, n > 0
  for (int i = count - 1; i >= 0; --i) {
    const Wide next = quotients[i] * n + m;   // q + m / n = (q n + m) / n
    m = n;
    n = next;
  }
  const Wide long_limit = Wide{1} << 63;
  if (n >= long_limit || n < -long_limit || m >= long_limit) return false;   // not reached (see above)
  mpq_set_si(out.get_mpq_t(), static_cast<long>(n), static_cast<unsigned long>(m));
  return true;
}

}  // namespace hipair::cspace::algebra
