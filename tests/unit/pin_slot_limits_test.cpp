// A pin-slot part's angle limits, decided exactly (src/core/angle_limits.hpp; session 53):
// psi = 2 atan(tau) at a rational tau against rational limits, modulo whole turns.
//
// The oracle is independent of MPFR/MPFI: an exact rational bracket of 2 atan(tau) from the
// alternating Taylor series of atan (|x| <= 1/3 after atan(tau) = pi/4 + atan((tau - 1) /
// (tau + 1)) or pi/2 - atan(1 / tau)) and pi's first 60 decimals, narrower than 1e-40. Limits
// 1e-30 rad inside and outside the bracket (and shifted by whole turns) must be decided so, on
// generated tangents from 1e-25 to 1e25; before session 53 locate compared a double atan with a
// 1e-12 margin and refused every such configuration as "too close to an angle limit".
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include "algebra/exact_real.hpp"
#include "core/angle_limits.hpp"
#include "curves/contact_curves.hpp"
#include "kinematics/axis.hpp"
#include "sliced/critical_angles.hpp"
#include "pin_slot_test_support.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <utility>

namespace hipair {
namespace {


// pi in [pi_lo, pi_hi]: its first 60 decimals, and one more unit in the last place
const Rational& pi_lo() {
  static const Rational value = Rational(mpz_class("3141592653589793238462643383279502884197169399375105820974944"),
                                         mpz_class("1000000000000000000000000000000000000000000000000000000000000"));
  return value;
}
const Rational& pi_hi() {
  static const Rational value = [] {
    Rational r = pi_lo() + pin_slot_test::exact_power10(-60);
    r.canonicalize();
    return r;
  }();
  return value;
}

using Bracket = std::pair<Rational, Rational>;

// atan(x) for |x| <= 1/3 in an exact bracket: partial sums of the alternating series, whose
// terms decrease, until a term is below 1e-45.
Bracket atan_small(const Rational& x) {
  Rational sum = 0, power = x, x2 = x * x;
  const Rational tiny = pin_slot_test::exact_power10(-45);
  for (long k = 0;; ++k) {
    Rational term = power / (2 * k + 1);
    term.canonicalize();
    Rational next = sum + (k % 2 == 0 ? term : Rational(-term));
    next.canonicalize();
    Rational magnitude = abs(term);
    if (magnitude < tiny) return sum < next ? Bracket{sum, next} : Bracket{next, sum};
    sum = next;
    power *= x2;
    power.canonicalize();
  }
}

// 2 atan(tau) in an exact bracket narrower than 1e-40 (for |tau| < 1e40).
Bracket psi_bracket(const Rational& tau) {
  if (abs(tau) <= Rational(1, 3)) {
    auto [a, b] = atan_small(tau);
    return {Rational(2 * a), Rational(2 * b)};
  }
  if (abs(tau) >= 3) {   // atan(tau) = sign(tau) pi / 2 - atan(1 / tau)
    Rational inverse = 1 / tau;
    inverse.canonicalize();
    auto [a, b] = atan_small(inverse);
    if (tau > 0) return {Rational(pi_lo() - 2 * b), Rational(pi_hi() - 2 * a)};
    return {Rational(-pi_hi() - 2 * b), Rational(-pi_lo() - 2 * a)};
  }
  // 1/3 < |tau| < 3: atan(tau) = s pi / 4 + atan(y), s = sign(tau), y = (tau - s) / (1 + s tau),
  // |y| < 1/2; and when |y| > 1/3, atan(y) = atan(+-1/3) + atan((y -+ 1/3) / (1 +- y / 3)), |.| <= 1/7
  Rational s = tau > 0 ? 1 : -1;
  Rational y = (tau - s) / (1 + s * tau);
  y.canonicalize();
  Rational quarter_lo = tau > 0 ? Rational(pi_lo() / 4) : Rational(-pi_hi() / 4);
  Rational quarter_hi = tau > 0 ? Rational(pi_hi() / 4) : Rational(-pi_lo() / 4);
  Rational shift_lo = 0, shift_hi = 0;
  if (abs(y) > Rational(1, 3)) {
    Rational third = y > 0 ? Rational(1, 3) : Rational(-1, 3);
    auto [a, b] = atan_small(third);
    shift_lo = a, shift_hi = b;
    y = (y - third) / (1 + y * third);
    y.canonicalize();
  }
  auto [a, b] = atan_small(y);
  return {Rational(2 * (quarter_lo + shift_lo + a)), Rational(2 * (quarter_hi + shift_hi + b))};
}

// A generated rational tangent of magnitude about 10^e, either sign.
Rational random_tangent(std::mt19937_64& random, int e) {
  // numerator and denominator in [1e9, 2e9): the quotient in (1/2, 2)
  mpz_class numerator(static_cast<unsigned long>(1000000000 + random() % 1000000000));
  mpz_class denominator(static_cast<unsigned long>(1000000000 + random() % 1000000000));
  Rational t = Rational(numerator, denominator) * pin_slot_test::exact_power10(e);
  t.canonicalize();
  if (random() % 2) t = -t;
  return t;
}

TEST(PinSlotAngleLimits, TheOracleBracketIsNarrowAndHoldsKnownAngles) {
  // the oracle itself: psi(1) = pi / 2, psi(-1) = -pi / 2, psi(0) = 0, narrow brackets
  auto one = psi_bracket(Rational(1));
  EXPECT_LE(one.first, Rational(pi_hi() / 2));
  EXPECT_GE(one.second, Rational(pi_lo() / 2));
  EXPECT_LT(Rational(one.second - one.first), pin_slot_test::exact_power10(-40));
  auto zero = psi_bracket(Rational(0));
  EXPECT_EQ(zero.first, 0);
  EXPECT_EQ(zero.second, 0);
  std::mt19937_64 random(53);
  for (int e = -25; e <= 25; e += 5) {
    Rational t = random_tangent(random, e);
    auto [a, b] = psi_bracket(t);
    EXPECT_LE(a, b);
    EXPECT_LT(Rational(b - a), pin_slot_test::exact_power10(-40)) << e;
    // and the double atan agrees to its own precision
    EXPECT_NEAR(to_double(a), 2 * std::atan(to_double(t)), 1e-12 * (1 + std::abs(to_double(a))));
  }
}

TEST(PinSlotAngleLimits, LimitsOneEMinus30RadAwayAreDecidedExactly) {
  std::mt19937_64 random(5302);
  const Rational delta = pin_slot_test::exact_power10(-30);
  int cases = 0;
  for (int round = 0; round < 12; ++round)
    for (int e = -25; e <= 25; ++e) {
      Rational tau = random_tangent(random, e);
      auto [a, b] = psi_bracket(tau);
      // whole turns: the same angle + 2 pi k against limits shifted by the bracket of 2 pi k
      for (long k : {0L, 1L, -1L, 3L}) {
        Rational turns_lo = k >= 0 ? Rational(2 * k * pi_lo()) : Rational(2 * k * pi_hi());
        Rational turns_hi = k >= 0 ? Rational(2 * k * pi_hi()) : Rational(2 * k * pi_lo());
        Rational below = a + turns_lo - delta, above = b + turns_hi + delta;   // psi + 2 pi k in (below, above)
        below.canonicalize();
        above.canonicalize();
        SCOPED_TRACE("tau = " + to_exact_string(tau) + ", k = " + std::to_string(k));
        // just inside: a limit 1e-30 below and one 1e-30 above
        EXPECT_TRUE(angle_within_limits(tau, below, above));
        EXPECT_TRUE(angle_within_limits(tau, below, Rational(above + 1)));
        EXPECT_TRUE(angle_within_limits(tau, Rational(below - 1), above));
        // just outside: the whole interval 1e-30 above psi, or 1e-30 below it (less than a turn wide)
        EXPECT_FALSE(angle_within_limits(tau, above, Rational(above + 3)));
        EXPECT_FALSE(angle_within_limits(tau, Rational(below - 3), below));
        // the signs themselves
        mpz_class m(2 * k);
        EXPECT_EQ(angle_sign(tau, m, below), 1);
        EXPECT_EQ(angle_sign(tau, m, above), -1);
        ++cases;
      }
    }
  EXPECT_EQ(cases, 12 * 51 * 4);
}

TEST(PinSlotAngleLimits, TiesAndWholeTurns) {
  // psi = 0 at tau = 0: a limit at exactly 0 is attained (the limits are closed)
  EXPECT_EQ(angle_sign(Rational(0), mpz_class(0), Rational(0)), 0);
  EXPECT_TRUE(angle_within_limits(Rational(0), Rational(0), Rational(1)));
  EXPECT_TRUE(angle_within_limits(Rational(0), Rational(-1), Rational(0)));
  EXPECT_FALSE(angle_within_limits(Rational(0), pin_slot_test::exact_power10(-30), Rational(1)));
  EXPECT_FALSE(angle_within_limits(Rational(0), Rational(-1), Rational(-pin_slot_test::exact_power10(-30))));
  // tiny tangents: psi = 2 tau - ... is decided at 1e-300 too
  Rational tiny = pin_slot_test::exact_power10(-300);
  EXPECT_TRUE(angle_within_limits(tiny, Rational(0), Rational(2 * tiny)));
  EXPECT_FALSE(angle_within_limits(tiny, Rational(2 * tiny), Rational(1)));   // psi < 2 tau
  EXPECT_FALSE(angle_within_limits(Rational(-tiny), Rational(0), Rational(1)));
  // a whole turn: 2 pi against rational widths 1e-50 apart from it
  EXPECT_TRUE(at_least_whole_turn(Rational(2 * pi_hi())));
  EXPECT_FALSE(at_least_whole_turn(Rational(2 * pi_lo())));
  EXPECT_TRUE(at_least_whole_turn(pin_slot_test::exact_power10(400)));
  // 1e400 rad: whole turns are reduced exactly (psi(1) = pi/2 against pi/2 + 2 pi k, k huge,
  // is out of reach of the oracle; the reduction is checked against the same angle at k = 0)
  EXPECT_TRUE(angle_within_limits(Rational(1), Rational(-pin_slot_test::exact_power10(400)), pin_slot_test::exact_power10(400)));
}

// A bar on a pin-slot motion against a fixed block (BadPairsAreRefusedWithAMessage's pair)
Model bar_and_block(const std::string& angle_limits, const std::string& initial_angle = "0") {
  return read_model(R"({ "hipair": 1, "name": "limits", "units": { "length": "mm", "angle": "deg" }, "parts": [
    { "name": "a", "motion": "fixed", "loops": [ { "start": [30, 0], "edges": [
      { "line_to": [34, 0] }, { "line_to": [34, 4] }, { "line_to": [30, 4] }, { "line_to": [30, 0] } ] } ] },
    { "name": "b", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": )" +
                    angle_limits + R"(, "limits": [-2, 2] } },
      "initial": { "angle": )" + initial_angle + R"( },
      "loops": [ { "start": [0, 0], "edges": [ { "line_to": [10, 0] }, { "line_to": [10, 2] }, { "line_to": [0, 2] },
      { "line_to": [0, 0] } ] } ] } ] })");
}

