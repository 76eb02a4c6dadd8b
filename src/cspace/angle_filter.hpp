// The filtered chart pieces of an angle enclosure, for CSpace::first_crossing's stretches.
//
// A rotating part's chart coordinate is t = tan((theta - c) / 2) in the chart centred at c = 0
// or c = pi, each clipped at its seams theta - c = +-pi/2 (t = +-1). first_crossing encloses a
// stretch of a path's angle in [lo, hi] and needs the t-range of every chart system it meets.
// angle_pieces (cspace_queries.cpp) computes them with MPFI/MPFR (mpfr_tan, directed rounding);
// this is the same computation in outward-rounded double intervals (kernels::Interval): a
// few units in the last place wider and about ten times cheaper. Certified either way; the test
// CSpaceAngleFilter.* compares it with a 256-bit MPFR oracle on generated angles.
#pragma once

#include "core/thread_switch.hpp"
#include <hipair/rational.hpp>

#include "cspace/path_filter.hpp"
#include "kernels/interval.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace hipair::cspace {

// pi enclosed: the double below pi and the next one.
inline constexpr double pi_below = 3.141592653589793;   // 3.14159265358979311... < pi
inline kernels::Interval pi_enclosure() {
  return kernels::Interval(pi_below, kernels::interval_detail::up(pi_below));
}

// tan(y) enclosed for |y| <= 0.8: sin and cos by their Taylor polynomials (to y^19 and y^20, in
// nested form) plus the Lagrange remainders |y|^21 / 21! and |y|^22 / 22! (21! > 5.1e19,
// 22! > 1.12e21), then the quotient (cos y >= 0.69 there). nullopt outside |y| <= 0.8.
inline std::optional<kernels::Interval> tan_enclosure_generic(const kernels::Interval& y);
inline std::optional<kernels::Interval> tan_enclosure_signed(const kernels::Interval& y);

// tan_enclosure: the same bounds, bit for bit, as tan_enclosure_generic (the interval
// operations below, written out): where y lies on one side of 0 (away from underflow) every
// product and quotient of the nested forms has operands of known signs, so the one end product
// that kernels::Interval's min/max would pick is computed alone (two products per step
// instead of four, no min/max); elsewhere the generic form. CSpaceAngleFilter.* checks the
// equality on generated and boundary arguments.
inline std::optional<kernels::Interval> tan_enclosure(const kernels::Interval& y) {
  if (std::optional<kernels::Interval> t = tan_enclosure_signed(y)) return t;
  return tan_enclosure_generic(y);
}

