// HIPAIR — dynamical simulation of fixed-axis mechanisms with changing contacts
// (docs/simulation.md). Collision detection uses only the public hipair::CSpace adaptor: every
// integration step's motion of every pair is a MotionPath checked with the certified
// CSpace::first_crossing, so that no contact is skipped whatever the step size; impacts use the
// contact point and normal of the crossing, sustained contact the contact curve's derivatives.
// No CGAL, Eigen or Boost type appears here.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hipair {

/// Options of a simulation. Times and rates are in the model's time unit
/// (SimulationSpec::time_unit), positions in rad or mm.
struct SimulationOptions {
  /// Relative and absolute error tolerance per integration step (Dormand–Prince 5(4) with
  /// error control). 0: the model's "simulation"/"accuracy", or 1e-9.
  double accuracy = 0;
  /// Largest integration step (time unit); 0: no limit beyond error control. Events never
  /// depend on it: each step's motion is checked as a whole.
  double max_step = 0;
  /// Width of the certified crossing brackets: (step) / 2^crossing_bits.
  unsigned crossing_bits = 44;
  /// Build each pair's C-space as an operating region around the initial configuration
  /// (CSpaceBuildOptions::operating_region); leaving it is a GeometryError.
  bool operating_region = false;
  /// When operating_region is false: a pair whose two parts have more than this many boundary
  /// edges in all (a gear pair, whose whole torus holds z1 z2 tooth encounters and takes minutes
  /// to build) is built as its operating region, the other pairs whole. A motion cannot leave
  /// the region without crossing contact space: the region holds the whole flooded channel of
  /// the start. 0: every pair whole. `hipair simulate --region auto` (its default) sets 120, the
  /// size above which `hipair analyze` draws a pair's operating region.
  std::size_t operating_region_above_edges = 0;
  /// Called with the progress of the pairs' C-space builds (CSpaceBuildOptions::progress; the
  /// terminal's reporter is stderr_progress()); empty: none.
  CSpaceProgress build_progress;
  /// The pairs' C-spaces take the filtered quadratic traits where it applies
  /// (CSpaceBuildOptions::quadratic_traits); false: CGAL's algebraic traits for every chart (for
  /// tests that compare the two: the same exact C-space, certified extents of other widths).
  bool quadratic_traits = true;
  /// Stop with NumericError after this many steps (a runaway or Zeno run).
  std::size_t max_steps = 2000000;
  /// PlanarSimulation: the largest deviation (mm) of any point of the planar part between its
  /// closed-form path and the straight chords in (x, y, tan(theta/2)) that are tested for
  /// contact near the fixed parts. 0: accuracy x the part's reach from its pivot.
  double chord_deviation = 0;
};

/// The state of every part (model order); fixed parts have position and velocity 0.
struct SimulationState {
  double time = 0;
  std::vector<double> position;   ///< rad or mm
  std::vector<double> velocity;   ///< rad or mm per time unit
};

/// A contact event of one pair.
struct SimulationEvent {
  enum class Kind {
    impact,      ///< free -> contact with an impulse (Newton restitution)
    contact,     ///< sustained contact begins (after an impact that left no separating speed)
    lift_off,    ///< sustained contact ends: its force would turn negative
    edge_end,    ///< sustained contact reaches the end of its contact edge (a contact change)
    stick,       ///< a frictional contact begins to stick (relative tangential velocity 0)
    slip         ///< a frictional contact begins to slide (static limit reached, or from an impact)
  };
  Kind kind = Kind::impact;
  double time = 0;
  std::size_t pair = 0;                  ///< index into Model::pairs
  std::string first_part, second_part;
  std::vector<std::string> features;     ///< feature-pair labels ("pin / slot wall")
  EdgeId edge;                           ///< the contact edge (sustained contact), when known
  /// impact: normal impulse, force unit x time unit. For a contact met at a C-space vertex while
  /// sliding, or joined to an impact within the accuracy of closing, the impulse is along the
  /// contact's C-space normal (generalised units) and point/normal are 0 (docs/simulation.md).
  double impulse = 0;
  double normal_speed_before = 0;        ///< impact: approach speed along the contact normal (mm / time unit)
  double normal_speed_after = 0;
  std::array<double, 2> point{};         ///< world contact point (mm), approximate
  std::array<double, 2> normal{};        ///< unit normal, first part into second
  /// impact: tangential (Coulomb) impulse, force unit x time unit, along the tangent
  /// (-normal.y, normal.x), acting on the second part (0 without friction).
  double tangential_impulse = 0;
  /// stick / slip: the contact's normal force and friction force (force unit; the friction force
  /// along the tangent on the second part) at the event, and for slip the sliding direction
  /// (+1 / -1: the second part's contact point moves along +/- the tangent relative to the first).
  double normal_force = 0;
  double friction_force = 0;
  int slip_direction = 0;
  /// stick / slip of a planar part: true when the decision was made by exact rational
  /// arithmetic on the state (the rest class of docs/simulation.md, "Stick or slip, decided
  /// exactly"); false: decided in floating point, to the integrator's stated accuracy.
  bool exact_decision = false;
};

