// HIPAIR — contact forces and impulses with Coulomb friction (docs/simulation.md#friction).
//
// Contacts k = 1..m with normal rows G_k (the constraint gradient over the coordinates; its
// multiplier lambda_k >= 0) and, where friction acts, a tangent row T_k (relative tangential
// velocity at the contact point v_t = T_k qdot, the second part relative to the first along
// t = (-n_y, n_x)) and the ratio s_k of the physical normal row to G_k (G_phys = s_k G_k, so the
// physical normal force is N_k = lambda_k / s_k). Each frictional contact is in one state:
//   stick  (0):  T_k x = 0, tangential force f_k a free unknown with |f_k| <= mu_s N_k;
//   slip  (+-1): f_k = -sign mu_k N_k: the force column of contact k becomes
//                W_k = G_k - sign (mu_k / s_k) T_k, and sign T_k x >= 0 (it keeps sliding that way);
//   off   (2):   frictionless.
// The unknown x is an acceleration (contact forces: x = a_free + M^-1 (W^T lambda + T_S^T f_S),
// w = G x + h with h the curvature terms) or a velocity (impacts: x = v- + M^-1 (...), w = G x
// + e G v-): the same algebra. The stick rows are eliminated by their Schur complement, leaving
// the normal LCP  w = A lambda + b  in lambda alone (A non-symmetric when some contact slips).
// The states of contacts that are not sliding (their |v_t| below the velocity tolerance, and
// every contact of an impact) are found by enumeration, the most sticking contacts first: the
// first assignment whose LCP solution satisfies the Coulomb conditions is taken (a principled
// active-set search on stick/slip states; no iteration with a stopping rule).
#pragma once

#include "kernels/interval.hpp"
#include "simulation/exact_elimination.hpp"
#include "simulation/exact_lemke.hpp"
#include "simulation/exact_lp.hpp"
#include "simulation/exact_lp_elimination.hpp"
#include "simulation/held_force_sign.hpp"
#include "simulation/lcp.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace hipair::simulation {

enum : int { stick = 0, slip_positive = 1, slip_negative = -1, frictionless = 2 };

/// Coulomb data of one contact.
struct Friction {
  bool on = false;
  Eigen::VectorXd T;            ///< tangent row over the coordinates
  double s = 1;                 ///< G_phys = s G (> 0)
  double mu_static = 0, mu_kinetic = 0;
  /// The contact's state when it is known (sliding: +-1), or `undecided` (stick or slip decided
  /// by the enumeration).
  int state = 0;
  bool decided = false;
  /// The tangential curvature term (T' qdot): a sticking contact keeps T x + bias = 0 (0: the
  /// term neglected, as the fixed-axis simulator does).
  double bias = 0;
};

/// A Friction's fields as a default one holds them, but its tangent row's storage (kept: read
/// only where `on`, and written wherever `on` is set).
inline void reset(Friction& c) {
  c.on = false;
  c.s = 1;
  c.mu_static = c.mu_kinetic = 0;
  c.state = 0;
  c.decided = false;
  c.bias = 0;
}

struct FrictionalSolution {
  bool solved = false;
  Eigen::VectorXd lambda;        ///< normal multipliers (>= 0 for an LCP solution)
  Eigen::VectorXd w;             ///< G x + h
  Eigen::VectorXd x;             ///< accelerations (or velocities after the impact)
  Eigen::VectorXd f;             ///< tangential force (physical) per contact: stick: solved; slip: -sign mu_k N
  std::vector<int> state;        ///< per contact
  double tolerance = 0;          ///< of the normal LCP
  /// The exact x of this solution's held set and states where an exact decision computed it
  /// (exact_assignment's; session 69, exact69: over the problem's own coordinates — the full
  /// form's M coordinates where one is given), empty otherwise. Read by the restitution limit's
  /// exact energy test (held_friction.hpp's creates_energy).
  std::vector<Rational> x_exact;
  /// Where `solved` is false, whether that is a verdict (session 71, exact71): true where the
  /// search was complete — every stick/slip assignment of the undecided frictional contacts (at
  /// most 8) decided on every held set (at most 12 contacts) by the exact LP (solve_frictional in
  /// exact mode, full_form_impulses): no consistent solution exists, exactly. False where it was
  /// not (more than 8 undecided frictional contacts: nothing tried; more than 12 contacts: one held
  /// set per assignment, the exact LCP's; the doubles alone deciding): none was found, which is
  /// not a proof that none exists.
  bool exhausted = false;
};

/// The reduced normal problem for given states: x = x0 + B lambda (stick forces eliminated),
/// f_S = f0 + F lambda.
struct Reduced {
  Eigen::MatrixXd B, F;
  Eigen::VectorXd x0, f0;
  std::vector<Eigen::Index> sticking;   ///< contact index of each row of f_S
};

/// Storage kept between calls of the bilateral solve (the `work` forms of reduce and
/// solve_bilateral; Simulation::Impl keeps one for its accelerations): every matrix is resized
/// and written on each call before it is read, by the same Eigen operations as the fresh
/// matrices of the value forms — the same doubles, without the allocations (docs/simulation.md,
/// "Session 51").
struct BilateralWork {
  Eigen::MatrixXd W, MinvWt, TS, MinvTt, K, A;
  Eigen::VectorXd bias, b;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> sticking_solve, normal_solve;
  Reduced r;
};

/// reduce() written into r, with w's matrices as its working storage.
inline void reduce(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                   const std::vector<Friction>& friction, const std::vector<int>& state, Reduced& r,
                   BilateralWork& w) {
  const Eigen::Index m = G.rows(), n = G.cols();
  w.W = G;   // force columns (as rows)
  r.sticking.clear();
  for (Eigen::Index k = 0; k < m; ++k) {
    const Friction& c = friction[static_cast<std::size_t>(k)];
    int st = state[static_cast<std::size_t>(k)];
    if (!c.on || st == frictionless) continue;
    if (st == stick) r.sticking.push_back(k);
    else w.W.row(k) -= st * (c.mu_kinetic / c.s) * c.T.transpose();
  }
  const auto p = static_cast<Eigen::Index>(r.sticking.size());
  w.MinvWt.noalias() = minv.asDiagonal() * w.W.transpose();   // n x m
  r.x0 = a0;
  r.B = w.MinvWt;
  r.f0.setZero(p);
  r.F.setZero(p, m);
  if (p == 0) return;
  w.TS.resize(p, n);
  for (Eigen::Index j = 0; j < p; ++j) w.TS.row(j) = friction[static_cast<std::size_t>(r.sticking[j])].T.transpose();
  w.MinvTt.noalias() = minv.asDiagonal() * w.TS.transpose();   // n x p
  w.K.noalias() = w.TS * w.MinvTt;                              // p x p
  w.sticking_solve.compute(w.K);
  // T_S (x0 + B lambda + MinvTt f) + bias = 0  =>  f = -K^+ (T_S x0 + bias + T_S B lambda)
  w.bias.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) w.bias(j) = friction[static_cast<std::size_t>(r.sticking[j])].bias;
  r.f0 = -w.sticking_solve.solve(w.TS * a0 + w.bias);
  r.F = -w.sticking_solve.solve(w.TS * w.MinvWt);
  r.x0 = a0 + w.MinvTt * r.f0;
  r.B = w.MinvWt + w.MinvTt * r.F;
}

inline Reduced reduce(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                      const std::vector<Friction>& friction, const std::vector<int>& state) {
  BilateralWork w;
  reduce(G, minv, a0, friction, state, w.r, w);
  return std::move(w.r);
}

/// Fills the solution's x, w, f for multipliers lambda and states.
inline void complete(FrictionalSolution& s, const Reduced& r, const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                     const std::vector<Friction>& friction) {
  const Eigen::Index m = G.rows();
  s.x = r.x0 + r.B * s.lambda;
  s.w = G * s.x + h;
  s.f = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd fs = r.f0 + r.F * s.lambda;
  for (std::size_t j = 0; j < r.sticking.size(); ++j) s.f(r.sticking[j]) = fs(static_cast<Eigen::Index>(j));
  for (Eigen::Index k = 0; k < m; ++k) {
    const Friction& c = friction[static_cast<std::size_t>(k)];
    int st = s.state[static_cast<std::size_t>(k)];
    if (c.on && (st == slip_positive || st == slip_negative)) s.f(k) = -st * c.mu_kinetic * s.lambda(k) / c.s;
  }
}

/// Whether the sticking rows leave the normal multipliers undetermined: the reduced normal matrix
/// A = G B is singular on the scale of the frictionless A_f = G M^-1 G^T (its smallest singular
/// value below 1e-9 of A_f's largest). Then every motion the normal rows would stop is already
/// stopped by the sticking rows (two sticking contacts of a wedge holding both coordinates of a
/// pair), the LCP's minimum-norm multipliers (0) say nothing, and the normal forces are taken
/// from the frictionless problem where they solve the reduced one: the load carried by the
/// normal forces, friction only for what they leave (session 36, docs/simulation.md).
inline bool undetermined(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Af) {
  if (A.size() == 0) return false;
  const Eigen::VectorXd sa = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  const Eigen::VectorXd sf = Eigen::JacobiSVD<Eigen::MatrixXd>(Af).singularValues();
  return sf.size() > 0 && sf(0) > 0 && sa(sa.size() - 1) <= 1e-9 * sf(0);
}

