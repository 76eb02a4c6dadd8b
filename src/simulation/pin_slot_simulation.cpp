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
//
// Sustained contact (session 58): a contact an impact leaves slower than the rest speed is held
// — a bilateral row of its features' signed gap g(s, psi, phi) within a step (J, the driver's
// share and the curvature term from a second-order forward-mode evaluation, Taylor2), the state
// projected onto the hold gap 3/4 delta after each step, its force from the contact LCP (J M^-1
// J^T over (s, psi)) at each step's start, lifting off where it would turn negative. The slot's
// ends and angle limits are plastic stops held the same way.
//
// Session 59: a rotating part turned by a constant torque with its own moment of inertia (its
// angle phi, the state's [4] and [5]) and a translating part pushed by the pin-slot part (its
// offset x along its unit direction, [6] and [7]; its damping's work [8]) join (s, psi) as
// generalized coordinates, the mass matrix block-diagonal diag(M(s), I, m_x); contact rows gain
// their columns (-n . (k x (p - C)) and -n . d at the kernels' contact point; a held gap's
// forward-mode derivatives), the contact problems are built over all coordinates. Without them
// every computation is the one before (the same outputs, byte for byte).
#include <hipair/error.hpp>
#include <hipair/pin_slot_simulation.hpp>
#include <hipair/simulation_stop.hpp>

#include "core/angle_limits.hpp"
#include "simulation/frame_rate.hpp"
#include "simulation/friction.hpp"
#include "simulation/held_friction.hpp"
#include "simulation/friction_names.hpp"
#include "simulation/held_extent.hpp"
#include "simulation/held_force_sign.hpp"
#include "simulation/jam.hpp"
#include "simulation/lcp.hpp"
#include "simulation/initial_energy.hpp"
#include "simulation/motion_datum.hpp"
#include "simulation/relative_configuration.hpp"
#include "simulation/units.hpp"

#include "kernels/contact_geometry.hpp"
#include "kernels/distance.hpp"
#include "kernels/model_features.hpp"
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

