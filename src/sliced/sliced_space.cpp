// The sliced 3-D C-space of a free (planar) part against a fixed part (include/hipair/sliced.hpp):
// slices through the translating-pair C-space (hipair::CSpace on the circle–segment stage),
// critical angles (critical_angles.hpp), representative slices, connections of free cells
// across critical angles, point location and connectivity.
#include <hipair/sliced.hpp>

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

#include "algebra/nearest_double.hpp"
#include "sliced/critical_angles.hpp"
#include "sliced/motion.hpp"
#include "sliced/nearby.hpp"
#include "core/exact_sqrt.hpp"
#include "core/model_scale.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>

namespace hipair {

namespace algebra = cspace::algebra;
using algebra::Real;

double SlicedAngle::radians() const {
  if (half_turn) return 3.141592653589793;
  return 2 * std::atan(to_double(t));
}

double SlicedAngle::degrees() const { return half_turn ? 180.0 : algebra::half_angle_degrees(t); }

double nearest_double(const AlgebraicNumber& number) { return algebra::nearest_double(sliced::real_of(number)); }

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The slice's part: `part` moved by p -> pivot + R (p - pivot) (R = [c -s; s c], exact, c^2 + s^2
// = 1), translating along `direction` within [-bound, bound], built directly as the model
// reader would build it from the text {"name": ..., "motion": {"translation": ...}, "loops":
// [...]} at index `index` of a model's parts (the same pointers; no labels, no features): a
// rotation keeps every loop's orientation, hole status and validity, so nothing is re-read,
// and no limit of the model format applies to the posed coordinates (a 10^-300 mm part turned
// by an angle of hundreds of bits).
Part slice_part(const Part& part, std::size_t index, const Point& pivot, const Rational& c, const Rational& s,
                const Point& direction, const Rational& bound) {
  auto map = [&](const Point& p) {
    Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
    return Point{Rational(pivot.x + c * dx - s * dy), Rational(pivot.y + s * dx + c * dy)};
  };
  const std::string at = "/parts/" + std::to_string(index);
  Part out;
  out.name = part.name;
  out.pointer = at;
  out.motion.kind = Motion::Kind::translation;
  out.motion.direction = direction;
  out.motion.translation_limits = RationalInterval{-bound, bound};
  out.motion.pointer = at + "/motion";
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const Loop& loop = part.loops[l];
    Loop moved;
    moved.is_hole = loop.is_hole;
    moved.pointer = at + "/loops/" + std::to_string(l);
    if (loop.edges.size() == 1 && loop.edges[0].is_full_circle()) {
      // the reader's circle: its source on the centre's right (a rational radius), else the
      // turned source (the same circle; never written as text)
      const Edge& e = loop.edges[0];
      Edge circle;
      circle.kind = Edge::Kind::arc;
      circle.center = map(e.center);
      circle.radius_squared = e.radius_squared;
      if (auto r = rational_sqrt(e.radius_squared))
        circle.source = Point{Rational(circle.center.x + *r), circle.center.y};
      else
        circle.source = map(e.source);
      circle.target = circle.source;
      circle.ccw = e.ccw;   // the reader's circle is ccw, turned clockwise when the loop is a hole
      circle.pointer = moved.pointer + "/circle";
      moved.edges.push_back(std::move(circle));
      out.loops.push_back(std::move(moved));
      continue;
    }
    Point current = map(loop.edges[0].source);
    for (std::size_t k = 0; k < loop.edges.size(); ++k) {
      const Edge& e = loop.edges[k];
      Edge edge;
      edge.kind = e.kind;
      edge.source = current;
      edge.target = map(e.target);
      edge.pointer = moved.pointer + "/edges/" + std::to_string(k);
      if (e.is_arc()) {
        edge.center = map(e.center);
        edge.ccw = e.ccw;
        Rational dx = edge.source.x - edge.center.x, dy = edge.source.y - edge.center.y;
        edge.radius_squared = dx * dx + dy * dy;
      }
      current = edge.target;
      moved.edges.push_back(std::move(edge));
    }
    out.loops.push_back(std::move(moved));
  }
  return out;
}

// An upper bound of max |p - pivot|_inf over the part's points... (L1 norms of vertices,
// centres plus radii, r <= max(unit, r^2 / unit); rational).
Rational reach(const Part& part, const Point& pivot, const Rational& unit) {
  Rational best = 0;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      Rational v = abs(e.source.x - pivot.x) + abs(e.source.y - pivot.y);
      if (v > best) best = v;
      if (e.is_arc()) {
        Rational r_bound = e.radius_squared > unit * unit ? Rational(e.radius_squared / unit) : unit;   // r <= max(unit, r^2 / unit)
        Rational w = abs(e.center.x - pivot.x) + abs(e.center.y - pivot.y) + r_bound;
        if (w > best) best = w;
      }
    }
  return best;
}

// The lever of a free part about its pivot: 1 when the part's reach about its pivot is within
// 16 times its reach about its own first vertex (the pivot on or near the part: every ordinary
// model), else the least power of two at least the ratio. A pure rotation by dt of the
// half-angle tangent moves the part's points by up to 2 dt reach(pivot): the crossings try
// angle ranges narrowed by this factor, so that the part moves as little across them as a part
// turning about a point of its own (session 57, hunt57: a peg-in-hole with the peg's pivot 10^6
// mm away had 9 components for 5).
Rational pivot_lever(const Part& free, const Rational& unit) {
  if (free.loops.empty() || free.loops.front().edges.empty()) return 1;
  const Rational own = reach(free, free.loops.front().edges.front().source, unit);
  const Rational about_pivot = reach(free, free.motion.pivot, unit);
  if (own <= 0 || about_pivot <= 16 * own) return 1;
  Rational lever = 1;
  while (lever * own < about_pivot) lever *= 2;
  return lever;
}

// The centre of the free part's bounding box (of its vertices and arc centres; rational): the
// point about which its critical angles are computed, and about which its crossings turn when
// its pivot is far from it (session 58).
Point part_centre(const Part& part) {
  std::optional<Rational> x_lo, x_hi, y_lo, y_hi;
  auto add = [&](const Point& p) {
    if (!x_lo || p.x < *x_lo) x_lo = p.x;
    if (!x_hi || p.x > *x_hi) x_hi = p.x;
    if (!y_lo || p.y < *y_lo) y_lo = p.y;
    if (!y_hi || p.y > *y_hi) y_hi = p.y;
  };
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      add(e.source);
      if (e.is_arc()) add(e.center);
    }
  if (!x_lo) return part.motion.pivot;
  return Point{Rational((*x_lo + *x_hi) / 2), Rational((*y_lo + *y_hi) / 2)};
}

struct UnionFind {
  std::vector<std::size_t> parent;
  std::size_t add() {
    parent.push_back(parent.size());
    return parent.size() - 1;
  }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

std::string kind_name(FeatureKind k) { return k == FeatureKind::vertex ? "vertex" : k == FeatureKind::arc ? "arc" : "segment"; }

bool has_arc(const Part& part) {
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges)
      if (e.is_arc()) return true;
  return false;
}

}  // namespace

