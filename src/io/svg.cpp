#include "io/svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace hipair::io {

std::string escape_xml(std::string_view text) {
  static const char replacement[] = "\xEF\xBF\xBD";  // U+FFFD
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    auto byte = static_cast<unsigned char>(text[i]);
    if (byte < 0x80) {
      switch (byte) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&apos;"; break;
        case '\t': out += "&#9;"; break;
        case '\n': out += "&#10;"; break;
        case '\r': out += "&#13;"; break;
        default:
          // other C0 controls are not XML characters at all; DEL is discouraged
          if (byte < 0x20 || byte == 0x7F) out += replacement;
          else out += static_cast<char>(byte);
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence: well-formed and an XML character, or replaced.
    std::size_t length = byte >= 0xF0 ? 4 : byte >= 0xE0 ? 3 : byte >= 0xC0 ? 2 : 0;
    unsigned long code = length == 4 ? (byte & 0x07u) : length == 3 ? (byte & 0x0Fu) : (byte & 0x1Fu);
    bool valid = length >= 2 && byte <= 0xF4 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0) == 0x80;
      code = (code << 6) | (next & 0x3Fu);
    }
    unsigned long smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
    valid = valid && code >= smallest && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF) &&
            !(code >= 0x80 && code <= 0x9F) && code != 0xFFFE && code != 0xFFFF;  // C1 controls, non-characters
    if (valid) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      out += replacement;
      ++i;
      while (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) ++i;
    }
  }
  return out;
}

std::string format_number(double value) {
  if (!std::isfinite(value) || value == 0) return "0";
  // Four decimals for ordinary drawing coordinates, at least seven significant digits for
  // tiny ones and an exponent for huge ones ("1e-300", "2.5e+60"): no value is cut or lost.
  int magnitude = static_cast<int>(std::floor(std::log10(std::abs(value))));
  int digits = std::clamp(magnitude + 5, 7, 15);
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  std::string s = buffer;
  if (s == "-0") s = "0";
  return s;
}

namespace {

std::string pair(double x, double y) { return format_number(x) + "," + format_number(-y); }

void add_extent_of_arc(std::vector<std::pair<double, double>>& extent, double cx, double cy,
                       double radius, double start, double span) {
  // Extremes of the arc: its end points plus every axis direction it passes.
  for (int quarter = -8; quarter <= 8; ++quarter) {
    double angle = quarter * M_PI / 2;
    double relative = angle - start;
    relative = std::fmod(relative, 2 * M_PI);
    if (relative < 0) relative += 2 * M_PI;
    if (relative <= span)
      extent.emplace_back(cx + radius * std::cos(angle), cy + radius * std::sin(angle));
  }
}

}  // namespace

void SvgPath::move_to(double x, double y) {
  data_ += (data_.empty() ? "M" : " M") + pair(x, y);
  x_ = x;
  y_ = y;
  extent_.emplace_back(x, y);
}

void SvgPath::line_to(double x, double y) {
  data_ += " L" + pair(x, y);
  x_ = x;
  y_ = y;
  extent_.emplace_back(x, y);
}

void SvgPath::arc_to(double x, double y, double cx, double cy, bool ccw) {
  double radius = std::hypot(x_ - cx, y_ - cy);
  double start = std::atan2(y_ - cy, x_ - cx);
  double end = std::atan2(y - cy, x - cx);
  bool full = x == x_ && y == y_;
  double span = full ? 2 * M_PI : (ccw ? end - start : start - end);
  if (!full) {
    span = std::fmod(span, 2 * M_PI);
    if (span <= 0) span += 2 * M_PI;
  }
  // Extent: for a clockwise arc, the same set of points as the ccw arc from end to start.
  add_extent_of_arc(extent_, cx, cy, radius, ccw ? start : (full ? start : end), span);
  // SVG's y axis points down, so a world counter-clockwise arc is sweep-flag 0.
  std::string sweep = ccw ? "0" : "1";
  std::string r = format_number(radius);
  if (full) {
    double ox = 2 * cx - x_, oy = 2 * cy - y_;  // the opposite point
    data_ += " A" + r + "," + r + " 0 0," + sweep + " " + pair(ox, oy);
    data_ += " A" + r + "," + r + " 0 0," + sweep + " " + pair(x, y);
  } else {
    std::string large = span > M_PI ? "1" : "0";
    data_ += " A" + r + "," + r + " 0 " + large + "," + sweep + " " + pair(x, y);
  }
  x_ = x;
  y_ = y;
  extent_.emplace_back(x, y);
}

void SvgPath::close() { data_ += " Z"; }

SvgWriter::SvgWriter(const SvgBox& box, double pixel_width)
    : box_(box), pixel_width_(pixel_width) {
  double size = std::max(box.width(), box.height());
  default_stroke_ = size > 0 ? size / 600 : 0.1;
}

void SvgWriter::add_definition(const std::string& markup) { definitions_ += markup + "\n"; }

