// Parser of model expressions into formulas of the parameters (formula.hpp). The grammar and
// its precedence are the exact evaluator's (expression.cpp); every text reaching this parser
// has already been evaluated exactly by the reader, so errors here are rare (the messages
// still name the JSON pointer).
#include "model/parametric/formula.hpp"

#include "model/expression.hpp"

#include <hipair/error.hpp>

#include <cctype>
#include <cmath>
#include <limits>

namespace hipair::model_detail {

FormulaPtr formula_constant(const Rational& value) {
  auto f = std::make_shared<Formula>();
  f->op = Formula::Op::constant;
  f->value = value;
  return f;
}

FormulaPtr formula_node(Formula::Op op, std::vector<FormulaPtr> arguments) {
  auto f = std::make_shared<Formula>();
  f->op = op;
  f->arguments = std::move(arguments);
  return f;
}

bool mentions_parameters(const FormulaPtr& formula) {
  if (formula->op == Formula::Op::parameter) return true;
  for (const FormulaPtr& argument : formula->arguments)
    if (mentions_parameters(argument)) return true;
  return false;
}

FormulaPtr formula_scaled(const FormulaPtr& formula, const Rational& factor, bool& parameter_scaled) {
  using Op = Formula::Op;
  const Formula& f = *formula;
  auto all = [&] {
    std::vector<FormulaPtr> arguments;
    for (const FormulaPtr& argument : f.arguments) arguments.push_back(formula_scaled(argument, factor, parameter_scaled));
    return formula_node(f.op, std::move(arguments));
  };
  switch (f.op) {
    case Op::constant: return formula_constant(Rational(f.value * factor));
    case Op::add:
    case Op::subtract:
    case Op::negate:
    case Op::abs:
    case Op::min:
    case Op::max: return all();
    case Op::multiply: {
      // into the factor free of parameters ("(p)*(1e400)": p * 1 at the scale 1e-400); of two
      // such factors the one whose value times the scale is nearest 1 in magnitude, the second
      // on a tie ("(20)*(1e-300)": 20 * 1; "(0)*(1e400)": 0 * 1; "(1e400)*(2)": 1 * 2)
      const bool a = mentions_parameters(f.arguments[0]), b = mentions_parameters(f.arguments[1]);
      std::size_t k = a && !b ? 1 : 0;
      if (!a && !b) {
        auto log2_abs = [](const Rational& q) {   // log2 |q|, -inf for 0 (beyond the doubles too)
          if (sgn(q) == 0) return -std::numeric_limits<double>::infinity();
          long en = 0, ed = 0;
          const double n = mpz_get_d_2exp(&en, q.get_num_mpz_t()), d = mpz_get_d_2exp(&ed, q.get_den_mpz_t());
          return std::log2(std::fabs(n)) + double(en) - std::log2(d) - double(ed);
        };
        auto none = [](std::size_t) { return 0.0; };
        auto distance = [&](const FormulaPtr& side) {
          const double log2 = side->op == Op::constant ? log2_abs(side->value)
                                                       : std::log2(std::fabs(evaluate_formula<double>(*side, none)));
          const double d = std::fabs(log2 + log2_abs(factor));
          return std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
        };
        k = distance(f.arguments[1]) <= distance(f.arguments[0]) ? 1 : 0;
      }
      std::vector<FormulaPtr> arguments = f.arguments;
      arguments[k] = formula_scaled(arguments[k], factor, parameter_scaled);
      // a factor that became exactly 1 is left out: x, not x * 1, for number types whose
      // products round outwards (intervals, jets, Taylor models): the unscaled form's values
      if (arguments[k]->op == Op::constant && arguments[k]->value == 1) return arguments[1 - k];
      return formula_node(Op::multiply, std::move(arguments));
    }
    case Op::divide:
      return formula_node(Op::divide, {formula_scaled(f.arguments[0], factor, parameter_scaled), f.arguments[1]});
    case Op::sqrt:
      return formula_node(Op::sqrt, {formula_scaled(f.arguments[0], Rational(factor * factor), parameter_scaled)});
    case Op::power:
      if (f.exponent == 1) {
        auto node = std::make_shared<Formula>(f);
        node->arguments = {formula_scaled(f.arguments[0], factor, parameter_scaled)};
        return node;
      }
      break;
    default: break;
  }
  parameter_scaled = parameter_scaled || mentions_parameters(formula);
  return formula_node(Op::multiply, {formula, formula_constant(factor)});
}

namespace {

using Token = ExpressionToken;

// A formula and whether its value carries an angle unit (the exact evaluator's Quantity::is_angle,
// by the same rules: expression.cpp).
struct Typed {
  FormulaPtr f;
  bool angle = false;
};

class Parser {
 public:
  Parser(std::string_view text, const std::string& pointer,
         const std::function<std::size_t(const std::string&)>& parameter_index, const FormulaUnits* units)
      : text_(text), pointer_(pointer), parameter_index_(parameter_index), units_(units) {
    tokenize();
  }

