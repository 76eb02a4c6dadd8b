// Dynamical simulation on the public C-space adaptor (docs/simulation.md).
//
// State: one coordinate per moving part (rad or mm). Integration: Dormand–Prince 5(4) with error
// control (Boost.Odeint), one controlled step at a time. Each step's motion of each part is the
// quintic Hermite polynomial through the step's end states (positions, velocities, accelerations):
// that polynomial is what is checked, per pair, by the certified CSpace::first_crossing, and it
// is the trajectory (states inside a step are read from it), so the detection covers the whole
// path. Sustained contacts are bilateral constraints q_y = Y(q_x) along a contact edge (Y', Y''
// from CSpace::derivatives), any number at once (of one pair and of several); their forces come
// from one complementarity problem (src/simulation/lcp.hpp), as do the impulses of simultaneous
// impacts, and a contact is held while its force stays non-negative. A sliding pair's new
// contacts are the other curves through its edge's end vertex (vertex_contacts).
#include <hipair/simulation.hpp>

#include <hipair/blocked_walk.hpp>
#include <hipair/contact_frame_doubles.hpp>
#include <hipair/contact_frame_exact.hpp>
#include <hipair/crossing_before.hpp>
#include <hipair/edge_slope.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/error.hpp>
#include <hipair/motion_words.hpp>
#include <hipair/simulation_stop.hpp>

#include "simulation/crossing_limit.hpp"
#include "simulation/crossing_sweep.hpp"
#include "simulation/cut_search.hpp"
#include "simulation/edge_watch.hpp"
#include "simulation/frame_cache.hpp"
#include "simulation/frame_rate.hpp"
#include "simulation/friction.hpp"
#include "simulation/friction_names.hpp"
#include "simulation/held_friction.hpp"
#include "simulation/jam.hpp"
#include "simulation/kept_scratch.hpp"
#include "simulation/lcp.hpp"
#include "simulation/initial_energy.hpp"
#include "simulation/motion_datum.hpp"
#include "simulation/normal_side.hpp"
#include "simulation/nudge_check.hpp"
#include "simulation/ordinate_filter.hpp"
#include "simulation/step_paths.hpp"
#include "simulation/time_rescale.hpp"
#include "simulation/touch_guard.hpp"
#include "simulation/units.hpp"
#include "simulation/vertex_graze.hpp"
#include "simulation/whole_turns.hpp"

#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <unordered_map>

namespace hipair {

std::string to_string(SimulationEvent::Kind kind) {
  switch (kind) {
    case SimulationEvent::Kind::impact: return "impact";
    case SimulationEvent::Kind::contact: return "contact";
    case SimulationEvent::Kind::lift_off: return "lift-off";
    case SimulationEvent::Kind::edge_end: return "edge-end";
    case SimulationEvent::Kind::stick: return "stick";
    case SimulationEvent::Kind::slip: return "slip";
  }
  return "?";
}

namespace {

using Vec = std::vector<double>;

double mid(const CertifiedRange& r) { return 0.5 * (r.lower + r.upper); }
double to_d(const Rational& r) { return r.get_d(); }

// A quintic in u in [0, 1] through (p, h v, h^2 a) at both ends.
std::array<double, 6> hermite(double q0, double v0, double a0, double q1, double v1, double a1, double h) {
  double c0 = q0, c1 = h * v0, c2 = h * h * a0 / 2;
  double A = q1 - (c0 + c1 + c2), B = h * v1 - (c1 + 2 * c2), C = h * h * a1 - 2 * c2;
  return {c0, c1, c2, 10 * A - 4 * B + C / 2, -15 * A + 7 * B - C, 6 * A - 3 * B + C / 2};
}
double poly(const std::array<double, 6>& c, double u) {
  double r = 0;
  for (int i = 5; i >= 0; --i) r = r * u + c[i];
  return r;
}
double dpoly(const std::array<double, 6>& c, double u) {
  double r = 0;
  for (int i = 5; i >= 1; --i) r = r * u + i * c[i];
  return r;
}

struct Dof {
  std::size_t part = 0;
  bool rotation = true;
  double pivot[2] = {0, 0};
  double dir[2] = {1, 0};
  double inertia = 0;        // kg mm^2 or kg
  double mass = 0;           // kg (gravity)
  double com[2] = {0, 0};    // rotation: centre of mass - pivot at zero configuration
  bool driven = false;
  double speed = 0;          // mm/s or rad/s
  // speed profile (law "speed_profile"): times (s), speeds, and the positions at those times
  // relative to q0 (the integral of the piecewise-linear speed); empty: constant speed
  std::vector<double> profile_t, profile_v, profile_q;
  double q0 = 0;             // initial position (driver law)
  double stiffness = 0, rest = 0, load = 0, damping = 0;   // internal units
  double force[2] = {0, 0};  // constant force at the centre of mass (mN)
};

struct Coupling {
  std::size_t first, second;
  double p1[2], p2[2];
  double k, rest, c;
};

// A sustained contact: g(q) = sigma (q_y - Y(q_x)) >= 0 (or sigma (q_x - c) for a point / vertical edge).
struct Active {
  std::size_t pair = 0;
  EdgeId edge;
  bool point = false;        // 1-D contact or vertical edge: q_x = c
  double c = 0;
  int sigma = 1;
  int xdof = -1, ydof = -1;
  std::size_t chart = 0;
  double x_lo = 0, x_hi = 0; // the edge's chart abscissa range
  bool bounded_y = false;    // a vertical edge: its chart ordinate range
  double y_lo = 0, y_hi = 0;
  // How far beyond the edge's certified extent the contact is still accepted, in `unit`s of the
  // watched chart coordinate (session 40: a fraction, so the same at every length scale; in
  // chart units slack * unit, Impl::slack_of)
  double slack = 1e-9;
  // The scale of the watched chart coordinate (the abscissa; a vertical edge's ordinate): 1 on a
  // rotating axis (t = tan(theta / 2) is dimensionless), the chart box's extent in mm on a
  // translating one (a length: a model scaled by L has its tolerances scaled by L)
  double unit = 1;
  bool at_vertex = false;    // taken up (or kept) at a contact-change vertex: valid up to the vertex
  int vertex_end = 0;        // at_vertex, non-vertical: that vertex's end of the edge (-1 lower abscissa, +1 upper)
  bool wedge = false;        // held at (or kept back from) a wedge's vertex: valid within 1e-10 of it
  std::vector<FeatureId> features;   // a contact without an edge (1-D pair): its feature pairs
  // Coulomb state (pairs with friction): simulation::stick or slip_positive / slip_negative,
  // once decided at a step's start (docs/simulation.md#friction)
  int coulomb = simulation::frictionless;
  bool coulomb_known = false;
  // the last certified point of the edge, for the contact rows' filtered derivatives
  mutable EdgeTracker tracker;
};

// The contact forces of the held contacts at a state (friction included).
struct ContactForces {
  bool friction = false;     // some held contact has friction
  std::vector<int> state;    // per active contact
  Vec normal, tangential;    // physical normal and friction force (internal units)
  Vec vt;                    // relative tangential velocity
  Vec mu_static;
  // held contacts (bilateral, at their states): each multiplier's sign and whether a sticking
  // contact's friction exceeds mu_s N, decided exactly on the rows (friction.hpp's held_verdict;
  // docs/simulation.md, "Session 63 (exact63)"), or from the doubles where the sticking rows
  // of a wedge leave the multipliers open (solve_bilateral's undetermined_plain)
  std::vector<int> force_sign;
  std::vector<bool> beyond_static;
};

struct ContactRow {
  Vec g;                     // over dofs
  double restitution = 0;
  std::size_t pair = 0;
  bool crossing = false;     // a new contact (false: an active sustained one)
  std::size_t active = 0;    // index into active_ when !crossing
  MotionCrossing hit;
  std::optional<Active> near;   // a contact of another pair within the accuracy of closing
  std::vector<FeatureId> features;   // its feature pairs (the Coulomb frame)
  // a grazing crossing through a vertex from free space into free space (vertex_pass): a touch
  // without impulse, left out of the impact problem (session 41)
  bool graze = false;
};

}  // namespace

struct Simulation::Impl {
  Model model;
  SimulationOptions options;
  std::vector<std::shared_ptr<const CSpace>> spaces;
  std::vector<Dof> dofs;
  std::vector<int> part_dof;          // part -> dof or -1
  std::vector<Coupling> couplings;
  Point gravity_file;
  double g[2] = {0, 0};
  double time_scale = 1, force_scale = 1000;   // seconds per time unit, mN per force unit
  double accuracy = 1e-9;
  std::string time_unit = "s", force_unit = "N";

  std::vector<double> mu_static, mu_kinetic;   // per pair (0: frictionless)
  double t = 0;                       // seconds
  // Whole turns taken out of the unlimited rotating coordinates (session 61, issue 11;
  // simulation/whole_turns.hpp): a coordinate that may wrap (a rotation without angle limits and
  // without a spring to the frame; a driver only when every driver has constant speed) is brought
  // back to [-pi, pi] at a step boundary once some such coordinate passes wrap_bound, and its
  // physical value is q + 2 pi turns (exact integer turns). The drivers' laws are then restarted
  // there: the time elapsed is moved from t into the exact t_offset (t = 0) and each driver's q0
  // becomes its law's exact position at that time, reduced by whole turns. So t and every angle
  // stay as small as in the run's first turns, whatever its length. Published times are
  // t_offset + t, published angles q + 2 pi turns, each rounded once.
  static constexpr double wrap_bound = 16 * std::numbers::pi;
  std::vector<char> wraps;            // per dof
  std::vector<Rational> turns;        // per dof
  std::vector<double> q0_law;         // per driver dof: its law's q0 at t_offset = 0
  bool time_rebase = false;           // every driver has constant speed
  Rational t_offset;                  // time units
  bool rebased = false;
  Vec q, v;                           // per dof
  std::vector<Active> active;
  std::vector<std::optional<Active>> last_contact;   // per pair: the contact of its last impact
  std::vector<SimulationEvent> events;
  SimulationState public_state;
  std::size_t steps = 0;
  double dt = 0;                      // next trial step, seconds
  // the end time of the last step whose impacts struck nothing (step()); NaN: none since
  double last_touch_end = std::numeric_limits<double>::quiet_NaN();
  // steps in a row that left the time where it was (step_and_free)
  std::size_t steps_in_place = 0;
  // the last step's accepted trial length where it was too short to move the time (t + trial
  // rounds to t: the error control asks for steps below the time's resolution there); 0 else.
  // Only the message of the steps-in-place guard reads it (step_and_free).
  double unresolved_trial = 0;
  // friction_of's contact frames at the configurations of this step (frame_cache.hpp)
  mutable simulation::FrameCache frames;

  // ---------------------------------------------------------------- kinematics and forces
  void world_point(const Dof* d, double qd, const double p0[2], double p[2], double J[2]) const {
    if (!d) {
      p[0] = p0[0];
      p[1] = p0[1];
      J[0] = J[1] = 0;
      return;
    }
    if (d->rotation) {
      double c = std::cos(qd), s = std::sin(qd);
      double rx = p0[0] - d->pivot[0], ry = p0[1] - d->pivot[1];
      double x = c * rx - s * ry, y = s * rx + c * ry;
      p[0] = d->pivot[0] + x;
      p[1] = d->pivot[1] + y;
      J[0] = -y;
      J[1] = x;
    } else {
      p[0] = p0[0] + qd * d->dir[0];
      p[1] = p0[1] + qd * d->dir[1];
      J[0] = d->dir[0];
      J[1] = d->dir[1];
    }
  }
  const Dof* dof_of_part(std::size_t part) const {
    int i = part_dof[part];
    return i < 0 ? nullptr : &dofs[i];
  }

  // A driver's law at `time` (s): position, speed, acceleration. Constant speed: q0 + speed t.
  // Speed profile: within segment i, v = v_i + a_i (t - t_i), q = q0 + Q_i + v_i (t - t_i) +
  // a_i (t - t_i)^2 / 2; after the last point the last speed.
  static void driver_law(const Dof& d, double time, double& qd, double& vd, double& ad) {
    if (d.profile_t.empty()) {
      qd = d.q0 + d.speed * time;
      vd = d.speed;
      ad = 0;
      return;
    }
    std::size_t i = std::upper_bound(d.profile_t.begin(), d.profile_t.end(), time) - d.profile_t.begin();
    i = i == 0 ? 0 : i - 1;
    double tau = time - d.profile_t[i];
    ad = i + 1 < d.profile_t.size() ? (d.profile_v[i + 1] - d.profile_v[i]) / (d.profile_t[i + 1] - d.profile_t[i]) : 0.0;
    vd = d.profile_v[i] + ad * tau;
    qd = d.q0 + d.profile_q[i] + d.profile_v[i] * tau + 0.5 * ad * tau * tau;
  }
  // The first profile point strictly after `time` (steps end there: a step's driver motion is
  // one polynomial), or infinity.
  double next_breakpoint(double time) const {
    double next = std::numeric_limits<double>::infinity();
    for (const Dof& d : dofs) {
      auto it = std::upper_bound(d.profile_t.begin(), d.profile_t.end(), time);
      if (it != d.profile_t.end()) next = std::min(next, *it);
    }
    return next;
  }

  Vec forces(double time, const Vec& qs, const Vec& vs) const {
    Vec Q;
    forces(time, qs, vs, Q);
    return Q;
  }
  // forces() written into Q
  void forces(double time, const Vec& qs, const Vec& vs, Vec& Q) const {
    (void)time;
    Q.assign(dofs.size(), 0.0);
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      const Dof& d = dofs[i];
      Q[i] = d.load - d.stiffness * (qs[i] - d.rest) - d.damping * vs[i];
      double F[2] = {d.force[0] + d.mass * g[0], d.force[1] + d.mass * g[1]};
      if (d.rotation) {
        double c = std::cos(qs[i]), s = std::sin(qs[i]);
        double rx = c * d.com[0] - s * d.com[1], ry = s * d.com[0] + c * d.com[1];
        Q[i] += rx * F[1] - ry * F[0];
      } else {
        Q[i] += F[0] * d.dir[0] + F[1] * d.dir[1];
      }
    }
    for (const Coupling& k : couplings) {
      int i1 = part_dof[k.first], i2 = part_dof[k.second];
      double p1[2], p2[2], J1[2], J2[2];
      world_point(dof_of_part(k.first), i1 < 0 ? 0 : qs[i1], k.p1, p1, J1);
      world_point(dof_of_part(k.second), i2 < 0 ? 0 : qs[i2], k.p2, p2, J2);
      double dx = p2[0] - p1[0], dy = p2[1] - p1[1], L = std::hypot(dx, dy);
      if (L == 0) continue;
      double ux = dx / L, uy = dy / L;
      double w1 = i1 < 0 ? 0 : vs[i1], w2 = i2 < 0 ? 0 : vs[i2];
      double Ldot = ux * (J2[0] * w2 - J1[0] * w1) + uy * (J2[1] * w2 - J1[1] * w1);
      double f = k.k * (L - k.rest) + k.c * Ldot;
      if (i2 >= 0) Q[i2] -= f * (J2[0] * ux + J2[1] * uy);
      if (i1 >= 0) Q[i1] += f * (J1[0] * ux + J1[1] * uy);
    }
  }

