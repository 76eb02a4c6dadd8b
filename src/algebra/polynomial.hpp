// Small exact bivariate polynomials for the contact kernels: a Rational-coefficient type the
// templated kernels compute with, and its conversion to the builder's IntegerPolynomial2.
#pragma once

#include <hipair/rational.hpp>

#include <gmpxx.h>

#include <vector>

namespace hipair::cspace {

/// Dense bivariate polynomial with integer coefficients: sum c[i][j] x^i y^j.
/// For a 1-D space only the x variable occurs (c[i][0]).
struct IntegerPolynomial2 {
  std::vector<std::vector<mpz_class>> coefficients;  ///< coefficients[i][j] of x^i y^j
  int degree_x() const noexcept;  ///< -1 for the zero polynomial (also degree_y)
  int degree_y() const noexcept;
  bool is_zero() const;
};

/// Dense polynomial sum c(i, j) x^i y^j with exact rational coefficients. Behaves as a
/// number type for kernels/ (construction from int, +, -, unary -, *).
/// Stored as integer numerators over one positive common denominator, so that arithmetic
/// never computes coefficient gcds (the zero set only needs the numerators).
class RationalPolynomial2 {
 public:
  RationalPolynomial2() = default;
  RationalPolynomial2(int constant);              // NOLINT(google-explicit-constructor)
  RationalPolynomial2(const Rational& constant);  // NOLINT(google-explicit-constructor)

  /// The polynomial x (variable 0) or y (variable 1).
  static RationalPolynomial2 variable(int which);

  /// Number of stored rows / columns (degree + 1 bounds; 0 for the zero polynomial).
  int rows() const noexcept { return rows_; }
  int columns() const noexcept { return columns_; }
  Rational coefficient(int i, int j) const;
  void set_coefficient(int i, int j, const Rational& value);
  /// Integer numerator of coefficient (i, j) over denominator().
  const mpz_class& numerator(int i, int j) const;
  const mpz_class& denominator() const noexcept { return denominator_; }

  bool is_zero() const noexcept { return rows_ == 0; }
  /// Exact value at (x, y).
  Rational evaluate(const Rational& x, const Rational& y) const;

  friend RationalPolynomial2 operator+(const RationalPolynomial2& a, const RationalPolynomial2& b);
  friend RationalPolynomial2 operator-(const RationalPolynomial2& a, const RationalPolynomial2& b);
  friend RationalPolynomial2 operator-(const RationalPolynomial2& a);
  friend RationalPolynomial2 operator*(const RationalPolynomial2& a, const RationalPolynomial2& b);
  friend bool operator==(const RationalPolynomial2& a, const RationalPolynomial2& b);

 private:
  // a + sign b, sign +1 or -1 (operator+, binary operator-)
  static RationalPolynomial2 combine(const RationalPolynomial2& a, const RationalPolynomial2& b, int sign);
  void resize(int rows, int columns);
  void trim();
  int rows_ = 0;
  int columns_ = 0;
  std::vector<mpz_class> numerators_;  // row-major, index i * columns_ + j
  mpz_class denominator_ = 1;          // > 0
};

/// Exact value of an integer polynomial at a rational point.
Rational evaluate(const IntegerPolynomial2& polynomial, const Rational& x, const Rational& y);

/// Integer polynomial with the same zero set and the same sign as `polynomial`, normalised:
/// denominators cleared, divided by the (positive) content of its coefficients, and every
/// factor (1 + x^2) and (1 + y^2) divided out (they have no real zeros and are positive, so
/// zero set and sign are unchanged). Trailing zero rows/columns are trimmed.
IntegerPolynomial2 normalized_integer_polynomial(const RationalPolynomial2& polynomial);

/// Normalises an integer polynomial in place as normalized_integer_polynomial does.
void normalize(IntegerPolynomial2& polynomial);

/// True when the polynomial does not involve y (resp. x).
bool depends_only_on_x(const IntegerPolynomial2& polynomial);
bool depends_only_on_y(const IntegerPolynomial2& polynomial);

}  // namespace hipair::cspace