  FormulaPtr run() {
    FormulaPtr f = expression().f;
    if (current().kind != Token::Kind::end) fail("unexpected '" + current().text + "'");
    return f;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    throw ModelError(pointer_, reason + " in expression '" + std::string(text_) + "' (parametric form)");
  }

  void tokenize() {
    if (expression_tokens(text_, tokens_)) fail("unexpected character");
  }

  const Token& current() const { return tokens_[next_]; }
  bool at_symbol(char symbol) const {
    return current().kind == Token::Kind::symbol && current().text[0] == symbol;
  }
  void expect_symbol(char symbol) {
    if (!at_symbol(symbol)) fail(std::string("expected '") + symbol + "'");
    ++next_;
  }

  static FormulaPtr degrees_to_radians(const FormulaPtr& value) {
    return formula_node(Formula::Op::multiply,
                        {value, formula_node(Formula::Op::divide, {formula_node(Formula::Op::pi, {}), formula_constant(180)})});
  }
  // as_angle: a plain value used as an angle is in the file's angle unit (since session 51, as
  // the exact evaluator does inside an expression too: `5 + atan2(p, -1)`, `sin(p)` or a plain
  // term next to an angle in a degree file; until then only a whole slot was converted, so the
  // tolerance analysis certified bands of another model than the one read)
  Typed as_angle(Typed value) const {
    if (!value.angle && units_ && units_->degrees) value.f = degrees_to_radians(value.f);
    value.angle = true;
    return value;
  }
  // unify: both operands angles when one is
  void unify(Typed& a, Typed& b) const {
    if (a.angle && !b.angle) b = as_angle(b);
    if (b.angle && !a.angle) a = as_angle(a);
  }

  Typed expression() {
    Typed value = term();
    while (at_symbol('+') || at_symbol('-')) {
      bool subtract = at_symbol('-');
      ++next_;
      Typed right = term();
      unify(value, right);
      value.f = formula_node(subtract ? Formula::Op::subtract : Formula::Op::add, {value.f, right.f});
    }
    return value;
  }

  Typed term() {
    Typed value = unary();
    while (true) {
      if (at_symbol('*') || at_symbol('/')) {
        bool divide = at_symbol('/');
        ++next_;
        Typed right = unary();
        value.f = formula_node(divide ? Formula::Op::divide : Formula::Op::multiply, {value.f, right.f});
        value.angle = divide ? value.angle && !right.angle : value.angle != right.angle;
      } else if (current().kind == Token::Kind::name && (current().text == "deg" || current().text == "rad")) {
        if (current().text == "deg") value.f = degrees_to_radians(value.f);
        value.angle = true;
        ++next_;
      } else {
        return value;
      }
    }
  }

  Typed unary() {
    if (at_symbol('-')) {
      ++next_;
      Typed value = unary();
      value.f = formula_node(Formula::Op::negate, {value.f});
      return value;
    }
    if (at_symbol('+')) {
      ++next_;
      return unary();
    }
    return power();
  }

  Typed power() {
    Typed base = primary();
    if (!at_symbol('^')) return base;
    ++next_;
    std::size_t first = next_;
    FormulaPtr exponent = unary().f;
    auto f = std::make_shared<Formula>();
    f->op = Formula::Op::power;
    f->exponent = integer_value(exponent, first, next_);
    f->arguments = {base.f};
    return Typed{f, base.angle && f->exponent == 1};   // the exact evaluator's x^1 is x
  }

