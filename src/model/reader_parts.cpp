// Reader steps for parts: loops and edges, feature templates, motions, initial
// configurations, dynamics; each part's geometry is validated and oriented exactly.
#include "model/reader.hpp"

#include "core/angle_limits.hpp"
#include "model/validate_geometry.hpp"

#include <hipair/error.hpp>

namespace hipair::model_detail {
namespace {

constexpr std::size_t max_feature_count = 10000;

}  // namespace

void Reader::read_parts(const JsonValue& parts) {
  expect_array(parts, "an array of parts");
  if (parts.items.empty()) throw ModelError(parts.pointer, "a model needs at least one part");
  std::map<std::string, std::string> names;
  for (const JsonValue& part_value : parts.items) {
    Part part = read_part(part_value);
    auto [where, inserted] = names.emplace(part.name, part.pointer);
    if (!inserted)
      throw ModelError(part_value.pointer + "/name",
                       "duplicate part name '" + part.name + "' (also " + where->second + ")");
    model_.parts.push_back(std::move(part));
  }
}

Part Reader::read_part(const JsonValue& value) {
  expect_object(value, "a part object");
  check_keys(value, {"name", "description", "motion", "initial", "loops", "features", "dynamics"});
  if (const JsonValue* description = value.find("description")) read_string(*description, true, true);
  Part part;
  part.pointer = value.pointer;
  part.name = read_name(require(value, "name"));
  part.motion = read_motion(require(value, "motion"));
  if (const JsonValue* initial = value.find("initial")) part.initial = read_initial(*initial, part.motion);
  if (const JsonValue* loops = value.find("loops")) {
    expect_array(*loops, "an array of loops");
    for (const JsonValue& loop : loops->items) part.loops.push_back(read_loop(loop));
  }
  if (const JsonValue* features = value.find("features")) read_features(*features, part);
  if (part.loops.empty())
    throw ModelError(value.pointer, "part '" + part.name + "' has no geometry: give 'loops' or 'features'");
  if (const JsonValue* dynamics = value.find("dynamics")) part.dynamics = read_dynamics(*dynamics);
  validate_part_geometry(part);
  return part;
}

Loop Reader::read_loop(const JsonValue& value) {
  expect_object(value, "a loop object {\"start\": ..., \"edges\": [...]}");
  Loop loop;
  loop.pointer = value.pointer;
  if (const JsonValue* circle = value.find("circle")) {
    check_keys(value, {"circle", "label"});
    std::string label;
    if (const JsonValue* l = value.find("label")) label = read_string(*l, true);
    loop.edges.push_back(read_circle(*circle, label));
    return loop;
  }
  check_keys(value, {"start", "edges", "label"});
  std::string loop_label;
  if (const JsonValue* l = value.find("label")) loop_label = read_string(*l, true);
  Point current = point(require(value, "start"));
  const JsonValue& edges = expect_array(require(value, "edges"), "an array of edges");
  if (edges.items.empty()) throw ModelError(edges.pointer, "a loop needs at least one edge");
  for (const JsonValue& edge_value : edges.items) {
    Edge edge = read_edge(edge_value, current);
    if (edge.label.empty()) edge.label = loop_label;
    current = edge.target;
    loop.edges.push_back(std::move(edge));
  }
  return loop;
}

Edge Reader::read_circle(const JsonValue& value, const std::string& label) {
  expect_object(value, "a circle {\"center\": C, \"radius\": r}");
  check_keys(value, {"center", "radius"});
  Edge edge;
  edge.kind = Edge::Kind::arc;
  edge.center = point(require(value, "center"));
  Rational radius = positive(require(value, "radius"), "a circle's radius");
  edge.source = Point{edge.center.x + radius, edge.center.y};
  edge.target = edge.source;
  edge.ccw = true;
  edge.radius_squared = radius * radius;
  edge.pointer = value.pointer;
  edge.label = label;
  return edge;
}

Edge Reader::read_edge(const JsonValue& value, const Point& from) {
  expect_object(value, "an edge object {\"line_to\": P} or {\"arc_to\": P, \"center\": C, \"dir\": \"ccw\"}");
  Edge edge;
  edge.pointer = value.pointer;
  edge.source = from;
  const JsonValue* line_to = value.find("line_to");
  const JsonValue* arc_to = value.find("arc_to");
  if (line_to && arc_to) throw ModelError(value.pointer, "an edge has either 'line_to' or 'arc_to', not both");
  if (line_to) {
    check_keys(value, {"line_to", "label"});
    edge.kind = Edge::Kind::segment;
    edge.target = point(*line_to);
  } else if (arc_to) {
    check_keys(value, {"arc_to", "center", "dir", "label"});
    edge.kind = Edge::Kind::arc;
    edge.target = point(*arc_to);
    edge.center = point(require(value, "center"));
    const JsonValue& direction = require(value, "dir");
    std::string word = read_string(direction, true);
    if (word != "ccw" && word != "cw")
      throw ModelError(direction.pointer, "an arc's direction is \"ccw\" or \"cw\", not '" + word + "'");
    edge.ccw = word == "ccw";
    edge.radius_squared = squared_distance(edge.source, edge.center);
  } else {
    check_keys(value, {"line_to", "arc_to", "center", "dir", "label"});
    throw ModelError(value.pointer, "an edge needs 'line_to' or 'arc_to'");
  }
  if (const JsonValue* label = value.find("label")) edge.label = read_string(*label, true);
  return edge;
}

void Reader::read_features(const JsonValue& features, Part& part) {
  expect_array(features, "an array of feature templates");
  if (features.items.size() > max_feature_count)
    throw ModelError(features.pointer, "too many features");
  for (const JsonValue& feature : features.items) {
    expect_object(feature, "a feature object {\"<template>\": {...}}");
    if (feature.members.size() != 1)
      throw ModelError(feature.pointer, "a feature holds exactly one template, found " +
                                            std::to_string(feature.members.size()) + " keys");
    const JsonMember& member = feature.members.front();
    const TemplateSpec* spec = nullptr;
    std::string known;
    for (const TemplateSpec& candidate : template_specs()) {
      if (candidate.name == member.key) spec = &candidate;
      known += (known.empty() ? "" : ", ") + candidate.name;
    }
    if (!spec)
      throw ModelError(member.value.pointer, "unknown feature template '" + escape_pointer_token(member.key) +
                                                 "' (known: " + known + ")");
    const JsonValue& arguments_value = expect_object(member.value, "an object of template arguments");
    std::map<std::string, TemplateValue> arguments;
    for (const JsonMember& argument : arguments_value.members) {
      const ArgumentSpec* argument_spec = nullptr;
      for (const ArgumentSpec& candidate : spec->arguments)
        if (candidate.key == argument.key) argument_spec = &candidate;
      if (!argument_spec) {
        std::string allowed;
        for (const ArgumentSpec& candidate : spec->arguments)
          allowed += (allowed.empty() ? "" : ", ") + candidate.key;
        throw ModelError(argument.value.pointer, "unknown argument '" + escape_pointer_token(argument.key) +
                                                     "' of template '" + spec->name + "' (allowed: " + allowed + ")");
      }
      arguments.emplace(argument.key, template_argument(argument.value, argument_spec->kind));
    }
    for (const ArgumentSpec& candidate : spec->arguments)
      if (candidate.required && !arguments.count(candidate.key))
        throw ModelError(member.value.pointer, "template '" + spec->name + "' needs argument '" + candidate.key + "'");
    std::vector<Loop> loops;
    try {
      loops = expand_template(spec->name, arguments, member.value.pointer, model_.roundings);
    } catch (const ModelError&) {
      throw;
    } catch (const Error& error) {
      throw ModelError(member.value.pointer, error.what());
    }
    for (Loop& loop : loops) part.loops.push_back(std::move(loop));
    part.features.push_back(spec->name);
  }
}

TemplateValue Reader::template_argument(const JsonValue& value, ArgumentKind kind) {
  switch (kind) {
    case ArgumentKind::length: return number(value);
    case ArgumentKind::angle: return angle(value);
    case ArgumentKind::count: {
      Quantity q = evaluate(value);
      if (!q.is_rational() || q.rational.get_den() != 1 || q.rational <= 0)
        throw ModelError(value.pointer, "expected a positive whole number");
      if (q.rational > Rational(static_cast<long>(max_feature_count)))
        throw ModelError(value.pointer, "count too large (at most " + std::to_string(max_feature_count) + ")");
      return q.rational;
    }
    case ArgumentKind::point: return point(value);
    case ArgumentKind::direction_word: {
      std::string word = read_string(value, true);
      if (word != "ccw" && word != "cw")
        throw ModelError(value.pointer, "expected \"ccw\" or \"cw\", not " + quoted_excerpt(word));
      return word;
    }
  }
  throw ModelError(value.pointer, "unsupported argument kind");
}

Motion Reader::read_motion(const JsonValue& value) {
  Motion motion;
  motion.pointer = value.pointer;
  if (value.is_string()) {
    if (value.text != "fixed")
      throw ModelError(value.pointer, "unknown motion " + quoted_excerpt(value.text) +
                                          " (\"fixed\", or an object: rotation, translation, planar, pin_slot)");
    motion.kind = Motion::Kind::fixed;
    return motion;
  }
  expect_object(value, "a motion (\"fixed\" or {\"rotation\": ...})");
  check_keys(value, {"fixed", "rotation", "translation", "planar", "pin_slot"});
  if (value.members.size() != 1)
    throw ModelError(value.pointer, "a motion holds exactly one of fixed, rotation, translation, planar, pin_slot");
  const JsonMember& member = value.members.front();
  const JsonValue& body = expect_object(member.value, "an object");
  if (member.key == "fixed") {
    check_keys(body, {});
    motion.kind = Motion::Kind::fixed;
  } else if (member.key == "rotation") {
    check_keys(body, {"pivot", "limits"});
    motion.kind = Motion::Kind::rotation;
    motion.pivot = point(require(body, "pivot"));
    if (const JsonValue* l = body.find("limits")) motion.angle_limits = limits(*l, true);
  } else if (member.key == "translation") {
    check_keys(body, {"direction", "limits"});
    motion.kind = Motion::Kind::translation;
    motion.direction = direction(require(body, "direction"));
    if (const JsonValue* l = body.find("limits")) motion.translation_limits = limits(*l, false);
  } else if (member.key == "planar") {
    check_keys(body, {"pivot"});
    motion.kind = Motion::Kind::planar;
    motion.pivot = point(require(body, "pivot"));
  } else {
    check_keys(body, {"pivot", "direction", "angle_limits", "limits"});
    motion.kind = Motion::Kind::pin_slot;
    motion.pivot = point(require(body, "pivot"));
    motion.direction = direction(require(body, "direction"));
    if (const JsonValue* l = body.find("angle_limits")) motion.angle_limits = limits(*l, true);
    if (const JsonValue* l = body.find("limits")) motion.translation_limits = limits(*l, false);
  }
  return motion;
}

PartConfiguration Reader::read_initial(const JsonValue& value, const Motion& motion) {
  expect_object(value, "an object {\"angle\": a, \"offset\": s, \"x\": x, \"y\": y}");
  PartConfiguration initial;
  switch (motion.kind) {
    case Motion::Kind::fixed: check_keys(value, {}); break;
    case Motion::Kind::rotation: check_keys(value, {"angle"}); break;
    case Motion::Kind::translation: check_keys(value, {"offset"}); break;
    case Motion::Kind::planar: check_keys(value, {"angle", "x", "y"}); break;
    case Motion::Kind::pin_slot: check_keys(value, {"angle", "offset"}); break;
  }
  if (const JsonValue* a = value.find("angle")) {
    initial.angle = angle(*a);
    if (motion.kind == Motion::Kind::pin_slot && motion.angle_limits) {
      // a pin-slot part's angle limits are angles modulo whole turns (docs/model-format.md), and
      // so is its initial angle: 370 deg against [-20, 20] deg is 10 deg (PinSlotSpace::locate
      // reduces the same way); decided exactly, the three values' roundings allowed for
      const Rational limits_slack = pin_slot_limits_slack(model_.roundings, motion);
      if (!initial_angle_within_limits(initial.angle, *motion.angle_limits, limits_slack,
                                       rounding_slack(model_.roundings, a->pointer)))
        throw ModelError(a->pointer, "the initial angle lies outside the motion's angle limits, also after whole turns "
                                     "(a pin-slot part's angles are taken modulo 360 deg)");
    } else if (motion.angle_limits && (initial.angle < motion.angle_limits->lo || initial.angle > motion.angle_limits->hi)) {
      throw ModelError(a->pointer, "the initial angle lies outside the motion's angle limits");
    }
  }
  if (const JsonValue* s = value.find("offset")) {
    initial.offset = number(*s);
    if (motion.translation_limits &&
        (initial.offset < motion.translation_limits->lo || initial.offset > motion.translation_limits->hi))
      throw ModelError(s->pointer, "the initial offset lies outside the motion's limits");
  }
  if (const JsonValue* x = value.find("x")) initial.x = number(*x);
  if (const JsonValue* y = value.find("y")) initial.y = number(*y);
  return initial;
}

Dynamics Reader::read_dynamics(const JsonValue& value) {
  expect_object(value, "a dynamics object");
  check_keys(value, {"mass", "moment_of_inertia", "torsional_spring", "linear_spring", "torque", "force", "damping"});
  SimulatorValues simulator_values(*this);
  Dynamics dynamics;
  if (const JsonValue* v = value.find("mass")) dynamics.mass = non_negative(*v, "mass");
  if (const JsonValue* v = value.find("moment_of_inertia"))
    dynamics.moment_of_inertia = non_negative(*v, "moment of inertia");
  if (const JsonValue* v = value.find("torsional_spring")) dynamics.torsional_spring = read_spring(*v, true);
  if (const JsonValue* v = value.find("linear_spring")) dynamics.linear_spring = read_spring(*v, false);
  if (const JsonValue* v = value.find("torque")) dynamics.torque = number(*v);
  if (const JsonValue* v = value.find("force")) {
    expect_array(*v, "a force [fx, fy]");
    if (v->items.size() != 2) throw ModelError(v->pointer, "a force is [fx, fy]: expected 2 numbers");
    dynamics.force = Point{number(v->items[0]), number(v->items[1])};
  }
  if (const JsonValue* v = value.find("damping")) dynamics.damping = non_negative(*v, "damping");
  return dynamics;
}

Spring Reader::read_spring(const JsonValue& value, bool torsional) {
  expect_object(value, "a spring {\"stiffness\": k, \"rest\": r}");
  check_keys(value, {"stiffness", "rest"});
  Spring spring;
  spring.stiffness = non_negative(require(value, "stiffness"), "stiffness");
  if (const JsonValue* rest = value.find("rest")) spring.rest = torsional ? angle(*rest) : number(*rest);
  return spring;
}

}  // namespace hipair::model_detail
