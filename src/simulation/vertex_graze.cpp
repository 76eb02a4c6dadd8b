#include "simulation/vertex_graze.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include <hipair/error.hpp>

namespace hipair::simulation {

namespace {

using Point = std::array<Rational, 2>;

// an algebraic number that is rational (exact, or the root of a linear polynomial)
std::optional<Rational> rational_value(const AlgebraicNumber& a) {
  if (a.exact) return a.lower;
  if (a.polynomial.size() == 2 && a.polynomial[1] != 0) {
    Rational r(-a.polynomial[0], a.polynomial[1]);
    r.canonicalize();
    return r;
  }
  return std::nullopt;
}

std::optional<Point> vertex_point(const CSpaceVertex& v) {
  if (!v.y_exact) return std::nullopt;
  std::optional<Rational> x = rational_value(v.x), y = rational_value(v.y);
  if (!x || !y) return std::nullopt;
  return Point{*x, *y};
}

// the polynomial of an offset axis at u (Horner) and its derivative
Rational value_at(const AxisPath& a, const Rational& u) {
  Rational r = 0;
  for (std::size_t i = a.coefficients.size(); i-- > 0;) r = r * u + a.coefficients[i];
  return r;
}

Rational slope_at(const AxisPath& a, const Rational& u) {
  Rational r = 0;
  for (std::size_t i = a.coefficients.size(); i-- > 1;) r = r * u + a.coefficients[i] * static_cast<long>(i);
  return r;
}

// whether the edge lies on a line: its polynomial has no term of degree above 1
bool straight(const CSpace& space, std::size_t edge) {
  const std::vector<std::vector<mpz_class>>& c = space.edge_polynomial_coefficients(edge);
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j)
      if (i + j > 1 && c[i][j] != 0) return false;
  return true;
}

Rational cross(const Point& a, const Point& b) { return a[0] * b[1] - a[1] * b[0]; }

// 0 for directions in [0, pi), 1 in [pi, 2 pi) (angle from the +x axis)
int half(const Point& d) { return d[1] > 0 || (d[1] == 0 && d[0] > 0) ? 0 : 1; }

// a's angle < b's angle, exactly, in [0, 2 pi)
bool before(const Point& a, const Point& b) {
  int ha = half(a), hb = half(b);
  if (ha != hb) return ha < hb;
  return cross(a, b) > 0;
}

struct Ray {
  Point direction;        // from the vertex along the edge
  std::size_t left_cell;  // the cell counter-clockwise next to it
};

// the cell of the sector around the vertex that holds direction d; nullopt when d runs along an
// edge or the sector's cell is unknown
std::optional<std::size_t> sector_cell(const std::vector<Ray>& rays, const Point& d) {
  const Ray* below = nullptr;   // the last ray clockwise from d (largest angle < d's, cyclically)
  const Ray* last = nullptr;    // the ray of largest angle
  for (const Ray& r : rays) {
    if (cross(r.direction, d) == 0 && r.direction[0] * d[0] + r.direction[1] * d[1] > 0) return std::nullopt;
    if (before(r.direction, d) && (!below || before(below->direction, r.direction))) below = &r;
    if (!last || before(last->direction, r.direction)) last = &r;
  }
  if (!below) below = last;   // d lies before every ray: the sector wraps around angle 0
  if (!below || below->left_cell == no_index) return std::nullopt;
  return below->left_cell;
}

}  // namespace

