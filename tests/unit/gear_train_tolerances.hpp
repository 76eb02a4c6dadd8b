// Gear-train variants (gear_train_models.hpp) for the assembly-chain tests (tolerance_chain_handover_test.cpp,
// tolerance_chain_monte_carlo_test.cpp): a model's tolerances replaced or scaled.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace hipair::test_gears {

/// `text` with every parameter's tolerance replaced: those named in `tolerances` get theirs,
/// the others none.
inline std::string retoleranced(const std::string& text, const std::map<std::string, double>& tolerances) {
  nlohmann::json j = nlohmann::json::parse(text);
  for (auto& [name, body] : j["parameters"].items()) {
    if (!body.contains("tolerance")) continue;
    auto it = tolerances.find(name);
    if (it == tolerances.end())
      body.erase("tolerance");
    else
      body["tolerance"] = it->second;
  }
  return j.dump();
}

/// `text` with every tolerance multiplied by `scale`.
inline std::string scaled(const std::string& text, double scale) {
  nlohmann::json j = nlohmann::json::parse(text);
  for (auto& [name, body] : j["parameters"].items())
    if (body.contains("tolerance")) body["tolerance"] = body["tolerance"].get<double>() * scale;
  return j.dump();
}

/// `text` with each parameter named in `names` negated: its nominal value is the old one's
/// negative and every feature value naming it names its negative instead (the same mechanism; a
/// symmetric tolerance box, its halves along those parameters swapped).
inline std::string mirrored(const std::string& text, const std::vector<std::string>& names) {
  nlohmann::json j = nlohmann::json::parse(text);
  for (const std::string& name : names) {
    nlohmann::json& nominal = j["parameters"][name]["nominal"];
    nominal = nominal.is_number() ? nlohmann::json(-nominal.get<double>()) : nlohmann::json("-" + nominal.get<std::string>());
    for (auto& part : j["parts"])
      for (auto& feature : part["features"])
        for (auto& [kind, body] : feature.items())
          for (auto& [key, value] : body.items())
            if (value.is_string() && value.get<std::string>() == name) value = "-" + name;
  }
  return j.dump();
}

/// gear_train(2) with gear A's flank profile toleranced wide (pitch radius +-0.05 mm, flank
/// radius +-0.2 mm, pressure angle +-0.02 rad) and nothing else: a tooth hand-over near driver
/// 0.18 rad moves inside the box (tolerance_chain_handover_test.cpp).
inline std::string handover_model(const std::string& gear_train_2) {
  return retoleranced(gear_train_2, {{"A-pitch-radius", 0.05}, {"A-flank-radius", 0.2}, {"A-pressure-angle", 0.02}});
}

}  // namespace hipair::test_gears
