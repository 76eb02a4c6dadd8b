// Certificates over intervals of configurations: free passage (boxes along a path, each with a
// certified clearance) and jamming (a trap whose cut and walls are covered by blocked pieces),
// and a simple search for the trap of a jam.
#include "certificates/producer.hpp"
#include "core/model_scale.hpp"
#include "certify/planar_check.hpp"

#include <hipair/overlap.hpp>


#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace hipair {
namespace {

using namespace certify_detail;
using verify::Interval;
using verify::IntervalEdge;
using verify::IntervalPart;

struct PairRoles {
  const Part* driver;
  const Part* other;
  bool has_follower;
};

PairRoles pair_roles(const Model& model, const std::string& first, const std::string& second, const std::string& driver,
                     const std::string& follower) {
  if (driver != first && driver != second) throw ModelError("/pairs", "the driver '" + driver + "' is not a part of the pair");
  const Part& d = part_of(model, driver);
  const Part& o = part_of(model, driver == first ? second : first);
  if (d.motion.kind == Motion::Kind::fixed) throw ModelError(d.pointer, "the driver '" + driver + "' is fixed");
  bool moves = o.motion.kind != Motion::Kind::fixed;
  if (moves && !follower.empty() && follower != o.name) throw ModelError(o.pointer, "the follower must be '" + o.name + "'");
  if (!moves && !follower.empty()) throw ModelError(o.pointer, "part '" + o.name + "' is fixed: no follower");
  return PairRoles{&d, &o, moves};
}

double mid(const Interval& value) { return mpfi_get_d(value.get()); }
Rational power_of_ten(int exponent) {
  mpz_class power;
  mpz_ui_pow_ui(power.get_mpz_t(), 10, unsigned(std::abs(exponent)));
  return exponent >= 0 ? Rational(power) : Rational(1) / Rational(power);
}
Rational middle(const RationalInterval& range) { return (range.lo + range.hi) / 2; }
Rational reach_of(const Part& part) {
  return part.motion.kind == Motion::Kind::rotation ? verify::reach(verify::shape_of(part)) : Rational(1);
}

struct Shapes {
  IntervalPart driver, other;
};

// Lower bound of the clearance with the driver at x and the other part at y (ignored if fixed),
// capped at `enough`; without a cap, at an upper bound of the distance (the L1 distance of two
// boundary points: any magnitude, nothing is lost).
Rational clearance_at(const PairRoles& r, const Shapes& shapes, const Rational& x, const Rational& y,
                      std::optional<Rational> enough = std::nullopt) {
  verify::IntervalMap driver = interval_map(*r.driver, {x, x});
  verify::IntervalMap other = r.has_follower ? interval_map(*r.other, {y, y}) : verify::IntervalMap{};
  if (!enough) {
    const verify::IntervalPoint p = verify::place_point(shapes.driver, driver, shapes.driver.loops.at(0).at(0).source);
    const verify::IntervalPoint q = verify::place_point(shapes.other, other, shapes.other.loops.at(0).at(0).source);
    Interval dx = p.x - q.x, dy = p.y - q.y, l1;
    mpfi_abs(dx.get(), dx.get());
    mpfi_abs(dy.get(), dy.get());
    l1 = dx + dy;
    enough = l1.is_bounded() ? l1.upper() : Rational(1);
  }
  return verify::boundary_distance_lower_bound(shapes.driver, driver, shapes.other, other, *enough);
}

Rational path_value(const std::vector<std::pair<Rational, Rational>>& path, const Rational& x) {
  if (path.empty()) return 0;
  for (std::size_t i = 1; i < path.size(); ++i)
    if (x <= path[i].first) {
      const auto &p = path[i - 1], &q = path[i];
      return p.second + (q.second - p.second) * (x - p.first) / (q.first - p.first);
    }
  return path.back().second;
}

RationalInterval path_image(const std::vector<std::pair<Rational, Rational>>& path, const Rational& lo, const Rational& hi) {
  Rational a = path_value(path, lo), b = path_value(path, hi);
  RationalInterval image{std::min(a, b), std::max(a, b)};
  for (const auto& vertex : path)
    if (vertex.first > lo && vertex.first < hi) {
      image.lo = std::min(image.lo, vertex.second);
      image.hi = std::max(image.hi, vertex.second);
    }
  return image;
}

// A free passage's driver range or follower path beyond the part's motion limits (the
// verifier's verify::range_within_limits) is an input error naming the part and its limits.
void require_range_within_limits(const Part& part, const RationalInterval& range, const std::string& what) {
  if (verify::range_within_limits(part, range)) return;
  bool rotating = part.motion.kind == Motion::Kind::rotation;
  const RationalInterval& limits = rotating ? *part.motion.angle_limits : *part.motion.translation_limits;
  std::string unit = rotating ? " rad" : " mm";
  throw ModelError(part.pointer, "the " + what + " of '" + part.name + "' runs over [" + to_decimal_string(range.lo) + ", " +
                                     to_decimal_string(range.hi) + "]" + unit + ", not within its motion limits [" +
                                     to_decimal_string(limits.lo) + ", " + to_decimal_string(limits.hi) + "]" + unit +
                                     (rotating ? " in one turn" : ""));
}

// ------------------------------------------------------------------------------ crossings
struct Placed {
  IntervalPart over;     // posed over the whole box
  IntervalPart centre;   // posed at the box centre
};

Placed place_box(const Part& part, const std::optional<RationalInterval>& range) {
  IntervalPart shape = verify::shape_of(part);
  if (!range) return Placed{verify::place_over(shape, {}), verify::place_over(shape, {})};
  Rational c = middle(*range);
  return Placed{verify::place_over(shape, interval_map(part, *range)), verify::place_over(shape, interval_map(part, {c, c}))};
}

// The middle of an enclosure as sign, binary exponent and mantissa: ordered like the middle
// itself at any magnitude (1e-400 is not 0, 1e400 is not infinite, unlike mid()), for the
// search below: a heuristic, never a bound.
struct MiddleValue {
  int sign = 0;
  long exponent = 0;
  double mantissa = 0;   // in [0.5, 1)
};
MiddleValue middle_value(const Interval& value) {
  MiddleValue m;
  if (mpfi_nan_p(value.get())) return m;
  mpfr_t middle;
  mpfr_init2(middle, model_detail::interval_bits);
  mpfi_mid(middle, value.get());
  m.sign = mpfr_sgn(middle);
  if (m.sign != 0) m.mantissa = std::abs(mpfr_get_d_2exp(&m.exponent, middle, MPFR_RNDN));
  mpfr_clear(middle);
  return m;
}
// a < b as numbers
bool less(const MiddleValue& a, const MiddleValue& b) {
  if (a.sign != b.sign) return a.sign < b.sign;
  if (a.sign == 0) return false;
  bool magnitude_less = a.exponent != b.exponent ? a.exponent < b.exponent : a.mantissa < b.mantissa;
  bool magnitude_greater = a.exponent != b.exponent ? a.exponent > b.exponent : a.mantissa > b.mantissa;
  return a.sign > 0 ? magnitude_less : magnitude_greater;
}
MiddleValue negated(MiddleValue a) {
  a.sign = -a.sign;
  return a;
}

// A piece of edge e (posed at the centre: ec, over the box: eo) crossing g, for every pose.
// The search is a heuristic (the piece is then proved by crossing_certain): the side of g along
// e at 32 samples, each sign change bisected; where no sample changes sign, a shallow crossing
// (an arc dipping through a line by less than the samples' spacing shows: a cam pushing its
// follower just past a limit) is sought by minimising the side value about every sample where
// it comes locally closest to the other side.
//
// `wide`: sub-curves of up to a tenth of the edge either side of the crossing are tried first
// (MarchCover: two nearly tangent arcs pushed into each other cross at a small angle, so their
// crossing slides along the edge as the pose moves; 1e-2 of the edge bounded the pieces).
std::optional<RationalInterval> crossing_piece(const IntervalEdge& ec, const IntervalEdge& eo, const IntervalEdge& gc,
                                               const IntervalEdge& go, bool wide = false) {
  double end = ec.arc ? mid(ec.sweep) : 1.0;   // a fraction or an angle (at most 2 pi)
  auto side_value = [&](double u) { return middle_value(verify::side_of(gc, verify::point_on(ec, Interval(approximate(u))))); };
  auto side = [&](double u) { return side_value(u).sign; };
  // The piece about the sign change between u0 (sign lo_value) and u1 (the other sign), if certain.
  auto piece_about = [&](double u0, double u1, int lo_value) -> std::optional<RationalInterval> {
    double lo = u0, hi = u1;
    for (int k = 0; k < 50; ++k) {
      double m = 0.5 * (lo + hi);
      if (side(m) == lo_value) lo = m;
      else hi = m;
    }
    double root = 0.5 * (lo + hi);
    static constexpr double usual[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 1e-5, 1e-6, 1e-7};
    static constexpr double wider[] = {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 1e-5, 1e-6, 1e-7};
    for (double delta : wide ? std::vector<double>(std::begin(wider), std::end(wider))
                             : std::vector<double>(std::begin(usual), std::end(usual))) {
      double a = std::max(0.0, root - delta * end), b = std::min(end * (1 - 1e-9), root + delta * end);
      if (!(a < b)) continue;
      RationalInterval along{approximate(a), approximate(b)};
      if (verify::crossing_certain(eo, along, go, nullptr)) return along;
    }
    return std::nullopt;
  };
  constexpr int samples = 32;
  std::vector<MiddleValue> values(samples + 1);
  for (int i = 0; i <= samples; ++i) values[i] = side_value(end * i / samples);
  bool changed = false;
  for (int i = 1; i <= samples; ++i) {
    int previous = values[i - 1].sign, value = values[i].sign;
    if (previous == value || previous == 0 || value == 0) continue;
    changed = true;
    if (auto along = piece_about(end * (i - 1) / samples, end * i / samples, previous)) return along;
  }
  if (changed || values[0].sign == 0) return std::nullopt;
  int sign = values[0].sign;   // every sample's (or 0)
  auto toward_other_side = [&](const MiddleValue& v) { return sign > 0 ? v : negated(v); };   // less: closer to it
  for (int i = 1; i < samples; ++i) {
    MiddleValue here = toward_other_side(values[i]);
    if (values[i].sign != sign || less(toward_other_side(values[i - 1]), here) || less(toward_other_side(values[i + 1]), here))
      continue;
    // golden-section search for the least side value on the samples' neighbours
    constexpr double ratio = 0.6180339887498949;
    double a = end * (i - 1) / samples, b = end * (i + 1) / samples;
    double c = b - ratio * (b - a), d = a + ratio * (b - a);
    MiddleValue fc = toward_other_side(side_value(c)), fd = toward_other_side(side_value(d));
    for (int k = 0; k < 80 && fc.sign == sign && fd.sign == sign; ++k) {
      if (less(fc, fd)) {
        b = d, d = c, fd = fc;
        c = b - ratio * (b - a);
        fc = toward_other_side(side_value(c));
      } else {
        a = c, c = d, fc = fd;
        d = a + ratio * (b - a);
        fd = toward_other_side(side_value(d));
      }
    }
    double beyond = fc.sign != sign ? c : fd.sign != sign ? d : -1;
    if (beyond < 0 || side(beyond) != -sign) continue;   // no dip to the other side here
    double before = end * (i - 1) / samples;             // the dip's entry lies between them
    if (auto along = piece_about(before, beyond, sign)) return along;
    double after = end * (i + 1) / samples;              // ... and its exit (from the other side)
    if (auto along = piece_about(beyond, after, -sign)) return along;
  }
  return std::nullopt;
}

// A crossing blocking every configuration of the box (driver range x other range).
std::optional<CrossingWitness> blocking_crossing(const PairRoles& r, const RationalInterval& driver_range,
                                                 const std::optional<RationalInterval>& other_range) {
  Placed driver = place_box(*r.driver, driver_range), other = place_box(*r.other, other_range);
  for (int order = 0; order < 2; ++order) {
    const Placed& e_part = order ? other : driver;
    const Placed& g_part = order ? driver : other;
    const Part& e_model = order ? *r.other : *r.driver;
    const Part& g_model = order ? *r.driver : *r.other;
    for (std::size_t i = 0; i < e_part.centre.loops.size(); ++i)
      for (std::size_t j = 0; j < e_part.centre.loops[i].size(); ++j)
        for (std::size_t k = 0; k < g_part.centre.loops.size(); ++k)
          for (std::size_t l = 0; l < g_part.centre.loops[k].size(); ++l) {
            const IntervalEdge &ec = e_part.centre.loops[i][j], &gc = g_part.centre.loops[k][l];
            // Skip the pair when its bounding discs are certainly apart (at the box centre).
            Interval dx = ec.disc_center.x - gc.disc_center.x, dy = ec.disc_center.y - gc.disc_center.y;
            Interval reach = ec.disc_radius + gc.disc_radius;
            if ((dx * dx + dy * dy - reach * reach).sign() > 0 && reach.sign() >= 0) continue;
            auto along = crossing_piece(ec, e_part.over.loops[i][j], gc, g_part.over.loops[k][l]);
            if (along)
              return CrossingWitness{{e_model.name, i, j, e_model.loops[i].edges[j].label},
                                     {g_model.name, k, l, g_model.loops[k].edges[l].label}, along};
          }
  }
  return std::nullopt;
}

// Covers `range` left to right with pieces blocked over make_box(piece range).
// `free_at(v)`: the configuration at value v of the range is certainly free (the verifier's
// start test: parts certainly apart, exact nesting test). Each piece proved blocked holds only
// configurations where the parts overlap strictly (a transversal crossing, or a point inside
// both), so a free one makes
// the cover impossible: the cover is given up at the first failed piece whose middle is free.
// The verdict is the one the bisection would reach (no cover), sooner: a trap whose cut or wall
// the free channel crosses (a zero-backlash mesh's closing missed by find_jam's grid) bisected
// toward the channel's edge down to 1e-12 (16 x 15 spur gears: 17 s in five such traps).
// `blocked(piece)` gives the piece's witness (its range is set here).
bool cover(const RationalInterval& range, std::vector<BlockedPiece>& pieces, std::size_t max_pieces,
           const std::function<std::optional<BlockedPiece>(const RationalInterval&)>& blocked,
           const std::function<bool(const Rational&)>& free_at, std::size_t* tests = nullptr) {
  std::vector<RationalInterval> stack{range};
  while (!stack.empty()) {
    RationalInterval piece = stack.back();
    stack.pop_back();
    // `tests`: the piece tests left to the whole search (certify_detail::certify_found_jam_within)
    if (tests) {
      if (*tests == 0) return false;
      --*tests;
    }
    if (auto witness = blocked(piece)) {
      witness->range = piece;
      pieces.push_back(std::move(*witness));
      continue;
    }
    if (pieces.size() + stack.size() >= max_pieces || piece.hi - piece.lo < Rational(1, 1000000000000)) return false;
    if (free_at(middle(piece))) return false;
    Rational m = middle(piece);
    stack.push_back({m, piece.hi});
    stack.push_back({piece.lo, m});
  }
  return true;
}

// The driver at x and the follower at y certainly apart: the verifier's test of a jam's start
// (an MPFI distance bound at exactly (x, y), then the exact nesting test near it).
// Not known to be free (false) when the test cannot be made (an angle too large to reduce).
bool certainly_free(const PairRoles& r, const Rational& x, const Rational& y) {
  ConfigurationBox at{{x, x}, r.has_follower ? std::optional<RationalInterval>(RationalInterval{y, y}) : std::nullopt};
  try {
    return verify::jam_start_failure(*r.driver, *r.other, at,
                                     JamStart{x, r.has_follower ? std::optional<Rational>(y) : std::nullopt})
        .empty();
  } catch (const Error&) {
    return false;
  }
}

PartRelation relation_at(const PairRoles& r, const Rational& x, const Rational& y) {
  auto exact_of = [](const Part& part, const Rational& value) {
    ExactPosition position = part.motion.kind == Motion::Kind::rotation ? exact_position_from_angle(value) : ExactPosition{value, true, false, {}, {}};
    return exact_map(part, &position);
  };
  auto placed = [](const verify::ExactMap& map) { return placement_about(map.pivot, map.c, map.s, map.shift); };
  verify::ExactMap other = r.has_follower ? exact_of(*r.other, y) : verify::ExactMap{};
  return part_overlap(*r.driver, placed(exact_of(*r.driver, x)), *r.other, placed(other)).relation;
}

bool overlapping_at(const PairRoles& r, const Rational& x, const Rational& y) {
  return relation_at(r, x, y) == PartRelation::overlapping;
}

// A point strictly inside both parts at every configuration of the box (driver range x other
// range; format version 2): flush faces — a slider pushed into a block of its own height — meet
// only along collinear edges, so no crossing blocks them. The candidate is the exact overlap's
// witness at the box's middle configuration; it is kept when the verifier's test holds
// (jam_point_failure: strictly inside both there, off both boundaries over the box).
std::optional<BlockedPiece> blocking_point(const PairRoles& r, const RationalInterval& driver_range,
                                           const std::optional<RationalInterval>& other_range) {
  auto exact_of = [](const Part& part, const Rational& value) {
    ExactPosition position = part.motion.kind == Motion::Kind::rotation ? exact_position_from_angle(value) : ExactPosition{value, true, false, {}, {}};
    return exact_map(part, &position);
  };
  auto placed = [](const verify::ExactMap& map) { return placement_about(map.pivot, map.c, map.s, map.shift); };
  try {
    verify::ExactMap other = other_range ? exact_of(*r.other, middle(*other_range)) : verify::ExactMap{};
    PartOverlap overlap = part_overlap(*r.driver, placed(exact_of(*r.driver, middle(driver_range))), *r.other, placed(other), true);
    if (overlap.relation != PartRelation::overlapping || !overlap.witness) return std::nullopt;
    if (!verify::jam_point_failure(*r.driver, *r.other, driver_range, other_range, *overlap.witness).empty()) return std::nullopt;
    return BlockedPiece{{Rational(0), Rational(0)}, {}, *overlap.witness};
  } catch (const Error&) {
    return std::nullopt;
  }
}

// The piece's witness: a crossing (blocking_crossing), else, with `points`, a point inside both parts.
std::optional<BlockedPiece> blocking_piece(const PairRoles& r, const RationalInterval& driver_range,
                                           const std::optional<RationalInterval>& other_range, bool points) {
  if (auto crossing = blocking_crossing(r, driver_range, other_range))
    return BlockedPiece{{Rational(0), Rational(0)}, *crossing, std::nullopt};
  if (!points) return std::nullopt;
  return blocking_point(r, driver_range, other_range);
}

// Covers of a trap's cut and walls for a closing channel (certify_closing_jam): the pieces
// march along the range, each proved by one feature pair. cover() with blocking_crossing poses
// both parts whole and tries every near feature pair on every piece, and bisects from the whole
// range: on a gear mesh (~130 edges a part, ~40 near pairs a piece) that made a closing's trap
// cost seconds. Here the feature pairs whose discs may meet anywhere in the trap are listed
// once; a piece is tried first with the pairs that proved earlier pieces (one pair: two edges
// posed), the whole list only when those fail on a piece already small; a proved piece's
// successor is tried twice as wide, a failed piece halved. The same witnesses as cover()'s
// (a crossing piece certain over the piece's box, crossing_piece): only the search differs.
class MarchCover {
 public:
  /// `budget`: crossing_piece searches left (shared by the traps of one closing, about 1/3 ms
  /// each; a certified gear closing takes about 40): the cover is given up when it runs out.
  MarchCover(const PairRoles& r, const Shapes& shapes, const ConfigurationBox& trap, std::size_t& budget)
      : r_(r), driver_shape_(shapes.driver), other_shape_(shapes.other), budget_(budget) {
    // the groups' discs first (runs of 8 edges), then the edges of groups that may meet
    verify::IntervalMap driver_map = interval_map(*r.driver, trap.driver), other_map = interval_map(*r.other, *trap.follower);
    auto apart = [](const verify::IntervalPoint& a, const Interval& ra, const verify::IntervalPoint& b, const Interval& rb) {
      Interval dx = a.x - b.x, dy = a.y - b.y, reach = ra + rb;
      return (dx * dx + dy * dy - reach * reach).sign() > 0 && reach.sign() >= 0;
    };
    std::vector<verify::IntervalPoint> other_centres;
    for (const auto& group : other_shape_.groups)
      other_centres.push_back(verify::place_point(other_shape_, other_map, group.center));
    std::map<std::pair<std::size_t, std::size_t>, IntervalEdge> posed_driver, posed_other;
    auto posed = [&](bool driver, std::size_t loop, std::size_t edge) -> const IntervalEdge& {
      auto& cache = driver ? posed_driver : posed_other;
      auto found = cache.find({loop, edge});
      if (found == cache.end())
        found = cache.emplace(std::make_pair(loop, edge), driver ? pose(driver_shape_, driver_map, loop, edge)
                                                                 : pose(other_shape_, other_map, loop, edge)).first;
      return found->second;
    };
    for (const auto& dg : driver_shape_.groups) {
      verify::IntervalPoint dcentre = verify::place_point(driver_shape_, driver_map, dg.center);
      for (std::size_t n = 0; n < other_shape_.groups.size(); ++n) {
        const auto& og = other_shape_.groups[n];
        if (apart(dcentre, dg.radius, other_centres[n], og.radius)) continue;
        for (std::size_t j = dg.first; j < dg.last; ++j)
          for (std::size_t l = og.first; l < og.last; ++l) {
            const IntervalEdge &a = posed(true, dg.loop, j), &b = posed(false, og.loop, l);
            if (!apart(a.disc_center, a.disc_radius, b.disc_center, b.disc_radius)) near_.push_back({0, dg.loop, j, og.loop, l});
          }
      }
    }
    // blocking_crossing's order: the driver's edges crossing the other's first
    std::size_t count = near_.size();
    for (std::size_t n = 0; n < count; ++n) near_.push_back({1, near_[n].i, near_[n].j, near_[n].k, near_[n].l});
  }

