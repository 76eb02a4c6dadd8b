#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// first_crossing's per-thread memo of the stretches' filtered angle pieces (cspace_queries.cpp,
// MotionScanner::pieces: their t-ranges filtered_angle_ranges(theta), the certified Taylor
// tangents of angle_filter.hpp, kept as doubles; memo_filtered_angle_ranges). The ranges are a
// pure function of the double interval theta; the same theta
// recurs where two pairs share a rotating part (the escapement's anchor is an axis of both of its
// pairs: the same path polynomial over the same stretches) and where a stretch or a start is
// evaluated again. A direct-mapped table of recent thetas (bit patterns of both ends) and their
// ranges; a hit returns a copy of the same ranges, so every answer is the same. Likewise the
// exact pieces (angle_pieces(theta, bits): MPFR tangents at 64 or 160 bits) of the last few exact
// thetas, compared exactly: the nudge's trials move only the free parts, so a driven part's start
// angle recurs in every trial whose start falls back to the 160-bit pieces. On by default;
// tests switch it off per thread to compare (CSpaceAngleMemo.*).
struct AngleMemoTag;
inline bool& angle_memo() { return thread_switch<AngleMemoTag>(); }
// How many stretches' pieces on this thread came from the memo (tests, profiling).
struct AngleMemoHitsTag;
inline std::size_t& angle_memo_hits() { return thread_counter<AngleMemoHitsTag>(); }

}  // namespace hipair::cspace
