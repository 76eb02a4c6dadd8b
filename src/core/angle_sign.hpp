// Exact signs of angles 2 atan(tau) + m pi - L (tau and L rational, m an integer): the
// comparisons of half-angle tangents with rational angle limits, modulo half turns, shared by
// pin-slot parts and model checks (core/angle_limits.hpp) and rotating parts' chart layout
// (curves/contact_curves.cpp).
//
// The sign comes from an MPFI enclosure of the difference, refined (precision doubled) until it
// excludes 0. The difference is never 0 except for tau = 0, m = 0, L = 0, which is decided
// directly: with m = 0 and L != 0, tau = tan(L / 2) would be rational, but tan of a nonzero
// algebraic number is transcendental (Lindemann); with tau = 0 and m != 0, pi = L / m would be
// rational; with tau != 0, tan(L / 2) = tau again (tan has period pi). So the refinement ends on
// every input: no tie is refused and no margin is guessed.
#pragma once

#include <hipair/rational.hpp>

#include <gmpxx.h>
#include <mpfi.h>

namespace hipair {

/// The sign of 2 atan(tau) + m pi - L, exactly (-1, 0 or +1; 0 only for tau = m = L = 0).
int angle_sign(const Rational& tau, const mpz_class& m, const Rational& L);

/// Bits above the binary point of |x| (0 for |x| < 1).
long magnitude_bits(const Rational& x);
long magnitude_bits(const mpz_class& x);

/// An enclosure of 2 atan(tau) + m pi - L at `bits` into `out` (initialised at `bits`).
void enclose_angle(mpfi_t out, const Rational& tau, const mpz_class& m, const Rational& L, mpfr_prec_t bits);

/// A precision at which enclose_angle(tau, m, L) is narrow (64 bits beyond the magnitudes).
mpfr_prec_t angle_bits(const mpz_class& m, const Rational& L);

}  // namespace hipair
