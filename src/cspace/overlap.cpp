// Exact overlap predicate: apart / touching / overlapping for two parts bounded by segments
// and circular arcs, posed by exact rational rigid maps. See overlap.hpp and
// docs/contact-kernels.md ("The overlap predicate") for the argument.
//
// Method (in the second part's body frame, where only the first part is moved):
//  1. double bounding boxes with a generous certified margin reject far edge pairs;
//  2. each remaining edge pair is intersected exactly: a transversal crossing interior to
//     both edges means overlap; a common piece (collinear segments, cocircular arcs) with
//     material on the same side means overlap, on opposite sides touching; every other
//     common point (a vertex on the other boundary, a tangency) is a rational touch point;
//  3. at each touch point the boundary germs of both parts are sorted by tangent direction
//     and curvature; overlap iff some sector between consecutive germs is material of both;
//  4. a loop with no common point with the other boundary lies entirely inside or outside
//     the other part's interior: one exact point-in-region test per such loop decides.
#include "cspace/overlap.hpp"

#include "kernels/interval.hpp"

#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace hipair::cspace {

namespace {

// ============================================================================ exact helpers

int sign_of(const Rational& value) { return sgn(value); }

// Sign of u + v sqrt(w), w >= 0.
int sign_with_root(const Rational& u, const Rational& v, const Rational& w) {
  int su = sgn(u);
  int sv = sgn(v);
  if (sv == 0 || sgn(w) == 0) return su;
  if (su == 0) return sv;
  if (su == sv) return su;
  int c = cmp(Rational(u * u), Rational(v * v * w));
  if (c > 0) return su;
  if (c < 0) return sv;
  return 0;
}

Point minus(const Point& a, const Point& b) { return difference(a, b); }

// Witness construction works at this precision: sites and directions are rational
// approximations with relative error about 2^-witness_bits.
constexpr mpfr_prec_t witness_bits = 640;

Rational to_rational(const mpfr_t value) {
  Rational result;
  mpfr_get_q(result.get_mpq_t(), value);
  return result;
}

// Rational approximation of sqrt(value), value >= 0.
Rational approximate_sqrt(const Rational& value) {
  mpfr_t root;
  mpfr_init2(root, witness_bits);
  mpfr_set_q(root, value.get_mpq_t(), MPFR_RNDN);
  mpfr_sqrt(root, root, MPFR_RNDN);
  Rational result = to_rational(root);
  mpfr_clear(root);
  return result;
}

// Rational approximation of v / |v|.
Point approximate_unit(const Point& v) {
  Rational length2 = dot(v, v);
  if (sgn(length2) == 0) return v;
  Rational length = approximate_sqrt(length2);
  return Point{Rational(v.x / length), Rational(v.y / length)};
}
Point left_perpendicular(const Point& v) { return Point{Rational(-v.y), v.x}; }

// ============================================================================ placed edges

struct Box {
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;
  bool meets(const Box& other) const {
    return xlo <= other.xhi && other.xlo <= xhi && ylo <= other.yhi && other.ylo <= yhi;
  }
  bool contains(double x, double y) const { return xlo <= x && x <= xhi && ylo <= y && y <= yhi; }
  void add(double x, double y) {
    xlo = std::min(xlo, x);
    xhi = std::max(xhi, x);
    ylo = std::min(ylo, y);
    yhi = std::max(yhi, y);
  }
};

struct PlacedEdge {
  bool arc = false;
  bool full = false;
  bool ccw = true;
  Point source;
  Point target;
  Point center;
  Rational radius_squared;
  kernels::ArcSector<Rational> sector;
  std::size_t loop = 0;
  std::size_t index = 0;
};

bool in_sector(const PlacedEdge& edge, const Point& v) { return sector_contains(edge.sector, v); }

// Closed membership of a rational point.
bool on_edge(const PlacedEdge& edge, const Point& p) {
  if (!edge.arc) {
    Point d = minus(edge.target, edge.source);
    Point f = minus(p, edge.source);
    if (sgn(cross(d, f)) != 0) return false;
    Rational along = dot(f, d);
    return sgn(along) >= 0 && along <= dot(d, d);
  }
  Point v = minus(p, edge.center);
  if (dot(v, v) != edge.radius_squared) return false;
  return in_sector(edge, v);
}

bool is_endpoint(const PlacedEdge& edge, const Point& p) {
  return p == edge.source || p == edge.target;
}

// A part placed in the common frame by an exact rigid map, with double boxes and lazily
// computed exact edges.
class PlacedPart {
 public:
  PlacedPart(const Part& part, const RigidMap& map, bool identity)
      : part_(part), map_(map), identity_(identity) {
    c_ = map.c.get_d();
    s_ = map.s.get_d();
    ox_ = map.offset.x.get_d();
    oy_ = map.offset.y.get_d();
    for (std::size_t l = 0; l < part.loops.size(); ++l) {
      loop_begin_.push_back(refs_.size());
      for (std::size_t e = 0; e < part.loops[l].edges.size(); ++e) refs_.push_back({l, e});
    }
    loop_begin_.push_back(refs_.size());
    boxes_.resize(refs_.size());
    exact_.resize(refs_.size());
    double scale = 1.0;
    for (std::size_t i = 0; i < refs_.size(); ++i) {
      boxes_[i] = double_box(original(i));
      scale = std::max({scale, std::fabs(boxes_[i].xlo), std::fabs(boxes_[i].xhi),
                        std::fabs(boxes_[i].ylo), std::fabs(boxes_[i].yhi)});
    }
    // Each double coordinate comes from at most ~10 operations on numbers bounded by the
    // scale: its error is below 1e-14 * scale. A margin of 1e-9 * scale is certain.
    margin_ = 1e-9 * scale;
    total_ = Box{1e300, -1e300, 1e300, -1e300};
    loop_boxes_.assign(part.loops.size(), Box{1e300, -1e300, 1e300, -1e300});
    for (std::size_t i = 0; i < refs_.size(); ++i) {
      Box& b = boxes_[i];
      b.xlo -= margin_;
      b.ylo -= margin_;
      b.xhi += margin_;
      b.yhi += margin_;
      total_.add(b.xlo, b.ylo);
      total_.add(b.xhi, b.yhi);
      loop_boxes_[refs_[i].first].add(b.xlo, b.ylo);
      loop_boxes_[refs_[i].first].add(b.xhi, b.yhi);
    }
  }

