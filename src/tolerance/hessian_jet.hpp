// A second-order forward-mode jet over certified intervals: a value, its gradient and its
// Hessian with respect to a fixed set of variables, the Hessian stored once per unordered pair
// (packed lower triangle). With interval components it encloses a function, its partial
// derivatives and its second partial derivatives over a whole box of the variables: what the
// second-order form of CurveSolver::tighten_partials needs (docs/tolerance.md).
//
// It replaces the nested Jet<Jet<Interval>>, which computes the same enclosures by the same
// chain rule but holds every second derivative twice (∂a∂b and ∂b∂a), one allocation per
// gradient entry, and each elementary function's derivative through a nested call: for the
// 15-variable Geneva contact functions about 2.3 times the interval products per operation
// and four MPFI calls per sine where one sine and one cosine suffice.
#pragma once

#include "kernels/interval.hpp"
#include "model/parametric/number_traits.hpp"
#include "tolerance/jet.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace hipair::tolerance_detail {

struct HessianJet {
  using Interval = kernels::Interval;
  Interval value{0};
  std::vector<Interval> gradient;   ///< empty: all first partial derivatives 0
  /// Packed lower triangle, (i, j) with j <= i at i (i + 1) / 2 + j, for the first
  /// gradient.size() variables; empty: all second partial derivatives 0.
  std::vector<Interval> hessian;

  HessianJet() = default;
  HessianJet(int v) : value(v) {}                          // NOLINT(google-explicit-constructor)
  explicit HessianJet(const Interval& v) : value(v) {}
  /// A first-order jet with zero second derivatives.
  explicit HessianJet(const Jet<Interval>& first) : value(first.value), gradient(first.gradient) {}

  static HessianJet variable(const Interval& v, std::size_t index, std::size_t count) {
    HessianJet x(v);
    x.gradient.assign(count, Interval(0));
    x.gradient[index] = Interval(1);
    return x;
  }
  static std::size_t packed(std::size_t i, std::size_t j) { return i >= j ? i * (i + 1) / 2 + j : j * (j + 1) / 2 + i; }
  Interval partial(std::size_t i) const { return i < gradient.size() ? gradient[i] : Interval(0); }
  Interval second(std::size_t i, std::size_t j) const {
    std::size_t p = packed(i, j);
    return p < hessian.size() ? hessian[p] : Interval(0);
  }
};

