// The stack-of-slices C-space of a pin-in-slot pair (include/hipair/pin_slot.hpp): slices at
// rational tau = tan(psi/2) built by hipair::CSpace on a derived two-part model, witnesses of
// connections between consecutive slices certified by exact 1-D C-spaces, changes of the
// free-cell structure isolated by bisection, exact point location.
#include <hipair/pin_slot.hpp>

#include <hipair/error.hpp>

#include "algebra/exact_real.hpp"
#include "algebra/nearest_double.hpp"
#include "sliced/witness_filter.hpp"
#include "core/model_scale.hpp"
#include "sliced/critical_angles.hpp"
#include "core/angle_limits.hpp"
#include "pinslot/moved_part.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <functional>
#include <limits>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

namespace hipair {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Rotation {
  Rational c = 1, s = 0;
};
// The exact rotation through psi with tan(psi/2) = t.
Rotation rotation_of_tangent(const Rational& t) {
  Rational d = 1 + t * t;
  Rotation r{Rational((1 - t * t) / d), Rational(2 * t / d)};
  r.c.canonicalize();
  r.s.canonicalize();
  return r;
}

Point rotate(const Point& v, const Rotation& r) {
  return Point{Rational(r.c * v.x - r.s * v.y), Rational(r.s * v.x + r.c * v.y)};
}

using pinslot_detail::moved_part;

std::string kind_text(Motion::Kind kind) {
  switch (kind) {
    case Motion::Kind::fixed: return "fixed";
    case Motion::Kind::rotation: return "rotation";
    case Motion::Kind::translation: return "translation";
    case Motion::Kind::planar: return "planar";
    case Motion::Kind::pin_slot: return "pin_slot";
  }
  return "?";
}

// A rational near `value` with denominator `den` (exact).
Rational near_rational(double value, long den) {
  Rational r(static_cast<long>(std::llround(value * static_cast<double>(den))), den);
  r.canonicalize();
  return r;
}

// The side of psi = 2 atan(x) + 2 pi turns against a rational angle limit L, for a real
// algebraic x: the sign of psi - L, exactly. x's isolating interval is refined until both its
// ends lie on one side (core/angle_sign.hpp): psi - L is never 0 but at psi = 0 = L - 2 pi turns
// (tan of a nonzero rational is transcendental, pi irrational), which is decided directly.
int limit_side(cspace::algebra::Real x, const mpz_class& turns, const Rational& L) {
  const mpz_class m = 2 * turns;
  if (sgn(m) == 0 && sgn(L) == 0) return x.compare(Rational(0));
  for (;;) {
    if (x.exact) return angle_sign(x.lower, m, L);
    if (angle_sign(x.upper, m, L) <= 0) return -1;   // x < upper
    if (angle_sign(x.lower, m, L) >= 0) return 1;    // x > lower
    x.refine();
  }
}

// A rational tau just beyond an angle limit L (side -1: below the lower limit, +1: above the
// upper one), psi = 2 atan(tau) + 2 pi turns: from the double tangent of the reduced limit
// (`reduced`, a choice), moved outward until the exact sign says so. \pre the reduced limit
// lies strictly inside (-pi, pi).
Rational beyond_limit(double reduced, const mpz_class& turns, const Rational& L, int side) {
  double t = std::tan(reduced / 2);
  if (!std::isfinite(t)) t = 0;
  const Rational base(t);
  Rational step = Rational(std::max(1.0, std::abs(t))) / (mpz_class(1) << 30);
  for (;;) {
    Rational candidate = base + side * step;
    candidate.canonicalize();
    if (angle_sign(candidate, 2 * turns, L) * side > 0) return candidate;
    step *= 2;
  }
}

// A rational tau strictly between the angle limit L (side -1: the lower one, +1: the upper
// one) and x, which lies strictly inside it; `outside` is a rational beyond the limit. Bisection
// between `outside` and x's end towards the limit once that end is inside too (exact signs).
Rational inside_limit(cspace::algebra::Real x, const Rational& outside, const mpz_class& turns, const Rational& L,
                      int side) {
  auto inside = [&](const Rational& t) { return angle_sign(t, 2 * turns, L) * side < 0; };
  while (!x.exact && !inside(side < 0 ? x.lower : x.upper)) x.refine();
  Rational near = outside, far = side < 0 ? x.lower : x.upper;   // far: x itself, or beyond it from the limit
  for (;;) {
    Rational middle = (near + far) / 2;
    middle.canonicalize();
    if (inside(middle)) return middle;
    near = middle;
  }
}

// The half-angle tangent tau = -1/u of psi = pi + 2 atan(u) (the chart about the half turn:
// tan((pi + psi') / 2) = -1 / tan(psi' / 2)), exactly, for a real u != 0: the root of
// tau^n p(-1/tau) (p's coefficients reversed, alternating in sign) in (-1/lower, -1/upper), once
// u's isolating interval excludes 0 (the map is increasing on each side of 0, and tau^n has one
// sign there, so the signs at the ends stay opposite and non-zero).
cspace::algebra::Real across_half_turn(cspace::algebra::Real u) {
  while (!u.exact && sgn(u.lower) <= 0 && sgn(u.upper) >= 0) u.refine();
  if (u.exact) {
    Rational t = Rational(-1) / u.lower;
    t.canonicalize();
    return cspace::algebra::Real::from_rational(t);
  }
  cspace::algebra::Real tau;
  const std::size_t n = u.polynomial.size() - 1;
  tau.polynomial.resize(n + 1);
  for (std::size_t k = 0; k <= n; ++k) {
    tau.polynomial[k] = u.polynomial[n - k];
    if ((n - k) % 2 == 1) tau.polynomial[k] = -tau.polynomial[k];
  }
  cspace::algebra::trim(tau.polynomial);
  if (sgn(tau.polynomial.back()) < 0)
    for (auto& c : tau.polynomial) c = -c;   // a positive leading coefficient, as the roots' polynomials
  tau.lower = Rational(-1) / u.lower;
  tau.upper = Rational(-1) / u.upper;
  tau.lower.canonicalize();
  tau.upper.canonicalize();
  return tau;
}

// Does the closed interval between `from` and `to` (either order) of the half-angle tangent of a 1-D rotation
// C-space lie inside one free interval of it, between two consecutive contact points of a chart
// about theta = 0? Exact: each interval's ends are exact algebraic numbers compared with the
// rationals. The answer to a motion from `from` to `to` that first_crossing left undecided (a
// contact closer to the path than its resolution, (to - from) / 2^44: one just beyond an end, as
// between two slices 10^-18 apart in tan(psi/2) about a pivot 10^18 mm away).
bool inside_one_free_interval(const CSpace& space, const Rational& a, const Rational& b) {
  const Rational& from = a < b ? a : b;
  const Rational& to = a < b ? b : a;
  for (std::size_t chart = 0; chart < space.charts().size(); ++chart) {
    const CSpaceChart& c = space.charts()[chart];
    if (c.x_kind != AxisKind::rotation || c.x_half_turn || from < c.x_lo || c.x_hi < to) continue;
    for (const CSpaceFace& face : space.faces(chart)) {
      if (face.kind != CellKind::free || !face.cell.valid()) continue;
      if (face.lower.valid() && sliced::real_of(space.vertices()[face.lower.index()].x).compare(from) >= 0) continue;
      if (face.upper.valid() && sliced::real_of(space.vertices()[face.upper.index()].x).compare(to) <= 0) continue;
      return true;   // (an interval without a lower or upper end reaches the chart's end)
    }
    return false;   // the chart's intervals partition it: from's interval does not reach to
  }
  return false;
}

struct UnionFind {
  std::vector<std::size_t> parent;
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

}  // namespace

Placement pin_slot_placement(const Part& part, const Rational& slide, const Rational& tau) {
  Rotation r = rotation_of_tangent(tau);
  Point shift = rotate(part.motion.direction, r);
  shift.x *= slide;
  shift.y *= slide;
  return placement_about(part.motion.pivot, r.c, r.s, shift);
}

Placement part_placement(const Part& part, const PartCoordinate& coordinate) {
  switch (part.motion.kind) {
    case Motion::Kind::fixed: return Placement{};
    case Motion::Kind::rotation: {
      if (coordinate.kind == PartCoordinate::Kind::offset)
        throw GeometryError("part '" + part.name + "' rotates: its coordinate is a half-angle tangent");
      if (coordinate.kind == PartCoordinate::Kind::half_turn)
        return placement_about(part.motion.pivot, Rational(-1), Rational(0), Point{});
      Rotation r = rotation_of_tangent(coordinate.value);
      return placement_about(part.motion.pivot, r.c, r.s, Point{});
    }
    case Motion::Kind::translation: {
      if (coordinate.kind != PartCoordinate::Kind::offset)
        throw GeometryError("part '" + part.name + "' translates: its coordinate is an offset");
      Point shift{Rational(part.motion.direction.x * coordinate.value), Rational(part.motion.direction.y * coordinate.value)};
      return placement_about(Point{}, Rational(1), Rational(0), shift);
    }
    default: break;
  }
  throw GeometryError("part '" + part.name + "': a " + kind_text(part.motion.kind) +
                      " part has no single coordinate");
}

struct PinSlotSpace::Impl {
  Model model;          // the two parts only: 0 = other, 1 = pin-slot part
  std::string other_name, pin_name;
  Motion::Kind other_kind = Motion::Kind::fixed;
  Rational tau_lo, tau_hi;
  bool whole_turn = false;
  std::vector<PinSlotSlice> slices;
  std::vector<PinSlotConnection> connections;
  std::vector<PinSlotChange> changes;
  std::vector<PinSlotCritical> critical;
  bool critical_exact = false;
  std::size_t group_count = 0;
  mutable PinSlotStatistics stats;
  mutable std::mutex mutex;
  mutable std::map<Rational, std::shared_ptr<const CSpace>> cache;
  mutable std::map<Rational, std::shared_ptr<const CSpace>> plane_cache;   // plane witnesses by slide
  bool witness_filter = true;   // PinSlotBuildOptions::witness_filter
  // the pair's length unit (sliced::length_unit): 1 mm for ordinary pairs, a power of two near
  // 1/16 of the largest coordinate for a pair drawn tiny or huge
  Rational unit = 1;
  long length_unit_exponent = 0;   // lengths in units of 2^this mm (PinSlotBuildOptions::normalise_lengths)

  const Part& other() const { return model.parts[0]; }
  const Part& pin() const { return model.parts[1]; }

  std::string where(const Rational& tau) const {
    return "pin-slot pair '" + other_name + "':'" + pin_name + "' at tan(psi/2) = " + to_exact_string(tau);
  }

