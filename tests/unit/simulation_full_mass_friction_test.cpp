// Frictional problems with a full mass matrix (session 65, pinslot65): friction.hpp's FullMass form,
// on which the pin-slot simulator's exact decisions are taken (held_verdict, exact_stick_holds
// through solve_frictional), and held_friction.hpp's restitution limit of a frictional impact.
//
// The ties: generated problems over n = 2..4 coordinates with a coupled mass matrix M (integer
// entries times a power of two: exact doubles), one held contact's normal row J and tangent row T
// (integers), an acceleration a (integers) with kappa = -J a and bias = -T a, and the multipliers
// planted: lambda = k 2^p, f = +-mu lambda with mu = j / 16; the loads Q = M a - J^T lambda - T^T f
// (exact), the normal force of the loads' size. The oracle is the planting: sticking, the friction is exactly mu_s N at mu_s = mu (it
// sticks: the tie rule) and beyond it at the next double below mu (it slips). The same problems
// in the coordinates of M's Cholesky factor (the rows J L^-T, T L^-T, M the identity: the pin-slot
// simulator's decisions until session 65) are counted where they disagree with the oracle.
#include <gtest/gtest.h>

#include "simulation/friction.hpp"
#include "simulation/held_friction.hpp"
#include "held_oracle_support.hpp"
#include "test_seed.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace hipair {
namespace {

using held_oracle::Rng;

struct Tie {
  simulation::FullMass full;   // the rows over the coordinates, M and Q
  Eigen::VectorXd kappa;
  double mu = 0;
};

// `shift`: the normal force 2^-shift smaller (0: of the loads' size)
Tie planted_tie(Rng& rng, int n, int shift = 0) {
  Tie out;
  const double unit = std::ldexp(1.0, rng.below(41) - 20);   // the masses' scale
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = rng.below(5) - 2;
  Eigen::MatrixXd M = A * A.transpose();
  for (int i = 0; i < n; ++i) M(i, i) += 1 + rng.below(4);
  M *= unit;
  Eigen::MatrixXd J(1, n);
  Eigen::VectorXd T(n), a(n);
  for (;;) {
    for (int i = 0; i < n; ++i) {
      J(0, i) = rng.below(7) - 3;
      T(i) = rng.below(7) - 3;
      a(i) = rng.below(9) - 4;
    }
    // independent rows: some 2 x 2 minor not 0
    bool independent = false;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) independent = independent || J(0, i) * T(j) - J(0, j) * T(i) != 0;
    if (independent) break;
  }
  // (shift 0: the normal force of the loads' size; where it is far below them the doubles'
  // multipliers miss the tie by more than solve_frictional's 1e-9 stick slack: the test below)
  const double lambda = (1 + rng.below(8)) * unit * std::ldexp(1.0, rng.below(7) - 3 - shift);
  out.mu = (2 + rng.below(14)) / 16.0;
  const double f = (rng.below(2) == 0 ? 1 : -1) * out.mu * lambda;
  out.full.G = J;
  out.full.M = M;
  out.full.Q = M * a - J.row(0).transpose() * lambda - T * f;   // exact: integers times powers of two
  out.kappa = Eigen::VectorXd::Constant(1, -J.row(0).dot(a));
  simulation::Friction fr;
  fr.on = true;
  fr.T = T;
  fr.mu_static = fr.mu_kinetic = out.mu;
  fr.bias = -T.dot(a);
  out.full.friction = {fr};
  return out;
}

// The same problem in the coordinates z = L^T q of M's Cholesky factor (M = L L^T; doubles)
struct Transformed {
  Eigen::MatrixXd G;
  Eigen::VectorXd minv, a0;
  std::vector<simulation::Friction> friction;
};
Transformed cholesky_form(const Tie& p) {
  Transformed out;
  const Eigen::LLT<Eigen::MatrixXd> llt(p.full.M);
  out.G = llt.matrixL().solve(p.full.G.transpose()).transpose();
  out.a0 = llt.matrixL().solve(p.full.Q);
  out.minv = Eigen::VectorXd::Ones(p.full.M.rows());
  out.friction = p.full.friction;
  out.friction[0].T = llt.matrixL().solve(p.full.friction[0].T);
  return out;
}

void set_mu(Tie& p, Transformed& z, double mu) {
  for (auto* f : {&p.full.friction[0], &z.friction[0]}) f->mu_static = f->mu_kinetic = mu;
}

