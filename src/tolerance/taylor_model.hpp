// First-order Taylor models over a box (docs/tolerance.md "Taylor-model partial derivatives"):
// a function f of the box's variables x_i = c_i + h_i xi_i (xi_i in [-1, 1]) enclosed as
//   f(x) in C + sum_i A_i xi_i + R     for every xi in [-1, 1]^n,
// the constant C, the coefficients A_i and the remainder R certified intervals (outward-rounded
// doubles, kernels::Interval). Unlike plain interval evaluation over the box, the linear part
// keeps the correlation between the variables (x - x is exactly 0, and so is the part of a
// tooth's flank that a module and a pressure angle move in opposite directions); what is not
// linear goes to R, second order in the box's width. Elementary functions by Taylor's theorem
// at the constant with a Lagrange remainder over the operand's range; comparisons, |x|, min and
// max that the range cannot decide throw NumericError (the caller then keeps its interval
// enclosure), as second-order interval jets do.
#pragma once

#include "model/parametric/number_traits.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace hipair::tolerance_detail {

struct TaylorModel1 {
  using Interval = kernels::Interval;
  Interval constant{0};
  std::vector<Interval> coefficients;   ///< of xi_0, xi_1, ...; missing ones are 0
  Interval remainder{0};

  TaylorModel1() = default;
  TaylorModel1(int value) : constant(value) {}                  // NOLINT(google-explicit-constructor)
  explicit TaylorModel1(const Interval& value) : constant(value) {}
  TaylorModel1(const Interval& c, std::vector<Interval> a, const Interval& r)
      : constant(c), coefficients(std::move(a)), remainder(r) {}

  /// The variable ranging over [lo, hi] as the `index`-th of the box's variables: c + h xi with
  /// c = the middle, h its half width rounded up, so that c + h [-1, 1] contains [lo, hi].
  static TaylorModel1 over(double lo, double hi, std::size_t index) {
    double c = 0.5 * (lo + hi);
    if (!(c >= lo && c <= hi)) c = lo;   // overflow of lo + hi
    double h = std::max((Interval::point(hi) - Interval::point(c)).hi, (Interval::point(c) - Interval::point(lo)).hi);
    TaylorModel1 x(Interval::point(c));
    x.coefficients.assign(index + 1, Interval(0));
    x.coefficients[index] = Interval::point(h);
    return x;
  }

  /// sum_i A_i [-1, 1]
  Interval linear_range() const {
    if (coefficients.empty()) return Interval(0);
    double m = 0;   // sum of |A_i|, rounded up
    for (const Interval& a : coefficients) {
      double e = std::max(std::fabs(a.lo), std::fabs(a.hi));
      if (e != 0.0) m = kernels::interval_detail::up(m + e);
    }
    return m == 0.0 ? Interval(0) : Interval(-m, m);
  }
  /// An enclosure of f over the box.
  Interval range() const { return constant + linear_range() + remainder; }
  bool exact_zero() const {
    if (!(constant.lo == 0.0 && constant.hi == 0.0 && remainder.lo == 0.0 && remainder.hi == 0.0)) return false;
    for (const Interval& a : coefficients)
      if (!(a.lo == 0.0 && a.hi == 0.0)) return false;
    return true;
  }
  /// No linear part and no remainder: an interval constant.
  bool is_constant() const {
    if (!(remainder.lo == 0.0 && remainder.hi == 0.0)) return false;
    for (const Interval& a : coefficients)
      if (!(a.lo == 0.0 && a.hi == 0.0)) return false;
    return true;
  }
};

