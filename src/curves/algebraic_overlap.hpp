// The exact overlap relation of a pair at a chart point with an irrational coordinate (a real
// algebraic number): the zero-clearance fits at irrational angles that the rational oracle
// (classify_overlap) cannot be posed at. Declared here, in the chart vocabulary, and
// implemented in src/oracle/algebraic_overlap.cpp, as classify_overlap is.
#pragma once

#include "algebra/exact_real.hpp"
#include "algebra/ordinate.hpp"
#include "curves/contact_curves.hpp"

#include <hipair/model.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

namespace hipair::cspace {

/// How often PairOverlap::certainly_overlapping was asked and how often it answered true,
/// over the process (for tests and measurements).
std::array<std::uint64_t, 2> overlap_filter_counts();

/// The certified filter in front of the algebraic oracle (the `filter` arguments below), on
/// this thread: off, the oracle decides every point itself (tests compare the two).
struct AlgebraicFilterTag;
inline bool& algebraic_filter_switch() { return thread_switch<AlgebraicFilterTag>(); }

/// Exact relation of the pair's parts posed at chart point (x, y) of chart (x_axis, y_axis),
/// where x and y are real algebraic numbers (rational or not; y is ignored for a 1-D space).
/// Every decision is the exact sign of a polynomial in the chart coordinates at the point
/// (algebra::sign_at: zero iff the polynomial vanishes there, by gcd; otherwise refined until
/// certain). Parts bounded by segments and circular arcs (arcs since session 34); nullopt when
/// both coordinates of a 2-D point are irrational, or (parts with arcs) in the one degenerate
/// case left: a loop without common point whose every vertex has a vertex of the other part (or
/// a circle's tangent) both at its height and at its abscissa.
/// `filter` (optional, the same model's and axes' prepared oracle): its certified filter
/// (PairOverlap::certainly_overlapping) is asked first over the point's box — the isolating
/// intervals — once the point is one this oracle decides; where it answers, the answer is
/// "overlapping", which the exact decision below would give too (a certain transversal crossing
/// of two edges' interiors is found by it before anything that can leave it undecided).
std::optional<Overlap> algebraic_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                         const ChartAxis& y_axis, const algebra::Real& x, const algebra::Real& y,
                                         const PairOverlap* filter = nullptr);

/// The certified filter of algebraic_overlap alone (PairOverlap::certainly_overlapping, when
/// `filter` is given and algebraic_filter_switch is on) over the box of x's value or isolating
/// interval and [y_lower, y_upper] (a 1-D space: y = 0): true only where the parts' interiors
/// certainly overlap at every configuration of the box — the exact relation at any point of it
/// is "overlapping"; false says nothing.
bool certainly_overlapping_over(const PairAxes& axes, const ChartAxis& x_axis, const ChartAxis& y_axis,
                                const algebra::Real& x, const Rational& y_lower, const Rational& y_upper,
                                const PairOverlap* filter);

/// A chart ordinate given as an expression in the abscissa (algebra/ordinate.hpp): y =
/// (numerator(x) + √radicand(x)) / denominator(x) at the point's x (an empty radicand: a
/// rational function), with lower <= y <= upper (the caller's enclosure; checked exactly). A
/// point with both coordinates irrational is posed this way: the common root in y of two curves
/// through it (their first subresultant), or a root of one of degree 2 in y.
using algebra::RadicalOrdinate;

/// algebraic_overlap at (x, y) of a 2-D chart: every sign is decided by signs of polynomials in
/// x at x (the ordinate substituted, the denominator's power's sign applied; with a radicand, the
/// terms with and without its root compared: algebra::sign_with_root). nullopt where the
/// degenerate ray case above leaves it undecided, or where the ordinate is not as described
/// (denominator(x) = 0, radicand(x) < 0, or y outside [lower, upper]).
/// `filter` as above, over the box of x's isolating interval and [lower, upper], once the
/// ordinate is checked to be as described.
std::optional<Overlap> algebraic_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x_axis,
                                         const ChartAxis& y_axis, const algebra::Real& x, const RadicalOrdinate& y,
                                         const PairOverlap* filter = nullptr);

}  // namespace hipair::cspace
