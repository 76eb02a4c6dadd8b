// Session 40 (scale40): the multi-precision interval filter of sign_at(Polynomial, Real)
// (src/algebra/multiprecision_sign.cpp) against the exact path (gcd, square-free part, Sturm
// sequence) on generated polynomials and real algebraic numbers: coefficients of 50-1 500 bits,
// values cancelling to 10^-100 ... 10^-600 of their terms (a rational approximation's linear
// form times a random factor, a multiple of u's polynomial plus a small constant), exact zeros
// (multiples of u's polynomial, u's polynomial itself), numbers near 2^+-1000, and random pairs.
// The filter must never give a sign other than the exact one, never decide a zero, and decide
// every non-zero value at its default precisions when the pair is certified coprime.
#include "algebra/multiprecision_sign.hpp"
#include "random_algebraic.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

using test_numbers::random_integer;

using test_algebraic::random_polynomial;

using test_algebraic::times;
using test_algebraic::random_irrational;

struct Tally {
  int cases = 0, decided = 0, zeros = 0, declined = 0;
};

// The filter against the exact path on p at u; `label` names the case on failure.
void check(const Polynomial& p, const Real& u, Tally& tally, const std::string& label) {
  const int exact = exact_sign_at(p, u);
  const MultiprecisionBits bits = multiprecision_sign_bits(p, u);
  const auto filtered = multiprecision_sign(p, u, bits.start, bits.cap);
  ++tally.cases;
  if (filtered) {
    ++tally.decided;
    EXPECT_EQ(*filtered, exact) << label << ": the filter's sign is wrong";
  } else {
    ++tally.declined;
  }
  if (exact == 0) {
    ++tally.zeros;
    EXPECT_FALSE(filtered) << label << ": a zero decided as " << *filtered;
    EXPECT_FALSE(coprime_modularly(p, u.polynomial)) << label << ": coprime, yet p(u) = 0";
  } else if (coprime_modularly(p, u.polynomial)) {
    EXPECT_TRUE(filtered) << label << ": a non-zero value the filter did not decide";
  }
  EXPECT_EQ(sign_at(p, u), exact) << label << ": sign_at differs from the exact path";
}

TEST(AlgebraMultiprecisionSign, AgreesWithTheExactPathOnCancellingValuesZerosAndWideScales) {
  std::mt19937_64 random(20261202);
  Tally tally;
  int cancelling = 0;
  for (int round = 0; round < 30; ++round) {
    const int bits = 50 + static_cast<int>(random() % 1450);
    const int shift = round % 5 == 0 ? (round % 10 == 0 ? 500 : -500) : 0;   // roots near 2^+-1000 when squared
    auto drawn = random_irrational(random, bits, shift);
    if (!drawn) continue;
    const Real& u = *drawn;
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits, shift " +
                           std::to_string(shift) + ")";
    // 1. D x - N with N / D within 2^-t |u| of u (t for 10^-100 ... 10^-600), times a random factor
    {
      const int t = 333 + static_cast<int>(random() % 1660);
      Real v = u;
      Rational width = abs(u.lower) + abs(u.upper);
      mpz_class scale = 1;
      mpz_mul_2exp(scale.get_mpz_t(), scale.get_mpz_t(), static_cast<mp_bitcnt_t>(t));
      refine_dyadically(v, width / scale);
      const Rational r = v.lower;
      Polynomial linear{-r.get_num(), r.get_den()};
      check(linear, u, tally, at + ", linear form of 2^-" + std::to_string(t));
      check(times(linear, random_polynomial(random, 1 + static_cast<int>(random() % 3), 60)), u, tally,
            at + ", linear form of 2^-" + std::to_string(t) + " times a factor");
      cancelling += 2;
    }
    // 2. u's polynomial times a factor plus a small constant: a value 10^-(bits/3) of the terms
    {
      Polynomial p = times(u.polynomial, random_polynomial(random, 1 + static_cast<int>(random() % 2), bits));
      p[0] += static_cast<long>(1 + random() % 1000) * (random() & 1 ? 1 : -1);
      trim(p);
      check(p, u, tally, at + ", multiple plus a constant");
    }
    // 3. exact zeros: u's polynomial, and a multiple of it
    check(u.polynomial, u, tally, at + ", its own polynomial");
    check(times(u.polynomial, random_polynomial(random, 2, 200)), u, tally, at + ", a multiple");
    // 4. a random polynomial
    check(random_polynomial(random, 1 + static_cast<int>(random() % 5), bits), u, tally, at + ", random");
  }
  EXPECT_GT(cancelling, 30);
  EXPECT_GT(tally.zeros, 30);
  EXPECT_GT(tally.decided, 70);
  std::printf("%d cases: %d decided, %d declined (%d zeros)\n", tally.cases, tally.decided, tally.declined,
              tally.zeros);
}