using held_oracle::slip_consistent;

TEST(FullMassFriction, StickLimitsAtPlantedTiesAreDecidedOnTheFullMassRows) {
  Rng rng{test::test_seed(6501)};
  int cases = 0, verdict_wrong = 0, enumeration_wrong = 0;
  const std::vector<std::size_t> own;   // each contact its own group
  for (int trial = 0; trial < 240; ++trial) {
    const int n = 2 + trial % 3;
    Tie p = planted_tie(rng, n);
    Transformed z = cholesky_form(p);
    const std::vector<int> stick{simulation::stick};
    for (const bool at_tie : {true, false}) {
      set_mu(p, z, at_tie ? p.mu : std::nextafter(p.mu, 0.0));
      ++cases;
      // held_verdict: the full form against the planting
      const simulation::HeldVerdict v =
          simulation::held_verdict(z.G, z.minv, z.a0, p.kappa, z.friction, stick, {}, nullptr, nullptr, nullptr, &p.full);
      ASSERT_EQ(v.force_sign[0], 1) << trial;
      EXPECT_EQ(v.beyond_static[0], !at_tie) << "trial " << trial << " n " << n << " mu " << p.mu;
      // the Cholesky form (the old decisions) against the planting: counted
      const simulation::HeldVerdict old = simulation::held_verdict(z.G, z.minv, z.a0, p.kappa, z.friction, stick);
      verdict_wrong += old.beyond_static[0] != !at_tie;
      // solve_frictional with exact stick limits on the full form: a stick at the tie, none below it
      std::vector<simulation::Friction> undecided = z.friction;
      undecided[0].decided = false;
      const simulation::FrictionalSolution sol =
          simulation::solve_frictional(z.G, z.minv, z.a0, p.kappa, undecided, {}, false, &own, &p.full);
      ASSERT_TRUE(sol.solved) << trial;
      EXPECT_EQ(sol.state[0] == simulation::stick, at_tie) << "trial " << trial << " n " << n << " mu " << p.mu;
      const simulation::FrictionalSolution before =
          simulation::solve_frictional(z.G, z.minv, z.a0, p.kappa, undecided, {}, false, &own);
      enumeration_wrong += !before.solved || (before.state[0] == simulation::stick) != at_tie;
    }
  }
  std::cout << "planted ties: " << cases << " decisions; the Cholesky form's held_verdict wrong in " << verdict_wrong
            << ", its enumeration's stick wrong in " << enumeration_wrong << "\n";
}