namespace taylor_detail {
using Interval = kernels::Interval;
inline bool zero(const Interval& x) { return x.lo == 0.0 && x.hi == 0.0; }
inline Interval plus(const Interval& a, const Interval& b) {
  if (zero(a)) return b;
  if (zero(b)) return a;
  return a + b;
}
inline Interval times(const Interval& a, const Interval& b) {
  if ((zero(a) && std::isfinite(b.lo) && std::isfinite(b.hi)) || (zero(b) && std::isfinite(a.lo) && std::isfinite(a.hi)))
    return Interval(0);
  return a * b;
}
inline Interval square(const Interval& x) {
  double m = std::max(std::fabs(x.lo), std::fabs(x.hi));
  double low = x.lo > 0 ? x.lo : (x.hi < 0 ? -x.hi : 0.0);
  Interval s = Interval::point(m) * Interval::point(m);
  Interval l = Interval::point(low) * Interval::point(low);
  return Interval(std::max(0.0, l.lo), s.hi);
}
// x scaled: coefficients and remainder times s, constant replaced by `constant`
inline TaylorModel1 scaled(const TaylorModel1& x, const Interval& s, const Interval& constant) {
  TaylorModel1 r(constant);
  r.coefficients.resize(x.coefficients.size());
  for (std::size_t i = 0; i < x.coefficients.size(); ++i) r.coefficients[i] = times(x.coefficients[i], s);
  r.remainder = times(x.remainder, s);
  return r;
}
// f(x) from f at the constant, f' at the constant and a bound on f''/2 over the range (and the
// constant): f(x) = f(c0) + f'(c0) (x - c0) + f''(eta)/2 (x - c0)^2, x - c0 = linear + remainder.
inline TaylorModel1 compose(const TaylorModel1& x, const Interval& f_c, const Interval& df_c, const Interval& half_d2f) {
  TaylorModel1 r = scaled(x, df_c, f_c);
  Interval d = x.linear_range() + x.remainder;
  if (!zero(d)) r.remainder = plus(r.remainder, half_d2f * square(d));
  return r;
}
// range of x together with its constant (the segment from c0 to any value lies in it)
inline Interval hull_range(const TaylorModel1& x) { return kernels::hull(x.range(), x.constant); }
}  // namespace taylor_detail