// The reader takes a pin-slot part's initial angle modulo whole turns, as its angle limits and
// PinSlotSpace::locate do (session 54): generated limits [lo, hi] (whole degrees, narrower than a
// turn) and initial angles a + 360 k deg, k from -10^6 to 10^6, against the oracle in whole
// degrees ((a - lo) mod 360 <= hi - lo); an angle at a limit plus whole turns is inside whichever
// way the reader rounded the three values; limits of a whole turn take any angle. Before, 370 deg
// against [-20, 20] deg was refused ("outside the motion's angle limits").
TEST(PinSlotAngleLimits, TheInitialAngleIsTakenModuloWholeTurns) {
  auto accepted = [](const std::string& limits, const std::string& angle) {
    try {
      Model model = bar_and_block(limits, angle);
      return true;
    } catch (const ModelError& e) {
      EXPECT_EQ(e.pointer(), "/parts/1/initial/angle") << e.what();
      EXPECT_NE(std::string(e.what()).find("modulo 360 deg"), std::string::npos) << e.what();
      return false;
    }
  };
  EXPECT_TRUE(accepted("[-20, 20]", "370"));
  EXPECT_TRUE(accepted("[-20, 20]", "-350"));
  EXPECT_FALSE(accepted("[-20, 20]", "390"));
  EXPECT_TRUE(accepted("[330, 390]", "0"));
  EXPECT_TRUE(accepted("[-180, 180]", "\"1e6 + 179.5\""));   // a whole turn: any angle
  std::mt19937_64 random(5401);
  std::uniform_int_distribution<long> lower(-400, 400), width(1, 300), turns(-12, 12);
  const long far_turns[] = {-1000000, -1000, 1000, 1000000};
  int inside = 0, outside = 0, at_limit = 0;
  for (int round = 0; round < 60; ++round) {
    const long lo = lower(random), hi = lo + width(random);
    const std::string limits = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    std::uniform_int_distribution<long> offset(0, 359);
    long a = lo + offset(random);   // an angle of the turn from lo
    if (round % 5 == 0) a = round % 10 == 0 ? lo : hi;   // at a limit
    const long k = round % 4 == 3 ? far_turns[(round / 4) % 4] : turns(random);
    const long written = a + 360 * k;
    const bool expected = ((a - lo) % 360 + 360) % 360 <= hi - lo;
    SCOPED_TRACE(limits + " at " + std::to_string(written) + " deg");
    EXPECT_EQ(accepted(limits, std::to_string(written)), expected);
    // the same angle and whole turns written as an expression (rounded once, as one value)
    EXPECT_EQ(accepted(limits, "\"" + std::to_string(a) + " + 360 * (" + std::to_string(k) + ")\""), expected);
    (expected ? (a == lo || a == hi ? at_limit : inside) : outside) += 1;
  }
  EXPECT_GT(inside, 5);
  EXPECT_GT(outside, 5);
  EXPECT_GT(at_limit, 5);
  // a rotating part's limits are not angles modulo whole turns: 370 deg against [-20, 20] deg is refused
  EXPECT_THROW(read_model(R"({ "hipair": 1, "name": "r", "units": { "length": "mm", "angle": "deg" }, "parts": [
    { "name": "b", "motion": { "rotation": { "pivot": [0, 0], "limits": [-20, 20] } }, "initial": { "angle": 370 },
      "loops": [ { "start": [0, 0], "edges": [ { "line_to": [10, 0] }, { "line_to": [10, 2] }, { "line_to": [0, 0] } ] } ] } ] })"),
               ModelError);
}