namespace hessian_detail {
using kernels::Interval;
using jet_detail::exact_zero;
using jet_detail::finite;
using jet_detail::plus;

// x y, exactly 0 when either is an exact zero and the other finite (a derivative with respect
// to a variable the quantity does not depend on stays exactly 0 through every operation)
// (and exactly x when y is exactly 1: a product's cross terms)
inline Interval times(const Interval& x, const Interval& y) {
  if ((exact_zero(x) && finite(y)) || (exact_zero(y) && finite(x))) return Interval(0);
  if (y.lo == 1.0 && y.hi == 1.0) return x;
  return x * y;
}

// The derivatives of a function of one argument at the argument's value: f', f''.
struct Unary {
  Interval d1, d2;
};
// Of a function of two arguments: f_u, f_v, f_uu, f_uv, f_vv.
struct Binary {
  Interval du, dv, duu, duv, dvv;
};

inline HessianJet chain(const HessianJet& u, const Interval& value, const Unary& d) {
  HessianJet r(value);
  std::size_t n = u.gradient.size();
  if (n == 0) return r;
  r.gradient.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.gradient[i] = times(u.gradient[i], d.d1);
  // f'' u_i u_j + f' u_ij
  r.hessian.assign(n * (n + 1) / 2, Interval(0));
  for (std::size_t i = 0, p = 0; i < n; ++i) {
    Interval scaled = times(u.gradient[i], d.d2);
    for (std::size_t j = 0; j <= i; ++j, ++p) r.hessian[p] = times(u.gradient[j], scaled);
  }
  for (std::size_t p = 0; p < u.hessian.size(); ++p) r.hessian[p] = plus(r.hessian[p], times(u.hessian[p], d.d1));
  return r;
}

inline HessianJet chain(const HessianJet& u, const HessianJet& v, const Interval& value, const Binary& d) {
  HessianJet r(value);
  std::size_t n = std::max(u.gradient.size(), v.gradient.size());
  if (n == 0) return r;
  r.gradient.assign(n, Interval(0));
  for (std::size_t i = 0; i < u.gradient.size(); ++i) r.gradient[i] = times(u.gradient[i], d.du);
  for (std::size_t i = 0; i < v.gradient.size(); ++i) r.gradient[i] = plus(r.gradient[i], times(v.gradient[i], d.dv));
  r.hessian.assign(n * (n + 1) / 2, Interval(0));
  // f_uu u_i u_j + f_uv (u_i v_j + v_i u_j) + f_vv v_i v_j, each term skipped where its
  // coefficient is an exact zero (a product's f_uu and f_vv)
  auto add_outer = [&](const std::vector<Interval>& a, const std::vector<Interval>& b, const Interval& c, bool symmetric) {
    if (exact_zero(c) || a.empty() || b.empty()) return;
    for (std::size_t i = 0, p = 0; i < n; ++i) {
      Interval ai = i < a.size() ? times(a[i], c) : Interval(0);
      Interval bi = !symmetric && i < b.size() ? times(b[i], c) : Interval(0);
      for (std::size_t j = 0; j <= i; ++j, ++p) {
        Interval t = j < b.size() ? times(b[j], ai) : Interval(0);
        if (!symmetric && j < a.size()) t = plus(t, times(a[j], bi));
        r.hessian[p] = plus(r.hessian[p], t);
      }
    }
  };
  add_outer(u.gradient, u.gradient, d.duu, true);
  add_outer(u.gradient, v.gradient, d.duv, false);
  add_outer(v.gradient, v.gradient, d.dvv, true);
  for (std::size_t p = 0; p < u.hessian.size(); ++p) r.hessian[p] = plus(r.hessian[p], times(u.hessian[p], d.du));
  for (std::size_t p = 0; p < v.hessian.size(); ++p) r.hessian[p] = plus(r.hessian[p], times(v.hessian[p], d.dv));
  return r;
}

// f(u, v) with its partial derivatives given as first-order jets c_u = f_u(u, v), c_v = f_v(u, v)
// (their gradients by the chain rule through u and v): the gradient u_i c_u + v_i c_v and
//   H_ij = u_ij c_u + u_i (c_u)_j + v_ij c_v + v_i (c_v)_j,
// the nested jets' form, enclosed for (i, j) and for (j, i) and intersected (both hold).
inline HessianJet chain(const HessianJet& u, const HessianJet& v, const Interval& value, const Jet<Interval>& cu,
                        const Jet<Interval>& cv) {
  HessianJet r(value);
  std::size_t n = std::max(u.gradient.size(), v.gradient.size());
  if (n == 0) return r;
  r.gradient.assign(n, Interval(0));
  for (std::size_t i = 0; i < u.gradient.size(); ++i) r.gradient[i] = times(u.gradient[i], cu.value);
  for (std::size_t i = 0; i < v.gradient.size(); ++i) r.gradient[i] = plus(r.gradient[i], times(v.gradient[i], cv.value));
  r.hessian.assign(n * (n + 1) / 2, Interval(0));
  for (std::size_t i = 0, p = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j, ++p) {
      Interval second = plus(times(u.second(i, j), cu.value), times(v.second(i, j), cv.value));
      Interval ij = plus(second, plus(times(u.partial(i), cu.partial(j)), times(v.partial(i), cv.partial(j))));
      Interval ji = plus(second, plus(times(u.partial(j), cu.partial(i)), times(v.partial(j), cv.partial(i))));
      Interval both(std::max(ij.lo, ji.lo), std::min(ij.hi, ji.hi));
      r.hessian[p] = both.lo <= both.hi ? both : ij;
    }
  return r;
}

// a + s b, s = 1 or -1 (exact)
inline HessianJet add(const HessianJet& a, const HessianJet& b, bool subtract) {
  HessianJet r(subtract ? a.value - b.value : a.value + b.value);
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  r.gradient.assign(n, Interval(0));
  for (std::size_t i = 0; i < a.gradient.size(); ++i) r.gradient[i] = a.gradient[i];
  for (std::size_t i = 0; i < b.gradient.size(); ++i) r.gradient[i] = plus(r.gradient[i], subtract ? -b.gradient[i] : b.gradient[i]);
  std::size_t m = std::max(a.hessian.size(), b.hessian.size());
  if (m == 0) return r;
  r.hessian.assign(n * (n + 1) / 2, Interval(0));
  for (std::size_t p = 0; p < a.hessian.size(); ++p) r.hessian[p] = a.hessian[p];
  for (std::size_t p = 0; p < b.hessian.size(); ++p) r.hessian[p] = plus(r.hessian[p], subtract ? -b.hessian[p] : b.hessian[p]);
  return r;
}
}  // namespace hessian_detail

