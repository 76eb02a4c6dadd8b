// Descartes root isolation (algebra::descartes_real_roots, algebra::square_free_test) against
// the Sturm isolation (algebra::real_roots) and against planted roots, on generated integer
// polynomials: multiple roots, clusters 2^-200 apart, coefficients up to about 3000 bits, roots
// at dyadic bisection points and at the ends of the interval, complex and irrational roots.
#include "algebra/exact_real.hpp"
#include "algebra/square_free_memo.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <thread>

namespace hipair::cspace::algebra {
namespace {

Polynomial multiply(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  trim(r);
  return r;
}

struct Generated {
  Polynomial p;
  std::vector<Rational> rational_roots;   // distinct planted rational roots
  Rational lo, hi;
};

class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}

  long uniform(long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(rng_); }

  mpz_class big(unsigned bits) {   // uniform in [0, 2^bits)
    mpz_class r = 0;
    for (unsigned b = 0; b < bits; b += 32) r = (r << 32) + static_cast<unsigned long>(rng_() & 0xffffffffu);
    return r >> ((bits + 31) / 32 * 32 - bits);
  }

  Rational rational(unsigned denominator_bits) {
    mpz_class den = big(denominator_bits) + 1;
    mpz_class num = big(denominator_bits + 3) - (mpz_class(1) << (denominator_bits + 2));
    Rational r(num, den);
    r.canonicalize();
    return r;
  }

  Generated next() {
    Generated g;
    g.p = Polynomial{1};
    const int kind = static_cast<int>(uniform(0, 4));
    const unsigned bits = kind == 4 ? static_cast<unsigned>(uniform(150, 300)) : static_cast<unsigned>(uniform(1, 40));
    const int factors = static_cast<int>(uniform(1, kind == 4 ? 10 : 6));
    std::vector<Rational> roots;
    for (int f = 0; f < factors; ++f) {
      Rational root;
      switch (uniform(0, 3)) {
        case 0:   // dyadic: on the bisection grid of [lo, hi] when the interval is dyadic too
          root = Rational(mpz_class(uniform(-64, 64)), mpz_class(1) << uniform(0, 6));
          break;
        case 1:   // a cluster next to an earlier root
          root = roots.empty() ? rational(bits) : roots.back() + Rational(mpz_class(1), mpz_class(1) << uniform(20, 200));
          break;
        default:
          root = rational(bits);
      }
      root.canonicalize();
      const int multiplicity = uniform(0, 3) == 0 ? static_cast<int>(uniform(2, 3)) : 1;
      for (int m = 0; m < multiplicity; ++m)
        g.p = multiply(g.p, Polynomial{-root.get_num(), root.get_den()});
      if (std::find(roots.begin(), roots.end(), root) == roots.end()) roots.push_back(root);
    }
    // quadratic factors: complex pairs (x^2 + c) or irrational pairs (x^2 - c, c not a square)
    for (int f = static_cast<int>(uniform(0, 2)); f > 0; --f) {
      mpz_class c = big(bits) + 2;
      if (mpz_perfect_square_p(c.get_mpz_t())) c += 1;
      if (mpz_perfect_square_p(c.get_mpz_t())) c += 1;
      g.p = multiply(g.p, Polynomial{uniform(0, 1) ? mpz_class(c) : mpz_class(-c), 0, mpz_class(1) << uniform(0, 8)});
    }
    // a random constant factor: coefficients of about 3000 bits on the big-coefficient kind
    if (kind == 4) g.p = multiply(g.p, Polynomial{big(static_cast<unsigned>(uniform(100, 600))) + 1});
    if (uniform(0, 1)) g.p = multiply(g.p, Polynomial{-1});
    std::sort(roots.begin(), roots.end());
    // the interval: around all roots, dyadic, or with a planted root as an end
    switch (uniform(0, 3)) {
      case 0:
        g.lo = Rational(-65);
        g.hi = Rational(65);
        break;
      case 1:
        g.lo = Rational(mpz_class(uniform(-64, 0)));
        g.hi = g.lo + Rational(mpz_class(1) << uniform(0, 7));
        break;
      case 2: {
        const Rational& a = roots[static_cast<std::size_t>(uniform(0, static_cast<long>(roots.size()) - 1))];
        const Rational& b = roots[static_cast<std::size_t>(uniform(0, static_cast<long>(roots.size()) - 1))];
        g.lo = std::min(a, b);
        g.hi = std::max(a, b);
        if (g.lo == g.hi) g.hi = g.lo + Rational(1, 3);
        break;
      }
      default:
        g.lo = rational(bits);
        g.hi = g.lo + rational(8) * rational(8) + Rational(1, 1000);
    }
    for (const Rational& r : roots)
      if (g.lo <= r && r <= g.hi) g.rational_roots.push_back(r);
    return g;
  }

 private:
  std::mt19937_64 rng_;
};

