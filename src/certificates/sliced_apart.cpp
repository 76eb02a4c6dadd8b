// The sliced_apart certificate's producer and writer (<hipair/sliced_apart.hpp>): an adaptive
// kd-subdivision of a domain of poses around a (offsets a +- h, the full turn). Each box is
// evaluated at its middle pose with the exact overlap oracle: overlapping there, a blocking proof
// is sought (two edges crossing at the middle whose crossing piece the verifier's
// crossing_certain proves for the whole box, or the oracle's witness point, certainly inside both
// parts over the box); apart there, the box is free when the certified distance of the
// boundaries over it is positive. Boxes on the domain's boundary are split until blocked (a free
// one there: the next h); then a shortest chain of open boxes from a to b is sought and its
// boxes neither blocked nor free are split, until no chain is left (certified, and re-checked by
// the verifier's code), a chain of free boxes joins a and b, or the limits are reached.
#include "certificates/producer.hpp"
#include "certify/certificate_json.hpp"
#include "certify/sliced_apart.hpp"
#include "certify/sliced_connected.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced_apart.hpp>

#include <algorithm>
#include <deque>
#include <unordered_map>

namespace hipair {
namespace {

using namespace certify_detail;
using verify::ApartBox;
using verify::ApartTree;

enum class State : char { blocked, free, mixed };

class ApartSearch {
 public:
  ApartSearch(const Part& fixed, const Part& planar, const ApartBox& domain, std::size_t max_leaves)
      : fixed_(fixed), planar_(planar), shape_fixed_(verify::shape_of(fixed)), shape_planar_(verify::shape_of(planar)),
        posed_fixed_(verify::place_over(shape_fixed_, verify::IntervalMap{})), placed_fixed_(verify::place(fixed, verify::ExactMap{})),
        max_leaves_(max_leaves) {
    reach_ = verify::reach(shape_planar_);
    if (sgn(reach_) <= 0) reach_ = 1;
    enough_ = reach_;
    tree_.periodic = true;
    tree_.nodes.push_back(ApartTree::Node{});
    tree_.nodes[0].box = domain;
    evaluate(0);
  }

  // "" when a's open boxes and b's are in different components; else why not.
  std::string run(const PlanarPose& a, const PlanarPose& b) {
    // 1. the domain's boundary blocked
    std::vector<std::size_t> queue{0};
    while (!queue.empty()) {
      const std::size_t n = queue.back();
      queue.pop_back();
      if (tree_.nodes[n].axis >= 0) {
        queue.push_back(tree_.nodes[n].child);
        queue.push_back(tree_.nodes[n].upper);
        continue;
      }
      if (state_[n] == State::blocked || !verify::apart_on_boundary(tree_, tree_.nodes[n].box)) continue;
      if (state_[n] == State::free) return "the domain's boundary has free poses";
      if (std::string why = split(n); !why.empty()) return why;
      queue.push_back(tree_.nodes[n].child);
      queue.push_back(tree_.nodes[n].upper);
    }
    // 2. chains of open boxes from a to b split until there is none
    const Rational ua = verify::apart_u_of(a), ub = verify::apart_u_of(b);
    for (;;) {
      std::vector<std::size_t> from = open_at(a.x, a.y, ua), to = open_at(b.x, b.y, ub);
      if (from.empty() || to.empty()) return "an end lies in blocked boxes only";
      std::unordered_map<std::size_t, std::size_t> parent;
      std::deque<std::size_t> frontier;
      for (std::size_t n : from) parent.emplace(n, n), frontier.push_back(n);
      std::size_t reached = std::size_t(-1);
      while (!frontier.empty() && reached == std::size_t(-1)) {
        const std::size_t n = frontier.front();
        frontier.pop_front();
        if (std::find(to.begin(), to.end(), n) != to.end()) {
          reached = n;
          break;
        }
        for (std::size_t m : adjacent_[n])
          if (state_[m] != State::blocked && parent.emplace(m, n).second) frontier.push_back(m);
      }
      if (reached == std::size_t(-1)) return "";
      std::vector<std::size_t> mixed;
      for (std::size_t n = reached;; n = parent[n]) {
        if (state_[n] == State::mixed) mixed.push_back(n);
        if (parent[n] == n) break;
      }
      if (mixed.empty()) return "a chain of boxes proved free joins a and b: they are connected (not certified here: --claim connected certifies it)";
      for (std::size_t n : mixed)
        if (std::string why = split(n); !why.empty()) return why;
    }
  }