  // ------------------------------------------------------------ slices
  std::shared_ptr<const CSpace> slice(const Rational& tau) const {
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = cache.find(tau);
      if (it != cache.end()) return it->second;
    }
    auto start = Clock::now();
    Rotation r = rotation_of_tangent(tau);
    Model derived;
    derived.name = "pin-slot slice";
    derived.angle_unit = "rad";
    derived.source = "<pin-slot slice>";
    derived.parts.push_back(other());
    Part turned = moved_part(pin(), placement_about(pin().motion.pivot, r.c, r.s, Point{}));
    turned.motion.kind = Motion::Kind::translation;
    turned.motion.pivot = Point{};   // unused by a translation (a far pin-slot pivot would be refused as a length)
    turned.motion.direction = rotate(pin().motion.direction, r);
    turned.motion.angle_limits.reset();
    turned.initial = PartConfiguration{};
    turned.initial.offset = pin().initial.offset;
    turned.dynamics.reset();
    derived.parts.push_back(std::move(turned));
    derived.parts[0].dynamics.reset();
    derived.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "", std::nullopt});
    derived.pairs_explicit = true;
    std::shared_ptr<const CSpace> space;
    try {
      space = std::make_shared<const CSpace>(CSpace::build(derived, other_name, pin_name));
    } catch (const Error& e) {
      throw GeometryError(where(tau) + ": the slice cannot be built: " + e.what());
    }
    std::lock_guard<std::mutex> lock(mutex);
    ++stats.slices_built;
    stats.seconds_slices += seconds_since(start);
    cache.emplace(tau, space);
    return space;
  }

  // A slice's chart point as coordinates per part.
  std::pair<PartCoordinate, Rational> coordinates(const CSpace& space, std::size_t chart, const Rational& x,
                                                  const Rational& y) const {
    if (space.dimension() == 1) return {PartCoordinate{}, x};
    const CSpaceChart& c = space.charts()[chart];
    PartCoordinate other;
    if (c.x_kind == AxisKind::translation) {
      other.kind = PartCoordinate::Kind::offset;
      other.value = x;
    } else if (!c.x_half_turn) {
      other.value = x;
    } else if (sgn(x) == 0) {
      other.kind = PartCoordinate::Kind::half_turn;
    } else {   // theta = pi + 2 atan(x): tan(theta/2) = -1/x
      other.value = Rational(-1) / x;
      other.value.canonicalize();
    }
    return {other, y};
  }

  Location locate_in(const CSpace& space, const PartCoordinate& other, const Rational& slide) const {
    if (space.dimension() == 1) return space.locate(PartCoordinate{PartCoordinate::Kind::offset, slide});
    return space.locate(other, PartCoordinate{PartCoordinate::Kind::offset, slide});
  }

  static PinSlotLocation::Kind kind_of(const CSpace& space, const Location& at) {
    switch (at.kind) {
      case Location::Kind::free: return PinSlotLocation::Kind::free;
      case Location::Kind::blocked: return PinSlotLocation::Kind::blocked;
      case Location::Kind::touching: return PinSlotLocation::Kind::contact;
      case Location::Kind::outside: return PinSlotLocation::Kind::outside;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        if (at.cell == no_index) return PinSlotLocation::Kind::contact;
        switch (space.cells()[at.cell].kind) {
          case CellKind::free: return PinSlotLocation::Kind::free;
          case CellKind::blocked: return PinSlotLocation::Kind::blocked;
          case CellKind::touching: return PinSlotLocation::Kind::contact;
        }
    }
    return PinSlotLocation::Kind::outside;
  }

  // ------------------------------------------------------------ cells of a slice
  static std::string cell_contacts(const CSpace& space, std::size_t cell) {
    std::set<std::string> labels;
    for (std::size_t e : space.cells()[cell].boundary)
      for (std::size_t f : space.edges()[e].curves) labels.insert(space.feature_pairs()[f].label);
    if (space.dimension() == 1) {
      // 1-D: a cell is an interval; its ends are vertices carrying the feature pairs
      for (const CSpaceFace& face : space.faces(0)) {
        if (face.cell.index() != cell) continue;
        for (VertexId v : {face.lower, face.upper})
          if (v.valid())
            for (std::size_t f : space.vertices()[v.index()].curves) labels.insert(space.feature_pairs()[f].label);
      }
    }
    std::string out;
    for (const auto& l : labels) out += (out.empty() ? "" : "; ") + l;
    return out.empty() ? "(no contact)" : out;
  }

  PinSlotSlice make_slice(const Rational& tau, bool refinement) const {
    auto space = slice(tau);
    PinSlotSlice out;
    out.tau = tau;
    out.degrees = cspace::algebra::half_angle_degrees(tau);   // correctly rounded
    out.refinement = refinement;
    out.cells = space->cells().size();
    for (std::size_t c = 0; c < space->cells().size(); ++c) {
      const CSpaceCell& cell = space->cells()[c];
      if (cell.kind != CellKind::free) continue;
      PinSlotCell fc;
      fc.slice_cell = c;
      fc.contacts = cell_contacts(*space, c);
      auto [other, slide] = coordinates(*space, cell.sample_chart, cell.sample_x, cell.sample_y);
      fc.sample_other = other;
      fc.sample_slide = slide;
      out.free_cells.push_back(std::move(fc));
    }
    return out;
  }

  static std::multiset<std::string> signature(const PinSlotSlice& slice) {
    std::multiset<std::string> out;
    for (const auto& c : slice.free_cells) out.insert(c.contacts);
    return out;
  }

  // ------------------------------------------------------------ witnesses
  // Is the segment at (other, slide) from tau a to tau b (a < b, the short way; across the
  // half turn when `wrap`) free throughout? Exact: the 1-D C-space of the pin-slot part turning
  // about its pivot, shifted by s along its direction, against the other part at `other`.
  bool segment_free(const PartCoordinate& other_at, const Rational& slide, const Rational& a, const Rational& b,
                    bool wrap) const {
    // The certified filter first (not across the half turn): the start (other_at, slide, a) is
    // strictly free (a free cell's sample), so boundaries that certainly stay apart over [a, b]
    // mean the segment is free throughout, the exact answer below.
    if (witness_filter && !wrap) {
      Part placed = moved_part(other(), part_placement(other(), other_at));
      Point shift{Rational(pin().motion.direction.x * slide), Rational(pin().motion.direction.y * slide)};
      if (pinslot::boundaries_certainly_apart(placed, pin(), pin().motion.pivot, shift, a, b)) {
        std::lock_guard<std::mutex> lock(mutex);
        ++stats.witness_spaces;   // a witness certified (statistics: witness_filtered of them by the filter)
        ++stats.witness_filtered;
        return true;
      }
    }
    Model derived;
    derived.name = "pin-slot witness";
    derived.angle_unit = "rad";
    derived.source = "<pin-slot witness>";
    Part fixed = moved_part(other(), part_placement(other(), other_at));
    fixed.motion = Motion{};
    fixed.motion.kind = Motion::Kind::fixed;
    fixed.dynamics.reset();
    Point shift{Rational(pin().motion.direction.x * slide), Rational(pin().motion.direction.y * slide)};
    // across the half turn the part is pre-turned by pi: psi = pi + psi', tan(psi'/2) = -1/tau
    Rational cos_pre = wrap ? -1 : 1;
    Part turning = moved_part(pin(), placement_about(pin().motion.pivot, cos_pre, Rational(0), Point{}));
    if (wrap) shift = Point{Rational(-shift.x), Rational(-shift.y)};
    turning = moved_part(turning, placement_about(Point{}, Rational(1), Rational(0), shift));
    turning.motion.kind = Motion::Kind::rotation;
    turning.motion.angle_limits.reset();
    turning.motion.translation_limits.reset();
    turning.initial = PartConfiguration{};
    turning.dynamics.reset();
    derived.parts = {fixed, turning};
    derived.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "", std::nullopt});
    derived.pairs_explicit = true;
    CSpace space = CSpace::build(derived, other_name, pin_name);
    {
      std::lock_guard<std::mutex> lock(mutex);
      ++stats.witness_spaces;
    }
    Rational from = a, to = b;
    if (wrap) {
      from = Rational(-1) / a;
      to = Rational(-1) / b;
      from.canonicalize();
      to.canonicalize();
    }
    MotionPath path;
    path.x.kind = AxisPath::Kind::half_tangent;
    path.x.coefficients = {from, Rational(to - from)};
    path.u_begin = 0;
    path.u_end = 1;
    MotionCrossing crossing = space.first_crossing(path);
    if (crossing.status == CrossingStatus::none) return true;
    // a contact within the query's resolution of the path (not certified to be entered) is
    // decided exactly on the 1-D C-space's intervals: a pivot 10^18 mm away put the slices as
    // close to a critical value (10^-36 in tau) as the path is long times 2^-44 (film:follower,
    // 6 groups at 10^18 for 2)
    if (crossing.status == CrossingStatus::crossing && crossing.grazing && inside_one_free_interval(space, from, to))
      return true;
    return false;
  }

  // Is the straight path at constant `slide` from (a_other, tau a) to (b_other, tau b) free
  // throughout? Exact: first crossing on the 2-D C-space of the other part (its own motion)
  // against the slotted part turning about its pivot, shifted by s along its direction.
  bool plane_free(const PartCoordinate& a_other, const PartCoordinate& b_other, const Rational& slide,
                  const Rational& a, const Rational& b) const {
    std::shared_ptr<const CSpace> space;
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = plane_cache.find(slide);
      if (it != plane_cache.end()) space = it->second;
    }
    if (!space) {
      Model derived;
      derived.name = "pin-slot plane witness";
      derived.angle_unit = "rad";
      derived.source = "<pin-slot plane witness>";
      Part moving = other();
      moving.dynamics.reset();
      Point shift{Rational(pin().motion.direction.x * slide), Rational(pin().motion.direction.y * slide)};
      Part turning = moved_part(pin(), placement_about(Point{}, Rational(1), Rational(0), shift));
      turning.motion.kind = Motion::Kind::rotation;
      turning.motion.angle_limits.reset();
      turning.motion.translation_limits.reset();
      turning.initial = PartConfiguration{};
      turning.dynamics.reset();
      derived.parts = {moving, turning};
      derived.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "", std::nullopt});
      derived.pairs_explicit = true;
      space = std::make_shared<const CSpace>(CSpace::build(derived, other_name, pin_name));
      std::lock_guard<std::mutex> lock(mutex);
      ++stats.plane_spaces;
      plane_cache.emplace(slide, space);
    }
    MotionPath path;
    if (other_kind == Motion::Kind::translation) {
      path.x.kind = AxisPath::Kind::offset;
    } else {
      // the straight path in t = tan(phi/2) is the short way only when it does not pass
      // through t = 0 between two large tangents of opposite signs: then it is skipped
      if (a_other.kind == PartCoordinate::Kind::half_turn || b_other.kind == PartCoordinate::Kind::half_turn) return false;
      if (sgn(a_other.value) * sgn(b_other.value) < 0 && (abs(a_other.value) > 1 || abs(b_other.value) > 1)) return false;
      path.x.kind = AxisPath::Kind::half_tangent;
    }
    path.x.coefficients = {a_other.value, Rational(b_other.value - a_other.value)};
    path.y.kind = AxisPath::Kind::half_tangent;
    path.y.coefficients = {a, Rational(b - a)};
    path.u_begin = 0;
    path.u_end = 1;
    return space->first_crossing(path).status == CrossingStatus::none;
  }

  // Points of free cell `cell` of `space` at slide s: (other coordinate) samples of the 1-D
  // slice along the other axis at y = s.
  std::vector<PartCoordinate> cell_points_at(const CSpace& space, std::size_t cell, const Rational& s) const {
    std::vector<PartCoordinate> out;
    for (const Slice& line : space.slice(SliceAxis::y, s))
      for (const Slice::Interval& in : line.intervals)
        if (in.cell.valid() && in.cell.index() == cell && in.kind == CellKind::free)
          out.push_back(coordinates(space, line.chart, in.sample, s).first);
    return out;
  }

  // The middle of each free cell of a slice, as witness candidates: the simplest slide, in the
  // pair's length unit, in the middle half of the cell's slide interval through the cell's
  // sample (2-D: on the line of the sample's other coordinate; 1-D: the cell itself), and, when
  // the other part translates, the simplest offset in the middle half of the cell's offset
  // interval at that slide. The intervals' ends are bounded by their exact isolating intervals;
  // a candidate is only proposed (connect locates it exactly in both slices). Only the free
  // cells k with wanted[k] are visited.
  std::vector<std::pair<PartCoordinate, Rational>> middle_candidates(const PinSlotSlice& s, const CSpace& space,
                                                                     const std::vector<bool>& wanted) const {
    std::vector<std::pair<PartCoordinate, Rational>> out;
    auto above = [](const AlgebraicNumber& a) { return a.exact ? a.lower : a.upper; };
    auto propose = [&](const Rational& lo, const Rational& hi) -> std::optional<Rational> {
      if (!(lo < hi)) return std::nullopt;   // isolating intervals wider than the cell
      Rational quarter = (hi - lo) / 4;
      Rational from = (lo + quarter) / unit, to = (hi - quarter) / unit;
      from.canonicalize();
      to.canonicalize();
      Rational middle = cspace::algebra::simplest_between(from, to) * unit;
      middle.canonicalize();
      return middle;
    };
    for (std::size_t index = 0; index < s.free_cells.size(); ++index) {
      if (!wanted[index]) continue;
      const PinSlotCell& c = s.free_cells[index];
      const CSpaceCell& cell = space.cells()[c.slice_cell];
      if (space.dimension() == 1) {
        for (const CSpaceFace& face : space.faces(0)) {
          if (!face.cell.valid() || face.cell.index() != c.slice_cell) continue;
          const CSpaceChart& chart = space.charts()[face.chart];
          Rational lo = face.lower.valid() ? above(space.vertices()[face.lower.index()].x) : chart.x_lo;
          Rational hi = face.upper.valid() ? space.vertices()[face.upper.index()].x.lower : chart.x_hi;
          if (auto slide = propose(lo, hi)) out.emplace_back(PartCoordinate{}, *slide);
        }
        continue;
      }
      // the middles of the cell's intervals on the line at `value` of `axis` (in its sample's chart)
      auto middles = [&](SliceAxis axis, const Rational& value) {
        std::vector<Rational> found;
        for (const Slice& line : space.slice(axis, value)) {
          if (line.chart != cell.sample_chart) continue;
          for (std::size_t k = 0; k < line.intervals.size(); ++k) {
            const Slice::Interval& in = line.intervals[k];
            if (!in.cell.valid() || in.cell.index() != c.slice_cell || in.kind != CellKind::free) continue;
            Rational lo = k == 0 ? line.lower : above(line.points[k - 1].at);
            Rational hi = k + 1 == line.intervals.size() ? line.upper : line.points[k].at.lower;
            if (auto middle = propose(lo, hi)) found.push_back(*middle);
          }
        }
        return found;
      };
      const bool other_translates = space.charts()[cell.sample_chart].x_kind == AxisKind::translation;
      for (const Rational& slide : middles(SliceAxis::x, cell.sample_x)) {
        out.emplace_back(coordinates(space, cell.sample_chart, cell.sample_x, slide).first, slide);
        // a translating other part's sample offset is a length too: its middle at that slide,
        // then the slide's middle at that offset
        if (other_translates)
          for (const Rational& offset : middles(SliceAxis::y, slide)) {
            out.emplace_back(coordinates(space, cell.sample_chart, offset, slide).first, slide);
            for (const Rational& again : middles(SliceAxis::x, offset))
              out.emplace_back(coordinates(space, cell.sample_chart, offset, again).first, again);
          }
      }
    }
    return out;
  }

  // Connections between slices i and j (j = i + 1, or the wrap from the last to the first).
  void connect(std::size_t i, std::size_t j, bool wrap, bool planes) {
    const PinSlotSlice& lo = slices[i];
    const PinSlotSlice& hi = slices[j];
    if (lo.free_cells.empty() || hi.free_cells.empty()) return;
    auto lo_space = slice(lo.tau);
    auto hi_space = slice(hi.tau);
    std::set<std::pair<std::size_t, std::size_t>> joined;
    auto cell_index = [](const PinSlotSlice& s, const Location& at) -> std::size_t {
      if (at.kind != Location::Kind::free) return no_index;
      for (std::size_t k = 0; k < s.free_cells.size(); ++k)
        if (s.free_cells[k].slice_cell == at.cell) return k;
      return no_index;
    };
    auto candidates = [&](const PinSlotSlice& s) {
      std::vector<std::pair<PartCoordinate, Rational>> out;
      for (const auto& c : s.free_cells) out.emplace_back(c.sample_other, c.sample_slide);
      return out;
    };
    std::vector<std::pair<PartCoordinate, Rational>> points = candidates(lo);
    for (auto& p : candidates(hi)) points.push_back(p);
    // cells a of lo and b of hi joined by a witness (p in lo at slide s, q in hi)
    auto join = [&](PinSlotConnection::Kind kind, std::size_t a, std::size_t b, const PartCoordinate& p,
                    const PartCoordinate& q, const Rational& s) {
      joined.insert({a, b});
      PinSlotConnection c;
      c.kind = kind;
      c.lower = i;   // across the half turn: i is the last slice, j == 0
      c.lower_cell = a;
      c.upper_cell = b;
      c.witness_other = p;
      c.witness_other_upper = q;
      c.witness_slide = s;
      connections.push_back(c);
    };
    auto try_points = [&](const std::vector<std::pair<PartCoordinate, Rational>>& tried) {
      for (const auto& [other_at, slide] : tried) {
        ++stats.witness_candidates;
        std::size_t a = cell_index(lo, locate_in(*lo_space, other_at, slide));
        std::size_t b = cell_index(hi, locate_in(*hi_space, other_at, slide));
        if (a == no_index || b == no_index || joined.count({a, b})) continue;
        if (!segment_free(other_at, slide, lo.tau, hi.tau, wrap)) continue;
        join(PinSlotConnection::Kind::vertical, a, b, other_at, other_at, slide);
      }
    };
    try_points(points);
    // Then the cells' middles. A pair drawn tiny or huge: a cell's sample (the simplest rational
    // of the cell in mm) lies within about 1 mm of a side (10^-100 of a cell at 10^100 mm), where
    // the segment to the next slice leaves the cell: the film advance x 10^+-100 ... 10^+-300 had
    // 3-4 connections for 14; every cell's middle is tried. An ordinary pair's sample can lie
    // near a side too: the film advance at 1 mm left two cells unjoined to the next slice (4
    // groups) that their middles join (2 groups, as at 10^100; session 49): there the middles
    // of the cells that no sample joined across these two slices are tried.
    std::vector<bool> lo_wanted(lo.free_cells.size(), unit != 1), hi_wanted(hi.free_cells.size(), unit != 1);
    if (unit == 1) {
      std::vector<bool> lo_joined(lo.free_cells.size()), hi_joined(hi.free_cells.size());
      for (const auto& [a, b] : joined) lo_joined[a] = hi_joined[b] = true;
      for (std::size_t k = 0; k < lo_wanted.size(); ++k) lo_wanted[k] = !lo_joined[k];
      for (std::size_t k = 0; k < hi_wanted.size(); ++k) hi_wanted[k] = !hi_joined[k];
    }
    std::vector<std::pair<PartCoordinate, Rational>> middles = middle_candidates(lo, *lo_space, lo_wanted);
    for (auto& p : middle_candidates(hi, *hi_space, hi_wanted)) middles.push_back(std::move(p));
    try_points(middles);
    if (!planes || wrap || other_kind == Motion::Kind::fixed) return;
    // plane witnesses between pairs of cells still apart: slides at both samples and between
    for (std::size_t a = 0; a < lo.free_cells.size(); ++a)
      for (std::size_t b = 0; b < hi.free_cells.size(); ++b) {
        if (joined.count({a, b})) continue;
        const PinSlotCell& ca = lo.free_cells[a];
        const PinSlotCell& cb = hi.free_cells[b];
        Rational middle = (ca.sample_slide + cb.sample_slide) / 2;
        middle.canonicalize();
        bool done = false;
        for (const Rational& s : {middle, ca.sample_slide, cb.sample_slide}) {
          if (done) break;
          std::vector<PartCoordinate> from = cell_points_at(*lo_space, ca.slice_cell, s);
          std::vector<PartCoordinate> to = cell_points_at(*hi_space, cb.slice_cell, s);
          for (const auto& p : from) {
            for (const auto& q : to) {
              ++stats.witness_candidates;
              if (!plane_free(p, q, s, lo.tau, hi.tau)) continue;
              join(PinSlotConnection::Kind::plane, a, b, p, q, s);
              done = true;
              break;
            }
            if (done) break;
          }
        }
      }
  }
};

