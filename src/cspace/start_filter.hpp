#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// first_crossing's filtered start (cspace_queries.cpp, CSpace::first_crossing and
// MotionScanner::evaluate's `filtered_point`): a start on a rotating axis is first enclosed by
// the certified double-interval pieces of the path's angle (the stretches' filter, each piece
// widened by one double either way so that it holds the 160-bit pieces' double box), not by
// the 160-bit MPFR pieces. Where those boxes are covered by the charts, no contact curve may
// vanish on them and the exact location of the front box's midpoint is inside a face (of a
// free cell, or of a blocked one: the simulator's nudge asks about many blocked points), the
// start is located there: the box holds the start and meets no cell boundary, so the cell is
// the 160-bit box's. Anything else (a start near a curve, near the built region's border, a
// midpoint on an edge) falls back to the 160-bit evaluation and its answer, unchanged. On by
// default; tests switch it off per thread to compare (CSpaceStartFilter.*).
struct StartFilterTag;
inline bool& start_filter() { return thread_switch<StartFilterTag>(); }
// How many starts the filter located on this thread (tests).
struct FilteredStartsTag;
inline std::size_t& filtered_starts() { return thread_counter<FilteredStartsTag>(); }

// The crossing's filtered ends (cspace_queries.cpp, CrossingRun::stretch): once a stretch within
// the resolution may touch contact space, the query moves an end forward until it is certainly
// outside the start cell, locating each end from its 160-bit pieces. With the filter, an end on a
// rotating axis is first enclosed as the filtered start is (the stretches' double pieces widened
// by one double: they hold the 160-bit pieces' box); where those boxes are covered, meet no
// contact curve and their front midpoint lies in a free or a blocked cell's face, that location
// is the end's (the box holds the end and meets no cell boundary, so the cell and its kind are
// the 160-bit box's, and the 160-bit evaluation would also find no curve: its boxes lie inside,
// and the interval enclosures are inclusion-monotone). Anything else falls back to the 160-bit
// end, unchanged. On by default; tests switch it off per thread to compare
// (CSpaceCrossingEndFilter.*).
struct EndFilterTag;
inline bool& end_filter() { return thread_switch<EndFilterTag>(); }
// How many ends the filter located on this thread (tests).
struct FilteredEndsTag;
inline std::size_t& filtered_ends() { return thread_counter<FilteredEndsTag>(); }

// certainly_blocked's walks (hipair/blocked_walk.hpp, cspace_queries.cpp): the simulator's
// nudge trials inside the blocked cell they start in, certified by a chain of boxes on which no
// contact curve vanishes instead of a point query each. On by default; tests switch it off per
// thread to compare (CSpaceBlockedWalk.*, the simulation's outputs).
struct BlockedWalksTag;
inline bool& blocked_walks() { return thread_switch<BlockedWalksTag>(); }
// How many configurations a walk certified from its last box (without a location) on this thread.
struct BlockedWalkStepsTag;
inline std::size_t& blocked_walk_steps() { return thread_counter<BlockedWalkStepsTag>(); }

}  // namespace hipair::cspace
