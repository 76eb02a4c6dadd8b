// Helpers shared by the certificate producers (src/certificates/*.cpp). Internal.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"

#include <optional>
#include <string>
#include <vector>

namespace hipair::certify_detail {

/// The part called `name`. \throws ModelError when there is none.
const Part& part_of(const Model& model, const std::string& name);

/// A certificate with the model's identity (name, file, hash, parameter values, roundings).
Certificate start_certificate(const Model& model, const CertifyContext& context, ClaimKind claim,
                              const std::string& first, const std::string& second);

/// Runs the verifier's own check on a certificate just produced.
/// \throws NumericError naming the reason if it does not verify (a producer bug).
void self_check(const Certificate& certificate, const Model& model);

/// A certificate produced on the model moved to the origin (pair_moved_to_origin: a pair far
/// from it for its size; the claim holds no world point), self-checked on the model as given.
inline std::optional<Certificate> checked_as_given(std::optional<Certificate> certificate, const Model& model) {
  if (certificate) self_check(*certificate, model);
  return certificate;
}

/// A configuration just before a jam where the follower's free range has not closed yet, read
/// off a kinematic analysis: the driver at `driver`, the follower free about [lo, hi] (doubles of
/// the analysis: estimates only; the start a certificate takes is checked with the verifier's
/// jam_start_failure).
struct ClosingStart {
  Rational driver, lo, hi;
};

/// The jam where the follower's free range closes (a zero-backlash mesh: the free channel
/// narrows to a point at the driver value `closing_driver`, follower `closing_follower`, both
/// estimates): a trap around the closing, from a free start before it (the first of `starts`
/// whose middle is certainly free) to a cut past the closing, its follower range the channel's
/// sweep with a margin. Each trap is certified by certify_jam (cover of the cut and walls,
/// self-checked by the verifier's code), with at most `max_pieces` pieces.
/// \returns nullopt when no trap tried is certified.
std::optional<Certificate> certify_closing_jam(const Model& model, const std::string& first, const std::string& second,
                                               const std::string& driver, int direction, const Rational& closing_driver,
                                               const Rational& closing_follower, const std::vector<ClosingStart>& starts,
                                               const CertifyContext& context, std::size_t max_pieces = 2000);

/// certify_found_jam with at most `tests` piece tests (one blocking crossing or point sought for
/// one piece of a cut or wall) over all its traps, `tests` counting down (0: the budget ran out,
/// the search gave up). `hipair analyze` uses it: its jam search is bounded, whatever the trap.
std::optional<Certificate> certify_found_jam_within(const Model& model, const std::string& first, const std::string& second,
                                                    const JamQuery& query, const Rational& step, const CertifyContext& context,
                                                    std::size_t& tests);

/// The exact world map of `part` at `position` (identity for a fixed part).
/// \throws GeometryError for parts that are neither fixed, rotating nor translating.
verify::ExactMap exact_map(const Part& part, const ExactPosition* position);

/// All poses of `part` with its coordinate (rad or mm) in `range` (identity if fixed).
verify::IntervalMap interval_map(const Part& part, const RationalInterval& range);

/// The largest e for which claimed_clearance (without `asked`, closer than its bound resolves)
/// tests cap 2^-e: 4096 + 8 S, S the bits (numerator and denominator) of both maps' entries and
/// of each part's largest vertex coordinate (a squared distance has degree at most 8 in them);
/// beyond it the search is refused (GeometryError) rather than carried on with ever larger numbers.
long clearance_search_limit(const Part& a, const verify::ExactMap& map_a, const Part& b, const verify::ExactMap& map_b);

/// The distance a clearance certificate claims: `asked` when the parts at their exact maps are at
/// least that far apart (the MPFI `bound` first, then exactly, as the verifier decides it: a
/// claim of exactly the distance holds at any magnitude), else nothing; without `asked`, `bound`
/// rounded down to 6 digits; when `bound` is not positive (parts the caller found apart exactly but
/// closer than the enclosures resolve), `cap` (an upper bound of the distance) 2^-e for the least
/// e that holds exactly, rounded down to 6 digits (nothing when `cap` is not positive; e beyond
/// clearance_search_limit: \throws GeometryError).
std::optional<Rational> claimed_clearance(const Rational& bound, const std::optional<Rational>& asked, const Part& a,
                                          const verify::ExactMap& map_a, const Part& b, const verify::ExactMap& map_b,
                                          const Rational& cap);

/// A piece of edge e (posed at one pose: ec, over a set of poses: eo) that crosses edge g (gc,
/// go) for every pose of the set, proved by verify::crossing_certain, or nullopt: the search of
/// the jam and free-passage producers (src/certificates/intervals.cpp), used by sliced_apart.
std::optional<RationalInterval> crossing_piece_of(const verify::IntervalEdge& ec, const verify::IntervalEdge& eo,
                                                  const verify::IntervalEdge& gc, const verify::IntervalEdge& go);

/// `value` rounded towards zero to `digits` significant decimal digits.
Rational round_down(const Rational& value, int digits);

/// A rational approximation of `value` (for choosing parameters; not a bound).
Rational approximate(double value);

}  // namespace hipair::certify_detail