PinSlotSpace PinSlotSpace::build(const Model& model, std::string_view other_part, std::string_view pin_slot_part,
                                 const PinSlotBuildOptions& options) {
  auto start = Clock::now();
  auto a = model.find_part(other_part);
  auto b = model.find_part(pin_slot_part);
  if (!a) throw ModelError("", "no part named '" + std::string(other_part) + "'");
  if (!b) throw ModelError("", "no part named '" + std::string(pin_slot_part) + "'");
  const Part& pin = model.parts[*b];
  const Part& other = model.parts[*a];
  std::string pair = "pair '" + other.name + "':'" + pin.name + "'";
  if (*a == *b) throw GeometryError(pair + ": a part cannot be paired with itself");
  if (pin.motion.kind != Motion::Kind::pin_slot)
    throw GeometryError(pair + ": part '" + pin.name + "' (" + pin.pointer + ") has " + kind_text(pin.motion.kind) +
                        " motion, not pin_slot");
  if (other.motion.kind == Motion::Kind::planar || other.motion.kind == Motion::Kind::pin_slot)
    throw GeometryError(pair + ": a pin_slot part against a " + kind_text(other.motion.kind) + " part (" +
                        other.pointer +
                        ") has a C-space of 4 or more dimensions, which is not built; the other part must be fixed, "
                        "rotate or translate");
  if (options.slices == 1) throw GeometryError(pair + ": a stack needs at least 2 slices");
  auto impl = std::make_shared<Impl>();
  impl->other_name = other.name;
  impl->pin_name = pin.name;
  impl->other_kind = other.motion.kind;
  impl->model.name = model.name;
  impl->model.parts = {other, pin};
  // a pair far from the origin for its size (drawn at 10^400 mm from it) is stacked moved to it
  // by one exact vector (core/model_scale.hpp), as SlicedSpace::build slices one: its
  // configurations (the other part's angle or offset, the slide, tau) are displacements, so every
  // slice, change and witness is the same, and its length unit and slice boxes are those of the
  // pair at the origin (before session 51 the far pair kept a unit of 2^1325 mm: other witnesses,
  // film:follower + 10^400 joined 80 cell pairs for 82; with normalise_lengths it was scaled by
  // 2^-L itself, its 10 mm parts shrunk to 10^-400 of their size, and refused)
  if (std::optional<Point> by = normalising_translation(impl->model, {0, 1}))
    impl->model = translated_model(impl->model, *by);
  // a pair drawn with lengths beyond 2^1016 mm (10^400 mm), when asked, is stacked on the copy
  // scaled by 2^-L (core/model_scale.hpp; the same slices divided by 2^L: slides, offsets and
  // witnesses in units of 2^L mm, angles unchanged); without the option its slices refuse such
  // lengths (require_length_coordinates_in_range)
  if (options.normalise_lengths)
    if (long unit = length_coordinate_shift(impl->model, {0, 1}); unit != 0) {
      impl->model = scaled_model(impl->model, unit);
      impl->length_unit_exponent = unit;
    }
  impl->unit = sliced::length_unit(impl->other(), impl->pin());
  // slice angles: interior points of n equal angle steps across the limits (or the turn)
  std::size_t n = options.slices ? options.slices : 16;
  double lo = -std::numbers::pi, hi = std::numbers::pi;
  const std::optional<RationalInterval>& limits = impl->pin().motion.angle_limits;
  // limits spanning a whole turn (exactly, allowing for the reader's rounding of the two limits:
  // [-180, 180] deg is a whole turn whichever way pi was rounded) are the whole turn, however
  // wide (1e400 deg); before session 53 this was decided in doubles
  // (core/angle_limits.hpp, the decision pin_slot_cycle takes too)
  impl->whole_turn = pin_slot_whole_turn(model.roundings, impl->pin().motion);
  ReducedLimits reduced;
  if (!impl->whole_turn) {
    // limits given beyond a half turn ([100, 170] + 360 k deg) are the same angles reduced by
    // whole turns (the angle is taken modulo 2 pi, as locate does); the reduction is a choice of
    // slice angles in doubles, each slice's tau is then checked exactly inside the limits
    reduced = reduced_limits(*limits);
    lo = reduced.lo;
    hi = reduced.hi;
  }
  // Each slice angle is n-th of the range away from the limits; the rational tangent is within
  // 2^-13 of tan(angle/2), i.e. within about 2^-12 rad (times 1 + tan^2 <= 2 inside a half
  // turn... checked below) of the intended angle: the check that it stays inside the limits
  // uses a margin of a quarter step, far above the doubles' rounding.
  std::vector<Rational> taus;
  const double step = (hi - lo) / static_cast<double>(n);
  if (!(step > 1e-9))
    throw GeometryError(pair + ": the angle limits of part '" + pin.name + "' are too narrow to slice");
  // the stack is ordered by tau = tan(psi / 2), which jumps at the half turn psi = +-pi: limits
  // (less than a whole turn) whose slices would lie on both sides of it are refused, naming the field
  if (lo <= -std::numbers::pi - step / 4 || hi >= std::numbers::pi + step / 4)
    throw GeometryError(pair + ": the angle_limits of part '" + pin.name + "' (" + pin.motion.pointer +
                        "/pin_slot/angle_limits) cross the half turn psi = +-180 deg, which a stack of slices in "
                        "tan(psi/2) cannot cross: give limits within [-180, 180] deg (shifted by whole turns if "
                        "need be), or limits spanning a whole turn");
  for (std::size_t k = 0; k < n; ++k) {
    double angle = lo + step * (static_cast<double>(k) + 0.5);
    // the simplest dyadic tangent (denominator 4096 or finer) within a quarter step of the
    // intended angle: far inside the limits (the doubles' rounding is below 1e-15 rad)
    Rational t;
    for (long den = 4096;; den *= 2) {
      t = near_rational(std::tan(angle / 2), den);
      double back = 2 * std::atan(to_double(t));
      if (std::abs(back - angle) <= step / 4) break;   // so also >= lo + step / 4, <= hi - step / 4
      if (den > (1L << 40))
        throw GeometryError(pair + ": no rational slice angle found inside the angle limits of part '" + pin.name + "'");
    }
    if (!taus.empty() && t <= taus.back()) continue;
    // certified, not assumed: the slice lies inside the limits (exact, modulo whole turns)
    if (!impl->whole_turn && !angle_within_limits(t, limits->lo, limits->hi))
      throw GeometryError(pair + ": internal: slice tan(psi/2) = " + to_exact_string(t) +
                          " chosen outside the angle limits of part '" + pin.name + "'");
    taus.push_back(t);
  }
  if (taus.size() < 2) throw GeometryError(pair + ": the angle limits of part '" + pin.name + "' are too narrow to slice");
  impl->tau_lo = taus.front();
  impl->tau_hi = taus.back();
  if (!options.stack) taus.clear();
  // exact critical values: a fixed or translating other part, slides within limits
  const bool exact_class = (impl->other().motion.kind == Motion::Kind::fixed ||
                            (impl->other().motion.kind == Motion::Kind::translation && impl->other().motion.translation_limits)) &&
                           impl->pin().motion.translation_limits.has_value();
  if (options.critical_values && options.stack && exact_class) {
    auto critical_start = Clock::now();
    if (options.progress) options.progress("critical values");
    std::optional<std::pair<Rational, Rational>> q_range;
    if (impl->other().motion.kind == Motion::Kind::translation)
      q_range.emplace(impl->other().motion.translation_limits->lo, impl->other().motion.translation_limits->hi);
    sliced::CriticalStatistics cs;
    std::vector<sliced::Critical> found;
    bool in_class = true;
    try {
      // A wide stack (a whole turn: limits of 360 deg or 1e400 deg, or none) is searched in
      // pieces of at most 30 deg between sample slices: the finder's certified filters (double
      // intervals over the range) prove far more event polynomials rootless over a narrow range,
      // so the film advance's film pair over a whole turn takes 14 s CPU instead of more than
      // 15 min (session 53). Each piece but the first reaches half-way into the gap below its
      // lower end, so that a value at that end is inside it; values found twice are kept once
      // (exact comparison). A stack of at most 30 deg (the film advance's +-8 deg) is one piece:
      // the call as before. The pieces are a choice in doubles; the values are exact either way.
      std::vector<Rational> ends{taus.front()};
      std::size_t last_end = 0;
      auto degrees_of = [](const Rational& t) { return 2 * std::atan(to_double(t)) * 180 / std::numbers::pi; };
      for (std::size_t k = 1; k < taus.size(); ++k)
        if (k + 1 == taus.size() || degrees_of(taus[k + 1]) - degrees_of(taus[last_end]) > 30)
          ends.push_back(taus[k]), last_end = k;
      for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
        Rational from = ends[k];
        if (k > 0) from = (ends[k - 1] + ends[k]) / 2;
        from.canonicalize();
        sliced::CriticalStatistics piece_stats;
        for (auto& c : sliced::pin_slot_critical_values(impl->other(), impl->pin(), impl->pin().motion.translation_limits->lo,
                                                        impl->pin().motion.translation_limits->hi, q_range,
                                                        std::make_pair(from, ends[k + 1]), piece_stats)) {
          bool seen = false;
          for (const auto& f : found)
            if (!c.half_turn && !f.half_turn && cspace::algebra::compare(f.t, c.t) == 0) seen = true;
          if (!seen) found.push_back(std::move(c));
        }
        cs.roots += piece_stats.roots;
      }
      // Limits narrower than a whole turn: the two end pieces between a limit and the end slice
      // (about half a step each; before session 55 they were not searched while the values were
      // claimed complete), from a rational just beyond the limit to the end slice; the values
      // beyond the limits are dropped below. A limit at or beyond the half turn (the reduced
      // limit outside (-pi, pi), at most a quarter step: the piece crosses the jump of tau,
      // which no search in tau can) leaves the values incomplete: the sampled stack.
      if (!impl->whole_turn) {
        const mpz_class& turns = reduced.turns;
        if (angle_sign(Rational(0), 2 * turns - 1, limits->lo) >= 0 || angle_sign(Rational(0), 2 * turns + 1, limits->hi) <= 0)
          throw GeometryError("pin-slot angle limits reach the half turn");
        const std::pair<Rational, Rational> ends_pieces[] = {
            {beyond_limit(reduced.lo, turns, limits->lo, -1), taus.front()},
            {taus.back(), beyond_limit(reduced.hi, turns, limits->hi, 1)}};
        for (const auto& piece : ends_pieces) {
          sliced::CriticalStatistics piece_stats;
          for (auto& c : sliced::pin_slot_critical_values(impl->other(), impl->pin(), impl->pin().motion.translation_limits->lo,
                                                          impl->pin().motion.translation_limits->hi, q_range, piece,
                                                          piece_stats)) {
            bool seen = false;
            for (const auto& f : found)
              if (!c.half_turn && !f.half_turn && cspace::algebra::compare(f.t, c.t) == 0) seen = true;
            if (!seen) found.push_back(std::move(c));
          }
          cs.roots += piece_stats.roots;
        }
      }
      std::sort(found.begin(), found.end(), [](const sliced::Critical& a, const sliced::Critical& b) {
        if (a.half_turn != b.half_turn) return b.half_turn;
        return !a.half_turn && cspace::algebra::compare(a.t, b.t) < 0;
      });
    } catch (const GeometryError&) {
      // outside the finder's class (an arc of irrational radius, a segment of irrational
      // length facing an arc): the sampled stack, as without critical values
      in_class = false;
    }
    // The gap across the half turn of a whole-turn stack, (tau_hi, +inf) + {psi = pi} + (-inf,
    // tau_lo), which no search in tau can reach (before session 54 it was left out while the
    // values were claimed complete): searched in the chart about the half turn, psi = pi + psi',
    // u = tan(psi'/2) = -1/tau in [-1/tau_hi, -1/tau_lo] (0 = the half turn), on the pin-slot
    // part pre-turned by pi about its pivot with its slide direction reversed (the same placed
    // part at every psi: R(psi') R(pi) P + s R(psi') (-d) = R(psi) P + s R(psi) d). In pieces of
    // at most 30 deg as above (a choice in doubles; the values are exact either way); values
    // at the gap's ends (the end slices' own tau) are left out as above.
    std::vector<cspace::algebra::Real> gap;
    if (in_class && impl->whole_turn) {
      try {
        Part turned = moved_part(impl->pin(), placement_about(impl->pin().motion.pivot, Rational(-1), Rational(0), Point{}));
        turned.motion.direction = Point{Rational(-impl->pin().motion.direction.x), Rational(-impl->pin().motion.direction.y)};
        Rational u_lo = Rational(-1) / impl->tau_hi, u_hi = Rational(-1) / impl->tau_lo;
        u_lo.canonicalize();
        u_hi.canonicalize();
        const double from_angle = 2 * std::atan(to_double(u_lo)), to_angle = 2 * std::atan(to_double(u_hi));
        const auto pieces = static_cast<long>(std::ceil((to_angle - from_angle) / (30 * std::numbers::pi / 180)));
        std::vector<Rational> ends{u_lo};
        for (long k = 1; k < pieces; ++k) {
          Rational end = near_rational(std::tan((from_angle + (to_angle - from_angle) * static_cast<double>(k) /
                                                                  static_cast<double>(pieces)) / 2), 4096);
          if (end > ends.back() && end < u_hi) ends.push_back(end);
        }
        ends.push_back(u_hi);
        for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
          sliced::CriticalStatistics piece_stats;
          for (auto& c : sliced::pin_slot_critical_values(impl->other(), turned, impl->pin().motion.translation_limits->lo,
                                                          impl->pin().motion.translation_limits->hi, q_range,
                                                          std::make_pair(ends[k], ends[k + 1]), piece_stats)) {
            if (c.half_turn || c.t.compare(u_lo) <= 0 || c.t.compare(u_hi) >= 0) continue;
            bool seen = false;
            for (const auto& f : gap)
              if (cspace::algebra::compare(f, c.t) == 0) seen = true;
            if (!seen) gap.push_back(std::move(c.t));
          }
          cs.roots += piece_stats.roots;
        }
        std::sort(gap.begin(), gap.end(),
                  [](const cspace::algebra::Real& a, const cspace::algebra::Real& b) { return cspace::algebra::compare(a, b) < 0; });
      } catch (const GeometryError&) {
        in_class = false;
      }
    }
    impl->stats.critical_roots = cs.roots;
    // the values strictly inside the stack's range: (tau_lo, tau_hi) for a whole turn; strictly
    // inside the angle limits otherwise (exact signs against the limits for those at or beyond
    // an end slice). A value at a limit itself (only psi = 0 can be: tau rational) is listed
    // too, and the limit becomes a slice of its own, the stack's end.
    std::vector<cspace::algebra::Real> inside;
    std::vector<Rational> at_limits;
    bool at_lower_limit = false, at_upper_limit = false;
    if (in_class)
      for (const auto& c : found) {
        if (c.half_turn) continue;
        const int below_hi = c.t.compare(impl->tau_hi), above_lo = c.t.compare(impl->tau_lo);
        if (above_lo > 0 && below_hi < 0) {
          inside.push_back(c.t);
        } else if (!impl->whole_turn) {
          const bool lower = above_lo <= 0;
          const int side = limit_side(c.t, reduced.turns, lower ? limits->lo : limits->hi);
          if (side == 0) {
            at_limits.push_back(Rational(0));
            (lower ? at_lower_limit : at_upper_limit) = true;
          } else if (lower ? side > 0 : side < 0) {
            inside.push_back(c.t);
          }
        }
      }
    // a slice in every interval between consecutive critical values
    for (std::size_t k = 0; k + 1 < inside.size(); ++k) {
      bool has = std::any_of(taus.begin(), taus.end(), [&](const Rational& t) {
        return inside[k].compare(t) < 0 && inside[k + 1].compare(t) > 0;
      });
      if (!has) taus.push_back(cspace::algebra::rational_between(inside[k], inside[k + 1]));
    }
    // and (limited stacks) between each limit and the value nearest it, when the end pieces
    // held values or one is at an end slice
    if (!impl->whole_turn && !inside.empty()) {
      const cspace::algebra::Real &first = inside.front(), &last = inside.back();
      if (std::none_of(taus.begin(), taus.end(), [&](const Rational& t) { return first.compare(t) > 0; }))
        taus.push_back(inside_limit(first, beyond_limit(reduced.lo, reduced.turns, limits->lo, -1), reduced.turns,
                                    limits->lo, -1));
      if (std::none_of(taus.begin(), taus.end(), [&](const Rational& t) { return last.compare(t) < 0; }))
        taus.push_back(inside_limit(last, beyond_limit(reduced.hi, reduced.turns, limits->hi, 1), reduced.turns,
                                    limits->hi, 1));
    }
    for (const Rational& t : at_limits)
      if (std::find(taus.begin(), taus.end(), t) == taus.end()) taus.push_back(t);
    // in the gap: a slice between consecutive values there (u = -1/tau, never u = 0), beyond
    // the end slices (which lie between the gap's values and the others); the stack's ends
    // become the outermost slices
    bool half_turn_critical = false;
    std::vector<cspace::algebra::Real> above, below;   // tau > tau_hi, tau < tau_lo
    if (in_class) {
      for (std::size_t k = 0; k + 1 < gap.size(); ++k) {
        const bool across = gap[k].compare(Rational(0)) < 0 && gap[k + 1].compare(Rational(0)) >= 0;
        Rational u = cspace::algebra::rational_between(gap[k], across ? cspace::algebra::Real::from_rational(Rational(0)) : gap[k + 1]);
        Rational t = Rational(-1) / u;
        t.canonicalize();
        taus.push_back(t);
      }
      for (const auto& u : gap) {
        int side = u.compare(Rational(0));
        if (side == 0) half_turn_critical = true;
        else (side < 0 ? above : below).push_back(across_half_turn(u));
      }
    }
    std::sort(taus.begin(), taus.end());
    impl->tau_lo = taus.front();
    impl->tau_hi = taus.back();
    std::vector<cspace::algebra::Real> listed = below;
    if (at_lower_limit) listed.push_back(cspace::algebra::Real::from_rational(Rational(0)));
    listed.insert(listed.end(), inside.begin(), inside.end());
    if (at_upper_limit) listed.push_back(cspace::algebra::Real::from_rational(Rational(0)));
    listed.insert(listed.end(), above.begin(), above.end());
    for (auto& r : listed) {
      PinSlotCritical c;
      cspace::algebra::refine_dyadically(r, Rational(1, 1 << 30));
      c.tau = sliced::algebraic_of(r);
      c.degrees = cspace::algebra::half_angle_degrees(r);   // correctly rounded (an interval about 0 included)
      impl->critical.push_back(std::move(c));
    }
    if (half_turn_critical) {
      PinSlotCritical c;
      c.half_turn = true;
      c.degrees = 180;
      impl->critical.push_back(std::move(c));
    }
    impl->critical_exact = in_class;
    impl->stats.seconds_critical = seconds_since(critical_start);
  }
  for (std::size_t k = 0; k < taus.size(); ++k) {
    if (options.progress) options.progress("slice " + std::to_string(k + 1) + " of " + std::to_string(taus.size()));
    impl->slices.push_back(impl->make_slice(taus[k], false));
  }
  // isolate changes by bisection (not needed with exact critical values)
  for (unsigned step_count = 0; step_count < (impl->critical_exact ? 0u : options.refine_steps); ++step_count) {
    std::vector<PinSlotSlice> refined;
    bool any = false;
    for (std::size_t k = 0; k < impl->slices.size(); ++k) {
      refined.push_back(impl->slices[k]);
      if (k + 1 == impl->slices.size()) break;
      if (Impl::signature(impl->slices[k]) == Impl::signature(impl->slices[k + 1])) continue;
      Rational mid = (impl->slices[k].tau + impl->slices[k + 1].tau) / 2;
      mid.canonicalize();
      if (options.progress) options.progress("isolating a change, step " + std::to_string(step_count + 1));
      refined.push_back(impl->make_slice(mid, true));
      any = true;
    }
    impl->slices = std::move(refined);
    if (!any) break;
  }
  for (std::size_t k = 0; k + 1 < impl->slices.size(); ++k) {
    const auto& p = impl->slices[k];
    const auto& q = impl->slices[k + 1];
    if (Impl::signature(p) == Impl::signature(q)) continue;
    std::string what = p.free_cells.size() != q.free_cells.size()
                           ? "free cells " + std::to_string(p.free_cells.size()) + " -> " + std::to_string(q.free_cells.size())
                           : "contacts of the free cells differ";
    impl->changes.push_back(PinSlotChange{k, what});
  }
  // connections and groups
  auto connections_start = Clock::now();
  impl->witness_filter = options.witness_filter;
  if (options.connections && impl->slices.size() >= 2) {
    std::size_t gaps = impl->slices.size() - 1 + (impl->whole_turn ? 1 : 0);
    for (std::size_t k = 0; k + 1 < impl->slices.size(); ++k) {
      if (options.progress) options.progress("connections " + std::to_string(k + 1) + " of " + std::to_string(gaps));
      impl->connect(k, k + 1, false, options.plane_witnesses);
    }
    if (impl->whole_turn) impl->connect(impl->slices.size() - 1, 0, true, false);
  }
  impl->stats.seconds_connections = seconds_since(connections_start);
  std::vector<std::size_t> offset;
  std::size_t total = 0;
  for (const auto& s : impl->slices) offset.push_back(total), total += s.free_cells.size();
  UnionFind uf;
  uf.parent.resize(total);
  for (std::size_t i = 0; i < total; ++i) uf.parent[i] = i;
  for (const auto& c : impl->connections) {
    std::size_t upper = c.lower + 1 == impl->slices.size() ? 0 : c.lower + 1;
    uf.unite(offset[c.lower] + c.lower_cell, offset[upper] + c.upper_cell);
  }
  std::map<std::size_t, std::size_t> group_of;
  for (std::size_t k = 0; k < impl->slices.size(); ++k)
    for (std::size_t c = 0; c < impl->slices[k].free_cells.size(); ++c) {
      std::size_t root = uf.find(offset[k] + c);
      auto [it, inserted] = group_of.emplace(root, group_of.size());
      impl->slices[k].free_cells[c].group = it->second;
    }
  impl->group_count = group_of.size();
  impl->stats.seconds_total = seconds_since(start);
  PinSlotSpace space;
  space.impl_ = impl;
  return space;
}

