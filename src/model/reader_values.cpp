// Reader steps for JSON structure (keys, types) and values: numbers and expressions, points,
// limits, unit directions.
#include "model/reader.hpp"

#include "model/exact_trig.hpp"

#include <hipair/error.hpp>

#include <cstdio>
#include <limits>
#include <utility>

namespace hipair::model_detail {

const JsonValue& Reader::require(const JsonValue& object, std::string_view key) {
  if (const JsonValue* value = object.find(key)) return *value;
  throw ModelError(object.pointer, "missing required key '" + std::string(key) + "'");
}

void Reader::check_keys(const JsonValue& object, std::initializer_list<std::string_view> allowed) {
  for (const JsonMember& member : object.members) {
    bool known = false;
    for (std::string_view key : allowed) known = known || member.key == key;
    if (!known)
      throw ModelError(member.value.pointer, "unknown key '" + escape_pointer_token(member.key) +
                                                 "' (allowed here: " + join(allowed) + ")");
  }
}

void Reader::expect(const JsonValue& value, JsonValue::Type type, const std::string& what) {
  if (value.type != type)
    throw ModelError(value.pointer, "expected " + what + ", found " + describe_type(value.type));
}

const JsonValue& Reader::expect_object(const JsonValue& value, const std::string& what) {
  expect(value, JsonValue::Type::object, what);
  return value;
}

const JsonValue& Reader::expect_array(const JsonValue& value, const std::string& what) {
  expect(value, JsonValue::Type::array, what);
  return value;
}

namespace {

// The first control character of `text` (C0 U+0000-U+001F, DEL U+007F, C1 U+0080-U+009F),
// except tab, line feed and carriage return when `layout` allows them: its code point and the
// (1-based) character position, or code point -1.
std::pair<long, std::size_t> first_control(std::string_view text, bool layout) {
  std::size_t character = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    auto byte = static_cast<unsigned char>(text[i]);
    if ((byte & 0xC0) != 0x80) ++character;  // not a continuation byte: a new character
    if (byte < 0x20 || byte == 0x7F) {
      if (layout && (byte == '\t' || byte == '\n' || byte == '\r')) continue;
      return {byte, character};
    }
    if (byte == 0xC2 && i + 1 < text.size()) {
      auto next = static_cast<unsigned char>(text[i + 1]);
      if (next >= 0x80 && next <= 0x9F) return {next, character};
    }
  }
  return {-1, 0};
}

}  // namespace

std::string Reader::read_string(const JsonValue& value, bool allow_empty, bool layout) {
  expect(value, JsonValue::Type::string, "a string");
  if (!allow_empty && value.text.empty()) throw ModelError(value.pointer, "must not be empty");
  // Names and labels reach SVG pictures, terminals and reports: no control characters.
  auto [code, position] = first_control(value.text, layout);
  if (code >= 0) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04lX", static_cast<unsigned long>(code));
    throw ModelError(value.pointer, std::string("control character U+") + hex + " (character " +
                                        std::to_string(position) + ") is not allowed in " +
                                        (layout ? "this text (only tab and line breaks are)" : "names and labels"));
  }
  return value.text;
}

