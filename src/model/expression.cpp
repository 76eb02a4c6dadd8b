#include "model/expression.hpp"

#include "core/exact_literal.hpp"
#include "core/model_scale.hpp"
#include "model/exact_trig.hpp"
#include "model/json_document.hpp"

#include <hipair/error.hpp>

#include <cctype>
#include <cmath>
#include <mpfi.h>

namespace hipair::model_detail {
namespace {

bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

std::optional<std::size_t> expression_tokens(std::string_view text, std::vector<ExpressionToken>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < text.size()) {
    char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    ExpressionToken token;
    token.position = i;
    if (is_digit(c) || (c == '.' && i + 1 < text.size() && is_digit(text[i + 1]))) {
      std::size_t j = i;
      while (j < text.size() && is_digit(text[j])) ++j;
      if (j < text.size() && text[j] == '.') {
        ++j;
        while (j < text.size() && is_digit(text[j])) ++j;
      }
      if (j < text.size() && (text[j] == 'e' || text[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
        if (k < text.size() && is_digit(text[k])) {
          while (k < text.size() && is_digit(text[k])) ++k;
          j = k;
        }
      }
      token.kind = ExpressionToken::Kind::number;
      token.text = std::string(text.substr(i, j - i));
      i = j;
    } else if (is_name_start(c)) {
      std::size_t j = i + 1;
      while (j < text.size()) {
        if (is_name_char(text[j])) {
          ++j;
        } else if (text[j] == '-' && j + 1 < text.size() && is_name_char(text[j + 1])) {
          j += 2;  // a '-' inside a name binds to the name
        } else {
          break;
        }
      }
      token.kind = ExpressionToken::Kind::name;
      token.text = std::string(text.substr(i, j - i));
      i = j;
    } else if (std::string_view("+-*/^(),").find(c) != std::string_view::npos) {
      token.kind = ExpressionToken::Kind::symbol;
      token.text = std::string(1, c);
      ++i;
    } else {
      return i;
    }
    tokens.push_back(std::move(token));
  }
  ExpressionToken end;
  end.kind = ExpressionToken::Kind::end;
  end.text = "end of expression";
  end.position = text.size();
  tokens.push_back(end);
  return std::nullopt;
}

namespace {

constexpr std::size_t max_nesting = 100;
constexpr long max_exponent = 1024;
constexpr long max_angle = 1000000;  // rad: larger angles orienting geometry are mistakes

std::string quoted_expression(std::string_view text) { return quoted_excerpt(text, 120); }

std::string lower_case(std::string_view text) {
  std::string out;
  for (char c : text) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

using Token = ExpressionToken;

// sin(p pi) when it is rational (Niven: only 0, +-1/2, +-1).
std::optional<Rational> exact_sin_of_pi_multiple(const Rational& multiple) {
  Rational six = multiple * 6;
  six.canonicalize();
  if (six.get_den() != 1) return std::nullopt;
  mpz_class k = six.get_num() % 12;
  if (k < 0) k += 12;
  switch (k.get_si()) {
    case 0: case 6: return Rational(0);
    case 1: case 5: return Rational(1, 2);
    case 3: return Rational(1);
    case 7: case 11: return Rational(-1, 2);
    case 9: return Rational(-1);
    default: return std::nullopt;
  }
}

class Evaluator {
 public:
  Evaluator(std::string_view text, const ExpressionContext& context)
      : text_(text), context_(context) {
    tokenize();
  }

  Quantity run() {
    Quantity value = expression();
    if (current().kind != Token::Kind::end) fail("unexpected '" + current().text + "'", current());
    return value;
  }

 private:
  // ------------------------------------------------------------------ errors
  [[noreturn]] void fail(const std::string& reason) const {
    throw ModelError(context_.pointer, reason + " in expression " + quoted_expression(text_));
  }
  [[noreturn]] void fail(const std::string& reason, const Token& at) const {
    fail(reason + " at character " + std::to_string(at.position + 1));
  }
  // A decision the current precision could not take (read_model retries at a higher one).
  [[noreturn]] void undecided(const std::string& reason) const {
    throw PrecisionExhausted(context_.pointer, reason + " in expression " + quoted_expression(text_));
  }

  // ------------------------------------------------------------------ tokens
  void tokenize() {
    if (std::optional<std::size_t> at = expression_tokens(text_, tokens_)) {
      const char c = text_[*at];
      std::string shown = static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f
                              ? "byte " + std::to_string(static_cast<unsigned char>(c))
                              : "'" + std::string(1, c) + "'";
      fail("unexpected character " + shown + " at character " + std::to_string(*at + 1));
    }
    if (tokens_.size() == 1) fail("empty expression");
  }

  const Token& current() const { return tokens_[next_]; }
  bool at_symbol(char symbol) const {
    return current().kind == Token::Kind::symbol && current().text[0] == symbol;
  }
  void expect_symbol(char symbol) {
    if (!at_symbol(symbol)) {
      const Token& t = current();
      fail("expected '" + std::string(1, symbol) + "' but found " +
               (t.kind == Token::Kind::end ? t.text : "'" + t.text + "'"),
           t);
    }
    ++next_;
  }

  struct DepthGuard {
    explicit DepthGuard(Evaluator& evaluator) : evaluator_(evaluator) {
      if (++evaluator_.depth_ > max_nesting) evaluator_.fail("nested too deeply");
    }
    ~DepthGuard() { --evaluator_.depth_; }
    Evaluator& evaluator_;
  };

  // ------------------------------------------------------------------ grammar
  // expression := term (('+' | '-') term)*
  Quantity expression() {
    DepthGuard guard(*this);
    Quantity value = term();
    while (at_symbol('+') || at_symbol('-')) {
      bool subtract = at_symbol('-');
      ++next_;
      Quantity right = term();
      value = add(value, subtract ? negate(right) : right);
    }
    return value;
  }

  // term := unary (('*' | '/') unary | unit)*     unit := 'deg' | 'rad'
  // A unit applies to the product or quotient accumulated so far: "pi/4 rad" is (pi/4) rad,
  // "360 deg / slots" is (360 deg) / slots.
  Quantity term() {
    Quantity value = unary();
    while (true) {
      if (at_symbol('*') || at_symbol('/')) {
        bool divide_by = at_symbol('/');
        ++next_;
        Quantity right = unary();
        value = divide_by ? divide(value, right) : multiply(value, right);
      } else if (current().kind == Token::Kind::name && (current().text == "deg" || current().text == "rad")) {
        if (value.is_angle) fail("'" + current().text + "' applied to a value that already is an angle", current());
        bool degrees = current().text == "deg";
        ++next_;
        if (degrees) {
          value = degrees_to_radians(value);
        } else {
          value.is_angle = true;
          value.mentions_pi = false;
        }
      } else {
        return value;
      }
    }
  }

  // unary := ('-' | '+') unary | power
  Quantity unary() {
    DepthGuard guard(*this);
    if (at_symbol('-')) {
      ++next_;
      return negate(unary());
    }
    if (at_symbol('+')) {
      ++next_;
      return unary();
    }
    return power();
  }

  // power := primary ('^' unary)?   (right associative through unary -> power)
  Quantity power() {
    Quantity base = primary();
    if (!at_symbol('^')) return base;
    const Token& caret = current();
    ++next_;
    Quantity exponent = unary();
    if (!exponent.is_rational() || exponent.rational.get_den() != 1)
      fail("the exponent after '^' must be an integer", caret);
    if (abs(exponent.rational) > max_exponent)
      fail("the exponent after '^' is larger than " + std::to_string(max_exponent), caret);
    return raise(base, exponent.rational.get_num().get_si());
  }

  // primary := number | name | name '(' arguments ')' | '(' expression ')'
  Quantity primary() {
    const Token token = current();
    switch (token.kind) {
      case Token::Kind::number: {
        ++next_;
        return Quantity::of(parse_literal(token.text, context_.pointer));
      }
      case Token::Kind::name: {
        ++next_;
        if (at_symbol('(')) return call(token);
        return named_value(token);
      }
      case Token::Kind::symbol:
        if (token.text == "(") {
          ++next_;
          Quantity value = expression();
          expect_symbol(')');
          return value;
        }
        fail("unexpected '" + token.text + "'", token);
      case Token::Kind::end:
        fail("unexpected end of expression", token);
    }
    fail("unexpected token", token);
  }

  Quantity named_value(const Token& token) {
    const std::string& name = token.text;
    std::string lower = lower_case(name);
    if (lower == "nan" || lower == "inf" || lower == "infinity")
      fail("'" + name + "' is not a number: NaN and infinity are not allowed");
    if (name == "pi") {
      Quantity pi = Quantity::of_pi(1, false);
      pi.mentions_pi = true;
      return pi;
    }
    if (name == "deg" || name == "rad") fail("unit '" + name + "' without a value before it", token);
    if (name == "sqrt" || name == "sin" || name == "cos" || name == "tan" || name == "atan2" ||
        name == "min" || name == "max" || name == "abs")
      fail("function '" + name + "' needs arguments in parentheses", token);
    if (!context_.parameter) fail("unknown parameter '" + name + "'");
    return context_.parameter(name);
  }

  Quantity call(const Token& function) {
    ++next_;  // '('
    std::vector<Quantity> arguments;
    if (!at_symbol(')')) {
      arguments.push_back(expression());
      while (at_symbol(',')) {
        ++next_;
        arguments.push_back(expression());
      }
    }
    expect_symbol(')');
    const std::string& name = function.text;
    auto arity = [&](std::size_t count) {
      if (arguments.size() != count)
        fail("function '" + name + "' takes " + std::to_string(count) + " argument" +
                 (count == 1 ? "" : "s") + ", not " + std::to_string(arguments.size()),
             function);
    };
    if (name == "sqrt") {
      arity(1);
      return with_pi(square_root(arguments[0]), arguments[0], arguments[0]);
    }
    if (name == "sin" || name == "cos" || name == "tan") {
      arity(1);
      return trigonometric(name, arguments[0]);
    }
    if (name == "atan2") {
      arity(2);
      return arc_tangent(arguments[0], arguments[1]);
    }
    if (name == "abs") {
      arity(1);
      const Quantity& x = arguments[0];
      if (x.exact || x.enclosure->sign() != 0) return sign(x, "abs") < 0 ? negate(x) : x;
      Interval magnitude;  // |x| needs no sign decision: enclose it directly
      mpfi_abs(magnitude.get(), x.enclosure->get());
      Quantity result = Quantity::approximate(magnitude, x.is_angle);
      result.mentions_pi = x.mentions_pi;
      return result;
    }
    if (name == "min" || name == "max") {
      if (arguments.size() < 2) fail("function '" + name + "' takes at least 2 arguments", function);
      Quantity best = arguments[0];
      bool any_pi = best.mentions_pi;
      for (std::size_t i = 1; i < arguments.size(); ++i) {
        unify(best, arguments[i]);
        any_pi = any_pi || arguments[i].mentions_pi;
        Quantity difference = add(arguments[i], negate(best));
        if (!difference.exact && difference.enclosure->sign() == 0) {
          best = enclose_extremum(best, arguments[i], name == "min");  // too close to choose
          continue;
        }
        int s = sign(difference, name);
        if ((name == "min" && s < 0) || (name == "max" && s > 0)) best = arguments[i];
      }
      best.mentions_pi = any_pi && !best.is_angle;
      return best;
    }
    fail("unknown function '" + name + "' (known: sqrt sin cos tan atan2 min max abs)", function);
  }

  // An enclosure of min(a, b) or max(a, b) without deciding which is smaller.
  static Quantity enclose_extremum(const Quantity& a, const Quantity& b, bool minimum) {
    Interval x = a.to_interval(), y = b.to_interval();
    mpfr_t lo_x, hi_x, lo_y, hi_y;
    mpfr_inits2(working_interval_bits(), lo_x, hi_x, lo_y, hi_y, static_cast<mpfr_ptr>(nullptr));
    mpfi_get_left(lo_x, x.get());
    mpfi_get_right(hi_x, x.get());
    mpfi_get_left(lo_y, y.get());
    mpfi_get_right(hi_y, y.get());
    if (minimum) {
      mpfr_min(lo_x, lo_x, lo_y, MPFR_RNDD);
      mpfr_min(hi_x, hi_x, hi_y, MPFR_RNDU);
    } else {
      mpfr_max(lo_x, lo_x, lo_y, MPFR_RNDD);
      mpfr_max(hi_x, hi_x, hi_y, MPFR_RNDU);
    }
    Interval result;
    mpfi_interv_fr(result.get(), lo_x, hi_x);
    mpfr_clears(lo_x, hi_x, lo_y, hi_y, static_cast<mpfr_ptr>(nullptr));
    return Quantity::approximate(result, a.is_angle);
  }

  // ------------------------------------------------------------------ arithmetic
  void check_size(const Rational& value) const {
    if (mpz_sizeinbase(value.get_num_mpz_t(), 2) > max_rational_bits ||
        mpz_sizeinbase(value.get_den_mpz_t(), 2) > max_rational_bits)
      fail("number too large (more than " + std::to_string(max_rational_bits) + " bits)");
  }
  Quantity checked(Quantity value) const {
    if (value.exact) {
      value.rational.canonicalize();
      value.pi_multiple.canonicalize();
      check_size(value.rational);
      check_size(value.pi_multiple);
    } else if (!value.enclosure->is_bounded()) {
      fail("the value is not finite");
    }
    return value;
  }

  // Makes both operands angles when one is (a plain number next to an angle is in file units).
  void unify(Quantity& a, Quantity& b) const {
    if (a.is_angle && !b.is_angle) b = as_angle(b, context_.degrees, context_.pointer, text_);
    if (b.is_angle && !a.is_angle) a = as_angle(a, context_.degrees, context_.pointer, text_);
  }

  Quantity add(Quantity a, Quantity b) const {
    unify(a, b);
    return with_pi(add_values(a, b), a, b);
  }

  Quantity add_values(const Quantity& a, const Quantity& b) const {
    if (a.exact && b.exact) {
      Quantity sum = Quantity::of(a.rational + b.rational, a.is_angle);
      sum.pi_multiple = a.pi_multiple + b.pi_multiple;
      return checked(sum);
    }
    return checked(Quantity::approximate(a.to_interval() + b.to_interval(), a.is_angle));
  }

  static Quantity with_pi(Quantity result, const Quantity& a, const Quantity& b) {
    result.mentions_pi = !result.is_angle && (a.mentions_pi || b.mentions_pi);
    return result;
  }

  Quantity degrees_to_radians(const Quantity& value) const {
    Quantity plain = value;
    plain.mentions_pi = false;
    return as_angle(plain, true, context_.pointer, text_);
  }

  Quantity negate(Quantity a) const {
    if (a.exact) {
      a.rational = -a.rational;
      a.pi_multiple = -a.pi_multiple;
    } else {
      a.enclosure = -*a.enclosure;
    }
    return a;
  }

  Quantity multiply(const Quantity& a, const Quantity& b) const {
    return with_pi(multiply_values(a, b), a, b);
  }

  Quantity multiply_values(const Quantity& a, const Quantity& b) const {
    bool angle = a.is_angle != b.is_angle;
    // An exact zero times anything is exactly zero (a profile offset of 0 along an irrational
    // normal leaves the nominal point exact).
    if ((a.is_rational() && a.rational == 0) || (b.is_rational() && b.rational == 0))
      return checked(Quantity::of(0, angle));
    if (a.exact && b.exact) {
      if (a.pi_multiple == 0) {
        Quantity product = Quantity::of(a.rational * b.rational, angle);
        product.pi_multiple = a.rational * b.pi_multiple;
        return checked(product);
      }
      if (b.pi_multiple == 0) {
        Quantity product = Quantity::of(b.rational * a.rational, angle);
        product.pi_multiple = b.rational * a.pi_multiple;
        return checked(product);
      }
    }
    return checked(Quantity::approximate(a.to_interval() * b.to_interval(), angle));
  }

  Quantity divide(const Quantity& a, const Quantity& b) const {
    return with_pi(divide_values(a, b), a, b);
  }

  Quantity divide_values(const Quantity& a, const Quantity& b) const {
    bool angle = a.is_angle && !b.is_angle;
    if (b.exact && b.pi_multiple == 0) {
      if (b.rational == 0) fail("division by zero");
      if (a.exact) {
        Quantity quotient = Quantity::of(a.rational / b.rational, angle);
        quotient.pi_multiple = a.pi_multiple / b.rational;
        return checked(quotient);
      }
    }
    if (a.exact && b.exact && a.rational == 0 && b.rational == 0)  // (p pi) / (q pi), q != 0
      return checked(Quantity::of(a.pi_multiple / b.pi_multiple, angle));
    Interval denominator = b.to_interval();
    if (denominator.sign() == 0) undecided("division by zero (or by a value too close to zero to decide)");
    return checked(Quantity::approximate(a.to_interval() / denominator, angle));
  }

  Quantity raise(const Quantity& base, long exponent) const {
    return with_pi(raise_value(base, exponent), base, base);
  }

  Quantity raise_value(const Quantity& base, long exponent) const {
    if (exponent == 0) return Quantity::of(1);
    if (exponent == 1) return base;
    if (base.is_rational()) {
      if (base.rational == 0 && exponent < 0) fail("division by zero (0 to a negative power)");
      unsigned long magnitude = static_cast<unsigned long>(exponent < 0 ? -exponent : exponent);
      // Bound the size before computing it.
      std::size_t bits = std::max(mpz_sizeinbase(base.rational.get_num_mpz_t(), 2),
                                  mpz_sizeinbase(base.rational.get_den_mpz_t(), 2));
      if (bits > 1 && (bits - 1) * magnitude > max_rational_bits)
        fail("number too large (more than " + std::to_string(max_rational_bits) + " bits)");
      mpz_class numerator, denominator;
      mpz_pow_ui(numerator.get_mpz_t(), base.rational.get_num_mpz_t(), magnitude);
      mpz_pow_ui(denominator.get_mpz_t(), base.rational.get_den_mpz_t(), magnitude);
      Rational result = exponent > 0 ? Rational(numerator, denominator) : Rational(denominator, numerator);
      result.canonicalize();  // a negative base to a negative power puts the sign below
      return checked(Quantity::of(result));
    }
    Interval value = base.to_interval();
    unsigned long magnitude = static_cast<unsigned long>(exponent < 0 ? -exponent : exponent);
    Interval result(Rational(1));
    Interval factor = value;
    while (magnitude > 0) {
      if (magnitude & 1) result = result * factor;
      magnitude >>= 1;
      if (magnitude > 0) factor = factor * factor;
    }
    if (exponent < 0) {
      if (result.sign() == 0) undecided("division by zero (or by a value too close to zero to decide)");
      result = Interval(Rational(1)) / result;
    }
    return checked(Quantity::approximate(result));
  }

  int sign(const Quantity& value, const std::string& what) const {
    if (value.exact) {
      int rational_sign = sgn(value.rational), pi_sign = sgn(value.pi_multiple);
      if (pi_sign == 0) return rational_sign;
      if (rational_sign == 0 || rational_sign == pi_sign) return pi_sign;
    }
    int s = value.to_interval().sign();
    if (s == 0) undecided("cannot decide the sign of a value too close to zero (in " + what + ")");
    return s;
  }

  Quantity square_root(const Quantity& value) const {
    if (value.is_rational()) {
      if (value.rational < 0) fail("square root of a negative number");
      if (mpz_perfect_square_p(value.rational.get_num_mpz_t()) &&
          mpz_perfect_square_p(value.rational.get_den_mpz_t())) {
        mpz_class numerator, denominator;
        mpz_sqrt(numerator.get_mpz_t(), value.rational.get_num_mpz_t());
        mpz_sqrt(denominator.get_mpz_t(), value.rational.get_den_mpz_t());
        return checked(Quantity::of(Rational(numerator, denominator)));
      }
    }
    Interval argument = value.to_interval();
    if (argument.sign() < 0) fail("square root of a negative number");
    if (!argument.is_bounded() || argument.lower() < 0)
      undecided("cannot decide whether the argument of sqrt is negative: it is too close to zero");
    Interval result;
    mpfi_sqrt(result.get(), argument.get());
    return checked(Quantity::approximate(result));
  }

  Quantity trigonometric(const std::string& name, const Quantity& argument) const {
    Quantity angle = as_angle(argument, context_.degrees, context_.pointer, text_);
    if (angle.is_rational() && angle.rational == 0)
      return Quantity::of(name == "cos" ? Rational(1) : Rational(0));
    if (angle.is_pi_multiple()) {
      const Rational& p = angle.pi_multiple;
      if (name == "sin") {
        if (auto exact = exact_sin_of_pi_multiple(p)) return Quantity::of(*exact);
      } else if (name == "cos") {
        if (auto exact = exact_sin_of_pi_multiple(p + Rational(1, 2))) return Quantity::of(*exact);
      } else {
        Rational twice = 2 * p;
        twice.canonicalize();
        if (twice.get_den() == 1 && twice.get_num() % 2 != 0)
          fail("tan is undefined at an odd multiple of 90 degrees");
        Rational four = 4 * p;
        four.canonicalize();
        if (four.get_den() == 1) {
          mpz_class k = four.get_num() % 4;
          if (k < 0) k += 4;
          return Quantity::of(k == 0 ? Rational(0) : k == 1 ? Rational(1) : Rational(-1));
        }
      }
    }
    Interval x = angle.to_interval();
    Interval result;
    if (name == "sin")
      mpfi_sin(result.get(), x.get());
    else if (name == "cos")
      mpfi_cos(result.get(), x.get());
    else
      mpfi_tan(result.get(), x.get());
    if (!result.is_bounded()) result = tangent_near_pole(angle);
    return checked(Quantity::approximate(result));
  }

  // tan of an angle whose 256-bit enclosure contains a pole (an odd multiple of pi/2). An exact
  // angle r + p*pi is at a pole only when r = 0 and 2p is an odd integer (pi is irrational),
  // which the caller has ruled out; so the enclosure is refined at doubling precision until it
  // excludes the pole, and the certified (huge) tangent is returned. An angle known only by an
  // enclosure cannot be decided.
  Interval tangent_near_pole(const Quantity& angle) const {
    if (!angle.exact)
      fail("cannot decide whether the argument of tan is at a pole (an odd multiple of 90 degrees): "
           "it is known only approximately and too close to one");
    constexpr mpfr_prec_t most_bits = 32768;
    for (mpfr_prec_t bits = 2 * working_interval_bits(); bits <= most_bits; bits *= 2) {
      mpfi_t pi, x, tangent;
      mpfi_init2(pi, bits);
      mpfi_init2(x, bits);
      mpfi_init2(tangent, bits);
      mpfi_const_pi(pi);
      mpfi_mul_q(x, pi, angle.pi_multiple.get_mpq_t());
      mpfi_add_q(x, x, angle.rational.get_mpq_t());
      mpfi_tan(tangent, x);
      bool bounded = !mpfi_nan_p(tangent) && mpfi_bounded_p(tangent);
      Interval result;
      if (bounded) mpfi_set(result.get(), tangent);  // outward to the working precision
      mpfi_clear(pi);
      mpfi_clear(x);
      mpfi_clear(tangent);
      if (bounded) return result;
    }
    fail("tan is too large: the argument is not at a pole (an odd multiple of 90 degrees) but so close to one that " +
         std::to_string(most_bits) + "-bit arithmetic cannot separate them");
    return Interval();
  }

  Quantity arc_tangent(const Quantity& y, const Quantity& x) const {
    if (y.is_rational() && x.is_rational()) {
      int sy = sgn(y.rational), sx = sgn(x.rational);
      if (sy == 0 && sx == 0) fail("atan2(0, 0) is undefined");
      if (sy == 0) return Quantity::of_pi(sx > 0 ? 0 : 1);
      if (sx == 0) return Quantity::of_pi(Rational(sy, 2));
      if (abs(y.rational) == abs(x.rational)) return Quantity::of_pi(Rational(sy * (sx > 0 ? 1 : 3), 4));
    }
    if (y.is_rational() && y.rational == 0) return Quantity::of_pi(sign(x, "atan2") > 0 ? 0 : 1);
    if (x.is_rational() && x.rational == 0) return Quantity::of_pi(Rational(sign(y, "atan2"), 2));
    Interval result;
    mpfi_atan2(result.get(), y.to_interval().get(), x.to_interval().get());
    return checked(Quantity::approximate(result, true));
  }

  std::string_view text_;
  const ExpressionContext& context_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::size_t depth_ = 0;
};

}  // namespace

Quantity Quantity::of(const Rational& value, bool is_angle) {
  Quantity q;
  q.rational = value;
  q.is_angle = is_angle;
  return q;
}

Quantity Quantity::of_pi(const Rational& multiple, bool is_angle) {
  Quantity q;
  q.pi_multiple = multiple;
  q.is_angle = is_angle;
  return q;
}

Quantity Quantity::approximate(Interval enclosure, bool is_angle) {
  Quantity q;
  q.exact = false;
  q.enclosure = std::move(enclosure);
  q.is_angle = is_angle;
  return q;
}

Interval Quantity::to_interval() const {
  if (!exact) return *enclosure;
  Interval value(rational);
  if (pi_multiple != 0) value = value + Interval::pi() * Interval(pi_multiple);
  return value;
}

Quantity evaluate_expression(std::string_view text, const ExpressionContext& context) {
  return Evaluator(text, context).run();
}

Quantity as_angle(const Quantity& value, bool degrees, const std::string& pointer,
                  std::string_view expression) {
  if (value.is_angle) return value;
  if (degrees && value.mentions_pi)
    throw ModelError(pointer, "ambiguous angle " + quoted_expression(expression) +
                                  ": the file's angle unit is deg but the value is computed with pi; "
                                  "write the unit ('pi/4 rad') or the angle in degrees");
  Quantity angle = value;
  angle.is_angle = true;
  angle.mentions_pi = false;
  if (!degrees) return angle;
  if (value.is_rational()) return Quantity::of_pi(value.rational / 180);
  return Quantity::approximate(value.to_interval() * Interval::pi() / Interval(Rational(180)), true);
}

static_assert(max_literal_exponent == exact_literal_max_exponent, "one exponent limit for every exact literal");

Rational parse_literal(std::string_view text, const std::string& pointer) {
  std::string lower = lower_case(text);
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
    throw ModelError(pointer, quoted_excerpt(text) + " is not a number: NaN and infinity are not allowed");
  if (auto e = lower.find('e'); e != std::string::npos) {
    std::string_view exponent = text.substr(e + 1);
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.remove_prefix(1);
    while (exponent.size() > 1 && exponent[0] == '0') exponent.remove_prefix(1);
    bool digits = !exponent.empty();
    for (char c : exponent) digits = digits && is_digit(c);
    if (digits && (exponent.size() > 4 || std::stol(std::string(exponent)) > max_literal_exponent))
      throw ModelError(pointer, "number " + quoted_excerpt(text) + " out of range: the decimal exponent is limited to " +
                                    std::to_string(max_literal_exponent));
  }
  Rational value;
  try {
    value = parse_exact_literal(text);
  } catch (const NumericError& error) {
    throw ModelError(pointer, error.what());
  }
  check_rational_size(value, pointer);
  return value;
}

void check_rational_size(const Rational& value, const std::string& pointer) {
  if (mpz_sizeinbase(value.get_num_mpz_t(), 2) > max_rational_bits ||
      mpz_sizeinbase(value.get_den_mpz_t(), 2) > max_rational_bits)
    throw ModelError(pointer, "number too large (more than " + std::to_string(max_rational_bits) + " bits)");
}

int sign_of(const Quantity& value, const std::string& pointer, std::string_view expression) {
  if (value.exact) {
    int rational_sign = sgn(value.rational), pi_sign = sgn(value.pi_multiple);
    if (pi_sign == 0) return rational_sign;
    if (rational_sign == 0 || rational_sign == pi_sign) return pi_sign;
  }
  int s = value.to_interval().sign();
  if (s == 0)
    throw PrecisionExhausted(pointer, "cannot decide the sign of " + quoted_expression(expression) +
                                          ": too close to zero");
  return s;
}

Rational rounding_bound_near(const Rational& magnitude) {
  const Rational& bound = rounding_bound();
  static const Rational small(1, mpz_class(1) << 20);
  static const Rational relative(1, mpz_class(1) << 44);
  if (magnitude <= 0 || magnitude >= small) return bound;
  Rational proportional = magnitude * relative;
  return proportional < bound ? proportional : bound;
}

Rational to_rational(const Quantity& value, const std::string& pointer,
                     const std::string& expression, std::vector<Rounding>& roundings) {
  if (value.is_rational()) return value.rational;
  Interval enclosure = value.to_interval();
  if (!enclosure.is_bounded())
    throw ModelError(pointer, "the value of " + quoted_expression(expression) + " is not finite");
  Rational lower = enclosure.lower(), upper = enclosure.upper();
  // Every value within the bound of each end of the enclosure is within the bound of the exact
  // value: the simplest rational of [upper - bound, lower + bound] (small denominators keep the
  // downstream polynomials' coefficients small).
  // A value that is certainly not 0 and outside [2^-20, 2^40] (in its unit) is rounded as at
  // its decimal scale: in units U = 10^E, E the multiple of 10 that brings it within [1e-4, 1e6)
  // (core/model_scale.hpp decimal_unit_exponent), the simplest rational within b of value / U,
  // times U (bound b U). A value written at 10^(10 j) times an ordinary one (in [1e-4, 1e6)) is
  // so exactly 10^(10 j) times the rational the ordinary one gets: a model scaled by 10^(10 j)
  // reads as that model scaled, as the templates do (template_geometry.cpp). Until session 54
  // large values kept the absolute bound b (the escapement x 1e400's banking pins and balance
  // spring were other rationals than x 1's, and its simulation jammed at 0.0082 s) and small
  // ones min(b, 2^-44 |v|) in units of the power of ten below them.
  Rational magnitude;
  if (enclosure.sign() != 0) magnitude = lower > 0 ? lower : Rational(-upper);
  static const Rational small(1, mpz_class(1) << 20), large(mpz_class(1) << 40);
  const bool decimal = magnitude > 0 && (magnitude < small || magnitude > large);
  const Rational unit = decimal ? power_of_ten_rational(decimal_unit_exponent(magnitude)) : Rational(1);
  const Rational bound = decimal ? Rational(rounding_bound() * unit) : rounding_bound();
  Rational from = upper - bound, to = lower + bound;
  if (from > to)
    throw PrecisionExhausted(pointer, "cannot evaluate " + quoted_expression(expression) + " to within the rounding bound " +
                                          to_decimal_string(bound, 3) + " (the value is too large for " +
                                          std::to_string(working_interval_bits()) + "-bit precision)");
  const Rational rounded = decimal ? Rational(unit * simplest_rational_between(Rational(from / unit), Rational(to / unit)))
                                   : simplest_rational_between(from, to);
  roundings.push_back(Rounding{pointer, expression, rounded, bound});
  return rounded;
}

Point unit_vector(const Quantity& angle, const std::string& pointer, const std::string& expression,
                  std::vector<Rounding>& roundings) {
  if (angle.is_pi_multiple()) {
    // Exact reduction to (-1, 1] turns of pi keeps the 256-bit evaluation accurate.
    Rational half = angle.pi_multiple / 2;
    mpz_class turns;
    Rational shifted = half + Rational(1, 2);
    mpz_fdiv_q(turns.get_mpz_t(), shifted.get_num_mpz_t(), shifted.get_den_mpz_t());
    Rational reduced = angle.pi_multiple - 2 * Rational(turns);
    return exact_unit_vector_pi(reduced, pointer, expression, roundings);
  }
  // rational + pi_multiple pi (Session 67, issue 14): take the whole half turns n out exactly
  // (pi_multiple = n + f, f in (-1/2, 1/2]), round the reduced angle rational + f pi once and
  // negate its direction for odd n. Features a half turn apart (k pi/2 + pi +- span/2 and
  // (k + 2) pi/2 + pi +- span/2) so get exactly negated directions, and the angle used,
  // rounded + n pi, is within the rounding bound of the exact one as before. Until session 66
  // each whole angle was rounded on its own (Geneva's lock arcs 1.8e-11 mm off their half turns).
  // n = 0 (|pi_multiple| <= 1/2) is the path below, as before.
  mpz_class turns;
  if (angle.exact && !angle.is_rational()) {
    Rational shifted = angle.pi_multiple - Rational(1, 2);
    shifted.canonicalize();
    mpz_cdiv_q(turns.get_mpz_t(), shifted.get_num_mpz_t(), shifted.get_den_mpz_t());
  }
  if (sgn(turns) != 0) {
    const Interval whole = angle.to_interval();
    if (whole.is_bounded() && (whole.lower() > max_angle || whole.upper() < -max_angle))
      throw ModelError(pointer, "the angle " + quoted_expression(expression) + " is larger than " +
                                    std::to_string(max_angle) + " rad in magnitude");
    Quantity reduced = angle;
    reduced.pi_multiple = angle.pi_multiple - Rational(turns);
    reduced.pi_multiple.canonicalize();
    // the text as written, and what the recorded value is: the angle less its n half turns
    const std::string reduced_text = expression + " (reduced by " + turns.get_str() + "*pi)";
    const Rational value = reduced.is_rational() ? reduced.rational : to_rational(reduced, pointer, reduced_text, roundings);
    Point unit = exact_unit_vector(value, pointer, reduced_text, roundings);
    if (mpz_odd_p(turns.get_mpz_t())) {
      unit.x = -unit.x;
      unit.y = -unit.y;
    }
    return unit;
  }
  Rational value = angle.is_rational() ? angle.rational : to_rational(angle, pointer, expression, roundings);
  if (abs(value) > max_angle)
    throw ModelError(pointer, "the angle " + quoted_expression(expression) + " is larger than " +
                                  std::to_string(max_angle) + " rad in magnitude");
  return exact_unit_vector(value, pointer, expression, roundings);
}

Point unit_direction(const Rational& dx, const Rational& dy, const std::string& pointer, const std::string& dx_text,
                     const std::string& dy_text, std::vector<Rounding>& roundings) {
  Rational length_squared = dx * dx + dy * dy;
  if (length_squared == 0) throw ModelError(pointer, "zero direction vector: the axis has no direction");
  if (mpz_perfect_square_p(length_squared.get_num_mpz_t()) &&
      mpz_perfect_square_p(length_squared.get_den_mpz_t())) {
    mpz_class numerator, denominator;
    mpz_sqrt(numerator.get_mpz_t(), length_squared.get_num_mpz_t());
    mpz_sqrt(denominator.get_mpz_t(), length_squared.get_den_mpz_t());
    Rational length(numerator, denominator);
    return Point{Rational(dx / length), Rational(dy / length)};
  }
  // Half-angle tangent t = dy / (|d| + dx) of the direction (or of its opposite when dx < 0,
  // which keeps |t| <= 1), rounded within the rounding bound: the vector is then exactly unit.
  bool flip = dx < 0;
  Rational x = flip ? Rational(-dx) : dx, y = flip ? Rational(-dy) : dy;
  Interval length;
  Interval squared(length_squared);
  mpfi_sqrt(length.get(), squared.get());
  Interval t = Interval(y) / (length + Interval(x));
  std::string expression = "direction [" + dx_text + ", " + dy_text + "] (half-angle tangent)";
  Rational rounded = to_rational(Quantity::approximate(t), pointer, expression, roundings);
  Point unit = unit_from_half_tangent(rounded);
  if (flip) unit = Point{Rational(-unit.x), Rational(-unit.y)};
  return unit;
}

}  // namespace hipair::model_detail
