// algebra::gcd is remembered per thread (a memo keyed by both arguments, in order): generated
// pairs that share one argument and differ in the other, asked in turn and again, must each give
// the exact primitive gcd, known by construction (products of primitive linear factors d x - n
// with small roots, times contents of either sign: the gcd is the product of the common factors
// at their smaller multiplicity, leading coefficient positive).
#include "algebra/content.hpp"
#include "algebra/exact_real.hpp"
#include "algebra/modular_gcd.hpp"
#include "algebra/polynomial.hpp"
#include "random_integers.hpp"

#include <gtest/gtest.h>

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdint>
#include <map>
#include <random>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

// the linear factors d x - n (d > 0, gcd(d, n) = 1): primitive, so their products are
using GcdMemoFactor = std::pair<long, long>;   // (n, d)
constexpr std::array<GcdMemoFactor, 9> gcd_memo_factors{
    {{0, 1}, {1, 1}, {-1, 1}, {2, 1}, {-3, 1}, {1, 2}, {-2, 3}, {5, 3}, {7, 1}}};

Polynomial gcd_memo_product(const std::map<int, int>& multiplicities, long content) {
  Polynomial p{mpz_class(content)};
  for (const auto& [k, m] : multiplicities)
    for (int r = 0; r < m; ++r) {
      const auto& [n, d] = gcd_memo_factors[static_cast<std::size_t>(k)];
      Polynomial q(p.size() + 1);
      for (std::size_t i = 0; i < p.size(); ++i) {
        q[i] -= p[i] * n;
        q[i + 1] += p[i] * d;
      }
      p = std::move(q);
    }
  trim(p);
  return p;
}

std::map<int, int> gcd_memo_factor_set(std::mt19937_64& random) {
  std::map<int, int> set;
  const int count = 1 + static_cast<int>(random() % 5);
  for (int k = 0; k < count; ++k) ++set[static_cast<int>(random() % gcd_memo_factors.size())];
  return set;
}

// The primitive polynomial remainder sequence, written plainly here as a second oracle: every
// remainder divided by its content.
Polynomial primitive_sequence_gcd(const Polynomial& a, const Polynomial& b) {
  Polynomial x = primitive_part(a), y = primitive_part(b);
  if (x.empty()) return y;
  if (y.empty()) return x;
  if (degree(x) < degree(y)) std::swap(x, y);
  while (!y.empty()) {
    Polynomial r = x;   // r <- lc(y)^k x mod y, by plain pseudo-division
    const mpz_class lb = y.back();
    while (!r.empty() && degree(r) >= degree(y)) {
      const int shift = degree(r) - degree(y);
      const mpz_class lr = r.back();
      for (auto& c : r) c *= lb;
      for (int i = 0; i <= degree(y); ++i) r[static_cast<std::size_t>(i + shift)] -= lr * y[static_cast<std::size_t>(i)];
      trim(r);
    }
    x = std::move(y);
    y = primitive_part(r);
  }
  return primitive_part(x);
}

Polynomial times(const Polynomial& p, const Polynomial& q) {
  if (p.empty() || q.empty()) return {};
  Polynomial r(p.size() + q.size() - 1);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j) r[i + j] += p[i] * q[j];
  trim(r);
  return r;
}

// A random integer of about `bits` bits (either sign, never zero when `nonzero`).
mpz_class random_integer(std::mt19937_64& random, int bits, bool nonzero) {
  mpz_class v = test_random::below_power_of_two(random, bits);
  if (nonzero && v == 0) v = 1;
  return test_random::random_sign(random, v);
}