namespace sliced {

// ------------------------------------------------------------ a scale-free frame for the critical angles
// The critical angles are angles: the parts multiplied about the origin by a positive rational
// k (every point, the pivot; radii by k) have the same ones, exactly (every event condition is
// homogeneous in lengths). A model drawn at 10^-300 or 10^400 mm carries 10^300 in every
// rational of the algebra; divided by the common measure of its coordinates it is drawn in small
// integers. `common_measure` is that measure g = gcd(numerators) / lcm(denominators) of every
// coordinate of both parts (vertices, arc centres, the pivot): every coordinate / g is an
// integer. Used only when the parts are all tiny or all huge (their largest coordinate outside
// [2^-20, 2^40] mm) and the division shortens the coordinates: ordinary models keep their
// computation (and their output) as they were.
struct CoordinateMeasure {
  mpz_class numerator_gcd = 0, denominator_lcm = 1;
  Rational largest = 0;
  std::size_t bits = 0;   // sum of the coordinates' numerator and denominator bits
  void add(const Rational& v) {
    if (sgn(v) == 0) return;
    mpz_gcd(numerator_gcd.get_mpz_t(), numerator_gcd.get_mpz_t(), v.get_num_mpz_t());
    mpz_lcm(denominator_lcm.get_mpz_t(), denominator_lcm.get_mpz_t(), v.get_den_mpz_t());
    Rational a = abs(v);
    if (a > largest) largest = a;
    bits += mpz_sizeinbase(v.get_num_mpz_t(), 2) + mpz_sizeinbase(v.get_den_mpz_t(), 2);
  }
  void add(const Point& p) {
    add(p.x);
    add(p.y);
  }
  void add(const Part& part) {
    for (const auto& loop : part.loops)
      for (const auto& e : loop.edges) {
        add(e.source);
        add(e.target);
        if (e.is_arc()) add(e.center);
      }
  }
};

bool ordinary_scale(const Rational& largest);

// The measure of every coordinate of both parts and the free part's pivot.
CoordinateMeasure pair_measure(const Part& fixed, const Part& free) {
  CoordinateMeasure m;
  m.add(fixed);
  m.add(free);
  m.add(free.motion.pivot);
  return m;
}

// 2^(e - 4) for 2^e within a factor 2 of `largest` > 0 (1 for a 16..32 mm model; exact).
Rational unit_of_size(const Rational& largest) {
  long e = static_cast<long>(mpz_sizeinbase(largest.get_num_mpz_t(), 2)) -
           static_cast<long>(mpz_sizeinbase(largest.get_den_mpz_t(), 2)) - 4;
  mpz_class p = 1;
  p <<= static_cast<unsigned long>(e < 0 ? -e : e);
  return e < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

std::optional<Rational> scale_free_factor(const Part& fixed, const Part& free, bool any_scale) {
  const CoordinateMeasure m = pair_measure(fixed, free);
  if (m.numerator_gcd == 0) return std::nullopt;
  if (!any_scale && ordinary_scale(m.largest)) return std::nullopt;
  Rational k(m.denominator_lcm, m.numerator_gcd);   // 1 / g
  k.canonicalize();
  if (k == 1) return std::nullopt;
  // the coordinates times k: integers; their bits
  Rational scaled_largest = m.largest * k;
  std::size_t after = mpz_sizeinbase(scaled_largest.get_num_mpz_t(), 2);
  std::size_t count = 0;
  for (const auto* part : {&fixed, &free})
    for (const auto& loop : part->loops) count += 6 * loop.edges.size();
  count += 2;
  // worth it when the integers are shorter than the coordinates were, on average
  if (after * count >= m.bits) return std::nullopt;
  return k;
}

bool ordinary_scale(const Rational& largest) {
  const Rational low(mpz_class(1), mpz_class(1) << 20), high(mpz_class(1) << 40);
  return largest >= low && largest <= high;
}

Rational length_unit(const Part& fixed, const Part& free) { return length_unit_of_largest(pair_measure(fixed, free).largest); }

Rational length_unit_of_largest(const Rational& largest) {
  if (sgn(largest) == 0 || ordinary_scale(largest)) return 1;
  return unit_of_size(largest);
}

Rational size_unit(const Part& fixed, const Part& free) {
  const CoordinateMeasure m = pair_measure(fixed, free);
  if (sgn(m.largest) == 0) return 1;
  return unit_of_size(m.largest);
}

// The part with every length multiplied by k > 0 (about the origin; radii by k).
Part scaled_part(const Part& part, const Rational& k) {
  Part out = part;
  auto scale = [&](Point& p) {
    p.x *= k;
    p.y *= k;
  };
  for (auto& loop : out.loops)
    for (auto& e : loop.edges) {
      scale(e.source);
      scale(e.target);
      if (e.is_arc()) {
        scale(e.center);
        e.radius_squared *= k * k;
      }
    }
  scale(out.motion.pivot);
  if (out.motion.translation_limits) {
    out.motion.translation_limits->lo *= k;
    out.motion.translation_limits->hi *= k;
  }
  out.initial.offset *= k;
  out.initial.x *= k;
  out.initial.y *= k;
  return out;
}

}  // namespace sliced

// Is the part invariant under every rotation about some point: every loop a full circle, all
// with one centre (exact)?
bool round_free_part(const Part& part) {
  const Point* centre = nullptr;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      if (!e.is_full_circle()) return false;
      if (centre && !(e.center.x == centre->x && e.center.y == centre->y)) return false;
      centre = &e.center;
    }
  return centre != nullptr;
}

struct SlicedSpace::Impl {
  Model model;
  std::size_t fixed = 0, free = 0;
  std::string fixed_name, free_name;
  Rational bound;
  Rational unit = 1;   // the length the crossings' sample nudges are measured in (sliced::length_unit)
  long length_unit_exponent = 0;   // lengths in units of 2^this mm (SlicedBuildOptions::normalise_lengths)
  // The free part's lever about its pivot (pivot_lever): 1, or the power of two by which the
  // crossings' angle ranges are narrowed for a pivot far from the part (session 57; since
  // session 65 only those of the published chords).
  Rational lever = 1;
  // The least power of two whose square is at least the lever: a far pivot's published chord
  // over a range narrowed by it leaves the turn about Q by |Q - P| dt^2 / lever, the part's own
  // size times dt^2, with half the bits of the range narrowed by the lever (session 65).
  Rational root_lever = 1;
  // A pivot far from the free part (lever above 1): the crossings turn the part about its own
  // bounding box's centre `reference` Q (model units, part_centre), not about the pivot P
  // (session 58). The configuration (d, theta) about P places the part as (d - (I - R)(Q - P), theta) about Q
  // (p -> P + R (p - P) + d is Q + R (p - Q) + d - (I - R)(Q - P)): the slices about Q are the
  // model's translated, with the same cells and contacts, and a pure turn about Q by the range
  // near() gives moves the part by at most its own size times that range. About P the same
  // turn swept a peg 10^6 mm away across a hole 10^-9 wider than it, so the hole's cells were
  // not linked (12 components for 5). `near_free`: the free part with its pivot at Q,
  // `near_bound` its slices' box, `near_unit` its nudges' unit (sliced::length_unit of the pair
  // about Q: the part's scale, not the pivot's distance; session 65), `near_motion` the
  // first-contact query of the part pivoted at Q (turn_free).
  std::optional<Point> reference;
  std::optional<Part> near_free;
  Rational near_bound, near_unit = 1;
  std::optional<Model> near_model;
  std::optional<sliced::MotionChecker> near_motion;
  // The scale-free frame of the crossings (a pair drawn at an extreme scale: sliced::
  // scale_free_factor k, the coordinates integers, then divided by the power of two that brings
  // them to an ordinary size, sliced::size_unit: `frame` = k / that unit): the parts times
  // `frame`, their polygonal pair, and the slice box and the nudge unit of the scaled parts, made
  // as for an ordinary pair at 1 mm (session 52: the box k * bound and the steps k * unit
  // carried the model's 10^300 x 2^-1000 in every rational, and integer coordinates put every
  // cell's sample, its simplest rational, against the cell's side). The slice of the scaled
  // parts at an angle is exactly `frame` times the model's slice (translations scale with the
  // parts) inside both boxes (each holds every contact translation with a free margin), so a
  // point q of a frame slice is the model's configuration q / frame, in the corresponding cell
  // (the same contact key), and every decision on it (free on both sides, steady across) is the
  // same exact predicate.
  std::optional<Rational> frame;
  std::optional<Part> frame_fixed, frame_free;
  std::optional<sliced::PolygonalPair> frame_pair;
  Rational frame_bound, frame_unit = 1;
  SlicedBuildOptions options;
  std::optional<sliced::PolygonalPair> pair;
  std::optional<sliced::MotionChecker> motion;
  std::vector<sliced::Critical> critical;
  std::vector<CriticalAngle> critical_public;
  std::vector<SlicedInterval> intervals;
  std::vector<SlicedCrossing> crossings;
  std::vector<std::map<std::string, std::size_t>> keys;   // per interval: cell key -> free cell
  std::size_t component_count = 0;
  mutable SlicedStatistics stats;
  mutable std::mutex mutex;
  mutable std::map<std::string, std::shared_ptr<const CSpace>> cache;

