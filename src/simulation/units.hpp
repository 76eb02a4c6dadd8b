// HIPAIR — the simulator's one conversion of the model's units (docs/simulation.md, "Model data
// and units"): internal time in s, force in kg·mm/s² = mN.
#pragma once

#include <hipair/model.hpp>

namespace hipair::simulation {

/// Seconds per time unit of the model ("s" or "ms").
inline double seconds_per(const SimulationSpec& spec) { return spec.time_unit == "ms" ? 1e-3 : 1.0; }
/// mN (kg·mm/s²) per force unit of the model ("N" or "mN").
inline double millinewtons_per(const SimulationSpec& spec) { return spec.force_unit == "mN" ? 1.0 : 1000.0; }

}  // namespace hipair::simulation
