// Pair axes, chart layout and contact-curve generation for fixed-axis pairs.
#include "curves/contact_curves.hpp"
#include "curves/formed_store.hpp"
#include "curves/half_turn_memo.hpp"

#include "oracle/blocked_tester.hpp"
#include "oracle/overlap.hpp"
#include "core/angle_sign.hpp"
#include "algebra/near_quotient.hpp"
#include "algebra/polynomial.hpp"
#include "curves/pair_sort.hpp"
#include "curves/pose.hpp"
#include "curves/squared_distance.hpp"
#include "curves/swept_box_memo.hpp"
#include "kernels/contact.hpp"
#include "kernels/contact_table.hpp"
#include "kernels/interval.hpp"
#include "algebra/small_integers.hpp"

#include <hipair/error.hpp>

#include <mpfi.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <optional>
#include <unordered_map>

namespace hipair::cspace {

// ============================================================================ pair axes

PairAxes pair_axes(const Model& model, std::size_t first, std::size_t second) {
  if (first >= model.parts.size() || second >= model.parts.size())
    throw GeometryError("pair refers to a part that does not exist");
  if (first == second) throw GeometryError("a part cannot be paired with itself");
  const Part& a = model.parts[first];
  const Part& b = model.parts[second];
  for (const Part* part : {&a, &b}) {
    if (motion_degrees_of_freedom(part->motion) > 1)
      throw GeometryError("part '" + part->name +
                          "' moves with more than one degree of freedom; its pair is not a "
                          "fixed-axis pair");
  }
  PairAxes axes;
  axes.first = first;
  axes.second = second;
  axes.first_moves = motion_degrees_of_freedom(a.motion) == 1;
  axes.second_moves = motion_degrees_of_freedom(b.motion) == 1;
  if (!axes.first_moves && !axes.second_moves)
    throw GeometryError("parts '" + a.name + "' and '" + b.name +
                        "' are both fixed: their pair has no configuration space");
  return axes;
}

double chart_to_coordinate(const ChartAxis& axis, double chart_value) {
  if (axis.kind == ChartAxis::Kind::translation) return chart_value;
  return (axis.half_turn ? std::numbers::pi : 0.0) + 2.0 * std::atan(chart_value);
}

namespace {

using kernels::Interval;

// ============================================================================ certified ranges

Interval root_of(const Rational& value) { return kernels::sqrt(algebra::enclose_kernel(value)); }

Rational squared_length(const Point& v) { return dot(v, v); }

// Certified [lo, hi] of the distances from `center` to the points of a feature.
Interval radial_range(const BodyFeature& feature, const Point& center) {
  const Edge& edge = *feature.edge;
  if (feature.ref.kind == FeatureRef::Kind::vertex)
    return root_of(squared_length(difference(feature.point(), center)));
  Interval source = root_of(squared_length(difference(edge.source, center)));
  Interval target = root_of(squared_length(difference(edge.target, center)));
  if (feature.ref.kind == FeatureRef::Kind::segment) {
    Point d = difference(edge.target, edge.source);
    Point from_source = difference(center, edge.source);
    Rational along = dot(from_source, d);
    Rational length2 = squared_length(d);
    Interval near = source.lo <= target.lo ? source : target;
    if (sgn(along) > 0 && along < length2) {
      Rational c = cross(d, from_source);
      near = root_of(Rational(c * c / length2));
    }
    return Interval(near.lo, std::max(source.hi, target.hi));
  }
  // Arc: extreme distances are at the points on the line through centre and arc centre when
  // they lie on the arc, else at the endpoints.
  kernels::ArcSector<Rational> sector = arc_sector(edge);
  Interval radius = root_of(edge.radius_squared);
  Point away = difference(edge.center, center);
  Rational distance2 = squared_length(away);
  if (sgn(distance2) == 0) return radius;
  Interval distance = root_of(distance2);
  double far = std::max(source.hi, target.hi);
  if (sector_contains(sector, away)) far = (distance + radius).hi;
  double near = std::min(source.lo, target.lo);
  if (sector_contains(sector, Point{Rational(-away.x), Rational(-away.y)})) {
    Interval gap = distance - radius;
    near = std::max({0.0, gap.lo, (-gap).lo});
  }
  return Interval(near, far);
}

}  // namespace

// Enclosure of u . p. For the axis directions (1, 0) and (0, 1) (every translating pair along
// the axes, and every feature's box) u . p is the coordinate itself: the same rational, without
// two products, a sum and their canonicalisations (the generator's construction spent 40 % of
// its time here on polygon pairs).
// The negated axes (the normal (-1, 0) of a translation along (0, 1)) take the negated
// enclosure: Interval::enclose truncates toward zero and widens away from it by one ulp, both
// symmetric under negation, so enclose(-q) is exactly -enclose(q) (enclose_dot_axis_fast_path
// in the tests compares the two).
Interval enclose_dot(const Point& unit, const Point& p) {
  if (sgn(unit.y) == 0) {
    if (unit.x == 1) return algebra::enclose_kernel(p.x);
    if (unit.x == -1) return -algebra::enclose_kernel(p.x);
  } else if (sgn(unit.x) == 0) {
    if (unit.y == 1) return algebra::enclose_kernel(p.y);
    if (unit.y == -1) return -algebra::enclose_kernel(p.y);
  }
  return algebra::enclose_kernel(dot(unit, p));
}

Interval projection_range(const BodyFeature& feature, const Point& unit) {
  const Edge& edge = *feature.edge;
  if (feature.ref.kind == FeatureRef::Kind::vertex) return enclose_dot(unit, feature.point());
  Interval range = kernels::hull(enclose_dot(unit, edge.source), enclose_dot(unit, edge.target));
  if (feature.ref.kind == FeatureRef::Kind::segment) return range;
  kernels::ArcSector<Rational> sector = arc_sector(edge);
  Interval centre = algebra::enclose_kernel(dot(unit, edge.center));
  Interval radius = root_of(edge.radius_squared);
  if (sector_contains(sector, unit)) range.hi = std::max(range.hi, (centre + radius).hi);
  if (sector_contains(sector, Point{Rational(-unit.x), Rational(-unit.y)}))
    range.lo = std::min(range.lo, (centre - radius).lo);
  return range;
}

AxisRanges axis_ranges(const BodyFeature& feature) {
  if (feature.ref.kind == FeatureRef::Kind::arc) throw GeometryError("internal: axis_ranges takes vertices and segments");
  const bool vertex = feature.ref.kind == FeatureRef::Kind::vertex;
  const Point& p = feature.point();   // a vertex, or a segment's start
  AxisRanges ranges{algebra::enclose_kernel(p.x), algebra::enclose_kernel(p.y)};
  if (!vertex) {
    ranges.x = kernels::hull(ranges.x, algebra::enclose_kernel(feature.edge->target.x));
    ranges.y = kernels::hull(ranges.y, algebra::enclose_kernel(feature.edge->target.y));
  }
  return ranges;
}

Interval axis_projection(const AxisRanges& ranges, const Point& unit) {
  if (sgn(unit.y) == 0 && unit.x == 1) return ranges.x;
  if (sgn(unit.y) == 0 && unit.x == -1) return -ranges.x;
  if (sgn(unit.x) == 0 && unit.y == 1) return ranges.y;
  if (sgn(unit.x) == 0 && unit.y == -1) return -ranges.y;
  throw GeometryError("internal: axis_projection takes the units +-(1, 0) and +-(0, 1)");
}

namespace {

bool disjoint(const Interval& a, const Interval& b) { return a.hi < b.lo || b.hi < a.lo; }

// Lower bound of the distance from point o to the box [bx] x [by].
double distance_to_box_lower(const Point& o, const Interval& bx, const Interval& by) {
  Interval ox = algebra::enclose_kernel(o.x);
  Interval oy = algebra::enclose_kernel(o.y);
  double gx = std::max({0.0, (Interval(bx.lo, bx.lo) - ox).lo, (ox - Interval(bx.hi, bx.hi)).lo});
  double gy = std::max({0.0, (Interval(by.lo, by.lo) - oy).lo, (oy - Interval(by.hi, by.hi)).lo});
  Interval g2 = Interval(gx, gx) * Interval(gx, gx) + Interval(gy, gy) * Interval(gy, gy);
  return kernels::sqrt(g2).lo;
}

// Upper bound of the largest distance from o to a point of the box.
double distance_to_box_upper(const Point& o, const Interval& bx, const Interval& by) {
  Interval ox = algebra::enclose_kernel(o.x);
  Interval oy = algebra::enclose_kernel(o.y);
  double gx = std::max((ox - Interval(bx.lo, bx.lo)).hi, (Interval(bx.hi, bx.hi) - ox).hi);
  double gy = std::max((oy - Interval(by.lo, by.lo)).hi, (Interval(by.hi, by.hi) - oy).hi);
  Interval g2 = Interval(gx, gx) * Interval(gx, gx) + Interval(gy, gy) * Interval(gy, gy);
  return kernels::sqrt(g2).hi;
}

// ============================================================================ culling

// Where a feature can be: the quantities the swept-region tests need.
struct SweptFeature {
  Interval radial[2];   // distances from the first / second part's pivot (when it rotates)
  Interval normal[2];   // projection on the first / second part's translation normal
  Interval box_x;       // swept bounding box (static one for parts that do not translate)
  Interval box_y;
};

enum class MotionKind { fixed, rotation, translation };

// The pivot and the direction are the part's own (the part outlives every culler: no copy);
// only a translation's normal is made (a fixed part's motion constructs no rational).
struct PartMotion {
  MotionKind kind = MotionKind::fixed;
  const Point* pivot_of = nullptr;       // a rotation's
  const Point* direction_of = nullptr;   // a translation's
  std::optional<Point> normal_of;        // a translation's: the direction turned by +90 degrees
  const Point& pivot() const { return *pivot_of; }
  const Point& direction() const { return *direction_of; }
  const Point& normal() const { return *normal_of; }
};

PartMotion part_motion(const Part& part, bool moves) {
  PartMotion motion;
  if (!moves) return motion;
  if (part.motion.kind == Motion::Kind::rotation) {
    motion.kind = MotionKind::rotation;
    motion.pivot_of = &part.motion.pivot;
  } else {
    motion.kind = MotionKind::translation;
    motion.direction_of = &part.motion.direction;
    motion.normal_of.emplace(Point{Rational(-part.motion.direction.y), part.motion.direction.x});
  }
  return motion;
}

class Culler {
 public:
  // The two parts' motions (part_motion) built in place: no PartMotion (eight rationals) copied.
  Culler(const Part& first_part, bool first_moves, const ChartAxis& first_axis, const Part& second_part,
         bool second_moves, const ChartAxis& second_axis)
      : motion_{part_motion(first_part, first_moves), part_motion(second_part, second_moves)} {
    const PartMotion& first = motion_[0];
    const PartMotion& second = motion_[1];
    travel_ = travel_over(first_axis, second_axis);
    auto on_axis = [](const Point& u) {
      return (sgn(u.y) == 0 && (u.x == 1 || u.x == -1)) || (sgn(u.x) == 0 && (u.y == 1 || u.y == -1));
    };
    axis_normals_ = first.kind != MotionKind::rotation && second.kind != MotionKind::rotation &&
                    (first.kind != MotionKind::translation || on_axis(first.normal())) &&
                    (second.kind != MotionKind::translation || on_axis(second.normal()));
    if (first.kind == MotionKind::rotation && second.kind == MotionKind::rotation) {
      Rational d2 = squared_length(difference(first.pivot(), second.pivot()));
      same_pivot_ = sgn(d2) == 0;
      pivot_distance_ = root_of(d2);
    }
    if (first.kind == MotionKind::translation && second.kind == MotionKind::translation)
      parallel_ = sgn(cross(first.direction(), second.direction())) == 0;
  }

  /// A translating part's travel over a chart box, the same for each of its features: side 0
  /// over `first_axis`, side 1 over `second_axis` (zero for a part that does not translate).
  /// Only this depends on the chart box; the rest of a Culler depends on the parts' motions.
  struct Travel {
    Interval x[2], y[2];
  };
  Travel travel_over(const ChartAxis& first_axis, const ChartAxis& second_axis) const {
    Travel travel;
    thread_local Rational x1, x2, y1, y2;   // scratch (assigned before every read)
    for (int side = 0; side < 2; ++side) {
      const PartMotion& own = motion_[side];
      if (own.kind != MotionKind::translation) continue;
      const ChartAxis& axis = side == 0 ? first_axis : second_axis;
      mpq_mul(x1.get_mpq_t(), axis.lo.get_mpq_t(), own.direction().x.get_mpq_t());
      mpq_mul(x2.get_mpq_t(), axis.hi.get_mpq_t(), own.direction().x.get_mpq_t());
      mpq_mul(y1.get_mpq_t(), axis.lo.get_mpq_t(), own.direction().y.get_mpq_t());
      mpq_mul(y2.get_mpq_t(), axis.hi.get_mpq_t(), own.direction().y.get_mpq_t());
      travel.x[side] = kernels::hull(algebra::enclose_kernel(x1), algebra::enclose_kernel(x2));
      travel.y[side] = kernels::hull(algebra::enclose_kernel(y1), algebra::enclose_kernel(y2));
    }
    return travel;
  }

  SweptFeature describe(const BodyFeature& feature, int side) const {
    return travel(describe_static(feature), side);
  }

  /// The part of describe() that does not depend on the chart box (radial and normal ranges,
  /// the feature's static box).
  SweptFeature describe_static(const BodyFeature& feature) const {
    SweptFeature swept;
    if (axis_normals_ && feature.ref.kind != FeatureRef::Kind::arc) {
      // every projection on an axis: each point's two enclosures once (axis_ranges), the same
      // intervals as projection_range
      const AxisRanges ranges = axis_ranges(feature);
      for (int k = 0; k < 2; ++k)
        if (motion_[k].kind == MotionKind::translation) swept.normal[k] = axis_projection(ranges, motion_[k].normal());
      swept.box_x = ranges.x;
      swept.box_y = ranges.y;
      return swept;
    }
    for (int k = 0; k < 2; ++k) {
      if (motion_[k].kind == MotionKind::rotation)
        swept.radial[k] = radial_range(feature, motion_[k].pivot());
      if (motion_[k].kind == MotionKind::translation)
        swept.normal[k] = projection_range(feature, motion_[k].normal());
    }
    swept.box_x = projection_range(feature, Point{Rational(1), Rational(0)});
    swept.box_y = projection_range(feature, Point{Rational(0), Rational(1)});
    return swept;
  }

  /// Adds a translating part's travel over the chart box to a static description.
  SweptFeature travel(SweptFeature swept, int side) const { return travel(std::move(swept), side, travel_); }
  /// The same over the chart box of `over` (travel_over).
  SweptFeature travel(SweptFeature swept, int side, const Travel& over) const {
    if (motion_[side].kind == MotionKind::translation) {
      swept.box_x = swept.box_x + over.x[side];
      swept.box_y = swept.box_y + over.y[side];
    }
    return swept;
  }

  /// True when the two features can never touch (certified).
  bool never_touch(const SweptFeature& a, const SweptFeature& b) const {
    MotionKind ka = motion_[0].kind;
    MotionKind kb = motion_[1].kind;
    using M = MotionKind;
    if (ka == M::rotation && kb == M::rotation) return annuli_disjoint(a.radial[0], b.radial[1]);
    if (ka == M::rotation && kb == M::fixed) return disjoint(a.radial[0], b.radial[0]);
    if (ka == M::fixed && kb == M::rotation) return disjoint(a.radial[1], b.radial[1]);
    if (ka == M::rotation && kb == M::translation) return disk_misses_strip(a, 0, b, 1);
    if (ka == M::translation && kb == M::rotation) return disk_misses_strip(b, 1, a, 0);
    bool boxes = disjoint(a.box_x, b.box_x) || disjoint(a.box_y, b.box_y);
    if (ka == M::translation && kb == M::translation)
      return boxes || (parallel_ && disjoint(a.normal[0], b.normal[0]));
    if (ka == M::translation) return boxes || disjoint(a.normal[0], b.normal[0]);
    if (kb == M::translation) return boxes || disjoint(a.normal[1], b.normal[1]);
    return false;
  }

 private:
  bool annuli_disjoint(const Interval& a, const Interval& b) const {
    if (same_pivot_) return disjoint(a, b);
    if ((Interval(a.hi, a.hi) + Interval(b.hi, b.hi)).hi < pivot_distance_.lo) return true;
    if ((Interval(a.lo, a.lo) - Interval(b.hi, b.hi)).lo > pivot_distance_.hi) return true;
    if ((Interval(b.lo, b.lo) - Interval(a.hi, a.hi)).lo > pivot_distance_.hi) return true;
    return false;
  }

  // Rotating feature `r` (annulus about its pivot) against translating feature `t`.
  bool disk_misses_strip(const SweptFeature& r, int rotating, const SweptFeature& t,
                         int translating) const {
    const Point& pivot = motion_[rotating].pivot();
    double reach = r.radial[rotating].hi;
    Interval centre = algebra::enclose_kernel(dot(motion_[translating].normal(), pivot));
    Interval disk = centre + Interval(-reach, reach);
    if (disjoint(disk, t.normal[translating])) return true;
    if (distance_to_box_lower(pivot, t.box_x, t.box_y) > reach) return true;
    if (distance_to_box_upper(pivot, t.box_x, t.box_y) < r.radial[rotating].lo) return true;
    return false;
  }

  PartMotion motion_[2];
  Travel travel_;                         // the constructor's chart box (travel())
  bool axis_normals_ = false;             // no rotation, every translation normal +-(1, 0) or +-(0, 1)
  bool same_pivot_ = false;
  bool parallel_ = false;
  Interval pivot_distance_;
};

// ============================================================================ blocked space

// A disk inside a part's material (body frame): centre enclosure and a certified lower bound
// of its radius. Two such disks overlapping proves the parts overlap.
struct Core {
  Interval x;
  Interval y;
  double radius = 0;
};

}  // namespace

// (flattened: the interval operations inlined, the same operations in the same order)
[[gnu::flatten]] std::pair<Interval, Interval> rotation_enclosure(bool half_turn, const Interval& t) {
  Interval c, s;
  auto cosine = [](double u) {  // (1 - t^2) / (1 + t^2) from u = t^2, certified
    return (Interval(1) - Interval(u, u)) / (Interval(1) + Interval(u, u));
  };
  auto sine = [](double v) { return (Interval(2) * Interval(v, v)) / (Interval(1) + Interval(v, v) * Interval(v, v)); };
  if (t.lo >= -1 && t.hi <= 1) {
    // (1 - u)/(1 + u) decreases in u = t^2; 2t/(1 + t^2) increases on [-1, 1].
    // Each end's square, cosine and sine is computed once (twice before: the same operations on
    // the same doubles, so the same bounds); a point t (the blocked-space tester's middle poses)
    // shares one square, one sine and, when u_lo = u_hi, one cosine between its two ends.
    const auto same = [](double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); };
    const bool point = same(t.lo, t.hi);
    const Interval lo2 = Interval(t.lo, t.lo) * Interval(t.lo, t.lo);
    const Interval hi2 = point ? lo2 : Interval(t.hi, t.hi) * Interval(t.hi, t.hi);
    double u_lo = (t.lo <= 0 && t.hi >= 0) ? 0.0 : std::min(lo2.lo, hi2.lo);
    double u_hi = std::max(lo2.hi, hi2.hi);
    const Interval c_hi_u = cosine(u_hi);
    c = Interval(c_hi_u.lo, same(u_lo, u_hi) ? c_hi_u.hi : cosine(u_lo).hi);
    const Interval s_lo = sine(t.lo);
    s = Interval(s_lo.lo, point ? s_lo.hi : sine(t.hi).hi);
  } else {
    Interval t2 = t * t;
    c = (Interval(1) - t2) / (Interval(1) + t2);
    s = (Interval(2) * t) / (Interval(1) + t2);
  }
  if (half_turn) {
    c = -c;
    s = -s;
  }
  return {c, s};
}