void SvgWriter::define_hatch(const std::string& id, const std::string& color, double spacing) {
  std::string s = format_number(spacing);
  add_definition("<pattern id=\"" + escape_xml(id) +
                 "\" patternUnits=\"userSpaceOnUse\" width=\"" + s + "\" height=\"" + s +
                 "\" patternTransform=\"rotate(45)\"><rect width=\"" + s + "\" height=\"" + s +
                 "\" fill=\"#e8e8e8\"/><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"" + s +
                 "\" stroke=\"" + escape_xml(color) + "\" stroke-width=\"" +
                 format_number(spacing / 4) + "\"/></pattern>");
}

void SvgWriter::define_arrow(const std::string& id, const std::string& color) {
  add_definition("<marker id=\"" + escape_xml(id) +
                 "\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" "
                 "markerHeight=\"6\" orient=\"auto-start-reverse\"><path d=\"M0,0 L10,5 L0,10 "
                 "z\" fill=\"" +
                 escape_xml(color) + "\"/></marker>");
}

void SvgWriter::begin_group(const std::string& id, const std::string& css_class,
                            const std::string& title) {
  body_ += "<g";
  if (!id.empty()) body_ += " id=\"" + escape_xml(id) + "\"";
  if (!css_class.empty()) body_ += " class=\"" + escape_xml(css_class) + "\"";
  body_ += ">\n";
  if (!title.empty()) body_ += "<title>" + escape_xml(title) + "</title>\n";
  ++open_groups_;
}

void SvgWriter::begin_transformed_group(const std::string& transform, const std::string& id,
                                        const std::string& css_class) {
  body_ += "<g";
  if (!id.empty()) body_ += " id=\"" + escape_xml(id) + "\"";
  if (!css_class.empty()) body_ += " class=\"" + escape_xml(css_class) + "\"";
  if (!transform.empty()) body_ += " transform=\"" + escape_xml(transform) + "\"";
  body_ += ">\n";
  ++open_groups_;
}

void SvgWriter::raw(const std::string& markup) { body_ += markup; }

void SvgWriter::define_clip_rectangle(const std::string& id, double x, double y, double width, double height) {
  add_definition("<clipPath id=\"" + escape_xml(id) + "\"><rect x=\"" + format_number(x) + "\" y=\"" +
                 format_number(-(y + height)) + "\" width=\"" + format_number(width) + "\" height=\"" +
                 format_number(height) + "\"/></clipPath>");
}

void SvgWriter::begin_clipped_group(const std::string& clip_id) {
  body_ += "<g clip-path=\"url(#" + escape_xml(clip_id) + ")\">\n";
  ++open_groups_;
}

void SvgWriter::end_group() {
  if (open_groups_ == 0) throw Error("SVG writer: end_group without begin_group");
  body_ += "</g>\n";
  --open_groups_;
}

std::string SvgWriter::style_attributes(const SvgStyle& style) const {
  std::string out = " fill=\"" + escape_xml(style.fill.empty() ? "none" : style.fill) + "\"";
  if (!style.stroke.empty()) {
    out += " stroke=\"" + escape_xml(style.stroke) + "\"";
    double width = style.stroke_width > 0 ? style.stroke_width : default_stroke_;
    out += " stroke-width=\"" + format_number(width) + "\"";
    out += " stroke-linejoin=\"round\"";
  }
  if (!style.fill_rule.empty()) out += " fill-rule=\"" + escape_xml(style.fill_rule) + "\"";
  if (!style.dash.empty()) out += " stroke-dasharray=\"" + escape_xml(style.dash) + "\"";
  if (style.opacity < 1) out += " fill-opacity=\"" + format_number(style.opacity) + "\"";
  if (!style.marker_end.empty()) out += " marker-end=\"" + escape_xml(style.marker_end) + "\"";
  return out;
}

void SvgWriter::path(const SvgPath& path, const SvgStyle& style, const std::string& title) {
  if (path.empty()) return;
  body_ += "<path d=\"" + path.data() + "\"" + style_attributes(style);
  if (title.empty()) {
    body_ += "/>\n";
  } else {
    body_ += "><title>" + escape_xml(title) + "</title></path>\n";
  }
}

void SvgWriter::line(double x1, double y1, double x2, double y2, const SvgStyle& style) {
  body_ += "<line x1=\"" + format_number(x1) + "\" y1=\"" + format_number(-y1) + "\" x2=\"" +
           format_number(x2) + "\" y2=\"" + format_number(-y2) + "\"" + style_attributes(style) +
           "/>\n";
}

void SvgWriter::circle(double cx, double cy, double r, const SvgStyle& style) {
  body_ += "<circle cx=\"" + format_number(cx) + "\" cy=\"" + format_number(-cy) + "\" r=\"" +
           format_number(r) + "\"" + style_attributes(style) + "/>\n";
}

