// HIPAIR — simulation of a pin-in-slot part among fixed parts and rotating drivers
// (include/hipair/pin_slot_simulation.hpp; docs/simulation.md, "Pin-in-slot parts").
//
// Coordinates q = (s, psi). Body point p goes to P + R(psi)(p - P) + s R(psi) d (P the pivot,
// the frame's pin; d the slot's unit direction). With the centre of mass c (body point), u =
// R(psi) d and w = R(psi)(c - P) + s u, the centre moves at s' u + psi' k x w, so
//   M = [[m, m e], [m e, I_c + m |w|^2]],  e = d . (k x (c - P)),  |w|^2 = |c - P|^2 + 2 s b + s^2,
//   b = d . (c - P), and Lagrange's equations are
//   m s'' + m e psi''          = Q_s + m psi'^2 (b + s)
//   m e s'' + M22 psi''        = Q_psi - 2 m (b + s) s' psi'
// with Q_s = F . u - k_l (s - s_rest), Q_psi = F . (k x w) + T - k_t (psi - psi_rest), F = m g +
// the constant force. I_c = I_P - m |c - P|^2 (the model gives the moment of inertia about the
// pivot, the body point at the pin when s = 0).
//
// Contacts: at fixed (s, psi) the pin-slot part is a placed planar part (shift s R(psi) d, angle
// psi about P), so each pair's contacts live in the exact 3-DOF C-space of the pin-slot part as
// a planar part against the other part (SlicedSpace), in the other part's frame when it is a
// rotating driver (the relative configuration is exact from rational half-angle tangents). A
// step's relative motion is covered by straight chords in (x, y, tan(theta/2)) whose deviation
// from the integrated path is at most delta/2 (estimated from the path's midpoint, the deviation
// of a quadratic path, doubled) and each chord is tested exactly by first_crossing; the state's
// exact configuration in each pair is the chord's point at the certified free side of the first
// crossing, so every accepted configuration is free. A pair whose boundaries are exactly farther
// apart at the step's start than twice the step's travel bound (plus delta), and exactly apart at
// its end, needs no chord (the far test: exact edge distances, a double travel bound).
#include <hipair/error.hpp>
#include <hipair/pin_slot_simulation.hpp>

#include "simulation/relative_configuration.hpp"
#include "simulation/units.hpp"

#include "kernels/distance.hpp"
#include "kernels/vector.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