// Session 66 (fullform66): the normal force 2^-24 ... 2^-32 of the loads' size, where the doubles'
// multipliers (in the Cholesky coordinates) miss the tie by far more than solve_frictional's 1e-9
// slack and their filter rejects sticks that exist. mu_s at the planted mu, the next double below
// it, and mu (1 +- 2^-k), k = 1..48. The oracle, exact rationals over the planted problem: held,
// the force is the planted (lambda, f) (one solution: J and T independent, M positive definite), so
// a stick exists iff mu_s >= mu (|f| = mu lambda); open (lambda = 0, f = 0) it needs T M^-1 Q +
// bias = 0 and J M^-1 Q + kappa >= 0 (such cases skipped); a slip in direction sigma (f = -sigma
// mu_k N) exists iff, held, lambda = -(J M^-1 Q + kappa) / (J M^-1 W^T) >= 0 (W = J - sigma mu_k T)
// and sigma (T x + bias) >= 0 at x = M^-1 (Q + W^T lambda), or, open, J M^-1 Q + kappa >= 0 and
// sigma (T M^-1 Q + bias) >= 0. Asserted on every case: solve_frictional (exact mode, the full
// form) sticks iff the oracle has a stick, finds an assignment iff the oracle has one, and a stick
// publishes accelerations x in the Cholesky coordinates (L^-T x = M^-1 (Q + J^T lambda + T^T f)
// at its multipliers, to the factor's rounding). Until session 66 solve_frictional did not ask the exact
// LP on a full form (`if (full) continue;`): the sticks the doubles rejected were missed.
TEST(FullMassFriction, StickWithANormalForceFarBelowTheLoadsIsDecidedOnTheFullMassRows) {
  using held_oracle::RMatrix;
  Rng rng{test::test_seed(6601)};
  const std::vector<std::size_t> own;
  int cases = 0, sticks = 0, slips = 0, none = 0, skipped = 0, doubles_wrong = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + trial % 3;
    Tie p = planted_tie(rng, n, 24 + rng.below(9));
    Transformed z = cholesky_form(p);
    const simulation::Friction& fr0 = p.full.friction[0];
    // exact data; Q as planted, checked exact
    RMatrix M(n, std::vector<Rational>(n));
    std::vector<Rational> Q(n), J(n), T(n), minus_Q(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) M[i][j] = Rational(p.full.M(i, j));
      Q[i] = Rational(p.full.Q(i));
      minus_Q[i] = -Q[i];
      J[i] = Rational(p.full.G(0, i));
      T[i] = Rational(fr0.T(i));
    }
    const std::vector<Rational> a0 = held_oracle::cramer(M, minus_Q);   // M a0 = Q
    const Rational kappa(p.kappa(0)), bias(fr0.bias);
    auto dot = [&](const std::vector<Rational>& u, const std::vector<Rational>& v) {
      Rational out = 0;
      for (int i = 0; i < n; ++i) out += u[i] * v[i];
      return out;
    };
    const Rational Ja0 = dot(J, a0) + kappa, Ta0 = dot(T, a0) + bias;
    if (sgn(Ta0) == 0 && sgn(Ja0) >= 0) {
      ++skipped;
      continue;
    }
    // the planted multipliers: M a = Q + J^T lambda + T^T f, J a + kappa = 0, T a + bias = 0
    // (one solution): recovered exactly from a0 and the 2 x 2 Delassus system (cramer: A x = -b)
    std::vector<Rational> minus_J(n), minus_T(n);
    for (int i = 0; i < n; ++i) {
      minus_J[i] = -J[i];
      minus_T[i] = -T[i];
    }
    const std::vector<Rational> MJ = held_oracle::cramer(M, minus_J), MT = held_oracle::cramer(M, minus_T);
    const RMatrix A{{dot(J, MJ), dot(J, MT)}, {dot(T, MJ), dot(T, MT)}};
    const std::vector<Rational> planted = held_oracle::cramer(A, {Ja0, Ta0});   // (lambda, f)
    ASSERT_GT(sgn(planted[0]), 0) << trial;
    ASSERT_EQ(abs(planted[1]), Rational(p.mu) * planted[0]) << trial;   // the planting exact
    for (int variant = 0; variant < 4; ++variant) {
      const int k = 1 + rng.below(48);
      double mu = p.mu;
      if (variant == 1) mu = std::nextafter(p.mu, 0.0);
      if (variant == 2) mu = to_double(Rational(p.mu) * (Rational(1) + Rational(std::ldexp(1.0, -k))));
      if (variant == 3) mu = to_double(Rational(p.mu) * (Rational(1) - Rational(std::ldexp(1.0, -k))));
      set_mu(p, z, mu);
      ++cases;
      const Rational muq(mu);
      const bool stick_exists = muq * planted[0] >= abs(planted[1]);
      const bool slip_exists = slip_consistent(1, muq, a0, J, T, MJ, MT, bias, Ja0, Ta0) ||
                               slip_consistent(-1, muq, a0, J, T, MJ, MT, bias, Ja0, Ta0);
      std::vector<simulation::Friction> undecided = z.friction;
      undecided[0].decided = false;
      const simulation::FrictionalSolution sol =
          simulation::solve_frictional(z.G, z.minv, z.a0, p.kappa, undecided, {}, false, &own, &p.full);
      const std::string where = "trial " + std::to_string(trial) + " variant " + std::to_string(variant) + " n " +
                                std::to_string(n) + " mu " + std::to_string(p.mu);
      ASSERT_EQ(sol.solved, stick_exists || slip_exists) << where;
      if (!sol.solved) {
        ++none;
        continue;
      }
      EXPECT_EQ(sol.state[0] == simulation::stick, stick_exists) << where;
      (sol.state[0] == simulation::stick ? sticks : slips) += 1;
      {   // the accelerations x in the Cholesky coordinates: L^-T x = M^-1 (Q + J^T lambda + T^T f) at the
          // published multipliers (the doubles' candidate or the exact LP's), to the factor's rounding
        const Eigen::LLT<Eigen::MatrixXd> llt(p.full.M);
        const Eigen::VectorXd a = llt.matrixU().solve(sol.x);
        const Eigen::VectorXd load = p.full.Q + p.full.G.row(0).transpose() * sol.lambda(0) + fr0.T * sol.f(0);
        const Eigen::VectorXd expected = p.full.M.ldlt().solve(load);
        const double condition = p.full.M.norm() * p.full.M.inverse().norm();
        const Eigen::VectorXd loads = p.full.Q.cwiseAbs() +
                                      p.full.G.row(0).transpose().cwiseAbs() * std::abs(sol.lambda(0)) +
                                      fr0.T.cwiseAbs() * std::abs(sol.f(0));
        const double scale = (p.full.M.inverse().cwiseAbs() * loads).maxCoeff();
        EXPECT_LE((a - expected).cwiseAbs().maxCoeff(), 256 * 0x1p-52 * condition * scale) << where;
        if (sol.state[0] == simulation::stick)   // the planted force, to the doubles' filter's 1e-9 slack at most
          EXPECT_LE(std::abs(sol.f(0)), sol.lambda(0) * mu * (1 + 1e-9) + 1e-300) << where;
      }
      const simulation::FrictionalSolution before =
          simulation::solve_frictional(z.G, z.minv, z.a0, p.kappa, undecided, {}, false, &own);
      doubles_wrong += !before.solved || (before.state[0] == simulation::stick) != stick_exists;
    }
  }
  std::cout << "normal force far below the loads: " << cases << " decisions (" << skipped << " trials skipped), "
            << sticks << " sticks, " << slips << " slips, " << none << " without a consistent assignment; the Cholesky "
            << "form's decision wrong in " << doubles_wrong << "\n";
  EXPECT_GT(sticks, cases / 4);
  EXPECT_GT(slips, cases / 8);
}

