// The Geneva pair's pin / slot 1 wall R contact curve as the tolerance solver takes it (the
// driver's chart held near pi: the pin in slot 1), shared by the solver's tests.
#pragma once

#include "tolerance/solver.hpp"

#include <hipair/model.hpp>

namespace hipair::test {

inline tolerance_detail::CurveSlice geneva_pin_wall_curve(const Model& nominal) {
  tolerance_detail::CurveSlice curve;
  curve.first = FeatureIdentity{0, 0, 0, FeatureKind::arc};   // driver pin
  for (std::size_t e = 0; e < nominal.parts[1].loops[0].edges.size(); ++e)
    if (nominal.parts[1].loops[0].edges[e].label == "slot 1 wall R")
      curve.second = FeatureIdentity{1, 0, e, FeatureKind::segment};
  curve.fixed_part = 0;
  curve.free_part = 1;
  curve.fixed_half_turn = true;   // the driver near pi: the pin in slot 1
  curve.free_half_turn = false;
  return curve;
}

}  // namespace hipair::test