// Random factors of degree 1 to 4 with coefficients of 1 to 300 bits (leading coefficients of
// either sign, the sizes of the gears' resultants), multiplied into pairs with a common part (the
// factors shared, each at the smaller multiplicity) and, for some pairs, a content; factors
// repeat (square_free_part's gcd with the derivative): the gcd is the primitive part of the
// common part (random cofactors are coprime) and the plain primitive sequence's gcd; degree
// gaps between the arguments from 0 to 12. (Session 53 measured a subresultant sequence here:
// slower on Geneva's and the gears' gcds, not kept.)
TEST(AlgebraGcdMemo, GcdOfLargeCoefficientProductsIsTheCommonPart) {
  std::mt19937_64 random(53053);
  auto factor = [&] {
    const int degree = 1 + static_cast<int>(random() % 4);
    const int bits = 1 + static_cast<int>(random() % 300);
    Polynomial f;
    for (int i = 0; i <= degree; ++i) f.push_back(random_integer(random, bits, i == degree));
    return f;
  };
  int checked = 0, constant = 0, large_gap = 0;
  for (int trial = 0; trial < 150; ++trial) {
    std::vector<Polynomial> pool;
    const int count = 2 + static_cast<int>(random() % 4);
    for (int k = 0; k < count; ++k) pool.push_back(factor());
    std::vector<int> ma(pool.size()), mb(pool.size());
    for (std::size_t k = 0; k < pool.size(); ++k) {
      ma[k] = static_cast<int>(random() % 3);
      mb[k] = static_cast<int>(random() % 3);
    }
    Polynomial a{mpz_class(1)}, b{mpz_class(1)}, common{mpz_class(1)};
    for (std::size_t k = 0; k < pool.size(); ++k) {
      for (int m = 0; m < ma[k]; ++m) a = times(a, pool[k]);
      for (int m = 0; m < mb[k]; ++m) b = times(b, pool[k]);
      for (int m = 0; m < std::min(ma[k], mb[k]); ++m) common = times(common, pool[k]);
    }
    if (random() % 3 == 0) a = times(a, Polynomial{random_integer(random, 90, true)});
    if (random() % 3 == 0) b = times(b, Polynomial{random_integer(random, 90, true)});
    const Polynomial expected = primitive_part(common);
    const Polynomial reference = primitive_sequence_gcd(a, b);
    ASSERT_EQ(reference, expected) << "trial " << trial << ": the primitive sequence's gcd of " << to_string(a, "x")
                                   << " and " << to_string(b, "x");
    for (int round = 0; round < 2; ++round) {
      ASSERT_EQ(gcd(a, b), expected) << "trial " << trial << ": gcd(" << to_string(a, "x") << ", " << to_string(b, "x")
                                     << ") is not " << to_string(expected, "x");
      ASSERT_EQ(gcd(b, a), expected) << "trial " << trial;
    }
    // a polynomial with its derivative (square_free_part's gcd): the repeated factors
    const Polynomial da = derivative(a);
    ASSERT_EQ(gcd(a, da), primitive_sequence_gcd(a, da)) << "trial " << trial << ": gcd with the derivative of "
                                                         << to_string(a, "x");
    ++checked;
    constant += degree(expected) == 0;
    large_gap += std::abs(degree(a) - degree(b)) >= 2;
  }
  EXPECT_EQ(checked, 150);
  EXPECT_GT(constant, 10);
  EXPECT_GT(large_gap, 50);
}

