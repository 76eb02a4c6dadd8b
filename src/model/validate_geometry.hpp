// Exact geometric validation of a part's loops, and their orientation (material on the left).
#pragma once

#include <hipair/model.hpp>

namespace hipair::model_detail {

/// Checks every loop of `part` exactly and orients it:
/// - each loop is non-empty, consecutive edges join exactly, the last edge ends at the first
///   edge's start ("open loop");
/// - segments have positive length; arcs have a positive radius and both ends exactly on their
///   circle (|source - center|^2 == |target - center|^2 == radius_squared); a full circle is a
///   loop of its own;
/// - no loop touches or crosses itself, no two loops of the part touch or cross, and no vertex
///   is a cusp (the boundary turning back on itself) — decided exactly for segment/segment,
///   segment/arc and arc/arc pairs;
/// - finally each loop is oriented so the material lies on its left: a loop nested in an odd
///   number of the part's other loops is a hole (clockwise), the others counter-clockwise.
/// Edges keep their pointers; a reversed loop has its edges reversed in order and direction.
/// \throws ModelError naming the pointer of the offending edge or loop.
void validate_part_geometry(Part& part);

}  // namespace hipair::model_detail
