// HIPAIR contact kernels — plane vectors over any number type T.
//
// T needs: copy, T(int), +, -, unary -, *. No comparisons and no division, so the same
// source serves exact rationals, exact polynomials, double, intervals and AutoDiff scalars.
#pragma once

namespace hipair::kernels {

/// A vector (or point) of the plane with coordinates of number type T.
template <class T>
struct Vector {
  T x;
  T y;
};

template <class T>
Vector<T> operator+(const Vector<T>& a, const Vector<T>& b) {
  return Vector<T>{T(a.x + b.x), T(a.y + b.y)};
}

template <class T>
Vector<T> operator-(const Vector<T>& a, const Vector<T>& b) {
  return Vector<T>{T(a.x - b.x), T(a.y - b.y)};
}

template <class T>
Vector<T> operator-(const Vector<T>& a) {
  return Vector<T>{T(-a.x), T(-a.y)};
}

template <class T>
Vector<T> scaled(const T& factor, const Vector<T>& a) {
  return Vector<T>{T(factor * a.x), T(factor * a.y)};
}

/// a.x b.y - a.y b.x: positive when b points to the left of a.
template <class T>
T cross(const Vector<T>& a, const Vector<T>& b) {
  return T(a.x * b.y - a.y * b.x);
}

template <class T>
T dot(const Vector<T>& a, const Vector<T>& b) {
  return T(a.x * b.x + a.y * b.y);
}

/// The left normal (-y, x).
template <class T>
Vector<T> left_normal(const Vector<T>& a) {
  return Vector<T>{T(-a.y), a.x};
}

/// Homogeneous rotation: (c x - s y, s x + c y), i.e. w times the rotation of `a` by the
/// angle whose cosine and sine are c/w and s/w.
template <class T>
Vector<T> rotated(const T& c, const T& s, const Vector<T>& a) {
  return Vector<T>{T(c * a.x - s * a.y), T(s * a.x + c * a.y)};
}

/// Converts a vector of one number type to another with a conversion function.
template <class To, class From, class Convert>
Vector<To> converted(const Vector<From>& a, Convert&& convert) {
  return Vector<To>{convert(a.x), convert(a.y)};
}

}  // namespace hipair::kernels
