// The model reader: JSON text -> exact, validated hipair::Model (docs/model-format.md).
#include "model/reader.hpp"
#include "model/simulation_reading.hpp"

#include "model/exact_trig.hpp"
#include "model/profile_tolerance.hpp"

#include "core/sha256.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace model_detail {

Model Reader::read() {
  std::string hash = detail::sha256_hex(text_);
  JsonValue root = parse_json(text_);
  if (!root.is_object() || !has_profile_tolerances(root)) {
    model_.content_hash = hash;
    return read_root(root);
  }
  // Profile tolerances: read the model without them (orientation, holes, exact corner tests),
  // translate them into offset parameters, read the translated document.
  ReadOptions plain = options_;
  const JsonValue* declared = root.find("parameters");
  std::erase_if(plain.parameter_values,
                [&](const auto& entry) { return !declared || !declared->find(entry.first); });
  Model nominal = Reader(text_, model_.source, plain).read_root(strip_profile_tolerances(root));
  std::vector<ProfileTolerance> tolerances = translate_profile_tolerances(root, nominal);
  Model model = read_root(root);
  model.content_hash = hash;
  model.profile_tolerances = tolerances;
  // The band's extremes must give valid geometry (each offset alone at -t/2 and +t/2).
  for (const ProfileTolerance& tolerance : tolerances) {
    const Parameter* parameter = model.find_parameter(tolerance.parameter);
    for (const Rational& value : {parameter->range.lo, parameter->range.hi}) {
      if (value == parameter->nominal) continue;
      ReadOptions extreme = options_;
      extreme.parameter_values[tolerance.parameter] = value;
      Model offset;
      try {
        offset = Reader(text_, model.source, extreme).read_root(root);
      } catch (const ModelError& error) {
        throw ModelError(tolerance.pointer, "the profile band is too wide: offsetting " + tolerance.loop + " by " +
                                                decimal(value) + " mm makes it invalid (" + error.what() + ")");
      }
      // An offset past a collapse turns the loop inside out, which the reader would silently
      // re-orient: the loop must keep its sense and its hole status.
      for (std::size_t l = 0; l < model.parts[tolerance.part].loops.size(); ++l) {
        const Loop& a = model.parts[tolerance.part].loops[l];
        const Loop& b = offset.parts[tolerance.part].loops[l];
        if (a.pointer != tolerance.loop) continue;
        bool inverted = a.is_hole != b.is_hole || a.edges.size() != b.edges.size() ||
                        a.edges.front().pointer != b.edges.front().pointer || a.edges.front().ccw != b.edges.front().ccw;
        // A segment running against its nominal direction: the offset passed a collapse (a
        // square offset by more than half its side is the same square turned by 180 degrees).
        for (std::size_t e = 0; !inverted && e < a.edges.size(); ++e) {
          const Edge& x = a.edges[e];
          const Edge& y = b.edges[e];
          if (x.is_arc()) {  // an arc whose radius passed zero: its start on the other side of the centre
            inverted = (x.source.x - x.center.x) * (y.source.x - y.center.x) +
                           (x.source.y - x.center.y) * (y.source.y - y.center.y) <= 0;
            continue;
          }
          inverted = (x.target.x - x.source.x) * (y.target.x - y.source.x) +
                         (x.target.y - x.source.y) * (y.target.y - y.source.y) <= 0;
        }
        if (inverted)
          throw ModelError(tolerance.pointer, "the profile band is too wide: offsetting " + tolerance.loop + " by " +
                                                  decimal(value) + " mm turns the loop inside out");
      }
    }
  }
  return model;
}