  double energy() const {
    double E = 0;
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      const Dof& d = dofs[i];
      if (!d.driven) E += 0.5 * d.inertia * v[i] * v[i];
      E += 0.5 * d.stiffness * (q[i] - d.rest) * (q[i] - d.rest) - d.load * absolute(i);
      double F[2] = {d.force[0] + d.mass * g[0], d.force[1] + d.mass * g[1]};
      if (d.rotation) {
        double c = std::cos(q[i]), s = std::sin(q[i]);
        double rx = c * d.com[0] - s * d.com[1], ry = s * d.com[0] + c * d.com[1];
        E -= F[0] * rx + F[1] * ry;
      } else {
        E -= q[i] * (F[0] * d.dir[0] + F[1] * d.dir[1]);
      }
    }
    for (const Coupling& k : couplings) {
      int i1 = part_dof[k.first], i2 = part_dof[k.second];
      double p1[2], p2[2], J[2];
      world_point(dof_of_part(k.first), i1 < 0 ? 0 : q[i1], k.p1, p1, J);
      world_point(dof_of_part(k.second), i2 < 0 ? 0 : q[i2], k.p2, p2, J);
      double L = std::hypot(p2[0] - p1[0], p2[1] - p1[1]);
      E += 0.5 * k.k * (L - k.rest) * (L - k.rest);
    }
    return E / force_scale;
  }

  // A step that left the run's energy beyond the doubles' range stops the run (session 65,
  // sim65: it ended with exit 0 and `"energy": null`), naming the moving parts and the largest
  // velocity or load given.
  void check_energy() const {
    if (std::isfinite(energy())) return;
    std::ostringstream where, parts;
    where << "simulation: at t = " << published_time(t) << " " << time_unit;
    const char* separator = "";
    for (std::size_t i : free_dofs) {
      const Part& p = model.parts[dofs[i].part];
      parts << separator << "part '" << p.name << "' (" << p.pointer << "/dynamics, " << p.pointer << "/initial; at "
            << q[i] << (dofs[i].rotation ? " rad" : " mm") << ", moving at " << v[i] * time_scale
            << (dofs[i].rotation ? " rad/" : " mm/") << time_unit << ")";
      separator = ", ";
    }
    throw NumericError(simulation::energy_overflow_message(where.str(), parts.str()) +
                       simulation::largest_motion_datum(model));
  }

  // the time a state at internal time `time` is published at (the model's time unit)
  double published_time(double time) const {
    // (a rational of a non-finite double would abort in GMP)
    if (!rebased || !std::isfinite(time)) return time / time_scale;
    return Rational(t_offset + Rational(time)).get_d() / time_scale;
  }
  // an internal time limit for the published internal-unit time `limit` (at or before it)
  double internal_time(double limit) const {
    if (!rebased || !std::isfinite(limit)) return limit;
    return Rational(Rational(limit) - t_offset).get_d();
  }
  // a coordinate's physical value (whole turns put back)
  double absolute(std::size_t i) const { return sgn(turns[i]) == 0 ? q[i] : simulation::add_turns(q[i], turns[i]); }

  // Between steps: once some wrapping coordinate passes wrap_bound, every wrapping coordinate is
  // reduced by its whole turns and (if any driver wraps) the drivers' laws restart at t = 0.
  void wrap_turns() {
    bool due = false;
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (wraps[i] && std::abs(q[i]) > wrap_bound) due = true;
    // (a non-finite state is reported by the step; its rational would abort in GMP)
    if (!due || !std::isfinite(t) || !std::all_of(q.begin(), q.end(), [](double x) { return std::isfinite(x); })) return;
    // a point contact's abscissa is the coordinate's value where it was taken up: moved by the
    // same whole turns
    auto shift_points = [&](std::size_t i, const Rational& removed) {
      auto shift = [&](Active& a) {
        if (a.point && a.xdof == static_cast<int>(i) && std::isfinite(a.c))
          a.c = simulation::minus_turns(Rational(a.c), removed);
      };
      for (Active& a : active) shift(a);
      for (std::optional<Active>& a : last_contact)
        if (a) shift(*a);
    };
    if (time_rebase) {
      t_offset += Rational(t);
      rebased = true;
      if (!std::isnan(last_touch_end)) last_touch_end -= t;
      t = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        if (!dofs[i].driven) continue;
        // the law's exact position at t_offset: q0 + speed t_offset
        Rational at = Rational(q0_law[i]) + Rational(dofs[i].speed) * t_offset;
        if (wraps[i]) {
          simulation::ReducedAngle r = simulation::reduce_turns(at);
          dofs[i].q0 = r.angle;
          if (r.turns != turns[i]) shift_points(i, Rational(r.turns - turns[i]));
          turns[i] = r.turns;
        } else {
          dofs[i].q0 = simulation::minus_turns(at, Rational(0));
        }
        q[i] = dofs[i].q0;
      }
    }
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      if (!wraps[i] || dofs[i].driven) continue;
      simulation::ReducedAngle r = simulation::reduce_turns(Rational(q[i]));
      if (sgn(r.turns) == 0) continue;
      shift_points(i, r.turns);
      q[i] = r.angle;
      turns[i] += r.turns;
    }
  }

  // ---------------------------------------------------------------- contact geometry
  const CSpaceChart& chart_of(const Active& a) const { return spaces[a.pair]->charts().at(a.chart); }

  // chart coordinate of a part coordinate (rotation: t = tan((theta - c)/2))
  static double to_chart(AxisKind kind, bool half_turn, double value) {
    if (kind == AxisKind::translation) return value;
    double centre = half_turn ? std::numbers::pi : 0.0;
    double a = std::remainder(value - centre, 2 * std::numbers::pi);
    return std::tan(a / 2);
  }

  // a fraction of the chart coordinate's unit (axis_unit): 1e-9 chart units on a rotating axis
  static constexpr double edge_slack = 1e-9;

  // The scale of a chart coordinate, what its tolerances are fractions of (session 40,
  // docs/simulation.md "Session 40 (graze40)"): 1 on a rotating axis, where the chart coordinate
  // t = tan(theta / 2) is dimensionless and |t| <= 1 on its chart; on a translating axis the
  // chart box's extent (the motion limits, mm), so that a model scaled in length by L sees its
  // slacks scaled by L, not the same absolute 1e-9 mm at 10^-6 mm and at 10^6 mm.
  static double axis_unit(const CSpaceChart& chart, bool ordinate) {
    if ((ordinate ? chart.y_kind : chart.x_kind) != AxisKind::translation) return 1;
    const double extent = ordinate ? to_d(chart.y_hi - chart.y_lo) : to_d(chart.x_hi - chart.x_lo);
    return extent > 0 && std::isfinite(extent) ? extent : 1;
  }
  // the unit of held contact `a`'s watched coordinate (a vertical edge's: its ordinate)
  double unit_of(const Active& a) const {
    if (a.point && !a.bounded_y) return 1;
    return axis_unit(chart_of(a), a.point);
  }
  // held contact `a`'s slack in chart units
  static double slack_of(const Active& a) { return a.slack * a.unit; }
  // strict rows' reach past a vertex (rounding about a corner held by two contacts), chart units
  static double strict_limit(const Active& a) { return 1e-12 * a.unit; }

  // Two rationals either side of an algebraic number, 2^-64 of its isolating interval apart
  // (exact bisection on the sign of its square-free polynomial).
  static std::vector<Rational> refined(const AlgebraicNumber& x) {
    auto sign_at = [&](const Rational& r) {
      Rational value = 0;
      for (std::size_t i = x.polynomial.size(); i-- > 0;) value = value * r + Rational(x.polynomial[i]);
      return sgn(value);
    };
    Rational lo = x.lower, hi = x.upper;
    int s_lo = sign_at(lo);
    for (int i = 0; i < 64; ++i) {
      Rational m = (lo + hi) / 2;
      int s_m = sign_at(m);
      if (s_m == 0) return {m};
      if (s_m == s_lo) lo = m;
      else hi = m;
    }
    return {lo, hi};
  }

  // Set while the step's motion is checked for contact ends: rows are then valid only on their
  // edges exactly, or within 1e-12 of the vertex where they were taken up (a contact taken up at
  // a vertex ends as soon as the motion leaves its edge).
  mutable bool strict_rows = false;

  // The edge's derivatives at chart abscissa tx; past the edge's exact end (derivatives()
  // throws) but within the contact's slack of an end vertex, those at the vertex (at the ends of
  // its isolating interval that lie on the edge): at a contact change the configuration is at the
  // vertex to the bisection's resolution, on either side of it by rounding.
  bool derivatives_near(const Active& a, double tx, EdgeDerivatives& d) const {
    const CSpace& space = *spaces[a.pair];
    try {
      d = space.derivatives(a.edge, Rational(tx));
      return true;
    } catch (const GeometryError&) {
    }
    if (!a.at_vertex) return false;
    // while the motion is checked, only within 1e-12 chart units of the vertex (rounding about a
    // corner held by two contacts), not along the curve past the vertex
    const double limit = strict_rows ? strict_limit(a) : slack_of(a);
    const CSpaceEdge& edge = space.edge(a.edge);
    for (std::size_t vertex : {edge.source, edge.target}) {
      if (vertex == no_index) continue;
      const AlgebraicNumber& x = space.vertex(VertexId(vertex)).x;
      if (!(std::abs(x.approximate() - tx) <= limit)) continue;
      std::vector<Rational> trials{x.lower};
      if (!x.exact) trials = refined(x);
      for (const Rational& r : trials) {
        if (!(std::abs(r.get_d() - tx) <= 2 * limit)) continue;
        try {
          d = space.derivatives(a.edge, r);
          return true;
        } catch (const GeometryError&) {
        }
      }
    }
    return false;
  }

  // Whether the ordinate ty lies on the vertical edge of `a`, decided exactly against its end
  // vertices (CSpace::compare_ordinate; the ends are closed), as derivatives() decides it for
  // the other edges: the vertex's isolating interval first (a rational comparison), the exact
  // comparison only inside it. Past an end but within the contact's slack of it (strict rows:
  // 1e-12), a contact taken up at a vertex still holds (as derivatives_near()). Where the exact
  // comparison does not decide (a vertex whose fibre does not change sign), the certified
  // extent already tested by row() stands.
  // Doubles lo <= y_lower and y_upper <= hi of each vertex's isolating interval, per pair
  // (filled on first use; NaN: not yet): on_vertical_edge's ordinate below lo or above hi is
  // below or above the interval exactly, as the rational comparison finds it
  // (simulation/ordinate_filter.hpp).
  mutable std::vector<std::vector<std::array<double, 2>>> vertex_bounds;

  std::array<double, 2> ordinate_bounds(std::size_t pair, std::size_t vertex) const {
    if (vertex_bounds.size() != spaces.size()) vertex_bounds.resize(spaces.size());
    std::vector<std::array<double, 2>>& bounds = vertex_bounds[pair];
    // (grown to the vertex read, not sized by CSpace::vertices(): that would write every
    // vertex's exact numbers; CSpace::vertex writes only this one's)
    if (vertex >= bounds.size()) bounds.resize(vertex + 1, {std::nan(""), std::nan("")});
    std::array<double, 2>& b = bounds[vertex];
    if (std::isnan(b[0])) {
      const CSpaceVertex& p = spaces[pair]->vertex(VertexId(vertex));
      b = {simulation::double_below(p.y_lower), simulation::double_above(p.y_upper)};
    }
    return b;
  }

  bool on_vertical_edge(const Active& a, double ty) const {
    const CSpace& space = *spaces[a.pair];
    const CSpaceEdge& edge = space.edge(a.edge);
    // the sign of y - (the vertex's y); nullopt where it is not decided
    auto side_of = [&](std::size_t vertex, const Rational& y) -> std::optional<int> {
      const CSpaceVertex& p = space.vertex(VertexId(vertex));
      if (y < p.y_lower) return -1;
      if (y > p.y_upper) return 1;
      try {
        return space.compare_ordinate(VertexId(vertex), y);
      } catch (const GeometryError&) {
        return std::nullopt;
      }
    };
    std::optional<Rational> y;   // made where the doubles do not decide
    const bool filter = simulation::ordinate_filter();
    // source: the lower end (same x, smaller y); target: the upper end
    for (int end = 0; end < 2; ++end) {
      std::size_t vertex = end == 0 ? edge.source : edge.target;
      if (vertex == no_index) continue;
      const int outside = end == 0 ? -1 : 1;   // the side of the vertex off the edge
      const std::array<double, 2> bounds = filter ? ordinate_bounds(a.pair, vertex) : std::array<double, 2>{};
      std::optional<int> side;
      if (filter && ty < bounds[0]) {
        side = -1;
        ++simulation::ordinate_filter_decided();
      } else if (filter && ty > bounds[1]) {
        side = 1;
        ++simulation::ordinate_filter_decided();
      } else {
        if (!y) y.emplace(ty);
        side = side_of(vertex, *y);
      }
      if (!side || *side != outside) continue;
      if (!a.at_vertex) return false;
      if (!y) y.emplace(ty);
      // within `limit` of the vertex: y moved back by limit is not off the edge
      const double limit = strict_rows ? strict_limit(a) : slack_of(a);
      std::optional<int> back = side_of(vertex, *y - outside * Rational(limit));
      if (back && *back == outside) return false;
    }
    return true;
  }

  // How far held contact `a` at qs is inside its edge's extent (with its slack), in the chart
  // coordinate row() watches: < 0 where row() fails for being past an end; NaN for a contact
  // whose extent is not watched. Only a proposal for the step's cut search (cut_search.hpp).
  double edge_room(const Active& a, const Vec& qs) const {
    if (a.point && !a.bounded_y) return std::nan("");
    const CSpaceChart& chart = chart_of(a);
    if (a.point) {
      // past the exact end vertex by more than on_vertical_edge's limit (none off a vertex)
      double ty = to_chart(chart.y_kind, chart.y_half_turn, qs[a.ydof]);
      double beyond = a.at_vertex ? std::min(slack_of(a), strict_rows ? strict_limit(a) : slack_of(a)) : 0.0;
      return std::min(ty - (a.y_lo - beyond), (a.y_hi + beyond) - ty);
    }
    double tx = to_chart(chart.x_kind, chart.x_half_turn, qs[a.xdof]);
    const auto [below, above] = end_slacks(a, abscissa_slack(a));
    return std::min(tx - (a.x_lo - below), (a.x_hi + above) - tx);
  }

  // How far past its edge's (double) abscissa extent a non-vertical held contact's row holds:
  // its slack; while the motion is checked, for a contact taken up (or kept) at a vertex, 1e-12
  // chart units only, as derivatives_near() allows it. With the slack there, the rows (clamped
  // into the edge) let the step's motion run up to 3e-9 past the vertex, into the other contact
  // of a wedge, and the cut came that far inside: the ratchet's wedge chattered for ever on the
  // energy that moving back out gave it each time (session 36, docs/simulation.md).
  double abscissa_slack(const Active& a) const {
    return strict_rows && a.wedge ? std::min(slack_of(a), vertex_limit * a.unit) : slack_of(a);
  }

  // How far past the lower and the upper end of its edge's abscissa extent non-vertical held
  // contact `a`'s row holds (`slack`: abscissa_slack, or the watch's slack_of): `slack` at both
  // ends, but for a contact taken up (or kept) at a vertex (at_vertex, vertex_end) only about
  // that vertex; past the other end at most the fixed edge slack, as for any held contact. A
  // corner contact taken up at a vertex with three times the edge slack ran 3e-9 past its far
  // end before the step's cut, exactly as far as the new contacts there reach with their own
  // slack: at a vertex where the new contact's edge ends too (the free cell closing in a cusp,
  // 6 x 8 teeth at t = 0.0700516 s) its row failed 1e-18 beyond that, no contact was taken up,
  // and the pair was released into blocked space ("a jammed contact change", session 58).
  std::pair<double, double> end_slacks(const Active& a, double slack) const {
    if (a.point || !a.at_vertex || a.vertex_end == 0) return {slack, slack};
    const double far = std::min(slack, edge_slack * a.unit);
    return a.vertex_end > 0 ? std::pair{far, slack} : std::pair{slack, far};
  }

  // Whether some pair holds a wedge: two held contacts, or one kept back from a wedge's vertex.
  bool wedged() const {
    return std::any_of(active.begin(), active.end(), [](const Active& a) { return a.wedge; });
  }
  static constexpr double vertex_limit = 1e-10;   // a fraction of the abscissa's unit

  // the constraint's gradient over dofs, its bias h (g'' = G q'' + h) and its value g
  bool row(const Active& a, const Vec& qs, const Vec& vs, Vec& G, double& h, double& gval) const {
    G.assign(dofs.size(), 0.0);
    h = 0;
    if (a.point) {
      if (a.bounded_y) {
        // a vertical edge ends where the other part leaves the edge's ordinate range
        const CSpaceChart& chart = chart_of(a);
        double ty = to_chart(chart.y_kind, chart.y_half_turn, qs[a.ydof]);
        if (ty < a.y_lo - slack_of(a) || ty > a.y_hi + slack_of(a)) return false;
        if (!on_vertical_edge(a, ty)) return false;
      }
      G[a.xdof] = a.sigma;
      gval = a.sigma * (qs[a.xdof] - a.c);
      return true;
    }
    const CSpaceChart& chart = chart_of(a);
    double tx = to_chart(chart.x_kind, chart.x_half_turn, qs[a.xdof]);
    const auto [below, above] = end_slacks(a, abscissa_slack(a));
    if (tx < a.x_lo - below || tx > a.x_hi + above) return false;
    // within the slack of an end: the nearest abscissa strictly inside (the ends are algebraic)
    const double at = tx;
    // (a fraction of the edge's own extent: scale-free already)
    double inset = 1e-9 * (a.x_hi - a.x_lo);
    tx = std::clamp(tx, a.x_lo + inset, a.x_hi - inset);
    // certified double-interval derivatives along the edge; the exact ones where that filter
    // cannot certify (an end, a near-singular point): the same rows within rounding
    double y1, y2, ty, dy_chart;
    if (std::optional<EdgeSlopes> s = track_derivatives(*spaces[a.pair], a.edge, tx, a.tracker)) {
      y1 = mid(s->coordinate_dy);
      y2 = mid(s->coordinate_d2y);
      ty = mid(s->y);
      dy_chart = mid(s->dy);
    } else {
      EdgeDerivatives d;
      if (!derivatives_near(a, tx, d)) return false;
      y1 = mid(d.coordinate_dy);
      y2 = mid(d.coordinate_d2y);
      ty = d.y.approximate();
      dy_chart = mid(d.dy);
    }
    // the rows are those at the clamped abscissa, but the contact's value is its curve's at the
    // configuration's own abscissa (continued along the tangent there), everywhere: taken at the
    // clamped point, it was off by the slope x the clamp (up to 1e-9 of the edge's length and the
    // slack past the end), and the configuration put on two contacts at their vertex landed that
    // far from it, outside the other's edge (the translating wedge, docs/simulation.md, sessions
    // 38 and 39)
    if (tx != at) ty += dy_chart * (at - tx);
    G[a.xdof] = -a.sigma * y1;
    G[a.ydof] += a.sigma;
    h = -a.sigma * y2 * vs[a.xdof] * vs[a.xdof];
    double dy;
    if (chart.y_kind == AxisKind::translation) {
      dy = qs[a.ydof] - ty;
    } else {
      double yq = (chart.y_half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(ty);
      dy = std::remainder(qs[a.ydof] - yq, 2 * std::numbers::pi);
    }
    gval = a.sigma * dy;
    return true;
  }

  // accelerations()'s and friction_of()'s working storage (simulation/kept_scratch.hpp): kept
  // between calls while the switch is on, fresh per call while it is off. Every member is
  // written on each call before it is read (resized to the call's sizes); a Coulomb row of a
  // contact without friction is reset to a default one's fields (its tangent row is read only
  // where `on`).
  struct Scratch {
    Vec Q, row, Gp, T;
    Vec rhs_q, rhs_v, rhs_acc, rhs_lambda;   // rhs()'s, handed to accelerations()
    std::vector<FeatureId> features;
    Eigen::MatrixXd G, MinvGt, A;
    Eigen::VectorXd h, minv, a0, vel, b, l, da;
    std::vector<simulation::Friction> friction;
    std::vector<int> state;
    simulation::FrictionalSolution solution;
    simulation::BilateralWork work;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solve;
    simulation::LcpWork lcp;             // the step start's contact LCP (lcp.hpp's work form)
    simulation::LcpSolution lcp_solution;
  };
  mutable Scratch scratch_;

  // The held conditions of the bilateral solution s (rows G, h; inverse masses minv; free
  // accelerations a0; states), exactly: simulation::held_verdict. A wedge (some active contact
  // a wedge: solve_bilateral may take the frictionless multipliers the sticking rows leave
  // open) keeps the doubles' signs and limits: which multipliers the equations leave open is
  // itself decided in floating point there (friction.hpp's undetermined()).
  void held_conditions(const Eigen::MatrixXd& G, const Eigen::VectorXd& minv, const Eigen::VectorXd& a0,
                       const Eigen::VectorXd& h, const std::vector<simulation::Friction>& friction,
                       const std::vector<int>& state, const simulation::FrictionalSolution& s, ContactForces& out) const {
    const auto m = static_cast<std::size_t>(G.rows());
    if (!wedged()) {
      simulation::HeldVerdict verdict = simulation::held_verdict(G, minv, a0, h, friction, state);
      out.force_sign = std::move(verdict.force_sign);
      out.beyond_static = std::move(verdict.beyond_static);
      return;
    }
    out.force_sign.assign(m, 0);
    out.beyond_static.assign(m, false);
    for (std::size_t k = 0; k < m; ++k) {
      const double lambda = s.lambda(static_cast<Eigen::Index>(k));
      out.force_sign[k] = (lambda > 0) - (lambda < 0);
      const simulation::Friction& c = friction[k];
      if (!c.on || state[k] != simulation::stick) continue;
      const double limit = c.mu_static * lambda / c.s;   // (the former margin: 2e-9 over the 1e-9 of the start)
      out.beyond_static[k] = std::abs(s.f(static_cast<Eigen::Index>(k))) > limit * (1 + 2e-9) + 1e-300;
    }
  }

  // accelerations (all dofs) and multipliers of the active constraints; false when a
  // constraint is outside its edge. `lifting` null: every active contact is held (a bilateral
  // constraint: the multipliers may come out negative, which the step's bisection detects).
  // `lifting` given: the contact forces of all active contacts at once from the complementarity
  // problem lambda >= 0, g'' = A lambda + b >= 0, lambda g'' = 0 (A = G M^-1 G^T, b = G a_free + h;
  // src/simulation/lcp.hpp); the contacts whose force is zero and whose normal acceleration is
  // positive (they would separate) are listed in `lifting`, and the accelerations are those of
  // the LCP's solution.
  bool accelerations(double time, const Vec& qs, const Vec& vs, Vec& acc, Vec& lambda,
                     std::vector<std::size_t>* lifting = nullptr, ContactForces* out = nullptr) const {
    std::optional<Scratch> fresh;   // (made only with the switch off: its destructor is not free)
    Scratch& w = simulation::kept_scratch() ? scratch_ : fresh.emplace();
    Vec& Q = w.Q;
    forces(time, qs, vs, Q);
    std::size_t n = dofs.size();
    acc.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      if (!dofs[i].driven) acc[i] = Q[i] / dofs[i].inertia;
      else if (!dofs[i].profile_t.empty()) {
        double qd, vd;
        driver_law(dofs[i], time, qd, vd, acc[i]);
      }
    lambda.clear();
    if (lifting) lifting->clear();
    if (active.empty()) return true;
    std::size_t m = active.size();
    Eigen::MatrixXd& G = w.G;
    Eigen::VectorXd& h = w.h;
    G.resize(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
    h.resize(static_cast<Eigen::Index>(m));
    Vec& row_k = w.row;
    for (std::size_t k = 0; k < m; ++k) {
      double hk, gk;
      if (!row(active[k], qs, vs, row_k, hk, gk)) return false;
      for (std::size_t i = 0; i < n; ++i) G(k, i) = row_k[i];
      h(k) = hk;
    }
    // Coulomb friction of the held contacts (docs/simulation.md#friction); without it the
    // frictionless code below runs unchanged (bit for bit)
    std::vector<simulation::Friction>& friction = w.friction;
    friction.resize(m);
    bool any = false;
    for (std::size_t k = 0; k < m; ++k) {
      if (mu_static[active[k].pair] <= 0) {
        simulation::reset(friction[k]);
        continue;
      }
      row_k.assign(n, 0.0);
      for (std::size_t i = 0; i < n; ++i) row_k[i] = G(k, i);
      features_of(active[k], w.features);
      friction_of(active[k].pair, w.features, row_k, qs, friction[k]);
      any = any || friction[k].on;
    }
    if (any) {
      Eigen::VectorXd& minv = w.minv;
      inverse_masses(minv);
      Eigen::VectorXd& a0 = w.a0;
      Eigen::VectorXd& vel = w.vel;
      a0 = Eigen::Map<const Eigen::VectorXd>(acc.data(), n);
      vel = Eigen::Map<const Eigen::VectorXd>(vs.data(), n);
      std::vector<int>& state = w.state;
      state.assign(m, simulation::frictionless);
      for (std::size_t k = 0; k < m; ++k) {
        simulation::Friction& c = friction[k];
        if (!c.on) continue;
        double vt = c.T.dot(vel);
        bool sliding = std::abs(vt) > tangential_tolerance(c.T);
        if (lifting) {
          // at a step's start: a sliding contact keeps its direction; one at rest is decided
          c.decided = sliding;
          c.state = sliding ? (vt > 0 ? simulation::slip_positive : simulation::slip_negative) : simulation::stick;
          if (!sliding) c.bias = tangent_drift(active[k], qs, vs);
        } else {
          c.decided = true;
          c.state = active[k].coulomb_known ? active[k].coulomb
                    : sliding                ? (vt > 0 ? simulation::slip_positive : simulation::slip_negative)
                                             : simulation::stick;
        }
        state[k] = c.state;
      }
      simulation::FrictionalSolution& s = w.solution;
      if (lifting) {
        static const std::vector<std::size_t> no_groups;   // (exact stick limits, except in a wedge)
        s = simulation::solve_frictional(G, minv, a0, h, friction, {}, wedged(), wedged() ? nullptr : &no_groups);
        if (!s.solved) {
          refuse_held_jam(G, qs, vs, time);   // (session 69: a lock does not depend on the friction)
          std::ostringstream text;
          text << "simulation: at t = " << published_time(time) << " " << time_unit << " the contact-force problem of "
               << m << " contacts with Coulomb friction has no consistent stick/slip solution (a frictional jam)";
          std::vector<std::size_t> involved;
          for (std::size_t k = 0; k < m; ++k) involved.push_back(active[k].pair);
          text << simulation::named_friction(model, involved);
          throw NumericError(text.str());
        }
        for (std::size_t k = 0; k < m; ++k)
          if (s.lambda(k) == 0 && s.w(k) > s.tolerance) lifting->push_back(k);
      } else {
        simulation::solve_bilateral(G, minv, a0, h, friction, state, wedged(), w.work, s);
        if (out) held_conditions(G, minv, a0, h, friction, state, s, *out);
      }
      for (std::size_t i = 0; i < n; ++i) acc[i] = s.x(i);
      lambda.assign(s.lambda.data(), s.lambda.data() + m);
      if (out) {
        out->friction = true;
        out->state = s.state;
        out->normal.assign(m, 0.0);
        out->tangential.assign(m, 0.0);
        out->vt.assign(m, 0.0);
        out->mu_static.assign(m, 0.0);
        for (std::size_t k = 0; k < m; ++k) {
          if (!friction[k].on) continue;
          out->normal[k] = s.lambda(k) / friction[k].s;
          out->tangential[k] = s.f(k);
          out->vt[k] = friction[k].T.dot(vel);
          out->mu_static[k] = friction[k].mu_static;
        }
      }
      return true;
    }
    Eigen::MatrixXd& MinvGt = w.MinvGt;
    MinvGt.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < m; ++k) MinvGt(i, k) = dofs[i].driven ? 0.0 : G(k, i) / dofs[i].inertia;
    Eigen::VectorXd& a0 = w.a0;
    a0 = Eigen::Map<const Eigen::VectorXd>(acc.data(), n);
    Eigen::MatrixXd& A = w.A;
    A.noalias() = G * MinvGt;
    Eigen::VectorXd& l = w.l;
    if (lifting) {
      Eigen::VectorXd& b = w.b;
      b = G * a0 + h;
      simulation::LcpSolution& s = w.lcp_solution;
      simulation::solve_lcp(A, b, w.lcp, s);
      if (!s.solved) {
        // (session 69, jam69) held contacts the drivers lock without a fresh contact: a jam,
        // named, where it is one (the state published is the step's start, this state)
        refuse_held_jam(G, qs, vs, time);
        std::ostringstream out;
        out << "simulation: at t = " << published_time(time) << " " << time_unit
            << " the contact-force complementarity problem of " << m << " contacts has no solution (a jam)";
        throw NumericError(out.str());
      }
      l = s.lambda;
      for (std::size_t k = 0; k < m; ++k)
        if (l(k) == 0 && s.w(k) > s.tolerance) lifting->push_back(k);
    } else {
      Eigen::VectorXd& rhs = w.b;
      rhs = -(G * a0 + h);
      w.solve.compute(A);
      l = w.solve.solve(rhs);
      if (out) {   // the multipliers' signs, exact (frictionless rows)
        inverse_masses(w.minv);
        for (std::size_t k = 0; k < m; ++k) simulation::reset(friction[k]);
        w.state.assign(m, simulation::frictionless);
        w.solution.lambda = l;
        w.solution.f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m));
        held_conditions(G, w.minv, a0, h, friction, w.state, w.solution, *out);
      }
    }
    Eigen::VectorXd& da = w.da;
    da.noalias() = MinvGt * l;
    for (std::size_t i = 0; i < n; ++i) acc[i] += da(i);
    lambda.assign(l.data(), l.data() + m);
    return true;
  }

  // ---------------------------------------------------------------- integration
  // ODE state: positions then velocities of the non-driven dofs
  std::vector<std::size_t> free_dofs;
  void unpack(double time, const Vec& x, Vec& qs, Vec& vs) const {
    qs.resize(dofs.size());
    vs.resize(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (dofs[i].driven) {
        if (dofs[i].profile_t.empty()) {
          qs[i] = dofs[i].q0 + dofs[i].speed * time;
          vs[i] = dofs[i].speed;
        } else {
          double ad;
          driver_law(dofs[i], time, qs[i], vs[i], ad);
        }
      }
    for (std::size_t k = 0; k < free_dofs.size(); ++k) {
      qs[free_dofs[k]] = x[k];
      vs[free_dofs[k]] = x[free_dofs.size() + k];
    }
  }
  Vec pack() const {
    Vec x(2 * free_dofs.size());
    for (std::size_t k = 0; k < free_dofs.size(); ++k) {
      x[k] = q[free_dofs[k]];
      x[free_dofs.size() + k] = v[free_dofs[k]];
    }
    return x;
  }
  void rhs(const Vec& x, Vec& dxdt, double time) const {
    // A stage of a trial step whose state overflowed (a load of 1e300 accelerates a part beyond
    // the doubles within the stages): its derivative is not a number, so the trial is rejected
    // (step(): a non-finite result is retried shorter). Until session 64 (hunt64) the stage's
    // NaN configuration reached the held contact's row and GMP's mpq_set_d(NaN) killed the
    // process with SIGFPE (scotch-yoke.json with the crank's torque 1e300 N mm).
    if (!std::all_of(x.begin(), x.end(), [](double value) { return std::isfinite(value); })) {
      dxdt.assign(x.size(), std::numeric_limits<double>::quiet_NaN());
      return;
    }
    std::optional<Scratch> fresh;   // (made only with the switch off: its destructor is not free)
    Scratch& w = simulation::kept_scratch() ? scratch_ : fresh.emplace();
    Vec &qs = w.rhs_q, &vs = w.rhs_v, &acc = w.rhs_acc, &lambda = w.rhs_lambda;
    unpack(time, x, qs, vs);
    // outside its edge a constraint is dropped here (free accelerations); the step is then cut
    // at the edge's end by end_of_step()
    accelerations(time, qs, vs, acc, lambda);
    dxdt.resize(x.size());
    std::size_t f = free_dofs.size();
    for (std::size_t k = 0; k < f; ++k) {
      dxdt[k] = vs[free_dofs[k]];
      dxdt[f + k] = acc[free_dofs[k]];
    }
  }

  // ---------------------------------------------------------------- the step's motion
  struct StepPath {
    double t0 = 0, h = 0;
    std::vector<std::array<double, 6>> c;   // per dof
    void at(double u, Vec& qs, Vec& vs) const {
      qs.resize(c.size());
      vs.resize(c.size());
      for (std::size_t i = 0; i < c.size(); ++i) {
        qs[i] = poly(c[i], u);
        vs[i] = dpoly(c[i], u) / h;
      }
    }
  };

  // The earliest u of the step's path at which held contact `a` may reach the end of its edge:
  // the watched coordinate (the abscissa, or the ordinate of a vertical edge) is a polynomial
  // of degree <= 5 in u, whose slope on [0, 1] is at most M = sum of i |c_i|; from a distance d
  // to the extent's ends (unwrapped angles about the start) it cannot pass them by tol before
  // u + (d + tol) / M, so the scan steps by that and cannot skip an excursion past an end
  // however long the step. Returns 1 when the path stays inside, else the first u found outside
  // by more than tol = 1e-12 (relative), or where the scan gives up after 10^5 steps (a graze
  // along an end: the step is only shortened there).
  double edge_watch_end(const Active& a, const StepPath& path) const {
    // a vertical edge (a point contact with an ordinate range) is watched in its ordinate
    if (a.point && !a.bounded_y) return 1;
    const bool ordinate = a.point;
    const int dof = ordinate ? a.ydof : a.xdof;
    if (dof < 0) return 1;
    const CSpaceChart& chart = chart_of(a);
    const auto [below, above] = end_slacks(a, slack_of(a));
    const double lo = (ordinate ? a.y_lo : a.x_lo) - below, hi = (ordinate ? a.y_hi : a.x_hi) + above;
    const AxisKind kind = ordinate ? chart.y_kind : chart.x_kind;
    const bool half_turn = ordinate ? chart.y_half_turn : chart.x_half_turn;
    const std::array<double, 6>& c = path.c[static_cast<std::size_t>(dof)];
    double q0 = c[0];
    double A = lo, B = hi;
    if (kind == AxisKind::rotation) {
      // the chart t = tan((q - centre)/2) on the branch of the path's start
      double centre = half_turn ? std::numbers::pi : 0.0;
      double base = q0 - std::remainder(q0 - centre, 2 * std::numbers::pi);
      A = base + 2 * std::atan(lo);
      B = base + 2 * std::atan(hi);
    }
    double slope = 0;
    for (int i = 1; i < 6; ++i) slope += i * std::abs(c[i]);
    if (!(slope > 0)) return 1;
    // outside by more than tol: past the end (the extent already holds the edge's slack)
    // (the 1 is the coordinate's unit: rad on a rotating axis, the chart's extent in mm on a
    // translating one, session 40)
    const double tol = 1e-12 * (a.unit + std::abs(A) + std::abs(B));
    // (the scan, and its exit at a fixed point: simulation/edge_watch.hpp)
    return simulation::watch_scan(c, A, B, tol, slope);
  }

  // A state taken from a step's path at time t: the prescribed parts exactly where their law
  // puts them at t, as the next step's path starts them (the path's polynomial and the law agree
  // only to rounding, and a state moved off contact space by a few units in the last place,
  // nudge_free, must be the state the next step starts from).
  void sync_driven() {
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (dofs[i].driven) {
        double ad;
        driver_law(dofs[i], t, q[i], v[i], ad);
      }
  }

  StepPath make_path(double t0, const Vec& q0, const Vec& v0, const Vec& a0, double t1, const Vec& q1, const Vec& v1,
                     const Vec& a1) const {
    StepPath p;
    p.t0 = t0;
    p.h = t1 - t0;
    p.c.resize(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      if (dofs[i].driven && !dofs[i].profile_t.empty()) {
        // a speed profile: one segment's quadratic exactly (steps end at the profile's points)
        double qd, vd, ad;
        driver_law(dofs[i], t0, qd, vd, ad);
        p.c[i] = {qd, vd * p.h, 0.5 * ad * p.h * p.h, 0, 0, 0};
      } else if (dofs[i].driven) {
        // the driver's law exactly: q0 + speed t
        p.c[i] = {dofs[i].q0 + dofs[i].speed * t0, dofs[i].speed * p.h, 0, 0, 0, 0};
      } else {
        p.c[i] = hermite(q0[i], v0[i], a0[i], q1[i], v1[i], a1[i], p.h);
      }
    }
    return p;
  }

  // the pair's motion along the step for u in [u0, u1], written into `m` (a path kept between
  // steps reuses its rationals' limbs: simulation/step_paths.hpp)
  void pair_path_into(MotionPath& m, std::size_t pair, const StepPath& p, double u0, double u1) const {
    const CSpace& space = *spaces[pair];
    auto axis = [&](AxisPath& out, const std::string& part) {
      if (part.empty()) return simulation::clear_axis_path(out);
      int d = part_dof[*model.find_part(part)];
      simulation::assign_axis_path(out, p.c[d], dofs[d].rotation);
    };
    axis(m.x, space.x_part());
    if (space.dimension() == 2) axis(m.y, space.y_part());
    else simulation::clear_axis_path(m.y);
    m.u_begin = u0;
    m.u_end = u1;
  }
  MotionPath pair_path(std::size_t pair, const StepPath& p, double u0, double u1) const {
    MotionPath m;
    pair_path_into(m, pair, p, u0, u1);
    return m;
  }
  // one kept path per pair for the step's crossing queries (step_motions_[pair])
  mutable std::vector<MotionPath> step_motions_;
  const MotionPath& step_motion(std::size_t pair, const StepPath& p, double u_end) const {
    if (step_motions_.size() < spaces.size()) step_motions_.resize(spaces.size());
    pair_path_into(step_motions_[pair], pair, p, 0, u_end);
    return step_motions_[pair];
  }

  MotionPath point_path(std::size_t pair, const Vec& qs) const {
    StepPath p;
    p.h = 1;
    p.c.resize(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i) p.c[i] = {qs[i], 0, 0, 0, 0, 0};
    return pair_path(pair, p, 0, 1);
  }
  // point_path(pair, qs) written into a path kept between calls (its coefficients' limbs
  // reused, no step path made): the same path — each axis the constant of its part's coordinate
  // (assign_axis_path of {qs[d], 0, ...}), u over [0, 1]. Valid until the next call (the
  // nudges' trials, each asked at once; session 60).
  mutable MotionPath kept_point_path_;
  const MotionPath& point_path_kept(std::size_t pair, const Vec& qs) const {
    const CSpace& space = *spaces[pair];
    auto axis = [&](AxisPath& out, const std::string& part) {
      if (part.empty()) return simulation::clear_axis_path(out);
      int d = part_dof[*model.find_part(part)];
      simulation::assign_axis_path(out, {qs[d], 0, 0, 0, 0, 0}, dofs[d].rotation);
    };
    axis(kept_point_path_.x, space.x_part());
    if (space.dimension() == 2) axis(kept_point_path_.y, space.y_part());
    else simulation::clear_axis_path(kept_point_path_.y);
    kept_point_path_.u_begin = 0;
    kept_point_path_.u_end = 1;
    return kept_point_path_;
  }

  bool in_active(std::size_t pair) const {
    return std::any_of(active.begin(), active.end(), [&](const Active& a) { return a.pair == pair; });
  }

  std::string pair_name(std::size_t pair) const {
    return "pair (" + model.parts[model.pairs[pair].first].name + ", " + model.parts[model.pairs[pair].second].name + ")";
  }

  // (session 70, stop70) The parts of `pair` at one of their own motion limits at the
  // coordinates qs: within 1e-6 of the limits' scale of an end, or beyond it. `text` "part
  // 'follower' (/parts/1) is at 4 mm, its limits [-12, 4]" (outside()'s words since session 61),
  // `limit` "upper limit 4 mm of [-12, 4]".
  struct AtLimit {
    std::string part, text, limit;
  };
  std::vector<AtLimit> at_limits(std::size_t pair, const Vec& qs) const {
    std::vector<AtLimit> found;
    for (const std::size_t index : {model.pairs[pair].first, model.pairs[pair].second}) {
      const int d = part_dof[index];
      if (d < 0) continue;
      const Part& part = model.parts[index];
      const auto& limits = dofs[d].rotation ? part.motion.angle_limits : part.motion.translation_limits;
      if (!limits) continue;
      const double lo = to_d(limits->lo), hi = to_d(limits->hi), at = qs[d];
      const double margin = 1e-6 * std::max({1.0, std::abs(lo), std::abs(hi)});
      if (at > lo + margin && at < hi - margin) continue;
      const char* unit = dofs[d].rotation ? " rad" : " mm";
      std::ostringstream text, limit;
      text << described_part(part) << " is at " << at << unit << ", its limits [" << lo << ", " << hi << "]";
      const bool upper = at >= hi - margin;
      limit << (upper ? "upper" : "lower") << " limit " << (upper ? hi : lo) << unit << " of [" << lo << ", " << hi << "]";
      found.push_back({part.name, text.str(), limit.str()});
    }
    return found;
  }

  // Leaving the pair's built C-space at `time`: at a part's motion limit a SimulationLimit
  // (session 70: the run's results up to it are kept), otherwise the border of its operating
  // region (GeometryError). The state published is the last step's, where this step starts.
  [[noreturn]] void outside(std::size_t pair, double time) const {
    std::ostringstream out;
    out << "simulation: at t = " << published_time(time) << " " << time_unit << " the motion of " << pair_name(pair)
        << " leaves its built C-space (a motion limit, or the border of its operating region)";
    // which part is at a motion limit, named with its pointer (session 61: cam-drive.json with the
    // follower thrown up at 1e5 mm/s named the pair only)
    const std::vector<AtLimit> limits = at_limits(pair, q);
    for (std::size_t k = 0; k < limits.size(); ++k) out << (k ? "; " : ": ") << limits[k].text;
    // (the stop's time: the published state's, the last step's end, where this step starts)
    if (!limits.empty()) throw SimulationLimit(out.str(), public_state.time, limits.front().part, limits.front().limit);
    throw GeometryError(out.str());
  }

  // The velocity of point p of the part moved by coordinate d, per unit coordinate speed.
  static void point_velocity(const Dof& d, const double p[2], double J[2]) {
    if (d.rotation) {
      J[0] = -(p[1] - d.pivot[1]);
      J[1] = p[0] - d.pivot[0];
    } else {
      J[0] = d.dir[0];
      J[1] = d.dir[1];
    }
  }

  // physical contact row of a crossing: separation speed = G v
  Vec physical_row(std::size_t pair, const MotionCrossing& hit, const Vec& qs) const {
    Vec G(dofs.size(), 0.0);
    const PairSpec& spec = model.pairs[pair];
    double p[2] = {mid(hit.point[0]), mid(hit.point[1])}, n[2] = {mid(hit.normal[0]), mid(hit.normal[1])};
    auto add = [&](std::size_t part, double sign) {
      int d = part_dof[part];
      if (d < 0) return;
      double J[2];
      point_velocity(dofs[d], p, J);
      G[d] += sign * (n[0] * J[0] + n[1] * J[1]);
    };
    // the crossing's feature pair names the first part (normal from first into second)
    std::size_t first = spec.first, second = spec.second;
    if (!hit.features.empty()) {
      const FeaturePair& fp = spaces[pair]->feature_pair(hit.features.front());
      first = fp.first.part;
      second = fp.second.part;
    }
    add(first, -1);
    add(second, +1);
    (void)qs;
    return G;
  }

  // A crossing of a 1-D pair decided from its exact C-space along the motion (docs/simulation.md,
  // "Session 75 (graze75)"): free or touching on both sides of the vertex (a corner the motion
  // only grazes, a flush edge it slides along) is a graze, left out of the impact problem;
  // blocked ahead is an impact, and where the front feature pair's row does not approach (a
  // corner meeting a corner: that pair's normal, at its edge's end, is not the blocked side's),
  // the row is the crossing's feature pair whose normal approaches fastest at the configuration.
  void line_row(ContactRow& r, const MotionCrossing& c, const MotionPath& path) {
    const simulation::VertexPass pass = simulation::line_pass(*spaces[r.pair], c, path);
    if (pass == simulation::VertexPass::graze) {
      r.graze = true;
      return;
    }
    if (pass == simulation::VertexPass::slides) {
      // no impulse can act there, but the pair would stay in contact space along the touching
      // cell, which the stepping (a free start for every query) does not follow: refused
      // rather than struck (before: an impact that threw the part back)
      std::ostringstream out;
      out << "simulation: at t = " << published_time(t) << " " << time_unit << " " << pair_name(r.pair)
          << " enters a touching cell of its C-space (the parts slide flush at zero clearance, no impulse acts): "
             "the simulator cannot follow a motion along contact space without a contact force";
      publish();   // the state there
      throw NumericError(out.str());
    }
    if (pass != simulation::VertexPass::enters) return;
    r.graze = false;
    auto speed = [&](const Vec& G) {
      double s = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) s += G[i] * v[i];
      return s;
    };
    if (speed(r.g) < 0) return;
    const CSpace& space = *spaces[r.pair];
    const int d = part_dof[*model.find_part(space.x_part())];
    const PartCoordinate x = coordinate(d, q);
    double best = 0;
    for (FeatureId f : c.features) {
      std::optional<Contact> frame;
      try {
        frame = space.contact_frame(f, x);
      } catch (const GeometryError&) {
        continue;
      }
      if (!frame) continue;
      MotionCrossing one = c;
      one.features = {f};
      one.point = frame->point_range;
      one.normal = frame->normal;
      const Vec G = physical_row(r.pair, one, q);
      const double s = speed(G);
      if (s < best) {
        best = s;
        r.g = G;
        r.hit.point = one.point;
        r.hit.normal = one.normal;
        r.hit.features = {f};
        r.hit.features.insert(r.hit.features.end(), c.features.begin(), c.features.end());
        r.hit.features.erase(std::find(r.hit.features.begin() + 1, r.hit.features.end(), f));
      }
    }
  }

  std::vector<std::string> labels(std::size_t pair, const std::vector<FeatureId>& features) const {
    std::vector<std::string> out;
    for (FeatureId f : features) out.push_back(spaces[pair]->feature_pair(f).label);
    return out;
  }

  // an active contact for a pair that touches after an impact, or nullopt
  std::optional<Active> sustain(std::size_t pair, const MotionCrossing& hit, const Vec& G) const {
    const CSpace& space = *spaces[pair];
    Active a;
    a.pair = pair;
    a.xdof = part_dof[*model.find_part(space.x_part())];
    a.features = hit.features;
    if (space.dimension() == 1) {
      a.point = true;
      a.c = q[a.xdof];
      a.sigma = G[a.xdof] >= 0 ? 1 : -1;
      return a;
    }
    a.ydof = part_dof[*model.find_part(space.y_part())];
    if (!hit.edge.valid()) return std::nullopt;
    const CSpaceEdge& edge = space.edge(hit.edge);
    a.edge = hit.edge;
    a.chart = edge.chart;
    if (edge.vertical) {
      a.point = true;
      a.bounded_y = true;
      a.y_lo = edge.y_chart.lower;
      a.y_hi = edge.y_chart.upper;
      a.c = q[a.xdof];
      a.sigma = G[a.xdof] >= 0 ? 1 : -1;
      a.unit = unit_of(a);
      return a;
    }
    a.x_lo = edge.x_chart.lower;
    a.unit = unit_of(a);
    a.x_hi = edge.x_chart.upper;
    const CSpaceChart* chart = &space.charts()[edge.chart];
    double tx = to_chart(chart->x_kind, chart->x_half_turn, q[a.xdof]);
    if (tx < a.x_lo || tx > a.x_hi) {
      // at the end of the crossing's edge (a chart seam, or a vertex where the same feature pair
      // continues): the edge that continues it here
      std::optional<Active> next = continuation(a);
      if (!next) return std::nullopt;
      a = *next;
      chart = &space.charts()[a.chart];
      tx = to_chart(chart->x_kind, chart->x_half_turn, q[a.xdof]);
      if (tx < a.x_lo || tx > a.x_hi) return std::nullopt;
    }
    // the side first from the slope's certified double enclosure on a fresh tracker
    // (normal_side.hpp); the tracker answers only strictly inside the edge's exact extent and
    // where F_y is bounded away from 0, where the exact slope below neither throws nor moves the
    // contact to another edge
    if (simulation::normal_filter()) {
      EdgeTracker probe;
      if (std::optional<EdgeSlopes> s = track_derivatives(space, a.edge, tx, probe)) {
        const int side = simulation::certified_side(s->coordinate_dy.lower, s->coordinate_dy.upper, G[a.xdof], G[a.ydof]);
        if (side != 0) {
          ++simulation::normal_filter_decided();
          a.sigma = side;
          return a;
        }
      }
    }
    // the edge's slope in part coordinates (hipair/edge_slope.hpp: derivatives()'s coordinate_dy
    // without the second derivatives, the same range and the same throws)
    CertifiedRange slope;
    try {
      slope = edge_coordinate_slope(space, a.edge, Rational(tx));
    } catch (const GeometryError&) {
      // exactly past the end of the edge (its ends are algebraic; x_lo, x_hi are double
      // bounds): the contact continues on the edge that meets this one here, the same feature
      // pair or another one (a contact change at a vertex), if the configuration lies on it
      std::optional<Active> next = continuation(a);
      if (!next) next = continuation(a, true);
      if (!next) return std::nullopt;
      a = *next;
      chart = &space.charts()[a.chart];
      tx = to_chart(chart->x_kind, chart->x_half_turn, q[a.xdof]);
      try {
        slope = edge_coordinate_slope(space, a.edge, Rational(tx));
      } catch (const GeometryError&) {
        return std::nullopt;
      }
    }
    double y1 = mid(slope);
    // orient so that the C-space normal (-sigma Y', sigma) agrees with the physical normal
    double dot = -y1 * G[a.xdof] + G[a.ydof];
    a.sigma = dot >= 0 ? 1 : -1;
    return a;
  }

  // Move the configuration off contact space along M^-1 G until the pair's exact point location
  // says free: the first trial is a few units in the last place of the coordinates (a
  // configuration computed in doubles on a contact curve lies on either side of it by rounding),
  // doubling up to 2^50 of them. Nothing is moved when the configuration is already free.
  void nudge_free(std::size_t pair, const Vec& G) { nudge_free(std::vector<std::pair<std::size_t, Vec>>{{pair, G}}); }

  // The joint form: every pair of `set` (pair, C-space normal G over the dofs) is moved off
  // contact space at once, and no other pair is pushed into it. Pairs that share a part are
  // coupled: the escapement's anchor squeezed between a tooth (wheel/anchor) and the impulse pin
  // (anchor/balance). Moving off one pair alone along its own M^-1 G moves the anchor into the
  // other pair's contact by the same few ulps; that pair's own nudge then moved it back (the
  // nudge jams at -612, -675, -800 and -1200 N.mm: a pair left inside blocked space, whose next
  // crossing starts in contact with no contact row to move along). So after the pairs of the set
  // are free, every other pair that the move touches is located exactly; one found not free joins
  // the set with its contact normal (its held contacts', or its last impact's edge) and the move
  // is redone from the start along M^-1 G^T mu, A mu = 1 (A = G M^-1 G^T): every contact of the
  // set opens at the same rate.
  //
  // `alternative`: the set tried in its place where the nudge along `set` finds no free state
  // (free_active: a pair held at a vertex of two contacts whose free cell is a cusp, below).
  void nudge_free(std::vector<std::pair<std::size_t, Vec>> set, std::vector<std::pair<std::size_t, Vec>> alternative = {}) {
    const Vec start = q;
    double scale = 1;
    for (double x : q) scale = std::max(scale, std::abs(x));
    const double first = 4 * std::numeric_limits<double>::epsilon() * scale;
    auto free_at = [&](std::size_t pair, bool* blocked = nullptr) {
      // the configuration alone (u_end = u_begin): the start's exact location is the answer; a
      // constant path over [0, 1] made the query also evaluate (and exclude) the stretch [0, 1]
      // of a motion that does not move
      MotionPath& at = kept_point_path_;
      point_path_kept(pair, q);
      at.u_end = at.u_begin;
      // (status and grazing are all it reads: no description made, simulation/nudge_check.hpp)
      std::optional<StatusOnlyCrossings> status_only;
      if (simulation::status_only_nudges()) status_only.emplace();
      MotionCrossing c = spaces[pair]->first_crossing(at);
      // a trial beyond the built space (an operating region's border, reached by a nudge grown
      // over many doublings) is not a configuration proven free: the nudge goes on, and one that
      // finds none is the jam it is over the whole space (before: "leaves its built C-space")
      if (c.status == CrossingStatus::outside_region) return false;
      if (blocked) *blocked = c.status == CrossingStatus::starts_in_contact && !c.grazing;
      return c.status == CrossingStatus::none;
    };
    // After a trial of a pair of the set that the query found inside a cell, not near a curve
    // (starts_in_contact, not grazing), the next ones are first offered to a walk
    // (certainly_blocked): a trial it certifies inside the blocked cell it started in is not
    // free (first_crossing would say starts_in_contact); the others are asked. The query's
    // answer only chooses when to try; the walk places itself by its own exact location.
    std::vector<BlockedWalk> walks;
    std::vector<bool> try_walk;
    auto trial_free = [&](std::size_t k) {
      std::size_t pair = set[k].first;
      if (try_walk[k] && certainly_blocked(*spaces[pair], point_path_kept(pair, q), walks[k])) return false;
      bool blocked = false;
      bool free = free_at(pair, &blocked);
      try_walk[k] = blocked && spaces[pair]->dimension() == 2;
      return free;
    };
    for (;;) {
      walks.assign(set.size(), BlockedWalk{});
      try_walk.assign(set.size(), false);
      Vec dir = nudge_direction(set);
      double norm = 0;
      for (double x : dir) norm = std::max(norm, std::abs(x));
      q = start;
      bool done = false;
      for (int k = 0; k <= 50 && !done; ++k) {
        done = true;
        for (std::size_t i = 0; i < set.size() && done; ++i) done = trial_free(i);
        if (done || norm == 0 || k == 50) break;
        double eps = first * std::ldexp(1.0, k);
        for (std::size_t i = 0; i < dofs.size(); ++i) q[i] += eps * dir[i] / norm;
      }
      if (!done && !alternative.empty()) {
        set = std::move(alternative);
        alternative.clear();
        continue;
      }
      if (!done) {
        stop_at_limit(set, start);
        jammed(set.front().first);
      }
      if (q == start) return;
      auto moves = [&](std::size_t pair) {
        int a = part_dof[model.pairs[pair].first], b = part_dof[model.pairs[pair].second];
        return (a >= 0 && dir[a] != 0) || (b >= 0 && dir[b] != 0);
      };
      // the other pairs the move touched must still be free
      std::optional<std::pair<std::size_t, Vec>> pushed;
      for (std::size_t pair = 0; pair < spaces.size() && !pushed; ++pair) {
        if (!spaces[pair] || std::any_of(set.begin(), set.end(), [&](const auto& s) { return s.first == pair; })) continue;
        if (!moves(pair) || free_at(pair)) continue;
        q = start;   // its normal at the configuration the move started from
        Vec G;
        if (!nudge_normal(pair, G)) jammed(pair);
        pushed.emplace(pair, G);
      }
      if (pushed) {
        set.push_back(*pushed);
        continue;
      }
      // the move itself, not only its end: every pair it moves stays in the free cell of the
      // end along the whole segment, except within the allowance of the start (the contact it
      // leaves); otherwise it crossed blocked space (a tooth, a sliver) on the way
      for (std::size_t pair = 0; pair < spaces.size(); ++pair)
        if (spaces[pair] && moves(pair) && !move_certified(pair, start, first)) jammed(pair, true);
      return;
    }
  }

  // Whether the straight move from `start` to q (the nudge's accepted trial, free for `pair`)
  // stays in q's free cell of the pair except within the allowance of the start
  // (simulation/nudge_check.hpp): the reversed segment q -> start, exact at both ends.
  bool move_certified(std::size_t pair, const Vec& start, double first) const {
    if (!simulation::nudge_check()) return true;
    double length = 0;
    for (std::size_t i = 0; i < q.size(); ++i) length = std::max(length, std::abs(q[i] - start[i]));
    // a move within the allowance is the rounding itself: certified without a query, and
    // without making its exact path (simulation::move_certified's first test, taken here)
    if (length <= simulation::nudge_allowance * first) return true;
    const CSpace& space = *spaces[pair];
    MotionPath back;
    auto axis = [&](const std::string& part) {
      AxisPath a;
      if (part.empty()) return a;
      int d = part_dof[*model.find_part(part)];
      a.kind = dofs[d].rotation ? AxisPath::Kind::angle : AxisPath::Kind::offset;
      Rational from(q[d]), to(start[d]);
      a.coefficients = {from, to - from};
      if (sgn(a.coefficients[1]) == 0) a.coefficients.pop_back();
      return a;
    };
    back.x = axis(space.x_part());
    if (space.dimension() == 2) back.y = axis(space.y_part());
    return simulation::move_certified(space, back, length, simulation::nudge_allowance * first, options.crossing_bits);
  }

  // (session 70, stop70) A nudge that finds no free state for a pair of `set` where a part of it
  // is at one of its own motion limits (at `start`, the state the nudge moves from): the part is
  // held at a limit the simulator does not model as a contact (a translating part's `limits`, a
  // rotating part's `angle_limits`: the borders of the pair's C-space), and whatever pushes it
  // there cannot go on. The run stops there with a SimulationLimit naming the part and the limit,
  // that state published (the step's end, before the nudge's trials). Until session 70 this was
  // "cannot be moved off its contact (a jammed contact change)" with the state of the step before.
  void stop_at_limit(const std::vector<std::pair<std::size_t, Vec>>& set, const Vec& start) {
    for (const auto& entry : set) {
      const std::size_t pair = entry.first;
      const std::vector<AtLimit> limits = at_limits(pair, start);
      if (limits.empty()) continue;
      std::ostringstream out;
      out << "simulation: at t = " << published_time(t) << " " << time_unit << " " << pair_name(pair)
          << " cannot be moved off its contact: ";
      for (std::size_t k = 0; k < limits.size(); ++k) out << (k ? "; " : "") << limits[k].text;
      out << " (a motion limit, not a contact: what pushes the part into it cannot go on)";
      q = start;
      publish();
      throw SimulationLimit(out.str(), published_time(t), limits.front().part, limits.front().limit);
    }
  }

  // `crossed`: the only free configurations found are beyond blocked space the move would cross
  [[noreturn]] void jammed(std::size_t pair, bool crossed = false) const {
    std::ostringstream out;
    out << "simulation: at t = " << published_time(t) << " " << time_unit << " " << pair_name(pair)
        << " cannot be moved off its contact (a jammed contact change)";
    if (crossed) out << ": the nearest free configuration found lies beyond blocked space of this pair";
    throw NumericError(out.str());
  }

  // The C-space normal of a pair pushed into contact by another pair's nudge: the sum of its held
  // contacts' rows (each scaled to 1), or its last impact's contact edge. False: none known.
  bool nudge_normal(std::size_t pair, Vec& out) const {
    out.assign(dofs.size(), 0.0);
    auto add = [&](const Active& a) {
      Vec G;
      double h, gval;
      if (!row(a, q, v, G, h, gval)) return;
      double norm = 0;
      for (double x : G) norm = std::max(norm, std::abs(x));
      if (norm > 0)
        for (std::size_t i = 0; i < dofs.size(); ++i) out[i] += G[i] / norm;
    };
    for (const Active& a : active)
      if (a.pair == pair) add(a);
    if (!in_active(pair) && pair < last_contact.size() && last_contact[pair]) add(*last_contact[pair]);
    return std::any_of(out.begin(), out.end(), [](double x) { return x != 0; });
  }

  // The rows of the contacts pair `pair` holds, each its own entry of a nudge's set, when it
  // holds two or more whose rows are independent (else none): the nudge along them opens every
  // contact at the same rate (nudge_direction). The sum of the rows (nudge_normal) opens a wedge
  // whose free side is a convex corner (the ratchet's), but not a cusp: two contact curves of
  // nearly the same slope meeting at a vertex with the free cell between them, only a sliver
  // wide (a 6-tooth pinion's radial flank on the gear's tip corner meeting the back flanks'
  // contact, 6 x 8 teeth at t = 0.0700516 s: the sum pointed along the pinion's axis alone, out
  // of the sliver, and every trial up to 2^50 units in the last place was blocked).
  std::vector<std::pair<std::size_t, Vec>> held_rows(std::size_t pair) const {
    std::vector<std::pair<std::size_t, Vec>> out;
    std::vector<const Active*> held;
    for (const Active& a : active)
      if (a.pair == pair) held.push_back(&a);
    if (held.size() < 2 || !independent(held)) return out;
    for (const Active* a : held) {
      Vec G;
      double h, gval;
      if (!row(*a, q, v, G, h, gval)) return {};
      out.emplace_back(pair, G);
    }
    return out;
  }

  // The direction of a nudge: M^-1 G for one pair (as always); for several, M^-1 G^T mu with
  // (G M^-1 G^T) mu = 1 over the rows scaled to 1 (complete orthogonal decomposition: minimum
  // norm where the rows are dependent), so that every row's gap opens; where that fails (rows
  // that cannot all open), the sum of the rows' M^-1 G.
  Vec nudge_direction(const std::vector<std::pair<std::size_t, Vec>>& set) const {
    const std::size_t n = dofs.size(), m = set.size();
    Vec dir(n, 0.0);
    if (m == 1) {
      for (std::size_t i = 0; i < n; ++i)
        if (!dofs[i].driven) dir[i] = set[0].second[i] / dofs[i].inertia;
      return dir;
    }
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
    Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i)
      if (!dofs[i].driven) w[static_cast<Eigen::Index>(i)] = 1 / dofs[i].inertia;
    for (std::size_t k = 0; k < m; ++k) {
      double norm = 0;
      for (double x : set[k].second) norm = std::max(norm, std::abs(x));
      if (norm > 0)
        for (std::size_t i = 0; i < n; ++i) G(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = set[k].second[i] / norm;
    }
    Eigen::MatrixXd A = G * w.asDiagonal() * G.transpose();
    Eigen::VectorXd mu = A.completeOrthogonalDecomposition().solve(Eigen::VectorXd::Ones(static_cast<Eigen::Index>(m)));
    Eigen::VectorXd d = w.asDiagonal() * (G.transpose() * mu);
    Eigen::VectorXd opens = G * d;
    if (!(opens.minCoeff() > 0)) d = w.asDiagonal() * (G.transpose() * Eigen::VectorXd::Ones(static_cast<Eigen::Index>(m)));
    for (std::size_t i = 0; i < n; ++i) dir[i] = d[static_cast<Eigen::Index>(i)];
    return dir;
  }

  // The held contacts' positions (g = 0) and, with `velocities`, their velocities (G v = 0),
  // mass-weighted, one contact at a time, three rounds.
  void project_active(bool velocities = true) {
    for (int iteration = 0; iteration < 3; ++iteration)
      for (const Active& a : active) {
        Vec G;
        double h, gval;
        if (!row(a, q, v, G, h, gval)) continue;
        double A = 0;
        for (std::size_t i = 0; i < dofs.size(); ++i)
          if (!dofs[i].driven) A += G[i] * G[i] / dofs[i].inertia;
        if (A == 0) continue;
        double gv = 0;
        for (std::size_t i = 0; i < dofs.size(); ++i) gv += G[i] * v[i];
        for (std::size_t i = 0; i < dofs.size(); ++i)
          if (!dofs[i].driven) {
            q[i] -= G[i] / dofs[i].inertia * gval / A;
            if (velocities) v[i] -= G[i] / dofs[i].inertia * gv / A;
          }
      }
  }

  // ---------------------------------------------------------------- Coulomb friction
  // The feature pairs of a held contact: its edge's curves, or (1-D pair) those it was met with.
  std::vector<FeatureId> features_of(const Active& a) const {
    std::vector<FeatureId> out;
    features_of(a, out);
    return out;
  }
  // features_of() written into out
  void features_of(const Active& a, std::vector<FeatureId>& out) const {
    if (!a.edge.valid()) {
      out = a.features;
      return;
    }
    out.clear();
    for (std::size_t f : spaces[a.pair]->edge(a.edge).curves) out.emplace_back(f);
  }

  // The part coordinate of qs[dof]: double_coordinate's, its value made exact.
  PartCoordinate coordinate(int dof, const Vec& qs) const {
    const DoubleCoordinate d = double_coordinate(dof, qs);
    PartCoordinate c;
    c.kind = d.kind;
    if (d.kind != PartCoordinate::Kind::half_turn) c.value = Rational(d.value);
    return c;
  }

  // coordinate(dof, qs) with the value as a double (its exact value: Rational(value) there)
  DoubleCoordinate double_coordinate(int dof, const Vec& qs) const {
    DoubleCoordinate c;
    if (dofs[dof].rotation) {
      double a = std::remainder(qs[dof], 2 * std::numbers::pi);
      double tangent = std::tan(a / 2);
      if (!std::isfinite(tangent) || std::abs(tangent) > 1e15) {
        c.kind = PartCoordinate::Kind::half_turn;
      } else {
        c.kind = PartCoordinate::Kind::half_angle_tangent;
        c.value = tangent;
      }
    } else {
      c.kind = PartCoordinate::Kind::offset;
      c.value = qs[dof];
    }
    return c;
  }

  // The Coulomb data of a contact of `pair` with feature pairs `features` and constraint row G at
  // configuration qs: the contact point and normal from the adaptor's contact_frame (the
  // kernels' frame at the configuration), the physical normal row Gp = n.(J2 - J1), the tangent
  // row T = t.(J2 - J1) with t = (-n_y, n_x), and s = (Gp.G)/(G.G) (Gp = s G for a contact whose
  // constraint is the C-space contact curve). Off when the pair is frictionless, the frame is
  // undefined, s <= 0, or the tangent has no freedom independent of the normal (T parallel to
  // G: a one-coordinate contact, whose guide takes the load; docs/simulation.md#friction).
  simulation::Friction friction_of(std::size_t pair, const std::vector<FeatureId>& features, const Vec& G,
                                   const Vec& qs) const {
    simulation::Friction c;
    friction_of(pair, features, G, qs, c);
    return c;
  }
  // friction_of() written into c (reset first: simulation::reset)
  void friction_of(std::size_t pair, const std::vector<FeatureId>& features, const Vec& G, const Vec& qs,
                   simulation::Friction& c) const {
    simulation::reset(c);
    if (mu_static[pair] <= 0 || features.empty()) return;
    const CSpace& space = *spaces[pair];
    const int xdof = part_dof[*model.find_part(space.x_part())];
    const int ydof = space.dimension() == 2 ? part_dof[*model.find_part(space.y_part())] : -1;
    // the part coordinates, made on the first frame not remembered (frame_cache.hpp)
    std::optional<std::pair<PartCoordinate, PartCoordinate>> xy;
    double p[2] = {0, 0}, n[2] = {0, 0};
    int count = 0;
    std::size_t first = 0, second = 0;
    // A frame sample from a contact frame's midpoints (a Contact or the same frame's FrameRanges).
    const auto sample_of = [](const auto& frame_ranges) {
      simulation::FrameSample sample;
      sample.defined = true;
      sample.normal[0] = mid(frame_ranges.normal[0]);
      sample.normal[1] = mid(frame_ranges.normal[1]);
      sample.point[0] = mid(frame_ranges.point_range[0]);
      sample.point[1] = mid(frame_ranges.point_range[1]);
      return sample;
    };
    for (FeatureId f : features) {
      simulation::FrameSample frame =
          frames.get(pair, f.index(), qs[xdof], ydof < 0 ? 0.0 : qs[ydof], [&]() {
            simulation::FrameSample sample;
            if (simulation::frame_doubles()) {
              // the same frame without rationals (hipair/contact_frame_doubles.hpp)
              std::optional<FrameRanges> r;
              try {
                r = contact_frame_ranges(space, f, double_coordinate(xdof, qs),
                                         ydof >= 0 ? double_coordinate(ydof, qs) : DoubleCoordinate{});
              } catch (const GeometryError&) {
                return sample;
              }
              return r ? sample_of(*r) : sample;
            }
            if (!xy) {
              xy.emplace(coordinate(xdof, qs), PartCoordinate{});
              if (ydof >= 0) xy->second = coordinate(ydof, qs);
            }
            std::optional<Contact> c;
            try {
              c = space.contact_frame(f, xy->first, xy->second);
            } catch (const GeometryError&) {
              return sample;
            }
            return c ? sample_of(*c) : sample;
          });
      if (!frame.defined) continue;
      if (count == 0) {
        n[0] = frame.normal[0];
        n[1] = frame.normal[1];
        const FeaturePair& fp = space.feature_pair(f);
        first = fp.first.part;
        second = fp.second.part;
      }
      p[0] += frame.point[0];
      p[1] += frame.point[1];
      ++count;
    }
    if (count == 0) return;
    p[0] /= count;
    p[1] /= count;
    std::optional<Scratch> fresh;   // (made only with the switch off: its destructor is not free)
    Scratch& w = simulation::kept_scratch() ? scratch_ : fresh.emplace();
    Vec& Gp = w.Gp;
    Vec& T = w.T;
    Gp.assign(dofs.size(), 0.0);
    T.assign(dofs.size(), 0.0);
    auto add = [&](std::size_t part, double sign) {
      int d = part_dof[part];
      if (d < 0) return;
      double J[2];
      point_velocity(dofs[d], p, J);
      Gp[d] += sign * (n[0] * J[0] + n[1] * J[1]);
      T[d] += sign * (-n[1] * J[0] + n[0] * J[1]);
    };
    add(first, -1);
    add(second, +1);
    double gg = 0, gpg = 0, tt = 0, tg = 0;
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      gg += G[i] * G[i];
      gpg += Gp[i] * G[i];
      tt += T[i] * T[i];
      tg += T[i] * G[i];
    }
    if (!(gg > 0) || !(gpg > 0) || !(tt > 0)) return;
    // the tangent's part orthogonal to the normal row
    double orthogonal = tt - tg * tg / gg;
    if (!(orthogonal > 1e-18 * tt)) return;
    c.on = true;
    c.s = gpg / gg;
    c.T = Eigen::Map<const Eigen::VectorXd>(T.data(), static_cast<Eigen::Index>(T.size()));
    c.mu_static = mu_static[pair];
    c.mu_kinetic = mu_kinetic[pair];
  }

  // The tangential curvature term T' qdot of held contact `a` at (qs, vs): the rate at which its
  // relative sliding speed T v changes at constant velocities (T' v), exact, by the chain rule
  // through the kernels' contact frame in dual numbers (simulation::tangent_drift,
  // simulation/frame_rate.hpp; docs/simulation.md, "The tangent's drift, exact (session 59)").
  // Only a contact at rest at a step's start takes it (Friction::bias): there the direction it
  // begins to slide in is decided by the sign of T a + T' v, and T' v is what turns the sliding
  // speed of two gear flanks through the pitch point (about 1e3 mm/s^2 for the 7 x 9 example,
  // where T a alone is of rounding size and picked either direction: docs/simulation.md,
  // session 58, slip58). 0 where no held feature pair has a frame.
  double tangent_drift(const Active& a, const Vec& qs, const Vec& vs) const {
    std::vector<FeatureId> features;
    features_of(a, features);
    const CSpace& space = *spaces[a.pair];
    std::vector<const FeaturePair*> pairs;
    for (FeatureId f : features) pairs.push_back(&space.feature_pair(f));
    const auto coordinate = [&](std::size_t part) -> std::optional<std::pair<double, double>> {
      const int d = part_dof[part];
      if (d < 0) return std::nullopt;
      return std::make_pair(qs[static_cast<std::size_t>(d)], vs[static_cast<std::size_t>(d)]);
    };
    // the feature pairs' dual geometries, made once per pair (their arcs' sectors are exact)
    const auto geometry = [&](const FeaturePair& pair) -> const simulation::DualFeatures& {
      auto [it, made] = dual_features_.try_emplace(&pair);
      if (made) it->second = simulation::dual_features(model, pair);
      return it->second;
    };
    return simulation::tangent_drift(model, pairs, coordinate, geometry);
  }
  // tangent_drift's remembered geometries, per feature pair of the spaces (which outlive them)
  mutable std::unordered_map<const FeaturePair*, simulation::DualFeatures> dual_features_;

  // tolerance of "no relative tangential velocity" for tangent row T (mm per second)
  double tangential_tolerance(const Eigen::VectorXd& T) const { return velocity_tolerance() * (1 + T.cwiseAbs().sum()); }

  Eigen::VectorXd inverse_masses() const {
    Eigen::VectorXd minv;
    inverse_masses(minv);
    return minv;
  }
  void inverse_masses(Eigen::VectorXd& minv) const {
    minv.resize(static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < dofs.size(); ++i) minv(i) = dofs[i].driven ? 0.0 : 1.0 / dofs[i].inertia;
  }

  // ---------------------------------------------------------------- impacts
  // Newton restitution for all rows at once: lambda >= 0, w = G v+ + e min(G v-, 0) >= 0,
  // lambda.w = 0. The min: a row that is already separating (a contact within the accuracy of
  // closing that joins another pair's impact, handle_contacts) has nothing to restitute; with
  // e G v- it could be struck into an approaching speed -e G v- (the escapement at -1200 N.mm,
  // t = 0.3314 s: anchor/banking left at -0.83 mm/s after separating at +2.76 mm/s).
  // Approaching rows (G v- < 0, every crossing) are unchanged.
  static bool approaching(const Eigen::VectorXd& g, const Eigen::VectorXd& v) { return simulation::approaches(g, v); }
  static Eigen::VectorXd restitutions(const std::vector<ContactRow>& rows) {
    Eigen::VectorXd e(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) e(static_cast<Eigen::Index>(k)) = rows[k].restitution;
    return e;
  }
  Vec solve_impacts(const std::vector<ContactRow>& rows, Vec* tangential = nullptr) {
    std::size_t m = rows.size(), n = dofs.size();
    if (tangential) tangential->assign(m, 0.0);
    // Coulomb friction in the impulse (docs/simulation.md#friction); without it the
    // frictionless code below runs unchanged (bit for bit)
    std::vector<simulation::Friction> friction(m);
    bool any = false;
    for (std::size_t k = 0; k < m; ++k) {
      friction[k] = friction_of(rows[k].pair, rows[k].features, rows[k].g, q);
      any = any || friction[k].on;
    }
    if (any) {
      Eigen::MatrixXd G(m, n);
      for (std::size_t k = 0; k < m; ++k)
        for (std::size_t i = 0; i < n; ++i) G(k, i) = rows[k].g[i];
      Eigen::VectorXd vm = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
      // velocity level: v+ = v- + M^-1 (W^T Lambda + T_S^T F_S), w = G v+ + e min(G v-, 0) (Newton),
      // the impulses' Coulomb conditions decided exactly (session 67, impact67) on the exact
      // restitution terms (session 68, impact68): held_friction.hpp's fixed_axis_frictional_impulses
      // (session 70, exact70: the composition moved there, a test runs it). No consistent
      // solution — up to 12 contacts with at most 8 frictional exactly none (the exact enumeration
      // is complete: session 69, exact69), else none found (more than 8 frictional: nothing tried;
      // beyond 12 the session-61 frictionless-impulse rule for a cusp of the free space, since
      // session 70 taken only where its held set is exactly consistent) — is refused below, naming
      // the pairs, in the words of a verdict only in the first case (session 71, exact71:
      // FrictionalSolution::exhausted). No model is known to reach it (session 69: the
      // session-61 cusps, 6 x 10, 6 x 11, 7 x 11 teeth, are solved by the exact enumeration).
      simulation::FrictionalSolution solution =
          simulation::fixed_axis_frictional_impulses(G, inverse_masses(), vm, restitutions(rows), friction);
      if (!solution.solved) {
        std::ostringstream when;
        when << published_time(t) << " " << time_unit;
        std::vector<std::size_t> involved;
        for (const ContactRow& r : rows) involved.push_back(r.pair);
        throw NumericError(
            simulation::inconsistent_frictional_impact(when.str(), m, model, involved, solution.exhausted));
      }
      for (std::size_t i = 0; i < n; ++i)
        if (!dofs[i].driven) v[i] = solution.x(i);
      if (tangential)
        for (std::size_t k = 0; k < m; ++k) (*tangential)[k] = solution.f(k);
      return Vec(solution.lambda.data(), solution.lambda.data() + m);
    }
    Eigen::MatrixXd G(m, n), MinvGt(n, m);
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t i = 0; i < n; ++i) {
        G(k, i) = rows[k].g[i];
        MinvGt(i, k) = dofs[i].driven ? 0.0 : rows[k].g[i] / dofs[i].inertia;
      }
    Eigen::MatrixXd A = G * MinvGt;
    Eigen::VectorXd vm = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
    Eigen::VectorXd gv = G * vm, b(m);
    for (std::size_t k = 0; k < m; ++k)
      b(k) = approaching(G.row(static_cast<Eigen::Index>(k)).transpose(), vm) ? (1 + rows[k].restitution) * gv(k)
                                                                              : gv(k);
    simulation::LcpSolution solution = simulation::solve_lcp(A, b);
    // (session 68, impact68: which contacts get an impulse and which separate decided exactly on
    // G, v and e — the doubles' LCP, with its tolerance, is the filter: exact_impact_lcp)
    const Eigen::VectorXd minv = inverse_masses();
    if (const std::optional<simulation::FrictionalSolution> exact = simulation::exact_impact_lcp(
            G, minv, vm, simulation::exact_restitution_terms(G, vm, restitutions(rows)), solution)) {
      solution.solved = exact->solved;
      if (exact->solved) {
        for (std::size_t i = 0; i < n; ++i)
          if (!dofs[i].driven) v[i] = exact->x(static_cast<Eigen::Index>(i));
        return Vec(exact->lambda.data(), exact->lambda.data() + m);
      }
    }
    if (!solution.solved) {
      std::ostringstream out;
      out << "simulation: at t = " << published_time(t) << " " << time_unit << " the impact problem of " << m
          << " simultaneous contacts has no solution";
      throw NumericError(out.str());
    }
    Eigen::VectorXd best = solution.lambda;
    Eigen::VectorXd dv = MinvGt * best;
    for (std::size_t i = 0; i < n; ++i) v[i] += dv(i);
    return Vec(best.data(), best.data() + m);
  }

  double velocity_tolerance() const {
    double vmax = 0;
    for (double x : v) vmax = std::max(vmax, std::abs(x));
    return std::sqrt(accuracy) * 1e-2 * (1 + vmax);
  }

  // A contact that separates after an impact but falls back: the free flight over the contact
  // curve, g(t) = w t + alpha t^2 / 2 in C-space units (g = the constraint of `a`, w = g', alpha
  // = g'' of the free motion), rises at most w^2 / (2 |alpha|). When that height is below the
  // integrator's accuracy (its absolute tolerance, rad or mm) the bounces that follow (a
  // geometric series of ever shorter flights under restitution < 1) are not resolved by the
  // integration anyway: the contact is taken as sustained, its remaining separating speed
  // removed by the projection on the constraint.
  bool settles(const Active& a) const {
    Vec G, acc, lambda;
    double h, gval;
    if (!row(a, q, v, G, h, gval)) return false;
    if (!accelerations(t, q, v, acc, lambda)) return false;
    double w = 0, alpha = h;
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      w += G[i] * v[i];
      alpha += G[i] * acc[i];
    }
    return w >= 0 && alpha < 0 && w * w <= 2 * -alpha * accuracy;
  }

  // (session 70, stop70) A contact row exactly, at the rational configuration of the state's
  // doubles qs (a rotation's half-angle tangent tan(theta/2) rounded to a double and taken as the
  // rational it is, or its half turn theta = pi where that tangent is beyond 1e15: coordinate(),
  // the part coordinates friction_of takes — session 71, jam71; session 70 made them itself and
  // had no half turn), a translation's offset: the kernels' exact contact frame of a feature
  // pair there (exact_contact_frame: point P, normal N), and physical_row's row on it,
  // N . (J_second(P) - J_first(P)) — J the velocity of P per unit rate of a part's coordinate
  // (a rotation k x (P - pivot), a translation its direction), exact from the model's pivots and
  // directions. Which feature pair (session 71, jam71; session 70 took the first named, whatever
  // the others): every feature pair of the row must have an exact frame there (session 72,
  // jam72: one without voids the row), each gives a row, and they must all be the same row up to
  // a positive factor (one feature pair, or coincident curves of one edge), decided exactly; rows
  // that differ (a C-space vertex, curves crossing) leave the row without an exact form, and the
  // verdict approximate. nullopt where there is none (no feature named, a feature pair without
  // an exact frame, a configuration outside every chart or beyond the doubles), or where it does
  // not agree in orientation with `g`, the doubles' row (their dot product not positive).
  std::optional<std::vector<Rational>> exact_jam_row(std::size_t pair, const std::vector<FeatureId>& features, const Vec& g,
                                                     const Vec& qs) const {
    if (features.empty() || !spaces[pair]) return std::nullopt;
    const CSpace& space = *spaces[pair];
    const int xdof = part_dof[*model.find_part(space.x_part())];
    const int ydof = space.dimension() == 2 ? part_dof[*model.find_part(space.y_part())] : -1;
    if (xdof < 0 || (space.dimension() == 2 && ydof < 0)) return std::nullopt;
    if (!std::isfinite(qs[xdof]) || (ydof >= 0 && !std::isfinite(qs[ydof]))) return std::nullopt;
    const PartCoordinate x = coordinate(xdof, qs);
    const PartCoordinate y = ydof >= 0 ? coordinate(ydof, qs) : PartCoordinate{};
    std::optional<std::vector<Rational>> found;
    for (const FeatureId f : features) {
      std::optional<Contact> frame;
      try {
        frame = exact_contact_frame(space, f, x, y);
      } catch (const GeometryError&) {
        return std::nullopt;
      }
      // (session 72, jam72; review71 jam71 M1) a feature pair whose exact frame is undefined at the
      // configuration (a vertex-vertex pair at a corner contact, a degenerate configuration: the
      // kernels' exact frame is nullopt there) may have a normal other than the others': the row
      // is not known exactly (session 71 skipped it and decided the row on the other feature pairs)
      if (!frame || !frame->exact) return std::nullopt;
      const std::array<Rational, 2>& P = frame->point;
      const std::array<Rational, 2>& N = frame->normal_direction;
      std::vector<Rational> row(dofs.size(), Rational(0));
      auto add = [&](std::size_t part, bool second) {
        const int d = part_dof[part];
        if (d < 0) return;
        const Motion& motion = model.parts[part].motion;
        const Rational along = dofs[d].rotation ? Rational(N[1] * (P[0] - motion.pivot.x) - N[0] * (P[1] - motion.pivot.y))
                                                : Rational(N[0] * motion.direction.x + N[1] * motion.direction.y);
        if (second) row[static_cast<std::size_t>(d)] += along;
        else row[static_cast<std::size_t>(d)] -= along;
      };
      const FeaturePair& fp = space.feature_pair(f);
      add(fp.first.part, false);
      add(fp.second.part, true);
      if (!found) {
        found = std::move(row);
        continue;
      }
      // the same row up to a positive factor: every 2x2 minor of (found, row) 0, and found . row > 0
      Rational dot(0);
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        dot += (*found)[i] * row[i];
        for (std::size_t j = i + 1; j < dofs.size(); ++j)
          if ((*found)[i] * row[j] != (*found)[j] * row[i]) return std::nullopt;
      }
      if (sgn(dot) <= 0) return std::nullopt;
    }
    if (!found) return std::nullopt;
    double agree = 0;
    for (std::size_t i = 0; i < dofs.size(); ++i) agree += to_d((*found)[i]) * g[i];
    if (!(agree > 0)) return std::nullopt;
    return found;
  }
  // A constant-speed driver's exact speed (the model's; its dof's speed is its double over the
  // time scale, the same for every driver), nullopt for a speed profile
  std::optional<Rational> exact_speed(std::size_t i) const {
    if (!dofs[i].profile_t.empty() || !model.simulation) return std::nullopt;
    for (const auto& driver : model.simulation->drivers)
      if (driver.part == dofs[i].part && driver.profile.empty()) return driver.speed;
    return std::nullopt;
  }

  // (session 69, jam69; session 70, stop70) Contact rows g (over the dofs: the pairs' C-space
  // contact gradients, or their physical rows) at the configuration qs that no velocity of the
  // free dofs keeps: is it a jam of the driven parts? Some y >= 0 with sum y_k a_k = 0 on the
  // free dofs and sum y_k (a_k . v_driven) < 0 (simulation/jam.hpp, the exact LP the pin-slot and
  // planar simulators use). EXACT since session 70 where every row has its exact frame
  // (exact_jam_row, at the rational configuration of qs) and every driver in them a constant
  // speed (its exact speed): the verdict is exact at that configuration, SimulationJam::exact()
  // true; where the exact rows lock nothing there is no jam (the caller's error stands).
  // Otherwise APPROXIMATE, as in session 69: the LP on the rows' doubles (rounded gradients) and
  // the drivers' velocity doubles, so a verdict at a lock that holds only in exact geometry may
  // differ; said so in the message and SimulationJam::exact() false. Returns the jam's message
  // naming the drivers, the jammed parts and the contacts of that combination, and whether it
  // was decided exactly; nullopt where there is none.
  std::optional<std::pair<std::string, bool>> jam(const std::vector<Vec>& g, const std::vector<std::size_t>& pair_of,
                                                  const std::vector<std::vector<FeatureId>>& features, const Vec& qs,
                                                  const Vec& vs, double time) const {
    std::vector<std::vector<Rational>> a;
    std::vector<Rational> d;
    for (const Vec& row : g)
      for (std::size_t i = 0; i < dofs.size(); ++i)
        if (!std::isfinite(row[i]) || !std::isfinite(vs[i])) return std::nullopt;
    // the exact rows (session 70), where every row and every driver in them has them
    std::vector<std::vector<Rational>> exact_rows;
    bool exact = true;
    for (std::size_t k = 0; k < g.size() && exact; ++k) {
      std::optional<std::vector<Rational>> row = exact_jam_row(pair_of[k], features[k], g[k], qs);
      if (!row) {
        exact = false;
        break;
      }
      std::vector<Rational> free;
      Rational closing(0);
      for (std::size_t i = 0; i < dofs.size() && exact; ++i) {
        if (!dofs[i].driven) {
          free.push_back((*row)[i]);
        } else if (sgn((*row)[i]) != 0) {
          const std::optional<Rational> speed = exact_speed(i);
          if (speed) closing += (*row)[i] * *speed;
          else exact = false;
        }
      }
      a.push_back(std::move(free));
      d.push_back(std::move(closing));
      exact_rows.push_back(std::move(*row));
    }
    if (!exact) {   // the doubles' rows (session 69)
      a.clear();
      d.clear();
      for (const Vec& row : g) {
        std::vector<Rational> free;
        Rational closing(0);
        for (std::size_t i = 0; i < dofs.size(); ++i) {
          if (!dofs[i].driven) free.emplace_back(row[i]);
          else if (row[i] != 0 && vs[i] != 0) closing += Rational(row[i]) * Rational(vs[i]);
        }
        a.push_back(std::move(free));
        d.push_back(std::move(closing));
      }
    }
    const std::optional<std::vector<std::size_t>> locked = simulation::locking_rows(a, d);
    if (!locked) return std::nullopt;
    std::vector<std::string> drivers, jammed, contacts;
    auto add = [](std::vector<std::string>& to, const std::string& name) {
      if (std::find(to.begin(), to.end(), name) == to.end()) to.push_back(name);
    };
    bool constant = true;
    for (const std::size_t k : *locked) {
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        if (exact ? sgn(exact_rows[k][i]) == 0 : g[k][i] == 0) continue;
        if (!dofs[i].driven) add(jammed, model.parts[dofs[i].part].name);
        else if (exact ? sgn(*exact_speed(i)) != 0 : vs[i] != 0) {
          add(drivers, model.parts[dofs[i].part].name);
          constant = constant && dofs[i].profile_t.empty();
        }
      }
      std::string named;   // the contact: its feature pairs (an edge's curves), or its pair
      for (const std::string& l : labels(pair_of[k], features[k])) named += (named.empty() ? "" : " + ") + l;
      contacts.push_back(named.empty() ? pair_name(pair_of[k]) : named);
    }
    if (jammed.empty() || drivers.empty()) return std::nullopt;   // (a driver against a fixed part: the caller's message)
    std::ostringstream out;
    out << "simulation: at t = " << published_time(time) << " " << time_unit << " "
        << simulation::jam_message(drivers, constant, jammed, locked->size(), contacts,
                                   exact ? "decided exactly (at the rational configuration of the state's doubles, on "
                                           "the kernels' exact contact frames there and the drivers' exact speeds)"
                                         : "approximate (found exactly on the contact rows' doubles, the C-spaces' "
                                           "rounded contact gradients, not on the exact geometry)");
    return std::make_pair(out.str(), exact);
  }
  // The held contacts' rows G (active order) at a state (qs, vs) whose force problem has no
  // solution: a jam throws its SimulationJam (the state published: the step's start, this state)
  void refuse_held_jam(const Eigen::MatrixXd& G, const Vec& qs, const Vec& vs, double time) const {
    std::vector<Vec> rows(active.size(), Vec(dofs.size(), 0.0));
    std::vector<std::size_t> pair_of;
    std::vector<std::vector<FeatureId>> features;
    for (std::size_t k = 0; k < active.size(); ++k) {
      for (std::size_t i = 0; i < dofs.size(); ++i) rows[k][i] = G(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i));
      pair_of.push_back(active[k].pair);
      features.push_back(features_of(active[k]));
    }
    if (const auto found = jam(rows, pair_of, features, qs, vs, time))
      throw SimulationJam(found->first, published_time(time), found->second);
  }
  void refuse_jam(const std::vector<ContactRow>& rows) {
    std::vector<Vec> g;
    std::vector<std::size_t> pair_of;
    std::vector<std::vector<FeatureId>> features;
    for (const ContactRow& r : rows) {
      if (r.graze) continue;
      g.push_back(r.g);
      pair_of.push_back(r.pair);
      features.push_back(r.features);
    }
    if (const auto found = jam(g, pair_of, features, q, v, t)) {
      publish();   // the state at the jam
      throw SimulationJam(found->first, published_time(t), found->second);
    }
  }
  // solve_impacts, and where it throws (no solution), the jam test first (session 69)
  Vec impacts(const std::vector<ContactRow>& rows, Vec* tangential) {
    try {
      return solve_impacts(rows, tangential);
    } catch (const NumericError&) {
      refuse_jam(rows);
      throw;
    }
  }

  // The impact problem without the rows that only graze a vertex (ContactRow::graze): their
  // impulses are 0, the others' are those of the problem without them. Without grazes, as before.
  Vec solve_grazed(const std::vector<ContactRow>& rows, Vec& tangential) {
    if (std::none_of(rows.begin(), rows.end(), [](const ContactRow& r) { return r.graze; }))
      return impacts(rows, &tangential);
    std::vector<ContactRow> struck;
    std::vector<std::size_t> index;
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (!rows[k].graze) {
        struck.push_back(rows[k]);
        index.push_back(k);
      }
    Vec lambda(rows.size(), 0.0);
    tangential.assign(rows.size(), 0.0);
    if (struck.empty()) return lambda;
    Vec struck_tangential;
    Vec struck_lambda = impacts(struck, &struck_tangential);
    for (std::size_t k = 0; k < index.size(); ++k) {
      lambda[index[k]] = struck_lambda[k];
      tangential[index[k]] = struck_tangential[k];
    }
    return lambda;
  }

  void handle_contacts(std::vector<ContactRow> rows) {
    // Contacts of other pairs that are open but within the integrator's accuracy of closing (a
    // C-space gap g of their last impact's contact edge below the absolute tolerance, rad or
    // mm) take part as impacts too: a part struck while it is squeezed between two others (the
    // escapement's anchor between a tooth and the impulse pin) otherwise bounces between the two
    // pairs at geometrically shrinking intervals, and each bounce's nudge off one contact pushes
    // it into the other. The gap is below what the integration resolves, so the contacts are
    // treated as one simultaneous impact.
    last_contact.resize(spaces.size());
    for (std::size_t pair = 0; pair < spaces.size(); ++pair) {
      if (!last_contact[pair] || in_active(pair)) continue;
      if (std::any_of(rows.begin(), rows.end(), [&](const ContactRow& r) { return r.pair == pair; })) continue;
      Vec G;
      double h, gval;
      if (!row(*last_contact[pair], q, v, G, h, gval)) continue;
      if (!(gval <= accuracy && gval > -accuracy)) continue;
      ContactRow r;
      r.g = G;
      r.pair = pair;
      r.crossing = true;
      r.restitution = model.pairs[pair].restitution ? to_d(*model.pairs[pair].restitution) : 0.0;
      r.near = last_contact[pair];
      r.features = features_of(*r.near);
      rows.push_back(r);
    }
    // the active sustained contacts take part as perfectly plastic contacts
    for (std::size_t k = 0; k < active.size(); ++k) {
      Vec G;
      double h, gval;
      if (!row(active[k], q, v, G, h, gval)) continue;
      ContactRow r;
      r.g = G;
      r.pair = active[k].pair;
      r.active = k;
      r.features = features_of(active[k]);
      rows.push_back(r);
    }
    Vec before(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      before[k] = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) before[k] += rows[k].g[i] * v[i];
    }
    Vec tangential;
    Vec lambda = solve_grazed(rows, tangential);
    double vtol = velocity_tolerance();
    std::vector<std::size_t> separate;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (!rows[k].crossing) continue;
      const ContactRow& r = rows[k];
      if (r.near && lambda[k] == 0 && before[k] >= 0) continue;   // not struck: it stays open
      double after = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) after += r.g[i] * v[i];
      SimulationEvent e;
      e.time = published_time(t);
      e.pair = r.pair;
      e.first_part = model.parts[model.pairs[r.pair].first].name;
      e.second_part = model.parts[model.pairs[r.pair].second].name;
      e.features = labels(r.pair, r.hit.features);
      e.edge = r.hit.edge;
      if (r.near && r.near->edge.valid()) {
        e.edge = r.near->edge;
        for (std::size_t f : spaces[r.pair]->edge(r.near->edge).curves)
          e.features.push_back(spaces[r.pair]->feature_pair(FeatureId(f)).label);
      }
      e.point = {mid(r.hit.point[0]), mid(r.hit.point[1])};
      e.normal = {mid(r.hit.normal[0]), mid(r.hit.normal[1])};
      e.impulse = lambda[k] / (force_scale * time_scale);
      e.tangential_impulse = tangential[k] / (force_scale * time_scale);
      e.normal_speed_before = before[k] * time_scale;
      e.normal_speed_after = after * time_scale;
      e.kind = SimulationEvent::Kind::impact;
      events.push_back(e);
      std::optional<Active> sustained = r.graze ? std::optional<Active>{} : r.near ? r.near : sustain(r.pair, r.hit, r.g);
      if (sustained) last_contact[r.pair] = sustained;
      if (sustained && after > vtol && !settles(*sustained)) sustained.reset();
      if (sustained) {
        active.push_back(*sustained);
        e.kind = SimulationEvent::Kind::contact;
        events.push_back(e);
      } else {
        separate.push_back(k);
      }
    }
    // A held contact the impact lets separate (no impulse, its normal speed after the impact
    // above the velocity tolerance) lifts off at the impact. Before (session 64, stick64), the
    // projection below put every held contact's normal speed back to 0, undoing the impact's
    // outcome: the escapement's balance pin striking the fork while the anchor rested on its
    // banking pin pushed the anchor off the pin, the projection took that speed away, the pin
    // struck again at the same instant, and again (25 impacts at t = 0.0712 s, each losing a
    // twelfth of the speed, when the exit pallet's lock slipped at t = 0.0547 s).
    std::vector<std::pair<std::size_t, Vec>> lifted;   // (active index, its normal beyond)
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (rows[k].crossing || lambda[k] != 0) continue;
      double after = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) after += rows[k].g[i] * v[i];
      if (after > vtol) lifted.emplace_back(rows[k].active, Vec());
    }
    std::sort(lifted.begin(), lifted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::pair<std::size_t, Vec>> gone;   // (pair, its normal)
    for (auto& [index, normal] : lifted) {
      gone.emplace_back(active[index].pair, Vec());
      release(index, SimulationEvent::Kind::lift_off, false, &gone.back().second);
    }
    project_active();
    for (std::size_t k : separate) nudge_free(rows[k].pair, rows[k].g);
    for (auto& [pair, G] : gone)
      if (!in_active(pair)) nudge_free(pair, G);
  }

  // ---------------------------------------------------------------- one step
  // The edge that continues sustained contact `a` past the end of its edge with the same feature
  // pair (across a chart seam, or past a vertex where another curve only crosses spurious
  // space): nullopt when the contact really changes there.
  std::optional<Active> continuation(const Active& a, bool any_curve = false) const {
    if (a.point || !a.edge.valid()) return std::nullopt;
    const CSpace& space = *spaces[a.pair];
    const CSpaceEdge& old_edge = space.edge(a.edge);
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      if (e == a.edge.index()) continue;
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.real || edge.vertical) continue;
      bool shares = std::any_of(edge.curves.begin(), edge.curves.end(), [&](std::size_t c) {
        return std::find(old_edge.curves.begin(), old_edge.curves.end(), c) != old_edge.curves.end();
      });
      if (!shares && !any_curve) continue;
      const CSpaceChart& chart = space.charts()[edge.chart];
      double tx = to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]);
      const double near_edge = edge_slack * axis_unit(chart, false);
      if (!(tx > edge.x_chart.lower - near_edge && tx < edge.x_chart.upper + near_edge)) continue;
      Active b = a;
      b.wedge = false;   // on along the curve, away from a wedge's vertex
      b.edge = EdgeId(e);
      b.chart = edge.chart;
      b.x_lo = edge.x_chart.lower;
      b.x_hi = edge.x_chart.upper;
      b.unit = unit_of(b);
      // a contact taken up at a vertex keeps its slack about the end it enters the new edge by
      // (the seam or vertex it is at now), the fixed edge slack past the other (end_slacks). The
      // old edge's vertex_end names the old edge's end the step's cut reached: copied, it named
      // the new edge's far end wherever the motion runs towards the upper end, and the cut there
      // came three edge slacks past it (session 61: 6 x 11 teeth, backlash 0.08 mm, offset -0.02 mm, the gear's tip on
      // the pinion's radial flank continued across the chart seam at 1/16 and ran 3e-9 past the
      // cusp where the back flanks' contact begins, beyond that contact's reach: released into
      // blocked space, "a jammed contact change")
      if (b.at_vertex) mark_vertex_end(b);
      Vec G;
      double h, gval;
      b.sigma = 1;
      if (!row(b, q, v, G, h, gval)) continue;
      if (another_branch(b, gval)) continue;
      BlockedSide side = space.blocked_side(b.edge);
      b.sigma = side == BlockedSide::left ? -1 : 1;
      return b;
    }
    return std::nullopt;
  }

  // Whether a contact's value gval (in its constraint's coordinate: the ordinate, a vertical
  // edge's abscissa; rad or mm) is too far from 0 for the configuration to be on that edge: more
  // than 1e-6 of the coordinate's unit (axis_unit; session 40: 1e-6 mm absolute before, larger
  // than a model at 10^-6 mm).
  bool another_branch(const Active& b, double gval) const {
    return std::abs(gval) > 1e-6 * axis_unit(chart_of(b), !b.point);
  }

  // The contact change at the end of sustained contact k's edge: the vertex reached, and the
  // real contact edges of the same pair that meet it there and bound the same free cell (the
  // other contact curves through the vertex). While the pair slides along the edge nothing else
  // can be touched: the arrangement has a vertex wherever another contact curve meets the edge,
  // and curves culled as certainly blocked cannot meet a free cell's boundary; so the vertex's
  // curves are every new contact of the pair, and they are all taken up here.
  std::vector<Active> vertex_candidates(const Active& a) const {
    std::vector<Active> out;
    if (!a.edge.valid()) return out;
    const CSpace& space = *spaces[a.pair];
    const CSpaceEdge& old_edge = space.edge(a.edge);
    const CSpaceChart& chart = chart_of(a);
    bool at_target;
    if (a.point) {
      double ty = to_chart(chart.y_kind, chart.y_half_turn, q[a.ydof]);
      at_target = ty > 0.5 * (a.y_lo + a.y_hi);
    } else {
      double tx = to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]);
      at_target = tx > 0.5 * (a.x_lo + a.x_hi);
    }
    std::size_t vertex = at_target ? old_edge.target : old_edge.source;
    if (vertex == no_index) return out;
    BlockedSide old_side = space.blocked_side(a.edge);
    std::size_t free_cell = old_side == BlockedSide::left ? old_edge.right_cell : old_edge.left_cell;
    for (std::size_t e : space.vertex(VertexId(vertex)).edges) {
      if (e == a.edge.index()) continue;
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.real || edge.role != EdgeRole::contact) continue;
      if (edge.curves == old_edge.curves) continue;   // the same contact (its continuation failed)
      BlockedSide side = space.blocked_side(EdgeId(e));
      if (side == BlockedSide::none) continue;
      std::size_t cell = side == BlockedSide::left ? edge.right_cell : edge.left_cell;
      if (cell != free_cell) continue;
      bool held = std::any_of(active.begin(), active.end(), [&](const Active& b) {
        return b.pair == a.pair && b.edge.valid() && space.edge(b.edge).curves == edge.curves;
      });
      if (held) continue;
      Active b;
      b.pair = a.pair;
      b.xdof = a.xdof;
      b.ydof = a.ydof;
      b.edge = EdgeId(e);
      b.chart = edge.chart;
      // the configuration is at the vertex to the bisection's resolution: accept the new edge
      // within three times the edge slack of its certified extent. Not three times the old
      // contact's slack: that grew threefold at every contact change (3^7 edge slacks, 2.2e-6,
      // after seven in a gear pair's mesh), and a contact taken up at a vertex is valid within
      // its slack past either end of its edge, so the motion ran 6.7e-7 past the far end of a
      // tooth's contact edge into the next tooth's blocked space without an edge end, and the
      // nudge found free space only beyond it ("a jammed contact change", session 57)
      b.slack = 3 * edge_slack;
      b.at_vertex = true;
      if (edge.vertical) {
        b.point = true;
        b.bounded_y = true;
        b.y_lo = edge.y_chart.lower;
        b.y_hi = edge.y_chart.upper;
        b.c = q[a.xdof];
        b.sigma = side == BlockedSide::left ? 1 : -1;   // upwards, left is smaller x
      } else {
        b.x_lo = edge.x_chart.lower;
        b.x_hi = edge.x_chart.upper;
        b.sigma = side == BlockedSide::left ? -1 : 1;   // left is above
      }
      b.unit = unit_of(b);
      Vec G;
      double h, gval;
      bool ok = row(b, q, v, G, h, gval);
      if (!ok) continue;
      if (another_branch(b, gval)) continue;
      if (std::none_of(out.begin(), out.end(), [&](const Active& c) { return space.edge(c.edge).curves == edge.curves; }))
        out.push_back(b);
    }
    return out;
  }

  void edge_event(const Active& a, SimulationEvent::Kind kind, double impulse = 0, double before = 0, double after = 0) {
    SimulationEvent e;
    e.kind = kind;
    e.time = published_time(t);
    e.pair = a.pair;
    e.first_part = model.parts[model.pairs[a.pair].first].name;
    e.second_part = model.parts[model.pairs[a.pair].second].name;
    e.edge = a.edge;
    if (a.edge.valid())
      for (std::size_t f : spaces[a.pair]->edge(a.edge).curves) e.features.push_back(spaces[a.pair]->feature_pair(FeatureId(f)).label);
    e.impulse = impulse;
    e.normal_speed_before = before;
    e.normal_speed_after = after;
    events.push_back(e);
  }

  // Sustained contact k reached the end of its edge at a vertex where other contact curves of
  // its pair begin: one impact problem over every active contact (plastic) and the new ones
  // (the pair's restitution), all at once; the new contacts left without separating speed are
  // held, and contact k stays held while it has no separating speed and either a new contact is
  // held (the corner of a wedge, held by both) or the motion leaves the vertex back along k's
  // edge (the new contacts struck off: the wedge's chatter, on k's edge). False when the vertex
  // has no new contact (the caller releases k).
  //
  // The configuration is first put on the vertex when the step's cut left it past the vertex,
  // inside a new contact's blocked side (session 36, docs/simulation.md): a held contact's rows
  // are valid up to its slack (1e-9 chart units) beyond its edge's end, so the cut comes there,
  // up to slack x slope inside the other curve — at the ratchet's wedge 2.6e-8, far beyond what
  // a nudge may move unchecked (nudge_check.hpp) and inside the blind zone of the blocked walk
  // next to the vertex: "cannot be moved off its contact".
  bool vertex_contacts(std::size_t k) {
    std::vector<Active> candidates = vertex_candidates(active[k]);
    if (candidates.empty()) return false;
    std::size_t pair = active[k].pair;
    double e = model.pairs[pair].restitution ? to_d(*model.pairs[pair].restitution) : 0.0;
    const Active old = active[k];
    // contact k's rows are those of its end (as when it is kept, below) within three times the
    // edge slack of it (not growing at each visit of a chattering wedge), and the configuration
    // is put on the vertex (place_at_vertex: where the pair's free coordinates can reach it)
    active[k].slack = std::max(old.slack, 3 * edge_slack);
    active[k].at_vertex = true;
    mark_vertex_end(active[k]);
    // the placement takes k's row at its end vertex wherever the cut left the configuration past
    // it (the event says the pair is at the vertex; its curve's value there, continued along the
    // tangent, puts the configuration on it), then k keeps the slack above
    const double past = past_end(active[k]);
    const double slack = active[k].slack;
    if (past > slack_of(active[k])) active[k].slack = 2 * past / active[k].unit;
    place_at_vertex(active[k], candidates);
    active[k].slack = slack;
    std::vector<ContactRow> rows;
    std::vector<std::size_t> row_active;   // active index, or no_index for a candidate
    for (std::size_t j = 0; j < active.size(); ++j) {
      ContactRow r;
      double h, gval;
      if (!row(active[j], q, v, r.g, h, gval)) continue;
      r.pair = active[j].pair;
      r.active = j;
      r.features = features_of(active[j]);
      rows.push_back(r);
      row_active.push_back(j);
    }
    std::size_t first_candidate = rows.size();
    for (const Active& c : candidates) {
      ContactRow r;
      double h, gval;
      row(c, q, v, r.g, h, gval);
      r.pair = pair;
      r.crossing = true;
      r.restitution = e;
      r.features = features_of(c);
      rows.push_back(r);
    }
    Vec before(rows.size(), 0.0);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (std::size_t i = 0; i < dofs.size(); ++i) before[r] += rows[r].g[i] * v[i];
    Vec tangential;
    Vec lambda = impacts(rows, &tangential);
    double vtol = velocity_tolerance();
    auto after_of = [&](std::size_t r) {
      double w = 0;
      for (std::size_t i = 0; i < dofs.size(); ++i) w += rows[r].g[i] * v[i];
      return w;
    };
    // the impulse of a contact met at a vertex is along its C-space normal (generalised units:
    // force unit x time unit x mm per C-space unit): no physical contact point is computed there
    bool struck = false;
    for (std::size_t r = first_candidate; r < rows.size(); ++r) {
      const Active& c = candidates[r - first_candidate];
      double after = after_of(r);
      if (lambda[r] > 0 || before[r] < 0) {
        struck = true;
        edge_event(c, SimulationEvent::Kind::impact, lambda[r] / (force_scale * time_scale), before[r] * time_scale,
                   after * time_scale);
        events.back().tangential_impulse = tangential[r] / (force_scale * time_scale);
      }
      if (after <= vtol || settles(c)) {
        active.push_back(c);
        mark_vertex_end(active.back());
        edge_event(c, SimulationEvent::Kind::contact);
      }
    }
    // the old contact: held when it has no separating speed and the motion stays on its edge,
    // else it ends here (no new contact held and the motion going on past the vertex: it leaves
    // the vertex into free space, k ends too)
    std::size_t r_old = std::find(row_active.begin(), row_active.end(), k) - row_active.begin();
    bool added = false;
    for (std::size_t j = 0; j < active.size(); ++j)
      for (const Active& c : candidates) added = added || (active[j].pair == pair && active[j].edge == c.edge);
    // a new contact held with k: both stay only where their rows hold the pair together (a
    // wedge, independent(): the ratchet's tooth between the pawl's nose face and corner); with
    // dependent rows (one free coordinate, or a curve tangent to k's: the Geneva pin from its
    // slot wall onto the mouth's corner) the new contact takes over and k ends at its vertex
    std::vector<const Active*> held;
    for (const Active& a : active)
      if (a.pair == pair) held.push_back(&a);
    bool keep = r_old < row_active.size() && after_of(r_old) <= vtol &&
                ((added && independent(held)) || (struck && back_along_edge(old)));
    if (!keep) {
      Vec G = normal_or_last(active[k]);
      edge_event(old, SimulationEvent::Kind::edge_end);
      active.erase(active.begin() + static_cast<std::ptrdiff_t>(k));
      // a new contact taking over keeps the velocity of the impact problem at the vertex (k's
      // row plastic there): its own row is taken inside its edge, up to 1e-9 of the edge's
      // length past the vertex, where a curve of high curvature (the pin rolling round the
      // slot's corner) has another slope (1.2e-7 rad/s of the Geneva wheel's speed)
      project_active(!added);
      if (!in_active(pair)) {
        // off the old contact and every new one struck here (the configuration is at their
        // vertex): the joint direction opens all of them
        std::vector<std::pair<std::size_t, Vec>> set{{pair, G}};
        if (struck)
          for (std::size_t r = first_candidate; r < rows.size(); ++r) set.emplace_back(pair, rows[r].g);
        nudge_free(set);
      }
    } else {
      // a wedge: held by both (or more) contacts of the pair, or by k back from its vertex
      active[k].wedge = true;
      for (Active& a : active)
        for (const Active& c : candidates) a.wedge = a.wedge || (a.pair == pair && a.edge == c.edge);
      project_active();
      // held by two contacts (or more) of the pair: on all of them at once, at rest on them
      if (added && held.size() > 1) project_jointly(held, true);
    }
    return true;
  }

  // How far the configuration moved from `from` along non-vertical held contact `a`'s chart
  // abscissa (0 for a point contact).
  double abscissa_shift(const Active& a, const Vec& from) const {
    if (a.point) return 0;
    const CSpaceChart& chart = chart_of(a);
    return std::abs(to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]) - to_chart(chart.x_kind, chart.x_half_turn, from[a.xdof]));
  }

  // The configuration moved onto held contact `a`'s curve by its ordinate alone, the abscissa
  // kept (nothing where the ordinate is driven or the row is not valid here).
  void onto_curve_at_abscissa(const Active& a) {
    if (a.point || a.ydof < 0 || dofs[a.ydof].driven) return;
    Vec G;
    double h, gval;
    if (!row(a, q, v, G, h, gval)) return;
    q[a.ydof] -= gval / G[a.ydof];
  }

  // The end of non-vertical held contact `a`'s edge nearer the configuration: the vertex where
  // it is taken up or kept (at_vertex).
  void mark_vertex_end(Active& a) const {
    if (a.point) return;
    const CSpaceChart& chart = chart_of(a);
    const double tx = to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]);
    a.vertex_end = tx > 0.5 * (a.x_lo + a.x_hi) ? 1 : -1;
  }

  // Whether the configuration lies past the end of non-vertical held contact `a`'s edge that is
  // not the vertex it was taken up (or kept) at: its slack holds about that vertex only (the
  // configuration there is on either side of it by rounding). Past the far end the contact
  // ends, as any held contact past its edge: a gear pair's contact on a tooth's base-circle
  // corner ran 9.7e-10 past its far end, inside the next tooth's blocked space, and the nudge
  // found free space only beyond it ("a jammed contact change", session 57).
  bool past_far_end(const Active& a) const {
    if (a.point || !a.at_vertex || a.vertex_end == 0) return false;
    const CSpaceChart& chart = chart_of(a);
    const double tx = to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]);
    return a.vertex_end > 0 ? tx < a.x_lo : tx > a.x_hi;
  }

  // How far the configuration lies past the nearer end of non-vertical held contact `a`'s edge
  // (chart abscissa; 0 inside it, and for a point contact).
  double past_end(const Active& a) const {
    if (a.point) return 0;
    const CSpaceChart& chart = chart_of(a);
    const double tx = to_chart(chart.x_kind, chart.x_half_turn, q[a.xdof]);
    return std::max({0.0, a.x_lo - tx, tx - a.x_hi});
  }

  // Whether the velocity moves the configuration from the end vertex of held contact `a`'s edge
  // back into the edge (the abscissa, or a vertical edge's ordinate, away from that end).
  bool back_along_edge(const Active& a) const {
    const CSpaceChart& chart = chart_of(a);
    const int dof = a.point ? a.ydof : a.xdof;
    if (dof < 0) return false;
    const double tx = a.point ? to_chart(chart.y_kind, chart.y_half_turn, q[dof]) : to_chart(chart.x_kind, chart.x_half_turn, q[dof]);
    const bool at_upper = a.point ? tx > 0.5 * (a.y_lo + a.y_hi) : tx > 0.5 * (a.x_lo + a.x_hi);
    return at_upper ? v[dof] < 0 : v[dof] > 0;
  }

  // The configuration moved onto held contact `a` and the new contacts `candidates` at once
  // (their common vertex), where it lies inside a candidate's blocked side (project_jointly).
  void place_at_vertex(const Active& a, const std::vector<Active>& candidates) {
    std::vector<const Active*> set{&a};
    bool inside = false;
    for (const Active& c : candidates) {
      Vec G;
      double h, gval;
      if (!row(c, q, v, G, h, gval)) return;
      inside = inside || gval < 0;
      set.push_back(&c);
    }
    if (inside) project_jointly(set, false);
  }

  // Whether the rows of the contacts of `set` at the configuration are independent over the
  // free coordinates, mass-weighted (rows scaled to 1: the smallest singular value of W^1/2 G^T
  // at least 1e-6 of the largest, W = M^-1 with 0 for a driven coordinate). Only then can the
  // contacts hold the pair together, each with its own force, and can the configuration be put
  // on all of them at once. A pair with one free coordinate (a fixed or driven part: the
  // driver's coordinate is the time's) has dependent rows at every vertex, as have two curves
  // tangent to each other there. False where a row is not valid.
  bool independent(const std::vector<const Active*>& set) const {
    const Eigen::VectorXd minv = inverse_masses();
    const Eigen::Index m = static_cast<Eigen::Index>(set.size()), n = static_cast<Eigen::Index>(dofs.size());
    Eigen::MatrixXd G(m, n);
    for (Eigen::Index k = 0; k < m; ++k) {
      Vec row_k;
      double h, gval;
      if (!row(*set[static_cast<std::size_t>(k)], q, v, row_k, h, gval)) return false;
      double norm = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        G(k, i) = row_k[static_cast<std::size_t>(i)] * std::sqrt(minv(i));
        norm += G(k, i) * G(k, i);
      }
      if (!(norm > 0)) return false;
      G.row(k) /= std::sqrt(norm);
    }
    const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(G).singularValues();
    return sv.size() == m && sv(m - 1) >= 1e-6 * sv(0);
  }

  // The configuration (and with `velocities` the velocity) moved onto every contact of `set` at
  // once, mass-weighted: Gauss-Newton on g = 0, q -= M^-1 G^T (G M^-1 G^T)^-1 g, three times;
  // v -= M^-1 G^T (G M^-1 G^T)^-1 G v. project_active's one contact at a time converges slowly
  // where two rows of a wedge meet at an angle (the ratchet's: 0.1 % of the velocity left after
  // its three rounds, enough to read as sliding). Only where the rows are independent over the
  // free coordinates (independent()); otherwise nothing moves.
  void project_jointly(const std::vector<const Active*>& set, bool velocities) {
    if (!independent(set)) return;
    const Eigen::VectorXd minv = inverse_masses();
    const Eigen::Index m = static_cast<Eigen::Index>(set.size()), n = static_cast<Eigen::Index>(dofs.size());
    auto rows = [&](Eigen::MatrixXd& G, Eigen::VectorXd& g) {
      G.resize(m, n);
      g.resize(m);
      for (Eigen::Index k = 0; k < m; ++k) {
        Vec row_k;
        double h, gval;
        if (!row(*set[static_cast<std::size_t>(k)], q, v, row_k, h, gval)) return false;
        for (Eigen::Index i = 0; i < n; ++i) G(k, i) = row_k[static_cast<std::size_t>(i)];
        g(k) = gval;
      }
      return true;
    };
    Eigen::MatrixXd G;
    Eigen::VectorXd g;
    for (int iteration = 0; iteration <= 3; ++iteration) {
      if (!rows(G, g)) return;
      const Eigen::MatrixXd WGt = minv.asDiagonal() * G.transpose();
      Eigen::FullPivLU<Eigen::MatrixXd> lu(G * WGt);
      if (lu.rank() < m) return;
      if (iteration == 3) {
        if (!velocities) return;
        const Eigen::VectorXd gv = G * Eigen::Map<const Eigen::VectorXd>(v.data(), n);
        const Eigen::VectorXd dv = WGt * lu.solve(gv);
        for (Eigen::Index i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] -= dv(i);
        return;
      }
      const Eigen::VectorXd dq = WGt * lu.solve(g);
      for (Eigen::Index i = 0; i < n; ++i) q[static_cast<std::size_t>(i)] -= dq(i);
    }
  }

  // The C-space normal of held contact `a` at the configuration, or past its edge's end the
  // last known direction (sigma on the abscissa for a point contact, else on the ordinate).
  Vec normal_or_last(const Active& a) const {
    Vec G;
    double h, gval;
    if (!row(a, q, v, G, h, gval)) {
      G.assign(dofs.size(), 0.0);
      G[a.xdof] = a.point ? a.sigma : 0;
      if (!a.point) G[a.ydof] = a.sigma;
    }
    return G;
  }

  // Ends sustained contact k (event `kind`). An edge end first tries the edge that continues the
  // same contact, then the new contacts at the edge's vertex. The pair is moved off contact
  // space when `nudge` and it holds no other contact; `normal` receives the contact's C-space
  // normal (for a caller that nudges later).
  void release(std::size_t k, SimulationEvent::Kind kind, bool nudge = true, Vec* normal = nullptr) {
    if (kind == SimulationEvent::Kind::edge_end) {
      if (std::optional<Active> next = continuation(active[k])) {
        active[k] = *next;
        project_active();
        return;
      }
      if (vertex_contacts(k)) return;
    }
    Active a = active[k];
    // beyond the edge: the last known direction, from the C-space normal at the edge's end
    Vec G = normal_or_last(a);
    edge_event(a, kind);
    active.erase(active.begin() + static_cast<std::ptrdiff_t>(k));
    if (normal) *normal = G;
    if (nudge && !in_active(a.pair)) nudge_free(a.pair, G);
  }

  // The stick/slip states decided at a step's start (the frictional LCP) replace the held
  // contacts' states; every change is a `stick` or `slip` event with its forces.
  void coulomb_states(const ContactForces& forces, const std::vector<std::size_t>& lifting) {
    for (std::size_t k = 0; k < active.size() && k < forces.state.size(); ++k) {
      int st = forces.state[k];
      if (st == simulation::frictionless) continue;
      if (std::find(lifting.begin(), lifting.end(), k) != lifting.end()) continue;
      Active& a = active[k];
      bool changed = !a.coulomb_known || a.coulomb != st;
      a.coulomb = st;
      a.coulomb_known = true;
      if (!changed) continue;
      edge_event(a, st == simulation::stick ? SimulationEvent::Kind::stick : SimulationEvent::Kind::slip);
      SimulationEvent& e = events.back();
      if (!a.edge.valid()) e.features = labels(a.pair, a.features);
      e.normal_force = forces.normal[k] / force_scale;
      e.friction_force = forces.tangential[k] / force_scale;
      e.slip_direction = st == simulation::stick ? 0 : st;
    }
  }

  // Sticking contacts keep no relative tangential velocity: after each step the velocities are
  // projected (mass-weighted) on T v = 0, as the normal rows are by project_active.
  void project_sticking() {
    for (int iteration = 0; iteration < 3; ++iteration)
      for (const Active& a : active) {
        if (!a.coulomb_known || a.coulomb != simulation::stick) continue;
        Vec G;
        double h, gval;
        if (!row(a, q, v, G, h, gval)) continue;
        simulation::Friction c = friction_of(a.pair, features_of(a), G, q);
        if (!c.on) continue;
        double A = 0, tv = 0;
        for (std::size_t i = 0; i < dofs.size(); ++i) {
          if (!dofs[i].driven) A += c.T(i) * c.T(i) / dofs[i].inertia;
          tv += c.T(i) * v[i];
        }
        if (A == 0) continue;
        for (std::size_t i = 0; i < dofs.size(); ++i)
          if (!dofs[i].driven) v[i] -= c.T(i) / dofs[i].inertia * tv / A;
      }
  }

  // The accelerations `a` at a step's start (q, v) must be finite: where they are not, no trial
  // step of any length can be taken and the run ended with "the integrator's step size
  // underflows" or, before session 59, "the integration produced a non-finite state (a singular
  // contact constraint?)" (geneva-drive.json with its driver at 1e50 … 1e152 rad/s). Throws
  // naming the parts whose acceleration is not finite, their speeds and the held contacts.
  void not_finite_accelerations(const Vec& qs, const Vec& vs, const Vec& a) const {
    if (std::all_of(a.begin(), a.end(), [](double value) { return std::isfinite(value); })) return;
    std::ostringstream out;
    out << "simulation: at t = " << published_time(t) << " " << time_unit << " the acceleration of";
    const char* separator = " ";
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (std::isfinite(a[i])) continue;
      out << separator << "part '" << model.parts[dofs[i].part].name << "' (" << model.parts[dofs[i].part].pointer
          << ", moving at " << vs[i] * time_scale
          << (dofs[i].rotation ? " rad/" : " mm/") << time_unit << ")";
      separator = ", ";
    }
    out << " is not finite";
    const auto finite = [](const Vec& x) { return std::all_of(x.begin(), x.end(), [](double e) { return std::isfinite(e); }); };
    if (!finite(qs) || !finite(vs)) {
      // the state itself: an event at this time (an impact's impulse, a projection) made it
      out << ": the state itself is not finite (";
      const char* comma = "";
      for (std::size_t i = 0; i < dofs.size(); ++i)
        if (!std::isfinite(qs[i]) || !std::isfinite(vs[i])) {
          out << comma << "part '" << model.parts[dofs[i].part].name << "' (" << model.parts[dofs[i].part].pointer
              << "/dynamics) at " << qs[i] << (dofs[i].rotation ? " rad" : " mm")
              << " moving at " << vs[i] * time_scale << (dofs[i].rotation ? " rad/" : " mm/") << time_unit;
          comma = ", ";
        }
      out << ")";
      const auto at_time = std::find_if(events.rbegin(), events.rend(), [&](const SimulationEvent& e) {
        return e.time != published_time(t);
      });
      if (at_time != events.rbegin()) {
        const SimulationEvent& e = *std::prev(at_time);
        out << " after the " << to_string(e.kind) << " of pair (" << e.first_part << ", " << e.second_part << ")";
        // the pair's pointer and its coefficients (session 63, hunt63: an impact with friction
        // 1.8e308 left the velocities NaN, and the message named no place of the data)
        for (const PairSpec& pair : model.pairs) {
          const std::string& a = model.parts[pair.first].name;
          const std::string& b = model.parts[pair.second].name;
          if (!((a == e.first_part && b == e.second_part) || (a == e.second_part && b == e.first_part))) continue;
          out << " (" << pair.pointer;
          if (pair.friction) out << ", friction " << to_d(*pair.friction);
          if (pair.kinetic_friction) out << ", kinetic " << to_d(*pair.kinetic_friction);
          if (pair.restitution) out << ", restitution " << to_d(*pair.restitution);
          out << ")";
          break;
        }
        if (!e.features.empty()) out << " [" << e.features.front() << "]";
        if (e.kind == SimulationEvent::Kind::impact)
          out << " at normal speed " << e.normal_speed_before << " mm/" << time_unit << " (impulse " << e.impulse << ")";
        out << " at this time";
      }
      for (std::size_t i = 0; i < dofs.size(); ++i)
        if (dofs[i].driven)
          out << "; driver '" << model.parts[dofs[i].part].name << "' turns at " << std::abs(vs[i]) * time_scale << " "
              << (dofs[i].rotation ? "rad/" : "mm/") << time_unit;
      throw NumericError(out.str());
    }
    Vec Q;
    forces(t, qs, vs, Q);
    const bool loads = std::any_of(Q.begin(), Q.end(), [](double value) { return !std::isfinite(value); });
    std::vector<FeatureId> features;
    std::string held;
    for (const Active& k : active) {
      features_of(k, features);
      held += (held.empty() ? "" : "; ") + pair_name(k.pair);
      if (!features.empty()) held += " [" + spaces[k.pair]->feature_pair(features.front()).label + "]";
    }
    if (loads) out << ": the loads on the parts (springs, dampers, torques, forces) are not finite";
    else if (!held.empty()) out << ": the loads are finite; the forces of the held contacts (" << held << ") are not";
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (dofs[i].driven)
        out << "; driver '" << model.parts[dofs[i].part].name << "' turns at " << std::abs(vs[i]) * time_scale << " "
            << (dofs[i].rotation ? "rad/" : "mm/") << time_unit;
    throw NumericError(out.str());
  }

  void step(double t_limit) {
    if (++steps > options.max_steps) throw SimulationStepBudget("simulation: more than max_steps steps");
    frames.clear();
    using namespace boost::numeric::odeint;
    Vec x = pack();
    Vec q0 = q, v0 = v, a0, l0;
    // the contact forces of all active contacts at once (the LCP): the contacts it leaves
    // without force and with a separating normal acceleration lift off, together
    std::vector<std::size_t> lifting;
    ContactForces start;
    bool held = !active.empty() && accelerations(t, q0, v0, a0, l0, &lifting, &start);
    if (held && start.friction) coulomb_states(start, lifting);
    if (held && !lifting.empty()) {
      std::vector<std::pair<std::size_t, Vec>> gone;
      for (std::size_t j = lifting.size(); j-- > 0;) {
        std::size_t k = lifting[j];
        gone.emplace_back(active[k].pair, Vec());
        release(k, SimulationEvent::Kind::lift_off, false, &gone.back().second);
      }
      project_active();
      for (auto& [pair, G] : gone)
        if (!in_active(pair)) nudge_free(pair, G);
      return;
    }
    accelerations(t, q0, v0, a0, l0);
    not_finite_accelerations(q0, v0, a0);
    double max_step = options.max_step > 0 ? options.max_step * time_scale : std::numeric_limits<double>::infinity();
    // a speed profile's next point ends the step (its driver's motion is one quadratic per step)
    double breakpoint = next_breakpoint(t);
    bool to_breakpoint = std::isfinite(breakpoint) && breakpoint <= t_limit;
    if (to_breakpoint) t_limit = breakpoint;
    double remaining = t_limit - t;
    if (dt <= 0) dt = std::min({max_step, remaining, 1e-3});
    dt = std::min({dt, max_step, remaining});
    auto stepper = make_controlled(accuracy, accuracy, runge_kutta_dopri5<Vec>());
    auto sys = [this](const Vec& state, Vec& d, double time) { rhs(state, d, time); };
    double t1 = t;
    Vec x1 = x;
    bool overflowed = false;   // the last trial rejected for a non-finite state
    for (int attempt = 0;; ++attempt) {
      x1 = x;
      t1 = t;
      double trial = dt;
      const double tried = dt;
      overflowed = false;
      if (stepper.try_step(sys, x1, t1, trial) == success) {
        // odeint accepts a trial whose error estimate is not a number (a comparison with NaN is
        // false): a first step of 1e-3 s with a driver at 1e100 rad/s overflowed within its
        // stages and was taken ("the integration produced a non-finite state", session 59). A
        // non-finite result is a rejected trial, retried at a quarter of its length.
        if (std::all_of(x1.begin(), x1.end(), [](double value) { return std::isfinite(value); })) {
          dt = std::min(trial, max_step);
          unresolved_trial = t1 == t ? tried : 0;
          break;
        }
        trial = dt / 4;
        overflowed = true;
      }
      dt = trial;
      if (attempt > 200 || dt < 1e-300) {
        std::ostringstream out;
        out << "simulation: at t = " << published_time(t) << " " << time_unit << " the integrator's step size underflows";
        if (overflowed)
          out << ": every trial step down to " << dt * 4 / time_scale << " " << time_unit
              << " gave a non-finite state (accelerations or velocities beyond the doubles' range)";
        if (overflowed) {
          // the parts and their loads' place in the file (session 64, hunt64: the scotch yoke's
          // crank at a torque of 1e300 N mm named no place of the data)
          const char* separator = "; the moving parts: ";
          for (std::size_t i : free_dofs) {
            out << separator << "part '" << model.parts[dofs[i].part].name << "' (" << model.parts[dofs[i].part].pointer
                << "/dynamics, moving at " << v[i] * time_scale << (dofs[i].rotation ? " rad/" : " mm/") << time_unit
                << ")";
            separator = ", ";
          }
        }
        throw NumericError(out.str());
      }
    }
    if (t1 > t_limit) t1 = t_limit;
    if (to_breakpoint && t_limit - t1 <= 4 * std::numeric_limits<double>::epsilon() * std::abs(t_limit)) t1 = t_limit;
    for (double value : x1)
      if (!std::isfinite(value)) {
        std::ostringstream out;
        out << "simulation: at t = " << published_time(t) << " " << time_unit
            << " the integration produced a non-finite state (a singular contact constraint?)";
        throw NumericError(out.str());
      }
    Vec q1, v1, a1, l1;
    unpack(t1, x1, q1, v1);
    accelerations(t1, q1, v1, a1, l1);
    StepPath path = make_path(t, q0, v0, a0, t1, q1, v1, a1);
    double u_end = 1;
    enum class Cut { none, lift_off, edge_end, coulomb } cut = Cut::none;
    std::size_t cut_active = 0;
    // sustained contacts: the multiplier's sign and the edge's extent, by bisection on the path
    // (and the Coulomb conditions of the contacts' states, except for a contact whose condition
    // the step's held motion already violates at its start: the step-start LCP and the held
    // (bilateral) forces can differ by round-off where a contact is at its limit, and a change
    // present at u = 0 would cut every step there)
    std::vector<bool> coulomb_ignored;
    // (each probe also gives every held condition's continuous indicator — each edge's room,
    // each multiplier, each Coulomb condition's slack — which only proposes the cut search's
    // next probe; the returned kind decides. Indicator k: contact k's room; n + k: its
    // multiplier; 2n + k: its Coulomb condition; 3n: none, the forces not computed)
    auto violated = [&](double u) {
      const std::size_t n = active.size();
      simulation::CutProbe p;
      p.margins.assign(3 * n + 1, std::numeric_limits<double>::quiet_NaN());
      auto found = [&p](int kind, std::size_t which, std::size_t indicator) {
        p.kind = kind;
        p.which = which;
        p.indicator = indicator;
        return p;
      };
      Vec qs, vs, acc, lambda;
      path.at(u, qs, vs);
      // the prescribed parts where their law puts them, as the state taken at a cut will have
      // them (sync_driven): the path's polynomial of a driver differs from its law by rounding,
      // which could put the cut's state past the edge's end (and its slack) the bisection found
      for (std::size_t i = 0; i < dofs.size(); ++i)
        if (dofs[i].driven) {
          double ad;
          driver_law(dofs[i], path.t0 + u * path.h, qs[i], vs[i], ad);
        }
      for (std::size_t k = 0; k < n; ++k) {
        Vec G;
        double h, gval;
        double room = edge_room(active[k], qs);
        if (!row(active[k], qs, vs, G, h, gval)) {
          // (failed for another reason than the end: no indicator)
          if (room < 0) p.margins[k] = room;
          return found(2, k, k);
        }
        p.margins[k] = room;
      }
      ContactForces cf;
      if (!accelerations(path.t0 + u * path.h, qs, vs, acc, lambda, nullptr, &cf))
        return found(2, 0, 3 * n);   // (no contact named, as before)
      for (std::size_t k = 0; k < lambda.size(); ++k) {
        if (k < n) p.margins[n + k] = lambda[k];
        if (cf.force_sign[k] < 0) return found(1, k, n + k);   // exact (held_conditions)
      }
      if (cf.friction && start.friction)
        for (std::size_t k = 0; k < cf.state.size() && k < start.vt.size(); ++k) {
          if (k < coulomb_ignored.size() && coulomb_ignored[k]) continue;
          int st = cf.state[k];
          if (st == simulation::stick) {
            // stick -> slip: the friction force beyond the static limit, exactly (held_conditions;
            // the margin only proposes probes)
            double limit = cf.mu_static[k] * cf.normal[k];
            if (k < n) p.margins[2 * n + k] = limit - std::abs(cf.tangential[k]);
            if (cf.beyond_static[k]) return found(3, k, 2 * n + k);
          } else if (st == simulation::slip_positive || st == simulation::slip_negative) {
            // slip -> stick (or reversal): the relative tangential velocity crosses zero
            double threshold = std::min(0.0, st * start.vt[k]);
            if (k < n) p.margins[2 * n + k] = st * cf.vt[k] - threshold;
            if (st * cf.vt[k] < threshold) return found(3, k, 2 * n + k);
          }
        }
      return p;
    };
    if (!active.empty()) {
      strict_rows = true;
      struct Reset {
        bool& flag;
        ~Reset() { flag = false; }
      } reset{strict_rows};
      std::size_t which = 0;
      coulomb_ignored.assign(active.size(), false);
      // The motion may leave a held contact's edge and come back to it within one step (a
      // driver turning once in a long step along a locking arc): the edge's extent is watched
      // along the whole path, not only at its end (edge_watch_end).
      double u_probe = 1;
      for (const Active& a : active) u_probe = std::min(u_probe, edge_watch_end(a, path));
      for (std::size_t pass = 0; pass <= active.size(); ++pass) {
        simulation::CutProbe upper = violated(u_probe);
        if (upper.kind == 0) {
          // the path came near an edge's end and did not pass it: the step ends there (no
          // event) and the next one watches on from that state
          if (u_probe < 1) u_end = u_probe;
          break;
        }
        // the change bracketed to 2^-50 of the probed path, as the former bisection's 50
        // halvings did (cut_search.hpp)
        simulation::CutBracket bracket =
            simulation::bracket_cut(u_probe, upper, std::ldexp(u_probe, -50), violated);
        simulation::cut_probes() += static_cast<std::size_t>(bracket.probes);
        double lo = bracket.lo;
        int kind = bracket.at_hi.kind;
        which = bracket.at_hi.which;
        if (kind == 3 && (lo == 0 || path.t0 + lo * path.h == path.t0) && which < coulomb_ignored.size()) {
          // a Coulomb change right at the step's start: not a change along the step (see above).
          // Also one bracketed so close to the start that the cut's time is the start's time
          // (lo h below half a unit in the last place of t): a cut there would leave the time
          // where it was, and the next step would find the same change again — the scotch yoke
          // at 1e-6 from 0.39554 s, a slip change at u = 4.4e-16 of every step, without end
          // (docs/simulation.md, "Session 32").
          coulomb_ignored[which] = true;
          continue;
        }
        u_end = lo;
        cut = kind == 1 ? Cut::lift_off : kind == 3 ? Cut::coulomb : Cut::edge_end;
        cut_active = which;
        break;
      }
    }
    // every free pair's motion, certified
    std::vector<ContactRow> hits;
    double u_hit = u_end, u_hit_upper = u_end;
    double u_out = std::numeric_limits<double>::infinity();
    std::size_t out_pair = 0;
    std::vector<std::pair<std::size_t, MotionCrossing>> crossings;
    CrossingOptions crossing_options;
    crossing_options.resolution_bits = options.crossing_bits;
    // The free pairs' queries: complete, or with crossing_limits() side by side with a limit
    // and resumed where they might matter (simulation/crossing_sweep.hpp): the same crossings,
    // rows and ends; a pair whose query stayed stopped is certainly not among them.
    std::vector<MotionCrossing> answers(spaces.size());
    std::vector<char> limited(spaces.size(), 0);
    if (!simulation::crossing_limits()) {
      for (std::size_t pair = 0; pair < spaces.size(); ++pair)
        if (spaces[pair] && !in_active(pair))
          answers[pair] = spaces[pair]->first_crossing(step_motion(pair, path, u_end), crossing_options);
    } else {
      std::vector<const CSpace*> asked(spaces.size(), nullptr);
      for (std::size_t pair = 0; pair < spaces.size(); ++pair)
        if (spaces[pair] && !in_active(pair)) {
          asked[pair] = spaces[pair].get();
          step_motion(pair, path, u_end);
        }
      // (the pairs not asked keep older paths there: sweep_crossings reads only the asked ones')
      simulation::SweptCrossings swept = simulation::sweep_crossings(asked, step_motions_, crossing_options, u_end);
      simulation::limited_queries() += swept.limited;
      simulation::requeried_limits() += swept.resumed;
      answers = std::move(swept.answers);
      limited = std::move(swept.stopped);
    }
    for (std::size_t pair = 0; pair < spaces.size(); ++pair) {
      if (!spaces[pair] || in_active(pair) || limited[pair]) continue;
      MotionCrossing c = std::move(answers[pair]);
      if (c.status == CrossingStatus::none) continue;
      if (c.status == CrossingStatus::outside_region) {
        // leaving the built space is an error only when it comes first; its bracket is
        // conservative, so the step is first shortened to its lower end (below)
        if (to_d(c.u_lower) < u_out) {
          u_out = to_d(c.u_lower);
          out_pair = pair;
        }
        continue;
      }
      if (c.status == CrossingStatus::starts_in_contact) {
        c.u_lower = c.u_upper = 0;
      }
      crossings.emplace_back(pair, c);
      if (to_d(c.u_lower) < u_hit) {
        u_hit = to_d(c.u_lower);
        u_hit_upper = to_d(c.u_upper);
      }
    }
    if (u_out <= u_hit && (crossings.empty() || u_out < u_hit)) {
      // no contact before the pair may leave its built space: at the very start of the step
      // that is the error; otherwise the step ends just before (no event) and the next step
      // looks again from there
      if (u_out * path.h <= 1e-12 * (1 + std::abs(path.t0))) outside(out_pair, path.t0 + u_out * path.h);
      path.at(u_out, q, v);
      t = path.t0 + u_out * path.h;
      sync_driven();
      dt = u_out * path.h;
      project_active();
      return;
    }
    if (!crossings.empty() && u_hit <= u_end) {
      // the earliest crossing, and every other one whose bracket meets it (simultaneous)
      path.at(u_hit, q, v);
      t = path.t0 + u_hit * path.h;
      sync_driven();
      std::vector<ContactRow> rows;
      for (auto& [pair, c] : crossings) {
        if (to_d(c.u_lower) > u_hit_upper) continue;
        ContactRow r;
        r.pair = pair;
        r.crossing = true;
        r.hit = c;
        r.restitution = model.pairs[pair].restitution ? to_d(*model.pairs[pair].restitution) : 0.0;
        r.g = physical_row(pair, c, q);
        r.features = c.features;
        r.graze = c.grazing && simulation::vertex_pass(*spaces[pair], c, step_motions_[pair]) ==
                                   simulation::VertexPass::graze;
        if (spaces[pair]->dimension() == 1) line_row(r, c, step_motions_[pair]);
        rows.push_back(r);
      }
      project_active();
      const std::size_t events_before = events.size();
      handle_contacts(rows);
      // A step that struck nothing at its very start: every event an impact without impulse
      // (a departing motion the query reports as a grazing touch, within its resolution of a
      // curve, at [0, u_upper]), at the time where the step before ended with such a touch: the
      // state has not changed, and the next step would ask the same query. The ratchet's tooth
      // tip leaving the pawl's nose corner at 424 mm/s repeated it without end (docs/simulation.md,
      // "The endless corner touch"). The touch is already an event: the state moves on along the
      // path to the bracket's end u_upper (the motion is certified free before u_lower = 0 and
      // within the touch's resolution up to u_upper), this step's events (the same touch again)
      // are dropped, and the pairs are certified free there (nudge_free). A bracket that ends
      // where it starts cannot move the state: an error.
      const bool touch_only = std::all_of(events.begin() + static_cast<std::ptrdiff_t>(events_before), events.end(),
                                          [](const SimulationEvent& e) {
                                            return e.kind == SimulationEvent::Kind::impact && e.impulse == 0 &&
                                                   e.tangential_impulse == 0;
                                          });
      const bool again = touch_only && t == path.t0 && last_touch_end == path.t0;
      last_touch_end = touch_only ? t : std::numeric_limits<double>::quiet_NaN();
      if (!again) return;
      ++simulation::touch_guard_moves();
      events.resize(events_before);
      path.at(u_hit_upper, q, v);
      t = path.t0 + u_hit_upper * path.h;
      if (!(t > path.t0)) {
        std::ostringstream out;
        out << "simulation: at t = " << published_time(t) << " " << time_unit << " " << pair_name(rows.front().pair)
            << " touches again and again without an impulse, and its crossing bracket does not move the time on";
        throw NumericError(out.str());
      }
      sync_driven();
      project_active();
      for (const ContactRow& r : rows)
        if (r.crossing && !in_active(r.pair)) nudge_free(r.pair, r.g);
      return;
    }
    path.at(u_end, q, v);
    t = u_end == 1 ? t1 : path.t0 + u_end * path.h;
    if (u_end == 1) {
      unpack(t1, x1, q, v);
    } else {
      sync_driven();
    }
    // a contact cut at its edge's end is at the end vertex to the bisection's resolution, and
    // the prescribed parts just moved to their law (sync_driven) may put it past the vertex by
    // rounding: it is projected (and continued or released) with the rows of that vertex, as a
    // contact taken up at a vertex is. Before, its row failed there, the projection skipped it,
    // and the state kept the step's drift off the curve (the Geneva drive at accuracy 1e-3:
    // 0.043 rad into slot 2's wall L at 1.62378 s, from where nudge_free found no free state).
    if (cut == Cut::edge_end) {
      active[cut_active].at_vertex = true;
      mark_vertex_end(active[cut_active]);
    }
    const Vec cut_q = q;
    project_active();
    if (cut == Cut::edge_end && abscissa_shift(active[cut_active], cut_q) > slack_of(active[cut_active])) {
      q = cut_q;
      onto_curve_at_abscissa(active[cut_active]);
      project_active();
    }
    project_sticking();
    // Cut::coulomb: the step ends where a contact's stick/slip state changes; the next step's
    // frictional LCP decides its new state (coulomb_states)
    if (cut == Cut::lift_off) release(cut_active, SimulationEvent::Kind::lift_off);
    else if (cut == Cut::edge_end) release(cut_active, SimulationEvent::Kind::edge_end);
  }

  // Every pair in sustained contact is left certainly free: its configuration, projected on
  // its contact curve(s) in doubles, lies on either side of them by rounding; it is moved by a
  // few units in the last place along M^-1 (sum of its contacts' normals) until the certified
  // point query says free (nudge_free). So no state is ever inside blocked space.
  void free_active() {
    // a held contact whose row cannot be evaluated here any more has left its edge (the step's
    // projection or rounding moved it past the edge's end, or the motion crept up to an end the
    // step's watch did not cut at: the escapement at -675 N.mm, t = 0.5543 s, the impulse pin
    // on fork slot wall R with steps shrinking to 1e-8 s). It ends as at a watched edge end:
    // continued on the next edge, taken up by the vertex's contacts, or released and nudged
    // along its last normal. Before, its pair was nudged along a zero direction: "cannot be
    // moved off its contact".
    for (std::size_t k = active.size(); k-- > 0;) {
      if (k >= active.size()) continue;
      Vec G;
      double h, gval;
      if (!row(active[k], q, v, G, h, gval) || (!active[k].at_vertex && past_end(active[k]) > 0) || past_far_end(active[k]))
        release(k, SimulationEvent::Kind::edge_end);
    }
    for (std::size_t pair = 0; pair < spaces.size(); ++pair) {
      if (!spaces[pair] || !in_active(pair)) continue;
      Vec sum;
      nudge_normal(pair, sum);   // the sum of its held contacts' rows, each scaled to 1
      nudge_free({{pair, sum}}, held_rows(pair));
    }
  }

  // A run of steps that do not move the time on ends: a contact change repeats without
  // progress (the endless corner touch was one). Lift-offs, edge ends and contact changes at
  // one time are a handful of steps; 10 000 in a row is an error.
  static constexpr std::size_t max_steps_in_place = 10000;

  void step_and_free(double t_limit) {
    const double before = t;
    step(t_limit);
    free_active();
    steps_in_place = t > before ? 0 : steps_in_place + 1;
    if (steps_in_place >= max_steps_in_place) {
      std::ostringstream out;
      out << "simulation: at t = " << published_time(t) << " " << time_unit << " " << steps_in_place
          << " steps in a row did not move the time on";
      if (unresolved_trial > 0) {
        // the integrator's error control, not a contact change: its accepted step is shorter
        // than half a unit in the last place of t, and a longer one fails the accuracy
        const double ulp = std::nextafter(t, std::numeric_limits<double>::infinity()) - t;
        out << ": the integrator accepts only steps of about " << unresolved_trial / time_scale << " " << time_unit
            << " here at accuracy " << accuracy << ", shorter than half the resolution of the time ("
            << ulp / time_scale << " " << time_unit
            << ", one unit in the last place of t), so no step moves the time; another --accuracy may pass";
      } else {
        out << " (a contact change that repeats without progress)";
      }
      throw NumericError(out.str());
    }
  }

  std::vector<SimulationContact> contacts() const {
    std::vector<SimulationContact> out;
    Vec acc, lambda;
    std::vector<std::size_t> lifting;
    ContactForces forces;
    if (active.empty() || !accelerations(t, q, v, acc, lambda, &lifting, &forces)) return out;
    for (std::size_t k = 0; k < active.size(); ++k) {
      const Active& a = active[k];
      SimulationContact c;
      c.pair = a.pair;
      c.edge = a.edge;
      if (a.edge.valid())
        for (std::size_t f : spaces[a.pair]->edge(a.edge).curves)
          c.features.push_back(spaces[a.pair]->feature_pair(FeatureId(f)).label);
      c.force = lambda[k] / force_scale;
      if (forces.friction && k < forces.state.size() && forces.state[k] != simulation::frictionless) {
        c.normal_force = forces.normal[k] / force_scale;
        c.friction_force = forces.tangential[k] / force_scale;
        c.sticking = forces.state[k] == simulation::stick;
      }
      out.push_back(c);
    }
    return out;
  }

  void publish() {
    public_state.time = published_time(t);
    public_state.position.assign(model.parts.size(), 0.0);
    public_state.velocity.assign(model.parts.size(), 0.0);
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      public_state.position[dofs[i].part] = absolute(i);
      public_state.velocity[dofs[i].part] = v[i] * time_scale;
    }
  }
};

