#include "render/mechanism_svg.hpp"

#include "io/svg.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <gmpxx.h>
#include <mpfr.h>
#include <cmath>
#include <cstdio>
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

double to_number(const Rational& q) { return to_double(q); }

// The drawing's coordinates: a world point q (exact, anywhere from 1e-300 to 1e400 mm) is drawn
// at (q - origin) / 10^k, computed exactly and rounded once to double, so every picture is
// normalised to a few hundred units whatever the model's scale.
struct Normalisation {
  Rational origin_x, origin_y;
  Rational inverse_scale = Rational(1);  // 10^-k
  long k = 0;
  double x(const Rational& q) const { return to_double(Rational((q - origin_x) * inverse_scale)); }
  double y(const Rational& q) const { return to_double(Rational((q - origin_y) * inverse_scale)); }
  double length(const Rational& q) const { return to_double(Rational(q * inverse_scale)); }
};

Rational power_of_ten(long exponent) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(exponent < 0 ? -exponent : exponent));
  return exponent < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

// floor(log10(|q|)) for q != 0, to within one (drawing scale only).
long decimal_exponent(const Rational& q) {
  mpfr_t value;
  mpfr_init2(value, 64);
  mpfr_set_q(value, q.get_mpq_t(), MPFR_RNDN);
  mpfr_abs(value, value, MPFR_RNDN);
  mpfr_log10(value, value, MPFR_RNDN);
  long exponent = mpfr_get_si(value, MPFR_RNDD);
  mpfr_clear(value);
  return exponent;
}

Normalisation normalisation_of(const Model& model, const std::vector<PartConfiguration>& configurations,
                               const std::vector<MechanismFrame>* frames = nullptr) {
  Normalisation n;
  bool have_origin = false;
  for (const Part& part : model.parts)
    for (const Loop& loop : part.loops)
      if (!have_origin && !loop.edges.empty()) {
        n.origin_x = loop.edges.front().source.x;
        n.origin_y = loop.edges.front().source.y;
        have_origin = true;
      }
  // The largest distance (per coordinate) of anything drawn from the origin: posing moves a
  // point by at most its distance to the pivot plus the offsets, so this bounds the picture.
  Rational largest(0);
  auto consider = [&](const Rational& value) {
    Rational a = abs(value);
    if (a > largest) largest = a;
  };
  auto point = [&](const Point& p) {
    consider(Rational(p.x - n.origin_x));
    consider(Rational(p.y - n.origin_y));
  };
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    for (const Loop& loop : part.loops)
      for (const Edge& edge : loop.edges) {
        point(edge.source);
        point(edge.target);
        if (edge.is_arc()) point(edge.center);
      }
    point(part.motion.pivot);
    const PartConfiguration& c = configurations[i];
    consider(c.offset);
    consider(c.x);
    consider(c.y);
    if (frames)
      for (const MechanismFrame& frame : *frames) {
        consider(frame.configurations[i].offset);
        consider(frame.configurations[i].x);
        consider(frame.configurations[i].y);
      }
  }
  if (largest == 0) return n;
  n.k = decimal_exponent(largest) - 2;  // the picture spans about 100 to 1000 units
  n.inverse_scale = power_of_ten(-n.k);
  return n;
}

// A length of the real (unnormalised) world for a label: `value` drawing units times 10^k,
// with up to 6 significant digits, in scientific form beyond 10^6 and below 10^-4.
std::string world_text(double value, long k) {
  if (!std::isfinite(value) || value == 0) return "0";
  Rational exact = Rational(value) * power_of_ten(k);
  mpfr_t m;
  mpfr_init2(m, 64);
  mpfr_set_q(m, exact.get_mpq_t(), MPFR_RNDN);
  long exponent = decimal_exponent(exact);
  char buffer[96];
  if (exponent >= -4 && exponent < 6) mpfr_snprintf(buffer, sizeof buffer, "%.6Rg", m);
  else mpfr_snprintf(buffer, sizeof buffer, "%.5Re", m);
  mpfr_clear(m);
  std::string text = buffer;
  // "2.00000e+400" -> "2e400"
  if (auto e = text.find('e'); e != std::string::npos) {
    std::string mantissa = text.substr(0, e), power = text.substr(e + 1);
    if (mantissa.find('.') != std::string::npos) {
      while (mantissa.back() == '0') mantissa.pop_back();
      if (mantissa.back() == '.') mantissa.pop_back();
    }
    if (!power.empty() && power[0] == '+') power.erase(0, 1);
    bool negative = !power.empty() && power[0] == '-';
    if (negative) power.erase(0, 1);
    while (power.size() > 1 && power[0] == '0') power.erase(0, 1);
    text = mantissa + "e" + (negative ? "-" : "") + power;
  }
  return text;
}