// Every property of an isolation of the roots of p in [lo, hi] that does not depend on how it
// was computed, checked exactly with a Sturm sequence of the square-free part.
void expect_certified(const Polynomial& p, const Rational& lo, const Rational& hi, const std::vector<Real>& roots,
                      const std::string& where) {
  const Polynomial q = square_free_part(p);
  const SturmSequence sturm(q);
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const Real& r = roots[i];
    SCOPED_TRACE(where + " root " + std::to_string(i));
    ASSERT_TRUE(lo <= r.lower && r.upper <= hi);
    if (r.exact) {
      EXPECT_EQ(r.lower, r.upper);
      EXPECT_EQ(sign_at(q, r.lower), 0);
    } else {
      ASSERT_LT(r.lower, r.upper);
      const int sl = sign_at(r.polynomial, r.lower), su = sign_at(r.polynomial, r.upper);
      EXPECT_NE(sl, 0);
      EXPECT_EQ(sl, -su);
      EXPECT_EQ(sturm.count(r.lower, r.upper), 1);   // exactly one root in (lower, upper]
      EXPECT_EQ(degree(gcd(r.polynomial, q)), degree(q));   // the square-free part itself
    }
    if (i > 0) {   // ascending, disjoint
      const Real& s = roots[i - 1];
      EXPECT_LE(s.upper, r.lower);
      if (s.exact || r.exact) EXPECT_LT(s.upper, r.upper);
    }
  }
}

TEST(CSpaceDescartes, SameRootsAsSturmOnGeneratedPolynomials) {
  Generator generator(20261128);
  int compared = 0, roots_seen = 0, end_roots = 0, exact_midpoints = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Generated g = generator.next();
    const std::string where = "trial " + std::to_string(trial);
    SCOPED_TRACE(where);
    const auto sturm = real_roots(g.p, g.lo, g.hi);
    const auto descartes = descartes_real_roots(g.p, g.lo, g.hi);
    ASSERT_EQ(descartes.size(), sturm.size());
    expect_certified(g.p, g.lo, g.hi, descartes, where);
    for (std::size_t i = 0; i < sturm.size(); ++i) {
      EXPECT_EQ(compare(descartes[i], sturm[i]), 0);
      // both enclose the same root: the intervals meet
      EXPECT_TRUE(sturm[i].lower <= descartes[i].upper && descartes[i].lower <= sturm[i].upper);
      if (descartes[i].exact) {   // (Sturm may stop before reaching a grid point that is the root)
        if (descartes[i].lower == g.lo || descartes[i].lower == g.hi) ++end_roots;
        else ++exact_midpoints;
      }
    }
    // every planted rational root is found, and exactly
    for (const Rational& r : g.rational_roots) {
      int equal = 0;
      for (const Real& x : descartes) equal += x.compare(r) == 0 ? 1 : 0;
      EXPECT_EQ(equal, 1);
    }
    // refinement keeps the number: a narrow Descartes interval inside the first, same root
    for (std::size_t i = 0; i < descartes.size(); ++i) {
      Real narrow = descartes[i];
      narrow.refine_to((descartes[i].upper - descartes[i].lower) / Rational(mpz_class(1) << 80));
      EXPECT_TRUE(descartes[i].lower <= narrow.lower && narrow.upper <= descartes[i].upper);
      EXPECT_EQ(compare(narrow, sturm[i]), 0);
      if (i + 1 < descartes.size()) EXPECT_EQ(compare(narrow, descartes[i + 1]), -1);
    }
    roots_seen += static_cast<int>(descartes.size());
    ++compared;
  }
  EXPECT_EQ(compared, 400);
  // the generator does reach the cases it is for
  EXPECT_GT(roots_seen, 800);
  EXPECT_GT(end_roots, 20);
  EXPECT_GT(exact_midpoints, 20);
}

TEST(CSpaceDescartes, SquareFreeTestMatchesTheExactSquareFreePart) {
  Generator generator(7);
  int modular = 0, exact = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    Generated g = generator.next();
    bool exact_needed = false;
    const Polynomial fast = square_free_test(g.p, &exact_needed);
    EXPECT_EQ(fast, square_free_part(g.p));
    const bool square_free = degree(gcd(g.p, derivative(g.p))) == 0;
    if (exact_needed) {
      ++exact;
    } else {
      EXPECT_TRUE(square_free || degree(g.p) <= 1);   // a modular certificate is never wrong
      ++modular;
    }
    if (!square_free) EXPECT_TRUE(exact_needed);
  }
  EXPECT_GT(modular, 50);
  EXPECT_GT(exact, 50);
}