  /// Covers `range` left to right; box(piece) is the configuration box (driver, other) of a piece.
  /// `finest`: the shortest piece, as a fraction of the range, before the cover is given up.
  bool march(const RationalInterval& range, std::vector<BlockedPiece>& pieces, std::size_t max_pieces,
             const std::function<std::pair<RationalInterval, RationalInterval>(const RationalInterval&)>& box,
             const Rational& finest) {
    Rational position = range.lo, width = (range.hi - range.lo) / 8;
    const Rational floor = std::max(Rational(1, 1000000000000), Rational((range.hi - range.lo) * finest));
    int failures = 0;      // consecutive failed widths at `position`
    bool grow = false;     // the last piece was proved at its first width: try the next one wider
    std::optional<Rational> rescued;   // the position where every other pair was last tried at the floor
    while (position < range.hi) {
      if (pieces.size() >= max_pieces || budget_ == 0) return false;
      Rational end = std::min(Rational(position + width), range.hi);
      RationalInterval piece{position, end};
      auto [driver_range, other_range] = box(piece);
      // a first try at a position takes the proved pairs' last sub-curves only (a wider piece that
      // fails is halved, which is cheaper than crossing_piece's search)
      std::optional<CrossingWitness> witness = hinted(driver_range, other_range, failures > 0 || !grow);
      // every pair only when the proved pairs failed twice here (their region ends) or none is known
      if (!witness && (hints_.empty() || failures >= 2)) witness = scan(driver_range, other_range);
      if (witness) {
        pieces.push_back({piece, *witness, std::nullopt});
        width = grow ? Rational(2 * (end - position)) : Rational(end - position);
        grow = failures == 0;
        failures = 0;
        position = end;
        continue;
      }
      if (end - position < floor) {
        // A proved pair's crossing that runs into a vertex ahead (its pieces shrink by halves
        // toward that point, each proved after one halving) brings the width to the floor before
        // the full search (two failures at one position) is tried: try every other pair once on
        // a piece of twice the floor before giving up (18 x 16 gears driven backwards: another
        // pair crosses there with pieces of 1e-4 of the cut; session 53, exact53b).
        if (rescued != position) {
          rescued = position;
          RationalInterval low{position, std::min(Rational(position + 2 * floor), range.hi)};
          auto [low_driver, low_other] = box(low);
          if (std::optional<CrossingWitness> found = scan(low_driver, low_other)) {
            pieces.push_back({low, *found, std::nullopt});
            width = low.hi - low.lo;
            grow = true;
            failures = 0;
            position = low.hi;
            continue;
          }
        }
        return false;
      }
      width = (end - position) / 2;
      ++failures;
      grow = false;
    }
    return true;
  }

