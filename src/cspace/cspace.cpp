// hipair::CSpace: accessors and coordinate conversions of the adaptor (CGAL-free).
#include <hipair/cspace.hpp>

#include <algorithm>
#include <hipair/error.hpp>

#include "cspace/builder_impl.hpp"
#include "algebra/real_approximation.hpp"

#include <cmath>
#include <numbers>

namespace hipair {

const CSpace::Impl& CSpaceAccess::implementation(const CSpace& space) {
  if (!space.impl_) throw GeometryError("empty C-space");
  return *space.impl_;
}

CSpace CSpaceAccess::make(std::shared_ptr<const CSpace::Impl> impl) {
  CSpace space;
  space.impl_ = std::move(impl);
  return space;
}

double AlgebraicNumber::approximate() const {
  if (exact) return lower.get_d();
  cspace::algebra::Real r;
  r.polynomial = polynomial;
  r.lower = lower;
  r.upper = upper;
  r.exact = exact;
  return cspace::algebra::approximate_refining(r);   // (r is this function's own copy)
}

std::string AlgebraicNumber::to_string(const std::string& variable) const {
  return cspace::algebra::root_description(polynomial, lower, upper, exact, variable);
}

namespace {
double to_coordinate(AxisKind kind, bool half_turn, double t) {
  if (kind == AxisKind::translation) return t;
  return (half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t);
}
}  // namespace

double CSpaceChart::x_to_coordinate(double chart_x) const { return to_coordinate(x_kind, x_half_turn, chart_x); }
double CSpaceChart::y_to_coordinate(double chart_y) const { return to_coordinate(y_kind, y_half_turn, chart_y); }

std::string_view to_string(ContactKind kind) {
  switch (kind) {
    case ContactKind::vertex_segment: return "vertex-segment";
    case ContactKind::segment_vertex: return "segment-vertex";
    case ContactKind::vertex_arc: return "vertex-arc";
    case ContactKind::arc_vertex: return "arc-vertex";
    case ContactKind::arc_arc: return "arc-arc";
    case ContactKind::arc_segment: return "arc-segment";
    case ContactKind::segment_arc: return "segment-arc";
  }
  return "contact";
}

int CSpace::dimension() const { return implementation(*this).dimension; }
const std::string& CSpace::first_part() const { return implementation(*this).first_part; }
const std::string& CSpace::second_part() const { return implementation(*this).second_part; }
const std::string& CSpace::x_part() const { return implementation(*this).x_part; }
const std::string& CSpace::y_part() const { return implementation(*this).y_part; }
const std::vector<CSpaceChart>& CSpace::charts() const { return implementation(*this).public_charts; }
const std::vector<FeaturePair>& CSpace::feature_pairs() const { return implementation(*this).feature_pairs; }
const std::vector<CSpaceVertex>& CSpace::vertices() const { return implementation(*this).vertex_numbers(); }
const std::vector<CSpaceEdge>& CSpace::edges() const { return implementation(*this).edges; }
const std::vector<CSpaceCell>& CSpace::cells() const { return implementation(*this).cell_samples(); }
const CSpaceStatistics& CSpace::statistics() const { return implementation(*this).statistics; }
bool CSpace::complete() const { return implementation(*this).complete; }
long CSpace::length_unit_exponent() const { return implementation(*this).length_unit_exponent; }

namespace {

// The configuration in every chart that holds it (several: on a seam or a chart corner), in
// chart order.
// The configuration's point in every chart that holds it (chart order); with `first_only`, the
// first of them alone (the loop stops there: the same point as the full list's front).
std::vector<ChartPoint> chart_points(const CSpace::Impl& impl, const PartCoordinate& x_input, const PartCoordinate& y_input,
                                     bool first_only = false) {
  PartCoordinate x = x_input, y = y_input;
  x.value.canonicalize();
  y.value.canonicalize();
  // chart coordinate of one part coordinate for a chart axis, or nullopt if it cannot be
  // expressed in that chart (t infinite)
  auto convert = [](const PartCoordinate& p, AxisKind kind, bool half_turn) -> std::optional<Rational> {
    if (kind == AxisKind::translation) {
      if (p.kind != PartCoordinate::Kind::offset) throw GeometryError("a translation axis takes an offset");
      return p.value;
    }
    if (p.kind == PartCoordinate::Kind::offset) throw GeometryError("a rotation axis takes a half-angle tangent");
    if (p.kind == PartCoordinate::Kind::half_turn) return half_turn ? std::optional<Rational>(Rational(0)) : std::nullopt;
    if (!half_turn) return p.value;
    if (sgn(p.value) == 0) return std::nullopt;
    Rational t = -1 / p.value;   // tan((theta - pi)/2) = -cot(theta/2)
    return t;
  };
  std::vector<ChartPoint> points;
  for (std::size_t c = 0; c < impl.public_charts.size(); ++c) {
    const CSpaceChart& chart = impl.public_charts[c];
    auto cx = convert(x, chart.x_kind, chart.x_half_turn);
    if (!cx || *cx < chart.x_lo || *cx > chart.x_hi) continue;
    if (impl.dimension == 1) {
      points.push_back(ChartPoint{c, *cx, Rational(0)});
      if (first_only) break;
      continue;
    }
    auto cy = convert(y, chart.y_kind, chart.y_half_turn);
    if (!cy || *cy < chart.y_lo || *cy > chart.y_hi) continue;
    points.push_back(ChartPoint{c, *cx, *cy});
    if (first_only) break;
  }
  return points;
}

// The parts touch there: on a real edge or vertex, or in a touching cell.
bool in_contact(const Location& l) {
  return l.kind == Location::Kind::touching ||
         ((l.kind == Location::Kind::edge || l.kind == Location::Kind::vertex) && l.cell == no_index);
}

}  // namespace

std::optional<ChartPoint> CSpace::to_chart(const PartCoordinate& x, const PartCoordinate& y) const {
  std::vector<ChartPoint> points = chart_points(implementation(*this), x, y, true);
  if (points.empty()) return std::nullopt;
  return std::move(points.front());
}

namespace {
// Rationals built from (numerator, denominator) pairs need not be in canonical form; GMP
// arithmetic requires it.
ChartPoint canonical(ChartPoint p) {
  p.x.canonicalize();
  p.y.canonicalize();
  return p;
}
}  // namespace

Location CSpace::locate(const ChartPoint& point_input) const {
  const Impl& impl = implementation(*this);
  const ChartPoint point = canonical(point_input);
  Location here = cspace::locate_point(impl, point);
  if (in_contact(here) || point.chart >= impl.public_charts.size()) return here;
  // on the chart's boundary: the configuration may lie on a contact curve that meets this chart
  // there alone (see locate by part coordinates): ask the charts that share it
  const CSpaceChart& chart = impl.public_charts[point.chart];
  const bool on_x_side = point.x == chart.x_lo || point.x == chart.x_hi;
  const bool on_y_side = impl.dimension == 2 && (point.y == chart.y_lo || point.y == chart.y_hi);
  if (!on_x_side && !on_y_side) return here;
  auto part_coordinate = [](AxisKind kind, bool half_turn, const Rational& v) {
    if (kind == AxisKind::translation) return PartCoordinate{PartCoordinate::Kind::offset, v};
    if (!half_turn) return PartCoordinate{PartCoordinate::Kind::half_angle_tangent, v};
    if (sgn(v) == 0) return PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)};
    return PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(-1 / v)};   // theta = pi + 2 atan(v)
  };
  const PartCoordinate x = part_coordinate(chart.x_kind, chart.x_half_turn, point.x);
  const PartCoordinate y = impl.dimension == 2 ? part_coordinate(chart.y_kind, chart.y_half_turn, point.y) : PartCoordinate{};
  for (const ChartPoint& other : chart_points(impl, x, y)) {
    if (other.chart == point.chart) continue;
    Location there = cspace::locate_point(impl, other);
    if (in_contact(there)) return there;
  }
  return here;
}

