// HIPAIR contact kernels — the (1 + t^2) normalisation. A half-angle chart's pose carries the
// weight w = 1 + t^2 > 0 (kernels/pose.hpp); every contact function is multiplied by positive
// weights so that it is a polynomial. Dividing a weight out again keeps the contact function's
// zero set and its sign (the blocked side), and lowers its degree: contact polynomials are
// stored with every exact factor (1 + x^2) and (1 + y^2) removed. Written for any coefficient
// type C with exact subtraction (mpz_class, mpq_class, ...).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace hipair::kernels {

/// Whether (1 + t^2) divides the polynomial sum a_k t^k, a_k = at(k) for k < n: exactly when
/// a(i) = (a_0 - a_2 + a_4 - ...) + i (a_1 - a_3 + ...) is zero (1 + t^2 is irreducible over
/// the rationals and monic: a(t) = q(t) (1 + t^2) + r_1 t + r_0 with a(i) = r_0 + i r_1).
template <class C, class At>
bool half_angle_weight_divides_one(std::size_t n, At at) {
  C even(0), odd(0);
  for (std::size_t k = 0; k < n; ++k) {
    C& sum = k % 2 == 0 ? even : odd;
    if (k % 4 < 2)
      sum += at(k);
    else
      sum -= at(k);
  }
  return even == C(0) && odd == C(0);
}

/// Whether (1 + x^2) divides c[i][j] x^i y^j (every column polynomial in x): what
/// divide_by_half_angle_weight(c) returns, without forming the quotient.
template <class C>
bool half_angle_weight_divides_x(const std::vector<std::vector<C>>& c) {
  std::size_t columns = 0;
  for (const auto& row : c) columns = row.size() > columns ? row.size() : columns;
  for (std::size_t j = 0; j < columns; ++j)
    if (!half_angle_weight_divides_one<C>(c.size(), [&](std::size_t k) -> const C& {
          static const C zero(0);
          return j < c[k].size() ? c[k][j] : zero;
        }))
      return false;
  return true;
}

/// Whether (1 + y^2) divides c[i][j] x^i y^j (every row polynomial in y): what
/// divide_by_half_angle_weight of the transpose returns, without transposing.
template <class C>
bool half_angle_weight_divides_y(const std::vector<std::vector<C>>& c) {
  for (const auto& row : c)
    if (!half_angle_weight_divides_one<C>(row.size(), [&](std::size_t k) -> const C& { return row[k]; })) return false;
  return true;
}

/// Divides the bivariate polynomial c[i][j] x^i y^j by (1 + x^2) when it divides exactly
/// (every column polynomial in x divides): returns true and replaces c by the quotient;
/// otherwise returns false and leaves c as it was. (For (1 + y^2), divide the transpose.)
/// The test a(i) = 0 per column comes first: most polynomials are not divisible, and then no
/// quotient is formed.
template <class C>
bool divide_by_half_angle_weight(std::vector<std::vector<C>>& c) {
  std::size_t n = c.size();
  if (n < 3) return false;
  if (!half_angle_weight_divides_x(c)) return false;
  std::size_t columns = 0;
  for (const auto& row : c) columns = row.size() > columns ? row.size() : columns;
  std::vector<std::vector<C>> quotient(n - 2, std::vector<C>(columns, C(0)));
  auto at = [&](std::size_t i, std::size_t j) -> C { return j < c[i].size() ? c[i][j] : C(0); };
  for (std::size_t j = 0; j < columns; ++j) {
    // a(x) = q(x) (x^2 + 1) + r: q_k = a_{k+2} - q_{k+2}, from the top.
    for (std::size_t k = n - 2; k-- > 0;) {
      C value = at(k + 2, j);
      if (k + 2 < n - 2) value -= quotient[k + 2][j];
      quotient[k][j] = value;
    }
    C r1 = at(1, j) - (n - 2 > 1 ? quotient[1][j] : C(0));
    C r0 = at(0, j) - quotient[0][j];
    if (!(r1 == C(0)) || !(r0 == C(0))) return false;
  }
  c = std::move(quotient);
  return true;
}

}  // namespace hipair::kernels
