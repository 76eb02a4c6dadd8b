// hipair::CSpace: accessors and coordinate conversions of the adaptor (CGAL-free).
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include "cspace/builder_impl.hpp"

#include <cmath>
#include <numbers>

namespace hipair {

const CSpace::Impl& implementation(const CSpace& space) {
  if (!space.impl_) throw GeometryError("empty C-space");
  return *space.impl_;
}

CSpace make_cspace(std::shared_ptr<const CSpace::Impl> impl) {
  CSpace space;
  space.impl_ = std::move(impl);
  return space;
}

double AlgebraicNumber::approximate() const {
  cspace::algebra::Real r;
  r.polynomial = polynomial;
  r.lower = lower;
  r.upper = upper;
  r.exact = exact;
  return r.approximate();
}

std::string AlgebraicNumber::to_string(const std::string& variable) const {
  cspace::algebra::Real r;
  r.polynomial = polynomial;
  r.lower = lower;
  r.upper = upper;
  r.exact = exact;
  return r.description(variable);
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
const std::vector<CSpaceVertex>& CSpace::vertices() const { return implementation(*this).vertices; }
const std::vector<CSpaceEdge>& CSpace::edges() const { return implementation(*this).edges; }
const std::vector<CSpaceCell>& CSpace::cells() const { return implementation(*this).cells; }
const CSpaceStatistics& CSpace::statistics() const { return implementation(*this).statistics; }
bool CSpace::complete() const { return implementation(*this).complete; }

std::optional<ChartPoint> CSpace::to_chart(const PartCoordinate& x_input, const PartCoordinate& y_input) const {
  const Impl& impl = implementation(*this);
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
  for (std::size_t c = 0; c < impl.public_charts.size(); ++c) {
    const CSpaceChart& chart = impl.public_charts[c];
    auto cx = convert(x, chart.x_kind, chart.x_half_turn);
    if (!cx || *cx < chart.x_lo || *cx > chart.x_hi) continue;
    if (impl.dimension == 1) return ChartPoint{c, *cx, Rational(0)};
    auto cy = convert(y, chart.y_kind, chart.y_half_turn);
    if (!cy || *cy < chart.y_lo || *cy > chart.y_hi) continue;
    return ChartPoint{c, *cx, *cy};
  }
  return std::nullopt;
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

Location CSpace::locate(const ChartPoint& point) const {
  return cspace::locate_point(implementation(*this), canonical(point));
}

Location CSpace::locate(const PartCoordinate& x, const PartCoordinate& y) const {
  auto point = to_chart(x, y);
  if (!point) return Location{};
  return locate(*point);
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

Crossing CSpace::first_crossing(const ChartPoint& from, const Rational& to_x, const Rational& to_y) const {
  Rational x = to_x, y = to_y;
  x.canonicalize();
  y.canonicalize();
  return cspace::first_crossing_in_chart(implementation(*this), canonical(from), x, y);
}

}  // namespace hipair
