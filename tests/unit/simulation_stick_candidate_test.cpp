// The step start's stick choice on dependent rows (src/simulation/friction.hpp's
// solve_frictional with exact stick limits, exact_stick_holds; docs/simulation.md, "Session 64
// (stick64)"). The escapement's lock, generated: a wheel (coordinate 0) driven into a locking
// face whose normal passes through the anchor's pivot (the lock's row G_l = (g_l, 0, 0), its
// tangent row T = (t0, t1, 0): friction turns the anchor), the anchor (coordinate 1) resting on
// a frictionless banking pin (G_b = (0, g_b, 0)), a third free coordinate. Sticking, the lock
// and its tangent hold both coordinates, and the banking row is a third row on them: the forces
// are a one-parameter family f (the friction), lambda_l(f) = -(a_w / m0 + t0 f) / g_l,
// lambda_b(f) = -(a_a / m1 + t1 f) / g_b. The oracle, exact rationals on the same doubles: a
// stick exists iff some f has lambda_l >= 0, lambda_b >= 0 and |f| <= mu lambda_l / s (linear in
// f: an interval). The stick the doubles' LCP proposes rests the banking pin (lambda_b = 0,
// f* = -a_a / (m1 t1)); where that point is in the oracle's interval the exact enumeration must
// choose stick (asserted on 90 % of such cases: the rest left, see the count), and it may choose
// stick only where the interval is not empty. Loads at
// 2^-900 ... 2^900, inverse masses at 2^-100 ... 2^100, mu in [1/16, 1] with no load on
// the anchor, or mu at |f*| s / lambda_l(f*) (1 +- 2^-k) with the anchor pulled off its pin.
// Before session 64 the exact test took the minimum-norm multipliers of all three rows (friction
// first), a choice among the family whose friction exceeded mu N, and rejected the stick (the
// escapement's lock at t = 0.0547 s became a slip).
#include <gtest/gtest.h>

#include "simulation/friction.hpp"
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

struct Lock {
  Eigen::MatrixXd G;
  Eigen::VectorXd minv, a0, h;
  std::vector<simulation::Friction> friction;
};

Lock make_lock(double g_b, double g_l, double t0, double t1, double s, double mu, const Eigen::Vector3d& minv,
               const Eigen::Vector3d& a0) {
  Lock p;
  p.G = Eigen::MatrixXd::Zero(2, 3);
  p.G(0, 1) = g_b;
  p.G(1, 0) = g_l;
  p.minv = minv;
  p.a0 = a0;
  p.h = Eigen::VectorXd::Zero(2);
  p.friction.resize(2);
  simulation::Friction& c = p.friction[1];
  c.on = true;
  c.T = Eigen::VectorXd::Zero(3);
  c.T(0) = t0;
  c.T(1) = t1;
  c.s = s;
  c.mu_static = c.mu_kinetic = mu;
  c.decided = false;
  return p;
}

// lo <= f <= hi from alpha + beta f >= 0 (exact); empty when lo > hi
struct Range {
  std::optional<Rational> lo, hi;
  bool empty = false;
  void at_least(const Rational& alpha, const Rational& beta) {
    if (sgn(beta) == 0) {
      empty = empty || sgn(alpha) < 0;
      return;
    }
    const Rational bound = -alpha / beta;
    if (sgn(beta) > 0) {
      if (!lo || bound > *lo) lo = bound;
    } else if (!hi || bound < *hi) {
      hi = bound;
    }
  }
  bool feasible() const { return !empty && (!lo || !hi || *lo <= *hi); }
  bool holds(const Rational& f) const { return !empty && (!lo || f >= *lo) && (!hi || f <= *hi); }
};

