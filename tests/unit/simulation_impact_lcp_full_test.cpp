// Frictionless impacts on a full mass matrix decided exactly (session 68, impactpin68):
// held_friction.hpp's exact_impact_lcp with `full` (friction.hpp's FullMass) — the pin-slot
// simulator's impact, whose part has the coupled mass matrix M = [[m, m e], [m e, M22]] (and a
// diagonal free-driver or slider coordinate). Until then the pin-slot impact decided which rows
// get an impulse by the doubles' LCP alone: A = G M^-1 G^T with M^-1 rounded and b = (1 + e) G v
// rounded, with solve_lcp's 1e-10 tolerance.
//
// Generated impacts: two contacts over n = 2..3 coordinates, M's coupled block with M22 a power of
// two and m e dyadic (so A21 / A11 is dyadic), rows g1 = c e_0 and g2 integers with g2_1 = +-1,
// velocities integers times 2^-s, row 1 approaching, e in {0, 0.1, 0.3, 0.5, 0.7, 1}. Planted as
// ImpactLcpExact.*: v_1 where contact 2's speed after contact 1's impulse alone is exactly 0 or
// +-2^-(s+k). A third of the impacts are padded to 14 contacts (12 more coordinates of unit mass,
// each with a contact separating at speed 1: the exact enumeration's bound is 12 contacts; until
// session 68, impactpin68, such an impact was not decided at all). The oracle: the two-contact
// LCP's four held sets in rationals on M's doubles (M^-1 exact), b = G v + e (G v)- exact. Asserted
// on every impact: a contact gets an impulse iff the oracle's does, separates iff it does, the
// impulses are the oracle's to 2^-40 of the largest and a few ulps; the padding contacts separate
// without impulse. The doubles' LCP alone (the call before) is counted where it disagrees.
#include <gtest/gtest.h>

