// The verifier's internals of the sliced_connected certificate (<hipair/sliced_certificate.hpp>):
// the move check the producer also uses, and what it shares with check.cpp. Internal.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced_certificate.hpp>

#include "certify/exact_geometry.hpp"

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

namespace verify {

/// The verifier's refusal: throws Rejection{reason} (shared by the certify/ checks).
[[noreturn]] void reject(const std::string& reason);
/// The part called `name` of `model`; rejected ("the model has no part ...") when there is none.
const Part& part_named(const Model& model, const std::string& name);
/// A planar pose in claims' words: "x=.., y=.., t=.." (t(pi)= in the chart centred at the half
/// turn), a pin-slot pose "s=.., t=..": numbers exact up to 60 characters (fraction_or_rounded).
std::string sliced_pose_words(const PlanarPose& pose);

/// The work budget of one move: interval pieces evaluated before the move is refused.
constexpr std::size_t sliced_move_budget = 40000;
/// The work budget of a whole certificate (every move's pieces together): a forged path of
/// grazing moves costs hipair-verify about a minute at most (about 0.5 ms a piece on a 10 mm peg).
constexpr std::size_t sliced_total_budget = 100000;

/// One move of a sliced claim proved free by bisection (session 72: the planar claim's path
/// moves and the pin-slot claim's steps share it). The move's parameter runs over [lo, hi]; a
/// piece [p0, p1] of it is proved when `apart(p0, p1)` (every configuration of the piece
/// certainly apart: the certified distance of the boundaries) holds, else halved; at a piece's
/// middle every sixth halving (depths 0, 6, 12, ...) the exact `overlap_at` (its evidence, "" when
/// the parts do not overlap there) refuses a blocked move early. A move that stays at one
/// configuration (`stay`) is tested once: apart, or refused (overlapping, or `not_apart`). Refused
/// too: a piece at depth `max_depth` (move_depth_limit) and more than `budget` pieces, the reasons
/// naming the parameter (`letter`) and the piece.
struct MoveBisection {
  Rational lo, hi;
  char letter = 'u';
  bool stay = false;
  long max_depth = 0;
  std::function<bool(const Rational& p0, const Rational& p1)> apart;
  std::function<std::string(const Rational& at)> overlap_at;
  std::string not_apart;
};
/// Why `move` is not proved free ("" when it is); `pieces` (optional) receives the pieces evaluated.
std::string move_bisection_failure(const MoveBisection& move, std::size_t budget, std::size_t* pieces = nullptr);
/// The depth at which a move's pieces are refused: 2^-(bits + 64 + k) of the move, k the bits of
/// `span` (the move's length in units of the part: at most 1024), bits the working interval
/// precision. A piece narrower than 2^-(bits + 64) of the move is not enclosed tighter than its
/// parent (the enclosures' rounding, relative to the move's size, dominates): the move is refused
/// there, in bounded time (a grazing move otherwise halves one end's piece until the budget runs
/// out); a move of 2^k units needs k more halvings before its pieces are short.
long move_depth_limit(const Rational& span);

/// Why the move from pose `a` to pose `b` of the planar part against the fixed part is not
/// certainly free ("" when it is proved free): not a pure translation, rotation or chart change,
/// the parts overlapping at an exact pose of the move, or a piece not proved apart within
/// `budget` evaluations. `pieces` (optional) receives the number of pieces evaluated.
std::string sliced_move_failure(const Part& fixed, const Part& planar, const PlanarPose& a, const PlanarPose& b,
                                std::size_t budget = sliced_move_budget, std::size_t* pieces = nullptr);
/// The model a connected claim of the pair (`fixed`, `planar`) is decided on: moved by
/// pair_moved_to_origin, then so that the planar part's pivot is the origin (the claim's poses are
/// relative: moving both parts moves the pivot with them); nullopt when that moves nothing. The
/// producer and the verifier both use it (a pair at 10^6 mm, under pair_moved_to_origin's
/// threshold, was otherwise checked there, its rotations' enclosures about 10^6 times wider).
std::optional<Model> connected_pair_at_origin(const Model& model, const std::string& fixed, const std::string& planar);
/// The pair of a sliced claim (connected, apart), checked: the certificate names the model
/// (check_certificate_model), the part posed at both ends is one of the envelope's two different
/// parts, free in the plane without motion limits, and the other is fixed; rejected otherwise, the
/// ends called `a_words` and `b_words` and the claim `claim` in the reasons. posed() is the model
/// the claim is decided on (connected_pair_at_origin).
struct SlicedPair {
  const Model* given = nullptr;
  std::optional<Model> moved;
  std::string planar_name, fixed_name;
  const Model& posed() const { return moved ? *moved : *given; }
  const Part& planar() const;
  const Part& fixed() const;
};
SlicedPair checked_sliced_pair(const Certificate& envelope, const Model& model, const PlanarPose& a, const PlanarPose& b,
                               const std::string& a_words, const std::string& b_words, const std::string& claim);
/// The exact map of a planar part at a pose (planar_check.cpp).
ExactMap planar_pose_map(const Part& part, const PlanarPose& pose);

// Shared from check.cpp.
/// The certificate names the model and its parameter values and roundings (check_model).
void check_certificate_model(const Certificate& c, const Model& model);
void check_nesting(const PlacedPart& a, const PlacedPart& b, const std::string& where);
/// The verdict of a check that returns its summary or throws a Rejection (or an Error).
VerificationResult verdict_of(const std::function<std::string()>& check);
bool read_certified_model(const Certificate& certificate, std::string_view text, const std::string& source_name,
                          Model& model, std::string& reason);

}  // namespace verify
}  // namespace hipair