const std::string& PinSlotSpace::other_part() const { return impl_->other_name; }
const std::string& PinSlotSpace::pin_slot_part() const { return impl_->pin_name; }
Motion::Kind PinSlotSpace::other_kind() const { return impl_->other_kind; }
int PinSlotSpace::dimension() const { return impl_->other_kind == Motion::Kind::fixed ? 2 : 3; }
const Rational& PinSlotSpace::tau_lower() const { return impl_->tau_lo; }
const Rational& PinSlotSpace::tau_upper() const { return impl_->tau_hi; }
long PinSlotSpace::length_unit_exponent() const { return impl_->length_unit_exponent; }
std::shared_ptr<const CSpace> PinSlotSpace::slice(const Rational& tau) const {
  Rational t = tau;
  t.canonicalize();
  return impl_->slice(t);
}
const std::vector<PinSlotSlice>& PinSlotSpace::slices() const { return impl_->slices; }
const std::vector<PinSlotConnection>& PinSlotSpace::connections() const { return impl_->connections; }
const std::vector<PinSlotChange>& PinSlotSpace::changes() const { return impl_->changes; }
std::size_t PinSlotSpace::groups() const { return impl_->group_count; }
bool PinSlotSpace::critical_values_exact() const { return impl_->critical_exact; }
const std::vector<PinSlotCritical>& PinSlotSpace::critical_values() const { return impl_->critical; }
const PinSlotStatistics& PinSlotSpace::statistics() const { return impl_->stats; }