inline TaylorModel1 operator+(const TaylorModel1& a, const TaylorModel1& b) {
  using taylor_detail::plus;
  TaylorModel1 r(plus(a.constant, b.constant));
  r.coefficients.assign(std::max(a.coefficients.size(), b.coefficients.size()), kernels::Interval(0));
  for (std::size_t i = 0; i < a.coefficients.size(); ++i) r.coefficients[i] = a.coefficients[i];
  for (std::size_t i = 0; i < b.coefficients.size(); ++i) r.coefficients[i] = plus(r.coefficients[i], b.coefficients[i]);
  r.remainder = plus(a.remainder, b.remainder);
  return r;
}
namespace taylor_detail {
/// a = a + b in place, bit for bit (the coefficients a lacks are 0, as in operator+).
inline void add_to(TaylorModel1& a, const TaylorModel1& b) {
  a.constant = plus(a.constant, b.constant);
  if (a.coefficients.size() < b.coefficients.size()) a.coefficients.resize(b.coefficients.size(), Interval(0));
  for (std::size_t i = 0; i < b.coefficients.size(); ++i) a.coefficients[i] = plus(a.coefficients[i], b.coefficients[i]);
  a.remainder = plus(a.remainder, b.remainder);
}
}  // namespace taylor_detail
inline TaylorModel1 operator-(const TaylorModel1& a) {
  TaylorModel1 r(-a.constant);
  r.coefficients.resize(a.coefficients.size());
  for (std::size_t i = 0; i < a.coefficients.size(); ++i) r.coefficients[i] = -a.coefficients[i];
  r.remainder = -a.remainder;
  return r;
}
inline TaylorModel1 operator-(const TaylorModel1& a, const TaylorModel1& b) { return a + (-b); }
namespace taylor_detail {
/// Where a model's coefficients are not exact zeros (session 39): a contact curve's Taylor
/// models carry a coefficient for every variable of its jets, most of them exact zeros (a tooth's
/// flank does not move with the other gear's parameters: on the 100-parameter gear train 29 % of
/// the coefficients multiplied are not zero). One pass lists the others (up to `capacity`; past
/// that the support is not listed and the products take the dense loops) together with what the
/// products read of the model: whether it is a constant, its linear range (linear_range(), bit
/// for bit: a zero coefficient adds nothing to it).
struct Support {
  static constexpr std::size_t capacity = 64;
  std::uint32_t index[capacity];
  std::size_t count = 0;     ///< coefficients that are not exact zeros
  bool listed = true;        ///< every one of them is in `index`
  bool constant = false;     ///< is_constant()
  Interval linear{0};        ///< linear_range()
};
inline void scan(const TaylorModel1& x, Support& s) {
  double m = 0;   // as linear_range()
  for (std::size_t i = 0; i < x.coefficients.size(); ++i) {
    const Interval& a = x.coefficients[i];
    if (zero(a)) continue;   // (its |a| is 0: linear_range skips it too)
    if (s.count < Support::capacity) s.index[s.count] = static_cast<std::uint32_t>(i);
    else s.listed = false;
    ++s.count;
    double e = std::max(std::fabs(a.lo), std::fabs(a.hi));
    if (e != 0.0) m = kernels::interval_detail::up(m + e);
  }
  s.constant = zero(x.remainder) && s.count == 0;
  s.linear = m == 0.0 ? Interval(0) : Interval(-m, m);
}
inline bool finite(const Interval& x) { return std::isfinite(x.lo) && std::isfinite(x.hi); }
/// scaled(x, s, constant) with x's support `sx`: only the listed coefficients multiplied when s
/// is finite (times(0, s) is then exactly 0, the value the others keep), else scaled().
inline TaylorModel1 scaled_on(const TaylorModel1& x, const Support& sx, const Interval& s, const Interval& constant) {
  if (!sx.listed || !finite(s)) return scaled(x, s, constant);
  TaylorModel1 r(constant);
  r.coefficients.assign(x.coefficients.size(), Interval(0));
  for (std::size_t j = 0; j < sx.count; ++j) r.coefficients[sx.index[j]] = times(x.coefficients[sx.index[j]], s);
  r.remainder = times(x.remainder, s);
  return r;
}

/// A right-hand factor of products with what its products read of it computed once (the jets
/// multiply every partial derivative by the same value: jet.hpp): whether it is a constant, and
/// its linear part's range when it is not, and its support. multiply(a, factor(b)) == a * b ==
/// multiply_dense(a, factor(b)), bit for bit.
struct Factor {
  const TaylorModel1* model = nullptr;
  bool constant = false;
  Interval linear{0};
  Support support;
};
inline Factor factor(const TaylorModel1& b) {
  Factor f;
  f.model = &b;
  scan(b, f.support);
  f.constant = f.support.constant;
  if (!f.constant) f.linear = f.support.linear;
  return f;
}
inline TaylorModel1 multiply(const TaylorModel1& a, const Factor& f);
inline TaylorModel1 multiply(const TaylorModel1& a, const Support& sa, const Factor& f);
}  // namespace taylor_detail

