// Frictionless impacts decided exactly (session 68, impact68): held_friction.hpp's
// exact_impact_lcp — which contacts of an impact get an impulse and which separate — on the exact
// restitution terms e G v- (exact_restitution_terms), the doubles' LCP (solve_lcp, its 1e-10
// tolerance, on b = (1 + e) G v rounded) as the filter; and slower_than (the planar simulators'
// plastic threshold) exactly.
//
// Generated impacts: two contacts over n = 2..4 coordinates, diagonal inverse masses (powers of
// two; some cases with a driver, inverse mass 0), rows g1 = c e_0 (c = +-1, +-2: A11 dyadic) and
// g2 integers with g2_1 = +-1, velocities v of integers times 2^-s (s = 0..40), row 1 approaching,
// the same restitution e in {0, 0.1, 0.3, 0.5, 0.7, 1} on both rows. Planted: v_1 put where
// contact 2's speed after contact 1's impulse alone, (1 + e)(g2 v - (A21 / A11) g1 v), is exactly
// 0 or +-2^-(s+k) (k = 1..60): contact 2 then exactly held without impulse, held with one, or
// separating; a quarter generic. The oracle: the LCP's four held sets in rationals on the same
// doubles, h = e G v exactly (A = G M^-1 G^T is positive definite here: one solution). Asserted on
// every impact: a contact gets an impulse iff the oracle's does, separates iff the oracle's
// separates, and the velocities after are the oracle's to 2^-40 of the impulses' reach (the
// doubles kept where they agree to that) and a few ulps. The call the
// simulators made before session 68 (the doubles' LCP alone) is counted where it disagrees.
#include <gtest/gtest.h>

#include "simulation/held_friction.hpp"
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

TEST(ImpactLcpExact, FrictionlessImpulsesAtPlantedTiesAreTheExactLawOnTheExactRestitutionTerms) {
  Rng rng{test::test_seed(6803)};
  static constexpr double restitutions[6] = {0, 0.1, 0.3, 0.5, 0.7, 1};
  int cases = 0, planted = 0, exact_used = 0, old_wrong = 0, impulses2 = 0, separations2 = 0, ties = 0;
  for (int trial = 0; cases < 800 && trial < 8000; ++trial) {
    const int n = 2 + trial % 3;
    const bool driver = n >= 3 && rng.below(4) == 0;
    Eigen::VectorXd minv(n), v(n);
    for (int i = 0; i < n; ++i) minv(i) = std::ldexp(1.0, rng.below(7) - 3);
    if (driver) minv(n - 1) = 0;
    const int s = rng.below(41);
    for (int i = 0; i < n; ++i) v(i) = std::ldexp(static_cast<double>(rng.below(17) - 8), -s);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(2, n);
    G(0, 0) = (rng.below(2) ? 1 : 2) * (rng.below(2) ? 1 : -1);
    G(1, 1) = rng.below(2) ? 1 : -1;
    G(1, 0) = rng.below(7) - 3;
    for (int i = 2; i < n; ++i) G(1, i) = rng.below(7) - 3;
    auto q = [](double d) { return Rational(d); };
    auto dot = [&](int row, const Eigen::VectorXd& u) {
      Rational out = 0;
      for (int i = 0; i < n; ++i) out += q(G(row, i)) * q(u(i));
      return out;
    };
    // A exactly
    Rational A[2][2];
    auto form_A = [&] {
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c) {
          A[a][c] = 0;
          for (int i = 0; i < n; ++i) A[a][c] += q(G(a, i)) * q(minv(i)) * q(G(c, i));
        }
    };
    const std::optional<impact_tie::Plant> tie = impact_tie::orient_and_plant(G, v, A, n, s, rng, form_A, dot);
    if (!tie) continue;
    const bool plant = tie->planted;
    const int k = tie->k, side = tie->side;
    const double e = restitutions[rng.below(6)];
    const Eigen::VectorXd ev = Eigen::VectorXd::Constant(2, e);
    const std::vector<Rational> h_exact = simulation::exact_restitution_terms(G, v, ev);
    Rational b[2];
    for (int r = 0; r < 2; ++r) b[r] = dot(r, v) + h_exact[static_cast<std::size_t>(r)];
    const impact_tie::Lcp2 o = impact_tie::lcp2(A, b);
    ASSERT_TRUE(o.found);
    // the doubles' problem as the fixed-axis simulator forms it
    const Eigen::MatrixXd Ad = G * minv.asDiagonal() * G.transpose();
    const Eigen::VectorXd gv = G * v;
    Eigen::VectorXd bd(2);
    for (int r = 0; r < 2; ++r)
      bd(r) = simulation::approaches(G.row(r).transpose(), v) ? (1 + e) * gv(r) : gv(r);
    const simulation::LcpSolution lcp = simulation::solve_lcp(Ad, bd);
    ASSERT_TRUE(lcp.solved);
    const std::optional<simulation::FrictionalSolution> exact = simulation::exact_impact_lcp(G, minv, v, h_exact, lcp);
    ++cases;
    planted += plant;
    ties += plant && side == 0;
    exact_used += exact.has_value();
    const std::string where = "trial " + std::to_string(trial) + " n " + std::to_string(n) + " s " +
                              std::to_string(s) + " k " + std::to_string(k) + " side " + std::to_string(side) +
                              " e " + std::to_string(e) + (driver ? " driver" : "");
    Eigen::VectorXd lambda(2), x;
    bool separates[2];
    if (exact) {
      ASSERT_TRUE(exact->solved) << where;
      lambda = exact->lambda;
      x = exact->x;
      for (int r = 0; r < 2; ++r) separates[r] = exact->w(r) > 0;
    } else {
      lambda = lcp.lambda;
      x = v + minv.asDiagonal() * (G.transpose() * lcp.lambda);
      for (int r = 0; r < 2; ++r) separates[r] = lcp.lambda(r) <= 0 && lcp.w(r) > lcp.tolerance;
    }
    bool old_ok = true;
    for (int r = 0; r < 2; ++r) {
      EXPECT_EQ(lambda(r) > 0, sgn(o.lambda[r]) > 0) << where << " contact " << r;
      EXPECT_EQ(separates[r], sgn(o.w[r]) > 0) << where << " contact " << r;
      old_ok = old_ok && (lcp.lambda(r) > 0) == (sgn(o.lambda[r]) > 0) &&
               (lcp.lambda(r) <= 0 && lcp.w(r) > lcp.tolerance) == (sgn(o.w[r]) > 0);
    }
    // the velocities after: the oracle's x = v + M^-1 G^T lambda
    // (the tolerance from the quantity: kept doubles' impulses agree with the exact ones to 2^-40 of
    // the largest, exact_impact_lcp, carried to x through M^-1 G^T; then the rounding of the doubles'
    // x = v + M^-1 G^T lambda, a few ulps of its terms)
    const double lmax = std::max(std::abs(to_double(o.lambda[0])), std::abs(to_double(o.lambda[1])));
    const double reach = (minv.asDiagonal() * G.transpose()).cwiseAbs().rowwise().sum().maxCoeff();
    const double scale = v.cwiseAbs().maxCoeff() + x.cwiseAbs().maxCoeff() + reach * lmax;
    const double tolerance = 0x1p-40 * reach * lmax + 8 * 0x1p-52 * scale;
    for (int i = 0; i < n; ++i) {
      const Rational xi = q(v(i)) + q(minv(i)) * (q(G(0, i)) * o.lambda[0] + q(G(1, i)) * o.lambda[1]);
      EXPECT_LE(std::abs(x(i) - to_double(xi)), tolerance) << where << " coordinate " << i << (exact ? " (exact)" : " (doubles)");
    }
    old_wrong += !old_ok;
    impulses2 += sgn(o.lambda[1]) > 0;
    separations2 += sgn(o.w[1]) > 0;
  }
  std::cout << "frictionless impact ties: " << cases << " impacts (" << planted << " planted, " << ties
            << " exactly on the tie), contact 2 struck in " << impulses2 << ", separating in " << separations2
            << "; the doubles' decision replaced in " << exact_used << "; the doubles alone (before session 68) wrong in "
            << old_wrong << "\n";
  EXPECT_EQ(cases, 800);
  EXPECT_GT(ties, cases / 8);
  EXPECT_GT(impulses2, cases / 8);
  EXPECT_GT(separations2, cases / 8);
  EXPECT_GT(old_wrong, 0);   // the doubles' tolerance decides planted ties wrongly
}

