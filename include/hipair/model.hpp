// HIPAIR — the exact parametric model of a planar mechanism.
#pragma once

#include <hipair/geometry.hpp>
#include <hipair/rational.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>
#include <utility>

namespace hipair {

/// Closed interval [lo, hi] of exact rationals.
struct RationalInterval {
  Rational lo;
  Rational hi;
};

/// A named design parameter with its tolerance. Lengths in mm, angles in radians.
struct Parameter {
  enum class Distribution { none, uniform, normal };
  std::string name;
  Rational nominal;
  RationalInterval range;   ///< allowed values, lo <= nominal <= hi (== nominal when untoleranced)
  Distribution distribution = Distribution::none;
  std::optional<Rational> sigma;  ///< normal distribution only
  bool is_angle = false;          ///< declared with an angle unit
  std::string pointer;
};

/// A value the reader could not represent exactly and rounded to a rational.
struct Rounding {
  std::string pointer;     ///< where in the model file
  std::string expression;  ///< the text as written
  Rational value;          ///< the rational used
  Rational bound;          ///< |exact - value| <= bound (mm, rad, or unitless as the quantity)
};

/// A geometric profile tolerance (ISO 1101 / ASME Y14.5 surface profile): a band of total
/// width `band` around the nominal profile of one loop of a part, translated by the reader into
/// the ordinary parameter `parameter` (nominal 0, range [-band/2, band/2]): the loop's offset,
/// positive outward from the material (docs/model-format.md "Profile tolerances").
struct ProfileTolerance {
  std::string parameter;   ///< name of the offset parameter (in Model::parameters)
  std::size_t part = 0;    ///< index into Model::parts
  std::string loop;        ///< JSON pointer of the toleranced loop or feature
  std::string pointer;     ///< JSON pointer of the profile tolerance entry
};

/// How a part may move. A part's geometry is given in world coordinates at its zero
/// configuration; a configuration moves it rigidly.
///
/// Rotations are carried exactly through rational unit vectors: an angle given in the model
/// is represented by t = tan(theta/2) rounded to a rational (see Rounding), so that
/// cos = (1-t^2)/(1+t^2), sin = 2t/(1+t^2) are exact.
struct Motion {
  enum class Kind {
    fixed,        ///< the frame: no degree of freedom
    rotation,     ///< about `pivot`; coordinate theta (rad, counter-clockwise)
    translation,  ///< along unit vector `direction`; coordinate s (mm)
    planar,       ///< free in the plane: x, y (mm) and theta (rad) about `pivot`
    pin_slot      ///< rotation theta about `pivot`, then translation s along `direction`
                  ///< rotated with the part (a slotted part on a fixed pin)
  };
  Kind kind = Kind::fixed;
  Point pivot;       ///< rotation centre (rotation, planar, pin_slot)
  Point direction;   ///< exact rational unit vector (translation, pin_slot)
  std::optional<RationalInterval> angle_limits;        ///< rad
  std::optional<RationalInterval> translation_limits;  ///< mm
  std::string pointer;

