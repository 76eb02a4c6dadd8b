// Exact proportionality of two integer polynomials: p = c q for a rational c != 0. Where a point
// is known to be an exact root of q (an event's own polynomial, an edge's support at its sample),
// a p proportional to q vanishes there with no sign computation (docs/performance.md, session 40
// fast40). Cross products of integers only: p_k q_0 = q_k p_0 at every place k, where (p_0, q_0)
// are the coefficients at the first place where either is non-zero (both must be).
#pragma once

#include "algebra/polynomial.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace hipair::cspace::algebra {

namespace detail {
/// The cross-product walk over places 0 … count − 1; at(k) gives (p_k, q_k) (zero past a
/// polynomial's stored coefficients).
template <class At>
bool proportional_places(std::size_t count, At at) {
  thread_local mpz_class left, right;
  const mpz_class *p0 = nullptr, *q0 = nullptr;
  for (std::size_t k = 0; k < count; ++k) {
    const auto [pk, qk] = at(k);
    if (!p0) {
      if ((sgn(*pk) == 0) != (sgn(*qk) == 0)) return false;
      if (sgn(*pk) != 0) p0 = pk, q0 = qk;
      continue;
    }
    mpz_mul(left.get_mpz_t(), pk->get_mpz_t(), q0->get_mpz_t());
    mpz_mul(right.get_mpz_t(), qk->get_mpz_t(), p0->get_mpz_t());
    if (mpz_cmp(left.get_mpz_t(), right.get_mpz_t()) != 0) return false;
  }
  return p0 != nullptr;   // the zero polynomial is proportional to nothing
}

inline const mpz_class& zero_coefficient() {
  static const mpz_class zero;
  return zero;
}
}  // namespace detail

/// p = c q for a rational c != 0 (ascending coefficients; trailing zeros allowed). False when
/// either is the zero polynomial.
inline bool proportional(const std::vector<mpz_class>& p, const std::vector<mpz_class>& q) {
  const mpz_class& zero = detail::zero_coefficient();
  return detail::proportional_places(std::max(p.size(), q.size()), [&](std::size_t k) {
    return std::pair{k < p.size() ? &p[k] : &zero, k < q.size() ? &q[k] : &zero};
  });
}

/// f = c g for a rational c != 0 (rows and columns of any lengths; a missing coefficient is
/// zero). False when either is the zero polynomial.
inline bool proportional(const IntegerPolynomial2& f, const IntegerPolynomial2& g) {
  const mpz_class& zero = detail::zero_coefficient();
  auto at = [&](const IntegerPolynomial2& p, std::size_t i, std::size_t j) -> const mpz_class& {
    return i < p.coefficients.size() && j < p.coefficients[i].size() ? p.coefficients[i][j] : zero;
  };
  const std::size_t rows = std::max(f.coefficients.size(), g.coefficients.size());
  std::size_t columns = 0;
  for (const auto& row : f.coefficients) columns = std::max(columns, row.size());
  for (const auto& row : g.coefficients) columns = std::max(columns, row.size());
  return detail::proportional_places(rows * columns, [&](std::size_t k) {
    return std::pair{&at(f, k / columns, k % columns), &at(g, k / columns, k % columns)};
  });
}

}  // namespace hipair::cspace::algebra
