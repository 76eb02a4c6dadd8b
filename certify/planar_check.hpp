// The verifier's check of planar claims (docs/certify.md, "Planar pairs"): a part free in the
// plane (motion "planar") at one exact pose (x, y and a rational half-angle tangent) against a
// fixed part, or a pin-in-slot part at an exact pose (slide s and tangent) against a fixed part
// or a rotating or translating one at its position in the certificate's configuration. Interference: a witness point strictly inside both posed parts, or two edges that
// cross transversally (exact). Clearance: a certified lower bound (MPFI) of the distance between
// the posed boundaries at least the claim, and no loop of one part inside the other (exact).
// Uses only the verifier's own geometry (exact_geometry, interval_geometry).
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"

#include <map>
#include <optional>
#include <string>

namespace hipair::verify {

/// The exact map of a fixed, rotating or translating part at its position in `configuration`
/// (identity when fixed); positions and limits checked (check.cpp). \throws Rejection.
ExactMap exact_map(const Part& part, const std::map<std::string, ExactPosition>& configuration);

/// Is every value of `value` certainly within `limits` (true when absent)? For an angle (rad)
/// up to whole turns (-3 ... 3). Decided with MPFI: an interval straddling an end is not within.
bool certainly_within(const std::optional<RationalInterval>& limits, const Interval& value, bool angle);

/// An MPFI enclosure of the angle 2 atan(t) (+ pi when `half_turn`) of a half-angle tangent.
Interval angle_of_tangent(const Rational& tangent, bool half_turn);

/// Checks a planar_interference or planar_clearance claim; returns the summary line.
/// \throws Rejection with the exact reason when the claim does not hold.
std::string check_planar(const Certificate& certificate, const Model& model);

}  // namespace hipair::verify
