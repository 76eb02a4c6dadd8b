// The certified move of a nudge off contact (src/simulation/nudge_check.hpp; docs/simulation.md,
// "Session 34"). A bar rotating about the origin rests on a fixed stop at theta = 0 (blocked
// below); a thin tooth of the same fixed part, above the bar, blocks a sliver [theta1, theta2]
// of angles just beyond the contact. A start left inside the stop by d is nudged as the
// simulator nudges: trials start + first (2^k - 1), first = 4 eps, the first one the exact point
// query finds free accepted. With d and the sliver swept so that the trial before the accepted
// one is still inside the stop and the sliver lies between the contact and the accepted trial,
// main's nudge (point checks only) jumps across the tooth: the oracle — the exact point query at
// 257 configurations spread over the move, independent of the crossing query — sees the move
// pass a free configuration and then a blocked one (a missed contact). The check of the move
// (nudge_check.hpp's move_certified, the reversed segment asked of the certified crossing
// query) rejects every such move, and accepts every move the oracle finds in one free cell once
// the start is within the allowance of the contact (starts a few ulps inside, which the
// rounding of a configuration on the curve gives).
//   - SimulationNudgeCheck.MainsNudgeJumpsTheToothTheCheckRejectsIt
//   - SimulationNudgeCheck.MovesOffTheContactItselfAreAccepted
//   - SimulationNudgeCheck.DeepStartsInATwoDimensionalSpace
#include "simulation/nudge_check.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

