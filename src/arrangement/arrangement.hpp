// The one CGAL stage of the C-space builder: a chart's contact curves, clipped to the chart
// box, inserted into a CGAL::Arrangement_2 with Arr_algebraic_segment_traits_2<Gmpz>, and the
// resulting topology exported as plain exact data (no CGAL types here). Everything after this
// stage (labelling, classification, cells, point location, path queries) is CGAL-free.
#pragma once

#include "algebra/exact_real.hpp"
#include "curves/contact_curves.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace hipair::cspace::raw {

inline constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

/// The chart box in chart coordinates.
struct Box {
  Rational x_lo, x_hi, y_lo, y_hi;
};

/// Direction in which an edge leaves a vertex.
enum class Direction { up, right, down, left };

/// One edge around a vertex, in clockwise order.
struct Incidence {
  std::size_t edge = none;
  Direction direction = Direction::right;
  std::size_t wedge_face = none;   ///< face between this edge and the next one clockwise
};

/// The direction in which an edge leaves a vertex, from the edge's halfedge that ends at the
/// vertex: down or up along a vertical edge, else left or right (`source_is_smaller`: the
/// halfedge runs from the edge's smaller end, so the edge leaves the vertex towards it).
inline Direction leaving_direction(bool vertical, bool source_is_smaller) {
  if (vertical) return source_is_smaller ? Direction::down : Direction::up;
  return source_is_smaller ? Direction::left : Direction::right;
}

/// Which wedge around a vertex contains the ray straight down (`below`) or straight up from it:
/// the face after the incidence at which the clockwise sweep from that reference direction wraps
/// around; `none` when the ray runs along an edge. `incidences` are the vertex's, clockwise.
/// `clockwise_before(a, b, side)` decides the order of incidences a and b that both leave on
/// `side` (Direction::right: the upper curve first; Direction::left: the lower curve first) with
/// the stage's exact comparison of the curves beside the vertex; every other order is fixed by
/// the directions. One definition for the arrangement stages (algebraic, quadratic and
/// circle-segment traits).
template <class ClockwiseBefore>
std::size_t wedge_around(const std::vector<Incidence>& incidences, bool below, ClockwiseBefore&& clockwise_before) {
  const std::size_t n = incidences.size();
  const Direction reference = below ? Direction::down : Direction::up;
  for (const auto& incidence : incidences)
    if (incidence.direction == reference) return none;   // the ray runs along an edge
  if (n == 1) return incidences[0].wedge_face;
  auto key = [&](Direction d) {   // clockwise from the reference
    if (below) return d == Direction::left ? 1 : d == Direction::up ? 2 : 3;
    return d == Direction::right ? 1 : d == Direction::down ? 2 : 3;
  };
  // is the angle of a before the angle of b (clockwise from the reference)?
  auto before = [&](std::size_t a, std::size_t b) {
    const Direction da = incidences[a].direction, db = incidences[b].direction;
    if (da != db) return key(da) < key(db);
    return clockwise_before(a, b, da);
  };
  for (std::size_t i = 0; i < n; ++i)
    if (!before(i, (i + 1) % n)) return incidences[i].wedge_face;   // the sweep wraps past the reference
  throw GeometryError("internal: no wedge contains the vertical direction at a vertex");
}

/// A vertex. Its x is an exact algebraic number. Its y is the `y_branch`-th (0-based,
/// ascending) distinct real root of y_curve(x, y) in y: exact; as an algebraic number `y`
/// only when x is rational (then y_exact), and always bounded by the certified rational
/// interval [y_lower, y_upper], which isolates it among the roots of y_curve(x, .).
struct Vertex {
  algebra::Real x;
  algebra::Real y;
  bool y_exact = false;
  Rational y_lower, y_upper;
  IntegerPolynomial2 y_curve;
  int y_branch = 0;
  double y_lower_bound() const { return algebra::lower_double(y_lower); }
  double y_upper_bound() const { return algebra::upper_double(y_upper); }
  bool isolated = false;
  std::vector<Incidence> around;       ///< clockwise
  std::size_t face_below = none;       ///< face containing the points straight below (none if a vertical edge goes down)
  std::size_t face_above = none;
};

/// Where an edge's support curve has its fiber events inside the edge's x-range, and the
/// arc number (index among the distinct real roots of support(x, y) in y, ascending) of the
/// edge between and at those events: the exact evaluation y(x) at a rational x.
struct ArcNumbers {
  std::vector<algebra::Real> events;     ///< ascending, strictly inside the x-range
  std::vector<int> between;              ///< events.size() + 1 entries
  std::vector<int> at_event;             ///< events.size() entries
};

