// HIPAIR — the first derivative alone of a contact edge's curve in part coordinates: what the
// simulator needs to orient a new contact's C-space normal (src/simulation, make_active).
//
// edge_coordinate_slope(space, e, x) is CSpace::derivatives(e, x).coordinate_dy: the same exact
// ordinate at x, refined the same way, and the same rational interval operations on it
// (y' = -(F_x / F_y), dY/dX = Y' y' / X' with a rotating axis's slope 2 / (1 + t^2)), so the
// same certified range bit for bit; it throws GeometryError exactly where derivatives() throws
// (a vertical edge, an abscissa outside the edge's extent, F_y = 0). It leaves out the second
// derivatives (F_xx, F_xy, F_yy and their rational interval products), most of derivatives()'s
// cost.
#pragma once

#include <hipair/cspace.hpp>

namespace hipair {

/// CSpace::derivatives(edge, x).coordinate_dy (the same range, the same exceptions).
CertifiedRange edge_coordinate_slope(const CSpace& space, EdgeId edge, const Rational& x);

}  // namespace hipair
