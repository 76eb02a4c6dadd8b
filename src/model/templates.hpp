// Parametric feature templates ("features" of a part): geneva wheels and drivers, gears,
// ratchets, escapement parts. Each expands to exact loops in world coordinates.
// Internal: the model reader calls these; see docs/model-format.md, "Features (templates)".
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <map>
#include <string>
#include <variant>
#include <vector>

namespace hipair::model_detail {

/// What kind of value an argument takes.
/// - length: mm, a Rational;
/// - angle: rad, a Rational already converted from the file's unit (exact or rounded);
/// - count: a positive integer, as a Rational;
/// - point: a Point;
/// - direction_word: the string "ccw" or "cw".
enum class ArgumentKind { length, angle, count, point, direction_word };

/// One argument of a template.
struct ArgumentSpec {
  std::string key;
  ArgumentKind kind;
  bool required;
};

/// A template: its name (the key in the "features" array) and its arguments.
struct TemplateSpec {
  std::string name;
  std::vector<ArgumentSpec> arguments;
};

/// Every template the reader accepts, with its arguments.
const std::vector<TemplateSpec>& template_specs();

/// An argument value: Rational (length, angle, count), Point, or std::string (direction word).
using TemplateValue = std::variant<Rational, Point, std::string>;

/// Expands one feature template into loops (world coordinates at the part's zero
/// configuration; any orientation, the reader orients them). Every arc endpoint lies exactly
/// on its circle. Values that cannot be exact (directions of irrational angles, vertices at
/// irrational intersections) are rounded to nearby exact points and recorded in `roundings`.
/// Every edge carries a label ("pin", "slot 2 wall L", "tooth 5 flank R", ...) and the
/// pointer `pointer`.
/// \throws ModelError(pointer + "/" + key, reason) for bad values (non-positive radii, slots
///         that do not fit, pointed teeth, ...), ModelError(pointer, ...) for an unknown name.
std::vector<Loop> expand_template(const std::string& name,
                                  const std::map<std::string, TemplateValue>& arguments,
                                  const std::string& pointer, std::vector<Rounding>& roundings);

}  // namespace hipair::model_detail