// Session 66 (slip66): ties at the slip direction. One held contact planted sliding in direction
// sigma: J a + kappa = 0, the friction f = -sigma mu_k lambda, and the tangential acceleration
// T a + bias = t planted exactly 0, +sigma delta (sliding on) or -sigma delta (the planted slip
// inconsistent by delta), delta = 2^-k (k = 31..48) of the loads' size |T| |a| — inside the 1e-9
// slack of the doubles' slip-direction test. mu_s = mu_k or mu_k / 2 (the stick then mostly
// excluded). Odd trials: a diagonal M (powers of two) solved in the diagonal form (the planar
// simulators'); even trials: a coupled M in the Cholesky coordinates with the full form given (the
// pin-slot simulator's). The oracle, exact rationals: a stick held ((lambda, f) of the 2 x 2
// system, lambda >= 0, |f| <= mu_s lambda) or open (J M^-1 Q + kappa >= 0, T M^-1 Q + bias = 0);
// a slip sigma held (lambda = -(J M^-1 Q + kappa) / (J M^-1 W^T) >= 0, W = J - sigma mu_k T,
// sigma (T x + bias) >= 0) or open. Asserted: solve_frictional (exact mode) finds an assignment
// iff the oracle has one, sticks iff the oracle has a stick, and a slip it publishes is one the
// oracle has. Until session 66 a slip the doubles accepted within their slack was taken unchecked.
TEST(FullMassFriction, ASlipTheDoublesAcceptAtATieIsConfirmedExactly) {
  using held_oracle::RMatrix;
  Rng rng{test::test_seed(6611)};
  const std::vector<std::size_t> own;
  int cases = 0, sticks = 0, slips = 0, none = 0, doubles_wrong = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 3;
    const bool diagonal = trial % 2 == 1;
    const double unit = std::ldexp(1.0, rng.below(21) - 10);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
    if (diagonal) {
      for (int i = 0; i < n; ++i) M(i, i) = std::ldexp(1.0, rng.below(7) - 3);
    } else {
      Eigen::MatrixXd A(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = rng.below(5) - 2;
      M = A * A.transpose();
      for (int i = 0; i < n; ++i) M(i, i) += 1 + rng.below(4);
    }
    M *= unit;
    Eigen::MatrixXd Jm(1, n);
    Eigen::VectorXd Tv(n), a(n);
    for (;;) {
      double size = 0;
      for (int i = 0; i < n; ++i) {
        Jm(0, i) = rng.below(7) - 3;
        Tv(i) = rng.below(7) - 3;
        a(i) = rng.below(9) - 4;
      }
      bool independent = false;
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) independent = independent || Jm(0, i) * Tv(j) - Jm(0, j) * Tv(i) != 0;
      size = Tv.cwiseAbs().dot(a.cwiseAbs());
      if (independent && size > 0) break;
    }
    const int sigma = rng.below(2) == 0 ? 1 : -1;
    const double mu_k = (2 + rng.below(14)) / 16.0;
    const double lambda0 = (1 + rng.below(8)) * unit * std::ldexp(1.0, rng.below(7) - 3);
    const double size = std::exp2(std::ceil(std::log2(Tv.cwiseAbs().dot(a.cwiseAbs()))));
    const int variant = trial % 3, k = 31 + rng.below(18);
    const double t = variant == 0 ? 0.0 : (variant == 1 ? sigma : -sigma) * std::ldexp(size, -k);
    const Eigen::VectorXd Q = M * a - Jm.row(0).transpose() * lambda0 + Tv * (sigma * mu_k * lambda0);   // exact
    const Eigen::VectorXd kappa = Eigen::VectorXd::Constant(1, -Jm.row(0).dot(a));
    simulation::Friction fr;
    fr.on = true;
    fr.T = Tv;
    fr.mu_kinetic = mu_k;
    fr.mu_static = rng.below(2) == 0 ? mu_k : mu_k / 2;
    fr.bias = t - Tv.dot(a);
    ASSERT_EQ(Rational(fr.bias), Rational(t) - Rational(Tv.dot(a))) << trial;   // the planting exact
    // the oracle, exact
    RMatrix Mq(n, std::vector<Rational>(n));
    std::vector<Rational> minus_Q(n), J(n), T(n), minus_J(n), minus_T(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) Mq[i][j] = Rational(M(i, j));
      minus_Q[i] = -Rational(Q(i));
      J[i] = Rational(Jm(0, i));
      T[i] = Rational(Tv(i));
      minus_J[i] = -J[i];
      minus_T[i] = -T[i];
    }
    auto dot = [&](const std::vector<Rational>& u, const std::vector<Rational>& v) {
      Rational out = 0;
      for (int i = 0; i < n; ++i) out += u[i] * v[i];
      return out;
    };
    const std::vector<Rational> a0 = held_oracle::cramer(Mq, minus_Q);   // M a0 = Q
    const std::vector<Rational> MJ = held_oracle::cramer(Mq, minus_J), MT = held_oracle::cramer(Mq, minus_T);
    const Rational bias(fr.bias), Ja0 = dot(J, a0) + Rational(kappa(0)), Ta0 = dot(T, a0) + bias;
    const RMatrix D{{dot(J, MJ), dot(J, MT)}, {dot(T, MJ), dot(T, MT)}};
    const std::vector<Rational> held_stick = held_oracle::cramer(D, {Ja0, Ta0});   // (lambda, f)
    const bool stick_exists =
        (sgn(held_stick[0]) >= 0 && abs(held_stick[1]) <= Rational(fr.mu_static) * held_stick[0]) ||
        (sgn(Ja0) >= 0 && sgn(Ta0) == 0);
    const bool slip_exists[2] = {   // [0]: +1, [1]: -1
        slip_consistent(1, Rational(mu_k), a0, J, T, MJ, MT, bias, Ja0, Ta0),
        slip_consistent(-1, Rational(mu_k), a0, J, T, MJ, MT, bias, Ja0, Ta0)};
    // the solver: the diagonal form, or the Cholesky form with the full form given
    std::vector<simulation::Friction> friction{fr};
    Eigen::MatrixXd G = Jm;
    Eigen::VectorXd minv = Eigen::VectorXd::Ones(n), a0d(n);
    std::optional<simulation::FullMass> full;
    if (diagonal) {
      for (int i = 0; i < n; ++i) {
        minv(i) = 1 / M(i, i);
        a0d(i) = Q(i) * minv(i);   // exact: powers of two
      }
    } else {
      full = simulation::FullMass{Jm, M, Q, {fr}};
      const Eigen::LLT<Eigen::MatrixXd> llt(M);
      G = llt.matrixL().solve(Jm.transpose()).transpose();
      a0d = llt.matrixL().solve(Q);
      friction[0].T = llt.matrixL().solve(Tv);
    }
    ++cases;
    const simulation::FrictionalSolution sol =
        simulation::solve_frictional(G, minv, a0d, kappa, friction, {}, false, &own, full ? &*full : nullptr);
    const std::string where = "trial " + std::to_string(trial) + " n " + std::to_string(n) + " sigma " +
                              std::to_string(sigma) + " t " + std::to_string(variant) + " k " + std::to_string(k) +
                              (diagonal ? " diagonal" : " full");
    EXPECT_EQ(sol.solved, stick_exists || slip_exists[0] || slip_exists[1]) << where;
    auto consistent = [&](const simulation::FrictionalSolution& r) {
      if (!r.solved) return !(stick_exists || slip_exists[0] || slip_exists[1]);
      if (r.state[0] == simulation::stick) return stick_exists;
      return !stick_exists && slip_exists[r.state[0] == simulation::slip_positive ? 0 : 1];
    };
    if (!sol.solved) ++none;
    else (sol.state[0] == simulation::stick ? sticks : slips) += 1;
    EXPECT_TRUE(consistent(sol)) << where << " state " << (sol.solved ? sol.state[0] : 9);
    const simulation::FrictionalSolution before = simulation::solve_frictional(G, minv, a0d, kappa, friction);
    doubles_wrong += !consistent(before);
  }
  std::cout << "slip-direction ties: " << cases << " decisions, " << sticks << " sticks, " << slips << " slips, "
            << none << " without a consistent assignment; the doubles-only enumeration wrong in " << doubles_wrong
            << "\n";
  EXPECT_GT(slips, cases / 4);
}

