// Exact validation of loops (closure, arcs, self- and mutual intersections) and their
// orientation. Intersections of segments and circles are decided exactly: their coordinates
// lie in Q(sqrt(D)) for a rational D and every test is an exact sign test there. Orientation
// and nesting are integer- or sign-valued quantities computed on certified MPFI enclosures.
#include "model/validate_geometry.hpp"
#include "core/exact_sqrt.hpp"
#include "core/decimal_text.hpp"

#include "model/expression.hpp"
#include "model/interval.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace hipair::model_detail {
namespace {

// ------------------------------------------------------------------ exact numbers a + b sqrt(D)
struct Surd {
  Rational a;  // rational part
  Rational b;  // coefficient of sqrt(D)
};

Surd operator-(const Surd& u, const Surd& v) { return {u.a - v.a, u.b - v.b}; }
Surd operator-(const Surd& u, const Rational& r) { return {u.a - r, u.b}; }
Surd operator*(const Rational& r, const Surd& u) { return {r * u.a, r * u.b}; }

// Sign of a + b sqrt(D), D >= 0 not a perfect square unless b == 0.
int sign(const Surd& u, const Rational& D) {
  int sa = sgn(u.a), sb = D == 0 ? 0 : sgn(u.b);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  int c = cmp(u.a * u.a, u.b * u.b * D);
  return c > 0 ? sa : c < 0 ? sb : 0;
}

struct SurdPoint {
  Surd x;
  Surd y;
};

Rational cross(const Point& u, const Point& v) { return u.x * v.y - u.y * v.x; }
Rational dot(const Point& u, const Point& v) { return u.x * v.x + u.y * v.y; }
Point operator-(const Point& u, const Point& v) { return {u.x - v.x, u.y - v.y}; }
Rational squared_length(const Point& u) { return dot(u, u); }

// cross(u, v) for a rational u and a point in Q(sqrt D)^2.
Surd cross(const Point& u, const SurdPoint& v) { return u.x * v.y - u.y * v.x; }
Surd cross(const SurdPoint& u, const Point& v) { return v.y * u.x - v.x * u.y; }

SurdPoint rational_point(const Point& p) { return {{p.x, 0}, {p.y, 0}}; }

bool equals(const SurdPoint& p, const Point& q) {
  return p.x.b == 0 && p.y.b == 0 && p.x.a == q.x && p.y.a == q.y;
}

// ------------------------------------------------------------------ messages
std::string decimal(const Rational& v) { return to_decimal_string(v, 10); }
std::string show(const Point& p) { return "(" + decimal(p.x) + ", " + decimal(p.y) + ")"; }
// Two points for one message, with enough digits to show that they differ.
std::pair<std::string, std::string> show_apart(const Point& p, const Point& q) {
  auto [px, qx] = to_decimal_strings_apart(p.x, q.x, 10);
  auto [py, qy] = to_decimal_strings_apart(p.y, q.y, 10);
  return {"(" + px + ", " + py + ")", "(" + qx + ", " + qy + ")"};
}
std::string show(const SurdPoint& p, const Rational& D) {
  double root = std::sqrt(to_double(D));
  std::ostringstream out;
  out.precision(10);
  out << "(" << to_double(p.x.a) + to_double(p.x.b) * root << ", "
      << to_double(p.y.a) + to_double(p.y.b) * root << ")";
  return out.str();
}

std::string describe(const Edge& edge) {
  std::string text = edge.pointer.empty() ? std::string("an edge") : edge.pointer;
  if (!edge.label.empty()) text += " ('" + edge.label + "')";
  return text;
}

// ------------------------------------------------------------------ arcs as ccw arcs
// The start and end directions from the centre, a = start - centre and b = end - centre, and
// turn = sgn(cross(a, b)): every sign test of a point against the arc reads them (the model's
// rationals are large: computed once per arc, when first asked for).
struct ArcFrame {
  Point a;
  Point b;
  int turn = 0;
};

struct ArcView {
  Point center;
  Rational radius_squared;
  Point start;  // counter-clockwise from start to end
  Point end;
  bool full = false;

