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

// The root end of a flank's radial segment from `base_point` (the lower arc's end on the base
// circle) down to the root circle: base_point - L w, with w an exact rational unit vector within
// the rounding bound b of base_point's direction (half-angle tangent) and L the root radius times
// the simplest rational within b/2 of (|base_point| - root_radius) / root_radius (a relative
// rounding, like the angles'). The segment's length is then the rational L, so the
// product of its length and a rational arc radius is rational: an arc's tangency to it is a
// contact curve of degree 2 in each angle's half-angle tangent (kernels/contact_table.hpp,
// ExactRootOrSquared), where an irrational length squares it to degree 4 (and the chart leaves
// the quadratic traits for CGAL's algebraic one: a 7-tooth pair took a minute). The foot lies
// within about (L + root_radius) b of the ideal point on the root circle (recorded).
Point radial_foot(const Point& base_point, const Rational& root_radius, const std::string& pointer,
                  std::vector<Rounding>& roundings) {
  Rational base_radius = tg::approximate_sqrt(tg::squared_norm(base_point));
  Point direction = tg::point_on_circle_near(Point{0, 0}, Rational(1), tg::scale(Rational(1 / base_radius), base_point),
                                             pointer, "tooth flank radial direction", roundings);
  Rational length = Rational(root_radius * round_simplest(Rational((base_radius - root_radius) / root_radius)));
  Point foot = tg::subtract(base_point, tg::scale(length, direction));
  Point ideal = tg::scale(Rational(root_radius / base_radius), base_point);
  roundings.push_back(Rounding{pointer,
                               "tooth flank end next to the root circle (radial below the base circle, rational "
                               "length; bound: displacement from the ideal end, mm)",
                               length, tg::upper_sqrt(tg::squared_distance(foot, ideal))});
  return foot;
}

}  // namespace

// One flank of the canonical tooth (axis along +x, the right flank y < 0), from the root
// circle to the tip circle: a list of arcs (end point, centre, ccw) after `start`.
struct Flank {
  Point start;                      // on the root circle
  std::vector<Point> ends;          // piece end points; the last is on the tip circle
  std::vector<Point> centres;       // arcs only
  std::vector<bool> counter_clockwise;
  std::vector<bool> is_arc;         // false: a segment
  std::vector<std::string> names;   // "", "radial", "lower", "upper"
};

// A flank arc tangent at `a` to the direction perpendicular to the exact unit vector `normal`,
// through a point near `ideal_end`: its centre a + s normal has s the simplest rational within
// b/2 of the exact s of the circle through `ideal_end` (so the radius |s| is rational and small,
// where the circle through an exact end point has a centre and a squared radius of hundreds of
// bits), and its end is the exact point of that circle nearest `ideal_end` (point_on_circle_near,
// polar angle about the centre rounded within b). Records the centre's and the end's
// displacements from the ideal construction (mm).
struct TangentArc {
  Point centre, end;
};
TangentArc tangent_arc_near(const Point& a, const Point& normal, const Point& ideal_end, const std::string& pointer,
                            const std::string& what, std::vector<Rounding>& roundings) {
  Point d = tg::subtract(ideal_end, a);
  Rational exact_s = dot(d, d) / (2 * dot(d, normal));
  Rational s = tg::round_length(exact_s);
  Point centre = tg::add(a, tg::scale(s, normal));
  roundings.push_back(Rounding{pointer, what + " centre on the normal at the pitch point, distance rounded (bound: centre "
                                               "displacement, mm)",
                               s, Rational(abs(Rational(s - exact_s)))});
  Point end = tg::point_on_circle_near(centre, Rational(abs(s)), ideal_end, pointer, what + " end", roundings);
  roundings.back().bound = Rational(tg::upper_sqrt(tg::squared_distance(end, ideal_end)));
  roundings.back().expression = what + " end: exact point of its arc's circle (half-angle tangent; bound: displacement "
                                       "from the ideal end, mm)";
  return {centre, end};
}

bool arc_is_ccw(const Point& from, const Point& to, const Point& centre) {
  Point a = tg::subtract(from, centre), b = tg::subtract(to, centre);
  return a.x * b.y - a.y * b.x > 0;  // the short way round
}

