// Exact univariate algebra behind the C-space adaptor: Sturm counts, root isolation, exact
// comparison of algebraic numbers, simplest rationals, substitutions and signs at algebraic
// points. Values are chosen where doubles fail (2^53 + 1, roots 10^-20 apart).
#include "algebra/exact_real.hpp"
#include "algebra/interval_times.hpp"
#include "algebra/real_filters.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

Polynomial poly(std::initializer_list<long> ascending) {
  Polynomial p;
  for (long c : ascending) p.push_back(mpz_class(c));
  trim(p);
  return p;
}

// The bisection of Real::refine_to as it was written before its integer and filtered form:
// halving canonical rationals, the sign at every midpoint decided exactly. The analysis prints
// doubles taken from these intervals, so the fast form must give the same intervals.
void reference_refine_to(Real& r, const Rational& width) {
  if (r.exact || r.upper - r.lower <= width) return;
  const int lower_sign = sign_at(r.polynomial, r.lower);
  while (r.upper - r.lower > width) {
    Rational middle = (r.lower + r.upper) / 2;
    int s = sign_at(r.polynomial, middle);
    if (s == 0) {
      r.lower = r.upper = middle;
      r.exact = true;
      return;
    }
    if (s == lower_sign)
      r.lower = middle;
    else
      r.upper = middle;
  }
}

// Random square-free products of linear and quadratic factors with integer coefficients (up to
// 2^70, beyond doubles), some with rational roots hit exactly by a dyadic midpoint.
// Session 26: double_between gives a rational strictly between two distinct real algebraic
// numbers (or nothing), and compare_filtered is Real::compare, on generated roots: products of
// linear and quadratic factors with roots up to 2^-60 apart (isolating intervals that overlap
// and double enclosures that touch), exact rationals among them, every ordered pair.
TEST(CSpaceAlgebra, DoubleFilteredSampleAndLocationAreExact) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(20261130);
  std::size_t samples = 0, none = 0, located = 0;
  for (int trial = 0; trial < 120; ++trial) {
    std::vector<Real> numbers;
    for (int q = 0; q < 3; ++q) {
      // (b x - a)(b x - a - e) (x^2 - c): two roots e / b apart, and +-sqrt(c)
      mpz_class a = random.get_z_bits(40) - (mpz_class(1) << 39), b = random.get_z_bits(20) + 1;
      mpz_class e = mpz_class(1) << (trial % 4 == 0 ? 0 : static_cast<int>(mpz_class(random.get_z_range(40)).get_si()));
      mpz_class c = random.get_z_bits(30) + 1;
      Polynomial p{1};
      for (const Polynomial& factor : {Polynomial{-a, b}, Polynomial{-a - e, b}, Polynomial{-c, mpz_class(0), mpz_class(1)}}) {
        Polynomial product(p.size() + factor.size() - 1);
        for (std::size_t i = 0; i < p.size(); ++i)
          for (std::size_t j = 0; j < factor.size(); ++j) product[i + j] += p[i] * factor[j];
        p = product;
      }
      if (q == 0) p = Polynomial{-a, b};   // a rational root, kept as an isolated root
      p = square_free_part(p);
      Rational bound = 1;
      for (const mpz_class& coefficient : p) bound += Rational(abs(coefficient), abs(p.back()));
      for (Real& root : real_roots(p, -bound, bound)) numbers.push_back(std::move(root));
      Rational value(a, b);
      value.canonicalize();
      numbers.push_back(Real::from_rational(value));   // exact, and equal to a root above
    }
    for (const Real& x : numbers)
      for (const Real& y : numbers) {
        int order = compare(x, y);
        if (order < 0) {
          std::optional<Rational> s = double_between(x, y);
          if (!s) {
            ++none;
          } else {
            ++samples;
            ASSERT_LT(x.compare(*s), 0) << x.description() << " < " << *s << " < " << y.description();
            ASSERT_GT(y.compare(*s), 0) << x.description() << " < " << *s << " < " << y.description();
          }
        }
        // compare_filtered at the other number's ends, its midpoint, a rational 2^-70 next to it
        Real fine = y;
        fine.refine_to(Rational(1, mpz_class(1) << 70));
        for (const Rational& r : {y.lower, y.upper, Rational((y.lower + y.upper) / 2), fine.lower, fine.upper}) {
          ASSERT_EQ(compare_filtered(x, r), x.compare(r)) << x.description() << " vs " << r;
          ++located;
        }
      }
  }
  EXPECT_GT(samples, 1000u);
  EXPECT_GT(located, 10000u);
  std::cout << samples << " samples, " << none << " pairs the filter could not separate, " << located << " locations\n";
}