  // ------------------------------------------------------------ slices
  std::shared_ptr<const CSpace> slice(const SlicedAngle& angle) const {
    return slice_of(model.parts[fixed], model.parts[free], bound, angle, "");
  }

  // The slice at `angle` in the crossings' frame (the model's slice when there is no frame;
  // about the part's own vertex when its pivot is far: `reference`).
  std::shared_ptr<const CSpace> frame_slice(const SlicedAngle& angle) const {
    if (!frame) return near_free ? slice_of(model.parts[fixed], *near_free, near_bound, angle, "near ") : slice(angle);
    return slice_of(*frame_fixed, *frame_free, frame_bound, angle, "frame ");
  }

  // (I - R(angle))(Q - P): the model's offset of the placement that is offset 0 about Q.
  Point about_pivot(const SlicedAngle& angle) const {
    auto [c, s] = sliced::rotation_of(angle);
    const Point& P = model.parts[free].motion.pivot;
    Rational vx = reference->x - P.x, vy = reference->y - P.y;
    return Point{Rational(vx - (c * vx - s * vy)), Rational(vy - (s * vx + c * vy))};
  }

  // The chart's angle at chart coordinate u (the chart about pi when `flip`: u = -1/t).
  static SlicedAngle chart_angle(const Rational& u, bool flip) {
    if (!flip) return SlicedAngle{u, false};
    if (sgn(u) == 0) return SlicedAngle{Rational(0), true};
    return SlicedAngle{Rational(-1 / u), false};
  }

  // The model's configuration of an offset q about the reference Q at an angle.
  Point from_reference(const Point& q, const SlicedAngle& angle) const {
    Point v = about_pivot(angle);
    return Point{Rational(q.x + v.x), Rational(q.y + v.y)};
  }

  // The turn about Q at offset q (model units, about Q) over [u_lo, u_hi] (chart about pi when
  // `flip`), ends included: certified free by the exact first-contact query of the part pivoted
  // at Q (near_motion: the pure rotation at offset q there), whose numbers are of the part's size.
  // The crossings of a far pivot look for their steady samples with it over near()'s ranges not
  // narrowed by the lever (session 65; sessions 57-64 tried every sample with chord_free over
  // the narrowed range, whose polynomials carried the pivot's |Q - P| in every coefficient and
  // the narrowed tangents' 330 bits at 10^100 mm).
  bool turn_free(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip) const {
    sliced::StraightMotion m{q.x, q.y, u_lo, q.x, q.y, u_hi, flip, {}};
    for (Rational* r : {&m.x0, &m.y0, &m.w0, &m.x1, &m.y1, &m.w1}) r->canonicalize();
    sliced::MotionResult r = near_motion->first_contact(m);
    return r.starts_apart && !r.found;
  }

  // The published witness of a far pivot's crossing: the turn about Q at offset q (model units,
  // about Q) over [u_lo, u_hi] is approximated by the straight motion of the model's chart
  // between its two ends (offsets about P, chart coordinates u_lo and u_hi): certified free by
  // the exact first-contact query, ends included. The chord leaves the turn's curve by |Q - P|
  // times the square of the range at most; near() narrows the range by the lever, so the chord
  // moves the part hardly more than the turn (checked once per link found by turn_free).
  bool chord_free(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip) const {
    const Point a = from_reference(q, chart_angle(u_lo, flip)), b = from_reference(q, chart_angle(u_hi, flip));
    sliced::StraightMotion m{a.x, a.y, u_lo, b.x, b.y, u_hi, flip, {}};
    for (Rational* r : {&m.x0, &m.y0, &m.w0, &m.x1, &m.y1, &m.w1}) r->canonicalize();
    sliced::MotionResult r = motion->first_contact(m);
    return r.starts_apart && !r.found;
  }

