// The sliced_apart certificate: reader, statement, the kd-tree of boxes and the verifier's check
// (<hipair/sliced_apart.hpp>, docs/certify.md "Poses of a planar pair that are not connected").
// The check uses only the verifier's own exact and interval geometry.
#include "certify/sliced_apart.hpp"

#include "certify/certificate_json.hpp"
#include "certify/interval_geometry.hpp"
#include "certify/planar_check.hpp"
#include "certify/sliced_connected.hpp"
#include "certify/tolerance_support.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <numeric>

namespace hipair {
namespace {

using certificate_json::JsonValue;
const char* const claim_name = "sliced_apart";

[[noreturn]] void reject(const std::string& reason) { throw verify::Rejection{reason}; }

std::string text(const Rational& r) { return verify::fraction_or_rounded(r); }

std::string pose_words(const PlanarPose& p) {
  return "x=" + text(p.x) + ", y=" + text(p.y) + (p.half_turn ? ", t(pi)=" : ", t=") + text(p.tangent);
}

std::string box_words(const verify::ApartBox& b) {
  return "x in [" + text(b.lo[0]) + ", " + text(b.hi[0]) + "], y in [" + text(b.lo[1]) + ", " + text(b.hi[1]) + "], u in [" +
         text(b.lo[2]) + ", " + text(b.hi[2]) + "]";
}

RationalInterval range_of(const JsonValue& value) {
  const JsonValue& items = certificate_json::read_array(value);
  if (items.items.size() != 2) certificate_json::refuse(value, "a range is [\"lo\", \"hi\"]");
  RationalInterval r{certificate_json::read_rational(items.items[0]), certificate_json::read_rational(items.items[1])};
  if (!(r.lo < r.hi)) certificate_json::refuse(value, "a range needs lo < hi");
  return r;
}

std::size_t index_of(const JsonValue& value) {
  Rational r = certificate_json::read_rational(value);
  if (r.get_den() != 1 || sgn(r) < 0 || r > Rational(1 << 30)) certificate_json::refuse(value, "an index is a whole number >= 0");
  return std::size_t(r.get_num().get_ui());
}

SlicedApartProof proof_of(const JsonValue& value) {
  const JsonValue& items = certificate_json::read_array(value);
  if (items.items.empty()) certificate_json::refuse(value, "a proof is [\"cross\", ...] or [\"point\", \"x\", \"y\"]");
  const std::string kind = certificate_json::read_text(items.items[0]);
  SlicedApartProof p;
  if (kind == "point") {
    if (items.items.size() != 3) certificate_json::refuse(value, "a point proof is [\"point\", \"x\", \"y\"]");
    p.kind = SlicedApartProof::Kind::point;
    p.point = Point{certificate_json::read_rational(items.items[1]), certificate_json::read_rational(items.items[2])};
    return p;
  }
  if (kind != "cross" || items.items.size() != 8)
    certificate_json::refuse(value, "a proof is [\"cross\", \"planar\" | \"fixed\", loop, edge, loop, edge, \"lo\", \"hi\"] or "
                                    "[\"point\", \"x\", \"y\"]");
  const std::string owner = certificate_json::read_text(items.items[1]);
  if (owner != "planar" && owner != "fixed") certificate_json::refuse(items.items[1], "the crossing edge's part is \"planar\" or \"fixed\"");
  p.planar_edge = owner == "planar";
  p.edge_loop = index_of(items.items[2]);
  p.edge = index_of(items.items[3]);
  p.across_loop = index_of(items.items[4]);
  p.across = index_of(items.items[5]);
  p.along = RationalInterval{certificate_json::read_rational(items.items[6]), certificate_json::read_rational(items.items[7])};
  return p;
}

}  // namespace

bool is_sliced_apart_certificate(std::string_view json_text) { return certificate_json::has_claim(json_text, claim_name); }

SlicedApartCertificate read_sliced_apart_certificate(std::string_view json_text) {
  JsonValue root = model_detail::parse_json(json_text);
  SlicedApartCertificate c;
  const JsonValue& body = certificate_json::read_claim(root, claim_name, c.envelope);
  certificate_json::keys(body, {"a", "b", "domain", "tree", "proofs"});
  c.a = certificate_json::read_pose(certificate_json::member(body, "a"));
  c.b = certificate_json::read_pose(certificate_json::member(body, "b"));
  for (const PlanarPose* end : {&c.a, &c.b})
    if (end->slide) certificate_json::refuse(body, "an apart claim poses a planar part by x, y and tangent, not a slide");
  const JsonValue& domain = certificate_json::member(body, "domain");
  certificate_json::keys(domain, {"x", "y", "angle"});
  c.x = range_of(certificate_json::member(domain, "x"));
  c.y = range_of(certificate_json::member(domain, "y"));
  const JsonValue& angle = certificate_json::member(domain, "angle");
  if (angle.is_string()) {
    if (angle.text != "full") certificate_json::refuse(angle, "the angle range is \"full\" or [\"u0\", \"u1\"] within [-1, 3]");
  } else {
    c.full_turn = false;
    c.u = range_of(angle);
    if (c.u.lo < -1 || c.u.hi > 3) certificate_json::refuse(angle, "the angle range [\"u0\", \"u1\"] lies within [-1, 3]");
  }
  c.tree = certificate_json::read_text(certificate_json::member(body, "tree"));
  for (const JsonValue& proof : certificate_json::read_array(certificate_json::member(body, "proofs")).items)
    c.proofs.push_back(proof_of(proof));
  return c;
}

std::string sliced_apart_statement(const SlicedApartCertificate& c) {
  const std::string& fixed = c.envelope.first == c.a.part ? c.envelope.second : c.envelope.first;
  return "Part '" + c.a.part + "' cannot move from " + pose_words(c.a) + " to " + pose_words(c.b) + " without touching part '" +
         fixed + "'.";
}

namespace verify {

ApartBox apart_domain(const SlicedApartCertificate& c) {
  ApartBox d;
  d.lo[0] = c.x.lo, d.hi[0] = c.x.hi, d.lo[1] = c.y.lo, d.hi[1] = c.y.hi;
  d.lo[2] = c.full_turn ? Rational(-1) : c.u.lo;
  d.hi[2] = c.full_turn ? Rational(3) : c.u.hi;
  return d;
}

std::size_t split_apart_leaf(ApartTree& tree, std::size_t n, int axis) {
  ApartTree::Node lower, upper;
  {
    const ApartTree::Node& node = tree.nodes[n];
    lower.box = upper.box = node.box;
    const Rational middle = (node.box.lo[axis] + node.box.hi[axis]) / 2;
    lower.box.hi[axis] = middle;
    upper.box.lo[axis] = middle;
    lower.depth = upper.depth = node.depth + 1;
  }
  const std::size_t first = tree.nodes.size();
  tree.nodes.push_back(lower);
  tree.nodes.push_back(upper);
  tree.nodes[n].axis = axis;
  tree.nodes[n].child = first;
  tree.nodes[n].upper = first + 1;
  tree.nodes[n].blocked = false;
  return first;
}

ApartTree parse_apart_tree(const std::string& text, const ApartBox& domain, bool periodic, std::size_t proofs) {
  ApartTree tree;
  tree.periodic = periodic;
  tree.nodes.push_back(ApartTree::Node{});
  tree.nodes[0].box = domain;
  std::size_t at = 0, leaves = 0, proof = 0;
  std::vector<std::size_t> stack{0};   // nodes still to read, next on top
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    if (at >= text.size()) reject("the tree ends before it covers the domain (a box is missing after " + std::to_string(at) + " marks)");
    const char mark = text[at++];
    if (mark == 'x' || mark == 'y' || mark == 'u') {
      if (tree.nodes[n].depth >= apart_max_depth)
        reject("the tree is deeper than " + std::to_string(apart_max_depth) + " halvings (mark " + std::to_string(at - 1) + ")");
      const std::size_t first = split_apart_leaf(tree, n, mark == 'x' ? 0 : mark == 'y' ? 1 : 2);
      stack.push_back(first + 1);
      stack.push_back(first);
    } else if (mark == 'o' || mark == 'b') {
      if (++leaves > apart_max_leaves) reject("the tree has more than " + std::to_string(apart_max_leaves) + " leaves");
      if (mark == 'b') {
        if (proof >= proofs) reject("the tree has more blocked leaves than proofs (" + std::to_string(proofs) + ")");
        tree.nodes[n].blocked = true;
        tree.nodes[n].proof = proof++;
      }
    } else {
      reject("the tree's mark " + std::to_string(at - 1) + " is not x, y, u, o or b");
    }
  }
  if (at != text.size()) reject("the tree has " + std::to_string(text.size() - at) + " marks after its last box");
  if (proof != proofs) reject("the certificate has " + std::to_string(proofs) + " proofs for " + std::to_string(proof) + " blocked leaves");
  return tree;
}

std::string apart_tree_text(const ApartTree& tree) {
  std::string out;
  std::vector<std::size_t> stack{0};
  while (!stack.empty()) {
    const ApartTree::Node& node = tree.nodes[stack.back()];
    stack.pop_back();
    if (node.axis >= 0) {
      out += "xyu"[node.axis];
      stack.push_back(node.upper);
      stack.push_back(node.child);
    } else {
      out += node.blocked ? 'b' : 'o';
    }
  }
  return out;
}

Rational apart_u_of(const PlanarPose& pose) {
  const Rational& t = pose.tangent;
  const bool small = abs(t) <= 1;
  if (!pose.half_turn) return small ? t : Rational(2 - 1 / t);
  return small ? Rational(2 + t) : Rational(-1 / t);
}

PlanarPose apart_pose_at(const std::string& part, const Rational& x, const Rational& y, const Rational& u) {
  return u <= 1 ? PlanarPose{part, x, y, u, false, std::nullopt} : PlanarPose{part, x, y, Rational(u - 2), true, std::nullopt};
}

namespace {
Interval theta_of(const Rational& u) { return u <= 1 ? angle_of_tangent(u, false) : angle_of_tangent(Rational(u - 2), true); }
Interval hull_of(const Rational& lo, const Rational& hi) { return hull2(Interval(lo), Interval(hi)); }
}  // namespace

IntervalMap apart_box_map(const Part& planar, const ApartBox& box) {
  const Interval angle = hull2(theta_of(box.lo[2]), theta_of(box.hi[2]));   // theta increases with u
  IntervalMap m;
  m.c = cos_of(angle);
  m.s = sin_of(angle);
  const Interval px(planar.motion.pivot.x), py(planar.motion.pivot.y);
  m.shift.x = px - (m.c * px - m.s * py) + hull_of(box.lo[0], box.hi[0]);
  m.shift.y = py - (m.s * px + m.c * py) + hull_of(box.lo[1], box.hi[1]);
  return m;
}

PlanarPose apart_middle_pose(const Part& planar, const ApartBox& box) {
  return apart_pose_at(planar.name, (box.lo[0] + box.hi[0]) / 2, (box.lo[1] + box.hi[1]) / 2, (box.lo[2] + box.hi[2]) / 2);
}

std::string apart_proof_failure(const Part& fixed, const Part& planar, const ApartBox& box, const SlicedApartProof& proof) {
  if (proof.kind == SlicedApartProof::Kind::point) {
    const Point p{Rational(planar.motion.pivot.x + proof.point.x), Rational(planar.motion.pivot.y + proof.point.y)};
    if (locate(place(fixed, ExactMap{}), p) <= 0) return "the point is not strictly inside '" + fixed.name + "'";
    if (sgn(point_boundary_distance_lower_bound(shape_of(planar), apart_box_map(planar, box), p, Rational(1))) <= 0)
      return "the point is not certainly off the boundary of '" + planar.name + "' over the box";
    if (locate(place(planar, planar_pose_map(planar, apart_middle_pose(planar, box))), p) <= 0)
      return "the point is not strictly inside '" + planar.name + "' at the box's middle";
    return "";
  }
  auto single = [&](const Part& owner, std::size_t loop, std::size_t edge, bool moving) -> std::optional<IntervalEdge> {
    if (loop >= owner.loops.size() || edge >= owner.loops[loop].edges.size()) return std::nullopt;
    Part one;   // the one edge, moving like its part
    one.name = owner.name;
    one.motion = owner.motion;
    one.loops.push_back(Loop{{owner.loops[loop].edges[edge]}, false, ""});
    return place_over(one, moving ? apart_box_map(planar, box) : IntervalMap{}).loops[0][0];
  };
  const Part& first = proof.planar_edge ? planar : fixed;
  const Part& second = proof.planar_edge ? fixed : planar;
  std::optional<IntervalEdge> e = single(first, proof.edge_loop, proof.edge, proof.planar_edge);
  std::optional<IntervalEdge> g = single(second, proof.across_loop, proof.across, !proof.planar_edge);
  if (!e) return "part '" + first.name + "' has no loop " + std::to_string(proof.edge_loop) + " edge " + std::to_string(proof.edge);
  if (!g) return "part '" + second.name + "' has no loop " + std::to_string(proof.across_loop) + " edge " + std::to_string(proof.across);
  std::string why;
  if (!crossing_certain(*e, proof.along, *g, &why)) return "the crossing does not hold over the box: " + why;
  return "";
}

bool apart_boxes_meet(const ApartBox& a, const ApartBox& b, bool periodic) {
  for (int k = 0; k < 2; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  if (!(a.hi[2] < b.lo[2] || b.hi[2] < a.lo[2])) return true;
  return periodic && ((a.hi[2] == 3 && b.lo[2] == -1) || (b.hi[2] == 3 && a.lo[2] == -1));
}

void apart_leaves_meeting(const ApartTree& tree, const ApartBox& box, std::size_t skip, std::vector<std::size_t>& out,
                          std::size_t* visited) {
  std::vector<std::size_t> stack{0};
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    if (visited) ++*visited;
    const ApartTree::Node& node = tree.nodes[n];
    if (!apart_boxes_meet(node.box, box, tree.periodic)) continue;
    if (node.axis >= 0) {
      stack.push_back(node.child);
      stack.push_back(node.upper);
    } else if (n != skip) {
      out.push_back(n);
    }
  }
}

std::vector<std::size_t> apart_leaves_at(const ApartTree& tree, const Rational& x, const Rational& y, const Rational& u) {
  ApartBox point;
  point.lo[0] = point.hi[0] = x, point.lo[1] = point.hi[1] = y, point.lo[2] = point.hi[2] = u;
  const ApartBox& d = tree.nodes[0].box;
  for (int k = 0; k < 3; ++k)
    if (point.lo[k] < d.lo[k] || point.hi[k] > d.hi[k]) return {};
  std::vector<std::size_t> out;
  // (a point meets a box across the seam only at u = -1 or 3, where it lies in the box's face
  // on the other side too: apart_boxes_meet joins them)
  apart_leaves_meeting(tree, point, std::size_t(-1), out);
  return out;
}

bool apart_on_boundary(const ApartTree& tree, const ApartBox& box) {
  const ApartBox& d = tree.nodes[0].box;
  for (int k = 0; k < 3; ++k) {
    if (k == 2 && tree.periodic) break;
    if (box.lo[k] == d.lo[k] || box.hi[k] == d.hi[k]) return true;
  }
  return false;
}

}  // namespace verify