TEST(CSpaceAlgebra, RefineToGivesTheIntervalsOfCanonicalBisection) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(20261127);
  std::size_t checked = 0, exact_hits = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Polynomial p{1};
    int factors = 1 + trial % 4;
    for (int f = 0; f < factors; ++f) {
      mpz_class a = random.get_z_bits(trial % 3 == 0 ? 70 : 12) - (mpz_class(1) << (trial % 3 == 0 ? 69 : 11));
      mpz_class b = random.get_z_bits(8) + 1;
      Polynomial factor = (f + trial) % 3 == 0 ? Polynomial{a, mpz_class(b)}                 // b x + a
                                                : Polynomial{a, mpz_class(0), mpz_class(b)};  // b x^2 + a
      if (trial % 7 == 0 && f == 0) factor = Polynomial{mpz_class(-3 * (trial % 5 + 1)), mpz_class(1) << 6};   // a dyadic root
      Polynomial product(p.size() + factor.size() - 1);
      for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = 0; j < factor.size(); ++j) product[i + j] += p[i] * factor[j];
      p = product;
    }
    p = square_free_part(p);
    if (degree(p) < 1) continue;
    Rational bound = 1;
    for (const mpz_class& c : p) bound += Rational(abs(c), abs(p.back()));   // Cauchy's bound
    std::vector<Real> roots = real_roots(p, -bound, bound);
    for (std::size_t i = 0, n = roots.size(); i < n; ++i) {   // also with reduced ends
      Real reduced = roots[i];
      reduced.lower.canonicalize();
      reduced.upper.canonicalize();
      roots.push_back(reduced);
    }
    for (Real& root : roots) {
      for (int bits : {10, 40, 64, 100}) {
        Real fast = root, reference = root;
        Rational width = (abs(root.lower) + abs(root.upper) + 1) / Rational(mpz_class(1) << bits);
        fast.refine_to(width);
        reference_refine_to(reference, width);
        ASSERT_EQ(fast.exact, reference.exact) << to_string(p, "x") << " at " << bits << " bits";
        // the same numbers, written the same way (an end that never moved is not reduced)
        ASSERT_EQ(fast.lower.get_str(), reference.lower.get_str()) << to_string(p, "x") << " at " << bits << " bits";
        ASSERT_EQ(fast.upper.get_str(), reference.upper.get_str()) << to_string(p, "x") << " at " << bits << " bits";
        // refine_to keeps the root: the polynomial changes sign across the interval
        if (!fast.exact) EXPECT_LT(sign_at(p, fast.lower) * sign_at(p, fast.upper), 0);
        exact_hits += fast.exact;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(exact_hits, 0u);
}

// compare() on roots of different polynomials against the exact order of their squares (roots
// of b x^2 - a are +-sqrt(a / b): compared exactly through a / b), equal ones included.
TEST(CSpaceAlgebra, CompareOrdersSquareRootsExactly) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(7);
  std::vector<std::pair<Real, Rational>> roots;   // root, its square
  for (int i = 0; i < 60; ++i) {
    mpz_class a = random.get_z_bits(i % 2 ? 60 : 10) + 1, b = random.get_z_bits(i % 2 ? 60 : 10) + 1;
    Polynomial p = square_free_part(Polynomial{-a, mpz_class(0), b});
    if (i % 5 == 4) {   // the same number as the previous one, from another polynomial: (x + 7) (b x^2 - a)
      a = roots.back().second.get_num();
      b = roots.back().second.get_den();
      p = square_free_part(Polynomial{-7 * a, -a, 7 * b, b});
    }
    Rational square(a, b);
    square.canonicalize();
    Rational top = square + 1;
    for (Real& root : real_roots(p, Rational(0), top)) roots.emplace_back(root, square);
  }
  ASSERT_GT(roots.size(), 40u);
  for (const auto& [x, x_square] : roots)
    for (const auto& [y, y_square] : roots) {
      int expected = x_square < y_square ? -1 : x_square > y_square ? 1 : 0;
      ASSERT_EQ(compare(x, y), expected) << x.description() << " vs " << y.description();
    }
}

TEST(CSpaceAlgebra, SturmCountsDistinctRoots) {
  // (x - 1)^2 (x + 2) (x - 3): distinct roots -2, 1, 3
  Polynomial p = poly({6, -11, 3, 3, -1});   // -(x-1)^2 (x+2)(x-3) expanded, sign irrelevant
  Polynomial q = square_free_part(p);
  EXPECT_EQ(degree(q), 3);
  SturmSequence sturm(q);
  EXPECT_EQ(sturm.total(), 3);
  EXPECT_EQ(sturm.count(Rational(-2), Rational(1)), 1);   // (-2, 1] holds 1 only
  EXPECT_EQ(sturm.count(Rational(-3), Rational(1)), 2);
  EXPECT_EQ(sturm.count_up_to(Rational(3)), 3);
  EXPECT_EQ(sturm.count_up_to(Rational(-5, 2)), 0);
}