std::string world_text(const Rational& value) {
  if (value == 0) return "0";
  long k = decimal_exponent(value) - 2;
  return world_text(to_double(Rational(value * power_of_ten(-k))), k);
}

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
      return "translation, s = " + world_text(c.offset) + " mm";
    case Motion::Kind::planar:
      return "planar, x = " + world_text(c.x) + ", y = " + world_text(c.y) + ", \u03b8 = " + angle_text(c.angle, unit);
    case Motion::Kind::pin_slot:
      return "pin-slot, \u03b8 = " + angle_text(c.angle, unit) +
             ", s = " + world_text(c.offset) + " mm";
  }
  return "";
}

// Moves the normalised zero-configuration point (x, y) of a part to its configuration, in
// normalised coordinates (the rotation about the normalised pivot, offsets scaled).
PosedPoint pose_normalised(const Motion& motion, const PartConfiguration& c, const Normalisation& n, double x,
                           double y) {
  double px = n.x(motion.pivot.x), py = n.y(motion.pivot.y);
  auto rotate_about_pivot = [&](double angle) {
    double dx = x - px, dy = y - py;
    double cs = std::cos(angle), sn = std::sin(angle);
    return PosedPoint{px + cs * dx - sn * dy, py + sn * dx + cs * dy};
  };
  switch (motion.kind) {
    case Motion::Kind::fixed: return PosedPoint{x, y};
    case Motion::Kind::rotation: return rotate_about_pivot(to_number(c.angle));
    case Motion::Kind::translation: {
      double s = n.length(c.offset);
      return PosedPoint{x + s * to_number(motion.direction.x), y + s * to_number(motion.direction.y)};
    }
    case Motion::Kind::planar: {
      PosedPoint p = rotate_about_pivot(to_number(c.angle));
      return PosedPoint{p.x + n.length(c.x), p.y + n.length(c.y)};
    }
    case Motion::Kind::pin_slot: {
      double angle = to_number(c.angle);
      PosedPoint p = rotate_about_pivot(angle);
      double dx = to_number(motion.direction.x), dy = to_number(motion.direction.y);
      double cs = std::cos(angle), sn = std::sin(angle), s = n.length(c.offset);
      return PosedPoint{p.x + s * (cs * dx - sn * dy), p.y + s * (sn * dx + cs * dy)};
    }
  }
  return PosedPoint{x, y};
}

PosedPoint pose_exact(const Motion& motion, const PartConfiguration& c, const Normalisation& n, const Point& p) {
  return pose_normalised(motion, c, n, n.x(p.x), n.y(p.y));
}

// Midpoint of an edge at the part's configuration, for its label.
PosedPoint edge_middle(const Part& part, const PartConfiguration& c, const Edge& edge, const Normalisation& n) {
  double sx = n.x(edge.source.x), sy = n.y(edge.source.y);
  double tx = n.x(edge.target.x), ty = n.y(edge.target.y);
  if (!edge.is_arc()) return pose_normalised(part.motion, c, n, (sx + tx) / 2, (sy + ty) / 2);
  double cx = n.x(edge.center.x), cy = n.y(edge.center.y);
  double radius = std::hypot(sx - cx, sy - cy);
  double start = std::atan2(sy - cy, sx - cx);
  double end = std::atan2(ty - cy, tx - cx);
  double span = edge.is_full_circle() ? 2 * M_PI : (edge.ccw ? end - start : start - end);
  span = std::fmod(span, 2 * M_PI);
  if (span <= 0) span += 2 * M_PI;
  double middle = start + (edge.ccw ? span / 2 : -span / 2);
  return pose_normalised(part.motion, c, n, cx + radius * std::cos(middle), cy + radius * std::sin(middle));
}


