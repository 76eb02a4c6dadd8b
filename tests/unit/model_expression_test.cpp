// The exact expression evaluator: rationals stay exact, multiples of pi stay exact, the rest
// is enclosed and rounded to the 10^-12 grid with a recorded, proven bound.
#include "model/expression.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace {

using hipair::Rational;
using hipair::model_detail::ExpressionContext;
using hipair::model_detail::Quantity;

Quantity evaluate(const std::string& text, bool degrees = false,
                  const std::map<std::string, Quantity>& parameters = {}) {
  ExpressionContext context;
  context.degrees = degrees;
  context.pointer = "/x";
  context.parameter = [&parameters](const std::string& name) {
    auto found = parameters.find(name);
    if (found == parameters.end()) throw hipair::ModelError("/x", "unknown parameter '" + name + "'");
    return found->second;
  };
  return hipair::model_detail::evaluate_expression(text, context);
}

Rational exact(const std::string& text, bool degrees = false,
               const std::map<std::string, Quantity>& parameters = {}) {
  Quantity q = evaluate(text, degrees, parameters);
  EXPECT_TRUE(q.is_rational()) << text;
  return q.rational;
}

Rational pi_multiple(const std::string& text, bool degrees = false,
                     const std::map<std::string, Quantity>& parameters = {}) {
  Quantity q = evaluate(text, degrees, parameters);
  EXPECT_TRUE(q.is_pi_multiple()) << text;
  return q.pi_multiple;
}

std::string error_of(const std::string& text, bool degrees = false) {
  try {
    evaluate(text, degrees);
  } catch (const hipair::ModelError& error) {
    EXPECT_EQ(error.pointer(), "/x");
    return error.reason();
  }
  ADD_FAILURE() << text << " evaluated without error";
  return "";
}

TEST(Expression, RationalArithmeticIsExact) {
  EXPECT_EQ(exact("46.683"), Rational(46683, 1000));
  EXPECT_EQ(exact("0.1 + 0.2"), Rational(3, 10));
  EXPECT_EQ(exact("1/3 + 1/6"), Rational(1, 2));
  EXPECT_EQ(exact("9007199254740993 - 9007199254740992"), Rational(1));
  EXPECT_EQ(exact("-2^2"), Rational(-4));
  EXPECT_EQ(exact("(-2)^3"), Rational(-8));
  EXPECT_EQ(exact("2^-2"), Rational(1, 4));
  EXPECT_EQ(exact("2^3^2"), Rational(512));  // right associative
  EXPECT_EQ(exact("2*3 + 4/8 - -1"), Rational(15, 2));
  EXPECT_EQ(exact("1e-30 * 1e30"), Rational(1));
  EXPECT_EQ(exact("abs(-7/2)"), Rational(7, 2));
  EXPECT_EQ(exact("min(3, 1/2, 2)"), Rational(1, 2));
  EXPECT_EQ(exact("max(3, 1/2, 2)"), Rational(3));
}

TEST(Expression, SquareRootsOfSquaresAreExact) {
  EXPECT_EQ(exact("sqrt(9/4)"), Rational(3, 2));
  EXPECT_EQ(exact("sqrt(3^2 + 4^2)"), Rational(5));
  EXPECT_EQ(exact("sqrt(0)"), Rational(0));
  EXPECT_FALSE(evaluate("sqrt(2)").exact);
}

