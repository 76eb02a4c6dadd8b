// The polygon front end of translating pairs (CSpaceBuildOptions::polygon_front_end: the
// reduced convolution's pairs by an angular walk, segments written from the vertices, each
// line edge's support carried through CGAL from its input curve, no interval culling
// quadtree for lines with an exact valid point in the chart) against the general path on
// generated pairs: the same curves, and the same C-space field by field (cells, edges,
// vertices, feature pairs, supports); and the blocked region against CGAL's minkowski_sum_2
// exactly. Cases: random rational star polygons (non-convex), with collinear edges (straight
// vertices), scaled by 10^-30 and 10^40 as exact rationals, a zero-clearance slot, shared
// vertex coordinates, and general translation directions.
#include "cspace/builder_impl.hpp"
#include "cspace_minkowski_support.hpp"
#include "cspace_topology_compare.hpp"
#include "curves/contact_curves.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <CGAL/Cartesian.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/minkowski_sum_2.h>

#include "polygon_loop_json.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>

namespace hipair {
namespace {

using namespace minkowski_support;
using test_loops::loop_json;
using test_loops::Points;

Model sliders(const Points& a, const Points& b, const std::string& da = "[1, 0]", const std::string& db = "[0, 1]") {
  return read_model(test_loops::sliders_json(a, b, da, db));
}

// The sliders model, or nullopt when rounding made a polygon degenerate (repeated vertex,
// self-touching): not a case.
std::optional<Model> sliders_or_none(const Points& a, const Points& b) {
  try {
    return sliders(a, b);
  } catch (const ModelError&) {
    return std::nullopt;
  }
}

// A star-shaped polygon of k vertices around (cx, cy) on a 1/q grid; with `collinear`, the
// exact midpoint of some edges is inserted (a straight vertex).
Points random_star(std::mt19937_64& random, int k, double cx, double cy, double radius, long q, bool collinear) {
  Points points = test_loops::grid_star(random, k, cx, cy, radius, q, Rational(1));
  if (!collinear) return points;
  Points with;
  for (std::size_t i = 0; i < points.size(); ++i) {
    with.push_back(points[i]);
    if (random() % 2 == 0) {
      const auto& next = points[(i + 1) % points.size()];
      with.emplace_back(Rational((points[i].first + next.first) / 2), Rational((points[i].second + next.second) / 2));
    }
  }
  return with;
}

Points scaled(Points points, const Rational& factor) {
  for (auto& [x, y] : points) {
    x *= factor;
    y *= factor;
  }
  return points;
}

// A copy of `points` shifted by a random vector of the integer grid (-2..2 in each coordinate,
// dx drawn first): its edges lie on lines of the original's when they are parallel.
Points shifted_on_grid(std::mt19937_64& random, Points points) {
  Rational dx(static_cast<long>(random() % 5) - 2), dy(static_cast<long>(random() % 5) - 2);
  for (auto& [x, y] : points) {
    x += dx;
    y += dy;
  }
  return points;
}

using test_numbers::power_of_ten;

void expect_same_numbers(const AlgebraicNumber& a, const AlgebraicNumber& b) {
  EXPECT_EQ(a.exact, b.exact);
  EXPECT_EQ(a.polynomial, b.polynomial);
  EXPECT_EQ(a.lower, b.lower);
  EXPECT_EQ(a.upper, b.upper);
}

// Field by field, indices included.
void expect_same_space(const CSpace& fast, const CSpace& general) {
  ASSERT_NO_FATAL_FAILURE(hipair::test::expect_same_topology(fast, general, "polygon front end against the general build"));
  for (std::size_t i = 0; i < fast.feature_pairs().size(); ++i)
    EXPECT_EQ(fast.feature_pairs()[i].label, general.feature_pairs()[i].label);
  for (std::size_t i = 0; i < fast.cells().size(); ++i) {
    EXPECT_EQ(fast.cells()[i].sample_x, general.cells()[i].sample_x);
    EXPECT_EQ(fast.cells()[i].sample_y, general.cells()[i].sample_y);
  }
  for (std::size_t i = 0; i < fast.vertices().size(); ++i) {
    const CSpaceVertex &p = fast.vertices()[i], &q = general.vertices()[i];
    expect_same_numbers(p.x, q.x);
    EXPECT_EQ(p.y_exact, q.y_exact);
    expect_same_numbers(p.y, q.y);
    EXPECT_EQ(p.y_curve, q.y_curve);
  }
  const auto& fast_impl = implementation(fast);
  const auto& general_impl = implementation(general);
  ASSERT_EQ(fast_impl.charts.size(), general_impl.charts.size());
  for (std::size_t c = 0; c < fast_impl.charts.size(); ++c) {
    const auto& p = fast_impl.charts[c].arrangement.edges;
    const auto& q = general_impl.charts[c].arrangement.edges;
    ASSERT_EQ(p.size(), q.size());
    for (std::size_t e = 0; e < p.size(); ++e)
      EXPECT_EQ(p[e].support.coefficients, q[e].support.coefficients) << "the support of edge " << e;
  }
  // the builder's own per-chart data (edge samples and labels, face kinds and samples,
  // zero-clearance flags): the point-location data behind the public fields
  for (std::size_t c = 0; c < fast_impl.charts.size(); ++c) {
    const cspace::ChartData& p = fast_impl.charts[c];
    const cspace::ChartData& q = general_impl.charts[c];
    ASSERT_EQ(p.edges.size(), q.edges.size());
    for (std::size_t e = 0; e < p.edges.size(); ++e) {
      SCOPED_TRACE("chart edge " + std::to_string(e));
      EXPECT_EQ(p.edges[e].sample_x, q.edges[e].sample_x);
      expect_same_numbers(cspace::to_public(p.edges[e].sample_y), cspace::to_public(q.edges[e].sample_y));
      ASSERT_EQ(p.edges[e].vertical_x.has_value(), q.edges[e].vertical_x.has_value());
      ASSERT_EQ(p.edges[e].vertical_x.has_value(), fast_impl.charts[c].arrangement.edges[e].vertical);
      if (p.edges[e].vertical_x)
        expect_same_numbers(cspace::to_public(*p.edges[e].vertical_x), cspace::to_public(*q.edges[e].vertical_x));
      EXPECT_EQ(p.edges[e].curves, q.edges[e].curves);
      EXPECT_EQ(p.edges[e].touching, q.edges[e].touching);
    }
    ASSERT_EQ(p.faces.size(), q.faces.size());
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      EXPECT_EQ(p.faces[f].kind, q.faces[f].kind);
      EXPECT_EQ(p.faces[f].cell, q.faces[f].cell);
      EXPECT_EQ(p.faces[f].sampled, q.faces[f].sampled);
      EXPECT_EQ(p.faces[f].sample_x, q.faces[f].sample_x);
      EXPECT_EQ(p.faces[f].sample_y, q.faces[f].sample_y);
    }
    EXPECT_EQ(p.touching_vertex, q.touching_vertex);
    EXPECT_EQ(p.rational_vertex_x, q.rational_vertex_x);
    EXPECT_EQ(p.curve_global, q.curve_global);
  }
  const CSpaceStatistics &s = fast.statistics(), &t = general.statistics();
  EXPECT_EQ(s.feature_pairs_considered, t.feature_pairs_considered);
  EXPECT_EQ(s.feature_pairs_culled, t.feature_pairs_culled);
  EXPECT_EQ(s.curves, t.curves);
  EXPECT_EQ(s.contact_edges, t.contact_edges);
  EXPECT_EQ(s.touching_edges, t.touching_edges);
  EXPECT_EQ(s.touching_vertices, t.touching_vertices);
  EXPECT_EQ(s.faces, t.faces);
}


struct Built {
  CSpace fast, general;
};

Built build_both(const Model& model, bool check = false) {
  CSpaceBuildOptions fast, general;
  fast.check_face_classification = general.check_face_classification = check;
  general.polygon_front_end = false;
  return Built{CSpace::build(model, "a", "b", fast), CSpace::build(model, "a", "b", general)};
}

// The front end's space equals the general path's field by field, and its blocked region equals
// minkowski_sum_2 of the parts.
void expect_front_end_as_general_and_minkowski(const Model& model, const Points& a, const Points& b, bool check) {
  Built built = build_both(model, check);
  expect_same_space(built.fast, built.general);
  expect_minkowski(built.fast, a, b);
}

// Two lists of contact curves equal curve by curve: features, type, polynomial, label, blocked
// side, validity clauses and their atoms, in the same order.
template <class Curves>
void expect_same_curve_lists(const Curves& p, const Curves& q) {
  ASSERT_EQ(p.size(), q.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_EQ(p[k].first, q[k].first);
    EXPECT_EQ(p[k].second, q[k].second);
    EXPECT_EQ(p[k].type, q[k].type);
    EXPECT_EQ(p[k].polynomial.coefficients, q[k].polynomial.coefficients);
    EXPECT_EQ(p[k].label, q[k].label);
    EXPECT_EQ(p[k].blocked_sign, q[k].blocked_sign);
    ASSERT_EQ(p[k].validity.size(), q[k].validity.size());
    for (std::size_t c = 0; c < p[k].validity.size(); ++c) {
      ASSERT_EQ(p[k].validity[c].atoms.size(), q[k].validity[c].atoms.size());
      for (std::size_t i = 0; i < p[k].validity[c].atoms.size(); ++i)
        EXPECT_EQ(p[k].validity[c].atoms[i].coefficients, q[k].validity[c].atoms[i].coefficients);
    }
  }
}

// The generator alone: the same curves (features, type, polynomial, validity, label) in the
// same order, and the same counts.
void expect_same_curves(const Model& model) {
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  cspace::CurveOptions fast, general;
  fast.cull_blocked_space = general.cull_blocked_space = false;
  general.polygon_front_end = false;
  cspace::CurveStatistics fast_stats, general_stats;
  auto p = cspace::CurveGenerator(model, axes, fast).generate(layout.x_charts[0], layout.y_charts[0], &fast_stats);
  auto q = cspace::CurveGenerator(model, axes, general).generate(layout.x_charts[0], layout.y_charts[0], &general_stats);
  expect_same_curve_lists(p, q);
  EXPECT_EQ(fast_stats.feature_pairs_considered, general_stats.feature_pairs_considered);
  EXPECT_EQ(fast_stats.feature_pairs_culled, general_stats.feature_pairs_culled);
  EXPECT_EQ(fast_stats.feature_pairs_in_blocked_space, general_stats.feature_pairs_in_blocked_space);
  EXPECT_EQ(fast_stats.curves, general_stats.curves);
  EXPECT_EQ(fast_stats.identically_zero, general_stats.identically_zero);
}

TEST(CSpacePolygonFrontEnd, RandomNonConvexPolygonsEqualTheGeneralPathAndTheMinkowskiSum) {
  std::mt19937_64 random(4242);
  int compared = 0;
  for (int instance = 0; instance < 30; ++instance) {
    int ka = 3 + static_cast<int>(random() % 9), kb = 3 + static_cast<int>(random() % 9);
    long q = instance % 3 == 0 ? 1 : instance % 3 == 1 ? 8 : 61;
    bool collinear = instance % 2 == 1;
    Points a = random_star(random, ka, 0, 0, 3 + static_cast<double>(random() % 4), q, collinear);
    Points b = random_star(random, kb, static_cast<double>(random() % 7) - 3, static_cast<double>(random() % 7) - 3,
                           2 + static_cast<double>(random() % 5), q, !collinear && instance % 4 == 0);
    // exact scales far from 1 on some instances
    if (instance % 5 == 3) {
      a = scaled(a, power_of_ten(-30));
      b = scaled(b, power_of_ten(-30));
    } else if (instance % 5 == 4) {
      a = scaled(a, power_of_ten(40));
      b = scaled(b, power_of_ten(40));
    }
    SCOPED_TRACE("instance " + std::to_string(instance));
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    const Model& model = *built_model;
    expect_same_curves(model);
    Built built = build_both(model, instance % 3 == 0);
    expect_same_space(built.fast, built.general);
    expect_minkowski(built.fast, a, b);
    ++compared;
  }
  EXPECT_GE(compared, 24);
}

// Zero clearance: a bar exactly as wide as a slot slides in it (a touching channel), and
// parts sharing vertex coordinates.
TEST(CSpacePolygonFrontEnd, ZeroClearanceSlotAndSharedVerticesEqualTheGeneralPath) {
  auto q = [](long n, long d = 1) {
    Rational r(n, d);
    r.canonicalize();
    return r;
  };
  Points slot{{q(0), q(0)}, {q(6), q(0)}, {q(6), q(5)}, {q(4), q(5)}, {q(4), q(1)}, {q(2), q(1)}, {q(2), q(5)}, {q(0), q(5)}};
  Points bar{{q(2), q(7)}, {q(4), q(7)}, {q(4), q(11)}, {q(2), q(11)}};
  Points notch{{q(0), q(0)}, {q(4), q(0)}, {q(4), q(4)}, {q(2), q(2)}, {q(0), q(4)}};
  Points wedge{{q(2), q(2)}, {q(4), q(4)}, {q(0), q(4)}};   // fits the notch exactly
  for (const auto& [a, b] : {std::pair{slot, bar}, std::pair{notch, wedge}, std::pair{bar, slot}}) {
    Model model = sliders(a, b);
    expect_same_curves(model);
    Built built = build_both(model, true);
    expect_same_space(built.fast, built.general);
    expect_minkowski(built.fast, a, b);
  }
  Built slot_built = build_both(sliders(slot, bar));
  EXPECT_GT(slot_built.fast.statistics().touching_edges + slot_built.fast.statistics().touching_vertices, 0u);
}

// Other translation directions (rational, not axis-parallel) and a fixed partner (1-D).
TEST(CSpacePolygonFrontEnd, GeneralDirectionsEqualTheGeneralPath) {
  std::mt19937_64 random(99);
  for (int instance = 0; instance < 8; ++instance) {
    Points a = random_star(random, 4 + static_cast<int>(random() % 6), 0, 0, 3, 4, instance % 2 == 0);
    Points b = random_star(random, 3 + static_cast<int>(random() % 6), 1, -1, 3, 4, false);
    SCOPED_TRACE("instance " + std::to_string(instance));
    Model model;
    try {
      model = sliders(a, b, instance % 2 ? "[3, 4]" : "[1, 2]", instance % 2 ? "[-5, 12]" : "[0, 1]");
    } catch (const ModelError&) {
      continue;
    }
    expect_same_curves(model);
    Built built = build_both(model);
    expect_same_space(built.fast, built.general);
  }
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// An axis-parallel staircase polygon on the integer grid: x from x0 to x0 + w, a floor at y0 and
// a roof of `steps` integer heights (collinear edges and shared coordinates everywhere).
Points random_staircase(std::mt19937_64& random, long x0, long y0, int steps) {
  Points points{{Rational(x0), Rational(y0)}};
  long x = x0;
  std::vector<long> roof;
  for (int i = 0; i < steps; ++i) roof.push_back(y0 + 1 + static_cast<long>(random() % 3));
  points.emplace_back(Rational(x0 + steps), Rational(y0));
  for (int i = steps - 1; i >= 0; --i) {
    long h = roof[static_cast<std::size_t>(i)];
    x = x0 + i + 1;
    if (points.back().second != h) points.emplace_back(Rational(x), Rational(h));
    points.emplace_back(Rational(x - 1), Rational(h));
  }
  return points;
}

// The segment traits (every contact curve of a polygon pair is a segment: the circle–segment
// stage inserts them with Arr_segment_traits_2 on rational points) against the circle–segment
// traits (polygon_front_end = false keeps them), field by field, and CGAL's minkowski_sum_2:
// generated pairs on coarse grids where edges are collinear, vertices coincide and parts touch
// at zero clearance (lattice stars of radius 1–3, staircases, and a part copied and shifted by a
// lattice vector so that its edges lie on the other's).
TEST(CSpacePolygonFrontEnd, SegmentTraitsEqualTheCircleSegmentTraitsOnTouchingCollinearGridPairs) {
  std::mt19937_64 random(20261128);
  int compared = 0;
  for (int instance = 0; instance < 48; ++instance) {
    Points a, b;
    switch (instance % 4) {
      case 0:
        a = random_star(random, 3 + static_cast<int>(random() % 6), 0, 0, 1 + static_cast<double>(random() % 3), 1, false);
        b = random_star(random, 3 + static_cast<int>(random() % 6), static_cast<double>(random() % 5) - 2,
                        static_cast<double>(random() % 5) - 2, 1 + static_cast<double>(random() % 3), 1, instance % 8 == 0);
        break;
      case 1:
        a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 4));
        b = random_staircase(random, static_cast<long>(random() % 5) - 2, static_cast<long>(random() % 5) - 2,
                             1 + static_cast<int>(random() % 4));
        break;
      case 2: {
        a = random_star(random, 4 + static_cast<int>(random() % 5), 0, 0, 2, 2, true);
        b = shifted_on_grid(random, a);
        break;
      }
      default:
        a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 3));
        b = random_star(random, 3 + static_cast<int>(random() % 4), 1, 1, 2, 1, true);
        break;
    }
    SCOPED_TRACE("instance " + std::to_string(instance));
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    const Model& model = *built_model;
    Built built = build_both(model, instance % 3 == 0);
    expect_same_space(built.fast, built.general);
    expect_minkowski(built.fast, a, b);
    ++compared;
  }
  EXPECT_GE(compared, 36);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Exact scales far from 1 (session 13): random stars and touching lattice pairs scaled by
