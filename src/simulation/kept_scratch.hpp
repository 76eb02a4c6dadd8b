// The working storage of the simulator's right-hand side, kept between its calls
// (simulation.cpp, Simulation::Impl::accelerations and friction_of; docs/simulation.md,
// "Session 51"): accelerations runs at every Runge-Kutta stage and every probe of a cut search,
// thousands of times a run, and each call built its constraint matrix, Coulomb rows, inverse
// masses and the bilateral solve's matrices (simulation/friction.hpp, BilateralWork) afresh.
// Kept, each is resized to the call's sizes and written before it is read, by the same
// operations in the same order: the same doubles, without the allocations.
//
// Switch simulation::kept_scratch() (on by default): off, every call takes fresh storage, as
// before; tests turn it off on their thread to compare runs bit for bit (SimulationKeptScratch.*).
#pragma once

#include "core/thread_switch.hpp"

namespace hipair::simulation {

struct KeptScratchTag;
inline bool& kept_scratch() { return thread_switch<KeptScratchTag>(); }

}  // namespace hipair::simulation