/// All normal rows held (bilateral: w = 0), states given: the integration's right-hand side.
/// `undetermined_plain`: where the sticking rows leave the multipliers open, take the
/// frictionless ones if they hold (undetermined(), above).
/// solve_bilateral() written into s, with w as its working storage (BilateralWork).
inline void solve_bilateral(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                            const Eigen::VectorXd& h, const std::vector<Friction>& friction,
                            const std::vector<int>& state, bool undetermined_plain, BilateralWork& w,
                            FrictionalSolution& s) {
  s.solved = false;
  s.tolerance = 0;
  s.state = state;
  Reduced& r = w.r;
  reduce(G, minv, a0, friction, state, r, w);
  w.A.noalias() = G * r.B;
  w.b = G * r.x0 + h;
  w.normal_solve.compute(w.A);
  s.lambda = w.normal_solve.solve(-w.b);
  // held forces left open by the sticking rows: the frictionless ones where they hold (below)
  if (undetermined_plain && !r.sticking.empty()) {
    const Eigen::MatrixXd Af = G * minv.asDiagonal() * G.transpose();
    const Eigen::VectorXd bf = G * a0 + h;
    if (undetermined(w.A, Af)) {
      Eigen::VectorXd lf = Af.completeOrthogonalDecomposition().solve(-bf);
      if (((w.A * lf + w.b).cwiseAbs().array() <= 10 * lcp_tolerance(Af, bf)).all()) s.lambda = lf;
    }
  }
  complete(s, r, G, h, friction);
  s.solved = true;
}

inline FrictionalSolution solve_bilateral(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv,
                                          const Eigen::VectorXd& a0, const Eigen::VectorXd& h,
                                          const std::vector<Friction>& friction, const std::vector<int>& state,
                                          bool undetermined_plain = false) {
  BilateralWork w;
  FrictionalSolution s;
  solve_bilateral(G, minv, a0, h, friction, state, undetermined_plain, w, s);
  return s;
}

/// A frictional problem whose mass matrix is full (session 65, pinslot65: the pin-slot part's
/// coupled (s, psi), M = [[m, m e], [m e, M22]]). Its doubles are solved in the coordinates of M's
/// Cholesky factor (rows G L^-T, M the identity there: this header's diagonal form) — rows that
/// carry the factor's rounding; its exact decisions (held_verdict, exact_stick_holds) are taken on
/// this form instead: the normal rows G and the Friction data (tangent rows T, bias) as the
/// simulator computes them over its coordinates, the mass matrix M and the generalized forces Q
/// (the free accelerations M^-1 Q): A = J M^-1 W^T and b = J M^-1 Q + kappa in exact rationals
/// (held_force_sign.hpp's full form). The same contacts, order, states, mu and s as the solved form.
struct FullMass {
  Eigen::MatrixXd G, M;
  Eigen::VectorXd Q;
  std::vector<Friction> friction;
};

/// The held contacts' force problem at given stick/slip states as exact rows
/// (held_force_sign.hpp; the tangent rows its `equalities`, solved first as reduce() does):
/// the constraint rows [G; T_S] and the force rows [W; T_S] (W_k = G_k -
/// sign (mu_k / s_k) T_k for a sliding contact, the double reduce() forms; T_S the sticking
/// contacts' tangent rows, whose multipliers are their friction forces), the velocity terms
/// [h; bias_S], the diagonal inverse masses and the free accelerations a0. `sticking` gets the
/// contact of each tangent row (the rows after G's).
/// `group` (by contact; empty: each its own): of a collinear group's sticking contacts only the
/// first has a tangent row (the group's: its multiplier is the group's friction; the members'
/// rows agree to the grouping's 10^-12, and the split among them is left open by the equations).
/// `full` (given): the problem's full form (FullMass) replaces G, friction, minv and a0: its rows,
/// its mass matrix M and loads Q.
inline HeldForceRows frictional_rows(const Eigen::MatrixXd& G_given, const Eigen::VectorXd& minv,
                                     const Eigen::VectorXd& a0, const Eigen::VectorXd& h,
                                     const std::vector<Friction>& friction_given, const std::vector<int>& state,
                                     std::vector<std::size_t>& sticking, const std::vector<std::size_t>& group = {},
                                     const FullMass* full = nullptr) {
  const Eigen::MatrixXd& G = full ? full->G : G_given;
  const std::vector<Friction>& friction = full ? full->friction : friction_given;
  const Eigen::Index m = G.rows(), n = G.cols();
  sticking.clear();
  std::vector<bool> represented(static_cast<std::size_t>(m), false);
  for (Eigen::Index k = 0; k < m; ++k)
    if (friction[static_cast<std::size_t>(k)].on && state[static_cast<std::size_t>(k)] == stick) {
      const std::size_t g = group.empty() ? static_cast<std::size_t>(k) : group[static_cast<std::size_t>(k)];
      if (represented[g]) continue;
      represented[g] = true;
      sticking.push_back(static_cast<std::size_t>(k));
    }
  const auto rows = m + static_cast<Eigen::Index>(sticking.size());
  HeldForceRows p;
  p.J.resize(rows, n);
  p.kappa.resize(rows);
  p.J.topRows(m) = G;
  p.kappa.head(m) = h;
  for (std::size_t j = 0; j < sticking.size(); ++j) {
    const Friction& c = friction[sticking[j]];
    p.J.row(m + static_cast<Eigen::Index>(j)) = c.T.transpose();
    p.kappa(m + static_cast<Eigen::Index>(j)) = c.bias;
  }
  p.W = p.J;
  // (session 67, impact67: the exact decisions form a sliding contact's row from mu, s and T in
  // their own arithmetic — HeldForceRows::slip — not from W's rounded doubles)
  p.slip.assign(static_cast<std::size_t>(m), 0);
  p.slip_mu = Eigen::VectorXd::Zero(m);
  p.slip_s = Eigen::VectorXd::Ones(m);
  p.tangent = Eigen::MatrixXd::Zero(m, n);
  for (Eigen::Index k = 0; k < m; ++k) {
    const Friction& c = friction[static_cast<std::size_t>(k)];
    const int st = state[static_cast<std::size_t>(k)];
    if (c.on && (st == slip_positive || st == slip_negative)) {
      p.W.row(k) -= st * (c.mu_kinetic / c.s) * c.T.transpose();
      p.slip[static_cast<std::size_t>(k)] = st;
      p.slip_mu(k) = c.mu_kinetic;
      p.slip_s(k) = c.s;
      p.tangent.row(k) = c.T.transpose();
    }
  }
  if (full) {
    p.M = full->M;
    p.Q = full->Q;
  } else {
    p.minv = minv;
    p.a0 = a0;
  }
  p.equalities = sticking.size();
  return p;
}

/// The held conditions of contacts moving at fixed stick/slip states, decided exactly on their
/// rows (docs/simulation.md, "Session 63 (exact63)"): per contact the sign of its normal
/// multiplier (lift-off: negative; exactly 0 stays held), and per sticking contact whether its
/// friction force exceeds the static limit, |f| > mu_s N with N = max(lambda, 0) / s (stick ->
/// slip; exactly at the limit it sticks). Contacts of one collinear group (`group`, by contact;
/// empty: each its own — the planar simulators' split_collinear) share their friction in
/// proportion to their normal forces: the group's |sum f| against mu_s sum N decides for every
/// member that carries a normal force (every member when none does). The multipliers are the
/// exact solution of the rows (frictional_rows: the sticking rows' forces first, then the
/// minimum-norm normal multipliers, as solve_bilateral) — the interval filter first (a regular
/// system: one solution), exact rationals where it does not decide (decide_on_multipliers);
/// mu_s and s are the doubles' values.
/// `open_sign` (only with open rows given): per open row (a contact not held: its normal row
/// G_o and velocity term h_o), the sign of its gap's acceleration G_o x + h_o at the held
/// contacts' exact solution x = a0 + M^-1 (W^T lambda + T_S^T f), decided exactly as well.
/// `full` (given): decided on the problem's full form (FullMass: its rows, M and Q replace G,
/// friction, minv and a0; open rows over its coordinates, x = M^-1 (Q + W^T lambda + T_S^T f)).
struct HeldVerdict {
  std::vector<int> force_sign;        ///< per contact: -1, 0, +1
  std::vector<bool> beyond_static;    ///< per contact: sticking, and its friction beyond mu_s N
  std::vector<int> open_sign;         ///< per open row: -1, 0, +1
};