// 10^-100, 10^-60, 10^60 and 10^100 as exact rationals (the segment traits crashed on some
// pairs at 10^150 and above: see the next test); the
// front end (segment traits, input points' rationals taken by handle identity in the export)
// equals the general path (circle–segment traits, every vertex converted from CGAL) field by
// field, and the blocked region equals minkowski_sum_2. Scales the model or the chart layout
// rejects with a clear error (10^400: a reach beyond 1e300 mm) are counted, not built.
TEST(CSpacePolygonFrontEnd, ExtremeScalesEqualTheGeneralPathAndTheMinkowskiSum) {
  std::mt19937_64 random(1313);
  int compared = 0, rejected = 0;
  const int exponents[] = {-100, -60, 60, 100, 400};
  for (int instance = 0; instance < 20; ++instance) {
    Points a, b;
    if (instance % 2 == 0) {
      a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 8, instance % 4 == 0);
      b = random_star(random, 3 + static_cast<int>(random() % 8), static_cast<double>(random() % 5) - 2,
                      static_cast<double>(random() % 5) - 2, 2, 8, false);
    } else {
      a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 3));
      b = random_star(random, 3 + static_cast<int>(random() % 4), 1, 1, 2, 1, true);
    }
    const int exponent = exponents[instance % 5];
    a = scaled(a, power_of_ten(exponent));
    b = scaled(b, power_of_ten(exponent));
    SCOPED_TRACE("instance " + std::to_string(instance) + ", scale 10^" + std::to_string(exponent));
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) {
      ++rejected;
      continue;
    }
    const Model& model = *built_model;
    std::optional<Built> built;
    try {
      built = build_both(model, instance % 3 == 0);
    } catch (const Error&) {
      EXPECT_GE(exponent, 400) << "only scales beyond the doubles may be refused";
      ++rejected;
      continue;
    }
    expect_same_space(built->fast, built->general);
    expect_minkowski(built->fast, a, b);
    ++compared;
  }
  EXPECT_GE(compared, 16);
  EXPECT_LE(rejected, 4);
}

