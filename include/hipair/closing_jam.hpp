// The jam of a closing free range, certified from a kinematic analysis (session 53). Used
// by `hipair analyze` (certify_kinematic_findings) and `hipair certify --claim jam`.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/kinematics.hpp>

#include <optional>

namespace hipair {

/// The analysis's jam (result.jam) of a follower whose free range closes — a zero-backlash mesh:
/// the channel the follower moves in narrows to a point — certified with a trap around the
/// closing (certify_detail::certify_closing_jam) for the pair of the driver and that follower:
/// its start is the middle of the follower's free interval at the last samples before the
/// closing where it has play (checked with the verifier's start test), its cut just past the
/// closing. nullopt when the result has no such jam or no trap is certified (never throws but
/// std::bad_alloc).
std::optional<Certificate> certify_closing_jam(const Model& model, const KinematicsResult& result,
                                               const CertifyContext& context = {});

}  // namespace hipair
