#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// CSpace::contact_frame's memo of the feature pairs' body geometries (cspace_queries.cpp): the
// kernels' FeatureGeometry of both features of a feature pair, the model's rationals enclosed
// in double intervals, is a pure function of the (immutable, shared) model; the simulator asks
// for the frames of its held contacts at every right-hand side evaluation (friction), and the
// enclosures were 45 % of those calls. Kept per thread and per space (a weak_ptr: a space freed
// and another built at its address is never matched), filled on first use; the frames are the
// same bit for bit. On by default; tests switch it off per thread to compare
// (CSpaceFrameMemo.*).
struct FrameMemoTag;
inline bool& frame_memo() { return thread_switch<FrameMemoTag>(); }
// How many contact_frame calls took their geometries from the memo on this thread (tests).
struct FrameMemoHitsTag;
inline std::size_t& frame_memo_hits() { return thread_counter<FrameMemoHitsTag>(); }

}  // namespace hipair::cspace
