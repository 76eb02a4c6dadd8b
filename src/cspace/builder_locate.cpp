// Exact queries on a built C-space: point location, edge evaluation, first contact crossing.
// CGAL-free: only the exported topology and the exact univariate algebra are used.
#include "cspace/builder_impl.hpp"
#include "cspace/angle_filter.hpp"
#include "cspace/locate_prefilter.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hipair::cspace {
namespace {

using algebra::Real;

Location located_in_face(const CSpace::Impl& impl, std::size_t chart, std::size_t face) {
  Location location;
  location.chart = chart;
  const FaceData& data = impl.charts[chart].faces[face];
  if (data.kind == FaceKind::outside) return location;
  location.cell = data.cell;
  location.kind = data.kind == FaceKind::blocked ? Location::Kind::blocked : Location::Kind::free;
  if (data.kind == FaceKind::touching) location.kind = Location::Kind::touching;   // touching throughout (degenerate)
  return location;
}

Location on_edge(const CSpace::Impl& impl, std::size_t chart, std::size_t local_edge) {
  const ChartData& data = impl.charts[chart];
  const raw::Edge& edge = data.arrangement.edges[local_edge];
  const CSpaceEdge& public_edge = impl.edges[data.edges[local_edge].global];
  Location location;
  location.chart = chart;
  location.edge = data.edges[local_edge].global;
  location.kind = Location::Kind::edge;
  // inside the space on a chart boundary that is no contact: the cell of the inner face
  if (edge.box_side >= 0 && !public_edge.real) {
    std::size_t inner = data.arrangement.faces[edge.left_face].unbounded ? edge.right_face : edge.left_face;
    Location inside = located_in_face(impl, chart, inner);
    inside.edge = location.edge;
    return inside;
  }
  if (!public_edge.real && public_edge.left_cell == public_edge.right_cell) location.cell = public_edge.left_cell;
  return location;
}

// The exact ordinate of a vertex that lies on the vertical line x = `x` (its x compares equal
// to the rational x). A vertex at an irrational-looking x (a root of a reducible resultant, as
// where a vertical contact line meets a circle: the side of a slot meeting its round end
// tangentially) carries no algebraic `y`, only y_curve and its branch, and at a tangency
// y_curve's fibre has a double root there, so a sign change cannot place a rational y. At the
// rational x itself the fibre is a univariate polynomial and the branch is its exact root.
Real ordinate_at(const raw::Vertex& vertex, const Rational& x) {
  if (vertex.y_exact) return vertex.y;
  return algebra::nth_real_root(algebra::substitute_x(vertex.y_curve, x), vertex.y_branch);
}

Location locate_2d(const CSpace::Impl& impl, const hipair::ChartPoint& q) {
  const ChartData& chart = impl.charts[q.chart];
  const auto& arrangement = chart.arrangement;
  const algebra::Interval xi = algebra::enclose(q.x), yi = algebra::enclose(q.y);
  Location location;
  location.chart = q.chart;
  if (q.x < chart.box.x_lo || q.x > chart.box.x_hi || q.y < chart.box.y_lo || q.y > chart.box.y_hi) return location;

  // best hit straight above q: a vertex or the interior of a non-vertical edge. The best
  // ordinate is known exactly (`best_y`, a vertex's or an edge's exact root) or, for an edge
  // whose support is quadratic in y, by a certified double enclosure [best_lo, best_hi] until
  // an exact comparison needs it (then `best_y` is made from the edge).
  bool found = false;
  bool best_exact = false;
  Real best_y;
  double best_lo = 0, best_hi = 0;
  std::size_t best_vertex = raw::none, best_edge = raw::none;
  auto exact_best = [&]() -> const Real& {
    if (!best_exact) {
      best_y = edge_y_at(chart, best_edge, q.x);
      best_exact = true;
    }
    return best_y;
  };
  // (the vertices away from q by their rational bounds: see locate_prefilter.hpp)
  const bool exact_prefilter = locate_exact_prefilter();
  const bool vertex_bounds = locate_vertex_bounds() && chart.vertex_bounds.size() == arrangement.vertices.size();
  for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
    if (vertex_bounds) {
      const std::array<double, 3>& b = chart.vertex_bounds[v];
      if (b[1] < xi.lo || b[0] > xi.hi || b[2] < yi.lo) continue;
    }
    const raw::Vertex& vertex = arrangement.vertices[v];
    if (exact_prefilter) {
      if (vertex.x.upper < q.x || vertex.x.lower > q.x || vertex.y_upper < q.y) continue;
    } else {
      if (vertex.x.upper_bound() < xi.lo || vertex.x.lower_bound() > xi.hi) continue;
      if (vertex.y_upper_bound() < yi.lo) continue;
    }
    if (vertex.x.compare(q.x) != 0) continue;
    Real vertex_y = ordinate_at(vertex, q.x);
    int c = vertex_y.compare(q.y);
    if (c == 0) {
      Location at;
      at.chart = q.chart;
      at.kind = Location::Kind::vertex;
      at.vertex = chart.vertex_global[v];
      // a vertex of spurious edges only lies inside one cell
      bool real = impl.vertices[at.vertex].touching;
      for (std::size_t e : impl.vertices[at.vertex].edges) real = real || impl.edges[e].real;
      if (!real) {
        if (vertex.isolated) {
          at.cell = chart.faces[vertex.face_below].cell;
        } else {
          for (const auto& incidence : vertex.around)
            if (incidence.wedge_face != raw::none && chart.faces[incidence.wedge_face].kind != FaceKind::outside) {
              at.cell = chart.faces[incidence.wedge_face].cell;
              break;
            }
        }
      }
      return at;
    }
    if (c > 0 && (!found || algebra::compare(vertex_y, best_y) < 0)) {
      found = true;
      best_exact = true;
      best_y = std::move(vertex_y);
      best_lo = best_y.lower_bound();
      best_hi = best_y.upper_bound();
      best_vertex = v;
      best_edge = raw::none;
    }
  }
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
    const raw::Edge& edge = arrangement.edges[e];
    if (edge.box[0] > xi.hi || edge.box[2] < xi.lo || edge.box[3] < yi.lo) continue;
    if (edge.vertical) {
      if (edge.box[1] > yi.hi) continue;
      if (chart.edges[e].vertical_x->compare(q.x) != 0) continue;
      if (ordinate_at(arrangement.vertices[edge.min_vertex], q.x).compare(q.y) < 0 &&
          ordinate_at(arrangement.vertices[edge.max_vertex], q.x).compare(q.y) > 0)
        return on_edge(impl, q.chart, e);
      continue;
    }
    candidates.emplace_back(edge.box[1], e);
  }
  std::sort(candidates.begin(), candidates.end());
  const bool filter = locate_filter();
  for (const auto& [low, e] : candidates) {
    // (a candidate whose box starts above the best's upper bound lies strictly above the best)
    if (found && low > best_hi) break;
    const raw::Edge& edge = arrangement.edges[e];
    if (arrangement.vertices[edge.min_vertex].x.compare(q.x) >= 0 ||
        arrangement.vertices[edge.max_vertex].x.compare(q.x) <= 0)
      continue;
    // the filter (support quadratic in y: the edge's root by its certified double enclosure,
    // its side of q by the exact sign of the quadratic at q.y; no root isolation), else the
    // exact ordinate; a comparison of two ordinates that the enclosures cannot separate is exact
    std::optional<QuadraticOrdinate> quadratic;
    if (filter) quadratic = quadratic_ordinate(chart, e, q.x);
    if (quadratic) {
      const algebra::Interval& y = quadratic->y;
      int c = quadratic->enclosed && y.hi < yi.lo ? -1 : quadratic->enclosed && y.lo > yi.hi ? 1 : quadratic->compare(q.y);
      if (c == 0) return on_edge(impl, q.chart, e);
      if (c < 0) continue;
      // the ordinate's enclosure: the filter's, or the edge's certified box above q
      double lo = quadratic->enclosed ? y.lo : std::max(edge.box[1], yi.lo);
      double hi = quadratic->enclosed ? y.hi : edge.box[3];
      std::optional<Real> exact;
      bool better;
      if (!found || hi < best_lo) {
        better = true;
      } else if (lo > best_hi) {
        better = false;
      } else {
        exact = edge_y_at(chart, e, q.x);
        better = algebra::compare(*exact, exact_best()) < 0;
      }
      if (better) {
        found = true;
        best_edge = e;
        best_vertex = raw::none;
        best_exact = exact.has_value();
        if (exact) best_y = std::move(*exact);
        best_lo = lo;
        best_hi = hi;
      }
      continue;
    }
    Real y = edge_y_at(chart, e, q.x);
    int c = y.compare(q.y);
    if (c == 0) return on_edge(impl, q.chart, e);
    if (c < 0) continue;
    if (!found || algebra::compare(y, exact_best()) < 0) {
      found = true;
      best_exact = true;
      best_y = std::move(y);
      best_lo = best_y.lower_bound();
      best_hi = best_y.upper_bound();
      best_edge = e;
      best_vertex = raw::none;
    }
  }
  if (!found) return location;   // cannot happen inside the box (its top side is an edge)
  std::size_t face = best_edge != raw::none ? arrangement.edges[best_edge].right_face
                                            : arrangement.vertices[best_vertex].face_below;
  if (face == raw::none) throw GeometryError("internal: point location reached a vertex with no face below");
  return located_in_face(impl, q.chart, face);
}

