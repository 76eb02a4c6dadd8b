// HIPAIR contact kernels — derivatives of a contact curve F(x, y) = 0 by implicit
// differentiation, and their conversion from chart coordinates to part coordinates, for any
// number type T with division (exact rational intervals in CSpace::derivatives, double, ...).
#pragma once

namespace hipair::kernels {

/// First and second derivatives of a function.
template <class T>
struct Slopes {
  T first;
  T second;
};

/// y'(x) and y''(x) of the curve F(x, y) = 0 from the partial derivatives of F at a point of
/// it (F_y != 0): y' = -F_x / F_y, y'' = -(F_xx + 2 F_xy y' + F_yy y'^2) / F_y.
template <class T>
Slopes<T> implicit_slopes(const T& fx, const T& fy, const T& fxx, const T& fxy, const T& fyy) {
  T first = T(-(fx / fy));
  T second = T(-((fxx + T(2) * fxy * first + fyy * first * first) / fy));
  return {first, second};
}

/// d/dt and d^2/dt^2 of the angle theta = c + 2 atan(t) of a half-angle chart coordinate t:
/// 2 / (1 + t^2) and -4 t / (1 + t^2)^2. (A translation's offset is its own coordinate:
/// slopes 1 and 0.)
template <class T>
Slopes<T> half_angle_slopes(const T& t) {
  T w = T(T(1) + t * t);
  return {T(T(2) / w), T(-(T(4) * t) / (w * w))};
}

/// The curve's slopes in part coordinates X(x), Y(y) (rad or mm) from its chart slopes, where
/// `x_axis` and `y_axis` are the slopes of X at x and of Y at y:
/// dY/dX = Y' y' / X', d^2Y/dX^2 = (Y'' y'^2 + Y' y'' - (dY/dX) X'') / X'^2.
template <class T>
Slopes<T> part_slopes(const Slopes<T>& chart, const Slopes<T>& x_axis, const Slopes<T>& y_axis) {
  T ratio = T(y_axis.first * chart.first / x_axis.first);
  T acceleration = T((y_axis.second * chart.first * chart.first + y_axis.first * chart.second - ratio * x_axis.second) /
                     (x_axis.first * x_axis.first));
  return {ratio, acceleration};
}

}  // namespace hipair::kernels