ClearanceBound::ClearanceBound(const Part& part) {
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      EdgeBox e;
      e.edge = &edge;
      e.sx = algebra::enclose_kernel(edge.source.x);
      e.sy = algebra::enclose_kernel(edge.source.y);
      e.tx = algebra::enclose_kernel(edge.target.x);
      e.ty = algebra::enclose_kernel(edge.target.y);
      if (edge.is_arc()) {
        e.arc = true;
        e.kx = algebra::enclose_kernel(edge.center.x);
        e.ky = algebra::enclose_kernel(edge.center.y);
        e.radius = kernels::sqrt(algebra::enclose_kernel(edge.radius_squared));
        kernels::ArcSector<Rational> sector = arc_sector(edge);
        e.start_x = algebra::enclose_kernel(sector.start.x);
        e.start_y = algebra::enclose_kernel(sector.start.y);
        e.end_x = algebra::enclose_kernel(sector.end.x);
        e.end_y = algebra::enclose_kernel(sector.end.y);
        e.large = sector.large;
        e.full = sector.full;
      } else {
        Interval dx = e.tx - e.sx, dy = e.ty - e.sy;
        e.length = kernels::sqrt(dx * dx + dy * dy);
      }
      edges_.push_back(e);
    }
}

// Certified lower bound of the distance from the box (cx, cy) to each edge, minimised.
// (flattened: the interval operations inlined, the same operations in the same order — a part's
// inscribed disks call it for every candidate against every edge, ≈ 1.4 G instructions of the
// 18×27 gears' analysis, most of them in the out-of-line interval products; session 46)
[[gnu::flatten]] double ClearanceBound::lower(const Interval& cx, const Interval& cy) const {
  auto length = [](const Interval& dx, const Interval& dy) { return kernels::sqrt(dx * dx + dy * dy); };
  double best = std::numeric_limits<double>::infinity();
  for (const EdgeBox& e : edges_) {
    double to_source = length(cx - e.sx, cy - e.sy).lo;
    double to_target = length(cx - e.tx, cy - e.ty).lo;
    double endpoints = std::min(to_source, to_target);
    double bound;
    if (!e.arc) {
      Interval dx = e.tx - e.sx, dy = e.ty - e.sy;
      Interval fx = cx - e.sx, fy = cy - e.sy;
      Interval line = kernels::sqrt((fx * dy - fy * dx) * (fx * dy - fy * dx)) / e.length;
      bound = std::min(endpoints, line.lo);   // the line distance bounds the foot case
    } else {
      Interval gap = length(cx - e.kx, cy - e.ky) - e.radius;
      bound = std::min(endpoints, std::max({0.0, gap.lo, (-gap).lo}));   // circle bounds the in-sector case
    }
    if (!(bound > 0)) return 0;   // NaN or touching: nothing proven
    best = std::min(best, bound);
  }
  return std::isfinite(best) ? best : 0;
}

double ClearanceBound::lower(const Rational& px, const Rational& py) const {
  auto length = [](const Interval& dx, const Interval& dy) { return kernels::sqrt(dx * dx + dy * dy); };
  const Interval cx = algebra::enclose_kernel(px), cy = algebra::enclose_kernel(py);
  const Point p{px, py};
  // sign of an interval, or of the exact value when the interval straddles zero
  auto sign = [](const Interval& value, auto exact) { return value.lo > 0 ? 1 : value.hi < 0 ? -1 : exact(); };
  double best = std::numeric_limits<double>::infinity();
  for (const EdgeBox& e : edges_) {
    const Edge& edge = *e.edge;
    double bound;
    if (!e.arc) {
      Interval dx = e.tx - e.sx, dy = e.ty - e.sy;
      Interval fx = cx - e.sx, fy = cy - e.sy;
      // foot parameter along = (p - s).(t - s), against 0 and |t - s|^2
      Interval along = fx * dx + fy * dy;
      Interval beyond = along - (dx * dx + dy * dy);
      // the exact differences only where an interval straddles 0 (most calls never need them)
      auto f_dot_d = [&] { return dot(difference(p, edge.source), difference(edge.target, edge.source)); };
      int before = sign(along, [&] { return sgn(f_dot_d()); });
      if (before <= 0) {
        bound = length(fx, fy).lo;   // nearest point: the source
      } else if (sign(beyond, [&] {
                   const Point d = difference(edge.target, edge.source);
                   return sgn(Rational(f_dot_d() - dot(d, d)));
                 }) >= 0) {
        bound = length(cx - e.tx, cy - e.ty).lo;   // the target
      } else {
        bound = (kernels::sqrt((fx * dy - fy * dx) * (fx * dy - fy * dx)) / e.length).lo;   // the foot
      }
    } else {
      Interval vx = cx - e.kx, vy = cy - e.ky;
      auto v = [&] { return difference(p, edge.center); };   // exact, only where needed
      bool inside = e.full;
      if (!inside) {
        // cross(start, v) >= 0 and cross(v, end) >= 0 (either, for a large sector)
        int after_start = sign(e.start_x * vy - e.start_y * vx, [&] {
          kernels::ArcSector<Rational> sector = arc_sector(edge);
          return sgn(cross(Point{sector.start.x, sector.start.y}, v()));
        });
        int before_end = sign(vx * e.end_y - vy * e.end_x, [&] {
          kernels::ArcSector<Rational> sector = arc_sector(edge);
          return sgn(cross(v(), Point{sector.end.x, sector.end.y}));
        });
        inside = e.large ? (after_start >= 0 || before_end >= 0) : (after_start >= 0 && before_end >= 0);
      }
      if (inside) {
        Interval gap = length(vx, vy) - e.radius;
        bound = std::max({0.0, gap.lo, (-gap).lo});
        if (!(bound > 0)) {
          // |v| - r = (|v|^2 - r^2) / (|v| + r), the difference of squares exact: the
          // enclosures' difference cancels for a circle of huge radius (an arc whose centre
          // lies 10^20 mm from a part of a few mm: every point of the part is within their
          // rounding of the circle, so no disk of it was certified; session 46)
          const Point d = v();
          Rational power = dot(d, d) - edge.radius_squared;
          if (sgn(power) != 0) bound = std::max(0.0, (algebra::enclose_kernel(abs(power)) / (length(vx, vy) + e.radius)).lo);
        }
      } else {
        bound = std::min(length(cx - e.sx, cy - e.sy).lo, length(cx - e.tx, cy - e.ty).lo);
      }
    }
    if (!(bound > 0)) return 0;   // NaN or touching: nothing proven
    best = std::min(best, bound);
  }
  return std::isfinite(best) ? best : 0;
}

std::optional<CertifiedDisk> certify_disk(const Part& part, const ClearanceBound& bound, const Rational& px,
                                          const Rational& py) {
  Interval cx = algebra::enclose_kernel(px), cy = algebra::enclose_kernel(py);
  double radius = bound.lower(px, py);
  if (!(radius > 0)) return std::nullopt;
  if (locate_point(part, RigidMap{}, Point{px, py}) != PointLocation::inside) return std::nullopt;
  return CertifiedDisk{cx, cy, radius};
}

namespace {

// Inscribed disks of a part: for each edge, points pushed inward from its middle by a few
// scales, kept when strictly inside; radius = certified distance to the whole boundary.
// A function of the part's loops alone (their exact geometry: kinds, points, senses, radii).
std::vector<Core> compute_inscribed_disks(const Part& part) {
  const ClearanceBound clearance(part);
  // the candidates' exact location on the part prepared once (locate_point's answer)
  const PartLocator locator(part);
  std::vector<const Edge*> edges;
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) edges.push_back(&edge);
  std::vector<Core> cores;
  for (const Edge* edge : edges) {
    // Candidates are guessed in doubles in the edge's own frame: origin at its (exact) source,
    // unit 2^k about its size, so that no coordinate over- or underflows at any scale the model
    // format admits (1e-300 mm features, 1e400 mm plates). They are then mapped back exactly and
    // certified (interval distance bound, exact location): the guess decides nothing.
    const Point& origin = edge->source;
    Rational extent = abs(edge->target.x - origin.x) + abs(edge->target.y - origin.y);
    if (edge->is_arc()) extent += abs(edge->center.x - origin.x) + abs(edge->center.y - origin.y);
    if (sgn(extent) == 0) continue;
    const long k = static_cast<long>(mpz_sizeinbase(extent.get_num_mpz_t(), 2)) -
                   static_cast<long>(mpz_sizeinbase(extent.get_den_mpz_t(), 2));
    auto local = [&](const Rational& value, const Rational& base) {
      Rational q = value - base;
      if (k >= 0)
        mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(k));
      else
        mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
      return q.get_d();
    };
    auto global = [&](double value, const Rational& base) {
      Rational q(value);
      if (k >= 0)
        mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(k));
      else
        mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
      return Rational(base + q);
    };
    const double sx = 0, sy = 0;
    const double tx = local(edge->target.x, origin.x), ty = local(edge->target.y, origin.y);
    for (double fraction : {0.25, 0.5, 0.75}) {
      double mx, my, nx, ny, scale;
      if (!edge->is_arc()) {
        mx = sx + fraction * (tx - sx);
        my = sy + fraction * (ty - sy);
        scale = std::hypot(tx - sx, ty - sy);
        nx = -(ty - sy) / scale;
        ny = (tx - sx) / scale;
      } else {
        double kx = local(edge->center.x, origin.x), ky = local(edge->center.y, origin.y);
        double r = std::hypot(kx - sx, ky - sy);   // |centre - source|, in the local unit
        double a0 = std::atan2(sy - ky, sx - kx), a1 = std::atan2(ty - ky, tx - kx);
        if (!edge->ccw) std::swap(a0, a1);
        double span = a1 - a0;
        while (span <= 0) span += 2 * std::numbers::pi;
        double angle = a0 + span * fraction;
        mx = kx + r * std::cos(angle);
        my = ky + r * std::sin(angle);
        nx = edge->ccw ? -std::cos(angle) : std::cos(angle);
        ny = edge->ccw ? -std::sin(angle) : std::sin(angle);
        scale = std::min(2 * r, r * span);
      }
      // The best candidate is the one of largest certified radius among those strictly
      // inside: rank the candidates by radius first (cheap interval work) and locate them
      // exactly in that order (ties keep the step order), stopping at the first inside.
      struct Candidate {
        Rational px, py;
        Core core;
      };
      std::vector<Candidate> candidates;
      candidates.reserve(6);
      for (int depth = 1; depth <= 6; ++depth) {
        double step = scale / double(1 << depth);
        double lx = mx + step * nx, ly = my + step * ny;
        if (!std::isfinite(lx) || !std::isfinite(ly)) continue;
        Rational px = global(lx, origin.x), py = global(ly, origin.y);
        Interval cx = algebra::enclose_kernel(px), cy = algebra::enclose_kernel(py);
        double radius = clearance.lower(cx, cy);
        if (!(radius > 0)) continue;   // could never beat the empty disk
        candidates.push_back(Candidate{std::move(px), std::move(py), Core{cx, cy, radius}});
      }
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const Candidate& a, const Candidate& b) { return a.core.radius > b.core.radius; });
      for (const Candidate& candidate : candidates)
        if (locator.locate(Point{candidate.px, candidate.py}) == PointLocation::inside) {
          cores.push_back(candidate.core);
          break;
        }
    }
  }
  // Drop disks contained in larger ones (only weakens nothing: a contained disk proves less).
  std::sort(cores.begin(), cores.end(), [](const Core& a, const Core& b) { return a.radius > b.radius; });
  std::vector<Core> kept;
  for (const Core& core : cores) {
    bool contained = false;
    for (const Core& big : kept) {
      double d = std::hypot(core.x.middle() - big.x.middle(), core.y.middle() - big.y.middle());
      if (d + core.radius <= big.radius) {
        contained = true;
        break;
      }
    }
    if (!contained) kept.push_back(core);
  }
  return kept;
}

// The loops' exact geometry equal (what compute_inscribed_disks reads; not labels or pointers).
bool same_loops(const std::vector<Loop>& a, const std::vector<Loop>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t l = 0; l < a.size(); ++l) {
    const std::vector<Edge>& ea = a[l].edges;
    const std::vector<Edge>& eb = b[l].edges;
    if (a[l].is_hole != b[l].is_hole || ea.size() != eb.size()) return false;
    for (std::size_t i = 0; i < ea.size(); ++i) {
      const Edge& x = ea[i];
      const Edge& y = eb[i];
      if (x.kind != y.kind || !(x.source == y.source) || !(x.target == y.target)) return false;
      if (x.is_arc() && (x.ccw != y.ccw || !(x.center == y.center) || x.radius_squared != y.radius_squared)) return false;
    }
  }
  return true;
}

// A part's inscribed disks, computed once per part: the curve generators of the pairs a part
// belongs to (a gear train's gear meshes with both neighbours) share them. Keyed by the loops'
// exact geometry (same_loops), so an equal part of another model shares them too; a pure
// function of the key, so the disks are the same with or without the memo. Bounded (the oldest
// entry dropped beyond `capacity`); thread safe (two threads may both compute a missing entry:
// the same disks).
struct InscribedDiskMemo {
  struct Entry {
    std::vector<Loop> loops;
    std::shared_ptr<const std::vector<Core>> cores;
  };
  static constexpr std::size_t capacity = 64;
  std::mutex mutex;
  std::vector<Entry> entries;   // oldest first
  std::size_t computed = 0;
};
InscribedDiskMemo& inscribed_disk_memo() {
  static InscribedDiskMemo memo;
  return memo;
}

std::shared_ptr<const std::vector<Core>> inscribed_disks(const Part& part) {
  InscribedDiskMemo& memo = inscribed_disk_memo();
  {
    std::lock_guard<std::mutex> lock(memo.mutex);
    for (const InscribedDiskMemo::Entry& entry : memo.entries)
      if (same_loops(entry.loops, part.loops)) return entry.cores;
  }
  auto cores = std::make_shared<const std::vector<Core>>(compute_inscribed_disks(part));
  std::vector<Loop> loops = part.loops;
  for (Loop& loop : loops) {
    loop.pointer.clear();
    for (Edge& edge : loop.edges) {
      edge.pointer.clear();
      edge.label.clear();
    }
  }
  std::lock_guard<std::mutex> lock(memo.mutex);
  if (memo.entries.size() >= InscribedDiskMemo::capacity) memo.entries.erase(memo.entries.begin());
  memo.entries.push_back(InscribedDiskMemo::Entry{std::move(loops), cores});
  ++memo.computed;
  return cores;
}

// Certified enclosure of a part's pose over an interval of its chart coordinate.
struct PoseBox {
  Interval c{1};
  Interval s{0};
  Interval pivot_x{0};
  Interval pivot_y{0};
  Interval shift_x{0};
  Interval shift_y{0};
  // (flattened: the interval operations inlined, the same operations in the same order)
  [[gnu::flatten]] void apply(const Interval& x, const Interval& y, Interval& u, Interval& v) const {
    Interval dx = x - pivot_x, dy = y - pivot_y;
    u = pivot_x + shift_x + c * dx - s * dy;
    v = pivot_y + shift_y + s * dx + c * dy;
  }
};

PoseBox pose_over(const PartMotion& motion, bool half_turn, const Interval& t) {
  PoseBox box;
  if (motion.kind == MotionKind::fixed) return box;
  if (motion.kind == MotionKind::translation) {
    box.shift_x = t * algebra::enclose_kernel(motion.direction().x);
    box.shift_y = t * algebra::enclose_kernel(motion.direction().y);
    return box;
  }
  box.pivot_x = algebra::enclose_kernel(motion.pivot().x);
  box.pivot_y = algebra::enclose_kernel(motion.pivot().y);
  std::tie(box.c, box.s) = rotation_enclosure(half_turn, t);
  return box;
}

struct WorldBox {
  double xlo, xhi, ylo, yhi;
  bool meets(const WorldBox& o) const {
    return xlo <= o.xhi && o.xlo <= xhi && ylo <= o.yhi && o.ylo <= yhi;
  }
};

// A feature's body bounding disk: centre enclosure and radius upper bound.
struct BodyDisk {
  Interval x;
  Interval y;
  double radius = 0;
};

BodyDisk body_disk(const BodyFeature& feature) {
  Interval bx = projection_range(feature, Point{Rational(1), Rational(0)});
  Interval by = projection_range(feature, Point{Rational(0), Rational(1)});
  double cx = bx.middle(), cy = by.middle();
  // half extents rounded up (the disk must contain the feature's box)
  using P = Interval;
  double half_x = std::max((P::point(bx.hi) - P::point(cx)).hi, (P::point(cx) - P::point(bx.lo)).hi);
  double half_y = std::max((P::point(by.hi) - P::point(cy)).hi, (P::point(cy) - P::point(by.lo)).hi);
  Interval r = kernels::sqrt(Interval(half_x, half_x) * Interval(half_x, half_x) +
                             Interval(half_y, half_y) * Interval(half_y, half_y));
  return BodyDisk{Interval(cx, cx), Interval(cy, cy), r.hi};
}

[[gnu::flatten]] WorldBox world_box(const PoseBox& pose, const Interval& x, const Interval& y, double radius) {
  Interval u, v;
  pose.apply(x, y, u, v);
  return WorldBox{(u - Interval(radius, radius)).lo, (u + Interval(radius, radius)).hi,
                  (v - Interval(radius, radius)).lo, (v + Interval(radius, radius)).hi};
}

// The cells a walk of BlockedSpaceCuller visits: those whose interval on `axis` (0: x, 1: y)
// meets one of `ranges` (closed double intervals).
struct CullFilter {
  int axis = 1;
  std::vector<std::pair<double, double>> ranges;
  bool meets(const Interval& cx, const Interval& cy) const {
    const Interval& c = axis == 0 ? cx : cy;
    for (const auto& [lo, hi] : ranges)
      if (lo <= c.hi && c.lo <= hi) return true;
    return false;
  }
};