// The outline of a part at a configuration (normalised units).
io::SvgPath part_path(const Part& part, const PartConfiguration& c, const Normalisation& n) {
  io::SvgPath path;
  for (const Loop& loop : part.loops) {
    if (loop.edges.empty()) continue;
    PosedPoint start = pose_exact(part.motion, c, n, loop.edges.front().source);
    path.move_to(start.x, start.y);
    for (const Edge& edge : loop.edges) {
      PosedPoint target = pose_exact(part.motion, c, n, edge.target);
      if (edge.is_arc()) {
        PosedPoint centre = pose_exact(part.motion, c, n, edge.center);
        path.arc_to(target.x, target.y, centre.x, centre.y, edge.ccw);
      } else {
        path.line_to(target.x, target.y);
      }
    }
    path.close();
  }
  return path;
}

bool animated_motion(const Motion& motion) {
  return motion.kind == Motion::Kind::rotation || motion.kind == Motion::Kind::translation ||
         motion.kind == Motion::Kind::planar;
}

// The SVG transform (user units, y down) that takes a part drawn at its zero configuration to
// configuration c: a rotation by -theta (degrees) about the normalised pivot (y negated), or a
// translation by the normalised offset along the axis. Same numbers as pose_normalised.
// A planar part takes both: its rotation about the pivot (`planar_part` 0), then its shift (x, y)
// (`planar_part` 1).
std::string transform_value(const Motion& motion, const PartConfiguration& c, const Normalisation& n,
                            int planar_part = 0) {
  if (motion.kind == Motion::Kind::planar && planar_part == 1)
    return io::format_number(n.length(c.x)) + " " + io::format_number(-n.length(c.y));
  if (motion.kind == Motion::Kind::rotation || motion.kind == Motion::Kind::planar)
    return io::format_number(-to_number(c.angle) * 180 / M_PI) + " " + io::format_number(n.x(motion.pivot.x)) + " " +
           io::format_number(-n.y(motion.pivot.y));
  double s = n.length(c.offset);
  return io::format_number(s * to_number(motion.direction.x)) + " " +
         io::format_number(-s * to_number(motion.direction.y));
}

