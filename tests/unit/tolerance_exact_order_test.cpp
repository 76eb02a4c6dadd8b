// The tolerance analysis' exact decisions (src/tolerance/exact_order.hpp): the order of slice
// points against rationals and each other, the slice point matched to a follower coordinate,
// and the free intervals inside a channel (the jamming threshold's exact confirmation), against
// closed-form oracles on square roots; and cases where the former double tests (1e-9 matching,
// comparing approximate() values) decide wrongly.
#include "tolerance/exact_order.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

namespace hipair {
namespace {

using tolerance_detail::compare;

// sqrt(n / d) as the root of d x^2 - n in (lo, hi).
AlgebraicNumber root(const mpz_class& n, const mpz_class& d, const Rational& lo, const Rational& hi) {
  AlgebraicNumber a;
  a.polynomial = {-n, 0, d};
  a.lower = lo;
  a.upper = hi;
  return a;
}
AlgebraicNumber sqrt_of(long n) {   // n not a square
  long f = static_cast<long>(std::floor(std::sqrt(static_cast<double>(n))));
  return root(n, 1, f, f + 1);
}
bool square(long n) {
  long f = static_cast<long>(std::llround(std::sqrt(static_cast<double>(n))));
  return f * f == n;
}
int sign_sqrt_minus(long n, const Rational& r) {   // sign(sqrt(n) - r), r > 0
  return sgn(Rational(n) - r * r);
}
// sign((t - sqrt a) - (sqrt b - t)), closed form.
int nearer(long a, long b, const Rational& t) {
  Rational lhs = 4 * t * t - a - b;   // compare 2t with sqrt a + sqrt b: 4t^2 - a - b vs 2 sqrt(ab)
  if (lhs < 0) return -1;
  return sgn(lhs * lhs - 4 * Rational(a) * b);
}

TEST(ToleranceExactOrder, RationalComparisonsAgreeWithSquares) {
  std::mt19937_64 rng(12);
  int cases = 0;
  for (long n = 2; n < 400; ++n) {
    if (square(n)) continue;
    AlgebraicNumber a = sqrt_of(n);
    double approx = std::sqrt(static_cast<double>(n));
    // The double nearest sqrt(n) as a rational: a double comparison calls it equal.
    Rational d(approx);
    EXPECT_EQ(compare(a, d), sign_sqrt_minus(n, d)) << n;
    EXPECT_NE(compare(a, d), 0) << n;
    for (int k = 0; k < 5; ++k) {
      Rational r(static_cast<long>(rng() % 100000) + 1, static_cast<long>(rng() % 1000) + 1);
      r.canonicalize();
      EXPECT_EQ(compare(a, r), sign_sqrt_minus(n, r)) << n << " " << r;
      ++cases;
    }
  }
  EXPECT_GT(cases, 1000);
}

TEST(ToleranceExactOrder, AlgebraicComparisons) {
  for (long n = 2; n < 80; ++n)
    for (long m = 2; m < 80; ++m) {
      if (square(n) || square(m)) continue;
      EXPECT_EQ(compare(sqrt_of(n), sqrt_of(m)), n < m ? -1 : n > m ? 1 : 0) << n << " " << m;
    }
  // Equal numbers with different polynomials: sqrt 8 and the root of (x^2 - 8)(x - 1) in (2, 3).
  AlgebraicNumber b;
  b.polynomial = {8, -8, -1, 1};
  b.lower = 2;
  b.upper = 3;
  EXPECT_EQ(compare(sqrt_of(8), b), 0);
  EXPECT_EQ(compare(b, sqrt_of(7)), 1);
  // An isolating interval whose lower end is another root: sqrt 2 as the root of
  // (x - 1)(x^2 - 2) in (1, 2).
  AlgebraicNumber r2;
  r2.polynomial = {2, -2, -1, 1};
  r2.lower = 1;
  r2.upper = 2;
  EXPECT_EQ(compare(r2, Rational(3, 2)), -1);
  EXPECT_EQ(compare(r2, Rational(7, 5)), 1);
  EXPECT_EQ(compare(r2, sqrt_of(2)), 0);
  EXPECT_EQ(compare(r2, sqrt_of(3)), -1);
  EXPECT_EQ(compare(sqrt_of(3), r2), 1);
  // 10^-30 apart: the doubles are equal, the order is not.
  mpz_class big("1000000000000000000000000000000");
  AlgebraicNumber c = root(2 * big + 1, big, 1, 2);
  EXPECT_EQ(c.approximate(), sqrt_of(2).approximate());
  EXPECT_EQ(compare(c, sqrt_of(2)), 1);
  EXPECT_EQ(compare(sqrt_of(2), c), -1);
}

std::vector<Slice::Point> points_of(const std::vector<long>& ns) {
  std::vector<Slice::Point> points;
  for (long n : ns) points.push_back(Slice::Point{sqrt_of(n), {}});
  return points;
}

TEST(ToleranceExactOrder, MatchIsTheExactNearestNeighbour) {
  std::mt19937_64 rng(5);
  int decided = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<long> ns;
    for (long n = 2 + static_cast<long>(rng() % 5); ns.size() < 6; n += 1 + static_cast<long>(rng() % 40))
      if (!square(n)) ns.push_back(n);
    std::vector<Slice::Point> points = points_of(ns);
    Rational t(static_cast<long>(rng() % 20000) + 1000, 1000);
    tolerance_detail::PointMatch match = tolerance_detail::match_point(points, t, true);
    std::size_t below = 0;
    for (std::size_t k = 0; k < ns.size(); ++k)
      if (sign_sqrt_minus(ns[k], t) < 0) below = k + 1;
    EXPECT_EQ(match.below, below);
    ASSERT_TRUE(match.at.has_value());
    std::size_t expected = below == 0 ? 0 : below == ns.size() ? below - 1
                          : nearer(ns[below - 1], ns[below], t) <= 0 ? below - 1 : below;
    EXPECT_EQ(*match.at, expected) << trial;
    ++decided;
    // Not in contact: no point is matched unless t is one.
    EXPECT_FALSE(tolerance_detail::match_point(points, t, false).at.has_value());
  }
  EXPECT_EQ(decided, 300);
}

TEST(ToleranceExactOrder, MatchWhereTheDoubleToleranceFails) {
  // sqrt 2 and sqrt(2 + 3e-10), 1.06e-10 apart: both within the former 1e-9 (1 + |v|) of the
  // double nearest sqrt 2, which matched the last of them; the exact match is sqrt 2.
  mpz_class e10("10000000000");
  std::vector<Slice::Point> points{{sqrt_of(2), {}}, {root(2 * e10 + 3, e10, 1, 2), {}}};
  double v = std::sqrt(2.0);
  std::optional<std::size_t> double_rule;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (std::fabs(points[k].at.approximate() - v) <= 1e-9 * (1 + std::fabs(v))) double_rule = k;
  EXPECT_EQ(double_rule, std::optional<std::size_t>(1));
  tolerance_detail::PointMatch match = tolerance_detail::match_point(points, Rational(v), true);
  ASSERT_TRUE(match.at.has_value());
  EXPECT_EQ(*match.at, 0u);
  // At the midpoint of two rationals the distances tie: not decided, said so.
  std::vector<Slice::Point> exact(2);
  exact[0].at.exact = exact[1].at.exact = true;
  exact[0].at.lower = exact[0].at.upper = 1;
  exact[1].at.lower = exact[1].at.upper = 2;
  tolerance_detail::PointMatch tie = tolerance_detail::match_point(exact, Rational(3, 2), true);
  EXPECT_FALSE(tie.at.has_value());
  EXPECT_TRUE(tie.ambiguous);
}

Slice slice_of(const std::vector<AlgebraicNumber>& points, const std::vector<CellKind>& kinds) {
  Slice s;
  for (const AlgebraicNumber& a : points) s.points.push_back(Slice::Point{a, {}});
  for (CellKind k : kinds) {
    Slice::Interval i;
    i.kind = k;
    s.intervals.push_back(i);
  }
  return s;
}

TEST(ToleranceExactOrder, FreeIntervalsInChannel) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<long> ns;
    for (long n = 2 + static_cast<long>(rng() % 5); ns.size() < 5; n += 1 + static_cast<long>(rng() % 30))
      if (!square(n)) ns.push_back(n);
    std::vector<AlgebraicNumber> pts;
    for (long n : ns) pts.push_back(sqrt_of(n));
    std::vector<CellKind> kinds;
    for (int j = 0; j < 6; ++j) kinds.push_back(rng() % 2 ? CellKind::free : CellKind::blocked);
    long lo = 2 + static_cast<long>(rng() % 150), hi = lo + 1 + static_cast<long>(rng() % 60);
    if (square(lo)) ++lo;
    if (square(hi)) ++hi;
    if (hi <= lo) continue;
    Slice s = slice_of(pts, kinds);
    std::size_t expected = 0;   // (sqrt n[j-1], sqrt n[j]) meets (sqrt lo, sqrt hi)
    for (std::size_t j = 0; j < kinds.size(); ++j)
      if (kinds[j] == CellKind::free && (j == 0 || ns[j - 1] < hi) && (j == ns.size() || ns[j] > lo)) ++expected;
    EXPECT_EQ(tolerance_detail::free_intervals_in_channel(s, sqrt_of(lo), sqrt_of(hi)), expected) << trial;
  }
  // A free interval ending 10^-30 above the channel's lower side: it meets the channel (open),
  // while the approximate() values are equal and the former double test found it closed.
  mpz_class big("1000000000000000000000000000000");
  AlgebraicNumber just_above = root(2 * big + 1, big, 1, 2);
  Slice s = slice_of({just_above, sqrt_of(5)}, {CellKind::free, CellKind::blocked, CellKind::free});
  EXPECT_FALSE(just_above.approximate() > sqrt_of(2).approximate());
  EXPECT_EQ(tolerance_detail::free_intervals_in_channel(s, sqrt_of(2), sqrt_of(3)), 1u);
  AlgebraicNumber just_below = root(2 * big - 1, big, 1, 2);
  Slice t = slice_of({just_below, sqrt_of(5)}, {CellKind::free, CellKind::blocked, CellKind::free});
  EXPECT_EQ(tolerance_detail::free_intervals_in_channel(t, sqrt_of(2), sqrt_of(3)), 0u);
}