Model Reader::read_root(const JsonValue& root) {
  if (!root.is_object()) throw ModelError("", "a model file must hold a JSON object");
  check_keys(root, {"hipair", "name", "description", "units", "rounding", "parameters", "parts", "pairs", "simulation"});
  read_version(require(root, "hipair"));
  RoundingBoundScope rounding_scope(read_rounding(root.find("rounding")), rounding_bound_overrides_model());
  model_.name = read_name(require(root, "name"));
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

Rational model_rounding_bound(const JsonValue& root) {
  ReadOptions options;
  return Reader("", "<string>", options).read_rounding(root.is_object() ? root.find("rounding") : nullptr);
}

Rational Reader::read_rounding(const JsonValue* value) {
  auto check = [&](const Rational& bound, const std::string& where, const std::string& what) {
    if (bound < smallest_rounding_bound() || bound > largest_rounding_bound())
      throw ModelError(where, what + " out of range: it must lie in [1e-30, 1e-3]");
  };
  if (rounding_bound_overrides_model()) {  // a command line's --rounding
    check(rounding_bound(), "", "--rounding " + to_decimal_string(rounding_bound(), 12));
    return rounding_bound();
  }
  if (!value) return default_rounding_bound();
  if (!value->is_number()) throw ModelError(value->pointer, "the rounding bound must be a number (e.g. 1e-9)");
  Rational bound = parse_literal(value->text, value->pointer);
  check(bound, value->pointer, "rounding bound " + quoted_excerpt(value->text));
  return bound;
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
      std::string name = read_name(names.items[k]);
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
    SimulatorValues simulator_values(*this);   // friction and restitution are simulator data
    if (const JsonValue* f = value.find("friction")) {
      if (f->is_object()) {
        // {"static": mu_s, "kinetic": mu_k}: both required, 0 <= mu_k <= mu_s
        check_keys(*f, {"static", "kinetic"});
        const JsonValue& s = require(*f, "static");
        const JsonValue& k = require(*f, "kinetic");
        pair.friction = non_negative(s, "static friction");
        pair.kinetic_friction = non_negative(k, "kinetic friction");
        if (*pair.kinetic_friction > *pair.friction)
          throw ModelError(k.pointer, "kinetic friction must not exceed static friction (" +
                                          decimal(*pair.friction) + ")");
      } else {
        pair.friction = non_negative(*f, "friction");
      }
    }
    if (const JsonValue* e = value.find("restitution")) {
      pair.restitution = non_negative(*e, "restitution");
      if (*pair.restitution > 1) throw ModelError(e->pointer, "restitution must lie in [0, 1]");
    }
    model_.pairs.push_back(pair);
  }
}

Model read_model_root(const JsonValue& root, std::string_view source_name, const ReadOptions& options) {
  return Reader("", source_name, options).read_root(root);
}

}  // namespace model_detail

namespace model_detail {

Model read_model_escalating(std::string_view json_text, std::string_view source_name, const ReadOptions& options,
                            mpfr_prec_t* bits_used) {
  // Most models read at the default precision; a value that it cannot decide or round within its
  // bound (a model drawn at 10^100 mm against a 10^-12 mm bound) reads the whole model again at
  // doubled precision, so every value of one model is evaluated at one precision.
  for (mpfr_prec_t bits = std::max(interval_bits, working_interval_bits());; bits *= 2) {
    PrecisionScope precision(bits);
    try {
      Model model = Reader(json_text, source_name, options).read();
      if (bits_used) *bits_used = bits;
      return model;
    } catch (const PrecisionExhausted&) {
      if (2 * bits > most_interval_bits) throw;
    }
  }
}

namespace {
// Set for the duration of one read_model_for_simulation call on this thread (nested Readers of
// the same read see it: profile tolerances, extreme offsets, precision escalation).
thread_local bool simulation_reading = false;

struct SimulationReading {
  bool before = simulation_reading;
  SimulationReading() { simulation_reading = true; }
  ~SimulationReading() { simulation_reading = before; }
  SimulationReading(const SimulationReading&) = delete;
  SimulationReading& operator=(const SimulationReading&) = delete;
};
}  // namespace

bool reading_for_simulation() { return simulation_reading; }

}  // namespace model_detail

Model read_model_for_simulation(std::string_view json_text, std::string_view source_name, const ReadOptions& options) {
  model_detail::SimulationReading scope;
  Model model = read_model(json_text, source_name, options);
  require_internal_units_in_double_range(model);
  return model;
}

Model read_model_file_for_simulation(const std::filesystem::path& path, const ReadOptions& options) {
  model_detail::SimulationReading scope;
  Model model = read_model_file(path, options);
  require_internal_units_in_double_range(model);
  return model;
}

