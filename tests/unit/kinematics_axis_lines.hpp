// Test helper: axes (kinematics/axis.hpp AxisLine) as make_axis builds them, for the kinematics
// tests that take positions on an axis without a model (kinematics_driver_plan_test.cpp,
// kinematics_exact_rest_test.cpp).
#pragma once

#include "kinematics/axis.hpp"

#include <numbers>

namespace hipair::kinematics_detail::test_axes {

/// A full turn: cyclic, the chart t in [-1, 1] about 0 then the one about pi (make_axis's
/// cyclic axis).
inline AxisLine full_turn() {
  AxisLine line;
  line.rotation = true;
  line.cyclic = true;
  line.pieces = {ChartAxis{ChartAxis::Kind::rotation, false, Rational(-1), Rational(1)},
                 ChartAxis{ChartAxis::Kind::rotation, true, Rational(-1), Rational(1)}};
  line.half_turns = {0, 1};
  line.offsets = {0.0, std::numbers::pi};
  return line;
}

}  // namespace hipair::kinematics_detail::test_axes