// p with a dyadic root r at an end of the bracket the filter's bisection reaches (u = sqrt(k) 2^e
// isolated in (s 2^e, (s + 1) 2^e), exact in MPFR): p(r) = 0 is exactly at the enclosure's edge,
// where a bound rounded the wrong way shows (a mutant with one product rounded inwards fails).
TEST(AlgebraMultiprecisionSign, DyadicRootsAtTheBracketsEndsAreNeverMisjudged) {
  std::mt19937_64 random(4020);
  Tally tally;
  for (int round = 0; round < 120; ++round) {
    mpz_class k = random_integer(random, 2 + static_cast<int>(random() % 300), false);
    if (mpz_perfect_square_p(k.get_mpz_t())) continue;
    const int e = round % 3 == 0 ? 0 : (round % 3 == 1 ? 1000 : -1000);
    mpz_class s;
    mpz_sqrt(s.get_mpz_t(), k.get_mpz_t());
    Rational scale = 1;
    if (e > 0) mpz_mul_2exp(scale.get_num_mpz_t(), scale.get_num_mpz_t(), static_cast<mp_bitcnt_t>(e));
    if (e < 0) mpz_mul_2exp(scale.get_den_mpz_t(), scale.get_den_mpz_t(), static_cast<mp_bitcnt_t>(-e));
    // u^2 = k scale^2: q = den^2 x^2 - k num^2
    const mpz_class n = scale.get_num(), d = scale.get_den();
    Real u{Polynomial{-k * n * n, 0, d * d}, Rational(s) * scale, Rational(s + 1) * scale, false};
    // the bracket's ends after t exact bisections (the filter's midpoints, as long as they are exact)
    const int t = random() & 1 ? 16 * (1 + static_cast<int>(random() % 12)) : 1 + static_cast<int>(random() % 190);
    Rational lo = u.lower, hi = u.upper;
    for (int i = 0; i < t; ++i) {
      Rational m = (lo + hi) / 2;
      (sgn(m) * (m * m - k * scale * scale) < 0 ? lo : hi) = m;   // (u > 0)
    }
    const Rational r = random() & 1 ? lo : hi;
    Polynomial linear{-r.get_num(), r.get_den()};
    const std::string at = "sqrt(" + k.get_str() + ") 2^" + std::to_string(e) + ", end after " + std::to_string(t);
    check(linear, u, tally, at);
    check(times(linear, random_polynomial(random, 1 + static_cast<int>(random() % 3), 100 + static_cast<int>(random() % 400))), u, tally,
          at + " times a factor");
  }
  EXPECT_GT(tally.cases, 150);
  std::printf("%d cases: %d decided, %d declined\n", tally.cases, tally.decided, tally.declined);
}

