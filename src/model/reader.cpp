// The model reader: JSON text -> exact, validated hipair::Model (docs/model-format.md).
#include "core/sha256.hpp"
#include "model/exact_trig.hpp"
#include "model/expression.hpp"
#include "model/json_document.hpp"
#include "model/validate_geometry.hpp"

#if __has_include("model/templates.hpp")
#include "model/templates.hpp"
#define HIPAIR_HAVE_TEMPLATES 1
#endif

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <cctype>
#include <fstream>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>

namespace hipair {
namespace model_detail {
namespace {

constexpr std::size_t max_feature_count = 10000;
constexpr std::size_t max_reference_depth = 200;

std::string join(std::initializer_list<std::string_view> words) {
  std::string out;
  for (std::string_view word : words) {
    if (!out.empty()) out += ", ";
    out += word;
  }
  return out;
}

std::string decimal(const Rational& value) { return to_decimal_string(value, 12); }

bool valid_parameter_name(const std::string& name) {
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  for (std::size_t i = 0; i < name.size(); ++i) {
    char c = name[i];
    bool word = std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    if (word) continue;
    if (c == '-' && i + 1 < name.size() &&
        (std::isalnum(static_cast<unsigned char>(name[i + 1])) || name[i + 1] == '_'))
      continue;
    return false;
  }
  return true;
}

bool reserved_name(const std::string& name) {
  static const std::set<std::string> reserved = {"pi", "deg", "rad", "sqrt", "sin", "cos", "tan",
                                                 "atan2", "min", "max", "abs", "nan", "inf",
                                                 "infinity", "NaN", "Inf", "Infinity"};
  return reserved.count(name) != 0;
}

Rational square(const Rational& v) { return v * v; }
Rational squared_distance(const Point& a, const Point& b) {
  return square(a.x - b.x) + square(a.y - b.y);
}

class Reader {
 public:
  Reader(std::string_view text, std::string_view source, const ReadOptions& options)
      : text_(text), options_(options) {
    model_.source = std::string(source);
  }

  Model read() {
    model_.content_hash = detail::sha256_hex(text_);
    JsonValue root = parse_json(text_);
    if (!root.is_object()) throw ModelError("", "a model file must hold a JSON object");
    check_keys(root, {"hipair", "name", "description", "units", "parameters", "parts", "pairs"});
    read_version(require(root, "hipair"));
    model_.name = read_string(require(root, "name"), false);
    if (const JsonValue* description = root.find("description"))
      model_.description = read_string(*description, true);
    read_units(root.find("units"));
    read_parameters(root.find("parameters"));
    read_parts(require(root, "parts"));
    read_pairs(root.find("pairs"));
    return std::move(model_);
  }

 private:
  // ---------------------------------------------------------------- JSON structure
  const JsonValue& require(const JsonValue& object, std::string_view key) {
    if (const JsonValue* value = object.find(key)) return *value;
    throw ModelError(object.pointer, "missing required key '" + std::string(key) + "'");
  }

  void check_keys(const JsonValue& object, std::initializer_list<std::string_view> allowed) {
    for (const JsonMember& member : object.members) {
      bool known = false;
      for (std::string_view key : allowed) known = known || member.key == key;
      if (!known)
        throw ModelError(member.value.pointer, "unknown key '" + escape_pointer_token(member.key) +
                                                   "' (allowed here: " + join(allowed) + ")");
    }
  }

  void expect(const JsonValue& value, JsonValue::Type type, const std::string& what) {
    if (value.type != type)
      throw ModelError(value.pointer, "expected " + what + ", found " + describe_type(value.type));
  }

  const JsonValue& expect_object(const JsonValue& value, const std::string& what = "an object") {
    expect(value, JsonValue::Type::object, what);
    return value;
  }

  const JsonValue& expect_array(const JsonValue& value, const std::string& what = "an array") {
    expect(value, JsonValue::Type::array, what);
    return value;
  }

  std::string read_string(const JsonValue& value, bool allow_empty) {
    expect(value, JsonValue::Type::string, "a string");
    if (!allow_empty && value.text.empty()) throw ModelError(value.pointer, "must not be empty");
    return value.text;
  }

  bool read_boolean(const JsonValue& value) {
    expect(value, JsonValue::Type::boolean, "true or false");
    return value.boolean;
  }

  // ---------------------------------------------------------------- numbers
  std::string text_of(const JsonValue& value) { return value.text; }

  ExpressionContext context_at(const std::string& pointer) {
    ExpressionContext context;
    context.degrees = degrees_;
    context.pointer = pointer;
    context.parameter = [this, pointer](const std::string& name) {
      return parameter_value(name, pointer);
    };
    return context;
  }

