// Robust input and output (issue 9, sections 4 and 5), with generated instances:
// - JSON numbers beyond double range read exactly; malformed numbers named by JSON pointer;
//   huge literals not echoed whole;
// - tan next to (not at) a pole is a certified huge value or "too large", never "undefined";
// - names with control characters refused with their pointer (a fuzz loop), every text of an
//   SVG XML-escaped, random bytes included;
// - mechanism SVGs of one model scaled by 10^k, k in [-300, 400], are well-formed, have a finite
//   non-empty viewBox and draw the same picture;
// - outputs that are inputs are refused; a directory of outputs is published all or nothing.
#include "io/output_directory.hpp"
#include "io/output_paths.hpp"
#include "io/svg.hpp"
#include "model/expression.hpp"
#include "render/mechanism_svg.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------ helpers

// A small XML well-formedness check: one root, tags closed in order, attributes quoted,
// references only to the predefined entities or numeric character references of XML
// characters, no control characters, valid UTF-8.
::testing::AssertionResult well_formed_xml(const std::string& xml) {
  // UTF-8 and XML characters
  for (std::size_t i = 0; i < xml.size();) {
    auto b = static_cast<unsigned char>(xml[i]);
    if (b < 0x80) {
      if ((b < 0x20 && b != '\t' && b != '\n' && b != '\r') || b == 0x7F)
        return ::testing::AssertionFailure() << "control character " << int(b) << " at byte " << i;
      ++i;
      continue;
    }
    std::size_t n = b >= 0xF0 ? 4 : b >= 0xE0 ? 3 : b >= 0xC2 ? 2 : 0;
    if (n == 0 || b > 0xF4 || i + n > xml.size()) return ::testing::AssertionFailure() << "bad UTF-8 at byte " << i;
    unsigned long code = b & (n == 2 ? 0x1F : n == 3 ? 0x0F : 0x07);
    for (std::size_t k = 1; k < n; ++k) {
      auto c = static_cast<unsigned char>(xml[i + k]);
      if ((c & 0xC0) != 0x80) return ::testing::AssertionFailure() << "bad UTF-8 at byte " << i;
      code = (code << 6) | (c & 0x3F);
    }
    if ((code >= 0x80 && code <= 0x9F) || (code >= 0xD800 && code <= 0xDFFF) || code == 0xFFFE || code == 0xFFFF)
      return ::testing::AssertionFailure() << "not an XML character U+" << std::hex << code;
    i += n;
  }
  if (xml.rfind("<?xml", 0) != 0) return ::testing::AssertionFailure() << "no XML declaration";
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = xml.find("?>") + 2;
  static const std::regex reference("^&(amp|lt|gt|quot|apos|#[0-9]+|#x[0-9a-fA-F]+);");
  auto check_references = [&](const std::string& text) {
    for (std::size_t amp = text.find('&'); amp != std::string::npos; amp = text.find('&', amp + 1))
      if (!std::regex_search(text.substr(amp, 12), reference)) return false;
    return true;
  };
  while (i < xml.size()) {
    std::size_t lt = xml.find('<', i);
    std::string text = xml.substr(i, (lt == std::string::npos ? xml.size() : lt) - i);
    if (!check_references(text)) return ::testing::AssertionFailure() << "bad reference in text near " << i;
    if (open.empty() && text.find_first_not_of(" \t\r\n") != std::string::npos)
      return ::testing::AssertionFailure() << "text outside the root element";
    if (lt == std::string::npos) break;
    // a tag: scan attributes with their quotes
    std::size_t j = lt + 1;
    bool closing = j < xml.size() && xml[j] == '/';
    if (closing) ++j;
    std::size_t name_end = xml.find_first_of(" \t\r\n/>", j);
    if (name_end == std::string::npos) return ::testing::AssertionFailure() << "unclosed tag at " << lt;
    std::string name = xml.substr(j, name_end - j);
    if (name.empty() || !std::regex_match(name, std::regex("[A-Za-z_][A-Za-z0-9_.:-]*")))
      return ::testing::AssertionFailure() << "bad tag name '" << name << "' at " << lt;
    j = name_end;
    bool self_closing = false;
    std::set<std::string> attributes;
    while (true) {
      while (j < xml.size() && std::isspace(static_cast<unsigned char>(xml[j]))) ++j;
      if (j >= xml.size()) return ::testing::AssertionFailure() << "unclosed tag at " << lt;
      if (xml[j] == '>') break;
      if (xml.compare(j, 2, "/>") == 0) {
        self_closing = true;
        ++j;
        break;
      }
      if (closing) return ::testing::AssertionFailure() << "attribute in a closing tag at " << lt;
      std::size_t eq = xml.find('=', j);
      if (eq == std::string::npos) return ::testing::AssertionFailure() << "attribute without value at " << j;
      std::string attribute = xml.substr(j, eq - j);
      if (!std::regex_match(attribute, std::regex("[A-Za-z_][A-Za-z0-9_.:-]*")))
        return ::testing::AssertionFailure() << "bad attribute name '" << attribute << "' at " << j;
      if (!attributes.insert(attribute).second) return ::testing::AssertionFailure() << "repeated attribute " << attribute;
      char quote = xml[eq + 1];
      if (quote != '"' && quote != '\'') return ::testing::AssertionFailure() << "unquoted attribute at " << eq;
      std::size_t close = xml.find(quote, eq + 2);
      if (close == std::string::npos) return ::testing::AssertionFailure() << "unterminated attribute at " << eq;
      std::string value = xml.substr(eq + 2, close - eq - 2);
      if (value.find('<') != std::string::npos) return ::testing::AssertionFailure() << "'<' in an attribute at " << eq;
      if (!check_references(value)) return ::testing::AssertionFailure() << "bad reference in an attribute at " << eq;
      j = close + 1;
    }
    if (closing) {
      if (open.empty() || open.back() != name) return ::testing::AssertionFailure() << "mismatched </" << name << ">";
      open.pop_back();
    } else {
      if (open.empty() && ++roots > 1) return ::testing::AssertionFailure() << "more than one root element";
      if (!self_closing) open.push_back(name);
    }
    i = j + 1;
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> not closed";
  if (roots != 1) return ::testing::AssertionFailure() << "no root element";
  return ::testing::AssertionSuccess();
}

std::string attribute(const std::string& xml, const std::string& name) {
  std::smatch match;
  if (!std::regex_search(xml, match, std::regex(" " + name + "=\"([^\"]*)\""))) return "";
  return match[1];
}

std::string model_error(const std::string& text) {
  try {
    read_model(text);
  } catch (const ModelError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("not a ModelError: ") + error.what();
  }
  return "accepted";
}

std::string pointer_of(const std::string& text) {
  try {
    read_model(text);
  } catch (const ModelError& error) {
    return error.pointer();
  }
  return "<accepted>";
}

// One plate whose corner coordinates are the given JSON texts.
std::string plate_model(const std::string& x, const std::string& y) {
  return R"({"hipair": 1, "name": "plate", "parts": [{"name": "plate", "motion": "fixed", "loops": [{"start": [0, 0],
    "edges": [{"line_to": [)" + x + R"(, 0]}, {"line_to": [)" + x + ", " + y + R"(]}, {"line_to": [0, )" + y +
         R"(]}, {"line_to": [0, 0]}]}]}]})";
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void write_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

// Every file (relative path -> bytes) under a directory, for before/after comparisons.
std::map<std::string, std::string> snapshot(const fs::path& directory) {
  std::map<std::string, std::string> files;
  if (!fs::exists(directory)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    std::string name = fs::relative(entry.path(), directory).string();
    files[name] = entry.is_directory() ? std::string("<dir>") : read_file(entry.path());
  }
  return files;
}

fs::path fresh_directory(const std::string& name) {
  fs::path directory = fs::temp_directory_path() / ("hipair-io-test-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

// ------------------------------------------------------------------ numbers

// The reader may reverse a loop to orient it: look for the value among the vertices.
bool has_vertex_x(const Model& model, const Rational& x) {
  for (const Edge& edge : model.parts[0].loops[0].edges)
    if (edge.source.x == x) return true;
  return false;
}

TEST(ExactNumbers, BeyondDoubleRangeAreReadExactly) {
  for (const char* literal : {"1e309", "1e-400", "1e1000", "-2.5e999", "1e-1000", "123456789e300",
                              "17976931348623159e292", "4.9e-325"}) {
    SCOPED_TRACE(literal);
    Model model = read_model(plate_model(literal, "1"));
    EXPECT_TRUE(has_vertex_x(model, parse_rational(literal))) << literal;
  }
  // generated: every decimal exponent from -1000 to 1000 in steps of 37, mantissa 7.25
  for (int e = -1000; e <= 1000; e += 37) {
    std::string literal = "7.25e" + std::to_string(e);
    Model model = read_model(plate_model(literal, "1"));
    Rational expected = parse_rational("725") / 100;
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(e)));
    expected = e >= 0 ? Rational(expected * p) : Rational(expected / p);
    EXPECT_TRUE(has_vertex_x(model, expected)) << literal;
  }
}

TEST(ExactNumbers, OutOfRangeAndMalformedNumbersAreNamedByPointer) {
  const std::string where = "/parts/0/loops/0/edges/0/line_to/0";
  for (const char* literal : {"1e1001", "1e5000", "1e100000", "-1e-5000", "1e99999999999"}) {
    std::string message = model_error(plate_model(literal, "1"));
    EXPECT_EQ(pointer_of(plate_model(literal, "1")), where) << literal << ": " << message;
    EXPECT_NE(message.find("out of range"), std::string::npos) << message;
    EXPECT_EQ(message.find("malformed JSON"), std::string::npos) << message;
  }
  for (const char* literal : {"1.", "-", "1e", "1e+", ".5", "-a", "1.e5", "+1", "-.5", "1.5e-"}) {
    std::string message = model_error(plate_model(literal, "1"));
    EXPECT_EQ(pointer_of(plate_model(literal, "1")), where) << literal << ": " << message;
  }
  // the second coordinate of a point, and an object member
  EXPECT_EQ(pointer_of(plate_model("1", "1e5000")), "/parts/0/loops/0/edges/1/line_to/1");
  EXPECT_EQ(pointer_of(R"({"hipair": 1, "name": "x", "parts": [], "z": 1e5000})"), "/z");
}

TEST(ExactNumbers, HugeLiteralsAreNotEchoedWhole) {
  std::string digits(100001, '7');
  // too large: refused without the number
  for (const std::string& literal : {digits, digits + "e5", "1" + std::string(100000, '0') + ".5", "-" + digits}) {
    std::string message = model_error(plate_model(literal, "1"));
    EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
    EXPECT_NE(message.find("too large"), std::string::npos) << message.substr(0, 300);
    EXPECT_EQ(pointer_of(plate_model(literal, "1")), "/parts/0/loops/0/edges/0/line_to/0");
  }
  // malformed: the number is cut, with its length
  for (const std::string& literal : {digits + ".", digits + "e", digits + "e+", "-" + digits + ".x"}) {
    std::string message = model_error(plate_model(literal, "1"));
    EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
    EXPECT_NE(message.find("...' ("), std::string::npos) << message.substr(0, 300);
    EXPECT_NE(message.find(" characters)"), std::string::npos) << message.substr(0, 300);
    EXPECT_EQ(pointer_of(plate_model(literal, "1")), "/parts/0/loops/0/edges/0/line_to/0");
  }
  // as strings and in expressions too
  std::string message = model_error(plate_model("\"" + digits + "x\"", "1"));
  EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
  message = model_error(plate_model("\"" + digits + "\"", "1"));
  EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
}

// ------------------------------------------------------------------ messages with two values

TEST(MessagesWithTwoValues, NeverPrintDifferentValuesAsEqual) {
  std::mt19937 random(6);
  for (int k = 1; k <= 400; k += 3) {
    std::string tiny = "1e-" + std::to_string(k);
    std::string base = std::to_string(1 + random() % 50) + "." + std::to_string(random() % 1000);
    std::string shifted = "\"" + base + " + " + tiny + "\"";
    // an open loop whose last vertex misses the start by 10^-k
    std::string loop = R"({"hipair": 1, "name": "p", "parts": [{"name": "plate", "motion": "fixed", "loops": [{"start": [)" +
                       base + R"(, 6], "edges": [{"line_to": [60, 0]}, {"line_to": [60, 6]}, {"line_to": [)" + shifted +
                       R"(, 6]}]}]}]})";
    std::string message = model_error(loop);
    std::smatch match;
    ASSERT_TRUE(std::regex_search(message, match, std::regex("ends at (\\([^)]*\\)), not at the start (\\([^)]*\\))")))
        << message;
    EXPECT_NE(match[1].str(), match[2].str()) << message;
    // limits lo >= hi by 10^-k
    std::string limits = R"({"hipair": 1, "name": "p", "parts": [{"name": "arm", "motion": {"rotation": {"pivot": [0, 0], "limits": [)" +
                         shifted + ", " + base + R"(]}}, "loops": [{"circle": {"center": [0, 0], "radius": 1}}]}]})";
    message = model_error(limits);
    ASSERT_TRUE(std::regex_search(message, match, std::regex("lower limit (\\S+) must be less than the upper limit (\\S+)")))
        << message;
    EXPECT_NE(match[1].str(), match[2].str()) << message;
    // a nominal value just outside its range
    std::string range = R"({"hipair": 1, "name": "p", "parameters": {"a": {"nominal": )" + shifted +
                        R"(, "range": [0, )" + base + R"(]}}, "parts": [{"name": "arm", "motion": "fixed", "loops": [{"circle": {"center": [0, 0], "radius": 1}}]}]})";
    message = model_error(range);
    ASSERT_TRUE(std::regex_search(message, match, std::regex("nominal value (\\S+) lies outside its range \\[0, (\\S+)\\]")))
        << message;
    EXPECT_NE(match[1].str(), match[2].str()) << message;
  }
}

// ------------------------------------------------------------------ tan next to a pole

std::string evaluate_message(const std::string& expression, Rational* value = nullptr) {
  model_detail::ExpressionContext context;
  context.pointer = "/x";
  try {
    std::vector<Rounding> roundings;
    Rational v = model_detail::to_rational(model_detail::evaluate_expression(expression, context), "/x", expression,
                                           roundings);
    if (value) *value = v;
    return "value";
  } catch (const ModelError& error) {
    return error.what();
  }
}

TEST(TangentNearPole, IsAHugeValueOrTooLargeNeverUndefined) {
  EXPECT_NE(evaluate_message("tan(pi/2)").find("undefined"), std::string::npos);
  EXPECT_NE(evaluate_message("tan(3*pi/2)").find("undefined"), std::string::npos);
  for (int k = 1; k <= 1000; k += (k < 20 ? 1 : 13)) {
    for (const char* form : {"tan(pi/2 + 10^-%d)", "tan(pi/2 - 10^-%d)", "tan(-pi/2 + 10^-%d)", "tan(7*pi/2 - 10^-%d)"}) {
      char expression[64];
      std::snprintf(expression, sizeof expression, form, k);
      Rational value;
      std::string message = evaluate_message(expression, &value);
      SCOPED_TRACE(expression);
      EXPECT_EQ(message.find("undefined"), std::string::npos) << message;
      if (message == "value") {
        // tan(pole + e) = -cot(e) ~ -1/e: certified sign and size
        bool above = std::string(form).find("+ 10") != std::string::npos;
        EXPECT_EQ(sgn(value), above ? -1 : 1);
        mpz_class p;
        mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(k));
        Rational size = abs(value) / Rational(p);
        EXPECT_GT(size, Rational(9, 10));
        EXPECT_LT(size, Rational(11, 10));
      } else {
        EXPECT_NE(message.find("too large"), std::string::npos) << message;
      }
    }
  }
  // in degrees: 90.000...1 deg is not a pole
  std::string message = evaluate_message("tan(90.0000000000000000000000000000000000000000000000000000000000000000000000000000000001 deg)");
  EXPECT_EQ(message.find("undefined"), std::string::npos) << message;
}

// ------------------------------------------------------------------ names and escaping

TEST(ControlCharacters, NamesWithThemAreRefusedWithTheirPointer) {
  std::mt19937 random(9);
  auto control = [&]() -> std::string {
    int kind = static_cast<int>(random() % 3);
    if (kind == 0) return std::string(1, static_cast<char>(random() % 0x20));  // C0, \u0000 included
    if (kind == 1) return "\x7F";                                                // DEL
    return std::string("\xC2") + static_cast<char>(0x80 + random() % 0x20);     // C1
  };
  auto json_escape = [](const std::string& text) {
    std::string out;
    for (char c : text) {
      auto u = static_cast<unsigned char>(c);
      if (u < 0x20 || c == '"' || c == '\\') {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "\\u%04x", u);
        out += buffer;
      } else {
        out += c;
      }
    }
    return out;
  };
  const char* printable[] = {"arm", "Zahnrad ä", "дуга", "歯車", "a<b&c", "x'\"y", "\xF0\x9F\x94\xA7"};
  int refused = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::string name = printable[random() % 7];
    std::string inserted = control();
    name.insert(random() % 2 ? name.size() : 0, inserted);
    int slot = static_cast<int>(random() % 5);
    std::string model_name = slot == 0 ? json_escape(name) : "m";
    std::string part_name = slot == 1 ? json_escape(name) : "plate";
    std::string label = slot == 2 ? json_escape(name) : "side";
    std::string loop_label = slot == 3 ? json_escape(name) : "outline";
    std::string description = slot == 4 ? json_escape(name) : "text";
    std::string text = R"({"hipair": 1, "name": ")" + model_name + R"(", "description": ")" + description +
                       R"(", "parts": [{"name": ")" + part_name + R"(", "motion": "fixed", "loops": [{"label": ")" +
                       loop_label + R"(", "start": [0, 0], "edges": [{"line_to": [1, 0], "label": ")" + label +
                       R"("}, {"line_to": [1, 1]}, {"line_to": [0, 0]}]}]}]})";
    const char* expected[] = {"/name", "/parts/0/name", "/parts/0/loops/0/edges/0/label", "/parts/0/loops/0/label",
                              "/description"};
    bool layout = slot == 4 && (inserted == "\t" || inserted == "\n" || inserted == "\r");
    if (layout) {
      EXPECT_NO_THROW(read_model(text)) << "a description may hold tabs and line breaks";
      continue;
    }
    SCOPED_TRACE(text);
    EXPECT_EQ(pointer_of(text), expected[slot]);
    std::string message = model_error(text);
    EXPECT_NE(message.find("control character U+"), std::string::npos) << message;
    for (char c : message) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7F) << "raw control in message";
    ++refused;
  }
  EXPECT_GT(refused, 500);
  // the same names without the control character are accepted and drawn well-formed
  for (const char* name : printable) {
    std::string text = R"({"hipair": 1, "name": ")" + json_escape(name) + R"(", "parts": [{"name": ")" +
                       json_escape(name) + R"(", "motion": "fixed", "loops": [{"start": [0, 0], "edges": [{"line_to": [1, 0], "label": ")" +
                       json_escape(name) + R"("}, {"line_to": [1, 1]}, {"line_to": [0, 0]}]}]}]})";
    Model model = read_model(text);
    render::MechanismSvgOptions options;
    options.labels = true;
    std::string svg = render::mechanism_svg(model, {model.parts[0].initial}, options);
    EXPECT_TRUE(well_formed_xml(svg)) << name;
    EXPECT_NE(svg.find(io::escape_xml(name)), std::string::npos) << name;
  }
}

