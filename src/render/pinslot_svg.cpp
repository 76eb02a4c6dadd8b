#include "render/pinslot_svg.hpp"

#include "io/svg.hpp"
#include "render/cspace_svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace hipair::render {

std::string pin_slot_stack_svg(const PinSlotSpace& space, const PinSlotSvgOptions& options) {
  const auto& slices = space.slices();
  const std::size_t n = slices.size();
  std::size_t columns = options.columns;
  if (columns == 0) columns = std::min<std::size_t>(6, static_cast<std::size_t>(std::ceil(std::sqrt(double(n)))));
  columns = std::max<std::size_t>(1, std::min(columns, n));
  const double gap = 14, heading = 22, top = options.title.empty() ? 10 : 40;
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
    std::string body = io::nested_svg(cspace_svg(*slice, CSpaceSvgOptions{}), x, y + heading, panel_width, &height);
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
  out += panels;
  out += "</svg>\n";
  return out;
}

}  // namespace hipair::render