// gcd's modular route (session 54): Brown's algorithm over primes below 2^31, its candidate
// checked by exact division. Generated pairs of degree >= 2 with a known common part: random
// factors of degree 1-4 and 1-400 bits (square factors too, as the gcd with a derivative),
// leading coefficients that the moduli divide (2147483647 times a factor: those primes must be
// skipped), and unlucky primes — the common part times (x - a) and (x - a - k P) for one of
// the first three moduli P, whose reductions modulo P share one more root than the integers do. Each gcd is the
// common part's primitive part, the plain primitive sequence's gcd, and the library's gcd with
// the modular route switched off (on a fresh thread: the memo is per thread); the modular
// route must answer most of them (else the test would test the sequence only).
TEST(AlgebraGcdMemo, ModularRouteIsThePrimitiveSequenceGcd) {
  std::mt19937_64 random(54054);
  const mpz_class big_prime = 2147483647;
  auto factor = [&](int max_degree) {
    const int degree = 1 + static_cast<int>(random() % static_cast<unsigned>(max_degree));
    const int bits = 1 + static_cast<int>(random() % 400);
    Polynomial f;
    for (int i = 0; i <= degree; ++i) f.push_back(random_integer(random, bits, i == degree));
    if (random() % 4 == 0) f.back() *= big_prime;   // a modulus divides the leading coefficient
    return f;
  };
  struct Case {
    Polynomial a, b, expected;
  };
  std::vector<Case> cases;
  int unlucky = 0, constant = 0, squares = 0;
  for (int trial = 0; trial < 160; ++trial) {
    Polynomial common{mpz_class(1)};
    const int shared = static_cast<int>(random() % 3);
    for (int k = 0; k < shared; ++k) common = times(common, factor(3));
    Polynomial a = times(common, factor(4)), b = times(common, factor(4));
    if (trial % 4 == 1) {
      // an unlucky prime: x - r and x - r - k p are one factor modulo p
      const mpz_class r = random_integer(random, 1 + static_cast<int>(random() % 60), false);
      const mpz_class k = 1 + static_cast<long>(random() % 1000);
      // the first, second or third modulus (2^31 - 1, 2^31 - 19, 2^31 - 61): unlucky before or
      // after a lucky one
      const mpz_class modulus = std::array<long, 3>{2147483647, 2147483629, 2147483587}[random() % 3];
      a = times(a, Polynomial{mpz_class(-r), mpz_class(1)});
      b = times(b, Polynomial{mpz_class(-(r + k * modulus)), mpz_class(1)});
      ++unlucky;
    }
    if (trial % 4 == 2) {
      // a square factor and the derivative (square_free_part's gcd)
      a = times(times(a, common), factor(2));
      b = derivative(a);
      ++squares;
      const Polynomial reference = primitive_sequence_gcd(a, b);
      cases.push_back({a, b, reference});
      continue;
    }
    if (random() % 3 == 0) a = times(a, Polynomial{random_integer(random, 90, true)});
    const Polynomial expected = primitive_part(common);
    constant += degree(expected) == 0;
    cases.push_back({a, b, expected});
  }
  const std::size_t before = modular_gcd_answers().load();
  std::size_t eligible = 0;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Case& k = cases[c];
    ASSERT_EQ(primitive_sequence_gcd(k.a, k.b), k.expected) << "case " << c << ": the oracle's own gcd";
    ASSERT_EQ(gcd(k.a, k.b), k.expected) << "case " << c << ": gcd(" << to_string(k.a, "x") << ", "
                                         << to_string(k.b, "x") << ") is not " << to_string(k.expected, "x");
    ASSERT_EQ(gcd(k.b, k.a), k.expected) << "case " << c;
    eligible += degree(primitive_part(k.a)) >= 2 && degree(primitive_part(k.b)) >= 2;
  }
  const std::size_t answered = modular_gcd_answers().load() - before;
  // the same gcds by the remainder sequence alone
  modular_gcd_enabled() = false;
  std::vector<Polynomial> sequence(cases.size());
  std::thread([&] {
    for (std::size_t c = 0; c < cases.size(); ++c) sequence[c] = gcd(cases[c].a, cases[c].b);
  }).join();
  modular_gcd_enabled() = true;
  for (std::size_t c = 0; c < cases.size(); ++c) EXPECT_EQ(sequence[c], cases[c].expected) << "case " << c;
  EXPECT_EQ(modular_gcd_answers().load() - before, answered) << "the switch did not switch the route off";
  EXPECT_EQ(cases.size(), 160u);
  EXPECT_GT(unlucky, 30);
  EXPECT_GT(squares, 30);
  EXPECT_GT(constant, 20);
  // every eligible pair asked both ways round (the memo holds each order once)
  EXPECT_GE(answered, eligible * 2 * 9 / 10) << eligible << " pairs of degree >= 2";
}

