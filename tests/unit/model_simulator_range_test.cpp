// Dynamics data beyond the doubles' range (session 43, hunt43). The simulator holds every value
// of a part's "dynamics", of the "simulation" object and a pair's friction and restitution in
// doubles; an exact literal such as 1e400 (the grammar takes exponents up to 1000) became
// infinity there, and `hipair simulate` died of SIGFPE (GMP's mpq_set_d(inf)) on a friction,
// a driver speed or an initial angle of 1e400, or integrated a non-finite state (mass,
// velocity, spring rest of 1e400). The reader now refuses such a value at its own pointer.
//
// Generated: every number of every bundled model's dynamics data is replaced, one at a time,
// by values beyond the range (huge, tiny, either sign); each must be refused with exactly its
// JSON pointer and the range's reason. Controls: the range's own ends (and values just inside
// them) are never refused for the range. On main 0bdc449 every beyond-range case was accepted.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "model/simulation_reading.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string range_reason = "for the simulator, which holds dynamics data in doubles";


// JSON pointer of every number (or number string) under the dynamics data of a model
void collect(const json& value, const std::string& pointer, std::vector<std::string>& out) {
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (it.key() == "units" || it.key() == "law" || it.key() == "part" || it.key() == "parts") continue;
      collect(it.value(), pointer + "/" + it.key(), out);
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) collect(value[i], pointer + "/" + std::to_string(i), out);
  } else if (value.is_number()) {
    out.push_back(pointer);
  }
}

struct Source {
  std::string name;
  json document;
  std::vector<std::string> pointers;   // the dynamics numbers
  // the range is that of the value the simulator holds, in rad: in a file whose angle unit is
  // deg an angle (a torsional spring's rest, a rotating part's velocity or driver speed) is
  // scaled by pi/180 first, so literals within a factor 100 of the range's ends are left out there
  bool degrees() const {
    return document.contains("units") && document["units"].value("angle", std::string("rad")) == "deg";
  }
  bool skip(const std::string& pointer, const std::string& literal) const {
    const bool angle = pointer.find("torsional_spring/rest") != std::string::npos ||
                       pointer.rfind("/simulation/velocities", 0) == 0 || pointer.rfind("/simulation/drivers", 0) == 0;
    if (!degrees() || !angle) return false;
    const long double v = std::abs(std::strtold(literal.c_str(), nullptr));   // x86 long double: to 1e4932
    return (v > 1e306L && v < 1e311L) || (v > 1e-311L && v < 1e-305L);
  }
};

std::vector<Source> sources() {
  std::vector<Source> result;
  for (const auto& entry : fs::directory_iterator(fs::path(HIPAIR_EXAMPLES))) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    json doc = json::parse(in);
    Source s{entry.path().filename().string(), doc, {}};
    if (doc.contains("simulation")) collect(doc["simulation"], "/simulation", s.pointers);
    for (std::size_t i = 0; doc.contains("parts") && i < doc["parts"].size(); ++i)
      if (doc["parts"][i].contains("dynamics"))
        collect(doc["parts"][i]["dynamics"], "/parts/" + std::to_string(i) + "/dynamics", s.pointers);
    for (std::size_t i = 0; doc.contains("pairs") && i < doc["pairs"].size(); ++i)
      for (const char* key : {"friction", "restitution"})
        if (doc["pairs"][i].contains(key))
          collect(doc["pairs"][i][key], "/pairs/" + std::to_string(i) + "/" + key, s.pointers);
    if (!s.pointers.empty()) result.push_back(std::move(s));
  }
  return result;
}

// the model's text with the number at `pointer` replaced by the literal `literal` (a JSON number)
std::string with(const json& document, const std::string& pointer, const std::string& literal) {
  json copy = document;
  copy[json::json_pointer(pointer)] = "@@MARK@@";   // a marker, replaced by the literal's own text
  std::string text = copy.dump();
  const std::string marker = "\"@@MARK@@\"";
  return text.replace(text.find(marker), marker.size(), literal);
}