// The same placement as configuration q about `from` (p -> from + R(theta)(p - from) + (x, y)),
// as a configuration about `to`: the shift gains (I - R(theta))(from - to); exact.
SlicedConfiguration repivot(const SlicedConfiguration& q, const Point& from, const Point& to) {
  if (from == to) return q;
  SlicedConfiguration r = q;
  auto [c, s] = cos_sin(q.angle);
  const Rational dx = from.x - to.x, dy = from.y - to.y;
  r.x += dx - (c * dx - s * dy);
  r.y += dy - (s * dx + c * dy);
  r.x.canonicalize();
  r.y.canonicalize();
  return r;
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

// s, psi, s', psi'; a torque-driven rotating part's (free driver's) phi, phi'; a translating
// part's (the slider's) offset x, x' and the work its damping and the pin-slot part's slide damping
// have done (0 without them)
using State = std::array<double, 9>;
bool finite(const State& s) {
  return std::all_of(s.begin(), s.end(), [](double v) { return std::isfinite(v); });
}

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

// A function of one parameter tau to second order: value, first and second derivative at tau = 0
// (forward mode), for a held contact's gap along a straight motion in (s, psi, phi).
struct Taylor2 {
  double v = 0, d = 0, dd = 0;
};
Taylor2 operator+(Taylor2 a, Taylor2 b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
Taylor2 operator-(Taylor2 a, Taylor2 b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
Taylor2 operator*(Taylor2 a, Taylor2 b) { return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd}; }
Taylor2 operator*(double k, Taylor2 a) { return {k * a.v, k * a.d, k * a.dd}; }
Taylor2 constant(double v) { return {v, 0, 0}; }
Taylor2 sqrt_of(Taylor2 a) {
  const double r = std::sqrt(a.v);
  return {r, a.d / (2 * r), a.dd / (2 * r) - a.d * a.d / (4 * r * r * r)};
}
Taylor2 cos_of(Taylor2 a) {
  const double c = std::cos(a.v), s = std::sin(a.v);
  return {c, -s * a.d, -c * a.d * a.d - s * a.dd};
}
Taylor2 sin_of(Taylor2 a) {
  const double c = std::cos(a.v), s = std::sin(a.v);
  return {s, c * a.d, -s * a.d * a.d + c * a.dd};
}
struct TPoint {
  Taylor2 x, y;
};
TPoint operator-(const TPoint& a, const TPoint& b) { return {a.x - b.x, a.y - b.y}; }
Taylor2 cross(const TPoint& a, const TPoint& b) { return a.x * b.y - a.y * b.x; }
Taylor2 norm_of(const TPoint& a) { return sqrt_of(a.x * a.x + a.y * a.y); }

// A rigid placement in Taylor2: p -> origin + R(angle) (p - pivot) (+ shift along a body direction).
struct TPose {
  Taylor2 c, s;
  double pivot[2] = {0, 0};
  TPoint origin;   // where the pivot goes
  TPoint place(const kernels::Vector<double>& p) const {
    const double dx = p.x - pivot[0], dy = p.y - pivot[1];
    return {origin.x + dx * c - dy * s, origin.y + dx * s + dy * c};
  }
  TPoint turn(double dx, double dy) const { return {dx * c - dy * s, dx * s + dy * c}; }
};

// The signed Euclidean gap of a feature pair (positive apart, mm) with the features placed by
// their poses; nullopt for the feature kinds a held contact does not take (segment on a concave
// arc, two concave arcs, vertex on vertex, segment on segment).
std::optional<Taylor2> feature_gap(const TPose& pa, const kernels::FeatureGeometry<double>& fa, const TPose& pb,
                                   const kernels::FeatureGeometry<double>& fb) {
  using kernels::FeatureShape;
  auto vertex_segment = [](const TPose& pv, const kernels::FeatureGeometry<double>& v, const TPose& ps,
                           const kernels::FeatureGeometry<double>& seg) {
    const TPoint q1 = ps.place(seg.point), q2 = ps.place(seg.target);
    const double length = std::hypot(seg.target.x - seg.point.x, seg.target.y - seg.point.y);
    return (1 / length) * cross(pv.place(v.point) - q1, q2 - q1);
  };
  auto vertex_arc = [](const TPose& pv, const kernels::FeatureGeometry<double>& v, const TPose& pk,
                       const kernels::FeatureGeometry<double>& arc) {
    const Taylor2 dist = norm_of(pv.place(v.point) - pk.place(arc.center));
    const Taylor2 r = constant(std::sqrt(arc.radius_squared));
    return arc.convex ? dist - r : r - dist;
  };
  auto segment_arc = [](const TPose& ps, const kernels::FeatureGeometry<double>& seg, const TPose& pk,
                        const kernels::FeatureGeometry<double>& arc) -> std::optional<Taylor2> {
    if (!arc.convex) return std::nullopt;
    const TPoint q1 = ps.place(seg.point), q2 = ps.place(seg.target);
    const double length = std::hypot(seg.target.x - seg.point.x, seg.target.y - seg.point.y);
    return (1 / length) * cross(pk.place(arc.center) - q1, q2 - q1) - constant(std::sqrt(arc.radius_squared));
  };
  const FeatureShape a = fa.shape, b = fb.shape;
  if (a == FeatureShape::vertex && b == FeatureShape::segment) return vertex_segment(pa, fa, pb, fb);
  if (a == FeatureShape::segment && b == FeatureShape::vertex) return vertex_segment(pb, fb, pa, fa);
  if (a == FeatureShape::vertex && b == FeatureShape::arc) return vertex_arc(pa, fa, pb, fb);
  if (a == FeatureShape::arc && b == FeatureShape::vertex) return vertex_arc(pb, fb, pa, fa);
  if (a == FeatureShape::segment && b == FeatureShape::arc) return segment_arc(pa, fa, pb, fb);
  if (a == FeatureShape::arc && b == FeatureShape::segment) return segment_arc(pb, fb, pa, fa);
  if (a == FeatureShape::arc && b == FeatureShape::arc) {
    if (!fa.convex && !fb.convex) return std::nullopt;
    const Taylor2 dist = norm_of(pa.place(fa.center) - pb.place(fb.center));
    const double ra = std::sqrt(fa.radius_squared), rb = std::sqrt(fb.radius_squared);
    if (fa.convex && fb.convex) return dist - constant(ra + rb);
    return constant(fa.convex ? rb - ra : ra - rb) - dist;   // the convex one inside the concave one
  }
  return std::nullopt;
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
  // viscous damping of the slide (session 60): Q_s gains -c s' (mN s/mm); its work is the state's [8]
  double damping = 0;
  std::optional<RationalInterval> slide_limits, angle_limits;
  struct Driver {
    std::size_t part = 0;
    double angle0 = 0, omega = 0;   // rad, rad/s
    // a torque-driven part with its own inertia (session 59): its angle and rate are the state's
    // [4] and [5], its equation I phi'' = torque + the contacts' share (no prescribed speed)
    bool free = false;
    double inertia = 0, torque = 0;   // kg mm^2, mN mm
    // the model's exact speed (rad per its time unit; omega is its double over the time scale):
    // the jam test's driver shares (session 70, stop70)
    Rational speed{0};
  };
  std::size_t free_driver = no_index;   // into drivers: the one torque-driven part, if any
  // A translating part pushed by the pin-slot part (session 59: the film): its offset x along its
  // unit direction is the state's [6], its rate [7]; m x'' = F . d - k (x - rest) - c x' + the
  // contacts' share; its limits are plastic stops.
  struct Slider {
    std::size_t part = no_index;
    double dir[2] = {0, 1};
    double mass = 0, load = 0, k = 0, rest = 0, damping = 0;   // kg, mN (F . d), mN/mm, mm, mN s/mm
    std::optional<RationalInterval> limits;
  };
  Slider slider;
  bool has_slider() const { return slider.part != no_index; }
  // The generalized coordinates: (s, psi), phi of the free driver and x of the slider when there
  // are ones (in that order).
  Eigen::Index coordinates() const { return 2 + (free_driver != no_index ? 1 : 0) + (has_slider() ? 1 : 0); }
  Eigen::Index x_column() const { return free_driver != no_index ? 3 : 2; }
  // The generalized velocity of a state.
  Eigen::VectorXd rates(const State& x) const {
    Eigen::VectorXd v(coordinates());
    v(0) = x[2];
    v(1) = x[3];
    if (free_driver != no_index) v(2) = x[5];
    if (has_slider()) v(x_column()) = x[7];
    return v;
  }
  void add_rates(State& x, const Eigen::VectorXd& dv) const {
    x[2] += dv(0);
    x[3] += dv(1);
    if (free_driver != no_index) x[5] += dv(2);
    if (has_slider()) x[7] += dv(x_column());
  }
  std::vector<Driver> drivers;
  std::vector<std::size_t> driver_of;   // model part -> drivers index (no_index: fixed or the pin-slot part)
  struct Pair {
    std::size_t index = 0;   // into Model::pairs
    std::size_t other = 0;   // model part
    double restitution = 0;
    double mu_static = 0, mu_kinetic = 0;   // Coulomb friction (session 64; 0: frictionless)
    std::shared_ptr<Model> frame_model;   // the other part fixed at its zero configuration, the pin-slot part planar
    SlicedSpace space;
    SlicedConfiguration q;   // the state's exact configuration (free)
    std::vector<Box> other_boxes;   // the other part's edge boxes at its zero configuration
    std::vector<PlacedEdge> other_edges;   // and its edges
    // The pin-slot part's planar pivot in this pair's C-space (session 66: `q` places its body
    // point p at pivot + R(theta)(p - pivot) + (x, y)): the pin P, or against a rotating part the
    // rotating part's pivot C, so that the rotating part's turning changes the chart angle alone
    // (a straight chord follows it; about P the shift circled at radius |P - C| and every chord
    // left the path by |P - C| dtheta^2 / 8: the film advance's 3.4e-6 s steps). `reach` is the
    // part's largest distance from it (the angle's share of a chord's deviation).
    Point pivot;
    double reach = 0;
  };
  std::vector<Pair> pairs;
  // A held (sustained) contact: a feature pair of a pair kept at the hold gap, its force the
  // multiplier of its bilateral row within a step, decided by the contact LCP at each step's start.
  struct Held {
    std::size_t pair = 0;   // into pairs (no_index for a limit)
    // 0: a contact; a limit of the part's own coordinates: 1 the slide's upper end, 2 its lower
    // end, 3 the upper angle limit, 4 the lower (its gap hi - s, s - lo, or reach x the angle's)
    int limit = 0;
    SlicedFeaturePair features;   // (a limit: its label only)
    kernels::FeatureGeometry<double> fixed_geometry, free_geometry;   // body coordinates
    // the same exactly and as certified intervals (the edge-end decision, held_extent.hpp)
    kernels::FeatureGeometry<Rational> fixed_exact, free_exact;
    kernels::FeatureGeometry<kernels::Interval> fixed_box, free_box;
    // and in dual numbers (the kernels' contact frame with its rate: held_frame)
    kernels::FeatureGeometry<kernels::Dual> fixed_dual, free_dual;
    double force = 0;   // internal units (mN), the last multiplier
    // Coulomb friction (session 64): stick, slip_positive / slip_negative (the pin-slot part's
    // contact point sliding along +-t = k x n relative to the other part) or frictionless (also a
    // frictional contact before its first decision: `decided` false); its friction force (mN,
    // along t on the pin-slot part) at the last decision
    int state = simulation::frictionless;
    bool decided = false;
    double friction_force = 0;
  };
  std::vector<Held> held;
  // A held contact's gap and its derivatives at a state: g, J = dg/d(s, psi), g_phi = dg/dphi
  // (the driver's angle), kappa = the gap's second derivative along the state's velocity with
  // zero accelerations (the driver at its constant speed). Its normal speed is J q' + g_phi omega.
  // Against the free driver (`free`) g_phi is the row's third column, omega its rate phi'.
  // Against the slider (`slider`) g_x is its column, x_rate its rate x'.
  struct HeldRow {
    double g = 0, J[2] = {0, 0}, g_phi = 0, kappa = 0, omega = 0, g_x = 0, x_rate = 0;
    bool free = false, slider = false;
    double speed(const State& x) const {
      const double v = J[0] * x[2] + J[1] * x[3] + g_phi * omega;
      return slider ? v + g_x * x_rate : v;
    }
  };
  double delta = 0, accuracy = 1e-9, rest_speed = 0, hold_gap = 0;
  // the run's length scale: the part's reach at its initial slide (reach_at; the angle limits'
  // rows are their angle gap times it)
  double size = 0;
  double forced_step = 0;   // a step length located by bisection (a held contact's force or edge ends there)
  int pending_limit = 0;    // the limit the forced step ends at (struck when the step is accepted)
  // the part's reach from its pin at slide 0 (its points' and arcs' largest distance from P)
  double part_reach = 0;
  // the part's reach from the pin's line position at the states given: part_reach plus their
  // largest |slide| (until session 58 the largest |slide limit|: a slot with limits of 1e9 mm made
  // the chord deviation 1 mm and the rest speed 140 mm/s, and the run stopped at the pin-slot
  // cam's second impact as a contact that would have to be sustained)
  double reach_at(std::initializer_list<const State*> states) const {
    double slide = 0;
    for (const State* x : states) slide = std::max(slide, std::abs((*x)[0]));
    return part_reach + slide;
  }
  double reach_at(std::initializer_list<std::pair<const State*, double>> states) const {
    double slide = 0;
    for (const auto& x : states) slide = std::max(slide, std::abs((*x.first)[0]));
    return part_reach + slide;
  }
  double t = 0;
  State y{};
  std::vector<SimulationEvent> events;
  std::size_t steps = 0, chords = 0;
  std::size_t steps_in_place = 0;   // consecutive steps that did not move the time on
  // energy removed by impacts and by the projections onto held contacts (internal units)
  double impact_loss = 0, settle_loss = 0;
  double step_guess = 0;
  PinSlotState public_state;

  // A driver's angle and rate at a state: the state's for the free driver, the prescribed law's
  // (exact linear in time) for a driver at constant speed.
  double driver_angle(std::size_t driver, const State& x, double time) const {
    if (drivers[driver].free) return x[4];
    return drivers[driver].angle0 + drivers[driver].omega * time;
  }
  double driver_rate(std::size_t driver, const State& x) const {
    return drivers[driver].free ? x[5] : drivers[driver].omega;
  }
  // the world configuration of the pin-slot part as a planar part about P, exact
  SlicedConfiguration follower_configuration(const State& s) const {
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
  SlicedConfiguration relative(const Pair& p, const State& s, double time) const {
    SlicedConfiguration f = follower_configuration(s);
    if (p.other == slider.part) {   // in the slider's frame: the shift less x d, exactly
      if (!std::isfinite(s[6])) throw NumericError("the simulated offset of a translating part is not finite");
      const Rational x(s[6]);
      const Point& dir = model.parts[p.other].motion.direction;
      f.x -= x * dir.x;
      f.y -= x * dir.y;
      f.x.canonicalize();
      f.y.canonicalize();
      return f;
    }
    const std::size_t dr = driver_of[p.other];
    if (dr == no_index) return f;
    SlicedConfiguration a;
    a.angle = exact_angle(driver_angle(dr, s, time));
    return relative_configuration(model.parts[p.other].motion.pivot, a, p.pivot,
                                  repivot(f, model.parts[part].motion.pivot, p.pivot));
  }
  // The pair's exact configuration `q` (about the pair's pivot) as the configuration about the
  // pin P (PinSlotState::pair_configurations; the same placement, exactly).
  SlicedConfiguration about_pin(const Pair& p, const SlicedConfiguration& q) const {
    return repivot(q, p.pivot, model.parts[part].motion.pivot);
  }
  double relative_angle(const Pair& p, const State& s, double time) const {
    const std::size_t dr = driver_of[p.other];
    return wrap(s[1] - (dr == no_index ? 0.0 : driver_angle(dr, s, time)));
  }
  // The same not wrapped (the part's psi and a driver's angle as integrated or prescribed): its
  // change over a step counts whole turns, which relative_angle's differences cannot see.
  double turned(const Pair& p, const State& s, double time) const {
    const std::size_t dr = driver_of[p.other];
    return s[1] - (dr == no_index ? 0.0 : driver_angle(dr, s, time));
  }
  // mass matrix and the right-hand side of Lagrange's equations
  void dynamics(const State& s, double M[2][2], double Q[2]) const {
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
    if (damping > 0) Q[0] -= damping * s[2];
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
  // M^-1 as a matrix, column by column through inverse_mass_times (its entries 1/m + e^2/D, -e/D
  // and 1/D: never det M)
  Eigen::Matrix2d inverse_mass2(double s0) const {
    Eigen::Matrix2d out;
    for (int c = 0; c < 2; ++c) {
      const double unit[2] = {c == 0 ? 1.0 : 0.0, c == 1 ? 1.0 : 0.0};
      double x[2];
      inverse_mass_times(s0, unit, x);
      out(0, c) = x[0];
      out(1, c) = x[1];
    }
    return out;
  }
  // The generalized forces (coordinates(): Q_s, Q_psi, and the free driver's torque) and the
  // inverse of the block-diagonal mass matrix diag(M(s), I) at a state.
  Eigen::VectorXd forces(const State& x) const {
    double M[2][2], Q[2];
    dynamics(x, M, Q);
    Eigen::VectorXd out(coordinates());
    out(0) = Q[0];
    out(1) = Q[1];
    if (free_driver != no_index) out(2) = drivers[free_driver].torque;
    if (has_slider()) out(x_column()) = slider.load - slider.k * (x[6] - slider.rest) - slider.damping * x[7];
    return out;
  }
  Eigen::MatrixXd inverse_mass(const State& x) const {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(coordinates(), coordinates());
    out.topLeftCorner(2, 2) = inverse_mass2(x[0]);
    if (free_driver != no_index) out(2, 2) = 1 / drivers[free_driver].inertia;
    if (has_slider()) out(x_column(), x_column()) = 1 / slider.mass;
    return out;
  }
  Eigen::MatrixXd mass_matrix(const State& x) const {
    double M[2][2], Q[2];
    dynamics(x, M, Q);
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(coordinates(), coordinates());
    out(0, 0) = M[0][0];
    out(0, 1) = M[0][1];
    out(1, 0) = M[1][0];
    out(1, 1) = M[1][1];
    if (free_driver != no_index) out(2, 2) = drivers[free_driver].inertia;
    if (has_slider()) out(x_column(), x_column()) = slider.mass;
    return out;
  }
  // The placements of a held contact's two parts along the straight motion (s, psi, phi) +
  // tau (ds, dpsi, dphi) at `time`.
  std::pair<TPose, TPose> held_poses(const Held& h, const State& s, double time, const double dir[4]) const {
    const Pair& p = pairs[h.pair];
    const std::size_t dr = driver_of[p.other];
    TPose other;
    other.c = constant(1);
    other.s = constant(0);
    if (dr != no_index) {
      const Point& C = model.parts[p.other].motion.pivot;
      const Taylor2 phi{driver_angle(dr, s, time), dir[2], 0};
      other.c = cos_of(phi);
      other.s = sin_of(phi);
      other.pivot[0] = C.x.get_d();
      other.pivot[1] = C.y.get_d();
      other.origin = {constant(other.pivot[0]), constant(other.pivot[1])};
    } else if (p.other == slider.part) {   // translated by x d
      const Taylor2 x{s[6], dir[3], 0};
      other.origin = {slider.dir[0] * x, slider.dir[1] * x};
    }
    TPose follower;
    const Taylor2 psi{s[1], dir[1], 0}, slide{s[0], dir[0], 0};
    follower.c = cos_of(psi);
    follower.s = sin_of(psi);
    follower.pivot[0] = P[0];
    follower.pivot[1] = P[1];
    const TPoint u = follower.turn(d[0], d[1]);
    follower.origin = {constant(P[0]) + slide * u.x, constant(P[1]) + slide * u.y};
    return {other, follower};
  }
  // The limit a state lies beyond (0: none; exact comparisons of the state's doubles).
  // A feature pair of pair `pi` as a row the projection can raise (its body geometry; none for
  // kinds the held gap does not cover: a segment on a concave arc, two concave arcs).
  std::optional<Held> clearance(std::size_t pi, const SlicedFeaturePair& f) const;
  // A held contact of pair `pi` on feature pair `f` with its body geometries (double, exact, interval).
  Held held_contact(std::size_t pi, const SlicedFeaturePair& f) const {
    const Model& frame = *pairs[pi].frame_model;
    Held h;
    h.pair = pi;
    h.features = f;
    h.fixed_geometry = kernels::feature_geometry<double>(frame, f.fixed, [](const Rational& r) { return r.get_d(); });
    h.free_geometry = kernels::feature_geometry<double>(frame, f.free, [](const Rational& r) { return r.get_d(); });
    h.fixed_exact = kernels::feature_geometry<Rational>(frame, f.fixed, [](const Rational& r) { return r; });
    h.free_exact = kernels::feature_geometry<Rational>(frame, f.free, [](const Rational& r) { return r; });
    h.fixed_box = simulation::enclose(h.fixed_exact);
    h.free_box = simulation::enclose(h.free_exact);
    const auto dual = [](const Rational& r) { return kernels::Dual(r.get_d()); };
    h.fixed_dual = kernels::feature_geometry<kernels::Dual>(frame, f.fixed, dual);
    h.free_dual = kernels::feature_geometry<kernels::Dual>(frame, f.free, dual);
    return h;
  }
  int outside_limit(const State& s) const {
    if (slide_limits && Rational(s[0]) > slide_limits->hi) return 1;
    if (slide_limits && Rational(s[0]) < slide_limits->lo) return 2;
    if (angle_limits && Rational(s[1]) > angle_limits->hi) return 3;
    if (angle_limits && Rational(s[1]) < angle_limits->lo) return 4;
    if (has_slider() && slider.limits && Rational(s[6]) > slider.limits->hi) return 5;
    if (has_slider() && slider.limits && Rational(s[6]) < slider.limits->lo) return 6;
    return 0;
  }
  // the part a limit belongs to (5, 6: the slider's offset limits)
  std::size_t limit_part(int limit) const { return limit >= 5 ? slider.part : part; }
  std::string limit_label(int limit) const {
    const Part& pp = model.parts[limit_part(limit)];
    static const char* const names[] = {"", "slide limit (upper end)", "slide limit (lower end)", "angle limit (upper)",
                                        "angle limit (lower)", "offset limit (upper end)", "offset limit (lower end)"};
    return pp.name + " " + names[limit] + " " + pp.motion.pointer + (limit <= 2 || limit >= 5 ? "/limits" : "/angle_limits");
  }
  HeldRow limit_row(int limit, const State& s) const {
    HeldRow row;
    switch (limit) {
      case 1: row.g = slide_limits->hi.get_d() - s[0], row.J[0] = -1; break;
      case 2: row.g = s[0] - slide_limits->lo.get_d(), row.J[0] = 1; break;
      case 3: row.g = (angle_limits->hi.get_d() - s[1]) * size, row.J[1] = -size; break;
      case 4: row.g = (s[1] - angle_limits->lo.get_d()) * size, row.J[1] = size; break;
      case 5: row.g = slider.limits->hi.get_d() - s[6], row.slider = true, row.g_x = -1, row.x_rate = s[7]; break;
      default: row.g = s[6] - slider.limits->lo.get_d(), row.slider = true, row.g_x = 1, row.x_rate = s[7]; break;
    }
    return row;
  }
  HeldRow held_row(const Held& h, const State& s, double time) const {
    if (h.limit) return limit_row(h.limit, s);
    const std::size_t dr = driver_of[pairs[h.pair].other];
    HeldRow row;
    row.omega = dr == no_index ? 0.0 : driver_rate(dr, s);
    row.free = dr != no_index && drivers[dr].free;
    const bool slid = pairs[h.pair].other == slider.part;
    row.slider = slid;
    row.x_rate = slid ? s[7] : 0.0;
    auto along = [&](double ds, double dpsi, double dphi, double dx = 0) {
      const double dir[4] = {ds, dpsi, dphi, dx};
      const auto [a, b] = held_poses(h, s, time, dir);
      return *feature_gap(a, h.fixed_geometry, b, h.free_geometry);
    };
    const Taylor2 v = along(s[2], s[3], row.omega, row.x_rate);
    row.g = v.v;
    row.kappa = v.dd;
    row.J[0] = along(1, 0, 0).d;
    row.J[1] = along(0, 1, 0).d;
    row.g_phi = along(0, 0, 1).d;
    if (slid) row.g_x = along(0, 0, 0, 1).d;
    return row;
  }
  // The held contacts' problem at a state, built once for the bilateral multipliers and the
  // contact LCP: their rows J (over the generalized coordinates), A = J M^-1 J^T and b = J M^-1 Q +
  // kappa (the gaps' accelerations are A lambda + b). Q: the generalized forces (coordinates()).
  struct HeldProblem {
    std::vector<HeldRow> rows;
    Eigen::MatrixXd J, A;
    Eigen::VectorXd kappa, b;
  };
  HeldProblem held_problem(const State& s, double time, const Eigen::VectorXd& Q) const {
    HeldProblem out;
    for (const Held& h : held) out.rows.push_back(held_row(h, s, time));
    const auto k = static_cast<Eigen::Index>(out.rows.size());
    const Eigen::MatrixXd Mi = inverse_mass(s);
    out.J = jacobian(out.rows);
    out.kappa.resize(k);
    for (Eigen::Index i = 0; i < k; ++i) out.kappa(i) = out.rows[static_cast<std::size_t>(i)].kappa;
    out.A = out.J * Mi * out.J.transpose();
    out.b = out.J * (Mi * Q) + out.kappa;
    return out;
  }
  // The rows' Jacobian over the generalized coordinates (the free driver's column g_phi).
  Eigen::MatrixXd jacobian(const std::vector<HeldRow>& rows) const {
    const auto k = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd J(k, coordinates());
    for (Eigen::Index i = 0; i < k; ++i) {
      const HeldRow& row = rows[static_cast<std::size_t>(i)];
      J(i, 0) = row.J[0];
      J(i, 1) = row.J[1];
      if (free_driver != no_index) J(i, 2) = row.free ? row.g_phi : 0.0;
      if (has_slider()) J(i, x_column()) = row.slider ? row.g_x : 0.0;
    }
    return J;
  }
  // ---- Coulomb friction (session 64; docs/simulation.md, "Friction at a pin-slot part's
  // contacts"). A contact's tangent row at the world point p with the unit normal n (from the
  // other part into the pin-slot part): the pin-slot part's contact point moves relative to the
  // other part along t = k x n at T . rates - v_other (v_other: a constant-speed driver's surface
  // speed along t) — T = [t . u, n . (p - P)] over (s, psi), the free driver's column
  // -n . (p - C), the slider's -t . d (the normal rows' columns with t for n).
  // With the frame's rates (session 65: a held contact's, held_frame) also the row's drift
  // T' rates - v_other' along the state's motion: the tangential curvature term a sticking contact
  // keeps (Friction::bias; T a + drift = 0), with t' = k x n', u' = psi' k x u and the lever's
  // rate n' . (p - X) + n . p'.
  struct Tangent {
    Eigen::VectorXd T;
    double v_other = 0, drift = 0;
  };
  Tangent tangent_at(std::size_t pi, const double p[2], const double n[2], const State& s,
                     const simulation::FrameRate* rate = nullptr) const {
    Tangent out;
    out.T = Eigen::VectorXd::Zero(coordinates());
    const double tx = -n[1], ty = n[0];
    const double c = std::cos(s[1]), sn = std::sin(s[1]);
    const double u[2] = {c * d[0] - sn * d[1], sn * d[0] + c * d[1]};
    out.T(0) = tx * u[0] + ty * u[1];
    out.T(1) = n[0] * (p[0] - P[0]) + n[1] * (p[1] - P[1]);   // t . (k x (p - P))
    const Pair& pair = pairs[pi];
    const std::size_t dr = driver_of[pair.other];
    if (dr != no_index) {
      const Point& C = model.parts[pair.other].motion.pivot;
      const double lever = n[0] * (p[0] - C.x.get_d()) + n[1] * (p[1] - C.y.get_d());
      if (drivers[dr].free) out.T(2) = -lever;
      else out.v_other = driver_rate(dr, s) * lever;
    }
    if (pair.other == slider.part) out.T(x_column()) = -(tx * slider.dir[0] + ty * slider.dir[1]);
    if (!rate) return out;
    const double* dp = rate->point_rate;
    const double* dn = rate->normal_rate;
    const double dtx = -dn[1], dty = dn[0];
    const double du[2] = {-s[3] * u[1], s[3] * u[0]};
    auto lever_rate = [&](double X, double Y) { return dn[0] * (p[0] - X) + dn[1] * (p[1] - Y) + n[0] * dp[0] + n[1] * dp[1]; };
    double drift = (dtx * u[0] + dty * u[1] + tx * du[0] + ty * du[1]) * s[2] + lever_rate(P[0], P[1]) * s[3];
    if (dr != no_index) {
      const Point& C = model.parts[pair.other].motion.pivot;
      const double dlever = lever_rate(C.x.get_d(), C.y.get_d());
      if (drivers[dr].free) drift -= dlever * s[5];
      else drift -= driver_rate(dr, s) * dlever;   // v_other' (a constant speed)
    }
    if (pair.other == slider.part) drift -= (dtx * slider.dir[0] + dty * slider.dir[1]) * s[7];
    out.drift = std::isfinite(drift) ? drift : 0.0;
    return out;
  }
  // A held contact's contact frame and its rate at a state (session 65; until then a point and a
  // normal computed here from the held gap's gradient): the kernels' contact frame
  // (kernels/contact_geometry.hpp) in dual numbers (simulation/frame_rate.hpp), the other part
  // posed at its angle or offset with its rate, the pin-slot part about P at angle psi shifted by
  // s R(psi) d with theirs: the world point, the unit normal from the other part into the pin-slot
  // part and their rates along the state's motion.
  simulation::FrameRate held_frame(const Held& h, const State& s, double time) const {
    using kernels::Dual;
    const Pair& pair = pairs[h.pair];
    const std::size_t dr = driver_of[pair.other];
    kernels::Pose<Dual> other = kernels::fixed_pose<Dual>();
    if (dr != no_index) {
      const Point& C = model.parts[pair.other].motion.pivot;
      const double phi = driver_angle(dr, s, time), w = driver_rate(dr, s);
      other = kernels::rotation_pose_from_cos_sin(kernels::Vector<Dual>{Dual(C.x.get_d()), Dual(C.y.get_d())},
                                                  Dual(std::cos(phi), -std::sin(phi) * w),
                                                  Dual(std::sin(phi), std::cos(phi) * w));
    } else if (pair.other == slider.part) {
      other = kernels::translation_pose(kernels::Vector<Dual>{Dual(slider.dir[0]), Dual(slider.dir[1])}, Dual(s[6], s[7]));
    }
    const Dual c(std::cos(s[1]), -std::sin(s[1]) * s[3]), sn(std::sin(s[1]), std::cos(s[1]) * s[3]);
    const Dual slide(s[0], s[2]);
    kernels::Pose<Dual> follower =
        kernels::rotation_pose_from_cos_sin(kernels::Vector<Dual>{Dual(P[0]), Dual(P[1])}, c, sn);
    follower.shift = {slide * (c * d[0] - sn * d[1]), slide * (sn * d[0] + c * d[1])};
    follower.translates = true;
    return simulation::frame_rate(kernels::contact_frame(other, h.fixed_dual, follower, h.free_dual));
  }
  bool frictional(const Held& h) const { return !h.limit && pairs[h.pair].mu_static > 0; }
  bool any_friction() const {
    return std::any_of(held.begin(), held.end(), [&](const Held& h) { return frictional(h); });
  }
  // Friction data of a contact (the tangent row in the problem's coordinates, see FrictionProblem)
  // with normal row G: off where the tangent is parallel to the normal row (as the fixed-axis
  // simulator's).
  static simulation::Friction friction_of(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::VectorXd& G,
                                          const Tangent& tangent, const Pair& pair) {
    simulation::Friction fr;
    const double gg = G.squaredNorm(), tt = tangent.T.squaredNorm(), tg = tangent.T.dot(G);
    if (!(gg > 0) || !(tt > 0) || !(tt - tg * tg / gg > 1e-18 * tt)) return fr;
    fr.on = true;
    fr.T = llt.matrixL().solve(tangent.T);
    fr.mu_static = pair.mu_static;
    fr.mu_kinetic = pair.mu_kinetic;
    return fr;
  }
  // The held contacts' frictional force problem at a state in the coordinates z = L^T q (M = L L^T,
  // its Cholesky factor): there the mass matrix is the identity, so the problem is friction.hpp's
  // (diagonal inverse masses 1) — rows G = J L^-T and T L^-T, free accelerations L^-1 Q, the
  // accelerations a = L^-T x. The multipliers and friction forces are the same numbers.
  // The exact decisions (session 65) are taken on `full`, the problem over (s, psi, ...) with the
  // mass matrix M itself (friction.hpp's FullMass): the rows J and T, M and Q as computed, not the
  // factor's rounded rows.
  struct FrictionProblem {
    simulation::FullMass full;
    Eigen::LLT<Eigen::MatrixXd> llt;
    Eigen::MatrixXd G;
    Eigen::VectorXd minv, a0, h;
    std::vector<simulation::Friction> friction;
    std::vector<Tangent> tangents;
    std::vector<double> vt;   // each contact's tangential speed at the state (0 without friction)
  };
  FrictionProblem friction_problem(const State& s, double time) const {
    FrictionProblem out;
    out.llt.compute(mass_matrix(s));
    if (out.llt.info() != Eigen::Success)
      throw NumericError("the mass matrix of a pin-slot simulation is not positive definite in doubles (its masses and "
                         "moments of inertia too far apart)");
    std::vector<HeldRow> rows;
    for (const Held& h : held) rows.push_back(held_row(h, s, time));
    const Eigen::MatrixXd J = jacobian(rows);
    out.G = out.llt.matrixL().solve(J.transpose()).transpose();
    out.a0 = out.llt.matrixL().solve(forces(s));
    out.minv = Eigen::VectorXd::Ones(coordinates());
    out.h.resize(J.rows());
    const Eigen::VectorXd v = rates(s);
    for (std::size_t i = 0; i < held.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      out.h(r) = rows[i].kappa;
      Tangent tangent;
      simulation::Friction fr;
      if (frictional(held[i])) {
        tangent = held_tangent(held[i], s, time);
        fr = friction_of(out.llt, J.row(r).transpose(), tangent, pairs[held[i].pair]);
        fr.bias = fr.on ? tangent.drift : 0.0;   // (session 65; 0 before: the drift neglected)
      }
      fr.state = held[i].state;
      fr.decided = true;
      out.vt.push_back(fr.on ? tangent.T.dot(v) - tangent.v_other : 0.0);
      simulation::Friction original = fr;   // the full form's: the tangent row over the coordinates
      if (fr.on) original.T = tangent.T;
      out.full.friction.push_back(std::move(original));
      out.friction.push_back(std::move(fr));
      out.tangents.push_back(std::move(tangent));
    }
    out.full.G = J;
    out.full.M = mass_matrix(s);
    out.full.Q = forces(s);
    return out;
  }
  Tangent held_tangent(const Held& h, const State& s, double time) const {
    const simulation::FrameRate f = held_frame(h, s, time);
    return tangent_at(h.pair, f.point, f.normal, s, &f);
  }
  // The held contacts' stick/slip states as integrated (frictionless where friction is off).
  std::vector<int> held_states(const FrictionProblem& fp) const {
    std::vector<int> out;
    for (std::size_t i = 0; i < held.size(); ++i) out.push_back(fp.friction[i].on ? held[i].state : simulation::frictionless);
    return out;
  }
  // The accelerations with frictional held contacts at their states (friction.hpp's bilateral
  // solve: a sticking contact keeps its tangential acceleration 0, a sliding one pushes along
  // J - sign mu_k T); `power`: the rate at which friction dissipates energy, -sum f v_t.
  Eigen::VectorXd frictional_accelerations(const State& s, double time, double* power,
                                           simulation::FrictionalSolution* out = nullptr) const {
    const FrictionProblem fp = friction_problem(s, time);
    simulation::FrictionalSolution sol =
        simulation::solve_bilateral(fp.G, fp.minv, fp.a0, fp.h, fp.friction, held_states(fp));
    if (power) {
      *power = 0;
      for (std::size_t i = 0; i < held.size(); ++i)
        if (fp.friction[i].on) *power -= sol.f(static_cast<Eigen::Index>(i)) * fp.vt[i];
    }
    Eigen::VectorXd a = fp.llt.matrixU().solve(sol.x);
    if (out) *out = std::move(sol);
    return a;
  }
  // The exact sign of a contact's tangential speed T . rates - v_other (the rates and the row as
  // their doubles give them).
  int tangential_sign(const Tangent& tangent, const State& s) const {
    const Eigen::Index n = tangent.T.size();
    Eigen::VectorXd a(n + 1), b(n + 1);
    a.head(n) = tangent.T;
    a(n) = -tangent.v_other;
    b.head(n) = rates(s);
    b(n) = 1;
    return simulation::exact_dot_sign(a, b);
  }
  // The held contacts' bilateral multipliers at a state (the minimum-norm solution when their
  // rows are dependent).
  Eigen::VectorXd held_multipliers(const State& s, double time, const Eigen::VectorXd& Q) const {
    const HeldProblem problem = held_problem(s, time, Q);
    return problem.A.completeOrthogonalDecomposition().solve(-problem.b);
  }
  // The accelerations with the held contacts kept (J a = -kappa: the same as M^-1 (Q + J^T lambda)
  // with held_multipliers' lambda), by the rows' null space: a = a_p + N z with a_p the rows'
  // minimum-norm solution, N orthogonal to them and z from N^T (M a - Q) = 0. Not through
  // Q + J^T lambda, whose terms cancel: a torque of 1e30 N mm held by an angle limit left round-off
  // of 1e17 rad/s^2 along the held row, which the adaptive integration then followed in steps of
  // 1e-13 s (a violent load held at a stop ran for hours).
  void held_accelerations(const State& s, double time, const double M[2][2], const double Q[2], double a[2]) const {
    const auto k = static_cast<Eigen::Index>(held.size());
    Eigen::MatrixXd J(k, 2);
    Eigen::VectorXd kappa(k);
    Eigen::Index widest = 0;
    for (Eigen::Index i = 0; i < k; ++i) {
      const HeldRow row = held_row(held[static_cast<std::size_t>(i)], s, time);
      J(i, 0) = row.J[0];
      J(i, 1) = row.J[1];
      kappa(i) = row.kappa;
      if (J.row(i).cwiseAbs().maxCoeff() > J.row(widest).cwiseAbs().maxCoeff()) widest = i;
    }
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J);
    const Eigen::Vector2d ap = cod.solve(-kappa);
    a[0] = ap(0);
    a[1] = ap(1);
    if (cod.rank() >= 2) return;   // the held rows fix both accelerations
    const double N[2] = {-J(widest, 1), J(widest, 0)};
    const double Ma[2] = {M[0][0] * ap(0) + M[0][1] * ap(1), M[1][0] * ap(0) + M[1][1] * ap(1)};
    const double num = N[0] * (Q[0] - Ma[0]) + N[1] * (Q[1] - Ma[1]);
    const double den = N[0] * (M[0][0] * N[0] + M[0][1] * N[1]) + N[1] * (M[1][0] * N[0] + M[1][1] * N[1]);
    a[0] += N[0] * (num / den);
    a[1] += N[1] * (num / den);
  }
  // The same over (s, psi, phi) with the free driver: a = a_p + N z, N the held rows' null space
  // (their SVD), z from N^T (M a - Q) = 0 (N^T M N is positive definite).
  Eigen::VectorXd held_accelerations(const State& s, double time) const {
    std::vector<HeldRow> rows;
    for (const Held& h : held) rows.push_back(held_row(h, s, time));
    const Eigen::MatrixXd J = jacobian(rows);
    Eigen::VectorXd kappa(J.rows());
    for (Eigen::Index i = 0; i < J.rows(); ++i) kappa(i) = rows[static_cast<std::size_t>(i)].kappa;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::VectorXd a = svd.solve(-kappa);
    const Eigen::Index rank = svd.rank(), n = coordinates();
    if (rank >= n) return a;
    const Eigen::MatrixXd N = svd.matrixV().rightCols(n - rank);
    const Eigen::MatrixXd M = mass_matrix(s);
    const Eigen::VectorXd z = (N.transpose() * M * N).ldlt().solve(N.transpose() * (forces(s) - M * a));
    return a + N * z;
  }
  void rhs(const State& s, State& ds, double time) const {
    ds[0] = s[2];
    ds[1] = s[3];
    ds[4] = s[5];
    ds[5] = 0;
    ds[6] = s[7];
    ds[7] = 0;
    ds[8] = 0;
    const bool friction = any_friction();
    if (free_driver != no_index || has_slider() || friction) {   // the free driver's and the slider's coordinates too
      Eigen::VectorXd a;
      double power = 0;   // friction's dissipation (session 64)
      if (held.empty()) a = inverse_mass(s) * forces(s);
      else if (friction) a = frictional_accelerations(s, time, &power);
      else a = held_accelerations(s, time);
      ds[2] = a(0);
      ds[3] = a(1);
      if (free_driver != no_index) ds[5] = a(2);
      if (has_slider()) {
        ds[7] = a(x_column());
        ds[8] = slider.damping * s[7] * s[7];   // the damping's work (dissipated)
      }
      if (damping > 0) ds[8] += damping * s[2] * s[2];   // the slide's damping's work
      if (friction) ds[8] += power;                        // friction's work
      return;
    }
    double M[2][2], Q[2], a[2];
    dynamics(s, M, Q);
    if (held.empty()) inverse_mass_times(s[0], Q, a);
    else held_accelerations(s, time, M, Q, a);
    ds[2] = a[0];
    ds[3] = a[1];
    if (damping > 0) ds[8] = damping * s[2] * s[2];   // the slide's damping's work (dissipated)
  }
  // Thrown by flight(.., capped) when the integration over its span needs more than flight_evaluations
  // right-hand sides: a load so violent (a torque of 10^100 N mm) that the part turns many times
  // within the span, which the adaptive stepper then follows in ever smaller steps for hours.
  struct FlightTooLong {};
  static constexpr long flight_evaluations = 60000;
  static constexpr double short_flight = 0x1p-20;
  State flight(const State& from, double span, double t0, bool capped = false) const {
    State s = from;
    if (span <= 0) return s;
    namespace ode = boost::numeric::odeint;
    auto stepper = ode::make_controlled(accuracy, accuracy, ode::runge_kutta_dopri5<State>());
    long evaluations = 0;
    // odeint's integrate_adaptive compares times absolutely (t1 - t0 > machine epsilon): a span
    // below 2.2e-16 s was not integrated at all (a follower that a torque of 10^30 N mm turns
    // within 10^-16 s stood still while the time ran on), and up to 2.2e-16 s of a short span was
    // left out. A short span is integrated in the scaled time u = tau / span, over [0, 1].
    const double scale = span < short_flight ? span : 1.0;
    ode::integrate_adaptive(
        stepper,
        [this, &evaluations, capped, scale, t0](const State& x, State& dx, double u) {
          if (capped && ++evaluations > flight_evaluations) throw FlightTooLong{};
          rhs(x, dx, t0 + u * scale);
          if (scale != 1.0)
            for (double& v : dx) v *= scale;
        },
        s, 0.0, span / scale, span / scale / 8);
    return s;
  }
  double potential(const State& s) const {
    const double c = std::cos(s[1]), sn = std::sin(s[1]);
    const double u[2] = {c * d[0] - sn * d[1], sn * d[0] + c * d[1]};
    const double X[2] = {c * cp[0] - sn * cp[1] + s[0] * u[0], sn * cp[0] + c * cp[1] + s[0] * u[1]};
    const double F[2] = {mass * g[0] + force[0], mass * g[1] + force[1]};
    const double own = -(F[0] * X[0] + F[1] * X[1]) - torque * s[1] +
                       0.5 * k_lin * (s[0] - rest_lin) * (s[0] - rest_lin) + 0.5 * k_tor * (s[1] - rest_tor) * (s[1] - rest_tor);
    double extra = free_driver == no_index ? 0.0 : -drivers[free_driver].torque * s[4];
    if (has_slider()) extra += -slider.load * s[6] + 0.5 * slider.k * (s[6] - slider.rest) * (s[6] - slider.rest);
    return free_driver == no_index && !has_slider() ? own : own + extra;
  }
  double energy_of(const State& s) const {
    double M[2][2], Q[2];
    dynamics(s, M, Q);
    double kinetic = 0.5 * (M[0][0] * s[2] * s[2] + 2 * M[0][1] * s[2] * s[3] + M[1][1] * s[3] * s[3]);
    if (free_driver != no_index) kinetic += 0.5 * drivers[free_driver].inertia * s[5] * s[5];
    if (has_slider()) kinetic += 0.5 * slider.mass * s[7] * s[7];
    return kinetic + potential(s);
  }
  std::string where(double time) const {
    std::ostringstream out;
    out << "simulation: at t = " << time / time_scale << " " << time_unit;
    return out.str();
  }
  // A step that left the run's energy beyond the doubles' range stops the run (session 66, as
  // the fixed-axis and planar simulators since session 65: it ended with exit 0 and "energy":
  // null), naming the moving parts (the pin-slot part, a torque-driven part, the translating
  // part) with their pointers and the largest velocity or load given (motion_datum.hpp).
  void check_energy() const {
    if (std::isfinite(energy_of(y))) return;
    std::ostringstream parts;
    const Part& pp = model.parts[part];
    parts << "pin-slot part '" << pp.name << "' (" << pp.pointer << "/dynamics, " << pp.pointer << "/initial; at slide "
          << y[0] << " mm, angle " << y[1] << " rad, moving at " << y[2] * time_scale << " mm/" << time_unit << " and "
          << y[3] * time_scale << " rad/" << time_unit << ")";
    if (free_driver != no_index) {
      const Part& dp = model.parts[drivers[free_driver].part];
      parts << ", part '" << dp.name << "' (" << dp.pointer << "/dynamics, " << dp.pointer << "/initial; at " << y[4]
            << " rad, moving at " << y[5] * time_scale << " rad/" << time_unit << ")";
    }
    if (has_slider()) {
      const Part& sp = model.parts[slider.part];
      parts << ", part '" << sp.name << "' (" << sp.pointer << "/dynamics, " << sp.pointer << "/initial; at " << y[6]
            << " mm, moving at " << y[7] * time_scale << " mm/" << time_unit << ")";
    }
    throw NumericError(simulation::energy_overflow_message(where(t), parts.str()) +
                       simulation::largest_motion_datum(model));
  }
  // The largest deviation (mm) of the pair's relative path from its straight chord over
  // [t0, t0 + h]: twice the midpoint's deviation (exact for a quadratic path) in the shift plus
  // the part's reach times the angle deviation (2 |dw| bounds the angle error). The chord's point
  // matched to the time t0 + tau h is the one at u = tau + bend tau (tau - 1) (session 66; |bend|
  // < 1 keeps it increasing; bend 0: u = tau, the straight time-matched chord as before): at the
  // midpoint u_m = 1/2 - bend/4. Where the chord at bend 0 does not fit, the bend whose midpoint
  // matches the path's angle coordinate w is tried (u_m = (w_m - w_0)/(w_1 - w_0) within [0.3,
  // 0.7]): a turn at a steady rate is linear in the angle, not in w = tan(theta/2), whose
  // curvature alone kept a chord about the cam's pivot within 2.7e-5 rad of the cam's turn;
  // `bend` is set to the one taken (0 when none fits).
  double chord_error(const Pair& p, const State& s0, const State& sm, const State& s1, double h, bool flip,
                     double* bend = nullptr) const {
    auto rel = [&](const State& s, double time) {
      const SlicedConfiguration c = relative(p, s, time);
      const double x = c.x.get_d(), yy = c.y.get_d();
      const double w = chart_w(c.angle, flip).get_d();
      return std::array<double, 3>{x, yy, w};
    };
    const auto a = rel(s0, t), m = rel(sm, t + h / 2), z = rel(s1, t + h);
    const double lever = 2 * (reach_at({&s0, &sm, &s1}) - part_reach + p.reach);
    auto error = [&](double um) {
      const double dx = m[0] - (a[0] + (z[0] - a[0]) * um), dy = m[1] - (a[1] + (z[1] - a[1]) * um);
      const double dw = m[2] - (a[2] + (z[2] - a[2]) * um);
      return 2 * (std::hypot(dx, dy) + lever * std::abs(dw));
    };
    if (bend) *bend = 0;
    const double straight = error(0.5);
    if (!bend || !(straight > delta / 2)) return straight;
    // the error is convex in u_m: its least value on [0.3, 0.7] (the w-matched midpoint, then a
    // ternary search: a part accelerating along a straight relative path is followed too)
    double um = 0.5, best = straight;
    if (z[2] != a[2]) {
      const double uw = std::clamp((m[2] - a[2]) / (z[2] - a[2]), 0.3, 0.7);
      if (const double e = error(uw); e < best) um = uw, best = e;
    }
    double lo = 0.3, hi = 0.7;
    for (int k = 0; k < 60 && !(best <= delta / 2); ++k) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      const double e1 = error(m1), e2 = error(m2);
      if (e1 < best) um = m1, best = e1;
      if (e2 < best) um = m2, best = e2;
      (e1 < e2 ? hi : lo) = e1 < e2 ? m2 : m1;
    }
    if (!(best <= delta / 2)) return straight;
    *bend = 2 - 4 * um;
    return best;
  }
  // The chord's parameter u at the step's fraction tau for a bend (chord_error), and back.
  static double chord_u(double bend, double tau) { return tau + bend * tau * (tau - 1); }
  static double chord_tau(double bend, double u) {
    if (bend == 0) return u;
    const double tau = 2 * u / ((1 - bend) + std::sqrt((1 - bend) * (1 - bend) + 4 * bend * u));
    return std::clamp(tau, 0.0, 1.0);
  }
  // A state beyond the part's own motion limits (a step that overshot them: the limits are
  // plastic stops, struck as impacts, so only an overshoot the bisection did not catch): the run
  // stops there (session 70: a SimulationLimit naming the part and the limit, the state
  // published the last step's; a GeometryError before).
  void check_limits(const State& s, double time) const {
    auto beyond = [&](const Part& p, const char* what, const char* symbol, double at, const RationalInterval& limits,
                      const char* unit, const std::string& pointer) {
      std::ostringstream out, limit;
      out << where(time) << ": " << what << " '" << p.name << "' leaves its " << (symbol[0] == 'p' ? "angle " : "")
          << (symbol[0] == 's' ? "slide " : "") << "limits (" << symbol << " = " << at << unit << "; " << pointer << ")";
      const bool upper = Rational(at) > limits.hi;
      limit << (upper ? "upper" : "lower") << " limit " << (upper ? limits.hi : limits.lo).get_d() << unit << " of ["
            << limits.lo.get_d() << ", " << limits.hi.get_d() << "]";
      throw SimulationLimit(out.str(), public_state.time, p.name, limit.str());
    };
    const Part& pp = model.parts[part];
    if (slide_limits && (Rational(s[0]) < slide_limits->lo || Rational(s[0]) > slide_limits->hi))
      beyond(pp, "pin-slot part", "s", s[0], *slide_limits, " mm", pp.motion.pointer + "/limits");
    if (angle_limits && (Rational(s[1]) < angle_limits->lo || Rational(s[1]) > angle_limits->hi))
      beyond(pp, "pin-slot part", "psi", s[1], *angle_limits, " rad", pp.motion.pointer + "/angle_limits");
    if (has_slider() && slider.limits && (Rational(s[6]) < slider.limits->lo || Rational(s[6]) > slider.limits->hi)) {
      const Part& sp = model.parts[slider.part];
      beyond(sp, "translating part", "x", s[6], *slider.limits, " mm", sp.motion.pointer + "/limits");
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
    public_state.rate.assign(model.parts.size(), 0.0);
    public_state.rate[part] = y[3] * time_scale;
    for (std::size_t i = 0; i < drivers.size(); ++i) {
      public_state.position[drivers[i].part] = driver_angle(i, y, t);
      public_state.rate[drivers[i].part] = driver_rate(i, y) * time_scale;
    }
    if (has_slider()) {
      public_state.position[slider.part] = y[6];
      public_state.rate[slider.part] = y[7] * time_scale;
    }
    public_state.pair_configurations.clear();
    for (const Pair& p : pairs) public_state.pair_configurations.push_back(about_pin(p, p.q));
    public_state.contacts.clear();
    if (!held.empty() && any_friction()) {   // (session 64) the frictional held set's multipliers at its states
      simulation::FrictionalSolution sol;
      frictional_accelerations(y, t, nullptr, &sol);
      const FrictionProblem fp = friction_problem(y, t);
      const simulation::HeldVerdict verdict = simulation::held_verdict(
          fp.G, fp.minv, fp.a0, fp.h, fp.friction, held_states(fp), {}, &force_count, nullptr, nullptr, &fp.full);
      for (std::size_t i = 0; i < held.size(); ++i) {
        const auto r = static_cast<Eigen::Index>(i);
        held[i].force = verdict.force_sign[i] == 0 ? 0.0 : sol.lambda(r);
        held[i].friction_force = fp.friction[i].on ? sol.f(r) : 0.0;
      }
    } else if (!held.empty()) {   // the forces at this state (the bilateral multipliers of the held set)
      // (a multiplier exactly 0 on the rows, the tie a contact stays held at, published as 0)
      const Eigen::VectorXd lambda = held_multipliers(y, t, forces(y));
      const std::vector<int> signs = simulation::held_force_signs(force_rows(y, t), &force_count);
      for (std::size_t i = 0; i < held.size(); ++i) held[i].force = signs[i] == 0 ? 0.0 : lambda(static_cast<Eigen::Index>(i));
    }
    for (const Held& h : held)
      public_state.contacts.push_back(
          PinSlotContact{h.limit ? no_index : pairs[h.pair].index, h.features.label, h.force / force_scale,
                         h.friction_force / force_scale});
  }
  // Are the parts of the pair certainly farther apart than d at configuration q (exact: every
  // edge box of the pin-slot part placed at q against every edge box of the other part)?
  // `skip`: edge pairs (the pin-slot part's edge, the other part's edge; flat indices in loop
  // order) left out: the held contacts' own edges, whose gap is the hold gap.
  bool apart(const Pair& p, const SlicedConfiguration& q, const Rational& d,
             const std::vector<std::pair<std::size_t, std::size_t>>& skip = {}) const {
    auto [c, sn] = cos_sin(q.angle);
    const Part& f = model.parts[part];
    std::size_t index = 0;
    for (const Loop& loop : f.loops)
      for (const Edge& e : loop.edges) {
        const std::size_t own = index++;
        const Box fb = edge_box(e, p.pivot, c, sn, q.x, q.y);
        std::optional<PlacedEdge> fe;
        for (std::size_t k = 0; k < p.other_boxes.size(); ++k) {
          if (std::find(skip.begin(), skip.end(), std::pair{own, k}) != skip.end()) continue;
          if (boxes_apart(fb, p.other_boxes[k], d)) continue;
          if (!fe) fe = placed_edge(e, p.pivot, c, sn, q.x, q.y);
          if (!edges_apart(*fe, p.other_edges[k], d)) return false;
        }
      }
    return true;
  }
  // The edge pairs the far test of pair `pi` leaves out: those of its held contacts between an
  // edge and an edge (segment or arc; not a vertex, which lies on two edges whose other
  // contacts the test must see), as flat indices (the pin-slot part's, the other part's).
  std::vector<std::pair<std::size_t, std::size_t>> held_edges(std::size_t pi) const {
    auto flat = [&](const FeatureIdentity& id) {
      const Part& owner = model.parts[id.part];
      std::size_t n = 0;
      for (std::size_t l = 0; l < id.loop; ++l) n += owner.loops[l].edges.size();
      return n + id.edge;
    };
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (const Held& h : held) {
      if (h.pair != pi || h.features.fixed.kind == FeatureKind::vertex || h.features.free.kind == FeatureKind::vertex)
        continue;
      out.emplace_back(flat(h.features.free), flat(h.features.fixed));
    }
    return out;
  }
  // A bound (double, from the speeds and accelerations at the states given) of how far any
  // point of the pin-slot part moves relative to the pair's other part over a step of length h.
  double travel(const Pair& p, std::initializer_list<std::pair<const State*, double>> states, double h) const {
    const std::size_t dr = driver_of[p.other];
    double omega = 0, arm = 0;
    if (dr != no_index) {
      omega = drivers[dr].free ? 0.0 : std::abs(drivers[dr].omega);
      const Point& C = model.parts[p.other].motion.pivot;
      arm = std::hypot(P[0] - C.x.get_d(), P[1] - C.y.get_d());
    }
    double out = 0;
    const double reach = reach_at(states);
    for (const auto& [s, time] : states) {
      State ds;
      rhs(*s, ds, time);
      double speed = std::abs((*s)[2]) + std::abs((*s)[3]) * reach + omega * (reach + arm);
      double gain = std::abs(ds[2]) + std::abs(ds[3]) * reach + (*s)[3] * (*s)[3] * reach;
      if (dr != no_index && drivers[dr].free) {   // the free driver's rate and acceleration at the state
        speed += std::abs((*s)[5]) * (reach + arm);
        gain += (std::abs(ds[5]) + (*s)[5] * (*s)[5]) * (reach + arm);
      }
      if (p.other == slider.part) {   // the slider's
        speed += std::abs((*s)[7]);
        gain += std::abs(ds[7]);
      }
      out = std::max(out, (speed + gain * h) * h);
    }
    return std::isfinite(out) ? out : std::numeric_limits<double>::max();
  }
  // A contact row's normal speed, exactly (session 60; docs/simulation.md, "The pin-slot
  // simulator's decisions, exact"): the coefficients a of the state's rates (s', psi', the free
  // driver's phi', the slider's x') and a constant-speed driver's surface speed v_other, exact
  // rationals from the kernels' exact contact frame at the pair's exact configuration carried into
  // the world by the driver's and the part's exact rotations (their half-angle tangents), the
  // normal not normalised (norm2 = |n|^2); the rates are the exact values of their doubles. The
  // normal speed is (a . rates - v_other) / |n|.
  struct ExactNormal {
    std::array<Rational, 4> a{Rational(0), Rational(0), Rational(0), Rational(0)};
    Rational v_other{0}, norm2{1};
    bool defined = false;
    Rational speed(const State& x) const {
      static constexpr int rate_of[4] = {2, 3, 5, 7};
      Rational out = -v_other;
      for (int k = 0; k < 4; ++k) {
        if (sgn(a[static_cast<std::size_t>(k)]) == 0) continue;
        const double v = x[static_cast<std::size_t>(rate_of[k])];
        if (!std::isfinite(v)) throw NumericError("a simulated rate of a pin-slot simulation is not finite");
        out += a[static_cast<std::size_t>(k)] * Rational(v);
      }
      return out;
    }
  };
  ExactNormal exact_normal(std::size_t pi, const SlicedContactFrame& cf) const {
    ExactNormal out;
    if (!cf.defined || (sgn(cf.normal.x) == 0 && sgn(cf.normal.y) == 0)) return out;
    const Pair& p = pairs[pi];
    Rational px = cf.point.x, py = cf.point.y, nx = cf.normal.x, ny = cf.normal.y;
    const Point& sd = model.parts[p.other].motion.direction;
    if (p.other == slider.part) {   // the slider's frame to the world: translated by x d
      if (!std::isfinite(y[6])) throw NumericError("the simulated offset of a translating part is not finite");
      const Rational x(y[6]);
      px += x * sd.x;
      py += x * sd.y;
    }
    const std::size_t dr = driver_of[p.other];
    const Point& C = model.parts[p.other].motion.pivot;
    if (dr != no_index) {   // the driver's frame to the world, by its exact rotation
      const auto [ca, sa] = cos_sin(exact_angle(driver_angle(dr, y, t)));
      const Rational rx = px - C.x, ry = py - C.y;
      px = C.x + ca * rx - sa * ry;
      py = C.y + sa * rx + ca * ry;
      const Rational mx = ca * nx - sa * ny, my = sa * nx + ca * ny;
      nx = mx;
      ny = my;
    }
    const auto [c, sn] = cos_sin(exact_angle(y[1]));
    const Point& dir = model.parts[part].motion.direction;
    const Point& pin = model.parts[part].motion.pivot;
    out.a[0] = nx * (c * dir.x - sn * dir.y) + ny * (sn * dir.x + c * dir.y);   // n . u
    out.a[1] = ny * (px - pin.x) - nx * (py - pin.y);                           // n . (k x (p - P))
    if (dr != no_index) {
      const Rational lever = ny * (px - C.x) - nx * (py - C.y);
      if (drivers[dr].free) out.a[2] = -lever;
      else out.v_other = lever * Rational(drivers[dr].omega);
    }
    if (p.other == slider.part) {
      out.a[3] = -(nx * sd.x + ny * sd.y);
      out.v_other = 0;
    }
    out.norm2 = nx * nx + ny * ny;
    out.defined = true;
    return out;
  }
  // A limit's row (unit normal: J = +-1, or +-size for the angle's), exactly from its doubles.
  static ExactNormal exact_limit(const HeldRow& row) {
    ExactNormal out;
    out.a[0] = Rational(row.J[0]);
    out.a[1] = Rational(row.J[1]);
    out.a[3] = Rational(row.g_x);
    out.defined = true;
    return out;
  }
  // A held contact's exact row at the current state (its contact frame at the pair's exact
  // configuration, which the kernels' formulas give away from touching too).
  ExactNormal exact_held(const Held& h) const {
    if (h.limit) return exact_limit(limit_row(h.limit, y));
    return exact_normal(h.pair, sliced_contact_frame(*pairs[h.pair].frame_model, h.features, pairs[h.pair].q));
  }
  // A touching feature pair's impact row at the current state: J (its normal speed is
  // J q' - v_other), the driver's surface speed along the normal, the world point and normal.
  // Against the free driver (`free`) J[2] is the row's phi column and v_other is 0.
  // Against the slider (`slider`) J[3] is the row's x column.
  struct Row {
    double J[4] = {0, 0, 0, 0}, v_other = 0, point[2] = {0, 0}, normal[2] = {0, 0};
    bool free = false, slider = false;
    double speed(const State& x) const {
      double v = J[0] * x[2] + J[1] * x[3];
      if (free) v += J[2] * x[5];
      if (slider) v += J[3] * x[7];
      return v - v_other;
    }
    std::string label;
    SlicedFeaturePair feature;
    std::size_t pair = 0;   // into pairs
    double restitution = 0;
    bool held = false;   // a held contact's row (plastic, no event)
    int limit = 0;       // a limit's row (Held::limit)
    ExactNormal exact;   // its normal speed, exactly (the hold and approach decisions)
  };
  // Does the row's contact separate faster than the rest speed at the current state (not held)?
  // Exact: a . v - v_other > rest |n| (squares and signs).
  bool separating(const Row& r) const {
    if (!r.exact.defined) return r.speed(y) > rest_speed;
    const Rational v = r.exact.speed(y);
    if (sgn(v) <= 0) return false;
    const Rational rest(rest_speed);
    return cmp(v * v, rest * rest * r.exact.norm2) > 0;
  }
  // Does it approach (a negative normal speed), exactly?
  bool approaching(const Row& r) const { return r.exact.defined ? sgn(r.exact.speed(y)) < 0 : r.speed(y) < 0; }
  std::vector<Row> contact_rows(std::size_t pi, const std::vector<SlicedFeaturePair>& features) const;
  // Newton impacts of the touching feature pairs at the current state (sequential impulses),
  // the held contacts plastic rows among them; the pairs left slower than the rest speed are held.
  // `hold_met`: the fresh contacts are held whatever their speed (advance: a contact met again at
  // the chord's start with nothing else changed, session 67)
  using Touching = std::vector<std::pair<std::size_t, std::vector<SlicedFeaturePair>>>;   // (pair, feature pairs)
  void impact(const Touching& touching, int limit = 0, bool hold_met = false);
  // (session 68, film68) An impact whose complementarity problem has no solution: is it a jam of
  // a constant-speed driver? Decided exactly on the rows' exact normals (Farkas): no velocity of
  // the free coordinates (s', psi', a torque-driven part's phi', the translating part's x') keeps
  // every row's normal speed a . rates - v_other >= 0 exactly when some y >= 0 has
  // sum y_i a_i = 0 and sum y_i v_other_i > 0 — the contacts of that combination lock the free
  // parts and the driver closes them. Throws the jam's NumericError naming the driver, the
  // locked part and those contacts (a limit by its label and pointer); returns where there is no
  // such combination (or a row has no exact normal). The state published before it throws is
  // the jam's (state(): the time and configuration where the contacts locked, their approach).
  // Exact on the simulated state (the rows at its pairs' exact configurations and the drivers'
  // exact angles, its rates' doubles); tried only where the doubles' problem fails (a jam they
  // solve within solve_lcp's tolerance is not looked for).
  void refuse_jam(const std::vector<Row>& rows);
  bool is_held(std::size_t pi, const SlicedFeaturePair& f) const {
    for (const Held& h : held)
      if (h.pair == pi && h.features.fixed == f.fixed && h.features.free == f.free) return true;
    return false;
  }
  // The held contacts' force problem at a state as the doubles give it (rows, mass matrix, loads,
  // velocity terms), whose multipliers' signs are decided exactly (held_force_sign.hpp; session 62:
  // until then a multiplier below -10^-9 of the loads counted as negative).
  simulation::HeldForceRows force_rows(const State& s, double time) const {
    simulation::HeldForceRows out;
    std::vector<HeldRow> rows;
    for (const Held& h : held) rows.push_back(held_row(h, s, time));
    out.J = jacobian(rows);
    out.kappa.resize(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) out.kappa(static_cast<Eigen::Index>(i)) = rows[i].kappa;
    out.M = mass_matrix(s);
    out.Q = forces(s);
    return out;
  }
  mutable simulation::HeldForceCount force_count;
  // Whether every held contact's point lies within both its features (the contact table's
  // validity: where it fails the contact has reached its edge's end), decided at the pair's exact
  // relative configuration of the state (held_extent.hpp: a certified interval filter, exact
  // rationals where it cannot decide). extent_exact counts those fallbacks.
  bool held_valid(const Held& h, const State& s, double time) const;
  mutable std::size_t extent_exact = 0;
  // Is every held contact's force non-negative and its point on its features at this state?
  bool held_conditions(const State& s, double time) const {
    if (held.empty()) return true;
    if (!finite(s)) return false;
    if (any_friction()) {
      // (session 64) the force signs and the stick limits exactly on the frictional rows at the
      // integrated states (friction.hpp's held_verdict: a force exactly 0 stays held, a friction
      // force exactly at mu_s N sticks), a slide's end by the exact sign of its tangential speed
      const FrictionProblem fp = friction_problem(s, time);
      if (!fp.G.allFinite() || !fp.a0.allFinite() || !fp.h.allFinite()) return false;
      const std::vector<int> states = held_states(fp);
      const simulation::HeldVerdict verdict = simulation::held_verdict(fp.G, fp.minv, fp.a0, fp.h, fp.friction, states,
                                                                       {}, &force_count, nullptr, nullptr, &fp.full);
      for (std::size_t i = 0; i < held.size(); ++i) {
        if (verdict.force_sign[i] < 0 || verdict.beyond_static[i]) return false;
        if ((states[i] == simulation::slip_positive || states[i] == simulation::slip_negative) &&
            states[i] * tangential_sign(fp.tangents[i], s) < 0)
          return false;
      }
      for (const Held& h : held)
        if (!held_valid(h, s, time)) return false;
      return true;
    }
    const simulation::HeldForceRows rows = force_rows(s, time);
    if (!rows.J.allFinite() || !rows.M.allFinite() || !rows.Q.allFinite() || !rows.kappa.allFinite()) return false;
    for (const int sign : simulation::held_force_signs(rows, &force_count))
      if (sign < 0) return false;
    for (const Held& h : held)
      if (!held_valid(h, s, time)) return false;
    return true;
  }
  // The state projected onto the held contacts: their gaps to the hold gap (Gauss-Newton,
  // mass-weighted) and their normal speeds to 0.
  // `clear`: contacts (not held) whose gaps the projection raises to the hold gap too (settle)
  State project(const State& s, double time, const std::vector<Held>& clear = {}) const;
  // Moves the state to its projection onto the held contacts, every pair's exact configuration
  // along a straight chord certified free by first_crossing.
  void settle();
  // At a step's start: held contacts past their edge's end leave (edge-end); when a held force
  // is negative the contact LCP decides which contacts lift off.
  void update_held();
  // update_held's decision with frictional contacts (session 64): the frictional contact LCP
  // (friction.hpp's solve_frictional, its stick limits exact) decides each contact's stick/slip
  // state and its lift-off (held_verdict's exact force signs, as the planar simulators' lift_offs)
  void update_friction();
  SimulationEvent held_event(SimulationEvent::Kind kind, const Held& h, const State& s, double time) const;
  bool advance(double span);
};

bool PinSlotSimulation::Impl::held_valid(const Held& h, const State& s, double time) const {
  if (h.limit) return true;
  if (!finite(s)) return false;
  const SlicedConfiguration q = relative(pairs[h.pair], s, time);
  simulation::ExtentPose<Rational> other, follower;   // the other part at its zero configuration
  auto [c, sn] = cos_sin(q.angle);
  follower.c = c;
  follower.s = sn;
  const Point& pivot = pairs[h.pair].pivot;   // the pair's configurations are about it
  follower.pivot = {pivot.x, pivot.y};
  follower.shift = {q.x, q.y};
  return simulation::contact_within_certified(other, h.fixed_exact, h.fixed_box, follower, h.free_exact, h.free_box,
                                              &extent_exact);
}

State PinSlotSimulation::Impl::project(const State& from, double time, const std::vector<Held>& clear) const {
  State s = from;
  if (held.empty()) return s;
  // the mass-weighted least correction dq with J dq = -r: -M^-1 J^T (J M^-1 J^T)^+ r (M^-1 of
  // (s, psi) as the 2 x 2 matrix without a free driver, as before session 59)
  auto correction = [&](const State& x, const Eigen::MatrixXd& J, const Eigen::VectorXd& r) -> Eigen::VectorXd {
    auto solve = [&](const auto& Mi) -> Eigen::VectorXd {
      return -Mi * J.transpose() * (J * Mi * J.transpose()).completeOrthogonalDecomposition().solve(r);
    };
    return coordinates() == 2 ? solve(inverse_mass2(x[0])) : solve(inverse_mass(x));
  };
  for (int iteration = 0; iteration < 2; ++iteration) {
    for (int pass = 0; pass < 8; ++pass) {
      std::vector<HeldRow> rows;
      for (const Held& h : held) rows.push_back(held_row(h, s, time));
      for (const Held& h : clear) rows.push_back(held_row(h, s, time));
      const auto k = static_cast<Eigen::Index>(rows.size());
      const Eigen::MatrixXd J = jacobian(rows);
      Eigen::VectorXd r(k);
      double worst = 0;
      for (Eigen::Index i = 0; i < k; ++i) {
        r(i) = rows[static_cast<std::size_t>(i)].g - hold_gap;
        if (static_cast<std::size_t>(i) >= held.size()) r(i) = std::min(r(i), 0.0);   // a clearance: at least the gap
        worst = std::max(worst, std::abs(r(i)));
      }
      if (worst <= 1e-3 * hold_gap) break;
      const Eigen::VectorXd dq = correction(s, J, r);
      s[0] += dq(0);
      s[1] += dq(1);
      if (free_driver != no_index) s[4] += dq(2);
      if (has_slider()) s[6] += dq(x_column());
    }
    // the normal speeds to 0
    std::vector<HeldRow> rows;
    for (const Held& h : held) rows.push_back(held_row(h, s, time));
    const auto k = static_cast<Eigen::Index>(rows.size());
    const Eigen::MatrixXd J = jacobian(rows);
    Eigen::VectorXd v(k);
    for (Eigen::Index i = 0; i < k; ++i) v(i) = rows[static_cast<std::size_t>(i)].speed(s);
    // (session 64) and a sticking contact's tangential speed to 0
    std::vector<Tangent> sticking;
    for (const Held& h : held)
      if (frictional(h) && h.decided && h.state == simulation::stick) sticking.push_back(held_tangent(h, s, time));
    if (sticking.empty()) {
      add_rates(s, correction(s, J, v));
      continue;
    }
    const auto m = static_cast<Eigen::Index>(sticking.size());
    Eigen::MatrixXd Jt(k + m, J.cols());
    Eigen::VectorXd vt(k + m);
    Jt.topRows(k) = J;
    vt.head(k) = v;
    for (Eigen::Index j = 0; j < m; ++j) {
      const Tangent& tg = sticking[static_cast<std::size_t>(j)];
      Jt.row(k + j) = tg.T.transpose();
      vt(k + j) = tg.T.dot(rates(s)) - tg.v_other;
    }
    add_rates(s, correction(s, Jt, vt));
  }
  return s;
}

std::optional<PinSlotSimulation::Impl::Held> PinSlotSimulation::Impl::clearance(std::size_t pi,
                                                                                  const SlicedFeaturePair& f) const {
  Held h = held_contact(pi, f);
  const double zero[4] = {0, 0, 0, 0};   // (held_poses reads a slider's rate too)
  const auto [pa, pb] = held_poses(h, y, t, zero);
  if (!feature_gap(pa, h.fixed_geometry, pb, h.free_geometry)) return std::nullopt;
  return h;
}

void PinSlotSimulation::Impl::settle() {
  // A contact within the hold gap that the projection moves the part into (session 59: the
  // follower's corner, touching the cam, struck its angle stop; the stop's projection onto its hold
  // gap turned the corner into the cam, a wedge) is projected out to the hold gap too (a clearance:
  // free, not held; the next step's chord meets it if it approaches), and the chords tested again.
  std::vector<Held> clear;
  State to_state;
  std::vector<SlicedConfiguration> to(pairs.size());
  for (bool kept = false; !kept;) {
    kept = true;
    to_state = project(y, t, clear);
    for (std::size_t i = 0; i < pairs.size() && kept; ++i) {
      to[i] = relative(pairs[i], to_state, t);
      const bool flip = std::abs(relative_angle(pairs[i], to_state, t)) > std::numbers::pi / 2;
      SlicedMotion motion{pairs[i].q, to[i], flip, {}};
      ++chords;
      const SlicedMotionCrossing c = pairs[i].space.first_crossing(motion, CrossingOptions{options.crossing_bits});
      bool fresh = false;
      for (const SlicedFeaturePair& f : c.features) {
        bool known = is_held(i, f);
        for (const Held& h : clear)
          known = known || (h.pair == i && h.features.fixed == f.fixed && h.features.free == f.free);
        if (known) continue;
        std::optional<Held> h = clearance(i, f);
        if (!h) continue;
        clear.push_back(std::move(*h));
        fresh = true;
      }
      if (c.status == CrossingStatus::crossing && fresh && clear.size() <= 4) {
        kept = false;
        continue;
      }
      if (c.status != CrossingStatus::none) {
        std::ostringstream out;
        out << where(t) << ": holding the contacts of '" << model.parts[part].name << "' moves it into '"
            << model.parts[pairs[i].other].name << "'"
            << (c.features.empty() ? std::string() : " (" + c.features.front().label + ")")
            << ": a held set the simulator cannot keep (docs/simulation.md)";
        throw NumericError(out.str());
      }
    }
  }
  settle_loss += energy_of(y) - energy_of(to_state);
  y = to_state;
  for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].q = to[i];
}

SimulationEvent PinSlotSimulation::Impl::held_event(SimulationEvent::Kind kind, const Held& h, const State& s,
                                                    double time) const {
  SimulationEvent ev;
  ev.kind = kind;
  ev.time = time / time_scale;
  ev.pair = h.limit ? no_index : pairs[h.pair].index;
  ev.first_part = model.parts[h.limit ? limit_part(h.limit) : pairs[h.pair].other].name;
  ev.second_part = model.parts[h.limit ? limit_part(h.limit) : part].name;
  ev.features = {h.features.label};
  ev.normal_force = h.force / force_scale;
  const HeldRow row = held_row(h, s, time);
  ev.normal_speed_after = row.speed(s) * time_scale;
  return ev;
}

void PinSlotSimulation::Impl::update_held() {
  if (held.empty()) return;
  // contacts past their edge's end leave
  for (std::size_t i = 0; i < held.size();) {
    if (held_valid(held[i], y, t)) {
      ++i;
      continue;
    }
    events.push_back(held_event(SimulationEvent::Kind::edge_end, held[i], y, t));
    held.erase(held.begin() + static_cast<std::ptrdiff_t>(i));
  }
  if (held.empty()) return;
  if (any_friction()) {
    update_friction();
    return;
  }
  // the force signs, exactly on the rows (the values published stay the doubles' multipliers, 0
  // where the exact sign is 0)
  const simulation::HeldForceRows rows = force_rows(y, t);
  const std::vector<int> signs = simulation::held_force_signs(rows, &force_count);
  const HeldProblem problem = held_problem(y, t, forces(y));
  const Eigen::VectorXd bilateral = problem.A.completeOrthogonalDecomposition().solve(-problem.b);
  if (std::none_of(signs.begin(), signs.end(), [](int sign) { return sign < 0; })) {
    for (std::size_t i = 0; i < held.size(); ++i)
      held[i].force = signs[i] == 0 ? 0.0 : std::max(bilateral(static_cast<Eigen::Index>(i)), 0.0);
    return;
  }
  // the contact LCP (lambda >= 0, w = A lambda + b >= 0, complementary) solved exactly on the same
  // rows for the contacts that stay; the doubles' LCP for the forces published
  const std::optional<std::vector<bool>> stays = simulation::held_after_lift_off(rows);
  const simulation::LcpSolution lcp = simulation::solve_lcp(problem.A, problem.b);
  std::vector<Held> kept;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const bool lifts = stays ? !(*stays)[i] : signs[i] < 0;
    held[i].force = lcp.solved && !lifts ? std::max(lcp.lambda(ii), 0.0) : 0.0;
    if (lifts) events.push_back(held_event(SimulationEvent::Kind::lift_off, held[i], y, t));
    else kept.push_back(held[i]);
  }
  held = std::move(kept);
}

void PinSlotSimulation::Impl::update_friction() {
  FrictionProblem fp = friction_problem(y, t);
  for (std::size_t i = 0; i < held.size(); ++i) {
    simulation::Friction& fr = fp.friction[i];
    if (!fr.on) continue;
    // sliding (decided) when faster than the rest speed or still sliding the way it slid; else
    // stick or slip is decided by the enumeration (a slide's end is located by bisection)
    // (held_friction.hpp's sliding_state; a contact not yet decided has no slide to keep)
    simulation::sliding_state(fr, fp.vt[i], rest_speed, held[i].decided ? held[i].state : simulation::frictionless);
    fp.full.friction[i].state = fr.state;
    fp.full.friction[i].decided = fr.decided;
  }
  const std::vector<std::size_t> own_groups;   // (each contact its own: stick limits decided exactly)
  const simulation::FrictionalSolution sol =
      simulation::solve_frictional(fp.G, fp.minv, fp.a0, fp.h, fp.friction, {}, false, &own_groups, &fp.full);
  if (!sol.solved)
    throw NumericError(where(t) + ": the contact problem of the held contacts of '" + model.parts[part].name +
                       "' has no consistent solution (a Painlevé-type inconsistency of Coulomb friction, or more "
                       "than 8 contacts)");
  const simulation::HeldVerdict verdict = simulation::held_verdict(fp.G, fp.minv, fp.a0, fp.h, fp.friction, sol.state,
                                                                   {}, &force_count, nullptr, nullptr, &fp.full);
  const std::vector<bool> lifts = simulation::lift_offs(sol, verdict);   // (held_friction.hpp)
  std::vector<Held> kept;
  bool sticks = false;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    Held h = held[i];
    const double lambda = sol.lambda(r);
    if (lifts[i]) {
      h.force = 0;
      events.push_back(held_event(SimulationEvent::Kind::lift_off, h, y, t));
      continue;
    }
    h.force = verdict.force_sign[i] == 0 ? 0.0 : std::max(lambda, 0.0);
    if (fp.friction[i].on) {
      const int state = sol.state[i];
      h.friction_force = sol.f(r);
      if (!h.decided || state != h.state) {
        h.state = state;
        SimulationEvent ev =
            held_event(state == simulation::stick ? SimulationEvent::Kind::stick : SimulationEvent::Kind::slip, h, y, t);
        ev.friction_force = h.friction_force / force_scale;
        if (state != simulation::stick) ev.slip_direction = state;
        const simulation::FrameRate f = held_frame(h, y, t);
        ev.point = {f.point[0], f.point[1]};
        ev.normal = {f.normal[0], f.normal[1]};
        events.push_back(std::move(ev));
        sticks = sticks || state == simulation::stick;
      }
      h.decided = true;
    }
    kept.push_back(std::move(h));
  }
  held = std::move(kept);
  // a contact that begins to stick keeps no sliding speed: removed by the projection (mass-weighted,
  // dissipative: settle_loss), its chord certified free as every projection's
  if (sticks) settle();
}

