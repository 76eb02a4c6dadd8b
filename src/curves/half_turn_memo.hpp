// HIPAIR — a feature pair's exact contact quantities carried from one half-turn chart to the
// other by reflection instead of formed again (private to src/curves; core/thread_switch.hpp).
//
// A rotating part's pose in the chart centred at 0 has (c, s, w) = (1 - t^2, 2t, 1 + t^2), in the
// chart centred at pi (-c, -s, w) (kernels/pose.hpp). Every kernel quantity (contact function,
// validity atom, corner-entry atom) is a polynomial H in the two parts' triples; when H is
// homogeneous of degree k in the triple of the chart's x (every term has k factors among c, s,
// w of x), then (c, s, w)(-1/x) x^2 = (-c, -s, w)(x) gives
//     H in the chart at pi  =  x^(2k) (H in the chart at 0)(-1/x)
// and the same in y: the same polynomial, exactly. Normalisation (normalized_integer_polynomial)
// divides the content and m factors (1 + x^2), which reflect to themselves, so the normalised N
// of one kind reflects with k - m (m = (deg H - deg N) / 2) to the normalised polynomial of the
// other (half_turn_reflected in algebra/polynomial.hpp): the curve's polynomial, validity atoms
// and corner-entry atoms are carried as formed, constants and dropped atoms alike. k is found by
// running the same kernel on TripleDegree, which follows the range of the terms' degrees through
// +, - and *; a zero value (a zero body datum) has no terms, so the range is that of the terms
// that may be non-zero, and a quantity is reflected only when the range is one degree.
// Otherwise (or a degree above 2k) the curve is formed in each chart kind as before.
#pragma once

#include "core/thread_switch.hpp"

#include <algorithm>

namespace hipair::cspace {

/// The range of the terms' degrees of a kernel quantity in the rotation triples of the chart's
/// x (index 0) and y (index 1): a number type for kernels/ (T(int), +, -, unary -, *).
struct TripleDegree {
  bool zero = true;   // no term: the zero polynomial (any degree)
  int lo[2] = {0, 0};
  int hi[2] = {0, 0};
  TripleDegree() = default;
  TripleDegree(int constant) : zero(constant == 0) {}   // NOLINT(google-explicit-constructor)
  /// A non-zero quantity of degree one in the triple of `variable` (0: x, 1: y) and none in the other.
  static TripleDegree unit(int variable) {
    TripleDegree d(1);
    d.lo[variable] = d.hi[variable] = 1;
    return d;
  }
  /// The degree of every term in `variable`, or -1 when the terms' degrees differ (no term: 0).
  int homogeneous(int variable) const {
    if (zero) return 0;
    return lo[variable] == hi[variable] ? hi[variable] : -1;
  }
  friend TripleDegree operator+(const TripleDegree& a, const TripleDegree& b) {
    if (a.zero) return b;
    if (b.zero) return a;
    TripleDegree r(1);
    for (int v = 0; v < 2; ++v) {
      r.lo[v] = std::min(a.lo[v], b.lo[v]);
      r.hi[v] = std::max(a.hi[v], b.hi[v]);
    }
    return r;
  }
  friend TripleDegree operator-(const TripleDegree& a, const TripleDegree& b) { return a + b; }
  friend TripleDegree operator-(const TripleDegree& a) { return a; }
  friend TripleDegree operator*(const TripleDegree& a, const TripleDegree& b) {
    if (a.zero || b.zero) return TripleDegree();
    TripleDegree r(1);
    for (int v = 0; v < 2; ++v) {
      r.lo[v] = a.lo[v] + b.lo[v];
      r.hi[v] = a.hi[v] + b.hi[v];
    }
    return r;
  }
};

/// The curve generator carries a pair's kernel quantities between half-turn charts by
/// reflection (CurveGenerator::Data::kernel_memo): on by default; off on this thread, every
/// chart forms them again (tests compare the curves: the same).
struct HalfTurnMemoTag {};
inline bool& half_turn_memo_switch() { return thread_switch<HalfTurnMemoTag>(); }
/// Pairs whose quantities were reflected on this thread (tests, profiling).
inline std::size_t& half_turn_memo_hits() { return thread_counter<HalfTurnMemoTag>(); }

}  // namespace hipair::cspace
