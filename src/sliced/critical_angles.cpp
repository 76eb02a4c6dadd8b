// Critical angles of a free polygonal part against a fixed one (see critical_angles.hpp).
#include "sliced/critical_angles.hpp"

#include "algebra/rational_root.hpp"   // detect_small_rational: exact angles are a saving here
#include "core/exact_sqrt.hpp"
#include "kernels/interval.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <type_traits>

namespace hipair::sliced {
namespace {

namespace algebra = cspace::algebra;
using algebra::Real;

// ---------------------------------------------------------------- number types
// Three arithmetics run the same formulas: TrigPoly (a polynomial in u over (1 + u^2)^w:
// the event polynomials), Rational (exact values at a rational rotation) and Box (exact
// rational intervals: enclosures over an interval of u).

// The coefficients are integers over one common positive denominator: products and sums need no
// gcd per coefficient (canonical rationals spent a fifth of the film advance's critical-value
// time in gcds); the sign of the value is the sign of the integer numerator.
struct TrigPoly {
  std::vector<mpz_class> c;   // ascending powers of u
  mpz_class den = 1;          // > 0
  int w = 0;                  // value = c(u) / (den (1 + u^2)^w)
  TrigPoly() = default;
  TrigPoly(const Rational& r) : c{r.get_num()}, den(r.get_den()) {}   // NOLINT: implicit, as for the other number types
  bool zero() const {
    for (const auto& x : c)
      if (sgn(x) != 0) return false;
    return true;
  }
};

TrigPoly lift(TrigPoly a, int w) {
  while (a.w < w) {
    std::vector<mpz_class> out(a.c.size() + 2);
    for (std::size_t i = 0; i < a.c.size(); ++i) {
      out[i] += a.c[i];
      out[i + 2] += a.c[i];
    }
    a.c = std::move(out);
    ++a.w;
  }
  return a;
}

TrigPoly operator+(const TrigPoly& x, const TrigPoly& y) {
  int w = std::max(x.w, y.w);
  TrigPoly a = lift(x, w), b = lift(y, w);
  if (a.den != b.den) {
    mpz_class g;
    mpz_gcd(g.get_mpz_t(), a.den.get_mpz_t(), b.den.get_mpz_t());
    mpz_class fa = b.den / g, fb = a.den / g;
    for (auto& v : a.c) v *= fa;
    for (auto& v : b.c) v *= fb;
    a.den *= fa;
  }
  if (a.c.size() < b.c.size()) a.c.resize(b.c.size());
  for (std::size_t i = 0; i < b.c.size(); ++i) a.c[i] += b.c[i];
  return a;
}
TrigPoly operator-(const TrigPoly& x) {
  TrigPoly a = x;
  for (auto& v : a.c) v = -v;
  return a;
}
TrigPoly operator-(const TrigPoly& x, const TrigPoly& y) { return x + (-y); }
TrigPoly operator*(const TrigPoly& x, const TrigPoly& y) {
  TrigPoly a;
  a.w = x.w + y.w;
  a.den = x.den * y.den;
  a.c.assign(x.c.size() + y.c.size(), mpz_class(0));
  for (std::size_t i = 0; i < x.c.size(); ++i)
    if (sgn(x.c[i]) != 0)
      for (std::size_t j = 0; j < y.c.size(); ++j) mpz_addmul(a.c[i + j].get_mpz_t(), x.c[i].get_mpz_t(), y.c[j].get_mpz_t());
  return a;
}

// Divides out the factors (1 + u^2) of the numerator (same value, lower degree).
TrigPoly reduced(TrigPoly a) {
  while (a.w > 0 && a.c.size() >= 3) {
    std::vector<mpz_class> r = a.c, q(a.c.size() - 2);
    for (std::size_t i = r.size() - 1; i >= 2; --i) {
      q[i - 2] = r[i];
      r[i - 2] -= r[i];
      r[i] = 0;
    }
    if (sgn(r[0]) != 0 || sgn(r[1]) != 0) break;
    a.c = std::move(q);
    --a.w;
  }
  return a;
}

// The integer polynomial with the same sign as the numerator (positive scaling: the
// denominators are positive; divided by the content of its coefficients).
algebra::Polynomial integer_numerator(const TrigPoly& unreduced) {
  const TrigPoly p = reduced(unreduced);
  mpz_class content = 0;
  for (const auto& q : p.c) mpz_gcd(content.get_mpz_t(), content.get_mpz_t(), q.get_mpz_t());
  algebra::Polynomial out;
  for (const auto& q : p.c) {
    if (sgn(content) > 0 && content != 1) {
      mpz_class v;
      mpz_divexact(v.get_mpz_t(), q.get_mpz_t(), content.get_mpz_t());
      out.push_back(v);
    } else {
      out.push_back(q);
    }
  }
  algebra::trim(out);
  return out;
}

struct Box {
  Rational lo, hi;
  Box() = default;
  Box(const Rational& r) : lo(r), hi(r) {}   // NOLINT
  Box(Rational l, Rational h) : lo(std::move(l)), hi(std::move(h)) {}
};
Box operator+(const Box& a, const Box& b) { return {a.lo + b.lo, a.hi + b.hi}; }
Box operator-(const Box& a) { return {-a.hi, -a.lo}; }
Box operator-(const Box& a, const Box& b) { return {a.lo - b.hi, a.hi - b.lo}; }
Box operator*(const Box& a, const Box& b) {
  // by the signs of the ends (two products) when neither box straddles zero; else all four
  const int al = sgn(a.lo), ah = sgn(a.hi), bl = sgn(b.lo), bh = sgn(b.hi);
  if (al >= 0 && bl >= 0) return {a.lo * b.lo, a.hi * b.hi};
  if (ah <= 0 && bh <= 0) return {a.hi * b.hi, a.lo * b.lo};
  if (al >= 0 && bh <= 0) return {a.hi * b.lo, a.lo * b.hi};
  if (ah <= 0 && bl >= 0) return {a.lo * b.hi, a.hi * b.lo};
  Rational p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}
// a / b, b not containing zero.
std::optional<Box> divide(const Box& a, const Box& b) {
  if (sgn(b.lo) <= 0 && sgn(b.hi) >= 0) return std::nullopt;
  Box inverse{1 / b.hi, 1 / b.lo};
  return a * inverse;
}
// The simplest rational (least denominator) of the closed box, canonical.
Rational simplest_inside(const Box& b) {
  Rational out = b.lo < b.hi ? cspace::algebra::simplest_between(b.lo, b.hi) : b.lo;
  out.canonicalize();
  return out;
}

// Certified double intervals (kernels::Interval, widened outwards by an ulp per operation): the
// fourth arithmetic of the formulas, for the filter that proves an event polynomial has no
// root in a range before its exact coefficients are formed.
struct IV {
  kernels::Interval v;
  IV() = default;
  IV(const Rational& r) : v(kernels::Interval::enclose(r)) {}   // NOLINT: implicit, as for the other number types
  IV(kernels::Interval i) : v(i) {}                              // NOLINT
};
IV operator+(const IV& a, const IV& b) { return a.v + b.v; }
IV operator-(const IV& a, const IV& b) { return a.v - b.v; }
IV operator*(const IV& a, const IV& b) { return a.v * b.v; }

template <class T>
struct Vec {
  T x, y;
};
template <class T>
Vec<T> operator+(const Vec<T>& a, const Vec<T>& b) {
  return {a.x + b.x, a.y + b.y};
}
template <class T>
Vec<T> operator-(const Vec<T>& a, const Vec<T>& b) {
  return {a.x - b.x, a.y - b.y};
}
template <class T>
Vec<T> scale(const T& k, const Vec<T>& a) {
  return {k * a.x, k * a.y};
}
template <class T>
T cross(const Vec<T>& a, const Vec<T>& b) {
  return a.x * b.y - a.y * b.x;
}
template <class T>
T dot(const Vec<T>& a, const Vec<T>& b) {
  return a.x * b.x + a.y * b.y;
}
template <class T>
Vec<T> lift_point(const Point& p) {
  return {T(p.x), T(p.y)};
}

template <class T>
struct Rotation {
  T c, s;
  // 1 - c and s for a point's lever term (I - R) l (see Aff): formed without cancellation and
  // rounded relatively (certified intervals by rotation_over, boxes by rotation_box; the exact
  // types form a + l + R (b - l) instead)
  T versine{}, sine{};
  bool levered = false;   // versine and sine formed
  Vec<T> apply(const Vec<T>& v) const { return {c * v.x - s * v.y, s * v.x + c * v.y}; }
};

TrigPoly poly_cos(bool flip) {
  TrigPoly c;
  c.c = {mpz_class(1), mpz_class(0), mpz_class(-1)};
  c.w = 1;
  return flip ? -c : c;
}
TrigPoly poly_sin(bool flip) {
  TrigPoly s;
  s.c = {mpz_class(0), mpz_class(2)};
  s.w = 1;
  return flip ? -s : s;
}

// cos, sin enclosures over u in [lo, hi] (any interval; flip: the half turn added); with
// `levered`, also the versine and sine for points with a lever term (see Aff). `extra`: bits of
// rounding beyond 64 (a lever of 2^e mm needs e more to keep its term as sharp).
Rotation<Box> rotation_box(const Rational& lo, const Rational& hi, bool flip, bool levered = false, long extra = 0) {
  Box u{lo, hi};
  Box u2 = u * u;
  if (sgn(lo) <= 0 && sgn(hi) >= 0) u2.lo = 0;
  Box one(Rational(1));
  Box den = one + u2;   // > 0
  Box c = *divide(one - u2, den);
  Box s = *divide(Box(Rational(2)) * u, den);
  // clamp to [-1, 1] (true values lie there)
  auto clamp = [](Box b) {
    if (b.lo < -1) b.lo = -1;
    if (b.hi > 1) b.hi = 1;
    return b;
  };
  // rounded outwards to dyadics of 64 bits (keeps the enclosures' numbers small)
  auto outward = [extra](Box b) {
    const mpz_class scale = mpz_class(1) << (64 + extra);
    mpz_class lo, hi;
    mpz_class n = b.lo.get_num() * scale;
    mpz_fdiv_q(lo.get_mpz_t(), n.get_mpz_t(), b.lo.get_den_mpz_t());
    n = b.hi.get_num() * scale;
    mpz_cdiv_q(hi.get_mpz_t(), n.get_mpz_t(), b.hi.get_den_mpz_t());
    Box out{Rational(lo, scale), Rational(hi, scale)};
    out.lo.canonicalize();
    out.hi.canonicalize();
    return out;
  };
  // 1 - c = 2 u^2 / (1 + u^2) and s for the lever term, rounded outwards to 64 significant bits
  // (a lever of 10^30 mm turned by 10^-29: 2^-64 absolute would blur it by 10^11 mm)
  auto relative = [extra](Box b) {
    auto round = [extra](const Rational& x, bool up) {
      if (sgn(x) == 0) return x;
      const long bits = static_cast<long>(mpz_sizeinbase(x.get_num_mpz_t(), 2)) - static_cast<long>(mpz_sizeinbase(x.get_den_mpz_t(), 2));
      const long k = std::max(64L, 66 - bits) + extra;
      const mpz_class scale = mpz_class(1) << k;
      mpz_class q, n = x.get_num() * scale;
      if (up) mpz_cdiv_q(q.get_mpz_t(), n.get_mpz_t(), x.get_den_mpz_t());
      else mpz_fdiv_q(q.get_mpz_t(), n.get_mpz_t(), x.get_den_mpz_t());
      Rational out(q, scale);
      out.canonicalize();
      return out;
    };
    return Box{round(b.lo, false), round(b.hi, true)};
  };
  // A tiny angle (|u| <= 2^-20 over the box): cos and sin rounded relatively too, cos as 1 less
  // the versine. Rounded to 2^-64 absolutely, a sine of 10^-13 kept 7 digits and cos had a
  // width of 2^-64 that no cancellation removes (c a - c b with a = b is 2^-64 |a| wide): the
  // crossing of two nearly parallel contact lines, divided by such a sine, had a box 10^4 mm
  // wide, and an event in blocked space was not certified (the pin 10^12 mm along its slot:
  // 153 critical values where 10^9 gave 29).
  const Rational tiny(1, mpz_class(1) << 20);
  const bool small = abs(lo) <= tiny && abs(hi) <= tiny;
  Box versine, sine;
  if (levered || small) {
    versine = relative(*divide(Box(Rational(2)) * u2, den));
    sine = relative(s);
  }
  if (small) {
    c = clamp(Box(Rational(1)) - versine);
    s = clamp(sine);
  } else {
    c = clamp(outward(c));
    s = clamp(outward(s));
  }
  if (flip) return {-c, -s, levered ? Box(Rational(2)) - versine : versine, -sine, levered};   // (1 - (-c) = 2 - (1 - c))
  return {c, s, versine, sine, levered};
}

// ---------------------------------------------------------------- the pair's formulas

// Contact segments: vertex of B on edge of A (ab), vertex of A on edge of B (ba); endpoints are
// vertex–vertex translations V(i, j) = a_i - R u_j.
struct Segment {
  bool ab = true;
  std::size_t i0, j0, i1, j1;   // endpoints V(i0, j0), V(i1, j1)
  std::size_t edge;             // A edge (ab) or B edge (ba)
};

template <class T>
Vec<T> vv(const PolygonalPair& g, const Rotation<T>& r, std::size_t i, std::size_t j) {
  return lift_point<T>(g.a[i]) - r.apply(lift_point<T>(g.u[j]));
}

// sign(a + b sqrt(d)), d >= 0.
int sign_with_root(const Rational& a, const Rational& b, const Rational& d) {
  int sa = sgn(a), sb = sgn(b);
  if (sb == 0 || sgn(d) == 0) return sa;
  if (sa == 0 || sa == sb) return sa == 0 ? sb : sa;
  // opposite signs: compare a^2 with b^2 d
  int c = cmp(Rational(a * a), Rational(b * b * d));
  return c == 0 ? 0 : (c > 0 ? sa : sb);
}

// Is the (world, rational) point strictly inside the region of loops (material left)?
// Crossing parity of the ray to +x over every loop: 1 inside, -1 outside, 0 on the boundary
// or undecided (the ray through an arc's end or tangent to an arc's circle: callers treat 0 as
// "not certainly inside").
int region_side(const std::vector<Loop>& loops, const Rational& x, const Rational& y) {
  bool inside = false;
  for (const auto& loop : loops)
    for (const auto& e : loop.edges) {
      const Point &p = e.source, &q = e.target;
      if (e.is_arc()) {
        if (!e.is_full_circle() && (p.y == y || q.y == y)) return 0;
        Rational dy = y - e.center.y, d = e.radius_squared - dy * dy;
        if (sgn(d) < 0) continue;
        if (sgn(d) == 0) return 0;   // tangent
        // the arc's span, counter-clockwise from s to f
        Rational sx = p.x - e.center.x, sy = p.y - e.center.y, fx = q.x - e.center.x, fy = q.y - e.center.y;
        if (!e.ccw) {
          std::swap(sx, fx);
          std::swap(sy, fy);
        }
        int span = sgn(Rational(sx * fy - sy * fx));
        for (int sigma : {-1, 1}) {
          // the point (cx + sigma sqrt(d), y)
          int right = sign_with_root(Rational(e.center.x - x), Rational(sigma), d);
          int on_arc_a = sign_with_root(Rational(sx * dy), Rational(-sy * sigma), d);   // cross(s, n)
          int on_arc_b = sign_with_root(Rational(-dy * fx), Rational(fy * sigma), d);   // cross(n, f)
          bool on_arc = e.is_full_circle() || (span > 0 ? on_arc_a > 0 && on_arc_b > 0
                                                 : span < 0 ? on_arc_a > 0 || on_arc_b > 0
                                                            : on_arc_a > 0);
          if (!on_arc) continue;
          if (right == 0) return 0;   // on the boundary
          if (right > 0) inside = !inside;
        }
        continue;
      }
      // cr = cross(q - p, (x, y) - p), formed only for edges whose y-range holds y (comparisons
      // first): zero with (x, y) in the edge's box, on the boundary; for an edge crossing the
      // line at height y, its crossing lies right of x iff cr has the sign of q.y - p.y
      // (x_cross - x = cr / (q.y - p.y)), so no division
      const bool straddles = (p.y <= y) != (q.y <= y);
      const bool in_y_range = std::min(p.y, q.y) <= y && y <= std::max(p.y, q.y);
      if (!straddles && !in_y_range) continue;
      const int side = sgn(Rational((q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x)));
      if (side == 0 && in_y_range && std::min(p.x, q.x) <= x && x <= std::max(p.x, q.x)) return 0;   // on the boundary
      if (straddles && side * sgn(Rational(q.y - p.y)) > 0) inside = !inside;
    }
  return inside ? 1 : -1;
}

// Does the closed segment pq meet the closed box [x0, x1] x [y0, y1]? (Liang–Barsky, exact.)
bool segment_meets_box(const Point& p, const Point& q, const Box& bx, const Box& by) {
  Rational t0 = 0, t1 = 1;
  Rational d[2] = {q.x - p.x, q.y - p.y};
  Rational s[2] = {p.x, p.y};
  const Box* b[2] = {&bx, &by};
  for (int k = 0; k < 2; ++k) {
    if (sgn(d[k]) == 0) {
      if (s[k] < b[k]->lo || s[k] > b[k]->hi) return false;
      continue;
    }
    Rational ta = (b[k]->lo - s[k]) / d[k], tb = (b[k]->hi - s[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) t0 = ta;
    if (tb < t1) t1 = tb;
    if (t0 > t1) return false;
  }
  return true;
}

// May the circle of an arc meet the box? (Conservative: the box's squared distances from the
// centre straddle the squared radius.)
bool circle_may_meet_box(const Edge& e, const Box& bx, const Box& by) {
  Box dx = bx - Box(e.center.x), dy = by - Box(e.center.y);
  auto square = [](const Box& b) {
    Box s = b * b;
    if (sgn(b.lo) <= 0 && sgn(b.hi) >= 0) s.lo = 0;
    return s;
  };
  Box d = square(dx) + square(dy);
  return d.lo <= e.radius_squared && e.radius_squared <= d.hi;
}

// Is the box strictly inside the part's region (world coordinates of its zero configuration)?
bool box_inside(const Part& part, const Box& bx, const Box& by) {
  // a corner strictly inside (cheap: most probes fail here), and no boundary in the box
  if (region_side(part.loops, bx.lo, by.lo) <= 0) return false;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges)
      if (e.is_arc() ? circle_may_meet_box(e, bx, by) : segment_meets_box(e.source, e.target, bx, by)) return false;
  return true;
}

Rotation<Rational> exact_rotation(Rational u) {
  u.canonicalize();
  Rational d = 1 + u * u;
  return {Rational((1 - u * u) / d), Rational(2 * u / d)};
}

// Certifies that a configuration lies inside blocked space (the relevance test of every event):
// exactly at a rational angle, and by enclosures over a narrow interval of an irrational one
// (a probe point of one part, a vertex, an edge midpoint or a circle's axis point, certainly
// strictly inside the other part; or the exact overlap witness at a mid configuration
// certainly inside both over the enclosure).
// A part's edges in certified double intervals, for the probe filter below.
struct IntervalEdge {
  bool arc = false;
  kernels::Interval px, py, qx, qy;   // segment ends; arc: the circle's centre in px, py
  kernels::Interval r2;               // arc: squared radius
  int dir = 0;                        // segment: sgn(q.y - p.y)
};

std::vector<IntervalEdge> interval_edges(const Part& part) {
  using kernels::Interval;
  std::vector<IntervalEdge> out;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      IntervalEdge ie;
      ie.arc = e.is_arc();
      if (ie.arc) {
        ie.px = Interval::enclose(e.center.x);
        ie.py = Interval::enclose(e.center.y);
        ie.r2 = Interval::enclose(e.radius_squared);
      } else {
        ie.px = Interval::enclose(e.source.x);
        ie.py = Interval::enclose(e.source.y);
        ie.qx = Interval::enclose(e.target.x);
        ie.qy = Interval::enclose(e.target.y);
        ie.dir = sgn(Rational(e.target.y - e.source.y));
      }
      out.push_back(ie);
    }
  return out;
}

// Is every point of the box X x Y certainly not strictly inside the region (region_side <= 0
// at each of them)? Decided by the crossing parity of region_side with every decision an
// interval sign that excludes zero (then region_side at any point of the box makes the same
// decisions and returns -1); false when any decision is uncertain (the caller then runs the
// exact test). Arcs: only those whose circle certainly misses the height Y are decided.
bool certainly_not_inside(const std::vector<IntervalEdge>& edges, const kernels::Interval& x, const kernels::Interval& y) {
  bool inside = false;
  for (const auto& e : edges) {
    if (e.arc) {
      const kernels::Interval dy = y - e.py;
      if ((e.r2 - dy * dy).sign() == -1) continue;   // the line at height y misses the circle
      return false;
    }
    const double lo_y = std::min(e.py.lo, e.qy.lo), hi_y = std::max(e.py.hi, e.qy.hi);
    if (y.hi < lo_y || y.lo > hi_y) continue;   // certainly outside the edge's y-range
    // certainly strictly between the ends' heights (then it straddles and is in range)
    const bool between = e.dir > 0 ? (e.py.hi < y.lo && y.hi < e.qy.lo) : e.dir < 0 ? (e.qy.hi < y.lo && y.hi < e.py.lo) : false;
    if (!between) return false;
    const int side = ((e.qx - e.px) * (y - e.py) - (e.qy - e.py) * (x - e.px)).sign();
    if (side != 1 && side != -1) return false;
    if (side * e.dir > 0) inside = !inside;
  }
  return !inside;
}

kernels::Interval interval_of(const Box& b) {
  return kernels::Interval(kernels::Interval::enclose(b.lo).lo, kernels::Interval::enclose(b.hi).hi);
}

class Certifier {
 public:
  Certifier(const Part& fixed, const Part& free, const Point& pivot) : fixed_(fixed), free_(free), pivot_(pivot) {
    collect(free, probes_free_);
    collect(fixed, probes_fixed_);
    for (const auto& u : probes_free_) probes_free_iv_.push_back({kernels::Interval::enclose(u.x), kernels::Interval::enclose(u.y)});
    for (const auto& a : probes_fixed_) probes_fixed_iv_.push_back({kernels::Interval::enclose(a.x), kernels::Interval::enclose(a.y)});
    edges_fixed_ = interval_edges(fixed);
    edges_free_ = interval_edges(free);
  }