 private:
  struct FeaturePair {
    int order;   // 0: driver edge (i, j) crosses other edge (k, l); 1: the other's crosses the driver's
    std::size_t i, j, k, l;
    std::optional<RationalInterval> along = std::nullopt;   // of the last piece it proved
  };

  static IntervalEdge pose(const verify::IntervalPart& shape, const verify::IntervalMap& map, std::size_t loop,
                           std::size_t edge) {
    verify::IntervalPart one;
    one.pivot = shape.pivot;
    one.loops = {{shape.loops[loop][edge]}};
    return verify::place_over(one, map).loops[0][0];
  }

  struct Maps {
    verify::IntervalMap driver_over, driver_centre, other_over, other_centre;
  };
  Maps maps(const RationalInterval& driver_range, const RationalInterval& other_range) const {
    Rational dc = middle(driver_range), oc = middle(other_range);
    return {interval_map(*r_.driver, driver_range), interval_map(*r_.driver, {dc, dc}),
            interval_map(*r_.other, other_range), interval_map(*r_.other, {oc, oc})};
  }

  // The pair's witness over the piece: first the sub-curve that proved the pair's last piece
  // (`guess`: the crossing moves on little from one piece to the next), else crossing_piece.
  std::optional<CrossingWitness> attempt(const FeaturePair& p, const Maps& m,
                                         const std::optional<RationalInterval>& guess = std::nullopt,
                                         bool search = true) const {
    IntervalEdge dover = pose(driver_shape_, m.driver_over, p.i, p.j), oover = pose(other_shape_, m.other_over, p.k, p.l);
    if (guess && (p.order == 0 ? verify::crossing_certain(dover, *guess, oover, nullptr)
                               : verify::crossing_certain(oover, *guess, dover, nullptr)))
      return witness_of(p, *guess);
    if (!search || budget_ == 0) return std::nullopt;
    --budget_;
    IntervalEdge dc = pose(driver_shape_, m.driver_centre, p.i, p.j), oc = pose(other_shape_, m.other_centre, p.k, p.l);
    // skip the pair when its bounding discs are certainly apart (at the box centre)
    Interval dx = dc.disc_center.x - oc.disc_center.x, dy = dc.disc_center.y - oc.disc_center.y;
    Interval reach = dc.disc_radius + oc.disc_radius;
    if ((dx * dx + dy * dy - reach * reach).sign() > 0 && reach.sign() >= 0) return std::nullopt;
    auto along = p.order == 0 ? crossing_piece(dc, dover, oc, oover, true) : crossing_piece(oc, oover, dc, dover, true);
    if (!along) return std::nullopt;
    return witness_of(p, *along);
  }

