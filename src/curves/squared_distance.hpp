// The blocked-space culler's core-pair test (contact_curves.cpp BlockedSpaceCuller): the
// squared distance of two posed disk centres against the squared sum of their radii, decided
// as the plain interval expression decides it, with less work. Internal to src/curves/.
#pragma once

#include "kernels/interval.hpp"

#include <algorithm>
#include <cmath>

namespace hipair::cspace::cull_detail {

using kernels::Interval;

namespace square_detail {
using kernels::interval_detail::down;
using kernels::interval_detail::up;
// The round-to-nearest end products of [lo, hi] * [lo, hi] that operator* keeps as its lower
// and upper end (lo <= hi, both finite). Rounding to nearest is monotone, so the order of the
// exact products (lo >= 0: lo lo <= lo hi <= hi hi; hi <= 0: the reverse; otherwise lo hi < 0 <=
// both squares) is the order of the rounded ones: the same values as operator*'s min and max of
// its four end products (a zero's sign aside, which up/down do not see).
inline void square_ends(double lo, double hi, double& low, double& high) {
  if (lo >= 0.0) {
    low = lo * lo;
    high = hi * hi;
  } else if (hi <= 0.0) {
    low = hi * hi;
    high = lo * lo;
  } else {
    low = lo * hi;
    high = std::max(lo * lo, hi * hi);
  }
}
// (a - b) * (a - b), bit for bit: the same ends, with a finite proper difference's square by
// its three end products
inline Interval squared_difference(const Interval& a, const Interval& b) {
  Interval d = a - b;
  if (!(std::isfinite(d.lo) && std::isfinite(d.hi) && d.lo <= d.hi)) return d * d;
  double low, high;
  square_ends(d.lo, d.hi, low, high);
  return Interval(down(low), up(high));
}
}  // namespace square_detail

/// Where the squared distance of two boxes' points lies against a squared reach `r2`, as the
/// interval expression D = (ax - bx) * (ax - bx) + (ay - by) * (ay - by) decides it:
/// -1 when D.hi < r2.lo (closer than the reach everywhere), 0 when not and D.lo < r2.hi
/// (possibly closer somewhere), +1 otherwise (never closer). The same answer as from D computed
/// with operator-, operator* and operator+, with less work. First on the differences before
/// their outward rounding (xl = ax.lo - bx.hi, ..., rounded to nearest), when every end is at
/// most 2^500 in magnitude (no square or sum overflows, nor does any outward rounding) and
/// the boxes are proper (lo <= hi, as every posed centre is):
/// - D.hi is at least S_hi, the rounded sum of their squares' upper ends, and D.lo at most
///   S_lo, that of the lower ends: the outward-rounded differences contain the rounded ones,
///   an interval square's ends are monotone under inclusion, and every rounding is monotone.
///   So S_hi >= r2.lo and S_lo < r2.hi answer 0.
/// - Where every end is at least 2^-500 in magnitude (its outward rounding, one unit in the
///   last place, keeps its sign, so each square's ends are the same end products of the
///   outward ends as S's of the rounded ones, and every product and end is a normal number),
///   each outward square's lower end, rounded down, is within 2^-48 |x_low| of x_low (the
///   rounded differences' square's lower end; likewise y), and the sum's two roundings add
///   2^-53 and 2^-52 of it and at most 2^-1073 where it is subnormal: D.lo >= S_lo - 2^-46.9 M
///   - 2^-1072, M = |x_low| + |y_low|. So S_hi >= r2.lo and S_lo - (2^-45 M + 2^-1000) >= r2.hi
///   (that rounded, which the margin's excess covers) answer +1.
/// Otherwise the full expression, a finite difference's square by its three end products
/// (square_detail::squared_difference).
inline int squared_distance_relation(const Interval& ax, const Interval& ay, const Interval& bx, const Interval& by,
                                     const Interval& r2) {
  constexpr double moderate = 0x1p500;   // squares and sums of these stay finite
  constexpr double normal = 0x1p-500;    // squares and sums of these stay normal
  double xl = ax.lo - bx.hi, xh = ax.hi - bx.lo, yl = ay.lo - by.hi, yh = ay.hi - by.lo;
  if (std::fabs(xl) <= moderate && std::fabs(xh) <= moderate && std::fabs(yl) <= moderate && std::fabs(yh) <= moderate &&
      xl <= xh && yl <= yh) {
    double x_low, x_high, y_low, y_high;
    square_detail::square_ends(xl, xh, x_low, x_high);
    square_detail::square_ends(yl, yh, y_low, y_high);
    if (x_high + y_high >= r2.lo) {
      double sum_low = x_low + y_low;
      if (sum_low < r2.hi) return 0;
      if (std::fabs(xl) >= normal && std::fabs(xh) >= normal && std::fabs(yl) >= normal && std::fabs(yh) >= normal &&
          sum_low - ((std::fabs(x_low) + std::fabs(y_low)) * 0x1p-45 + 0x1p-1000) >= r2.hi)
        return 1;
    }
  }
  Interval d = square_detail::squared_difference(ax, bx) + square_detail::squared_difference(ay, by);
  if (d.hi < r2.lo) return -1;
  return d.lo < r2.hi ? 0 : 1;
}

}  // namespace hipair::cspace::cull_detail
