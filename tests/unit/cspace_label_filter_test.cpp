// label_edges' interval filter through the samples' k-d tree (curves_at_samples, session 41
// fast41) against the plain filter (every curve's enclosure over every sample box) and the
// exact value of every curve at every sample point (the label's own test): on generated curves
// through random rational points (general conics through the point, squared lines through it:
// a tangency, zero along a line; a circle of radius 0 there: a single zero, zero clearance),
// boxes around random rational samples of widths 0 … 2^-3 relative, placed asymmetrically
// around the sample, at scales 1, 2^300 and 2^-300. The tree may drop a pair the plain filter
// passes only where the curve has no zero in the box: every pair with an exact zero at the
// sample point is listed, and every listed pair passes the plain filter.
#include "cspace/label_filter.hpp"
#include "cspace/quadratic_root.hpp"
#include "algebra/polynomial.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::cspace {
namespace {

using algebra::Interval;

// An integer polynomial with the zero set and sign of the rational coefficients c[i][j] (x^i y^j).
IntegerPolynomial2 integer_curve(const std::vector<std::vector<Rational>>& c) {
  RationalPolynomial2 f;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) f.set_coefficient(static_cast<int>(i), static_cast<int>(j), c[i][j]);
  return normalized_integer_polynomial(f);
}

// The value at (x, y) of the polynomial of rational coefficients c[i][j] (x^i y^j), exactly.
Rational value_of(const std::vector<std::vector<Rational>>& c, const Rational& x, const Rational& y) {
  Rational value = 0, xi = 1;
  for (std::size_t i = 0; i < c.size(); ++i, xi *= x) {
    Rational yj = 1;
    for (std::size_t j = 0; j < c[i].size(); ++j, yj *= y) value += c[i][j] * xi * yj;
  }
  return value;
}

struct Generated {
  std::vector<IntegerPolynomial2> curves;
  std::vector<Rational> xs, ys;   // the samples
  std::vector<SampleBox> boxes;
};

Generated generate(std::mt19937_64& random, int scale_exponent) {
  const Rational scale = scale_exponent >= 0 ? Rational(mpz_class(1) << scale_exponent)
                                             : Rational(mpz_class(1), mpz_class(1) << -scale_exponent);
  std::uniform_int_distribution<int> small(-40, 40), positive(1, 37);
  auto coordinate = [&] { return Rational(Rational(small(random), positive(random)) * scale); };
  Generated g;
  std::vector<Rational> px, py;   // the curves' own points
  for (int k = 0; k < 48; ++k) {
    // every sixth point on the integer grid (times the scale): exact doubles, so that enclosures
    // over boxes of that point alone can be exactly [0, 0] (the tree's test touches zero)
    const Rational x = k % 6 == 2 ? Rational(small(random) * scale) : coordinate();
    const Rational y = k % 6 == 2 ? Rational(small(random) * scale) : coordinate();
    px.push_back(x);
    py.push_back(y);
    std::vector<std::vector<Rational>> c(3, std::vector<Rational>(3, Rational(0)));
    switch (k % 3) {
      case 0: {   // a general conic through (x, y): g - g(x, y), coefficients scaled to the point
        for (int i = 0; i <= 2; ++i)
          for (int j = 0; i + j <= 2; ++j) {
            Rational s = 1;
            for (int d = 0; d < 2 - i - j; ++d) s *= scale;   // homogeneous in the scale
            c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = Rational(small(random)) * s;
          }
        c[0][0] -= value_of(c, x, y);
        break;
      }
      case 1: {   // (u (x - px) + v (y - py))^2: zero along a line, touching zero
        const Rational u(small(random) | 1), v(small(random));
        const Rational w = -(u * x + v * y);
        c[2][0] = u * u;
        c[0][2] = v * v;
        c[1][1] = 2 * u * v;
        c[1][0] = 2 * u * w;
        c[0][1] = 2 * v * w;
        c[0][0] = w * w;
        break;
      }
      default:   // (x - px)^2 + (y - py)^2: one zero
        c[2][0] = 1;
        c[0][2] = 1;
        c[1][0] = -2 * x;
        c[0][1] = -2 * y;
        c[0][0] = x * x + y * y;
    }
    g.curves.push_back(integer_curve(c));
  }
  // samples: every curve's point, and random points; boxes of random widths around them
  std::uniform_int_distribution<int> width_kind(0, 4);
  for (int e = 0; e < 160; ++e) {
    Rational x, y;
    if (e < 48) {
      x = px[static_cast<std::size_t>(e)], y = py[static_cast<std::size_t>(e)];
    } else if (e < 96) {   // the curves' points again, in boxes of other widths
      x = px[static_cast<std::size_t>(e % 48)], y = py[static_cast<std::size_t>(e % 48)];
    } else {
      x = coordinate(), y = coordinate();
    }
    SampleBox box{algebra::enclose(x), algebra::enclose(y)};
    const int kind = width_kind(random);
    if (kind > 0) {
      const double relative[] = {0, 0x1p-48, 0x1p-20, 0x1p-8, 0x1p-3};
      std::uniform_real_distribution<double> part(0, 1);
      for (int axis = 0; axis < 2; ++axis) {
        const double w = relative[kind] * (std::abs(box[axis].lo) + std::abs(box[axis].hi) + scale.get_d());
        box[axis].lo -= w * part(random);   // asymmetric around the sample
        box[axis].hi += w * part(random);
      }
    }
    g.xs.push_back(x);
    g.ys.push_back(y);
    g.boxes.push_back(box);
  }
  // the grid points again, five times each in boxes of width 0: groups of equal boxes
  for (std::size_t k = 2; k < px.size(); k += 6)
    for (int copy = 0; copy < 5; ++copy) {
      g.xs.push_back(px[k]);
      g.ys.push_back(py[k]);
      g.boxes.push_back(SampleBox{algebra::enclose(px[k]), algebra::enclose(py[k])});
    }
  return g;
}

}  // namespace

