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
#include <vector>

namespace hipair::verify {

/// The exact map of a fixed, rotating or translating part at its position in `configuration`
/// (identity when fixed); positions and limits checked (check.cpp). \throws Rejection.
ExactMap exact_map(const Part& part, const std::map<std::string, ExactPosition>& configuration);

/// The largest `angle_error` a position's angle label may carry: 10^-12 rad, the resolution of
/// the statement's 12 significant digits (session 42, hunt42: the error was unbounded, so a
/// certificate could state a configuration at any angle).
Rational max_angle_error();

/// Rejects a configuration that names a part other than `allowed` (the pair's parts, or for a
/// pin-slot claim the part not posed): such a position was never checked, yet the statement
/// printed it (session 42, hunt42). \throws Rejection.
void check_configuration_parts(const std::map<std::string, ExactPosition>& configuration,
                               const std::vector<std::string>& allowed);

/// Is every value of `value` certainly within `limits` (true when absent)? For an angle (rad)
/// up to whole turns (-3 ... 3). Decided with MPFI: an interval straddling an end is not within.
bool certainly_within(const std::optional<RationalInterval>& limits, const Interval& value, bool angle);

/// Does a part's coordinate stay within its motion limits (true when it has none) over the whole
/// of `range`: a free passage's driver range, or the hull of its follower path (docs/certify.md,
/// "Free passage")? A continuous motion keeps its turn: for a rotating part the range shifted by
/// one whole number of turns 2 pi k (k = -3 ... 3) must lie within the limits, decided exactly
/// (rational comparisons) for k = 0 and certainly (MPFI) for the others. A path each of whose
/// points is within the limits in some turn, but not all in the same one (from 0 across 2 pi),
/// is not within. Until session 35 (hunt35) the follower path was not tested at all: a path far
/// beyond the limits (a follower 100 mm past its 12 mm stop) was certified and verified.
bool range_within_limits(const Part& part, const RationalInterval& range);

/// May a jam certificate's wall at the lower (`upper` false) or upper end of the follower's trap
/// range `band` go without pieces because the follower's motion limit closes it (docs/certify.md,
/// "Jam")? Yes when the end is at or beyond that limit and, for a rotating follower, no other
/// turn of the band reaches into the limits on the far side of the wall: the band shifted a turn
/// down (for the upper wall; up for the lower one) must lie certainly beyond the other limit.
/// Otherwise a band shifted by a whole turn (the same poses) would count as "beyond the limit"
/// and the open side of the trap would go unchecked (session 34, hunt34).
bool wall_closed_by_limit(const Part& follower, const RationalInterval& band, bool upper);

/// "0.5 rad" (the recorded angle), "2 atan(1/3) + pi rad" (an exact tangent), "-3 mm": a
/// position in statements and messages (statement.cpp).
std::string position_text(const ExactPosition& position);

/// Rejects a certificate whose `statement` is not certificate_statement() of its data (called
/// once the claim's data are checked). \throws Rejection.
void check_statement(const Certificate& certificate, const Model& model);

/// Does a jam trap's follower range `band` meet the follower's motion limits (true when it has
/// none), so that the trap holds configurations the mechanism can reach? The band need not lie
/// within the limits (a wall may be closed by a limit, wall_closed_by_limit), but a band wholly
/// outside them in every turn makes the claim empty. For a rotating follower the band shifted
/// by one whole number of turns 2 pi k (k = -3 ... 3) must meet the limits: exactly (rational
/// comparisons, touching counts) for k = 0, certainly (MPFI) for the others. Shared by
/// certify_jam and the verifier (session 36, hunt36; hunt35's open finding).
bool band_meets_limits(const Part& follower, const RationalInterval& band);

/// Why `start` is not a free configuration of the jam's trap ("" when it is): it must lie in
/// the trap (exact), the follower's value within its limits, and the parts posed there (MPFI)
/// be certainly apart by more than the distance to an exact configuration next to it, at which
/// no loop of one part lies inside the other (exact). Shared by certify_jam, which tries
/// candidates with it, and the verifier (session 42, hunt42: a trap wholly inside the parts'
/// overlap verified, the claim "cannot pass" of a motion that cannot start).
std::string jam_start_failure(const Part& driver, const Part& other, const ConfigurationBox& trap,
                              const std::optional<JamStart>& start);

/// Why the world point `point` (of the model checked) is not a witness that every configuration
/// of the box driver_range x follower_range (no follower range: the other part is fixed) is
/// blocked ("" when it is): at an exact configuration near the box's middle the point lies
/// strictly inside both parts (exact), and over the box widened to hold that configuration its
/// certified distance from both boundaries is positive. Shared by certify_jam, which tries
/// candidate points with it, and the verifier (jam pieces of format version 2, session 57).
std::string jam_point_failure(const Part& driver, const Part& other, const RationalInterval& driver_range,
                              const std::optional<RationalInterval>& follower_range, const Point& point);

/// The vector pair_moved_to_origin (src/core/model_scale.hpp) subtracts from the model to check
/// the pair of parts `first` and `second`, or nullopt when it does not move it: jam pieces'
/// witness points are world points of the model as given, moved with the pair.
std::optional<Point> pair_translation(const Model& model, const std::string& first, const std::string& second);

/// An MPFI enclosure of the angle 2 atan(t) (+ pi when `half_turn`) of a half-angle tangent.
Interval angle_of_tangent(const Rational& tangent, bool half_turn);

/// Checks a planar_interference or planar_clearance claim; returns the summary line.
/// \throws Rejection with the exact reason when the claim does not hold.
std::string check_planar(const Certificate& certificate, const Model& model);

}  // namespace hipair::verify
