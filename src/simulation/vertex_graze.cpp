#include "simulation/vertex_graze.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <optional>
#include <vector>

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

VertexPass vertex_pass(const CSpace& space, const MotionCrossing& crossing, const MotionPath& path) {
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

}  // namespace hipair::simulation