  // Whether exact answers are remembered and probes pass the interval filter first (tests
  // compare with and without).
  void remember(bool on) { remember_ = on; }
  // Where probes rejected by the interval filter are counted.
  void count_filtered_into(std::size_t* counter) { filtered_ = counter; }
  // Where witness searches are counted (CriticalStatistics::witness_searches and the two after).
  void count_searches_into(CriticalStatistics* statistics) { searches_ = statistics; }
  // The event points carry a lever term (I - R) l with |l.x| + |l.y| up to `reach` (a pin-slot
  // window about a centre far from the pivot, CurveFinder): roots are refined to 2^-bits over
  // the least power of two at least `reach`, so that the points' boxes stay as narrow as
  // without a lever (10^30 mm turned through 2^-52: 10^14 mm).
  void lever_reach(const Rational& reach) {
    levered_ = sgn(reach) != 0;
    refine_scale_ = 1;
    while (refine_scale_ < reach) refine_scale_ *= 2;
  }

  // Is the configuration (point(c, s), theta) certainly overlapping (inside blocked space)?
  template <class PointOf>
  bool certainly_blocked(const Real& root, bool half_turn, PointOf point_of) const {
    if (half_turn || root.exact) {
      Rotation<Rational> r = half_turn ? Rotation<Rational>{Rational(-1), Rational(0)} : exact_rotation(root.lower);
      std::optional<Vec<Rational>> p = point_of(r);
      if (!p) return false;
      // the same exact configuration recurs (an end of one curve against many others at one
      // rational angle): the oracle's answer is remembered
      std::array<Rational, 4> key{Rational(half_turn ? 1 : 0), half_turn ? Rational(0) : root.lower, p->x, p->y};
      for (auto& q : key) q.canonicalize();
      if (remember_) {
        auto found = exact_answers_.find(key);
        if (found != exact_answers_.end()) return found->second;
      }
      auto relation = part_overlap(fixed_, Placement{}, free_, placement_about(pivot_, r.c, r.s, Point{p->x, p->y}));
      const bool blocked = relation.relation == PartRelation::overlapping;
      if (remember_) exact_answers_.emplace(std::move(key), blocked);
      return blocked;
    }
    Real t = root;
    // stages: 2^-20 and 2^-52 over refine_scale_; with a lever, also 2^-52 over its square (an
    // event blocked by a sliver as thick as the lever's tilt times a depth, both about 1 / |l|:
    // the pin 10^15 mm from its slot's end, the claw's corner 10^-15 mm deep in the film and the
    // sliver 10^-29 mm thick, where the second stage's boxes are 10^-29 mm wide)
    const int stages = levered_ ? 3 : 2;
    for (int stage = 0; stage < stages; ++stage) {
      const long extra = refine_for(t, stage);
      if (t.exact) return certainly_blocked(t, false, point_of);
      Rotation<Box> rb = rotation_box(t.lower, t.upper, false, levered_, extra);
      std::optional<Vec<Box>> pb = point_of(rb);
      if (!pb) continue;
      // a vertex or edge midpoint of one part certainly strictly inside the other; with the
      // filter, a probe whose box (enclosed in certified doubles: the exact box's corner lies in
      // it) is certainly not inside is rejected without its exact box: box_inside would return
      // false for it (its corner is not strictly inside), so the answer is the same
      using kernels::Interval;
      const Interval ic = interval_of(rb.c), is = interval_of(rb.s), ipx = interval_of(pb->x), ipy = interval_of(pb->y);
      const Interval pvx = Interval::enclose(pivot_.x), pvy = Interval::enclose(pivot_.y);
      for (std::size_t k = 0; k < probes_free_.size(); ++k) {
        if (remember_) {
          const auto& [ux, uy] = probes_free_iv_[k];
          if (certainly_not_inside(edges_fixed_, ic * ux - is * uy + ipx + pvx, is * ux + ic * uy + ipy + pvy)) {
            if (filtered_) ++*filtered_;
            continue;
          }
        }
        const auto& u = probes_free_[k];
        Vec<Box> w = rb.apply(Vec<Box>{Box(u.x), Box(u.y)});
        if (box_inside(fixed_, w.x + pb->x + Box(pivot_.x), w.y + pb->y + Box(pivot_.y))) return true;
      }
      for (std::size_t k = 0; k < probes_fixed_.size(); ++k) {
        if (remember_) {
          const auto& [ax, ay] = probes_fixed_iv_[k];
          const Interval rx = ax - ipx, ry = ay - ipy;
          if (certainly_not_inside(edges_free_, ic * rx + is * ry + pvx, ic * ry - is * rx + pvy)) {
            if (filtered_) ++*filtered_;
            continue;
          }
        }
        const auto& a = probes_fixed_[k];
        Vec<Box> rel{Box(a.x) - pb->x, Box(a.y) - pb->y};
        if (box_inside(free_, rb.c * rel.x + rb.s * rel.y + Box(pivot_.x), rb.c * rel.y - rb.s * rel.x + Box(pivot_.y)))
          return true;
      }
      // a configuration of the enclosure: the simplest rationals of its angle's interval and of
      // its point's box (the witness is then checked over the whole enclosure, so any of its
      // configurations will do; the middles carried twice the bits into every exact overlap test)
      Rational um = simplest_inside(Box{t.lower, t.upper});
      Rotation<Rational> rm = exact_rotation(um);
      Point d{simplest_inside(pb->x), simplest_inside(pb->y)};
      // a configuration of the enclosure that is not overlapping: no certificate (kept) — after
      // the finer stage: the mid of a coarse box may lie far from the event (the crossing of two
      // nearly parallel contact lines, 10^12 mm from the pivot: 10^4 mm wide at 2^-20)
      if (apart_in_enclosure(um, rm, *pb, d) || (stage + 1 < stages && apart_in_last_stage(t, *pb, point_of, stages))) {
        if (searches_) ++searches_->witness_searches_skipped;
        if (stage + 1 == stages) return false;
        continue;
      }
      const PartOverlap relation = overlap_at(um, rm, d);
      if (relation.relation != PartRelation::overlapping) {
        if (stage + 1 == stages) return false;
        continue;
      }
      if (!relation.witness) continue;
      // the witness w (world) is inside the fixed part; in the free part's body it is
      // p + R^T (w - p - d) over every (c, s, d) of the enclosure
      Vec<Box> rel{Box(relation.witness->x - pivot_.x) - pb->x, Box(relation.witness->y - pivot_.y) - pb->y};
      Box bx = rb.c * rel.x + rb.s * rel.y + Box(pivot_.x);
      Box by = rb.c * rel.y - rb.s * rel.x + Box(pivot_.y);
      if (box_inside(free_, bx, by)) return true;
    }
    return false;
  }

 private:
  // probe points relative to the pivot: vertices, segment midpoints, axis points of circles
  // of rational radius
  void collect(const Part& part, std::vector<Point>& out) const {
    for (const auto& loop : part.loops)
      for (const auto& e : loop.edges) {
        Point v{Rational(e.source.x - pivot_.x), Rational(e.source.y - pivot_.y)};
        if (!e.is_full_circle()) out.push_back(v);
        if (!e.is_arc()) {
          out.push_back(Point{Rational((e.source.x + e.target.x) / 2 - pivot_.x), Rational((e.source.y + e.target.y) / 2 - pivot_.y)});
          continue;
        }
        // rational points of an arc: its source turned by rational rotations (half-angle
        // tangents m), those strictly inside the arc's span
        const Rational sx = e.source.x - e.center.x, sy = e.source.y - e.center.y;
        const Rational fx = e.target.x - e.center.x, fy = e.target.y - e.center.y;
        const int span = sgn(Rational(sx * fy - sy * fx)) * (e.ccw ? 1 : -1);
        for (const Rational& m : {Rational(1, 4), Rational(1, 2), Rational(1), Rational(2), Rational(4), Rational(-4), Rational(-2),
                                  Rational(-1), Rational(-1, 2), Rational(-1, 4)}) {
          Rational d = 1 + m * m, c = (1 - m * m) / d, si = (e.ccw ? 2 : -2) * m / d;
          Rational px = c * sx - si * sy, py = si * sx + c * sy;
          // strictly between source and target along the arc's sense
          Rational a = (e.ccw ? 1 : -1) * (sx * py - sy * px), b = (e.ccw ? 1 : -1) * (px * fy - py * fx);
          bool inside = e.is_full_circle() || (span > 0 ? sgn(a) > 0 && sgn(b) > 0 : span < 0 ? sgn(a) > 0 || sgn(b) > 0 : sgn(a) > 0);
          if (inside) out.push_back(Point{Rational(e.center.x + px - pivot_.x), Rational(e.center.y + py - pivot_.y)});
        }
      }
  }