  CrossingWitness witness_of(const FeaturePair& p, const RationalInterval& along) const {
    const Part &d = *r_.driver, &o = *r_.other;
    EdgeReference de{d.name, p.i, p.j, d.loops[p.i].edges[p.j].label}, oe{o.name, p.k, p.l, o.loops[p.k].edges[p.l].label};
    return p.order == 0 ? CrossingWitness{de, oe, along} : CrossingWitness{oe, de, along};
  }

  std::optional<CrossingWitness> hinted(const RationalInterval& driver_range, const RationalInterval& other_range,
                                        bool search) {
    if (hints_.empty()) return std::nullopt;
    Maps m = maps(driver_range, other_range);
    for (std::size_t n = 0; n < hints_.size(); ++n)
      if (auto witness = attempt(hints_[n], m, hints_[n].along, search)) {
        hints_[n].along = witness->along;
        std::rotate(hints_.begin(), hints_.begin() + long(n), hints_.begin() + long(n) + 1);   // most recent first
        return witness;
      }
    return std::nullopt;
  }

  // Every near pair not among the proved ones: first those next to a proved pair (the other
  // order, or an edge next to one of its edges: a contact moving on along a flank), then the rest.
  std::optional<CrossingWitness> scan(const RationalInterval& driver_range, const RationalInterval& other_range) {
    Maps m = maps(driver_range, other_range);
    auto close = [](std::size_t a, std::size_t b) { return a == b || a + 1 == b || b + 1 == a; };
    auto proved = [&](const FeaturePair& p) {
      for (const FeaturePair& h : hints_)
        if (h.order == p.order && h.i == p.i && h.j == p.j && h.k == p.k && h.l == p.l) return true;
      return false;
    };
    auto next_to_proved = [&](const FeaturePair& p) {
      for (const FeaturePair& h : hints_)
        if (h.i == p.i && h.k == p.k && close(h.j, p.j) && close(h.l, p.l)) return true;
      return false;
    };
    for (int round = 0; round < 2; ++round)
      for (const FeaturePair& p : near_) {
        if (proved(p) || next_to_proved(p) != (round == 0) || !seems_to_cross(p, m)) continue;
        if (auto witness = attempt(p, m)) {
          hints_.insert(hints_.begin(), p);
          hints_.front().along = witness->along;
          return witness;
        }
      }
    return std::nullopt;
  }