Location locate_1d(const CSpace::Impl& impl, const hipair::ChartPoint& q) {
  const ChartData& chart = impl.charts[q.chart];
  Location location;
  location.chart = q.chart;
  if (q.x < chart.box.x_lo || q.x > chart.box.x_hi) return location;
  std::size_t i = 0;
  for (; i < chart.points.size(); ++i) {
    int c = chart.points[i].compare(q.x);
    if (c == 0) {
      location.kind = Location::Kind::vertex;
      location.vertex = chart.vertex_global[i];
      // a point of a contact curve with the same cell on both sides is no contact boundary
      const FaceData& before = chart.faces[i];
      const FaceData& after = chart.faces[i + 1];
      // (a touching point is a contact configuration even where its two sides join round the circle)
      // (nor is a grazing contact between free intervals, where the parts touch: session 30)
      if (before.kind != FaceKind::outside && after.kind != FaceKind::outside && before.cell == after.cell &&
          !(i < chart.touching_vertex.size() && chart.touching_vertex[i]) && !(i < chart.grazing_point.size() && chart.grazing_point[i]))
        location.cell = before.cell;
      // a point on the chart's end (a seam or a motion limit) is a contact only where the parts
      // touch there (the exact oracle at build time, seam_relation): where they overlap it lies
      // in its blocked cell, where they are apart in its free cell (session 32, hunt32b)
      if ((before.kind == FaceKind::outside) != (after.kind == FaceKind::outside)) {
        const FaceData& inner = before.kind == FaceKind::outside ? after : before;
        const signed char relation = i < chart.seam_relation.size() ? chart.seam_relation[i] : static_cast<signed char>(-1);
        if ((inner.kind == FaceKind::blocked && relation == 0) || (inner.kind == FaceKind::free && relation == 2))
          location.cell = inner.cell;
      }
      return location;
    }
    if (c > 0) break;
  }
  return located_in_face(impl, q.chart, i);
}

}  // namespace