// slower_than (the planar simulators' plastic threshold, max(0, -min J v) < rest): planted with
// J v exactly -rest and 2^-k off it, against the rationals; the rounded J v's decision counted.
TEST(ImpactLcpExact, PlasticThresholdIsDecidedExactly) {
  Rng rng{test::test_seed(6804)};
  int cases = 0, old_wrong = 0, slow = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 3;
    Eigen::MatrixXd J(2, n);
    Eigen::VectorXd v(n);
    for (int r = 0; r < 2; ++r)
      for (int i = 0; i < n; ++i) J(r, i) = rng.below(9) - 4 + rng.below(3) * 0.1;
    for (int i = 0; i < n; ++i) v(i) = rng.uniform(-1, 1);
    // rest: the first row's exact approach, rounded, its neighbours or 2^-k off
    Rational jv = 0;
    for (int i = 0; i < n; ++i) jv += Rational(J(0, i)) * Rational(v(i));
    if (sgn(jv) >= 0) continue;
    const double approach = to_double(-jv);
    const int variant = rng.below(4);
    const double rest = variant == 0   ? approach
                        : variant == 1 ? std::nextafter(approach, 0.0)
                        : variant == 2 ? std::nextafter(approach, 2.0)
                                       : approach * (1 + std::ldexp(1.0, -(20 + rng.below(33))));
    bool oracle = rest > 0;
    for (int r = 0; r < 2; ++r) {
      Rational row = Rational(rest);
      for (int i = 0; i < n; ++i) row += Rational(J(r, i)) * Rational(v(i));
      oracle = oracle && sgn(row) > 0;
    }
    ++cases;
    slow += oracle;
    EXPECT_EQ(simulation::slower_than(J, v, rest), oracle) << "trial " << trial;
    const Eigen::VectorXd before = J * v;
    old_wrong += (std::max(0.0, -before.minCoeff()) < rest) != oracle;
  }
  std::cout << "plastic threshold: " << cases << " impacts, " << slow << " slower than the rest speed; the rounded "
            << "J v (before session 68) wrong in " << old_wrong << "\n";
  EXPECT_GT(cases, 500);
  EXPECT_GT(slow, cases / 8);
  EXPECT_GT(old_wrong, 0);
}

}  // namespace
}  // namespace hipair
