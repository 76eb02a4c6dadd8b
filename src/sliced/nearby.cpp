// Feature pairs near a configuration (see nearby.hpp).
#include "sliced/nearby.hpp"

#include "sliced/motion.hpp"

#include "kernels/distance.hpp"

#include <algorithm>
#include <optional>

namespace hipair::sliced {
namespace {

// Certified rational bounds of sqrt(x), x >= 0, 2^-40 relative to the denominator.
struct Bounds {
  Rational lo, hi;
};
Bounds root_bounds(const Rational& x) {
  const unsigned bits = 40;
  mpz_class n = x.get_num() * x.get_den();
  n <<= 2 * bits;
  mpz_class floor_root;
  mpz_sqrt(floor_root.get_mpz_t(), n.get_mpz_t());
  mpz_class scale = x.get_den() * (mpz_class(1) << bits);
  Rational lo(floor_root, scale), hi(floor_root * floor_root == n ? floor_root : mpz_class(floor_root + 1), scale);
  lo.canonicalize();
  hi.canonicalize();
  return {lo, hi};
}
Bounds abs_difference(const Bounds& a, const Bounds& b) {   // |a - b|
  Rational lo = std::max({Rational(0), Rational(a.lo - b.hi), Rational(b.lo - a.hi)});
  Rational hi = std::max(Rational(a.hi - b.lo), Rational(b.hi - a.lo));
  return {lo, hi};
}

Rational cross(const Point& a, const Point& b) { return a.x * b.y - a.y * b.x; }
Rational dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }
Point minus(const Point& a, const Point& b) { return Point{Rational(a.x - b.x), Rational(a.y - b.y)}; }

struct Arc {
  Point center, from, to, source, target;
  Rational r2;
  bool full = false, reflex = false;
};
bool in_sector(const Arc& a, const Point& direction) {
  if (a.full) return true;
  int s1 = sgn(cross(a.from, direction)), s2 = sgn(cross(direction, a.to));
  return a.reflex ? (s1 >= 0 || s2 >= 0) : (s1 >= 0 && s2 >= 0);
}

// Sign of a + b sqrt(c), c >= 0.
int sign_with_root(const Rational& a, const Rational& b, const Rational& c) {
  int sa = sgn(a), sb = sgn(b) * (sgn(c) > 0 ? 1 : 0);
  if (sa == sb || sb == 0) return sa != 0 ? sa : sb;
  if (sa == 0) return sb;
  Rational d = a * a - b * b * c;   // |a| vs |b| sqrt(c)
  return sa * sgn(d);
}

struct PointResult {
  Bounds distance;
  bool within;   // exact: distance <= delta
};

PointResult point_arc(const Point& p, const Arc& a, const Rational& delta) {
  Point q = minus(p, a.center);
  if (in_sector(a, q)) {
    // distance = | |q| - r |; <= delta iff |q| <= r + delta and |q| >= r - delta, with
    // A = |q|^2 - r^2 - delta^2: |q| <= r + delta iff A <= 2 delta r; |q| >= r - delta iff A >= -2 delta r
    Rational q2 = dot(q, q), A = q2 - a.r2 - delta * delta;
    bool upper = sign_with_root(-A, 2 * delta, a.r2) >= 0;
    bool lower = sign_with_root(A, 2 * delta, a.r2) >= 0;
    return {abs_difference(root_bounds(q2), root_bounds(a.r2)), upper && lower};
  }
  Point s = minus(p, a.source), t = minus(p, a.target);
  Rational d2 = std::min(dot(s, s), dot(t, t));
  return {root_bounds(d2), d2 <= delta * delta};
}

}  // namespace

