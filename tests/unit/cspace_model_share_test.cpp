// A built space keeps a copy of its model; an equal copy still held by a live space built on
// the same thread is shared instead of copied again (cspace/builder_model.cpp, model_copy).
// The equality is core/model_equal's same_model, field by field: these tests change every
// field of every model type one at a time (same_model must see each change), and check that a
// space holds a model equal to the one it was built from, shared only when equal.
#include "core/model_equal.hpp"
#include "cspace/builder_impl.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

Model example(const char* name) { return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name); }

// Every optional and vector of the model types given one value (or element), so that a change
// of any field has something to change.
void fill_everything(Model& m) {
  Parameter parameter;
  parameter.name = "p";
  parameter.nominal = Rational(1, 3);
  parameter.range = {Rational(0), Rational(1)};
  parameter.distribution = Parameter::Distribution::normal;
  parameter.sigma = Rational(1, 10);
  parameter.is_angle = false;
  parameter.pointer = "/parameters/p";
  m.parameters.push_back(parameter);
  m.roundings.push_back(Rounding{"/r", "pi", Rational(355, 113), Rational(1, 1000000)});
  m.profile_tolerances.push_back(ProfileTolerance{"p", 0, "/parts/0/loops/0", "/parts/0/profile"});
  Part& part = m.parts.at(0);
  part.features.push_back("template");
  part.motion.angle_limits = RationalInterval{Rational(-1), Rational(1)};
  part.motion.translation_limits = RationalInterval{Rational(-5), Rational(7)};
  Dynamics dynamics;
  dynamics.mass = Rational(2);
  dynamics.moment_of_inertia = Rational(3);
  dynamics.torsional_spring = Spring{Rational(4), Rational(5)};
  dynamics.linear_spring = Spring{Rational(6), Rational(7)};
  dynamics.torque = Rational(8);
  dynamics.force = Point{Rational(9), Rational(10)};
  dynamics.damping = Rational(11);
  part.dynamics = dynamics;
  if (m.pairs.empty()) m.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "", std::nullopt});
  m.pairs.front().friction = Rational(1, 4);
  m.pairs.front().restitution = Rational(1, 2);
  m.pairs.front().kinetic_friction = Rational(1, 5);
  SimulationSpec simulation;
  simulation.gravity = Point{Rational(0), Rational(-9810)};
  simulation.velocities.push_back(SimulationSpec::Velocity{0, Rational(1), "/v"});
  simulation.drivers.push_back(SimulationSpec::Driver{0, Rational(2), "/d", {{Rational(0), Rational(1)}}});
  simulation.couplings.push_back(SimulationSpec::Coupling{0, 1, Point{Rational(1), Rational(2)},
                                                          Point{Rational(3), Rational(4)}, Rational(5), Rational(6),
                                                          Rational(7), "/c"});
  simulation.centers_of_mass.push_back(SimulationSpec::CenterOfMass{0, Point{Rational(1), Rational(1)}, "/m"});
  simulation.accuracy = Rational(1, 1000);
  simulation.pointer = "/simulation";
  m.simulation = simulation;
}