/// A sustained contact at the current state and its force from the contact complementarity
/// problem of all sustained contacts at once (docs/simulation.md). The force is the multiplier
/// of the contact's constraint g = sigma (q_y - Y(q_x)) >= 0 (or sigma (q_x - c)) in the
/// model's force unit, per unit of g: a force when g is an offset (mm), a torque (force unit x
/// mm) when g is an angle (rad).
struct SimulationContact {
  std::size_t pair = 0;                  ///< index into Model::pairs
  EdgeId edge;                           ///< the contact edge (invalid for a 1-D pair)
  std::vector<std::string> features;     ///< feature-pair labels of the edge
  double force = 0;                      ///< >= 0
  /// Coulomb friction (pairs with "friction" > 0 whose contact frame is defined): the physical
  /// normal force (force unit), the friction force along the tangent (-n_y, n_x) on the second
  /// part (force unit), and whether the contact sticks (else it slides, or is frictionless).
  double normal_force = 0;
  double friction_force = 0;
  bool sticking = false;
};

/// Refuses (ModelError at `/parts/N/initial/KEY`) an initial coordinate of a moving part that the
/// simulator's doubles cannot hold (magnitude above DBL_MAX). The model grammar takes exact
/// literals up to 10^1000, which `validate`, `cspace` and `analyze` handle exactly; a simulation
/// integrates in doubles. Every create() below calls it first.
void check_simulator_range(const Model& model);

/// Name of an event kind: "impact", "contact", "lift-off", "edge-end", "stick", "slip".
std::string to_string(SimulationEvent::Kind kind);

/// A simulation of a model with a "simulation" section (or none: all defaults).
class Simulation {
 public:
  /// Builds the C-spaces of the model's pairs whose parts move (once) and the initial state.
  /// \throws ModelError for dynamics data the simulator cannot use (a free part without mass,
  /// a linear spring on a rotating part, ...), GeometryError for pairs that are not fixed-axis.
  static Simulation create(const Model& model, const SimulationOptions& options = {});
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  /// One integration step; it ends exactly at the earliest contact event of any pair.
  /// \throws GeometryError when a part leaves a pair's built C-space (or its motion limits),
  /// NumericError when the integration fails.
  void step();
  /// Steps until `t_end` (the last step ends there exactly). `progress(t)` is called after
  /// each step when given.
  void run_until(double t_end, const std::function<void(double)>& progress = {});

  const SimulationState& state() const;
  const std::vector<SimulationEvent>& events() const;
  /// The sustained contacts at the current state, with their forces (solved at once).
  std::vector<SimulationContact> contacts() const;
  /// Kinetic energy plus the potential of springs, gravity and constant loads, in the model's
  /// force unit x mm.
  double energy() const;
  /// Accepted steps so far.
  std::size_t steps() const;
  /// The model and its pairs' C-spaces (index = Model::pairs index; null for pairs skipped
  /// because no part of them moves).
  const Model& model() const;
  const std::vector<std::shared_ptr<const CSpace>>& spaces() const;
  /// The time unit and force unit of the model ("s", "N", ...).
  const std::string& time_unit() const;
  const std::string& force_unit() const;

 private:
  struct Impl;
  explicit Simulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The state of a planar part (PlanarSimulation), in the model's units (mm, rad, time unit).
struct PlanarState {
  double time = 0;
  double x = 0, y = 0, angle = 0;       ///< the part's planar coordinates (shift, angle about its pivot)
  double vx = 0, vy = 0, omega = 0;     ///< their rates (the pivot is the centre of mass)
  /// The exact configuration of this state (x, y, tan(angle/2)): certified not blocked against
  /// every fixed part (free, or touching at an impact).
  SlicedConfiguration configuration;
  bool resting = false;                 ///< at rest in sustained contact (forces balanced)
};

/// Counts of a planar run's collision tests (docs/simulation.md, "Parts free in the plane").
struct PlanarStatistics {
  std::size_t advancement_steps = 0;    ///< free intervals certified by a distance bound
  std::size_t chord_tests = 0;          ///< chords tested with SlicedSpace::first_crossing
  std::size_t distance_queries = 0;     ///< SlicedSpace::features_near calls
  /// Frictional impacts whose restitution was scaled down because Newton's law with Coulomb
  /// friction would have created energy (docs/simulation.md).
  std::size_t restitution_limited = 0;
};

/// A simulation of one part free in the plane (motion "planar") among fixed parts: free flight
/// in closed form (gravity, constant force and torque, linear viscous damping), collision
/// detection by the pairs' exact 3-DOF C-spaces (hipair::SlicedSpace) so that no contact deeper
/// than the stated chord deviation is missed, impacts by Newton restitution at the contact
/// points and normals of the kernels (with Coulomb friction), sustained sliding, rocking and
/// sticking on vertex–segment contacts (forces from the complementarity problem, integrated
/// with error control), and resting contact (docs/simulation.md).
class PlanarSimulation {
 public:
  /// \throws ModelError when the model is not one planar part among fixed parts, or its
  /// dynamics data cannot be used (no mass or moment of inertia, springs, a driver, ...).
  static PlanarSimulation create(const Model& model, const SimulationOptions& options = {});
  PlanarSimulation(PlanarSimulation&&) noexcept;
  PlanarSimulation& operator=(PlanarSimulation&&) noexcept;
  ~PlanarSimulation();