  // A quick look in doubles (a heuristic: it only orders the search): does edge e of the pair,
  // posed at the piece's centre, pass to the other side of g's line or circle, at 256 points,
  // at a point within g's extent? Pairs that do not are not tried by scan().
  bool seems_to_cross(const FeaturePair& p, const Maps& m) const {
    IntervalEdge dc = pose(driver_shape_, m.driver_centre, p.i, p.j), oc = pose(other_shape_, m.other_centre, p.k, p.l);
    const IntervalEdge& e = p.order == 0 ? dc : oc;
    const IntervalEdge& g = p.order == 0 ? oc : dc;
    auto d = [](const Interval& v) { return mid(v); };
    double sx = d(e.source.x), sy = d(e.source.y), tx = d(e.target.x), ty = d(e.target.y), cx = d(e.center.x),
           cy = d(e.center.y), sweep = e.arc ? d(e.sweep) : 1.0;
    double gsx = d(g.source.x), gsy = d(g.source.y), gtx = d(g.target.x), gty = d(g.target.y), gcx = d(g.center.x),
           gcy = d(g.center.y), gr2 = d(g.radius_squared);
    auto side = [&](double x, double y) {
      return g.arc ? (x - gcx) * (x - gcx) + (y - gcy) * (y - gcy) - gr2 : (gtx - gsx) * (y - gsy) - (gty - gsy) * (x - gsx);
    };
    auto within = [&](double x, double y) {
      if (!g.arc) {
        double along = (x - gsx) * (gtx - gsx) + (y - gsy) * (gty - gsy);
        double length2 = (gtx - gsx) * (gtx - gsx) + (gty - gsy) * (gty - gsy);
        return along > -0.01 * length2 && along < 1.01 * length2;
      }
      if (g.full_circle) return true;
      // within the arc's sweep from its source, in its direction
      double a0 = std::atan2(gsy - gcy, gsx - gcx), a = std::atan2(y - gcy, x - gcx);
      double turn = (g.ccw ? a - a0 : a0 - a) / (2 * M_PI);
      turn -= std::floor(turn);
      double sweep = mid(g.sweep);   // (a hundredth more either side: a crossing at a vertex)
      return turn * 2 * M_PI < 1.01 * sweep || (1 - turn) * 2 * M_PI < 0.01 * sweep;
    };
    constexpr int samples = 256;
    double previous = 0;
    for (int n = 0; n <= samples; ++n) {
      double u = sweep * n / samples, x, y;
      if (!e.arc) {
        x = sx + u * (tx - sx), y = sy + u * (ty - sy);
      } else {
        double c = std::cos(u), sn = e.ccw ? std::sin(u) : -std::sin(u), wx = sx - cx, wy = sy - cy;
        x = cx + c * wx - sn * wy, y = cy + sn * wx + c * wy;
      }
      double value = side(x, y);
      if (n > 0 && ((previous < 0) != (value < 0)) && within(x, y)) return true;
      previous = value;
    }
    return false;
  }

  const PairRoles& r_;
  const verify::IntervalPart &driver_shape_, &other_shape_;
  std::vector<FeaturePair> near_, hints_;
  std::size_t& budget_;
};

}  // namespace

std::optional<RationalInterval> certify_detail::crossing_piece_of(const IntervalEdge& ec, const IntervalEdge& eo,
                                                                  const IntervalEdge& gc, const IntervalEdge& go) {
  return crossing_piece(ec, eo, gc, go);
}

std::optional<Certificate> certify_free_passage(const Model& model, const std::string& first, const std::string& second,
                                                const PassagePath& path, std::optional<Rational> distance,
                                                const CertifyContext& context, const IntervalSearchOptions& options) {
  // a pair far from the origin for its size is certified moved to it (its enclosures there)
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return checked_as_given(certify_free_passage(*moved, first, second, path, distance, context, options), model);
  Certificate c = start_certificate(model, context, ClaimKind::free_passage, first, second);
  PairRoles r = pair_roles(model, first, second, path.driver, path.follower);
  if (path.range.lo >= path.range.hi) throw NumericError("the driver range must have start < end");
  c.driver = r.driver->name;
  c.follower = r.has_follower ? r.other->name : "";
  c.range = path.range;
  if (r.has_follower) {
    c.path = path.polyline;
    if (c.path.size() < 2 || c.path.front().first != c.range.lo || c.path.back().first != c.range.hi)
      throw NumericError("the follower path must run from the start to the end of the driver range");
  }
  // The driver's range and the follower's path must be motions the mechanism can make: within
  // the parts' motion limits, in one turn (the verifier's rule; an input error naming the part)
  require_range_within_limits(*r.driver, c.range, "driver range");
  if (r.has_follower) require_range_within_limits(*r.other, path_image(c.path, c.range.lo, c.range.hi), "follower path");
  // At the start the parts must not overlap (a part inside the other has a positive boundary distance).
  if (overlapping_at(r, c.range.lo, path_value(c.path, c.range.lo))) return std::nullopt;
  Rational reach_driver = reach_of(*r.driver), reach_other = reach_of(*r.other);
  Shapes shapes{verify::shape_of(*r.driver), verify::shape_of(*r.other)};
  if (!distance) {
    std::optional<Rational> smallest;
    for (int i = 0; i <= 256; ++i) {
      Rational x = c.range.lo + (c.range.hi - c.range.lo) * i / 256;
      Rational bound = clearance_at(r, shapes, x, path_value(c.path, x));
      if (!smallest || bound < *smallest) smallest = bound;
    }
    if (sgn(*smallest) <= 0) return std::nullopt;
    distance = round_down(*smallest / 2, 3);
  }
  c.distance = *distance;
  std::vector<RationalInterval> stack{c.range};
  while (!stack.empty()) {
    RationalInterval piece = stack.back();
    stack.pop_back();
    RationalInterval image = r.has_follower ? path_image(c.path, piece.lo, piece.hi) : RationalInterval{0, 0};
    Rational half_driver = (piece.hi - piece.lo) / 2, half_other = (image.hi - image.lo) / 2;
    Rational needed = c.distance + reach_driver * half_driver + reach_other * half_other;
    // The verifier's nesting slack on box 0: its exact configuration lies within 1e-60 rad of the
    // centre (relative to the parts' reach, so that it also holds at 1e-300 mm).
    if (c.boxes.empty()) {
      Rational reach_sum = r.driver->motion.kind == Motion::Kind::rotation ? reach_driver : Rational(0);
      if (r.has_follower && r.other->motion.kind == Motion::Kind::rotation) reach_sum += reach_other;
      needed += reach_sum * power_of_ten(-60);
    }
    Rational bound = clearance_at(r, shapes, middle(piece), middle(image), needed);   // only "enough?" matters
    if (bound >= needed) {
      c.boxes.push_back({piece, r.has_follower ? std::optional<RationalInterval>(image) : std::nullopt});
      continue;
    }
    if (bound <= c.distance || c.boxes.size() + stack.size() >= options.max_boxes) return std::nullopt;
    // Split into enough pieces for the margin bound - distance to absorb the motion (exact
    // rationals: the magnitudes may lie beyond double range).
    Rational slope = sgn(half_driver) > 0 ? Rational(half_other / half_driver) : Rational(0);
    Rational motion = reach_driver + reach_other * slope;
    Rational ratio = sgn(motion) > 0 ? Rational(half_driver * motion / (bound - c.distance) * Rational(5, 4)) : Rational(0);
    long parts = 1024;
    if (ratio < 1024) {
      mpz_class whole;
      mpz_cdiv_q(whole.get_mpz_t(), ratio.get_num_mpz_t(), ratio.get_den_mpz_t());
      parts = std::max(2L, whole.get_si());
    }
    for (long i = parts; i-- > 0;)
      stack.push_back({piece.lo + (piece.hi - piece.lo) * i / parts, piece.lo + (piece.hi - piece.lo) * (i + 1) / parts});
  }
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}