// One change per field of every model type (a rational by 1/7 or a tiny amount, a string by a
// character, a flag, an index, an enum, an optional emptied, a vector's length).
std::vector<std::pair<std::string, std::function<void(Model&)>>> changes() {
  const Rational tiny(1, mpz_class(1) << 200);
  auto bump = [tiny](Rational& q) {
    q += tiny;
    q.canonicalize();
  };
  auto edge = [](Model& m) -> Edge& { return m.parts.at(0).loops.at(0).edges.at(0); };
  auto part = [](Model& m) -> Part& { return m.parts.at(0); };
  auto sim = [](Model& m) -> SimulationSpec& { return *m.simulation; };
  std::vector<std::pair<std::string, std::function<void(Model&)>>> c;
  auto add = [&](std::string name, std::function<void(Model&)> f) { c.emplace_back(std::move(name), std::move(f)); };
  // Model
  add("name", [](Model& m) { m.name += "x"; });
  add("description", [](Model& m) { m.description += "x"; });
  add("angle_unit", [](Model& m) { m.angle_unit += "x"; });
  add("parameters size", [](Model& m) { m.parameters.pop_back(); });
  add("parts size", [](Model& m) { m.parts.push_back(m.parts.back()); });
  add("pairs size", [](Model& m) { m.pairs.push_back(m.pairs.back()); });
  add("pairs_explicit", [](Model& m) { m.pairs_explicit = !m.pairs_explicit; });
  add("simulation", [](Model& m) { m.simulation.reset(); });
  add("roundings size", [](Model& m) { m.roundings.clear(); });
  add("profile_tolerances size", [](Model& m) { m.profile_tolerances.clear(); });
  add("source", [](Model& m) { m.source += "x"; });
  add("content_hash", [](Model& m) { m.content_hash += "0"; });
  // Parameter
  add("parameter name", [](Model& m) { m.parameters.back().name += "x"; });
  add("parameter nominal", [bump](Model& m) { bump(m.parameters.back().nominal); });
  add("parameter range lo", [bump](Model& m) { bump(m.parameters.back().range.lo); });
  add("parameter range hi", [bump](Model& m) { bump(m.parameters.back().range.hi); });
  add("parameter distribution", [](Model& m) { m.parameters.back().distribution = Parameter::Distribution::uniform; });
  add("parameter sigma", [bump](Model& m) { bump(*m.parameters.back().sigma); });
  add("parameter sigma absent", [](Model& m) { m.parameters.back().sigma.reset(); });
  add("parameter is_angle", [](Model& m) { m.parameters.back().is_angle = true; });
  add("parameter pointer", [](Model& m) { m.parameters.back().pointer += "x"; });
  // Rounding, ProfileTolerance
  add("rounding pointer", [](Model& m) { m.roundings.back().pointer += "x"; });
  add("rounding expression", [](Model& m) { m.roundings.back().expression += "x"; });
  add("rounding value", [bump](Model& m) { bump(m.roundings.back().value); });
  add("rounding bound", [bump](Model& m) { bump(m.roundings.back().bound); });
  add("profile parameter", [](Model& m) { m.profile_tolerances.back().parameter += "x"; });
  add("profile part", [](Model& m) { m.profile_tolerances.back().part += 1; });
  add("profile loop", [](Model& m) { m.profile_tolerances.back().loop += "x"; });
  add("profile pointer", [](Model& m) { m.profile_tolerances.back().pointer += "x"; });
  // Part
  add("part name", [part](Model& m) { part(m).name += "x"; });
  add("part loops size", [part](Model& m) { part(m).loops.push_back(part(m).loops.back()); });
  add("part features", [part](Model& m) { part(m).features.back() += "x"; });
  add("part initial angle", [part, bump](Model& m) { bump(part(m).initial.angle); });
  add("part initial offset", [part, bump](Model& m) { bump(part(m).initial.offset); });
  add("part initial x", [part, bump](Model& m) { bump(part(m).initial.x); });
  add("part initial y", [part, bump](Model& m) { bump(part(m).initial.y); });
  add("part dynamics absent", [part](Model& m) { part(m).dynamics.reset(); });
  add("part pointer", [part](Model& m) { part(m).pointer += "x"; });
  // Loop, Edge
  add("loop is_hole", [part](Model& m) { part(m).loops.at(0).is_hole = !part(m).loops.at(0).is_hole; });
  add("loop pointer", [part](Model& m) { part(m).loops.at(0).pointer += "x"; });
  add("loop edges size", [part](Model& m) { part(m).loops.at(0).edges.pop_back(); });
  add("edge kind", [edge](Model& m) { edge(m).kind = edge(m).is_arc() ? Edge::Kind::segment : Edge::Kind::arc; });
  add("edge source x", [edge, bump](Model& m) { bump(edge(m).source.x); });
  add("edge source y", [edge, bump](Model& m) { bump(edge(m).source.y); });
  add("edge target x", [edge, bump](Model& m) { bump(edge(m).target.x); });
  add("edge target y", [edge, bump](Model& m) { bump(edge(m).target.y); });
  add("edge center x", [edge, bump](Model& m) { bump(edge(m).center.x); });
  add("edge center y", [edge, bump](Model& m) { bump(edge(m).center.y); });
  add("edge ccw", [edge](Model& m) { edge(m).ccw = !edge(m).ccw; });
  add("edge radius_squared", [edge, bump](Model& m) { bump(edge(m).radius_squared); });
  add("edge pointer", [edge](Model& m) { edge(m).pointer += "x"; });
  add("edge label", [edge](Model& m) { edge(m).label += "x"; });
  // Motion
  add("motion kind", [part](Model& m) {
    part(m).motion.kind = part(m).motion.kind == Motion::Kind::fixed ? Motion::Kind::rotation : Motion::Kind::fixed;
  });
  add("motion pivot x", [part, bump](Model& m) { bump(part(m).motion.pivot.x); });
  add("motion pivot y", [part, bump](Model& m) { bump(part(m).motion.pivot.y); });
  add("motion direction x", [part, bump](Model& m) { bump(part(m).motion.direction.x); });
  add("motion direction y", [part, bump](Model& m) { bump(part(m).motion.direction.y); });
  add("motion angle_limits lo", [part, bump](Model& m) { bump(part(m).motion.angle_limits->lo); });
  add("motion angle_limits absent", [part](Model& m) { part(m).motion.angle_limits.reset(); });
  add("motion translation_limits hi", [part, bump](Model& m) { bump(part(m).motion.translation_limits->hi); });
  add("motion translation_limits absent", [part](Model& m) { part(m).motion.translation_limits.reset(); });
  add("motion pointer", [part](Model& m) { part(m).motion.pointer += "x"; });
  // Dynamics, Spring
  add("dynamics mass", [part, bump](Model& m) { bump(*part(m).dynamics->mass); });
  add("dynamics moment_of_inertia", [part, bump](Model& m) { bump(*part(m).dynamics->moment_of_inertia); });
  add("dynamics torsional stiffness", [part, bump](Model& m) { bump(part(m).dynamics->torsional_spring->stiffness); });
  add("dynamics torsional rest", [part, bump](Model& m) { bump(part(m).dynamics->torsional_spring->rest); });
  add("dynamics linear stiffness", [part, bump](Model& m) { bump(part(m).dynamics->linear_spring->stiffness); });
  add("dynamics linear rest", [part, bump](Model& m) { bump(part(m).dynamics->linear_spring->rest); });
  add("dynamics linear absent", [part](Model& m) { part(m).dynamics->linear_spring.reset(); });
  add("dynamics torque", [part, bump](Model& m) { bump(*part(m).dynamics->torque); });
  add("dynamics force x", [part, bump](Model& m) { bump(part(m).dynamics->force->x); });
  add("dynamics force y", [part, bump](Model& m) { bump(part(m).dynamics->force->y); });
  add("dynamics damping", [part, bump](Model& m) { bump(*part(m).dynamics->damping); });
  add("dynamics damping absent", [part](Model& m) { part(m).dynamics->damping.reset(); });
  // PairSpec
  add("pair first", [](Model& m) { m.pairs.front().first += 1; });
  add("pair second", [](Model& m) { m.pairs.front().second += 1; });
  add("pair friction", [bump](Model& m) { bump(*m.pairs.front().friction); });
  add("pair restitution", [bump](Model& m) { bump(*m.pairs.front().restitution); });
  add("pair pointer", [](Model& m) { m.pairs.front().pointer += "x"; });
  add("pair kinetic_friction", [bump](Model& m) { bump(*m.pairs.front().kinetic_friction); });
  add("pair kinetic_friction absent", [](Model& m) { m.pairs.front().kinetic_friction.reset(); });
  // SimulationSpec and its parts
  add("simulation time_unit", [sim](Model& m) { sim(m).time_unit = "ms"; });
  add("simulation force_unit", [sim](Model& m) { sim(m).force_unit = "mN"; });
  add("simulation gravity x", [sim, bump](Model& m) { bump(sim(m).gravity.x); });
  add("simulation gravity y", [sim, bump](Model& m) { bump(sim(m).gravity.y); });
  add("simulation velocities size", [sim](Model& m) { sim(m).velocities.clear(); });
  add("simulation velocity part", [sim](Model& m) { sim(m).velocities.back().part += 1; });
  add("simulation velocity value", [sim, bump](Model& m) { bump(sim(m).velocities.back().value); });
  add("simulation velocity pointer", [sim](Model& m) { sim(m).velocities.back().pointer += "x"; });
  add("simulation drivers size", [sim](Model& m) { sim(m).drivers.clear(); });
  add("simulation driver part", [sim](Model& m) { sim(m).drivers.back().part += 1; });
  add("simulation driver speed", [sim, bump](Model& m) { bump(sim(m).drivers.back().speed); });
  add("simulation driver pointer", [sim](Model& m) { sim(m).drivers.back().pointer += "x"; });
  add("simulation driver profile time", [sim, bump](Model& m) { bump(sim(m).drivers.back().profile.back().first); });
  add("simulation driver profile speed", [sim, bump](Model& m) { bump(sim(m).drivers.back().profile.back().second); });
  add("simulation driver profile size", [sim](Model& m) { sim(m).drivers.back().profile.clear(); });
  add("simulation couplings size", [sim](Model& m) { sim(m).couplings.clear(); });
  add("simulation coupling first", [sim](Model& m) { sim(m).couplings.back().first += 1; });
  add("simulation coupling second", [sim](Model& m) { sim(m).couplings.back().second += 1; });
  add("simulation coupling first_point", [sim, bump](Model& m) { bump(sim(m).couplings.back().first_point.x); });
  add("simulation coupling second_point", [sim, bump](Model& m) { bump(sim(m).couplings.back().second_point.y); });
  add("simulation coupling stiffness", [sim, bump](Model& m) { bump(sim(m).couplings.back().stiffness); });
  add("simulation coupling rest_length", [sim, bump](Model& m) { bump(sim(m).couplings.back().rest_length); });
  add("simulation coupling damping", [sim, bump](Model& m) { bump(sim(m).couplings.back().damping); });
  add("simulation coupling pointer", [sim](Model& m) { sim(m).couplings.back().pointer += "x"; });
  add("simulation centers_of_mass size", [sim](Model& m) { sim(m).centers_of_mass.clear(); });
  add("simulation center part", [sim](Model& m) { sim(m).centers_of_mass.back().part += 1; });
  add("simulation center at", [sim, bump](Model& m) { bump(sim(m).centers_of_mass.back().at.y); });
  add("simulation center pointer", [sim](Model& m) { sim(m).centers_of_mass.back().pointer += "x"; });
  add("simulation accuracy", [sim, bump](Model& m) { bump(*sim(m).accuracy); });
  add("simulation accuracy absent", [sim](Model& m) { sim(m).accuracy.reset(); });
  add("simulation pointer", [sim](Model& m) { sim(m).pointer += "x"; });
  return c;
}

