#pragma once

namespace hipair::cspace {

// Point location's vertex prefilter (builder_locate.cpp, locate_2d): a vertex is passed over
// when its certified rational bounds place it away from the point (x's isolating interval
// entirely left or right of the point's rational x, or the ordinate's bound y_upper below the
// point's y), by exact rational comparisons. Until session 22 the same test converted the
// three bounds to doubles at every location (upper_double / lower_double: mpq_get_d and an
// exact check, 11 % of the simulator's run_until on the escapement) and compared them with the
// point's double enclosure. Every vertex the double test passes over, the exact one passes over
// too, and a vertex only the exact one passes over has x != the point's x or lies below it: one
// the loop's exact comparisons pass over as well. So every location is the same. On by default;
// tests switch it off per thread to compare (CSpaceLocateFilterVertices.*).
inline bool& locate_exact_prefilter() {
  thread_local bool on = true;
  return on;
}

}  // namespace hipair::cspace
