// Kinematic plots and C-space path pictures (SVG).
#include "render/kinematics_svg.hpp"

#include "io/svg.hpp"
#include "core/length_display.hpp"
#include "core/plot_axis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace hipair::render {
namespace {

constexpr double degrees = 180 / std::numbers::pi;

// A rectangular plot area in world units (y up) with its two axes.
struct Panel {
  double left = 0, bottom = 0, width = 0, height = 0;
  PlotAxis x_axis, y_axis;
  double x(long double value) const { return left + x_axis.fraction(value) * width; }
  double y(long double value) const { return bottom + y_axis.fraction(value) * height; }
};

// An axis over the data range itself (not extended), at most 9 ticks.
PlotAxis range_axis(double lo, double hi) {
  PlotAxisOptions options;
  options.max_ticks = 9;
  return plot_axis(lo, hi, options);
}

void draw_axes(io::SvgWriter& svg, const Panel& panel, const std::string& x_label, const std::string& y_label,
               const std::string& title) {
  io::SvgStyle frame;
  frame.stroke = "#444";
  frame.stroke_width = 1;
  io::SvgStyle grid;
  grid.stroke = "#ddd";
  grid.stroke_width = 0.6;
  for (std::size_t i = 0; i < panel.x_axis.ticks.size(); ++i) {
    double x = panel.x(panel.x_axis.ticks[i]);
    svg.line(x, panel.bottom, x, panel.bottom + panel.height, grid);
    svg.text(x, panel.bottom - 14, panel.x_axis.labels[i], 11);
  }
  if (!panel.x_axis.base_label.empty())
    svg.text(panel.left, panel.bottom - 32, panel.x_axis.base_label, 11, "start");
  for (std::size_t i = 0; i < panel.y_axis.ticks.size(); ++i) {
    double y = panel.y(panel.y_axis.ticks[i]);
    svg.line(panel.left, y, panel.left + panel.width, y, grid);
    svg.text(panel.left - 6, y - 4, panel.y_axis.labels[i], 11, "end");
  }
  if (!panel.y_axis.base_label.empty())
    svg.text(panel.left - 6, panel.bottom + panel.height + 8 + 14, panel.y_axis.base_label, 11, "end");
  svg.rectangle(panel.left, panel.bottom, panel.width, panel.height, frame);
  svg.text(panel.left + panel.width / 2, panel.bottom - 32, x_label, 12);
  // The axis name sits above the axis, ending at it; a name longer than the margin (a length unit
  // such as "1e400 mm") starts at the picture's edge instead of running off it (DejaVu Sans at
  // 12 px: about 0.47 em per character of such labels).
  if (0.47 * 12.0 * static_cast<double>(y_label.size()) > panel.left - 10)
    svg.text(2, panel.bottom + panel.height + 8, y_label, 12, "start");
  else
    svg.text(panel.left - 8, panel.bottom + panel.height + 8, y_label, 12, "end");
  svg.text(panel.left + panel.width / 2, panel.bottom + panel.height + 24, title, 13, "middle", "black", "bold");
}

}  // namespace

