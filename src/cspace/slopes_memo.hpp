#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// track_derivatives' memo of its last slopes (cspace_queries.cpp, slopes_from's step 4: the
// partials on {x} x Y1, the implicit and the part slopes). Step 4 is a pure function of the
// tracker's edge data, the abscissa x and the certified root bracket Y1 (double intervals); the
// tracker keeps its last (x, Y1) by their bit patterns and the answer, and a call that reaches
// step 4 with the same ones returns that answer (cleared when the tracker is placed on another
// edge). The simulator asks twice at every state of its contact bisection (the watch of each
// held contact's row, then the accelerations' rows at the same state): the second call's Newton
// and bracket mostly land on the same Y1 (its steps 1-3, the bracket and the certificate, still
// run), and the memo answers. Not always: in the escapement's 0.5 s at 1e-3, 24 of 328 second
// calls of the cut search's probes gave a row differing from the first call's (23 in h, 1 in G;
// session 74, docs/performance.md "Session 74 (speed74)"), so the two calls cannot be merged
// without changing outputs. The memo's answers are the same as without it either way (a pure
// function of the bit patterns). On by default; tests switch it off per thread to compare
// (CSpaceSlopesMemo.*).
struct SlopesMemoTag;
inline bool& slopes_memo() { return thread_switch<SlopesMemoTag>(); }
// How many track_derivatives answers on this thread came from the memo (tests, profiling).
struct SlopesMemoHitsTag;
inline std::size_t& slopes_memo_hits() { return thread_counter<SlopesMemoHitsTag>(); }

}  // namespace hipair::cspace
