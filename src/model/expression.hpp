// Exact evaluation of the number expressions of a model file (docs/model-format.md, "Numbers").
//
// A value is kept exact as long as possible, in the form  rational + rational * pi  (so
// "360 deg / slots" stays an exact multiple of pi); anything else (sqrt(2), sin(1), pi^2) is
// carried as a certified 256-bit MPFI enclosure and rounded to the nearest multiple of 10^-12
// only when a number must be produced; the rounding is then recorded.
#pragma once

#include "model/interval.hpp"

#include <hipair/error.hpp>
#include <hipair/geometry.hpp>
#include <hipair/model.hpp>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair::model_detail {

/// The value of an expression.
struct Quantity {
  bool exact = true;
  Rational rational;                 ///< exact: value = rational + pi_multiple * pi
  Rational pi_multiple;
  std::optional<Interval> enclosure; ///< !exact: certified enclosure of the value
  /// Carries an angle unit (a `deg`/`rad` postfix, atan2, an angle parameter): the value is in
  /// radians. A plain number used as an angle is in the file's angle unit.
  bool is_angle = false;
  /// A plain value computed with pi: ambiguous as an angle in a degree file (is "pi/4" meant in
  /// radians?), so using it as one there is an error.
  bool mentions_pi = false;

  static Quantity of(const Rational& value, bool is_angle = false);
  static Quantity of_pi(const Rational& multiple, bool is_angle = true);
  static Quantity approximate(Interval enclosure, bool is_angle = false);

  bool is_rational() const { return exact && pi_multiple == 0; }
  bool is_pi_multiple() const { return exact && rational == 0; }
  /// A certified enclosure of the value (exact values are enclosed too).
  Interval to_interval() const;
};

/// What an expression may refer to.
struct ExpressionContext {
  bool degrees = false;  ///< the file's angle unit is deg
  std::string pointer;   ///< JSON pointer reported in errors
  /// Value of a parameter; throws ModelError for unknown names or reference cycles.
  std::function<Quantity(const std::string& name)> parameter;
};

/// Largest size (bits of numerator or denominator) of an exact value.
inline constexpr unsigned long max_rational_bits = 4096;

/// Evaluates `text` (grammar in docs/model-format.md). \throws ModelError(context.pointer, ...)
/// for syntax errors, unknown parameters, division by zero, sqrt of a negative number, ...
Quantity evaluate_expression(std::string_view text, const ExpressionContext& context);

/// The value used as an angle in radians: a plain number is converted from the file's unit.
/// \throws ModelError(pointer, ...) for a plain value computed with pi in a degree file.
Quantity as_angle(const Quantity& value, bool degrees, const std::string& pointer,
                  std::string_view expression);

/// A value the current precision (working_interval_bits()) could neither decide (a sign, a
/// divisor, a square root's argument too close to zero) nor round within its bound: read_model
/// reads the model again at doubled precision, up to most_interval_bits, and reports this
/// error only there.
class PrecisionExhausted : public ModelError {
 public:
  using ModelError::ModelError;
};

/// The bound within which a value of magnitude `magnitude` (> 0; 0 when unknown or zero) is
/// rounded: the thread's rounding bound b (rounding_bound()), and for a value smaller than
/// 2^-20 (about 10^-6, in the value's unit) the smaller of b and 2^-44 times the value, so that
/// a part drawn at 10^-300 mm keeps its shape instead of rounding to 0 (docs/model-format.md
/// "Exactness and rounding"). Used by round_simplest (model/exact_trig.hpp); to_rational rounds
/// values outside [2^-20, 2^40] at their decimal scale instead.
Rational rounding_bound_near(const Rational& magnitude);

/// A token of an expression: a number literal ("2.5e-3"), a name ("pi", "lever-length": a '-'
/// between name characters binds to the name), one of the symbols + - * / ^ ( ) , or the end.
struct ExpressionToken {
  enum class Kind { number, name, symbol, end };
  Kind kind = Kind::end;
  std::string text;
  std::size_t position = 0;   ///< of its first character in the expression
};

/// Splits `text` into `tokens` (white space skipped, the last token the end, "end of
/// expression", at text.size()): the one tokenizer of the exact evaluator and the parametric
/// form's formula parser (model/parametric/formula.cpp). Returns the position of the first
/// character that starts no token (the tokens before it kept), nullopt when every one does.
std::optional<std::size_t> expression_tokens(std::string_view text, std::vector<ExpressionToken>& tokens);

/// Largest decimal exponent accepted in a literal ("1e1000").
inline constexpr long max_literal_exponent = 1000;

/// The exact value of a number literal ("46.683", "-2.5e-3", "1/3").
/// \throws ModelError(pointer, ...) when it is not a literal, its exponent exceeds
///         max_literal_exponent or its value exceeds max_rational_bits.
Rational parse_literal(std::string_view text, const std::string& pointer);

/// \throws ModelError(pointer, ...) when `value` has more than max_rational_bits bits.
void check_rational_size(const Rational& value, const std::string& pointer);

/// Sign of `value`, decided exactly or on its certified enclosure.
/// \throws ModelError(pointer, ...) when the enclosure contains 0 and the value is not exact.
int sign_of(const Quantity& value, const std::string& pointer, std::string_view expression);

/// The rational value: exact when the value is rational, else the simplest rational within the
/// rounding bound b of it (a Rounding {pointer, expression, value, b} is appended); a value
/// certainly not 0 and outside [2^-20, 2^40] is rounded as at its decimal scale instead: U times
/// the simplest rational within b of value / U, U = 10^E with E a multiple of 10 bringing it
/// within [1e-4, 1e6) (core/model_scale.hpp decimal_unit_exponent; the Rounding's bound b U), so
/// a value written 10^(10 j) times an ordinary one is exactly 10^(10 j) times that one's rational.
/// \throws PrecisionExhausted(pointer, ...) when the enclosure is too wide to round within the bound.
Rational to_rational(const Quantity& value, const std::string& pointer,
                     const std::string& expression, std::vector<Rounding>& roundings);

/// Exact rational unit vector (cos a, sin a) for an angle value (radians; use as_angle first):
/// exact for 0 and multiples of pi/2, else through the rounded half-angle tangent (recorded).
Point unit_vector(const Quantity& angle, const std::string& pointer, const std::string& expression,
                  std::vector<Rounding>& roundings);

/// Exact rational unit vector along [dx, dy] (a direction written as a vector, `dx_text` and
/// `dy_text` as written): d / |d| when |d|^2 is the square of a rational, else through the
/// half-angle tangent t = dy / (|d| + dx) (of -d when dx < 0, which keeps |t| <= 1) rounded
/// within the rounding bound and recorded under `pointer` ("direction [dx, dy] (half-angle
/// tangent)"): the stored vector is exactly unit. The reader's and the parametric model's one
/// construction of a direction vector. \throws ModelError(pointer, ...) for a zero vector.
Point unit_direction(const Rational& dx, const Rational& dy, const std::string& pointer, const std::string& dx_text,
                     const std::string& dy_text, std::vector<Rounding>& roundings);

}  // namespace hipair::model_detail
