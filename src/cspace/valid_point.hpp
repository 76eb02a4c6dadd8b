#pragma once
// The front end's exact shortcut in front of the culling quadtree (builder.cpp), declared for
// its test (tests/unit/cspace_valid_point_test.cpp).
#include "arrangement/arrangement.hpp"
#include "curves/contact_curves.hpp"

namespace hipair::cspace {

/// True when the line `curve.polynomial` (total degree 1, no xy term) has a point in the closed
/// box where every validity clause holds (some atom >= 0), found where the line meets the line
/// of one of its linear atoms; false otherwise (also for any other curve, or no validity).
bool valid_point_in_box(const ContactCurve& curve, const raw::Box& box);

}  // namespace hipair::cspace
