// Complete decision of whether a real algebraic number is rational (its exact value if so).
// A narrow header of the algebra layer (exact_real.hpp is included almost everywhere).
#pragma once

#include "algebra/exact_real.hpp"

#include <optional>
#include <vector>

namespace hipair::cspace::algebra {

/// Every rational root of p, ascending, each once; nullopt only when no prime among the 40
/// tried (from 257 on) leaves p primitive of its degree with only simple roots modulo it (a
/// finite set of primes, those dividing a_n or the discriminant, can fail). A rational root
/// num/den (lowest terms) of the primitive p has num | a_0 and den | a_n, and is the unique
/// such fraction congruent to its image a modulo M > 2 |a_0| |a_n|, a power of a prime l not
/// dividing a_n; a is the Hensel lift of a simple root of p modulo l. So the roots modulo l
/// (at most l evaluations in words), lifted quadratically and reconstructed (extended Euclid),
/// are the only candidates, each tested exactly. Cost: polynomial in the size of p.
std::optional<std::vector<Rational>> rational_roots(const Polynomial& p);

/// The value of r when it is a rational number, decided completely; nullopt when r is
/// irrational: r exact or a root of a linear factor; else the rational roots of r.polynomial
/// (rational_roots) compared exactly with r; without them, rational_root_by_refinement.
/// r itself is not changed.
std::optional<Rational> rational_root(const Real& r);

/// Real::detect_rational's fast path alone, for callers to which exactness is only a saving (the
/// sliced critical angles): makes r exact when it is a rational of denominator below about 2^31
/// (three refinements, to 2^-8, 2^-24, 2^-64 of its size, each tried with the simplest rational
/// of the interval); true when r is exact. Not complete: Real::detect_rational is.
bool detect_small_rational(Real& r);

/// rational_root by refinement (the fallback). A rational root p/q (lowest terms) of the integer
/// polynomial P = r.polynomial has q | Q = |a_n| / content(P), and two distinct rationals of
/// denominators <= Q differ by >= 1/Q^2. A copy of r is refined (dyadic bisection, exact signs
/// behind a certified filter) in stages until its open isolating interval holds no rational of
/// denominator <= Q (r is irrational), or its simplest rational (smallest denominator) is a
/// root of P (r is that rational), or it is <= 1/Q^2 wide with a simplest rational that is no
/// root (irrational: no other rational of denominator <= Q fits in it). Cost: up to about
/// log2(width * Q^2) sign evaluations of P at ever longer dyadics (slow for Q of thousands of
/// bits); a root p/q is met by the time the interval is 1/q^2 wide.
std::optional<Rational> rational_root_by_refinement(const Real& r);

}  // namespace hipair::cspace::algebra
