// CGAL-free pieces shared by the arrangement stages of the algebraic and the quadratic
// traits: grouping a chart's curves, validity and windows along a curve, edge boxes.
#pragma once

#include "algebra/exact_real.hpp"
#include "arrangement/arrangement.hpp"
#include "curves/contact_curves.hpp"

#include <array>
#include <functional>
#include <utility>

#include <cstddef>
#include <string>
#include <vector>

namespace hipair::cspace::raw {

/// Curves with the same polynomial up to a constant factor form one group (clipped once,
/// valid where any member is). Monomial factors x^i y^j are split off first: x = 0 and y = 0
/// are lines shared by many curves (coincident lock arcs of a zero-clearance fit give
/// y * g(x, y)), and one line is handled far more robustly than the same line hidden in
/// several reducible curves; the zero set is the same.
struct CurveGroups {
  std::vector<IntegerPolynomial2> polynomials;   ///< primitive, first non-zero coefficient positive
  std::vector<std::vector<std::size_t>> members; ///< indices of the input curves, per group
};

CurveGroups group_curves(const std::vector<IntegerPolynomial2>& curves);

/// Does some alternative (the clauses of one curve of a group) hold at (x, y): in each of its
/// clauses some atom >= 0?
bool clauses_hold(const std::vector<const std::vector<ValidityClause>*>& alternatives, const Rational& x,
                  const algebra::Real& y);

/// The certified double filter of clauses_hold: encloses every atom over the box x_i × y_i
/// (which must contain the exact point) in interval arithmetic. Returns 1 when some
/// alternative certainly holds there (in each of its clauses an atom's enclosure is >= 0),
/// 0 when every alternative certainly fails (some clause with every atom's enclosure < 0),
/// -1 when the enclosures do not decide (the caller decides exactly with clauses_hold).
int clauses_hold_filter(const std::vector<const std::vector<ValidityClause>*>& alternatives, algebra::Interval x_i,
                        algebra::Interval y_i);

/// Is x in one of the windows (none: no restriction)?
bool in_windows(const Rational& x, const std::vector<std::pair<Rational, Rational>>* windows);

/// Boxes {x_lo, x_hi, y_lo, y_hi} of the plane (closed, doubles), sorted by x_lo.
using CellBoxes = std::vector<std::array<double, 4>>;

/// The boxes of a group's members (Options::cells), sorted by x_lo; false when some member has
/// none (the group is not restricted).
bool group_cells(const std::vector<std::vector<std::array<double, 4>>>* cells, const std::vector<std::size_t>& members,
                 CellBoxes& out);

/// May a branch over the x-range [x_lo, x_hi] meet one of the boxes? `y_over(x)` encloses the
/// branch's y for every x of the interval x where the branch is defined (an infinite or NaN
/// enclosure: it may). False only when, over each box's x-range, the branch's enclosure misses
/// the box's y-range: then every point of the branch there lies outside all boxes.
bool branch_meets_cells(const CellBoxes& cells, double x_lo, double x_hi,
                        const std::function<algebra::Interval(algebra::Interval)>& y_over);

/// The edge's certified bounding box: the box of its ends (edges are monotone in x and y),
/// widened by one ulp so that exact root brackets never end on a root.
void fill_edge_box(const std::vector<Vertex>& vertices, Edge& out);

}  // namespace hipair::cspace::raw