TEST(CSpaceDescartes, RememberedSquareFreePartsAreTheExactOnes) {
  // square_free_test remembers the exact square-free parts it computed (per thread, emptied
  // at 4,096 polynomials): asked again, in three passes over 2,500 generated polynomials (so
  // the memo is emptied on the way) and with the same polynomial times -1 and times 3 (other
  // keys, the same primitive part), it gives square_free_part's answer every time
  Generator generator(21);
  std::vector<Polynomial> polynomials;
  for (int trial = 0; trial < 2500; ++trial) polynomials.push_back(generator.next().p);
  std::vector<Polynomial> expected;
  for (const Polynomial& p : polynomials) expected.push_back(square_free_part(p));
  int exact = 0;
  for (int pass = 0; pass < 3; ++pass)
    for (std::size_t i = 0; i < polynomials.size(); ++i) {
      SCOPED_TRACE("pass " + std::to_string(pass) + " polynomial " + std::to_string(i));
      bool exact_needed = false;
      Polynomial p = polynomials[i];
      if (pass > 0)
        for (auto& c : p) c *= pass == 1 ? -1 : 3;
      EXPECT_EQ(square_free_test(p, &exact_needed), expected[i]);
      if (exact_needed) ++exact;
    }
  EXPECT_GT(exact, 3 * 400);
}

TEST(CSpaceDescartes, RememberedSquareFreeTestsGiveTheSameIsolations) {
  // descartes_real_roots remembers square_free_test's answer per input polynomial (per thread,
  // emptied at 4,096 polynomials): 1,500 generated polynomials isolated in this thread in three
  // passes (the memo is emptied on the way), as given, negated and tripled (other keys, the
  // same square-free part), twice each (the second a hit), give root for root the isolation of
  // a fresh thread whose memo is empty: the same defining polynomial (square_free_test's), the
  // same interval, the same exactness.
  Generator generator(2024);
  std::vector<Generated> cases;
  for (int trial = 0; trial < 1500; ++trial) cases.push_back(generator.next());
  std::vector<std::vector<Real>> expected(cases.size());
  std::thread([&] {
    for (std::size_t i = 0; i < cases.size(); ++i) expected[i] = descartes_real_roots(cases[i].p, cases[i].lo, cases[i].hi);
  }).join();
  std::size_t roots = 0;
  for (int pass = 0; pass < 3; ++pass)
    for (std::size_t i = 0; i < cases.size(); ++i) {
      Polynomial p = cases[i].p;
      if (pass > 0)
        for (auto& c : p) c *= pass == 1 ? -1 : 3;
      const Polynomial square_free = square_free_test(p);
      for (int again = 0; again < 2; ++again) {
        SCOPED_TRACE("pass " + std::to_string(pass) + " polynomial " + std::to_string(i) + " call " + std::to_string(again));
        const std::vector<Real> found = descartes_real_roots(p, cases[i].lo, cases[i].hi);
        ASSERT_EQ(found.size(), expected[i].size());
        for (std::size_t k = 0; k < found.size(); ++k) {
          EXPECT_EQ(found[k].lower, expected[i][k].lower);
          EXPECT_EQ(found[k].upper, expected[i][k].upper);
          EXPECT_EQ(found[k].exact, expected[i][k].exact);
          if (!found[k].exact) {
            EXPECT_EQ(found[k].polynomial, expected[i][k].polynomial);
            EXPECT_EQ(found[k].polynomial, square_free);
          }
        }
        roots += found.size();
      }
    }
  EXPECT_GT(roots, 6u * 1500u);
}

TEST(CSpaceDescartes, RememberedSquareFreeTestIsTheSquareFreeTest) {
  // remembered_square_free_test (the kernel slicer's and descartes_real_roots' memo, per thread,
  // emptied at 4,096 polynomials) against square_free_part (the exact gcd: an independent
  // oracle) and square_free_test computed afresh in a new thread: 800 generated polynomials
  // in three passes (4,800 keys: the memo emptied on the way), as given, times -1, times 3 * 2^200 (a
  // content to divide out), and each with its constant coefficient moved by one (a key differing
  // in one coefficient, another answer), every call asked twice (the second a hit).
  Generator generator(3607);
  std::vector<Polynomial> polynomials;
  for (int trial = 0; trial < 800; ++trial) polynomials.push_back(generator.next().p);
  std::vector<Polynomial> moved = polynomials;
  for (Polynomial& p : moved) {
    if (p.empty()) p.push_back(0);
    p[0] += 1;
    trim(p);
  }
  std::vector<Polynomial> expected, expected_moved, fresh;
  for (std::size_t i = 0; i < polynomials.size(); ++i) {
    expected.push_back(square_free_part(polynomials[i]));
    expected_moved.push_back(square_free_part(moved[i]));
  }
  std::thread([&] {
    for (const Polynomial& p : polynomials) fresh.push_back(square_free_test(p));
  }).join();
  const mpz_class scale = mpz_class(3) << 200;
  int hits_checked = 0;
  for (int pass = 0; pass < 3; ++pass)
    for (std::size_t i = 0; i < polynomials.size(); ++i) {
      SCOPED_TRACE("pass " + std::to_string(pass) + " polynomial " + std::to_string(i));
      Polynomial p = polynomials[i];
      if (pass > 0)
        for (auto& c : p) c *= pass == 1 ? mpz_class(-1) : scale;
      Polynomial q = moved[i];
      if (pass > 0)
        for (auto& c : q) c *= pass == 1 ? mpz_class(-1) : scale;
      for (int again = 0; again < 2; ++again) {
        const Polynomial found = remembered_square_free_test(p);
        EXPECT_EQ(found, expected[i]);
        EXPECT_EQ(found, fresh[i]);
        EXPECT_EQ(remembered_square_free_test(q), expected_moved[i]);
        hits_checked += again;
      }
    }
  EXPECT_EQ(hits_checked, 3 * 800);
}

