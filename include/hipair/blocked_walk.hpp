// HIPAIR — a certified walk of configurations through one blocked cell of a 2-D C-space, for
// the simulator's nudges off contact (src/simulation: a configuration computed in doubles on a
// contact curve is moved by a growing step along a fixed direction until the pair's exact point
// query says free; most trials are still inside the blocked cell it started in).
//
// certainly_blocked answers `true` only where it has proved that the configuration lies inside
// a blocked cell: then CSpace::first_crossing of any motion starting there reports
// starts_in_contact, so the caller may skip that query. `false` says nothing (ask the query).
// The proof (docs/performance.md, session 25 (sim25)): both axes rotate; the configuration's
// chart coordinates are enclosed in a double box B by the certified angle filter
// (cspace/angle_filter.hpp), strictly inside one chart. The walk keeps the box B' of the last
// configuration it certified, in a blocked cell. Every point where two cells meet or the parts
// touch (a real edge, an edge between different cells, a vertex of one, an isolated vertex) lies
// on a contact curve carried by such an edge, inside that edge's certified bounding box (or, for
// an isolated vertex, on one of its curves). If the hull H of B' and B (a box: connected) lies
// strictly inside the chart and none of those curves whose edge's box meets H vanishes on H
// (outward-rounded interval evaluation; the isolated vertices' curves always), H holds no such
// point, so it lies inside one cell: B' 's, which is blocked. The walk's first box is placed by
// the exact location of its rational midpoint, after the same test on B alone. A walk ends at
// the first configuration it cannot certify (the caller's trials have left the cell or come near
// its boundary): from then on it answers `false`.
#pragma once

#include <hipair/cspace.hpp>

#include <array>
#include <cstddef>

namespace hipair {

/// The last configuration a walk certified inside a blocked cell (its chart and double box).
/// Default-constructed: not placed; it places itself at the first call (one per walk: a new
/// walk for each sequence of trials).
class BlockedWalk {
 public:
  BlockedWalk() = default;

 private:
  friend bool certainly_blocked(const CSpace&, const MotionPath&, BlockedWalk&);
  const void* space_ = nullptr;   // not placed yet
  bool spent_ = false;            // ended: answers false
  std::size_t chart_ = 0;
  std::array<double, 4> side_{};   // the chart's sides {x_lo, x_hi, y_lo, y_hi}, rounded inward
  std::array<double, 4> box_{};    // the last configuration's box {x_lo, x_hi, y_lo, y_hi}
  // per axis, the last exact angle and its chart range (a pure function of it): a nudge moves
  // only the free parts, so a driven part's angle recurs in every trial
  struct Axis {
    bool set = false, half_turn = false;
    Rational theta;
    double lo = 0, hi = 0;
  };
  std::array<Axis, 2> axes_;
};

/// True: certified that the configuration of `point` at u = point.u_begin lies inside a blocked
/// cell of the 2-D space (first_crossing from there reports starts_in_contact). False: unknown
/// (a 1-D space, an operating region rather than the whole space, an axis that does not rotate,
/// a box near a contact curve or a chart side, a free cell; any configuration after the walk's
/// first `false`). Moves `walk` to the
/// configuration when true, ends it otherwise.
bool certainly_blocked(const CSpace& space, const MotionPath& point, BlockedWalk& walk);

}  // namespace hipair