Location locate_point(const CSpace::Impl& impl, const hipair::ChartPoint& q) {
  if (q.chart >= impl.charts.size()) throw GeometryError("point location: no chart " + std::to_string(q.chart));
  return impl.dimension == 1 ? locate_1d(impl, q) : locate_2d(impl, q);
}

CertifiedValue evaluate_edge(const CSpace::Impl& impl, std::size_t edge, double x) {
  if (edge >= impl.edge_local.size()) throw GeometryError("evaluate: no edge " + std::to_string(edge));
  auto [c, e] = impl.edge_local[edge];
  const ChartData& chart = impl.charts[c];
  const raw::Edge& raw_edge = chart.arrangement.edges[e];
  if (raw_edge.vertical) {
    Real v = *chart.edges[e].vertical_x;
    v.refine_to(Rational(1, mpz_class(1) << 64));
    double value = v.approximate();
    return {value, std::max(std::fabs(v.upper_bound() - value), std::fabs(value - v.lower_bound()))};
  }
  if (!std::isfinite(x)) throw GeometryError("evaluate: abscissa is not finite");
  Rational q(x);
  const raw::Vertex& low = chart.arrangement.vertices[raw_edge.min_vertex];
  const raw::Vertex& high = chart.arrangement.vertices[raw_edge.max_vertex];
  Real y;
  int cl = low.x.compare(q), ch = high.x.compare(q);
  if (cl > 0 || ch < 0) throw GeometryError("evaluate: abscissa outside the edge's extent");
  if (cl == 0)
    y = low.y;
  else if (ch == 0)
    y = high.y;
  else
    y = edge_y_at(chart, e, q);
  // refine to a width of a few units in the last place
  double magnitude = std::max(1.0, std::fabs(y.lower_bound()));
  y.refine_to(Rational(magnitude * std::ldexp(1.0, -55)));
  Rational middle = y.exact ? y.lower : Rational((y.lower + y.upper) / 2);
  double value = middle.get_d();
  double error = std::max(std::fabs(y.upper_bound() - value), std::fabs(value - y.lower_bound()));
  return {value, error};
}

