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

// track_derivatives' placement data per edge (cspace_queries.cpp: TrackerData, tracker_data_of,
// in the scan memo, so per thread and per space): the edge's support polynomial in doubles, in
// interval forms and with its premultiplied partial terms, and its extent (the end vertices'
// abscissae refined to 2^-60). All are pure functions of the edge (and of the switch
// partial_terms()); they were made anew at every placement of a tracker (every contact taken up
// by the simulator: ≈ 2 exact refinements of algebraic abscissae each). The exact point of the
// edge at the placement's abscissa is still computed per placement. The answers are the same. On
// by default; tests switch it off per thread to compare (CSpaceTrackerMemo.*).
struct TrackerMemoTag;
inline bool& tracker_memo() { return thread_switch<TrackerMemoTag>(); }
// How many placements on this thread took data already made (tests, profiling).
struct TrackerMemoHitsTag;
inline std::size_t& tracker_memo_hits() { return thread_counter<TrackerMemoHitsTag>(); }

// The exact ordinate of a contact edge at a rational abscissa (cspace_queries.cpp: edge_ordinate,
// EdgeOrdinate, in the scan memo: the last 4 per thread and space): the fibre's root of the
// edge's arc number (edge_y_at) and it refined to 2^-64, as derivatives_of (CSpace::derivatives,
// edge_coordinate_slope) and track_derivatives' exact points compute them. The simulator asks
// them twice at one abscissa: an impact's new contact orients its normal by
// edge_coordinate_slope at the configuration, and its first contact row places a tracker there.
// Pure functions of the edge and x (Real::refine_to is deterministic): the answers are the same.
// On by default; tests switch it off per thread to compare (CSpaceTrackerMemo.*).
struct OrdinateAtMemoTag;
inline bool& ordinate_at_memo() { return thread_switch<OrdinateAtMemoTag>(); }
// How many exact edge ordinates on this thread came from the memo (tests, profiling).
struct OrdinateAtMemoHitsTag;
inline std::size_t& ordinate_at_memo_hits() { return thread_counter<OrdinateAtMemoHitsTag>(); }

// How many first_crossing calls on this thread took a memo already made for their space (tests).
struct ScanMemoHitsTag;
inline std::size_t& scan_memo_hits() { return thread_counter<ScanMemoHitsTag>(); }

}  // namespace hipair::cspace