#include "simulation/held_friction.hpp"
#include "simulation/exact_lemke.hpp"
#include "simulation/exact_lp.hpp"
#include "simulation/lcp.hpp"
#include "held_oracle_support.hpp"
#include "impact_tie_support.hpp"
#include "test_seed.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace hipair {
namespace {

using held_oracle::Rng;

TEST(ImpactLcpFullMass, PinSlotImpulsesAtPlantedTiesAreTheExactLawOnTheFullMassMatrix) {
  Rng rng{test::test_seed(6805)};
  static constexpr double restitutions[6] = {0, 0.1, 0.3, 0.5, 0.7, 1};
  int cases = 0, planted = 0, ties = 0, padded = 0, old_wrong = 0, old_wrong_padded = 0, impulses2 = 0,
      separations2 = 0;
  for (int trial = 0; cases < 600 && trial < 8000; ++trial) {
    const int n = 2 + trial % 2;
    const bool pad = trial % 3 == 0;
    const int pads = pad ? 12 : 0;
    const int N = n + pads, m = 2 + pads;
    // the mass matrix: the coupled block, a diagonal third coordinate, the padding's unit masses
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(N, N);
    const double M22 = std::ldexp(1.0, rng.below(5) - 2), me = (rng.below(9) - 4) * 0.125;
    const double mass = std::ceil((me * me / M22 + 0.25) * 8 + rng.below(16)) / 8;   // m M22 > me^2
    M(0, 0) = mass;
    M(0, 1) = M(1, 0) = me;
    M(1, 1) = M22;
    if (n == 3) M(2, 2) = std::ldexp(1.0, rng.below(5) - 2);
    const int s = rng.below(41);
    Eigen::VectorXd v = Eigen::VectorXd::Zero(N);
    for (int i = 0; i < n; ++i) v(i) = std::ldexp(static_cast<double>(rng.below(17) - 8), -s);
    for (int j = 0; j < pads; ++j) v(n + j) = 1;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m, N);
    G(0, 0) = (rng.below(2) ? 1 : 2) * (rng.below(2) ? 1 : -1);
    G(1, 1) = rng.below(2) ? 1 : -1;
    G(1, 0) = rng.below(7) - 3;
    if (n == 3) G(1, 2) = rng.below(7) - 3;
    for (int j = 0; j < pads; ++j) G(2 + j, n + j) = 1;   // separating at speed 1
    auto q = [](double d) { return Rational(d); };
    auto dot = [&](int row, const Eigen::VectorXd& u) {
      Rational out = 0;
      for (int i = 0; i < N; ++i) out += q(G(row, i)) * q(u(i));
      return out;
    };
    // M^-1 of the first n coordinates exactly (the block's 2x2 inverse, the diagonal's)
    const Rational det = q(M(0, 0)) * q(M(1, 1)) - q(M(0, 1)) * q(M(1, 0));
    std::vector<std::vector<Rational>> minv(n, std::vector<Rational>(n, Rational(0)));
    minv[0][0] = q(M(1, 1)) / det;
    minv[1][1] = q(M(0, 0)) / det;
    minv[0][1] = minv[1][0] = -q(M(0, 1)) / det;
    if (n == 3) minv[2][2] = 1 / q(M(2, 2));
    Rational A[2][2];
    auto form_A = [&] {
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c) {
          A[a][c] = 0;
          for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) A[a][c] += q(G(a, i)) * minv[i][j] * q(G(c, j));
        }
    };
    const std::optional<impact_tie::Plant> tie = impact_tie::orient_and_plant(G, v, A, n, s, rng, form_A, dot);
    if (!tie) continue;
    const bool plant = tie->planted;
    const int k = tie->k, side = tie->side;
    const double e = restitutions[rng.below(6)];
    const std::vector<Rational> h_exact =
        simulation::exact_restitution_terms(G, v, Eigen::VectorXd::Constant(m, e));
    std::vector<Rational> b_exact(static_cast<std::size_t>(m));
    for (int r = 0; r < m; ++r) b_exact[static_cast<std::size_t>(r)] = dot(r, v) + h_exact[static_cast<std::size_t>(r)];
    // the oracle: the two contacts' LCP (A positive definite: one held set consistent)
    Rational bb[2] = {b_exact[0], b_exact[1]};
    const impact_tie::Lcp2 o = impact_tie::lcp2(A, bb);
    ASSERT_TRUE(o.found);
    const Rational(&lam)[2] = o.lambda;
    const Rational(&w)[2] = o.w;
    // the doubles' problem as the pin-slot simulator forms it: A = G M^-1 G^T with M^-1 in
    // doubles, b = (1 + e) G v rounded on an approaching row
    Eigen::MatrixXd Minv = Eigen::MatrixXd::Identity(N, N);
    Minv.topLeftCorner(2, 2) = M.topLeftCorner(2, 2).inverse();
    if (n == 3) Minv(2, 2) = 1 / M(2, 2);
    const Eigen::MatrixXd Ad = G * Minv * G.transpose();
    const Eigen::VectorXd gv = G * v;
    Eigen::VectorXd bd(m);
    for (int r = 0; r < m; ++r)
      bd(r) = simulation::approaches(G.row(r).transpose(), v) ? (1 + e) * gv(r) : gv(r);
    const simulation::LcpSolution lcp = simulation::solve_lcp(Ad, bd);
    ASSERT_TRUE(lcp.solved);
    simulation::FullMass full;
    full.G = G;
    full.M = M;
    full.Q = Eigen::VectorXd::Zero(N);
    full.friction.assign(static_cast<std::size_t>(m), simulation::Friction{});
    const Eigen::VectorXd none = Eigen::VectorXd::Zero(N);
    const std::optional<simulation::FrictionalSolution> exact =
        simulation::exact_impact_lcp(G, none, none, b_exact, lcp, &full);
    ++cases;
    planted += plant;
    ties += plant && side == 0;
    padded += pad;
    const std::string where = "trial " + std::to_string(trial) + " n " + std::to_string(n) + " s " +
                              std::to_string(s) + " k " + std::to_string(k) + " side " + std::to_string(side) +
                              " e " + std::to_string(e) + (pad ? " padded" : "");
    Eigen::VectorXd lambda(m);
    std::vector<bool> separates(static_cast<std::size_t>(m));
    if (exact) {
      ASSERT_TRUE(exact->solved) << where;
      lambda = exact->lambda;
      for (int r = 0; r < m; ++r) separates[static_cast<std::size_t>(r)] = exact->w(r) > 0;
    } else {
      lambda = lcp.lambda;
      for (int r = 0; r < m; ++r)
        separates[static_cast<std::size_t>(r)] = lcp.lambda(r) <= 0 && lcp.w(r) > lcp.tolerance;
    }
    bool old_ok = true;
    const double lmax = std::max(std::abs(to_double(lam[0])), std::abs(to_double(lam[1])));
    for (int r = 0; r < m; ++r) {
      const bool struck = r < 2 ? sgn(lam[r]) > 0 : false, apart = r < 2 ? sgn(w[r]) > 0 : true;
      EXPECT_EQ(lambda(r) > 0, struck) << where << " contact " << r;
      EXPECT_EQ(separates[static_cast<std::size_t>(r)], apart) << where << " contact " << r;
      // (the tolerance: kept doubles' impulses agree with the exact ones to 2^-40 of the largest,
      // exact_impact_lcp; the exact ones rounded once)
      const double oracle = r < 2 ? to_double(lam[r]) : 0.0;
      EXPECT_LE(std::abs(lambda(r) - oracle), 0x1p-40 * lmax + 2 * 0x1p-52 * std::abs(oracle)) << where << " contact " << r;
      old_ok = old_ok && (lcp.lambda(r) > 0) == struck && (lcp.lambda(r) <= 0 && lcp.w(r) > lcp.tolerance) == apart;
    }
    old_wrong += !old_ok;
    old_wrong_padded += !old_ok && pad;
    impulses2 += sgn(lam[1]) > 0;
    separations2 += sgn(w[1]) > 0;
  }
  std::cout << "full-mass frictionless impact ties: " << cases << " impacts (" << planted << " planted, " << ties
            << " exactly on the tie, " << padded << " padded to 14 contacts), contact 2 struck in " << impulses2
            << ", separating in " << separations2 << "; the doubles alone (the pin-slot impact before) wrong in "
            << old_wrong << " (" << old_wrong_padded << " padded)\n";
  EXPECT_EQ(cases, 600);
  EXPECT_GT(ties, cases / 8);
  EXPECT_GT(padded, cases / 4);
  EXPECT_GT(impulses2, cases / 8);
  EXPECT_GT(separations2, cases / 8);
  EXPECT_GT(old_wrong_padded, 0);   // beyond 12 contacts the doubles decided, wrongly at planted ties
}