  /// Number of degrees of freedom: 0, 1, 2 or 3.
  int degrees_of_freedom() const noexcept;
};

/// A configuration of one part: the coordinates its Motion uses (others stay zero).
struct PartConfiguration {
  Rational angle;        ///< theta, rad (rounded rational)
  Rational offset;       ///< s, mm (translation, pin_slot)
  Rational x;            ///< planar
  Rational y;            ///< planar
};

struct Spring {
  Rational stiffness;   ///< N·mm/rad (torsional) or N/mm (linear)
  Rational rest;        ///< rest angle (rad) or rest offset (mm)
};

/// Optional data for dynamical simulation.
struct Dynamics {
  std::optional<Rational> mass;                 ///< kg
  std::optional<Rational> moment_of_inertia;    ///< kg·mm^2 about the pivot
  std::optional<Spring> torsional_spring;
  std::optional<Spring> linear_spring;
  std::optional<Rational> torque;               ///< constant, N·mm, counter-clockwise positive
  std::optional<Point> force;                   ///< constant, N
  std::optional<Rational> damping;              ///< viscous coefficient
};

/// A rigid part.
struct Part {
  std::string name;
  std::vector<Loop> loops;              ///< outer boundaries and holes
  std::vector<std::string> features;    ///< templates the loops were expanded from (for reports)
  Motion motion;
  PartConfiguration initial;
  std::optional<Dynamics> dynamics;
  std::string pointer;
};

/// A pair of parts whose contacts are analysed, with its contact properties.
struct PairSpec {
  std::size_t first = 0;   ///< index into Model::parts
  std::size_t second = 0;
  /// Coulomb friction coefficient, static (mu_s): the scalar form "friction": mu, or
  /// "friction": {"static": mu_s, "kinetic": mu_k}. Absent: frictionless.
  std::optional<Rational> friction;
  std::optional<Rational> restitution;
  std::string pointer;
  /// Kinetic coefficient mu_k <= mu_s; absent: equal to `friction` (the scalar form).
  std::optional<Rational> kinetic_friction;
};

/// What a dynamical simulation needs beyond the parts' dynamics data (top-level key
/// "simulation", docs/model-format.md#simulation). Values are stored as written in the file's
/// declared units (angles in rad); hipair::Simulation converts them once, using `time_unit`
/// and `force_unit`, to its internal consistent system kg, mm, s (force kg·mm/s² = mN).
struct SimulationSpec {
  std::string time_unit = "s";     ///< "s" or "ms": unit of time of every rate in the file
  std::string force_unit = "N";    ///< "N" or "mN": unit of every force, torque, stiffness, damping
  Point gravity;                   ///< global acceleration, mm / time_unit^2
  /// Initial velocity of a moving part: rad / time_unit (rotation) or mm / time_unit.
  /// A planar part's initial velocity {"x": vx, "y": vy, "angle": omega} is three entries of
  /// that part, in the order vx, vy (its pivot's velocity, mm / time_unit), omega (rad /
  /// time_unit), each with the pointer of the velocity object.
  struct Velocity {
    std::size_t part = 0;
    Rational value;
    std::string pointer;
  };
  /// A driver whose coordinate follows a prescribed law instead of its dynamics:
  /// q(t) = q0 + speed * t (constant speed; rad or mm per time_unit), or a piecewise-linear
  /// speed profile.
  struct Driver {
    std::size_t part = 0;
    Rational speed;
    std::string pointer;
    /// law "speed_profile": (time, speed) points, times strictly increasing from 0; the speed
    /// is linear between them and keeps the last value after the last time; q(t) = q0 + the
    /// integral of the speed. Empty for "constant_speed" (then `speed`).
    std::vector<std::pair<Rational, Rational>> profile;
  };
  /// A linear spring and damper between a point of one part and a point of another (or of the
  /// frame: a fixed part). Points in world coordinates at the parts' zero configuration (mm).
  /// Force along the line: stiffness * (length - rest_length) + damping * d(length)/dt.
  struct Coupling {
    std::size_t first = 0, second = 0;
    Point first_point, second_point;
    Rational stiffness;            ///< force_unit / mm
    Rational rest_length;          ///< mm
    Rational damping;              ///< force_unit * time_unit / mm
    std::string pointer;
  };
  /// Centre of mass of a rotating part (world coordinates at its zero configuration, mm):
  /// where gravity acts. Default: the pivot (gravity exerts no torque).
  struct CenterOfMass {
    std::size_t part = 0;
    Point at;
    std::string pointer;
  };
  std::vector<Velocity> velocities;
  std::vector<Driver> drivers;
  std::vector<Coupling> couplings;
  std::vector<CenterOfMass> centers_of_mass;
  std::optional<Rational> accuracy;   ///< default integration accuracy (relative, > 0)
  std::string pointer;
};

/// A whole mechanism, exact.
struct Model {
  std::string name;
  std::string description;
  std::string angle_unit;                  ///< "rad" or "deg" as declared (values stored in rad)
  std::vector<Parameter> parameters;
  std::vector<Part> parts;
  std::vector<PairSpec> pairs;             ///< explicit, or every pair of parts (see docs)
  bool pairs_explicit = false;
  std::optional<SimulationSpec> simulation; ///< top-level "simulation" (docs/model-format.md)
  std::vector<Rounding> roundings;         ///< every inexact input that was rounded
  std::vector<ProfileTolerance> profile_tolerances; ///< as translated into parameters
  std::string source;                      ///< file name or "<string>"
  std::string content_hash;                ///< SHA-256 of the file bytes, hex

  /// Index of the part called `name`, or nullopt.
  std::optional<std::size_t> find_part(std::string_view name) const;
  /// The parameter called `name`, or nullptr.
  const Parameter* find_parameter(std::string_view name) const;
};

/// Options for reading a model.
struct ReadOptions {
  /// Override parameter values (name -> value) before evaluation; must lie in the
  /// parameter's tolerance range unless `allow_out_of_tolerance`.
  std::map<std::string, Rational> parameter_values;
  bool allow_out_of_tolerance = false;
  /// The overrides replace the parameters' nominal values, not only the values the geometry is
  /// built at (tolerance analysis of a changed design: `hipair tolerance --set`): a parameter's
  /// `tolerance` is then about the new nominal, a `range` stays where it is and must hold it.
  bool overrides_set_nominal = false;
};

/// Reads and validates a model from JSON text. \throws ModelError naming the JSON pointer.
Model read_model(std::string_view json_text, std::string_view source_name = "<string>",
                 const ReadOptions& options = {});

/// Reads and validates a model file. \throws IoError, ModelError.
Model read_model_file(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace hipair
