#include "core/model_scale.hpp"

#include <hipair/error.hpp>

#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace hipair {

namespace {

// floor(log2 |value|) within one: bits of the numerator minus bits of the denominator.
long binary_exponent(const Rational& value) {
  return static_cast<long>(mpz_sizeinbase(value.get_num_mpz_t(), 2)) -
         static_cast<long>(mpz_sizeinbase(value.get_den_mpz_t(), 2));
}

// The exact axis-aligned box of the points seen (empty until the first): its sides are the
// extreme coordinates themselves, read in place (the points must outlive the box; no rational
// is copied per improvement).
struct BoundingBox {
  const Rational *x_lo = nullptr, *x_hi = nullptr, *y_lo = nullptr, *y_hi = nullptr;
  void see(const Point& p) {
    if (!x_lo || p.x < *x_lo) x_lo = &p.x;
    if (!x_hi || p.x > *x_hi) x_hi = &p.x;
    if (!y_lo || p.y < *y_lo) y_lo = &p.y;
    if (!y_hi || p.y > *y_hi) y_hi = &p.y;
  }
  bool empty() const { return !x_lo; }
  /// The larger side. \pre !empty()
  Rational size() const { return std::max(Rational(*x_hi - *x_lo), Rational(*y_hi - *y_lo)); }
};

// Every edge's source and target of `part` into `box`, and its arcs' centres when `arc_centres`:
// the one walk behind normalising_translation (centres in) and require_feature_spread (out).
void see_vertices(BoundingBox& box, const Part& part, bool arc_centres) {
  for (const auto& loop : part.loops)
    for (const auto& edge : loop.edges) {
      box.see(edge.source);
      box.see(edge.target);
      if (arc_centres && edge.kind == Edge::Kind::arc) box.see(edge.center);
    }
}

}  // namespace

void require_kinematic_length_scale(const Model& model, const std::vector<std::size_t>& parts) {
  Rational largest = 0;                   // of the parts' points
  const Part* widest = nullptr;           // the part that reaches it
  const Part* length_coordinate = nullptr;   // the first part that neither rotates nor stays fixed
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    if (!length_coordinate && part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed)
      length_coordinate = &part;
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center})
          for (const Rational* v : {&p->x, &p->y})
            if (abs(*v) > largest) {
              largest = abs(*v);
              widest = &part;
            }
  }
  if (!length_coordinate || sgn(largest) == 0) return;
  const long exponent = binary_exponent(largest);
  if (exponent >= -30 && exponent <= 30) return;
  const Motion::Kind kind = length_coordinate->motion.kind;
  const char* how = kind == Motion::Kind::translation ? "translates"
                    : kind == Motion::Kind::planar    ? "moves in the plane"
                                                      : "slides in a slot";
  throw GeometryError("part '" + length_coordinate->name + "' (" + length_coordinate->pointer + ") " + how +
                      ": the kinematic analysis of a mechanism with a length coordinate needs its lengths between "
                      "about 1e-9 mm and 1e9 mm (its positions are lengths and its resolutions absolute), and part '" +
                      widest->name + "' (" + widest->pointer + ") reaches about 2^" + std::to_string(exponent) +
                      " mm: scale the model (`hipair analyze` analyses such a model divided exactly by a power of ten, and "
                      "`hipair cspace` builds such a pair in units of 2^L mm)");
}

long normalising_shift(const Model& model, const std::vector<std::size_t>& parts) {
  Rational largest = 0;
  auto see = [&](const Rational& value) {
    if (abs(value) > largest) largest = abs(value);
  };
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    if (part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed) return 0;
    if (part.motion.kind == Motion::Kind::rotation) {
      see(part.motion.pivot.x);
      see(part.motion.pivot.y);
    }
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          see(p->x);
          see(p->y);
        }
  }
  if (sgn(largest) == 0) return 0;
  long exponent = binary_exponent(largest);
  if (exponent >= -30 && exponent <= 60) return 0;   // about 1e-9 mm .. 1e18 mm: as is
  return exponent - 6;
}