  // The exponent's exact value: its tokens evaluated again by the exact evaluator
  // (expression.cpp: rationals and multiples of pi, certified enclosures otherwise), which
  // already accepted it as an integer when the model was read. No double on the way.
  long integer_value(const FormulaPtr& f, std::size_t first, std::size_t last) {
    if (mentions_parameters(f)) fail("an exponent must not depend on parameters");
    std::string text;
    for (std::size_t i = first; i < last; ++i) text += (i > first ? " " : "") + tokens_[i].text;
    ExpressionContext context;
    context.pointer = pointer_;
    context.parameter = [&](const std::string& name) -> Quantity {
      fail("an exponent must not depend on parameters ('" + name + "')");
    };
    Quantity value = evaluate_expression(text, context);
    if (!value.is_rational() || value.rational.get_den() != 1 || !value.rational.get_num().fits_slong_p())
      fail("the exponent '" + text + "' is not an integer");
    return value.rational.get_num().get_si();
  }

  Typed primary() {
    Token token = current();
    switch (token.kind) {
      case Token::Kind::number:
        ++next_;
        return Typed{formula_constant(parse_literal(token.text, pointer_))};
      case Token::Kind::name: {
        ++next_;
        if (at_symbol('(')) return call(token.text);
        if (token.text == "pi") return Typed{formula_node(Formula::Op::pi, {})};
        auto f = std::make_shared<Formula>();
        f->op = Formula::Op::parameter;
        f->parameter = parameter_index_(token.text);
        return Typed{f, units_ && units_->parameter_is_angle && units_->parameter_is_angle(f->parameter)};
      }
      case Token::Kind::symbol:
        if (token.text == "(") {
          ++next_;
          Typed value = expression();
          expect_symbol(')');
          return value;
        }
        fail("unexpected '" + token.text + "'");
      case Token::Kind::end:
        fail("unexpected end of expression");
    }
    fail("unexpected token");
  }

  Typed call(const std::string& name) {
    ++next_;  // '('
    std::vector<Typed> typed;
    if (!at_symbol(')')) {
      typed.push_back(expression());
      while (at_symbol(',')) {
        ++next_;
        typed.push_back(expression());
      }
    }
    expect_symbol(')');
    using Op = Formula::Op;
    bool trigonometric = name == "sin" || name == "cos" || name == "tan";
    if (trigonometric && typed.size() == 1) typed[0] = as_angle(typed[0]);
    bool any_angle = false;   // min/max: every argument an angle when one is
    for (const Typed& t : typed) any_angle = any_angle || t.angle;
    if ((name == "min" || name == "max") && any_angle)
      for (Typed& t : typed) t = as_angle(t);
    std::vector<FormulaPtr> arguments;
    for (const Typed& t : typed) arguments.push_back(t.f);
    if (name == "sqrt" && arguments.size() == 1) return Typed{formula_node(Op::sqrt, arguments)};
    if (name == "sin" && arguments.size() == 1) return Typed{formula_node(Op::sin, arguments)};
    if (name == "cos" && arguments.size() == 1) return Typed{formula_node(Op::cos, arguments)};
    if (name == "tan" && arguments.size() == 1) return Typed{formula_node(Op::tan, arguments)};
    if (name == "atan2" && arguments.size() == 2) return Typed{formula_node(Op::atan2, arguments), true};
    if (name == "abs" && arguments.size() == 1) return Typed{formula_node(Op::abs, arguments), typed[0].angle};
    if (name == "min" && arguments.size() >= 2) return Typed{formula_node(Op::min, arguments), any_angle};
    if (name == "max" && arguments.size() >= 2) return Typed{formula_node(Op::max, arguments), any_angle};
    fail("unknown function '" + name + "'");
  }

  std::string_view text_;
  const std::string& pointer_;
  const std::function<std::size_t(const std::string&)>& parameter_index_;
  const FormulaUnits* units_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

}  // namespace

FormulaPtr parse_formula(std::string_view text, const std::string& pointer,
                         const std::function<std::size_t(const std::string&)>& parameter_index, const FormulaUnits* units) {
  return Parser(text, pointer, parameter_index, units).run();
}

}  // namespace hipair::model_detail
