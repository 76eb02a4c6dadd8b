// HIPAIR — exact_lp.hpp's feasibility decided by exact elimination (session 71, speed71): the
// equalities substituted away and the remaining unknowns eliminated from the inequalities by
// Fourier–Motzkin, every row an integer vector (fraction-free: scaled by its common denominator,
// combined with positive integer factors, divided by its content). Each step is an exact
// projection of the solution set onto the unknowns left, so the system has a solution iff no row
// without unknowns ends false: the same verdict as CGAL's linear program, decided without it.
// exact_feasible_point answers "no solution" from here; a system with a solution still takes its
// point from CGAL's solver, as before (the same point: no published number changes). The
// escapement's impact decisions asked CGAL's solver 12 times per 0.5 s, each time for a system
// without a solution, at ≈ 1.9 M instructions each (docs/performance.md, "Session 71 (speed71)").
// In front of it a certified filter (certainly_infeasible_in_intervals): the same elimination in
// kernels::Interval arithmetic, every entry enclosing the exact one, every multiplier of an
// inequality certainly positive, rows whose sign is uncertain dropped (a subset of the rows without
// a solution: the system has none); it answers only "no solution", otherwise the exact elimination
// decides. Internal to src/simulation.
#pragma once

#include "core/thread_switch.hpp"
#include "kernels/interval.hpp"
#include "simulation/exact_lp.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::simulation {

// The switch (on by default; a test turns it off on its thread to compare with CGAL's solver
// alone), how many systems it found without a solution on this thread, and how many of those the
// interval filter decided.
struct ExactLpEliminationTag;
inline bool& exact_lp_elimination() { return thread_switch<ExactLpEliminationTag>(); }
struct ExactLpEliminationCountTag;
inline std::size_t& exact_lp_eliminated() { return thread_counter<ExactLpEliminationCountTag>(); }
struct ExactLpIntervalCountTag;
inline std::size_t& exact_lp_interval_decided() { return thread_counter<ExactLpIntervalCountTag>(); }

/// Whether `system` has a solution, decided exactly by elimination (see above); none when the
/// Fourier–Motzkin rows would exceed `max_rows` (then the linear program decides).
std::optional<bool> feasible_by_elimination(const ExactLinearSystem& system, std::size_t max_rows = 400);

/// A linear system as ExactLinearSystem's, each number given by an interval enclosing the exact
/// one, [0, 0] only where the exact number is 0 (session 72, speed72: friction.hpp's
/// exact_assignment forms its held sets' systems so, from its rows' enclosures, and refuses most
/// of them before any rational is formed).
struct IntervalLinearSystem {
  std::size_t variables = 0;
  std::vector<bool> nonnegative;                      ///< per variable
  std::vector<std::vector<kernels::Interval>> rows;   ///< each of `variables` entries
  std::vector<kernels::Interval> rhs;
  std::vector<bool> equality;                         ///< per row: = (true) or >= (false)
};

/// True when the elimination in intervals (see above) certainly finds no solution; false:
/// undecided. On exact data each number is enclosed (Interval::enclose) and the interval system
/// decided (the same answer: the enclosures are those the filter formed before session 72).
bool certainly_infeasible_in_intervals(const ExactLinearSystem& system, std::size_t max_rows = 400);
bool certainly_infeasible_in_intervals(const IntervalLinearSystem& system, std::size_t max_rows = 400);

}  // namespace hipair::simulation
