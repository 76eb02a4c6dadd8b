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

#include <hipair/rational.hpp>

#include "kernels/interval.hpp"

#include <algorithm>
#include <cmath>
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
inline std::optional<kernels::Interval> tan_enclosure(const kernels::Interval& y) {
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
inline bool& carried_bounds() {
  thread_local bool on = true;
  return on;
}

// The t-ranges of every chart system that an angle in [theta_lo, theta_hi] (width < 2) may be
// in, as angle_pieces computes them; nullopt where the filter cannot decide (an angle beyond
// 2^40 turns, a non-finite bound).
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const kernels::Interval& theta);
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const Rational& theta_lo, const Rational& theta_hi) {
  using kernels::Interval;
  return filtered_angle_pieces(Interval(Interval::enclose(theta_lo).lo, Interval::enclose(theta_hi).hi));
}

// The same from the angle's double enclosure.
inline std::optional<std::vector<AnglePiece>> filtered_angle_pieces(const kernels::Interval& theta) {
  using kernels::Interval;
  const Interval pi = pi_enclosure();
  Interval angle = theta;
  if (!std::isfinite(angle.lo) || !std::isfinite(angle.hi)) return std::nullopt;
  // reduce by a whole number of turns k (any k is certified; this one centres the angle)
  double k = std::floor((angle.middle() + pi_below) / (2 * pi_below));
  if (!(std::abs(k) <= 1099511627776.0)) return std::nullopt;
  angle = angle - Interval::point(2 * k) * pi;
  const Interval half_pi(0.5 * pi.lo, 0.5 * pi.hi);   // exact halvings
  std::vector<AnglePiece> pieces;
  bool failed = false;
  auto tan_half = [&](double tau, bool upper) {
    std::optional<Interval> t = tan_enclosure(Interval::point(tau) * Interval::point(0.5));
    if (!t) {
      failed = true;
      return 0.0;
    }
    return upper ? t->hi : t->lo;
  };
  auto piece = [&](const Interval& tau, bool half_turn) {
    // certainly below -pi/2 or certainly above pi/2: not in this chart
    if (tau.hi < -half_pi.hi || tau.lo > half_pi.hi) return;
    AnglePiece p;
    p.half_turn = half_turn;
    p.dlo = tau.lo <= -half_pi.lo ? -1.0 : tan_half(tau.lo, false);
    p.dhi = tau.hi >= half_pi.lo ? 1.0 : tan_half(tau.hi, true);
    if (failed || p.dlo > p.dhi) return;
    p.lo = Rational(p.dlo);
    p.hi = Rational(p.dhi);
    pieces.push_back(std::move(p));
  };
  piece(angle, false);
  piece(angle - pi, true);
  piece(angle + pi, true);
  if (failed) return std::nullopt;
  return pieces;
}

}  // namespace hipair::cspace
