// HIPAIR — exact linear feasibility (exact_lp.hpp); its decision by elimination
// (exact_lp_elimination.hpp).
#include "simulation/exact_lp.hpp"

#include "simulation/exact_lp_elimination.hpp"
#include "simulation/fraction_free.hpp"

#include "kernels/interval.hpp"

#include <hipair/error.hpp>

#include <CGAL/gmpxx.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>
#include <string>
#include <utility>

namespace hipair::simulation {

namespace {

// an integer row: the unknowns' coefficients, then the constant c of  a . z + c (= or >=) 0
using IntegerRow = std::vector<mpz_class>;

enum class Constant { no, holds, fails };

// the row divided by its entries' content (a positive factor: the same condition); when no
// unknown is left, whether the condition holds
Constant reduce(IntegerRow& row, bool equality, mpz_class& g) {
  g = 0;
  for (const mpz_class& e : row)
    if (sgn(e) != 0) {
      mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), e.get_mpz_t());
      if (mpz_cmp_ui(g.get_mpz_t(), 1) == 0) break;
    }
  if (sgn(g) != 0 && mpz_cmp_ui(g.get_mpz_t(), 1) != 0)
    for (mpz_class& e : row)
      if (sgn(e) != 0) mpz_divexact(e.get_mpz_t(), e.get_mpz_t(), g.get_mpz_t());
  const std::size_t n = row.size() - 1;
  for (std::size_t j = 0; j < n; ++j)
    if (sgn(row[j]) != 0) return Constant::no;
  const int s = sgn(row[n]);
  return (equality ? s == 0 : s >= 0) ? Constant::holds : Constant::fails;
}

// row := f row - g pivot (a Bareiss step whose previous pivot is 1)
void combine(IntegerRow& row, const mpz_class& f, const IntegerRow& pivot, const mpz_class& g) {
  static const mpz_class one(1);
  thread_local mpz_class scratch;
  fraction_free_detail::bareiss_row(row, pivot, f, g, one, 0, scratch);
}

// whether the row has an unknown left (a nonzero entry before the constant)
bool has_unknown(const IntegerRow& row) {
  for (std::size_t j = 0; j + 1 < row.size(); ++j)
    if (sgn(row[j]) != 0) return true;
  return false;
}

// of rows whose unknowns' parts are positive multiples of one another (a . z + c >= 0 for the same
// a up to the factor), only the tightest (the least c / factor) kept: the same solution set
void drop_parallel(std::vector<IntegerRow>& rows) {
  struct Parallel {
    IntegerRow part;   // the unknowns' part divided by its content
    Rational c;        // the constant divided by the same
    std::size_t row;
  };
  std::vector<Parallel> parts(rows.size());
  mpz_class g;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const IntegerRow& row = rows[r];
    const std::size_t n = row.size() - 1;
    g = 0;
    for (std::size_t j = 0; j < n; ++j)
      if (sgn(row[j]) != 0) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), row[j].get_mpz_t());
    parts[r].part.assign(row.begin(), row.end() - 1);
    for (mpz_class& e : parts[r].part)
      if (sgn(e) != 0) mpz_divexact(e.get_mpz_t(), e.get_mpz_t(), g.get_mpz_t());
    parts[r].c = Rational(row[n], g);
    parts[r].c.canonicalize();
    parts[r].row = r;
  }
  std::sort(parts.begin(), parts.end(), [](const Parallel& a, const Parallel& b) {
    if (a.part != b.part) return a.part < b.part;
    return a.c < b.c || (a.c == b.c && a.row < b.row);
  });
  std::vector<IntegerRow> kept;
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (k == 0 || parts[k].part != parts[k - 1].part) kept.push_back(std::move(rows[parts[k].row]));
  std::swap(rows, kept);
}

// ---- the filter in intervals: entries enclosing the exact ones; [0, 0] only where the exact
// entry is 0 (a sum or product is formed only of nonzero terms, so that zeros stay exact)
using kernels::Interval;
using IntervalRow = std::vector<Interval>;

// row := f row - g pivot, entry by entry (f > 0 certainly where row is an inequality)
void combine(IntervalRow& row, const Interval& f, const IntervalRow& pivot, const Interval& g) {
  for (std::size_t j = 0; j < row.size(); ++j) {
    const bool e = row[j].sign() != 0, p = pivot[j].sign() != 0;
    if (e && p) row[j] = f * row[j] - g * pivot[j];
    else if (e) row[j] = f * row[j];
    else if (p) row[j] = -(g * pivot[j]);
  }
}

// a row without unknowns that certainly fails (an inequality's constant < 0, an equality's != 0)
bool certainly_fails(const IntervalRow& row, bool equality) {
  for (std::size_t j = 0; j + 1 < row.size(); ++j)
    if (row[j].sign() != 0) return false;
  const int s = row.back().sign();
  return equality ? (s == 1 || s == -1) : s == -1;
}

bool unknown_left(const IntervalRow& row) {
  for (std::size_t j = 0; j + 1 < row.size(); ++j)
    if (row[j].sign() != 0) return true;
  return false;
}

}  // namespace