// A number with enough digits to keep keyTimes of up to a million frames apart.
std::string key_time(double value) {
  if (value <= 0) return "0";
  if (value >= 1) return "1";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

// <animate> of visibility, discrete: visible over [from, to) of the cycle (fractions in [0, 1]).
std::string blink(double from, double to, double duration) {
  std::string values, times;
  if (from <= 0) {
    values = "visible;hidden";
    times = "0;" + key_time(to);
  } else if (to >= 1) {
    values = "hidden;visible";
    times = "0;" + key_time(from);
  } else {
    values = "hidden;visible;hidden";
    times = "0;" + key_time(from) + ";" + key_time(to);
  }
  if (from <= 0 && to >= 1) return "";
  return "<animate attributeName=\"visibility\" calcMode=\"discrete\" values=\"" + values + "\" keyTimes=\"" +
         times + "\" dur=\"" + io::format_number(duration) + "s\" repeatCount=\"indefinite\"/>";
}

// A spring's (or damper's) zig-zag between two drawing points, as an SVG "points" value in
// the writer's user units (y negated): straight leads of a sixth of the length at each end,
// 12 zigs of half-width `amplitude` between them (the same number of points at any length, so
// frames can be interpolated).
std::string zigzag_points(PosedPoint a, PosedPoint b, double amplitude) {
  double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
  double ux = length > 0 ? dx / length : 1, uy = length > 0 ? dy / length : 0;
  const int zigs = 12;
  std::string points;
  auto add = [&](double along, double across) {
    double x = a.x + ux * along - uy * across, y = a.y + uy * along + ux * across;
    points += (points.empty() ? "" : " ") + io::format_number(x) + "," + io::format_number(-y);
  };
  add(0, 0);
  double lead = length / 6, body = length - 2 * lead;
  add(lead, 0);
  for (int k = 0; k < zigs; ++k) add(lead + body * (k + 0.5) / zigs, k % 2 == 0 ? amplitude : -amplitude);
  add(length - lead, 0);
  add(length, 0);
  return points;
}

struct Animation {
  const std::vector<MechanismFrame>& frames;
  const MechanismAnimationOptions& options;
};

std::string draw(const Model& model, const std::vector<PartConfiguration>& configurations,
                 const MechanismSvgOptions& options, const Animation* animation) {
  if (configurations.size() != model.parts.size())
    throw Error("mechanism_svg: " + std::to_string(configurations.size()) +
                " configurations for " + std::to_string(model.parts.size()) + " parts");

  // Paths of every part at its configuration, and the drawing's extent (normalised units).
  Normalisation n = normalisation_of(model, configurations, animation ? &animation->frames : nullptr);
  std::vector<io::SvgPath> paths(model.parts.size());
  std::vector<Box> part_boxes(model.parts.size());
  Box extent;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    const PartConfiguration& c = configurations[i];
    paths[i] = part_path(part, c, n);
    for (const auto& [x, y] : paths[i].extent_points()) {
      part_boxes[i].add(x, y);
      extent.add(x, y);
    }
    // an animated part: the extent covers it at every frame
    if (animation && animated_motion(part.motion))
      for (const MechanismFrame& frame : animation->frames) {
        io::SvgPath posed = part_path(part, frame.configurations[i], n);
        for (const auto& [x, y] : posed.extent_points()) extent.add(x, y);
      }
    if (part.motion.kind != Motion::Kind::fixed && part.motion.kind != Motion::Kind::translation) {
      PosedPoint pivot = pose_exact(part.motion, c, n, part.motion.pivot);
      extent.add(pivot.x, pivot.y);
    }
  }
  // springs' attachment points (a fixed attachment may lie off every part), at every frame
  if (model.simulation)
    for (const SimulationSpec::Coupling& k : model.simulation->couplings) {
      if (k.first >= model.parts.size() || k.second >= model.parts.size()) continue;
      auto add_ends = [&](const std::vector<PartConfiguration>& cs) {
        for (const PosedPoint& p : {pose_exact(model.parts[k.first].motion, cs[k.first], n, k.first_point),
                                    pose_exact(model.parts[k.second].motion, cs[k.second], n, k.second_point)})
          extent.add(p.x, p.y);
      };
      add_ends(configurations);
      if (animation)
        for (const MechanismFrame& frame : animation->frames) add_ends(frame.configurations);
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
    std::string label = part.name + " (" +
                        (animation ? motion_name(part.motion)
                                   : configuration_text(part, configurations[i], model.angle_unit)) +
                        ")";
    longest = std::max(longest, label.size());
    legend.push_back({swatch, label});
  }
  double legend_width =
      options.legend ? text_size * (2.2 + 0.62 * static_cast<double>(longest)) + margin : 0;

  io::SvgBox box;
  box.min_x = extent.min_x - margin;
  box.max_x = extent.max_x + margin + legend_width;
  box.min_y = extent.min_y - margin - text_size * 3;
  box.max_y = extent.max_y + margin + text_size * (animation ? 4.5 : 2.5);
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
      if (animation && animated_motion(part.motion)) {
        // drawn at its zero configuration, moved by the transform (the first frame's when the
        // renderer does not animate), animated through every frame
        const auto& frames = animation->frames;
        double t0 = frames.front().time, span = frames.back().time - t0;
        bool planar = part.motion.kind == Motion::Kind::planar;
        // a planar part: an outer group shifts it, an inner one turns it about its pivot
        for (int layer = planar ? 1 : 0; layer >= 0; --layer) {
          const char* type = part.motion.kind == Motion::Kind::translation || layer == 1 ? "translate" : "rotate";
          std::string values, times;
          for (std::size_t f = 0; f < frames.size(); ++f) {
            values += (f ? ";" : "") + transform_value(part.motion, frames[f].configurations[i], n, layer);
            times += (f ? ";" : "") + key_time(f + 1 == frames.size() ? 1.0 : (frames[f].time - t0) / span);
          }
          svg.begin_transformed_group(std::string(type) + "(" +
                                          transform_value(part.motion, frames.front().configurations[i], n, layer) +
                                          ")",
                                      "motion-" + part.name + (layer == 1 ? "-shift" : ""), "moving");
          svg.raw("<animateTransform attributeName=\"transform\" type=\"" + std::string(type) + "\" values=\"" +
                  values + "\" keyTimes=\"" + times + "\" dur=\"" + io::format_number(animation->options.duration) +
                  "s\" calcMode=\"linear\" repeatCount=\"indefinite\"/>\n");
        }
        svg.path(part_path(part, PartConfiguration{}, n), style, part.name);
        if (options.labels)
          for (const Loop& loop : part.loops)
            for (const Edge& edge : loop.edges) {
              if (edge.label.empty()) continue;
              PosedPoint m = edge_middle(part, PartConfiguration{}, edge, n);
              svg.text(m.x, m.y, edge.label, text_size * 0.4, "middle", "#202020");
            }
        svg.end_group();
        if (part.motion.kind == Motion::Kind::planar) svg.end_group();
      } else {
        svg.path(paths[i], style, part.name);
      }
      svg.end_group();
    }
  }

  // Springs and dampers ("simulation"/"springs"): a zig-zag between the attachment points,
  // moving with the parts in an animation (one <animate> of the points per coupling); a damper
  // alone (no stiffness) is dashed.
  if (model.simulation && !model.simulation->couplings.empty()) {
    auto attachment = [&](std::size_t part, const Point& p, const PartConfiguration& c) {
      return pose_exact(model.parts[part].motion, c, n, p);
    };
    svg.begin_group("springs", "springs");
    for (std::size_t s = 0; s < model.simulation->couplings.size(); ++s) {
      const SimulationSpec::Coupling& k = model.simulation->couplings[s];
      if (k.first >= model.parts.size() || k.second >= model.parts.size()) continue;
      double amplitude = text_size * 0.35;
      std::string first = zigzag_points(attachment(k.first, k.first_point, configurations[k.first]),
                                        attachment(k.second, k.second_point, configurations[k.second]), amplitude);
      std::string dash = k.stiffness == 0 ? " stroke-dasharray=\"" + io::format_number(text_size * 0.3) + " " +
                                                 io::format_number(text_size * 0.2) + "\""
                                           : "";
      std::string element = "<polyline class=\"spring\" points=\"" + first + "\" fill=\"none\" stroke=\"#222222\"" +
                            dash + " stroke-width=\"" + io::format_number(size / 400) +
                            "\" stroke-linejoin=\"round\"><title>" +
                            io::escape_xml((k.stiffness == 0 ? "damper " : "spring ") + model.parts[k.first].name +
                                           " - " + model.parts[k.second].name) +
                            "</title>";
      if (animation) {
        const auto& frames = animation->frames;
        double t0 = frames.front().time, span = frames.back().time - t0;
        std::string values, times;
        for (std::size_t f = 0; f < frames.size(); ++f) {
          const auto& cf = frames[f].configurations;
          values += (f ? ";" : "") + zigzag_points(attachment(k.first, k.first_point, cf[k.first]),
                                                   attachment(k.second, k.second_point, cf[k.second]), amplitude);
          times += (f ? ";" : "") + key_time(f + 1 == frames.size() ? 1.0 : (frames[f].time - t0) / span);
        }
        element += "<animate attributeName=\"points\" values=\"" + values + "\" keyTimes=\"" + times + "\" dur=\"" +
                   io::format_number(animation->options.duration) +
                   "s\" calcMode=\"linear\" repeatCount=\"indefinite\"/>";
      }
      svg.raw(element + "</polyline>\n");
    }
    svg.end_group();
  }

  // Motion marks: pivots and translation axes.
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    const PartConfiguration& c = configurations[i];
    const Motion& motion = part.motion;
    io::SvgStyle mark;
    mark.stroke = "#111111";
    mark.stroke_width = size / 700;
    // (an animated planar part's pivot moves with it: no mark left at its first place)
    bool moving_pivot = animation && motion.kind == Motion::Kind::planar;
    if ((motion.kind == Motion::Kind::rotation || motion.kind == Motion::Kind::planar ||
         motion.kind == Motion::Kind::pin_slot) && !moving_pivot) {
      PosedPoint pivot = pose_exact(motion, c, n, motion.pivot);
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
    // A part that moves its position (translating, planar) carries its name along: the name is
    // placed at the drawn configuration and shifted by the part's displacement from it in each
    // frame. A rotating part's name stays where it is (the part turns in place).
    bool carried = animation && (part.motion.kind == Motion::Kind::translation ||
                                 part.motion.kind == Motion::Kind::planar);
    if (carried) {
      const auto& frames = animation->frames;
      double t0 = frames.front().time, span = frames.back().time - t0;
      auto shift = [&](const PartConfiguration& c) {
        const PartConfiguration& c0 = configurations[i];
        if (part.motion.kind == Motion::Kind::planar)
          return io::format_number(n.length(c.x) - n.length(c0.x)) + " " +
                 io::format_number(n.length(c0.y) - n.length(c.y));
        double s = n.length(c.offset) - n.length(c0.offset);
        return io::format_number(s * to_number(part.motion.direction.x)) + " " +
               io::format_number(-s * to_number(part.motion.direction.y));
      };
      std::string values, times;
      for (std::size_t f = 0; f < frames.size(); ++f) {
        values += (f ? ";" : "") + shift(frames[f].configurations[i]);
        times += (f ? ";" : "") + key_time(f + 1 == frames.size() ? 1.0 : (frames[f].time - t0) / span);
      }
      svg.begin_transformed_group("translate(" + shift(frames.front().configurations[i]) + ")",
                                  "name-" + part.name, "moving");
      svg.raw("<animateTransform attributeName=\"transform\" type=\"translate\" values=\"" + values +
              "\" keyTimes=\"" + times + "\" dur=\"" + io::format_number(animation->options.duration) +
              "s\" calcMode=\"linear\" repeatCount=\"indefinite\"/>\n");
    }
    svg.text(best_x, best_y, part.name, text_size, "middle", "#111111", "bold");
    if (carried) svg.end_group();
  }

  // Feature labels on request.
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    if (!part_boxes[i].valid()) continue;
    if (!options.labels) continue;
    if (animation && animated_motion(part.motion)) continue;  // drawn in the moving group
    svg.begin_group("labels-" + part.name, "labels");
    for (const Loop& loop : part.loops)
      for (const Edge& edge : loop.edges) {
        if (edge.label.empty()) continue;
        PosedPoint m = edge_middle(part, configurations[i], edge, n);
        svg.text(m.x, m.y, edge.label, text_size * 0.4, "middle", "#202020");
      }
    svg.end_group();
  }

  double bar = io::nice_length(size / 5);
  svg.scale_bar(extent.min_x, box.min_y + text_size * 1.4, bar, world_text(bar, n.k) + " mm", text_size);
  if (options.legend && !legend.empty())
    svg.legend(extent.max_x + margin, extent.max_y, legend, text_size);

  if (animation) {
    const auto& frames = animation->frames;
    const MechanismAnimationOptions& a = animation->options;
    double t0 = frames.front().time, span = frames.back().time - t0;
    std::string duration = io::format_number(a.duration) + "s";
    // marks: a ring at the point, visible for mark_seconds of playback from its time
    io::SvgStyle ring;
    ring.stroke = "#d62728";
    ring.stroke_width = size / 250;
    svg.begin_group("marks", "marks");
    for (const MechanismMark& mark : a.marks) {
      if (!(mark.time >= t0 && mark.time <= frames.back().time) || !std::isfinite(mark.x) || !std::isfinite(mark.y))
        continue;
      double from = (mark.time - t0) / span, to = from + a.mark_seconds / a.duration;
      double x = n.x(Rational(mark.x)), y = n.y(Rational(mark.y)), r = text_size * 0.5;
      svg.raw("<g visibility=\"" + std::string(from <= 0 ? "visible" : "hidden") + "\">" +
              (mark.title.empty() ? "" : "<title>" + io::escape_xml(mark.title) + "</title>") + blink(from, to, a.duration));
      svg.circle(x, y, r, ring);
      svg.raw("</g>\n");
    }
    svg.end_group();
    // time readout (every k-th frame beyond max_readouts) and a progress bar
    double y = box.max_y - text_size * 3.4;
    std::size_t every = std::max<std::size_t>(1, (frames.size() + std::max<std::size_t>(a.max_readouts, 1) - 1) /
                                                     std::max<std::size_t>(a.max_readouts, 1));
    double spacing = span / static_cast<double>(frames.size() - 1) * static_cast<double>(every);
    int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(spacing))), 0, 9);
    svg.begin_group("time", "time-readout");
    std::vector<std::size_t> shown;
    for (std::size_t f = 0; f < frames.size(); f += every) shown.push_back(f);
    for (std::size_t k = 0; k < shown.size(); ++k) {
      double from = (frames[shown[k]].time - t0) / span;
      double to = k + 1 < shown.size() ? (frames[shown[k + 1]].time - t0) / span : 1.0;
      char text[96];
      std::snprintf(text, sizeof text, "t = %.*f %s", decimals, frames[shown[k]].time, a.time_unit.c_str());
      svg.raw("<g visibility=\"" + std::string(k == 0 ? "visible" : "hidden") + "\">" + blink(from, to, a.duration));
      svg.text(extent.min_x, y, text, text_size, "start", "#111111");
      svg.raw("</g>\n");
    }
    svg.end_group();
    double bar_x = extent.min_x + text_size * 11, bar_width = std::max(extent.max_x - bar_x, text_size * 5);
    double bar_height = text_size * 0.5;
    svg.rectangle(bar_x, y, bar_width, bar_height, io::SvgStyle{"#e6e6e6", "#999999", 0, "", "", 1, ""});
    // the rectangle's SVG y is -(y + height): the bar grows from its left end
    svg.raw("<rect class=\"progress\" x=\"" + io::format_number(bar_x) + "\" y=\"" +
            io::format_number(-(y + bar_height)) + "\" width=\"0\" height=\"" + io::format_number(bar_height) +
            "\" fill=\"#4e79a7\"><animate attributeName=\"width\" values=\"0;" + io::format_number(bar_width) +
            "\" keyTimes=\"0;1\" dur=\"" + duration + "\" calcMode=\"linear\" repeatCount=\"indefinite\"/></rect>\n");
  }
  return svg.str();
}

}  // namespace