  // Is some configuration of the enclosure (the rotation rm of u, an offset in the box pb)
  // certainly not overlapping? Then no witness passes box_inside over the enclosure: a witness
  // w is strictly inside the fixed part (the oracle's), and its body boxes enclose its body
  // point at every (c, s) of rb and d of pb, the rotation of u and such a configuration's offset
  // among them, where w would then be strictly inside both parts. So the witness search (a
  // failed one cost ~600 halvings of exact point locations: the claw 10^400 mm along its slot
  // spent 90 % of its time there, on events whose mid configuration overlaps by a sliver of
  // 10^-400 mm across a touching event) is skipped, with the same answer. Asked only with a
  // lever (far pivots, `lever_reach`), where the sliver's depth lies below the search's reach,
  // and with the filters (off: the plain exact path, the tests' oracle, as before);
  // the mid configuration d first (the answer as before when it does not overlap), then the
  // box's four corners' simplest rationals (the contact's free side of a touching event; a
  // quarter of each side in from the corner).
  bool apart_in_enclosure(const Rational& u, const Rotation<Rational>& rm, const Vec<Box>& pb, const Point& d) const {
    if (!levered_ || !remember_) return false;
    if (relation_at(u, rm, d) != PartRelation::overlapping) return true;
    for (const Point& c : corners(pb))
      if (relation_at(u, rm, c) != PartRelation::overlapping) return true;
    return false;
  }
  // The same look-ahead from a coarser stage's enclosure (t, pb): the configurations that
  // apart_in_enclosure tries in the last stage's enclosure (t refined), each used only when it
  // lies in this enclosure too (its angle in t's interval, its offset in pb, exactly), where the
  // same argument holds. (The claw at 10^400: four events whose coarser stages' corners all
  // overlap, their witness searches failing, and the last stage's corners apart.)
  template <class PointOf>
  bool apart_in_last_stage(const Real& current, const Vec<Box>& pb, PointOf point_of, int stages) const {
    if (!levered_ || !remember_) return false;
    Real t = current;
    const long extra = refine_for(t, stages - 1);
    if (t.exact) return false;
    const std::optional<Vec<Box>> fine = point_of(rotation_box(t.lower, t.upper, false, levered_, extra));
    if (!fine) return false;
    const Rational u = simplest_inside(Box{t.lower, t.upper});
    if (u < current.lower || u > current.upper) return false;
    const Rotation<Rational> rm = exact_rotation(u);
    auto in = [](const Box& b, const Rational& x) { return b.lo <= x && x <= b.hi; };
    std::vector<Point> tried{Point{simplest_inside(fine->x), simplest_inside(fine->y)}};
    for (const Point& c : corners(*fine)) tried.push_back(c);
    for (const Point& c : tried)
      if (in(pb.x, c.x) && in(pb.y, c.y) && relation_at(u, rm, c) != PartRelation::overlapping) return true;
    return false;
  }
  // The simplest rationals of the box's four corner quarters (a quarter of each side in from
  // the corner).
  static std::array<Point, 4> corners(const Vec<Box>& pb) {
    auto near_end = [](const Box& b, bool high) {
      const Rational quarter = (b.hi - b.lo) / 4;
      return simplest_inside(high ? Box{Rational(b.hi - quarter), b.hi} : Box{b.lo, Rational(b.lo + quarter)});
    };
    std::array<Point, 4> out;
    for (int corner = 0; corner < 4; ++corner) out[corner] = Point{near_end(pb.x, corner & 1), near_end(pb.y, corner & 2)};
    return out;
  }
  // Refines t to the width of stage `stage` of certainly_blocked; returns the bits of rounding
  // beyond 64 that its boxes take (as fine as the stage's refinement: 2^-64 relative of a sine
  // turning a lever of 10^30 mm is 10^-20 mm).
  long refine_for(Real& t, int stage) const {
    const int bits = stage == 0 ? 20 : 52;
    const mpz_class scale = stage == 2 ? mpz_class(refine_scale_ * refine_scale_) : refine_scale_;
    algebra::refine_dyadically(t, Rational(1) / Rational(scale * (mpz_class(1) << bits)));
    return static_cast<long>(mpz_sizeinbase(scale.get_mpz_t(), 2)) - 1;
  }

  // The exact relation (no witness) at the rotation rm of u and the offset d, remembered.
  PartRelation relation_at(const Rational& u, const Rotation<Rational>& rm, const Point& d) const {
    std::array<Rational, 3> key{u, d.x, d.y};
    auto found = relations_.find(key);
    if (found != relations_.end()) return found->second;
    const PartRelation relation = part_overlap(fixed_, Placement{}, free_, placement_about(pivot_, rm.c, rm.s, d)).relation;
    relations_.emplace(std::move(key), relation);
    return relation;
  }

  // The exact oracle (with a witness) at the rotation rm of u and the offset d, remembered:
  // events found by different curves at one root name the same mid configuration (a pure
  // function of (u, d): the same answer, the same witness).
  PartOverlap overlap_at(const Rational& u, const Rotation<Rational>& rm, const Point& d) const {
    auto searched = [&] {
      PartOverlap relation = part_overlap(fixed_, Placement{}, free_, placement_about(pivot_, rm.c, rm.s, d), true);
      if (searches_ && relation.relation == PartRelation::overlapping) {
        ++searches_->witness_searches;
        if (!relation.witness) ++searches_->witness_searches_failed;
      }
      return relation;
    };
    if (!remember_) return searched();
    std::array<Rational, 3> key{u, d.x, d.y};
    auto found = mid_answers_.find(key);
    if (found != mid_answers_.end()) return found->second;
    PartOverlap relation = searched();
    mid_answers_.emplace(std::move(key), relation);
    return relation;
  }

  const Part& fixed_;
  const Part& free_;
  Point pivot_;
  std::vector<Point> probes_free_, probes_fixed_;
  std::vector<std::pair<kernels::Interval, kernels::Interval>> probes_free_iv_, probes_fixed_iv_;
  std::vector<IntervalEdge> edges_fixed_, edges_free_;
  std::size_t* filtered_ = nullptr;
  CriticalStatistics* searches_ = nullptr;
  mpz_class refine_scale_ = 1;   // see lever_reach
  bool levered_ = false;
  // exact oracle answers at rational configurations: (half turn?, u, x, y)
  mutable std::map<std::array<Rational, 4>, bool> exact_answers_;
  // the oracle's answers at mid configurations: (u, x, y) (see overlap_at)
  mutable std::map<std::array<Rational, 3>, PartOverlap> mid_answers_;
  // the exact relations at configurations of enclosures (see apart_in_enclosure)
  mutable std::map<std::array<Rational, 3>, PartRelation> relations_;
  bool remember_ = true;
};

// Sorted counter-clockwise from -pi (t ascending, the half turn last); equal angles merged
// with their events united.
std::vector<Critical> merged(std::vector<Critical> found) {
  std::sort(found.begin(), found.end(), [](const Critical& a, const Critical& b) {
    if (a.half_turn != b.half_turn) return !a.half_turn;
    if (a.half_turn) return false;
    return algebra::compare(a.t, b.t) < 0;
  });
  std::vector<Critical> out;
  for (auto& c : found) {
    bool same = !out.empty() && out.back().half_turn == c.half_turn &&
                (c.half_turn || algebra::compare(out.back().t, c.t) == 0);
    if (same) {
      for (auto e : c.events)
        if (std::find(out.back().events.begin(), out.back().events.end(), e) == out.back().events.end())
          out.back().events.push_back(e);
      continue;
    }
    out.push_back(std::move(c));
  }
  return out;
}

class Finder {
 public:
  Finder(const PolygonalPair& g, CriticalStatistics& stats) : g_(g), stats_(stats), cert_(*g.fixed, *g.free, g.pivot) {
    for (std::size_t k = 0; k < g.a_edges.size(); ++k)
      for (std::size_t j = 0; j < g.u.size(); ++j)
        segments_.push_back({true, g.a_edges[k].first, j, g.a_edges[k].second, j, k});
    for (std::size_t i = 0; i < g.a.size(); ++i)
      for (std::size_t m = 0; m < g.b_edges.size(); ++m)
        segments_.push_back({false, i, g.b_edges[m].first, i, g.b_edges[m].second, m});
  }

  std::vector<Critical> run() {
    compute_masks();
    antiparallel();
    vertex_on_segment();
    parallel_overlap();
    three_concurrent();
    return merged(std::move(found_));
  }

 private:
  template <class T>
  Vec<T> endpoint(const Rotation<T>& r, const Segment& s, bool second) const {
    return second ? vv(g_, r, s.i1, s.j1) : vv(g_, r, s.i0, s.j0);
  }

  // ------------------------------------------------------------ prefilter masks
  // 64 ranges of the angle (32 of u in [-1, 1], 32 of the half-turn chart); bit r of a
  // segment pair's mask: their bounding boxes meet over range r (certified, exact rationals).
  void compute_masks() {
    const std::size_t n = segments_.size();
    std::vector<std::vector<std::pair<Box, Box>>> boxes(n);
    std::vector<std::vector<std::pair<Box, Box>>> vbox(g_.a.size() * g_.u.size());
    for (int r = 0; r < 64; ++r) {
      bool flip = r >= 32;
      int k = r % 32;
      Rational lo(k - 16, 16), hi(k - 15, 16);
      lo.canonicalize();
      hi.canonicalize();
      Rotation<Box> rot = rotation_box(lo, hi, flip);
      for (std::size_t i = 0; i < g_.a.size(); ++i)
        for (std::size_t j = 0; j < g_.u.size(); ++j) {
          auto v = vv(g_, rot, i, j);
          vbox[i * g_.u.size() + j].push_back({v.x, v.y});
        }
      for (std::size_t s = 0; s < n; ++s) {
        const auto& p = vbox[segments_[s].i0 * g_.u.size() + segments_[s].j0].back();
        const auto& q = vbox[segments_[s].i1 * g_.u.size() + segments_[s].j1].back();
        boxes[s].push_back({Box{std::min(p.first.lo, q.first.lo), std::max(p.first.hi, q.first.hi)},
                            Box{std::min(p.second.lo, q.second.lo), std::max(p.second.hi, q.second.hi)}});
      }
    }
    auto meet = [](const std::pair<Box, Box>& a, const std::pair<Box, Box>& b) {
      return !(a.first.hi < b.first.lo || b.first.hi < a.first.lo || a.second.hi < b.second.lo || b.second.hi < a.second.lo);
    };
    masks_.assign(n * n, 0);
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        std::uint64_t m = 0;
        for (int r = 0; r < 64; ++r)
          if (meet(boxes[a][r], boxes[b][r])) m |= std::uint64_t(1) << r;
        masks_[a * n + b] = masks_[b * n + a] = m;
      }
    vmasks_.assign(vbox.size() * n, 0);
    for (std::size_t v = 0; v < vbox.size(); ++v)
      for (std::size_t s = 0; s < n; ++s) {
        std::uint64_t m = 0;
        for (int r = 0; r < 64; ++r)
          if (meet(vbox[v][r], boxes[s][r])) m |= std::uint64_t(1) << r;
        vmasks_[v * n + s] = m;
      }
  }

  Vec<Rational> edge_a(std::size_t k) const {
    const auto& e = g_.a_edges[k];
    return lift_point<Rational>(g_.a[e.second]) - lift_point<Rational>(g_.a[e.first]);
  }
  Vec<Rational> edge_b(std::size_t m) const {
    const auto& e = g_.b_edges[m];
    return lift_point<Rational>(g_.u[e.second]) - lift_point<Rational>(g_.u[e.first]);
  }
  // Are the lines of two segments parallel at every angle?
  bool always_parallel(const Segment& s, const Segment& t) const {
    if (s.ab != t.ab) return false;
    return s.ab ? sgn(cross(edge_a(s.edge), edge_a(t.edge))) == 0 : sgn(cross(edge_b(s.edge), edge_b(t.edge))) == 0;
  }

  template <class PointOf>
  bool certainly_blocked(const Real& root, bool half_turn, PointOf point_of) const {
    return cert_.certainly_blocked(root, half_turn, point_of);
  }

  // Records the roots of `poly` (and the half turn when `at_half_turn` vanishes) that pass
  // `accept` (exact extents) and are not certainly inside blocked space.
  template <class Accept, class PointOf>
  void roots_of(const TrigPoly& poly, CriticalEvent kind, std::uint64_t mask, Accept accept, PointOf point_of,
                const Rational& at_half_turn, bool half_turn_ok) {
    if (poly.zero()) return;
    ++stats_.polynomials;
    algebra::Polynomial p = integer_numerator(poly);
    if (algebra::degree(p) >= 1) {
      for (Real root : algebra::real_roots(algebra::square_free_part(p))) {
        algebra::detect_small_rational(root);
        if (!accept(root)) continue;
        ++stats_.roots;
        if (certainly_blocked(root, false, point_of)) {
          ++stats_.irrelevant;
          continue;
        }
        found_.push_back(Critical{false, root, {kind}});
      }
    }
    if (sgn(at_half_turn) == 0 && half_turn_ok && (mask >> 32) != 0) {
      ++stats_.roots;
      if (certainly_blocked(Real{}, true, point_of)) {
        ++stats_.irrelevant;
        return;
      }
      found_.push_back(Critical{true, Real{}, {kind}});
    }
  }

  // ------------------------------------------------------------ events

  void antiparallel() {
    for (std::size_t k = 0; k < g_.a_edges.size(); ++k)
      for (std::size_t m = 0; m < g_.b_edges.size(); ++m) {
        Vec<Rational> ea = edge_a(k), eb = edge_b(m);
        Rotation<TrigPoly> r{poly_cos(false), poly_sin(false)};
        Vec<TrigPoly> reb = r.apply(Vec<TrigPoly>{TrigPoly(eb.x), TrigPoly(eb.y)});
        Vec<TrigPoly> eat{TrigPoly(ea.x), TrigPoly(ea.y)};
        TrigPoly poly = cross(eat, reb);
        TrigPoly sense = dot(eat, reb);
        algebra::Polynomial sense_p = integer_numerator(sense);
        const auto& ae = g_.a_edges[k];
        const auto& be = g_.b_edges[m];
        // the edge–edge contact locus: the hull of the four vertex–vertex points; probed at
        // the four and their centroid
        auto probes = [&](auto rot) {
          using T = std::decay_t<decltype(rot.c)>;
          std::vector<Vec<T>> out;
          Vec<T> sum{T(Rational(0)), T(Rational(0))};
          for (std::size_t i : {ae.first, ae.second})
            for (std::size_t j : {be.first, be.second}) {
              out.push_back(vv(g_, rot, i, j));
              sum = sum + out.back();
            }
          out.push_back(scale(T(Rational(1, 4)), sum));
          return out;
        };
        auto accept = [&](const Real& root) { return algebra::sign_at(sense_p, root) < 0; };
        if (poly.zero()) continue;
        ++stats_.polynomials;
        algebra::Polynomial p = integer_numerator(poly);
        auto consider = [&](const Real& root, bool half_turn) {
          ++stats_.roots;
          bool all_blocked = true;
          for (int probe = 0; probe < 5 && all_blocked; ++probe) {
            auto point_of = [&](auto rot) { return std::optional(probes(rot)[probe]); };
            if (!certainly_blocked(root, half_turn, point_of)) all_blocked = false;
          }
          if (all_blocked) {
            ++stats_.irrelevant;
            return;
          }
          found_.push_back(Critical{half_turn, root, {CriticalEvent::antiparallel_edges}});
        };
        if (algebra::degree(p) >= 1)
          for (Real root : algebra::real_roots(algebra::square_free_part(p))) {
            algebra::detect_small_rational(root);
            if (accept(root)) consider(root, false);
          }
        // half turn: R = -I
        Vec<Rational> minus_eb{-eb.x, -eb.y};
        if (sgn(cross(ea, minus_eb)) == 0 && sgn(dot(ea, minus_eb)) < 0) consider(Real{}, true);
      }
  }

