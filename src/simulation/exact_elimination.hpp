// HIPAIR — exact Gaussian elimination on rational matrices, shared by the held-contact decisions
// (held_force_sign.hpp: a force problem's independent rows and columns; held_resolution.hpp: an
// impact's projection). Internal to src/simulation.
#pragma once

#include <hipair/rational.hpp>

#include "simulation/fraction_free.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace hipair::simulation {

/// Forward elimination of E to row echelon form over its first `columns` columns, every row's
/// later entries (an augmented right-hand side) carried along: a pivot is the first row (from the
/// current one down) whose entry is not 0 — exact, no choice by size. Returns the pivot columns
/// in order (their count is E's rank over those columns; the rows beyond it are 0 there).
/// (Session 70, speed70: in integers, fraction_free_echelon — E's rows nonzero multiples of these,
/// the same pivots, zero rows and back-substitutions; this rational form with the switch off.)
inline std::vector<std::size_t> row_echelon(std::vector<std::vector<Rational>>& E, std::size_t columns) {
  if (fraction_free() && E.size() >= 2) return fraction_free_echelon(E, columns);   // one row: no elimination
  const std::size_t k = E.size();
  std::vector<std::size_t> pivot_column;
  std::size_t row = 0;
  for (std::size_t c = 0; c < columns && row < k; ++c) {
    std::size_t r = row;
    while (r < k && sgn(E[r][c]) == 0) ++r;
    if (r == k) continue;
    std::swap(E[r], E[row]);
    for (std::size_t i = row + 1; i < k; ++i) {
      if (sgn(E[i][c]) == 0) continue;
      const Rational f = E[i][c] / E[row][c];
      for (std::size_t j = c; j < E[i].size(); ++j) E[i][j] -= f * E[row][j];
    }
    pivot_column.push_back(c);
    ++row;
  }
  return pivot_column;
}

}  // namespace hipair::simulation
