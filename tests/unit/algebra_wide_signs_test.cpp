// Session 45 (scale45): signs at real algebraic numbers with wide coefficients (mixed scales), the
// path of the oracle at the mixed-scale squares' contact vertices (two rotating squares of 10^-a
// and 10^b mm spent most of their `cspace` in it: an integer gcd per sign, then 16 MPFR
// halvings of u's bracket per round).
//  1. The multi-precision filter narrows u's bracket by interval Newton steps: a value that
//     cancels to 2^-t of its terms (t = 1 500 … 4 000) is decided with a number of polynomial
//     enclosures that grows like log t, not like t (bisection alone needs about t of them), and
//     the sign is the exact path's (gcd, square-free part, Sturm sequence).
//  2. sign_at's zero test: a wide polynomial certified coprime to u's modulo a word-size prime
//     needs no gcd over the integers; exact zeros (multiples of u's polynomial) and
//     polynomials sharing another root of u's polynomial still go through it, with the exact
//     path's sign.
//  3. The mixed-scale squares (10^-a / 10^b mm, generated a, b) are built completely, and
//     exact point location at generated rational configurations equals the exact overlap
//     oracle.
#include "algebra/multiprecision_sign.hpp"
#include "cspace_test_support.hpp"
#include "random_algebraic.hpp"
#include "random_rationals.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

using test_numbers::random_integer;

using test_algebraic::random_polynomial;

using test_algebraic::times;

// D x - N with N / D within 2^-t |u| of u: its value at u cancels to about 2^-t of its terms.
Polynomial cancelling_linear_form(const Real& u, int t) {
  Real v = u;
  Rational width = abs(u.lower) + abs(u.upper);
  mpz_class scale = 1;
  mpz_mul_2exp(scale.get_mpz_t(), scale.get_mpz_t(), static_cast<mp_bitcnt_t>(t));
  refine_dyadically(v, width / scale);
  return Polynomial{-v.lower.get_num(), v.lower.get_den()};
}

TEST(AlgebraWideSigns, TheFilterConvergesLikeNewtonOnDeepCancellation) {
  std::mt19937_64 random(45);
  int cases = 0;
  long most = 0;
  for (int round = 0; round < 24; ++round) {
    const int bits = 200 + static_cast<int>(random() % 600);
    auto drawn = test_algebraic::random_irrational(random, bits, 0);
    if (!drawn) continue;
    const Real& u = *drawn;
    const int t = 1500 + static_cast<int>(random() % 2500);
    Polynomial p = cancelling_linear_form(u, t);
    if (round % 2) p = times(p, random_polynomial(random, 1 + static_cast<int>(random() % 2), 80));
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + "-bit u, 2^-" +
                           std::to_string(t) + ")";
    const int exact = exact_sign_at(p, u);
    ASSERT_NE(exact, 0) << at;
    const MultiprecisionBits precisions = multiprecision_sign_bits(p, u);
    const long before = multiprecision_enclosures();
    const auto filtered = multiprecision_sign(p, u, precisions.start, precisions.cap);
    const long used = multiprecision_enclosures() - before;
    ASSERT_TRUE(filtered) << at << ": not decided within " << precisions.cap << " bits";
    EXPECT_EQ(*filtered, exact) << at;
    // Newton doubles the correct bits per step at each precision (192, 384, … bits): a few
    // dozen enclosures; 16 halvings a round take about t point enclosures
    EXPECT_LE(used, 300) << at << ": " << used << " enclosures";
    EXPECT_EQ(sign_at(p, u), exact) << at;
    most = std::max(most, used);
    ++cases;
  }
  EXPECT_GE(cases, 12);
  std::printf("%d cases, at most %ld enclosures\n", cases, most);
}