  const ArcFrame& frame() const {
    if (!frame_) {
      ArcFrame f{start - center, end - center, 0};
      f.turn = sgn(cross(f.a, f.b));
      frame_ = std::move(f);
    }
    return *frame_;
  }

 private:
  mutable std::optional<ArcFrame> frame_;
};

ArcView view_of(const Edge& edge) {
  ArcView arc;
  arc.center = edge.center;
  arc.radius_squared = edge.radius_squared;
  arc.start = edge.ccw ? edge.source : edge.target;
  arc.end = edge.ccw ? edge.target : edge.source;
  arc.full = edge.source == edge.target;
  return arc;
}

// Whether the direction v (from the centre; exact in Q(sqrt D)) lies on the closed arc.
bool direction_on_arc(const ArcView& arc, const Surd& cross_start_v, const Surd& cross_v_end,
                      const Rational& D) {
  if (arc.full) return true;
  int turn = arc.frame().turn;
  int sa = sign(cross_start_v, D), sb = sign(cross_v_end, D);
  if (turn > 0) return sa >= 0 && sb >= 0;
  if (turn < 0) return sa >= 0 || sb >= 0;
  return sa >= 0;  // half circle
}

bool on_arc(const ArcView& arc, const SurdPoint& x, const Rational& D) {
  if (arc.full) return true;
  SurdPoint v{x.x - arc.center.x, x.y - arc.center.y};
  const ArcFrame& f = arc.frame();
  return direction_on_arc(arc, cross(f.a, v), cross(v, f.b), D);
}

// Whether the axis direction (dx, dy) in {(1,0), (0,1), (-1,0), (0,-1)} points from the centre
// into the closed arc: the sign tests of direction_on_arc on the coordinates alone.
bool axis_on_arc(const ArcView& arc, int dx, int dy) {
  if (arc.full) return true;
  const ArcFrame& f = arc.frame();
  // cross(a, d) = a.x dy - a.y dx, cross(d, b) = dx b.y - dy b.x
  int sa = dy != 0 ? dy * sgn(f.a.x) : -dx * sgn(f.a.y);
  int sb = dx != 0 ? dx * sgn(f.b.y) : -dy * sgn(f.b.x);
  if (f.turn > 0) return sa >= 0 && sb >= 0;
  if (f.turn < 0) return sa >= 0 || sb >= 0;
  return sa >= 0;
}

bool strictly_inside_arc(const ArcView& arc, const Point& p) {
  return on_arc(arc, rational_point(p), Rational(0)) && (arc.full || (p != arc.start && p != arc.end));
}

// ------------------------------------------------------------------ intersections
struct Intersection {
  bool overlap = false;             // infinitely many common points
  Rational D;                       // the points' coordinates lie in Q(sqrt D)
  std::vector<SurdPoint> points;
};

Intersection intersect_segments(const Edge& e, const Edge& f) {
  Intersection result;
  Point d1 = e.target - e.source, d2 = f.target - f.source, r = f.source - e.source;
  Rational denominator = cross(d1, d2);
  if (denominator != 0) {
    Rational t = cross(r, d2) / denominator, u = cross(r, d1) / denominator;
    if (t >= 0 && t <= 1 && u >= 0 && u <= 1)
      result.points.push_back(rational_point({e.source.x + t * d1.x, e.source.y + t * d1.y}));
    return result;
  }
  if (cross(r, d1) != 0) return result;  // parallel, distinct lines
  Rational length = squared_length(d1);
  Rational t0 = dot(f.source - e.source, d1) / length, t1 = dot(f.target - e.source, d1) / length;
  Rational lo = std::max(Rational(std::min(t0, t1)), Rational(0));
  Rational hi = std::min(Rational(std::max(t0, t1)), Rational(1));
  if (lo < hi) {
    result.overlap = true;
  } else if (lo == hi) {
    result.points.push_back(rational_point({e.source.x + lo * d1.x, e.source.y + lo * d1.y}));
  }
  return result;
}

Intersection intersect_segment_arc(const Edge& segment, const Edge& arc_edge) {
  Intersection result;
  ArcView arc = view_of(arc_edge);
  Point d = segment.target - segment.source, p = segment.source - arc.center;
  Rational A = squared_length(d), B = 2 * dot(d, p), C = squared_length(p) - arc.radius_squared;
  Rational discriminant = B * B - 4 * A * C;
  if (discriminant < 0) return result;
  // u = (-B +- sqrt(disc)) / (2A) = u0 +- u1 sqrt(disc)
  Rational u0 = -B / (2 * A);
  std::vector<Surd> roots;
  if (auto root = rational_sqrt(discriminant)) {
    Rational delta = *root / (2 * A);
    roots.push_back({u0 + delta, 0});
    if (delta != 0) roots.push_back({u0 - delta, 0});
    result.D = 0;
  } else {
    Rational u1 = Rational(1) / (2 * A);
    roots.push_back({u0, u1});
    roots.push_back({u0, -u1});
    result.D = discriminant;
  }
  for (const Surd& u : roots) {
    if (sign(u, result.D) < 0 || sign(u - Rational(1), result.D) > 0) continue;
    SurdPoint x{Surd{segment.source.x + d.x * u.a, d.x * u.b},
                Surd{segment.source.y + d.y * u.a, d.y * u.b}};
    if (on_arc(arc, x, result.D)) result.points.push_back(x);
  }
  return result;
}

Intersection intersect_arcs(const Edge& e, const Edge& f) {
  Intersection result;
  ArcView first = view_of(e), second = view_of(f);
  if (first.center == second.center) {
    if (first.radius_squared != second.radius_squared) return result;
    // The same circle: overlap unless they share at most endpoints.
    if (first.full || second.full || first.start == second.start ||
        strictly_inside_arc(second, first.start) || strictly_inside_arc(first, second.start)) {
      result.overlap = true;
      return result;
    }
    for (const Point& p : {first.start, first.end})
      if (on_arc(second, rational_point(p), Rational(0))) result.points.push_back(rational_point(p));
    for (const Point& p : {second.start, second.end})
      if (on_arc(first, rational_point(p), Rational(0)) && p != first.start && p != first.end)
        result.points.push_back(rational_point(p));
    return result;
  }
  Point d = second.center - first.center;
  Rational L = squared_length(d);
  Rational a = (first.radius_squared - second.radius_squared + L) / 2;
  Rational discriminant = first.radius_squared * L - a * a;
  if (discriminant < 0) return result;
  // x = c1 + (a/L) d +- (sqrt(disc)/L) perp(d), perp(d) = (-d.y, d.x)
  Point foot{first.center.x + a / L * d.x, first.center.y + a / L * d.y};
  std::vector<SurdPoint> candidates;
  if (auto root = rational_sqrt(discriminant)) {
    Rational k = *root / L;
    candidates.push_back(rational_point({foot.x - k * d.y, foot.y + k * d.x}));
    if (k != 0) candidates.push_back(rational_point({foot.x + k * d.y, foot.y - k * d.x}));
    result.D = 0;
  } else {
    Rational k = Rational(1) / L;
    candidates.push_back({{foot.x, -k * d.y}, {foot.y, k * d.x}});
    candidates.push_back({{foot.x, k * d.y}, {foot.y, -k * d.x}});
    result.D = discriminant;
  }
  for (const SurdPoint& x : candidates)
    if (on_arc(first, x, result.D) && on_arc(second, x, result.D)) result.points.push_back(x);
  return result;
}

Intersection intersect(const Edge& e, const Edge& f) {
  if (!e.is_arc() && !f.is_arc()) return intersect_segments(e, f);
  if (!e.is_arc()) return intersect_segment_arc(e, f);
  if (!f.is_arc()) return intersect_segment_arc(f, e);
  return intersect_arcs(e, f);
}

// ------------------------------------------------------------------ bounding boxes (filter only)
struct Box {
  double x_lo, x_hi, y_lo, y_hi;
  void include(const Box& other) {
    x_lo = std::min(x_lo, other.x_lo);
    x_hi = std::max(x_hi, other.x_hi);
    y_lo = std::min(y_lo, other.y_lo);
    y_hi = std::max(y_hi, other.y_hi);
  }
  // Conservative: false only when p is certainly outside.
  bool contains(const Point& p) const {
    double x = to_double(p.x), y = to_double(p.y);
    if (!std::isfinite(x) || !std::isfinite(y)) return true;
    return x >= x_lo && x <= x_hi && y >= y_lo && y <= y_hi;
  }
};

// Outward-widened double bounds of a rational: conservative for the filter.
void widen(double value, double& lo, double& hi) {
  if (!std::isfinite(value)) {
    lo = -std::numeric_limits<double>::infinity();
    hi = std::numeric_limits<double>::infinity();
    return;
  }
  double margin = std::fabs(value) * 1e-9 + 1e-300;
  lo = value - margin;
  hi = value + margin;
}

void include(Box& box, double x, double y) {
  double lo, hi;
  widen(x, lo, hi);
  box.x_lo = std::min(box.x_lo, lo);
  box.x_hi = std::max(box.x_hi, hi);
  widen(y, lo, hi);
  box.y_lo = std::min(box.y_lo, lo);
  box.y_hi = std::max(box.y_hi, hi);
}

Box box_of(const Edge& edge) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  Box box{infinity, -infinity, infinity, -infinity};
  include(box, to_double(edge.source.x), to_double(edge.source.y));
  include(box, to_double(edge.target.x), to_double(edge.target.y));
  if (edge.is_arc()) {
    ArcView arc = view_of(edge);
    double cx = to_double(arc.center.x), cy = to_double(arc.center.y);
    double r = std::sqrt(to_double(arc.radius_squared)) * (1 + 1e-9);
    const int directions[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (const auto& direction : directions)
      if (axis_on_arc(arc, direction[0], direction[1])) include(box, cx + r * direction[0], cy + r * direction[1]);
  }
  if (std::isnan(box.x_lo) || std::isnan(box.x_hi) || std::isnan(box.y_lo) || std::isnan(box.y_hi))
    box = Box{-infinity, infinity, -infinity, infinity};
  return box;
}

// ------------------------------------------------------------------ certified angles
Interval exact_interval(const Rational& value) { return Interval(value); }

// atan2(y, x) in (-pi, pi] for exact y, x not both 0; exact branch decisions.
Interval angle_of(const Rational& y, const Rational& x) {
  if (y == 0) return x > 0 ? Interval(Rational(0)) : Interval::pi();
  Interval result;
  mpfi_atan2(result.get(), exact_interval(y).get(), exact_interval(x).get());
  return result;
}

// Counter-clockwise angle from u to v in [0, 2 pi).
Interval ccw_angle(const Point& u, const Point& v) {
  Rational c = cross(u, v), d = dot(u, v);
  Interval angle = angle_of(c, d);
  if (c < 0) angle = angle + Interval::pi() * Interval(Rational(2));
  return angle;
}


// Twice the signed area enclosed by the loop: the polygon of its vertices (exact) plus, per
// arc, r^2 times its signed sweep (an enclosure). Coordinates are taken relative to the first
// vertex so that a small loop far from the origin loses no precision.
Interval twice_area(const Loop& loop) {
  const Point origin = loop.edges.front().source;
  Rational polygonal = 0;
  Interval curved(Rational(0));
  bool has_arc = false;
  for (const Edge& edge : loop.edges) {
    Point source = edge.source - origin, target = edge.target - origin;
    if (!edge.is_arc()) {
      polygonal += cross(source, target);
      continue;
    }
    has_arc = true;
    polygonal += cross(edge.center - origin, target - source);
    Point a = edge.source - edge.center, b = edge.target - edge.center;
    // a full circle turns by 2 pi in its own direction: a clockwise one (a hole written as
    // the reader wants it) encloses negative area
    Interval sweep = edge.source == edge.target ? Interval::pi() * Interval(Rational(edge.ccw ? 2 : -2))
                     : edge.ccw                 ? ccw_angle(a, b)
                                                : -ccw_angle(b, a);
    curved = curved + Interval(edge.radius_squared) * sweep;
  }
  if (!has_arc) return Interval(polygonal);
  return Interval(polygonal) + curved;
}

// 0 for directions with angle in [0, pi), 1 for [pi, 2 pi).
int half_plane(const Point& w) { return (w.y > 0 || (w.y == 0 && w.x > 0)) ? 0 : 1; }

// Whether the polar angle of v (in [0, 2 pi)) is less than that of u.
bool angle_less(const Point& v, const Point& u) {
  int hv = half_plane(v), hu = half_plane(u);
  if (hv != hu) return hv < hu;
  return cross(v, u) > 0;
}

// Winding number of the loop around p (p not on the loop), exactly, by counting quarter
// decisions instead of summing angles. Each edge turns the direction from p by an angle
// a = alpha - 2 pi k, where alpha in [0, 2 pi) is the counter-clockwise angle from the
// edge's start direction u to its end direction v, and k in {0, 1} follows from the edge:
// a segment (or an arc of a circle p is not inside) turns by the principal angle, so
// k = [cross(u, v) < 0]; an arc around p turns by alpha (ccw) or alpha - 2 pi (cw).
// Summed over the closed loop, the alphas add up to 2 pi times the number of times the
// direction passes the +x axis, which is [angle(v) < angle(u)] per edge.
long winding_number(const Loop& loop, const Point& p) {
  long winding = 0;
  for (const Edge& edge : loop.edges) {
    Point u = edge.source - p, v = edge.target - p;
    bool around = edge.is_arc() && squared_length(p - edge.center) < edge.radius_squared;
    if (edge.is_arc() && edge.source == edge.target) {
      if (around) winding += edge.ccw ? 1 : -1;
      continue;
    }
    if (angle_less(v, u)) ++winding;
    if (!around) {
      if (cross(u, v) < 0) --winding;
    } else if (!edge.ccw) {
      --winding;
    }
  }
  return winding;
}

// ------------------------------------------------------------------ checks
void check_loop_edges(const Loop& loop) {
  if (loop.edges.empty()) throw ModelError(loop.pointer, "a loop needs at least one edge");
  for (std::size_t i = 0; i < loop.edges.size(); ++i) {
    const Edge& edge = loop.edges[i];
    if (i > 0 && !(edge.source == loop.edges[i - 1].target)) {
      auto [start, previous_end] = show_apart(edge.source, loop.edges[i - 1].target);
      throw ModelError(edge.pointer, "edge " + describe(edge) + " does not start where the previous edge ends " +
                                         previous_end + ": it starts at " + start);
    }
    if (!edge.is_arc()) {
      if (edge.source == edge.target)
        throw ModelError(edge.pointer, "zero-length segment: it starts and ends at " + show(edge.source));
      continue;
    }
    Rational start_distance = squared_length(edge.source - edge.center);
    Rational end_distance = squared_length(edge.target - edge.center);
    if (edge.radius_squared < 0)
      throw ModelError(edge.pointer, "negative radius");
    if (edge.radius_squared == 0 || start_distance == 0)
      throw ModelError(edge.pointer, "zero radius: the arc starts at its centre " + show(edge.center));
    if (start_distance != edge.radius_squared)
      throw ModelError(edge.pointer, "inconsistent arc: its start is not on its circle");
    if (end_distance != start_distance) {
      auto [end_text, start_text] = to_decimal_strings_apart(end_distance, start_distance, 10);
      // Squared distances that differ only far into their digits (a centre 1e999 mm away, an end
      // 1e-999 off the circle) were written whole, thousands of digits each, which the console
      // cuts to their first 60 (shortened_message): both read "9.99999..." with the exponent and
      // "^(1/2)" cut off (hunt65). Then: 12 digits each, and their exact difference.
      std::string differ;
      if (end_text.size() > 40 || start_text.size() > 40) {
        end_text = to_decimal_string(end_distance, 12);
        start_text = to_decimal_string(start_distance, 12);
        differ = ", the squares differing by " + to_decimal_string(Rational(end_distance - start_distance), 12);
      }
      throw ModelError(edge.pointer, "inconsistent arc: the end " + show(edge.target) + " is at distance " +
                                         end_text + "^(1/2) from the centre " + show(edge.center) +
                                         " but the start " + show(edge.source) + " at distance " +
                                         start_text + "^(1/2)" + differ +
                                         " (they must be equal exactly: place the end with a polar point on the arc's circle)");
    }
    if (edge.is_full_circle() && loop.edges.size() > 1)
      throw ModelError(edge.pointer, "a full circle (arc ending at its start) must be a loop of its own");
  }
  if (!(loop.edges.back().target == loop.edges.front().source))
  {
    auto [end, start] = show_apart(loop.edges.back().target, loop.edges.front().source);
    throw ModelError(loop.pointer, "open loop: the last edge ends at " + end + ", not at the start " + start);
  }
}

struct EdgeRef {
  std::size_t loop;
  std::size_t index;
  Box box;
};

bool consecutive(const Loop& loop, std::size_t first, std::size_t second) {
  std::size_t size = loop.edges.size();
  return (first + 1) % size == second || (second + 1) % size == first;
}

// Checks that edges (l1, i1) and (l2, i2), (l1, i1) < (l2, i2), share no point except the
// vertex joining them when they are consecutive in a loop.
void check_pair(const Part& part, std::size_t l1, std::size_t i1, std::size_t l2, std::size_t i2) {
  const Loop& loop = part.loops[l1];
  const Edge& e = loop.edges[i1];
  const Edge& f = part.loops[l2].edges[i2];
  std::vector<Point> allowed;
  bool same_loop = l1 == l2;
  bool joined = same_loop && consecutive(loop, i1, i2);
  if (same_loop) {
    std::size_t size = loop.edges.size();
    if ((i1 + 1) % size == i2) allowed.push_back(e.target);
    if ((i2 + 1) % size == i1) allowed.push_back(e.source);
  }
  Intersection common = intersect(e, f);
  if (common.overlap) {
    if (joined)
      throw ModelError(f.pointer, "edge " + describe(f) + " runs back along " + describe(e) +
                                      " (a zero-area spike: the boundary overlaps itself)");
    throw ModelError(f.pointer, "edge " + describe(f) + " overlaps " + describe(e) +
                                    (same_loop ? " (the loop overlaps itself)"
                                               : " (loops " + loop.pointer + " and " + part.loops[l2].pointer +
                                                     " of part '" + part.name + "' overlap)"));
  }
  for (const SurdPoint& x : common.points) {
    bool is_allowed = false;
    for (const Point& p : allowed) is_allowed = is_allowed || equals(x, p);
    if (is_allowed) continue;
    if (same_loop)
      throw ModelError(f.pointer, "the loop intersects itself: edge " + describe(f) + " crosses or touches " +
                                      describe(e) + " at " + show(x, common.D));
    throw ModelError(f.pointer, "loops " + loop.pointer + " and " + part.loops[l2].pointer + " of part '" +
                                    part.name + "' cross or touch: edge " + describe(f) + " meets " + describe(e) +
                                    " at " + show(x, common.D));
  }
}

// Each loop's edges' boxes, computed once for the intersection sweep and the nesting test.
using EdgeBoxes = std::vector<std::vector<Box>>;

EdgeBoxes edge_boxes(const Part& part) {
  EdgeBoxes boxes(part.loops.size());
  for (std::size_t l = 0; l < part.loops.size(); ++l)
    for (const Edge& edge : part.loops[l].edges) boxes[l].push_back(box_of(edge));
  return boxes;
}

void check_intersections(const Part& part, const EdgeBoxes& boxes) {
  // Consecutive edges first (a spike is reported as such), then every other pair whose
  // bounding boxes overlap, found by a sweep in x.
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    std::size_t size = part.loops[l].edges.size();
    if (size < 2) continue;
    for (std::size_t i = 0; i + 1 < size; ++i) check_pair(part, l, i, l, i + 1);
    if (size > 2) check_pair(part, l, 0, l, size - 1);
  }
  std::vector<EdgeRef> edges;
  for (std::size_t l = 0; l < part.loops.size(); ++l)
    for (std::size_t i = 0; i < part.loops[l].edges.size(); ++i)
      edges.push_back(EdgeRef{l, i, boxes[l][i]});
  std::sort(edges.begin(), edges.end(), [&](const EdgeRef& a, const EdgeRef& b) {
    if (a.box.x_lo != b.box.x_lo) return a.box.x_lo < b.box.x_lo;
    return std::tie(a.loop, a.index) < std::tie(b.loop, b.index);
  });
  for (std::size_t m = 0; m < edges.size(); ++m) {
    for (std::size_t n = m + 1; n < edges.size() && edges[n].box.x_lo <= edges[m].box.x_hi; ++n) {
      const EdgeRef* first = &edges[m];
      const EdgeRef* second = &edges[n];
      if (first->box.y_hi < second->box.y_lo || second->box.y_hi < first->box.y_lo) continue;
      if (std::tie(first->loop, first->index) > std::tie(second->loop, second->index)) std::swap(first, second);
      if (first->loop == second->loop && consecutive(part.loops[first->loop], first->index, second->index)) continue;
      check_pair(part, first->loop, first->index, second->loop, second->index);
    }
  }
}

