// The model reader: JSON text -> exact, validated hipair::Model (docs/model-format.md).
#include "model/reader.hpp"

#include "core/sha256.hpp"

#include <hipair/error.hpp>

#include <fstream>
#include <sstream>

namespace hipair {
namespace model_detail {

Model Reader::read() {
  model_.content_hash = detail::sha256_hex(text_);
  JsonValue root = parse_json(text_);
  if (!root.is_object()) throw ModelError("", "a model file must hold a JSON object");
  check_keys(root, {"hipair", "name", "description", "units", "parameters", "parts", "pairs", "simulation"});
  read_version(require(root, "hipair"));
  model_.name = read_string(require(root, "name"), false);
  if (const JsonValue* description = root.find("description"))
    model_.description = read_string(*description, true, true);
  read_units(root.find("units"));
  read_parameters(root.find("parameters"));
  read_parts(require(root, "parts"));
  read_pairs(root.find("pairs"));
  read_simulation(root.find("simulation"));
  return std::move(model_);
}

void Reader::read_version(const JsonValue& value) {
  bool one = false;
  if (value.is_number()) {
    try {
      one = parse_rational(value.text) == 1;
    } catch (const NumericError&) {
    }
  }
  if (!one)
    throw ModelError(value.pointer, "unsupported format version " +
                                        (value.is_number() || value.is_string() ? quoted_excerpt(value.text)
                                                                                : std::string(describe_type(value.type))) +
                                        ": this reader reads \"hipair\": 1");
}

void Reader::read_units(const JsonValue* units) {
  model_.angle_unit = "rad";
  if (!units) return;
  expect_object(*units);
  check_keys(*units, {"length", "angle"});
  if (const JsonValue* length = units->find("length")) {
    std::string unit = read_string(*length, false);
    if (unit != "mm") throw ModelError(length->pointer, "unsupported length unit '" + unit + "' (only \"mm\")");
  }
  if (const JsonValue* angle_unit = units->find("angle")) {
    std::string unit = read_string(*angle_unit, false);
    if (unit != "rad" && unit != "deg")
      throw ModelError(angle_unit->pointer, "unsupported angle unit '" + unit + "' (\"rad\" or \"deg\")");
    model_.angle_unit = unit;
    degrees_ = unit == "deg";
  }
}

void Reader::read_pairs(const JsonValue* pairs) {
  if (!pairs) {
    for (std::size_t i = 0; i < model_.parts.size(); ++i)
      for (std::size_t j = i + 1; j < model_.parts.size(); ++j) {
        if (model_.parts[i].motion.kind == Motion::Kind::fixed &&
            model_.parts[j].motion.kind == Motion::Kind::fixed)
          continue;
        PairSpec pair;
        pair.first = i;
        pair.second = j;
        pair.pointer = "/parts";
        model_.pairs.push_back(pair);
      }
    return;
  }
  model_.pairs_explicit = true;
  expect_array(*pairs, "an array of pairs");
  std::map<std::pair<std::size_t, std::size_t>, std::string> seen;
  for (const JsonValue& value : pairs->items) {
    expect_object(value, "a pair object {\"parts\": [a, b]}");
    check_keys(value, {"parts", "friction", "restitution"});
    const JsonValue& names = expect_array(require(value, "parts"), "two part names [a, b]");
    if (names.items.size() != 2)
      throw ModelError(names.pointer, "a pair names exactly 2 parts, found " + std::to_string(names.items.size()));
    PairSpec pair;
    pair.pointer = value.pointer;
    std::size_t indices[2];
    for (int k = 0; k < 2; ++k) {
      std::string name = read_string(names.items[k], false);
      auto index = model_.find_part(name);
      if (!index) throw ModelError(names.items[k].pointer, "unknown part '" + name + "'");
      indices[k] = *index;
    }
    if (indices[0] == indices[1])
      throw ModelError(names.pointer, "a part cannot be paired with itself ('" +
                                          model_.parts[indices[0]].name + "')");
    pair.first = indices[0];
    pair.second = indices[1];
    auto key = std::minmax(indices[0], indices[1]);
    if (auto [where, inserted] = seen.emplace(key, value.pointer); !inserted)
      throw ModelError(value.pointer, "duplicate pair (also " + where->second + ")");
    if (const JsonValue* f = value.find("friction")) pair.friction = non_negative(*f, "friction");
    if (const JsonValue* e = value.find("restitution")) {
      pair.restitution = non_negative(*e, "restitution");
      if (*pair.restitution > 1) throw ModelError(e->pointer, "restitution must lie in [0, 1]");
    }
    model_.pairs.push_back(pair);
  }
}

}  // namespace model_detail

Model read_model(std::string_view json_text, std::string_view source_name, const ReadOptions& options) {
  return model_detail::Reader(json_text, source_name, options).read();
}

Model read_model_file(const std::filesystem::path& path, const ReadOptions& options) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError("cannot read model file '" + path.string() + "': it is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + path.string() + "'");
  std::ostringstream content;
  content << file.rdbuf();
  if (file.bad()) throw IoError("cannot read model file '" + path.string() + "'");
  return read_model(content.str(), path.string(), options);
}

}  // namespace hipair