  // Two always-parallel contact segments become collinear (e.g. the free strip between two
  // parallel walls closes): the event holds along their overlap, probed at the four endpoints
  // and their six pairwise midpoints (the overlap's ends and middle are among them).
  void parallel_overlap() {
    const std::size_t n = segments_.size();
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        const Segment &s = segments_[a], &t = segments_[b];
        if (masks_[a * n + b] == 0 || !always_parallel(s, t)) continue;
        auto probes = [&](auto rot) {
          using T = std::decay_t<decltype(rot.c)>;
          Vec<T> e[4] = {endpoint(rot, s, false), endpoint(rot, s, true), endpoint(rot, t, false), endpoint(rot, t, true)};
          std::vector<Vec<T>> out(e, e + 4);
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) out.push_back(scale(T(Rational(1, 2)), e[i] + e[j]));
          return out;
        };
        // signs that put probe k on both segments (all >= 0)
        auto within = [&](auto rot, std::size_t k) {
          using T = std::decay_t<decltype(rot.c)>;
          Vec<T> q = probes(rot)[k];
          std::vector<T> out;
          for (const Segment* x : {&s, &t}) {
            Vec<T> p0 = endpoint(rot, *x, false), d = endpoint(rot, *x, true) - p0, w = q - p0;
            T along = dot(w, d);
            out.push_back(along);
            out.push_back(dot(d, d) - along);
          }
          return out;
        };
        Rotation<TrigPoly> rp{poly_cos(false), poly_sin(false)};
        TrigPoly poly;
        {
          Vec<TrigPoly> p0 = endpoint(rp, s, false), d = endpoint(rp, s, true) - p0;
          poly = cross(endpoint(rp, t, false) - p0, d);
        }
        if (poly.zero()) continue;   // on one line at every angle
        ++stats_.polynomials;
        std::vector<std::vector<algebra::Polynomial>> ext(10);
        for (std::size_t k = 0; k < 10; ++k)
          for (const auto& q : within(rp, k)) ext[k].push_back(integer_numerator(q));
        auto consider = [&](const Real& root, bool half_turn, const std::vector<bool>& inside) {
          ++stats_.roots;
          for (std::size_t k = 0; k < 10; ++k) {
            if (!inside[k]) continue;
            auto point_of = [&](auto rot) { return std::optional(probes(rot)[k]); };
            if (!certainly_blocked(root, half_turn, point_of)) {
              found_.push_back(Critical{half_turn, root, {CriticalEvent::vertex_on_contact}});
              return;
            }
          }
          ++stats_.irrelevant;
        };
        algebra::Polynomial p = integer_numerator(poly);
        if (algebra::degree(p) >= 1)
          for (Real root : algebra::real_roots(algebra::square_free_part(p))) {
            algebra::detect_small_rational(root);
            std::vector<bool> inside(10, true);
            bool any = false;
            for (std::size_t k = 0; k < 10; ++k) {
              for (const auto& q : ext[k])
                if (algebra::sign_at(q, root) < 0) inside[k] = false;
              any = any || inside[k];
            }
            if (any) consider(root, false, inside);
          }
        Rotation<Rational> half{Rational(-1), Rational(0)};
        Vec<Rational> h0 = endpoint(half, s, false), hd = endpoint(half, s, true) - h0;
        if (sgn(cross(endpoint(half, t, false) - h0, hd)) == 0 && (masks_[a * n + b] >> 32) != 0) {
          std::vector<bool> inside(10, true);
          bool any = false;
          for (std::size_t k = 0; k < 10; ++k) {
            for (const auto& q : within(half, k))
              if (sgn(q) < 0) inside[k] = false;
            any = any || inside[k];
          }
          if (any) consider(Real{}, true, inside);
        }
      }
  }

  void vertex_on_segment() {
    const std::size_t n = segments_.size();
    for (std::size_t i = 0; i < g_.a.size(); ++i)
      for (std::size_t j = 0; j < g_.u.size(); ++j)
        for (std::size_t si = 0; si < n; ++si) {
          const Segment& s = segments_[si];
          if ((s.i0 == i && s.j0 == j) || (s.i1 == i && s.j1 == j)) continue;
          std::uint64_t mask = vmasks_[(i * g_.u.size() + j) * n + si];
          if (mask == 0) continue;
          auto quantities = [&](auto rot) {
            using T = std::decay_t<decltype(rot.c)>;
            Vec<T> v = vv(g_, rot, i, j), p0 = endpoint(rot, s, false), p1 = endpoint(rot, s, true);
            Vec<T> d = p1 - p0, w = v - p0;
            return std::array<T, 3>{cross(w, d), dot(w, d), dot(d, d) - dot(w, d)};
          };
          Rotation<TrigPoly> rp{poly_cos(false), poly_sin(false)};
          auto q = quantities(rp);
          algebra::Polynomial lower = integer_numerator(q[1]), upper = integer_numerator(q[2]);
          auto accept = [&](const Real& root) {
            return algebra::sign_at(lower, root) >= 0 && algebra::sign_at(upper, root) >= 0;
          };
          auto point_of = [&](auto rot) { return std::optional(vv(g_, rot, i, j)); };
          Rotation<Rational> half{Rational(-1), Rational(0)};
          auto qh = quantities(half);
          roots_of(q[0], CriticalEvent::vertex_on_contact, mask, accept, point_of, qh[0],
                   sgn(qh[1]) >= 0 && sgn(qh[2]) >= 0);
        }
  }

  void three_concurrent() {
    const std::size_t n = segments_.size();
    Rotation<TrigPoly> rp{poly_cos(false), poly_sin(false)};
    for (const auto& segment : segments_) {
      auto line = line_of(rp, segment);
      lines_.emplace_back(Vec<TrigPoly>{reduced(line.first.x), reduced(line.first.y)}, reduced(line.second));
    }
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        std::uint64_t mab = masks_[a * n + b];
        if (mab == 0 || always_parallel(segments_[a], segments_[b])) continue;
        for (std::size_t c = b + 1; c < n; ++c) {
          std::uint64_t mask = mab & masks_[a * n + c] & masks_[b * n + c];
          if (mask == 0) continue;
          if (always_parallel(segments_[a], segments_[c]) || always_parallel(segments_[b], segments_[c])) continue;
          triple(a, b, c, mask);
        }
      }
  }

  // Line n . X = h through a segment.
  template <class T>
  std::pair<Vec<T>, T> line_of(const Rotation<T>& r, const Segment& s) const {
    Vec<T> p0 = endpoint(r, s, false), p1 = endpoint(r, s, true);
    Vec<T> d = p1 - p0;
    Vec<T> nn{-d.y, d.x};
    return {nn, dot(nn, p0)};
  }

  void triple(std::size_t i1, std::size_t i2, std::size_t i3, std::uint64_t mask) {
    const Segment &s1 = segments_[i1], &s2 = segments_[i2], &s3 = segments_[i3];
    const Segment* s[3] = {&s1, &s2, &s3};
    // determinant and the meeting point (Cramer, from the first two lines whose denominator
    // does not vanish), with extents checked on all three
    auto det_of = [&](auto rot) {
      using T = std::decay_t<decltype(rot.c)>;
      auto l1 = line_of(rot, s1), l2 = line_of(rot, s2), l3 = line_of(rot, s3);
      auto& n1 = l1.first;
      auto& n2 = l2.first;
      auto& n3 = l3.first;
      return T(n1.x * (n2.y * l3.second - l2.second * n3.y) - n1.y * (n2.x * l3.second - l2.second * n3.x) +
               l1.second * (n2.x * n3.y - n2.y * n3.x));
    };
    // point of lines (p, q): num / den
    auto meet = [&](auto rot, int p, int q) {
      using T = std::decay_t<decltype(rot.c)>;
      auto lp = line_of(rot, *s[p]), lq = line_of(rot, *s[q]);
      T den = cross(lp.first, lq.first);
      T nx = lp.second * lq.first.y - lq.second * lp.first.y;
      T ny = lp.first.x * lq.second - lq.first.x * lp.second;
      return std::make_tuple(nx, ny, den);
    };
    TrigPoly poly;
    {
      // the determinant from the lines computed once per segment
      const auto &l1 = lines_[i1], &l2 = lines_[i2], &l3 = lines_[i3];
      const auto &n1 = l1.first, &n2 = l2.first, &n3 = l3.first;
      poly = reduced(n1.x * (n2.y * l3.second - l2.second * n3.y) - n1.y * (n2.x * l3.second - l2.second * n3.x) +
                     l1.second * (n2.x * n3.y - n2.y * n3.x));
    }
    // exact extents at a root: lambda_k = dot(num - den p0, d) / (den |d|^2) in [0, 1]
    auto extent_polys = [&](auto rot, int p, int q) {
      auto [nx, ny, den] = meet(rot, p, q);
      using T = std::decay_t<decltype(den)>;
      std::vector<T> out{den};
      for (int k = 0; k < 3; ++k) {
        Vec<T> p0 = endpoint(rot, *s[k], false), p1 = endpoint(rot, *s[k], true);
        Vec<T> d = p1 - p0;
        Vec<T> num{nx - den * p0.x, ny - den * p0.y};
        T lam = dot(num, d);
        out.push_back(lam * den);                         // >= 0
        out.push_back(den * den * dot(d, d) - lam * den); // >= 0
      }
      return out;
    };
    const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    int chosen = -1;   // the pair used for the point (set by accept)
    auto accept_exact = [&](const Real& t) {
      Rotation<Rational> r = exact_rotation(t.lower);
      for (int k = 0; k < 3; ++k) {
        auto e = extent_polys(r, pairs[k][0], pairs[k][1]);
        if (sgn(e[0]) == 0) continue;
        for (std::size_t m = 1; m < e.size(); ++m)
          if (sgn(e[m]) < 0) return false;
        chosen = k;
        return true;
      }
      return false;
    };
    // Extents at a root: exactly at a rational root; at an irrational one by an enclosure over
    // a narrow isolating interval, a sign the enclosure leaves open counting as inside (the
    // point is at a segment's end: an event anyway, or so close to one that keeping it only
    // adds a critical angle, still subject to the blocked-space test).
    auto accept = [&](const Real& root) {
      chosen = -1;
      if (root.exact) {
        Rotation<Rational> r = exact_rotation(root.lower);
        for (int k = 0; k < 3; ++k) {
          auto e = extent_polys(r, pairs[k][0], pairs[k][1]);
          if (sgn(e[0]) == 0) continue;
          for (std::size_t m = 1; m < e.size(); ++m)
            if (sgn(e[m]) < 0) return false;
          chosen = k;
          return true;
        }
        return false;
      }
      Real t = root;
      for (int bits : {40}) {
        algebra::refine_dyadically(t, Rational(1) / Rational(mpz_class(1) << bits));
        if (t.exact) return accept_exact(t);
        Rotation<Box> rb = rotation_box(t.lower, t.upper, false);
        bool open = false;
        for (int k = 0; k < 3; ++k) {
          auto e = extent_polys(rb, pairs[k][0], pairs[k][1]);
          if (sgn(e[0].lo) <= 0 && sgn(e[0].hi) >= 0) continue;   // lines (nearly) parallel: another pair
          bool undecided = false;
          for (std::size_t m = 1; m < e.size(); ++m) {
            if (sgn(e[m].hi) < 0) return false;   // certainly outside an extent
            if (sgn(e[m].lo) <= 0) undecided = true;
          }
          chosen = k;
          if (!undecided) return true;
          open = true;
          break;
        }
        if (open) return true;   // undecided: kept (see above)
      }
      return chosen >= 0;
    };
    auto point_of = [&](auto rot) {
      using T = std::decay_t<decltype(rot.c)>;
      auto [nx, ny, den] = meet(rot, pairs[chosen][0], pairs[chosen][1]);
      if constexpr (std::is_same_v<T, Box>) {
        auto x = divide(nx, den), y = divide(ny, den);
        if (!x || !y) return std::optional<Vec<Box>>{};
        return std::optional(Vec<Box>{*x, *y});
      } else {
        if (sgn(den) == 0) return std::optional<Vec<Rational>>{};
        return std::optional(Vec<Rational>{Rational(nx / den), Rational(ny / den)});
      }
    };
    // the half turn, exactly
    Rotation<Rational> half{Rational(-1), Rational(0)};
    Rational at_half = det_of(half);
    bool half_ok = false;
    if (sgn(at_half) == 0)
      for (int k = 0; k < 3 && !half_ok; ++k) {
        auto e = extent_polys(half, pairs[k][0], pairs[k][1]);
        if (sgn(e[0]) == 0) continue;
        half_ok = true;
        for (std::size_t m = 1; m < e.size(); ++m)
          if (sgn(e[m]) < 0) half_ok = false;
        chosen = k;
        if (!half_ok) break;
      }
    roots_of(poly, CriticalEvent::three_contacts, mask, accept, point_of, Rational(1), false);
    if (sgn(at_half) == 0 && half_ok && (mask >> 32) != 0) {
      // (chosen: recomputed for the half turn)
      for (int k = 0; k < 3; ++k)
        if (sgn(extent_polys(half, pairs[k][0], pairs[k][1])[0]) != 0) {
          chosen = k;
          break;
        }
      ++stats_.roots;
      if (certainly_blocked(Real{}, true, point_of))
        ++stats_.irrelevant;
      else
        found_.push_back(Critical{true, Real{}, {CriticalEvent::three_contacts}});
    }
  }

  const PolygonalPair& g_;
  CriticalStatistics& stats_;
  Certifier cert_;
  std::vector<Segment> segments_;
  std::vector<std::pair<Vec<TrigPoly>, TrigPoly>> lines_;   // n . X = h per segment (three_concurrent)
  std::vector<std::uint64_t> masks_, vmasks_;
  std::vector<Critical> found_;
};

// ---------------------------------------------------------------- pairs with arcs
// The contact curves of a slice are line segments (vertex–segment, and segment–arc: the segment
// offset by the radius) and circular arcs (vertex–arc, arc–arc). Every point of their geometry
// is a + R b with rational a, b (R the rotation), so every event below is a polynomial in the
// half-angle tangent. Events: an end of one curve on another, two curves tangent, three curves
// concurrent, a segment–arc contact appearing (the segment's normal at an end of the arc's
// span) and the ends of the two spans of an arc–arc contact meeting. Each root is checked
// exactly against the curves' extents (sign_at) and dropped only when certainly blocked.

// A point a + R b + (I - R) l. The lever l (a pin-slot window seen about a centre other than
// the part's pivot P: (I - R)(P - Q), see CurveFinder) is kept apart so that certified double
// intervals form it from 1 - cos and sin, without the cancellation of a + R b at |l| = 10^30.
struct Aff {
  Vec<Rational> a{Rational(0), Rational(0)}, b{Rational(0), Rational(0)}, l{Rational(0), Rational(0)};
  mutable std::optional<std::array<IV, 6>> enclosed;   // a.x, a.y, b.x, b.y, l.x, l.y (see at<IV>)
  mutable std::optional<Vec<TrigPoly>> polynomial;     // at the rotation (poly_cos, poly_sin) (see at<TrigPoly>)
  bool levered() const { return sgn(l.x) != 0 || sgn(l.y) != 0; }
  bool operator==(const Aff& o) const { return a.x == o.a.x && a.y == o.a.y && b.x == o.b.x && b.y == o.b.y && l.x == o.l.x && l.y == o.l.y; }
};
Aff operator+(const Aff& x, const Aff& y) { return {x.a + y.a, x.b + y.b, x.l + y.l, {}, {}}; }
Aff operator-(const Aff& x, const Aff& y) { return {x.a - y.a, x.b - y.b, x.l - y.l, {}, {}}; }
const Vec<Rational> zero_vec{Rational(0), Rational(0)};
Aff fixed_point(const Vec<Rational>& v) { return {v, zero_vec, zero_vec, {}, {}}; }
Aff turning_point(const Vec<Rational>& v) { return {zero_vec, v, zero_vec, {}, {}}; }
Aff lever_point(const Vec<Rational>& v) { return {zero_vec, zero_vec, v, {}, {}}; }

// (exact number types: a + l + R (b - l); boxes and intervals below)
template <class T>
Vec<T> at(const Aff& p, const Rotation<T>& r) {
  if (p.levered()) return Vec<T>{T(p.a.x + p.l.x), T(p.a.y + p.l.y)} + r.apply(Vec<T>{T(p.b.x - p.l.x), T(p.b.y - p.l.y)});
  return Vec<T>{T(p.a.x), T(p.a.y)} + r.apply(Vec<T>{T(p.b.x), T(p.b.y)});
}
// (the event polynomials are all formed at the rotation (poly_cos(false), poly_sin(false)): a
// point's polynomial coordinates there are formed once per point)
bool standard_rotation(const Rotation<TrigPoly>& r) {
  static const TrigPoly c = poly_cos(false), s = poly_sin(false);
  return r.c.w == c.w && r.s.w == s.w && r.c.den == c.den && r.s.den == s.den && r.c.c == c.c && r.s.c == s.c;
}
template <>
Vec<TrigPoly> at(const Aff& p, const Rotation<TrigPoly>& r) {
  auto form = [&] {
    const Vec<Rational> a = p.a + p.l, b = p.b - p.l;
    return Vec<TrigPoly>{TrigPoly(a.x), TrigPoly(a.y)} + r.apply(Vec<TrigPoly>{TrigPoly(b.x), TrigPoly(b.y)});
  };
  if (!standard_rotation(r)) return form();
  if (!p.polynomial) p.polynomial = form();
  return *p.polynomial;
}
// (boxes: the lever term from the rotation's versine and sine)
template <>
Vec<Box> at(const Aff& p, const Rotation<Box>& r) {
  if (p.levered() && !r.levered) {   // (no versine formed: the exact form, enclosed)
    const Vec<Rational> a = p.a + p.l, b = p.b - p.l;
    return Vec<Box>{Box(a.x), Box(a.y)} + r.apply(Vec<Box>{Box(b.x), Box(b.y)});
  }
  Vec<Box> out = Vec<Box>{Box(p.a.x), Box(p.a.y)} + r.apply(Vec<Box>{Box(p.b.x), Box(p.b.y)});
  if (p.levered()) out = out + Vec<Box>{r.versine * Box(p.l.x) + r.sine * Box(p.l.y), r.versine * Box(p.l.y) - r.sine * Box(p.l.x)};
  return out;
}
// (the interval filter: the enclosures of a point's rationals, formed once per point; the lever
// term (I - R) l = ((1 - c) l.x + s l.y, (1 - c) l.y - s l.x) from the rotation's versine)
template <>
Vec<IV> at(const Aff& p, const Rotation<IV>& r) {
  if (!p.enclosed) p.enclosed = std::array<IV, 6>{IV(p.a.x), IV(p.a.y), IV(p.b.x), IV(p.b.y), IV(p.l.x), IV(p.l.y)};
  const auto& e = *p.enclosed;
  if (p.levered() && !r.levered)   // (no versine formed: the exact form, enclosed)
    return Vec<IV>{e[0] + e[4], e[1] + e[5]} + r.apply(Vec<IV>{e[2] - e[4], e[3] - e[5]});
  Vec<IV> out = Vec<IV>{e[0], e[1]} + r.apply(Vec<IV>{e[2], e[3]});
  if (p.levered()) out = out + Vec<IV>{r.versine * e[4] + r.s * e[5], r.versine * e[5] - r.s * e[4]};
  return out;
}

