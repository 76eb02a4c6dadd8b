// Generated idler gear trains for the gear-train tolerance tests and benchmarks: the C++ form of
// examples/models/gear-train.py (gear_train(9) is examples/models/gear-train.json's model,
// gear_train(3) gear-train-3.json's), with the teeth as arguments: `gears` spur gears in a row,
// gear k with `even_teeth` teeth when k is even and `odd_teeth` when odd (both even numbers: the
// phases below put a tooth of one gear into a gap of the next), module 2 mm shared by every gear,
// each flank one circular arc (flank_radius). Per gear 12 toleranced parameters (bearing x, y,
// runout x, y, pitch radius, addendum, dedendum, thinning, flank radius, pressure angle, phase)
// plus the module: 12 gears + 1 in all.
#pragma once

#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <random>
#include <string>
#include <vector>

namespace hipair::test_gears {

inline std::string gear_train(unsigned gears, unsigned even_teeth = 10, unsigned odd_teeth = 12) {
  std::string params = "\"module\": {\"nominal\": 2, \"tolerance\": 0.002}";
  std::string parts, pairs;
  unsigned pivot_x = 0;
  for (unsigned k = 0; k < gears; ++k) {
    std::string g(1, static_cast<char>('A' + k));
    unsigned z = k % 2 == 0 ? even_teeth : odd_teeth;
    if (k > 0) pivot_x += even_teeth + odd_teeth;   // module x (z1 + z2) / 2
    std::string phase = k == 0 ? "0" : k % 2 == 1 ? "pi + pi / " + std::to_string(odd_teeth) : "pi";
    auto P = [&](const std::string& s) { return g + "-" + s; };
    auto add = [&](const std::string& name, const std::string& body) { params += ", \"" + P(name) + "\": {" + body + "}"; };
    add("teeth", "\"nominal\": " + std::to_string(z));
    add("pivot-x", "\"nominal\": " + std::to_string(pivot_x) + ", \"tolerance\": 0.01");
    add("pivot-y", "\"nominal\": 0, \"tolerance\": 0.01");
    add("runout-x", "\"nominal\": 0, \"tolerance\": 0.005");
    add("runout-y", "\"nominal\": 0, \"tolerance\": 0.005");
    add("pitch-radius", "\"nominal\": \"module * " + P("teeth") + " / 2\", \"tolerance\": 0.005");
    add("addendum", "\"nominal\": \"module\", \"tolerance\": 0.01");
    add("dedendum", "\"nominal\": \"1.25 * module\", \"tolerance\": 0.01");
    add("thinning", "\"nominal\": 0.1, \"tolerance\": 0.01");
    add("flank-radius", "\"nominal\": 4, \"tolerance\": 0.02");
    add("pressure-angle", "\"nominal\": \"20 deg\", \"tolerance\": 0.002, \"angle\": true");
    add("phase", "\"nominal\": \"" + phase + "\", \"tolerance\": 0.001, \"angle\": true");
    if (k > 0) parts += ", ";
    parts += "{\"name\": \"gear-" + g + "\", \"motion\": {\"rotation\": {\"pivot\": [\"" + P("pivot-x") + "\", \"" +
             P("pivot-y") + "\"]}}, \"initial\": {\"angle\": 0}, \"features\": [{\"spur_gear\": {\"center\": [\"" +
             P("pivot-x") + " + " + P("runout-x") + "\", \"" + P("pivot-y") + " + " + P("runout-y") +
             "\"], \"teeth\": \"" + P("teeth") + "\", \"pitch_radius\": \"" + P("pitch-radius") + "\", \"addendum\": \"" +
             P("addendum") + "\", \"dedendum\": \"" + P("dedendum") + "\", \"tooth_thickness\": \"pi * module / 2 - " +
             P("thinning") + "\", \"flank_radius\": \"" + P("flank-radius") + "\", \"pressure_angle\": \"" +
             P("pressure-angle") + "\", \"phase\": \"" + P("phase") + "\"}}]}";
    if (k > 0) {
      if (k > 1) pairs += ", ";
      pairs += "{\"parts\": [\"gear-" + std::string(1, static_cast<char>('A' + k - 1)) + "\", \"gear-" + g + "\"]}";
    }
  }
  return "{\"hipair\": 1, \"name\": \"gear-train-" + std::to_string(gears) +
         "\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"}, \"parameters\": {" + params + "}, \"parts\": [" + parts +
         "], \"pairs\": [" + pairs + "]}";
}

/// A deviation vector (Model::parameters order) drawn uniformly on a grid of 1/1000 of each
/// toleranced parameter's range (exact rationals); 0 for the others.
inline std::vector<Rational> random_deviations(const std::vector<Parameter>& parameters, std::mt19937& rng) {
  std::uniform_int_distribution<int> u(0, 1000);
  std::vector<Rational> d(parameters.size(), Rational(0));
  for (std::size_t i = 0; i < d.size(); ++i) {
    const Parameter& p = parameters[i];
    if (p.range.lo != p.range.hi) d[i] = p.range.lo - p.nominal + Rational(u(rng), 1000) * (p.range.hi - p.range.lo);
  }
  return d;
}

// The chain from gear-A over [0, end] at 120 positions per turn, on 2 threads, with
// `monte_carlo` Monte Carlo samples from `seed`.
inline ToleranceOptions chain_options(const Rational& end, std::size_t monte_carlo, unsigned seed) {
  ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = std::make_pair(Rational(0), end);
  options.positions = 120;
  options.threads = 2;
  options.monte_carlo = monte_carlo;
  options.seed = seed;
  return options;
}

}  // namespace hipair::test_gears
