#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// CSpace::first_crossing's per-space memo of its scanner's derived curve data
// (cspace_queries.cpp: ScanMemo, scan_memo_of): per chart, the interval forms of every local
// curve's first and second partial derivatives and of its validity clauses, the carriers
// (contact edges' certified boxes with their curves) and the chart's double sides, and per vertex
// compare_ordinate's fibre signs (which polynomial decides the vertex's side, and its sign at the
// isolating interval's lower end: two exact signs at the vertex's algebraic x). All are pure
// functions of the immutable space; they were made anew by every first_crossing call (its
// MotionScanner's memos), and converting the integer polynomials to interval ones was about 5 %
// of the simulator's loop on the escapement. Kept per thread and per space (a weak_ptr: a space
// freed and another built at its address is never matched; at most 16 spaces per thread), filled
// on first use; the values are the same ones, so every answer is the same. On by default; tests
// switch it off per thread to compare (CSpaceScanMemo.*).
struct ScanMemoTag;
inline bool& scan_memo() { return thread_switch<ScanMemoTag>(); }
// CSpace::compare_ordinate's memo of what it proved (cspace_queries.cpp: OrdinateBounds, in the
// scan memo, so per thread and per space): every ordinate y it compared exactly bounds the
// vertex's ordinate y_v (y < y_v, y > y_v or y == y_v), and an ordinate at or beyond the
// nearest such bound is decided by a rational comparison instead of the exact sign of the
// fibre at the vertex's algebraic abscissa (≈ 200 k instructions each on the escapement's
// vertical edges). The answers are the same (each bound a proved inequality). On by default;
// tests switch it off per thread to compare (CSpaceOrdinateMemo.*).
struct OrdinateMemoTag;
inline bool& ordinate_memo() { return thread_switch<OrdinateMemoTag>(); }
// How many ordinates on this thread the memo's bounds decided (tests, profiling).
struct OrdinateMemoHitsTag;
inline std::size_t& ordinate_memo_hits() { return thread_counter<OrdinateMemoHitsTag>(); }
// CSpace::compare_ordinate's certified filter (cspace_queries.cpp: enclosed_fibre_sign, its data
// in the scan memo): the sign of the deciding polynomial (the fibre or its y-derivative) at
// (x_v, y) from an outward-rounded double-interval evaluation over a few-ulp enclosure of the
// vertex's algebraic abscissa x_v; only a sign whose enclosure excludes zero is taken, else the
// exact sign at x_v decides as before. The answers are the same. On by default; tests switch it
// off per thread to compare (CSpaceOrdinateEnclosure.*).
struct OrdinateEnclosureTag;
inline bool& ordinate_enclosure() { return thread_switch<OrdinateEnclosureTag>(); }
// How many ordinates on this thread the filter decided (tests, profiling).
struct OrdinateEnclosureDecidedTag;
inline std::size_t& ordinate_enclosure_decided() { return thread_counter<OrdinateEnclosureDecidedTag>(); }

// How many first_crossing calls on this thread took a memo already made for their space (tests).
struct ScanMemoHitsTag;
inline std::size_t& scan_memo_hits() { return thread_counter<ScanMemoHitsTag>(); }

}  // namespace hipair::cspace
