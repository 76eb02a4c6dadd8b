// The exact linear feasibility's elimination (simulation/exact_lp_elimination.hpp, session 71,
// speed71) against CGAL's exact linear program (exact_feasible_point with the elimination off) on
// generated small systems: planted solutions (strict, degenerate — every inequality tight — and
// a single feasible point), random right-hand sides (mostly without a solution), contradictions by
// a margin of 2^-70, dependent equalities consistent or not, numbers from small integers to the
// exact values of doubles as the impact decisions make them.
#include "simulation/exact_lp.hpp"
#include "simulation/exact_lp_elimination.hpp"

#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hipair {
namespace {

Rational number(std::mt19937_64& random, int kind) {
  switch (kind) {
    case 0: return Rational(static_cast<long>(random() % 7) - 3);
    case 1: return test_numbers::random_rational(random, Rational(-5), Rational(5));
    default: {   // a double's exact value, over 2^-40 .. 2^40
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const double v = std::ldexp(u(random), static_cast<int>(random() % 81) - 40);
      return Rational(v);
    }
  }
}

Rational dot(const std::vector<Rational>& a, const std::vector<Rational>& z) {
  Rational s = 0;
  for (std::size_t j = 0; j < a.size(); ++j) s += a[j] * z[j];
  return s;
}

bool satisfies(const simulation::ExactLinearSystem& lp, const std::vector<Rational>& z) {
  for (std::size_t j = 0; j < lp.variables; ++j)
    if (lp.nonnegative[j] && sgn(z[j]) < 0) return false;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    const Rational s = dot(lp.rows[i], z);
    if (lp.equality[i] ? s != lp.rhs[i] : s < lp.rhs[i]) return false;
  }
  return true;
}