TEST(ModelSimulatorRange, ValuesBeyondTheDoublesRangeAreRefusedAtTheirPointer) {
  const std::vector<std::string> beyond = {"1e400", "-1e400", "1.8e308", "-1.7976931348623159e308", "1e-400",
                                           "-3e-310", "2.2e-308"};
  std::size_t cases = 0, failures = 0;
  for (const Source& s : sources()) {
    for (const std::string& pointer : s.pointers) {
      for (const std::string& literal : beyond) {
        if (s.skip(pointer, literal)) continue;
        ++cases;
        std::string text = with(s.document, pointer, literal);
        // the exact commands read the same text without the simulator's range (a model scaled
        // to 10^-300 has inertias of 10^-600): never refused for the range
        try {
          hipair::read_model(text, s.name);
        } catch (const hipair::ModelError& e) {
          if (std::string(e.what()).find(range_reason) != std::string::npos) {
            ++failures;
            ADD_FAILURE() << s.name << " " << pointer << " = " << literal << " refused by the exact commands' reading";
          }
        }
        try {
          hipair::read_model_for_simulation(text, s.name);
          ++failures;
          ADD_FAILURE() << s.name << " " << pointer << " = " << literal << " was accepted";
        } catch (const hipair::ModelError& e) {
          const std::string message = e.what();
          if (e.pointer() != pointer || message.find(range_reason) == std::string::npos) {
            ++failures;
            ADD_FAILURE() << s.name << " " << pointer << " = " << literal << ": " << message;
          }
        }
      }
    }
  }
  EXPECT_GT(cases, 300u);   // 16 bundled models with dynamics data, about 60 numbers
  EXPECT_EQ(failures, 0u) << "of " << cases;
}

// The parts' initial coordinates stay unlimited for the exact commands; every simulator refuses
// one beyond the doubles' range at its pointer when it is created (the library, not only the
// command: a caller of Simulation::create got SIGFPE from GMP's mpq_set_d(inf)).
TEST(ModelSimulatorRange, EverySimulatorRefusesAnInitialCoordinateBeyondTheDoubles) {
  using hipair::Motion;
  std::size_t cases = 0, failures = 0;
  std::vector<std::string> kinds_seen;
  for (const auto& entry : fs::directory_iterator(fs::path(HIPAIR_EXAMPLES))) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    const json document = json::parse(in);
    const hipair::Model nominal = hipair::read_model_file(entry.path());
    std::size_t planar = 0;
    for (const hipair::Part& part : nominal.parts) planar += part.motion.kind == Motion::Kind::planar;
    for (std::size_t i = 0; i < nominal.parts.size(); ++i) {
      std::vector<std::string> keys;
      switch (nominal.parts[i].motion.kind) {
        case Motion::Kind::rotation: keys = {"angle"}; break;
        case Motion::Kind::translation: keys = {"offset"}; break;
        case Motion::Kind::planar: keys = {"x", "y", "angle"}; break;
        case Motion::Kind::pin_slot: keys = {"angle", "offset"}; break;
        default: break;
      }
      for (const std::string& key : keys) {
        for (const char* literal : {"1e400", "-1e320"}) {   // beyond DBL_MAX in rad in deg files too
          json copy = document;
          if (!copy["parts"][i].contains("initial")) copy["parts"][i]["initial"] = json::object();
          const std::string pointer = "/parts/" + std::to_string(i) + "/initial/" + key;
          hipair::Model model;
          try {
            model = hipair::read_model(with(copy, pointer, literal), entry.path().filename().string());
          } catch (const hipair::ModelError&) {
            continue;   // outside the motion's limits: the reader's own refusal
          }
          ++cases;
          try {
            hipair::SimulationOptions options;
            if (planar == 0) (void)hipair::Simulation::create(model, options);
            else if (planar == 1) (void)hipair::PlanarSimulation::create(model, options);
            else (void)hipair::PlanarSystemSimulation::create(model, options);
            ++failures;
            ADD_FAILURE() << entry.path().filename() << " " << pointer << " = " << literal << " was simulated";
          } catch (const hipair::ModelError& e) {
            if (e.pointer() != pointer) {
              ++failures;
              ADD_FAILURE() << entry.path().filename() << " " << pointer << " = " << literal << ": " << e.what();
            }
          }
          kinds_seen.push_back(std::to_string(planar == 0 ? 0 : planar == 1 ? 1 : 2));
        }
      }
    }
  }
  for (const char* kind : {"0", "1", "2"})   // Simulation, PlanarSimulation, PlanarSystemSimulation
    EXPECT_NE(std::find(kinds_seen.begin(), kinds_seen.end(), kind), kinds_seen.end()) << "no case for simulator " << kind;
  EXPECT_GT(cases, 40u);
  EXPECT_EQ(failures, 0u) << "of " << cases;
}