// session 41's rule: two translating axes, a rational vertex of straight edges (exact rationals)
static VertexPass vertex_pass_rational(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path) {
  if (space.dimension() != 2 || crossing.status != CrossingStatus::crossing || !crossing.grazing) return VertexPass::unknown;
  if (path.x.kind != AxisPath::Kind::offset || path.y.kind != AxisPath::Kind::offset) return VertexPass::unknown;
  if (crossing.chart >= space.charts().size()) return VertexPass::unknown;
  const CSpaceChart& chart = space.charts()[crossing.chart];
  if (chart.x_kind != AxisKind::translation || chart.y_kind != AxisKind::translation) return VertexPass::unknown;
  // the path's piece over the crossing's bracket and its direction there, exact
  const Point p{value_at(path.x, crossing.u_lower), value_at(path.y, crossing.u_lower)};
  const Point q{value_at(path.x, crossing.u_upper), value_at(path.y, crossing.u_upper)};
  const Point d{slope_at(path.x, crossing.u_lower), slope_at(path.y, crossing.u_lower)};
  if (d[0] == 0 && d[1] == 0) return VertexPass::unknown;
  // the one vertex near the piece: within the piece's extent of its bounding box, per axis
  const Rational reach = 2 * (abs(q[0] - p[0]) + abs(q[1] - p[1]));
  std::optional<Point> at;
  std::size_t found = no_index;
  for (std::size_t i = 0; i < space.vertices().size(); ++i) {
    const CSpaceVertex& v = space.vertices()[i];
    if (v.chart != crossing.chart) continue;
    // its isolating box against the piece's, widened
    const Rational& x_lo = v.x.lower;
    const Rational& x_hi = v.x.exact ? v.x.lower : v.x.upper;
    if (x_hi < std::min(p[0], q[0]) - reach || x_lo > std::max(p[0], q[0]) + reach) continue;
    if (v.y_upper < std::min(p[1], q[1]) - reach || v.y_lower > std::max(p[1], q[1]) + reach) continue;
    std::optional<Point> w = vertex_point(v);
    if (!w) return VertexPass::unknown;   // an irrational vertex that may be near: not decided here
    bool near = true;
    for (int k = 0; k < 2; ++k)
      near = near && (*w)[k] >= std::min(p[k], q[k]) - reach && (*w)[k] <= std::max(p[k], q[k]) + reach;
    if (!near) continue;
    if (found != no_index) return VertexPass::unknown;
    found = i;
    at = w;
  }
  if (found == no_index) return VertexPass::unknown;
  // the rays of its edges, each with the cell counter-clockwise next to it
  const CSpaceVertex& v = space.vertices()[found];
  std::vector<Ray> rays;
  for (std::size_t e : v.edges) {
    const CSpaceEdge& edge = space.edges()[e];
    const bool from_source = edge.source == found;
    if (!from_source && edge.target != found) return VertexPass::unknown;
    const std::size_t other = from_source ? edge.target : edge.source;
    if (other == no_index || !straight(space, e)) return VertexPass::unknown;
    std::optional<Point> w = vertex_point(space.vertices()[other]);
    if (!w) return VertexPass::unknown;
    Point direction{(*w)[0] - (*at)[0], (*w)[1] - (*at)[1]};
    if (direction[0] == 0 && direction[1] == 0) return VertexPass::unknown;
    // left of source -> target is left_cell; from the target the ray runs the other way
    rays.push_back(Ray{direction, from_source ? edge.left_cell : edge.right_cell});
  }
  if (rays.size() < 2) return VertexPass::unknown;
  std::optional<std::size_t> ahead = sector_cell(rays, d);
  std::optional<std::size_t> behind = sector_cell(rays, Point{-d[0], -d[1]});
  if (ahead && space.cell(CellId(*ahead)).kind == CellKind::blocked) return VertexPass::enters;
  if (!ahead || !behind) return VertexPass::unknown;
  if (space.cell(CellId(*ahead)).kind == CellKind::free && space.cell(CellId(*behind)).kind == CellKind::free)
    return VertexPass::graze;
  return VertexPass::unknown;
}


// ------------------------------------------------------------------ algebraic vertices
// (session 42, graze42: a rotating axis, curved edges, irrational vertices)