// Quadtree over the chart: a cell is dropped when no candidate pair can meet in it or when it
// is certainly blocked (every configuration there is blocked); feature pairs still candidates
// in the smallest cells are kept. The blocked test is either the chart box's grid of the
// merged cull (`grid`: the builder's BlockedTester, memoised per cell and shared with the
// windows of the kept curves, the grid's cells and depth) or, without a grid, two inscribed
// disks of the parts (`cores`) certainly overlapping in all of the cell (midpoint cells to
// depth 10).
class BlockedSpaceCuller {
  // Two cores (one of each part) that may overlap somewhere in a cell, with the square of
  // their reach (the sum of their radii).
  struct CorePair {
    int i, j;
    Interval reach2;
  };

 public:
  // The two parts' motions (part_motion) built in place, the disks and cores read where they
  // are (they outlive the culler): nothing copied.
  BlockedSpaceCuller(const Part& first_part, bool first_moves, const Part& second_part, bool second_moves,
                     const ChartAxis& x, const ChartAxis& y, int dimension, const std::vector<BodyDisk>& disks_a,
                     const std::vector<BodyDisk>& disks_b, const std::vector<Core>& cores_a,
                     const std::vector<Core>& cores_b, BlockedCells* grid = nullptr)
      : motion_{part_motion(first_part, first_moves), part_motion(second_part, second_moves)},
        x_(x), y_(y), dimension_(dimension), disks_{&disks_a, &disks_b}, cores_{&cores_a, &cores_b}, grid_(grid) {}

  // needed[k] set for the candidate pairs that survive.
  void run(const std::vector<std::pair<int, int>>& pairs, std::vector<char>& needed) {
    prepare(pairs, needed);
    if (grid_) {
      size_lists();
      visit(grid_cell_x(0, 0), grid_cell_y(0, 0), 0, 0, 0, indices_, {});
      return;
    }
    walk(nullptr);
  }

  // run() in steps (no grid): prepare once, then walk the quadtree over the cells whose
  // interval on the filter's axis meets one of its ranges (closed), any number of times. A
  // walk takes each cell it visits from the root by the same halvings and tests it exactly as
  // run() does (the lists a cell reads depend only on its ancestors, and a pair already needed
  // is only skipped), so the pairs needed after walks over filters whose ranges cover every
  // leaf are run()'s, and after any walks, those with a surviving leaf among the leaves visited.
  void prepare(const std::vector<std::pair<int, int>>& pairs, std::vector<char>& needed) {
    indices_.resize(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) indices_[k] = static_cast<int>(k);
    pairs_ = &pairs;
    needed_ = &needed;
    // the features of some candidate pair get a slot in the cell's world boxes (a chart box's
    // pairs use few of the parts' features)
    for (int side = 0; side < 2; ++side) {
      slot_[side].assign(disks_[side]->size(), -1);
      slots_[side] = 0;
    }
    for (const auto& [i, j] : pairs) {
      for (auto [side, feature] : {std::pair{0, i}, std::pair{1, j}}) {
        int& slot = slot_[side][static_cast<std::size_t>(feature)];
        if (slot < 0) slot = static_cast<int>(slots_[side]++);
      }
    }
    memo_ = cell_pose_memo_switch();
    depths_ = static_cast<std::size_t>(grid_ ? std::max(grid_->depth(), min_grid_depth) : max_depth) + 1;
    if (grid_) return;
    root_x_ = Interval(algebra::enclose_kernel(x_.lo).lo, algebra::enclose_kernel(x_.hi).hi);
    root_y_ = dimension_ == 2 ? Interval(algebra::enclose_kernel(y_.lo).lo, algebra::enclose_kernel(y_.hi).hi)
                              : Interval(0);
    root_core_pairs_ = near_core_pairs(root_x_, root_y_);
  }

  // One walk after prepare() (no grid); nullptr: every cell.
  void walk(const CullFilter* filter) {
    filter_ = filter;
    size_lists();
    if (!filter || filter->meets(root_x_, root_y_)) visit(root_x_, root_y_, 0, 0, 0, indices_, root_core_pairs_);
    filter_ = nullptr;
  }

  std::size_t cells_visited() const { return cells_; }

 private:
  // Poses of the pair's parts over the cell: the x axis belongs to the first moving part.
  std::pair<PoseBox, PoseBox> poses(const Interval& cx, const Interval& cy) const {
    bool first_moves = motion_[0].kind != MotionKind::fixed;
    PoseBox a = pose_over(motion_[0], x_.half_turn, cx);
    PoseBox b = first_moves ? pose_over(motion_[1], y_.half_turn, cy)
                            : pose_over(motion_[1], x_.half_turn, cx);
    return {a, b};
  }

  // Core pairs whose posed disks can overlap somewhere in the root cell: sweep and prune on
  // the x extents of the posed cores grown by their radii (the pairs left out are apart over
  // the whole cell, so they can neither certify it blocked nor be near in a sub-cell).
  std::vector<CorePair> near_core_pairs(const Interval& cx, const Interval& cy) const {
    auto [pa, pb] = poses(cx, cy);
    std::vector<CorePair> pairs;
    std::vector<std::pair<int, int>> result;
    sweep_core_pairs(pa, pb, result, pairs);
    return pairs;
  }

  // The sweep and prune of near_core_pairs() over the cores posed by `pa` and `pb` (a cell's
  // poses), into `pairs` (ascending by (i, j); `result`: its work list). Every pair it leaves
  // out is apart over the whole of the poses' cell: core_relation() can only call it apart
  // there (it is certified: the extents are grown by a relative margin far above rounding), and
  // it is apart in every sub-cell.
  void sweep_core_pairs(const PoseBox& pa, const PoseBox& pb, std::vector<std::pair<int, int>>& result,
                        std::vector<CorePair>& pairs) const {
    struct Extent {
      double x_lo, x_hi, y_lo, y_hi;
      int index;
    };
    thread_local std::array<std::vector<Extent>, 2> extents;
    for (int side = 0; side < 2; ++side) {
      extents[side].clear();
      const PoseBox& pose = side == 0 ? pa : pb;
      for (std::size_t i = 0; i < cores_[side]->size(); ++i) {
        Interval u, v;
        pose.apply((*cores_[side])[i].x, (*cores_[side])[i].y, u, v);
        double r = (*cores_[side])[i].radius;
        // grown outward by a relative margin far above double rounding
        double margin = 1e-9 * (1 + std::fabs(u.lo) + std::fabs(u.hi) + std::fabs(v.lo) + std::fabs(v.hi) + r);
        extents[side].push_back({u.lo - r - margin, u.hi + r + margin, v.lo - r - margin, v.hi + r + margin,
                                 static_cast<int>(i)});
      }
      std::sort(extents[side].begin(), extents[side].end(),
                [](const Extent& a, const Extent& b) { return a.x_lo < b.x_lo; });
    }
    result.clear();
    // sweep over starts in x: a starting box meets the active boxes of the other list
    thread_local std::array<std::vector<const Extent*>, 2> active;
    active[0].clear();
    active[1].clear();
    std::size_t next[2] = {0, 0};
    while (next[0] < extents[0].size() || next[1] < extents[1].size()) {
      int side = next[1] >= extents[1].size() ||
                         (next[0] < extents[0].size() && extents[0][next[0]].x_lo <= extents[1][next[1]].x_lo)
                     ? 0
                     : 1;
      const Extent& box = extents[side][next[side]++];
      auto& others = active[1 - side];
      std::erase_if(others, [&](const Extent* e) { return e->x_hi < box.x_lo; });
      for (const Extent* other : others)
        if (!(other->y_hi < box.y_lo || other->y_lo > box.y_hi))
          result.emplace_back(side == 0 ? box.index : other->index, side == 0 ? other->index : box.index);
      active[side].push_back(&box);
    }
    // (std::sort's order, by counting passes over the core indices: a shallow cell's list is
    // most of the cores' pairs)
    sort_index_pairs(result, cores_[0]->size(), cores_[1]->size());
    // each pair's reach (the sum of the radii) squared, once: every cell compares with it
    pairs.clear();
    pairs.reserve(result.size());
    for (const auto& [ci, cj] : result) {
      double ra = (*cores_[0])[static_cast<std::size_t>(ci)].radius, rb = (*cores_[1])[static_cast<std::size_t>(cj)].radius;
      Interval reach = Interval(ra, ra) + Interval(rb, rb);
      pairs.push_back(CorePair{ci, cj, reach * reach});
    }
  }

  // One part's pose over one axis interval, with the world boxes of its features and the posed
  // centres of its cores computed on first use (a slot holds the interval's value when its stamp
  // is the set's). Each value is a function of (the part's axis interval, the feature or core),
  // computed by the same operations whichever cell asks for it.
  struct CellPoses {
    PoseBox pose;
    std::uint64_t key_lo = 0, key_hi = 0;   // the interval's bits (valid when stamp != 0)
    std::uint64_t stamp = 0;                // 0: holds no interval
    std::vector<WorldBox> boxes;
    std::vector<std::uint64_t> box_stamp;
    std::vector<Interval> core_x, core_y;
    std::vector<std::uint64_t> core_stamp;
  };
  // The sets of one part at one depth of the quadtree: the last four axis intervals met there. A
  // cell's children split its intervals, so the cells of one depth met in a row share an interval
  // of each part with a sibling or a cousin (the four children of a cell: two x intervals, two y
  // intervals; the children of its next sibling along y: the same x intervals again) — what a
  // cache keyed by every interval shared, without its memory. A cell reads its depth's sets only
  // before visiting its children (which use the next depth's), so no set changes under it.
  static constexpr int pose_ways = 4;
  struct PoseMemo {
    CellPoses way[pose_ways];
    int next = 0;   // the way replaced on the next miss (round robin)
  };
  // Per thread, shared by the cullers as the lists are (a walk never runs inside another): every
  // set is emptied when a walk starts (size_lists) and its slots only grow, so a walk allocates
  // nothing once the thread has met the largest part. [depth][side]. Only while the sets are
  // small (memo_budget: a chart box's few features, as in a grid's cull); larger parts (the
  // gears' strips, hundreds of cores and features) use one set per part for every cell, as
  // before the memo, so the thread's memory stays that of one set per part.
  static constexpr std::size_t memo_budget = std::size_t(1) << 20;   // bytes per thread
  static std::vector<std::array<PoseMemo, 2>>& thread_poses() {
    thread_local std::vector<std::array<PoseMemo, 2>> poses;
    return poses;
  }
  // Stamps are unique per thread (a set's stamp is new whenever it takes an interval), so a slot
  // stamped for another interval or another culler never passes for this one.
  static std::uint64_t& thread_stamp() {
    thread_local std::uint64_t stamp = 0;
    return stamp;
  }
  static std::uint64_t bits_of(double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
  }

  // The poses of one part over a cell of depth `depth` whose axis interval is `interval` (a fixed
  // part: the constant key 0): a function of the part's motion, its axis' half-turn flag and the
  // interval's bits; the depth's set holding that interval when there is one (memo on), else a set
  // given the interval with a new stamp.
  CellPoses& pose_cell(int side, const Interval& interval, std::size_t depth) {
    PoseMemo& memo = thread_poses()[memo_levels_ == 1 ? 0 : depth][static_cast<std::size_t>(side)];
    const std::uint64_t lo = bits_of(interval.lo), hi = bits_of(interval.hi);
    if (memo_) {
      for (int w = 0; w < ways_; ++w) {
        CellPoses& held = memo.way[w];
        if (held.stamp != 0 && held.key_lo == lo && held.key_hi == hi) return held;
      }
    }
    const int w = memo_ ? memo.next : 0;
    memo.next = (w + 1) % ways_;
    CellPoses& posed = memo.way[w];
    const bool first_moves = motion_[0].kind != MotionKind::fixed;
    posed.pose = pose_over(motion_[side], side == 0 || !first_moves ? x_.half_turn : y_.half_turn, interval);
    posed.key_lo = lo;
    posed.key_hi = hi;
    posed.stamp = ++thread_stamp();
    return posed;
  }

  Interval grid_cell_x(int depth, long i) const {
    algebra::Interval c = grid_->cell_x(depth, i);
    return Interval(c.lo, c.hi);
  }
  Interval grid_cell_y(int depth, long j) const {
    algebra::Interval c = grid_->cell_y(depth, j);
    return Interval(c.lo, c.hi);
  }

  enum class CoreRelation { overlapping, near, apart };

  // Two cores over the cell of the two axis caches: certainly overlapping everywhere in it,
  // possibly overlapping somewhere (near), or apart everywhere. The posed centres are memoised
  // in the caches.
  // (flattened: the interval operations inlined, the same operations in the same order — the
  // quadtree's innermost loop)
  [[gnu::flatten]] CoreRelation core_relation(const CorePair& pair, CellPoses& cache_a, CellPoses& cache_b) const {
    auto ui = static_cast<std::size_t>(pair.i), uj = static_cast<std::size_t>(pair.j);
    if (!memo_ || cache_a.core_stamp[ui] != cache_a.stamp) {
      cache_a.pose.apply((*cores_[0])[ui].x, (*cores_[0])[ui].y, cache_a.core_x[ui], cache_a.core_y[ui]);
      cache_a.core_stamp[ui] = cache_a.stamp;
    }
    if (!memo_ || cache_b.core_stamp[uj] != cache_b.stamp) {
      cache_b.pose.apply((*cores_[1])[uj].x, (*cores_[1])[uj].y, cache_b.core_x[uj], cache_b.core_y[uj]);
      cache_b.core_stamp[uj] = cache_b.stamp;
    }
    // (dx * dx + dy * dy against the reach, dx and dy the centres' differences)
    int relation = cull_detail::squared_distance_relation(cache_a.core_x[ui], cache_a.core_y[ui], cache_b.core_x[uj],
                                                      cache_b.core_y[uj], pair.reach2);
    return relation < 0 ? CoreRelation::overlapping : relation == 0 ? CoreRelation::near : CoreRelation::apart;
  }

  void visit(const Interval& cx, const Interval& cy, int depth, long i, long j, const std::vector<int>& candidates,
             const std::vector<CorePair>& core_pairs) {
    ++cells_;
    // this depth's lists (the children's are the next depth's: nothing is allocated per cell)
    Scratch& scratch = scratch_at(static_cast<std::size_t>(depth));
    // Pairs already kept need no further exploration.
    std::vector<int>& open = scratch.open;
    open.clear();
    for (int k : candidates)
      if (!(*needed_)[static_cast<std::size_t>(k)]) open.push_back(k);
    if (open.empty()) return;
    bool first_moves = motion_[0].kind != MotionKind::fixed;
    // the interval each part's pose depends on (a fixed part: a constant key)
    Interval key_a = first_moves ? cx : Interval(0);
    Interval key_b = motion_[1].kind == MotionKind::fixed ? Interval(0) : (first_moves ? cy : cx);
    CellPoses& cache_a = pose_cell(0, key_a, static_cast<std::size_t>(depth));
    CellPoses& cache_b = pose_cell(1, key_b, static_cast<std::size_t>(depth));
    const PoseBox& pa = cache_a.pose;
    const PoseBox& pb = cache_b.pose;
    // Blocked: some pair of inscribed disks certainly overlaps everywhere in the cell.
    const bool leaf = depth >= (grid_ ? std::max(grid_->depth(), min_grid_depth) : max_depth);
    std::vector<CorePair>& near_cores = scratch.near_cores;
    near_cores.clear();
    // A long inherited list (the shallow cells of a large pair: every core pair at the root,
    // most of them apart in a child) is replaced by the sweep of this cell's own posed cores
    // when that is cheaper. The decision is the same: the cell is blocked exactly when some core
    // pair certainly overlaps everywhere in it, and such a pair is in both lists (it is not apart
    // in the cell, nor in any cell holding it). Pairs only one list holds are apart in this cell
    // or in an ancestor, so they certify no sub-cell either: the children decide as before.
    const std::vector<CorePair>* tested = &core_pairs;
    if (depth > 0 && core_pairs.size() > core_sweep_factor * (cores_[0]->size() + cores_[1]->size()) &&
        core_sweep_switch()) {
      sweep_core_pairs(pa, pb, scratch.swept, scratch.swept_cores);
      tested = &scratch.swept_cores;
      ++core_sweeps();
    }
    for (const CorePair& pair : *tested) {
      const CoreRelation relation = core_relation(pair, cache_a, cache_b);
      if (relation == CoreRelation::overlapping) return;   // blocked everywhere in the cell
      if (relation == CoreRelation::near && !leaf) near_cores.push_back(pair);   // (a leaf has no children)
    }
    // Candidate pairs whose features can meet in the cell.
    std::vector<int>& meeting = scratch.meeting;
    meeting.clear();
    for (int k : open) {
      auto [i, j] = (*pairs_)[static_cast<std::size_t>(k)];
      auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      auto sa = static_cast<std::size_t>(slot_[0][ui]), sb = static_cast<std::size_t>(slot_[1][uj]);
      if (!memo_ || cache_a.box_stamp[sa] != cache_a.stamp) {
        const BodyDisk& disk = (*disks_[0])[ui];
        cache_a.boxes[sa] = world_box(pa, disk.x, disk.y, disk.radius);
        cache_a.box_stamp[sa] = cache_a.stamp;
      }
      if (!memo_ || cache_b.box_stamp[sb] != cache_b.stamp) {
        const BodyDisk& disk = (*disks_[1])[uj];
        cache_b.boxes[sb] = world_box(pb, disk.x, disk.y, disk.radius);
        cache_b.box_stamp[sb] = cache_b.stamp;
      }
      if (cache_a.boxes[sa].meets(cache_b.boxes[sb])) meeting.push_back(k);
    }
    if (meeting.empty()) return;
    // the grid's blocked test (memoised, shared with the builder) after the cheap box tests
    if (grid_ && depth >= 2 && grid_->blocked(depth, i, j)) return;
    if (leaf) {
      for (int k : meeting) (*needed_)[static_cast<std::size_t>(k)] = 1;
      return;
    }
    if (grid_) {
      for (long di = 0; di < 2; ++di) {
        if (dimension_ != 2) {
          visit(grid_cell_x(depth + 1, 2 * i + di), cy, depth + 1, 2 * i + di, j, meeting, near_cores);
          continue;
        }
        for (long dj = 0; dj < 2; ++dj)
          visit(grid_cell_x(depth + 1, 2 * i + di), grid_cell_y(depth + 1, 2 * j + dj), depth + 1, 2 * i + di,
                2 * j + dj, meeting, near_cores);
      }
      return;
    }
    // Split every axis at its middle.
    double mx = 0.5 * (cx.lo + cx.hi);
    std::array<Interval, 2> xs{Interval(cx.lo, mx), Interval(mx, cx.hi)};
    if (dimension_ == 2) {
      double my = 0.5 * (cy.lo + cy.hi);
      std::array<Interval, 2> ys{Interval(cy.lo, my), Interval(my, cy.hi)};
      for (const Interval& sx : xs)
        for (const Interval& sy : ys)
          if (!filter_ || filter_->meets(sx, sy)) visit(sx, sy, depth + 1, 0, 0, meeting, near_cores);
    } else {
      for (const Interval& sx : xs)
        if (!filter_ || filter_->meets(sx, cy)) visit(sx, cy, depth + 1, 0, 0, meeting, near_cores);
    }
  }

