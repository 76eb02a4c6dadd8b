// The C-space builder's fast CGAL stage for charts whose contact curves are all lines and
// circles (translating pairs: vertex–segment contacts are segments, anything with an arc is a
// circular arc): CGAL::Arr_circle_segment_traits_2<Epeck> instead of the algebraic traits.
// It exports the same plain exact topology (raw::Arrangement) as arrangement.hpp, so that
// labelling, classification, cells, point location and every adaptor query are shared.
// All circle–segment CGAL code is in circle_segment_traits.cpp (one translation unit).
#pragma once

#include "arrangement/arrangement.hpp"

#include <utility>
#include <vector>

namespace hipair::cspace::raw {

/// True when every curve is a line or a circle with rational centre and squared radius (or
/// zero / a non-zero constant: no points), every validity atom of a line has total degree
/// <= 1, and every atom of a circle is linear or a circle (q (x^2 + y^2) + linear: the
/// external/internal branch of an arc–arc contact): then build_circle_segment_arrangement applies.
bool circle_segment_applies(const std::vector<IntegerPolynomial2>& curves,
                            const std::vector<std::vector<ValidityClause>>& validity);

/// build_arrangement for curves that circle_segment_applies() accepts: each curve clipped
/// exactly to the box, its validity and its windows (one-root coordinates a + b sqrt(c)),
/// circles split at their four extreme points (every edge is monotone in x and y), inserted by
/// CGAL's aggregated insertion. Every vertex has exact coordinates (`y_exact`; y_curve is the
/// minimal polynomial of y, in y alone). `options.keep_cgal` keeps nothing (the raw CGAL
/// access of hipair/cgal/arrangement.hpp is for algebraic-traits arrangements).
/// \throws GeometryError when the curves do not fit (see circle_segment_applies).
/// CGAL's interval of an exact rational, as its kernel numbers carry it (`CGAL::to_interval`:
/// the value itself when it is a double, else its two neighbouring doubles). The stage makes
/// its kernel numbers with it; when numerator and denominator have at most 53 bits it is
/// computed without MPFR (one division and one fma). Exposed for its test.
std::pair<double, double> kernel_interval(const Rational& value);

/// {algebra::lower_double(value), algebra::upper_double(value)} (the largest double <= value and
/// the smallest >= value), through kernel_interval's fast case where it applies (the same two
/// doubles) instead of two conversions with exact comparisons.
std::pair<double, double> double_bounds(const Rational& value);

/// |value rounded to the nearest double| <= 2^exponent: the segment traits' range guard (the
/// segment flavour is taken while the box and the lines' coefficients pass it), decided from the
/// bit sizes of numerator and denominator where they decide it. Exposed for its test.
bool within_segment_filter_range(const Rational& value, int exponent);

Arrangement build_circle_segment_arrangement(const Box& box, const std::vector<IntegerPolynomial2>& curves,
                                             const std::vector<std::vector<ValidityClause>>& validity,
                                             const std::vector<std::vector<std::pair<Rational, Rational>>>& windows,
                                             const Options& options);

}  // namespace hipair::cspace::raw