void require_length_coordinates_in_range(const Model& model, const std::vector<std::size_t>& parts) {
  bool lengths = false;
  for (std::size_t index : parts) {
    Motion::Kind kind = model.parts.at(index).motion.kind;
    lengths = lengths || (kind != Motion::Kind::rotation && kind != Motion::Kind::fixed);
  }
  if (!lengths) return;
  // |value| < 2^1016 exactly: the numerator has fewer bits than the denominator plus 1016
  // (comparisons with +-bound: no absolute value copied per coordinate)
  static const Rational limit(mpz_class(1) << 1016);
  static const Rational negative_limit(-limit);
  auto check = [&](const Rational& value, const Part& part) {
    if (value < limit && value > negative_limit) return;
    throw GeometryError("part '" + part.name + "' (" + part.pointer + ") has lengths beyond 2^1016 mm (about 7e305 mm) and "
                        "a pair of it has lengths as C-space coordinates, which must stay within the range of doubles: "
                        "scale the model down");
  };
  // Below: a pair with arcs whose every length lies under 2^-1000 mm (about 9e-302 mm) goes
  // through the quadratic traits with double enclosures in the subnormal range, and at 1e-331
  // it gave a wrong cell (free where the parts overlap) and a failed self-check: refused.
  // Polygon pairs are built by exact CGAL traits and stay correct there (tests/unit/cspace_scale_test.cpp).
  static const Rational tiny(mpz_class(1), mpz_class(1) << 1000);
  static const Rational negative_tiny(-tiny);
  bool below_tiny = true;   // every noted |value| < tiny (the largest below it)
  bool arcs = false;
  auto note = [&](const Rational& value) {
    if (below_tiny && !(value < tiny && value > negative_tiny)) below_tiny = false;
  };
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    if (part.motion.translation_limits) {
      note(part.motion.translation_limits->lo);
      note(part.motion.translation_limits->hi);
    }
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges) {
        arcs = arcs || edge.kind == Edge::Kind::arc;
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          note(p->x);
          note(p->y);
        }
      }
  }
  if (arcs && below_tiny) {
    const Part& part = model.parts.at(parts.front());
    throw GeometryError("part '" + part.name + "' (" + part.pointer + ") and the part it is paired with have all their lengths "
                        "below 2^-1000 mm (about 9e-302 mm), have arcs, and a pair of them has lengths as C-space "
                        "coordinates, which must stay within the normal range of doubles: scale the model up");
  }
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    check(part.motion.pivot.x, part);
    check(part.motion.pivot.y, part);
    if (part.motion.translation_limits) {
      check(part.motion.translation_limits->lo, part);
      check(part.motion.translation_limits->hi, part);
    }
    for (const Rational* v : {&part.initial.offset, &part.initial.x, &part.initial.y}) check(*v, part);
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          check(p->x, part);
          check(p->y, part);
        }
  }
}

long length_coordinate_shift(const Model& model, const std::vector<std::size_t>& parts) {
  bool lengths = false, arcs = false;
  Rational largest = 0;
  auto see = [&](const Rational& value) {
    if (abs(value) > largest) largest = abs(value);
  };
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    lengths = lengths || (part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed);
    see(part.motion.pivot.x);
    see(part.motion.pivot.y);
    if (part.motion.translation_limits) {
      see(part.motion.translation_limits->lo);
      see(part.motion.translation_limits->hi);
    }
    for (const Rational* v : {&part.initial.offset, &part.initial.x, &part.initial.y}) see(*v);
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges) {
        arcs = arcs || edge.kind == Edge::Kind::arc;
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          see(p->x);
          see(p->y);
        }
      }
  }
  if (!lengths || sgn(largest) == 0) return 0;
  // the bounds of require_length_coordinates_in_range (|value| < 2^1016; arcs with every length < 2^-1000)
  const bool huge = !(largest < Rational(mpz_class(1) << 1016));
  const bool tiny = arcs && largest < Rational(mpz_class(1), mpz_class(1) << 1000);
  if (!huge && !tiny) return 0;
  return binary_exponent(largest) - 6;
}

