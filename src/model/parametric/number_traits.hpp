// The number types a parametric model can be evaluated in, and the few functions formulas
// need beyond + - * / (docs/tolerance.md "The parametric model"):
//   double                                   approximate, for drawing and sampling
//   kernels::Interval                        certified (outward-rounded) enclosures; sin, cos,
//                                            tan and atan2 through MPFI with outward rounding
//   Eigen::AutoDiffScalar<Eigen::VectorXd>   value and gradient over the parameters
// Exact rationals are served by the exact evaluator (expression.cpp), which keeps
// rational + rational * pi values and rounds directions exactly as the reader does.
#pragma once

#include "kernels/interval.hpp"
#include "model/parametric/arithmetic.hpp"

#include <hipair/rational.hpp>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>
#include <mpfi.h>

#include <cmath>
#include <numbers>

namespace hipair::model_detail {

/// Gradient-carrying scalar over all parameters: Eigen's AutoDiffScalar with a dynamic-size
/// gradient, whose arithmetic is evaluated at once and treats an empty gradient as zero.
///
/// Eigen's own operators return lazy expressions and reconcile an empty gradient (a constant
/// such as the kernels' T(0), T(1), T(2), or a fixed part's pose) with a sized one only when
/// both sides are plain vectors; inside nested expressions (a.x * b.y - a.y * b.x with
/// constant a and moving b) the sizes disagree and Eigen reads out of bounds (an assertion
/// in debug builds). Here every +, -, *, / returns a plain AutoDiff, so the kernels
/// (templated on the number type) run on it unchanged, with constants of any origin.
class AutoDiff : public Eigen::AutoDiffScalar<Eigen::VectorXd> {
 public:
  using Base = Eigen::AutoDiffScalar<Eigen::VectorXd>;
  using Gradient = Eigen::VectorXd;

  AutoDiff() = default;
  /// A constant (empty gradient: zero with respect to everything).
  AutoDiff(double value) : Base(value) {}                                   // NOLINT(google-explicit-constructor)
  AutoDiff(int value) : Base(static_cast<double>(value)) {}                 // NOLINT(google-explicit-constructor)
  AutoDiff(double value, const Gradient& gradient) : Base(value, gradient) {}
  /// The `index`-th of `size` variables at `value`.
  AutoDiff(double value, Eigen::Index size, Eigen::Index index) : Base(value, size, index) {}
  /// Evaluates any Eigen AutoDiff expression (Eigen::sqrt(x), Eigen::atan2(y, x), ...).
  template <class Derivatives>
  AutoDiff(const Eigen::AutoDiffScalar<Derivatives>& other)  // NOLINT(google-explicit-constructor)
      : Base(other.value(), Gradient(other.derivatives())) {}

  friend AutoDiff operator+(const AutoDiff& a, const AutoDiff& b) {
    return AutoDiff(a.value() + b.value(), combine(a.derivatives(), 1.0, b.derivatives(), 1.0));
  }
  friend AutoDiff operator-(const AutoDiff& a, const AutoDiff& b) {
    return AutoDiff(a.value() - b.value(), combine(a.derivatives(), 1.0, b.derivatives(), -1.0));
  }
  friend AutoDiff operator-(const AutoDiff& a) { return AutoDiff(-a.value(), Gradient(-a.derivatives())); }
  friend AutoDiff operator*(const AutoDiff& a, const AutoDiff& b) {
    return AutoDiff(a.value() * b.value(), combine(a.derivatives(), b.value(), b.derivatives(), a.value()));
  }
  friend AutoDiff operator/(const AutoDiff& a, const AutoDiff& b) {
    const double inverse = 1.0 / b.value();
    const double quotient = a.value() * inverse;
    return AutoDiff(quotient, combine(a.derivatives(), inverse, b.derivatives(), -quotient * inverse));
  }
  friend AutoDiff operator+(const AutoDiff& a, double b) { return a + AutoDiff(b); }
  friend AutoDiff operator+(double a, const AutoDiff& b) { return AutoDiff(a) + b; }
  friend AutoDiff operator-(const AutoDiff& a, double b) { return a - AutoDiff(b); }
  friend AutoDiff operator-(double a, const AutoDiff& b) { return AutoDiff(a) - b; }
  friend AutoDiff operator*(const AutoDiff& a, double b) { return a * AutoDiff(b); }
  friend AutoDiff operator*(double a, const AutoDiff& b) { return AutoDiff(a) * b; }
  friend AutoDiff operator/(const AutoDiff& a, double b) { return a / AutoDiff(b); }
  friend AutoDiff operator/(double a, const AutoDiff& b) { return AutoDiff(a) / b; }
  AutoDiff& operator+=(const AutoDiff& b) { return *this = *this + b; }
  AutoDiff& operator-=(const AutoDiff& b) { return *this = *this - b; }
  AutoDiff& operator*=(const AutoDiff& b) { return *this = *this * b; }
  AutoDiff& operator/=(const AutoDiff& b) { return *this = *this / b; }
  friend bool operator==(const AutoDiff& a, const AutoDiff& b) { return a.value() == b.value(); }
  friend bool operator!=(const AutoDiff& a, const AutoDiff& b) { return a.value() != b.value(); }
  friend bool operator<(const AutoDiff& a, const AutoDiff& b) { return a.value() < b.value(); }
  friend bool operator>(const AutoDiff& a, const AutoDiff& b) { return a.value() > b.value(); }
  friend bool operator<=(const AutoDiff& a, const AutoDiff& b) { return a.value() <= b.value(); }
  friend bool operator>=(const AutoDiff& a, const AutoDiff& b) { return a.value() >= b.value(); }