// The continued-fraction descent on rationals (simplest_between before it ran on integers):
// the oracle for the integer version.
Rational simplest_between_on_rationals(const Rational& lo, const Rational& hi) {
  mpz_class floor_lo;
  mpz_fdiv_q(floor_lo.get_mpz_t(), lo.get_num_mpz_t(), lo.get_den_mpz_t());
  Rational candidate(floor_lo + 1);
  if (candidate < hi) {
    if (lo < 0 && hi > 0) return Rational(0);
    if (hi <= 0) {
      mpz_class ceil_hi;
      mpz_cdiv_q(ceil_hi.get_mpz_t(), hi.get_num_mpz_t(), hi.get_den_mpz_t());
      Rational c(ceil_hi - 1);
      if (c > lo) return c;
    }
    return candidate;
  }
  Rational fl(floor_lo);
  Rational low_gap = lo - fl, high_gap = hi - fl;
  Rational z;
  Rational z_low = 1 / high_gap;
  if (sgn(low_gap) == 0) {
    mpz_class f;
    mpz_fdiv_q(f.get_mpz_t(), z_low.get_num_mpz_t(), z_low.get_den_mpz_t());
    z = Rational(f + 1);
  } else {
    z = simplest_between_on_rationals(z_low, 1 / low_gap);
  }
  Rational result = fl + 1 / z;
  result.canonicalize();
  return result;
}

TEST(CSpaceDescartes, SimplestBetweenOnIntegersIsTheRationalDescent) {
  // 20,000 generated open intervals: integer ends, ends sharing a floor, negative, straddling
  // zero, widths 2^-200 ... 2^10, ends of 1 ... 300 bits; the answer is canonical and the
  // descent's, strictly inside, and no rational of smaller denominator lies inside (checked
  // on the small ones)
  Generator generator(5);
  for (int trial = 0; trial < 20000; ++trial) {
    Rational lo;
    switch (generator.uniform(0, 3)) {
      case 0: lo = Rational(mpz_class(generator.uniform(-20, 20))); break;
      case 1: lo = Rational(mpz_class(generator.uniform(-1000, 1000)), mpz_class(1) << generator.uniform(0, 64)); break;
      default: lo = generator.rational(static_cast<unsigned>(generator.uniform(1, 300)));
    }
    lo.canonicalize();
    Rational width = generator.uniform(0, 4) == 0 ? Rational(mpz_class(generator.uniform(1, 5)))
                                                  : Rational(mpz_class(generator.uniform(1, 1000)), mpz_class(1) << generator.uniform(0, 200));
    width.canonicalize();
    const Rational hi = lo + width;
    SCOPED_TRACE("(" + lo.get_str() + ", " + hi.get_str() + ")");
    const Rational s = simplest_between(lo, hi);
    const Rational expected = simplest_between_on_rationals(lo, hi);
    EXPECT_EQ(s, expected);
    EXPECT_EQ(s.get_num(), expected.get_num());
    EXPECT_EQ(s.get_den(), expected.get_den());
    Rational canonical = s;
    canonical.canonicalize();
    EXPECT_EQ(canonical.get_den(), s.get_den());
    EXPECT_TRUE(lo < s && s < hi);
    if (s.get_den() < 200)
      for (long q = 1; q < s.get_den(); ++q) {
        mpz_class p;
        mpz_class scaled = lo.get_num() * q;
        mpz_fdiv_q(p.get_mpz_t(), scaled.get_mpz_t(), lo.get_den_mpz_t());
        Rational above(p + 1, q);   // the first p / q above lo
        above.canonicalize();
        EXPECT_FALSE(above < hi) << "denominator " << q;
      }
  }
}