void SvgWriter::rectangle(double x, double y, double width, double height,
                          const SvgStyle& style) {
  // (x, y) is the lower-left corner in world coordinates.
  body_ += "<rect x=\"" + format_number(x) + "\" y=\"" + format_number(-(y + height)) +
           "\" width=\"" + format_number(width) + "\" height=\"" + format_number(height) + "\"" +
           style_attributes(style) + "/>\n";
}

void SvgWriter::text(double x, double y, const std::string& content, double size,
                     const std::string& anchor, const std::string& fill,
                     const std::string& weight) {
  body_ += "<text x=\"" + format_number(x) + "\" y=\"" + format_number(-y) + "\" font-size=\"" +
           format_number(size) + "\" font-family=\"DejaVu Sans, Arial, sans-serif\"" +
           " text-anchor=\"" + escape_xml(anchor) + "\" fill=\"" + escape_xml(fill) + "\"";
  if (weight != "normal") body_ += " font-weight=\"" + escape_xml(weight) + "\"";
  body_ += ">" + escape_xml(content) + "</text>\n";
}

std::pair<double, double> SvgWriter::legend_size(const std::vector<LegendEntry>& entries, double size) {
  double longest = 0;
  for (const LegendEntry& entry : entries)
    longest = std::max(longest, static_cast<double>(entry.label.size()));
  return {size * (2.2 + 0.62 * longest), size * 1.5 * static_cast<double>(entries.size()) + size * 0.6};
}

void SvgWriter::legend(double x, double y, const std::vector<LegendEntry>& entries,
                       double size) {
  double row = size * 1.5;
  auto [width, height] = legend_size(entries, size);
  SvgStyle frame;
  frame.fill = "white";
  frame.stroke = "#999999";
  frame.opacity = 0.85;
  begin_group("", "legend");
  rectangle(x, y - height, width, height, frame);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    double top = y - size * 0.3 - row * static_cast<double>(i);
    rectangle(x + size * 0.4, top - size * 1.1, size, size, entries[i].swatch);
    text(x + size * 1.8, top - size * 0.95, entries[i].label, size, "start");
  }
  end_group();
}

void SvgWriter::scale_bar(double x, double y, double length, const std::string& label,
                          double size) {
  SvgStyle bar;
  bar.stroke = "black";
  bar.stroke_width = size / 6;
  begin_group("", "scale-bar");
  line(x, y, x + length, y, bar);
  line(x, y - size * 0.3, x, y + size * 0.3, bar);
  line(x + length, y - size * 0.3, x + length, y + size * 0.3, bar);
  text(x + length / 2, y + size * 0.5, label, size, "middle");
  end_group();
}

std::string SvgWriter::str() const {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  double aspect = box_.width() > 0 ? box_.height() / box_.width() : 1;
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + format_number(pixel_width_) +
         "\" height=\"" + format_number(std::round(pixel_width_ * aspect)) + "\" viewBox=\"" +
         format_number(box_.min_x) + " " + format_number(-box_.max_y) + " " +
         format_number(box_.width()) + " " + format_number(box_.height()) + "\">\n";
  if (!definitions_.empty()) out += "<defs>\n" + definitions_ + "</defs>\n";
  out += body_;
  for (int i = 0; i < open_groups_; ++i) out += "</g>\n";
  out += "</svg>\n";
  return out;
}

double nice_length(double approximate) {
  if (!(approximate > 0)) return 1;
  double power = std::pow(10.0, std::floor(std::log10(approximate)));
  double mantissa = approximate / power;
  double nice = mantissa < 1.5 ? 1 : mantissa < 3.5 ? 2 : mantissa < 7.5 ? 5 : 10;
  return nice * power;
}

namespace {

// The attribute `name="..."` of the first <svg> tag of `document`, as a number (0 when absent).
double svg_attribute(const std::string& document, const std::string& name) {
  std::size_t tag = document.find("<svg");
  if (tag == std::string::npos) return 0;
  std::size_t end = document.find('>', tag);
  std::size_t at = document.find(" " + name + "=\"", tag);
  if (at == std::string::npos || at > end) return 0;
  return std::atof(document.c_str() + at + name.size() + 3);
}

}  // namespace

std::string nested_svg(const std::string& document, double x, double y, double width, double* height) {
  std::size_t tag = document.find("<svg");
  std::size_t view = tag == std::string::npos ? std::string::npos : document.find(" viewBox=", tag);
  if (tag == std::string::npos || view == std::string::npos)
    throw GeometryError("internal: the slice renderer did not produce an <svg> element");
  double w = svg_attribute(document, "width"), h = svg_attribute(document, "height");
  *height = w > 0 ? width * h / w : width;
  return "<svg x=\"" + format_number(x) + "\" y=\"" + format_number(y) + "\" width=\"" + format_number(width) +
         "\" height=\"" + format_number(*height) + "\"" + document.substr(view);
}

}  // namespace hipair::io