  SlicedApartCertificate certificate_body() const {
    SlicedApartCertificate c;
    const ApartBox& d = tree_.nodes[0].box;
    c.x = RationalInterval{d.lo[0], d.hi[0]};
    c.y = RationalInterval{d.lo[1], d.hi[1]};
    c.full_turn = true;
    c.tree = verify::apart_tree_text(tree_);
    std::vector<std::size_t> stack{0};   // proofs in the tree's preorder
    while (!stack.empty()) {
      const ApartTree::Node& node = tree_.nodes[stack.back()];
      const std::size_t n = stack.back();
      stack.pop_back();
      if (node.axis >= 0) {
        stack.push_back(node.upper);
        stack.push_back(node.child);
      } else if (state_[n] == State::blocked) {
        c.proofs.push_back(proofs_.at(n));
      }
    }
    return c;
  }

  std::size_t leaves() const { return leaves_; }
  std::size_t blocked() const { return std::size_t(std::count(state_.begin(), state_.end(), State::blocked)); }

 private:
  std::vector<std::size_t> open_at(const Rational& x, const Rational& y, const Rational& u) const {
    std::vector<std::size_t> out;
    for (std::size_t n : verify::apart_leaves_at(tree_, x, y, u))
      if (state_[n] != State::blocked) out.push_back(n);
    return out;
  }

  std::string split(std::size_t n) {
    if (tree_.nodes[n].depth + 1 >= verify::apart_max_depth) return "boxes reached the verifier's depth limit near " + where(n);
    if (leaves_ + 1 > max_leaves_) return "more than " + std::to_string(max_leaves_) + " boxes (stuck near " + where(n) + ")";
    const ApartBox& box = tree_.nodes[n].box;
    const Rational sizes[3] = {box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], (box.hi[2] - box.lo[2]) * reach_};
    const int axis = int(std::max_element(sizes, sizes + 3) - sizes);
    const std::size_t first = verify::split_apart_leaf(tree_, n, axis);
    ++leaves_;
    // the halves' neighbours: the sibling and those of the box halved that meet them
    adjacent_.resize(tree_.nodes.size());
    std::vector<std::size_t> old = std::move(adjacent_[n]);
    adjacent_[n].clear();
    for (std::size_t c : {first, first + 1}) adjacent_[c].push_back(c == first ? first + 1 : first);
    for (std::size_t m : old) {
      auto& theirs = adjacent_[m];
      theirs.erase(std::find(theirs.begin(), theirs.end(), n));
      for (std::size_t c : {first, first + 1})
        if (verify::apart_boxes_meet(tree_.nodes[c].box, tree_.nodes[m].box, tree_.periodic)) {
          adjacent_[c].push_back(m);
          theirs.push_back(c);
        }
    }
    state_.resize(tree_.nodes.size(), State::mixed);
    proofs_.erase(n);
    evaluate(first);
    evaluate(first + 1);
    return "";
  }

  std::string where(std::size_t n) const {
    const ApartBox& b = tree_.nodes[n].box;
    return "x = " + to_decimal_string(b.lo[0]) + ", y = " + to_decimal_string(b.lo[1]) + ", u = " + to_decimal_string(b.lo[2]);
  }

  bool try_proof(std::size_t n, const SlicedApartProof& proof) {
    if (!verify::apart_proof_failure(fixed_, planar_, tree_.nodes[n].box, proof).empty()) return false;
    proofs_[n] = proof;
    state_[n] = State::blocked;
    tree_.nodes[n].blocked = true;
    return true;
  }

