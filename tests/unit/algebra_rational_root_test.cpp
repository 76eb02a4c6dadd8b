// algebra::rational_root (session 28): the exact value of a real algebraic number when it is
// rational, decided completely, on generated polynomials against their planted roots: products
// of rational linear factors (q y - p), irreducible quadratics (a y^2 + b y + c with a positive
// discriminant that is no square, or a negative one), irreducible cubics (a y^3 - c, c / a no
// cube of a rational), and quadratics whose irrational roots lie 2^-k from a planted rational;
// some factors repeated; the whole product scaled to roots of magnitude 10^-300 ... 10^400
// (y -> y / s, coefficients up to thousands of bits). Every real root of the product, isolated
// by Descartes (descartes_real_roots) and by Sturm (real_roots), is rational exactly when it is
// a planted rational, and rational_root gives that value.
#include "algebra/rational_root.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

Polynomial times(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  trim(r);
  return r;
}

struct Planted {
  Polynomial p;
  std::vector<Rational> rational_roots;   // every rational root (planted), distinct or not
};

class Generator {
 public:
  explicit Generator(unsigned seed) : random_(seed) {}

  long uniform(long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(random_); }

  mpz_class big(unsigned bits) {   // in [1, 2^bits]
    mpz_class r = 0;
    for (unsigned b = 0; b < bits; b += 32) r = (r << 32) + static_cast<unsigned long>(random_() & 0xffffffffu);
    r >>= (bits + 31) / 32 * 32 - bits;
    return r + 1;
  }
  mpz_class signed_big(unsigned bits) { return uniform(0, 1) ? big(bits) : mpz_class(-big(bits)); }