TEST(CSpaceModelShare, SameModelSeesAChangeOfEveryFieldOnExampleModels) {
  const auto all = changes();
  std::size_t models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_EXAMPLES))) {
    if (entry.path().extension() != ".json") continue;
    Model base;
    try {
      base = read_model_file(entry.path());
    } catch (const std::exception&) {
      continue;   // templates that are not models by themselves
    }
    if (base.parts.size() < 2 || base.parts.at(0).loops.empty() || base.parts.at(0).loops.at(0).edges.size() < 2)
      continue;
    ++models;
    Model read_again = read_model_file(entry.path());
    EXPECT_TRUE(same_model(base, read_again)) << entry.path();
    fill_everything(base);
    Model copy = base;
    EXPECT_TRUE(same_model(base, copy)) << entry.path();
    EXPECT_TRUE(same_model(copy, base)) << entry.path();
    for (const auto& [name, change] : all) {
      Model changed = base;
      change(changed);
      EXPECT_FALSE(same_model(base, changed)) << entry.path() << ": " << name;
      EXPECT_FALSE(same_model(changed, base)) << entry.path() << ": " << name;
      Model changed_again = base;
      change(changed_again);
      EXPECT_TRUE(same_model(changed, changed_again)) << entry.path() << ": " << name;
    }
  }
  EXPECT_GE(models, 20u);
}