  static constexpr int max_depth = 10;
  // With a grid, pairs are followed at least to this depth of the box: an operating-region
  // tile's grid is as coarse as the chart's 512 columns allow (the builder's windows), but a
  // pair is dropped only where the tile's own finer cells are blocked.
  static constexpr int min_grid_depth = 9;
  PartMotion motion_[2];
  ChartAxis x_;
  ChartAxis y_;
  int dimension_;
  const std::vector<BodyDisk>* disks_[2];
  std::vector<int> slot_[2];       // feature -> its slot in CellPoses::boxes (-1: in no pair)
  std::size_t slots_[2] = {0, 0};
  const std::vector<Core>* cores_[2];
  const std::vector<std::pair<int, int>>* pairs_ = nullptr;
  std::vector<char>* needed_ = nullptr;
  std::size_t cells_ = 0;
  bool memo_ = true;          // cell_pose_memo_switch() when prepared
  BlockedCells* grid_ = nullptr;
  // prepare(): the candidate indices and the root cell with its near core pairs; walk(): its filter
  std::vector<int> indices_;
  Interval root_x_{0}, root_y_{0};
  std::vector<CorePair> root_core_pairs_;
  const CullFilter* filter_ = nullptr;
  // per depth of the quadtree: the open and meeting candidate pairs and the near core pairs of
  // the cell being visited there (a child reads its parent's lists by reference)
  struct Scratch {
    std::vector<int> open, meeting;
    std::vector<CorePair> near_cores;
    std::vector<std::pair<int, int>> swept;   // sweep_core_pairs()'s work list and pairs
    std::vector<CorePair> swept_cores;
  };
  // a cell sweeps its own cores when its inherited list is longer than this many per core
  static constexpr std::size_t core_sweep_factor = 16;
  // The lists of depth `depth` (< depths_), shared by the cullers of a thread: a walk never
  // runs inside another (nothing a cell calls walks a culler), and its lists are cleared before
  // use, so they only keep their capacity between walks — a gear strip's shallow lists hold
  // hundreds of thousands of core pairs, allocated and faulted in again by every walk before.
  static std::vector<Scratch>& thread_lists() {
    thread_local std::vector<Scratch> lists;
    return lists;
  }
  // (sized before the root is visited: no list moves while a cell holds its parent's)
  // (and the pose memo: every set emptied, its slots grown to this culler's cores and features)
  void size_lists() {
    if (thread_lists().size() < depths_) thread_lists().resize(depths_);
    // the memo's shape: a set per depth and way while all of them fit the budget, else one
    std::size_t set_bytes = 0;
    for (std::size_t side = 0; side < 2; ++side)
      set_bytes += cores_[side]->size() * (2 * sizeof(Interval) + sizeof(std::uint64_t)) +
                   slots_[side] * (sizeof(WorldBox) + sizeof(std::uint64_t));
    const bool small = set_bytes * depths_ * pose_ways <= memo_budget;
    memo_levels_ = small ? depths_ : 1;
    ways_ = small ? pose_ways : 1;
    auto& poses = thread_poses();
    if (poses.size() < memo_levels_) poses.resize(memo_levels_);
    for (std::size_t depth = 0; depth < memo_levels_; ++depth)
      for (std::size_t side = 0; side < 2; ++side)
        for (int w = 0; w < ways_; ++w) {
          CellPoses& posed = poses[depth][side].way[w];
          posed.stamp = 0;
          poses[depth][side].next = 0;
          const std::size_t cores = cores_[side]->size(), slots = slots_[side];
          if (posed.core_stamp.size() < cores) {
            posed.core_x.resize(cores);
            posed.core_y.resize(cores);
            posed.core_stamp.resize(cores, 0);
          }
          if (posed.box_stamp.size() < slots) {
            posed.boxes.resize(slots);
            posed.box_stamp.resize(slots, 0);
          }
        }
  }
  Scratch& scratch_at(std::size_t depth) const { return thread_lists()[depth]; }
  std::size_t depths_ = max_depth + 1;
  // the pose memo's shape for this culler's walks (size_lists): its depths and ways
  std::size_t memo_levels_ = 1;
  int ways_ = 1;
};

// ============================================================================ exact kernels

using Polynomial = RationalPolynomial2;
using PolyVector = kernels::Vector<Polynomial>;

// The contact table (kernels/contact_table.hpp) in exact polynomials of the chart coordinates:
// body data are rationals, the radius products' roots taken when they are rational.
std::optional<kernels::ContactFunction<Polynomial>> contact_of(const kernels::FeatureGeometry<Rational>& fa,
                                                               const kernels::FeatureGeometry<Rational>& fb,
                                                               const kernels::Pose<Polynomial>& a,
                                                               const kernels::Pose<Polynomial>& b) {
  return kernels::contact_function(a, fa, b, fb,
                                   [](const Rational& r) { return Polynomial(r); },
                                   kernels::ExactRootOrSquared{[](const Rational& square) { return exact_square_root(square); }});
}

// A feature's directions for corner_enters_segment: a vertex's outgoing and incoming tangents, a
// segment's direction (source to target); nothing for other features.
struct FeatureDirections {
  bool vertex = false, segment = false;
  Point out, in;   // vertex; segment: out = direction
  Interval out_x, out_y, in_x, in_y;   // their enclosures (the filter of corner_enters_segment)
};

FeatureDirections feature_directions(const Model& model, const BodyFeature& feature) {
  FeatureDirections d;
  if (feature.ref.kind == FeatureRef::Kind::vertex) {
    const Loop& loop = model.parts.at(feature.ref.part).loops.at(feature.ref.loop);
    const std::size_t n = loop.edges.size();
    d.vertex = true;
    d.out = edge_tangent(loop.edges[feature.ref.edge], feature.point());
    d.in = edge_tangent(loop.edges[(feature.ref.edge + n - 1) % n], feature.point());
  } else if (feature.ref.kind == FeatureRef::Kind::segment) {
    d.segment = true;
    d.out = difference(feature.edge->target, feature.edge->source);
  }
  d.out_x = algebra::enclose_kernel(d.out.x);
  d.out_y = algebra::enclose_kernel(d.out.y);
  d.in_x = algebra::enclose_kernel(d.in.x);
  d.in_y = algebra::enclose_kernel(d.in.y);
  return d;
}

// Translating pairs (no rotation: body directions are world directions): a vertex feature of
// one part against a segment feature of the other whose corner enters the segment's side. The
// corner's material near the vertex is the closed cone of its edges' tangents (out, -in; the
// vertex is not strictly reflex), the other part's material near a point inside the segment is
// the open half-plane behind it (outward normal n, material on the left of every edge). When
// out . n < 0 or in . n > 0 the cone reaches into that half-plane, so wherever the vertex lies
// inside the segment the interiors overlap: the whole open contact curve is in blocked space
// and bounds nothing (its end points are contacts of the neighbouring features). Exact.
bool corner_enters_segment(const FeatureDirections& vertex, const FeatureDirections& segment) {
  if (!vertex.vertex || !segment.segment) return false;
  const Point& t = segment.out;
  // sign of u . n with the segment's outward normal n = (t.y, -t.x): certified in interval
  // arithmetic, exact when the enclosure holds zero
  auto dot_n = [&](const Point& u, const Interval& ux, const Interval& uy) {
    int sign = (ux * segment.out_y - uy * segment.out_x).sign();
    if (sign == 1 || sign == -1) return sign;
    return cmp(u.x * t.y, u.y * t.x);
  };
  return dot_n(vertex.out, vertex.out_x, vertex.out_y) < 0 || dot_n(vertex.in, vertex.in_x, vertex.in_y) > 0;
}

// ---------------------------------------------------------------- polygon front end
//
// Translating polygon pairs (no rotation, segments and vertices only). The pairs whose curve
// is not entirely in blocked space are those of the reduced convolution: a vertex v (tangents
// in, out) of one part and a segment with direction t of the other, with cross(out, t) >= 0
// and cross(in, t) <= 0 (the complement of corner_enters_segment). That set of directions t
// is an arc of the circle of directions (the cone from -in to -out for a convex vertex, the
// two directions +-out for a straight one, a half-plane for a spike), so the pairs are found
// by walking the segments' directions sorted by angle from the arc's start: O((m + n) log n +
// pairs) exact predicates instead of m n corner tests.

// A direction with its enclosure (the filter of the exact signs below).
// A segment's direction in the front end: the primitive integer vector along it (target -
// source times a positive factor, front_direction), with double enclosures of its coordinates
// for the filters below. Integers (not a Point of rationals): no denominators made, and the
// exact fallbacks are integer products (session 42).
struct Direction {
  mpz_class x, y;
  Interval ix, iy;
  // an integer's enclosure: the double itself when |z| < 2^53 (exact), else the kernels'
  static Interval enclose(const mpz_class& z) {
    if (mpz_sizeinbase(z.get_mpz_t(), 2) <= 53) {
      const double d = z.get_d();   // exact
      return Interval(d, d);
    }
    return algebra::enclose_kernel(mpq_class(z));
  }
  static Direction of(mpz_class x, mpz_class y) {
    Interval ix = enclose(x), iy = enclose(y);
    return Direction{std::move(x), std::move(y), ix, iy};
  }
  Direction negated() const { return Direction{mpz_class(-x), mpz_class(-y), -ix, -iy}; }
};

// Exact cross(a, b) or dot(a, b) sign of two integer vectors (per-thread scratch integers).
int integer_cross_sign(const Direction& a, const Direction& b) {
  thread_local mpz_class t;
  mpz_mul(t.get_mpz_t(), a.x.get_mpz_t(), b.y.get_mpz_t());
  mpz_submul(t.get_mpz_t(), a.y.get_mpz_t(), b.x.get_mpz_t());
  return sgn(t);
}
int integer_dot_sign(const Direction& a, const Direction& b) {
  thread_local mpz_class t;
  mpz_mul(t.get_mpz_t(), a.x.get_mpz_t(), b.x.get_mpz_t());
  mpz_addmul(t.get_mpz_t(), a.y.get_mpz_t(), b.y.get_mpz_t());
  return sgn(t);
}

// Sign of cross(a, b): interval filter, exact when the enclosure holds zero.
int cross_sign(const Direction& a, const Direction& b) {
  int sign = (a.ix * b.iy - a.iy * b.ix).sign();
  if (sign == 1 || sign == -1) return sign;
  return integer_cross_sign(a, b);
}

// Exact angular order of non-zero directions: angle in [0, 2 pi) from +x.
int half_of(const Direction& u) { return sgn(u.y) > 0 || (sgn(u.y) == 0 && sgn(u.x) > 0) ? 0 : 1; }
bool angle_before(const Direction& a, const Direction& b) {
  int ha = half_of(a), hb = half_of(b);
  if (ha != hb) return ha < hb;
  return cross_sign(a, b) > 0;
}

// The reduced convolution's (vertex feature, segment feature) pairs: `vertices` with their
// tangents, `segments` with their directions (indices into the parts' feature lists).
struct DirectedFeature {
  int index;
  // into the generator's per-edge directions (no copies of their rationals): vertex: its two
  // tangents; segment: out = its direction, in unused (null)
  const Direction* out;
  const Direction* in;
};

std::vector<std::pair<int, int>> cone_pairs(const std::vector<DirectedFeature>& vertices,
                                            std::vector<DirectedFeature> segments) {
  std::vector<std::pair<int, int>> result;
  if (segments.empty()) return result;
  std::sort(segments.begin(), segments.end(),
            [](const DirectedFeature& a, const DirectedFeature& b) { return angle_before(*a.out, *b.out); });
  const std::size_t n = segments.size();
  for (const DirectedFeature& v : vertices) {
    const Direction& out = *v.out;
    const Direction& in = *v.in;
    auto inside = [&](const Direction& t) { return cross_sign(out, t) >= 0 && cross_sign(in, t) <= 0; };
    // walk cyclically from the first direction at or after `start` while inside the arc
    auto walk = [&](const Direction& start) {
      std::size_t first = static_cast<std::size_t>(
          std::lower_bound(segments.begin(), segments.end(), start,
                           [](const DirectedFeature& s, const Direction& u) { return angle_before(*s.out, u); }) -
          segments.begin());
      for (std::size_t k = 0; k < n; ++k) {
        const DirectedFeature& s = segments[(first + k) % n];
        if (!inside(*s.out)) break;
        result.emplace_back(v.index, s.index);
      }
    };
    int turn = cross_sign(in, out);
    if (turn > 0) {
      walk(in.negated());   // the cone from -in counter-clockwise to -out
    } else if (turn == 0 && integer_dot_sign(in, out) > 0) {
      walk(in.negated());   // a straight vertex: the directions -out and +out
      walk(out);
    } else if (turn == 0) {
      walk(out);            // a spike (in = -out): the half-plane from out to -out
    } else {
      for (const DirectedFeature& s : segments)   // (no feature: strictly reflex vertices are skipped)
        if (inside(*s.out)) result.emplace_back(v.index, s.index);
    }
  }
  return result;
}

// The world shift of a translating part as an affine form of the chart coordinates.
struct Shift {
  Point x, y;   // shift = x * chart_x + y * chart_y
};

// ---------------------------------------------------------------- the front end in integers
//
// The curves of the kernels' vertex_segment for translation poses (weights 1, no rotation):
// cross(P - Q1, d) with its validity 0 <= dot(P - Q1, d) <= |d|^2, in homogeneous integer
// arithmetic. A point is (X, Y) / W with W = lcm of its coordinates' denominators > 0; a
// segment's direction is carried as D, the primitive integer vector along target - source (a
// positive multiple of it). The contact and both atoms are positive multiples of the rational
// forms: with the vertex P = (X, Y) / W, the source Q1 = (X1, Y1) / W1, the target
// Q2 = (X2, Y2) / W2 and the chart shifts' cross and dot products with D over a common K > 0,
//   value  = cross(P - Q1, d) + ...   ~ K (cross((X, Y), D) W1 - cross((X1, Y1), D) W) + x kx W W1 + y ky W W1
//   along  = dot(P - Q1, d) + ...     ~ K (dot((X, Y), D) W1 - dot((X1, Y1), D) W) + x gx W W1 + y gy W W1
//   |d|^2 - along = dot(Q2 - P, d) - ...
//                                     ~ K (dot((X2, Y2), D) W - dot((X, Y), D) W2) - x gx W W2 - y gy W W2
// (cross(Q2 - Q1, d) = 0 and |d|^2 - dot(P - Q1, d) = dot(Q2 - P, d); every factor is positive).
// Normalising (dividing by the positive content) makes each the polynomial that
// normalized_integer_polynomial writes from the kernels' rational forms (the general path): the
// primitive integer form is unique up to a positive factor.
struct HomogeneousPoint {
  mpz_class x, y, w;
};

HomogeneousPoint homogeneous(const Point& p) {
  HomogeneousPoint h;
  mpz_lcm(h.w.get_mpz_t(), p.x.get_den_mpz_t(), p.y.get_den_mpz_t());
  mpz_divexact(h.x.get_mpz_t(), h.w.get_mpz_t(), p.x.get_den_mpz_t());
  h.x *= p.x.get_num();
  mpz_divexact(h.y.get_mpz_t(), h.w.get_mpz_t(), p.y.get_den_mpz_t());
  h.y *= p.y.get_num();
  return h;
}

// A vertex feature: its point (the part's edge end, kept by the generator: not a copy).
struct FrontVertex {
  const HomogeneousPoint* p;
};

// A segment feature: the ends' denominators W1, W2, the primitive direction D (the ends' and
// the edge's direction, and k, kept by the generator and read through pointers: no copies),
// cross((X1, Y1), D), dot((X1, Y1), D), dot((X2, Y2), D), and the chart shifts' products kx, ky,
// gx, gy (integers over k > 0) for the other part's vertices.
struct FrontSegment {
  const mpz_class *w1, *w2, *dx, *dy, *k;
  mpz_class cross1, dot1, dot2;
  mpz_class kx, ky, gx, gy;
};

// The chart shifts' difference u = (vertex part's shift) - (segment part's shift) as integers
// over a common denominator k > 0: ux = (x1, x2) / k, uy = (y1, y2) / k.
struct IntegerShift {
  mpz_class x1, x2, y1, y2, k;
};

IntegerShift integer_shift(const Point& ux, const Point& uy) {
  IntegerShift u;
  u.k = 1;
  for (const Rational* q : {&ux.x, &ux.y, &uy.x, &uy.y}) mpz_lcm(u.k.get_mpz_t(), u.k.get_mpz_t(), q->get_den_mpz_t());
  auto scaled = [&](const Rational& q) { return mpz_class(q.get_num() * (u.k / q.get_den())); };
  u.x1 = scaled(ux.x);
  u.x2 = scaled(ux.y);
  u.y1 = scaled(uy.x);
  u.y2 = scaled(uy.y);
  return u;
}

// D of the edge from q1 to q2 written into dx, dy (the edge's ends read in place: no copies)
void front_direction(const HomogeneousPoint& q1, const HomogeneousPoint& q2, mpz_class& dx, mpz_class& dy) {
  // (products accumulated in place with mpz_addmul / mpz_submul: no temporary integers)
  mpz_mul(dx.get_mpz_t(), q2.x.get_mpz_t(), q1.w.get_mpz_t());
  mpz_submul(dx.get_mpz_t(), q1.x.get_mpz_t(), q2.w.get_mpz_t());
  mpz_mul(dy.get_mpz_t(), q2.y.get_mpz_t(), q1.w.get_mpz_t());
  mpz_submul(dy.get_mpz_t(), q1.y.get_mpz_t(), q2.w.get_mpz_t());
  thread_local mpz_class g;
  mpz_gcd(g.get_mpz_t(), dx.get_mpz_t(), dy.get_mpz_t());
  if (g > 1) {
    mpz_divexact(dx.get_mpz_t(), dx.get_mpz_t(), g.get_mpz_t());
    mpz_divexact(dy.get_mpz_t(), dy.get_mpz_t(), g.get_mpz_t());
  }
}

