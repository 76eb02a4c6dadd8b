// `hipair cspace --json` for a 1-D or 2-D C-space: the document written as text as it is made,
// byte for byte what nlohmann::json's dump(1) of the document's tree wrote before (session 32),
// without a JSON tree per vertex and edge: an operating region's text is made in one pass over
// the space, and the tree of a large space (an 80 x 80 gear pair's region) is never held.
#pragma once

#include <hipair/cspace.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace hipair::cli {

/// JSON text as nlohmann::json::dump(1) writes a tree: one space of indentation per level,
/// `"key": value`, every member and element on its own line, "{}" and "[]" when empty; doubles
/// as nlohmann prints them (the shortest Grisu2 digits, "1.0", "1e-05", "null" when not
/// finite), integers in decimal, strings escaped as nlohmann escapes them. An object's keys are
/// given in ascending byte order, the order of nlohmann's std::map (a key out of order throws
/// hipair::Error: the text would differ from the tree's). The text is kept in a buffer that
/// goes to `out` in large pieces; finish() writes what is left.
class JsonText {
 public:
  explicit JsonText(std::ostream& out);
  JsonText(const JsonText&) = delete;
  JsonText& operator=(const JsonText&) = delete;

  void begin_object();
  void end_object();
  void begin_array();
  void end_array();
  /// The next value is the member `name` of the innermost object.
  JsonText& key(std::string_view name);

  void string(std::string_view value);
  void boolean(bool value);
  void number(std::size_t value);
  void number(long value);
  void number(int value) { number(static_cast<long>(value)); }
  void number(double value);
  void null();
  /// An array of unsigned integers.
  void numbers(const std::vector<std::size_t>& values);

  /// Writes the buffered text to the stream (call once, after the outermost value).
  void finish();

 private:
  struct Level {
    bool object = false;
    bool empty = true;
    std::string last_key;
  };
  Level& top() { return levels_[depth_ - 1]; }
  void before_value();
  void quoted(std::string_view value);
  void open(bool object, char bracket);
  void close(char bracket);
  void spill();

  std::ostream& out_;
  std::string text_;
  std::vector<Level> levels_;   // [0, depth_) open; the rest kept for their keys' capacity
  std::size_t depth_ = 0;
  bool after_key_ = false;
};

/// The JSON names of an edge's role ("contact", "spurious", "seam", "limit", "touching") and of a
/// cell's kind ("free", "blocked", "touching").
const char* role_name(EdgeRole role);
const char* cell_kind_name(CellKind kind);

/// A polynomial sum_ij c[i][j] x^i y^j as text, highest terms first: "3*x^2*y - y + 7"; "0".
void append_polynomial_text(std::string& text, const std::vector<std::vector<mpz_class>>& coefficients);

/// The texts of an irrational vertex coordinate as write_space_json writes them (the decimal, the
/// exact text, the interval's ends), remembered for one document: a 2-D space's vertices repeat
/// their numbers (a seam vertex in both charts, a mapped twin chart's vertices in its twin's
/// columns: Geneva's 424 irrational coordinates are 118 numbers), and each costs a refinement
/// to the nearest double and a polynomial's text. An entry is keyed by everything its texts are
/// functions of (the number's polynomial, interval and exactness, the variable's name, the axis
/// unit), compared exactly (the hash picks a bucket only), so a remembered text is the one the
/// number would be given anew: the same bytes.
class ExactNumberMemo {
 public:
  struct Text {
    double decimal = 0;   // the number's approximate()
    std::string exact, lower, upper;
  };
  /// The texts remembered for `given` (with `hash` = hash(given, unit)); null when none.
  const Text* find(const AlgebraicNumber& given, const char* variable, long unit, std::size_t hash) const;
  /// Remembers `text` as given's (not found before) and returns it.
  const Text& add(const AlgebraicNumber& given, const char* variable, long unit, std::size_t hash, Text text);
  /// A bucket: of the coefficients' and ends' sizes and lowest limbs, and the unit.
  static std::size_t hash(const AlgebraicNumber& n, long unit);

 private:
  struct Entry {
    AlgebraicNumber number;
    std::string variable;
    long unit;
    Text text;
  };
  std::unordered_map<std::size_t, std::vector<Entry>> entries_;
};

/// An edge's polynomial text (append_polynomial_text, in mm when an axis has a unit exponent),
/// remembered for one document: the edges of one curve, and a mapped twin chart's, have the
/// same support. Keyed by the coefficients and the axes' units, compared exactly: the same bytes
/// as making each text anew.
class PolynomialTextMemo {
 public:
  using Coefficients = std::vector<std::vector<mpz_class>>;
  const std::string& text(const Coefficients& c, long x_unit, long y_unit);
  static std::size_t hash(const Coefficients& c, long x_unit, long y_unit);

 private:
  struct Entry {
    Coefficients coefficients;
    long x_unit, y_unit;
    std::string text;
  };
  std::unordered_map<std::size_t, std::vector<Entry>> entries_;
};

/// Writes the JSON document of a 1-D or 2-D C-space (what `hipair cspace --json` writes: pair,
/// charts, feature pairs, cells, vertices, edges with their exact polynomials, statistics;
/// the stages' seconds only when `with_seconds`) and a final newline.
void write_space_json(std::ostream& out, const CSpace& space, bool with_seconds);

}  // namespace hipair::cli