// ------------------------------------------------------------------ construction

Simulation::Simulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

// The simulator holds the parts' initial coordinates in doubles: an exact initial coordinate
// beyond the doubles' range (an unlimited crank at "angle": 1e400, valid for the exact commands)
// became infinity, and GMP's mpq_set_d(inf) killed the process with SIGFPE (session 43). Refused
// at its pointer before anything runs; the dynamics data itself is checked by the reader.
void check_simulator_range(const Model& model) {
  static const Rational largest(std::numeric_limits<double>::max());
  for (const Part& part : model.parts) {
    if (part.motion.kind == Motion::Kind::fixed) continue;
    const std::pair<const char*, const Rational*> coordinates[] = {
        {"angle", &part.initial.angle}, {"offset", &part.initial.offset}, {"x", &part.initial.x}, {"y", &part.initial.y}};
    for (const auto& [key, value] : coordinates)
      if (abs(*value) > largest)
        throw ModelError(part.pointer + "/initial/" + key,
                         "the initial " + std::string(key) + " of part '" + part.name +
                             "' is too large for the simulator, which holds coordinates in doubles (magnitude at most "
                             "1.7976931348623157e+308)");
  }
}

// A rotating driver at speed w moves a point of its part at distance r from the pivot with the
// centripetal acceleration w^2 r, and whatever it pushes takes an acceleration of that size:
// beyond the doubles' range (1.8e308 mm/s^2) the first step's state was not finite and the run
// ended with "the integration produced a non-finite state (a singular contact constraint?)" at
// t = 0 (cam-drive.json at 1e300 rad/s), or a jammed contact change (geneva-drive.json at
// 1e300 rad/s; session 58's note). Refused before anything is built, naming the driver, its
// speed, the reach and the acceleration (docs/simulation.md, "A driver too fast for the doubles").
// `ts`: seconds per time unit `time_unit`. The reach is the farthest vertex, or arc centre plus radius, of
// the part's loops from its pivot.
static double rotation_reach(const Part& part) {
  double reach = 0;
  const double px = part.motion.pivot.x.get_d(), py = part.motion.pivot.y.get_d();
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      reach = std::max(reach, std::hypot(edge.source.x.get_d() - px, edge.source.y.get_d() - py));
      if (edge.is_arc())
        reach = std::max(reach, std::hypot(edge.center.x.get_d() - px, edge.center.y.get_d() - py) +
                                    std::sqrt(edge.radius_squared.get_d()));
    }
  return reach;
}

