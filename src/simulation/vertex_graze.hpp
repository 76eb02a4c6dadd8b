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
  unknown,   // not decided here (not at one rational vertex of straight edges): the old rule
  graze,     // the motion passes through the vertex from a free sector into a free sector
  enters     // the motion's direction at the vertex points into a blocked sector
};

// Decided exactly for a grazing crossing (`crossing.grazing`) of a 2-D space whose two axes
// translate (chart coordinates are the offsets, mm), at the one vertex of the crossing's chart
// near the crossing's path piece [u_lower, u_upper] (within the piece's own extent) that has
// rational coordinates and only straight incident edges with rational other ends: the path's
// direction at u_lower (exact, from its rational polynomials) against the sectors between the
// vertex's edges, each sector's cell from the edge bounding it (left_cell / right_cell); the
// direction the motion comes from must lie in a free sector too. A direction along an edge (the
// motion slides on it), a vertex of curved edges, a rotating axis, several or no vertices
// near: unknown.
VertexPass vertex_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path);

}  // namespace hipair::simulation