// The shifts' products with D are integers over u.k (any positive common factor: the forms are
// made primitive afterwards). The edge is given by its ends q1, q2 and its D (dx, dy); the
// segment points to them and to u.k, which must outlive it.
FrontSegment front_segment(const HomogeneousPoint& q1, const HomogeneousPoint& q2, const mpz_class& dx,
                           const mpz_class& dy, const IntegerShift& u) {
  FrontSegment s;
  s.w1 = &q1.w;
  s.w2 = &q2.w;
  s.dx = &dx;
  s.dy = &dy;
  // a b + sign c d in place (no temporary integers)
  auto combine = [](mpz_class& out, const mpz_class& a, const mpz_class& b, int sign, const mpz_class& c,
                    const mpz_class& d) {
    mpz_mul(out.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
    if (sign < 0) mpz_submul(out.get_mpz_t(), c.get_mpz_t(), d.get_mpz_t());
    else mpz_addmul(out.get_mpz_t(), c.get_mpz_t(), d.get_mpz_t());
  };
  combine(s.cross1, q1.x, dy, -1, q1.y, dx);
  combine(s.dot1, q1.x, dx, 1, q1.y, dy);
  combine(s.dot2, q2.x, dx, 1, q2.y, dy);
  combine(s.kx, u.x1, dy, -1, u.x2, dx);
  combine(s.ky, u.y1, dy, -1, u.y2, dx);
  combine(s.gx, u.x1, dx, 1, u.x2, dy);
  combine(s.gy, u.y1, dx, 1, u.y2, dy);
  s.k = &u.k;
  return s;
}

// c + cx x + cy y divided by its content, trimmed as normalize() leaves it.
IntegerPolynomial2 primitive_affine(mpz_class& c, mpz_class& cx, mpz_class& cy, mpz_class& scratch) {
  IntegerPolynomial2 p;
  mpz_gcd(scratch.get_mpz_t(), c.get_mpz_t(), cx.get_mpz_t());
  mpz_gcd(scratch.get_mpz_t(), scratch.get_mpz_t(), cy.get_mpz_t());
  if (sgn(scratch) == 0) return p;   // the zero polynomial: no coefficients
  if (scratch > 1)
    for (mpz_class* v : {&c, &cx, &cy}) mpz_divexact(v->get_mpz_t(), v->get_mpz_t(), scratch.get_mpz_t());
  if (sgn(cx) != 0) {
    p.coefficients.resize(2);
    p.coefficients[1].push_back(cx);
  } else {
    p.coefficients.resize(1);
  }
  auto& row = p.coefficients[0];
  if (sgn(cy) != 0) {
    row.reserve(2);
    row.push_back(c);
    row.push_back(cy);
  } else if (sgn(c) != 0) {
    row.push_back(c);
  }
  return p;
}

bool front_contact_gmp(const HomogeneousPoint& p, const FrontSegment& s, ContactCurve& curve);

// primitive_affine of c + cx x + cy y given as machine integers below 2^63 in magnitude: the
// same polynomial (the same content removed, the same trimming), its integers made from longs.
IntegerPolynomial2 primitive_affine_small(long c, long cx, long cy) {
  IntegerPolynomial2 p;
  auto magnitude = [](long v) { return v < 0 ? 0 - static_cast<unsigned long>(v) : static_cast<unsigned long>(v); };
  const unsigned long g = std::gcd(std::gcd(magnitude(c), magnitude(cx)), magnitude(cy));
  if (g == 0) return p;   // the zero polynomial: no coefficients
  if (g > 1) {            // (exact divisions: |v| / g of the magnitude, the sign kept)
    const long sg = static_cast<long>(g);
    c /= sg;
    cx /= sg;
    cy /= sg;
  }
  if (cx != 0) {
    p.coefficients.resize(2);
    p.coefficients[1].emplace_back(cx);
  } else {
    p.coefficients.resize(1);
  }
  auto& row = p.coefficients[0];
  if (cy != 0) {
    row.reserve(2);
    row.emplace_back(c);
    row.emplace_back(cy);
  } else if (c != 0) {
    row.emplace_back(c);
  }
  return p;
}

// front_contact in machine integers (algebra/small_integers.hpp): the same integer expressions,
// exact in __int128 with every operation checked for overflow, and the same polynomials
// (primitive_affine_small). Nothing written and std::nullopt when an integer read is not below
// 2^62 or a form's coefficient does not fit a long: front_contact then takes its GMP path.
std::optional<bool> front_contact_small(const HomogeneousPoint& p, const FrontSegment& s, ContactCurve& curve) {
  namespace si = algebra::small_integers;
  si::Wide px, py, pw, w1, w2, dx, dy, cross1, dot1, dot2, k, kx, ky, gx, gy;
  if (!si::read(p.x.get_mpz_t(), px) || !si::read(p.y.get_mpz_t(), py) || !si::read(p.w.get_mpz_t(), pw) ||
      !si::read(s.w1->get_mpz_t(), w1) || !si::read(s.w2->get_mpz_t(), w2) || !si::read(s.dx->get_mpz_t(), dx) ||
      !si::read(s.dy->get_mpz_t(), dy) || !si::read(s.cross1.get_mpz_t(), cross1) || !si::read(s.dot1.get_mpz_t(), dot1) ||
      !si::read(s.dot2.get_mpz_t(), dot2) || !si::read(s.k->get_mpz_t(), k) || !si::read(s.kx.get_mpz_t(), kx) ||
      !si::read(s.ky.get_mpz_t(), ky) || !si::read(s.gx.get_mpz_t(), gx) || !si::read(s.gy.get_mpz_t(), gy))
    return std::nullopt;
  auto fits_long = [](si::Wide v) { return v >= std::numeric_limits<long>::min() + 1L && v <= std::numeric_limits<long>::max(); };
  // value: ((P x D) W1 - cross1 W) k + kx W W1 x + ky W W1 y
  si::Wide ww1, pd, c, cx, cy;
  if (!si::mul(pw, w1, ww1) || !si::cross(px, dy, py, dx, pd) || !si::cross(pd, w1, cross1, pw, c) || !si::mul(c, k, c) ||
      !si::mul(kx, ww1, cx) || !si::mul(ky, ww1, cy) || !fits_long(c) || !fits_long(cx) || !fits_long(cy))
    return std::nullopt;
  // along: ((P . D) W1 - dot1 W) k + gx W W1 x + gy W W1 y; the far end: (dot2 W - (P . D) W2) k - gx W W2 x - gy W W2 y
  const bool constant_atoms = gx == 0 && gy == 0;
  si::Wide pdot, near0, far0, nx = 0, ny = 0, fx = 0, fy = 0, ww2, t;
  if (!si::mul(px, dx, pdot) || !si::mul(py, dy, t) || !si::add(pdot, t, pdot) || !si::cross(pdot, w1, dot1, pw, near0) ||
      !si::mul(near0, k, near0) || !si::cross(dot2, pw, pdot, w2, far0) || !si::mul(far0, k, far0) || !fits_long(near0) ||
      !fits_long(far0))
    return std::nullopt;
  if (!constant_atoms && (!si::mul(gx, ww1, nx) || !si::mul(gy, ww1, ny) || !si::mul(pw, w2, ww2) || !si::mul(gx, ww2, fx) ||
                          !si::mul(gy, ww2, fy) || !fits_long(nx) || !fits_long(ny) || !fits_long(fx) || !fits_long(fy)))
    return std::nullopt;
  curve.polynomial = primitive_affine_small(static_cast<long>(c), static_cast<long>(cx), static_cast<long>(cy));
  const IntegerPolynomial2& value = curve.polynomial;
  if (!value.is_zero() && value.degree_x() == 0 && value.degree_y() == 0) return false;   // a non-zero constant
  if (constant_atoms) {
    if (near0 < 0) return false;
  } else {
    curve.validity.reserve(2);
    curve.validity.emplace_back().atoms.push_back(
        primitive_affine_small(static_cast<long>(near0), static_cast<long>(nx), static_cast<long>(ny)));
  }
  if (constant_atoms) {
    if (far0 < 0) return false;
  } else {
    curve.validity.emplace_back().atoms.push_back(
        primitive_affine_small(static_cast<long>(far0), -static_cast<long>(fx), -static_cast<long>(fy)));
  }
  return true;
}

// The contact of `vertex` on `segment` and its validity clauses (a constant atom that holds is
// left out, as convert_validity does): false when the features never touch within both (the curve is then not
// kept; `curve` is left partly written). Machine integers first (front_contact_small), GMP's
// when they do not suffice.
bool front_contact(const FrontVertex& vertex, const FrontSegment& s, ContactCurve& curve) {
  const HomogeneousPoint& p = *vertex.p;
  if (const std::optional<bool> small = front_contact_small(p, s, curve)) return *small;
  return front_contact_gmp(p, s, curve);
}

// front_contact in GMP integers (any size).
bool front_contact_gmp(const HomogeneousPoint& p, const FrontSegment& s, ContactCurve& curve) {
  // (this thread's scratch integers, products accumulated in place with mpz_addmul /
  // mpz_submul: no integer allocated per call once they have grown)
  thread_local mpz_class c, cx, cy, scratch, ww1, pd;
  // value
  mpz_mul(ww1.get_mpz_t(), p.w.get_mpz_t(), s.w1->get_mpz_t());
  mpz_mul(pd.get_mpz_t(), p.x.get_mpz_t(), s.dy->get_mpz_t());
  mpz_submul(pd.get_mpz_t(), p.y.get_mpz_t(), s.dx->get_mpz_t());
  mpz_mul(c.get_mpz_t(), pd.get_mpz_t(), s.w1->get_mpz_t());
  mpz_submul(c.get_mpz_t(), s.cross1.get_mpz_t(), p.w.get_mpz_t());
  c *= *s.k;
  mpz_mul(cx.get_mpz_t(), s.kx.get_mpz_t(), ww1.get_mpz_t());
  mpz_mul(cy.get_mpz_t(), s.ky.get_mpz_t(), ww1.get_mpz_t());
  curve.polynomial = primitive_affine(c, cx, cy, scratch);
  const IntegerPolynomial2& value = curve.polynomial;
  if (!value.is_zero() && value.degree_x() == 0 && value.degree_y() == 0) return false;   // a non-zero constant
  // along >= 0, then |d|^2 - along >= 0 (in this order; constant atoms tested, not kept)
  const bool constant_atoms = sgn(s.gx) == 0 && sgn(s.gy) == 0;
  mpz_mul(pd.get_mpz_t(), p.x.get_mpz_t(), s.dx->get_mpz_t());
  mpz_addmul(pd.get_mpz_t(), p.y.get_mpz_t(), s.dy->get_mpz_t());
  mpz_mul(c.get_mpz_t(), pd.get_mpz_t(), s.w1->get_mpz_t());
  mpz_submul(c.get_mpz_t(), s.dot1.get_mpz_t(), p.w.get_mpz_t());
  c *= *s.k;
  if (constant_atoms) {
    if (sgn(c) < 0) return false;
  } else {
    mpz_mul(cx.get_mpz_t(), s.gx.get_mpz_t(), ww1.get_mpz_t());
    mpz_mul(cy.get_mpz_t(), s.gy.get_mpz_t(), ww1.get_mpz_t());
    curve.validity.reserve(2);
    curve.validity.emplace_back().atoms.push_back(primitive_affine(c, cx, cy, scratch));   // (no initializer_list copy)
  }
  mpz_mul(c.get_mpz_t(), s.dot2.get_mpz_t(), p.w.get_mpz_t());
  mpz_submul(c.get_mpz_t(), pd.get_mpz_t(), s.w2->get_mpz_t());
  c *= *s.k;
  if (constant_atoms) {
    if (sgn(c) < 0) return false;
  } else {
    mpz_mul(ww1.get_mpz_t(), p.w.get_mpz_t(), s.w2->get_mpz_t());   // now W W2
    mpz_mul(cx.get_mpz_t(), s.gx.get_mpz_t(), ww1.get_mpz_t());
    mpz_mul(cy.get_mpz_t(), s.gy.get_mpz_t(), ww1.get_mpz_t());
    mpz_neg(cx.get_mpz_t(), cx.get_mpz_t());
    mpz_neg(cy.get_mpz_t(), cy.get_mpz_t());
    curve.validity.emplace_back().atoms.push_back(primitive_affine(c, cx, cy, scratch));
  }
  return true;
}

// Validity clauses as integer polynomials; returns false when some clause can never hold.
// `zero_not_strict` (when true is returned): some clause holds everywhere only because an atom
// is identically zero, none being a positive constant (not strict: corner_entry_atoms).
// `sources` (when true is returned): (clause, atom) of each atom kept, in order; `constants`: per
// atom of `validity`, in order, whether it normalised to a non-zero constant.
bool convert_validity(const kernels::Validity<Polynomial>& validity,
                      std::vector<ValidityClause>& clauses, bool& zero_not_strict,
                      std::vector<std::pair<int, int>>* sources = nullptr, std::vector<char>* constants = nullptr) {
  zero_not_strict = false;
  std::size_t first_source = sources ? sources->size() : 0;
  for (std::size_t k = 0; k < validity.clauses.size(); ++k) {
    const auto& clause = validity.clauses[k];
    if (sources) sources->resize(first_source);   // this clause's atoms, if it is kept
    ValidityClause converted;
    bool always = false;
    bool possible = false;
    bool strict = false, zero = false;
    for (int i = 0; i < clause.count; ++i) {
      IntegerPolynomial2 atom =
          normalized_integer_polynomial(clause.atoms[static_cast<std::size_t>(i)]);
      const bool constant = atom.degree_x() <= 0 && atom.degree_y() <= 0;
      if (constants) constants->push_back(constant && !atom.is_zero() ? 1 : 0);
      if (constant) {
        // constant atom: zero or positive holds everywhere, negative never
        const int s = atom.is_zero() ? 0 : sgn(atom.coefficients[0][0]);
        strict = strict || s > 0;
        zero = zero || s == 0;
        if (s >= 0) always = true;
        continue;
      }
      possible = true;
      converted.atoms.push_back(std::move(atom));
      if (sources) sources->emplace_back(static_cast<int>(k), i);
    }
    if (zero && !strict) zero_not_strict = true;
    if (always) continue;
    if (!possible) return false;
    clauses.push_back(std::move(converted));
    if (sources) first_source = sources->size();
  }
  if (sources) sources->resize(first_source);
  return true;
}

// Corner-entry atoms of a vertex contact (ContactCurve::corner_entry): vertex v of one part
// (tangents `out` along the edge it starts, `in` along the edge it ends, forward, body frame)
// against a segment or arc b of the other part, whose outward normal at the contact point is n.
// The atoms are w (out . n) and -w (in . n) in world coordinates (w > 0: the pair's weights).
//
// Why an atom < 0 with every validity clause strict proves the interiors overlap, at every
// configuration of the curve where that holds (the generalisation of corner_enters_segment to
// rotating parts, where the directions turn with the configuration):
// - On the curve the vertex lies on b's support; validity holds strictly, so the contact point
//   lies in b's relative interior (the foot strictly inside the segment, the direction strictly
//   inside the arc's sector). Near it the other part is the open side of b's curve against n:
//   a point z near the contact point with (z - v) . n < 0 of first order is in its interior
//   (b is a line or circle, whose deviation from its tangent is of second order).
// - The vertex is not a spike (checked exactly below), so the part's interior near v contains,
//   for every small enough rotation of `out` to its left (the material side of the edge it
//   starts) and of -in to its right, the points v + e d for small e > 0 (edges are segments or
//   circular arcs: second-order deviation from their tangents).
// - out . n < 0 (or -in . n < 0): a small rotation d of out (or -in) into the part keeps
//   d . n < 0, so v + e d lies in both interiors for small e.
// Interior overlap is an open condition of the configuration: such a configuration lies in the
// interior of blocked space, and a piece of the curve made of such configurations bounds
// nothing. Empty (no claim) for other contact types, for a spike, and when a validity clause
// was dropped as holding everywhere only because an atom is identically zero (not strict).
// The atoms' values before normalisation, w (out . n) and then -w (in . n), in any kernel
// number type T (`constant`: a body datum as T); empty when there is no claim for the pair's
// features (the cases above but the validity's, which is the caller's: corner_entry_atoms).
template <class T, class Constant>
std::vector<T> corner_entry_values(const Model& model, const BodyFeature& fa, const BodyFeature& fb,
                                   const kernels::FeatureGeometry<Rational>& ga, const kernels::FeatureGeometry<Rational>& gb,
                                   const kernels::Pose<T>& a, const kernels::Pose<T>& b, Constant&& constant_of) {
  using Shape = kernels::FeatureShape;
  using Vector = kernels::Vector<T>;
  const bool vertex_first = ga.shape == Shape::vertex;
  if (vertex_first == (gb.shape == Shape::vertex)) return {};
  const kernels::FeatureGeometry<Rational>& other = vertex_first ? gb : ga;
  if (other.shape != Shape::segment && other.shape != Shape::arc) return {};
  const FeatureDirections corner = feature_directions(model, vertex_first ? fa : fb);
  if (sgn(cross(corner.in, corner.out)) == 0 && sgn(dot(corner.in, corner.out)) < 0) return {};   // a spike
  auto constant = [&](const Rational& x, const Rational& y) { return Vector{constant_of(x), constant_of(y)}; };
  auto on_vertex_part = [&](const Point& u) {
    return vertex_first ? kernels::first_direction(constant(u.x, u.y)) : kernels::second_direction(constant(u.x, u.y));
  };
  kernels::PairVector<T> normal;
  if (other.shape == Shape::segment) {
    const kernels::Vector<Rational> d = other.target - other.point;
    const Vector n = constant(d.y, Rational(-d.x));   // right normal: out of the material
    normal = vertex_first ? kernels::second_direction(n) : kernels::first_direction(n);
  } else {
    // the contact point minus the arc's centre (out of a convex arc's material)
    normal = vertex_first ? kernels::point_difference(a, constant(ga.point.x, ga.point.y), b, constant(gb.center.x, gb.center.y))
                          : kernels::detail::negated(kernels::point_difference(a, constant(ga.center.x, ga.center.y), b,
                                                                               constant(gb.point.x, gb.point.y)));
    if (!other.convex) normal = kernels::detail::negated(normal);
  }
  std::vector<T> values;
  for (int k = 0; k < 2; ++k) {
    T value = kernels::dot_homogeneous(on_vertex_part(k == 0 ? corner.out : corner.in), normal, a, b);
    values.push_back(k == 0 ? value : T(-value));
  }
  return values;
}

// The atoms from corner_entry_values (Polynomial): normalised, constants >= 0 dropped; none when
// a validity clause was dropped as holding everywhere only because an atom is identically zero
// (the atoms classified once, by convert_validity).
// `sources`: the index in `values` of each atom kept; `constants`: per value, whether it normalised
// to a non-zero constant.
std::vector<IntegerPolynomial2> corner_entry_atoms(const std::vector<Polynomial>& values, bool validity_zero_not_strict,
                                                   std::vector<int>* sources, std::vector<char>* constants) {
  if (validity_zero_not_strict) return {};
  std::vector<IntegerPolynomial2> atoms;
  for (std::size_t k = 0; k < values.size(); ++k) {
    IntegerPolynomial2 atom = normalized_integer_polynomial(values[k]);
    constants->push_back(atom.degree_x() <= 0 && atom.degree_y() <= 0 && !atom.is_zero() ? 1 : 0);
    // a constant >= 0 never certifies
    if (atom.degree_x() <= 0 && atom.degree_y() <= 0 && (atom.is_zero() || sgn(atom.coefficients[0][0]) >= 0)) continue;
    atoms.push_back(std::move(atom));
    sources->push_back(static_cast<int>(k));
  }
  return atoms;
}


}  // namespace

// ============================================================================ broad phase

