// `hipair show MODEL --svg OUT [--config part=value,...] [--labels]`: draws the mechanism at
// its initial configuration (or the one given) as an SVG picture.
#include "cli/commands.hpp"

#include "core/angle_limits.hpp"
#include "io/atomic_file.hpp"
#include "io/output_paths.hpp"
#include "render/mechanism_svg.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

namespace hipair::cli {
namespace {

struct ShowOptions {
  std::string model;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string rounding;
  std::string svg;
  std::vector<std::string> configuration;
  bool labels = false;
  double width = 900;
};

// An angle in the model's angle unit, or with an explicit "deg"/"rad" suffix, to rad.
Rational angle_value(const std::string& text, const std::string& unit, const std::string& item) {
  const auto [body, suffix] = split_unit_suffix(text, {"deg", "rad"}, unit);
  Rational value;
  try {
    value = parse_rational(body);
  } catch (const Error&) {
    throw ModelError("", "--config " + item + ": '" + text + "' is not a number");
  }
  if (suffix != "deg") return value;
  return degrees_to_radians(value);
}

Rational length_value(const std::string& text, const std::string& item) {
  try {
    return parse_rational(trim(text));
  } catch (const Error&) {
    throw ModelError("", "--config " + item + ": '" + text + "' is not a number");
  }
}

// Applies "part=value" or "part.coordinate=value" items (comma separated lists allowed).
void apply_configuration(const Model& model, const std::vector<std::string>& items,
                         std::vector<PartConfiguration>& configurations) {
  OnceEach once("--config", "coordinate");   // part.coordinate, once (`driver=1,driver.angle=2` is a repeat)
  for (const std::string& list : items) {
    std::stringstream stream(list);
    std::string item;
    while (std::getline(stream, item, ',')) {
      item = trim(item);
      if (item.empty()) continue;
      std::size_t equals = item.find('=');
      if (equals == std::string::npos)
        throw ModelError("", "--config expects part=value, got '" + item + "'");
      std::string name = trim(item.substr(0, equals));
      std::string value = item.substr(equals + 1);
      std::string coordinate;
      std::size_t dot = name.rfind('.');
      if (dot != std::string::npos && !model.find_part(name)) {
        coordinate = name.substr(dot + 1);
        name = name.substr(0, dot);
      }
      std::optional<std::size_t> index = model.find_part(name);
      if (!index) throw ModelError("", "--config: no part named '" + name + "'");
      const Motion& motion = model.parts[*index].motion;
      PartConfiguration& c = configurations[*index];
      if (coordinate.empty()) {
        switch (motion.kind) {
          case Motion::Kind::rotation:
          case Motion::Kind::pin_slot: coordinate = "angle"; break;
          case Motion::Kind::translation: coordinate = "offset"; break;
          case Motion::Kind::planar:
            throw ModelError("", "--config: part '" + name +
                                     "' moves in the plane: give part.x=, part.y=, part.angle=");
          case Motion::Kind::fixed:
            throw ModelError("", "--config: part '" + name + "' is fixed");
        }
      }
      once.add(name + "." + coordinate, item);
      bool has_angle = motion.kind == Motion::Kind::rotation ||
                       motion.kind == Motion::Kind::planar ||
                       motion.kind == Motion::Kind::pin_slot;
      bool has_offset =
          motion.kind == Motion::Kind::translation || motion.kind == Motion::Kind::pin_slot;
      bool planar = motion.kind == Motion::Kind::planar;
      if (coordinate == "angle" && has_angle) {
        c.angle = angle_value(value, model.angle_unit, item);
      } else if (coordinate == "offset" && has_offset) {
        c.offset = length_value(value, item);
      } else if (coordinate == "x" && planar) {
        c.x = length_value(value, item);
      } else if (coordinate == "y" && planar) {
        c.y = length_value(value, item);
      } else {
        throw ModelError("", "--config: part '" + name + "' has no coordinate '" + coordinate +
                                 "'");
      }
    }
  }
}

// The configuration drawn must be one the mechanism can take: a part placed outside its motion
// limits is refused, as the reader refuses such an initial configuration and `certify --at`
// such a position (until session 56 `--config lever=1e400` drew the lever through its stop,
// exit 0). Exact, allowing for the roundings of the limits as read (rounding_slack) and of a
// degree value (below 1e-18 rad, degrees_to_radians), so that a part placed at a limit written
// the same way is inside: a rotating part's angle against its limits as written (they bound the
// unwrapped angle), a pin-slot part's modulo whole turns (initial_angle_within_limits, as the
// reader), offsets against their limits. Parts left at their initial configuration were checked
// by the reader.
void refuse_outside_limits(const Model& model, const std::vector<PartConfiguration>& configurations) {
  const Rational degree_rounding(1, 1000000000000000000ul);
  for (std::size_t k = 0; k < model.parts.size(); ++k) {
    const Part& part = model.parts[k];
    const Motion& motion = part.motion;
    const PartConfiguration& c = configurations[k];
    if (c.angle == part.initial.angle && c.offset == part.initial.offset) continue;
    auto slack = [&](const char* limits) {
      return motion.pointer.empty() ? Rational(0) : rounding_slack(model.roundings, motion.pointer + limits);
    };
    auto text = [](const RationalInterval& limits, const char* unit) {
      return "[" + to_decimal_string(limits.lo) + ", " + to_decimal_string(limits.hi) + "] " + unit;
    };
    const bool pin_slot = motion.kind == Motion::Kind::pin_slot;
    if (motion.angle_limits && (motion.kind == Motion::Kind::rotation || pin_slot)) {
      const RationalInterval& limits = *motion.angle_limits;
      bool inside;
      if (pin_slot) {
        inside = initial_angle_within_limits(c.angle, limits, pin_slot_limits_slack(model.roundings, motion), degree_rounding);
      } else {
        const Rational allowed = slack("/rotation/limits/") + degree_rounding;
        inside = limits.lo - allowed <= c.angle && c.angle <= limits.hi + allowed;
      }
      if (!inside)
        throw ModelError("", "--config: part '" + part.name + "' at " + to_decimal_string(c.angle) +
                                 " rad lies outside its angle limits " + text(limits, "rad") +
                                 (pin_slot ? ", also after whole turns" : ""));
    }
    if (motion.translation_limits && (motion.kind == Motion::Kind::translation || pin_slot)) {
      const Rational allowed = slack(pin_slot ? "/pin_slot/limits/" : "/translation/limits/");
      if (c.offset < motion.translation_limits->lo - allowed || c.offset > motion.translation_limits->hi + allowed)
        throw ModelError("", "--config: part '" + part.name + "' at offset " + to_decimal_string(c.offset) +
                                 " mm lies outside its motion limits " + text(*motion.translation_limits, "mm"));
    }
  }
}

int run_show(const ShowOptions& options) {
  io::refuse_overwriting_input(options.svg, "--svg", options.model);
  io::refuse_unusable_output_files({{options.svg, "--svg"}});   // before reading and drawing
  auto rounding = rounding_scope(options.rounding);
  ReadOptions overrides = parameter_overrides(options.overrides, options.allow_out_of_tolerance);
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  Model model = read_model_file(options.model, overrides);
  std::vector<PartConfiguration> configurations;
  for (const Part& part : model.parts) configurations.push_back(part.initial);
  apply_configuration(model, options.configuration, configurations);
  refuse_outside_limits(model, configurations);
  render::MechanismSvgOptions drawing;
  drawing.labels = options.labels;
  drawing.pixel_width = options.width;
  std::string svg = render::mechanism_svg(model, configurations, drawing);
  io::write_file_atomically(options.svg, svg);
  std::cout << "wrote " << options.svg << " (" << model.parts.size() << " parts of '"
            << shown_name(model.name) << "')\n";
  return 0;
}

}  // namespace

void register_show(CLI::App& app, Action& action) {
  auto options = std::make_shared<ShowOptions>();
  CLI::App* command =
      app.add_subcommand("show", "Draw a mechanism at its initial (or a given) configuration");
  command->add_option("model", options->model, "model file (JSON, see docs/model-format.md)")
      ->required();
  add_parameter_options(command, options->overrides, options->allow_out_of_tolerance);
  add_rounding_option(command, options->rounding);
  command->add_option("--svg", options->svg, "output SVG file (written atomically)")->required()->check(output_path());
  command->add_option("--config", options->configuration,
                      "part configuration: part=value (angle in the model's angle unit, or with "
                      "a deg/rad suffix; offset in mm), part.x=, part.y=, part.angle=; comma "
                      "separated")
      ->delimiter(',');
  command->add_flag("--labels", options->labels, "write the feature label of every edge");
  command->add_option("--width", options->width, "picture width in pixels (default 900)")
      ->check(real_range(100.0, 20000.0));
  command->callback([&action, options] { action = [options] { return run_show(*options); }; });
}

}  // namespace hipair::cli