// Beyond the segment traits' filter range (session 13): at 10^150 and above CGAL's
// Arr_segment_traits_2 on Epeck overflowed its interval filter and the sweep crashed (SIGSEGV)
// on these pairs; the front end now takes the circle–segment traits there. Tiny scales stay on
// the segment traits. Every build must succeed and equal the general path and minkowski_sum_2.
TEST(CSpacePolygonFrontEnd, ScalesBeyondTheSegmentFilterBuildTheSameSpace) {
  std::mt19937_64 random(2613);
  int compared = 0;
  const int exponents[] = {-300, -200, 150, 200, 300};
  for (int instance = 0; instance < 10; ++instance) {
    Points a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 8, instance % 4 == 0);
    Points b = random_star(random, 3 + static_cast<int>(random() % 8), static_cast<double>(random() % 5) - 2,
                           static_cast<double>(random() % 5) - 2, 2, 8, false);
    const int exponent = exponents[instance % 5];
    a = scaled(a, power_of_ten(exponent));
    b = scaled(b, power_of_ten(exponent));
    SCOPED_TRACE("instance " + std::to_string(instance) + ", scale 10^" + std::to_string(exponent));
    std::optional<Model> built_model = sliders_or_none(a, b);
    ASSERT_TRUE(built_model.has_value());
    expect_front_end_as_general_and_minkowski(*built_model, a, b, instance % 3 == 0);
    ++compared;
  }
  EXPECT_EQ(compared, 10);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Session 16 (mink3x): the front end labels a line edge from its carried support (no root
// isolation, no vanishing test) and edge_y_at evaluates a line edge in rationals. Reference:
// for every edge of every chart, the sample as the general labelling takes it (rational_between
// of the ends, the root of the support substituted at the abscissa by Sturm isolation) and the
// labels as every chart curve that vanishes at the sample and is valid there (exact algebra,
// over all curves, not only those of the edge's support); edge_y_at at the sample and at other
// rationals inside the edge against the same root isolation. Generated pairs: non-convex
// stars, collinear and touching lattice pairs (a polygon and its shifted copy), staircases with
// collinear steps, and zero-clearance slots.
void expect_reference_labels(const CSpace& space) {
  const auto& impl = implementation(space);
  for (const cspace::ChartData& chart : impl.charts) {
    const auto& arrangement = chart.arrangement;
    ASSERT_EQ(chart.edges.size(), arrangement.edges.size());
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      const cspace::raw::Edge& edge = arrangement.edges[e];
      const cspace::EdgeData& data = chart.edges[e];
      if (edge.vertical) continue;
      SCOPED_TRACE("edge " + std::to_string(e));
      const auto& low = arrangement.vertices[edge.min_vertex];
      const auto& high = arrangement.vertices[edge.max_vertex];
      const Rational x = cspace::algebra::rational_between(low.x, high.x);
      EXPECT_EQ(data.sample_x, x);
      auto reference_y = [&](const Rational& at) {
        return cspace::algebra::nth_real_root_in(cspace::algebra::substitute_x(edge.support, at),
                                                 edge.arc_numbers.between.back(), Rational(edge.box[1]),
                                                 Rational(edge.box[3]));
      };
      const cspace::algebra::Real y = reference_y(x);
      expect_same_numbers(cspace::to_public(data.sample_y), cspace::to_public(y));
      std::vector<std::size_t> labels;
      for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
        if (!cspace::algebra::vanishes_at(chart.polynomials[k], x, y)) continue;
        bool valid = true;
        for (const auto& clause : chart.validity[k]) {
          bool holds = false;
          for (const auto& atom : clause.atoms) holds = holds || cspace::algebra::sign_at(atom, x, y) >= 0;
          valid = valid && holds;
        }
        if (valid) labels.push_back(k);
      }
      EXPECT_EQ(data.curves, labels);
      // edge_y_at at the sample and between it and the ends
      const Rational left = cspace::algebra::rational_between(low.x, cspace::algebra::Real::from_rational(x));
      const Rational right = cspace::algebra::rational_between(cspace::algebra::Real::from_rational(x), high.x);
      for (const Rational& at : {x, left, right})
        expect_same_numbers(cspace::to_public(cspace::edge_y_at(chart, e, at)), cspace::to_public(reference_y(at)));
    }
  }
}

