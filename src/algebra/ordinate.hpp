// Points of a chart whose ordinate is a rational function of the abscissa, y = P(x) / Q(x):
// the substitution that turns the sign of a bivariate polynomial there into the sign of a
// univariate one at x (the algebraic oracle at vertices with both coordinates irrational,
// cspace/builder.cpp and oracle/algebraic_overlap.cpp; implemented in exact_real.cpp).
#pragma once

#include "algebra/exact_real.hpp"

namespace hipair::cspace::algebra {

/// The coefficient of y^j of f, a polynomial in x (zero beyond f's degree in y).
Polynomial y_coefficient(const IntegerPolynomial2& f, int j);
/// The product of two polynomials.
Polynomial product(const Polynomial& a, const Polynomial& b);
/// Q(x)^d f(x, P(x) / Q(x)), d = f's degree in y (0 for the zero polynomial): at an x where
/// Q(x) != 0, its sign is that of f at (x, P(x) / Q(x)) times sign(Q(x))^d.
Polynomial substitute_ordinate(const IntegerPolynomial2& f, const Polynomial& P, const Polynomial& Q);

}  // namespace hipair::cspace::algebra
