// HIPAIR — the linear complementarity problem in exact rationals by Lemke's complementary pivoting
// with the lexicographic minimum-ratio rule (session 68, impactpin68): lambda >= 0,
// w = A lambda + b >= 0, lambda_k w_k = 0. For any number of contacts, unlike the enumeration of
// held sets (friction.hpp's exact_assignment, bounded to 12 contacts: 2^m linear programs).
// Internal to src/simulation (GMP rationals; no type of it crosses include/hipair).
#pragma once

#include <hipair/rational.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::simulation {

struct ExactLcpSolution {
  std::vector<Rational> lambda, w;
};

/// Lemke's algorithm (Cottle, Pang & Stone, "The Linear Complementarity Problem", 4.4 and 4.9) on
/// the tableau [I  -A  -d | b] with covering vector d = 1, every pivot in rationals; the leaving
/// row by the lexicographic minimum ratio over (b, B^-1) (no cycling: it ends), z0 leaving first
/// where it ties in the ratio. For A copositive-plus — positive semidefinite, as a contact LCP's
/// A = G M^-1 G^T with M positive definite — it ends with a solution whenever the LCP has one;
/// ray termination then proves it has none: nullopt. (Also nullopt after 2^20 pivots: never
/// reached by a terminating run of the sizes a simulator gives; the caller then does not decide.)
/// `ray` (given) is set where nullopt is the ray termination.
inline std::optional<ExactLcpSolution> exact_lemke(const std::vector<std::vector<Rational>>& A,
                                                   const std::vector<Rational>& b, bool* ray = nullptr) {
  const std::size_t m = b.size();
  if (ray) *ray = false;
  ExactLcpSolution s;
  s.lambda.assign(m, Rational(0));
  s.w = b;
  bool nonnegative = true;
  for (const Rational& bi : b) nonnegative = nonnegative && sgn(bi) >= 0;
  if (nonnegative) return s;
  // columns: w (0..m-1), lambda (m..2m-1), z0 (2m), the right-hand side (2m+1)
  const std::size_t z0 = 2 * m, rhs = 2 * m + 1;
  std::vector<std::vector<Rational>> T(m, std::vector<Rational>(2 * m + 2, Rational(0)));
  for (std::size_t i = 0; i < m; ++i) {
    T[i][i] = 1;
    for (std::size_t j = 0; j < m; ++j) T[i][m + j] = -A[i][j];
    T[i][z0] = -1;
    T[i][rhs] = b[i];
  }
  std::vector<std::size_t> basis(m);
  for (std::size_t i = 0; i < m; ++i) basis[i] = i;
  auto pivot = [&](std::size_t row, std::size_t col) {
    const Rational p = T[row][col];
    for (Rational& t : T[row]) t /= p;
    for (std::size_t i = 0; i < m; ++i) {
      if (i == row || sgn(T[i][col]) == 0) continue;
      const Rational f = T[i][col];
      for (std::size_t c = 0; c < T[i].size(); ++c)
        if (sgn(T[row][c]) != 0) T[i][c] -= f * T[row][c];
    }
    basis[row] = col;
  };
  // the lexicographic order of rows i, j by (rhs, B^-1 row) / T[.][col] (B^-1: columns 0..m-1)
  auto lex_less = [&](std::size_t i, std::size_t j, std::size_t col) {
    const Rational ri = T[i][rhs] / T[i][col], rj = T[j][rhs] / T[j][col];
    if (ri != rj) return ri < rj;
    for (std::size_t c = 0; c < m; ++c) {
      const Rational a = T[i][c] / T[i][col], d = T[j][c] / T[j][col];
      if (a != d) return a < d;
    }
    return false;
  };
  // z0 enters: the row of the lexicographically least (b_i, e_i) / 1 leaves (the most negative b)
  std::size_t row = 0;
  for (std::size_t i = 1; i < m; ++i) {
    // (ratio with column -d = -1: compare (b_i, e_i) directly)
    if (b[i] < b[row] || (b[i] == b[row] && i > row)) row = i;
  }
  std::size_t leaving = basis[row];
  pivot(row, z0);
  for (std::size_t iteration = 0; iteration < (std::size_t{1} << 20); ++iteration) {
    const std::size_t entering = leaving < m ? leaving + m : leaving - m;   // the complement
    std::size_t best = m;
    bool z0_ties = false;
    std::size_t z0_row = m;
    Rational least;
    for (std::size_t i = 0; i < m; ++i) {
      if (sgn(T[i][entering]) <= 0) continue;
      const Rational r = T[i][rhs] / T[i][entering];
      if (best == m || r < least) {
        least = r;
        best = i;
      } else if (r == least && lex_less(i, best, entering)) {
        best = i;
      }
      if (basis[i] == z0) z0_row = i;
    }
    if (best == m) {   // ray termination
      if (ray) *ray = true;
      return std::nullopt;
    }
    if (z0_row != m && T[z0_row][rhs] / T[z0_row][entering] == least) {
      best = z0_row;
      z0_ties = true;
    }
    leaving = basis[best];
    pivot(best, entering);
    if (z0_ties || leaving == z0) {
      for (std::size_t i = 0; i < m; ++i) {
        s.lambda[i] = 0;
        s.w[i] = 0;
      }
      for (std::size_t i = 0; i < m; ++i) {
        if (basis[i] < m) s.w[basis[i]] = T[i][rhs];
        else if (basis[i] < 2 * m) s.lambda[basis[i] - m] = T[i][rhs];
      }
      return s;
    }
  }
  return std::nullopt;
}

}  // namespace hipair::simulation
