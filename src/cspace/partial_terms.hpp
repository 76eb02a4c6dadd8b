// HIPAIR — the partial derivatives of one bivariate polynomial, evaluated many times (the
// filtered edge slopes of track_derivatives, src/cspace/cspace_queries.cpp: a Newton step in
// doubles and two interval boxes at every right-hand side of the simulator's integration).
//
// kernels::polynomial_partials converts each coefficient, skips the zero ones and multiplies
// it by its derivative factors (i, j, i (i - 1), i j, j (j - 1)) at every call, computes all
// five partials when the caller may need one or two, and allocates its power tables on the
// heap. PartialTerms does the conversion and the products a * factor once, keeps the nonzero
// terms only, powers on the stack, and evaluates only what is asked. Every result is
// bit-for-bit polynomial_partials' (the same operations in the same order: the product
// a * factor is the first one polynomial_partials does, each partial sums its terms in the
// same (i, j) order, the powers are made the same way); tests/unit/cspace_partial_terms_test.cpp
// checks that on generated polynomials and boxes. Switch cspace::partial_terms() (tests): off,
// track_derivatives calls polynomial_partials as before.
#pragma once

#include "core/thread_switch.hpp"
#include "kernels/implicit_curve.hpp"

#include <boost/container/small_vector.hpp>

#include <cstddef>
#include <utility>
#include <vector>

namespace hipair::cspace {

struct PartialTermsTag;
inline bool& partial_terms() { return thread_switch<PartialTermsTag>(); }

template <class T>
class PartialTerms {
 public:
  PartialTerms() = default;
  /// The polynomial with coefficients c[i][j] of x^i y^j, converted by `convert` into T.
  template <class Coefficient, class Convert>
  PartialTerms(const std::vector<std::vector<Coefficient>>& c, Convert&& convert) {
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t j = 0; j < c[i].size(); ++j) {
        T a = convert(c[i][j]);
        if (a == T(0)) continue;
        int ii = static_cast<int>(i), jj = static_cast<int>(j);
        terms_.push_back(Term{i, j, T(a * T(ii)), T(a * T(jj)), T(a * T(ii * (ii - 1))), T(a * T(ii * jj)),
                              T(a * T(jj * (jj - 1)))});
        if (i > max_i_) max_i_ = i;
        if (j > max_j_) max_j_ = j;
      }
  }

  /// F_x and F_y at (x, y): polynomial_partials(c, x, y, convert).fx and .fy.
  std::pair<T, T> first(const T& x, const T& y) const {
    Powers xp = powers(x, max_i_), yp = powers(y, max_j_);
    T fx(0), fy(0);
    for (const Term& t : terms_) {
      if (t.i >= 1) fx = T(fx + t.ax * xp[t.i - 1] * yp[t.j]);
      if (t.j >= 1) fy = T(fy + t.ay * xp[t.i] * yp[t.j - 1]);
    }
    return {fx, fy};
  }

  /// F_y at (x, y): polynomial_partials(c, x, y, convert).fy.
  T fy(const T& x, const T& y) const {
    Powers xp = powers(x, max_i_), yp = powers(y, max_j_);
    T fy(0);
    for (const Term& t : terms_)
      if (t.j >= 1) fy = T(fy + t.ay * xp[t.i] * yp[t.j - 1]);
    return fy;
  }

  /// All five: polynomial_partials(c, x, y, convert).
  kernels::Partials<T> all(const T& x, const T& y) const {
    Powers xp = powers(x, max_i_), yp = powers(y, max_j_);
    kernels::Partials<T> d{T(0), T(0), T(0), T(0), T(0)};
    for (const Term& t : terms_) {
      if (t.i >= 1) d.fx = T(d.fx + t.ax * xp[t.i - 1] * yp[t.j]);
      if (t.j >= 1) d.fy = T(d.fy + t.ay * xp[t.i] * yp[t.j - 1]);
      if (t.i >= 2) d.fxx = T(d.fxx + t.axx * xp[t.i - 2] * yp[t.j]);
      if (t.i >= 1 && t.j >= 1) d.fxy = T(d.fxy + t.axy * xp[t.i - 1] * yp[t.j - 1]);
      if (t.j >= 2) d.fyy = T(d.fyy + t.ayy * xp[t.i] * yp[t.j - 2]);
    }
    return d;
  }

  std::size_t size() const { return terms_.size(); }

 private:
  struct Term {
    std::size_t i, j;
    T ax, ay, axx, axy, ayy;   // a i, a j, a i (i - 1), a i j, a j (j - 1), as polynomial_partials rounds them
  };
  using Powers = boost::container::small_vector<T, 16>;
  // v^0 ... v^n, made as polynomial_partials makes them (T(1), then T(previous * v))
  static Powers powers(const T& v, std::size_t n) {
    Powers p(n + 1, T(1));
    for (std::size_t k = 1; k <= n; ++k) p[k] = T(p[k - 1] * v);
    return p;
  }
  std::vector<Term> terms_;
  std::size_t max_i_ = 0, max_j_ = 0;
};

}  // namespace hipair::cspace
