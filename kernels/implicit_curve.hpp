// HIPAIR contact kernels — derivatives of a contact curve F(x, y) = 0 by implicit
// differentiation, and their conversion from chart coordinates to part coordinates, for any
// number type T with division (exact rational intervals in CSpace::derivatives, double, ...).
#pragma once

#include <cstddef>
#include <vector>

namespace hipair::kernels {

/// The partial derivatives of a bivariate polynomial F at a point, up to second order.
template <class T>
struct Partials {
  T fx, fy, fxx, fxy, fyy;
};

/// F_x, F_y, F_xx, F_xy, F_yy at (x, y) of the polynomial with coefficients c[i][j] of x^i y^j
/// (any coefficient type; `convert` turns a coefficient into T), evaluated in T.
template <class T, class Coefficient, class Convert>
Partials<T> polynomial_partials(const std::vector<std::vector<Coefficient>>& c, const T& x, const T& y,
                                Convert&& convert) {
  std::size_t max_i = c.size(), max_j = 0;
  for (const auto& row : c) max_j = row.size() > max_j ? row.size() : max_j;
  std::vector<T> xp(max_i + 1, T(1)), yp(max_j + 1, T(1));   // powers
  for (std::size_t i = 1; i <= max_i; ++i) xp[i] = T(xp[i - 1] * x);
  for (std::size_t j = 1; j <= max_j; ++j) yp[j] = T(yp[j - 1] * y);
  Partials<T> d{T(0), T(0), T(0), T(0), T(0)};
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) {
      T a = convert(c[i][j]);
      if (a == T(0)) continue;
      int ii = static_cast<int>(i), jj = static_cast<int>(j);
      if (i >= 1) d.fx = T(d.fx + a * T(ii) * xp[i - 1] * yp[j]);
      if (j >= 1) d.fy = T(d.fy + a * T(jj) * xp[i] * yp[j - 1]);
      if (i >= 2) d.fxx = T(d.fxx + a * T(ii * (ii - 1)) * xp[i - 2] * yp[j]);
      if (i >= 1 && j >= 1) d.fxy = T(d.fxy + a * T(ii * jj) * xp[i - 1] * yp[j - 1]);
      if (j >= 2) d.fyy = T(d.fyy + a * T(jj * (jj - 1)) * xp[i] * yp[j - 2]);
    }
  return d;
}

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

/// d/ds and d^2/ds^2 of a translation's offset s in its own chart coordinate: 1 and 0.
template <class T>
Slopes<T> offset_slopes() {
  return {T(1), T(0)};
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
