// The held conditions of frictional contacts, decided exactly on their rows
// (src/simulation/friction.hpp's held_verdict, session 63): generated frictional problems — normal
// rows G, tangent rows T, stick/slip/frictionless states, diagonal inverse masses, free
// accelerations a0 and velocity terms — whose normal multiplier is driven to +-2^-e of its size by
// its velocity term (lift-off or hold), or whose static coefficient is put at |f| s / lambda
// (1 +- 2^-e) (stick or slip), e up to 200, at the scales 10^-300, 1 and 10^300 of the loads and
// 10^-150 ... 10^150 of the masses. The oracle: exact rationals on the same doubles by an
// independent route (the augmented system [G; T_S] M^-1 [W; T_S]^T by cofactors and Cramer's rule;
// a collinear group by its one tangent row). The doubles' former rules (a multiplier below 0, a
// friction force beyond mu_s N (1 + 2e-9)) on the same rows are counted where they disagree.
#include <gtest/gtest.h>

#include "simulation/friction.hpp"
#include "held_oracle_support.hpp"
#include "test_seed.hpp"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace hipair {
namespace {

using held_oracle::cramer;
using held_oracle::det;
using held_oracle::Rng;
using held_oracle::RMatrix;




struct Problem {
  Eigen::MatrixXd G;
  Eigen::VectorXd minv, a0, h;
  std::vector<simulation::Friction> friction;
  std::vector<int> state;
};

// The oracle's augmented system: constraint rows [G; T_S], force rows [G - sign mu_k / s T (slip); T_S],
// A = J diag(minv) W^T, b = J a0 + [h; bias], exactly on the doubles (since session 67 a sliding
// contact's force row formed exactly from its doubles G, mu_k, s and T, as held_verdict forms it;
// until then the rounded double row the simulators' solve forms).
void oracle_system(const Problem& p, const std::vector<Eigen::VectorXd>& stick_rows, const std::vector<double>& bias,
                   RMatrix& A, std::vector<Rational>& b) {
  const auto m = static_cast<std::size_t>(p.G.rows()), n = static_cast<std::size_t>(p.G.cols());
  std::vector<Eigen::VectorXd> J;
  std::vector<std::vector<Rational>> W;
  std::vector<double> kappa;
  auto exact_row = [&](const Eigen::VectorXd& r) {
    std::vector<Rational> out(n);
    for (std::size_t c = 0; c < n; ++c) out[c] = Rational(r(Eigen::Index(c)));
    return out;
  };
  for (std::size_t k = 0; k < m; ++k) {
    J.push_back(p.G.row(Eigen::Index(k)).transpose());
    std::vector<Rational> w = exact_row(J.back());
    const simulation::Friction& c = p.friction[k];
    if (c.on && (p.state[k] == 1 || p.state[k] == -1))
      for (std::size_t i = 0; i < n; ++i)
        w[i] -= p.state[k] * (Rational(c.mu_kinetic) / Rational(c.s)) * Rational(c.T(Eigen::Index(i)));
    W.push_back(w);
    kappa.push_back(p.h(Eigen::Index(k)));
  }
  for (std::size_t j = 0; j < stick_rows.size(); ++j) {
    J.push_back(stick_rows[j]);
    W.push_back(exact_row(stick_rows[j]));
    kappa.push_back(bias[j]);
  }
  const std::size_t r = J.size();
  A.assign(r, std::vector<Rational>(r, Rational(0)));
  b.assign(r, Rational(0));
  for (std::size_t i = 0; i < r; ++i) {
    b[i] = Rational(kappa[i]);
    for (std::size_t c = 0; c < n; ++c) {
      const Rational jic(J[i](Eigen::Index(c)));
      b[i] += jic * Rational(p.a0(Eigen::Index(c)));
      for (std::size_t j = 0; j < r; ++j)
        A[i][j] += jic * Rational(p.minv(Eigen::Index(c))) * W[j][c];
    }
  }
}

std::vector<Rational> oracle_multipliers(const Problem& p) {
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> bias;
  for (std::size_t k = 0; k < p.friction.size(); ++k)
    if (p.friction[k].on && p.state[k] == simulation::stick) {
      rows.push_back(p.friction[k].T);
      bias.push_back(p.friction[k].bias);
    }
  RMatrix A;
  std::vector<Rational> b;
  oracle_system(p, rows, bias, A, b);
  return cramer(A, b);
}

// A generated problem: n coordinates, m contacts (independent rows with the sticking tangent rows:
// m + sticking <= n), masses at sm, loads (free accelerations, velocity terms) at sq.
Problem generated(Rng& rng, int n, int m, double sm, double sq) {
  Problem p;
  p.G.resize(m, n);
  p.minv.resize(n);
  p.a0.resize(n);
  p.h.resize(m);
  for (int c = 0; c < n; ++c) {
    p.minv(c) = 1 / (rng.uniform(0.5, 2) * sm);
    p.a0(c) = rng.uniform(-1, 1) * sq;
  }
  int rows = m;
  for (int k = 0; k < m; ++k) {
    for (int c = 0; c < n; ++c) p.G(k, c) = rng.below(4) == 0 ? 0.0 : rng.uniform(-2, 2);
    p.G(k, k) += 3;
    p.h(k) = rng.uniform(-1, 1) * sq;
    simulation::Friction f;
    const int kind = rng.below(4);   // 0 stick, 1 slip +, 2 slip -, 3 frictionless
    const int st = kind == 0 && rows < n ? simulation::stick
                   : kind == 1           ? simulation::slip_positive
                   : kind == 2           ? simulation::slip_negative
                                         : simulation::frictionless;
    if (st != simulation::frictionless) {
      f.on = true;
      f.T.resize(n);
      for (int c = 0; c < n; ++c) f.T(c) = rng.uniform(-2, 2);
      if (st == simulation::stick) f.T(rows) += 3, ++rows;   // independent of the rows before
      f.s = rng.below(2) == 0 ? 1.0 : rng.uniform(0.5, 2);
      f.mu_static = rng.uniform(0.1, 1);
      f.mu_kinetic = f.mu_static * rng.uniform(0.5, 1);
      f.bias = st == simulation::stick ? rng.uniform(-1, 1) * sq : 0.0;
    }
    p.friction.push_back(f);
    p.state.push_back(st);
  }
  return p;
}

// the double nearest to v (get_d truncates toward zero)
double nearest(const Rational& v) {
  const double d = v.get_d();
  if (!std::isfinite(d) || sgn(v) == 0) return d;
  const double away = std::nextafter(d, sgn(v) > 0 ? HUGE_VAL : -HUGE_VAL);
  if (!std::isfinite(away)) return d;
  return abs(Rational(v - Rational(d))) <= abs(Rational(Rational(away) - v)) ? d : away;
}

Rational two_to_minus(int e) {
  mpz_class two = 1;
  two <<= e;
  return Rational(1) / Rational(two);
}

TEST(HeldVerdict, ForceSignsAndStaticLimitsNearTheirTiesAreTheOraclesOnTheRows) {
  const std::uint64_t seed = test::test_seed(63);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  Rng rng{seed};
  simulation::HeldForceCount count;
  int cases = 0, lifts = 0, holds = 0, slips = 0, sticks = 0, ties = 0, old_wrong = 0;
  for (const double sq : {1e-300, 1.0, 1e300}) {
    for (const double sm : {1e-150, 1.0, 1e150}) {
      if (std::abs(std::log10(sq * sm)) > 300) continue;   // (the forces sq sm doubles)
      for (int c = 0; c < 40; ++c) {
        const int n = 3 + rng.below(3), m = 1 + rng.below(std::min(n, 3));
        Problem p = generated(rng, n, m, sm, sq);
        const int e = c % 8 == 7 ? 0 : 1 + rng.below(200);
        const Rational sigma = rng.below(2) == 0 ? Rational(-1) : Rational(1);
        std::vector<Rational> x;
        const int i = rng.below(m);
        std::size_t sticking_index = static_cast<std::size_t>(m);   // i's tangent row's multiplier
        for (int k = 0; k < i; ++k) sticking_index += p.friction[k].on && p.state[k] == simulation::stick;
        const bool limit_case = p.friction[i].on && p.state[i] == simulation::stick && c % 2 == 0;
        // lambda is affine in h_i: lambda_i = x0 + slope h_i
        const double h0 = p.h(i);
        p.h(i) = 0;
        const std::vector<Rational> x0 = oracle_multipliers(p);
        p.h(i) = 1;
        const Rational slope = Rational(oracle_multipliers(p)[i] - x0[i]);
        p.h(i) = h0;
        if (sgn(slope) == 0) continue;
        const Rational size = abs(x0[i]) + abs(Rational(slope * Rational(h0)));
        if (limit_case) {
          // lambda_i = size > 0 (its velocity term), then mu_s at |f| s / lambda (1 + sigma 2^-e),
          // rounded to a double
          p.h(i) = nearest(Rational((size - x0[i]) / slope));
          x = oracle_multipliers(p);
          if (sgn(x[i]) <= 0 || sgn(x[sticking_index]) == 0) continue;
          const Rational mu = abs(x[sticking_index]) * Rational(p.friction[i].s) / x[i] * Rational(1 + sigma * two_to_minus(e));
          p.friction[i].mu_static = nearest(mu);
          if (!(p.friction[i].mu_static > 0) || !std::isfinite(p.friction[i].mu_static)) continue;
        } else {
          // h_i so that lambda_i = sigma 2^-e size
          p.h(i) = nearest(Rational((sigma * size * two_to_minus(e) - x0[i]) / slope));
          if (!std::isfinite(p.h(i))) continue;
        }
        x = oracle_multipliers(p);
        const simulation::HeldVerdict v =
            simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state, {}, &count);
        // the doubles' former rules on the same rows
        const simulation::FrictionalSolution old = simulation::solve_bilateral(p.G, p.minv, p.a0, p.h, p.friction, p.state);
        std::size_t j = static_cast<std::size_t>(m);
        for (int k = 0; k < m; ++k) {
          const int sign = sgn(x[k]);
          EXPECT_EQ(v.force_sign[k], sign) << "case " << c << " contact " << k << " e " << e << " sq " << sq << " sm " << sm;
          bool beyond = false;
          if (p.friction[k].on && p.state[k] == simulation::stick) {
            const Rational normal = sign > 0 ? x[k] / Rational(p.friction[k].s) : Rational(0);
            beyond = abs(x[j]) > Rational(p.friction[k].mu_static) * normal;
            ties += abs(x[j]) == Rational(p.friction[k].mu_static) * normal;
            const double limit = p.friction[k].mu_static * std::max(old.lambda(k), 0.0) / p.friction[k].s;
            const double f = std::abs(old.f(k));
            old_wrong += k == i && limit_case && (f > limit * (1 + 2e-9) + 1e-300) != beyond;
            ++j;
          }
          EXPECT_EQ(v.beyond_static[k], beyond) << "case " << c << " contact " << k << " e " << e << " sq " << sq
                                                << " sm " << sm;
          if (k == i && !limit_case) {
            (sign < 0 ? lifts : holds)++;
            old_wrong += (old.lambda(k) < 0) != (sign < 0);
          }
          if (k == i && limit_case) (beyond ? slips : sticks)++;
        }
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 250);
  EXPECT_GT(lifts, 40);
  EXPECT_GT(holds, 40);
  EXPECT_GT(slips, 5);
  EXPECT_GT(sticks, 5);
  EXPECT_GT(count.filtered, 10u);   // the far cases: the interval filter alone
  EXPECT_GT(count.exact, 30u);      // the near ones: the rationals
  std::cout << cases << " problems: lift " << lifts << ", hold " << holds << ", slip " << slips << ", stick " << sticks
            << " (ties " << ties << "); filter " << count.filtered << ", exact " << count.exact
            << "; the doubles' former rules decided " << old_wrong << " of the driven contacts otherwise\n";
  EXPECT_GT(old_wrong, 0);   // the generated cases reach where the former rules err
}

// Two sticking contacts of one face (equal tangent rows: the friction's split is left open, only
// its sum is determined) share it in proportion to their normal forces: the group's |sum f|
// against mu_s sum N decides for both (a member without normal force only when the group has
// none). Oracle: the problem with the group's one tangent row (regular), by Cramer's rule; mu_s put
// at |F| / N (1 +- 2^-e).
TEST(HeldVerdict, CollinearStickingContactsShareTheirLimitAsTheirGroup) {
  Rng rng{test::test_seed(631)};
  int slips = 0, sticks = 0;
  for (int c = 0; c < 60; ++c) {
    Problem p = generated(rng, 3 + rng.below(2), 2, 1, 1);
    const auto n = p.G.cols();
    simulation::Friction f;
    f.on = true;
    f.T.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) f.T(i) = rng.uniform(-2, 2);
    f.T(2) += 3;
    f.mu_static = 1;
    f.mu_kinetic = 0.5;
    f.bias = rng.uniform(-1, 1);
    p.friction = {f, f};
    p.state = {simulation::stick, simulation::stick};
    // the oracle: one tangent row for the group
    RMatrix A;
    std::vector<Rational> b;
    oracle_system(p, {f.T}, {f.bias}, A, b);
    std::vector<Rational> x = cramer(A, b);
    const Rational N = (sgn(x[0]) > 0 ? x[0] : Rational(0)) + (sgn(x[1]) > 0 ? x[1] : Rational(0));
    if (sgn(N) == 0) continue;
    const int e = 1 + rng.below(200);
    const Rational sigma = c % 2 ? Rational(1) : Rational(-1);
    const double mu = nearest(Rational(abs(x[2]) / N * Rational(1 + sigma * two_to_minus(e))));
    if (!(mu > 0)) continue;
    p.friction[0].mu_static = p.friction[1].mu_static = mu;
    const bool beyond = abs(x[2]) > Rational(mu) * N;
    (beyond ? slips : sticks)++;
    const simulation::HeldVerdict v = simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state, {0, 0});
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(v.force_sign[k], sgn(x[k])) << "case " << c;
      EXPECT_EQ(v.beyond_static[k], beyond && sgn(x[k]) > 0) << "case " << c << " contact " << k << " e " << e;
    }
  }
  EXPECT_GT(slips, 10);
  EXPECT_GT(sticks, 10);
}

