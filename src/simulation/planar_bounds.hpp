// HIPAIR — certified bounds of the planar simulator (docs/simulation.md, "What is certified"):
// the sweep of a straight motion in (x, y, w) and a rational upper bound of a square root, in
// exact rationals. Internal to src/simulation.
#pragma once

#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include <cmath>
#include <optional>

namespace hipair::simulation {

/// A rational r >= sqrt(v) (v >= 0), within about 2^-40 relative of it.
inline Rational sqrt_upper(const Rational& v) {
  if (sgn(v) <= 0) return Rational(0);
  if (!std::isfinite(v.get_d())) {   // beyond the doubles (lengths of 1e154 mm and more): floor(sqrt(ceil v)) + 1
    mpz_class c;
    mpz_cdiv_q(c.get_mpz_t(), v.get_num_mpz_t(), v.get_den_mpz_t());
    mpz_sqrt(c.get_mpz_t(), c.get_mpz_t());
    return Rational(c + 1);
  }
  Rational r(std::sqrt(v.get_d()));
  if (sgn(r) <= 0) r = Rational(1, 1 << 30);
  const Rational grow = 1 + Rational(1) / Rational(1099511627776.0);   // 1 + 2^-40
  while (r * r < v) r *= grow;
  r.canonicalize();
  return r;
}

/// The chart coordinate w of a configuration's angle on a straight motion (SlicedMotion): t
/// without the half turn, -1/t with it; empty where the chart does not reach (the half turn
/// without it, theta = 0 with it).
inline std::optional<Rational> chart_w(const SlicedConfiguration& c, bool through_half_turn) {
  if (!through_half_turn) {
    if (c.angle.half_turn) return std::nullopt;
    return c.angle.t;
  }
  if (c.angle.half_turn) return Rational(0);
  if (sgn(c.angle.t) == 0) return std::nullopt;
  Rational w = -1 / c.angle.t;
  return w;
}

/// A certified upper bound D of the distance any point of a part moves along the straight motion
/// from `a` to `b` in (x, y, w): every point at most `reach` (a rational upper bound) from the
/// pivot moves at most |dx| + |dy| + reach |d theta|, and |d theta| <= 2 |dw| (theta = c + 2
/// atan w, |d theta / dw| = 2 / (1 + w^2) <= 2). Empty where the chart does not reach an end.
inline std::optional<Rational> motion_sweep_bound(const SlicedConfiguration& a, const SlicedConfiguration& b,
                                                  bool through_half_turn, const Rational& reach) {
  std::optional<Rational> wa = chart_w(a, through_half_turn), wb = chart_w(b, through_half_turn);
  if (!wa || !wb) return std::nullopt;
  Rational d = abs(b.x - a.x) + abs(b.y - a.y) + 2 * reach * abs(*wb - *wa);
  d.canonicalize();
  return d;
}

}  // namespace hipair::simulation
