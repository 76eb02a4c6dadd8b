// The certified double filter of the validity clauses (raw::clauses_hold_filter, used by the
// quadratic traits' clipping before the exact fibre root) against the exact answer
// (raw::clauses_hold): on generated clause sets, points and enclosures, every answer the
// filter gives (1 holds, 0 fails) is the exact one; it declines (-1) only where it may.
// Generated cases include atoms vanishing exactly at the point (the exact answer is "holds",
// an enclosure around 0 must not say "fails"), coefficients of 2-200 bits, and wide and
// narrow enclosures of the algebraic y.
#include "arrangement/clip_common.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hipair {
namespace {

using cspace::IntegerPolynomial2;
using hipair::Rational;
using cspace::ValidityClause;
namespace raw = cspace::raw;
namespace algebra = cspace::algebra;

mpz_class random_integer(std::mt19937_64& rng, int bits) {
  mpz_class v = 0;
  for (int b = 0; b < bits; b += 30) v = (v << 30) + static_cast<long>(rng() & ((1u << 30) - 1));
  v >>= (bits + 29) / 30 * 30 - bits;
  return (rng() & 1) ? mpz_class(-v) : v;
}

IntegerPolynomial2 random_polynomial(std::mt19937_64& rng, int degree_x, int degree_y, int bits) {
  IntegerPolynomial2 f;
  f.coefficients.assign(static_cast<std::size_t>(degree_x + 1), std::vector<mpz_class>(static_cast<std::size_t>(degree_y + 1)));
  for (auto& row : f.coefficients)
    for (auto& c : row) c = (rng() % 4 == 0) ? mpz_class(0) : random_integer(rng, bits);
  return f;
}

TEST(CSpaceClauseFilter, GeneratedClausesGiveTheExactAnswerWheneverTheFilterDecides) {
  std::mt19937_64 rng(20261128);
  int decided = 0, declined = 0, vanishing = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int bits = trial % 3 == 0 ? 200 : trial % 3 == 1 ? 40 : 4;
    // the point: a rational x, y a real root of a quadratic fibre of a curve through x
    Rational x(random_integer(rng, 12), mpz_class(1 + static_cast<long>(rng() % 997)));
    x.canonicalize();
    IntegerPolynomial2 curve = random_polynomial(rng, 2, 2, bits);
    algebra::Polynomial fiber = algebra::substitute_x(curve, x);
    const auto roots = algebra::degree(fiber) >= 1 ? algebra::real_roots(fiber) : std::vector<algebra::Real>{};
    if (roots.empty()) continue;
    algebra::Real y = roots[rng() % roots.size()];
    if (rng() % 2) algebra::refine_dyadically(y, Rational(1, mpz_class(1) << (rng() % 60)));
    // alternatives of 1-2 clause lists, clauses of 1-3 atoms; some atoms vanish at the point
    std::vector<std::vector<ValidityClause>> lists(1 + rng() % 2);
    for (auto& clauses : lists) {
      clauses.resize(rng() % 3);
      for (auto& clause : clauses) {
        clause.atoms.resize(1 + rng() % 3);
        for (auto& atom : clause.atoms) {
          if (rng() % 8 == 0) {
            atom = curve;   // vanishes at (x, y): the exact sign is 0 (holds)
            if (rng() % 2)
              for (auto& row : atom.coefficients)
                for (auto& c : row) c = -c;
            ++vanishing;
          } else {
            atom = random_polynomial(rng, static_cast<int>(rng() % 3), static_cast<int>(rng() % 3), bits);
          }
        }
      }
    }
    std::vector<const std::vector<ValidityClause>*> alternatives;
    for (const auto& clauses : lists) alternatives.push_back(&clauses);
    const algebra::Interval xi{algebra::lower_double(x), algebra::upper_double(x)};
    const algebra::Interval yi{y.lower_bound(), y.upper_bound()};
    const int filtered = raw::clauses_hold_filter(alternatives, xi, yi);
    const bool exact = raw::clauses_hold(alternatives, x, y);
    if (filtered < 0) {
      ++declined;
      continue;
    }
    ++decided;
    ASSERT_EQ(filtered == 1, exact) << "trial " << trial << ", x = " << x.get_str();
  }
  // the filter decides most cases (else it saves nothing) and declines some (the vanishing
  // atoms and the wide enclosures)
  EXPECT_GT(decided, 1000);
  EXPECT_GT(declined, 10);
  EXPECT_GT(vanishing, 100);
}

}  // namespace
}  // namespace hipair
