// Shared helpers of the C-space tests: the oracle's chart axis of a public chart, and a
// random rational configuration inside a random built chart or tile.
#pragma once

#include "curves/contact_curves.hpp"

#include <hipair/cspace.hpp>

#include <random>

namespace hipair::test {

// The overlap oracle's description of one axis of a public chart.
inline cspace::ChartAxis axis_of(AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
  cspace::ChartAxis axis;
  axis.kind = kind == AxisKind::rotation ? cspace::ChartAxis::Kind::rotation : cspace::ChartAxis::Kind::translation;
  axis.half_turn = half_turn;
  axis.lo = lo;
  axis.hi = hi;
  return axis;
}

// A random rational configuration inside a random built chart or tile (y = 0 in a 1-D space).
inline ChartPoint random_tile_point(const CSpace& space, std::mt19937_64& random) {
  std::size_t t = random() % space.charts().size();
  const CSpaceChart& chart = space.charts()[t];
  auto pick = [&](const Rational& lo, const Rational& hi) {
    Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
    u.canonicalize();
    Rational v = lo + u * (hi - lo);
    v.canonicalize();
    return v;
  };
  Rational x = pick(chart.x_lo, chart.x_hi);
  Rational y = space.dimension() == 2 ? pick(chart.y_lo, chart.y_hi) : Rational(0);
  return ChartPoint{t, x, y};
}

}  // namespace hipair::test