std::optional<Point> normalising_translation(const Model& model, const std::vector<std::size_t>& parts) {
  BoundingBox box;
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    if (part.motion.kind != Motion::Kind::fixed && part.motion.kind != Motion::Kind::translation)
      box.see(part.motion.pivot);   // a centre of turning belongs to the pair's extent
    see_vertices(box, part, true);
  }
  if (box.empty()) return std::nullopt;
  // (the test below in this thread's scratch rationals, written in place: a pair built again and
  // again makes no rational here; the same exact comparison as |centre| <= 2^20 size, doubled)
  thread_local Rational width, height, sum_x, sum_y, far_x, far_y, bound;
  mpq_sub(width.get_mpq_t(), box.x_hi->get_mpq_t(), box.x_lo->get_mpq_t());
  mpq_sub(height.get_mpq_t(), box.y_hi->get_mpq_t(), box.y_lo->get_mpq_t());
  const Rational& size = width < height ? height : width;   // (box.size())
  if (sgn(size) == 0) return std::nullopt;
  mpq_add(sum_x.get_mpq_t(), box.x_lo->get_mpq_t(), box.x_hi->get_mpq_t());   // 2 cx
  mpq_add(sum_y.get_mpq_t(), box.y_lo->get_mpq_t(), box.y_hi->get_mpq_t());   // 2 cy
  mpq_abs(far_x.get_mpq_t(), sum_x.get_mpq_t());
  mpq_abs(far_y.get_mpq_t(), sum_y.get_mpq_t());
  const Rational& twice_far = far_x < far_y ? far_y : far_x;
  mpq_mul_2exp(bound.get_mpq_t(), size.get_mpq_t(), 21);
  // |centre| <= 2^20 * size: as is (every example; the doubles keep about 30 bits of the parts)
  if (twice_far <= bound) return std::nullopt;
  Rational cx = sum_x / 2, cy = sum_y / 2;
  const long e = binary_exponent(size);
  auto round_down = [e](const Rational& v) {   // floor(v / 2^e) * 2^e, exactly
    Rational q = v;
    if (e >= 0)
      mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
    else
      mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
    mpz_class floor;
    mpz_fdiv_q(floor.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
    Rational r(floor);
    if (e >= 0)
      mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
    else
      mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
    return r;
  };
  return Point{round_down(cx), round_down(cy)};
}

namespace {

// Every length of a model's geometry, motion and initial pose (edges' points and squared radii,
// pivots, translation limits, initial offsets and positions) through `scale(value, power)`,
// power 1 for a length and 2 for a squared length: the one walk behind scaled_model (powers of
// two) and decimal_scaled_model (powers of ten).
template <class Scale>
void scale_lengths(Model& model, Scale scale) {
  auto scale_point = [&](Point& p) {
    scale(p.x, 1);
    scale(p.y, 1);
  };
  for (Part& part : model.parts) {
    for (Loop& loop : part.loops)
      for (Edge& edge : loop.edges) {
        scale_point(edge.source);
        scale_point(edge.target);
        scale_point(edge.center);
        scale(edge.radius_squared, 2);
      }
    scale_point(part.motion.pivot);
    if (part.motion.translation_limits) {
      scale(part.motion.translation_limits->lo, 1);
      scale(part.motion.translation_limits->hi, 1);
    }
    scale(part.initial.offset, 1);
    scale(part.initial.x, 1);
    scale(part.initial.y, 1);
  }
}

}  // namespace

Model translated_model(const Model& model, const Point& by) {
  auto move = [&](Point& p) {
    p.x -= by.x;
    p.y -= by.y;
  };
  Model moved = model;
  for (Part& part : moved.parts) {
    for (Loop& loop : part.loops)
      for (Edge& edge : loop.edges) {
        move(edge.source);
        move(edge.target);
        if (edge.kind == Edge::Kind::arc) move(edge.center);   // a segment's is unused (0)
      }
    // a pivot means something only for a part that turns (a fixed or translating part's
    // pivot is unused, and stays as read)
    if (part.motion.kind != Motion::Kind::fixed && part.motion.kind != Motion::Kind::translation)
      move(part.motion.pivot);
  }
  return moved;
}