namespace {

using Impl = PinSlotSpace::Impl;

PinSlotLocation locate_in_stack(const Impl& impl, const PinSlotConfiguration& q) {
  Rational tau = q.tau;
  tau.canonicalize();
  // outside the angle limits (modulo whole turns; the limits themselves are inside): psi =
  // 2 atan(tau) against the rational limits, decided exactly (core/angle_limits.hpp; before
  // session 53 a double atan with a 1e-12 margin, refusing configurations within it)
  if (impl.pin().motion.angle_limits && !impl.whole_turn &&
      !angle_within_limits(tau, impl.pin().motion.angle_limits->lo, impl.pin().motion.angle_limits->hi))
    return PinSlotLocation{};
  auto space = impl.slice(tau);
  PinSlotLocation out;
  out.in_slice = impl.locate_in(*space, q.other, q.slide);
  out.kind = Impl::kind_of(*space, out.in_slice);
  for (std::size_t k = 0; k < impl.slices.size(); ++k)
    if (impl.slices[k].tau == tau) {
      out.slice = k;
      if (out.kind == PinSlotLocation::Kind::free && out.in_slice.kind == Location::Kind::free)
        for (std::size_t c = 0; c < impl.slices[k].free_cells.size(); ++c)
          if (impl.slices[k].free_cells[c].slice_cell == out.in_slice.cell) out.cell = c;
    }
  return out;
}

// The stack cell (slice, free cell) a free configuration is joined to: its own when tau is a
// slice's, else through a witnessed segment (constant other and s) to the nearest slice below
// or above. nullopt when the configuration is not free or no such segment is certified.
std::optional<std::pair<std::size_t, std::size_t>> attach(const Impl& impl, const PinSlotConfiguration& q) {
  PinSlotLocation at = locate_in_stack(impl, q);
  if (at.kind != PinSlotLocation::Kind::free) return std::nullopt;
  if (at.cell != no_index) return std::make_pair(at.slice, at.cell);
  Rational tau = q.tau;
  tau.canonicalize();
  std::size_t above = 0;
  while (above < impl.slices.size() && impl.slices[above].tau < tau) ++above;
  for (std::size_t k : {above, above - 1}) {
    if (k >= impl.slices.size()) continue;
    const PinSlotSlice& s = impl.slices[k];
    PinSlotLocation there = locate_in_stack(impl, PinSlotConfiguration{q.other, q.slide, s.tau});
    if (there.cell == no_index) continue;
    bool ok = k == above ? impl.segment_free(q.other, q.slide, tau, s.tau, false)
                         : impl.segment_free(q.other, q.slide, s.tau, tau, false);
    if (ok) return std::make_pair(k, there.cell);
  }
  return std::nullopt;
}

bool same_coordinate(const PartCoordinate& a, const PartCoordinate& b) {
  if (a.kind != b.kind) return false;
  return a.kind == PartCoordinate::Kind::half_turn || a.value == b.value;
}

bool same_configuration(const PinSlotConfiguration& a, const PinSlotConfiguration& b) {
  return same_coordinate(a.other, b.other) && a.slide == b.slide && a.tau == b.tau;
}

PinSlotConfiguration canonical(PinSlotConfiguration q) {
  q.other.value.canonicalize();
  q.slide.canonicalize();
  q.tau.canonicalize();
  return q;
}

// The motion certificate (PinSlotSpace::motion_free); errors of the exact spaces built for it
// (a motion leaving a built box) leave the motion uncertified.
bool certify_motion(const Impl& impl, const PinSlotConfiguration& a0, const PinSlotConfiguration& b0, bool wrap) {
  const PinSlotConfiguration a = canonical(a0), b = canonical(b0);
  if (impl.other_kind == Motion::Kind::fixed) {
    if (!same_coordinate(a.other, b.other)) return false;
  }
  try {
    if (locate_in_stack(impl, a).kind != PinSlotLocation::Kind::free ||
        locate_in_stack(impl, b).kind != PinSlotLocation::Kind::free)
      return false;
    if (wrap) {   // across psi = pi: tau from a > 0 up through infinity to b < 0 (or back)
      if (!impl.whole_turn || !same_coordinate(a.other, b.other) || a.slide != b.slide) return false;
      if (sgn(a.tau) > 0 && sgn(b.tau) < 0) return impl.segment_free(a.other, a.slide, a.tau, b.tau, true);
      if (sgn(a.tau) < 0 && sgn(b.tau) > 0) return impl.segment_free(a.other, a.slide, b.tau, a.tau, true);
      return false;
    }
    if (same_configuration(a, b)) return true;
    if (same_coordinate(a.other, b.other) && a.slide == b.slide) {   // a turn of the pin-slot part
      return a.tau < b.tau ? impl.segment_free(a.other, a.slide, a.tau, b.tau, false)
                           : impl.segment_free(a.other, a.slide, b.tau, a.tau, false);
    }
    if (a.tau == b.tau) {   // in the slice
      if (a.other.kind == PartCoordinate::Kind::half_turn || b.other.kind == PartCoordinate::Kind::half_turn)
        return false;
      auto space = impl.slice(a.tau);
      MotionPath path;
      if (space->dimension() == 1) {
        path.x.kind = AxisPath::Kind::offset;
        path.x.coefficients = {a.slide, Rational(b.slide - a.slide)};
      } else {
        path.x.kind = impl.other_kind == Motion::Kind::translation ? AxisPath::Kind::offset : AxisPath::Kind::half_tangent;
        path.x.coefficients = {a.other.value, Rational(b.other.value - a.other.value)};
        path.y.kind = AxisPath::Kind::offset;
        path.y.coefficients = {a.slide, Rational(b.slide - a.slide)};
      }
      return space->first_crossing(path).status == CrossingStatus::none;
    }
    if (a.slide == b.slide && impl.other_kind != Motion::Kind::fixed)   // a plane witness's motion
      return impl.plane_free(a.other, b.other, a.slide, a.tau, b.tau);
  } catch (const Error&) {
    return false;
  }
  return false;
}

// Moves inside free cell `cell` of slice `k` (located exactly: both ends lie in it) from `from`
// to `to`, appended to `out` (without `from`): a straight motion, else a lazy shortest path over
// points of the cell on the exact 1-D slices through the points found so far (axis-parallel
// lines; a few rounds). The doubles only rank candidate motions; each is certified.
class CellPlanner {
 public:
  CellPlanner(const Impl& impl, PinSlotPath& out) : impl_(impl), out_(out) {}