const std::shared_ptr<const Model>& model_of(const CSpace& space) { return cspace::impl_of(space).model; }

// Two translating pairs (a polygon pair and a part against a fixed guide) and a rotating one: equal models (distinct objects) share the copy of
// a live space; a model that differs in one place gets its own copy, equal to it; a space's
// model is always equal to the model it was built from.
TEST(CSpaceModelShare, SpacesShareOnlyEqualModels) {
  const std::vector<std::pair<const char*, std::pair<const char*, const char*>>> pairs = {
      {"two-pin-wedge.json", {"wedge", "plunger"}}, {"cam-drive.json", {"follower", "guide"}},
      {"cam-follower.json", {"cam", "follower"}}};
  for (const auto& [file, names] : pairs) {
    Model model = example(file);
    const std::string first = names.first, second = names.second;
    CSpace a = CSpace::build(model, first, second);
    ASSERT_TRUE(model_of(a));
    EXPECT_NE(model_of(a).get(), &model) << file;
    EXPECT_TRUE(same_model(*model_of(a), model)) << file;
    Model equal = example(file);
    CSpace b = CSpace::build(equal, first, second);
    EXPECT_EQ(model_of(b).get(), model_of(a).get()) << file << ": an equal model shares the live copy";
    // a change that the builder does not read (a label of an edge, a description) still gives
    // a model of its own, equal to the changed one
    for (int k = 0; k < 3; ++k) {
      Model changed = model;
      if (k == 0) changed.description += " (changed)";
      if (k == 1) changed.parts.back().loops.at(0).edges.at(0).label += "x";
      if (k == 2) {
        Rational& y = changed.parts.back().initial.offset;
        y += Rational(1, mpz_class(1) << 300);
        y.canonicalize();
      }
      CSpace c = CSpace::build(changed, first, second);
      EXPECT_NE(model_of(c).get(), model_of(a).get()) << file << " change " << k;
      EXPECT_TRUE(same_model(*model_of(c), changed)) << file << " change " << k;
      EXPECT_FALSE(same_model(*model_of(c), model)) << file << " change " << k;
      // the changed space's copy is now the thread's last one; the first model gets a new copy
      // while `c` lives, equal to it
      CSpace d = CSpace::build(model, first, second);
      EXPECT_TRUE(same_model(*model_of(d), model)) << file << " change " << k;
      EXPECT_EQ(a.statistics().vertices, d.statistics().vertices) << file;
      EXPECT_EQ(a.statistics().edges, d.statistics().edges) << file;
    }
  }
}

}  // namespace
}  // namespace hipair
