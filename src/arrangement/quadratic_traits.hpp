// The C-space builder's filtered CGAL stage for charts whose contact curves all have degree
// <= 2 in y (rot–rot contacts in half-angle tangents are bi-quadratic): a model of CGAL's
// ArrangementXMonotoneTraits_2 for arcs (support F = a(x) y^2 + b(x) y + c(x), branch,
// x-interval), whose points have an algebra::Real x and y = (P + s sqrt(D)) / Q with P, Q, D
// polynomials in x. Every predicate is decided in certified double intervals first and by
// exact univariate sign evaluation (algebra::sign_at at a Real, repeated squaring of the
// square roots) when the filter fails; no Curve_analysis_2. The x-monotone split, clipping to
// the chart box, validity, windows and the export to raw::Arrangement are those of
// arrangement.hpp (same cuts, same pieces), so labelling and everything after are shared.
// All code is in quadratic_traits.cpp (one translation unit).
#pragma once

#include "arrangement/arrangement.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace hipair::cspace::raw {

/// Coefficient size above which the quadratic traits declines: its exact fallback squares
/// the square roots away (polynomials of 4x the coefficient size), and on the 18x27 spur
/// gears (247-653-bit coefficients) the operating region took 103 s CPU against 40 s on the
/// algebraic traits, while Geneva (at most 139 bits) is 1.4x faster (docs/performance.md).
inline constexpr std::size_t quadratic_max_coefficient_bits = 200;

/// True when every curve has degree <= 2 in y and coefficients of at most
/// quadratic_max_coefficient_bits bits (then build_quadratic_arrangement may apply).
bool quadratic_applies(const std::vector<IntegerPolynomial2>& curves);

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