TEST(Expression, DegreesStayExactMultiplesOfPi) {
  std::map<std::string, Quantity> parameters{{"slots", Quantity::of(4)}};
  EXPECT_EQ(pi_multiple("360 deg / slots", false, parameters), Rational(1, 2));
  EXPECT_EQ(pi_multiple("pi/4"), Rational(1, 4));
  EXPECT_EQ(pi_multiple("30 deg + 15 deg"), Rational(1, 4));
  EXPECT_EQ(exact("(90 deg) / (30 deg)"), Rational(3));  // a ratio of angles is a plain number
  // In a degree file, a plain number next to an angle is in degrees.
  EXPECT_EQ(pi_multiple("pi/4 rad + 45", true), Rational(1, 2));
  EXPECT_EQ(pi_multiple("30 deg + 15", true), Rational(1, 4));
  // pi is a plain number: lengths computed with pi stay lengths in a degree file...
  Quantity thickness = evaluate("pi * 2 / 2 - 0.1 / 2", true);
  EXPECT_FALSE(thickness.is_angle);
  EXPECT_EQ(thickness.rational, Rational(-1, 20));
  EXPECT_EQ(thickness.pi_multiple, Rational(1));
  // ...and as an angle there it is ambiguous.
  EXPECT_NE(error_of("sin(pi/6)", true).find("ambiguous angle"), std::string::npos);
  EXPECT_NE(error_of("pi/4 + 45 deg", true).find("ambiguous angle"), std::string::npos);
  EXPECT_EQ(exact("sin(pi/6 rad)", true), Rational(1, 2));
  EXPECT_EQ(exact("sin(pi/6)"), Rational(1, 2));  // in a radian file pi/6 is an angle in rad
  // A unit applies to the product or quotient before it.
  EXPECT_EQ(pi_multiple("pi/4 rad", true), Rational(1, 4));
  EXPECT_TRUE(evaluate("pi/4 rad", true).is_angle);
  EXPECT_EQ(pi_multiple("-90 deg / 3"), Rational(-1, 6));
  EXPECT_EQ(pi_multiple("2 * 45 deg"), Rational(1, 2));
  EXPECT_TRUE(evaluate("30 deg").is_angle);
  EXPECT_TRUE(evaluate("atan2(1, 1)").is_angle);
  EXPECT_FALSE(evaluate("30").is_angle);
}

TEST(Expression, TrigonometryIsExactWhereTheValueIsRational) {
  EXPECT_EQ(exact("sin(30 deg)"), Rational(1, 2));
  EXPECT_EQ(exact("cos(60 deg)"), Rational(1, 2));
  EXPECT_EQ(exact("cos(pi)"), Rational(-1));
  EXPECT_EQ(exact("sin(-pi/2)"), Rational(-1));
  EXPECT_EQ(exact("tan(45 deg)"), Rational(1));
  EXPECT_EQ(exact("tan(-135 deg)"), Rational(1));
  EXPECT_EQ(exact("sin(0)"), Rational(0));
  EXPECT_EQ(exact("cos(0)"), Rational(1));
  EXPECT_EQ(exact("sin(30)", true), Rational(1, 2));  // literal in a degree file
  EXPECT_EQ(pi_multiple("atan2(1, -1)"), Rational(3, 4));
  EXPECT_EQ(pi_multiple("atan2(0, -5)"), Rational(1));
  EXPECT_EQ(pi_multiple("atan2(-2, 0)"), Rational(-1, 2));
  EXPECT_FALSE(evaluate("cos(30 deg)").exact);
  EXPECT_FALSE(evaluate("sin(1)").exact);
}

TEST(Expression, InexactValuesAreRoundedWithARecordedBound) {
  std::vector<hipair::Rounding> roundings;
  Rational root2 = hipair::model_detail::to_rational(evaluate("sqrt(2)"), "/p", "sqrt(2)", roundings);
  // the simplest rational within 1e-12 of sqrt(2): the convergent 1607521/1136689 (was the grid
  // value 1.414213562373)
  EXPECT_EQ(root2, Rational(1607521, 1136689));
  ASSERT_EQ(roundings.size(), 1u);
  EXPECT_EQ(roundings[0].pointer, "/p");
  EXPECT_EQ(roundings[0].expression, "sqrt(2)");
  EXPECT_EQ(roundings[0].bound, hipair::parse_rational("1e-12"));
  // The bound is true: |2 - value^2| <= 2 * sqrt(2) * bound + bound^2.
  EXPECT_LT(abs(Rational(2 - root2 * root2)), hipair::parse_rational("3e-12"));
  Rational cos30 = hipair::model_detail::to_rational(evaluate("cos(30 deg)"), "/q", "cos(30 deg)", roundings);
  EXPECT_EQ(cos30, Rational(489061, 564719));  // simplest within 1e-12 of 0.86602540378443...
  EXPECT_LT(abs(Rational(cos30 * cos30 - Rational(3, 4))), hipair::parse_rational("2e-12"));
  Rational pi4 = hipair::model_detail::to_rational(evaluate("pi/4"), "/r", "pi/4", roundings);
  EXPECT_EQ(pi4, Rational(286602, 364913));  // simplest within 1e-12 of 0.78539816339744...
  EXPECT_LT(abs(Rational(pi4 - hipair::parse_rational("0.78539816339744830961566"))), hipair::parse_rational("1e-12"));
  EXPECT_EQ(roundings.size(), 3u);
  // Exact values are never recorded.
  hipair::model_detail::to_rational(evaluate("1/3"), "/s", "1/3", roundings);
  EXPECT_EQ(roundings.size(), 3u);
}