TEST(LabelFilter, TreeListsEveryExactZeroAndOnlyPairsThePlainFilterPasses) {
  std::mt19937_64 random(41);
  std::size_t zeros = 0, dropped = 0, listed = 0;
  for (int scale : {0, 300, -300})
    for (int round = 0; round < 6; ++round) {
      const Generated g = generate(random, scale);
      std::vector<algebra::IntervalPolynomial2> curves;
      for (const auto& f : g.curves) curves.emplace_back(f);
      const auto tree = curves_at_samples(curves, g.boxes);
      ASSERT_EQ(tree.size(), g.boxes.size());
      for (std::size_t e = 0; e < g.boxes.size(); ++e) {
        std::vector<std::size_t> plain;
        for (std::size_t k = 0; k < curves.size(); ++k)
          if (curves[k].evaluate(g.boxes[e][0], g.boxes[e][1]).contains_zero()) plain.push_back(k);
        // the tree's list: ascending, a subsequence of the plain filter's
        std::size_t at = 0;
        for (std::size_t k : tree[e]) {
          while (at < plain.size() && plain[at] < k) ++at;
          ASSERT_TRUE(at < plain.size() && plain[at] == k) << "scale 2^" << scale << ", sample " << e << ", curve " << k;
          ++at;
        }
        dropped += plain.size() - tree[e].size();
        listed += tree[e].size();
        // every exact zero at the sample point is listed
        for (std::size_t k = 0; k < curves.size(); ++k) {
          if (sgn(evaluate(g.curves[k], g.xs[e], g.ys[e])) != 0) continue;
          ++zeros;
          EXPECT_TRUE(std::find(tree[e].begin(), tree[e].end(), k) != tree[e].end())
              << "scale 2^" << scale << ", sample " << e << ", curve " << k << " vanishes there";
        }
      }
    }
  // the cases reach both sides: exact zeros, and pairs the tree drops before the plain filter
  EXPECT_GT(zeros, 1000u);
  EXPECT_GT(listed, zeros);
  std::printf("exact zeros %zu, listed %zu, dropped by the tree (plain filter passes) %zu\n", zeros, listed, dropped);
}

TEST(LabelFilter, EmptyInputs) {
  EXPECT_TRUE(curves_at_samples({}, {}).empty());
  EXPECT_EQ(curves_at_samples({}, std::vector<SampleBox>(3)).size(), 3u);
}