// The signed fast path of tan_enclosure; nullopt where it does not apply (y meets
// [-1e-150, 1e-150], |y| > 0.8, a sign assumption fails on the way): then the generic form
// decides.
inline std::optional<kernels::Interval> tan_enclosure_signed(const kernels::Interval& y) {
  using kernels::Interval;
  // interval_detail::down / up on the doubles met below: every argument of down is a positive
  // normal double and every argument of up a finite double >= +0 (shown per line below for
  // 1e-150 <= a <= b <= 0.8; the one exception, sl + -rs, is discussed there), where the neighbour is the bit pattern's predecessor / successor
  // (up(+0) is the smallest subnormal, the pattern 1): the same doubles as the general rule
  // without its zero, sign and infinity tests (esc46b: this function is ~5.8 % of the
  // escapement's simulation loop, called ~4 700 times)
  auto up = [](double x) { return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) + 1); };
  // odd: the generic operations on -y are those on y negated (rounding to nearest and the
  // one-ulp widening are symmetric), so [-a, -b] is done as [b, a]
  bool negative = y.hi < 0;
  double a = negative ? -y.hi : y.lo, b = negative ? -y.lo : y.hi;   // 0 < a <= b
  if (!(a >= 1e-150) || !(b <= 0.8) || !(a <= b)) return std::nullopt;
  const double r = b;
  // y2 = y * y: all ends positive, the minimum a a and the maximum b b (a a >= 1e-300 rounds
  // to a positive normal double; b b <= 0.64)
  // (y2 below: [down(a a), up(b b)])
  // s = 1 - over(y2, n) * s with over(y2, n) = [down(y2l / n), up(y2h / n)] >= 0 and s > 0:
  // the product [down(ol sl), up(oh sh)], the difference [down(1 - ph), up(1 - pl)].
  // Signs, by induction over the steps: ol >= 1e-300 / 380 > 2.6e-303 (normal), oh <= 0.65 / n;
  // sh, ch <= 1 + 2^-52 (1 - pl <= 1 rounds to <= 1); so ph <= 0.65 / 6 * (1 + 2^-52) < 0.11
  // for s (n >= 6) and < 0.33 for c (n >= 2): sl > 0.88, cl > 0.66, hence pl >= ol * 0.66,
  // positive normal, and 1 - ph, 1 - pl in (0.66, 1]. The generic form's sign assumptions
  // (ol >= 0, sl > 0, cl > 0) therefore hold at every step and are not re-tested here.
  // (esc49b) The lower and upper ends below go in the two lanes of one vector, lane 0 the
  // scalar form's lower end (stepped down: the pattern - 1), lane 1 its upper end (stepped up:
  // + 1), every operation the scalar form's on that end in its order: the same doubles, the
  // same steps on them. Where the scalar form pairs a lower end with an upper one (1 - ph, the
  // quotient sl / ch) the operand's lanes are swapped.
  using v2d = path_filter_detail::v2d;
  using v2u = path_filter_detail::v2u;
  auto step = [](v2d v) { return reinterpret_cast<v2d>(reinterpret_cast<v2u>(v) + v2u{~std::uint64_t{0}, 1}); };
  auto swapped = [](v2d v) { return v2d{v[1], v[0]}; };
  const v2d y2 = step(v2d{a, b} * v2d{a, b});
  const v2d one{1, 1};
  v2d s = one, c = one;
  for (int k = 9; k >= 1; --k) {
    const double n = 2 * k * (2 * k + 1);
    const v2d o = step(y2 / v2d{n, n});
    const v2d p = step(o * s);
    s = step(one - swapped(p));
  }
  for (int k = 10; k >= 1; --k) {
    const double n = (2 * k - 1) * (2 * k);
    const v2d o = step(y2 / v2d{n, n});
    const v2d p = step(o * c);
    c = step(one - swapped(p));
  }
  // s = y * s: both positive
  s = step(v2d{a, b} * s);
  // power >= +0 finite at every step (it may underflow to +0 or a subnormal for small r: up
  // steps those by the pattern too, as the general rule does)
  // (the chain in both lanes of a vector, stepped up by the pattern: up's doubles, kept in the
  // vector registers)
  const v2d rr{r, r};
  auto upward = [](v2d v) { return reinterpret_cast<v2d>(reinterpret_cast<v2u>(v) + v2u{1, 1}); };
  v2d power = rr;   // r^21, then r^22, rounded up (as in the generic form)
#pragma GCC unroll 20
  for (int i = 2; i <= 21; ++i) power = upward(power * rr);
  const double rs = up(power[0] / 5.1e19);
  power = upward(power * rr);
  const double rc = up(power[0] / 1.12e21);
  // s + [-rs, rs], c + [-rc, rc] (rs, rc < 0.8^21 / 5.1e19 < 1e-21: cl stays > 0.6, and so
  // does sl / a for a point or narrow y; a wide y with a small lower end a < rs can make
  // sl + -rs <= 0: the pattern's step then gives a double <= 0 or NaN (from -0 or +0) where the
  // general rule gives one <= 0, and the check below answers nullopt from either, as before)
  s = step(s + v2d{-rs, rs});
  c = step(c + v2d{-rc, rc});
  if (!(c[0] > 0) || !(s[0] > 0)) return std::nullopt;
  // s / c, both positive: [down(sl / ch), up(sh / cl)]
  const v2d q = step(s / swapped(c));
  const double ql = q[0], qh = q[1];
  return negative ? Interval(-qh, -ql) : Interval(ql, qh);
}