std::string kinematics_plot_svg(const KinematicsResult& result, double pixel_width) {
  bool rot = result.driver_rotates;
  double driver_scale = rot ? degrees : 1.0;
  const double width = 900, panel_height = 220, gap = 90, left = 90;
  std::size_t followers = result.followers.size();
  double total = followers * 2 * (panel_height + gap) + 50;
  io::SvgWriter svg(io::SvgBox{0, 0, width, total}, pixel_width);
  svg.set_default_stroke_width(1);
  double x_min = std::min(result.start, result.reached) * driver_scale, x_max = std::max(result.start, result.reached) * driver_scale;
  if (!result.samples.empty()) {
    x_min = std::min(result.samples.front().driver, result.samples.back().driver) * driver_scale;
    x_max = std::max(result.samples.front().driver, result.samples.back().driver) * driver_scale;
  }
  PlotAxis x_axis = range_axis(x_min, x_max);
  const std::string mm = "(" + length_unit_name() + ")";   // "(1e400 mm)": core/length_display.hpp
  std::string x_label = result.driver + (rot ? " angle (deg)" : " offset " + mm);
  double top = total - 70;
  for (std::size_t f = 0; f < followers; ++f) {
    bool frot = result.follower_rotates[f];
    double scale = frot ? degrees : 1.0;
    for (int kind = 0; kind < 2; ++kind) {
      Panel panel;
      panel.left = left;
      panel.width = width - left - 30;
      panel.height = panel_height;
      panel.bottom = top - panel_height;
      top -= panel_height + gap;
      panel.x_axis = x_axis;
      double lo = std::numeric_limits<double>::quiet_NaN(), hi = lo;
      auto value = [&](const KinematicSample& sample) {
        if (kind == 0) return sample.positions[f] * scale;
        return sample.velocity_ratios[f] * scale / driver_scale;
      };
      for (const KinematicSample& sample : result.samples) {
        double v = value(sample);
        if (!std::isfinite(v)) continue;
        lo = std::isnan(lo) ? v : std::min(lo, v);
        hi = std::isnan(hi) ? v : std::max(hi, v);
      }
      PlotAxisOptions y_options;
      y_options.snap = true;   // the range extended to the nearest ticks
      panel.y_axis = plot_axis(lo, hi, y_options);
      // dwell periods shaded
      io::SvgStyle dwell;
      dwell.fill = "#eef3fb";
      dwell.stroke = "none";
      for (const KinematicPiece& piece : result.pieces) {
        if (piece.part != result.followers[f] || piece.moving) continue;
        double a = piece.start.value() * driver_scale, b = piece.end.value() * driver_scale;
        svg.rectangle(panel.x(std::min(a, b)), panel.bottom, std::abs(panel.x(b) - panel.x(a)), panel.height, dwell);
      }
      std::string name = result.followers[f];
      // the ratio's unit: the follower's per the driver's (deg/deg and mm/mm: none)
      const std::string ratio_unit = frot == rot ? "" : frot ? " (deg/" + length_unit_name() + ")" : " (" + length_unit_name() + "/deg)";
      std::string y_label = kind == 0 ? (frot ? "angle (deg)" : "offset " + mm) : "velocity ratio" + ratio_unit;
      std::string title = kind == 0 ? name + ": position against the driver (shaded: dwell)"
                                    : name + ": velocity ratio d(" + name + ")/d(" + result.driver + ")";
      draw_axes(svg, panel, x_label, y_label, title);
      // contact changes
      io::SvgStyle change;
      change.stroke = "#999";
      change.stroke_width = 0.8;
      change.dash = "4 3";
      for (const KinematicEvent& event : result.events) {
        if (event.part != name) continue;
        double x = panel.x(event.at.value() * driver_scale);
        svg.line(x, panel.bottom, x, panel.bottom + panel.height, change);
      }
      io::SvgPath curve;
      bool pen = false;
      for (const KinematicSample& sample : result.samples) {
        double v = value(sample);
        if (!std::isfinite(v)) {
          pen = false;
          continue;
        }
        double px = panel.x(sample.driver * driver_scale), py = panel.y(v);
        if (pen) curve.line_to(px, py);
        else curve.move_to(px, py);
        pen = true;
      }
      io::SvgStyle line;
      line.stroke = kind == 0 ? "#1f4e9c" : "#b03a2e";
      line.stroke_width = 1.6;
      if (!curve.empty()) svg.path(curve, line);
      if (result.jam) {
        io::SvgStyle jam;
        jam.stroke = "#c00";
        jam.stroke_width = 2;
        double x = panel.x(result.jam->at.value() * driver_scale);
        svg.line(x, panel.bottom, x, panel.bottom + panel.height, jam);
        svg.text(x + 4, panel.bottom + panel.height - 14, "blocked", 12, "start", "#c00");
      }
    }
  }
  svg.text(width / 2, total - 22, "Kinematics of " + result.model_name + ", driven by " + result.driver, 15, "middle", "black", "bold");
  return svg.str();
}

