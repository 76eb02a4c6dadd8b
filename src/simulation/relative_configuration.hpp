// Exact relative configurations of two planar (3-DOF) parts, shared by the planar system
// simulator (planar.cpp) and the pin-in-slot simulator (pin_slot_simulation.cpp). Internal to
// src/simulation/.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include <utility>

namespace hipair::simulation_detail {

// tan(theta/2) -> (cos, sin) exactly; the half turn (-1, 0)
inline std::pair<Rational, Rational> cos_sin(const SlicedAngle& a) {
  if (a.half_turn) return {Rational(-1), Rational(0)};
  Rational d = 1 + a.t * a.t;
  Rational c = (1 - a.t * a.t) / d, s = 2 * a.t / d;
  c.canonicalize();
  s.canonicalize();
  return {c, s};
}

// The configuration of part B (pivot pb, world configuration b) relative to part A (pivot pa,
// world configuration a) held at its zero configuration: A^-1 o B = pb + R(theta_b - theta_a)
// (P - pb) + s with s = pa - pb + R(-theta_a)(pb - pa + t_b - t_a); exact.
inline SlicedConfiguration relative_configuration(const Point& pa, const SlicedConfiguration& a, const Point& pb,
                                           const SlicedConfiguration& b) {
  SlicedConfiguration r;
  auto [c, s] = cos_sin(a.angle);
  Rational dx = pb.x - pa.x + b.x - a.x, dy = pb.y - pa.y + b.y - a.y;
  r.x = pa.x - pb.x + c * dx + s * dy;
  r.y = pa.y - pb.y - s * dx + c * dy;
  r.x.canonicalize();
  r.y.canonicalize();
  // tan((theta_b - theta_a)/2)
  const SlicedAngle &ta = a.angle, &tb = b.angle;
  if (ta.half_turn && tb.half_turn) {
    r.angle.t = 0;
  } else if (ta.half_turn) {   // tan((theta_b - pi)/2) = -1/t_b
    if (sgn(tb.t) == 0) r.angle.half_turn = true;
    else r.angle.t = -1 / tb.t;
  } else if (tb.half_turn) {   // tan((pi - theta_a)/2) = 1/t_a
    if (sgn(ta.t) == 0) r.angle.half_turn = true;
    else r.angle.t = 1 / ta.t;
  } else {
    Rational den = 1 + ta.t * tb.t;
    if (sgn(den) == 0) r.angle.half_turn = true;
    else r.angle.t = (tb.t - ta.t) / den;
  }
  r.angle.t.canonicalize();
  return r;
}

}  // namespace hipair::simulation_detail
