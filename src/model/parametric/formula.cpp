// Parser of model expressions into formulas of the parameters (formula.hpp). The grammar and
// its precedence are the exact evaluator's (expression.cpp); every text reaching this parser
// has already been evaluated exactly by the reader, so errors here are rare (the messages
// still name the JSON pointer).
#include "model/parametric/formula.hpp"

#include "model/expression.hpp"

#include <hipair/error.hpp>

#include <cctype>
#include <cmath>

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

namespace {

struct Token {
  enum class Kind { number, name, symbol, end } kind = Kind::end;
  std::string text;
};

class Parser {
 public:
  Parser(std::string_view text, const std::string& pointer,
         const std::function<std::size_t(const std::string&)>& parameter_index)
      : text_(text), pointer_(pointer), parameter_index_(parameter_index) {
    tokenize();
  }

  FormulaPtr run() {
    FormulaPtr f = expression();
    if (current().kind != Token::Kind::end) fail("unexpected '" + current().text + "'");
    return f;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    throw ModelError(pointer_, reason + " in expression '" + std::string(text_) + "' (parametric form)");
  }

  void tokenize() {
    std::size_t i = 0;
    auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
    auto name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
    while (i < text_.size()) {
      char c = text_[i];
      if (std::isspace(static_cast<unsigned char>(c))) {
        ++i;
        continue;
      }
      Token token;
      if (digit(c) || (c == '.' && i + 1 < text_.size() && digit(text_[i + 1]))) {
        std::size_t j = i;
        while (j < text_.size() && digit(text_[j])) ++j;
        if (j < text_.size() && text_[j] == '.') {
          ++j;
          while (j < text_.size() && digit(text_[j])) ++j;
        }
        if (j < text_.size() && (text_[j] == 'e' || text_[j] == 'E')) {
          std::size_t k = j + 1;
          if (k < text_.size() && (text_[k] == '+' || text_[k] == '-')) ++k;
          if (k < text_.size() && digit(text_[k])) {
            while (k < text_.size() && digit(text_[k])) ++k;
            j = k;
          }
        }
        token.kind = Token::Kind::number;
        token.text = std::string(text_.substr(i, j - i));
        i = j;
      } else if (std::isalpha(static_cast<unsigned char>(c))) {
        std::size_t j = i + 1;
        while (j < text_.size()) {
          if (name_char(text_[j])) {
            ++j;
          } else if (text_[j] == '-' && j + 1 < text_.size() && name_char(text_[j + 1])) {
            j += 2;
          } else {
            break;
          }
        }
        token.kind = Token::Kind::name;
        token.text = std::string(text_.substr(i, j - i));
        i = j;
      } else if (std::string_view("+-*/^(),").find(c) != std::string_view::npos) {
        token.kind = Token::Kind::symbol;
        token.text = std::string(1, c);
        ++i;
      } else {
        fail("unexpected character");
      }
      tokens_.push_back(std::move(token));
    }
    tokens_.push_back(Token{Token::Kind::end, "end of expression"});
  }

  const Token& current() const { return tokens_[next_]; }
  bool at_symbol(char symbol) const {
    return current().kind == Token::Kind::symbol && current().text[0] == symbol;
  }
  void expect_symbol(char symbol) {
    if (!at_symbol(symbol)) fail(std::string("expected '") + symbol + "'");
    ++next_;
  }

  FormulaPtr expression() {
    FormulaPtr value = term();
    while (at_symbol('+') || at_symbol('-')) {
      bool subtract = at_symbol('-');
      ++next_;
      value = formula_node(subtract ? Formula::Op::subtract : Formula::Op::add, {value, term()});
    }
    return value;
  }

  FormulaPtr term() {
    FormulaPtr value = unary();
    while (true) {
      if (at_symbol('*') || at_symbol('/')) {
        bool divide = at_symbol('/');
        ++next_;
        value = formula_node(divide ? Formula::Op::divide : Formula::Op::multiply, {value, unary()});
      } else if (current().kind == Token::Kind::name && (current().text == "deg" || current().text == "rad")) {
        if (current().text == "deg")
          value = formula_node(Formula::Op::multiply,
                               {value, formula_node(Formula::Op::divide,
                                                    {formula_node(Formula::Op::pi, {}), formula_constant(180)})});
        ++next_;
      } else {
        return value;
      }
    }
  }

  FormulaPtr unary() {
    if (at_symbol('-')) {
      ++next_;
      return formula_node(Formula::Op::negate, {unary()});
    }
    if (at_symbol('+')) {
      ++next_;
      return unary();
    }
    return power();
  }

  FormulaPtr power() {
    FormulaPtr base = primary();
    if (!at_symbol('^')) return base;
    ++next_;
    std::size_t first = next_;
    FormulaPtr exponent = unary();
    auto f = std::make_shared<Formula>();
    f->op = Formula::Op::power;
    f->exponent = integer_value(exponent, first, next_);
    f->arguments = {base};
    return f;
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

  FormulaPtr primary() {
    Token token = current();
    switch (token.kind) {
      case Token::Kind::number:
        ++next_;
        return formula_constant(parse_literal(token.text, pointer_));
      case Token::Kind::name: {
        ++next_;
        if (at_symbol('(')) return call(token.text);
        if (token.text == "pi") return formula_node(Formula::Op::pi, {});
        auto f = std::make_shared<Formula>();
        f->op = Formula::Op::parameter;
        f->parameter = parameter_index_(token.text);
        return f;
      }
      case Token::Kind::symbol:
        if (token.text == "(") {
          ++next_;
          FormulaPtr value = expression();
          expect_symbol(')');
          return value;
        }
        fail("unexpected '" + token.text + "'");
      case Token::Kind::end:
        fail("unexpected end of expression");
    }
    fail("unexpected token");
  }

  FormulaPtr call(const std::string& name) {
    ++next_;  // '('
    std::vector<FormulaPtr> arguments;
    if (!at_symbol(')')) {
      arguments.push_back(expression());
      while (at_symbol(',')) {
        ++next_;
        arguments.push_back(expression());
      }
    }
    expect_symbol(')');
    using Op = Formula::Op;
    if (name == "sqrt" && arguments.size() == 1) return formula_node(Op::sqrt, arguments);
    if (name == "sin" && arguments.size() == 1) return formula_node(Op::sin, arguments);
    if (name == "cos" && arguments.size() == 1) return formula_node(Op::cos, arguments);
    if (name == "tan" && arguments.size() == 1) return formula_node(Op::tan, arguments);
    if (name == "atan2" && arguments.size() == 2) return formula_node(Op::atan2, arguments);
    if (name == "abs" && arguments.size() == 1) return formula_node(Op::abs, arguments);
    if (name == "min" && arguments.size() >= 2) return formula_node(Op::min, arguments);
    if (name == "max" && arguments.size() >= 2) return formula_node(Op::max, arguments);
    fail("unknown function '" + name + "'");
  }

  std::string_view text_;
  const std::string& pointer_;
  const std::function<std::size_t(const std::string&)>& parameter_index_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

}  // namespace

FormulaPtr parse_formula(std::string_view text, const std::string& pointer,
                         const std::function<std::size_t(const std::string&)>& parameter_index) {
  return Parser(text, pointer, parameter_index).run();
}

}  // namespace hipair::model_detail
