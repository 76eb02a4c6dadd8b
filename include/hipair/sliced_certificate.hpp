// HIPAIR — the `sliced_connected` certificate (docs/certify.md, "Connected poses of a planar
// pair"): a part free in the plane (motion "planar") can move from one exact pose (x, y, theta)
// to another without touching a fixed part. The witness is a staircase path of exact poses:
// each move between consecutive ones a pure translation at a fixed rational rotation, a pure
// rotation about the part's pivot at a fixed rational offset (linear in the half-angle tangent of
// the vertices' chart, centre 0 or pi), or a change of chart at one pose. hipair-verify proves
// every move free by certified interval subdivision and the start free of nesting exactly,
// without the sliced C-space. Kept apart from the Certificate struct (<hipair/certificate.hpp> is
// widely included): its own reader and writer over the same envelope.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

struct SlicedConnectedCertificate {
  Certificate envelope;            ///< statement, model identity, pair (its claim field unused)
  PlanarPose from, to;             ///< the claim: both poses of the planar part (`part` names it)
  std::vector<PlanarPose> path;    ///< the witness: from ... to, consecutive poses one move apart
  /// Pin-slot claims (session 71: `from` and `to` give a slide): a part on a pin in a slot against
  /// a fixed, rotating or translating part. `from_other` / `to_other` the other part's positions
  /// (absent when it is fixed); the witness is `steps` (not `path`): configurations in the
  /// coordinates (q, s, u) of sliced_apart's pin-slot domain (<hipair/sliced_apart.hpp>: q the
  /// other's angle coordinate or offset, 0 when fixed; s the slide; u the pin-slot part's angle
  /// coordinate), consecutive ones differing in one coordinate, or the same configuration.
  bool pin_slot = false;
  std::optional<ExactPosition> from_other, to_other;
  std::vector<std::array<Rational, 3>> steps;
};

/// Is `json_text` a certificate whose claim is "sliced_connected"? (false when it does not parse)
bool is_sliced_connected_certificate(std::string_view json_text);
/// \throws ModelError at a JSON pointer (strict, as read_certificate).
SlicedConnectedCertificate read_sliced_connected_certificate(std::string_view json_text);
std::string write_sliced_connected_certificate(const SlicedConnectedCertificate& certificate);
/// The claim in words, a function of the claim's data (names and the two poses).
std::string sliced_connected_statement(const SlicedConnectedCertificate& certificate);
/// Checks the claim against `model` (model identity, parts, ends, every move, nesting, statement).
VerificationResult check_sliced_connected(const SlicedConnectedCertificate& certificate, const Model& model);
/// The same against the model file's text (content hash, parameter values first).
VerificationResult check_sliced_connected_text(const SlicedConnectedCertificate& certificate, std::string_view text,
                                               const std::string& source_name);

/// What certify_sliced_connected found.
struct SlicedConnectedResult {
  std::optional<SlicedConnectedCertificate> certificate;   ///< self-checked by the verifier's code
  /// Why there is none: an end not free, the ends in different components of the sliced free
  /// space (not certified: the verdict of the cell structure only), no path found, or a move the
  /// staircase could not prove free.
  std::string failure;
  std::size_t sliced_waypoints = 0;   ///< waypoints of the sliced C-space's path (pin-slot claims: the boxes of the free chain, 0 for a direct walk)
};

/// Certifies that the planar part can move from `from` to `to` without touching the fixed part
/// `fixed`: the sliced C-space's path (SlicedSpace::path), turned into a staircase of pure
/// translations and rotations each proved free by the verifier's own move check (diagonal
/// motions split until their staircase steps are), then the whole certificate re-checked.
/// \throws ModelError / GeometryError for parts that are not a fixed part and a planar part.
SlicedConnectedResult certify_sliced_connected(const Model& model, const std::string& fixed, const PlanarPose& from,
                                               const PlanarPose& to, const CertifyContext& context = {});

/// The same for a path of the sliced C-space (SlicedSpace::path, status found: straight motions in
/// (x, y, w), w the half-angle tangent of the motion's chart), which may have diagonal motions;
/// the claim is its first and last waypoint. A caller's path is taken as a proposal: nothing in
/// it is trusted (each staircase move is proved free by the verifier's check).
struct SlicedPath;
SlicedConnectedResult certify_sliced_path(const Model& model, const std::string& fixed, const std::string& planar,
                                          const SlicedPath& path, const CertifyContext& context = {});

/// Certifies that the pin-slot part (from.part, motion "pin_slot") can move from (from,
/// from_other) to (to, to_other) without touching `other` (fixed: no positions; rotating:
/// tangents; translating: offsets), within the parts' motion limits: sliced_apart's adaptive
/// subdivision over (q, s, u) (within the limits) until a chain of boxes proved free joins the
/// ends, then a staircase through the chain's shared faces, each move proved free by the
/// verifier's own check. At most `max_leaves` boxes: beyond, `failure` says so.
/// \throws ModelError / GeometryError for parts that are not a pin-slot part and a fixed, rotating
/// or translating part, or positions that do not fit them.
SlicedConnectedResult certify_pin_slot_connected(const Model& model, const std::string& other, const PlanarPose& from,
                                                 const std::optional<ExactPosition>& from_other, const PlanarPose& to,
                                                 const std::optional<ExactPosition>& to_other, const CertifyContext& context = {},
                                                 std::size_t max_leaves = 40000);

}  // namespace hipair
