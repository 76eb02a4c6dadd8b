// Session 66 (geneva66): is a rotating part exactly symmetric under the half turn about its
// pivot? Issue 14's Geneva lever (docs/performance.md "Session 66 (geneva66)"): where the part
// maps onto itself under q -> 2 p - q (p the pivot), the chart at theta + pi carries the same
// contact curves as the chart at theta, with the part's features permuted. Decided on the
// model's exact rationals (the rounded values the C-space is built from), no tolerance.
#pragma once

#include <hipair/model.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hipair::cspace {

/// Where an edge goes under the half turn: (loop, edge) of its image.
struct HalfTurnImage {
  std::size_t loop = 0;
  std::size_t edge = 0;
  friend bool operator==(const HalfTurnImage&, const HalfTurnImage&) = default;
};

/// The half turn about `pivot` of one edge: endpoints and centre q -> 2 pivot - q; the same kind,
/// orientation (a half turn is a rotation) and squared radius.
Edge half_turned(const Edge& edge, const Point& pivot);

/// The permutation of the part's edges (per loop, per edge: its image) when every edge's half
/// turn about the part's pivot is exactly an edge of a loop of the same kind (outer / hole) and
/// the map is a bijection carrying each loop's successive edges to successive edges of one loop
/// (so vertices map with their edges); nullopt otherwise, and for parts that do not rotate
/// (fixed, translation, planar, pin-slot) or turn within angle limits (no half-turn chart).
/// `why` (optional): the first edge without an image, or the reason, for reports and tests.
std::optional<std::vector<std::vector<HalfTurnImage>>> half_turn_symmetry(const Part& part,
                                                                           std::string* why = nullptr);

}  // namespace hipair::cspace
