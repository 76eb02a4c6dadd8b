// HIPAIR — the simulator's one conversion of the model's units (docs/simulation.md, "Model data
// and units"): internal time in s, force in kg·mm/s² = mN.
#pragma once

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

namespace hipair::simulation {

/// Seconds per time unit of the model ("s" or "ms").
inline double seconds_per(const SimulationSpec& spec) { return spec.time_unit == "ms" ? 1e-3 : 1.0; }
/// mN (kg·mm/s²) per force unit of the model ("N" or "mN").
inline double millinewtons_per(const SimulationSpec& spec) { return spec.force_unit == "mN" ? 1.0 : 1000.0; }

/// The set-up every simulator's create starts with (the fixed-axis Simulation, PlanarSimulation,
/// PlanarSystemSimulation), after its check_simulator_range: the model and options kept, the
/// model's units and their scales, and gravity in internal units (mm/s²). `State` is the
/// simulator's state (its model, options, time_unit, force_unit, time_scale, force_scale and
/// g[2]). Returns the model's simulation data, or the defaults when it has none.
template <class State>
SimulationSpec start_simulation(State& s, const Model& model, const SimulationOptions& options) {
  s.model = model;
  s.options = options;
  SimulationSpec spec = model.simulation.value_or(SimulationSpec{});
  s.time_unit = spec.time_unit;
  s.force_unit = spec.force_unit;
  s.time_scale = seconds_per(spec);
  s.force_scale = millinewtons_per(spec);   // internal force: kg mm / s^2 = mN
  s.g[0] = spec.gravity.x.get_d() / (s.time_scale * s.time_scale);
  s.g[1] = spec.gravity.y.get_d() / (s.time_scale * s.time_scale);
  return spec;
}

/// The integration accuracy: the options' when given, else the model's, else 1e-9.
inline double simulation_accuracy(const SimulationOptions& options, const SimulationSpec& spec) {
  return options.accuracy > 0 ? options.accuracy : spec.accuracy ? spec.accuracy->get_d() : 1e-9;
}

/// A planar body's constant loads in internal units from its dynamics data (`fs`, `ts`: the
/// force and time scales, `g`: gravity in internal units): mass, moment of inertia, force,
/// torque, damping rate, torsional spring, and the accelerations they give it alone (`accel`,
/// `alpha`). `Body` holds those members (PlanarSimulation's state, a PlanarSystemSimulation body).
template <class Body>
void set_planar_loads(Body& b, const Dynamics& dyn, double fs, double ts, const double (&g)[2]) {
  b.mass = dyn.mass->get_d();
  b.inertia = dyn.moment_of_inertia->get_d();
  if (dyn.force) {
    b.force[0] = dyn.force->x.get_d() * fs;
    b.force[1] = dyn.force->y.get_d() * fs;
  }
  if (dyn.torque) b.torque = dyn.torque->get_d() * fs;
  if (dyn.damping) b.damping_rate = dyn.damping->get_d() * fs * ts / b.mass;
  if (dyn.torsional_spring) {
    b.torsion_k = dyn.torsional_spring->stiffness.get_d() * fs;
    b.torsion_rest = dyn.torsional_spring->rest.get_d();
  }
  b.accel[0] = g[0] + b.force[0] / b.mass;
  b.accel[1] = g[1] + b.force[1] / b.mass;
  b.alpha = b.torque / b.inertia;
}

}  // namespace hipair::simulation
