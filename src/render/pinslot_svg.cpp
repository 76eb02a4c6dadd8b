#include "render/pinslot_svg.hpp"

#include "io/svg.hpp"
#include "render/cspace_svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <set>

namespace hipair::render {

namespace {

// The slice of the stack at tau, or no_index.
std::size_t slice_at(const PinSlotSpace& space, const Rational& tau) {
  for (std::size_t k = 0; k < space.slices().size(); ++k)
    if (space.slices()[k].tau == tau) return k;
  return no_index;
}

// A configuration in a panel's part coordinates (rad or the space's length unit): x the other
// part's (1-D: the slide), y the slide.
std::pair<double, double> panel_point(const PinSlotSpace& space, const PinSlotConfiguration& q) {
  if (space.other_kind() == Motion::Kind::fixed) return {to_double(q.slide), 0};   // 1-D slices: x = s
  double x = 0;
  if (q.other.kind == PartCoordinate::Kind::half_turn) x = std::numbers::pi;
  else if (q.other.kind == PartCoordinate::Kind::offset) x = to_double(q.other.value);
  else x = 2 * std::atan(to_double(q.other.value));
  return {x, to_double(q.slide)};
}

// The path's drawing on panel `k`: its in-slice motions there and its marks.
void path_on_panel(const PinSlotSpace& space, const PinSlotPath& path, std::size_t k, CSpaceSvgOptions& svg) {
  const auto& w = path.waypoints;
  if (path.status != PinSlotPath::Status::found || w.empty()) return;
  const Rational& tau = space.slices()[k].tau;
  auto where = [&](std::size_t j) {
    std::size_t s = slice_at(space, w[j].tau);
    if (j == 0) return std::string("start");
    if (j + 1 == w.size()) return std::string("end");
    if (s != no_index) return std::to_string(s);
    char text[48];
    std::snprintf(text, sizeof text, "\u03c8 %.2f\u00b0", 2 * std::atan(to_double(w[j].tau)) * 180 / std::numbers::pi);
    return std::string(text);
  };
  for (std::size_t j = 0; j < w.size(); ++j) {
    if (w[j].tau != tau) continue;
    auto [x, y] = panel_point(space, w[j]);
    const bool in_from = j > 0 && w[j - 1].tau == tau;
    const bool in_to = j + 1 < w.size() && w[j + 1].tau == tau;
    // a motion is straight in the other part's half-angle tangent: drawn through 15 points
    // between its ends (a chord in the angle would not be the certified motion)
    if (in_from && space.other_kind() == Motion::Kind::rotation &&
        w[j - 1].other.kind == PartCoordinate::Kind::half_angle_tangent &&
        w[j].other.kind == PartCoordinate::Kind::half_angle_tangent) {
      const double t0 = to_double(w[j - 1].other.value), t1 = to_double(w[j].other.value);
      const double s0 = to_double(w[j - 1].slide), s1 = to_double(w[j].slide);
      for (int i = 1; i < 16; ++i) {
        const double u = i / 16.0;
        svg.path.push_back(CSpacePathPoint{2 * std::atan(t0 + u * (t1 - t0)), s0 + u * (s1 - s0), false, false});
      }
    }
    if (in_from || in_to) svg.path.push_back(CSpacePathPoint{x, y, false, !in_from});
    std::string label;
    if (j == 0) label = "start";
    if (j + 1 == w.size()) label += label.empty() ? "end" : ", end";
    if (j > 0 && w[j - 1].tau != tau) label += (label.empty() ? "" : ", ") + std::string("<- ") + where(j - 1);
    if (j + 1 < w.size() && w[j + 1].tau != tau) label += (label.empty() ? "" : ", ") + std::string("-> ") + where(j + 1);
    if (!label.empty()) svg.marks.push_back(CSpaceMark{x, y, label});
  }
  if (svg.path.size() == 1) svg.path.clear();
  if (!svg.path.empty() || !svg.marks.empty()) {
    const double huge = 1e300;
    svg.window = std::array<double, 4>{-huge, huge, -huge, huge};   // the whole slice, not the path's zoom
  }
}

}  // namespace

std::string pin_slot_stack_svg(const PinSlotSpace& space, const PinSlotSvgOptions& options) {
  const auto& slices = space.slices();
  const std::size_t n = slices.size();
  std::size_t columns = options.columns;
  if (columns == 0) columns = std::min<std::size_t>(6, static_cast<std::size_t>(std::ceil(std::sqrt(double(n)))));
  columns = std::max<std::size_t>(1, std::min(columns, n));
  const double gap = 14, heading = 22;
  const double top = (options.title.empty() ? 10 : 40) + (options.path ? 16 : 0);
  const double panel_width = options.panel_pixel_width;
  std::string panels;
  double y = top, row_height = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t column = i % columns;
    if (column == 0 && i > 0) {
      y += row_height + gap;
      row_height = 0;
    }
    double x = gap + static_cast<double>(column) * (panel_width + gap);
    auto slice = space.slice(slices[i].tau);
    std::set<std::size_t> groups;
    for (const auto& c : slices[i].free_cells) groups.insert(c.group);
    char label[160];
    std::snprintf(label, sizeof label, "%s%zu: \u03c8 = %.3f\u00b0, %zu free cell%s, group%s", slices[i].refinement ? "r" : "",
                  i, slices[i].degrees, slices[i].free_cells.size(), slices[i].free_cells.size() == 1 ? "" : "s",
                  groups.size() == 1 ? "" : "s");
    std::string text = label;
    for (std::size_t g : groups) text += " " + std::to_string(g);
    if (groups.empty()) text += " -";
    double height = 0;
    CSpaceSvgOptions panel;
    if (options.path) path_on_panel(space, *options.path, i, panel);
    std::string body = io::nested_svg(cspace_svg(*slice, panel), x, y + heading, panel_width, &height);
    panels += "<text x=\"" + io::format_number(x + 4) + "\" y=\"" + io::format_number(y + heading - 7) +
              "\" font-family=\"sans-serif\" font-size=\"11\">" + io::escape_xml(text) + "</text>\n";
    panels += "<rect x=\"" + io::format_number(x) + "\" y=\"" + io::format_number(y) + "\" width=\"" +
              io::format_number(panel_width) + "\" height=\"" + io::format_number(height + heading) +
              "\" fill=\"none\" stroke=\"#888\" stroke-width=\"0.8\"/>\n";
    panels += body;
    row_height = std::max(row_height, height + heading);
  }
  double width = gap + static_cast<double>(columns) * (panel_width + gap);
  double total = y + row_height + gap;
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + io::format_number(width) + "\" height=\"" +
         io::format_number(total) + "\" viewBox=\"0 0 " + io::format_number(width) + " " + io::format_number(total) +
         "\">\n";
  out += "<rect x=\"0\" y=\"0\" width=\"" + io::format_number(width) + "\" height=\"" + io::format_number(total) +
         "\" fill=\"white\"/>\n";
  if (!options.title.empty())
    out += "<text x=\"" + io::format_number(gap) + "\" y=\"26\" font-family=\"sans-serif\" font-size=\"15\">" +
           io::escape_xml(options.title) + "</text>\n";
  if (options.path) {
    std::string text = "path: " + std::string(to_string(options.path->status));
    if (options.path->status == PinSlotPath::Status::found) {
      std::size_t between = 0;
      for (std::size_t j = 0; j + 1 < options.path->waypoints.size(); ++j)
        between += options.path->waypoints[j].tau != options.path->waypoints[j + 1].tau ? 1 : 0;
      text += ", " + std::to_string(options.path->waypoints.size()) + " waypoints, " + std::to_string(between) +
              " moves between slices (-> k: leaves for slice k, <- k: arrives from it); in-slice motions drawn in blue; "
              "every motion certified free";
    }
    out += "<text x=\"" + io::format_number(gap) + "\" y=\"" + io::format_number(top - 8) +
           "\" font-family=\"sans-serif\" font-size=\"11\">" + io::escape_xml(text) + "</text>\n";
  }
  out += panels;
  out += "</svg>\n";
  return out;
}

}  // namespace hipair::render