  /// One step: free flight until `t_limit` (time unit) or the first contact, whichever is first;
  /// in sustained contact one integration step (or a step of its own for a contact change).
  /// \throws NumericError for a runaway of plastic impacts that hold no contact (contacts on
  /// arcs are not held), or an inconsistent frictional contact problem.
  void step(double t_limit);
  /// Steps until `t_end` (the last step ends there exactly).
  void run_until(double t_end, const std::function<void(double)>& progress = {});

  const PlanarState& state() const;
  const std::vector<SimulationEvent>& events() const;
  /// Kinetic energy plus the potential of gravity and the constant loads (force unit x mm).
  double energy() const;
  std::size_t steps() const;
  const PlanarStatistics& statistics() const;
  /// The chord deviation in use (mm) and the planar part's index in the model.
  double chord_deviation() const;
  std::size_t part() const;
  const Model& model() const;
  const std::string& time_unit() const;
  const std::string& force_unit() const;

 private:
  struct Impl;
  explicit PlanarSimulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The state of several planar parts (PlanarSystemSimulation): one PlanarState per planar part,
/// in `parts` order (model indices).
struct PlanarSystemState {
  double time = 0;
  std::vector<std::size_t> parts;      ///< model indices of the planar parts
  std::vector<PlanarState> states;     ///< per planar part (configuration: world, exact)
};

/// A simulation of several parts free in the plane among fixed parts (docs/simulation.md,
/// "Several planar parts"): every pair's contacts (planar–fixed and planar–planar, the latter
/// in the first part's frame: the second part's exact relative configuration in the pair's
/// 3-DOF C-space) by the certified far test and exact chords (SlicedSpace::first_crossing);
/// free flight integrated with error control (gravity, constant loads, damping, springs between
/// any two parts); frictionless Newton impacts of all contacts met at once. The class of inputs:
/// impacts that separate (restitution > 0, faster than the rest speed) and frictionless pairs;
/// a contact that would have to be sustained is a NumericError naming the parts.
class PlanarSystemSimulation {
 public:
  /// \throws ModelError when the model has no planar part or a part that is neither fixed nor
  /// planar, a planar part without mass or moment of inertia, a frictional pair of two moving
  /// parts (at the pair's pointer), or a start not apart (at the part's initial).
  static PlanarSystemSimulation create(const Model& model, const SimulationOptions& options = {});
  PlanarSystemSimulation(PlanarSystemSimulation&&) noexcept;
  PlanarSystemSimulation& operator=(PlanarSystemSimulation&&) noexcept;
  ~PlanarSystemSimulation();

  /// One integration step (until `t_limit` or the first impact).
  void step(double t_limit);
  void run_until(double t_end, const std::function<void(double)>& progress = {});
  const PlanarSystemState& state() const;
  const std::vector<SimulationEvent>& events() const;
  /// Kinetic energy plus the potential of gravity, constant loads and springs (force unit x mm).
  double energy() const;
  std::size_t steps() const;
  const PlanarStatistics& statistics() const;
  double chord_deviation() const;
  const Model& model() const;
  const std::string& time_unit() const;
  const std::string& force_unit() const;

 private:
  struct Impl;
  explicit PlanarSystemSimulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The model's own fastest motion (docs/simulation.md, "Stiff inputs"): the largest angular
/// frequency ω (rad per the model's time unit) of the free parts' springs and pendulums, read from
/// the dynamics data alone (nothing is built). Per free (not fixed, not driven) part: its own
/// spring, k/I or k/m; each spring between two parts at each free end, k/m for a translating part,
/// k·r²/I for a rotating one (r: the attachment point's distance from the pivot), both for a planar
/// part (r from its centre of mass); gravity about a rotating part's pivot, m·|g|·r/I (r: the centre
/// of mass's distance from it); a planar part hung from a spring, m·|g + F/m|·r/I per attachment.
/// An explicit integrator resolving that motion takes at least about one step per period 2π/ω, so
/// `simulate` refuses a run whose T·ω/2π exceeds its step budget before it starts. An estimate, not
/// a bound: a spring left at rest is never excited. ω = 0 (and `pointer` empty) when no such motion.
struct OwnFrequency {
  double omega = 0;      ///< rad per time unit of the model
  std::string pointer;   ///< JSON pointer of the data that sets it (a spring, the gravity)
  std::string what;      ///< what sets it, e.g. "the torsional spring of part 'balance'"
};
OwnFrequency own_frequency(const Model& model);

}  // namespace hipair