Location CSpace::locate(const PartCoordinate& x, const PartCoordinate& y) const {
  std::vector<ChartPoint> points = chart_points(implementation(*this), x, y);
  if (points.empty()) return Location{};
  // On a seam or a chart corner the configuration lies in several charts; a contact curve may
  // meet one of them only at that boundary point (it passes through a chart's corner from
  // outside: found at theta = -90 deg, 90 deg, a pin tangent to a lever's side), where that
  // chart's arrangement has only its box corner. The parts touch there if any chart says so.
  return locate(points.front());   // which asks the other charts on a boundary
}

CertifiedValue CSpace::evaluate(std::size_t edge, double x) const {
  return cspace::evaluate_edge(implementation(*this), edge, x);
}

AlgebraicNumber CSpace::evaluate_exact(std::size_t edge, const Rational& x_input) const {
  Rational x = x_input;
  x.canonicalize();
  return cspace::evaluate_edge_exact(implementation(*this), edge, x);
}

std::string CSpace::edge_polynomial(std::size_t edge) const {
  return cspace::algebra::to_string(cspace::IntegerPolynomial2{edge_polynomial_coefficients(edge)}, "x", "y");
}

const std::vector<std::vector<mpz_class>>& CSpace::edge_polynomial_coefficients(std::size_t edge) const {
  const Impl& impl = implementation(*this);
  if (edge >= impl.edge_local.size()) throw GeometryError("no edge " + std::to_string(edge));
  auto [c, e] = impl.edge_local[edge];
  return impl.charts[c].arrangement.edges[e].support.coefficients;
}

