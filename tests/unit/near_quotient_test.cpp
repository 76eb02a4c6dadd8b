// The machine-number fast cases of session 32 (docs/performance.md) against the GMP paths they
// stand for, on generated inputs:
//  - enclose_rational (src/algebra/near_quotient.hpp): the doubles around a rational of 53-bit
//    numerator and denominator by one division and an fma, against mpq_get_d's truncation and
//    an exact comparison of the rational with it, under every rounding mode; enclose_kernel
//    against kernels::Interval::enclose; lower_double and upper_double through it;
//  - simplest_between_small (src/algebra/simplest_small.hpp) against the GMP descent.
#include "algebra/exact_real.hpp"
#include "algebra/near_quotient.hpp"
#include "algebra/simplest_small.hpp"
#include "kernels/interval.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cfenv>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace hipair {
namespace {

using cspace::algebra::enclose_kernel;
using cspace::algebra::enclose_rational;

using test_numbers::canonical;
using test_numbers::random_integer;

// The integers the fast case's limits turn on, and around them.
std::vector<mpz_class> boundary_integers() {
  std::vector<mpz_class> out{1, 2, 3, 5, 7, 10, 1000};
  for (int e : {26, 52, 53, 54, 62, 63, 64})
    for (long delta : {-2L, -1L, 0L, 1L, 2L}) out.push_back((mpz_class(1) << e) + delta);
  return out;
}

// >= 100,000 rationals: random numerators and denominators of 1 ... 70 bits (most within 53,
// many exactly at 53 and 54), exact doubles (integers over powers of two), the boundary
// integers over one another, quotients close to halfway between two doubles (1 + (2k + 1)
// 2^-53 and neighbours, 54 significant bits), subnormal and overflowing magnitudes, negatives.
std::vector<Rational> generated_rationals(std::mt19937_64& random) {
  std::vector<Rational> values{Rational(0)};
  for (int i = 0; i < 80000; ++i) {
    const int num_bits = 1 + static_cast<int>(random() % 70), den_bits = 1 + static_cast<int>(random() % 70);
    mpz_class den = random_integer(random, i % 4 == 0 ? 53 : den_bits, false);
    if (den == 0) den = 1;
    values.push_back(canonical(random_integer(random, i % 5 == 0 ? 53 : num_bits, true), den));
  }
  for (int i = 0; i < 5000; ++i) {   // exact doubles
    mpz_class den = mpz_class(1) << static_cast<unsigned>(random() % 60);
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 53), true), den));
  }
  const std::vector<mpz_class> edges = boundary_integers();
  for (const mpz_class& n : edges)
    for (const mpz_class& d : edges) {
      values.push_back(canonical(n, d));
      values.push_back(canonical(-n, d));
    }
  for (int i = 0; i < 5000; ++i) {   // halfway between two doubles, and one unit of 2^-60 off it
    mpz_class odd = 2 * random_integer(random, 52, false) + 1;
    mpz_class half = (mpz_class(1) << 53) + odd;   // (2^53 + odd) / 2^53 is halfway in [1, 2)
    const unsigned shift = 53 + static_cast<unsigned>(random() % 20);
    values.push_back(canonical(half, mpz_class(1) << 53));
    values.push_back(canonical(-(half << 7) + 1, mpz_class(1) << 60));
    values.push_back(canonical((half << 7) - 1, mpz_class(1) << shift));
  }
  for (int i = 0; i < 3000; ++i) {   // tiny (subnormal and below) and huge (beyond the doubles)
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 53), true),
                              mpz_class(1) << static_cast<unsigned>(1000 + random() % 100)));
    values.push_back(canonical(random_integer(random, 1000 + static_cast<int>(random() % 100), true),
                              random_integer(random, 1 + static_cast<int>(random() % 53), false) + 1));
  }
  for (int i = 0; i < 10000; ++i)   // small numerators over 53-bit denominators and back: |q| near 2^+-53
    values.push_back(i % 2 ? canonical(random_integer(random, 3, true) + 7, random_integer(random, 53, false) + 1)
                           : canonical(random_integer(random, 53, true), random_integer(random, 3, false) + 1));
  return values;
}

bool fits_53(const mpz_class& z) { return z == 0 || mpz_sizeinbase(z.get_mpz_t(), 2) <= 53; }

// The oracle: mpq_get_d truncates toward zero; an exact comparison with the truncation says
// whether the rational is that double, else it lies strictly between it and the next one away
// from zero.
struct Around {
  double lower, upper;
};
Around around(const Rational& q) {
  const double t = q.get_d();
  if (Rational(t) == q) return {t, t};
  constexpr double inf = std::numeric_limits<double>::infinity();
  return sgn(q) > 0 ? Around{t, std::nextafter(t, inf)} : Around{std::nextafter(t, -inf), t};
}