// Generated pairs shared by the label tests (the random numbers drawn in the same order as the
// cases they came from): a star with collinear edges and its copy shifted by a lattice vector
// (collinear and touching edges everywhere); two staircases (collinear steps, shared
// coordinates); a bar exactly as wide as a slot (zero clearance, random widths and depths).
std::pair<Points, Points> shifted_copy_pair(std::mt19937_64& random) {
  Points a = random_star(random, 4 + static_cast<int>(random() % 5), 0, 0, 2, 1, true);
  Points b = a;
  Rational dx(static_cast<long>(random() % 5) - 2), dy(static_cast<long>(random() % 5) - 2);
  for (auto& [x, y] : b) {
    x += dx;
    y += dy;
  }
  return {a, b};
}

std::pair<Points, Points> staircase_pair(std::mt19937_64& random) {
  Points a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 4));
  Points b = random_staircase(random, static_cast<long>(random() % 5) - 2, static_cast<long>(random() % 5) - 2,
                              1 + static_cast<int>(random() % 4));
  return {a, b};
}

std::pair<Points, Points> zero_clearance_slot_pair(std::mt19937_64& random) {
  long w = 1 + static_cast<long>(random() % 3), depth = 1 + static_cast<long>(random() % 4);
  long wall = 1 + static_cast<long>(random() % 2);
  Points a = {{Rational(0), Rational(0)}, {Rational(2 * wall + w), Rational(0)}, {Rational(2 * wall + w), Rational(depth + 1)},
              {Rational(wall + w), Rational(depth + 1)}, {Rational(wall + w), Rational(1)}, {Rational(wall), Rational(1)},
              {Rational(wall), Rational(depth + 1)}, {Rational(0), Rational(depth + 1)}};
  Points b = {{Rational(wall), Rational(depth + 3)}, {Rational(wall + w), Rational(depth + 3)},
              {Rational(wall + w), Rational(depth + 6)}, {Rational(wall), Rational(depth + 6)}};
  return {a, b};
}

// The label tests' touching shapes by number: 1 a polygon and its shifted copy (collinear and
// touching edges everywhere), 2 staircases (collinear steps, shared coordinates), 3 a bar exactly
// as wide as a slot (zero clearance, random widths and depths).
std::pair<Points, Points> touching_case_pair(std::mt19937_64& random, int which) {
  return which == 1 ? shifted_copy_pair(random) : which == 2 ? staircase_pair(random) : zero_clearance_slot_pair(random);
}

TEST(CSpacePolygonFrontEnd, LineEdgeLabelsAndSamplesEqualTheReferenceOnGeneratedPairs) {
  std::mt19937_64 random(16031);
  int checked = 0, collinear_labels = 0;
  for (int instance = 0; instance < 40; ++instance) {
    Points a, b;
    switch (instance % 5) {
      case 0:   // non-convex stars on a coarse grid
        a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 2, instance % 2 == 0);
        b = random_star(random, 3 + static_cast<int>(random() % 8), static_cast<double>(random() % 5) - 2,
                        static_cast<double>(random() % 5) - 2, 2, 2, false);
        break;
      case 1:
      case 2:
      case 3:   // touching_case_pair's shapes
        std::tie(a, b) = touching_case_pair(random, instance % 5);
        break;
      default:   // a staircase against a star with collinear edges
        a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 3));
        b = random_star(random, 3 + static_cast<int>(random() % 4), 1, 1, 2, 1, true);
        break;
    }
    SCOPED_TRACE("instance " + std::to_string(instance));
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    CSpace space = CSpace::build(*built_model, "a", "b");
    expect_reference_labels(space);
    for (const cspace::ChartData& chart : implementation(space).charts)
      for (const cspace::EdgeData& data : chart.edges) collinear_labels += data.curves.size() >= 2;
    if (instance % 5 == 3) {
      Built built = build_both(*built_model, true);
      expect_same_space(built.fast, built.general);
      expect_minkowski(built.fast, a, b);
      EXPECT_GT(built.fast.statistics().touching_edges + built.fast.statistics().touching_vertices, 0u);
    }
    ++checked;
  }
  EXPECT_GE(checked, 32);
  EXPECT_GT(collinear_labels, 0) << "no edge with two collinear contacts: the cases test too little";
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// A convex polygon with vertices on the circle of radius r about (cx, cy) at rational half-angle
// tangents k / q (every vertex its own denominator, as the benchmark's polygons), or its
// reverse order.
Points circle_polygon(std::mt19937_64& random, int n, const Rational& r, const Rational& cx, const Rational& cy,
                      long q) {
  Points points;
  std::vector<long> tangents;
  for (int i = 0; i < n; ++i) {
    double angle = -3.141592653589793 + 2 * 3.141592653589793 * (i + 0.2 + 0.6 * static_cast<double>(random() % 1000) / 1000.0) / n;
    tangents.push_back(std::lround(std::tan(angle / 2) * static_cast<double>(q)));
  }
  for (long k : tangents) {
    Rational t(k, q);
    t.canonicalize();
    Rational d = 1 + t * t;
    points.emplace_back(Rational(cx + r * (1 - t * t) / d), Rational(cy + r * 2 * t / d));
  }
  return points;
}

// The generator of the front end in homogeneous integers against the kernels' general path,
// curve for curve, and the built spaces field by field, on generated pairs that exercise what it
// forms from the integers: vertices with distinct coprime denominators (on circles), a part with
// a hole (the edges of several loops), rational translation directions with denominators,
// parallel edges (constant validity atoms), a fixed part (a 1-D space), and scales 10^-40 and
// 10^40 (several limbs).
TEST(CSpacePolygonFrontEnd, HomogeneousIntegerCurvesEqualTheGeneralPathOnGeneratedPairs) {
  std::mt19937_64 random(20261129);
  auto curves_of = [](const Model& model, bool front_end, cspace::CurveStatistics& stats) {
    cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    cspace::CurveOptions options;
    options.cull_blocked_space = false;
    options.polygon_front_end = front_end;
    cspace::ChartAxis y = layout.y_charts.empty() ? cspace::ChartAxis{} : layout.y_charts[0];
    return cspace::CurveGenerator(model, axes, options).generate(layout.x_charts[0], y, &stats);
  };
  const std::vector<std::pair<std::string, std::string>> directions{
      {"[1, 0]", "[0, 1]"}, {"[\"1/3\", \"2/7\"]", "[\"-5/11\", \"3/4\"]"}, {"[3, 4]", "[\"1/6\", 0]"}, {"fixed", "[0, \"2/3\"]"}};
  int cases = 0, with_constant_atoms = 0;
  for (int instance = 0; instance < 24; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const Rational scale = instance % 6 == 4 ? power_of_ten(-40) : instance % 6 == 5 ? power_of_ten(40) : Rational(1);
    const long q = 8 + static_cast<long>(random() % 40);
    Points outer = scaled(circle_polygon(random, 5 + static_cast<int>(random() % 6), 9, 0, 0, q), scale);
    Points hole = scaled(circle_polygon(random, 3 + static_cast<int>(random() % 5), 5, Rational(1, 3), 0, q + 3), scale);
    Points peg = instance % 3 == 0 ? scaled(Points{{Rational(-1), Rational(-1)}, {Rational(2), Rational(-1)},
                                                   {Rational(2), Rational(1, 2)}, {Rational(-1), Rational(1, 2)}},
                                            scale)
                                   : scaled(circle_polygon(random, 3 + static_cast<int>(random() % 6), Rational(3, 2),
                                                           Rational(1, 2), Rational(-1, 5), q + 7),
                                            scale);
    Points frame_box = scaled(Points{{Rational(-12), Rational(-12)}, {Rational(12), Rational(-12)},
                                     {Rational(12), Rational(12)}, {Rational(-12), Rational(12)}},
                              scale);
    const auto& [da, db] = directions[static_cast<std::size_t>(instance) % directions.size()];
    auto motion = [](const std::string& d) {
      return d == "fixed" ? std::string("\"fixed\"") : "{ \"translation\": { \"direction\": " + d + " } }";
    };
    // the frame: a square or a circle polygon with a polygonal hole; the peg inside the hole
    const bool square_frame = instance % 2 == 0;
    std::string text = R"({ "hipair": 1, "name": "frame", "parts": [
      { "name": "a", "motion": )" + motion(da) + R"(, "loops": [ )" +
                       loop_json(square_frame ? frame_box : outer) + ", " + loop_json(hole) + R"( ] },
      { "name": "b", "motion": )" + motion(db) + R"(, "loops": [ )" + loop_json(peg) + R"( ] } ] })";
    Model model;
    try {
      model = read_model(text);
    } catch (const ModelError&) {
      continue;   // rounding made a polygon degenerate: not a case
    }
    ++cases;
    cspace::CurveStatistics fast_stats, general_stats;
    auto p = curves_of(model, true, fast_stats);
    auto g = curves_of(model, false, general_stats);
    ASSERT_FALSE(p.empty());
    expect_same_curve_lists(p, g);
    for (const auto& curve : p) with_constant_atoms += curve.validity.size() < 2;
    EXPECT_EQ(fast_stats.curves, general_stats.curves);
    EXPECT_EQ(fast_stats.feature_pairs_considered, general_stats.feature_pairs_considered);
    EXPECT_EQ(fast_stats.feature_pairs_in_blocked_space, general_stats.feature_pairs_in_blocked_space);
    if (instance % 4 == 1 && scale == 1) {   // the whole space on some (the 2-D ones)
      Built built = build_both(model);
      expect_same_space(built.fast, built.general);
    }
  }
  EXPECT_GE(cases, 16);
  // a part moving perpendicular to edges (the 1-D cases): some curves keep fewer than two clauses
  EXPECT_GT(with_constant_atoms, 0);
}

