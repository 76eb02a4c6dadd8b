// Feature templates with teeth: spur gears with circular-arc flanks, ratchet wheels.
#include "model/exact_trig.hpp"
#include "model/template_arguments.hpp"
#include "model/template_geometry.hpp"

#include <hipair/error.hpp>

#include <cmath>

namespace hipair::model_detail::template_detail {
namespace tg = template_geometry;

namespace {

std::string tooth(long index) { return "tooth " + std::to_string(index + 1); }

Point place(const Point& center, const Point& unit, const Point& local) {
  return tg::add(center, tg::rotate(local, unit));
}

Rational dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }

}  // namespace

// Canonical tooth: axis along +x. The right flank (y < 0) is a circular arc of radius
// flank_radius through the pitch point at angle -beta (beta = half the tooth's angular
// thickness), with its centre on the line of action (pressure angle alpha), i.e. at
// P + rf * u(pi/2 + alpha - beta): the centre of curvature of the involute at the pitch point
// when rf = rp sin(alpha). The flank meets the tip and root circles at irrational points; we
// take exact rational points on those circles next to them and move the flank's centre onto
// their perpendicular bisector (the flank radius changes by less than the recorded bound).
std::vector<Loop> expand_spur_gear(const Arguments& arguments, std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  long teeth = arguments.count("teeth", 3, 2000);
  Rational pitch = arguments.positive_length("pitch_radius");
  Rational addendum = arguments.positive_length("addendum");
  Rational dedendum = arguments.positive_length("dedendum");
  Rational thickness = arguments.positive_length("tooth_thickness");
  Rational phase = arguments.angle("phase");
  Rational tip_radius = pitch + addendum;
  Rational root_radius = pitch - dedendum;
  if (root_radius <= 0)
    throw ModelError(arguments.at("dedendum"), "must be less than pitch_radius");

  Point pressure;  // u(alpha)
  double alpha;
  if (arguments.has("pressure_angle")) {
    Rational value = arguments.angle("pressure_angle");
    alpha = tg::approximate(value);
    if (alpha <= 0.01 || alpha >= 0.7)
      throw ModelError(arguments.at("pressure_angle"),
                       "must lie between 0.01 and 0.7 rad (about 0.6 to 40 degrees)");
    pressure = exact_unit_vector(value, arguments.at("pressure_angle"), "pressure_angle",
                                 roundings);
  } else {
    alpha = M_PI / 9;
    pressure = exact_unit_vector_pi(Rational(1, 9), pointer, "default pressure_angle 20 deg",
                                    roundings);
  }
  Rational flank_radius;
  if (arguments.has("flank_radius")) {
    flank_radius = arguments.positive_length("flank_radius");
  } else {
    // rp * sin(alpha) from the exact unit vector (already rounded, exact from here on).
    flank_radius = round_to_grid(Rational(pitch * pressure.y));
    roundings.push_back(Rounding{pointer + "/flank_radius",
                                 "default flank_radius = pitch_radius * sin(pressure_angle)",
                                 flank_radius, tg::grid_step()});
  }

  Rational half_angle = thickness / (2 * pitch);  // beta, exact
  if (tg::approximate(half_angle) >= M_PI / static_cast<double>(teeth))
    throw ModelError(arguments.at("tooth_thickness"),
                     "is at least the circular pitch: no space is left between the teeth");
  Point half_unit = exact_unit_vector(Rational(-half_angle), arguments.at("tooth_thickness"),
                                      "tooth_thickness / (2 pitch_radius)", roundings);
  Point pitch_point = tg::scale(pitch, half_unit);
  Point toward_centre = tg::perpendicular(tg::rotate(pressure, half_unit));  // u(pi/2+a-b)
  Point ideal_centre = tg::add(pitch_point, tg::scale(flank_radius, toward_centre));

  auto nearest_crossing = [&](const Rational& radius, const std::string& key,
                              const std::string& what) {
    Point first, second;
    if (!tg::circle_intersections(radius, ideal_centre, flank_radius, first, second))
      throw ModelError(arguments.at(key), "the flank arc (flank_radius " +
                                              to_decimal_string(flank_radius, 6) +
                                              ") does not reach the " + what + " circle");
    return tg::squared_distance(first, pitch_point) < tg::squared_distance(second, pitch_point)
               ? first
               : second;
  };
  Point tip_ideal = nearest_crossing(tip_radius, "addendum", "tip");
  Point root_ideal = nearest_crossing(root_radius, "dedendum", "root");
  Point tip = tg::point_on_circle_near(Point{0, 0}, tip_radius, tip_ideal, pointer,
                                       "tooth flank end on the tip circle", roundings);
  Point root = tg::point_on_circle_near(Point{0, 0}, root_radius, root_ideal, pointer,
                                        "tooth flank end on the root circle", roundings);
  if (tip.y >= 0)
    throw ModelError(arguments.at("addendum"),
                     "the teeth are pointed: the flanks cross before the tip circle (reduce the "
                     "addendum or increase tooth_thickness or flank_radius)");
  double root_angle = std::atan2(tg::approximate(root.y), tg::approximate(root.x));
  if (root.y >= 0 || root_angle <= -M_PI / static_cast<double>(teeth))
    throw ModelError(arguments.at("dedendum"),
                     "the flanks of neighbouring teeth meet above the root circle (reduce the "
                     "dedendum or tooth_thickness)");

  // Flank centre: the point of the perpendicular bisector of root-tip nearest the ideal one.
  Point middle = tg::scale(Rational(1, 2), tg::add(tip, root));
  Point normal = tg::perpendicular(tg::subtract(tip, root));
  Rational along = dot(tg::subtract(ideal_centre, middle), normal) / dot(normal, normal);
  Point flank_centre = tg::add(middle, tg::scale(along, normal));
  Rational moved = tg::squared_distance(flank_centre, ideal_centre);
  roundings.push_back(Rounding{pointer, "tooth flank centre moved onto the bisector of its exact "
                                        "end points (bound: centre displacement, mm)",
                               flank_centre.x,
                               Rational(tg::upper_sqrt(moved) +
                                        tip_radius * Rational(2 * tg::grid_step()))});
  Point arm_root = tg::subtract(root, flank_centre);
  Point arm_tip = tg::subtract(tip, flank_centre);
  bool flank_ccw = arm_root.x * arm_tip.y - arm_root.y * arm_tip.x > 0;

  Point tip_left = tg::mirror(tip);
  Point root_left = tg::mirror(root);
  Point centre_left = tg::mirror(flank_centre);

  std::vector<Point> turn(teeth);
  for (long k = 0; k < teeth; ++k)
    turn[k] = direction(phase, Rational(2 * k, teeth), pointer,
                        tooth(k) + " axis direction", roundings);
  Point origin{0, 0};
  tg::LoopBuilder loop(place(center, turn[0], root), pointer);
  for (long k = 0; k < teeth; ++k) {
    const Point& u = turn[k];
    loop.arc_to(place(center, u, tip), place(center, u, flank_centre), flank_ccw,
                tooth(k) + " flank R");
    loop.arc_to(place(center, u, tip_left), place(center, u, origin), true, tooth(k) + " tip");
    loop.arc_to(place(center, u, root_left), place(center, u, centre_left), flank_ccw,
                tooth(k) + " flank L");
    loop.arc_to(place(center, turn[(k + 1) % teeth], root), center, true, tooth(k) + " root");
  }
  return {loop.finish()};
}

