// Shared pieces of the first_crossing tests that compare a switch's answers (start filter, scan
// memo, angle memo): the exact description of an answer, and the starts they generate near
// contact edges and on chart sides.
#pragma once

#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

namespace hipair::test {

// The answer to `path` on `space`, described exactly ("throws: ..." where it throws).
inline std::string crossing_answer(const CSpace& space, const MotionPath& path) {
  try {
    return describe_crossing(space, space.first_crossing(path));
  } catch (const GeometryError& e) {
    return std::string("throws: ") + e.what();
  }
}

// A coordinate moved off where it was: by -4 ... 4 ulps, or by +-(1e-15 ... 1e-3).
inline void move_off(double& value, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  if (random() % 2 == 0) {
    int k = static_cast<int>(random() % 9) - 4;
    for (int j = 0; j < std::abs(k); ++j) value = std::nextafter(value, k > 0 ? 1e300 : -1e300);
  } else {
    value += sym(random) * std::pow(10.0, -15 + 12 * unit(random));
  }
}

// A point (chart values) of the edge e's interior, x at 2 % ... 98 % of its x-range: false where
// the edge is vertical (nothing changed) or its ordinate cannot be evaluated there (c and x0 set).
inline bool onto_edge(const CSpace& space, std::size_t e, std::mt19937_64& random, std::size_t& c, double& x0, double& y0) {
  std::uniform_real_distribution<double> unit(0, 1);
  const CSpaceEdge& edge = space.edges()[e];
  if (edge.vertical) return false;
  c = edge.chart;
  x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
  try {
    y0 = space.evaluate(e, x0).value;
  } catch (const GeometryError&) {
    return false;
  }
  return true;
}

// x or y (chart values) put on one of the chart's sides (x only in a 1-D space).
inline void to_chart_side(const CSpaceChart& chart, bool two, double& x, double& y, std::mt19937_64& random) {
  bool on_x = !two || random() % 2 == 0;
  double side = (random() % 2 == 0) ? (on_x ? chart.x_lo : chart.y_lo).get_d() : (on_x ? chart.x_hi : chart.y_hi).get_d();
  (on_x ? x : y) = side;
}

// The tests' motion from the part values (qx0, qy0) by (vx, vy), bent by `bend` (x quadratic,
// y cubic, the same end); a point path when `point`.
inline MotionPath bent_motion(const CSpaceChart& chart, bool two, double qx0, double qy0, double vx, double vy,
                              double bend, bool point) {
  MotionPath path;
  path.x = axis_path(chart.x_kind, {qx0, vx * (1 - bend), vx * bend, 0});
  if (two) path.y = axis_path(chart.y_kind, {qy0, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
  if (point) path.u_end = path.u_begin;
  return path;
}

}  // namespace hipair::test
