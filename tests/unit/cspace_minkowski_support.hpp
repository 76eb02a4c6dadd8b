// The exact blocked region of a built translating (or sliced) C-space as a CGAL polygon set, for
// the tests that compare it with CGAL's minkowski_sum_2 (cspace_minkowski_test,
// sliced_minkowski_test, cspace_polygon_front_end_test). Includes CGAL: only for those units.
#pragma once

#include "cspace/builder_impl.hpp"

#include <hipair/cspace.hpp>

#include <CGAL/Cartesian.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/minkowski_sum_2.h>

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace hipair::minkowski_support {

using Kernel = CGAL::Cartesian<CGAL::Gmpq>;
using Point2 = Kernel::Point_2;
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet = CGAL::Polygon_set_2<Kernel>;

inline CGAL::Gmpq gmpq(const Rational& r) { return CGAL::Gmpq(r.get_mpq_t()); }

// A vertex of a polygonal C-space: both coordinates are rational.
inline Point2 vertex_point(const cspace::raw::Vertex& v) {
  EXPECT_TRUE(v.x.exact);
  EXPECT_TRUE(v.y_exact && v.y.exact);
  return Point2(gmpq(v.x.lower), gmpq(v.y.lower));
}

// The union of the blocked faces of every chart, exactly.
inline PolygonSet blocked_region(const CSpace& space) {
  PolygonSet region;
  for (const auto& chart : implementation(space).charts) {
    const auto& arrangement = chart.arrangement;
    for (std::size_t f = 0; f < arrangement.faces.size(); ++f) {
      if (chart.faces[f].kind != cspace::FaceKind::blocked) continue;
      const auto& face = arrangement.faces[f];
      std::vector<Polygon> components;
      for (std::size_t k = 0; k < face.component_starts.size(); ++k) {
        std::size_t begin = face.component_starts[k];
        std::size_t end = k + 1 < face.component_starts.size() ? face.component_starts[k + 1] : face.boundary.size();
        // cancel antennas (an edge walked out and back)
        std::vector<std::pair<std::size_t, bool>> walk;
        for (std::size_t i = begin; i < end; ++i) {
          if (!walk.empty() && walk.back().first == face.boundary[i].first && walk.back().second != face.boundary[i].second)
            walk.pop_back();
          else
            walk.push_back(face.boundary[i]);
        }
        while (walk.size() >= 2 && walk.front().first == walk.back().first && walk.front().second != walk.back().second) {
          walk.pop_back();
          walk.erase(walk.begin());
        }
        Polygon polygon;
        for (const auto& [e, forward] : walk) {
          const auto& edge = arrangement.edges[e];
          polygon.push_back(vertex_point(arrangement.vertices[forward ? edge.min_vertex : edge.max_vertex]));
        }
        if (polygon.size() >= 3) components.push_back(polygon);
      }
      if (components.empty()) continue;
      PolygonWithHoles piece(components[0]);
      for (std::size_t k = 1; k < components.size(); ++k) piece.add_hole(components[k]);
      region.join(piece);
    }
  }
  return region;
}

using Points = std::vector<std::pair<Rational, Rational>>;

// The polygon of `points` times `scale` (negated: the reflection -P), counter-clockwise.
inline Polygon cgal_polygon(const Points& points, const Rational& scale, bool negate) {
  Polygon p;
  for (const auto& [x, y] : points) {
    Rational px = x * scale, py = y * scale;
    if (negate) {
      px = -px;
      py = -py;
    }
    p.push_back(Point2(gmpq(px), gmpq(py)));
  }
  if (p.is_clockwise_oriented()) p.reverse_orientation();
  return p;
}

// Part a (points `a` times scale) along x by u, part b along y by v: blocked iff
// u e_x - v e_y lies in the interior of B + (-A); the space's blocked faces must equal it exactly.
inline void expect_minkowski(const CSpace& space, const Points& a, const Points& b, const Rational& scale = Rational(1)) {
  PolygonWithHoles sum = CGAL::minkowski_sum_2(cgal_polygon(b, scale, false), cgal_polygon(a, scale, true));
  auto reflect = [](const Polygon& polygon) {
    Polygon out;
    for (auto it = polygon.vertices_begin(); it != polygon.vertices_end(); ++it) out.push_back(Point2(it->x(), -it->y()));
    out.reverse_orientation();
    return out;
  };
  PolygonWithHoles expected(reflect(sum.outer_boundary()));
  for (auto hole = sum.holes_begin(); hole != sum.holes_end(); ++hole) expected.add_hole(reflect(*hole));
  PolygonSet difference = blocked_region(space);
  EXPECT_FALSE(difference.is_empty());
  difference.symmetric_difference(expected);
  EXPECT_TRUE(difference.is_empty()) << "blocked faces differ from the Minkowski sum";
}

}  // namespace hipair::minkowski_support
