#include "render/sliced_svg.hpp"

#include "io/svg.hpp"
#include "render/cspace_svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace hipair::render {
namespace {

std::string degrees_text(double degrees) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f\u00b0", degrees);
  return buffer;
}

}  // namespace

std::string sliced_interval_label(const SlicedSpace& space, std::size_t interval) {
  const SlicedInterval& in = space.intervals().at(interval);
  const double representative = in.representative.degrees();   // correctly rounded, as the JSON
  std::string slice = "slice at \u03b8 = " + degrees_text(representative);
  if (in.lower_critical == no_index) return "all \u03b8, " + slice;
  double lo = space.critical_angles()[in.lower_critical].degrees;
  double hi = space.critical_angles()[in.upper_critical].degrees;
  if (space.critical_angles().size() == 1) hi = lo + 360;   // the whole turn but one angle
  if (hi <= lo && interval + 1 == space.intervals().size())
    return "\u03b8 in (" + degrees_text(lo) + ", " + degrees_text(hi + 360) + "), " + slice;
  return "\u03b8 in (" + degrees_text(lo) + ", " + degrees_text(hi) + "), " + slice;
}

namespace {

// The crossing of the critical angle nearest theta = 0 at which the free space changes its
// structure (no_index: none).
std::size_t structure_change(const SlicedSpace& space) {
  const auto& intervals = space.intervals();
  // critical angles where the free space changes its structure: a free cell ends or starts
  // there, or splits or merges (the crossing's connections are not one-to-one onto both sides)
  std::size_t best = no_index;
  double best_distance = 0;
  for (std::size_t k = 0; k < space.crossings().size(); ++k) {
    const SlicedCrossing& c = space.crossings()[k];
    if (c.left_interval == c.right_interval) continue;   // one interval all round: nothing to compare
    std::vector<int> left(intervals[c.left_interval].free_cells.size()), right(intervals[c.right_interval].free_cells.size());
    for (const auto& link : c.connections) {
      ++left.at(link.left_cell);
      ++right.at(link.right_cell);
    }
    bool changes = !c.ending.empty() || !c.starting.empty();
    for (int n : left) changes = changes || n != 1;
    for (int n : right) changes = changes || n != 1;
    if (!changes) continue;
    // nearest theta = 0 (display choice: the approximate degrees, rounded so that mirror
    // images tie and the first in order of theta wins)
    const CriticalAngle& angle = space.critical_angles()[c.critical];
    double distance = angle.half_turn ? 180.0 : std::round(std::fabs(angle.degrees) * 1e6) / 1e6;
    if (best == no_index || distance < best_distance) {
      best = k;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace

std::vector<std::size_t> sliced_default_full_size(const SlicedSpace& space) {
  const auto& intervals = space.intervals();
  const std::size_t best = structure_change(space);
  std::vector<std::size_t> chosen;
  if (best != no_index) {
    const SlicedCrossing& c = space.crossings()[best];
    chosen = {c.left_interval, c.right_interval};
  } else {   // no change of structure: up to two slices with the most free cells (more than one)
    std::vector<std::size_t> order(intervals.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return intervals[a].free_cells.size() > intervals[b].free_cells.size();
    });
    for (std::size_t i : order)
      if (intervals[i].free_cells.size() > 1 && chosen.size() < 2) chosen.push_back(i);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

namespace {

struct Box {
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  void add(const CSpaceEdge& e) {
    x_lo = std::min(x_lo, e.x_coordinate.lower);
    x_hi = std::max(x_hi, e.x_coordinate.upper);
    y_lo = std::min(y_lo, e.y_coordinate.lower);
    y_hi = std::max(y_hi, e.y_coordinate.upper);
  }
  bool empty() const { return !(x_lo < x_hi && y_lo < y_hi); }
  // square, centred, with a margin of `pad` times the larger side
  std::array<double, 4> window(double pad) const {
    double cx = (x_lo + x_hi) / 2, cy = (y_lo + y_hi) / 2;
    double half = std::max(x_hi - x_lo, y_hi - y_lo) * (0.5 + pad);
    return {cx - half, cx + half, cy - half, cy + half};
  }
};

// The extent of a slice's real (contact) edges: everything outside it is free.
Box blocked_extent(const CSpace& slice) {
  Box box;
  for (const auto& e : slice.edges())
    if (e.real) box.add(e);
  return box;
}

// The extent of the free cells other than the outer one (which holds the chart box's corner).
Box inner_free_extent(const CSpace& slice) {
  Box box;
  const auto& chart = slice.charts()[0];
  Location corner = slice.locate(ChartPoint{0, Rational(chart.x_lo + Rational(1, 2)), Rational(chart.y_lo + Rational(1, 2))});
  for (std::size_t c = 0; c < slice.cells().size(); ++c) {
    if (slice.cells()[c].kind != CellKind::free || c == corner.cell) continue;
    for (std::size_t e : slice.cells()[c].boundary) box.add(slice.edges()[e]);
  }
  return box;
}

std::string text_at(double x, double y, const std::string& text, double size, const char* weight = "normal") {
  return "<text x=\"" + io::format_number(x) + "\" y=\"" + io::format_number(y) + "\" font-family=\"sans-serif\" font-size=\"" +
         io::format_number(size) + "\" font-weight=\"" + weight + "\">" + io::escape_xml(text) + "</text>\n";
}

}  // namespace

std::string sliced_stack_svg(const SlicedSpace& space, const SlicedSvgOptions& options) {
  const std::size_t n = space.intervals().size();
  std::size_t columns = options.columns;
  if (columns == 0) columns = std::min<std::size_t>(6, static_cast<std::size_t>(std::ceil(std::sqrt(double(n)))));
  columns = std::max<std::size_t>(1, std::min(columns, n));
  const double gap = 16, heading = 22, top = options.title.empty() ? 30 : 62;
  const double panel_width = options.panel_pixel_width;
  const std::string free = space.free_part();
  const std::string x_label = "x (mm): shift of " + free + "'s pivot", y_label = "y (mm)";
  // one window for every panel: the union of the blocked regions' extents
  Box all;
  std::vector<std::shared_ptr<const CSpace>> slices;
  for (std::size_t i = 0; i < n; ++i) {
    slices.push_back(space.slice(space.intervals()[i].representative));
    Box b = blocked_extent(*slices.back());
    if (!b.empty()) {
      all.x_lo = std::min(all.x_lo, b.x_lo);
      all.x_hi = std::max(all.x_hi, b.x_hi);
      all.y_lo = std::min(all.y_lo, b.y_lo);
      all.y_hi = std::max(all.y_hi, b.y_hi);
    }
  }
  std::string panels;
  double y = top, row_height = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t column = i % columns;
    if (column == 0 && i > 0) {
      y += row_height + gap;
      row_height = 0;
    }
    double x = gap + static_cast<double>(column) * (panel_width + gap);
    CSpaceSvgOptions panel;   // no title: the heading above the panel labels it
    panel.x_axis_label = x_label;
    panel.y_axis_label = y_label;
    if (!all.empty()) panel.window = all.window(0.08);
    panel.legend_pairs_per_kind = 0;   // the kinds only: a legend per panel, readable at this size
    panel.legend_text_size = 10;
    // the inner free cells (often too small to see at this scale) are marked with a dot
    {
      const CSpace& slice = *slices[i];
      const auto& chart = slice.charts()[0];
      Location corner = slice.locate(ChartPoint{0, Rational(chart.x_lo + Rational(1, 2)), Rational(chart.y_lo + Rational(1, 2))});
      for (std::size_t c = 0; c < slice.cells().size(); ++c)
        if (slice.cells()[c].kind == CellKind::free && c != corner.cell)
          panel.marks.push_back(CSpaceMark{slice.cells()[c].sample_x.get_d(), slice.cells()[c].sample_y.get_d(), "free cell"});
    }
    std::string label = "slice " + std::to_string(i) + ": " + sliced_interval_label(space, i) + " (" +
                        std::to_string(space.intervals()[i].free_cells.size()) + " free cells)";
    double height = 0;
    std::string body = io::nested_svg(cspace_svg(*slices[i], panel), x, y + heading, panel_width, &height);
    panels += text_at(x + 4, y + heading - 7, label, 11);
    panels += "<rect x=\"" + io::format_number(x) + "\" y=\"" + io::format_number(y) + "\" width=\"" +
              io::format_number(panel_width) + "\" height=\"" + io::format_number(height + heading) +
              "\" fill=\"none\" stroke=\"#888\" stroke-width=\"0.8\"/>\n";
    panels += body;
    row_height = std::max(row_height, height + heading);
  }
  double width = gap + static_cast<double>(columns) * (panel_width + gap);
  y += row_height + gap;
  // chosen slices at full size, zoomed onto their inner free cells
  std::vector<std::size_t> chosen = options.full_size;
  for (std::size_t i : chosen)
    if (i >= n) throw GeometryError("slice " + std::to_string(i) + " does not exist (the pair has " + std::to_string(n) + " slices)");
  std::string heading_text = "Chosen slices at full size, zoomed onto their inner free cells:";
  Box shared;   // the two sides of a change share one window, so the panels compare
  if (chosen.empty() && options.choose_full_size) {
    chosen = sliced_default_full_size(space);
    if (std::size_t change = structure_change(space); change != no_index) {
      for (std::size_t i : chosen) {
        Box b = inner_free_extent(*slices[i]);
        if (!b.empty()) {
          shared.x_lo = std::min(shared.x_lo, b.x_lo);
          shared.x_hi = std::max(shared.x_hi, b.x_hi);
          shared.y_lo = std::min(shared.y_lo, b.y_lo);
          shared.y_hi = std::max(shared.y_hi, b.y_hi);
        }
      }
      const CriticalAngle& angle = space.critical_angles()[space.crossings()[change].critical];
      heading_text = "Chosen slices at full size, either side of the critical angle \u03b8 = " +
                     degrees_text(angle.half_turn ? 180.0 : angle.degrees) +
                     " where the free cells change, zoomed onto their inner free cells (one window):";
    }
  }
  if (!chosen.empty()) {
    panels += text_at(gap, y + 14, heading_text, 13, "bold");
    y += 24;
  }
  for (std::size_t i : chosen) {
    const double full_width = std::max(options.full_pixel_width, 300.0);
    CSpaceSvgOptions panel;
    panel.x_axis_label = x_label;
    panel.y_axis_label = y_label;
    Box inner = shared.empty() ? inner_free_extent(*slices[i]) : shared;
    if (!inner.empty()) panel.window = inner.window(0.6);
    else if (!all.empty()) panel.window = all.window(0.08);
    panel.legend_pairs_per_kind = 4;
    panel.legend_text_size = 6;
    double height = 0;
    std::string body = io::nested_svg(cspace_svg(*slices[i], panel), gap, y + heading, full_width, &height);
    panels += text_at(gap + 4, y + heading - 7, "slice " + std::to_string(i) + ": " + sliced_interval_label(space, i), 12);
    panels += "<rect x=\"" + io::format_number(gap) + "\" y=\"" + io::format_number(y) + "\" width=\"" +
              io::format_number(full_width) + "\" height=\"" + io::format_number(height + heading) +
              "\" fill=\"none\" stroke=\"#888\" stroke-width=\"0.8\"/>\n";
    panels += body;
    width = std::max(width, full_width + 2 * gap);
    y += height + heading + gap;
  }
  double total = y;
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + io::format_number(width) + "\" height=\"" +
         io::format_number(total) + "\" viewBox=\"0 0 " + io::format_number(width) + " " + io::format_number(total) +
         "\">\n";
  out += "<rect x=\"0\" y=\"0\" width=\"" + io::format_number(width) + "\" height=\"" + io::format_number(total) +
         "\" fill=\"white\"/>\n";
  if (!options.title.empty()) out += text_at(gap, 26, options.title, 16);
  out += text_at(gap, top - 12,
                 "Axes: x, y (mm) the shift of " + free + "'s pivot; \u03b8 its angle, one panel per interval between critical "
                 "angles, in order of \u03b8 (the slice drawn at the angle named)",
                 11);
  out += panels;
  out += "</svg>\n";
  return out;
}

}  // namespace hipair::render