namespace {

// A closed interval with rational ends: the arithmetic encloses every value, without rounding.
struct Span {
  Rational lo, hi;
};

Span point(const Rational& r) { return {r, r}; }
Span operator+(const Span& a, const Span& b) { return {a.lo + b.lo, a.hi + b.hi}; }
Span operator-(const Span& a) { return {-a.hi, -a.lo}; }
Span operator-(const Span& a, const Span& b) { return {a.lo - b.hi, a.hi - b.lo}; }
Span operator*(const Span& a, const Span& b) {
  const Rational p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  Span r{p[0], p[0]};
  for (const Rational& q : p) {
    if (q < r.lo) r.lo = q;
    if (q > r.hi) r.hi = q;
  }
  return r;
}
// +1 / -1 where the interval excludes 0 (certified); 0 where it does not decide
int sign_of(const Span& a) { return a.lo > 0 ? 1 : a.hi < 0 ? -1 : 0; }

// the univariate integer polynomial (ascending powers) at a rational, exactly: its sign
int sign_at(const std::vector<mpz_class>& p, const Rational& x) {
  Rational r = 0;
  for (std::size_t i = p.size(); i-- > 0;) r = r * x + p[i];
  return sgn(r);
}

// A vertex's chart coordinates enclosed by rational intervals, refined on demand by exact
// bisection: x on its polynomial (square-free, one root in (lower, upper), where it changes
// sign), y on its own polynomial (y_exact) or by the adaptor's exact ordinate comparison
// (CSpace::compare_ordinate: the sign of y - the vertex's y).
class VertexEnclosure {
 public:
  VertexEnclosure(const CSpace& space, std::size_t index) : space_(space), index_(index), v_(space.vertices()[index]) {
    x_ = v_.x.exact ? point(v_.x.lower) : Span{v_.x.lower, v_.x.upper};
    if (v_.y_exact) y_ = v_.y.exact ? point(v_.y.lower) : Span{v_.y.lower, v_.y.upper};
    else y_ = {v_.y_lower, v_.y_upper};
    ok_ = x_.lo <= x_.hi && y_.lo <= y_.hi;
  }
  bool ok() const { return ok_; }
  const Span& x() const { return x_; }
  const Span& y() const { return y_; }
  // halves each interval `times` times (a point stays); false where a step is not decided
  // (the enclosure is then the last certified one)
  bool refine(int times) {
    for (int k = 0; k < times && ok_; ++k) {
      if (x_.lo != x_.hi) ok_ = bisect(v_.x, x_);
      if (ok_ && y_.lo != y_.hi) ok_ = v_.y_exact ? bisect(v_.y, y_) : bisect_ordinate();
    }
    return ok_;
  }

 private:
  static bool bisect(const AlgebraicNumber& a, Span& at) {
    const int s_lo = sign_at(a.polynomial, at.lo), s_hi = sign_at(a.polynomial, at.hi);
    if (s_lo == 0 || s_hi == 0 || s_lo == s_hi) return false;   // not one sign change: undecided
    Rational m = (at.lo + at.hi) / 2;
    m.canonicalize();
    const int s = sign_at(a.polynomial, m);
    if (s == 0) at = point(m);
    else if (s == s_lo) at.lo = m;
    else at.hi = m;
    return true;
  }
  bool bisect_ordinate() {
    Rational m = (y_.lo + y_.hi) / 2;
    m.canonicalize();
    int s = 0;
    try {
      s = space_.compare_ordinate(VertexId(index_), m);
    } catch (const GeometryError&) {
      return false;
    }
    if (s == 0) y_ = point(m);
    else if (s > 0) y_.hi = m;
    else y_.lo = m;
    return true;
  }