  std::shared_ptr<const CSpace> slice_of(const Part& a, const Part& b, const Rational& box, const SlicedAngle& angle,
                                         const std::string& prefix) const {
    std::string key = prefix + (angle.half_turn ? "pi" : to_exact_string(angle.t));
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = cache.find(key);
      if (it != cache.end()) return it->second;
    }
    auto start = Clock::now();
    auto [c, s] = sliced::rotation_of(angle);
    Model slice_model;
    slice_model.name = "slice";
    slice_model.angle_unit = "rad";
    slice_model.source = "<slice>";
    slice_model.parts.push_back(slice_part(a, 0, b.motion.pivot, Rational(1), Rational(0), Point{Rational(-1), Rational(0)}, box));
    slice_model.parts.push_back(slice_part(b, 1, b.motion.pivot, c, s, Point{Rational(0), Rational(1)}, box));
    slice_model.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "/pairs/0", std::nullopt});
    slice_model.pairs_explicit = true;
    auto space = std::make_shared<const CSpace>(CSpace::build(slice_model, a.name, b.name));
    std::lock_guard<std::mutex> lock(mutex);
    ++stats.slices_built;
    stats.seconds_slices += seconds_since(start);
    cache.emplace(key, space);
    return space;
  }

  // Does the free part at offset q stay apart from the fixed part while it turns through the
  // half-angle range [u_lo, u_hi] (chart about pi when `flip`)? Polygonal pairs: no contact
  // line passes q (steady_along, cheap, sufficient), else — and for pairs with arcs — the pure
  // rotation is certified free by the exact first-contact query (rotation_free). steady_along
  // ignores the contact segments' extents, so at a critical angle where the parts' edges are
  // parallel (a zero-clearance fit: the peg of side 10 in the hole of side 10 at theta = 0) some
  // infinite contact line passes through every sample of the outer free cell, far from any
  // actual contact: without the exact fallback the outer cell was not linked across such an
  // angle (4 components for 1, session 53).
  // `exact_fallback` false: the line test alone for polygonal pairs (the crossings' first pass).
  bool steady(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip, bool exact_fallback = true) const {
    if (pair && sliced::steady_along(*pair, q, u_lo, u_hi, flip)) return true;
    if (pair && !exact_fallback) return false;
    return rotation_free(q, u_lo, u_hi, flip);
  }

  // The pure rotation at offset q (model units) over [u_lo, u_hi] is free, ends included (exact).
  bool rotation_free(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip) const {
    sliced::StraightMotion m{q.x, q.y, u_lo, q.x, q.y, u_hi, flip, {}};
    for (Rational* r : {&m.x0, &m.y0, &m.w0, &m.x1, &m.y1, &m.w1}) r->canonicalize();
    sliced::MotionResult r = motion->first_contact(m);
    return r.starts_apart && !r.found;
  }

  // steady() for a point q of the crossings' frame (the model's q / k): the scaled pair's
  // contact lines are the model's times k, so steady_along on it is the same exact test.
  // A far pivot (`reference`): q is about Q, and the turn about Q is checked (turn_free; its
  // link's published chord about P is certified after, chord_free).
  bool steady_in_frame(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip, bool exact_fallback) const {
    if (reference) return turn_free(frame ? Point{Rational(q.x / *frame), Rational(q.y / *frame)} : q, u_lo, u_hi, flip);
    if (!frame) return steady(q, u_lo, u_hi, flip, exact_fallback);
    if (frame_pair && sliced::steady_along(*frame_pair, q, u_lo, u_hi, flip)) return true;
    if (frame_pair && !exact_fallback) return false;
    return rotation_free(Point{Rational(q.x / *frame), Rational(q.y / *frame)}, u_lo, u_hi, flip);
  }

  // ------------------------------------------------------------ cells of a slice
  static std::string cell_key(const CSpace& space, std::size_t cell) {
    std::set<std::string> labels;
    for (std::size_t e : space.cells()[cell].boundary)
      for (std::size_t f : space.edges()[e].curves) {
        const FeaturePair& fp = space.feature_pairs()[f];
        auto name = [](const std::string& part, const FeatureIdentity& id) {
          return part + " " + kind_name(id.kind) + " loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
        };
        labels.insert(name(fp.first_part, fp.first) + " / " + name(fp.second_part, fp.second));
      }
    std::string key;
    for (const auto& l : labels) {
      if (!key.empty()) key += "; ";
      key += l;
    }
    return key.empty() ? "(no contact)" : key;
  }

  // free cells of a slice: cell index -> key
  static std::vector<std::pair<std::size_t, std::string>> free_cells(const CSpace& space) {
    std::vector<std::pair<std::size_t, std::string>> out;
    for (std::size_t c = 0; c < space.cells().size(); ++c)
      if (space.cells()[c].kind == CellKind::free) out.emplace_back(c, cell_key(space, c));
    return out;
  }

  // The free cell of interval `interval` that the slice cell corresponds to.
  std::size_t match(std::size_t interval, const CSpace& space, std::size_t cell) const {
    std::string key = cell_key(space, cell);
    auto it = keys[interval].find(key);
    if (it == keys[interval].end())
      throw GeometryError("3-DOF pair '" + fixed_name + "'/'" + free_name + "': a free cell (" + key +
                          ") has no counterpart in the representative slice of interval " + std::to_string(interval) +
                          " (an unlisted critical angle)");
    return it->second;
  }

  // ------------------------------------------------------------ location
  SlicedLocation::Kind classify(const CSpace& space, const Rational& x, const Rational& y, std::size_t* cell) const {
    return classify_in(space, bound, x, y, cell);
  }

  // `box`: the slice's bound (bound, or frame_bound for a frame slice)
  SlicedLocation::Kind classify_in(const CSpace& space, const Rational& box, const Rational& x, const Rational& y,
                                   std::size_t* cell) const {
    *cell = no_index;
    if (abs(x) >= box || abs(y) >= box) return SlicedLocation::Kind::free;   // outside the box: apart
    Location l = space.locate(ChartPoint{0, x, y});
    switch (l.kind) {
      case Location::Kind::free:
        *cell = l.cell;
        return SlicedLocation::Kind::free;
      case Location::Kind::blocked: return SlicedLocation::Kind::blocked;
      case Location::Kind::touching: return SlicedLocation::Kind::contact;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        if (l.cell == no_index) return SlicedLocation::Kind::contact;
        if (space.cells()[l.cell].kind == CellKind::free) {
          *cell = l.cell;
          return SlicedLocation::Kind::free;
        }
        return space.cells()[l.cell].kind == CellKind::blocked ? SlicedLocation::Kind::blocked : SlicedLocation::Kind::contact;
      case Location::Kind::outside: break;
    }
    throw GeometryError("internal: a configuration inside the slice box located outside the slice");
  }

  // The free cell of the slice holding (x, y) outside the box: the cell touching the box.
  // `margin_unit`: unit (the model's slices) or frame_unit (a frame slice).
  std::size_t outer_cell(const CSpace& space) const { return outer_cell_in(space, unit); }
  std::size_t outer_cell_in(const CSpace& space, const Rational& margin_unit) const {
    const Rational& lo = space.charts()[0].x_lo;
    // a point just inside the box corner is free (the box exceeds the blocked region by 2 units)
    Location l = space.locate(ChartPoint{0, lo + margin_unit / 2, space.charts()[0].y_lo + margin_unit / 2});
    if (l.kind != Location::Kind::free) throw GeometryError("internal: the slice box corner is not free");
    return l.cell;
  }

  // Position of a rational angle: (interval, false) or (critical index, true).
  std::pair<std::size_t, bool> position(const SlicedAngle& angle) const {
    const std::size_t n = critical.size();
    if (n == 0) return {0, false};
    if (angle.half_turn) {
      if (critical.back().half_turn) return {n - 1, true};
      return {n - 1, false};
    }
    std::size_t below = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (critical[i].half_turn) continue;
      int c = critical[i].t.compare(angle.t);   // sign of critical - t
      if (c == 0) return {i, true};
      if (c < 0) ++below;
    }
    if (below == 0) return {n - 1, false};
    return {below - 1, false};
  }

  // A rational angle just after critical angle i with the half-angle range to it (u range and
  // chart flip), narrowed by `halvings`, and by `by` (1, or a far pivot's chord: the lever or its
  // square root).
  struct Near {
    SlicedAngle left, right;
    Rational u_lo, u_hi;
    bool flip = false;
  };
  Near near(std::size_t i, int halvings, const Rational& by = Rational(1)) const {
    const Rational& lever = by;
    const sliced::Critical& c = critical[i];
    Near out;
    // The range found (separated from the other critical angles) is then narrowed by `by` (a far
    // pivot's published chord; sessions 57-64 narrowed every range by the lever: a point of the
    // free part moves |q - pivot| dtheta, and dtheta <= 2 dt; a pivot 10^6 part sizes away
    // swept the part across the plate's hole within 2^-16 of t, so no sample was steady and the
    // hole's cells ended at every critical angle (9 components for 5; with a clearance of 10^-9
    // the range next to a critical angle 10^-10 away moved the peg 10^-4; since session 65 the
    // search turns about Q itself, turn_free).
    Rational width = Rational(1) / Rational(mpz_class(1) << (10 + 2 * halvings));
    auto separated = [&](const Rational& lo, const Rational& hi) {
      for (std::size_t k = 0; k < critical.size(); ++k) {
        if (k == i || critical[k].half_turn) continue;
        if (critical[k].t.compare(lo) >= 0 && critical[k].t.compare(hi) <= 0) return false;
      }
      return true;
    };
    if (c.half_turn) {
      // every other critical angle must lie in (-1/d, 1/d)
      Rational d = width;
      for (std::size_t k = 0; k < critical.size(); ++k)
        while (!critical[k].half_turn && (critical[k].t.compare(-1 / d) <= 0 || critical[k].t.compare(1 / d) >= 0)) d /= 2;
      d /= lever;
      out.flip = true;
      out.u_lo = -d;
      out.u_hi = d;
      out.left.t = 1 / d;      // theta just below pi: u = -1/t = -d
      out.right.t = -1 / d;    // just above -pi: u = d
      return out;
    }
    Real t = c.t;
    Rational lo, hi;
    if (t.exact) {
      Rational d = width;
      while (!separated(t.lower - d, t.lower + d)) d /= 2;
      d /= lever;
      lo = t.lower - d;
      hi = t.lower + d;
    } else {
      algebra::refine_dyadically(t, width);
      while (!t.exact && !separated(t.lower, t.upper)) algebra::refine_dyadically(t, (t.upper - t.lower) / 4);
      if (!t.exact && lever != 1) algebra::refine_dyadically(t, (t.upper - t.lower) / lever);
      if (t.exact) {
        Rational d = width;
        while (!separated(t.lower - d, t.lower + d)) d /= 2;
        d /= lever;
        lo = t.lower - d;
        hi = t.lower + d;
      } else {
        lo = t.lower;
        hi = t.upper;
      }
    }
    out.u_lo = lo;
    out.u_hi = hi;
    out.left.t = lo;
    out.right.t = hi;
    return out;
  }

  // ------------------------------------------------------------ the structure
  void build_structure() {
    auto start = Clock::now();
    sliced::CriticalStatistics cs;
    if (round_free_part(model.parts[free])) {
      // A disc (or concentric rings) turning about its pivot only moves its centre: the slice at
      // theta is the slice at 0 translated by (c - pivot) - R(theta)(c - pivot). Its contact
      // structure never changes: no critical angle, whatever the fixed part (arcs included).
    } else {
      // the critical angles in the scale-free frame when the parts are all tiny or all huge, or
      // normalised from beyond the doubles (scale_free_factor: the same angles, exactly, in
      // short integers; the normalised copy's rationals carry the 5^400 of a decimal 10^400)
      const Part* a = &model.parts[fixed];
      const Part* b = &model.parts[free];
      // A far pivot (`reference`): the critical angles and the crossings' frame are about Q, so
      // the scale-free factor and the frame's size are measured with the pivot at Q. Measured
      // with a pivot 10^400 mm away (the model normalised by 2^-1325) the factor was refused (no
      // shorter integers) and every candidate and frame slice carried 1 300-bit rationals: the peg
      // in the slot 10^400 mm from its pivot took 8 times the critical angles' time and 70 times
      // the slices' of the peg about its centre (session 59).
      std::optional<Part> about_reference;
      if (reference) {
        about_reference = *b;
        about_reference->motion.pivot = *reference;
        b = &*about_reference;
      }
      std::optional<Part> scaled_a, scaled_b;
      if (auto k = sliced::scale_free_factor(*a, *b, length_unit_exponent != 0)) {
        scaled_a = sliced::scaled_part(*a, *k);
        scaled_b = sliced::scaled_part(*b, *k);
        a = &*scaled_a;
        b = &*scaled_b;
        // the crossings' frame: the same parts at an ordinary size (kept in Impl: frame_pair
        // points at them), their box and unit as an ordinary pair's
        const Rational to_ordinary = 1 / sliced::size_unit(*a, *b);
        frame = *k * to_ordinary;
        frame_fixed = sliced::scaled_part(*a, to_ordinary);
        frame_free = sliced::scaled_part(*b, to_ordinary);
        if (reference) frame_free->motion.pivot = part_centre(*frame_free);   // Q times frame
        frame_unit = sliced::length_unit(*frame_fixed, *frame_free);
        const Point& frame_pivot = frame_free->motion.pivot;
        frame_bound = reach(*frame_fixed, frame_pivot, frame_unit) + reach(*frame_free, frame_pivot, frame_unit) + 2 * frame_unit;
        if (!has_arc(*a) && !has_arc(*b)) frame_pair = sliced::polygonal_pair(*frame_fixed, *frame_free);
      }
      // The critical angles do not depend on the pivot: the slice at theta about pivot P is the
      // slice about P0 translated by (I - R(theta))(P - P0), the same contacts. They are computed
      // with the pivot moved to the centre of the part's bounding box: about a pivot 10^12 mm
      // away the candidates' certification lost its intervals and kept 2 320 critical angles for
      // the peg-in-hole's 12 (session 57, hunt57), and about the part's first vertex that of a
      // hole 10^-9 wider than the peg kept 4 more than about its centre (certified over
      // enclosures that widen with the distance from the pivot; session 58): the same list
      // whatever the pivot.
      std::optional<Part> near_pivot;
      if (const Point centre = part_centre(*b); centre.x != b->motion.pivot.x || centre.y != b->motion.pivot.y) {
        near_pivot = *b;
        near_pivot->motion.pivot = centre;
        b = &*near_pivot;
      }
      if (has_arc(*a) || has_arc(*b)) {
        if (options.progress) options.progress("critical angles");
        critical = sliced::critical_angles_with_arcs(*a, *b, cs);
      } else {
        pair = sliced::polygonal_pair(model.parts[fixed], model.parts[free]);   // model units (steady_along)
        if (options.progress) options.progress("critical angles");
        if (scaled_a || near_pivot || about_reference) {
          sliced::PolygonalPair scaled = sliced::polygonal_pair(*a, *b);
          critical = sliced::critical_angles(scaled, cs);
        } else {
          critical = sliced::critical_angles(*pair, cs);
        }
      }
    }
    stats.candidate_polynomials = cs.polynomials;
    stats.candidate_roots = cs.roots;
    stats.irrelevant_roots = cs.irrelevant;
    stats.seconds_critical = seconds_since(start);
    for (const auto& c : critical) {
      CriticalAngle out;
      out.half_turn = c.half_turn;
      out.events = c.events;
      if (c.half_turn) {
        out.degrees = 180;
      } else {
        out.t.polynomial = c.t.polynomial;
        out.t.lower = c.t.lower;
        out.t.upper = c.t.upper;
        out.t.exact = c.t.exact;
        out.degrees = algebra::half_angle_degrees(c.t);   // correctly rounded, whatever the scale
      }
      critical_public.push_back(std::move(out));
    }
    // intervals and representatives
    const std::size_t n = critical.size();
    std::size_t count = std::max<std::size_t>(n, 1);
    intervals.resize(count);
    keys.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      SlicedInterval& in = intervals[i];
      if (n == 0) {
        in.representative.t = 0;
      } else {
        in.lower_critical = i;
        in.upper_critical = (i + 1) % n;
        const auto& L = critical[i];
        const auto& U = critical[(i + 1) % n];
        if (L.half_turn && U.half_turn) {
          in.representative.t = 0;
        } else if (L.half_turn) {
          mpz_class f;
          mpz_fdiv_q(f.get_mpz_t(), U.t.lower.get_num_mpz_t(), U.t.lower.get_den_mpz_t());
          in.representative.t = Rational(f - 1);
        } else if (U.half_turn || i + 1 == n) {
          mpz_class f;
          mpz_cdiv_q(f.get_mpz_t(), L.t.upper.get_num_mpz_t(), L.t.upper.get_den_mpz_t());
          in.representative.t = Rational(f + 1);
        } else {
          in.representative.t = algebra::rational_between(L.t, U.t);
        }
      }
      if (options.progress) options.progress("slice " + std::to_string(i + 1) + " of " + std::to_string(count));
      auto space = slice(in.representative);
      for (const auto& [cell, key] : free_cells(*space)) {
        if (!keys[i].emplace(key, in.free_cells.size()).second)
          throw GeometryError("3-DOF pair '" + fixed_name + "'/'" + free_name +
                              "': two free cells of one slice have the same contacts (" + key + "); cannot match slices");
        in.free_cells.push_back(SlicedInterval::Cell{cell, key, no_index});
      }
    }
    // crossings
    UnionFind uf;
    std::vector<std::size_t> first_node(count);
    for (std::size_t i = 0; i < count; ++i) {
      first_node[i] = uf.parent.size();
      for (std::size_t k = 0; k < intervals[i].free_cells.size(); ++k) uf.add();
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (options.progress) options.progress("crossing " + std::to_string(i + 1) + " of " + std::to_string(n));
      SlicedCrossing crossing;
      crossing.critical = i;
      crossing.left_interval = (i + n - 1) % n;
      crossing.right_interval = i;
      std::set<std::size_t> left_done, right_done;
      std::map<std::pair<std::size_t, std::size_t>, SlicedConnection> links;
      const std::size_t left_count = intervals[crossing.left_interval].free_cells.size();
      const std::size_t right_count = intervals[crossing.right_interval].free_cells.size();
      // Two passes: the line test alone (steady_along: cheap; the links and witnesses as before
      // session 53), then, for polygonal pairs with a cell still without a link, the same rounds
      // with the exact pure-rotation check where the line test refuses (steady()).
      const bool polygonal = frame ? frame_pair.has_value() : pair.has_value();
      for (int pass = 0; pass < (polygonal && !reference ? 2 : 1); ++pass)
      for (int round = 0; round < 4 && (left_done.size() < left_count || right_done.size() < right_count); ++round) {
        const bool exact_fallback = pass == 1;
        Near nr = near(i, round);
        // A pair drawn at an extreme scale crosses in its scale-free frame (frame_slice: the
        // slices of the parts times `frame`, whose cells' samples are the simplest rationals of
        // cells of ordinary size, well inside them, as at scale 1; the model's own slices at
        // 10^-30 mm put them against a cell's side, on or beside the contact lines the steady
        // test refuses, and so did a frame of integers up to 36 540 (session 51's frame: 10
        // components for 3 without steps)). Every point below is in the frame's coordinates; a
        // link's witnesses are the model's configurations q / frame. Ordinary pairs: the
        // model's slices (no frame).
        auto ls = frame_slice(nr.left), rs = frame_slice(nr.right);
        // (a far pivot without a frame: the slices about Q, near_bound and near_unit)
        const Rational& box = frame ? frame_bound : reference ? near_bound : bound;
        const Rational& nudge = frame ? frame_unit : reference ? near_unit : unit;
        // each free cell's sample, and the same nudged off the contact lines through it
        std::vector<Point> samples;
        for (const auto* space : {ls.get(), rs.get()})
          for (const auto& cell : space->cells())
            if (cell.kind == CellKind::free)
              for (const Rational& e : {Rational(0), Rational(nudge / 1009), Rational(-nudge / 10007)}) {
                samples.push_back(Point{Rational(cell.sample_x + e), Rational(cell.sample_y + e * Rational(13, 10))});
              }
        // A pair at an extreme scale outside the frame (mixed scales: unit != 1 and no factor
        // shortens the coordinates) also tries the samples moved by larger steps of the pair's
        // own unit in four directions (only certified ones are used: free on the left, steady
        // across, free on the right). Ordinary pairs and frames (an ordinary pair: session 52)
        // keep their samples.
        if (!frame && nudge != 1) {
          const std::size_t base_count = samples.size();
          for (std::size_t n = 0; n < base_count; n += 3)
            for (const Rational& e : {Rational(nudge / 256), Rational(nudge / 64), Rational(nudge / 16), Rational(nudge / 4), nudge})
              for (const auto& [dx, dy] : {std::pair<int, int>{1, 1}, {1, -1}, {-1, 1}, {-1, -1}})
                samples.push_back(Point{Rational(samples[n].x + dx * e), Rational(samples[n].y + dy * e * Rational(13, 10))});
        }
        std::size_t before = links.size();
        for (const Point& q : samples) {
          std::size_t lc = no_index, rc = no_index;
          if (classify_in(*ls, box, q.x, q.y, &lc) != SlicedLocation::Kind::free) continue;
          if (!steady_in_frame(q, nr.u_lo, nr.u_hi, nr.flip, exact_fallback)) continue;
          if (classify_in(*rs, box, q.x, q.y, &rc) != SlicedLocation::Kind::free)
            throw GeometryError("internal: a configuration steady across a critical angle is not free on both sides");
          if (lc == no_index) lc = outer_cell_in(*ls, nudge);
          if (rc == no_index) rc = outer_cell_in(*rs, nudge);
          std::size_t a = match(crossing.left_interval, *ls, lc), b = match(crossing.right_interval, *rs, rc);
          Point w = q;   // the model's configuration
          if (frame) w = Point{Rational(q.x / *frame), Rational(q.y / *frame)};
          // about Q (a far pivot): the published witnesses are the ends of the chord about P of the
          // turn about Q over the range narrowed by the lever (inside the turn's certified range:
          // the same cells), certified free; else (a clearance too small for the chord) the
          // narrower ranges of the next rounds, and without one the sample is not used
          Near witness_range = nr;
          if (reference && !links.count(std::make_pair(a, b))) {
            bool found = false;
            for (const Rational* by : {&root_lever, &lever})
              for (int more = 0; more < 2 && !found; ++more) {
                witness_range = near(i, round + more, *by);
                found = chord_free(w, witness_range.u_lo, witness_range.u_hi, witness_range.flip);
              }
            if (!found) continue;
          }
          left_done.insert(a);
          right_done.insert(b);
          // about Q (a far pivot): the chord's two ends, the model's offsets about P
          const SlicedAngle &al = witness_range.left, &ar = witness_range.right;
          const Point wl = reference ? from_reference(w, al) : w, wr = reference ? from_reference(w, ar) : w;
          SlicedConnection link{a, b, SlicedConfiguration{wl.x, wl.y, al}, SlicedConfiguration{wr.x, wr.y, ar}, nr.flip};
          for (Rational* r : {&link.left_witness.x, &link.left_witness.y, &link.right_witness.x, &link.right_witness.y}) r->canonicalize();
          link.left_witness.angle.t.canonicalize();   // (dyadic refinement leaves fractions unreduced)
          link.right_witness.angle.t.canonicalize();
          links.emplace(std::make_pair(a, b), link);
        }
        if (round >= 1 && links.size() == before) break;   // the rest end or start here
      }
      for (const auto& [ab, link] : links) {
        const auto [a, b] = ab;
        crossing.connections.push_back(link);
        uf.unite(first_node[crossing.left_interval] + a, first_node[crossing.right_interval] + b);
      }
      for (std::size_t a = 0; a < left_count; ++a)
        if (!left_done.count(a)) crossing.ending.push_back(a);
      for (std::size_t b = 0; b < right_count; ++b)
        if (!right_done.count(b)) crossing.starting.push_back(b);
      crossings.push_back(std::move(crossing));
    }
    std::map<std::size_t, std::size_t> numbering;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < intervals[i].free_cells.size(); ++k) {
        std::size_t root = uf.find(first_node[i] + k);
        auto it = numbering.emplace(root, numbering.size()).first;
        intervals[i].free_cells[k].component = it->second;
      }
    component_count = numbering.size();
  }

  // The free cell (interval, cell) of a free configuration (structure built).
  std::pair<std::size_t, std::size_t> node_of(const SlicedConfiguration& q) const {
    auto [index, critical_angle] = position(q.angle);
    Point p{q.x, q.y};
    if (!critical_angle) {
      auto space = slice(q.angle);
      std::size_t cell = no_index;
      if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free) return {no_index, no_index};
      if (cell == no_index) cell = outer_cell(*space);
      return {index, match(index, *space, cell)};
    }
    // on a critical angle: follow the configuration's offset into the next interval, along
    // angles where it certainly stays free
    {
      auto space = slice(q.angle);
      std::size_t cell = no_index;
      if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free) return {no_index, no_index};
    }
    // The pure rotation at q from the critical angle towards the next interval (the chart range
    // of near(): no other critical angle in it) is free up to its first contact, exactly: turn to
    // half-way to it (a rational chart coordinate strictly before the contact, all of the turn
    // certified free). A free configuration is at a positive distance from every contact, so the
    // turn is never empty — also at a clearance of 1e-30 (session 53: the halvings of near()
    // stopped at 2^-88 and threw "no certified free motion" in a hole 1e-30 wider than the peg).
    Near nr = near(index, 0);
    const Rational u_lo = nr.flip ? Rational(0) : q.angle.t;
    Rational end = nr.u_hi;
    if (!(pair && sliced::steady_along(*pair, p, u_lo, nr.u_hi, nr.flip))) {
      sliced::StraightMotion m{q.x, q.y, u_lo, q.x, q.y, nr.u_hi, nr.flip, {}};
      for (Rational* r : {&m.x0, &m.y0, &m.w0, &m.x1, &m.y1, &m.w1}) r->canonicalize();
      sliced::MotionResult r = motion->first_contact(m);
      if (!r.starts_apart) throw GeometryError("internal: a free configuration on a critical angle starts in contact");
      if (r.found) {
        Real u = r.u;
        while (!u.exact && sgn(u.lower) <= 0) algebra::refine_dyadically(u, Rational((u.upper - u.lower) / 4));
        if (sgn(u.lower) <= 0) throw GeometryError("internal: a free rotation touches at once");
        end = u_lo + (nr.u_hi - u_lo) * u.lower / 2;
        end.canonicalize();
      }
    }
    const SlicedAngle off = nr.flip ? SlicedAngle{Rational(-1 / end), false} : SlicedAngle{end, false};
    auto space = slice(off);
    std::size_t cell = no_index;
    if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free)
      throw GeometryError("internal: a configuration steady off a critical angle is not free");
    if (cell == no_index) cell = outer_cell(*space);
    return {index, match(index, *space, cell)};
  }
};

