// The rational oracle beside a zero-clearance vertex (the fit tests: cspace_round_fit_test.cpp,
// cspace_radical_ordinate_test.cpp): at the eight rationals (x0 + dx ex, y0 + dy ey), dx, dy in
// {-1, 0, 1} not both 0, the parts overlap (a vertex blocked all around); the oracle at a chart
// point.
#pragma once

#include "curves/contact_curves.hpp"

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

namespace hipair::test {

// The exact overlap relation at a rational point of a pair's chart (chart = x index * the
// number of y charts + y index, as the public vertices number them).
inline cspace::Overlap chart_overlap(const Model& model, const cspace::PairAxes& axes, const cspace::ChartLayout& layout,
                                     std::size_t chart, const Rational& x, const Rational& y) {
  const std::size_t n = layout.y_charts.size();
  return cspace::classify_overlap(model, axes, layout.x_charts[chart / n], layout.y_charts[chart % n], cspace::ChartPoint{x, y});
}

template <class Oracle>   // cspace::Overlap oracle(const Rational& x, const Rational& y)
void expect_overlapping_beside(const Oracle& oracle, const Rational& x0, const Rational& y0, const Rational& ex, const Rational& ey) {
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      if (dx == 0 && dy == 0) continue;
      Rational x = x0 + dx * ex, y = y0 + dy * ey;
      x.canonicalize();
      y.canonicalize();
      EXPECT_EQ(oracle(x, y), cspace::Overlap::overlapping) << "beside the fit " << dx << ", " << dy;
    }
}

}  // namespace hipair::test
