// An edge's ordinate at a rational abscissa when its support there is a quadratic in y with two
// distinct real roots (docs/performance.md, session 41 fast41): algebra::nth_real_root_in's
// answer, bound for bound, without its exact square-free part (a polynomial gcd) and Sturm
// sequence. For such a quadratic the square-free part is its primitive part (its gcd with its
// derivative is 1), and the number of roots up to m — the Sturm count the bisection reads — is
// decided by the signs of p(m) and p'(m): with p's leading coefficient > 0, p(m) < 0 between
// the roots (1); p(m) = 0 at a root, the smaller where p'(m) < 0 (1), else the larger (2);
// p(m) > 0 left of both where p'(m) < 0 (0), right of both otherwise (2). The bisection below
// is nth_real_root_in's with these counts, so the interval and polynomial returned are its own.
#pragma once

#include "algebra/exact_real.hpp"

#include <hipair/error.hpp>

#include <optional>
#include <string>

namespace hipair::cspace {

/// algebra::nth_real_root_in(input, index, lo, hi) (the same Real, the same error) when input's
/// primitive part has degree 2 and a discriminant > 0; std::nullopt otherwise (nothing decided).
inline std::optional<algebra::Real> quadratic_root_in(const algebra::Polynomial& input, int index, const Rational& lo,
                                                      const Rational& hi) {
  algebra::Polynomial p = algebra::primitive_part(input);   // leading coefficient > 0
  if (algebra::degree(p) != 2) return std::nullopt;
  thread_local mpz_class discriminant, t;
  mpz_mul(discriminant.get_mpz_t(), p[1].get_mpz_t(), p[1].get_mpz_t());
  mpz_mul(t.get_mpz_t(), p[2].get_mpz_t(), p[0].get_mpz_t());
  mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), 2);
  if (mpz_cmp(discriminant.get_mpz_t(), t.get_mpz_t()) <= 0) return std::nullopt;   // a double root, or none
  // roots of p in (-infinity, m]
  auto up_to = [&](const Rational& m) {
    const int value = algebra::sign_at(p, m);
    if (value < 0) return 1;
    // p'(m) = 2 p2 m + p1, times m's denominator (> 0); never 0 where p(m) >= 0 (two roots)
    mpz_mul(t.get_mpz_t(), p[2].get_mpz_t(), m.get_num_mpz_t());
    mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), 1);
    mpz_addmul(t.get_mpz_t(), p[1].get_mpz_t(), m.get_den_mpz_t());
    const bool falling = sgn(t) < 0;
    if (value == 0) return falling ? 1 : 2;
    return falling ? 0 : 2;
  };
  Rational a = lo, b = hi;
  if (up_to(a) > index || up_to(b) <= index || algebra::sign_at(p, a) == 0)
    throw NumericError("internal: contact curve root " + std::to_string(index) + " is not in its certified box");
  // as nth_real_root_in: halve [a, b] to one root in (a, b], then until p(a) != 0 or p(b) = 0
  for (int below_a = up_to(a), below_b = up_to(b); below_b - below_a > 1;) {
    Rational m = (a + b) / 2;
    const int below_m = up_to(m);
    if (below_m > index)
      b = m, below_b = below_m;
    else
      a = m, below_a = below_m;
  }
  while (algebra::sign_at(p, b) != 0) {
    if (algebra::sign_at(p, a) != 0) {
      algebra::Real r;
      r.polynomial = std::move(p);
      r.lower = std::move(a);
      r.upper = std::move(b);
      return r;
    }
    Rational m = (a + b) / 2;
    if (up_to(m) - up_to(a) == 1)
      b = m;
    else
      a = m;
  }
  return algebra::Real::from_rational(b);
}

}  // namespace hipair::cspace
