// A forward-mode jet over a scalar type S: a value and its gradient with respect to a fixed
// set of variables, every component of type S. With S = kernels::Interval it encloses a
// function and its partial derivatives over a whole box of the variables (the certified
// mean-value form of docs/tolerance.md); Eigen's AutoDiffScalar serves the double case.
#pragma once

#include "model/parametric/number_traits.hpp"
#include "tolerance/taylor_model.hpp"

#include <hipair/error.hpp>

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace hipair::tolerance_detail {

template <class S>
struct Jet {
  S value{0};
  std::vector<S> gradient;   ///< empty: a constant (all partial derivatives 0)

  Jet() = default;
  Jet(int v) : value(S(v)) {}                      // NOLINT(google-explicit-constructor)
  explicit Jet(const S& v) : value(v) {}
  Jet(const S& v, std::vector<S> g) : value(v), gradient(std::move(g)) {}

  static Jet variable(const S& v, std::size_t index, std::size_t count) {
    std::vector<S> g(count, S(0));
    g[index] = S(1);
    return Jet(v, std::move(g));
  }
  S partial(std::size_t i) const { return i < gradient.size() ? gradient[i] : S(0); }
};

namespace jet_detail {
// True when the box of (x, y) may meet atan2's branch cut, the half-line y = 0, x <= 0 (the
// origin included), where atan2 jumps by 2 pi and has no derivative.
inline bool meets_cut(const kernels::Interval& y, const kernels::Interval& x) {
  return y.lo <= 0.0 && y.hi >= 0.0 && !(x.lo > 0.0);
}
// The enclosure of a (possibly nested) jet's value.
inline kernels::Interval enclosure(const kernels::Interval& x) { return x; }
inline kernels::Interval enclosure(const TaylorModel1& x) { return x.range(); }
template <class S>
kernels::Interval enclosure(const Jet<S>& x) {
  return enclosure(x.value);
}
// Exact zeros of interval gradients (a partial derivative that is exactly 0: a variable the
// quantity does not depend on) stay exact: 0 x f is exactly 0 for a finite f, and 0 + x is
// exactly x, so neither needs the one-ulp outward widening, and the enclosures are the same
// as before or tighter (by those widenings), never looser. Without it every zero became
// [-denorm_min, denorm_min] after one operation and was multiplied on through every later one.
template <class S>
bool exact_zero(const S& x) {
  if constexpr (std::is_same_v<S, kernels::Interval>) return x.lo == 0.0 && x.hi == 0.0;
  else if constexpr (std::is_same_v<S, TaylorModel1>) return x.exact_zero();
  else return false;
}
template <class S>
bool finite(const S& x) {
  if constexpr (std::is_same_v<S, kernels::Interval>) return std::isfinite(x.lo) && std::isfinite(x.hi);
  else if constexpr (std::is_same_v<S, TaylorModel1>) {
    kernels::Interval r = x.range();
    return std::isfinite(r.lo) && std::isfinite(r.hi);
  } else return false;
}
// x f, exactly 0 when x is an exact zero and f is finite
template <class S>
S times(const S& x, const S& f, bool f_finite) {
  if (f_finite && exact_zero(x)) return S(0);
  return x * f;
}
// x + y, exact when either is an exact zero
template <class S>
S plus(const S& x, const S& y) {
  if (exact_zero(x)) return y;
  if (exact_zero(y)) return x;
  return x + y;
}
// a.gradient * fa + b.gradient * fb
template <class S>
std::vector<S> combine_plain(const Jet<S>& a, const S& fa, const Jet<S>& b, const S& fb) {
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<S> g(n, S(0));
  bool fa_finite = finite(fa), fb_finite = finite(fb);
  for (std::size_t i = 0; i < a.gradient.size(); ++i) g[i] = times(a.gradient[i], fa, fa_finite);
  for (std::size_t i = 0; i < b.gradient.size(); ++i) g[i] = plus(g[i], times(b.gradient[i], fb, fb_finite));
  return g;
}
template <class S>
std::vector<S> scaled_plain(const Jet<S>& a, const S& f) {
  std::vector<S> g(a.gradient.size());
  bool f_finite = finite(f);
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = times(a.gradient[i], f, f_finite);
  return g;
}
// a.gradient + b.gradient
template <class S>
std::vector<S> sum_plain(const Jet<S>& a, const Jet<S>& b) {
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<S> g(n, S(0));
  for (std::size_t i = 0; i < a.gradient.size(); ++i) g[i] = a.gradient[i];
  for (std::size_t i = 0; i < b.gradient.size(); ++i) g[i] = plus(g[i], b.gradient[i]);
  return g;
}

// Taylor-model jets (the assembly chains' partial derivatives, the bulk of their certified
// band): every partial derivative is multiplied by the same factor, so what a product reads of
// that factor (taylor_detail::Factor) is computed once per jet operation, sums accumulate in
// place and operands are not copied first. Bit for bit the *_plain forms above (the same
// operations on the same operands in the same order; plus() returns the same operand or sum):
// tests/unit/taylor_jet_test.cpp compares them.
// (x's support listed once: it answers exact_zero() and what the product reads of x)
inline TaylorModel1 times(const TaylorModel1& x, const taylor_detail::Factor& f, bool f_finite) {
  taylor_detail::Support sx;
  taylor_detail::scan(x, sx);
  if (f_finite && sx.constant && taylor_detail::zero(x.constant)) return TaylorModel1(0);   // x.exact_zero()
  return taylor_detail::multiply(x, sx, f);
}
// g = plus(g, t)
inline void accumulate(TaylorModel1& g, TaylorModel1&& t) {
  if (g.exact_zero()) g = std::move(t);
  else if (!t.exact_zero()) taylor_detail::add_to(g, t);
}
template <class S>
std::vector<S> combine(const Jet<S>& a, const S& fa, const Jet<S>& b, const S& fb) {
  if constexpr (!std::is_same_v<S, TaylorModel1>) {
    return combine_plain(a, fa, b, fb);
  } else {
    std::size_t n = std::max(a.gradient.size(), b.gradient.size());
    std::vector<S> g;
    g.reserve(n);
    bool fa_finite = finite(fa), fb_finite = finite(fb);
    const taylor_detail::Factor pa = taylor_detail::factor(fa), pb = taylor_detail::factor(fb);
    for (std::size_t i = 0; i < a.gradient.size(); ++i) g.push_back(times(a.gradient[i], pa, fa_finite));
    g.resize(n, S(0));
    for (std::size_t i = 0; i < b.gradient.size(); ++i) accumulate(g[i], times(b.gradient[i], pb, fb_finite));
    return g;
  }
}
template <class S>
std::vector<S> scaled(const Jet<S>& a, const S& f) {
  if constexpr (!std::is_same_v<S, TaylorModel1>) {
    return scaled_plain(a, f);
  } else {
    std::vector<S> g(a.gradient.size());
    bool f_finite = finite(f);
    const taylor_detail::Factor pf = taylor_detail::factor(f);
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = times(a.gradient[i], pf, f_finite);
    return g;
  }
}
template <class S>
std::vector<S> sum(const Jet<S>& a, const Jet<S>& b) {
  if constexpr (!std::is_same_v<S, TaylorModel1>) {
    return sum_plain(a, b);
  } else {
    // plus(a_i, b_i) where both are present, else a_i, or plus(0, b_i) = b_i
    std::size_t n = std::max(a.gradient.size(), b.gradient.size());
    std::vector<S> g(n, S(0));
    for (std::size_t i = 0; i < n; ++i) {
      if (i < a.gradient.size() && i < b.gradient.size()) g[i] = plus(a.gradient[i], b.gradient[i]);
      else g[i] = i < a.gradient.size() ? a.gradient[i] : b.gradient[i];
    }
    return g;
  }
}
// Sums and differences of Taylor-model jets that are temporaries (session 40): the kernels'
// expressions (a.x * b.y - a.y * b.x, ...) add and subtract jets just made, and the result is
// built in a temporary's own storage instead of new vectors and models. Bit for bit the forms
// on const operands (sum(), scaled(a, -1)): the same operations on the same operands in the
// same order (tests/unit/taylor_jet_prepared_test.cpp).
// a = plus(a, b) for one partial, b's entry moved or copied (B: const TaylorModel1& or TaylorModel1&&)
template <class B>
void add_partial(TaylorModel1& a, B&& b) {
  if (a.exact_zero()) a = std::forward<B>(b);                 // plus(0, b) = b
  else if (!b.exact_zero()) taylor_detail::add_to(a, b);      // a + b (plus(a, 0) = a)
}
// a = sum(a, b): the partials b has beyond a are b's, those a has beyond b stay
template <class V>
void add_gradient(std::vector<TaylorModel1>& a, V&& b) {
  std::size_t common = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < common; ++i) {
    if constexpr (std::is_rvalue_reference_v<V&&>) add_partial(a[i], std::move(b[i]));
    else add_partial(a[i], b[i]);
  }
  for (std::size_t i = common; i < b.size(); ++i) {
    if constexpr (std::is_rvalue_reference_v<V&&>) a.push_back(std::move(b[i]));
    else a.push_back(b[i]);
  }
}
// x = times(x, f, f_finite) in x's storage where the product is x scaled by f's constant
// (scaled_on: the coefficients that are exact zeros become Interval(0), the others times(c, s),
// for a listed support and for the dense loop alike when s is finite); otherwise the product
// made anew
inline void times_in_place(TaylorModel1& x, const taylor_detail::Factor& f, bool f_finite) {
  using taylor_detail::zero;
  taylor_detail::Support sx;
  taylor_detail::scan(x, sx);
  if (f_finite && sx.constant && zero(x.constant)) {   // x.exact_zero()
    x = TaylorModel1(0);
    return;
  }
  const kernels::Interval& s = f.model->constant;
  if (sx.constant || !f.constant || !taylor_detail::finite(s)) {
    x = taylor_detail::multiply(x, sx, f);
    return;
  }
  x.constant = taylor_detail::times(x.constant, s);
  for (kernels::Interval& c : x.coefficients) c = zero(c) ? kernels::Interval(0) : taylor_detail::times(c, s);
  x.remainder = taylor_detail::times(x.remainder, s);
}
// x = -x, exact (TaylorModel1's unary minus)
inline void negate(TaylorModel1& x) {
  x.constant = -x.constant;
  for (kernels::Interval& c : x.coefficients) c = -c;
  x.remainder = -x.remainder;
}
}  // namespace jet_detail