// Directions counter-clockwise from s to e of an arc of rational radius (|s| = |e| = radius).
struct Span {
  Vec<Rational> s, e;
  Rational radius;
  enum Mode { full, below_half, above_half, half } mode = full;
};

// A direction w (of a circle curve: from its centre to the point; of a line curve: `dir`) must
// lie in the span, turned by R when `turning`, after negation when `negate`.
struct SpanCondition {
  Span span;
  bool turning = false;
  bool negate = false;
};

struct Curve {
  bool circle = false;
  bool extra = false;  // a line of the slice window (pin-slot pairs), not a contact
  int pins = 0;        // extra: the in_window conditions that hold at every point of its line (bits)
  Aff p0, d;          // line: p0 + lambda d, lambda in [0, 1]
  Aff centre;         // circle
  Rational radius;
  Aff dir;            // line: the direction its span conditions test (segment–arc contacts)
  std::vector<SpanCondition> spans;
  struct End {
    Aff point;
    std::size_t own = no_index;   // circle: the span condition it ends
  };
  std::vector<End> ends;
};

// A sign condition at a root: every polynomial >= 0 (or, `any`, one of them; `strict`: > 0).
template <class T>
struct ConditionOf {
  std::vector<T> p;
  bool any = false;
  bool strict = false;
  bool guard = false;   // see CurveFinder::verdict_at
};
using Condition = ConditionOf<TrigPoly>;

class CurveFinder {
 public:
  // The curves are formed about `centre` (the free part turning about it; default its pivot).
  // A pin-slot part turning about its pivot P is the part turning about Q = centre, translated
  // by (I - R)(P - Q): the slices are the same, shifted by that lever term, which the pin-slot
  // window takes (pin_slot_window). The critical angles are the same.
  CurveFinder(const Part& fixed, const Part& free, CriticalStatistics& stats, const std::optional<Point>& centre = std::nullopt)
      : stats_(stats), cert_(fixed, free, centre ? *centre : free.motion.pivot) {
    cert_.count_filtered_into(&stats.probes_filtered);
    cert_.count_searches_into(&stats);
    const Point& pivot = centre ? *centre : free.motion.pivot;
    lever_ = Vec<Rational>{Rational(free.motion.pivot.x - pivot.x), Rational(free.motion.pivot.y - pivot.y)};
    // the lever in the parts' length unit about the centre (1 mm for parts of ordinary size, as
    // before; a pair drawn at 10^-300 mm with its pivot 10^18 of its size away gets the stages
    // of that pair at 1 mm: in mm its lever of 10^-282 mm asked for no finer stage, and 25
    // critical values were left for 15)
    Rational extent = 0;
    for (const Part* part : {&fixed, &free})
      for (const auto& loop : part->loops)
        for (const auto& e : loop.edges)
          for (const Point* p : {&e.source, &e.target, &e.center}) {
            if (p == &e.center && !e.is_arc()) continue;
            extent = std::max({extent, Rational(abs(p->x - pivot.x)), Rational(abs(p->y - pivot.y))});
          }
    cert_.lever_reach(Rational((abs(lever_.x) + abs(lever_.y)) / length_unit_of_largest(extent)));
    auto rel = [&](const Point& p) { return Vec<Rational>{Rational(p.x - pivot.x), Rational(p.y - pivot.y)}; };
    auto features = [&](const Part& part, Features& f) {
      for (const auto& loop : part.loops)
        for (const auto& e : loop.edges) {
          if (!e.is_full_circle()) f.vertices.push_back(rel(e.source));
          if (!e.is_arc()) {
            f.segments.push_back({rel(e.source), rel(e.target)});
            continue;
          }
          auto r = rational_sqrt(e.radius_squared);
          if (!r)
            throw GeometryError("part '" + part.name + "': an arc of irrational radius (" + e.pointer +
                                "): critical angles of 3-DOF pairs with arcs need rational radii");
          Arc a;
          a.centre = rel(e.center);
          a.convex = e.ccw;
          a.span.radius = *r;
          if (e.is_full_circle()) {
            a.span.mode = Span::full;
          } else {
            a.span.s = rel(e.source) - a.centre;
            a.span.e = rel(e.target) - a.centre;
            if (!e.ccw) std::swap(a.span.s, a.span.e);
            int c = sgn(cross(a.span.s, a.span.e));
            a.span.mode = c > 0 ? Span::below_half : c < 0 ? Span::above_half : Span::half;
          }
          f.arcs.push_back(a);
        }
    };
    features(fixed, a_);
    features(free, b_);
    make_curves();
  }

  // A pin-slot slice sees the translations X = s R d (other part fixed: a segment of the line,
  // s in [s_lo, s_hi]) or X = s R d - q f (other part translating along f: a parallelogram,
  // q in [q_lo, q_hi]); events count only inside, and the window's edges are extra curves.
  void pin_slot_window(const Vec<Rational>& d, const Rational& s_lo, const Rational& s_hi,
                       const std::optional<std::pair<Vec<Rational>, std::pair<Rational, Rational>>>& translating) {
    window_ = Window{d, s_lo, s_hi, translating};
    // (about a centre Q other than the pivot P: every window point shifted by (I - R)(P - Q))
    auto extra = [&](const Aff& p0, const Aff& dd, int pins) {
      add_line(p0 + lever_point(lever_), dd);
      curves_.back().extra = true;
      curves_.back().pins = pins;
    };
    // (pins: see in_window; the segment's line is the window's, the parallelogram's edges have
    // s or q at a limit)
    if (!translating) {
      only_extra_ = true;
      extra(turning_point(scale(s_lo, d)), turning_point(scale(Rational(s_hi - s_lo), d)), 1);
      return;
    }
    const Vec<Rational>& f = translating->first;
    const auto& [q_lo, q_hi] = translating->second;
    for (const Rational& sv : {s_lo, s_hi})
      extra(turning_point(scale(sv, d)) - fixed_point(scale(q_lo, f)), fixed_point(scale(Rational(q_lo - q_hi), f)), 1);
    for (const Rational& qv : {q_lo, q_hi})
      extra(turning_point(scale(s_lo, d)) - fixed_point(scale(qv, f)), turning_point(scale(Rational(s_hi - s_lo), d)), 2);
    // the window degenerates where R d is parallel to f
    auto build = [&](const Rotation<TrigPoly>& r) {
      Event e;
      e.poly = cross(at(turning_point(d), r), Vec<TrigPoly>{TrigPoly(f.x), TrigPoly(f.y)});
      return e;
    };
    degenerate_ = build;
  }

  // Only half-angle tangents in [lo, hi] matter (the pin-slot part's angle limits): masks over
  // that range, roots isolated in it, no half turn.
  void restrict_to(const Rational& lo, const Rational& hi) { range_ = std::make_pair(lo, hi); }

  // Narrow the restricted range to where the part's curves can meet the window (run_narrowed;
  // pin-slot parts far from their pivot, session 58; with the filters only: the plain exact
  // path, filters off, is the tests' oracle).
  void narrow_to_window(bool on) { narrow_ = on; }

  // The interval filter and the oracle's memory (on by default; off: the plain exact path).
  void use_filters(bool on) {
    filters_ = on;
    cert_.remember(on);
  }

  std::vector<Critical> run() {
    compute_masks();
    if (degenerate_) window_degenerate();
    auto skip = [&](std::initializer_list<std::size_t> ids) {
      if (!only_extra_) return false;
      for (std::size_t id : ids)
        if (curves_[id].extra) return false;
      return true;
    };
    if (narrow_ && filters_ && range_ && window_) return run_narrowed(skip);   // (filters off: the plain path)
    candidates([&](std::initializer_list<std::size_t> ids) { return !skip(ids); });
    return merged(std::move(found_));
  }

 private:
  struct Arc {
    Vec<Rational> centre;
    Span span;
    bool convex = true;
  };
  struct Features {
    std::vector<Vec<Rational>> vertices;
    std::vector<std::pair<Vec<Rational>, Vec<Rational>>> segments;
    std::vector<Arc> arcs;
  };

  static Vec<Rational> outward(const Vec<Rational>& e) { return {e.y, -e.x}; }   // material on the left
  static std::optional<Rational> length(const Vec<Rational>& e) { return rational_sqrt(Rational(dot(e, e))); }

  void add_circle(const Aff& centre, const Rational& radius, std::vector<SpanCondition> spans) {
    Curve c;
    c.circle = true;
    c.centre = centre;
    c.radius = radius;
    c.spans = std::move(spans);
    for (std::size_t k = 0; k < c.spans.size(); ++k) {
      const SpanCondition& sc = c.spans[k];
      if (sc.span.mode == Span::full) continue;
      for (const auto& end : {sc.span.s, sc.span.e}) {
        // w = +-(R) end / radius_of_span
        Vec<Rational> v = scale(Rational(radius / sc.span.radius), end);
        if (sc.negate) v = scale(Rational(-1), v);
        c.ends.push_back({c.centre + (sc.turning ? turning_point(v) : fixed_point(v)), k});
      }
    }
    curves_.push_back(std::move(c));
  }
  void add_line(const Aff& p0, const Aff& d, const Aff& dir = {}, std::vector<SpanCondition> spans = {}) {
    Curve c;
    c.p0 = p0;
    c.d = d;
    c.dir = dir;
    c.spans = std::move(spans);
    c.ends = {{p0}, {p0 + d}};
    curves_.push_back(std::move(c));
  }

  void make_curves() {
    for (const auto& [p, q] : a_.segments)
      for (const auto& u : b_.vertices) add_line(fixed_point(p) - turning_point(u), fixed_point(q - p));
    for (const auto& a : a_.vertices)
      for (const auto& [p, q] : b_.segments) add_line(fixed_point(a) - turning_point(p), turning_point(scale(Rational(-1), q - p)));
    for (const auto& arc : a_.arcs)
      for (const auto& u : b_.vertices) add_circle(fixed_point(arc.centre) - turning_point(u), arc.span.radius, {{arc.span, false, false}});
    for (const auto& a : a_.vertices)
      for (const auto& arc : b_.arcs) add_circle(fixed_point(a) - turning_point(arc.centre), arc.span.radius, {{arc.span, true, true}});
    auto unit_normal = [](const Vec<Rational>& e, const char* which) {
      auto l = length(e);
      if (!l)
        throw GeometryError(std::string("3-DOF pair with arcs: a ") + which +
                            " segment of irrational length faces an arc; critical angles need rational lengths there");
      return scale(Rational(1 / *l), outward(e));
    };
    // fixed segment against a convex arc of the free part: the arc's centre at distance rho
    // outside the segment; contact direction -N from the arc's centre in R span
    for (const auto& [p, q] : a_.segments)
      for (const auto& arc : b_.arcs) {
        if (!arc.convex) continue;
        Vec<Rational> n = unit_normal(q - p, "fixed");
        add_line(fixed_point(p + scale(arc.span.radius, n)) - turning_point(arc.centre), fixed_point(q - p),
                 fixed_point(scale(Rational(-1), n)), {{arc.span, true, false}});
      }
    // free segment against a convex arc of the fixed part
    for (const auto& arc : a_.arcs)
      for (const auto& [p, q] : b_.segments) {
        if (!arc.convex) continue;
        Vec<Rational> n = unit_normal(q - p, "free");
        add_line(fixed_point(arc.centre) - turning_point(p + scale(arc.span.radius, n)), turning_point(scale(Rational(-1), q - p)),
                 turning_point(scale(Rational(-1), n)), {{arc.span, false, false}});
      }
    // arc against arc: X = cA - R cB + Rc w, w from the fixed arc's centre towards the free one's
    for (const auto& A : a_.arcs)
      for (const auto& B : b_.arcs) {
        Aff centre = fixed_point(A.centre) - turning_point(B.centre);
        const Rational &ra = A.span.radius, &rb = B.span.radius;
        if (A.convex && B.convex) {
          add_circle(centre, ra + rb, {{A.span, false, false}, {B.span, true, true}});
        } else if (!A.convex && B.convex) {
          if (ra > rb) add_circle(centre, ra - rb, {{A.span, false, false}, {B.span, true, false}});
        } else if (A.convex && !B.convex) {
          if (rb > ra) add_circle(centre, rb - ra, {{A.span, false, true}, {B.span, true, true}});
        }
        // concave against concave: no tangential contact; equal radii: the arcs coincide at one
        // translation, reached through their ends' vertex–arc contacts
      }
  }

  // ------------------------------------------------------------ conditions
  template <class T>
  static ConditionOf<T> in_span(const SpanCondition& sc, Vec<T> w, const Rotation<T>& r) {
    if (sc.span.mode == Span::full) return {};
    if (sc.negate) w = scale(T(Rational(-1)), w);
    Vec<T> s{T(sc.span.s.x), T(sc.span.s.y)}, e{T(sc.span.e.x), T(sc.span.e.y)};
    if (sc.turning) {
      s = r.apply(s);
      e = r.apply(e);
    }
    if (sc.span.mode == Span::half) return {{cross(s, w)}, false};
    return {{cross(s, w), cross(w, e)}, sc.span.mode == Span::above_half};
  }
  // The conditions for the point num / den to lie on curve c's extent (given it lies on its
  // supporting line or circle).
  template <class T>
  void on_extent(const Curve& c, const Vec<T>& num, const T& den, const Rotation<T>& r,
                        std::vector<ConditionOf<T>>& out) {
    if (skip_conditions_) return;
    if (c.circle) {
      Vec<T> w = scale(den, num - scale(den, at(c.centre, r)));
      for (const auto& sc : c.spans) out.push_back(in_span(sc, w, r));
      return;
    }
    Vec<T> d = at(c.d, r);
    T l = dot(num - scale(den, at(c.p0, r)), d) * den;
    out.push_back({{l, den * den * dot(d, d) - l}, false});
    for (const auto& sc : c.spans) out.push_back(in_span(sc, at(c.dir, r), r));
  }
  // Is the curve's end k a true end (inside the curve's other span conditions)?
  template <class T>
  void end_valid(const Curve& c, std::size_t k, const Rotation<T>& r, std::vector<ConditionOf<T>>& out) {
    if (skip_conditions_) return;
    if (!c.circle) {
      for (const auto& sc : c.spans) out.push_back(in_span(sc, at(c.dir, r), r));
      return;
    }
    Vec<T> w = at(c.ends[k].point, r) - at(c.centre, r);
    for (std::size_t m = 0; m < c.spans.size(); ++m)
      if (m != c.ends[k].own) out.push_back(in_span(c.spans[m], w, r));
  }
  // The polynomial vanishing when num / den lies on the curve's supporting line or circle.
  template <class T>
  static T on_support(const Curve& c, const Vec<T>& num, const T& den, const Rotation<T>& r) {
    if (c.circle) {
      Vec<T> w = num - scale(den, at(c.centre, r));
      return dot(w, w) - T(Rational(c.radius * c.radius)) * den * den;
    }
    return cross(num - scale(den, at(c.p0, r)), at(c.d, r));
  }

