// A part with every point of its boundary moved by a rigid placement (radii and orientation kept),
// shared by the pin-slot C-space and its cycle analysis.
#pragma once

#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

namespace hipair::pinslot_detail {

inline Part moved_part(const Part& part, const Placement& placement) {
  Part out = part;
  for (auto& loop : out.loops)
    for (auto& e : loop.edges) {
      e.source = placement.apply(e.source);
      e.target = placement.apply(e.target);
      if (e.is_arc()) e.center = placement.apply(e.center);
    }
  return out;
}

}  // namespace hipair::pinslot_detail