  const CSpace& space_;
  std::size_t index_;
  const CSpaceVertex& v_;
  Span x_, y_;
  bool ok_ = true;
};

using Coefficients = std::vector<std::vector<mpz_class>>;   // c[i][j] of x^i y^j

Coefficients partial_x(const Coefficients& c) {
  Coefficients d(c.size() > 1 ? c.size() - 1 : 0);
  for (std::size_t i = 1; i < c.size(); ++i) {
    d[i - 1].resize(c[i].size());
    for (std::size_t j = 0; j < c[i].size(); ++j) d[i - 1][j] = c[i][j] * static_cast<long>(i);
  }
  return d;
}

Coefficients partial_y(const Coefficients& c) {
  Coefficients d(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 1; j < c[i].size(); ++j) {
      if (d[i].size() < j) d[i].resize(j);
      d[i][j - 1] = c[i][j] * static_cast<long>(j);
    }
  return d;
}

Span evaluate(const Coefficients& c, const Span& x, const Span& y) {
  Span total = point(0);
  for (std::size_t i = c.size(); i-- > 0;) {
    Span row = point(0);
    for (std::size_t j = c[i].size(); j-- > 0;) row = row * y + point(Rational(c[i][j]));
    total = total * x + row;
  }
  return total;
}

// the polynomial's derivative over [lo, hi] (interval Horner)
Span slope_over(const AxisPath& a, const Span& u) {
  Span r = point(0);
  for (std::size_t i = a.coefficients.size(); i-- > 1;) r = r * u + point(a.coefficients[i] * static_cast<long>(i));
  return r;
}

// The path's velocity in chart coordinates at the vertex, for every u of the bracket: the axis
// polynomial's derivative over the bracket times d(chart)/d(path coordinate) at the vertex's
// coordinate c — 1 for an offset, (1 + c^2) / 2 for an angle (c = tan((theta - centre) / 2)),
// 1 for a half-angle tangent on a chart centred at 0 and c^2 on one centred at pi (c = -1/t).
std::optional<Span> chart_velocity(const AxisPath& a, AxisKind kind, bool half_turn, const Span& u, const Span& c) {
  const Span rate = slope_over(a, u);
  if (kind == AxisKind::translation) {
    if (a.kind != AxisPath::Kind::offset) return std::nullopt;
    return rate;
  }
  if (a.kind == AxisPath::Kind::angle) return rate * (point(1) + c * c) * point(Rational(1, 2));
  if (a.kind == AxisPath::Kind::half_tangent) return half_turn ? rate * (c * c) : rate;
  return std::nullopt;
}

struct Ray2 {
  Span x, y;               // the edge's tangent at the vertex, pointing along the edge
  std::size_t left_cell;   // the cell counter-clockwise next to it
  int side = 0;            // sign of cross(d, ray): +1 in (0, pi) from d, -1 in (pi, 2 pi)
};

Span cross(const Span& ax, const Span& ay, const Span& bx, const Span& by) { return ax * by - ay * bx; }

enum class Decided { yes, no, never };

// The sector decision at one enclosure of the vertex: the cells ahead of d and behind it.
struct Sectors {
  Decided state = Decided::no;
  std::size_t ahead = no_index, behind = no_index;
};

Sectors decide_sectors(const CSpace& space, std::size_t vertex, const VertexEnclosure& at, const Span& dx, const Span& dy) {
  Sectors out;
  const CSpaceVertex& v = space.vertices()[vertex];
  std::vector<Ray2> rays;
  for (std::size_t e : v.edges) {
    const CSpaceEdge& edge = space.edges()[e];
    const bool from_source = edge.source == vertex;
    if (!from_source && edge.target != vertex) return {Decided::never};
    Ray2 r;
    r.left_cell = from_source ? edge.left_cell : edge.right_cell;
    if (edge.vertical) {
      // x constant: from the (lower) source up, from the target down
      r.x = point(0);
      r.y = point(from_source ? 1 : -1);
    } else {
      // x-monotone: from the source towards larger x, from the target towards smaller; the
      // tangent (F_y, -F_x), oriented so, where F_y excludes 0 (else a vertical tangent or a
      // singular point: not decided here)
      const Coefficients& c = space.edge_polynomial_coefficients(e);
      const Span fx = evaluate(partial_x(c), at.x(), at.y()), fy = evaluate(partial_y(c), at.x(), at.y());
      const int s = sign_of(fy);
      if (s == 0) return out;
      const bool flip = (s > 0) != from_source;
      r.x = flip ? -fy : fy;
      r.y = flip ? fx : -fx;
    }
    r.side = sign_of(cross(dx, dy, r.x, r.y));
    if (r.side == 0) return out;   // d (or -d) along the edge, or not yet separated
    rays.push_back(r);
  }
  if (rays.size() < 2) return {Decided::never};
  // within one open half-plane of d the angular order is the sign of the cross product; the
  // ray of largest angle from d among those of one side (a total order there)
  auto largest = [&](int side, const Ray2*& best) {
    best = nullptr;
    for (const Ray2& r : rays) {
      if (r.side != side) continue;
      if (!best) {
        best = &r;
        continue;
      }
      const int s = sign_of(cross(best->x, best->y, r.x, r.y));
      if (s == 0) return false;   // tangent edges (or not yet separated)
      if (s > 0) best = &r;
    }
    return true;
  };
  const Ray2 *below_pos = nullptr, *below_neg = nullptr;
  if (!largest(1, below_pos) || !largest(-1, below_neg)) return out;
  // ahead (d): the last ray clockwise from d is the largest angle in (pi, 2 pi), else in (0, pi);
  // behind (-d): the largest in (0, pi) (that is (pi, 2 pi) from -d), else in (pi, 2 pi)
  const Ray2* ahead = below_neg ? below_neg : below_pos;
  const Ray2* behind = below_pos ? below_pos : below_neg;
  out.state = Decided::yes;
  out.ahead = ahead->left_cell;
  out.behind = behind->left_cell;
  return out;
}

// a double range as rationals (doubles are exact rationals); false for a non-finite end
bool span_of(const CertifiedRange& r, Span& out) {
  if (!std::isfinite(r.lower) || !std::isfinite(r.upper) || r.lower > r.upper) return false;
  out = {Rational(r.lower), Rational(r.upper)};
  return true;
}

bool meets(const Span& a, const Span& b) { return !(a.hi < b.lo || b.hi < a.lo); }
bool inside(const Span& a, const Span& b) { return a.lo >= b.lo && a.hi <= b.hi; }

}  // namespace

