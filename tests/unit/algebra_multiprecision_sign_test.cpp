// Session 40 (scale40): the multi-precision interval filter of sign_at(Polynomial, Real)
// (src/algebra/multiprecision_sign.cpp) against the exact path (gcd, square-free part, Sturm
// sequence) on generated polynomials and real algebraic numbers: coefficients of 50-1 500 bits,
// values cancelling to 10^-100 ... 10^-600 of their terms (a rational approximation's linear
// form times a random factor, a multiple of u's polynomial plus a small constant), exact zeros
// (multiples of u's polynomial, u's polynomial itself), numbers near 2^+-1000, and random pairs.
// The filter must never give a sign other than the exact one, never decide a zero, and decide
// every non-zero value at its default precisions when the pair is certified coprime.
#include "algebra/multiprecision_sign.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

using test_numbers::random_integer;

Polynomial random_polynomial(std::mt19937_64& random, int degree, int bits) {
  Polynomial p;
  for (int i = 0; i <= degree; ++i) p.push_back(random_integer(random, 1 + static_cast<int>(random() % bits), true));
  trim(p);
  return p;
}

Polynomial times(const Polynomial& a, const Polynomial& b) {
  Polynomial c(a.size() + b.size() - 1, mpz_class(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  trim(c);
  return c;
}

// An irrational real root of a random quadratic or cubic with coefficients of `bits` bits,
// scaled by 2^shift (x -> x / 2^shift), or nothing when the draw has no irrational root.
std::optional<Real> random_irrational(std::mt19937_64& random, int bits, int shift) {
  const int degree = 2 + static_cast<int>(random() % 2);
  Polynomial q;
  for (int i = 0; i <= degree; ++i) q.push_back(random_integer(random, bits, true));
  // roots scaled by 2^shift: q(x / 2^shift) 2^(shift deg) for shift > 0, reversed otherwise
  for (int i = 0; i <= degree; ++i) {
    const int e = shift >= 0 ? shift * (degree - i) : -shift * i;
    mpz_mul_2exp(q[i].get_mpz_t(), q[i].get_mpz_t(), static_cast<mp_bitcnt_t>(e));
  }
  auto roots = real_roots(q);
  if (roots.empty()) return std::nullopt;
  Real u = roots[random() % roots.size()];
  if (u.exact) return std::nullopt;
  return u;
}

struct Tally {
  int cases = 0, decided = 0, zeros = 0, declined = 0;
};

// The filter against the exact path on p at u; `label` names the case on failure.
void check(const Polynomial& p, const Real& u, Tally& tally, const std::string& label) {
  const int exact = exact_sign_at(p, u);
  const auto [start, cap] = multiprecision_sign_bits(p, u);
  const auto filtered = multiprecision_sign(p, u, start, cap);
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
  for (int round = 0; round < 60; ++round) {
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
  EXPECT_GT(cancelling, 60);
  EXPECT_GT(tally.zeros, 60);
  EXPECT_GT(tally.decided, 150);
  std::printf("%d cases: %d decided, %d declined (%d zeros)\n", tally.cases, tally.decided, tally.declined,
              tally.zeros);
}

}  // namespace
}  // namespace hipair::cspace::algebra