// The two enclosures against p's exact rational values: at points (x rounded to the precision)
// and over intervals (at both ends and a point inside), coefficients of 50-1 500 bits, x of
// 2^+-1000 and cancelling values, at 64-1 024 bits: every value inside its enclosure. Any one
// rounding turned inwards fails it.
TEST(AlgebraMultiprecisionSign, EnclosuresHoldTheExactValues) {
  std::mt19937_64 random(1202);
  int points = 0, intervals = 0;
  for (int round = 0; round < 150; ++round) {
    const long bits = 64L << (random() % 5);
    const int coefficient_bits = 50 + static_cast<int>(random() % 1450);
    Polynomial p = random_polynomial(random, 1 + static_cast<int>(random() % 6), coefficient_bits);
    if (p.empty()) continue;
    const int e = static_cast<int>(random() % 2001) - 1000;
    Rational x(random_integer(random, 1 + static_cast<int>(random() % 300), true));
    if (e > 0) mpz_mul_2exp(x.get_num_mpz_t(), x.get_num_mpz_t(), static_cast<mp_bitcnt_t>(e));
    if (e < 0) mpz_mul_2exp(x.get_den_mpz_t(), x.get_den_mpz_t(), static_cast<mp_bitcnt_t>(-e));
    x.canonicalize();
    if (round % 4 == 0) {   // a value cancelling: p's constant term moved so that p(x) is nearly 0
      const Rational v = value_at(p, x);
      p[0] -= v.get_num() / v.get_den();
      trim(p);
    }
    const std::string at = "round " + std::to_string(round);
    const MultiprecisionEnclosure point = multiprecision_enclosure_at_point(p, x, bits);
    const Rational exact = value_at(p, point.point);
    EXPECT_LE(point.lo, exact) << at << ": the point enclosure's lower bound is above the value";
    EXPECT_GE(point.hi, exact) << at << ": the point enclosure's upper bound is below the value";
    ++points;
    const Rational y = x + Rational(random_integer(random, 1 + static_cast<int>(random() % 200), false), mpz_class(1) << static_cast<mp_bitcnt_t>(random() % 400));
    const MultiprecisionEnclosure over = multiprecision_enclosure_over(p, x, y, bits);
    for (const Rational& z : {x, y, Rational((x + y) / 2)}) {
      const Rational value = value_at(p, z);
      EXPECT_LE(over.lo, value) << at << ": the interval enclosure's lower bound is above a value";
      EXPECT_GE(over.hi, value) << at << ": the interval enclosure's upper bound is below a value";
    }
    ++intervals;
  }
  EXPECT_GT(points, 120);
  EXPECT_GT(intervals, 120);
}


// ---------------------------------------------------------------- session 41 (scale41): order

using test_algebraic::moved;

struct OrderTally {
  int cases = 0, distinct = 0, equal = 0, ordered = 0;
  void print() const {
    std::printf("%d cases: %d distinct, %d equal, %d ordered by MPFR\n", cases, distinct, equal, ordered);
  }
};

// compare, the exact path and the MPFR order (at its default precisions, or at `bits` alone when
// given) against the order known by construction.
void check_order(const Real& a, const Real& b, int expected, OrderTally& tally, const std::string& label,
                 long bits = 0) {
  ++tally.cases;
  (expected == 0 ? tally.equal : tally.distinct)++;
  EXPECT_EQ(exact_compare(a, b), expected) << label << ": the exact path";
  EXPECT_EQ(compare(a, b), expected) << label << ": compare";
  EXPECT_EQ(compare(b, a), -expected) << label << ": compare, swapped";
  const MultiprecisionBits defaults = multiprecision_order_bits(a, b);
  const auto order = bits > 0 ? multiprecision_order(a, b, bits, bits) : multiprecision_order(a, b, defaults.start, defaults.cap);
  if (order) {
    ++tally.ordered;
    EXPECT_EQ(*order, expected) << label << ": the MPFR order is wrong";
  } else if (bits == 0 && expected != 0 && !a.exact && !b.exact) {   // (a rational is not its to order)
    ADD_FAILURE() << label << ": distinct numbers the MPFR order did not separate";
  }
}

