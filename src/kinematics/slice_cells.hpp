// Binary searches of the kernel slicer and the slice reader over sorted exact values: the
// follower cells holding a value or meeting a range (cells [edges[c], edges[c + 1]], closed,
// edges ascending), and the first point of a slice not below a rational. Each answers what a
// linear scan with the same exact comparisons answers (tests/unit/kinematics_slice_cells_test.cpp),
// in O(log n) comparisons instead of two per cell (one-limb values compared in machine integers,
// compare_rationals).
#pragma once

#include "algebra/rational_order.hpp"
#include "algebra/real_filters.hpp"

#include <hipair/rational.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace hipair::kinematics_detail::slice_cells {

/// The first index i with edges[i] >= value (edges.size() when none), edges ascending.
inline std::size_t first_not_below(const std::vector<Rational>& edges, const Rational& value) {
  std::size_t lo = 0, hi = edges.size();
  while (lo < hi) {
    const std::size_t middle = lo + (hi - lo) / 2;
    if (cspace::algebra::compare_rationals(edges[middle], value) < 0) lo = middle + 1;
    else hi = middle;
  }
  return lo;
}

/// The cells c (bit c; at most 32 cells, edges.size() <= 33) with edges[c] <= value <=
/// edges[c + 1]: one cell inside, two on an inner edge, none outside [edges.front(), edges.back()].
inline std::uint32_t cells_holding(const std::vector<Rational>& edges, const Rational& value) {
  const std::size_t cells = edges.size() < 2 ? 0 : edges.size() - 1;
  const std::size_t i = first_not_below(edges, value);   // edges[i - 1] < value <= edges[i]
  std::uint32_t bits = 0;
  // cell i - 1 holds it when i >= 1 and i <= cells (edges[i - 1] < value <= edges[i])
  if (i >= 1 && i <= cells) bits |= std::uint32_t(1) << (i - 1);
  // cell i holds it when the value is edges[i] itself (and cell i exists)
  if (i < cells && edges[i] == value) bits |= std::uint32_t(1) << i;
  return bits;
}

/// The cells c with edges[c + 1] >= lo and edges[c] <= hi (those the closed range [lo, hi]
/// meets), as bits; lo <= hi.
inline std::uint32_t cells_meeting(const std::vector<Rational>& edges, const Rational& lo, const Rational& hi) {
  const std::size_t cells = edges.size() < 2 ? 0 : edges.size() - 1;
  // first cell: the least c with edges[c + 1] >= lo, i.e. c = first_not_below(lo) - 1 (0 at least)
  const std::size_t above_lo = first_not_below(edges, lo);
  const std::size_t first = above_lo == 0 ? 0 : above_lo - 1;
  // end: the cells c with edges[c] <= hi are those below the first edge above hi
  std::size_t a = 0, b = edges.size();
  while (a < b) {
    const std::size_t middle = a + (b - a) / 2;
    if (cspace::algebra::compare_rationals(hi, edges[middle]) < 0) b = middle;
    else a = middle + 1;
  }
  const std::size_t end = a < cells ? a : cells;   // cells [first, end)
  std::uint32_t bits = 0;
  for (std::size_t c = first; c < end; ++c) bits |= std::uint32_t(1) << c;
  return bits;
}

/// The index of the first point whose value is at or above `bound` (points ascending by
/// `.value`, a Real), by exact comparisons behind the certified double filter of
/// compare_filtered; nullopt when a point equals `bound`.
template <class Points>
std::optional<std::size_t> first_point_not_below(const Points& points, const Rational& bound) {
  std::size_t lo = 0, hi = points.size();
  while (lo < hi) {
    const std::size_t middle = lo + (hi - lo) / 2;
    const int side = cspace::algebra::compare_filtered(points[middle].value, bound);
    if (side == 0) return std::nullopt;
    if (side < 0) lo = middle + 1;
    else hi = middle;
  }
  return lo;
}

}  // namespace hipair::kinematics_detail::slice_cells
