// Exact comparisons of an angle 2 atan(tau) with rational angle limits (angle_limits.hpp).
#include "core/angle_limits.hpp"

#include "core/angle_sign.hpp"
#include "core/mp_values.hpp"

#include <mpfi.h>
#include <mpfr.h>

#include <algorithm>
#include <optional>

namespace hipair {

bool angle_within_limits(const Rational& tau, const Rational& lo, const Rational& hi) {
  // k: the fewest whole turns with 2 atan(tau) + 2 pi k >= lo. An estimate, ceil((lo - psi) /
  // 2 pi) from an enclosure, then made exact by the signs.
  mpfr_prec_t bits = angle_bits(mpz_class(0), lo) + 16;
  mpz_class k;
  {
    MpfiValue x(bits), two_pi(bits);
    enclose_angle(x.v, tau, mpz_class(0), lo, bits);   // psi - lo
    mpfi_const_pi(two_pi.v);
    mpfi_mul_2ui(two_pi.v, two_pi.v, 1);
    mpfi_div(x.v, x.v, two_pi.v);                 // (psi - lo) / 2 pi
    mpfi_neg(x.v, x.v);                           // (lo - psi) / 2 pi
    MpfrValue middle(bits);
    mpfi_mid(middle.v, x.v);
    if (mpfr_number_p(middle.v)) mpfr_get_z(k.get_mpz_t(), middle.v, MPFR_RNDU);
  }
  while (angle_sign(tau, 2 * k, lo) < 0) ++k;
  while (angle_sign(tau, 2 * (k - 1), lo) >= 0) --k;
  return angle_sign(tau, 2 * k, hi) <= 0;
}

bool at_least_whole_turn(const Rational& width) {
  // 2 pi - width < 0 or ... never 0 (pi is irrational)
  return angle_sign(Rational(0), mpz_class(2), width) <= 0;
}

Rational rounding_slack(const std::vector<Rounding>& roundings, const std::string& pointer) {
  Rational slack = 0;
  if (pointer.empty()) return slack;
  for (const Rounding& r : roundings)
    if (r.pointer.compare(0, pointer.size(), pointer) == 0) slack += r.bound;
  return slack;
}

Rational pin_slot_limits_slack(const std::vector<Rounding>& roundings, const Motion& motion) {
  if (motion.pointer.empty()) return Rational(0);
  return rounding_slack(roundings, motion.pointer + "/pin_slot/angle_limits/");
}

bool pin_slot_whole_turn(const std::vector<Rounding>& roundings, const Motion& motion) {
  const std::optional<RationalInterval>& limits = motion.angle_limits;
  return !limits || at_least_whole_turn(Rational(limits->hi - limits->lo + pin_slot_limits_slack(roundings, motion)));
}

ReducedLimits reduced_limits(const RationalInterval& limits) {
  ReducedLimits out;
  out.turns = nearest_whole_turns(Rational((limits.lo + limits.hi) / 2));
  out.lo = reduced_angle(limits.lo, out.turns);
  out.hi = reduced_angle(limits.hi, out.turns);
  return out;
}

bool initial_angle_within_limits(const Rational& angle, const RationalInterval& limits, const Rational& limits_slack,
                                 const Rational& angle_slack) {
  if (at_least_whole_turn(Rational(limits.hi - limits.lo + limits_slack))) return true;
  const Rational slack = limits_slack + angle_slack;
  // angle + 2 pi k in [lo - slack, hi + slack]: 2 atan(0) + 2 pi k in [lo - slack - angle, hi + slack - angle]
  return angle_within_limits(Rational(0), Rational(limits.lo - slack - angle), Rational(limits.hi + slack - angle));
}

mpz_class nearest_whole_turns(const Rational& x) {
  mpfr_prec_t bits = angle_bits(mpz_class(0), x) + 16;
  MpfrValue value(bits), two_pi(bits);
  mpfr_set_q(value.v, x.get_mpq_t(), MPFR_RNDN);
  mpfr_const_pi(two_pi.v, MPFR_RNDN);
  mpfr_mul_2ui(two_pi.v, two_pi.v, 1, MPFR_RNDN);
  mpfr_div(value.v, value.v, two_pi.v, MPFR_RNDN);
  mpz_class k;
  mpfr_get_z(k.get_mpz_t(), value.v, MPFR_RNDN);
  return k;
}

double reduced_angle(const Rational& x, const mpz_class& k) {
  mpfr_prec_t bits = angle_bits(k, x) + 64;
  MpfrValue value(bits), turns(bits);
  mpfr_set_q(value.v, x.get_mpq_t(), MPFR_RNDN);
  mpfr_const_pi(turns.v, MPFR_RNDN);
  mpfr_mul_z(turns.v, turns.v, k.get_mpz_t(), MPFR_RNDN);
  mpfr_mul_2ui(turns.v, turns.v, 1, MPFR_RNDN);
  mpfr_sub(value.v, value.v, turns.v, MPFR_RNDN);
  return mpfr_get_d(value.v, MPFR_RNDN);
}

}  // namespace hipair