namespace {
// Configurations found certainly free (certainly_free) while covering traps of one jam search:
// a later trap whose cut or wall holds one is given up before its cover of that part (the traps
// of certify_found_jam share their follower range; each reaches further than the one before).
using FreeConfigurations = std::vector<std::pair<Rational, Rational>>;   // (driver, follower)

// certify_jam's work on a pair at the origin; `march`: cover the cut and walls with MarchCover
// (certify_closing_jam) instead of cover() with blocking_crossing; `seen`: free configurations
// met so far (cover()'s), read and added to; `points`: pieces a crossing does not prove may be
// proved by a point inside both parts (format version 2; certify_trap_with_points). Without
// `march`, `budget` (when given) bounds the piece tests of the covers (cover()'s `tests`).
std::optional<Certificate> certify_trap(const Model& model, const std::string& first, const std::string& second,
                                        const JamQuery& query, const CertifyContext& context,
                                        const IntervalSearchOptions& options, const Shapes* march = nullptr,
                                        std::size_t* budget = nullptr, FreeConfigurations* seen = nullptr,
                                        bool points = false) {
  // march (certify_closing_jam): its start, checked there, is the certificate's; no grid
  Certificate c = start_certificate(model, context, ClaimKind::jam, first, second);
  PairRoles r = pair_roles(model, first, second, query.driver, query.follower);
  if (r.has_follower != bool(query.trap.follower)) throw NumericError("the trap needs a follower range exactly when the follower moves");
  c.driver = r.driver->name;
  c.follower = r.has_follower ? r.other->name : "";
  if (query.direction != 1 && query.direction != -1)
    throw NumericError("the jam direction must be +1 or -1, not " + std::to_string(query.direction));
  c.direction = query.direction;
  c.trap = query.trap;
  Rational far = c.direction > 0 ? c.trap.driver.hi : c.trap.driver.lo;
  RationalInterval cut_at{far, far};
  if (!r.has_follower) {
    auto piece = blocking_piece(r, cut_at, std::nullopt, points);
    if (!piece) return std::nullopt;
    c.cut.push_back(std::move(*piece));
  } else {
    const RationalInterval& band = *c.trap.follower;
    if (!verify::band_meets_limits(*r.other, band)) {
      bool rotating = r.other->motion.kind == Motion::Kind::rotation;
      const RationalInterval& limits = rotating ? *r.other->motion.angle_limits : *r.other->motion.translation_limits;
      std::string unit = rotating ? " rad" : " mm";
      throw ModelError(r.other->pointer, "the trap's follower range [" + to_decimal_string(band.lo) + ", " +
                                             to_decimal_string(band.hi) + "]" + unit + " of '" + r.other->name +
                                             "' lies outside its motion limits [" + to_decimal_string(limits.lo) + ", " +
                                             to_decimal_string(limits.hi) + "]" + unit + (rotating ? " in every turn" : "") +
                                             ": the trap holds no configuration of the mechanism");
    }
    // (a piece shorter than a billionth of the cut or a hundred-thousandth of a wall gives the
    // trap up: the pieces approach free space by halves; a closing's cut took pieces of 1e-7 of
    // its range, its walls 1/64)
    std::optional<MarchCover> marching;
    if (march) marching.emplace(r, *march, c.trap, *budget);
    FreeConfigurations none;
    FreeConfigurations& free_seen = seen ? *seen : none;
    // a free configuration met before on this side of the trap: no cover of it exists
    auto free_met = [&](const RationalInterval& driver, const RationalInterval& follower) {
      return std::any_of(free_seen.begin(), free_seen.end(), [&](const auto& p) {
        return driver.lo <= p.first && p.first <= driver.hi && follower.lo <= p.second && p.second <= follower.hi;
      });
    };
    auto free_at = [&](const Rational& x, const Rational& y) {
      if (!certainly_free(r, x, y)) return false;
      free_seen.emplace_back(x, y);
      return true;
    };
    if (!marching && free_met(cut_at, band)) return std::nullopt;
    if (marching ? !marching->march(band, c.cut, options.max_boxes,
                                    [&](const RationalInterval& piece) { return std::make_pair(cut_at, piece); },
                                    Rational(1, 1000000000))
                 : !cover(band, c.cut, options.max_boxes,
                          [&](const RationalInterval& piece) { return blocking_piece(r, cut_at, piece, points); },
                          [&](const Rational& y) { return free_at(far, y); }, budget))
      return std::nullopt;
    for (int upper = 0; upper < 2; ++upper) {
      Rational at = upper ? band.hi : band.lo;
      if (verify::wall_closed_by_limit(*r.other, band, upper)) continue;
      RationalInterval wall_at{at, at};
      std::vector<BlockedPiece>& wall = upper ? c.upper_wall : c.lower_wall;
      if (!marching && free_met(c.trap.driver, wall_at)) return std::nullopt;
      if (marching ? !marching->march(c.trap.driver, wall, options.max_boxes,
                                      [&](const RationalInterval& piece) { return std::make_pair(piece, wall_at); },
                                      Rational(1, 100000))
                   : !cover(c.trap.driver, wall, options.max_boxes,
                            [&](const RationalInterval& piece) { return blocking_piece(r, piece, wall_at, points); },
                            [&](const Rational& x) { return free_at(x, at); }, budget))
        return std::nullopt;
    }
  }
  // A free configuration in the trap (the claim is empty without one): the query's start, else
  // a grid over the trap, the near driver end first and the band's middle outwards.
  std::vector<JamStart> candidates;
  if (query.start) candidates.push_back(*query.start);
  if (march) {
    if (!query.start) return std::nullopt;
    c.start = query.start;
  }
  const RationalInterval& span = c.trap.driver;
  Rational near_end = c.direction > 0 ? span.lo : span.hi;
  for (const Rational& fraction : {Rational(0), Rational(1, 2), Rational(1, 4), Rational(3, 4)}) {
    if (march) break;
    Rational x = near_end + (c.direction > 0 ? Rational(1) : Rational(-1)) * fraction * (span.hi - span.lo);
    if (!r.has_follower) {
      candidates.push_back({x, std::nullopt});
      continue;
    }
    const RationalInterval& band = *c.trap.follower;
    for (int k = 0; k <= 30; ++k) {   // 16/32, 15/32, 17/32, 14/32, ...
      int offset = (k + 1) / 2 * (k % 2 ? -1 : 1);
      candidates.push_back({x, Rational(band.lo + (band.hi - band.lo) * Rational(16 + offset, 32))});
    }
  }
  for (const JamStart& candidate : candidates)
    if (!c.start && verify::jam_start_failure(*r.driver, *r.other, c.trap, candidate).empty()) {
      c.start = candidate;
      break;
    }
  if (!c.start) return std::nullopt;
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}
}  // namespace

