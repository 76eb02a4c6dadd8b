// The exact polynomial type's sums, differences and products (equal denominators summed as
// they stand, binary minus without a negated copy, products not trimmed) against coefficient-
// wise rational arithmetic; and the kernels' homogeneous products (each piece rotated once,
// w_a w_b once) against the world-frame product computed with rational rotations.
#include "algebra/polynomial.hpp"
#include "kernels/pose.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

namespace hipair::cspace {
namespace {

using kernels::PairVector;
using kernels::Pose;
using kernels::Vector;
using Coefficients = std::map<std::pair<int, int>, Rational>;   // the non-zero ones

Rational random_rational(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 9), small(-40, 40), den(1, 12), shift(-700, 700);
  Rational value(small(rng), den(rng));
  value.canonicalize();
  if (kind(rng) == 0) {   // scales 2^-700 .. 2^700 (beyond a double's range at both ends)
    const int s = shift(rng);
    if (s >= 0)
      mpq_mul_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(s));
    else
      mpq_div_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(-s));
  }
  return value;
}

// A polynomial of up to 4 x 4 coefficients, some of them zero (also whole last rows/columns).
RationalPolynomial2 random_polynomial(std::mt19937_64& rng, Coefficients& out) {
  std::uniform_int_distribution<int> size(0, 4), zero(0, 3);
  RationalPolynomial2 p;
  out.clear();
  const int rows = size(rng), columns = size(rng);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      if (zero(rng) == 0) continue;
      Rational v = random_rational(rng);
      if (sgn(v) == 0) continue;
      p.set_coefficient(i, j, v);
      out[{i, j}] = v;
    }
  return p;
}

Coefficients coefficients_of(const RationalPolynomial2& p) {
  Coefficients c;
  for (int i = 0; i < p.rows(); ++i)
    for (int j = 0; j < p.columns(); ++j) {
      Rational v = p.coefficient(i, j);
      if (sgn(v) != 0) c[{i, j}] = v;
    }
  return c;
}

Coefficients oracle_sum(const Coefficients& a, const Coefficients& b, int sign) {
  Coefficients r = a;
  for (const auto& [at, v] : b) r[at] += sign > 0 ? Rational(v) : Rational(-v);
  for (auto it = r.begin(); it != r.end();) it = sgn(it->second) == 0 ? r.erase(it) : std::next(it);
  return r;
}

Coefficients oracle_product(const Coefficients& a, const Coefficients& b) {
  Coefficients r;
  for (const auto& [p, u] : a)
    for (const auto& [q, v] : b) r[{p.first + q.first, p.second + q.second}] += u * v;
  for (auto it = r.begin(); it != r.end();) it = sgn(it->second) == 0 ? r.erase(it) : std::next(it);
  return r;
}

// The polynomial holds exactly the oracle's coefficients, trimmed (rows and columns the least
// that hold them), over a positive denominator (1 for the zero polynomial).
void expect_is(const RationalPolynomial2& p, const Coefficients& expected, const char* what, int round) {
  SCOPED_TRACE(::testing::Message() << what << ", round " << round);
  EXPECT_EQ(coefficients_of(p), expected);
  int rows = 0, columns = 0;
  for (const auto& [at, v] : expected) rows = std::max(rows, at.first + 1), columns = std::max(columns, at.second + 1);
  EXPECT_EQ(p.rows(), rows);
  EXPECT_EQ(p.columns(), columns);
  EXPECT_GT(sgn(p.denominator()), 0);
  if (expected.empty()) EXPECT_EQ(p.denominator(), 1);
  EXPECT_EQ(p.is_zero(), expected.empty());
}

