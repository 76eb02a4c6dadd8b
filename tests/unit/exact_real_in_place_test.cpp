// Session 35 (trans35): exact algebra written in place, against independent references on
// generated inputs:
//  - Real::from_rational (its polynomial written in place) against primitive_part of
//    {-num, den}, on canonical rationals and on rationals with a common factor, and zero;
//  - substitute_x (products accumulated in place, per-thread weights) against the rational
//    coefficients sum_i c_ij x^i times den(x)^(rows - 1);
//  - sign_at(f, x, y) (a constant f's sign without the substitution; the interval filter's first
//    round on y itself, a copy only to refine) against the sign of f(x, y) computed exactly: in
//    rationals at a rational y, and at y = +-sqrt(k) (k a non-square rational) by reducing
//    f(x, y) modulo y^2 - k to a + b y and comparing a^2 with b^2 k.
#include "algebra/exact_real.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hipair::cspace {
namespace {

using algebra::Polynomial;
using algebra::Real;
using test_numbers::random_integer;

mpz_class random_small(std::mt19937_64& random, int max_bits) {
  const int bits = 1 + static_cast<int>(random() % static_cast<unsigned long>(max_bits));
  return random() % 5 == 0 ? mpz_class(0) : random_integer(random, bits, true);
}

Rational random_rational_any(std::mt19937_64& random, int max_bits) {
  mpz_class num = random_small(random, max_bits);
  mpz_class den = random_integer(random, 1 + static_cast<int>(random() % static_cast<unsigned long>(max_bits)), false);
  return test_numbers::canonical(num, den);
}

// f with `rows` rows of up to `columns` entries; some rows zero-padded, some entries zero.
IntegerPolynomial2 random_polynomial(std::mt19937_64& random, bool constant) {
  IntegerPolynomial2 f;
  const std::size_t rows = random() % 4;
  for (std::size_t i = 0; i < rows; ++i) {
    f.coefficients.emplace_back();
    const std::size_t columns = random() % 4;
    for (std::size_t j = 0; j < columns; ++j)
      f.coefficients.back().push_back((constant && (i > 0 || j > 0)) ? mpz_class(0) : random_small(random, 40));
  }
  return f;
}

// The exact sign of f(x, y) at rational x, y.
int reference_sign(const IntegerPolynomial2& f, const Rational& x, const Rational& y) {
  Rational value = 0, x_power = 1;
  for (const auto& row : f.coefficients) {
    Rational y_power = 1;
    for (const auto& c : row) {
      value += Rational(c) * x_power * y_power;
      y_power *= y;
    }
    x_power *= x;
  }
  return sgn(value);
}

// The exact sign of f(x, s sqrt(k)) (k > 0 not a square of a rational, s = +-1): f(x, y) mod
// (y^2 - k) = a + b y, sign(a + b s sqrt(k)) from the signs of a, b s and of a^2 - b^2 k.
int reference_sign_at_root(const IntegerPolynomial2& f, const Rational& x, const Rational& k, int s) {
  Rational a = 0, b = 0, x_power = 1;
  for (const auto& row : f.coefficients) {
    Rational k_power = 1;   // y^j = k^(j/2) (j even) or k^((j-1)/2) y (j odd)
    for (std::size_t j = 0; j < row.size(); ++j) {
      Rational term = Rational(row[j]) * x_power * k_power;
      if (j % 2 == 0) {
        a += term;
      } else {
        b += term;
        k_power *= k;
      }
    }
    x_power *= x;
  }
  b *= s;
  const int sa = sgn(a), sb = sgn(b);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  // opposite signs: a + b sqrt(k) has the sign of the larger magnitude
  const int c = cmp(Rational(a * a), Rational(b * b * k));
  return c > 0 ? sa : sb;   // c == 0 cannot happen: k is not a square
}

TEST(ExactRealInPlace, FromRationalIsThePrimitivePartOnGeneratedRationals) {
  std::mt19937_64 random(3501);
  int non_canonical = 0;
  for (int n = 0; n < 20000; ++n) {
    const int bits = 1 + static_cast<int>(random() % 150);
    mpz_class num = n % 7 == 0 ? mpz_class(0) : random_integer(random, bits, true);
    // (a positive denominator: GMP's rationals, mpq_set included, require one)
    mpz_class den = random_integer(random, 1 + static_cast<int>(random() % 150), false);
    if (n % 4 == 0) {   // a common factor
      mpz_class factor = random_integer(random, 1 + static_cast<int>(random() % 40), false);
      num *= factor;
      den *= factor;
    }
    Rational value;
    mpz_set(mpq_numref(value.get_mpq_t()), num.get_mpz_t());
    mpz_set(mpq_denref(value.get_mpq_t()), den.get_mpz_t());   // possibly with a common factor
    Rational copy = value;   // (mpq_canonicalize accepts common factors)
    copy.canonicalize();
    if (cmp(copy.get_num(), num) != 0 || cmp(copy.get_den(), den) != 0) ++non_canonical;
    const Real r = Real::from_rational(value);
    const Polynomial reference = algebra::primitive_part(Polynomial{mpz_class(-num), den});
    ASSERT_EQ(r.polynomial.size(), reference.size()) << value;
    for (std::size_t i = 0; i < reference.size(); ++i) ASSERT_EQ(cmp(r.polynomial[i], reference[i]), 0) << value;
    ASSERT_TRUE(r.exact);
    ASSERT_EQ(mpq_equal(r.lower.get_mpq_t(), value.get_mpq_t()), 1);
    ASSERT_EQ(mpq_equal(r.upper.get_mpq_t(), value.get_mpq_t()), 1);
    // the root of the polynomial is the value
    ASSERT_EQ(algebra::sign_at(r.polynomial, copy), 0);
  }
  EXPECT_GE(non_canonical, 4000);
}

TEST(ExactRealInPlace, SubstituteXIsTheRationalSubstitutionOnGeneratedPolynomials) {
  std::mt19937_64 random(3502);
  for (int n = 0; n < 20000; ++n) {
    const IntegerPolynomial2 f = random_polynomial(random, false);
    const Rational x = random_rational_any(random, 1 + static_cast<int>(random() % 90));
    const Polynomial p = algebra::substitute_x(f, x);
    // reference: coefficient of y^j is (sum_i c_ij x^i) den^(rows - 1)
    std::size_t columns = 0;
    for (const auto& row : f.coefficients) columns = std::max(columns, row.size());
    const long rows = static_cast<long>(f.coefficients.size());
    mpz_class scale;
    mpz_pow_ui(scale.get_mpz_t(), x.get_den_mpz_t(), static_cast<unsigned long>(std::max(rows - 1, 0L)));
    Polynomial reference(columns);
    for (std::size_t j = 0; j < columns; ++j) {
      Rational sum = 0, x_power = 1;
      for (const auto& row : f.coefficients) {
        if (j < row.size()) sum += Rational(row[j]) * x_power;
        x_power *= x;
      }
      Rational scaled = sum * Rational(scale);
      scaled.canonicalize();
      ASSERT_EQ(cmp(scaled.get_den(), 1), 0);
      reference[j] = scaled.get_num();
    }
    algebra::trim(reference);
    ASSERT_EQ(p.size(), reference.size()) << n;
    for (std::size_t j = 0; j < p.size(); ++j) ASSERT_EQ(cmp(p[j], reference[j]), 0) << n;
  }
}

TEST(ExactRealInPlace, SignAtIsTheExactSignOnGeneratedPolynomialsAndPoints) {
  std::mt19937_64 random(3503);
  int constants = 0, at_roots = 0, zeros = 0;
  for (int n = 0; n < 6000; ++n) {
    const bool constant = n % 3 == 0;
    const IntegerPolynomial2 f = random_polynomial(random, constant);
    const Rational x = random_rational_any(random, 1 + static_cast<int>(random() % 60));
    if (n % 2 == 0) {
      const Rational y = random_rational_any(random, 1 + static_cast<int>(random() % 60));
      const int expected = reference_sign(f, x, y);
      zeros += expected == 0;
      ASSERT_EQ(algebra::sign_at(f, x, Real::from_rational(y)), expected) << n;
    } else {
      // y = s sqrt(k), k = m / d not a square (m d not a square: then m / d is none either)
      Rational k;
      for (;;) {
        mpz_class m = random_integer(random, 1 + static_cast<int>(random() % 30), false);
        mpz_class d = random_integer(random, 1 + static_cast<int>(random() % 30), false);
        k = test_numbers::canonical(m, d);
        mpz_class product = k.get_num() * k.get_den();
        if (!mpz_perfect_square_p(product.get_mpz_t())) break;
      }
      const int s = random() % 2 == 0 ? 1 : -1;
      Real y;
      y.polynomial = Polynomial{mpz_class(-k.get_num()), mpz_class(0), k.get_den()};
      // a wide isolating interval (0, k + 1] or [-(k + 1), 0): the filter must refine
      const Rational wide = k + 1;
      y.lower = s > 0 ? Rational(0) : Rational(-wide);
      y.upper = s > 0 ? wide : Rational(0);
      y.exact = false;
      const int expected = reference_sign_at_root(f, x, k, s);
      ASSERT_EQ(algebra::sign_at(f, x, y), expected) << n;
      ++at_roots;
    }
    constants += constant;
  }
  EXPECT_GE(constants, 1500);
  EXPECT_GE(at_roots, 2500);
  EXPECT_GE(zeros, 100);
}

}  // namespace
}  // namespace hipair::cspace