namespace {

// The code point of the UTF-8 sequence at text[i] (the JSON layer has checked the encoding) and
// its length in bytes.
std::pair<unsigned long, std::size_t> code_point_at(std::string_view text, std::size_t i) {
  auto byte = static_cast<unsigned char>(text[i]);
  std::size_t length = byte < 0x80 ? 1 : byte < 0xE0 ? 2 : byte < 0xF0 ? 3 : 4;
  if (i + length > text.size()) length = text.size() - i;
  unsigned long code = length == 1 ? byte : byte & (0x7F >> length);
  for (std::size_t k = 1; k < length; ++k) code = (code << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
  return {code, length};
}

// White space (Unicode's White_Space property, less the control characters refused before) and
// the invisible characters that read as nothing or as a space: no name may hold them.
bool blank_character(unsigned long code) {
  return code == 0xA0 || code == 0x1680 || code == 0x180E || (code >= 0x2000 && code <= 0x200D) ||
         code == 0x2028 || code == 0x2029 || code == 0x202F || code == 0x205F || code == 0x2060 ||
         code == 0x3000 || code == 0xFEFF;
}

}  // namespace

std::string Reader::read_name(const JsonValue& value) {
  std::string name = read_string(value, false);
  std::size_t characters = 0;
  bool after_space = true;  // a space at the start is refused as at the end
  for (std::size_t i = 0; i < name.size();) {
    auto [code, length] = code_point_at(name, i);
    ++characters;
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04lX", code);
    if (blank_character(code))
      throw ModelError(value.pointer, std::string("a name may not hold U+") + hex + " (character " +
                                          std::to_string(characters) + "): " + name_rule);
    if (code == ' ' && after_space)
      throw ModelError(value.pointer, std::string(characters == 1 ? "a name may not begin with a space"
                                                                  : "a name may not hold two spaces in a row") +
                                          " (character " + std::to_string(characters) + "): " + name_rule);
    after_space = code == ' ';
    i += length;
  }
  if (after_space) throw ModelError(value.pointer, std::string("a name may not end with a space: ") + name_rule);
  return name;
}

bool Reader::read_boolean(const JsonValue& value) {
  expect(value, JsonValue::Type::boolean, "true or false");
  return value.boolean;
}

ExpressionContext Reader::context_at(const std::string& pointer) {
  ExpressionContext context;
  context.degrees = degrees_;
  context.pointer = pointer;
  context.parameter = [this, pointer](const std::string& name) {
    return parameter_value(name, pointer);
  };
  return context;
}

/// The value of a number slot: a JSON number (exact from its text) or an expression string.
Quantity Reader::evaluate(const JsonValue& value) {
  if (value.is_number()) {
    return Quantity::of(parse_literal(value.text, value.pointer));
  }
  if (value.is_string()) return evaluate_expression(value.text, context_at(value.pointer));
  throw ModelError(value.pointer, std::string("expected a number or an expression string, found ") +
                                      describe_type(value.type));
}

Rational Reader::number(const JsonValue& value) {
  Rational result = to_rational(evaluate(value), value.pointer, text_of(value), model_.roundings);
  if (simulator_values_ && reading_for_simulation()) check_simulator_range(result, value);
  return result;
}

Rational Reader::angle(const JsonValue& value) {
  Rational result = to_rational(as_angle(evaluate(value), degrees_, value.pointer, text_of(value)), value.pointer,
                                text_of(value), model_.roundings);
  if (simulator_values_ && reading_for_simulation()) check_simulator_range(result, value);
  return result;
}

void Reader::check_simulator_range(const Rational& value, const JsonValue& where) {
  if (sgn(value) == 0) return;
  const Rational magnitude = abs(value);
  // exact comparisons with the doubles' largest finite and smallest normal magnitudes
  static const Rational largest(std::numeric_limits<double>::max());
  static const Rational smallest(std::numeric_limits<double>::min());
  if (magnitude <= largest && magnitude >= smallest) return;
  throw ModelError(where.pointer, "'" + text_of(where) + "' is " +
                                      (magnitude > largest ? "too large" : "too small") +
                                      " for the simulator, which holds dynamics data in doubles: a nonzero "
                                      "magnitude must lie in [2.2250738585072014e-308, 1.7976931348623157e+308]");
}

Rational Reader::non_negative(const JsonValue& value, const std::string& what) {
  Rational result = number(value);
  if (result < 0) throw ModelError(value.pointer, what + " must not be negative (got " + decimal(result) + ")");
  return result;
}

Rational Reader::positive(const JsonValue& value, const std::string& what) {
  Rational result = number(value);
  if (result <= 0) throw ModelError(value.pointer, what + " must be positive (got " + decimal(result) + ")");
  return result;
}

Point Reader::point(const JsonValue& value) {
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
    // Signed: a negative radius puts the point on the opposite side (an offset toleranced
    // about 0, such as the Geneva slot's medial offset, changes sign inside its box).
    Rational radius = number(radius_value);
    const JsonValue& angle_value = require(polar, "angle");
    Point unit = unit_vector(as_angle(evaluate(angle_value), degrees_, angle_value.pointer, text_of(angle_value)),
                             angle_value.pointer,
                             text_of(angle_value), model_.roundings);
    return point_on_circle(center, radius, unit);
  }
  throw ModelError(value.pointer, std::string("expected a point [x, y] or {\"polar\": ...}, found ") +
                                      describe_type(value.type));
}

RationalInterval Reader::limits(const JsonValue& value, bool angles) {
  expect_array(value, "limits [lo, hi]");
  if (value.items.size() != 2)
    throw ModelError(value.pointer, "limits are [lo, hi]: expected 2 values, found " +
                                        std::to_string(value.items.size()));
  Rational lo = angles ? angle(value.items[0]) : number(value.items[0]);
  Rational hi = angles ? angle(value.items[1]) : number(value.items[1]);
  if (!(lo < hi))
    throw ModelError(value.pointer, "the lower limit " + apart(lo, hi).first +
                                        " must be less than the upper limit " + apart(lo, hi).second);
  return RationalInterval{lo, hi};
}

/// An exact rational unit vector from [dx, dy] or from an angle.
Point Reader::direction(const JsonValue& value) {
  if (!value.is_array()) {
    Quantity a = as_angle(evaluate(value), degrees_, value.pointer, text_of(value));
    return unit_vector(a, value.pointer, text_of(value), model_.roundings);
  }
  if (value.items.size() != 2)
    throw ModelError(value.pointer, "a direction is [dx, dy] or an angle: expected 2 numbers, found " +
                                        std::to_string(value.items.size()));
  Rational dx = number(value.items[0]), dy = number(value.items[1]);   // in order: their roundings are recorded
  return unit_direction(dx, dy, value.pointer, text_of(value.items[0]), text_of(value.items[1]), model_.roundings);
}

}  // namespace hipair::model_detail
