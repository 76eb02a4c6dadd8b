#include "render/mechanism_svg.hpp"

#include "io/svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hipair::render {
namespace {

const char* const palette[] = {"#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1",
                               "#edc948", "#76b7b2", "#ff9da7", "#9c755f"};
const char* const outline[] = {"#27405a", "#8a4a0c", "#2d5a27", "#7d2223", "#5e3a57",
                               "#7a6113", "#335c58", "#8a4a52", "#4e3a2e"};

struct Box {
  double min_x = std::numeric_limits<double>::infinity();
  double min_y = std::numeric_limits<double>::infinity();
  double max_x = -std::numeric_limits<double>::infinity();
  double max_y = -std::numeric_limits<double>::infinity();
  void add(double x, double y) {
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
  bool valid() const { return min_x <= max_x; }
};

double to_number(const Rational& q) { return q.get_d(); }

std::string motion_name(const Motion& motion) {
  switch (motion.kind) {
    case Motion::Kind::fixed: return "fixed";
    case Motion::Kind::rotation: return "rotation";
    case Motion::Kind::translation: return "translation";
    case Motion::Kind::planar: return "planar";
    case Motion::Kind::pin_slot: return "pin-slot";
  }
  return "";
}

std::string angle_text(const Rational& angle, const std::string& unit) {
  double value = to_number(angle);
  if (unit == "deg") return io::format_number(value * 180 / M_PI) + "\u00b0";
  return io::format_number(value) + " rad";
}

std::string configuration_text(const Part& part, const PartConfiguration& c,
                               const std::string& unit) {
  switch (part.motion.kind) {
    case Motion::Kind::fixed: return "fixed";
    case Motion::Kind::rotation: return "rotation, \u03b8 = " + angle_text(c.angle, unit);
    case Motion::Kind::translation:
      return "translation, s = " + io::format_number(to_number(c.offset)) + " mm";
    case Motion::Kind::planar:
      return "planar, x = " + io::format_number(to_number(c.x)) +
             ", y = " + io::format_number(to_number(c.y)) + ", \u03b8 = " + angle_text(c.angle, unit);
    case Motion::Kind::pin_slot:
      return "pin-slot, \u03b8 = " + angle_text(c.angle, unit) +
             ", s = " + io::format_number(to_number(c.offset)) + " mm";
  }
  return "";
}

// Midpoint of an edge at the part's configuration, for its label.
PosedPoint edge_middle(const Part& part, const PartConfiguration& c, const Edge& edge) {
  double sx = to_number(edge.source.x), sy = to_number(edge.source.y);
  double tx = to_number(edge.target.x), ty = to_number(edge.target.y);
  if (!edge.is_arc()) return pose_point(part.motion, c, (sx + tx) / 2, (sy + ty) / 2);
  double cx = to_number(edge.center.x), cy = to_number(edge.center.y);
  double radius = std::hypot(sx - cx, sy - cy);
  double start = std::atan2(sy - cy, sx - cx);
  double end = std::atan2(ty - cy, tx - cx);
  double span = edge.is_full_circle() ? 2 * M_PI : (edge.ccw ? end - start : start - end);
  span = std::fmod(span, 2 * M_PI);
  if (span <= 0) span += 2 * M_PI;
  double middle = start + (edge.ccw ? span / 2 : -span / 2);
  return pose_point(part.motion, c, cx + radius * std::cos(middle), cy + radius * std::sin(middle));
}

}  // namespace

PosedPoint pose_point(const Motion& motion, const PartConfiguration& c, double x, double y) {
  double px = to_number(motion.pivot.x), py = to_number(motion.pivot.y);
  auto rotate_about_pivot = [&](double angle) {
    double dx = x - px, dy = y - py;
    double cs = std::cos(angle), sn = std::sin(angle);
    return PosedPoint{px + cs * dx - sn * dy, py + sn * dx + cs * dy};
  };
  switch (motion.kind) {
    case Motion::Kind::fixed: return PosedPoint{x, y};
    case Motion::Kind::rotation: return rotate_about_pivot(to_number(c.angle));
    case Motion::Kind::translation: {
      double s = to_number(c.offset);
      return PosedPoint{x + s * to_number(motion.direction.x),
                        y + s * to_number(motion.direction.y)};
    }
    case Motion::Kind::planar: {
      PosedPoint p = rotate_about_pivot(to_number(c.angle));
      return PosedPoint{p.x + to_number(c.x), p.y + to_number(c.y)};
    }
    case Motion::Kind::pin_slot: {
      double angle = to_number(c.angle);
      PosedPoint p = rotate_about_pivot(angle);
      double dx = to_number(motion.direction.x), dy = to_number(motion.direction.y);
      double cs = std::cos(angle), sn = std::sin(angle), s = to_number(c.offset);
      return PosedPoint{p.x + s * (cs * dx - sn * dy), p.y + s * (sn * dx + cs * dy)};
    }
  }
  return PosedPoint{x, y};
}

std::string mechanism_svg(const Model& model, const std::vector<PartConfiguration>& configurations,
                          const MechanismSvgOptions& options) {
  if (configurations.size() != model.parts.size())
    throw Error("mechanism_svg: " + std::to_string(configurations.size()) +
                " configurations for " + std::to_string(model.parts.size()) + " parts");

  // Paths of every part at its configuration, and the drawing's extent.
  std::vector<io::SvgPath> paths(model.parts.size());
  std::vector<Box> part_boxes(model.parts.size());
  Box extent;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    const PartConfiguration& c = configurations[i];
    for (const Loop& loop : part.loops) {
      if (loop.edges.empty()) continue;
      PosedPoint start = pose_point(part.motion, c, to_number(loop.edges.front().source.x),
                                    to_number(loop.edges.front().source.y));
      paths[i].move_to(start.x, start.y);
      for (const Edge& edge : loop.edges) {
        PosedPoint target =
            pose_point(part.motion, c, to_number(edge.target.x), to_number(edge.target.y));
        if (edge.is_arc()) {
          PosedPoint centre =
              pose_point(part.motion, c, to_number(edge.center.x), to_number(edge.center.y));
          paths[i].arc_to(target.x, target.y, centre.x, centre.y, edge.ccw);
        } else {
          paths[i].line_to(target.x, target.y);
        }
      }
      paths[i].close();
    }
    for (const auto& [x, y] : paths[i].extent_points()) {
      part_boxes[i].add(x, y);
      extent.add(x, y);
    }
    if (part.motion.kind != Motion::Kind::fixed && part.motion.kind != Motion::Kind::translation) {
      PosedPoint pivot = pose_point(part.motion, c, to_number(part.motion.pivot.x),
                                    to_number(part.motion.pivot.y));
      extent.add(pivot.x, pivot.y);
    }
  }
  if (!extent.valid()) extent.add(0, 0), extent.add(1, 1);
  double size = std::max({extent.max_x - extent.min_x, extent.max_y - extent.min_y, 1e-6});
  double text_size = size / 40;
  double margin = size * 0.08;