std::optional<Model> pair_moved_to_origin(const Model& model, std::string_view first, std::string_view second) {
  std::vector<std::size_t> pair;
  for (std::size_t k = 0; k < model.parts.size(); ++k)
    if (model.parts[k].name == first || model.parts[k].name == second) pair.push_back(k);
  std::optional<Point> by = normalising_translation(model, pair);
  if (!by) return std::nullopt;
  return translated_model(model, *by);
}

std::optional<NormalisedMechanism> normalised_mechanism(const Model& model) {
  std::vector<std::size_t> parts(model.parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) parts[k] = k;
  std::optional<Point> by = normalising_translation(model, parts);
  std::optional<Model> moved;
  if (by) moved = translated_model(model, *by);
  const long shift = normalising_shift(moved ? *moved : model, parts);
  if (!by && shift == 0) return std::nullopt;
  NormalisedMechanism out;
  out.model = shift != 0 ? scaled_model(moved ? *moved : model, shift) : std::move(*moved);
  if (by) out.by = *by;
  out.shift = shift;
  return out;
}

Point NormalisedMechanism::to_model(const Point& p) const {
  Point out{times_power_of_two(p.x, shift), times_power_of_two(p.y, shift)};
  out.x += by.x;
  out.y += by.y;
  return out;
}

namespace {

// 10^|exponent| as an integer.
mpz_class power_of_ten(long exponent) {
  mpz_class out;
  mpz_ui_pow_ui(out.get_mpz_t(), 10, static_cast<unsigned long>(exponent < 0 ? -exponent : exponent));
  return out;
}

// floor(log10 value) for value > 0, exactly.
long decimal_exponent(const Rational& value) {
  // log10(2) < 0.30103: a first guess within one or two of the answer, then exact comparisons
  long guess = static_cast<long>(std::floor(static_cast<double>(binary_exponent(value)) * 0.30102999566398));
  auto ten_to = [](long e) { return e >= 0 ? Rational(power_of_ten(e)) : Rational(mpz_class(1), power_of_ten(e)); };
  while (ten_to(guess) > value) --guess;
  while (ten_to(guess + 1) <= value) ++guess;
  return guess;
}

}  // namespace

long kinematic_decimal_exponent(const Model& model) {
  std::vector<std::size_t> parts(model.parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) parts[k] = k;
  std::optional<Model> moved;
  if (std::optional<Point> by = normalising_translation(model, parts)) moved = translated_model(model, *by);
  const Model& measured = moved ? *moved : model;
  bool length_coordinate = false;
  Rational largest = 0;
  for (const Part& part : measured.parts) {
    length_coordinate = length_coordinate || (part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed);
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center})
          for (const Rational* v : {&p->x, &p->y})
            if (abs(*v) > largest) largest = abs(*v);
  }
  if (sgn(largest) == 0) return 0;
  const long binary = binary_exponent(largest);
  if (length_coordinate && binary >= -30 && binary <= 30) return 0;   // require_kinematic_length_scale's range: as is
  if (!length_coordinate) {
    // rotation-only: normalising_shift's range (its pivots too) decides; a power of ten then
    // rather than its power of two, so that a model scaled by 10^(10 j) is analysed as at 1
    // (a power of two left the copy another model: the escapement x 1e400's jam enclosure
    // differed from x 1's in the 12th digit, both certified)
    std::vector<std::size_t> all(measured.parts.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    if (normalising_shift(measured, all) == 0) return 0;
    for (const Part& part : measured.parts)
      if (part.motion.kind == Motion::Kind::rotation)
        for (const Rational* v : {&part.motion.pivot.x, &part.motion.pivot.y})
          if (abs(*v) > largest) largest = abs(*v);
  }
  return decimal_unit_exponent(largest);
}

long decimal_unit_exponent(const Rational& magnitude) {
  if (sgn(magnitude) <= 0) return 0;
  // 10 * floor((d + 4) / 10), d = floor(log10 magnitude): magnitude / 10^E within [1e-4, 1e6)
  const long shifted = decimal_exponent(magnitude) + 4;
  return 10 * (shifted >= 0 ? shifted / 10 : -((-shifted + 9) / 10));
}

