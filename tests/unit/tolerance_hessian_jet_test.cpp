// Second-order jets with a packed Hessian (src/tolerance/hessian_jet.hpp; session 22), the
// second-order form of the tolerance solver's partial derivatives. Generated tests:
// (1) random functions of every operation of number_traits (+ - * /, sqrt, sin, cos, tan,
//     atan2, |x|, min, max, negation) over random narrow boxes: at sampled points of each box
//     (corners included), the value, gradient and every second partial derivative there
//     (nested interval jets Jet<Jet<Interval>> at the point: certified, a few ulps wide) meet
//     the Hessian jet's enclosures over the box; the enclosures are as narrow as the nested
//     jets' over the same box (the same chain rule: only the rounding order differs), and a
//     variable the expression does not use has exactly zero derivatives;
// (2) |x|, min and max undecided over the box throw (the solver then stays at first order).
#include "model/parametric/number_traits.hpp"
#include "random_expression.hpp"
#include "tolerance/hessian_jet.hpp"
#include "tolerance/jet.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using model_detail::Arithmetic;
using test::evaluate;
using test::Expression;
using test::random_box;
using test::random_expression;
using test::RandomBox;
using tolerance_detail::HessianJet;
using tolerance_detail::Jet;
using Nested = Jet<Jet<Interval>>;

bool meets(const Interval& a, const Interval& b) { return a.lo <= b.hi && b.lo <= a.hi; }
bool finite(const Interval& a) { return std::isfinite(a.lo) && std::isfinite(a.hi); }

Nested nested_variable(const Interval& v, std::size_t i, std::size_t n) {
  return Nested::variable(Jet<Interval>::variable(v, i, n), i, n);
}
Interval nested_second(const Nested& f, std::size_t i, std::size_t j) { return f.partial(i).partial(j); }

TEST(ToleranceHessianJet, RandomFunctionsAreEnclosedWithTheirDerivativesAtSampledPointsOfTheBox) {
  std::mt19937_64 random(2201);
  std::size_t cases = 0, refused = 0, points = 0, compared = 0, as_narrow = 0, zeros_checked = 0;
  double width_hessian = 0, width_nested = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    std::size_t used = 2 + trial % 4;
    std::size_t n = used + 1;   // the last variable unused: its derivatives are exact zeros
    Expression e = random_expression(random, used, 4 + trial % 9);
    RandomBox box = random_box(random, n);
    std::vector<HessianJet> hx(n);
    std::vector<Nested> nx(n);
    for (std::size_t i = 0; i < n; ++i) {
      hx[i] = HessianJet::variable(Interval(box.lo[i], box.hi[i]), i, n);
      nx[i] = nested_variable(Interval(box.lo[i], box.hi[i]), i, n);
    }
    HessianJet h;
    Nested over_box;
    try {
      h = evaluate(e, hx);
    } catch (const NumericError&) {
      ++refused;   // |x|, min or max undecided over the box
      EXPECT_THROW(evaluate(e, nx), NumericError);
      continue;
    }
    over_box = evaluate(e, nx);
    ++cases;
    // the unused variable (where the enclosures are finite: an unbounded derivative, atan2's
    // at a range reaching its origin, times an exact zero is no exact zero)
    bool bounded = true;
    for (std::size_t i = 0; i < used; ++i) {
      bounded = bounded && finite(h.partial(i));
      for (std::size_t j = 0; j <= i; ++j) bounded = bounded && finite(h.second(i, j));
    }
    if (bounded) {
      ++zeros_checked;
      EXPECT_EQ(h.partial(n - 1).lo, 0.0);
      EXPECT_EQ(h.partial(n - 1).hi, 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(h.second(i, n - 1).lo, 0.0);
        EXPECT_EQ(h.second(n - 1, i).hi, 0.0);
      }
    }
    // as narrow as the nested jets over the box (each entry within a few ulps' worth: 1e-9
    // relative of its magnitude), summed over the finite entries
    for (std::size_t i = 0; i < used; ++i)
      for (std::size_t j = 0; j < used; ++j) {
        Interval a = h.second(i, j), b = nested_second(over_box, i, j);
        if (!finite(a) || !finite(b) || b.width() == 0) continue;
        ++compared;
        width_hessian += a.width();
        width_nested += b.width();
        if (a.width() <= b.width() * (1 + 1e-9) + 1e-12 * (std::fabs(b.lo) + std::fabs(b.hi))) ++as_narrow;
      }
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int s = 0; s < 100; ++s) {
      std::vector<Nested> px(n);
      for (std::size_t i = 0; i < n; ++i) {
        double u = s < 4 ? ((s >> (i % 2)) & 1) : unit(random);
        double x = std::min(std::max(box.lo[i] + u * (box.hi[i] - box.lo[i]), box.lo[i]), box.hi[i]);
        px[i] = nested_variable(Interval::point(x), i, n);
      }
      Nested at;
      try {
        at = evaluate(e, px);
      } catch (const NumericError&) {
        continue;   // cannot happen where the box decided; kept for safety of the sampler
      }
      if (!finite(at.value.value)) continue;
      ++points;
      ASSERT_TRUE(meets(h.value, at.value.value)) << "point " << s;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_TRUE(meets(h.partial(i), at.partial(i).value)) << "point " << s << ", partial " << i;
        for (std::size_t j = 0; j < n; ++j) {
          Interval p = nested_second(at, i, j);
          if (!finite(p)) continue;
          ASSERT_TRUE(meets(h.second(i, j), p))
              << "point " << s << ", second partial (" << i << ", " << j << "): at the point [" << p.lo << ", "
              << p.hi << "], over the box [" << h.second(i, j).lo << ", " << h.second(i, j).hi << "]";
        }
      }
    }
  }
  std::printf("Hessian jets: %zu cases (%zu refused, %zu with exact zeros checked), %zu points; %zu second partials compared with nested jets over "
              "the box: %zu as narrow; total width %.6g against %.6g\n",
              cases, refused, zeros_checked, points, compared, as_narrow, width_hessian, width_nested);
  EXPECT_GE(cases, 250u);
  EXPECT_GE(zeros_checked, cases / 2);
  EXPECT_GE(points, 25000u);
  EXPECT_GE(as_narrow, compared * 9 / 10);
  EXPECT_LE(width_hessian, 1.01 * width_nested);
}

TEST(ToleranceHessianJet, UndecidableComparisonsThrow) {
  using A = Arithmetic<HessianJet>;
  HessianJet x = HessianJet::variable(Interval(-1, 1), 0, 2), y = HessianJet::variable(Interval(0.5, 2), 1, 2);
  EXPECT_THROW(A::abs(x), NumericError);
  EXPECT_THROW(A::min(x, y), NumericError);
  EXPECT_THROW(A::max(x, y), NumericError);
  HessianJet z = HessianJet::variable(Interval(3, 4), 0, 2);
  EXPECT_EQ(A::min(z, y).value.lo, 0.5);
  EXPECT_EQ(A::abs(-z).value.lo, 3.0);
}

}  // namespace
}  // namespace hipair