  void evaluate(std::size_t n) {
    state_.resize(tree_.nodes.size(), State::mixed);
    state_[n] = State::mixed;
    const ApartBox& box = tree_.nodes[n].box;
    const PlanarPose middle = verify::apart_middle_pose(planar_, box);
    const verify::ExactMap exact = verify::planar_pose_map(planar_, middle);
    const verify::IntervalMap map = verify::apart_box_map(planar_, box);
    const verify::PlacedPart placed = verify::place(planar_, exact);
    // the boundaries apart over the whole box: free, or nested (blocked) at every pose
    const bool apart_over = sgn(verify::boundary_distance_lower_bound(shape_fixed_, verify::IntervalMap{}, shape_planar_, map, enough_)) > 0;
    if (apart_over) {
      bool nested = false;
      for (int side = 0; side < 2 && !nested; ++side) {
        const verify::PlacedPart& inner = side ? placed : placed_fixed_;
        const verify::PlacedPart& outer = side ? placed_fixed_ : placed;
        for (const auto& loop : inner.loops)
          if (!loop.empty() && verify::locate(outer, loop[0].source) >= 0) nested = true;
      }
      if (!nested) {
        state_[n] = State::free;
        return;
      }
    }
    // edges crossing at the middle, their crossing pieces tried over the box
    const verify::IntervalPart at_middle = verify::place_over(shape_planar_, verify::to_interval_map(exact));
    std::optional<verify::IntervalPart> over;
    for (std::size_t i = 0; i < placed.loops.size(); ++i)
      for (std::size_t j = 0; j < placed.loops[i].size(); ++j)
        for (std::size_t k = 0; k < placed_fixed_.loops.size(); ++k)
          for (std::size_t l = 0; l < placed_fixed_.loops[k].size(); ++l) {
            if (!verify::edges_cross(placed.loops[i][j], placed_fixed_.loops[k][l])) continue;
            if (!over) over = verify::place_over(shape_planar_, map);
            const verify::IntervalEdge &pc = at_middle.loops[i][j], &po = over->loops[i][j], &f = posed_fixed_.loops[k][l];
            for (int order = 0; order < 2; ++order) {
              const verify::PlacedEdge& pe = order == 0 ? placed.loops[i][j] : placed_fixed_.loops[k][l];
              const verify::PlacedEdge& pg = order == 0 ? placed_fixed_.loops[k][l] : placed.loops[i][j];
              const verify::IntervalEdge& eo = order == 0 ? po : f;
              const verify::IntervalEdge& go = order == 0 ? f : po;
              std::optional<RationalInterval> piece;
              if (!pe.arc && !pg.arc) {
                // two segments: pieces about the exact crossing at the middle, narrowing
                auto side = [&](const Point& p) {
                  return Rational((pg.target.x - pg.source.x) * (p.y - pg.source.y) - (pg.target.y - pg.source.y) * (p.x - pg.source.x));
                };
                const Rational ss = side(pe.source), st = side(pe.target);
                if (ss == st) continue;
                const Rational at = ss / (ss - st);
                for (Rational delta(1, 2); delta > Rational(1, 1 << 20) && !piece; delta /= 4) {
                  RationalInterval along{std::max(Rational(0), Rational(at - delta)), std::min(Rational(1), Rational(at + delta))};
                  if (verify::crossing_certain(eo, along, go, nullptr)) piece = along;
                }
              } else {
                piece = order == 0 ? crossing_piece_of(pc, po, f, f) : crossing_piece_of(f, f, pc, po);
              }
              if (!piece) continue;
              SlicedApartProof proof;
              proof.planar_edge = order == 0;
              proof.edge_loop = order == 0 ? i : k;
              proof.edge = order == 0 ? j : l;
              proof.across_loop = order == 0 ? k : i;
              proof.across = order == 0 ? l : j;
              proof.along = *piece;
              // (proved by crossing_certain over the box: the verifier's check of the finished tree repeats it)
              proofs_[n] = proof;
              state_[n] = State::blocked;
              tree_.nodes[n].blocked = true;
              return;
            }
          }
    // no crossing proved: a point strictly inside both parts at the middle, off the planar part's
    // boundary over the box (the fixed part does not move): the points of a 6 x 6 grid over the
    // planar part's box at the middle, the farthest from its boundary first, then the oracle's witness
    {
      Rational x0 = placed.loops[0][0].source.x, x1 = x0, y0 = placed.loops[0][0].source.y, y1 = y0;
      for (const auto& loop : placed.loops)
        for (const verify::PlacedEdge& e : loop) {
          x0 = std::min(x0, e.box[0]), x1 = std::max(x1, e.box[1]), y0 = std::min(y0, e.box[2]), y1 = std::max(y1, e.box[3]);
        }
      std::optional<Point> best;
      Rational best_bound(0);
      for (int i = 1; i <= 6; ++i)
        for (int j = 1; j <= 6; ++j) {
          const Point p{Rational(x0 + (x1 - x0) * Rational(2 * i - 1, 12)), Rational(y0 + (y1 - y0) * Rational(2 * j - 1, 12))};
          if (verify::locate(placed_fixed_, p) <= 0 || verify::locate(placed, p) <= 0) continue;
          const Rational bound = verify::point_boundary_distance_lower_bound(shape_planar_, map, p, enough_);
          if (bound > best_bound) best = p, best_bound = bound;
        }
      if (best) {
        SlicedApartProof proof;
        proof.kind = SlicedApartProof::Kind::point;
        proof.point = Point{Rational(best->x - planar_.motion.pivot.x), Rational(best->y - planar_.motion.pivot.y)};
        if (try_proof(n, proof)) return;
      }
    }
    const Placement placement = placement_about(planar_.motion.pivot, exact.c, exact.s, Point{middle.x, middle.y});
    const PartOverlap overlap = part_overlap(fixed_, Placement{}, planar_, placement, true);
    if (overlap.relation == PartRelation::overlapping && overlap.witness) {
      SlicedApartProof proof;
      proof.kind = SlicedApartProof::Kind::point;
      proof.point = Point{Rational(overlap.witness->x - planar_.motion.pivot.x), Rational(overlap.witness->y - planar_.motion.pivot.y)};
      try_proof(n, proof);
    }
  }

