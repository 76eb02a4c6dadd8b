#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// track_derivatives' memo of its last slopes (cspace_queries.cpp, slopes_from's step 4: the
// partials on {x} x C, the implicit and the part slopes, C the canonical cell of the edge's root
// at x). Since session 75 (speed75) track_derivatives' answer is a function of the edge and the
// abscissa x alone (slopes_from's step 3b: the root's grid cell, whatever bracket the tracker's
// history found; before, the bracket Y1 came from a Newton start at the tracker's last point and
// 24 of 328 second calls of the escapement's cut-search probes gave a row differing from the
// first: docs/performance.md, "Session 74 (speed74)" and "Session 75 (speed75)"). The tracker
// keeps its last (x, C) by their bit patterns and the answer: a call at the same x on the same
// placement returns it without steps 1-3 (track_derivatives), and a call that reaches step 4
// with the same x and C takes it there (cleared when the tracker is placed on another edge).
// The memo's answers are the same as without it (a pure function of the bit patterns). On by
// default; tests switch it off per thread to compare (CSpaceSlopesMemo.*).
struct SlopesMemoTag;
inline bool& slopes_memo() { return thread_switch<SlopesMemoTag>(); }
// How many track_derivatives answers on this thread came from the memo (tests, profiling).
struct SlopesMemoHitsTag;
inline std::size_t& slopes_memo_hits() { return thread_counter<SlopesMemoHitsTag>(); }

}  // namespace hipair::cspace
