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
#include "certify/planar_check.hpp"
#include "certify/sliced_apart.hpp"
#include "certify/sliced_connected.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced_apart.hpp>
#include <hipair/sliced_certificate.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <queue>
#include <unordered_map>

namespace hipair {
namespace {

using namespace certify_detail;

enum class State : char { blocked, free, mixed };

// the placement of an exact map (p -> pivot + R (p - pivot) + shift)
Placement placement_of(const verify::ExactMap& m) { return placement_about(m.pivot, m.c, m.s, m.shift); }

class ApartSearch {
 public:
  // `tree` holds the domain (its axes' seams and closed faces set); `weights` scale the box's
  // sides to lengths (mm per unit of each coordinate) when the longest is halved
  ApartSearch(const verify::ApartPair& pair, verify::ApartTree tree, const Rational (&weights)[3], std::size_t max_leaves)
      : pair_(pair), tree_(std::move(tree)), max_leaves_(max_leaves) {
    for (int k = 0; k < 3; ++k) weights_[k] = weights[k];
    enough_ = weights[2];
    if (sgn(enough_) <= 0) enough_ = 1;
    // (the free test needs only the sign of the bound, and its sign does not depend on the cap:
    // a pair skipped is farther than the cap; a tiny cap skips every pair that is not close,
    // session 72)
    apart_cap_ = enough_ / Rational(mpz_class(1) << 32);
    evaluate(0);
  }

  // "" when a's open boxes and b's are in different components; else why not.
  std::string run(const Rational (&a)[3], const Rational (&b)[3]) {
    // 1. the domain's walled faces blocked
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
    std::vector<std::size_t> chain;
    std::string why;
    if (free_chain(a, b, chain, why))
      return "a chain of boxes proved free joins a and b: they are connected (not certified here: --claim connected certifies it)";
    return why;
  }

  // Splits the mixed boxes of shortest chains of open boxes from a to b until no chain is left
  // (false, `why` empty), a chain of boxes proved free joins them (true; `chain` the leaves from
  // a's to b's, consecutive closed boxes meeting), or a limit is reached (false, `why` says so).
  // `prefer_free` (the connected producer): the chains are the cheapest with a box proved free
  // costing 1 and a mixed one 8, so that a chain around a wall of mixed boxes is found before the
  // wall's boxes are all split.
  bool free_chain(const Rational (&a)[3], const Rational (&b)[3], std::vector<std::size_t>& chain, std::string& why,
                  bool prefer_free = false) {
    for (;;) {
      std::vector<std::size_t> from = open_at(a), to = open_at(b);
      if (from.empty() || to.empty()) {
        why = "an end lies in blocked boxes only";
        return false;
      }
      std::unordered_map<std::size_t, std::size_t> parent;
      std::deque<std::size_t> frontier;
      for (std::size_t n : from) parent.emplace(n, n), frontier.push_back(n);
      std::size_t reached = std::size_t(-1);
      if (prefer_free) {
        using Entry = std::pair<std::size_t, std::size_t>;   // (cost, leaf)
        std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
        std::unordered_map<std::size_t, std::size_t> cost;
        for (std::size_t n : from) cost[n] = 0, queue.push({0, n});
        while (!queue.empty()) {
          const auto [c, n] = queue.top();
          queue.pop();
          if (c != cost[n]) continue;
          if (std::find(to.begin(), to.end(), n) != to.end()) {
            reached = n;
            break;
          }
          for (std::size_t m : adjacent_[n]) {
            if (state_[m] == State::blocked) continue;
            const std::size_t next = c + (state_[m] == State::free ? 1 : 8);
            auto found = cost.find(m);
            if (found != cost.end() && found->second <= next) continue;
            cost[m] = next;
            parent[m] = n;
            queue.push({next, m});
          }
        }
        frontier.clear();
      }
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
      if (reached == std::size_t(-1)) return false;
      std::vector<std::size_t> mixed;
      chain.clear();
      for (std::size_t n = reached;; n = parent[n]) {
        chain.push_back(n);
        if (state_[n] == State::mixed) mixed.push_back(n);
        if (parent[n] == n) break;
      }
      if (mixed.empty()) {
        std::reverse(chain.begin(), chain.end());
        return true;
      }
      for (std::size_t n : mixed)
        if (why = split(n, look_ahead_); !why.empty()) return false;
    }
  }

