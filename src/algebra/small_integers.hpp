// Exact integer arithmetic in __int128 for the small integers of tiny translating polygon pairs
// (docs/performance.md, session 58): an integer below 2^62 in magnitude is read from its GMP
// number without a call, and every product, sum and difference is checked for overflow
// (__builtin_*_overflow), so that a caller either gets the exact value of its whole expression
// or learns that it does not fit and takes its GMP path. No rounding anywhere: a result that is
// returned is the integer the GMP path computes.
#pragma once

#include <gmp.h>

namespace hipair::cspace::algebra::small_integers {

using Wide = __int128;
static_assert(GMP_LIMB_BITS == 64, "reads one 64-bit limb");

/// z as a Wide when |z| < 2^62 (true); false (out untouched) for a larger z.
inline bool read(mpz_srcptr z, Wide& out) {
  const int size = z->_mp_size;
  if (size == 0) {
    out = 0;
    return true;
  }
  if (size > 1 || size < -1 || z->_mp_d[0] >= (mp_limb_t{1} << 62)) return false;
  out = static_cast<Wide>(z->_mp_d[0]);
  if (size < 0) out = -out;
  return true;
}

/// Products, sums and differences that fit (true, the exact value in r); false on overflow.
inline bool mul(Wide a, Wide b, Wide& r) { return !__builtin_mul_overflow(a, b, &r); }
inline bool add(Wide a, Wide b, Wide& r) { return !__builtin_add_overflow(a, b, &r); }
inline bool sub(Wide a, Wide b, Wide& r) { return !__builtin_sub_overflow(a, b, &r); }

/// a b - c d, exactly, when it fits.
inline bool cross(Wide a, Wide b, Wide c, Wide d, Wide& r) {
  Wide ab, cd;
  return mul(a, b, ab) && mul(c, d, cd) && sub(ab, cd, r);
}

inline int sign(Wide v) { return v > 0 ? 1 : v < 0 ? -1 : 0; }

/// z = w exactly (any Wide: two limbs at most).
inline void write(mpz_ptr z, Wide w) {
  const bool negative = w < 0;
  const unsigned __int128 magnitude = negative ? -static_cast<unsigned __int128>(w) : static_cast<unsigned __int128>(w);
  const auto low = static_cast<mp_limb_t>(magnitude), high = static_cast<mp_limb_t>(magnitude >> 64);
  if (high == 0) {
    mpz_set_ui(z, low);
  } else {
    mp_limb_t* limbs = mpz_limbs_write(z, 2);
    limbs[0] = low;
    limbs[1] = high;
    mpz_limbs_finish(z, 2);
  }
  if (negative) mpz_neg(z, z);
}

}  // namespace hipair::cspace::algebra::small_integers