VerificationResult check_sliced_apart(const SlicedApartCertificate& c, const Model& model) {
  using namespace verify;
  return verdict_of([&] {
    const SlicedPair pair = checked_sliced_pair(c.envelope, model, c.a, c.b, "a", "b", "apart");
    const std::string &name = pair.planar_name, &fixed_name = pair.fixed_name;
    const Part &planar = pair.planar(), &fixed = pair.fixed();
    if (!(c.x.lo < c.x.hi) || !(c.y.lo < c.y.hi) || (!c.full_turn && !(c.u.lo < c.u.hi && c.u.lo >= -1 && c.u.hi <= 3)))
      reject("the domain is empty or its angle range leaves [-1, 3]");
    const ApartTree tree = parse_apart_tree(c.tree, apart_domain(c), c.full_turn, c.proofs.size());
    // both ends free (the claim is about two poses of the free space)
    for (const PlanarPose* end : {&c.a, &c.b}) {
      const std::string which = end == &c.a ? "a" : "b";
      std::string failure = sliced_move_failure(fixed, planar, *end, *end);
      if (!failure.empty()) reject("the end " + which + " (" + pose_words(*end) + ") is not certainly free: " + failure);
      check_nesting(place(fixed, ExactMap{}), place(planar, planar_pose_map(planar, *end)), "at the end " + which);
    }
    // every leaf on the domain's boundary blocked, then the open leaves' components
    std::size_t leaves = 0, open = 0;
    std::vector<std::size_t> parent(tree.nodes.size());
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto root = [&](std::size_t n) {
      while (parent[n] != n) n = parent[n] = parent[parent[n]];
      return n;
    };
    std::vector<std::size_t> around;
    std::size_t visited = 0;
    const std::size_t visit_budget = std::max<std::size_t>(1000000, apart_visits_per_node * tree.nodes.size());
    for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
      const ApartTree::Node& node = tree.nodes[n];
      if (node.axis >= 0) continue;
      ++leaves;
      if (node.blocked) continue;
      ++open;
      if (apart_on_boundary(tree, node.box))
        reject("the open leaf " + box_words(node.box) + " touches the domain's boundary (every leaf there must be blocked)");
      around.clear();
      apart_leaves_meeting(tree, node.box, n, around, &visited);
      if (visited > visit_budget)
        reject("the open leaves' adjacency needs more than " + std::to_string(visit_budget) + " box tests (" +
               std::to_string(apart_visits_per_node) + " per node of the tree)");
      for (std::size_t m : around)
        if (!tree.nodes[m].blocked) parent[root(m)] = root(n);
    }
    auto open_at = [&](const PlanarPose& p, const std::string& which) {
      std::vector<std::size_t> found, components;
      found = apart_leaves_at(tree, p.x, p.y, apart_u_of(p));
      if (found.empty()) reject("the end " + which + " (" + pose_words(p) + ") lies outside the domain");
      for (std::size_t n : found)
        if (!tree.nodes[n].blocked) components.push_back(root(n));
      if (components.empty()) reject("the end " + which + " lies in blocked leaves only");
      return components;
    };
    const std::vector<std::size_t> at_a = open_at(c.a, "a"), at_b = open_at(c.b, "b");
    for (std::size_t k : at_a)
      if (std::find(at_b.begin(), at_b.end(), k) != at_b.end())
        reject("a and b lie in one component of the open leaves (" + box_words(tree.nodes[k].box) + " and its neighbours)");
    // every blocked leaf's proof
    std::size_t blocked = 0;
    for (const ApartTree::Node& node : tree.nodes) {
      if (node.axis >= 0 || !node.blocked) continue;
      ++blocked;
      std::string failure = apart_proof_failure(fixed, planar, node.box, c.proofs[node.proof]);
      if (!failure.empty()) reject("the blocked leaf " + box_words(node.box) + " (proof " + std::to_string(node.proof) + "): " + failure);
    }
    const std::string expected = sliced_apart_statement(c);
    if (c.envelope.statement != expected)
      reject("the statement does not say what the claim's data prove: it reads '" + c.envelope.statement.substr(0, 400) +
             "', the claim's data give '" + expected + "'");
    return std::string(claim_name) + ": part '" + name + "' cannot move from " + pose_words(c.a) + " to " + pose_words(c.b) +
           " without touching '" + fixed_name + "' (" + std::to_string(leaves) + " boxes, " + std::to_string(blocked) +
           " proved blocked, none open on the domain's boundary, the ends in different components of the " +
           std::to_string(open) + " open ones; " + std::to_string(visited) + " box tests)";
  });
}

VerificationResult check_sliced_apart_text(const SlicedApartCertificate& c, std::string_view text, const std::string& source_name) {
  Model model;
  std::string reason;
  if (verify::read_certified_model(c.envelope, text, source_name, model, reason)) return check_sliced_apart(c, model);
  VerificationResult refused;
  refused.reason = reason;
  return refused;
}

}  // namespace hipair
