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
                                          decimal(*pair.friction) + " at " + s.pointer + ")");
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

namespace model_detail {
namespace {

Rational l1(const Rational& x, const Rational& y) { return abs(x) + abs(y); }

using Terms = std::vector<std::pair<Rational, std::string>>;

// A bound (the 1-norm, mm) on the world coordinates of point p (world coordinates at the part's
// zero configuration, given at `point_at`) of `part` at its start, in any turn of the part (the
// 1-norm of a vector turned grows by at most a factor sqrt(2) < 2): the sum of `terms`, each with
// the pointer of its datum.
Rational start_reach(const Part& part, const Point& p, const std::string& point_at, Terms& terms) {
  const Motion& m = part.motion;
  const Rational arm = l1(p.x - m.pivot.x, p.y - m.pivot.y);
  const std::string initial = part.pointer + "/initial/";
  Terms own;
  switch (m.kind) {
    case Motion::Kind::fixed: own = {{l1(p.x, p.y), point_at}}; break;
    case Motion::Kind::rotation: own = {{l1(m.pivot.x, m.pivot.y), m.pointer}, {2 * arm, point_at}}; break;
    case Motion::Kind::translation: own = {{l1(p.x, p.y), point_at}, {2 * abs(part.initial.offset), initial + "offset"}}; break;
    case Motion::Kind::planar:
      own = {{l1(m.pivot.x, m.pivot.y), m.pointer}, {2 * arm, point_at}, {abs(part.initial.x), initial + "x"},
             {abs(part.initial.y), initial + "y"}};
      break;
    case Motion::Kind::pin_slot:
      own = {{l1(m.pivot.x, m.pivot.y), m.pointer}, {2 * arm, point_at}, {2 * abs(part.initial.offset), initial + "offset"}};
      break;
  }
  Rational total(0);
  for (auto& term : own) {
    total += term.first;
    terms.push_back(std::move(term));
  }
  return total;
}

// the lever (mm) of a force at p about the part's pivot, bounded by the 1-norm (a turn keeps the
// arm's length): 0 for a fixed or translating part
Rational lever(const Part& part, const Point& p) {
  const Motion& m = part.motion;
  if (m.kind == Motion::Kind::fixed || m.kind == Motion::Kind::translation) return Rational(0);
  Rational arm = l1(p.x - m.pivot.x, p.y - m.pivot.y);
  if (m.kind == Motion::Kind::pin_slot) arm += abs(part.initial.offset);
  return arm;
}

// the pointer of the largest of `terms` (value, pointer): the datum that takes a product beyond
// the doubles' range
std::string largest_term(const Terms& terms) {
  const std::pair<Rational, std::string>* best = nullptr;
  for (const auto& term : terms)
    if (!best || abs(term.first) > abs(best->first)) best = &term;
  return best->second;
}

const char* const beyond_loads =
    ", beyond the range of doubles the simulator computes its loads in (magnitude at most 1.7976931348623157e+308)";

// The loads the data makes at the start, in the simulator's internal units (s, mN): each datum
// lies within the doubles' range, but the simulator forms products of them in doubles. Until
// session 61 (hunt61) a spring's attachment point or rest length near 1.8e308 mm, a part's spring
// rest of 1.8e308, or a mass of 1.8e308 kg under gravity ran to "the loads on the parts ... are
// not finite" or "the simulated configuration of a planar part is not finite" at t = 0 (exit 3,
// without a pointer). Bounds (exact, from the data, in 1-norms): a spring's stretch
// |L - rest| <= L + rest with L at most the sum of its two points' reaches; its force k (L +
// rest) and the moment of that force about a pivot; a part's own spring k (|q| + |rest|) at its
// initial coordinate or the farthest motion limit; a part's weight and constant force m |g| + |F|
// and their moment about its pivot. A product beyond DBL_MAX is refused at the pointer of its
// largest factor.
void require_start_loads_in_double_range(const Model& model, const Rational& force, const Rational& per_time) {
  const SimulationSpec& spec = *model.simulation;
  static const Rational largest(std::numeric_limits<double>::max());
  // an initial coordinate beyond the doubles is every simulator's own refusal, at its pointer
  // (check_simulator_range: "too large for the simulator, which holds coordinates in doubles")
  for (const Part& part : model.parts)
    if (part.motion.kind != Motion::Kind::fixed)
      for (const Rational* value : {&part.initial.angle, &part.initial.offset, &part.initial.x, &part.initial.y})
        if (abs(*value) > largest) return;
  for (const auto& c : spec.couplings) {
    const Part& a = model.parts.at(c.first);
    const Part& b = model.parts.at(c.second);
    Terms terms;
    const Rational reach_a = start_reach(a, c.first_point, c.pointer + "/points/0", terms);
    const Rational reach_b = start_reach(b, c.second_point, c.pointer + "/points/1", terms);
    const Rational stretch = reach_a + reach_b + c.rest_length;
    const Rational k = c.stiffness * force;
    const Rational arm = std::max({Rational(1), lever(a, c.first_point), lever(b, c.second_point)});
    const Rational moment = k * stretch * arm;
    // the energy it stores, k stretch^2 / 2 (mN mm; published by every simulator: until session
    // 62 a stretch far below the force bound's, e.g. a rest length of 1e154 mm on 0.05 N/mm, made
    // it infinite in `simulate`'s summary)
    const Rational energy = k * stretch * stretch / 2;
    if (stretch <= largest && moment <= largest && energy <= largest) continue;
    terms.emplace_back(k, c.pointer + "/stiffness");
    terms.emplace_back(lever(a, c.first_point), c.pointer + "/points/0");
    terms.emplace_back(lever(b, c.second_point), c.pointer + "/points/1");
    terms.emplace_back(c.rest_length, c.pointer + "/rest_length");
    const std::string at = largest_term(terms);
    std::ostringstream text;
    text << "the spring between parts '" << a.name << "' and '" << b.name << "': ";
    if (stretch > largest)
      text << "its attachment points up to " << decimal(reach_a + reach_b) << " mm apart at the start and its rest length "
           << decimal(c.rest_length) << " mm make a stretch of up to " << decimal(stretch) << " mm";
    else if (moment <= largest)
      text << "its stiffness " << decimal(k) << " mN/mm and its stretch (attachment points up to "
           << decimal(reach_a + reach_b) << " mm apart at the start, rest length " << decimal(c.rest_length)
           << " mm) store an energy k stretch^2 / 2 of up to " << decimal(energy) << " mN mm";
    else
      text << "its stiffness " << decimal(k) << " mN/mm times its stretch (attachment points up to "
           << decimal(reach_a + reach_b) << " mm apart at the start, rest length " << decimal(c.rest_length)
           << " mm) and a lever of up to " << decimal(arm) << " mm make a force or moment of up to " << decimal(moment)
           << " mN or mN mm";
    text << beyond_loads;
    throw ModelError(at, text.str());
  }
  const Rational g = l1(spec.gravity.x, spec.gravity.y) * per_time * per_time;   // mm/s^2
  for (const Part& part : model.parts) {
    if (!part.dynamics || part.motion.kind == Motion::Kind::fixed) continue;
    const Dynamics& d = *part.dynamics;
    const std::string at = part.pointer + "/dynamics/";
    // a part's own spring: k (q - rest) at the initial coordinate or a motion limit
    auto own = [&](const std::optional<Spring>& spring, const char* key, const char* words, const Rational& start,
                   const char* coordinate, const std::optional<RationalInterval>& limits, const char* unit,
                   const char* load_unit) {
      if (!spring) return;
      Rational q = abs(start);
      std::string q_at = part.pointer + "/initial/" + coordinate;
      if (limits && std::max<Rational>(abs(limits->lo), abs(limits->hi)) > q) {
        q = std::max<Rational>(abs(limits->lo), abs(limits->hi));
        q_at = part.motion.pointer;
      }
      const Rational k = spring->stiffness * force, stretch = q + abs(spring->rest), load = k * stretch;
      const Rational energy = load * stretch / 2;   // k stretch^2 / 2, the energy it stores (session 62)
      if (stretch <= largest && load <= largest && energy <= largest) return;
      std::ostringstream text;
      text << "the " << words << " of part '" << part.name << "': its stiffness " << decimal(k) << " " << load_unit
           << " per " << unit << " times its stretch |" << coordinate << " - rest| (rest " << decimal(spring->rest) << " "
           << unit << ", " << coordinate << " up to " << decimal(q) << " " << unit << ") makes ";
      if (stretch <= largest && load <= largest)
        text << "a load of " << decimal(load) << " " << load_unit << " but stores an energy k stretch^2 / 2 of up to "
             << decimal(energy) << " mN mm";
      else
        text << "a load of up to " << decimal(load) << " " << load_unit;
      text << beyond_loads;
      throw ModelError(largest_term(Terms{{k, at + key + "/stiffness"}, {spring->rest, at + key + "/rest"}, {q, q_at}}),
                       text.str());
    };
    own(d.torsional_spring, "torsional_spring", "torsional spring", part.initial.angle, "angle", part.motion.angle_limits,
        "rad", "mN mm");
    own(d.linear_spring, "linear_spring", "linear spring", part.initial.offset, "offset", part.motion.translation_limits,
        "mm", "mN");
    // weight and constant force, and their moment about the pivot at the centre of mass
    if (!d.mass) continue;
    const Rational m = abs(*d.mass), f = d.force ? l1(d.force->x, d.force->y) * force : Rational(0);
    const Rational load = m * g + f;
    Rational arm(1);
    for (const auto& c : spec.centers_of_mass)
      if (&model.parts.at(c.part) == &part) arm = std::max<Rational>(arm, l1(c.at.x - part.motion.pivot.x, c.at.y - part.motion.pivot.y));
    if (load * arm <= largest) continue;
    std::ostringstream text;
    text << "the weight and force on part '" << part.name << "': mass " << decimal(m) << " kg times gravity up to "
         << decimal(g) << " mm/s^2 plus a force up to " << decimal(f) << " mN, on a lever of up to " << decimal(arm)
         << " mm, make a load of up to " << decimal(load * arm) << " mN or mN mm" << beyond_loads;
    throw ModelError(largest_term(Terms{{m, at + "mass"}, {g, spec.pointer + "/gravity"}, {f, at + "force"}}), text.str());
  }
}

}  // namespace
}  // namespace model_detail