SlicedSpace SlicedSpace::build(const Model& model, std::string_view fixed_part, std::string_view free_part,
                               const SlicedBuildOptions& options) {
  auto start = Clock::now();
  auto impl = std::make_shared<Impl>();
  impl->model = model;
  auto fixed = model.find_part(fixed_part);
  auto free = model.find_part(free_part);
  if (!fixed) throw ModelError("", "no part named '" + std::string(fixed_part) + "'");
  if (!free) throw ModelError("", "no part named '" + std::string(free_part) + "'");
  // a pair far from the origin for its size (drawn at 10^400 mm) is sliced moved to the origin
  // by one exact vector (core/model_scale.hpp): a configuration (x, y, theta about the pivot) is
  // a displacement, so every slice, critical angle, cell, crossing and witness is the same; the
  // length unit, the box and the slices then follow the pair's size, not its distance
  if (std::optional<Point> by = normalising_translation(model, {*fixed, *free}))
    impl->model = translated_model(model, *by);
  // a pair drawn with lengths beyond 2^1016 mm (10^400 mm), when asked, is sliced on the copy
  // scaled by 2^-L (core/model_scale.hpp): a configuration (x, y, theta) of the copy is the
  // model's (x 2^L, y 2^L, theta) — translations scale with the parts — so the critical angles
  // are the same numbers, every slice is the model's divided by 2^L, and every decision (exact
  // overlap, steady crossings) is the same predicate; its lengths are in units of 2^L mm.
  // Without the option the slices refuse such lengths (require_length_coordinates_in_range).
  if (options.normalise_lengths)
    if (long unit = length_coordinate_shift(impl->model, {*fixed, *free}); unit != 0) {
      impl->model = scaled_model(impl->model, unit);
      impl->length_unit_exponent = unit;
    }
  const Part& a = impl->model.parts[*fixed];
  const Part& b = impl->model.parts[*free];
  if (a.motion.kind != Motion::Kind::fixed)
    throw GeometryError("3-DOF pair: part '" + a.name + "' (" + a.pointer + ") must be fixed");
  if (b.motion.kind != Motion::Kind::planar)
    throw GeometryError("3-DOF pair: part '" + b.name + "' (" + b.pointer + ") must have a planar motion");
  if (b.motion.angle_limits || b.motion.translation_limits)
    throw GeometryError("3-DOF pair: part '" + b.name + "' has limits; the sliced C-space is built without limits");
  impl->fixed = *fixed;
  impl->free = *free;
  impl->fixed_name = a.name;
  impl->free_name = b.name;
  impl->options = options;
  // every contact translation d = a - pivot - R (b - pivot) has |d|_inf <= reach(a) + reach(b)
  // (a margin of 2 units: 2 mm for ordinary pairs, the pair's own scale at extreme ones, so that
  // the box's free margin, its outer cell's samples and the crossings' nudges follow the parts)
  impl->unit = sliced::length_unit(a, b);
  impl->bound = reach(a, b.motion.pivot, impl->unit) + reach(b, b.motion.pivot, impl->unit) + 2 * impl->unit;
  impl->lever = pivot_lever(b, impl->unit);
  impl->root_lever = Rational(mpz_class(1) << ((mpz_sizeinbase(impl->lever.get_num_mpz_t(), 2) - 1 + 1) / 2));
  if (impl->lever != 1) {
    impl->reference = part_centre(b);
    impl->near_free = b;
    impl->near_free->motion.pivot = *impl->reference;
    impl->near_unit = sliced::length_unit(a, *impl->near_free);
    impl->near_bound = reach(a, *impl->reference, impl->near_unit) + reach(b, *impl->reference, impl->near_unit) + 2 * impl->near_unit;
    impl->near_model = impl->model;
    impl->near_model->parts[*free].motion.pivot = *impl->reference;
    impl->near_motion.emplace(*impl->near_model, *fixed, *free);
  }
  impl->motion.emplace(impl->model, *fixed, *free);
  if (options.cell_structure) impl->build_structure();
  impl->stats.seconds_total = seconds_since(start);
  SlicedSpace out;
  out.impl_ = impl;
  return out;
}

