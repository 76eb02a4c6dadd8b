// Test helper: products of integer polynomials and random irrational algebraic numbers (roots
// of random quadratics and cubics), shared by the multi-precision sign and bracket tests.
#pragma once

#include "algebra/multiprecision_sign.hpp"
#include "random_rationals.hpp"

#include <optional>
#include <random>

namespace hipair::cspace::algebra::test_algebraic {

inline Polynomial times(const Polynomial& a, const Polynomial& b) {
  Polynomial c(a.size() + b.size() - 1, mpz_class(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  trim(c);
  return c;
}

// A random integer polynomial of the given degree, each coefficient of 1 ... bits bits and a
// random sign (trimmed: its degree may come out lower).
inline Polynomial random_polynomial(std::mt19937_64& random, int degree, int bits) {
  Polynomial p;
  for (int i = 0; i <= degree; ++i) p.push_back(test_numbers::random_integer(random, 1 + static_cast<int>(random() % bits), true));
  trim(p);
  return p;
}

// An irrational real root of a random quadratic or cubic with coefficients of `bits` bits,
// scaled by 2^shift (x -> x / 2^shift), or nothing when the draw has no irrational root.
inline std::optional<Real> random_irrational(std::mt19937_64& random, int bits, int shift) {
  const int degree = 2 + static_cast<int>(random() % 2);
  Polynomial q;
  for (int i = 0; i <= degree; ++i) q.push_back(test_numbers::random_integer(random, bits, true));
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

// q(x - delta) as an integer polynomial (delta = n / d): the sum of q_i (d x - n)^i d^(deg - i),
// primitive; its roots are q's moved by delta.
inline Polynomial moved(const Polynomial& q, const Rational& delta) {
  const Polynomial step{-delta.get_num(), delta.get_den()};
  const int deg = degree(q);
  Polynomial sum, power{1};
  for (int i = 0; i <= deg; ++i) {
    mpz_class factor;
    mpz_pow_ui(factor.get_mpz_t(), delta.get_den_mpz_t(), static_cast<unsigned long>(deg - i));
    Polynomial term = times(power, Polynomial{q[i] * factor});
    if (sum.size() < term.size()) sum.resize(term.size(), mpz_class(0));
    for (std::size_t j = 0; j < term.size(); ++j) sum[j] += term[j];
    power = times(power, step);
  }
  trim(sum);
  return primitive_part(sum);
}

}  // namespace hipair::cspace::algebra::test_algebraic