// The same bound on a freely rotating part's initial angle rate (session 61, hunt61): the
// bouncing bar started at 1e300 or 1.8e308 rad/s struck its stop at a normal speed of 2e302 mm/s
// or infinity, and the run ended with "the state itself is not finite (... -nan rad/s)" at
// t = 0 (exit 3, no pointer). Refused at the velocity's pointer with the largest rate allowed.
static void check_rate_reach(const Model& model, const SimulationSpec::Velocity& velocity, double ts,
                             const std::string& time_unit) {
  const Part& part = model.parts.at(velocity.part);
  if (part.motion.kind != Motion::Kind::rotation) return;
  const double speed = std::abs(velocity.value.get_d()), reach = rotation_reach(part);
  const double rate = speed / ts;
  if (std::isfinite(rate * rate * reach) || !(reach > 0)) return;
  const long double wide = static_cast<long double>(rate) * rate * reach;   // (x86: range to 1e4932)
  std::ostringstream text;
  text << "the initial angle rate " << speed << " rad/" << time_unit << " of rotating part '" << part.name
       << "': its point " << reach << " mm from the pivot accelerates at " << rate << "^2 rad^2/s^2 x " << reach
       << " mm = " << wide << " mm/s^2, beyond the doubles' range (1.8e308) the simulator integrates in: give at most "
       << std::sqrt(std::numeric_limits<double>::max() / reach) * ts << " rad/" << time_unit;
  throw ModelError(velocity.pointer, text.str());
}

