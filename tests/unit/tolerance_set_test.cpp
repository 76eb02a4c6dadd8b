// Tolerance analysis of a changed design (ToleranceOptions::parameter_values, `hipair tolerance
// --set NAME=VALUE`): the override replaces the parameter's nominal value and its tolerance
// moves with it (a `range` stays). Oracle: the same analysis of the model file with that
// nominal written into it — the variation and sensitivity tables, the parameters' nominals and
// ranges and the contact regions must be identical, on generated overrides of every kind of
// parameter (lengths, angles in a radian file, an angle in a degree file, asymmetric
// tolerances), for a single pair and an assembly chain. Values outside the tolerance are
// refused unless allowed; certificates are refused with overrides.
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>

namespace hipair {
namespace {

std::string example(const std::string& name) {
  std::ifstream file(std::string(HIPAIR_EXAMPLES) + "/" + name);
  EXPECT_TRUE(file.good()) << name;
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The model text with parameter `name`'s nominal written as `value` (an exact literal string,
// " rad" appended for an angle).
std::string with_nominal(const std::string& text, const std::string& name, const std::string& value) {
  std::regex nominal("(\"" + name + "\"\\s*:\\s*\\{\\s*\"nominal\"\\s*:\\s*)([^,}\\n]+)");
  std::smatch match;
  EXPECT_TRUE(std::regex_search(text, match, nominal)) << name;
  return std::regex_replace(text, nominal, "$1\"" + value + "\"", std::regex_constants::format_first_only);
}

void expect_same_analysis(const ToleranceResult& overridden, const ToleranceResult& rewritten) {
  EXPECT_EQ(tolerance_csv(overridden), tolerance_csv(rewritten));
  EXPECT_EQ(tolerance_sensitivity_csv(overridden), tolerance_sensitivity_csv(rewritten));
  ASSERT_EQ(overridden.parameters.size(), rewritten.parameters.size());
  for (std::size_t i = 0; i < overridden.parameters.size(); ++i) {
    EXPECT_EQ(overridden.parameters[i].nominal, rewritten.parameters[i].nominal) << overridden.parameters[i].name;
    EXPECT_EQ(overridden.parameters[i].range.lo, rewritten.parameters[i].range.lo) << overridden.parameters[i].name;
    EXPECT_EQ(overridden.parameters[i].range.hi, rewritten.parameters[i].range.hi) << overridden.parameters[i].name;
  }
  EXPECT_EQ(overridden.regions.size(), rewritten.regions.size());
  EXPECT_EQ(overridden.samples.size(), rewritten.samples.size());
}

struct Case {
  std::string model;
  ToleranceOptions options;
};

TEST(ToleranceSet, AnOverrideIsTheSameAnalysisAsTheNominalWrittenIntoTheModel) {
  std::mt19937 random(19);
  std::vector<Case> cases;
  {
    Case geneva{"geneva.json", {}};
    geneva.options.range = std::make_pair(Rational(2), Rational(5, 2));
    geneva.options.positions = 240;
    geneva.options.threads = 2;
    cases.push_back(geneva);
    Case lever{"cam-follower-lever.json", {}};
    lever.options.driver = "cam";
    lever.options.chain = true;
    lever.options.positions = 48;
    lever.options.threads = 2;
    cases.push_back(lever);
  }
  int checked = 0;
  for (const Case& c : cases) {
    std::string text = example(c.model);
    Model model = read_model(text, c.model);
    std::vector<const Parameter*> toleranced;
    for (const Parameter& parameter : model.parameters)
      if (parameter.range.lo < parameter.range.hi) toleranced.push_back(&parameter);
    ASSERT_GE(toleranced.size(), 3u) << c.model;
    for (int round = 0; round < 4; ++round) {
      const Parameter& parameter = *toleranced[random() % toleranced.size()];
      // A rational point of the tolerance range: lo + k/8 (hi - lo).
      Rational value = parameter.range.lo + Rational(static_cast<long>(random() % 9), 8) * (parameter.range.hi - parameter.range.lo);
      value.canonicalize();
      SCOPED_TRACE(c.model + ": " + parameter.name + " = " + value.get_str());
      ToleranceOptions options = c.options;
      options.parameter_values[parameter.name] = value;
      ToleranceResult overridden = analyze_tolerances_text(text, options);
      std::string rewritten_text =
          with_nominal(text, parameter.name, value.get_str() + (parameter.is_angle ? " rad" : ""));
      ToleranceResult rewritten = analyze_tolerances_text(rewritten_text, c.options);
      expect_same_analysis(overridden, rewritten);
      // The tolerance moved with the nominal.
      const Parameter* moved = nullptr;
      for (const Parameter& p : overridden.parameters)
        if (p.name == parameter.name) moved = &p;
      ASSERT_NE(moved, nullptr);
      EXPECT_EQ(moved->nominal, value);
      EXPECT_EQ(Rational(moved->range.hi - moved->range.lo), Rational(parameter.range.hi - parameter.range.lo));
      EXPECT_EQ(Rational(moved->range.lo - moved->nominal), Rational(parameter.range.lo - parameter.nominal));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);
}

TEST(ToleranceSet, AnAngleInADegreeFileIsGivenInRadians) {
  // cam-follower-lever.json is a degree file; lever-lower-limit is an angle parameter (deg).
  std::string text = example("cam-follower-lever.json");
  ToleranceOptions options;
  options.driver = "cam";
  options.chain = true;
  options.positions = 48;
  options.threads = 2;
  options.allow_out_of_tolerance = true;   // the limit is untoleranced: any change is outside
  Rational value(-1, 2);                   // rad, about -28.6 deg
  options.parameter_values["lever-lower-limit"] = value;
  ToleranceResult overridden = analyze_tolerances_text(text, options);
  ToleranceOptions plain = options;
  plain.parameter_values.clear();
  ToleranceResult rewritten = analyze_tolerances_text(with_nominal(text, "lever-lower-limit", "-1/2 rad"), plain);
  expect_same_analysis(overridden, rewritten);
  for (const Parameter& p : overridden.parameters)
    if (p.name == "lever-lower-limit") EXPECT_EQ(p.nominal, value);
}

TEST(ToleranceSet, OutOfToleranceUnknownNamesAndCertificatesAreRefused) {
  std::string text = example("geneva.json");
  ToleranceOptions options;
  options.range = std::make_pair(Rational(2), Rational(5, 2));
  options.positions = 120;
  options.threads = 2;
  options.parameter_values["pin-radius"] = Rational(23, 5);   // 4.6, outside 4.5 +- 0.02
  try {
    analyze_tolerances_text(text, options);
    ADD_FAILURE() << "an override outside the tolerance was accepted";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find("pin-radius"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("outside its tolerance range"), std::string::npos) << error.what();
  }
  options.allow_out_of_tolerance = true;
  ToleranceResult allowed = analyze_tolerances_text(text, options);
  for (const Parameter& p : allowed.parameters)
    if (p.name == "pin-radius") {
      EXPECT_EQ(p.nominal, Rational(23, 5));
      EXPECT_EQ(p.range.lo, Rational(229, 50));
      EXPECT_EQ(p.range.hi, Rational(231, 50));
    }
  ToleranceOptions unknown = options;
  unknown.parameter_values = {{"no-such-parameter", Rational(1)}};
  EXPECT_THROW(analyze_tolerances_text(text, unknown), ModelError);
  ToleranceOptions certify = options;
  certify.parameter_values = {{"pin-radius", Rational(4501, 1000)}};
  certify.certify = true;
  try {
    analyze_tolerances_text(text, certify);
    ADD_FAILURE() << "a certificate was produced for an overridden design";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find("certificates"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace hipair