PosedPoint pose_point(const Motion& motion, const PartConfiguration& c, double x, double y) {
  return pose_normalised(motion, c, Normalisation{}, x, y);
}

std::string mechanism_svg(const Model& model, const std::vector<PartConfiguration>& configurations,
                          const MechanismSvgOptions& options) {
  return draw(model, configurations, options, nullptr);
}

std::string mechanism_animation_svg(const Model& model, const std::vector<MechanismFrame>& frames,
                                    const MechanismAnimationOptions& options) {
  if (frames.size() < 2) throw Error("mechanism_animation_svg: at least two frames are needed");
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].configurations.size() != model.parts.size())
      throw Error("mechanism_animation_svg: frame " + std::to_string(f) + " has " +
                  std::to_string(frames[f].configurations.size()) + " configurations for " +
                  std::to_string(model.parts.size()) + " parts");
    if (!std::isfinite(frames[f].time) || (f > 0 && !(frames[f].time > frames[f - 1].time)))
      throw Error("mechanism_animation_svg: frame times must increase (frame " + std::to_string(f) + ")");
  }
  if (!(options.duration > 0) || !std::isfinite(options.duration))
    throw Error("mechanism_animation_svg: the playback duration must be positive");
  Animation animation{frames, options};
  return draw(model, frames.front().configurations, options.drawing, &animation);
}

}  // namespace hipair::render
