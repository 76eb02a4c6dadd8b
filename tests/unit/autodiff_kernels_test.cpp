// The library's AutoDiff scalar (src/model/parametric/number_traits.hpp) through the contact
// kernels with constants that carry no gradient: the kernels' own T(0), T(1), T(2), a fixed
// part's pose, the features' body data. Eigen's AutoDiffScalar<VectorXd> read out of bounds
// there (nested expressions of an empty and a sized gradient: an assertion in debug builds,
// garbage or a crash in release). Oracle: the exact partial derivatives of the same kernel
// evaluated in exact bivariate polynomials of the two chart coordinates.
#include "algebra/polynomial.hpp"
#include "kernels/contact_table.hpp"
#include "kernels/interval.hpp"
#include "model/parametric/number_traits.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace hipair {
namespace {

using cspace::RationalPolynomial2;
using kernels::FeatureGeometry;
using kernels::FeatureShape;
using kernels::Interval;
using kernels::Pose;
using kernels::Vector;
using model_detail::AutoDiff;

// Forward mode over certified intervals with the gradient over both chart coordinates: its
// enclosures contain the exact partials, and (each interval operation widened outward by an
// ulp) the double evaluation of the same formula in AutoDiff, so their width bounds how far
// the AutoDiff gradient may be from the exact one.
struct Dual {
  Interval value;
  std::array<Interval, 2> gradient{Interval(0), Interval(0)};
  Dual(int v = 0) : value(v) {}  // NOLINT(google-explicit-constructor)
  Dual(Interval v, std::array<Interval, 2> g) : value(v), gradient(g) {}
};
Dual operator+(const Dual& a, const Dual& b) {
  return {a.value + b.value, {a.gradient[0] + b.gradient[0], a.gradient[1] + b.gradient[1]}};
}
Dual operator-(const Dual& a, const Dual& b) {
  return {a.value - b.value, {a.gradient[0] - b.gradient[0], a.gradient[1] - b.gradient[1]}};
}
Dual operator-(const Dual& a) { return {-a.value, {-a.gradient[0], -a.gradient[1]}}; }
Dual operator*(const Dual& a, const Dual& b) {
  return {a.value * b.value,
          {a.gradient[0] * b.value + a.value * b.gradient[0], a.gradient[1] * b.value + a.value * b.gradient[1]}};
}

Rational dyadic(long numerator, int shift) {
  Rational value(numerator, 1L << shift);
  value.canonicalize();
  return value;
}

FeatureGeometry<Rational> vertex(long x, long y) {
  FeatureGeometry<Rational> f;
  f.shape = FeatureShape::vertex;
  f.point = {dyadic(x, 2), dyadic(y, 2)};
  return f;
}
FeatureGeometry<Rational> segment(long x, long y, long u, long v) {
  FeatureGeometry<Rational> f;
  f.shape = FeatureShape::segment;
  f.point = {dyadic(x, 2), dyadic(y, 2)};
  f.target = {dyadic(u, 2), dyadic(v, 2)};
  return f;
}
FeatureGeometry<Rational> arc(long x, long y, long r2) {
  FeatureGeometry<Rational> f;
  f.shape = FeatureShape::arc;
  f.center = {dyadic(x, 2), dyadic(y, 2)};
  f.radius_squared = dyadic(r2, 4);
  f.convex = true;
  f.sector.start = {Rational(1), Rational(0)};
  f.sector.end = {Rational(0), Rational(1)};
  return f;
}

enum class Motion { fixed, rotating, translating };

// The pair's poses at chart coordinates (ta, tb); constants come from `constant` (for AutoDiff:
// an empty gradient).
template <class T, class Constant>
std::pair<Pose<T>, Pose<T>> poses(Motion a, Motion b, const T& ta, const T& tb, Constant&& constant) {
  auto pose = [&](Motion m, const T& t, long px, long py, bool half_turn) {
    Vector<T> pivot{constant(dyadic(px, 2)), constant(dyadic(py, 2))};
    if (m == Motion::rotating) return kernels::rotation_pose_from_half_tangent(pivot, t, half_turn);
    if (m == Motion::translating)
      return kernels::translation_pose(Vector<T>{constant(dyadic(3, 2)), constant(dyadic(-4, 2))}, t);
    return kernels::fixed_pose<T>();
  };
  return {pose(a, ta, 1, -2, false), pose(b, tb, 21, 3, true)};
}

// Every value a feature pair's contact function yields: the function and its validity atoms.
template <class T, class Constant>
std::vector<T> kernel_values(const FeatureGeometry<Rational>& fa, const FeatureGeometry<Rational>& fb, Motion ma,
                             Motion mb, const T& ta, const T& tb, Constant&& constant) {
  auto [a, b] = poses<T>(ma, mb, ta, tb, constant);
  auto function = kernels::contact_function(a, fa, b, fb, constant, kernels::AlwaysSquared{});
  std::vector<T> values;
  if (!function) return values;
  values.push_back(function->value);
  for (const auto& clause : function->validity.clauses)
    for (int k = 0; k < clause.count; ++k) values.push_back(clause.atoms[static_cast<std::size_t>(k)]);
  return values;
}

// Exact partial derivative of a polynomial in x (variable 0) or y (variable 1) at (x, y).
Rational partial(const RationalPolynomial2& p, int variable, const Rational& x, const Rational& y) {
  Rational sum = 0;
  for (int i = 0; i < p.rows(); ++i)
    for (int j = 0; j < p.columns(); ++j) {
      Rational c = p.coefficient(i, j);
      if (sgn(c) == 0) continue;
      int power = variable == 0 ? i : j;
      if (power == 0) continue;
      Rational term = c * power;
      for (int k = 0; k < (variable == 0 ? i - 1 : i); ++k) term *= x;
      for (int k = 0; k < (variable == 0 ? j : j - 1); ++k) term *= y;
      sum += term;
    }
  return sum;
}

TEST(AutoDiffKernels, ConstantsWithoutGradientMixIntoEveryContactOfEveryMotionPair) {
  const std::vector<std::pair<FeatureGeometry<Rational>, FeatureGeometry<Rational>>> pairs = {
      {vertex(1, 2), segment(3, 0, 4, 1)}, {segment(3, 0, 4, 1), vertex(1, 2)}, {vertex(1, 2), arc(3, 1, 7)},
      {arc(3, 1, 7), vertex(1, 2)},        {arc(1, 1, 5), arc(3, 1, 9)},        {arc(1, 1, 5), segment(3, 0, 4, 1)},
      {segment(3, 0, 4, 1), arc(1, 1, 5)}};
  const std::vector<std::pair<Motion, Motion>> motions = {
      {Motion::rotating, Motion::rotating},    {Motion::fixed, Motion::rotating},
      {Motion::rotating, Motion::fixed},       {Motion::translating, Motion::rotating},
      {Motion::rotating, Motion::translating}, {Motion::fixed, Motion::translating}};
  const std::vector<std::pair<Rational, Rational>> points = {
      {dyadic(3, 4), dyadic(-5, 3)}, {dyadic(-7, 3), dyadic(1, 1)}, {dyadic(0, 0), dyadic(9, 4)}};
  int checked = 0;
  for (const auto& [fa, fb] : pairs)
    for (const auto& [ma, mb] : motions)
      for (const auto& [ta, tb] : points) {
        // exact: the kernel as polynomials in (ta, tb)
        auto exact = kernel_values<RationalPolynomial2>(
            fa, fb, ma, mb, RationalPolynomial2::variable(0), RationalPolynomial2::variable(1),
            [](const Rational& r) { return RationalPolynomial2(r); });
        // AutoDiff: the chart coordinates carry the gradient, every constant none
        auto automatic = kernel_values<AutoDiff>(fa, fb, ma, mb, AutoDiff(ta.get_d(), 2, 0),
                                                 AutoDiff(tb.get_d(), 2, 1),
                                                 [](const Rational& r) { return AutoDiff(r.get_d()); });
        auto certified = kernel_values<Dual>(
            fa, fb, ma, mb, Dual(Interval::enclose(ta), {Interval(1), Interval(0)}),
            Dual(Interval::enclose(tb), {Interval(0), Interval(1)}),
            [](const Rational& r) { return Dual(Interval::enclose(r), {Interval(0), Interval(0)}); });
        ASSERT_EQ(exact.size(), automatic.size());
        ASSERT_EQ(exact.size(), certified.size());
        ASSERT_FALSE(exact.empty());
        for (std::size_t k = 0; k < exact.size(); ++k) {
          const std::string where = "pair " + std::to_string(checked) + " value " + std::to_string(k);
          Rational value = exact[k].evaluate(ta, tb);
          ASSERT_TRUE(certified[k].value.contains(value)) << where;
          EXPECT_LE(std::fabs(automatic[k].value() - value.get_d()), certified[k].value.width()) << where;
          const auto& gradient = automatic[k].derivatives();
          // a constant result may keep an empty gradient (zero); otherwise both partials
          ASSERT_TRUE(gradient.size() == 0 || gradient.size() == 2) << where;
          for (int v = 0; v < 2; ++v) {
            Rational d = partial(exact[k], v, ta, tb);
            const Interval& enclosure = certified[k].gradient[static_cast<std::size_t>(v)];
            ASSERT_TRUE(enclosure.contains(d)) << where << " partial " << v;
            double computed = gradient.size() == 0 ? 0.0 : gradient(v);
            EXPECT_LE(std::fabs(computed - d.get_d()), enclosure.width() + std::fabs(d.get_d()) * 0x1p-52)
                << where << " partial " << v;
          }
        }
        ++checked;
      }
  EXPECT_EQ(checked, 7 * 6 * 3);
}

TEST(AutoDiffKernels, EmptyGradientIsZeroInArithmetic) {
  AutoDiff x(3.0, 2, 0), y(-2.0, 2, 1);
  AutoDiff two(2), half(0.5);
  EXPECT_EQ(two.derivatives().size(), 0);
  // (2 x - 0.5) * y / (x + 1) - 2, with a constant on either side of every operation
  AutoDiff f = (two * x - half) * y / (x + AutoDiff(1)) - two;
  // f = (2x - 1/2) y / (x + 1) - 2: df/dx = y (2 (x + 1) - (2x - 1/2)) / (x + 1)^2 = 5y / (2 (x+1)^2),
  // df/dy = (2x - 1/2) / (x + 1); at (3, -2): -10 / 32 and 5.5 / 4, exact in double, and every
  // operation above is exact in double at these dyadic values.
  EXPECT_EQ(f.value(), 5.5 * -2.0 / 4.0 - 2.0);
  ASSERT_EQ(f.derivatives().size(), 2);
  EXPECT_EQ(f.derivatives()(0), -10.0 / 32.0);
  EXPECT_EQ(f.derivatives()(1), 5.5 / 4.0);
  AutoDiff g = two * half + AutoDiff(1);
  EXPECT_EQ(g.value(), 2.0);
  EXPECT_EQ(g.derivatives().size(), 0);
  AutoDiff s = model_detail::Arithmetic<AutoDiff>::sqrt(x * x + two * two * y * y);   // 5
  EXPECT_EQ(s.value(), 5.0);
  EXPECT_NEAR(s.derivatives()(0), 3.0 / 5.0, 1e-15);   // x / s, a rounding of 3/5
  EXPECT_NEAR(s.derivatives()(1), 4.0 * -2.0 / 5.0, 1e-15);
}

}  // namespace
}  // namespace hipair