// Session 20 (mink20): two cuts of the front end's fixed cost, each against an independent
// reference on generated pairs. (1) The supports of chart-side pieces are written from the box
// (no exact conversion of CGAL's lazy line): every arrangement edge on a chart side that carries
// no input curve is compared with the primitive integer form, sign kept, of the exact rational
// line (a, b, c) through the side's segment corner i -> corner i + 1 (the segment the builder
// inserts), and the whole space with the general path's (circle–segment traits, supports from
// CGAL's exact lines). (2) Feature labels are made only for kept curves (feature_label): every
// feature pair's label is compared with the former part_features text, written out here
// (edge labels or "loop l edge e"; a vertex is "corner of P and E", or "corner of E" when the
// previous edge has the same name), on parts with labelled loops, labelled edges and unnamed
// edges.
TEST(CSpacePolygonFrontEnd, ChartSideSupportsAndLazyLabelsEqualTheirReferencesOnGeneratedPairs) {
  std::mt19937_64 random(2020);
  // a loop's JSON with, by `style`, no labels (0), a loop label (1) or labels on some edges (2)
  auto labelled_loop = [&](const Points& points, int style, const std::string& prefix) {
    auto value = [](const Rational& q) { return "\"" + q.get_str() + "\""; };
    std::string text = "{ \"start\": [" + value(points[0].first) + ", " + value(points[0].second) + "], ";
    if (style == 1) text += "\"label\": \"" + prefix + " rim\", ";
    text += "\"edges\": [";
    for (std::size_t i = 1; i <= points.size(); ++i) {
      const auto& p = points[i % points.size()];
      text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + value(p.first) + ", " + value(p.second) + "]";
      if (style == 2 && i % 3 != 0) text += ", \"label\": \"" + prefix + " side " + std::to_string(i % 2) + "\"";
      text += " }";
    }
    return text + "] }";
  };
  // the former part_features label of a feature
  auto edge_name = [](const Edge& edge, std::size_t loop, std::size_t index) {
    return edge.label.empty() ? "loop " + std::to_string(loop) + " edge " + std::to_string(index) : edge.label;
  };
  auto reference_label = [&](const Model& model, const FeatureIdentity& id) {
    const Loop& loop = model.parts.at(id.part).loops.at(id.loop);
    const std::size_t n = loop.edges.size();
    std::string name = edge_name(loop.edges.at(id.edge), id.loop, id.edge);
    if (id.kind != FeatureKind::vertex) return name;
    std::string previous = edge_name(loop.edges[(id.edge + n - 1) % n], id.loop, (id.edge + n - 1) % n);
    return previous == name ? "corner of " + name : "corner of " + previous + " and " + name;
  };
  int compared = 0, side_edges = 0, corners_of_two = 0, corners_of_one = 0;
  for (int instance = 0; instance < 24; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    int ka = 3 + static_cast<int>(random() % 8), kb = 3 + static_cast<int>(random() % 8);
    long q = instance % 2 == 0 ? 4 : 37;
    Points a = random_star(random, ka, 0, 0, 2 + static_cast<double>(random() % 4), q, instance % 3 == 1);
    Points b = random_star(random, kb, static_cast<double>(random() % 9) - 4, static_cast<double>(random() % 9) - 4,
                           1 + static_cast<double>(random() % 4), q, instance % 3 == 2);
    if (instance % 4 == 3) {
      a = scaled(a, power_of_ten(-20));
      b = scaled(b, power_of_ten(-20));
    }
    std::optional<Model> built_model;
    try {
      built_model = read_model(R"({ "hipair": 1, "name": "sliders", "parts": [
        { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ )" +
                               labelled_loop(a, instance % 3, "a") + R"( ] },
        { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [ )" +
                               labelled_loop(b, (instance + 1) % 3, "b") + R"( ] } ] })");
    } catch (const ModelError&) {
      continue;   // rounding made a polygon degenerate: not a case
    }
    const Model& model = *built_model;
    Built built = build_both(model);
    expect_same_space(built.fast, built.general);
    expect_minkowski(built.fast, a, b);
    // (1) chart sides
    for (const cspace::ChartData& chart : implementation(built.fast).charts) {
      const cspace::raw::Box& box = chart.box;
      const Point2 corners[4] = {Point2(gmpq(box.x_lo), gmpq(box.y_lo)), Point2(gmpq(box.x_hi), gmpq(box.y_lo)),
                                 Point2(gmpq(box.x_hi), gmpq(box.y_hi)), Point2(gmpq(box.x_lo), gmpq(box.y_hi))};
      for (const cspace::raw::Edge& edge : chart.arrangement.edges) {
        if (edge.support_curve != cspace::raw::none) continue;   // an input line's piece
        const cspace::raw::Vertex& u = chart.arrangement.vertices.at(edge.min_vertex);
        const cspace::raw::Vertex& w = chart.arrangement.vertices.at(edge.max_vertex);
        auto on = [](const cspace::raw::Vertex& v, bool x, const Rational& value) {
          return (x ? v.x : v.y).compare(value) == 0;
        };
        int side = on(u, false, box.y_lo) && on(w, false, box.y_lo)   ? 0
                   : on(u, true, box.x_hi) && on(w, true, box.x_hi)   ? 1
                   : on(u, false, box.y_hi) && on(w, false, box.y_hi) ? 2
                   : on(u, true, box.x_lo) && on(w, true, box.x_lo)   ? 3
                                                                      : -1;
        ASSERT_GE(side, 0) << "an edge without an input line off the chart's sides";
        const Kernel::Line_2 line(corners[side], corners[(side + 1) % 4]);
        // (c + b y + a x) times the lcm of the denominators, divided by the content (> 0)
        std::vector<Rational> abc{Rational(line.c().mpq()), Rational(line.b().mpq()), Rational(line.a().mpq())};
        mpz_class lcm = 1, content = 0;
        for (const Rational& r : abc) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), r.get_den_mpz_t());
        std::vector<mpz_class> z;
        for (const Rational& r : abc) {
          z.push_back(r.get_num() * (lcm / r.get_den()));
          mpz_gcd(content.get_mpz_t(), content.get_mpz_t(), z.back().get_mpz_t());
        }
        for (auto& v : z) v /= content;
        const std::vector<std::vector<mpz_class>> expected{{z[0], z[1]}, {z[2], mpz_class(0)}};
        EXPECT_EQ(edge.support.coefficients, expected) << "chart side " << side;
        EXPECT_EQ(edge.box_side, side);
        ++side_edges;
      }
    }
    // (2) labels
    for (const FeaturePair& pair : built.fast.feature_pairs()) {
      const std::string expected = "a " + reference_label(model, pair.first) + " / b " + reference_label(model, pair.second) + " (";
      EXPECT_EQ(pair.label.substr(0, expected.size()), expected);
      for (const FeatureIdentity* id : {&pair.first, &pair.second})
        if (id->kind == FeatureKind::vertex)
          ++(reference_label(model, *id).find(" and ") != std::string::npos ? corners_of_two : corners_of_one);
    }
    ++compared;
  }
  EXPECT_GE(compared, 18);
  EXPECT_GE(side_edges, 4 * compared);
  EXPECT_GT(corners_of_two, 0);
  EXPECT_GT(corners_of_one, 0);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Session 36 (trans36): label_edges groups the curves by support in one sorted key buffer