// to_string(Polynomial) (the text of every algebraic number `cspace --json` writes; session 54
// wrote it into one string instead of an ostringstream): written by hand for a few, and for
// generated polynomials (zero, unit and 1-300-bit coefficients of either sign, degrees 0-9)
// the plain stream rendition of the same rules.
TEST(AlgebraPolynomialText, TermsHighestFirstWithSignsUnitsAndPowers) {
  auto text = [](std::vector<long> c) {
    Polynomial p;
    for (long v : c) p.emplace_back(v);
    trim(p);
    return to_string(p, "x");
  };
  EXPECT_EQ(text({}), "0");
  EXPECT_EQ(text({5}), "5");
  EXPECT_EQ(text({-5}), "-5");
  EXPECT_EQ(text({1}), "1");
  EXPECT_EQ(text({-1}), "-1");
  EXPECT_EQ(text({0, 1}), "x");
  EXPECT_EQ(text({0, -1}), "-x");
  EXPECT_EQ(text({-2, 0, 1}), "x^2 - 2");
  EXPECT_EQ(text({1, -1}), "-x + 1");
  EXPECT_EQ(text({0, 0, 0, -1}), "-x^3");
  EXPECT_EQ(text({-1, 3, 0, -12, 0, 0, 0, 0, 0, 0, 0, 1}), "x^11 - 12*x^3 + 3*x - 1");
  std::mt19937_64 random(5454);
  for (int trial = 0; trial < 2000; ++trial) {
    Polynomial p(random() % 10 + 1);
    for (auto& c : p) {
      const int kind = static_cast<int>(random() % 4);
      c = kind == 0 ? mpz_class(0) : kind == 1 ? mpz_class(random() % 2 ? 1 : -1)
                                                : random_integer(random, 1 + static_cast<int>(random() % 300), false);
    }
    trim(p);
    std::ostringstream plain;
    if (p.empty()) plain << "0";
    bool first = true;
    for (int i = degree(p); i >= 0; --i) {
      const mpz_class& c = p[static_cast<std::size_t>(i)];
      if (sgn(c) == 0) continue;
      plain << (first ? (sgn(c) < 0 ? "-" : "") : (sgn(c) < 0 ? " - " : " + "));
      first = false;
      const mpz_class magnitude = abs(c);
      if (i == 0 || magnitude != 1) plain << magnitude.get_str() << (i > 0 ? "*" : "");
      if (i > 0) plain << "t";
      if (i > 1) plain << "^" << i;
    }
    ASSERT_EQ(to_string(p, "t"), plain.str()) << "trial " << trial;
  }
}

TEST(AlgebraGcdMemo, PairsSharingAnArgumentGiveTheirOwnGcd) {
  std::mt19937_64 random(20261203);
  auto content = [&] {
    const long c = 1 + static_cast<long>(random() % 40);
    return random() % 2 ? c : -c;
  };
  int checked = 0, repeated = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const std::map<int, int> a_set = gcd_memo_factor_set(random);
    const Polynomial a = gcd_memo_product(a_set, content());
    // several second arguments with the same first (and each asked twice, both ways round)
    std::vector<std::pair<Polynomial, Polynomial>> cases;   // (b, expected gcd)
    for (int k = 0; k < 4; ++k) {
      const std::map<int, int> b_set = gcd_memo_factor_set(random);
      std::map<int, int> common;
      for (const auto& [f, m] : a_set)
        if (auto it = b_set.find(f); it != b_set.end()) common[f] = std::min(m, it->second);
      cases.emplace_back(gcd_memo_product(b_set, content()), gcd_memo_product(common, 1));
    }
    for (int round = 0; round < 2; ++round)
      for (const auto& [b, expected] : cases) {
        ASSERT_EQ(gcd(a, b), expected) << "trial " << trial << ": gcd(" << to_string(a, "x") << ", " << to_string(b, "x")
                                       << ") is not " << to_string(expected, "x");
        ASSERT_EQ(gcd(b, a), expected) << "trial " << trial << ": gcd(" << to_string(b, "x") << ", " << to_string(a, "x")
                                       << ") is not " << to_string(expected, "x");
        ++checked;
        repeated += round;
      }
    // a zero argument: the other's primitive part
    ASSERT_EQ(gcd(Polynomial{}, a), primitive_part(a));
    ASSERT_EQ(gcd(a, Polynomial{}), primitive_part(a));
  }
  EXPECT_EQ(checked, 1200);
  EXPECT_EQ(repeated, 600);
}

// The gcd of a list taken left to right, plainly (the oracle of the smallest-first content).
mpz_class plain_content(const std::vector<mpz_class>& values) {
  mpz_class g = 0;
  for (const mpz_class& v : values) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v.get_mpz_t());
  return g;
}