TEST(ModelSimulatorRange, TheRangesEndsAreNotRefusedForTheRange) {
  // the largest finite double, the smallest normal one, and values just inside; other checks
  // (restitution <= 1, accuracy in [1e-15, 0.1], a kinetic friction above the static one,
  // signs) may still refuse them, but never for the doubles' range
  const std::vector<std::string> inside = {"1.7976931348623157e308", "-1.7976931348623157e308",
                                           "2.2250738585072014e-308", "-2.2250738585072014e-308",
                                           "1e308", "3e-308", "0"};
  std::size_t cases = 0;
  for (const Source& s : sources()) {
    for (const std::string& pointer : s.pointers) {
      for (const std::string& literal : inside) {
        if (s.skip(pointer, literal)) continue;
        ++cases;
        std::string text = with(s.document, pointer, literal);
        try {
          hipair::read_model_for_simulation(text, s.name);
        } catch (const hipair::ModelError& e) {
          EXPECT_EQ(std::string(e.what()).find(range_reason), std::string::npos)
              << s.name << " " << pointer << " = " << literal << ": " << e.what();
        }
      }
    }
  }
  EXPECT_GT(cases, 300u);
}

TEST(ModelSimulatorRange, TheModelsAccuracyTakesTheRangeOfTheOption) {
  // --accuracy takes [1e-15, 0.1]; the model's own key took (0, 1), and 1e-300 ran to "the
  // integrator's step size underflows" with no pointer
  std::ifstream in(fs::path(HIPAIR_EXAMPLES) / "bouncing-bar.json");
  json doc = json::parse(in);
  for (const std::string& literal : {"1e-300", "9.9e-16", "0.10000001", "0.5"}) {
    try {
      hipair::read_model_for_simulation(with(doc, "/simulation/accuracy", literal), "bouncing-bar.json");
      ADD_FAILURE() << literal << " was accepted";
    } catch (const hipair::ModelError& e) {
      EXPECT_EQ(e.pointer(), "/simulation/accuracy") << e.what();
      EXPECT_NE(std::string(e.what()).find("[1e-15, 0.1]"), std::string::npos) << e.what();
    }
  }
  for (const std::string& literal : {"1e-15", "0.1", "1e-9"})
    EXPECT_NO_THROW(hipair::read_model_for_simulation(with(doc, "/simulation/accuracy", literal), "bouncing-bar.json")) << literal;
}

