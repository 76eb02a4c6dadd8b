// Reader step for the top-level "simulation" object (docs/model-format.md#simulation): units of
// time and force, gravity, initial velocities, drivers with a prescribed motion law, springs and
// dampers between two parts, centres of mass, the default accuracy. Every error names the JSON
// pointer of the offending value.
#include "model/reader.hpp"

#include <hipair/error.hpp>

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <set>

namespace hipair::model_detail {

std::size_t Reader::moving_part(const JsonValue& value) {
  std::string name = read_name(value);
  auto index = model_.find_part(name);
  if (!index) throw ModelError(value.pointer, "unknown part '" + name + "'");
  const Motion& motion = model_.parts[*index].motion;
  if (motion.kind != Motion::Kind::rotation && motion.kind != Motion::Kind::translation)
    throw ModelError(value.pointer, "part '" + name + "' " +
                                        (motion.kind == Motion::Kind::fixed
                                             ? std::string("is fixed")
                                             : std::string("is not a fixed-axis part (rotation or translation)")) +
                                        ": the simulator moves rotating and translating parts");
  return *index;
}

void Reader::read_simulation(const JsonValue* value) {
  if (!value) return;
  expect_object(*value, "a simulation object");
  check_keys(*value, {"units", "gravity", "velocities", "drivers", "springs", "centers_of_mass", "accuracy"});
  SimulatorValues simulator_values(*this);
  SimulationSpec spec;
  spec.pointer = value->pointer;
  if (const JsonValue* units = value->find("units")) {
    expect_object(*units, "an object {\"time\": \"s\", \"force\": \"N\"}");
    check_keys(*units, {"time", "force"});
    if (const JsonValue* time = units->find("time")) {
      spec.time_unit = read_string(*time, false);
      if (spec.time_unit != "s" && spec.time_unit != "ms")
        throw ModelError(time->pointer, "unsupported time unit '" + spec.time_unit + "' (\"s\" or \"ms\")");
    }
    if (const JsonValue* force = units->find("force")) {
      spec.force_unit = read_string(*force, false);
      if (spec.force_unit != "N" && spec.force_unit != "mN")
        throw ModelError(force->pointer, "unsupported force unit '" + spec.force_unit + "' (\"N\" or \"mN\")");
    }
  }
  if (const JsonValue* gravity = value->find("gravity")) {
    expect_array(*gravity, "a gravity vector [gx, gy] (mm per time unit squared)");
    if (gravity->items.size() != 2)
      throw ModelError(gravity->pointer, "gravity is [gx, gy]: expected 2 numbers, found " +
                                             std::to_string(gravity->items.size()));
    spec.gravity = Point{number(gravity->items[0]), number(gravity->items[1])};
  }
  // a rate of a part's coordinate: angle per time (in the file's angle unit) or mm per time
  auto rate = [&](const JsonValue& v, std::size_t part) {
    return model_.parts[part].motion.kind == Motion::Kind::rotation ? angle(v) : number(v);
  };
  std::set<std::size_t> driven;
  // a driver's law: "constant_speed" (the default; no profile) or "speed_profile"
  auto law_of = [&](const JsonValue& d) {
    std::string law_name = "constant_speed";
    if (const JsonValue* law = d.find("law")) {
      law_name = read_string(*law, false);
      if (law_name != "constant_speed" && law_name != "speed_profile")
        throw ModelError(law->pointer,
                         "unsupported motion law '" + law_name + "' (\"constant_speed\" or \"speed_profile\")");
    }
    if (const JsonValue* profile = d.find("profile"); profile && law_name == "constant_speed")
      throw ModelError(profile->pointer, "a profile needs \"law\": \"speed_profile\" (at " + d.pointer + "/law)");
    return law_name;
  };
  // a speed profile [[t, v], ...]: times strictly increasing from 0, no "speed"; `point` reads
  // each point's speed (the JSON value after its time), `items` names what a point holds
  auto read_profile = [&](const JsonValue& d, const std::string& items,
                          const std::function<void(const Rational&, const JsonValue&)>& point_speed) {
    if (const JsonValue* speed = d.find("speed"))
      throw ModelError(speed->pointer, "a speed profile gives its speeds in \"profile\"");
    const JsonValue& profile = expect_array(require(d, "profile"), "an array of [time, speed] points");
    if (profile.items.empty()) throw ModelError(profile.pointer, "a speed profile needs at least one point");
    std::optional<Rational> last;
    std::string last_at;
    for (const JsonValue& point : profile.items) {
      expect_array(point, "a point [time, speed]");
      if (point.items.size() != 2)
        throw ModelError(point.pointer, "a profile point is [time, speed]: expected 2 " + items + ", found " +
                                            std::to_string(point.items.size()));
      Rational time = number(point.items[0]);
      if (!last && time != 0) throw ModelError(point.items[0].pointer, "a speed profile starts at time 0");
      if (last && time <= *last)
        throw ModelError(point.items[0].pointer, "profile times must increase strictly: " + decimal(time) + " after " +
                                                     decimal(*last) + " (" + last_at + ")");
      point_speed(time, point.items[1]);
      last = time;
      last_at = point.items[0].pointer;
    }
  };
  if (const JsonValue* drivers = value->find("drivers")) {
    expect_array(*drivers, "an array of drivers");
    for (const JsonValue& d : drivers->items) {
      expect_object(d, "a driver {\"part\": name, \"speed\": v}");
      check_keys(d, {"part", "law", "speed", "profile"});
      SimulationSpec::Driver driver;
      driver.pointer = d.pointer;
      {
        // a planar part: a constant velocity {"x": vx, "y": vy, "angle": omega}, three drivers
        // of that part in the order vx, vy, omega (as its initial velocity, SimulationSpec::Velocity)
        const JsonValue& named = require(d, "part");
        auto index = named.is_string() ? model_.find_part(read_name(named)) : std::nullopt;
        if (index && model_.parts[*index].motion.kind == Motion::Kind::planar) {
          // {"x": vx, "y": vy, "angle": omega} -> the three components
          auto velocity = [&](const JsonValue& speed) {
            expect_object(speed, "a planar part's velocity {\"x\": vx, \"y\": vy, \"angle\": omega}");
            check_keys(speed, {"x", "y", "angle"});
            const JsonValue* vx = speed.find("x");
            const JsonValue* vy = speed.find("y");
            const JsonValue* omega = speed.find("angle");
            return std::array<Rational, 3>{vx ? number(*vx) : Rational(0), vy ? number(*vy) : Rational(0),
                                           omega ? angle(*omega) : Rational(0)};
          };
          const std::string law_name = law_of(d);
          if (!driven.insert(*index).second)
            throw ModelError(d.pointer, "part '" + model_.parts[*index].name + "' is driven twice");
          std::array<SimulationSpec::Driver, 3> parts;
          for (SimulationSpec::Driver& c : parts) {
            c.part = *index;
            c.pointer = d.pointer;
          }
          if (law_name == "constant_speed") {
            const std::array<Rational, 3> v = velocity(require(d, "speed"));
            for (int c = 0; c < 3; ++c) parts[c].speed = v[c];
          } else {   // [[t, {"x": vx, "y": vy, "angle": omega}], ...]: per component
            read_profile(d, "items", [&](const Rational& time, const JsonValue& speed) {
              const std::array<Rational, 3> v = velocity(speed);
              for (int c = 0; c < 3; ++c) parts[c].profile.emplace_back(time, v[c]);
            });
            for (SimulationSpec::Driver& c : parts) c.speed = c.profile.front().second;
          }
          // three drivers of that part in the order vx, vy, omega (as its initial velocity)
          for (SimulationSpec::Driver& c : parts) spec.drivers.push_back(std::move(c));
          continue;
        }
      }
      driver.part = moving_part(require(d, "part"));
      if (!driven.insert(driver.part).second)
        throw ModelError(d.pointer, "part '" + model_.parts[driver.part].name + "' is driven twice");
      if (law_of(d) == "constant_speed") {
        driver.speed = rate(require(d, "speed"), driver.part);
      } else {   // the speed linear between the points
        read_profile(d, "numbers", [&](const Rational& time, const JsonValue& speed) {
          driver.profile.emplace_back(time, rate(speed, driver.part));
        });
        driver.speed = driver.profile.front().second;
      }
      spec.drivers.push_back(driver);
    }
  }
  if (const JsonValue* velocities = value->find("velocities")) {
    expect_object(*velocities, "an object: part name -> initial velocity");
    for (const JsonMember& member : velocities->members) {
      auto index = model_.find_part(member.key);
      if (!index) throw ModelError(member.value.pointer, "unknown part '" + member.key + "'");
      const Motion& motion = model_.parts[*index].motion;
      if (motion.kind == Motion::Kind::planar) {
        // {"x": vx, "y": vy, "angle": omega}, each optional (0)
        if (driven.count(*index))
          throw ModelError(member.value.pointer, "part '" + member.key + "' is a driver: its velocity is the driver's");
        expect_object(member.value, "a planar part's velocity {\"x\": vx, \"y\": vy, \"angle\": omega}");
        check_keys(member.value, {"x", "y", "angle"});
        const JsonValue* vx = member.value.find("x");
        const JsonValue* vy = member.value.find("y");
        const JsonValue* omega = member.value.find("angle");
        spec.velocities.push_back({*index, vx ? number(*vx) : Rational(0), member.value.pointer});
        spec.velocities.push_back({*index, vy ? number(*vy) : Rational(0), member.value.pointer});
        spec.velocities.push_back({*index, omega ? angle(*omega) : Rational(0), member.value.pointer});
        continue;
      }
      if (motion.kind == Motion::Kind::pin_slot) {
        // {"slide": v, "angle": omega}, each optional (0): the rates of s (mm / time unit) and psi
        expect_object(member.value, "a pin-slot part's velocity {\"slide\": v, \"angle\": omega}");
        check_keys(member.value, {"slide", "angle"});
        const JsonValue* v = member.value.find("slide");
        const JsonValue* omega = member.value.find("angle");
        spec.velocities.push_back({*index, v ? number(*v) : Rational(0), member.value.pointer});
        spec.velocities.push_back({*index, omega ? angle(*omega) : Rational(0), member.value.pointer});
        continue;
      }
      if (motion.kind != Motion::Kind::rotation && motion.kind != Motion::Kind::translation)
        throw ModelError(member.value.pointer, "part '" + member.key + "' has no single coordinate to give a velocity");
      if (driven.count(*index))
        throw ModelError(member.value.pointer, "part '" + member.key + "' is a driver: its speed is the driver's");
      spec.velocities.push_back(SimulationSpec::Velocity{*index, rate(member.value, *index), member.value.pointer});
    }
  }
  if (const JsonValue* springs = value->find("springs")) {
    expect_array(*springs, "an array of springs between two parts");
    for (const JsonValue& s : springs->items) {
      expect_object(s, "a spring {\"parts\": [a, b], \"points\": [[x, y], [x, y]], \"stiffness\": k}");
      check_keys(s, {"parts", "points", "stiffness", "rest_length", "damping"});
      SimulationSpec::Coupling coupling;
      coupling.pointer = s.pointer;
      const JsonValue& names = expect_array(require(s, "parts"), "two part names [a, b]");
      if (names.items.size() != 2)
        throw ModelError(names.pointer, "a spring joins exactly 2 parts, found " + std::to_string(names.items.size()));
      std::size_t indices[2];
      for (int k = 0; k < 2; ++k) {
        std::string name = read_name(names.items[k]);
        auto index = model_.find_part(name);
        if (!index) throw ModelError(names.items[k].pointer, "unknown part '" + name + "'");
        const Motion& motion = model_.parts[*index].motion;
        if (motion.kind == Motion::Kind::pin_slot)
          throw ModelError(names.items[k].pointer, "part '" + name +
                                                       "' is a pin-slot part: a spring joins fixed, rotating, "
                                                       "translating or planar parts");
        indices[k] = *index;
      }
      if (indices[0] == indices[1])
        throw ModelError(names.pointer, "a spring joins two different parts");
      coupling.first = indices[0];
      coupling.second = indices[1];
      const JsonValue& points = expect_array(require(s, "points"), "two points [[x, y], [x, y]]");
      if (points.items.size() != 2)
        throw ModelError(points.pointer, "a spring has 2 attachment points, found " + std::to_string(points.items.size()));
      coupling.first_point = point(points.items[0]);
      coupling.second_point = point(points.items[1]);
      coupling.stiffness = non_negative(require(s, "stiffness"), "stiffness");
      if (const JsonValue* rest = s.find("rest_length")) coupling.rest_length = non_negative(*rest, "rest length");
      if (const JsonValue* damping = s.find("damping")) coupling.damping = non_negative(*damping, "damping");
      if (coupling.rest_length == 0 && coupling.first_point == coupling.second_point && coupling.damping > 0)
        throw ModelError(s.pointer, "a damper needs two distinct attachment points (its direction is undefined)");
      spec.couplings.push_back(coupling);
    }
  }
  if (const JsonValue* centers = value->find("centers_of_mass")) {
    expect_object(*centers, "an object: part name -> centre of mass [x, y]");
    for (const JsonMember& member : centers->members) {
      auto index = model_.find_part(member.key);
      if (!index) throw ModelError(member.value.pointer, "unknown part '" + member.key + "'");
      if (model_.parts[*index].motion.kind == Motion::Kind::planar)
        throw ModelError(member.value.pointer, "part '" + member.key +
                                                   "' is planar: its centre of mass is its pivot (set \"pivot\" there)");
      if (model_.parts[*index].motion.kind != Motion::Kind::rotation &&
          model_.parts[*index].motion.kind != Motion::Kind::pin_slot)
        throw ModelError(member.value.pointer, "part '" + member.key +
                                                   "' does not rotate: a centre of mass only matters for a rotating "
                                                   "or pin-slot part");
      spec.centers_of_mass.push_back(SimulationSpec::CenterOfMass{*index, point(member.value), member.value.pointer});
    }
  }
  if (const JsonValue* accuracy = value->find("accuracy")) {
    spec.accuracy = positive(*accuracy, "accuracy");
    // the range `hipair simulate --accuracy` takes (below 1e-15 the integrator's steps underflow:
    // 1e-300 ran to "the integrator's step size underflows" with no pointer; session 43)
    if (*spec.accuracy > Rational(1, 10) || *spec.accuracy < Rational(1, 1000000000000000))
      throw ModelError(accuracy->pointer, "accuracy is relative, in (0, 1), and the integrator takes it in "
                                          "[1e-15, 0.1] (the range of --accuracy); got " + decimal(*spec.accuracy));
  }
  model_.simulation = std::move(spec);
}

}  // namespace hipair::model_detail