TEST(CSpaceAlgebra, RootsAreIsolatedAndExactWhenRational) {
  // x^3 - 2x = x (x^2 - 2): 0 exact, +-sqrt(2) isolated
  auto roots = real_roots(poly({0, -2, 0, 1}));
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_FALSE(roots[0].exact);
  EXPECT_TRUE(roots[1].exact);
  EXPECT_EQ(roots[1].lower, 0);
  EXPECT_EQ(roots[2].compare(Rational(141421, 100000)), 1);
  EXPECT_EQ(roots[2].compare(Rational(141422, 100000)), -1);
  // roots in a closed interval include its ends
  auto ends = real_roots(poly({-1, 0, 1}), Rational(-1), Rational(1));
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_TRUE(ends[0].exact && ends[1].exact);
}

TEST(CSpaceAlgebra, CloseRootsBeyondDoublePrecision) {
  // (x - a)(x - a - 10^-20) with a = 2^53 + 1: doubles cannot separate them
  mpz_class a = (mpz_class(1) << 53) + 1;
  Rational r1(a), r2 = Rational(a) + Rational(1, mpz_class("100000000000000000000"));
  Polynomial p = from_rationals({r1 * r2, -(r1 + r2), Rational(1)});
  auto roots = real_roots(p);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_EQ(roots[0].compare(r1), 0);
  EXPECT_EQ(roots[1].compare(r2), 0);
  EXPECT_EQ(compare(roots[0], roots[1]), -1);
  Rational between = rational_between(roots[0], roots[1]);
  EXPECT_TRUE(r1 < between && between < r2);
}

TEST(CSpaceAlgebra, EqualAlgebraicNumbersFromDifferentPolynomials) {
  // sqrt(2) as a root of x^2 - 2 and of x^4 - 4 = (x^2 - 2)(x^2 + 2)
  Real a = nth_real_root(poly({-2, 0, 1}), 1);
  Real b = nth_real_root(poly({-4, 0, 0, 0, 1}), 1);
  EXPECT_EQ(compare(a, b), 0);
  Real c = nth_real_root(poly({-3, 0, 1}), 1);   // sqrt(3)
  EXPECT_EQ(compare(a, c), -1);
  EXPECT_EQ(compare(c, b), 1);
}

TEST(CSpaceAlgebra, SimplestRationalBetween) {
  EXPECT_EQ(simplest_between(Rational(1, 3), Rational(1, 2)), Rational(2, 5));
  EXPECT_EQ(simplest_between(Rational(-1, 2), Rational(1, 2)), Rational(0));
  EXPECT_EQ(simplest_between(Rational(3), Rational(5)), Rational(4));
  EXPECT_EQ(simplest_between(Rational(-7, 2), Rational(-3)), Rational(-10, 3));
  Rational lo(314159, 100000), hi(314160, 100000);
  Rational s = simplest_between(lo, hi);
  EXPECT_TRUE(lo < s && s < hi);
  EXPECT_LE(s.get_den(), 100000);
}

// rational_between as it was written before its first pass on the numbers themselves: copies
// refined until their enclosures separate or both are exact.
Rational reference_rational_between(const Real& a, const Real& b) {
  Real x = a, y = b;
  for (;;) {
    const Rational& hi_x = x.upper;
    const Rational& lo_y = y.lower;
    if (hi_x < lo_y) return simplest_between(hi_x, lo_y);
    if (x.exact && y.exact) return simplest_between(x.lower, y.lower);
    if (x.exact && hi_x == lo_y && !y.exact) {
      y.refine();
      continue;
    }
    x.refine();
    y.refine();
  }
}

