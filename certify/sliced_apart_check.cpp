// The sliced_apart certificate: reader, statement, the kd-tree of boxes and the verifier's check
// (<hipair/sliced_apart.hpp>, docs/certify.md "Poses of a planar pair that are not connected").
// The check uses only the verifier's own exact and interval geometry.
#include "certify/sliced_apart.hpp"

#include "certify/certificate_json.hpp"
#include "certify/interval_geometry.hpp"
#include "certify/planar_check.hpp"
#include "certify/sliced_connected.hpp"
#include "certify/tolerance_support.hpp"
#include "core/model_scale.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <numeric>
#include <optional>
#include <utility>

namespace hipair {
namespace {

using certificate_json::JsonValue;
using verify::fraction_or_rounded;
using verify::reject;
using verify::sliced_pose_words;
const char* const claim_name = "sliced_apart";

std::string box_words(const verify::ApartTree& tree, const verify::ApartBox& b) {
  std::string out;
  for (int k = 0; k < 3; ++k)
    out += std::string(k ? ", " : "") + tree.marks[k] + " in [" + fraction_or_rounded(b.lo[k]) + ", " + fraction_or_rounded(b.hi[k]) + "]";
  return out;
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
  certificate_json::keys(body, {"a", "b", "a_other", "b_other", "domain", "tree", "proofs"});
  c.a = certificate_json::read_pose(certificate_json::member(body, "a"));
  c.b = certificate_json::read_pose(certificate_json::member(body, "b"));
  c.pin_slot = bool(c.a.slide);
  if (bool(c.b.slide) != c.pin_slot)
    certificate_json::refuse(body, "both ends give a slide (a pin-slot part) or neither (a planar part: x, y and tangent)");
  for (const char* key : {"a_other", "b_other"})
    if (const JsonValue* other = body.find(key)) {
      if (!c.pin_slot) certificate_json::refuse(*other, "the other part's position belongs to pin-slot claims (ends with a slide)");
      (key[0] == 'a' ? c.a_other : c.b_other) = verify::read_position(*other);
    }
  if (bool(c.a_other) != bool(c.b_other)) certificate_json::refuse(body, "give the other part's position at both ends (a_other, b_other) or at neither");
  const JsonValue& domain = certificate_json::member(body, "domain");
  if (c.pin_slot) {
    certificate_json::keys(domain, {"other", "slide", "angle"});
    if (const JsonValue* other = domain.find("other")) {
      if (!c.a_other) certificate_json::refuse(*other, "a fixed other part (no a_other, b_other) has no range");
      if (other->is_string()) {
        if (other->text != "full" || c.a_other->is_offset)
          certificate_json::refuse(*other, "the other part's range is \"full\" (rotating) or [\"lo\", \"hi\"]");
        c.other_full_turn = true;
        c.x = RationalInterval{Rational(-1), Rational(3)};
      } else {
        c.x = range_of(*other);
      }
    } else {
      if (c.a_other) certificate_json::refuse(domain, "the domain needs the other part's range (\"other\")");
      c.x = RationalInterval{Rational(0), Rational(0)};
    }
    c.y = range_of(certificate_json::member(domain, "slide"));
  } else {
    certificate_json::keys(domain, {"x", "y", "angle"});
    c.x = range_of(certificate_json::member(domain, "x"));
    c.y = range_of(certificate_json::member(domain, "y"));
  }
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
  return "Part '" + c.a.part + "' cannot move from " + verify::sliced_end_words(c.a, c.a_other, fixed) + " to " +
         verify::sliced_end_words(c.b, c.b_other, fixed) +
         " without touching part '" + fixed + "'.";
}

namespace verify {

std::string position_words(const ExactPosition& p) {
  if (p.is_offset) return "offset " + fraction_or_rounded(p.value);
  return (p.half_turn ? "t(pi)=" : "t=") + fraction_or_rounded(p.value);
}

std::string sliced_end_words(const PlanarPose& pose, const std::optional<ExactPosition>& position, const std::string& other) {
  return sliced_pose_words(pose) + (position ? " ('" + other + "' at " + position_words(*position) + ")" : "");
}

ExactPosition read_position(const JsonValue& value) {
  certificate_json::keys(value, {"tangent", "centre", "offset"});
  ExactPosition p;
  p.is_offset = value.find("offset") != nullptr;
  if (p.is_offset == (value.find("tangent") != nullptr))
    certificate_json::refuse(value, "a position gives exactly one of \"tangent\" (rotating) and \"offset\" (translating)");
  p.value = certificate_json::read_rational(certificate_json::member(value, p.is_offset ? "offset" : "tangent"));
  if (const JsonValue* centre = value.find("centre")) {
    const std::string c = certificate_json::read_text(*centre);
    if (p.is_offset || (c != "pi" && c != "0")) certificate_json::refuse(*centre, "centre is \"0\" or \"pi\", for a tangent");
    p.half_turn = c == "pi";
  }
  return p;
}

ApartTree apart_tree_of(const SlicedApartCertificate& c) {
  ApartTree tree;
  ApartBox d;
  d.lo[0] = c.x.lo, d.hi[0] = c.x.hi, d.lo[1] = c.y.lo, d.hi[1] = c.y.hi;
  d.lo[2] = c.full_turn ? Rational(-1) : c.u.lo;
  d.hi[2] = c.full_turn ? Rational(3) : c.u.hi;
  tree.nodes.push_back(ApartTree::Node{});
  tree.nodes[0].box = d;
  tree.periodic[0] = c.pin_slot && c.other_full_turn;
  tree.periodic[1] = false;
  tree.periodic[2] = c.full_turn;
  tree.marks = c.pin_slot ? "qsu" : "xyu";
  for (int k = 0; k < 3; ++k)
    if (d.lo[k] == d.hi[k]) tree.closed_lo[k] = tree.closed_hi[k] = true;   // an axis of one value (a fixed other part)
  return tree;
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
  tree.nodes.push_back(std::move(lower));
  tree.nodes.push_back(std::move(upper));
  tree.nodes[n].axis = axis;
  tree.nodes[n].child = first;
  tree.nodes[n].upper = first + 1;
  tree.nodes[n].blocked = false;
  return first;
}

void parse_apart_tree(const std::string& text, ApartTree& tree, std::size_t proofs) {
  std::size_t at = 0, leaves = 0, proof = 0;
  std::vector<std::size_t> stack{0};   // nodes still to read, next on top
  const std::string marks = tree.marks;
  // room for every node read before the leaf or depth limit refuses the tree (each halving adds
  // two nodes; a preorder text has at most one halving more than its leaves read, plus the depth
  // of the boxes still to read): the nodes' rationals are copied, not moved, when the vector
  // grows (session 73)
  {
    std::size_t halvings = 0;
    for (char mark : text)
      if (marks.find(mark) != std::string::npos && ++halvings >= apart_max_leaves + apart_max_depth + 1) break;
    tree.nodes.reserve(tree.nodes.size() + 2 * halvings);
  }
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    if (at >= text.size()) reject("the tree ends before it covers the domain (a box is missing after " + std::to_string(at) + " marks)");
    const char mark = text[at++];
    if (const std::size_t axis = marks.find(mark); axis != std::string::npos) {
      if (tree.nodes[n].depth >= apart_max_depth)
        reject("the tree is deeper than " + std::to_string(apart_max_depth) + " halvings (mark " + std::to_string(at - 1) + ")");
      if (tree.nodes[0].box.lo[axis] == tree.nodes[0].box.hi[axis])
        reject("the tree's mark " + std::to_string(at - 1) + " halves " + mark + ", an axis of one value");
      const std::size_t first = split_apart_leaf(tree, n, int(axis));
      stack.push_back(first + 1);
      stack.push_back(first);
    } else if (mark == 'o' || mark == 'b') {
      if (++leaves > apart_max_leaves) reject("the tree has more than " + std::to_string(apart_max_leaves) + " leaves (the format's limit)");
      if (mark == 'b') {
        if (proof >= proofs) reject("the tree has more blocked leaves than proofs (" + std::to_string(proofs) + ")");
        tree.nodes[n].blocked = true;
        tree.nodes[n].proof = proof++;
      }
    } else {
      reject("the tree's mark " + std::to_string(at - 1) + " is not " + marks[0] + ", " + marks[1] + ", " + marks[2] + ", o or b");
    }
  }
  if (at != text.size()) reject("the tree has " + std::to_string(text.size() - at) + " marks after its last box");
  if (proof != proofs) reject("the certificate has " + std::to_string(proofs) + " proofs for " + std::to_string(proof) + " blocked leaves");
}

std::string apart_tree_text(const ApartTree& tree) {
  std::string out;
  std::vector<std::size_t> stack{0};
  while (!stack.empty()) {
    const ApartTree::Node& node = tree.nodes[stack.back()];
    stack.pop_back();
    if (node.axis >= 0) {
      out += tree.marks[node.axis];
      stack.push_back(node.upper);
      stack.push_back(node.child);
    } else {
      out += node.blocked ? 'b' : 'o';
    }
  }
  return out;
}

Rational apart_u_of(const Rational& t, bool half_turn) {
  const bool small = abs(t) <= 1;
  if (!half_turn) return small ? t : Rational(2 - 1 / t);
  return small ? Rational(2 + t) : Rational(-1 / t);
}

Rational apart_u_of(const PlanarPose& pose) { return apart_u_of(pose.tangent, pose.half_turn); }

PlanarPose apart_pose_at(const std::string& part, const Rational& x, const Rational& y, const Rational& u) {
  return u <= 1 ? PlanarPose{part, x, y, u, false, std::nullopt} : PlanarPose{part, x, y, Rational(u - 2), true, std::nullopt};
}

namespace {
Interval theta_of(const Rational& u) { return u <= 1 ? angle_of_tangent(u, false) : angle_of_tangent(Rational(u - 2), true); }
Interval hull_of(const Rational& lo, const Rational& hi) { return hull2(Interval(lo), Interval(hi)); }
// the rotations of the box's u range about the origin
IntervalMap turned_over(const Rational& lo, const Rational& hi) {
  const Interval angle = hull2(theta_of(lo), theta_of(hi));   // theta increases with u
  IntervalMap m;
  m.c = cos_of(angle);
  m.s = sin_of(angle);
  return m;
}
// the rotation at u (exact), about the origin
ExactMap turned_at(const Rational& u) {
  const PlanarPose p = apart_pose_at("", Rational(0), Rational(0), u);
  const Rational w = 1 + p.tangent * p.tangent;
  const int sign = p.half_turn ? -1 : 1;
  ExactMap m;
  m.c = sign * (1 - p.tangent * p.tangent) / w;
  m.s = sign * 2 * p.tangent / w;
  return m;
}
}  // namespace

Rational reach_about_pivot(const Part& part) {
  Part turning = part;   // the part as if it only turned about its pivot: its shape relative to the pivot
  turning.motion.kind = Motion::Kind::rotation;
  return reach(shape_of(turning));
}

IntervalMap apart_box_map(const Part& planar, const ApartBox& box) {
  IntervalMap m = turned_over(box.lo[2], box.hi[2]);
  const Interval px(planar.motion.pivot.x), py(planar.motion.pivot.y);
  m.shift.x = px - (m.c * px - m.s * py) + hull_of(box.lo[0], box.hi[0]);
  m.shift.y = py - (m.s * px + m.c * py) + hull_of(box.lo[1], box.hi[1]);
  return m;
}

void apart_middle(const ApartBox& box, Rational out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = (box.lo[k] + box.hi[k]) / 2;
}

PlanarPose apart_middle_pose(const Part& planar, const ApartBox& box) {
  return apart_pose_at(planar.name, (box.lo[0] + box.hi[0]) / 2, (box.lo[1] + box.hi[1]) / 2, (box.lo[2] + box.hi[2]) / 2);
}

ApartPair::ApartPair(const Part& other_part, const Part& moving_part)
    : other(other_part), moving(moving_part), pin_slot(moving_part.motion.kind == Motion::Kind::pin_slot),
      other_shape(shape_of(other_part)), moving_shape(shape_of(moving_part)), other_placed(place(other_part, ExactMap{})) {}

ExactMap ApartPair::moving_at(const Rational& x0, const Rational& x1, const Rational& u) const {
  if (!pin_slot) return planar_pose_map(moving, apart_pose_at(moving.name, x0, x1, u));
  PlanarPose p = apart_pose_at(moving.name, Rational(0), Rational(0), u);
  p.slide = x1;
  return planar_pose_map(moving, p);
}

ExactMap ApartPair::other_at(const Rational& q) const {
  ExactMap m;
  if (other.motion.kind == Motion::Kind::rotation) {
    m = turned_at(q);
    m.pivot = other.motion.pivot;
  } else if (other.motion.kind == Motion::Kind::translation) {
    m.shift = Point{Rational(q * other.motion.direction.x), Rational(q * other.motion.direction.y)};
  }
  return m;
}

IntervalMap ApartPair::moving_over(const ApartBox& box) const {
  if (!pin_slot) return apart_box_map(moving, box);
  // p -> P + R (p - P) + s R d over the box (pin_slot parts are shaped about the origin)
  IntervalMap m = turned_over(box.lo[2], box.hi[2]);
  const Interval px(moving.motion.pivot.x), py(moving.motion.pivot.y), dx(moving.motion.direction.x), dy(moving.motion.direction.y);
  const Interval slide = hull_of(box.lo[1], box.hi[1]);
  m.shift.x = px - (m.c * px - m.s * py) + slide * (m.c * dx - m.s * dy);
  m.shift.y = py - (m.s * px + m.c * py) + slide * (m.s * dx + m.c * dy);
  return m;
}

IntervalMap ApartPair::other_over(const ApartBox& box) const {
  if (other.motion.kind == Motion::Kind::rotation) return turned_over(box.lo[0], box.hi[0]);   // about its pivot (its shape's)
  if (other.motion.kind == Motion::Kind::translation) return translation_over(other.motion.direction, RationalInterval{box.lo[0], box.hi[0]});
  return IntervalMap{};
}

void ApartPair::coordinates(const PlanarPose& pose, const std::optional<ExactPosition>& position, Rational out[3]) const {
  out[2] = apart_u_of(pose);
  if (!pin_slot) {
    out[0] = pose.x, out[1] = pose.y;
    return;
  }
  out[1] = pose.slide ? *pose.slide : Rational(0);
  out[0] = !position ? Rational(0) : position->is_offset ? position->value : apart_u_of(position->value, position->half_turn);
}

std::string apart_proof_failure(const ApartPair& pair, const ApartBox& box, const SlicedApartProof& proof) {
  const Part &fixed = pair.other, &planar = pair.moving;
  Rational middle[3];
  apart_middle(box, middle);
  const bool other_moves = pair.other.motion.kind != Motion::Kind::fixed;
  if (proof.kind == SlicedApartProof::Kind::point) {
    // planar claims: relative to the planar part's pivot; pin-slot claims: a world point
    const Point p = pair.pin_slot ? proof.point
                                  : Point{Rational(planar.motion.pivot.x + proof.point.x), Rational(planar.motion.pivot.y + proof.point.y)};
    if (!other_moves) {
      if (locate(pair.other_placed, p) <= 0) return "the point is not strictly inside '" + fixed.name + "'";
    } else {
      if (sgn(point_boundary_distance_lower_bound(pair.other_shape, pair.other_over(box), p, Rational(1))) <= 0)
        return "the point is not certainly off the boundary of '" + fixed.name + "' over the box";
      if (locate(place(fixed, pair.other_at(middle[0])), p) <= 0)
        return "the point is not strictly inside '" + fixed.name + "' at the box's middle";
    }
    if (sgn(point_boundary_distance_lower_bound(pair.moving_shape, pair.moving_over(box), p, Rational(1))) <= 0)
      return "the point is not certainly off the boundary of '" + planar.name + "' over the box";
    if (locate(place(planar, pair.moving_at(middle[0], middle[1], middle[2])), p) <= 0)
      return "the point is not strictly inside '" + planar.name + "' at the box's middle";
    return "";
  }
  auto single = [&](const Part& owner, const IntervalPart& shape, std::size_t loop, std::size_t edge,
                    const IntervalMap& map) -> std::optional<IntervalEdge> {
    if (loop >= owner.loops.size() || edge >= owner.loops[loop].edges.size()) return std::nullopt;
    IntervalPart one;   // the one edge, moving like its part
    one.name = shape.name;
    one.pivot = shape.pivot;
    one.loops.push_back({shape.loops[loop][edge]});
    return place_over(one, map).loops[0][0];
  };
  const Part& first = proof.planar_edge ? planar : fixed;
  const Part& second = proof.planar_edge ? fixed : planar;
  const IntervalMap moving_map = pair.moving_over(box), other_map = pair.other_over(box);
  std::optional<IntervalEdge> e = proof.planar_edge ? single(planar, pair.moving_shape, proof.edge_loop, proof.edge, moving_map)
                                                    : single(fixed, pair.other_shape, proof.edge_loop, proof.edge, other_map);
  std::optional<IntervalEdge> g = proof.planar_edge ? single(fixed, pair.other_shape, proof.across_loop, proof.across, other_map)
                                                    : single(planar, pair.moving_shape, proof.across_loop, proof.across, moving_map);
  if (!e) return "part '" + first.name + "' has no loop " + std::to_string(proof.edge_loop) + " edge " + std::to_string(proof.edge);
  if (!g) return "part '" + second.name + "' has no loop " + std::to_string(proof.across_loop) + " edge " + std::to_string(proof.across);
  std::string why;
  if (!crossing_certain(*e, proof.along, *g, &why)) return "the crossing does not hold over the box: " + why;
  return "";
}

std::string apart_pin_slot_end_failure(const ApartPair& pair, const Rational at[3]) {
  const ExactMap moving = pair.moving_at(at[0], at[1], at[2]), other = pair.other_at(at[0]);
  if (sgn(boundary_distance_lower_bound(pair.other_shape, to_interval_map(other), pair.moving_shape, to_interval_map(moving), Rational(1))) <= 0)
    return "the boundaries are not certainly apart there";
  try {
    check_nesting(place(pair.other, other), place(pair.moving, moving), "there");
  } catch (const Rejection& rejection) {
    return rejection.reason;
  }
  return "";
}

PinSlotParts checked_pin_slot_pair(const Certificate& envelope, const Model& model, const PlanarPose& a, const PlanarPose& b,
                                   const std::optional<ExactPosition>& a_other, const std::optional<ExactPosition>& b_other,
                                   const std::string& a_name, const std::string& b_name) {
  check_certificate_model(envelope, model);
  const std::string &first = envelope.first, &second = envelope.second;
  if (first == second) reject("a pair needs two different parts");
  if (b.part != a.part) reject("the claim poses '" + a.part + "' at " + a_name + " and '" + b.part + "' at " + b_name);
  if (!a.slide || !b.slide) reject("a pin-slot claim's ends give the part's slide and tangent");
  if (a.part != first && a.part != second) reject("the posed part '" + a.part + "' is not a part of the pair");
  const Part& moving = part_named(model, a.part);
  const Part& other = part_named(model, a.part == first ? second : first);
  if (moving.motion.kind != Motion::Kind::pin_slot) reject("part '" + moving.name + "' has no pin_slot motion (a pose with a slide)");
  const Motion::Kind kind = other.motion.kind;
  if (kind != Motion::Kind::fixed && kind != Motion::Kind::rotation && kind != Motion::Kind::translation)
    reject("part '" + other.name + "' must be fixed, rotate or translate");
  if (bool(a_other) != bool(b_other)) reject("the ends give the other part's position at one end only");
  if ((kind == Motion::Kind::fixed) != !a_other)
    reject(kind == Motion::Kind::fixed ? "part '" + other.name + "' is fixed: the ends give no position of it"
                                       : "the ends give no position of the moving part '" + other.name + "'");
  for (const std::optional<ExactPosition>* position : {&a_other, &b_other})
    if (*position && (*position)->is_offset != (kind == Motion::Kind::translation))
      reject("part '" + other.name + "' " + (kind == Motion::Kind::rotation ? "rotates: its positions are tangents" : "translates: its positions are offsets"));
  // the ends are configurations: within the motion limits (the slide exactly, angles certainly)
  for (const PlanarPose* end : {&a, &b}) {
    const std::string& which = end == &a ? a_name : b_name;
    const auto& limits = moving.motion.translation_limits;
    if (limits && (*end->slide < limits->lo || *end->slide > limits->hi))
      reject("the end " + which + ": the slide of '" + moving.name + "' (" + fraction_or_rounded(*end->slide) + ") is outside its limits");
    if (!certainly_within(moving.motion.angle_limits, angle_of_tangent(end->tangent, end->half_turn), true))
      reject("the end " + which + ": the angle of '" + moving.name + "' is not certainly within its limits");
    const std::optional<ExactPosition>& position = end == &a ? a_other : b_other;
    if (position) {
      try {
        exact_map(other, {{other.name, *position}});
      } catch (const Rejection& rejection) {
        reject("the end " + which + ": " + rejection.reason);
      }
    }
  }
  return PinSlotParts{&other, &moving};
}

std::string apart_limits_failure(const ApartPair& pair, const ApartBox& box) {
  const Part &moving = pair.moving, &other = pair.other;
  auto range = [&](int k) { return "[" + fraction_or_rounded(box.lo[k]) + ", " + fraction_or_rounded(box.hi[k]) + "]"; };
  const auto& slide = moving.motion.translation_limits;
  if (pair.pin_slot && slide && (box.lo[1] < slide->lo || box.hi[1] > slide->hi))
    return "the slide of '" + moving.name + "' (s in " + range(1) + ") leaves its limits";
  // theta is continuous and increasing in u: the angles of a u range are the hull of its ends'
  if (!certainly_within(moving.motion.angle_limits, hull2(theta_of(box.lo[2]), theta_of(box.hi[2])), true))
    return "the angle of '" + moving.name + "' (u in " + range(2) + ") is not certainly within its limits";
  if (other.motion.kind == Motion::Kind::translation) {
    const auto& offsets = other.motion.translation_limits;
    if (offsets && (box.lo[0] < offsets->lo || box.hi[0] > offsets->hi))
      return "the offset of '" + other.name + "' (q in " + range(0) + ") leaves its limits";
  } else if (other.motion.kind == Motion::Kind::rotation) {
    if (!certainly_within(other.motion.angle_limits, hull2(theta_of(box.lo[0]), theta_of(box.hi[0])), true))
      return "the angle of '" + other.name + "' (q in " + range(0) + ") is not certainly within its limits";
  } else if (sgn(box.lo[0]) != 0 || sgn(box.hi[0]) != 0) {
    return "q is " + range(0) + " for the fixed part '" + other.name + "' (it is 0)";
  }
  return "";
}

bool apart_same_configuration(const ApartPair& pair, const Rational a[3], const Rational b[3]) {
  auto same = [](const ExactMap& p, const ExactMap& q) { return p.c == q.c && p.s == q.s && p.shift.x == q.shift.x && p.shift.y == q.shift.y; };
  return same(pair.moving_at(a[0], a[1], a[2]), pair.moving_at(b[0], b[1], b[2])) && same(pair.other_at(a[0]), pair.other_at(b[0]));
}

std::string apart_move_failure(const ApartPair& pair, const Rational from[3], const Rational to[3], std::size_t budget,
                               std::size_t* pieces) {
  std::size_t count = 0;
  auto done = [&](std::string why) {
    if (pieces) *pieces = count;
    return why;
  };
  int axis = -1;
  for (int k = 0; k < 3; ++k)
    if (from[k] != to[k]) {
      if (axis >= 0) return done("it changes two coordinates at once (each move changes one of q, s, u)");
      axis = k;
    }
  ApartBox whole;
  for (int k = 0; k < 3; ++k) whole.lo[k] = std::min(from[k], to[k]), whole.hi[k] = std::max(from[k], to[k]);
  if (std::string why = apart_limits_failure(pair, whole); !why.empty()) return done(why);
  Rational size = reach(pair.moving_shape);
  if (sgn(size) <= 0) size = 1;
  const Rational enough = size / Rational(mpz_class(1) << 32);
  // the move's parameter: the changing coordinate (a move that stays: q over [0, 0])
  MoveBisection move;
  move.stay = axis < 0;
  move.letter = axis >= 0 ? "qsu"[axis] : 'q';
  move.lo = axis >= 0 ? whole.lo[axis] : Rational(0);
  move.hi = axis >= 0 ? whole.hi[axis] : Rational(0);
  auto piece_box = [&](const Rational& p0, const Rational& p1) {
    ApartBox box = whole;
    if (axis >= 0) box.lo[axis] = p0, box.hi[axis] = p1;
    return box;
  };
  move.apart = [&](const Rational& p0, const Rational& p1) {
    const ApartBox box = piece_box(p0, p1);
    return sgn(boundary_distance_lower_bound(pair.other_shape, pair.other_over(box), pair.moving_shape, pair.moving_over(box), enough)) > 0;
  };
  move.overlap_at = [&](const Rational& p) -> std::string {
    Rational at[3];
    apart_middle(piece_box(p, p), at);
    std::string evidence = overlap_evidence(place(pair.other, pair.other_at(at[0])), place(pair.moving, pair.moving_at(at[0], at[1], at[2])));
    return evidence.empty() ? std::string()
                            : "the parts overlap at q = " + fraction_or_rounded(at[0]) + ", s = " + fraction_or_rounded(at[1]) + ", u = " +
                                  fraction_or_rounded(at[2]) + ": " + evidence;
  };
  move.not_apart = "the parts are not certainly apart there";
  // the move's length in units of the part: angle coordinates as they are, a slide or an offset
  // over the part's reach
  Rational span(0);
  if (axis >= 0) {
    const bool angle = axis == 2 || (axis == 0 && pair.other.motion.kind == Motion::Kind::rotation);
    span = angle ? Rational(whole.hi[axis] - whole.lo[axis]) : Rational((whole.hi[axis] - whole.lo[axis]) / size);
  }
  move.max_depth = move_depth_limit(span);
  return move_bisection_failure(move, budget, pieces);
}

bool apart_boxes_meet(const ApartBox& a, const ApartBox& b, const bool periodic[3]) {
  for (int k = 0; k < 3; ++k) {
    if (!(a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k])) continue;
    if (periodic[k] && ((a.hi[k] == 3 && b.lo[k] == -1) || (b.hi[k] == 3 && a.lo[k] == -1))) continue;
    return false;
  }
  return true;
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

std::vector<std::size_t> apart_leaves_at(const ApartTree& tree, const Rational at[3]) {
  ApartBox point;
  const ApartBox& d = tree.nodes[0].box;
  for (int k = 0; k < 3; ++k) {
    point.lo[k] = point.hi[k] = at[k];
    if (at[k] < d.lo[k] || at[k] > d.hi[k]) return {};
  }
  std::vector<std::size_t> out;
  // (a point meets a box across a seam only at -1 or 3, where it lies in the box's face on the
  // other side too: apart_boxes_meet joins them)
  apart_leaves_meeting(tree, point, std::size_t(-1), out);
  return out;
}

bool apart_on_boundary(const ApartTree& tree, const ApartBox& box) {
  const ApartBox& d = tree.nodes[0].box;
  for (int k = 0; k < 3; ++k) {
    if (tree.periodic[k]) continue;
    if ((box.lo[k] == d.lo[k] && !tree.closed_lo[k]) || (box.hi[k] == d.hi[k] && !tree.closed_hi[k])) return true;
  }
  return false;
}

}  // namespace verify

namespace {

// The pin-slot claim's pair and ends, checked; the faces at motion limits closed in `tree`.
void check_pin_slot_pair(const SlicedApartCertificate& c, const Model& model, verify::ApartTree& tree, const Part*& other_part,
                         const Part*& moving_part) {
  using namespace verify;
  const PinSlotParts parts = checked_pin_slot_pair(c.envelope, model, c.a, c.b, c.a_other, c.b_other, "a", "b");
  const Part &moving = *parts.moving, &other = *parts.other;
  const Motion::Kind kind = other.motion.kind;
  if (c.other_full_turn && kind != Motion::Kind::rotation) reject("only a rotating part's range is the full turn");
  if (kind == Motion::Kind::rotation && !c.other_full_turn && !(c.x.lo >= -1 && c.x.hi <= 3))
    reject("the rotating part's range [" + fraction_or_rounded(c.x.lo) + ", " + fraction_or_rounded(c.x.hi) + "] leaves [-1, 3]");
  // faces at motion limits: no motion of the mechanism crosses them (a rotating part's or the
  // pin-slot part's angle limits are not used: the full turn holds every motion within them)
  auto close = [&](int k, const std::optional<RationalInterval>& limits) {
    if (!limits) return;
    const ApartBox& d = tree.nodes[0].box;
    if (d.lo[k] <= limits->lo) tree.closed_lo[k] = true;
    if (d.hi[k] >= limits->hi) tree.closed_hi[k] = true;
  };
  if (kind == Motion::Kind::translation) close(0, other.motion.translation_limits);
  close(1, moving.motion.translation_limits);
  other_part = &other;
  moving_part = &moving;
}

}  // namespace

VerificationResult check_sliced_apart(const SlicedApartCertificate& c, const Model& model) {
  using namespace verify;
  return verdict_of([&] {
    // (a fixed other part: q's range is [0, 0], the axis of one value)
    const bool one_q = c.pin_slot && !c.a_other;
    if (!(one_q ? sgn(c.x.lo) == 0 && sgn(c.x.hi) == 0 : c.x.lo < c.x.hi) || !(c.y.lo < c.y.hi) ||
        (!c.full_turn && !(c.u.lo < c.u.hi && c.u.lo >= -1 && c.u.hi <= 3)))
      reject("the domain is empty or its angle range leaves [-1, 3]");
    if (c.other_full_turn && !(c.x.lo == -1 && c.x.hi == 3)) reject("the other part's full turn is the range [-1, 3]");
    ApartTree tree = apart_tree_of(c);
    std::optional<SlicedPair> planar_pair;
    const Part *other = nullptr, *moving = nullptr;
    if (c.pin_slot) {
      check_pin_slot_pair(c, model, tree, other, moving);
    } else {
      if (c.a_other || c.b_other || c.other_full_turn) reject("a planar claim gives no other part's position");
      planar_pair = checked_sliced_pair(c.envelope, model, c.a, c.b, "a", "b", "apart");
      other = &planar_pair->fixed();
      moving = &planar_pair->planar();
    }
    const ApartPair pair(*other, *moving);
    parse_apart_tree(c.tree, tree, c.proofs.size());
    // both ends free (the claim is about two poses of the free space)
    Rational at_a[3], at_b[3];
    pair.coordinates(c.a, c.a_other, at_a);
    pair.coordinates(c.b, c.b_other, at_b);
    for (const PlanarPose* end : {&c.a, &c.b}) {
      const std::string which = end == &c.a ? "a" : "b";
      std::string failure = c.pin_slot ? apart_pin_slot_end_failure(pair, end == &c.a ? at_a : at_b)
                                       : sliced_move_failure(*other, *moving, *end, *end);
      if (!failure.empty()) reject("the end " + which + " (" + sliced_pose_words(*end) + ") is not certainly free: " + failure);
      if (!c.pin_slot) check_nesting(place(*other, ExactMap{}), place(*moving, planar_pose_map(*moving, *end)), "at the end " + which);
    }
    // every leaf on the domain's walled faces blocked, then the open leaves' components
    std::size_t leaves = 0, open = 0;
    std::vector<std::size_t> parent(tree.nodes.size());
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto root = [&](std::size_t n) {
      while (parent[n] != n) n = parent[n] = parent[parent[n]];
      return n;
    };
    std::vector<std::size_t> around;
    std::size_t visited = 0;
    for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
      const ApartTree::Node& node = tree.nodes[n];
      if (node.axis >= 0) continue;
      ++leaves;
      if (node.blocked) continue;
      ++open;
      if (apart_on_boundary(tree, node.box))
        reject("the open leaf " + box_words(tree, node.box) + " touches the domain's boundary (every leaf there must be blocked)");
      around.clear();
      apart_leaves_meeting(tree, node.box, n, around, &visited);
      if (visited > apart_max_box_tests)
        reject("the open leaves' adjacency needs more than " + std::to_string(apart_max_box_tests) +
               " box tests (the format's limit; refused before any proof is checked)");
      for (std::size_t m : around)
        if (!tree.nodes[m].blocked) parent[root(m)] = root(n);
    }
    auto open_at = [&](const PlanarPose& p, const Rational at[3], const std::string& which) {
      std::vector<std::size_t> found, components;
      found = apart_leaves_at(tree, at);
      if (found.empty()) reject("the end " + which + " (" + sliced_pose_words(p) + ") lies outside the domain");
      for (std::size_t n : found)
        if (!tree.nodes[n].blocked) components.push_back(root(n));
      if (components.empty()) reject("the end " + which + " lies in blocked leaves only");
      return components;
    };
    const std::vector<std::size_t> in_a = open_at(c.a, at_a, "a"), in_b = open_at(c.b, at_b, "b");
    for (std::size_t k : in_a)
      if (std::find(in_b.begin(), in_b.end(), k) != in_b.end())
        reject("a and b lie in one component of the open leaves (" + box_words(tree, tree.nodes[k].box) + " and its neighbours)");
    // every blocked leaf's proof (the point proofs' work bounded first)
    std::size_t edges = 0, point_proofs = 0;
    for (const Part* part : {other, moving})
      for (const Loop& loop : part->loops) edges += loop.edges.size();
    for (const ApartTree::Node& node : tree.nodes)
      if (node.axis < 0 && node.blocked && c.proofs[node.proof].kind == SlicedApartProof::Kind::point) ++point_proofs;
    if (point_proofs * edges > apart_max_point_edge_tests)
      reject("the " + std::to_string(point_proofs) + " point proofs need more than " + std::to_string(apart_max_point_edge_tests) +
             " edge tests (" + std::to_string(edges) + " edges; the format's limit)");
    std::size_t blocked = 0;
    for (const ApartTree::Node& node : tree.nodes) {
      if (node.axis >= 0 || !node.blocked) continue;
      ++blocked;
      std::string failure = apart_proof_failure(pair, node.box, c.proofs[node.proof]);
      if (!failure.empty()) reject("the blocked leaf " + box_words(tree, node.box) + " (proof " + std::to_string(node.proof) + "): " + failure);
    }
    const std::string expected = sliced_apart_statement(c);
    if (c.envelope.statement != expected)
      reject("the statement does not say what the claim's data prove: it reads '" + c.envelope.statement.substr(0, 400) +
             "', the claim's data give '" + expected + "'");
    const std::string& fixed_name = other->name;
    return std::string(claim_name) + ": part '" + moving->name + "' cannot move from " + sliced_end_words(c.a, c.a_other, fixed_name) +
           " to " + sliced_end_words(c.b, c.b_other, fixed_name) + " without touching '" + fixed_name + "' (" + std::to_string(leaves) + " boxes, " +
           std::to_string(blocked) + " proved blocked, none open on the domain's boundary, the ends in different components of the " +
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
