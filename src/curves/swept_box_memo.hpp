// HIPAIR — the curve generator's memo of swept boxes per axis interval (private to src/curves;
// core/thread_switch.hpp).
#pragma once

#include "core/thread_switch.hpp"

namespace hipair::cspace {

/// The broad phase's swept boxes of a moving rotating part remembered per axis interval by the
/// curve generator (CurveGenerator::Data::swept_memo): on by default; off on this thread, every
/// chart box computes its boxes again (tests compare the curves: the same).
struct SweptBoxMemoTag {};
inline bool& swept_box_memo_switch() { return thread_switch<SweptBoxMemoTag>(); }
/// Boxes of one part taken from the memo on this thread (tests, profiling).
inline std::size_t& swept_box_memo_hits() { return thread_counter<SweptBoxMemoTag>(); }

}  // namespace hipair::cspace