struct Edge {
  std::size_t min_vertex = none;   ///< lexicographically smaller end (left, or bottom if vertical)
  std::size_t max_vertex = none;
  bool vertical = false;
  IntegerPolynomial2 support;      ///< polynomial of the CGAL supporting curve
  std::size_t left_face = none;    ///< left of min -> max (above for a non-vertical edge)
  std::size_t right_face = none;
  double box[4] = {0, 0, 0, 0};    ///< certified x_min, y_min, x_max, y_max (the edge is monotone
                                   ///< in x and y: the box of its ends)
  ArcNumbers arc_numbers;          ///< non-vertical edges
  int box_side = -1;               ///< on the chart box: 0 bottom, 1 right, 2 top, 3 left
  std::vector<std::size_t> source_curves;   ///< curves whose pieces were inserted along it (hint)
  /// Circle–segment stage: an input line curve whose piece lies along the edge (so `support`
  /// is that curve up to a non-zero factor), carried through CGAL as curve data; none when
  /// the edge is a chart side or an arc.
  std::size_t support_curve = none;
};

struct Face {
  bool unbounded = false;
  std::vector<std::pair<std::size_t, bool>> boundary;   ///< (edge, face is on the edge's left side),
                                                        ///< connected boundary components in turn,
                                                        ///< each in order with the face on the left
  std::vector<std::size_t> component_starts;            ///< index in `boundary` of each component
  std::vector<std::size_t> isolated_vertices;
};

/// The boundary of face `f` of a CGAL arrangement into `out`: its outer boundary (when it has
/// one), then each hole's, each component in the arrangement's order with the fictitious
/// halfedges left out, `component_starts` marking where each begins. `edge_of(h)` and
/// `forward_of(h)` give the export's edge of a halfedge and whether the halfedge runs from the
/// edge's min vertex to its max (the algebraic and the quadratic stages' export).
template <class ArrangementFace, class EdgeOf, class ForwardOf>
void export_face_boundary(const ArrangementFace& f, Face& out, EdgeOf&& edge_of, ForwardOf&& forward_of) {
  auto add_ccb = [&](auto c) {
    out.component_starts.push_back(out.boundary.size());
    auto first = c;
    do {
      if (!c->is_fictitious()) out.boundary.emplace_back(edge_of(c), forward_of(c));
    } while (++c != first);
  };
  if (f.has_outer_ccb()) add_ccb(f.outer_ccb());
  for (auto inner = f.inner_ccbs_begin(); inner != f.inner_ccbs_end(); ++inner) add_ccb(*inner);
}

struct StageTimes {
  double curves_seconds = 0;        ///< curve analysis + x-monotone split + clipping
  double insertion_seconds = 0;
  double export_seconds = 0;
};

struct Arrangement {
  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Face> faces;
  std::size_t unbounded_face = none;
  StageTimes times;
  std::size_t pieces_inserted = 0;
  std::shared_ptr<void> cgal;   ///< the CGAL arrangement when kept (see include/hipair/cgal/)
};

struct Options {
  bool aggregated_insertion = false;   ///< CGAL::insert(arr, begin, end) instead of one by one
  bool keep_cgal = false;
  /// Circle–segment stage: a line edge's support from its input curve (Edge::support_curve)
  /// instead of CGAL's lazy line (the same polynomial; false for tests of the general path).
  bool carry_line_supports = true;
  /// Quadratic stage: declines curves with a coefficient of more bits (CSpaceBuildOptions).
  std::size_t quadratic_max_coefficient_bits = 1024;
  /// Quadratic stage, optional (one entry per curve, empty = no restriction; the other stages
  /// ignore it): boxes {x_lo, x_hi, y_lo, y_hi} (closed, doubles) outside which the curve
  /// certainly bounds nothing — the culling's surviving cells, whose x-ranges are the curve's
  /// windows. A piece of a branch between two cuts is not inserted when its certified y
  /// enclosure meets none of its group's boxes (see clip_common.hpp, branch_meets_cells).
  const std::vector<std::vector<std::array<double, 4>>>* cells = nullptr;
};

/// Real::from_rational(value), the same fields (polynomial {-num, den}, lower = upper = value,
/// exact), formed directly when the rational is canonical (den > 0, gcd(num, den) = 1: then that
/// is already the primitive polynomial with a positive leading coefficient) instead of through
/// primitive_part's copies; from_rational otherwise.
algebra::Real exact_real(const Rational& value);
/// exact_real(value) written into r, reusing the storage of r's rationals and polynomial and
/// taking value's integers for r.lower (for a Real already made, e.g. a default one in a vector:
/// no second Real made and moved over it).
void exact_real_into(algebra::Real& r, Rational&& value);

/// Builds the arrangement of the curves (each square-free, non-zero) clipped to the box and,
/// when `validity` is not empty (one entry per curve, possibly empty), to the parts of each
/// curve where its validity clauses hold.
/// \throws GeometryError when CGAL rejects the input.
/// `windows` (one entry per curve, possibly empty = no restriction): x-intervals outside
/// which the curve is not inserted (it certainly bounds nothing there).
Arrangement build_arrangement(const Box& box, const std::vector<IntegerPolynomial2>& curves,
                              const std::vector<std::vector<ValidityClause>>& validity,
                              const std::vector<std::vector<std::pair<Rational, Rational>>>& windows,
                              const Options& options);

}  // namespace hipair::cspace::raw