// Generated ordered pairs a < b of exact rationals and algebraic roots (square roots, roots of
// cubics), with enclosures apart, overlapping, touching an exact end, and rationals 2^-200 apart: the same rational as the reference, strictly between.
TEST(CSpaceAlgebra, RationalBetweenIsTheReferenceOnGeneratedPairs) {
  std::mt19937_64 random(20261130);
  auto rational = [&](int bits) {
    mpz_class n = static_cast<long>(random() % 2000001) - 1000000;
    mpz_class d = static_cast<long>(random() % 999) + 1;
    Rational q(n << (random() % 3 == 0 ? bits : 0), d);
    q.canonicalize();
    return q;
  };
  // q itself, a root of x^2 - m (m = q^2 + 1/k: next to |q|, of q's sign), or the least real root
  // of a cubic whose coefficients are q's numerator and denominator
  auto real_near = [&](const Rational& q, int kind) -> Real {
    if (kind == 0) return Real::from_rational(q);
    if (kind == 1 && sgn(q) != 0) {
      // sqrt(m) with m = q^2 + 1/k, the positive (or negative) root
      Rational m = q * q + Rational(1, static_cast<long>(random() % 97) + 3);
      m.canonicalize();
      Polynomial p{mpz_class(-m.get_num()), mpz_class(0), mpz_class(m.get_den())};
      return nth_real_root(p, sgn(q) > 0 ? 1 : 0);
    }
    Polynomial p{mpz_class(-q.get_num() + 1), mpz_class(q.get_den()), mpz_class(-q.get_num() * q.get_den()),
                 mpz_class(q.get_den() * q.get_den())};
    trim(p);
    std::vector<Real> roots = real_roots(p);
    return roots.empty() ? Real::from_rational(q) : roots.front();
  };
  std::size_t exact_pairs = 0, algebraic_pairs = 0, overlapping = 0, separated = 0;
  for (int i = 0; i < 3000; ++i) {
    Rational p = rational(i % 5 == 0 ? 200 : 0), q = rational(0);
    if (i % 7 == 0) q = p + Rational(1, mpz_class(1) << 200);
    if (i % 11 == 0) q = p + Rational(1, 3);
    q.canonicalize();
    if (p == q) continue;
    if (q < p) std::swap(p, q);
    Real a = real_near(p, static_cast<int>(random() % 3)), b = real_near(q, static_cast<int>(random() % 3));
    if (random() % 4 == 0) a.refine_to(Rational(1, 1024));
    if (random() % 4 == 0) b.refine();
    if (random() % 5 == 0 && b.exact) {
      // an enclosure of a whose upper end touches the exact b
      if (!a.exact && a.upper > b.lower && a.lower < b.lower && sign_at(a.polynomial, b.lower) != 0) {
        Real c = a;
        if (compare(c, b) < 0) {
          c.upper = b.lower;
          a = c;
        }
      }
    }
    const int order = compare(a, b);
    if (order == 0) continue;
    const Real& lo = order < 0 ? a : b;
    const Real& hi = order < 0 ? b : a;
    (lo.exact && hi.exact ? exact_pairs : algebraic_pairs) += 1;
    (lo.upper < hi.lower ? separated : overlapping) += 1;
    const Rational expected = reference_rational_between(lo, hi);
    const Rational got = rational_between(lo, hi);
    EXPECT_EQ(got, expected) << i;
    EXPECT_EQ(lo.compare(got), -1) << i;
    EXPECT_EQ(hi.compare(got), 1) << i;
  }
  EXPECT_GE(exact_pairs, 200u);
  EXPECT_GE(algebraic_pairs, 1000u);
  EXPECT_GE(overlapping, 200u);
  EXPECT_GE(separated, 200u);
}

TEST(CSpaceAlgebra, NthRootInBracket) {
  // roots of (x^2 - 2)(x - 5): -sqrt2, sqrt2, 5; the root number 1 lies in (1, 2)
  Polynomial p = poly({10, -2, -5, 1});
  Real r = nth_real_root_in(p, 1, Rational(1), Rational(2));
  EXPECT_EQ(r.compare(Rational(14142, 10000)), 1);
  EXPECT_EQ(r.compare(Rational(14143, 10000)), -1);
  EXPECT_THROW(nth_real_root_in(p, 2, Rational(1), Rational(2)), NumericError);
}

TEST(CSpaceAlgebra, BivariateSubstitutionsAndSigns) {
  // f = x^2 + y^2 - 1
  IntegerPolynomial2 f{{{-1, 0, 1}, {0}, {1}}};
  Polynomial at_x = substitute_x(f, Rational(3, 5));   // y^2 - 16/25, scaled
  auto roots = real_roots(at_x);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_EQ(roots[1].compare(Rational(4, 5)), 0);
  // line (x, y) = (-1, 0) + u (2, 0): u^2 ... roots u = 0 and u = 1
  Polynomial along = substitute_line(f, Rational(-1), Rational(2), Rational(0), Rational(0));
  auto u = real_roots(along, Rational(0), Rational(1));
  ASSERT_EQ(u.size(), 2u);
  EXPECT_TRUE(u[0].exact && u[1].exact);
  // the point (1/2, sqrt(3)/2) is on the circle, (1/2, sqrt(2)/2) inside
  Real s3 = nth_real_root(poly({-3, 0, 4}), 1);   // sqrt(3)/2
  Real s2 = nth_real_root(poly({-1, 0, 2}), 1);   // sqrt(2)/2
  EXPECT_TRUE(vanishes_at(f, Rational(1, 2), s3));
  EXPECT_EQ(sign_at(f, Rational(1, 2), s3), 0);
  EXPECT_EQ(sign_at(f, Rational(1, 2), s2), -1);
  EXPECT_EQ(sign_at(f, s3, Rational(1, 2)), 0);
}

TEST(CSpaceAlgebra, CertifiedDoubleEvaluation) {
  // f = (x - 1/3)(x + y): the exact value at doubles is within the stated bound
  IntegerPolynomial2 f{{{0, -1}, {-1, 3}, {3}}};   // 3x^2 + 3xy - x - y
  IntervalPolynomial2 g(f);
  for (double x : {0.1, 1.0 / 3, 2.5, -7.25})
    for (double y : {-0.5, 0.3333333333333333, 9.0}) {
      double bound = 0;
      double value = g.evaluate(x, y, &bound);
      Rational exact = Rational(3) * Rational(x) * Rational(x) + Rational(3) * Rational(x) * Rational(y) - Rational(x) -
                       Rational(y);
      EXPECT_LE(abs(exact - Rational(value)), Rational(bound)) << x << " " << y;
      Interval box = g.evaluate(enclose(Rational(x)), enclose(Rational(y)));
      EXPECT_LE(Rational(box.lo), exact);
      EXPECT_GE(Rational(box.hi), exact);
    }
}