// edge_y_at's quadratic path (quadratic_root_in, session 41 fast41) against
// algebra::nth_real_root_in (the exact square-free part and Sturm sequence): the same Real (bounds,
// polynomial, exactness) or the same error, on quadratics with two random rational roots (dyadic
// ones, met exactly by the bisection's midpoints; close pairs; a double root: not taken), times a
// random integer factor of either sign, in boxes around either root or both, scaled by 2^0,
// 2^300 and 2^-300.
TEST(QuadraticRoot, SameRootAsTheSturmBisection) {
  std::mt19937_64 random(4141);
  std::uniform_int_distribution<int> small(-60, 60), positive(1, 29), power(0, 6), kind(0, 3), factor(-5, 5);
  std::size_t taken = 0, declined = 0, errors = 0, exact = 0;
  for (int scale_exponent : {0, 300, -300})
    for (int round = 0; round < 400; ++round) {
      const Rational scale = scale_exponent >= 0 ? Rational(mpz_class(1) << scale_exponent)
                                                 : Rational(mpz_class(1), mpz_class(1) << -scale_exponent);
      auto root_value = [&] {
        Rational v(small(random), kind(random) == 0 ? mpz_class(1) << power(random) : mpz_class(positive(random)));   // dyadic or not
        v.canonicalize();
        return Rational(v * scale);
      };
      Rational r0 = root_value(), r1 = kind(random) == 0 ? r0 : root_value();
      if (kind(random) == 1) r1 = r0 + Rational(1, mpz_class(1) << 40) * scale;   // a close pair
      if (r1 < r0) std::swap(r0, r1);
      // c (y - r0)(y - r1), integer coefficients
      const Rational s = r0 + r1, p = r0 * r1;
      mpz_class common;
      mpz_lcm(common.get_mpz_t(), s.get_den_mpz_t(), p.get_den_mpz_t());
      int c = factor(random);
      if (c == 0) c = 1;
      algebra::Polynomial q{mpz_class(p.get_num() * (common / p.get_den()) * c),
                            mpz_class(-s.get_num() * (common / s.get_den()) * c), mpz_class(common * c)};
      // boxes: around r0, around r1, around both, and one beside them (an error)
      Rational width(positive(random), kind(random) < 2 ? mpz_class(1) << power(random) : mpz_class(7));   // dyadic or not
      width.canonicalize();
      width *= scale;
      const int which = kind(random);
      Rational lo, hi;
      int index = 0;
      if (which == 0) lo = r0 - width, hi = r0 + (r1 - r0) / 2, index = 0;
      if (which == 1) lo = r0 + (r1 - r0) / 2, hi = r1 + width, index = 1;
      if (which == 2) {   // both roots; half the time with r1 at the first midpoint (an exact root)
        lo = r0 - width;
        hi = random() % 2 ? Rational(r1 + width) : Rational(2 * r1 - lo);
        index = static_cast<int>(random() % 2);
      }
      if (which == 3) lo = r1 + width, hi = r1 + 2 * width, index = 1;
      if (r0 == r1 && which == 1) lo = r0 - width;   // a double root: boxes around it
      std::optional<algebra::Real> expected;
      std::string expected_error;
      try {
        expected = algebra::nth_real_root_in(q, index, lo, hi);
      } catch (const NumericError& e) {
        expected_error = e.what();
      }
      std::optional<algebra::Real> got;
      std::string got_error;
      bool declined_here = false;
      try {
        got = quadratic_root_in(q, index, lo, hi);
        declined_here = !got;
      } catch (const NumericError& e) {
        got_error = e.what();
      }
      if (declined_here) {
        ++declined;
        EXPECT_EQ(r0, r1) << "declined a quadratic with two roots";
        continue;
      }
      ++taken;
      const std::string where = "scale 2^" + std::to_string(scale_exponent) + ", roots " + r0.get_str() + ", " + r1.get_str() +
                                ", box [" + lo.get_str() + ", " + hi.get_str() + "], index " + std::to_string(index);
      ASSERT_EQ(expected_error, got_error) << where;
      if (!expected_error.empty()) {
        ++errors;
        continue;
      }
      ASSERT_TRUE(expected && got) << where;
      EXPECT_EQ(expected->exact, got->exact) << where;
      EXPECT_EQ(expected->lower, got->lower) << where;
      EXPECT_EQ(expected->upper, got->upper) << where;
      EXPECT_EQ(expected->polynomial, got->polynomial) << where;
      exact += got->exact;
    }
  // every kind of case is reached
  EXPECT_GT(taken, 600u);
  EXPECT_GT(declined, 20u);
  EXPECT_GT(errors, 20u);
  EXPECT_GT(exact, 50u);
  std::printf("taken %zu (errors %zu, exact roots %zu), declined (double roots) %zu\n", taken, errors, exact, declined);
}

}  // namespace hipair::cspace