  const verify::ApartTree& tree() const { return tree_; }

  // the tree and its proofs (preorder); the domain's ranges
  SlicedApartCertificate certificate_body() const {
    SlicedApartCertificate c;
    const verify::ApartBox& d = tree_.nodes[0].box;
    c.x = RationalInterval{d.lo[0], d.hi[0]};
    c.y = RationalInterval{d.lo[1], d.hi[1]};
    c.full_turn = tree_.periodic[2];
    c.u = RationalInterval{d.lo[2], d.hi[2]};
    c.tree = verify::apart_tree_text(tree_);
    std::vector<std::size_t> stack{0};   // proofs in the tree's preorder
    while (!stack.empty()) {
      const verify::ApartTree::Node& node = tree_.nodes[stack.back()];
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
  std::vector<std::size_t> open_at(const Rational (&at)[3]) const {
    std::vector<std::size_t> out;
    for (std::size_t n : verify::apart_leaves_at(tree_, at))
      if (state_[n] != State::blocked) out.push_back(n);
    return out;
  }

  // Halves leaf n. Plain: along its longest side (lengths in mm: weights_). Looking ahead (the
  // mixed boxes of a chain from a to b): along the side, among those at least a quarter of the
  // longest, whose halves are decided (blocked or free) the most, the longest on a tie; the
  // halves' outcomes tried are kept.
  std::string split(std::size_t n, bool look_ahead = false) {
    if (tree_.nodes[n].depth + 1 >= verify::apart_max_depth) return "boxes reached the verifier's depth limit near " + where(n);
    if (leaves_ + 1 > max_leaves_) return "more than " + std::to_string(max_leaves_) + " boxes (stuck near " + where(n) + ")";
    const verify::ApartBox box = tree_.nodes[n].box;
    Rational sizes[3];
    for (int k = 0; k < 3; ++k) sizes[k] = (box.hi[k] - box.lo[k]) * weights_[k];
    int axis = int(std::max_element(sizes, sizes + 3) - sizes);
    std::optional<std::pair<Outcome, Outcome>> halves;
    if (look_ahead) {
      int best_score = -1;
      for (int k : {axis, (axis + 1) % 3, (axis + 2) % 3}) {
        if (sgn(sizes[k]) <= 0 || sizes[k] * 4 < sizes[axis]) continue;
        verify::ApartBox lower = box, upper = box;
        lower.hi[k] = upper.lo[k] = (box.lo[k] + box.hi[k]) / 2;
        std::pair<Outcome, Outcome> tried{assess(lower), assess(upper)};
        const int score = int(tried.first.state != State::mixed) + int(tried.second.state != State::mixed);
        if (score > best_score) best_score = score, axis = k, halves = std::move(tried);
        if (score == 2) break;
      }
    }
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
    record(first, halves ? halves->first : assess(tree_.nodes[first].box));
    record(first + 1, halves ? halves->second : assess(tree_.nodes[first + 1].box));
    return "";
  }

  std::string where(std::size_t n) const {
    const verify::ApartBox& b = tree_.nodes[n].box;
    std::string out;
    for (int k = 0; k < 3; ++k) out += std::string(k ? ", " : "") + tree_.marks[k] + " = " + to_decimal_string(b.lo[k]);
    return out;
  }

  // what a box is: free, blocked (with its proof) or mixed
  struct Outcome {
    State state = State::mixed;
    std::optional<SlicedApartProof> proof;
  };

  void evaluate(std::size_t n) { record(n, assess(tree_.nodes[n].box)); }

  void record(std::size_t n, const Outcome& outcome) {
    state_.resize(tree_.nodes.size(), State::mixed);
    state_[n] = outcome.state;
    if (outcome.state == State::blocked) {
      proofs_[n] = *outcome.proof;
      tree_.nodes[n].blocked = true;
    }
  }

  // a point proof's point: world (pin-slot claims) or relative to the planar part's pivot
  SlicedApartProof point_proof(const Point& world) const {
    SlicedApartProof proof;
    proof.kind = SlicedApartProof::Kind::point;
    const Point& pivot = pair_.moving.motion.pivot;
    proof.point = pair_.pin_slot ? world : Point{Rational(world.x - pivot.x), Rational(world.y - pivot.y)};
    return proof;
  }

  Outcome assess(const verify::ApartBox& box) const {
    auto blocked_by = [](const SlicedApartProof& proof) { return Outcome{State::blocked, proof}; };
    auto proved = [&](const SlicedApartProof& proof) { return verify::apart_proof_failure(pair_, box, proof).empty(); };
    Rational middle[3];
    verify::apart_middle(box, middle);
    const verify::ExactMap exact = pair_.moving_at(middle[0], middle[1], middle[2]);
    const verify::ExactMap other_exact = pair_.other_at(middle[0]);
    const bool other_moves = pair_.other.motion.kind != Motion::Kind::fixed;
    const verify::IntervalMap map = pair_.moving_over(box), other_map = pair_.other_over(box);
    const verify::PlacedPart placed = verify::place(pair_.moving, exact);
    const verify::PlacedPart placed_other = other_moves ? verify::place(pair_.other, other_exact) : pair_.other_placed;
    // the boundaries apart over the whole box: free, or nested (blocked) at every pose
    const bool apart_over =
        sgn(verify::boundary_distance_lower_bound(pair_.other_shape, other_map, pair_.moving_shape, map, apart_cap_)) > 0;
    if (apart_over) {
      bool nested = false;
      for (int side = 0; side < 2 && !nested; ++side) {
        const verify::PlacedPart& inner = side ? placed : placed_other;
        const verify::PlacedPart& outer = side ? placed_other : placed;
        for (const auto& loop : inner.loops)
          if (!loop.empty() && verify::locate(outer, loop[0].source) >= 0) nested = true;
      }
      if (!nested) return Outcome{State::free, std::nullopt};
    }
    // a blocked box's middle overlaps (each proof below shows a point strictly inside both parts
    // there): the exact predicate at the middle first, so that a box whose middle is apart or
    // touching is mixed without the tests below (session 72: most of the connected producer's
    // boxes in thin free space)
    // (asked once, with its witness: the last resort below)
    const PartOverlap overlap = part_overlap(pair_.other, placement_of(other_exact), pair_.moving, placement_of(exact), true);
    if (overlap.relation != PartRelation::overlapping) return Outcome{};
    // edges crossing at the middle, their crossing pieces tried over the box
    const verify::IntervalPart at_middle = verify::place_over(pair_.moving_shape, verify::to_interval_map(exact));
    const verify::IntervalPart other_middle = verify::place_over(pair_.other_shape, verify::to_interval_map(other_exact));
    std::optional<verify::IntervalPart> over, other_over;
    for (std::size_t i = 0; i < placed.loops.size(); ++i)
      for (std::size_t j = 0; j < placed.loops[i].size(); ++j)
        for (std::size_t k = 0; k < placed_other.loops.size(); ++k)
          for (std::size_t l = 0; l < placed_other.loops[k].size(); ++l) {
            if (!verify::edges_cross(placed.loops[i][j], placed_other.loops[k][l])) continue;
            if (!over) over = verify::place_over(pair_.moving_shape, map), other_over = verify::place_over(pair_.other_shape, other_map);
            const verify::IntervalEdge &pc = at_middle.loops[i][j], &po = over->loops[i][j];
            const verify::IntervalEdge &fc = other_middle.loops[k][l], &fo = other_over->loops[k][l];
            for (int order = 0; order < 2; ++order) {
              const verify::PlacedEdge& pe = order == 0 ? placed.loops[i][j] : placed_other.loops[k][l];
              const verify::PlacedEdge& pg = order == 0 ? placed_other.loops[k][l] : placed.loops[i][j];
              const verify::IntervalEdge& eo = order == 0 ? po : fo;
              const verify::IntervalEdge& go = order == 0 ? fo : po;
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
                piece = order == 0 ? crossing_piece_of(pc, po, fc, fo) : crossing_piece_of(fc, fo, pc, po);
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
              return blocked_by(proof);
            }
          }
    // no crossing proved: a point strictly inside both parts at the middle, off the moving
    // boundaries over the box: the points of a 6 x 6 grid over the moving part's box at the
    // middle, the farthest from its boundary first, then the oracle's witness
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
          if (verify::locate(placed_other, p) <= 0 || verify::locate(placed, p) <= 0) continue;
          Rational bound = verify::point_boundary_distance_lower_bound(pair_.moving_shape, map, p, enough_);
          if (other_moves && sgn(bound) > 0)
            bound = std::min(bound, verify::point_boundary_distance_lower_bound(pair_.other_shape, other_map, p, enough_));
          if (bound > best_bound) best = p, best_bound = bound;
        }
      if (best && proved(point_proof(*best))) return blocked_by(point_proof(*best));
    }
    if (overlap.witness && proved(point_proof(*overlap.witness)))
      return blocked_by(point_proof(*overlap.witness));
    return Outcome{};
  }

