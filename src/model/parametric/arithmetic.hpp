// The number-type interface of formulas and parametric models (docs/tolerance.md "The
// parametric model"): Arithmetic<T> supplies constants, pi and the few functions formulas need
// beyond + - * /. Only the primary template and the double case live here, so that the
// formulas and the parametric model can be compiled without Eigen or the kernels' intervals
// (the independent verifier instantiates them with its own MPFI arithmetic, certify/);
// number_traits.hpp adds the kernels' certified intervals and Eigen's AutoDiff scalars.
#pragma once

#include <hipair/rational.hpp>

#include <cmath>
#include <numbers>

namespace hipair::model_detail {

template <class T>
struct Arithmetic;

template <>
struct Arithmetic<double> {
  static double constant(const Rational& q) { return q.get_d(); }
  static double pi() { return std::numbers::pi; }
  static double sqrt(double x) { return std::sqrt(x); }
  static double sin(double x) { return std::sin(x); }
  static double cos(double x) { return std::cos(x); }
  static double tan(double x) { return std::tan(x); }
  static double atan2(double y, double x) { return std::atan2(y, x); }
  static double abs(double x) { return std::fabs(x); }
  static double min(double a, double b) { return a < b ? a : b; }
  static double max(double a, double b) { return a < b ? b : a; }
  static double value(double x) { return x; }
};

}  // namespace hipair::model_detail
