// The verifier's internals of the sliced_apart certificate (<hipair/sliced_apart.hpp>): the kd-tree
// of boxes, its adjacency, the angle coordinate u, how a box poses the pair (a planar part
// against a fixed one, or a pin-slot part against a fixed, rotating or translating one) and the
// blocked-box proofs, shared with the producer (src/certificates/sliced_apart.cpp). Internal.
#pragma once

#include <hipair/model.hpp>
#include <hipair/sliced_apart.hpp>

#include "certify/certificate_json.hpp"
#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace hipair::verify {

/// Work limits of a certificate, stated in its format (docs/certify.md): leaves of its tree,
/// halvings from the domain to a leaf, and box tests of the open leaves' adjacency (the whole
/// certificate's). A forged tree of slabs meeting slabs (2^17 x-slabs against 2^17 y-slabs:
/// 10^10 pairs) is refused after apart_max_box_tests tests, a few seconds; an honest tree tests
/// 20 to 40 boxes per node (the 14.14 mm hole's 32 499 leaves: 2.4 million).
constexpr std::size_t apart_max_leaves = 100000;
constexpr std::size_t apart_max_depth = 160;
constexpr std::size_t apart_max_box_tests = 10000000;
/// Point proofs cost each about one test per edge of the two parts (the certified distance from the
/// moving boundary, the exact location): at most this many edge tests in all (a forged certificate
/// of 100 000 point proofs against parts of hundreds of edges is refused before they are checked).
constexpr std::size_t apart_max_point_edge_tests = 4000000;

/// A box of poses: lo[k] .. hi[k] for k = 0 (x, or q), 1 (y, or s), 2 (u).
struct ApartBox {
  Rational lo[3], hi[3];
};

struct ApartTree {
  struct Node {
    ApartBox box;
    int axis = -1;                  ///< halved along (0, 1, 2), or -1 for a leaf
    std::size_t child = 0;          ///< a node's lower half
    std::size_t upper = 0;          ///< a node's upper half
    bool blocked = false;           ///< a leaf's label
    std::size_t proof = 0;          ///< a blocked leaf's proof (index)
    std::size_t depth = 0;
  };
  std::vector<Node> nodes;          ///< nodes[0] the domain
  /// Per axis: periodic (the full turn [-1, 3]: u = -1 and u = 3 the same angle); a face that
  /// needs no blocked leaf (a motion limit no motion crosses, or an axis of one value).
  bool periodic[3] = {false, false, true};
  bool closed_lo[3] = {false, false, false}, closed_hi[3] = {false, false, false};
  const char* marks = "xyu";        ///< the tree's letters for the three axes ("qsu" for pin-slot claims)
  ApartBox domain() const { return nodes[0].box; }
};

/// The domain's box and the tree's axes (periodic, marks) of a certificate; the faces at motion
/// limits are closed by the caller (apart_close_limits).
ApartTree apart_tree_of(const SlicedApartCertificate& c);
/// Reads the preorder tree into `tree` (holding the domain only). \throws Rejection (malformed,
/// too deep, too many leaves, a halving of an axis of one value, proofs not one per blocked leaf).
void parse_apart_tree(const std::string& text, ApartTree& tree, std::size_t proofs);
/// The preorder text of `tree` (the producer's).
std::string apart_tree_text(const ApartTree& tree);
/// Halves leaf `n` along `axis` (the producer's); returns the lower half's index.
std::size_t split_apart_leaf(ApartTree& tree, std::size_t n, int axis);

/// The angle coordinate of a pose (u in [-1, 3], see sliced_apart.hpp), exact.
Rational apart_u_of(const PlanarPose& pose);
Rational apart_u_of(const Rational& tangent, bool half_turn);
/// The pose (x, y, u) of `part` (chart 0 for u <= 1, the chart centred at pi beyond).
PlanarPose apart_pose_at(const std::string& part, const Rational& x, const Rational& y, const Rational& u);

/// The pair of an apart claim and how the domain's coordinates pose it: a planar part (x, y, u)
/// against a fixed part, or a pin-slot part (q, s, u) against a fixed, rotating (q its angle
/// coordinate) or translating (q its offset) part. Shapes made once.
struct ApartPair {
  ApartPair(const Part& other, const Part& moving);
  const Part& other;
  const Part& moving;
  bool pin_slot = false;
  IntervalPart other_shape, moving_shape;
  PlacedPart other_placed;          ///< the other part when fixed
  /// Exact maps at the coordinates (q or x, s or y, u), and the maps of every pose of a box.
  ExactMap moving_at(const Rational& x0, const Rational& x1, const Rational& u) const;
  ExactMap other_at(const Rational& q) const;
  IntervalMap moving_over(const ApartBox& box) const;
  IntervalMap other_over(const ApartBox& box) const;
  /// The coordinates of a claim's end (a pose and, for pin-slot claims, the other's position).
  void coordinates(const PlanarPose& pose, const std::optional<ExactPosition>& other_position, Rational out[3]) const;
};

