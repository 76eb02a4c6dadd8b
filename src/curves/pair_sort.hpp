// HIPAIR — index pairs sorted ascending in linear time (private to src/curves).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace hipair::cspace {

/// Sorts `pairs` ascending by (first, second), exactly the order std::sort gives, where every
/// first lies in [0, first_bound) and every second in [0, second_bound): two stable counting
/// passes (by second, then by first) when the list is long against the bounds, else std::sort.
/// The blocked-space culler's core-pair sweeps sort hundreds of thousands of pairs of a few
/// hundred cores per cell (docs/performance.md, "Session 46 (gear46)").
inline void sort_index_pairs(std::vector<std::pair<int, int>>& pairs, std::size_t first_bound,
                             std::size_t second_bound) {
  const std::size_t n = pairs.size();
  if (n < 64 || n < (first_bound + second_bound) / 2) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  thread_local std::vector<std::pair<int, int>> by_second;
  thread_local std::vector<std::uint32_t> start;
  by_second.resize(n);
  // by the second index (stable: the first pass's order is kept among equal seconds)
  start.assign(second_bound + 1, 0);
  for (const auto& p : pairs) ++start[static_cast<std::size_t>(p.second) + 1];
  for (std::size_t k = 0; k < second_bound; ++k) start[k + 1] += start[k];
  for (const auto& p : pairs) by_second[start[static_cast<std::size_t>(p.second)]++] = p;
  // then by the first index, stable: equal firsts stay ascending by second
  start.assign(first_bound + 1, 0);
  for (const auto& p : by_second) ++start[static_cast<std::size_t>(p.first) + 1];
  for (std::size_t k = 0; k < first_bound; ++k) start[k + 1] += start[k];
  for (const auto& p : by_second) pairs[start[static_cast<std::size_t>(p.first)]++] = p;
}

}  // namespace hipair::cspace