const std::string& SlicedSpace::fixed_part() const { return impl_->fixed_name; }
const std::string& SlicedSpace::free_part() const { return impl_->free_name; }
std::shared_ptr<const CSpace> SlicedSpace::slice(const SlicedAngle& angle) const { return impl_->slice(angle); }
const Rational& SlicedSpace::bound() const { return impl_->bound; }
const Rational& SlicedSpace::length_unit() const { return impl_->unit; }
long SlicedSpace::length_unit_exponent() const { return impl_->length_unit_exponent; }
const std::vector<CriticalAngle>& SlicedSpace::critical_angles() const { return impl_->critical_public; }
const std::vector<SlicedInterval>& SlicedSpace::intervals() const { return impl_->intervals; }
const std::vector<SlicedCrossing>& SlicedSpace::crossings() const { return impl_->crossings; }
std::size_t SlicedSpace::components() const { return impl_->component_count; }
const SlicedStatistics& SlicedSpace::statistics() const { return impl_->stats; }

SlicedLocation SlicedSpace::locate(const SlicedConfiguration& q) const {
  SlicedLocation out;
  auto space = impl_->slice(q.angle);
  std::size_t cell = no_index;
  out.kind = impl_->classify(*space, q.x, q.y, &cell);
  if (out.kind != SlicedLocation::Kind::free || !impl_->options.cell_structure) return out;
  auto [index, critical_angle] = impl_->position(q.angle);
  if (critical_angle) return out;
  if (cell == no_index) cell = impl_->outer_cell(*space);
  out.interval = index;
  out.cell = impl_->match(index, *space, cell);
  return out;
}

