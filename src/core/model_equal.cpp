// Exact equality of two models, field by field (see model_equal.hpp).
#include "core/model_equal.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace hipair {
namespace {

// The sizes of the model types (x86-64, libstdc++) when every field below was compared: a field
// added to one of them changes its size, and the build stops here until the comparison below
// covers it (a flag that fits in existing padding would not change the size: add it to the
// comparison all the same). Other standard libraries have other sizes and skip the check: a
// field added without a comparison is caught by the next build with libstdc++ on x86-64.
#if defined(__GLIBCXX__) && defined(__x86_64__)
static_assert(sizeof(Point) == 64 && sizeof(Edge) == 304 && sizeof(Loop) == 64);
static_assert(sizeof(RationalInterval) == 64 && sizeof(Parameter) == 216 && sizeof(Rounding) == 128);
static_assert(sizeof(ProfileTolerance) == 104 && sizeof(Motion) == 312 && sizeof(PartConfiguration) == 128);
static_assert(sizeof(Spring) == 64 && sizeof(Dynamics) == 376 && sizeof(Part) == 936 && sizeof(PairSpec) == 168);
static_assert(sizeof(SimulationSpec) == 296 && sizeof(SimulationSpec::Velocity) == 72 &&
              sizeof(SimulationSpec::Driver) == 96 && sizeof(SimulationSpec::Coupling) == 272 &&
              sizeof(SimulationSpec::CenterOfMass) == 104);
static_assert(sizeof(Model) == 592);
#endif

// Rationals are compared exactly (mpq_equal: canonical values), every other leaf by ==.
bool same(const Rational& a, const Rational& b) { return a == b; }
bool same(const std::string& a, const std::string& b) { return a == b; }
bool same(bool a, bool b) { return a == b; }
bool same(std::size_t a, std::size_t b) { return a == b; }
template <class E>
  requires std::is_enum_v<E>
bool same(E a, E b) {
  return a == b;
}
template <class T>
bool same(const std::optional<T>& a, const std::optional<T>& b);
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b);
template <class A, class B>
bool same(const std::pair<A, B>& a, const std::pair<A, B>& b) {
  return same(a.first, b.first) && same(a.second, b.second);
}

bool same(const Point& a, const Point& b) { return same(a.x, b.x) && same(a.y, b.y); }
bool same(const Edge& a, const Edge& b) {
  return same(a.kind, b.kind) && same(a.source, b.source) && same(a.target, b.target) && same(a.center, b.center) &&
         same(a.ccw, b.ccw) && same(a.radius_squared, b.radius_squared) && same(a.pointer, b.pointer) &&
         same(a.label, b.label);
}
bool same(const Loop& a, const Loop& b) {
  return same(a.edges, b.edges) && same(a.is_hole, b.is_hole) && same(a.pointer, b.pointer);
}
bool same(const RationalInterval& a, const RationalInterval& b) { return same(a.lo, b.lo) && same(a.hi, b.hi); }
bool same(const Parameter& a, const Parameter& b) {
  return same(a.name, b.name) && same(a.nominal, b.nominal) && same(a.range, b.range) &&
         same(a.distribution, b.distribution) && same(a.sigma, b.sigma) && same(a.is_angle, b.is_angle) &&
         same(a.pointer, b.pointer);
}
bool same(const Rounding& a, const Rounding& b) {
  return same(a.pointer, b.pointer) && same(a.expression, b.expression) && same(a.value, b.value) &&
         same(a.bound, b.bound);
}
bool same(const ProfileTolerance& a, const ProfileTolerance& b) {
  return same(a.parameter, b.parameter) && same(a.part, b.part) && same(a.loop, b.loop) && same(a.pointer, b.pointer);
}
bool same(const Motion& a, const Motion& b) {
  return same(a.kind, b.kind) && same(a.pivot, b.pivot) && same(a.direction, b.direction) &&
         same(a.angle_limits, b.angle_limits) && same(a.translation_limits, b.translation_limits) &&
         same(a.pointer, b.pointer);
}
bool same(const PartConfiguration& a, const PartConfiguration& b) {
  return same(a.angle, b.angle) && same(a.offset, b.offset) && same(a.x, b.x) && same(a.y, b.y);
}
bool same(const Spring& a, const Spring& b) { return same(a.stiffness, b.stiffness) && same(a.rest, b.rest); }
bool same(const Dynamics& a, const Dynamics& b) {
  return same(a.mass, b.mass) && same(a.moment_of_inertia, b.moment_of_inertia) &&
         same(a.torsional_spring, b.torsional_spring) && same(a.linear_spring, b.linear_spring) &&
         same(a.torque, b.torque) && same(a.force, b.force) && same(a.damping, b.damping);
}
bool same(const Part& a, const Part& b) {
  return same(a.name, b.name) && same(a.loops, b.loops) && same(a.features, b.features) && same(a.motion, b.motion) &&
         same(a.initial, b.initial) && same(a.dynamics, b.dynamics) && same(a.pointer, b.pointer);
}
bool same(const PairSpec& a, const PairSpec& b) {
  return same(a.first, b.first) && same(a.second, b.second) && same(a.friction, b.friction) &&
         same(a.restitution, b.restitution) && same(a.pointer, b.pointer) && same(a.kinetic_friction, b.kinetic_friction);
}
bool same(const SimulationSpec::Velocity& a, const SimulationSpec::Velocity& b) {
  return same(a.part, b.part) && same(a.value, b.value) && same(a.pointer, b.pointer);
}
bool same(const SimulationSpec::Driver& a, const SimulationSpec::Driver& b) {
  return same(a.part, b.part) && same(a.speed, b.speed) && same(a.pointer, b.pointer) && same(a.profile, b.profile);
}
bool same(const SimulationSpec::Coupling& a, const SimulationSpec::Coupling& b) {
  return same(a.first, b.first) && same(a.second, b.second) && same(a.first_point, b.first_point) &&
         same(a.second_point, b.second_point) && same(a.stiffness, b.stiffness) &&
         same(a.rest_length, b.rest_length) && same(a.damping, b.damping) && same(a.pointer, b.pointer);
}
bool same(const SimulationSpec::CenterOfMass& a, const SimulationSpec::CenterOfMass& b) {
  return same(a.part, b.part) && same(a.at, b.at) && same(a.pointer, b.pointer);
}
bool same(const SimulationSpec& a, const SimulationSpec& b) {
  return same(a.time_unit, b.time_unit) && same(a.force_unit, b.force_unit) && same(a.gravity, b.gravity) &&
         same(a.velocities, b.velocities) && same(a.drivers, b.drivers) && same(a.couplings, b.couplings) &&
         same(a.centers_of_mass, b.centers_of_mass) && same(a.accuracy, b.accuracy) && same(a.pointer, b.pointer);
}

template <class T>
bool same(const std::optional<T>& a, const std::optional<T>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || same(*a, *b);
}
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

}  // namespace

bool same_model(const Model& a, const Model& b) {
  if (&a == &b) return true;
  // the cheap and most distinguishing fields first
  return same(a.content_hash, b.content_hash) && same(a.source, b.source) && same(a.name, b.name) &&
         same(a.parts, b.parts) && same(a.description, b.description) && same(a.angle_unit, b.angle_unit) &&
         same(a.parameters, b.parameters) && same(a.pairs, b.pairs) && same(a.pairs_explicit, b.pairs_explicit) &&
         same(a.simulation, b.simulation) && same(a.roundings, b.roundings) &&
         same(a.profile_tolerances, b.profile_tolerances);
}

}  // namespace hipair
