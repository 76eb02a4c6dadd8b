// The certified nudge off a corner of contact space (src/simulation/nudge_check.hpp;
// docs/simulation.md, "Session 35"). The Geneva drive's pin held at the corner of a slot
// (geneva-drive.json, 1.3947 s into the second turn) leaves a state about 1.7e-11 rad inside the
// corner, where two contact curves meet; the nudge moves the wheel alone. Near the start the
// blocked walk cannot be placed or step (the interval evaluation of the curves through the
// corner still holds zero 2e-11 rad away), and session 34's allowance, 2^10 first trials
// (9.1e-13 rad), left that stretch to the walk: its check refused the legitimate move and the
// two-turn runs stopped with a jammed contact change. With the allowance 2^16 first trials
// (5.8e-11 rad) the stretch the walk cannot certify lies within the start's allowance.
//
// Generated starts at the corner (10) and at its images under the drive's quarter-turn symmetry
// (3 at each other slot: the driver's turn k, the wheel a quarter turn k on), driver angles swept
// over 1e-9 rad about the corner and depths 2^-37 ... 2^-30 rad: each is nudged as the simulator
// nudges (trials start - first (2^j - 1) on the wheel's angle, the first the exact point query
// finds free). Oracle: the exact point query at 257 configurations over the move (independent of
// the crossing query and of the walk): a free configuration and then a blocked one is a tunnel.
// The check accepts exactly the moves the oracle finds no tunnel in; with session 34's allowance
// it refuses most of the corner's.
//   - SimulationNudgeCorner.GenevaSlotCornerStartsAreMovedOff
#include "simulation/nudge_check.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>

namespace hipair {
namespace {

MotionPath at(double driver, double wheel) {
  MotionPath p;
  p.x.kind = p.y.kind = AxisPath::Kind::angle;
  p.x.coefficients = {Rational(driver)};
  p.y.coefficients = {Rational(wheel)};
  p.u_begin = p.u_end = 0;
  return p;
}

bool free_at(const CSpace& space, double driver, double wheel) {
  return space.first_crossing(at(driver, wheel)).status == CrossingStatus::none;
}

TEST(SimulationNudgeCorner, GenevaSlotCornerStartsAreMovedOff) {
  const Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva-drive.json");
  const CSpace space = CSpace::build(model, "driver", "wheel");
  ASSERT_EQ(space.x_part(), "driver");
  std::mt19937_64 random(35);
  std::uniform_real_distribution<double> unit(0, 1);
  // the corner the second turn's run met: driver 8.76304187767 rad, wheel -pi/2
  const double driver0 = 8.7630418776698402 - 2 * std::numbers::pi;
  int cases = 0, accepted = 0, corner = 0, refused_before = 0;
  for (int slot = 0; slot < 4; ++slot)
    for (int n = 0; n < (slot == 1 ? 10 : 3); ++n) {
      const double driver = driver0 + 2 * std::numbers::pi * slot + 1e-9 * (unit(random) - 0.5);
      const double depth = std::ldexp(1.0, -37 + static_cast<int>(random() % 7)) * (1 + unit(random));
      const double wheel0 = -std::numbers::pi / 2 * slot + depth;
      const double first = 4 * std::numeric_limits<double>::epsilon() * std::max({1.0, std::abs(driver), std::abs(wheel0)});
      double wheel = wheel0;
      int j = 0;
      while (j <= 50 && !free_at(space, driver, wheel)) wheel = wheel0 - first * (std::ldexp(1.0, ++j) - 1);
      ASSERT_LE(j, 50) << "slot " << slot << " case " << n;
      if (j == 0) continue;   // the start was free
      ++cases;
      bool seen_free = false, tunnel = false;
      for (int i = 0; i <= 256; ++i) {
        const bool f = free_at(space, driver, wheel0 + (wheel - wheel0) * i / 256.0);
        tunnel = tunnel || (seen_free && !f);
        seen_free = seen_free || f;
      }
      MotionPath back = at(driver, wheel);
      back.u_end = 1;
      back.y.coefficients.push_back(Rational(wheel0) - Rational(wheel));
      const double length = std::abs(wheel - wheel0);
      const bool ok = simulation::move_certified(space, back, length, simulation::nudge_allowance * first, 44);
      EXPECT_EQ(ok, !tunnel) << "slot " << slot << " case " << n << ": driver " << driver << " depth " << depth;
      accepted += ok;
      if (slot == 1) {
        ++corner;
        refused_before += !simulation::move_certified(space, back, length, 1024 * first, 44);
      }
    }
  EXPECT_GE(cases, 8);
  EXPECT_EQ(accepted, cases);
  // at slot 1 (the run's corner; the other slots' corners lie elsewhere by the rounding of the
  // model's rational geometry) session 34's allowance refused the moves
  EXPECT_GE(refused_before, corner / 2) << refused_before << " of " << corner << " corner moves refused with 2^10";
}

}  // namespace
}  // namespace hipair