// The products by a variable of known sign (two end products) against operator* (four), bound
// for bound and bit for bit, on generated intervals: random magnitudes 2^-70..2^70 and both
// signs, zeros of either sign, infinities, the largest double and the smallest subnormal, in
// every order of signs of both factors (the other factor's sign fixed as each product needs).
namespace interval_products {

std::uint64_t next_state(std::uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return state >> 11;
}

double random_end(std::uint64_t& state) {
  const std::uint64_t r = next_state(state);
  switch (r % 16) {
    case 0: return 0.0;
    case 1: return -0.0;
    case 2: return __builtin_inf();
    case 3: return -__builtin_inf();
    case 4: return 1.7976931348623157e308;
    case 5: return 4.9406564584124654e-324;
    default: break;
  }
  const double mantissa = static_cast<double>(next_state(state) % (1ull << 52)) / 0x1p52 + 1;
  const int exponent = static_cast<int>(next_state(state) % 141) - 70;
  return (r & 32 ? -1 : 1) * std::ldexp(mantissa, exponent);
}

Interval random_interval(std::uint64_t& state) {
  double a = random_end(state), b = random_end(state);
  if (next_state(state) % 8 == 0) b = a;   // a point
  if (b < a) std::swap(a, b);
  if (a == b && std::isinf(a)) {          // no interval of infinity alone: the whole line
    a = -__builtin_inf();
    b = __builtin_inf();
  }
  return {a, b};
}

// An end anywhere: random_end's three times in four, else any normal double (exponent -1022 …
// 1023) or a subnormal, of either sign.
double wide_end(std::uint64_t& state) {
  const std::uint64_t r = next_state(state);
  if (r % 4 != 0) return random_end(state);
  const double mantissa = static_cast<double>(next_state(state) % (1ull << 52)) / 0x1p52 + 1;
  const double v = r % 8 == 1 ? std::ldexp(mantissa, -1074 + static_cast<int>(next_state(state) % 60))   // subnormal
                              : std::ldexp(mantissa, static_cast<int>(next_state(state) % 2046) - 1022);  // anywhere
  return r & 64 ? -v : v;
}

// An interval of wide ends, a point one time in six (infinity alone: the whole line).
Interval wide_interval(std::uint64_t& state) {
  double a = wide_end(state), b = next_state(state) % 6 == 0 ? a : wide_end(state);
  if (b < a) std::swap(a, b);
  if (a == b && std::isinf(a)) return Interval{-__builtin_inf(), __builtin_inf()};
  return Interval{a, b};
}

bool same_bits(Interval a, Interval b) {
  return std::memcmp(&a.lo, &b.lo, sizeof(double)) == 0 && std::memcmp(&a.hi, &b.hi, sizeof(double)) == 0;
}

// f over the box by nested Horner with operator* and operator+ only (the evaluation as it was
// written before the products by a known sign): the oracle of the fast evaluation.
Interval reference_evaluate(const IntegerPolynomial2& f, Interval x, Interval y) {
  Interval result{0, 0};
  for (auto row = f.coefficients.rbegin(); row != f.coefficients.rend(); ++row) {
    Interval inner{0, 0};
    for (auto c = row->rbegin(); c != row->rend(); ++c) inner = inner * y + enclose(*c);
    result = result * x + inner;
  }
  return result;
}

}  // namespace interval_products

TEST(CSpaceAlgebra, ProductsByAKnownSignAreTheGenericProducts) {
  using namespace interval_products;
  std::uint64_t state = 0x2545f4914f6cdd1dull;
  int nonnegative = 0, nonpositive = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const Interval a = random_interval(state);
    Interval b = random_interval(state);
    // the dispatch by b's sign (the slicer's and the sign filter's Horner schemes), every case
    const Interval dispatched = interval_detail::times(a, b), generic_product = a * b;
    ASSERT_TRUE(same_bits(dispatched, generic_product))
        << "times([" << a.lo << ", " << a.hi << "], [" << b.lo << ", " << b.hi << "]): " << dispatched.lo << " "
        << dispatched.hi << " against " << generic_product.lo << " " << generic_product.hi;
    if (b.lo >= 0) {
      ++nonnegative;
      const Interval fast = interval_detail::times_nonnegative(a, b), generic = a * b;
      ASSERT_TRUE(same_bits(fast, generic)) << "[" << a.lo << ", " << a.hi << "] * [" << b.lo << ", " << b.hi
                                            << "]: " << fast.lo << " " << fast.hi << " against " << generic.lo << " "
                                            << generic.hi;
    }
    if (b.hi <= 0) {
      ++nonpositive;
      const Interval fast = interval_detail::times_nonpositive(a, b), generic = a * b;
      ASSERT_TRUE(same_bits(fast, generic)) << "[" << a.lo << ", " << a.hi << "] * [" << b.lo << ", " << b.hi
                                            << "]: " << fast.lo << " " << fast.hi << " against " << generic.lo << " "
                                            << generic.hi;
    }
  }
  // every sign case of both factors was met many times
  EXPECT_GT(nonnegative, 40000);
  EXPECT_GT(nonpositive, 40000);
}

