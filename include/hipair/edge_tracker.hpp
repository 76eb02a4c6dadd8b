// HIPAIR — filtered derivatives of a contact edge along a motion, for the right-hand side of a
// numerical integration (the simulator's contact rows): many evaluations per step along one
// edge, each at a double abscissa near the last one.
//
// CSpace::derivatives evaluates y, y', y'' exactly (the edge's ordinate as an algebraic
// number, rational interval arithmetic): certified, and far too slow for every Runge–Kutta
// stage. track_derivatives evaluates the same quantities in outward-rounded double intervals.
// It is certified too: the ordinate is located on the edge's own branch of its curve by an
// a-priori argument from the last certified point of the edge (docs/simulation.md, "Filtered
// contact rows"), not by a guess. Where it cannot certify (an abscissa at or beyond the edge's
// ends, F_y not bounded away from 0, a branch it cannot follow in a small box), it returns
// nullopt and the caller takes the exact CSpace::derivatives.
#pragma once

#include <hipair/cspace.hpp>

#include <cstdint>
#include <memory>
#include <optional>

namespace hipair {

/// Certified enclosures of a contact edge's ordinate and slopes at one abscissa (chart and part
/// coordinates, as in EdgeDerivatives; the ordinate as an interval of doubles).
struct EdgeSlopes {
  CertifiedRange y;
  CertifiedRange dy, d2y;
  CertifiedRange coordinate_dy, coordinate_d2y;
};

/// The last certified point of an edge, carried between calls of track_derivatives (one per
/// contact being followed). Default-constructed: on no edge; it places itself (one exact
/// evaluation) at the first call and after a change of space or edge.
class EdgeTracker {
 public:
  EdgeTracker() = default;

 private:
  friend std::optional<EdgeSlopes> track_derivatives(const CSpace&, EdgeId, double, EdgeTracker&);
  const void* space_ = nullptr;
  EdgeId edge_;
  double x_ = 0;
  CertifiedRange y_;
  std::shared_ptr<const void> data_;
  // the last slopes computed from a certified root bracket (x, [y_lo, y_hi]) of this placement
  // (bit patterns; a pure function of them): the simulator asks twice at each state
  struct Memo {
    bool set = false;
    std::uint64_t x = 0, y_lo = 0, y_hi = 0;
    std::optional<EdgeSlopes> slopes;
  } memo_;
};

/// y, y', y'' of the non-vertical edge `edge` at the double abscissa `x` (chart coordinates),
/// certified enclosures in doubles; moves `tracker` to x. nullopt when the filter cannot
/// certify them (then use CSpace::derivatives at the rational x, which decides exactly and
/// throws where the derivatives do not exist).
std::optional<EdgeSlopes> track_derivatives(const CSpace& space, EdgeId edge, double x, EdgeTracker& tracker);

}  // namespace hipair