inline HessianJet operator+(const HessianJet& a, const HessianJet& b) { return hessian_detail::add(a, b, false); }
inline HessianJet operator-(const HessianJet& a, const HessianJet& b) { return hessian_detail::add(a, b, true); }
inline HessianJet operator-(const HessianJet& a) {
  HessianJet r(-a.value);
  r.gradient.reserve(a.gradient.size());
  for (const kernels::Interval& g : a.gradient) r.gradient.push_back(-g);
  r.hessian.reserve(a.hessian.size());
  for (const kernels::Interval& h : a.hessian) r.hessian.push_back(-h);
  return r;
}
inline HessianJet operator*(const HessianJet& a, const HessianJet& b) {
  using kernels::Interval;
  return hessian_detail::chain(a, b, a.value * b.value, {b.value, a.value, Interval(0), Interval(1), Interval(0)});
}
// q = a / b by the derivatives of q b = a, q's own gradient inside its Hessian:
//   q_i = (a_i - q b_i) / b,  q_ij = (a_ij - q b_ij - (b_i q_j + b_j q_i)) / b,
// the grouping of the nested jets, which keeps the cancellation in a_i - q b_i (a and b
// correlated) that the expanded form -(a_i b_j + b_i a_j) / b^2 + 2 q b_i b_j / b^2 loses.
inline HessianJet operator/(const HessianJet& a, const HessianJet& b) {
  using kernels::Interval;
  using hessian_detail::plus;
  using hessian_detail::times;
  Interval q = a.value / b.value;
  Interval inverse = Interval(1) / b.value;
  Interval minus_q_inverse = -(q * inverse);
  HessianJet r(q);
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  if (n == 0) return r;
  r.gradient.assign(n, Interval(0));
  for (std::size_t i = 0; i < a.gradient.size(); ++i) r.gradient[i] = times(a.gradient[i], inverse);
  for (std::size_t i = 0; i < b.gradient.size(); ++i) r.gradient[i] = plus(r.gradient[i], times(b.gradient[i], minus_q_inverse));
  r.hessian.assign(n * (n + 1) / 2, Interval(0));
  for (std::size_t p = 0; p < a.hessian.size(); ++p) r.hessian[p] = times(a.hessian[p], inverse);
  for (std::size_t p = 0; p < b.hessian.size(); ++p) r.hessian[p] = plus(r.hessian[p], times(b.hessian[p], minus_q_inverse));
  if (!b.gradient.empty()) {
    Interval minus_inverse = -inverse;
    for (std::size_t i = 0, p = 0; i < n; ++i) {
      Interval bi = b.partial(i);
      for (std::size_t j = 0; j <= i; ++j, ++p) {
        Interval t = plus(times(bi, r.gradient[j]), times(b.partial(j), r.gradient[i]));
        r.hessian[p] = plus(r.hessian[p], times(t, minus_inverse));
      }
    }
  }
  return r;
}

}  // namespace hipair::tolerance_detail

namespace hipair::model_detail {

template <>
struct Arithmetic<tolerance_detail::HessianJet> {
  using J = tolerance_detail::HessianJet;
  using I = kernels::Interval;
  using A = Arithmetic<I>;
  static J constant(const Rational& q) { return J(A::constant(q)); }
  static J pi() { return J(A::pi()); }
  static J sqrt(const J& x) {
    I r = A::sqrt(x.value);
    I d1 = I(1) / (I(2) * r);
    // (x^(1/2))'' = -(1/4) x^(-3/2) = -f' / (2x)
    return tolerance_detail::hessian_detail::chain(x, r, {d1, -(d1 / (I(2) * x.value))});
  }
  static J sin(const J& x) {
    I s = A::sin(x.value), c = A::cos(x.value);
    return tolerance_detail::hessian_detail::chain(x, s, {c, -s});
  }
  static J cos(const J& x) {
    I s = A::sin(x.value), c = A::cos(x.value);
    return tolerance_detail::hessian_detail::chain(x, c, {-s, -c});
  }
  static J tan(const J& x) { return sin(x) / cos(x); }
  static J atan2(const J& y, const J& x) {
    // d/dy = x / r2, d/dx = -y / r2 as first-order jets (r2 = x^2 + y^2), as the nested jets
    // form them: the quotients keep the cancellations the expanded second derivatives
    // -2xy / r2^2, (y^2 - x^2) / r2^2 lose
    // across the branch cut (y = 0, x <= 0) atan2 jumps: no second derivative (the caller
    // falls back to first order, whose partials are then the whole line)
    if (tolerance_detail::jet_detail::meets_cut(y.value, x.value))
      throw NumericError("atan2 is not differentiable over the box (its branch cut crosses it)");
    using F = tolerance_detail::Jet<I>;
    F yf(y.value, y.gradient), xf(x.value, x.gradient);
    F r2 = xf * xf + yf * yf;
    return tolerance_detail::hessian_detail::chain(y, x, A::atan2(y.value, x.value), xf / r2, -(yf / r2));
  }
  // |x|, min and max have no second derivative where the argument may vanish or the two may
  // cross: undecided there (the caller falls back to first order)
  static J abs(const J& x) {
    if (x.value.lo >= 0) return x;
    if (x.value.hi <= 0) return -x;
    throw NumericError("|x| is not twice differentiable over the box");
  }
  static J extremum(const J& a, const J& b, bool minimum) {
    if (a.value.hi <= b.value.lo) return minimum ? a : b;
    if (b.value.hi <= a.value.lo) return minimum ? b : a;
    throw NumericError("min/max is not twice differentiable over the box");
  }
  static J min(const J& a, const J& b) { return extremum(a, b, true); }
  static J max(const J& a, const J& b) { return extremum(a, b, false); }
  static double value(const J& x) { return A::value(x.value); }
};

}  // namespace hipair::model_detail
