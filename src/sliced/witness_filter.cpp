// The pin-slot stack's witness filter (see witness_filter.hpp).
#include "sliced/witness_filter.hpp"

#include "kernels/interval.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <vector>

namespace hipair::pinslot {

// Is the boundary of `turning` (shifted by `shift`, then turned about `pivot` by psi with
// tan(psi/2) = tau) certainly apart from the boundary of `fixed` for every tau in [a, b]?
// Certified double intervals: each turning edge over [a, b] lies in the hull of its ends'
// enclosures (at each tau the edge is the segment between its ends); a fixed edge certainly
// misses that box when their boxes are certainly disjoint or the box's four corners are
// certainly strictly on one side of the edge's line, or the fixed edge's ends certainly strictly
// on one side of the turning edge's line (its ends in their enclosures). Undecided pairs bisect [a, b] (depth 4),
// then the answer is false (the caller takes the exact path). Segments only (arcs: false).
bool boundaries_certainly_apart(const Part& fixed, const Part& turning, const Point& pivot, const Point& shift,
                                const Rational& a, const Rational& b) {
  using kernels::Interval;
  struct Seg {
    Interval px, py, qx, qy;
  };
  auto segments = [](const Part& part, std::vector<Seg>& out, const Point& offset) {
    for (const auto& loop : part.loops)
      for (const auto& e : loop.edges) {
        if (e.is_arc()) return false;
        out.push_back(Seg{Interval::enclose(Rational(e.source.x + offset.x)), Interval::enclose(Rational(e.source.y + offset.y)),
                          Interval::enclose(Rational(e.target.x + offset.x)), Interval::enclose(Rational(e.target.y + offset.y))});
      }
    return true;
  };
  std::vector<Seg> fixed_edges, turning_edges;
  if (!segments(fixed, fixed_edges, Point{Rational(0), Rational(0)})) return false;
  // turning edges relative to the pivot, shifted
  if (!segments(turning, turning_edges, Point{Rational(shift.x - pivot.x), Rational(shift.y - pivot.y)})) return false;
  const Interval cx = Interval::enclose(pivot.x), cy = Interval::enclose(pivot.y);
  auto hull = [](const Interval& u, const Interval& v) { return Interval(std::min(u.lo, v.lo), std::max(u.hi, v.hi)); };
  std::function<bool(const Interval&, int)> apart = [&](const Interval& t, int depth) {
    const Interval t2 = t * t, den = Interval(1) + t2;
    const Interval c = (Interval(1) - t2) / den, s = (Interval(2) * t) / den;
    for (const auto& m : turning_edges) {
      const Interval x = hull(cx + c * m.px - s * m.py, cx + c * m.qx - s * m.qy);
      const Interval y = hull(cy + s * m.px + c * m.py, cy + s * m.qx + c * m.qy);
      if (!(x.hi < std::numeric_limits<double>::infinity()) || !(x.lo > -std::numeric_limits<double>::infinity()) ||
          !(y.hi < std::numeric_limits<double>::infinity()) || !(y.lo > -std::numeric_limits<double>::infinity()))
        return false;
      for (const auto& f : fixed_edges) {
        if (std::max(f.px.hi, f.qx.hi) < x.lo || std::min(f.px.lo, f.qx.lo) > x.hi || std::max(f.py.hi, f.qy.hi) < y.lo ||
            std::min(f.py.lo, f.qy.lo) > y.hi)
          continue;
        const Interval dx = f.qx - f.px, dy = f.qy - f.py;
        int side = 0;
        bool one_side = true;
        for (double u : {x.lo, x.hi})
          for (double v : {y.lo, y.hi}) {
            const int k = (dx * (Interval(v, v) - f.py) - dy * (Interval(u, u) - f.px)).sign();
            if ((k != 1 && k != -1) || (side != 0 && k != side)) one_side = false;
            side = k;
          }
        if (one_side) continue;
        // or the fixed edge's two ends certainly strictly on one side of the turning edge's
        // line, for every pair of ends (p, q) in their enclosures over the range (so at every tau
        // of it): the fixed edge misses that line, hence the edge
        {
          const Interval ex0 = cx + c * m.px - s * m.py, ey0 = cy + s * m.px + c * m.py;
          const Interval ex1 = cx + c * m.qx - s * m.qy, ey1 = cy + s * m.qx + c * m.qy;
          const Interval mx = ex1 - ex0, my = ey1 - ey0;
          const int k0 = (mx * (f.py - ey0) - my * (f.px - ex0)).sign();
          const int k1 = (mx * (f.qy - ey0) - my * (f.qx - ex0)).sign();
          if ((k0 == 1 || k0 == -1) && k0 == k1) continue;
        }
        if (depth == 0) return false;
        const double mid = t.middle();
        if (!(t.lo < mid && mid < t.hi)) return false;
        return apart(Interval(t.lo, mid), depth - 1) && apart(Interval(mid, t.hi), depth - 1);
      }
    }
    return true;
  };
  return apart(Interval(Interval::enclose(a).lo, Interval::enclose(b).hi), 4);
}

}  // namespace hipair::pinslot
