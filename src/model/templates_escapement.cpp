// Feature templates of an escapement-type balance governor: escape wheel, anchor (pallet fork),
// balance (roller disc with impulse pin).
#include "model/exact_trig.hpp"
#include "model/template_arguments.hpp"
#include "model/template_geometry.hpp"

#include <hipair/error.hpp>

#include <cmath>

namespace hipair::model_detail::template_detail {
namespace tg = template_geometry;

namespace {

std::string tooth(long index) { return "tooth " + std::to_string(index + 1); }

// Exact unit vector near the direction of `v` (exact when |v| is rational).
Point unit_toward(const Point& v, const std::string& pointer, const std::string& what,
                  std::vector<Rounding>& roundings) {
  Rational squared = tg::squared_norm(v);
  mpz_class num_root, den_root;
  mpz_sqrt(num_root.get_mpz_t(), squared.get_num_mpz_t());
  mpz_sqrt(den_root.get_mpz_t(), squared.get_den_mpz_t());
  if (num_root * num_root == squared.get_num() && den_root * den_root == squared.get_den()) {
    Rational length(num_root, den_root);
    length.canonicalize();
    return tg::scale(Rational(1 / length), v);
  }
  Rational length = tg::approximate_sqrt(squared);
  return tg::point_on_circle_near(Point{0, 0}, Rational(1),
                                  tg::scale(Rational(1 / length), v), pointer, what, roundings);
}

}  // namespace

// Teeth built for a wheel driven counter-clockwise, mirrored for "cw": tooth k's leading tip
// corner at 2 pi k / z on the tip circle, an optional flat top (club) of angular width tip_angle
// behind it, a locking face from the leading corner to the root circle whose root lags by
// face_angle (rake), and a straight back from the root circle at back_angle behind the leading
// corner up to the trailing top corner. Between a face root and the next back root runs an arc
// of the root circle (none when back_angle = pitch + face_angle, the default: ratchet teeth).
std::vector<Loop> expand_escape_wheel(const Arguments& arguments,
                                      std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  long teeth = arguments.count("teeth", 3, 2000);
  Rational tip_radius = arguments.positive_length("tip_radius");
  Rational root_radius = arguments.positive_length("root_radius");
  Rational phase = arguments.angle("phase");
  bool driven_ccw = arguments.counter_clockwise("dir", false);
  Rational tip_angle = arguments.angle("tip_angle");
  Rational face_angle = arguments.angle("face_angle");
  if (tip_angle < 0) throw ModelError(arguments.at("tip_angle"), "must not be negative");
  if (face_angle < 0) throw ModelError(arguments.at("face_angle"), "must not be negative");
  // root below tip, the tooth's angles within the pitch (template_rules.cpp, shared with the
  // tolerance box's check)
  check_rules("escape_wheel", arguments, teeth);
  Rational pitch_turns(2, teeth);  // the pitch as a multiple of pi
  pitch_turns.canonicalize();      // 2/teeth is not in lowest terms for an even tooth count
  bool has_root_arc = arguments.has("back_angle");
  Rational back_angle = has_root_arc ? arguments.angle("back_angle") : Rational(0);

  Point trailing = tip_angle == 0
                       ? Point{Rational(1), Rational(0)}
                       : exact_unit_vector(Rational(-tip_angle), arguments.at("tip_angle"),
                                           "-tip_angle", roundings);
  Point rake = face_angle == 0
                   ? Point{Rational(1), Rational(0)}
                   : exact_unit_vector(Rational(-face_angle), arguments.at("face_angle"),
                                       "-face_angle", roundings);
  Point leading_corner{tip_radius, Rational(0)};
  Point trailing_corner = tg::scale(tip_radius, trailing);
  Point face_root = tg::scale(root_radius, rake);
  Point back_root = face_root;  // of the previous tooth, rotated: no root arc
  if (has_root_arc)
    back_root = tg::scale(root_radius, exact_unit_vector(Rational(-back_angle),
                                                         arguments.at("back_angle"),
                                                         "-back_angle", roundings));

  Point phase_unit = exact_unit_vector(phase, arguments.at("phase"), "phase", roundings);
  std::vector<Point> turn(teeth);
  for (long k = 0; k < teeth; ++k)
    turn[k] = exact_unit_vector_pi(Rational(pitch_turns * k), pointer, tooth(k) + " direction",
                                   roundings);
  // Canonical (counter-clockwise driven) frame, then mirrored for clockwise, then placed.
  auto at = [&](long k, const Point& local) {
    Point p = tg::rotate(local, turn[((k % teeth) + teeth) % teeth]);
    if (!driven_ccw) p = tg::mirror(p);
    return tg::add(center, tg::rotate(p, phase_unit));
  };
  Point wheel_center = center;
  tg::LoopBuilder loop(at(teeth - 1, face_root), pointer);
  for (long k = 0; k < teeth; ++k) {
    if (has_root_arc)
      loop.arc_to(at(k, back_root), wheel_center, driven_ccw, "root " + std::to_string(k + 1));
    if (tip_angle != 0) {
      loop.line_to(at(k, trailing_corner), tooth(k) + " back");
      loop.line_to(at(k, leading_corner), tooth(k) + " top");
    } else {
      loop.line_to(at(k, leading_corner), tooth(k) + " back");
    }
    loop.line_to(at(k, face_root), tooth(k) + " face");
  }
  return {loop.finish()};
}

// A dead-beat (Graham-type) anchor. Canonical frame: pivot A at the origin, escape wheel
// centre W at (0, -D) (D = |A - W|), fork pointing away from the wheel (+y). The tangents from A
// touch the wheel's tip circle at distance L = sqrt(D^2 - R^2) from A. Both pallets span the
// radii L -+ pallet_width/2 about A. The entry pallet (left) locks on its outer face, the exit
// pallet (right) on its inner face: both are arcs about A (no recoil). Their impulse faces are
// straight and each spans `lift` of anchor rotation; the impulse intervals of the two pallets
// overlap by `lock`, which is the locking depth when the wheel drops onto a pallet.
std::vector<Loop> expand_anchor(const Arguments& arguments, std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point pivot = arguments.point("center");
  Point wheel = arguments.point("wheel_center");
  Rational wheel_radius = arguments.positive_length("wheel_radius");
  Rational width = arguments.positive_length("pallet_width");
  Rational lift = arguments.angle("lift");
  Rational lock = arguments.angle("lock");
  Rational default_extent = Rational(174533, 500000);  // canonical 0.349066:  // about 20 degrees
  Rational extent = arguments.angle("pallet_extent", default_extent);
  Rational fork_length = arguments.positive_length("fork_length");
  Rational fork_width = arguments.positive_length("fork_width");
  Rational slot_width = arguments.positive_length("fork_slot_width");
  Rational slot_depth = arguments.positive_length("fork_slot_depth");
  if (lift <= 0) throw ModelError(arguments.at("lift"), "must be positive");
  if (lock < 0) throw ModelError(arguments.at("lock"), "must not be negative");
  if (extent <= 0) throw ModelError(arguments.at("pallet_extent"), "must be positive");
  // the angles' sum, the pivot outside the wheel, the pallet circle and the fork
  // (template_rules.cpp, shared with the tolerance box's check)
  check_rules("anchor", arguments, 0);

  Point axis = tg::subtract(pivot, wheel);  // from the wheel centre to the pivot
  Rational distance_squared = tg::squared_norm(axis);
  double D = std::sqrt(tg::approximate_squared_length(distance_squared));
  double R = tg::approximate_length(wheel_radius);
  Rational tangent = tg::round_length(tg::approximate_sqrt(distance_squared - wheel_radius * wheel_radius));
  roundings.push_back(Rounding{pointer, "anchor tangent length sqrt(|center - wheel_center|^2 - "
                                        "wheel_radius^2)",
                               tangent, tg::length_rounding_bound()});
  Rational inner = tangent - width / 2;
  Rational outer = tangent + width / 2;
  Rational half_fork = fork_width / 2;
  Rational half_slot = slot_width / 2;

  auto path_angle = [&](double rho) {
    // Angle at A between A->W and A->P for P on the wheel's tip circle at distance rho from A.
    double c = (D * D + rho * rho - R * R) / (2 * D * rho);
    return std::acos(std::max(-1.0, std::min(1.0, c)));
  };
  double down = 1.5 * M_PI;
  double rho_in = tg::approximate_length(inner), rho_out = tg::approximate_length(outer);
  double lift_d = tg::approximate(lift), lock_d = tg::approximate(lock);
  double extent_d = tg::approximate(extent);
  double entry_corner = down - path_angle(rho_out) - lift_d / 2 + lock_d / 2;
  double exit_corner = down + path_angle(rho_in) + lift_d / 2 - lock_d / 2;
  if (entry_corner + lift_d >= down || exit_corner - lift_d <= down)
    throw ModelError(arguments.at("lift"), "the pallets would meet under the pivot: reduce lift "
                                           "or pallet_width");

  auto polar = [&](const Rational& radius, double angle, const std::string& what) {
    double r = tg::approximate_length(radius);
    Point near{tg::length_from(r * std::cos(angle)), tg::length_from(r * std::sin(angle))};
    return tg::point_on_circle_near(Point{0, 0}, radius, near, pointer, what, roundings);
  };
  Point entry_lock_corner = polar(outer, entry_corner, "entry pallet locking corner");
  Point entry_discharge = polar(inner, entry_corner + lift_d, "entry pallet discharge corner");
  Point entry_outer_end = polar(outer, entry_corner - extent_d, "entry pallet outer end");
  Point entry_inner_end = polar(inner, entry_corner - extent_d, "entry pallet inner end");
  Point exit_lock_corner = polar(inner, exit_corner, "exit pallet locking corner");
  Point exit_discharge = polar(outer, exit_corner - lift_d, "exit pallet discharge corner");
  Point exit_outer_end = polar(outer, exit_corner + extent_d, "exit pallet outer end");
  Point exit_inner_end = polar(inner, exit_corner + extent_d, "exit pallet inner end");
  Rational fork_base_y =
      tg::approximate_sqrt(Rational(outer * outer - half_fork * half_fork));
  Point fork_base_right =
      tg::point_on_circle_near(Point{0, 0}, outer, Point{half_fork, fork_base_y}, pointer,
                               "fork base on the pallet circle", roundings);
  Point fork_base_left{-fork_base_right.x, fork_base_right.y};
  // The fork's outer sides run parallel to its axis from the pallet circle to the fork's end, at
  // the abscissa of their exact base points (within the recorded displacement of fork_width / 2):
  // their lengths fork_length - y are rational, so a pin's tangency to them is a contact curve of
  // degree 2 in each half-angle tangent (kernels/contact_table.hpp), where a side to the exact
  // (fork_width / 2, fork_length) from a point of the circle has an irrational length (degree 4).
  Point fork_end_right{fork_base_right.x, fork_length};
  Point fork_end_left{-fork_base_right.x, fork_length};
  Rational notch_depth = tg::round_length(tg::length_from((D - R) / 2));
  Point notch{Rational(0), Rational(-notch_depth)};

  // Canonical +y is the direction from the wheel to the pivot.
  Point up = unit_toward(axis, pointer, "anchor axis direction (wheel centre to pivot)",
                         roundings);
  Point frame{up.y, -up.x};  // rotates (0, 1) onto `up`
  auto at = [&](const Point& local) { return tg::add(pivot, tg::rotate(local, frame)); };
  Point origin = at(Point{0, 0});

  tg::LoopBuilder loop(at(exit_discharge), pointer);
  loop.arc_to(at(exit_outer_end), origin, true, "exit pallet back");
  loop.arc_to(at(fork_base_right), origin, true, "arm R");
  loop.line_to(at(fork_end_right), "fork R outer");
  loop.line_to(at(Point{half_slot, fork_length}), "fork R tip");
  loop.line_to(at(Point{half_slot, Rational(fork_length - slot_depth)}), "fork slot wall R");
  loop.line_to(at(Point{-half_slot, Rational(fork_length - slot_depth)}), "fork slot bottom");
  loop.line_to(at(Point{-half_slot, fork_length}), "fork slot wall L");
  loop.line_to(at(fork_end_left), "fork L tip");
  loop.line_to(at(fork_base_left), "fork L outer");
  loop.arc_to(at(entry_outer_end), origin, true, "arm L");
  loop.arc_to(at(entry_lock_corner), origin, true, "entry locking face");
  loop.line_to(at(entry_discharge), "entry impulse face");
  loop.arc_to(at(entry_inner_end), origin, false, "entry pallet back");
  loop.line_to(at(notch), "notch L");
  loop.line_to(at(exit_inner_end), "notch R");
  loop.arc_to(at(exit_lock_corner), origin, false, "exit locking face");
  loop.line_to(at(exit_discharge), "exit impulse face");
  return {loop.finish()};
}

// A roller disc with an impulse pin: the disc circle (radius) and the pin circle (pin_radius
// at pin_center_radius, direction phase) merged into one outline. The two circles meet at
// irrational points; exact points on the disc circle next to them are used and the pin circle
// passes through both (its radius changes by at most the recorded bound).
std::vector<Loop> expand_balance(const Arguments& arguments, std::vector<Rounding>& roundings) {
  const std::string& pointer = arguments.pointer();
  Point center = arguments.point("center");
  Rational radius = arguments.positive_length("radius");
  Rational pin_radius = arguments.positive_length("pin_radius");
  Rational pin_distance = arguments.positive_length("pin_center_radius");
  Rational phase = arguments.angle("phase");
  check_rules("balance", arguments, 0);   // the pin and the disc (template_rules.cpp)
  Rational along =
      (pin_distance * pin_distance + radius * radius - pin_radius * pin_radius) / (2 * pin_distance);
  Rational across = tg::approximate_sqrt(Rational(radius * radius - along * along));
  // The pin keeps its rational radius (its tangency to a segment of rational length is then a
  // contact curve of degree 2 in each half-angle tangent, kernels/contact_table.hpp; through
  // points of the disc circle its squared radius would be irrational and the curve of degree 4):
  // the junctions are exact points of the pin circle next to the circles' crossings, mirror
  // images in the pin's axis, and the rim is the arc about the centre through them (its radius
  // within the recorded displacement of `radius`).
  Point pin_center{pin_distance, Rational(0)};
  Point meet = tg::point_on_circle_near(pin_center, pin_radius, Point{along, across}, pointer,
                                        "impulse pin meets the disc (exact point of the pin circle; the rim "
                                        "passes through it)",
                                        roundings);
  Point meet_below = tg::mirror(meet);
  Point unit = exact_unit_vector(phase, arguments.at("phase"), "phase", roundings);
  auto at = [&](const Point& local) { return tg::add(center, tg::rotate(local, unit)); };
  tg::LoopBuilder loop(at(meet), pointer);
  loop.arc_to(at(meet_below), center, true, "rim");
  loop.arc_to(at(meet), at(pin_center), true, "impulse pin");
  return {loop.finish()};
}

}  // namespace hipair::model_detail::template_detail
