// HIPAIR — the sign of a held contact's force, decided exactly on its rows (docs/simulation.md,
// "Session 62 (exact62): held contacts' force signs, exact").
//
// A simulator keeps a contact held (bilateral) while its multiplier is not negative; whether it is
// negative is a decision, so it is taken on exact numbers: the rows as the simulator's doubles give
// them at a state (every double the exact number it is), the multipliers of those rows solved
// first in certified intervals (kernels::Interval: interval Gaussian elimination encloses the
// exact solution while no pivot holds 0) and, where an enclosure holds 0 or a pivot is undecided,
// in exact rationals. No tolerance: a multiplier below 0 by any amount is negative; exactly 0 (a
// part resting against a stop with no load on it) is not, and the contact stays held.
// Internal to src/simulation (Eigen, GMP; no type of it crosses include/hipair).
#pragma once

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include "kernels/interval.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::simulation {

/// The held contacts' force problem as a simulator's doubles give it at a state: the rows J
/// (k x n: the gaps' derivatives over the n generalized coordinates), the mass matrix M (n x n,
/// symmetric positive definite), the generalized forces Q (n) and the rows' velocity terms kappa
/// (k). With M a = Q + J^T lambda the gaps' accelerations are J a + kappa = A lambda + b,
/// A = J M^-1 J^T, b = J M^-1 Q + kappa. The bilateral multipliers solve A lambda = -b: the
/// minimum-norm solution where A is singular (dependent rows), the least-squares one where -b is
/// not in A's range (A^+ (-b), as the simulators' complete orthogonal decomposition gives it).
struct HeldForceRows {
  Eigen::MatrixXd J, M;
  Eigen::VectorXd Q, kappa;
};

/// How the decisions were taken (a test's count): by the interval filter alone, or in rationals.
struct HeldForceCount {
  std::size_t filtered = 0, exact = 0;
};

namespace held_force_detail {

template <typename T>
using Matrix = std::vector<std::vector<T>>;

inline bool nonzero(const Rational& v) { return sgn(v) != 0; }
inline bool nonzero(const kernels::Interval& v) { return v.lo > 0.0 || v.hi < 0.0; }
// a pivot's size for the choice among the rows (any nonzero pivot is exact for rationals: the first)
inline double magnitude(const Rational&) { return 1.0; }
inline double magnitude(const kernels::Interval& v) { return std::min(std::abs(v.lo), std::abs(v.hi)); }

/// X with A X = B (A n x n, B n x m) by Gauss–Jordan elimination with row pivoting; none when no
/// pivot is certainly nonzero (A singular, or an interval pivot holding 0).
template <typename T>
std::optional<Matrix<T>> solve(Matrix<T> A, Matrix<T> B) {
  const std::size_t n = A.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t best = n;
    for (std::size_t r = c; r < n; ++r)
      if (nonzero(A[r][c]) && (best == n || magnitude(A[r][c]) > magnitude(A[best][c]))) best = r;
    if (best == n) return std::nullopt;
    std::swap(A[c], A[best]);
    std::swap(B[c], B[best]);
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const T f = A[r][c] / A[c][c];
      for (std::size_t k = c; k < n; ++k) A[r][k] = A[r][k] - f * A[c][k];
      for (std::size_t k = 0; k < B[r].size(); ++k) B[r][k] = B[r][k] - f * B[c][k];
    }
  }
  for (std::size_t r = 0; r < n; ++r)
    for (auto& v : B[r]) v = v / A[r][r];
  return B;
}

// the doubles as exact rationals, and as point intervals
inline Rational exact_value(double v) {
  if (!std::isfinite(v)) throw NumericError("a held contact's force problem is not finite (a row, a mass or a load)");
  return Rational(v);
}
inline kernels::Interval point_interval(double v) { return kernels::Interval::point(v); }

