// HIPAIR — the `sliced_apart` certificate (docs/certify.md, "Poses of a planar pair that are not
// connected"): a part free in the plane (motion "planar") cannot move from one exact pose a to
// another b without touching a fixed part. The witness is a kd-tree of boxes over a domain D of
// poses (x, y, u): x and y the offset, u the angle coordinate (u in [-1, 1]: theta = 2 atan u;
// u in [1, 3]: theta = pi + 2 atan(u - 2); the full turn is u in [-1, 3] with u = -1 and u = 3 the
// same angle). Every split halves its box along one axis. Leaves labelled blocked carry a proof
// that every pose of the closed box overlaps (two edges that cross for every pose, or a point
// strictly inside both parts); every leaf touching D's non-periodic boundary is blocked, and the
// leaves not blocked, joined when their closed boxes meet (across the seam u = 3 / u = -1 for a
// full turn), leave a's and b's leaves in different components. Pin-slot claims (session 70): a
// part on a pin in a slot (motion "pin_slot") against a fixed, rotating or translating part, the
// domain's axes the other part's coordinate q, the slide s and the pin-slot part's angle u. Kept apart from the Certificate
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
  /// Pin-slot claims (a and b give a slide; session 70): the axes are q (the other part's
  /// coordinate: its angle coordinate u when it rotates, `other_full_turn` the periodic full turn
  /// [-1, 3]; its offset when it translates; none, [0, 0], when it is fixed), the slide s and the
  /// pin-slot part's angle u; `x` holds q's range and `y` s's; the tree's marks are q, s, u. A
  /// point proof's point is a world point (not relative to a pivot).
  bool pin_slot = false;
  bool other_full_turn = false;
  std::optional<ExactPosition> a_other, b_other;   ///< the other part's position at a and b (absent when fixed)
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

/// Certifies that the pin-slot part (a.part, motion "pin_slot") cannot move from (a, a_other)
/// to (b, b_other) without touching `other` (fixed: no positions; rotating: tangents; translating:
/// offsets): the same adaptive subdivision over the domain q x s x u: q the other's full turn or
/// its offset limits (a's offset +- its reach without), s the slide limits (a's slide +- h
/// without), the pin-slot part's full turn. Faces of the domain at a motion limit need no
/// blocked box (no motion crosses them).
/// \throws ModelError / GeometryError for parts that are not a pin-slot part and a fixed,
/// rotating or translating part, or positions that do not fit them.
SlicedApartResult certify_pin_slot_apart(const Model& model, const std::string& other, const PlanarPose& a,
                                         const std::optional<ExactPosition>& a_other, const PlanarPose& b,
                                         const std::optional<ExactPosition>& b_other, const CertifyContext& context = {},
                                         std::size_t max_leaves = 40000);

}  // namespace hipair
