// Double-filtered answers about real algebraic numbers (implemented in exact_real.cpp, where
// the certified double bisection of compare() lives). A narrow header: the kinematic slicer's
// class transfer uses them without every includer of exact_real.hpp rebuilding.
#pragma once

#include "algebra/exact_real.hpp"

#include <optional>
#include <utility>

namespace hipair::cspace::algebra {

/// A rational strictly between a < b (a double's value) read off certified double enclosures
/// of a and b (compare()'s filter: halvings of their isolating intervals in doubles, the signs
/// certified), or nothing when the filter cannot separate them. No exact refinement.
std::optional<Rational> double_between(const Real& a, const Real& b);

/// Certified double bounds lo < x < hi of an irrational-form x (not exact), narrowed by
/// compare()'s double bisection (at most `halvings` halvings, as far as its certified filter
/// decides the signs): near the precision of a double for a well-conditioned root. No exact
/// refinement; the bounds are those of the isolating interval's enclosure when the filter
/// cannot start. \pre !x.exact.
std::pair<double, double> double_bounds(const Real& x, int halvings = 64);

/// x.compare(r), with the polynomial's sign at r first taken by a certified double filter and
/// exactly only when the filter cannot decide it: the same answer.
int compare_filtered(const Real& x, const Rational& r);

}  // namespace hipair::cspace::algebra
