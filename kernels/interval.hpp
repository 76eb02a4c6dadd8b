// HIPAIR contact kernels — a certified floating-point interval.
//
// Each operation is computed in round-to-nearest and then widened outward by one unit in the
// last place on each side. A round-to-nearest result is within half an ulp of the exact
// value, so the widened interval always contains the exact result of the operation applied
// to any points of the operands. No rounding-mode switches: the compiler cannot break it.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace hipair::kernels {

namespace interval_detail {
// The smallest positive subnormal, 2^-1074, as a compile-time constant. (With -frounding-math,
// std::numeric_limits<double>::denorm_min() is the long double literal __DBL_DENORM_MIN__
// converted at run time through the x87 unit, an underflowing store that cost about 0.1 us per
// call: most of the time of interval products with an exact zero end. Same value.)
inline constexpr double smallest_subnormal = std::bit_cast<double>(std::uint64_t{1});
static_assert(smallest_subnormal > 0.0 && smallest_subnormal / 2 == 0.0);

// The next double above `value` (std::nextafter without the library call).
inline double up(double value) {
  // +inf stays; NaN (an overflowed operation) bounds nothing: the whole line
  if (!(value < std::numeric_limits<double>::infinity())) return value == value ? value : std::numeric_limits<double>::infinity();
  if (value == 0.0) return smallest_subnormal;
  auto bits = std::bit_cast<std::uint64_t>(value);
  bits = value > 0.0 ? bits + 1 : bits - 1;
  return std::bit_cast<double>(bits);
}
inline double down(double value) { return -up(-value); }
}  // namespace interval_detail

/// Closed interval [lo, hi] of doubles that encloses an exact real value.
struct Interval {
  double lo = 0.0;
  double hi = 0.0;

  Interval() = default;
  /// Exact point interval of an integer (|value| <= 2^53 is exact in double).
  Interval(int value) : lo(value), hi(value) {}  // NOLINT(google-explicit-constructor)
  Interval(double low, double high) : lo(low), hi(high) {}

  /// Point enclosure of an exact double.
  static Interval point(double value) { return Interval(value, value); }

  /// Enclosure of an exact rational.
  static Interval enclose(const mpq_class& value) {
    // mpq_get_d truncates toward zero: the exact value lies between it and the next double
    // away from zero.
    double truncated = value.get_d();
    int sign = sgn(value);
    if (sign == 0) return Interval(0.0, 0.0);
    // beyond the doubles' range get_d gives an infinity: the value lies beyond the largest double
    if (std::isinf(truncated))
      return sign > 0 ? Interval(std::numeric_limits<double>::max(), truncated)
                      : Interval(truncated, std::numeric_limits<double>::lowest());
    double away = sign > 0 ? interval_detail::up(truncated) : interval_detail::down(truncated);
    return sign > 0 ? Interval(truncated, away) : Interval(away, truncated);
  }

  bool contains(double value) const { return lo <= value && value <= hi; }
  /// True when the exact rational `value` lies in the interval.
  bool contains(const mpq_class& value) const {
    return !(mpq_class(lo) > value) && !(mpq_class(hi) < value);
  }
  double width() const { return hi - lo; }
  double middle() const { return 0.5 * (lo + hi); }
  /// -1, 0, +1 when certain, 2 when the interval contains 0 but is not {0}.
  int sign() const {
    if (lo > 0.0) return 1;
    if (hi < 0.0) return -1;
    if (lo == 0.0 && hi == 0.0) return 0;
    return 2;
  }
};



inline Interval operator+(const Interval& a, const Interval& b) {
  return Interval(interval_detail::down(a.lo + b.lo), interval_detail::up(a.hi + b.hi));
}

inline Interval operator-(const Interval& a, const Interval& b) {
  return Interval(interval_detail::down(a.lo - b.hi), interval_detail::up(a.hi - b.lo));
}

inline Interval operator-(const Interval& a) { return Interval(-a.hi, -a.lo); }

inline Interval operator*(const Interval& a, const Interval& b) {
  // an end product 0 * inf is 0 (a bound 0 times an unbounded end: the hull of the products of
  // the reals in the two intervals, IEEE 1788), not a NaN that std::min/max would drop unevenly
  auto end = [](double u, double v) {
    double p = u * v;
    return p == p ? p : 0.0;
  };
  double p1 = end(a.lo, b.lo);
  double p2 = end(a.lo, b.hi);
  double p3 = end(a.hi, b.lo);
  double p4 = end(a.hi, b.hi);
  double low = std::min(std::min(p1, p2), std::min(p3, p4));
  double high = std::max(std::max(p1, p2), std::max(p3, p4));
  return Interval(interval_detail::down(low), interval_detail::up(high));
}

/// Quotient; `b` must not contain 0 (the result is then the whole line, returned as
/// [-inf, inf]).
inline Interval operator/(const Interval& a, const Interval& b) {
  if (b.lo <= 0.0 && b.hi >= 0.0)
    return Interval(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  double q1 = a.lo / b.lo;
  double q2 = a.lo / b.hi;
  double q3 = a.hi / b.lo;
  double q4 = a.hi / b.hi;
  if (q1 != q1 || q2 != q2 || q3 != q3 || q4 != q4)   // inf / inf: no bound from these ends
    return Interval(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  double low = std::min(std::min(q1, q2), std::min(q3, q4));
  double high = std::max(std::max(q1, q2), std::max(q3, q4));
  return Interval(interval_detail::down(low), interval_detail::up(high));
}

/// Enclosure of the square root of the non-negative part of `a`.
inline Interval sqrt(const Interval& a) {
  double low = a.lo <= 0.0 ? 0.0 : interval_detail::down(std::sqrt(a.lo));
  double high = a.hi <= 0.0 ? 0.0 : interval_detail::up(std::sqrt(a.hi));
  return Interval(std::max(0.0, low), high);
}

/// Union hull.
inline Interval hull(const Interval& a, const Interval& b) {
  return Interval(std::min(a.lo, b.lo), std::max(a.hi, b.hi));
}

}  // namespace hipair::kernels
