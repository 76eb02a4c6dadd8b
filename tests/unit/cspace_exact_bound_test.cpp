// first_crossing's lazy exact bounds and reused stretch stack (src/cspace/exact_bound.hpp,
// used by src/cspace/cspace_queries.cpp). Oracles: GMP's own comparisons of the rationals the
// bounds stand for, a std::vector of rational pairs, and the same first_crossing queries with
// the lazy bounds off (every bound an owned rational, as before them).
#include "cspace/exact_bound.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/crossing_before.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using cspace::ExactBound;
using cspace::Side;

int sign(int c) { return (c > 0) - (c < 0); }

// a finite double: small integers and halves, values in [-1, 1] (the pieces' range), +-0, the
// smallest subnormals, huge magnitudes, or random bits
double random_double(std::mt19937_64& random) {
  switch (random() % 6) {
    case 0: return static_cast<double>(static_cast<int>(random() % 9) - 4) / (1 + random() % 2);
    case 1: return std::uniform_real_distribution<double>(-1, 1)(random);
    case 2: return random() % 2 ? 0.0 : -0.0;
    case 3: return std::bit_cast<double>(std::uint64_t{1 + random() % 4}) * (random() % 2 ? 1 : -1);
    case 4: return std::ldexp(std::uniform_real_distribution<double>(-1, 1)(random), static_cast<int>(random() % 2000) - 1000);
    default: {
      double d;
      do d = std::bit_cast<double>(static_cast<std::uint64_t>(random())); while (!std::isfinite(d));
      return d;
    }
  }
}

// a rational near d: d itself, its neighbouring doubles, d +- 2^-1100 or +- 2^-60 |d|, or p/q
Rational rational_near(double d, std::mt19937_64& random) {
  const double inf = std::numeric_limits<double>::infinity();
  Rational tiny(1);
  switch (random() % 6) {
    case 0: return Rational(d);
    case 1: return Rational(std::nextafter(d, random() % 2 ? inf : -inf));
    case 2: {
      mpq_div_2exp(tiny.get_mpq_t(), tiny.get_mpq_t(), 1100);
      return random() % 2 ? Rational(Rational(d) + tiny) : Rational(Rational(d) - tiny);
    }
    case 3: {
      Rational r(d), step = r * Rational(1, 1L << 60);
      return random() % 2 ? Rational(r + step) : Rational(r - step);
    }
    case 4: return Rational(static_cast<long>(random() % 7) - 3, 1 + static_cast<long>(random() % 5));
    default: {
      Rational r(static_cast<long>(random() % 2001) - 1000, 1 + static_cast<long>(random() % 997));
      r.canonicalize();
      return r;
    }
  }
}

// the bound in one of its three forms (a double, an owned rational, a borrowed one)
ExactBound make_bound(double d, const Rational& keep, int form) {
  if (form == 0) return ExactBound::of_double(d);
  if (form == 1) return ExactBound(Rational(d));
  return ExactBound::borrowed(keep);
}

// doubles lo <= r <= hi: r's own double when exact, else a few doubles either side of it
std::pair<double, double> enclosure(const Rational& r, std::mt19937_64& random) {
  const double inf = std::numeric_limits<double>::infinity();
  double d = r.get_d();
  if (Rational(d) == r && random() % 2) return {d, d};
  double lo = d, hi = d;
  for (int i = 0, n = 1 + static_cast<int>(random() % 3); i < n; ++i) {
    lo = std::nextafter(lo, -inf);
    hi = std::nextafter(hi, inf);
  }
  return {lo, hi};
}

