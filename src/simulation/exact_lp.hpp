// HIPAIR — exact linear feasibility on rational data (CGAL's linear programming solver with
// GMP rationals as its exact type): whether a system of linear equations and inequalities has a
// solution, and one solution. Used by friction.hpp's exact stick/slip decisions (docs/simulation.md,
// "Session 65 (stick65)"). Internal to src/simulation.
#pragma once

#include <hipair/rational.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::simulation {

/// rows[i] . z  (= or >=)  rhs[i], z_j >= 0 where nonnegative[j], every number exact.
struct ExactLinearSystem {
  std::size_t variables = 0;
  std::vector<bool> nonnegative;              ///< per variable
  std::vector<std::vector<Rational>> rows;    ///< each of `variables` entries
  std::vector<Rational> rhs;
  std::vector<bool> equality;                 ///< per row: = (true) or >= (false)
};

/// A solution of the system, exact, or none when it has none (decided exactly: "none" by elimination
/// since session 71, exact_lp_elimination.hpp; a solution from CGAL's solve_linear_program, as before).
std::optional<std::vector<Rational>> exact_feasible_point(const ExactLinearSystem& system);

}  // namespace hipair::simulation
