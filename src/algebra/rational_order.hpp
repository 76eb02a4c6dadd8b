// The order of two rationals with a machine-integer fast path (the isolating intervals' ends
// compared in the exact-real and axis code: mostly fractions of one limb each, where GMP's
// mpq_cmp takes ≈ 300 instructions for its cross products).
#pragma once

#include <hipair/rational.hpp>

#include <gmp.h>

namespace hipair::cspace::algebra {

/// The sign of a - b (-1, 0 or 1 when every numerator and denominator fits one limb; otherwise
/// mpq_cmp's value, whose sign is that of a - b). Rationals canonical or not (only the
/// denominators' positivity is used).
inline int compare_rationals(const Rational& a, const Rational& b) {
  const __mpq_struct* x = a.get_mpq_t();
  const __mpq_struct* y = b.get_mpq_t();
  const int xs = x->_mp_num._mp_size, ys = y->_mp_num._mp_size;
  if (xs >= -1 && xs <= 1 && ys >= -1 && ys <= 1 && x->_mp_den._mp_size == 1 && y->_mp_den._mp_size == 1) {
    if (xs != ys) return xs < ys ? -1 : 1;   // signs differ (sizes carry the sign: -1, 0, 1)
    if (xs == 0) return 0;
    // |a| against |b|: |num_a| den_b against |num_b| den_a, exact in 128 bits
    const unsigned __int128 left = static_cast<unsigned __int128>(x->_mp_num._mp_d[0]) * y->_mp_den._mp_d[0];
    const unsigned __int128 right = static_cast<unsigned __int128>(y->_mp_num._mp_d[0]) * x->_mp_den._mp_d[0];
    if (left == right) return 0;
    return (left < right) == (xs > 0) ? -1 : 1;
  }
  return mpq_cmp(x, y);
}

}  // namespace hipair::cspace::algebra
