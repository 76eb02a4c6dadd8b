// A small SVG writer for figures in world coordinates (mm, y axis up): mechanisms now,
// configuration-space plots later. Pictures only: coordinates are doubles.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hipair::io {

/// Presentation attributes of one SVG element. Empty strings are omitted.
struct SvgStyle {
  std::string fill = "none";
  std::string stroke = "black";
  double stroke_width = 0;           ///< in world units; 0 means the writer's default
  std::string fill_rule;             ///< "evenodd" cuts holes
  std::string dash;                  ///< stroke-dasharray in world units, e.g. "2 1"
  double opacity = 1;                ///< fill-opacity
  std::string marker_end;            ///< e.g. "url(#arrow)"
};

/// A path in world coordinates (y up) made of segments and circular arcs.
class SvgPath {
 public:
  void move_to(double x, double y);
  void line_to(double x, double y);
  /// Circular arc from the current point to (x, y) around (cx, cy), counter-clockwise in the
  /// world (y up) when `ccw`. If (x, y) equals the current point it is a full circle.
  /// The radius is taken from the current point; SVG's large-arc and sweep flags are derived.
  void arc_to(double x, double y, double cx, double cy, bool ccw);
  void close();
  bool empty() const { return data_.empty(); }
  /// The "d" attribute, with y negated for SVG's y-down axis.
  const std::string& data() const { return data_; }
  /// Points visited (end points and arc extremes), for bounding boxes.
  const std::vector<std::pair<double, double>>& extent_points() const { return extent_; }

 private:
  std::string data_;
  double x_ = 0, y_ = 0;
  std::vector<std::pair<double, double>> extent_;
};

/// Axis-aligned box in world coordinates.
struct SvgBox {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
};

/// Escapes &, <, >, " and ' for XML text and attributes.
std::string escape_xml(std::string_view text);

/// Formats a coordinate compactly (up to 4 decimals, no trailing zeros, no "-0").
std::string format_number(double value);

/// A whole SVG document (as SvgWriter writes it) placed as a nested <svg> element at (x, y) with
/// the given width: the XML declaration is dropped and the outer size is replaced by the
/// placement; `*height` receives the placed height (the document's aspect ratio kept). Stacks of
/// C-space slices are drawn this way, one panel per slice.
std::string nested_svg(const std::string& document, double x, double y, double width, double* height);

/// Builds one SVG document. The viewBox is the world box (y up, flipped for SVG).
class SvgWriter {
 public:
  /// `box` in world units; `pixel_width` sets the document's width attribute (height follows).
  SvgWriter(const SvgBox& box, double pixel_width = 900);

  /// Default stroke width (world units), used when a style's stroke_width is 0.
  void set_default_stroke_width(double width) { default_stroke_ = width; }
  double default_stroke_width() const { return default_stroke_; }

  /// Appends raw markup to <defs> (patterns, markers).
  void add_definition(const std::string& markup);
  /// Defines a hatch pattern `id` with lines of `color`, spacing `spacing` (world units).
  void define_hatch(const std::string& id, const std::string& color, double spacing);
  /// Defines an arrowhead marker `id` of `color`.
  void define_arrow(const std::string& id, const std::string& color);

  /// Opens <g> with an optional id/class and a title (tooltip).
  void begin_group(const std::string& id, const std::string& css_class = "",
                   const std::string& title = "");
  /// Opens <g> with a transform attribute (SVG user units, y down) and an optional id/class.
  void begin_transformed_group(const std::string& transform, const std::string& id = "",
                               const std::string& css_class = "");
  /// Appends raw markup (animation elements, for instance) to the body, inside the open group.
  void raw(const std::string& markup);
  void end_group();
  /// Defines a clip path `id`: the world rectangle from (x, y) of `width` x `height`.
  void define_clip_rectangle(const std::string& id, double x, double y, double width, double height);
  /// Opens <g> clipped to the clip path `clip_id` (closed by end_group()).
  void begin_clipped_group(const std::string& clip_id);

  void path(const SvgPath& path, const SvgStyle& style, const std::string& title = "");
  void line(double x1, double y1, double x2, double y2, const SvgStyle& style);
  void circle(double cx, double cy, double r, const SvgStyle& style);
  void rectangle(double x, double y, double width, double height, const SvgStyle& style);
  /// Text at world (x, y) (baseline), `size` in world units; anchor "start", "middle", "end".
  void text(double x, double y, const std::string& content, double size,
            const std::string& anchor = "middle", const std::string& fill = "black",
            const std::string& weight = "normal");

  /// One legend row: a swatch of `style` and a label.
  struct LegendEntry {
    SvgStyle swatch;
    std::string label;
  };
  /// Draws a legend box with its top-left corner at world (x, y); rows of height `size`*1.5.
  void legend(double x, double y, const std::vector<LegendEntry>& entries, double size);
  /// Width and height (world units) of the box legend() draws for these entries.
  static std::pair<double, double> legend_size(const std::vector<LegendEntry>& entries, double size);
  /// Draws a scale bar of `length` world units from (x, y) to the right, labelled `label`.
  void scale_bar(double x, double y, double length, const std::string& label, double size);

  const SvgBox& box() const { return box_; }
  /// The complete document.
  std::string str() const;

 private:
  std::string style_attributes(const SvgStyle& style) const;
  SvgBox box_;
  double pixel_width_;
  double default_stroke_;
  std::string definitions_;
  std::string body_;
  int open_groups_ = 0;
};

/// A "nice" length near `approximate` (1, 2 or 5 times a power of ten).
double nice_length(double approximate);

}  // namespace hipair::io
