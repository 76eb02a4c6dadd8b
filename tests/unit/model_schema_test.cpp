// docs/model.schema.json stays in step with the reader: it is valid JSON, describes every
// feature template the reader knows with the same arguments, and accepts the key names the
// reader accepts.
#include "model/templates.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>

namespace {

nlohmann::json load_schema() {
  std::ifstream in(std::string(HIPAIR_SOURCE_DIR) + "/docs/model.schema.json");
  return nlohmann::json::parse(in);
}

TEST(ModelSchema, IsDraft2020JsonSchema) {
  nlohmann::json schema = load_schema();
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(schema["additionalProperties"], false);
  std::set<std::string> top;
  for (auto& [key, value] : schema["properties"].items()) top.insert(key);
  EXPECT_EQ(top, (std::set<std::string>{"hipair", "name", "description", "units", "rounding", "parameters", "parts", "pairs", "simulation"}));
}

TEST(ModelSchema, DescribesEveryTemplateWithItsArguments) {
  nlohmann::json schema = load_schema();
  std::map<std::string, nlohmann::json> variants;
  for (const nlohmann::json& variant : schema["$defs"]["feature"]["oneOf"]) {
    std::string name = variant["required"][0];
    variants[name] = variant["properties"][name];
  }
  for (const hipair::model_detail::TemplateSpec& spec : hipair::model_detail::template_specs()) {
    ASSERT_TRUE(variants.count(spec.name)) << "template " << spec.name << " missing from the schema";
    const nlohmann::json& arguments = variants[spec.name];
    std::set<std::string> keys, required, schema_keys, schema_required;
    for (const auto& argument : spec.arguments) {
      keys.insert(argument.key);
      if (argument.required) required.insert(argument.key);
    }
    for (auto& [key, value] : arguments["properties"].items()) schema_keys.insert(key);
    if (arguments.contains("required"))
      for (const auto& key : arguments["required"]) schema_required.insert(key.get<std::string>());
    EXPECT_EQ(keys, schema_keys) << spec.name;
    EXPECT_EQ(required, schema_required) << spec.name;
    variants.erase(spec.name);
  }
  EXPECT_TRUE(variants.empty()) << "the schema lists a template the reader does not know: " << variants.begin()->first;
}

}  // namespace
