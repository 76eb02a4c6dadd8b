#pragma once

// A step's per-axis quintic (doubles, simulation.cpp's StepPath) as the C-space's AxisPath, written
// into a path kept between steps (Simulation::Impl's per-pair motions): the coefficients' limbs are
// reused, so a step's crossing queries cost no rational allocation for their paths. Everything
// written is all a fresh path holds: the kind, the coefficients up to the last nonzero one (trailing
// zeros dropped), nothing left from a longer path before.

#include <hipair/cspace.hpp>

#include <array>
#include <cstddef>

namespace hipair::simulation {

inline void assign_axis_path(AxisPath& out, const std::array<double, 6>& c, bool rotation) {
  out.kind = rotation ? AxisPath::Kind::angle : AxisPath::Kind::offset;
  std::size_t count = 6;
  while (count > 1 && c[count - 1] == 0) --count;
  out.coefficients.resize(count);
  for (std::size_t i = 0; i < count; ++i) out.coefficients[i] = c[i];
}

// no part on that axis: what AxisPath{} holds
inline void clear_axis_path(AxisPath& out) {
  out.kind = AxisPath{}.kind;
  out.coefficients.clear();
}

}  // namespace hipair::simulation