static VertexPass vertex_pass_algebraic(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path) {
  if (crossing.chart >= space.charts().size()) return VertexPass::unknown;
  const CSpaceChart& chart = space.charts()[crossing.chart];
  // the path's chart box over the bracket (the query's certified piece box), widened by twice
  // its extent: the vertex passed must lie in it, alone
  Span bx, by;
  if (!span_of(crossing.chart_point[0], bx) || !span_of(crossing.chart_point[1], by)) return VertexPass::unknown;
  const Rational reach = 2 * ((bx.hi - bx.lo) + (by.hi - by.lo));
  if (reach == 0) return VertexPass::unknown;
  const Span wx{bx.lo - reach, bx.hi + reach}, wy{by.lo - reach, by.hi + reach};
  std::optional<VertexEnclosure> found;
  std::size_t found_index = no_index;
  for (std::size_t i = 0; i < space.vertices().size(); ++i) {
    const CSpaceVertex& v = space.vertices()[i];
    if (v.chart != crossing.chart) continue;
    VertexEnclosure at(space, i);
    if (!at.ok()) return VertexPass::unknown;
    if (!meets(at.x(), wx) || !meets(at.y(), wy)) continue;
    // near: refined until inside the widened box or apart from it (or not decided: unknown)
    for (int k = 0; k < 8 && !(inside(at.x(), wx) && inside(at.y(), wy)); ++k) {
      if (!at.refine(8)) return VertexPass::unknown;
      if (!meets(at.x(), wx) || !meets(at.y(), wy)) break;
    }
    if (!meets(at.x(), wx) || !meets(at.y(), wy)) continue;
    if (!(inside(at.x(), wx) && inside(at.y(), wy))) return VertexPass::unknown;
    if (found) return VertexPass::unknown;   // a second vertex near
    found.emplace(at);
    found_index = i;
  }
  if (!found) return VertexPass::unknown;
  const CSpaceVertex& v = space.vertices()[found_index];
  if (v.on_chart_boundary || v.touching) return VertexPass::unknown;
  const Span u{crossing.u_lower, crossing.u_upper};
  // refined in stages: the signs at the vertex are certified once its enclosure separates
  // them from 0; a sign that is 0 exactly (a motion along an edge's tangent, tangent edges, a
  // vertical tangent) never separates and the rule answers unknown after the last stage
  for (int stage : {0, 16, 32, 64, 96}) {
    if (stage > 0 && !found->refine(stage)) return VertexPass::unknown;
    const std::optional<Span> dx = chart_velocity(path.x, chart.x_kind, chart.x_half_turn, u, found->x());
    const std::optional<Span> dy = chart_velocity(path.y, chart.y_kind, chart.y_half_turn, u, found->y());
    if (!dx || !dy) return VertexPass::unknown;
    const Sectors s = decide_sectors(space, found_index, *found, *dx, *dy);
    if (s.state == Decided::never) return VertexPass::unknown;
    if (s.state == Decided::no) continue;
    if (s.ahead != no_index && space.cell(CellId(s.ahead)).kind == CellKind::blocked) return VertexPass::enters;
    if (s.ahead == no_index || s.behind == no_index) return VertexPass::unknown;
    if (space.cell(CellId(s.ahead)).kind == CellKind::free && space.cell(CellId(s.behind)).kind == CellKind::free)
      return VertexPass::graze;
    return VertexPass::unknown;
  }
  return VertexPass::unknown;
}

