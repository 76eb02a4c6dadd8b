// HIPAIR contact kernels — a forward-mode dual number (value, derivative along a motion).
//
// The kernels' formulas (contact_geometry.hpp, pose.hpp) evaluated with it give a quantity and
// its exact time derivative at once: pose a part with Dual(cos q, -sin q q'), Dual(sin q,
// cos q q') (or an offset Dual(s, s')) and the contact point's and normal's rates come out of
// the same formulas that give the point and the normal (the chain rule, no difference quotient).
// Used by the planar simulator's held arc contacts and the fixed-axis simulator's tangent drift.
#pragma once

namespace hipair::kernels {

/// A forward-mode dual number: value v and derivative d.
struct Dual {
  double v = 0, d = 0;
  Dual() = default;
  Dual(double value) : v(value) {}   // NOLINT: constants of the kernels' formulas
  Dual(double value, double rate) : v(value), d(rate) {}
};
inline Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator-(Dual a) { return {-a.v, -a.d}; }
inline Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
inline Dual operator/(Dual a, Dual b) { return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)}; }

}  // namespace hipair::kernels