namespace hipair {
namespace {

double wrap(double theta) {
  double w = std::remainder(theta, 2 * std::numbers::pi);
  return w <= -std::numbers::pi ? w + 2 * std::numbers::pi : w;
}

SlicedAngle exact_angle(double theta) {
  if (!std::isfinite(theta))
    throw NumericError("the simulated angle of a pin-slot simulation is not finite (a diverging integration)");
  SlicedAngle a;
  const double w = wrap(theta);
  if (w == std::numbers::pi) a.half_turn = true;
  else a.t = Rational(std::tan(w / 2));
  return a;
}

using simulation_detail::cos_sin;
using simulation_detail::relative_configuration;

// The chart coordinate of a configuration's angle: tan(theta/2), or (flip) tan((theta - pi)/2).
Rational chart_w(const SlicedAngle& a, bool flip) {
  if (!flip) return a.t;
  if (a.half_turn) return Rational(0);
  return Rational(-1) / a.t;
}

// The point at u of the straight motion from -> to in (x, y, w), exactly.
SlicedConfiguration chord_point(const SlicedConfiguration& from, const SlicedConfiguration& to, bool flip,
                                const Rational& u) {
  SlicedConfiguration c;
  c.x = from.x + u * (to.x - from.x);
  c.y = from.y + u * (to.y - from.y);
  c.x.canonicalize();
  c.y.canonicalize();
  const Rational w0 = chart_w(from.angle, flip), w1 = chart_w(to.angle, flip);
  Rational w = w0 + u * (w1 - w0);
  w.canonicalize();
  if (!flip) {
    c.angle.t = w;
  } else if (sgn(w) == 0) {
    c.angle.half_turn = true;
  } else {
    c.angle.t = Rational(-1) / w;
    c.angle.t.canonicalize();
  }
  return c;
}

using State4 = std::array<double, 4>;   // s, psi, s', psi'

// An axis-aligned box holding an edge, exact.
struct Box {
  Rational lo[2], hi[2];
};

// A rational upper bound of sqrt(v), v >= 0.
Rational sqrt_upper(const Rational& v) {
  Rational r(std::sqrt(v.get_d()) * (1 + 1e-12) + 1e-300);
  while (r * r < v) r *= Rational(2);
  return r;
}

// The box of an edge whose points are placed by p -> pivot + R (p - pivot) + shift (cos c, sin s)
// (an arc: the box of its whole circle).
Box edge_box(const Edge& e, const Point& pivot, const Rational& c, const Rational& s, const Rational& sx,
             const Rational& sy) {
  auto place = [&](const Point& p) {
    const Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
    return std::array<Rational, 2>{pivot.x + c * dx - s * dy + sx, pivot.y + s * dx + c * dy + sy};
  };
  Box b;
  if (e.is_arc()) {
    const auto m = place(e.center);
    const Rational r = sqrt_upper(e.radius_squared);
    for (int k = 0; k < 2; ++k) {
      b.lo[k] = m[k] - r;
      b.hi[k] = m[k] + r;
    }
    return b;
  }
  const auto a = place(e.source), z = place(e.target);
  for (int k = 0; k < 2; ++k) {
    b.lo[k] = std::min(a[k], z[k]);
    b.hi[k] = std::max(a[k], z[k]);
  }
  return b;
}

using P2 = kernels::Vector<Rational>;
using kernels::point_segment_squared_distance;
using kernels::segment_segment_squared_distance;
using kernels::squared_distance;

// A placed edge: a segment [a, b], or (arc) the whole circle of centre m and squared radius r2
// (the arc lies on it, so a distance from the circle bounds the arc's from below).
struct PlacedEdge {
  bool arc = false;
  P2 a, b, m;
  Rational r2, r_up, r_lo;   // arcs: r_lo <= r <= r_up
};

// Are the two edges certainly farther apart than d >= 0? Exact.
bool edges_apart(const PlacedEdge& e, const PlacedEdge& f, const Rational& d) {
  if (!e.arc && !f.arc) {
    return segment_segment_squared_distance(e.a, e.b, f.a, f.b) > d * d;
  }
  if (e.arc && f.arc) {
    const Rational c2 = squared_distance(e.m, f.m);
    const Rational out = e.r_up + f.r_up + d;
    if (c2 > out * out) return true;
    for (const auto& [big, small] : {std::pair{&e, &f}, std::pair{&f, &e}}) {
      const Rational in = big->r_lo - small->r_up - d;   // one circle inside the other
      if (sgn(in) > 0 && c2 < in * in) return true;
    }
    return false;
  }
  const PlacedEdge& seg = e.arc ? f : e;
  const PlacedEdge& circle = e.arc ? e : f;
  const Rational out = circle.r_up + d;
  if (point_segment_squared_distance(circle.m, seg.a, seg.b) > out * out) return true;   // outside the circle
  const Rational in = circle.r_lo - d;
  return sgn(in) > 0 && std::max(squared_distance(seg.a, circle.m), squared_distance(seg.b, circle.m)) < in * in;   // inside it
}

PlacedEdge placed_edge(const Edge& e, const Point& pivot, const Rational& c, const Rational& s, const Rational& sx,
                       const Rational& sy) {
  auto place = [&](const Point& p) {
    const Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
    return P2{pivot.x + c * dx - s * dy + sx, pivot.y + s * dx + c * dy + sy};
  };
  PlacedEdge out;
  if (e.is_arc()) {
    out.arc = true;
    out.m = place(e.center);
    out.r2 = e.radius_squared;
    out.r_up = sqrt_upper(e.radius_squared);
    out.r_lo = e.radius_squared / out.r_up;
  } else {
    out.a = place(e.source);
    out.b = place(e.target);
  }
  return out;
}

// Is the box distance of a and b (the larger of the x and y gaps: a lower bound of the
// Euclidean distance of any two points in them) greater than d? Exact.
bool boxes_apart(const Box& a, const Box& b, const Rational& d) {
  for (int k = 0; k < 2; ++k)
    if (a.lo[k] - b.hi[k] > d || b.lo[k] - a.hi[k] > d) return true;
  return false;
}

}  // namespace

struct PinSlotSimulation::Impl {
  Model model;
  SimulationOptions options;
  double time_scale = 1, force_scale = 1000;
  std::string time_unit = "s", force_unit = "N";
  double g[2] = {0, 0};
  std::size_t part = 0;
  // the pin-slot part, internal units (kg, mm, s, mN)
  double P[2] = {0, 0}, d[2] = {0, 1}, cp[2] = {0, 0};   // pivot, slot direction, c - P (body)
  double mass = 0, inertia_c = 0, e = 0, b = 0, cp2 = 0;
  double force[2] = {0, 0}, torque = 0, k_lin = 0, rest_lin = 0, k_tor = 0, rest_tor = 0;
  std::optional<RationalInterval> slide_limits, angle_limits;
  struct Driver {
    std::size_t part = 0;
    double angle0 = 0, omega = 0;   // rad, rad/s
  };
  std::vector<Driver> drivers;
  std::vector<std::size_t> driver_of;   // model part -> drivers index (no_index: fixed or the pin-slot part)
  struct Pair {
    std::size_t index = 0;   // into Model::pairs
    std::size_t other = 0;   // model part
    double restitution = 0;
    std::shared_ptr<Model> frame_model;   // the other part fixed at its zero configuration, the pin-slot part planar
    SlicedSpace space;
    SlicedConfiguration q;   // the state's exact configuration (free)
    std::vector<Box> other_boxes;   // the other part's edge boxes at its zero configuration
    std::vector<PlacedEdge> other_edges;   // and its edges
  };
  std::vector<Pair> pairs;
  double delta = 0, accuracy = 1e-9, rest_speed = 0;
  // the part's reach from its pin at slide 0 (its points' and arcs' largest distance from P)
  double part_reach = 0;
  // the part's reach from the pin's line position at the states given: part_reach plus their
  // largest |slide| (until session 58 the largest |slide limit|: a slot with limits of 1e9 mm made
  // the chord deviation 1 mm and the rest speed 140 mm/s, and the run stopped at the pin-slot
  // cam's second impact as a contact that would have to be sustained)
  double reach_at(std::initializer_list<const State4*> states) const {
    double slide = 0;
    for (const State4* x : states) slide = std::max(slide, std::abs((*x)[0]));
    return part_reach + slide;
  }
  double t = 0;
  State4 y{};
  std::vector<SimulationEvent> events;
  std::size_t steps = 0, chords = 0;
  double step_guess = 0;
  PinSlotState public_state;