TEST(PinSlotAngleLimits, LocateAtALimitOneEMinus30Away) {
  Model model = bar_and_block("[-30, 30]");
  std::mt19937_64 random(5303);
  PinSlotBuildOptions lazy;
  lazy.stack = false;
  const Rational delta = pin_slot_test::exact_power10(-30);
  for (int round = 0; round < 8; ++round) {
    Rational tau = random_tangent(random, -1 - round % 3);   // |psi| up to about 0.2 rad
    auto [a, b] = psi_bracket(tau);
    for (bool upper : {true, false}) {
      // the limit 1e-30 beyond psi (inside) or short of it (outside), the other limit far
      Model m = model;
      Rational inside = upper ? Rational(b + delta) : Rational(a - delta);
      Rational outside = upper ? Rational(a - delta) : Rational(b + delta);
      for (bool in : {true, false}) {
        Rational limit = in ? inside : outside;
        limit.canonicalize();
        m.parts[1].motion.angle_limits =
            upper ? RationalInterval{Rational(-1), limit} : RationalInterval{limit, Rational(1)};
        PinSlotSpace space = PinSlotSpace::build(m, "a", "b", lazy);
        for (const Rational& slide : {Rational(0), Rational(3, 2)}) {
          PinSlotLocation at = space.locate(PinSlotConfiguration{{}, slide, tau});
          SCOPED_TRACE("tau = " + to_exact_string(tau) + (upper ? ", upper" : ", lower") + (in ? " inside" : " outside"));
          if (!in) {
            EXPECT_EQ(at.kind, PinSlotLocation::Kind::outside);
            continue;
          }
          // inside: the exact overlap oracle
          const Part& other = m.parts[0];
          const Part& pin = m.parts[1];
          PartOverlap o = part_overlap(other, Placement{}, pin, pin_slot_placement(pin, slide, tau));
          PinSlotLocation::Kind expected = o.relation == PartRelation::apart      ? PinSlotLocation::Kind::free
                                           : o.relation == PartRelation::touching ? PinSlotLocation::Kind::contact
                                                                                  : PinSlotLocation::Kind::blocked;
          EXPECT_EQ(at.kind, expected);
        }
      }
    }
  }
}

TEST(PinSlotAngleLimits, LimitsBeyondAHalfTurnAreTheAnglesModuloWholeTurns) {
  // [330, 390] deg is [-30, 30] deg: the same slices, and a configuration at -20 deg inside
  PinSlotBuildOptions options;
  options.slices = 4;
  options.refine_steps = 0;
  options.connections = false;
  PinSlotSpace shifted = PinSlotSpace::build(bar_and_block("[330, 390]", "360"), "a", "b", options);
  PinSlotSpace plain = PinSlotSpace::build(bar_and_block("[-30, 30]"), "a", "b", options);
  ASSERT_EQ(shifted.slices().size(), plain.slices().size());
  for (std::size_t k = 0; k < plain.slices().size(); ++k) EXPECT_EQ(shifted.slices()[k].tau, plain.slices()[k].tau);
  Rational tau_minus_20 = Rational(-176, 1000);   // tan(-10 deg) = -0.1763
  EXPECT_NE(shifted.locate(PinSlotConfiguration{{}, Rational(0), tau_minus_20}).kind, PinSlotLocation::Kind::outside);
  EXPECT_EQ(shifted.locate(PinSlotConfiguration{{}, Rational(0), Rational(1, 2)}).kind,
            PinSlotLocation::Kind::outside);   // 53 deg
  // [150, 200] deg crosses the half turn: refused, naming the field
  try {
    PinSlotSpace::build(bar_and_block("[150, 200]", "170"), "a", "b", options);
    FAIL() << "limits across the half turn were accepted";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("angle_limits"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/parts/1/motion"), std::string::npos) << e.what();
  }
}

TEST(PinSlotAngleLimits, AWholeTurnOrMoreIsTheWholeTurn) {
  // [-180, 180] deg (pi rounded by the reader either way), [0, 360] deg and +-1e400 deg are the
  // whole turn: the stack of no limits, with the connection across the half turn
  PinSlotBuildOptions options;
  options.slices = 4;
  options.refine_steps = 0;
  PinSlotSpace none = PinSlotSpace::build(
      read_model(R"({ "hipair": 1, "name": "limits", "parts": [
        { "name": "a", "motion": "fixed", "loops": [ { "start": [30, 0], "edges": [
          { "line_to": [34, 0] }, { "line_to": [34, 4] }, { "line_to": [30, 4] }, { "line_to": [30, 0] } ] } ] },
        { "name": "b", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "limits": [-2, 2] } },
          "loops": [ { "start": [0, 0], "edges": [ { "line_to": [10, 0] }, { "line_to": [10, 2] }, { "line_to": [0, 2] },
          { "line_to": [0, 0] } ] } ] } ] })"),
      "a", "b", options);
  for (const char* limits : {"[-180, 180]", "[0, 360]", "[-1e400, 1e400]", "[-90, 1e400]"}) {
    SCOPED_TRACE(limits);
    auto start = std::chrono::steady_clock::now();
    PinSlotSpace space = PinSlotSpace::build(bar_and_block(limits), "a", "b", options);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
    ASSERT_EQ(space.slices().size(), none.slices().size());
    for (std::size_t k = 0; k < none.slices().size(); ++k) EXPECT_EQ(space.slices()[k].tau, none.slices()[k].tau);
    EXPECT_EQ(space.connections().size(), none.connections().size());
    EXPECT_EQ(space.groups(), none.groups());
    // psi near +-pi is inside
    EXPECT_NE(space.locate(PinSlotConfiguration{{}, Rational(0), Rational(1000000)}).kind, PinSlotLocation::Kind::outside);
  }
  // limits 1e-60 short of a whole turn are the whole turn when the reader rounded them by more
  // (its Rounding records at the limits' pointers), not otherwise
  Model near = bar_and_block("[-30, 30]");
  near.parts[1].motion.angle_limits = RationalInterval{Rational(-pi_lo()), pi_lo()};
  near.roundings.clear();   // the records of [-30, 30] deg's rounding
  PinSlotSpace strict = PinSlotSpace::build(near, "a", "b", options);
  EXPECT_EQ(strict.locate(PinSlotConfiguration{{}, Rational(0), pin_slot_test::exact_power10(70)}).kind, PinSlotLocation::Kind::outside);
  for (const char* end : {"0", "1"})
    near.roundings.push_back(Rounding{"/parts/1/motion/pin_slot/angle_limits/" + std::string(end), "180", pi_lo(), pin_slot_test::exact_power10(-59)});
  PinSlotSpace rounded = PinSlotSpace::build(near, "a", "b", options);
  EXPECT_NE(rounded.locate(PinSlotConfiguration{{}, Rational(0), pin_slot_test::exact_power10(70)}).kind, PinSlotLocation::Kind::outside);
  EXPECT_EQ(rounded.connections().size(), none.connections().size());
  // just short of a whole turn (359.999 deg): not the whole turn; psi = 180 - 0.0001 deg is outside
  PinSlotSpace short_turn = PinSlotSpace::build(bar_and_block("[-179.9995, 179.9995]"), "a", "b", options);
  EXPECT_EQ(short_turn.locate(PinSlotConfiguration{{}, Rational(0), Rational(2000000)}).kind,
            PinSlotLocation::Kind::outside);   // 2 atan(2e6) = 179.99994 deg
  EXPECT_NE(short_turn.locate(PinSlotConfiguration{{}, Rational(0), Rational(100000)}).kind,
            PinSlotLocation::Kind::outside);   // 179.9989 deg
}

