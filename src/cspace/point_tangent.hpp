#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

#include <gmp.h>
#include <mpfr.h>

namespace hipair::cspace {

// The exact angle pieces' shortcuts (cspace_queries.cpp, angle_pieces: the MPFR pieces at 64 or
// 160 bits of the starts, ends and nudge points that the double filter cannot locate). Both give
// the same numbers as the general route, bit for bit:
//  - a point angle (tau's ends equal, as the 160-bit pieces of a rational point in the chart
//    centred at 0 are): tan(tau / 2) rounded down and rounded up from one mpfr_tan. MPFR rounds
//    correctly, so the value rounded up is the value rounded down when the ternary value says it
//    is exact, and the next number of the same precision above it otherwise (tan_half_bounds);
//  - an angle within [-3, 3] (an exact rational test on theta's ends) needs no reduction by whole
//    turns: its midpoint m has floor((m + pi) / 2 pi) = 0 at any precision of 10 bits or more
//    ((m + pi) / 2 pi lies in [0.022, 0.978] before rounding), and subtracting 0 turns is exact
//    (zero_turns).
// On by default; tests switch it off per thread to compare (CSpacePointTangent.*).
struct PointTangentsTag;
inline bool& point_tangents() { return thread_switch<PointTangentsTag>(); }
// How many shortcuts (a tangent pair from one tangent, a reduction skipped) this thread took (tests).
struct PointTangentShortcutsTag;
inline std::size_t& point_tangent_shortcuts() { return thread_counter<PointTangentShortcutsTag>(); }

// tan(lo / 2) rounded down into `down` and tan(hi / 2) rounded up into `up` (\pre all four of
// one precision; -pi < lo <= hi < pi). A point (lo == hi, switch on): one tangent, the upward one
// the next number above when the ternary value says it is inexact.
inline void tan_half_bounds(mpfr_t down, mpfr_t up, const mpfr_t lo, const mpfr_t hi) {
  mpfr_t half;
  mpfr_init2(half, mpfr_get_prec(lo));
  mpfr_div_2ui(half, lo, 1, MPFR_RNDN);   // exact
  const int ternary = mpfr_tan(down, half, MPFR_RNDD);
  if (point_tangents() && mpfr_equal_p(lo, hi)) {
    ++point_tangent_shortcuts();
    mpfr_set(up, down, MPFR_RNDN);   // exact (the same precision)
    if (ternary != 0) mpfr_nextabove(up);
  } else {
    mpfr_div_2ui(half, hi, 1, MPFR_RNDN);
    mpfr_tan(up, half, MPFR_RNDU);
  }
  mpfr_clear(half);
}

// An angle enclosure [lo, hi] that certainly needs no reduction by whole turns (see above).
inline bool zero_turns(const mpq_t lo, const mpq_t hi) {
  return mpq_cmp_si(lo, -3, 1) >= 0 && mpq_cmp_si(hi, 3, 1) <= 0;
}

}  // namespace hipair::cspace