  double driver_angle(std::size_t driver, double time) const {
    return drivers[driver].angle0 + drivers[driver].omega * time;
  }
  // the world configuration of the pin-slot part as a planar part about P, exact
  SlicedConfiguration follower_configuration(const State4& s) const {
    // (before any double becomes a Rational: GMP's mpq_set_d(inf) raises SIGFPE)
    if (!std::isfinite(s[0])) throw NumericError("the simulated slide of a pin-slot part is not finite");
    SlicedConfiguration c;
    c.angle = exact_angle(s[1]);
    auto [cs, sn] = cos_sin(c.angle);
    const Point& dir = model.parts[part].motion.direction;
    const Rational slide(s[0]);
    c.x = slide * (cs * dir.x - sn * dir.y);
    c.y = slide * (sn * dir.x + cs * dir.y);
    c.x.canonicalize();
    c.y.canonicalize();
    return c;
  }
  SlicedConfiguration relative(const Pair& p, const State4& s, double time) const {
    SlicedConfiguration f = follower_configuration(s);
    const std::size_t dr = driver_of[p.other];
    if (dr == no_index) return f;
    SlicedConfiguration a;
    a.angle = exact_angle(driver_angle(dr, time));
    return relative_configuration(model.parts[p.other].motion.pivot, a, model.parts[part].motion.pivot, f);
  }
  double relative_angle(const Pair& p, const State4& s, double time) const {
    const std::size_t dr = driver_of[p.other];
    return wrap(s[1] - (dr == no_index ? 0.0 : driver_angle(dr, time)));
  }
  // mass matrix and the right-hand side of Lagrange's equations
  void dynamics(const State4& s, double M[2][2], double Q[2]) const {
    const double c = std::cos(s[1]), sn = std::sin(s[1]);
    const double u[2] = {c * d[0] - sn * d[1], sn * d[0] + c * d[1]};
    const double rc[2] = {c * cp[0] - sn * cp[1], sn * cp[0] + c * cp[1]};
    const double w[2] = {rc[0] + s[0] * u[0], rc[1] + s[0] * u[1]};
    const double kw[2] = {-w[1], w[0]};
    const double F[2] = {mass * g[0] + force[0], mass * g[1] + force[1]};
    M[0][0] = mass;
    M[0][1] = M[1][0] = mass * e;
    M[1][1] = inertia_c + mass * (cp2 + 2 * s[0] * b + s[0] * s[0]);
    Q[0] = F[0] * u[0] + F[1] * u[1] - k_lin * (s[0] - rest_lin) + mass * s[3] * s[3] * (b + s[0]);
    Q[1] = F[0] * kw[0] + F[1] * kw[1] + torque - k_tor * (s[1] - rest_tor) - 2 * mass * (b + s[0]) * s[2] * s[3];
  }
  // M^-1 v for the mass matrix M = [[m, m e], [m e, M22]] at slide s0, by the Schur complement
  // D = M22 - m e^2 = I_c + m (b + s0)^2 > 0 (|d| = 1: |c - P|^2 = e^2 + b^2): x1 = (v1 - e v0) / D,
  // x0 = v0 / m - e x1. Never through det M = m M22 - (m e)^2 and M22 v0: those products of a mass,
  // a moment of inertia and a force leave the doubles' range long before the data do (lengths
  // 10^-150 gave no motion at all: M22 Q_s underflowed to 0; 10^150 or a mass 10^160 gave inf).
  void inverse_mass_times(double s0, const double v[2], double x[2]) const {
    const double D = inertia_c + mass * (b + s0) * (b + s0);
    x[1] = (v[1] - e * v[0]) / D;
    x[0] = v[0] / mass - e * x[1];
  }
  void rhs(const State4& s, State4& ds) const {
    double M[2][2], Q[2], a[2];
    dynamics(s, M, Q);
    inverse_mass_times(s[0], Q, a);
    ds[0] = s[2];
    ds[1] = s[3];
    ds[2] = a[0];
    ds[3] = a[1];
  }
  // Thrown by flight(.., capped) when the integration over its span needs more than flight_evaluations
  // right-hand sides: a load so violent (a torque of 10^100 N mm) that the part turns many times
  // within the span, which the adaptive stepper then follows in ever smaller steps for hours.
  struct FlightTooLong {};
  static constexpr long flight_evaluations = 60000;
  static constexpr double short_flight = 0x1p-20;
  State4 flight(const State4& from, double span, bool capped = false) const {
    State4 s = from;
    if (span <= 0) return s;
    namespace ode = boost::numeric::odeint;
    auto stepper = ode::make_controlled(accuracy, accuracy, ode::runge_kutta_dopri5<State4>());
    long evaluations = 0;
    // odeint's integrate_adaptive compares times absolutely (t1 - t0 > machine epsilon): a span
    // below 2.2e-16 s was not integrated at all (a follower that a torque of 10^30 N mm turns
    // within 10^-16 s stood still while the time ran on), and up to 2.2e-16 s of a short span was
    // left out. A short span is integrated in the scaled time u = tau / span, over [0, 1].
    const double scale = span < short_flight ? span : 1.0;
    ode::integrate_adaptive(
        stepper,
        [this, &evaluations, capped, scale](const State4& x, State4& dx, double) {
          if (capped && ++evaluations > flight_evaluations) throw FlightTooLong{};
          rhs(x, dx);
          if (scale != 1.0)
            for (double& v : dx) v *= scale;
        },
        s, 0.0, span / scale, span / scale / 8);
    return s;
  }
  double potential(const State4& s) const {
    const double c = std::cos(s[1]), sn = std::sin(s[1]);
    const double u[2] = {c * d[0] - sn * d[1], sn * d[0] + c * d[1]};
    const double X[2] = {c * cp[0] - sn * cp[1] + s[0] * u[0], sn * cp[0] + c * cp[1] + s[0] * u[1]};
    const double F[2] = {mass * g[0] + force[0], mass * g[1] + force[1]};
    return -(F[0] * X[0] + F[1] * X[1]) - torque * s[1] + 0.5 * k_lin * (s[0] - rest_lin) * (s[0] - rest_lin) +
           0.5 * k_tor * (s[1] - rest_tor) * (s[1] - rest_tor);
  }
  double energy_of(const State4& s) const {
    double M[2][2], Q[2];
    dynamics(s, M, Q);
    const double kinetic =
        0.5 * (M[0][0] * s[2] * s[2] + 2 * M[0][1] * s[2] * s[3] + M[1][1] * s[3] * s[3]);
    return kinetic + potential(s);
  }
  std::string where(double time) const {
    std::ostringstream out;
    out << "simulation: at t = " << time / time_scale << " " << time_unit;
    return out.str();
  }
  // The largest deviation (mm) of the pair's relative path from its straight chord over
  // [t0, t0 + h]: twice the midpoint's deviation (exact for a quadratic path) in the shift plus
  // the part's reach times the angle deviation (2 |dw| bounds the angle error).
  double chord_error(const Pair& p, const State4& s0, const State4& sm, const State4& s1, double h, bool flip) const {
    auto rel = [&](const State4& s, double time) {
      const SlicedConfiguration c = relative(p, s, time);
      const double x = c.x.get_d(), yy = c.y.get_d();
      const double w = chart_w(c.angle, flip).get_d();
      return std::array<double, 3>{x, yy, w};
    };
    const auto a = rel(s0, t), m = rel(sm, t + h / 2), z = rel(s1, t + h);
    const double dx = m[0] - (a[0] + z[0]) / 2, dy = m[1] - (a[1] + z[1]) / 2, dw = m[2] - (a[2] + z[2]) / 2;
    return 2 * (std::hypot(dx, dy) + 2 * reach_at({&s0, &sm, &s1}) * std::abs(dw));
  }
  void check_limits(const State4& s, double time) const {
    const Part& pp = model.parts[part];
    if (slide_limits && (Rational(s[0]) < slide_limits->lo || Rational(s[0]) > slide_limits->hi)) {
      std::ostringstream out;
      out << where(time) << ": pin-slot part '" << pp.name << "' leaves its slide limits (s = " << s[0]
          << " mm; " << pp.motion.pointer << "/limits)";
      throw GeometryError(out.str());
    }
    if (angle_limits && (Rational(s[1]) < angle_limits->lo || Rational(s[1]) > angle_limits->hi)) {
      std::ostringstream out;
      out << where(time) << ": pin-slot part '" << pp.name << "' leaves its angle limits (psi = " << s[1]
          << " rad; " << pp.motion.pointer << "/angle_limits)";
      throw GeometryError(out.str());
    }
  }
  void publish() {
    public_state.time = t / time_scale;
    public_state.slide = y[0];
    public_state.angle = y[1];
    public_state.slide_rate = y[2] * time_scale;
    public_state.angle_rate = y[3] * time_scale;
    public_state.position.assign(model.parts.size(), 0.0);
    public_state.position[part] = y[1];
    for (std::size_t i = 0; i < drivers.size(); ++i) public_state.position[drivers[i].part] = driver_angle(i, t);
    public_state.pair_configurations.clear();
    for (const Pair& p : pairs) public_state.pair_configurations.push_back(p.q);
  }
  // Are the parts of the pair certainly farther apart than d at configuration q (exact: every
  // edge box of the pin-slot part placed at q against every edge box of the other part)?
  bool apart(const Pair& p, const SlicedConfiguration& q, const Rational& d) const {
    auto [c, sn] = cos_sin(q.angle);
    const Part& f = model.parts[part];
    for (const Loop& loop : f.loops)
      for (const Edge& e : loop.edges) {
        const Box fb = edge_box(e, f.motion.pivot, c, sn, q.x, q.y);
        std::optional<PlacedEdge> fe;
        for (std::size_t k = 0; k < p.other_boxes.size(); ++k) {
          if (boxes_apart(fb, p.other_boxes[k], d)) continue;
          if (!fe) fe = placed_edge(e, f.motion.pivot, c, sn, q.x, q.y);
          if (!edges_apart(*fe, p.other_edges[k], d)) return false;
        }
      }
    return true;
  }
  // A bound (double, from the speeds and accelerations at the states given) of how far any
  // point of the pin-slot part moves relative to the pair's other part over a step of length h.
  double travel(const Pair& p, std::initializer_list<const State4*> states, double h) const {
    const std::size_t dr = driver_of[p.other];
    double omega = 0, arm = 0;
    if (dr != no_index) {
      omega = std::abs(drivers[dr].omega);
      const Point& C = model.parts[p.other].motion.pivot;
      arm = std::hypot(P[0] - C.x.get_d(), P[1] - C.y.get_d());
    }
    double out = 0;
    const double reach = reach_at(states);
    for (const State4* s : states) {
      State4 ds;
      rhs(*s, ds);
      const double speed = std::abs((*s)[2]) + std::abs((*s)[3]) * reach + omega * (reach + arm);
      const double gain = std::abs(ds[2]) + std::abs(ds[3]) * reach + (*s)[3] * (*s)[3] * reach;
      out = std::max(out, (speed + gain * h) * h);
    }
    return std::isfinite(out) ? out : std::numeric_limits<double>::max();
  }
  // A touching feature pair's impact row at the current state: J (its normal speed is
  // J q' - v_other), the driver's surface speed along the normal, the world point and normal.
  struct Row {
    double J[2], v_other, point[2], normal[2];
    std::string label;
  };
  std::vector<Row> contact_rows(std::size_t pi, const std::vector<SlicedFeaturePair>& features) const;
  // Newton impacts of the touching feature pairs at the current state (sequential impulses).
  void impact(std::size_t pi, const std::vector<SlicedFeaturePair>& features);
  bool advance(double span);
};

std::vector<PinSlotSimulation::Impl::Row> PinSlotSimulation::Impl::contact_rows(
    std::size_t pi, const std::vector<SlicedFeaturePair>& features) const {
  const Pair& p = pairs[pi];
  const Model& frame = *p.frame_model;
  const std::size_t dr = driver_of[p.other];
  const double phi = dr == no_index ? 0.0 : driver_angle(dr, t), omega = dr == no_index ? 0.0 : drivers[dr].omega;
  const double ca = std::cos(phi), sa = std::sin(phi);
  const Point& C = model.parts[p.other].motion.pivot;
  const double Cx = C.x.get_d(), Cy = C.y.get_d();
  std::vector<Row> rows;
  for (const SlicedFeaturePair& f : features) {
    const SlicedContactFrame cf = sliced_contact_frame(frame, f, p.q);
    if (!cf.defined) continue;
    double px = cf.point.x.get_d(), py = cf.point.y.get_d(), nx = cf.normal.x.get_d(), ny = cf.normal.y.get_d();
    const double nn = std::hypot(nx, ny);
    if (!(nn > 0)) continue;
    nx /= nn;
    ny /= nn;
    if (dr != no_index) {   // the driver's frame to the world
      const double rx = px - Cx, ry = py - Cy;
      px = Cx + ca * rx - sa * ry;
      py = Cy + sa * rx + ca * ry;
      const double mx = ca * nx - sa * ny, my = sa * nx + ca * ny;
      nx = mx;
      ny = my;
    }
    const double c = std::cos(y[1]), sn = std::sin(y[1]);
    const double u[2] = {c * d[0] - sn * d[1], sn * d[0] + c * d[1]};
    const double r[2] = {px - P[0], py - P[1]};
    Row row;
    row.J[0] = nx * u[0] + ny * u[1];
    row.J[1] = nx * -r[1] + ny * r[0];
    row.v_other = omega * (nx * -(py - Cy) + ny * (px - Cx));
    row.point[0] = px;
    row.point[1] = py;
    row.normal[0] = nx;
    row.normal[1] = ny;
    row.label = f.label;
    rows.push_back(row);
  }
  return rows;
}

void PinSlotSimulation::Impl::impact(std::size_t pi, const std::vector<SlicedFeaturePair>& features) {
  const Pair& p = pairs[pi];
  const std::vector<Row> rows = contact_rows(pi, features);
  if (rows.empty()) {
    std::ostringstream out;
    out << where(t) << ": the contact of '" << model.parts[p.other].name << "' and '" << model.parts[part].name
        << "' has no contact frame (a vertex meeting a vertex)";
    throw NumericError(out.str());
  }
  auto speed = [&](const Row& r) { return r.J[0] * y[2] + r.J[1] * y[3] - r.v_other; };
  std::vector<double> before(rows.size()), total(rows.size(), 0.0);
  for (std::size_t i = 0; i < rows.size(); ++i) before[i] = speed(rows[i]);
  // sequential impulses: each approaching row gets Newton's law, repeated until none approaches
  for (int sweep = 0; sweep < 50; ++sweep) {
    bool any = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const double v = speed(r);
      const double target = before[i] < 0 ? -p.restitution * before[i] : 0.0;
      if (v >= target - 1e-12 * (std::abs(target) + std::abs(before[i]))) continue;
      double mj[2];
      inverse_mass_times(y[0], r.J, mj);
      const double k = r.J[0] * mj[0] + r.J[1] * mj[1];
      double lambda = (target - v) / k;
      if (total[i] + lambda < 0) lambda = -total[i];
      total[i] += lambda;
      y[2] += mj[0] * lambda;
      y[3] += mj[1] * lambda;
      any = true;
    }
    if (!any) break;
  }
  double approach = 0, leave = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (total[i] <= 0) continue;
    approach = std::max(approach, -before[i]);
    leave = std::min(leave, speed(rows[i]));
    SimulationEvent ev;
    ev.kind = SimulationEvent::Kind::impact;
    ev.time = t / time_scale;
    ev.pair = p.index;
    ev.first_part = model.parts[p.other].name;
    ev.second_part = model.parts[part].name;
    ev.features = {rows[i].label};
    ev.impulse = total[i] / (force_scale * time_scale);
    ev.normal_speed_before = -before[i] * time_scale;
    ev.normal_speed_after = speed(rows[i]) * time_scale;
    ev.point = {rows[i].point[0], rows[i].point[1]};
    ev.normal = {rows[i].normal[0], rows[i].normal[1]};
    events.push_back(std::move(ev));
  }
  if (approach == 0 || leave <= rest_speed) {
    std::ostringstream out;
    out << where(t) << ": the contact of '" << model.parts[p.other].name << "' and '" << model.parts[part].name
        << "' (" << rows.front().label << ") would have to be sustained (approach speed " << approach * time_scale
        << " mm/" << time_unit << ", separating speed below the rest speed " << rest_speed * time_scale << " mm/"
        << time_unit << "): a pin-slot part's sustained contacts are not simulated (docs/simulation.md)";
    throw NumericError(out.str());
  }
}

