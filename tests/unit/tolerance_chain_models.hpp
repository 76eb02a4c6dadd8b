// Generated lift chains for the assembly-chain tolerance tests and benchmarks: an eccentric cam
// (e = 5, radius 20) under lifter1's flat face; lifter k's roller (radius 5) under lifter k+1's
// face; every lifter translating along y under its weight. Lifter k's face sits on `shims`
// toleranced shims of nominal 1/5 (parameters s<k>_<j>), so the output (the last lifter) is
// out = e sin(theta) - 10 - sum over all shims of (shim - 1/5): linear in the parameters, each
// shim's sensitivity -1 and e's sin(theta). Tolerances and distributions are drawn at random
// (ranges in thousandths; none, uniform or normal), with their mean and sigma as
// docs/tolerance.md "Distributions" defines them.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair::test_chain {

struct ChainParameter {
  std::string name;
  double lo = 0, hi = 0;        ///< tolerance range (deviations)
  double mean = 0, sigma = 0;   ///< of the distribution (deviations)
};

struct LiftChain {
  std::string json;
  std::vector<ChainParameter> parameters;   ///< Model::parameters order (e first)
};

/// `pairs` pairs (cam:lifter1, lifter1:lifter2, ...); with `rng` null every shim is 1/5 +- 0.002
/// without distribution and e is 5 +- 0.01.
inline LiftChain lift_chain(std::size_t pairs, std::size_t shims, std::mt19937& rng, bool random = true) {
  LiftChain chain;
  std::uniform_int_distribution<int> thousandths(1, 9), kind(0, 2);
  std::string params;
  // n / 1000 as a decimal (n < 1000).
  auto milli = [](int n) { return "0." + std::string(n < 10 ? "00" : n < 100 ? "0" : "") + std::to_string(n); };
  auto add = [&](const std::string& name, const std::string& nominal) {
    ChainParameter p;
    p.name = name;
    std::string spec;
    int k = random ? kind(rng) : 0;
    if (k == 0) {   // symmetric, no distribution: normal about the centre, sigma = width / 6
      int t = random ? thousandths(rng) : (name == "e" ? 10 : 2);
      p.lo = -t / 1000.0;
      p.hi = t / 1000.0;
      p.sigma = (p.hi - p.lo) / 6;
      spec = "\"tolerance\": " + milli(t);
    } else if (k == 1) {   // asymmetric, uniform: mean at the centre, sigma = width / sqrt(12)
      int a = thousandths(rng), b = thousandths(rng);
      p.lo = -a / 1000.0;
      p.hi = b / 1000.0;
      p.mean = 0.5 * (p.lo + p.hi);
      p.sigma = (p.hi - p.lo) / std::sqrt(12.0);
      spec = "\"tolerance\": [-" + std::to_string(a) + "e-3, " + std::to_string(b) + "e-3], \"distribution\": \"uniform\"";
    } else {   // normal with its own sigma, about the nominal
      int t = thousandths(rng);
      p.lo = -t / 1000.0;
      p.hi = t / 1000.0;
      p.sigma = t / 2000.0;
      std::string half = "0." + std::string(t < 2 ? "000" : "00") + std::to_string(5 * t);   // t / 2000
      spec = "\"tolerance\": " + milli(t) + ", \"distribution\": {\"normal\": {\"sigma\": " + half + "}}";
    }
    params += (params.empty() ? "" : ",\n  ") + ("\"" + name + "\": {\"nominal\": " + nominal + ", " + spec + "}");
    chain.parameters.push_back(p);
  };
  add("e", "5");
  std::string parts = R"({"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": 20}}]})";
  std::string pair_list = "";
  for (std::size_t k = 1; k <= pairs; ++k) {
    std::string sum;
    for (std::size_t j = 1; j <= shims; ++j) {
      std::string name = "s" + std::to_string(k) + "_" + std::to_string(j);
      add(name, "\"1/5\"");
      sum += (j > 1 ? " + " : "") + name;
    }
    int base = 30 + 25 * static_cast<int>(k - 1);
    std::string face = std::to_string(base) + " + (" + sum + ") - " + std::to_string(shims) + "/5";
    std::string top = std::to_string(base + 10);
    std::string name = "lifter" + std::to_string(k);
    parts += R"(,
    {"name": ")" + name + R"(", "motion": {"translation": {"direction": [0, 1], "limits": [-40, 40]}}, "initial": {"offset": -10},
     "loops": [{"start": [-40, ")" + face + R"("], "edges": [{"line_to": [40, ")" + face + R"("]},
       {"line_to": [40, )" + top + R"(]}, {"line_to": [-40, )" + top + R"(]}, {"line_to": [-40, ")" + face + R"("]}]},
       {"circle": {"center": [0, )" + std::to_string(base + 20) + R"(], "radius": 5}}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}})";
    std::string previous = k == 1 ? "cam" : "lifter" + std::to_string(k - 1);
    pair_list += std::string(k > 1 ? ", " : "") + "{\"parts\": [\"" + previous + "\", \"" + name + "\"]}";
  }
  chain.json = R"({"hipair": 1, "name": "lift-chain", "units": {"length": "mm", "angle": "rad"}, "parameters": {
  )" + params + R"(},
  "parts": [)" + parts + R"(],
  "pairs": [)" + pair_list + "]}";
  return chain;
}

}  // namespace hipair::test_chain