std::size_t SlicedSpace::component_of(const SlicedConfiguration& q) const {
  if (!impl_->options.cell_structure) throw GeometryError("3-DOF pair: connectivity needs the cell structure");
  auto [interval, cell] = impl_->node_of(q);
  if (interval == no_index) return no_index;
  return impl_->intervals[interval].free_cells[cell].component;
}

namespace {

std::string feature_text(const Model& model, const FeatureIdentity& id) {
  std::string out = model.parts[id.part].name + " ";
  if (id.kind == FeatureKind::vertex) return out + "vertex of loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
  const std::string& label = model.parts[id.part].loops[id.loop].edges[id.edge].label;
  out += (id.kind == FeatureKind::arc ? "arc" : "segment");
  out += " loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
  if (!label.empty()) out += " (" + label + ")";
  return out;
}

// The motion's chart coordinate of an end.
Rational chart_w(SlicedAngle angle, bool flip, const char* which) {
  angle.t.canonicalize();
  if (!flip) {
    if (angle.half_turn)
      throw GeometryError(std::string("3-DOF motion: its ") + which +
                          " is the half turn; give the motion through_half_turn (the chart centred at pi)");
    return angle.t;
  }
  if (angle.half_turn) return Rational(0);
  if (sgn(angle.t) == 0)
    throw GeometryError(std::string("3-DOF motion: its ") + which +
                        " is at theta = 0, outside the chart centred at the half turn (through_half_turn)");
  return Rational(-1 / angle.t);
}

SlicedAngle angle_of_w(const Rational& w, bool flip) {
  if (!flip) return SlicedAngle{w, false};
  if (sgn(w) == 0) return SlicedAngle{Rational(0), true};
  return SlicedAngle{Rational(-1 / w), false};
}

SlicedFeaturePair sliced_feature_pair(const Model& model, const FeatureIdentity& fixed, const FeatureIdentity& free) {
  return SlicedFeaturePair{fixed, free, feature_text(model, fixed) + " / " + feature_text(model, free)};
}

}  // namespace