std::vector<PinSlotSimulation::Impl::Row> PinSlotSimulation::Impl::contact_rows(
    std::size_t pi, const std::vector<SlicedFeaturePair>& features) const {
  const Pair& p = pairs[pi];
  const Model& frame = *p.frame_model;
  const std::size_t dr = driver_of[p.other];
  const double phi = dr == no_index ? 0.0 : driver_angle(dr, y, t), omega = dr == no_index ? 0.0 : driver_rate(dr, y);
  const bool free = dr != no_index && drivers[dr].free;
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
    if (p.other == slider.part) {   // the slider's frame to the world: translated by x d; its column -n . d
      px += y[6] * slider.dir[0];
      py += y[6] * slider.dir[1];
    }
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
    // the driver's surface speed along n: omega n . (k x (p - C)); the free driver's column is
    // its negative per unit rate
    const double lever = nx * -(py - Cy) + ny * (px - Cx);
    if (free) {
      row.free = true;
      row.J[2] = -lever;
      row.v_other = 0;
    } else {
      row.v_other = omega * lever;
    }
    if (p.other == slider.part) {
      row.slider = true;
      row.J[3] = -(nx * slider.dir[0] + ny * slider.dir[1]);
      row.v_other = 0;
    }
    row.point[0] = px;
    row.point[1] = py;
    row.normal[0] = nx;
    row.normal[1] = ny;
    row.label = f.label;
    row.feature = f;
    row.pair = pi;
    row.restitution = p.restitution;
    row.exact = exact_normal(pi, cf);
    rows.push_back(row);
  }
  return rows;
}