TEST(NearQuotient, EncloseRationalIsTheExactNeighbourPairOnGeneratedRationals) {
  std::mt19937_64 random(32);
  const std::vector<Rational> values = generated_rationals(random);
  ASSERT_GE(values.size(), 100000u);
  std::size_t fast_exact = 0, fast_between = 0, slow = 0;
  for (const int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    for (const Rational& q : values) {
      double lower = -1, upper = -1;
      const bool fast = enclose_rational(q, lower, upper);
      const bool small = fits_53(q.get_num()) && fits_53(q.get_den());
      std::fesetround(FE_TONEAREST);   // the oracle and the messages in the default mode
      ASSERT_EQ(fast, small) << q.get_str();
      if (fast) {
        // lower <= q <= upper exactly, adjacent or equal, and the oracle's pair bit for bit
        ASSERT_LE(Rational(lower), q) << q.get_str();
        ASSERT_GE(Rational(upper), q) << q.get_str();
        ASSERT_TRUE(lower == upper || std::nextafter(lower, upper) == upper) << q.get_str();
        const Around want = around(q);
        ASSERT_EQ(std::signbit(lower), std::signbit(want.lower)) << q.get_str();
        ASSERT_EQ(lower, want.lower) << q.get_str() << " mode " << mode;
        ASSERT_EQ(upper, want.upper) << q.get_str() << " mode " << mode;
        if (mode == FE_TONEAREST) (lower == upper ? fast_exact : fast_between) += 1;
      } else if (mode == FE_TONEAREST) {
        ++slow;
      }
      // the lower_double / upper_double and kernels' enclosures taken through it
      const auto kernel = enclose_kernel(q), reference = kernels::Interval::enclose(q);
      ASSERT_EQ(kernel.lo, reference.lo) << q.get_str();
      ASSERT_EQ(kernel.hi, reference.hi) << q.get_str();
      ASSERT_EQ(std::signbit(kernel.lo), std::signbit(reference.lo)) << q.get_str();
      if (std::isfinite(q.get_d())) {
        const Around want = around(q);
        ASSERT_EQ(cspace::algebra::lower_double(q), want.lower) << q.get_str();
        ASSERT_EQ(cspace::algebra::upper_double(q), want.upper) << q.get_str();
      }
      std::fesetround(mode);
    }
  }
  std::fesetround(FE_TONEAREST);
  EXPECT_GE(fast_exact, 9000u);
  EXPECT_GE(fast_between, 50000u);
  EXPECT_GE(slow, 20000u);
}

TEST(NearQuotient, EncloseRationalDeclinesWhatDoesNotFit53Bits) {
  // the limits exactly: 2^53 - 1 fits, 2^53 does not, in the numerator (either sign) and the
  // denominator; a non-canonical zero denominator or a negative one is declined
  const mpz_class fits = (mpz_class(1) << 53) - 1, over = mpz_class(1) << 53;
  double lower = 0, upper = 0;
  EXPECT_TRUE(enclose_rational(canonical(fits, 3), lower, upper));
  EXPECT_TRUE(enclose_rational(canonical(-fits, 3), lower, upper));
  EXPECT_TRUE(enclose_rational(canonical(1, fits), lower, upper));
  EXPECT_FALSE(enclose_rational(canonical(over + 2, 3), lower, upper));
  EXPECT_FALSE(enclose_rational(canonical(-over - 2, 3), lower, upper));
  EXPECT_FALSE(enclose_rational(canonical(1, over + 1), lower, upper));
  const mpz_class zero = 0, minus_one = -1, one = 1;
  EXPECT_FALSE(enclose_rational(one.get_mpz_t(), zero.get_mpz_t(), lower, upper));
  EXPECT_FALSE(enclose_rational(one.get_mpz_t(), minus_one.get_mpz_t(), lower, upper));
  EXPECT_TRUE(enclose_rational(fits.get_mpz_t(), one.get_mpz_t(), lower, upper));
  EXPECT_EQ(lower, 9007199254740991.0);
  EXPECT_EQ(upper, 9007199254740991.0);
}