Rational power_of_ten_rational(long exponent) {
  return exponent >= 0 ? Rational(power_of_ten(exponent)) : Rational(mpz_class(1), power_of_ten(exponent));
}

Model decimal_scaled_model(const Model& model, long exponent) {
  if (exponent == 0) return model;
  const Rational factor = exponent > 0 ? Rational(mpz_class(1), power_of_ten(exponent)) : Rational(power_of_ten(exponent));
  const Rational square = factor * factor;
  Model scaled = model;
  scale_lengths(scaled, [&](Rational& value, int power) { value *= power == 1 ? factor : square; });
  for (Part& part : scaled.parts)
    if (part.dynamics) {
      if (part.dynamics->linear_spring) part.dynamics->linear_spring->rest *= factor;
      if (part.dynamics->force) {
        part.dynamics->force->x *= factor;
        part.dynamics->force->y *= factor;
      }
    }
  return scaled;
}

Model decimal_scaled_dynamics_model(const Model& model, long exponent) {
  if (exponent == 0) return model;
  Model scaled = decimal_scaled_model(model, exponent);
  const Rational factor = exponent > 0 ? Rational(mpz_class(1), power_of_ten(exponent)) : Rational(power_of_ten(exponent));
  const Rational square = factor * factor;
  auto scale_point = [&](Point& p) {
    p.x *= factor;
    p.y *= factor;
  };
  for (Part& part : scaled.parts) {
    if (!part.dynamics) continue;
    Dynamics& d = *part.dynamics;
    const bool rotating = part.motion.kind == Motion::Kind::rotation;
    if (d.moment_of_inertia) *d.moment_of_inertia *= square;   // kg mm^2
    if (d.torsional_spring) d.torsional_spring->stiffness *= square;   // N mm / rad
    if (d.torque) *d.torque *= square;                          // N mm
    if (d.damping && rotating) *d.damping *= square;            // N mm s / rad (N s / mm: unchanged)
  }
  if (scaled.simulation) {
    SimulationSpec& spec = *scaled.simulation;
    scale_point(spec.gravity);
    // a planar part's velocity is three entries (vx, vy, omega): the first two are speeds
    std::vector<int> seen(scaled.parts.size(), 0);
    for (SimulationSpec::Velocity& v : spec.velocities) {
      const Motion::Kind kind = scaled.parts.at(v.part).motion.kind;
      const int entry = seen[v.part]++;
      if (kind == Motion::Kind::translation || (kind == Motion::Kind::planar && entry < 2)) v.value *= factor;
    }
    // a planar part's driver is three entries too (vx, vy, omega)
    std::vector<int> driven(scaled.parts.size(), 0);
    for (SimulationSpec::Driver& driver : spec.drivers) {
      const Motion::Kind kind = scaled.parts.at(driver.part).motion.kind;
      const int entry = driven[driver.part]++;
      if (!(kind == Motion::Kind::translation || (kind == Motion::Kind::planar && entry < 2))) continue;
      driver.speed *= factor;
      for (auto& point : driver.profile) point.second *= factor;
    }
    for (SimulationSpec::Coupling& coupling : spec.couplings) {
      scale_point(coupling.first_point);
      scale_point(coupling.second_point);
      coupling.rest_length *= factor;
    }
    for (SimulationSpec::CenterOfMass& centre : spec.centers_of_mass) scale_point(centre.at);
  }
  return scaled;
}

