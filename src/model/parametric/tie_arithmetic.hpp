// Two number types for the ties of ParametricModel::check_choices (session 64, tol64): a box whose
// margin reaches its bound exactly (a non-strict shape check ending on 0 through a formula such as
// "a - 0.1" or "a - b") is decided exactly, not by enclosures that can only straddle 0 there.
//  * PiRational: the exact value rational + rational * pi of a formula at one parameter vector (the
//    exact evaluator's form, model/expression.hpp Quantity), or "not exact" when the formula leaves
//    that form (a square root of a non-square, the sine of a non-multiple of pi, a product of two
//    multiples of pi); its sign decided by sign_of.
//  * MpfiJet: an MPFI enclosure of a formula and of its partial derivatives with respect to the
//    parameter deviations over a box (forward mode): where every partial derivative keeps one sign
//    over the box, the margin is smallest at one corner, whose exact value then decides the box.
#pragma once

#include "model/expression.hpp"
#include "model/interval.hpp"
#include "model/parametric/arithmetic.hpp"
#include "model/parametric/mpfi_arithmetic.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace hipair::model_detail {

struct PiRational {
  Rational rational, pi_multiple;
  bool exact = true;

  PiRational() = default;
  explicit PiRational(const Rational& q) : rational(q) {}
  PiRational(const Rational& q, const Rational& p, bool e = true) : rational(q), pi_multiple(p), exact(e) {}
  static PiRational inexact() { return PiRational(Rational(0), Rational(0), false); }
  bool is_rational() const { return exact && pi_multiple == 0; }

  /// The sign, decided exactly (sign_of on growing precisions); nullopt when not exact.
  std::optional<int> sign() const {
    if (!exact) return std::nullopt;
    Quantity q = Quantity::of(rational);
    q.pi_multiple = pi_multiple;
    for (mpfr_prec_t bits = 256; bits <= (mpfr_prec_t(1) << 17); bits *= 4) {
      PrecisionScope precision(bits);
      try {
        return sign_of(q, "", "");
      } catch (const PrecisionExhausted&) {
      }
    }
    return std::nullopt;
  }

  friend PiRational operator+(const PiRational& a, const PiRational& b) {
    if (!a.exact || !b.exact) return inexact();
    return {Rational(a.rational + b.rational), Rational(a.pi_multiple + b.pi_multiple)};
  }
  friend PiRational operator-(const PiRational& a, const PiRational& b) {
    if (!a.exact || !b.exact) return inexact();
    return {Rational(a.rational - b.rational), Rational(a.pi_multiple - b.pi_multiple)};
  }
  PiRational operator-() const { return exact ? PiRational(Rational(-rational), Rational(-pi_multiple)) : inexact(); }
  friend PiRational operator*(const PiRational& a, const PiRational& b) {
    if (!a.exact || !b.exact) return inexact();
    if (a.is_rational()) return {Rational(a.rational * b.rational), Rational(a.rational * b.pi_multiple)};
    if (b.is_rational()) return b * a;
    return inexact();   // pi^2
  }
  friend PiRational operator/(const PiRational& a, const PiRational& b) {
    if (!a.exact || !b.is_rational() || b.rational == 0) return inexact();
    return {Rational(a.rational / b.rational), Rational(a.pi_multiple / b.rational)};
  }
};

template <>
struct Arithmetic<PiRational> {
  using P = PiRational;
  static P constant(const Rational& q) { return P(q); }
  static P pi() { return P(Rational(0), Rational(1)); }
  static P sqrt(const P& x) {
    if (!x.is_rational() || x.rational < 0) return P::inexact();
    mpz_class n = x.rational.get_num(), d = x.rational.get_den();
    if (!mpz_perfect_square_p(n.get_mpz_t()) || !mpz_perfect_square_p(d.get_mpz_t())) return P::inexact();
    mpz_sqrt(n.get_mpz_t(), n.get_mpz_t());
    mpz_sqrt(d.get_mpz_t(), d.get_mpz_t());
    return P(Rational(n, d));
  }
  // sin, cos, tan exact at integer multiples of pi only
  static P sin(const P& x) { return whole_turns(x) ? P(Rational(0)) : P::inexact(); }
  static P cos(const P& x) {
    if (!whole_turns(x)) return P::inexact();
    return P(Rational(mpz_even_p(x.pi_multiple.get_num().get_mpz_t()) ? 1 : -1));
  }
  static P tan(const P& x) { return whole_turns(x) ? P(Rational(0)) : P::inexact(); }
  static P atan2(const P& y, const P& x) {
    const std::optional<int> sy = y.sign(), sx = x.sign();
    if (sy == 0 && sx && *sx > 0) return P(Rational(0));
    return P::inexact();
  }
  static P abs(const P& x) {
    const std::optional<int> s = x.sign();
    if (!s) return P::inexact();
    return *s < 0 ? -x : x;
  }
  static P min(const P& a, const P& b) {
    const std::optional<int> s = (a - b).sign();
    if (!s) return P::inexact();
    return *s <= 0 ? a : b;
  }
  static P max(const P& a, const P& b) {
    const std::optional<int> s = (a - b).sign();
    if (!s) return P::inexact();
    return *s >= 0 ? a : b;
  }