// Saw teeth: tooth tips on the tip circle at phase + 2 pi k / z, a radial face from each tip to
// the root circle and a straight back to the next tip. `dir` is the direction in which the
// wheel may turn with a pawl riding over the backs; the radial faces stop the other one.
std::vector<Loop> expand_ratchet_wheel(const Arguments& arguments,
                                       std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  long teeth = arguments.count("teeth", 3, 2000);
  Rational tip_radius = arguments.positive_length("tip_radius");
  Rational root_radius = arguments.positive_length("root_radius");
  Rational phase = arguments.angle("phase");
  bool free_ccw = arguments.counter_clockwise("dir", true);
  if (root_radius >= tip_radius)
    throw ModelError(arguments.at("root_radius"), "must be less than tip_radius");
  std::vector<Point> turn(teeth);
  for (long k = 0; k < teeth; ++k)
    turn[k] = direction(phase, Rational(2 * k, teeth), pointer, tooth(k) + " tip direction",
                        roundings);
  auto tip = [&](long k) { return tg::add(center, tg::scale(tip_radius, turn[k % teeth])); };
  auto root = [&](long k) { return tg::add(center, tg::scale(root_radius, turn[k % teeth])); };
  if (free_ccw) {
    // root k -> tip k (face, facing clockwise) -> root k+1 (back of tooth k).
    tg::LoopBuilder loop(root(0), pointer);
    for (long k = 0; k < teeth; ++k) {
      loop.line_to(tip(k), tooth(k) + " face");
      loop.line_to(root(k + 1), tooth(k) + " back");
    }
    return {loop.finish()};
  }
  // tip k -> root k (face, facing counter-clockwise) -> tip k+1 (back of tooth k+1).
  tg::LoopBuilder loop(tip(0), pointer);
  for (long k = 0; k < teeth; ++k) {
    loop.line_to(root(k), tooth(k) + " face");
    loop.line_to(tip(k + 1), tooth((k + 1) % teeth) + " back");
  }
  return {loop.finish()};
}

}  // namespace hipair::model_detail::template_detail
