#pragma once
// The front end's exact shortcut in front of the culling quadtree (builder.cpp), declared for
// its test (tests/unit/cspace_valid_point_test.cpp).
#include "arrangement/arrangement.hpp"
#include "curves/contact_curves.hpp"

namespace hipair::cspace {

/// True when the line `curve.polynomial` (total degree 1, no xy term) has a point in the closed
/// box where every validity clause holds (some atom >= 0), found where the line meets the line
/// of one of its linear atoms; false otherwise (also for any other curve, or no validity).
/// Decided in machine integers when every integer involved is below 2^62 and no expression
/// overflows (src/algebra/small_integers.hpp), by valid_point_in_box_gmp otherwise.
bool valid_point_in_box(const ContactCurve& curve, const raw::Box& box);

/// The same answer from GMP integers alone (the path for integers of any size; the tests
/// compare the two).
bool valid_point_in_box_gmp(const ContactCurve& curve, const raw::Box& box);

}  // namespace hipair::cspace