TEST(CSpaceDescartes, RootsAtTheEndsAndAtBisectionPoints) {
  // x (x - 1/2)(x - 1/4)(x - 1)(x^2 - 2) on [0, 1]: ends and midpoints are roots
  Polynomial p = multiply(multiply(multiply(Polynomial{0, 1}, Polynomial{-1, 2}), Polynomial{-1, 4}),
                          multiply(Polynomial{-1, 1}, Polynomial{-2, 0, 1}));
  auto roots = descartes_real_roots(p, Rational(0), Rational(1));
  ASSERT_EQ(roots.size(), 4u);
  EXPECT_TRUE(roots[0].exact && roots[0].lower == 0);
  EXPECT_TRUE(roots[1].exact && roots[1].lower == Rational(1, 4));
  EXPECT_TRUE(roots[2].exact && roots[2].lower == Rational(1, 2));
  EXPECT_TRUE(roots[3].exact && roots[3].lower == 1);
  // on [-2, 2] the irrational roots +-sqrt(2) are isolated too, and a double root at 1 counts once
  auto wide = descartes_real_roots(multiply(p, Polynomial{-1, 1}), Rational(-2), Rational(2));
  ASSERT_EQ(wide.size(), 6u);
  EXPECT_FALSE(wide[0].exact);
  EXPECT_EQ(wide[0].compare(Rational(-141422, 100000)), 1);
  EXPECT_EQ(wide[0].compare(Rational(-141421, 100000)), -1);
  EXPECT_TRUE(wide[4].exact && wide[4].lower == 1);
  EXPECT_FALSE(wide[5].exact);
  // empty and degenerate intervals, constants, no root inside
  EXPECT_TRUE(descartes_real_roots(p, Rational(2), Rational(3)).empty());
  EXPECT_TRUE(descartes_real_roots(Polynomial{5}, Rational(-1), Rational(1)).empty());
  EXPECT_EQ(descartes_real_roots(p, Rational(1, 2), Rational(1, 2)).size(), 1u);
  EXPECT_TRUE(descartes_real_roots(p, Rational(1), Rational(0)).empty());
}

TEST(CSpaceDescartes, ClusteredRootsWithHugeCoefficients) {
  // eight roots within 2^-1000 of each other around a 300-bit rational, a 2000-bit constant
  Generator generator(3);
  Rational centre = generator.rational(300);
  Polynomial p{generator.big(2000) + 1};
  std::vector<Rational> planted;
  for (int k = 0; k < 8; ++k) {
    Rational r = centre + Rational(mpz_class(k), mpz_class(1) << 1000);
    planted.push_back(r);
    p = multiply(p, Polynomial{-r.get_num(), r.get_den()});
  }
  p = multiply(p, Polynomial{1, 0, 1});   // and a complex pair
  std::size_t bits = 0;
  for (const auto& c : p) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  EXPECT_GT(bits, 3000u);
  const Rational lo = centre - 1, hi = centre + 1;
  auto roots = descartes_real_roots(p, lo, hi);
  ASSERT_EQ(roots.size(), 8u);
  expect_certified(p, lo, hi, roots, "cluster");
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(roots[i].compare(planted[i]), 0);
  auto sturm = real_roots(p, lo, hi);
  ASSERT_EQ(sturm.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(compare(roots[i], sturm[i]), 0);
}

// refine_dyadically as documented, every sign exact (no double filter): the oracle for the
// filtered one, which must take the same steps and end at the same interval.
Real exact_dyadic_refinement(Real r, const Rational& width) {
  if (r.exact || r.upper - r.lower <= width) return r;
  const int lower_sign = sign_at(r.polynomial, r.lower);
  const Rational gap = (r.upper - r.lower) / 4;
  unsigned long k = 0;
  while (Rational(1, mpz_class(1) << k) > gap) ++k;
  mpz_class scale = mpz_class(1) << k, a, b;
  mpz_class scaled_lower = r.lower.get_num() * scale, scaled_upper = r.upper.get_num() * scale;
  mpz_cdiv_q(a.get_mpz_t(), scaled_lower.get_mpz_t(), r.lower.get_den_mpz_t());
  mpz_fdiv_q(b.get_mpz_t(), scaled_upper.get_mpz_t(), r.upper.get_den_mpz_t());
  auto at = [](const mpz_class& n, const mpz_class& d) {
    Rational q(n, d);
    q.canonicalize();
    return q;
  };
  auto settle = [&](const Rational& root) {
    r.lower = r.upper = root;
    r.exact = true;
    return r;
  };
  const int sa = sign_at(r.polynomial, at(a, scale)), sb = sign_at(r.polynomial, at(b, scale));
  if (sa == 0) return settle(at(a, scale));
  if (sb == 0) return settle(at(b, scale));
  if (sa != lower_sign || sb == lower_sign) {
    r.refine_to(width);
    return r;
  }
  while (Rational(b - a, scale) > width) {
    mpz_class middle = a + b;
    a <<= 1;
    b <<= 1;
    scale <<= 1;
    const int s = sign_at(r.polynomial, at(middle, scale));
    if (s == 0) return settle(at(middle, scale));
    (s == lower_sign ? a : b) = middle;
  }
  r.lower = at(a, scale);
  r.upper = at(b, scale);
  return r;
}

// refine_dyadically(r, width) ends where the exact refinement does; the filtered result
Real expect_exact_dyadic_steps(const Real& r, const Rational& width) {
  Real filtered = r;
  refine_dyadically(filtered, width);
  const Real expected = exact_dyadic_refinement(r, width);
  EXPECT_EQ(filtered.exact, expected.exact);
  EXPECT_EQ(filtered.lower, expected.lower);
  EXPECT_EQ(filtered.upper, expected.upper);
  return filtered;
}

TEST(CSpaceDescartes, FilteredDyadicRefinementTakesTheExactSteps) {
  // generated polynomials (small and 3000-bit coefficients, clustered roots), every isolated
  // root refined to widths 2^-4 ... 2^-140; plus dyadic roots hit exactly by a bisection
  // midpoint, behind non-dyadic isolating intervals
  Generator generator(14);
  int refined = 0, exact_hits = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Generated g = generator.next();
    std::vector<Real> roots = descartes_real_roots(g.p, g.lo, g.hi);
    for (const Real& root : roots) {
      if (root.exact) continue;
      const Rational width(1, mpz_class(1) << generator.uniform(4, 140));
      SCOPED_TRACE("trial " + std::to_string(trial) + " " + root.description());
      expect_exact_dyadic_steps(root, width);
      ++refined;
    }
  }
  for (int trial = 0; trial < 200; ++trial) {
    Rational root(mpz_class(generator.uniform(-4096, 4096)), mpz_class(1) << generator.uniform(0, 40));
    root.canonicalize();
    Polynomial p = multiply(Polynomial{-root.get_num(), root.get_den()}, Polynomial{-2, 0, 1});   // and +-sqrt 2
    p = multiply(p, Polynomial{generator.big(static_cast<unsigned>(generator.uniform(1, 400))) + 1});
    Real r;
    r.polynomial = square_free_part(p);
    r.lower = root - Rational(1, 3 + generator.uniform(0, 1000)) / Rational(mpz_class(1) << 40);
    r.upper = root + Rational(1, 5 + generator.uniform(0, 1000)) / Rational(mpz_class(1) << 40);
    const Rational width(1, mpz_class(1) << generator.uniform(44, 100));
    SCOPED_TRACE("dyadic root " + root.get_str());
    const Real filtered = expect_exact_dyadic_steps(r, width);
    if (filtered.exact) {
      EXPECT_EQ(filtered.lower, root);
      ++exact_hits;
    }
  }
  EXPECT_GT(refined, 300);
  EXPECT_GT(exact_hits, 50);   // 86 of 200 with this seed (a bisection of [a, b] meets the root when it is a midpoint)
}