// exact_lemke (exact_lemke.hpp) on generated positive semidefinite LCPs, degenerate on purpose:
// A = G D G^T with G small integers (repeated and opposite rows, more contacts than coordinates,
// some coordinates of inverse mass 0) and b = G v + h with many zeros (ties). Its solution is
// checked exactly (lambda >= 0, w = A lambda + b >= 0, lambda w = 0); where it reports none (ray
// termination) the LCP must be infeasible: for m <= 6 no held set of the enumeration in rationals
// is consistent. (Lexicographic pivoting: no cycling on the degenerate ties.)
TEST(ImpactLcpFullMass, ExactLemkeSolvesDegeneratePositiveSemidefiniteLcps) {
  Rng rng{test::test_seed(6806)};
  int solved = 0, infeasible = 0, large = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int m = trial % 4 == 0 ? 13 + rng.below(4) : 2 + rng.below(7), n = 1 + rng.below(5);
    std::vector<std::vector<Rational>> G(m, std::vector<Rational>(n));
    for (int k = 0; k < m; ++k) {
      if (k > 0 && rng.below(4) == 0) {   // a repeated or opposite row
        const int other = rng.below(k), sign = rng.below(2) ? 1 : -1;
        for (int i = 0; i < n; ++i) G[k][i] = sign * G[other][i];
        continue;
      }
      for (int i = 0; i < n; ++i) G[k][i] = rng.below(5) - 2;
    }
    std::vector<Rational> d(n), v(n);
    for (int i = 0; i < n; ++i) {
      d[i] = rng.below(5) == 0 ? Rational(0) : Rational(1 + rng.below(4)) / Rational(1 + rng.below(3));
      v[i] = rng.below(7) - 3;
    }
    std::vector<std::vector<Rational>> A(m, std::vector<Rational>(m, Rational(0)));
    std::vector<Rational> b(m, Rational(0));
    for (int k = 0; k < m; ++k) {
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) A[k][j] += G[k][i] * d[i] * G[j][i];
      for (int i = 0; i < n; ++i) b[k] += G[k][i] * v[i];
      if (rng.below(3) == 0) b[k] += Rational(rng.below(5) - 2) / Rational(2);
    }
    large += m > 12;
    const std::optional<simulation::ExactLcpSolution> s = simulation::exact_lemke(A, b);
    if (s) {
      ++solved;
      for (int k = 0; k < m; ++k) {
        Rational w = b[k];
        for (int j = 0; j < m; ++j) w += A[k][j] * s->lambda[j];
        ASSERT_EQ(w, s->w[k]) << "trial " << trial;
        ASSERT_GE(sgn(s->lambda[k]), 0) << "trial " << trial;
        ASSERT_GE(sgn(w), 0) << "trial " << trial;
        ASSERT_TRUE(sgn(w) == 0 || sgn(s->lambda[k]) == 0) << "trial " << trial;
      }
      continue;
    }
    ++infeasible;
    if (m > 6) continue;
    // infeasible: no held set H has lambda_H >= 0 with w_H = 0, w_O >= 0 (Farkas on the rationals:
    // the held set's system solved by exact_lp's feasible point)
    for (int code = 0; code < (1 << m); ++code) {
      simulation::ExactLinearSystem lp;
      lp.variables = static_cast<std::size_t>(m);
      lp.nonnegative.assign(m, true);
      for (int k = 0; k < m; ++k) {
        std::vector<Rational> row(m);
        for (int j = 0; j < m; ++j) row[j] = ((code >> j) & 1) ? A[k][j] : Rational(0);
        lp.rows.push_back(row);
        lp.rhs.push_back(-b[k]);
        lp.equality.push_back((code >> k) & 1);
        if (!((code >> k) & 1)) {   // lambda_k = 0
          std::vector<Rational> zero(m, Rational(0));
          zero[k] = 1;
          lp.rows.push_back(zero);
          lp.rhs.push_back(Rational(0));
          lp.equality.push_back(true);
        }
      }
      ASSERT_FALSE(simulation::exact_feasible_point(lp).has_value()) << "trial " << trial << " held set " << code;
    }
  }
  std::cout << "exact Lemke: " << solved << " solved, " << infeasible << " infeasible, " << large
            << " of more than 12 contacts\n";
  EXPECT_GT(solved, 100);
  EXPECT_GT(large, 40);
}

}  // namespace
}  // namespace hipair