  /// The value of a number slot: a JSON number (exact from its text) or an expression string.
  Quantity evaluate(const JsonValue& value) {
    if (value.is_number()) {
      return Quantity::of(parse_literal(value.text, value.pointer));
    }
    if (value.is_string()) return evaluate_expression(value.text, context_at(value.pointer));
    throw ModelError(value.pointer, std::string("expected a number or an expression string, found ") +
                                        describe_type(value.type));
  }

  Rational number(const JsonValue& value) {
    return to_rational(evaluate(value), value.pointer, text_of(value), model_.roundings);
  }

  Rational angle(const JsonValue& value) {
    return to_rational(as_angle(evaluate(value), degrees_, value.pointer, text_of(value)), value.pointer, text_of(value),
                       model_.roundings);
  }

  Rational non_negative(const JsonValue& value, const std::string& what) {
    Rational result = number(value);
    if (result < 0) throw ModelError(value.pointer, what + " must not be negative (got " + decimal(result) + ")");
    return result;
  }

  Rational positive(const JsonValue& value, const std::string& what) {
    Rational result = number(value);
    if (result <= 0) throw ModelError(value.pointer, what + " must be positive (got " + decimal(result) + ")");
    return result;
  }

  Point point(const JsonValue& value) {
    if (value.is_array()) {
      if (value.items.size() != 2)
        throw ModelError(value.pointer, "a point is [x, y]: expected 2 numbers, found " +
                                            std::to_string(value.items.size()));
      return Point{number(value.items[0]), number(value.items[1])};
    }
    if (value.is_object() && value.find("polar")) {
      check_keys(value, {"polar"});
      const JsonValue& polar = expect_object(*value.find("polar"));
      check_keys(polar, {"center", "radius", "angle"});
      Point center = point(require(polar, "center"));
      const JsonValue& radius_value = require(polar, "radius");
      Rational radius = non_negative(radius_value, "the radius");
      const JsonValue& angle_value = require(polar, "angle");
      Point unit = unit_vector(as_angle(evaluate(angle_value), degrees_, angle_value.pointer, text_of(angle_value)),
                               angle_value.pointer,
                               text_of(angle_value), model_.roundings);
      return point_on_circle(center, radius, unit);
    }
    throw ModelError(value.pointer, std::string("expected a point [x, y] or {\"polar\": ...}, found ") +
                                        describe_type(value.type));
  }

  RationalInterval limits(const JsonValue& value, bool angles) {
    expect_array(value, "limits [lo, hi]");
    if (value.items.size() != 2)
      throw ModelError(value.pointer, "limits are [lo, hi]: expected 2 values, found " +
                                          std::to_string(value.items.size()));
    Rational lo = angles ? angle(value.items[0]) : number(value.items[0]);
    Rational hi = angles ? angle(value.items[1]) : number(value.items[1]);
    if (!(lo < hi))
      throw ModelError(value.pointer, "the lower limit " + decimal(lo) +
                                          " must be less than the upper limit " + decimal(hi));
    return RationalInterval{lo, hi};
  }

  // ---------------------------------------------------------------- top level
  void read_version(const JsonValue& value) {
    if (!value.is_number() || value.text != "1")
      throw ModelError(value.pointer, "unsupported format version " +
                                          (value.is_number() || value.is_string() ? "'" + value.text + "'"
                                                                                  : std::string(describe_type(value.type))) +
                                          ": this reader reads \"hipair\": 1");
  }

  void read_units(const JsonValue* units) {
    model_.angle_unit = "rad";
    if (!units) return;
    expect_object(*units);
    check_keys(*units, {"length", "angle"});
    if (const JsonValue* length = units->find("length")) {
      std::string unit = read_string(*length, false);
      if (unit != "mm") throw ModelError(length->pointer, "unsupported length unit '" + unit + "' (only \"mm\")");
    }
    if (const JsonValue* angle_unit = units->find("angle")) {
      std::string unit = read_string(*angle_unit, false);
      if (unit != "rad" && unit != "deg")
        throw ModelError(angle_unit->pointer, "unsupported angle unit '" + unit + "' (\"rad\" or \"deg\")");
      model_.angle_unit = unit;
      degrees_ = unit == "deg";
    }
  }

  // ---------------------------------------------------------------- parameters
  struct ParameterState {
    const JsonValue* definition = nullptr;
    std::size_t index = 0;
    enum class Status { pending, evaluating, done } status = Status::pending;
    Quantity value;
  };

