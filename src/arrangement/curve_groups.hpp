// Grouping of a chart's contact curves before an arrangement stage clips them (CGAL-free,
// shared by the algebraic and the quadratic traits stages).
#pragma once

#include "curves/contact_curves.hpp"

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

}  // namespace hipair::cspace::raw