void reverse(Loop& loop) {
  std::reverse(loop.edges.begin(), loop.edges.end());
  for (Edge& edge : loop.edges) {
    std::swap(edge.source, edge.target);
    edge.ccw = !edge.ccw;
  }
}

// The sign of the loop's twice_area: first from 64-bit enclosures (a sign they decide is the
// exact sign: every enclosure holds the exact value), at the working precision only when they
// leave it open. The 256-bit arc tangents of large rationals were most of the reader's time.
int area_sign(const Loop& loop) {
  {
    PrecisionScope low(std::min<mpfr_prec_t>(64, working_interval_bits()));
    if (int s = twice_area(loop).sign(); s != 0) return s;
  }
  return twice_area(loop).sign();
}

void orient(Part& part, const EdgeBoxes& edge_boxes) {
  std::vector<Box> boxes;
  for (const std::vector<Box>& loop_boxes : edge_boxes) {
    Box box = loop_boxes.front();
    for (const Box& edge_box : loop_boxes) box.include(edge_box);
    boxes.push_back(box);
  }
  std::vector<int> orientation(part.loops.size());
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    int s = area_sign(part.loops[l]);
    // A loop of segments only has an exact (rational) area. With arcs, an enclosure that holds
    // 0 says only that this precision cannot settle the sign: an arc of radius 10^80 on a part of
    // a few mm cancels r^2 * sweep against the polygon's 10^160 in the last bits, and until
    // session 44 such a loop (area 480 mm^2) was refused as enclosing "no area". The whole model
    // is read again at doubled precision (read_model_escalating), up to most_interval_bits.
    bool has_arc = std::any_of(part.loops[l].edges.begin(), part.loops[l].edges.end(),
                               [](const Edge& edge) { return edge.is_arc(); });
    if (s == 0 && has_arc)
      throw PrecisionExhausted(part.loops[l].pointer,
                               "cannot decide the loop's orientation at " + std::to_string(working_interval_bits()) +
                                   "-bit precision (its area is too small against its arcs' radii, or zero)");
    if (s == 0) throw ModelError(part.loops[l].pointer, "cannot decide the loop's orientation (it encloses no area)");
    orientation[l] = s;
  }
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    std::size_t depth = 0;
    const Point& probe = part.loops[l].edges.front().source;
    for (std::size_t other = 0; other < part.loops.size(); ++other) {
      if (other == l) continue;
      if (!boxes[other].contains(probe)) continue;
      if (winding_number(part.loops[other], probe) != 0) ++depth;
    }
    Loop& loop = part.loops[l];
    loop.is_hole = depth % 2 == 1;
    int wanted = loop.is_hole ? -1 : 1;
    if (orientation[l] != wanted) reverse(loop);
  }
}

}  // namespace

void validate_part_geometry(Part& part) {
  for (const Loop& loop : part.loops) check_loop_edges(loop);
  const EdgeBoxes boxes = edge_boxes(part);
  check_intersections(part, boxes);
  orient(part, boxes);
}

}  // namespace hipair::model_detail