  Planted next() {
    Planted g;
    g.p = Polynomial{1};
    const int factors = static_cast<int>(uniform(1, 4));
    for (int f = 0; f < factors; ++f) {
      const unsigned bits = static_cast<unsigned>(uniform(0, 3) == 0 ? uniform(60, 200) : uniform(1, 24));
      Polynomial factor;
      switch (uniform(0, 4)) {
        case 0: {   // rational linear factor q y - p
          mpz_class q = big(bits), p = signed_big(bits);
          Rational root(p, q);
          root.canonicalize();
          factor = {-root.get_num(), root.get_den()};
          g.rational_roots.push_back(root);
          break;
        }
        case 1: {   // irreducible quadratic with real roots: b^2 - 4ac > 0 and no square
          for (;;) {
            mpz_class a = big(bits), b = signed_big(bits), c = signed_big(bits);
            mpz_class d = b * b - 4 * a * c;
            if (d > 0 && !mpz_perfect_square_p(d.get_mpz_t())) {
              factor = {c, b, a};
              break;
            }
          }
          break;
        }
        case 2: {   // no real roots
          mpz_class a = big(bits), b = signed_big(bits);
          factor = {b * b + big(bits), 2 * a * b, a * a};   // (a y + b)^2 + positive
          break;
        }
        case 3: {   // a y^3 - c with c / a no cube of a rational: a c^2 no cube
          for (;;) {
            mpz_class a = big(bits), c = signed_big(bits);
            mpz_class test = abs(a * c * c);
            if (!mpz_root(mpz_class().get_mpz_t(), test.get_mpz_t(), 3)) {
              factor = {-c, 0, 0, a};
              break;
            }
          }
          break;
        }
        default: {   // roots p/q +- sqrt(2) / (2^k q) beside a planted rational p/q:
                     // 4^k (q y - p)^2 - 2
          mpz_class q = big(bits), p = signed_big(bits);
          Rational root(p, q);
          root.canonicalize();
          mpz_class four_k = mpz_class(1) << (2 * uniform(1, 120));
          Polynomial linear{-root.get_num(), root.get_den()};
          Polynomial square = times(linear, linear);
          for (mpz_class& c : square) c *= four_k;
          square[0] -= 2;
          factor = square;
          if (uniform(0, 1)) {
            factor = times(factor, linear);
            g.rational_roots.push_back(root);
          }
          break;
        }
      }
      g.p = times(g.p, factor);
      if (uniform(0, 7) == 0) g.p = times(g.p, factor);   // a repeated factor
    }
    // scale every root by s = 10^e (e in -300 ... 400): P(y / s) s^n with integer coefficients
    const long e = uniform(0, 2) == 0 ? 0 : uniform(-300, 400);
    mpz_class ten_e;
    mpz_ui_pow_ui(ten_e.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
    const mpz_class numerator = e >= 0 ? ten_e : mpz_class(1), denominator = e >= 0 ? mpz_class(1) : ten_e;
    const int n = degree(g.p);
    for (int i = 0; i <= n; ++i) {   // c_i y^i -> c_i (D y)^i N^(n - i), roots times N / D
      mpz_class d_i, n_i;
      mpz_pow_ui(d_i.get_mpz_t(), denominator.get_mpz_t(), static_cast<unsigned long>(i));
      mpz_pow_ui(n_i.get_mpz_t(), numerator.get_mpz_t(), static_cast<unsigned long>(n - i));
      g.p[static_cast<std::size_t>(i)] *= d_i * n_i;
    }
    for (Rational& r : g.rational_roots) {
      r *= Rational(numerator, denominator);
      r.canonicalize();
    }
    return g;
  }

 private:
  std::mt19937_64 random_;
};

// The planted rational equal to r, or nullopt.
std::optional<Rational> planted_value(const Planted& g, const Real& r) {
  for (const Rational& q : g.rational_roots)
    if (r.compare(q) == 0) return q;
  return std::nullopt;
}

TEST(AlgebraRationalRoot, EveryRootOfGeneratedProductsIsRationalExactlyWhenPlanted) {
  Generator generator(2811);
  std::size_t rational = 0, irrational = 0, huge = 0;
  for (int trial = 0; trial < 160; ++trial) {
    Planted g = generator.next();
    const Rational bound = root_bound(g.p);
    if (degree(g.p) > 9) continue;   // the isolation of large degrees with clusters is slow
    for (bool sturm : {false, true}) {
      if (sturm && degree(g.p) > 5) continue;   // Sturm sequences of large degree grow slow
      const std::vector<Real> roots = sturm ? real_roots(g.p, -bound, bound) : descartes_real_roots(g.p, -bound, bound);
      for (const Real& root : roots) {
        const std::string where = "trial " + std::to_string(trial) + " " + (sturm ? "Sturm" : "Descartes") + ": " +
                                  root.description("y");
        std::optional<Rational> expected = planted_value(g, root);
        std::optional<Rational> found = rational_root(root);
        // the fallback alone, on the smaller cases (it refines to 1/a_n^2: slow for huge a_n)
        if (mpz_sizeinbase(root.polynomial.back().get_mpz_t(), 2) < 600)
          EXPECT_EQ(rational_root_by_refinement(root), expected) << where;
        ASSERT_EQ(found.has_value(), expected.has_value()) << where;
        if (expected) {
          EXPECT_EQ(*found, *expected) << where;
          ++rational;
          huge += !root.exact && degree(root.polynomial) >= 2 && mpz_sizeinbase(expected->get_den_mpz_t(), 2) > 64;
        } else {
          ++irrational;
        }
      }
    }
  }
  EXPECT_GT(rational, 100u);
  EXPECT_GT(irrational, 100u);
  EXPECT_GT(huge, 20u);   // beyond Real::detect_rational's reach (denominators below 2^31)
}

// Real::detect_rational (session 28, zc28b) is complete: the root becomes exact exactly when it
// is a planted rational, with that value; an irrational root keeps an isolating interval of it.
// Many planted rationals have denominators > 2^64, beyond the old refinement-only detection.
TEST(AlgebraRationalRoot, DetectRationalMakesExactlyThePlantedRationalsExact) {
  Generator generator(2812);
  std::size_t rational = 0, irrational = 0, huge = 0;
  for (int trial = 0; trial < 160; ++trial) {
    Planted g = generator.next();
    if (degree(g.p) > 9) continue;
    const Rational bound = root_bound(g.p);
    for (const Real& root : descartes_real_roots(g.p, -bound, bound)) {
      const std::string where = "trial " + std::to_string(trial) + ": " + root.description("y");
      const std::optional<Rational> expected = planted_value(g, root);
      Real detected = root;
      detected.detect_rational();
      ASSERT_EQ(detected.exact, expected.has_value()) << where;
      if (expected) {
        EXPECT_EQ(detected.lower, *expected) << where;
        EXPECT_EQ(detected.upper, *expected) << where;
        ++rational;
        huge += !root.exact && degree(root.polynomial) >= 2 && mpz_sizeinbase(expected->get_den_mpz_t(), 2) > 64;
      } else {
        // still an isolating interval of the same root: the polynomial changes sign over it
        EXPECT_TRUE(detected.lower < detected.upper) << where;
        EXPECT_NE(sign_at(detected.polynomial, detected.lower), 0) << where;
        EXPECT_EQ(sign_at(detected.polynomial, detected.lower), -sign_at(detected.polynomial, detected.upper)) << where;
        EXPECT_TRUE(root.lower <= detected.lower && detected.upper <= root.upper) << where;
        ++irrational;
      }
    }
  }
  EXPECT_GT(rational, 50u);
  EXPECT_GT(irrational, 50u);
  EXPECT_GT(huge, 10u);
}

TEST(AlgebraRationalRoot, ExactLinearAndTheSimplestCases) {
  EXPECT_EQ(rational_root(Real::from_rational(Rational(-7, 3))), Rational(-7, 3));
  // (3y - 1)(y^2 - 2): the root 1/3 in an interval that is no bisection point of it
  Polynomial p{2, -6, -1, 3};
  for (const Real& root : descartes_real_roots(p, Rational(-4), Rational(4))) {
    if (root.compare(Rational(1, 3)) == 0) {
      ASSERT_FALSE(root.exact);
      EXPECT_EQ(rational_root(root), Rational(1, 3));
    } else {
      EXPECT_FALSE(rational_root(root).has_value()) << root.description("y");
    }
  }
  // a root of a linear factor
  Real linear;
  linear.polynomial = {-5, 7};
  linear.lower = 0;
  linear.upper = 1;
  EXPECT_EQ(rational_root(linear), Rational(5, 7));
  // not primitive: 6 (3y - 1)(y^2 - 2), the root 1/3 with a_n = 18
  Real scaled;
  scaled.polynomial = {12, -36, -6, 18};
  scaled.lower = Rational(1, 4);
  scaled.upper = Rational(1, 2);
  EXPECT_EQ(rational_root(scaled), Rational(1, 3));
  // the interval is left as it was
  EXPECT_EQ(scaled.lower, Rational(1, 4));
  EXPECT_FALSE(scaled.exact);
}

}  // namespace
}  // namespace hipair::cspace::algebra
