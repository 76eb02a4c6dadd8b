// The exact solves and echelon forms of the held-contact and impact decisions by fraction-free
// elimination (src/simulation/fraction_free.hpp, switch simulation::fraction_free(); used by
// held_force_sign.hpp's solve and exact_elimination.hpp's row_echelon). Oracles:
// - generated rational systems (integers, rationals with small and 2^k denominators, doubles
//   across 2^±60, zeros, planted dependent rows), solved with the switch on and off (rational
//   Gauss–Jordan): the same refusal of a singular matrix and the same rationals; every regular
//   answer also checked by A X = B exactly;
// - generated echelon forms with the switch on and off: the same pivot columns, every row a
//   nonzero multiple of the rational one (so the same zero rows and back-substitutions), and the
//   back-substituted solution of a consistent system the same rationals;
// - whole simulations side by side with the switch on and off (tests/unit/simulation_side_by_side.hpp):
//   every state and event bit for bit (the escapement's frictional impacts, the ratchet, the
//   scotch yoke).
#include "simulation/exact_elimination.hpp"
#include "simulation/fraction_free.hpp"
#include "simulation/held_force_sign.hpp"
#include "random_rationals.hpp"
#include "simulation_side_by_side.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Matrix = std::vector<std::vector<Rational>>;

// One entry: zero, an integer, a rational with a small or a power-of-two denominator, or a double
// anywhere in 2^±60 (as the simulators' rows give them).
Rational entry(std::mt19937_64& random) {
  switch (random() % 6) {
    case 0: return 0;
    case 1: return Rational(static_cast<long>(random() % 2001) - 1000);
    case 2: return test_numbers::random_rational(random, Rational(-50), Rational(50));
    case 3: {
      const mpz_class num = test_numbers::random_integer(random, 1 + static_cast<int>(random() % 60), true);
      mpz_class d = 1;
      d <<= static_cast<mp_bitcnt_t>(random() % 80);
      return test_numbers::canonical(num, d);
    }
    default: {
      std::uniform_real_distribution<double> unit(-1, 1);
      return Rational(std::ldexp(unit(random), static_cast<int>(random() % 121) - 60));
    }
  }
}

// Row `target` of M replaced by a rational combination of two other rows (a dependent row).
void plant_dependent(std::mt19937_64& random, Matrix& M, std::size_t target) {
  if (M.size() < 2) {
    for (Rational& e : M[target]) e = 0;
    return;
  }
  std::size_t a = random() % M.size(), b = random() % M.size();
  if (a == target) a = (a + 1) % M.size();
  if (b == target) b = (b + 1) % M.size();
  const Rational s = entry(random), t = entry(random);
  for (std::size_t j = 0; j < M[target].size(); ++j) M[target][j] = s * M[a][j] + t * M[b][j];
}

std::optional<Matrix> solve_with(bool fraction_free, const Matrix& A, const Matrix& B) {
  simulation::fraction_free() = fraction_free;
  std::optional<Matrix> X = simulation::held_force_detail::solve(A, B);
  simulation::fraction_free() = true;
  return X;
}

TEST(SimulationFractionFree, SolvesAsRationalGaussJordan) {
  std::mt19937_64 random(test::test_seed(7001));
  int regular = 0, singular = 0, several_rows = 0;
  const std::size_t before = simulation::fraction_free_eliminations();
  for (int trial = 0; trial < 2500; ++trial) {
    const std::size_t n = 1 + random() % 6, m = 1 + random() % 3;
    several_rows += n >= 2;   // a single row stays rational (one division): not dispatched
    Matrix A(n, std::vector<Rational>(n)), B(n, std::vector<Rational>(m));
    for (auto& row : A)
      for (Rational& e : row) e = entry(random);
    for (auto& row : B)
      for (Rational& e : row) e = entry(random);
    if (random() % 4 == 0) plant_dependent(random, A, random() % n);
    const std::optional<Matrix> oracle = solve_with(false, A, B), fast = solve_with(true, A, B);
    ASSERT_EQ(oracle.has_value(), fast.has_value()) << "trial " << trial;
    if (!oracle) {
      ++singular;
      continue;
    }
    ++regular;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < m; ++j) ASSERT_EQ((*fast)[i][j], (*oracle)[i][j]) << "trial " << trial;
    for (std::size_t i = 0; i < n; ++i)   // A X = B exactly
      for (std::size_t j = 0; j < m; ++j) {
        Rational sum = 0;
        for (std::size_t l = 0; l < n; ++l) sum += A[i][l] * (*fast)[l][j];
        ASSERT_EQ(sum, B[i][j]) << "trial " << trial;
      }
  }
  std::printf("fraction-free solves: %d regular, %d singular, as rational Gauss-Jordan\n", regular, singular);
  EXPECT_GT(regular, 1000);
  EXPECT_GT(singular, 200);
  EXPECT_GE(simulation::fraction_free_eliminations() - before, static_cast<std::size_t>(several_rows));
}