 private:
  // ka a + kb b, an empty gradient standing for zero (of the other's size).
  static Gradient combine(const Gradient& a, double ka, const Gradient& b, double kb) {
    if (a.size() == 0) return b.size() == 0 ? Gradient() : Gradient(kb * b);
    if (b.size() == 0) return Gradient(ka * a);
    return Gradient(ka * a + kb * b);
  }
};

namespace number_detail {
// f applied to an interval through MPFI at 80 bits, rounded outward to doubles.
template <class Function>
kernels::Interval through_mpfi(const kernels::Interval& x, Function&& f) {
  mpfi_t a, r;
  mpfi_init2(a, 80);
  mpfi_init2(r, 80);
  mpfi_interv_d(a, x.lo, x.hi);
  f(r, a);
  mpfr_t bound;
  mpfr_init2(bound, 80);
  mpfi_get_left(bound, r);
  double lo = mpfr_get_d(bound, MPFR_RNDD);
  mpfi_get_right(bound, r);
  double hi = mpfr_get_d(bound, MPFR_RNDU);
  mpfr_clear(bound);
  mpfi_clear(a);
  mpfi_clear(r);
  return kernels::Interval(lo, hi);
}

/// through_mpfi of mpfi_sin / mpfi_cos, remembered per thread by the argument's two doubles
/// (number_traits.cpp): the same function of the same interval, so the same bounds. A parametric
/// model evaluated over many boxes asks few distinct arguments (gear-train.json's tolerance run:
/// 51 564 calls, 406 distinct; session 30).
kernels::Interval interval_sin(const kernels::Interval& x);
kernels::Interval interval_cos(const kernels::Interval& x);
}  // namespace number_detail

template <>
struct Arithmetic<kernels::Interval> {
  using I = kernels::Interval;
  static I constant(const Rational& q) { return I::enclose(q); }
  static I pi() { return I(std::numbers::pi, kernels::interval_detail::up(std::numbers::pi)); }
  static I sqrt(const I& x) { return kernels::sqrt(x); }
  static I sin(const I& x) { return number_detail::interval_sin(x); }
  static I cos(const I& x) { return number_detail::interval_cos(x); }
  static I tan(const I& x) { return number_detail::through_mpfi(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_tan(r, a); }); }
  static I atan2(const I& y, const I& x) {
    mpfi_t a, b, r;
    mpfi_init2(a, 80);
    mpfi_init2(b, 80);
    mpfi_init2(r, 80);
    mpfi_interv_d(a, y.lo, y.hi);
    mpfi_interv_d(b, x.lo, x.hi);
    mpfi_atan2(r, a, b);
    mpfr_t bound;
    mpfr_init2(bound, 80);
    mpfi_get_left(bound, r);
    double lo = mpfr_get_d(bound, MPFR_RNDD);
    mpfi_get_right(bound, r);
    double hi = mpfr_get_d(bound, MPFR_RNDU);
    mpfr_clear(bound);
    mpfi_clear(a);
    mpfi_clear(b);
    mpfi_clear(r);
    return I(lo, hi);
  }
  static I abs(const I& x) {
    if (x.lo >= 0) return x;
    if (x.hi <= 0) return -x;
    return I(0.0, std::max(-x.lo, x.hi));
  }
  static I min(const I& a, const I& b) { return I(std::min(a.lo, b.lo), std::min(a.hi, b.hi)); }
  static I max(const I& a, const I& b) { return I(std::max(a.lo, b.lo), std::max(a.hi, b.hi)); }
  static double value(const I& x) { return x.middle(); }
};

template <>
struct Arithmetic<AutoDiff> {
  static AutoDiff constant(const Rational& q) { return AutoDiff(q.get_d()); }   // empty gradient: zero
  static AutoDiff pi() { return AutoDiff(std::numbers::pi); }
  static AutoDiff sqrt(const AutoDiff& x) { return Eigen::sqrt(x); }
  static AutoDiff sin(const AutoDiff& x) { return Eigen::sin(x); }
  static AutoDiff cos(const AutoDiff& x) { return Eigen::cos(x); }
  static AutoDiff tan(const AutoDiff& x) { return AutoDiff(Eigen::sin(x)) / AutoDiff(Eigen::cos(x)); }
  static AutoDiff atan2(const AutoDiff& y, const AutoDiff& x) { return Eigen::atan2(y, x); }
  static AutoDiff abs(const AutoDiff& x) { return x.value() < 0 ? AutoDiff(-x) : x; }
  static AutoDiff min(const AutoDiff& a, const AutoDiff& b) { return a.value() <= b.value() ? a : b; }
  static AutoDiff max(const AutoDiff& a, const AutoDiff& b) { return a.value() >= b.value() ? a : b; }
  static double value(const AutoDiff& x) { return x.value(); }
};

}  // namespace hipair::model_detail