TEST(RationalPolynomialArithmetic, SumsDifferencesAndProductsAreCoefficientwise) {
  std::mt19937_64 rng(38);
  std::uniform_int_distribution<int> relation(0, 5);
  for (int round = 0; round < 3000; ++round) {
    Coefficients ca, cb;
    RationalPolynomial2 a = random_polynomial(rng, ca);
    RationalPolynomial2 b = random_polynomial(rng, cb);
    switch (relation(rng)) {
      case 0: b = a; cb = ca; break;                        // a - a: everything cancels
      case 1: {                                             // b = a + integer polynomial: same denominator
        Coefficients ci;
        RationalPolynomial2 integer;
        for (const auto& [at, v] : cb) {
          Rational n = v.get_num();
          integer.set_coefficient(at.first, at.second, n);
          ci[at] = n;
        }
        b = a + integer;
        cb = oracle_sum(ca, ci, 1);
        break;
      }
      case 2: b = a * RationalPolynomial2(Rational(-1)); cb = oracle_sum({}, ca, -1); break;   // a + b = 0
      default: break;                                       // unrelated (denominators mostly differ)
    }
    expect_is(b, cb, "b", round);
    expect_is(a + b, oracle_sum(ca, cb, 1), "a + b", round);
    expect_is(a - b, oracle_sum(ca, cb, -1), "a - b", round);
    expect_is(b - a, oracle_sum(cb, ca, -1), "b - a", round);
    expect_is(-a, oracle_sum({}, ca, -1), "-a", round);
    expect_is(a * b, oracle_product(ca, cb), "a * b", round);
    expect_is((a - b) * (a + b), oracle_product(oracle_sum(ca, cb, -1), oracle_sum(ca, cb, 1)), "(a - b)(a + b)", round);
    if (::testing::Test::HasFailure()) return;
  }
}

// ------------------------------------------------------------------ homogeneous products

Vector<Rational> random_vector(std::mt19937_64& rng) { return {random_rational(rng), random_rational(rng)}; }

// A rotating (half-angle tangent t, either chart), translating or fixed part's pose.
Pose<Rational> random_pose(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 3);
  switch (kind(rng)) {
    case 0: return kernels::fixed_pose<Rational>();
    case 1: return kernels::translation_pose(random_vector(rng), random_rational(rng));
    default: return kernels::rotation_pose_from_half_tangent(random_vector(rng), random_rational(rng), kind(rng) == 3);
  }
}

PairVector<Rational> random_pair_vector(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> bit(0, 1);
  PairVector<Rational> v;
  do {
    v.has_fixed = bit(rng) == 1;
    v.has_first = bit(rng) == 1;
    v.has_second = bit(rng) == 1;
  } while (!v.has_fixed && !v.has_first && !v.has_second);
  if (v.has_fixed) v.fixed = random_vector(rng);
  if (v.has_first) v.on_first = random_vector(rng);
  if (v.has_second) v.on_second = random_vector(rng);
  return v;
}

// R p with R = [c -s; s c] / w (the identity for a part that does not rotate)
Vector<Rational> world_rotated(const Pose<Rational>& pose, const Vector<Rational>& p) {
  if (!pose.rotates) return p;
  return {Rational((pose.c * p.x - pose.s * p.y) / pose.w), Rational((pose.s * p.x + pose.c * p.y) / pose.w)};
}

Vector<Rational> world(const PairVector<Rational>& v, const Pose<Rational>& a, const Pose<Rational>& b) {
  Vector<Rational> r{0, 0};
  if (v.has_fixed) r = {Rational(r.x + v.fixed.x), Rational(r.y + v.fixed.y)};
  if (v.has_first) {
    Vector<Rational> q = world_rotated(a, v.on_first);
    r = {Rational(r.x + q.x), Rational(r.y + q.y)};
  }
  if (v.has_second) {
    Vector<Rational> q = world_rotated(b, v.on_second);
    r = {Rational(r.x + q.x), Rational(r.y + q.y)};
  }
  return r;
}