void require_dynamics_in_double_range(const Model& model, const std::string& unit) {
  static const Rational least(std::numeric_limits<double>::min()), largest(std::numeric_limits<double>::max());
  auto check = [&](const Rational& value, const std::string& pointer) {
    if (sgn(value) == 0) return;
    const Rational magnitude = abs(value);
    if (magnitude < least || magnitude > largest)
      throw ModelError(pointer, std::string("in units of ") + unit + " (the model's lengths rescaled to an ordinary size), "
                                    "this value is too " + (magnitude < least ? "small" : "large") +
                                    " for the simulator, which holds dynamics data in doubles: a nonzero magnitude "
                                    "must lie in [2.2250738585072014e-308, 1.7976931348623157e+308]");
  };
  for (const Part& part : model.parts) {
    if (!part.dynamics) continue;
    const Dynamics& d = *part.dynamics;
    const std::string at = part.pointer + "/dynamics/";
    if (d.mass) check(*d.mass, at + "mass");
    if (d.moment_of_inertia) check(*d.moment_of_inertia, at + "moment_of_inertia");
    if (d.torsional_spring) check(d.torsional_spring->stiffness, at + "torsional_spring");
    if (d.linear_spring) {
      check(d.linear_spring->stiffness, at + "linear_spring");
      check(d.linear_spring->rest, at + "linear_spring");
    }
    if (d.torque) check(*d.torque, at + "torque");
    if (d.force) {
      check(d.force->x, at + "force");
      check(d.force->y, at + "force");
    }
    if (d.damping) check(*d.damping, at + "damping");
  }
  if (!model.simulation) return;
  const SimulationSpec& spec = *model.simulation;
  check(spec.gravity.x, spec.pointer + "/gravity");
  check(spec.gravity.y, spec.pointer + "/gravity");
  for (const auto& v : spec.velocities) check(v.value, v.pointer);
  for (const auto& driver : spec.drivers) {
    check(driver.speed, driver.pointer);
    for (const auto& point : driver.profile) check(point.second, driver.pointer);
  }
  for (const auto& coupling : spec.couplings)
    for (const Rational* value : {&coupling.first_point.x, &coupling.first_point.y, &coupling.second_point.x,
                                  &coupling.second_point.y, &coupling.rest_length, &coupling.stiffness, &coupling.damping})
      check(*value, coupling.pointer);
  for (const auto& centre : spec.centers_of_mass) {
    check(centre.at.x, centre.pointer);
    check(centre.at.y, centre.pointer);
  }
}

void require_feature_spread(const Model& model, std::size_t first, std::size_t second) {
  BoundingBox box;
  // vertices only: an arc's centre may lie 10^1000 mm away from a part of a few mm
  // (tests/cli/run_far_arc_tests.sh)
  for (std::size_t index : {first, second}) see_vertices(box, model.parts.at(index), false);
  if (box.empty()) return;
  const Rational extent = box.size();
  if (sgn(extent) == 0) return;
  const long extent_bits = binary_exponent(extent);
  for (std::size_t index : {first, second}) {
    const Part& part = model.parts.at(index);
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges) {
        long size_bits = 0;
        if (edge.kind == Edge::Kind::arc) {
          if (sgn(edge.radius_squared) == 0) continue;
          size_bits = binary_exponent(edge.radius_squared) / 2;   // of the radius, within one
        } else {
          const Rational size = std::max(Rational(abs(Rational(edge.target.x - edge.source.x))),
                                         Rational(abs(Rational(edge.target.y - edge.source.y))));
          if (sgn(size) == 0) continue;
          size_bits = binary_exponent(size);
        }
        if (extent_bits - size_bits <= max_feature_spread_bits) continue;
        const Part& other = model.parts.at(index == first ? second : first);
        throw GeometryError("part '" + part.name + "' (" + part.pointer + ") has an edge (" +
                            (edge.pointer.empty() ? loop.pointer : edge.pointer) + ") of about 2^" +
                            std::to_string(size_bits) + " mm in its pair with '" + other.name +
                            "', which spans about 2^" + std::to_string(extent_bits) +
                            " mm: a pair's smallest edge must be at least 2^-" + std::to_string(max_feature_spread_bits) +
                            " (about 1e-400) of its extent (the exact arithmetic's cost grows with the square of that "
                            "spread's exponent; a whole model may have any scale from 1e-1000 to 1e1000 mm)");
      }
  }
}

void require_feature_spread(const Model& model) {
  for (const PairSpec& pair : model.pairs) require_feature_spread(model, pair.first, pair.second);
}

Rational times_power_of_two(Rational value, long exponent) {
  if (exponent > 0) mpq_mul_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
  if (exponent < 0) mpq_div_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
  return value;
}

Model scaled_model(const Model& model, long shift) {
  Model scaled = model;
  scale_lengths(scaled, [shift](Rational& value, int power) { value = times_power_of_two(std::move(value), -shift * power); });
  return scaled;
}

}  // namespace hipair