 private:
  static bool whole_turns(const P& x) { return x.exact && x.rational == 0 && x.pi_multiple.get_den() == 1; }
};

/// A value and its partial derivatives, MPFI enclosures over a box. `derivatives` empty: a
/// constant. A derivative the box leaves undefined (a square root reaching 0, atan2 across its
/// branch cut, abs/min/max at their kinks) is the whole line.
struct MpfiJet {
  Interval value;
  std::vector<Interval> derivatives;

  MpfiJet() = default;
  explicit MpfiJet(Interval v, std::vector<Interval> d = {}) : value(std::move(v)), derivatives(std::move(d)) {}

  static Interval whole_line() {
    Interval r;
    mpfr_set_inf(&r.get()->left, -1);
    mpfr_set_inf(&r.get()->right, 1);
    return r;
  }
  /// d_i(a) * f + d_i(b) * g, an empty gradient standing for 0
  static std::vector<Interval> combine(const MpfiJet& a, const Interval& f, const MpfiJet& b, const Interval& g) {
    const std::size_t n = std::max(a.derivatives.size(), b.derivatives.size());
    std::vector<Interval> d(n, Interval(Rational(0)));
    for (std::size_t i = 0; i < a.derivatives.size(); ++i) d[i] = d[i] + a.derivatives[i] * f;
    for (std::size_t i = 0; i < b.derivatives.size(); ++i) d[i] = d[i] + b.derivatives[i] * g;
    return d;
  }
  /// every derivative the whole line
  MpfiJet undefined_slope(Interval v) const {
    return MpfiJet(std::move(v), std::vector<Interval>(derivatives.size(), whole_line()));
  }

  friend MpfiJet operator+(const MpfiJet& a, const MpfiJet& b) {
    return MpfiJet(a.value + b.value, combine(a, Interval(Rational(1)), b, Interval(Rational(1))));
  }
  friend MpfiJet operator-(const MpfiJet& a, const MpfiJet& b) {
    return MpfiJet(a.value - b.value, combine(a, Interval(Rational(1)), b, Interval(Rational(-1))));
  }
  MpfiJet operator-() const { return MpfiJet(-value, combine(*this, Interval(Rational(-1)), MpfiJet(), Interval())); }
  friend MpfiJet operator*(const MpfiJet& a, const MpfiJet& b) {
    return MpfiJet(a.value * b.value, combine(a, b.value, b, a.value));
  }
  friend MpfiJet operator/(const MpfiJet& a, const MpfiJet& b) {
    const Interval q = a.value / b.value, inverse = Interval(Rational(1)) / b.value;
    return MpfiJet(q, combine(a, inverse, b, -(q * inverse)));
  }
};

template <>
struct Arithmetic<MpfiJet> {
  using J = MpfiJet;
  using A = Arithmetic<Interval>;
  static J constant(const Rational& q) { return J(Interval(q)); }
  static J pi() { return J(Interval::pi()); }
  static J sqrt(const J& x) {
    const Interval r = A::sqrt(x.value);
    if (!(mpfr_sgn(&x.value.get()->left) > 0)) return x.undefined_slope(r);
    return J(r, J::combine(x, Interval(Rational(1)) / (r + r), J(), Interval()));
  }
  static J sin(const J& x) { return J(A::sin(x.value), J::combine(x, A::cos(x.value), J(), Interval())); }
  static J cos(const J& x) { return J(A::cos(x.value), J::combine(x, -A::sin(x.value), J(), Interval())); }
  static J tan(const J& x) {
    const Interval t = A::tan(x.value);
    return J(t, J::combine(x, Interval(Rational(1)) + t * t, J(), Interval()));
  }
  static J atan2(const J& y, const J& x) {
    const Interval v = A::atan2(y.value, x.value);
    // the branch cut (y = 0, x <= 0) may cross the box: no derivative
    if (!(y.value.sign() != 0 || mpfr_sgn(&x.value.get()->left) > 0)) {
      J wide = y.derivatives.size() >= x.derivatives.size() ? y : x;
      return wide.undefined_slope(v);
    }
    const Interval r2 = x.value * x.value + y.value * y.value;
    return J(v, J::combine(y, x.value / r2, x, -(y.value / r2)));
  }
  static J abs(const J& x) {
    const int s = x.value.sign();
    if (s > 0) return x;
    if (s < 0) return -x;
    return x.undefined_slope(A::abs(x.value));
  }
  static J min(const J& a, const J& b) { return pick(a, b, true); }
  static J max(const J& a, const J& b) { return pick(a, b, false); }

 private:
  static J pick(const J& a, const J& b, bool smaller) {
    const int s = (a.value - b.value).sign();
    if (s != 0) return (s < 0) == smaller ? a : b;
    J wide = a.derivatives.size() >= b.derivatives.size() ? a : b;
    return wide.undefined_slope(smaller ? A::min(a.value, b.value) : A::max(a.value, b.value));
  }
};

}  // namespace hipair::model_detail