// refine_dyadically's first grid 2^-k (the least k >= 0 with 2^-k <= (upper - lower) / 4, now
// read off bit sizes) on the boundary cases the generated roots above rarely meet: quarter
// widths exactly a power of two 2^-j (j from -5 to 80: k = j, or 0 for wide intervals), a
// part of a unit more or less, and wide intervals (k = 0), with the roots of x^2 - c near
// 1000 placed anywhere inside; every result the exact refinement's.
TEST(CSpaceDescartes, DyadicRefinementFirstGridOnPowerOfTwoWidths) {
  Generator generator(36);
  int checked = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const long j = generator.uniform(-5, 80);
    Rational quarter = j >= 0 ? Rational(mpz_class(1), mpz_class(1) << j) : Rational(mpz_class(1) << -j);
    switch (trial % 3) {
      case 1: quarter += quarter / Rational(mpz_class(1) << generator.uniform(1, 70)); break;
      case 2: quarter -= quarter / Rational(mpz_class(1) << generator.uniform(1, 70)); break;
      default: break;
    }
    const long c = 1000000 + generator.uniform(1, 4000);   // sqrt(c) in (1000, 1002), no square
    if (static_cast<long>(std::sqrt(static_cast<double>(c))) * static_cast<long>(std::sqrt(static_cast<double>(c))) == c) continue;
    Real r;
    r.polynomial = Polynomial{-c, 0, 1};
    // sqrt(c) to 2^-200 (below every width here): then the interval placed around it
    Real root;
    root.polynomial = r.polynomial;
    root.lower = 1000;
    root.upper = 1003;
    root.refine_to(Rational(mpz_class(1), mpz_class(1) << 200));
    const Rational width = 4 * quarter;
    const Rational t(mpz_class(1 + generator.uniform(0, 998)), mpz_class(1000));
    r.lower = root.lower - width * t;
    r.upper = r.lower + width;
    if (!(r.lower < root.lower && r.upper > root.upper) || r.lower <= -1000) continue;
    const Rational target = width / Rational(mpz_class(1) << generator.uniform(1, 60));
    SCOPED_TRACE("j " + std::to_string(j) + " " + r.description());
    expect_exact_dyadic_steps(r, target);
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

// equal(a, b), the equality test that skips compare()'s 2^-20 refinement, is compare(a, b) == 0
// on generated numbers: the roots of p against the roots of p times more factors (the same
// numbers with other polynomials and other isolating intervals; irrational ones from p's
// quadratic factors), of p times a factor with a root 2^-100 from a planted root or
// x^2 - (c + 1) beside x^2 - c (distinct numbers whose enclosures overlap), and copies of p's
// roots refined to random widths (the same polynomial, nested intervals).
TEST(CSpaceDescartes, EqualityIsCompareZero) {
  Generator generator(23);
  int pairs = 0, equal_other_polynomial = 0, overlapping_distinct = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Generated g = generator.next();
    Polynomial q = g.p;
    switch (generator.uniform(0, 2)) {
      case 0: {   // an irrational pair beside every quadratic factor's: x^2 - (c + 1) for x^2 - c
        mpz_class c = generator.big(static_cast<unsigned>(generator.uniform(2, 40))) + 2;
        q = multiply(q, Polynomial{mpz_class(-c), 0, 1});
        q = multiply(q, Polynomial{mpz_class(-c - 1), 0, 1});
        break;
      }
      case 1:   // a root 2^-100 beside a planted one
        if (!g.rational_roots.empty()) {
          Rational near = g.rational_roots[static_cast<std::size_t>(
                              generator.uniform(0, static_cast<long>(g.rational_roots.size()) - 1))] +
                          Rational(mpz_class(1), mpz_class(1) << 100);
          near.canonicalize();
          q = multiply(q, Polynomial{-near.get_num(), near.get_den()});
        }
        break;
      default:   // another constant and a far factor: the same roots, other coefficients
        q = multiply(q, Polynomial{mpz_class(3), mpz_class(7)});
        q = multiply(q, Polynomial{mpz_class(-5), 0, 1});
    }
    std::vector<Real> a = descartes_real_roots(g.p, g.lo, g.hi);
    const std::vector<Real> b = descartes_real_roots(q, g.lo, g.hi);
    const std::size_t plain = a.size();
    for (std::size_t i = 0; i < plain; ++i) {
      if (a[i].exact) continue;
      Real refined = a[i];
      refined.refine_to(Rational(1, mpz_class(1) << generator.uniform(1, 80)));
      a.push_back(refined);
    }
    for (const Real& x : a)
      for (const Real& y : b) {
        const bool expected = compare(x, y) == 0;
        SCOPED_TRACE("trial " + std::to_string(trial) + ": " + x.description() + " and " + y.description());
        EXPECT_EQ(equal(x, y), expected);
        EXPECT_EQ(equal(y, x), expected);
        ++pairs;
        const bool overlapping = !x.exact && !y.exact && x.lower < y.upper && y.lower < x.upper;
        if (expected && overlapping && x.polynomial != y.polynomial) ++equal_other_polynomial;
        if (!expected && overlapping) ++overlapping_distinct;
      }
  }
  std::cout << pairs << " pairs, " << equal_other_polynomial << " equal with other polynomials, "
            << overlapping_distinct << " distinct with overlapping intervals\n";
  EXPECT_GT(equal_other_polynomial, 50);
  EXPECT_GT(overlapping_distinct, 10);
}

