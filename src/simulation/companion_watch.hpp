// Feature pairs certified apart relative to a held contact (src/simulation/planar.cpp,
// PlanarSimulation::Impl::companion_apart; docs/simulation.md, "Turning on a vertex"). While a
// planar part turns on a held vertex–segment contact, another vertex on the same segment's line
// (the second top vertex of a bump 1e-8 mm wide under the part's face) lies within the chord
// deviation of it: the far test never passed and every step was a chord of deviation delta / 2
// (about 15 000 of them for 6 ms of turning). That vertex's gap is the held one's plus
// n . (V_f - V_c), a function of the angle only, bounded exactly over the step's angles: where
// the sum stays positive the pair is left out of the far test, as the held pair is.
//
// Switch simulation::companion_watch() (on by default): off, such pairs count in the far test as
// before; tests turn it off on their thread to compare runs (SimulationPlanarNeedle.*). Counter
// simulation::companion_steps(): the pairs so certified on this thread.
#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::simulation {

struct CompanionWatchTag;
inline bool& companion_watch() { return thread_switch<CompanionWatchTag>(); }
inline std::size_t& companion_steps() { return thread_counter<CompanionWatchTag>(); }

}  // namespace hipair::simulation