  bool motion(const PinSlotConfiguration& a, const PinSlotConfiguration& b, bool wrap = false) {
    ++out_.motions_checked;
    return certify_motion(impl_, a, b, wrap);
  }
  void append(const PinSlotConfiguration& q, bool wrap = false) {
    out_.waypoints.push_back(q);
    out_.through_half_turn.push_back(wrap);
  }

  bool within(std::size_t k, std::size_t cell, const PinSlotConfiguration& from, const PinSlotConfiguration& to) {
    if (same_configuration(from, to)) return true;
    if (motion(from, to)) {
      append(to);
      return true;
    }
    auto space = impl_.slice(impl_.slices[k].tau);
    if (space->dimension() == 1) return false;   // an interval is convex: the straight motion is the path
    if (decomposed(k, cell, from, to)) return true;
    // (the sampled roadmap of session 68: what the decomposition did not join)
    const std::size_t slice_cell = impl_.slices[k].free_cells[cell].slice_cell;
    const Rational& tau = impl_.slices[k].tau;
    std::vector<PinSlotConfiguration> nodes{from, to};
    const PinSlotCell& c = impl_.slices[k].free_cells[cell];
    nodes.push_back(PinSlotConfiguration{c.sample_other, c.sample_slide, tau});
    const std::size_t max_nodes = 240;
    // vertical lines through the strips between the abscissae of the cell's boundary vertices
    // (at 1/8, 1/2 and 7/8 of each strip: each free interval of a strip's line lies in one
    // trapezoid of the cell's vertical decomposition, the lines near a strip's ends reach
    // across its passages), and the cell's points on them
    std::map<std::size_t, std::set<double>> abscissae;   // by chart
    for (std::size_t e : space->cells()[slice_cell].boundary) {
      const CSpaceEdge& edge = space->edges()[e];
      for (std::size_t v : {edge.source, edge.target})
        if (v != no_index) abscissae[space->vertices()[v].chart].insert(to_double(space->vertices()[v].x.lower));
    }
    for (auto& [chart, xs] : abscissae) {
      const CSpaceChart& box = space->charts()[chart];
      if (box.x_half_turn) continue;
      xs.insert(to_double(box.x_lo));
      xs.insert(to_double(box.x_hi));
      std::vector<double> sorted(xs.begin(), xs.end());
      for (std::size_t i = 0; i + 1 < sorted.size() && nodes.size() < max_nodes; ++i) {
        const double p = std::max(sorted[i], to_double(box.x_lo)), q = std::min(sorted[i + 1], to_double(box.x_hi));
        if (!(q > p)) continue;
        for (double f : {0.125, 0.5, 0.875}) {
          Rational x(p + (q - p) * f);
          x.canonicalize();
          if (!(box.x_lo < x && x < box.x_hi)) continue;
          for (const Slice& line : space->slice(SliceAxis::x, x)) {
            if (line.chart != chart) continue;
            for (const Rational& y : interval_points(line, slice_cell)) {
              PartCoordinate other = impl_.coordinates(*space, chart, x, y).first;
              if (other.kind != PartCoordinate::Kind::half_turn) nodes.push_back(PinSlotConfiguration{other, y, tau});
            }
          }
        }
      }
    }
    std::set<Rational> xs_done, ys_done;
    std::map<std::pair<std::size_t, std::size_t>, bool> known;   // certified motions (true free)
    for (int round = 0; round < 6; ++round) {
      // points of the cell on the lines through the nodes
      std::vector<PinSlotConfiguration> added;
      for (const auto& n : nodes) {
        if (n.other.kind == PartCoordinate::Kind::half_turn) continue;
        if (xs_done.insert(n.other.value).second)
          for (const Slice& line : space->slice(SliceAxis::x, n.other.value)) {
            if (space->charts()[line.chart].x_half_turn) continue;
            for (const Rational& y : interval_points(line, slice_cell)) added.push_back(PinSlotConfiguration{n.other, y, tau});
          }
        if (ys_done.insert(n.slide).second)
          for (const Slice& line : space->slice(SliceAxis::y, n.slide))
            for (const Rational& x : interval_points(line, slice_cell)) {
              PartCoordinate other = impl_.coordinates(*space, line.chart, x, n.slide).first;
              if (other.kind != PartCoordinate::Kind::half_turn) added.push_back(PinSlotConfiguration{other, n.slide, tau});
            }
      }
      for (auto& q : added) {
        if (nodes.size() >= max_nodes) break;
        bool seen = false;
        for (const auto& n : nodes) seen = seen || same_configuration(n, q);
        if (!seen) nodes.push_back(q);
      }
      if (auto route = shortest(nodes, known)) {
        for (std::size_t i = 1; i < route->size(); ++i) append(nodes[(*route)[i]]);
        return true;
      }
    }
    return false;
  }

 private:
  // ---------------------------------------------------------------- vertical decomposition
  // A complete planner inside one free cell of a 2-D slice (session 69). The cell's boundary
  // edges are x-monotone and the abscissae of their end vertices (with the charts' box ends,
  // all in the other part's coordinate: its half-angle tangent or offset) cut the x axis into
  // open strips; inside a strip no boundary vertex lies, so the cell's part there is a union of
  // trapezoids, each bounded below and above by one edge (or a box side), each met by every
  // vertical line of the strip in one interval, in the same order on every line. Inside a
  // trapezoid two points are joined by bisection towards the middle of the trapezoid's
  // intervals (the polyline of middles converges to the trapezoid's mid-curve, which lies
  // inside it: a fine enough one is free). Trapezoids of neighbouring strips are joined across
  // the vertex abscissa between them by a motion at constant y from a line just left of it to
  // a line just right of it (closer and closer), at ordinates inside both intervals. Every
  // motion is certified by certify_motion before it is used; doubles only rank. Gives up (a
  // status) on its motion budget, and for paths that would have to pass the other part's half
  // turn.
  struct Range {
    Rational lo, hi;    // certainly inside the interval: (lo, hi), exact
    double dlo = 0, dhi = 0;
  };
  struct Strip {
    Rational lo, hi;
    bool lo_infinite = false, hi_infinite = false;
  };

  // The cell's intervals on the vertical line at the other part's coordinate x (adjacent
  // intervals of the cell merged), ascending in y.
  const std::vector<Range>& line_ranges(const CSpace& space, std::size_t slice_cell, const Rational& x) {
    auto it = lines_.find(x);
    if (it != lines_.end()) return it->second;
    std::vector<Range> out;
    bool done = false;
    for (std::size_t chart = 0; chart < space.charts().size() && !done; ++chart) {
      const CSpaceChart& box = space.charts()[chart];
      Rational at = x;
      if (box.x_half_turn) {
        if (sgn(x) == 0) continue;
        at = Rational(-1) / x;
        at.canonicalize();
      }
      if (!(box.x_lo < at && at < box.x_hi)) continue;
      for (const Slice& line : space.slice(SliceAxis::x, at)) {
        if (line.chart != chart) continue;
        done = true;
        bool open = false;
        for (std::size_t k = 0; k < line.intervals.size(); ++k) {
          const Slice::Interval& in = line.intervals[k];
          const bool mine = in.cell.valid() && in.cell.index() == slice_cell && in.kind == CellKind::free;
          if (!mine) {
            open = false;
            continue;
          }
          Rational lo = k == 0 ? line.lower : (line.points[k - 1].at.exact ? line.points[k - 1].at.lower : line.points[k - 1].at.upper);
          Rational hi = k + 1 == line.intervals.size() ? line.upper : line.points[k].at.lower;
          if (open && !out.empty()) {
            out.back().hi = hi;
          } else {
            out.push_back(Range{lo, hi});
          }
          open = true;
        }
      }
    }
    for (Range& r : out) r.dlo = to_double(r.lo), r.dhi = to_double(r.hi);
    return lines_.emplace(x, std::move(out)).first->second;
  }

