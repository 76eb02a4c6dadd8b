#pragma once

#include "core/thread_switch.hpp"
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
struct LocateExactPrefilterTag;
inline bool& locate_exact_prefilter() { return thread_switch<LocateExactPrefilterTag>(); }

// Point location's vertex bounds (builder_locate.cpp, locate_2d; ChartData::vertex_bounds, made
// once when the space is built): before the exact rational comparisons above, a vertex is passed
// over when certified doubles of its algebraic coordinates (x_lo <= x <= x_hi, y <= y_hi,
// outward-rounded from its rational bounds) place it away from the point's double enclosure
// [xi.lo, xi.hi] x [yi.lo, yi.hi]: x_hi < xi.lo or x_lo > xi.hi (then x != the point's x) or
// y_hi < yi.lo (then the vertex lies below the point). Such a vertex contributes nothing to the
// location (the loop's exact comparisons pass over a vertex with another x, and one below the
// point), whatever its bounds are now, so every location is the same; a vertex the doubles
// cannot place goes through the exact comparisons as before. Session 23's Geneva spent 16 M of
// its 212 M instructions in mpq_cmp here (96,646 calls, about 184 per location). On by
// default; tests switch it off per thread to compare (CSpaceLocateVertexBounds.*).
struct LocateVertexBoundsTag;
inline bool& locate_vertex_bounds() { return thread_switch<LocateVertexBoundsTag>(); }

}  // namespace hipair::cspace
