// HIPAIR — exact linear feasibility (exact_lp.hpp).
#include "simulation/exact_lp.hpp"

#include <hipair/error.hpp>

#include <CGAL/gmpxx.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <string>

namespace hipair::simulation {

std::optional<std::vector<Rational>> exact_feasible_point(const ExactLinearSystem& system) {
  // every variable free unless marked; the default relation is overwritten per row
  CGAL::Quadratic_program<Rational> lp(CGAL::EQUAL, false, 0, false, 0);
  for (std::size_t j = 0; j < system.variables; ++j) {
    if (system.nonnegative[j]) lp.set_l(static_cast<int>(j), true, Rational(0));
    lp.set_c(static_cast<int>(j), Rational(0));
  }
  for (std::size_t i = 0; i < system.rows.size(); ++i) {
    for (std::size_t j = 0; j < system.variables; ++j)
      if (sgn(system.rows[i][j]) != 0) lp.set_a(static_cast<int>(j), static_cast<int>(i), system.rows[i][j]);
    lp.set_b(static_cast<int>(i), system.rhs[i]);
    lp.set_r(static_cast<int>(i), system.equality[i] ? CGAL::EQUAL : CGAL::LARGER);
  }
  if (system.rows.empty()) return std::vector<Rational>(system.variables, Rational(0));
  const CGAL::Quadratic_program_solution<Rational> s = CGAL::solve_linear_program(lp, Rational());
  if (s.is_infeasible()) return std::nullopt;
  std::vector<Rational> z;
  z.reserve(system.variables);
  for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
    z.push_back(Rational(it->numerator() / it->denominator()));
  // (the solver's answer checked: a feasible point must satisfy every row exactly)
  for (std::size_t i = 0; i < system.rows.size(); ++i) {
    Rational sum = 0;
    for (std::size_t j = 0; j < system.variables; ++j) sum += system.rows[i][j] * z[j];
    if (system.equality[i] ? sum != system.rhs[i] : sum < system.rhs[i])
      throw NumericError("internal: the exact linear program's solution does not satisfy its row " + std::to_string(i));
  }
  for (std::size_t j = 0; j < system.variables; ++j)
    if (system.nonnegative[j] && sgn(z[j]) < 0)
      throw NumericError("internal: the exact linear program's solution has a negative variable");
  return z;
}

}  // namespace hipair::simulation