// sign_at(p, x) is the sign of an integer Horner value (shifts for power-of-two denominators,
// per-thread scratch integers); here against the sign of p(x) evaluated in rationals.
TEST(CSpaceDescartes, IntegerHornerSignsAreTheSignsOfTheRationalValues) {
  Generator generator(17);
  int zeros = 0, dyadic = 0, checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // a point: a dyadic n / 2^k (k up to 300), a general rational, or an integer
    Rational x;
    switch (generator.uniform(0, 2)) {
      case 0: {
        mpz_class n = generator.big(static_cast<unsigned>(generator.uniform(1, 320)));
        if (generator.uniform(0, 1)) n = -n;
        x = Rational(n, mpz_class(1) << generator.uniform(0, 300));
        break;
      }
      case 1:
        x = generator.rational(static_cast<unsigned>(generator.uniform(1, 200)));
        break;
      default:
        x = Rational(mpz_class(generator.uniform(-1000, 1000)));
    }
    x.canonicalize();
    // a polynomial: degree 0..10, 0-600-bit coefficients, some zero; a third vanish at x
    Polynomial p;
    const long degree_wanted = generator.uniform(0, 10);
    for (long i = 0; i <= degree_wanted; ++i) {
      mpz_class c = generator.uniform(0, 3) == 0 ? mpz_class(0) : generator.big(static_cast<unsigned>(generator.uniform(1, 600)));
      if (generator.uniform(0, 1)) c = -c;
      p.push_back(c);
    }
    trim(p);
    if (generator.uniform(0, 2) == 0) p = multiply(p, Polynomial{-x.get_num(), x.get_den()});
    const int expected = sgn(value_at(p, x));
    SCOPED_TRACE("trial " + std::to_string(trial) + " x = " + x.get_str());
    EXPECT_EQ(sign_at(p, x), expected);
    // an unreduced fraction of the same value (a common odd or even factor): the same sign
    const mpz_class factor = generator.uniform(0, 1) ? mpz_class(mpz_class(1) << generator.uniform(1, 80))
                                                   : mpz_class(generator.big(static_cast<unsigned>(generator.uniform(1, 90))) * 2 + 1);
    const Rational unreduced(mpz_class(x.get_num() * factor), mpz_class(x.get_den() * factor));   // not canonicalized
    EXPECT_EQ(sign_at(p, unreduced), expected);
    zeros += expected == 0 && !p.empty();
    dyadic += mpz_popcount(x.get_den_mpz_t()) == 1;
    ++checked;
  }
  EXPECT_GT(zeros, 500);
  EXPECT_GT(dyadic, 1000);
  EXPECT_EQ(checked, 3000);
}