/// The farthest a point of `part` lies from its pivot (its shape as if it only turned about it).
Rational reach_about_pivot(const Part& part);

/// The box's middle (exact).
void apart_middle(const ApartBox& box, Rational out[3]);
/// Every pose of the box of a planar part, enclosed: theta is increasing and continuous in u.
IntervalMap apart_box_map(const Part& planar, const ApartBox& box);
/// The box's middle pose of a planar part (exact).
PlanarPose apart_middle_pose(const Part& planar, const ApartBox& box);

/// Why `proof` does not show every pose of `box` blocked ("" when it does).
std::string apart_proof_failure(const ApartPair& pair, const ApartBox& box, const SlicedApartProof& proof);
/// Why the pin-slot end (coordinates `at`) is not certainly free ("" when it is): the certified
/// distance of the boundaries positive and no loop of one part inside the other (exact).
std::string apart_pin_slot_end_failure(const ApartPair& pair, const Rational at[3]);

/// The pin-slot pair of a sliced claim (apart, connected; session 71), checked: the certificate
/// names the model, the part posed at both ends (`a`, `b`: with a slide) is one of the envelope's
/// two different parts and sits on a pin in a slot, the other is fixed, rotating or translating,
/// its positions are given at both ends exactly when it moves and are of its kind, and both ends
/// lie within the motion limits (the slide exactly, angles certainly). Rejected otherwise, the
/// ends called `a_name` and `b_name` in the reasons.
struct PinSlotParts {
  const Part* other = nullptr;
  const Part* moving = nullptr;
};
PinSlotParts checked_pin_slot_pair(const Certificate& envelope, const Model& model, const PlanarPose& a, const PlanarPose& b,
                                   const std::optional<ExactPosition>& a_other, const std::optional<ExactPosition>& b_other,
                                   const std::string& a_name, const std::string& b_name);
/// Why a configuration of the box may lie outside the pair's motion limits ("" when every one
/// certainly lies within): the pin-slot part's slide and angle, the other part's offset or angle.
std::string apart_limits_failure(const ApartPair& pair, const ApartBox& box);
/// Do the coordinates `a` and `b` pose both parts alike (exact maps; u = 3 and u = -1 do)?
bool apart_same_configuration(const ApartPair& pair, const Rational a[3], const Rational b[3]);
/// Why the move of a pin-slot pair from coordinates `from` to `to` (one of q, s, u changing) is
/// not certainly free ("" when it is proved free): two coordinates changing, a configuration
/// outside the motion limits, the parts overlapping at an exact configuration of the move, or a
/// piece not proved apart (certified distance of the boundaries) within `budget` pieces or
/// 2^-(bits + 64 + k) of the move. `pieces` (optional) receives the pieces evaluated.
std::string apart_move_failure(const ApartPair& pair, const Rational from[3], const Rational to[3], std::size_t budget,
                               std::size_t* pieces = nullptr);
/// The other part's position in claims' words: "t=1/3", "t(pi)=0", "offset 2".
std::string position_words(const ExactPosition& p);
/// A claim's end in words: the pose (sliced_pose_words) and, when given, "('OTHER' at POSITION)".
std::string sliced_end_words(const PlanarPose& pose, const std::optional<ExactPosition>& position, const std::string& other);
/// Reads a position {"tangent": "t", "centre": "pi"?} (rotating) or {"offset": "s"} (translating).
ExactPosition read_position(const certificate_json::JsonValue& value);

/// Do the closed boxes meet (across the seam of each periodic axis)?
bool apart_boxes_meet(const ApartBox& a, const ApartBox& b, const bool periodic[3]);
/// The leaves whose closed boxes meet `box` (leaf `skip` left out); `visited` (optional) counts the
/// tree's nodes tested.
void apart_leaves_meeting(const ApartTree& tree, const ApartBox& box, std::size_t skip, std::vector<std::size_t>& out,
                          std::size_t* visited = nullptr);
/// The leaves whose closed boxes hold the point `at`.
std::vector<std::size_t> apart_leaves_at(const ApartTree& tree, const Rational at[3]);
/// Does the box touch a face of the domain that must be walled (not periodic, not closed)?
bool apart_on_boundary(const ApartTree& tree, const ApartBox& box);

}  // namespace hipair::verify