// Session 60 (hunt60): the range holds for the values the simulator holds, in its internal units
// (s, mN). Every bundled model rewritten in ms and N: a value within the doubles in the file's
// units whose conversion leaves them (a rate x 1000, gravity x 10^6, a force, torque or stiffness
// x 1000) is refused at its pointer (or the velocity object holding it); the same datum at half
// the largest value the message gives, and every datum whose factor is 1 (masses, inertias,
// dampings in N ms, rests, points, times, friction), is not refused for it. base60 accepted them
// all, and `simulate` ran to "moving at inf rad/ms ... not finite" at t = 0 without a pointer.
TEST(ModelSimulatorRange, ValuesBeyondTheDoublesInTheSimulatorsUnitsAreRefusedAtTheirPointer) {
  const std::string internal_reason = "in the simulator's internal units (s, mN), beyond the doubles' range";
  // the factor from (ms, N) to (s, mN) of the datum at `pointer`
  auto factor = [](const std::string& pointer) -> double {
    auto has = [&](const char* part) { return pointer.find(part) != std::string::npos; };
    if (pointer.rfind("/simulation/gravity", 0) == 0) return 1e6;
    if (pointer.rfind("/simulation/velocities", 0) == 0) return 1e3;
    if (pointer.rfind("/simulation/drivers", 0) == 0) {   // a speed, or a profile point's [time, speed]
      const std::size_t at = pointer.find("/profile/");
      const std::size_t point_end = at == std::string::npos ? at : pointer.find('/', at + 9);
      return has("/speed") || (point_end != std::string::npos && pointer.compare(point_end, 2, "/1") == 0) ? 1e3 : 1;
    }
    if (has("/stiffness") || has("/torque") || has("/dynamics/force/")) return 1e3;
    return 1;
  };
  std::size_t refused = 0, kept = 0;
  for (const Source& s : sources()) {
    json document = s.document;
    if (!document.contains("simulation")) continue;
    document["simulation"]["units"] = {{"time", "ms"}, {"force", "N"}};
    for (const std::string& pointer : s.pointers) {
      if (pointer.rfind("/simulation/units", 0) == 0) continue;
      const double f = factor(pointer);
      // (an angle rate of a file in degrees is held in rad: 1e306 deg/ms fits once converted)
      const bool angle_rate = pointer.rfind("/simulation/velocities", 0) == 0 || pointer.rfind("/simulation/drivers", 0) == 0;
      if (s.degrees() && angle_rate) continue;
      const std::string text = with(document, pointer, f > 1 ? "5e307" : "1e306");
      try {
        hipair::read_model_for_simulation(text, s.name);
        if (f > 1) ADD_FAILURE() << s.name << " " << pointer << " = 5e307 (x " << f << ") was accepted";
        ++kept;
      } catch (const hipair::ModelError& e) {
        const std::string message = e.what();
        if (f == 1) {
          EXPECT_EQ(message.find(internal_reason), std::string::npos) << s.name << " " << pointer << ": " << message;
          ++kept;
          continue;
        }
        ++refused;
        EXPECT_EQ(pointer.rfind(e.pointer(), 0), 0u) << s.name << " " << pointer << ": named " << e.pointer();
        ASSERT_NE(message.find(internal_reason), std::string::npos) << s.name << " " << pointer << ": " << message;
        // the largest value the message allows, halved: not refused for the range
        const std::size_t at = message.find("give at most ");
        ASSERT_NE(at, std::string::npos) << message;
        const double largest = std::strtod(message.c_str() + at + 13, nullptr);
        EXPECT_GT(largest, 1.7e308 / f) << message;
        EXPECT_LE(largest, 1.8e308 / f) << message;
        std::ostringstream half;
        half.precision(17);
        half << largest / 2;
        try {
          hipair::read_model_for_simulation(with(document, pointer, half.str()), s.name);
        } catch (const hipair::ModelError& again) {
          EXPECT_EQ(std::string(again.what()).find(internal_reason), std::string::npos)
              << s.name << " " << pointer << " = " << half.str() << ": " << again.what();
        }
      }
    }
  }
  EXPECT_GT(refused, 30u);
  EXPECT_GT(kept, 30u);
}

