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

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
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

// The deviations of the box's corner that moves a sample's linearised output up (way 1) or down
// (way -1): each toleranced parameter at the end its sensitivity's sign points to.
inline std::vector<Rational> linearised_corner(const VariationSample& sample, const std::vector<Parameter>& parameters,
                                               int way) {
  std::vector<Rational> d(parameters.size(), Rational(0));
  for (std::size_t p = 0; p < d.size() && p < sample.sensitivities.size(); ++p) {
    const Parameter& q = parameters[p];
    if (q.range.lo == q.range.hi) continue;
    bool up = (sample.sensitivities[p] >= 0) == (way > 0);
    d[p] = (up ? q.range.hi : q.range.lo) - q.nominal;
  }
  return d;
}

// The least (non-zero) and the most effective toleranced parameter at a sample, by |sensitivity|
// times the tolerance's width; parameters.size() where there is none.
struct Effects {
  std::size_t least, most;
};
inline Effects effects(const VariationSample& sample, const std::vector<Parameter>& parameters) {
  Effects e{parameters.size(), parameters.size()};
  double least_effect = std::numeric_limits<double>::infinity(), most_effect = -1;
  for (std::size_t p = 0; p < parameters.size() && p < sample.sensitivities.size(); ++p) {
    const Parameter& q = parameters[p];
    if (q.range.lo == q.range.hi) continue;
    double effect = std::fabs(sample.sensitivities[p]) * Rational(q.range.hi - q.range.lo).get_d();
    if (effect > 0 && effect < least_effect) least_effect = effect, e.least = p;
    if (effect > most_effect) most_effect = effect, e.most = p;
  }
  return e;
}

// The probe vectors of a sample the exact-train tests evaluate, per way: the linearised corner,
// the same with the least effective parameter at its other end, and with the most effective one
// nominal (e.most must name a parameter).
inline std::vector<std::pair<int, std::vector<Rational>>> corner_probes(const VariationSample& sample,
                                                                        const std::vector<Parameter>& parameters,
                                                                        const Effects& e) {
  std::vector<std::pair<int, std::vector<Rational>>> probes;
  for (int way : {1, -1}) {
    std::vector<Rational> d = linearised_corner(sample, parameters, way);
    probes.emplace_back(way, d);
    if (e.least < d.size()) {
      std::vector<Rational> flipped = d;
      const Parameter& q = parameters[e.least];
      flipped[e.least] = (d[e.least] == q.range.hi - q.nominal ? q.range.lo : q.range.hi) - q.nominal;
      probes.emplace_back(way, flipped);
    }
    std::vector<Rational> centred = d;
    centred[e.most] = Rational(0);
    probes.emplace_back(way, centred);
  }
  return probes;
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