Crossing CSpace::first_crossing(const ChartPoint& from_input, const Rational& to_x, const Rational& to_y) const {
  const Impl& impl = implementation(*this);
  ChartPoint from = canonical(from_input);
  Rational x = to_x, y = impl.dimension == 2 ? to_y : Rational(0);
  x.canonicalize();
  y.canonicalize();
  if (from.chart >= impl.public_charts.size()) throw GeometryError("path: no chart " + std::to_string(from.chart));
  const CSpaceChart& home = impl.public_charts[from.chart];
  auto inside = [&](const CSpaceChart& c, const Rational& px, const Rational& py) {
    return px >= c.x_lo && px <= c.x_hi && (impl.dimension == 1 || (py >= c.y_lo && py <= c.y_hi));
  };
  if (!inside(home, from.x, from.y)) throw GeometryError("path: the start is outside its chart's box");
  if (inside(home, x, y)) return cspace::first_crossing_in_chart(impl, from, x, y);

  // The segment leaves its box: continue through the other boxes with the same coordinates
  // (the tiles of one chart in an operating region, the charts of a limited rotation), where
  // the path is the same straight segment. Pieces [u0, u1] of the path, in order.
  const Rational dx = x - from.x, dy = y - from.y;
  auto same_system = [&](const CSpaceChart& c) {
    bool x_same = c.x_kind == home.x_kind && (c.x_kind == AxisKind::translation || c.x_half_turn == home.x_half_turn);
    bool y_same = impl.dimension == 1 ||
                  (c.y_kind == home.y_kind && (c.y_kind == AxisKind::translation || c.y_half_turn == home.y_half_turn));
    return x_same && y_same;
  };
  struct Piece {
    Rational u0, u1;
    std::size_t chart;
  };
  std::vector<Piece> pieces;
  for (std::size_t c = 0; c < impl.public_charts.size(); ++c) {
    const CSpaceChart& chart = impl.public_charts[c];
    if (!same_system(chart)) continue;
    Rational u0(0), u1(1);
    bool empty = false;
    auto clip = [&](const Rational& start, const Rational& delta, const Rational& lo, const Rational& hi) {
      if (sgn(delta) == 0) {
        if (start < lo || start > hi) empty = true;
        return;
      }
      Rational a = (lo - start) / delta, b = (hi - start) / delta;
      a.canonicalize();
      b.canonicalize();
      if (a > b) std::swap(a, b);
      if (a > u0) u0 = a;
      if (b < u1) u1 = b;
    };
    clip(from.x, dx, chart.x_lo, chart.x_hi);
    if (impl.dimension == 2) clip(from.y, dy, chart.y_lo, chart.y_hi);
    if (!empty && u0 < u1) pieces.push_back({u0, u1, c});
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.u0 < b.u0; });
  Rational covered(0);
  for (const Piece& piece : pieces) {
    if (piece.u1 <= covered) continue;
    if (piece.u0 > covered)
      throw GeometryError("path: the segment leaves the built space at parameter " + std::to_string(covered.get_d()) +
                          " (split it at the chart side, or build the whole space)");
    Rational start = covered, span = piece.u1 - start;
    ChartPoint a{piece.chart, from.x + start * dx, from.y + start * dy};
    a.x.canonicalize();
    a.y.canonicalize();
    Rational bx = from.x + piece.u1 * dx, by = from.y + piece.u1 * dy;
    bx.canonicalize();
    by.canonicalize();
    Crossing crossing = cspace::first_crossing_in_chart(impl, a, bx, by);
    if (crossing.found) {
      // back to the whole path's parameter
      crossing.parameter_lower = start + crossing.parameter_lower * span;
      crossing.parameter_upper = start + crossing.parameter_upper * span;
      crossing.parameter_lower.canonicalize();
      crossing.parameter_upper.canonicalize();
      return crossing;
    }
    covered = piece.u1;
    if (covered >= 1) break;
  }
  if (covered < 1)
    throw GeometryError("path: the segment leaves the built space at parameter " + std::to_string(covered.get_d()) +
                        " (split it at the chart side, or build the whole space)");
  return Crossing{};
}

}  // namespace hipair