AlgebraicNumber evaluate_edge_exact(const CSpace::Impl& impl, std::size_t edge, const Rational& x) {
  if (edge >= impl.edge_local.size()) throw GeometryError("evaluate: no edge " + std::to_string(edge));
  auto [c, e] = impl.edge_local[edge];
  const ChartData& chart = impl.charts[c];
  const raw::Edge& raw_edge = chart.arrangement.edges[e];
  if (raw_edge.vertical) return to_public(*chart.edges[e].vertical_x);
  const raw::Vertex& low = chart.arrangement.vertices[raw_edge.min_vertex];
  const raw::Vertex& high = chart.arrangement.vertices[raw_edge.max_vertex];
  int cl = low.x.compare(x), ch = high.x.compare(x);
  if (cl > 0 || ch < 0) throw GeometryError("evaluate: abscissa outside the edge's extent");
  if (cl == 0) return to_public(low.y);
  if (ch == 0) return to_public(high.y);
  return to_public(edge_y_at(chart, e, x));
}

// ---------------------------------------------------------------- first contact crossing

namespace {

struct Candidate {
  Real u;
  std::vector<std::size_t> curves;   // local curves vanishing there
  bool tangent = false;              // even-multiplicity root of some curve
};

bool contact_location(const CSpace::Impl& impl, const Location& location) {
  if (location.kind == Location::Kind::edge) return impl.edges[location.edge].real;
  if (location.kind == Location::Kind::vertex) {
    if (impl.vertices[location.vertex].touching) return true;
    for (std::size_t e : impl.vertices[location.vertex].edges)
      if (impl.edges[e].real) return true;
    return impl.dimension == 1 && location.cell == no_index;
  }
  return false;
}

std::size_t cell_of(const Location& location) { return location.cell; }

}  // namespace