TEST(ControlCharacters, EveryTextOfAnSvgIsEscaped) {
  // Models made through the API are not read: the writer itself must keep the XML well-formed.
  std::mt19937 random(4);
  for (int trial = 0; trial < 300; ++trial) {
    std::string name;
    std::size_t length = 1 + random() % 24;
    for (std::size_t i = 0; i < length; ++i) name += static_cast<char>(random() % 256);
    std::string escaped = io::escape_xml(name);
    io::SvgWriter svg(io::SvgBox{0, 0, 10, 10});
    svg.begin_group(name, name, name);
    svg.text(1, 1, name, 1, name, name, name);
    io::SvgPath path;
    path.move_to(0, 0);
    path.line_to(1, 1);
    svg.path(path, io::SvgStyle{}, name);
    svg.end_group();
    EXPECT_TRUE(well_formed_xml(svg.str())) << escaped;
    // printable ASCII survives unchanged
    std::string plain = "plain <name> & 'quotes'";
    EXPECT_EQ(io::escape_xml(plain), "plain &lt;name&gt; &amp; &apos;quotes&apos;");
  }
  EXPECT_EQ(io::escape_xml(std::string("a\0b", 3)), "a\xEF\xBF\xBD" "b");
  EXPECT_EQ(io::escape_xml("a\x1b[31mb"), "a\xEF\xBF\xBD[31mb");
  EXPECT_EQ(io::escape_xml("tab\there"), "tab&#9;here");
  EXPECT_EQ(io::escape_xml("\xC2\x9B"), "\xEF\xBF\xBD");  // C1 CSI
  EXPECT_EQ(io::escape_xml("\xC3\xA4"), "\xC3\xA4");      // ä stays
}