  // ------------------------------------------------------------ roots
  struct Event {
    TrigPoly poly;
    std::vector<Condition> conditions;
  };
  static bool holds(const Condition& c, const Real& root) {
    if (c.p.empty()) return true;
    for (const auto& p : c.p) {
      int s = p.zero() ? 0 : algebra::sign_at(integer_numerator(p), root);
      bool ok = c.strict ? s > 0 : s >= 0;
      if (c.any && ok) return true;
      if (!c.any && !ok) return false;
    }
    return !c.any;
  }

  // cos and sin of theta(u) = 2 atan(u) for u in [a, b] (doubles, -1 <= a <= b <= 1), in
  // certified double intervals: enclosed by their values at the ends (sin is increasing there,
  // cos increasing up to 0, then decreasing).
  static Rotation<IV> rotation_over(double a, double b) {
    auto at_point = [](double u) {
      const kernels::Interval x = kernels::Interval::point(u), one(1);
      const kernels::Interval d = one + x * x;
      return std::make_tuple((one - x * x) / d, kernels::Interval(2) * x / d, kernels::Interval(2) * x * x / d);
    };
    auto [ca, sa, va] = at_point(a);
    auto [cb, sb, vb] = at_point(b);
    kernels::Interval c = b <= 0.0   ? kernels::Interval(ca.lo, cb.hi)
                          : a >= 0.0 ? kernels::Interval(cb.lo, ca.hi)
                                     : kernels::Interval(std::min(ca.lo, cb.lo), 1.0);
    kernels::Interval sn(sa.lo, sb.hi);
    if (c.hi > 1.0) c.hi = 1.0;
    // 1 - c = 2 u^2 / (1 + u^2): decreasing up to 0, then increasing
    kernels::Interval versine = b <= 0.0   ? kernels::Interval(vb.lo, va.hi)
                                : a >= 0.0 ? kernels::Interval(va.lo, vb.hi)
                                           : kernels::Interval(0.0, std::max(va.hi, vb.hi));
    if (versine.lo < 0.0) versine.lo = 0.0;
    return Rotation<IV>{IV(c), IV(sn), IV(versine), IV(sn), true};
  }

  // The verdict of an event's conditions at a root without forming them as polynomials:
  // `conditions_of(rotation)` gives them as functions of (cos, sin), for Rotation<IV> and
  // Rotation<Rational>. A condition polynomial's exact sign at a root u is the sign of its value
  // at the rotation of u (integer_numerator divides out only positive factors). At a rational
  // root that value is computed exactly; at an irrational one it lies in the certified double
  // interval over the rotation's enclosure (over the isolating interval, then over a copy
  // refined to 2^-40), and an interval excluding 0 (or the point 0) gives its sign. `holds`
  // when every condition holds, `fails` when one that is not a `guard` fails, else `unknown`
  // (the caller decides exactly): a certain verdict is the exact one when the conditions are
  // the event's or, as the callers prove, imply them (guards: conditions under which the
  // others imply them, that the exact event does not have).
  enum class Verdict { holds, fails, unknown };
  template <class T>
  static Verdict judge(const std::vector<ConditionOf<T>>& conditions) {
    Verdict all = Verdict::holds;
    for (const auto& condition : conditions) {
      if (condition.p.empty()) continue;
      int ok_count = 0, fail_count = 0;
      for (const auto& x : condition.p) {
        int sign;
        if constexpr (std::is_same_v<T, IV>) {
          sign = x.v.sign();
          if (sign == 2) continue;
        } else {
          sign = sgn(x);
        }
        (condition.strict ? sign > 0 : sign >= 0) ? ++ok_count : ++fail_count;
      }
      const int n = static_cast<int>(condition.p.size());
      const Verdict v = condition.any ? (ok_count > 0 ? Verdict::holds : fail_count == n ? Verdict::fails : Verdict::unknown)
                                      : (fail_count > 0 ? Verdict::fails : ok_count == n ? Verdict::holds : Verdict::unknown);
      if (v == Verdict::fails && !condition.guard) return Verdict::fails;
      if (v != Verdict::holds) all = Verdict::unknown;
    }
    return all;
  }
  template <class ConditionsOf>
  Verdict verdict_at(ConditionsOf conditions_of, const Real& root) const {
    if (!range_ || !filters_) return Verdict::unknown;
    if (root.exact) return judge(conditions_of(exact_rotation(root.lower)));
    auto decide = [&](const Real& r) {
      const double a = algebra::lower_double(r.lower), b = algebra::upper_double(r.upper);
      if (!(a >= -1.0 && b <= 1.0 && a <= b)) return Verdict::unknown;
      return judge(conditions_of(rotation_over(a, b)));
    };
    Verdict v = decide(root);
    if (v != Verdict::unknown) return v;
    Real narrow = root;
    algebra::refine_dyadically(narrow, Rational(1, mpz_class(1) << 40));
    if (narrow.exact) return judge(conditions_of(exact_rotation(narrow.lower)));
    return decide(narrow);
  }

  // Records the roots of build(rotation).poly (in the chart about 0, and the half turn: u = 0 in
  // the chart about pi) that meet the conditions and are not certainly blocked at any of the
  // points point_of(rotation) (optional<Vec<T>> each, for T Rational and Box).
  // The interval filter: true when value_of (the event polynomial's value as a function of
  // (cos, sin), in certified double intervals, with the event's conditions) certainly has no
  // zero at which every condition may hold, for u in the whole restricted range. The range is
  // one piece with double ends (`depth` bisections where a piece's enclosure holds zero; 0
  // since the conditions at roots are decided in intervals too: session 15 measured 8 levels
  // 1.33 s, 5 levels 1.22 s, 0 levels 1.12 s for the film advance, the exact path after a root
  // found being cheaper than deep bisection); cos and sin over a piece inside [-1, 1] are
  // enclosed by rotation_over. Then the exact polynomial has no root in the range that meets
  // its conditions (a condition certainly negative over a piece is negative at every root
  // there), and the exact path would record nothing.
  template <class ValueOf>
  bool certainly_no_root(ValueOf value_of) const {
    if (!range_ || !filters_) return false;
    const kernels::Interval lo = kernels::Interval::enclose(range_->first), hi = kernels::Interval::enclose(range_->second);
    if (!(lo.lo >= -1.0 && hi.hi <= 1.0)) return false;
    // (the pieces are the same for every event: their rotations' enclosures are formed once,
    // by the piece's index in the bisection tree)
    if (pieces_.empty()) pieces_.resize(std::size_t(1) << 10);
    std::vector<ConditionOf<IV>> conditions;
    std::function<bool(std::size_t, double, double, int)> clear = [&](std::size_t node, double a, double b, int depth) {
      if (!pieces_[node]) pieces_[node] = rotation_over(a, b);
      const int sign = value_of(*pieces_[node], nullptr).v.sign();
      if (sign == 1 || sign == -1) return true;
      conditions.clear();
      value_of(*pieces_[node], &conditions);
      // or a condition of the event certainly fails throughout the piece (a root there would
      // not be recorded)
      auto negative = [](const IV& x) { return x.v.hi < 0.0; };
      for (const auto& condition : conditions) {
        if (condition.p.empty()) continue;
        if (condition.any ? std::all_of(condition.p.begin(), condition.p.end(), negative)
                          : std::any_of(condition.p.begin(), condition.p.end(), negative))
          return true;
      }
      if (depth == 0) return false;
      const double m = 0.5 * (a + b);
      if (!(a < m && m < b)) return false;
      return clear(2 * node, a, m, depth - 1) && clear(2 * node + 1, m, b, depth - 1);
    };
    constexpr int depth = 0;
    return clear(1, lo.lo, hi.hi, depth);
  }

  // roots() with the interval filter first (restricted ranges only: the pin-slot finder).
  // (`value_of(rotation, conditions)`: the polynomial's value in intervals, and when
  // `conditions` is not null, the event's conditions appended there; `conditions_of`: the
  // conditions at a root for verdict_at)
  template <class Build, class PointsOf, class ValueOf, class ConditionsOf>
  void roots(Build build, CriticalEvent kind, std::uint64_t mask, PointsOf points_of, ValueOf value_of, ConditionsOf conditions_of) {
    if (certainly_no_root(value_of)) return;   // nothing would be recorded
    roots(build, kind, mask, points_of, [&](const Real& root) { return verdict_at(conditions_of, root); }, 0);
  }

  template <class Build, class PointsOf>
  void roots(Build build, CriticalEvent kind, std::uint64_t mask, PointsOf points_of) {
    roots(build, kind, mask, points_of, [](const Real&) { return Verdict::unknown; }, 0);
  }

  // (`verdict`: the conditions at a root when certain, see verdict_at; the event's exact
  // conditions are formed only when some root's verdict is unknown)
  template <class Build, class PointsOf, class VerdictOf>
  void roots(Build build, CriticalEvent kind, std::uint64_t mask, PointsOf points_of, VerdictOf verdict, int) {
    const std::size_t count = points_of(Rotation<Rational>{Rational(1), Rational(0)}).size();
    auto relevant = [&](const Real& root, bool half_turn) {
      ++stats_.roots;
      for (std::size_t k = 0; k < count; ++k) {
        auto point_of = [&](auto rot) { return points_of(rot)[k]; };
        if (!cert_.certainly_blocked(root, half_turn, point_of)) return true;
      }
      ++stats_.irrelevant;
      return false;
    };
    // the polynomial alone first (its conditions only when it has roots)
    skip_conditions_ = true;
    Event e = build(Rotation<TrigPoly>{poly_cos(false), poly_sin(false)});
    skip_conditions_ = false;
    if (!e.poly.zero()) {
      ++stats_.polynomials;
      algebra::Polynomial p = integer_numerator(e.poly);
      std::vector<Real> found = algebra::degree(p) >= 1 ? isolated(p) : std::vector<Real>{};
      bool formed = false;
      for (Real root : found) {
          algebra::detect_small_rational(root);
          bool ok;
          const Verdict v = verdict(root);
          if (v != Verdict::unknown) {
            ++stats_.verdicts;
            ok = v == Verdict::holds;
          } else {
            if (!formed) e = build(Rotation<TrigPoly>{poly_cos(false), poly_sin(false)});
            formed = true;
            ok = std::all_of(e.conditions.begin(), e.conditions.end(), [&](const Condition& c) { return holds(c, root); });
          }
          if (ok && relevant(root, false)) found_.push_back(Critical{false, root, {kind}});
        }
    }
    if ((mask >> 32) == 0 || range_) return;
    Event h = build(Rotation<TrigPoly>{poly_cos(true), poly_sin(true)});
    if (h.poly.zero() || sgn(reduced(h.poly).c[0]) != 0) return;
    Real zero = Real::from_rational(Rational(0));
    if (!std::all_of(h.conditions.begin(), h.conditions.end(), [&](const Condition& c) { return holds(c, zero); })) return;
    if (relevant(Real{}, true)) found_.push_back(Critical{true, Real{}, {kind}});
  }

  // The real roots of p (in the range, when restricted).
  std::vector<Real> isolated(const algebra::Polynomial& p) const {
    algebra::Polynomial q = algebra::square_free_part(p);
    return range_ ? algebra::real_roots(q, range_->first, range_->second) : algebra::real_roots(q);
  }

  // A point num / den as optional<Vec<T>> (T Rational or Box).
  template <class T>
  static std::optional<Vec<T>> quotient(const Vec<T>& num, const T& den) {
    if constexpr (std::is_same_v<T, Box>) {
      auto x = divide(num.x, den), y = divide(num.y, den);
      if (!x || !y) return std::nullopt;
      return Vec<Box>{*x, *y};
    } else {
      if (sgn(den) == 0) return std::nullopt;
      return Vec<Rational>{Rational(num.x / den), Rational(num.y / den)};
    }
  }

  // The conditions for the point num / den to lie in the pin-slot window (none without one).
  // `skip` (bits 1, 2: the first, second condition) leaves out conditions that hold at the
  // point: those of a window edge whose line the point lies on (`Curve::pins`; both at a corner).
  // On the segment window's line c = 0 (bit 1); at its ends s is a limit (bit 2). On the
  // parallelogram's edge s = s_lo or s_hi (bit 1), q = q_lo or q_hi (bit 2). At a limit, with
  // v = value m^2 den^2 (k != 0), one of the two polynomials below is 0 and the other is
  // (hi - lo) m^2 den^2 >= 0; with k = 0 or den = 0 both are 0: the condition holds.
  template <class T>
  void in_window(const Vec<T>& num_about_centre, const T& den, const Rotation<T>& r, std::vector<ConditionOf<T>>& out, int skip = 0) const {
    if (!window_ || skip_conditions_) return;
    const Window& w = *window_;
    Vec<T> rd = at(turning_point(w.d), r);
    const T dd = den * den;
    // about a centre other than the pivot: the point less the window's shift (I - R)(P - Q)
    const Vec<T> num = sgn(lever_.x) == 0 && sgn(lever_.y) == 0 ? num_about_centre : num_about_centre - scale(den, at(lever_point(lever_), r));
    // lo <= v / m <= hi for v = value * m * den^2 and m^2 den^2 > 0: signs of v - lo m^2 den^2, hi m^2 den^2 - v
    auto between = [&](const T& v, const T& m2, const Rational& lo, const Rational& hi) {
      out.push_back({{v - T(lo) * m2 * dd, T(hi) * m2 * dd - v}, false});
    };
    if (!w.translating) {
      T c = cross(rd, num);
      if (!(skip & 1)) out.push_back({{c, T(Rational(0)) - c}, false});   // on the line: c = 0
      if (!(skip & 2)) between(dot(num, rd) * den, T(Rational(1)), w.s_lo, w.s_hi);   // s = dot(X, R d), |d| = 1
      return;
    }
    Vec<T> f{T(w.translating->first.x), T(w.translating->first.y)};
    const T k = cross(rd, f);
    // s = cross(X, f) / k, q = cross(X, R d) / k
    if (!(skip & 1)) between(cross(num, f) * den * k, k * k, w.s_lo, w.s_hi);
    if (!(skip & 2)) between(cross(num, rd) * den * k, k * k, w.translating->second.first, w.translating->second.second);
  }

  // Where the translating window degenerates (R d parallel to f): critical, kept unfiltered.
  void window_degenerate() {
    Event e = degenerate_(Rotation<TrigPoly>{poly_cos(false), poly_sin(false)});
    if (e.poly.zero()) return;
    ++stats_.polynomials;
    algebra::Polynomial p = integer_numerator(e.poly);
    if (algebra::degree(p) >= 1)
      for (Real root : isolated(p)) {
        algebra::detect_small_rational(root);
        ++stats_.roots;
        found_.push_back(Critical{false, root, {CriticalEvent::antiparallel_edges}});
      }
    if (range_) return;
    Event h = degenerate_(Rotation<TrigPoly>{poly_cos(true), poly_sin(true)});
    if (!h.poly.zero() && sgn(reduced(h.poly).c[0]) == 0) found_.push_back(Critical{true, Real{}, {CriticalEvent::antiparallel_edges}});
  }

  // ------------------------------------------------------------ events
  void end_on_curve(std::size_t i, std::size_t k, std::size_t j) {
    const Curve &ci = curves_[i], &cj = curves_[j];
    auto build = [&](const Rotation<TrigPoly>& r) {
      Event e;
      Vec<TrigPoly> p = at(ci.ends[k].point, r);
      TrigPoly one(Rational(1));
      e.poly = on_support(cj, p, one, r);
      end_valid(ci, k, r, e.conditions);
      on_extent(cj, p, one, r, e.conditions);
      in_window(p, one, r, e.conditions);
      return e;
    };
    auto points = [&](auto rot) { return std::vector{std::optional(at(ci.ends[k].point, rot))}; };
    auto value = [&](const Rotation<IV>& r, std::vector<ConditionOf<IV>>* conditions) {   // `build` in intervals
      Vec<IV> p = at(ci.ends[k].point, r);
      IV one(Rational(1));
      if (conditions) {
        end_valid(ci, k, r, *conditions);
        on_extent(cj, p, one, r, *conditions);
        in_window(p, one, r, *conditions);
      }
      return on_support(cj, p, one, r);
    };
    // at a root the end lies on cj's line, and a window edge's end is a corner of the window
    const int pinned = (ci.extra ? 3 : 0) | cj.pins;
    auto at_root = [&](const auto& r) {
      using T = std::decay_t<decltype(r.c)>;
      std::vector<ConditionOf<T>> conditions;
      Vec<T> p = at(ci.ends[k].point, r);
      T one(Rational(1));
      end_valid(ci, k, r, conditions);
      on_extent(cj, p, one, r, conditions);
      in_window(p, one, r, conditions, pinned);
      return conditions;
    };
    roots(build, CriticalEvent::vertex_on_contact, mask(i, j), points, value, at_root);
  }