// Two numbers 2^-t |u| apart (t for 10^-100 ... 10^-600; u a root of a random quadratic or cubic
// of 50-1 500-bit coefficients, some near 2^+-1000): u against u moved by +-delta (q(x - delta),
// the interval moved alike); equal numbers given by different polynomials and intervals (q times
// a factor without real roots, the interval refined differently); a rational against u. compare,
// the exact path and the MPFR order against the order known by construction; the MPFR order
// never orders equal numbers and separates every distinct pair at its default precisions.
TEST(AlgebraMultiprecisionOrder, CloseEqualAndWideScaleNumbersInTheirKnownOrder) {
  std::mt19937_64 random(41);
  OrderTally tally;
  for (int round = 0; round < 16; ++round) {
    const int bits = 50 + static_cast<int>(random() % 1450);
    const int shift = round % 4 == 0 ? (round % 8 == 0 ? 1000 : -1000) : 0;
    auto drawn = random_irrational(random, shift == 0 ? bits : 50 + bits / 8, shift);
    if (!drawn) continue;
    const Real& u = *drawn;
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits, shift " +
                           std::to_string(shift) + ")";
    // 1. u and u + delta, |delta| = 2^-t (|u.lower| + |u.upper|) rounded to a dyadic
    {
      const int t = 333 + static_cast<int>(random() % 1660);
      Rational size = abs(u.lower) + abs(u.upper);
      Rational delta(mpz_class(1) + static_cast<long>(random() % 1000));
      mpz_mul_2exp(delta.get_den_mpz_t(), delta.get_den_mpz_t(), static_cast<mp_bitcnt_t>(t));
      delta *= size;
      if (random() & 1) delta = -delta;
      const Real v{moved(u.polynomial, delta), u.lower + delta, u.upper + delta, false};
      check_order(u, v, -sgn(delta), tally, at + ", moved by 2^-" + std::to_string(t));
    }
    // 2. u given by q times a factor without real roots (a x^2 + c, a, c > 0), a refined interval
    {
      Polynomial factor{abs(random_integer(random, 1 + static_cast<int>(random() % 300), false)), 0,
                        abs(random_integer(random, 1 + static_cast<int>(random() % 300), false))};
      Real v{times(u.polynomial, factor), u.lower, u.upper, false};
      Rational width = (u.upper - u.lower) / Rational(mpz_class(1) << static_cast<mp_bitcnt_t>(1 + random() % 200));
      refine_dyadically(v, width);
      if (!v.exact) check_order(u, v, 0, tally, at + ", the same number by another polynomial");
    }
    // 3. a rational inside u's interval against u
    {
      Real v = u;
      refine_dyadically(v, (u.upper - u.lower) / 1024);
      if (!v.exact) {
        const Rational r = v.lower;
        check_order(Real::from_rational(r), u, -1, tally, at + ", a rational just below");
      }
    }
  }
  EXPECT_GT(tally.distinct, 16);
  EXPECT_GT(tally.equal, 8);
  tally.print();
}

// At one precision P (no doubling), numbers 2^-(P - 8) ... 2^-(P + 8) of |u| apart and equal
// numbers by another polynomial: at this precision's floor a bracket end rounded the wrong way
// or a midpoint or Newton end not strictly inside would order them wrongly; every order given
// must be right, and equal numbers never ordered.
TEST(AlgebraMultiprecisionOrder, AtThePrecisionsFloorNoOrderIsWrong) {
  std::mt19937_64 random(4141);
  OrderTally tally;
  for (int round = 0; round < 40; ++round) {
    const long precision = 192L << (random() % 3);
    const int bits = 200 + static_cast<int>(random() % 400);
    auto drawn = random_irrational(random, bits, round % 3 == 0 ? 0 : (round % 3 == 1 ? 300 : -300));
    if (!drawn) continue;
    const Real& u = *drawn;
    const int t = static_cast<int>(precision) - 8 + static_cast<int>(random() % 17);
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits, P = " +
                           std::to_string(precision) + ", t = " + std::to_string(t) + ")";
    Rational delta(Rational(mpz_class(1) + static_cast<long>(random() % 100)) / Rational(mpz_class(1) << static_cast<mp_bitcnt_t>(t)));
    delta *= abs(u.lower) + abs(u.upper);
    if (random() & 1) delta = -delta;
    const Real v{moved(u.polynomial, delta), u.lower + delta, u.upper + delta, false};
    check_order(u, v, -sgn(delta), tally, at + ", moved", precision);
    Polynomial factor{abs(random_integer(random, 1 + static_cast<int>(random() % 200), false)), 0,
                      abs(random_integer(random, 1 + static_cast<int>(random() % 200), false))};
    const Real w{times(u.polynomial, factor), u.lower, u.upper, false};
    check_order(u, w, 0, tally, at + ", equal", precision);
  }
  EXPECT_GT(tally.cases, 50);
  tally.print();
}