inline HeldVerdict held_verdict(const Eigen::MatrixXd& G_given, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                                const Eigen::VectorXd& h, const std::vector<Friction>& friction_given,
                                const std::vector<int>& state, const std::vector<std::size_t>& group = {},
                                HeldForceCount* count = nullptr, const Eigen::MatrixXd* open_G = nullptr,
                                const Eigen::VectorXd* open_h = nullptr, const FullMass* full = nullptr) {
  const Eigen::MatrixXd& G = full ? full->G : G_given;
  const std::vector<Friction>& friction = full ? full->friction : friction_given;
  std::vector<std::size_t> sticking;   // one tangent row per group
  const HeldForceRows rows = frictional_rows(G, minv, a0, h, friction, state, sticking, group, full);
  const std::size_t m = static_cast<std::size_t>(G.rows());
  const std::size_t open = open_G ? static_cast<std::size_t>(open_G->rows()) : 0;
  auto group_of = [&](std::size_t k) { return group.empty() ? k : group[k]; };
  return decide_on_multipliers(
      rows,
      [&](const auto& x) -> std::optional<HeldVerdict> {
        using T = std::decay_t<decltype(x[0])>;
        auto value = [](double d) {
          if constexpr (std::is_same_v<T, Rational>) return held_force_detail::exact_value(d);
          else return kernels::Interval::point(d);
        };
        HeldVerdict v;
        v.force_sign.assign(m, 0);
        v.beyond_static.assign(m, false);
        for (std::size_t k = 0; k < m; ++k)
          if ((v.force_sign[k] = exact_sign(x[k])) == 2) return std::nullopt;
        std::vector<bool> done(m, false);
        for (std::size_t j = 0; j < sticking.size(); ++j) {
          const std::size_t g = group_of(sticking[j]);
          if (done[g]) continue;
          done[g] = true;
          const T force = x[m + j];   // the group's friction (its one tangent row)
          T normal = T(0);
          int normal_sign = 0;
          for (std::size_t k = 0; k < m; ++k) {
            if (group_of(k) != g || !friction[k].on || state[k] != stick) continue;
            normal = normal + nonnegative_part(x[k]) / value(friction[k].s);
            normal_sign = std::max(normal_sign, v.force_sign[k]);
          }
          const int margin = exact_sign(value(friction[sticking[j]].mu_static) * normal - magnitude_of(force));
          if (margin == 2) return std::nullopt;
          if (margin >= 0) continue;
          for (std::size_t k = 0; k < m; ++k)
            if (group_of(k) == g && friction[k].on && state[k] == stick && (v.force_sign[k] > 0 || normal_sign <= 0))
              v.beyond_static[k] = true;
        }
        if (open > 0) {
          // the accelerations the held forces give, x_i = a0_i + minv_i sum_r W_ri x_r, and the
          // open rows' gap accelerations on them
          const auto n = static_cast<std::size_t>(G.cols());
          std::vector<T> acc(n, T(0));
          held_force_detail::Matrix<T> mass(n, std::vector<T>(n, T(0))), load(n, std::vector<T>(1, T(0)));
          for (std::size_t i = 0; i < n; ++i) {
            T sum = T(0);
            for (std::size_t r = 0; r < x.size(); ++r)
              sum = sum + held_force_detail::force_entry<T>(rows, r, i, value) * x[r];
            if (full) {   // M x = Q + W^T (lambda; f), solved below
              load[i][0] = value(full->Q(static_cast<Eigen::Index>(i))) + sum;
              for (std::size_t j = 0; j < n; ++j)
                mass[i][j] = value(full->M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
              continue;
            }
            acc[i] = value(a0(static_cast<Eigen::Index>(i))) + value(minv(static_cast<Eigen::Index>(i))) * sum;
          }
          if (full) {
            const auto solved = held_force_detail::solve(std::move(mass), std::move(load));
            if (!solved) {
              if constexpr (std::is_same_v<T, Rational>)
                throw NumericError("a held contact's force problem: the mass matrix is singular");
              else
                return std::nullopt;
            }
            for (std::size_t i = 0; i < n; ++i) acc[i] = (*solved)[i][0];
          }
          v.open_sign.assign(open, 0);
          for (std::size_t o = 0; o < open; ++o) {
            T gap = value((*open_h)(static_cast<Eigen::Index>(o)));
            for (std::size_t i = 0; i < n; ++i)
              gap = gap + value((*open_G)(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i))) * acc[i];
            if ((v.open_sign[o] = exact_sign(gap)) == 2) return std::nullopt;
          }
        }
        return v;
      },
      count);
}

/// True when the Coulomb conditions hold for the solution (stick: |f| <= mu_s N; a slip decided
/// here: it accelerates (or moves) in its sliding direction). `stick_limits` false: the stick
/// limits are not tested here (decided exactly instead: exact_stick_holds).
inline bool coulomb_satisfied(const FrictionalSolution& s, const std::vector<Friction>& friction,
                              bool stick_limits = true) {
  // A candidate with a non-finite multiplier, force or acceleration satisfies nothing: NaN fails
  // every comparison below, so until session 64 (hunt64) it passed them all (a slip assignment
  // at friction 1e308: rows G - mu T of 1e308 turned the LCP's solution into NaN, which the
  // planar simulator's impact took as the velocity after it).
  if (!s.lambda.allFinite() || !s.f.allFinite() || !s.x.allFinite()) return false;
  for (std::size_t k = 0; k < friction.size(); ++k) {
    const Friction& c = friction[k];
    if (!c.on) continue;
    const auto i = static_cast<Eigen::Index>(k);
    double N = s.lambda(i) / c.s;
    int st = s.state[k];
    if (st == stick) {
      if (!stick_limits) continue;
      double limit = c.mu_static * N;
      if (std::abs(s.f(i)) > limit + 1e-9 * (limit + std::abs(s.f(i))) + 1e-300) return false;
    } else if (!c.decided && (st == slip_positive || st == slip_negative)) {
      double vt = c.T.dot(s.x) + c.bias;
      double scale = c.T.cwiseAbs().dot(s.x.cwiseAbs()) + std::abs(c.bias);
      if (st * vt < -1e-9 * scale) return false;
    }
  }
  return true;
}

/// The stick limits of a candidate solution s decided exactly (held_verdict) on the rows of its
/// held contacts (all but those the LCP lets separate: lambda 0 and w beyond its tolerance), at
/// its states: false when a sticking contact's friction exceeds mu_s N exactly. `group`: the
/// collinear groups by contact (empty: each its own).
/// Dependent rows (session 64, stick64): where the held contacts' rows with the sticking tangent
/// rows are dependent (the exact rank of [G; T_S] M^-1 [W; T_S]^T below their count: the
/// escapement's anchor on its banking pin while the exit pallet locks a tooth whose normal passes
/// through the anchor's pivot — banking, lock and the lock's tangent rows on two coordinates) the
/// forces are a family, and the exact multipliers above (friction first, minimum norm) are one
/// choice in it: a friction beyond mu_s N there says nothing about the others. Then the stick
/// holds when some member is exactly consistent at a vertex where held contacts without friction
/// state of their own (frictionless or sliding) carry no force: for each such set Z (smallest
/// first), the rows without Z solved exactly, every remaining force not negative, no sticking
/// friction beyond mu_s N, and every contact of Z not pressed into (its gap acceleration at that
/// solution not negative) — all exact. A consistent stick whose forces leave room on every
/// normal (inside the cone) is reached by moving along the family until a normal force vanishes
/// or a friction reaches mu_s N; the latter is a slip candidate of the enumeration (at zero
/// sliding acceleration), the former one of these sets. Regular rows (one solution) are decided
/// by the test of all held contacts alone, as before.
/// Session 65: every witness (the candidate's member, or a vertex) is also checked exactly for the
/// contacts the candidate lets separate (their gaps not closing), for sliding contacts whose
/// direction is not given (keeping it), and for negative forces on regular rows; a sticking
/// contact the candidate lets separate is not verified here. False is not a verdict on the
/// assignment: solve_frictional then decides it exactly (exact_assignment).
/// `full` (given): decided on the problem's full form (FullMass; held_verdict's, frictional_rows').
inline bool exact_stick_holds(const Eigen::MatrixXd& G_given, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                              const Eigen::VectorXd& h, const std::vector<Friction>& friction_given,
                              const FrictionalSolution& s, const std::vector<std::size_t>& group,
                              const FullMass* full = nullptr) {
  const Eigen::MatrixXd& G = full ? full->G : G_given;
  const std::vector<Friction>& friction = full ? full->friction : friction_given;
  const auto m = static_cast<std::size_t>(G.rows());
  bool any = false;
  for (std::size_t k = 0; k < m; ++k) any = any || (friction[k].on && s.state[k] == stick);
  if (!any) return true;
  std::vector<std::size_t> held, apart;   // apart: the contacts the candidate lets separate
  for (std::size_t k = 0; k < m; ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    if (s.lambda(r) <= 0 && s.w(r) > s.tolerance) apart.push_back(k);
    else held.push_back(k);
  }
  // a sticking contact the candidate lets separate must carry no friction: not verified here
  // (session 65: exact_assignment decides such an assignment)
  for (std::size_t k : apart)
    if (friction[k].on && s.state[k] == stick) return false;
  // the conditions of a witness at held rows `set`, the rows `dropped` (held contacts taken
  // without force) watched as open too: every force not negative, no sticking friction beyond
  // mu_s N, no open gap closing (the separated contacts' and the dropped ones'), and (session 65)
  // a sliding contact whose direction is not given keeping it — all exact on the same rows
  std::vector<Eigen::VectorXd> slip_rows;
  std::vector<double> slip_terms;
  for (std::size_t k = 0; k < m; ++k) {
    const Friction& c = friction[k];
    const int st = s.state[k];
    if (c.on && !c.decided && (st == slip_positive || st == slip_negative)) {
      slip_rows.push_back(st * c.T);
      slip_terms.push_back(st * c.bias);
    }
  }
  auto witness = [&](const std::vector<std::size_t>& set, const std::vector<std::size_t>& dropped, HeldVerdict& v) {
    const auto n = static_cast<Eigen::Index>(set.size());
    Eigen::MatrixXd Gh(n, G.cols());
    Eigen::VectorXd hh(n);
    std::vector<Friction> fh;
    std::vector<int> sh;
    std::vector<std::size_t> gh;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const std::size_t k = set[i];
      Gh.row(static_cast<Eigen::Index>(i)) = G.row(static_cast<Eigen::Index>(k));
      hh(static_cast<Eigen::Index>(i)) = h(static_cast<Eigen::Index>(k));
      fh.push_back(friction[k]);
      sh.push_back(s.state[k]);
      std::size_t first = i;   // the group's first held member
      if (!group.empty())
        for (std::size_t j = 0; j < i; ++j)
          if (group[set[j]] == group[k]) {
            first = j;
            break;
          }
      gh.push_back(first);
    }
    const auto o = static_cast<Eigen::Index>(apart.size() + dropped.size() + slip_rows.size());
    Eigen::MatrixXd Go(o, G.cols());
    Eigen::VectorXd ho(o);
    Eigen::Index i = 0;
    for (const std::vector<std::size_t>* list : {static_cast<const std::vector<std::size_t>*>(&apart), &dropped})
      for (std::size_t k : *list) {
        Go.row(i) = G.row(static_cast<Eigen::Index>(k));
        ho(i++) = h(static_cast<Eigen::Index>(k));
      }
    for (std::size_t j = 0; j < slip_rows.size(); ++j) {
      Go.row(i) = slip_rows[j].transpose();
      ho(i++) = slip_terms[j];
    }
    std::optional<FullMass> sub;   // the rows `set` of the full form
    if (full) sub = FullMass{Gh, full->M, full->Q, fh};
    v = held_verdict(Gh, minv, a0, hh, fh, sh, gh, nullptr, o > 0 ? &Go : nullptr, o > 0 ? &ho : nullptr,
                     sub ? &*sub : nullptr);
    return std::none_of(v.force_sign.begin(), v.force_sign.end(), [](int sign) { return sign < 0; }) &&
           std::none_of(v.beyond_static.begin(), v.beyond_static.end(), [](bool b) { return b; }) &&
           std::none_of(v.open_sign.begin(), v.open_sign.end(), [](int sign) { return sign < 0; });
  };
  HeldVerdict v;
  if (witness(held, {}, v)) return true;
  // the rows' dependence, exactly (asked only where the test of all held contacts fails): regular
  // rows have one solution, which failed
  {
    std::vector<Friction> fh;
    std::vector<int> sh;
    std::vector<std::size_t> gh, sticking;
    Eigen::MatrixXd Gh(static_cast<Eigen::Index>(held.size()), G.cols());
    Eigen::VectorXd hh(static_cast<Eigen::Index>(held.size()));
    for (std::size_t i = 0; i < held.size(); ++i) {
      Gh.row(static_cast<Eigen::Index>(i)) = G.row(static_cast<Eigen::Index>(held[i]));
      hh(static_cast<Eigen::Index>(i)) = h(static_cast<Eigen::Index>(held[i]));
      fh.push_back(friction[held[i]]);
      sh.push_back(s.state[held[i]]);
      std::size_t first = i;
      if (!group.empty())
        for (std::size_t j = 0; j < i; ++j)
          if (group[held[j]] == group[held[i]]) {
            first = j;
            break;
          }
      gh.push_back(first);
    }
    std::optional<FullMass> sub;   // the held rows of the full form
    if (full) sub = FullMass{Gh, full->M, full->Q, fh};
    const HeldForceRows rows = frictional_rows(Gh, minv, a0, hh, fh, sh, sticking, gh, sub ? &*sub : nullptr);
    auto [A, b] = held_force_detail::exact_delassus(rows, held_force_detail::all_rows(rows));
    if (row_echelon(A, A.size()).size() == A.size()) return false;
  }
  std::vector<std::size_t> free;   // held contacts without a sticking tangent row
  for (std::size_t k : held)
    if (!(friction[k].on && s.state[k] == stick)) free.push_back(k);
  if (free.empty() || free.size() > 8) return false;
  std::vector<std::size_t> codes((std::size_t{1} << free.size()) - 1);
  for (std::size_t c = 0; c < codes.size(); ++c) codes[c] = c + 1;
  std::stable_sort(codes.begin(), codes.end(), [](std::size_t x, std::size_t y) {
    return __builtin_popcountll(x) < __builtin_popcountll(y);
  });
  for (std::size_t code : codes) {
    std::vector<std::size_t> kept, dropped;
    for (std::size_t k : held) {
      const auto at = std::find(free.begin(), free.end(), k);
      const bool drop = at != free.end() && ((code >> static_cast<std::size_t>(at - free.begin())) & 1);
      (drop ? dropped : kept).push_back(k);
    }
    if (witness(kept, dropped, v)) return true;
  }
  return false;
}

