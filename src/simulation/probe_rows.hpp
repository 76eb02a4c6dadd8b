// The cut search's probes hand their held rows to their accelerations (simulation.cpp, step()'s
// `violated` and Simulation::Impl::accelerations' `rows`; session 75, speed75). A probe makes
// every held contact's row at the probed state (for the rooms it reports) and then asks the
// accelerations at the same state, which made the same rows again. Since track_derivatives
// answers the same bits at a state whatever its tracker's history (src/cspace/cspace_queries.cpp,
// slopes_from's step 3b), the rows made twice are equal and the second making is skipped: the
// same doubles. Before session 75 they were not (24 of 328 second rows differed in the
// escapement: docs/performance.md, "Session 74 (speed74)").
//
// Switch simulation::probe_rows() (on by default): off, the accelerations make the rows again;
// tests turn it off on their thread to compare runs bit for bit (SimulationProbeRows.*).
#pragma once

#include "core/thread_switch.hpp"

namespace hipair::simulation {

struct ProbeRowsTag;
inline bool& probe_rows() { return thread_switch<ProbeRowsTag>(); }

}  // namespace hipair::simulation