Crossing first_crossing_in_chart(const CSpace::Impl& impl, const hipair::ChartPoint& from, const Rational& to_x,
                                 const Rational& to_y) {
  if (from.chart >= impl.charts.size()) throw GeometryError("path: no chart " + std::to_string(from.chart));
  const ChartData& chart = impl.charts[from.chart];
  const Rational dx = to_x - from.x;
  const Rational dy = impl.dimension == 2 ? Rational(to_y - from.y) : Rational(0);
  auto point_at = [&](const Rational& u) {
    return hipair::ChartPoint{from.chart, from.x + u * dx, impl.dimension == 2 ? Rational(from.y + u * dy) : Rational(0)};
  };
  Crossing result;
  Location start = locate_point(impl, from);
  if (start.kind == Location::Kind::outside || locate_point(impl, point_at(1)).kind == Location::Kind::outside)
    throw GeometryError("path: the segment leaves the chart box");
  if (contact_location(impl, start)) {
    result.found = true;
    result.parameter_lower = result.parameter_upper = 0;
    result.edge = start.edge;
    result.vertex = start.vertex;
    result.cell_left = result.cell_entered = no_index;
    return result;
  }
  // candidate parameters: roots of every curve restricted to the path
  std::vector<Candidate> candidates;
  for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
    algebra::Polynomial p = impl.dimension == 2
                                ? algebra::substitute_line(chart.polynomials[k], from.x, dx, from.y, dy)
                                : algebra::univariate_x(chart.polynomials[k]);
    if (impl.dimension == 1) {
      // x = from.x + u dx: substitute into the univariate polynomial
      IntegerPolynomial2 f;
      for (const auto& c : p) f.coefficients.push_back({c});
      p = algebra::substitute_line(f, from.x, dx, Rational(0), Rational(0));
    }
    if (p.empty()) continue;   // the path runs along the curve: its points are located below
    algebra::Polynomial derivative = algebra::derivative(p);
    for (auto& u : algebra::real_roots(p, Rational(0), Rational(1))) {
      if (u.compare(Rational(0)) == 0) continue;
      u.detect_rational();
      bool tangent = algebra::vanishes_at(derivative, u);
      auto it = std::find_if(candidates.begin(), candidates.end(),
                             [&](const Candidate& c) { return algebra::compare(c.u, u) == 0; });
      if (it == candidates.end()) {
        candidates.push_back(Candidate{std::move(u), {k}, tangent});
      } else {
        it->curves.push_back(k);
        it->tangent = it->tangent || tangent;
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return algebra::compare(a.u, b.u) < 0; });
  Location before = start;
  Real previous = Real::from_rational(0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& candidate = candidates[i];
    // the open stretch before the candidate: a point inside it (the path may run along an
    // edge there)
    Location stretch = locate_point(impl, point_at(algebra::rational_between(previous, candidate.u)));
    if (contact_location(impl, stretch)) {
      result.found = true;
      result.parameter_lower = previous.lower;
      result.parameter_upper = previous.upper;
      result.edge = stretch.edge;
      result.vertex = stretch.vertex;
      result.cell_left = cell_of(before);
      result.cell_entered = no_index;
      return result;
    }
    before = stretch;
    Location after;
    if (candidate.u.compare(Rational(1)) == 0) {
      after = before;
    } else {
      Real next = i + 1 < candidates.size() ? candidates[i + 1].u : Real::from_rational(1);
      after = locate_point(impl, point_at(algebra::rational_between(candidate.u, next)));
    }
    Location at;
    bool at_known = false;
    if (candidate.u.exact) {
      at = locate_point(impl, point_at(candidate.u.lower));
      at_known = true;
    }
    bool crossing = at_known ? contact_location(impl, at)
                             : (cell_of(before) != cell_of(after) || before.kind != after.kind);
    bool grazing = false;
    if (!crossing && !at_known && candidate.tangent) {
      // the path touches a curve: conservative: a touch of a real edge of that curve whose
      // certified box holds the touching point counts
      Real u = candidate.u;
      u.refine_to(Rational(1, mpz_class(1) << 90));
      for (std::size_t e = 0; e < chart.edges.size() && !grazing; ++e) {
        const CSpaceEdge& edge = impl.edges[chart.edges[e].global];
        if (!edge.real) continue;
        bool on_curve = false;
        for (std::size_t k : candidate.curves)
          if (std::find(chart.edges[e].curves.begin(), chart.edges[e].curves.end(), k) != chart.edges[e].curves.end())
            on_curve = true;
        if (!on_curve) continue;
        hipair::ChartPoint lo = point_at(u.lower), hi = point_at(u.upper);
        double x_lo = algebra::lower_double(std::min(lo.x, hi.x)), x_hi = algebra::upper_double(std::max(lo.x, hi.x));
        double y_lo = algebra::lower_double(std::min(lo.y, hi.y)), y_hi = algebra::upper_double(std::max(lo.y, hi.y));
        const raw::Edge& raw_edge = chart.arrangement.edges[e];
        if (x_hi < raw_edge.box[0] || x_lo > raw_edge.box[2] || y_hi < raw_edge.box[1] || y_lo > raw_edge.box[3])
          continue;
        grazing = true;
        result.edge = chart.edges[e].global;
      }
    }
    if (crossing || grazing) {
      result.found = true;
      Real u = candidate.u;
      u.refine_to(Rational(1, mpz_class(1) << 64));
      result.parameter_lower = u.lower;
      result.parameter_upper = u.upper;
      result.grazing = grazing;
      result.cell_left = cell_of(before);
      result.cell_entered = grazing ? cell_of(before) : cell_of(after);
      if (at_known) {
        result.edge = at.edge;
        result.vertex = at.vertex;
      } else if (!grazing) {
        // the real edge of a vanishing curve between the two cells whose box holds the point
        hipair::ChartPoint lo = point_at(u.lower), hi = point_at(u.upper);
        double x_lo = algebra::lower_double(std::min(lo.x, hi.x)), x_hi = algebra::upper_double(std::max(lo.x, hi.x));
        double y_lo = algebra::lower_double(std::min(lo.y, hi.y)), y_hi = algebra::upper_double(std::max(lo.y, hi.y));
        for (std::size_t e = 0; e < chart.edges.size(); ++e) {
          const CSpaceEdge& edge = impl.edges[chart.edges[e].global];
          if (!edge.real) continue;
          bool separates = (edge.left_cell == result.cell_left && edge.right_cell == result.cell_entered) ||
                           (edge.right_cell == result.cell_left && edge.left_cell == result.cell_entered);
          if (!separates) continue;
          const raw::Edge& raw_edge = chart.arrangement.edges[e];
          if (impl.dimension == 2 &&
              (x_hi < raw_edge.box[0] || x_lo > raw_edge.box[2] || y_hi < raw_edge.box[1] || y_lo > raw_edge.box[3]))
            continue;
          result.edge = chart.edges[e].global;
          break;
        }
        if (impl.dimension == 1) {
          // the contact point itself
          for (std::size_t p = 0; p < chart.points.size(); ++p) {
            Real x = candidate.u;   // x = from.x + u dx
            hipair::ChartPoint lo2 = point_at(u.lower), hi2 = point_at(u.upper);
            Rational a = std::min(lo2.x, hi2.x), b = std::max(lo2.x, hi2.x);
            if (chart.points[p].compare(a) >= 0 && chart.points[p].compare(b) <= 0) {
              result.vertex = chart.vertex_global[p];
              break;
            }
          }
        }
      }
      return result;
    }
    before = after;
    previous = candidate.u;
  }
  // the last stretch may run along a real edge
  if (!candidates.empty()) {
    Location stretch = locate_point(impl, point_at(algebra::rational_between(previous, Real::from_rational(1))));
    if (contact_location(impl, stretch)) {
      result.found = true;
      result.parameter_lower = previous.lower;
      result.parameter_upper = previous.upper;
      result.edge = stretch.edge;
      result.cell_left = cell_of(before);
      return result;
    }
  } else {
    Location middle = locate_point(impl, point_at(Rational(1, 2)));
    if (contact_location(impl, middle)) {
      result.found = true;
      result.parameter_lower = 0;
      result.parameter_upper = 0;
      result.edge = middle.edge;
      return result;
    }
  }
  return result;
}

}  // namespace hipair::cspace