TEST(AlgebraWideSigns, CoprimeWideValuesNeedNoIntegerGcdAndZerosStillFindIt) {
  std::mt19937_64 random(4545);
  int coprime = 0, zeros = 0, shared = 0;
  for (int round = 0; round < 40; ++round) {
    const int bits = 200 + static_cast<int>(random() % 1200);
    auto drawn = test_algebraic::random_irrational(random, bits, 0);
    if (!drawn) continue;
    const Real& u = *drawn;
    const std::string at = "round " + std::to_string(round) + " (" + std::to_string(bits) + " bits)";
    // a random wide polynomial, and one cancelling to 2^-(bits / 2)
    for (Polynomial p : {random_polynomial(random, 1 + static_cast<int>(random() % 5), bits),
                         cancelling_linear_form(u, 200 + bits / 2)}) {
      if (multiprecision_sign_bits(p, u).width <= 192 || !coprime_modularly(u.polynomial, p)) continue;
      const long before = wide_sign_gcds();
      EXPECT_EQ(sign_at(p, u), exact_sign_at(p, u)) << at;
      EXPECT_EQ(wide_sign_gcds(), before) << at << ": an integer gcd for a certified coprime pair";
      ++coprime;
    }
    // exact zeros: u's polynomial times a factor
    {
      const Polynomial p = times(u.polynomial, random_polynomial(random, 1 + static_cast<int>(random() % 2), 100));
      const long before = wide_sign_gcds();
      EXPECT_EQ(sign_at(p, u), 0) << at << ": a zero";
      EXPECT_EQ(wide_sign_gcds(), before + 1) << at;
      ++zeros;
    }
    // a polynomial sharing another root of u's: u a root of f g (f, g irrational quadratics),
    // p = g times a factor: not coprime, p(u) != 0 (the gcd's root is not u)
    {
      Polynomial f{random_integer(random, bits, true), random_integer(random, bits, true), mpz_class(1)};
      Polynomial g{-random_integer(random, bits, false), random_integer(random, 40, true), mpz_class(1)};
      f[0] = -abs(f[0]);   // real roots
      std::vector<Real> roots = real_roots(times(f, g));
      for (const Real& w : roots) {
        if (w.exact || sign_at(f, w.lower) * sign_at(f, w.upper) >= 0) continue;   // a root of f
        const Polynomial p = times(g, random_polynomial(random, 1, bits));
        const int exact = exact_sign_at(p, w);
        ASSERT_NE(exact, 0) << at;
        EXPECT_EQ(sign_at(p, w), exact) << at << ": a polynomial sharing another root";
        ++shared;
        break;
      }
    }
  }
  EXPECT_GE(coprime, 30);
  EXPECT_GE(zeros, 15);
  EXPECT_GE(shared, 15);
  std::printf("%d coprime, %d zeros, %d others\n", coprime, zeros, shared);
}

}  // namespace
}  // namespace hipair::cspace::algebra

namespace hipair {
namespace {

// Two squares turning about their centres' neighbourhood: a of half-side 10^-a mm about the
// origin, b of half-side 10^b mm about (10^-a + 1.001·10^b, 0) (tests/cli/run_hostile_cli_tests.sh).
std::string mixed_squares(int small, int large) {
  const std::string s = "1e-" + std::to_string(small), l = "e" + std::to_string(large);
  const std::string near = "\"" + s + " + 0.001" + l + "\"", far = "\"" + s + " + 2.001" + l + "\"";
  return R"({ "hipair": 1, "name": "mixed", "parts": [
  { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } },
    "loops": [ { "start": ["-)" + s + R"(", "-)" + s + R"("], "edges": [
      { "line_to": [")" + s + R"(", "-)" + s + R"("] }, { "line_to": [")" + s + R"(", ")" + s + R"("] },
      { "line_to": ["-)" + s + R"(", ")" + s + R"("] }, { "line_to": ["-)" + s + R"(", "-)" + s + R"("] } ] } ] },
  { "name": "b", "motion": { "rotation": { "pivot": [")" + s + " + 1.001" + l + R"(", 0] } },
    "loops": [ { "start": [)" + near + R"(, "-1)" + l + R"("], "edges": [
      { "line_to": [)" + far + R"(, "-1)" + l + R"("] }, { "line_to": [)" + far + R"(, "1)" + l + R"("] },
      { "line_to": [)" + near + R"(, "1)" + l + R"("] }, { "line_to": [)" + near + R"(, "-1)" + l + R"("] } ] } ] } ] })";
}

TEST(AlgebraWideSigns, MixedScaleSquaresLocateAsTheExactOracle) {
  std::mt19937_64 random(20261203);
  for (int round = 0; round < 2; ++round) {
    const int small = 10 + static_cast<int>(random() % 21), large = 50 + static_cast<int>(random() % 51);
    SCOPED_TRACE("squares of 1e-" + std::to_string(small) + " and 1e" + std::to_string(large) + " mm");
    ReadOptions options;
    Model model = read_model(mixed_squares(small, large), "mixed", options);
    CSpace space = CSpace::build(model, "a", "b");
    ASSERT_TRUE(space.complete());
    ASSERT_FALSE(space.cells().empty());
    cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("a"), *model.find_part("b"));
    int free = 0, blocked = 0;
    for (int i = 0; i < 200; ++i) {
      const ChartPoint q = test::random_tile_point(space, random);
      const Location location = space.locate(q);
      const CSpaceChart& chart = space.charts()[q.chart];
      const cspace::Overlap overlap = cspace::classify_overlap(
          model, axes, test::axis_of(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi),
          test::axis_of(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi), cspace::ChartPoint{q.x, q.y});
      if (location.kind == Location::Kind::free) {
        EXPECT_EQ(overlap, cspace::Overlap::apart) << "at " << q.x << ", " << q.y;
        ++free;
      } else if (location.kind == Location::Kind::blocked) {
        EXPECT_EQ(overlap, cspace::Overlap::overlapping) << "at " << q.x << ", " << q.y;
        ++blocked;
      }
    }
    EXPECT_GT(free, 0);
    EXPECT_GT(blocked, 0);
  }
}

}  // namespace
}  // namespace hipair