TEST(Expression, ParametersWithMinusInsideTheirNames) {
  std::map<std::string, Quantity> parameters{{"pin-radius", Quantity::of(Rational(9, 2))},
                                             {"pin-center", Quantity::of(20)},
                                             {"a", Quantity::of(5)},
                                             {"b", Quantity::of(2)}};
  EXPECT_EQ(exact("pin-center + 2*pin-radius", false, parameters), Rational(29));
  EXPECT_EQ(exact("a - b", false, parameters), Rational(3));
  EXPECT_EQ(exact("a -b", false, parameters), Rational(3));
  EXPECT_THROW(exact("a-b", false, parameters), hipair::ModelError);  // one unknown name "a-b"
}

TEST(Expression, ErrorsNameTheProblem) {
  EXPECT_NE(error_of("1/0").find("division by zero"), std::string::npos);
  EXPECT_NE(error_of("1/(pi - pi)").find("division by zero"), std::string::npos);
  EXPECT_NE(error_of("sqrt(-4)").find("square root of a negative"), std::string::npos);
  EXPECT_NE(error_of("sqrt(1 - pi)").find("square root of a negative"), std::string::npos);
  EXPECT_NE(error_of("tan(90 deg)").find("tan is undefined"), std::string::npos);
  EXPECT_NE(error_of("tan(pi/2)").find("tan is undefined"), std::string::npos);
  EXPECT_NE(error_of("atan2(0, 0)").find("undefined"), std::string::npos);
  EXPECT_NE(error_of("2^0.5").find("integer"), std::string::npos);
  EXPECT_NE(error_of("2^100000").find("larger than"), std::string::npos);
  EXPECT_NE(error_of("10^1000^1000").find("too large"), std::string::npos);
  EXPECT_NE(error_of("(2 + 3").find("expected ')'"), std::string::npos);
  EXPECT_NE(error_of("2 +").find("unexpected end"), std::string::npos);
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
  EXPECT_NE(error_of("2 $ 3").find("unexpected character"), std::string::npos);
  EXPECT_NE(error_of("nan").find("NaN"), std::string::npos);
  EXPECT_NE(error_of("Infinity").find("NaN and infinity"), std::string::npos);
  EXPECT_NE(error_of("1e99999").find("out of range"), std::string::npos);
  EXPECT_NE(error_of("log(2)").find("unknown function"), std::string::npos);
  EXPECT_NE(error_of("sin(1, 2)").find("takes 1 argument"), std::string::npos);
  EXPECT_NE(error_of("30 deg deg").find("already is an angle"), std::string::npos);
  EXPECT_NE(error_of("30 deg )").find("unexpected ')'"), std::string::npos);
  EXPECT_NE(error_of("(30 deg) rad").find("already is an angle"), std::string::npos);
  EXPECT_NE(error_of("width").find("unknown parameter 'width'"), std::string::npos);
  EXPECT_NE(error_of(std::string(500, '(') + "1" + std::string(500, ')')).find("nested too deeply"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(5000, '-') + "1").find("nested too deeply"), std::string::npos);
}

