// An interval product with operator*'s bounds, dispatched on the second factor's sign: the two
// end products of interval_detail::times_nonnegative / times_nonpositive when that sign is known
// (they give operator*'s bounds there), the four of operator* otherwise. For Horner's schemes at
// a point or over a box that mostly keeps one sign (the kernel slicer's enclosures, the exact
// reals' sign filter).
#pragma once

#include "algebra/exact_real.hpp"

namespace hipair::cspace::algebra::interval_detail {

inline Interval times(Interval a, Interval b) {
  if (b.lo >= 0) return times_nonnegative(a, b);
  if (b.hi <= 0) return times_nonpositive(a, b);
  return a * b;
}

}  // namespace hipair::cspace::algebra::interval_detail