// p divided by its plain content, the sign making the leading coefficient positive.
Polynomial plain_primitive_part(Polynomial p) {
  trim(p);
  if (p.empty()) return p;
  mpz_class g = plain_content(p);
  if (sgn(p.back()) < 0) g = -g;
  for (auto& c : p) c /= g;
  return p;
}

// Session 55: contents are taken smallest coefficient first, stopping at 1 (content.hpp; used
// by primitive_part, normalize and the Descartes isolator). Generated coefficient lists (zeros,
// units, 1-20 and 1-600 bits, either sign, lengths 1-10, some all zero, some times a common
// factor of up to 200 bits): smallest_first_content is the plain left-to-right gcd,
// primitive_part the plain division by it, and normalize of the bivariate polynomial (the
// list as rows) divides by it: normalize(P) = normalize(P / content) = normalize(k P), k > 0.
TEST(AlgebraContent, SmallestFirstIsThePlainLeftToRightGcd) {
  std::mt19937_64 random(55055);
  int ones = 0, larger = 0, zero = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<mpz_class> values(1 + random() % 10);
    const bool all_zero = random() % 40 == 0;
    for (auto& v : values) {
      const int kind = all_zero ? 0 : static_cast<int>(random() % 5);
      v = kind == 0 ? mpz_class(0)
          : kind == 1 ? mpz_class(random() % 2 ? 1 : -1)
          : kind == 2 ? random_integer(random, 1 + static_cast<int>(random() % 20), true)
                      : random_integer(random, 1 + static_cast<int>(random() % 600), true);
    }
    if (random() % 2) {
      const mpz_class k = random_integer(random, 1 + static_cast<int>(random() % 200), true);
      for (auto& v : values) v *= k;
    }
    const mpz_class expected = plain_content(values);
    const mpz_class content = smallest_first_content([&](auto visit) {
      for (const mpz_class& v : values) visit(v.get_mpz_t());
    });
    ASSERT_EQ(content, expected) << "trial " << trial;
    ones += expected == 1;
    larger += expected > 1;
    zero += expected == 0;
    const Polynomial p(values.begin(), values.end());
    ASSERT_EQ(primitive_part(p), plain_primitive_part(p)) << "trial " << trial << ": " << to_string(p, "x");
    // the bivariate normalisation's content
    IntegerPolynomial2 bivariate, divided, multiplied;
    const std::size_t width = 1 + random() % 3;
    const mpz_class k = 1 + static_cast<long>(random() % 1000);
    for (std::size_t i = 0; i < values.size(); i += width) {
      bivariate.coefficients.emplace_back(values.begin() + static_cast<long>(i),
                                          values.begin() + static_cast<long>(std::min(values.size(), i + width)));
      divided.coefficients.push_back(bivariate.coefficients.back());
      multiplied.coefficients.push_back(bivariate.coefficients.back());
      for (auto& v : divided.coefficients.back())
        if (expected > 1) v /= expected;
      for (auto& v : multiplied.coefficients.back()) v *= k;
    }
    normalize(bivariate);
    normalize(divided);
    normalize(multiplied);
    ASSERT_EQ(bivariate.coefficients, divided.coefficients) << "trial " << trial;
    ASSERT_EQ(multiplied.coefficients, divided.coefficients) << "trial " << trial;
  }
  EXPECT_GT(ones, 500);
  EXPECT_GT(larger, 500);
  EXPECT_GT(zero, 20);
}

