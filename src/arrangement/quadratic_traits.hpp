// The C-space builder's filtered CGAL stage for charts whose contact curves all have degree
// <= 2 in y (rot–rot contacts in half-angle tangents are bi-quadratic): a model of CGAL's
// ArrangementXMonotoneTraits_2 for arcs (support F = a(x) y^2 + b(x) y + c(x), branch,
// x-interval), whose points have an algebra::Real x and y = (P + s sqrt(D)) / Q with P, Q, D
// polynomials in x. Every predicate is decided in certified double intervals first; when
// they fail, equality of two arcs at a root of their supports' resultant by the first
// subresultant, then certified MPFI intervals at a finer x, and last exact univariate sign
// evaluation (algebra::sign_at at a Real, repeated squaring of the square roots); pairs of
// arcs whose interval enclosures are apart are not intersected. No Curve_analysis_2. The
// x-monotone split, clipping to the chart box, validity, windows and the export to raw::Arrangement are those of
// arrangement.hpp (same cuts, same pieces), so labelling and everything after are shared.
// All code is in quadratic_traits.cpp (one translation unit).
#pragma once

#include "arrangement/arrangement.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::cspace::raw {

/// True when every curve has degree <= 2 in y and coefficients of at most `max_bits` bits
/// (then build_quadratic_arrangement may apply). The default (Options and
/// CSpaceBuildOptions::quadratic_max_coefficient_bits) is 200: predicates are decided in
/// double intervals, then (at a common root of two supports) by their first subresultant,
/// then in MPFI intervals at 192-2064 bits, and only then exactly by squaring the square
/// roots away; on the spur gears (247-653 bits) this is at parity with the algebraic traits
/// at 18x27 teeth and 9-20 % slower at 40x40 and 80x80 (docs/performance.md, session 9), so
/// they keep the algebraic traits unless the limit is raised.
bool quadratic_applies(const std::vector<IntegerPolynomial2>& curves, std::size_t max_bits);

/// build_arrangement for curves of degree <= 2 in y, on the filtered quadratic traits.
/// Returns nullopt (the caller takes the algebraic traits) for inputs outside the class it
/// decides: two distinct curves with a common non-vertical component, a vertex whose curve
/// vanishes on its whole fibre, or bounds that do not separate after refinement.
/// `options.keep_cgal` is not supported (the caller keeps the algebraic traits then).
std::optional<Arrangement> build_quadratic_arrangement(
    const Box& box, const std::vector<IntegerPolynomial2>& curves,
    const std::vector<std::vector<ValidityClause>>& validity,
    const std::vector<std::vector<std::pair<Rational, Rational>>>& windows, const Options& options);

}  // namespace hipair::cspace::raw
