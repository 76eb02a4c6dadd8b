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

/// Gradient-carrying scalar over all parameters.
using AutoDiff = Eigen::AutoDiffScalar<Eigen::VectorXd>;

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
}  // namespace number_detail

template <>
struct Arithmetic<kernels::Interval> {
  using I = kernels::Interval;
  static I constant(const Rational& q) { return I::enclose(q); }
  static I pi() { return I(std::numbers::pi, kernels::interval_detail::up(std::numbers::pi)); }
  static I sqrt(const I& x) { return kernels::sqrt(x); }
  static I sin(const I& x) { return number_detail::through_mpfi(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_sin(r, a); }); }
  static I cos(const I& x) { return number_detail::through_mpfi(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_cos(r, a); }); }
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
  static AutoDiff constant(const Rational& q) { return AutoDiff(q.get_d()); }
  static AutoDiff pi() { return AutoDiff(std::numbers::pi); }
  static AutoDiff sqrt(const AutoDiff& x) { return Eigen::sqrt(x); }
  static AutoDiff sin(const AutoDiff& x) { return Eigen::sin(x); }
  static AutoDiff cos(const AutoDiff& x) { return Eigen::cos(x); }
  static AutoDiff tan(const AutoDiff& x) { return AutoDiff(Eigen::sin(x) / Eigen::cos(x)); }
  static AutoDiff atan2(const AutoDiff& y, const AutoDiff& x) { return Eigen::atan2(y, x); }
  static AutoDiff abs(const AutoDiff& x) { return x.value() < 0 ? AutoDiff(-x) : x; }
  static AutoDiff min(const AutoDiff& a, const AutoDiff& b) { return a.value() <= b.value() ? a : b; }
  static AutoDiff max(const AutoDiff& a, const AutoDiff& b) { return a.value() >= b.value() ? a : b; }
  static double value(const AutoDiff& x) { return x.value(); }
};

}  // namespace hipair::model_detail