namespace hipair {
namespace {

constexpr double first = 4 * std::numeric_limits<double>::epsilon();   // scale 1: |theta| < 1
constexpr double half = 1e-9;   // the bar's half thickness (mm)

std::string decimal(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

// The bar (x in [0, 60], |y| <= half) and the frame: the stop below the bar's lower side
// (contact at theta = 0) and, when theta1 < theta2, a tooth whose lower corner at x = 40 + half
// the upper side meets at theta1 and whose upper corner at x = 40 the lower side passes at theta2.
// `rotating`: the frame turns about (100, 100) (a 2-D space, the frame at angle 0 throughout;
// the blocked walk applies), else fixed (a 1-D space).
CSpace bar_space(double theta1, double theta2, bool rotating = false) {
  const std::string h = decimal(half), mh = decimal(-half);
  std::string tooth;
  if (theta1 < theta2) {
    const double xa = 40 + half, xb = 40;
    const double ya = (half + xa * std::sin(theta1)) / std::cos(theta1);
    const double yb = (xb * std::sin(theta2) - half) / std::cos(theta2);
    tooth = R"(, { "start": [)" + decimal(xb) + ", " + decimal(ya) + R"(], "edges": [ { "line_to": [)" + decimal(xa) +
            ", " + decimal(ya) + R"(] }, { "line_to": [)" + decimal(xa) + ", " + decimal(yb) + R"(] }, { "line_to": [)" +
            decimal(xb) + ", " + decimal(yb) + R"(] }, { "line_to": [)" + decimal(xb) + ", " + decimal(ya) + "] } ] }";
  }
  const std::string text = R"({ "hipair": 1, "name": "bar-stop-tooth", "parts": [
      { "name": "bar", "motion": { "rotation": { "pivot": [0, 0] } }, "dynamics": { "moment_of_inertia": 1 },
        "loops": [ { "start": [0, )" + mh + R"(], "edges": [ { "line_to": [60, )" + mh + R"(] }, { "line_to": [60, )" + h +
                           R"(] }, { "line_to": [0, )" + h + R"(] }, { "line_to": [0, )" + mh + R"(] } ] } ] },
      { "name": "frame", "motion": )" + std::string(rotating ? R"({ "rotation": { "pivot": [100, 100] } })" : R"("fixed")") + R"(,
        "loops": [ { "start": [20, -5], "edges": [ { "line_to": [50, -5] }, { "line_to": [50, )" + mh +
                           R"(] }, { "line_to": [20, )" + mh + R"(] }, { "line_to": [20, -5] } ] })" + tooth + R"( ] } ],
    "pairs": [ { "parts": ["bar", "frame"] } ] })";
  return CSpace::build(read_model(text), "bar", "frame");
}

// the bar at angle theta (the frame at 0)
MotionPath point(double theta) {
  MotionPath at;
  at.x.kind = AxisPath::Kind::angle;
  at.x.coefficients = {Rational(theta)};
  at.y.kind = AxisPath::Kind::angle;
  at.u_begin = at.u_end = 0;
  return at;
}

// the bar at angle theta alone: free (the simulator's point query)
bool free_at(const CSpace& space, double theta) { return space.first_crossing(point(theta)).status == CrossingStatus::none; }

// main's ladder from `start` along +theta: the first trial the point query finds free (k <= 50)
bool ladder(const CSpace& space, double start, double& trial, double& before) {
  double q = start;
  before = start;
  for (int k = 0; k <= 50; ++k) {
    if (free_at(space, q)) {
      trial = q;
      return true;
    }
    before = q;
    q += first * std::ldexp(1.0, k);
  }
  return false;
}

// the oracle: along the move start -> trial, a free configuration and then a non-free one
bool oracle_tunnels(const CSpace& space, double start, double trial) {
  bool seen_free = false;
  for (int i = 0; i <= 256; ++i) {
    double theta = start + (trial - start) * i / 256.0;
    bool f = free_at(space, theta);
    if (seen_free && !f) return true;
    seen_free = seen_free || f;
  }
  return false;
}

bool checked(const CSpace& space, double start, double trial) {
  MotionPath back = point(0);
  back.u_end = 1;
  Rational from(trial), to(start);
  back.x.coefficients = {from, to - from};
  return simulation::move_certified(space, back, std::abs(trial - start), simulation::nudge_allowance * first, 44);
}

TEST(SimulationNudgeCheck, MainsNudgeJumpsTheToothTheCheckRejectsIt) {
  std::mt19937_64 random(34);
  std::uniform_real_distribution<double> unit(0, 1);
  int tunnels = 0, cases = 0;
  for (int n = 0; n < 24; ++n) {
    // the accepted trial is trial k (k in 24..44): the start d below the contact with trial
    // k - 1 below it; the sliver between the contact and trial k
    const int k = 24 + static_cast<int>(random() % 21);
    const double below = first * (std::ldexp(1.0, k - 1) - 1), at = first * (std::ldexp(1.0, k) - 1);
    const double d = below + (at - below) * (0.05 + 0.4 * unit(random));   // trial k at at - d > 0
    const double reach = at - d;
    const double a = 0.1 + 0.4 * unit(random), width = 0.05 + 0.3 * unit(random);   // positions, widths
    const double theta1 = reach * a, theta2 = reach * std::min(a + width, 0.9);
    CSpace space = bar_space(theta1, theta2);
    double trial = 0, before = 0;
    ASSERT_TRUE(ladder(space, -d, trial, before)) << "case " << n;
    ++cases;
    const bool tunnel = oracle_tunnels(space, -d, trial);
    tunnels += tunnel;
    // the check never accepts a move the oracle sees cross the tooth
    if (tunnel) EXPECT_FALSE(checked(space, -d, trial)) << "case " << n << ": k " << k << " d " << d << " trial " << trial;
  }
  // the generated cases are ones main's nudge tunnels through
  EXPECT_GE(tunnels, cases * 3 / 4) << tunnels << " of " << cases;
}

TEST(SimulationNudgeCheck, MovesOffTheContactItselfAreAccepted) {
  std::mt19937_64 random(3434);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int n = 0; n < 24; ++n) {
    // a start a few ulps inside the stop, the tooth (if any) well beyond the first free trial
    const double d = first * std::ldexp(1.0, static_cast<int>(random() % 9)) * unit(random);
    const bool tooth = n % 2 == 0;
    CSpace space = tooth ? bar_space(1e-6 * (1 + unit(random)), 4e-6) : bar_space(1, 0);
    double trial = 0, before = 0;
    ASSERT_TRUE(ladder(space, -d, trial, before)) << "case " << n;
    ASSERT_FALSE(oracle_tunnels(space, -d, trial)) << "case " << n;
    EXPECT_TRUE(checked(space, -d, trial)) << "case " << n << ": d " << d << " trial " << trial;
    // and a longer move into the same free cell (short of the tooth): certified by the query
    const double far = tooth ? 5e-7 : 1e-3;
    EXPECT_TRUE(checked(space, -d, far)) << "case " << n;
    if (tooth) EXPECT_FALSE(checked(space, -d, 1e-5)) << "case " << n << ": across the tooth";
  }
}

// The same in the 2-D space of the bar and a turning frame, where a start deep inside the stop
// can be certified (the blocked walk from the start to within the allowance of the crossing):
// deep starts whose move ends short of the tooth are accepted, those whose move jumps the tooth
// (main's nudge: a missed contact, the oracle's free-then-blocked) rejected.
TEST(SimulationNudgeCheck, DeepStartsInATwoDimensionalSpace) {
  std::mt19937_64 random(343434);
  std::uniform_real_distribution<double> unit(0, 1);
  int tunnels = 0, accepted = 0;
  for (int s = 0; s < 2; ++s) {
    const double theta1 = std::ldexp(1.0, -30 + 6 * s) * (1 + unit(random)), theta2 = theta1 * (1.5 + unit(random));
    CSpace space = bar_space(theta1, theta2, true);
    ASSERT_EQ(space.dimension(), 2u);
    for (int n = 0; n < 6; ++n) {
      // k: trial k short of the tooth (n even) or beyond it (n odd); trial k - 1 inside the stop
      int k = 0;
      while (first * std::ldexp(1.0, k + 1) < theta1) ++k;
      if (n % 2) {
        while (first * std::ldexp(1.0, k - 1) < 1.5 * theta2) ++k;
        k += static_cast<int>(random() % 3);
      } else {
        k -= 1 + static_cast<int>(random() % 4);
      }
      const double below = first * (std::ldexp(1.0, k - 1) - 1), at = first * (std::ldexp(1.0, k) - 1);
      const double top = n % 2 ? at - 1.2 * theta2 : at;
      const double d = below + (top - below) * (0.05 + 0.9 * unit(random));
      double trial = 0, before = 0;
      ASSERT_TRUE(ladder(space, -d, trial, before)) << "space " << s << " case " << n;
      const bool tunnel = oracle_tunnels(space, -d, trial);
      ASSERT_EQ(tunnel, n % 2 == 1) << "space " << s << " case " << n << ": k " << k << " d " << d << " trial " << trial;
      const bool ok = checked(space, -d, trial);
      EXPECT_EQ(ok, !tunnel) << "space " << s << " case " << n << ": k " << k << " d " << d << " trial " << trial;
      tunnels += tunnel;
      accepted += ok;
    }
  }
  EXPECT_EQ(tunnels, 6);
  EXPECT_EQ(accepted, 6);
}

}  // namespace
}  // namespace hipair