TEST(NearQuotient, SimplestBetweenInMachineIntegersIsTheGmpDescentOnGeneratedIntervals) {
  // 60,000 intervals: ends of 1 ... 66 bits (around the 2^62 limit), integers, shared floors,
  // negatives, straddling zero, touching an integer, widths 2^-120 ... 2^8; where every end
  // fits, the answer is the GMP descent's to the integer (canonical form included), else the
  // machine-integer version declines
  std::mt19937_64 random(3232);
  std::size_t small = 0, declined = 0, integers = 0, deep = 0;
  for (int trial = 0; trial < 60000; ++trial) {
    const int bits = 1 + static_cast<int>(random() % 66);
    Rational lo;
    switch (random() % 4) {
      case 0: lo = Rational(random_integer(random, 1 + static_cast<int>(random() % 8), true)); break;
      case 1: lo = canonical(random_integer(random, bits, true), mpz_class(1) << static_cast<unsigned>(random() % 62)); break;
      default: lo = canonical(random_integer(random, bits, true), random_integer(random, bits, false) + 1);
    }
    Rational width;
    switch (random() % 4) {
      case 0: width = Rational(static_cast<long>(1 + random() % 300)); break;
      case 1: width = canonical(1, random_integer(random, bits, false) + 1); break;
      default: width = canonical(static_cast<long>(1 + random() % 1000), mpz_class(1) << static_cast<unsigned>(random() % 120));
    }
    const Rational hi = lo + width;
    const Rational want = cspace::algebra::simplest_between_gmp(lo, hi);
    Rational got(17, 5);
    const bool fits = mpz_sizeinbase(lo.get_num_mpz_t(), 2) <= 62 && mpz_sizeinbase(lo.get_den_mpz_t(), 2) <= 62 &&
                      mpz_sizeinbase(hi.get_num_mpz_t(), 2) <= 62 && mpz_sizeinbase(hi.get_den_mpz_t(), 2) <= 62;
    const bool taken = cspace::algebra::simplest_between_small(lo, hi, got);
    ASSERT_EQ(taken, fits) << lo.get_str() << " " << hi.get_str();
    if (!taken) {
      EXPECT_EQ(got, Rational(17, 5));   // untouched
      ++declined;
      continue;
    }
    ASSERT_EQ(got.get_num(), want.get_num()) << lo.get_str() << " " << hi.get_str();
    ASSERT_EQ(got.get_den(), want.get_den()) << lo.get_str() << " " << hi.get_str();
    ASSERT_EQ(cspace::algebra::simplest_between(lo, hi), want);
    ++small;
    if (want.get_den() == 1) ++integers;
    if (mpz_sizeinbase(want.get_den_mpz_t(), 2) >= 40) ++deep;
  }
  EXPECT_GE(small, 30000u);
  EXPECT_GE(declined, 5000u);
  EXPECT_GE(integers, 5000u);
  EXPECT_GE(deep, 1800u);
}

TEST(NearQuotient, SimplestBetweenInMachineIntegersAtTheLimits) {
  // ends at 2^62 - 1 (taken) and 2^62 (declined), the deepest descents there are (consecutive
  // Fibonacci ratios), and hand-checked answers
  const mpz_class top = (mpz_class(1) << 62) - 1;
  Rational out;
  ASSERT_TRUE(cspace::algebra::simplest_between_small(Rational(top - 1), Rational(top), out));
  EXPECT_EQ(out, canonical(2 * top - 1, 2));   // no integer strictly inside
  EXPECT_EQ(out, cspace::algebra::simplest_between_gmp(Rational(top - 1), Rational(top)));
  EXPECT_FALSE(cspace::algebra::simplest_between_small(Rational(top), Rational(top + 1), out));
  EXPECT_FALSE(cspace::algebra::simplest_between_small(canonical(1, top + 1), canonical(1, top), out));
  // between F(k) / F(k-1) and F(k+1) / F(k), the largest Fibonacci numbers below 2^62: a
  // descent of every quotient 1, the longest there is; the answer is F(k+2) / F(k+1)
  mpz_class f0 = 1, f1 = 1, f2 = 2;
  while (f1 + f2 <= top) {
    mpz_class next = f1 + f2;
    f0 = f1;
    f1 = f2;
    f2 = next;
  }
  const Rational one = canonical(f1, f0), two = canonical(f2, f1);
  for (const int sign : {1, -1}) {
    const Rational a = sign * one, b = sign * two, lo = std::min(a, b), hi = std::max(a, b);
    ASSERT_TRUE(cspace::algebra::simplest_between_small(lo, hi, out));
    EXPECT_EQ(out, cspace::algebra::simplest_between_gmp(lo, hi));
    EXPECT_EQ(out, canonical(sign * (f1 + f2), f2));
  }
  for (const auto& [a, b, want] : {std::tuple{canonical(1, 3), canonical(1, 2), canonical(2, 5)},
                                   std::tuple{canonical(-1, 2), canonical(1, 2), Rational(0)},
                                   std::tuple{Rational(3), Rational(5), Rational(4)},
                                   std::tuple{canonical(-7, 2), Rational(-3), canonical(-10, 3)},
                                   std::tuple{Rational(-5), Rational(-3), Rational(-4)},
                                   std::tuple{canonical(-9, 2), canonical(-1, 2), Rational(-1)}}) {
    ASSERT_TRUE(cspace::algebra::simplest_between_small(a, b, out));
    EXPECT_EQ(out, want) << a.get_str() << " " << b.get_str();
  }
}

}  // namespace
}  // namespace hipair
