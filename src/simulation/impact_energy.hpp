#pragma once
// The exact energy balance of a frictionless impact (session 75, jam75; Issue 11, review74 H1).
// Internal to src/simulation (Eigen; no type of it crosses include/hipair).
//
// An impact with Newton's restitution e <= 1 may give the free parts kinetic energy only as the
// prescribed drivers' work: K_after - K_before <= W, with K = 1/2 sum_i x_i^2 / minv_i over the
// coordinates with minv_i > 0 and W = -sum_i v_i (G^T lambda)_i over the drivers' coordinates
// (minv_i = 0: their velocity v_i is kept, and the impulse G^T lambda the contacts put on them is
// what their motors answer — W is the work those motors do on the rest, through the contacts).
// Decided exactly on the impact's exact solution: the held set the exact decision chose (the rows
// whose published multiplier is positive — exact_impact_lcp's solution, its exact multipliers
// rounded, keeps their signs), its multipliers solved exactly from w_H = 0, i.e.
// J_H M^-1 J_H^T lambda_H = -(J_H v + h_H) in rationals on the doubles J, minv, v and the exact
// restitution terms h, and x = v + M^-1 J_H^T lambda_H exactly — the law itself, not its rounding,
// so an elastic impact that keeps the energy exactly (e = 1) is not read as creating some by the
// doubles' round-off. (friction.hpp's FrictionalSolution keeps x_exact but not the multipliers;
// solving the held set again here keeps that widely included header unchanged.)
//
// For the LCP form of the planar impacts (w = G x + e G v >= 0 on every row, lambda >= 0, lambda w
// = 0) the excess is exactly sum_r lambda_r (1 - e_r) (G v)_r / 2: with one restitution for every
// row it is -(1 - e) / (2 (1 + e)) lambda^T A lambda <= 0 (A = G M^-1 G^T positive semidefinite),
// so a gain can come only from rows of different restitutions at which a contact separating
// before the impact (G v > 0) is given an impulse. The check does not rely on that identity: it
// compares the energies and the drivers' work themselves.
#include "simulation/held_force_sign.hpp"

#include <Eigen/Dense>

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::simulation {

struct ImpactEnergy {
  Rational kinetic_before, kinetic_after;   ///< 1/2 sum_i x_i^2 / minv_i over minv_i > 0
  Rational driver_work;                     ///< the drivers' work on the rest through the contacts
  std::vector<Rational> multipliers;        ///< the exact impulses per row (0 off the held set)
  /// K_after - K_before - W: positive where the impact creates energy
  Rational excess() const { return kinetic_after - kinetic_before - driver_work; }
};

/// The exact energy balance of an impact (rows G, inverse masses minv, 0 for a driver, velocities
/// before v, exact restitution terms h) whose held set is the rows where `published` — the
/// multipliers published, exact_impact_lcp's decision — is positive; nullopt where it cannot be
/// formed exactly: the held set's rows dependent (J_H M^-1 J_H^T singular: the multipliers are not
/// unique), or a multiplier solved not positive (not that held set's solution).
inline std::optional<ImpactEnergy> impact_energy(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv,
                                                 const Eigen::VectorXd& v, const std::vector<Rational>& h,
                                                 const Eigen::VectorXd& published) {
  const auto m = static_cast<std::size_t>(G.rows()), n = static_cast<std::size_t>(G.cols());
  if (static_cast<std::size_t>(published.size()) != m || h.size() != m) return std::nullopt;
  using held_force_detail::exact_value;
  std::vector<std::size_t> held;
  for (std::size_t r = 0; r < m; ++r)
    if (published(static_cast<Eigen::Index>(r)) > 0) held.push_back(r);
  std::vector<Rational> vq(n), mi(n);
  for (std::size_t i = 0; i < n; ++i) {
    vq[i] = exact_value(v(static_cast<Eigen::Index>(i)));
    mi[i] = exact_value(minv(static_cast<Eigen::Index>(i)));
  }
  auto g = [&](std::size_t r, std::size_t i) {
    return exact_value(G(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)));
  };
  const std::size_t k = held.size();
  std::vector<Rational> lambda(k, Rational(0));
  if (k > 0) {
    held_force_detail::Matrix<Rational> A(k, std::vector<Rational>(k, Rational(0))), B(k, std::vector<Rational>(1));
    for (std::size_t a = 0; a < k; ++a) {
      Rational rhs = -h[held[a]];
      for (std::size_t i = 0; i < n; ++i) {
        const Rational ga = g(held[a], i);
        if (sgn(ga) == 0) continue;
        rhs -= ga * vq[i];
        if (sgn(mi[i]) == 0) continue;
        for (std::size_t b = 0; b < k; ++b) A[a][b] += ga * mi[i] * g(held[b], i);
      }
      B[a][0] = rhs;
    }
    const std::optional<held_force_detail::Matrix<Rational>> solved = held_force_detail::solve(A, B);
    if (!solved) return std::nullopt;
    for (std::size_t a = 0; a < k; ++a) {
      lambda[a] = (*solved)[a][0];
      if (sgn(lambda[a]) <= 0) return std::nullopt;
    }
  }
  ImpactEnergy e;
  for (std::size_t i = 0; i < n; ++i) {
    Rational impulse = 0;   // (J_H^T lambda_H)_i
    for (std::size_t a = 0; a < k; ++a) impulse += g(held[a], i) * lambda[a];
    if (sgn(mi[i]) > 0) {
      const Rational after = vq[i] + mi[i] * impulse;
      e.kinetic_before += vq[i] * vq[i] / mi[i] / 2;
      e.kinetic_after += after * after / mi[i] / 2;
    } else {
      e.driver_work -= vq[i] * impulse;
    }
  }
  e.multipliers.assign(m, Rational(0));
  for (std::size_t a = 0; a < k; ++a) e.multipliers[held[a]] = lambda[a];
  return e;
}

}  // namespace hipair::simulation
