// Typed access to a template's arguments with JSON-pointer errors, and the per-family
// expanders. Internal to src/model/templates*.cpp.
#pragma once

#include "model/templates.hpp"

#include <hipair/error.hpp>

#include <map>
#include <string>
#include <vector>

namespace hipair::model_detail::template_detail {

/// The arguments of one template occurrence.
class Arguments {
 public:
  Arguments(const std::map<std::string, TemplateValue>& values, std::string pointer)
      : values_(values), pointer_(std::move(pointer)) {}

  const std::string& pointer() const { return pointer_; }
  /// Pointer of an argument: pointer + "/" + key.
  std::string at(const std::string& key) const { return pointer_ + "/" + key; }
  bool has(const std::string& key) const { return values_.count(key) != 0; }

  /// A point argument. \throws ModelError when missing or not a point.
  Point point(const std::string& key) const {
    const TemplateValue& value = get(key);
    if (const Point* p = std::get_if<Point>(&value)) return *p;
    throw ModelError(at(key), "expected a point [x, y]");
  }
  /// A number (length or angle in rad), or `fallback` when absent.
  Rational number(const std::string& key, const Rational* fallback = nullptr) const {
    if (!has(key) && fallback) return *fallback;
    const TemplateValue& value = get(key);
    if (const Rational* q = std::get_if<Rational>(&value)) return *q;
    throw ModelError(at(key), "expected a number");
  }
  /// A length that must be > 0.
  Rational positive_length(const std::string& key) const {
    Rational value = number(key);
    if (value <= 0) throw ModelError(at(key), "must be positive");
    return value;
  }
  /// An angle (rad); `fallback` when absent (0 unless given).
  Rational angle(const std::string& key, const Rational& fallback = Rational(0)) const {
    return number(key, &fallback);
  }
  /// A count: an integer >= `minimum`.
  long count(const std::string& key, long minimum, long maximum = 10000) const {
    Rational value = number(key);
    if (value.get_den() != 1)
      throw ModelError(at(key), "must be a whole number");
    if (value < minimum)
      throw ModelError(at(key), "must be at least " + std::to_string(minimum));
    if (value > maximum)
      throw ModelError(at(key), "must be at most " + std::to_string(maximum));
    return value.get_num().get_si();
  }
  /// "ccw" -> true, "cw" -> false; `fallback` when absent.
  bool counter_clockwise(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const TemplateValue& value = get(key);
    const std::string* word = std::get_if<std::string>(&value);
    if (!word || (*word != "ccw" && *word != "cw"))
      throw ModelError(at(key), "expected \"ccw\" or \"cw\"");
    return *word == "ccw";
  }

 private:
  const TemplateValue& get(const std::string& key) const {
    auto found = values_.find(key);
    if (found == values_.end()) throw ModelError(at(key), "missing argument '" + key + "'");
    return found->second;
  }
  const std::map<std::string, TemplateValue>& values_;
  std::string pointer_;
};

/// Exact unit vector of the angle phase + pi * multiple_of_pi (exact_unit_vector_sum: one
/// rounding of the whole angle's half-angle tangent; exact for phase 0 and multiples of pi/2).
Point direction(const Rational& phase, const Rational& multiple_of_pi, const std::string& pointer,
                const std::string& what, std::vector<Rounding>& roundings);

/// Template `name`'s rules (model/template_rules.hpp) at its exact argument values, lengths and
/// points in the template's unit of length (template_geometry.hpp LengthScaleScope); `count` its
/// tooth or slot count. \throws ModelError at the argument a failing rule names, with the
/// template's message.
void check_rules(const std::string& name, const Arguments& arguments, long count);

std::vector<Loop> expand_circle(const Arguments& arguments, const std::string& label);
std::vector<Loop> expand_geneva_wheel(const Arguments& arguments, std::vector<Rounding>& roundings);
std::vector<Loop> expand_geneva_driver(const Arguments& arguments,
                                       std::vector<Rounding>& roundings);
std::vector<Loop> expand_spur_gear(const Arguments& arguments, std::vector<Rounding>& roundings);
std::vector<Loop> expand_ratchet_wheel(const Arguments& arguments,
                                       std::vector<Rounding>& roundings);
std::vector<Loop> expand_escape_wheel(const Arguments& arguments,
                                      std::vector<Rounding>& roundings);
std::vector<Loop> expand_anchor(const Arguments& arguments, std::vector<Rounding>& roundings);
std::vector<Loop> expand_balance(const Arguments& arguments, std::vector<Rounding>& roundings);

}  // namespace hipair::model_detail::template_detail