inline std::optional<kernels::Interval> tan_enclosure_generic(const kernels::Interval& y) {
  using kernels::Interval;
  using kernels::interval_detail::up;
  double r = std::max(std::abs(y.lo), std::abs(y.hi));
  if (!(r <= 0.8)) return std::nullopt;
  Interval y2 = y * y;
  // sin y = y (1 - y^2/(2.3) (1 - y^2/(4.5) (... (1 - y^2/(18.19))))),
  // cos y = 1 - y^2/(1.2) (1 - y^2/(3.4) (... (1 - y^2/(19.20))))
  // y2 / n for an integer n > 0: kernels' quotient with the divisor a point, two divisions
  // instead of four (rounding to nearest is monotone, so lo / n and hi / n are its minimum and
  // maximum: the same bounds)
  auto over = [](const Interval& a, int n) {
    return Interval(kernels::interval_detail::down(a.lo / n), kernels::interval_detail::up(a.hi / n));
  };
  Interval s(1), c(1);
  for (int k = 9; k >= 1; --k) s = Interval(1) - over(y2, 2 * k * (2 * k + 1)) * s;
  for (int k = 10; k >= 1; --k) c = Interval(1) - over(y2, (2 * k - 1) * (2 * k)) * c;
  s = y * s;
  double power = r;   // r^21, then r^22, rounded up
  for (int i = 2; i <= 21; ++i) power = up(power * r);
  double rs = up(power / 5.1e19);
  power = up(power * r);
  double rc = up(power / 1.12e21);
  s = s + Interval(-rs, rs);
  c = c + Interval(-rc, rc);
  if (!(c.lo > 0)) return std::nullopt;
  return s / c;
}

// One chart system's t-range: half_turn false: the chart centred at 0, true: at pi. `dlo`,
// `dhi`: the same bounds as doubles (lo and hi are doubles, so these are exact).
struct AnglePiece {
  bool half_turn = false;
  Rational lo, hi;
  double dlo = 0, dhi = 0;
};

// The first_crossing stretches' double bookkeeping (cspace_queries.cpp: every double bound of a
// piece, box and path value carried along with its rational instead of converted back from it,
// the same doubles either way). On by default; tests switch it off per thread to compare every
// answer with the conversions' (CSpaceCarriedBounds.*).
struct CarriedBoundsTag;
inline bool& carried_bounds() { return thread_switch<CarriedBoundsTag>(); }

// first_crossing's second-order (Taylor) exclusion of the stretches next to a sliding start
// (cspace_queries.cpp, MotionScanner::second_order_excludes), tried where the mean-value form
// fails. On by default; tests switch it off per thread to compare the answers with and without
// (CSpaceSecondOrder.*) and the speed benchmark runs both.
struct SecondOrderTag;
inline bool& second_order() { return thread_switch<SecondOrderTag>(); }
// How many curves over a stretch the second-order form has excluded on this thread (tests).
struct SecondOrderExclusionsTag;
inline std::size_t& second_order_exclusions() { return thread_counter<SecondOrderExclusionsTag>(); }
// The second-order exclusion's parts that are the same for every curve it tries over one
// stretch — the start's rates X'(a), Y'(a) (kept with the start's pieces, for the next stretch
// from the same a too) and the stretch's X'', Y'' — computed once instead of once per curve (pure
// functions: the same bits). On by default; tests switch it off per thread to compare
// (CSpaceSecondOrderShared.*). Counter: the computations taken again.
// The second-order form's nested (Horner) enclosure start + h (rate_at + [0, h / 2] curvature),
// tried where the summed one fails (cspace_queries.cpp, second_order_excludes): only adds
// certified exclusions. On by default; tests switch it off per thread to compare
// (CSpaceNestedTaylor.*). Counter: the curves it excluded that the summed form did not.
struct NestedTaylorTag;
inline bool& nested_taylor() { return thread_switch<NestedTaylorTag>(); }
struct NestedTaylorExclusionsTag;
inline std::size_t& nested_taylor_exclusions() { return thread_counter<NestedTaylorExclusionsTag>(); }
struct SecondOrderSharedTag;
inline bool& second_order_shared() { return thread_switch<SecondOrderSharedTag>(); }
struct SecondOrderSharedHitsTag;
inline std::size_t& second_order_shared_hits() { return thread_counter<SecondOrderSharedHitsTag>(); }