// Canonical tooth: axis along +x; beta = half the tooth's angular thickness at the pitch
// circle, P = rp u(-beta) the right flank's pitch point, n = u(pi/2 + alpha - beta) the flank
// normal at P (towards the involute's centre of curvature on the base circle).
// Default: each flank is two circular arcs tangent at P, with centres on the normal: the upper
// one through the involute's point on the tip circle, the lower one through its point on the
// base circle (or on the root circle when that is larger), continued down to the root circle.
// With flank_radius: one arc of that radius centred at P + rf n (rf = rp sin(alpha) is the
// involute's curvature at P). The left flank is the mirror image. Vertices on the tip and
// root circles are exact rational points next to the ideal ones; the arcs' centres are then
// placed exactly (on the normal through P, or on the bisector of the arc's end points), and
// the displacement is recorded as a rounding.
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
  check_rules("spur_gear", arguments, teeth);   // dedendum and pressure angle (template_rules.cpp)

  Point pressure;  // u(alpha)
  double alpha;
  if (arguments.has("pressure_angle")) {
    Rational value = arguments.angle("pressure_angle");
    alpha = tg::approximate(value);
    pressure = exact_unit_vector(value, arguments.at("pressure_angle"), "pressure_angle",
                                 roundings);
  } else {
    alpha = M_PI / 9;
    pressure = exact_unit_vector_pi(Rational(1, 9), pointer, "default pressure_angle 20 deg",
                                    roundings);
  }
  Rational half_angle = thickness / (2 * pitch);  // beta, exact
  if (tg::approximate(half_angle) >= M_PI / static_cast<double>(teeth))
    throw ModelError(arguments.at("tooth_thickness"),
                     "is at least the circular pitch: no space is left between the teeth");
  Point half_unit = exact_unit_vector(Rational(-half_angle), arguments.at("tooth_thickness"),
                                      "tooth_thickness / (2 pitch_radius)", roundings);
  Point pitch_point = tg::scale(pitch, half_unit);
  Point normal = tg::perpendicular(tg::rotate(pressure, half_unit));  // u(pi/2 + alpha - beta)

  auto crossing = [&](const Point& centre, const Rational& radius, const Rational& circle,
                      const std::string& key, const std::string& what) {
    Point first, second;
    if (!tg::circle_intersections(circle, centre, radius, first, second))
      throw ModelError(arguments.at(key), "the tooth flank does not reach the " + what +
                                              " circle (check addendum, dedendum, "
                                              "pressure_angle, flank_radius)");
    return tg::squared_distance(first, pitch_point) < tg::squared_distance(second, pitch_point)
               ? first
               : second;
  };

  Flank flank;
  if (arguments.has("flank_radius")) {
    Rational radius = arguments.positive_length("flank_radius");
    // The centre P + rf n is exact and the radius rf rational: the ends are exact points of
    // that circle next to its crossings with the tip and root circles (they need not lie on
    // those circles exactly: the tip and root arcs are centred on the gear's centre and run
    // between mirror images, equidistant from it whatever the ends).
    Point centre = tg::add(pitch_point, tg::scale(radius, normal));
    Point tip = tg::point_on_circle_near(centre, radius, crossing(centre, radius, tip_radius, "addendum", "tip"),
                                         pointer, "tooth flank end next to the tip circle", roundings);
    Point root = tg::point_on_circle_near(centre, radius, crossing(centre, radius, root_radius, "dedendum", "root"),
                                          pointer, "tooth flank end next to the root circle", roundings);
    flank.start = root;
    flank.ends = {tip};
    flank.centres = {centre};
    flank.counter_clockwise = {arc_is_ccw(root, tip, centre)};
    flank.is_arc = {true};
    flank.names = {""};
  } else {
    double rp = tg::approximate_length(pitch), beta = tg::approximate(half_angle);
    double base = rp * std::cos(alpha);
    double low = std::max(base, tg::approximate_length(root_radius));
    auto involute_function = [](double angle) { return std::tan(angle) - angle; };
    auto involute_point = [&](double r) {
      double pressure_at_r = std::acos(std::min(1.0, base / r));
      double angle = -beta + involute_function(pressure_at_r) - involute_function(alpha);
      return Point{tg::length_from(r * std::cos(angle)), tg::length_from(r * std::sin(angle))};
    };
    if (tg::approximate_length(tip_radius) <= base)
      throw ModelError(arguments.at("addendum"),
                       "the tip circle lies inside the base circle: no involute to follow");
    // Each arc's centre lies on the normal at P at a rounded distance (tangent_arc_near), and
    // its far end is an exact point of that circle next to the involute's point; the tip need
    // not lie on the tip circle exactly (the tip arc is centred on the gear's centre and runs
    // between mirror images).
    TangentArc upper = tangent_arc_near(pitch_point, normal, involute_point(tg::approximate_length(tip_radius)), pointer,
                                        "upper tooth flank arc (involute point on the tip circle)", roundings);
    Point tip = upper.end;
    Point upper_centre = upper.centre;
    if (low > tg::approximate_length(root_radius)) {
      // Below the base circle the involute does not exist: a radial segment down to the root
      // circle; the lower arc runs from the involute's start on the base circle to P.
      TangentArc lower = tangent_arc_near(pitch_point, normal, involute_point(low), pointer,
                                          "lower tooth flank arc (involute point on the base circle)", roundings);
      Point base_point = lower.end;
      Point lower_centre = lower.centre;
      Point root = radial_foot(base_point, root_radius, pointer, roundings);
      flank.start = root;
      flank.ends = {base_point, pitch_point, tip};
      flank.centres = {Point{}, lower_centre, upper_centre};
      flank.counter_clockwise = {false, arc_is_ccw(base_point, pitch_point, lower_centre),
                                 arc_is_ccw(pitch_point, tip, upper_centre)};
      flank.is_arc = {false, true, true};
      flank.names = {"radial", "lower", "upper"};
    } else {
      TangentArc lower = tangent_arc_near(pitch_point, normal, involute_point(low), pointer,
                                          "lower tooth flank arc (involute point on the root circle)", roundings);
      Point root = lower.end;
      Point lower_centre = lower.centre;
      flank.start = root;
      flank.ends = {pitch_point, tip};
      flank.centres = {lower_centre, upper_centre};
      flank.counter_clockwise = {arc_is_ccw(root, pitch_point, lower_centre),
                                 arc_is_ccw(pitch_point, tip, upper_centre)};
      flank.is_arc = {true, true};
      flank.names = {"lower", "upper"};
    }
  }

  const Point& tip = flank.ends.back();
  const Point& root = flank.start;
  if (tip.y >= 0)
    throw ModelError(arguments.at("addendum"),
                     "the teeth are pointed: the flanks cross before the tip circle (reduce the "
                     "addendum or increase tooth_thickness)");
  double root_angle = std::atan2(tg::approximate_length(root.y), tg::approximate_length(root.x));
  if (root.y >= 0 || root_angle <= -M_PI / static_cast<double>(teeth))
    throw ModelError(arguments.at("dedendum"),
                     "the flanks of neighbouring teeth meet above the root circle (reduce the "
                     "dedendum or tooth_thickness)");

  std::vector<Point> turn(teeth);
  for (long k = 0; k < teeth; ++k)
    turn[k] = direction(phase, Rational(2 * k, teeth), pointer, tooth(k) + " axis direction",
                        roundings);
  Point origin{0, 0};
  std::size_t pieces = flank.ends.size();
  auto piece_label = [&](long k, const std::string& side, std::size_t i) {
    std::string label = tooth(k) + " flank " + side;
    if (!flank.names[i].empty()) label += " " + flank.names[i];
    return label;
  };
  auto add_piece = [&](tg::LoopBuilder& loop, const Point& u, std::size_t i, const Point& end,
                       bool mirrored, const std::string& label) {
    Point target = place(center, u, mirrored ? tg::mirror(end) : end);
    if (!flank.is_arc[i]) {
      loop.line_to(target, label);
      return;
    }
    const Point& centre = flank.centres[i];
    loop.arc_to(target, place(center, u, mirrored ? tg::mirror(centre) : centre),
                flank.counter_clockwise[i], label);
  };
  tg::LoopBuilder loop(place(center, turn[0], root), pointer);
  for (long k = 0; k < teeth; ++k) {
    const Point& u = turn[k];
    for (std::size_t i = 0; i < pieces; ++i)
      add_piece(loop, u, i, flank.ends[i], false, piece_label(k, "R", i));
    loop.arc_to(place(center, u, tg::mirror(tip)), place(center, u, origin), true,
                tooth(k) + " tip");
    // Left flank: the mirror image, run from the tip down (mirroring and reversing keep the
    // turning sense of each arc).
    for (std::size_t i = pieces; i-- > 0;)
      add_piece(loop, u, i, i == 0 ? flank.start : flank.ends[i - 1], true,
                piece_label(k, "L", i));
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
  check_rules("ratchet_wheel", arguments, teeth);   // root below tip (template_rules.cpp)
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
