// Exact comparisons of an angle psi = 2 atan(tau) (tau rational: a pin-slot part's configuration's
// half-angle tangent; tau = 0 for a rational angle shifted into the limits, as the model reader
// checks a pin-slot part's initial angle) with rational angle limits (rad), modulo whole turns.
// (angle_sign is core/angle_sign.hpp's, since session 54 shared with rotating parts' charts.)
//
// 2 atan(tau) + m pi (m an integer) is compared with a rational L through an MPFI enclosure of
// the difference, refined (precision doubled) until it excludes 0. The difference is never 0
// except for tau = 0, m = 0, L = 0, which is decided directly: with m = 0 and L != 0,
// tau = tan(L / 2) would be rational, but tan of a nonzero algebraic number is transcendental
// (Lindemann); with tau = 0 and m != 0, pi = L / m would be rational; with tau != 0, tan(L / 2)
// = tau again (tan has period pi). So the refinement ends on every input: no tie is refused and
// no margin is guessed (before session 53, PinSlotSpace::locate compared a double atan with a
// 1e-12 margin and refused configurations within it).
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include "core/angle_sign.hpp"

#include <gmpxx.h>

#include <string>
#include <vector>

namespace hipair {

/// Is psi = 2 atan(tau) inside [lo, hi] modulo whole turns (some psi + 2 pi k in [lo, hi],
/// the limits included)? Exact. \pre lo <= hi.
bool angle_within_limits(const Rational& tau, const Rational& lo, const Rational& hi);

/// Is `width` >= 2 pi? Exact (never equal: pi is irrational).
bool at_least_whole_turn(const Rational& width);

/// The sum of the bounds of the reader's roundings recorded under `pointer` (exactly, or below
/// it: "/parts/1/motion/pin_slot/angle_limits/" covers both limits); 0 when there is none (exact
/// values, or a model built in code). The values as written lie within it of the stored ones.
Rational rounding_slack(const std::vector<Rounding>& roundings, const std::string& pointer);

/// The reader's rounding bound of a pin-slot motion's two angle limits: rounding_slack under
/// `motion.pointer` + "/pin_slot/angle_limits/" (0 for a motion built in code).
Rational pin_slot_limits_slack(const std::vector<Rounding>& roundings, const Motion& motion);

/// Are a pin-slot motion's angles unlimited: no angle limits, or limits spanning a whole turn
/// allowing for the reader's rounding of the two (pin_slot_limits_slack: [-180, 180] deg is a
/// whole turn whichever way pi was rounded), however wide (1e400 deg)? Exact. The one decision
/// PinSlotSpace::build and pin_slot_cycle take (session 55; before, the cycle left out the
/// rounding and could take limits the stack called a whole turn for narrower ones).
bool pin_slot_whole_turn(const std::vector<Rounding>& roundings, const Motion& motion);

/// Limits narrower than a whole turn shifted by the whole turns nearest their middle (the
/// angle is taken modulo 2 pi), for choosing slice angles and poses: a choice in doubles
/// (each end within a few units in the last place of limit - 2 pi turns), not a decision.
struct ReducedLimits {
  mpz_class turns;
  double lo = 0, hi = 0;
};
ReducedLimits reduced_limits(const RationalInterval& limits);

/// Is a pin-slot part's initial angle `angle` (rad) inside its angle limits modulo whole turns,
/// as PinSlotSpace::locate takes its angle? Limits spanning a whole turn, allowing for the
/// rounding of the two (`limits_slack`), are the whole turn: every angle is inside. Otherwise
/// some angle + 2 pi k must lie in [lo - slack, hi + slack], slack = `limits_slack` +
/// `angle_slack` (the rounding of the initial angle), so that an angle written at a limit plus
/// whole turns (380 deg against [-20, 20] deg) is inside whichever way the three were rounded.
/// Exact. \pre limits.lo <= limits.hi.
bool initial_angle_within_limits(const Rational& angle, const RationalInterval& limits, const Rational& limits_slack,
                                 const Rational& angle_slack);

/// A choice, not a decision: the number of whole turns k nearest to x / (2 pi), and x - 2 pi k
/// as a double (within a few units in the last place).
mpz_class nearest_whole_turns(const Rational& x);
double reduced_angle(const Rational& x, const mpz_class& k);

}  // namespace hipair
