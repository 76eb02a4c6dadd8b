// A number expression of a model file kept as a formula of the named parameters, so that it
// can be evaluated for any number type (double, certified intervals, AutoDiff scalars) at any
// parameter vector without re-reading the file (docs/model-format.md "Numbers";
// docs/tolerance.md "The parametric model"). The grammar is the one of expression.cpp; the
// exact evaluation (rational + rational * pi, with certified enclosures) stays there.
#pragma once

#include "model/parametric/arithmetic.hpp"

#include <hipair/rational.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hipair::model_detail {

/// A node of a formula.
struct Formula {
  enum class Op { constant, pi, parameter, add, subtract, multiply, divide, negate, power,
                  sqrt, sin, cos, tan, atan2, min, max, abs };
  Op op = Op::constant;
  Rational value;              ///< constant
  std::size_t parameter = 0;   ///< parameter: index into Model::parameters
  long exponent = 0;           ///< power: integer exponent
  std::vector<std::shared_ptr<const Formula>> arguments;
};
using FormulaPtr = std::shared_ptr<const Formula>;

FormulaPtr formula_constant(const Rational& value);
FormulaPtr formula_node(Formula::Op op, std::vector<FormulaPtr> arguments);

/// The file's angle unit and which parameters are angles (docs/model-format.md "Angles").
struct FormulaUnits {
  bool degrees = false;
  std::function<bool(std::size_t)> parameter_is_angle;
};

/// Parses an expression text (the grammar of docs/model-format.md) into a formula; `deg`
/// becomes a factor pi/180, and with `units` in a degree file so does a plain value used as an
/// angle inside the expression (a trigonometric function's argument, a term added to an angle,
/// min/max next to an angle), as the exact evaluator reads it. `parameter_index` maps a
/// parameter name to its index (throws for unknown names). \throws ModelError(pointer, ...)
/// for syntax errors.
FormulaPtr parse_formula(std::string_view text, const std::string& pointer,
                         const std::function<std::size_t(const std::string&)>& parameter_index,
                         const FormulaUnits* units = nullptr);

/// Whether the formula refers to any parameter.
bool mentions_parameters(const FormulaPtr& formula);

/// The formula times `factor` (a positive rational), with the factor carried into its constants
/// where the formula's form allows it, so that a length written at an extreme scale evaluates
/// in doubles in the unit its model is analysed in (the tolerance analysis of a model divided by
/// 10^E, ParametricModel::rescaled): a constant c becomes c * factor (exactly); a sum, a
/// difference, min, max, abs and a negation carry it into each operand; a product into its
/// factor free of parameters (of two such, the one whose scaled magnitude is nearest 1; else its
/// first), leaving out a factor that became exactly 1; a quotient into its numerator, sqrt(x) as
/// sqrt(x * factor^2). Elsewhere (a parameter, pi, a trigonometric value, a power) the node is
/// multiplied by the constant `factor`: `parameter_scaled` is set then when the node mentions a
/// parameter (its double value times the factor may leave the doubles' range). Exact: the
/// result's value is the formula's times `factor` for every number type up to its rounding.
FormulaPtr formula_scaled(const FormulaPtr& formula, const Rational& factor, bool& parameter_scaled);

/// Evaluates a formula for number type T (see number_traits.hpp); `parameter(i)` gives the
/// value of parameter i.
template <class T, class ParameterValue>
T evaluate_formula(const Formula& f, ParameterValue&& parameter) {
  using A = Arithmetic<T>;
  auto arg = [&](std::size_t i) { return evaluate_formula<T>(*f.arguments[i], parameter); };
  switch (f.op) {
    case Formula::Op::constant: return A::constant(f.value);
    case Formula::Op::pi: return A::pi();
    case Formula::Op::parameter: return parameter(f.parameter);
    case Formula::Op::add: return T(arg(0) + arg(1));
    case Formula::Op::subtract: return T(arg(0) - arg(1));
    case Formula::Op::multiply: return T(arg(0) * arg(1));
    case Formula::Op::divide: return T(arg(0) / arg(1));
    case Formula::Op::negate: return T(-arg(0));
    case Formula::Op::power: {
      T base = arg(0);
      long n = f.exponent < 0 ? -f.exponent : f.exponent;
      T result = A::constant(Rational(1));
      for (long k = 0; k < n; ++k) result = T(result * base);
      return f.exponent < 0 ? T(A::constant(Rational(1)) / result) : result;
    }
    case Formula::Op::sqrt: return A::sqrt(arg(0));
    case Formula::Op::sin: return A::sin(arg(0));
    case Formula::Op::cos: return A::cos(arg(0));
    case Formula::Op::tan: return A::tan(arg(0));
    case Formula::Op::atan2: return A::atan2(arg(0), arg(1));
    case Formula::Op::abs: return A::abs(arg(0));
    case Formula::Op::min:
    case Formula::Op::max: {
      T best = arg(0);
      for (std::size_t i = 1; i < f.arguments.size(); ++i)
        best = f.op == Formula::Op::min ? A::min(best, arg(i)) : A::max(best, arg(i));
      return best;
    }
  }
  return A::constant(Rational(0));
}

}  // namespace hipair::model_detail
