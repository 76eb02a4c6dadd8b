#include "model/json_document.hpp"

#include "model/expression.hpp"

#include <hipair/error.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <unordered_set>

namespace hipair::model_detail {
namespace {

// nlohmann's lexer converts every number to its float type and calls a number beyond that
// type's range malformed. With long double (exponent range about ±4932) every literal the model
// format admits (decimal exponent at most 1000, values of at most 4096 bits, about 10^1233)
// lexes; the value is never used: the exact value comes from the number's text.
using ExactJson = nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t, std::uint64_t, long double>;
static_assert(std::numeric_limits<long double>::max_exponent10 > 1300,
              "the JSON layer needs a long double with a wide exponent range");

// Keeps messages on one line and printable.
std::string sanitize(std::string_view text) {
  std::string out;
  for (char c : text) {
    auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      out += ' ';
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string quoted_excerpt(std::string_view text, std::size_t limit) {
  if (text.size() <= limit) return "'" + sanitize(text) + "'";
  std::size_t cut = limit;
  // do not cut a UTF-8 sequence in two
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return "'" + sanitize(text.substr(0, cut)) + "...' (" + std::to_string(text.size()) + " characters)";
}

namespace {

// The reason part of an nlohmann exception message; quoted tokens longer than 40 characters
// (a 100,000-digit number) are cut, with their length.
std::string reason_of(const std::string& what) {
  std::string reason = what;
  if (!reason.empty() && reason[0] == '[') {
    if (auto close = reason.find("] "); close != std::string::npos) reason.erase(0, close + 2);
  }
  if (reason.rfind("parse error", 0) == 0) {
    if (auto colon = reason.find(": "); colon != std::string::npos) reason.erase(0, colon + 2);
  }
  std::string shortened;
  for (std::size_t i = 0; i < reason.size();) {
    std::size_t open = reason.find('\'', i);
    std::size_t close = open == std::string::npos ? std::string::npos : reason.find('\'', open + 1);
    if (close == std::string::npos) {
      shortened += reason.substr(i);
      break;
    }
    shortened += reason.substr(i, open - i) + quoted_excerpt(std::string_view(reason).substr(open + 1, close - open - 1));
    i = close + 1;
  }
  reason = shortened;
  std::string printable = sanitize(reason);
  for (char& c : printable)
    if (static_cast<unsigned char>(c) >= 0x80) c = '?';  // the offending bytes may not be UTF-8
  return printable;
}

class DocumentBuilder final : public nlohmann::json_sax<ExactJson> {
 public:
  explicit DocumentBuilder(std::string_view text) : text_(text) {}

  JsonValue take_root() { return std::move(root_); }

  bool null() override {
    add(JsonValue::Type::null);
    return true;
  }
  bool boolean(bool value) override {
    add(JsonValue::Type::boolean).boolean = value;
    return true;
  }
  bool number_integer(number_integer_t value) override {
    add(JsonValue::Type::number).text = std::to_string(value);
    return true;
  }
  bool number_unsigned(number_unsigned_t value) override {
    add(JsonValue::Type::number).text = std::to_string(value);
    return true;
  }
  // Integers beyond 64 bits arrive here too, with their full text.
  bool number_float(number_float_t, const string_t& text) override {
    add(JsonValue::Type::number).text = text;
    return true;
  }
  bool string(string_t& value) override {
    add(JsonValue::Type::string).text = std::move(value);
    return true;
  }
  bool binary(binary_t&) override {
    throw ModelError("", "malformed JSON: binary values are not JSON");
  }
  bool start_object(std::size_t) override {
    open(add(JsonValue::Type::object));
    return true;
  }
  bool key(string_t& key) override {
    if (!keys_.back().insert(key).second)
      throw ModelError(open_.back()->pointer + "/" + escape_pointer_token(key),
                       "duplicate key '" + sanitize(key) + "'");
    pending_key_ = std::move(key);
    key_read_ = true;
    return true;
  }
  bool end_object() override {
    close();
    return true;
  }
  bool start_array(std::size_t) override {
    open(add(JsonValue::Type::array));
    return true;
  }
  bool end_array() override {
    close();
    return true;
  }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& error) override {
    // A number the lexer could not take (beyond even long double's range, or malformed):
    // named by the JSON pointer of the value it was to be.
    // (nlohmann's lexer says "invalid number"; "+1" and ".5" are "invalid literal"s read up to
    // the '+' or '.', and the token may start before the value)
    std::string what = error.what();
    bool number_token = what.find("invalid number") != std::string::npos ||
                        (what.find("invalid literal") != std::string::npos && !last_token.empty() &&
                         (last_token.back() == '+' || last_token.back() == '.'));
    if (error.id == 406 || (error.id == 101 && number_token)) {
      std::string pointer = pending_pointer();
      if (error.id == 406) {
        // The exact reader says why (exponent or size limit); it accepts nothing that
        // overflows long double, but a message is given even so.
        parse_literal(last_token, pointer);
        throw ModelError(pointer, "number " + quoted_excerpt(last_token) + " out of range");
      }
      throw ModelError(pointer, "malformed number: " + reason_of(error.what()));
    }
    // `position` counts the bytes read, including the offending one.
    std::size_t offset = position > 0 ? position - 1 : 0;
    if (offset > text_.size()) offset = text_.size();
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
      if (text_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string reason = reason_of(error.what());
    if (offset >= text_.size() && !text_.empty()) reason = "unexpected end of file (truncated?): " + reason;
    throw ModelError("", "malformed JSON at line " + std::to_string(line) + ", column " +
                             std::to_string(column) + " (byte " + std::to_string(offset) +
                             "): " + reason);
  }

 private:
  JsonValue& add(JsonValue::Type type) {
    JsonValue* value = nullptr;
    if (open_.empty()) {
      if (have_root_) throw ModelError("", "malformed JSON: more than one value");
      have_root_ = true;
      value = &root_;
      value->pointer = "";
    } else if (open_.back()->is_array()) {
      JsonValue& parent = *open_.back();
      parent.items.emplace_back();
      value = &parent.items.back();
      value->pointer = parent.pointer + "/" + std::to_string(parent.items.size() - 1);
    } else {
      JsonValue& parent = *open_.back();
      parent.members.push_back(JsonMember{pending_key_, JsonValue{}});
      value = &parent.members.back().value;
      value->pointer = parent.pointer + "/" + escape_pointer_token(pending_key_);
    }
    value->type = type;
    key_read_ = false;
    return *value;
  }
  void open(JsonValue& container) {
    if (open_.size() >= json_max_depth)
      throw ModelError(container.pointer, "nested too deeply (more than " +
                                              std::to_string(json_max_depth) + " levels)");
    open_.push_back(&container);
    keys_.emplace_back();
  }
  void close() {
    open_.pop_back();
    keys_.pop_back();
  }

  // The pointer of the value being read when the error came: the next item of the open array,
  // the member whose key was just read, or the open container itself.
  std::string pending_pointer() const {
    if (open_.empty()) return "";
    const JsonValue& parent = *open_.back();
    if (parent.is_array()) return parent.pointer + "/" + std::to_string(parent.items.size());
    if (key_read_) return parent.pointer + "/" + escape_pointer_token(pending_key_);
    return parent.pointer;
  }

  std::string_view text_;
  JsonValue root_;
  bool have_root_ = false;
  std::vector<JsonValue*> open_;
  std::vector<std::unordered_set<std::string>> keys_;
  std::string pending_key_;
  bool key_read_ = false;
};

}  // namespace

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const JsonMember& member : members)
    if (member.key == key) return &member.value;
  return nullptr;
}

JsonValue parse_json(std::string_view text) {
  // The parser's lexer takes a NUL byte for the end of the input, so a document followed by a
  // NUL and anything at all would be accepted (session 29): no JSON text holds a NUL byte.
  if (std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    std::string reason = "malformed JSON: a NUL byte at offset ";
    reason += std::to_string(nul);
    throw ModelError("", reason);
  }
  DocumentBuilder builder(text);
  bool ok = ExactJson::sax_parse(text.begin(), text.end(), &builder, ExactJson::input_format_t::json, true);
  if (!ok) throw ModelError("", "malformed JSON");
  return builder.take_root();
}

std::string escape_pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return sanitize(out);
}

const char* describe_type(JsonValue::Type type) {
  switch (type) {
    case JsonValue::Type::null: return "null";
    case JsonValue::Type::boolean: return "a boolean";
    case JsonValue::Type::number: return "a number";
    case JsonValue::Type::string: return "a string";
    case JsonValue::Type::array: return "an array";
    case JsonValue::Type::object: return "an object";
  }
  return "a value";
}

}  // namespace hipair::model_detail
