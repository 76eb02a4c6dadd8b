// Correctly rounded figures of exact numbers (issue 13, session 63): to_double of rationals,
// algebra::nearest_double of real algebraic numbers (isolating intervals about 0 included) and
// algebra::half_angle_degrees, at scales 2^-1200 ... 2^1100, against the oracle of
// rounding_oracle.hpp: round to nearest even on the exact rational in integers (no MPFR), atan by
// its alternating series and pi between two 60-digit decimals (a bracket of the value; the case
// counts only when both ends of the bracket round to the same double).
#include "algebra/exact_real.hpp"
#include "algebra/nearest_double.hpp"
#include "pin_slot_test_support.hpp"
#include "rounding_oracle.hpp"
#include "test_seed.hpp"

#include <hipair/model.hpp>
#include <hipair/pin_slot.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>

namespace hipair {
namespace {

namespace algebra = cspace::algebra;
using algebra::Real;

using test::rounding::expected_degrees;
using test::rounding::oracle_round;
using test::rounding::power_of_two;
using test::rounding::same_double;

// A root of an integer polynomial in its isolating interval.
Real root(algebra::Polynomial p, const Rational& lower, const Rational& upper) {
  Real r;
  r.polynomial = std::move(p);
  r.lower = lower;
  r.upper = upper;
  return r;
}

TEST(NearestDouble, RationalsRoundToNearestEvenAtEveryScale) {
  std::mt19937_64 random(test::test_seed(63));
  int subnormal = 0;
  for (int i = 0; i < 4000; ++i) {
    const long e = static_cast<long>(random() % 2300) - 1200;   // 2^-1200 ... 2^1100
    mpz_class num(static_cast<unsigned long>(random() >> 1)), den(static_cast<unsigned long>((random() >> 1) | 1));
    if (i % 3 == 0) num = num * mpz_class(static_cast<unsigned long>(random() >> 1)) + 1;   // longer numerators
    Rational q(num, den);
    q.canonicalize();
    q *= power_of_two(e);
    if (i % 2) q = -q;
    // ties and near-ties: a 54-bit odd mantissa (a tie of the 53-bit grid) and its neighbours
    if (i % 5 == 0) {
      mpz_class tie = (mpz_class(1) << 53) + (mpz_class(static_cast<unsigned long>(random() >> 12)) * 2 + 1);
      q = Rational(tie) * power_of_two(e - 53);
      if (i % 10 == 0) q += power_of_two(e - 200) * ((i % 20 == 0) ? 1 : -1);
    }
    const double expected = oracle_round(q);
    if (expected != 0 && std::fabs(expected) < std::numeric_limits<double>::min()) ++subnormal;
    EXPECT_TRUE(same_double(to_double(q), expected)) << to_exact_string(q) << ": " << to_double(q) << " for " << expected;
    EXPECT_TRUE(same_double(algebra::nearest_double(q), expected)) << to_exact_string(q);
  }
  EXPECT_GT(subnormal, 20);
  // the ends of the subnormal range
  for (long k : {1073L, 1074L, 1075L, 1076L}) {
    for (int s : {1, -1}) {
      const Rational q = power_of_two(-k) * s;
      EXPECT_TRUE(same_double(to_double(q), oracle_round(q))) << k;
      const Rational above = q * Rational(1025, 1024);
      EXPECT_TRUE(same_double(to_double(above), oracle_round(above))) << k;
    }
  }
}

TEST(NearestDouble, AlgebraicNumbersNearZeroAndAtExtremeScales) {
  // 0 itself, isolated by an interval about 0: +0
  {
    const Real zero = root({mpz_class(0), mpz_class(-3), mpz_class(1)}, Rational(-1), Rational(1));   // t (t - 3)
    EXPECT_TRUE(same_double(algebra::nearest_double(zero), 0.0));
    EXPECT_TRUE(same_double(algebra::half_angle_degrees(zero), 0.0));
  }
  std::mt19937_64 random(test::test_seed(63));
  for (long k = 1; k <= 1200; k += 1 + static_cast<long>(random() % 7)) {
    const mpz_class two_k = mpz_class(1) << static_cast<mp_bitcnt_t>(k);
    for (int s : {1, -1}) {
      // +-2^-k, a root of (2^k t -+ 1)(t - 5) isolated by (-1, 1): an interval straddling 0
      const algebra::Polynomial p = {mpz_class(5 * s), -(5 * two_k + s), two_k};
      const Real exact_power = root(p, Rational(-1), Rational(1));
      const Rational value = power_of_two(-k) * s;
      EXPECT_TRUE(same_double(algebra::nearest_double(exact_power), oracle_round(value))) << "2^-" << k << " sign " << s;
      // the degrees of that angle: the same as of the rational, and the oracle's where it decides
      const double degrees = algebra::half_angle_degrees(exact_power);
      EXPECT_TRUE(same_double(degrees, algebra::half_angle_degrees(value))) << k;
      if (auto expected = expected_degrees(power_of_two(-k), power_of_two(-k))) {
        EXPECT_TRUE(same_double(degrees, s * *expected)) << "degrees of 2^-" << k << ": " << degrees << " for " << s * *expected;
      } else {
        ADD_FAILURE() << "the oracle's bracket does not decide 2^-" << k;
      }
      // s sqrt(2) 2^-k, a root of 4^k t^2 - 2 isolated by (0, 1) or (-1, 0): an end at 0
      const Real irrational = root({mpz_class(-2), mpz_class(0), two_k * two_k}, s > 0 ? Rational(0) : Rational(-1),
                                   s > 0 ? Rational(1) : Rational(0));
      // the oracle: sqrt(2) 2^-k between two rationals 2^-400 of it apart
      mpz_class floor_root;
      mpz_class radicand = mpz_class(2) << 800;
      mpz_sqrt(floor_root.get_mpz_t(), radicand.get_mpz_t());
      const Rational lo = Rational(floor_root) * power_of_two(-400 - k), hi = Rational(floor_root + 1) * power_of_two(-400 - k);
      const double a = oracle_round(lo), b = oracle_round(hi);
      ASSERT_TRUE(same_double(a, b)) << k;
      EXPECT_TRUE(same_double(algebra::nearest_double(irrational), s > 0 ? a : -b)) << "sqrt(2) 2^-" << k;
      if (k >= 2)
        if (auto expected = expected_degrees(lo, hi)) {
          EXPECT_TRUE(same_double(algebra::half_angle_degrees(irrational), s * *expected)) << "degrees of sqrt(2) 2^-" << k;
        }
    }
  }
  // the right angle and the half-angle tangents near it
  EXPECT_TRUE(same_double(algebra::half_angle_degrees(Rational(1)), 90.0));
  EXPECT_TRUE(same_double(algebra::half_angle_degrees(Rational(-1)), -90.0));
}

// Random rational tangents in (0, 1/2] at every scale against the series oracle.
TEST(NearestDouble, HalfAngleDegreesOfRandomTangents) {
  std::mt19937_64 random(test::test_seed(63));
  int decided = 0;
  for (int i = 0; i < 600; ++i) {
    const long e = 1 + static_cast<long>(random() % 1150);
    Rational x(mpz_class(static_cast<unsigned long>((random() >> 2) | 1)), mpz_class(static_cast<unsigned long>(random() | (1ul << 63))));
    x.canonicalize();
    x *= power_of_two(-e + 1);
    if (x > Rational(1, 2)) x /= 2;
    const auto expected = expected_degrees(x, x);
    if (!expected) continue;
    ++decided;
    EXPECT_TRUE(same_double(algebra::half_angle_degrees(x), *expected)) << to_exact_string(x);
    EXPECT_TRUE(same_double(algebra::half_angle_degrees(Rational(-x)), -*expected)) << to_exact_string(x);
  }
  EXPECT_GT(decided, 550);
}

// The pin-slot claw of PinSlotScale.AClawFarAlongItsSlot... pivoted 10^60 mm and 10^200 mm
// along its slot: its critical values' tau lie near 10^-(e+1), in isolating intervals with an
// end at 0; the published degrees are the oracle's (base62: 2.09e-134 degrees for about
// 2.9e-199 at 10^200, the refinement measured against the interval, not the value).
TEST(NearestDouble, PinSlotCriticalDegreesOfAFarClaw) {
  for (int exponent : {60, 200}) {
    const Model model = pin_slot_test::claw_far_along_slot(exponent);
    PinSlotBuildOptions options;
    options.normalise_lengths = true;
    const PinSlotSpace space = PinSlotSpace::build(model, "block", "claw", options);
    ASSERT_GT(space.critical_values().size(), 5u);
    int nonzero = 0;
    for (const PinSlotCritical& c : space.critical_values()) {
      if (c.half_turn) continue;
      Real r = root(c.tau.polynomial, c.tau.lower, c.tau.upper);
      r.exact = c.tau.exact;
      if (r.exact || r.compare(Rational(0)) == 0) {
        EXPECT_TRUE(same_double(c.degrees, 0.0));
        continue;
      }
      ++nonzero;
      // the oracle's bracket on an enclosure apart from 0 and narrow enough to decide
      const int sign = r.compare(Rational(0));
      std::optional<double> expected;
      for (int round = 0; round < 200 && !expected; ++round) {
        Rational width = r.upper - r.lower;
        r.refine_to(width / 1024);
        if (r.exact) break;
        if (sgn(r.lower) * sgn(r.upper) <= 0) continue;
        expected = sign > 0 ? expected_degrees(r.lower, r.upper) : expected_degrees(Rational(-r.upper), Rational(-r.lower));
      }
      ASSERT_TRUE(expected.has_value()) << c.tau.to_string("tau");
      EXPECT_TRUE(same_double(c.degrees, sign * *expected))
          << "10^" << exponent << ": " << c.tau.to_string("tau") << ": " << c.degrees << " for " << sign * *expected;
    }
    EXPECT_GT(nonzero, 5);
    for (const PinSlotSlice& s : space.slices())
      if (sgn(s.tau) != 0 && abs(s.tau) <= Rational(1, 2)) {
        const Rational x = abs(s.tau);
        if (auto expected = expected_degrees(x, x)) EXPECT_TRUE(same_double(s.degrees, sgn(s.tau) * *expected)) << to_exact_string(s.tau);
      }
  }
}

}  // namespace
}  // namespace hipair