// first_crossing's start anchors (cspace_queries.cpp): a query answering `none` whose last
// stretch's box holds no curve of its chart remembers that box and its free cell (per thread,
// per space); a later start inside the box is located there without the exact ray shooting.
// On by default; tests switch it off to compare, and count the starts it located.
struct StartAnchorsTag;
inline bool& start_anchors() { return thread_switch<StartAnchorsTag>(); }
struct AnchoredStartsTag;
inline std::size_t& anchored_starts() { return thread_counter<AnchoredStartsTag>(); }
// And the anchor boxes: every stretch a query excludes whose evaluation is one box clear of the
// cell-bounding curves lies in the query's start cell (the stretches before it were excluded, or
// certified free by the Newton shrink's bound), so the query (finished or stopped) leaves those
// boxes with its start cell (per thread, per space: the last query's that excluded one); a later
// start whose located point lies in one, strictly inside its chart, is located in that cell
// without the exact ray shooting once no curve of the chart (not only the bounding ones) vanishes
// on the box (checked on first use, as the start anchor's box). The simulator's next step starts
// where the last one ended, mostly inside a stretch the pair's last query excluded. On by
// default; tests switch it off to compare (CSpaceCrossingAnchorBoxes.*), and count the starts
// located by a box.
struct AnchorBoxesTag;
inline bool& anchor_boxes() { return thread_switch<AnchorBoxesTag>(); }
struct BoxAnchoredStartsTag;
inline std::size_t& box_anchored_starts() { return thread_counter<BoxAnchoredStartsTag>(); }

// Point location's filter (builder_locate.cpp, locate_2d): an edge whose support is quadratic
// in y at the point's rational abscissa is placed above or below the point by a certified double
// enclosure of its root, or the exact sign of the quadratic at the point's ordinate, instead of
// the exact root isolation; ordinates the enclosures cannot order are compared exactly. On by
// default; tests switch it off per thread to compare every location with the exact one.
struct LocateFilterTag;
inline bool& locate_filter() { return thread_switch<LocateFilterTag>(); }

// How many edges the filter placed on this thread (quadratic_ordinate's answers: tests).
struct LocateFilterEdgesTag;
inline std::size_t& locate_filter_edges() { return thread_counter<LocateFilterEdgesTag>(); }

// filtered_angle_ranges' half-angle tangents through a per-thread memo: tan_enclosure(tau / 2)
// is a pure function of the double tau, and a subdivision's stretches share their ends' tau (a
// stretch [a, b] and its first half [a, m] enclose a monotone angle from the same double at a),
// so a direct-mapped table of recent taus (bit patterns) and their enclosures (both ends, or
// none where tan_enclosure has none) returns the same bits without the Taylor polynomials. On by
// default; tests switch it off per thread to compare (CSpaceAngleFilter.TanMemo*).
struct TanMemoTag;
inline bool& tan_memo() { return thread_switch<TanMemoTag>(); }
// How many half-angle tangents on this thread came from the memo (tests, profiling).
struct TanMemoHitsTag;
inline std::size_t& tan_memo_hits() { return thread_counter<TanMemoHitsTag>(); }

// first_crossing's scanner remembers the filtered enclosures of its path's polynomials (the
// path, its rate, its acceleration per axis) over the last few stretches' end doubles
// (cspace_queries.cpp, MotionScanner::path_enclosure): the same bits without the Taylor shift.
// On by default; tests switch it off per thread to compare (CSpaceCrossingPathMemo.*).
struct PathMemoTag;
inline bool& path_memo() { return thread_switch<PathMemoTag>(); }
// How many path enclosures on this thread came from the memo (tests, profiling).
struct PathMemoHitsTag;
inline std::size_t& path_memo_hits() { return thread_counter<PathMemoHitsTag>(); }

inline std::optional<kernels::Interval> half_angle_tan(double tau) {
  using kernels::Interval;
  if (!tan_memo()) return tan_enclosure(Interval::point(tau) * Interval::point(0.5));
  struct Entry {
    std::uint64_t key = 0;
    bool used = false;
    std::optional<Interval> value;
  };
  constexpr std::size_t size = 256;
  thread_local std::array<Entry, size> table;
  const std::uint64_t key = std::bit_cast<std::uint64_t>(tau);
  Entry& entry = table[static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 56) % size];
  if (entry.used && entry.key == key) {
    ++tan_memo_hits();
    return entry.value;
  }
  entry.value = tan_enclosure(Interval::point(tau) * Interval::point(0.5));
  entry.key = key;
  entry.used = true;
  return entry.value;
}

// The t-ranges of every chart system that an angle in [theta_lo, theta_hi] (width < 2) may be
// in, as angle_pieces computes them; nullopt where the filter cannot decide (an angle beyond
// 2^40 turns, a non-finite bound).
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const kernels::Interval& theta);
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const Rational& theta_lo, const Rational& theta_hi) {
  using kernels::Interval;
  return filtered_angle_pieces(Interval(Interval::enclose(theta_lo).lo, Interval::enclose(theta_hi).hi));
}

