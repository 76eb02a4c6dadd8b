// HIPAIR — the linear complementarity problem of contact forces and impacts (docs/simulation.md):
//   find lambda >= 0 with w = A lambda + b >= 0 and lambda_k w_k = 0 for every k,
// where A = G M^-1 G^T (symmetric positive semidefinite: the contacts' Delassus matrix) and b the
// contacts' free normal accelerations (forces) or (1 + e) normal speeds (impacts). Two principled
// solvers: enumeration of the active sets (exact up to the linear solves; the smallest set first,
// and within a set the minimum-norm multipliers, so that redundant contacts share a load
// symmetrically) for the small problems of a mechanism, and Lemke's complementary pivoting
// (covering vector 1, lexicographic-free minimum-ratio test with a tolerance) beyond.
// Internal to src/simulation (uses Eigen; no Eigen type crosses include/hipair).
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace hipair::simulation {

struct LcpSolution {
  Eigen::VectorXd lambda;   ///< >= 0
  Eigen::VectorXd w;        ///< A lambda + b
  bool solved = false;      ///< complementarity holds to the tolerance
  double tolerance = 0;     ///< the tolerance used (see lcp_tolerance)
};

/// Tolerance of the complementarity conditions, derived from the data: 1e-10 relative to the
/// larger of |b| and |A| times the multipliers' natural scale |b| / max diag A (a solution's
/// residuals are round-off of a solve with those magnitudes, a few hundred ulps at most).
inline double lcp_tolerance(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  double bmax = b.size() ? b.cwiseAbs().maxCoeff() : 0.0;
  double amax = A.size() ? A.cwiseAbs().maxCoeff() : 0.0;
  double dmax = A.size() ? A.diagonal().cwiseAbs().maxCoeff() : 0.0;
  double lscale = dmax > 0 ? bmax / dmax : 0.0;
  return 1e-10 * std::max({bmax, amax * lscale, std::numeric_limits<double>::min()});
}

/// True when (lambda, w = A lambda + b) satisfies the LCP to `tol`.
/// `w`: storage for A lambda + b (overwritten).
inline bool lcp_satisfied(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& lambda, double tol,
                          Eigen::VectorXd& w) {
  w = A * lambda + b;
  double lmax = std::max(1.0, lambda.size() ? lambda.cwiseAbs().maxCoeff() : 0.0);
  for (Eigen::Index k = 0; k < b.size(); ++k) {
    if (lambda(k) < -tol * lmax || w(k) < -tol) return false;
    // complementarity: one of the two is zero (to the tolerance)
    if (lambda(k) > tol * lmax && std::abs(w(k)) > tol) return false;
  }
  return true;
}

inline bool lcp_satisfied(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& lambda, double tol) {
  Eigen::VectorXd w;
  return lcp_satisfied(A, b, lambda, tol, w);
}

/// Storage kept between calls of the enumeration (its `work` form; the simulator's Coulomb
/// enumeration solves one LCP per stick/slip assignment): every member is resized and written
/// on each use before it is read, by the same Eigen operations as the fresh objects of the value
/// form — the same doubles, without the allocations (docs/performance.md, "Session 60
/// (escape60)").
struct LcpWork {
  std::vector<bool> pick;
  std::vector<Eigen::Index> set;
  Eigen::VectorXd l, bs, ls, w;
  Eigen::MatrixXd As;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solve;
};

/// Active-set enumeration: every subset S (by decreasing size) with w_S = 0 solved for
/// lambda_S (complete orthogonal decomposition: minimum norm when A_SS is singular), accepted
/// when lambda >= 0, w >= 0 and the solve is consistent (w_S = 0). Exact for a P-matrix or a
/// positive semidefinite A with a solution. The largest consistent set first: where the
/// solution is not unique (redundant contacts, A singular), the minimum-norm multipliers over
/// the most contacts (a load shared symmetrically). 2^m subsets: for m <= 12.
inline void solve_lcp_enumeration(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, LcpWork& work, LcpSolution& s) {
  const Eigen::Index m = b.size();
  s.solved = false;
  s.tolerance = lcp_tolerance(A, b);
  s.lambda = Eigen::VectorXd::Zero(m);
  s.w = b;
  std::vector<bool>& pick = work.pick;
  std::vector<Eigen::Index>& set = work.set;
  Eigen::VectorXd& l = work.l;
  for (Eigen::Index size = m; size >= 0; --size) {
    // subsets of `size` elements in lexicographic order
    pick.assign(static_cast<std::size_t>(m), false);
    std::fill(pick.begin(), pick.begin() + size, true);
    do {
      set.clear();
      for (Eigen::Index k = 0; k < m; ++k)
        if (pick[static_cast<std::size_t>(k)]) set.push_back(k);
      l = Eigen::VectorXd::Zero(m);
      if (!set.empty()) {
        const auto n = static_cast<Eigen::Index>(set.size());
        Eigen::MatrixXd& As = work.As;
        Eigen::VectorXd& bs = work.bs;
        As.resize(n, n);
        bs.resize(n);
        for (Eigen::Index i = 0; i < n; ++i) {
          bs(i) = -b(set[i]);
          for (Eigen::Index j = 0; j < n; ++j) As(i, j) = A(set[i], set[j]);
        }
        // (As.completeOrthogonalDecomposition().solve(bs): the same decomposition, kept)
        work.solve.compute(As);
        work.ls = work.solve.solve(bs);
        for (Eigen::Index i = 0; i < n; ++i) l(set[i]) = work.ls(i);
      }
      if (lcp_satisfied(A, b, l, s.tolerance, work.w)) {
        s.lambda = l.cwiseMax(0.0);
        s.w = A * s.lambda + b;
        s.solved = true;
        return;
      }
    } while (std::prev_permutation(pick.begin(), pick.end()));
  }
}

inline LcpSolution solve_lcp_enumeration(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  LcpWork work;
  LcpSolution s;
  solve_lcp_enumeration(A, b, work, s);
  return s;
}

/// Lemke's complementary pivoting algorithm (Cottle, Pang & Stone, "The Linear Complementarity
/// Problem", 4.4) on the tableau [I  -A  -d | b] with covering vector d = 1: terminates with a
/// solution for a positive semidefinite A whenever the LCP is feasible (ray termination
/// otherwise: solved = false).
inline LcpSolution solve_lcp_lemke(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::Index m = b.size();
  LcpSolution s;
  s.tolerance = lcp_tolerance(A, b);
  s.lambda = Eigen::VectorXd::Zero(m);
  s.w = b;
  if (m == 0 || b.minCoeff() >= 0) {
    s.solved = true;
    return s;
  }
  // variables: w_0..w_{m-1} (0..m-1), lambda_0..lambda_{m-1} (m..2m-1), z0 (2m)
  Eigen::MatrixXd T(m, 2 * m + 2);
  T.setZero();
  T.block(0, 0, m, m) = Eigen::MatrixXd::Identity(m, m);
  T.block(0, m, m, m) = -A;
  T.col(2 * m) = -Eigen::VectorXd::Ones(m);
  T.col(2 * m + 1) = b;
  std::vector<Eigen::Index> basis(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i) basis[static_cast<std::size_t>(i)] = i;
  auto pivot = [&](Eigen::Index row, Eigen::Index col) {
    T.row(row) /= T(row, col);
    for (Eigen::Index i = 0; i < m; ++i)
      if (i != row && T(i, col) != 0) T.row(i) -= T(i, col) * T.row(row);
    basis[static_cast<std::size_t>(row)] = col;
  };
  Eigen::Index row;
  T.col(2 * m + 1).minCoeff(&row);
  Eigen::Index leaving = basis[static_cast<std::size_t>(row)];
  pivot(row, 2 * m);
  const double eps = 1e-12;
  for (int iteration = 0; iteration < 1000; ++iteration) {
    Eigen::Index entering = leaving < m ? leaving + m : leaving - m;   // the complement
    Eigen::Index best = -1;
    double ratio = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < m; ++i) {
      double a = T(i, entering);
      if (a > eps) {
        double r = T(i, 2 * m + 1) / a;
        // ties: prefer z0 leaving (termination)
        if (r < ratio - eps || (r <= ratio + eps && basis[static_cast<std::size_t>(i)] == 2 * m)) {
          ratio = r;
          best = i;
        }
      }
    }
    if (best < 0) return s;   // ray termination
    leaving = basis[static_cast<std::size_t>(best)];
    pivot(best, entering);
    if (leaving == 2 * m) {
      Eigen::VectorXd l = Eigen::VectorXd::Zero(m);
      for (Eigen::Index i = 0; i < m; ++i) {
        Eigen::Index v = basis[static_cast<std::size_t>(i)];
        if (v >= m && v < 2 * m) l(v - m) = T(i, 2 * m + 1);
      }
      s.lambda = l.cwiseMax(0.0);
      s.w = A * s.lambda + b;
      s.solved = lcp_satisfied(A, b, s.lambda, s.tolerance);
      return s;
    }
  }
  return s;
}

/// The contact LCP: enumeration up to 10 contacts, Lemke beyond (or when enumeration finds no
/// consistent set, e.g. a singular A whose minimum-norm solves all miss the cone).
/// solve_lcp() written into s, with `work` as the enumeration's storage.
inline void solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, LcpWork& work, LcpSolution& s) {
  if (b.size() <= 10) {
    solve_lcp_enumeration(A, b, work, s);
    if (s.solved) return;
  }
  s = solve_lcp_lemke(A, b);
}

inline LcpSolution solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  LcpWork work;
  LcpSolution s;
  solve_lcp(A, b, work, s);
  return s;
}

}  // namespace hipair::simulation
