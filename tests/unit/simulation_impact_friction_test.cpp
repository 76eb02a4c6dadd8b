// Frictional impacts decided exactly (session 67, impact67): held_friction.hpp's
// frictional_impulses, the Newton–Coulomb impulse problem the fixed-axis, planar and pin-slot
// simulators solve at an impact (x = v + M^-1 (W^T Lambda + T_S^T F) the velocities after,
// w = G x + h >= 0, h = e G v for an approaching row), on ties planted from the exact law.
//
// Generated problems: one frictional contact over n = 2..4 coordinates, diagonal inverse masses
// (powers of two; some cases with a driver, inverse mass 0), integer rows G and T, velocities
// before v of integers times 2^-s (s = 0..60: speeds of 2^-60 as of 1), the row approaching or
// separating (G v = +-2^-s ...), restitution e in {0, 0.3, 0.5, 1} (h = e G v for an approaching
// row, exactly as approaches() decides, else 0). Families:
//   cone edge: mu_s put at the exact stick's ratio |F| / Lambda (the impulse on the friction cone's
//     edge), rounded, its neighbouring doubles, and mu (1 +- 2^-k), k = 20..60;
//   slip direction: mu_k put where the held slip's tangential velocity after is exactly 0, rounded,
//     and mu (1 +- 2^-k), k = 20..60 (the slip's velocity after reversing or not by 2^-k);
//   generic: mu = j / 16.
// The oracle, exact rationals on the same doubles: a stick held (Lambda, F of the 2 x 2 system,
// Lambda >= 0, |F| <= mu_s Lambda) or open (G v + h >= 0, T v = 0); a slip sigma held or open
// (held_oracle::slip_consistent). Asserted: an impulse iff the oracle has a consistent one, a stick
// iff it has a stick, any slip published one the oracle has. The simulators' call before session 67
// (solve_frictional without exact mode: the doubles' 1e-9 slack decided) is counted where it
// disagrees with the oracle.
#include <gtest/gtest.h>

#include "simulation/friction.hpp"
#include "simulation/held_friction.hpp"
#include "held_oracle_support.hpp"
#include "test_seed.hpp"

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using held_oracle::Rng;
using held_oracle::RMatrix;
using held_oracle::slip_consistent;

double rounded(const Rational& r) { return to_double(r); }   // (nearest)