namespace {

// World box of a feature swept over a chart box (double, grown by a generous margin: it only
// skips pairs that cannot touch).
struct SweptBox {
  double x_lo, x_hi, y_lo, y_hi;
  int index;
};

SweptBox swept_box(const SweptFeature& swept, int side, const Part& part, bool moves, const ChartAxis& axis,
                   int index) {
  SweptBox box{swept.box_x.lo, swept.box_x.hi, swept.box_y.lo, swept.box_y.hi, index};
  constexpr double pi = 3.14159265358979323846;
  if (moves && part.motion.kind == Motion::Kind::rotation) {
    double px = part.motion.pivot.x.get_d(), py = part.motion.pivot.y.get_d();
    double r0 = std::max(0.0, swept.radial[side].lo), r1 = swept.radial[side].hi;
    double margin = 1e-7 * (1 + std::fabs(px) + std::fabs(py) + r1);
    // polar angles of the static box about the pivot (full turn if the box holds the pivot)
    bool full = px >= box.x_lo - margin && px <= box.x_hi + margin && py >= box.y_lo - margin &&
                py <= box.y_hi + margin;
    double a0 = 0, a1 = 2 * pi;
    if (!full) {
      double centre = std::atan2(0.5 * (box.y_lo + box.y_hi) - py, 0.5 * (box.x_lo + box.x_hi) - px);
      double low = 0, high = 0;
      for (double cx : {box.x_lo, box.x_hi})
        for (double cy : {box.y_lo, box.y_hi}) {
          double d = std::remainder(std::atan2(cy - py, cx - px) - centre, 2 * pi);
          low = std::min(low, d);
          high = std::max(high, d);
        }
      double c = axis.half_turn ? pi : 0.0;
      double t0 = c + 2 * std::atan(axis.lo.get_d()), t1 = c + 2 * std::atan(axis.hi.get_d());
      a0 = centre + low + t0 - 1e-9;
      a1 = centre + high + t1 + 1e-9;
      if (a1 - a0 >= 2 * pi) full = true;
    }
    if (full) return {px - r1 - margin, px + r1 + margin, py - r1 - margin, py + r1 + margin, index};
    double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
    auto add = [&](double r, double a) {
      double x = px + r * std::cos(a), y = py + r * std::sin(a);
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
    };
    for (double r : {r0, r1})
      for (double a : {a0, a1}) add(r, a);
    // extreme points of the outer circle inside the angle range
    for (double k = std::ceil(a0 / (0.5 * pi)); k * 0.5 * pi <= a1; k += 1) add(r1, k * 0.5 * pi);
    return {x_lo - margin, x_hi + margin, y_lo - margin, y_hi + margin, index};
  }
  double margin = 1e-9 * (1 + std::fabs(box.x_lo) + std::fabs(box.x_hi) + std::fabs(box.y_lo) + std::fabs(box.y_hi));
  box.x_lo -= margin;
  box.x_hi += margin;
  box.y_lo -= margin;
  box.y_hi += margin;
  return box;
}

// Pairs (index in a, index in b) whose boxes meet, ascending.
std::vector<std::pair<int, int>> meeting_boxes(std::vector<SweptBox> a, std::vector<SweptBox> b) {
  auto by_start = [](const SweptBox& p, const SweptBox& q) { return p.x_lo < q.x_lo; };
  std::sort(a.begin(), a.end(), by_start);
  std::sort(b.begin(), b.end(), by_start);
  std::vector<std::pair<int, int>> result;
  std::array<const std::vector<SweptBox>*, 2> lists{&a, &b};
  std::array<std::vector<const SweptBox*>, 2> active;
  std::size_t next[2] = {0, 0};
  while (next[0] < a.size() || next[1] < b.size()) {
    int side = next[1] >= b.size() || (next[0] < a.size() && a[next[0]].x_lo <= b[next[1]].x_lo) ? 0 : 1;
    const SweptBox& box = (*lists[static_cast<std::size_t>(side)])[next[side]++];
    auto& others = active[static_cast<std::size_t>(1 - side)];
    std::erase_if(others, [&](const SweptBox* e) { return e->x_hi < box.x_lo; });
    for (const SweptBox* other : others)
      if (!(other->y_hi < box.y_lo || other->y_lo > box.y_hi))
        result.emplace_back(side == 0 ? box.index : other->index, side == 0 ? other->index : box.index);
    active[static_cast<std::size_t>(side)].push_back(&box);
  }
  std::sort(result.begin(), result.end());
  return result;
}

}  // namespace

// ============================================================================ curves

std::vector<ContactCurve> generate_contact_curves(const Model& model, const PairAxes& axes,
                                                  const ChartAxis& x, const ChartAxis& y,
                                                  CurveStatistics* statistics) {
  return generate_contact_curves(model, axes, x, y, statistics, CurveOptions{});
}

std::vector<ContactCurve> generate_contact_curves(const Model& model, const PairAxes& axes,
                                                  const ChartAxis& x, const ChartAxis& y,
                                                  CurveStatistics* statistics,
                                                  const CurveOptions& options) {
  return CurveGenerator(model, axes, options).generate(x, y, statistics);
}

std::size_t inscribed_disk_parts_computed() {
  InscribedDiskMemo& memo = inscribed_disk_memo();
  std::lock_guard<std::mutex> lock(memo.mutex);
  return memo.computed;
}

void clear_inscribed_disk_memo() {
  InscribedDiskMemo& memo = inscribed_disk_memo();
  std::lock_guard<std::mutex> lock(memo.mutex);
  memo.entries.clear();
}

namespace {

// A feature pair's curve as formed in the first chart kind that needed it, with what carries
// each of its normalised polynomials to the other half-turn kinds by reflection
// (curves/half_turn_memo.hpp): every raw kernel quantity's degrees in x and y and whether it
// normalised to a non-zero constant. The quantities' degrees in the rotation triples are found
// when a reflection is asked for (TripleDegree: most pairs are never asked). A constant C of one
// kind is C x^(2k') in the other (a factor vanishing at the half turn), and a monomial c x^(2k')
// reflects to a constant: the formation's decisions on constants (a constant curve is not kept,
// constant atoms are dropped or decide their clause, constant corner-entry atoms are dropped or
// kept) are the same in both kinds only when every constant stays one (k' = 0) and every other
// polynomial the curve keeps stays non-constant; otherwise the curve is formed again.
struct PairQuantities {
  struct Source {
    int clause = 0, index = 0;   // validity atom: clause and atom; corner-entry value: index
    int degree[2] = {-1, -1};    // the raw quantity's degrees in x and y (-1: zero)
    bool constant = false;       // normalised to a non-zero constant
  };
  bool x_half = false, y_half = false;   // the chart kind of `formed` (kept only)
  std::shared_ptr<const FormedCurve> formed;
  Source value;
  std::vector<Source> raw_atoms, raw_entry;   // every validity atom (clause by clause), every corner-entry value
  std::vector<std::size_t> atoms;   // per atom of curve.validity, clause by clause: its index in raw_atoms
  std::vector<std::size_t> entry;   // per corner-entry atom: its index in raw_entry
};

}  // namespace

struct CurveGenerator::Data {
  const Model& model;
  PairAxes axes;
  CurveOptions options;
  std::vector<BodyFeature> features_a, features_b;
  std::size_t reflex_vertices_skipped = 0;
  std::vector<BodyDisk> disks_a, disks_b;
  // the parts' inscribed disks (the cull without a grid), computed on the first cull: a slicer
  // that takes a congruent pair's selections never culls
  // (shared with every generator of a part with the same loops: inscribed_disks)
  mutable std::shared_ptr<const std::vector<Core>> cores_a, cores_b;
  std::vector<SweptFeature> static_a, static_b;   // Culler::describe_static, chart independent
  bool polygons = true;   // every feature of both parts is a vertex or a segment
  // The features' exact body-frame geometry, chart independent (formed once, not per tile).
  std::vector<kernels::FeatureGeometry<Rational>> geometry_a, geometry_b;
  // A feature pair's exact curve depends on the chart only through the half-turn flags of its
  // two axes (the poses of pair_poses), not on the chart box: an operating region's tiles of
  // one chart, and the charts of one kind, share it. Each pair's curve (or its absence:
  // nullopt) is formed once, kept here for the next tiles, under the mutex (generate() may run
  // on several threads). The key: pair index, then the two half-turn bits.
  // (curves/formed_store.hpp; shared with other generators of an equal model and pair while a
  // SharedContactCurves lives on the thread that made this one)
  using Formed = FormedCurve;
  std::shared_ptr<FormedStore> formed;
  // generate() takes the polygon front end (a translating polygon pair without the blocked-space
  // cull): the general path's feature geometry is not formed for it
  bool front_end = false;
  mutable std::once_flag cores_once;
  // The front end's chart-independent data: the features' directions (cone_pairs) and their
  // homogeneous integer forms (front_contact), indexed through front_index by feature index.
  std::vector<DirectedFeature> vertices_a, segments_a, vertices_b, segments_b;
  std::vector<Direction> directions_a, directions_b;   // per edge of the part: what the above point to
  std::vector<std::size_t> front_index_a, front_index_b;
  std::vector<FrontVertex> front_vertices_a, front_vertices_b;
  std::vector<FrontSegment> front_segments_a, front_segments_b;
  // what the front end's features point to: per part, its edges' homogeneous ends (each edge's
  // source, then the open edges' targets) and the chart shifts' difference over its k
  std::vector<HomogeneousPoint> ends_a, ends_b;
  IntegerShift front_shift_a, front_shift_b;
  std::uint64_t id = 0;   // this generator's number, unique in the process (FormedCurve::maker)
  // The parts' motions for the swept-region cull, chart independent: every generate() reads it
  // with its own chart box's travel (Culler::travel_over) instead of building a Culler again.
  std::optional<Culler> culler;
  // The broad phase's swept boxes of a moving rotating part over one axis interval (swept_box of
  // each of its features: trigonometry per feature), kept for the next chart boxes with the same
  // interval — an operating region's tiles of one column share the first part's, those of one
  // row the second's (session 46). A pure function of (side, axis) for a rotating part (its
  // features' static boxes do not travel), so the boxes are the same with or without the memo.
  // Under the mutex (generate() may run on several threads); emptied when it holds
  // swept_capacity intervals.
  struct SweptKey {
    int side = 0;
    bool half_turn = false;
    Rational lo, hi;
    bool operator<(const SweptKey& o) const {
      if (side != o.side) return side < o.side;
      if (half_turn != o.half_turn) return half_turn < o.half_turn;
      if (int c = cmp(lo, o.lo); c != 0) return c < 0;
      return cmp(hi, o.hi) < 0;
    }
  };
  static constexpr std::size_t swept_capacity = 1024;
  mutable std::mutex swept_mutex;
  mutable std::map<SweptKey, std::shared_ptr<const std::vector<SweptBox>>> swept_memo;
  // A feature pair's kernel quantities as formed in the first chart kind that needed them
  // (PairQuantities): another half-turn kind takes them by reflection. Key: the pair's index;
  // under the mutex.
  mutable std::mutex quantities_mutex;
  mutable std::unordered_map<std::uint64_t, std::shared_ptr<const PairQuantities>> quantities;
};

namespace {

// The pose in TripleDegree: a rotating part's c, s, w of degree one in the triple of its
// chart variable (x when its polynomials are in x), every other datum of degree zero (or zero).
kernels::Pose<TripleDegree> triple_degree_pose(const kernels::Pose<Polynomial>& p) {
  auto of = [](const Polynomial& q) { return TripleDegree(q.is_zero() ? 0 : 1); };
  kernels::Pose<TripleDegree> d;
  d.rotates = p.rotates;
  d.translates = p.translates;
  if (p.rotates) {
    d.c = d.s = d.w = TripleDegree::unit(p.w.rows() > 1 ? 0 : 1);
  } else {
    d.c = of(p.c);
    d.s = of(p.s);
    d.w = of(p.w);
  }
  d.pivot = {of(p.pivot.x), of(p.pivot.y)};
  d.shift = {of(p.shift.x), of(p.shift.y)};
  return d;
}

// A raw kernel quantity's record: its degrees in x and y, and whether it normalises to a
// non-zero constant.
PairQuantities::Source source_of(const Polynomial& raw, bool constant, int clause = 0, int index = 0) {
  PairQuantities::Source source;
  source.clause = clause;
  source.index = index;
  source.constant = constant;
  for (int i = 0; i < raw.rows(); ++i)
    for (int j = 0; j < raw.columns(); ++j)
      if (sgn(raw.numerator(i, j)) != 0) {
        source.degree[0] = std::max(source.degree[0], i);
        source.degree[1] = std::max(source.degree[1], j);
      }
  return source;
}

// The degree bound with which the normalised form (degree `normalised` in `variable`) of the raw
// quantity `source`, whose terms have triple degrees `degree`, reflects in `variable`, or -1:
// raw = content (1 + t^2)^m N, so m = (deg raw - deg N) / 2 and N reflects with k - m.
int normalised_degree(const PairQuantities::Source& source, const TripleDegree& degree, int normalised, int variable) {
  const int raw = source.degree[variable];
  if (raw < 0) return 0;   // zero reflects to zero
  const int k = degree.homogeneous(variable);
  const int removed = raw - normalised;
  if (k < 0 || raw > 2 * k || removed < 0 || removed % 2 != 0) return -1;
  return k - removed / 2;
}

// `q`'s curve carried to the chart kind (x_half, y_half) by reflection; nullptr when some
// polynomial does not reflect in a variable it must be reflected in, or a constant would not
// stay one (PairQuantities). `degrees`: the pair's kernel on TripleDegree; `entry_degrees`:
// corner_entry_values on TripleDegree (made on demand).
template <class EntryDegrees>
std::shared_ptr<FormedCurve> reflected(const PairQuantities& q, bool x_half, bool y_half,
                                       const kernels::ContactFunction<TripleDegree>& degrees, EntryDegrees&& entry_degrees) {
  const bool in_x = x_half != q.x_half, in_y = y_half != q.y_half;
  auto bounds = [&](const PairQuantities::Source& source, const TripleDegree& degree, int nx, int ny) {
    return std::array<int, 2>{in_x ? normalised_degree(source, degree, nx, 0) : -1,
                              in_y ? normalised_degree(source, degree, ny, 1) : -1};
  };
  auto usable = [&](const std::array<int, 2>& k) { return !(in_x && k[0] < 0) && !(in_y && k[1] < 0); };
  // constants stay constants: k' = 0 in every reflected variable
  auto stays_constant = [&](const PairQuantities::Source& source, const TripleDegree& degree) {
    const std::array<int, 2> k = bounds(source, degree, 0, 0);
    return usable(k) && (!in_x || k[0] == 0) && (!in_y || k[1] == 0);
  };
  auto atom_degree = [&](const PairQuantities::Source& source) -> const TripleDegree& {
    const auto& clause = degrees.validity.clauses[static_cast<std::size_t>(source.clause)];
    return clause.atoms[static_cast<std::size_t>(source.index)];
  };
  for (const PairQuantities::Source& source : q.raw_atoms)
    if (source.constant && !stays_constant(source, atom_degree(source))) return nullptr;
  std::vector<TripleDegree> entry;
  if (!q.raw_entry.empty()) {
    entry = entry_degrees();
    for (const PairQuantities::Source& source : q.raw_entry)
      if (source.constant && !stays_constant(source, entry[static_cast<std::size_t>(source.index)])) return nullptr;
  }
  auto made = std::make_shared<FormedCurve>();
  made->kept = true;
  made->curve = q.formed->curve;
  // a kept polynomial: reflected, and non-constant if it was
  auto reflect = [&](IntegerPolynomial2& p, const PairQuantities::Source& source, const TripleDegree& degree) {
    const bool varying = p.degree_x() > 0 || p.degree_y() > 0;
    const std::array<int, 2> k = bounds(source, degree, p.degree_x(), p.degree_y());
    if (!usable(k)) return false;
    std::optional<IntegerPolynomial2> r = half_turn_reflected(p, k[0], k[1]);
    if (!r || (varying && r->degree_x() <= 0 && r->degree_y() <= 0)) return false;
    p = std::move(*r);
    return true;
  };
  if (!reflect(made->curve.polynomial, q.value, degrees.value)) return nullptr;
  std::size_t atom = 0;
  for (ValidityClause& clause : made->curve.validity)
    for (IntegerPolynomial2& p : clause.atoms) {
      const PairQuantities::Source& source = q.raw_atoms[q.atoms[atom++]];
      if (!reflect(p, source, atom_degree(source))) return nullptr;
    }
  for (std::size_t e = 0; e < made->curve.corner_entry.size(); ++e) {
    const PairQuantities::Source& source = q.raw_entry[q.entry[e]];
    if (!reflect(made->curve.corner_entry[e], source, entry[static_cast<std::size_t>(source.index)])) return nullptr;
  }
  return made;
}

}  // namespace