static void check_driver_reach(const Model& model, const SimulationSpec::Driver& driver, double ts,
                               const std::string& time_unit) {
  const Part& part = model.parts.at(driver.part);
  if (part.motion.kind != Motion::Kind::rotation) return;
  double speed = std::abs(driver.speed.get_d());   // rad per time unit
  for (const auto& [time, value] : driver.profile) speed = std::max(speed, std::abs(value.get_d()));
  const double reach = rotation_reach(part);
  const double rate = speed / ts, acceleration = rate * rate * reach;   // mm/s^2
  if (std::isfinite(acceleration) || !(reach > 0)) return;
  const long double wide = static_cast<long double>(rate) * rate * reach;   // (x86: range to 1e4932)
  std::ostringstream text;
  text << "driver '" << part.name << "' turns at " << speed << " rad/" << time_unit << ": its point " << reach
       << " mm from the pivot accelerates at " << rate << "^2 rad^2/s^2 x " << reach << " mm = " << wide
       << " mm/s^2, beyond the doubles' range (1.8e308), and so would a part it pushes; the simulator "
          "integrates in doubles: give a driver speed of at most "
       << std::sqrt(std::numeric_limits<double>::max() / reach) * ts << " rad/" << time_unit;
  throw ModelError(driver.profile.empty() ? driver.pointer + "/speed" : driver.pointer + "/profile", text.str());
}