bool PinSlotSimulation::Impl::advance(double span) {
  const double pi = std::numbers::pi;
  double h = std::min(span, step_guess > 0 ? step_guess : span);
  if (options.max_step > 0) h = std::min(h, options.max_step * time_scale);
  for (int attempt = 0;; ++attempt) {
    if (attempt > 2000 || !(h > 0))
      throw NumericError(where(t) + ": no chord within the chord deviation (the step size underflows)");
    // a step too long for a violent load (a torque of 10^100 N mm) overflows or turns the part many
    // times: shorter steps reach the limits, which then stop the run naming them
    State4 mid, end;
    try {
      mid = flight(y, h / 2, true);
      end = flight(mid, h / 2, true);
    } catch (const FlightTooLong&) {
      h /= 2;
      continue;
    }
    auto finite = [](const State4& s) { return std::all_of(s.begin(), s.end(), [](double v) { return std::isfinite(v); }); };
    if (!finite(mid) || !finite(end)) {
      h /= 2;
      continue;
    }
    // the far test: a pair whose features are certainly farther apart than twice the step's
    // travel bound (plus delta) is free over the step without a chord
    std::vector<bool> far(pairs.size(), false), flips(pairs.size(), false);
    std::vector<SlicedConfiguration> to(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) to[i] = relative(pairs[i], end, t + h);
    bool fits = true;
    for (std::size_t i = 0; i < pairs.size() && fits; ++i) {
      const double reach_i = travel(pairs[i], {&y, &mid, &end}, h);
      if (reach_i < std::numeric_limits<double>::max() / 4) {
        // (and the end configuration's boundaries exactly apart: certified, whatever the bound)
        far[i] = apart(pairs[i], pairs[i].q, Rational(2 * reach_i + delta)) &&
                 apart(pairs[i], to[i], Rational(0));
      }
      if (far[i]) continue;
      // a chord turns the relative angle by at most pi/4 (it stays inside one chart) and lies
      // within delta/2 of the path
      const double a0 = relative_angle(pairs[i], y, t), a1 = relative_angle(pairs[i], end, t + h);
      const double am = relative_angle(pairs[i], mid, t + h / 2);
      if (std::abs(wrap(a1 - a0)) > pi / 4 || std::abs(wrap(am - a0)) > pi / 4) fits = false;
      flips[i] = std::abs(am) > pi / 2;
      // the chart about the half turn excludes theta = 0 at either end, the chart about 0 the half turn
      if (fits && flips[i] && (std::abs(a0) < pi / 8 || std::abs(a1) < pi / 8)) fits = false;
      if (fits && !flips[i] && (std::abs(a0) > 7 * pi / 8 || std::abs(a1) > 7 * pi / 8)) fits = false;
      if (fits && chord_error(pairs[i], y, mid, end, h, flips[i]) > delta / 2) fits = false;
    }
    if (!fits) {
      h /= 2;
      continue;
    }
    // the chords of this step, tested exactly
    std::size_t first = no_index;
    SlicedMotionCrossing earliest;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (far[i]) continue;
      SlicedMotion motion{pairs[i].q, to[i], static_cast<bool>(flips[i]), {}};
      ++chords;
      SlicedMotionCrossing c = pairs[i].space.first_crossing(motion, CrossingOptions{options.crossing_bits});
      if (c.status == CrossingStatus::starts_in_contact) {
        std::ostringstream out;
        out << where(t) << ": a chord of '" << model.parts[part].name << "' starts in contact with '"
            << model.parts[pairs[i].other].name << "' (its start was certified free: an internal error)";
        throw NumericError(out.str());
      }
      if (c.status == CrossingStatus::crossing && (first == no_index || c.u_lower < earliest.u_lower)) {
        first = i;
        earliest = std::move(c);
      }
    }
    if (first == no_index) {
      check_limits(end, t + h);
      y = end;
      t += h;
      for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].q = to[i];
      step_guess = 2 * h;
      return false;
    }
    // the first contact: every pair's state is its chord's point at the crossing's free side
    std::vector<SlicedConfiguration> kept;
    for (const Pair& p : pairs) kept.push_back(p.q);
    const Rational& u = earliest.u_lower;
    const double hc = h * u.get_d();
    const State4 at = flight(y, hc);
    check_limits(at, t + hc);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (i == first || !far[i]) {
        pairs[i].q = i == first ? earliest.before : chord_point(pairs[i].q, to[i], flips[i], u);
        continue;
      }
      pairs[i].q = relative(pairs[i], at, t + hc);
      if (!apart(pairs[i], pairs[i].q, Rational(0))) {
        std::ostringstream out;
        out << where(t + hc) << ": '" << model.parts[part].name << "' is not certainly apart from '"
            << model.parts[pairs[i].other].name << "' at a state its far test covered (an internal error)";
        throw NumericError(out.str());
      }
    }
    const State4 y_kept = y;
    const double t_kept = t;
    y = at;
    t += hc;
    // a chord that cuts the corner of a path touching and departing meets a contact the path
    // leaves at once (no feature pair approaching): a shorter chord deviates less (delta ~ h^2)
    bool approaching = false;
    for (const Row& r : contact_rows(first, earliest.features))
      approaching = approaching || r.J[0] * y[2] + r.J[1] * y[3] - r.v_other < 0;
    if (!approaching && h > 1e-9 * std::max(t, h) && attempt < 1900) {
      y = y_kept;
      t = t_kept;
      for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].q = kept[i];
      h /= 4;
      continue;
    }
    step_guess = std::max(h, 1e-12);
    impact(first, earliest.features);
    return true;
  }
}

