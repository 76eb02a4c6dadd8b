// label_edges' interval filter for every curve at every edge's sample, through a k-d tree of the
// samples' boxes (docs/performance.md, session 41 fast41). The plain filter evaluates each
// curve's enclosure over each edge's sample box (curves x edges enclosures); here a curve's
// enclosure over the hull of a group of boxes that certainly excludes zero drops the whole
// group (the curve has no zero in the hull, so none at any sample there, and the exact test
// would reject each), and the boxes of the groups it cannot drop get the plain test, box by box.
#pragma once

#include "algebra/exact_real.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace hipair::cspace {

/// A sample's box: {x, y} enclosures of the sample point.
using SampleBox = std::array<algebra::Interval, 2>;

/// Per box e (ascending curve indices): the curves k whose enclosure over box e contains zero
/// (`curves[k].evaluate(x, y).contains_zero()`, the plain filter), except curves that certainly
/// have no zero in a hull of boxes holding box e (enclosure over the hull > 0 or < 0; a NaN or
/// a zero-holding enclosure drops nothing). Every pair (e, k) this lists passes the plain
/// filter, and every pair the plain filter passes with a zero of curve k in box e is listed.
inline std::vector<std::vector<std::size_t>> curves_at_samples(const std::vector<algebra::IntervalPolynomial2>& curves,
                                                               const std::vector<SampleBox>& boxes) {
  std::vector<std::vector<std::size_t>> out(boxes.size());
  if (boxes.empty() || curves.empty()) return out;
  // the tree: boxes ordered so that a node holds the range [begin, end) of `order`; a node's
  // hull encloses its boxes; children split at the median of the longer side's centres
  struct Node {
    std::size_t begin, end;
    SampleBox hull;
    std::size_t left = 0, right = 0;   // children (0: a leaf; node 0 is the root)
  };
  constexpr std::size_t leaf_size = 2;
  std::vector<std::size_t> order(boxes.size());
  for (std::size_t e = 0; e < order.size(); ++e) order[e] = e;
  std::vector<Node> nodes;
  nodes.reserve(2 * boxes.size());
  auto centre = [&](std::size_t e, int axis) { return boxes[e][axis].lo / 2 + boxes[e][axis].hi / 2; };
  auto build = [&](auto& self, std::size_t begin, std::size_t end) -> std::size_t {
    const std::size_t index = nodes.size();
    SampleBox hull = boxes[order[begin]];
    for (std::size_t i = begin + 1; i < end; ++i)
      for (int axis = 0; axis < 2; ++axis) {
        hull[axis].lo = std::min(hull[axis].lo, boxes[order[i]][axis].lo);
        hull[axis].hi = std::max(hull[axis].hi, boxes[order[i]][axis].hi);
      }
    nodes.push_back(Node{begin, end, hull});
    if (end - begin <= leaf_size) return index;
    const int axis = hull[0].hi - hull[0].lo >= hull[1].hi - hull[1].lo ? 0 : 1;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(middle),
                     order.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](std::size_t a, std::size_t b) { return centre(a, axis) < centre(b, axis); });
    const std::size_t left = self(self, begin, middle);
    const std::size_t right = self(self, middle, end);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  };
  build(build, 0, boxes.size());
  std::vector<std::size_t> stack;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const algebra::IntervalPolynomial2& curve = curves[k];
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Node& node = nodes[stack.back()];
      stack.pop_back();
      if (node.left == 0) {
        for (std::size_t i = node.begin; i < node.end; ++i) {
          const std::size_t e = order[i];
          if (curve.evaluate(boxes[e][0], boxes[e][1]).contains_zero()) out[e].push_back(k);
        }
        continue;
      }
      const algebra::Interval at = curve.evaluate(node.hull[0], node.hull[1]);
      if (at.lo > 0 || at.hi < 0) continue;   // certainly no zero in the hull
      stack.push_back(node.right);
      stack.push_back(node.left);
    }
  }
  return out;
}

}  // namespace hipair::cspace