// Each datum times the factor that takes it to the simulator's internal units (s, mN): a rate
// of 1e306 rad/ms is 1e309 rad/s, a torque of 1e306 N mm 1e309 mN mm, beyond the doubles'
// range. Until session 60 (hunt60) such values passed the reader's range check (made in the
// file's units) and the run ended at t = 0 with "moving at inf rad/ms ... not finite" or "the
// loads on the parts ... are not finite" (exit 3, no pointer).
static void require_factors_in_double_range(const Model& model, const Rational& force, const Rational& per_time);

void require_internal_units_in_double_range(const Model& model) {
  if (!model.simulation) return;
  const SimulationSpec& spec = *model.simulation;
  const bool ms = spec.time_unit == "ms", newtons = spec.force_unit != "mN";
  const Rational per_time = ms ? Rational(1000) : Rational(1);             // 1 / (s per time unit)
  const Rational force = newtons ? Rational(1000) : Rational(1);           // mN per force unit
  if (ms || newtons) require_factors_in_double_range(model, force, per_time);   // else every factor is 1
  // the loads the data makes at the start, whatever the units (session 61), once each datum is
  // known to lie in the doubles' range in the simulator's units
  model_detail::require_start_loads_in_double_range(model, force, per_time);
}

// (each datum times its factor, require_internal_units_in_double_range)
static void require_factors_in_double_range(const Model& model, const Rational& force, const Rational& per_time) {
  const SimulationSpec& spec = *model.simulation;
  const bool ms = spec.time_unit == "ms";
  static const Rational largest(std::numeric_limits<double>::max());
  static const Rational smallest(std::numeric_limits<double>::min());
  const Rational force_time = ms ? force / Rational(1000) : force;         // force unit x time unit
  auto check = [&](const Rational& value, const Rational& factor, const std::string& pointer, const std::string& unit,
                   const char* internal) {
    // A factor below 1 (a damping in mN ms: x 1/1000) takes a value of the doubles' normal range
    // below it: 3e-308 mN ms per mm was 3e-311 mN s, subnormal, unchecked until session 61
    if (factor < 1 && sgn(value) != 0 && abs(value) * factor < smallest) {
      std::ostringstream text;
      text << "'" << model_detail::decimal(value) << "' " << unit << " is " << model_detail::decimal(value * factor) << " "
           << internal
           << " in the simulator's internal units (s, mN), below the doubles' normal range (a nonzero magnitude at "
              "least 2.2250738585072014e-308): give 0 or at least "
           << model_detail::decimal(smallest / factor) << " " << unit;
      throw ModelError(pointer, text.str());
    }
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