inline Jet<TaylorModel1> operator+(Jet<TaylorModel1>&& a, const Jet<TaylorModel1>& b) {
  taylor_detail::add_to(a.value, b.value);
  jet_detail::add_gradient(a.gradient, b.gradient);
  return std::move(a);
}
inline Jet<TaylorModel1> operator+(Jet<TaylorModel1>&& a, Jet<TaylorModel1>&& b) {
  taylor_detail::add_to(a.value, b.value);
  jet_detail::add_gradient(a.gradient, std::move(b.gradient));
  return std::move(a);
}
inline Jet<TaylorModel1> operator-(Jet<TaylorModel1>&& a) {
  jet_detail::negate(a.value);
  const TaylorModel1 minus_one(-1);
  const taylor_detail::Factor f = taylor_detail::factor(minus_one);
  for (TaylorModel1& g : a.gradient) jet_detail::times_in_place(g, f, true);   // scaled(a, S(-1)): -1 is finite
  return std::move(a);
}
inline Jet<TaylorModel1> operator-(Jet<TaylorModel1>&& a, const Jet<TaylorModel1>& b);
inline Jet<TaylorModel1> operator-(Jet<TaylorModel1>&& a, Jet<TaylorModel1>&& b);
inline Jet<TaylorModel1> operator-(const Jet<TaylorModel1>& a, Jet<TaylorModel1>&& b);