// The full form with a diagonal mass matrix (exact inverses: powers of two) decides as the
// diagonal form, open rows included (exact_stick_holds' open rows, x = M^-1 (Q + W^T lambda)).
TEST(FullMassFriction, ADiagonalFullFormDecidesAsTheDiagonalForm) {
  Rng rng{test::test_seed(6502)};
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 2, m = 2;
    Eigen::MatrixXd G(m, n), Go(1, n), M = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd minv(n), a0(n), Q(n), h(m), ho(1);
    for (int i = 0; i < n; ++i) {
      minv(i) = std::ldexp(1.0, rng.below(9) - 4);
      M(i, i) = 1 / minv(i);
      Q(i) = rng.uniform(-1, 1);
      a0(i) = Q(i) * minv(i);   // exact: a power of two
      Go(0, i) = rng.uniform(-2, 2);
    }
    ho(0) = rng.uniform(-1, 1);
    std::vector<simulation::Friction> friction(m);
    std::vector<int> state(m);
    for (int k = 0; k < m; ++k) {
      for (int i = 0; i < n; ++i) G(k, i) = rng.uniform(-2, 2);
      G(k, k) += 3;
      h(k) = rng.uniform(-1, 1);
      friction[k].on = k == 0;
      friction[k].T = Eigen::VectorXd::Zero(n);
      friction[k].T(n - 1) = 3;
      friction[k].T(0) += rng.uniform(-1, 1);
      friction[k].mu_static = friction[k].mu_kinetic = rng.uniform(0.1, 1);
      friction[k].bias = rng.uniform(-0.5, 0.5);
      state[k] = k == 0 ? simulation::stick : simulation::frictionless;
    }
    const simulation::FullMass full{G, M, Q, friction};
    const simulation::HeldVerdict d = simulation::held_verdict(G, minv, a0, h, friction, state, {}, nullptr, &Go, &ho);
    const simulation::HeldVerdict f =
        simulation::held_verdict(G, minv, a0, h, friction, state, {}, nullptr, &Go, &ho, &full);
    EXPECT_EQ(d.force_sign, f.force_sign) << trial;
    EXPECT_EQ(d.beyond_static, f.beyond_static) << trial;
    EXPECT_EQ(d.open_sign, f.open_sign) << trial;
  }
}