TEST(SimulationExactLp, EliminationDecidesAsTheLinearProgram) {
  std::mt19937_64 random(test::test_seed(7101));
  const Rational margin = Rational(1) / Rational(mpz_class(1) << 70);
  std::size_t feasible = 0, infeasible = 0, degenerate = 0, point = 0, dependent = 0, undecided = 0, eliminated = 0,
              by_intervals = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = static_cast<int>(random() % 3);
    const int mode = static_cast<int>(random() % 5);   // 0 strict, 1 tight, 2 random, 3 margin, 4 one point
    simulation::ExactLinearSystem lp;
    lp.variables = 1 + random() % 5;
    const std::size_t n = lp.variables;
    lp.nonnegative.resize(n);
    std::vector<Rational> z(n);   // the planted point
    for (std::size_t j = 0; j < n; ++j) {
      lp.nonnegative[j] = random() % 2;
      z[j] = number(random, kind);
      if (lp.nonnegative[j]) z[j] = random() % 4 == 0 ? Rational(0) : Rational(abs(z[j]));
    }
    auto row = [&] {
      std::vector<Rational> a(n);
      for (Rational& e : a) e = random() % 3 == 0 ? Rational(0) : number(random, kind);
      return a;
    };
    const std::size_t equalities = random() % std::min<std::size_t>(n + 1, 4);
    const std::size_t inequalities = random() % 8;
    for (std::size_t i = 0; i < equalities + inequalities; ++i) {
      const bool eq = i < equalities;
      std::vector<Rational> a = row();
      Rational b = dot(a, z);
      if (!eq && mode == 0) b -= abs(number(random, kind));
      if (mode == 2) b = number(random, kind);
      lp.rows.push_back(a);
      lp.rhs.push_back(b);
      lp.equality.push_back(eq);
    }
    if (mode == 3 || mode == 4) {   // a . z >= b and -a . z >= -b (+ 2^-70: no solution)
      std::vector<Rational> a = row();
      a[random() % n] = 1;
      const Rational b = dot(a, z);
      lp.rows.push_back(a);
      lp.rhs.push_back(b);
      lp.equality.push_back(false);
      for (Rational& e : a) e = -e;
      lp.rows.push_back(a);
      lp.rhs.push_back(-b + (mode == 3 ? margin : Rational(0)));
      lp.equality.push_back(false);
    }
    if (mode == 4)   // every unknown pinned by a pair of inequalities: one feasible point
      for (std::size_t j = 0; j < n; ++j)
        for (int side : {1, -1}) {
          std::vector<Rational> a(n, Rational(0));
          a[j] = side;
          lp.rows.push_back(a);
          lp.rhs.push_back(side * z[j]);
          lp.equality.push_back(false);
        }
    bool broken = false;   // the planted point no longer a solution
    if (equalities > 0 && random() % 3 == 0) {   // a dependent equality, consistent or off by 2^-70
      const std::size_t i = random() % equalities;
      const Rational f = number(random, 1) + 7;
      std::vector<Rational> a = lp.rows[i];
      for (Rational& e : a) e *= f;
      lp.rows.push_back(a);
      lp.rhs.push_back(lp.rhs[i] * f + (random() % 2 ? margin : Rational(0)));
      lp.equality.push_back(true);
      broken = sgn(lp.rhs.back() - lp.rhs[i] * f) != 0;
      ++dependent;
    }
    simulation::exact_lp_elimination() = false;
    const std::optional<std::vector<Rational>> oracle = simulation::exact_feasible_point(lp);
    simulation::exact_lp_elimination() = true;
    const std::size_t before = simulation::exact_lp_eliminated();
    const std::optional<std::vector<Rational>> answer = simulation::exact_feasible_point(lp);
    eliminated += simulation::exact_lp_eliminated() - before;
    const std::optional<bool> decided = simulation::feasible_by_elimination(lp);
    // the interval filter: never "no solution" where there is one
    const bool filtered = simulation::certainly_infeasible_in_intervals(lp);
    if (filtered) ASSERT_FALSE(oracle.has_value()) << "trial " << trial << ": the filter refused a system with a solution";
    by_intervals += filtered;
    ASSERT_EQ(answer.has_value(), oracle.has_value()) << "trial " << trial;
    if (oracle) {
      ASSERT_TRUE(satisfies(lp, *oracle)) << "trial " << trial;
      ASSERT_EQ(*answer, *oracle) << "trial " << trial;   // the linear program's point, as before
    }
    if (!decided) {
      ++undecided;
      continue;
    }
    ASSERT_EQ(*decided, oracle.has_value()) << "trial " << trial << " mode " << mode;
    if (mode != 2 && mode != 3 && !broken) ASSERT_TRUE(*decided) << "trial " << trial << ": a planted solution not found";
    (*decided ? feasible : infeasible) += 1;
    degenerate += *decided && (mode == 1 || mode == 4);
    point += *decided && mode == 4;
  }
  std::cout << "exact LP elimination: " << feasible << " with a solution (" << degenerate << " degenerate, " << point
            << " one point), " << infeasible << " without, " << dependent << " with a dependent equality, "
            << undecided << " left to the linear program; " << by_intervals << " refused by the interval filter\n";
  EXPECT_GT(feasible, 1000u);
  EXPECT_GT(infeasible, 500u);
  EXPECT_GT(degenerate, 300u);
  EXPECT_GT(point, 200u);
  EXPECT_GE(eliminated, infeasible);
  EXPECT_LE(eliminated, infeasible + undecided);
  EXPECT_GT(by_intervals, 400u);
  EXPECT_LT(by_intervals, infeasible);   // (the margins of 2^-70 and the dependent rows left to the exact elimination)
  EXPECT_LT(undecided, 30u);
}

TEST(SimulationExactLp, RowLimitLeavesTheDecisionToTheLinearProgram) {
  // |x + k y| <= 10 for k = 1 .. 4: eliminating either unknown makes 16 rows
  simulation::ExactLinearSystem lp;
  lp.variables = 2;
  lp.nonnegative = {false, false};
  for (int k = 1; k <= 4; ++k)
    for (int side : {1, -1}) {
      lp.rows.push_back({Rational(side), Rational(side * k)});
      lp.rhs.push_back(Rational(-10));
      lp.equality.push_back(false);
    }
  EXPECT_FALSE(simulation::feasible_by_elimination(lp, 8).has_value());
  ASSERT_TRUE(simulation::feasible_by_elimination(lp, 400).has_value());
  EXPECT_TRUE(*simulation::feasible_by_elimination(lp, 400));
  lp.rows.push_back({Rational(1), Rational(0)});
  lp.rhs.push_back(Rational(11));   // x >= 11
  lp.equality.push_back(false);
  const std::optional<bool> verdict = simulation::feasible_by_elimination(lp, 400);
  simulation::exact_lp_elimination() = false;
  const bool oracle = simulation::exact_feasible_point(lp).has_value();
  simulation::exact_lp_elimination() = true;
  ASSERT_TRUE(verdict.has_value());
  EXPECT_EQ(*verdict, oracle);
}

}  // namespace
}  // namespace hipair
