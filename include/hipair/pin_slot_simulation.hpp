// HIPAIR — dynamical simulation of a pin-in-slot part (motion "pin_slot": turning by psi about
// the frame's pin and sliding by s along its slot) among fixed parts and rotating drivers
// (docs/simulation.md, "Pin-in-slot parts").
//
// The part moves in its own two coordinates (s, psi) by Lagrange's equations; contacts are
// found exactly in each pair's 3-DOF C-space (hipair::SlicedSpace; against a rotating driver in
// the driver's frame), impacts are Newton impacts in (s, psi). Class of inputs and what is
// certified: docs/simulation.md.
#pragma once

#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/simulation.hpp>
#include <hipair/sliced.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hipair {

/// A held (sustained) contact of the pin-slot part at a state.
struct PinSlotContact {
  std::size_t pair = 0;   ///< index into Model::pairs
  std::string feature;    ///< the feature pair's label
  double normal_force = 0;   ///< force unit: the contact LCP's multiplier at the last step's start
  /// force unit: its Coulomb friction force on the pin-slot part along the tangent (-n_y, n_x)
  /// (n the normal from the other part into the pin-slot part); 0 without friction
  double friction_force = 0;
};

/// The state of a pin-in-slot simulation, in the model's units (mm, rad, time unit).
struct PinSlotState {
  double time = 0;
  double slide = 0, angle = 0;             ///< the pin-slot part's s (mm) and psi (rad)
  double slide_rate = 0, angle_rate = 0;   ///< their rates
  /// Every part's coordinate (model order): psi for the pin-slot part, the drivers' angles (a
  /// torque-driven part's too), 0 for fixed parts.
  std::vector<double> position;
  /// Their rates (rad per time unit; 0 for fixed parts).
  std::vector<double> rate;
  /// The exact configuration of this state in every pair's 3-DOF C-space (the pin-slot part
  /// relative to the other part; index = the pair's index among the simulated pairs, in model
  /// order): certified free (a contact is met on its chord's free side, 2^-crossing_bits before).
  std::vector<SlicedConfiguration> pair_configurations;
  /// The held contacts (sustained contact: each kept at the hold gap 3/4 delta, its force from
  /// the contact complementarity problem).
  std::vector<PinSlotContact> contacts;
};

/// A simulation of one pin-in-slot part among fixed parts, parts rotating at a prescribed
/// constant speed (drivers) and at most one rotating part turned by a constant torque with its
/// own moment of inertia (its angle a third coordinate; session 59) and at most one translating
/// part pushed by the pin-slot part (its offset a coordinate, its limits stops): free flight of (s, psi) under gravity, a constant force and
/// torque, a linear spring on s and a torsional spring on psi (Lagrange's equations, integrated
/// with error control); every pair's contacts by straight chords in its exact 3-DOF C-space
/// (SlicedSpace::first_crossing) within the chord deviation of the path; Newton impacts in
/// (s, psi) with the driver's infinite inertia. A contact an impact leaves slower than the rest
/// speed is held: sustained contact, its force from the contact LCP over (s, psi), lifting off
/// where the force would turn negative.
class PinSlotSimulation {
 public:
  struct Impl;
  /// \throws ModelError when the model is not one pin-slot part among fixed parts, rotating
  /// drivers at constant speed, at most one torque-driven rotating part (moment of inertia and
  /// torque only) and at most one translating part (mass, force, linear spring, damping), or its
  /// dynamics data cannot be used (at the data's pointer);
  /// GeometryError when a pair's C-space cannot be built.
  static PinSlotSimulation create(const Model& model, const SimulationOptions& options = {});
  /// One step: free flight until `t_limit` (time unit) or the first contact.
  /// \throws GeometryError when the part leaves its slide or angle limits, NumericError for a
  /// contact that would have to be sustained between feature kinds a held contact does not take.
  void step(double t_limit);
  void run_until(double t_end, const std::function<void(double)>& progress = {});
  const PinSlotState& state() const;
  const std::vector<SimulationEvent>& events() const;
  std::size_t steps() const;
  /// Chords tested exactly (SlicedSpace::first_crossing calls).
  std::size_t chord_tests() const;
  /// Kinetic energy plus the potential of gravity, the constant loads and the springs
  /// (force unit x mm); a torque-driven part's kinetic energy and its torque's potential -T phi
  /// included.
  double energy() const;
  /// The energy the run has removed (force unit x mm): the impacts' losses (Newton restitution)
  /// and the projections of held contacts onto their hold gap and zero normal speed. Between
  /// these jumps energy() is kept by the integration: energy() + dissipated() stays at its start.
  double dissipated() const;
  /// The chord deviation in use (mm) and the pin-slot part's index in the model.
  double chord_deviation() const;
  std::size_t part() const;
  const Model& model() const;
  /// The model's time unit and force unit ("s", "N", ...).
  const std::string& time_unit() const;
  const std::string& force_unit() const;

  PinSlotSimulation(PinSlotSimulation&&) noexcept;
  PinSlotSimulation& operator=(PinSlotSimulation&&) noexcept;
  ~PinSlotSimulation();

 private:
  explicit PinSlotSimulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hipair