TEST(CSpaceExactBound, ComparesAsItsRational) {
  std::mt19937_64 random(20261130);
  std::size_t filtered = 0, exact = 0;
  for (int i = 0; i < 200000; ++i) {
    const double d = random_double(random);
    const Rational value(d);
    const Rational r = rational_near(random() % 4 ? d : random_double(random), random);
    const int form = static_cast<int>(random() % 3);
    const Rational keep(d);
    const ExactBound b = make_bound(d, keep, form);
    const std::string where = "d " + std::to_string(d) + " (bits " + std::to_string(std::bit_cast<std::uint64_t>(d)) +
                              ") form " + std::to_string(form) + " r " + r.get_str();
    ASSERT_EQ(b.rational(), value) << where;
    const int expected = sign(cmp(value, r));
    ASSERT_EQ(sign(compare(b, r)), expected) << where;
    ASSERT_EQ(r < b, expected > 0) << where;
    ASSERT_EQ(r > b, expected < 0) << where;
    // a second bound in any form
    const double e = random() % 3 ? r.get_d() : d;
    const Rational keep_e(e);
    const ExactBound c = make_bound(e, keep_e, static_cast<int>(random() % 3));
    const int expected_bc = sign(cmp(value, Rational(e)));
    ASSERT_EQ(sign(compare(b, c)), expected_bc) << where << " e " << e;
    ASSERT_EQ(b > c, expected_bc > 0) << where << " e " << e;
    ASSERT_EQ(b == c, expected_bc == 0) << where << " e " << e;
    // against a side r with its doubles
    auto [lo, hi] = enclosure(r, random);
    const Side side{r, lo, hi};
    const bool decided_by_doubles = form == 0 && (d < lo || d > hi);
    (decided_by_doubles ? filtered : exact) += 1;
    ASSERT_EQ(sign(compare(b, side)), expected) << where;
    ASSERT_EQ(b < side, expected < 0) << where;
    ASSERT_EQ(b > side, expected > 0) << where;
    ASSERT_EQ(b <= side, expected <= 0) << where;
    ASSERT_EQ(b >= side, expected >= 0) << where;
    const ExactBound high = max_with(b, side), low = min_with(b, side);
    ASSERT_EQ(high.rational(), std::max(value, r)) << where;
    ASSERT_EQ(low.rational(), std::min(value, r)) << where;
  }
  std::printf("exact bounds: %zu sides decided by the doubles, %zu exactly\n", filtered, exact);
  EXPECT_GT(filtered, 10000u);
  EXPECT_GT(exact, 10000u);
}

TEST(CSpaceExactBound, StretchStackIsAStack) {
  std::mt19937_64 random(20261131);
  for (int run = 0; run < 200; ++run) {
    cspace::StretchStack stack;
    std::vector<std::pair<Rational, Rational>> model;
    for (int op = 0; op < 400; ++op) {
      if (!model.empty() && random() % 5 < 2) {
        ASSERT_EQ(stack.back().first, model.back().first);
        ASSERT_EQ(stack.back().second, model.back().second);
        stack.pop_back();
        model.pop_back();
      } else {
        // rationals of every size: the reused slots' limbs grow and shrink
        Rational a(static_cast<long>(random() % 1000), 1 + static_cast<long>(random() % 1000));
        Rational b = a;
        mpq_div_2exp(b.get_mpq_t(), b.get_mpq_t(), static_cast<unsigned long>(random() % 300));
        if (random() % 2) std::swap(a, b);
        stack.emplace_back(a, b);
        model.emplace_back(a, b);
      }
      ASSERT_EQ(stack.empty(), model.empty());
      if (!model.empty()) {
        ASSERT_EQ(stack.back().first, model.back().first) << "run " << run << " op " << op;
        ASSERT_EQ(stack.back().second, model.back().second) << "run " << run << " op " << op;
      }
    }
  }
}

// The queries with the lazy bounds equal the queries with every bound an owned rational (the
// representation before them), field for field, run to the end and stopped and resumed.
TEST(CSpaceExactBound, QueriesEqualTheQueriesWithRationalBounds) {
  std::mt19937_64 random(20261132);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::size_t queries = 0, crossings = 0;
  for (int query = 0; query < 400; ++query) {
    test::GeneratedQuery g;
    if (!test::random_query(spaces, random, g)) continue;
    const CSpace& space = *spaces[g.s];
    ++queries;
    crossings += g.answer.status == CrossingStatus::crossing;
    cspace::lazy_bounds() = false;
    MotionCrossing oracle = space.first_crossing(g.path);
    cspace::lazy_bounds() = true;
    const std::string expected = test::describe_crossing(space, oracle);
    const std::string where = "query " + std::to_string(query) + " space " + std::to_string(g.s) + " kind " +
                              std::to_string(g.kind) + "; oracle " + expected;
    ASSERT_EQ(test::describe_crossing(space, g.answer), expected) << where;
    ASSERT_EQ(g.answer.u_lower, oracle.u_lower) << where;
    ASSERT_EQ(g.answer.u_upper, oracle.u_upper) << where;
    // stopped halfway and resumed: the stack's reused slots across a stop
    CrossingQuery q(space, g.path, CrossingOptions{});
    Rational stop(std::uniform_real_distribution<double>(0, 1)(random));
    q.run(&stop);
    q.run(nullptr);
    ASSERT_EQ(test::describe_crossing(space, q.answer()), expected) << where;
  }
  cspace::lazy_bounds() = true;
  std::printf("lazy bounds: %zu queries, %zu crossings\n", queries, crossings);
  EXPECT_GT(queries, 300u);
  EXPECT_GT(crossings, 50u);
}

}  // namespace
}  // namespace hipair