Simulation Simulation::create(const Model& model, const SimulationOptions& options) {
  check_simulator_range(model);
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  SimulationSpec spec = simulation::start_simulation(s, model, options);
  s.accuracy = simulation::simulation_accuracy(options, spec);
  const double seconds_per = s.time_scale;
  // a fast mechanism integrates in a time unit of 2^-e s (time_rescale.hpp): the time, speed,
  // force and gravity conversions at the boundary scaled by powers of two
  const int e = simulation::time_exponent(simulation::fastest_speed(spec, seconds_per));
  s.time_scale = std::ldexp(s.time_scale, e);
  s.force_scale = std::ldexp(s.force_scale, -2 * e);
  s.g[0] = std::ldexp(s.g[0], -2 * e);
  s.g[1] = std::ldexp(s.g[1], -2 * e);
  const double fs = s.force_scale, ts = s.time_scale;

  s.part_dof.assign(model.parts.size(), -1);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    auto kind = part.motion.kind;
    if (kind == Motion::Kind::fixed) continue;
    if (kind != Motion::Kind::rotation && kind != Motion::Kind::translation)
      throw ModelError(part.motion.pointer, "part '" + part.name +
                                                "': the simulator moves rotating and translating parts only");
    Dof d;
    d.part = p;
    d.rotation = kind == Motion::Kind::rotation;
    d.pivot[0] = to_d(part.motion.pivot.x);
    d.pivot[1] = to_d(part.motion.pivot.y);
    d.dir[0] = to_d(part.motion.direction.x);
    d.dir[1] = to_d(part.motion.direction.y);
    d.q0 = to_d(d.rotation ? part.initial.angle : part.initial.offset);
    if (part.dynamics) {
      const Dynamics& dyn = *part.dynamics;
      if (dyn.mass) d.mass = to_d(*dyn.mass);
      d.inertia = d.rotation ? (dyn.moment_of_inertia ? to_d(*dyn.moment_of_inertia) : 0) : d.mass;
      if (d.rotation && dyn.linear_spring)
        throw ModelError(part.pointer + "/dynamics/linear_spring",
                         "part '" + part.name + "' rotates: give it a torsional_spring (or a spring between two parts)");
      if (!d.rotation && dyn.torsional_spring)
        throw ModelError(part.pointer + "/dynamics/torsional_spring",
                         "part '" + part.name + "' translates: give it a linear_spring");
      if (!d.rotation && dyn.torque)
        throw ModelError(part.pointer + "/dynamics/torque", "part '" + part.name + "' translates: a torque cannot move it");
      const auto& spring = d.rotation ? dyn.torsional_spring : dyn.linear_spring;
      if (spring) {
        d.stiffness = to_d(spring->stiffness) * fs;
        d.rest = to_d(spring->rest);
      }
      if (dyn.torque) d.load = to_d(*dyn.torque) * fs;
      if (dyn.force) {
        d.force[0] = to_d(dyn.force->x) * fs;
        d.force[1] = to_d(dyn.force->y) * fs;
      }
      if (dyn.damping) d.damping = to_d(*dyn.damping) * fs * ts;
    }
    s.part_dof[p] = static_cast<int>(s.dofs.size());
    s.dofs.push_back(d);
  }
  for (const auto& driver : spec.drivers) {
    Dof& d = s.dofs[s.part_dof[driver.part]];
    d.driven = true;
    d.speed = to_d(driver.speed) / ts;
    double position = 0;
    for (std::size_t k = 0; k < driver.profile.size(); ++k) {
      double time = to_d(driver.profile[k].first) * ts, speed = to_d(driver.profile[k].second) / ts;
      if (k > 0) position += 0.5 * (speed + d.profile_v.back()) * (time - d.profile_t.back());
      d.profile_t.push_back(time);
      d.profile_v.push_back(speed);
      d.profile_q.push_back(position);
    }
  }
  for (const auto& driver : spec.drivers) check_driver_reach(model, driver, seconds_per, s.time_unit);
  for (const auto& velocity : spec.velocities) check_rate_reach(model, velocity, seconds_per, s.time_unit);
  for (const auto& c : spec.centers_of_mass) {
    Dof& d = s.dofs[s.part_dof[c.part]];
    d.com[0] = to_d(c.at.x) - d.pivot[0];
    d.com[1] = to_d(c.at.y) - d.pivot[1];
  }
  for (const Dof& d : s.dofs)
    if (!d.driven && !(d.inertia > 0)) {
      const Part& part = model.parts[d.part];
      throw ModelError(part.pointer, "part '" + part.name + "' moves freely but has no " +
                                         (d.rotation ? "moment_of_inertia" : "mass") +
                                         " (give dynamics data, or make it a driver in \"simulation\"/\"drivers\")");
    }
  for (const auto& k : spec.couplings) {
    Coupling c;
    c.first = k.first;
    c.second = k.second;
    c.p1[0] = to_d(k.first_point.x);
    c.p1[1] = to_d(k.first_point.y);
    c.p2[0] = to_d(k.second_point.x);
    c.p2[1] = to_d(k.second_point.y);
    c.k = to_d(k.stiffness) * fs;
    c.rest = to_d(k.rest_length);
    c.c = to_d(k.damping) * fs * ts;
    s.couplings.push_back(c);
  }
  s.q.resize(s.dofs.size());
  s.v.assign(s.dofs.size(), 0.0);
  for (std::size_t i = 0; i < s.dofs.size(); ++i) {
    s.q[i] = s.dofs[i].q0;
    if (s.dofs[i].driven) s.v[i] = s.dofs[i].speed;
    else s.free_dofs.push_back(i);
  }
  for (const auto& velocity : spec.velocities) s.v[s.part_dof[velocity.part]] = to_d(velocity.value) / ts;
  // the coordinates whose whole turns may be taken out (Impl::wrap_turns)
  s.time_rebase = std::all_of(s.dofs.begin(), s.dofs.end(), [](const Dof& d) { return !d.driven || d.profile_t.empty(); });
  s.wraps.assign(s.dofs.size(), 0);
  s.turns.assign(s.dofs.size(), Rational(0));
  s.q0_law.assign(s.dofs.size(), 0.0);
  for (std::size_t i = 0; i < s.dofs.size(); ++i) {
    const Dof& d = s.dofs[i];
    s.q0_law[i] = d.q0;
    const Motion& motion = model.parts[d.part].motion;
    s.wraps[i] = d.rotation && motion.kind == Motion::Kind::rotation && !motion.angle_limits && d.stiffness == 0 &&
                 (!d.driven || s.time_rebase);
  }

  // Coulomb coefficients per pair (static; kinetic defaults to static)
  for (const PairSpec& pair : model.pairs) {
    double mus = pair.friction ? to_d(*pair.friction) : 0.0;
    s.mu_static.push_back(mus);
    s.mu_kinetic.push_back(pair.kinetic_friction ? to_d(*pair.kinetic_friction) : mus);
  }
  // the pairs' C-spaces, built once
  CSpaceBuildOptions build;
  build.operating_region = options.operating_region;
  build.quadratic_traits = options.quadratic_traits;
  build.progress = options.build_progress;
  s.spaces.assign(model.pairs.size(), nullptr);
  // a pair of more than options.operating_region_above_edges boundary edges (a gear pair) is
  // built as its operating region: the whole flooded channel of its start, so a motion from the
  // start meets contact space before it can leave the region; the others whole, as before
  auto large_pair = [&](const PairSpec& pair) {
    std::size_t edges = 0;
    for (std::size_t part : {pair.first, pair.second})
      for (const Loop& loop : model.parts[part].loops) edges += loop.edges.size();
    return edges > options.operating_region_above_edges;
  };
  std::vector<PairBuild> built;
  if (!options.operating_region && options.operating_region_above_edges > 0 &&
      std::any_of(model.pairs.begin(), model.pairs.end(), large_pair)) {
    Model small = model, large = model;
    small.pairs.clear();
    large.pairs.clear();
    for (const PairSpec& pair : model.pairs) (large_pair(pair) ? large : small).pairs.push_back(pair);
    CSpaceBuildOptions region = build;
    region.operating_region = true;
    built = CSpace::build_pairs(large, region);
    if (!small.pairs.empty()) {
      std::vector<PairBuild> whole = CSpace::build_pairs(small, build);
      built.insert(built.end(), std::make_move_iterator(whole.begin()), std::make_move_iterator(whole.end()));
    }
  } else {
    built = CSpace::build_pairs(model, build);
  }
  for (const PairBuild& b : built) {
    if (b.status != PairBuild::Status::built)
      throw GeometryError("simulation: the C-space of pair (" + b.first_part + ", " + b.second_part +
                          ") does not build: " + b.error);
    for (std::size_t pair = 0; pair < model.pairs.size(); ++pair) {
      const std::string& a = model.parts[model.pairs[pair].first].name;
      const std::string& c = model.parts[model.pairs[pair].second].name;
      if ((a == b.first_part && c == b.second_part) || (a == b.second_part && c == b.first_part)) s.spaces[pair] = b.space;
    }
  }
  // the start: every pair certainly free
  for (std::size_t pair = 0; pair < s.spaces.size(); ++pair) {
    if (!s.spaces[pair]) continue;
    MotionCrossing c = s.spaces[pair]->first_crossing(s.point_path(pair, s.q));
    if (c.status == CrossingStatus::outside_region) s.outside(pair, 0);
    if (c.status == CrossingStatus::starts_in_contact) {
      std::ostringstream out;
      out << "simulation: the initial configuration of " << s.pair_name(pair)
          << " is not free (the parts touch or overlap"
          << (c.features.empty() ? std::string() : ": " + s.spaces[pair]->feature_pair(c.features.front()).label)
          << "); start the simulation in free space";
      // (where the start is given: a hostile initial angle was named only as the pair, session 61)
      const char* separator = " (the initial configuration: ";
      for (const std::size_t index : {model.pairs[pair].first, model.pairs[pair].second})
        if (model.parts[index].motion.kind != Motion::Kind::fixed) {
          out << separator << model.parts[index].pointer << "/initial";
          separator = ", ";
        }
      if (std::string(separator) == ", ") out << ")";
      throw ModelError(model.pairs[pair].pointer, out.str());
    }
  }
  s.publish();
  Simulation simulated(std::move(impl));
  // (session 72, jam72) an initial state beyond the doubles: bad input at its datum, nothing run
  simulation::refuse_initial_energy(model, simulated.energy());
  return simulated;
}