bool certainly_infeasible_in_intervals(const ExactLinearSystem& system, std::size_t max_rows) {
  IntervalLinearSystem enclosed;
  enclosed.variables = system.variables;
  enclosed.nonnegative = system.nonnegative;
  enclosed.equality = system.equality;
  enclosed.rows.reserve(system.rows.size());
  enclosed.rhs.reserve(system.rows.size());
  for (std::size_t i = 0; i < system.rows.size(); ++i) {
    IntervalRow row(system.variables);
    for (std::size_t j = 0; j < system.variables; ++j) row[j] = Interval::enclose(system.rows[i][j]);
    enclosed.rows.push_back(std::move(row));
    enclosed.rhs.push_back(Interval::enclose(system.rhs[i]));
  }
  return certainly_infeasible_in_intervals(enclosed, max_rows);
}

bool certainly_infeasible_in_intervals(const IntervalLinearSystem& system, std::size_t max_rows) {
  const std::size_t n = system.variables;
  std::vector<IntervalRow> equalities, inequalities;
  for (std::size_t i = 0; i < system.rows.size(); ++i) {
    IntervalRow row(n + 1);
    for (std::size_t j = 0; j < n; ++j) row[j] = system.rows[i][j];
    row[n] = -system.rhs[i];
    if (certainly_fails(row, system.equality[i])) return true;
    if (unknown_left(row)) (system.equality[i] ? equalities : inequalities).push_back(std::move(row));
  }
  for (std::size_t j = 0; j < n; ++j)
    if (system.nonnegative[j]) {
      inequalities.emplace_back(n + 1, Interval(0));
      inequalities.back()[j] = Interval(1);
    }
  // each equality solved for an unknown whose coefficient's sign is certain, substituted into the
  // other rows: p row - row_j pivot with p > 0 (the pivot negated where p < 0); an equality
  // without such an unknown is dropped
  while (!equalities.empty()) {
    IntervalRow pivot = std::move(equalities.back());
    equalities.pop_back();
    std::size_t j = 0;
    while (j < n && (pivot[j].sign() == 0 || pivot[j].sign() == 2)) ++j;
    if (j == n) continue;
    if (pivot[j].sign() < 0)
      for (Interval& e : pivot) e = -e;
    for (bool equality : {true, false}) {
      std::vector<IntervalRow>& rows = equality ? equalities : inequalities;
      for (std::size_t r = 0; r < rows.size();) {
        IntervalRow& row = rows[r];
        if (row[j].sign() != 0) {
          const Interval g = row[j];
          combine(row, pivot[j], pivot, g);
          row[j] = Interval(0);   // (exactly 0 in the exact elimination)
          if (certainly_fails(row, equality)) return true;
          if (!unknown_left(row)) {
            if (r + 1 != rows.size()) row = std::move(rows.back());
            rows.pop_back();
            continue;
          }
        }
        ++r;
      }
    }
  }
  // Fourier–Motzkin on the certain signs; a row whose sign on the unknown eliminated is
  // uncertain, and the rows of an unknown bounded on one side, are dropped
  std::vector<IntervalRow> next;
  while (!inequalities.empty()) {
    std::size_t best = n, best_cost = 0;
    for (std::size_t j = 0; j < n; ++j) {
      std::size_t positive = 0, negative = 0, uncertain = 0;
      for (const IntervalRow& row : inequalities) {
        const int s = row[j].sign();
        positive += s == 1;
        negative += s == -1;
        uncertain += s == 2;
      }
      if (positive + negative + uncertain == 0) continue;
      const std::size_t cost = positive * negative + 1000 * uncertain;
      if (best == n || cost < best_cost) {
        best = j;
        best_cost = cost;
      }
    }
    if (best == n) return false;
    const std::size_t j = best;
    next.clear();
    for (const IntervalRow& p : inequalities) {
      if (p[j].sign() != 1) continue;
      for (const IntervalRow& q : inequalities) {
        if (q[j].sign() != -1) continue;
        IntervalRow row = p;
        combine(row, -q[j], q, -p[j]);   // (-q_j) p + p_j q
        row[j] = Interval(0);
        if (certainly_fails(row, false)) return true;
        if (unknown_left(row)) next.push_back(std::move(row));
        if (next.size() > max_rows) return false;
      }
    }
    for (IntervalRow& row : inequalities)
      if (row[j].sign() == 0) next.push_back(std::move(row));
    if (next.size() > max_rows) return false;
    std::swap(inequalities, next);
  }
  return false;
}

