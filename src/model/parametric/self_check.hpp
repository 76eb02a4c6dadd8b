// The parametric model's self-check (parametric.cpp, RecipeBuilder): the exact geometry its
// recorded formulas give at the nominal vector must be the part read, exactly. The model read
// was validated and oriented by its reader; the check compares the two parts directly (loops,
// edges, pivot, direction) instead of validating the parametric form's geometry again. Each
// loop of the parametric form, in the order its recipe writes it, matches the loop read either
// as it is or reversed (the reader oriented it): which one is the loop's recorded reversal.
#pragma once

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <optional>
#include <vector>

namespace hipair::model_detail {

/// Whether edge `y` is edge `x` exactly (kind, ends, sense, an arc's centre and radius), or
/// with `reversed`, edge `x` run backwards (ends swapped, the other sense).
inline bool same_edge(const Edge& x, const Edge& y, bool reversed = false) {
  if (x.kind != y.kind) return false;
  if (reversed ? !(x.source == y.target && x.target == y.source && x.ccw != y.ccw)
               : !(x.source == y.source && x.target == y.target && x.ccw == y.ccw))
    return false;
  return !x.is_arc() || (x.center == y.center && x.radius_squared == y.radius_squared);
}

/// Whether loop `read` is loop `mine` edge for edge, or with `reversed`, `mine` run backwards
/// (its edges in the reverse order, each reversed).
inline bool same_loop(const Loop& mine, const Loop& read, bool reversed) {
  const std::size_t n = mine.edges.size();
  if (read.edges.size() != n) return false;
  for (std::size_t e = 0; e < n; ++e)
    if (!same_edge(mine.edges[reversed ? n - 1 - e : e], read.edges[e], reversed)) return false;
  return true;
}

/// Whether `read` has the geometry of `mine` (the parametric form's part at the nominal vector,
/// its loops as the recipe writes them): the same pivot and direction, and each loop the same
/// as read or reversed. Returns the reversal of each loop, or nothing when they differ.
inline std::optional<std::vector<bool>> loop_reversals(const Part& mine, const Part& read) {
  if (mine.loops.size() != read.loops.size() || !(mine.motion.pivot == read.motion.pivot) ||
      !(mine.motion.direction == read.motion.direction))
    return std::nullopt;
  std::vector<bool> reversed;
  for (std::size_t l = 0; l < mine.loops.size(); ++l) {
    if (same_loop(mine.loops[l], read.loops[l], false)) {
      reversed.push_back(false);
    } else if (same_loop(mine.loops[l], read.loops[l], true)) {
      reversed.push_back(true);
    } else {
      return std::nullopt;
    }
  }
  return reversed;
}

/// loop_reversals. \throws ModelError naming `read` when its geometry is not `mine`'s.
inline std::vector<bool> checked_loop_reversals(const Part& mine, const Part& read) {
  std::optional<std::vector<bool>> reversed = loop_reversals(mine, read);
  if (!reversed)
    throw ModelError(read.pointer, "internal error: the parametric form of part '" + read.name +
                                       "' does not reproduce the geometry read");
  return *reversed;
}

}  // namespace hipair::model_detail