TEST(ImpactFriction, CoulombImpulsesAtPlantedTiesAreTheExactLawsOnTheDoubles) {
  Rng rng{test::test_seed(6701)};
  const std::vector<std::size_t> own;
  int cases = 0, sticks = 0, slips = 0, none = 0, old_wrong = 0, planted = 0;
  int wrong_by_family[3] = {0, 0, 0};
  for (int trial = 0; cases < 600 && trial < 4000; ++trial) {
    const int n = 2 + trial % 3;
    const int family = (trial / 3) % 3;
    const bool driver = n >= 3 && rng.below(4) == 0;
    Eigen::VectorXd minv(n), v(n), Gv(n), Tv(n);
    for (int i = 0; i < n; ++i) minv(i) = std::ldexp(1.0, rng.below(7) - 3);
    if (driver) minv(n - 1) = 0;
    const int s = rng.below(61);
    for (int i = 0; i < n; ++i) {
      Gv(i) = rng.below(7) - 3;
      Tv(i) = rng.below(7) - 3;
      v(i) = std::ldexp(static_cast<double>(rng.below(9) - 4), -s);
    }
    // the oracle's data, exact
    std::vector<Rational> vq(n), J(n), T(n), MJ(n), MT(n);
    for (int i = 0; i < n; ++i) {
      vq[i] = Rational(v(i));
      J[i] = Rational(Gv(i));
      T[i] = Rational(Tv(i));
      MJ[i] = Rational(minv(i)) * J[i];
      MT[i] = Rational(minv(i)) * T[i];
    }
    auto dot = [&](const std::vector<Rational>& a, const std::vector<Rational>& b) {
      Rational out = 0;
      for (int i = 0; i < n; ++i) out += a[i] * b[i];
      return out;
    };
    const Rational gv = dot(J, vq);
    if (sgn(gv) == 0) continue;
    if (rng.below(4) != 0 && sgn(gv) > 0) {   // mostly approaching
      v = -v;
      for (Rational& x : vq) x = -x;
    }
    const Rational GG = dot(J, MJ), GT = dot(J, MT), TT = dot(T, MT);
    const RMatrix D{{GG, GT}, {GT, TT}};
    if (sgn(held_oracle::det(D)) == 0) continue;   // G and T dependent on the free coordinates
    static constexpr double restitutions[4] = {0, 0.3, 0.5, 1};
    const double e = restitutions[rng.below(4)];
    const Eigen::MatrixXd G = Gv.transpose();
    const Eigen::VectorXd h =
        Eigen::VectorXd::Constant(1, simulation::approaches(Gv, v) ? e * Gv.dot(v) : 0.0);   // (G v exact)
    const Rational a = dot(J, vq) + Rational(h(0)), tv = dot(T, vq);
    const std::vector<Rational> stick = held_oracle::cramer(D, {a, tv});   // (Lambda, F)
    // mu by family
    const int k = 20 + rng.below(41);
    const int variant = rng.below(5);
    auto put = [&](const Rational& mu) -> double {
      const double r = rounded(mu);
      switch (variant) {
        case 0: return r;
        case 1: return std::nextafter(r, 0.0);
        case 2: return std::nextafter(r, 2 * r);
        case 3: return rounded(mu * (1 - Rational(std::ldexp(1.0, -k))));
        default: return rounded(mu * (1 + Rational(std::ldexp(1.0, -k))));
      }
    };
    double mu_s = (1 + rng.below(15)) / 16.0, mu_k = mu_s;
    bool tie = false;
    if (family == 0 && sgn(stick[0]) > 0 && sgn(stick[1]) != 0) {
      mu_s = put(abs(stick[1]) / stick[0]);
      mu_k = mu_s * (2 + rng.below(3)) / 4;
      tie = true;
    } else if (family == 1) {
      const int sigma = rng.below(2) == 0 ? 1 : -1;
      const Rational denominator = sigma * (a * TT - tv * GT);
      if (sgn(denominator) != 0) {
        const Rational mu = (a * GT - tv * GG) / denominator;
        if (sgn(mu) > 0 && mu < 4) {
          mu_k = put(mu);
          mu_s = mu_k * (4 + rng.below(2)) / 4;
          tie = true;
        }
      }
    }
    if (!(mu_k > 0) || !(mu_s >= mu_k)) continue;
    planted += tie;
    simulation::Friction fr;
    fr.on = true;
    fr.T = Tv;
    fr.mu_static = mu_s;
    fr.mu_kinetic = mu_k;
    const bool stick_exists = (sgn(stick[0]) >= 0 && abs(stick[1]) <= Rational(mu_s) * stick[0]) ||
                              (sgn(a) >= 0 && sgn(tv) == 0);
    const bool slip_exists[2] = {slip_consistent(1, Rational(mu_k), vq, J, T, MJ, MT, Rational(0), a, tv),
                                 slip_consistent(-1, Rational(mu_k), vq, J, T, MJ, MT, Rational(0), a, tv)};
    const bool any = stick_exists || slip_exists[0] || slip_exists[1];
    auto consistent = [&](const simulation::FrictionalSolution& r) {
      if (!r.solved) return !any;
      if (r.state[0] == simulation::stick) return stick_exists;
      return !stick_exists && slip_exists[r.state[0] == simulation::slip_positive ? 0 : 1];
    };
    ++cases;
    const std::string where = "trial " + std::to_string(trial) + " n " + std::to_string(n) + " family " +
                              std::to_string(family) + " variant " + std::to_string(variant) + " k " +
                              std::to_string(k) + " s " + std::to_string(s) + " e " + std::to_string(e) +
                              (driver ? " driver" : "");
    const simulation::FrictionalSolution sol = simulation::frictional_impulses(G, minv, v, h, {fr}, own);
    EXPECT_EQ(sol.solved, any) << where;
    if (sol.solved) EXPECT_EQ(sol.state[0] == simulation::stick, stick_exists) << where;
    EXPECT_TRUE(consistent(sol)) << where << " state " << (sol.solved ? sol.state[0] : 9);
    if (!sol.solved) ++none;
    else (sol.state[0] == simulation::stick ? sticks : slips) += 1;
    // a stick published stops the contact's sliding and leaves the row not approaching, exactly
    // on the published velocities' own scale (they are the rounded ones)
    if (sol.solved && sol.state[0] == simulation::stick && stick_exists) {
      const double scale = Tv.cwiseAbs().dot(sol.x.cwiseAbs()) + Tv.cwiseAbs().dot(v.cwiseAbs());
      EXPECT_LE(std::abs(Tv.dot(sol.x)), 1e-12 * scale + 1e-300) << where;
    }
    // the simulators' call before session 67
    const simulation::FrictionalSolution old = simulation::solve_frictional(G, minv, v, h, {fr});
    if (!consistent(old)) {
      ++old_wrong;
      ++wrong_by_family[family];
    }
  }
  std::cout << "impact ties: " << cases << " impacts (" << planted << " planted on a tie), " << sticks << " sticks, "
            << slips << " slips, " << none << " without a consistent impulse; the doubles-only call (before "
            << "session 67) wrong in " << old_wrong << " (cone edge " << wrong_by_family[0] << ", slip direction "
            << wrong_by_family[1] << ", generic " << wrong_by_family[2] << ")\n";
  EXPECT_EQ(cases, 600);
  EXPECT_GT(planted, cases / 3);
  EXPECT_GT(sticks, cases / 10);
  EXPECT_GT(slips, cases / 10);
}