// Session 61 (hunt61): the loads the data makes at the start, in the simulator's units (s, mN),
// each datum within the doubles' range but their product not: a mass under gravity, a part's own
// spring far from its rest, a spring with a rest length near the doubles' end; and a damping in
// mN ms that is subnormal in mN s. On base61 each of these ran to "not finite" at t = 0 (exit 3,
// no pointer) or, for the damping, was taken. Oracle: the load itself in closed form (the weight
// m g, the spring's k |rest - q0| with q0 = 0, the rest length's force k (rest - L0) with L0 <
// 200 mm), refused at the datum's pointer when it is beyond DBL_MAX, and accepted when the
// reader's bound is within (the spring's moment: its force times the lever's 1-norm, 15 mm;
// between the two either, at the pointer); values clear of each boundary by 1 %; seeded
// (HIPAIR_TEST_SEED). Since session 62 (exact62) a spring's stored energy k stretch^2 / 2 is
// bounded too (it overflowed `simulate`'s summary far below the force bound): the two springs'
// rest cases are drawn about that bound, their oracle the energy in closed form.
TEST(ModelSimulatorRange, StartLoadsBeyondTheDoublesAreRefusedAtTheirLargestFactor) {
  const std::uint64_t seed = hipair::test::test_seed(61);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(1.0, 9.99);
  const double largest = std::numeric_limits<double>::max();
  auto load = [](const char* name) {
    std::ifstream in(fs::path(HIPAIR_EXAMPLES) / name);
    return json::parse(in);
  };
  const json block = load("spring-block.json"), bar = load("bouncing-bar.json");
  json block_ms = block;
  block_ms["simulation"]["units"] = {{"time", "ms"}, {"force", "mN"}};
  struct Case {
    const json* document;
    const char* name;
    std::string pointer;
    int lowest, highest;        // decimal exponents drawn
    double factor;              // the load (or the internal value) per unit of the datum
    double bound;               // the reader's bound on it per unit of the datum
    bool below;                 // refused below DBL_MIN (a damping), else above DBL_MAX
    int power = 1;              // the load (and the bound) per unit of the datum's power: 2 for an energy
  };
  const std::vector<Case> cases = {
      {&block, "spring-block.json", "/parts/1/dynamics/mass", 300, 308, 9810.0, 9810.0, false},           // m g, mN
      // the torsional spring's energy k rest^2 / 2 (its load k rest is in range up to 1.8e305 rad;
      // session 62: the energy bound, k (|q| + |rest|)^2 / 2, refuses from 6e152 rad on)
      {&bar, "bouncing-bar.json", "/parts/0/dynamics/torsional_spring/rest", 150, 156, 500.0, 500.0, false, 2},
      // the spring's stored energy k stretch^2 / 2 (session 62: it overflowed the summary's energy
      // from a rest length of 2.7e153 mm on, while its force k rest stays in range up to 2.4e305):
      // the true 25 (L - rest)^2 mN mm and the reader's bound 25 (170 + rest)^2, equal to 1e-150 here
      {&block, "spring-block.json", "/simulation/springs/0/rest_length", 150, 156, 25.0, 25.0, false, 2},
      {&block_ms, "spring-block.json", "/simulation/springs/0/damping", -308, -305, 1e-3, 1e-3, true},     // mN s
  };
  std::size_t refused = 0, kept = 0;
  for (int round = 0; round < 12; ++round)
    for (const Case& c : cases) {
      std::uniform_int_distribution<int> exponent(c.lowest, c.highest);
      std::ostringstream literal;
      literal.precision(6);
      literal << mantissa(rng) << "e" << exponent(rng);
      const double value = std::strtod(literal.str().c_str(), nullptr);
      if (!(value >= std::numeric_limits<double>::min()) || !(value <= largest)) continue;   // the datum's own range
      const long double power = c.power == 2 ? static_cast<long double>(value) * value : static_cast<long double>(value);
      const long double internal = power * c.factor;
      const long double bounded = power * c.bound;
      const long double end = c.below ? std::numeric_limits<double>::min() : largest;
      if (std::abs(internal / end - 1) < 0.01L || std::abs(bounded / end - 1) < 0.01L) continue;   // clear of the ends
      const bool beyond = c.below ? internal < end : internal > end;
      const bool within = c.below ? bounded > end : bounded < end;
      const std::string what = std::string(c.name) + " " + c.pointer + " = " + literal.str() + " (seed " +
                               std::to_string(seed) + ")";
      try {
        hipair::read_model_for_simulation(with(*c.document, c.pointer, literal.str()), c.name);
        EXPECT_FALSE(beyond) << what << " was accepted";
        ++kept;
      } catch (const hipair::ModelError& e) {
        EXPECT_FALSE(within) << what << ": " << e.what();
        EXPECT_EQ(e.pointer(), c.pointer) << what << ": " << e.what();
        ++refused;
      }
    }
  EXPECT_GT(refused, 5u) << "seed " << seed;
  EXPECT_GT(kept, 5u) << "seed " << seed;
}

}  // namespace
