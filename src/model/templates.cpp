#include "model/templates.hpp"

#include "model/exact_trig.hpp"
#include "model/template_arguments.hpp"
#include "model/template_geometry.hpp"
#include "model/template_rules.hpp"

#include <hipair/error.hpp>

#include <cmath>
#include <optional>

namespace hipair::model_detail {

using template_detail::Arguments;
namespace tg = template_geometry;

const std::vector<TemplateSpec>& template_specs() {
  using K = ArgumentKind;
  static const std::vector<TemplateSpec> specs = {
      {"circle", {{"center", K::point, true}, {"radius", K::length, true}}},
      {"pin", {{"center", K::point, true}, {"radius", K::length, true}}},
      {"geneva_wheel",
       {{"center", K::point, true},
        {"slots", K::count, true},
        {"slot_width", K::length, true},
        {"slot_inner_radius", K::length, true},
        {"slot_outer_radius", K::length, true},
        {"lock_center_radius", K::length, true},
        {"lock_radius", K::length, true},
        {"lock_span", K::angle, true},
        {"phase", K::angle, false}}},
      {"geneva_driver",
       {{"center", K::point, true},
        {"pin_radius", K::length, true},
        {"pin_center_radius", K::length, true},
        {"lock_outer_radius", K::length, true},
        {"lock_inner_radius", K::length, true},
        {"lock_span", K::angle, true},
        {"lock_offset", K::angle, false},
        {"phase", K::angle, false}}},
      {"spur_gear",
       {{"center", K::point, true},
        {"teeth", K::count, true},
        {"pitch_radius", K::length, true},
        {"addendum", K::length, true},
        {"dedendum", K::length, true},
        {"tooth_thickness", K::length, true},
        {"flank_radius", K::length, false},
        {"pressure_angle", K::angle, false},
        {"phase", K::angle, false}}},
      {"ratchet_wheel",
       {{"center", K::point, true},
        {"teeth", K::count, true},
        {"tip_radius", K::length, true},
        {"root_radius", K::length, true},
        {"phase", K::angle, false},
        {"dir", K::direction_word, false}}},
      {"escape_wheel",
       {{"center", K::point, true},
        {"teeth", K::count, true},
        {"tip_radius", K::length, true},
        {"root_radius", K::length, true},
        {"phase", K::angle, false},
        {"dir", K::direction_word, false},
        {"tip_angle", K::angle, false},
        {"face_angle", K::angle, false},
        {"back_angle", K::angle, false}}},
      {"anchor",
       {{"center", K::point, true},
        {"wheel_center", K::point, true},
        {"wheel_radius", K::length, true},
        {"pallet_width", K::length, true},
        {"lift", K::angle, true},
        {"lock", K::angle, true},
        {"pallet_extent", K::angle, false},
        {"fork_length", K::length, true},
        {"fork_width", K::length, true},
        {"fork_slot_width", K::length, true},
        {"fork_slot_depth", K::length, true}}},
      {"balance",
       {{"center", K::point, true},
        {"radius", K::length, true},
        {"pin_radius", K::length, true},
        {"pin_center_radius", K::length, true},
        {"phase", K::angle, false}}},
  };
  return specs;
}

std::vector<Loop> expand_template(const std::string& name,
                                  const std::map<std::string, TemplateValue>& arguments,
                                  const std::string& pointer, std::vector<Rounding>& roundings) {
  const TemplateSpec* spec = nullptr;
  for (const TemplateSpec& candidate : template_specs())
    if (candidate.name == name) spec = &candidate;
  if (!spec) throw ModelError(pointer, "unknown feature template '" + name + "'");
  for (const auto& [key, value] : arguments) {
    bool known = false;
    for (const ArgumentSpec& argument : spec->arguments) known = known || argument.key == key;
    if (!known)
      throw ModelError(pointer + "/" + key,
                       "unknown argument '" + key + "' of template '" + name + "'");
  }
  Arguments typed(arguments, pointer);
  // Doubles of the construction in units of the template's own size (tg::approximate_length).
  Rational largest(0);
  for (const ArgumentSpec& argument : spec->arguments) {
    auto found = arguments.find(argument.key);
    if (found == arguments.end()) continue;
    if (argument.kind == ArgumentKind::length)
      if (const Rational* value = std::get_if<Rational>(&found->second)) largest = std::max(largest, Rational(abs(*value)));
  }
  tg::LengthScaleScope length_scale(largest);
  for (const ArgumentSpec& argument : spec->arguments)
    if (argument.required && !typed.has(argument.key))
      throw ModelError(pointer + "/" + argument.key,
                       "template '" + name + "' needs the argument '" + argument.key + "'");
  if (name == "circle") return template_detail::expand_circle(typed, "circle");
  if (name == "pin") return template_detail::expand_circle(typed, "pin");
  if (name == "geneva_wheel") return template_detail::expand_geneva_wheel(typed, roundings);
  if (name == "geneva_driver") return template_detail::expand_geneva_driver(typed, roundings);
  if (name == "spur_gear") return template_detail::expand_spur_gear(typed, roundings);
  if (name == "ratchet_wheel") return template_detail::expand_ratchet_wheel(typed, roundings);
  if (name == "escape_wheel") return template_detail::expand_escape_wheel(typed, roundings);
  if (name == "anchor") return template_detail::expand_anchor(typed, roundings);
  return template_detail::expand_balance(typed, roundings);
}

namespace template_detail {

Point direction(const Rational& phase, const Rational& multiple_of_pi, const std::string& pointer,
                const std::string& what, std::vector<Rounding>& roundings) {
  return exact_unit_vector_sum(phase, multiple_of_pi, pointer, what, roundings);
}

std::vector<Loop> expand_circle(const Arguments& arguments, const std::string& label) {
  Point center = arguments.point("center");
  Rational radius = arguments.positive_length("radius");
  return {tg::LoopBuilder::circle(center, radius, label, arguments.pointer())};
}

namespace {

std::string numbered(const std::string& what, long index) {
  return what + " " + std::to_string(index + 1);
}

// Places a point of a canonical frame (centre at origin) by the exact rotation `unit`, then
// translates it to `center`.
Point place(const Point& center, const Point& unit, const Point& local) {
  return tg::add(center, tg::rotate(local, unit));
}

// The length of a slot wall from (inner, y) along the slot axis (+x, slot frame) whose end
// W = (inner + L, y) lies at a rational distance from the mouth's other end `far`, with L within
// half the rounding bound of `ideal` relative to `unit_length` (r_out): a pin's tangency to the
// mouth is then a contact curve of degree 2 as well (kernels/contact_table.hpp). In units of
// r_out, with a = far.x - inner and c = (y - far.y)^2, the mouth's squared length is
// f(L) = (L - a)^2 + c, and for every rational s the length L = a + (c - s^2) / (2 s) gives
// f(L) = (L - a + s)^2, a rational square: s is the simplest rational next to the one that
// gives `ideal` (a double guess; the result is checked exactly). nullopt when no such s is
// found within the bound (the caller keeps the rounded length; the mouth is then irrational).
std::optional<Rational> wall_length_with_rational_mouth(const Rational& inner, const Rational& y, const Point& far,
                                                        const Rational& ideal, const Rational& unit_length) {
  const Rational a = (far.x - inner) / unit_length;
  const Rational dy = (y - far.y) / unit_length;
  const Rational c = dy * dy;
  const Rational target = ideal / unit_length;
  const Rational half_bound = rounding_bound() / 2;
  if (sgn(c) == 0) return std::nullopt;   // the mouth continues the wall: any length is rational
  const double d0 = Rational(target - a).get_d(), cd = c.get_d();
  const double s0 = -d0 + std::sqrt(d0 * d0 + cd);   // the positive s with L(s) = target
  if (!(s0 > 0) || !std::isfinite(s0)) return std::nullopt;
  const double slope = (cd + s0 * s0) / (2 * s0 * s0);   // |dL/ds| at s0
  Rational width = half_bound / Rational(4 * slope + 1);
  for (int attempt = 0; attempt < 40; ++attempt, width /= 2) {
    Rational s = simplest_rational_between(Rational(s0) - width, Rational(s0) + width);
    if (sgn(s) <= 0) continue;
    Rational length = a + (c - s * s) / (2 * s);
    if (abs(Rational(length - target)) <= half_bound) return Rational(length * unit_length);
  }
  return std::nullopt;
}

}  // namespace

void check_rules(const std::string& name, const Arguments& arguments, long count) {
  const TemplateSpec* spec = nullptr;
  for (const TemplateSpec& candidate : template_specs())
    if (candidate.name == name) spec = &candidate;
  auto is_length = [&](const char* key) {
    if (spec)
      for (const ArgumentSpec& argument : spec->arguments)
        if (argument.key == key) return argument.kind == ArgumentKind::length;
    return false;
  };
  const Rational& unit = tg::length_unit();
  auto in_unit = [&](const Rational& length) { return unit == 1 ? length : Rational(length / unit); };
  ExactTemplateRuleValues values;
  values.has = [&](const char* key) { return arguments.has(key); };
  values.value = [&](const char* key) {
    Rational number = arguments.number(key);
    return is_length(key) ? in_unit(number) : number;
  };
  values.point = [&](const char* key) {
    Point p = arguments.point(key);
    return kernels::Vector<Rational>{in_unit(p.x), in_unit(p.y)};
  };
  values.count = count;
  check_template_rules_exactly(name, values, arguments.pointer());
}

std::vector<Loop> expand_geneva_wheel(const Arguments& arguments,
                                      std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  long slots = arguments.count("slots", 3, 360);
  Rational width = arguments.positive_length("slot_width");
  Rational inner = arguments.positive_length("slot_inner_radius");
  Rational outer = arguments.positive_length("slot_outer_radius");
  Rational lock_distance = arguments.positive_length("lock_center_radius");
  Rational lock_radius = arguments.positive_length("lock_radius");
  Rational span = arguments.angle("lock_span");
  Rational phase = arguments.angle("phase");
  Rational half = width / 2;
  // the template's rules (template_rules.cpp, shared with the tolerance box's check)
  check_rules("geneva_wheel", arguments, slots);
  Rational wall_end_squared = outer * outer - half * half;

  // Slot frame: slot axis along +x. Walls at y = +-w/2 from the bottom towards radius r_out, of
  // rational lengths within b r_out of sqrt(r_out^2 - (w/2)^2) - r_in (a relative rounding, like
  // the angles', so that the rationals keep their size at every scale of the model): a pin's
  // tangency to a wall (rational pin radius times rational length) is then a contact curve of
  // degree 2 in each half-angle tangent, where a wall ending exactly on the circle r_out
  // (irrational length) squares it to degree 4 and leaves the quadratic traits
  // (kernels/contact_table.hpp). Each slot's walls are chosen below (wall_length_with_rational_mouth)
  // so that its mouths are rational too; this canonical wall, r_out times the simplest rational
  // within b/2 of the ideal ratio, is the fallback and the fit checks' geometry.
  Rational wall_reach = tg::approximate_sqrt(wall_end_squared);
  Rational wall_length = Rational(outer * round_simplest(Rational((wall_reach - inner) / outer)));
  Point wall_end_left{Rational(inner + wall_length), half};
  Point wall_end_right = tg::mirror(wall_end_left);
  Point bottom_center{inner, Rational(0)};
  Point bottom_left{inner, half};
  Point bottom_right{inner, -half};

  // Lock frame: locking arc centre on +x at lock_center_radius; the arc faces the wheel centre.
  Point half_span = exact_unit_vector(Rational(span / 2), arguments.at("lock_span"),
                                      "lock_span/2", roundings);
  Point lock_center{lock_distance, Rational(0)};
  Point lock_start{lock_distance - lock_radius * half_span.x, -lock_radius * half_span.y};
  Point lock_end{lock_distance - lock_radius * half_span.x, lock_radius * half_span.y};

  // (the fit of the slots and locking arcs: check_rules above; the reader's exact loop checks
  // back them up)

  std::vector<Point> lock_turn(slots), slot_turn(slots);
  for (long k = 0; k < slots; ++k) {
    lock_turn[k] = direction(phase, Rational(2 * k, slots), pointer,
                             "locking arc " + std::to_string(k + 1) + " direction", roundings);
    slot_turn[k] = direction(phase, Rational(2 * k + 1, slots), pointer,
                             "slot " + std::to_string(k + 1) + " axis direction", roundings);
  }
  // Each slot's walls get lengths (within the same bound) that also make both mouths rational:
  // the rounded slot and lock directions are not exact mirror images, so each slot and side has
  // its own (wall_length_with_rational_mouth).
  auto in_slot_frame = [&](long k, const Point& local, const Point& turn) {
    Point unit = slot_turn[k];
    return tg::rotate(tg::rotate(local, turn), Point{unit.x, Rational(-unit.y)});
  };
  auto wall_end = [&](long k, bool right) {
    const Point far = right ? in_slot_frame(k, lock_end, lock_turn[k]) : in_slot_frame(k, lock_start, lock_turn[(k + 1) % slots]);
    const Rational y = right ? Rational(-half) : half;
    std::optional<Rational> length = wall_length_with_rational_mouth(inner, y, far, Rational(wall_reach - inner), outer);
    const std::string what = numbered("slot", k) + (right ? " wall R" : " wall L");
    if (!length) {
      roundings.push_back(Rounding{pointer,
                                   what + " length (rational; its end next to slot_outer_radius; bound: displacement "
                                          "of the end along the wall, mm)",
                                   wall_length, Rational(outer * rounding_bound() / 2)});
      return right ? wall_end_right : wall_end_left;
    }
    roundings.push_back(Rounding{pointer,
                                 what + " length (rational, and so is its mouth; its end next to slot_outer_radius; "
                                        "bound: displacement of the end along the wall, mm)",
                                 *length, Rational(outer * rounding_bound() / 2)});
    return Point{Rational(inner + *length), y};
  };
  tg::LoopBuilder loop(place(center, lock_turn[0], lock_start), pointer);
  for (long k = 0; k < slots; ++k) {
    const Point& lock = lock_turn[k];
    const Point& slot = slot_turn[k];
    const Point slot_wall_end_right = wall_end(k, true), slot_wall_end_left = wall_end(k, false);
    loop.arc_to(place(center, lock, lock_end), place(center, lock, lock_center), false,
                numbered("lock arc", k));
    loop.line_to(place(center, slot, slot_wall_end_right), numbered("slot", k) + " mouth R");
    loop.line_to(place(center, slot, bottom_right), numbered("slot", k) + " wall R");
    loop.arc_to(place(center, slot, bottom_left), place(center, slot, bottom_center), false,
                numbered("slot", k) + " bottom");
    loop.line_to(place(center, slot, slot_wall_end_left), numbered("slot", k) + " wall L");
    loop.line_to(place(center, lock_turn[(k + 1) % slots], lock_start),
                 numbered("slot", k) + " mouth L");
  }
  return {loop.finish()};
}

std::vector<Loop> expand_geneva_driver(const Arguments& arguments,
                                       std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  Rational pin_radius = arguments.positive_length("pin_radius");
  Rational pin_distance = arguments.positive_length("pin_center_radius");
  Rational outer = arguments.positive_length("lock_outer_radius");
  Rational inner = arguments.number("lock_inner_radius");
  Rational span = arguments.angle("lock_span");
  Rational default_offset = -span / 2;
  Rational offset = arguments.angle("lock_offset", default_offset);
  Rational phase = arguments.angle("phase");
  if (inner < 0) throw ModelError(arguments.at("lock_inner_radius"), "must not be negative");
  check_rules("geneva_driver", arguments, 0);   // template_rules.cpp

  Point pin_direction = exact_unit_vector(phase, arguments.at("phase"), "phase", roundings);
  Point pin_center = tg::add(center, tg::scale(pin_distance, pin_direction));

  // The crescent is centred on the side opposite the pin: angles phase + pi + offset .. + span.
  Point start = exact_unit_vector(Rational(phase + offset), arguments.at("lock_offset"),
                                  "phase + lock_offset", roundings);
  Point end = exact_unit_vector(Rational(phase + offset + span), arguments.at("lock_span"),
                                "phase + lock_offset + lock_span", roundings);
  start = Point{-start.x, -start.y};
  end = Point{-end.x, -end.y};

  // Coarse check that the pin does not sit in or on the crescent (the reader checks exactly).
  {
    double dx = tg::approximate(pin_direction.x), dy = tg::approximate(pin_direction.y);
    double pin_angle = std::atan2(dy, dx);
    double start_angle = std::atan2(tg::approximate(start.y), tg::approximate(start.x));
    double relative = std::remainder(pin_angle - start_angle, 2 * M_PI);
    if (relative < 0) relative += 2 * M_PI;
    double distance = tg::approximate_length(pin_distance);
    double rp = tg::approximate_length(pin_radius);
    bool within_span = relative <= tg::approximate(span);
    if (within_span && distance + rp > tg::approximate_length(inner) &&
        distance - rp < tg::approximate_length(outer))
      throw ModelError(arguments.at("pin_center_radius"),
                       "the pin overlaps the locking crescent (check phase and lock_offset)");
  }

  std::vector<Loop> loops;
  loops.push_back(tg::LoopBuilder::circle(pin_center, pin_radius, "pin", pointer));
  tg::LoopBuilder crescent(tg::add(center, tg::scale(outer, start)), pointer);
  crescent.arc_to(tg::add(center, tg::scale(outer, end)), center, true, "lock arc outer");
  if (inner > 0) {
    crescent.line_to(tg::add(center, tg::scale(inner, end)), "lock end 2");
    crescent.arc_to(tg::add(center, tg::scale(inner, start)), center, false, "lock arc inner");
    crescent.line_to(tg::add(center, tg::scale(outer, start)), "lock end 1");
  } else {
    crescent.line_to(center, "lock end 2");
    crescent.line_to(tg::add(center, tg::scale(outer, start)), "lock end 1");
  }
  loops.push_back(crescent.finish());
  return loops;
}

}  // namespace template_detail
}  // namespace hipair::model_detail