TEST(Expression, UnitVectorsOfAnglesAreExactlyUnit) {
  std::vector<hipair::Rounding> roundings;
  for (const char* text : {"30 deg", "pi/3", "1", "sqrt(2)", "-170 deg", "atan2(3, 4)"}) {
    Quantity angle = hipair::model_detail::as_angle(evaluate(text), false, "/d", text);
    hipair::Point unit = hipair::model_detail::unit_vector(angle, "/d", text, roundings);
    EXPECT_EQ(unit.x * unit.x + unit.y * unit.y, Rational(1)) << text;
  }
  roundings.clear();
  hipair::Point up = hipair::model_detail::unit_vector(evaluate("90 deg"), "/d", "90 deg", roundings);
  EXPECT_EQ(up, (hipair::Point{Rational(0), Rational(1)}));
  // Multiples of pi are reduced exactly first, however large.
  hipair::Point left = hipair::model_detail::unit_vector(evaluate("1000001 * pi"), "/d", "1000001 pi", roundings);
  EXPECT_EQ(left, (hipair::Point{Rational(-1), Rational(0)}));
  hipair::Point down = hipair::model_detail::unit_vector(evaluate("-(10^30 + 1/2) * pi"), "/d", "big", roundings);
  EXPECT_EQ(down, (hipair::Point{Rational(0), Rational(-1)}));
  EXPECT_TRUE(roundings.empty());
  hipair::Point tilted = hipair::model_detail::unit_vector(evaluate("(10^30 + 1/3) * pi"), "/d", "big", roundings);
  EXPECT_NEAR(hipair::to_double(tilted.x), 0.5, 1e-11);
  EXPECT_NEAR(hipair::to_double(tilted.y), std::sqrt(3.0) / 2, 1e-11);
  EXPECT_THROW(hipair::model_detail::unit_vector(evaluate("10^7"), "/d", "10^7", roundings), hipair::ModelError);
}

// Random expressions built together with their double value: the exact evaluator agrees to
// within the double's own error, so precedence, associativity and functions are right.
struct RandomExpression {
  std::string text;
  double value;
};

RandomExpression random_expression(std::mt19937& engine, int depth) {
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine); };
  if (depth == 0 || pick(4) == 0) {
    int n = pick(9) + 1;
    return {std::to_string(n), double(n)};
  }
  RandomExpression a = random_expression(engine, depth - 1), b = random_expression(engine, depth - 1);
  switch (pick(9)) {
    case 0: return {a.text + " + " + b.text, a.value + b.value};
    case 1: return {a.text + " - (" + b.text + ")", a.value - b.value};
    case 2: return {"(" + a.text + ") * (" + b.text + ")", a.value * b.value};
    case 3: return {"(" + a.text + ") / (" + b.text + ")", b.value == 0 ? a.value : a.value / b.value};
    case 4: return {"sqrt(abs(" + a.text + "))", std::sqrt(std::fabs(a.value))};
    case 5: return {"sin(" + a.text + ")", std::sin(a.value)};
    case 6: return {"atan2(" + a.text + ", " + b.text + ")", std::atan2(a.value, b.value)};
    case 7: return {"max(" + a.text + ", " + b.text + ") - min(" + a.text + ", 2)", std::max(a.value, b.value) - std::min(a.value, 2.0)};
    default: return {"-(" + a.text + ")^2", -a.value * a.value};
  }
}

TEST(Expression, RandomExpressionsAgreeWithDoubleEvaluation) {
  std::mt19937 engine(7);
  int evaluated = 0;
  for (int trial = 0; trial < 400; ++trial) {
    RandomExpression expression = random_expression(engine, 4);
    if (!std::isfinite(expression.value) || std::fabs(expression.value) > 1e6) continue;
    std::vector<hipair::Rounding> roundings;
    Rational value;
    try {
      value = hipair::model_detail::to_rational(evaluate(expression.text), "/e", expression.text, roundings);
    } catch (const hipair::ModelError& error) {
      // Division by an exact zero is the only expected failure (the double path skipped it).
      EXPECT_NE(std::string(error.what()).find("division by zero"), std::string::npos) << expression.text;
      continue;
    }
    ++evaluated;
    EXPECT_NEAR(hipair::to_double(value), expression.value, 1e-9 * (1 + std::fabs(expression.value))) << expression.text;
  }
  EXPECT_GT(evaluated, 200);
}

}  // namespace