// Session 75 (graze75): a 1-D space. The crossing's vertex alone in a window around the query's
// chart point; the path's chart velocity there of certified sign s; the cell ahead located
// exactly at a rational point between the vertex and the window's end on side s (no other vertex
// there), the cell behind likewise on side -s.
VertexPass line_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path) {
  if (space.dimension() != 1 || crossing.status != CrossingStatus::crossing) return VertexPass::unknown;
  if (crossing.chart >= space.charts().size()) return VertexPass::unknown;
  const CSpaceChart& chart = space.charts()[crossing.chart];
  Span bx;
  if (!span_of(crossing.chart_point[0], bx)) return VertexPass::unknown;
  Rational reach = 2 * (bx.hi - bx.lo);
  if (reach == 0) reach = 1;
  std::optional<VertexEnclosure> found;
  // the window shrinks (by 4) while it holds more than one vertex, each refined to it
  for (int attempt = 0; attempt < 40 && !found; ++attempt, reach /= 4) {
    const Span w{bx.lo - reach, bx.hi + reach};
    std::size_t near = 0;
    std::optional<VertexEnclosure> one;
    bool undecided = false;
    for (std::size_t i = 0; i < space.vertices().size(); ++i) {
      if (space.vertices()[i].chart != crossing.chart) continue;
      VertexEnclosure at(space, i);
      if (!at.ok()) return VertexPass::unknown;
      for (int k = 0; k < 16 && meets(at.x(), w) && !(at.x().lo > w.lo && at.x().hi < w.hi); ++k)
        if (!at.refine(4)) return VertexPass::unknown;
      if (!meets(at.x(), w)) continue;
      if (!(at.x().lo > w.lo && at.x().hi < w.hi)) undecided = true;
      ++near;
      one.emplace(at);
    }
    if (near == 0) return VertexPass::unknown;
    if (near == 1 && !undecided) {
      found.emplace(*one);
      const Span& x = found->x();
      const Span u{crossing.u_lower, crossing.u_upper};
      int s = 0;
      for (int stage = 0; stage < 5 && s == 0; ++stage) {
        if (stage > 0 && !found->refine(16)) return VertexPass::unknown;
        const std::optional<Span> dx = chart_velocity(path.x, chart.x_kind, chart.x_half_turn, u, found->x());
        if (!dx) return VertexPass::unknown;
        s = sign_of(*dx);
      }
      if (s == 0) return VertexPass::unknown;
      // the motion comes from the query's starting free cell (certified before u_lower); the
      // cell ahead decides
      Rational ahead = s > 0 ? (x.hi + w.hi) / 2 : (x.lo + w.lo) / 2;
      ahead.canonicalize();
      const Location a = space.locate(ChartPoint{crossing.chart, ahead, 0});
      if (a.kind == Location::Kind::blocked) return VertexPass::enters;
      if (a.kind == Location::Kind::free) return VertexPass::graze;
      if (a.kind == Location::Kind::touching) return VertexPass::slides;
      return VertexPass::unknown;
    }
  }
  return VertexPass::unknown;
}

VertexPass vertex_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path) {
  if (space.dimension() != 2 || crossing.status != CrossingStatus::crossing || !crossing.grazing) return VertexPass::unknown;
  const VertexPass exact = vertex_pass_rational(space, crossing, path);
  if (exact != VertexPass::unknown) return exact;
  return vertex_pass_algebraic(space, crossing, path);
}

}  // namespace hipair::simulation