// (no hash map of strings), reads an exact sample coordinate in place (no refined copy), and
// the segment stage gives each known point's rationals to its vertex. Reference, independent
// of all three: at every edge's sample point, vertical edges included, the labels are every
// chart curve (all of them, not only the edge's support group) that vanishes there and whose
// every validity clause has an atom >= 0 there, evaluated in rationals term by term; the
// sample lies strictly inside the edge; every vertex's coordinates are exact, canonical and
// their polynomial is den t - num. Both paths (front end: supports carried, groups by curve;
// general: every edge's support looked up by key), on generated pairs: stars with collinear
// edges, a polygon and its shifted copy (touching and collinear everywhere), staircases
// (vertical contact edges), zero-clearance slots, and scales 10^-300 and 10^300 (beyond the
// segment filter: the circle–segment stage's export).
Rational evaluate_exactly(const cspace::IntegerPolynomial2& f, const Rational& x, const Rational& y) {
  Rational sum(0), x_power(1);
  for (const auto& row : f.coefficients) {
    Rational term(0), y_power(1);
    for (const auto& c : row) {
      term += Rational(c) * y_power;
      y_power *= y;
    }
    sum += term * x_power;
    x_power *= x;
  }
  return sum;
}

struct LabelCounts {
  int edges = 0, vertical_labelled = 0, shared = 0, looked_up = 0;
};

void expect_labels_by_rational_reference(const CSpace& space, LabelCounts& counts) {
  for (const cspace::ChartData& chart : implementation(space).charts) {
    const auto& arrangement = chart.arrangement;
    ASSERT_EQ(chart.edges.size(), arrangement.edges.size());
    for (const cspace::raw::Vertex& v : arrangement.vertices)
      for (const cspace::algebra::Real* r : {&v.x, &v.y}) {
        ASSERT_TRUE(r->exact);
        ASSERT_EQ(r->lower, r->upper);
        Rational canonical = r->lower;
        canonical.canonicalize();
        EXPECT_EQ(canonical.get_num(), r->lower.get_num());
        EXPECT_EQ(canonical.get_den(), r->lower.get_den());
        ASSERT_EQ(r->polynomial.size(), 2u);
        EXPECT_EQ(r->polynomial[0], -r->lower.get_num());
        EXPECT_EQ(r->polynomial[1], r->lower.get_den());
      }
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      SCOPED_TRACE("edge " + std::to_string(e));
      const cspace::raw::Edge& edge = arrangement.edges[e];
      const cspace::EdgeData& data = chart.edges[e];
      const auto& low = arrangement.vertices[edge.min_vertex];
      const auto& high = arrangement.vertices[edge.max_vertex];
      ASSERT_TRUE(data.sample_y.exact);
      const Rational x = edge.vertical ? low.x.lower : data.sample_x;
      const Rational y = data.sample_y.lower;
      if (edge.vertical) {
        EXPECT_EQ(high.x.lower, x);
        EXPECT_TRUE(low.y.lower < y && y < high.y.lower);
      } else {
        EXPECT_TRUE(low.x.lower < x && x < high.x.lower);
      }
      std::vector<std::size_t> labels;
      for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
        if (sgn(evaluate_exactly(chart.polynomials[k], x, y)) != 0) continue;
        bool valid = true;
        for (const auto& clause : chart.validity[k]) {
          bool holds = false;
          for (const auto& atom : clause.atoms) holds = holds || sgn(evaluate_exactly(atom, x, y)) >= 0;
          valid = valid && holds;
        }
        if (valid) labels.push_back(k);
      }
      EXPECT_EQ(data.curves, labels);
      ++counts.edges;
      counts.vertical_labelled += edge.vertical && !labels.empty();
      counts.shared += labels.size() >= 2;
      counts.looked_up += edge.support_curve == cspace::raw::none && !labels.empty();
    }
  }
}