SlicedMotionCrossing SlicedSpace::first_crossing(const SlicedMotion& motion, const CrossingOptions& options) const {
  sliced::StraightMotion m;
  m.flip = motion.through_half_turn;
  m.x0 = motion.from.x;
  m.y0 = motion.from.y;
  m.w0 = chart_w(motion.from.angle, m.flip, "start");
  m.x1 = motion.to.x;
  m.y1 = motion.to.y;
  m.w1 = chart_w(motion.to.angle, m.flip, "end");
  for (Rational* r : {&m.x0, &m.y0, &m.x1, &m.y1}) r->canonicalize();
  for (const auto& [fixed, free] : motion.ignored) m.ignored.push_back(sliced::MotionContact{fixed, free});
  sliced::MotionResult r = impl_->motion->first_contact(m);
  SlicedMotionCrossing out;
  if (!r.starts_apart) {
    out.status = CrossingStatus::starts_in_contact;
    out.before = motion.from;
    return out;
  }
  if (!r.found) {
    out.u_lower = out.u_upper = 1;
    out.before = motion.to;
    return out;
  }
  out.status = CrossingStatus::crossing;
  Rational width = Rational(1) / Rational(mpz_class(1) << options.resolution_bits);
  Real u = r.u;
  if (!u.exact) algebra::refine_dyadically(u, width);
  out.u.polynomial = u.polynomial;
  out.u.lower = u.lower;
  out.u.upper = u.upper;
  out.u.exact = u.exact;
  out.u.lower.canonicalize();
  out.u.upper.canonicalize();
  out.u_lower = out.u.lower;
  out.u_upper = u.exact ? out.u.lower : out.u.upper;
  Rational before = u.exact ? Rational(out.u_lower - width) : out.u_lower;   // < u: free
  if (sgn(before) < 0) before = 0;
  auto lerp = [&](const Rational& a, const Rational& b) { return Rational(a + before * (b - a)); };
  out.before = SlicedConfiguration{lerp(m.x0, m.x1), lerp(m.y0, m.y1), angle_of_w(lerp(m.w0, m.w1), m.flip)};
  for (const auto& c : r.contacts) out.features.push_back(sliced_feature_pair(impl_->model, c.fixed, c.free));
  return out;
}

bool SlicedSpace::motion_free(const SlicedMotion& motion) const {
  return first_crossing(motion, CrossingOptions{4}).status == CrossingStatus::none;
}

std::vector<SlicedNearFeature> SlicedSpace::features_near(const SlicedConfiguration& q, const Rational& distance) const {
  if (sgn(distance) < 0) throw GeometryError("3-DOF pair: features_near needs a distance >= 0");
  auto found = sliced::near_features(impl_->model, impl_->fixed, impl_->free, q, distance);
  std::vector<SlicedNearFeature> out;
  for (const auto& f : found) {
    SlicedNearFeature n;
    n.pair = sliced_feature_pair(impl_->model, f.fixed, f.free);
    n.distance_lower = f.lower;
    n.distance_upper = f.upper;
    n.exact = f.exact;
    out.push_back(std::move(n));
  }
  return out;
}

bool SlicedSpace::connected(const SlicedConfiguration& a, const SlicedConfiguration& b) const {
  std::size_t ca = component_of(a), cb = component_of(b);
  return ca != no_index && ca == cb;
}

}  // namespace hipair
