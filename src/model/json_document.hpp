// A small JSON document model for the model reader: keeps every number's original text (so
// decimals are read exactly, never through a double), rejects duplicate keys and knows the
// JSON pointer of every value.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hipair::model_detail {

struct JsonMember;

/// One JSON value with its JSON pointer ("" for the root, "/parts/0/name", ...).
struct JsonValue {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  std::string text;                 ///< number: its literal text as written; string: its value
  std::vector<JsonValue> items;     ///< array elements
  std::vector<JsonMember> members;  ///< object members in file order (keys unique)
  std::string pointer;

  bool is_null() const noexcept { return type == Type::null; }
  bool is_boolean() const noexcept { return type == Type::boolean; }
  bool is_number() const noexcept { return type == Type::number; }
  bool is_string() const noexcept { return type == Type::string; }
  bool is_array() const noexcept { return type == Type::array; }
  bool is_object() const noexcept { return type == Type::object; }

  /// The member called `key` of an object, or nullptr (also for non-objects).
  const JsonValue* find(std::string_view key) const;
};

struct JsonMember {
  std::string key;
  JsonValue value;
};

/// Maximum nesting depth of arrays and objects accepted.
inline constexpr std::size_t json_max_depth = 64;

/// Parses `text` as one JSON document (RFC 8259).
/// \throws ModelError("", "malformed JSON at line L, column C (byte B): reason") on bad syntax,
///         ModelError(pointer, "duplicate key ...") on a repeated key, and
///         ModelError(pointer, "nested too deeply ...") beyond json_max_depth.
JsonValue parse_json(std::string_view text);

/// Escapes a key for use in a JSON pointer (RFC 6901: "~" -> "~0", "/" -> "~1").
std::string escape_pointer_token(std::string_view key);

/// `text` in single quotes for a message, on one line (control characters as spaces); a text
/// longer than `limit` characters is cut to its first `limit` with "..." and its length, so a
/// 100,000-digit number does not fill the message.
std::string quoted_excerpt(std::string_view text, std::size_t limit = 40);

/// Human name of a JSON type ("a number", "an object", ...) for messages.
const char* describe_type(JsonValue::Type type);

}  // namespace hipair::model_detail
