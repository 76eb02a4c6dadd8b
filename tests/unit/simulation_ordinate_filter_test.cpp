// The vertical-edge ordinate test in doubles first (src/simulation/ordinate_filter.hpp, switch
// simulation::ordinate_filter()): the directed conversions against exact rational comparisons
// on generated rationals of every scale, and the simulator's runs with the filter against the
// runs without it, side by side (tests/unit/simulation_side_by_side.hpp), bit for bit, on the
// escapement (held contacts on its locking faces, vertical edges) with friction and without.
#include "simulation/ordinate_filter.hpp"
#include "simulation_side_by_side.hpp"
#include "random_integers.hpp"

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

// r <= double_above(r), double_below(r) <= r, and no double strictly between: the neighbours
// outside are on the other side of r (in the normal range); random numerators and denominators
// of up to 200 bits scaled by 2^k, |k| <= 800 (1e-300 .. 1e300), exact doubles, their
// neighbours, halves between neighbours, zero.
TEST(SimulationOrdinateFilter, DirectedConversionsBoundEveryRational) {
  std::mt19937_64 random(20261201);
  auto big = [&](int bits) { return test_random::whole_words(random, bits); };
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Rational r;
    const int kind = trial % 4;
    if (kind == 0) {
      mpz_class n = big(1 + static_cast<int>(random() % 200)), d = big(1 + static_cast<int>(random() % 200)) + 1;
      r = Rational(n, d);
      const long k = static_cast<long>(random() % 1601) - 800;   // |r| in 2^-1000 .. 2^1000
      if (k >= 0) r *= Rational(mpz_class(1) << static_cast<unsigned long>(k));
      else r /= Rational(mpz_class(1) << static_cast<unsigned long>(-k));
    } else {
      const double x = std::ldexp(std::uniform_real_distribution<double>(0.5, 1)(random),
                                  static_cast<int>(random() % 2001) - 1000);
      const double next = std::nextafter(x, std::numeric_limits<double>::infinity());
      r = kind == 1 ? Rational(x) : kind == 2 ? (Rational(x) + Rational(next)) / 2 : Rational(next);
      if (trial % 8 == 7) r = 0;
    }
    r.canonicalize();
    if (random() % 2) r = -r;
    const double lo = simulation::double_below(r), hi = simulation::double_above(r);
    ASSERT_TRUE(std::isfinite(lo) && std::isfinite(hi)) << r.get_str();
    ASSERT_LE(Rational(lo), r) << r.get_str();
    ASSERT_GE(Rational(hi), r) << r.get_str();
    // the tightest: the next double outward is past r (normal range)
    if (std::abs(lo) > std::numeric_limits<double>::min() && std::abs(hi) > std::numeric_limits<double>::min()) {
      ASSERT_GT(Rational(std::nextafter(lo, std::numeric_limits<double>::infinity())), r) << r.get_str();
      ASSERT_LT(Rational(std::nextafter(hi, -std::numeric_limits<double>::infinity())), r) << r.get_str();
    }
    if (lo == hi) ASSERT_EQ(Rational(lo), r);
    ++checked;
  }
  // beyond the doubles' range
  const Rational huge = Rational(mpz_class(1) << 1100), tiny = Rational(1, mpz_class(1) << 1100);
  EXPECT_LE(Rational(simulation::double_below(huge)), huge);
  EXPECT_EQ(simulation::double_above(huge), std::numeric_limits<double>::infinity());
  EXPECT_EQ(simulation::double_below(-huge), -std::numeric_limits<double>::infinity());
  EXPECT_GE(Rational(simulation::double_above(-huge)), -huge);
  EXPECT_LE(Rational(simulation::double_below(tiny)), tiny);
  EXPECT_GE(Rational(simulation::double_above(tiny)), tiny);
  EXPECT_LE(Rational(simulation::double_below(-tiny)), -tiny);
  EXPECT_GE(Rational(simulation::double_above(-tiny)), -tiny);
  EXPECT_EQ(checked, 20000);
}

TEST(SimulationOrdinateFilter, EscapementRunsEqualTheRunsWithoutIt) {
  const std::size_t decided_before = simulation::ordinate_filter_decided();
  const test::SideBySide total = test::runs_side_by_side<simulation::ordinate_filter>(
      HIPAIR_SOURCE_DIR,
      {{"examples/models/escapement.json", 0.5, 1e-3},
       {"examples/models/escapement.json", 0.25, 1e-6},
       {"tests/data/simulation/escapement-frictionless.json", 0.25, 1e-3}},
      std::numeric_limits<std::size_t>::max());
  const std::size_t steps = total.steps, events = total.events;
  const std::size_t decided = simulation::ordinate_filter_decided() - decided_before;
  std::printf("ordinate filter: %zu steps, %zu events equal; %zu vertex comparisons decided in doubles\n", steps, events,
              decided);
  EXPECT_GT(decided, 100u);
}

}  // namespace
}  // namespace hipair
