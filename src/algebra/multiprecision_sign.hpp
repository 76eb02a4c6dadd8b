// A multi-precision interval filter for the sign of an integer polynomial at a real algebraic
// number (MPFR, every rounding outward), between sign_at(Polynomial, Real)'s double filter and
// its exact path (gcd, square-free part, Sturm sequence). A narrow header: sign_at's callers do
// not see it; tests compare it with the exact path.
#pragma once

#include "algebra/exact_real.hpp"

#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::cspace::algebra {

/// The sign of p at u (p not zero, u not exact) from MPFR interval arithmetic, or nothing when
/// the filter cannot decide it within its precisions (from `start_bits`, doubled while at most
/// `max_bits`). The isolating interval of u is enclosed outwards and narrowed by bisection in
/// MPFR (each midpoint's sign of u.polynomial certified by a point enclosure, the midpoint kept
/// only when it lies strictly inside the bracket), and p is enclosed over the bracket by
/// interval Horner; a sign is returned only when the enclosure excludes zero, so it is never
/// wrong. A zero of p at u is never decided (nothing).
std::optional<int> multiprecision_sign(const Polynomial& p, const Real& u, long start_bits, long max_bits);

/// The filter's precisions for p at u: the start and the cap, from `width`, the bits of the
/// widest coefficient of p and u's polynomial.
struct MultiprecisionBits {
  long width, start, cap;
};
MultiprecisionBits multiprecision_sign_bits(const Polynomial& p, const Real& u);

/// The order of two non-exact reals a and b (-1: a < b, 1: a > b) from their brackets bisected in
/// MPFR as multiprecision_sign's (each midpoint kept only strictly inside, with a certified sign
/// of the number's own polynomial), or nothing when the brackets still overlap at `max_bits`
/// (precisions from `start_bits`, doubled). The order is given only when the enclosures of the
/// brackets are disjoint, so it is never wrong; equal numbers are never ordered. `equal`, when
/// given, is asked once, when the brackets still overlap at the start precision's floor: true
/// returns 0 (the caller's exact equality test), false goes on to higher precisions.
std::optional<int> multiprecision_order(const Real& a, const Real& b, long start_bits, long max_bits,
                                        const std::function<bool()>& equal = nullptr);
/// multiprecision_order's precisions for a and b (as multiprecision_sign_bits').
MultiprecisionBits multiprecision_order_bits(const Real& a, const Real& b);

/// multiprecision_order's bracket of u at `bits` after each of `rounds` rounds (two halvings and
/// an interval Newton step each), as exact rationals, for tests: each must hold u.
std::vector<std::pair<Rational, Rational>> multiprecision_brackets(const Real& u, long bits, int rounds);

/// compare(a, b) by the exact path only (rational bisection, the gcd's roots): tests' oracle.
int exact_compare(const Real& a, const Real& b);

/// True when gcd(p, q) is certified constant modulo a word-size prime not dividing p's leading
/// coefficient (then p and q share no root); false when that cannot be certified.
bool coprime_modularly(const Polynomial& p, const Polynomial& q);

/// The filter's enclosures, for tests: `over` is p over [a, b] (a <= b, the ends enclosed
/// outwards at `bits`) by interval Horner; `at_point` is p at x rounded to nearest at `bits`
/// (that point returned as `point`). Each bound is the MPFR number exactly.
struct MultiprecisionEnclosure {
  Rational point, lo, hi;
};
MultiprecisionEnclosure multiprecision_enclosure_over(const Polynomial& p, const Rational& a, const Rational& b, long bits);
MultiprecisionEnclosure multiprecision_enclosure_at_point(const Polynomial& p, const Rational& x, long bits);

/// The polynomial enclosures (at a point or over a bracket) the filters above have computed on
/// this thread so far, for tests of their convergence.
long multiprecision_enclosures();
/// The integer gcds sign_at(Polynomial, Real) has computed on this thread so far for
/// coefficients wider than 192 bits (its zero test), for tests.
long wide_sign_gcds();

/// Session 46: multiprecision_order and multiprecision_sign start a number's bracket where the
/// thread's last bracket of the same number (polynomial and isolating interval) ended, and leave
/// theirs when narrower (a per-thread memo of at most 4 096 numbers). For tests: the memo's uses
/// on this thread so far; switching it off (returns the previous setting); the bracket it holds
/// for u (nothing when none narrower than u's interval), as exact rationals.
long multiprecision_bracket_memo_hits();
bool set_multiprecision_bracket_memo(bool enabled);
std::optional<std::pair<Rational, Rational>> remembered_bracket(const Real& u);

/// sign_at(p, u) by the exact path only (gcd, square-free part, Sturm sequence): tests' oracle.
int exact_sign_at(const Polynomial& p, const Real& u);

}  // namespace hipair::cspace::algebra