namespace {
// certify_trap with crossings only, then, when that fails, with point pieces too: every trap that
// crossings prove keeps the certificate it had (version 1, byte for byte), and point pieces
// (version 2) appear only where they are needed — flush faces, whose boundaries never cross.
std::optional<Certificate> certify_trap_with_points(const Model& model, const std::string& first, const std::string& second,
                                                    const JamQuery& query, const CertifyContext& context,
                                                    const IntervalSearchOptions& options, FreeConfigurations* seen,
                                                    std::size_t* tests = nullptr) {
  if (auto c = certify_trap(model, first, second, query, context, options, nullptr, tests, seen)) return c;
  return certify_trap(model, first, second, query, context, options, nullptr, tests, seen, true);
}

// A jam certificate produced on the pair moved to the origin (pair_moved_to_origin): its pieces'
// witness points, world points of the moved model, moved back to the model's (the verifier
// moves them again with the pair).
std::optional<Certificate> points_moved_back(std::optional<Certificate> c, const Model& model, const std::string& first,
                                             const std::string& second) {
  if (!c) return c;
  std::optional<Point> by = verify::pair_translation(model, first, second);
  for (auto* list : {&c->cut, &c->lower_wall, &c->upper_wall})
    for (BlockedPiece& piece : *list)
      if (piece.point && by) piece.point = Point{piece.point->x + by->x, piece.point->y + by->y};
  return c;
}
}  // namespace

std::optional<Certificate> certify_jam(const Model& model, const std::string& first, const std::string& second,
                                       const JamQuery& query, const CertifyContext& context,
                                       const IntervalSearchOptions& options) {
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return checked_as_given(points_moved_back(certify_jam(*moved, first, second, query, context, options), model, first, second), model);
  return certify_trap_with_points(model, first, second, query, context, options, nullptr);
}

namespace {
// certify_jam, sharing the free configurations its covers meet with the next call (`seen`)
std::optional<Certificate> certify_jam_seeing(const Model& model, const std::string& first, const std::string& second,
                                              const JamQuery& query, const CertifyContext& context,
                                              const IntervalSearchOptions& options, FreeConfigurations& seen,
                                              std::size_t* tests) {
  // (the copy moved to the origin is the same at every call: its configurations are the model's)
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return checked_as_given(
        points_moved_back(certify_jam_seeing(*moved, first, second, query, context, options, seen, tests), model, first, second),
        model);
  return certify_trap_with_points(model, first, second, query, context, options, &seen, tests);
}

std::optional<Certificate> found_jam(const Model& model, const std::string& first, const std::string& second,
                                     const JamQuery& query, const Rational& step, const CertifyContext& context,
                                     const IntervalSearchOptions& options, std::size_t* tests) {
  // The traps share the follower range and reach further each time: a free configuration that
  // made one trap's wall fail lies on the next ones' walls too (a closing channel that find_jam's
  // grid missed crosses them: 16 x 15 spur gears at zero backlash, session 54).
  FreeConfigurations seen;
  if (auto certificate = certify_jam_seeing(model, first, second, query, context, options, seen, tests)) return certificate;
  for (int further : {1, 2, 4, 8}) {
    JamQuery longer = query;
    Rational& far = query.direction > 0 ? longer.trap.driver.hi : longer.trap.driver.lo;
    far += query.direction * further * step;
    if (auto certificate = certify_jam_seeing(model, first, second, longer, context, options, seen, tests)) return certificate;
  }
  return std::nullopt;
}
}  // namespace

std::optional<Certificate> certify_found_jam(const Model& model, const std::string& first, const std::string& second,
                                             const JamQuery& query, const Rational& step, const CertifyContext& context,
                                             const IntervalSearchOptions& options) {
  return found_jam(model, first, second, query, step, context, options, nullptr);
}

std::optional<Certificate> certify_detail::certify_found_jam_within(const Model& model, const std::string& first,
                                                                    const std::string& second, const JamQuery& query,
                                                                    const Rational& step, const CertifyContext& context,
                                                                    std::size_t& tests) {
  return found_jam(model, first, second, query, step, context, IntervalSearchOptions{}, &tests);
}

std::optional<Certificate> certify_detail::certify_closing_jam(
    const Model& model, const std::string& first, const std::string& second, const std::string& driver, int direction,
    const Rational& closing_driver, const Rational& closing_follower, const std::vector<ClosingStart>& starts,
    const CertifyContext& context, std::size_t max_pieces) {
  if (direction != 1 && direction != -1) return std::nullopt;
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return checked_as_given(certify_closing_jam(*moved, first, second, driver, direction, closing_driver, closing_follower,
                                                starts, context, max_pieces),
                            model);
  const Part& d = part_of(model, driver);
  const Part& o = part_of(model, driver == first ? second : first);
  if (o.motion.kind == Motion::Kind::fixed) return std::nullopt;
  IntervalSearchOptions options;
  options.max_boxes = max_pieces;
  PairRoles r = pair_roles(model, first, second, driver, o.name);
  Shapes shapes{verify::shape_of(*r.driver), verify::shape_of(*r.other)};
  std::size_t budget = 300;
  for (const ClosingStart& s : starts) {
    Rational lead = (closing_driver - s.driver) * direction;   // driver travel from the start to the closing
    Rational width = s.hi - s.lo;
    if (sgn(lead) <= 0 || sgn(width) <= 0) continue;
    Rational y0 = (s.lo + s.hi) / 2;
    // how far the channel moves per driver unit (it runs from about y0 to the closing)
    Rational rate = abs(closing_follower - y0) / lead;
    bool start_free = false;
    // Past the closing by `past`: the channel's two sides have crossed, so the cut's depth grows
    // with `past`; the walls must clear the channel's sweep up to the cut.
    // (past, the walls' margin beyond the channel's span): a quarter of the lead past, then the
    // whole lead; margins of twice the sweep past the closing and all of, else a quarter of, the
    // travel from the start, else an eighth of that travel (a deeper wall takes fewer pieces, but
    // a wide one met free space: a 19 x 18 mesh at 3/4 of its travel; a narrower one's cut did
    // not pass the hardest point of a 17 x 17 mesh)
    const std::pair<Rational, Rational> shapes_of_trap[] = {
        {lead / 4, rate * (lead + lead / 2) + 2 * width}, {lead / 4, rate * (lead / 4 + lead / 2) + 2 * width},
        {lead / 4, rate * lead / 8 + 2 * width}, {lead, rate * (lead / 4 + 2 * lead) + 2 * width}};
    for (const auto& [past, margin] : shapes_of_trap) {
      Rational x1 = closing_driver + direction * past;
      RationalInterval band{std::min({s.lo, y0, closing_follower}) - margin, std::max({s.hi, y0, closing_follower}) + margin};
      JamQuery query{d.name, o.name, direction,
                     {direction > 0 ? RationalInterval{s.driver, x1} : RationalInterval{x1, s.driver}, band},
                     JamStart{s.driver, y0}};
      if (!verify::band_meets_limits(o, band)) break;
      // the start first: one not certainly free gives no certificate, whatever the trap (the MPFI
      // distance bound here; the verifier's whole check, with its exact nesting test, is
      // certify_trap's self-check)
      if (!start_free) {
        if (sgn(clearance_at(r, shapes, s.driver, y0)) <= 0) break;
        start_free = true;
      }
      std::optional<Certificate> certificate;
      try {
        certificate = certify_trap(model, first, second, query, context, options, &shapes, &budget);
      } catch (const NumericError&) {
        break;   // the self-check refused it: the start (its exact nesting test); the next start
      }
      if (certificate) return certificate;
    }
  }
  return std::nullopt;
}