/// The feasibility of an exact linear system decided by exact elimination where its equalities
/// leave at most one unknown free (session 67, impactfast67): the equalities reduced to row
/// echelon form (row_echelon, rationals) — inconsistent: no solution; their solution set
/// z = z_p + t d (d = 0 when none is free) — and every inequality and sign c0 + t c1 >= 0 bounds
/// t exactly; the bounds crossing: no solution, the same answer as the linear program's. Where
/// the set is one point that point is the answer (the linear program's only feasible point);
/// where it is a segment or more, or two or more unknowns are free, the linear program decides
/// (exact_feasible_point: its point, as before). An impact's singular held sets (two contacts of
/// one pair with their tangent rows over two coordinates) are square with dependent equalities:
/// the linear program was asked for every one of them, most without a solution.
inline std::optional<std::vector<Rational>> reduced_feasible_point(const ExactLinearSystem& lp) {
  const std::size_t vars = lp.variables;
  std::vector<std::vector<Rational>> E;
  for (std::size_t i = 0; i < lp.rows.size(); ++i)
    if (lp.equality[i]) {
      E.push_back(lp.rows[i]);
      E.back().push_back(lp.rhs[i]);
    }
  const std::vector<std::size_t> pivots = row_echelon(E, vars);
  const std::size_t rank = pivots.size();
  for (std::size_t r = rank; r < E.size(); ++r)
    if (sgn(E[r][vars]) != 0) return std::nullopt;   // 0 = nonzero: the equalities are inconsistent
  if (vars - rank > 1) return exact_feasible_point(lp);
  std::size_t free_var = vars;   // the free unknown, if any
  for (std::size_t j = 0, r = 0; j < vars && free_var == vars; ++j) {
    if (r < rank && pivots[r] == j) ++r;
    else free_var = j;
  }
  std::vector<Rational> zp(vars, Rational(0)), d(vars, Rational(0));
  if (free_var < vars) d[free_var] = 1;
  for (std::size_t r = rank; r-- > 0;) {
    const std::size_t c = pivots[r];
    Rational sp = E[r][vars], sd = 0;
    for (std::size_t j = c + 1; j < vars; ++j)
      if (sgn(E[r][j]) != 0) {
        sp -= E[r][j] * zp[j];
        sd -= E[r][j] * d[j];
      }
    zp[c] = sp / E[r][c];
    d[c] = sd / E[r][c];
  }
  std::optional<Rational> lo, hi;   // the bounds on t
  auto bound = [&](const Rational& c0, const Rational& c1) {   // c0 + t c1 >= 0; false: never
    if (sgn(c1) == 0) return sgn(c0) >= 0;
    const Rational t = -c0 / c1;
    if (sgn(c1) > 0) {
      if (!lo || t > *lo) lo = t;
    } else if (!hi || t < *hi) {
      hi = t;
    }
    return true;
  };
  for (std::size_t j = 0; j < vars; ++j)
    if (lp.nonnegative[j] && !bound(zp[j], d[j])) return std::nullopt;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    if (lp.equality[i]) continue;
    Rational c0 = -lp.rhs[i], c1 = 0;
    for (std::size_t j = 0; j < vars; ++j)
      if (sgn(lp.rows[i][j]) != 0) {
        c0 += lp.rows[i][j] * zp[j];
        if (sgn(d[j]) != 0) c1 += lp.rows[i][j] * d[j];
      }
    if (!bound(c0, c1)) return std::nullopt;
  }
  if (lo && hi && *lo > *hi) return std::nullopt;
  if (free_var == vars) return zp;
  return exact_feasible_point(lp);
}

/// exact_feasible_point where the system's equalities are as many as its unknowns and regular
/// (session 67, impact67): then the feasible set is at most their one solution — solved exactly
/// (held_force_detail::solve, Gauss–Jordan in rationals) and every inequality and sign checked
/// exactly; the same answer as the linear program's, without it (an impact's held set with its
/// sticking rows is square: the linear program was 87 % of the escapement's impacts; no unknowns
/// at all — an open set without sticking rows — is the rows' signs). Other systems (fewer
/// equalities, or dependent ones): reduced_feasible_point (session 67, impactfast67; until then
/// the linear program for every one). Since session 67 (impactfast67) a square system the interval
/// filter (square_certainly_infeasible) finds certainly without a solution is answered there.
/// A certified filter in front of the exact solve of a square system (session 67, impactfast67):
/// the equalities solved in intervals (every entry kernels::Interval::enclose of the exact one,
/// held_force_detail::solve: each pivot certainly nonzero, so the system is regular and its one
/// solution lies in the enclosure); true when that solution certainly breaks a sign (an unknown
/// required >= 0 whose enclosure is below 0) or an inequality (its row's enclosure at the
/// solution's below the right-hand side's) — no solution, exactly. False: undecided (a pivot's
/// enclosure holding 0, or every condition's enclosure reaching it): the exact solve decides.
/// On an interval system (every number an enclosure of the exact one, [0, 0] only where it is 0;
/// session 72, speed72: exact_assignment's held sets before any rational is formed): true, no
/// solution, exactly; false, the equalities are regular and their solution's enclosure breaks
/// nothing; nullopt, not decided here (not square, or a pivot's enclosure holding 0).
/// (Session 73, speed73: the equalities' Gauss–Jordan in one flat row-major block [A | b] kept per
/// thread and reused, the rows' order an index permutation — the same operations in the same order
/// as held_force_detail::solve's on Matrix<Interval>, so the same bits, without a vector per row
/// and per held set; tests/unit/simulation_square_filter_test.cpp compares it with that form.)
inline std::optional<bool> square_certainly_infeasible(const IntervalLinearSystem& lp) {
  using kernels::Interval;
  const std::size_t vars = lp.variables;
  std::size_t equalities = 0;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) equalities += lp.equality[i] ? 1 : 0;
  if (equalities != vars) return std::nullopt;
  const std::size_t w = vars + 1;   // a row: its vars coefficients, then its right-hand side
  thread_local std::vector<Interval> block;
  thread_local std::vector<std::size_t> at;   // at[r]: where the r-th row of the elimination is
  block.resize(vars * w);
  at.resize(vars);
  for (std::size_t i = 0, r = 0; i < lp.rows.size(); ++i)
    if (lp.equality[i]) {
      Interval* row = block.data() + r * w;
      std::copy(lp.rows[i].begin(), lp.rows[i].end(), row);
      row[vars] = lp.rhs[i];
      at[r] = r * w;
      ++r;
    }
  using held_force_detail::magnitude;
  using held_force_detail::nonzero;
  Interval* const A = block.data();
  for (std::size_t c = 0; c < vars; ++c) {
    std::size_t best = vars;
    for (std::size_t r = c; r < vars; ++r)
      if (nonzero(A[at[r] + c]) && (best == vars || magnitude(A[at[r] + c]) > magnitude(A[at[best] + c]))) best = r;
    if (best == vars) return std::nullopt;
    std::swap(at[c], at[best]);
    const Interval* pivot = A + at[c];
    for (std::size_t r = 0; r < vars; ++r) {
      if (r == c) continue;
      Interval* row = A + at[r];
      const Interval f = row[c] / pivot[c];
      for (std::size_t k = c; k < vars; ++k) row[k] = row[k] - f * pivot[k];
      row[vars] = row[vars] - f * pivot[vars];
    }
  }
  // the solution z_j = b_j / A_jj, j in the elimination's order (as solve's last loop)
  auto z = [&](std::size_t j) { return A[at[j] + vars] / A[at[j] + j]; };
  for (std::size_t j = 0; j < vars; ++j)
    if (lp.nonnegative[j] && z(j).hi < 0) return true;
  thread_local std::vector<Interval> solution;
  solution.resize(vars);
  for (std::size_t j = 0; j < vars; ++j) solution[j] = z(j);
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    if (lp.equality[i]) continue;
    Interval sum(0);
    for (std::size_t j = 0; j < vars; ++j)
      if (lp.rows[i][j].sign() != 0) sum = sum + lp.rows[i][j] * solution[j];
    if (sum.hi < lp.rhs[i].lo) return true;
  }
  return false;
}

