// `hipair validate MODEL`: reads a model exactly, reports every error as one line (via main)
// and, when valid, prints a summary including every value that had to be rounded.
#include "cli/commands.hpp"
#include "core/decimal_text.hpp"
#include "io/atomic_file.hpp"
#include "model/json_document.hpp"
#include "model/expression.hpp"
#include "model/interval.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <iostream>
#include <memory>
#include <cmath>
#include <sstream>

namespace hipair::cli {
namespace {

std::string number(const Rational& value) { return to_decimal_string(value, 12); }

std::string point(const Point& p) { return "(" + number(p.x) + ", " + number(p.y) + ")"; }

std::string bound(const Rational& value) {
  const double approximate = to_double(value);
  // beyond the doubles (a model at 10^400 mm: "inf" until session 53; at 10^-400: "0") the
  // decimal of the rational itself
  if (!std::isfinite(approximate) || (approximate == 0 && sgn(value) != 0)) return to_decimal_string(value, 3);
  std::ostringstream out;
  out.precision(3);
  out << approximate;
  return out.str();
}

std::string plural(std::size_t count, const std::string& word) {
  return std::to_string(count) + " " + word + (count == 1 ? "" : "s");
}

std::string interval(const RationalInterval& range) {
  auto [lo, hi] = to_decimal_strings_apart(range.lo, range.hi, 12);  // a narrow range shows as one
  return "[" + lo + ", " + hi + "]";
}

std::string describe_motion(const Motion& motion) {
  switch (motion.kind) {
    case Motion::Kind::fixed: return "fixed";
    case Motion::Kind::rotation: {
      std::string text = "rotation about " + point(motion.pivot);
      if (motion.angle_limits) text += ", angle limits " + interval(*motion.angle_limits) + " rad";
      return text;
    }
    case Motion::Kind::translation: {
      std::string text = "translation along " + point(motion.direction);
      if (motion.translation_limits) text += ", limits " + interval(*motion.translation_limits) + " mm";
      return text;
    }
    case Motion::Kind::planar: return "planar, rotations about " + point(motion.pivot);
    case Motion::Kind::pin_slot: {
      std::string text = "pin-slot: rotation about " + point(motion.pivot) + ", sliding along " +
                         point(motion.direction);
      if (motion.angle_limits) text += ", angle limits " + interval(*motion.angle_limits) + " rad";
      if (motion.translation_limits) text += ", limits " + interval(*motion.translation_limits) + " mm";
      return text;
    }
  }
  return "?";
}

void print_summary(const Model& model, const ReadOptions& options, std::ostream& out) {
  out << "model: " << shown_name(model.name) << "  (" << model.source << ")\n";
  out << "sha256: " << model.content_hash << "\n";
  for (const auto& [name, value] : options.parameter_values)
    out << "override: " << name << " = " << number(value) << "\n";
  out << "angle unit in file: " << model.angle_unit << " (stored in rad)\n";
  std::size_t toleranced = 0;
  for (const Parameter& parameter : model.parameters)
    if (parameter.range.lo != parameter.range.hi) ++toleranced;
  out << "parameters: " << model.parameters.size() << " (" << toleranced << " toleranced)\n";
  for (const Parameter& parameter : model.parameters) {
    out << "  " << shown_name(parameter.name) << " = " << number(parameter.nominal) << (parameter.is_angle ? " rad" : "");
    if (parameter.range.lo != parameter.range.hi) out << "  range " << interval(parameter.range);
    if (parameter.distribution == Parameter::Distribution::uniform) out << "  uniform";
    if (parameter.distribution == Parameter::Distribution::normal)
      out << "  normal sigma " << number(*parameter.sigma);
    out << "\n";
  }
  out << "parts: " << model.parts.size() << "\n";
  for (const Part& part : model.parts) {
    std::size_t segments = 0, arcs = 0, holes = 0;
    for (const Loop& loop : part.loops) {
      if (loop.is_hole) ++holes;
      for (const Edge& edge : loop.edges) (edge.is_arc() ? arcs : segments)++;
    }
    out << "  " << shown_name(part.name) << ": " << describe_motion(part.motion) << "\n";
    out << "    " << plural(part.loops.size(), "loop") << " (" << plural(holes, "hole") << "), "
        << plural(segments + arcs, "edge") << ": " << plural(segments, "segment") << ", " << plural(arcs, "arc");
    if (!part.features.empty()) {
      out << "; features:";
      for (const std::string& feature : part.features) out << " " << feature;
    }
    out << "\n";
  }
  out << "pairs: " << model.pairs.size() << (model.pairs_explicit ? " (listed)" : " (every pair of parts except fixed-fixed)")
      << "\n";
  for (const PairSpec& pair : model.pairs) {
    out << "  " << shown_name(model.parts[pair.first].name) << " - " << shown_name(model.parts[pair.second].name);
    if (pair.friction) out << "  friction " << number(*pair.friction);
    if (pair.restitution) out << "  restitution " << number(*pair.restitution);
    out << "\n";
  }
  out << "roundings: " << model.roundings.size() << (model.roundings.empty() ? " (every value is exact)" : " (|exact - used| <= bound)")
      << "\n";
  for (const Rounding& rounding : model.roundings)
    out << "  " << rounding.pointer << "  \"" << rounding.expression << "\"  -> " << number(rounding.value)
        << "  bound " << bound(rounding.bound) << "\n";
  out << "valid\n";
}

struct ValidateArguments {
  std::string path;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string rounding;
};

ReadOptions read_options(const ValidateArguments& arguments) {
  return parameter_overrides(arguments.overrides, arguments.allow_out_of_tolerance);
}

}  // namespace

void register_validate(CLI::App& app, Action& action) {
  auto arguments = std::make_shared<ValidateArguments>();
  CLI::App* command = app.add_subcommand("validate", "Read a model exactly, check it, and summarise it");
  command->add_option("model", arguments->path, "model file (JSON, see docs/model-format.md)")->required();
  add_parameter_options(command, arguments->overrides, arguments->allow_out_of_tolerance);
  add_rounding_option(command, arguments->rounding);
  command->callback([&action, arguments] {
    action = [arguments] {
      ReadOptions options = read_options(*arguments);
      refuse_unknown_parameters(arguments->path, arguments->overrides, "--set");
      auto rounding = rounding_scope(arguments->rounding);
      Model model = read_model_file(arguments->path, options);
      std::ostringstream summary;
      print_summary(model, options, summary);
      std::cout << summary.str();
      return 0;
    };
  });
}

void add_parameter_options(CLI::App* command, std::vector<std::string>& assignments, bool& allow_out_of_tolerance) {
  command->add_option("--set", assignments, "override a parameter: NAME=VALUE (exact literal in mm or rad; repeatable)");
  command->add_flag("--allow-out-of-tolerance", allow_out_of_tolerance,
                    "accept --set values outside the parameter's tolerance range");
}

void OnceEach::add(const std::string& target, const std::string& item) {
  auto [at, inserted] = seen_.emplace(target, item);
  if (!inserted)
    throw CLI::ArgumentMismatch(option_ + ": " + what_ + " '" + target + "' is given twice ('" + at->second + "', then '" +
                                item + "'); give each " + what_ + " once");
}

void refuse_repeated_names(const std::vector<std::string>& items, const std::string& option, const std::string& what) {
  OnceEach once(option, what);
  for (const std::string& item : items)
    if (auto equals = item.find('='); equals != std::string::npos) once.add(item.substr(0, equals), item);
}

Rational exact_option_literal(const std::string& value, const std::string& argument, const std::string& note) {
  try {
    return model_detail::parse_literal(value, "");
  } catch (const ModelError& error) {
    std::string shown = argument.size() <= 120
                            ? argument
                            : argument.substr(0, 120) + "... (" + std::to_string(argument.size()) + " characters)";
    throw ModelError("", shown + ": " + error.reason() + note);
  }
}

std::set<std::string> given_options(const CLI::App& command) {
  std::set<std::string> given;
  for (const CLI::Option* option : command.get_options())
    if (option->count() > 0)
      for (const std::string& name : option->get_lnames()) given.insert("--" + name);
  return given;
}

void refuse_unknown_parameters(const std::string& path, const std::vector<std::string>& items, const std::string& option) {
  if (items.empty()) return;
  model_detail::JsonValue root;
  try {
    root = model_detail::parse_json(io::read_file(path));
  } catch (const Error&) {   // the reader reports a file it cannot read, or bad JSON, itself
    return;
  }
  if (root.type != model_detail::JsonValue::Type::object) return;
  const model_detail::JsonValue* parameters = root.find("parameters");
  if (parameters && parameters->type != model_detail::JsonValue::Type::object) return;
  for (const std::string& item : items) {
    auto equals = item.find('=');
    if (equals == std::string::npos) continue;   // the option's own parser says what is wrong
    std::string name = item.substr(0, equals);
    if (parameters && parameters->find(name)) continue;
    std::string names;   // the first ten, and how many there are
    if (parameters)
      for (std::size_t k = 0; k < parameters->members.size() && k < 10; ++k)
        names += (names.empty() ? "'" : ", '") + shown_name(parameters->members[k].key) + "'";
    if (parameters && parameters->members.size() > 10)
      names += ", ... (" + std::to_string(parameters->members.size()) + " parameters)";
    // (an item "NAME=" stands for a bare name: tolerance --vary NAME)
    const std::string& shown = equals + 1 == item.size() ? name : item;
    throw ModelError("", shortened_message(option + " " + shown) + ": the model has no parameter called '" +
                             shown_name(name) + "' (" + (names.empty() ? "it has no parameters" : "the parameters: " + names) +
                             ")");
  }
}

ReadOptions parameter_overrides(const std::vector<std::string>& assignments, bool allow_out_of_tolerance) {
  refuse_repeated_names(assignments, "--set", "parameter");
  ReadOptions options;
  options.allow_out_of_tolerance = allow_out_of_tolerance;
  for (const std::string& assignment : assignments) {
    auto equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0)
      throw ModelError("", "--set expects NAME=VALUE, got '" + assignment + "'");
    options.parameter_values[assignment.substr(0, equals)] =
        exact_option_literal(assignment.substr(equals + 1), "--set " + assignment, " (values are exact literals in mm or rad)");
  }
  return options;
}

CLI::Validator output_path() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        return input.empty() ? "an empty path names no file or directory to write (nothing was run or written)" : "";
      },
      "PATH");
}

CLI::Validator real_range(double lo, double hi) {
  auto text = [](double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  const std::string range = "[" + text(lo) + ", " + text(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& input) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(input, value)) return "Value " + input + " is not a number";
        if (!(lo <= value && value <= hi)) return "Value " + input + " not in " + range;
        return {};
      },
      "NUMBER in " + range);
}

void add_rounding_option(CLI::App* command, std::string& text) {
  command->add_option("--rounding", text,
                      "rounding bound B for values that cannot be exact (default: the model's \"rounding\", else "
                      "1e-12): each becomes the simplest rational within B");
}

std::unique_ptr<model_detail::RoundingBoundScope> rounding_scope(const std::string& text) {
  if (text.empty()) return nullptr;
  Rational bound;
  try {
    bound = parse_rational(text);
  } catch (const NumericError& error) {
    throw ModelError("", "--rounding " + text + ": " + error.what() + " (a number such as 1e-9)");
  }
  return std::make_unique<model_detail::RoundingBoundScope>(bound, true);
}

}  // namespace hipair::cli
