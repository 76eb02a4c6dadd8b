// Points of a chart whose ordinate is an expression in the abscissa: a rational function,
// y = P(x) / Q(x), or one with a square root, y = (P(x) + √R(x)) / Q(x): the substitution that
// turns the sign of a bivariate polynomial there into signs of univariate ones at x (the
// algebraic oracle at vertices with both coordinates irrational, cspace/builder.cpp and
// oracle/algebraic_overlap.cpp; substitute_ordinate is in exact_real.cpp, the rest in
// ordinate.cpp).
#pragma once

#include "algebra/exact_real.hpp"

#include <utility>

namespace hipair::cspace::algebra {

/// The coefficient of y^j of f, a polynomial in x (zero beyond f's degree in y).
Polynomial y_coefficient(const IntegerPolynomial2& f, int j);
/// The product of two polynomials.
Polynomial product(const Polynomial& a, const Polynomial& b);
/// Q(x)^d f(x, P(x) / Q(x)), d = f's degree in y (0 for the zero polynomial): at an x where
/// Q(x) != 0, its sign is that of f at (x, P(x) / Q(x)) times sign(Q(x))^d.
Polynomial substitute_ordinate(const IntegerPolynomial2& f, const Polynomial& P, const Polynomial& Q);

/// A chart ordinate as an expression in the abscissa x: y = (numerator(x) + √radicand(x)) /
/// denominator(x), at an x where denominator(x) != 0 and radicand(x) >= 0 (an empty radicand:
/// the rational function numerator / denominator), with an enclosure lower <= y <= upper (the
/// caller's; oracle/algebraic_overlap.cpp checks it exactly). A root of a y^2 + b y + c (a != 0
/// at x, b^2 - 4ac > 0) is (-b + √(b^2 - 4ac)) / 2a or (b + √(b^2 - 4ac)) / -2a.
struct RadicalOrdinate {
  Polynomial numerator, radicand, denominator;
  Rational lower, upper;
};

/// Q^d f(x, (P + √R) / Q) = A(x) + B(x) √R(x) as the pair (A, B), d = f's degree in y (B is 0
/// when R is empty).
std::pair<Polynomial, Polynomial> substitute_radical_ordinate(const IntegerPolynomial2& f, const RadicalOrdinate& y);

/// The exact sign of A(x) + B(x) √R(x) at the algebraic x, where R(x) >= 0: where A and B have
/// opposite non-zero signs (and R(x) > 0), A's sign times that of A^2 - B^2 R; otherwise the
/// sign of the term that is not zero. Each a univariate sign at x (sign_at).
int sign_with_root(const Polynomial& A, const Polynomial& B, const Polynomial& R, const Real& x);

/// The exact sign of f at (x, y), where `denominator_sign` is the sign of y.denominator at x
/// (non-zero) and y.radicand(x) >= 0: sign_with_root of substitute_radical_ordinate (one
/// univariate sign when the radicand is empty), times denominator_sign^d.
int sign_at(const IntegerPolynomial2& f, const Real& x, const RadicalOrdinate& y, int denominator_sign);

}  // namespace hipair::cspace::algebra