void PinSlotSimulation::Impl::refuse_jam(const std::vector<Row>& rows) {
  // (session 69, jam69: the exact test shared with the planar simulators, simulation/jam.hpp:
  // a row's speed a . rates - v_other, so d = -v_other)
  // (session 70, stop70) d from the drivers' exact speeds: v_other is the exact lever times the
  // driver's rate double omega, so d = -(v_other / omega) times the model's exact speed — every
  // d over the same positive time scale, which leaves the verdict as it is. With the rates'
  // doubles two drivers' shares were in the ratio of their rounded speeds; a driver whose double
  // rate is 0 (an underflowed speed) leaves its share 0 and the verdict approximate.
  std::vector<std::vector<Rational>> a;
  std::vector<Rational> d;
  bool exact = true;
  for (const Row& r : rows) {
    if (!r.exact.defined) return;
    a.emplace_back(r.exact.a.begin(), r.exact.a.end());
    const std::size_t dr = r.limit != 0 || r.pair >= pairs.size() ? no_index : driver_of[pairs[r.pair].other];
    if (dr == no_index || drivers[dr].free || drivers[dr].omega == 0 || pairs[r.pair].other == slider.part) {
      exact = exact && !(dr != no_index && !drivers[dr].free && drivers[dr].omega == 0 && sgn(drivers[dr].speed) != 0);
      // (session 71, jam71) no driver's share here: exact_normal gives v_other (the lever times
      // the rate double, per internal time unit) only for a driven, not free part, which this
      // branch takes only at omega 0, where it is 0 exactly; a nonzero one would be a share in
      // internal time units next to the exact ones in the model's, so it is refused, not mixed
      if (sgn(r.exact.v_other) != 0) return;
      d.emplace_back(0);
      continue;
    }
    d.push_back(-(r.exact.v_other / Rational(drivers[dr].omega)) * drivers[dr].speed);
  }
  const std::optional<std::vector<std::size_t>> locked = simulation::locking_rows(a, d);
  if (!locked) return;
  std::vector<std::string> drivers_closing, contacts;   // every driver whose surface speed closes the combination
  for (const std::size_t i : *locked) {
    const Row& r = rows[i];
    if (!r.limit && sgn(r.exact.v_other) != 0) {
      const std::string& name = model.parts[pairs[r.pair].other].name;
      if (std::find(drivers_closing.begin(), drivers_closing.end(), name) == drivers_closing.end())
        drivers_closing.push_back(name);
    }
    contacts.push_back(r.label);
  }
  const std::string message =
      where(t) + ": " +
      simulation::jam_message(drivers_closing, true, {model.parts[part].name}, contacts.size(), contacts,
                              exact ? "decided exactly"
                                    : "approximate (found exactly on the exact contact normals and a driver's rate "
                                      "double, 0 for its nonzero speed)");
  publish();
  throw SimulationJam(message, t / time_scale, exact);
}

