// HIPAIR — exact sums of dyadic rationals without a gcd, for the crossing query's subdivision
// (cspace_queries.cpp, CrossingRun and MotionScanner).
//
// The subdivision's stretch ends are the nodes u_begin + k (u_end - u_begin) / 2^bits of a binary
// tree; the simulator's paths run over [0, u_end] with u_end a double, so every end, every width
// and the resolution are dyadic (a denominator that is a power of two). GMP's mpq_add / mpq_sub /
// mpq_mul reduce their results by a gcd of the (multi-limb) denominators and numerators: most of
// the ≈ 1 000 instructions each of those operations cost there. For dyadic operands the sum is
// formed on the common denominator 2^max(ea, eb) by shifts and reduced by the numerator's trailing
// zero bits alone (the only common factor a power-of-two denominator can share): the same
// rational, in canonical form (numerator and denominator coprime, denominator positive), as GMP's.
// Any other operand goes through GMP unchanged. The value and its representation are GMP's, so
// no decision changes.
//
// Switch cspace::dyadic_sums() (on by default; CSpaceDyadicSums.* compares every result and the
// first_crossing answers with it off); counter cspace::dyadic_sum_count().
#pragma once

#include "core/thread_switch.hpp"
#include "kernels/interval.hpp"

#include <hipair/rational.hpp>

#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hipair::cspace {

struct DyadicSumsTag;
inline bool& dyadic_sums() { return thread_switch<DyadicSumsTag>(); }
// How many sums the shifts formed on this thread (tests).
struct DyadicSumCountTag;
inline std::size_t& dyadic_sum_count() { return thread_counter<DyadicSumCountTag>(); }

namespace dyadic_detail {
// the denominator's exponent when it is a power of two (a positive mpz with one bit set), else -1
inline long exponent(mpz_srcptr den) {
  if (mpz_sgn(den) <= 0 || mpz_popcount(den) != 1) return -1;
  return static_cast<long>(mpz_scan1(den, 0));
}
// out = na / 2^ea + sign nb / 2^eb, canonical; out's limbs reused. \pre out aliases neither numerator
inline void sum(mpq_ptr out, mpz_srcptr na, unsigned long ea, mpz_srcptr nb, unsigned long eb, int sign) {
  mpz_ptr n = mpq_numref(out);
  mpz_ptr d = mpq_denref(out);
  const unsigned long e = std::max(ea, eb);
  if (eb == e) {
    mpz_mul_2exp(n, na, e - ea);
    if (sign > 0) mpz_add(n, n, nb);
    else mpz_sub(n, n, nb);
  } else {   // ea == e > eb
    mpz_mul_2exp(n, nb, e - eb);
    if (sign > 0) mpz_add(n, na, n);
    else mpz_sub(n, na, n);
  }
  if (mpz_sgn(n) == 0) {
    mpz_set_ui(d, 1);
    return;
  }
  // the numerator's trailing zero bits (the same for -n: two's complement), at most e of them
  const unsigned long t = std::min<unsigned long>(mpz_scan1(n, 0), e);
  if (t > 0) mpz_tdiv_q_2exp(n, n, t);   // exact
  mpz_set_ui(d, 1);
  mpz_mul_2exp(d, d, e - t);
}
}  // namespace dyadic_detail

/// out = a + sign b (sign +1 or -1), canonical. \pre out is neither a nor b.
inline void sum_into(Rational& out, const Rational& a, const Rational& b, int sign) {
  if (dyadic_sums() && &out != &a && &out != &b) {
    const long ea = dyadic_detail::exponent(mpq_denref(a.get_mpq_t()));
    const long eb = ea < 0 ? -1 : dyadic_detail::exponent(mpq_denref(b.get_mpq_t()));
    if (eb >= 0) {
      dyadic_detail::sum(out.get_mpq_t(), mpq_numref(a.get_mpq_t()), static_cast<unsigned long>(ea),
                         mpq_numref(b.get_mpq_t()), static_cast<unsigned long>(eb), sign);
      ++dyadic_sum_count();
      return;
    }
  }
  if (sign > 0) out = a + b;
  else out = a - b;
  out.canonicalize();
}