CurveGenerator::CurveGenerator(const Model& model, const PairAxes& axes, const CurveOptions& options)
    : data_(new Data{model, axes, options, {}, {}, 0, {}, {}, {}, {}, {}, {}, true, {}, {},
                     formed_store(model, axes, options.cull_blocked_space), false, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {},
                     {}, {}, 0, {}, {}, {}}) {
  Data& d = *data_;
  static std::atomic<std::uint64_t> generators{0};
  d.id = ++generators;
  // labels only for the kept curves (feature_label): most feature pairs are never kept
  d.features_a = part_features(model, axes.first, &d.reflex_vertices_skipped, false);
  d.features_b = part_features(model, axes.second, &d.reflex_vertices_skipped, false);
  for (const auto* features : {&d.features_a, &d.features_b})
    for (const BodyFeature& f : *features)
      if (f.ref.kind != FeatureRef::Kind::vertex && f.ref.kind != FeatureRef::Kind::segment) d.polygons = false;
  {
    // the pivots and directions of the motions do not depend on the chart
    ChartAxis any;
    any.kind = ChartAxis::Kind::translation;
    const Culler& culler =
        d.culler.emplace(model.parts.at(axes.first), axes.first_moves, any, model.parts.at(axes.second), axes.second_moves, any);
    for (const BodyFeature& f : d.features_a) d.static_a.push_back(culler.describe_static(f));
    for (const BodyFeature& f : d.features_b) d.static_b.push_back(culler.describe_static(f));
  }
  auto without_rotation = [](const Part& part) {
    return part.motion.kind == Motion::Kind::fixed || part.motion.kind == Motion::Kind::translation;
  };
  d.front_end = without_rotation(model.parts.at(axes.first)) && without_rotation(model.parts.at(axes.second)) &&
                d.polygons && options.polygon_front_end && !options.cull_blocked_space;
  if (!d.front_end) {
    for (const BodyFeature& f : d.features_a) d.geometry_a.push_back(feature_geometry(f));
    for (const BodyFeature& f : d.features_b) d.geometry_b.push_back(feature_geometry(f));
  } else {
    // the parts' world shifts as affine forms of the chart coordinates
    auto shift_of = [&](const Part& part, bool moves, int variable) {
      Shift shift{Point{Rational(0), Rational(0)}, Point{Rational(0), Rational(0)}};
      if (moves && part.motion.kind == Motion::Kind::translation) (variable == 0 ? shift.x : shift.y) = part.motion.direction;
      return shift;
    };
    const Shift shift_a = shift_of(model.parts.at(axes.first), axes.first_moves, 0);
    const Shift shift_b = shift_of(model.parts.at(axes.second), axes.second_moves, axes.first_moves ? 1 : 0);
    // segments of one part meet the other part's vertices: u = vertex shift - segment shift
    auto prepare = [&](std::size_t part_index, const std::vector<BodyFeature>& features, const Shift& own,
                       const Shift& other, std::vector<Direction>& directions, std::vector<DirectedFeature>& vertices,
                       std::vector<DirectedFeature>& segments,
                       std::vector<std::size_t>& index, std::vector<FrontVertex>& front_vertices,
                       std::vector<FrontSegment>& front_segments, std::vector<HomogeneousPoint>& ends, IntegerShift& u) {
      u = integer_shift(difference(other.x, own.x), difference(other.y, own.y));
      // every edge of the part once: its homogeneous ends, each made once (a closed loop's
      // target is the next edge's source) and read in place, and its direction
      const Part& part = model.parts.at(part_index);
      std::vector<std::size_t> loop_start;
      std::size_t edge_count = 0;
      for (const Loop& loop : part.loops) edge_count += loop.edges.size();
      // `ends`: each edge's source, then the open edges' targets (kept: the features point to them)
      std::vector<std::size_t> target_end;      // per edge: its target in `ends`
      ends.reserve(edge_count);
      target_end.reserve(edge_count);
      directions.reserve(edge_count);
      for (const Loop& loop : part.loops) {
        loop_start.push_back(ends.size());
        for (const Edge& edge : loop.edges) ends.push_back(homogeneous(edge.source));
      }
      for (std::size_t l = 0; l < part.loops.size(); ++l) {
        const Loop& loop = part.loops[l];
        const std::size_t n = loop.edges.size();
        for (std::size_t e = 0; e < n; ++e) {
          const Edge& edge = loop.edges[e];
          const bool closes = edge.target == loop.edges[(e + 1) % n].source;
          if (closes) {
            target_end.push_back(loop_start[l] + (e + 1) % n);
          } else {
            target_end.push_back(ends.size());
            ends.push_back(homogeneous(edge.target));
          }
        }
      }
      for (std::size_t e = 0; e < edge_count; ++e) {
        mpz_class dx, dy;   // (moved into the direction: its integers, no rationals)
        front_direction(ends[e], ends[target_end[e]], dx, dy);
        directions.push_back(Direction::of(std::move(dx), std::move(dy)));
      }
      index.resize(features.size());
      vertices.reserve(features.size());
      segments.reserve(features.size());
      front_vertices.reserve(features.size());
      front_segments.reserve(features.size());
      for (std::size_t i = 0; i < features.size(); ++i) {
        const FeatureRef& ref = features[i].ref;
        const std::size_t n = part.loops.at(ref.loop).edges.size();
        const std::size_t e = loop_start[ref.loop] + ref.edge;
        if (ref.kind == FeatureRef::Kind::vertex) {
          // tangents: out along this edge, in along the previous one (feature_directions)
          const std::size_t previous = loop_start[ref.loop] + (ref.edge + n - 1) % n;
          vertices.push_back(DirectedFeature{static_cast<int>(i), &directions[e], &directions[previous]});
          index[i] = front_vertices.size();
          front_vertices.push_back(FrontVertex{&ends[e]});
        } else {
          segments.push_back(DirectedFeature{static_cast<int>(i), &directions[e], nullptr});
          index[i] = front_segments.size();
          // (D is the direction's numerators: a canonical rational of an integer has
          // denominator 1)
          front_segments.push_back(
              front_segment(ends[e], ends[target_end[e]], directions[e].x, directions[e].y, u));
        }
      }
    };
    prepare(axes.first, d.features_a, shift_a, shift_b, d.directions_a, d.vertices_a, d.segments_a, d.front_index_a, d.front_vertices_a,
            d.front_segments_a, d.ends_a, d.front_shift_a);
    prepare(axes.second, d.features_b, shift_b, shift_a, d.directions_b, d.vertices_b, d.segments_b, d.front_index_b, d.front_vertices_b,
            d.front_segments_b, d.ends_b, d.front_shift_b);
  }
  if (options.cull_blocked_space) {
    for (const BodyFeature& f : d.features_a) d.disks_a.push_back(body_disk(f));
    for (const BodyFeature& f : d.features_b) d.disks_b.push_back(body_disk(f));
  }
}

CurveGenerator::~CurveGenerator() = default;

std::vector<ContactCurve> CurveGenerator::generate(const ChartAxis& x, const ChartAxis& y,
                                                   CurveStatistics* statistics, BlockedCells* grid) const {
  return generate_impl(x, y, statistics, grid, nullptr, nullptr, nullptr);
}

std::vector<CurveGenerator::FeaturePair> CurveGenerator::select(const ChartAxis& x, const ChartAxis& y) const {
  if (data_->front_end || data_->options.blocked_grid)
    throw GeometryError("internal: select() is for the general path of the curve generator without a grid");
  std::vector<FeaturePair> selected;
  generate_impl(x, y, nullptr, nullptr, nullptr, &selected, nullptr);
  return selected;
}

struct CurveGenerator::Selection::Impl {
  std::vector<FeaturePair> pairs;   // the candidates after the broad phase, ascending
  std::vector<char> needed;
  std::vector<char> returned;   // by extend() so far
  std::optional<BlockedSpaceCuller> culler;
};

CurveGenerator::Selection::Selection() : impl_(new Impl) {}
CurveGenerator::Selection::~Selection() = default;

std::vector<CurveGenerator::FeaturePair> CurveGenerator::Selection::extend(
    int axis, const std::vector<std::pair<double, double>>& ranges) {
  Impl& impl = *impl_;
  if (impl.culler) {
    CullFilter filter{axis, ranges};
    impl.culler->walk(&filter);
  }
  std::vector<FeaturePair> added;
  for (std::size_t k = 0; k < impl.pairs.size(); ++k)
    if (impl.needed[k] && !impl.returned[k]) {
      impl.returned[k] = 1;
      added.push_back(impl.pairs[k]);
    }
  return added;
}

std::unique_ptr<CurveGenerator::Selection> CurveGenerator::incremental_select(const ChartAxis& x, const ChartAxis& y) const {
  if (data_->front_end || data_->options.blocked_grid)
    throw GeometryError("internal: incremental_select() is for the general path of the curve generator without a grid");
  const Data& d = *data_;
  std::unique_ptr<Selection> selection(new Selection);
  Selection::Impl& impl = *selection->impl_;
  generate_impl(x, y, nullptr, nullptr, nullptr, nullptr, &impl.pairs);
  // without the cull every candidate is kept at once (select())
  impl.needed.assign(impl.pairs.size(), d.options.cull_blocked_space ? 0 : 1);
  impl.returned.assign(impl.pairs.size(), 0);
  if (d.options.cull_blocked_space) {
    const Part& part_a = d.model.parts.at(d.axes.first);
    const Part& part_b = d.model.parts.at(d.axes.second);
    std::call_once(d.cores_once, [&] {
      d.cores_a = inscribed_disks(part_a);
      d.cores_b = inscribed_disks(part_b);
    });
    impl.culler.emplace(part_a, d.axes.first_moves, part_b, d.axes.second_moves, x, y, d.axes.dimension(), d.disks_a,
                        d.disks_b, *d.cores_a, *d.cores_b);
    impl.culler->prepare(impl.pairs, impl.needed);
  }
  return selection;
}

std::vector<ContactCurve> CurveGenerator::generate_selected(const ChartAxis& x, const ChartAxis& y,
                                                            const std::vector<FeaturePair>& selected) const {
  if (data_->front_end || data_->options.blocked_grid)
    throw GeometryError("internal: generate_selected() is for the general path of the curve generator without a grid");
  return generate_impl(x, y, nullptr, nullptr, &selected, nullptr, nullptr);
}

std::string CurveGenerator::congruence_key() const {
  const Data& d = *data_;
  if (d.front_end) return {};
  const Part& part_a = d.model.parts.at(d.axes.first);
  const Part& part_b = d.model.parts.at(d.axes.second);
  Point origin{Rational(0), Rational(0)};
  if (!part_a.loops.empty() && !part_a.loops.front().edges.empty()) origin = part_a.loops.front().edges.front().source;
  std::string key;
  auto number = [&](const Rational& q) {
    key += q.get_str();
    key += ',';
  };
  auto point = [&](const Point& p) {
    number(Rational(p.x - origin.x));
    number(Rational(p.y - origin.y));
  };
  key += d.options.cull_blocked_space ? 'c' : '-';
  key += d.options.blocked_grid ? 'g' : '-';
  key += d.options.polygon_front_end ? 'p' : '-';
  key += d.axes.first_moves ? '1' : '0';
  key += d.axes.second_moves ? '1' : '0';
  for (const Part* part : {&part_a, &part_b}) {
    key += "|part:";
    key += std::to_string(static_cast<int>(part->motion.kind));
    key += ':';
    point(part->motion.pivot);
    number(part->motion.direction.x);
    number(part->motion.direction.y);
    for (const Loop& loop : part->loops) {
      key += loop.is_hole ? "|hole:" : "|loop:";
      for (const Edge& edge : loop.edges) {
        key += edge.is_arc() ? (edge.ccw ? "a+" : "a-") : "s";
        point(edge.source);
        point(edge.target);
        if (edge.is_arc()) {
          point(edge.center);
          number(edge.radius_squared);
        }
        key += ';';
      }
    }
  }
  return key;
}

std::vector<ContactCurve> CurveGenerator::generate_impl(const ChartAxis& x, const ChartAxis& y,
                                                        CurveStatistics* statistics, BlockedCells* grid,
                                                        const std::vector<FeaturePair>* selected_in,
                                                        std::vector<FeaturePair>* selected_out,
                                                        std::vector<FeaturePair>* candidates_out) const {
  const Data& d = *data_;
  const Model& model = d.model;
  const PairAxes& axes = d.axes;
  const CurveOptions& options = d.options;
  CurveStatistics local;
  CurveStatistics& stats = statistics ? *statistics : local;
  const Part& part_a = model.parts.at(axes.first);
  const Part& part_b = model.parts.at(axes.second);
  const std::vector<BodyFeature>& features_a = d.features_a;
  const std::vector<BodyFeature>& features_b = d.features_b;
  stats.reflex_vertices_skipped += d.reflex_vertices_skipped;

  const ChartAxis& second_axis = axes.first_moves ? y : x;
  const Culler& culler = *d.culler;
  const Culler::Travel travel = culler.travel_over(x, second_axis);
  std::vector<SweptFeature> swept_a;
  std::vector<SweptFeature> swept_b;
  swept_a.reserve(features_a.size());
  swept_b.reserve(features_b.size());
  // (a given selection needs no broad phase: the swept boxes stay empty)
  if (!selected_in) {
    for (const SweptFeature& f : d.static_a) swept_a.push_back(culler.travel(f, 0, travel));
    for (const SweptFeature& f : d.static_b) swept_b.push_back(culler.travel(f, 1, travel));
  }

  // Broad phase: world boxes of the features swept over the chart box (a rotation over the
  // box's angle range, not the whole turn), pairs whose boxes meet by a sweep in x; then the
  // swept-region culling, then blocked-space culling over the chart.
  std::vector<SweptBox> boxes_a, boxes_b;
  // one part's boxes over its axis: from the memo when the part rotates (swept_memo)
  auto part_boxes = [&](int side, const std::vector<SweptFeature>& swept, const Part& part, bool moves,
                        const ChartAxis& axis, std::vector<SweptBox>& boxes) {
    const bool remembered = !selected_in && swept_box_memo_switch() && moves &&
                            part.motion.kind == Motion::Kind::rotation;
    Data::SweptKey key;
    if (remembered) {
      key.side = side;
      key.half_turn = axis.half_turn;
      key.lo = axis.lo;
      key.hi = axis.hi;
      std::lock_guard<std::mutex> lock(d.swept_mutex);
      if (auto found = d.swept_memo.find(key); found != d.swept_memo.end()) {
        ++swept_box_memo_hits();
        boxes = *found->second;
        return;
      }
    }
    boxes.reserve(swept.size());
    for (std::size_t i = 0; i < swept.size(); ++i)
      boxes.push_back(swept_box(swept[i], side, part, moves, axis, static_cast<int>(i)));
    if (remembered) {
      auto kept = std::make_shared<const std::vector<SweptBox>>(boxes);
      std::lock_guard<std::mutex> lock(d.swept_mutex);
      if (d.swept_memo.size() >= Data::swept_capacity) d.swept_memo.clear();
      d.swept_memo.emplace(std::move(key), std::move(kept));
    }
  };
  part_boxes(0, swept_a, part_a, axes.first_moves, x, boxes_a);
  part_boxes(1, swept_b, part_b, axes.second_moves, second_axis, boxes_b);
  std::vector<std::pair<int, int>> pairs;
  auto without_rotation = [](const Part& part) {
    return part.motion.kind == Motion::Kind::fixed || part.motion.kind == Motion::Kind::translation;
  };
  const bool translating = without_rotation(part_a) && without_rotation(part_b);
  // A curve that passed the constant and validity tests: labelled, counted and kept.
  auto keep = [&](std::vector<ContactCurve>& out, ContactCurve&& curve, const BodyFeature& fa, const BodyFeature& fb) {
    curve.label = curve_label(model, fa.ref, fb.ref, curve.type);
    if (curve.polynomial.is_zero()) {
      ++stats.identically_zero;
    } else {
      ++stats.curves;
    }
    out.push_back(std::move(curve));
  };
  if (d.front_end) {
    // The polygon front end: the reduced convolution's pairs by the angular walk (cone_pairs),
    // then the same broad-phase box test and swept-region cull as the general path (so the
    // same pairs, in the same order), and each curve written down from the vertices.
    const std::vector<DirectedFeature>& vertices_a = d.vertices_a;
    const std::vector<DirectedFeature>& segments_a = d.segments_a;
    const std::vector<DirectedFeature>& vertices_b = d.vertices_b;
    const std::vector<DirectedFeature>& segments_b = d.segments_b;
    std::vector<std::pair<int, int>> reduced = cone_pairs(vertices_a, segments_b);
    for (auto [j, i] : cone_pairs(vertices_b, segments_a)) reduced.emplace_back(i, j);
    std::sort(reduced.begin(), reduced.end());
    auto meets = [](const SweptBox& a, const SweptBox& b) {
      return !(a.x_hi < b.x_lo || b.x_hi < a.x_lo || a.y_hi < b.y_lo || b.y_hi < a.y_lo);
    };
    // statistics as the general path counts them: vertex–segment pairs whose boxes meet
    std::size_t considered = 0, kept = 0;
    for (const auto& v : vertices_a)
      for (const auto& t : segments_b) considered += meets(boxes_a[static_cast<std::size_t>(v.index)], boxes_b[static_cast<std::size_t>(t.index)]);
    for (const auto& t : segments_a)
      for (const auto& v : vertices_b) considered += meets(boxes_a[static_cast<std::size_t>(t.index)], boxes_b[static_cast<std::size_t>(v.index)]);
    stats.feature_pairs_considered += considered;
    for (auto [i, j] : reduced) {
      auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      if (!meets(boxes_a[ui], boxes_b[uj])) continue;
      ++kept;
      if (culler.never_touch(swept_a[ui], swept_b[uj])) {
        ++stats.feature_pairs_culled;
        continue;
      }
      pairs.emplace_back(i, j);
    }
    stats.feature_pairs_in_blocked_space += considered - kept;
    std::vector<ContactCurve> curves;
    curves.reserve(pairs.size());
    for (auto [i, j] : pairs) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      const BodyFeature& fa = features_a[ui];
      const BodyFeature& fb = features_b[uj];
      const bool vertex_first = fa.ref.kind == FeatureRef::Kind::vertex;
      const FrontVertex& vertex = vertex_first ? d.front_vertices_a[d.front_index_a[ui]] : d.front_vertices_b[d.front_index_b[uj]];
      const FrontSegment& segment = vertex_first ? d.front_segments_b[d.front_index_b[uj]] : d.front_segments_a[d.front_index_a[ui]];
      ContactCurve curve;
      curve.first = fa.ref;
      curve.second = fb.ref;
      curve.type = vertex_first ? ContactType::vertex_segment : ContactType::segment_vertex;
      curve.blocked_sign = kernels::blocked_sign;
      if (!front_contact(vertex, segment, curve)) continue;   // a non-zero constant, or never within both
      keep(curves, std::move(curve), fa, fb);
    }
    return curves;
  }
  auto constant = [](const Rational& value) { return Polynomial(value); };
  PairPoses<Polynomial> poses = pair_poses(model, axes, x, y, Polynomial::variable(0),
                                           Polynomial::variable(1), constant);
  const std::vector<kernels::FeatureGeometry<Rational>>& geometry_a = d.geometry_a;
  const std::vector<kernels::FeatureGeometry<Rational>>& geometry_b = d.geometry_b;
  std::vector<FeatureDirections> directions_a, directions_b;
  if (translating && !selected_in) {
    for (const BodyFeature& f : features_a) directions_a.push_back(feature_directions(model, f));
    for (const BodyFeature& f : features_b) directions_b.push_back(feature_directions(model, f));
  }
  // (a given selection: meeting_boxes of the empty box lists is empty)
  for (auto [i, j] : meeting_boxes(boxes_a, boxes_b)) {
    auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    const bool enters = translating && (corner_enters_segment(directions_a[ui], directions_b[uj]) ||
                                        corner_enters_segment(directions_b[uj], directions_a[ui]));
    if (!enters && !kernels::contact_type(geometry_a[ui], geometry_b[uj]).has_value()) continue;   // has_contact
    ++stats.feature_pairs_considered;
    if (enters) {
      ++stats.feature_pairs_in_blocked_space;
      continue;
    }
    if (culler.never_touch(swept_a[ui], swept_b[uj])) {
      ++stats.feature_pairs_culled;
      continue;
    }
    pairs.emplace_back(i, j);
  }
  // the merged cull: the caller's grid of the chart box (see BlockedCells)
  const bool on_grid = grid != nullptr && options.cull_blocked_space && options.blocked_grid;
  if (options.blocked_grid && options.cull_blocked_space && !on_grid)
    throw GeometryError("internal: the curve generator of a merged cull was given no blocked-space grid");
  if (candidates_out) {
    *candidates_out = std::move(pairs);   // incremental_select: its culler walks them
    return {};
  }
  if (selected_in) pairs = *selected_in;
  std::vector<char> needed(pairs.size(), options.cull_blocked_space && !selected_in ? 0 : 1);
  if (options.cull_blocked_space && !selected_in) {
    // the merged cull's grid when the caller has one, else the parts' inscribed disks
    if (!on_grid)
      std::call_once(d.cores_once, [&] {
        d.cores_a = inscribed_disks(part_a);
        d.cores_b = inscribed_disks(part_b);
      });
    static const std::vector<Core> no_cores;
    BlockedSpaceCuller blocked(part_a, axes.first_moves, part_b, axes.second_moves, x, y, axes.dimension(), d.disks_a,
                               d.disks_b, on_grid ? no_cores : *d.cores_a, on_grid ? no_cores : *d.cores_b,
                               on_grid ? grid : nullptr);
    blocked.run(pairs, needed);
  }

  if (selected_out) {
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (needed[k]) selected_out->push_back(pairs[k]);
    return {};
  }
  std::vector<ContactCurve> curves;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!needed[k]) {
      ++stats.feature_pairs_in_blocked_space;
      continue;
    }
    const auto ui = static_cast<std::size_t>(pairs[k].first), uj = static_cast<std::size_t>(pairs[k].second);
    const std::uint64_t key = ((static_cast<std::uint64_t>(ui) * features_b.size() + uj) << 2) |
                              (x.half_turn ? 2u : 0u) | (y.half_turn ? 1u : 0u);
    std::shared_ptr<const Data::Formed> formed;
    {
      std::lock_guard<std::mutex> lock(d.formed->mutex);
      auto found = d.formed->curves.find(key);
      if (found != d.formed->curves.end()) formed = found->second;
    }
    if (formed && formed->maker != d.id) ++*d.formed->reused;
    if (!formed) {
      const BodyFeature& fa = features_a[ui];
      const BodyFeature& fb = features_b[uj];
      // the curve of another half-turn kind carried here by reflection when that kind formed it
      // (and every polynomial reflects), else formed here (and remembered for the other kinds)
      const std::uint64_t pair = static_cast<std::uint64_t>(ui) * features_b.size() + uj;
      const bool memo = half_turn_memo_switch();
      std::shared_ptr<const PairQuantities> known;
      if (memo) {
        std::lock_guard<std::mutex> lock(d.quantities_mutex);
        auto found = d.quantities.find(pair);
        if (found != d.quantities.end()) known = found->second;
      }
      std::shared_ptr<Data::Formed> made;
      if (known && (known->x_half != x.half_turn || known->y_half != y.half_turn)) {
        // the degrees: the same kernels on TripleDegree (curves/half_turn_memo.hpp)
        const kernels::Pose<TripleDegree> da = triple_degree_pose(poses.first), db = triple_degree_pose(poses.second);
        auto degree_of = [](const Rational& r) { return TripleDegree(sgn(r) != 0 ? 1 : 0); };
        const std::optional<kernels::ContactFunction<TripleDegree>> degrees = kernels::contact_function(
            da, geometry_a[ui], db, geometry_b[uj], degree_of,
            kernels::ExactRootOrSquared{[](const Rational& square) { return exact_square_root(square); }});
        if (degrees)
          made = reflected(*known, x.half_turn, y.half_turn, *degrees, [&] {
            return corner_entry_values(model, fa, fb, geometry_a[ui], geometry_b[uj], da, db, degree_of);
          });
        if (made) ++half_turn_memo_hits();
      }
      if (!made) {
        made = std::make_shared<Data::Formed>();
        std::optional<kernels::ContactFunction<Polynomial>> kernel =
            contact_of(geometry_a[ui], geometry_b[uj], poses.first, poses.second);
        auto quantities = std::make_shared<PairQuantities>();   // (remembered when memo && !known)
        std::vector<std::pair<int, int>> atom_sources;
        std::vector<int> entry_sources;
        std::vector<char> constant_atoms, constant_entry;   // per raw atom / value: a non-zero constant
        std::vector<Polynomial> entry;
        if (kernel) {
          ContactCurve& curve = made->curve;
          curve.first = fa.ref;
          curve.second = fb.ref;
          curve.type = kernel->type;
          curve.polynomial = normalized_integer_polynomial(kernel->value);
          curve.blocked_sign = kernels::blocked_sign;
          const bool zero = curve.polynomial.is_zero();
          // a non-zero constant: these features never touch; an empty validity: never within both
          bool zero_not_strict = false;
          made->kept = (zero || curve.polynomial.degree_x() != 0 || curve.polynomial.degree_y() != 0) &&
                       convert_validity(kernel->validity, curve.validity, zero_not_strict, &atom_sources, &constant_atoms);
          if (made->kept) {
            curve.label = curve_label(model, fa.ref, fb.ref, curve.type);
            // (a blocked-space cull: not without it, so that tests compare against builds without)
            if (options.cull_blocked_space && !zero_not_strict) {
              entry = corner_entry_values(model, fa, fb, geometry_a[ui], geometry_b[uj], poses.first, poses.second,
                                          [](const Rational& r) { return Polynomial(r); });
              curve.corner_entry = corner_entry_atoms(entry, zero_not_strict, &entry_sources, &constant_entry);
            }
          } else {
            made->curve = ContactCurve{};   // nothing kept but the answer
          }
        }
        if (memo && !known && made->kept) {   // (a curve not kept is formed in each kind)
          quantities->x_half = x.half_turn;
          quantities->y_half = y.half_turn;
          quantities->formed = made;
          quantities->value = source_of(kernel->value, false);
          std::size_t raw = 0;
          for (std::size_t c = 0; c < kernel->validity.clauses.size(); ++c)
            for (int a = 0; a < kernel->validity.clauses[c].count; ++a)
              quantities->raw_atoms.push_back(source_of(kernel->validity.clauses[c].atoms[static_cast<std::size_t>(a)],
                                                        constant_atoms[raw++] != 0, static_cast<int>(c), a));
          for (const auto& [c, a] : atom_sources) {
            std::size_t index = 0;
            while (quantities->raw_atoms[index].clause != c || quantities->raw_atoms[index].index != a) ++index;
            quantities->atoms.push_back(index);
          }
          for (std::size_t e = 0; e < entry.size(); ++e)
            quantities->raw_entry.push_back(source_of(entry[e], constant_entry[e] != 0, 0, static_cast<int>(e)));
          for (int e : entry_sources) quantities->entry.push_back(static_cast<std::size_t>(e));
          std::lock_guard<std::mutex> lock(d.quantities_mutex);
          d.quantities.try_emplace(pair, std::move(quantities));
        }
      }
      made->maker = d.id;
      std::lock_guard<std::mutex> lock(d.formed->mutex);
      formed = d.formed->curves.try_emplace(key, std::move(made)).first->second;
    }
    if (!formed->kept) continue;
    if (formed->curve.polynomial.is_zero()) {
      ++stats.identically_zero;
    } else {
      ++stats.curves;
    }
    curves.push_back(formed->curve);
  }
  return curves;
}

