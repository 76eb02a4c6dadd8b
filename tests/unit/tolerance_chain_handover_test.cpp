// exploration
#include "gear_train_models.hpp"
#include "tolerance_chain_oracle.hpp"

#include "model/parametric/parametric.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

namespace hipair {
namespace {

std::string wide_runout(std::string text, const std::string& tolerance) {
  for (const char* axis : {"x", "y"}) {
    std::string from = std::string("runout-") + axis + "\": {\"nominal\": 0, \"tolerance\": 0.005";
    std::string to = std::string("runout-") + axis + "\": {\"nominal\": 0, \"tolerance\": " + tolerance;
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  return text;
}

std::string retoleranced(const std::string& text, const std::map<std::string, double>& tolerances) {
  nlohmann::json j = nlohmann::json::parse(text);
  for (auto& [name, body] : j["parameters"].items()) {
    if (!body.contains("tolerance")) continue;
    auto it = tolerances.find(name);
    if (it == tolerances.end()) body.erase("tolerance");
    else body["tolerance"] = it->second;
  }
  return j.dump();
}

TEST(ToleranceChainHandover, Explore) {
  std::string text = retoleranced(test_gears::gear_train(2), {{"A-pitch-radius", 0.05}, {"A-flank-radius", 0.2}, {"A-pressure-angle", 0.02}});
  ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = std::make_pair(Rational(16, 100), Rational(19, 100));
  options.positions = 2000;
  options.threads = 2;
  ToleranceResult result = analyze_tolerances_text(text, options);
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  for (const std::string& n : result.notes) std::cout << "note " << n << "\n";
  for (const VariationSample& s : result.samples)
    std::cout << s.driver << " " << s.contact << " " << s.nominal << " [" << s.certified.lower << ", " << s.certified.upper
              << "] region " << s.region << "\n";
  std::size_t k0 = 0;
  while (result.samples[k0 + 1].region == result.samples[0].region) ++k0;
  const std::size_t k1 = k0 + 1;   // the last position of region 0, the first of region 1
  for (std::size_t i = 0; i < result.parameters.size(); ++i) {
    const Parameter& p = result.parameters[i];
    double w = Rational(p.range.hi - p.range.lo).get_d() / 2;
    std::cout << "sens " << p.name << " " << result.samples[k0].sensitivities[i] * w << " " << result.samples[k1].sensitivities[i] * w << "\n";
  }
  for (auto [k, from] : {std::pair{k0, k1}, std::pair{k1, k0}, std::pair{k0 - 1, k1}, std::pair{k1 + 1, k0}}) {
    const VariationSample& s = result.samples[k];
    std::vector<Rational> d(result.parameters.size(), Rational(0));
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Parameter& p = result.parameters[i];
      double si = result.samples[from].sensitivities[i];
      if (si != 0) d[i] = (si > 0 ? p.range.lo : p.range.hi) - p.nominal;
    }
    double out = test_chain::chain_output(model->exact_model(d), "gear-A", s.driver, "gear-B");
    std::cout << "pos " << s.driver << " exact " << out << " band [" << s.certified.lower << ", " << s.certified.upper << "]\n";
  }
  for (const auto& r : result.regions) std::cout << "region " << r.contact << " " << r.driver_start << " .. " << r.driver_end << "\n";
}

}  // namespace
}  // namespace hipair