  const verify::ApartPair& pair_;
  verify::ApartTree tree_;
  Rational weights_[3], enough_, apart_cap_;
  std::vector<State> state_;
  std::unordered_map<std::size_t, SlicedApartProof> proofs_;
  std::vector<std::vector<std::size_t>> adjacent_{1};   // each leaf's neighbours (closed boxes meet)
  std::size_t leaves_ = 1, max_leaves_;
  bool look_ahead_ = true;   // chains' mixed boxes halved looking ahead (session 70: 3-15 % fewer boxes)
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
  using certificate_json::position;
  using certificate_json::quoted_text;
  std::string out = certificate_json::envelope(c.envelope, 1, "sliced_apart");
  out += "  \"sliced_apart\": {\n    \"a\": " + certificate_json::pose(c.a, true) + ",\n    \"b\": " + certificate_json::pose(c.b, true);
  if (c.a_other && c.b_other) out += ",\n    \"a_other\": " + position(*c.a_other) + ",\n    \"b_other\": " + position(*c.b_other);
  const std::string angle = c.full_turn ? std::string("\"full\"") : range_text(c.u);
  if (c.pin_slot)
    out += ",\n    \"domain\": {" +
           (c.a_other ? "\"other\": " + (c.other_full_turn ? std::string("\"full\"") : range_text(c.x)) + ", " : std::string()) +
           "\"slide\": " + range_text(c.y) + ", \"angle\": " + angle + "}";
  else
    out += ",\n    \"domain\": {\"x\": " + range_text(c.x) + ", \"y\": " + range_text(c.y) + ", \"angle\": " + angle + "}";
  out += ",\n    \"tree\": " + quoted_text(c.tree) + ",\n    \"proofs\": [";
  for (std::size_t i = 0; i < c.proofs.size(); ++i) out += std::string(i ? ",\n      " : "\n      ") + proof_text(c.proofs[i]);
  out += c.proofs.empty() ? "]" : "\n    ]";
  return out + "\n  }\n}\n";
}

namespace {

// the certificate of the search's tree, self-checked by the verifier's code
SlicedApartCertificate finished(const ApartSearch& search, const Model& model, const CertifyContext& context, const std::string& other,
                                const PlanarPose& a, const PlanarPose& b, const std::optional<ExactPosition>& a_other,
                                const std::optional<ExactPosition>& b_other, bool other_full_turn) {
  SlicedApartCertificate c = search.certificate_body();
  c.envelope = start_certificate(model, context, ClaimKind::planar_clearance, other, a.part);
  c.a = a;
  c.b = b;
  c.pin_slot = bool(a.slide);
  c.a_other = a_other;
  c.b_other = b_other;
  c.other_full_turn = other_full_turn;
  c.envelope.statement = sliced_apart_statement(c);
  VerificationResult check = check_sliced_apart(c, model);
  if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
  return c;
}

}  // namespace

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
  const verify::ApartPair pair(*fixed_part, *planar_part);
  const Rational reach = verify::reach(pair.moving_shape);
  const Rational weights[3] = {Rational(1), Rational(1), sgn(reach) > 0 ? reach : Rational(1)};
  Rational at_a[3], at_b[3];
  pair.coordinates(a, std::nullopt, at_a);
  pair.coordinates(b, std::nullopt, at_b);
  std::string failures;
  for (int k : {1, 2, 0, 3, 4}) {   // half the reach first: a wall at the reach is often all boundary
    const Rational h = round_down((sgn(reach) > 0 ? reach : Rational(1)) / Rational(1 << k), 2);
    if (abs(b.x - a.x) >= h || abs(b.y - a.y) >= h) continue;   // b within the domain
    verify::ApartTree tree;
    tree.nodes.push_back(verify::ApartTree::Node{});
    verify::ApartBox& domain = tree.nodes[0].box;
    domain.lo[0] = a.x - h, domain.hi[0] = a.x + h, domain.lo[1] = a.y - h, domain.hi[1] = a.y + h;
    domain.lo[2] = -1, domain.hi[2] = 3;
    ApartSearch search(pair, std::move(tree), weights, max_leaves);
    std::string why = search.run(at_a, at_b);
    result.leaves = search.leaves();
    result.blocked = search.blocked();
    if (why.empty()) {
      result.certificate = finished(search, model, context, fixed, a, b, std::nullopt, std::nullopt, false);
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

namespace {

// The search of a pin-slot claim (apart, connected): the pair, the ends' coordinates (q, s, u) and
// the domain around them, or why an end is not certainly free (`failure`).
struct PinSlotSearch {
  std::optional<verify::ApartPair> pair;
  Rational at_a[3], at_b[3];
  verify::ApartTree tree;
  Rational weights[3];
  bool full_other = false;
  std::string failure;
};

// A range [lo, hi] of an angle coordinate (u, see <hipair/sliced_apart.hpp>) holding the ends'
// coordinates e0, e1 and within `limits` (rad), chosen in doubles (the caller checks it with the
// verifier's apart_limits_failure); the full turn [-1, 3] (periodic) without limits.
void angle_range(const std::optional<RationalInterval>& limits, const Rational& e0, const Rational& e1, Rational& lo, Rational& hi,
                 bool& periodic) {
  const double pi = 3.141592653589793;
  periodic = !limits || Rational(limits->hi - limits->lo).get_d() > 2 * pi + 1e-3;
  if (periodic) {
    lo = -1, hi = 3;
    return;
  }
  double l = limits->lo.get_d(), h = limits->hi.get_d();
  const double shift = 2 * pi * std::floor((l + pi / 2) / (2 * pi));   // l in [-pi/2, 3pi/2): the coordinate's chart
  l -= shift, h -= shift;
  auto u_of = [&](double theta) { return theta <= pi / 2 ? std::tan(theta / 2) : 2 + std::tan((theta - pi) / 2); };
  double ul = u_of(l), uh = u_of(std::min(h, 2 * pi - 1e-3));
  ul += 1e-9 * (1 + std::fabs(ul)), uh -= 1e-9 * (1 + std::fabs(uh));
  lo = std::min({approximate(ul), e0, e1});
  hi = std::max({approximate(uh), e0, e1});
}

PinSlotSearch pin_slot_search(const Model& model, const std::string& other, const PlanarPose& a, const std::optional<ExactPosition>& a_other,
                              const PlanarPose& b, const std::optional<ExactPosition>& b_other, const std::string& claim,
                              bool within_limits) {
  if (b.part != a.part) throw ModelError("", claim + ": both poses must be of one part");
  if (!a.slide || !b.slide) throw ModelError("", claim + ": a pin-slot part's poses give its slide and tangent");
  const Part& other_part = part_of(model, other);
  const Part& moving = part_of(model, a.part);
  if (&other_part == &moving) throw ModelError("", claim + ": a pair needs two different parts");
  if (moving.motion.kind != Motion::Kind::pin_slot) throw GeometryError(claim + ": part '" + a.part + "' has no pin_slot motion");
  const Motion::Kind kind = other_part.motion.kind;
  if (kind != Motion::Kind::fixed && kind != Motion::Kind::rotation && kind != Motion::Kind::translation)
    throw GeometryError(claim + ": part '" + other + "' must be fixed, rotate or translate (against a pin-slot part)");
  const bool offsets = kind == Motion::Kind::translation;
  if ((kind == Motion::Kind::fixed) != (!a_other || !b_other) ||
      (a_other && b_other && (a_other->is_offset != offsets || b_other->is_offset != offsets)))
    throw ModelError("", claim + ": give the positions of '" + other + "' at both ends exactly when it moves (" +
                             (kind == Motion::Kind::translation ? "offsets" : "tangents") + ")");
  PinSlotSearch search;
  search.pair.emplace(other_part, moving);
  const verify::ApartPair& pair = *search.pair;
  Rational(&at_a)[3] = search.at_a;
  Rational(&at_b)[3] = search.at_b;
  pair.coordinates(a, a_other, at_a);
  pair.coordinates(b, b_other, at_b);
  const auto& slide_limits = moving.motion.translation_limits;
  const auto& offset_limits = other_part.motion.translation_limits;
  for (int end = 0; end < 2; ++end) {
    const PlanarPose& pose = end == 0 ? a : b;
    const std::optional<ExactPosition>& position = end == 0 ? a_other : b_other;
    const std::string which = end == 0 ? "a" : "b";
    // a configuration of the mechanism (the verifier's tests): else bad input
    if (slide_limits && (*pose.slide < slide_limits->lo || *pose.slide > slide_limits->hi))
      throw ModelError("", claim + ": the end " + which + ": the slide of '" + moving.name + "' (" + to_decimal_string(*pose.slide) +
                               ") is outside its limits [" + to_decimal_string(slide_limits->lo) + ", " +
                               to_decimal_string(slide_limits->hi) + "]");
    if (!verify::certainly_within(moving.motion.angle_limits, verify::angle_of_tangent(pose.tangent, pose.half_turn), true))
      throw ModelError("", claim + ": the end " + which + ": the angle of '" + moving.name + "' is not certainly within its limits");
    if (position) {
      try {
        verify::exact_map(other_part, {{other, *position}});
      } catch (const verify::Rejection& rejection) {
        throw ModelError("", claim + ": the end " + which + ": " + rejection.reason);
      }
    }
    const std::string failure = verify::apart_pin_slot_end_failure(pair, end == 0 ? at_a : at_b);
    if (!failure.empty()) {
      search.failure = "the end " + which + " is not certainly free: " + failure;
      return search;
    }
  }
  // the domain: q the other's full turn, its offset limits (or the ends +- the reaches), s the
  // slide limits (or the ends +- the part's reach), u the full turn; a connected claim's search
  // (`within_limits`) keeps to the rotating parts' angle limits too
  const Rational reach = verify::reach_about_pivot(moving);   // about the pin
  const Rational other_reach = kind == Motion::Kind::rotation ? verify::reach_about_pivot(other_part) : Rational(1);
  verify::ApartTree& tree = search.tree;
  tree.marks = "qsu";
  tree.nodes.push_back(verify::ApartTree::Node{});
  verify::ApartBox& d = tree.nodes[0].box;
  auto around = [&](int k, const Rational& margin) {
    d.lo[k] = std::min(at_a[k], at_b[k]) - margin;
    d.hi[k] = std::max(at_a[k], at_b[k]) + margin;
  };
  const bool full_other = kind == Motion::Kind::rotation;
  if (kind == Motion::Kind::fixed) {
    d.lo[0] = d.hi[0] = 0;
    tree.closed_lo[0] = tree.closed_hi[0] = true;
  } else if (full_other) {
    bool periodic = true;
    if (within_limits) angle_range(other_part.motion.angle_limits, at_a[0], at_b[0], d.lo[0], d.hi[0], periodic);
    else d.lo[0] = -1, d.hi[0] = 3;
    tree.periodic[0] = periodic;
  } else if (offset_limits && offset_limits->lo < offset_limits->hi) {
    d.lo[0] = offset_limits->lo, d.hi[0] = offset_limits->hi;
    tree.closed_lo[0] = tree.closed_hi[0] = true;
  } else {
    around(0, reach + other_reach);
  }
  if (slide_limits && slide_limits->lo < slide_limits->hi) {
    d.lo[1] = slide_limits->lo, d.hi[1] = slide_limits->hi;
    tree.closed_lo[1] = tree.closed_hi[1] = true;
  } else {
    around(1, sgn(reach) > 0 ? reach : Rational(1));
  }
  if (within_limits) {
    angle_range(moving.motion.angle_limits, at_a[2], at_b[2], d.lo[2], d.hi[2], tree.periodic[2]);
  } else {
    d.lo[2] = -1, d.hi[2] = 3;
  }
  if (within_limits)
    if (std::string why = verify::apart_limits_failure(pair, d); !why.empty())
      throw GeometryError(claim + ": the search's domain could not be placed within the motion limits (" + why + ")");
  const Rational slide_reach = std::max(Rational(abs(d.lo[1])), Rational(abs(d.hi[1])));
  search.weights[0] = kind == Motion::Kind::fixed ? Rational(0) : full_other ? other_reach : Rational(1);
  search.weights[1] = Rational(1);
  search.weights[2] = Rational(reach + slide_reach);
  search.full_other = full_other;
  return search;
}

// The staircase through a chain of boxes proved free (consecutive closed boxes meeting): from
// `a` to a point of each shared face (across a periodic seam: the same configuration at 3 and at
// -1) and on to `b`, one coordinate at a time, every step inside one closed box of the chain.
std::vector<std::array<Rational, 3>> staircase_through(const verify::ApartTree& tree, const std::vector<std::size_t>& chain,
                                                       const Rational (&a)[3], const Rational (&b)[3]) {
  std::vector<std::array<Rational, 3>> steps{{a[0], a[1], a[2]}};
  auto walk_to = [&](const Rational (&target)[3]) {
    for (int k = 0; k < 3; ++k) {
      if (steps.back()[k] == target[k]) continue;
      std::array<Rational, 3> next = steps.back();
      next[k] = target[k];
      steps.push_back(next);
    }
  };
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    const verify::ApartBox &here = tree.nodes[chain[i]].box, &there = tree.nodes[chain[i + 1]].box;
    Rational in_here[3], in_there[3];
    for (int k = 0; k < 3; ++k) {
      const Rational lo = std::max(here.lo[k], there.lo[k]), hi = std::min(here.hi[k], there.hi[k]);
      if (lo <= hi) {
        in_here[k] = in_there[k] = (lo + hi) / 2;
      } else {   // across the seam of a periodic axis
        const bool up = here.hi[k] == 3;
        in_here[k] = up ? Rational(3) : Rational(-1);
        in_there[k] = up ? Rational(-1) : Rational(3);
      }
    }
    walk_to(in_here);
    if (steps.back() != std::array<Rational, 3>{in_there[0], in_there[1], in_there[2]}) steps.push_back({in_there[0], in_there[1], in_there[2]});
  }
  walk_to(b);
  return steps;
}

}  // namespace

SlicedApartResult certify_pin_slot_apart(const Model& model, const std::string& other, const PlanarPose& a,
                                         const std::optional<ExactPosition>& a_other, const PlanarPose& b,
                                         const std::optional<ExactPosition>& b_other, const CertifyContext& context,
                                         std::size_t max_leaves) {
  PinSlotSearch setup = pin_slot_search(model, other, a, a_other, b, b_other, "sliced_apart", false);
  SlicedApartResult result;
  if (!setup.failure.empty()) {
    result.failure = setup.failure;
    return result;
  }
  ApartSearch search(*setup.pair, std::move(setup.tree), setup.weights, max_leaves);
  const std::string why = search.run(setup.at_a, setup.at_b);
  result.leaves = search.leaves();
  result.blocked = search.blocked();
  if (why.empty()) {
    result.certificate = finished(search, model, context, other, a, b, a_other, b_other, setup.full_other);
    return result;
  }
  result.failure = "no separation proved: " + why;
  return result;
}

SlicedConnectedResult certify_pin_slot_connected(const Model& model, const std::string& other, const PlanarPose& from,
                                                 const std::optional<ExactPosition>& from_other, const PlanarPose& to,
                                                 const std::optional<ExactPosition>& to_other, const CertifyContext& context,
                                                 std::size_t max_leaves) {
  PinSlotSearch setup = pin_slot_search(model, other, from, from_other, to, to_other, "sliced_connected", true);
  SlicedConnectedResult result;
  if (!setup.failure.empty()) {
    result.failure = setup.failure;
    return result;
  }
  // the ends joined by at most three moves, one coordinate each, in some order: no search
  std::vector<std::array<Rational, 3>> direct;
  for (const std::array<int, 3>& order : {std::array<int, 3>{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}) {
    direct.assign(1, {setup.at_a[0], setup.at_a[1], setup.at_a[2]});
    for (int k : order) {
      if (direct.back()[k] == setup.at_b[k]) continue;
      std::array<Rational, 3> next = direct.back();
      next[k] = setup.at_b[k];
      if (!verify::apart_move_failure(*setup.pair, direct.back().data(), next.data(), 1000).empty()) {
        direct.clear();
        break;
      }
      direct.push_back(next);
    }
    if (!direct.empty()) break;
  }
  // domains around the ends first (a path within a smaller domain is a path: its search is
  // cheaper), the ends' hull widened by 1/8, then 1/2 of the whole domain's sides, then the whole
  const verify::ApartBox whole = setup.tree.nodes[0].box;
  std::optional<ApartSearch> search;
  std::vector<std::size_t> chain;
  std::string why;
  for (int widening : {8, 2, 0}) {
    if (!direct.empty()) break;
    verify::ApartTree tree = setup.tree;
    verify::ApartBox& d = tree.nodes[0].box;
    if (widening > 0) {
      bool smaller = false;
      for (int k = 0; k < 3; ++k) {
        const Rational margin = (whole.hi[k] - whole.lo[k]) / widening;
        d.lo[k] = std::max(whole.lo[k], Rational(std::min(setup.at_a[k], setup.at_b[k]) - margin));
        d.hi[k] = std::min(whole.hi[k], Rational(std::max(setup.at_a[k], setup.at_b[k]) + margin));
        if (d.lo[k] != whole.lo[k] || d.hi[k] != whole.hi[k]) smaller = true, tree.periodic[k] = false;
      }
      if (!smaller) continue;
    }
    search.emplace(*setup.pair, std::move(tree), setup.weights, max_leaves);
    why.clear();
    if (search->free_chain(setup.at_a, setup.at_b, chain, why, true)) break;
    result.failure = why.empty() ? "no chain of boxes proved free joins the ends within the motion limits: the boxes proved "
                                   "blocked separate them there (--claim apart may certify it)"
                                 : "no path proved: " + why;
    if (!why.empty()) return result;   // a limit reached: a larger domain costs more
    search.reset();
  }
  if (!search && direct.empty()) return result;
  result.failure.clear();
  SlicedConnectedCertificate c;
  c.envelope = start_certificate(model, context, ClaimKind::planar_clearance, other, from.part);
  c.from = from;
  c.to = to;
  c.pin_slot = true;
  c.from_other = from_other;
  c.to_other = to_other;
  c.steps = search ? staircase_through(search->tree(), chain, setup.at_a, setup.at_b) : direct;
  c.envelope.statement = sliced_connected_statement(c);
  result.sliced_waypoints = chain.size();
  VerificationResult check = check_sliced_connected(c, model);
  if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
  result.certificate = std::move(c);
  return result;
}

}  // namespace hipair