// IntervalPolynomial2::evaluate (products by x and y of known sign where the box allows) and
// rows_at / evaluate_rows against the generic nested Horner, bit for bit, on generated polynomials (bidegree up to
// (4, 4), coefficients up to 2^1100, beyond the doubles' range) over boxes on either side of
// and across the axes; and against the exact value of f at rational points of the box.
TEST(CSpaceAlgebra, IntervalPolynomialEvaluationIsTheGenericHorner) {
  using namespace interval_products;
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  for (int trial = 0; trial < 3000; ++trial) {
    IntegerPolynomial2 f;
    const std::size_t rows = 1 + next_state(state) % 5, columns = 1 + next_state(state) % 5;
    f.coefficients.assign(rows, std::vector<mpz_class>(columns));
    for (auto& row : f.coefficients)
      for (auto& c : row) {
        const std::uint64_t r = next_state(state);
        if (r % 5 == 0) continue;   // some zeros
        c = mpz_class(static_cast<unsigned long>(next_state(state) % 100000));
        if (r % 97 == 1) c <<= 1100;   // beyond the doubles: an unbounded enclosure
        else if (r % 7 == 1) c <<= static_cast<unsigned long>(next_state(state) % 80);
        if (r & 64) c = -c;
      }
    const IntervalPolynomial2 g(f);
    for (int box = 0; box < 20; ++box) {
      // ends: small dyadic rationals of either sign (so the exact value is at hand), and zero
      auto end = [&] {
        const std::uint64_t r = next_state(state);
        if (r % 6 == 0) return Rational(0);
        Rational v(mpz_class(static_cast<unsigned long>(next_state(state) % 4096)), mpz_class(1) << (r % 9));
        return r & 16 ? Rational(-v) : v;
      };
      Rational x0 = end(), x1 = end(), y0 = end(), y1 = end();
      if (x1 < x0) std::swap(x0, x1);
      if (y1 < y0) std::swap(y0, y1);
      const Interval x{enclose(x0).lo, enclose(x1).hi}, y{enclose(y0).lo, enclose(y1).hi};
      const Interval fast = g.evaluate(x, y), reference = reference_evaluate(f, x, y);
      ASSERT_TRUE(same_bits(fast, reference)) << "trial " << trial << " box " << box << ": [" << fast.lo << ", "
                                              << fast.hi << "] against [" << reference.lo << ", " << reference.hi
                                              << "]";
      // the rows at y, shared by boxes of the same y (the culling quadtree's sibling cells)
      std::vector<Interval> rows_at_y;
      g.rows_at(y, rows_at_y);
      const Interval from_rows = g.evaluate_rows(x, rows_at_y);
      ASSERT_TRUE(same_bits(from_rows, reference)) << "trial " << trial << " box " << box << ": rows give ["
                                                   << from_rows.lo << ", " << from_rows.hi << "] against ["
                                                   << reference.lo << ", " << reference.hi << "]";
      for (const Rational& px : {x0, x1, Rational((x0 + x1) / 2)})
        for (const Rational& py : {y0, y1, Rational((y0 + y1) / 2)}) {
          Rational exact = 0;
          for (std::size_t i = rows; i-- > 0;) {
            Rational inner = 0;
            for (std::size_t j = columns; j-- > 0;) inner = inner * py + Rational(f.coefficients[i][j]);
            exact = exact * px + inner;
          }
          if (std::isfinite(fast.lo)) ASSERT_LE(Rational(fast.lo), exact);
          if (std::isfinite(fast.hi)) ASSERT_GE(Rational(fast.hi), exact);
        }
    }
  }
}

