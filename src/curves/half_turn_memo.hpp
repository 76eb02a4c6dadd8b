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
// other (half_turn_reflected below): the curve's polynomial, validity atoms
// and corner-entry atoms are carried as formed, constants and dropped atoms alike. k is found by
// running the same kernel on TripleDegree, which follows the range of the terms' degrees through
// +, - and *; a zero value (a zero body datum) has no terms, so the range is that of the terms
// that may be non-zero, and a quantity is reflected only when the range is one degree.
// Otherwise (or a degree above 2k) the curve is formed in each chart kind as before.
#pragma once

#include "algebra/polynomial.hpp"
#include "core/thread_switch.hpp"

#include <algorithm>
#include <optional>

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

/// The polynomial x^(2 kx) y^(2 ky) p(-1/x, -1/y), reflected only in the variables whose degree
/// bound is >= 0 (kx < 0: x kept; ky < 0: y kept), trimmed as normalize trims (no trailing zero
/// in a row, no trailing empty row); nullopt when the degree in a reflected variable exceeds 2 kx
/// (2 ky). Content and factors (1 + x^2), (1 + y^2) are kept: a normalised polynomial stays
/// normalised.
inline std::optional<IntegerPolynomial2> half_turn_reflected(const IntegerPolynomial2& polynomial, int kx, int ky) {
  const int dx = polynomial.degree_x(), dy = polynomial.degree_y();
  if ((kx >= 0 && dx > 2 * kx) || (ky >= 0 && dy > 2 * ky)) return std::nullopt;
  IntegerPolynomial2 r;
  if (dx < 0) return r;
  const int rows = kx >= 0 ? 2 * kx + 1 : dx + 1, columns = ky >= 0 ? 2 * ky + 1 : dy + 1;
  auto& c = r.coefficients;
  c.assign(static_cast<std::size_t>(rows), std::vector<mpz_class>(static_cast<std::size_t>(columns)));
  for (std::size_t i = 0; i < polynomial.coefficients.size(); ++i)
    for (std::size_t j = 0; j < polynomial.coefficients[i].size(); ++j) {
      const mpz_class& value = polynomial.coefficients[i][j];
      if (sgn(value) == 0) continue;
      // x^(2 kx) (-1/x)^i = (-1)^i x^(2 kx - i), the same in y
      const std::size_t ri = kx >= 0 ? static_cast<std::size_t>(2 * kx) - i : i;
      const std::size_t rj = ky >= 0 ? static_cast<std::size_t>(2 * ky) - j : j;
      const bool negate = (kx >= 0 && i % 2 == 1) != (ky >= 0 && j % 2 == 1);
      if (negate)
        mpz_neg(c[ri][rj].get_mpz_t(), value.get_mpz_t());
      else
        c[ri][rj] = value;
    }
  for (auto& row : c)
    while (!row.empty() && sgn(row.back()) == 0) row.pop_back();
  while (!c.empty() && c.back().empty()) c.pop_back();
  return r;
}

/// The curve generator carries a pair's kernel quantities between half-turn charts by
/// reflection (CurveGenerator::Data::kernel_memo): on by default; off on this thread, every
/// chart forms them again (tests compare the curves: the same).
struct HalfTurnMemoTag {};
inline bool& half_turn_memo_switch() { return thread_switch<HalfTurnMemoTag>(); }
/// Pairs whose quantities were reflected on this thread (tests, profiling).
inline std::size_t& half_turn_memo_hits() { return thread_counter<HalfTurnMemoTag>(); }

}  // namespace hipair::cspace
