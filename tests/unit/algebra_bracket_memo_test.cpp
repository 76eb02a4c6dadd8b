// Session 46 (scale46): the per-thread memo of the MPFR brackets multiprecision_order and
// multiprecision_sign narrow (src/algebra/multiprecision_sign.cpp, RememberedBracket). A
// number's second order starts from the bracket its first one reached; a bracket remembered at
// one precision and loaded at a lower one (rounded outwards, or u's rational end again) must
// still hold the number, so that no order or sign is ever wrong. Generated wide numbers (roots
// of random quadratics and cubics of 200-1 000-bit coefficients, some near 2^+-300), neighbours
// 2^-t of their size apart near each precision's floor, equal numbers by another polynomial;
// every answer against the exact path (rational bisection, the gcd's roots).
#include "algebra/multiprecision_sign.hpp"
#include "random_algebraic.hpp"
#include "random_rationals.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

using test_numbers::random_integer;

using test_algebraic::times;
using test_algebraic::random_irrational;

using test_algebraic::moved;

// u moved by +-(1 + k) 2^-t (|u.lower| + |u.upper|), k < 100.
Real neighbour(std::mt19937_64& random, const Real& u, int t, Rational* delta_out = nullptr) {
  Rational delta(Rational(mpz_class(1) + static_cast<long>(random() % 100)) / Rational(mpz_class(1) << static_cast<mp_bitcnt_t>(t)));
  delta *= abs(u.lower) + abs(u.upper);
  if (random() & 1) delta = -delta;
  if (delta_out) *delta_out = delta;
  return Real{moved(u.polynomial, delta), u.lower + delta, u.upper + delta, false};
}

// u by u's polynomial times a factor without real roots (the same number, another key).
Real same_number(std::mt19937_64& random, const Real& u) {
  const Polynomial factor{abs(random_integer(random, 1 + static_cast<int>(random() % 200), false)) + 1, 0,
                          abs(random_integer(random, 1 + static_cast<int>(random() % 200), false)) + 1};
  return Real{times(u.polynomial, factor), u.lower, u.upper, false};
}

// The second order of the same two numbers at the same precisions starts from the brackets the
// first one left, which already separate them: no enclosure at all (the first took many). Uses
// only functions the library had before the memo, so that it can be run against that library:
// there every second order costs what the first did.
TEST(AlgebraBracketMemo, TheSecondOrderOfTheSameNumbersNeedsNoEnclosure) {
  std::mt19937_64 random(4646);
  int pairs = 0, separated = 0, narrowed = 0;
  for (int round = 0; round < 24; ++round) {
    const int bits = 200 + static_cast<int>(random() % 800);
    auto drawn = random_irrational(random, bits, round % 3 == 0 ? 0 : (round % 3 == 1 ? 300 : -300));
    if (!drawn) continue;
    const Real& u = *drawn;
    const int t = 2 * bits + static_cast<int>(random() % 1000);
    Rational delta;
    const Real v = neighbour(random, u, t, &delta);
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits, t = " + std::to_string(t) + ")";
    const MultiprecisionBits b = multiprecision_order_bits(u, v);
    const long before = multiprecision_enclosures();
    const auto first = multiprecision_order(u, v, b.start, b.cap);
    const long middle = multiprecision_enclosures();
    const auto second = multiprecision_order(u, v, b.start, b.cap);
    const long after = multiprecision_enclosures();
    ++pairs;
    EXPECT_EQ(compare(v, u), sgn(delta)) << at << ": compare";
    if (!first) {   // (not separated at the cap, as without the memo: the exact path decides)
      EXPECT_FALSE(second) << at << ": the second order was given, the first not";
      continue;
    }
    ++separated;
    ASSERT_TRUE(second) << at << ": the second order was not given";
    EXPECT_EQ(*first, -sgn(delta)) << at << ": the first order is wrong";
    EXPECT_EQ(*second, -sgn(delta)) << at << ": the second order is wrong";
    if (middle - before > 0) ++narrowed;
    EXPECT_EQ(after - middle, 0) << at << ": the second order took " << after - middle << " enclosures (the first "
                                 << middle - before << ")";
  }
  EXPECT_GT(pairs, 12);
  EXPECT_GT(narrowed, 10);
  std::printf("%d pairs, %d separated by MPFR, %d of them after narrowing\n", pairs, separated, narrowed);
}