  // (num, den) of the tangency point of two curves (one a circle).
  template <class T>
  std::pair<Vec<T>, T> touch_point(const Curve& a, const Curve& b, const Rotation<T>& r, bool internal) const {
    if (!a.circle) return touch_point(b, a, r, internal);
    Vec<T> c = at(a.centre, r);
    if (!b.circle) {
      Vec<T> d = at(b.d, r), p0 = at(b.p0, r);
      Vec<T> n{T(Rational(0)) - d.y, d.x};
      T nn = dot(n, n);
      return {scale(nn, c) + scale(T(dot(n, p0) - dot(n, c)), n), nn};
    }
    // c + ra / (ra -+ rb) (c2 - c)
    Rational k = a.radius / (internal ? Rational(a.radius - b.radius) : Rational(a.radius + b.radius));
    return {c + scale(T(k), at(b.centre, r) - c), T(Rational(1))};
  }

  void tangent(std::size_t i, std::size_t j) {
    const Curve &a = curves_[i], &b = curves_[j];
    for (bool internal : {false, true}) {
      if (!(a.circle && b.circle) && internal) break;
      if (internal && a.radius == b.radius) break;   // coincident circles: their ends' events
      auto build = [&](const Rotation<TrigPoly>& r) {
        Event e;
        if (a.circle && b.circle) {
          Vec<TrigPoly> v = at(a.centre, r) - at(b.centre, r);
          Rational sum = internal ? Rational(a.radius - b.radius) : Rational(a.radius + b.radius);
          e.poly = dot(v, v) - TrigPoly(Rational(sum * sum));
        } else {
          const Curve& c = a.circle ? a : b;
          const Curve& l = a.circle ? b : a;
          Vec<TrigPoly> d = at(l.d, r), w = at(c.centre, r) - at(l.p0, r);
          TrigPoly off = cross(d, w);
          e.poly = off * off - TrigPoly(Rational(c.radius * c.radius)) * dot(d, d);
        }
        auto [num, den] = touch_point(a, b, r, internal);
        on_extent(a, num, den, r, e.conditions);
        on_extent(b, num, den, r, e.conditions);
        in_window(num, den, r, e.conditions);
        return e;
      };
      auto points = [&](auto rot) {
        auto [num, den] = touch_point(a, b, rot, internal);
        return std::vector{quotient(num, den)};
      };
      roots(build, CriticalEvent::three_contacts, mask(i, j), points);
    }
  }

  // The line n . X = h of a line curve, or the radical axis of two circle curves.
  template <class T>
  static std::pair<Vec<T>, T> line_form(const Curve& c, const Rotation<T>& r) {
    Vec<T> d = at(c.d, r);
    Vec<T> n{T(Rational(0)) - d.y, d.x};
    return {n, dot(n, at(c.p0, r))};
  }
  template <class T>
  static std::pair<Vec<T>, T> radical_axis(const Curve& a, const Curve& b, const Rotation<T>& r) {
    Vec<T> ca = at(a.centre, r), cb = at(b.centre, r);
    Vec<T> n = scale(T(Rational(2)), cb - ca);
    return {n, T(dot(cb, cb) - dot(ca, ca) + T(Rational(a.radius * a.radius - b.radius * b.radius)))};
  }

  void concurrent(std::size_t i, std::size_t j, std::size_t k, std::uint64_t m) {
    std::array<const Curve*, 3> c{&curves_[i], &curves_[j], &curves_[k]};
    std::stable_partition(c.begin(), c.end(), [](const Curve* x) { return !x->circle; });   // lines first
    const int lines = static_cast<int>(std::count_if(c.begin(), c.end(), [](const Curve* x) { return !x->circle; }));
    if (lines >= 2) {
      // two lines that are not parallel at every angle give the point; the third is checked
      const Rotation<TrigPoly> rp{poly_cos(false), poly_sin(false)};
      auto parallel = [&](const Curve* a, const Curve* b) { return cross(at(a->d, rp), at(b->d, rp)).zero(); };
      if (parallel(c[0], c[1])) {
        if (lines == 3 && !parallel(c[0], c[2])) std::swap(c[1], c[2]);
        else if (lines == 3 && !parallel(c[1], c[2])) std::swap(c[0], c[2]);
        else return;   // all parallel (or two lines and a circle: the lines meet only when they coincide)
      }
    }
    // two linear equations and the curve the point must also lie on
    auto meet = [&](auto rot) {
      using T = std::decay_t<decltype(rot.c)>;
      std::pair<Vec<T>, T> e1, e2;
      if (lines >= 2) {
        e1 = line_form(*c[0], rot);
        e2 = line_form(*c[1], rot);
      } else if (lines == 1) {
        e1 = line_form(*c[0], rot);
        e2 = radical_axis(*c[1], *c[2], rot);
      } else {
        e1 = radical_axis(*c[0], *c[1], rot);
        e2 = radical_axis(*c[0], *c[2], rot);
      }
      const auto &[n1, h1] = e1;
      const auto &[n2, h2] = e2;
      T den = cross(n1, n2);
      Vec<T> num{T(h1 * n2.y - h2 * n1.y), T(n1.x * h2 - n2.x * h1)};
      return std::make_pair(num, den);
    };
    const Curve& check = lines >= 2 ? *c[2] : *c[1];   // (no lines: radical axes of c0 with c1, c2)
    auto build = [&](const Rotation<TrigPoly>& r) {
      Event e;
      auto [num, den] = meet(r);
      if (den.zero()) return e;   // never a single point: parallel lines or concentric circles
      e.poly = on_support(check, num, den, r);
      e.conditions.push_back({{den, TrigPoly(Rational(0)) - den}, true, true});   // den != 0
      for (const Curve* x : c) on_extent(*x, num, den, r, e.conditions);
      in_window(num, den, r, e.conditions);
      return e;
    };
    auto points = [&](auto rot) {
      auto [num, den] = meet(rot);
      return std::vector{quotient(num, den)};
    };
    if (lines < 2) {   // (radical axes may be parallel at every angle: no polynomial at all)
      roots(build, CriticalEvent::three_contacts, m, points);
      return;
    }
    // two lines not parallel at every angle: the exact polynomial is formed unless this
    // certainly has no zero
    auto value = [&](const Rotation<IV>& r, std::vector<ConditionOf<IV>>* conditions) {   // `build` in intervals
      auto [num, den] = meet(r);
      if (conditions) {
        conditions->push_back({{den, IV(Rational(0)) - den}, true, true});   // den != 0
        for (const Curve* x : c) on_extent(*x, num, den, r, *conditions);
        in_window(num, den, r, *conditions);
      }
      return on_support(check, num, den, r);
    };
    // At a root with den != 0 the point X = num / den lies on the lines of all three curves.
    // Two of them with a common end E (the same point a + R b; no span conditions) that are not
    // parallel there meet only at E, so X = E, an end of both: their extent conditions hold
    // (l = den^2 lambda |d|^2 with lambda 0 or 1: the pair l, den^2 |d|^2 - l is 0 and
    // den^2 |d|^2). At a root with den = 0 the first condition fails either way. So for the
    // interval verdict such a pair's extent conditions are replaced by "not parallel" (cross
    // of their directions != 0), which stays away from 0 where the originals vanish; and the
    // window conditions pinned by a window edge among the three are left out (see in_window).
    const int pinned = c[0]->pins | c[1]->pins | c[2]->pins;
    auto common_end = [&](const Curve* x, const Curve* y) {
      if (x->circle || y->circle || !x->spans.empty() || !y->spans.empty()) return false;
      for (const auto& ex : x->ends)
        for (const auto& ey : y->ends)
          if (ex.point == ey.point) return true;
      return false;
    };
    std::array<bool, 3> at_end{false, false, false};
    std::vector<std::pair<const Curve*, const Curve*>> meeting;   // pairs with a common end
    for (int x = 0; x < 3; ++x)
      for (int y = x + 1; y < 3; ++y)
        if (common_end(c[x], c[y])) {
          at_end[x] = at_end[y] = true;
          meeting.emplace_back(c[x], c[y]);
        }
    auto at_root = [&](const auto& r) {
      using T = std::decay_t<decltype(r.c)>;
      auto [num, den] = meet(r);
      std::vector<ConditionOf<T>> conditions;
      conditions.push_back({{den, T(Rational(0)) - den}, true, true});   // den != 0
      for (const auto& [x, y] : meeting) {
        const T cr = cross(at(x->d, r), at(y->d, r));
        conditions.push_back({{cr, T(Rational(0)) - cr}, true, true, true});   // not parallel (a guard)
      }
      for (int x = 0; x < 3; ++x)
        if (!at_end[x]) on_extent(*c[x], num, den, r, conditions);
      in_window(num, den, r, conditions, pinned);
      return conditions;
    };
    roots(build, CriticalEvent::three_contacts, m, points, value, at_root);
  }

  // A segment–arc contact appears or goes (the segment's normal at an end of the arc's span),
  // and the ends of an arc–arc contact's two spans meet.
  void appearing(std::size_t i) {
    const Curve& c = curves_[i];
    std::vector<std::pair<Aff, Aff>> pairs;   // directions to align (same sense)
    if (!c.circle) {
      for (const auto& sc : c.spans)
        for (const auto& end : {sc.span.s, sc.span.e}) {
          if (sc.span.mode == Span::full) continue;
          Vec<Rational> v = sc.negate ? scale(Rational(-1), end) : end;
          pairs.emplace_back(c.dir, sc.turning ? turning_point(v) : fixed_point(v));
        }
    } else if (c.spans.size() == 2) {
      for (std::size_t k = 0; k < c.ends.size(); ++k)
        for (std::size_t l = k + 1; l < c.ends.size(); ++l)
          if (c.ends[k].own != c.ends[l].own) pairs.emplace_back(c.ends[k].point - c.centre, c.ends[l].point - c.centre);
    }
    for (const auto& [x, y] : pairs) {
      auto build = [&](const Rotation<TrigPoly>& r) {
        Event e;
        Vec<TrigPoly> u = at(x, r), v = at(y, r);
        e.poly = cross(u, v);
        e.conditions.push_back({{dot(u, v)}, false});
        return e;
      };
      auto points = [&](auto rot) {
        using T = std::decay_t<decltype(rot.c)>;
        std::vector<std::optional<Vec<T>>> out;
        for (const auto& end : c.ends) out.push_back(at(end.point, rot));
        if (!c.circle) out.push_back(scale(T(Rational(1, 2)), at(c.ends[0].point, rot) + at(c.ends[1].point, rot)));
        return out;
      };
      roots(build, CriticalEvent::antiparallel_edges, ~std::uint64_t(0), points);
    }
  }

