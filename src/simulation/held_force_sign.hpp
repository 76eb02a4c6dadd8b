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
#include "simulation/exact_elimination.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

namespace hipair::simulation {

/// The held contacts' force problem as a simulator's doubles give it at a state: the rows J
/// (k x n: the gaps' derivatives over the n generalized coordinates), the mass matrix M (n x n,
/// symmetric positive definite), the generalized forces Q (n) and the rows' velocity terms kappa
/// (k). With M a = Q + J^T lambda the gaps' accelerations are J a + kappa = A lambda + b,
/// A = J M^-1 J^T, b = J M^-1 Q + kappa. The bilateral multipliers solve A lambda = -b: the
/// minimum-norm solution where A is singular (dependent rows), the least-squares one where -b is
/// not in A's range (A^+ (-b), as the simulators' complete orthogonal decomposition gives it).
///
/// Frictional problems (friction.hpp's held_verdict) give two more things: force rows W (k x n)
/// distinct from J — a contact sliding with kinetic friction pushes along W_k = J_k - sign mu_k T_k
/// while its gap keeps J_k: then A = J M^-1 W^T, not symmetric — and a diagonal mass matrix by
/// its inverse `minv` (0 for a driven coordinate) with the free accelerations a0 = M^-1 Q (then
/// M and Q are not read): b = J a0 + kappa.
struct HeldForceRows {
  Eigen::MatrixXd J, M;
  Eigen::VectorXd Q, kappa;
  Eigen::MatrixXd W;           ///< force rows (empty: W = J)
  /// A sliding contact's force row formed exactly (session 67, impact67; empty: W's doubles):
  /// per force row r < slip.size() with slip[r] != 0, W_r = J_r - slip[r] (mu[r] / s[r]) T_r in
  /// the decision's arithmetic (rationals; intervals enclosing it), T_r the row r of `tangent`.
  std::vector<int> slip;
  Eigen::VectorXd slip_mu, slip_s;
  Eigen::MatrixXd tangent;
  Eigen::VectorXd minv, a0;    ///< the diagonal form (empty: M and Q)
  std::size_t equalities = 0;  ///< the last rows: sticking tangent rows (solve_with_equalities)
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
  // (session 70, speed70: rationals by fraction-free elimination, the same exact answer; a
  // single row stays rational: one division, where the integer route's set-up costs more)
  if constexpr (std::is_same_v<T, Rational>)
    if (fraction_free() && A.size() >= 2 && B.size() == A.size() &&
        std::all_of(B.begin(), B.end(), [&](const std::vector<T>& row) { return row.size() == B.front().size(); }))
      return fraction_free_solve(A, B);
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

/// The force row r's entry i in T: W's double, or a sliding contact's row formed in T from its
/// doubles (HeldForceRows::slip): J_ri - sign (mu / s) T_ri, exact in rationals, enclosed in intervals.
template <typename T, typename Convert>
T force_entry(const HeldForceRows& p, std::size_t r, std::size_t i, Convert convert) {
  const auto ri = Eigen::Index(r), ii = Eigen::Index(i);
  if (r < p.slip.size() && p.slip[r] != 0) {
    if (p.tangent(ri, ii) == 0) return convert(p.J(ri, ii));
    return convert(p.J(ri, ii)) -
           convert(static_cast<double>(p.slip[r])) * (convert(p.slip_mu(ri)) / convert(p.slip_s(ri))) * convert(p.tangent(ri, ii));
  }
  return convert(p.W.size() > 0 ? p.W(ri, ii) : p.J(ri, ii));
}

/// A = J M^-1 W^T and b = J M^-1 Q + kappa over the rows `set`, in T (none: M's elimination undecided).
template <typename T, typename Convert>
std::optional<std::pair<Matrix<T>, std::vector<T>>> delassus(const HeldForceRows& p, const std::vector<std::size_t>& set,
                                                            Convert convert) {
  const bool diagonal = p.minv.size() > 0;
  const auto n = static_cast<std::size_t>(p.J.cols());
  const std::size_t k = set.size();
  Matrix<T> M(n, std::vector<T>(n)), rhs(n, std::vector<T>(k + 1));
  for (std::size_t i = 0; i < n; ++i) {
    if (!diagonal)
      for (std::size_t j = 0; j < n; ++j) M[i][j] = convert(p.M(Eigen::Index(i), Eigen::Index(j)));
    for (std::size_t r = 0; r < k; ++r) rhs[i][r] = force_entry<T>(p, set[r], i, convert);
    rhs[i][k] = convert(diagonal ? p.a0(Eigen::Index(i)) : p.Q(Eigen::Index(i)));
  }
  std::optional<Matrix<T>> X;   // M^-1 [W^T Q]
  if (diagonal) {
    for (std::size_t i = 0; i < n; ++i) {
      const T minv = convert(p.minv(Eigen::Index(i)));
      for (std::size_t r = 0; r < k; ++r) rhs[i][r] = minv * rhs[i][r];   // (a0 is M^-1 Q already)
    }
    X = std::move(rhs);
  } else {
    X = solve(std::move(M), std::move(rhs));
  }
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

/// The exact minimum-norm least-squares solution of A lambda = -b, lambda = A^+ (-b), by a
/// full-rank factorization: with C A's independent columns and R its independent rows (exact
/// elimination, exact_elimination.hpp), A^+ = R^T (C^T A R^T)^-1 C^T (C^T A R^T is regular).
/// Symmetric A (frictionless rows): R = C^T and lambda = C (C^T A C)^-1 C^T (-b). With A
/// regular, lambda = A^-1 (-b).
inline std::vector<Rational> minimum_norm(const Matrix<Rational>& A, const std::vector<Rational>& b) {
  const std::size_t k = A.size();
  Matrix<Rational> E = A;
  const std::vector<std::size_t> columns = row_echelon(E, k);
  const std::size_t r = columns.size();
  std::vector<Rational> lambda(k, Rational(0));
  if (r == 0) return lambda;   // A = 0: the minimum norm is 0
  bool symmetric = true;
  for (std::size_t i = 0; i < k && symmetric; ++i)
    for (std::size_t j = 0; j < i && symmetric; ++j) symmetric = A[i][j] == A[j][i];
  std::vector<std::size_t> rows = columns;   // A's independent rows (columns of A^T)
  if (!symmetric) {
    Matrix<Rational> Et(k, std::vector<Rational>(k));
    for (std::size_t i = 0; i < k; ++i)
      for (std::size_t j = 0; j < k; ++j) Et[i][j] = A[j][i];
    rows = row_echelon(Et, k);
  }
  // ART = A R^T (k x r), G = C^T A R^T (r x r), h = C^T (-b)
  Matrix<Rational> ART(k, std::vector<Rational>(r));
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < r; ++j) {
      Rational sum = 0;
      for (std::size_t l = 0; l < k; ++l) sum += A[i][l] * A[rows[j]][l];
      ART[i][j] = sum;
    }
  Matrix<Rational> G(r, std::vector<Rational>(r)), h(r, std::vector<Rational>(1));
  for (std::size_t i = 0; i < r; ++i) {
    for (std::size_t j = 0; j < r; ++j) {
      Rational sum = 0;
      for (std::size_t l = 0; l < k; ++l) sum += A[l][columns[i]] * ART[l][j];
      G[i][j] = sum;
    }
    Rational sum = 0;
    for (std::size_t l = 0; l < k; ++l) sum -= A[l][columns[i]] * b[l];
    h[i][0] = sum;
  }
  const std::optional<Matrix<Rational>> mu = solve(std::move(G), std::move(h));
  if (!mu) throw NumericError("a held contact's force problem: the range basis is singular (internal)");
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < r; ++j) lambda[i] += A[rows[j]][i] * (*mu)[j][0];
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

namespace held_force_detail {

/// The multipliers of A lambda = -b whose last `equalities` rows are sticking tangent rows
/// (friction.hpp's frictional_rows): those rows' forces first, lambda after, as the doubles'
/// reduce() and solve_bilateral() take them — with K the tangent rows' block, D and E the
/// couplings, c and b_G the right-hand sides: f = -K^+ (c + D lambda) and lambda the minimum-norm
/// solution of (A_GG - E K^+ D) lambda = -(b_G - E K^+ c). Where the rows are dependent (a normal
/// row that the sticking rows already hold: a pusher's face along a sticking block's ground) the
/// sticking rows carry the load and the normal multipliers only what they leave — the doubles'
/// convention, exactly (a joint minimum norm would split it between them). Without equalities:
/// the minimum-norm solution. Regular systems have one solution, whatever the order.
inline std::vector<Rational> solve_with_equalities(const Matrix<Rational>& A, const std::vector<Rational>& b,
                                                   std::size_t equalities) {
  if (equalities == 0) return minimum_norm(A, b);
  const std::size_t total = A.size(), k = total - equalities, p = equalities;
  Matrix<Rational> K(p, std::vector<Rational>(p));
  std::vector<Rational> c(p);
  for (std::size_t i = 0; i < p; ++i) {
    c[i] = b[k + i];
    for (std::size_t j = 0; j < p; ++j) K[i][j] = A[k + i][k + j];
  }
  const std::vector<Rational> f0 = minimum_norm(K, c);   // -K^+ c
  Matrix<Rational> F(p, std::vector<Rational>(k));      // -K^+ D
  for (std::size_t j = 0; j < k; ++j) {
    std::vector<Rational> d(p);
    for (std::size_t i = 0; i < p; ++i) d[i] = A[k + i][j];
    const std::vector<Rational> column = minimum_norm(K, d);
    for (std::size_t i = 0; i < p; ++i) F[i][j] = column[i];
  }
  Matrix<Rational> reduced(k, std::vector<Rational>(k));
  std::vector<Rational> reduced_b(k);
  for (std::size_t i = 0; i < k; ++i) {
    reduced_b[i] = b[i];
    for (std::size_t l = 0; l < p; ++l) reduced_b[i] += A[i][k + l] * f0[l];
    for (std::size_t j = 0; j < k; ++j) {
      reduced[i][j] = A[i][j];
      for (std::size_t l = 0; l < p; ++l) reduced[i][j] += A[i][k + l] * F[l][j];
    }
  }
  std::vector<Rational> out = k > 0 ? minimum_norm(reduced, reduced_b) : std::vector<Rational>{};
  out.resize(total);
  for (std::size_t i = 0; i < p; ++i) {
    out[k + i] = f0[i];
    for (std::size_t j = 0; j < k; ++j) out[k + i] += F[i][j] * out[j];
  }
  return out;
}

}  // namespace held_force_detail

/// The exact bilateral multipliers of the rows (held_force_signs' exact path; a test's oracle of
/// the LCP's forces): minimum-norm, the `equalities` last rows' first (solve_with_equalities).
inline std::vector<Rational> exact_held_multipliers(const HeldForceRows& p) {
  using namespace held_force_detail;
  const auto [A, b] = exact_delassus(p, all_rows(p));
  return solve_with_equalities(A, b, p.equalities);
}

/// A decision on the exact multipliers of the rows (every row's, in order), taken first on their
/// enclosures and, where those do not decide, on the exact rationals: `decide` is called with a
/// std::vector<kernels::Interval> (the system A lambda = -b enclosed from the rows' doubles and
/// solved by interval elimination; not called when a pivot's enclosure holds 0) and returns an
/// empty optional when the enclosures do not decide; then it is called with the exact
/// minimum-norm multipliers (std::vector<Rational>) and must decide. `exact_sign` and
/// `nonnegative_part` / `magnitude_of` below are the comparisons both kinds share.
template <typename Decide>
auto decide_on_multipliers(const HeldForceRows& p, Decide decide, HeldForceCount* count = nullptr)
    -> std::decay_t<decltype(*decide(std::vector<Rational>{}))> {
  using namespace held_force_detail;
  using kernels::Interval;
  const std::vector<std::size_t> set = all_rows(p);
  const std::size_t k = set.size();
  if (k == 0) return std::move(*decide(std::vector<Rational>{}));   // nothing held: nothing counted
  if (const auto filtered = delassus<Interval>(p, set, [](double v) { return point_interval(v); })) {
    Matrix<Interval> minus_b(k, std::vector<Interval>(1));
    for (std::size_t i = 0; i < k; ++i) minus_b[i][0] = -filtered->second[i];
    if (const auto lambda = solve(filtered->first, std::move(minus_b))) {
      std::vector<Interval> x(k);
      for (std::size_t i = 0; i < k; ++i) x[i] = (*lambda)[i][0];
      if (auto decided = decide(x)) {
        if (count) ++count->filtered;
        return std::move(*decided);
      }
    }
  }
  if (count) ++count->exact;
  return std::move(*decide(exact_held_multipliers(p)));
}

/// The sign of an enclosure (2: it holds 0 and is not {0}) or of an exact value.
inline int exact_sign(const kernels::Interval& v) { return v.sign(); }
inline int exact_sign(const Rational& v) { return sgn(v); }
/// max(v, 0) and |v|, enclosed or exact.
inline kernels::Interval nonnegative_part(const kernels::Interval& v) {
  return kernels::Interval(std::max(v.lo, 0.0), std::max(v.hi, 0.0));
}
inline Rational nonnegative_part(const Rational& v) { return sgn(v) > 0 ? v : Rational(0); }
inline kernels::Interval magnitude_of(const kernels::Interval& v) {
  if (v.lo >= 0) return v;
  if (v.hi <= 0) return -v;
  return kernels::Interval(0.0, std::max(-v.lo, v.hi));
}
inline Rational magnitude_of(const Rational& v) { return abs(v); }

/// The sign of a . b for vectors of doubles, exactly: the double sum decides when it exceeds its
/// rounding bound (products and sums: gamma_2n sum |a_i b_i|, plus the products' underflow, n
/// half subnormal units each), else the exact rationals.
inline int exact_dot_sign(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double sum = 0, magnitude = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    sum += a(i) * b(i);
    magnitude += std::abs(a(i) * b(i));
  }
  if (std::isfinite(magnitude)) {
    const double n = static_cast<double>(2 * a.size() + 2);
    const double bound = n * 0x1p-52 * magnitude + n * std::numeric_limits<double>::denorm_min();
    if (sum > bound) return 1;
    if (sum < -bound) return -1;
  }
  Rational exact = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    exact += held_force_detail::exact_value(a(i)) * held_force_detail::exact_value(b(i));
  return sgn(exact);
}

/// The signs (-1, 0, +1) of the held contacts' bilateral multipliers, exactly on the rows: the
/// interval filter first (A and b enclosed from the rows' doubles, the system solved by interval
/// elimination: decided when no pivot and no multiplier's enclosure holds 0, or an enclosure is
/// the point 0), the exact rationals where it does not decide.
inline std::vector<int> held_force_signs(const HeldForceRows& p, HeldForceCount* count = nullptr) {
  return decide_on_multipliers(
      p,
      [](const auto& lambda) -> std::optional<std::vector<int>> {
        std::vector<int> signs(lambda.size());
        for (std::size_t i = 0; i < lambda.size(); ++i)
          if ((signs[i] = exact_sign(lambda[i])) == 2) return std::nullopt;
        return signs;
      },
      count);
}

/// Which held contacts stay held when a multiplier is negative: the contact LCP (lambda >= 0,
/// w = A lambda + b >= 0, lambda_i w_i = 0) solved exactly on the rows by enumeration of the held
/// sets S, by decreasing size and in lexicographic order within a size (as solve_lcp_enumeration):
/// lambda_S the exact minimum-norm multipliers of S, accepted when lambda_S >= 0, w_S = 0 and
/// w_j >= 0 off S. A multiplier exactly 0 in S, or a w_j exactly 0 off S, is a tie the larger set
/// takes first (held with zero force). None when no set is consistent (2^k sets; k <= 12).
/// `companion` (frictional rows, friction.hpp): rows beyond the first `contacts` are equalities
/// (a sticking contact's tangent row) with a free multiplier, held exactly while the contact
/// companion[j - contacts] is: they take part in every set that contact is in, and are not
/// enumerated. The result has one entry per contact row.
namespace held_force_detail {

/// Whether the held set `pick` (one entry per contact row; companions held with their contact)
/// solves the contact LCP exactly on A, b: its exact multipliers (solve_with_equalities) >= 0,
/// its gaps' accelerations exactly 0 on it and >= 0 off it, its companion equalities exactly 0.
inline bool consistent_set(const Matrix<Rational>& A, const std::vector<Rational>& b, std::size_t m,
                           const std::vector<std::size_t>& companion, const std::vector<bool>& pick) {
  const std::size_t total = A.size();
  std::vector<std::size_t> set;
  std::vector<bool> in(total, false);
  for (std::size_t i = 0; i < total; ++i)
    if (in[i] = i < m ? bool(pick[i]) : bool(pick[companion[i - m]]); in[i]) set.push_back(i);
  Matrix<Rational> As(set.size(), std::vector<Rational>(set.size()));
  std::vector<Rational> bs(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    bs[i] = b[set[i]];
    for (std::size_t j = 0; j < set.size(); ++j) As[i][j] = A[set[i]][set[j]];
  }
  std::size_t equalities = 0;   // (the companions come last in the set)
  for (const std::size_t i : set) equalities += i >= m;
  const std::vector<Rational> ls = set.empty() ? std::vector<Rational>{} : solve_with_equalities(As, bs, equalities);
  std::vector<Rational> lambda(total, Rational(0));
  for (std::size_t i = 0; i < set.size(); ++i) {
    lambda[set[i]] = ls[i];
    if (set[i] < m && sgn(ls[i]) < 0) return false;
  }
  for (std::size_t i = 0; i < total; ++i) {
    if (i >= m && !in[i]) continue;
    Rational w = b[i];
    for (std::size_t j = 0; j < total; ++j) w += A[i][j] * lambda[j];
    if ((i >= m || pick[i]) ? sgn(w) != 0 : sgn(w) < 0) return false;
  }
  return true;
}

}  // namespace held_force_detail

inline std::optional<std::vector<bool>> held_after_lift_off(const HeldForceRows& p,
                                                           const std::vector<std::size_t>& companion = {}) {
  using namespace held_force_detail;
  const std::vector<std::size_t> rows = all_rows(p);
  const std::size_t total = rows.size(), m = total - companion.size();
  if (m > 12) return std::nullopt;
  const auto [A, b] = exact_delassus(p, rows);
  std::vector<bool> pick;
  for (std::size_t size = m + 1; size-- > 0;) {
    pick.assign(m, false);
    std::fill(pick.begin(), pick.begin() + static_cast<std::ptrdiff_t>(size), true);
    do {
      if (consistent_set(A, b, m, companion, pick)) return pick;
    } while (std::prev_permutation(pick.begin(), pick.end()));
  }
  return std::nullopt;
}

}  // namespace hipair::simulation