  void read_parameters(const JsonValue* parameters) {
    if (parameters) {
      expect_object(*parameters);
      std::size_t index = 0;
      for (const JsonMember& member : parameters->members) {
        if (!valid_parameter_name(member.key))
          throw ModelError(member.value.pointer,
                           "invalid parameter name '" + escape_pointer_token(member.key) +
                               "' (letters, digits, '_' and '-' inside, starting with a letter)");
        if (reserved_name(member.key))
          throw ModelError(member.value.pointer, "'" + member.key + "' is a reserved word, not a parameter name");
        expect_object(member.value, "a parameter object {\"nominal\": ...}");
        ParameterState state;
        state.definition = &member.value;
        state.index = index++;
        parameters_.emplace(member.key, std::move(state));
      }
    }
    for (const auto& [name, value] : options_.parameter_values)
      if (!parameters_.count(name))
        throw ModelError("/parameters", "cannot override unknown parameter '" + name + "'");
    resolved_.resize(parameters_.size());
    if (parameters)
      for (const JsonMember& member : parameters->members) parameter_value(member.key, member.value.pointer);
    for (Parameter& parameter : resolved_) model_.parameters.push_back(std::move(parameter));
  }

  Quantity parameter_value(const std::string& name, const std::string& used_at) {
    auto found = parameters_.find(name);
    if (found == parameters_.end()) {
      std::string hint = name.find('-') != std::string::npos
                             ? " (to subtract, write 'a - b' with spaces: a '-' inside a name is part of the name)"
                             : "";
      throw ModelError(used_at, "unknown parameter '" + name + "'" + hint);
    }
    ParameterState& state = found->second;
    if (state.status == ParameterState::Status::done) return state.value;
    if (state.status == ParameterState::Status::evaluating) {
      std::string cycle;
      bool in_cycle = false;
      for (const std::string& step : evaluation_stack_) {
        in_cycle = in_cycle || step == name;
        if (in_cycle) cycle += step + " -> ";
      }
      throw ModelError(state.definition->pointer, "circular parameter references: " + cycle + name);
    }
    if (evaluation_stack_.size() >= max_reference_depth)
      throw ModelError(state.definition->pointer, "parameters refer to each other more than " +
                                                      std::to_string(max_reference_depth) + " levels deep");
    state.status = ParameterState::Status::evaluating;
    evaluation_stack_.push_back(name);
    resolved_[state.index] = read_parameter(name, *state.definition, state.value);
    evaluation_stack_.pop_back();
    state.status = ParameterState::Status::done;
    return state.value;
  }

