// Cells of a chart axis for the culling tests (cspace_cell_pose_memo_test.cpp,
// cspace_gear_broad_phase_test.cpp).
#pragma once

#include "curves/contact_curves.hpp"

namespace hipair::test_charts {

// Cells [first, first + width) of `cells` equal cells of a chart axis (exact ends).
inline cspace::ChartAxis sub_axis(const cspace::ChartAxis& axis, long first, long width, long cells) {
  cspace::ChartAxis sub = axis;
  sub.lo = axis.lo + (axis.hi - axis.lo) * Rational(first, cells);
  sub.hi = axis.lo + (axis.hi - axis.lo) * Rational(first + width, cells);
  sub.lo.canonicalize();
  sub.hi.canonicalize();
  return sub;
}

}  // namespace hipair::test_charts
