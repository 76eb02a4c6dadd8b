// The sliced_connected certificate: reader, writer, statement and the verifier's check
// (sliced_connected.hpp, docs/certify.md "Connected poses of a planar pair"). The check uses only
// the verifier's own exact and interval geometry.
#include "certify/sliced_connected.hpp"

#include "certify/certificate_json.hpp"
#include "certify/interval_geometry.hpp"
#include "certify/planar_check.hpp"
#include "certify/sliced_apart.hpp"
#include "certify/tolerance_support.hpp"
#include "core/model_scale.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>

namespace hipair {
namespace {

using certificate_json::JsonValue;
const char* const claim_name = "sliced_connected";

using verify::fraction_or_rounded;
using verify::part_named;
using verify::reject;
using verify::sliced_pose_words;

// A path vertex: ["x", "y", "tangent"] or ["x", "y", "tangent", "pi"] (the chart centred at the
// half turn: tangent = tan((theta - pi)/2)).
PlanarPose vertex_of(const JsonValue& value, const std::string& part) {
  const JsonValue& items = certificate_json::read_array(value);
  if (items.items.size() != 3 && items.items.size() != 4)
    certificate_json::refuse(value, "a path vertex is [\"x\", \"y\", \"tangent\"] or [\"x\", \"y\", \"tangent\", \"pi\"]");
  PlanarPose pose;
  pose.part = part;
  pose.x = certificate_json::read_rational(items.items[0]);
  pose.y = certificate_json::read_rational(items.items[1]);
  pose.tangent = certificate_json::read_rational(items.items[2]);
  if (items.items.size() == 4) {
    std::string centre = certificate_json::read_text(items.items[3]);
    if (centre != "pi" && centre != "0") certificate_json::refuse(items.items[3], "centre is \"0\" or \"pi\"");
    pose.half_turn = centre == "pi";
  }
  return pose;
}

bool same_pose(const Part& part, const PlanarPose& a, const PlanarPose& b) {
  verify::ExactMap p = verify::planar_pose_map(part, a), q = verify::planar_pose_map(part, b);
  return p.c == q.c && p.s == q.s && p.shift.x == q.shift.x && p.shift.y == q.shift.y;
}

}  // namespace

bool is_sliced_connected_certificate(std::string_view json_text) { return certificate_json::has_claim(json_text, claim_name); }

SlicedConnectedCertificate read_sliced_connected_certificate(std::string_view json_text) {
  JsonValue root = model_detail::parse_json(json_text);
  SlicedConnectedCertificate c;
  const JsonValue& body = certificate_json::read_claim(root, claim_name, c.envelope);
  certificate_json::keys(body, {"from", "to", "from_other", "to_other", "path", "steps"});
  c.from = certificate_json::read_pose(certificate_json::member(body, "from"));
  c.to = certificate_json::read_pose(certificate_json::member(body, "to"));
  c.pin_slot = bool(c.from.slide);
  if (bool(c.to.slide) != c.pin_slot)
    certificate_json::refuse(body, "both ends give a slide (a pin-slot part) or neither (a planar part: x, y and tangent)");
  if (!c.pin_slot) {
    for (const char* key : {"from_other", "to_other", "steps"})
      if (const JsonValue* found = body.find(key)) certificate_json::refuse(*found, "a planar part's claim has a path, not steps or other positions");
    for (const JsonValue& vertex : certificate_json::read_array(certificate_json::member(body, "path")).items)
      c.path.push_back(vertex_of(vertex, c.from.part));
    if (c.path.empty()) certificate_json::refuse(certificate_json::member(body, "path"), "the path has no vertex");
    return c;
  }
  // a pin-slot part (session 71): the other part's positions and the steps (q, s, u)
  if (const JsonValue* found = body.find("path")) certificate_json::refuse(*found, "a pin-slot claim's witness is \"steps\" [\"q\", \"s\", \"u\"]");
  for (const char* key : {"from_other", "to_other"})
    if (const JsonValue* other = body.find(key)) (key[0] == 'f' ? c.from_other : c.to_other) = verify::read_position(*other);
  if (bool(c.from_other) != bool(c.to_other)) certificate_json::refuse(body, "give the other part's position at both ends (from_other, to_other) or at neither");
  const JsonValue& steps = certificate_json::read_array(certificate_json::member(body, "steps"));
  for (const JsonValue& step : steps.items) {
    const JsonValue& items = certificate_json::read_array(step);
    if (items.items.size() != 3) certificate_json::refuse(step, "a step is [\"q\", \"s\", \"u\"]");
    c.steps.push_back({certificate_json::read_rational(items.items[0]), certificate_json::read_rational(items.items[1]),
                       certificate_json::read_rational(items.items[2])});
  }
  if (c.steps.empty()) certificate_json::refuse(certificate_json::member(body, "steps"), "the steps have no configuration");
  return c;
}

std::string sliced_connected_statement(const SlicedConnectedCertificate& c) {
  const std::string& fixed = c.envelope.first == c.from.part ? c.envelope.second : c.envelope.first;
  return "Part '" + c.from.part + "' moves from " + verify::sliced_end_words(c.from, c.from_other, fixed) + " to " +
         verify::sliced_end_words(c.to, c.to_other, fixed) + " without touching part '" + fixed + "'.";
}

namespace verify {

void reject(const std::string& reason) { throw Rejection{reason}; }

const Part& part_named(const Model& model, const std::string& name) {
  auto index = model.find_part(name);
  if (!index) reject("the model has no part '" + name + "'");
  return model.parts[*index];
}

std::string sliced_pose_words(const PlanarPose& p) {
  const std::string turned = (p.half_turn ? ", t(pi)=" : ", t=") + fraction_or_rounded(p.tangent);
  if (p.slide) return "s=" + fraction_or_rounded(*p.slide) + turned;
  return "x=" + fraction_or_rounded(p.x) + ", y=" + fraction_or_rounded(p.y) + turned;
}

std::optional<Model> connected_pair_at_origin(const Model& model, const std::string& fixed, const std::string& planar) {
  std::optional<Model> moved = pair_moved_to_origin(model, fixed, planar);
  const Model& at = moved ? *moved : model;
  auto index = at.find_part(planar);
  if (!index) return moved;
  const Point pivot = at.parts[*index].motion.pivot;
  if (sgn(pivot.x) == 0 && sgn(pivot.y) == 0) return moved;
  return translated_model(at, pivot);   // every point minus the pivot
}

const Part& SlicedPair::planar() const { return part_named(posed(), planar_name); }
const Part& SlicedPair::fixed() const { return part_named(posed(), fixed_name); }

SlicedPair checked_sliced_pair(const Certificate& envelope, const Model& model, const PlanarPose& a, const PlanarPose& b,
                               const std::string& a_words, const std::string& b_words, const std::string& claim) {
  check_certificate_model(envelope, model);
  const std::string &first = envelope.first, &second = envelope.second;
  if (first == second) reject("a pair needs two different parts");
  const std::string& name = a.part;
  if (b.part != name) reject("the claim poses '" + name + "' at " + a_words + " and '" + b.part + "' at " + b_words);
  if (name != first && name != second) reject("the posed part '" + name + "' is not a part of the pair");
  SlicedPair pair;
  pair.given = &model;
  pair.planar_name = name;
  pair.fixed_name = name == first ? second : first;
  // a pair far from the origin for its size is checked moved to it (its poses are relative:
  // moving both parts moves the pivot with them), as planar clearance claims are
  pair.moved = connected_pair_at_origin(model, pair.fixed_name, name);
  const Part &planar = pair.planar(), &fixed = pair.fixed();
  if (planar.motion.kind != Motion::Kind::planar) reject("part '" + name + "' is not free in the plane (motion \"planar\")");
  if (fixed.motion.kind != Motion::Kind::fixed) reject("part '" + pair.fixed_name + "' is not fixed");
  if (planar.motion.angle_limits || planar.motion.translation_limits)
    reject("part '" + name + "' has motion limits (" + claim + " claims cover parts without limits)");
  return pair;
}

std::string sliced_move_failure(const Part& fixed, const Part& planar, const PlanarPose& a, const PlanarPose& b,
                                std::size_t budget, std::size_t* pieces) {
  if (a.slide || b.slide) return "a pose with a slide (a connected claim poses x, y and tangent)";
  enum class Kind { stay, translation, rotation } kind;
  const bool same_xy = a.x == b.x && a.y == b.y, same_chart = a.half_turn == b.half_turn, same_t = a.tangent == b.tangent;
  if (same_xy && same_chart && same_t) kind = Kind::stay;
  else if (same_xy && !same_chart) {
    if (!same_pose(planar, a, b)) return "it changes the chart (centre) and the angle at once";
    kind = Kind::stay;
  } else if (same_xy) kind = Kind::rotation;
  else if (same_chart && same_t) kind = Kind::translation;
  else return "it changes both the offset and the rotation (each move is a pure translation or a pure rotation)";

  const IntervalPart shape_fixed = shape_of(fixed), shape_free = shape_of(planar);
  const IntervalMap identity;
  Rational enough = reach(shape_free) / Rational(mpz_class(1) << 32);
  if (sgn(enough) <= 0) enough = 1;
  const Point& pivot = planar.motion.pivot;
  auto pose_at = [&](const Rational& u) {
    PlanarPose p = a;
    if (kind == Kind::translation) {
      p.x = a.x + u * (b.x - a.x);
      p.y = a.y + u * (b.y - a.y);
    } else if (kind == Kind::rotation) {
      p.tangent = a.tangent + u * (b.tangent - a.tangent);
    }
    return p;
  };
  // every pose of the move with u in [u0, u1], enclosed
  auto map_over = [&](const Rational& u0, const Rational& u1) {
    if (kind == Kind::stay) return to_interval_map(planar_pose_map(planar, a));
    if (kind == Kind::translation) {
      IntervalMap m = to_interval_map(planar_pose_map(planar, a));
      const Interval u = hull2(Interval(u0), Interval(u1));
      m.shift.x = m.shift.x + Interval(Rational(b.x - a.x)) * u;
      m.shift.y = m.shift.y + Interval(Rational(b.y - a.y)) * u;
      return m;
    }
    // the tangent is monotone in u, so the angles of the piece lie between those of its ends
    const Interval angle = hull2(angle_of_tangent(pose_at(u0).tangent, a.half_turn), angle_of_tangent(pose_at(u1).tangent, a.half_turn));
    IntervalMap m;
    m.c = cos_of(angle);
    m.s = sin_of(angle);
    const Interval px(pivot.x), py(pivot.y);
    m.shift.x = px - (m.c * px - m.s * py) + Interval(a.x);
    m.shift.y = py - (m.s * px + m.c * py) + Interval(a.y);
    return m;
  };
  const PlacedPart placed_fixed = place(fixed, ExactMap{});
  MoveBisection move;
  move.lo = 0;
  move.hi = 1;
  move.stay = kind == Kind::stay;
  move.apart = [&](const Rational& u0, const Rational& u1) {
    return sgn(boundary_distance_lower_bound(shape_fixed, identity, shape_free, map_over(u0, u1), enough)) > 0;
  };
  move.overlap_at = [&](const Rational& u) -> std::string {
    const PlanarPose p = pose_at(u);
    std::string evidence = overlap_evidence(placed_fixed, place(planar, planar_pose_map(planar, p)));
    return evidence.empty() ? std::string() : "the parts overlap at u = " + fraction_or_rounded(u) + " (" + sliced_pose_words(p) + "): " + evidence;
  };
  move.not_apart = "the parts are not certainly apart at " + sliced_pose_words(a);
  // the move's length in units of the part: a translation over the part's reach, a rotation's
  // tangent step as it is
  Rational size = reach(shape_free);
  if (sgn(size) <= 0) size = 1;
  move.max_depth = move_depth_limit(kind == Kind::translation ? Rational(Rational(abs(b.x - a.x) + abs(b.y - a.y)) / size)
                                                              : Rational(abs(b.tangent - a.tangent)));
  return move_bisection_failure(move, budget, pieces);
}

long move_depth_limit(const Rational& span) {
  const mpz_class whole = span.get_num() / span.get_den();
  // (at most 1024 more: a move longer than 2^1024 times the part is refused near its ends in
  // bounded time, before pieces of 40 000-bit rationals)
  const long longer = sgn(whole) > 0 ? std::min(1024L, long(mpz_sizeinbase(whole.get_mpz_t(), 2))) : 0;
  return long(model_detail::working_interval_bits()) + 64 + longer;
}

std::string move_bisection_failure(const MoveBisection& move, std::size_t budget, std::size_t* pieces) {
  struct Piece {
    Rational p0, p1;
    long depth;
  };
  std::size_t count = 0;
  auto done = [&](std::string why) {
    if (pieces) *pieces = count;
    return why;
  };
  auto near = [&](const Piece& piece) {
    return std::string(1, move.letter) + " in [" + fraction_or_rounded(piece.p0) + ", " + fraction_or_rounded(piece.p1) + "]";
  };
  std::vector<Piece> stack{{move.lo, move.hi, 0}};
  while (!stack.empty()) {
    Piece piece = stack.back();
    stack.pop_back();
    if (piece.depth >= move.max_depth)
      return done("not proved free: its pieces reached 2^-" + std::to_string(move.max_depth) + " of the move near " + near(piece) +
                  " (narrower than the enclosures resolve: the parts come too close, or touch)");
    if (count == budget)
      return done("not proved free within " + std::to_string(budget) + " interval pieces (stuck near " + near(piece) +
                  ": the parts come too close, or touch)");
    ++count;
    if (move.apart(piece.p0, piece.p1)) continue;
    const Rational middle = (piece.p0 + piece.p1) / 2;
    if (move.stay || piece.depth % 6 == 0) {
      if (std::string overlap = move.overlap_at(middle); !overlap.empty()) return done(overlap);
      if (move.stay) return done(move.not_apart);
    }
    stack.push_back({middle, piece.p1, piece.depth + 1});
    stack.push_back({piece.p0, middle, piece.depth + 1});
  }
  return done("");
}

}  // namespace verify

namespace {

// A pin-slot part's claim (session 71): every step's move proved free over the pair's coordinates
// (verify::apart_move_failure), within the motion limits, the start free and not nested.
std::string pin_slot_connected_summary(const SlicedConnectedCertificate& c, const Model& model) {
  using namespace verify;
  const PinSlotParts parts = checked_pin_slot_pair(c.envelope, model, c.from, c.to, c.from_other, c.to_other, "from", "to");
  const ApartPair pair(*parts.other, *parts.moving);
  if (!c.path.empty()) reject("a pin-slot claim's witness is its steps, not a path of planar poses");
  if (c.steps.empty()) reject("the steps have no configuration");
  auto words = [](const std::array<Rational, 3>& at) {
    return "q=" + fraction_or_rounded(at[0]) + ", s=" + fraction_or_rounded(at[1]) + ", u=" + fraction_or_rounded(at[2]);
  };
  Rational from[3], to[3];
  pair.coordinates(c.from, c.from_other, from);
  pair.coordinates(c.to, c.to_other, to);
  if (!apart_same_configuration(pair, c.steps.front().data(), from))
    reject("the steps start at " + words(c.steps.front()) + ", not at the claim's start");
  if (!apart_same_configuration(pair, c.steps.back().data(), to)) reject("the steps end at " + words(c.steps.back()) + ", not at the claim's end");
  if (c.steps.size() - 1 > sliced_total_budget)
    reject("the steps make " + std::to_string(c.steps.size() - 1) + " moves, more than the " + std::to_string(sliced_total_budget) +
           " interval pieces a certificate may need in all");
  // the start free and its nesting exact (the boundaries never meet along the steps, so the
  // parts' nesting is the start's throughout)
  if (std::string failure = apart_pin_slot_end_failure(pair, c.steps.front().data()); !failure.empty())
    reject("at the start (" + words(c.steps.front()) + "): " + failure);
  {
    ApartBox start;
    for (int k = 0; k < 3; ++k) start.lo[k] = start.hi[k] = c.steps.front()[k];
    if (std::string failure = apart_limits_failure(pair, start); !failure.empty()) reject("at the start: " + failure);
  }
  std::size_t pieces = 0, total = 0, proved = 0;
  for (std::size_t i = 0; i + 1 < c.steps.size(); ++i) {
    // a move that stays at one configuration (a repeated step, or u = 3 to u = -1) is free where
    // the moves around it are
    if (apart_same_configuration(pair, c.steps[i].data(), c.steps[i + 1].data())) continue;
    if (total >= sliced_total_budget) reject("the steps' moves need more than " + std::to_string(sliced_total_budget) + " interval pieces in all");
    const std::string failure =
        apart_move_failure(pair, c.steps[i].data(), c.steps[i + 1].data(), std::min(sliced_move_budget, sliced_total_budget - total), &pieces);
    if (!failure.empty()) reject("move " + std::to_string(i) + " (" + words(c.steps[i]) + " to " + words(c.steps[i + 1]) + "): " + failure);
    total += pieces;
    ++proved;
  }
  const std::string expected = sliced_connected_statement(c);
  if (c.envelope.statement != expected)
    reject("the statement does not say what the claim's data prove: it reads '" + c.envelope.statement.substr(0, 400) +
           "', the claim's data give '" + expected + "'");
  return std::string(claim_name) + ": part '" + parts.moving->name + "' moves from " + sliced_end_words(c.from, c.from_other, parts.other->name) +
         " to " + sliced_end_words(c.to, c.to_other, parts.other->name) + " without touching '" + parts.other->name + "' (" +
         std::to_string(c.steps.size() - 1) + " steps, " + std::to_string(proved) + " moves proved free over " + std::to_string(total) +
         " interval pieces in all, within the motion limits)";
}

}  // namespace

VerificationResult check_sliced_connected(const SlicedConnectedCertificate& c, const Model& model) {
  using namespace verify;
  if (c.pin_slot) return verdict_of([&] { return pin_slot_connected_summary(c, model); });
  return verdict_of([&] {
    if (!c.steps.empty() || c.from_other || c.to_other) reject("a planar part's claim has a path, not steps or other positions");
    const SlicedPair pair = checked_sliced_pair(c.envelope, model, c.from, c.to, "the start", "the end", "connected");
    const std::string &name = pair.planar_name, &fixed_name = pair.fixed_name;
    const Part &planar = pair.planar(), &fixed = pair.fixed();
    if (c.path.empty()) reject("the path has no vertex");
    if (!same_pose(planar, c.path.front(), c.from)) reject("the path starts at " + sliced_pose_words(c.path.front()) + ", not at the claim's start " + sliced_pose_words(c.from));
    if (!same_pose(planar, c.path.back(), c.to)) reject("the path ends at " + sliced_pose_words(c.path.back()) + ", not at the claim's end " + sliced_pose_words(c.to));
    // each move within its budget, and all of them within the certificate's (a forged path of
    // many grazing moves is refused in bounded time)
    // (more moves than pieces in all cannot be proved: refused before any is checked)
    if (c.path.size() - 1 > sliced_total_budget)
      reject("the path has " + std::to_string(c.path.size() - 1) + " moves, more than the " + std::to_string(sliced_total_budget) +
             " interval pieces a certificate may need in all");
    std::size_t pieces = 0, total = 0, proved = 0;
    auto budget = [&] { return std::min(sliced_move_budget, sliced_total_budget - total); };
    for (std::size_t i = 0; i + 1 < c.path.size(); ++i) {
      // a move that stays at one pose (a repeated vertex or a change of chart) is free where the
      // moves around it are: its pose is an end of one of them (or the start, checked below)
      if (same_pose(planar, c.path[i], c.path[i + 1])) continue;
      if (total >= sliced_total_budget)
        reject("the path's moves need more than " + std::to_string(sliced_total_budget) + " interval pieces in all");
      std::string failure = sliced_move_failure(fixed, planar, c.path[i], c.path[i + 1], budget(), &pieces);
      if (!failure.empty())
        reject("move " + std::to_string(i) + " (" + sliced_pose_words(c.path[i]) + " to " + sliced_pose_words(c.path[i + 1]) + "): " + failure);
      total += pieces;
      ++proved;
    }
    if (proved == 0) {   // every move stays at the start
      std::string failure = sliced_move_failure(fixed, planar, c.path[0], c.path[0], budget(), &pieces);
      if (!failure.empty()) reject("at the start: " + failure);
      total += pieces;
    }
    // the boundaries never meet along the path, so the parts' nesting is that of the start
    check_nesting(place(fixed, ExactMap{}), place(planar, planar_pose_map(planar, c.path.front())), "at the start");
    const std::string expected = sliced_connected_statement(c);
    if (c.envelope.statement != expected)
      reject("the statement does not say what the claim's data prove: it reads '" + c.envelope.statement.substr(0, 400) +
             "', the claim's data give '" + expected + "'");
    return std::string(claim_name) + ": part '" + name + "' moves from " + sliced_pose_words(c.from) + " to " + sliced_pose_words(c.to) +
           " without touching '" + fixed_name + "' (" + std::to_string(c.path.size() - 1) + " moves, each proved free over " +
           std::to_string(total) + " interval pieces in all)";
  });
}

VerificationResult check_sliced_connected_text(const SlicedConnectedCertificate& c, std::string_view text,
                                               const std::string& source_name) {
  Model model;
  std::string reason;
  if (verify::read_certified_model(c.envelope, text, source_name, model, reason)) return check_sliced_connected(c, model);
  VerificationResult refused;
  refused.reason = reason;
  return refused;
}

}  // namespace hipair