std::optional<bool> feasible_by_elimination(const ExactLinearSystem& system, std::size_t max_rows) {
  const std::size_t n = system.variables;
  std::vector<IntegerRow> equalities, inequalities;
  mpz_class f, g;
  std::vector<Rational> constant(1);
  for (std::size_t i = 0; i < system.rows.size(); ++i) {
    constant[0] = -system.rhs[i];
    IntegerRow row;
    fraction_free_detail::integer_row(system.rows[i], &constant, row);
    // (not divided by its content: the fraction-free steps keep the entries minors)
    if (!has_unknown(row)) {
      const int c = sgn(row.back());
      if (system.equality[i] ? c != 0 : c < 0) return false;
      continue;
    }
    (system.equality[i] ? equalities : inequalities).push_back(std::move(row));
  }
  for (std::size_t j = 0; j < n; ++j)
    if (system.nonnegative[j]) {
      inequalities.emplace_back(n + 1, mpz_class(0));
      inequalities.back()[j] = 1;
    }
  // each equality solved for its first unknown and substituted into every other row, by
  // fraction-free (Bareiss) steps (fraction_free.hpp): row := (p row - row_j pivot) / p_prev, an
  // exact division; after the step with pivot p every row is p times itself plus a combination
  // of equalities (the products of p_k / p_(k-1) telescope), so on the equalities' solutions an
  // inequality row keeps its sense when p > 0 and is reversed when p < 0
  mpz_class previous = 1, t;
  int sense = 1;
  while (!equalities.empty()) {
    IntegerRow pivot = std::move(equalities.back());
    equalities.pop_back();
    if (!has_unknown(pivot)) {   // 0 = c
      if (sgn(pivot.back()) != 0) return false;
      continue;
    }
    std::size_t j = 0;
    while (sgn(pivot[j]) == 0) ++j;
    const mpz_class& p = pivot[j];
    for (std::vector<IntegerRow>* rows : {&equalities, &inequalities})
      for (IntegerRow& row : *rows) {
        f = row[j];
        fraction_free_detail::bareiss_row(row, pivot, p, f, previous, 0, t);
      }
    sense = sgn(p);
    previous = p;
  }
  for (std::size_t r = 0; r < inequalities.size();) {
    IntegerRow& row = inequalities[r];
    if (sense < 0)
      for (mpz_class& e : row) mpz_neg(e.get_mpz_t(), e.get_mpz_t());
    const Constant c = reduce(row, false, g);
    if (c == Constant::fails) return false;
    if (c == Constant::holds) {
      if (r + 1 != inequalities.size()) row = std::move(inequalities.back());
      inequalities.pop_back();
    } else {
      ++r;
    }
  }
  // Fourier–Motzkin: the unknown whose elimination makes the fewest rows first (the first such)
  std::vector<IntegerRow> next;
  while (!inequalities.empty()) {
    std::size_t best = n, best_made = 0, best_positive = 0, best_negative = 0;
    for (std::size_t j = 0; j < n; ++j) {
      std::size_t positive = 0, negative = 0;
      for (const IntegerRow& row : inequalities) {
        const int s = sgn(row[j]);
        positive += s > 0;
        negative += s < 0;
      }
      if (positive + negative == 0) continue;
      const std::size_t made = positive * negative;
      if (best == n || made < best_made) {
        best = j;
        best_made = made;
        best_positive = positive;
        best_negative = negative;
      }
    }
    const std::size_t j = best;   // (every row left has an unknown)
    next.clear();
    const std::size_t kept = inequalities.size() - best_positive - best_negative;
    if (kept + best_made > max_rows) return std::nullopt;
    // an unknown bounded on one side only satisfies its rows whatever the others are: they go
    for (const IntegerRow& p : inequalities) {
      if (sgn(p[j]) <= 0) continue;
      for (const IntegerRow& q : inequalities) {
        if (sgn(q[j]) >= 0) continue;
        // (-q_j) p + p_j q: both factors positive, unknown j gone
        IntegerRow row = p;
        f = -q[j];
        g = -p[j];
        combine(row, f, q, g);
        const Constant c = reduce(row, false, g);
        if (c == Constant::fails) return false;
        if (c == Constant::no) next.push_back(std::move(row));
      }
    }
    for (IntegerRow& row : inequalities)
      if (sgn(row[j]) == 0) next.push_back(std::move(row));
    std::swap(inequalities, next);
    if (inequalities.size() > 8) drop_parallel(inequalities);
  }
  return true;
}

std::optional<std::vector<Rational>> exact_feasible_point(const ExactLinearSystem& system) {
  if (system.rows.empty()) return std::vector<Rational>(system.variables, Rational(0));
  // no solution decided by elimination; a solution's point from the linear program, as before
  if (exact_lp_elimination() && certainly_infeasible_in_intervals(system)) {
    ++exact_lp_eliminated();
    ++exact_lp_interval_decided();
    return std::nullopt;
  }
  // (too many rows for the elimination: the linear program decides alone)
  const std::optional<bool> feasible =
      exact_lp_elimination() ? feasible_by_elimination(system) : std::optional<bool>();
  if (feasible && !*feasible) {
    ++exact_lp_eliminated();
    return std::nullopt;
  }
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
  const CGAL::Quadratic_program_solution<Rational> s = CGAL::solve_linear_program(lp, Rational());
  if (s.is_infeasible()) {
    if (feasible)
      throw NumericError("internal: the exact linear program has no solution where exact elimination found one");
    return std::nullopt;
  }
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