PinSlotSimulation::PinSlotSimulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PinSlotSimulation::PinSlotSimulation(PinSlotSimulation&&) noexcept = default;
PinSlotSimulation& PinSlotSimulation::operator=(PinSlotSimulation&&) noexcept = default;
PinSlotSimulation::~PinSlotSimulation() = default;

PinSlotSimulation PinSlotSimulation::create(const Model& model, const SimulationOptions& options) {
  check_simulator_range(model);
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  const SimulationSpec spec = simulation::start_simulation(s, model, options);
  s.accuracy = simulation::simulation_accuracy(options, spec);
  const double ts = s.time_scale, fs = s.force_scale;
  // the parts: one pin-slot part, fixed parts and rotating drivers at constant speed
  std::size_t found = no_index;
  s.driver_of.assign(model.parts.size(), no_index);
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& p = model.parts[i];
    if (p.motion.kind == Motion::Kind::pin_slot) {
      if (found != no_index)
        throw ModelError(p.pointer + "/motion", "part '" + p.name + "': the pin-slot simulator moves one pin-slot part ('" +
                                                    model.parts[found].name + "' is one)");
      found = i;
    }
  }
  if (found == no_index) throw ModelError("/parts", "the pin-slot simulator needs a part with motion \"pin_slot\"");
  s.part = found;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const Part& p = model.parts[i];
    if (i == found || p.motion.kind == Motion::Kind::fixed) continue;
    const SimulationSpec::Driver* driver = nullptr;
    for (const SimulationSpec::Driver& d : spec.drivers)
      if (d.part == i) driver = &d;
    if (p.motion.kind != Motion::Kind::rotation || !driver)
      throw ModelError(p.pointer + "/motion", "part '" + p.name +
                                                  "': beside a pin-slot part the simulator moves only rotating "
                                                  "drivers (simulation.drivers, constant speed); other parts are fixed");
    if (!driver->profile.empty())
      throw ModelError(driver->pointer, "part '" + p.name + "': a pin-slot simulation takes constant-speed drivers only");
    s.driver_of[i] = s.drivers.size();
    s.drivers.push_back(Impl::Driver{i, p.initial.angle.get_d(), driver->speed.get_d() / ts});
  }
  for (const SimulationSpec::Driver& d : spec.drivers)
    if (d.part == found) throw ModelError(d.pointer, "the pin-slot part cannot be a driver");
  if (!spec.couplings.empty())
    throw ModelError(spec.couplings.front().pointer, "a pin-slot simulation takes no springs between parts "
                                                     "(the pin-slot part's own springs act on s and psi)");
  if (!spec.velocities.empty())
    throw ModelError(spec.velocities.front().pointer, "a pin-slot simulation starts at rest (the drivers move at their speed)");
  // the pin-slot part's dynamics
  const Part& fp = model.parts[found];
  if (!fp.dynamics || !fp.dynamics->mass || !fp.dynamics->moment_of_inertia)
    throw ModelError(fp.pointer + "/dynamics", "pin-slot part '" + fp.name +
                                                   "' needs \"mass\" and \"moment_of_inertia\" (about its pivot)");
  const Dynamics& dyn = *fp.dynamics;
  if (dyn.damping) throw ModelError(fp.pointer + "/dynamics/damping", "a pin-slot part takes no damping");
  s.mass = dyn.mass->get_d();
  if (!(s.mass > 0)) throw ModelError(fp.pointer + "/dynamics/mass", "a pin-slot part needs a positive mass");
  const Motion& motion = fp.motion;
  s.P[0] = motion.pivot.x.get_d();
  s.P[1] = motion.pivot.y.get_d();
  s.d[0] = motion.direction.x.get_d();
  s.d[1] = motion.direction.y.get_d();
  Point centre = motion.pivot;
  for (const SimulationSpec::CenterOfMass& c : spec.centers_of_mass)
    if (c.part == found) centre = c.at;
  s.cp[0] = Rational(centre.x - motion.pivot.x).get_d();
  s.cp[1] = Rational(centre.y - motion.pivot.y).get_d();
  s.cp2 = s.cp[0] * s.cp[0] + s.cp[1] * s.cp[1];
  s.e = s.d[0] * -s.cp[1] + s.d[1] * s.cp[0];
  s.b = s.d[0] * s.cp[0] + s.d[1] * s.cp[1];
  s.inertia_c = dyn.moment_of_inertia->get_d() - s.mass * s.cp2;
  if (!(s.inertia_c > 0))
    throw ModelError(fp.pointer + "/dynamics/moment_of_inertia",
                     "pin-slot part '" + fp.name + "': the moment of inertia about the pivot must exceed mass x "
                     "(distance of the centre of mass from the pivot)^2");
  if (dyn.force) {
    s.force[0] = dyn.force->x.get_d() * fs;
    s.force[1] = dyn.force->y.get_d() * fs;
  }
  if (dyn.torque) s.torque = dyn.torque->get_d() * fs;
  if (dyn.linear_spring) {
    s.k_lin = dyn.linear_spring->stiffness.get_d() * fs;
    s.rest_lin = dyn.linear_spring->rest.get_d();
  }
  if (dyn.torsional_spring) {
    s.k_tor = dyn.torsional_spring->stiffness.get_d() * fs;
    s.rest_tor = dyn.torsional_spring->rest.get_d();
  }
  s.slide_limits = motion.translation_limits;
  s.angle_limits = motion.angle_limits;
  s.y = {fp.initial.offset.get_d(), fp.initial.angle.get_d(), 0, 0};
  s.check_limits(s.y, 0);
  // the part's reach from its pivot (for the angle's share of a chord's deviation, reach_at)
  double reach = 0;
  for (const Loop& loop : fp.loops)
    for (const Edge& edge : loop.edges) {
      for (const Point* q : {&edge.source, &edge.target})
        reach = std::max(reach, std::hypot(q->x.get_d() - s.P[0], q->y.get_d() - s.P[1]));
      if (edge.is_arc())
        reach = std::max(reach, std::hypot(edge.center.x.get_d() - s.P[0], edge.center.y.get_d() - s.P[1]) +
                                    std::sqrt(edge.radius_squared.get_d()));
    }
  s.part_reach = std::max(reach, 1e-300);
  // the run's length scale: the part's reach at its initial slide (not its limits': see reach_at)
  const double size = s.reach_at({&s.y});
  s.delta = options.chord_deviation > 0 ? options.chord_deviation : s.accuracy * size;
  // the rest speed: the speed a load gains over the chord deviation
  double load = std::hypot(s.mass * s.g[0] + s.force[0], s.mass * s.g[1] + s.force[1]) / s.mass;
  load += (std::abs(s.torque) / s.inertia_c) * size;
  s.rest_speed = std::sqrt(2 * load * s.delta);
  // the pairs
  for (std::size_t i = 0; i < model.pairs.size(); ++i) {
    const PairSpec& spec_pair = model.pairs[i];
    if (spec_pair.first != found && spec_pair.second != found) continue;
    Impl::Pair p;
    p.index = i;
    p.other = spec_pair.first == found ? spec_pair.second : spec_pair.first;
    if (spec_pair.friction && sgn(*spec_pair.friction) > 0)
      throw ModelError(spec_pair.pointer + "/friction", "a pin-slot simulation is frictionless");
    p.restitution = spec_pair.restitution ? spec_pair.restitution->get_d() : 0.0;
    auto frame = std::make_shared<Model>(model);
    frame->parts[p.other].motion.kind = Motion::Kind::fixed;
    frame->parts[p.other].initial = PartConfiguration{};
    frame->parts[found].motion.kind = Motion::Kind::planar;
    frame->parts[found].motion.angle_limits.reset();
    frame->parts[found].motion.translation_limits.reset();
    frame->parts[found].initial = PartConfiguration{};
    p.space = SlicedSpace::build(*frame, model.parts[p.other].name, fp.name, SlicedBuildOptions{false, {}});
    p.frame_model = std::move(frame);
    for (const Loop& loop : model.parts[p.other].loops)
      for (const Edge& e : loop.edges) {
        p.other_boxes.push_back(edge_box(e, Point{}, Rational(1), Rational(0), 0, 0));
        p.other_edges.push_back(placed_edge(e, Point{}, Rational(1), Rational(0), 0, 0));
      }
    p.q = s.relative(p, s.y, 0);
    const SlicedLocation where = p.space.locate(p.q);
    if (where.kind != SlicedLocation::Kind::free)
      throw ModelError(fp.pointer + "/initial", "pin-slot part '" + fp.name + "' starts " +
                                                    (where.kind == SlicedLocation::Kind::blocked ? "overlapping"
                                                                                                 : "touching") +
                                                    " '" + model.parts[p.other].name + "'");
    s.pairs.push_back(std::move(p));
  }
  s.publish();
  return PinSlotSimulation(std::move(impl));
}

