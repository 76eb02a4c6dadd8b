// The crossing scanner's paired path enclosures (src/cspace/path_filter.hpp,
// evaluate_path_filtered_pair; switch cspace::paired_paths()): two polynomials of one length over
// one stretch evaluated in the two lanes of one pass must give, for each, the bits of the scalar
// evaluate_path_filtered_d — on generated polynomials of 1 to 8 coefficients (points and narrow
// and wide intervals, zeros, signed zeros, subnormals, magnitudes up to the doubles' range where
// products overflow) over generated stretches (points, zero, narrow, wide, both signs); the
// crossing answers on generated motions with the switch on equal those with it off; and the
// escapement and the ratchet side by side with the switch off, step for step.
#include "cspace/path_filter.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;

// A double of a random kind: zero (either sign), a subnormal, a magnitude 10^-300 ... 10^300, a
// huge one near the range's end, an ordinary one near 1.
double generated_double(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double sign = random() % 2 == 0 ? 1.0 : -1.0;
  switch (random() % 8) {
    case 0: return sign * 0.0;
    case 1: return sign * std::ldexp(unit(random), -1060);
    case 2: return sign * std::pow(10.0, -300 + 600 * unit(random));
    case 3: return sign * std::numeric_limits<double>::max() * (0.5 + 0.5 * unit(random));
    default: return sign * std::pow(10.0, -3 + 6 * unit(random));
  }
}

// An interval around a generated double: a point, a few ulps, or a relative width.
Interval generated_interval(std::mt19937_64& random) {
  double a = generated_double(random);
  switch (random() % 4) {
    case 0: return Interval::point(a);
    case 1: {
      double b = a;
      for (int k = static_cast<int>(random() % 4) + 1; k > 0; --k) b = std::nextafter(b, INFINITY);
      return Interval(a, b);
    }
    case 2: return Interval(a, a + std::abs(a) * 1e-9 + 1e-300);
    default: {
      double b = generated_double(random);
      return Interval(std::min(a, b), std::max(a, b));
    }
  }
}

std::string bits(const std::optional<Interval>& v) {
  if (!v) return "none";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%016llx:%016llx", static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(v->lo)),
                static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(v->hi)));
  return buffer;
}

TEST(CSpacePathFilter, PairGivesTheScalarFormsBits) {
  std::mt19937_64 random(49);
  std::uniform_real_distribution<double> unit(0, 1);
  int finite = 0, overflowed = 0;
  for (int i = 0; i < 200000; ++i) {
    const std::size_t n = 1 + random() % 8;
    std::vector<Interval> p(n), q(n);
    for (std::size_t k = 0; k < n; ++k) {
      p[k] = generated_interval(random);
      q[k] = generated_interval(random);
    }
    // the stretch: [a, b] of the path parameter (mostly in [0, 1] as the scanner's), a point, 0
    double a = unit(random), b = a + unit(random) * std::pow(10.0, -16 * unit(random));
    switch (random() % 6) {
      case 0: b = a; break;
      case 1: a = b = 0; break;
      case 2: a = -a; break;
      case 3: a = generated_double(random), b = a + std::abs(a) * unit(random); break;
      default: break;
    }
    Interval A(a, std::nextafter(a, INFINITY)), B(std::nextafter(b, -INFINITY), b);
    if (random() % 2 == 0) A = Interval::point(a), B = Interval::point(b);
    std::optional<Interval> pv, qv;
    ASSERT_TRUE(cspace::evaluate_path_filtered_pair(p, q, A, B, pv, qv));
    const std::optional<Interval> ps = cspace::evaluate_path_filtered_d(p, A, B), qs = cspace::evaluate_path_filtered_d(q, A, B);
    ASSERT_EQ(bits(pv), bits(ps)) << "case " << i << " (p, n = " << n << ")";
    ASSERT_EQ(bits(qv), bits(qs)) << "case " << i << " (q, n = " << n << ")";
    (ps ? finite : overflowed) += 1;
  }
  // lengths that differ, or beyond 8: not paired
  std::optional<Interval> pv, qv;
  EXPECT_FALSE(cspace::evaluate_path_filtered_pair(std::vector<Interval>(3, Interval(1)), std::vector<Interval>(4, Interval(1)),
                                                   Interval(0), Interval(1), pv, qv));
  EXPECT_FALSE(cspace::evaluate_path_filtered_pair(std::vector<Interval>(9, Interval(1)), std::vector<Interval>(9, Interval(1)),
                                                   Interval(0), Interval(1), pv, qv));
  std::printf("pairs: %d finite, %d overflowed, each lane the scalar form's bits\n", finite, overflowed);
  EXPECT_GT(finite, 100000);
  EXPECT_GT(overflowed, 1000);
}

TEST(CSpacePathFilter, CrossingAnswersEqualTheAnswersWithoutPairs) {
  test::SwitchCounts counts;
  std::uint64_t seed = 4949;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    test::switch_answers_equal<&cspace::paired_paths, &cspace::paired_path_count>(*space, 100, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("motions %d: crossing %d, none %d; %zu pairs\n", counts.motions, counts.crossing, counts.none, counts.hits);
  EXPECT_GE(counts.motions, 400);
  EXPECT_GE(counts.crossing, 30);
  EXPECT_GE(counts.hits, 1000u);
}

TEST(CSpacePathFilter, SimulationRunsEqualTheRunsWithoutPairs) {
  const std::size_t before = cspace::paired_path_count();
  test::SideBySide runs =
      test::examples_side_by_side<cspace::paired_paths>({{"escapement.json", 0.3, 1e-3}, {"ratchet.json", 0.1, 1e-6}});
  ASSERT_FALSE(HasFailure());
  std::printf("paired paths: %zu steps, %zu events equal with the switch off; %zu pairs\n", runs.steps, runs.events,
              cspace::paired_path_count() - before);
  EXPECT_GT(runs.events, 20u);
  EXPECT_GT(cspace::paired_path_count() - before, 0u);
}

}  // namespace
}  // namespace hipair