TEST(SimulationFractionFree, EchelonFormsAsRationalElimination) {
  std::mt19937_64 random(test::test_seed(7002));
  int deficient = 0, consistent = 0;
  for (int trial = 0; trial < 2500; ++trial) {
    const std::size_t k = 1 + random() % 6, columns = 1 + random() % 6;
    Matrix E(k, std::vector<Rational>(columns + 1));   // an augmented right-hand side
    for (auto& row : E)
      for (Rational& e : row) e = entry(random);
    const int planted = static_cast<int>(random() % 3);
    for (int p = 0; p < planted; ++p) plant_dependent(random, E, random() % k);
    Matrix rational = E, integer = E;
    simulation::fraction_free() = false;
    const std::vector<std::size_t> pivots = simulation::row_echelon(rational, columns);
    simulation::fraction_free() = true;
    const std::vector<std::size_t> fast = simulation::row_echelon(integer, columns);
    ASSERT_EQ(fast, pivots) << "trial " << trial;
    if (pivots.size() < std::min(k, columns)) ++deficient;
    for (std::size_t i = 0; i < k; ++i) {
      // row i a nonzero multiple of the rational row i
      std::optional<Rational> factor;
      for (std::size_t j = 0; j <= columns; ++j) {
        ASSERT_EQ(sgn(integer[i][j]) == 0, sgn(rational[i][j]) == 0) << "trial " << trial << " row " << i;
        if (sgn(rational[i][j]) == 0) continue;
        const Rational f = integer[i][j] / rational[i][j];
        if (!factor) factor = f;
        ASSERT_EQ(f, *factor) << "trial " << trial << " row " << i;
      }
    }
    // the back-substitution of a consistent system (reduced_feasible_point's, held_resolution's)
    const std::size_t rank = pivots.size();
    bool inconsistent = false;
    for (std::size_t r = rank; r < k; ++r) inconsistent = inconsistent || sgn(rational[r][columns]) != 0;
    if (inconsistent) continue;
    ++consistent;
    auto back = [&](const Matrix& M) {
      std::vector<Rational> z(columns, Rational(0));
      for (std::size_t r = rank; r-- > 0;) {
        const std::size_t c = pivots[r];
        Rational s = M[r][columns];
        for (std::size_t j = c + 1; j < columns; ++j) s -= M[r][j] * z[j];
        z[c] = s / M[r][c];
      }
      return z;
    };
    ASSERT_EQ(back(integer), back(rational)) << "trial " << trial;
  }
  std::printf("fraction-free echelon forms: 2500 as rational elimination (%d rank-deficient, %d consistent)\n",
              deficient, consistent);
  EXPECT_GT(deficient, 300);
  EXPECT_GT(consistent, 300);
}

// Whole runs: every state and event bit for bit with the switch on and off, and the escapement's
// exact impact decisions through the fraction-free code.
TEST(SimulationFractionFree, RunsEqualTheRunsWithRationalElimination) {
  const std::size_t before = simulation::fraction_free_eliminations();
  const test::SideBySide runs = test::examples_side_by_side<simulation::fraction_free>(
      {{"escapement.json", 0.5, 1e-3}, {"ratchet.json", 0.05, 0, -20}, {"scotch-yoke.json", 0.3, 1e-6}}, 3000);
  std::printf("fraction-free runs: %zu steps, %zu events equal\n", runs.steps, runs.events);
  EXPECT_GT(runs.events, 80u);
  EXPECT_GT(simulation::fraction_free_eliminations() - before, 100u);
}

}  // namespace
}  // namespace hipair