  const Part& fixed_;
  const Part& planar_;
  verify::IntervalPart shape_fixed_, shape_planar_, posed_fixed_;
  verify::PlacedPart placed_fixed_;
  Rational reach_, enough_;
  ApartTree tree_;
  std::vector<State> state_;
  std::unordered_map<std::size_t, SlicedApartProof> proofs_;
  std::vector<std::vector<std::size_t>> adjacent_{1};   // each leaf's neighbours (closed boxes meet)
  std::size_t leaves_ = 1, max_leaves_;
};

std::pair<const Part*, const Part*> apart_parts(const Model& model, const std::string& fixed, const std::string& planar) {
  const Part& fixed_part = part_of(model, fixed);
  const Part& planar_part = part_of(model, planar);
  if (fixed_part.motion.kind != Motion::Kind::fixed) throw GeometryError("sliced_apart: part '" + fixed + "' must be fixed");
  if (planar_part.motion.kind != Motion::Kind::planar)
    throw GeometryError("sliced_apart: part '" + planar + "' must be free in the plane (motion \"planar\")");
  if (planar_part.motion.angle_limits || planar_part.motion.translation_limits)
    throw GeometryError("sliced_apart: part '" + planar + "' has motion limits");
  return {&fixed_part, &planar_part};
}

std::string proof_text(const SlicedApartProof& p) {
  using certificate_json::quoted_text;
  if (p.kind == SlicedApartProof::Kind::point)
    return "[\"point\", " + quoted_text(to_exact_string(p.point.x)) + ", " + quoted_text(to_exact_string(p.point.y)) + "]";
  auto index = [](std::size_t i) { return "\"" + std::to_string(i) + "\""; };
  return std::string("[\"cross\", ") + (p.planar_edge ? "\"planar\"" : "\"fixed\"") + ", " + index(p.edge_loop) + ", " +
         index(p.edge) + ", " + index(p.across_loop) + ", " + index(p.across) + ", " +
         quoted_text(to_exact_string(p.along.lo)) + ", " + quoted_text(to_exact_string(p.along.hi)) + "]";
}

std::string range_text(const RationalInterval& r) {
  return "[" + certificate_json::quoted_text(to_exact_string(r.lo)) + ", " + certificate_json::quoted_text(to_exact_string(r.hi)) + "]";
}

}  // namespace

