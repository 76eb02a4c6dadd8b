// The parametric formulas read angles as the exact reader does (session 51, exact51). In a
// degree file a plain value used as an angle inside an expression is in degrees: `5 + atan2(p,
// -1)` is 5° plus an angle, `sin(p)` is the sine of p degrees (docs/model-format.md "Angles").
// The tolerance analysis evaluates the parametric form of each derived parameter (its formula
// over the parameters, as intervals, jets and Taylor models); until session 51 that form
// converted only a whole slot, so such an expression was read as radians there: the certified
// band was computed for another model than the one read (cam-follower.json with eccentricity
// `5 + atan2(skew, -1)/100`: follower at 0.12 mm, certified band at 4.95 mm).
// Generated expressions over a plain parameter p, an angle parameter a and literals, in deg and
// rad files; oracle: the reader's exact value of the derived parameter (its rational nominal,
// within 10^-9 relative for the recorded roundings), which must meet the parametric form's
// interval value.
#include "kernels/interval.hpp"
#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>

namespace hipair {
namespace {

std::string cam_follower() {
  std::ifstream file(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples" / "models" / "cam-follower.json");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A random expression over p (plain), a (an angle) and small literals, mixing angles and plain
// values the ways the grammar allows.
std::string random_expression(std::mt19937& random, int depth) {
  auto pick = [&](int n) { return int(random() % unsigned(n)); };
  if (depth == 0) {
    switch (pick(6)) {
      case 0: return "p";
      case 1: return "a";
      case 2: return std::to_string(1 + pick(9));
      case 3: return std::to_string(1 + pick(40)) + " deg";
      case 4: return "atan2(p, -" + std::to_string(1 + pick(5)) + ")";
      default: return std::to_string(1 + pick(9)) + "/" + std::to_string(2 + pick(7));
    }
  }
  std::string x = random_expression(random, depth - 1), y = random_expression(random, depth - 1);
  switch (pick(8)) {
    case 0: return "(" + x + " + " + y + ")";
    case 1: return "(" + x + " - " + y + ")";
    case 2: return "(" + x + " * " + y + ")";
    case 3: return "sin(" + x + ")";
    case 4: return "cos(" + x + ")";
    case 5: return "min(" + x + ", " + y + ")";
    case 6: return "abs(" + x + ")";
    default: return "(" + x + ")^" + std::to_string(1 + pick(2));
  }
}

TEST(ParametricFormulaUnits, DerivedParametersAreTheReadersValues) {
  const std::string base = cam_follower();
  ASSERT_FALSE(base.empty());
  std::mt19937 random(51);
  int checked = 0, mixed = 0;
  for (int trial = 0; trial < 160; ++trial) {
    bool degrees = trial % 4 != 3;
    std::string expression = random_expression(random, 1 + int(random() % 3));
    std::string text = base;
    // parameters p (plain, toleranced), a (an angle) and x = the expression (derived from p)
    std::string added = "\"p\": { \"nominal\": \"" + std::to_string(1 + random() % 9) + "/" + std::to_string(3 + random() % 5) +
                        "\", \"tolerance\": 0.01 }, \"a\": { \"nominal\": \"" + std::to_string(5 + random() % 60) +
                        " deg\", \"tolerance\": 0.001 }, \"x\": { \"nominal\": \"p * 0 + " + expression + "\" }, ";
    text.replace(text.find("\"parameters\": {") + 15, 0, added);
    if (!degrees) text.replace(text.find("\"angle\": \"deg\""), 14, "\"angle\": \"rad\"");
    SCOPED_TRACE(std::string(degrees ? "deg" : "rad") + " file, x = " + expression);
    std::optional<model_detail::ParametricModel> model;
    try {
      model = model_detail::ParametricModel::read(text);
    } catch (const Error&) {
      continue;   // refused by the reader (an ambiguous angle, a division by zero, ...)
    }
    const Model& nominal = model->nominal();
    std::size_t x = std::size_t(nominal.find_parameter("x") - nominal.parameters.data());
    std::vector<kernels::Interval> zero(model->parameter_count(), kernels::Interval(0));
    kernels::Interval value = model->parameter_values<kernels::Interval>(zero)[x];
    // the reader's value: its rational nominal, within the rounding bounds it recorded (x's own,
    // and a's: the parametric form starts from a's rounded nominal, the reader from a's exact
    // value), taken as 10^-9 (1 + |x|): the defect is a factor pi/180 on a term, far larger
    const Rational& exact = nominal.parameters[x].nominal;
    Rational bound = Rational(1, 1000000000) * (1 + abs(exact));
    for (const Rounding& rounding : nominal.roundings)
      if (rounding.bound > Rational(1, 1000000000)) ADD_FAILURE() << "a rounding bound beyond the slack: " << rounding.pointer;
    bool inside = !(Rational(value.hi) < exact - bound) && !(Rational(value.lo) > exact + bound);
    EXPECT_TRUE(inside) << "reader " << exact.get_d() << ", parametric form [" << value.lo << ", " << value.hi << "]";
    ++checked;
    mixed += degrees && expression.find("atan2") != std::string::npos;
  }
  EXPECT_GE(checked, 100);
  EXPECT_GE(mixed, 20);
}

}  // namespace
}  // namespace hipair
