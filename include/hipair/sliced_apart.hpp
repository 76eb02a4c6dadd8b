// HIPAIR — the `sliced_apart` certificate (docs/certify.md, "Poses of a planar pair that are not
// connected"): a part free in the plane (motion "planar") cannot move from one exact pose a to
// another b without touching a fixed part. The witness is a kd-tree of boxes over a domain D of
// poses (x, y, u): x and y the offset, u the angle coordinate (u in [-1, 1]: theta = 2 atan u;
// u in [1, 3]: theta = pi + 2 atan(u - 2); the full turn is u in [-1, 3] with u = -1 and u = 3 the
// same angle). Every split halves its box along one axis. Leaves labelled blocked carry a proof
// that every pose of the closed box overlaps (two edges that cross for every pose, or a point
// strictly inside both parts); every leaf touching D's non-periodic boundary is blocked, and the
// leaves not blocked, joined when their closed boxes meet (across the seam u = 3 / u = -1 for a
// full turn), leave a's and b's leaves in different components. Kept apart from the Certificate
// struct (<hipair/certificate.hpp> is widely included): its own reader and writer.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

/// Why every pose of a blocked leaf's closed box overlaps.
struct SlicedApartProof {
  enum class Kind { cross, point } kind = Kind::cross;
  /// cross: edge (edge_loop, edge) of the planar part (`planar_edge`) or of the fixed part, its
  /// piece `along` (segment fraction, or arc angle from its source), crosses edge (across_loop,
  /// across) of the other part for every pose of the box (crossing_certain).
  bool planar_edge = true;
  std::size_t edge_loop = 0, edge = 0, across_loop = 0, across = 0;
  RationalInterval along{Rational(0), Rational(1)};
  /// point: a point, relative to the planar part's pivot, strictly inside the fixed part and,
  /// for every pose of the box, strictly inside the posed planar part.
  Point point{Rational(0), Rational(0)};
};

struct SlicedApartCertificate {
  Certificate envelope;   ///< statement, model identity, pair (its claim field unused)
  PlanarPose a, b;        ///< the claim: two poses of the planar part (`part` names it)
  RationalInterval x, y;  ///< the domain's offsets
  bool full_turn = true;  ///< the domain's angles: the full turn (u in [-1, 3], periodic) or `u`
  RationalInterval u{Rational(-1), Rational(3)};
  /// The kd-tree in preorder: 'x', 'y', 'u' a node halved along that axis (its two halves follow,
  /// the lower first), 'o' an open leaf, 'b' a blocked leaf (its proof the next of `proofs`).
  std::string tree;
  std::vector<SlicedApartProof> proofs;
};

/// Is `json_text` a certificate whose claim is "sliced_apart"? (false when it does not parse)
bool is_sliced_apart_certificate(std::string_view json_text);
/// \throws ModelError at a JSON pointer (strict, as read_certificate).
SlicedApartCertificate read_sliced_apart_certificate(std::string_view json_text);
std::string write_sliced_apart_certificate(const SlicedApartCertificate& certificate);
/// The claim in words, a function of the claim's data (names and the two poses).
std::string sliced_apart_statement(const SlicedApartCertificate& certificate);
/// Checks the claim against `model` (identity, parts, ends free, the tree's proofs, boundary,
/// components, statement); within fixed work limits (leaves, depth).
VerificationResult check_sliced_apart(const SlicedApartCertificate& certificate, const Model& model);
VerificationResult check_sliced_apart_text(const SlicedApartCertificate& certificate, std::string_view text,
                                           const std::string& source_name);

/// What certify_sliced_apart found.
struct SlicedApartResult {
  std::optional<SlicedApartCertificate> certificate;   ///< self-checked by the verifier's code
  std::string failure;                                 ///< why there is none (unproven, never "connected" as a fact)
  std::size_t leaves = 0, blocked = 0;                 ///< the last tree tried
};

/// Certifies that the planar part cannot move from `a` to `b` without touching `fixed`: an
/// adaptive subdivision of domains around a (offsets a's +- h, h from 1/64 of the planar part's
/// reach up to its reach, the full turn), each box proved blocked (crossing edges, a point inside
/// both), proved free or split along a path of open boxes from a to b until none is left.
/// At most `max_leaves` leaves per domain: beyond, `failure` says so (unproven).
/// \throws ModelError / GeometryError for parts that are not a fixed part and a planar part.
SlicedApartResult certify_sliced_apart(const Model& model, const std::string& fixed, const PlanarPose& a, const PlanarPose& b,
                                       const CertifyContext& context = {}, std::size_t max_leaves = 40000);

}  // namespace hipair
