// HIPAIR — a real algebraic number's double and text without copies, and refine_to's switch
// (exact_real.cpp; a header of its own so that exact_real.hpp's many includers are untouched).
#pragma once

#include "algebra/exact_real.hpp"

#include <atomic>
#include <cstddef>
#include <string>

namespace hipair::cspace::algebra {

/// Real::approximate() without its copy: refines r itself (to the width approximate() refines
/// its copy to) and returns the same double.
double approximate_refining(Real& r);

/// Real::description's text of the root of `polynomial` in (lower, upper) (exact: the rational
/// `lower`), from the parts, without a Real.
std::string root_description(const Polynomial& polynomial, const Rational& lower, const Rational& upper, bool exact,
                             const std::string& variable);

/// refine_to takes its first (filtered) halvings at once, from a Newton iterate in doubles whose
/// cell the certified filter confirms (the same intervals and exact roots as halving step by
/// step). On by default; tests turn it off to compare.
std::atomic<bool>& refine_jump_enabled();
/// How many times refine_to or refine_dyadically took halvings at once in this thread (tests).
std::size_t& refine_jumps();

}  // namespace hipair::cspace::algebra