// IntervalPolynomial2::evaluate computes its intervals in the two lanes of a vector (lo, hi), the
// scalar form's operations lane by lane: bit for bit the generic nested Horner and the scalar
// rows_at / evaluate_rows, over boxes with any ends — zeros of both signs, subnormals, 10^-300 …
// 10^308, DBL_MAX, infinities, points, boxes across zero — and polynomials with zero, huge and
// unbounded (beyond 2^1024) coefficients, rows of differing lengths.
TEST(CSpaceAlgebra, IntervalPolynomialLanesAreTheScalarHornerOnAnyBox) {
  using namespace interval_products;
  std::uint64_t state = 0xd1b54a32d192ed03ull;
  int boxes = 0, unbounded = 0, mixed = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    IntegerPolynomial2 f;
    const std::size_t rows = 1 + next_state(state) % 5;
    f.coefficients.resize(rows);
    for (auto& row : f.coefficients) {
      row.resize(1 + next_state(state) % 5);
      for (auto& c : row) {
        const std::uint64_t r = next_state(state);
        if (r % 5 == 0) continue;
        c = mpz_class(static_cast<unsigned long>(next_state(state) % 100000));
        if (r % 41 == 1) c <<= 1100;
        else if (r % 3 == 1) c <<= static_cast<unsigned long>(next_state(state) % 1000);
        if (r & 64) c = -c;
      }
    }
    const IntervalPolynomial2 g(f);
    for (int box = 0; box < 25; ++box, ++boxes) {
      const Interval x = wide_interval(state), y = wide_interval(state);
      const Interval lanes = g.evaluate(x, y), reference = reference_evaluate(f, x, y);
      std::vector<Interval> rows_at_y;
      g.rows_at(y, rows_at_y);
      const Interval scalar = g.evaluate_rows(x, rows_at_y);
      ASSERT_TRUE(same_bits(lanes, reference) && same_bits(lanes, scalar))
          << "trial " << trial << " box [" << x.lo << ", " << x.hi << "] x [" << y.lo << ", " << y.hi << "]: ["
          << lanes.lo << ", " << lanes.hi << "] against [" << reference.lo << ", " << reference.hi << "] and ["
          << scalar.lo << ", " << scalar.hi << "]";
      unbounded += !std::isfinite(lanes.lo) || !std::isfinite(lanes.hi);
      mixed += (x.lo < 0 && x.hi > 0) || (y.lo < 0 && y.hi > 0);
    }
  }
  // the exceptional bounds and the boxes across an axis were met many times
  EXPECT_GT(unbounded, 5000);
  EXPECT_GT(mixed, 20000);
  EXPECT_EQ(boxes, 100000);
}

// algebra::horner (from 0) and horner_from_leading (from the leading coefficient), the one-variable
// interval Horner of the quadratic traits' arcs and no-root tests, the sign filter and
// evaluate_rows, computed in the lanes: bit for bit the generic scalar Horner v = v * x + c
// (operator*, operator+) from the same start, over coefficient intervals and x with any ends
// (zeros, subnormals, huge, infinite, points, across zero), 0 to 6 coefficients.
TEST(CSpaceAlgebra, OneVariableHornerIsTheGenericScalarHorner) {
  using namespace interval_products;
  std::uint64_t state = 0x2545f4914f6cdd1dull;
  int mixed = 0, differing_starts = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    std::vector<Interval> c(next_state(state) % 7);
    for (Interval& v : c) v = next_state(state) % 5 == 0 ? Interval{0, 0} : wide_interval(state);
    const Interval x = wide_interval(state);
    Interval from_zero{0, 0};
    for (auto it = c.rbegin(); it != c.rend(); ++it) from_zero = from_zero * x + *it;
    const Interval fast = horner(c, x);
    ASSERT_TRUE(same_bits(fast, from_zero)) << "trial " << trial << ": [" << fast.lo << ", " << fast.hi
                                            << "] against [" << from_zero.lo << ", " << from_zero.hi << "]";
    mixed += x.lo < 0 && x.hi > 0;
    if (c.empty()) continue;
    Interval from_leading = c.back();
    for (auto it = std::next(c.rbegin()); it != c.rend(); ++it) from_leading = from_leading * x + *it;
    const Interval leading = horner_from_leading(c, x);
    ASSERT_TRUE(same_bits(leading, from_leading)) << "trial " << trial << ": from the leading coefficient ["
                                                  << leading.lo << ", " << leading.hi << "] against ["
                                                  << from_leading.lo << ", " << from_leading.hi << "]";
    differing_starts += !same_bits(from_zero, from_leading);
  }
  // boxes across zero, and the two starts giving different bounds, met many times
  EXPECT_GT(mixed, 5000);
  EXPECT_GT(differing_starts, 5000);
}

