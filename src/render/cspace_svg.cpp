#include "render/cspace_svg.hpp"

#include "io/svg.hpp"
#include "render/edge_ordinates.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>

namespace hipair::render {
namespace {


constexpr double plot_size = 360;   // world units of the square plot
constexpr const char* touching_colour = "#6a1b9a";   // zero-clearance contacts

const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
                         "#17becf", "#bcbd22", "#7f7f7f", "#393b79", "#ad494a", "#637939", "#e7ba52",
                         "#7b4173", "#3182bd", "#e6550d", "#31a354", "#756bb1", "#636363"};

double to_display(AxisKind kind, bool half_turn, double chart_value) {
  if (kind == AxisKind::translation) return chart_value;
  double theta = (half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(chart_value);
  return theta * 180 / std::numbers::pi;
}
double display_x(const CSpaceChart& chart, double value) { return to_display(chart.x_kind, chart.x_half_turn, value); }
double display_y(const CSpaceChart& chart, double value) { return to_display(chart.y_kind, chart.y_half_turn, value); }

double vertex_y(const CSpaceVertex& v) {
  if (v.y_exact) return v.y.approximate();
  return Rational((v.y_lower + v.y_upper) / 2).get_d();
}

// Display range of an axis over all charts.
struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

class Painter {
 public:
  Painter(const CSpace& space, const CSpaceSvgOptions& options)
      : space_(space),
        charts_(space.charts()),
        edges_(space.edges()),
        vertices_(space.vertices()),
        pairs_(space.feature_pairs()),
        dimension_(space.dimension()),
        complete_(space.complete()),
        region_tiles_(space.statistics().region_tiles),
        options_(options) {}

  std::string run() {
    for (const auto& chart : charts_) {
      x_range_.add(display_x(chart, chart.x_lo.get_d()));
      x_range_.add(display_x(chart, chart.x_hi.get_d()));
      if (dimension_ == 2) {
        y_range_.add(display_y(chart, chart.y_lo.get_d()));
        y_range_.add(display_y(chart, chart.y_hi.get_d()));
      }
    }
    if (dimension_ == 1) {
      y_range_.lo = 0;
      y_range_.hi = 1;
    }
    chart_x_ = x_range_;
    chart_y_ = y_range_;
    zoom_to_path();
    if (options_.window) {
      const auto& w = *options_.window;
      x_range_.lo = std::max(chart_x_.lo, w[0]);
      x_range_.hi = std::min(chart_x_.hi, w[1]);
      if (dimension_ == 2) {
        y_range_.lo = std::max(chart_y_.lo, w[2]);
        y_range_.hi = std::min(chart_y_.hi, w[3]);
      }
      if (!(x_range_.lo < x_range_.hi) || !(y_range_.lo < y_range_.hi)) {
        x_range_ = chart_x_;
        y_range_ = chart_y_;
      }
    }
    const double margin = 60;
    double height = dimension_ == 2 ? plot_size : 60;
    plot_height_ = height;
    // the drawing goes first (into a buffer writer), since the legend lists what it drew and
    // the canvas is sized to hold the legend
    io::SvgWriter body({0, 0, 1, 1});
    body.set_default_stroke_width(0.6);
    if (dimension_ == 2)
      draw_2d(body);
    else
      draw_1d(body);
    std::vector<io::SvgWriter::LegendEntry> entries = legend_entries();
    touching_edges_.clear();
    touching_vertices_ = 0;
    visible_pairs_.clear();
    const double legend_text = options_.legend_text_size;
    auto [legend_width, legend_height] = io::SvgWriter::legend_size(entries, legend_text);
    double right = plot_size + 15 + legend_width + 10;
    double bottom = std::min(-margin, height - legend_height - 10);
    io::SvgBox box{-margin, bottom, right, height + 40};
    io::SvgWriter svg(box, options_.pixel_width);
    svg.set_default_stroke_width(0.6);
    svg.rectangle(-margin, bottom, right + margin, height + 40 - bottom, io::SvgStyle{"white", "none"});
    // everything over the C-space is clipped to the plotted window
    svg.define_clip_rectangle("plot-window", 0, 0, plot_size, height);
    if (!complete_ && dimension_ == 2) svg.define_hatch("not-built", "#b0b0b0", 6);
    svg.begin_clipped_group("plot-window");
    if (dimension_ == 2)
      draw_2d(svg);
    else
      draw_1d(svg);
    draw_path(svg);
    draw_marks(svg);
    svg.end_group();
    draw_axes(svg);
    svg.legend(plot_size + 15, plot_height_, entries, legend_text);
    if (!options_.title.empty()) svg.text(plot_size / 2, height + 25, options_.title, 9);
    return svg.str();
  }

 private:
  double X(double display_x) const { return (display_x - x_range_.lo) / (x_range_.hi - x_range_.lo) * plot_size; }
  double Y(double display_y) const {
    return (display_y - y_range_.lo) / (y_range_.hi - y_range_.lo) * plot_height_;
  }
  std::pair<double, double> world(const CSpaceChart& chart, double cx, double cy) const {
    return {X(display_x(chart, cx)), Y(dimension_ == 2 ? display_y(chart, cy) : 0.5)};
  }

  // With a motion path, the plotted window is the path's (and the marks') bounding box plus a
  // margin, within the charts' range (the paper's Figure 6b shows the band the motion lives
  // in). Angles are brought into the charts' range as the path is drawn.
  void zoom_to_path() {
    if (options_.path.size() < 2) return;
    Range x, y;
    for (const auto& p : options_.path) {
      auto [dx, dy] = display_of(p.x, p.y);
      if (!std::isfinite(dx) || !std::isfinite(dy)) continue;
      x.add(dx);
      y.add(dy);
    }
    for (const auto& mark : options_.marks) {
      auto [dx, dy] = display_of(mark.x, mark.y);
      if (!std::isfinite(dx) || !std::isfinite(dy)) continue;
      x.add(dx);
      y.add(dy);
    }
    if (!(x.lo <= x.hi)) return;
    auto zoom = [](Range& window, const Range& path, const Range& chart) {
      double span = path.hi - path.lo, full = chart.hi - chart.lo;
      // a margin of 8 % of the path's extent, at least 0.5 % of the charts' (1.8 deg of a
      // turn: a path along a contact curve, or at rest, still shows its neighbourhood)
      double pad = std::max(0.08 * span, 0.005 * full);
      double lo = std::max(chart.lo, path.lo - pad), hi = std::min(chart.hi, path.hi + pad);
      if (hi - lo >= 0.85 * full) return;   // nearly everything: show the whole range
      window.lo = lo;
      window.hi = hi;
    };
    zoom(x_range_, x, chart_x_);
    if (dimension_ == 2) zoom(y_range_, y, chart_y_);
  }

  bool zoomed() const {
    return x_range_.lo != chart_x_.lo || x_range_.hi != chart_x_.hi || y_range_.lo != chart_y_.lo ||
           y_range_.hi != chart_y_.hi;
  }

  // Whether a polyline (world coordinates) meets the plotted window.
  bool meets_window(const std::vector<std::pair<double, double>>& world_points) const {
    const double w = plot_size, h = plot_height_;
    auto inside = [&](double x, double y) { return x >= 0 && x <= w && y >= 0 && y <= h; };
    for (std::size_t i = 0; i < world_points.size(); ++i) {
      auto [x0, y0] = world_points[i];
      if (inside(x0, y0)) return true;
      if (i + 1 == world_points.size()) break;
      auto [x1, y1] = world_points[i + 1];
      // Liang-Barsky: the parameter interval of the segment inside the window
      double t0 = 0, t1 = 1, dx = x1 - x0, dy = y1 - y0;
      bool out = false;
      for (auto [p, q] : {std::pair{-dx, x0}, std::pair{dx, w - x0}, std::pair{-dy, y0}, std::pair{dy, h - y0}}) {
        if (p == 0) {
          if (q < 0) out = true;
          continue;
        }
        double t = q / p;
        if (p < 0)
          t0 = std::max(t0, t);
        else
          t1 = std::min(t1, t);
      }
      if (!out && t0 <= t1) return true;
    }
    return false;
  }

  bool edge_visible(std::size_t e) {
    const CSpaceChart& chart = charts_[edges_[e].chart];
    std::vector<std::pair<double, double>> points;
    for (const auto& p : samples(e)) points.push_back(world(chart, p.first, p.second));
    return meets_window(points);
  }

  // Points along an edge in chart coordinates, from its source (lexicographically smaller) to
  // its target vertex.
  const std::vector<std::pair<double, double>>& samples(std::size_t edge_index) {
    auto it = samples_.find(edge_index);
    if (it != samples_.end()) return it->second;
    const CSpaceEdge& edge = edges_[edge_index];
    const CSpaceChart& chart = charts_[edge.chart];
    std::vector<std::pair<double, double>> points;
    const auto [xa, ya] = vertex_point(edge.source);
    const auto [xb, yb] = vertex_point(edge.target);
    points.emplace_back(xa, ya);
    if (!edge.vertical) {
      auto [wa_x, wa_y] = world(chart, xa, ya);
      auto [wb_x, wb_y] = world(chart, xb, yb);
      double length = std::hypot(wb_x - wa_x, wb_y - wa_y);
      int n = std::clamp(static_cast<int>(length / 3), 1, 24);
      std::vector<double> xs;
      for (int i = 1; i < n; ++i) xs.push_back(xa + (xb - xa) * i / n);
      // the ordinates in certified doubles where they decide every printed digit and every
      // window test as the exact ordinate would (edge_ordinates.hpp), else exactly
      std::optional<EdgeOrdinates> fast;
      if (dimension_ == 2 && !xs.empty() && options_.certified_samples) fast.emplace(space_, edge_index, xs);
      for (std::size_t i = 0; i < xs.size(); ++i) {
        const double x = xs[i];
        if (fast && i == xs.size() / 2 && fast->reference()) {
          points.emplace_back(x, fast->reference()->value);
          continue;
        }
        if (fast)
          if (std::optional<DoubleRange> y = fast->enclose(x))
            if (std::optional<double> drawn = drawn_ordinate(chart, *y)) {
              points.emplace_back(x, *drawn);
              continue;
            }
        try {
          points.emplace_back(x, space_.evaluate(edge_index, x).value);
        } catch (const Error&) {
        }
      }
    }
    points.emplace_back(xb, yb);
    return samples_.emplace(edge_index, std::move(points)).first->second;
  }

  // A double inside a certified enclosure `y` of an edge's exact ordinate (chart coordinates)
  // to draw instead of the exact path's (CSpace::evaluate: within 2^-55 max(1, |y|) plus a unit
  // in the last place of the exact value), when every double that path could return prints
  // the same drawing coordinate and lies on the same side of the plotted window's bottom and
  // top: the drawing's y is monotone in the ordinate, so the picture is the same; nullopt when
  // that is not certain (a rounding boundary or the window's edge inside the enclosure).
  std::optional<double> drawn_ordinate(const CSpaceChart& chart, const DoubleRange& y) const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double m = std::max({1.0, std::fabs(y.lo), std::fabs(y.hi)});
    const double lo = std::nextafter(y.lo - m * 0x1p-50, -inf), hi = std::nextafter(y.hi + m * 0x1p-50, inf);
    const double wlo = Y(display_y(chart, lo)), whi = Y(display_y(chart, hi));
    if (!std::isfinite(wlo) || !std::isfinite(whi) || !(wlo <= whi)) return std::nullopt;
    if (io::format_number(-wlo) != io::format_number(-whi)) return std::nullopt;
    for (double bound : {0.0, plot_height_})
      if ((wlo < bound) != (whi < bound) || (wlo > bound) != (whi > bound)) return std::nullopt;
    const double middle = y.lo + (y.hi - y.lo) / 2;
    if (!(middle >= y.lo && middle <= y.hi)) return std::nullopt;
    return middle;
  }

  // A vertex's drawing coordinates (x approximated, vertex_y), computed once per vertex: the
  // edges meeting at it draw the same doubles.
  std::pair<double, double> vertex_point(std::size_t v) {
    if (vertex_points_.empty()) vertex_points_.resize(vertices_.size());
    std::optional<std::pair<double, double>>& point = vertex_points_[v];
    if (!point) point = std::pair<double, double>{vertices_[v].x.approximate(), vertex_y(vertices_[v])};
    return *point;
  }

  void draw_2d(io::SvgWriter& svg) {
    // an operating region: what was not built is hatched, free faces drawn white over it
    if (!complete_) {
      svg.rectangle(0, 0, plot_size, plot_height_, io::SvgStyle{"url(#not-built)", "none"});
    }
    // blocked (and touching) faces
    for (std::size_t c = 0; c < charts_.size(); ++c) {
      const std::vector<CSpaceFace> faces = space_.faces(c);
      for (std::size_t k = 0; k < faces.size(); ++k) {
        const CSpaceFace& face = faces[k];
        if (!face.classified || (face.kind == CellKind::free && complete_)) continue;
        const io::SvgPath* path = face_path(c, k, face);
        if (!path) continue;
        std::string colour = face.kind == CellKind::blocked ? "#c8c8c8" : face.kind == CellKind::touching ? "#f4d35e" : "white";
        io::SvgStyle style{colour, colour};   // stroked too, to hide seams between faces
        style.stroke_width = 0.35;
        style.fill_rule = "evenodd";
        svg.path(*path, style);
      }
    }
    // edges: contact edges coloured by feature pair, seams dashed, limits black
    {
      for (std::size_t e = 0; e < edges_.size(); ++e) {
        const CSpaceEdge& edge = edges_[e];
        io::SvgStyle style{"none", "black"};
        std::string title;
        if (zoomed() && !edge_visible(e)) continue;
        if (edge.role == EdgeRole::touching) {
          // a zero-clearance channel: drawn after the faces, as a dark band with a white core
          touching_edges_.push_back(e);
          continue;
        }
        if (edge.role == EdgeRole::contact || (edge.real && !edge.curves.empty())) {
          std::size_t pair = edge.curves.empty() ? 0 : edge.curves.front();
          style.stroke = colour_of(pair);
          for (std::size_t k : edge.curves) visible_pairs_.insert(k);
          style.stroke_width = 1.1;
          for (std::size_t k : edge.curves) title += (title.empty() ? "" : "; ") + pairs_[k].label;
        } else if (edge.role == EdgeRole::seam) {
          if (!complete_) continue;   // tiles of an operating region meet everywhere
          style.stroke = "#555555";
          style.dash = "3 2";
          style.stroke_width = 0.4;
        } else if (edge.role == EdgeRole::limit) {
          style.stroke_width = complete_ ? 0.8 : 0.3;
          if (!complete_) style.stroke = "#707070";
        } else if (options_.show_spurious) {
          style.stroke = "#999999";
          style.stroke_width = 0.25;
        } else {
          continue;
        }
        svg.path(edge_path(e), style, title);
      }
    }
    draw_touching(svg);
  }

  // Face k of chart c as a drawing path through its boundary's samples, or nullptr when it lies
  // outside the plotted window. Made once: run() draws twice (the first time to learn the
  // legend), and the second drawing writes the same paths.
  const io::SvgPath* face_path(std::size_t c, std::size_t k, const CSpaceFace& face) {
    auto [slot, made] = face_paths_.try_emplace({c, k});
    if (!made) return slot->second ? &*slot->second : nullptr;
    const CSpaceChart& chart = charts_[c];
    io::SvgPath path;
    Range fx, fy;   // the face's extent (world), to leave out faces outside the window
    for (const auto& component : face.boundary) {
      bool first = true;
      for (auto [e, forward] : component) {
        const auto& points = samples(e.index());
        for (std::size_t j = 0; j < points.size(); ++j) {
          const auto& p = forward ? points[j] : points[points.size() - 1 - j];
          auto [wx, wy] = world(chart, p.first, p.second);
          fx.add(wx);
          fy.add(wy);
          if (first) {
            path.move_to(wx, wy);
            first = false;
          } else {
            path.line_to(wx, wy);
          }
        }
      }
      if (!first) path.close();
    }
    if (fx.hi < 0 || fx.lo > plot_size || fy.hi < 0 || fy.lo > plot_height_) return nullptr;
    slot->second = std::move(path);
    return &*slot->second;
  }

  // An edge as a drawing path through its samples (made once, as face_path).
  const io::SvgPath& edge_path(std::size_t e) {
    auto [slot, made] = edge_paths_.try_emplace(e);
    if (made) slot->second = make_edge_path(e);
    return slot->second;
  }

  io::SvgPath make_edge_path(std::size_t e) {
    const CSpaceChart& chart = charts_[edges_[e].chart];
    io::SvgPath path;
    bool first = true;
    for (const auto& p : samples(e)) {
      auto [wx, wy] = world(chart, p.first, p.second);
      if (first) {
        path.move_to(wx, wy);
        first = false;
      } else {
        path.line_to(wx, wy);
      }
    }
    return path;
  }

  // Zero-clearance contacts (EdgeRole::touching edges, CSpaceVertex::touching vertices): the
  // parts only touch there, with blocked space on every side.
  void draw_touching(io::SvgWriter& svg) {
    for (std::size_t e : touching_edges_) {
      const CSpaceEdge& edge = edges_[e];
      std::string title = "touching (zero clearance): ";
      for (std::size_t k = 0; k < edge.curves.size(); ++k) title += (k ? "; " : "") + pairs_[edge.curves[k]].label;
      const io::SvgPath& path = edge_path(e);
      io::SvgStyle band{"none", touching_colour};
      band.stroke_width = 2.2;
      svg.path(path, band, title);
      io::SvgStyle core{"none", "white"};
      core.stroke_width = 0.7;
      svg.path(path, core);
    }
    for (std::size_t v = 0; v < vertices_.size(); ++v) {
      const CSpaceVertex& vertex = vertices_[v];
      if (!vertex.touching) continue;
      const CSpaceChart& chart = charts_[vertex.chart];
      const auto [x, y] = vertex_point(v);
      auto [wx, wy] = world(chart, x, y);
      if (wx < 0 || wx > plot_size || wy < 0 || wy > plot_height_) continue;
      io::SvgStyle dot{"white", touching_colour};
      dot.stroke_width = 1.2;
      svg.circle(wx, wy, 2.4, dot);
      ++touching_vertices_;
    }
  }

  void draw_1d(io::SvgWriter& svg) {
    for (std::size_t c = 0; c < charts_.size(); ++c) {
      const CSpaceChart& chart = charts_[c];
      std::vector<CSpaceFace> faces = space_.faces(c);
      for (const CSpaceFace& face : faces) {
        if (!face.classified) continue;
        double lo = face.lower.valid() ? vertices_[face.lower.index()].x.approximate() : chart.x_lo.get_d();
        double hi = face.upper.valid() ? vertices_[face.upper.index()].x.approximate() : chart.x_hi.get_d();
        double a = X(display_x(chart, lo)), b = X(display_x(chart, hi));
        std::string fill = face.kind == CellKind::blocked ? "#c8c8c8" : face.kind == CellKind::touching ? "#f4d35e" : "white";
        svg.rectangle(a, 0, b - a, plot_height_, io::SvgStyle{fill, "none"});
      }
      for (const CSpaceFace& face : faces) {
        if (!face.upper.valid()) continue;
        const CSpaceVertex& vertex = vertices_[face.upper.index()];
        double x = X(display_x(chart, vertex.x.approximate()));
        io::SvgStyle style{"none", vertex.curves.empty() ? "black" : colour_of(vertex.curves.front())};
        style.stroke_width = 1.2;
        svg.line(x, 0, x, plot_height_, style);
      }
    }
  }

  // Contact curves are coloured by the kind of contact (vertex-segment, arc-arc, ...): a
  // colour per feature pair repeats and cannot be told apart once there are dozens of pairs.
  std::string colour_of(std::size_t pair) {
    return palette[static_cast<std::size_t>(pairs_[pair].kind) % (sizeof(palette) / sizeof(palette[0]))];
  }

  void draw_axes(io::SvgWriter& svg) {
    io::SvgStyle frame{"none", "black"};
    frame.stroke_width = 0.8;
    svg.rectangle(0, 0, plot_size, plot_height_, frame);
    const CSpaceChart& first = charts_.front();
    auto ticks = [&](bool x_axis, const Range& range, bool rotation) {
      double step = io::nice_length((range.hi - range.lo) / 6);
      if (rotation) {   // degrees: steps of 1, 2, 5, 10, 15, 30, 45 or 90 (finer: a nice length)
        double span = range.hi - range.lo;
        for (double candidate : {1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0})
          if (span / candidate <= 9) {
            step = span >= 5 ? candidate : step;
            break;
          }
      }
      double first = std::ceil(range.lo / step - 1e-9);
      // by index, with tolerances relative to the step: `v += step` never ends where step is
      // below the spacing of doubles at v, and a range of 1e-300 mm gets its ticks and ends
      for (int i = 0; i <= 100; ++i) {
        double v = (first + i) * step;
        if (!(v <= range.hi + step * 1e-9)) break;
        io::SvgStyle tick{"none", "black"};
        tick.stroke_width = 0.5;
        if (x_axis) {
          svg.line(X(v), 0, X(v), -4, tick);
          svg.text(X(v), -12, io::format_number(std::round(v / step) * step), 7);
        } else {
          svg.line(0, Y(v), -4, Y(v), tick);
          svg.text(-6, Y(v) - 2.5, io::format_number(std::round(v / step) * step), 7, "end");
        }
      }
    };
    bool x_rotation = first.x_kind == AxisKind::rotation;
    ticks(true, x_range_, x_rotation);
    svg.text(plot_size / 2, -26,
             options_.x_axis_label.empty() ? space_.x_part() + (x_rotation ? " angle (deg)" : " offset (mm)") : options_.x_axis_label, 8);
    if (dimension_ == 2) {
      bool y_rotation = first.y_kind == AxisKind::rotation;
      ticks(false, y_range_, y_rotation);
      svg.text(-30, plot_height_ + 8,
               options_.y_axis_label.empty() ? space_.y_part() + (y_rotation ? " angle (deg)" : " offset (mm)") : options_.y_axis_label,
               8, "start");
    }
  }

  // Part coordinates to display coordinates, angles brought into the plotted window.
  std::pair<double, double> display_of(double px, double py) const {
    bool x_rotates = charts_.front().x_kind == AxisKind::rotation;
    bool y_rotates = dimension_ == 2 && charts_.front().y_kind == AxisKind::rotation;
    double x = x_rotates ? px * 180 / std::numbers::pi : px;
    double y = dimension_ == 2 ? (y_rotates ? py * 180 / std::numbers::pi : py) : 0;
    if (x_rotates) x = chart_x_.lo + std::fmod(std::fmod(x - chart_x_.lo, 360.0) + 360.0, 360.0);
    if (y_rotates) y = chart_y_.lo + std::fmod(std::fmod(y - chart_y_.lo, 360.0) + 360.0, 360.0);
    return {x, y};
  }

  void draw_path(io::SvgWriter& svg) {
    const auto& path = options_.path;
    if (path.size() < 2) return;
    auto style_of = [](bool contact) {
      io::SvgStyle style{"none", contact ? "#d62728" : "#1f4e9c"};
      style.stroke_width = 1.4;
      return style;
    };
    io::SvgPath polyline;
    bool open = false, contact = path.front().contact;
    std::pair<double, double> previous{};
    auto flush = [&] {
      if (open) svg.path(polyline, style_of(contact));
      polyline = io::SvgPath();
      open = false;
    };
    for (std::size_t i = 0; i < path.size(); ++i) {
      auto point = display_of(path[i].x, path[i].y);
      double wx = X(point.first), wy = dimension_ == 2 ? Y(point.second) : plot_height_ / 2;
      bool wraps = open && (std::fabs(point.first - previous.first) > 180 || std::fabs(point.second - previous.second) > 180);
      if (open && path[i].break_before) flush();
      if (open && (wraps || path[i].contact != contact)) {
        if (!wraps) polyline.line_to(wx, wy);   // the segment ends where the contact changes
        flush();
      }
      if (!open) {
        polyline.move_to(wx, wy);
        open = true;
        contact = path[i].contact;
      } else {
        polyline.line_to(wx, wy);
      }
      previous = point;
    }
    flush();
  }

  void draw_marks(io::SvgWriter& svg) {
    for (const auto& mark : options_.marks) {
      auto [x, y] = display_of(mark.x, mark.y);   // angles brought into the charts' range
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      double wy = dimension_ == 2 ? Y(y) : plot_height_ / 2;
      svg.circle(X(x), wy, 2.5, io::SvgStyle{"black", "white"});
      if (!mark.label.empty()) svg.text(X(x) + 4, wy + 3, mark.label, 6, "start");
    }
  }

  // The legend: shading, the path, and the contact curves drawn in the window, grouped by
  // kind of contact (one colour each), a few feature pairs per kind and "+N more".
  std::vector<io::SvgWriter::LegendEntry> legend_entries() const {
    std::vector<io::SvgWriter::LegendEntry> entries;
    entries.push_back({io::SvgStyle{"#c8c8c8", "none"}, "blocked"});
    entries.push_back({io::SvgStyle{"white", "black"}, "free"});
    if (!complete_)
      entries.push_back({io::SvgStyle{"url(#not-built)", "#b0b0b0"},
                         "not built (outside the " + std::to_string(region_tiles_) + " tiles of the operating region)"});
    if (!touching_edges_.empty() || touching_vertices_ > 0) {
      io::SvgStyle swatch{"none", touching_colour};
      swatch.stroke_width = 2.2;
      entries.push_back({swatch, "touching, zero clearance (blocked on both sides):"});
      // the feature pairs that touch along the channels
      std::vector<std::size_t> pairs;
      for (std::size_t e : touching_edges_)
        for (std::size_t k : edges_[e].curves)
          if (std::find(pairs.begin(), pairs.end(), k) == pairs.end()) pairs.push_back(k);
      for (std::size_t i = 0; i < pairs.size() && i < max_pairs_per_kind; ++i)
        entries.push_back({swatch, "  " + shortened(pairs_[pairs[i]].label)});
      if (pairs.size() > max_pairs_per_kind)
        entries.push_back({io::SvgStyle{"none", "none"}, "  +" + std::to_string(pairs.size() - max_pairs_per_kind) + " more"});
    }
    if (options_.path.size() >= 2) {
      io::SvgStyle free{"none", "#1f4e9c"}, contact{"none", "#d62728"};
      free.stroke_width = contact.stroke_width = 1.5;
      entries.push_back({free, "motion path, parts apart"});
      entries.push_back({contact, "motion path, in contact"});
    }
    std::map<ContactKind, std::vector<std::size_t>> by_kind;
    for (std::size_t k : visible_pairs_) by_kind[pairs_[k].kind].push_back(k);
    if (!by_kind.empty())
      entries.push_back({io::SvgStyle{"none", "none"}, std::string("contact curves") + (zoomed() ? " in view" : "") +
                                                           " (" + std::to_string(visible_pairs_.size()) + " feature pairs):"});
    for (const auto& [kind, pairs] : by_kind) {
      io::SvgStyle swatch{"none", palette[static_cast<std::size_t>(kind) % (sizeof(palette) / sizeof(palette[0]))]};
      swatch.stroke_width = 1.5;
      entries.push_back({swatch, std::string(to_string(kind)) + " (" + std::to_string(pairs.size()) + ")" +
                                     (options_.legend_pairs_per_kind > 0 ? ":" : "")});
      const std::size_t listed = options_.legend_pairs_per_kind;
      for (std::size_t i = 0; i < pairs.size() && i < listed; ++i)
        entries.push_back({swatch, "  " + shortened(pairs_[pairs[i]].label)});
      if (listed > 0 && pairs.size() > listed)
        entries.push_back({io::SvgStyle{"none", "none"}, "  +" + std::to_string(pairs.size() - listed) + " more"});
    }
    return entries;
  }

  // A feature-pair label cut to a readable length (the curves' tooltips have it in full).
  static std::string shortened(const std::string& label) {
    constexpr std::size_t longest = 72;
    if (label.size() <= longest) return label;
    std::size_t cut = longest - 3;
    while (cut > 0 && (static_cast<unsigned char>(label[cut]) & 0xC0) == 0x80) --cut;   // UTF-8 boundary
    return label.substr(0, cut) + "...";
  }

  static constexpr std::size_t max_pairs_per_kind = 3;

  const CSpace& space_;
  const std::vector<CSpaceChart>& charts_;
  const std::vector<CSpaceEdge>& edges_;
  const std::vector<CSpaceVertex>& vertices_;
  const std::vector<FeaturePair>& pairs_;
  int dimension_ = 2;
  bool complete_ = true;
  std::size_t region_tiles_ = 0;   // tiles built of an operating region
  const CSpaceSvgOptions& options_;
  Range x_range_, y_range_;   // the plotted window (display units)
  Range chart_x_, chart_y_;   // the charts' whole range
  double plot_height_ = plot_size;
  std::map<std::size_t, std::vector<std::pair<double, double>>> samples_;   // per edge
  std::vector<std::optional<std::pair<double, double>>> vertex_points_;   // per vertex, once drawn
  std::map<std::pair<std::size_t, std::size_t>, std::optional<io::SvgPath>> face_paths_;   // (chart, face): nullopt outside
  std::map<std::size_t, io::SvgPath> edge_paths_;
  std::set<std::size_t> visible_pairs_;   // feature pairs of the contact curves drawn
  std::vector<std::size_t> touching_edges_;   // edges
  std::size_t touching_vertices_ = 0;
};

}  // namespace

std::string cspace_svg(const CSpace& space, const CSpaceSvgOptions& options) {
  Painter painter(space, options);
  return painter.run();
}

}  // namespace hipair::render