// The chart systems' t-ranges of an angle enclosure as doubles alone (filtered_angle_pieces'
// bounds, without their rationals): at most three, `size` of them.
struct AngleRanges {
  std::size_t size = 0;
  bool half_turn[3] = {false, false, false};
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

inline std::optional<AngleRanges> filtered_angle_ranges(const kernels::Interval& theta) {
  using kernels::Interval;
  const Interval pi = pi_enclosure();
  Interval angle = theta;
  if (!std::isfinite(angle.lo) || !std::isfinite(angle.hi)) return std::nullopt;
  // reduce by a whole number of turns k (any k is certified; this one centres the angle)
  double k = std::floor((angle.middle() + pi_below) / (2 * pi_below));
  if (!(std::abs(k) <= 1099511627776.0)) return std::nullopt;
  angle = angle - Interval::point(2 * k) * pi;
  const Interval half_pi(0.5 * pi.lo, 0.5 * pi.hi);   // exact halvings
  AngleRanges ranges;
  bool failed = false;
  auto tan_half = [&](double tau, bool upper) {
    std::optional<Interval> t = half_angle_tan(tau);
    if (!t) {
      failed = true;
      return 0.0;
    }
    return upper ? t->hi : t->lo;
  };
  auto piece = [&](const Interval& tau, bool half_turn) {
    // certainly below -pi/2 or certainly above pi/2: not in this chart
    if (tau.hi < -half_pi.hi || tau.lo > half_pi.hi) return;
    double lo = tau.lo <= -half_pi.lo ? -1.0 : tan_half(tau.lo, false);
    double hi = tau.hi >= half_pi.lo ? 1.0 : tan_half(tau.hi, true);
    if (failed || lo > hi) return;
    ranges.half_turn[ranges.size] = half_turn;
    ranges.lo[ranges.size] = lo;
    ranges.hi[ranges.size] = hi;
    ++ranges.size;
  };
  piece(angle, false);
  piece(angle - pi, true);
  piece(angle + pi, true);
  if (failed) return std::nullopt;
  return ranges;
}

// The same from the angle's double enclosure.
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const kernels::Interval& theta) {
  std::optional<AngleRanges> ranges = filtered_angle_ranges(theta);
  if (!ranges) return std::nullopt;
  std::vector<AnglePiece> pieces;
  for (std::size_t i = 0; i < ranges->size; ++i)
    pieces.push_back(AnglePiece{ranges->half_turn[i], Rational(ranges->lo[i]), Rational(ranges->hi[i]), ranges->lo[i], ranges->hi[i]});
  return pieces;
}


// kernels::Interval::enclose(c * m) (the double that mpq_get_d truncates the exact product to, and
// the next one away from 0), computed in doubles where c is exactly a double d of moderate
// exponent: the product's residual fma(d, m, -p) is exact there and tells on which side of the
// rounded p = d m the product lies. Elsewhere (c no double, or the product near the doubles'
// range's ends) the enclosure of the rational product. The first_crossing scanner's derivative
// coefficients (CSpaceCrossingScanner.MultiplesEncloseAsTheRationalProduct compares both).
inline kernels::Interval enclose_multiple(const Rational& c, long m) {
  const mpz_class& num = c.get_num();
  const mpz_class& den = c.get_den();
  if (sgn(num) != 0 && m > 0 && m < (1L << 20) && mpz_popcount(den.get_mpz_t()) == 1 &&
      mpz_sizeinbase(num.get_mpz_t(), 2) <= 53 && mpz_sizeinbase(den.get_mpz_t(), 2) <= 900) {
    const double d = c.get_d();   // exact: a numerator of at most 53 bits over 2^k, k < 900
    const double factor = static_cast<double>(m);
    const double p = d * factor;
    const double magnitude = std::fabs(p);
    if (magnitude >= 0x1p-900 && magnitude <= 0x1p+900) {
      const double residual = std::fma(d, factor, -p);   // d m = p + residual exactly
      // the truncation toward 0: p, unless p lies beyond the product (then the double before it)
      double truncated = p;
      if (residual != 0 && (residual > 0) != (p > 0)) truncated = std::nextafter(p, 0.0);
      return p > 0 ? kernels::Interval(truncated, kernels::interval_detail::up(truncated))
                   : kernels::Interval(kernels::interval_detail::down(truncated), truncated);
    }
  }
  Rational product = c * m;
  return kernels::Interval::enclose(product);
}

}  // namespace hipair::cspace