  Parameter read_parameter(const std::string& name, const JsonValue& definition, Quantity& value) {
    check_keys(definition, {"nominal", "tolerance", "range", "distribution", "angle", "description"});
    Parameter parameter;
    parameter.name = name;
    parameter.pointer = definition.pointer;
    if (const JsonValue* angle_flag = definition.find("angle")) parameter.is_angle = read_boolean(*angle_flag);
    const JsonValue& nominal_value = require(definition, "nominal");
    Quantity nominal = evaluate(nominal_value);
    if (parameter.is_angle || nominal.is_angle) {
      nominal = as_angle(nominal, degrees_, nominal_value.pointer, text_of(nominal_value));
      parameter.is_angle = true;
    }
    parameter.nominal = to_rational(nominal, nominal_value.pointer, text_of(nominal_value), model_.roundings);
    auto deviation = [&](const JsonValue& v) {
      Quantity q = evaluate(v);
      if (parameter.is_angle) q = as_angle(q, degrees_, v.pointer, text_of(v));
      return to_rational(q, v.pointer, text_of(v), model_.roundings);
    };
    const JsonValue* tolerance = definition.find("tolerance");
    const JsonValue* range = definition.find("range");
    if (tolerance && range)
      throw ModelError(range->pointer, "give either 'tolerance' or 'range', not both");
    parameter.range = RationalInterval{parameter.nominal, parameter.nominal};
    if (tolerance) {
      if (tolerance->is_array()) {
        if (tolerance->items.size() != 2)
          throw ModelError(tolerance->pointer, "an asymmetric tolerance is [lo, hi]: expected 2 values, found " +
                                                   std::to_string(tolerance->items.size()));
        Rational lo = deviation(tolerance->items[0]), hi = deviation(tolerance->items[1]);
        if (lo > hi)
          throw ModelError(tolerance->pointer, "tolerance lower deviation " + decimal(lo) +
                                                   " is greater than the upper deviation " + decimal(hi));
        if (lo > 0 || hi < 0)
          throw ModelError(tolerance->pointer, "the nominal value lies outside its tolerance [" + decimal(lo) +
                                                   ", " + decimal(hi) + "] (deviations must satisfy lo <= 0 <= hi)");
        parameter.range = RationalInterval{parameter.nominal + lo, parameter.nominal + hi};
      } else {
        Rational t = deviation(*tolerance);
        if (t < 0) throw ModelError(tolerance->pointer, "a tolerance must not be negative (got " + decimal(t) + ")");
        parameter.range = RationalInterval{parameter.nominal - t, parameter.nominal + t};
      }
    } else if (range) {
      expect_array(*range, "a range [lo, hi]");
      if (range->items.size() != 2)
        throw ModelError(range->pointer, "a range is [lo, hi]: expected 2 values, found " +
                                             std::to_string(range->items.size()));
      Rational lo = deviation(range->items[0]), hi = deviation(range->items[1]);
      if (lo > hi)
        throw ModelError(range->pointer, "range lower end " + decimal(lo) + " is greater than the upper end " + decimal(hi));
      if (parameter.nominal < lo || parameter.nominal > hi)
        throw ModelError(nominal_value.pointer, "the nominal value " + decimal(parameter.nominal) +
                                                    " lies outside its range [" + decimal(lo) + ", " + decimal(hi) + "]");
      parameter.range = RationalInterval{lo, hi};
    }
    if (const JsonValue* distribution = definition.find("distribution")) {
      if (!tolerance && !range)
        throw ModelError(distribution->pointer, "a distribution needs a 'tolerance' or 'range'");
      if (distribution->is_string() && distribution->text == "uniform") {
        parameter.distribution = Parameter::Distribution::uniform;
      } else if (distribution->is_object() && distribution->find("normal")) {
        check_keys(*distribution, {"normal"});
        const JsonValue& normal = expect_object(*distribution->find("normal"));
        check_keys(normal, {"sigma"});
        const JsonValue& sigma = require(normal, "sigma");
        Quantity s = evaluate(sigma);
        if (parameter.is_angle) s = as_angle(s, degrees_, sigma.pointer, text_of(sigma));
        parameter.sigma = to_rational(s, sigma.pointer, text_of(sigma), model_.roundings);
        if (*parameter.sigma <= 0) throw ModelError(sigma.pointer, "sigma must be positive");
        parameter.distribution = Parameter::Distribution::normal;
      } else {
        throw ModelError(distribution->pointer,
                         "expected \"uniform\" or {\"normal\": {\"sigma\": s}}");
      }
    }
    value = nominal;
    if (auto override_value = options_.parameter_values.find(name);
        override_value != options_.parameter_values.end()) {
      const Rational& v = override_value->second;
      if (!options_.allow_out_of_tolerance && (v < parameter.range.lo || v > parameter.range.hi))
        throw ModelError(definition.pointer, "override value " + decimal(v) + " of parameter '" + name +
                                                 "' lies outside its tolerance range [" + decimal(parameter.range.lo) +
                                                 ", " + decimal(parameter.range.hi) + "]");
      value = Quantity::of(v, parameter.is_angle);
    }
    return parameter;
  }

  // ---------------------------------------------------------------- parts
  void read_parts(const JsonValue& parts) {
    expect_array(parts, "an array of parts");
    if (parts.items.empty()) throw ModelError(parts.pointer, "a model needs at least one part");
    std::map<std::string, std::string> names;
    for (const JsonValue& part_value : parts.items) {
      Part part = read_part(part_value);
      auto [where, inserted] = names.emplace(part.name, part.pointer);
      if (!inserted)
        throw ModelError(part_value.pointer + "/name",
                         "duplicate part name '" + part.name + "' (also " + where->second + ")");
      model_.parts.push_back(std::move(part));
    }
  }

  Part read_part(const JsonValue& value) {
    expect_object(value, "a part object");
    check_keys(value, {"name", "description", "motion", "initial", "loops", "features", "dynamics"});
    Part part;
    part.pointer = value.pointer;
    part.name = read_string(require(value, "name"), false);
    part.motion = read_motion(require(value, "motion"));
    if (const JsonValue* initial = value.find("initial")) part.initial = read_initial(*initial, part.motion);
    if (const JsonValue* loops = value.find("loops")) {
      expect_array(*loops, "an array of loops");
      for (const JsonValue& loop : loops->items) part.loops.push_back(read_loop(loop));
    }
    if (const JsonValue* features = value.find("features")) read_features(*features, part);
    if (part.loops.empty())
      throw ModelError(value.pointer, "part '" + part.name + "' has no geometry: give 'loops' or 'features'");
    if (const JsonValue* dynamics = value.find("dynamics")) part.dynamics = read_dynamics(*dynamics);
    validate_part_geometry(part);
    return part;
  }

