// HIPAIR — the model's own fastest motion, from its dynamics data alone (docs/simulation.md,
// "Stiff inputs"): what `simulate` compares with its step budget before a run starts.
#include <hipair/simulation.hpp>

#include "simulation/units.hpp"

#include <algorithm>
#include <cmath>

namespace hipair {

namespace {

// (long double: on x86 its range reaches 1e4932, so that ω² of data near the doubles' end, a
// stiffness of 1 on an inertia of 3e-308, is not infinity; until session 61 the period was then
// shown as "2π/ω = 0 s")
long double to_d(const Rational& r) { return r.get_d(); }
long double distance(const Point& a, const Point& b) { return std::hypot(to_d(a.x - b.x), to_d(a.y - b.y)); }

}  // namespace

OwnFrequency own_frequency(const Model& model) {
  OwnFrequency best;
  const SimulationSpec spec = model.simulation.value_or(SimulationSpec{});
  // internal units: s and mN (kg·mm/s²); ω² in 1/s², reported per time unit of the model
  const long double ts = simulation::seconds_per(spec), fs = simulation::millinewtons_per(spec);
  const long double g = std::hypot(to_d(spec.gravity.x), to_d(spec.gravity.y)) / (ts * ts);
  std::vector<bool> free(model.parts.size(), false);
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    free[p] = model.parts[p].motion.kind != Motion::Kind::fixed && model.parts[p].dynamics;
  for (const auto& driver : spec.drivers) free[driver.part] = false;
  auto mass = [&](const Part& part) {
    return part.dynamics->mass ? to_d(*part.dynamics->mass) : 0.0L;
  };
  auto inertia = [&](const Part& part) {
    return part.dynamics->moment_of_inertia ? to_d(*part.dynamics->moment_of_inertia) : 0.0L;
  };
  // ω² = num / den, kept when finite and above the best so far (a zero or missing mass or
  // inertia is the simulator's own refusal, not this estimate's)
  long double best_sq = 0;
  auto consider = [&](long double num, long double den, const std::string& pointer, const std::string& what) {
    if (!(den > 0) || !(num > 0)) return;
    long double sq = num / den;
    if (std::isnan(sq) || !(sq > best_sq)) return;
    best_sq = sq;
    best.pointer = pointer;
    best.what = what;
  };
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    if (!free[p]) continue;
    const Part& part = model.parts[p];
    const Dynamics& dyn = *part.dynamics;
    const std::string name = "part '" + part.name + "'";
    // (each message names the data that set the period: a mass or inertia near the doubles' end
    // is found at its pointer)
    const std::string mass_at = part.pointer + "/dynamics/mass", inertia_at = part.pointer + "/dynamics/moment_of_inertia";
    const bool rotates = part.motion.kind == Motion::Kind::rotation;
    if (dyn.torsional_spring)
      consider(to_d(dyn.torsional_spring->stiffness) * fs, inertia(part), part.pointer + "/dynamics/torsional_spring",
               "the torsional spring of " + name + " on its moment of inertia (" + inertia_at + ")");
    if (dyn.linear_spring)
      consider(to_d(dyn.linear_spring->stiffness) * fs, mass(part), part.pointer + "/dynamics/linear_spring",
               "the linear spring of " + name + " on its mass (" + mass_at + ")");
    if (rotates && g > 0)
      for (const auto& c : spec.centers_of_mass)
        if (c.part == p)
          consider(mass(part) * g * distance(c.at, part.motion.pivot), inertia(part), spec.pointer + "/gravity",
                   "gravity on " + name + " about its pivot (a pendulum: its mass " + mass_at + ", moment of inertia " +
                       inertia_at + ", centre of mass " + c.pointer + ")");
  }
  for (const auto& c : spec.couplings) {
    const long double k = to_d(c.stiffness) * fs;
    for (int end = 0; end < 2; ++end) {
      const std::size_t p = end == 0 ? c.first : c.second;
      if (!free[p]) continue;
      const Part& part = model.parts[p];
      const Point& at = end == 0 ? c.first_point : c.second_point;
      const std::string what = "the spring between parts '" + model.parts[c.first].name + "' and '" +
                               model.parts[c.second].name + "' on part '" + part.name + "'";
      const long double r = distance(at, part.motion.pivot);
      const std::string on_mass = what + " (its mass " + part.pointer + "/dynamics/mass)";
      const std::string on_inertia = what + " (its moment of inertia " + part.pointer + "/dynamics/moment_of_inertia)";
      switch (part.motion.kind) {
        case Motion::Kind::rotation:
          consider(k * r * r, inertia(part), c.pointer, on_inertia);
          break;
        case Motion::Kind::translation:
          consider(k, mass(part), c.pointer, on_mass);
          break;
        case Motion::Kind::planar: {
          consider(k, mass(part), c.pointer, on_mass);
          consider(k * r * r, inertia(part), c.pointer, on_inertia);
          // hung from the spring, the part swings about the attachment under its constant load
          const Dynamics& dyn = *part.dynamics;
          long double ax = to_d(spec.gravity.x) / (ts * ts), ay = to_d(spec.gravity.y) / (ts * ts);
          if (dyn.force && mass(part) > 0) {
            ax += to_d(dyn.force->x) * fs / mass(part);
            ay += to_d(dyn.force->y) * fs / mass(part);
          }
          consider(mass(part) * std::hypot(ax, ay) * r, inertia(part),
                   dyn.force ? part.pointer + "/dynamics/force" : spec.pointer + "/gravity",
                   "the load on part '" + part.name + "' hung from the spring between parts '" +
                       model.parts[c.first].name + "' and '" + model.parts[c.second].name + "' (a pendulum: its mass " + part.pointer + "/dynamics/mass, moment of inertia " +
                       part.pointer + "/dynamics/moment_of_inertia)");
          break;
        }
        default:
          break;
      }
    }
  }
  // (ω beyond the doubles' range, a spring at 1e308 mm from a pivot, is infinity: simulate says
  // "a period below 2π/DBL_MAX")
  if (best_sq > 0) best.omega = static_cast<double>(std::isfinite(best_sq) ? std::sqrt(best_sq) * ts : best_sq);
  return best;
}

}  // namespace hipair