// The other root of an even polynomial: -a.
AlgebraicNumber negated(AlgebraicNumber a) {
  Rational lower = -a.upper;
  a.upper = -a.lower;
  a.lower = lower;
  return a;
}

// Session 60: the same angle in the other half-turn chart, -1 / a (the operating region's slice
// continued across the follower's seam). Oracle: the closed form -1 / (+-sqrt(n)) = -+sqrt(1 / n):
// against rationals q on its side of 0, sign(b - q) = sign(a - (-1 / q)) (-1 / x increases on
// either side of 0), and against the square root of 1 / n isolated directly; isolating intervals
// with an end at 0, or straddling it, are refined first; 0 itself has no image.
TEST(ToleranceExactOrder, OtherHalfTurnIsMinusTheReciprocal) {
  std::mt19937_64 rng(60);
  int cases = 0;
  for (long n = 2; n < 200; ++n) {
    if (square(n)) continue;
    for (int sign : {1, -1}) {
      AlgebraicNumber a = sqrt_of(n);   // sign sqrt(n), a root of x^2 - n
      if (sign < 0) a = negated(a);
      std::optional<AlgebraicNumber> b = tolerance_detail::other_half_turn(a);
      ASSERT_TRUE(b) << n;
      EXPECT_TRUE(b->lower < b->upper && (b->upper < 0 || b->lower > 0)) << n;
      // -sign / sqrt(n), isolated directly: a root of n x^2 - 1 in (1 / (f + 1), 1 / f), negated
      long f = static_cast<long>(std::floor(std::sqrt(static_cast<double>(n))));
      AlgebraicNumber direct = root(1, n, Rational(1, f + 1), Rational(1, f));
      if (sign > 0) direct = negated(direct);
      EXPECT_EQ(compare(*b, direct), 0) << n;
      for (int k = 0; k < 4; ++k) {
        Rational q(static_cast<long>(rng() % 100000) + 1, static_cast<long>(rng() % 1000) + 1);
        q *= -sign;
        q.canonicalize();
        EXPECT_EQ(compare(*b, q), compare(a, Rational(-1 / q))) << n << " " << q;
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 1000);
  // an isolating interval ending at 0, and one straddling it: refined to exclude 0 first
  AlgebraicNumber minus_half = root(1, 4, Rational(-1), Rational(0));   // 4 x^2 - 1 in (-1, 0)
  std::optional<AlgebraicNumber> two = tolerance_detail::other_half_turn(minus_half);
  ASSERT_TRUE(two);
  EXPECT_EQ(compare(*two, Rational(2)), 0);
  AlgebraicNumber third;   // 3 x - 1 in (-1, 1)
  third.polynomial = {-1, 3};
  third.lower = -1;
  third.upper = 1;
  std::optional<AlgebraicNumber> minus_three = tolerance_detail::other_half_turn(third);
  ASSERT_TRUE(minus_three);
  EXPECT_EQ(compare(*minus_three, Rational(-3)), 0);
  EXPECT_FALSE(tolerance_detail::other_half_turn(tolerance_detail::exact_algebraic(Rational(0))));
  EXPECT_EQ(compare(*tolerance_detail::other_half_turn(tolerance_detail::exact_algebraic(Rational(-2, 7))), Rational(7, 2)), 0);
}

}  // namespace
}  // namespace hipair
