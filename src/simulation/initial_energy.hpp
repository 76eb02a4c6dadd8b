// HIPAIR — a simulation whose initial state's energy is not finite is bad input (session 72,
// jam72; Issue 11): refused at the pointer of the datum that puts it beyond the doubles.
//
// Until session 72 such a run (the ladder under gravity 1.79e308 mm/s^2, the pin-slot follower
// thrown at 1e160 mm/s) computed one step, found the energy not finite and stopped with exit 3,
// writing a trajectory of its initial state alone with "energy": null. No step of it can be
// computed: every step's end checks the energy (the three simulators' check_energy), and a state
// whose energy is beyond the doubles stays there. Session 71 (jam71) refused it after the fact
// with the simulator's stop message, which begins with "simulation: at t = ...", not with the
// place of the data (the seeded fuzz of `simulate` holds every exit 2 to begin with one); it was
// reverted. Now each simulator's create() refuses it before anything runs, its ModelError's
// pointer the offending datum.
//
// Which datum: the simulators' energies are sums of products of the model's data (kinetic
// m v^2 / 2 and I w^2 / 2, the work of gravity m g . x and of constant forces and torques, the
// springs' k (L - rest)^2 / 2, a pin-slot part's mass matrix m s^2, which overflows at rest too).
// Each product is listed with its factors as the file gives them (their pointers); the product of
// largest magnitude (by its factors' logarithms, so nothing overflows here) is the one beyond the
// doubles, and its largest factor is named. The unit conversions to the simulator's kg, mm, s (a
// factor 10^3 per ms or mN) move a product's logarithm by a few units only, far less than the
// ~300 between a finite energy and an overflowing one, so they are left out. Where no product
// comes within 10^6 of the doubles' end (a term this list does not hold), the largest datum in
// any of them is named, and the message says that is all it is.
#pragma once

#include "simulation/motion_datum.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace hipair::simulation {

// A factor of a product in the energy: the datum's pointer, what it is, and its magnitude.
struct EnergyFactor {
  std::string pointer;
  std::string name;
  double magnitude = 0;
};

// A product of data in the initial energy (`what`: "the kinetic energy of part 'ladder'")
struct EnergyTerm {
  std::string what;
  std::vector<EnergyFactor> factors;
};

inline double datum_magnitude(const Rational& value) {
  const double v = std::abs(value.get_d());
  return std::isfinite(v) ? v : std::numeric_limits<double>::max();
}

// log10 of a product's magnitude; -inf for a zero factor (the product is 0)
inline double log_magnitude(const EnergyTerm& term) {
  double sum = 0;
  for (const EnergyFactor& f : term.factors) {
    if (!(f.magnitude > 0)) return -std::numeric_limits<double>::infinity();
    sum += std::log10(f.magnitude);
  }
  return sum;
}