void PinSlotSimulation::Impl::impact(const Touching& touching, int limit, bool hold_met) {
  // (an impact's rows and exact speeds turn the state's doubles into rationals: a state made
  // infinite by a violent load stops here, with one message, not in GMP's mpq_set_d(inf))
  if (!finite(y)) throw NumericError(where(t) + ": the simulated state is not finite at an impact (a load too violent for the doubles)");
  std::vector<Row> rows;
  if (limit) {   // a slot end or angle limit struck: a plastic row of the part's own coordinate
    const HeldRow lr = limit_row(limit, y);
    Row row{};
    row.J[0] = lr.J[0];
    row.J[1] = lr.J[1];
    row.slider = lr.slider;
    row.J[3] = lr.g_x;
    row.v_other = 0;
    row.label = limit_label(limit);
    row.feature.label = row.label;
    row.pair = no_index;
    row.limit = limit;
    row.exact = exact_limit(lr);
    rows.push_back(row);
  }
  for (const auto& [pi, features] : touching) {
    std::vector<SlicedFeaturePair> fresh;
    for (const SlicedFeaturePair& f : features)
      if (!is_held(pi, f)) fresh.push_back(f);
    for (Row& r : contact_rows(pi, fresh)) rows.push_back(std::move(r));
  }
  if (rows.empty()) {
    const Pair& p = pairs[touching.front().first];
    std::ostringstream out;
    out << where(t) << ": the contact of '" << model.parts[p.other].name << "' and '" << model.parts[part].name
        << "' has no contact frame (a vertex meeting a vertex, or a held contact met again)";
    throw NumericError(out.str());
  }
  const std::size_t fresh_rows = rows.size();
  for (const Held& h : held) {   // the held contacts: plastic rows of the same impact
    const HeldRow hr = held_row(h, y, t);
    Row row{};
    row.J[0] = hr.J[0];
    row.J[1] = hr.J[1];
    if (hr.free) {
      row.free = true;
      row.J[2] = hr.g_phi;
    } else {
      row.v_other = -hr.g_phi * hr.omega;
    }
    row.slider = hr.slider;
    row.J[3] = hr.g_x;
    row.label = h.features.label;
    row.feature = h.features;
    row.pair = h.pair;
    row.limit = h.limit;
    row.held = true;
    row.exact = exact_held(h);
    rows.push_back(row);
  }
  const bool free = free_driver != no_index;
  const double inverse_inertia = free ? 1 / drivers[free_driver].inertia : 0.0;
  const double inverse_slider_mass = has_slider() ? 1 / slider.mass : 0.0;
  auto speed = [&](const Row& r) { return r.speed(y); };
  const double energy_before = energy_of(y);
  std::vector<double> before(rows.size()), total(rows.size(), 0.0);
  for (std::size_t i = 0; i < rows.size(); ++i) before[i] = speed(rows[i]);
  // whether a row approaches (its restitution applies), decided exactly on its doubles (session 68,
  // impact68: was the rounded speed's sign, before[i] < 0 — held_friction.hpp's approaches)
  std::vector<bool> approach(rows.size());
  // (session 68, impactpin68: the rows' speeds and restitution terms exactly on their doubles —
  // held_friction.hpp's exact_restitution_terms over [J, v_other] . [q', -1]: the speed
  // J q' - v_other with e = 1 on every row, the terms e v- on the approaching rows only)
  const auto row_count = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd g5(row_count, 5), u5(row_count, 5);
  Eigen::VectorXd restitutions(row_count);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const auto ii = static_cast<Eigen::Index>(i);
    g5.row(ii) << r.J[0], r.J[1], r.free ? r.J[2] : 0.0, r.slider ? r.J[3] : 0.0, r.v_other;
    u5.row(ii) << y[2], y[3], r.free ? y[5] : 0.0, r.slider ? y[7] : 0.0, -1.0;
    restitutions(ii) = r.restitution;
    approach[i] = simulation::approaches(g5.row(ii).transpose(), u5.row(ii).transpose());
  }
  // (each row its own velocity vector u5: a row's free or slider column is 0 where it has none)
  std::vector<Rational> speed_exact(rows.size()), restitution_exact(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const Eigen::MatrixXd gi = g5.row(ii);
    const Eigen::VectorXd ui = u5.row(ii).transpose();
    speed_exact[i] = simulation::exact_restitution_terms(gi, ui, Eigen::VectorXd::Ones(1), false)[0];
    restitution_exact[i] = simulation::exact_restitution_terms(gi, ui, restitutions.segment(ii, 1), true)[0];
  }
  // (session 64) a pair with friction: Coulomb impacts
  std::vector<double> tangential(rows.size(), 0.0);
  bool coulomb = false;
  for (const Row& r : rows) coulomb = coulomb || (!r.limit && pairs[r.pair].mu_static > 0);
  if (coulomb) {
    // Newton's restitution with Coulomb-limited tangential impulses (friction.hpp's frictional
    // LCP, every contact's stick or slip by enumeration; mu_s limits a sticking impulse, mu_k a
    // sliding one) in the coordinates z = L^T q of the mass matrix's Cholesky factor (there M is
    // the identity, friction.hpp's diagonal form): x the velocities after, w = G x + h with
    // h = e v- for an approaching row less the driver's surface speed; a held contact's row
    // plastic.
    const auto k = static_cast<Eigen::Index>(rows.size());
    const Eigen::Index n = coordinates();
    const Eigen::LLT<Eigen::MatrixXd> llt(mass_matrix(y));
    if (llt.info() != Eigen::Success)
      throw NumericError("the mass matrix of a pin-slot simulation is not positive definite in doubles (its masses and "
                         "moments of inertia too far apart)");
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(k, n);
    Eigen::VectorXd hv(k);
    std::vector<simulation::Friction> friction(rows.size());
    std::vector<Eigen::VectorXd> tangents(rows.size());   // over the coordinates (q)
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const auto ii = static_cast<Eigen::Index>(i);
      G(ii, 0) = r.J[0];
      G(ii, 1) = r.J[1];
      if (free) G(ii, 2) = r.free ? r.J[2] : 0.0;
      if (has_slider()) G(ii, x_column()) = r.slider ? r.J[3] : 0.0;
      hv(ii) = -r.v_other + (approach[i] ? r.restitution * before[i] : 0.0);
      if (r.limit || !(pairs[r.pair].mu_static > 0)) continue;
      const Tangent tangent = r.held ? held_tangent(held[i - fresh_rows], y, t) : tangent_at(r.pair, r.point, r.normal, y);
      friction[i] = friction_of(llt, G.row(ii).transpose(), tangent, pairs[r.pair]);
      friction[i].bias = -tangent.v_other;
      tangents[i] = tangent.T;
    }
    const Eigen::MatrixXd Gz = llt.matrixL().solve(G.transpose()).transpose();
    const Eigen::VectorXd vz = llt.matrixU() * rates(y);
    // Newton's restitution with Coulomb friction can create energy where the normal and tangent
    // rows couple (Kane and Levinson): where the kinetic energy (|x|^2 / 2 in these coordinates)
    // would grow and no constant-speed driver takes part (a driver may do work), the restitution
    // is scaled down to the largest factor (bisection, 2^-30) whose impact creates none, as the
    // planar simulators' frictional_impact (held_friction.hpp's restitution_limited)
    Eigen::VectorXd restitution_part = Eigen::VectorXd::Zero(k), offsets = Eigen::VectorXd::Zero(k);
    bool driven = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      offsets(ii) = -rows[i].v_other;
      restitution_part(ii) = hv(ii) - offsets(ii);
      driven = driven || rows[i].v_other != 0 || (friction[i].on && friction[i].bias != 0);
    }
    // (session 67, impact67: the impulses' Coulomb conditions decided exactly on these rows;
    // session 68, impactpin68: on the exact velocity terms -v_other + scale e v-; session 70,
    // exact70: on the full form, below — the Cholesky rows' doubles are only its filter since
    // session 71, exact71)
    const Eigen::VectorXd unit = Eigen::VectorXd::Ones(n);
    // (session 70, exact70: the impulses decided exactly on the full form — the rows G and T over
    // the coordinates, M itself, Q = 0 so that x is the velocities' change, the normal rows'
    // constants G q'- - v_other + scale e v- and the tangent rows' T q'- - v_other exact: held_friction.hpp's
    // full_form_impulses, the Cholesky rows' doubles solution its filter (its held set and states
    // confirmed there, else every assignment decided there); until then every decision was exact
    // on the Cholesky rows' doubles Gz = G L^-T, vz = L^T q'-, each rounded)
    simulation::FullMass full;
    full.G = G;
    full.M = mass_matrix(y);
    full.Q = Eigen::VectorXd::Zero(n);
    full.friction = friction;
    const Eigen::VectorXd velocities = rates(y);
    std::vector<Rational> tangent_exact(rows.size(), Rational(0));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!friction[i].on) continue;
      full.friction[i].T = tangents[i];
      full.friction[i].bias = 0;
      Rational constant = simulation::held_force_detail::exact_value(friction[i].bias);   // -v_other
      for (Eigen::Index j = 0; j < n; ++j)
        if (tangents[i](j) != 0)
          constant += simulation::held_force_detail::exact_value(tangents[i](j)) *
                      simulation::held_force_detail::exact_value(velocities(j));
      tangent_exact[i] = constant;
    }
    auto full_terms = [&](double scale) {
      std::vector<Rational> h_exact(rows.size());
      const Rational s = simulation::held_force_detail::exact_value(scale);
      for (std::size_t i = 0; i < rows.size(); ++i) h_exact[i] = speed_exact[i] + s * restitution_exact[i];
      return h_exact;
    };
    // (session 71, exact71, review70 M2: the filter in doubles only — solve_frictional without its
    // exact mode; until then frictional_impulses, whose exact decisions on the Cholesky rows were
    // taken and then taken again on the full form: the full form's is the one exact decision)
    auto solve = [&](double scale) {
      const simulation::FrictionalSolution filter =
          simulation::solve_frictional(Gz, unit, vz, offsets + scale * restitution_part, friction);
      return simulation::full_form_impulses(filter, full, full_terms(scale), tangent_exact);
    };
    // (session 69, exact69: whether the impact creates kinetic energy decided exactly; session 70,
    // exact70: on M and the exact change of the velocities, 2 q'-^T M dq' + dq'^T M dq' > 0 —
    // held_friction.hpp's kinetic_grows; until then |x|^2 > |vz|^2 on the Cholesky coordinates)
    auto creates = [&](const simulation::FrictionalSolution& s, double) {
      return simulation::kinetic_grows(full.M, velocities, s.x_exact);
    };
    bool limited = false;
    simulation::FrictionalSolution sol = driven ? solve(1) : simulation::restitution_limited(solve, creates, limited);
    if (!sol.solved) {
      refuse_jam(rows);
      std::ostringstream out;
      // (session 71, exact71: the words of a verdict only where the exact search was complete)
      if (sol.exhausted)
        out << where(t) << ": the frictional impact of '" << model.parts[part].name << "' on " << rows.size()
            << " contacts has no consistent solution (a Painlevé-type inconsistency of Coulomb friction; "
            << rows.front().label << ")";
      else
        out << where(t) << ": no consistent solution was found for the frictional impact of '"
            << model.parts[part].name << "' on " << rows.size()
            << " contacts (" << simulation::incomplete_frictional_search << "; " << rows.front().label << ")";
      throw NumericError(out.str());
    }
    // (session 70, exact70: the velocities after q'- + dq' with the exact change, rounded once;
    // until then L^-T x of the Cholesky coordinates' rounded solution)
    const Eigen::VectorXd after = simulation::exact_sum(velocities, sol.x_exact);
    y[2] = after(0);
    y[3] = after(1);
    if (free) y[5] = after(2);
    if (has_slider()) y[7] = after(x_column());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      total[i] = std::max(sol.lambda(static_cast<Eigen::Index>(i)), 0.0);
      tangential[i] = friction[i].on ? sol.f(static_cast<Eigen::Index>(i)) : 0.0;
    }
  } else {
    // Newton's law over every row at once, the contact LCP: lambda >= 0, w = A lambda + b >= 0,
    // lambda w = 0, with A = J M^-1 J^T and b = (1 + e) v for an approaching row (v otherwise):
    // w is the row's speed after less e times its approach (src/simulation/lcp.hpp)
    const auto k = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd A(k, k);
    Eigen::VectorXd bv(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const Row& ri = rows[static_cast<std::size_t>(i)];
      double mj[2];
      inverse_mass_times(y[0], ri.J, mj);
      for (Eigen::Index j = 0; j < k; ++j) {
        const Row& rj = rows[static_cast<std::size_t>(j)];
        A(i, j) = rj.J[0] * mj[0] + rj.J[1] * mj[1];
        if (free) A(i, j) += rj.J[2] * ri.J[2] * inverse_inertia;
        if (has_slider()) A(i, j) += rj.J[3] * ri.J[3] * inverse_slider_mass;
      }
      const double v = before[static_cast<std::size_t>(i)];
      bv(i) = approach[static_cast<std::size_t>(i)] ? (1 + ri.restitution) * v : v;
    }
    simulation::LcpSolution lcp = simulation::solve_lcp(A, bv);
    // (session 68, impactpin68: which rows get an impulse decided exactly — held_friction.hpp's
    // exact_impact_lcp on the full form: the rows G over the coordinates, the mass matrix M as
    // its doubles, w = G M^-1 G^T lambda + (v + e v-) with the speeds and terms exact; until then
    // the doubles' A (the rounded M^-1) and b = (1 + e) v decided, with solve_lcp's tolerance)
    const Eigen::Index n = coordinates();
    simulation::FullMass full;
    std::vector<Rational> change;   // M^-1 G^T lambda, exactly (session 69, exact69)
    {
      full.G = Eigen::MatrixXd::Zero(k, n);
      for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const auto ii = static_cast<Eigen::Index>(i);
        full.G(ii, 0) = r.J[0];
        full.G(ii, 1) = r.J[1];
        if (free) full.G(ii, 2) = r.free ? r.J[2] : 0.0;
        if (has_slider()) full.G(ii, x_column()) = r.slider ? r.J[3] : 0.0;
      }
      full.M = mass_matrix(y);
      full.Q = Eigen::VectorXd::Zero(n);
      full.friction.assign(rows.size(), simulation::Friction{});
      std::vector<Rational> b_exact(rows.size());
      for (std::size_t i = 0; i < rows.size(); ++i) b_exact[i] = speed_exact[i] + restitution_exact[i];
      const Eigen::VectorXd none = Eigen::VectorXd::Zero(n);
      if (const std::optional<simulation::FrictionalSolution> exact =
              simulation::exact_impact_lcp(full.G, none, none, b_exact, lcp, &full)) {
        lcp.solved = exact->solved;
        if (exact->solved) {
          lcp.lambda = exact->lambda;
          change = exact->x_exact;   // (Q = 0: x = M^-1 G^T lambda, the exact impulses')
        }
      }
    }
    if (!lcp.solved) {
      refuse_jam(rows);
      std::ostringstream out;
      out << where(t) << ": the impact of '" << model.parts[part].name << "' on " << rows.size()
          << " contacts has no solution of its complementarity problem (" << rows.front().label << ")";
      throw NumericError(out.str());
    }
    // (session 69, exact69: where the exact decision published the impulses — the doubles' held
    // set not the exact one, or their impulses off by more than 2^-40 — they are applied exactly,
    // q'+ = q'- + M^-1 G^T lambda in rationals on the full form's M and G (the exact solution's own
    // x), the velocities after rounded once; until then the rounded exact impulses went through
    // the rounded M^-1, rounded at every product and sum. Where the doubles' solution is kept (it
    // agrees with the exact one) it is applied as before: output identity.)
    const Eigen::Matrix2d Minv = inverse_mass2(y[0]);   // (by the Schur complement: never det M)
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double lambda = lcp.lambda(static_cast<Eigen::Index>(i));
      if (!(lambda > 0)) continue;
      const Row& r = rows[i];
      total[i] = lambda;
      if (!change.empty()) continue;
      y[2] += (Minv(0, 0) * r.J[0] + Minv(0, 1) * r.J[1]) * lambda;
      y[3] += (Minv(1, 0) * r.J[0] + Minv(1, 1) * r.J[1]) * lambda;
      if (free) y[5] += r.J[2] * inverse_inertia * lambda;
      if (has_slider()) y[7] += r.J[3] * inverse_slider_mass * lambda;
    }
    if (!change.empty()) {
      const Eigen::VectorXd after = simulation::exact_sum(rates(y), change);
      y[2] = after(0);
      y[3] = after(1);
      if (free) y[5] = after(2);
      if (has_slider()) y[7] = after(x_column());
    }
  }
  impact_loss += energy_before - energy_of(y);
  for (std::size_t i = 0; i < fresh_rows; ++i) {
    if (total[i] <= 0) continue;
    SimulationEvent ev;
    ev.kind = SimulationEvent::Kind::impact;
    ev.time = t / time_scale;
    ev.pair = rows[i].limit ? no_index : pairs[rows[i].pair].index;
    ev.first_part = model.parts[rows[i].limit ? limit_part(rows[i].limit) : pairs[rows[i].pair].other].name;
    ev.second_part = model.parts[rows[i].limit ? limit_part(rows[i].limit) : part].name;
    ev.features = {rows[i].label};
    ev.impulse = total[i] / (force_scale * time_scale);
    ev.tangential_impulse = tangential[i] / (force_scale * time_scale);
    ev.normal_speed_before = -before[i] * time_scale;
    ev.normal_speed_after = speed(rows[i]) * time_scale;
    ev.point = {rows[i].point[0], rows[i].point[1]};
    ev.normal = {rows[i].normal[0], rows[i].normal[1]};
    events.push_back(std::move(ev));
  }
  // a held contact the impact left separating faster than the rest speed is free again
  for (std::size_t i = fresh_rows, k = 0; i < rows.size(); ++i) {
    if (!separating(rows[i])) {
      ++k;
      continue;
    }
    events.push_back(held_event(SimulationEvent::Kind::lift_off, held[k], y, t));
    held.erase(held.begin() + static_cast<std::ptrdiff_t>(k));
  }
  // the new contacts left slower than the rest speed are held (sustained contact)
  bool added = false;
  for (std::size_t i = 0; i < fresh_rows; ++i) {
    if (separating(rows[i]) && !hold_met) continue;
    if (rows[i].limit) {
      Held h;
      h.pair = no_index;
      h.limit = rows[i].limit;
      h.features.label = rows[i].label;
      held.push_back(std::move(h));
      added = true;
      events.push_back(held_event(SimulationEvent::Kind::contact, held.back(), y, t));
      continue;
    }
    const Pair& p = pairs[rows[i].pair];
    Held h = held_contact(rows[i].pair, rows[i].feature);
    const double zero[4] = {0, 0, 0, 0};   // (held_poses reads a slider's rate too)
    const auto [pa, pb] = held_poses(h, y, t, zero);
    if (!feature_gap(pa, h.fixed_geometry, pb, h.free_geometry)) {
      std::ostringstream out;
      out << where(t) << ": the contact of '" << model.parts[p.other].name << "' and '" << model.parts[part].name
          << "' (" << rows[i].label << ") would have to be sustained, and a pin-slot part holds no contact of "
          << "these feature kinds (a segment on a concave arc, two concave arcs; docs/simulation.md)";
      throw NumericError(out.str());
    }
    held.push_back(std::move(h));
    added = true;
    SimulationEvent ev = held_event(SimulationEvent::Kind::contact, held.back(), y, t);
    ev.point = {rows[i].point[0], rows[i].point[1]};
    ev.normal = {rows[i].normal[0], rows[i].normal[1]};
    events.push_back(std::move(ev));
  }
  if (added || !held.empty()) settle();
}