TEST(KernelsHomogeneousProduct, EachPieceRotatedOnceIsTheWorldFrameProduct) {
  std::mt19937_64 rng(3838);
  std::uniform_int_distribution<int> same(0, 2);
  for (int round = 0; round < 4000; ++round) {
    Pose<Rational> a = random_pose(rng), b = random_pose(rng);
    PairVector<Rational> u = random_pair_vector(rng);
    PairVector<Rational> v = same(rng) == 0 ? u : random_pair_vector(rng);   // dot(v, v) as the kernels ask
    const Vector<Rational> wu = world(u, a, b), wv = world(v, a, b);
    const Rational weight = a.w * b.w;
    const Rational dot = weight * (wu.x * wv.x + wu.y * wv.y);
    const Rational cross = weight * (wu.x * wv.y - wu.y * wv.x);
    ASSERT_EQ(kernels::dot_homogeneous(u, v, a, b), dot) << "round " << round;
    ASSERT_EQ(kernels::cross_homogeneous(u, v, a, b), cross) << "round " << round;
  }
}

// The same with polynomial coordinates (the curve generator's number type): the products as
// polynomials in the two half-angle tangents, evaluated at random points, are the rational
// products of the poses at those points.
TEST(KernelsHomogeneousProduct, PolynomialProductsEvaluateToTheRationalOnes) {
  std::mt19937_64 rng(383838);
  std::uniform_int_distribution<int> bit(0, 1);
  auto lift = [](const Vector<Rational>& p) {
    return Vector<RationalPolynomial2>{RationalPolynomial2(p.x), RationalPolynomial2(p.y)};
  };
  for (int round = 0; round < 400; ++round) {
    const Vector<Rational> pivot_a = random_vector(rng), pivot_b = random_vector(rng);
    const bool half_a = bit(rng) == 1, half_b = bit(rng) == 1;
    const Pose<RationalPolynomial2> pa =
        kernels::rotation_pose_from_half_tangent(lift(pivot_a), RationalPolynomial2::variable(0), half_a);
    const Pose<RationalPolynomial2> pb =
        kernels::rotation_pose_from_half_tangent(lift(pivot_b), RationalPolynomial2::variable(1), half_b);
    const PairVector<Rational> u = random_pair_vector(rng), v = bit(rng) == 1 ? u : random_pair_vector(rng);
    PairVector<RationalPolynomial2> pu, pv;
    for (auto [from, to] : {std::pair{&u, &pu}, std::pair{&v, &pv}}) {
      to->fixed = lift(from->fixed);
      to->on_first = lift(from->on_first);
      to->on_second = lift(from->on_second);
      to->has_fixed = from->has_fixed;
      to->has_first = from->has_first;
      to->has_second = from->has_second;
    }
    const RationalPolynomial2 dot = kernels::dot_homogeneous(pu, pv, pa, pb);
    const RationalPolynomial2 cross = kernels::cross_homogeneous(pu, pv, pa, pb);
    for (int point = 0; point < 3; ++point) {
      Rational x(std::uniform_int_distribution<int>(-30, 30)(rng), 7), y(std::uniform_int_distribution<int>(-30, 30)(rng), 5);
      x.canonicalize();
      y.canonicalize();
      const Pose<Rational> a = kernels::rotation_pose_from_half_tangent(pivot_a, x, half_a);
      const Pose<Rational> b = kernels::rotation_pose_from_half_tangent(pivot_b, y, half_b);
      ASSERT_EQ(dot.evaluate(x, y), kernels::dot_homogeneous(u, v, a, b)) << "round " << round;
      ASSERT_EQ(cross.evaluate(x, y), kernels::cross_homogeneous(u, v, a, b)) << "round " << round;
      const Vector<Rational> wu = world(u, a, b), wv = world(v, a, b);
      ASSERT_EQ(dot.evaluate(x, y), a.w * b.w * (wu.x * wv.x + wu.y * wv.y)) << "round " << round;
    }
  }
}

}  // namespace
}  // namespace hipair::cspace