inline bool square_certainly_infeasible(const ExactLinearSystem& lp) {
  using kernels::Interval;
  IntervalLinearSystem enclosed;
  enclosed.variables = lp.variables;
  enclosed.nonnegative = lp.nonnegative;
  enclosed.equality = lp.equality;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    std::vector<Interval> row(lp.variables);
    for (std::size_t j = 0; j < lp.variables; ++j) row[j] = Interval::enclose(lp.rows[i][j]);
    enclosed.rows.push_back(std::move(row));
    enclosed.rhs.push_back(Interval::enclose(lp.rhs[i]));
  }
  return square_certainly_infeasible(enclosed).value_or(false);
}

/// `filtered` (session 73, speed73): the caller has already put this system's interval enclosure
/// through square_certainly_infeasible (exact_assignment's held sets): the filter on the rationals'
/// enclosures is not run again (the exact solve below decides; the same answer either way).
inline std::optional<std::vector<Rational>> square_feasible_point(const ExactLinearSystem& lp, bool filtered = false) {
  const std::size_t vars = lp.variables;
  std::size_t equalities = 0;
  for (bool e : lp.equality) equalities += e;
  if (equalities != vars) return reduced_feasible_point(lp);
  if (!filtered && square_certainly_infeasible(lp)) return std::nullopt;
  held_force_detail::Matrix<Rational> A, b;
  for (std::size_t i = 0; i < lp.rows.size(); ++i)
    if (lp.equality[i]) {
      A.push_back(lp.rows[i]);
      b.push_back({lp.rhs[i]});
    }
  const std::optional<held_force_detail::Matrix<Rational>> solved = held_force_detail::solve(std::move(A), std::move(b));
  if (!solved) return reduced_feasible_point(lp);
  std::vector<Rational> z(vars);
  for (std::size_t j = 0; j < vars; ++j) z[j] = (*solved)[j][0];
  for (std::size_t j = 0; j < vars; ++j)
    if (lp.nonnegative[j] && sgn(z[j]) < 0) return std::nullopt;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    if (lp.equality[i]) continue;
    Rational sum = 0;
    for (std::size_t j = 0; j < vars; ++j)
      if (sgn(lp.rows[i][j]) != 0) sum += lp.rows[i][j] * z[j];
    if (sum < lp.rhs[i]) return std::nullopt;
  }
  return z;
}

// exact_assignment's interval filter on each held set (session 72, speed72; see there): the
// switch (on by default; a test turns it off on its thread to compare with the exact path alone)
// and how many held sets it refused on this thread.
struct AssignmentIntervalFilterTag;
inline bool& assignment_interval_filter() { return thread_switch<AssignmentIntervalFilterTag>(); }
struct AssignmentIntervalRefusedTag;
inline std::size_t& assignment_interval_refused() { return thread_counter<AssignmentIntervalRefusedTag>(); }

