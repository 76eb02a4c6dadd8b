// The exact angle pieces' shortcuts (src/cspace/point_tangent.hpp, used by angle_pieces in
// src/cspace/cspace_queries.cpp; switch cspace::point_tangents()). Oracles: MPFR's own tangent
// rounded down and rounded up (two calls) for tan_half_both; the turn count angle_pieces computes
// (floor((m + pi) / 2 pi) at 64 and 160 bits) for zero_turns; the same crossing queries and the
// same simulations with the switch off (the general route) for both together.
#include "cspace/angle_memo.hpp"
#include "cspace/point_tangent.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation_side_by_side.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

struct Number {
  explicit Number(mpfr_prec_t bits) { mpfr_init2(v, bits); }
  ~Number() { mpfr_clear(v); }
  Number(const Number&) = delete;
  Number& operator=(const Number&) = delete;
  mpfr_t v;
};

// A generated angle of `bits` precision in (-pi, pi): log-uniform magnitudes 1e-300 ... 3.1, with
// random low bits below the double's, values next to +-pi/2 and +-pi, binade ends, zero.
void generated_angle(std::mt19937_64& random, mpfr_t angle) {
  std::uniform_real_distribution<double> unit(0, 1);
  const int kind = static_cast<int>(random() % 6);
  double d = 0;
  if (kind == 0) d = std::pow(10.0, -300 + 300.5 * unit(random));
  else if (kind == 1) d = 3.1 * unit(random);
  else if (kind == 2) d = std::nextafter(std::numbers::pi / 2, static_cast<double>(random() % 2) * 4) * (1 - 1e-12 * unit(random));
  else if (kind == 3) d = std::nextafter(std::numbers::pi, 0.0) * (1 - 1e-9 * unit(random));
  else if (kind == 4) d = std::ldexp(1.0, -static_cast<int>(random() % 60));   // tan(2^-k / 2) near a binade end
  else d = random() % 50 == 0 ? 0.0 : std::ldexp(1.0 + unit(random), -static_cast<int>(random() % 1000));
  mpfr_set_d(angle, d, MPFR_RNDN);
  if (random() % 2 == 0 && d != 0) {   // low bits beyond the double's
    Number low(mpfr_get_prec(angle));
    mpfr_set_d(low.v, std::ldexp(unit(random), -60), MPFR_RNDN);
    mpfr_mul(low.v, low.v, angle, MPFR_RNDN);
    mpfr_add(angle, angle, low.v, MPFR_RNDN);
  }
  if (random() % 2 == 0) mpfr_neg(angle, angle, MPFR_RNDN);
}

TEST(CSpacePointTangent, BoundsAreMpfrsDirectedTangents) {
  std::mt19937_64 random(4848);
  std::size_t compared = 0, points = 0, exact = 0, shortcuts = 0;
  const std::size_t before = cspace::point_tangent_shortcuts();
  for (mpfr_prec_t bits : {64, 160}) {
    Number lo(bits), hi(bits), down(bits), up(bits), half(bits), want_down(bits), want_up(bits);
    for (int i = 0; i < 60000; ++i) {
      generated_angle(random, lo.v);
      // a point, or an interval 1 ... 4 units in the last place wide (tau = angle -+ pi's
      // enclosures are that wide)
      const int ulps = random() % 2 == 0 ? 0 : 1 + static_cast<int>(random() % 4);
      mpfr_set(hi.v, lo.v, MPFR_RNDN);
      for (int k = 0; k < ulps; ++k) mpfr_nextabove(hi.v);
      const bool on = random() % 4 != 0;
      {
        test::FlagSwitch<&cspace::point_tangents> flag(on);
        cspace::tan_half_bounds(down.v, up.v, lo.v, hi.v);
      }
      mpfr_div_2ui(half.v, lo.v, 1, MPFR_RNDN);
      mpfr_tan(want_down.v, half.v, MPFR_RNDD);
      mpfr_div_2ui(half.v, hi.v, 1, MPFR_RNDN);
      mpfr_tan(want_up.v, half.v, MPFR_RNDU);
      ASSERT_TRUE(mpfr_equal_p(down.v, want_down.v) && mpfr_get_prec(down.v) == bits)
          << "angle " << mpfr_get_d(lo.v, MPFR_RNDN) << " + " << ulps << " ulps at " << bits << " bits (down)";
      ASSERT_TRUE(mpfr_equal_p(up.v, want_up.v) && mpfr_get_prec(up.v) == bits)
          << "angle " << mpfr_get_d(lo.v, MPFR_RNDN) << " + " << ulps << " ulps at " << bits << " bits (up)";
      ++compared;
      if (ulps == 0) ++points;
      if (ulps == 0 && mpfr_equal_p(want_down.v, want_up.v)) ++exact;
    }
  }
  shortcuts = cspace::point_tangent_shortcuts() - before;
  std::printf("tangent bounds: %zu angle ranges, %zu points (%zu exact), %zu shortcuts\n", compared, points, exact, shortcuts);
  EXPECT_GT(exact, 0u);   // tan(0) = 0: the ternary value's exact case is met
  EXPECT_GT(shortcuts, 40000u);
}