Range oracle(const Lock& p) {
  const Rational g_b(p.G(0, 1)), g_l(p.G(1, 0)), t0(p.friction[1].T(0)), t1(p.friction[1].T(1));
  const Rational m0(p.minv(0)), m1(p.minv(1)), a_w(p.a0(0)), a_a(p.a0(1));
  const Rational mu(p.friction[1].mu_static), s(p.friction[1].s);
  // lambda_l = al + bl f, lambda_b = ab + bb f
  const Rational al = -(a_w / m0) / g_l, bl = -t0 / g_l, ab = -(a_a / m1) / g_b, bb = -t1 / g_b;
  Range r;
  r.at_least(al, bl);
  r.at_least(ab, bb);
  const Rational k = mu / s;
  r.at_least(k * al, k * bl - Rational(1));   // mu lambda_l / s - f >= 0
  r.at_least(k * al, k * bl + Rational(1));   // mu lambda_l / s + f >= 0
  return r;
}

// Session 66 (fullform66): whether the lock slips consistently in direction sigma (its friction
// -sigma mu N, mu_k = mu_s): the lock's force row W_l = G_l - sigma (mu / s) T, x = a0 + M^-1
// (G_b^T lambda_b + W_l^T lambda_l); the lock held (the wheel is driven into it: open, its gap
// would close), x_0 = 0 gives lambda_l = -a_w / (m0 (g_l - sigma k t0)) >= 0 (k = mu / s; a
// denominator 0 leaves x_0 = a_w: no solution); the banking held (x_1 = 0, lambda_b >= 0, the
// slide's acceleration 0) or open (lambda_b = 0, g_b x_1 >= 0 and sigma t1 x_1 >= 0) — exact.
bool slip_exists(const Lock& p, int sigma) {
  const Rational g_b(p.G(0, 1)), g_l(p.G(1, 0)), t0(p.friction[1].T(0)), t1(p.friction[1].T(1));
  const Rational m0(p.minv(0)), m1(p.minv(1)), a_w(p.a0(0)), a_a(p.a0(1));
  const Rational k = Rational(p.friction[1].mu_kinetic) / Rational(p.friction[1].s);
  const Rational denominator = g_l - sigma * k * t0;
  if (sgn(denominator) == 0) return false;
  const Rational lambda_l = -a_w / (m0 * denominator);
  if (sgn(lambda_l) < 0) return false;
  const Rational lambda_b = (sigma * k * t1 * lambda_l - a_a / m1) / g_b;
  if (sgn(lambda_b) >= 0) return true;
  const Rational x1 = a_a - m1 * sigma * k * t1 * lambda_l;
  return sgn(g_b * x1) >= 0 && sigma * sgn(t1 * x1) >= 0;
}

double two_to(int e) { return std::ldexp(1.0, e); }