/// One stick/slip assignment's consistency decided exactly (session 65, stick65): whether SOME
/// force of the contact problem at these states satisfies its conditions, on the rows as the
/// doubles give them (every double the exact number it is). For a held set H (the others open:
/// lambda_k = 0) the unknowns are the held normal multipliers lambda_H and the sticking contacts'
/// friction forces f (one per collinear group: `group`, by contact; empty: each its own), the
/// accelerations x = a0 + M^-1 (W_H^T lambda_H + T_S^T f) (W the force rows of frictional_rows;
/// since session 66 a sliding contact's row G_k - sign (mu_k / s_k) T_k formed in rationals, not
/// the doubles' rounded one), and the conditions are linear: G_H x + h_H = 0, G_O x + h_O >= 0
/// (an open gap does not close), T_S x + bias_S = 0 (a sticking contact keeps its tangential
/// acceleration 0, as reduce()),
/// lambda_H >= 0, |f_g| <= mu_s sum_{k in g, held} lambda_k / s_k (a sticking contact that is
/// open carries no friction), and a sliding contact whose direction is not given keeps it,
/// sign (T_k x + bias_k) >= 0 (coulomb_satisfied's conditions without their slack). For each held
/// set — `first` (the doubles' LCP's, when given) first, then all, the largest first and
/// lexicographic within a size — the linear system is decided by the exact linear program
/// (exact_lp.hpp); the first feasible one gives the solution, its numbers rounded to the nearest
/// doubles (x and w from the exact ones; a friction shared by a group split in proportion to its
/// members' normal forces). None: the assignment has no consistent force, exactly.
/// Beyond 12 contacts (session 70, exact70) the held sets are not enumerated: after `first`, only
/// the held set of the assignment's exact LCP (Lemke's algorithm in rationals, its pivots capped
/// at 2^20) is decided; none found there — Lemke's ray or cap, dependent sticking rows, the LCP's
/// held set breaking a Coulomb condition — is not a verdict (nullopt, as the bound's nullopt
/// before). This applies to the held contacts' stepping decisions too (solve_frictional's exact
/// mode at each step's start), not only to impacts.
/// `tried` (optional) counts the linear programs solved. `first_only` (with `first` given; session
/// 66, slip66): only the held set `first` is decided (any number of contacts): a candidate's
/// confirmation, not the assignment's verdict.
/// `full` (given; session 66, fullform66): decided on the problem's full form (FullMass: its rows
/// G and Friction data, M and Q replace G, friction, minv and a0), x = M^-1 (Q + W_H^T lambda_H +
/// T_S^T f) with M^-1 Q and M^-1 W^T solved exactly (held_force_detail::solve on the exact
/// doubles of M); the published accelerations are then mapped to the coordinates of the rows as
/// given, z = L^T q (L: Eigen's Cholesky factor of M in doubles, the pin-slot simulator's
/// FrictionProblem), x_z = L^T x rounded — the coordinates the doubles' solutions are in; the
/// multipliers, forces and gap accelerations are the full form's exact ones rounded once.
/// `h_exact` (given; session 68, impact68): the velocity terms of the normal rows as exact
/// rationals in place of h's doubles (an impact's restitution terms e G v-, exact on G, v and e:
/// exact_restitution_terms in held_friction.hpp; h's doubles are their rounding).
/// `bias_exact` (given; session 70, exact70): the tangent rows' constants (by contact) as exact
/// rationals in place of the Friction data's `bias` doubles (an impact on the full form with
/// Q = 0: x the velocities' change, a tangent row's constant T v- less the driver's speed, exact).
inline std::optional<FrictionalSolution> exact_assignment(const Eigen::MatrixXd& G_given, const Eigen::VectorXd& minv,
                                                          const Eigen::VectorXd& a0, const Eigen::VectorXd& h,
                                                          const std::vector<Friction>& friction_given,
                                                          const std::vector<int>& state,
                                                          const std::vector<std::size_t>& group,
                                                          const std::vector<bool>* first = nullptr,
                                                          std::size_t* tried = nullptr,
                                                          const FullMass* full = nullptr,
                                                          bool first_only = false,
                                                          const std::vector<Rational>* h_exact = nullptr,
                                                          const std::vector<Rational>* bias_exact = nullptr) {
  const Eigen::MatrixXd& G = full ? full->G : G_given;
  const std::vector<Friction>& friction = full ? full->friction : friction_given;
  const auto m = static_cast<std::size_t>(G.rows()), n = static_cast<std::size_t>(G.cols());
  first_only = first_only && first;
  std::vector<std::size_t> reps;   // the sticking rows (one per group)
  const HeldForceRows rows = frictional_rows(G, minv, a0, h, friction, state, reps, group, full);
  auto group_of = [&](std::size_t k) { return group.empty() ? k : group[k]; };
  auto exact = [](double v) { return held_force_detail::exact_value(v); };
  const std::size_t p = reps.size();
  // the free accelerations x0 = M^-1 Q and each force row's response D_r = M^-1 W_r^T, exact
  // (diagonal form: a0 and minv_i W_ri, as given)
  const auto force_rows = static_cast<std::size_t>(rows.W.rows());   // m + p
  // (session 72, speed72: formed on the first held set the interval filter below does not refuse
  // — on the full form at once, its enclosures being those of the exact solve's)
  held_force_detail::Matrix<Rational> W, D;
  std::vector<Rational> x0;
  bool prepared = false;
  auto prepare = [&] {
    if (prepared) return;
    prepared = true;
    // the force rows exactly: J's, a sliding contact's G_k - sign (mu_k / s_k) T_k in rationals
    // (session 66; rows.W is that row in doubles)
    W.assign(force_rows, std::vector<Rational>(n));
    for (std::size_t r = 0; r < force_rows; ++r) {
      for (std::size_t i = 0; i < n; ++i) W[r][i] = exact(rows.J(Eigen::Index(r), Eigen::Index(i)));
      if (r >= m) continue;
      const Friction& c = friction[r];
      const int st = state[r];
      if (!c.on || (st != slip_positive && st != slip_negative)) continue;
      const Rational k = exact(c.mu_kinetic) / exact(c.s);
      for (std::size_t i = 0; i < n; ++i)
        if (c.T(Eigen::Index(i)) != 0) W[r][i] -= st * k * exact(c.T(Eigen::Index(i)));
    }
    x0.assign(n, Rational(0));
    D.assign(force_rows, std::vector<Rational>(n));
    if (full) {
      held_force_detail::Matrix<Rational> mass(n, std::vector<Rational>(n));
      held_force_detail::Matrix<Rational> rhs(n, std::vector<Rational>(force_rows + 1));
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) mass[i][j] = exact(full->M(Eigen::Index(i), Eigen::Index(j)));
        for (std::size_t r = 0; r < force_rows; ++r) rhs[i][r] = W[r][i];
        rhs[i][force_rows] = exact(full->Q(Eigen::Index(i)));
      }
      const auto solved = held_force_detail::solve(std::move(mass), std::move(rhs));
      if (!solved) throw NumericError("a held contact's force problem: the mass matrix is singular");
      for (std::size_t i = 0; i < n; ++i) {
        x0[i] = (*solved)[i][force_rows];
        for (std::size_t r = 0; r < force_rows; ++r) D[r][i] = (*solved)[i][r];
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        x0[i] = exact(a0(static_cast<Eigen::Index>(i)));
        const Rational mi = exact(minv(static_cast<Eigen::Index>(i)));
        for (std::size_t r = 0; r < force_rows; ++r)
          if (sgn(W[r][i]) != 0) D[r][i] = mi * W[r][i];
      }
    }
  };
  if (full) prepare();
  // a row r over the coordinates as an affine function of the unknowns z = [lambda_H, f]:
  // r . x + c = (r . x0 + c) + sum_v (r . D_v) z_v. Its constant and its coefficient on every
  // force row (r . D_row) do not depend on the held set: formed once per row (contact k's gap
  // row, `tangent` false, or its tangent row) and selected per held set (session 67,
  // impactfast67: until then formed again for each of the up to 2^m held sets; the same rationals)
  struct AffineRow {
    bool formed = false;
    Rational constant;
    std::vector<Rational> on;   // by force row (m + p)
  };
  std::vector<AffineRow> affine_rows(2 * m);
  auto affine = [&](std::size_t k, bool tangent, const std::vector<std::size_t>& held,
                    std::vector<Rational>& coefficients, Rational& constant) {
    AffineRow& a = affine_rows[2 * k + (tangent ? 1 : 0)];
    if (!a.formed) {
      const Eigen::VectorXd r = tangent ? friction[k].T : Eigen::VectorXd(G.row(static_cast<Eigen::Index>(k)).transpose());
      const double c = tangent ? friction[k].bias : h(static_cast<Eigen::Index>(k));
      std::vector<Rational> rq(n);
      a.constant = !tangent && h_exact ? (*h_exact)[k] : tangent && bias_exact ? (*bias_exact)[k] : exact(c);
      for (std::size_t i = 0; i < n; ++i) {
        rq[i] = exact(r(static_cast<Eigen::Index>(i)));
        if (sgn(rq[i]) != 0) a.constant += rq[i] * x0[i];
      }
      a.on.assign(force_rows, Rational(0));
      for (std::size_t row = 0; row < force_rows; ++row) {
        Rational sum = 0;
        for (std::size_t i = 0; i < n; ++i)
          if (sgn(rq[i]) != 0 && sgn(D[row][i]) != 0) sum += rq[i] * D[row][i];
        a.on[row] = sum;
      }
      a.formed = true;
    }
    constant = a.constant;
    coefficients.resize(held.size() + p);
    for (std::size_t v = 0; v < held.size() + p; ++v)
      coefficients[v] = a.on[v < held.size() ? held[v] : m + (v - held.size())];
  };
  // (session 72, speed72) The same rows in intervals, each formed once from enclosures of x0 and
  // D (every entry Interval::enclose of the exact one; the rows' doubles are exact points): a sum
  // or product only of terms certainly nonzero, so [0, 0] only where the exact number is 0, every
  // other entry an enclosure of it. A held set's system formed from them is refused where the
  // interval filters (square_certainly_infeasible, certainly_infeasible_in_intervals) find it
  // certainly without a solution — no rational formed for it; otherwise the exact path below
  // decides, as before. Of the escapement's 0.5 s (644 held sets) most are refused so.
  using kernels::Interval;
  const bool filter = assignment_interval_filter();
  struct IntervalAffineRow {
    bool formed = false;
    Interval constant;
    std::vector<Interval> on;   // by force row (m + p)
  };
  std::vector<IntervalAffineRow> interval_rows(filter ? 2 * m : 0);
  std::vector<Interval> x0_enclosed;
  held_force_detail::Matrix<Interval> D_enclosed;
  auto interval_affine = [&](std::size_t k, bool tangent) -> const IntervalAffineRow& {
    if (x0_enclosed.empty() && n > 0) {
      x0_enclosed.resize(n);
      D_enclosed.assign(force_rows, std::vector<Interval>(n, Interval(0)));
      if (full) {   // of the exact solve's (prepared above)
        for (std::size_t i = 0; i < n; ++i) {
          x0_enclosed[i] = Interval::enclose(x0[i]);
          for (std::size_t r = 0; r < force_rows; ++r) D_enclosed[r][i] = Interval::enclose(D[r][i]);
        }
      } else {   // from the doubles: x0 = a0, D_ri = minv_i W_ri, W as prepare() forms it
        for (std::size_t i = 0; i < n; ++i) {
          const auto c = static_cast<Eigen::Index>(i);
          x0_enclosed[i] = Interval::point(a0(c));
          for (std::size_t r = 0; r < force_rows; ++r) {
            const double j = rows.J(Eigen::Index(r), c);
            Interval w = j != 0 ? Interval::point(j) : Interval(0);
            bool zero = j == 0;
            if (r < m) {
              const Friction& f = friction[r];
              const int st = state[r];
              if (f.on && (st == slip_positive || st == slip_negative) && f.T(c) != 0) {
                const Interval term = Interval(st) * (Interval::point(f.mu_kinetic) / Interval::point(f.s)) * Interval::point(f.T(c));
                w = zero ? -term : w - term;
                zero = false;
              }
            }
            if (!zero) D_enclosed[r][i] = Interval::point(minv(c)) * w;
          }
        }
      }
    }
    IntervalAffineRow& a = interval_rows[2 * k + (tangent ? 1 : 0)];
    if (a.formed) return a;
    const auto row_k = static_cast<Eigen::Index>(k);
    auto coordinate = [&](std::size_t i) {
      const auto c = static_cast<Eigen::Index>(i);
      return tangent ? friction[k].T(c) : G(row_k, c);
    };
    a.constant = !tangent && h_exact    ? Interval::enclose((*h_exact)[k])
                 : tangent && bias_exact ? Interval::enclose((*bias_exact)[k])
                                         : Interval::point(tangent ? friction[k].bias : h(row_k));
    for (std::size_t i = 0; i < n; ++i)
      if (coordinate(i) != 0 && x0_enclosed[i].sign() != 0)
        a.constant = a.constant + Interval::point(coordinate(i)) * x0_enclosed[i];
    a.on.assign(force_rows, Interval(0));
    for (std::size_t row = 0; row < force_rows; ++row) {
      bool any = false;
      for (std::size_t i = 0; i < n; ++i) {
        if (coordinate(i) == 0 || D_enclosed[row][i].sign() == 0) continue;
        const Interval term = Interval::point(coordinate(i)) * D_enclosed[row][i];
        a.on[row] = any ? a.on[row] + term : term;
        any = true;
      }
    }
    a.formed = true;
    return a;
  };
  // true: the held set's system certainly has no solution (the filters above on its enclosure).
  // (Session 73, speed73: one system reused across the held sets — every held set has the same
  // rows, only the number of unknowns changes — its rows overwritten in place: no vector made per
  // row and per held set.)
  IntervalLinearSystem interval_lp;
  auto refused_in_intervals = [&](const std::vector<bool>& is_held, const std::vector<std::size_t>& held) {
    const std::size_t vars = held.size() + p;
    IntervalLinearSystem& lp = interval_lp;
    lp.variables = vars;
    lp.nonnegative.assign(vars, false);
    for (std::size_t v = 0; v < held.size(); ++v) lp.nonnegative[v] = true;
    std::size_t used = 0;   // rows written
    auto next_row = [&](bool equality, const Interval& rhs) -> std::vector<Interval>& {
      if (used == lp.rows.size()) {
        lp.rows.emplace_back();
        lp.rhs.emplace_back();
        lp.equality.push_back(false);
      }
      lp.rhs[used] = rhs;
      lp.equality[used] = equality;
      std::vector<Interval>& row = lp.rows[used++];
      row.resize(vars);
      return row;
    };
    auto add = [&](const IntervalAffineRow& a, bool equality, int sign) {   // as try_set's add
      std::vector<Interval>& row = next_row(equality, sign > 0 ? -a.constant : a.constant);
      for (std::size_t v = 0; v < vars; ++v) {
        const Interval& c = a.on[v < held.size() ? held[v] : m + (v - held.size())];
        row[v] = sign > 0 ? c : -c;
      }
    };
    for (std::size_t k = 0; k < m; ++k) add(interval_affine(k, false), is_held[k], 1);
    for (std::size_t j = 0; j < p; ++j) {
      const Friction& c = friction[reps[j]];
      add(interval_affine(reps[j], true), true, 1);
      for (int side : {1, -1}) {
        std::vector<Interval>& row = next_row(false, Interval(0));
        std::fill(row.begin(), row.end(), Interval(0));
        for (std::size_t v = 0; v < held.size(); ++v) {
          const std::size_t k = held[v];
          if (group_of(k) == group_of(reps[j]) && friction[k].on && state[k] == stick && c.mu_static != 0)
            row[v] = Interval::point(c.mu_static) / Interval::point(friction[k].s);
        }
        row[held.size() + j] = Interval(-side);
      }
    }
    for (std::size_t k = 0; k < m; ++k) {
      const Friction& c = friction[k];
      const int st = state[k];
      if (!c.on || c.decided || (st != slip_positive && st != slip_negative)) continue;
      add(interval_affine(k, true), false, st);
    }
    lp.rows.resize(used);   // (the same count for every held set: nothing freed)
    lp.rhs.resize(used);
    lp.equality.resize(used);
    const std::optional<bool> square = square_certainly_infeasible(lp);
    if (square) return *square;
    return certainly_infeasible_in_intervals(lp);
  };
  auto try_set = [&](const std::vector<bool>& is_held) -> std::optional<FrictionalSolution> {
    std::vector<std::size_t> held;
    for (std::size_t k = 0; k < m; ++k)
      if (is_held[k]) held.push_back(k);
    const std::size_t vars = held.size() + p;
    if (filter && refused_in_intervals(is_held, held)) {
      if (tried) ++*tried;
      ++assignment_interval_refused();
      return std::nullopt;
    }
    prepare();
    ExactLinearSystem lp;
    lp.variables = vars;
    lp.nonnegative.assign(vars, false);
    for (std::size_t v = 0; v < held.size(); ++v) lp.nonnegative[v] = true;
    std::vector<Rational> coefficients;
    Rational constant;
    auto add = [&](bool equality, int sign) {   // sign (coefficients . z + constant) (= or >=) 0
      for (Rational& c : coefficients) c *= sign;
      lp.rows.push_back(coefficients);
      lp.rhs.push_back(-sign * constant);
      lp.equality.push_back(equality);
    };
    for (std::size_t k = 0; k < m; ++k) {
      affine(k, false, held, coefficients, constant);
      add(is_held[k], 1);
    }
    for (std::size_t j = 0; j < p; ++j) {
      const Friction& c = friction[reps[j]];
      affine(reps[j], true, held, coefficients, constant);
      add(true, 1);
      // mu_s sum lambda_k / s_k -+ f_j >= 0 over the group's held sticking members
      for (int side : {1, -1}) {
        std::vector<Rational> row(vars, Rational(0));
        for (std::size_t v = 0; v < held.size(); ++v) {
          const std::size_t k = held[v];
          if (group_of(k) == group_of(reps[j]) && friction[k].on && state[k] == stick)
            row[v] = exact(c.mu_static) / exact(friction[k].s);
        }
        row[held.size() + j] = -side;
        lp.rows.push_back(std::move(row));
        lp.rhs.push_back(Rational(0));
        lp.equality.push_back(false);
      }
    }
    for (std::size_t k = 0; k < m; ++k) {
      const Friction& c = friction[k];
      const int st = state[k];
      if (!c.on || c.decided || (st != slip_positive && st != slip_negative)) continue;
      affine(k, true, held, coefficients, constant);
      add(false, st);
    }
    if (tried) ++*tried;
    const std::optional<std::vector<Rational>> z = square_feasible_point(lp, filter);
    if (!z) return std::nullopt;
    // the solution: exact multipliers and forces, accelerations and gap accelerations
    std::vector<Rational> lambda(m, Rational(0)), force(m, Rational(0));
    for (std::size_t v = 0; v < held.size(); ++v) lambda[held[v]] = (*z)[v];
    std::vector<Rational> x(x0);
    for (std::size_t v = 0; v < vars; ++v) {
      if (sgn((*z)[v]) == 0) continue;
      const std::size_t row = v < held.size() ? held[v] : m + (v - held.size());
      for (std::size_t i = 0; i < n; ++i)
        if (sgn(D[row][i]) != 0) x[i] += D[row][i] * (*z)[v];
    }
    for (std::size_t j = 0; j < p; ++j) {
      const Rational& fg = (*z)[held.size() + j];
      Rational total = 0;
      for (std::size_t k = 0; k < m; ++k)
        if (group_of(k) == group_of(reps[j]) && friction[k].on && state[k] == stick)
          total += lambda[k] / exact(friction[k].s);
      for (std::size_t k = 0; k < m; ++k)
        if (group_of(k) == group_of(reps[j]) && friction[k].on && state[k] == stick)
          force[k] = sgn(total) > 0 ? Rational(fg * (lambda[k] / exact(friction[k].s)) / total)
                                    : (k == reps[j] ? fg : Rational(0));
    }
    FrictionalSolution s;
    s.solved = true;
    s.state = state;
    s.tolerance = 0;   // exact: an open contact with w > 0 lifts, one at w = 0 stays
    s.lambda.resize(static_cast<Eigen::Index>(m));
    s.f.resize(static_cast<Eigen::Index>(m));
    s.w.resize(static_cast<Eigen::Index>(m));
    s.x.resize(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) s.x(static_cast<Eigen::Index>(i)) = to_double(x[i]);
    if (full) {   // to the coordinates of the rows as given, z = L^T q (M = L L^T)
      const Eigen::LLT<Eigen::MatrixXd> llt(full->M);
      if (llt.info() != Eigen::Success)
        throw NumericError("a held contact's force problem: the mass matrix is not positive definite in doubles");
      s.x = llt.matrixU() * s.x;
    }
    for (std::size_t k = 0; k < m; ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      const Friction& c = friction[k];
      if (c.on && (state[k] == slip_positive || state[k] == slip_negative))
        force[k] = -state[k] * exact(c.mu_kinetic) * lambda[k] / exact(c.s);
      Rational wk = h_exact ? (*h_exact)[k] : exact(h(r));
      for (std::size_t i = 0; i < n; ++i) wk += exact(G(r, static_cast<Eigen::Index>(i))) * x[i];
      s.lambda(r) = to_double(lambda[k]);
      s.f(r) = to_double(force[k]);
      // (an open contact's gap acceleration exactly 0 published as 0; a positive one stays positive)
      s.w(r) = is_held[k] ? 0.0 : to_double(wk);
    }
    s.x_exact = std::move(x);
    return s;
  };
  if (first) {
    if (auto s = try_set(*first)) return s;
    if (first_only) return std::nullopt;
  }
  // (session 70, exact70: beyond 12 contacts, where the 2^m held sets are not enumerated — until
  // then nullopt there, the doubles deciding — the held set of the assignment's exact LCP: the
  // sticking rows' friction eliminated exactly, T_S x + bias_S = 0 solved for f in lambda, then
  // w = A lambda + b over every contact in rationals, Lemke's algorithm exactly (exact_lemke.hpp);
  // its solution's held set (w = 0) is decided by the same exact LP as any other, the Coulomb
  // conditions included. Where Lemke ends on a ray (A need not be copositive-plus once contacts
  // slip), the sticking rows are dependent, or the LCP's solution breaks a Coulomb condition,
  // nothing is decided: nullopt, as before.)
  if (m > 12) {
    prepare();
    std::vector<std::size_t> all(m);
    for (std::size_t k = 0; k < m; ++k) all[k] = k;
    std::vector<Rational> coefficients;
    Rational constant;
    // f = F lambda + F0: the sticking rows' equalities T_S D^T [lambda; f] + c_S = 0
    held_force_detail::Matrix<Rational> stick_rows(p, std::vector<Rational>(p)), stick_rhs(p, std::vector<Rational>(m + 1));
    for (std::size_t j = 0; j < p; ++j) {
      affine(reps[j], true, all, coefficients, constant);
      for (std::size_t l = 0; l < p; ++l) stick_rows[j][l] = coefficients[m + l];
      for (std::size_t l = 0; l < m; ++l) stick_rhs[j][l] = -coefficients[l];
      stick_rhs[j][m] = -constant;
    }
    held_force_detail::Matrix<Rational> F;
    if (p > 0) {
      std::optional<held_force_detail::Matrix<Rational>> solved =
          held_force_detail::solve(std::move(stick_rows), std::move(stick_rhs));
      if (!solved) return std::nullopt;
      F = std::move(*solved);
    }
    held_force_detail::Matrix<Rational> A(m, std::vector<Rational>(m));
    std::vector<Rational> b(m);
    for (std::size_t k = 0; k < m; ++k) {
      affine(k, false, all, coefficients, constant);
      b[k] = constant;
      for (std::size_t l = 0; l < m; ++l) A[k][l] = coefficients[l];
      for (std::size_t j = 0; j < p; ++j) {
        const Rational& c = coefficients[m + j];
        if (sgn(c) == 0) continue;
        b[k] += c * F[j][m];
        for (std::size_t l = 0; l < m; ++l)
          if (sgn(F[j][l]) != 0) A[k][l] += c * F[j][l];
      }
    }
    const std::optional<ExactLcpSolution> lcp = exact_lemke(A, b);
    if (!lcp) return std::nullopt;
    std::vector<bool> is_held(m);
    for (std::size_t k = 0; k < m; ++k) is_held[k] = sgn(lcp->w[k]) == 0;
    // (the doubles' held set `first` was decided above; Lemke's being the same, nothing else is
    // tried although another held set might be consistent at these states: nullopt, not a verdict
    // — every caller reads a nullopt beyond 12 contacts so: solve_frictional's unsolved result is
    // not `exhausted`, creates_energy compares the applied velocities' energy, the fixed-axis and
    // full-form impacts publish `exhausted` false)
    if (first && is_held == *first) return std::nullopt;
    return try_set(is_held);
  }
  std::vector<std::size_t> codes(std::size_t{1} << m);
  for (std::size_t c = 0; c < codes.size(); ++c) codes[c] = c;
  // the largest held sets first (bit k set: contact k open), lexicographic within a size
  std::stable_sort(codes.begin(), codes.end(), [](std::size_t a, std::size_t b) {
    return __builtin_popcountll(a) < __builtin_popcountll(b);
  });
  for (std::size_t code : codes) {
    std::vector<bool> is_held(m);
    for (std::size_t k = 0; k < m; ++k) is_held[k] = !((code >> k) & 1);
    if (first && is_held == *first) continue;
    if (auto s = try_set(is_held)) return s;
  }
  return std::nullopt;
}