  // ---------------------------------------------------------------- loops
  Loop read_loop(const JsonValue& value) {
    expect_object(value, "a loop object {\"start\": ..., \"edges\": [...]}");
    Loop loop;
    loop.pointer = value.pointer;
    if (const JsonValue* circle = value.find("circle")) {
      check_keys(value, {"circle", "label"});
      std::string label;
      if (const JsonValue* l = value.find("label")) label = read_string(*l, true);
      loop.edges.push_back(read_circle(*circle, label));
      return loop;
    }
    check_keys(value, {"start", "edges", "label"});
    std::string loop_label;
    if (const JsonValue* l = value.find("label")) loop_label = read_string(*l, true);
    Point current = point(require(value, "start"));
    const JsonValue& edges = expect_array(require(value, "edges"), "an array of edges");
    if (edges.items.empty()) throw ModelError(edges.pointer, "a loop needs at least one edge");
    for (const JsonValue& edge_value : edges.items) {
      Edge edge = read_edge(edge_value, current);
      if (edge.label.empty()) edge.label = loop_label;
      current = edge.target;
      loop.edges.push_back(std::move(edge));
    }
    return loop;
  }

  Edge read_circle(const JsonValue& value, const std::string& label) {
    expect_object(value, "a circle {\"center\": C, \"radius\": r}");
    check_keys(value, {"center", "radius"});
    Edge edge;
    edge.kind = Edge::Kind::arc;
    edge.center = point(require(value, "center"));
    Rational radius = positive(require(value, "radius"), "a circle's radius");
    edge.source = Point{edge.center.x + radius, edge.center.y};
    edge.target = edge.source;
    edge.ccw = true;
    edge.radius_squared = radius * radius;
    edge.pointer = value.pointer;
    edge.label = label;
    return edge;
  }

  Edge read_edge(const JsonValue& value, const Point& from) {
    expect_object(value, "an edge object {\"line_to\": P} or {\"arc_to\": P, \"center\": C, \"dir\": \"ccw\"}");
    Edge edge;
    edge.pointer = value.pointer;
    edge.source = from;
    const JsonValue* line_to = value.find("line_to");
    const JsonValue* arc_to = value.find("arc_to");
    if (line_to && arc_to) throw ModelError(value.pointer, "an edge has either 'line_to' or 'arc_to', not both");
    if (line_to) {
      check_keys(value, {"line_to", "label"});
      edge.kind = Edge::Kind::segment;
      edge.target = point(*line_to);
    } else if (arc_to) {
      check_keys(value, {"arc_to", "center", "dir", "label"});
      edge.kind = Edge::Kind::arc;
      edge.target = point(*arc_to);
      edge.center = point(require(value, "center"));
      const JsonValue& direction = require(value, "dir");
      std::string word = read_string(direction, true);
      if (word != "ccw" && word != "cw")
        throw ModelError(direction.pointer, "an arc's direction is \"ccw\" or \"cw\", not '" + word + "'");
      edge.ccw = word == "ccw";
      edge.radius_squared = squared_distance(edge.source, edge.center);
    } else {
      check_keys(value, {"line_to", "arc_to", "center", "dir", "label"});
      throw ModelError(value.pointer, "an edge needs 'line_to' or 'arc_to'");
    }
    if (const JsonValue* label = value.find("label")) edge.label = read_string(*label, true);
    return edge;
  }