TEST(CSpacePolygonFrontEnd, SupportGroupsAndInPlaceSamplesLabelAsTheRationalReferenceOnGeneratedPairs) {
  std::mt19937_64 random(36036);
  LabelCounts counts;
  int built = 0, scaled_cases = 0;
  for (int instance = 0; instance < 36; ++instance) {
    Points a, b;
    switch (instance % 6) {
      case 0:
        a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 2, true);
        b = random_star(random, 3 + static_cast<int>(random() % 6), static_cast<double>(random() % 5) - 2,
                        static_cast<double>(random() % 5) - 2, 2, 2, true);
        break;
      case 1:
      case 2:
      case 3:
        std::tie(a, b) = touching_case_pair(random, instance % 6);
        break;
      default: {   // a staircase and a star with collinear edges, at 10^-300 or 10^300
        a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 3));
        b = random_star(random, 3 + static_cast<int>(random() % 4), 1, 1, 2, 1, true);
        const Rational factor = power_of_ten(instance % 12 == 4 ? -300 : 300);
        a = scaled(a, factor);
        b = scaled(b, factor);
        ++scaled_cases;
        break;
      }
    }
    SCOPED_TRACE("instance " + std::to_string(instance));
    std::optional<Model> model = sliders_or_none(a, b);
    if (!model) continue;
    Built both = build_both(*model);
    expect_labels_by_rational_reference(both.fast, counts);
    expect_labels_by_rational_reference(both.general, counts);
    expect_same_space(both.fast, both.general);
    ++built;
  }
  EXPECT_GE(built, 30);
  EXPECT_GE(scaled_cases, 10);
  EXPECT_GT(counts.vertical_labelled, 20) << "too few vertical contact edges";
  EXPECT_GT(counts.shared, 10) << "too few edges with collinear contacts (a support group of two or more)";
  EXPECT_GT(counts.looked_up, 50) << "too few labelled edges whose support is looked up by key";
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// The segment stage's input points take their exact values only when CGAL's kernel asks for
// them (a filter that fails on a degenerate predicate, an intersection point's exact
// coordinates; session 37), read from the stage's own rationals, and are found again by value
// through one probing table. Generated pairs on non-dyadic grids (1/3, 1/7, 1/9, 1/11: no
// coordinate is a double, so collinear and touching configurations defeat the interval
// filters) with straight vertices, a part and its copy shifted by a grid vector (edges on
// edges everywhere), and both scaled by 10^-300, 10^-30, 10^30 and 10^300 on some instances:
// the front end (segment traits, deferred exact values) equals the general path
// (circle–segment traits, every kernel number exact from the start) field by field, and the
// blocked region equals minkowski_sum_2.
TEST(CSpacePolygonFrontEnd, DeferredExactPointsEqualTheCircleSegmentTraitsOnNonDyadicTouchingPairs) {
  std::mt19937_64 random(370037);
  const long grids[] = {3, 7, 9, 11};
  const int exponents[] = {0, -300, -30, 30, 300};
  int compared = 0;
  for (int instance = 0; instance < 30; ++instance) {
    const long q = grids[instance % 4];
    Points a = random_star(random, 3 + static_cast<int>(random() % 5), 0, 0, 2, q, true);
    Points b;
    if (instance % 3 == 0) {
      b = random_star(random, 3 + static_cast<int>(random() % 5), static_cast<double>(random() % 3) - 1, 1, 2, q, true);
    } else {
      // a shifted copy: every edge of b lies on a parallel edge of a for some translation
      Rational dx(static_cast<long>(random() % 7) - 3, q), dy(static_cast<long>(random() % 7) - 3, q);
      dx.canonicalize();
      dy.canonicalize();
      b = a;
      for (auto& [x, y] : b) {
        x += dx;
        y += dy;
      }
    }
    const int exponent = instance % 6 == 5 ? exponents[1 + (instance / 6) % 4] : 0;
    if (exponent != 0) {
      a = scaled(a, power_of_ten(exponent));
      b = scaled(b, power_of_ten(exponent));
    }
    SCOPED_TRACE("instance " + std::to_string(instance) + ", grid 1/" + std::to_string(q) + ", scale 10^" +
                 std::to_string(exponent));
    std::optional<Model> model = sliders_or_none(a, b);
    if (!model) continue;
    expect_front_end_as_general_and_minkowski(*model, a, b, instance % 4 == 0);
    ++compared;
  }
  EXPECT_GE(compared, 24);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Session 40 (trans40): the segment flavour's `vertical` read from the edge's ends' exact
// abscissae (not from CGAL's lazily constructed supporting line, whose interval filter throws
// when an end's ordinate is not a point), and label_edges' exact samples of vertical and front-end
// edges written in place. Generated pairs with axis-parallel edges on non-dyadic grids (1/3, 1/7,
// 5/7: no coordinate is a double, so CGAL's interval filter is uncertain on them) — staircases,
// stars with collinear vertices, and a part copied and shifted by a grid vector so that its edges
// lie on the other's (zero clearance) — at scales 2^-300, 1 and 2^300: field by field against the
// general path (circle–segment traits, whose vertical flag is CGAL's is_vertical and whose
// samples are made as before), the blocked region against CGAL's minkowski_sum_2, and every chart
// edge against exact arithmetic: vertical exactly when its ends' abscissae are equal
// (algebra::compare), a vertical edge's sample exact, on the edge's abscissa and strictly between
// its ends' ordinates, a non-vertical edge's sample strictly between its ends' abscissae.
TEST(CSpacePolygonFrontEnd, NonDyadicAxisParallelPairsAtScales2ToThe300EqualTheGeneralPathAndTheMinkowskiSum) {
  std::mt19937_64 random(40);
  const Rational grids[] = {Rational(1, 3), Rational(1, 7), Rational(5, 7)};
  const mpz_class two_300 = mpz_class(1) << 300;
  const Rational scales[] = {Rational(mpz_class(1), two_300), Rational(1), Rational(two_300)};
  int compared = 0, vertical_edges = 0, non_vertical_edges = 0;
  for (int instance = 0; instance < 27; ++instance) {
    // a staircase against a staircase, its own shifted copy (zero clearance), or a star
    Points a = random_staircase(random, 0, 0, 2 + static_cast<int>(random() % 3)), b;
    if (instance % 3 == 1) {
      b = shifted_on_grid(random, a);
    } else if (instance % 3 == 0) {
      const long x0 = static_cast<long>(random() % 5) - 2, y0 = static_cast<long>(random() % 5) - 2;
      b = random_staircase(random, x0, y0, 1 + static_cast<int>(random() % 3));
    } else {
      b = random_star(random, 3 + static_cast<int>(random() % 4), 1, 1, 2, 1, true);
    }
    const Rational factor = grids[(instance / 3) % 3] * scales[instance / 9];
    a = scaled(a, factor);
    b = scaled(b, factor);
    SCOPED_TRACE("instance " + std::to_string(instance) + ", factor " + factor.get_str());
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    Built built = build_both(*built_model, instance % 4 == 0);
    expect_same_space(built.fast, built.general);
    expect_minkowski(built.fast, a, b);
    for (const cspace::ChartData& chart : implementation(built.fast).charts) {
      ASSERT_EQ(chart.edges.size(), chart.arrangement.edges.size());
      for (std::size_t e = 0; e < chart.edges.size(); ++e) {
        SCOPED_TRACE("chart edge " + std::to_string(e));
        const cspace::raw::Edge& edge = chart.arrangement.edges[e];
        const cspace::raw::Vertex& low = chart.arrangement.vertices[edge.min_vertex];
        const cspace::raw::Vertex& high = chart.arrangement.vertices[edge.max_vertex];
        const cspace::EdgeData& data = chart.edges[e];
        EXPECT_EQ(edge.vertical, cspace::algebra::compare(low.x, high.x) == 0);
        if (edge.vertical) {
          ++vertical_edges;
          ASSERT_TRUE(data.vertical_x.has_value());
          EXPECT_EQ(cspace::algebra::compare(*data.vertical_x, low.x), 0);
          EXPECT_TRUE(data.sample_y.exact);
          EXPECT_EQ(data.sample_y.lower, data.sample_y.upper);
          EXPECT_EQ(data.sample_y.polynomial, cspace::algebra::Real::from_rational(data.sample_y.lower).polynomial);
          ASSERT_TRUE(low.y_exact && high.y_exact);
          EXPECT_LT(cspace::algebra::compare(low.y, data.sample_y), 0);
          EXPECT_LT(cspace::algebra::compare(data.sample_y, high.y), 0);
        } else {
          ++non_vertical_edges;
          EXPECT_LT(low.x.compare(data.sample_x), 0);
          EXPECT_GT(high.x.compare(data.sample_x), 0);
          if (data.sample_y.exact) {
            EXPECT_EQ(data.sample_y.lower, data.sample_y.upper);
            EXPECT_EQ(data.sample_y.polynomial, cspace::algebra::Real::from_rational(data.sample_y.lower).polynomial);
          }
        }
      }
    }
    ++compared;
  }
  EXPECT_GE(compared, 24);
  EXPECT_GE(vertical_edges, 100);
  EXPECT_GE(non_vertical_edges, 100);
}

// Session 42 (trans42): the front end's segment directions are primitive integer vectors whose
// angular order (cone_pairs) is decided by a double filter with an exact integer fallback.
// Directions of 60 to 90 bits, the second part's edges nearly parallel to the first's (their
// cross product a few units against products of ~2^150: the filter cannot decide) or exactly
// parallel: the front end's curves equal the general path's (exact rational tangents), the
// space equals it field by field, and the blocked region equals minkowski_sum_2.
TEST(CSpacePolygonFrontEnd, WideNearlyParallelDirectionsEqualTheGeneralPathAndTheMinkowskiSum) {
  std::mt19937_64 random(4201);
  auto big = [&](int bits) {   // a random integer of exactly `bits` bits
    mpz_class z = 1;
    for (int i = 1; i < bits; ++i) z = 2 * z + static_cast<long>(random() % 2);
    return z;
  };
  int compared = 0;
  for (int instance = 0; instance < 24; ++instance) {
    const int bits = 60 + static_cast<int>(random() % 31);
    const mpz_class n = mpz_class(1) << bits;
    // u, v counter-clockwise (u along x-ish, v along y-ish), coordinates about 1
    mpz_class ux = n + big(bits - 2), uy = big(bits - 3), vx = big(bits - 3), vy = n + big(bits - 2);
    if (instance % 2 == 1) uy = -uy;
    auto at = [&](const mpz_class& x, const mpz_class& y) {
      Rational px(x, n), py(y, n);
      px.canonicalize();
      py.canonicalize();
      return std::make_pair(px, py);
    };
    Points a;
    a.push_back(at(0, 0));
    a.push_back(at(ux, uy));
    if (instance % 3 == 2) a.push_back(at(ux + vx, uy + vy));   // a parallelogram
    a.push_back(at(vx, vy));
    // b: a turned half a turn about a centre (its edges antiparallel to a's, so parallel to
    // those of -b in the sum), each vertex moved by a few units of 1 / (n 2^k) on some instances
    // (nearly parallel) and not on others (exactly parallel)
    const mpz_class centre_x = 3 * n, centre_y = 2 * n;
    const long unit = instance % 4 == 0 ? 0 : 1;
    const mpz_class fine = mpz_class(1) << (2 + static_cast<int>(random() % 12));
    Points b;
    for (const auto& [x, y] : a) {
      Rational bx = Rational(centre_x, n) - x, by = Rational(centre_y, n) - y;
      bx.canonicalize();
      by.canonicalize();
      Rational dx(mpz_class(unit * (static_cast<long>(random() % 7) - 3)), n * fine);
      Rational dy(mpz_class(unit * (static_cast<long>(random() % 7) - 3)), n * fine);
      dx.canonicalize();
      dy.canonicalize();
      b.emplace_back(Rational(bx + dx), Rational(by + dy));
    }
    SCOPED_TRACE("instance " + std::to_string(instance) + ", " + std::to_string(bits) + " bits");
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    expect_same_curves(*built_model);
    expect_front_end_as_general_and_minkowski(*built_model, a, b, instance % 3 == 0);
    ++compared;
  }
  EXPECT_GE(compared, 20);
}


// Session 59 (hunt59): the machine-integer paths of session 58 (algebra/small_integers.hpp:
// front_contact, the contact lines' clip, valid_point_in_box and the labels' line signs read an
// integer only below 2^62 and check every product for overflow) at their limits. Small lattice
// stars placed far out: every vertex times a factor (2^e + odd) / odd' and moved by an offset
// near 2^e' (e, e' from 50 to 66), so that the homogeneous integers the front end reads lie just
// below and just above 2^62, the edge directions stay small (their products with the coordinates
// near 2^127 fit or overflow by little) or are large too. Oracles: the general path (GMP rationals
// throughout, field by field) and CGAL's minkowski_sum_2 of the parts (exact). The integers'
// sizes are counted so that both sides of 2^62 are met.
TEST(CSpacePolygonFrontEnd, CoordinatesAcrossTheMachineIntegerLimitsEqualTheGeneralPathAndTheMinkowskiSum) {
  std::mt19937_64 random(5962);
  auto near_power = [&](int e) {   // 2^e plus or minus a small odd number
    const mpz_class odd = 2 * static_cast<long>(random() % 50) + 1;
    return random() % 2 ? mpz_class((mpz_class(1) << e) + odd) : mpz_class((mpz_class(1) << e) - odd);
  };
  // the largest homogeneous integer (numerators over the point's common denominator) in bits
  auto largest_bits = [](const Points& points) {
    std::size_t bits = 0;
    for (const auto& [x, y] : points) {
      mpz_class w;
      mpz_lcm(w.get_mpz_t(), x.get_den_mpz_t(), y.get_den_mpz_t());
      for (const mpz_class& v : {mpz_class(w), mpz_class(x.get_num() * (w / x.get_den())), mpz_class(y.get_num() * (w / y.get_den()))})
        bits = std::max(bits, mpz_sizeinbase(v.get_mpz_t(), 2));
    }
    return bits;
  };
  int compared = 0, below = 0, above = 0;
  for (int instance = 0; instance < 18; ++instance) {
    Points a = random_star(random, 3 + static_cast<int>(random() % 6), 0, 0, 3, instance % 3 == 0 ? 1 : 4, instance % 4 == 1);
    Points b = random_star(random, 3 + static_cast<int>(random() % 6), static_cast<double>(random() % 5) - 2,
                           static_cast<double>(random() % 5) - 2, 2, instance % 3 == 2 ? 3 : 1, false);
    const int e = 50 + static_cast<int>(random() % 17);
    Rational factor(instance % 2 == 0 ? near_power(e - 10) : mpz_class(1), mpz_class(2 * static_cast<long>(random() % 4) + 1));
    factor.canonicalize();
    const Rational offset_x(near_power(e)), offset_y(random() % 2 ? near_power(e - 1) : mpz_class(-near_power(e)));
    a = test_loops::moved(scaled(a, factor), offset_x, offset_y);
    b = test_loops::moved(scaled(b, factor), random() % 3 == 0 ? offset_x + 5 : offset_x, offset_y);
    const std::size_t bits = std::max(largest_bits(a), largest_bits(b));
    SCOPED_TRACE("instance " + std::to_string(instance) + ", integers of " + std::to_string(bits) + " bits");
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    expect_same_curves(*built_model);
    expect_front_end_as_general_and_minkowski(*built_model, a, b, instance % 3 == 0);
    (bits <= 62 ? below : above) += 1;
    ++compared;
  }
  EXPECT_GE(compared, 16);
  EXPECT_GE(below, 4);
  EXPECT_GE(above, 4);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Session 73 (poly73): a line edge between rational abscissae without a carried support (the
// chart's bottom and top sides on the front end; every line edge on the general path) is sampled
// in rationals in place (label_edges' line_sample), and edge_y_at decides its certified-box
// check from the root's double enclosure when that enclosure lies strictly inside the box. Both
// against the reference (expect_reference_labels: rational_between of the ends, the support's
// root by Sturm isolation at the sample and at two more rationals, the labels by exact algebra
// over every chart curve), on both paths, at scales 10^-300 ... 10^400 (10^400 may be refused,
// nothing else); the two paths field by field and the blocked region against minkowski_sum_2.
// Cases: convex and non-convex stars (collinear edges), a star and its lattice-shifted copy
// (collinear, touching), staircases (collinear steps), zero-clearance slots (zero-area overlaps).
TEST(CSpacePolygonFrontEnd, UncarriedLineEdgeSamplesEqualTheReferenceOnBothPathsAtScales) {
  const std::uint64_t seed = test::test_seed(7373);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  const int exponents[] = {-300, -30, 0, 40, 300, 400};
  int compared = 0, refused = 0;
  std::size_t chart_sides = 0, general_lines = 0;
  for (int instance = 0; instance < 30; ++instance) {
    Points a, b;
    switch (instance % 5) {
      case 0:   // convex against non-convex
        a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 8, instance % 2 == 0);
        b = circle_polygon(random, 3 + static_cast<int>(random() % 6), Rational(2), Rational(static_cast<long>(random() % 5) - 2),
                           Rational(static_cast<long>(random() % 5) - 2), 16);
        break;
      case 1:
      case 2:
      case 3:
        std::tie(a, b) = touching_case_pair(random, instance % 5);
        break;
      default:
        a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3, 97, false);
        b = random_star(random, 3 + static_cast<int>(random() % 8), static_cast<double>(random() % 5) - 2,
                        static_cast<double>(random() % 5) - 2, 2, 16, true);
        break;
    }
    const int exponent = exponents[instance % 6];
    a = scaled(a, power_of_ten(exponent));
    b = scaled(b, power_of_ten(exponent));
    SCOPED_TRACE("instance " + std::to_string(instance) + ", scale 10^" + std::to_string(exponent));
    std::optional<Model> built_model = sliders_or_none(a, b);
    if (!built_model) continue;
    std::optional<Built> built;
    try {
      built = build_both(*built_model, instance % 4 == 0);
    } catch (const Error&) {
      EXPECT_GE(exponent, 400) << "only scales beyond the doubles may be refused";
      ++refused;
      continue;
    }
    ASSERT_NO_FATAL_FAILURE(expect_reference_labels(built->fast));
    ASSERT_NO_FATAL_FAILURE(expect_reference_labels(built->general));
    expect_same_space(built->fast, built->general);
    expect_minkowski(built->fast, a, b);
    // the edges that take the new branch (exact ends, a line support, no carried curve)
    auto uncarried = [](const CSpace& space, bool sides) {
      std::size_t n = 0;
      for (const cspace::ChartData& chart : implementation(space).charts)
        for (const cspace::raw::Edge& edge : chart.arrangement.edges) {
          const auto& low = chart.arrangement.vertices[edge.min_vertex];
          const auto& high = chart.arrangement.vertices[edge.max_vertex];
          if (edge.vertical || edge.support_curve != cspace::raw::none || !low.x.exact || !high.x.exact) continue;
          if (!sides || edge.box_side == 0 || edge.box_side == 2) ++n;
        }
      return n;
    };
    chart_sides += uncarried(built->fast, true);
    general_lines += uncarried(built->general, false) - uncarried(built->general, true);
    ++compared;
  }
  RecordProperty("compared", compared);
  RecordProperty("chart_sides", static_cast<int>(chart_sides));
  RecordProperty("general_lines", static_cast<int>(general_lines));
  EXPECT_GE(compared, 20);
  EXPECT_LE(refused, 5);
  EXPECT_GE(chart_sides, 40u) << "too few chart sides sampled by the new branch";
  EXPECT_GE(general_lines, 200u) << "too few contact line edges sampled by the new branch on the general path";
}

}  // namespace
}  // namespace hipair