inline TaylorModel1 operator*(const TaylorModel1& a, const TaylorModel1& b) {
  return taylor_detail::multiply(a, taylor_detail::factor(b));
}
namespace taylor_detail {
/// The remainder of a product of two models that are not constants, La and Lb their linear ranges:
/// La Lb + La Rb + Ra (Lb + Rb) + ca Rb + cb Ra.
inline Interval product_remainder(const TaylorModel1& a, const Interval& la, const TaylorModel1& b, const Interval& lb) {
  Interval rem = times(la, lb);
  rem = plus(rem, times(la, b.remainder));
  rem = plus(rem, times(a.remainder, lb + b.remainder));
  rem = plus(rem, times(a.constant, b.remainder));
  return plus(rem, times(b.constant, a.remainder));
}
/// The product on every coefficient (the form before session 39; the sparse form's fallback and
/// its tests' reference).
inline TaylorModel1 multiply_dense(const TaylorModel1& a, const Factor& f) {
  const TaylorModel1& b = *f.model;
  if (a.is_constant()) return scaled(b, a.constant, times(a.constant, b.constant));
  if (f.constant) return scaled(a, b.constant, times(a.constant, b.constant));
  // (ca + La + Ra)(cb + Lb + Rb) = ca cb + ca Lb + cb La + [La Lb + La Rb + Ra (Lb + Rb) + ca Rb + cb Ra]
  TaylorModel1 r(a.constant * b.constant);
  r.coefficients.assign(std::max(a.coefficients.size(), b.coefficients.size()), kernels::Interval(0));
  for (std::size_t i = 0; i < a.coefficients.size(); ++i) r.coefficients[i] = times(a.coefficients[i], b.constant);
  for (std::size_t i = 0; i < b.coefficients.size(); ++i)
    r.coefficients[i] = plus(r.coefficients[i], times(b.coefficients[i], a.constant));
  kernels::Interval la = a.linear_range(), lb = f.linear;
  r.remainder = product_remainder(a, la, b, lb);
  return r;
}
/// The product over the supports: a coefficient that is an exact zero in a (in b) contributes
/// times(0, cb) = 0 (times(0, ca) = 0) when cb (ca) is finite, so only the listed ones are
/// multiplied, in the same order, with the same operations; with an unbounded constant or a
/// support too long to list, the dense form. Bit for bit multiply_dense (tests/unit/
/// taylor_jet_prepared_test.cpp).
inline TaylorModel1 multiply(const TaylorModel1& a, const Support& sa, const Factor& f) {
  const TaylorModel1& b = *f.model;
  const Support& sb = f.support;
  if (sa.constant) return scaled_on(b, sb, a.constant, times(a.constant, b.constant));
  if (f.constant) return scaled_on(a, sa, b.constant, times(a.constant, b.constant));
  if (!sa.listed || !sb.listed || !finite(a.constant) || !finite(b.constant)) return multiply_dense(a, f);
  TaylorModel1 r(a.constant * b.constant);
  r.coefficients.assign(std::max(a.coefficients.size(), b.coefficients.size()), kernels::Interval(0));
  for (std::size_t j = 0; j < sa.count; ++j) r.coefficients[sa.index[j]] = times(a.coefficients[sa.index[j]], b.constant);
  for (std::size_t j = 0; j < sb.count; ++j) {
    Interval& c = r.coefficients[sb.index[j]];
    c = plus(c, times(b.coefficients[sb.index[j]], a.constant));
  }
  kernels::Interval la = sa.linear, lb = f.linear;
  r.remainder = product_remainder(a, la, b, lb);
  return r;
}
inline TaylorModel1 multiply(const TaylorModel1& a, const Factor& f) {
  Support sa;
  scan(a, sa);
  return multiply(a, sa, f);
}
}  // namespace taylor_detail
inline TaylorModel1 reciprocal(const TaylorModel1& x) {
  using kernels::Interval;
  if (x.is_constant()) return TaylorModel1(Interval(1) / x.constant);
  Interval u = taylor_detail::hull_range(x);
  if (u.lo <= 0.0 && u.hi >= 0.0) throw NumericError("division by a Taylor model whose range contains 0");
  Interval inv_c = Interval(1) / x.constant;
  Interval inv_u = Interval(1) / u;
  // (1/x)' = -1/x^2, (1/x)''/2 = 1/x^3
  return taylor_detail::compose(x, inv_c, -(inv_c * inv_c), inv_u * inv_u * inv_u);
}
inline TaylorModel1 operator/(const TaylorModel1& a, const TaylorModel1& b) {
  if (b.is_constant()) {
    // exact division of every component by the constant interval
    TaylorModel1 r(a.constant / b.constant);
    r.coefficients.resize(a.coefficients.size());
    for (std::size_t i = 0; i < a.coefficients.size(); ++i)
      r.coefficients[i] = taylor_detail::zero(a.coefficients[i]) ? kernels::Interval(0) : a.coefficients[i] / b.constant;
    r.remainder = taylor_detail::zero(a.remainder) ? kernels::Interval(0) : a.remainder / b.constant;
    return r;
  }
  return a * reciprocal(b);
}

}  // namespace hipair::tolerance_detail

