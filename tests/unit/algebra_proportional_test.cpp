// algebra::proportional (the builder's edge labels and the quadratic traits' branch-end signs
// skip an exact sign where a polynomial is proportional to a point's own polynomial): generated
// univariate and bivariate integer polynomials against an independent oracle, each polynomial's
// coefficients divided by their gcd and signed by the first non-zero one (two non-zero
// polynomials are proportional exactly when these normal forms are equal).
#include "algebra/proportional.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

using Flat = std::vector<mpz_class>;

// The normal form over places 0 … count − 1 (empty for the zero polynomial).
Flat normal_form(Flat c) {
  while (!c.empty() && sgn(c.back()) == 0) c.pop_back();
  if (c.empty()) return c;
  mpz_class g = 0;
  for (const auto& v : c) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v.get_mpz_t());
  int first = 0;
  for (const auto& v : c)
    if (sgn(v) != 0) { first = sgn(v); break; }
  for (auto& v : c) {
    mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), g.get_mpz_t());
    if (first < 0) v = -v;
  }
  return c;
}

bool oracle(const Flat& p, const Flat& q) {
  const Flat a = normal_form(p), b = normal_form(q);
  return !a.empty() && a == b;
}

class Generator {
 public:
  explicit Generator(std::uint32_t seed) : rng_(seed), big_(gmp_randinit_default) { big_.seed(seed); }
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  // a non-zero random integer of 1 … bits bits, or zero with probability zero_odds / 8
  mpz_class integer(int bits, int zero_odds) {
    if (pick(0, 7) < zero_odds) return 0;
    mpz_class v = big_.get_z_bits(static_cast<unsigned long>(pick(1, bits)));
    if (v == 0) v = 1;
    return pick(0, 1) ? v : mpz_class(-v);
  }

 private:
  std::mt19937 rng_;
  gmp_randclass big_;
};

// q and a partner p: c q (c = a / b with b dividing every coefficient, after q was multiplied
// by b), a near miss (one coefficient moved by ±1 or ±q_0), a random polynomial, or zero.
Flat partner(Generator& g, Flat& q, int bits) {
  const int kind = g.pick(0, 5);
  if (kind <= 2) {
    const mpz_class a = g.integer(bits, 0), b = abs(g.integer(bits, 0));
    for (auto& v : q) v *= b;
    Flat p = q;
    for (auto& v : p) {
      mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), b.get_mpz_t());
      v *= a;
    }
    if (kind == 2 && !p.empty()) {   // a near miss of a proportional pair
      const std::size_t k = static_cast<std::size_t>(g.pick(0, static_cast<int>(p.size()) - 1));
      p[k] += g.pick(0, 1) ? mpz_class(1) : mpz_class(-1);
    }
    return p;
  }
  if (kind == 3) return Flat(q.size());
  Flat p(static_cast<std::size_t>(g.pick(0, static_cast<int>(q.size()) + 2)));
  for (auto& v : p) v = g.integer(bits, 3);
  return p;
}

TEST(AlgebraProportional, UnivariatePairsAgreeWithNormalForms) {
  Generator g(20261202);
  int yes = 0, no = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int bits = trial % 4 == 0 ? 1500 : g.pick(1, 80);
    Flat q(static_cast<std::size_t>(g.pick(1, 9)));
    for (auto& v : q) v = g.integer(bits, trial % 3 == 0 ? 5 : 2);
    for (int pad = g.pick(0, 2); pad > 0; --pad) q.push_back(0);   // trailing zeros allowed
    const Flat p = partner(g, q, bits);
    const bool expected = oracle(p, q);
    (expected ? yes : no) += 1;
    ASSERT_EQ(proportional(p, q), expected) << "trial " << trial;
    ASSERT_EQ(proportional(q, p), expected) << "trial " << trial << " (swapped)";
  }
  EXPECT_GT(yes, 1000);
  EXPECT_GT(no, 1000);
}

TEST(AlgebraProportional, BivariatePairsAgreeWithNormalFormsWhateverTheRowsLengths) {
  Generator g(7);
  int yes = 0, no = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int bits = trial % 5 == 0 ? 700 : g.pick(1, 64);
    const int rows = g.pick(0, 5), columns = g.pick(1, 5);
    // one flat list of rows × columns places, then stored with ragged rows (trailing zeros cut
    // or padded per row): the polynomial is the same
    Flat q(static_cast<std::size_t>(rows * columns));
    for (auto& v : q) v = g.integer(bits, trial % 2 ? 4 : 1);
    const Flat p = [&] {
      Flat r = partner(g, q, bits);
      r.resize(q.size());
      return r;
    }();
    auto stored = [&](const Flat& flat) {
      IntegerPolynomial2 f;
      f.coefficients.resize(static_cast<std::size_t>(rows + g.pick(0, 1)));
      for (int i = 0; i < rows; ++i) {
        auto& row = f.coefficients[static_cast<std::size_t>(i)];
        row.assign(flat.begin() + i * columns, flat.begin() + (i + 1) * columns);
        if (g.pick(0, 1)) while (!row.empty() && sgn(row.back()) == 0) row.pop_back();
        else row.resize(row.size() + static_cast<std::size_t>(g.pick(0, 2)));
      }
      return f;
    };
    const bool expected = oracle(p, q);
    (expected ? yes : no) += 1;
    const IntegerPolynomial2 fp = stored(p), fq = stored(q);
    ASSERT_EQ(proportional(fp, fq), expected) << "trial " << trial;
    ASSERT_EQ(proportional(fq, fp), expected) << "trial " << trial << " (swapped)";
  }
  EXPECT_GT(yes, 500);
  EXPECT_GT(no, 500);
}

}  // namespace
}  // namespace hipair::cspace::algebra