/// A = J M^-1 J^T and b = J M^-1 Q + kappa over the rows `set`, in T (none: M's elimination undecided).
template <typename T, typename Convert>
std::optional<std::pair<Matrix<T>, std::vector<T>>> delassus(const HeldForceRows& p, const std::vector<std::size_t>& set,
                                                            Convert convert) {
  const auto n = static_cast<std::size_t>(p.M.rows());
  const std::size_t k = set.size();
  Matrix<T> M(n, std::vector<T>(n)), rhs(n, std::vector<T>(k + 1));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) M[i][j] = convert(p.M(Eigen::Index(i), Eigen::Index(j)));
    for (std::size_t r = 0; r < k; ++r) rhs[i][r] = convert(p.J(Eigen::Index(set[r]), Eigen::Index(i)));
    rhs[i][k] = convert(p.Q(Eigen::Index(i)));
  }
  const std::optional<Matrix<T>> X = solve(std::move(M), std::move(rhs));   // M^-1 [J^T Q]
  if (!X) return std::nullopt;
  Matrix<T> A(k, std::vector<T>(k));
  std::vector<T> b(k);
  for (std::size_t r = 0; r < k; ++r) {
    std::vector<T> row(n);
    for (std::size_t i = 0; i < n; ++i) row[i] = convert(p.J(Eigen::Index(set[r]), Eigen::Index(i)));
    for (std::size_t c = 0; c < k; ++c) {
      T sum = T(0);
      for (std::size_t i = 0; i < n; ++i) sum = sum + row[i] * (*X)[i][c];
      A[r][c] = sum;
    }
    T sum = convert(p.kappa(Eigen::Index(set[r])));
    for (std::size_t i = 0; i < n; ++i) sum = sum + row[i] * (*X)[i][k];
    b[r] = sum;
  }
  return std::pair{std::move(A), std::move(b)};
}

/// The exact minimum-norm (least-squares) solution of A lambda = -b, A symmetric positive
/// semidefinite: lambda = C (C^T A C)^-1 C^T (-b) with C a basis of A's range (its independent
/// columns, found by exact elimination). C^T A C is positive definite, lambda lies in A's range and
/// A lambda is -b's projection onto it: lambda = A^+ (-b). With A regular, C = A and lambda = A^-1 (-b).
inline std::vector<Rational> minimum_norm(const Matrix<Rational>& A, const std::vector<Rational>& b) {
  const std::size_t k = A.size();
  // the independent columns: row echelon form of a copy
  Matrix<Rational> E = A;
  std::vector<std::size_t> columns;
  std::size_t row = 0;
  for (std::size_t c = 0; c < k && row < k; ++c) {
    std::size_t r = row;
    while (r < k && sgn(E[r][c]) == 0) ++r;
    if (r == k) continue;
    std::swap(E[r], E[row]);
    for (std::size_t i = row + 1; i < k; ++i) {
      if (sgn(E[i][c]) == 0) continue;
      const Rational f = E[i][c] / E[row][c];
      for (std::size_t j = c; j < k; ++j) E[i][j] -= f * E[row][j];
    }
    columns.push_back(c);
    ++row;
  }
  const std::size_t r = columns.size();
  std::vector<Rational> lambda(k, Rational(0));
  if (r == 0) return lambda;   // A = 0: the minimum norm is 0
  // AC = A C (k x r), G = C^T A C = C^T (A C) (r x r), h = C^T (-b)
  Matrix<Rational> AC(k, std::vector<Rational>(r));
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < r; ++j) {
      Rational sum = 0;
      for (std::size_t l = 0; l < k; ++l) sum += A[i][l] * A[l][columns[j]];
      AC[i][j] = sum;
    }
  Matrix<Rational> G(r, std::vector<Rational>(r)), h(r, std::vector<Rational>(1));
  for (std::size_t i = 0; i < r; ++i) {
    for (std::size_t j = 0; j < r; ++j) {
      Rational sum = 0;
      for (std::size_t l = 0; l < k; ++l) sum += A[l][columns[i]] * AC[l][j];
      G[i][j] = sum;
    }
    Rational sum = 0;
    for (std::size_t l = 0; l < k; ++l) sum -= A[l][columns[i]] * b[l];
    h[i][0] = sum;
  }
  const std::optional<Matrix<Rational>> mu = solve(std::move(G), std::move(h));
  if (!mu) throw NumericError("a held contact's force problem: the range basis is singular (internal)");
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < r; ++j) lambda[i] += A[i][columns[j]] * (*mu)[j][0];
  return lambda;
}

inline std::vector<std::size_t> all_rows(const HeldForceRows& p) {
  std::vector<std::size_t> set(static_cast<std::size_t>(p.J.rows()));
  for (std::size_t i = 0; i < set.size(); ++i) set[i] = i;
  return set;
}

inline std::pair<Matrix<Rational>, std::vector<Rational>> exact_delassus(const HeldForceRows& p,
                                                                        const std::vector<std::size_t>& set) {
  auto out = delassus<Rational>(p, set, [](double v) { return exact_value(v); });
  if (!out) throw NumericError("a held contact's force problem: the mass matrix is singular");
  return std::move(*out);
}

}  // namespace held_force_detail