std::string cspace_path_svg(const CSpaceRaster& raster, const PairPath& path, const std::string& title, double pixel_width) {
  double xs = raster.x_rotates ? degrees : 1.0, ys = raster.y_rotates ? degrees : 1.0;
  const double size = 600, left = 90, bottom = 110;
  io::SvgWriter svg(io::SvgBox{0, 0, left + size + 40, bottom + size + 50}, pixel_width);
  svg.set_default_stroke_width(1);
  Panel panel;
  panel.left = left;
  panel.bottom = bottom;
  panel.width = size;
  panel.height = size;
  panel.x_axis = range_axis(raster.x_lo * xs, raster.x_hi * xs);
  panel.y_axis = range_axis(raster.y_lo * ys, raster.y_hi * ys);
  double y_min = static_cast<double>(panel.y_axis.lo), y_max = static_cast<double>(panel.y_axis.hi);
  io::SvgStyle blocked;
  blocked.fill = "#9a9a9a";
  blocked.stroke = "none";
  for (std::size_t c = 0; c < raster.x.size(); ++c) {
    double x0 = panel.x((raster.x[c] - raster.column_width / 2) * xs);
    double x1 = panel.x((raster.x[c] + raster.column_width / 2) * xs);
    for (auto [lo, hi] : raster.blocked[c]) {
      double y0 = panel.y(std::max(lo * ys, y_min)), y1 = panel.y(std::min(hi * ys, y_max));
      if (y1 > y0) svg.rectangle(x0, y0, x1 - x0 + 0.8, y1 - y0, blocked);
    }
  }
  const std::string mm = "(" + length_unit_name() + ")";   // "(1e400 mm)": core/length_display.hpp
  draw_axes(svg, panel, raster.x_part + (raster.x_rotates ? " angle (deg)" : " offset " + mm),
            raster.y_part + (raster.y_rotates ? " (deg)" : " " + mm),
            title.empty() ? "C-space of " + raster.pair + ": blocked grey, free white; path: free blue, contact red" : title);
  // the path, broken where it wraps around
  double x_period = raster.x_rotates ? 360 : 0, y_period = raster.y_rotates ? 360 : 0;
  io::SvgStyle free_style, contact_style;
  free_style.stroke = "#1f4e9c";
  free_style.stroke_width = 2.2;
  contact_style.stroke = "#d62d20";
  contact_style.stroke_width = 2.6;
  for (std::size_t i = 1; i < path.points.size(); ++i) {
    const PathPoint& a = path.points[i - 1];
    const PathPoint& b = path.points[i];
    double ax = a.x * xs, ay = a.y * ys, bx = b.x * xs, by = b.y * ys;
    if ((x_period > 0 && std::abs(bx - ax) > x_period / 2) || (y_period > 0 && std::abs(by - ay) > y_period / 2)) continue;
    bool contact = a.contact && b.contact;
    svg.line(panel.x(ax), panel.y(ay), panel.x(bx), panel.y(by), contact ? contact_style : free_style);
  }
  if (!path.points.empty()) {
    io::SvgStyle start;
    start.fill = "#2a9d3a";
    start.stroke = "white";
    io::SvgStyle end;
    end.fill = "black";
    end.stroke = "white";
    svg.circle(panel.x(path.points.front().x * xs), panel.y(path.points.front().y * ys), 6, start);
    svg.circle(panel.x(path.points.back().x * xs), panel.y(path.points.back().y * ys), 5, end);
  }
  std::vector<io::SvgWriter::LegendEntry> legend;
  io::SvgStyle swatch_blocked = blocked;
  legend.push_back({swatch_blocked, "blocked (parts overlap)"});
  legend.push_back({free_style, "path, no contact"});
  legend.push_back({contact_style, "path, in contact"});
  svg.legend(left, bottom - 48, legend, 11);
  return svg.str();
}

}  // namespace hipair::render
