// Reader steps for parameters: names, nominal values, tolerances, distributions, overrides,
// and lazy evaluation with reference-cycle detection.
#include "model/reader.hpp"

#include <hipair/error.hpp>

#include <cctype>
#include <set>

namespace hipair::model_detail {
namespace {

constexpr std::size_t max_reference_depth = 200;

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

}  // namespace

void Reader::read_parameters(const JsonValue* parameters) {
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

Quantity Reader::parameter_value(const std::string& name, const std::string& used_at) {
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

Parameter Reader::read_parameter(const std::string& name, const JsonValue& definition, Quantity& value) {
  check_keys(definition, {"nominal", "tolerance", "range", "distribution", "angle", "description"});
  if (const JsonValue* description = definition.find("description")) read_string(*description, true, true);
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
        throw ModelError(tolerance->pointer, "tolerance lower deviation " + apart(lo, hi).first +
                                                 " is greater than the upper deviation " + apart(lo, hi).second);
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
      throw ModelError(range->pointer, "range lower end " + apart(lo, hi).first + " is greater than the upper end " +
                                           apart(lo, hi).second);
    if (parameter.nominal < lo || parameter.nominal > hi)
      throw ModelError(nominal_value.pointer, "the nominal value " + outside(parameter.nominal, lo, hi).first +
                                                  " lies outside its range " + outside(parameter.nominal, lo, hi).second);
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
    Rational v = override_value->second;
    v.canonicalize();  // callers may pass mpq_class(a, b), which is not canonical
    if (!options_.allow_out_of_tolerance && (v < parameter.range.lo || v > parameter.range.hi))
      throw ModelError(definition.pointer, "override value " + outside(v, parameter.range.lo, parameter.range.hi).first +
                                               " of parameter '" + name + "' lies outside its tolerance range " +
                                               outside(v, parameter.range.lo, parameter.range.hi).second);
    value = Quantity::of(v, parameter.is_angle);
    if (options_.overrides_set_nominal) {
      // The design changes: the nominal is v, a relative tolerance moves with it.
      if (definition.find("tolerance")) {
        Rational shift = v - parameter.nominal;
        parameter.range = RationalInterval{parameter.range.lo + shift, parameter.range.hi + shift};
      } else if (const JsonValue* range = definition.find("range")) {
        if (v < parameter.range.lo || v > parameter.range.hi)
          throw ModelError(range->pointer, "the new nominal value " + outside(v, parameter.range.lo, parameter.range.hi).first +
                                               " of parameter '" + name + "' lies outside its range " +
                                               outside(v, parameter.range.lo, parameter.range.hi).second +
                                               " (a range is absolute: widen it in the model)");
      } else {
        parameter.range = RationalInterval{v, v};
      }
      parameter.nominal = v;
    }
  }
  return parameter;
}

}  // namespace hipair::model_detail