  std::size_t size() const { return refs_.size(); }
  std::size_t loops() const { return part_.loops.size(); }
  std::size_t loop_begin(std::size_t loop) const { return loop_begin_[loop]; }
  std::size_t loop_end(std::size_t loop) const { return loop_begin_[loop + 1]; }
  const Box& box(std::size_t i) const { return boxes_[i]; }
  const Box& total() const { return total_; }
  const Box& loop_box(std::size_t loop) const { return loop_boxes_[loop]; }
  double margin() const { return margin_; }
  const Edge& original(std::size_t i) const {
    return part_.loops[refs_[i].first].edges[refs_[i].second];
  }

  const PlacedEdge& edge(std::size_t i) {
    if (!exact_[i]) {
      const Edge& source = original(i);
      PlacedEdge placed;
      placed.arc = source.is_arc();
      placed.full = source.is_full_circle();
      placed.ccw = source.ccw;
      placed.loop = refs_[i].first;
      placed.index = refs_[i].second;
      if (identity_) {
        placed.source = source.source;
        placed.target = source.target;
      } else {
        placed.source = map_.apply(source.source);
        placed.target = map_.apply(source.target);
      }
      if (placed.arc) {
        placed.center = identity_ ? source.center : map_.apply(source.center);
        placed.radius_squared = source.radius_squared;
        Edge moved;
        moved.kind = Edge::Kind::arc;
        moved.source = placed.source;
        moved.target = placed.target;
        moved.center = placed.center;
        moved.ccw = placed.ccw;
        placed.sector = arc_sector(moved);
      }
      exact_[i] = std::move(placed);
    }
    return *exact_[i];
  }

 private:
  void apply_double(double x, double y, double& u, double& v) const {
    u = c_ * x - s_ * y + ox_;
    v = s_ * x + c_ * y + oy_;
  }

  Box double_box(const Edge& edge) const {
    double sx, sy, tx, ty;
    apply_double(edge.source.x.get_d(), edge.source.y.get_d(), sx, sy);
    apply_double(edge.target.x.get_d(), edge.target.y.get_d(), tx, ty);
    Box box{std::min(sx, tx), std::max(sx, tx), std::min(sy, ty), std::max(sy, ty)};
    if (!edge.is_arc()) return box;
    double cx, cy;
    apply_double(edge.center.x.get_d(), edge.center.y.get_d(), cx, cy);
    double r = std::sqrt(edge.radius_squared.get_d());
    if (edge.is_full_circle()) return Box{cx - r, cx + r, cy - r, cy + r};
    // Extreme points in the axis directions, included when possibly on the arc.
    double ax = sx - cx, ay = sy - cy, bx = tx - cx, by = ty - cy;
    if (!edge.ccw) {
      std::swap(ax, bx);
      std::swap(ay, by);
    }
    double tolerance = 1e-7 * r * r;
    bool large = ax * by - ay * bx < tolerance;  // possibly more than a half turn
    const double directions[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& u : directions) {
      double after = ax * u[1] - ay * u[0];
      double before = u[0] * by - u[1] * bx;
      bool possibly = large ? (after > -tolerance || before > -tolerance)
                            : (after > -tolerance && before > -tolerance);
      if (possibly) box.add(cx + r * u[0], cy + r * u[1]);
    }
    return box;
  }

