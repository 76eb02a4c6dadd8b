// Integer exponents of the parametric formulas are the exact evaluator's integers
// (src/model/parametric/formula.cpp): an exponent written as an expression whose double
// evaluation loses the integer (10^20 + e - 10^20 is 0 in double for |e| < 8 193) must still
// give e. Generated cases against the closed form; a non-integer exponent is refused.
#include "model/parametric/formula.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace hipair {
namespace {

std::size_t no_parameters(const std::string& name) { throw ModelError("/p", "unknown parameter '" + name + "'"); }

TEST(ParametricFormulaExponent, ExponentsAreExactIntegers) {
  std::mt19937_64 random(5);
  std::uniform_int_distribution<int> small(-6, 6), big(15, 30), base_numerator(1, 9);
  for (int trial = 0; trial < 300; ++trial) {
    int e = small(random), k = big(random), a = base_numerator(random);
    std::string text = "(" + std::to_string(a) + "/3)^((10^" + std::to_string(k) + " + (" + std::to_string(e) +
                       ")) - 10^" + std::to_string(k) + ")";
    model_detail::FormulaPtr f = model_detail::parse_formula(text, "/p", no_parameters);
    ASSERT_EQ(f->op, model_detail::Formula::Op::power) << text;
    ASSERT_EQ(f->exponent, e) << text;
    // And the value: (a/3)^e, against the closed form in double (relative error of e products).
    double value = model_detail::evaluate_formula<double>(*f, [](std::size_t) { return 0.0; });
    EXPECT_NEAR(value, std::pow(a / 3.0, e), 1e-14 * (1 + std::abs(e)) * std::pow(a / 3.0, e)) << text;
  }
  // An exponent with pi that cancels exactly.
  EXPECT_EQ(model_detail::parse_formula("2^(3*pi/pi)", "/p", no_parameters)->exponent, 3);
}

TEST(ParametricFormulaExponent, NonIntegerExponentIsRefused) {
  EXPECT_THROW(model_detail::parse_formula("2^(1/2)", "/p", no_parameters), ModelError);
  EXPECT_THROW(model_detail::parse_formula("2^(10^20 + 1/2 - 10^20)", "/p", no_parameters), ModelError);
}

}  // namespace
}  // namespace hipair