// A number's bracket narrowed at 4P (to that precision's floor, against a neighbour 2^-(4P - 8
// ... 4P + 8) of its size away), then ordered at P alone against neighbours 2^-(P - 8 ... P + 8)
// away and against itself by another polynomial: the remembered bracket is loaded rounded
// outwards (or as u's rational end). Every order given must be right, equal numbers never
// ordered, and the remembered bracket must hold the number after each step.
TEST(AlgebraBracketMemo, BracketsRememberedAtOnePrecisionAndLoadedAtAnotherHoldTheNumber) {
  std::mt19937_64 random(46046);
  int cases = 0, ordered = 0, remembered = 0;
  auto holds = [&](const Real& u, const std::string& at) {
    const auto r = remembered_bracket(u);
    if (!r) return;
    ++remembered;
    EXPECT_GE(u.compare(r->first), 0) << at << ": the remembered lower end is above the number";
    EXPECT_LE(u.compare(r->second), 0) << at << ": the remembered upper end is below the number";
  };
  for (int round = 0; round < 40; ++round) {
    const long precision = 192L << (random() % 3);
    const int bits = 200 + static_cast<int>(random() % 400);
    auto drawn = random_irrational(random, bits, round % 3 == 0 ? 0 : (round % 3 == 1 ? 300 : -300));
    if (!drawn) continue;
    const Real& u = *drawn;
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits, P = " + std::to_string(precision) + ")";
    // 1. narrowed at 4P, in either order of the arguments
    {
      Rational delta;
      const int t = static_cast<int>(4 * precision) - 8 + static_cast<int>(random() % 17);
      const Real far = neighbour(random, u, t, &delta);
      const auto order = (round & 1) ? multiprecision_order(u, far, 4 * precision, 4 * precision)
                                     : multiprecision_order(far, u, 4 * precision, 4 * precision);
      ++cases;
      if (order) {
        ++ordered;
        EXPECT_EQ(*order, (round & 1) ? -sgn(delta) : sgn(delta)) << at << ": at 4P, the order is wrong";
      }
      holds(u, at + ", after 4P");
      holds(far, at + ", the neighbour after 4P");
    }
    // 2. at P: three neighbours near P's floor and the same number by another polynomial
    for (int k = 0; k < 3; ++k) {
      Rational delta;
      const int t = static_cast<int>(precision) - 8 + static_cast<int>(random() % 17);
      const Real v = neighbour(random, u, t, &delta);
      const auto order = multiprecision_order(u, v, precision, precision);
      ++cases;
      if (order) {
        ++ordered;
        EXPECT_EQ(*order, -sgn(delta)) << at << ", neighbour " << k << " at 2^-" << t << ": the order is wrong";
      }
      EXPECT_EQ(compare(v, u), sgn(delta)) << at << ", neighbour " << k << ": compare";
      holds(u, at + ", after neighbour " + std::to_string(k));
      holds(v, at + ", neighbour " + std::to_string(k));
    }
    const Real w = same_number(random, u);
    const auto order = multiprecision_order(w, u, precision, precision);
    ++cases;
    EXPECT_FALSE(order) << at << ": the same number ordered " << *order;
    EXPECT_EQ(compare(u, w), 0) << at << ": compare of the same number";
    holds(u, at + ", after itself");
    holds(w, at + ", itself by another polynomial");
  }
  EXPECT_GT(cases, 120);
  EXPECT_GT(ordered, 20);
  EXPECT_GT(remembered, 150);
  std::printf("%d cases, %d ordered, %d remembered brackets checked\n", cases, ordered, remembered);
}

// Clusters of numbers 2^-(w ... w + 300) of their size apart (w the coefficients' bits),
// sorted by compare with the memo (each number met by many comparisons, its bracket carried from
// one to the next, signs of polynomials at them between): the same order as the exact path's
// and as with the memo off, and sign_at equal to the exact path's.
TEST(AlgebraBracketMemo, ClustersSortAndSignAsTheExactPath) {
  std::mt19937_64 random(460046);
  int clusters = 0, comparisons = 0, signs = 0;
  const long hits_before = multiprecision_bracket_memo_hits();
  for (int round = 0; round < 5; ++round) {
    const int bits = 200 + static_cast<int>(random() % 200);
    auto drawn = random_irrational(random, bits, round % 2 == 0 ? 0 : 300);
    if (!drawn) continue;
    ++clusters;
    std::vector<Real> numbers{*drawn};
    for (int k = 0; k < 5; ++k) numbers.push_back(neighbour(random, *drawn, bits + static_cast<int>(random() % 300)));
    numbers.push_back(same_number(random, *drawn));
    std::vector<int> expected;   // expected[i * n + j] = exact_compare(i, j)
    const std::size_t n = numbers.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) expected.push_back(exact_compare(numbers[i], numbers[j]));
    for (int pass = 0; pass < 2; ++pass) {
      const bool was = set_multiprecision_bracket_memo(pass == 0);
      std::vector<std::size_t> order(n);
      for (std::size_t i = 0; i < n; ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), random);
      for (std::size_t i : order)
        for (std::size_t j : order) {
          ++comparisons;
          EXPECT_EQ(compare(numbers[i], numbers[j]), expected[i * n + j])
              << "cluster " << round << ", numbers " << i << " and " << j << (pass == 0 ? " (memo on)" : " (memo off)");
        }
      // signs of a neighbour's polynomial (a value cancelling deeply) at each number
      for (std::size_t i : order) {
        const Polynomial& p = numbers[(i + 1) % n].polynomial;
        ++signs;
        EXPECT_EQ(sign_at(p, numbers[i]), exact_sign_at(p, numbers[i])) << "cluster " << round << ", sign at number " << i;
      }
      set_multiprecision_bracket_memo(was);
    }
  }
  EXPECT_GE(clusters, 3);
  EXPECT_GT(multiprecision_bracket_memo_hits() - hits_before, 100) << "the memo was not used";
  std::printf("%d clusters, %d comparisons, %d signs\n", clusters, comparisons, signs);
}

