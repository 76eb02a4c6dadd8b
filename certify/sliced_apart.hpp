// The verifier's internals of the sliced_apart certificate (<hipair/sliced_apart.hpp>): the kd-tree
// of boxes, its adjacency, the angle coordinate u and the blocked-box proofs, shared with the
// producer (src/certificates/sliced_apart.cpp). Internal.
#pragma once

#include <hipair/model.hpp>
#include <hipair/sliced_apart.hpp>

#include "certify/interval_geometry.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace hipair::verify {

/// Work limits of a certificate: leaves of its tree, and halvings from the domain to a leaf.
constexpr std::size_t apart_max_leaves = 400000;
constexpr std::size_t apart_max_depth = 160;

/// A box of poses: lo[k] .. hi[k] for k = 0 (x), 1 (y), 2 (u).
struct ApartBox {
  Rational lo[3], hi[3];
};

struct ApartTree {
  struct Node {
    ApartBox box;
    int axis = -1;                  ///< halved along (0, 1, 2), or -1 for a leaf
    std::size_t child = 0;          ///< a node's lower half (its upper half: child + 1 ... see halves)
    std::size_t upper = 0;          ///< a node's upper half
    bool blocked = false;           ///< a leaf's label
    std::size_t proof = 0;          ///< a blocked leaf's proof (index)
    std::size_t depth = 0;
  };
  std::vector<Node> nodes;          ///< nodes[0] the domain
  bool periodic = true;             ///< u = -1 and u = 3 are the same angle
  ApartBox domain() const { return nodes[0].box; }
};

/// The domain's box (x, y, the angle coordinate u; [-1, 3] for the full turn).
ApartBox apart_domain(const SlicedApartCertificate& c);
/// Reads the preorder tree over `domain`. \throws Rejection (malformed, too deep, too many leaves,
/// proofs not one per blocked leaf).
ApartTree parse_apart_tree(const std::string& tree, const ApartBox& domain, bool periodic, std::size_t proofs);
/// The preorder text of `tree` (the producer's).
std::string apart_tree_text(const ApartTree& tree);
/// Halves leaf `n` along `axis` (the producer's); returns the lower half's index.
std::size_t split_apart_leaf(ApartTree& tree, std::size_t n, int axis);

/// The angle coordinate of a pose (u in [-1, 3], see sliced_apart.hpp), exact.
Rational apart_u_of(const PlanarPose& pose);
/// The pose (x, y, u) of `part` (chart 0 for u <= 1, the chart centred at pi beyond).
PlanarPose apart_pose_at(const std::string& part, const Rational& x, const Rational& y, const Rational& u);
/// Every pose of the box, enclosed: theta is increasing and continuous in u over [-1, 3].
IntervalMap apart_box_map(const Part& planar, const ApartBox& box);
/// The box's middle pose (exact).
PlanarPose apart_middle_pose(const Part& planar, const ApartBox& box);

/// Why `proof` does not show every pose of `box` blocked ("" when it does).
std::string apart_proof_failure(const Part& fixed, const Part& planar, const ApartBox& box, const SlicedApartProof& proof);

/// Do the closed boxes meet (across the seam when periodic)?
bool apart_boxes_meet(const ApartBox& a, const ApartBox& b, bool periodic);
/// The leaves whose closed boxes meet `box` (leaf `skip` left out); `visited` (optional) counts the
/// tree's nodes tested.
void apart_leaves_meeting(const ApartTree& tree, const ApartBox& box, std::size_t skip, std::vector<std::size_t>& out,
                          std::size_t* visited = nullptr);
/// The verifier's work on the open leaves' adjacency: nodes tested, at most this many per node of
/// the tree (and 10^6 in all at least). A forged tree of 2^17 x-slabs meeting 2^17 y-slabs would
/// otherwise cost 10^10 box comparisons; an honest tree tests 20 to 40 per node (the 12 and
/// 14.14 mm holes' certificates): a forged tree of 400 000 leaves costs about a minute at most.
constexpr std::size_t apart_visits_per_node = 128;
/// The leaves whose closed boxes hold the pose (x, y, u).
std::vector<std::size_t> apart_leaves_at(const ApartTree& tree, const Rational& x, const Rational& y, const Rational& u);
/// Does the box touch the domain's non-periodic boundary?
bool apart_on_boundary(const ApartTree& tree, const ApartBox& box);

}  // namespace hipair::verify