  const Part& part_;
  RigidMap map_;
  bool identity_;
  double c_, s_, ox_, oy_;
  std::vector<std::pair<std::size_t, std::size_t>> refs_;
  std::vector<std::size_t> loop_begin_;
  std::vector<Box> boxes_;
  std::vector<Box> loop_boxes_;
  std::vector<std::optional<PlacedEdge>> exact_;
  Box total_;
  double margin_ = 0;
};

// ============================================================================ the analysis

struct Site {
  Point point;          // rational approximation of where overlap was found
  bool known = false;
};

class OverlapAnalysis {
 public:
  OverlapAnalysis(PlacedPart& first, PlacedPart& second) : parts_{&first, &second} {
    touched_[0].assign(first.loops(), false);
    touched_[1].assign(second.loops(), false);
  }

  Overlap run() {
    if (!parts_[0]->total().meets(parts_[1]->total())) return Overlap::apart;
    PlacedPart& a = *parts_[0];
    PlacedPart& b = *parts_[1];
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a.box(i).meets(b.total())) continue;
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (!a.box(i).meets(b.box(j))) continue;
        if (intersect(i, j)) return Overlap::overlapping;
      }
    }
    for (const Point& p : touch_points_)
      if (locally_overlapping(p)) return Overlap::overlapping;
    for (int side = 0; side < 2; ++side)
      if (loop_inside_other(side)) return Overlap::overlapping;
    return touch_points_.empty() && !shared_ ? Overlap::apart : Overlap::touching;
  }

  const std::vector<Point>& touch_points() const { return touch_points_; }
  const Site& site() const { return site_; }

  // Edges of part `side` through p (exact), with endpoint flags.
  std::vector<TouchEdge> edges_through(int side, const Point& p) {
    std::vector<TouchEdge> result;
    PlacedPart& part = *parts_[side];
    double px = p.x.get_d();
    double py = p.y.get_d();
    for (std::size_t i = 0; i < part.size(); ++i) {
      if (!part.box(i).contains(px, py)) continue;
      const PlacedEdge& e = part.edge(i);
      if (!on_edge(e, p)) continue;
      result.push_back(TouchEdge{e.loop, e.index, p == e.source, p == e.target});
    }
    return result;
  }

 private:
  // ---------------------------------------------------------------- edge pairs

  // Returns true on overlap.
  bool intersect(std::size_t i, std::size_t j) {
    const PlacedEdge& ea = parts_[0]->edge(i);
    const PlacedEdge& eb = parts_[1]->edge(j);
    if (!ea.arc && !eb.arc) return segment_segment(ea, eb);
    if (!ea.arc) return segment_arc(ea, eb, true);
    if (!eb.arc) return segment_arc(eb, ea, false);
    return arc_arc(ea, eb);
  }

  void touch(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb) {
    touched_[0][ea.loop] = true;
    touched_[1][eb.loop] = true;
    for (const Point& q : touch_points_)
      if (q == p) return;
    touch_points_.push_back(p);
  }

  bool overlap_at(const Point& p) {
    site_ = Site{p, true};
    return true;
  }

  // Inward normal (exact, not unit) of an edge's material near point p.
  static Point inward_normal(const PlacedEdge& e, const Point& p) {
    if (!e.arc) return left_perpendicular(minus(e.target, e.source));
    Point to_centre = minus(e.center, p);
    return e.ccw ? to_centre : Point{Rational(-to_centre.x), Rational(-to_centre.y)};
  }

  // Overlap found at a transversal crossing of ea and eb near p: the sum of the inward
  // normals points into both materials.
  bool crossing_at(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb) {
    site_ = Site{p, true};
    crossing_edges_ = {&ea, &eb};
    return true;
  }

  // A rational common point of ea and eb, known to lie on both underlying curves.
  // `transversal`: the curves cross there (not tangent).
  bool common_point(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb, bool transversal) {
    if (!on_edge(ea, p) || !on_edge(eb, p)) return false;
    if (transversal && !is_endpoint(ea, p) && !is_endpoint(eb, p)) return crossing_at(p, ea, eb);
    touch(p, ea, eb);
    return false;
  }

  void endpoints_on(const PlacedEdge& ea, const PlacedEdge& eb) {
    for (const Point* p : {&ea.source, &ea.target})
      if (on_edge(eb, *p)) touch(*p, ea, eb);
    for (const Point* p : {&eb.source, &eb.target})
      if (on_edge(ea, *p)) touch(*p, ea, eb);
  }

  bool segment_segment(const PlacedEdge& ea, const PlacedEdge& eb) {
    Point da = minus(ea.target, ea.source);
    Point db = minus(eb.target, eb.source);
    int o1 = sign_of(cross(db, minus(ea.source, eb.source)));
    int o2 = sign_of(cross(db, minus(ea.target, eb.source)));
    int o3 = sign_of(cross(da, minus(eb.source, ea.source)));
    int o4 = sign_of(cross(da, minus(eb.target, ea.source)));
    if (o1 * o2 < 0 && o3 * o4 < 0) {
      // proper crossing; the point is rational
      Rational t = cross(db, minus(eb.source, ea.source)) / cross(db, da);
      return crossing_at(Point{Rational(ea.source.x + t * da.x), Rational(ea.source.y + t * da.y)},
                         ea, eb);
    }
    if (o1 == 0 && o2 == 0) {
      // collinear: common piece of positive length?
      Rational length = dot(da, da);
      Rational u0 = dot(minus(eb.source, ea.source), da);
      Rational u1 = dot(minus(eb.target, ea.source), da);
      Rational low = std::max(Rational(0), std::min(u0, u1));
      Rational high = std::min(length, std::max(u0, u1));
      if (low < high) {
        if (sgn(dot(da, db)) > 0) {
          Rational middle = (low + high) / (2 * length);
          Point p{Rational(ea.source.x + middle * da.x), Rational(ea.source.y + middle * da.y)};
          hints_.push_back(inward_normal(ea, p));
          return overlap_at(p);
        }
        shared_ = true;
        touched_[0][ea.loop] = true;
        touched_[1][eb.loop] = true;
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  bool segment_arc(const PlacedEdge& segment, const PlacedEdge& arc, bool segment_first) {
    // ea / eb: the same edges as (first part, second part), for touch bookkeeping.
    const PlacedEdge& ea = segment_first ? segment : arc;
    const PlacedEdge& eb = segment_first ? arc : segment;
    Point d = minus(segment.target, segment.source);
    Point f = minus(segment.source, arc.center);
    Rational a = dot(d, d);
    Rational b = dot(d, f);
    Rational c = dot(f, f) - arc.radius_squared;
    Rational disc = b * b - a * c;
    int sd = sgn(disc);
    if (sd >= 0) {
      std::optional<Rational> root = exact_square_root(disc);
      if (root) {
        for (int k = 0; k < (sd == 0 ? 1 : 2); ++k) {
          Rational lambda = (-b + (k == 0 ? *root : Rational(-*root))) / a;
          Point p{Rational(segment.source.x + lambda * d.x),
                  Rational(segment.source.y + lambda * d.y)};
          if (common_point(p, ea, eb, sd > 0)) return true;
        }
      } else {
        // Irrational crossing points: never endpoints; overlap iff one lies strictly inside
        // both edges.
        for (int k = 0; k < 2; ++k) {
          Rational sign = k == 0 ? 1 : -1;
          // lambda = (-b + sign sqrt(disc)) / a ; 0 < lambda < 1
          if (sign_with_root(Rational(-b), sign, disc) <= 0) continue;
          if (sign_with_root(Rational(-b - a), sign, disc) >= 0) continue;
          if (!arc.sector.full) {
            Point start{arc.sector.start.x, arc.sector.start.y};
            Point end{arc.sector.end.x, arc.sector.end.y};
            // a * cross(start, f + lambda d) = [a cross(start,f) - b cross(start,d)] + sign cross(start,d) sqrt
            Rational sd_start = cross(start, d);
            int after = sign_with_root(Rational(a * cross(start, f) - b * sd_start),
                                       Rational(sign * sd_start), disc);
            Rational sd_end = cross(d, end);
            int before = sign_with_root(Rational(a * cross(f, end) - b * sd_end),
                                        Rational(sign * sd_end), disc);
            bool inside = arc.sector.large ? (after > 0 || before > 0) : (after > 0 && before > 0);
            if (!inside) continue;
          }
          Rational lambda = (-b + sign * approximate_sqrt(disc)) / a;
          return crossing_at(Point{Rational(segment.source.x + lambda * d.x),
                                   Rational(segment.source.y + lambda * d.y)},
                             ea, eb);
        }
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  bool arc_arc(const PlacedEdge& ea, const PlacedEdge& eb) {
    Point d = minus(eb.center, ea.center);
    Rational distance2 = dot(d, d);
    if (sgn(distance2) == 0) {
      if (ea.radius_squared == eb.radius_squared && arcs_share_piece(ea, eb)) {
        if (ea.ccw == eb.ccw) {
          // same side of a common arc: overlap near any common point
          const Point& p = in_sector(eb, minus(ea.source, eb.center)) ? ea.source : eb.source;
          hints_.push_back(inward_normal(ea, p));
          return overlap_at(p);
        }
        shared_ = true;
        touched_[0][ea.loop] = true;
        touched_[1][eb.loop] = true;
      }
      endpoints_on(ea, eb);
      return false;
    }
    Rational m = distance2 + ea.radius_squared - eb.radius_squared;
    Rational h = 4 * distance2 * ea.radius_squared - m * m;
    int sh = sgn(h);
    if (sh >= 0) {
      Point perpendicular = left_perpendicular(d);
      std::optional<Rational> root = exact_square_root(h);
      Rational scale = 2 * distance2;
      if (root) {
        for (int k = 0; k < (sh == 0 ? 1 : 2); ++k) {
          Rational beta = k == 0 ? *root : Rational(-*root);
          Point p{Rational(ea.center.x + (m * d.x + beta * perpendicular.x) / scale),
                  Rational(ea.center.y + (m * d.y + beta * perpendicular.y) / scale)};
          if (common_point(p, ea, eb, sh > 0)) return true;
        }
      } else {
        for (int k = 0; k < 2; ++k) {
          Rational sign = k == 0 ? 1 : -1;
          // 2 D2 (x - ka) = m d + sign sqrt(h) perp ; 2 D2 (x - kb) = (m - 2 D2) d + sign sqrt(h) perp
          if (!strictly_in_arc(ea, d, perpendicular, m, sign, h)) continue;
          if (!strictly_in_arc(eb, d, perpendicular, Rational(m - scale), sign, h)) continue;
          Rational beta = sign * approximate_sqrt(h) / scale;
          Rational alpha = m / scale;
          return crossing_at(Point{Rational(ea.center.x + alpha * d.x + beta * perpendicular.x),
                                   Rational(ea.center.y + alpha * d.y + beta * perpendicular.y)},
                             ea, eb);
        }
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  // Whether the irrational point with (x - centre) = (alpha d + sign sqrt(h) perp) / positive
  // lies in the arc's sector (never on its boundary rays: those carry rational points).
  static bool strictly_in_arc(const PlacedEdge& arc, const Point& d, const Point& perpendicular,
                              const Rational& alpha, const Rational& sign, const Rational& h) {
    if (arc.sector.full) return true;
    Point start{arc.sector.start.x, arc.sector.start.y};
    Point end{arc.sector.end.x, arc.sector.end.y};
    int after = sign_with_root(Rational(alpha * cross(start, d)),
                               Rational(sign * cross(start, perpendicular)), h);
    int before = sign_with_root(Rational(alpha * cross(d, end)),
                                Rational(sign * cross(perpendicular, end)), h);
    return arc.sector.large ? (after > 0 || before > 0) : (after > 0 && before > 0);
  }

  // Cocircular arcs: do they share a piece of positive length?
  static bool arcs_share_piece(const PlacedEdge& ea, const PlacedEdge& eb) {
    if (ea.sector.full || eb.sector.full) return true;
    auto starts_inside = [](const PlacedEdge& x, const PlacedEdge& y) {
      // start of y in [start of x, end of x)
      Point start{y.sector.start.x, y.sector.start.y};
      Point end{x.sector.end.x, x.sector.end.y};
      if (!sector_contains(x.sector, start)) return false;
      return !(sgn(cross(start, end)) == 0 && sgn(dot(start, end)) > 0);
    };
    return starts_inside(ea, eb) || starts_inside(eb, ea);
  }

 private:
  // ---------------------------------------------------------------- local analysis

  struct Germ {
    Point direction;
    int curvature_sign = 0;
    Rational radius_squared;
    bool forward = true;
    int owner = 0;
  };

  static int half(const Point& d) { return (sgn(d.y) > 0 || (sgn(d.y) == 0 && sgn(d.x) > 0)) ? 0 : 1; }

  // -1, 0, +1: order of germs counter-clockwise from direction (1, 0).
  static int compare(const Germ& g, const Germ& h) {
    int hg = half(g.direction);
    int hh = half(h.direction);
    if (hg != hh) return hg < hh ? -1 : 1;
    int c = sgn(cross(g.direction, h.direction));
    if (c > 0) return -1;
    if (c < 0) return 1;
    // same tangent: the germ curving more to the left comes later
    if (g.curvature_sign != h.curvature_sign) return g.curvature_sign < h.curvature_sign ? -1 : 1;
    if (g.curvature_sign == 0) return 0;
    int r = cmp(g.radius_squared, h.radius_squared);  // larger radius: smaller |curvature|
    if (r == 0) return 0;
    return (g.curvature_sign > 0) == (r > 0) ? -1 : 1;
  }

  void add_germs(int owner, const PlacedEdge& e, const Point& p, std::vector<Germ>& germs) {
    bool at_source = p == e.source;
    bool at_target = p == e.target;
    bool interior = !at_source && !at_target;
    bool forward_present = at_source || interior;
    bool backward_present = at_target || interior;
    Point tangent;
    int curvature = 0;
    if (e.arc) {
      Point left = left_perpendicular(minus(p, e.center));
      tangent = e.ccw ? left : Point{Rational(-left.x), Rational(-left.y)};
      curvature = e.ccw ? 1 : -1;
    } else {
      tangent = minus(e.target, e.source);
    }
    if (forward_present)
      germs.push_back(Germ{tangent, curvature, e.radius_squared, true, owner});
    if (backward_present)
      germs.push_back(Germ{Point{Rational(-tangent.x), Rational(-tangent.y)}, -curvature,
                           e.radius_squared, false, owner});
  }

  bool locally_overlapping(const Point& p) {
    std::vector<Germ> germs;
    double px = p.x.get_d();
    double py = p.y.get_d();
    for (int side = 0; side < 2; ++side) {
      PlacedPart& part = *parts_[side];
      for (std::size_t i = 0; i < part.size(); ++i) {
        if (!part.box(i).contains(px, py)) continue;
        const PlacedEdge& e = part.edge(i);
        if (on_edge(e, p)) add_germs(side, e, p, germs);
      }
    }
    std::sort(germs.begin(), germs.end(),
              [](const Germ& g, const Germ& h) { return compare(g, h) < 0; });
    // Groups of identical germs; material state of each part after each group.
    std::vector<std::size_t> group_start;
    for (std::size_t i = 0; i < germs.size(); ++i)
      if (i == 0 || compare(germs[i - 1], germs[i]) != 0) group_start.push_back(i);
    std::size_t groups = group_start.size();
    if (groups == 0) return false;
    std::vector<std::array<int, 2>> after(groups, {-1, -1});  // -1: part has no germ here
    for (std::size_t g = 0; g < groups; ++g) {
      std::size_t end = g + 1 < groups ? group_start[g + 1] : germs.size();
      for (std::size_t i = group_start[g]; i < end; ++i) {
        int& state = after[g][static_cast<std::size_t>(germs[i].owner)];
        if (germs[i].forward) {
          state = 1;
        } else if (state != 1) {
          state = 0;
        }
      }
    }
    std::array<int, 2> state{-1, -1};
    for (int side = 0; side < 2; ++side)
      for (std::size_t g = 0; g < groups; ++g)
        if (after[g][static_cast<std::size_t>(side)] >= 0)
          state[static_cast<std::size_t>(side)] = after[g][static_cast<std::size_t>(side)];
    for (std::size_t g = 0; g < groups; ++g) {
      for (int side = 0; side < 2; ++side)
        if (after[g][static_cast<std::size_t>(side)] >= 0)
          state[static_cast<std::size_t>(side)] = after[g][static_cast<std::size_t>(side)];
      if (state[0] == 1 && state[1] == 1) {
        // the sector between group g and the next one is material of both
        const Germ& from = germs[group_start[g]];
        const Germ& to = germs[group_start[(g + 1) % groups]];
        site_ = Site{p, true};
        hints_.push_back(bisector(from.direction, to.direction, groups == 1));
        return true;
      }
    }
    return false;
  }

  static Point bisector(const Point& from, const Point& to, bool whole_turn) {
    double fx = from.x.get_d(), fy = from.y.get_d(), tx = to.x.get_d(), ty = to.y.get_d();
    double a = std::atan2(fy, fx);
    double b = std::atan2(ty, tx);
    double span = b - a;
    while (span <= 0) span += 2 * M_PI;
    if (whole_turn) span = 2 * M_PI;
    double m = a + span / 2;
    return Point{Rational(std::cos(m)), Rational(std::sin(m))};
  }

  // ---------------------------------------------------------------- containment

  bool loop_inside_other(int side) {
    PlacedPart& part = *parts_[side];
    PlacedPart& other = *parts_[1 - side];
    for (std::size_t l = 0; l < part.loops(); ++l) {
      if (touched_[side][l]) continue;
      if (!part.loop_box(l).meets(other.total())) continue;
      std::size_t first = part.loop_begin(l);
      if (first == part.loop_end(l)) continue;
      const Point& probe = part.edge(first).source;
      if (locate(other, probe) == PointLocation::inside) {
        site_ = Site{probe, true};
        material_hints(side, probe);
        return true;
      }
    }
    return false;
  }

 public:
  /// A rational point strictly inside both parts near the overlap site, or nullopt.
  /// Candidates site + delta * u are tried for hint directions u (into both materials) at
  /// scales delta = size * 2^-k down to the precision of the site, and for 16 fixed
  /// directions at coarse scales; each candidate is verified exactly.
  std::optional<Point> find_witness() {
    if (!site_.known) return std::nullopt;
    std::vector<Point> hints;
    if (crossing_edges_[0]) {
      // Sum of the unit inward normals of two crossing edges points into both materials.
      Point na = approximate_unit(inward_normal(*crossing_edges_[0], site_.point));
      Point nb = approximate_unit(inward_normal(*crossing_edges_[1], site_.point));
      hints.push_back(Point{Rational(na.x + nb.x), Rational(na.y + nb.y)});
    }
    for (const Point& h : hints_) hints.push_back(approximate_unit(h));
    std::vector<Point> directions;
    for (int k = 0; k < 16; ++k)
      directions.push_back(Point{Rational(std::cos(k * M_PI / 8 + 0.1)),
                                 Rational(std::sin(k * M_PI / 8 + 0.1))});
    const Box& total = parts_[1]->total();
    double size = std::max({total.xhi - total.xlo, total.yhi - total.ylo, 1e-6});
    Rational step = Rational(size) / 4;
    auto inside_both = [&](const Point& direction) {
      Point candidate{Rational(site_.point.x + step * direction.x),
                      Rational(site_.point.y + step * direction.y)};
      if (locate(*parts_[0], candidate) == PointLocation::inside &&
          locate(*parts_[1], candidate) == PointLocation::inside)
        return std::optional<Point>(candidate);
      return std::optional<Point>();
    };
    for (int level = 2; level < static_cast<int>(witness_bits) - 40; ++level) {
      for (const Point& h : hints)
        if (auto found = inside_both(h)) return found;
      if (level < 40)
        for (const Point& d : directions)
          if (auto found = inside_both(d)) return found;
      step /= 2;
    }
    return std::nullopt;
  }

 private:
  // Directions into part `side`'s material at boundary point p.
  void material_hints(int side, const Point& p) {
    PlacedPart& part = *parts_[side];
    std::vector<Germ> germs;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const PlacedEdge& e = part.edge(i);
      if (on_edge(e, p)) add_germs(side, e, p, germs);
    }
    std::sort(germs.begin(), germs.end(),
              [](const Germ& g, const Germ& h) { return compare(g, h) < 0; });
    for (std::size_t i = 0; i < germs.size(); ++i)
      if (germs[i].forward)
        hints_.push_back(bisector(germs[i].direction, germs[(i + 1) % germs.size()].direction,
                                  germs.size() == 1));
  }

 public:
  // Exact location of p relative to a placed part (see locate_point).
  static PointLocation locate(PlacedPart& part, const Point& p) {
    double px = p.x.get_d();
    double py = p.y.get_d();
    const Box& total = part.total();
    if (!total.contains(px, py)) return PointLocation::outside;
    for (std::size_t i = 0; i < part.size(); ++i)
      if (part.box(i).contains(px, py) && on_edge(part.edge(i), p)) return PointLocation::boundary;
    // Parity of crossings of the ray from p' = p + (eps^2, eps) towards +x.
    bool inside = false;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const Box& box = part.box(i);
      if (box.xhi < px || box.yhi < py || box.ylo > py) continue;  // cannot meet the ray
      const PlacedEdge& e = part.edge(i);
      if (!e.arc) {
        if (ray_crosses_chord(e.source, e.target, p)) inside = !inside;
        continue;
      }
      if (!e.full && ray_crosses_chord(e.source, e.target, p)) inside = !inside;
      if (in_lens(e, p)) inside = !inside;
    }
    return inside ? PointLocation::inside : PointLocation::outside;
  }

 private:
  // Sign of orient(a, b, p + (eps^2, eps)), lexicographic in eps.
  static int perturbed_orientation(const Point& a, const Point& b, const Point& p) {
    int s = sgn(cross(minus(b, a), minus(p, a)));
    if (s != 0) return s;
    s = sgn(b.x - a.x);
    if (s != 0) return s;
    return -sgn(b.y - a.y);
  }

  static bool ray_crosses_chord(const Point& a, const Point& b, const Point& p) {
    bool a_above = a.y > p.y;  // a.y > p.y + eps  <=>  a.y > p.y
    bool b_above = b.y > p.y;
    if (a_above == b_above) return false;
    int o = perturbed_orientation(a, b, p);
    return b_above ? o > 0 : o < 0;  // upward: crossing to the right iff p' left of a->b
  }

  // p' strictly inside the region bounded by the arc and its chord (the whole disk for a
  // full circle).
  static bool in_lens(const PlacedEdge& e, const Point& p) {
    Point v = minus(p, e.center);
    int s = sgn(dot(v, v) - e.radius_squared);
    if (s == 0) s = sgn(v.y);
    if (s == 0) s = sgn(2 * v.x + 1);
    if (s == 0) s = 1;
    if (s >= 0) return false;
    if (e.full) return true;
    int side = perturbed_orientation(e.source, e.target, p);
    return e.ccw ? side < 0 : side > 0;
  }

  std::array<PlacedPart*, 2> parts_;
  std::array<std::vector<bool>, 2> touched_;
  std::vector<Point> touch_points_;
  bool shared_ = false;
  Site site_;
  std::vector<Point> hints_;
  std::array<const PlacedEdge*, 2> crossing_edges_{nullptr, nullptr};
};

RigidMap inverse(const RigidMap& map) {
  RigidMap result;
  result.c = map.c;
  result.s = -map.s;
  result.offset = Point{Rational(-(map.c * map.offset.x + map.s * map.offset.y)),
                        Rational(-(-map.s * map.offset.x + map.c * map.offset.y))};
  return result;
}

// (outer o inner)(p) = outer(inner(p))
RigidMap compose(const RigidMap& outer, const RigidMap& inner) {
  RigidMap result;
  result.c = outer.c * inner.c - outer.s * inner.s;
  result.s = outer.s * inner.c + outer.c * inner.s;
  Point moved = outer.rotate(inner.offset);
  result.offset = Point{Rational(moved.x + outer.offset.x), Rational(moved.y + outer.offset.y)};
  return result;
}

}  // namespace

OverlapReport analyse_overlap(const Part& first, const RigidMap& first_map, const Part& second,
                              const RigidMap& second_map, const OverlapOptions& options) {
  RigidMap relative = compose(inverse(second_map), first_map);
  PlacedPart a(first, relative, false);
  PlacedPart b(second, RigidMap{}, true);
  OverlapAnalysis analysis(a, b);
  OverlapReport report;
  report.relation = analysis.run();
  if (options.want_touches && report.relation == Overlap::touching) {
    for (const Point& p : analysis.touch_points()) {
      TouchPoint touch;
      touch.point = second_map.apply(p);
      touch.first_edges = analysis.edges_through(0, p);
      touch.second_edges = analysis.edges_through(1, p);
      report.touches.push_back(std::move(touch));
    }
  }
  if (options.want_witness && report.relation == Overlap::overlapping) {
    std::optional<Point> witness = analysis.find_witness();
    if (witness) report.witness = second_map.apply(*witness);
  }
  return report;
}

namespace {

std::pair<RigidMap, RigidMap> world_maps(const Model& model, const PairAxes& axes,
                                         const ChartAxis& x, const ChartAxis& y,
                                         const ChartPoint& q) {
  const ChartAxis& second_axis = axes.first_moves ? y : x;
  const Rational& second_value = axes.first_moves ? q.y : q.x;
  return {world_map(model.parts.at(axes.first), axes.first_moves, x, q.x),
          world_map(model.parts.at(axes.second), axes.second_moves, second_axis, second_value)};
}

}  // namespace

OverlapReport analyse_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                              const ChartAxis& y, const ChartPoint& q,
                              const OverlapOptions& options) {
  auto [first_map, second_map] = world_maps(model, axes, x, y, q);
  return analyse_overlap(model.parts.at(axes.first), first_map, model.parts.at(axes.second),
                         second_map, options);
}

Overlap classify_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                         const ChartAxis& y, const ChartPoint& q) {
  return analyse_overlap(model, axes, x, y, q).relation;
}

std::optional<Point> interior_witness(const Model& model, const PairAxes& axes,
                                      const ChartAxis& x, const ChartAxis& y,
                                      const ChartPoint& q) {
  OverlapOptions options;
  options.want_witness = true;
  return analyse_overlap(model, axes, x, y, q, options).witness;
}

PointLocation locate_point(const Part& part, const RigidMap& map, const Point& p) {
  // Locate in the part's body frame.
  RigidMap back = inverse(map);
  PlacedPart placed(part, RigidMap{}, true);
  return OverlapAnalysis::locate(placed, back.apply(p));
}

}  // namespace hipair::cspace