// ------------------------------------------------------------------ SVG at every scale

// A plate, a rotating arm with an arc, a translating puck and a planar block, every length
// written as a JSON number m·10^k.
std::string scaled_model(int k) {
  auto n = [k](const char* mantissa) { return std::string(mantissa) + "e" + std::to_string(k); };
  return R"({"hipair": 1, "name": "scaled 10^)" + std::to_string(k) + R"(", "units": {"angle": "deg"}, "parts": [
    {"name": "plate", "motion": "fixed", "loops": [{"start": [0, 0], "edges": [{"line_to": [)" + n("20") +
         R"(, 0]}, {"line_to": [)" + n("20") + ", " + n("10") + R"(]}, {"line_to": [0, )" + n("10") +
         R"(]}, {"line_to": [0, 0]}]}]},
    {"name": "arm", "motion": {"rotation": {"pivot": [)" + n("30") + ", " + n("5") + R"(]}}, "initial": {"angle": 30},
     "loops": [{"start": [)" + n("30") + ", " + n("3") + R"(], "edges": [{"line_to": [)" + n("45") + ", " + n("3") +
         R"(], "label": "lower"}, {"arc_to": [)" + n("45") + ", " + n("7") + R"(], "center": [)" + n("45") + ", " + n("5") +
         R"(], "dir": "ccw", "label": "tip"}, {"line_to": [)" + n("30") + ", " + n("7") + R"(]}, {"line_to": [)" + n("30") +
         ", " + n("3") + R"(]}]}]},
    {"name": "puck", "motion": {"translation": {"direction": [1, 0]}}, "initial": {"offset": )" + n("5") + R"(},
     "loops": [{"circle": {"center": [)" + n("10") + ", " + n("25") + R"(], "radius": )" + n("3") + R"(}}]},
    {"name": "block", "motion": {"planar": {"pivot": [)" + n("50") + ", " + n("20") + R"(]}},
     "initial": {"x": )" + n("1") + R"(, "y": )" + n("-2") + R"(, "angle": 45},
     "loops": [{"start": [)" + n("48") + ", " + n("18") + R"(], "edges": [{"line_to": [)" + n("52") + ", " + n("18") +
         R"(]}, {"line_to": [)" + n("52") + ", " + n("22") + R"(]}, {"line_to": [)" + n("48") + ", " + n("22") +
         R"(]}, {"line_to": [)" + n("48") + ", " + n("18") + R"(]}]}]}
  ]})";
}

std::vector<std::string> path_data(const std::string& svg) {
  std::vector<std::string> paths;
  static const std::regex d(" d=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), d); it != std::sregex_iterator(); ++it)
    if ((*it)[1] != "M0,0 L10,5 L0,10 z") paths.push_back((*it)[1]);  // not the arrowhead marker
  return paths;
}

::testing::AssertionResult sane_view_box(const std::string& svg) {
  std::istringstream box(attribute(svg, "viewBox"));
  double values[4];
  for (double& v : values)
    if (!(box >> v) || !std::isfinite(v)) return ::testing::AssertionFailure() << "viewBox '" << attribute(svg, "viewBox") << "'";
  if (!(values[2] > 0 && values[3] > 0)) return ::testing::AssertionFailure() << "empty viewBox";
  if (std::abs(values[0]) > 1e6 || std::abs(values[1]) > 1e6 || values[2] > 1e6 || values[3] > 1e6 || values[2] < 1e-3)
    return ::testing::AssertionFailure() << "viewBox not normalised: " << attribute(svg, "viewBox");
  return ::testing::AssertionSuccess();
}

TEST(SvgScale, OneModelScaledBy10ToTheKDrawsTheSamePicture) {
  Model unit = read_model(scaled_model(0));
  std::vector<PartConfiguration> initial;
  for (const Part& part : unit.parts) initial.push_back(part.initial);
  std::string reference = render::mechanism_svg(unit, initial);
  ASSERT_TRUE(well_formed_xml(reference));
  ASSERT_TRUE(sane_view_box(reference));
  std::vector<std::string> reference_paths = path_data(reference);
  ASSERT_GE(reference_paths.size(), 4u);
  std::smatch reference_match;
  ASSERT_TRUE(std::regex_search(reference, reference_match, std::regex(">([0-9.e-]+) mm</text>")));
  Rational reference_bar = parse_rational(reference_match[1].str());
  for (int k = -300; k <= 400; k += (k > -290 && k < 390 ? 7 : 1)) {
    SCOPED_TRACE("scale 10^" + std::to_string(k));
    Model model = read_model(scaled_model(k));
    std::vector<PartConfiguration> configurations;
    for (const Part& part : model.parts) configurations.push_back(part.initial);
    render::MechanismSvgOptions options;
    options.labels = true;
    std::string svg = render::mechanism_svg(model, configurations, options);
    ASSERT_TRUE(well_formed_xml(svg));
    ASSERT_TRUE(sane_view_box(svg));
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
    // the same geometry: the normalised drawing does not depend on the scale
    EXPECT_EQ(path_data(svg), path_data(render::mechanism_svg(model, configurations)));
    EXPECT_EQ(path_data(render::mechanism_svg(model, configurations)), reference_paths);
    // the scale bar says the real length: its length at scale 1 times 10^k
    std::smatch bar;
    ASSERT_TRUE(std::regex_search(svg, bar, std::regex(">([0-9.e-]+) mm</text>")));
    Rational shown = parse_rational(bar[1].str());
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(k)));
    Rational expected = reference_bar * (k >= 0 ? Rational(p) : Rational(mpz_class(1), p));
    EXPECT_EQ(shown, expected) << bar[1];
    // the legend gives the puck's offset 5·10^k
    std::string offset = k == 0 ? "s = 5 mm" : "s = 5e" + std::to_string(k) + " mm";
    if (k >= -4 && k < 6) offset = "";
    if (!offset.empty()) EXPECT_NE(svg.find(offset), std::string::npos) << offset;
  }
}

TEST(SvgScale, APlateOfWidth2e400DrawsItsFullWidth) {
  Model model = read_model(plate_model("2e400", "1e400"));
  std::string svg = render::mechanism_svg(model, {model.parts[0].initial});
  ASSERT_TRUE(well_formed_xml(svg));
  ASSERT_TRUE(sane_view_box(svg));
  std::vector<std::string> paths = path_data(svg);
  ASSERT_FALSE(paths.empty());
  EXPECT_EQ(paths[0], "M0,0 L200,0 L200,-100 L0,-100 L0,0 Z");
  // and a plate of width 2e-300 far from the origin
  model = read_model(plate_model("2e-300", "1e-300"));
  svg = render::mechanism_svg(model, {model.parts[0].initial});
  ASSERT_TRUE(sane_view_box(svg));
  EXPECT_EQ(path_data(svg)[0], "M0,0 L200,0 L200,-100 L0,-100 L0,0 Z");
}

TEST(SvgScale, NumbersAreNeverCutOrLost) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> exponent(-300, 300), mantissa(-10, 10);
  for (int trial = 0; trial < 5000; ++trial) {
    double value = mantissa(random) * std::pow(10.0, exponent(random));
    std::string text = io::format_number(value);
    ASSERT_LT(text.size(), 32u) << text;
    double back = std::strtod(text.c_str(), nullptr);
    EXPECT_LE(std::abs(back - value), std::abs(value) * 1e-6) << value << " -> " << text;
  }
  EXPECT_EQ(io::format_number(1.5), "1.5");
  EXPECT_EQ(io::format_number(-3.25), "-3.25");
  EXPECT_EQ(io::format_number(1234.56789), "1234.5679");
  EXPECT_EQ(io::format_number(std::numeric_limits<double>::infinity()), "0");  // never "inf"
  EXPECT_EQ(io::format_number(1e-300), "1e-300");
  EXPECT_EQ(io::format_number(-0.00001), "-1e-05");
}

// ------------------------------------------------------------------ outputs that are inputs

TEST(OutputPaths, AnOutputThatIsAnInputIsRefused) {
  fs::path directory = fresh_directory("refuse");
  fs::path model = directory / "model.json";
  write_file(model, "{}");
  fs::create_symlink(model, directory / "link.json");
  fs::create_hard_link(model, directory / "hard.json");
  fs::create_directories(directory / "sub");
  for (const fs::path& output : {model, directory / "." / "model.json", directory / "sub" / ".." / "model.json",
                                 directory / "link.json", directory / "hard.json"}) {
    SCOPED_TRACE(output.string());
    EXPECT_THROW(io::refuse_overwriting_input(output, "--svg", model), IoError);
    try {
      io::refuse_overwriting_input(output, "--svg", model);
    } catch (const IoError& error) {
      EXPECT_NE(std::string(error.what()).find("--svg"), std::string::npos);
      EXPECT_NE(std::string(error.what()).find("refusing"), std::string::npos);
    }
  }
  // relative to the working directory
  fs::path here = fs::current_path();
  fs::current_path(directory);
  EXPECT_THROW(io::refuse_overwriting_input("model.json", "--out", directory / "model.json"), IoError);
  EXPECT_THROW(io::refuse_overwriting_input("./sub/../model.json", "--out", "model.json"), IoError);
  fs::current_path(here);
  EXPECT_NO_THROW(io::refuse_overwriting_input(directory / "other.json", "--svg", model));
  EXPECT_NO_THROW(io::refuse_overwriting_input(directory / "sub" / "model.json", "--svg", model));
  // two outputs that are one file
  EXPECT_THROW(io::refuse_overwriting_inputs({{directory / "a.svg", "--svg"}, {directory / "./a.svg", "--json"}}, {model}),
               IoError);
  EXPECT_EQ(read_file(model), "{}");
  fs::remove_all(directory);
}

// ------------------------------------------------------------------ publishing a directory

std::vector<io::RunFile> run_files(const std::string& tag, std::size_t count) {
  std::vector<io::RunFile> files;
  files.push_back({"report.json", "{\"run\": \"" + tag + "\"}\n"});
  files.push_back({"kinematics.csv", "run," + tag + "\n"});
  for (std::size_t i = 1; i <= count; ++i)
    files.push_back({"certificate-" + std::to_string(i) + ".json", tag + std::to_string(i)});
  return files;
}

bool is_output(const std::string& name) {
  return name == "report.json" || name == "kinematics.csv" || name.rfind("certificate-", 0) == 0;
}

std::vector<std::string> leftovers(const fs::path& parent) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(parent))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) names.push_back(entry.path().string());
  return names;
}

TEST(PublishDirectory, AllFilesOfARunOrNone) {
  fs::path parent = fresh_directory("publish");
  fs::path out = parent / "out";
  // into a new directory
  io::publish_directory(out, run_files("one", 3), is_output);
  EXPECT_EQ(read_file(out / "report.json"), "{\"run\": \"one\"}\n");
  EXPECT_EQ(read_file(out / "certificate-3.json"), "one3");
  write_file(out / "notes.txt", "mine");
  // a second run replaces the first one's files, drops its extra certificate, keeps others
  io::publish_directory(out, run_files("two", 2), is_output);
  EXPECT_EQ(read_file(out / "kinematics.csv"), "run,two\n");
  EXPECT_FALSE(fs::exists(out / "certificate-3.json"));
  EXPECT_EQ(read_file(out / "notes.txt"), "mine");
  EXPECT_TRUE(leftovers(parent).empty());

  // a failure at every step of the publication leaves the directory exactly as it was
  std::map<std::string, std::string> before = snapshot(out);
  for (int step = 1; step <= 12; ++step) {
    SCOPED_TRACE("failure at move " + std::to_string(step));
    ::setenv("HIPAIR_TEST_PUBLISH_FAIL_AT", std::to_string(step).c_str(), 1);
    bool threw = false;
    try {
      io::publish_directory(out, run_files("three", 4), is_output);
    } catch (const IoError& error) {
      threw = true;
      EXPECT_NE(std::string(error.what()).find("left as it was"), std::string::npos) << error.what();
    }
    ::unsetenv("HIPAIR_TEST_PUBLISH_FAIL_AT");
    if (!threw) {  // fewer moves than `step`: the run was published whole
      EXPECT_EQ(read_file(out / "certificate-4.json"), "three4");
      break;
    }
    EXPECT_EQ(snapshot(out), before);
    EXPECT_TRUE(leftovers(parent).empty());
  }
  // a failure renaming the staging directory into a new one leaves no directory
  ::setenv("HIPAIR_TEST_PUBLISH_FAIL_AT", "1", 1);
  EXPECT_THROW(io::publish_directory(parent / "new", run_files("four", 1), is_output), IoError);
  ::unsetenv("HIPAIR_TEST_PUBLISH_FAIL_AT");
  EXPECT_FALSE(fs::exists(parent / "new"));
  EXPECT_TRUE(leftovers(parent).empty());
  fs::remove_all(parent);
}

TEST(PublishDirectory, AFullDiskLeavesTheDirectoryAsItWas) {
  // RLIMIT_FSIZE makes writes beyond 4 KB fail (EFBIG) like a full disk.
  fs::path parent = fresh_directory("full");
  fs::path out = parent / "out";
  io::publish_directory(out, run_files("old", 2), is_output);
  std::map<std::string, std::string> before = snapshot(out);
  std::vector<io::RunFile> files = run_files("new", 2);
  files.insert(files.begin() + 1, io::RunFile{"kinematics.svg", std::string(20000, 'x')});
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old_limit{};
  ::getrlimit(RLIMIT_FSIZE, &old_limit);
  rlimit small = old_limit;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    io::publish_directory(out, files, is_output);
  } catch (const IoError&) {
    threw = true;
  }
  bool threw_new = false;
  try {
    io::publish_directory(parent / "new", files, is_output);
  } catch (const IoError&) {
    threw_new = true;
  }
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_TRUE(threw);
  EXPECT_TRUE(threw_new);
  EXPECT_EQ(snapshot(out), before);
  EXPECT_FALSE(fs::exists(parent / "new"));
  EXPECT_TRUE(leftovers(parent).empty());
  fs::remove_all(parent);
}

}  // namespace
}  // namespace hipair
