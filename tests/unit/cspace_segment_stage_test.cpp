// The circle–segment stage's kernel numbers and range guard (docs/performance.md, session 29):
// kernel_interval (the interval a kernel number of the stage carries, computed without MPFR
// for numerators and denominators of at most 53 bits) against CGAL's own to_interval of the
// exact rational, double_bounds against lower_double and upper_double, and
// within_segment_filter_range (decided from bit sizes where they decide
// it) against the rounded comparison it replaces, on generated rationals.
#include "algebra/exact_real.hpp"
#include "arrangement/circle_segment_traits.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <CGAL/mpq_class.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test_numbers::canonical;
using test_numbers::random_integer;

// Rationals around the 53-bit boundary of the fast case, exact doubles, thirds, powers of two
// and their neighbours, huge and tiny values.
std::vector<Rational> generated_rationals(std::mt19937_64& random) {
  std::vector<Rational> values{Rational(0), Rational(1), Rational(-1), canonical(1, 3), canonical(-1, 7),
                               canonical(10, 1), canonical(23, 2), canonical(1, 1L << 52)};
  for (int i = 0; i < 6000; ++i) {
    const int num_bits = 1 + static_cast<int>(random() % 60), den_bits = 1 + static_cast<int>(random() % 60);
    values.push_back(canonical(random_integer(random, num_bits, true), random_integer(random, den_bits, false)));
  }
  for (int i = 0; i < 500; ++i) {   // exact doubles: 53-bit integers over powers of two
    mpz_class den = 1;
    den <<= static_cast<unsigned>(random() % 80);
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 53), true), den));
  }
  for (int i = 0; i < 300; ++i) {   // huge and tiny
    values.push_back(canonical(random_integer(random, 150 + static_cast<int>(random() % 300), true),
                               random_integer(random, 1 + static_cast<int>(random() % 40), false)));
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 40), true),
                               random_integer(random, 150 + static_cast<int>(random() % 300), false)));
  }
  return values;
}

TEST(CSpaceSegmentStage, KernelIntervalIsCgalsIntervalOnGeneratedRationals) {
  std::mt19937_64 random(29);
  const std::vector<Rational> values = generated_rationals(random);
  std::size_t fast_exact = 0, fast_inexact = 0, other = 0;
  for (const Rational& q : values) {
    const auto got = cspace::raw::kernel_interval(q);
    const auto want = CGAL::to_interval(q);
    ASSERT_EQ(got.first, want.first) << q.get_str();
    ASSERT_EQ(got.second, want.second) << q.get_str();
    const bool small = mpz_sizeinbase(q.get_num_mpz_t(), 2) <= 53 && mpz_sizeinbase(q.get_den_mpz_t(), 2) <= 53;
    if (!small)
      ++other;
    else if (want.first == want.second)
      ++fast_exact;
    else
      ++fast_inexact;
  }
  EXPECT_GE(fast_exact, 300u);
  EXPECT_GE(fast_inexact, 2000u);
  EXPECT_GE(other, 1000u);
}

TEST(CSpaceSegmentStage, DoubleBoundsAreLowerAndUpperDoubleOnGeneratedRationals) {
  std::mt19937_64 random(292);
  std::vector<Rational> values = generated_rationals(random);
  for (int i = 0; i < 200; ++i) {   // beyond the doubles' range: lower_double's clamping
    mpz_class huge = random_integer(random, 1100 + static_cast<int>(random() % 200), true);
    values.push_back(canonical(huge, 1));
    values.push_back(canonical(1, abs(huge)));
  }
  std::size_t apart = 0;
  for (const Rational& q : values) {
    const auto [lo, hi] = cspace::raw::double_bounds(q);
    ASSERT_EQ(lo, cspace::algebra::lower_double(q)) << q.get_str();
    ASSERT_EQ(hi, cspace::algebra::upper_double(q)) << q.get_str();
    if (lo != hi) ++apart;
  }
  EXPECT_GE(apart, 3000u);
}

TEST(CSpaceSegmentStage, RangeGuardIsTheRoundedComparisonOnGeneratedRationals) {
  std::mt19937_64 random(2929);
  std::vector<Rational> values = generated_rationals(random);
  std::size_t inside = 0, outside = 0, rounded_onto_the_limit = 0;
  for (int exponent : {-5, 0, 3, 52, 60, 200, 400}) {
    const Rational limit = exponent >= 0 ? canonical(mpz_class(1) << exponent, 1) : canonical(1, mpz_class(1) << -exponent);
    std::vector<Rational> cases = values;
    // around the limit: just below, just above (some round onto it), far and near
    for (int shift : {1, 10, 52, 53, 54, 60, 120}) {
      const Rational tiny = canonical(1, mpz_class(1) << shift);
      for (int sign : {1, -1}) {
        cases.push_back(Rational(sign * limit * (1 + tiny)));
        cases.push_back(Rational(sign * limit * (1 - tiny)));
        cases.push_back(Rational(sign * limit * (2 + tiny)));
        cases.push_back(Rational(sign * limit * (2 - tiny)));
        cases.push_back(Rational(sign * limit / 2 * (1 - tiny)));
      }
    }
    cases.push_back(limit);
    cases.push_back(Rational(-limit));
    for (int i = 0; i < 500; ++i) {   // numerators and denominators of sizes around the limit's
      const int den_bits = 1 + static_cast<int>(random() % 100);
      const int num_bits = std::max(1, den_bits + exponent - 3 + static_cast<int>(random() % 7));
      cases.push_back(canonical(random_integer(random, num_bits, true), random_integer(random, den_bits, false)));
    }
    for (const Rational& q : cases) {
      const bool want = std::abs(to_double(q)) <= std::ldexp(1.0, exponent);
      ASSERT_EQ(cspace::raw::within_segment_filter_range(q, exponent), want) << q.get_str() << " 2^" << exponent;
      (want ? inside : outside) += 1;
      if (want && abs(q) > limit) ++rounded_onto_the_limit;
    }
  }
  EXPECT_GE(inside, 5000u);
  EXPECT_GE(outside, 5000u);
  EXPECT_GE(rounded_onto_the_limit, 7u);
}

}  // namespace
}  // namespace hipair
