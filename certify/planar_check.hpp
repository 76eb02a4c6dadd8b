// The verifier's check of planar claims (docs/certify.md, "Planar pairs"): a part free in the
// plane (motion "planar") at one exact pose (x, y and a rational half-angle tangent) against a
// fixed part. Interference: a witness point strictly inside both posed parts, or two edges that
// cross transversally (exact). Clearance: a certified lower bound (MPFI) of the distance between
// the posed boundaries at least the claim, and no loop of one part inside the other (exact).
// Uses only the verifier's own geometry (exact_geometry, interval_geometry).
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include <string>

namespace hipair::verify {

/// Checks a planar_interference or planar_clearance claim; returns the summary line.
/// \throws Rejection with the exact reason when the claim does not hold.
std::string check_planar(const Certificate& certificate, const Model& model);

}  // namespace hipair::verify