bool PinSlotSimulation::Impl::advance(double span) {
  const double pi = std::numbers::pi;
  update_held();
  double h = std::min(span, step_guess > 0 ? step_guess : span);
  if (options.max_step > 0) h = std::min(h, options.max_step * time_scale);
  if (forced_step > 0) h = std::min(h, forced_step);
  // The part reaches a slot end or angle limit within [0, reached] of the step from y: the last
  // state inside by bisection (to 2^-30 of the span), where the limit is struck at the end of a
  // forced step. Only for a step that fits its chords and whose end (or first contact) lies beyond
  // the limit, so that limits beyond the motion change nothing (not a trial step's overshoot).
  // False when a flight is too long or the state beyond is not finite (a load too violent for the
  // span: a shorter step). Every flight of a step is capped (flight_evaluations).
  // The bisection tests the very states a step of that length computes (two half flights, then
  // the projection onto the held contacts): a single flight differs from them by the integration's
  // error, which at a high rate carried the forced step's end past the stop it was cut at.
  auto beyond_limit = [&](double span) {
    const State half = flight(y, span / 2, t, true);
    const State whole = flight(half, span / 2, t + span / 2, true);
    if (!finite(half) || !finite(whole)) return -1;
    const int beyond = outside_limit(whole);
    return beyond ? beyond : outside_limit(project(whole, t + span));
  };
  auto locate_limit = [&](double reached) {
    double lo = 0, hi = reached;
    int beyond = 0;
    try {
      while (hi - lo > 0x1p-30 * reached) {
        const double m = (lo + hi) / 2;
        (beyond_limit(m) != 0 ? hi : lo) = m;
      }
      beyond = beyond_limit(hi);
    } catch (const FlightTooLong&) {
      return false;
    }
    if (beyond <= 0) return false;
    pending_limit = beyond;
    forced_step = lo;
    return true;
  };
  // The limit located at the step's start (lo = 0: the state is within the bisection's resolution,
  // 2^-30 of the step, of the limit it approaches) is struck there, without a step. Until session
  // 60 the zero forced step read as "the step size underflows": a follower spun at 1e15 rad/s and
  // more bouncing between its angle stop and the cam came within one unit in the last place of
  // the stop (the rate times 2^-30 of the step exceeds it) and stopped the run.
  auto strike_at_start = [&]() {
    if (forced_step > 0 || !pending_limit) return false;
    const int limit = pending_limit;
    pending_limit = 0;
    impact({}, limit);
    return true;
  };
  for (int attempt = 0;; ++attempt) {
    if (attempt > 2000 || !(h > 0))
      throw NumericError(where(t) + ": no chord within the chord deviation (the step size underflows)");
    // a step too long for a violent load (a torque of 10^100 N mm) overflows or turns the part many
    // times: shorter steps reach the limits, where the part stops
    State mid, unprojected;
    try {
      mid = flight(y, h / 2, t, true);
      unprojected = flight(mid, h / 2, t + h / 2, true);
    } catch (const FlightTooLong&) {
      h /= 2;
      continue;
    }
    if (!finite(mid) || !finite(unprojected)) {
      h /= 2;
      continue;
    }
    if (!held.empty() && h != forced_step && !held_conditions(unprojected, t + h)) {
      // a held contact's force turns negative or its point leaves its feature within the step:
      // the first such time by bisection (to 2^-30 of the step); the next step's start decides
      double lo = 0, hi = h;
      try {
        while (hi - lo > 0x1p-30 * h) {
          const double m = (lo + hi) / 2;
          (held_conditions(flight(y, m, t, true), t + m) ? lo : hi) = m;
        }
      } catch (const FlightTooLong&) {
        h /= 2;
        continue;
      }
      forced_step = h = hi;
      continue;
    }
    const State end = project(unprojected, t + h);
    // the far test: a pair whose features are certainly farther apart than twice the step's
    // travel bound (plus delta) is free over the step without a chord
    std::vector<bool> far(pairs.size(), false), flips(pairs.size(), false);
    std::vector<double> bends(pairs.size(), 0.0);   // each chord's bend (chord_error)
    std::vector<SlicedConfiguration> to(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) to[i] = relative(pairs[i], end, t + h);
    // the step's fraction at pair i's chord parameter u, and the parameter at a fraction (exact
    // and the identity for a chord without a bend; a bent chord's in doubles, as its estimate)
    auto time_of = [&](std::size_t i, const Rational& u) {
      return bends[i] == 0 ? u : Rational(chord_tau(bends[i], u.get_d()));
    };
    auto u_at = [&](std::size_t i, const Rational& tau) {
      return bends[i] == 0 ? tau : Rational(chord_u(bends[i], tau.get_d()));
    };
    bool fits = true;
    for (std::size_t i = 0; i < pairs.size() && fits; ++i) {
      const double reach_i = travel(pairs[i], {{&y, t}, {&mid, t + h / 2}, {&end, t + h}}, h);
      if (reach_i < std::numeric_limits<double>::max() / 4) {
        // (and the end configuration's boundaries exactly apart: certified, whatever the bound)
        // (a held contact's own edges are kept at the hold gap: left out of the distance bound,
        // and the end configuration's boundaries, theirs included, exactly apart)
        far[i] = apart(pairs[i], pairs[i].q, Rational(2 * reach_i + delta), held_edges(i)) &&
                 apart(pairs[i], to[i], Rational(0));
      }
      if (far[i]) continue;
      // a chord turns the relative angle by at most pi/4 (it stays inside one chart) and lies
      // within delta/2 of the path
      const double a0 = relative_angle(pairs[i], y, t), a1 = relative_angle(pairs[i], end, t + h);
      const double am = relative_angle(pairs[i], mid, t + h / 2);
      if (std::abs(wrap(a1 - a0)) > pi / 4 || std::abs(wrap(am - a0)) > pi / 4) fits = false;
      // and unwrapped (session 67): the wrapped differences alias whole turns — a cam at constant
      // speed whose step's half spans exactly one turn has the same relative angle at the step's
      // start, middle and end, and its chord (of zero length) tunnelled through the follower (a
      // step-size rule in doubles, as the wrapped one: what certifies the step is the exact test of
      // the chord, which must follow the motion — not a verdict of its own)
      if (fits && (std::abs(turned(pairs[i], end, t + h) - turned(pairs[i], y, t)) > pi / 4 ||
                   std::abs(turned(pairs[i], mid, t + h / 2) - turned(pairs[i], y, t)) > pi / 4))
        fits = false;
      flips[i] = std::abs(am) > pi / 2;
      // the chart about the half turn excludes theta = 0 at either end, the chart about 0 the half turn
      if (fits && flips[i] && (std::abs(a0) < pi / 8 || std::abs(a1) < pi / 8)) fits = false;
      if (fits && !flips[i] && (std::abs(a0) > 7 * pi / 8 || std::abs(a1) > 7 * pi / 8)) fits = false;
      if (fits && chord_error(pairs[i], y, mid, end, h, flips[i], &bends[i]) > delta / 2) fits = false;
    }
    if (!fits) {
      h /= 2;
      continue;
    }
    // the chords of this step, tested exactly
    std::size_t first = no_index;
    SlicedMotionCrossing earliest;
    std::vector<std::optional<SlicedMotionCrossing>> crossings(pairs.size());
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
      if (c.status == CrossingStatus::crossing &&
          (first == no_index || time_of(i, c.u_lower) < time_of(first, earliest.u_lower))) {
        first = i;
        earliest = c;
      }
      if (c.status == CrossingStatus::crossing) crossings[i] = std::move(c);
    }
    if (first == no_index) {
      if (!(h == forced_step && pending_limit) && (outside_limit(unprojected) || outside_limit(end))) {
        h = locate_limit(h) ? forced_step : h / 2;
        if (strike_at_start()) return true;
        continue;
      }
      check_limits(end, t + h);
      y = end;
      t += h;
      for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].q = to[i];
      step_guess = 2 * h;
      const int limit = h == forced_step ? pending_limit : 0;
      forced_step = 0;
      pending_limit = 0;
      if (limit) {
        impact({}, limit);
        return true;
      }
      return false;
    }
    // the first contact: every pair's state is its chord's point at the crossing's free side
    std::vector<SlicedConfiguration> kept;
    for (const Pair& p : pairs) kept.push_back(p.q);
    const Rational u = time_of(first, earliest.u_lower);   // the step's fraction at the first crossing
    const double hc = h * u.get_d();
    State at;
    try {
      at = flight(y, hc, t, true);
    } catch (const FlightTooLong&) {
      h /= 2;
      continue;
    }
    if (!finite(at)) {
      h /= 2;
      continue;
    }
    if (outside_limit(at)) {   // the limit comes before the first contact
      h = locate_limit(hc) ? forced_step : h / 2;
      if (strike_at_start()) return true;
      continue;
    }
    check_limits(at, t + hc);
    // the pairs touching together: their crossings within the first one's bounds (several
    // contacts of one impact, e.g. a face landing on two supports at once)
    Touching touching;
    const Rational u_upper = time_of(first, earliest.u_upper);
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if (crossings[i] && (i == first || time_of(i, crossings[i]->u_lower) <= u_upper ||
                           u_at(i, u) >= crossings[i]->u_lower))
        touching.emplace_back(i, crossings[i]->features);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (!far[i]) {
        // (every pair's configuration on its chord at or before its first crossing: free)
        const Rational ui = i == first ? earliest.u_lower : u_at(i, u);
        pairs[i].q = crossings[i] && crossings[i]->u_lower <= ui ? crossings[i]->before
                                                                  : chord_point(pairs[i].q, to[i], flips[i], ui);
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
    const State y_kept = y;
    const double t_kept = t;
    y = at;
    t += hc;
    // a chord that cuts the corner of a path touching and departing meets a contact the path
    // leaves at once (no feature pair approaching): a shorter chord deviates less (delta ~ h^2)
    bool closing = false;
    for (const auto& [pi, features] : touching)
      for (const Row& r : contact_rows(pi, features))
        closing = closing || approaching(r);
    if (!closing && h > 1e-9 * std::max(t, h) && attempt < 1900) {
      y = y_kept;
      t = t_kept;
      for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].q = kept[i];
      h /= 4;
      continue;
    }
    // A contact met at the chord's very start (hc = 0: the state and the time as they were) that
    // no row approaches and that separates by the exact test, with no contact held: the impact
    // below would change nothing (no impulse, nothing held, no settling) and every later step
    // would meet it again, at every step length. Seen in session 67 (filmstall67) on a two-turn
    // film advance (the cam at constant speed, no loads: the rest speed is 0): the cam's plastic
    // impact on the window's top left the normal speed at +1.6e-14 mm/s (the doubles' rounding),
    // "separating", so nothing was held, while the cam kept pushing the window (the path's
    // configuration inside the cam's C-obstacle, the chord's exact one at its boundary); 10000
    // steps stayed at t = 0.856661 s. Such a contact is held (plastic: settle() projects onto its
    // hold gap along an exactly tested chord; the next step decides its force's sign exactly and
    // lifts it off if negative).
    bool hold_met = held.empty() && hc == 0;
    for (const auto& [pi, features] : touching)
      for (const Row& r : contact_rows(pi, features))
        hold_met = hold_met && separating(r);
    step_guess = std::max(h, 1e-12);
    forced_step = 0;
    pending_limit = 0;
    impact(touching, 0, hold_met);
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
    if (p.motion.kind == Motion::Kind::translation) {
      // a translating part pushed by the pin-slot part (session 59: the film): its offset joins
      // (s, psi); mass, a constant force, gravity, a spring and viscous damping to the frame
      for (const SimulationSpec::Driver& d : spec.drivers)
        if (d.part == i)
          throw ModelError(d.pointer, "part '" + p.name + "': beside a pin-slot part a translating part moves by its "
                                                          "own dynamics (no driver)");
      if (s.has_slider())
        throw ModelError(p.pointer + "/motion", "part '" + p.name + "': the pin-slot simulator moves one translating "
                                                    "part ('" + model.parts[s.slider.part].name + "' is one)");
      if (!p.dynamics || !p.dynamics->mass || !(sgn(*p.dynamics->mass) > 0))
        throw ModelError(p.pointer + "/dynamics", "translating part '" + p.name + "' beside a pin-slot part needs a "
                                                      "positive \"mass\"");
      const Dynamics& dd = *p.dynamics;
      for (const auto& [present, what] : {std::pair{dd.torque.has_value(), "torque"},
                                          std::pair{dd.torsional_spring.has_value(), "torsional_spring"}})
        if (present)
          throw ModelError(p.pointer + "/dynamics/" + what, "translating part '" + p.name + "' takes no " + what);
      Impl::Slider& sl = s.slider;
      sl.part = i;
      sl.dir[0] = p.motion.direction.x.get_d();
      sl.dir[1] = p.motion.direction.y.get_d();
      sl.mass = dd.mass->get_d();
      const double F[2] = {sl.mass * s.g[0] + (dd.force ? dd.force->x.get_d() * fs : 0.0),
                           sl.mass * s.g[1] + (dd.force ? dd.force->y.get_d() * fs : 0.0)};
      sl.load = F[0] * sl.dir[0] + F[1] * sl.dir[1];
      if (dd.linear_spring) {
        sl.k = dd.linear_spring->stiffness.get_d() * fs;
        sl.rest = dd.linear_spring->rest.get_d();
      }
      if (dd.damping) sl.damping = dd.damping->get_d() * fs * ts;   // force unit x time unit / mm
      sl.limits = p.motion.translation_limits;
      continue;
    }
    const SimulationSpec::Driver* driver = nullptr;
    for (const SimulationSpec::Driver& d : spec.drivers)
      if (d.part == i) driver = &d;
    if (p.motion.kind == Motion::Kind::rotation && !driver) {
      // a torque-driven rotating part with its own inertia (session 59): its angle joins (s, psi)
      if (!p.dynamics || !p.dynamics->moment_of_inertia)
        throw ModelError(p.pointer + "/motion", "part '" + p.name +
                                                    "': beside a pin-slot part a rotating part is a driver "
                                                    "(simulation.drivers) or turns by its own dynamics, which need "
                                                    "\"moment_of_inertia\" (and a \"torque\")");
      const Dynamics& dd = *p.dynamics;
      if (!(sgn(*dd.moment_of_inertia) > 0))
        throw ModelError(p.pointer + "/dynamics/moment_of_inertia",
                         "part '" + p.name + "': a torque-driven part needs a positive moment of inertia");
      if (s.free_driver != no_index)
        throw ModelError(p.pointer + "/motion", "part '" + p.name + "': the pin-slot simulator turns one "
                                                    "torque-driven part ('" + model.parts[s.drivers[s.free_driver].part].name +
                                                    "' is one); give the others a driver");
      for (const auto& [present, what] :
           {std::pair{dd.mass.has_value(), "mass"}, std::pair{dd.force.has_value(), "force"},
            std::pair{dd.linear_spring.has_value(), "linear_spring"},
            std::pair{dd.torsional_spring.has_value(), "torsional_spring"}, std::pair{dd.damping.has_value(), "damping"}})
        if (present)
          throw ModelError(p.pointer + "/dynamics/" + what,
                           "part '" + p.name + "': a torque-driven part beside a pin-slot part takes a moment of "
                           "inertia and a constant torque only (its centre of mass on its pivot)");
      for (const SimulationSpec::CenterOfMass& c : spec.centers_of_mass)
        if (c.part == i && c.at != p.motion.pivot)
          throw ModelError(c.pointer, "part '" + p.name + "': a torque-driven part beside a pin-slot part has its "
                                                          "centre of mass on its pivot");
      Impl::Driver free;
      free.part = i;
      free.angle0 = p.initial.angle.get_d();
      free.free = true;
      free.inertia = dd.moment_of_inertia->get_d();
      free.torque = dd.torque ? dd.torque->get_d() * fs : 0.0;
      s.driver_of[i] = s.drivers.size();
      s.free_driver = s.drivers.size();
      s.drivers.push_back(free);
      continue;
    }
    if (p.motion.kind != Motion::Kind::rotation || !driver)
      throw ModelError(p.pointer + "/motion", "part '" + p.name +
                                                  "': beside a pin-slot part the simulator moves only rotating "
                                                  "parts (drivers at constant speed, or torque-driven with their "
                                                  "inertia); other parts are fixed");
    if (!driver->profile.empty())
      throw ModelError(driver->pointer, "part '" + p.name + "': a pin-slot simulation takes constant-speed drivers only");
    s.driver_of[i] = s.drivers.size();
    s.drivers.push_back(Impl::Driver{i, p.initial.angle.get_d(), driver->speed.get_d() / ts});
    s.drivers.back().speed = driver->speed;
  }
  for (const SimulationSpec::Driver& d : spec.drivers)
    if (d.part == found) throw ModelError(d.pointer, "the pin-slot part cannot be a driver");
  if (!spec.couplings.empty())
    throw ModelError(spec.couplings.front().pointer, "a pin-slot simulation takes no springs between parts "
                                                     "(the pin-slot part's own springs act on s and psi)");
  std::vector<const SimulationSpec::Velocity*> own_velocity;
  std::optional<double> free_rate;   // the torque-driven part's initial rate (rad per time unit)
  std::optional<double> slider_rate;   // the translating part's (mm per time unit)
  for (const SimulationSpec::Velocity& v : spec.velocities) {
    if (s.free_driver != no_index && v.part == s.drivers[s.free_driver].part) {
      free_rate = v.value.get_d();
      continue;
    }
    if (s.has_slider() && v.part == s.slider.part) {
      slider_rate = v.value.get_d();
      continue;
    }
    if (v.part != found)
      throw ModelError(v.pointer, "beside the pin-slot part only drivers move (at their speed) and a torque-driven "
                                  "part: no initial velocity");
    own_velocity.push_back(&v);
  }
  // the pin-slot part's dynamics
  const Part& fp = model.parts[found];
  if (!fp.dynamics || !fp.dynamics->mass || !fp.dynamics->moment_of_inertia)
    throw ModelError(fp.pointer + "/dynamics", "pin-slot part '" + fp.name +
                                                   "' needs \"mass\" and \"moment_of_inertia\" (about its pivot)");
  const Dynamics& dyn = *fp.dynamics;
  if (dyn.damping) s.damping = dyn.damping->get_d() * fs * ts;   // viscous on the slide: force unit x time unit / mm
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
  // A pin-slot part's initial angle is an angle modulo whole turns against its angle limits, as
  // the reader decides it exactly (docs/model-format.md, "Motion"): outside the limits, it starts
  // at the whole turns nearest the limits' middle, kept inside them exactly. Until session 60
  // (hunt60) 2 pi + 0.1 rad against [-0.5, 0.5] (accepted by the reader) stopped the run at t = 0:
  // "leaves its angle limits (psi = 6.38319 rad)". An angle inside them is taken as it is.
  double psi0 = fp.initial.angle.get_d();
  if (const auto& limits = motion.angle_limits;
      limits && (fp.initial.angle < limits->lo || fp.initial.angle > limits->hi)) {
    const Rational middle = (limits->lo + limits->hi) / 2;
    psi0 = reduced_angle(fp.initial.angle, nearest_whole_turns(fp.initial.angle - middle));
    constexpr double up = std::numeric_limits<double>::infinity();
    if (Rational(psi0) < limits->lo) {
      psi0 = limits->lo.get_d();
      if (Rational(psi0) < limits->lo) psi0 = std::nextafter(psi0, up);
    }
    if (Rational(psi0) > limits->hi) {
      psi0 = limits->hi.get_d();
      if (Rational(psi0) > limits->hi) psi0 = std::nextafter(psi0, -up);
    }
  }
  s.y = {fp.initial.offset.get_d(), psi0, 0, 0, 0, 0};
  if (own_velocity.size() == 2) {   // {"slide": v, "angle": omega}
    s.y[2] = own_velocity[0]->value.get_d() / ts;
    s.y[3] = own_velocity[1]->value.get_d() / ts;
  }
  if (s.free_driver != no_index) {
    s.y[4] = s.drivers[s.free_driver].angle0;
    s.y[5] = free_rate ? *free_rate / ts : 0.0;
  }
  if (s.has_slider()) {
    s.y[6] = model.parts[s.slider.part].initial.offset.get_d();
    s.y[7] = slider_rate ? *slider_rate / ts : 0.0;
  }
  s.check_limits(s.y, 0);
  // the part's reach from a point (its pivot: for the angle's share of a chord's deviation,
  // reach_at; a pair's pivot: Pair::reach)
  const auto reach_from = [&](double px, double py) {
    double reach = 0;
    for (const Loop& loop : fp.loops)
      for (const Edge& edge : loop.edges) {
        for (const Point* q : {&edge.source, &edge.target})
          reach = std::max(reach, std::hypot(q->x.get_d() - px, q->y.get_d() - py));
        if (edge.is_arc())
          reach = std::max(reach, std::hypot(edge.center.x.get_d() - px, edge.center.y.get_d() - py) +
                                      std::sqrt(edge.radius_squared.get_d()));
      }
    return std::max(reach, 1e-300);
  };
  s.part_reach = reach_from(s.P[0], s.P[1]);
  // the run's length scale: the part's reach at its initial slide (not its limits': see reach_at)
  const double size = s.reach_at({&s.y});
  s.size = size;
  s.delta = options.chord_deviation > 0 ? options.chord_deviation : s.accuracy * size;
  // An initial angle rate the doubles cannot carry (session 59): a rate w turns a point at the
  // part's reach r with the acceleration w^2 r; beyond the doubles' range (1.8e308) the run crawled
  // towards its step budget at t = 1e-317 s (the pin-slot cam spun at 1e200 rad/s: 84 s, 646 MB).
  // Refused at once, at its pointer, with the largest rate the reach allows (a slide rate of
  // 1e300 mm/s runs: the part strikes its slot's end; constant-speed drivers: hipair simulate).
  auto refuse_rate = [&](const SimulationSpec::Velocity& v, const std::string& pointer, double r,
                         const std::string& whose) {
    const double rate = std::abs(v.value.get_d()) / ts;
    if (std::isfinite(rate * rate * r)) return;
    std::ostringstream out;
    out << "the initial angle rate " << v.value.get_d() << " rad/" << s.time_unit << " of " << whose << " '"
        << model.parts[v.part].name << "' is beyond what the simulator's doubles carry: its point " << r
        << " mm from the pivot would accelerate beyond their range (1.8e308); give at most "
        << std::sqrt(std::numeric_limits<double>::max() / r) * ts << " rad/" << s.time_unit;
    throw ModelError(pointer, out.str());
  };
  if (own_velocity.size() == 2) refuse_rate(*own_velocity[1], own_velocity[1]->pointer + "/angle", size, "pin-slot part");
  for (const SimulationSpec::Velocity& v : spec.velocities)
    if (s.free_driver != no_index && v.part == s.drivers[s.free_driver].part) {
      const Part& cam = model.parts[v.part];
      double r = 0;
      for (const Loop& loop : cam.loops)
        for (const Edge& edge : loop.edges) {
          for (const Point* q : {&edge.source, &edge.target})
            r = std::max(r, std::hypot(Rational(q->x - cam.motion.pivot.x).get_d(),
                                       Rational(q->y - cam.motion.pivot.y).get_d()));
          if (edge.is_arc())
            r = std::max(r, std::hypot(Rational(edge.center.x - cam.motion.pivot.x).get_d(),
                                       Rational(edge.center.y - cam.motion.pivot.y).get_d()) +
                                std::sqrt(edge.radius_squared.get_d()));
        }
      refuse_rate(v, v.pointer, std::max(r, 1e-300), "torque-driven part");
    }
  // the rest speed: the speed a load gains over the chord deviation; each share with the pointer
  // of its data (a refusal names the largest)
  std::vector<std::pair<double, std::string>> shares;
  const std::string own_at = fp.pointer + "/dynamics/";
  shares.emplace_back(std::hypot(s.g[0], s.g[1]), spec.pointer + "/gravity");
  shares.emplace_back(std::hypot(s.force[0], s.force[1]) / s.mass, own_at + "force");
  shares.emplace_back((std::abs(s.torque) / s.inertia_c) * size, own_at + "torque");
  if (s.free_driver != no_index)   // a torque-driven part's surface accelerates the contacts too
    shares.emplace_back(std::abs(s.drivers[s.free_driver].torque) / s.drivers[s.free_driver].inertia * size,
                        model.parts[s.drivers[s.free_driver].part].pointer + "/dynamics/torque");
  if (s.has_slider())   // and a translating part's load
    shares.emplace_back(std::abs(s.slider.load) / s.slider.mass, model.parts[s.slider.part].pointer + "/dynamics");
  double load = std::hypot(s.mass * s.g[0] + s.force[0], s.mass * s.g[1] + s.force[1]) / s.mass;
  load += (std::abs(s.torque) / s.inertia_c) * size;
  if (s.free_driver != no_index) load += shares[3].first;
  if (s.has_slider()) load += shares.back().first;
  // (the springs' force at the start's stretch, or the torsional one's at the angle limits if they
  // are nearer than half a turn beyond the start: limits far beyond the motion change nothing)
  shares.emplace_back(s.k_lin * (std::abs(s.y[0]) + std::abs(s.rest_lin)) / s.mass, own_at + "linear_spring");
  load += shares.back().first;
  if (s.k_tor > 0) {
    double turn = std::abs(s.y[1] - s.rest_tor) + std::numbers::pi;
    if (s.angle_limits)
      turn = std::min(turn, std::max(std::abs(s.angle_limits->lo.get_d() - s.rest_tor),
                                     std::abs(s.angle_limits->hi.get_d() - s.rest_tor)));
    shares.emplace_back(s.k_tor * turn / s.inertia_c * size, own_at + "torsional_spring");
    load += shares.back().first;
  }
  s.rest_speed = std::sqrt(2 * load * s.delta);
  // (the rest speed decides hold or rebound exactly, as a rational: loads beyond the doubles —
  // gravity, forces, torques or springs near 1e308 — stop here, not in GMP's mpq_set_d(inf);
  // since session 61 refused as data, at the pointer of the largest share: gravity of 1.8e308
  // mm/s^2 stopped with exit 3 and no pointer)
  if (!std::isfinite(s.rest_speed)) {
    const auto key = [](double x) { return std::isnan(x) ? std::numeric_limits<double>::infinity() : x; };
    const auto largest = std::max_element(shares.begin(), shares.end(),
                                          [&](const auto& a, const auto& b) { return key(a.first) < key(b.first); });
    throw ModelError(largest->second, "the loads on pin-slot part '" + fp.name +
                                          "' (gravity, forces, torques, springs) accelerate it beyond the doubles' "
                                          "range (1.8e308) the simulator integrates in; the largest share is this "
                                          "datum's");
  }
  s.hold_gap = 0.75 * s.delta;
  // the pairs
  for (std::size_t i = 0; i < model.pairs.size(); ++i) {
    const PairSpec& spec_pair = model.pairs[i];
    if (spec_pair.first != found && spec_pair.second != found) continue;
    Impl::Pair p;
    p.index = i;
    p.other = spec_pair.first == found ? spec_pair.second : spec_pair.first;
    if (spec_pair.friction) {   // Coulomb friction (session 64): mu_s sticks, mu_k slides
      p.mu_static = spec_pair.friction->get_d();
      p.mu_kinetic = spec_pair.kinetic_friction ? spec_pair.kinetic_friction->get_d() : p.mu_static;
    }
    p.restitution = spec_pair.restitution ? spec_pair.restitution->get_d() : 0.0;
    // the pair's pivot (session 66): the rotating part's against a rotating part, else the pin
    p.pivot = s.driver_of[p.other] != no_index ? model.parts[p.other].motion.pivot : fp.motion.pivot;
    p.reach = s.driver_of[p.other] != no_index ? reach_from(p.pivot.x.get_d(), p.pivot.y.get_d()) : s.part_reach;
    auto frame = std::make_shared<Model>(model);
    frame->parts[p.other].motion.kind = Motion::Kind::fixed;
    frame->parts[p.other].initial = PartConfiguration{};
    frame->parts[found].motion.kind = Motion::Kind::planar;
    frame->parts[found].motion.pivot = p.pivot;
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
                                                    " '" + model.parts[p.other].name + "'" +
                                                    (model.parts[p.other].motion.kind == Motion::Kind::fixed
                                                         ? std::string()
                                                         : " (its initial configuration: " +
                                                               model.parts[p.other].pointer + "/initial)"));
    s.pairs.push_back(std::move(p));
  }
  s.publish();
  PinSlotSimulation simulated(std::move(impl));
  // (session 72, jam72) an initial state beyond the doubles: bad input at its datum, nothing run
  simulation::refuse_initial_energy(model, simulated.energy());
  return simulated;
}