// The products of the model's data that make up a simulation's energy at its initial state
// (every part that moves, driven or not: a driver's kinetic energy is its motor's, its
// potential is counted; the springs between parts).
inline std::vector<EnergyTerm> initial_energy_terms(const Model& model) {
  std::vector<EnergyTerm> terms;
  if (!model.simulation) return terms;
  const SimulationSpec& spec = *model.simulation;
  const EnergyFactor gravity[2] = {{spec.pointer + "/gravity/0", "gravity", datum_magnitude(spec.gravity.x)},
                                   {spec.pointer + "/gravity/1", "gravity", datum_magnitude(spec.gravity.y)}};
  // a part's linear coordinates (mm) and its angle (rad) as given
  auto coordinates = [&](const Part& part, bool linear) {
    std::vector<EnergyFactor> out;
    const std::string at = part.pointer + "/initial/";
    if (linear) {
      if (part.motion.kind == Motion::Kind::planar) {
        out.push_back({at + "x", "initial x", datum_magnitude(part.initial.x)});
        out.push_back({at + "y", "initial y", datum_magnitude(part.initial.y)});
      } else if (part.motion.kind == Motion::Kind::translation || part.motion.kind == Motion::Kind::pin_slot) {
        out.push_back({at + "offset", "initial offset", datum_magnitude(part.initial.offset)});
      } else {   // a rotating part: gravity acts at its centre of mass, a bounded arm
        for (const auto& c : spec.centers_of_mass)
          if (&model.parts[c.part] == &part)
            out.push_back({c.pointer, "centre of mass",
                           std::max(datum_magnitude(c.at.x - part.motion.pivot.x), datum_magnitude(c.at.y - part.motion.pivot.y))});
      }
    } else if (part.motion.kind != Motion::Kind::translation) {
      out.push_back({at + "angle", "initial angle", datum_magnitude(part.initial.angle)});
    }
    return out;
  };
  // a spring's stretch: the larger of its coordinate and its rest (their difference is at most twice it)
  auto stretch = [](const EnergyFactor& coordinate, const EnergyFactor& rest) {
    return coordinate.magnitude >= rest.magnitude ? coordinate : rest;
  };
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    if (part.motion.kind == Motion::Kind::fixed || !part.dynamics) continue;
    const Dynamics& d = *part.dynamics;
    const std::string dyn = part.pointer + "/dynamics/";
    const std::string name = "part '" + part.name + "'";
    const EnergyFactor mass{dyn + "mass", "mass", d.mass ? datum_magnitude(*d.mass) : 0};
    const EnergyFactor inertia{dyn + "moment_of_inertia", "moment of inertia",
                               d.moment_of_inertia ? datum_magnitude(*d.moment_of_inertia) : 0};
    // kinetic: each velocity entry of the part (planar vx, vy, w; pin-slot slide, angle; one rate)
    std::size_t entry = 0;
    for (const auto& v : spec.velocities) {
      if (v.part != i) continue;
      std::string key;
      bool angular = part.motion.kind == Motion::Kind::rotation;
      if (part.motion.kind == Motion::Kind::planar) key = entry == 0 ? "/x" : entry == 1 ? "/y" : "/angle", angular = entry == 2;
      if (part.motion.kind == Motion::Kind::pin_slot) key = entry == 0 ? "/slide" : "/angle", angular = entry == 1;
      ++entry;
      const EnergyFactor speed{v.pointer + key, "initial velocity", datum_magnitude(v.value)};
      terms.push_back({"the kinetic energy of " + name, {angular ? inertia : mass, speed, speed}});
    }
    // a pin-slot part's mass matrix holds m s^2 (its slide s about the pin): beyond the doubles it
    // makes the kinetic energy not finite at any velocity, 0 included (infinity times 0)
    if (part.motion.kind == Motion::Kind::pin_slot)
      for (const EnergyFactor& x : coordinates(part, true)) terms.push_back({"the mass matrix of " + name, {mass, x, x}});
    // the work of gravity and of the constant force along the part's linear coordinates
    const std::vector<EnergyFactor> linear = coordinates(part, true);
    for (std::size_t j = 0; j < linear.size(); ++j)
      for (int k = 0; k < 2; ++k) {
        // (a planar part's x meets gravity's and the force's x, its y their y; an offset along its
        // direction, or a rotating part's arm, meets both)
        if (part.motion.kind == Motion::Kind::planar && static_cast<std::size_t>(k) != j) continue;
        const EnergyFactor& x = linear[j];
        terms.push_back({"the work of gravity on " + name, {mass, gravity[k], x}});
        if (d.force)
          terms.push_back({"the work of the force on " + name,
                           {{dyn + "force/" + std::to_string(k), "force", datum_magnitude(k == 0 ? d.force->x : d.force->y)}, x}});
      }
    for (const EnergyFactor& angle : coordinates(part, false)) {
      if (d.torque) terms.push_back({"the work of the torque on " + name, {{dyn + "torque", "torque", datum_magnitude(*d.torque)}, angle}});
      if (d.torsional_spring) {
        const EnergyFactor s = stretch(angle, {dyn + "torsional_spring/rest", "rest angle", datum_magnitude(d.torsional_spring->rest)});
        terms.push_back({"the torsional spring's energy of " + name,
                         {{dyn + "torsional_spring/stiffness", "stiffness", datum_magnitude(d.torsional_spring->stiffness)}, s, s}});
      }
    }
    if (d.linear_spring)
      for (const EnergyFactor& x : coordinates(part, true)) {
        const EnergyFactor s = stretch(x, {dyn + "linear_spring/rest", "rest offset", datum_magnitude(d.linear_spring->rest)});
        terms.push_back({"the linear spring's energy of " + name,
                         {{dyn + "linear_spring/stiffness", "stiffness", datum_magnitude(d.linear_spring->stiffness)}, s, s}});
      }
  }
  // the springs between parts: stiffness times the square of the larger of its points' and its
  // parts' coordinates and its rest length
  for (const SimulationSpec::Coupling& c : spec.couplings) {
    EnergyFactor reach{c.pointer + "/rest_length", "rest length", datum_magnitude(c.rest_length)};
    const EnergyFactor points[] = {
        {c.pointer + "/points/0", "point", std::max(datum_magnitude(c.first_point.x), datum_magnitude(c.first_point.y))},
        {c.pointer + "/points/1", "point", std::max(datum_magnitude(c.second_point.x), datum_magnitude(c.second_point.y))}};
    for (const EnergyFactor& p : points) reach = stretch(p, reach);
    for (std::size_t index : {c.first, c.second})
      for (const EnergyFactor& x : coordinates(model.parts[index], true)) reach = stretch(x, reach);
    terms.push_back({"the spring's energy", {{c.pointer + "/stiffness", "stiffness", datum_magnitude(c.stiffness)}, reach, reach}});
  }
  return terms;
}