/// The order in which the stick/slip assignments of `open` undecided contacts are tried: codes in
/// base 3 (digit i: contact open[i] sticks, 0, slides positive, 1, or negative, 2), the fewest
/// sliding contacts first, in code order within a count (solve_frictional's enumeration; session
/// 70, exact70: shared with held_friction.hpp's full_form_impulses).
inline std::vector<std::size_t> assignment_order(std::size_t open) {
  std::size_t combinations = 1;
  for (std::size_t i = 0; i < open; ++i) combinations *= 3;
  std::vector<std::size_t> order(combinations);
  auto slips = [&](std::size_t code) {
    int count = 0;
    for (std::size_t i = 0; i < open; ++i, code /= 3) count += code % 3 != 0;
    return count;
  };
  for (std::size_t c = 0; c < combinations; ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return slips(a) < slips(b); });
  return order;
}

/// The states of the contacts `open` for an assignment's code (assignment_order) written into state.
inline void assign_states(std::size_t code, const std::vector<std::size_t>& open, std::vector<int>& state) {
  for (std::size_t i = 0; i < open.size(); ++i, code /= 3) {
    static constexpr int digit_state[3] = {stick, slip_positive, slip_negative};
    state[open[i]] = digit_state[code % 3];
  }
}

/// The normal LCP with Coulomb friction: states of the undecided frictional contacts by
/// enumeration (fewest sliding contacts first; at most 3^8 assignments), each assignment's
/// normal LCP solved by solve_lcp. solved = false when no assignment is consistent.
/// `adjust` (optional) may redistribute the tangential forces of a candidate solution before
/// its Coulomb conditions are checked (the planar simulator splits the friction of collinear
/// contacts, whose split the equations leave open, in proportion to their normal forces).
/// `undetermined_plain`: an assignment whose sticking rows leave the multipliers open is also
/// tried with the frictionless multipliers (undetermined(), above; the fixed-axis simulator's
/// wedges, session 36). `exact_groups` (given: the collinear groups by contact, empty for none):
/// an assignment's stick limits are also decided exactly (exact_stick_holds; session 63), a
/// friction force beyond mu_s N by any amount rejects the sticking assignment, and every
/// assignment the doubles' filter does not accept (a stick not verified exactly; since session 66
/// also one without a sticking contact whose LCP or slip-direction test failed) is decided by the
/// exact LP (exact_assignment). `full` (given, with exact_groups): those decisions taken on the
/// problem's full form (FullMass); an exact solution's x is then in the given rows' coordinates.
inline FrictionalSolution solve_frictional(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv,
                                           const Eigen::VectorXd& a0, const Eigen::VectorXd& h,
                                           const std::vector<Friction>& friction,
                                           const std::function<void(FrictionalSolution&)>& adjust = {},
                                           bool undetermined_plain = false,
                                           const std::vector<std::size_t>* exact_groups = nullptr,
                                           const FullMass* full = nullptr,
                                           const std::vector<Rational>* h_exact = nullptr) {
  const std::size_t m = friction.size();
  // (session 68, impact68: h_exact, with exact_groups, the velocity terms as exact rationals — an
  // impact's restitution terms e G v-. Where every double of h is its exact term the decisions
  // below are exact on them as before; where some is rounded (e = 0.3), a candidate the doubles'
  // filters accept is kept only where its held set is also exactly consistent on the exact terms
  // (exact_assignment, first_only), and every exact decision is taken on the exact terms.)
  const std::vector<Rational>* rounded = nullptr;
  if (exact_groups && h_exact)
    for (std::size_t k = 0; k < m && !rounded; ++k)
      if ((*h_exact)[k] != held_force_detail::exact_value(h(static_cast<Eigen::Index>(k)))) rounded = h_exact;
  std::vector<std::size_t> open;
  std::vector<int> state(m, frictionless);
  for (std::size_t k = 0; k < m; ++k) {
    if (!friction[k].on) continue;
    if (friction[k].decided) state[k] = friction[k].state;
    else open.push_back(k);
  }
  FrictionalSolution best;
  if (open.size() > 8) return best;   // (not a verdict: exhausted false)
  // (session 71, exact71: an unsolved result is a verdict only where the exact mode decided every
  // assignment on every held set — up to 12 contacts, exact_assignment's enumeration)
  best.exhausted = exact_groups && m <= 12;
  std::optional<LcpSolution> plain;   // the frictionless problem, once needed
  Eigen::MatrixXd Af;
  Eigen::VectorXd bf;
  const std::vector<std::size_t> order = assignment_order(open.size());
  // Every assignment's matrices, LCP and candidate solution in storage kept across the
  // enumeration (BilateralWork, LcpWork): each is resized and written before it is read, by the
  // same Eigen operations as the fresh ones per assignment before — the same doubles (session
  // 60: the impacts' enumeration allocated some 200 blocks per call).
  BilateralWork work;
  const Reduced& r = work.r;
  Eigen::MatrixXd& A = work.A;
  Eigen::VectorXd& b = work.b;
  LcpWork lcp_work;
  LcpSolution lcp;
  FrictionalSolution s;
  for (std::size_t code : order) {
    assign_states(code, open, state);
    reduce(G, minv, a0, friction, state, work.r, work);
    A.noalias() = G * r.B;
    b = G * r.x0 + h;
    solve_lcp(A, b, lcp_work, lcp);
    // (every field coulomb_satisfied and adjust read is written below before it is read)
    s.solved = false;
    s.state = state;
    s.x_exact.clear();
    bool sticks = false;   // some contact of this assignment sticks
    bool slides = false;   // some undecided contact of this assignment slides
    for (std::size_t k = 0; k < m; ++k) {
      sticks = sticks || (friction[k].on && state[k] == stick);
      slides = slides || (friction[k].on && !friction[k].decided &&
                          (state[k] == slip_positive || state[k] == slip_negative));
    }
    // the doubles' held set (all but the contacts their LCP lets separate), exact mode
    std::vector<bool> held_first;
    if (exact_groups && lcp.solved) {
      held_first.resize(m);
      for (std::size_t k = 0; k < m; ++k) {
        const auto r = static_cast<Eigen::Index>(k);
        held_first[k] = !(lcp.lambda(r) <= 0 && lcp.w(r) > lcp.tolerance);
      }
    }
    if (lcp.solved) {
      s.lambda = lcp.lambda;
      s.tolerance = lcp.tolerance;
      complete(s, r, G, h, friction);
      if (adjust) adjust(s);
      // (exact mode, an assignment with a sticking contact: the doubles' Coulomb test is a filter;
      // a candidate it accepts is taken only where exact_stick_holds verifies a consistent member
      // exactly, and every other case — the doubles' LCP failed, their test or the exact one
      // rejected — is decided by exact_assignment below (session 65). Session 64's scotch yoke
      // change, "dropping the doubles' test", was exact_stick_holds accepting a stick whose
      // sticking contact the LCP let separate with a friction of 3e21 and no normal force: that
      // contact was left out of its rows; exact_assignment finds no consistent stick there.)
      // (session 66, slip66: an assignment without a sticking contact whose undecided sliding
      // contacts the doubles accept — their slip-direction test has a 1e-9 slack — is taken only
      // where the exact LP on the candidate's held set confirms it; otherwise decided below as
      // a rejected candidate.)
      // (session 69, exact69: a confirmation's exact x is kept with the doubles' candidate —
      // FrictionalSolution::x_exact — for the restitution limit's exact energy test)
      std::optional<FrictionalSolution> confirmation;
      auto confirmed = [&] {
        confirmation =
            exact_assignment(G, minv, a0, h, friction, state, *exact_groups, &held_first, nullptr, full, true, rounded);
        return confirmation.has_value();
      };
      if (exact_groups && sticks
              ? coulomb_satisfied(s, friction) &&
                    exact_stick_holds(G, minv, a0, h, friction, s, *exact_groups, full) && (!rounded || confirmed())
              : coulomb_satisfied(s, friction) && (!exact_groups || (!slides && !rounded) || confirmed())) {
        s.solved = true;
        if (confirmation) s.x_exact = std::move(confirmation->x_exact);
        return s;
      }
    }
    // (session 65: where the doubles' candidate is not an exactly consistent stick — their LCP
    // failed, their Coulomb test rejected it, or the exact limits did — whether SOME force of the
    // assignment is consistent is decided exactly, exact_assignment; the doubles' held set first.
    // Session 66 (fullform66): with a full form given (the pin-slot part, FullMass) on that form
    // (exact M^-1 Q and M^-1 W^T; until then not asked there: a stick the doubles rejected beyond
    // their slack was missed), and an assignment without a sticking contact (every undecided
    // contact sliding) the same way where the doubles' filter fails — their LCP failed or their
    // slip-direction test with its 1e-9 slack rejected it: the LP with the sliding forces
    // f = -sign mu_k N fixed (until then the doubles' "no" was the decision).)
    if (exact_groups) {
      if (std::optional<FrictionalSolution> e =
              exact_assignment(G, minv, a0, h, friction, state, *exact_groups, lcp.solved ? &held_first : nullptr,
                               nullptr, full, false, rounded))
        return *e;
      continue;
    }
    // multipliers left open by the sticking rows: the frictionless ones, where they solve this
    // assignment's problem and satisfy its Coulomb conditions (undetermined(), above)
    if (!undetermined_plain || r.sticking.empty()) continue;
    if (!plain) {
      Af = G * minv.asDiagonal() * G.transpose();
      bf = G * a0 + h;
      plain = solve_lcp(Af, bf);
    }
    if (!plain->solved || !undetermined(A, Af)) continue;
    const double tolerance = 10 * std::max(plain->tolerance, lcp_tolerance(A, b));
    if (!lcp_satisfied(A, b, plain->lambda, tolerance, lcp_work.w)) continue;
    s.lambda = plain->lambda;
    s.tolerance = tolerance;
    complete(s, r, G, h, friction);
    if (adjust) adjust(s);
    if (!coulomb_satisfied(s, friction)) continue;
    s.solved = true;
    return s;
  }
  return best;
}

}  // namespace hipair::simulation