// A stack wider than 30 deg searches its critical values in pieces between sample slices
// (src/pinslot/pin_slot_space.cpp; session 53: the film advance's film pair over a whole turn,
// minutes in one piece): the values are those of one search over the whole range, exactly.
TEST(PinSlotAngleLimits, CriticalValuesInPiecesAreThoseOfOneSearch) {
  for (const char* limits : {"[-60, 60]", "[-170, 170]", "[-180, 180]", "[-1e400, 1e400]"}) {
    SCOPED_TRACE(limits);
    Model model = read_model(std::string(R"({ "hipair": 1, "name": "bar-wall", "units": { "length": "mm", "angle": "deg" },
      "parts": [
      { "name": "wall", "motion": "fixed", "loops": [ { "start": [12, -20], "edges": [ { "line_to": [20, -20] },
        { "line_to": [20, 20] }, { "line_to": [12, 20] }, { "line_to": [12, -20] } ] } ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": )") + limits + R"(,
        "limits": [-5, 5] } }, "loops": [ { "start": [0, -1], "edges": [ { "line_to": [10, -1] }, { "line_to": [10, 1] },
        { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] } ],
      "pairs": [ { "parts": ["wall", "bar"] } ] })");
    PinSlotBuildOptions options;
    options.connections = false;
    PinSlotSpace space = PinSlotSpace::build(model, "wall", "bar", options);
    ASSERT_TRUE(space.critical_values_exact());
    sliced::CriticalStatistics statistics;
    std::vector<cspace::algebra::Real> one;
    for (auto& c : sliced::pin_slot_critical_values(model.parts[0], model.parts[1], Rational(-5), Rational(5), std::nullopt,
                                                    std::make_pair(space.tau_lower(), space.tau_upper()), statistics))
      if (!c.half_turn && c.t.compare(space.tau_lower()) > 0 && c.t.compare(space.tau_upper()) < 0) one.push_back(c.t);
    ASSERT_EQ(space.critical_values().size(), one.size());
    for (std::size_t k = 0; k < one.size(); ++k)
      EXPECT_EQ(cspace::algebra::compare(sliced::real_of(space.critical_values()[k].tau), one[k]), 0) << k;
    // the wall's three (the slide's end on the wall at 27 t^2 -+ 2 t - 3 = 0, and t = 0) at least
    EXPECT_GE(one.size(), 3u);
  }
}

// ------------------------------------------------------------------ across the half turn
// A whole-turn stack is a cycle: the critical values between its last and first slices (the
// gap across psi = +-180 deg, which no search in tau = tan(psi/2) reaches) are found in the chart
// about the half turn, u = -1/tau (session 54; before, the gap was left out while the values were
// claimed complete). The oracle scans the slices by brute force: 1-D slices (exact C-spaces in
// the slide) at rational tau across the gap and the whole turn; two consecutive scanned slices
// whose structure differs must have a listed critical value between them (cyclically), and every
// interval between cyclically consecutive values must hold a slice of the stack.


// A bar [0, 10] x [-1, 1] turning (a whole turn) about (0, 0) and sliding along itself by s in
// [-5, 5], against a wall x <= -`wall` (|y| <= 20): behind the pivot, so the bar meets it near
// psi = 180 deg. Its far corners reach (10 + s) cos psi' + |sin psi'| behind the pivot (psi =
// 180 deg + psi').
Model bar_behind_wall(const std::string& wall) {
  return read_model(R"({ "hipair": 1, "name": "bar-wall behind", "units": { "length": "mm", "angle": "deg" },
    "parts": [
    { "name": "wall", "motion": "fixed", "loops": [ { "start": [-20, -20], "edges": [ { "line_to": [)" + wall + R"(, -20] },
      { "line_to": [)" + wall + R"(, 20] }, { "line_to": [-20, 20] }, { "line_to": [-20, -20] } ] } ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "limits": [-5, 5] } },
      "loops": [ { "start": [0, -1], "edges": [ { "line_to": [10, -1] }, { "line_to": [10, 1] },
      { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] } ],
    "pairs": [ { "parts": ["wall", "bar"] } ] })");
}

int algebra_compare(const PinSlotCritical& a, const PinSlotCritical& b) {
  return cspace::algebra::compare(sliced::real_of(a.tau), sliced::real_of(b.tau));
}

// Is a listed critical value between scanned slices a and b, going counter-clockwise from a
// (a > b: across the half turn)?
bool critical_between(const PinSlotSpace& space, const Rational& a, const Rational& b) {
  for (const PinSlotCritical& c : space.critical_values()) {
    if (c.half_turn) {
      if (a > b) return true;
      continue;
    }
    const cspace::algebra::Real t = sliced::real_of(c.tau);
    if (a < b ? t.compare(a) > 0 && t.compare(b) < 0 : t.compare(a) > 0 || t.compare(b) < 0) return true;
  }
  return false;
}

// The brute-force scan: `count` slices at rational u = -1/tau evenly across the gap beyond the
// stack's first slices (and `count` more over the rest of the turn); returns the number of
// structure changes seen. Every change has a critical value between its two slices, and every
// interval between cyclically consecutive critical values holds a slice of the stack.
int scan_whole_turn(const PinSlotSpace& space, const Rational& u_lo, const Rational& u_hi, int count, int main_count = -1) {
  std::vector<Rational> taus;
  if (main_count < 0) main_count = count;
  for (int k = 0; k <= main_count && main_count > 0; ++k) {   // psi from -180 + ... to 180 - ...: tau = tan(psi / 2)
    double psi = -std::numbers::pi + (2 * std::numbers::pi) * (k + 0.5) / (main_count + 1);
    Rational t(static_cast<long>(std::llround(std::tan(psi / 2) * 65536)), 65536);
    t.canonicalize();
    if (t > Rational(-1) / u_hi && t < Rational(-1) / u_lo && (taus.empty() || t > taus.back())) taus.push_back(t);
  }
  std::vector<Rational> above, below;   // the gap: u in (u_lo, 0) is tau > -1/u_lo, u in (0, u_hi) tau < -1/u_hi
  for (int k = 1; k < count; ++k) {
    Rational u = u_lo + (u_hi - u_lo) * Rational(k, count);
    u.canonicalize();
    if (sgn(u) == 0) continue;
    Rational t = Rational(-1) / u;
    t.canonicalize();
    (sgn(u) < 0 ? above : below).push_back(t);
  }
  std::vector<Rational> cycle = below;   // ascending tau: below the stack, the stack, above it
  cycle.insert(cycle.end(), taus.begin(), taus.end());
  cycle.insert(cycle.end(), above.begin(), above.end());
  std::vector<std::string> seen;
  for (const Rational& t : cycle) seen.push_back(pin_slot_test::free_structure(*space.slice(t)));
  int changes = 0;
  for (std::size_t k = 0; k < cycle.size(); ++k) {
    std::size_t next = (k + 1) % cycle.size();
    if (seen[k] == seen[next]) continue;
    ++changes;
    EXPECT_TRUE(critical_between(space, cycle[k], cycle[next]))
        << "slices at tau " << cycle[k].get_str() << " and " << cycle[next].get_str() << " differ with no critical value between: "
        << seen[k] << " | " << seen[next];
  }
  // a slice of the stack in every interval between cyclically consecutive critical values
  const auto& critical = space.critical_values();
  const auto& slices = space.slices();
  for (std::size_t k = 0; k < critical.size(); ++k) {
    const PinSlotCritical& a = critical[k];
    const PinSlotCritical& b = critical[(k + 1) % critical.size()];
    bool has = false;
    for (const PinSlotSlice& s : slices) {
      if (a.half_turn) has = has || sliced::real_of(b.tau).compare(s.tau) > 0;        // (-inf, b)
      else if (b.half_turn) has = has || sliced::real_of(a.tau).compare(s.tau) < 0;   // (a, +inf)
      else {
        bool after_a = sliced::real_of(a.tau).compare(s.tau) < 0, before_b = sliced::real_of(b.tau).compare(s.tau) > 0;
        has = has || (algebra_compare(a, b) < 0 ? after_a && before_b : after_a || before_b);   // across the half turn
      }
    }
    EXPECT_TRUE(has) << "no slice between critical values " << k << " and " << (k + 1) % critical.size();
  }
  return changes;
}

TEST(PinSlotAngleLimits, CriticalValuesAcrossTheHalfTurnAreFound) {
  // wall at x = -15.02: the slide's end s = 5 meets it where 15 cos psi' + |sin psi'| = 15.02,
  // |psi'| = atan(1/15) -+ acos(15.02 / sqrt 226) (1.404 and 6.224 deg): four critical values
  // within 7 deg of 180, inside the gap (168.75, 191.25) deg between the 16 slices' last and first
  PinSlotBuildOptions options;
  options.connections = false;
  Model model = bar_behind_wall("-15.02");
  PinSlotSpace space = PinSlotSpace::build(model, "wall", "bar", options);
  ASSERT_TRUE(space.critical_values_exact());
  const double phi = std::atan(1.0 / 15), delta = std::acos(15.02 / std::sqrt(226.0));
  std::vector<double> expected;   // degrees in (-180, 180]
  for (double psi : {phi - delta, phi + delta}) {
    expected.push_back(180 - psi * 180 / std::numbers::pi);
    expected.push_back(-180 + psi * 180 / std::numbers::pi);
  }
  std::string listing;
  for (const auto& c : space.critical_values()) listing += std::to_string(c.degrees) + (c.half_turn ? " (half turn)" : "") + "\n";
  for (double e : expected) {
    bool found = false;
    for (const auto& c : space.critical_values())
      if (!c.half_turn && std::abs(c.degrees - e) < 1e-6) found = true;
    EXPECT_TRUE(found) << e << " deg not listed:\n" << listing;
  }
  // the stack reaches into the gap: slices between the values there (180 - 6.224 ... 180 -
  // 1.404 deg, 180 - 1.404 ... -180 + 1.404 across the half turn, -180 + 1.404 ... -180 + 6.224)
  EXPECT_GT(space.slices().back().degrees, 180 - 6.2);
  EXPECT_LT(space.slices().front().degrees, -180 + 6.2);
  // the gap of the 16 slices: u = -1/tau within tan(11.25 deg / 2) of 0
  const Rational gap(1, 8);
  EXPECT_GE(scan_whole_turn(space, Rational(-gap), gap, 240), 4);
}

// The film advance with its follower turning a whole turn (no angle limits): the film pair's
// critical values across the half turn, against 2-D slices scanned across the gap.
TEST(PinSlotAngleLimits, FilmAdvanceWholeTurnAcrossTheHalfTurn) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  for (Part& part : model.parts)
    if (part.name == "follower") part.motion.angle_limits.reset();
  PinSlotBuildOptions options;
  options.connections = false;
  PinSlotSpace space = PinSlotSpace::build(model, "film", "follower", options);
  ASSERT_TRUE(space.critical_values_exact());
  EXPECT_GE(space.critical_values().size(), 22u);
  // the 16 slices' gap: |u| < tan(11.25 deg / 2) < 1/10 (40 slices across it, none elsewhere)
  scan_whole_turn(space, Rational(-1, 10), Rational(1, 10), 40, 0);
}

TEST(PinSlotAngleLimits, TheHalfTurnItselfIsACriticalValue) {
  // wall at x = -12 (the wall of BarAgainstAWallHasThreeCriticalValues, behind the pivot): the
  // end edge is parallel to it at psi = 180 deg, where the touching corner changes
  PinSlotBuildOptions options;
  options.connections = false;
  PinSlotSpace space = PinSlotSpace::build(bar_behind_wall("-12"), "wall", "bar", options);
  ASSERT_TRUE(space.critical_values_exact());
  ASSERT_FALSE(space.critical_values().empty());
  EXPECT_TRUE(space.critical_values().back().half_turn);
  EXPECT_EQ(space.critical_values().back().degrees, 180);
  // slices on both sides of the half turn, between it and the values at 180 -+ 40.9 deg
  EXPECT_GT(space.slices().back().degrees, 139.2);
  EXPECT_LT(space.slices().front().degrees, -139.2);
  EXPECT_GE(scan_whole_turn(space, Rational(-1, 8), Rational(1, 8), 180), 3);
}

// ------------------------------------------------------------------ rotating parts' charts
// A rotating part's angle limits [lo, hi] (rad) choose its charts (src/curves/contact_curves.cpp,
// limited_rotation_charts): the chart about c = centre pi for each whole turn k whose local range
// [lo, hi] - m pi (m = 2 k + centre) meets [-pi/2, pi/2], its edges the tangents of the local
// range's ends rounded outward to the 10^-12 grid (+-1 when the range passes the seam). Before
// session 54 every comparison was made in MPFR at 256 bits: limits within 2^-250 of a seam
// (m pi +- pi/2) or of a whole turn could be misjudged, and limits beyond 2^200 rad were reduced
// by garbage. The oracle: pi as an exact rational bracket narrower than 10^-digits (Machin's
// formula, the alternating atan series), the comparisons decided on it (and refused when it
// cannot decide them), the edges checked tight with psi_bracket.

// atan(x), 0 < x <= 1/3, in an exact bracket narrower than 10^-digits.
Bracket atan_series(const Rational& x, int digits) {
  Rational sum = 0, power = x, x2 = x * x;
  const Rational tiny = pin_slot_test::exact_power10(-digits);
  for (long k = 0;; ++k) {
    Rational term = power / (2 * k + 1);
    term.canonicalize();
    Rational next = sum + (k % 2 == 0 ? term : Rational(-term));
    next.canonicalize();
    if (abs(term) < tiny) return sum < next ? Bracket{sum, next} : Bracket{next, sum};
    sum = next;
    power *= x2;
    power.canonicalize();
  }
}

// pi = 16 atan(1/5) - 4 atan(1/239), in an exact bracket narrower than about 10^-digits.
Bracket pi_bracket(int digits) {
  auto [a_lo, a_hi] = atan_series(Rational(1, 5), digits + 2);
  auto [b_lo, b_hi] = atan_series(Rational(1, 239), digits + 2);
  Rational lo = 16 * a_lo - 4 * b_hi, hi = 16 * a_hi - 4 * b_lo;
  lo.canonicalize();
  hi.canonicalize();
  return {lo, hi};
}

// The sign of L - q pi (q rational) on the bracket; 0 when the bracket cannot decide it.
int sign_on(const Rational& L, const Rational& q, const Bracket& pi) {
  Rational a = L - q * (sgn(q) >= 0 ? pi.second : pi.first), b = L - q * (sgn(q) >= 0 ? pi.first : pi.second);
  if (sgn(a) > 0) return 1;
  if (sgn(b) < 0) return -1;
  return 0;
}

// The charts of a rotating part with limits [lo, hi] (rad), as chart_layout gives them.
Model arm_model(const Rational& lo, const Rational& hi) {
  static const Model base = read_model(R"({ "hipair": 1, "name": "charts", "units": { "length": "mm", "angle": "rad" },
    "parts": [
    { "name": "arm", "motion": { "rotation": { "pivot": [0, 0], "limits": [-1, 1] } }, "loops": [ { "start": [0, -1],
      "edges": [ { "line_to": [10, -1] }, { "line_to": [10, 1] }, { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] },
    { "name": "block", "motion": "fixed", "loops": [ { "start": [20, 0], "edges": [ { "line_to": [24, 0] },
      { "line_to": [24, 4] }, { "line_to": [20, 4] }, { "line_to": [20, 0] } ] } ] } ] })");
  Model model = base;
  model.parts[0].motion.angle_limits = RationalInterval{lo, hi};
  return model;
}

std::vector<cspace::ChartAxis> charts_for(const Rational& lo, const Rational& hi) {
  Model model = arm_model(lo, hi);
  return cspace::chart_layout(model, cspace::pair_axes(model, 0, 1)).x_charts;
}

// Checks charts_for(lo, hi) against the oracle (`pi`: a bracket narrow enough for the limits).
void expect_charts(const Rational& lo, const Rational& hi, const Bracket& pi, const std::string& what) {
  SCOPED_TRACE(what);
  std::vector<cspace::ChartAxis> charts = charts_for(lo, hi);
  const int whole = sign_on(Rational(hi - lo), Rational(2), pi);   // hi - lo - 2 pi
  ASSERT_NE(whole, 0) << "the oracle's pi is too coarse";
  if (whole > 0) {   // a whole turn: the two full charts
    ASSERT_EQ(charts.size(), 2u);
    for (const auto& c : charts) EXPECT_TRUE(c.lo == -1 && c.hi == 1);
    return;
  }
  // expected charts, in the code's order (centre 0 then the half turn, turns ascending)
  const Rational turns = lo / (2 * pi.first);
  mpz_class k0 = turns.get_num() / turns.get_den();   // truncated: within 1 of the turns
  std::size_t next = 0;
  const Rational grid(3, 1000000000000);   // the edge within 3 grid steps of the exact one
  for (int centre = 0; centre < 2; ++centre)
    for (mpz_class k = k0 - 3; k <= k0 + 3; ++k) {
      const mpz_class m = 2 * k + centre;
      const Rational below(Rational(m) - Rational(1, 2)), above(Rational(m) + Rational(1, 2));
      const int hi_below = sign_on(hi, below, pi), lo_above = sign_on(lo, above, pi);   // hi - (m - 1/2) pi, lo - (m + 1/2) pi
      ASSERT_TRUE(hi_below != 0 && lo_above != 0) << "the oracle's pi is too coarse";
      if (hi_below < 0 || lo_above > 0) continue;   // the range misses this chart
      ASSERT_LT(next, charts.size()) << "chart m = " << m.get_str() << " missing";
      const cspace::ChartAxis& c = charts[next++];
      EXPECT_EQ(c.half_turn, centre == 1) << m.get_str();
      const int lo_below = sign_on(lo, below, pi), hi_above = sign_on(hi, above, pi);
      ASSERT_TRUE(lo_below != 0 && hi_above != 0) << "the oracle's pi is too coarse";
      // the local range's ends L - m pi against the edges' angles 2 atan(edge) (m pi bracketed)
      auto local = [&](const Rational& L) {
        return Bracket{Rational(L - m * (sgn(m) >= 0 ? pi.second : pi.first)), Rational(L - m * (sgn(m) >= 0 ? pi.first : pi.second))};
      };
      if (lo_below <= 0) {
        EXPECT_EQ(c.lo, -1) << m.get_str();
      } else {
        const Bracket end = local(lo);
        // (an edge clamped to -1 is 2 atan(-1) = -pi/2, below the local end as decided above)
        if (c.lo > -1) EXPECT_LT(psi_bracket(c.lo).second, end.first) << "lower edge not below the limit, m = " << m.get_str();
        if (c.lo > -1) {
          EXPECT_GT(psi_bracket(Rational(c.lo + grid)).first, end.second) << "lower edge not tight, m = " << m.get_str();
        }
      }
      if (hi_above >= 0) {
        EXPECT_EQ(c.hi, 1) << m.get_str();
      } else {
        const Bracket end = local(hi);
        if (c.hi < 1) EXPECT_GT(psi_bracket(c.hi).first, end.second) << "upper edge not above the limit, m = " << m.get_str();
        if (c.hi < 1) {
          EXPECT_LT(psi_bracket(Rational(c.hi - grid)).second, end.first) << "upper edge not tight, m = " << m.get_str();
        }
      }
    }
  EXPECT_EQ(next, charts.size()) << "extra charts";
}

TEST(RotationChartLimits, TheOraclePiIsPi) {
  const Bracket pi = pi_bracket(120);
  EXPECT_LT(Rational(pi.second - pi.first), pin_slot_test::exact_power10(-118));
  EXPECT_LE(pi.first, pi_hi());
  EXPECT_GE(pi.second, pi_lo());
}

TEST(RotationChartLimits, OrdinaryAndHugeLimitsGiveTheExactCharts) {
  std::mt19937_64 random(54);
  const Bracket pi = pi_bracket(500);
  for (int round = 0; round < 60; ++round) {
    // magnitudes 1 ... 10^400 rad, widths 0.01 ... 6.2 rad
    const int e = round < 20 ? 0 : round < 40 ? 20 * (round - 19) : 100 + 15 * (round - 40);
    Rational lo = random_tangent(random, e);
    Rational width(static_cast<long>(1 + random() % 620), 100);
    Rational hi = lo + width;
    hi.canonicalize();
    expect_charts(lo, hi, pi, "limits 10^" + std::to_string(e) + " rad, width " + width.get_str());
  }
}

TEST(RotationChartLimits, TiesAtSeamsAndWholeTurnsAreDecidedExactly) {
  const Bracket pi = pi_bracket(200);
  const Rational& p = pi.first;   // within 10^-200 of pi
  for (int e : {30, 80, 150}) {
    const Rational d = pin_slot_test::exact_power10(-e);
    for (int j = -5; j <= 5; ++j) {
      for (int side : {-1, 1}) {
        // a limit 10^-e from the seam or chart centre j pi / 2 (odd j: a seam between charts)
        Rational L = Rational(j) * p / 2 + side * d;
        L.canonicalize();
        std::string what = "j = " + std::to_string(j) + ", 10^-" + std::to_string(e) + (side < 0 ? " below" : " above");
        expect_charts(L, Rational(L + Rational(1, 2)), pi, what + " (lower limit)");
        expect_charts(Rational(L - Rational(1, 2)), L, pi, what + " (upper limit)");
      }
    }
    // a width 10^-e short of or beyond a whole turn
    for (int side : {-1, 1}) {
      Rational lo(1, 3), hi = lo + 2 * p + side * d;
      hi.canonicalize();
      expect_charts(lo, hi, pi, "whole turn " + std::string(side < 0 ? "- " : "+ ") + "10^-" + std::to_string(e));
    }
  }
  // limits whose half-angle tangent is rational (0): the edge one grid step out of 0
  for (const auto& [lo, hi] : {std::pair<Rational, Rational>{Rational(0), Rational(1)}, {Rational(-1), Rational(0)}}) {
    std::vector<cspace::ChartAxis> charts = charts_for(lo, hi);
    ASSERT_EQ(charts.size(), 1u);
    if (sgn(lo) == 0) {
      EXPECT_EQ(charts[0].lo, Rational(-1, 1000000000000));
    } else {
      EXPECT_EQ(charts[0].hi, Rational(1, 1000000000000));
    }
    expect_charts(lo, hi, pi, "a limit at 0");
  }
}

// ------------------------------------------------------------------ session 55
// A pin-slot part's limits are the whole turn when they span it allowing for the reader's
// rounding of the two (core/angle_limits.hpp, pin_slot_whole_turn): the one decision of
// PinSlotSpace::build and pin_slot_cycle (before session 55 the cycle left the rounding out and
// took limits the stack called a whole turn for narrower ones). Widths 10^-30 ... 10^-150 from
// 2 pi, either side, decided against the oracle's pi (Machin, 10^-200), with rounding records
// at the limits of 10^-e each (the short width becomes a whole turn), of 10^-e / 8 each (it
// stays short) and at other fields (nothing).
TEST(PinSlotAngleLimits, TheWholeTurnIsOneExactDecisionAtTies) {
  const Bracket pi = pi_bracket(200);
  std::mt19937_64 random(5501);
  Motion motion;
  motion.kind = Motion::Kind::pin_slot;
  motion.pointer = "/parts/1/motion";
  EXPECT_TRUE(pin_slot_whole_turn({}, motion));   // no limits
  const std::string at = "/parts/1/motion/pin_slot/angle_limits/";
  for (int e : {30, 60, 100, 150}) {
    const Rational d = pin_slot_test::exact_power10(-e);
    for (int side : {-1, 1}) {
      Rational lo(static_cast<long>(random() % 8001) - 4000, 1000);
      lo.canonicalize();
      Rational hi = lo + 2 * (side < 0 ? pi.first : pi.second) + side * d;   // hi - lo - 2 pi has the sign of side
      hi.canonicalize();
      motion.angle_limits = RationalInterval{lo, hi};
      SCOPED_TRACE("2 pi " + std::string(side < 0 ? "- " : "+ ") + "10^-" + std::to_string(e));
      EXPECT_EQ(pin_slot_whole_turn({}, motion), side > 0);
      EXPECT_EQ(at_least_whole_turn(Rational(hi - lo)), side > 0);
      const Rational eighth = d / 8;
      const std::vector<Rounding> wide{{at + "0", "", lo, d}, {at + "1", "", hi, d}};
      const std::vector<Rounding> narrow{{at + "0", "", lo, eighth}, {at + "1", "", hi, eighth}};
      const std::vector<Rounding> elsewhere{{"/parts/1/motion/pin_slot/limits/0", "", lo, d},
                                            {"/parts/11/motion/pin_slot/angle_limits/1", "", hi, d}};
      EXPECT_TRUE(pin_slot_whole_turn(wide, motion));
      EXPECT_EQ(pin_slot_whole_turn(narrow, motion), side > 0);
      EXPECT_EQ(pin_slot_whole_turn(elsewhere, motion), side > 0);
      EXPECT_EQ(pin_slot_limits_slack(wide, motion), Rational(2 * d));
    }
  }
  // the stack takes the same decision: limits 10^-60 short of a whole turn, widened by the
  // reader's rounding, are the whole turn (psi near pi inside), not without it
  PinSlotBuildOptions options;
  options.slices = 4;
  options.refine_steps = 0;
  options.critical_values = false;
  options.connections = false;
  Model near = bar_and_block("[-30, 30]");
  near.roundings.clear();
  const Rational d = pin_slot_test::exact_power10(-60);
  near.parts[1].motion.angle_limits = RationalInterval{Rational(-pi.first), Rational(pi.first - d)};
  near.parts[1].motion.angle_limits->hi.canonicalize();
  EXPECT_EQ(PinSlotSpace::build(near, "a", "b", options).locate(PinSlotConfiguration{{}, Rational(0), pin_slot_test::exact_power10(70)}).kind,
            PinSlotLocation::Kind::outside);
  for (const char* end : {"0", "1"}) near.roundings.push_back(Rounding{at + end, "", Rational(0), d});
  EXPECT_TRUE(pin_slot_whole_turn(near.roundings, near.parts[1].motion));
  EXPECT_NE(PinSlotSpace::build(near, "a", "b", options).locate(PinSlotConfiguration{{}, Rational(0), pin_slot_test::exact_power10(70)}).kind,
            PinSlotLocation::Kind::outside);
}

// A stack narrower than a whole turn: its end slices lie about half a step inside the limits,
// and the end pieces between them and the limits are searched for critical values too (before
// session 55 they were not, while the values were claimed complete: the wall's value at 40.85
// deg went unlisted under limits of 41 deg). The bar against the wall x >= 12 (its slide's end
// on the wall at 27 t^2 -+ 2 t - 3 = 0: +-40.853 deg) under generated limits around that angle,
// either side of it, with 8 to 20 slices. The oracle scans 1-D slices by brute force across the
// limits (each certainly inside them by psi_bracket); two scanned slices whose structure differs
// have a listed value between them; every listed value is inside the limits (psi_bracket); the
// value 40.853 deg is listed exactly when it is inside; every interval between consecutive
// values, and between the limits and the outermost values, holds a slice of the stack.
Model bar_wall_limits(const std::string& limits, const std::string& initial_angle = "0") {
  return read_model(std::string(R"({ "hipair": 1, "name": "bar-wall", "units": { "length": "mm", "angle": "deg" },
    "parts": [
    { "name": "wall", "motion": "fixed", "loops": [ { "start": [12, -20], "edges": [ { "line_to": [20, -20] },
      { "line_to": [20, 20] }, { "line_to": [12, 20] }, { "line_to": [12, -20] } ] } ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": )") + limits + R"(,
      "limits": [-5, 5] } }, "initial": { "angle": )" + initial_angle + R"( },
      "loops": [ { "start": [0, -1], "edges": [ { "line_to": [10, -1] }, { "line_to": [10, 1] },
      { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] } ],
    "pairs": [ { "parts": ["wall", "bar"] } ] })");
}

// Checks a limited stack's critical values against the brute-force scan (`count` slices).
void expect_limited_stack_complete(const PinSlotSpace& space, const RationalInterval& limits, int count) {
  const double lo = to_double(limits.lo), hi = to_double(limits.hi);
  auto certainly_inside = [&](const Rational& t) {
    auto [a, b] = psi_bracket(t);
    return a > limits.lo && b < limits.hi;
  };
  std::vector<Rational> taus;
  for (const PinSlotSlice& s : space.slices()) taus.push_back(s.tau);
  for (int k = 0; k <= count; ++k) {
    double psi = lo + (hi - lo) * (k == 0 ? 1e-7 : k == count ? 1 - 1e-7 : static_cast<double>(k) / count);
    Rational t(std::tan(psi / 2));
    t.canonicalize();
    if (certainly_inside(t)) taus.push_back(t);
  }
  std::sort(taus.begin(), taus.end());
  taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  const auto& critical = space.critical_values();
  auto listed_between = [&](const Rational& a, const Rational& b) {
    return std::any_of(critical.begin(), critical.end(), [&](const PinSlotCritical& c) {
      const cspace::algebra::Real t = sliced::real_of(c.tau);
      return t.compare(a) >= 0 && t.compare(b) <= 0;   // (a scanned slice may be a stack's slice at a value)
    });
  };
  std::vector<std::string> seen;
  for (const Rational& t : taus) seen.push_back(pin_slot_test::free_structure(*space.slice(t)));
  int changes = 0;
  for (std::size_t k = 0; k + 1 < taus.size(); ++k) {
    if (seen[k] == seen[k + 1]) continue;
    ++changes;
    EXPECT_TRUE(listed_between(taus[k], taus[k + 1]))
        << "slices at tau " << taus[k].get_str() << " and " << taus[k + 1].get_str() << " differ with no critical value between: "
        << seen[k] << " | " << seen[k + 1];
  }
  EXPECT_GT(changes, 0);
  // inside the limits, and a slice of the stack in every interval they bound
  for (std::size_t k = 0; k < critical.size(); ++k) {
    cspace::algebra::Real t = sliced::real_of(critical[k].tau);
    t.refine_to(pin_slot_test::exact_power10(-30));
    if (t.exact && sgn(t.lower) == 0 && (sgn(limits.lo) == 0 || sgn(limits.hi) == 0)) continue;   // at a limit 0
    EXPECT_TRUE(t.exact ? certainly_inside(t.lower) : certainly_inside(t.lower) && certainly_inside(t.upper))
        << critical[k].degrees << " deg outside the limits";
  }
  const auto& slices = space.slices();
  for (std::size_t k = 0; k <= critical.size(); ++k) {
    // (a value at the limit 0 has no interval below it: the limit is the stack's first slice)
    if (k == 0 && !critical.empty() && sgn(limits.lo) == 0 && sliced::real_of(critical[0].tau).compare(Rational(0)) == 0) {
      EXPECT_EQ(slices.front().tau, 0);
      continue;
    }
    if (k == critical.size() && k > 0 && sgn(limits.hi) == 0 && sliced::real_of(critical[k - 1].tau).compare(Rational(0)) == 0) {
      EXPECT_EQ(slices.back().tau, 0);
      continue;
    }
    const bool has = std::any_of(slices.begin(), slices.end(), [&](const PinSlotSlice& s) {
      const bool after = k == 0 || sliced::real_of(critical[k - 1].tau).compare(s.tau) < 0;
      const bool before = k == critical.size() || sliced::real_of(critical[k].tau).compare(s.tau) > 0;
      return after && before;
    });
    EXPECT_TRUE(has) << "no slice of the stack between critical values " << k << " - 1 and " << k << " (or a limit)";
  }
  for (const PinSlotSlice& s : slices) EXPECT_TRUE(angle_within_limits(s.tau, limits.lo, limits.hi)) << s.degrees;
}

TEST(PinSlotAngleLimits, CriticalValuesBetweenTheLimitsAndTheEndSlicesAreFound) {
  const double wall_degrees = 2 * std::atan((1 + std::sqrt(82.0)) / 27) * 180 / std::numbers::pi;   // 40.853
  std::mt19937_64 random(5502);
  PinSlotBuildOptions options;
  options.connections = false;
  int listed_near_limit = 0;
  for (int round = 0; round < 8; ++round) {
    // each limit 0.05 ... 2.5 deg beyond +-40.853 deg (inside: listed), or short of it (rounds 3 and 6)
    auto offset = [&] { return (5 + static_cast<long>(random() % 246)) / 100.0; };
    const double below = -(wall_degrees + offset()) + (round == 3 ? 2.6 : 0);
    const double above = wall_degrees + (round == 6 ? -offset() : offset());
    char text[64];
    std::snprintf(text, sizeof text, "[%.2f, %.2f]", below, above);
    options.slices = 8 + static_cast<std::size_t>(random() % 13);
    SCOPED_TRACE(std::string(text) + " deg, " + std::to_string(options.slices) + " slices");
    Model model = bar_wall_limits(text);
    PinSlotSpace space = PinSlotSpace::build(model, "wall", "bar", options);
    ASSERT_TRUE(space.critical_values_exact());
    const RationalInterval& limits = *model.parts[1].motion.angle_limits;
    for (double target : {-wall_degrees, wall_degrees}) {
      const bool inside = target > below && target < above;
      const bool listed = std::any_of(space.critical_values().begin(), space.critical_values().end(),
                                      [&](const PinSlotCritical& c) { return std::abs(c.degrees - target) < 1e-6; });
      EXPECT_EQ(listed, inside) << target << " deg";
      // the end slices' angles: the value lies in an end piece (beyond them)
      if (inside) {
        const double step = (above - below) / static_cast<double>(options.slices);
        if (target > above - step / 2 || target < below + step / 2) ++listed_near_limit;
      }
    }
    expect_limited_stack_complete(space, limits, 160);
  }
  EXPECT_GE(listed_near_limit, 6);   // most rounds put a value in an end piece
  // a limit at psi = 0, where a critical value lies (t = 0): listed, and the limit is the
  // stack's first slice
  Model zero = bar_wall_limits("[0, 42]");
  options.slices = 12;
  PinSlotSpace from_zero = PinSlotSpace::build(zero, "wall", "bar", options);
  ASSERT_TRUE(from_zero.critical_values_exact());
  EXPECT_EQ(from_zero.slices().front().tau, 0);
  ASSERT_FALSE(from_zero.critical_values().empty());
  EXPECT_EQ(sliced::real_of(from_zero.critical_values().front().tau).compare(Rational(0)), 0);
  expect_limited_stack_complete(from_zero, *zero.parts[1].motion.angle_limits, 120);
  // a limit at or beyond the half turn (within the quarter step the stack accepts): the end
  // piece crosses the jump of tau, which no search in tau reaches: the values are not claimed
  Model half = bar_wall_limits("[100, 150]", "120");
  half.roundings.clear();
  half.parts[1].motion.angle_limits = RationalInterval{Rational(2), pi_hi()};
  EXPECT_FALSE(PinSlotSpace::build(half, "wall", "bar", options).critical_values_exact());
  half.parts[1].motion.angle_limits = RationalInterval{Rational(2), Rational(314159, 100000)};
  EXPECT_TRUE(PinSlotSpace::build(half, "wall", "bar", options).critical_values_exact());
}

// A limited rotation's axis (kinematics/axis.hpp, make_axis): its charts in the order of the
// exact half turns m pi they lie about (session 55; before, of double angles: limits beyond
// 2^53 rad gave coarse or infinite offsets and charts in any order). Generated limits of
// magnitude 1 ... 10^18 rad and widths 0.01 ... 6.2 rad against the oracle's pi: consecutive
// half turns, the chart's half_turn flag of m's parity, the first chart holding the lower
// limit and the last the upper one; limits beyond the range of a long are refused naming the part.
TEST(RotationChartLimits, TheAxisOrdersItsChartsByExactHalfTurns) {
  const Bracket pi = pi_bracket(80);
  std::mt19937_64 random(5503);
  for (int round = 0; round < 48; ++round) {
    const int e = round % 12 == 0 ? 0 : round % 19;   // 10^0 ... 10^18 rad
    Rational lo = pin_slot_test::exact_power10(e) * Rational(static_cast<long>(1000 + random() % 9000), 1000);
    if (random() % 2) lo = -lo;
    lo.canonicalize();
    Rational hi = lo + Rational(static_cast<long>(1 + random() % 620), 100);
    hi.canonicalize();
    SCOPED_TRACE("limits [" + lo.get_str() + ", " + hi.get_str() + "] rad");
    Model model = arm_model(lo, hi);
    const kinematics_detail::AxisLine line = kinematics_detail::make_axis(model, 0, charts_for(lo, hi));
    ASSERT_FALSE(line.pieces.empty());
    ASSERT_EQ(line.half_turns.size(), line.pieces.size());
    for (std::size_t p = 0; p < line.pieces.size(); ++p) {
      const long m = line.half_turns[p];
      EXPECT_EQ(line.pieces[p].half_turn, m % 2 != 0) << p;
      if (p > 0) EXPECT_EQ(m, line.half_turns[p - 1] + 1) << p;
      EXPECT_NEAR(line.offsets[p], static_cast<double>(m) * std::numbers::pi, 1e-15 * std::abs(static_cast<double>(m)) + 1e-15);
    }
    // the lower limit within [m - 1/2, m + 1/2] pi of the first chart, the upper one of the last
    const Rational m_first(line.half_turns.front()), m_last(line.half_turns.back());
    EXPECT_GT(sign_on(lo, Rational(m_first - Rational(1, 2)), pi), 0);
    EXPECT_LT(sign_on(lo, Rational(m_first + Rational(1, 2)), pi), 0);
    EXPECT_GT(sign_on(hi, Rational(m_last - Rational(1, 2)), pi), 0);
    EXPECT_LT(sign_on(hi, Rational(m_last + Rational(1, 2)), pi), 0);
  }
  const Rational far = pin_slot_test::exact_power10(25);
  try {
    Model model = arm_model(far, Rational(far + 1));
    kinematics_detail::make_axis(model, 0, charts_for(far, Rational(far + 1)));
    FAIL() << "limits at 10^25 rad were taken";
  } catch (const GeometryError& error) {
    EXPECT_NE(std::string(error.what()).find("'arm'"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace hipair