void PinSlotSimulation::step(double t_limit) {
  Impl& s = *impl_;
  const double end = t_limit * s.time_scale;
  if (!(end > s.t)) return;
  if (++s.steps > s.options.max_steps)
    throw SimulationStepBudget(s.where(s.t) + ": more than " + std::to_string(s.options.max_steps) +
                       " steps (a runaway or Zeno run)");
  const double before = s.t;
  s.advance(end - s.t);
  // The step's end is taken as `end` only when the two differ by the time's own resolution (a few
  // units in the last place of end: the sum of the steps' rounding). Until session 60 the snap
  // was an absolute 1e-15 time units: a follower spun at 1e20 rad/s runs to 8e-20 s, and its
  // first step's flight of 0.0625 rad jumped to t_end (the rest of the run skipped, exit 0).
  const double resolution = std::nextafter(std::abs(end), std::numeric_limits<double>::infinity()) - std::abs(end);
  if (end - s.t <= 4 * resolution) s.t = end;
  // steps that do not move the time on (a strike at a stop, or a step below the time's resolution):
  // after 10000 in a row the run stops, naming that, rather than spin through its step budget
  s.steps_in_place = s.t > before ? 0 : s.steps_in_place + 1;
  if (s.steps_in_place >= 10000) {
    std::ostringstream out;
    out << s.where(s.t) << ": 10000 steps in a row did not move the time on (a contact change that repeats "
        << "without progress, or steps shorter than the resolution of the time, "
        << (std::nextafter(s.t, std::numeric_limits<double>::infinity()) - s.t) / s.time_scale << " " << s.time_unit
        << ")";
    throw NumericError(out.str());
  }
  s.check_energy();
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
double PinSlotSimulation::dissipated() const {
  return (impl_->impact_loss + impl_->settle_loss + impl_->y[8]) / impl_->force_scale;
}
double PinSlotSimulation::chord_deviation() const { return impl_->delta; }
std::size_t PinSlotSimulation::part() const { return impl_->part; }
const Model& PinSlotSimulation::model() const { return impl_->model; }
const std::string& PinSlotSimulation::time_unit() const { return impl_->time_unit; }
const std::string& PinSlotSimulation::force_unit() const { return impl_->force_unit; }

}  // namespace hipair