// The brackets the MPFR order narrows (halvings and interval Newton steps), round by round down
// to the precision's floor, against u exactly (Real::compare with the ends: a sign of u's
// polynomial at a rational): u a root of a linear polynomial with wide random coefficients (a
// rational no MPFR number equals, met within an ulp or two by the Newton ends) or of a random
// quadratic or cubic, 64-1 024 bits, near 2^+-1000. Every bracket must hold u: a bound rounded
// the wrong way fails this.
TEST(AlgebraMultiprecisionOrder, BracketsHoldTheNumberDownToThePrecisionsFloor) {
  std::mt19937_64 random(20261241);
  int brackets = 0, tight = 0;
  for (int round = 0; round < 120; ++round) {
    const long precision = 64L << (random() % 5);
    Real u;
    if (round % 2 == 0) {
      // c1 x + c0 = 0 with an odd c1 (the root is not dyadic), in (floor, floor + 1) scaled
      const int bits = static_cast<int>(precision) + static_cast<int>(random() % 200);
      mpz_class c1 = abs(random_integer(random, bits, false)) | 1, c0 = random_integer(random, bits + static_cast<int>(random() % 64), true);
      if (mpz_divisible_p(c0.get_mpz_t(), c1.get_mpz_t())) continue;
      mpz_class f;
      mpz_fdiv_q(f.get_mpz_t(), mpz_class(-c0).get_mpz_t(), c1.get_mpz_t());
      u = Real{Polynomial{c0, c1}, Rational(f), Rational(f + 1), false};
    } else {
      const int shift = round % 3 == 0 ? 0 : (round % 3 == 1 ? 1000 : -1000);
      auto drawn = random_irrational(random, 50 + static_cast<int>(random() % 400), shift / 3);
      if (!drawn) continue;
      u = *drawn;
    }
    const std::string at = "round " + std::to_string(round) + " (P = " + std::to_string(precision) + ")";
    const auto narrowed = multiprecision_brackets(u, precision, 40 + static_cast<int>(precision / 8));
    for (std::size_t k = 0; k < narrowed.size(); ++k) {
      const auto& [lo, hi] = narrowed[k];
      ++brackets;
      EXPECT_GE(u.compare(lo), 0) << at << ", round " << k << ": the bracket's lower end is above the number";
      EXPECT_LE(u.compare(hi), 0) << at << ", round " << k << ": the bracket's upper end is below the number";
    }
    if (!narrowed.empty()) {
      const auto& [lo, hi] = narrowed.back();
      // at the floor: a few ulps of the precision (|u| + 1 as the scale)
      Rational ulps = (abs(lo) + 1) * 64 / Rational(mpz_class(1) << static_cast<mp_bitcnt_t>(precision));
      if (hi - lo <= ulps) ++tight;
    }
  }
  EXPECT_GT(brackets, 3000);
  EXPECT_GT(tight, 60);
  std::printf("%d brackets, %d narrowed to a few ulps\n", brackets, tight);
}

}  // namespace
}  // namespace hipair::cspace::algebra