void PinSlotSimulation::step(double t_limit) {
  Impl& s = *impl_;
  const double end = t_limit * s.time_scale;
  if (!(end > s.t)) return;
  if (++s.steps > s.options.max_steps)
    throw NumericError(s.where(s.t) + ": more than " + std::to_string(s.options.max_steps) +
                       " steps (a runaway or Zeno run)");
  s.advance(end - s.t);
  if (end - s.t < 1e-15 * std::max(1.0, std::abs(end))) s.t = end;
  s.publish();
}

void PinSlotSimulation::run_until(double t_end, const std::function<void(double)>& progress) {
  while (impl_->t < t_end * impl_->time_scale) {
    step(t_end);
    if (progress) progress(impl_->public_state.time);
  }
}

const PinSlotState& PinSlotSimulation::state() const { return impl_->public_state; }
const std::vector<SimulationEvent>& PinSlotSimulation::events() const { return impl_->events; }
std::size_t PinSlotSimulation::steps() const { return impl_->steps; }
std::size_t PinSlotSimulation::chord_tests() const { return impl_->chords; }
double PinSlotSimulation::energy() const { return impl_->energy_of(impl_->y) / impl_->force_scale; }
double PinSlotSimulation::chord_deviation() const { return impl_->delta; }
std::size_t PinSlotSimulation::part() const { return impl_->part; }
const Model& PinSlotSimulation::model() const { return impl_->model; }
const std::string& PinSlotSimulation::time_unit() const { return impl_->time_unit; }
const std::string& PinSlotSimulation::force_unit() const { return impl_->force_unit; }

}  // namespace hipair