/// The exact minimum-norm bilateral multipliers of the rows (held_force_signs' exact path; a
/// test's oracle of the LCP's forces).
inline std::vector<Rational> exact_held_multipliers(const HeldForceRows& p) {
  using namespace held_force_detail;
  const auto [A, b] = exact_delassus(p, all_rows(p));
  return minimum_norm(A, b);
}

/// The signs (-1, 0, +1) of the held contacts' bilateral multipliers, exactly on the rows: the
/// interval filter first (A and b enclosed from the rows' doubles, the system solved by interval
/// elimination: decided when no pivot and no multiplier's enclosure holds 0, or an enclosure is
/// the point 0), the exact rationals where it does not decide.
inline std::vector<int> held_force_signs(const HeldForceRows& p, HeldForceCount* count = nullptr) {
  using namespace held_force_detail;
  using kernels::Interval;
  const std::vector<std::size_t> set = all_rows(p);
  const std::size_t k = set.size();
  std::vector<int> signs(k, 0);
  if (k == 0) return signs;
  if (const auto filtered = delassus<Interval>(p, set, [](double v) { return point_interval(v); })) {
    Matrix<Interval> minus_b(k, std::vector<Interval>(1));
    for (std::size_t i = 0; i < k; ++i) minus_b[i][0] = -filtered->second[i];
    if (const auto lambda = solve(filtered->first, std::move(minus_b))) {
      bool decided = true;
      for (std::size_t i = 0; i < k && decided; ++i) {
        const int s = (*lambda)[i][0].sign();
        decided = s != 2;
        signs[i] = s;
      }
      if (decided) {
        if (count) ++count->filtered;
        return signs;
      }
    }
  }
  if (count) ++count->exact;
  const std::vector<Rational> lambda = exact_held_multipliers(p);
  for (std::size_t i = 0; i < k; ++i) signs[i] = sgn(lambda[i]);
  return signs;
}

/// Which held contacts stay held when a multiplier is negative: the contact LCP (lambda >= 0,
/// w = A lambda + b >= 0, lambda_i w_i = 0) solved exactly on the rows by enumeration of the held
/// sets S, by decreasing size and in lexicographic order within a size (as solve_lcp_enumeration):
/// lambda_S the exact minimum-norm multipliers of S, accepted when lambda_S >= 0, w_S = 0 and
/// w_j >= 0 off S. A multiplier exactly 0 in S, or a w_j exactly 0 off S, is a tie the larger set
/// takes first (held with zero force). None when no set is consistent (2^k sets; k <= 12).
inline std::optional<std::vector<bool>> held_after_lift_off(const HeldForceRows& p) {
  using namespace held_force_detail;
  const std::vector<std::size_t> rows = all_rows(p);
  const std::size_t m = rows.size();
  if (m > 12) return std::nullopt;
  const auto [A, b] = exact_delassus(p, rows);
  std::vector<bool> pick;
  for (std::size_t size = m + 1; size-- > 0;) {
    pick.assign(m, false);
    std::fill(pick.begin(), pick.begin() + static_cast<std::ptrdiff_t>(size), true);
    do {
      std::vector<std::size_t> set;
      for (std::size_t i = 0; i < m; ++i)
        if (pick[i]) set.push_back(i);
      Matrix<Rational> As(set.size(), std::vector<Rational>(set.size()));
      std::vector<Rational> bs(set.size());
      for (std::size_t i = 0; i < set.size(); ++i) {
        bs[i] = b[set[i]];
        for (std::size_t j = 0; j < set.size(); ++j) As[i][j] = A[set[i]][set[j]];
      }
      const std::vector<Rational> ls = set.empty() ? std::vector<Rational>{} : minimum_norm(As, bs);
      std::vector<Rational> lambda(m, Rational(0));
      bool ok = true;
      for (std::size_t i = 0; i < set.size() && ok; ++i) {
        lambda[set[i]] = ls[i];
        ok = sgn(ls[i]) >= 0;
      }
      for (std::size_t i = 0; i < m && ok; ++i) {
        Rational w = b[i];
        for (std::size_t j = 0; j < m; ++j) w += A[i][j] * lambda[j];
        ok = pick[i] ? sgn(w) == 0 : sgn(w) >= 0;
      }
      if (ok) return pick;
    } while (std::prev_permutation(pick.begin(), pick.end()));
  }
  return std::nullopt;
}

}  // namespace hipair::simulation
