// The pin-slot stack's witness filter (src/pinslot/pin_slot_space.cpp; in the sliced layer for its certified intervals): a certified test that
// a turning part's boundary stays apart from a fixed part's boundary over a range of tau.
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

namespace hipair::pinslot {

// Is the boundary of `turning` (shifted by `shift`, then turned about `pivot` by psi with
// tan(psi/2) = tau) certainly apart from the boundary of `fixed` for every tau in [a, b]?
// Certified double intervals: each turning edge over [a, b] lies in the hull of its ends'
// enclosures (at each tau the edge is the segment between its ends); a fixed edge certainly
// misses that box when their boxes are certainly disjoint or the box's four corners are
// certainly strictly on one side of the edge's line, or the fixed edge's ends certainly strictly
// on one side of the turning edge's line (its ends in their enclosures). Undecided pairs bisect [a, b] (depth 4),
// then the answer is false (the caller takes the exact path). Segments only (arcs: false).
bool boundaries_certainly_apart(const Part& fixed, const Part& turning, const Point& pivot, const Point& shift,
                                const Rational& a, const Rational& b);

}  // namespace hipair::pinslot