// held_friction.hpp's restitution_limited on the pin-slot simulator's frictional impacts: a bar on
// its pin (M = [[m, m e], [m e, M22]] over (s, psi)) striking with its corner, e = 1, the Coulomb
// impact solved in the coordinates of M's Cholesky factor as the simulator solves it. Where the
// full restitution creates kinetic energy (Newton's restitution with Coulomb friction on coupled
// rows), the restitution taken is the largest (to 2^-30) that creates none: the result's energy
// 1/2 v^T M v (the mass matrix itself) not above the energy before (to the rounding of the factor's
// coordinates), and the bracket's upper end 2^-30 above it creating energy.
TEST(RestitutionLimited, AFrictionalImpactThatWouldCreateEnergyIsScaledToTheLargestRestitutionThatCreatesNone) {
  Rng rng{test::test_seed(6503)};
  int limited_cases = 0, cases = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double m = rng.uniform(0.5, 2), e = rng.uniform(-3, 3), Ic = rng.uniform(0.05, 2) * m;
    const double b = rng.uniform(-3, 3);
    Eigen::Matrix2d M;
    M << m, m * e, m * e, Ic + m * (e * e + b * b);
    // the corner's contact: normal row J and tangent row T (over (s, psi)), a lever of the corner
    const double angle = rng.uniform(0, 2 * M_PI), rx = rng.uniform(-3, 3), ry = rng.uniform(-3, 3);
    const double nx = std::cos(angle), ny = std::sin(angle), ux = 0, uy = 1;
    Eigen::RowVector2d J(nx * ux + ny * uy, nx * -ry + ny * rx);
    Eigen::Vector2d T(-ny * ux + nx * uy, nx * rx + ny * ry);
    Eigen::Vector2d v(rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double vn = J.dot(v);
    if (!(vn < -1e-3)) continue;   // approaching
    ++cases;
    const Eigen::LLT<Eigen::MatrixXd> llt{Eigen::MatrixXd(M)};
    const Eigen::MatrixXd Gz = llt.matrixL().solve(Eigen::MatrixXd(J.transpose())).transpose();
    const Eigen::VectorXd vz = llt.matrixU() * v;
    std::vector<simulation::Friction> friction(1);
    friction[0].on = true;
    friction[0].T = llt.matrixL().solve(T);
    friction[0].mu_static = rng.uniform(0.2, 1.5);
    friction[0].mu_kinetic = friction[0].mu_static * rng.uniform(0.5, 1);
    const Eigen::VectorXd restitution = Eigen::VectorXd::Constant(1, vn);   // e = 1: h = e v-
    auto solve = [&](double scale) {
      return simulation::solve_frictional(Gz, Eigen::VectorXd::Ones(2), vz, scale * restitution, friction);
    };
    // (session 69, exact69: the energy test exact — held_friction.hpp's creates_energy)
    auto creates_energy = [&](const simulation::FrictionalSolution& s, double scale) {
      return simulation::creates_energy(Gz, Eigen::VectorXd::Ones(2), vz, scale * restitution, friction, {}, s);
    };
    bool limited = false;
    double scale = -1;
    const simulation::FrictionalSolution sol = simulation::restitution_limited(solve, creates_energy, limited, &scale);
    ASSERT_TRUE(sol.solved) << trial;
    const simulation::FrictionalSolution full = solve(1);
    const bool creates = full.solved && creates_energy(full, 1);
    ASSERT_EQ(limited, creates) << trial;
    const Eigen::Vector2d after = llt.matrixU().solve(sol.x);
    const double before_energy = 0.5 * v.dot(M * v), after_energy = 0.5 * after.dot(M * after);
    const double rounding = 64 * 0x1p-52 * before_energy * (1 + M.norm() * M.inverse().norm());
    EXPECT_LE(after_energy, before_energy + rounding) << trial;
    EXPECT_GE(J.dot(after), -1e-9 * std::abs(vn)) << trial;   // no longer approaching
    if (!limited) {
      EXPECT_EQ(scale, 1.0);
      continue;
    }
    ++limited_cases;
    EXPECT_GE(scale, 0.0);
    EXPECT_LT(scale, 1.0);
    EXPECT_EQ(solve(scale).x, sol.x) << trial;   // the factor reported is the one taken
    const simulation::FrictionalSolution above = solve(scale + 0x1p-30);
    EXPECT_TRUE(!above.solved || creates_energy(above, scale + 0x1p-30)) << trial;   // the largest, to 2^-30
  }
  std::cout << "frictional corner impacts: " << cases << ", restitution limited in " << limited_cases << "\n";
  EXPECT_GE(limited_cases, cases / 20) << "the generated impacts should reach the guard";
}

}  // namespace
}  // namespace hipair