// Session 67: a sliding contact's force row W = G - sign (mu / s) T formed exactly in the held
// decisions (HeldForceRows::slip), not from its rounded doubles. Planted where the rounding decides:
// G = (g, 0), T = sigma (t, 1) with the double mu = fl(p / q) and t such that fl(mu t) = g while
// mu t != g exactly (mu is not p / q): the rounded row's first entry is exactly 0, the Delassus
// number G M^-1 W^T of the rounded rows 0 (singular: the minimum-norm multiplier 0, "held without
// force"), the exact one g (g - mu t) / m_0 of about 10^-17 — the multiplier -b / A is of b's sign
// times A's: a lift-off or a hold the rounded rows cannot see. Oracle: rationals on the same doubles.
// Asserted: held_verdict's force sign is the oracle's in every case; the rounded rows' (the slip
// fields cleared: held_verdict before session 67) are counted.
TEST(HeldSlipRow, ASlidingContactsForceRowIsFormedExactlyInTheHeldVerdict) {
  Rng rng{test::test_seed(6702)};
  int cases = 0, rounded_wrong = 0;
  for (int trial = 0; trial < 400 && cases < 200; ++trial) {
    const int q = 3 + rng.below(20), p = 1 + rng.below(q - 1);
    const double mu = static_cast<double>(p) / q;
    const int g = 1 + rng.below(6);
    if ((g * q) % p != 0) continue;
    const double t = static_cast<double>(g * q / p);
    if (mu * t != g || Rational(mu) * Rational(t) == Rational(g)) continue;   // the rounding must decide
    const int sigma = rng.below(2) == 0 ? 1 : -1;
    const double m0 = std::ldexp(1.0, rng.below(9) - 4), m1 = std::ldexp(1.0, rng.below(9) - 4);
    Eigen::MatrixXd G(1, 2);
    G << g, 0;
    Eigen::VectorXd minv(2), a0(2), h(1);
    minv << 1 / m0, 1 / m1;
    a0 << rng.below(9) - 4, rng.below(9) - 4;
    h << std::ldexp(static_cast<double>(rng.below(9) - 4), -rng.below(40));
    simulation::Friction fr;
    fr.on = true;
    fr.T = Eigen::Vector2d(sigma * t, sigma * 1.0);
    fr.mu_static = fr.mu_kinetic = mu;
    fr.state = sigma;
    fr.decided = true;
    // the oracle: lambda = -(G a0 + h) / (G M^-1 W^T), W = G - sigma mu T, exact
    const Rational b = Rational(g) * Rational(a0(0)) + Rational(h(0));
    const Rational W0 = Rational(g) - Rational(sigma) * Rational(mu) * Rational(sigma * t);
    const Rational A = Rational(g) * Rational(minv(0)) * W0;   // (G's second entry 0)
    ASSERT_NE(sgn(A), 0);
    const int oracle = sgn(b) == 0 ? 0 : -sgn(b) * sgn(A);
    ++cases;
    const simulation::HeldVerdict v = simulation::held_verdict(G, minv, a0, h, {fr}, {sigma});
    EXPECT_EQ(v.force_sign[0], oracle) << "trial " << trial << " mu " << p << "/" << q << " g " << g << " t " << t
                                       << " sigma " << sigma;
    // the rounded rows (before session 67)
    std::vector<std::size_t> sticking;
    simulation::HeldForceRows rows = simulation::frictional_rows(G, minv, a0, h, {fr}, {sigma}, sticking);
    rows.slip.clear();
    rounded_wrong += simulation::held_force_signs(rows)[0] != oracle;
  }
  std::cout << "sliding rows at the rounding's tie: " << cases << " cases; the rounded rows' force sign wrong in "
            << rounded_wrong << "\n";
  EXPECT_GE(cases, 50);
}

}  // namespace
}  // namespace hipair