// ============================================================================ chart layout

namespace {

constexpr mpfr_prec_t chart_bits = 256;

// Rational on the 10^-12 grid below (down) or above (up) an MPFR value, one extra step out
// (the product with 10^12 rounded outward too: the result is certainly below / above).
Rational grid_round(const mpfr_t value, bool up) {
  mpfr_t scaled;
  mpfr_init2(scaled, std::max(chart_bits, mpfr_get_prec(value) + 64));
  mpz_class denominator;
  mpz_ui_pow_ui(denominator.get_mpz_t(), 10, 12);
  mpfr_mul_z(scaled, value, denominator.get_mpz_t(), up ? MPFR_RNDU : MPFR_RNDD);
  if (up) {
    mpfr_ceil(scaled, scaled);
  } else {
    mpfr_floor(scaled, scaled);
  }
  mpz_class numerator;
  mpfr_get_z(numerator.get_mpz_t(), scaled, MPFR_RNDN);
  mpfr_clear(scaled);
  numerator += up ? 1 : -1;
  Rational result(numerator, denominator);
  result.canonicalize();
  return result;
}

// A rational certainly below (up: above) tan((L - m pi) / 2), for |L - m pi| < pi / 2: the
// MPFI enclosure's end at a precision above L's and m's magnitudes, on the grid.
Rational chart_edge(const Rational& L, const mpz_class& m, bool up) {
  const mpfr_prec_t bits = std::max(chart_bits, hipair::angle_bits(m, L) + chart_bits);
  mpfi_t angle;
  mpfi_init2(angle, bits);
  hipair::enclose_angle(angle, Rational(0), m, L, bits);   // m pi - L
  mpfi_neg(angle, angle);
  mpfi_div_2ui(angle, angle, 1);
  mpfi_tan(angle, angle);
  mpfr_t end;
  mpfr_init2(end, bits);
  if (up) {
    mpfi_get_right(end, angle);
  } else {
    mpfi_get_left(end, angle);
  }
  Rational out = grid_round(end, up);
  mpfr_clear(end);
  mpfi_clear(angle);
  return out;
}

// Chart intervals for a rotation with limits [lo, hi] (rad). Returns false when the range
// covers a full turn (then the caller uses the two full charts). Chart edges inside the range
// are rounded outward to the 10^-12 grid of t. Every decision is exact (session 54; before,
// the comparisons were made in MPFR at a fixed 256 bits, wrong for limits within 2^-250 of a
// chart seam or beyond 2^200 rad): whether the range is a whole turn, and whether the range
// in a chart, [lo, hi] - m pi (m = 2 k + centre), reaches -pi/2 or pi/2, are signs of
// 2 atan(0 or +-1) + m pi - L (hipair::angle_sign: MPFI refined until certain, never 0, pi
// being irrational); the edges' tangents are MPFI enclosures rounded outward. The turns k
// tried (four around an estimate) are a choice: charts that miss the range are skipped exactly.
bool limited_rotation_charts(const RationalInterval& limits, std::vector<ChartAxis>& charts) {
  // hi - lo >= 2 pi: 2 pi - (hi - lo) < 0 (never 0)
  if (hipair::angle_sign(Rational(0), mpz_class(2), Rational(limits.hi - limits.lo)) <= 0) return false;
  const mpfr_prec_t bits = hipair::angle_bits(mpz_class(0), limits.lo) + chart_bits;
  mpfr_t pi, two_pi, tmp;
  mpfr_inits2(bits, pi, two_pi, tmp, static_cast<mpfr_ptr>(nullptr));
  mpfr_const_pi(pi, MPFR_RNDN);
  mpfr_mul_ui(two_pi, pi, 2, MPFR_RNDN);
  for (int centre = 0; centre < 2; ++centre) {
    // The chart around c = centre * pi covers theta in [c - pi/2, c + pi/2] + 2 pi k.
    mpfr_mul_ui(tmp, pi, static_cast<unsigned long>(centre), MPFR_RNDN);
    mpfr_sub_q(tmp, tmp, limits.lo.get_mpq_t(), MPFR_RNDN);
    mpfr_neg(tmp, tmp, MPFR_RNDN);
    mpfr_div(tmp, tmp, two_pi, MPFR_RNDN);
    mpz_class first;
    mpfr_get_z(first.get_mpz_t(), tmp, MPFR_RNDD);
    first -= 1;
    for (mpz_class k = first; k <= first + 3; ++k) {
      const mpz_class m = 2 * k + centre;   // local angles theta - m pi
      // the range ends below the chart (hi - m pi < -pi/2: -pi/2 + m pi - hi > 0) or starts
      // above it (lo - m pi > pi/2: pi/2 + m pi - lo < 0)
      if (hipair::angle_sign(Rational(-1), m, limits.hi) > 0 || hipair::angle_sign(Rational(1), m, limits.lo) < 0) continue;
      ChartAxis axis;
      axis.kind = ChartAxis::Kind::rotation;
      axis.half_turn = centre == 1;
      // lo - m pi <= -pi/2: -pi/2 + m pi - lo >= 0
      if (hipair::angle_sign(Rational(-1), m, limits.lo) >= 0) {
        axis.lo = -1;
      } else {
        axis.lo = std::max(Rational(-1), chart_edge(limits.lo, m, false));
      }
      // hi - m pi >= pi/2: pi/2 + m pi - hi <= 0
      if (hipair::angle_sign(Rational(1), m, limits.hi) <= 0) {
        axis.hi = 1;
      } else {
        axis.hi = std::min(Rational(1), chart_edge(limits.hi, m, true));
      }
      if (axis.lo <= axis.hi) charts.push_back(axis);
    }
  }
  mpfr_clears(pi, two_pi, tmp, static_cast<mpfr_ptr>(nullptr));
  return true;
}

std::vector<ChartAxis> rotation_charts(const Motion& motion) {
  std::vector<ChartAxis> charts;
  if (motion.angle_limits && limited_rotation_charts(*motion.angle_limits, charts)) return charts;
  charts.clear();
  for (int centre = 0; centre < 2; ++centre) {
    ChartAxis axis;
    axis.kind = ChartAxis::Kind::rotation;
    axis.half_turn = centre == 1;
    axis.lo = -1;
    axis.hi = 1;
    charts.push_back(axis);
  }
  return charts;
}

// Certified extent of a whole part along the exact unit vector u.
// The part's segment and arc features, without labels (part_features' curve features, in
// its order).
template <class Visit>
void for_each_curve_feature(const Model& model, std::size_t part_index, Visit&& visit) {
  const Part& part = model.parts.at(part_index);
  BodyFeature feature;   // one, re-assigned
  for (std::size_t l = 0; l < part.loops.size(); ++l)
    for (std::size_t e = 0; e < part.loops[l].edges.size(); ++e) {
      const Edge& edge = part.loops[l].edges[e];
      feature.ref = FeatureRef{part_index, l, e, edge.is_arc() ? FeatureRef::Kind::arc : FeatureRef::Kind::segment};
      feature.edge = &edge;
      visit(feature);
    }
}

Interval part_extent(const Model& model, std::size_t part_index, const Point& unit) {
  Interval extent(0.0, 0.0);
  bool first = true;
  for_each_curve_feature(model, part_index, [&](const BodyFeature& feature) {
    Interval range = projection_range(feature, unit);
    extent = first ? range : kernels::hull(extent, range);
    first = false;
  });
  return extent;
}

// Certified largest distance of a part from a point.
double part_reach(const Model& model, std::size_t part_index, const Point& centre) {
  double reach = 0.0;
  for_each_curve_feature(model, part_index, [&](const BodyFeature& feature) {
    reach = std::max(reach, radial_range(feature, centre).hi);
  });
  return reach;
}

// Rational bounds around a certified range, widened by a margin so that the chart edges lie
// in free space: integers outside the range, then max(1, 10% of the length) more.
std::pair<Rational, Rational> widened(double lo, double hi) {
  // certified bounds beyond the range of doubles (parts of 1e300 mm and more that translate):
  // say so rather than turn an infinity into a rational
  if (!std::isfinite(lo) || !std::isfinite(hi))
    throw GeometryError("a translating part's reach exceeds about 1e300 mm: give it translation limits, or "
                        "use a smaller unit of length");
  double low = std::floor(lo);
  double high = std::ceil(hi);
  double margin = std::max(1.0, std::ceil((high - low) / 10.0));
  return {Rational(low - margin), Rational(high + margin)};
}

// Offsets s of translating part `mover` (along d) outside of which it never touches `other`.
ChartAxis translation_chart(const Model& model, std::size_t mover, std::size_t other,
                            bool other_moves) {
  const Part& part = model.parts[mover];
  const Part& partner = model.parts[other];
  ChartAxis axis;
  axis.kind = ChartAxis::Kind::translation;
  if (part.motion.translation_limits) {
    axis.lo = part.motion.translation_limits->lo;
    axis.hi = part.motion.translation_limits->hi;
    return axis;
  }
  const Point& d = part.motion.direction;
  Interval own = part_extent(model, mover, d);
  Interval target;  // where the other part can be, projected on d
  if (!other_moves) {
    target = part_extent(model, other, d);
  } else if (partner.motion.kind == Motion::Kind::rotation) {
    double reach = part_reach(model, other, partner.motion.pivot);
    target = algebra::enclose_kernel(dot(d, partner.motion.pivot)) + Interval(-reach, reach);
  } else {
    const Point& e = partner.motion.direction;
    if (partner.motion.translation_limits) {
      Interval base = part_extent(model, other, d);
      Rational along = dot(e, d);
      Interval shift = kernels::hull(
          algebra::enclose_kernel(Rational(partner.motion.translation_limits->lo * along)),
          algebra::enclose_kernel(Rational(partner.motion.translation_limits->hi * along)));
      target = base + shift;
    } else {
      Point normal{Rational(-e.y), e.x};
      Rational rate = dot(d, normal);
      if (sgn(rate) == 0)
        throw GeometryError("parts '" + part.name + "' and '" + partner.name +
                            "' translate along parallel directions without limits: give "
                            "translation limits to bound their configuration space");
      // (own + s d) . n meets other . n:  s * rate in [theirs.lo - mine.hi, theirs.hi - mine.lo].
      // Double rounding here is far below the >= 1 mm margin widened() adds.
      Interval mine = part_extent(model, mover, normal);
      Interval theirs = part_extent(model, other, normal);
      double rate_value = rate.get_d();
      double first = (theirs.lo - mine.hi) / rate_value;
      double second = (theirs.hi - mine.lo) / rate_value;
      auto [a, b] = widened(std::min(first, second), std::max(first, second));
      axis.lo = a;
      axis.hi = b;
      return axis;
    }
  }
  // own + s in [target]: s in [target.lo - own.hi, target.hi - own.lo]
  double lo = (Interval(target.lo, target.lo) - Interval(own.hi, own.hi)).lo;
  double hi = (Interval(target.hi, target.hi) - Interval(own.lo, own.lo)).hi;
  auto [a, b] = widened(lo, hi);
  axis.lo = a;
  axis.hi = b;
  return axis;
}

std::vector<ChartAxis> charts_of(const Model& model, std::size_t mover, std::size_t other,
                                 bool other_moves) {
  const Part& part = model.parts[mover];
  if (part.motion.kind == Motion::Kind::rotation) return rotation_charts(part.motion);
  return {translation_chart(model, mover, other, other_moves)};
}

}  // namespace

ChartLayout chart_layout(const Model& model, const PairAxes& axes) {
  ChartLayout layout;
  if (axes.first_moves) {
    layout.x_charts = charts_of(model, axes.first, axes.second, axes.second_moves);
    if (axes.second_moves)
      layout.y_charts = charts_of(model, axes.second, axes.first, axes.first_moves);
  } else if (axes.second_moves) {
    layout.x_charts = charts_of(model, axes.second, axes.first, axes.first_moves);
  }
  return layout;
}

ContactKind public_kind(ContactType type) noexcept {
  switch (type) {
    case ContactType::vertex_segment: return ContactKind::vertex_segment;
    case ContactType::segment_vertex: return ContactKind::segment_vertex;
    case ContactType::vertex_arc: return ContactKind::vertex_arc;
    case ContactType::arc_vertex: return ContactKind::arc_vertex;
    case ContactType::arc_arc: return ContactKind::arc_arc;
    case ContactType::arc_segment: return ContactKind::arc_segment;
    case ContactType::segment_arc: return ContactKind::segment_arc;
  }
  return ContactKind::vertex_segment;
}

}  // namespace hipair::cspace
