// Session 32's endless-touch guard (simulation.cpp, Simulation::Impl::step; docs/simulation.md,
// "The endless corner touch"): a step that struck nothing at its very start, every event an
// impact without impulse, at the time where the step before ended with such a touch, moves the
// state on along its path to the touch's bracket end instead of asking the same query again.
// Counter touch_guard_moves() (tests: the path is reached), per thread.
#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::simulation {

struct TouchGuardMovesTag;
// How many steps the guard moved on past a repeated grazing touch (tests, profiling).
inline std::size_t& touch_guard_moves() { return thread_counter<TouchGuardMovesTag>(); }

}  // namespace hipair::simulation
