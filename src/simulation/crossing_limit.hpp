#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::simulation {

// The step's crossing queries with a limit (simulation.cpp, Simulation::Impl::step; the query is
// hipair/crossing_before.hpp): once a free pair's motion reaches contact space at u in
// [u_lower, u_upper], the later pairs' queries stop where their subdivision passes the earliest
// such u_upper (their crossings after it are discarded by the step), and a pair stopped at a
// stretch start a that might still be simultaneous (a's double not above the step's final
// u_upper) is asked again without the limit. The step's crossings, rows and ends are the same.
// On by default; tests switch it off per thread to compare (SimulationCrossingLimit.*).
struct CrossingLimitsTag;
inline bool& crossing_limits() { return thread_switch<CrossingLimitsTag>(); }
// How many step queries stopped at their limit, and how many of those were asked again (tests).
struct LimitedQueriesTag;
inline std::size_t& limited_queries() { return thread_counter<LimitedQueriesTag>(); }
struct RequeriedLimitsTag;
inline std::size_t& requeried_limits() { return thread_counter<RequeriedLimitsTag>(); }

}  // namespace hipair::simulation