// floor((m + pi) / 2 pi) at `bits`, m the midpoint of [lo, hi], as angle_pieces computes it.
long turns_of(const mpq_class& lo, const mpq_class& hi, mpfr_prec_t bits) {
  Number mid(bits), turn(bits), k(bits);
  mpq_class m = (lo + hi) / 2;
  mpfr_set_q(mid.v, m.get_mpq_t(), MPFR_RNDN);
  mpfr_const_pi(turn.v, MPFR_RNDN);
  mpfr_add(mid.v, mid.v, turn.v, MPFR_RNDN);
  mpfr_mul_2ui(turn.v, turn.v, 1, MPFR_RNDN);
  mpfr_div(k.v, mid.v, turn.v, MPFR_RNDN);
  mpfr_floor(k.v, k.v);
  return mpfr_get_si(k.v, MPFR_RNDN);
}

TEST(CSpacePointTangent, ZeroTurnsOnlyWhereTheReductionFindsNone) {
  std::mt19937_64 random(4849);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t said_zero = 0, reduced = 0, compared = 0;
  for (int i = 0; i < 40000; ++i) {
    // ends within, at and beyond +-3, beyond +-pi (one turn), far; points and narrow or wide ranges
    const double centre = random() % 4 == 0 ? (random() % 2 ? 1 : -1) * (3 + 0.2 * (unit(random) - 0.5))
                        : random() % 3 == 0 ? (random() % 2 ? 1 : -1) * (std::numbers::pi + 1.5 * unit(random))
                                            : 8 * (unit(random) - 0.5);
    const double width = random() % 3 == 0 ? 0.0 : std::pow(10.0, -15 + 15 * unit(random));
    mpq_class lo(centre), hi(centre + width);
    if (random() % 2 == 0) {   // non-dyadic ends
      lo -= mpq_class(1, 3 + static_cast<long>(random() % 1000000));
      hi += mpq_class(1, 3 + static_cast<long>(random() % 1000000));
    }
    const bool zero = cspace::zero_turns(lo.get_mpq_t(), hi.get_mpq_t());
    for (mpfr_prec_t bits : {64, 160}) {
      const long turns = turns_of(lo, hi, bits);
      ++compared;
      if (turns != 0) ++reduced;
      if (zero) ASSERT_EQ(turns, 0) << "[" << lo.get_d() << ", " << hi.get_d() << "] at " << bits << " bits";
    }
    if (zero) ++said_zero;
  }
  std::printf("zero turns: %zu ranges said zero, %zu of %zu reductions with a turn\n", said_zero, reduced, compared);
  EXPECT_GT(said_zero, 10000u);
  EXPECT_GT(reduced, 10000u);
}

TEST(CSpacePointTangent, CrossingAnswersEqualTheAnswersWithoutThem) {
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  test::FlagSwitch<&cspace::angle_memo> memo(false);   // every query computes its own pieces
  std::mt19937_64 random(4850);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::size_t compared = 0, shortcuts = 0;
  for (int i = 0; i < 900; ++i) {
    test::PartStart s = test::part_start(spaces, random, test::pick_start);
    const CSpaceChart& chart = s.space->charts()[s.chart];
    if (random() % 6 == 0 && chart.x_kind == AxisKind::rotation)   // beyond +-3 and +-pi: reduced
      s.qx0 += (random() % 2 ? 1 : -1) * (random() % 2 ? 2 * std::numbers::pi : 0.2 * unit(random));
    const bool point = random() % 2 == 0;
    const double scale = std::pow(10.0, -4 + 4 * unit(random));
    const double vx = point ? 0 : sym(random) * scale, vy = point ? 0 : sym(random) * scale;
    MotionPath path = test::bent_motion(chart, s.two, s.qx0, s.qy0, vx, vy, 0.0, point);
    std::ostringstream what;
    what.precision(17);
    what << s.space->first_part() << ":" << s.space->second_part() << " motion " << i << " from " << s.qx0 << ", "
         << s.qy0 << " by " << vx << ", " << vy << (point ? " (point)" : "");
    const std::size_t before = cspace::point_tangent_shortcuts();
    auto [on, off] = test::on_and_off<&cspace::point_tangents>(random, [&](bool) { return test::crossing_answer(*s.space, path); });
    ASSERT_EQ(on, off) << what.str();
    shortcuts += cspace::point_tangent_shortcuts() - before;
    ++compared;
  }
  std::printf("point tangents: %zu queries equal, %zu shortcuts taken\n", compared, shortcuts);
  EXPECT_GT(shortcuts, 100u);
}

TEST(CSpacePointTangent, SimulationRunsEqualTheRunsWithoutThem) {
  test::FlagSwitch<&cspace::angle_memo> memo(false);
  const std::size_t before = cspace::point_tangent_shortcuts();
  test::SideBySide runs = test::examples_side_by_side<cspace::point_tangents>(
      {{"escapement.json", 0.3, 1e-3}, {"ratchet.json", 0.1, 1e-6}});
  ASSERT_FALSE(HasFailure());
  const std::size_t events = runs.events;
  std::printf("point tangents: %zu steps, %zu events equal with the switch off; %zu shortcuts\n", runs.steps, events,
              cspace::point_tangent_shortcuts() - before);
  EXPECT_GT(events, 20u);
  EXPECT_GT(cspace::point_tangent_shortcuts() - before, 0u);
}

}  // namespace
}  // namespace hipair