// Each datum times the factor that takes it to the simulator's internal units (s, mN): a rate
// of 1e306 rad/ms is 1e309 rad/s, a torque of 1e306 N mm 1e309 mN mm, beyond the doubles'
// range. Until session 60 (hunt60) such values passed the reader's range check (made in the
// file's units) and the run ended at t = 0 with "moving at inf rad/ms ... not finite" or "the
// loads on the parts ... are not finite" (exit 3, no pointer).
void require_internal_units_in_double_range(const Model& model) {
  if (!model.simulation) return;
  const SimulationSpec& spec = *model.simulation;
  const bool ms = spec.time_unit == "ms", newtons = spec.force_unit != "mN";
  if (!ms && !newtons) return;   // every factor is 1
  static const Rational largest(std::numeric_limits<double>::max());
  const Rational per_time = ms ? Rational(1000) : Rational(1);             // 1 / (s per time unit)
  const Rational force = newtons ? Rational(1000) : Rational(1);           // mN per force unit
  const Rational force_time = ms ? force / Rational(1000) : force;         // force unit x time unit
  auto check = [&](const Rational& value, const Rational& factor, const std::string& pointer, const std::string& unit,
                   const char* internal) {
    if (factor <= 1 || abs(value) * factor <= largest) return;
    std::ostringstream text;
    text << "'" << model_detail::decimal(value) << "' " << unit << " is " << model_detail::decimal(value * factor) << " " << internal
         << " in the simulator's internal units (s, mN), beyond the doubles' range (magnitude at most "
            "1.7976931348623157e+308): give at most "
         << model_detail::decimal(largest / factor) << " " << unit;
    throw ModelError(pointer, text.str());
  };
  const std::string t = spec.time_unit, f = spec.force_unit;
  for (const Part& part : model.parts) {
    if (!part.dynamics) continue;
    const Dynamics& d = *part.dynamics;
    const std::string at = part.pointer + "/dynamics/";
    if (d.torsional_spring) check(d.torsional_spring->stiffness, force, at + "torsional_spring/stiffness", f + " mm/rad", "mN mm/rad");
    if (d.linear_spring) check(d.linear_spring->stiffness, force, at + "linear_spring/stiffness", f + "/mm", "mN/mm");
    if (d.torque) check(*d.torque, force, at + "torque", f + " mm", "mN mm");
    if (d.force) {
      check(d.force->x, force, at + "force/0", f, "mN");
      check(d.force->y, force, at + "force/1", f, "mN");
    }
    if (d.damping) check(*d.damping, force_time, at + "damping", f + " " + t + " per mm or rad", "mN s");
  }
  check(spec.gravity.x, per_time * per_time, spec.pointer + "/gravity/0", "mm/" + t + "^2", "mm/s^2");
  check(spec.gravity.y, per_time * per_time, spec.pointer + "/gravity/1", "mm/" + t + "^2", "mm/s^2");
  // a rate's length or angle: of a rotating part rad, of a translating part mm, else either
  auto rate = [&](std::size_t part) -> std::string {
    const Motion::Kind kind = model.parts.at(part).motion.kind;
    return kind == Motion::Kind::rotation ? "rad" : kind == Motion::Kind::translation ? "mm" : "mm or rad";
  };
  for (const auto& v : spec.velocities)
    check(v.value, per_time, v.pointer, rate(v.part) + "/" + t, (rate(v.part) + "/s").c_str());
  for (const auto& driver : spec.drivers) {
    const std::string unit = rate(driver.part), internal = unit + "/s";
    // (a profile's driver holds its first speed here too: named at the profile)
    check(driver.speed, per_time, driver.pointer + (driver.profile.empty() ? "/speed" : "/profile"), unit + "/" + t,
          internal.c_str());
    for (const auto& point : driver.profile) check(point.second, per_time, driver.pointer + "/profile", unit + "/" + t, internal.c_str());
  }
  for (const auto& coupling : spec.couplings) {
    check(coupling.stiffness, force, coupling.pointer + "/stiffness", f + "/mm", "mN/mm");
    check(coupling.damping, force_time, coupling.pointer + "/damping", f + " " + t + "/mm", "mN s/mm");
  }
}

Model read_model(std::string_view json_text, std::string_view source_name, const ReadOptions& options) {
  return model_detail::read_model_escalating(json_text, source_name, options, nullptr);
}

Model read_model_file(const std::filesystem::path& path, const ReadOptions& options) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError("cannot read model file '" + path.string() + "': it is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + path.string() + "'");
  // read in blocks, at most 256 MiB: a device or pipe without end (/dev/zero) is refused instead
  // of read until memory runs out (session 33: `hipair cspace /dev/zero` hung)
  constexpr std::size_t most_bytes = std::size_t{256} << 20;
  // (the block is not zeroed: filling 1 MiB with zeros was about 1 M instructions, more than a
  // small translating pair's whole C-space build, docs/performance.md session 58; read() writes
  // the gcount() bytes appended)
  std::string content;
  constexpr std::size_t block_size = std::size_t{1} << 20;
  const std::unique_ptr<char[]> block = std::make_unique_for_overwrite<char[]>(block_size);
  while (file) {
    file.read(block.get(), static_cast<std::streamsize>(block_size));
    content.append(block.get(), static_cast<std::size_t>(file.gcount()));
    if (content.size() > most_bytes)
      throw IoError("cannot read model file '" + path.string() + "': it is larger than 256 MiB");
  }
  if (file.bad()) throw IoError("cannot read model file '" + path.string() + "'");
  return read_model(content, path.string(), options);
}

}  // namespace hipair
