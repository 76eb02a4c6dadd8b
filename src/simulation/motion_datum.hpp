// HIPAIR — the velocity or load of a model's simulation data that a stop beyond the doubles'
// range names (shared by the planar and fixed-axis simulators; session 65 moved it here from
// planar.cpp for the fixed-axis energy stop).
#pragma once

#include <hipair/model.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace hipair::simulation {

// The velocity or load given whose magnitude is the largest (velocities, drivers' speeds, gravity,
// forces, torques, as the file gives them), named at its pointer: what a "not finite" stop of a
// planar run adds to its message (session 61, hunt61: a block thrown at 1.8e308 mm/s, gravity
// or a pusher's speed near the doubles' end stopped with exit 3 and no pointer).
inline std::string largest_motion_datum(const Model& model) {
  if (!model.simulation) return "";
  const SimulationSpec& spec = *model.simulation;
  double largest = -1;
  std::string at;
  auto consider = [&](const Rational& value, const std::string& pointer) {
    const double v = std::abs(value.get_d());
    if (v > largest) largest = v, at = pointer;
  };
  for (const auto& v : spec.velocities) consider(v.value, v.pointer);
  for (const auto& d : spec.drivers) {
    consider(d.speed, d.pointer);
    for (const auto& point : d.profile) consider(point.second, d.pointer + "/profile");
  }
  consider(spec.gravity.x, spec.pointer + "/gravity/0");
  consider(spec.gravity.y, spec.pointer + "/gravity/1");
  for (const Part& part : model.parts) {
    if (!part.dynamics) continue;
    if (part.dynamics->force) {
      consider(part.dynamics->force->x, part.pointer + "/dynamics/force/0");
      consider(part.dynamics->force->y, part.pointer + "/dynamics/force/1");
    }
    if (part.dynamics->torque) consider(*part.dynamics->torque, part.pointer + "/dynamics/torque");
  }
  if (at.empty()) return "";
  std::ostringstream out;
  out << "; the largest velocity or load given is " << at << " (" << largest << ")";
  return out.str();
}

// A run whose energy left the doubles' range (session 65, sim65: it ended with exit 0 and
// `"energy": null`): the stop's message, at `where` (the simulator's "simulation: at t = ..."),
// naming the moving parts (`parts`: "part 'ladder' (/parts/1/dynamics, moving at ...)"); the
// caller adds the largest velocity or load given (largest_motion_datum). Like the other stops
// beyond the doubles, nothing is written.
inline std::string energy_overflow_message(const std::string& where, const std::string& parts) {
  return where + ": the run's energy is not finite (beyond the doubles' range: a kinetic energy m v^2/2 or a load's "
                 "work overflows), so the run stops there (smaller loads or velocities, or a shorter --t-end, keep it "
                 "within); the moving parts: " + parts;
}

}  // namespace hipair::simulation