bool periodic_jam_search(const Part& driver, const Part& other) {
  return driver.motion.kind == Motion::Kind::rotation && !driver.motion.angle_limits && other.motion.kind == Motion::Kind::fixed;
}

Rational periodic_jam_travel() { return Rational(710, 113); }

std::optional<JamQuery> find_jam(const Model& model, const std::string& first, const std::string& second,
                                 const std::string& driver, const Rational& start, const Rational& follower_start,
                                 int direction, const Rational& step, const Rational& travel) {
  // the query holds driver and follower values only: searched on a far pair moved to the origin
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return find_jam(*moved, first, second, driver, start, follower_start, direction, step, travel);
  const Part& d = part_of(model, driver);
  const Part& o = part_of(model, driver == first ? second : first);
  PairRoles r = pair_roles(model, first, second, driver, o.motion.kind == Motion::Kind::fixed ? "" : o.name);
  if (direction != 1 && direction != -1)
    throw NumericError("the jam direction must be +1 or -1, not " + std::to_string(direction));
  if (sgn(step) <= 0) throw NumericError("the step must be positive");
  // The driver moves within its own motion limits (session 56, hunt56): until then the search
  // drove a lever limited to [-30, 120] deg backward from 0 through its -30 deg limit, round to
  // -5.452 rad, and reported the stop's far side as the jam of that motion; with a limit before
  // the contact it searched past it and then "could not certify" the trap it found there.
  const auto& driver_limits = d.motion.kind == Motion::Kind::rotation      ? d.motion.angle_limits
                              : d.motion.kind == Motion::Kind::translation ? d.motion.translation_limits
                                                                           : std::optional<RationalInterval>{};
  if (driver_limits && (start < driver_limits->lo || start > driver_limits->hi))
    throw GeometryError("the jam search's start " + to_decimal_string(start) + (d.motion.kind == Motion::Kind::rotation ? " rad" : " mm") +
                        " lies outside the motion limits [" + to_decimal_string(driver_limits->lo) + ", " +
                        to_decimal_string(driver_limits->hi) + "] of '" + d.name + "'");
  JamQuery query{d.name, r.has_follower ? o.name : "", direction, {}, std::nullopt};
  // (session 57: `--travel 1e30` against a fixed part stepped through 10^30 rad of repeats)
  const Rational searched = periodic_jam_search(d, o) ? std::min(travel, periodic_jam_travel()) : travel;
  Rational x = start, f = follower_start;
  // A follower resting on a contact may overlap by a rounding: nudge it off, either way.
  for (Rational nudge(1, 10000000000); overlapping_at(r, x, f) && nudge < Rational(1, 100); nudge *= 10) {
    if (r.has_follower && !overlapping_at(r, x, follower_start + nudge)) f = follower_start + nudge;
    else if (r.has_follower && !overlapping_at(r, x, follower_start - nudge)) f = follower_start - nudge;
  }
  if (overlapping_at(r, x, f)) throw GeometryError("the parts overlap at the start");
  const auto& limits = o.motion.kind == Motion::Kind::rotation ? o.motion.angle_limits : o.motion.translation_limits;
  Rational follower_step = step / 4, follower_span = o.motion.kind == Motion::Kind::rotation ? Rational(1) : Rational(10);
  int last_side = 1;   // the follower's last move: 0 down, 1 up
  for (Rational moved = 0; moved < searched; moved += step) {
    Rational next = x + direction * step;
    if (driver_limits) {
      // the last step ends on the limit; standing on it, the driver goes no further
      const Rational& end = direction > 0 ? driver_limits->hi : driver_limits->lo;
      if (x == end) break;
      if (direction > 0 ? next > end : next < end) next = end;
    }
    if (!r.has_follower) {
      if (overlapping_at(r, next, 0)) {
        // The trap needs a free start (certify_jam): a grid point where the parts touch (a
        // contact on the step grid: a square sliding into a square 1 mm away, steps of 0.01 mm;
        // a lever resting on its stop) is none, and so is the rest of [x, next]. The start moves
        // back towards the previous grid point (x - step/2, - 3/4 step, ...) to a configuration
        // the exact predicate finds apart (session 56: until then such a jam was never certified).
        Rational near = x;
        for (int k = 1; k <= 8 && relation_at(r, near, 0) == PartRelation::touching; ++k) {
          Rational back = x - direction * step * Rational((1L << k) - 1, 1L << k);
          if (driver_limits && (back < driver_limits->lo || back > driver_limits->hi)) break;
          near = back;
        }
        query.trap.driver = direction > 0 ? RationalInterval{near, next} : RationalInterval{next, near};
        query.start = JamStart{near, std::nullopt};
        return query;
      }
    } else if (overlapping_at(r, next, f)) {
      // The follower's position nearest f, on the half-step grid about f within the free run
      // around f at x (channel's run, extended only as far as the search needs it), that is free
      // at the next driver position. A cam pushing its follower moves it a few steps each time:
      // extending the whole run first (up to follower_span on either side, an exact test per
      // step) made every driver step cost tens of thousands of tests.
      Rational half = follower_step / 2;
      Rational end[2] = {f, f};          // the run's ends so far (lower, upper)
      bool stopped[2] = {false, false};  // ... reached: blocked, at a limit, or follower_span away
      bool end_tested[2] = {false, false};
      auto extend = [&](int side) {      // channel's step, one at a time
        int sign = side == 0 ? -1 : 1;
        Rational step_to = end[side] + sign * follower_step;
        if (limits && (step_to < limits->lo || step_to > limits->hi)) {
          end[side] = side == 0 ? limits->lo : limits->hi;
          stopped[side] = true;
          return;
        }
        if (abs(step_to - f) > follower_span) {
          stopped[side] = true;
          return;
        }
        end[side] = step_to;
        if (overlapping_at(r, x, step_to)) stopped[side] = true;
      };
      bool moved_on = false;
      for (long k = 1; !moved_on && !(stopped[0] && stopped[1] && end_tested[0] && end_tested[1]); ++k) {
        for (int turn = 0; turn < 2 && !moved_on; ++turn) {
          int side = turn == 0 ? last_side : 1 - last_side;   // the way it moved last, first
          int sign = side == 0 ? -1 : 1;
          Rational y = f + sign * k * half;
          while (!stopped[side] && (side == 0 ? y < end[side] : y > end[side])) extend(side);
          bool inside = side == 0 ? y >= end[side] : y <= end[side];
          if (!inside) {
            // beyond the run: its end (a limit off the grid, say) is the last candidate this side
            if (end_tested[side]) continue;
            y = end[side];
            end_tested[side] = true;
          } else if (y == end[side] && stopped[side]) {
            end_tested[side] = true;
          }
          if (!overlapping_at(r, next, y)) {
            last_side = y < f ? 0 : 1;
            f = y;
            moved_on = true;
          }
        }
      }
      if (!moved_on) {
        query.trap.driver = direction > 0 ? RationalInterval{x, next} : RationalInterval{next, x};
        query.trap.follower = RationalInterval{end[0], end[1]};
        query.start = JamStart{x, f};
        return query;
      }
    }
    x = next;
  }
  return std::nullopt;
}

}  // namespace hipair