// Session 55: square_free_part no longer recomputes the content of its primitive argument
// (in the gcd with the derivative) nor of the quotient (primitive by Gauss's lemma), and
// real_roots(p) / nth_real_root / nth_real_root_in take square_free_test's polynomial (the
// exact gcd only when the modular test cannot certify p square-free). Generated products of
// random factors (degree 1-3, 1-200 bits) and of small linear factors (real roots), each at
// multiplicity 1-3, times a content of either sign: square_free_part is the plain primitive
// part divided by the plain sequence's gcd with the derivative (itself primitive), real_roots(p)
// is real_roots of that polynomial in its Cauchy bound (the route before session 55), root
// for root, nth_real_root its roots in turn, nth_real_root_in the same numbers, and every
// root is a root of the square-free part (exact, or a sign change over its interval).
TEST(AlgebraGcdMemo, SquareFreePartAndRootsAreThePlainRoute) {
  std::mt19937_64 random(55505);
  int repeated = 0, roots_seen = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Polynomial a{random_integer(random, 1 + static_cast<int>(random() % 90), true)};
    const int factors = 1 + static_cast<int>(random() % 3);
    bool square = false;
    for (int k = 0; k < factors; ++k) {
      Polynomial f;
      if (random() % 2) {
        const auto& [n, d] = gcd_memo_factors[random() % gcd_memo_factors.size()];
        f = {mpz_class(-n), mpz_class(d)};
      } else {
        const int deg = 1 + static_cast<int>(random() % 3);
        const int bits = 1 + static_cast<int>(random() % 200);
        for (int i = 0; i <= deg; ++i) f.push_back(random_integer(random, bits, i == deg));
      }
      const int multiplicity = 1 + static_cast<int>(random() % 3);
      square = square || multiplicity > 1;
      for (int m = 0; m < multiplicity; ++m) a = times(a, f);
    }
    repeated += square;
    // the plain square-free part
    const Polynomial q = plain_primitive_part(a);
    const Polynomial g = primitive_sequence_gcd(q, derivative(q));
    Polynomial expected(q.size() - g.size() + 1), rest = q;
    for (int k = degree(q) - degree(g); k >= 0; --k) {
      mpz_class& top = rest[static_cast<std::size_t>(k + degree(g))];
      ASSERT_TRUE(mpz_divisible_p(top.get_mpz_t(), g.back().get_mpz_t())) << "trial " << trial;
      expected[static_cast<std::size_t>(k)] = top / g.back();
      for (int i = 0; i <= degree(g); ++i)
        rest[static_cast<std::size_t>(k + i)] -= expected[static_cast<std::size_t>(k)] * g[static_cast<std::size_t>(i)];
    }
    trim(rest);
    ASSERT_TRUE(rest.empty()) << "trial " << trial << ": the gcd does not divide";
    ASSERT_EQ(plain_primitive_part(expected), expected) << "trial " << trial << ": the quotient is not primitive";
    ASSERT_EQ(square_free_part(a), expected) << "trial " << trial << ": " << to_string(a, "x");
    ASSERT_EQ(square_free_part(a), expected) << "trial " << trial << " (memo)";
    if (degree(expected) < 1) continue;
    const Rational bound = root_bound(expected);
    const std::vector<Real> reference = real_roots(expected, -bound, bound);
    const std::vector<Real> roots = real_roots(a);
    ASSERT_EQ(roots.size(), reference.size()) << "trial " << trial;
    for (std::size_t i = 0; i < roots.size(); ++i) {
      const Real& r = roots[i];
      ASSERT_EQ(r.polynomial, reference[i].polynomial) << "trial " << trial << " root " << i;
      ASSERT_EQ(r.lower, reference[i].lower) << "trial " << trial << " root " << i;
      ASSERT_EQ(r.upper, reference[i].upper) << "trial " << trial << " root " << i;
      ASSERT_EQ(r.exact, reference[i].exact) << "trial " << trial << " root " << i;
      if (r.exact) {
        ASSERT_EQ(sign_at(expected, r.lower), 0) << "trial " << trial << " root " << i;
      } else {
        ASSERT_EQ(r.polynomial, expected) << "trial " << trial << " root " << i;
        ASSERT_LT(sign_at(expected, r.lower) * sign_at(expected, r.upper), 0) << "trial " << trial << " root " << i;
      }
      const Real nth = nth_real_root(a, static_cast<int>(i));
      ASSERT_EQ(nth.lower, r.lower) << "trial " << trial << " root " << i;
      ASSERT_EQ(nth.upper, r.upper) << "trial " << trial << " root " << i;
      if (!r.exact) {
        const Real in = nth_real_root_in(a, static_cast<int>(i), -bound, bound);
        ASSERT_EQ(in.polynomial, expected) << "trial " << trial << " root " << i;
        ASSERT_EQ(compare(in, r), 0) << "trial " << trial << " root " << i;
      }
      ++roots_seen;
    }
  }
  EXPECT_GT(repeated, 100);
  EXPECT_GT(roots_seen, 300);
}

}  // namespace
}  // namespace hipair::cspace::algebra