template <class S>
Jet<S> operator+(const Jet<S>& a, const Jet<S>& b) {
  return Jet<S>(a.value + b.value, jet_detail::sum(a, b));
}
template <class S>
Jet<S> operator-(const Jet<S>& a) {
  return Jet<S>(-a.value, jet_detail::scaled(a, S(-1)));
}
template <class S>
Jet<S> operator-(const Jet<S>& a, const Jet<S>& b) {
  return a + (-b);
}
inline Jet<TaylorModel1> operator-(Jet<TaylorModel1>&& a, const Jet<TaylorModel1>& b) { return std::move(a) + (-b); }
inline Jet<TaylorModel1> operator-(Jet<TaylorModel1>&& a, Jet<TaylorModel1>&& b) { return std::move(a) + (-std::move(b)); }
inline Jet<TaylorModel1> operator-(const Jet<TaylorModel1>& a, Jet<TaylorModel1>&& b) { return a + (-std::move(b)); }
template <class S>
Jet<S> operator*(const Jet<S>& a, const Jet<S>& b) {
  return Jet<S>(a.value * b.value, jet_detail::combine(a, b.value, b, a.value));
}
template <class S>
Jet<S> operator/(const Jet<S>& a, const Jet<S>& b) {
  S q = a.value / b.value;
  S inverse = S(1) / b.value;
  return Jet<S>(q, jet_detail::combine(a, inverse, b, S(-(q * inverse))));
}

}  // namespace hipair::tolerance_detail

