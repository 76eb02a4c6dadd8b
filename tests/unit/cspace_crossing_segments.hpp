// Generated motion segments for the first_crossing filters' side-by-side tests (a switch on
// against off): random segments, segments ending exactly on a contact curve, tangent to one,
// through a vertex, and across a chart seam (an angle passing +-pi, t -> -1/t), on the example
// spaces and the degenerate ones.
#pragma once

#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair::test {

// The spaces the segments run on: the example spaces (the first `examples`) and the degenerate
// models' built pairs.
inline std::vector<std::unique_ptr<CSpace>> crossing_test_spaces(std::size_t& examples) {
  std::vector<std::unique_ptr<CSpace>> spaces = example_spaces();
  examples = spaces.size();
  for (test::NamedSpace& named : test::degenerate_spaces()) spaces.push_back(std::move(named.space));
  return spaces;
}

enum class SegmentKind { random, onto_curve, tangent, vertex, seam };
inline constexpr int segment_kinds = 5;

inline const char* segment_name(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::random: return "random";
    case SegmentKind::onto_curve: return "ending on a curve";
    case SegmentKind::tangent: return "tangent to a curve";
    case SegmentKind::vertex: return "through a vertex";
    case SegmentKind::seam: return "across a seam";
  }
  return "?";
}

// A motion segment of the kind asked on `space` (chart values (x0, y0) -> (x1, y1), a cubic in u
// with a random bend, or straight), described in `what`. False where that kind cannot be made
// there (no real edge, no vertex, no rotating axis).
inline bool crossing_segment(const CSpace& space, SegmentKind kind, std::mt19937_64& random, MotionPath& path,
                             std::string& what) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const bool two = space.dimension() == 2;
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> edges = real_edges(space);
  std::size_t c = random() % charts.size();
  double x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
  double y0 = two ? charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random) : 0;
  double x1 = x0, y1 = y0;
  double bend = random() % 2 == 0 ? 0.0 : 0.3 * sym(random);
  switch (kind) {
    case SegmentKind::random: {
      int k = 0;
      std::size_t chart = 0;
      path = random_motion(space, random, k, chart);
      what = std::string(segment_name(kind)) + " (kind " + std::to_string(k) + ", chart " + std::to_string(chart) + ")";
      return true;
    }
    case SegmentKind::onto_curve: {
      // from anywhere in the edge's chart straight to a point of the edge (its double ordinate:
      // on the curve or within an ulp of it), ending there
      if (edges.empty()) return false;
      std::size_t e = edges[random() % edges.size()];
      if (!onto_edge(space, e, random, c, x1, y1)) return false;
      x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
      y0 = two ? charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random) : 0;
      if (!two) x1 = space.edges()[e].x_chart.lower;
      break;
    }
    case SegmentKind::tangent: {
      // from a point of the edge moved a few ulps (or 1e-15 ... 1e-3) off it, along the edge's
      // chord to a nearby point of it: grazing, sliding along, or crossing at a shallow angle
      if (edges.empty() || !two) return false;
      std::size_t e = edges[random() % edges.size()];
      double xa = 0, ya = 0;
      if (!onto_edge(space, e, random, c, xa, ya)) return false;
      const CSpaceEdge& edge = space.edges()[e];
      double step = (edge.x_chart.upper - edge.x_chart.lower) * std::pow(10.0, -6 + 5 * unit(random)) * (random() % 2 ? 1 : -1);
      double xb = std::min(edge.x_chart.upper, std::max(edge.x_chart.lower, xa + step)), yb = 0;
      try {
        yb = space.evaluate(e, xb).value;
      } catch (const GeometryError&) {
        return false;
      }
      x0 = xa;
      y0 = ya;
      move_off(random() % 2 == 0 ? y0 : x0, random);
      x1 = x0 + (xb - xa);
      y1 = y0 + (yb - ya);
      bend = 0;
      break;
    }
    case SegmentKind::vertex: {
      // from anywhere in the vertex's chart through the vertex (its doubles) and past it
      const std::vector<CSpaceVertex>& vertices = space.vertices();
      if (vertices.empty()) return false;
      const CSpaceVertex& v = vertices[random() % vertices.size()];
      c = v.chart;
      double xv = (v.x.lower.get_d() + v.x.upper.get_d()) / 2;
      double yv = two ? (v.y_lower.get_d() + v.y_upper.get_d()) / 2 : 0;
      x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
      y0 = two ? charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random) : 0;
      double past = random() % 3 == 0 ? 1.0 : 1 + 0.5 * unit(random);
      x1 = x0 + (xv - x0) * past;
      y1 = y0 + (yv - y0) * past;
      bend = 0;
      break;
    }
    case SegmentKind::seam: {
      // a rotating axis through its half-turn seam (the angle across +-pi, t -> -1/t), the
      // other axis anywhere
      bool x_turns = charts[c].x_kind == AxisKind::rotation;
      bool y_turns = two && charts[c].y_kind == AxisKind::rotation;
      if (!x_turns && !y_turns) return false;
      bool on_x = x_turns && (!y_turns || random() % 2 == 0);
      double qx0 = part_value(charts[c].x_kind, charts[c].x_half_turn, x0);
      double qy0 = two ? part_value(charts[c].y_kind, charts[c].y_half_turn, y0) : 0;
      double qx1 = qx0 + sym(random) * 0.01, qy1 = two ? qy0 + sym(random) * 0.01 : 0;
      double width = std::pow(10.0, -6 + 5.5 * unit(random));
      double from = std::numbers::pi - width * unit(random), to = from + width * (1 + unit(random));
      if (random() % 2 == 0) std::swap(from, to);
      if (random() % 4 == 0) to = std::numbers::pi;   // ending on the seam (at pi's double)
      (on_x ? qx0 : qy0) = from;
      (on_x ? qx1 : qy1) = to;
      path = bent_motion(charts[c], two, qx0, qy0, qx1 - qx0, qy1 - qy0, bend, false);
      std::ostringstream out;
      out.precision(17);
      out << segment_name(kind) << " on " << (on_x ? "x" : "y") << " from " << qx0 << ", " << qy0 << " to " << qx1 << ", "
          << qy1 << " bend " << bend;
      what = out.str();
      return true;
    }
  }
  const CSpaceChart& chart = charts[c];
  double qx0 = part_value(chart.x_kind, chart.x_half_turn, x0), qx1 = part_value(chart.x_kind, chart.x_half_turn, x1);
  double qy0 = two ? part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
  double qy1 = two ? part_value(chart.y_kind, chart.y_half_turn, y1) : 0;
  path = bent_motion(chart, two, qx0, qy0, qx1 - qx0, qy1 - qy0, bend, false);
  std::ostringstream out;
  out.precision(17);
  out << segment_name(kind) << " chart " << c << " from " << x0 << ", " << y0 << " to " << x1 << ", " << y1 << " bend "
      << bend;
  what = out.str();
  return true;
}

}  // namespace hipair::test
