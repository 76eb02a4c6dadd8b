// The scan of a held contact's watched coordinate along the step's path (simulation.cpp,
// Simulation::Impl::edge_watch_end; docs/simulation.md, "Session 43 (esc43)").
//
// The watched coordinate is q(u) = c0 + c1 u + ... + c5 u^5 (Horner in doubles, `poly`), the
// edge's extent (with its slack) is [A, B], and slope >= sum i |c_i| bounds |q'| on [0, 1]. From
// u = 0 the scan steps u += (d + tol) / slope with d = min(q(u) - A, B - q(u)): it returns the
// first u where d < -tol (outside by more than tol), 1 once u >= 1, or the u it has reached after
// `max_iterations` steps (a graze along an end: the step is only shortened there).
//
// The stall exit (switch simulation::watch_stall_exit(), on by default; counter watch_stalls()):
// every step's increment (d + tol) / slope is >= 0 once d >= -tol has been checked, so u never
// decreases; where the path passes an end by just tol, u creeps up to the root of d = -tol and
// the increment rounds to nothing: u + (d + tol) / slope == u. From there every further
// iteration evaluates the same q(u), the same d (already found >= -tol, so no return) and the
// same u: the scan would spin to max_iterations and return that u. It returns it at once: the
// same double, bit for bit. (The escapement at 1e-3 reached that fixed point after 15 to 33
// iterations in each of its six grazes and spun on for the remaining 99 967 or so: 600 116
// iterations, 16.4 M of the loop's 154 M instructions.) A NaN increment never compares equal,
// so a NaN scan runs as before.
#pragma once

#include "core/thread_switch.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

namespace hipair::simulation {

struct WatchStallExitTag;
inline bool& watch_stall_exit() { return thread_switch<WatchStallExitTag>(); }
struct WatchStallsTag;
inline std::size_t& watch_stalls() { return thread_counter<WatchStallsTag>(); }

inline double watch_poly(const std::array<double, 6>& c, double u) {
  double r = 0;
  for (int i = 5; i >= 0; --i) r = r * u + c[i];
  return r;
}

/// The scan above: the first u in [0, 1) found outside [A, B] by more than tol, 1 if none, or
/// where it stops after max_iterations steps.
inline double watch_scan(const std::array<double, 6>& c, double A, double B, double tol, double slope,
                         int max_iterations = 100000) {
  const bool stall_exit = watch_stall_exit();
  double u = 0;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    double q = watch_poly(c, u);
    double d = std::min(q - A, B - q);
    // (a start already outside is left to violated(), as before)
    if (d < -tol) return u > 0 ? u : 1;
    // cannot be outside by tol before u + (d + tol) / slope: a step of at least tol / slope
    const double before = u;
    u += (d + tol) / slope;
    if (u >= 1) return 1;
    if (stall_exit && u == before) {
      ++watch_stalls();
      return u;
    }
  }
  return u;
}

}  // namespace hipair::simulation
