// A grazing crossing through a C-space vertex: does the motion enter blocked space there, or only
// pass through the vertex from free space to free space (docs/simulation.md, "Session 41
// (graze41)")? Two translating squares whose corners pass exactly through each other move along
// a line through the vertex where the two corner curves meet, outside the blocked quadrant on
// both sides; the crossing query reports that within its resolution as a grazing touch of one of
// the vertex's edges, and striking that edge is a velocity change physics does not make.
#pragma once

#include <hipair/cspace.hpp>

namespace hipair::simulation {

enum class VertexPass {
  unknown,   // not decided here: the old rule
  graze,     // the motion passes through the vertex from a free sector into a free sector
  enters,    // the motion's direction at the vertex points into a blocked sector
  slides     // 1-D (line_pass): the motion enters a touching cell (flush at zero clearance)
};

// Decided for a grazing crossing (`crossing.grazing`) of a 2-D space, at the one vertex of the
// crossing's chart near the crossing, by the path's direction against the sectors between the
// vertex's edges, each sector's cell from the edge bounding it (left_cell / right_cell); the
// direction the motion comes from must lie in a free sector too.
// - Session 41, exact rationals: two translating axes, a rational vertex with straight edges,
//   near the path's piece [u_lower, u_upper] (within the piece's own extent).
// - Session 42, where that answers unknown (any axes: a rotating axis, curved edges, an
//   algebraic vertex): the vertex alone within twice the extent of the query's chart box
//   (crossing.chart_point); the edges' tangents (F_y, -F_x) and the path's chart velocity over
//   the bracket ordered by certified signs of rational interval enclosures of the vertex,
//   refined by exact bisection (its polynomial; CSpace::compare_ordinate).
// A direction along an edge (the motion slides on it), tangent edges, a vertical tangent, a
// vertex on a chart boundary, several or no vertices near: unknown (the old rule).
VertexPass vertex_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path);

// Session 75 (graze75): a crossing of a 1-D space (grazing or not), at the one vertex near the
// query's chart point, exactly: the path's chart velocity of certified sign there, the cells on
// ahead of the vertex by exact point location at a rational point with no other vertex between
// (the motion comes from the query's free starting cell). Ahead blocked: `enters` (an impact);
// free: `graze`; a touching cell (the parts touch along the motion, no normal along it): `slides`;
// else (outside the chart, undecided) unknown.
VertexPass line_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path);

}  // namespace hipair::simulation