  // ---------------------------------------------------------------- features
  void read_features(const JsonValue& features, Part& part) {
    expect_array(features, "an array of feature templates");
    if (features.items.size() > max_feature_count)
      throw ModelError(features.pointer, "too many features");
    for (const JsonValue& feature : features.items) {
      expect_object(feature, "a feature object {\"<template>\": {...}}");
      if (feature.members.size() != 1)
        throw ModelError(feature.pointer, "a feature holds exactly one template, found " +
                                              std::to_string(feature.members.size()) + " keys");
      const JsonMember& member = feature.members.front();
#ifdef HIPAIR_HAVE_TEMPLATES
      const TemplateSpec* spec = nullptr;
      std::string known;
      for (const TemplateSpec& candidate : template_specs()) {
        if (candidate.name == member.key) spec = &candidate;
        known += (known.empty() ? "" : ", ") + candidate.name;
      }
      if (!spec)
        throw ModelError(member.value.pointer, "unknown feature template '" + escape_pointer_token(member.key) +
                                                   "' (known: " + known + ")");
      const JsonValue& arguments_value = expect_object(member.value, "an object of template arguments");
      std::map<std::string, TemplateValue> arguments;
      for (const JsonMember& argument : arguments_value.members) {
        const ArgumentSpec* argument_spec = nullptr;
        for (const ArgumentSpec& candidate : spec->arguments)
          if (candidate.key == argument.key) argument_spec = &candidate;
        if (!argument_spec) {
          std::string allowed;
          for (const ArgumentSpec& candidate : spec->arguments)
            allowed += (allowed.empty() ? "" : ", ") + candidate.key;
          throw ModelError(argument.value.pointer, "unknown argument '" + escape_pointer_token(argument.key) +
                                                       "' of template '" + spec->name + "' (allowed: " + allowed + ")");
        }
        arguments.emplace(argument.key, template_argument(argument.value, argument_spec->kind));
      }
      for (const ArgumentSpec& candidate : spec->arguments)
        if (candidate.required && !arguments.count(candidate.key))
          throw ModelError(member.value.pointer, "template '" + spec->name + "' needs argument '" + candidate.key + "'");
      std::vector<Loop> loops;
      try {
        loops = expand_template(spec->name, arguments, member.value.pointer, model_.roundings);
      } catch (const ModelError&) {
        throw;
      } catch (const Error& error) {
        throw ModelError(member.value.pointer, error.what());
      }
      for (Loop& loop : loops) part.loops.push_back(std::move(loop));
      part.features.push_back(spec->name);
#else
      throw ModelError(member.value.pointer, "feature templates are not available in this build");
#endif
    }
  }

#ifdef HIPAIR_HAVE_TEMPLATES
  TemplateValue template_argument(const JsonValue& value, ArgumentKind kind) {
    switch (kind) {
      case ArgumentKind::length: return number(value);
      case ArgumentKind::angle: return angle(value);
      case ArgumentKind::count: {
        Quantity q = evaluate(value);
        if (!q.is_rational() || q.rational.get_den() != 1 || q.rational <= 0)
          throw ModelError(value.pointer, "expected a positive whole number");
        if (q.rational > Rational(static_cast<long>(max_feature_count)))
          throw ModelError(value.pointer, "count too large (at most " + std::to_string(max_feature_count) + ")");
        return q.rational;
      }
      case ArgumentKind::point: return point(value);
      case ArgumentKind::direction_word: {
        std::string word = read_string(value, true);
        if (word != "ccw" && word != "cw")
          throw ModelError(value.pointer, "expected \"ccw\" or \"cw\", not '" + word + "'");
        return word;
      }
    }
    throw ModelError(value.pointer, "unsupported argument kind");
  }
#endif

  // ---------------------------------------------------------------- motion
  Motion read_motion(const JsonValue& value) {
    Motion motion;
    motion.pointer = value.pointer;
    if (value.is_string()) {
      if (value.text != "fixed")
        throw ModelError(value.pointer, "unknown motion '" + value.text +
                                            "' (\"fixed\", or an object: rotation, translation, planar, pin_slot)");
      motion.kind = Motion::Kind::fixed;
      return motion;
    }
    expect_object(value, "a motion (\"fixed\" or {\"rotation\": ...})");
    check_keys(value, {"fixed", "rotation", "translation", "planar", "pin_slot"});
    if (value.members.size() != 1)
      throw ModelError(value.pointer, "a motion holds exactly one of fixed, rotation, translation, planar, pin_slot");
    const JsonMember& member = value.members.front();
    const JsonValue& body = expect_object(member.value, "an object");
    if (member.key == "fixed") {
      check_keys(body, {});
      motion.kind = Motion::Kind::fixed;
    } else if (member.key == "rotation") {
      check_keys(body, {"pivot", "limits"});
      motion.kind = Motion::Kind::rotation;
      motion.pivot = point(require(body, "pivot"));
      if (const JsonValue* l = body.find("limits")) motion.angle_limits = limits(*l, true);
    } else if (member.key == "translation") {
      check_keys(body, {"direction", "limits"});
      motion.kind = Motion::Kind::translation;
      motion.direction = direction(require(body, "direction"));
      if (const JsonValue* l = body.find("limits")) motion.translation_limits = limits(*l, false);
    } else if (member.key == "planar") {
      check_keys(body, {"pivot"});
      motion.kind = Motion::Kind::planar;
      motion.pivot = point(require(body, "pivot"));
    } else {
      check_keys(body, {"pivot", "direction", "angle_limits", "limits"});
      motion.kind = Motion::Kind::pin_slot;
      motion.pivot = point(require(body, "pivot"));
      motion.direction = direction(require(body, "direction"));
      if (const JsonValue* l = body.find("angle_limits")) motion.angle_limits = limits(*l, true);
      if (const JsonValue* l = body.find("limits")) motion.translation_limits = limits(*l, false);
    }
    return motion;
  }