/// out = a + r k, canonical. \pre out is neither a nor r.
inline void sum_multiple_into(Rational& out, const Rational& a, const Rational& r, long k) {
  if (dyadic_sums() && &out != &a && &out != &r) {
    const long ea = dyadic_detail::exponent(mpq_denref(a.get_mpq_t()));
    const long er = ea < 0 ? -1 : dyadic_detail::exponent(mpq_denref(r.get_mpq_t()));
    if (er >= 0) {
      thread_local mpz_class product;   // its limbs reused
      mpz_mul_si(product.get_mpz_t(), mpq_numref(r.get_mpq_t()), k);
      dyadic_detail::sum(out.get_mpq_t(), mpq_numref(a.get_mpq_t()), static_cast<unsigned long>(ea),
                         product.get_mpz_t(), static_cast<unsigned long>(er), 1);
      ++dyadic_sum_count();
      return;
    }
  }
  out = a + r * k;
  out.canonicalize();
}

/// out = (a + b) / 2, canonical. \pre out is neither a nor b.
inline void midpoint_into(Rational& out, const Rational& a, const Rational& b) {
  sum_into(out, a, b, 1);
  mpq_div_2exp(out.get_mpq_t(), out.get_mpq_t(), 1);   // canonical in, canonical out
}

}  // namespace hipair::cspace

namespace hipair::cspace {
// kernels::Interval::enclose(value) for a dyadic value without mpq_get_d's division: the
// numerator truncated to 53 bits by mpz_get_d_2exp (toward zero, as mpq_get_d), scaled by the
// denominator's power of two, which is exact while the result is a normal double (its exponent in
// [-1021, 1024]); then enclose's own rule ([v, up(v)] above 0, [down(v), v] below, [0, 0]). The
// same two doubles (CSpaceDyadicSums.* compares them); elsewhere enclose itself. Under the switch
// dyadic_sums(); counter: the enclosures made this way.
struct DyadicEnclosureCountTag;
inline std::size_t& dyadic_enclosure_count() { return thread_counter<DyadicEnclosureCountTag>(); }

inline kernels::Interval enclose_exact(const Rational& value) {
  if (dyadic_sums()) {
    const int sign = mpz_sgn(mpq_numref(value.get_mpq_t()));
    const long e = sign == 0 ? -1 : dyadic_detail::exponent(mpq_denref(value.get_mpq_t()));
    if (e >= 0) {
      long exponent = 0;
      const double d = mpz_get_d_2exp(&exponent, mpq_numref(value.get_mpq_t()));   // 0.5 <= |d| < 1
      const long scale = exponent - e;
      if (scale >= -1021 && scale <= 1024) {
        const double truncated = std::ldexp(d, static_cast<int>(scale));
        ++dyadic_enclosure_count();
        return sign > 0 ? kernels::Interval(truncated, kernels::interval_detail::up(truncated))
                        : kernels::Interval(kernels::interval_detail::down(truncated), truncated);
      }
    }
  }
  return kernels::Interval::enclose(value);
}
}  // namespace hipair::cspace

namespace hipair::cspace {
// The subdivision's skip tests (cspace_queries.cpp, CrossingRun::free_before / past_change)
// compare the product offset * r of a rational offset and a double rate with a double bound s.
// The product's certified double enclosure first (kernels::Interval::enclose(offset) times the
// point r, outward rounded: it holds the exact product), which decides whenever s lies outside
// it; else the exact product. The same sign as the exact comparison (CSpaceDyadicSums.* compares
// it with generated bounds at and around the product); counter: the signs the enclosure gave.
struct OffsetFilterTag;
inline bool& offset_filter() { return thread_switch<OffsetFilterTag>(); }
struct OffsetFilterCountTag;
inline std::size_t& offset_filter_count() { return thread_counter<OffsetFilterCountTag>(); }

/// The sign of offset * r - s, exactly. `scratch` holds the exact product (its limbs reused).
/// \pre r and s finite
inline int compare_product(const Rational& offset, double r, double s, Rational& scratch) {
  if (offset_filter()) {
    const kernels::Interval product = enclose_exact(offset) * kernels::Interval::point(r);
    if (product.hi < s) return ++offset_filter_count(), -1;
    if (product.lo > s) return ++offset_filter_count(), 1;
  }
  scratch = offset;
  scratch *= Rational(r);
  const int sign = cmp(scratch, Rational(s));
  return (sign > 0) - (sign < 0);
}
}  // namespace hipair::cspace
