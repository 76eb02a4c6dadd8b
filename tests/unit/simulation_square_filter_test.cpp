// The square systems' interval filter in its flat form (friction.hpp's
// square_certainly_infeasible(IntervalLinearSystem), session 73, speed73: one reused row-major
// block, rows permuted by index) against its former form (held_force_detail::solve on vectors of
// rows, written out below as it stood until session 72) and against the exact answer (the exact
// elimination, exact_lp_elimination.hpp, on the rational system the intervals enclose). Generated
// systems: square and not, regular and singular (duplicated and dependent equality rows), planted
// solutions (strict, tight, a multiplier exactly 0), contradictions by 2^-70, zero entries,
// entries enclosed as points, as Interval::enclose of a rational, and widened to hold 0 (an
// uncertain pivot). The filter must answer as the former form on every one, and "no solution"
// only where the exact elimination finds none.
#include "simulation/friction.hpp"

#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace hipair {
namespace {

using kernels::Interval;
using simulation::ExactLinearSystem;
using simulation::IntervalLinearSystem;

// the filter as it stood until session 72 (friction.hpp, speed72)
std::optional<bool> former_square_filter(const IntervalLinearSystem& lp) {
  namespace detail = simulation::held_force_detail;
  const std::size_t vars = lp.variables;
  detail::Matrix<Interval> A, b;
  for (std::size_t i = 0; i < lp.rows.size(); ++i)
    if (lp.equality[i]) {
      A.push_back(lp.rows[i]);
      b.push_back({lp.rhs[i]});
    }
  if (A.size() != vars) return std::nullopt;
  const std::optional<detail::Matrix<Interval>> z = detail::solve(std::move(A), std::move(b));
  if (!z) return std::nullopt;
  for (std::size_t j = 0; j < vars; ++j)
    if (lp.nonnegative[j] && (*z)[j][0].hi < 0) return true;
  for (std::size_t i = 0; i < lp.rows.size(); ++i) {
    if (lp.equality[i]) continue;
    Interval sum(0);
    for (std::size_t j = 0; j < vars; ++j)
      if (lp.rows[i][j].sign() != 0) sum = sum + lp.rows[i][j] * (*z)[j][0];
    if (sum.hi < lp.rhs[i].lo) return true;
  }
  return false;
}

Rational number(std::mt19937_64& random) {
  switch (random() % 4) {
    case 0: return Rational(static_cast<long>(random() % 7) - 3);
    case 1: return test_numbers::random_rational(random, Rational(-5), Rational(5));
    case 2: return Rational(0);
    default: {   // a double's exact value, 2^-30 .. 2^30
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      return Rational(std::ldexp(u(random), static_cast<int>(random() % 61) - 30));
    }
  }
}

// an enclosure of r: the point where r is a double, else Interval::enclose; sometimes widened
// (by a relative 2^-20, or to hold 0 where r is small: an uncertain sign), never [0, 0] unless r is 0
Interval enclosure(std::mt19937_64& random, const Rational& r) {
  Interval e = Interval::enclose(r);
  if (sgn(r) == 0) return e;
  switch (random() % 6) {
    case 0: {
      const double w = std::ldexp(std::max(std::abs(e.lo), std::abs(e.hi)), -20);
      return Interval(e.lo - w, e.hi + w);
    }
    case 1:
      if (random() % 4 == 0) return Interval(std::min(e.lo, -1e-300), std::max(e.hi, 1e-300));
      return e;
    default: return e;
  }
}

TEST(SimulationSquareFilter, FlatFormAnswersAsTheFormerAndOnlyWhereTheExactEliminationFindsNoSolution) {
  std::mt19937_64 random(test::test_seed(7301));
  std::size_t decided = 0, refused = 0, undecided = 0, square = 0;
  const Rational tiny = Rational(1) / Rational(mpz_class(1) << 70);
  for (int trial = 0; trial < 4000; ++trial) {
    const std::size_t vars = random() % 5;   // 0 .. 4 unknowns
    const bool make_square = random() % 5 != 0;
    const std::size_t eq = make_square ? vars : random() % (vars + 2);
    const std::size_t ineq = random() % 4;
    ExactLinearSystem exact;
    exact.variables = vars;
    exact.nonnegative.resize(vars);
    for (std::size_t j = 0; j < vars; ++j) exact.nonnegative[j] = random() % 2 == 0;
    // a planted point (some of its entries 0), or none
    const int plan = static_cast<int>(random() % 4);   // 0: none, 1: strict, 2: tight, 3: off by 2^-70
    std::vector<Rational> z(vars);
    for (std::size_t j = 0; j < vars; ++j) {
      z[j] = random() % 4 == 0 ? Rational(0) : number(random);
      if (exact.nonnegative[j] && sgn(z[j]) < 0) z[j] = -z[j];
    }
    auto add_row = [&](bool equality) {
      std::vector<Rational> row(vars);
      for (Rational& e : row) e = number(random);
      // degenerate: a duplicated or dependent equality (a singular square system)
      if (equality && !exact.rows.empty() && random() % 6 == 0) {
        const std::vector<Rational>& other = exact.rows[random() % exact.rows.size()];
        const Rational f = random() % 2 ? Rational(1) : Rational(-2, 3);
        for (std::size_t j = 0; j < vars; ++j) row[j] = f * other[j];
      }
      Rational value = 0;
      for (std::size_t j = 0; j < vars; ++j) value += row[j] * z[j];
      Rational rhs = plan == 0 ? number(random) : value;
      if (plan == 1 && !equality) rhs -= Rational(1, 1 + static_cast<long>(random() % 9));
      if (plan == 3) rhs += random() % 2 ? tiny : -tiny;
      exact.rows.push_back(std::move(row));
      exact.rhs.push_back(rhs);
      exact.equality.push_back(equality);
    };
    // the equalities among the inequalities at random places
    std::vector<bool> kinds(eq + ineq, false);
    std::fill(kinds.begin(), kinds.begin() + static_cast<long>(eq), true);
    std::shuffle(kinds.begin(), kinds.end(), random);
    for (bool k : kinds) add_row(k);
    IntervalLinearSystem lp;
    lp.variables = vars;
    lp.nonnegative = exact.nonnegative;
    lp.equality = exact.equality;
    for (std::size_t i = 0; i < exact.rows.size(); ++i) {
      std::vector<Interval> row(vars);
      for (std::size_t j = 0; j < vars; ++j) row[j] = enclosure(random, exact.rows[i][j]);
      lp.rows.push_back(std::move(row));
      lp.rhs.push_back(enclosure(random, exact.rhs[i]));
    }
    const std::optional<bool> flat = simulation::square_certainly_infeasible(lp);
    const std::optional<bool> former = former_square_filter(lp);
    ASSERT_EQ(flat.has_value(), former.has_value()) << "trial " << trial;
    if (flat) ASSERT_EQ(*flat, *former) << "trial " << trial;
    square += eq == vars;
    if (!flat) {
      ++undecided;
      continue;
    }
    ++decided;
    if (*flat) {
      ++refused;
      const std::optional<bool> feasible = simulation::feasible_by_elimination(exact);
      ASSERT_TRUE(feasible.has_value()) << "trial " << trial;
      ASSERT_FALSE(*feasible) << "trial " << trial << ": the filter says no solution, the exact elimination finds one";
    }
    if (plan == 1 || plan == 2) ASSERT_FALSE(*flat) << "trial " << trial << ": a planted solution refused";
  }
  // the generator reaches every answer
  EXPECT_GT(refused, 200u);
  EXPECT_GT(decided - refused, 200u);
  EXPECT_GT(undecided, 200u);
  EXPECT_GT(square, 2000u);
}

}  // namespace
}  // namespace hipair