  // ------------------------------------------------------------ prefilter
  // Bit r of a curve pair's mask: their boxes over angle range r meet (and, with a window, each
  // meets the window's box: the hull of its edges').
  void compute_masks() {
    outside_.clear();
    in_window_.assign(curves_.size(), ~std::uint64_t(0));
    if (range_ && filters_ && interval_masks()) return;
    const std::size_t n = curves_.size();
    std::vector<std::vector<std::pair<Box, Box>>> boxes(n);
    for (int r = 0; r < 64; ++r) {
      bool flip = r >= 32 && !range_;
      Rational lo(r % 32 - 16, 16), hi(r % 32 - 15, 16);
      if (range_) {
        lo = range_->first + (range_->second - range_->first) * Rational(r, 64);
        hi = range_->first + (range_->second - range_->first) * Rational(r + 1, 64);
      }
      lo.canonicalize();
      hi.canonicalize();
      Rotation<Box> rot = rotation_box(lo, hi, flip, sgn(lever_.x) != 0 || sgn(lever_.y) != 0);
      // at(p, rot) with the turned part R b formed once per distinct b in this range (many
      // curves share the free part's vertex b): the same arithmetic, the same boxes
      std::map<std::pair<Rational, Rational>, Vec<Box>> turned;
      auto at_range = [&](const Aff& p) {
        if (p.levered()) return at(p, rot);
        auto [it, fresh] = turned.try_emplace(std::make_pair(p.b.x, p.b.y));
        if (fresh) it->second = rot.apply(Vec<Box>{Box(p.b.x), Box(p.b.y)});
        return Vec<Box>{Box(p.a.x), Box(p.a.y)} + it->second;
      };
      for (std::size_t i = 0; i < n; ++i) {
        const Curve& c = curves_[i];
        std::pair<Box, Box> b;
        if (c.circle) {
          Vec<Box> p = at_range(c.centre);
          b = {p.x + Box(-c.radius, c.radius), p.y + Box(-c.radius, c.radius)};
        } else {
          Vec<Box> p = at_range(c.p0), q = at_range(c.p0 + c.d);
          b = {Box{std::min(p.x.lo, q.x.lo), std::max(p.x.hi, q.x.hi)}, Box{std::min(p.y.lo, q.y.lo), std::max(p.y.hi, q.y.hi)}};
        }
        boxes[i].push_back(b);
      }
    }
    // the boxes rounded outwards to doubles (a prefilter: disjoint doubles, disjoint boxes)
    std::vector<std::array<double, 4>> near(n * 64);
    for (std::size_t i = 0; i < n; ++i)
      for (int r = 0; r < 64; ++r) {
        const auto& b = boxes[i][r];
        near[i * 64 + r] = {algebra::lower_double(b.first.lo), algebra::upper_double(b.first.hi), algebra::lower_double(b.second.lo),
                            algebra::upper_double(b.second.hi)};
      }
    masks_from(near);
    // with a window: a curve whose box never meets the window's (the hull of its edges') is out
    if (!window_) return;
    std::vector<std::pair<Box, Box>> window(64);
    std::vector<bool> set(64, false);
    for (std::size_t i = 0; i < n; ++i)
      if (curves_[i].extra)
        for (int r = 0; r < 64; ++r) {
          const auto& b = boxes[i][r];
          if (!set[r]) {
            window[r] = b;
            set[r] = true;
            continue;
          }
          window[r] = {Box{std::min(window[r].first.lo, b.first.lo), std::max(window[r].first.hi, b.first.hi)},
                       Box{std::min(window[r].second.lo, b.second.lo), std::max(window[r].second.hi, b.second.hi)}};
        }
    // Per range: an event of a window curve with another curve lies on the window curve, inside
    // the window, at an angle of some range r; so it lies in the curve's box and the window's box
    // of range r (both closed enclosures over the closed range). A range where a curve's box
    // misses the window's is cleared from every mask of that curve.
    std::vector<std::uint64_t> in_window(n, ~std::uint64_t(0));
    for (std::size_t i = 0; i < n; ++i) {
      if (curves_[i].extra) continue;
      std::uint64_t bits = 0;
      for (int r = 0; r < 64; ++r) {
        const auto &x = boxes[i][r], &y = window[r];
        if (!(x.first.hi < y.first.lo || y.first.hi < x.first.lo || x.second.hi < y.second.lo || y.second.hi < x.second.lo))
          bits |= std::uint64_t(1) << r;
      }
      in_window[i] = bits;
      if (bits == 0) outside_.push_back(i);
    }
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) masks_[a * n + b] &= in_window[a] & in_window[b];
    in_window_ = std::move(in_window);
  }
  // The pairwise masks of boxes given as doubles (x lo, x hi, y lo, y hi per curve and range).
  // A pair whose hulls over the 64 ranges are apart has boxes apart in every range (mask 0):
  // only pairs whose hulls meet compare their 64 boxes (the same masks; the film advance's
  // film:follower pair has about 1 000 curves, and the 64 comparisons of every pair were an
  // eighth of its instructions).
  void masks_from(const std::vector<std::array<double, 4>>& near) {
    const std::size_t n = curves_.size();
    masks_.assign(n * n, 0);
    std::vector<std::array<double, 4>> hull(n);
    constexpr double infinity = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < n; ++a) {
      hull[a] = {infinity, -infinity, infinity, -infinity};
      bool nan = false;
      for (int r = 0; r < 64; ++r) {
        const auto& x = near[a * 64 + r];
        nan = nan || std::isnan(x[0]) || std::isnan(x[1]) || std::isnan(x[2]) || std::isnan(x[3]);
        hull[a] = {std::min(hull[a][0], x[0]), std::max(hull[a][1], x[1]), std::min(hull[a][2], x[2]), std::max(hull[a][3], x[3])};
      }
      if (nan) hull[a] = {-infinity, infinity, -infinity, infinity};   // (a NaN bound meets everything below)
    }
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        const auto &ha = hull[a], &hb = hull[b];
        if (ha[1] < hb[0] || hb[1] < ha[0] || ha[3] < hb[2] || hb[3] < ha[2]) continue;
        std::uint64_t m = 0;
        for (int r = 0; r < 64; ++r) {
          const auto &x = near[a * 64 + r], &y = near[b * 64 + r];
          if (!(x[1] < y[0] || y[1] < x[0] || x[3] < y[2] || y[3] < x[2])) m |= std::uint64_t(1) << r;
        }
        masks_[a * n + b] = masks_[b * n + a] = m;
      }
  }

  // The masks from certified double boxes (pin-slot ranges inside [-1, 1], no curve with span
  // conditions; false, nothing set, otherwise). A recorded event of curves i, j (k) at an angle
  // of range r lies on their extents and in the window (its conditions), so in all their boxes
  // of range r and in the window's: bit r is set in the masks of the exact boxes above and of
  // any boxes enclosing them, as these do (cos and sin over the range by rotation_over, interval
  // arithmetic). Wider masks only examine events that record nothing: the same critical values.
  // `outside_` stays empty: it only skips appearing events, and without span conditions there
  // are none.
  bool interval_masks() {
    if (std::any_of(curves_.begin(), curves_.end(), [](const Curve& c) { return !c.spans.empty(); })) return false;
    const std::size_t n = curves_.size();
    std::vector<Rotation<IV>> rotations;
    for (int r = 0; r < 64; ++r) {
      Rational lo = range_->first + (range_->second - range_->first) * Rational(r, 64);
      Rational hi = range_->first + (range_->second - range_->first) * Rational(r + 1, 64);
      const double a = algebra::lower_double(lo), b = algebra::upper_double(hi);
      if (!(a >= -1.0 && b <= 1.0 && a <= b)) return false;
      rotations.push_back(rotation_over(a, b));
    }
    std::vector<std::array<double, 4>> near(n * 64);
    for (std::size_t i = 0; i < n; ++i) {
      const Curve& c = curves_[i];
      for (int r = 0; r < 64; ++r) {
        if (c.circle) {
          const Vec<IV> p = at(c.centre, rotations[r]);
          const kernels::Interval radius = kernels::Interval::enclose(c.radius);
          near[i * 64 + r] = {(p.x.v - radius).lo, (p.x.v + radius).hi, (p.y.v - radius).lo, (p.y.v + radius).hi};
        } else {
          const Vec<IV> p = at(c.ends[0].point, rotations[r]), q = at(c.ends[1].point, rotations[r]);   // p0, p0 + d
          near[i * 64 + r] = {std::min(p.x.v.lo, q.x.v.lo), std::max(p.x.v.hi, q.x.v.hi), std::min(p.y.v.lo, q.y.v.lo),
                              std::max(p.y.v.hi, q.y.v.hi)};
        }
      }
    }
    masks_from(near);
    if (!window_) return true;
    std::array<std::array<double, 4>, 64> window;
    bool set = false;
    for (std::size_t i = 0; i < n; ++i)
      if (curves_[i].extra) {
        for (int r = 0; r < 64; ++r) {
          const auto& b = near[i * 64 + r];
          window[r] = set ? std::array<double, 4>{std::min(window[r][0], b[0]), std::max(window[r][1], b[1]), std::min(window[r][2], b[2]),
                                                  std::max(window[r][3], b[3])}
                          : b;
        }
        set = true;
      }
    if (!set) return false;
    std::vector<std::uint64_t> in_window(n, ~std::uint64_t(0));
    for (std::size_t i = 0; i < n; ++i) {
      if (curves_[i].extra) continue;
      std::uint64_t bits = 0;
      for (int r = 0; r < 64; ++r) {
        const auto &x = near[i * 64 + r], &y = window[r];
        if (!(x[1] < y[0] || y[1] < x[0] || x[3] < y[2] || y[3] < x[2])) bits |= std::uint64_t(1) << r;
      }
      in_window[i] = bits;
    }
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) masks_[a * n + b] &= in_window[a] & in_window[b];
    in_window_ = std::move(in_window);
    return true;
  }

  std::uint64_t mask(std::size_t i, std::size_t j) const { return masks_[i * curves_.size() + j]; }

  // Every candidate event of the curves whose ids (one, two or three) pass `wanted` and whose
  // masks meet: curves appearing, an end on another curve, tangencies, three curves concurrent.
  template <class Wanted>
  void candidates(Wanted wanted) {
    const std::size_t n = curves_.size();
    for (std::size_t i = 0; i < n; ++i)
      if (wanted({i}) && std::find(outside_.begin(), outside_.end(), i) == outside_.end()) appearing(i);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        if (i == j || mask(i, j) == 0 || !wanted({i, j})) continue;
        for (std::size_t k = 0; k < curves_[i].ends.size(); ++k) end_on_curve(i, k, j);
        if (i < j && (curves_[i].circle || curves_[j].circle)) tangent(i, j);
      }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        std::uint64_t mij = mask(i, j);
        if (mij == 0) continue;
        for (std::size_t k = j + 1; k < n; ++k) {
          std::uint64_t m = mij & mask(i, k) & mask(j, k);
          if (m != 0 && wanted({i, j, k})) concurrent(i, j, k, m);
        }
      }
  }

  // run() for a pin-slot part far from its pivot (narrow_to_window). Its curves sweep
  // |b - pivot| dtheta within an angle range: 10^6 mm from the pivot, each of the 64 mask ranges
  // of +-8 degrees moves them 4 400 mm, so every curve's box meets every other's and the window's
  // in the few ranges where they pass the window, and every pair and triple was solved exactly
  // over the whole range (no answer within 200 s; session 57's film-advance with the follower's
  // pivot at (10^6, 40)). Every event of a curve that is not a window edge lies on that curve
  // inside the window (its conditions), so at an angle of a range where the curve's box meets
  // the window's (`in_window_`, closed enclosures over closed ranges): the hull of those ranges
  // holds all of them. The events of window edges alone (and the window's degeneracy) are found
  // first over the whole range; then the range is narrowed to the hull (masks recomputed over
  // the hull's 64 ranges) while that at least halves it, and the other events are found there:
  // the same events, far fewer candidates.
  template <class Skip>
  std::vector<Critical> run_narrowed(Skip skip) {
    const std::size_t n = curves_.size();
    auto all_extra = [&](std::initializer_list<std::size_t> ids) {
      return std::all_of(ids.begin(), ids.end(), [&](std::size_t id) { return curves_[id].extra; });
    };
    auto events = [&](bool window_edges_only) {
      candidates([&](std::initializer_list<std::size_t> ids) { return !skip(ids) && all_extra(ids) == window_edges_only; });
    };
    events(true);
    for (int step = 0; step < 64; ++step) {
      std::uint64_t live = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (!curves_[i].extra) live |= in_window_[i];
      if (live == 0) return merged(std::move(found_));   // no curve ever meets the window
      int r0 = 0, r1 = 63;
      while (!((live >> r0) & 1)) ++r0;
      while (!((live >> r1) & 1)) --r1;
      if (r1 - r0 + 1 > 32) break;   // narrowing would not halve the range
      const Rational width = range_->second - range_->first;
      Rational lo = range_->first + width * Rational(r0, 64), hi = range_->first + width * Rational(r1 + 1, 64);
      lo.canonicalize();
      hi.canonicalize();
      range_ = std::make_pair(lo, hi);
      pieces_.clear();   // (the interval filter's enclosures are of the range's pieces)
      compute_masks();
    }
    events(false);
    return merged(std::move(found_));
  }

  struct Window {
    Vec<Rational> d;
    Rational s_lo, s_hi;
    std::optional<std::pair<Vec<Rational>, std::pair<Rational, Rational>>> translating;
  };
  CriticalStatistics& stats_;
  Certifier cert_;
  std::optional<Window> window_;
  Vec<Rational> lever_{Rational(0), Rational(0)};   // P - Q: the pivot less the curves' centre
  std::optional<std::pair<Rational, Rational>> range_;
  mutable std::vector<std::optional<Rotation<IV>>> pieces_;   // see certainly_no_root
  std::vector<std::size_t> outside_;   // curves never meeting the window's box
  std::vector<std::uint64_t> in_window_;   // per curve: the mask ranges where its box meets the window's (all: no window)
  bool narrow_ = false;                    // run_narrowed (narrow_to_window)
  bool only_extra_ = false;
  bool skip_conditions_ = false;   // while building an event's polynomial alone
  bool filters_ = true;            // the interval filter (restricted ranges) before exact polynomials
  std::function<Event(const Rotation<TrigPoly>&)> degenerate_;
  Features a_, b_;
  std::vector<Curve> curves_;
  std::vector<std::uint64_t> masks_;
  std::vector<Critical> found_;
};

}  // namespace

PolygonalPair polygonal_pair(const Part& fixed, const Part& free) {
  PolygonalPair g;
  g.pivot = free.motion.pivot;
  g.fixed = &fixed;
  g.free = &free;
  auto collect = [&](const Part& part, std::vector<Point>& vertices, std::vector<std::pair<std::size_t, std::size_t>>& edges,
                     const Point& origin) {
    for (const auto& loop : part.loops) {
      std::size_t first = vertices.size();
      for (const auto& e : loop.edges) {
        if (e.is_arc())
          throw GeometryError("part '" + part.name + "' has an arc (" + e.pointer +
                              "): critical angles of 3-DOF pairs are computed for polygonal parts only");
        vertices.push_back(Point{Rational(e.source.x - origin.x), Rational(e.source.y - origin.y)});
      }
      std::size_t count = vertices.size() - first;
      for (std::size_t k = 0; k < count; ++k) edges.emplace_back(first + k, first + (k + 1) % count);
    }
  };
  collect(fixed, g.a, g.a_edges, g.pivot);
  collect(free, g.u, g.b_edges, g.pivot);
  return g;
}

std::vector<Critical> critical_angles(const PolygonalPair& pair, CriticalStatistics& statistics) {
  Finder finder(pair, statistics);
  return finder.run();
}

std::vector<Critical> critical_angles_with_arcs(const Part& fixed, const Part& free, CriticalStatistics& statistics) {
  CurveFinder finder(fixed, free, statistics);
  return finder.run();
}

std::vector<Critical> pin_slot_critical_values(const Part& other, const Part& pin, const Rational& s_lo, const Rational& s_hi,
                                               const std::optional<std::pair<Rational, Rational>>& q_range,
                                               const std::optional<std::pair<Rational, Rational>>& tau_range,
                                               CriticalStatistics& statistics, bool filters, const std::optional<Point>& centre) {
  // a pin-slot part whose reach about its pivot exceeds 16 times its reach about its own first
  // vertex (the pivot far from it; the film advance's follower: 0.7): the range narrowed to the
  // window (run_narrowed); beyond 2^20 times, the curves formed about that vertex Q and the
  // window shifted by (I - R)(P - Q) instead (CurveFinder): about the far pivot P the curves
  // a - R u cancel 10^30 mm to a few mm, beyond the certified double intervals of the masks, the
  // filter and the certificates (session 59: the pivot at 10^30 mm gave no answer in 250 s).
  // Ordinary parts keep the one pass over the whole range, about the pivot.
  bool far = false;
  std::optional<Point> about = centre;
  if (!pin.loops.empty() && !pin.loops.front().edges.empty()) {
    const Point& first = pin.loops.front().edges.front().source;
    Rational about_pivot = 0, own = 0;
    for (const auto& loop : pin.loops)
      for (const auto& e : loop.edges)
        for (const Point* p : {&e.source, e.is_arc() ? &e.center : &e.source}) {
          about_pivot = std::max(about_pivot, Rational(abs(p->x - pin.motion.pivot.x) + abs(p->y - pin.motion.pivot.y)));
          own = std::max(own, Rational(abs(p->x - first.x) + abs(p->y - first.y)));
        }
    far = about_pivot > 16 * own;
    if (!about && about_pivot > Rational(mpz_class(1) << 20) * own) about = first;
  }
  CurveFinder finder(other, pin, statistics, about);
  finder.use_filters(filters);
  if (tau_range) finder.restrict_to(tau_range->first, tau_range->second);
  finder.narrow_to_window(far);
  const Vec<Rational> d{pin.motion.direction.x, pin.motion.direction.y};
  std::optional<std::pair<Vec<Rational>, std::pair<Rational, Rational>>> translating;
  if (q_range) translating.emplace(Vec<Rational>{other.motion.direction.x, other.motion.direction.y}, *q_range);
  finder.pin_slot_window(d, s_lo, s_hi, translating);
  return finder.run();
}

AlgebraicNumber algebraic_of(const Real& r) {
  AlgebraicNumber out;
  out.polynomial = r.polynomial;
  out.lower = r.lower;
  out.upper = r.upper;
  out.exact = r.exact;
  out.lower.canonicalize();
  out.upper.canonicalize();
  return out;
}

Real real_of(const AlgebraicNumber& a) {
  Real t;
  t.polynomial = a.polynomial;
  t.lower = a.lower;
  t.upper = a.upper;
  t.exact = a.exact;
  return t;
}

std::pair<Rational, Rational> rotation_at(const Rational& u, bool flip) {
  Rational d = 1 + u * u;
  Rational c = (1 - u * u) / d, s = 2 * u / d;
  if (flip) return {-c, -s};
  return {c, s};
}

std::pair<Rational, Rational> rotation_of(const SlicedAngle& angle) {
  if (angle.half_turn) return {Rational(-1), Rational(0)};
  return rotation_at(angle.t, false);
}

bool steady_along(const PolygonalPair& g, const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip) {
  Rotation<TrigPoly> r{poly_cos(flip), poly_sin(flip)};
  const Vec<TrigPoly> qq{TrigPoly(q.x), TrigPoly(q.y)};
  auto no_root = [&](const TrigPoly& poly) {
    if (poly.zero()) return false;
    algebra::Polynomial p = integer_numerator(poly);
    if (algebra::degree(p) < 1) return true;   // a non-zero constant
    return algebra::real_roots(algebra::square_free_part(p), u_lo, u_hi).empty();
  };
  // vertex j of the free part on the line of fixed edge k: cross(R u_j + q - a_k, e_A) = 0
  for (const auto& [k0, k1] : g.a_edges) {
    Vec<TrigPoly> ea{TrigPoly(Rational(g.a[k1].x - g.a[k0].x)), TrigPoly(Rational(g.a[k1].y - g.a[k0].y))};
    for (const auto& uj : g.u) {
      Vec<TrigPoly> v = r.apply(lift_point<TrigPoly>(uj)) + qq - lift_point<TrigPoly>(g.a[k0]);
      if (!no_root(cross(v, ea))) return false;
    }
  }
  // vertex i of the fixed part on the line of free edge m: cross(a_i - q - R u_m, R e_m) = 0
  for (const auto& [m0, m1] : g.b_edges) {
    Vec<TrigPoly> em = r.apply(Vec<TrigPoly>{TrigPoly(Rational(g.u[m1].x - g.u[m0].x)), TrigPoly(Rational(g.u[m1].y - g.u[m0].y))});
    Vec<TrigPoly> um = r.apply(lift_point<TrigPoly>(g.u[m0]));
    for (const auto& ai : g.a) {
      Vec<TrigPoly> w = lift_point<TrigPoly>(ai) - qq - um;
      if (!no_root(cross(w, em))) return false;
    }
  }
  return true;
}

}  // namespace hipair::sliced