namespace hipair::model_detail {

template <>
struct Arithmetic<tolerance_detail::TaylorModel1> {
  using T = tolerance_detail::TaylorModel1;
  using I = kernels::Interval;
  using A = Arithmetic<I>;
  static T constant(const Rational& q) { return T(A::constant(q)); }
  static T pi() { return T(A::pi()); }
  static T sqrt(const T& x) {
    if (x.is_constant()) return T(A::sqrt(x.constant));
    I u = tolerance_detail::taylor_detail::hull_range(x);
    if (!(u.lo > 0.0)) throw NumericError("square root of a Taylor model whose range reaches 0");
    I r_c = A::sqrt(x.constant);
    I r_u = A::sqrt(u);
    // sqrt' = 1/(2 sqrt x), sqrt''/2 = -1/(8 x sqrt x)
    return tolerance_detail::taylor_detail::compose(x, r_c, I(1) / (I(2) * r_c), -(I(1) / (I(8) * u * r_u)));
  }
  static T sin(const T& x) {
    if (x.is_constant()) return T(A::sin(x.constant));
    I u = tolerance_detail::taylor_detail::hull_range(x);
    return tolerance_detail::taylor_detail::compose(x, A::sin(x.constant), A::cos(x.constant), -(A::sin(u) * I(1) / I(2)));
  }
  static T cos(const T& x) {
    if (x.is_constant()) return T(A::cos(x.constant));
    I u = tolerance_detail::taylor_detail::hull_range(x);
    return tolerance_detail::taylor_detail::compose(x, A::cos(x.constant), -A::sin(x.constant), -(A::cos(u) * I(1) / I(2)));
  }
  static T tan(const T& x) { return sin(x) / cos(x); }
  /// atan2 over a range of (x, y) that avoids the origin and the cut along the negative x-axis
  /// (where atan2 jumps by 2 pi: no Taylor model encloses it); throws otherwise.
  static T atan2(const T& y, const T& x) {
    using tolerance_detail::taylor_detail::hull_range;
    using tolerance_detail::taylor_detail::square;
    using tolerance_detail::taylor_detail::times;
    if (x.is_constant() && y.is_constant()) return T(A::atan2(y.constant, x.constant));
    I X = hull_range(x), Y = hull_range(y);
    if (X.lo <= 0.0 && Y.lo <= 0.0 && Y.hi >= 0.0) throw NumericError("atan2 of a Taylor model whose range meets the cut");
    I r2c = x.constant * x.constant + y.constant * y.constant;
    I dy = x.constant / r2c, dx = -(y.constant / r2c);   // d atan2 / dy, d atan2 / dx at the constant
    T r = tolerance_detail::taylor_detail::scaled(y, dy, A::atan2(y.constant, x.constant));
    T rx = tolerance_detail::taylor_detail::scaled(x, dx, I(0));
    r = r + rx;
    // Lagrange remainder: (1/2) [t_xx ex^2 + 2 t_xy ex ey + t_yy ey^2] over the range box, with
    // t_xx = 2xy/r^4 = -t_yy, t_xy = (y^2 - x^2)/r^4.
    I ex = x.linear_range() + x.remainder, ey = y.linear_range() + y.remainder;
    I r2 = square(X) + square(Y);
    I r4 = r2 * r2;
    I txx = I(2) * X * Y / r4;   // (over the box: every product of the ranges)
    I txy = (square(Y) - square(X)) / r4;
    I second = times(txx, square(ex) - square(ey)) * I(1) / I(2) + times(txy, ex * ey);
    r.remainder = r.remainder + second;
    return r;
  }
  static T abs(const T& x) {
    I u = x.range();
    if (u.lo >= 0.0) return x;
    if (u.hi <= 0.0) return -x;
    throw NumericError("|x| of a Taylor model whose range contains 0");
  }
  static T extremum(const T& a, const T& b, bool minimum) {
    T d = a - b;
    I u = d.range();
    if (u.hi <= 0.0) return minimum ? a : b;
    if (u.lo >= 0.0) return minimum ? b : a;
    throw NumericError("min/max of Taylor models that may cross");
  }
  static T min(const T& a, const T& b) { return extremum(a, b, true); }
  static T max(const T& a, const T& b) { return extremum(a, b, false); }
  static double value(const T& x) { return x.constant.middle(); }
};

}  // namespace hipair::model_detail