void Simulation::step() {
  impl_->wrap_turns();
  impl_->step_and_free(std::numeric_limits<double>::infinity());
  impl_->publish();
  impl_->check_energy();
}

void Simulation::run_until(double t_end, const std::function<void(double)>& progress) {
  double limit = t_end * impl_->time_scale;
  for (;;) {
    impl_->wrap_turns();
    const double internal = impl_->internal_time(limit);
    if (!(impl_->t < internal)) break;
    impl_->step_and_free(internal);
    impl_->publish();
    impl_->check_energy();
    // (after whole turns were taken out, the internal limit is t_end - t_offset rounded down:
    // a run that reached it is at t_end, and stops there — a wrap after it would leave the
    // rounding's remainder as a limit past t = 0)
    const bool reached = impl_->t >= internal;
    if (impl_->rebased && reached) impl_->public_state.time = t_end;
    if (progress) progress(impl_->public_state.time);
    if (reached) break;
  }
}

const SimulationState& Simulation::state() const { return impl_->public_state; }
const std::vector<SimulationEvent>& Simulation::events() const { return impl_->events; }
std::vector<SimulationContact> Simulation::contacts() const { return impl_->contacts(); }
double Simulation::energy() const { return impl_->energy(); }
std::size_t Simulation::steps() const { return impl_->steps; }
const Model& Simulation::model() const { return impl_->model; }
const std::vector<std::shared_ptr<const CSpace>>& Simulation::spaces() const { return impl_->spaces; }
const std::string& Simulation::time_unit() const { return impl_->time_unit; }
const std::string& Simulation::force_unit() const { return impl_->force_unit; }

}  // namespace hipair