std::vector<NearPair> near_features(const Model& model, std::size_t fixed, std::size_t free, const SlicedConfiguration& q,
                                    const Rational& delta) {
  const Part& a = model.parts[fixed];
  const Part& b = model.parts[free];
  auto [c, s] = q.angle.half_turn ? std::pair<Rational, Rational>{Rational(-1), Rational(0)}
                                  : chart_rotation(q.angle.t, false);
  const Point pivot = b.motion.pivot;
  auto place = [&](const Point& p, bool moving) {
    if (!moving) return p;
    Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
    return Point{Rational(pivot.x + c * dx - s * dy + q.x), Rational(pivot.y + s * dx + c * dy + q.y)};
  };
  struct Features {
    std::vector<std::pair<Point, FeatureIdentity>> vertices;
    std::vector<std::pair<std::pair<Point, Point>, FeatureIdentity>> segments;
    std::vector<std::pair<Arc, FeatureIdentity>> arcs;
  };
  auto collect = [&](const Part& part, std::size_t index, bool moving) {
    Features out;
    for (std::size_t l = 0; l < part.loops.size(); ++l)
      for (std::size_t k = 0; k < part.loops[l].edges.size(); ++k) {
        const Edge& e = part.loops[l].edges[k];
        Point p0 = place(e.source, moving), p1 = place(e.target, moving);
        if (!e.is_full_circle()) out.vertices.push_back({p0, FeatureIdentity{index, l, k, FeatureKind::vertex}});
        if (!e.is_arc()) {
          out.segments.push_back({{p0, p1}, FeatureIdentity{index, l, k, FeatureKind::segment}});
          continue;
        }
        Arc arc;
        arc.center = place(e.center, moving);
        arc.source = p0;
        arc.target = p1;
        Point u = minus(p0, arc.center), v = minus(p1, arc.center);
        arc.from = e.ccw ? u : v;
        arc.to = e.ccw ? v : u;
        arc.r2 = e.radius_squared;
        arc.full = e.is_full_circle();
        arc.reflex = !arc.full && sgn(cross(arc.from, arc.to)) < 0;
        out.arcs.push_back({arc, FeatureIdentity{index, l, k, FeatureKind::arc}});
      }
    return out;
  };
  const Features fa = collect(a, fixed, false), fb = collect(b, free, true);
  std::vector<NearPair> out;
  auto keep = [&](const FeatureIdentity& f, const FeatureIdentity& g, const Bounds& d, std::optional<bool> within) {
    bool near = within ? *within : d.lo <= delta;
    if (!near) return;
    out.push_back(NearPair{f, g, d.lo, d.hi, within.has_value()});
  };
  // vertex–segment, vertex–arc (exact)
  for (int side = 0; side < 2; ++side) {
    const Features& vs = side ? fb : fa;
    const Features& es = side ? fa : fb;
    for (const auto& [p, vid] : vs.vertices) {
      for (const auto& [seg, sid] : es.segments) {
        Rational d2 = kernels::point_segment_squared_distance(p, seg.first, seg.second);
        side ? keep(sid, vid, root_bounds(d2), d2 <= delta * delta) : keep(vid, sid, root_bounds(d2), d2 <= delta * delta);
      }
      for (const auto& [arc, aid] : es.arcs) {
        PointResult r = point_arc(p, arc, delta);
        side ? keep(aid, vid, r.distance, r.within) : keep(vid, aid, r.distance, r.within);
      }
    }
  }
  // segment–arc: lower bound from the line and the circle, upper bound from actual points
  for (int side = 0; side < 2; ++side) {
    const Features& ss = side ? fb : fa;
    const Features& as = side ? fa : fb;
    for (const auto& [seg, sid] : ss.segments)
      for (const auto& [arc, aid] : as.arcs) {
        Point d = minus(seg.second, seg.first), w = minus(arc.center, seg.first);
        Rational k = cross(d, w), length2 = dot(d, d);
        Bounds h = root_bounds(k * k / length2), r = root_bounds(arc.r2);
        // every point of the segment lies at least the centre's distance from the segment (not
        // its line: session 63, hunt63) from the centre, so at least that minus r from the circle;
        // the line's distance let a disc flying along a long floor's line far beyond its end
        // advance by the floor's height per step (gravity 1.8e308 along the floor: > 10 min)
        Bounds centre = root_bounds(kernels::point_segment_squared_distance(arc.center, seg.first, seg.second));
        Rational lo = std::max(Rational(0), Rational(centre.lo - r.hi));
        Rational hi = std::min(root_bounds(kernels::point_segment_squared_distance(arc.source, seg.first, seg.second)).hi,
                               std::min(point_arc(seg.first, arc, delta).distance.hi, point_arc(seg.second, arc, delta).distance.hi));
        if (arc.full) hi = std::min(point_arc(seg.first, arc, delta).distance.hi, point_arc(seg.second, arc, delta).distance.hi);
        Rational along = dot(w, d);
        Point toward{Rational(-sgn(k) * -d.y), Rational(-sgn(k) * d.x)};   // from the centre to the line
        if (sgn(along) >= 0 && along <= length2 && sgn(k) != 0 && in_sector(arc, toward))
          hi = std::min(hi, abs_difference(h, r).hi);
        Bounds bounds{lo, std::max(lo, hi)};
        side ? keep(aid, sid, bounds, std::nullopt) : keep(sid, aid, bounds, std::nullopt);
      }
  }
  // arc–arc: lower bound from the circles
  for (const auto& [x, xid] : fa.arcs)
    for (const auto& [y, yid] : fb.arcs) {
      Point n = minus(y.center, x.center);
      Bounds D = root_bounds(dot(n, n)), r1 = root_bounds(x.r2), r2 = root_bounds(y.r2);
      Rational lo = std::max({Rational(0), Rational(D.lo - r1.hi - r2.hi), Rational(abs_difference(r1, r2).lo - D.hi)});
      // (an arc's source is a point of it, also for a full circle)
      Rational hi = std::min(point_arc(x.source, y, delta).distance.hi, point_arc(y.source, x, delta).distance.hi);
      Bounds bounds{lo, std::max(lo, hi)};
      keep(xid, yid, bounds, std::nullopt);
    }
  std::sort(out.begin(), out.end(), [](const NearPair& p, const NearPair& q) { return p.lower < q.lower; });
  return out;
}

}  // namespace hipair::sliced