// enclose(mpz_class) bounds an integer straight from it (mpz_get_d and the bit span of z); it must give the
// bounds of the rational path enclose(Rational(z)) bit for bit, and both must be the tightest
// doubles around z, checked exactly: lo is the greatest double (or -inf) not above z, hi the least
// double (or +inf) not below it, except that beyond the doubles' range a lower bound is DBL_MAX
// and an upper one -DBL_MAX (the overflowed bounds interval_detail::down and up keep). Generated
// integers of 0 to 1,100 bits of either sign: powers of two and their neighbours, 53- and 54-bit
// values (the first inexact conversions), the doubles' largest finite value and its neighbours,
// 2^1024 and beyond.
TEST(CSpaceAlgebra, IntegerEnclosureIsTheRationalEnclosureAndTight) {
  using namespace interval_products;
  const double inf = std::numeric_limits<double>::infinity(), largest = std::numeric_limits<double>::max();
  std::vector<mpz_class> values{mpz_class(0), mpz_class(1), mpz_class(-1)};
  const mpz_class largest_integer(largest);
  for (const mpz_class& base : {largest_integer, mpz_class(mpz_class(1) << 1024), mpz_class(mpz_class(1) << 53), mpz_class(mpz_class(1) << 54)})
    for (long delta = -3; delta <= 3; ++delta) values.push_back(base + delta);
  values.push_back(largest_integer + (mpz_class(1) << 969) - 1);   // truncates to DBL_MAX, rounds to 2^1024
  values.push_back(largest_integer + (mpz_class(1) << 970));       // 2^1024 + ...: infinite conversion
  // 53 and 54 significant bits anywhere (session 53: enclose decides exactness from the bit
  // span): exact and inexact conversions of every size, both signs
  for (unsigned long shift : {0ul, 1ul, 11ul, 64ul, 500ul, 970ul, 971ul})
    for (const mpz_class& m : {mpz_class((mpz_class(1) << 53) - 1), mpz_class((mpz_class(1) << 53) + 1),
                               mpz_class((mpz_class(1) << 52) + 1), mpz_class((mpz_class(1) << 54) - 1)}) {
      values.push_back(m << shift);
      values.push_back(-(m << shift));
    }
  std::uint64_t state = 0x5851f42d4c957f2dull;
  for (int trial = 0; trial < 20000; ++trial) {
    const unsigned long bits = next_state(state) % 1101;
    mpz_class z = 0;
    if (next_state(state) % 4 == 0) {
      z = mpz_class(1) << bits;   // a power of two and a neighbour
      z += static_cast<long>(next_state(state) % 5) - 2;
    } else {
      for (unsigned long done = 0; done < bits; done += 32) z = (z << 32) + static_cast<unsigned long>(next_state(state) & 0xffffffffu);
      z >>= static_cast<unsigned long>((bits + 31) / 32 * 32 - bits);
    }
    values.push_back(next_state(state) % 2 ? mpz_class(-z) : z);
  }
  int finite = 0, inexact = 0, unbounded = 0;
  for (const mpz_class& z : values) {
    const Interval direct = enclose(z), rational = enclose(Rational(z));
    ASSERT_TRUE(same_bits(direct, rational)) << z.get_str(16) << ": [" << direct.lo << ", " << direct.hi
                                             << "] against [" << rational.lo << ", " << rational.hi << "]";
    // the exact oracle
    const Rational exact(z);
    if (std::isfinite(direct.lo)) {
      ASSERT_LE(Rational(direct.lo), exact) << z.get_str(16);
      const double next = std::nextafter(direct.lo, inf);
      if (std::isfinite(next)) ASSERT_GT(Rational(next), exact) << z.get_str(16);
      else ASSERT_EQ(direct.lo, largest) << z.get_str(16);
    } else {
      ASSERT_EQ(direct.lo, -inf);
      ASSERT_LT(exact, Rational(-largest)) << z.get_str(16);
    }
    if (std::isfinite(direct.hi)) {
      ASSERT_GE(Rational(direct.hi), exact) << z.get_str(16);
      const double previous = std::nextafter(direct.hi, -inf);
      if (std::isfinite(previous)) ASSERT_LT(Rational(previous), exact) << z.get_str(16);
      else ASSERT_EQ(direct.hi, -largest) << z.get_str(16);
    } else {
      ASSERT_EQ(direct.hi, inf);
      ASSERT_GT(exact, Rational(largest)) << z.get_str(16);
    }
    if (std::isfinite(direct.lo) && std::isfinite(direct.hi)) ++finite;
    else ++unbounded;
    if (direct.lo != direct.hi) ++inexact;
  }
  // every kind was met
  EXPECT_GT(finite, 1000);
  EXPECT_GT(inexact, 1000);
  EXPECT_GT(unbounded, 100);
}

// GMP's rational functions expect canonical operands and mpq_equal compares numerators and
// denominators: the root bound 1 + max |a_i / a_n| was built from a non-canonical quotient, so
// 2x^2 + 4x + 6 gave 8/2, unequal to 4 under ==. Every bound is now in lowest terms.
TEST(CSpaceAlgebra, RootBoundIsInLowestTerms) {
  EXPECT_EQ(root_bound(Polynomial{mpz_class(6), mpz_class(4), mpz_class(2)}), Rational(4));
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<long>((state >> 33) % 2001) - 1000;
  };
  for (int trial = 0; trial < 500; ++trial) {
    Polynomial p;
    for (int i = 0; i < 2 + trial % 7; ++i) p.emplace_back(next());
    if (p.back() == 0) p.back() = 6 * (trial % 4 + 1);
    Rational bound = root_bound(p);
    mpz_class g;
    mpz_gcd(g.get_mpz_t(), bound.get_num_mpz_t(), bound.get_den_mpz_t());
    EXPECT_EQ(g, 1) << "trial " << trial;
    Rational reduced(bound);
    reduced.canonicalize();
    EXPECT_EQ(bound, reduced) << "trial " << trial;
  }
}

}  // namespace
}  // namespace hipair::cspace::algebra