namespace hipair::model_detail {

template <class S>
struct Arithmetic<tolerance_detail::Jet<S>> {
  using J = tolerance_detail::Jet<S>;
  using A = Arithmetic<S>;
  static J constant(const Rational& q) { return J(A::constant(q)); }
  static J pi() { return J(A::pi()); }
  static J sqrt(const J& x) {
    S r = A::sqrt(x.value);
    return J(r, tolerance_detail::jet_detail::scaled(x, S(S(1) / (S(2) * r))));
  }
  static J sin(const J& x) { return J(A::sin(x.value), tolerance_detail::jet_detail::scaled(x, A::cos(x.value))); }
  static J cos(const J& x) { return J(A::cos(x.value), tolerance_detail::jet_detail::scaled(x, S(-A::sin(x.value)))); }
  static J tan(const J& x) { return sin(x) / cos(x); }
  static J atan2(const J& y, const J& x) {
    if constexpr (std::is_same_v<S, kernels::Interval>) {
      // The branch cut (y = 0, x <= 0) inside the range: atan2 jumps by 2 pi there and no
      // gradient bounds its difference quotients, so every partial through y or x is the whole
      // line (the mean-value form then falls back to the value, MPFI's hull). Until session 51
      // (exact51) the gradient x / r^2, -y / r^2 was used across the jump: atan2(p, -1) over
      // p in [-0.1, 0.1] was enclosed in [pi - 0.1, pi + 0.1] by the mean-value form, its
      // values near -pi left out. (The verifier's jets: certify/tolerance_check.cpp, exact50b.)
      if (tolerance_detail::jet_detail::meets_cut(y.value, x.value)) {
        S whole(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
        return J(A::atan2(y.value, x.value), tolerance_detail::jet_detail::combine(y, whole, x, whole));
      }
    } else if constexpr (!std::is_same_v<S, double>) {
      // second-order (nested) jets and Taylor-model jets: no derivative across the cut, as the
      // Hessian jets (hessian_jet.hpp) and the Taylor models refuse it
      if (tolerance_detail::jet_detail::meets_cut(tolerance_detail::jet_detail::enclosure(y.value),
                                                  tolerance_detail::jet_detail::enclosure(x.value)))
        throw NumericError("atan2 is not differentiable over the box (its branch cut crosses it)");
    }
    S r2 = x.value * x.value + y.value * y.value;
    return J(A::atan2(y.value, x.value),
             tolerance_detail::jet_detail::combine(y, S(x.value / r2), x, S(-(y.value / r2))));
  }
  static J abs(const J& x) {
    if constexpr (std::is_same_v<S, double>) {
      return x.value < 0 ? J(-x) : x;
    } else if constexpr (!std::is_same_v<S, kernels::Interval>) {
      // second-order jets: |x| has no second derivative where x may vanish
      kernels::Interval e = tolerance_detail::jet_detail::enclosure(x.value);
      if (e.lo >= 0) return x;
      if (e.hi <= 0) return -x;
      throw NumericError("|x| is not twice differentiable over the box");
    } else {
      if (x.value.lo >= 0) return x;
      if (x.value.hi <= 0) return -x;
      return J(A::abs(x.value), tolerance_detail::jet_detail::scaled(x, S(-1.0, 1.0)));
    }
  }
  static J extremum(const J& a, const J& b, bool minimum) {
    if constexpr (std::is_same_v<S, double>) {
      return (a.value <= b.value) == minimum ? a : b;
    } else if constexpr (!std::is_same_v<S, kernels::Interval>) {
      // second-order jets: min/max has no second derivative where the two may cross
      kernels::Interval ea = tolerance_detail::jet_detail::enclosure(a.value);
      kernels::Interval eb = tolerance_detail::jet_detail::enclosure(b.value);
      if (ea.hi <= eb.lo) return minimum ? a : b;
      if (eb.hi <= ea.lo) return minimum ? b : a;
      throw NumericError("min/max is not twice differentiable over the box");
    } else {
      if (a.value.hi <= b.value.lo) return minimum ? a : b;
      if (b.value.hi <= a.value.lo) return minimum ? b : a;
      std::size_t n = std::max(a.gradient.size(), b.gradient.size());
      std::vector<S> g(n, S(0));
      for (std::size_t i = 0; i < n; ++i) g[i] = kernels::hull(a.partial(i), b.partial(i));
      return J(minimum ? A::min(a.value, b.value) : A::max(a.value, b.value), std::move(g));
    }
  }
  static J min(const J& a, const J& b) { return extremum(a, b, true); }
  static J max(const J& a, const J& b) { return extremum(a, b, false); }
  static double value(const J& x) { return A::value(x.value); }
};

}  // namespace hipair::model_detail