  // A simple rational in the middle part [lo + f (hi - lo), lo + g (hi - lo)].
  static Rational between(const Rational& lo, const Rational& hi, long f_num, long g_num, long den) {
    Rational a = lo + (hi - lo) * Rational(f_num, den), b = lo + (hi - lo) * Rational(g_num, den);
    a.canonicalize();
    b.canonicalize();
    return cspace::algebra::simplest_between(a, b);
  }

  // The strips of the cell's vertical decomposition (see above).
  std::vector<Strip> strips(const CSpace& space, std::size_t slice_cell) {
    std::vector<std::pair<Rational, Rational>> groups;   // isolating intervals of abscissae
    auto add = [&](const Rational& lo, const Rational& hi) { groups.emplace_back(lo, hi); };
    bool rotation = false;
    for (const CSpaceChart& box : space.charts()) {
      rotation = rotation || box.x_kind == AxisKind::rotation;
      for (const Rational& end : {box.x_lo, box.x_hi}) {
        if (!box.x_half_turn) {
          add(end, end);
        } else if (sgn(end) != 0) {
          Rational t = Rational(-1) / end;
          t.canonicalize();
          add(t, t);
        }
      }
    }
    for (std::size_t e : space.cells()[slice_cell].boundary) {
      const CSpaceEdge& edge = space.edges()[e];
      for (std::size_t v : {edge.source, edge.target}) {
        if (v == no_index) continue;
        const CSpaceVertex& vertex = space.vertices()[v];
        const AlgebraicNumber& x = vertex.x;
        Rational lo = x.lower, hi = x.exact ? x.lower : x.upper;
        if (space.charts()[vertex.chart].x_half_turn) {
          if (!(sgn(lo) > 0 || sgn(hi) < 0)) continue;   // at the half turn itself
          Rational a = Rational(-1) / lo, b = Rational(-1) / hi;
          a.canonicalize();
          b.canonicalize();
          lo = a, hi = b;
        }
        add(lo, hi);
      }
    }
    std::sort(groups.begin(), groups.end());
    std::vector<std::pair<Rational, Rational>> merged;
    for (auto& g : groups) {
      if (!merged.empty() && !(merged.back().second < g.first)) {
        if (merged.back().second < g.second) merged.back().second = g.second;
      } else {
        merged.push_back(g);
      }
    }
    std::vector<Strip> out;
    if (merged.empty()) return out;
    if (rotation) out.push_back(Strip{merged.front().first, merged.front().first, true, false});
    for (std::size_t i = 0; i + 1 < merged.size(); ++i) out.push_back(Strip{merged[i].second, merged[i + 1].first});
    if (rotation) out.push_back(Strip{merged.back().second, merged.back().second, false, true});
    return out;
  }

  // A line of strip `s` at 1/e of its width from its right end (`right`) or its left end
  // (infinite strips: at 1/e from the finite end).
  static Rational near_end(const Strip& s, bool right, long e) {
    Rational x = right ? (s.lo_infinite ? Rational(s.hi - Rational(1, e)) : Rational(s.hi - (s.hi - s.lo) / e))
                       : (s.hi_infinite ? Rational(s.lo + Rational(1, e)) : Rational(s.lo + (s.hi - s.lo) / e));
    x.canonicalize();
    return x;
  }

  // The strip holding x strictly inside, or no_index.
  static std::size_t strip_of(const std::vector<Strip>& strips, const Rational& x) {
    for (std::size_t i = 0; i < strips.size(); ++i)
      if ((strips[i].lo_infinite || strips[i].lo < x) && (strips[i].hi_infinite || x < strips[i].hi)) return i;
    return no_index;
  }

  // The range of `ranges` holding y (exactly inside when it can tell, else nearest by doubles).
  static std::size_t range_of(const std::vector<Range>& ranges, const Rational& y) {
    for (std::size_t k = 0; k < ranges.size(); ++k)
      if (ranges[k].lo < y && y < ranges[k].hi) return k;
    const double d = to_double(y);
    std::size_t best = no_index;
    double gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < ranges.size(); ++k) {
      double g = d < ranges[k].dlo ? ranges[k].dlo - d : d > ranges[k].dhi ? d - ranges[k].dhi : 0;
      if (g < gap) gap = g, best = k;
    }
    return best;
  }

  PinSlotConfiguration at(const PartCoordinate& like, const Rational& x, const Rational& y, const Rational& tau) const {
    PartCoordinate other;
    other.kind = like.kind == PartCoordinate::Kind::offset ? PartCoordinate::Kind::offset
                                                           : PartCoordinate::Kind::half_angle_tangent;
    other.value = x;
    return PinSlotConfiguration{other, y, tau};
  }

  // Inside trapezoid k of the strip holding both abscissae: from `p` to `q`, appending to out_.
  bool walk(const CSpace& space, std::size_t slice_cell, const PinSlotConfiguration& p, const PinSlotConfiguration& q,
            std::size_t k, int depth) {
    if (same_configuration(p, q)) return true;
    if (budget_ == 0) return false;
    --budget_;
    if (motion(p, q)) {
      append(q);
      return true;
    }
    if (depth == 0 || p.other.value == q.other.value) return false;
    Rational xm = between(p.other.value < q.other.value ? p.other.value : q.other.value,
                          p.other.value < q.other.value ? q.other.value : p.other.value, 1, 3, 4);
    const std::vector<Range>& ranges = line_ranges(space, slice_cell, xm);
    if (k >= ranges.size()) return false;
    PinSlotConfiguration m = at(p.other, xm, between(ranges[k].lo, ranges[k].hi, 3, 5, 8), p.tau);
    return walk(space, slice_cell, p, m, k, depth - 1) && walk(space, slice_cell, m, q, k, depth - 1);
  }

  // From `from` to `to` in free cell `cell` of slice `k` by the vertical decomposition.
  bool decomposed(std::size_t k, std::size_t cell, const PinSlotConfiguration& from, const PinSlotConfiguration& to) {
    if (from.other.kind == PartCoordinate::Kind::half_turn || to.other.kind == PartCoordinate::Kind::half_turn)
      return false;
    auto space = impl_.slice(impl_.slices[k].tau);
    const std::size_t slice_cell = impl_.slices[k].free_cells[cell].slice_cell;
    const Rational& tau = impl_.slices[k].tau;
    lines_.clear();
    budget_ = 4000;
    const std::vector<Strip> all = strips(*space, slice_cell);
    const std::size_t before = out_.waypoints.size();
    auto undo = [&] {
      out_.waypoints.resize(before);
      out_.through_half_turn.resize(before - 1);
      return false;
    };
    // an end on a strip boundary is first moved at constant y into a strip beside it
    auto into_strip = [&](const PinSlotConfiguration& q, bool is_start, PinSlotConfiguration& moved) -> std::size_t {
      const Rational& x0 = q.other.value;
      std::size_t s = strip_of(all, x0);
      if (s != no_index) {
        moved = q;
        return s;
      }
      std::size_t left = no_index, right = no_index;   // the strips either side of x0's group
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (!all[i].hi_infinite && !(x0 < all[i].hi)) left = i;
        if (right == no_index && !all[i].lo_infinite && !(all[i].lo < x0)) right = i;
      }
      for (long e = 8; e <= (1L << 20); e *= 8)
        for (std::size_t i : {left, right}) {
          if (i == no_index) continue;
          const Strip& strip = all[i];
          const Rational x = near_end(strip, i == left, e);
          PinSlotConfiguration m = at(q.other, x, q.slide, tau);
          if (is_start ? motion(q, m) : motion(m, q)) {
            moved = m;
            return i;
          }
        }
      return no_index;
    };
    PinSlotConfiguration start, goal;
    const std::size_t s0 = into_strip(from, true, start), s1 = into_strip(to, false, goal);
    if (s0 == no_index || s1 == no_index) return false;
    const std::size_t k0 = range_of(line_ranges(*space, slice_cell, start.other.value), start.slide);
    const std::size_t k1 = range_of(line_ranges(*space, slice_cell, goal.other.value), goal.slide);
    if (k0 == no_index || k1 == no_index) return false;
    // crossings between trapezoids of strips i and i + 1: (k, m) -> the motion's ends
    using Node = std::pair<std::size_t, std::size_t>;
    std::map<std::size_t, std::vector<std::tuple<std::size_t, std::size_t, PinSlotConfiguration, PinSlotConfiguration>>> crossings;
    auto crossings_at = [&](std::size_t i) -> const auto& {   // between strips i and i + 1
      auto it = crossings.find(i);
      if (it != crossings.end()) return it->second;
      auto& list = crossings[i];
      const Strip& left = all[i];
      const Strip& right = all[i + 1];
      std::set<std::pair<std::size_t, std::size_t>> joined;
      for (long e = 8; e <= 4096; e *= 8) {
        const Rational xl = near_end(left, true, e), xr = near_end(right, false, e);
        const std::vector<Range> L = line_ranges(*space, slice_cell, xl);
        const std::vector<Range>& R = line_ranges(*space, slice_cell, xr);
        for (std::size_t a = 0; a < L.size(); ++a)
          for (std::size_t b = 0; b < R.size(); ++b) {
            if (joined.count({a, b})) continue;
            Rational lo = L[a].lo < R[b].lo ? R[b].lo : L[a].lo, hi = L[a].hi < R[b].hi ? L[a].hi : R[b].hi;
            if (!(lo < hi)) continue;
            for (auto [f, g] : {std::pair{3L, 5L}, std::pair{1L, 3L}, std::pair{5L, 7L}}) {
              if (budget_ == 0) return list;
              --budget_;
              Rational y = between(lo, hi, f, g, 8);
              PinSlotConfiguration p = at(start.other, xl, y, tau), q = at(start.other, xr, y, tau);
              if (motion(p, q)) {
                joined.insert({a, b});
                list.emplace_back(a, b, p, q);
                break;
              }
            }
          }
      }
      return list;
    };
    // breadth-first over trapezoids (strip, index)
    std::map<Node, std::pair<Node, std::optional<std::pair<PinSlotConfiguration, PinSlotConfiguration>>>> seen;
    std::deque<Node> queue{Node{s0, k0}};
    seen[Node{s0, k0}] = {Node{s0, k0}, std::nullopt};
    const Node target{s1, k1};
    while (!queue.empty() && !seen.count(target)) {
      Node n = queue.front();
      queue.pop_front();
      if (n.first + 1 < all.size())
        for (const auto& [a, b, p, q] : crossings_at(n.first))
          if (a == n.second && !seen.count(Node{n.first + 1, b})) {
            seen[Node{n.first + 1, b}] = {n, std::make_pair(p, q)};
            queue.push_back(Node{n.first + 1, b});
          }
      if (n.first > 0)
        for (const auto& [a, b, p, q] : crossings_at(n.first - 1))
          if (b == n.second && !seen.count(Node{n.first - 1, a})) {
            seen[Node{n.first - 1, a}] = {n, std::make_pair(q, p)};
            queue.push_back(Node{n.first - 1, a});
          }
      if (budget_ == 0) break;
    }
    if (!seen.count(target)) return undo();
    std::vector<std::pair<Node, std::pair<PinSlotConfiguration, PinSlotConfiguration>>> chain;
    for (Node n = target; seen[n].second; n = seen[n].first) chain.emplace_back(seen[n].first, *seen[n].second);
    std::reverse(chain.begin(), chain.end());
    budget_ = 4000;
    if (!same_configuration(from, start)) append(start);
    PinSlotConfiguration current = start;
    for (const auto& [node, ends] : chain) {
      if (!walk(*space, slice_cell, current, ends.first, node.second, 16)) return undo();
      append(ends.second);
      current = ends.second;
    }
    if (!walk(*space, slice_cell, current, goal, k1, 16)) return undo();
    if (!same_configuration(goal, to)) append(to);
    return true;
  }

  std::map<Rational, std::vector<Range>> lines_;
  std::size_t budget_ = 0;

  // Points of the free intervals of `cell` on a line: each interval's sample and the simplest
  // rational of its middle half (its ends bounded by their exact isolating intervals): a sample
  // can lie near an end, a thin channel's middle is where motions along it stay inside.
  static std::vector<Rational> interval_points(const Slice& line, std::size_t cell) {
    std::vector<Rational> out;
    auto above = [](const AlgebraicNumber& a) { return a.exact ? a.lower : a.upper; };
    for (std::size_t k = 0; k < line.intervals.size(); ++k) {
      const Slice::Interval& in = line.intervals[k];
      if (!in.cell.valid() || in.cell.index() != cell || in.kind != CellKind::free) continue;
      out.push_back(in.sample);
      Rational lo = k == 0 ? line.lower : above(line.points[k - 1].at);
      Rational hi = k + 1 == line.intervals.size() ? line.upper : line.points[k].at.lower;
      if (!(lo < hi)) continue;
      Rational quarter = (hi - lo) / 4;
      Rational from = lo + quarter, to = hi - quarter;
      from.canonicalize();
      to.canonicalize();
      Rational middle = cspace::algebra::simplest_between(from, to);
      if (middle != in.sample) out.push_back(middle);
    }
    return out;
  }
  static double coordinate(const PartCoordinate& c) {
    return c.kind == PartCoordinate::Kind::half_turn ? std::numeric_limits<double>::infinity() : to_double(c.value);
  }
  // Lazy shortest path from node 0 to node 1 over the complete graph of `nodes` (Euclidean in
  // the chart coordinates, doubles: a ranking only), certifying the motions on it.
  std::optional<std::vector<std::size_t>> shortest(const std::vector<PinSlotConfiguration>& nodes,
                                                   std::map<std::pair<std::size_t, std::size_t>, bool>& known) {
    const std::size_t n = nodes.size();
    auto length = [&](std::size_t i, std::size_t j) {
      return std::hypot(coordinate(nodes[i].other) - coordinate(nodes[j].other),
                        to_double(nodes[i].slide) - to_double(nodes[j].slide));
    };
    // the k nearest of each node (and the goal from the start), both ways
    const std::size_t k_nearest = 14;
    std::vector<std::set<std::size_t>> neighbours(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::size_t> order;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) order.push_back(j);
      std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return length(i, p) < length(i, q); });
      for (std::size_t j = 0; j < order.size() && j < k_nearest; ++j) {
        neighbours[i].insert(order[j]);
        neighbours[order[j]].insert(i);
      }
    }
    // and the nearest on the same line (the lines' points of one interval see each other)
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::size_t> line;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i && (same_coordinate(nodes[i].other, nodes[j].other) || nodes[i].slide == nodes[j].slide))
          line.push_back(j);
      std::sort(line.begin(), line.end(), [&](std::size_t p, std::size_t q) { return length(i, p) < length(i, q); });
      for (std::size_t j = 0; j < line.size() && j < 4; ++j) {
        neighbours[i].insert(line[j]);
        neighbours[line[j]].insert(i);
      }
    }
    if (n > 1) neighbours[0].insert(1), neighbours[1].insert(0);
    for (int attempt = 0; attempt < 400; ++attempt) {
      std::vector<double> dist(n, std::numeric_limits<double>::infinity());
      std::vector<std::size_t> previous(n, no_index);
      std::vector<bool> done(n, false);
      dist[0] = 0;
      for (;;) {
        std::size_t u = no_index;
        for (std::size_t i = 0; i < n; ++i)
          if (!done[i] && std::isfinite(dist[i]) && (u == no_index || dist[i] < dist[u])) u = i;
        if (u == no_index || u == 1) break;
        done[u] = true;
        for (std::size_t v : neighbours[u]) {
          if (done[v]) continue;
          auto it = known.find({std::min(u, v), std::max(u, v)});
          if (it != known.end() && !it->second) continue;
          double d = dist[u] + length(u, v);
          if (d < dist[v]) dist[v] = d, previous[v] = u;
        }
      }
      if (!std::isfinite(dist[1])) return std::nullopt;
      std::vector<std::size_t> route;
      for (std::size_t v = 1; v != no_index; v = previous[v]) route.push_back(v);
      std::reverse(route.begin(), route.end());
      bool all = true;
      for (std::size_t i = 0; i + 1 < route.size(); ++i) {
        auto key = std::make_pair(std::min(route[i], route[i + 1]), std::max(route[i], route[i + 1]));
        auto it = known.find(key);
        if (it == known.end()) it = known.emplace(key, motion(nodes[route[i]], nodes[route[i + 1]])).first;
        if (!it->second) {
          all = false;
          break;
        }
      }
      if (all) return route;
    }
    return std::nullopt;
  }

  const Impl& impl_;
  PinSlotPath& out_;
};

}  // namespace