// Two roots c -+ sqrt(e) of one quadratic, 2 sqrt(e) ~ 2^-(K - 1) apart (K = 280 ... 330, c a
// non-dyadic rational near 1/2): u one of them, its isolating interval ending at c, the other root
// less than one ulp of P = 192 bits beyond that end. u's bracket is narrowed at 1 536 bits (the
// memo then holds MPFR ends strictly inside (c, u) or (u, c)); ordered at P (doubling to 1 536)
// against u moved 2^-(K + 10) towards the other root, the remembered end rounded at P lies past
// the other root: it must become u's rational end again, or the bisection at 2P takes a midpoint
// beyond the other root for one on u's far side, Newton converges to the other root and the
// order is wrong. Every order given must be right and the remembered bracket must hold u.
TEST(AlgebraBracketMemo, AnEndRoundedPastTheIntervalIsTheRationalEndAgain) {
  std::mt19937_64 random(46464);
  int cases = 0, ordered = 0;
  for (int round = 0; round < 16; ++round) {
    const int k = 280 + static_cast<int>(random() % 51);
    const long d = 3 + 2 * static_cast<long>(random() % 50);   // odd: c = n / d not dyadic
    const Rational c(mpz_class(d / 2 + static_cast<long>(random() % 3) - 1), mpz_class(d));
    const bool upper_root = round % 2 == 0;   // u = c + sqrt(e), its interval (c, c + 1/4)
    // q = (x - c)^2 - e, e = 3 * 2^-2k: d^2 2^2k x^2 - 2 n d 2^2k x + n^2 2^2k - 3 d^2
    const mpz_class n = c.get_num(), den = c.get_den(), two_k = mpz_class(1) << static_cast<mp_bitcnt_t>(2 * k);
    const Polynomial q{n * n * two_k - 3 * den * den, -2 * n * den * two_k, den * den * two_k};
    const Rational quarter(1, 4);
    const Real u = upper_root ? Real{q, c, c + quarter, false} : Real{q, c - quarter, c, false};
    ASSERT_EQ(sgn(value_at(q, u.lower)) * sgn(value_at(q, u.upper)), -1);
    const std::string at = "round " + std::to_string(round) + " (K = " + std::to_string(k) + ", c = " + c.get_str() +
                           (upper_root ? ", the upper root)" : ", the lower root)");
    // 1. the memo narrowed at 1 536 bits against a neighbour 2^-1 100 away
    {
      const Rational delta = Rational(upper_root ? 1 : -1) / Rational(mpz_class(1) << 1100);
      const Real w{moved(q, delta), u.lower + delta, u.upper + delta, false};
      const auto order = multiprecision_order(u, w, 1536, 1536);
      ASSERT_TRUE(order) << at << ": not separated at 1 536 bits";
      EXPECT_EQ(*order, -sgn(delta)) << at << ": at 1 536 bits";
    }
    // 2. at 192 bits, doubling to 6 144, against u moved towards the other root
    const Rational delta = Rational(upper_root ? -1 : 1) / Rational(mpz_class(1) << static_cast<mp_bitcnt_t>(k + 10));
    const Real v{moved(q, delta), u.lower + delta, u.upper + delta, false};
    const auto order = multiprecision_order(u, v, 192, 6144);
    ++cases;
    if (order) {
      ++ordered;
      EXPECT_EQ(*order, -sgn(delta)) << at << ": the order is wrong";
    }
    EXPECT_EQ(compare(u, v), -sgn(delta)) << at << ": compare";
    if (const auto r = remembered_bracket(u)) {
      EXPECT_GE(u.compare(r->first), 0) << at << ": the remembered lower end is above u";
      EXPECT_LE(u.compare(r->second), 0) << at << ": the remembered upper end is below u";
    }
  }
  EXPECT_EQ(cases, 16);
  EXPECT_GT(ordered, 8);
  std::printf("%d cases, %d ordered\n", cases, ordered);
}

}  // namespace
}  // namespace hipair::cspace::algebra
