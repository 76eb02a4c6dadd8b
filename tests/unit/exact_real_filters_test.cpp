// The certified double filters of exact_real.cpp against the exact paths they stand in front of:
// enclose(Rational) in one pass against the two-pass bounds (nearest-towards-zero double, moved
// outwards by the exact sign of the difference), the sign filter's coefficients through
// compare_filtered and refine_to, and compare()/equal() with the one-polynomial test before the
// double bisection against the closed-form order of roots ±sqrt(q) and rationals. Generated
// values: random rationals of 1 to 1,200 bits, scales 2^-1000..2^1000, dyadic and subnormal
// values, equal numbers from different polynomials, numbers differing in the last bit.
#include "algebra/exact_real.hpp"
#include "algebra/rational_order.hpp"
#include "algebra/real_filters.hpp"
#include "algebra/real_approximation.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

// The enclosure as it was computed before the one-pass form: d = r.get_d() (towards zero), the
// exact sign of r - d (the double as an exact rational), the bound on the far side moved to the
// next double; beyond the doubles' range the largest finite double.
Interval reference_enclose(const Rational& r) {
  const double d = r.get_d();
  if (std::isinf(d))
    return {d > 0 ? std::numeric_limits<double>::max() : d, d < 0 ? std::numeric_limits<double>::lowest() : d};
  const int c = cmp(r, Rational(d));
  return {c < 0 ? std::nextafter(d, -HUGE_VAL) : d, c > 0 ? std::nextafter(d, HUGE_VAL) : d};
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

mpz_class random_integer(std::mt19937_64& random, unsigned bits) {
  mpz_class z = 0;
  for (unsigned done = 0; done < bits; done += 64) {
    z <<= 64;
    z += mpz_class(static_cast<unsigned long>(random()));
  }
  if (bits % 64 != 0) z >>= 64 - bits % 64;
  return z;
}

std::vector<Rational> generated_rationals(std::mt19937_64& random, int count) {
  std::vector<Rational> values;
  auto sign = [&](Rational r) { return random() % 2 ? r : Rational(-r); };
  for (int i = 0; i < count; ++i) {
    const unsigned num_bits = 1 + static_cast<unsigned>(random() % 1200), den_bits = 1 + static_cast<unsigned>(random() % 1200);
    mpz_class num = random_integer(random, num_bits), den = random_integer(random, den_bits);
    if (den == 0) den = 1;
    Rational r(num, den);
    r.canonicalize();
    values.push_back(sign(r));
    // dyadic: a numerator of 40..60 bits over 2^k, k up to 1,100 (normal, subnormal, beyond)
    const unsigned k = static_cast<unsigned>(random() % 1101);
    mpz_class odd = random_integer(random, 40 + static_cast<unsigned>(random() % 21));
    mpz_setbit(odd.get_mpz_t(), 0);
    Rational dyadic(odd, mpz_class(1) << k);
    dyadic.canonicalize();
    values.push_back(sign(dyadic));
    // an exact double of any exponent (subnormals included), and its neighbours' rationals
    std::uint64_t bits = random() & 0x7FEFFFFFFFFFFFFFull;
    double d = 0;
    std::memcpy(&d, &bits, sizeof d);
    values.push_back(sign(Rational(d)));
    values.push_back(sign(Rational(Rational(d) + Rational(1, mpz_class(1) << 1200))));
    values.push_back(sign(Rational(Rational(d) - Rational(1, mpz_class(1) << 1200))));
    // 2^53 +- 1 and friends over small denominators
    const long offset = static_cast<long>(random() % 5) - 2;
    Rational near(mpz_class(1) << (53 + random() % 3), mpz_class(1 + random() % 7));
    near += offset;
    near.canonicalize();
    values.push_back(sign(near));
  }
  values.push_back(Rational(0));
  values.push_back(Rational(mpz_class(1) << 1100));
  values.push_back(Rational(-Rational(mpz_class(1) << 1100)));
  values.push_back(Rational(mpz_class(1), mpz_class(1) << 1100));
  values.push_back(Rational(mpz_class(1), mpz_class(1) << 1074));
  values.push_back(Rational(mpz_class(1), mpz_class(1) << 1022));
  values.push_back(Rational(mpz_class(3), mpz_class(1) << 1023));
  return values;
}

TEST(ExactRealFilters, EncloseIsTheReferenceBoundsBitForBit) {
  std::mt19937_64 random(20261201);
  const std::vector<Rational> values = generated_rationals(random, 20000);
  ASSERT_GT(values.size(), 100000u);
  for (const Rational& r : values) {
    const Interval got = enclose(r), want = reference_enclose(r);
    ASSERT_TRUE(same_bits(got.lo, want.lo) && same_bits(got.hi, want.hi))
        << r.get_str() << ": [" << got.lo << ", " << got.hi << "] against [" << want.lo << ", " << want.hi << "]";
    // certified: lo <= r <= hi whenever the bound is finite
    if (std::isfinite(got.lo) && got.lo != std::numeric_limits<double>::max()) ASSERT_LE(Rational(got.lo), r);
    if (std::isfinite(got.hi) && got.hi != std::numeric_limits<double>::lowest()) ASSERT_GE(Rational(got.hi), r);
  }
}

// ---------------------------------------------------------------- roots with a closed-form order

// s sqrt(q): s in {-1, 0, 1}, q > 0 (q = 0 when s = 0); rational when q is a square.
struct Known {
  int s = 0;
  Rational q;
};

int order(const Known& a, const Known& b) {
  if (a.s != b.s) return a.s < b.s ? -1 : 1;
  if (a.s == 0) return 0;
  const int c = cmp(a.q, b.q);
  return a.s > 0 ? (c > 0) - (c < 0) : (c < 0) - (c > 0);
}

Polynomial times(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}

// A factor with its known roots: den x - num (root num / den), or den x^2 - num (roots +- sqrt).
struct Factor {
  Polynomial p;
  std::vector<Known> roots;
};

Factor linear(const Rational& r) {
  Factor f;
  f.p = {-r.get_num(), r.get_den()};
  f.roots.push_back(Known{sgn(r), r * r});
  return f;
}

Factor square_root_pair(const Rational& q) {   // x^2 - q, q > 0 not a square
  Factor f;
  f.p = {-q.get_num(), mpz_class(0), q.get_den()};
  f.roots.push_back(Known{-1, q});
  f.roots.push_back(Known{1, q});
  return f;
}

// A non-square positive rational near `magnitude` squared: (2 m + 1) / 2 times a square scale.
Rational non_square(std::mt19937_64& random, int exponent) {
  Rational q(mpz_class(2 * (1 + random() % 1000) + 1), mpz_class(2));   // (2m + 1)/2: never a square
  if (exponent >= 0) q *= Rational(mpz_class(1) << (2 * exponent));
  else q /= Rational(mpz_class(1) << (-2 * exponent));
  q.canonicalize();
  return q;
}

struct Numbers {
  std::vector<Real> reals;
  std::vector<Known> known;
};

// The roots of the product of `factors` (distinct: square-free), isolated, with their known values,
// each in several versions of its isolating interval (as isolated, refined to random widths,
// dyadically, narrowed at random inner rationals).
void add_roots(const std::vector<Factor>& factors, std::mt19937_64& random, Numbers& out) {
  Polynomial p{mpz_class(1)};
  std::vector<Known> known;
  for (const Factor& f : factors) {
    p = times(p, f.p);
    known.insert(known.end(), f.roots.begin(), f.roots.end());
  }
  std::sort(known.begin(), known.end(), [](const Known& a, const Known& b) { return order(a, b) < 0; });
  std::vector<Real> roots = real_roots(p);
  ASSERT_EQ(roots.size(), known.size());
  for (std::size_t i = 0; i < roots.size(); ++i) {
    out.reals.push_back(roots[i]);
    out.known.push_back(known[i]);
    if (roots[i].exact) continue;
    Real refined = roots[i];
    refined.refine_to((roots[i].upper - roots[i].lower) / Rational(mpz_class(1) << (1 + random() % 80)));
    out.reals.push_back(refined);
    out.known.push_back(known[i]);
    Real dyadic = roots[i];
    refine_dyadically(dyadic, (roots[i].upper - roots[i].lower) / Rational(mpz_class(1) << (1 + random() % 40)));
    out.reals.push_back(dyadic);
    out.known.push_back(known[i]);
    Real narrowed = roots[i];
    for (int step = 0; step < 6 && !narrowed.exact; ++step) {
      Rational t(mpz_class(1 + random() % 1023), mpz_class(1024));
      Rational m = narrowed.lower + (narrowed.upper - narrowed.lower) * t;
      m.canonicalize();
      const int s = sign_at(narrowed.polynomial, m);
      if (s == 0) narrowed = Real::from_rational(m);
      else if (s == sign_at(narrowed.polynomial, narrowed.lower)) narrowed.lower = m;
      else narrowed.upper = m;
    }
    out.reals.push_back(narrowed);
    out.known.push_back(known[i]);
    // widened down into the previous root's isolating interval, still isolating: its lower end
    // above the previous root (a refined upper end of it), so that the two intervals of one
    // polynomial overlap around no root of either (the one-polynomial order without a sign change)
    if (i >= 1 && !roots[i - 1].exact) {
      Real previous = roots[i - 1];
      for (int step = 0; step < 12 && !previous.exact && previous.upper == roots[i - 1].upper; ++step) previous.refine();
      if (!previous.exact && previous.upper < roots[i - 1].upper) {
        Real widened = roots[i];
        widened.lower = previous.upper;
        out.reals.push_back(widened);
        out.known.push_back(known[i]);
      }
    }
  }
}

Rational power_of_two(int e) {
  return e >= 0 ? Rational(mpz_class(1) << e) : Rational(mpz_class(1), mpz_class(1) << -e);
}

// floor(sqrt(q) 2^t) / 2^t with 2^t = 2^60 / 2^exponent (sqrt(q) is about 2^exponent), exactly:
// a rational within the last bit (a relative 2^-60) of sqrt(q).
Rational below_square_root(const Rational& q, int exponent) {
  const int t = 60 - exponent;
  Rational scaled = q * power_of_two(2 * t);
  mpz_class whole = scaled.get_num() / scaled.get_den(), root;
  mpz_sqrt(root.get_mpz_t(), whole.get_mpz_t());
  Rational r = Rational(root) / power_of_two(t);
  r.canonicalize();
  return r;
}

// Groups of three polynomials at one scale (2^-1000 .. 2^1000: 1e-300 .. 1e300) sharing the
// square roots +-sqrt(q) (equal numbers from different polynomials), each with other factors:
// rationals a last bit beside sqrt(q) on both sides, small rationals, a second square root.
Numbers generated_numbers(std::mt19937_64& random, int groups) {
  Numbers numbers;
  for (int g = 0; g < groups; ++g) {
    const int exponent = static_cast<int>(random() % 2001) - 1000;
    const Rational q = non_square(random, exponent);
    const Rational below = below_square_root(q, exponent);
    Rational above = below + power_of_two(exponent - 60);
    above.canonicalize();
    for (int n = 0; n < 3; ++n) {
      std::vector<Factor> factors{square_root_pair(q)};
      if (n != 1 && sgn(below) != 0) factors.push_back(linear(below));
      if (n != 0) factors.push_back(linear(Rational(-above)));
      if (n == 2) {
        factors.push_back(linear(Rational(mpz_class(1 + random() % 50), mpz_class(51 + random() % 50))));
        Rational other = non_square(random, exponent + 1 + static_cast<int>(random() % 2));
        factors.push_back(square_root_pair(other));
      }
      add_roots(factors, random, numbers);
    }
  }
  return numbers;
}

TEST(ExactRealFilters, CompareAndEqualAreTheClosedFormOrder) {
  std::mt19937_64 random(31);
  const Numbers numbers = generated_numbers(random, 6);
  ASSERT_GT(numbers.reals.size(), 150u);
  std::size_t equal_pairs = 0, same_polynomial_distinct = 0, other_polynomial_equal = 0, overlapping_distinct = 0;
  const std::size_t n = numbers.reals.size();
  for (std::size_t i = 0; i < n; ++i) {
    // the numbers of the same group (neighbours in the list: close values, shared roots) and a
    // few from anywhere
    std::vector<std::size_t> partners;
    for (std::size_t j = i < 12 ? 0 : i - 12; j < std::min(n, i + 12); ++j) partners.push_back(j);
    for (int k = 0; k < 3; ++k) partners.push_back(static_cast<std::size_t>(random() % n));
    for (std::size_t j : partners) {
      const Real &a = numbers.reals[i], &b = numbers.reals[j];
      const int want = order(numbers.known[i], numbers.known[j]);
      ASSERT_EQ(compare(a, b), want) << a.description() << " against " << b.description();
      ASSERT_EQ(equal(a, b), want == 0) << a.description() << " against " << b.description();
      const bool same = a.polynomial == b.polynomial && !a.exact && !b.exact;
      if (want == 0) ++equal_pairs;
      if (want == 0 && !same && !a.exact && !b.exact) ++other_polynomial_equal;
      if (want != 0 && same) ++same_polynomial_distinct;
      if (want != 0 && same && a.upper > b.lower && b.upper > a.lower) ++overlapping_distinct;
    }
  }
  std::cout << n << " numbers: " << equal_pairs << " equal pairs (" << other_polynomial_equal
            << " of different polynomials), " << same_polynomial_distinct << " distinct of one polynomial (" << overlapping_distinct
            << " with overlapping intervals)\n";
  EXPECT_GT(equal_pairs, n);
  EXPECT_GT(other_polynomial_equal, 50u);
  EXPECT_GT(same_polynomial_distinct, 300u);
  EXPECT_GT(overlapping_distinct, 50u);
}

TEST(ExactRealFilters, FilteredComparisonWithRationalsIsTheExactOne) {
  std::mt19937_64 random(7);
  const Numbers numbers = generated_numbers(random, 5);
  std::size_t inside = 0;
  for (const Real& x : numbers.reals) {
    if (x.exact) continue;
    // rationals inside the isolating interval (most decided by the filter), its ends, outside,
    // and the roots' neighbours in the last bit
    std::vector<Rational> probes{x.lower, x.upper, Rational(x.lower - 1), Rational(x.upper + 1)};
    for (int k = 0; k < 12; ++k) {
      Rational t(mpz_class(1 + random() % 4095), mpz_class(4096));
      Rational m = x.lower + (x.upper - x.lower) * t;
      m.canonicalize();
      probes.push_back(m);
    }
    Real tight = x;
    refine_dyadically(tight, (x.upper - x.lower) / Rational(mpz_class(1) << 70));
    probes.push_back(tight.lower);
    probes.push_back(tight.upper);
    for (const Rational& r : probes) {
      ASSERT_EQ(compare_filtered(x, r), x.compare(r)) << x.description() << " at " << r.get_str();
      if (x.lower < r && r < x.upper) ++inside;
    }
  }
  std::cout << inside << " rationals inside isolating intervals\n";
  EXPECT_GT(inside, 1000u);
}

// Coefficients beyond 53 bits (the sign filter's outward-moved bounds) and beyond 900 bits (its
// scaled path): refine_to's filtered bisection gives the canonical bisection's intervals.
// The reference refinement: canonical halving with exact signs until the interval is at most
// `width` wide (a midpoint that is a root ends it).
Real canonical_halving(Real reference, const Rational& width) {
  const int lower_sign = sign_at(reference.polynomial, reference.lower);
  while (!reference.exact && reference.upper - reference.lower > width) {
    Rational middle = (reference.lower + reference.upper) / 2;
    const int s = sign_at(reference.polynomial, middle);
    if (s == 0) reference = Real::from_rational(middle);
    else if (s == lower_sign) reference.lower = middle;
    else reference.upper = middle;
  }
  return reference;
}

TEST(ExactRealFilters, RefinementWithLargeCoefficientsIsTheExactBisection) {
  std::mt19937_64 random(99);
  for (int n = 0; n < 200; ++n) {
    const unsigned bits = n % 2 ? 60 + static_cast<unsigned>(random() % 800) : 900 + static_cast<unsigned>(random() % 300);
    // (x^2 - q) times a big linear factor: coefficients of about `bits` bits
    const Rational q = non_square(random, static_cast<int>(random() % 20) - 10);
    mpz_class big = random_integer(random, bits);
    mpz_setbit(big.get_mpz_t(), 0);
    Polynomial p = times({-q.get_num(), mpz_class(0), q.get_den()}, {-big, big + 1});
    for (Real root : real_roots(p)) {
      if (root.exact) continue;
      const Rational width = (root.upper - root.lower) / Rational(mpz_class(1) << 70);
      const Real reference = canonical_halving(root, width);
      root.refine_to(width);
      ASSERT_EQ(root.exact, reference.exact);
      ASSERT_EQ(root.lower, reference.lower);
      ASSERT_EQ(root.upper, reference.upper);
    }
  }
}


// refine_to's and refine_dyadically's first halvings taken at once (a Newton iterate in doubles,
// its cell at level <= 52 (50) confirmed by the certified filter's signs at the cell's two ends)
// against the same functions halving one step at a time (refine_jump_enabled() off) and, for
// every fourth, refine_to against canonical halving with exact signs: roots of products of two to four factors d x - n (n / d dyadic at times: a
// midpoint, so an exact end) and d x^2 - n (irrational roots; neighbouring roots near each other
// at times), coefficients of 1 to 200 bits at scales 2^-80 .. 2^80, widths 2^-1 .. 2^-140 of the
// interval, approximate()'s width, and a second refinement from the first's ends (unreduced
// and dyadic ends, the jump's m at the interval's ends). The same exact flag, ends and
// approximate() double every time; the jump must be taken (counted) often.
TEST(ExactRealFilters, RefinementFromAFilteredNewtonCellIsTheStepByStepBisection) {
  const std::uint64_t seed = hipair::test::test_seed(62);
  std::mt19937_64 random(seed);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::size_t compared = 0, exact_ends = 0;
  const std::size_t jumps_before = refine_jumps();
  auto scaled = [&](mpz_class z, int exponent) {
    return exponent >= 0 ? mpz_class(z << exponent) : z;
  };
  for (int n = 0; n < 400; ++n) {
    Polynomial p{mpz_class(1)};
    const int factors = 2 + static_cast<int>(random() % 3);
    const int exponent = static_cast<int>(random() % 161) - 80;
    for (int f = 0; f < factors; ++f) {
      const unsigned bits = 1 + static_cast<unsigned>(random() % 200);
      mpz_class num = random_integer(random, bits);
      if (num == 0) num = 1;
      if (random() % 2) num = -num;
      if (random() % 3 == 0) {
        const Rational q = non_square(random, exponent / 2);
        p = times(p, {-q.get_num(), mpz_class(0), q.get_den()});
      } else {
        mpz_class den = random() % 3 == 0 ? mpz_class(1) << (random() % 100) : random_integer(random, bits);
        if (den == 0) den = 1;
        p = times(p, {-scaled(num, std::max(exponent, 0)), scaled(den, std::max(-exponent, 0))});
      }
    }
    const bool check_canonical = n % 4 == 0;
    for (const Real& found : real_roots(p)) {
      if (found.exact) continue;
      Real first = found, first_stepwise = found;
      for (int round = 0; round < 2 && !first.exact; ++round) {
        const int shift = round == 1 && random() % 2 ? 60 : 1 + static_cast<int>(random() % 140);
        Rational width = (first.upper - first.lower) / Rational(mpz_class(1) << shift);
        if (round == 1 && shift == 60) width = (abs(first.upper) + abs(first.lower)) / Rational(mpz_class(1) << 60);
        Real jumped = first, stepwise = first_stepwise;
        Real dyadic_jumped = first, dyadic_stepwise = first_stepwise;
        refine_jump_enabled().store(false);
        stepwise.refine_to(width);
        refine_dyadically(dyadic_stepwise, width);
        const double stepwise_double = first_stepwise.approximate();
        refine_jump_enabled().store(true);
        jumped.refine_to(width);
        refine_dyadically(dyadic_jumped, width);
        const double jumped_double = first.approximate();
        ASSERT_EQ(jumped.exact, stepwise.exact) << n;
        ASSERT_EQ(jumped.lower, stepwise.lower) << n;
        ASSERT_EQ(jumped.upper, stepwise.upper) << n;
        ASSERT_TRUE(same_bits(jumped_double, stepwise_double)) << n;
        ASSERT_EQ(dyadic_jumped.exact, dyadic_stepwise.exact) << n;
        ASSERT_EQ(dyadic_jumped.lower, dyadic_stepwise.lower) << n;
        ASSERT_EQ(dyadic_jumped.upper, dyadic_stepwise.upper) << n;
        if (check_canonical) {
          const Real reference = canonical_halving(first, width);
          ASSERT_EQ(jumped.exact, reference.exact) << n;
          ASSERT_EQ(jumped.lower, reference.lower) << n;
          ASSERT_EQ(jumped.upper, reference.upper) << n;
        }
        ++compared;
        if (jumped.exact) ++exact_ends;
        first = jumped;
        first_stepwise = stepwise;
      }
    }
  }
  // dyadic roots r0 = num / 2^k of (2^k x - num)(x^2 - q) in intervals (r0 - a s, r0 + (2^e - a) s),
  // s = 2^-(e + 20 .. e + 119): r0 is a point of the halvings' grid at level e (1 .. 40), where both
  // functions must end exactly at r0 (no jump may step over it)
  for (int n = 0; n < 400; ++n) {
    const unsigned k = static_cast<unsigned>(random() % 80);
    mpz_class num = random_integer(random, 1 + static_cast<unsigned>(random() % 100));
    if (random() % 2) num = -num;
    Rational r0(num, mpz_class(1) << k);
    r0.canonicalize();
    const Rational q = non_square(random, static_cast<int>(random() % 20) - 10);
    Real root;
    root.polynomial = times({-num, mpz_class(1) << k}, {-q.get_num(), mpz_class(0), q.get_den()});
    const unsigned e = 1 + static_cast<unsigned>(random() % 40);
    const mpz_class cells = mpz_class(1) << e;
    mpz_class a = 1 + mpz_class(static_cast<unsigned long>(random())) % (cells - 1);
    const Rational step(mpz_class(1), mpz_class(1) << (e + 20 + random() % 100));
    root.lower = r0 - Rational(a) * step;
    root.upper = r0 + Rational(cells - a) * step;
    root.lower.canonicalize();
    root.upper.canonicalize();
    // (an interval that also holds a root of x^2 - q isolates nothing: not a case)
    if (SturmSequence(root.polynomial).count(root.lower, root.upper) != 1) continue;
    ASSERT_NE(sign_at(root.polynomial, root.lower), sign_at(root.polynomial, root.upper)) << n;
    const Rational width = (root.upper - root.lower) / Rational(mpz_class(1) << (e + random() % 60));
    Real jumped = root, stepwise = root, dyadic_jumped = root, dyadic_stepwise = root;
    refine_jump_enabled().store(false);
    stepwise.refine_to(width);
    refine_dyadically(dyadic_stepwise, width);
    refine_jump_enabled().store(true);
    jumped.refine_to(width);
    refine_dyadically(dyadic_jumped, width);
    ASSERT_TRUE(jumped.exact) << n;
    ASSERT_EQ(jumped.lower, r0) << n;
    ASSERT_EQ(jumped.exact, stepwise.exact) << n;
    ASSERT_EQ(jumped.lower, stepwise.lower) << n;
    ASSERT_EQ(jumped.upper, stepwise.upper) << n;
    ASSERT_EQ(dyadic_jumped.exact, dyadic_stepwise.exact) << n;
    ASSERT_EQ(dyadic_jumped.lower, dyadic_stepwise.lower) << n;
    ASSERT_EQ(dyadic_jumped.upper, dyadic_stepwise.upper) << n;
    ++compared;
    ++exact_ends;
  }
  const std::size_t jumps = refine_jumps() - jumps_before;
  std::cout << compared << " refinements, " << exact_ends << " exact, " << jumps << " jumps\n";
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(jumps, compared / 4);
  EXPECT_GE(exact_ends, 350u);
}

// refine_dyadically's definition with exact rationals only: inward dyadic ends a / 2^k, b / 2^k
// with 2^-k <= (upper - lower) / 4, then halving [a, b] with exact signs until it is at most
// `width` wide (a midpoint that is a root ends it; refine_to when the root is outside [a, b]).
Real reference_dyadic(Real r, const Rational& width) {
  if (r.exact || r.upper - r.lower <= width) return r;
  const int lower_sign = sign_at(r.polynomial, r.lower);
  const Rational gap = (r.upper - r.lower) / 4;
  unsigned long k = 0;
  while (Rational(mpz_class(1), mpz_class(1) << k) > gap) ++k;
  mpz_class scale = mpz_class(1) << k, a, b;
  mpz_class scaled_lower = r.lower.get_num() * scale, scaled_upper = r.upper.get_num() * scale;
  mpz_cdiv_q(a.get_mpz_t(), scaled_lower.get_mpz_t(), r.lower.get_den_mpz_t());
  mpz_fdiv_q(b.get_mpz_t(), scaled_upper.get_mpz_t(), r.upper.get_den_mpz_t());
  auto at = [&](const mpz_class& n) {
    Rational q(n, scale);
    q.canonicalize();
    return q;
  };
  const int sign_a = sign_at(r.polynomial, at(a)), sign_b = sign_at(r.polynomial, at(b));
  if (sign_a == 0 || sign_b == 0) return Real::from_rational(at(sign_a == 0 ? a : b));
  if (sign_a != lower_sign || sign_b == lower_sign) {
    r.refine_to(width);
    return r;
  }
  while (Rational(b - a, scale) > width) {
    const mpz_class middle = a + b;
    a *= 2;
    b *= 2;
    scale *= 2;
    const int s = sign_at(r.polynomial, at(middle));
    if (s == 0) return Real::from_rational(at(middle));
    (s == lower_sign ? a : b) = middle;
  }
  r.lower = at(a);
  r.upper = at(b);
  return r;
}

// refine_dyadically (its bisection steps in machine integers while the numerators stay below
// 2^126; beyond, the last cell found at once from a Newton approximation of the root and
// checked by the exact signs at its ends, else the mpz halving) against the exact definition
// above: roots of (x^2 - q)(d x - n) with
// coefficients of 1 to 120 bits (q at scales 2^-60 .. 2^60), the linear factor's root dyadic
// (a midpoint of some step: the exact end) or not, widths 2^-1 .. 2^-130 of the interval, and
// each root refined again from a dyadic result (a second call starts from other ends).
TEST(ExactRealFilters, DyadicRefinementIsTheExactDyadicBisection) {
  std::mt19937_64 random(48);
  std::size_t compared = 0, exact_ends = 0;
  for (int n = 0; n < 300; ++n) {
    const int exponent = static_cast<int>(random() % 121) - 60;
    const Rational q = non_square(random, exponent / 2);
    mpz_class num = random_integer(random, 1 + static_cast<unsigned>(random() % 120));
    if (random() % 2) num = -num;
    mpz_class den = n % 3 == 0 ? mpz_class(1) << (random() % 90) : random_integer(random, 1 + static_cast<unsigned>(random() % 120));
    if (den == 0) den = 1;
    const Polynomial p = times({-q.get_num(), mpz_class(0), q.get_den()}, {-num, den});
    for (Real root : real_roots(p)) {
      if (root.exact) continue;
      for (int round = 0; round < 2 && !root.exact; ++round) {
        const Rational width = (root.upper - root.lower) / Rational(mpz_class(1) << (1 + random() % 130));
        const Real reference = reference_dyadic(root, width);
        refine_dyadically(root, width);
        ASSERT_EQ(root.exact, reference.exact) << n;
        ASSERT_EQ(root.lower, reference.lower) << n;
        ASSERT_EQ(root.upper, reference.upper) << n;
        ++compared;
        if (root.exact) ++exact_ends;
      }
    }
  }
  std::cout << compared << " refinements, " << exact_ends << " ended at an exact dyadic root\n";
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(exact_ends, 20u);
}

// compare_rationals (the one-limb fast path of the isolating ends' comparisons) against GMP's
// mpq_cmp on generated pairs: numerators and denominators of 1 to 64 bits (the fast path) and
// beyond (the fallback), at the limb's edges (2^63, 2^64 - 1, 2^64), zero and both signs,
// equal values in other forms (unreduced fractions, which the fast path also takes), the
// rationals of generated_rationals, and every pair's swap.
TEST(ExactRealFilters, RationalOrderIsMpqCmp) {
  std::mt19937_64 random(36);
  std::vector<Rational> values = generated_rationals(random, 40);
  auto limb_edge = [&]() -> mpz_class {
    switch (random() % 6) {
      case 0: return mpz_class(1) << 63;
      case 1: return (mpz_class(1) << 64) - 1;
      case 2: return mpz_class(1) << 64;
      case 3: return (mpz_class(1) << 64) - 1 - static_cast<unsigned long>(random() % 3);
      case 4: return mpz_class(1);
      default: return mpz_class(static_cast<unsigned long>(random() >> (random() % 64)) | 1ul);
    }
  };
  for (int i = 0; i < 3000; ++i) {
    const unsigned num_bits = 1 + static_cast<unsigned>(random() % 66), den_bits = 1 + static_cast<unsigned>(random() % 66);
    mpz_class num = random() % 4 ? random_integer(random, num_bits) : limb_edge();
    mpz_class den = random() % 4 ? random_integer(random, den_bits) : limb_edge();
    if (den == 0) den = 1;
    if (random() % 2) num = -num;
    Rational r(num, den);
    if (random() % 3) r.canonicalize();   // else an unreduced form (a common factor kept)
    values.push_back(r);
    if (random() % 4 == 0) {
      // the same value in another form: numerator and denominator times a small factor
      const unsigned long f = 2 + random() % 1000;
      values.push_back(Rational(mpz_class(r.get_num() * f), mpz_class(r.get_den() * f)));
    }
  }
  values.push_back(Rational(0));
  values.push_back(Rational(mpz_class(0), mpz_class(7)));   // zero over a denominator other than 1
  auto sign = [](int c) { return (c > 0) - (c < 0); };
  std::size_t fast = 0, equal = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    // every value against a few others (neighbours in generation order share sizes) and itself
    for (std::size_t j : {i, (i + 1) % values.size(), (i + 7) % values.size(), static_cast<std::size_t>(random() % values.size())}) {
      const Rational& a = values[i];
      const Rational& b = values[j];
      ASSERT_EQ(sign(compare_rationals(a, b)), sign(mpq_cmp(a.get_mpq_t(), b.get_mpq_t()))) << a.get_str() << " against " << b.get_str();
      ASSERT_EQ(sign(compare_rationals(b, a)), -sign(mpq_cmp(a.get_mpq_t(), b.get_mpq_t())));
      if (std::abs(a.get_num_mpz_t()->_mp_size) <= 1 && std::abs(b.get_num_mpz_t()->_mp_size) <= 1 &&
          a.get_den_mpz_t()->_mp_size == 1 && b.get_den_mpz_t()->_mp_size == 1)
        ++fast;
      if (mpq_equal(a.get_mpq_t(), b.get_mpq_t()) || (i != j && mpq_cmp(a.get_mpq_t(), b.get_mpq_t()) == 0)) ++equal;
    }
  }
  EXPECT_GT(fast, 4000u);
  EXPECT_GT(equal, values.size());
}

}  // namespace
}  // namespace hipair::cspace::algebra
