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

/// Divides the bivariate polynomial c[i][j] x^i y^j by (1 + x^2) when it divides exactly
/// (every column polynomial in x divides): returns true and replaces c by the quotient;
/// otherwise returns false and leaves c as it was. (For (1 + y^2), divide the transpose.)
template <class C>
bool divide_by_half_angle_weight(std::vector<std::vector<C>>& c) {
  std::size_t n = c.size();
  if (n < 3) return false;
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