PinSlotLocation PinSlotSpace::locate(const PinSlotConfiguration& q) const { return locate_in_stack(*impl_, q); }

bool PinSlotSpace::certainly_connected(const PinSlotConfiguration& a, const PinSlotConfiguration& b) const {
  auto na = attach(*impl_, a), nb = attach(*impl_, b);
  if (!na || !nb) return false;
  return impl_->slices[na->first].free_cells[na->second].group == impl_->slices[nb->first].free_cells[nb->second].group;
}

bool PinSlotSpace::motion_free(const PinSlotConfiguration& a, const PinSlotConfiguration& b, bool through_half_turn) const {
  return certify_motion(*impl_, a, b, through_half_turn);
}

std::string_view to_string(PinSlotPath::Status status) {
  switch (status) {
    case PinSlotPath::Status::found: return "found";
    case PinSlotPath::Status::not_free: return "not_free";
    case PinSlotPath::Status::not_shown_connected: return "not_shown_connected";
    case PinSlotPath::Status::not_found: return "not_found";
  }
  return "?";
}

PinSlotPath PinSlotSpace::path(const PinSlotConfiguration& a0, const PinSlotConfiguration& b0) const {
  const Impl& impl = *impl_;
  const PinSlotConfiguration a = canonical(a0), b = canonical(b0);
  PinSlotPath out;
  if (locate(a).kind != PinSlotLocation::Kind::free || locate(b).kind != PinSlotLocation::Kind::free) return out;
  auto na = attach(impl, a), nb = attach(impl, b);
  out.status = PinSlotPath::Status::not_shown_connected;
  if (!na || !nb) return out;
  if (impl.slices[na->first].free_cells[na->second].group != impl.slices[nb->first].free_cells[nb->second].group)
    return out;
  out.status = PinSlotPath::Status::not_found;
  // the cell graph: nodes (slice, free cell), edges the connections (either way)
  using Node = std::pair<std::size_t, std::size_t>;
  struct Step {
    Node previous;
    const PinSlotConnection* connection = nullptr;
    bool upwards = true;
  };
  auto upper_of = [&](const PinSlotConnection& c) { return c.lower + 1 == impl.slices.size() ? std::size_t{0} : c.lower + 1; };
  std::map<Node, Step> seen;
  std::deque<Node> queue{*na};
  seen[*na] = Step{*na, nullptr, true};
  while (!queue.empty()) {
    Node node = queue.front();
    queue.pop_front();
    if (node == *nb) break;
    for (const auto& c : impl.connections) {
      Node lower{c.lower, c.lower_cell}, upper{upper_of(c), c.upper_cell};
      for (bool upwards : {true, false}) {
        const Node& here = upwards ? lower : upper;
        const Node& there = upwards ? upper : lower;
        if (here != node || seen.count(there)) continue;
        seen[there] = Step{node, &c, upwards};
        queue.push_back(there);
      }
    }
  }
  if (!seen.count(*nb)) return out;   // (the groups agreed: should not happen)
  std::vector<std::pair<Node, Step>> chain;
  for (Node n = *nb; seen[n].connection; n = seen[n].previous) chain.emplace_back(n, seen[n]);
  std::reverse(chain.begin(), chain.end());
  CellPlanner planner(impl, out);
  out.waypoints.push_back(a);
  PinSlotConfiguration current = a;
  auto go = [&](const PinSlotConfiguration& to, bool wrap) {
    if (!wrap && same_configuration(current, to)) return true;
    if (!planner.motion(current, to, wrap)) return false;
    planner.append(to, wrap);
    current = to;
    return true;
  };
  // onto the start's slice
  Node node = *na;
  if (!go(PinSlotConfiguration{a.other, a.slide, impl.slices[node.first].tau}, false)) return out;
  for (const auto& [next, step] : chain) {
    const PinSlotConnection& c = *step.connection;
    const Rational& lower_tau = impl.slices[c.lower].tau;
    const Rational& upper_tau = impl.slices[upper_of(c)].tau;
    PinSlotConfiguration at_lower{c.witness_other, c.witness_slide, lower_tau};
    PinSlotConfiguration at_upper{c.witness_other_upper, c.witness_slide, upper_tau};
    const PinSlotConfiguration& enter = step.upwards ? at_lower : at_upper;
    const PinSlotConfiguration& leave = step.upwards ? at_upper : at_lower;
    const bool wrap = upper_of(c) == 0;
    if (!planner.within(node.first, node.second, current, enter)) return out;
    current = out.waypoints.back();
    if (!go(leave, wrap)) return out;
    node = next;
  }
  PinSlotConfiguration landing{b.other, b.slide, impl.slices[node.first].tau};
  if (!planner.within(node.first, node.second, current, landing)) return out;
  current = out.waypoints.back();
  if (!go(b, false)) return out;
  // consecutive in-slice motions along one line, the same way, joined: their union is the
  // joined segment, certified free throughout by the two certificates (exact: collinear by the
  // cross product, the same way by the dot product)
  std::vector<PinSlotConfiguration> joined{out.waypoints.front()};
  std::vector<bool> wraps;
  for (std::size_t j = 1; j < out.waypoints.size(); ++j) {
    const PinSlotConfiguration& q = out.waypoints[j];
    const bool wrap = out.through_half_turn[j - 1];
    if (joined.size() >= 2 && !wrap && !wraps.back()) {
      const PinSlotConfiguration& p = joined[joined.size() - 2];
      const PinSlotConfiguration& m = joined.back();
      const bool rotation_or_offset = p.other.kind != PartCoordinate::Kind::half_turn &&
                                      m.other.kind != PartCoordinate::Kind::half_turn &&
                                      q.other.kind != PartCoordinate::Kind::half_turn;
      if (rotation_or_offset && p.tau == m.tau && m.tau == q.tau) {
        const Rational ux = m.other.value - p.other.value, uy = m.slide - p.slide;
        const Rational vx = q.other.value - m.other.value, vy = q.slide - m.slide;
        if (ux * vy - uy * vx == 0 && ux * vx + uy * vy > 0) {
          joined.back() = q;
          continue;
        }
      }
    }
    joined.push_back(q);
    wraps.push_back(wrap);
  }
  out.waypoints = std::move(joined);
  out.through_half_turn = std::move(wraps);
  out.status = PinSlotPath::Status::found;
  return out;
}

}  // namespace hipair