// Refuses a simulation whose initial energy `energy` (the simulator's, internal units) is not
// finite: a ModelError at the largest factor of the largest product of data in it (or, where no
// product stands out, the largest velocity or load given).
inline void refuse_initial_energy(const Model& model, double energy) {
  if (std::isfinite(energy)) return;
  const std::vector<EnergyTerm> terms = initial_energy_terms(model);
  const EnergyTerm* largest = nullptr;
  double largest_log = -std::numeric_limits<double>::infinity();
  for (const EnergyTerm& t : terms) {
    const double l = log_magnitude(t);
    if (l > largest_log) largest_log = l, largest = &t;
  }
  std::ostringstream text;
  // (session 73, jam73: until then "so no step of the run can be computed", which is not true of
  // every such run — a dissipative impact may bring the energy back; but whether one will cannot
  // be known without running, and until then no state's energy can be published or checked)
  text << "the initial state's energy is not finite (beyond the doubles' range the simulator computes in), so the "
          "energy the run publishes with every state and checks at every step's end cannot be computed";
  if (!largest) {
    const std::string datum = largest_motion_datum(model);
    throw ModelError(model.simulation ? model.simulation->pointer : "", text.str() + datum + "; nothing was run or written");
  }
  // no product reaches the doubles' end (1.8e308 by 10^-6 at most): the terms above do not explain
  // it — the largest datum of them all is named, and said to be only that
  if (largest_log < std::log10(std::numeric_limits<double>::max()) - 6) {
    const EnergyFactor* datum = nullptr;
    for (const EnergyTerm& t : terms)
      for (const EnergyFactor& f : t.factors)
        if (!datum || f.magnitude > datum->magnitude) datum = &f;
    text << ": no product of the data in it reaches the doubles' end; the largest datum in it is the " << datum->name
         << " " << datum->pointer << " (" << datum->magnitude << ") (nothing was run or written)";
    throw ModelError(datum->pointer, text.str());
  }
  const EnergyFactor* named = &largest->factors.front();
  for (const EnergyFactor& f : largest->factors)
    if (f.magnitude > named->magnitude) named = &f;
  text << ": its largest term is " << largest->what << ", about 10^" << static_cast<long>(std::floor(largest_log))
       << " in the file's units, the product of";
  const char* separator = " ";
  std::vector<std::string> seen;
  for (const EnergyFactor& f : largest->factors) {
    if (std::find(seen.begin(), seen.end(), f.pointer) != seen.end()) continue;   // a square's factor once
    seen.push_back(f.pointer);
    text << separator << f.name << " " << f.pointer << " (" << f.magnitude << ")";
    separator = ", ";
  }
  text << "; give a smaller " << named->name << " (nothing was run or written)";
  throw ModelError(named->pointer, text.str());
}

}  // namespace hipair::simulation
