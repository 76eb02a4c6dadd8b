#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::simulation {

// The step's crossing queries side by side with a limit (simulation.cpp, Simulation::Impl::step;
// the query is hipair/crossing_before.hpp's CrossingQuery): the free pairs' queries advance one
// stretch at a time, always the one whose next stretch starts first; once a free pair's motion
// reaches contact space at u in [u_lower, u_upper], the queries stop where their next stretch
// starts past the earliest such u_upper (their crossings after it are discarded by the step),
// and a query stopped at a stretch start a that might still be simultaneous (a's double not
// above the step's final u_upper) is resumed to its end. The step's crossings, rows and ends are
// the same as with every query complete. On by default; tests switch it off per thread to
// compare (SimulationCrossingLimit.*).
struct CrossingLimitsTag;
inline bool& crossing_limits() { return thread_switch<CrossingLimitsTag>(); }
// How many step queries stopped at their limit, and how many of those were resumed (tests).
struct LimitedQueriesTag;
inline std::size_t& limited_queries() { return thread_counter<LimitedQueriesTag>(); }
struct RequeriedLimitsTag;
inline std::size_t& requeried_limits() { return thread_counter<RequeriedLimitsTag>(); }

}  // namespace hipair::simulation