TEST(StickCandidate, TheLockOnItsBankingPinSticksWhereTheOracleHasAStickAtTheCandidate) {
  Rng rng{hipair::test::test_seed(0x5717c64ULL)};
  static const std::vector<std::size_t> no_groups;
  int cases = 0, feasible = 0, must_stick = 0, stuck = 0, ties_near = 0, unsolved = 0, stuck_at_candidate = 0, slipped = 0;
  for (int c = 0; c < 400; ++c) {
    const bool pulled = c % 2 == 1;   // the anchor pulled off its pin (else no load on it)
    const int e_load = static_cast<int>(rng.uniform(-900, 900)), e_mass = static_cast<int>(rng.uniform(-100, 100));
    const double g_b = (rng.below(2) ? 1 : -1) * rng.uniform(0.25, 4);
    const double g_l = (rng.below(2) ? 1 : -1) * rng.uniform(0.25, 4);
    const double t0 = rng.uniform(-4, 4), t1 = (rng.below(2) ? 1 : -1) * rng.uniform(0.5, 12);
    const double s = rng.uniform(0.5, 30);
    const Eigen::Vector3d minv(two_to(e_mass) * rng.uniform(0.5, 2), two_to(e_mass) * rng.uniform(0.5, 2),
                               two_to(e_mass) * rng.uniform(0.5, 2));
    // the wheel driven into its lock (g_l a_w < 0), the anchor pulled off its pin (g_b a_a > 0)
    const double load = two_to(e_load) * rng.uniform(0.5, 2);
    const double a_w = -(g_l > 0 ? 1 : -1) * load;
    const double a_a = pulled ? (g_b > 0 ? 1 : -1) * load * rng.uniform(1e-3, 0.5) : 0.0;
    const Eigen::Vector3d a0(a_w, a_a, rng.uniform(-1, 1) * two_to(e_load));
    const int k = 1 + rng.below(200);
    // (no load on the anchor: mu in [1/16, 1]; the doubles' own stick test, |f| <= mu_s N (1 + 1e-9),
    // still precedes the exact one and rejects a round-off friction against mu_s = 2^-118: left)
    double mu = rng.uniform(0.0625, 1);
    if (pulled) {
      // mu at the candidate's limit |f*| s / lambda_l(f*) (1 +- 2^-k)
      const Rational f = -(Rational(a_a) / Rational(minv(1))) / Rational(t1);
      const Rational lambda_l = -(Rational(a_w) / Rational(minv(0)) + Rational(t0) * f) / Rational(g_l);
      if (sgn(lambda_l) <= 0) continue;
      const Rational limit = abs(f) * Rational(s) / lambda_l;
      const Rational side = rng.below(2) ? Rational(Rational(1) + Rational(two_to(-k))) : Rational(Rational(1) - Rational(two_to(-k)));
      mu = to_double(limit * side);
      if (!(mu > 0) || !std::isfinite(mu)) continue;
    }
    const Lock p = make_lock(g_b, g_l, t0, t1, s, mu, minv, a0);
    const Range r = oracle(p);
    const Rational f_star = -(Rational(a_a) / Rational(minv(1))) / Rational(t1);
    const bool at_candidate = r.holds(f_star);
    const simulation::FrictionalSolution sol =
        simulation::solve_frictional(p.G, p.minv, p.a0, p.h, p.friction, {}, false, &no_groups);
    const bool slips[2] = {slip_exists(p, 1), slip_exists(p, -1)};
    if (!sol.solved) {   // no assignment: never where the oracle has a stick (the stick is tried first)
      ++unsolved;
      EXPECT_FALSE(r.feasible()) << "case " << c << ": a stick exists and none was found";
      // (session 66: nor a slip — an assignment without a sticking contact decided exactly where
      // the doubles' filter fails; session 65 left 12 such cases unsolved)
      EXPECT_FALSE(slips[0] || slips[1]) << "case " << c << ": a slip exists and none was found";
      continue;
    }
    if (sol.state[1] != simulation::stick) {   // a slip: one the oracle has
      EXPECT_TRUE(slips[sol.state[1] == simulation::slip_positive ? 0 : 1]) << "case " << c << ": an inconsistent slip";
      slipped += 1;
    }
    ++cases;
    const bool sticks = sol.state[1] == simulation::stick;
    stuck += sticks;
    must_stick += at_candidate;
    ties_near += pulled;
    const std::string where = "case " + std::to_string(c) + " k " + std::to_string(k) + " loads 2^" +
                              std::to_string(e_load) + " masses 2^" + std::to_string(e_mass) +
                              (pulled ? " pulled" : " unloaded");
    stuck_at_candidate += at_candidate && sticks;
    // a stick exactly where one exists (the stick assignment is tried first, its consistency
    // decided exactly: session 65)
    EXPECT_EQ(sticks, r.feasible()) << where;
    feasible += r.feasible();
  }
  EXPECT_GT(cases, 300);
  EXPECT_GT(must_stick, 150);
  // (session 64: 250 of 276 — the rest, where the doubles' LCP of the stick state picks another
  // member of the family and the doubles' own stick test rejects it first; before: 32 of 178;
  // session 65: all, the stick's existence decided exactly)
  EXPECT_EQ(stuck_at_candidate, must_stick);
  std::cout << "[stick candidate] " << cases << " cases (" << ties_near << " at mu's tie), the oracle's stick at the candidate in "
            << must_stick << ", a stick in the oracle " << feasible << ", stuck " << stuck << ", slipped " << slipped << ", no consistent assignment found " << unsolved << "\n";
}

}  // namespace
}  // namespace hipair