// The ties, exactly: a block on a floor (normal row (0, 1, 0), tangent row (1, 0, 0), unit
// masses) under the load (a_x, a_y) has lambda = -a_y and f = -a_x exactly; with
// mu_s = |a_x / a_y| a double, the friction is exactly at the limit and the contact sticks, one
// unit in the last place more of a_x slips; a_y = 0 is a zero force (held), one subnormal unit
// of pull lifts off. At the scales 2^-996, 1, 2^996 (about 10^-300 ... 10^300; powers of two keep
// the ratio 3 : 4 exact).
TEST(HeldVerdict, ExactTiesStickAndHoldAndTheNextDoubleDecides) {
  for (const double scale : {std::ldexp(1.0, -996), 1.0, std::ldexp(1.0, 996)}) {
    Problem p;
    p.G = Eigen::RowVector3d(0, 1, 0);
    p.minv = Eigen::Vector3d(1, 1, 1);
    p.h = Eigen::VectorXd::Zero(1);
    simulation::Friction f;
    f.on = true;
    f.T = Eigen::Vector3d(1, 0, 0);
    f.mu_static = 0.75;
    f.mu_kinetic = 0.5;
    p.friction = {f};
    p.state = {simulation::stick};
    for (const double sign : {1.0, -1.0}) {
      p.a0 = Eigen::Vector3d(sign * 3 * scale, -4 * scale, 0);
      simulation::HeldVerdict v = simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state);
      EXPECT_EQ(v.force_sign[0], 1) << scale;
      EXPECT_FALSE(v.beyond_static[0]) << scale;   // |f| = mu_s N exactly: it sticks
      p.a0(0) = std::nextafter(p.a0(0), sign * HUGE_VAL);
      v = simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state);
      EXPECT_TRUE(v.beyond_static[0]) << scale;
    }
    p.a0 = Eigen::Vector3d(3 * scale, 0, 0);
    simulation::HeldVerdict v = simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state);
    EXPECT_EQ(v.force_sign[0], 0) << scale;   // no force: held
    EXPECT_TRUE(v.beyond_static[0]) << scale;   // friction without a normal force: slips
    p.a0(1) = std::numeric_limits<double>::denorm_min();
    EXPECT_EQ(simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state).force_sign[0], -1) << scale;
    p.a0(1) = -std::numeric_limits<double>::denorm_min();
    EXPECT_EQ(simulation::held_verdict(p.G, p.minv, p.a0, p.h, p.friction, p.state).force_sign[0], 1) << scale;
  }
}

}  // namespace
}  // namespace hipair