std::string write_sliced_apart_certificate(const SlicedApartCertificate& c) {
  std::string out = certificate_json::envelope(c.envelope, 1, "sliced_apart");
  out += "  \"sliced_apart\": {\n    \"a\": " + certificate_json::pose(c.a, true) + ",\n    \"b\": " + certificate_json::pose(c.b, true) +
         ",\n    \"domain\": {\"x\": " + range_text(c.x) + ", \"y\": " + range_text(c.y) +
         ", \"angle\": " + (c.full_turn ? std::string("\"full\"") : range_text(c.u)) + "},\n    \"tree\": " +
         certificate_json::quoted_text(c.tree) + ",\n    \"proofs\": [";
  for (std::size_t i = 0; i < c.proofs.size(); ++i) out += std::string(i ? ",\n      " : "\n      ") + proof_text(c.proofs[i]);
  out += c.proofs.empty() ? "]" : "\n    ]";
  return out + "\n  }\n}\n";
}

SlicedApartResult certify_sliced_apart(const Model& model, const std::string& fixed, const PlanarPose& a, const PlanarPose& b,
                                       const CertifyContext& context, std::size_t max_leaves) {
  if (b.part != a.part) throw ModelError("", "sliced_apart: both poses must be of one part");
  if (a.slide || b.slide) throw ModelError("", "sliced_apart: poses are x, y and tangent, not a slide");
  apart_parts(model, fixed, a.part);
  std::optional<Model> moved = verify::connected_pair_at_origin(model, fixed, a.part);
  const Model& at = moved ? *moved : model;
  auto [fixed_part, planar_part] = apart_parts(at, fixed, a.part);
  SlicedApartResult result;
  for (const PlanarPose* end : {&a, &b}) {
    std::string failure = verify::sliced_move_failure(*fixed_part, *planar_part, *end, *end);
    if (failure.empty()) {
      try {
        verify::check_nesting(verify::place(*fixed_part, verify::ExactMap{}),
                              verify::place(*planar_part, verify::planar_pose_map(*planar_part, *end)), "there");
      } catch (const verify::Rejection& rejection) {
        failure = rejection.reason;
      }
    }
    if (!failure.empty()) {
      result.failure = std::string("the end ") + (end == &a ? "a" : "b") + " is not certainly free: " + failure;
      return result;
    }
  }
  const Rational reach = verify::reach(verify::shape_of(*planar_part));
  std::string failures;
  for (int k : {1, 2, 0, 3, 4}) {   // half the reach first: a wall at the reach is often all boundary
    const Rational h = round_down((sgn(reach) > 0 ? reach : Rational(1)) / Rational(1 << k), 2);
    if (abs(b.x - a.x) >= h || abs(b.y - a.y) >= h) continue;   // b within the domain
    ApartBox domain;
    domain.lo[0] = a.x - h, domain.hi[0] = a.x + h, domain.lo[1] = a.y - h, domain.hi[1] = a.y + h;
    domain.lo[2] = -1, domain.hi[2] = 3;
    ApartSearch search(*fixed_part, *planar_part, domain, max_leaves);
    std::string why = search.run(a, b);
    result.leaves = search.leaves();
    result.blocked = search.blocked();
    if (why.empty()) {
      SlicedApartCertificate c = search.certificate_body();
      c.envelope = start_certificate(model, context, ClaimKind::planar_clearance, fixed, a.part);
      c.a = a;
      c.b = b;
      c.envelope.statement = sliced_apart_statement(c);
      VerificationResult check = check_sliced_apart(c, model);
      if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
      result.certificate = std::move(c);
      return result;
    }
    failures += (failures.empty() ? "" : "; ") + std::string("h = ") + to_decimal_string(h) + ": " + why;
    // another domain only when this one's boundary has free poses (the work spent on a wall that
    // would not close is not repeated: bounded by max_leaves and the five domains)
    if (why != "the domain's boundary has free poses") break;
  }
  result.failure = "no separation proved: " +
                   (failures.empty() ? std::string("b lies too far from a for the domains tried") : failures);
  return result;
}

}  // namespace hipair