// lower_double / upper_double compare r with its double exactly on integers (d = m 2^e); here
// against the former comparison with the rational of the double, and the enclosure is tight:
// [lo, hi] contains r, lo == hi when r is a double, else they are adjacent doubles (or the
// ends of the double range).
TEST(CSpaceDescartes, DoubleEnclosuresOfRationalsAreTheFormerOnes) {
  Generator generator(19);
  auto former_lower = [](const Rational& r) {
    double d = r.get_d();
    if (std::isinf(d)) return d > 0 ? std::numeric_limits<double>::max() : d;
    if (Rational(d) > r) d = std::nextafter(d, -std::numeric_limits<double>::infinity());
    return d;
  };
  auto former_upper = [](const Rational& r) {
    double d = r.get_d();
    if (std::isinf(d)) return d < 0 ? std::numeric_limits<double>::lowest() : d;
    if (Rational(d) < r) d = std::nextafter(d, std::numeric_limits<double>::infinity());
    return d;
  };
  int exact = 0, inexact = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Rational r;
    switch (generator.uniform(0, 5)) {
      case 0: {   // a double exactly (normal or subnormal, any exponent)
        double d = std::ldexp(static_cast<double>(generator.uniform(1, (1L << 53) - 1)), static_cast<int>(generator.uniform(-1126, 970)));
        if (generator.uniform(0, 1)) d = -d;
        r = Rational(d);
        break;
      }
      case 1: {   // a dyadic rational with more than 53 bits
        mpz_class n = generator.big(static_cast<unsigned>(generator.uniform(54, 400))) + 1;
        if (generator.uniform(0, 1)) n = -n;
        r = Rational(n, mpz_class(1) << generator.uniform(0, 1200));
        break;
      }
      case 2:   // general rationals
        r = generator.rational(static_cast<unsigned>(generator.uniform(1, 300)));
        break;
      case 3: {   // beyond the double range, or below the smallest subnormal
        mpz_class n = generator.big(static_cast<unsigned>(generator.uniform(1, 60))) + 1;
        if (generator.uniform(0, 1)) n = -n;
        r = generator.uniform(0, 1) ? Rational(mpz_class(n << 1100)) : Rational(n, mpz_class(mpz_class(1) << 1200));
        break;
      }
      case 4: {   // unreduced fractions (not canonicalized: their values count)
        mpz_class f = generator.big(static_cast<unsigned>(generator.uniform(1, 70))) + 1;
        Rational c = generator.rational(static_cast<unsigned>(generator.uniform(1, 60)));
        r = Rational(mpz_class(c.get_num() * f), mpz_class(c.get_den() * f));
        break;
      }
      default:
        r = Rational(mpz_class(generator.uniform(-5, 5)), mpz_class(generator.uniform(1, 3)));
    }
    if (generator.uniform(0, 4) != 4) r.canonicalize();
    SCOPED_TRACE("trial " + std::to_string(trial) + " r = " + r.get_str());
    const double lo = lower_double(r), hi = upper_double(r);
    EXPECT_EQ(lo, former_lower(r));
    EXPECT_EQ(hi, former_upper(r));
    if (std::isfinite(lo) && std::isfinite(hi) && lo > std::numeric_limits<double>::lowest() &&
        hi < std::numeric_limits<double>::max()) {
      Rational value = r;   // GMP compares canonical fractions only
      value.canonicalize();
      EXPECT_LE(Rational(lo), value);
      EXPECT_GE(Rational(hi), value);
      if (lo == hi) {
        EXPECT_EQ(Rational(lo), value);
        ++exact;
      } else {
        EXPECT_EQ(std::nextafter(lo, HUGE_VAL), hi);
        ++inexact;
      }
    }
  }
  EXPECT_GT(exact, 3000);
  EXPECT_GT(inexact, 8000);
}

}  // namespace
}  // namespace hipair::cspace::algebra