  /// An exact rational unit vector from [dx, dy] or from an angle.
  Point direction(const JsonValue& value) {
    if (!value.is_array()) {
      Quantity a = as_angle(evaluate(value), degrees_, value.pointer, text_of(value));
      return unit_vector(a, value.pointer, text_of(value), model_.roundings);
    }
    if (value.items.size() != 2)
      throw ModelError(value.pointer, "a direction is [dx, dy] or an angle: expected 2 numbers, found " +
                                          std::to_string(value.items.size()));
    Rational dx = number(value.items[0]), dy = number(value.items[1]);
    Rational length_squared = dx * dx + dy * dy;
    if (length_squared == 0) throw ModelError(value.pointer, "zero direction vector: the axis has no direction");
    if (mpz_perfect_square_p(length_squared.get_num_mpz_t()) &&
        mpz_perfect_square_p(length_squared.get_den_mpz_t())) {
      mpz_class numerator, denominator;
      mpz_sqrt(numerator.get_mpz_t(), length_squared.get_num_mpz_t());
      mpz_sqrt(denominator.get_mpz_t(), length_squared.get_den_mpz_t());
      Rational length(numerator, denominator);
      return Point{Rational(dx / length), Rational(dy / length)};
    }
    // Half-angle tangent t = dy / (|d| + dx) of the direction (or of its opposite when dx < 0,
    // which keeps |t| <= 1), rounded to the 10^-12 grid: the vector is then exactly unit.
    bool flip = dx < 0;
    Rational x = flip ? Rational(-dx) : dx, y = flip ? Rational(-dy) : dy;
    Interval length;
    Interval squared(length_squared);
    mpfi_sqrt(length.get(), squared.get());
    Interval t = Interval(y) / (length + Interval(x));
    std::string expression = "direction [" + text_of(value.items[0]) + ", " + text_of(value.items[1]) +
                             "] (half-angle tangent)";
    Rational rounded = to_rational(Quantity::approximate(t), value.pointer, expression, model_.roundings);
    Point unit = unit_from_half_tangent(rounded);
    if (flip) unit = Point{Rational(-unit.x), Rational(-unit.y)};
    return unit;
  }

  PartConfiguration read_initial(const JsonValue& value, const Motion& motion) {
    expect_object(value, "an object {\"angle\": a, \"offset\": s, \"x\": x, \"y\": y}");
    PartConfiguration initial;
    switch (motion.kind) {
      case Motion::Kind::fixed: check_keys(value, {}); break;
      case Motion::Kind::rotation: check_keys(value, {"angle"}); break;
      case Motion::Kind::translation: check_keys(value, {"offset"}); break;
      case Motion::Kind::planar: check_keys(value, {"angle", "x", "y"}); break;
      case Motion::Kind::pin_slot: check_keys(value, {"angle", "offset"}); break;
    }
    if (const JsonValue* a = value.find("angle")) {
      initial.angle = angle(*a);
      if (motion.angle_limits && (initial.angle < motion.angle_limits->lo || initial.angle > motion.angle_limits->hi))
        throw ModelError(a->pointer, "the initial angle lies outside the motion's angle limits");
    }
    if (const JsonValue* s = value.find("offset")) {
      initial.offset = number(*s);
      if (motion.translation_limits &&
          (initial.offset < motion.translation_limits->lo || initial.offset > motion.translation_limits->hi))
        throw ModelError(s->pointer, "the initial offset lies outside the motion's limits");
    }
    if (const JsonValue* x = value.find("x")) initial.x = number(*x);
    if (const JsonValue* y = value.find("y")) initial.y = number(*y);
    return initial;
  }

