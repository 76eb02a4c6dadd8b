// The model reader's internal state and steps (docs/model-format.md). One Reader reads one
// document: reader.cpp (top level, units, pairs, public entry points), reader_values.cpp
// (JSON structure, numbers, points, directions), reader_parameters.cpp, reader_parts.cpp
// (parts, loops, features, motions, dynamics). Internal: not part of the public API.
#pragma once

#include "model/expression.hpp"
#include "model/json_document.hpp"
#include "model/templates.hpp"
#include "core/decimal_text.hpp"

#include <hipair/model.hpp>

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hipair::model_detail {

/// "a, b, c".
inline std::string join(std::initializer_list<std::string_view> words) {
  std::string out;
  for (std::string_view word : words) {
    if (!out.empty()) out += ", ";
    out += word;
  }
  return out;
}

/// A value for messages, 12 significant digits.
inline std::string decimal(const Rational& value) { return to_decimal_string(value, 12); }
/// Two values for one message, with enough digits to show that they differ.
inline std::pair<std::string, std::string> apart(const Rational& a, const Rational& b) {
  return to_decimal_strings_apart(a, b, 12);
}
/// The texts of v and of "[lo, hi]" for a message that v lies outside, with enough digits to
/// show on which side.
inline std::pair<std::string, std::string> outside(const Rational& v, const Rational& lo, const Rational& hi) {
  const Rational& near = v < lo ? lo : hi;
  auto [value, end] = to_decimal_strings_apart(v, near, 12);
  return {value, "[" + (v < lo ? end : decimal(lo)) + ", " + (v < lo ? decimal(hi) : end) + "]"};
}

inline Rational squared_distance(const Point& a, const Point& b) {
  Rational dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

/// Whether this thread is reading a model for a simulation (read_model_for_simulation): the
/// Reader then refuses dynamics data beyond the doubles' range (docs/model-format.md).
bool reading_for_simulation();

/// read_model, and the precision (bits) at which it read: the default 256, or the doubled one
/// that every value of this model needed (PrecisionExhausted).
Model read_model_escalating(std::string_view json_text, std::string_view source_name, const ReadOptions& options,
                            mpfr_prec_t* bits_used);

/// Reads one model document into an exact, validated Model; every error is a ModelError
/// naming the JSON pointer of the offending value.
class Reader {
 public:
  Reader(std::string_view text, std::string_view source, const ReadOptions& options)
      : text_(text), options_(options) {
    model_.source = std::string(source);
  }

  /// Parses, evaluates and validates the whole document (profile tolerances translated into
  /// parameters first, and checked at their band's extremes: profile_tolerance.hpp).
  Model read();
  /// Evaluates and validates a parsed document (without profile tolerances).
  Model read_root(const JsonValue& root);
  /// The rounding bound: the optional top-level "rounding" key, or a command line's override
  /// (rounding_bound_overrides_model()), else the default.
  Rational read_rounding(const JsonValue* value);

 private:
  struct ParameterState {
    const JsonValue* definition = nullptr;
    std::size_t index = 0;  ///< position in the file
    enum class Status { pending, evaluating, done } status = Status::pending;
    Quantity value;         ///< exact or enclosed value used by expressions (override applied)
  };

  std::string text_of(const JsonValue& value) { return value.text; }

  // JSON structure
  const JsonValue& require(const JsonValue& object, std::string_view key);
  void check_keys(const JsonValue& object, std::initializer_list<std::string_view> allowed);
  void expect(const JsonValue& value, JsonValue::Type type, const std::string& what);
  const JsonValue& expect_object(const JsonValue& value, const std::string& what = "an object");
  const JsonValue& expect_array(const JsonValue& value, const std::string& what = "an array");
  /// A string value; control characters are refused (`layout`: tab and line breaks allowed).
  std::string read_string(const JsonValue& value, bool allow_empty, bool layout = false);
  /// A name (the model's, a part's, a part's in a pair, driver or spring): a non-empty string
  /// without control characters, white space only as single spaces between other characters
  /// (docs/model-format.md#names-and-text). Any length: messages cut it (hunt38).
  std::string read_name(const JsonValue& value);
  static constexpr const char* name_rule =
      "a name's only white space is a single space (U+0020) between two other characters";
  bool read_boolean(const JsonValue& value);

  // numbers, points, directions (reader_values.cpp)
  ExpressionContext context_at(const std::string& pointer);
  /// The value of a number slot: a JSON number (exact from its text) or an expression string.
  Quantity evaluate(const JsonValue& value);
  Rational number(const JsonValue& value);
  Rational angle(const JsonValue& value);
  /// Dynamics data (a part's "dynamics", the "simulation" object, a pair's friction and
  /// restitution) is held by the simulator in doubles: while a SimulatorValues guard lives,
  /// number() and angle() refuse a value whose magnitude is beyond the doubles' normal range
  /// (|v| > DBL_MAX, or 0 < |v| < DBL_MIN), at its pointer (session 43: 1e400 became infinity
  /// and GMP's mpq_set_d(inf) killed the process with SIGFPE).
  void check_simulator_range(const Rational& value, const JsonValue& where);
  struct SimulatorValues {
    explicit SimulatorValues(Reader& reader) : reader_(reader), before_(reader.simulator_values_) {
      reader_.simulator_values_ = true;
    }
    ~SimulatorValues() { reader_.simulator_values_ = before_; }
    SimulatorValues(const SimulatorValues&) = delete;
    SimulatorValues& operator=(const SimulatorValues&) = delete;
    Reader& reader_;
    bool before_;
  };
  Rational non_negative(const JsonValue& value, const std::string& what);
  Rational positive(const JsonValue& value, const std::string& what);
  Point point(const JsonValue& value);
  RationalInterval limits(const JsonValue& value, bool angles);
  /// An exact rational unit vector from [dx, dy] or from an angle.
  Point direction(const JsonValue& value);

  // top level (reader.cpp)
  void read_version(const JsonValue& value);
  void read_units(const JsonValue* units);
  void read_pairs(const JsonValue* pairs);

  // simulation data (reader_dynamics.cpp)
  void read_simulation(const JsonValue* simulation);
  std::size_t moving_part(const JsonValue& name);

  // parameters (reader_parameters.cpp)
  void read_parameters(const JsonValue* parameters);
  Quantity parameter_value(const std::string& name, const std::string& used_at);
  Parameter read_parameter(const std::string& name, const JsonValue& definition, Quantity& value);

  // parts (reader_parts.cpp)
  void read_parts(const JsonValue& parts);
  Part read_part(const JsonValue& value);
  Loop read_loop(const JsonValue& value);
  Edge read_circle(const JsonValue& value, const std::string& label);
  Edge read_edge(const JsonValue& value, const Point& from);
  void read_features(const JsonValue& features, Part& part);
  TemplateValue template_argument(const JsonValue& value, ArgumentKind kind);
  Motion read_motion(const JsonValue& value);
  PartConfiguration read_initial(const JsonValue& value, const Motion& motion);
  Dynamics read_dynamics(const JsonValue& value);
  Spring read_spring(const JsonValue& value, bool torsional);

  std::string_view text_;
  const ReadOptions& options_;
  Model model_;
  bool simulator_values_ = false;                     ///< number()/angle() check the doubles' range
  bool degrees_ = false;                              ///< the file's angle unit is deg
  std::map<std::string, ParameterState> parameters_;
  std::vector<Parameter> resolved_;                   ///< in file order
  std::vector<std::string> evaluation_stack_;         ///< parameters being evaluated (cycles)
};

}  // namespace hipair::model_detail