  // Legend rows: one per part.
  std::vector<io::SvgWriter::LegendEntry> legend;
  std::size_t longest = 0;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    io::SvgStyle swatch;
    bool fixed = part.motion.kind == Motion::Kind::fixed;
    swatch.fill = fixed ? "url(#hatch)" : palette[i % 9];
    swatch.stroke = fixed ? "#555555" : outline[i % 9];
    std::string label =
        part.name + " (" + configuration_text(part, configurations[i], model.angle_unit) + ")";
    longest = std::max(longest, label.size());
    legend.push_back({swatch, label});
  }
  double legend_width =
      options.legend ? text_size * (2.2 + 0.62 * static_cast<double>(longest)) + margin : 0;

  io::SvgBox box;
  box.min_x = extent.min_x - margin;
  box.max_x = extent.max_x + margin + legend_width;
  box.min_y = extent.min_y - margin - text_size * 3;
  box.max_y = extent.max_y + margin + text_size * 2.5;
  io::SvgWriter svg(box, options.pixel_width);
  svg.set_default_stroke_width(size / 500);
  svg.define_hatch("hatch", "#8c8c8c", text_size * 0.6);
  svg.define_arrow("arrow", "#333333");
  svg.rectangle(box.min_x, box.min_y, box.width(), box.height(),
                io::SvgStyle{"white", "", 0, "", "", 1, ""});

  std::string title = options.title.empty() ? model.name : options.title;
  svg.text(extent.min_x, box.max_y - text_size * 1.6, title, text_size * 1.2, "start", "black",
           "bold");

  // Fixed parts first (underneath), then moving ones.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < model.parts.size(); ++i) {
      const Part& part = model.parts[i];
      bool fixed = part.motion.kind == Motion::Kind::fixed;
      if ((pass == 0) != fixed) continue;
      io::SvgStyle style;
      style.fill = fixed ? "url(#hatch)" : palette[i % 9];
      style.stroke = fixed ? "#555555" : outline[i % 9];
      style.fill_rule = "evenodd";
      style.opacity = fixed ? 1 : 0.8;
      svg.begin_group("part-" + part.name, "part", part.name);
      svg.path(paths[i], style, part.name);
      svg.end_group();
    }
  }

  // Motion marks: pivots and translation axes.
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    const PartConfiguration& c = configurations[i];
    const Motion& motion = part.motion;
    io::SvgStyle mark;
    mark.stroke = "#111111";
    mark.stroke_width = size / 700;
    if (motion.kind == Motion::Kind::rotation || motion.kind == Motion::Kind::planar ||
        motion.kind == Motion::Kind::pin_slot) {
      PosedPoint pivot =
          pose_point(motion, c, to_number(motion.pivot.x), to_number(motion.pivot.y));
      double r = text_size * 0.45;
      io::SvgStyle ring = mark;
      ring.fill = "white";
      svg.circle(pivot.x, pivot.y, r, ring);
      svg.line(pivot.x - r * 1.6, pivot.y, pivot.x + r * 1.6, pivot.y, mark);
      svg.line(pivot.x, pivot.y - r * 1.6, pivot.x, pivot.y + r * 1.6, mark);
    }
    if ((motion.kind == Motion::Kind::translation || motion.kind == Motion::Kind::pin_slot) &&
        part_boxes[i].valid()) {
      double dx = to_number(motion.direction.x), dy = to_number(motion.direction.y);
      if (motion.kind == Motion::Kind::pin_slot) {
        double angle = to_number(c.angle);
        double rx = std::cos(angle) * dx - std::sin(angle) * dy;
        double ry = std::sin(angle) * dx + std::cos(angle) * dy;
        dx = rx;
        dy = ry;
      }
      const Box& b = part_boxes[i];
      double cx = (b.min_x + b.max_x) / 2, cy = (b.min_y + b.max_y) / 2;
      double length = std::max(b.max_x - b.min_x, b.max_y - b.min_y) * 0.35 + text_size;
      io::SvgStyle arrow = mark;
      arrow.dash = io::format_number(text_size * 0.4) + " " + io::format_number(text_size * 0.25);
      arrow.marker_end = "url(#arrow)";
      svg.line(cx, cy, cx + dx * length, cy + dy * length, arrow);
      svg.line(cx, cy, cx - dx * length, cy - dy * length, arrow);
    }
  }

  // Names: beside each part where they cover the fewest other parts and names.
  std::vector<Box> placed;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    if (!part_boxes[i].valid()) continue;
    const Box& b = part_boxes[i];
    double width = text_size * 0.62 * static_cast<double>(part.name.size());
    double gap = text_size * 0.4;
    double mid_x = (b.min_x + b.max_x) / 2, mid_y = (b.min_y + b.max_y) / 2;
    // Candidate baselines (x is the text's centre): above, below, right, left, inside top.
    const double candidates[][2] = {{mid_x, b.max_y + gap},
                                    {mid_x, b.min_y - gap - text_size},
                                    {b.max_x + gap + width / 2, mid_y - text_size / 2},
                                    {b.min_x - gap - width / 2, mid_y - text_size / 2},
                                    {mid_x, b.max_y - gap - text_size}};
    double best_cost = std::numeric_limits<double>::infinity();
    Box best_box;
    double best_x = mid_x, best_y = b.max_y + gap;
    for (const auto& candidate : candidates) {
      Box label;
      label.add(candidate[0] - width / 2, candidate[1] - text_size * 0.25);
      label.add(candidate[0] + width / 2, candidate[1] + text_size * 0.9);
      auto overlap = [&](const Box& other) {
        double w = std::min(label.max_x, other.max_x) - std::max(label.min_x, other.min_x);
        double h = std::min(label.max_y, other.max_y) - std::max(label.min_y, other.min_y);
        return w > 0 && h > 0 ? w * h : 0.0;
      };
      double cost = 0;
      for (std::size_t j = 0; j < part_boxes.size(); ++j)
        if (j != i && part_boxes[j].valid()) cost += overlap(part_boxes[j]);
      for (const Box& other : placed) cost += 4 * overlap(other);
      double outside = (label.max_x - label.min_x) * (label.max_y - label.min_y);
      Box frame;
      frame.add(box.min_x, box.min_y);
      frame.add(extent.max_x + margin, box.max_y - text_size * 2.5);
      outside -= overlap(frame);
      cost += 10 * outside;
      if (cost < best_cost - 1e-12) {
        best_cost = cost;
        best_box = label;
        best_x = candidate[0];
        best_y = candidate[1];
      }
    }
    placed.push_back(best_box);
    svg.text(best_x, best_y, part.name, text_size, "middle", "#111111", "bold");
  }

  // Feature labels on request.
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    if (!part_boxes[i].valid()) continue;
    if (!options.labels) continue;
    svg.begin_group("labels-" + part.name, "labels");
    for (const Loop& loop : part.loops)
      for (const Edge& edge : loop.edges) {
        if (edge.label.empty()) continue;
        PosedPoint m = edge_middle(part, configurations[i], edge);
        svg.text(m.x, m.y, edge.label, text_size * 0.4, "middle", "#202020");
      }
    svg.end_group();
  }

  double bar = io::nice_length(size / 5);
  svg.scale_bar(extent.min_x, box.min_y + text_size * 1.4, bar,
                io::format_number(bar) + " mm", text_size);
  if (options.legend && !legend.empty())
    svg.legend(extent.max_x + margin, extent.max_y, legend, text_size);
  return svg.str();
}

}  // namespace hipair::render