  // ---------------------------------------------------------------- dynamics
  Dynamics read_dynamics(const JsonValue& value) {
    expect_object(value, "a dynamics object");
    check_keys(value, {"mass", "moment_of_inertia", "torsional_spring", "linear_spring", "torque", "force", "damping"});
    Dynamics dynamics;
    if (const JsonValue* v = value.find("mass")) dynamics.mass = non_negative(*v, "mass");
    if (const JsonValue* v = value.find("moment_of_inertia"))
      dynamics.moment_of_inertia = non_negative(*v, "moment of inertia");
    if (const JsonValue* v = value.find("torsional_spring")) dynamics.torsional_spring = read_spring(*v, true);
    if (const JsonValue* v = value.find("linear_spring")) dynamics.linear_spring = read_spring(*v, false);
    if (const JsonValue* v = value.find("torque")) dynamics.torque = number(*v);
    if (const JsonValue* v = value.find("force")) {
      expect_array(*v, "a force [fx, fy]");
      if (v->items.size() != 2) throw ModelError(v->pointer, "a force is [fx, fy]: expected 2 numbers");
      dynamics.force = Point{number(v->items[0]), number(v->items[1])};
    }
    if (const JsonValue* v = value.find("damping")) dynamics.damping = non_negative(*v, "damping");
    return dynamics;
  }

  Spring read_spring(const JsonValue& value, bool torsional) {
    expect_object(value, "a spring {\"stiffness\": k, \"rest\": r}");
    check_keys(value, {"stiffness", "rest"});
    Spring spring;
    spring.stiffness = non_negative(require(value, "stiffness"), "stiffness");
    if (const JsonValue* rest = value.find("rest")) spring.rest = torsional ? angle(*rest) : number(*rest);
    return spring;
  }

  // ---------------------------------------------------------------- pairs
  void read_pairs(const JsonValue* pairs) {
    if (!pairs) {
      for (std::size_t i = 0; i < model_.parts.size(); ++i)
        for (std::size_t j = i + 1; j < model_.parts.size(); ++j) {
          if (model_.parts[i].motion.kind == Motion::Kind::fixed &&
              model_.parts[j].motion.kind == Motion::Kind::fixed)
            continue;
          PairSpec pair;
          pair.first = i;
          pair.second = j;
          pair.pointer = "/parts";
          model_.pairs.push_back(pair);
        }
      return;
    }
    model_.pairs_explicit = true;
    expect_array(*pairs, "an array of pairs");
    std::map<std::pair<std::size_t, std::size_t>, std::string> seen;
    for (const JsonValue& value : pairs->items) {
      expect_object(value, "a pair object {\"parts\": [a, b]}");
      check_keys(value, {"parts", "friction", "restitution"});
      const JsonValue& names = expect_array(require(value, "parts"), "two part names [a, b]");
      if (names.items.size() != 2)
        throw ModelError(names.pointer, "a pair names exactly 2 parts, found " + std::to_string(names.items.size()));
      PairSpec pair;
      pair.pointer = value.pointer;
      std::size_t indices[2];
      for (int k = 0; k < 2; ++k) {
        std::string name = read_string(names.items[k], false);
        auto index = model_.find_part(name);
        if (!index) throw ModelError(names.items[k].pointer, "unknown part '" + name + "'");
        indices[k] = *index;
      }
      if (indices[0] == indices[1])
        throw ModelError(names.pointer, "a part cannot be paired with itself ('" +
                                            model_.parts[indices[0]].name + "')");
      pair.first = indices[0];
      pair.second = indices[1];
      auto key = std::minmax(indices[0], indices[1]);
      if (auto [where, inserted] = seen.emplace(key, value.pointer); !inserted)
        throw ModelError(value.pointer, "duplicate pair (also " + where->second + ")");
      if (const JsonValue* f = value.find("friction")) pair.friction = non_negative(*f, "friction");
      if (const JsonValue* e = value.find("restitution")) {
        pair.restitution = non_negative(*e, "restitution");
        if (*pair.restitution > 1) throw ModelError(e->pointer, "restitution must lie in [0, 1]");
      }
      model_.pairs.push_back(pair);
    }
  }

  std::string_view text_;
  const ReadOptions& options_;
  Model model_;
  bool degrees_ = false;
  std::map<std::string, ParameterState> parameters_;
  std::vector<Parameter> resolved_;
  std::vector<std::string> evaluation_stack_;
};

}  // namespace
}  // namespace model_detail

Model read_model(std::string_view json_text, std::string_view source_name, const ReadOptions& options) {
  return model_detail::Reader(json_text, source_name, options).read();
}

Model read_model_file(const std::filesystem::path& path, const ReadOptions& options) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError("cannot read model file '" + path.string() + "': it is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + path.string() + "'");
  std::ostringstream content;
  content << file.rdbuf();
  if (file.bad()) throw IoError("cannot read model file '" + path.string() + "'");
  return read_model(content.str(), path.string(), options);
}

}  // namespace hipair
