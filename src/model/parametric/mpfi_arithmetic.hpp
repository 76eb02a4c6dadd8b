// The parametric formulas over MPFI enclosures (model/interval.hpp, at the thread's working
// precision, PrecisionScope): the certified box check of the templates' rules (session 62,
// ParametricModel::check_choices) evaluates the parameters, the slots and the rules' margins in
// it when the doubles' enclosures cannot decide a margin (a box 2^-k from a rule's bound, lengths
// of 1e-300 or 1e400 mm). No overflow or underflow: MPFR's exponents reach far beyond them.
#pragma once

#include "model/interval.hpp"
#include "model/parametric/arithmetic.hpp"

#include <mpfi.h>

namespace hipair::model_detail {

template <>
struct Arithmetic<Interval> {
  using I = Interval;
  static I constant(const Rational& q) { return I(q); }
  static I pi() { return I::pi(); }
  /// A square root of an interval reaching below 0 is the whole line (undecided), never a part
  /// of it: a margin reading it is then decided on smaller boxes or not at all.
  static I sqrt(const I& x) { return apply(x, nonnegative(x), mpfi_sqrt); }
  static I sin(const I& x) { return apply(x, true, mpfi_sin); }
  static I cos(const I& x) { return apply(x, true, mpfi_cos); }
  static I tan(const I& x) { return apply(x, true, mpfi_tan); }
  static I atan2(const I& y, const I& x) {
    I result;
    mpfi_atan2(result.get(), y.get(), x.get());
    return result;
  }
  static I abs(const I& x) { return apply(x, true, mpfi_abs); }
  static I min(const I& a, const I& b) {
    I result;
    mpfr_min(&result.get()->left, &a.get()->left, &b.get()->left, MPFR_RNDD);
    mpfr_min(&result.get()->right, &a.get()->right, &b.get()->right, MPFR_RNDU);
    return result;
  }
  static I max(const I& a, const I& b) {
    I result;
    mpfr_max(&result.get()->left, &a.get()->left, &b.get()->left, MPFR_RNDD);
    mpfr_max(&result.get()->right, &a.get()->right, &b.get()->right, MPFR_RNDU);
    return result;
  }

 private:
  static bool nonnegative(const I& x) { return x.is_bounded() && mpfr_sgn(&x.get()->left) >= 0; }
  template <class Function>
  static I apply(const I& x, bool defined, Function f) {
    I result;
    if (!defined) {
      mpfr_set_inf(&result.get()->left, -1);
      mpfr_set_inf(&result.get()->right, 1);
      return result;
    }
    f(result.get(), x.get());
    return result;
  }
};

}  // namespace hipair::model_detail
