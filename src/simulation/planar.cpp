// HIPAIR — simulation of a part free in the plane among fixed parts (docs/simulation.md, "Parts
// free in the plane"). Collision detection uses only the 3-DOF C-space adaptor
// (include/hipair/sliced.hpp) and contact frames from the kernels (sliced_contact_frame).
//
// Free flight is integrated in closed form: with the pivot at the centre of mass, constant
// acceleration a = g + F/m, linear damping k = c/m, constant angular acceleration alpha = T/I,
//   v(s) = v_inf + (v0 - v_inf) e^{-ks},  X(s) = X0 + v_inf s + (v0 - v_inf)(1 - e^{-ks})/k
//   (k = 0: v0 + a s, X0 + v0 s + a s^2/2),   omega(s) = omega0 + alpha s,
//   theta(s) = theta0 + omega0 s + alpha s^2/2.
// Every velocity lies on a segment between its values at the ends of any interval (it moves
// along a straight line, monotonically), so |v| and |omega| over an interval are bounded by
// their values at its ends, and so is |a - k v| (the translational acceleration).
//
// A step from s = 0 to its end is covered by nodes s_0 = 0 < s_1 < ... ; at each node:
//  1. Conservative advancement over a horizon H (at most the rest of the step; about the time
//     in which the speed would double, at least a chord length): L = max|v| + max|omega| R over
//     [s_i, s_i + H] bounds the speed of every point of the part (R: the part's reach from its
//     pivot). features_near gives a certified lower bound d of the distance between the parts;
//     the part is then apart from the fixed part on [s_i, s_i + min(d / L, H)] (no point moves
//     farther than d). Nothing within L H: free over the whole horizon.
//  2. Near a fixed part (d / L below the chord length tau), the chord from the node's
//     configuration to the next one's, straight in (x, y, w = tan((theta - c)/2)), is tested
//     exactly by SlicedSpace::first_crossing. Its length tau keeps every point of the part within
//     delta of the closed-form path: |X_chord - X| <= tau^2/8 max|X''|,
//     |w_chord - w| <= tau^2/8 max|w''| with w'' = (1 + w^2)/2 (alpha + w omega^2), and an angle
//     error of at most 2 |dw|, so delta = tau^2/8 (max|X''| + 2 R max|w''|).
// Certified: every state's configuration is free or touching (never blocked); the simulated
// path is free except for contacts that would penetrate less than delta within one chord; the
// first contact is exact on its chord (bracketed to 2^-crossing_bits of the chord's time).
//
// Sustained contact (held_advance; docs/simulation.md, "Sustained contact of a planar part"):
// vertex–segment contacts (and, for this single-part simulator, vertex–arc, arc–segment and
// arc–arc contacts: docs/simulation.md, "Held contacts on arcs of a planar part") without
// separating speed after an impact are held; their forces come
// from the fixed-axis simulator's frictional complementarity problem (simulation/friction.hpp)
// over (x, y, theta); the state is integrated by Dormand–Prince with error control, projected
// onto the held gaps (3/4 delta) and J v = 0; lift-off, stick/slip changes and a vertex leaving
// its segment are located by bisection; the other feature pairs are watched by features_near
// (far) or by exact chords that skip the held pairs (SlicedMotion::ignored).
#include <hipair/error.hpp>
#include <hipair/simulation.hpp>
#include <hipair/simulation_stop.hpp>

#include "kernels/contact_geometry.hpp"
#include "kernels/dual.hpp"
#include "kernels/model_features.hpp"
#include "simulation/friction.hpp"
#include "simulation/held_friction.hpp"
#include "simulation/friction_names.hpp"
#include "simulation/companion_watch.hpp"
#include "simulation/held_resolution.hpp"
#include "simulation/impact_energy.hpp"
#include "simulation/jam.hpp"
#include "simulation/lcp.hpp"
#include "simulation/initial_energy.hpp"
#include "simulation/motion_datum.hpp"
#include "simulation/planar_bounds.hpp"
#include "simulation/relative_configuration.hpp"
#include "simulation/units.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <type_traits>

namespace hipair {
namespace {

double to_d(const Rational& r) { return r.get_d(); }

// theta wrapped into (-pi, pi]
double wrap(double theta) {
  double w = std::remainder(theta, 2 * std::numbers::pi);
  return w <= -std::numbers::pi ? w + 2 * std::numbers::pi : w;
}

// A double on its way to an exact decision (a query radius, a velocity or a rest speed): a
// non-finite one (velocities or loads beyond the doubles' range: an initial speed or gravity of
// 1e308) stops the run. Until session 60 (hunt60) GMP's mpq_set_d(inf) killed the process with
// SIGFPE (friction-slide.json with the block thrown at 1.7976931348623157e308 mm/s or gravity
// [0, 1.54e308]).
Rational finite_exact(double value, const std::string& where, const char* what) {
  if (!std::isfinite(value))
    throw NumericError(where + ": " + what + " is not finite: the velocities or loads are beyond the range of "
                       "doubles (an initial velocity, gravity or force too large for the simulator)");
  return Rational(value);
}

using simulation::largest_motion_datum;

// A "not finite" stop of a step, or one beyond the doubles' resolution, with the largest velocity or load named
template <class Step>
void naming_the_data(const Model& model, Step&& step) {
  try {
    step();
  } catch (const NumericError& e) {
    const std::string what = e.what();
    if (what.find("not finite") == std::string::npos && what.find("beyond the doubles' resolution") == std::string::npos)
      throw;
    throw NumericError(what + largest_motion_datum(model));
  }
}

SlicedConfiguration configuration_of(double x, double y, double theta) {
  // a state that overflowed (extreme scales, a diverging integration) has no exact configuration
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta))
    throw NumericError("the simulated configuration of a planar part is not finite: the model's lengths or "
                       "dynamics are beyond the range of doubles");
  SlicedConfiguration c;
  c.x = Rational(x);
  c.y = Rational(y);
  double w = wrap(theta);
  if (w == std::numbers::pi) {
    c.angle.half_turn = true;
  } else {
    c.angle.t = Rational(std::tan(w / 2));
  }
  return c;
}


// A kinematic state in internal units (s, mm, rad, kg, mN).
struct Kinematic {
  double x = 0, y = 0, theta = 0, vx = 0, vy = 0, omega = 0;
};

using State6 = std::array<double, 6>;
State6 to_array(const Kinematic& k) { return {k.x, k.y, k.theta, k.vx, k.vy, k.omega}; }
Kinematic to_kinematic(const State6& y) { return {y[0], y[1], y[2], y[3], y[4], y[5]}; }

// ---- held contacts: the contact function of a vertex–segment feature pair, from the kernels
// (kernels::contact_frame), for double (integration) and Rational (the exact sign at a state).

// The kernels' dual number (kernels/dual.hpp): the kernels' contact frame evaluated with it gives
// the contact point's and normal's time derivatives (held arc contacts).
using kernels::Dual;

template <class T>
T number(const Rational& r) {
  if constexpr (std::is_same_v<T, double>) return r.get_d();
  else if constexpr (std::is_same_v<T, Dual>) return Dual(r.get_d());
  else return r;
}

// A feature of the model in body coordinates (an arc with its centre, squared radius, side and
// angular sector): the kernels' FeatureGeometry (kernels/model_features.hpp) in T.
template <class T>
kernels::FeatureGeometry<T> feature_geometry(const Model& model, const FeatureIdentity& id) {
  return kernels::feature_geometry<T>(model, id, [](const Rational& r) { return number<T>(r); });
}

// The contact function of a held pair at a pose of the planar part: the kernels' contact point
// and normal (fixed part into the planar part, not unit), the gap g (times |normal|: > 0 apart,
// 0 touching, < 0 penetrating) and the foot parameter along the pair's segment (the contact is
// valid for 0 <= along <= 1). Vertex–segment pairs always; pairs with an arc (vertex–arc,
// arc–segment, arc–arc) when `arcs` (the single-part simulator): their gap is |normal| times
// the signed distance (double), or a number of its exact sign (Rational, from squared radii
// only); `along` is -1 when the contact point leaves an arc's sector (double only).
template <class T>
struct ContactGap {
  bool defined = false;
  bool free_vertex = false;   // the planar part's vertex on a fixed segment (else the reverse)
  bool arc = false;           // a pair with an arc (its curvature terms from the kernels' derivatives)
  kernels::Vector<T> point{T(0), T(0)}, normal{T(0), T(0)};
  T gap{0}, along{0};
};

// sign(a - (b + c)) for a, b, c >= 0 given their squares A, B, C, exactly.
inline int sign_of_difference(const Rational& A, const Rational& B, const Rational& C) {
  const Rational x = A - B - C;   // a^2 - (b + c)^2 = x - 2 b c
  if (sgn(x) < 0) return -1;
  if (sgn(x) == 0) return sgn(B * C) == 0 ? 0 : -1;
  return sgn(x * x - Rational(4) * B * C);
}

// The gap of an arc pair: `sign` (a - (b + c)) times |normal| (n2 = |normal|^2) for double;
// its exact sign for Rational.
template <class T>
T arc_gap(int sign, const T& A, const T& B, const T& C, const T& n2) {
  if constexpr (std::is_same_v<T, double>)
    return sign * (std::sqrt(std::max(A, 0.0)) - std::sqrt(std::max(B, 0.0)) - std::sqrt(std::max(C, 0.0))) *
           std::sqrt(n2);
  else return Rational(sign * sign_of_difference(A, B, C));
}

// Whether world direction `d` from an arc's centre lies in the arc's sector (pose: its part's).
inline bool in_sector(const kernels::ArcSector<double>& sector, const kernels::Pose<double>& pose,
                      const kernels::Vector<double>& d) {
  if (sector.full) return true;
  const double bx = pose.c * d.x + pose.s * d.y, by = -pose.s * d.x + pose.c * d.y;   // body direction
  const bool after_start = sector.start.x * by - sector.start.y * bx >= 0;
  const bool before_end = bx * sector.end.y - by * sector.end.x >= 0;
  return sector.large ? after_start || before_end : after_start && before_end;
}

template <class T>
ContactGap<T> contact_gap(const Model& model, const SlicedFeaturePair& pair, const kernels::Pose<T>& free_pose,
                          bool arcs = false) {
  using S = kernels::FeatureShape;
  kernels::FeatureGeometry<T> fa = feature_geometry<T>(model, pair.fixed), fb = feature_geometry<T>(model, pair.free);
  ContactGap<T> g;
  kernels::Vector<T> s0, s1;
  const kernels::Pose<T> fixed = kernels::fixed_pose<T>();
  kernels::ContactFrame<T> frame = kernels::contact_frame(fixed, fa, free_pose, fb);
  bool segment = true;
  if (fa.shape == S::segment && fb.shape == S::vertex) {
    s0 = fa.point;
    s1 = fa.target;
    g.free_vertex = true;
    g.gap = kernels::dot(frame.normal, frame.point - s0);
  } else if (fa.shape == S::vertex && fb.shape == S::segment) {
    s0 = kernels::world_point(free_pose, fb.point);
    s1 = kernels::world_point(free_pose, fb.target);
    g.gap = kernels::dot(frame.normal, s0 - frame.point);
  } else if (!arcs || !frame.defined) {
    return g;
  } else {
    g.arc = true;
    const T n2 = kernels::dot(frame.normal, frame.normal);
    const T zero(0);
    if (fa.shape == S::segment || fb.shape == S::segment) {   // a convex arc on a segment
      const bool fixed_segment = fa.shape == S::segment;
      const kernels::FeatureGeometry<T>& seg = fixed_segment ? fa : fb;
      const kernels::FeatureGeometry<T>& arc = fixed_segment ? fb : fa;
      if (!arc.convex) return g;   // a concave arc meets a segment at its ends only (vertex pairs)
      const kernels::Pose<T>& seg_pose = fixed_segment ? fixed : free_pose;
      s0 = kernels::world_point(seg_pose, seg.point);
      s1 = kernels::world_point(seg_pose, seg.target);
      const kernels::Vector<T> k = kernels::world_point(fixed_segment ? free_pose : fixed, arc.center);
      // the centre's distance from the line along the normal (from the fixed part into the free)
      const T s = fixed_segment ? kernels::dot(frame.normal, k - s0) : kernels::dot(frame.normal, s0 - k);
      if constexpr (std::is_same_v<T, Rational>)
        g.gap = sgn(s) <= 0 ? Rational(-1) : Rational(sgn(s * s - arc.radius_squared * n2));
      else g.gap = s - std::sqrt(arc.radius_squared * n2);
    } else {
      segment = false;
      if (fa.shape == S::arc && fb.shape == S::arc) {
        const kernels::Vector<T> d = kernels::world_point(free_pose, fb.center) - kernels::world_point(fixed, fa.center);
        const T D2 = kernels::dot(d, d);
        if (fa.convex && fb.convex) g.gap = arc_gap(1, D2, fa.radius_squared, fb.radius_squared, n2);
        else if (!fa.convex && fb.convex) g.gap = arc_gap(1, fa.radius_squared, fb.radius_squared, D2, n2);
        else if (fa.convex && !fb.convex) g.gap = arc_gap(1, fb.radius_squared, fa.radius_squared, D2, n2);
        else return g;
      } else {   // a vertex on an arc
        const bool fixed_arc = fa.shape == S::arc;
        const kernels::FeatureGeometry<T>& arc = fixed_arc ? fa : fb;
        const kernels::Vector<T> d = frame.point - kernels::world_point(fixed_arc ? fixed : free_pose, arc.center);
        const T D2 = kernels::dot(d, d);
        g.gap = arc.convex ? arc_gap(1, D2, arc.radius_squared, zero, n2) : arc_gap(1, arc.radius_squared, D2, zero, n2);
      }
      g.along = T(1) / T(2);
    }
    if constexpr (std::is_same_v<T, double>) {   // the contact point within the arcs' sectors
      bool inside = true;
      if (fa.shape == S::arc) inside = inside && in_sector(fa.sector, fixed, frame.point - fa.center);
      if (fb.shape == S::arc)
        inside = inside && in_sector(fb.sector, free_pose, frame.point - kernels::world_point(free_pose, fb.center));
      if (!inside) g.along = -1;
    }
    g.defined = true;
    g.point = frame.point;
    g.normal = frame.normal;
    if (!segment) return g;
    kernels::Vector<T> dseg = s1 - s0;
    if (!(g.along < T(0))) g.along = T(kernels::dot(frame.point - s0, dseg) / kernels::dot(dseg, dseg));
    return g;
  }
  g.defined = true;
  g.point = frame.point;
  g.normal = frame.normal;
  kernels::Vector<T> d = s1 - s0;
  g.along = T(kernels::dot(frame.point - s0, d) / kernels::dot(d, d));
  return g;
}

kernels::Pose<double> pose_of(const Point& pivot, const Kinematic& k) {
  kernels::Pose<double> pose =
      kernels::rotation_pose_from_cos_sin(kernels::Vector<double>{pivot.x.get_d(), pivot.y.get_d()}, std::cos(k.theta),
                                          std::sin(k.theta));
  pose.shift = kernels::Vector<double>{k.x, k.y};
  pose.translates = true;
  return pose;
}

// The curvature terms of a held pair with an arc at state k (r = contact point - reference
// point): the kernels' contact frame evaluated in dual numbers along the motion gives the
// contact point's rate c' and the unit normal's rate n'; with the material velocity
// V(c) = v + w J r of the planar part at the contact, d/dt (n . V(c)) = J qdd + h and
// d/dt (t . V(c)) = T qdd + h_t, h = n' . V + w (c' - v) x n, h_t = t' . V + w (c' - v) x t.
void held_arc_terms(const Model& model, const SlicedFeaturePair& pair, const Point& pivot, const Kinematic& k, double rx,
                    double ry, double& h, double& h_t) {
  const double cs = std::cos(k.theta), sn = std::sin(k.theta);
  kernels::Pose<Dual> pose = kernels::rotation_pose_from_cos_sin(
      kernels::Vector<Dual>{Dual(pivot.x.get_d()), Dual(pivot.y.get_d())}, Dual(cs, -sn * k.omega), Dual(sn, cs * k.omega));
  pose.shift = kernels::Vector<Dual>{Dual(k.x, k.vx), Dual(k.y, k.vy)};
  pose.translates = true;
  kernels::ContactFrame<Dual> frame = kernels::contact_frame(kernels::fixed_pose<Dual>(), feature_geometry<Dual>(model, pair.fixed),
                                                             pose, feature_geometry<Dual>(model, pair.free));
  const double len = std::hypot(frame.normal.x.v, frame.normal.y.v);
  const double nx = frame.normal.x.v / len, ny = frame.normal.y.v / len;
  const double along = (nx * frame.normal.x.d + ny * frame.normal.y.d);
  const double dnx = (frame.normal.x.d - nx * along) / len, dny = (frame.normal.y.d - ny * along) / len;
  const double tx = -ny, ty = nx, dtx = -dny, dty = dnx;
  const double w = k.omega, Vx = k.vx - w * ry, Vy = k.vy + w * rx;
  const double ux = frame.point.x.d - k.vx, uy = frame.point.y.d - k.vy;   // c' - v
  h = dnx * Vx + dny * Vy + w * (ux * ny - uy * nx);
  h_t = dtx * Vx + dty * Vy + w * (ux * ty - uy * tx);
}

kernels::Pose<Rational> pose_of(const Point& pivot, const SlicedConfiguration& c) {
  kernels::Vector<Rational> p{pivot.x, pivot.y};
  kernels::Pose<Rational> pose;
  if (c.angle.half_turn) {
    pose.c = Rational(-1);
    pose.s = Rational(0);
    pose.w = Rational(1);
    pose.pivot = p;
    pose.rotates = true;
  } else {
    pose = kernels::rotation_pose_from_half_tangent(p, c.angle.t, false);
  }
  pose.shift = kernels::Vector<Rational>{c.x, c.y};
  pose.translates = true;
  return pose;
}

// A feature pair near (not at) contact whose vertex lies strictly behind its segment's line (the
// exact gap < 0 at configuration c, the free part's pose about `pivot`): in a free configuration
// the vertex is beside the segment, past one of its ends (or across a wall thinner than the near
// distance), on the side of the part that carries the segment, so it can meet that segment only
// through the part. It is no contact of the motion: the segment's end vertex,
// or the edge beyond it, is the feature the vertex meets first, and features_near lists that one
// too. Where a whole part lies within the near distance (a bump smaller than the chord
// deviation), such pairs would put rows facing every way into an impact (docs/simulation.md,
// "Impacts on nearly dependent contacts"). Pairs with an arc and vertex–vertex pairs are kept.
bool behind_segment(const Model& model, const SlicedFeaturePair& f, const Point& pivot, const SlicedConfiguration& c) {
  const ContactGap<Rational> g = contact_gap(model, f, pose_of(pivot, c));
  return g.defined && !g.arc && sgn(g.gap) < 0;
}

// The force of a linear spring and damper on its end at offset d from the other end (relative
// velocity dv): -(k (L - rest) + c dL/dt) d / L; rest 0: the vector spring -k d (defined at
// L = 0); the damper acts along the line (nothing at L = 0, no direction).
std::array<double, 2> spring_force(double k, double rest, double c, const double d[2], const double dv[2]) {
  const double L = std::hypot(d[0], d[1]);
  std::array<double, 2> f{0, 0};
  if (rest == 0) {
    f = {-k * d[0], -k * d[1]};
  } else if (L > 0) {
    f = {-k * (L - rest) * d[0] / L, -k * (L - rest) * d[1] / L};
  }
  if (c > 0 && L > 0) {
    const double ux = d[0] / L, uy = d[1] / L, ldot = ux * dv[0] + uy * dv[1];
    f[0] -= c * ldot * ux;
    f[1] -= c * ldot * uy;
  }
  return f;
}


// Collinear contacts of one pair (equal tangent rows: a face on a face, where the equations fix
// only the sum of their sticking friction): groups, and the split of that friction in
// proportion to the normal forces (the Coulomb condition of the sum is then that of each).
std::vector<std::size_t> collinear_groups(const std::vector<simulation::Friction>& friction,
                                          const std::vector<std::size_t>& pair_of) {
  std::vector<std::size_t> group(friction.size());
  for (std::size_t i = 0; i < friction.size(); ++i) {
    group[i] = i;
    for (std::size_t j = 0; j < i; ++j)
      if (friction[i].on && friction[j].on && pair_of[i] == pair_of[j] &&
          (friction[i].T - friction[j].T).cwiseAbs().maxCoeff() <= 1e-12 * (1 + friction[i].T.cwiseAbs().maxCoeff())) {
        group[i] = group[j];
        break;
      }
  }
  return group;
}

void split_collinear(simulation::FrictionalSolution& s, const std::vector<simulation::Friction>& friction,
                     const std::vector<std::size_t>& group) {
  for (std::size_t g = 0; g < group.size(); ++g) {
    double total = 0, normal = 0;
    std::size_t members = 0;
    for (std::size_t k = 0; k < group.size(); ++k)
      if (group[k] == g && s.state[k] == simulation::stick) {
        total += s.f(static_cast<Eigen::Index>(k));
        normal += std::max(0.0, s.lambda(static_cast<Eigen::Index>(k)) / friction[k].s);
        ++members;
      }
    if (members < 2) continue;
    for (std::size_t k = 0; k < group.size(); ++k)
      if (group[k] == g && s.state[k] == simulation::stick) {
        double share = normal > 0 ? std::max(0.0, s.lambda(static_cast<Eigen::Index>(k)) / friction[k].s) / normal
                                  : 1.0 / static_cast<double>(members);
        s.f(static_cast<Eigen::Index>(k)) = total * share;
      }
  }
}

// The forces of a held-contact problem `p` (rows G, h, free accelerations a0, friction rows):
// unilateral, the frictional complementarity problem; else bilateral at the given stick/slip
// states. Collinear rows of one pair share their sticking friction (split_collinear).
// `exact_limits` (unilateral): the stick limits decided exactly too (exact_stick_holds; off where
// the states are forced by the model-exact rest decision, exact_rest_state, which decides on the
// model's exact numbers and takes precedence).
template <class Problem>
void solve_held_forces(Problem& p, const Eigen::VectorXd& minv, const std::vector<std::size_t>& pair_of,
                       bool unilateral, const std::vector<int>& states, bool exact_limits = true) {
  const std::vector<std::size_t> group = collinear_groups(p.friction, pair_of);
  auto split = [&](simulation::FrictionalSolution& s) { split_collinear(s, p.friction, group); };
  if (unilateral) {
    p.solution =
        simulation::solve_frictional(p.G, minv, p.a0, p.h, p.friction, split, false, exact_limits ? &group : nullptr);
  } else {
    p.solution = simulation::solve_bilateral(p.G, minv, p.a0, p.h, p.friction, states);
    split(p.solution);
  }
}

// Newton restitution with Coulomb-limited tangential impulses (the fixed-axis simulator's
// frictional impulse problem, src/simulation/friction.hpp) over the coordinates of J: velocities
// v before, h = e J v- (restitution), tangent rows in `friction`. Newton's restitution with
// Coulomb friction can create energy where the normal and tangential rows are coupled
// (J M^-1 T^T != 0: a corner of a turning part; Kane and Levinson). Where it would, the
// restitution is scaled down to the largest factor (by bisection, 2^-30) whose impact creates
// none (`limited` set). Coordinates with inverse mass 0 (drivers) carry no kinetic energy here.
simulation::FrictionalSolution frictional_impact(const Eigen::MatrixXd& J, const Eigen::VectorXd& minv,
                                                 const Eigen::VectorXd& v, const Eigen::VectorXd& h,
                                                 const std::vector<simulation::Friction>& friction,
                                                 const std::vector<std::size_t>& group, const std::string& where,
                                                 const std::string& named, bool& limited,
                                                 const std::vector<Rational>* h_exact = nullptr) {
  // (session 67, impact67: the impulses' Coulomb conditions decided exactly, the collinear
  // groups given — held_friction.hpp's frictional_impulses; session 68, impact68: on the exact
  // restitution terms, scaled exactly — the scale is dyadic; session 69, exact69: the energy test
  // exact, and the composition in held_friction.hpp's limited_frictional_impulses)
  return simulation::limited_frictional_impulses(
      J, minv, v, h, friction, group, [&](simulation::FrictionalSolution& s) { split_collinear(s, friction, group); },
      h_exact, limited, [&](const simulation::FrictionalSolution& unsolved) {
        // (session 72, jam72: a verdict's words only where the exact search was complete)
        throw NumericError(where + ": " +
                           simulation::frictional_refusal("the frictional impact problem", unsolved.exhausted) + named);
      });
}

// ---- held contacts, shared by both planar simulators (docs/simulation.md, "Sustained contact
// of a planar part", "Sustained contact between moving parts")

// Projects a state onto its m held contacts: positions by Gauss–Newton onto gap = hold_gap
// (mass-weighted, at most 4 iterations), then velocities onto J v = 0 and, for sticking
// contacts, T v = 0. frame(c): contact c's frame (J, T, gap) at the current state; move(dq)
// shifts the configuration; velocity() / set_velocity(v) read and write the velocities.
template <class FrameOf, class Sticking, class Move, class GetV, class SetV>
void project_held(std::size_t m, const Eigen::VectorXd& minv, double hold_gap, bool positions, FrameOf frame,
                  Sticking sticking, Move move, GetV velocity, SetV set_velocity) {
  if (m == 0) return;
  const Eigen::Index n = minv.size(), rows_m = static_cast<Eigen::Index>(m);
  for (int iteration = 0; positions && iteration < 4; ++iteration) {
    Eigen::MatrixXd J(rows_m, n);
    Eigen::VectorXd g(rows_m);
    for (Eigen::Index r = 0; r < rows_m; ++r) {
      const auto f = frame(static_cast<std::size_t>(r));
      J.row(r) = f.J.transpose();
      g(r) = f.gap - hold_gap;
    }
    if (g.cwiseAbs().maxCoeff() <= 1e-3 * hold_gap) break;
    Eigen::MatrixXd MJt = minv.asDiagonal() * J.transpose();
    move(Eigen::VectorXd(-MJt * (J * MJt).completeOrthogonalDecomposition().solve(g)));
  }
  std::vector<Eigen::VectorXd> rows;
  for (std::size_t c = 0; c < m; ++c) {
    const auto f = frame(c);
    rows.push_back(f.J);
    if (sticking(c)) rows.push_back(f.T);
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), n);
  for (std::size_t r = 0; r < rows.size(); ++r) A.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
  Eigen::VectorXd v = velocity();
  Eigen::MatrixXd MAt = minv.asDiagonal() * A.transpose();
  v -= MAt * (A * MAt).completeOrthogonalDecomposition().solve(A * v);
  set_velocity(v);
}

// The held conditions at a state integrated with fixed states (problem p: frames, friction,
// bilateral solution; velocities v; inverse masses minv): 0 when all hold, else bits 1 lift-off
// (a force below 0), 2 stick -> slip, 4 slip -> stick (the sliding velocity changes sign), 8
// edge end (the foot leaves the segment); per contact in `per_contact` when given. Bits 1 and 2
// are decided exactly on the problem's rows (friction.hpp's held_verdict: a force exactly 0
// stays held, a friction force exactly at mu_s N sticks; docs/simulation.md, "Session 63
// (exact63)"), bit 4 by the exact sign of T . v.
template <class Problem, class HeldT, class PairT>
unsigned held_violations(const Problem& p, const std::vector<HeldT>& held, const std::vector<PairT>& pairs,
                         const Eigen::VectorXd& v, const Eigen::VectorXd& minv, std::vector<unsigned>* per_contact) {
  unsigned all = 0;
  if (per_contact) per_contact->assign(held.size(), 0);
  if (held.empty()) return 0;
  std::vector<std::size_t> pair_of;
  for (const HeldT& c : held) pair_of.push_back(c.pair);
  const simulation::HeldVerdict verdict = simulation::held_verdict(
      p.G, minv, p.a0, p.h, p.friction, p.solution.state, collinear_groups(p.friction, pair_of));
  for (std::size_t k = 0; k < held.size(); ++k) {
    const HeldT& c = held[k];
    unsigned bits = 0;
    if (verdict.force_sign[k] < 0) bits |= 1;
    if (p.friction[k].on && c.state == simulation::stick && verdict.beyond_static[k]) bits |= 2;
    if (p.friction[k].on && (c.state == simulation::slip_positive || c.state == simulation::slip_negative))
      if (c.state * simulation::exact_dot_sign(p.frames[k].T, v) < 0) bits |= 4;
    if (p.frames[k].along < 0 || p.frames[k].along > 1) bits |= 8;
    all |= bits;
    if (per_contact) (*per_contact)[k] = bits;
  }
  return all;
}

// Which held contacts lift off at a step's start (problem p: the frictional LCP's solution and
// its stick/slip states; inverse masses minv): simulation::lift_offs (held_friction.hpp) on the
// exact verdict of every held row at the solution's states, collinear contacts grouped.
template <class Problem>
std::vector<bool> lift_offs(const Problem& p, const Eigen::VectorXd& minv, const std::vector<std::size_t>& pair_of) {
  return simulation::lift_offs(p.solution, simulation::held_verdict(p.G, minv, p.a0, p.h, p.friction, p.solution.state,
                                                                    collinear_groups(p.friction, pair_of)));
}

using simulation::held_friction;   // (simulation/held_friction.hpp)

// Cuts a step of length `end` ending at state `at` at its first violated held condition, by
// bisection to 2^-50 of the step: step(s) is the state after s, violated(state, bits) the
// held conditions (held_violations); `bits` gets the violations per contact at the cut.
template <class State, class Step, class Violated>
void cut_at_first_violation(double& end, State& at, Step step, Violated violated, std::vector<unsigned>& bits) {
  if (violated(at, nullptr) == 0) return;
  double lo = 0, hi = end;
  for (int i = 0; i < 50; ++i) {
    double mid = 0.5 * (lo + hi);
    if (violated(step(mid), nullptr) != 0) hi = mid;
    else lo = mid;
  }
  end = hi;
  at = step(hi);
  violated(at, &bits);
}

// Ends the held contacts whose foot left their feature at the end of a step (bit 8 of their
// violations `bits`, empty: none), one edge-end event each (`ended(c)`: the event of contact c);
// the same for both planar simulators. Returns true when one ended.
template <class HeldT, class Ended>
bool end_held_at_edges(std::vector<HeldT>& held, const std::vector<unsigned>& bits, Ended ended) {
  std::vector<HeldT> kept;
  for (std::size_t c = 0; c < held.size(); ++c) {
    if (!bits.empty() && (bits[c] & 8)) {
      ended(held[c]);
      continue;
    }
    kept.push_back(held[c]);
  }
  const bool any = kept.size() != held.size();
  held = std::move(kept);
  return any;
}

// An event of a held contact (contact, lift-off, stick, slip, edge-end) at its frame (point,
// unit normal); forces in the internal unit (divided by force_scale).
SimulationEvent held_contact_event(SimulationEvent::Kind kind, double time, std::size_t pair, const std::string& first,
                                   const std::string& second, const std::string& label, const std::array<double, 4>& frame,
                                   double normal_force, double friction_force, double force_scale) {
  SimulationEvent e;
  e.kind = kind;
  e.time = time;
  e.pair = pair;
  e.first_part = first;
  e.second_part = second;
  e.features.push_back(label);
  e.point = {frame[0], frame[1]};
  e.normal = {frame[2], frame[3]};
  e.normal_force = normal_force / force_scale;
  e.friction_force = friction_force / force_scale;
  return e;
}

// The first trial of an integration that has no step guess yet: the span, but at most 2^20
// times the time in which the state's fastest rate moves it by its own scale (at least 1). The
// span alone (the whole time left: `--t-end 1e150` gives 1e150 s) overflowed the error control:
// 200 halvings by at most 5 could not bring it down, or the trial's state was no longer finite
// (docs/simulation.md, "Session 34"). Far above any step the integrator takes (a part falling
// its own size under gravity, a spring's period): a run's steps are those of the span alone.
template <class State, class Rhs>
double first_trial(const State& y, Rhs rhs, double span) {
  State dy = y;
  rhs(y, dy);
  double scale = 1, rate = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    scale = std::max(scale, std::abs(y[i]));
    rate = std::max(rate, std::abs(dy[i]));
  }
  if (!(rate > 0) || !std::isfinite(rate)) return span;
  return std::min(span, 0x1p20 * scale / rate);
}

// The pairs (into s.pairs) of either planar simulator's held contacts, and the friction data of
// some of its pairs for a message (simulation/friction_names.hpp).
template <class State>
std::vector<std::size_t> pairs_of_held(const State& s) {
  std::vector<std::size_t> out;
  for (const auto& c : s.held) out.push_back(c.pair);
  return out;
}
template <class State>
std::string friction_of_pairs(const State& s, const std::vector<std::size_t>& of) {
  std::vector<std::size_t> indices;
  for (std::size_t i : of) indices.push_back(s.pairs[i].index);
  return simulation::named_friction(s.model, indices);
}

// Steps until t_end (the model's time unit) for either planar simulator: `s` is its state (internal
// time `t`, `time_scale`, `events`, `public_state`), `step` one step towards t_end.
template <class State, class Step>
void run_steps(State& s, double t_end, const std::function<void(double)>& progress, Step step) {
  while (s.t < t_end * s.time_scale) {
    double before = s.t;
    std::size_t events = s.events.size();
    step();
    if (progress) progress(s.public_state.time);
    // no progress possible (t_end reached in the internal unit)
    if (s.t == before && s.events.size() == events) break;
  }
}

// The span (internal time) of the next step of either planar simulator towards t_limit (the
// model's time unit; `limit`: it in internal time), at most the options' max_step; 0 (no step)
// when there is nothing left to do. A step counts against max_steps.
template <class State>
double next_span(State& s, double t_limit, double& limit) {
  limit = t_limit * s.time_scale;
  double span = limit - s.t;
  if (s.options.max_step > 0) span = std::min(span, s.options.max_step * s.time_scale);
  if (!(span > 0)) return 0;
  if (++s.steps > s.options.max_steps)
    throw SimulationStepBudget(s.where(s.t) + ": more than " + std::to_string(s.options.max_steps) + " steps");
  return span;
}

}  // namespace

// One free-flight step's collision tests (certified advances and exact chords) are at most this
// many (session 65, sim65); the most an ordinary step takes (every example model and every
// simulation test, measured: docs/simulation.md, "Session 65 (sim65)") is the second figure.
constexpr std::size_t max_step_collision_tests = 100000;
constexpr std::size_t ordinary_step_collision_tests = 2865;

struct PlanarSimulation::Impl {
  Model model;
  SimulationOptions options;
  std::size_t part = 0;
  double time_scale = 1, force_scale = 1000;
  std::string time_unit = "s", force_unit = "N";
  double mass = 0, inertia = 0, damping_rate = 0;   // damping_rate = c / m (1/s)
  double accel[2] = {0, 0};                         // g + F/m (mm/s^2)
  double alpha = 0;                                 // T / I (rad/s^2)
  double force[2] = {0, 0}, torque = 0, g[2] = {0, 0};
  Rational load_x, load_y, load_torque;             // m g + F (mN) and T (mN mm), exact
  double reach = 0;                                 // max |q - pivot| over the part (mm)
  Rational reach_bound;                             // a certified rational upper bound of it
  double delta = 0;                                 // chord deviation (mm)
  double rest_speed = 0;                            // impacts slower than this are plastic
  // Springs and dampers (docs/simulation.md, "Springs on a planar part"): a torsional spring
  // to the frame about the pivot, and linear springs/dampers ("simulation"/"springs") from a
  // point of the part to a point of a fixed part. With any of them the free flight is no longer
  // in closed form: it is integrated with error control (held_advance with no held contact).
  struct LineSpring {
    double body[2] = {0, 0};     // the part's attachment point relative to its pivot, zero configuration (mm)
    double anchor[2] = {0, 0};   // the fixed part's attachment point, world (mm)
    double k = 0, rest = 0, c = 0;   // mN/mm, mm, mN s/mm
  };
  std::vector<LineSpring> springs;
  double torsion_k = 0, torsion_rest = 0;           // mN mm/rad, rad
  bool integrated = false;                          // springs present: free flight integrated
  // The acceleration of the free part at a state (loads, damping, springs), internal units.
  Eigen::Vector3d free_acceleration(const Kinematic& at) const;
  // The springs' potential at a state (mN mm).
  double spring_potential(const Kinematic& at) const;
  struct Pair {
    std::size_t index = 0;                          // into Model::pairs
    std::size_t fixed = 0;
    double restitution = 0;
    SlicedSpace space;
    double mu_static = 0, mu_kinetic = 0;   // Coulomb friction (0: frictionless)
    Rational mu_static_exact;
  };
  std::vector<Pair> pairs;
  double t = 0;
  Kinematic k;
  PlanarState public_state;
  SlicedConfiguration q;                            // exact configuration of the state
  bool resting = false;
  std::vector<SimulationEvent> events;
  std::size_t steps = 0;
  std::size_t plastic_run = 0;                      // consecutive plastic impacts without rest
  PlanarStatistics stats;

  // closed-form free flight for a duration s from k
  Kinematic flight(const Kinematic& a, double s) const {
    Kinematic b = a;
    double v0[2] = {a.vx, a.vy}, x0[2] = {a.x, a.y}, v[2], x[2];
    for (int i = 0; i < 2; ++i) {
      if (damping_rate > 0) {
        double vinf = accel[i] / damping_rate;
        double decay = -std::expm1(-damping_rate * s);   // 1 - e^{-ks}
        v[i] = vinf + (v0[i] - vinf) * (1 - decay);
        x[i] = x0[i] + vinf * s + (v0[i] - vinf) * decay / damping_rate;
      } else {
        v[i] = v0[i] + accel[i] * s;
        x[i] = x0[i] + v0[i] * s + 0.5 * accel[i] * s * s;
      }
    }
    b.x = x[0];
    b.y = x[1];
    b.vx = v[0];
    b.vy = v[1];
    b.omega = a.omega + alpha * s;
    b.theta = a.theta + a.omega * s + 0.5 * alpha * s * s;
    return b;
  }

  std::string where(double time) const {
    std::ostringstream out;
    out << "simulation: at t = " << time / time_scale << " " << time_unit << " the planar part '"
        << model.parts[part].name << "'";
    return out.str();
  }

  void publish() {
    public_state.time = t / time_scale;
    public_state.x = k.x;
    public_state.y = k.y;
    public_state.angle = k.theta;
    public_state.vx = k.vx * time_scale;
    public_state.vy = k.vy * time_scale;
    public_state.omega = k.omega * time_scale;
    public_state.configuration = q;
    public_state.resting = resting;
  }

  // Moves the state to the exact configuration c (free or touching) with velocities of `at`.
  void set_state(const Kinematic& at, const SlicedConfiguration& c) {
    k = at;
    q = c;
    // the double coordinates of the exact configuration (theta continuous with the flight)
    k.x = to_d(c.x);
    k.y = to_d(c.y);
    double exact_theta = c.angle.half_turn ? std::numbers::pi : 2 * std::atan(to_d(c.angle.t));
    k.theta = at.theta + wrap(exact_theta - at.theta);
  }

  // One step of free flight of at most `span` seconds; ends at the first contact (then resolved).
  bool advance(double span);
  // The earliest of a chord's crossings (pair index, crossing), and in `touching` every feature
  // pair touching there: those whose bracket meets the earliest one, and those within delta of
  // touching at its configuration (met at once: within the chord's accuracy).
  const SlicedMotionCrossing& earliest(const std::vector<std::pair<std::size_t, SlicedMotionCrossing>>& crossings,
                                       std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const;
  // The contact rows of the touching feature pairs at configuration c (state `at`).
  struct Rows {
    Eigen::MatrixXd J;                         // [n_x, n_y, r x n] per contact
    std::vector<std::array<double, 4>> frames; // point, unit normal
    std::vector<std::size_t> pair;             // index into pairs
    std::vector<SlicedFeaturePair> feature;
    std::vector<simulation::ExactRow> exact;   // J's rows at c in exact rationals (the held decision)
  };
  Rows contact_rows(double time, const Kinematic& at, const SlicedConfiguration& c,
                    const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const;
  // One event per fixed part met: its features, the sum of its rows' multipliers and its row
  // of largest multiplier.
  struct PairEvent {
    SimulationEvent event;
    double total = 0;
    Eigen::Index top = 0;
  };
  std::vector<PairEvent> pair_events(SimulationEvent::Kind kind, double time, const Rows& rows,
                                     const Eigen::VectorXd& lambda) const;
  void impact(double time, const Rows& rows);
  bool try_rest(const Rows& rows);

  // ---- sustained contact (docs/simulation.md, "Sustained contact of a planar part")
  struct Held {
    std::size_t pair = 0;                        // into pairs
    SlicedFeaturePair feature;
    int state = simulation::frictionless;        // stick, slip +-1 (friction), frictionless
  };
  std::vector<Held> held;
  // the pairs (into pairs) of the held contacts, and some pairs' friction data for a message
  std::vector<std::size_t> held_pairs() const { return pairs_of_held(*this); }
  std::string named_pairs(const std::vector<std::size_t>& of) const { return friction_of_pairs(*this, of); }
  double hold_gap = 0;                           // the gap (mm) held contacts are projected to
  double step_guess = 0;                         // the integrator's suggested next step (s)
  double accuracy = 1e-9;
  // A held contact's data at a state: the normal row J = [n, r x n], the tangent row
  // T = [t, r x t] (t = (-n_y, n_x)), the curvature term h (d2g/dt2 = J qdd + h), the unit gap
  // and the foot parameter.
  struct HeldFrame {
    Eigen::Vector3d J, T;
    double h = 0, h_t = 0, gap = 0, along = 0;   // h_t: the tangential curvature term
    std::array<double, 4> frame{};               // point, unit normal
  };
  HeldFrame held_frame(const Held& c, const Kinematic& at) const;
  // The contact problem of the held contacts at a state: unilateral (the frictional LCP, states
  // decided where not sliding) or bilateral with the given states (the integration's RHS).
  struct HeldProblem {
    std::vector<HeldFrame> frames;
    std::vector<simulation::Friction> friction;
    Eigen::MatrixXd G;
    Eigen::VectorXd h, a0;
    simulation::FrictionalSolution solution;
  };
  HeldProblem held_problem(const Kinematic& at, bool unilateral, std::optional<int> forced = std::nullopt) const;
  // Stick or slip decided exactly (docs/simulation.md, "Stick or slip, decided exactly"): for a
  // part at rest (slower than v_rest) on held contacts of one frictional pair with parallel normals,
  // whose contact resultant balancing the loads (-(m g + F)) presses (N > 0) and passes between
  // the extreme contacts (no tipping), the sign of mu_s N - |F_t| in rationals at the exact
  // configuration and the model's exact loads: stick (0) at >= 0, else the slip direction of
  // the loads. Empty outside that class (the floating-point decision stands, labelled so).
  std::optional<int> exact_rest_state() const;
  Eigen::Vector3d inverse_mass() const { return Eigen::Vector3d(1 / mass, 1 / mass, 1 / inertia); }
  double tangential_tolerance() const { return rest_speed; }
  // Projects a state onto the held contacts' surfaces (gap = hold_gap) and their velocities
  // onto J v = 0 (and T v = 0 for sticking contacts), mass-weighted.
  void project(Kinematic& at, bool positions) const;
  // The longest chord (s) from a within delta/2 of the path to b (the bounds of both ends).
  double chord_cap(const Kinematic& a, const Kinematic& b) const;
  // Whether feature pair f, a vertex on the segment of a held vertex–segment contact, stays
  // apart along the held step from q0 to q1 (docs/simulation.md, "Turning on a vertex"):
  // eta bounds how far the path's angle leaves the ends' range.
  bool companion_apart(const SlicedFeaturePair& f, const SlicedConfiguration& q0, const SlicedConfiguration& q1,
                       const Rational& eta) const;
  // The held conditions at a state integrated with fixed states: 0 when all hold, else a
  // bit set: 1 lift-off (a bilateral force below 0), 2 stick -> slip, 4 slip -> stick
  // (the sliding velocity changes sign), 8 edge end (the foot leaves the segment).
  unsigned violated(const Kinematic& at, std::vector<unsigned>* per_contact = nullptr) const;
  // One fixed Dormand–Prince step of the held system from `from` for `span` seconds.
  Kinematic held_step(const Kinematic& from, double span) const;
  void held_rhs(const State6& y, State6& dy) const;
  // After an impact: hold the contacts without separating speed (vertex–segment contacts).
  void hold(double time, const Rows& rows);
  // Decides the held contacts' states at the start of a step (lift-offs, stick/slip, rest).
  // Returns true when it changed something (events: lift-off, stick/slip, rest).
  bool decide();
  // One step in sustained contact (always an event or progress: returns true, t advanced).
  bool held_advance(double span);
  SimulationEvent held_event(SimulationEvent::Kind kind, const Held& c, const HeldFrame& f, double normal_force,
                             double friction_force) const;
};

Eigen::Vector3d PlanarSimulation::Impl::free_acceleration(const Kinematic& at) const {
  Eigen::Vector3d a(accel[0] - damping_rate * at.vx, accel[1] - damping_rate * at.vy, alpha);
  if (!integrated) return a;
  double fx = 0, fy = 0, tau = -torsion_k * (at.theta - torsion_rest);
  const double c = std::cos(at.theta), sn = std::sin(at.theta);
  const double px = to_d(model.parts[part].motion.pivot.x) + at.x, py = to_d(model.parts[part].motion.pivot.y) + at.y;
  for (const LineSpring& sp : springs) {
    // the attachment point r (from the centre of mass), the line d from the anchor to it
    const double rx = c * sp.body[0] - sn * sp.body[1], ry = sn * sp.body[0] + c * sp.body[1];
    const double d[2] = {px + rx - sp.anchor[0], py + ry - sp.anchor[1]};
    const double dv[2] = {at.vx - at.omega * ry, at.vy + at.omega * rx};
    const auto [gx, gy] = spring_force(sp.k, sp.rest, sp.c, d, dv);
    fx += gx;
    fy += gy;
    tau += rx * gy - ry * gx;
  }
  return a + Eigen::Vector3d(fx / mass, fy / mass, tau / inertia);
}

double PlanarSimulation::Impl::spring_potential(const Kinematic& at) const {
  double e = 0.5 * torsion_k * (at.theta - torsion_rest) * (at.theta - torsion_rest);
  const double c = std::cos(at.theta), sn = std::sin(at.theta);
  const double px = to_d(model.parts[part].motion.pivot.x) + at.x, py = to_d(model.parts[part].motion.pivot.y) + at.y;
  for (const LineSpring& sp : springs) {
    const double rx = c * sp.body[0] - sn * sp.body[1], ry = sn * sp.body[0] + c * sp.body[1];
    const double L = std::hypot(px + rx - sp.anchor[0], py + ry - sp.anchor[1]);
    e += 0.5 * sp.k * (L - sp.rest) * (L - sp.rest);
  }
  return e;
}

const SlicedMotionCrossing& PlanarSimulation::Impl::earliest(
    const std::vector<std::pair<std::size_t, SlicedMotionCrossing>>& crossings,
    std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const {
  std::size_t best = 0;
  for (std::size_t i = 1; i < crossings.size(); ++i)
    if (crossings[i].second.u_lower < crossings[best].second.u_lower) best = i;
  const SlicedMotionCrossing& c = crossings[best].second;
  // every pair whose bracket meets the earliest one touches there (to the bracket's width)
  for (const auto& [i, other] : crossings)
    if (other.u_lower <= c.u_upper)
      for (const SlicedFeaturePair& f : other.features) touching.emplace_back(i, f);
  // contacts within delta of touching there are met at once (within the accuracy: a contact
  // this close is separated from the first by less than the chord's deviation)
  for (std::size_t i = 0; i < pairs.size(); ++i)
    for (const SlicedNearFeature& f : pairs[i].space.features_near(c.before, Rational(delta))) {
      if (behind_segment(model, f.pair, model.parts[part].motion.pivot, c.before)) continue;
      bool listed = false;
      for (const auto& [j, g] : touching) listed = listed || (j == i && g.label == f.pair.label);
      if (!listed) touching.emplace_back(i, f.pair);
    }
  return c;
}

bool PlanarSimulation::Impl::advance(double span) {
  const double pi = std::numbers::pi;
  Kinematic start = k;
  SlicedConfiguration node_q = q;
  double sa = 0;
  Kinematic node = start;
  const double slack = 64 * std::numeric_limits<double>::epsilon() * (std::abs(k.x) + std::abs(k.y) + reach + 1);
  double shorten = 1;   // < 1 after a chord met a contact the path leaves (see below)
  bool straight_chords = true;   // false once a straight chord met a crossing (see below)
  std::size_t tests = 0;         // this step's certified advances and exact chords
  while (sa < span) {
    // One step's collision tests are bounded (session 65, sim65): a part skimming a surface
    // took 23 819 chords in one step (hunt64's ladder pulled along the floor at 1.79e308 mm/s^2;
    // see the straight chords below). The bound is far above any ordinary step's count
    // (docs/simulation.md, "Session 65 (sim65)"), and independent of --max-steps.
    if (++tests > max_step_collision_tests) {
      std::ostringstream out;
      out << where(t + sa) << ": one step of the run took more than " << max_step_collision_tests
          << " collision tests (certified advances and exact chords; ordinary steps take at most "
          << ordinary_step_collision_tests << ") between t = " << t / time_scale << " and "
          << (t + sa) / time_scale << " " << time_unit << " of its step to " << (t + span) / time_scale << " "
          << time_unit << ", moving at " << std::hypot(node.vx, node.vy) * time_scale << " mm/" << time_unit
          << " (angular " << node.omega * time_scale << " rad/" << time_unit << ") within the chord deviation "
          << delta << " mm of the fixed parts" << largest_motion_datum(model)
          << "; a larger --accuracy (chord deviation) or a shorter --max-step lets it finish";
      throw NumericError(out.str());
    }
    double remaining = span - sa;
    // The horizon of the bounds: short enough that the speed at most about doubles over it (a
    // bound over a whole long step would be dominated by the speed gained at its end), at
    // least a chord length. The bounds below are computed for it exactly as stated.
    double horizon = remaining;
    {
      double now = std::hypot(node.vx, node.vy) + std::abs(node.omega) * reach;
      double gain = std::hypot(accel[0] - damping_rate * node.vx, accel[1] - damping_rate * node.vy) +
                    std::abs(alpha) * reach;
      if (gain > 0) horizon = std::min(remaining, std::max(now / gain, std::sqrt(8 * delta / gain)));
    }
    Kinematic end = flight(start, sa + horizon);
    double vmax = std::max(std::hypot(node.vx, node.vy), std::hypot(end.vx, end.vy));
    double wmax = std::max(std::abs(node.omega), std::abs(end.omega));
    double speed = vmax + wmax * reach;
    if (speed == 0) break;   // nothing moves
    // 1. conservative advancement
    double reach_distance = speed * horizon;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Pair& p : pairs) {
      ++stats.distance_queries;
      auto near = p.space.features_near(node_q, finite_exact(reach_distance, where(t), "the distance a step covers"));
      for (const auto& f : near) nearest = std::min(nearest, to_d(f.distance_lower));
    }
    if (nearest > reach_distance + slack) {   // no feature within reach: free over the horizon
      ++stats.advancement_steps;
      sa = horizon == remaining ? span : sa + horizon;
      node = end;
      node_q = configuration_of(node.x, node.y, node.theta);
      continue;
    }
    double safe = std::max(0.0, nearest - slack) / speed * (1 - 1e-12);
    // the chord length for the deviation delta
    double amax = 0;
    for (const Kinematic* s : {&node, &end})
      amax = std::max(amax, std::hypot(accel[0] - damping_rate * s->vx, accel[1] - damping_rate * s->vy));
    double phi = std::abs(wrap(node.theta));
    bool flip = phi > pi / 2;
    if (flip) phi = pi - phi;
    double tau_cap = wmax > 0 ? (pi / 4) / wmax : horizon;
    double w_bound = std::tan((phi + pi / 4) / 2);
    double wpp = 0.5 * (1 + w_bound * w_bound) * (std::abs(alpha) + w_bound * wmax * wmax);
    double bend = amax + 2 * reach * wpp;
    double tau = std::min(horizon, tau_cap);
    if (bend > 0) tau = std::min(tau, std::sqrt(8 * std::max(delta - slack, 0.5 * delta) / bend));
    tau *= shorten;
    bool straight = false;   // tau is a straight chord's, longer than the time-matched one
    // A straight chord (session 65, sim65): a part that does not turn (omega = alpha = 0, so
    // w is constant) moves on a straight line when its acceleration lies along its motion. The
    // chord bound above takes the whole acceleration, so a part skimming a surface under a load
    // along it took one chord per sqrt(8 delta / |a|) of time whatever the load: sqrt(L / delta)/2
    // chords for L mm (23 819 for the ladder pulled 200 mm along the floor, at 9810 mm/s^2 as at
    // 1.79e308 mm/s^2). The set swept by the path lies within delta of the chord's segment when
    // (a) its progress along the chord's direction e never reverses (the velocity moves on a
    // segment between its values at the ends, so e.v at both ends >= 0 suffices) and (b) its
    // distance from the chord's line, d(s) = n.(X(s) - X(s_a)), zero at both ends, has
    // |d''| = |n.X''| <= max over the ends of |n.(a - k v)|: |d| <= tau^2/8 max|n.X''|. The
    // direction's rounding is covered by a term of |X''| times the ends' coordinates' ulps over
    // the chord's length. Such a chord certifies freedom only: a crossing on it sends the step
    // back to the time-matched chords above (its contact time and state exactly as before).
    if (straight_chords && shorten == 1 && node.omega == 0 && alpha == 0 && tau < horizon) {
      const double limit = std::max(delta - slack, 0.5 * delta);
      double try_tau = horizon;
      for (int round = 0; round < 2; ++round) {
        const double sb_try = try_tau >= remaining ? span : sa + try_tau;
        const Kinematic e = flight(start, sb_try);
        const double dx = e.x - node.x, dy = e.y - node.y, length = std::hypot(dx, dy);
        if (!(length > 0) || !std::isfinite(length)) break;
        const double ux = dx / length, uy = dy / length;
        if (ux * node.vx + uy * node.vy < 0 || ux * e.vx + uy * e.vy < 0) break;   // (a)
        double normal = 0, whole = 0;
        for (const Kinematic* s : std::array<const Kinematic*, 2>{&node, &e}) {
          const double ax = accel[0] - damping_rate * s->vx, ay = accel[1] - damping_rate * s->vy;
          normal = std::max(normal, std::abs(-uy * ax + ux * ay));
          whole = std::max(whole, std::hypot(ax, ay));
        }
        const double ulps = 16 * std::numeric_limits<double>::epsilon() *
                            (std::abs(node.x) + std::abs(node.y) + std::abs(e.x) + std::abs(e.y) + length);
        normal += whole * ulps / length;
        const double span_try = sb_try - sa;
        if (!std::isfinite(normal)) break;
        if (span_try * span_try / 8 * normal <= limit) {   // (b)
          if (span_try > tau) tau = span_try, straight = true;
          break;
        }
        if (!(normal > 0)) break;
        try_tau = std::sqrt(8 * limit / normal) * (1 - 1e-9);   // the estimate's chord, checked again
        if (!(try_tau > tau)) break;
      }
    }
    // A chord the doubles cannot take (session 63, hunt63): a part spun by an impact at a speed
    // near the doubles' end (a ladder or a peg thrown at 1e308 mm/s) bends its path by more than
    // the doubles hold (bend = inf, so tau = 0); the certified advances then shrank geometrically
    // towards the contact and, once below the slack, stopped: the loop spun for ever, unbounded
    // by the step budget (a step's advances and chords do not count against it). Stopped when the
    // move it would take (the advance, else the chord) no longer advances the step's time.
    if (!(sa + (safe >= tau ? safe : tau) > sa)) {
      std::ostringstream out;
      out << where(t + sa) << " moves beyond the doubles' resolution: at speed " << speed << " mm/s (angular "
          << wmax << " rad/s) its certified free advance (" << safe << " s) and a chord of its path within the chord "
          << "deviation " << delta << " mm (" << tau << " s) are too short to advance the run's time "
          << (t + sa) / time_scale << " " << time_unit;
      throw NumericError(out.str());
    }
    if (safe >= tau) {
      ++stats.advancement_steps;
      sa = safe >= horizon ? (horizon == remaining ? span : sa + horizon) : sa + safe;
      node = flight(start, sa);
      node_q = configuration_of(node.x, node.y, node.theta);
      continue;
    }
    // 2. the chord [sa, sa + tau], exact
    double sb = tau >= remaining ? span : sa + tau;
    Kinematic next = flight(start, sb);
    SlicedConfiguration next_q = configuration_of(next.x, next.y, next.theta);
    SlicedMotion motion{node_q, next_q, flip, {}};
    ++stats.chord_tests;
    std::vector<std::pair<std::size_t, SlicedMotionCrossing>> crossings;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      SlicedMotionCrossing c = pairs[i].space.first_crossing(motion, CrossingOptions{options.crossing_bits});
      if (c.status == CrossingStatus::starts_in_contact) {
        std::ostringstream out;
        out << where(t + sa) << " starts a chord in contact with '" << model.parts[pairs[i].fixed].name
            << "' (the previous node was certified free: an internal error)";
        throw NumericError(out.str());
      }
      if (c.status == CrossingStatus::crossing) crossings.emplace_back(i, std::move(c));
    }
    if (crossings.empty()) {
      sa = sb;
      node = next;
      node_q = next_q;
      shorten = 1;
      continue;
    }
    if (straight) {   // a straight chord met a contact: the time-matched chords find it
      straight_chords = false;
      continue;
    }
    std::vector<std::pair<std::size_t, SlicedFeaturePair>> touching;
    const SlicedMotionCrossing& c = earliest(crossings, touching);
    double u = to_d(c.u_lower);
    double s_contact = sa + u * (sb - sa);
    Kinematic at = flight(start, s_contact);
    Rows rows = contact_rows(t + s_contact, at, c.before, touching);
    Eigen::VectorXd normal_speed = rows.J * Eigen::Vector3d(at.vx, at.vy, at.omega);
    if (normal_speed.minCoeff() >= 0 && shorten > 1e-9) {
      // The path leaves every contact the chord met (the chord, within delta of the path, cuts
      // the corner of a path that starts touching and departs): no impact; a shorter chord
      // deviates less (delta ~ tau^2) while the path departs linearly.
      shorten /= 4;
      continue;
    }
    t += s_contact;
    set_state(at, c.before);
    impact(t, rows);
    return true;
  }
  // the end node: certified free by the advancement or the last chord (its own configuration)
  if (sa == 0 && node.vx == 0 && node.vy == 0 && node.omega == 0 && accel[0] == 0 && accel[1] == 0 && alpha == 0)
    return false;   // nothing moves: the exact configuration stays
  k = flight(start, span);
  q = configuration_of(k.x, k.y, k.theta);
  return false;
}

PlanarSimulation::Impl::Rows PlanarSimulation::Impl::contact_rows(
    double time, const Kinematic& at, const SlicedConfiguration& c,
    const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const {
  // contact rows J = [n_x, n_y, r x n] (unit normal from the fixed part into the planar part)
  std::vector<std::array<double, 3>> rows;
  Rows out;
  for (const auto& [i, f] : touching) {
    SlicedContactFrame frame = sliced_contact_frame(model, f, c);
    if (!frame.defined) continue;   // vertex–vertex: its neighbouring edges carry the contact
    double px = to_d(frame.point.x), py = to_d(frame.point.y);
    double nx = to_d(frame.normal.x), ny = to_d(frame.normal.y), n = std::hypot(nx, ny);
    if (!(n > 0)) continue;
    nx /= n;
    ny /= n;
    double rx = px - (to_d(model.parts[part].motion.pivot.x) + at.x);
    double ry = py - (to_d(model.parts[part].motion.pivot.y) + at.y);
    std::array<double, 3> row{nx, ny, rx * ny - ry * nx};
    bool repeated = false;
    for (const auto& r : rows)
      if (std::abs(r[0] - row[0]) + std::abs(r[1] - row[1]) + std::abs(r[2] - row[2]) / std::max(reach, 1.0) < 1e-12)
        repeated = true;
    if (repeated) continue;
    rows.push_back(row);
    out.frames.push_back({px, py, nx, ny});
    out.pair.push_back(i);
    out.feature.push_back(f);
    const Rational erx = frame.point.x - (model.parts[part].motion.pivot.x + c.x);
    const Rational ery = frame.point.y - (model.parts[part].motion.pivot.y + c.y);
    out.exact.push_back({{frame.normal.x, frame.normal.y, Rational(erx * frame.normal.y - ery * frame.normal.x)},
                         Rational(frame.normal.x * frame.normal.x + frame.normal.y * frame.normal.y)});
  }
  if (rows.empty())
    throw GeometryError(where(time) + " touches a fixed part only at vertex–vertex contacts: no contact normal");
  out.J.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) out.J.row(static_cast<Eigen::Index>(r)) << rows[r][0], rows[r][1], rows[r][2];
  return out;
}

std::vector<PlanarSimulation::Impl::PairEvent> PlanarSimulation::Impl::pair_events(
    SimulationEvent::Kind kind, double time, const Rows& rows, const Eigen::VectorXd& lambda) const {
  std::vector<PairEvent> out;
  std::vector<bool> done(pairs.size(), false);
  for (std::size_t r = 0; r < rows.pair.size(); ++r) {
    std::size_t i = rows.pair[r];
    if (done[i]) continue;
    done[i] = true;
    PairEvent p;
    p.event.kind = kind;
    p.event.time = time / time_scale;
    p.event.pair = pairs[i].index;
    p.event.first_part = model.parts[pairs[i].fixed].name;
    p.event.second_part = model.parts[part].name;
    p.top = static_cast<Eigen::Index>(r);
    for (std::size_t s = 0; s < rows.pair.size(); ++s)
      if (rows.pair[s] == i) {
        auto row = static_cast<Eigen::Index>(s);
        p.event.features.push_back(rows.feature[s].label);
        p.total += lambda(row);
        if (lambda(row) > lambda(p.top)) p.top = row;
      }
    out.push_back(std::move(p));
  }
  return out;
}

void PlanarSimulation::Impl::impact(double time, const Rows& contact) {
  const Eigen::MatrixXd& J = contact.J;
  const auto& frames = contact.frames;
  const auto& rows_pair = contact.pair;
  const Kinematic at = k;
  const std::size_t m = rows_pair.size();
  Eigen::Vector3d minv(1 / mass, 1 / mass, 1 / inertia);
  Eigen::Vector3d v(at.vx, at.vy, at.omega);
  Eigen::VectorXd before = J * v;
  // (session 68, impact68: slower than the rest speed decided exactly on J, v — was the rounded J v)
  bool plastic = simulation::slower_than(J, v, rest_speed);
  Eigen::MatrixXd A = J * minv.asDiagonal() * J.transpose();
  Eigen::VectorXd b(m), restitution(m);
  for (std::size_t r = 0; r < m; ++r) {
    double e = plastic ? 0.0 : pairs[rows_pair[r]].restitution;
    restitution(static_cast<Eigen::Index>(r)) = e;
    b(r) = (1 + e) * before(r);
  }
  // the restitution terms e J v- exactly (every row, as b)
  const std::vector<Rational> h_exact =
      simulation::exact_restitution_terms(J, Eigen::VectorXd(v), restitution, false);
  bool frictional = false;
  for (std::size_t r = 0; r < m; ++r) frictional = frictional || pairs[rows_pair[r]].mu_static > 0;
  simulation::LcpSolution lcp;
  Eigen::VectorXd tangential = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m));
  Eigen::Vector3d after_v;
  if (!frictional) {
    lcp = simulation::solve_lcp(A, b);
    // (session 68, impact68: which rows get an impulse decided exactly — exact_impact_lcp)
    const std::optional<simulation::FrictionalSolution> exact =
        simulation::exact_impact_lcp(J, Eigen::VectorXd(minv), Eigen::VectorXd(v), h_exact, lcp);
    if (exact) lcp.solved = exact->solved;
    if (!lcp.solved) throw NumericError(where(time) + ": the impact problem has no solution");
    if (exact) {
      lcp.lambda = exact->lambda;
      after_v = exact->x;
    } else {
      after_v = v + minv.asDiagonal() * (J.transpose() * lcp.lambda);
    }
  } else {
    // Newton restitution with Coulomb-limited tangential impulses: the fixed-axis simulator's
    // frictional impulse problem (src/simulation/friction.hpp) over (x, y, theta)
    std::vector<simulation::Friction> friction(m);
    for (std::size_t r = 0; r < m; ++r) {
      const Pair& pair = pairs[rows_pair[r]];
      simulation::Friction& f = friction[r];
      f.on = pair.mu_static > 0;
      double nx = frames[r][2], ny = frames[r][3];
      double rx = frames[r][0] - (to_d(model.parts[part].motion.pivot.x) + at.x);
      double ry = frames[r][1] - (to_d(model.parts[part].motion.pivot.y) + at.y);
      f.T = Eigen::Vector3d(-ny, nx, rx * nx + ry * ny);
      f.mu_static = pair.mu_static;
      f.mu_kinetic = pair.mu_kinetic;
    }
    Eigen::VectorXd h = b - before;   // e J v-
    bool limited = false;
    simulation::FrictionalSolution sol = frictional_impact(J, Eigen::VectorXd(minv), v, h, friction,
                                                           collinear_groups(friction, rows_pair), where(time),
                                                           named_pairs(rows_pair), limited, &h_exact);
    if (limited) ++stats.restitution_limited;
    lcp.lambda = sol.lambda;
    lcp.solved = true;
    tangential = sol.f;
    after_v = sol.x;
  }
  Eigen::VectorXd after = J * after_v;
  k.vx = after_v(0);
  k.vy = after_v(1);
  k.omega = after_v(2);
  // one impact event per pair, at its row of largest impulse
  for (PairEvent& p : pair_events(SimulationEvent::Kind::impact, time, contact, lcp.lambda)) {
    p.event.impulse = p.total / (force_scale * time_scale);
    p.event.normal_speed_before = before(p.top) * time_scale;
    p.event.normal_speed_after = after(p.top) * time_scale;
    p.event.point = {frames[p.top][0], frames[p.top][1]};
    p.event.normal = {frames[p.top][2], frames[p.top][3]};
    for (std::size_t r = 0; r < m; ++r)
      if (pairs[rows_pair[r]].index == p.event.pair)
        p.event.tangential_impulse += tangential(static_cast<Eigen::Index>(r)) / (force_scale * time_scale);
    events.push_back(std::move(p.event));
  }
  if (!plastic) {
    plastic_run = 0;
    hold(time, contact);
    return;
  }
  if (try_rest(contact)) {
    plastic_run = 0;
    return;
  }
  hold(time, contact);
  if (!held.empty()) {
    plastic_run = 0;
    return;
  }
  if (++plastic_run > 200)
    throw NumericError(where(time) + " keeps touching a fixed part at speeds below " +
                       std::to_string(rest_speed * time_scale) +
                       " mm per time unit without coming to rest: sustained sliding or rocking contact of a planar "
                       "part is not supported (only resting contact is; docs/simulation.md)");
}

// After a plastic impact: does the part rest? Its speed is below the rest speed and the contact
// forces (a complementarity problem on the normal accelerations) balance the loads.
bool PlanarSimulation::Impl::try_rest(const Rows& contact) {
  const Eigen::MatrixXd& J = contact.J;
  double speed = std::hypot(k.vx, k.vy) + std::abs(k.omega) * reach;
  if (speed > rest_speed) return false;
  Eigen::Vector3d minv(1 / mass, 1 / mass, 1 / inertia);
  Kinematic still = k;
  still.vx = still.vy = still.omega = 0;
  Eigen::Vector3d free_acc = free_acceleration(still);   // at rest: no damping, no centripetal terms
  Eigen::MatrixXd A = J * minv.asDiagonal() * J.transpose();
  Eigen::VectorXd b = J * free_acc;
  simulation::LcpSolution lcp = simulation::solve_lcp(A, b);
  if (!lcp.solved) return false;
  Eigen::Vector3d acc = free_acc + minv.asDiagonal() * (J.transpose() * lcp.lambda);
  double scale = std::hypot(free_acc(0), free_acc(1)) + std::abs(free_acc(2)) * reach;
  double residual = std::hypot(acc(0), acc(1)) + std::abs(acc(2)) * reach;
  // balanced: the residual acceleration is round-off of the solve (its tolerance is 1e-10
  // relative, lcp_tolerance), not a motion
  if (residual > 1e-9 * std::max(scale, 1e-300)) return false;
  resting = true;
  k.vx = k.vy = k.omega = 0;
  for (PairEvent& p : pair_events(SimulationEvent::Kind::contact, t, contact, lcp.lambda)) {
    p.event.normal_force = p.total / force_scale;
    events.push_back(std::move(p.event));
  }
  return true;
}

// ---------------------------------------------------------------- sustained contact

PlanarSimulation::Impl::HeldFrame PlanarSimulation::Impl::held_frame(const Held& c, const Kinematic& at) const {
  const Point& pivot = model.parts[part].motion.pivot;
  ContactGap<double> g = contact_gap(model, c.feature, pose_of(pivot, at), true);
  double n = std::hypot(g.normal.x, g.normal.y);
  double nx = g.normal.x / n, ny = g.normal.y / n;
  double rx = g.point.x - (pivot.x.get_d() + at.x), ry = g.point.y - (pivot.y.get_d() + at.y);
  HeldFrame f;
  f.J = Eigen::Vector3d(nx, ny, rx * ny - ry * nx);
  f.T = Eigen::Vector3d(-ny, nx, rx * nx + ry * ny);
  f.gap = g.gap / n;
  f.along = g.along;
  f.frame = {g.point.x, g.point.y, nx, ny};
  // curvature terms (d2g/dt2 - J qdd): a vertex of the part on a fixed segment: -w^2 (n . r);
  // a fixed vertex on a segment of the part: -2 w (v x n) + w^2 (r . n)
  double w = at.omega, rn = rx * nx + ry * ny;
  if (g.arc) {   // a pair with an arc: the curvature terms from the kernels' frame differentiated
    held_arc_terms(model, c.feature, pivot, at, rx, ry, f.h, f.h_t);
    return f;
  }
  f.h = g.free_vertex ? -w * w * rn : -2 * w * (at.vx * ny - at.vy * nx) + w * w * rn;
  // the same for the sliding velocity T qdot (a sticking contact keeps it 0): a vertex of the
  // part: -w^2 (t . r); a fixed vertex on the part's segment: -w (J qdot) - w (v x t)
  double rt = rx * -ny + ry * nx;
  double jv = f.J.dot(Eigen::Vector3d(at.vx, at.vy, at.omega));
  f.h_t = g.free_vertex ? -w * w * rt : -w * jv - w * (at.vx * nx - at.vy * -ny);
  return f;
}

PlanarSimulation::Impl::HeldProblem PlanarSimulation::Impl::held_problem(const Kinematic& at, bool unilateral,
                                                                         std::optional<int> forced) const {
  HeldProblem p;
  const auto m = static_cast<Eigen::Index>(held.size());
  p.G.resize(m, 3);
  p.h.resize(m);
  p.a0 = free_acceleration(at);
  if (m == 0) {   // free flight (integrated: springs act)
    p.solution.solved = true;
    p.solution.x = p.a0;
    p.solution.lambda = p.solution.w = p.solution.f = Eigen::VectorXd(0);
    return p;
  }
  Eigen::Vector3d v(at.vx, at.vy, at.omega);
  std::vector<int> states;
  for (Eigen::Index r = 0; r < m; ++r) {
    const Held& c = held[static_cast<std::size_t>(r)];
    p.frames.push_back(held_frame(c, at));
    const HeldFrame& f = p.frames.back();
    p.G.row(r) = f.J.transpose();
    p.h(r) = f.h;
    const Pair& pair = pairs[c.pair];
    simulation::Friction fr = held_friction(f, pair.mu_static, pair.mu_kinetic, v, tangential_tolerance(), c.state);
    if (forced && fr.on) {   // the exact decision (exact_rest_state)
      fr.decided = true;
      fr.state = *forced;
    }
    p.friction.push_back(fr);
    states.push_back(fr.on ? c.state : simulation::frictionless);
  }
  std::vector<std::size_t> pair_of;
  for (const Held& c : held) pair_of.push_back(c.pair);
  solve_held_forces(p, inverse_mass(), pair_of, unilateral, states, !forced);
  return p;
}

void PlanarSimulation::Impl::project(Kinematic& at, bool positions) const {
  project_held(
      held.size(), Eigen::VectorXd(inverse_mass()), hold_gap, positions, [&](std::size_t c) { return held_frame(held[c], at); },
      [&](std::size_t c) { return pairs[held[c].pair].mu_static > 0 && held[c].state == simulation::stick; },
      [&](const Eigen::VectorXd& dq) {
        at.x += dq(0);
        at.y += dq(1);
        at.theta += dq(2);
      },
      [&] { return Eigen::VectorXd(Eigen::Vector3d(at.vx, at.vy, at.omega)); },
      [&](const Eigen::VectorXd& v) {
        at.vx = v(0);
        at.vy = v(1);
        at.omega = v(2);
      });
}

void PlanarSimulation::Impl::held_rhs(const State6& y, State6& dy) const {
  Kinematic at = to_kinematic(y);
  HeldProblem p = held_problem(at, false);
  dy = {at.vx, at.vy, at.omega, p.solution.x(0), p.solution.x(1), p.solution.x(2)};
}

Kinematic PlanarSimulation::Impl::held_step(const Kinematic& from, double span) const {
  boost::numeric::odeint::runge_kutta_dopri5<State6> stepper;
  State6 y = to_array(from);
  stepper.do_step([this](const State6& x, State6& dx, double) { held_rhs(x, dx); }, y, 0.0, span);
  Kinematic out = to_kinematic(y);
  project(out, true);
  return out;
}

unsigned PlanarSimulation::Impl::violated(const Kinematic& at, std::vector<unsigned>* per_contact) const {
  return held_violations(held_problem(at, false), held, pairs, Eigen::VectorXd(Eigen::Vector3d(at.vx, at.vy, at.omega)),
                         Eigen::VectorXd(inverse_mass()), per_contact);
}

SimulationEvent PlanarSimulation::Impl::held_event(SimulationEvent::Kind kind, const Held& c, const HeldFrame& f,
                                                   double normal_force, double friction_force) const {
  return held_contact_event(kind, t / time_scale, pairs[c.pair].index, model.parts[pairs[c.pair].fixed].name,
                            model.parts[part].name, c.feature.label, f.frame, normal_force, friction_force, force_scale);
}

void PlanarSimulation::Impl::hold(double time, const Rows& rows) {
  held.clear();
  // exact decisions (held_resolution.hpp): the rows at the exact configuration, the velocities,
  // masses and speeds as the exact values of their doubles
  const char* const speed = "the part's velocity";
  const std::vector<Rational> v{finite_exact(k.vx, where(time), speed), finite_exact(k.vy, where(time), speed),
                                finite_exact(k.omega, where(time), speed)};
  const Eigen::Vector3d minv_d = inverse_mass();
  const std::vector<Rational> minv{Rational(minv_d(0)), Rational(minv_d(1)), Rational(minv_d(2))};
  const Rational rest = finite_exact(rest_speed, where(time), "the rest speed"), reach_exact(reach);
  std::vector<bool> candidate(rows.pair.size());
  for (std::size_t r = 0; r < rows.pair.size(); ++r)
    candidate[r] = !simulation::separating_faster_than(rows.exact[r], v, rest) &&   // not separating
                   contact_gap(model, rows.feature[r], pose_of(model.parts[part].motion.pivot, k), true).defined;   // a contact of its own
  const std::vector<bool> keep =
      simulation::held_at_resolution(candidate, rows.exact, minv, v, [&](std::size_t) { return reach_exact; }, rest);
  for (std::size_t r = 0; r < rows.pair.size(); ++r) {
    if (!keep[r]) continue;
    Held c{rows.pair[r], rows.feature[r], simulation::frictionless};
    bool repeated = false;
    for (const Held& h : held) repeated = repeated || (h.feature.fixed == c.feature.fixed && h.feature.free == c.feature.free);
    if (!repeated) held.push_back(c);
  }
  if (held.empty()) return;
  // the velocity onto the held contacts' tangent space (their normal speeds are below the rest
  // speed: a plastic remainder)
  project(k, false);
  for (const Held& c : held) events.push_back(held_event(SimulationEvent::Kind::contact, c, held_frame(c, k), 0, 0));
  (void)time;
}

std::optional<int> PlanarSimulation::Impl::exact_rest_state() const {
  if (held.size() < 2) return std::nullopt;   // one vertex: no balance at rest in general
  if (integrated) return std::nullopt;        // spring forces are not exact rationals: labelled approximate
  double speed = std::hypot(k.vx, k.vy) + std::abs(k.omega) * reach;
  if (speed > rest_speed) return std::nullopt;
  const Pair& pair = pairs[held.front().pair];
  if (!(pair.mu_static > 0)) return std::nullopt;
  const Point& pivot = model.parts[part].motion.pivot;
  const kernels::Pose<Rational> pose = pose_of(pivot, q);
  using V = kernels::Vector<Rational>;
  std::vector<ContactGap<Rational>> gaps;
  for (const Held& c : held) {
    if (c.pair != held.front().pair) return std::nullopt;
    gaps.push_back(contact_gap(model, c.feature, pose));
    if (!gaps.back().defined) return std::nullopt;
  }
  const V n = gaps.front().normal, t{-n.y, n.x};
  const V centre{pivot.x + q.x, pivot.y + q.y};
  // a face on a face: the normals parallel and of one direction (exactly; the contact points
  // lie on one line to the hold gap)
  for (const ContactGap<Rational>& g : gaps)
    if (sgn(g.normal.x * n.y - g.normal.y * n.x) != 0 || sgn(kernels::dot(g.normal, n)) <= 0) return std::nullopt;
  // the contact resultant at rest balances the loads: C = -(m g + F); it presses
  const V C{-load_x, -load_y};
  const Rational normal = kernels::dot(C, n), tangential = kernels::dot(C, t);
  if (sgn(normal) <= 0) return std::nullopt;
  // no tipping: the torque balance puts C between the extreme contacts a, b along the line,
  // sigma (r_a x C) + (1 - sigma) (r_b x C) = -T with 0 <= sigma <= 1
  std::size_t a = 0, b = 0;
  for (std::size_t i = 1; i < gaps.size(); ++i) {
    if (kernels::dot(gaps[i].point, t) < kernels::dot(gaps[a].point, t)) a = i;
    if (kernels::dot(gaps[i].point, t) > kernels::dot(gaps[b].point, t)) b = i;
  }
  auto cross = [](const V& u, const V& v) { return Rational(u.x * v.y - u.y * v.x); };
  const V ra = gaps[a].point - centre, rb = gaps[b].point - centre;
  const Rational den = cross(ra - rb, C), num = -load_torque - cross(rb, C);
  if (sgn(den) == 0) return std::nullopt;
  const Rational sigma = num / den;
  if (sgn(sigma) < 0 || sigma > 1) return std::nullopt;
  // the static cone (mu_s N - |F| scaled by the common positive |n| / m): exact
  const Rational margin = pair.mu_static_exact * normal - abs(tangential);
  if (sgn(margin) >= 0) return simulation::stick;
  // slipping from rest: the contact point moves the way the loads push along t
  return sgn(tangential) < 0 ? simulation::slip_positive : simulation::slip_negative;
}

bool PlanarSimulation::Impl::decide() {
  if (held.empty()) return false;   // integrated free flight: nothing to decide
  HeldProblem p = held_problem(k, true);
  // stick or slip decided exactly where the state is in the rest class (else in floating point)
  std::optional<int> exact = exact_rest_state();
  if (exact) {
    bool agree = p.solution.solved;
    for (std::size_t c = 0; agree && c < held.size(); ++c) agree = p.solution.state[c] == *exact;
    if (!agree) {
      HeldProblem forced = held_problem(k, true, exact);
      if (forced.solution.solved) p = std::move(forced);
      else exact.reset();
    }
  }
  if (!p.solution.solved)
    throw NumericError(where(t) + ": " +
                       simulation::frictional_refusal("the contact problem of its held contacts", p.solution.exhausted) +
                       named_pairs(held_pairs()));
  std::vector<std::size_t> pair_of;
  for (const Held& c : held) pair_of.push_back(c.pair);
  const std::vector<bool> lifts = lift_offs(p, Eigen::VectorXd(inverse_mass()), pair_of);
  std::vector<Held> kept;
  std::vector<HeldFrame> frames;
  bool changed = false;
  for (std::size_t c = 0; c < held.size(); ++c) {
    const auto r = static_cast<Eigen::Index>(c);
    Held h = held[c];
    double lambda = p.solution.lambda(r);
    if (lifts[c]) {   // no force and separating, exactly: lift-off
      events.push_back(held_event(SimulationEvent::Kind::lift_off, h, p.frames[c], 0, 0));
      continue;
    }
    int state = p.friction[c].on ? p.solution.state[c] : simulation::frictionless;
    if (state != h.state && p.friction[c].on) {
      SimulationEvent e = held_event(state == simulation::stick ? SimulationEvent::Kind::stick : SimulationEvent::Kind::slip,
                                     h, p.frames[c], lambda, p.solution.f(r));
      if (state != simulation::stick) e.slip_direction = state;
      e.exact_decision = exact.has_value();
      events.push_back(std::move(e));
      changed = true;
    }
    h.state = state;
    kept.push_back(h);
    frames.push_back(p.frames[c]);
  }
  bool lifted = kept.size() != held.size();
  held = std::move(kept);
  // a contact that starts to stick keeps no sliding velocity (below the tangential tolerance):
  // removed now, mass-weighted (dissipative), so that its stick force does no work
  if (changed) project(k, false);
  if (held.empty() || lifted) return true;   // the next problem (or free flight) decides the rest
  // at rest: slower than the rest speed and the contact forces balance the loads
  double speed = std::hypot(k.vx, k.vy) + std::abs(k.omega) * reach;
  const Eigen::VectorXd& acc = p.solution.x;
  double scale = std::hypot(p.a0(0), p.a0(1)) + std::abs(p.a0(2)) * reach;
  double residual = std::hypot(acc(0), acc(1)) + std::abs(acc(2)) * reach;
  if (speed > rest_speed || residual > 1e-9 * std::max(scale, 1e-300)) return changed;
  if (exact && *exact != simulation::stick) return changed;   // slipping, decided exactly: not at rest
  resting = true;
  k.vx = k.vy = k.omega = 0;
  // one event per fixed part, with its total normal force and friction force (as try_rest)
  Rows rows;
  rows.J = p.G;
  for (std::size_t c = 0; c < held.size(); ++c) {
    rows.frames.push_back(frames[c].frame);
    rows.pair.push_back(held[c].pair);
    rows.feature.push_back(held[c].feature);
  }
  for (PairEvent& e : pair_events(SimulationEvent::Kind::contact, t, rows, p.solution.lambda)) {
    e.event.normal_force = e.total / force_scale;
    for (std::size_t c = 0; c < held.size(); ++c)
      if (pairs[held[c].pair].index == e.event.pair) e.event.friction_force += p.solution.f(static_cast<Eigen::Index>(c)) / force_scale;
    e.event.point = {frames[static_cast<std::size_t>(e.top)].frame[0], frames[static_cast<std::size_t>(e.top)].frame[1]};
    e.event.normal = {frames[static_cast<std::size_t>(e.top)].frame[2], frames[static_cast<std::size_t>(e.top)].frame[3]};
    events.push_back(std::move(e.event));
  }
  return true;
}

double PlanarSimulation::Impl::chord_cap(const Kinematic& a, const Kinematic& b) const {
  const double pi = std::numbers::pi;
  double amax = 0, wmax = 0, alpha_max = 0;
  for (const Kinematic* s : {&a, &b}) {
    Eigen::VectorXd acc = held_problem(*s, false).solution.x;
    amax = std::max(amax, std::hypot(acc(0), acc(1)));
    alpha_max = std::max(alpha_max, std::abs(acc(2)));
    wmax = std::max(wmax, std::abs(s->omega));
  }
  double phi = std::abs(wrap(a.theta));
  if (phi > pi / 2) phi = pi - phi;
  double w_bound = std::tan((phi + pi / 4) / 2);
  double wpp = 0.5 * (1 + w_bound * w_bound) * (alpha_max + w_bound * wmax * wmax);
  double bend = amax + 2 * reach * wpp;
  double cap = wmax > 0 ? (pi / 4) / wmax : std::numeric_limits<double>::infinity();
  if (bend > 0) cap = std::min(cap, std::sqrt(8 * 0.5 * delta / bend));
  return cap;
}

bool PlanarSimulation::Impl::companion_apart(const SlicedFeaturePair& f, const SlicedConfiguration& q0,
                                             const SlicedConfiguration& q1, const Rational& eta) const {
  using V = kernels::Vector<Rational>;
  if (q0.angle.half_turn || q1.angle.half_turn) return false;
  const Point& pivot = model.parts[part].motion.pivot;
  const kernels::Pose<Rational> pose0 = pose_of(pivot, q0), pose1 = pose_of(pivot, q1);
  for (const Held& c : held) {
    // the held contact and f: vertex–segment pairs on one segment, each vertex on the other part
    const bool fixed_segment = c.feature.fixed.kind == FeatureKind::segment && c.feature.free.kind == FeatureKind::vertex;
    const bool free_segment = c.feature.fixed.kind == FeatureKind::vertex && c.feature.free.kind == FeatureKind::segment;
    if (fixed_segment ? !(f.fixed == c.feature.fixed && f.free.kind == FeatureKind::vertex)
                      : !(free_segment && f.free == c.feature.free && f.fixed.kind == FeatureKind::vertex))
      continue;
    const kernels::FeatureGeometry<Rational> seg = feature_geometry<Rational>(model, fixed_segment ? c.feature.fixed : c.feature.free);
    const V vc = feature_geometry<Rational>(model, fixed_segment ? c.feature.free : c.feature.fixed).point;
    const V vf = feature_geometry<Rational>(model, fixed_segment ? f.free : f.fixed).point;
    // at an end: n (the segment's normal, world, |n| = the segment's length), the held vertex's
    // gap n . (V_c - s0) and the difference of the gaps n . (V_f - V_c), a function of the angle only
    auto at = [&](const kernels::Pose<Rational>& pose, Rational& gap, Rational& difference) {
      V s0 = seg.point, s1 = seg.target, c_world = vc, f_world = vf;
      if (fixed_segment) {
        c_world = kernels::world_point(pose, vc);
        f_world = kernels::world_point(pose, vf);
      } else {
        s0 = kernels::world_point(pose, seg.point);
        s1 = kernels::world_point(pose, seg.target);
      }
      const V d = s1 - s0, n{d.y, Rational(-d.x)};
      gap = kernels::dot(n, c_world - s0);
      difference = kernels::dot(n, f_world - c_world);
    };
    Rational g0, g1, d0, d1;
    at(pose0, g0, d0);
    at(pose1, g1, d1);
    if (sgn(g0) < 0) {   // the normal toward the held vertex's side (apart)
      g0 = -g0;
      g1 = -g1;
      d0 = -d0;
      d1 = -d1;
    }
    if (sgn(g0) <= 0 || sgn(g1) <= 0) return false;
    // the difference is rho cos(theta - phi), rho = |n| |V_f - V_c| (body vectors for the
    // rotating ones): over an angle range of length l it is at least its smaller end value less
    // rho l^2 / 8, and over the range widened by eta at each side less rho eta more.
    // l <= 2 |t1 - t0| (theta = 2 atan t); rho from above by the 1-norms
    const V dn = seg.target - seg.point, dd = vf - vc;
    const Rational rho = (abs(dn.x) + abs(dn.y)) * (abs(dd.x) + abs(dd.y));
    const Rational l = 2 * abs(q1.angle.t - q0.angle.t);
    const Rational lowest = (cmp(d0, d1) < 0 ? d0 : d1) - rho * (l * l / 8 + eta);
    // the held gap along the path: at least half its smaller end value (the held dynamics keep
    // it constant; the projection puts it at the hold gap within 1e-3 at every state)
    return sgn((g0 < g1 ? g0 : g1) / 2 + lowest) > 0;
  }
  return false;
}

bool PlanarSimulation::Impl::held_advance(double span) {
  using namespace boost::numeric::odeint;
  // a change of the held set or of a state is a step of its own (its events at its time)
  if (decide()) return true;
  const Kinematic k0 = k;
  const SlicedConfiguration q0 = q;
  auto rhs = [this](const State6& x, State6& dx, double) { held_rhs(x, dx); };
  double h = step_guess > 0 ? std::min(step_guess, span)
                            : first_trial(to_array(k0), [this](const State6& x, State6& dx) { held_rhs(x, dx); }, span);
  const bool flip = std::abs(wrap(k0.theta)) > std::numbers::pi / 2;
  std::vector<std::pair<FeatureIdentity, FeatureIdentity>> ignored;
  for (const Held& c : held) ignored.emplace_back(c.feature.fixed, c.feature.free);
  for (int attempt = 0; attempt < 60; ++attempt) {
    // a fresh stepper per attempt: Dormand–Prince reuses its last derivative (FSAL), which
    // belongs to the previous attempt's end
    auto stepper = make_controlled(accuracy, accuracy, runge_kutta_dopri5<State6>());
    State6 y = to_array(k0);
    double tt = 0, trial = h;
    for (int tries = 0; stepper.try_step(rhs, y, tt, trial) == fail; ++tries)
      if (tries > 200 || !(trial > 0)) throw NumericError(where(t) + ": the integration in sustained contact fails");
    double end = tt;
    step_guess = trial;
    Kinematic kend = to_kinematic(y);
    project(kend, true);
    std::vector<unsigned> bits;   // the first violated condition, by bisection to 2^-50 of the step
    cut_at_first_violation(
        end, kend, [&](double s) { return held_step(k0, s); },
        [&](const Kinematic& at, std::vector<unsigned>* b) { return violated(at, b); }, bits);
    // Far from every other feature pair: certified, the straight motion q0 -> q1 in (x, y, w)
    // moves no point of the part farther than the exact sweep bound D (planar_bounds.hpp), and
    // features_near's certified lower distance of every other feature pair exceeds D (compared
    // in rationals). The integrated path between the two states is the integrator's (to its
    // accuracy): it is also kept apart from them, in double, by twice the distance its points can
    // travel in the step (speed at the ends plus acceleration x step) plus delta. Otherwise the
    // chord, within delta of the path, is tested exactly.
    double travel = 0, turn_acceleration = 0;
    for (const Kinematic* e : std::array<const Kinematic*, 2>{&k0, &kend}) {
      Eigen::VectorXd acc = held_problem(*e, false).solution.x;
      double speed = std::hypot(e->vx, e->vy) + std::abs(e->omega) * reach;
      double gain = std::hypot(acc(0), acc(1)) + std::abs(acc(2)) * reach;
      travel = std::max(travel, (speed + gain * end) * end);
      turn_acceleration = std::max(turn_acceleration, std::abs(acc(2)));
    }
    // how far the path's angle can leave the range of its ends: max|theta''| step^2 / 8, twice
    // (none certified without a finite bound)
    const double eta_bound = 2 * turn_acceleration * end * end / 8;
    const bool companions = simulation::companion_watch() && std::isfinite(eta_bound);
    const Rational eta(companions ? eta_bound : 0.0);
    const SlicedConfiguration q_end = configuration_of(kend.x, kend.y, kend.theta);
    const std::optional<Rational> sweep = simulation::motion_sweep_bound(q0, q_end, flip, reach_bound);
    Rational radius(2 * travel + delta);
    if (sweep && *sweep > radius) radius = *sweep;
    double nearest = std::numeric_limits<double>::infinity();
    std::optional<Rational> nearest_exact;
    for (const Pair& pr : pairs) {
      ++stats.distance_queries;
      for (const SlicedNearFeature& f : pr.space.features_near(q0, radius)) {
        bool is_held = false;
        for (const Held& c : held) is_held = is_held || (c.feature.fixed == f.pair.fixed && c.feature.free == f.pair.free);
        if (is_held) continue;
        if (companions && companion_apart(f.pair, q0, q_end, eta)) {   // apart along the step
          ++simulation::companion_steps();
          continue;
        }
        nearest = std::min(nearest, to_d(f.distance_lower));
        if (!nearest_exact || f.distance_lower < *nearest_exact) nearest_exact = f.distance_lower;
      }
    }
    // none returned: every other feature pair is farther than the radius (>= D)
    const bool far = sweep && (!nearest_exact || *nearest_exact > *sweep) && nearest > 2 * travel + delta;
    double cap = far ? std::numeric_limits<double>::infinity() : chord_cap(k0, kend);
    if (!far) {
      // conservative advancement as in free flight: a step short enough to be far, when that
      // is longer than a chord (e.g. just after a lift-off, the contact left slowly); the sweep
      // bound grows about linearly with the step, so the step is also scaled to half of it
      double rate = travel / end;   // speed + gain x end, which only falls as the step does
      double h_far = rate > 0 && nearest > delta ? 0.5 * (nearest - delta) / rate * (1 - 1e-6) : 0;
      if (sweep && sgn(*sweep) > 0 && nearest_exact)
        h_far = std::min(h_far, 0.5 * end * to_d(*nearest_exact) / to_d(*sweep));
      if (!sweep) h_far = 0;
      if (h_far > cap && h_far < end) {
        h = step_guess = h_far;
        continue;
      }
    }
    if (end > cap * (1 + 1e-9)) {   // the chord would deviate more than delta: shorter
      h = step_guess = cap;
      continue;
    }
    const SlicedConfiguration& q1 = q_end;
    // the held contacts at the new state: exactly apart from their segments' lines
    const Point& pivot = model.parts[part].motion.pivot;
    for (const Held& c : held)
      if (sgn(contact_gap(model, c.feature, pose_of(pivot, q1), true).gap) <= 0)
        throw NumericError(where(t + end) + ": a held contact's projected state is not exactly apart (internal error)");
    // every other feature pair: the chord q0 -> q1, certified
    SlicedMotion motion{q0, q1, flip, ignored};
    if (far) ++stats.advancement_steps;
    else ++stats.chord_tests;
    std::vector<std::pair<std::size_t, SlicedMotionCrossing>> crossings;
    for (std::size_t i = 0; !far && i < pairs.size(); ++i) {
      SlicedMotionCrossing c = pairs[i].space.first_crossing(motion, CrossingOptions{options.crossing_bits});
      if (c.status == CrossingStatus::starts_in_contact)
        throw NumericError(where(t) + " starts a chord in contact with '" + model.parts[pairs[i].fixed].name +
                           "' (an internal error)");
      if (c.status == CrossingStatus::crossing) crossings.emplace_back(i, std::move(c));
    }
    if (!crossings.empty()) {
      std::vector<std::pair<std::size_t, SlicedFeaturePair>> touching;
      const SlicedMotionCrossing& c = earliest(crossings, touching);
      double s_contact = to_d(c.u_lower) * end;
      Kinematic at = s_contact > 0 ? held_step(k0, s_contact) : k0;
      Rows rows = contact_rows(t + s_contact, at, c.before, touching);
      Eigen::VectorXd normal_speed = rows.J * Eigen::Vector3d(at.vx, at.vy, at.omega);
      double approach = 0;
      for (std::size_t r = 0; r < rows.pair.size(); ++r) {
        bool is_held = false;
        for (const Held& hc : held)
          is_held = is_held || (hc.feature.fixed == rows.feature[r].fixed && hc.feature.free == rows.feature[r].free);
        if (!is_held) approach = std::min(approach, normal_speed(static_cast<Eigen::Index>(r)));
      }
      if (approach >= 0 && attempt < 40) {   // a contact the path leaves (the chord cut its corner)
        h = std::max(end / 4, 1e-300);
        continue;
      }
      t += s_contact;
      set_state(at, c.before);
      impact(t, rows);
      return true;
    }
    t += end;
    k = kend;
    q = q1;
    // contacts reaching the end of their segment end; lift-offs and stick/slip changes are
    // decided by the next step's problem
    end_held_at_edges(held, bits, [&](const Held& c) {
      events.push_back(held_event(SimulationEvent::Kind::edge_end, c, held_frame(c, k), 0, 0));
    });
    return true;
  }
  throw NumericError(where(t) + ": no step in sustained contact could be certified");
}

PlanarSimulation::PlanarSimulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PlanarSimulation::PlanarSimulation(PlanarSimulation&&) noexcept = default;
PlanarSimulation& PlanarSimulation::operator=(PlanarSimulation&&) noexcept = default;
PlanarSimulation::~PlanarSimulation() = default;

namespace {

// A planar part's dynamics data, checked (at the part's pointer; a linear spring at its own).
const Dynamics& checked_planar_dynamics(const Part& part) {
  if (!part.dynamics || !part.dynamics->mass || !(*part.dynamics->mass > 0))
    throw ModelError(part.pointer, "planar part '" + part.name + "' needs a positive dynamics mass");
  const Dynamics& dyn = *part.dynamics;
  if (!dyn.moment_of_inertia || !(*dyn.moment_of_inertia > 0))
    throw ModelError(part.pointer, "planar part '" + part.name +
                                       "' needs a positive dynamics moment_of_inertia (about its pivot, its centre of mass)");
  if (dyn.linear_spring)
    throw ModelError(part.pointer + "/dynamics/linear_spring",
                     "a planar part has no single direction for a linear spring: give a spring between points in "
                     "\"simulation\"/\"springs\"");
  return dyn;
}

// A planar part's reach from its pivot: the farthest boundary point (an arc: its centre's
// distance + radius) in double (with 1e-12 to spare), and a certified rational upper bound (the
// far test's sweep bound: exact squared distances, rational square roots rounded up).
struct PlanarReach {
  double reach = 0;
  Rational bound;
};
PlanarReach planar_reach(const Part& part) {
  PlanarReach r;
  const Point& pivot = part.motion.pivot;
  const double px = to_d(pivot.x), py = to_d(pivot.y);
  Rational vertex_sq(0);
  for (const Loop& loop : part.loops)
    for (const Edge& e : loop.edges) {
      r.reach = std::max(r.reach, std::hypot(to_d(e.source.x) - px, to_d(e.source.y) - py));
      Rational dx = e.source.x - pivot.x, dy = e.source.y - pivot.y;
      Rational sq = dx * dx + dy * dy;
      if (sq > vertex_sq) vertex_sq = sq;
      if (e.is_arc()) {
        r.reach = std::max(r.reach, std::hypot(to_d(e.center.x) - px, to_d(e.center.y) - py) +
                                        std::sqrt(to_d(e.radius_squared)));
        Rational cx = e.center.x - pivot.x, cy = e.center.y - pivot.y;
        Rational arc = simulation::sqrt_upper(cx * cx + cy * cy) + simulation::sqrt_upper(e.radius_squared);
        if (arc > r.bound) r.bound = arc;
      }
    }
  r.reach *= 1 + 1e-12;
  Rational vertex = simulation::sqrt_upper(vertex_sq);
  if (vertex > r.bound) r.bound = vertex;
  return r;
}

// A planar part's initial state: its initial configuration and its velocity, three entries
// vx, vy, omega (SimulationSpec::Velocity), in internal units (ts: seconds per time unit).
Kinematic initial_kinematic(const Model& model, std::size_t part, const SimulationSpec& spec, double ts) {
  const Part& p = model.parts[part];
  Kinematic k{to_d(p.initial.x), to_d(p.initial.y), to_d(p.initial.angle), 0, 0, 0};
  std::vector<double> rates;
  for (const auto& v : spec.velocities)
    if (v.part == part) rates.push_back(to_d(v.value) / ts);
  if (rates.size() == 3) {
    k.vx = rates[0];
    k.vy = rates[1];
    k.omega = rates[2];
  }
  return k;
}

}  // namespace

PlanarSimulation PlanarSimulation::create(const Model& model, const SimulationOptions& options) {
  check_simulator_range(model);
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  SimulationSpec spec = simulation::start_simulation(s, model, options);
  const double fs = s.force_scale, ts = s.time_scale;
  std::optional<std::size_t> planar;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    if (part.motion.kind == Motion::Kind::fixed) continue;
    if (part.motion.kind != Motion::Kind::planar)
      throw ModelError(part.motion.pointer, "part '" + part.name +
                                                "': the planar simulator moves one planar part among fixed parts");
    if (planar)
      throw ModelError(part.motion.pointer, "part '" + part.name +
                                                "': the planar simulator moves one planar part only ('" +
                                                model.parts[*planar].name +
                                                "' is the other; several planar parts: the C++ API's "
                                                "PlanarSystemSimulation, docs/simulation.md)");
    planar = p;
  }
  if (!planar) throw ModelError("", "the model has no planar part to simulate");
  s.part = *planar;
  const Part& part = model.parts[s.part];
  if (!spec.drivers.empty())
    throw ModelError(spec.drivers.front().pointer, "a driven planar part among fixed parts only would jam: drivers of "
                                                   "planar parts are PlanarSystemSimulation's (several planar parts)");
  const Dynamics& dyn = checked_planar_dynamics(part);
  simulation::set_planar_loads(s, dyn, fs, ts, s.g);
  {
    // the loads in exact rationals (the unit factors are exact: 1 or 1/1000 s, 1000 or 1 mN)
    const Rational ts_exact = spec.time_unit == "ms" ? Rational(1, 1000) : Rational(1);
    const Rational fs_exact = spec.force_unit == "mN" ? Rational(1) : Rational(1000);
    s.load_x = *dyn.mass * spec.gravity.x / (ts_exact * ts_exact);
    s.load_y = *dyn.mass * spec.gravity.y / (ts_exact * ts_exact);
    if (dyn.force) {
      s.load_x += dyn.force->x * fs_exact;
      s.load_y += dyn.force->y * fs_exact;
    }
    if (dyn.torque) s.load_torque = *dyn.torque * fs_exact;
  }
  // springs: a torsional spring to the frame about the pivot; linear springs and dampers from a
  // point of the part to a point of a fixed part (a spring between two fixed parts acts on nothing)
  for (const auto& coupling : spec.couplings) {
    if (coupling.first != s.part && coupling.second != s.part) continue;
    const bool first = coupling.first == s.part;
    const Point& body = first ? coupling.first_point : coupling.second_point;
    const Point& anchor = first ? coupling.second_point : coupling.first_point;
    Impl::LineSpring sp;
    sp.body[0] = to_d(body.x - part.motion.pivot.x);
    sp.body[1] = to_d(body.y - part.motion.pivot.y);
    sp.anchor[0] = to_d(anchor.x);
    sp.anchor[1] = to_d(anchor.y);
    sp.k = to_d(coupling.stiffness) * fs;
    sp.rest = to_d(coupling.rest_length);
    sp.c = to_d(coupling.damping) * fs * ts;
    s.springs.push_back(sp);
  }
  s.integrated = !s.springs.empty() || dyn.torsional_spring.has_value();
  {
    PlanarReach r = planar_reach(part);
    s.reach = r.reach;
    s.reach_bound = r.bound;
  }
  double accuracy = simulation::simulation_accuracy(options, spec);
  s.delta = options.chord_deviation > 0 ? options.chord_deviation : accuracy * std::max(s.reach, 1.0);
  s.accuracy = accuracy;
  // held contacts are kept 3/4 delta apart and chords deviate at most delta / 2 from the path
  // (chord_cap): a chord never touches a held contact
  s.hold_gap = 0.75 * s.delta;
  // a bounce that would rise less than delta under the loads is plastic
  {
    // the springs' scale of acceleration: their stiffness over the part's size and stretch
    double spring_accel = s.torsion_k * std::numbers::pi / s.inertia * s.reach;
    for (const Impl::LineSpring& sp : s.springs)
      spring_accel += sp.k * (s.reach + std::hypot(sp.anchor[0] - to_d(part.motion.pivot.x) - to_d(part.initial.x),
                                                   sp.anchor[1] - to_d(part.motion.pivot.y) - to_d(part.initial.y)) +
                              sp.rest) *
                      (1 / s.mass + s.reach * s.reach / s.inertia);
    s.rest_speed = std::sqrt(
        2 * (std::hypot(s.accel[0], s.accel[1]) + std::abs(s.alpha) * s.reach + spring_accel) * s.delta);
  }
  for (std::size_t i = 0; i < model.pairs.size(); ++i) {
    const PairSpec& pair = model.pairs[i];
    std::size_t other = pair.first == s.part ? pair.second : pair.second == s.part ? pair.first : no_index;
    if (other == no_index) continue;   // two fixed parts
    Impl::Pair p{i, other, pair.restitution ? to_d(*pair.restitution) : 0.0,
                 SlicedSpace::build(model, model.parts[other].name, part.name, SlicedBuildOptions{false, {}}),
                 0.0, 0.0, Rational(0)};
    if (pair.friction) {
      p.mu_static = to_d(*pair.friction);
      p.mu_static_exact = *pair.friction;
      p.mu_kinetic = pair.kinetic_friction ? to_d(*pair.kinetic_friction) : p.mu_static;
    }
    s.pairs.push_back(std::move(p));
  }
  s.k = initial_kinematic(model, s.part, spec, ts);
  s.q = configuration_of(s.k.x, s.k.y, s.k.theta);
  for (const Impl::Pair& p : s.pairs) {
    SlicedLocation where = p.space.locate(s.q);
    if (where.kind != SlicedLocation::Kind::free)
      throw ModelError(part.pointer + "/initial", "planar part '" + part.name + "' starts " +
                                                      (where.kind == SlicedLocation::Kind::blocked ? "overlapping"
                                                                                                   : "touching") +
                                                      " fixed part '" + model.parts[p.fixed].name +
                                                      "': it must start apart");
  }
  s.publish();
  PlanarSimulation simulated(std::move(impl));
  // (session 72, jam72) an initial state beyond the doubles: bad input at its datum, nothing run
  simulation::refuse_initial_energy(model, simulated.energy());
  return simulated;
}

void PlanarSimulation::step(double t_limit) {
  Impl& s = *impl_;
  double limit = 0;
  const double span = next_span(s, t_limit, limit);
  if (!(span > 0)) return;
  // forces balanced and constant: a resting part stays
  bool event = false;
  naming_the_data(s.model, [&] {
    event = !s.resting && (s.held.empty() && !s.integrated ? s.advance(span) : s.held_advance(span));
    if (!event) s.t = span == limit - s.t ? limit : s.t + span;
    if (!std::isfinite(energy())) {   // (session 65, sim65) a stop, not "energy null" and exit 0
      std::ostringstream parts;
      const Part& p = s.model.parts[s.part];
      parts << "part '" << p.name << "' (" << p.pointer << "/dynamics, " << p.pointer << "/initial; at (" << s.k.x << ", "
            << s.k.y << ") mm, moving at " << std::hypot(s.k.vx, s.k.vy) * s.time_scale << " mm/" << s.time_unit << " and "
            << s.k.omega * s.time_scale << " rad/" << s.time_unit << ")";
      throw NumericError(simulation::energy_overflow_message(s.where(s.t), parts.str()));
    }
  });
  s.publish();
}

void PlanarSimulation::run_until(double t_end, const std::function<void(double)>& progress) {
  run_steps(*impl_, t_end, progress, [&] { step(t_end); });
}

const PlanarState& PlanarSimulation::state() const { return impl_->public_state; }
const std::vector<SimulationEvent>& PlanarSimulation::events() const { return impl_->events; }
std::size_t PlanarSimulation::steps() const { return impl_->steps; }
const PlanarStatistics& PlanarSimulation::statistics() const { return impl_->stats; }
double PlanarSimulation::chord_deviation() const { return impl_->delta; }
std::size_t PlanarSimulation::part() const { return impl_->part; }
const Model& PlanarSimulation::model() const { return impl_->model; }
const std::string& PlanarSimulation::time_unit() const { return impl_->time_unit; }
const std::string& PlanarSimulation::force_unit() const { return impl_->force_unit; }

double PlanarSimulation::energy() const {
  const Impl& s = *impl_;
  double kinetic = 0.5 * s.mass * (s.k.vx * s.k.vx + s.k.vy * s.k.vy) + 0.5 * s.inertia * s.k.omega * s.k.omega;
  double potential = -(s.mass * s.g[0] + s.force[0]) * s.k.x - (s.mass * s.g[1] + s.force[1]) * s.k.y -
                     s.torque * s.k.theta + s.spring_potential(s.k);
  return (kinetic + potential) / s.force_scale;
}

}  // namespace hipair

// ====================================================================== several planar parts
// docs/simulation.md, "Several planar parts". Each pair's contacts are found in its own 3-DOF
// C-space: a planar part B against a fixed part, or against another planar part A in A's frame
// (the pair's SlicedSpace is built with A as the fixed part at its zero configuration, and B's
// configuration relative to A is computed exactly from both world configurations).

namespace hipair {
namespace {

using simulation_detail::relative_configuration;

}  // namespace

struct PlanarSystemSimulation::Impl {
  Model model;
  SimulationOptions options;
  double time_scale = 1, force_scale = 1000;
  std::string time_unit = "s", force_unit = "N";
  struct Body {
    std::size_t part = 0;
    double mass = 0, inertia = 0, damping_rate = 0, accel[2] = {0, 0}, alpha = 0, torque = 0, force[2] = {0, 0};
    double pivot[2] = {0, 0};
    double torsion_k = 0, torsion_rest = 0;
    double reach = 0;
    Rational reach_bound;
    bool driven = false;   // moves at its driver's velocity (infinite inertia in impacts)
    // a driver's speed profile (law "speed_profile"): points (t, vx, vy, omega), internal units;
    // the velocity linear between them, constant after the last; empty: a constant velocity
    std::vector<std::array<double, 4>> profile;
    double drive_accel[3] = {0, 0, 0};   // the current profile segment's slope (set per step)
    // a constant-velocity driver's exact (vx, vy, omega), per the model's time unit (the jam
    // test's driver shares, session 70: the doubles over the time scale are its velocity)
    std::array<Rational, 3> speed{Rational(0), Rational(0), Rational(0)};
  };
  std::vector<Body> bodies;
  std::vector<std::size_t> body_of;   // model part -> body index (no_index: fixed)
  struct Spring {
    std::size_t body[2] = {no_index, no_index};   // no_index: a fixed part
    double point[2][2] = {{0, 0}, {0, 0}};        // relative to the body's pivot, or world (fixed)
    double k = 0, rest = 0, c = 0;
  };
  std::vector<Spring> springs;
  struct Pair {
    std::size_t index = 0;                    // into Model::pairs
    std::size_t first = 0, second = 0;        // model parts: first fixed (or held fixed), second planar
    std::size_t body_a = no_index, body_b = 0;   // bodies (body_a no_index: a fixed part)
    double restitution = 0;
    double mu_static = 0, mu_kinetic = 0;     // Coulomb friction (0: frictionless)
    std::shared_ptr<Model> frame_model;       // the model with `first` fixed (planar-planar pairs)
    SlicedSpace space;
  };
  std::vector<Pair> pairs;
  double g[2] = {0, 0};
  double delta = 0, accuracy = 1e-9, rest_speed = 0, step_guess = 0;
  double t = 0;
  std::vector<Kinematic> k;
  std::vector<SlicedConfiguration> q;   // world, exact, per body
  std::vector<SimulationEvent> events;
  std::size_t steps = 0;
  PlanarStatistics stats;
  PlanarSystemState public_state;

  using StateN = std::vector<double>;
  StateN pack(const std::vector<Kinematic>& ks) const {
    StateN y;
    for (const Kinematic& b : ks) {
      State6 a = to_array(b);
      y.insert(y.end(), a.begin(), a.end());
    }
    return y;
  }
  std::vector<Kinematic> unpack(const StateN& y) const {
    std::vector<Kinematic> ks;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      ks.push_back(Kinematic{y[6 * i], y[6 * i + 1], y[6 * i + 2], y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]});
    return ks;
  }
  // world point and velocity of a spring end
  void spring_end(const Spring& sp, int e, const std::vector<Kinematic>& ks, double p[2], double v[2], double r[2]) const {
    if (sp.body[e] == no_index) {
      p[0] = sp.point[e][0];
      p[1] = sp.point[e][1];
      v[0] = v[1] = r[0] = r[1] = 0;
      return;
    }
    const Body& b = bodies[sp.body[e]];
    const Kinematic& s = ks[sp.body[e]];
    double c = std::cos(s.theta), sn = std::sin(s.theta);
    r[0] = c * sp.point[e][0] - sn * sp.point[e][1];
    r[1] = sn * sp.point[e][0] + c * sp.point[e][1];
    p[0] = b.pivot[0] + s.x + r[0];
    p[1] = b.pivot[1] + s.y + r[1];
    v[0] = s.vx - s.omega * r[1];
    v[1] = s.vy + s.omega * r[0];
  }
  // accelerations of every body (3 per body)
  std::vector<double> accelerations(const std::vector<Kinematic>& ks) const {
    std::vector<double> a(3 * bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Body& b = bodies[i];
      if (b.driven) continue;
      a[3 * i] = b.mass * (b.accel[0] - b.damping_rate * ks[i].vx);
      a[3 * i + 1] = b.mass * (b.accel[1] - b.damping_rate * ks[i].vy);
      a[3 * i + 2] = b.torque - b.torsion_k * (ks[i].theta - b.torsion_rest);
    }
    for (const Spring& sp : springs) {
      double p0[2], v0[2], r0[2], p1[2], v1[2], r1[2];
      spring_end(sp, 0, ks, p0, v0, r0);
      spring_end(sp, 1, ks, p1, v1, r1);
      const double d[2] = {p0[0] - p1[0], p0[1] - p1[1]}, dv[2] = {v0[0] - v1[0], v0[1] - v1[1]};
      const auto [fx, fy] = spring_force(sp.k, sp.rest, sp.c, d, dv);   // on end 0
      const double* rr[2] = {r0, r1};
      for (int e = 0; e < 2; ++e) {
        if (sp.body[e] == no_index || bodies[sp.body[e]].driven) continue;
        double sx = e == 0 ? fx : -fx, sy = e == 0 ? fy : -fy;
        a[3 * sp.body[e]] += sx;
        a[3 * sp.body[e] + 1] += sy;
        a[3 * sp.body[e] + 2] += rr[e][0] * sy - rr[e][1] * sx;
      }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].driven) {   // its law's acceleration (0 at a constant velocity)
        for (int j = 0; j < 3; ++j) a[3 * i + j] = bodies[i].drive_accel[j];
        continue;
      }
      a[3 * i] /= bodies[i].mass;
      a[3 * i + 1] /= bodies[i].mass;
      a[3 * i + 2] /= bodies[i].inertia;
    }
    return a;
  }
  void rhs(const StateN& y, StateN& dy) const {
    std::vector<Kinematic> ks = unpack(y);
    std::vector<double> a = accelerations(ks);
    dy.resize(y.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      dy[6 * i] = ks[i].vx;
      dy[6 * i + 1] = ks[i].vy;
      dy[6 * i + 2] = ks[i].omega;
      dy[6 * i + 3] = a[3 * i];
      dy[6 * i + 4] = a[3 * i + 1];
      dy[6 * i + 5] = a[3 * i + 2];
    }
  }
  std::vector<Kinematic> fixed_step(const std::vector<Kinematic>& from, double span) const {
    boost::numeric::odeint::runge_kutta_dopri5<StateN> stepper;
    StateN y = pack(from);
    stepper.do_step([this](const StateN& x, StateN& dx, double) { held_rhs(x, dx); }, y, 0.0, span);
    std::vector<Kinematic> out = unpack(y);
    project(out, true);
    return out;
  }
  const Point& pivot_of(std::size_t part) const { return model.parts[part].motion.pivot; }
  // the pair's configuration (second part relative to the first) from world configurations
  SlicedConfiguration relative(const Pair& p, const std::vector<SlicedConfiguration>& qs) const {
    if (p.body_a == no_index) return qs[p.body_b];
    return relative_configuration(pivot_of(p.first), qs[p.body_a], pivot_of(p.second), qs[p.body_b]);
  }
  double relative_angle(const Pair& p, const std::vector<Kinematic>& ks) const {
    return ks[p.body_b].theta - (p.body_a == no_index ? 0.0 : ks[p.body_a].theta);
  }
  std::string where(double time) const {
    std::ostringstream out;
    out << "simulation: at t = " << time / time_scale << " " << time_unit;
    return out.str();
  }
  // The longest chord (s) of a pair's relative motion within delta/2 of its path, from the
  // bounds at both ends (double accelerations, as the single-part simulator's chord_cap).
  double chord_cap(const Pair& p, const std::vector<Kinematic>& k0, const std::vector<Kinematic>& k1) const {
    const double pi = std::numbers::pi;
    double bend_s = 0, wrel = 0, arel = 0;
    for (const std::vector<Kinematic>* ks : {&k0, &k1}) {
      std::vector<double> a = motion_accelerations(*ks);
      const Kinematic& B = (*ks)[p.body_b];
      const Body& bb = bodies[p.body_b];
      double ab[3] = {a[3 * p.body_b], a[3 * p.body_b + 1], a[3 * p.body_b + 2]};
      double aa[3] = {0, 0, 0}, va[2] = {0, 0}, wa = 0, d = 0;
      if (p.body_a != no_index) {
        const Kinematic& A = (*ks)[p.body_a];
        const Body& ba = bodies[p.body_a];
        for (int i = 0; i < 3; ++i) aa[i] = a[3 * p.body_a + i];
        va[0] = A.vx;
        va[1] = A.vy;
        wa = A.omega;
        d = std::hypot(bb.pivot[0] + B.x - ba.pivot[0] - A.x, bb.pivot[1] + B.y - ba.pivot[1] - A.y);
      }
      double s2 = std::hypot(ab[0] - aa[0], ab[1] - aa[1]) + 2 * std::abs(wa) * std::hypot(B.vx - va[0], B.vy - va[1]) +
                  (std::abs(aa[2]) + wa * wa) * d;
      bend_s = std::max(bend_s, s2);
      wrel = std::max(wrel, std::abs(B.omega - wa));
      arel = std::max(arel, std::abs(ab[2] - aa[2]));
    }
    double phi = std::abs(wrap(relative_angle(p, k0)));
    if (phi > pi / 2) phi = pi - phi;
    double w_bound = std::tan((phi + pi / 4) / 2);
    double wpp = 0.5 * (1 + w_bound * w_bound) * (arel + w_bound * wrel * wrel);
    double bend = bend_s + 2 * bodies[p.body_b].reach * wpp;
    double cap = wrel > 0 ? (pi / 4) / wrel : std::numeric_limits<double>::infinity();
    if (bend > 0) cap = std::min(cap, std::sqrt(8 * 0.5 * delta / bend));
    return cap;
  }
  // A bound (double) of how far any point of the pair's second part moves relative to the
  // first over a step of length `end` (speeds at the ends plus acceleration x step).
  double travel(const Pair& p, const std::vector<Kinematic>& k0, const std::vector<Kinematic>& k1, double end) const {
    double out = 0;
    for (const std::vector<Kinematic>* ks : {&k0, &k1}) {
      std::vector<double> a = motion_accelerations(*ks);
      auto part_travel = [&](std::size_t body, double reach) {
        const Kinematic& s = (*ks)[body];
        double speed = std::hypot(s.vx, s.vy) + std::abs(s.omega) * reach;
        double gain = std::hypot(a[3 * body], a[3 * body + 1]) + std::abs(a[3 * body + 2]) * reach + s.omega * s.omega * reach;
        return (speed + gain * end) * end;
      };
      double tb = part_travel(p.body_b, bodies[p.body_b].reach);
      if (p.body_a != no_index) {
        const Kinematic &A = (*ks)[p.body_a], &B = (*ks)[p.body_b];
        double d = std::hypot(bodies[p.body_b].pivot[0] + B.x - bodies[p.body_a].pivot[0] - A.x,
                              bodies[p.body_b].pivot[1] + B.y - bodies[p.body_a].pivot[1] - A.y);
        tb += part_travel(p.body_a, d + bodies[p.body_b].reach);
      }
      out = std::max(out, tb);
    }
    return out;
  }
  void publish() {
    public_state.time = t / time_scale;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      PlanarState& s = public_state.states[i];
      s.time = public_state.time;
      s.x = k[i].x;
      s.y = k[i].y;
      s.angle = k[i].theta;
      s.vx = k[i].vx * time_scale;
      s.vy = k[i].vy * time_scale;
      s.omega = k[i].omega * time_scale;
      s.configuration = q[i];
      s.resting = resting;
    }
  }
  // ---- sustained contact between moving parts (docs/simulation.md, "Several planar parts")
  struct Held {
    std::size_t pair = 0;                   // into pairs
    SlicedFeaturePair feature;
    int state = simulation::frictionless;   // stick, slip +-1 (friction), frictionless
  };
  std::vector<Held> held;
  // the pairs (into pairs) of the held contacts, and some pairs' friction data for a message
  std::vector<std::size_t> held_pairs() const { return pairs_of_held(*this); }
  std::string named_pairs(const std::vector<std::size_t>& of) const { return friction_of_pairs(*this, of); }
  double hold_gap = 0;     // the gap (mm) held contacts are projected to (3/4 delta)
  bool resting = false;    // every part at rest on its held contacts (constant loads): stays
  // The kernels' contact function of a vertex–segment feature pair at double states, in the
  // world: the contact point (the vertex), the unit normal (first part into the second), the
  // unit gap, the foot parameter along the segment and whether the second part owns the vertex.
  struct WorldGap {
    bool defined = false, free_vertex = false;
    double point[2] = {0, 0}, normal[2] = {0, 0}, gap = 0, along = 0;
  };
  WorldGap world_gap(const Pair& p, const SlicedFeaturePair& f, const std::vector<Kinematic>& ks) const;
  // A held contact's rows over all coordinates (3 per body): J (g' = J qdot), T (the sliding
  // velocity), the curvature terms h, h_t (g'' = J qdd + h, (T qdot)' = T qdd + h_t), the gap and
  // the foot parameter.
  struct HeldFrame {
    Eigen::VectorXd J, T;
    double h = 0, h_t = 0, gap = 0, along = 0;
    std::array<double, 4> frame{};   // point, unit normal (world)
  };
  HeldFrame held_frame(const Held& c, const std::vector<Kinematic>& ks) const;
  struct HeldProblem {
    std::vector<HeldFrame> frames;
    std::vector<simulation::Friction> friction;
    Eigen::MatrixXd G;
    Eigen::VectorXd h, a0;
    simulation::FrictionalSolution solution;
  };
  HeldProblem held_problem(const std::vector<Kinematic>& ks, bool unilateral) const;
  Eigen::VectorXd inverse_mass() const {
    Eigen::VectorXd minv(static_cast<Eigen::Index>(3 * bodies.size()));
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const double free = bodies[i].driven ? 0.0 : 1.0;   // a driver: infinite inertia
      minv.segment(static_cast<Eigen::Index>(3 * i), 3) << free / bodies[i].mass, free / bodies[i].mass,
          free / bodies[i].inertia;
    }
    return minv;
  }
  Eigen::VectorXd velocity(const std::vector<Kinematic>& ks) const {
    Eigen::VectorXd v(static_cast<Eigen::Index>(3 * bodies.size()));
    for (std::size_t i = 0; i < bodies.size(); ++i)
      v.segment(static_cast<Eigen::Index>(3 * i), 3) << ks[i].vx, ks[i].vy, ks[i].omega;
    return v;
  }
  void set_velocity(std::vector<Kinematic>& ks, const Eigen::VectorXd& v) const {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      ks[i].vx = v(static_cast<Eigen::Index>(3 * i));
      ks[i].vy = v(static_cast<Eigen::Index>(3 * i + 1));
      ks[i].omega = v(static_cast<Eigen::Index>(3 * i + 2));
    }
  }
  // The accelerations of the motion: free, or with the held contacts' forces (their states fixed)
  std::vector<double> motion_accelerations(const std::vector<Kinematic>& ks) const {
    if (held.empty()) return accelerations(ks);
    const Eigen::VectorXd& x = held_problem(ks, false).solution.x;
    return std::vector<double>(x.data(), x.data() + x.size());
  }
  void held_rhs(const StateN& y, StateN& dy) const;
  void project(std::vector<Kinematic>& ks, bool positions) const;
  unsigned violated(const std::vector<Kinematic>& ks, std::vector<unsigned>* per_contact = nullptr) const;
  bool is_held(std::size_t pair, const SlicedFeaturePair& f) const {
    for (const Held& c : held)
      if (c.pair == pair && c.feature.fixed == f.fixed && c.feature.free == f.free) return true;
    return false;
  }
  SimulationEvent held_event(SimulationEvent::Kind kind, const Held& c, const HeldFrame& f, double normal_force,
                             double friction_force) const;
  bool decide();
  // The impact rows of touching feature pairs at the state (k, q): rows over all coordinates.
  struct Rows {
    std::vector<Eigen::VectorXd> J, T;
    std::vector<std::array<double, 4>> frames;
    std::vector<std::size_t> pair;
    std::vector<SlicedFeaturePair> feature;
    std::vector<simulation::ExactRow> exact;   // J's rows at q in exact rationals (the held decision)
  };
  Rows contact_rows(const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const;
  void impact(double time, const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching);
  // (session 69, jam69) Contact rows (an impact's, or the held contacts') that no velocity of
  // the free bodies keeps: is it a jam of the constant-speed drivers? Decided exactly on the
  // rows' exact normals (simulation/jam.hpp, as the pin-slot simulator's refuse_jam): some y >= 0
  // with sum y_i a_i = 0 on the free bodies' coordinates and sum y_i (a_i . v_driven) < 0 (the
  // driven bodies' velocities: a constant-velocity driver's exact speeds from the model, since
  // session 70 — the doubles before; a speed profile's velocity doubles, the verdict then
  // labelled approximate). Throws the jam's SimulationJam naming the
  // drivers, the jammed parts and the contacts of that combination, the state published at the
  // jam; returns where there is none.
  void refuse_jam(double time, const Rows& rows);
  // (session 75, jam75; Issue 11, review74 H1) A frictionless impact whose exact solution gives
  // the free parts more kinetic energy than the drivers' work through the contacts
  // (simulation/impact_energy.hpp, decided exactly on the exact solution of the impact's held set,
  // the rows with a positive `published` multiplier): refused before its velocities are set or
  // published — a NumericError naming the time, the pairs, the restitutions and the energies.
  // Nothing where that balance cannot be formed exactly (dependent held rows).
  void refuse_energy_gain(double time, const Rows& rows, const Eigen::MatrixXd& J, const Eigen::VectorXd& minv,
                          const Eigen::VectorXd& v, const Eigen::VectorXd& restitution,
                          const std::vector<Rational>& h_exact, const Eigen::VectorXd& published) const {
    const std::optional<simulation::ImpactEnergy> energy = simulation::impact_energy(J, minv, v, h_exact, published);
    if (!energy || sgn(energy->excess()) <= 0) return;
    std::ostringstream out;
    out.precision(12);
    out << where(time) << ": the impact at";
    std::vector<std::size_t> named;
    for (std::size_t r = 0; r < rows.pair.size(); ++r) {
      if (std::find(named.begin(), named.end(), rows.pair[r]) != named.end()) continue;
      named.push_back(rows.pair[r]);
      const Pair& p = pairs[rows.pair[r]];
      out << (named.size() > 1 ? ", " : " ") << "'" << model.parts[p.first].name << "' / '"
          << model.parts[p.second].name << "' (restitution " << restitution(static_cast<Eigen::Index>(r)) << ")";
    }
    const double unit = force_scale;   // (energies in the model's force x length units, as energy())
    out << " would create kinetic energy: " << to_double(energy->excess()) / unit
        << " beyond the drivers' work (kinetic " << to_double(energy->kinetic_before) / unit << " before, "
        << to_double(energy->kinetic_after) / unit << " after, the drivers' work "
        << to_double(energy->driver_work) / unit
        << "; decided exactly on the impact's exact solution) — Newton's restitution at simultaneous contacts of "
           "different restitutions can do that where a contact separating before the impact is given an impulse; "
           "refused (docs/simulation.md, Session 75)";
    throw NumericError(out.str());
  }
  bool advance(double span);
};

PlanarSystemSimulation::Impl::WorldGap PlanarSystemSimulation::Impl::world_gap(
    const Pair& p, const SlicedFeaturePair& f, const std::vector<Kinematic>& ks) const {
  // the second part's pose relative to the first (held at its zero configuration), as
  // relative_configuration: s = pa - pb + R(-theta_a)(pb - pa + t_b - t_a)
  Kinematic rel = ks[p.body_b];
  double c = 1, sn = 0;
  const Body& bb = bodies[p.body_b];
  if (p.body_a != no_index) {
    const Body& ba = bodies[p.body_a];
    const Kinematic &A = ks[p.body_a], &B = ks[p.body_b];
    c = std::cos(A.theta);
    sn = std::sin(A.theta);
    const double dx = bb.pivot[0] + B.x - ba.pivot[0] - A.x, dy = bb.pivot[1] + B.y - ba.pivot[1] - A.y;
    rel.x = ba.pivot[0] - bb.pivot[0] + c * dx + sn * dy;
    rel.y = ba.pivot[1] - bb.pivot[1] - sn * dx + c * dy;
    rel.theta = B.theta - A.theta;
  }
  ContactGap<double> g = contact_gap(p.frame_model ? *p.frame_model : model, f, pose_of(pivot_of(p.second), rel));
  WorldGap w;
  const double n = std::hypot(g.normal.x, g.normal.y);
  if (!g.defined || !(n > 0)) return w;
  w.defined = true;
  w.free_vertex = g.free_vertex;
  w.gap = g.gap / n;
  w.along = g.along;
  double px = g.point.x, py = g.point.y, nx = g.normal.x / n, ny = g.normal.y / n;
  if (p.body_a != no_index) {   // the first part's frame to the world
    const Body& ba = bodies[p.body_a];
    const Kinematic& A = ks[p.body_a];
    const double rx = px - ba.pivot[0], ry = py - ba.pivot[1];
    px = ba.pivot[0] + A.x + c * rx - sn * ry;
    py = ba.pivot[1] + A.y + sn * rx + c * ry;
    const double mx = c * nx - sn * ny, my = sn * nx + c * ny;
    nx = mx;
    ny = my;
  }
  w.point[0] = px;
  w.point[1] = py;
  w.normal[0] = nx;
  w.normal[1] = ny;
  return w;
}

PlanarSystemSimulation::Impl::HeldFrame PlanarSystemSimulation::Impl::held_frame(
    const Held& c, const std::vector<Kinematic>& ks) const {
  const Pair& p = pairs[c.pair];
  const WorldGap g = world_gap(p, c.feature, ks);
  const auto n3 = static_cast<Eigen::Index>(3 * bodies.size());
  HeldFrame f;
  f.J = Eigen::VectorXd::Zero(n3);
  f.T = Eigen::VectorXd::Zero(n3);
  f.gap = g.gap;
  f.along = g.along;
  const double px = g.point[0], py = g.point[1], nx = g.normal[0], ny = g.normal[1];
  f.frame = {px, py, nx, ny};
  // per part of the pair: its centre's velocity, rate and the contact point's velocity
  struct Side {
    double v[2] = {0, 0}, w = 0, r[2] = {0, 0}, vp[2] = {0, 0};
  } side[2];   // 0: the first part (fixed or A), 1: the second (B)
  const std::size_t body_of_side[2] = {p.body_a, p.body_b};
  for (int e = 0; e < 2; ++e) {
    const std::size_t body = body_of_side[e];
    if (body == no_index) continue;
    const Kinematic& s = ks[body];
    Side& sd = side[e];
    sd.v[0] = s.vx;
    sd.v[1] = s.vy;
    sd.w = s.omega;
    sd.r[0] = px - (bodies[body].pivot[0] + s.x);
    sd.r[1] = py - (bodies[body].pivot[1] + s.y);
    sd.vp[0] = s.vx - s.omega * sd.r[1];
    sd.vp[1] = s.vy + s.omega * sd.r[0];
    const double sign = e == 1 ? 1.0 : -1.0;
    const auto at = static_cast<Eigen::Index>(3 * body);
    f.J(at) = sign * nx;
    f.J(at + 1) = sign * ny;
    f.J(at + 2) = sign * (sd.r[0] * ny - sd.r[1] * nx);
    f.T(at) = sign * -ny;
    f.T(at + 1) = sign * nx;
    f.T(at + 2) = sign * (sd.r[0] * nx + sd.r[1] * ny);
  }
  // curvature terms. V owns the vertex (the contact point is its material point), S the
  // segment; n_S is the segment's normal towards V and t_S = k x n_S. Then (g' = J qdot)
  //   g''       = J qdd - w_V^2 n_S.r_V + w_S t_S.(vp_V - v_S) + w_S t_S.(vp_V - vp_S)
  //   (T qdot)' = T qdd - w_V^2 t_S.r_V - w_S n_S.(vp_V - v_S) - w_S n_S.(vp_V - vp_S)
  // (the single-part formulas with a fixed S or a fixed V; J and T are the same for both roles)
  const Side& V = g.free_vertex ? side[1] : side[0];
  const Side& S = g.free_vertex ? side[0] : side[1];
  const double sgn_n = g.free_vertex ? 1.0 : -1.0;
  const double ns[2] = {sgn_n * nx, sgn_n * ny}, ts[2] = {-ns[1], ns[0]};
  auto dot = [](const double a[2], double x, double y) { return a[0] * x + a[1] * y; };
  const double dv_s[2] = {V.vp[0] - S.v[0], V.vp[1] - S.v[1]}, dv_p[2] = {V.vp[0] - S.vp[0], V.vp[1] - S.vp[1]};
  f.h = -V.w * V.w * dot(ns, V.r[0], V.r[1]) + S.w * dot(ts, dv_s[0], dv_s[1]) + S.w * dot(ts, dv_p[0], dv_p[1]);
  f.h_t = -V.w * V.w * dot(ts, V.r[0], V.r[1]) - S.w * dot(ns, dv_s[0], dv_s[1]) - S.w * dot(ns, dv_p[0], dv_p[1]);
  return f;
}

PlanarSystemSimulation::Impl::HeldProblem PlanarSystemSimulation::Impl::held_problem(const std::vector<Kinematic>& ks,
                                                                                     bool unilateral) const {
  HeldProblem p;
  const auto m = static_cast<Eigen::Index>(held.size());
  const auto n3 = static_cast<Eigen::Index>(3 * bodies.size());
  p.G.resize(m, n3);
  p.h.resize(m);
  std::vector<double> free = accelerations(ks);
  p.a0 = Eigen::Map<const Eigen::VectorXd>(free.data(), n3);
  const Eigen::VectorXd v = velocity(ks);
  std::vector<int> states;
  std::vector<std::size_t> pair_of;
  for (Eigen::Index r = 0; r < m; ++r) {
    const Held& c = held[static_cast<std::size_t>(r)];
    p.frames.push_back(held_frame(c, ks));
    const HeldFrame& f = p.frames.back();
    p.G.row(r) = f.J.transpose();
    p.h(r) = f.h;
    const Pair& pair = pairs[c.pair];
    p.friction.push_back(held_friction(f, pair.mu_static, pair.mu_kinetic, v, rest_speed, c.state));
    states.push_back(p.friction.back().on ? c.state : simulation::frictionless);
    pair_of.push_back(c.pair);
  }
  if (m == 0) {
    p.solution.solved = true;
    p.solution.x = p.a0;
    p.solution.lambda = p.solution.w = p.solution.f = Eigen::VectorXd(0);
    return p;
  }
  solve_held_forces(p, inverse_mass(), pair_of, unilateral, states);
  return p;
}

void PlanarSystemSimulation::Impl::held_rhs(const StateN& y, StateN& dy) const {
  if (held.empty()) {
    rhs(y, dy);
    return;
  }
  const std::vector<Kinematic> ks = unpack(y);
  const Eigen::VectorXd& a = held_problem(ks, false).solution.x;
  dy.resize(y.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    dy[6 * i] = ks[i].vx;
    dy[6 * i + 1] = ks[i].vy;
    dy[6 * i + 2] = ks[i].omega;
    for (int j = 0; j < 3; ++j)
      dy[6 * i + 3 + j] = bodies[i].driven ? bodies[i].drive_accel[j] : a(static_cast<Eigen::Index>(3 * i + j));
  }
}

void PlanarSystemSimulation::Impl::project(std::vector<Kinematic>& ks, bool positions) const {
  project_held(
      held.size(), inverse_mass(), hold_gap, positions, [&](std::size_t c) { return held_frame(held[c], ks); },
      [&](std::size_t c) { return pairs[held[c].pair].mu_static > 0 && held[c].state == simulation::stick; },
      [&](const Eigen::VectorXd& dq) {
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          ks[i].x += dq(static_cast<Eigen::Index>(3 * i));
          ks[i].y += dq(static_cast<Eigen::Index>(3 * i + 1));
          ks[i].theta += dq(static_cast<Eigen::Index>(3 * i + 2));
        }
      },
      [&] { return velocity(ks); }, [&](const Eigen::VectorXd& v) { set_velocity(ks, v); });
}

unsigned PlanarSystemSimulation::Impl::violated(const std::vector<Kinematic>& ks, std::vector<unsigned>* per_contact) const {
  return held_violations(held_problem(ks, false), held, pairs, velocity(ks), inverse_mass(), per_contact);
}

SimulationEvent PlanarSystemSimulation::Impl::held_event(SimulationEvent::Kind kind, const Held& c, const HeldFrame& f,
                                                         double normal_force, double friction_force) const {
  return held_contact_event(kind, t / time_scale, pairs[c.pair].index, model.parts[pairs[c.pair].first].name,
                            model.parts[pairs[c.pair].second].name, c.feature.label, f.frame, normal_force, friction_force,
                            force_scale);
}

bool PlanarSystemSimulation::Impl::decide() {
  if (held.empty()) return false;
  HeldProblem p = held_problem(k, true);
  if (!p.solution.solved) {
    // (session 69, jam69) a held set that the constant-speed drivers lock without a fresh contact
    std::vector<std::pair<std::size_t, SlicedFeaturePair>> touching;
    for (const Held& h : held) touching.emplace_back(h.pair, h.feature);
    refuse_jam(t, contact_rows(touching));
    throw NumericError(where(t) + ": " +
                       simulation::frictional_refusal("the contact problem of the held contacts", p.solution.exhausted) +
                       named_pairs(held_pairs()));
  }
  std::vector<std::size_t> pair_of;
  for (const Held& c : held) pair_of.push_back(c.pair);
  const std::vector<bool> lifts = lift_offs(p, inverse_mass(), pair_of);
  std::vector<Held> kept;
  std::vector<HeldFrame> frames;
  std::vector<Eigen::Index> rows;
  bool changed = false;
  for (std::size_t c = 0; c < held.size(); ++c) {
    const auto r = static_cast<Eigen::Index>(c);
    Held h = held[c];
    const double lambda = p.solution.lambda(r);
    if (lifts[c]) {   // no force and separating, exactly: lift-off
      events.push_back(held_event(SimulationEvent::Kind::lift_off, h, p.frames[c], 0, 0));
      continue;
    }
    const int state = p.friction[c].on ? p.solution.state[c] : simulation::frictionless;
    if (state != h.state && p.friction[c].on) {
      SimulationEvent e = held_event(state == simulation::stick ? SimulationEvent::Kind::stick : SimulationEvent::Kind::slip,
                                     h, p.frames[c], lambda, p.solution.f(r));
      if (state != simulation::stick) e.slip_direction = state;
      events.push_back(std::move(e));   // decided in floating point (exact_decision false)
      changed = true;
    }
    h.state = state;
    kept.push_back(h);
    frames.push_back(p.frames[c]);
    rows.push_back(r);
  }
  const bool lifted = kept.size() != held.size();
  held = std::move(kept);
  if (changed) project(k, false);   // a contact that starts to stick keeps no sliding velocity
  if (held.empty() || lifted) return true;
  // at rest: every part slower than the rest speed, no driver moving, the forces balance the loads
  double speed = 0, scale = 0, residual = 0;
  const Eigen::VectorXd& acc = p.solution.x;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Kinematic& s = k[i];
    const double v = std::hypot(s.vx, s.vy) + std::abs(s.omega) * bodies[i].reach;
    if (bodies[i].driven && (v > 0 || !bodies[i].profile.empty())) return changed;
    if (bodies[i].driven) continue;
    const auto j = static_cast<Eigen::Index>(3 * i);
    speed = std::max(speed, v);
    scale = std::max(scale, std::hypot(p.a0(j), p.a0(j + 1)) + std::abs(p.a0(j + 2)) * bodies[i].reach);
    residual = std::max(residual, std::hypot(acc(j), acc(j + 1)) + std::abs(acc(j + 2)) * bodies[i].reach);
  }
  if (speed > rest_speed || residual > 1e-9 * std::max(scale, 1e-300)) return changed;
  resting = true;
  for (Kinematic& s : k) s.vx = s.vy = s.omega = 0;
  // one `contact` event per pair: its total normal and friction forces, at its largest force
  std::vector<bool> done(pairs.size(), false);
  for (std::size_t c = 0; c < held.size(); ++c) {
    if (done[held[c].pair]) continue;
    done[held[c].pair] = true;
    double normal = 0, friction = 0;
    std::size_t top = c;
    for (std::size_t d = c; d < held.size(); ++d)
      if (held[d].pair == held[c].pair) {
        normal += p.solution.lambda(rows[d]);
        friction += p.solution.f(rows[d]);
        if (p.solution.lambda(rows[d]) > p.solution.lambda(rows[top])) top = d;
      }
    SimulationEvent e = held_event(SimulationEvent::Kind::contact, held[top], frames[top], normal, friction);
    for (std::size_t d = c; d < held.size(); ++d)
      if (held[d].pair == held[c].pair && d != top) e.features.push_back(held[d].feature.label);
    events.push_back(std::move(e));
  }
  return true;
}

PlanarSystemSimulation::Impl::Rows PlanarSystemSimulation::Impl::contact_rows(
    const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) const {
  const auto n = static_cast<Eigen::Index>(3 * bodies.size());
  Rows out;
  for (const auto& [i, f] : touching) {
    const Pair& p = pairs[i];
    SlicedConfiguration rel = relative(p, q);
    SlicedContactFrame frame = sliced_contact_frame(p.frame_model ? *p.frame_model : model, f, rel);
    if (!frame.defined) continue;
    double px = to_d(frame.point.x), py = to_d(frame.point.y), nx = to_d(frame.normal.x), ny = to_d(frame.normal.y);
    double nn = std::hypot(nx, ny);
    if (!(nn > 0)) continue;
    nx /= nn;
    ny /= nn;
    if (p.body_a != no_index) {   // from the first part's frame to the world
      const Body& ba = bodies[p.body_a];
      const Kinematic& A = k[p.body_a];
      double c = std::cos(A.theta), s = std::sin(A.theta);
      double rx = px - ba.pivot[0], ry = py - ba.pivot[1];
      px = ba.pivot[0] + A.x + c * rx - s * ry;
      py = ba.pivot[1] + A.y + s * rx + c * ry;
      double mx = c * nx - s * ny, my = s * nx + c * ny;
      nx = mx;
      ny = my;
    }
    Eigen::VectorXd row = Eigen::VectorXd::Zero(n), tan = Eigen::VectorXd::Zero(n);
    auto put = [&](std::size_t body, double sign) {
      const Body& b = bodies[body];
      double rx = px - (b.pivot[0] + k[body].x), ry = py - (b.pivot[1] + k[body].y);
      const auto at = static_cast<Eigen::Index>(3 * body);
      row(at) += sign * nx;
      row(at + 1) += sign * ny;
      row(at + 2) += sign * (rx * ny - ry * nx);
      tan(at) += sign * -ny;
      tan(at + 1) += sign * nx;
      tan(at + 2) += sign * (rx * nx + ry * ny);
    };
    put(p.body_b, 1);
    if (p.body_a != no_index) put(p.body_a, -1);
    bool repeated = false;
    for (const Eigen::VectorXd& r : out.J)
      repeated = repeated || (r - row).cwiseAbs().maxCoeff() < 1e-12 * (1 + row.cwiseAbs().maxCoeff());
    if (repeated) continue;
    out.J.push_back(row);
    out.T.push_back(tan);
    out.frames.push_back({px, py, nx, ny});
    out.pair.push_back(i);
    out.feature.push_back(f);
    // the same row exactly: the frame to the world by the first part's exact pose (its normal
    // by a positive multiple of the rotation), arms from the bodies' exact reference points
    kernels::Vector<Rational> ep{frame.point.x, frame.point.y}, en{frame.normal.x, frame.normal.y};
    if (p.body_a != no_index) {
      const kernels::Pose<Rational> pose = pose_of(pivot_of(p.first), q[p.body_a]);
      ep = kernels::world_point(pose, ep);
      en = kernels::world_direction_homogeneous(pose, en);
    }
    simulation::ExactRow exact{std::vector<Rational>(static_cast<std::size_t>(n), Rational(0)),
                               Rational(en.x * en.x + en.y * en.y)};
    auto put_exact = [&](std::size_t body, std::size_t part, int sign) {
      const Rational rx = ep.x - (pivot_of(part).x + q[body].x), ry = ep.y - (pivot_of(part).y + q[body].y);
      exact.a[3 * body] += sign * en.x;
      exact.a[3 * body + 1] += sign * en.y;
      exact.a[3 * body + 2] += sign * (rx * en.y - ry * en.x);
    };
    put_exact(p.body_b, p.second, 1);
    if (p.body_a != no_index) put_exact(p.body_a, p.first, -1);
    out.exact.push_back(std::move(exact));
  }
  return out;
}

void PlanarSystemSimulation::Impl::refuse_jam(double time, const Rows& rows) {
  if (rows.exact.empty()) return;
  const Eigen::VectorXd v = velocity(k);
  // (session 70, stop70) a constant-velocity driver's share from its exact speeds (the same
  // positive time scale over every share leaves the verdict as it is); a profile's from its
  // velocity doubles, and then the verdict is approximate. Every share in the model's time unit
  // (session 71, jam71): a profile's velocity double is per internal time unit (the model's
  // speed over time_scale, the seconds per model time unit), so it is taken times time_scale —
  // session 70 put it next to the constant drivers' model-unit speeds as it was, a factor
  // time_scale wrong for a model whose time unit is not the second (a millisecond model: a
  // profile closing at 0.5 mm/ms counted as 500 against a constant driver's 1)
  std::vector<std::vector<Rational>> a;
  std::vector<Rational> d;
  bool exact = true;
  for (const simulation::ExactRow& r : rows.exact) {
    std::vector<Rational> free;
    Rational closing(0);
    for (std::size_t body = 0; body < bodies.size(); ++body)
      for (std::size_t j = 3 * body; j < 3 * body + 3; ++j) {
        if (!bodies[body].driven) {
          free.push_back(r.a[j]);
          continue;
        }
        const double vj = v(static_cast<Eigen::Index>(j));
        if (!std::isfinite(vj)) return;
        if (sgn(r.a[j]) == 0) continue;
        if (bodies[body].profile.empty()) {
          closing += r.a[j] * bodies[body].speed[j - 3 * body];
        } else if (vj != 0) {
          closing += r.a[j] * Rational(vj) * Rational(time_scale);
          exact = false;
        }
      }
    a.push_back(std::move(free));
    d.push_back(std::move(closing));
  }
  const std::optional<std::vector<std::size_t>> locked = simulation::locking_rows(a, d);
  if (!locked) return;
  std::vector<std::string> drivers, jammed, contacts;
  auto add = [](std::vector<std::string>& to, const std::string& name) {
    if (std::find(to.begin(), to.end(), name) == to.end()) to.push_back(name);
  };
  for (const std::size_t i : *locked) {
    const Pair& p = pairs[rows.pair[i]];
    for (const std::size_t part : {p.first, p.second}) {
      const std::size_t body = body_of[part];
      if (body == no_index) continue;
      if (!bodies[body].driven) add(jammed, model.parts[part].name);
      else if (sgn(d[i]) != 0) add(drivers, model.parts[part].name);
    }
    contacts.push_back(rows.feature[i].label);
  }
  if (jammed.empty() || drivers.empty()) return;   // (a driver against a fixed part: the caller's message)
  bool constant = true;   // (session 70: a speed profile is a prescribed driver, not a constant-speed one)
  for (const std::size_t i : *locked) {
    const Pair& p = pairs[rows.pair[i]];
    for (const std::size_t part : {p.first, p.second})
      if (body_of[part] != no_index && bodies[body_of[part]].driven)
        constant = constant && bodies[body_of[part]].profile.empty();
  }
  const std::string message =
      where(time) + ": " +
      simulation::jam_message(drivers, constant, jammed, contacts.size(), contacts,
                              exact ? "decided exactly"
                                    : "approximate (found exactly on the exact contact normals and the prescribed "
                                      "drivers' velocity doubles)");
  publish();
  throw SimulationJam(message, time / time_scale, exact);
}

void PlanarSystemSimulation::Impl::impact(double time,
                                          const std::vector<std::pair<std::size_t, SlicedFeaturePair>>& touching) {
  const auto n = static_cast<Eigen::Index>(3 * bodies.size());
  Rows contact = contact_rows(touching);
  if (contact.J.empty()) throw GeometryError(where(time) + ": parts touch only at vertex–vertex contacts: no contact normal");
  const auto m = static_cast<Eigen::Index>(contact.J.size());
  const std::vector<std::size_t>& row_pair = contact.pair;
  const auto& frames = contact.frames;
  Eigen::MatrixXd J(m, n);
  for (Eigen::Index r = 0; r < m; ++r) J.row(r) = contact.J[static_cast<std::size_t>(r)].transpose();
  const Eigen::VectorXd minv = inverse_mass(), v = velocity(k);
  Eigen::VectorXd before = J * v;
  // an impact slower than the rest speed is plastic, and so are the held contacts' rows
  // (session 68, impact68: decided exactly on J, v — was the rounded J v; slower_than)
  const bool plastic = simulation::slower_than(J, v, rest_speed);
  Eigen::VectorXd b(m), restitution(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    const auto row = static_cast<std::size_t>(r);
    const double e = plastic || is_held(row_pair[row], contact.feature[row]) ? 0.0 : pairs[row_pair[row]].restitution;
    restitution(r) = e;
    b(r) = (1 + e) * before(r);
  }
  // the restitution terms e J v- exactly (every row, as b)
  const std::vector<Rational> h_exact = simulation::exact_restitution_terms(J, v, restitution, false);
  Eigen::MatrixXd A = J * minv.asDiagonal() * J.transpose();
  for (Eigen::Index r = 0; r < m; ++r)
    // (session 68, impactpin68: decided exactly — was the rounded J v's sign and the rounded A_rr)
    if (simulation::approaches(J.row(r).transpose(), v) &&
        !simulation::gives_way(J.row(r).transpose(), minv)) {   // a driver against a fixed part or another driver
      const Pair& p = pairs[row_pair[static_cast<std::size_t>(r)]];
      refuse_jam(time, contact);   // (session 69: the jam's contacts named where the exact test finds them)
      publish();   // (session 69: a jam, the state published at it, its run's result kept by the CLI)
      throw SimulationJam(where(time) + ": driven part '" + model.parts[p.second].name + "' runs into '" +
                              model.parts[p.first].name + "': nothing there can give way (a jam)",
                          time / time_scale, true);   // (exact: no inverse mass on either side of the row)
    }
  bool frictional = false;
  for (std::size_t i : row_pair) frictional = frictional || pairs[i].mu_static > 0;
  Eigen::VectorXd lambda, after_v, tangential = Eigen::VectorXd::Zero(m);
  if (!frictional) {
    simulation::LcpSolution lcp = simulation::solve_lcp(A, b);
    // (session 68, impact68: which rows get an impulse decided exactly — exact_impact_lcp)
    // (session 74, jam74: in a plastic impact — every row's restitution 0 — the exact solution's
    // velocities are kept also where the doubles' agree: a block carried off plastically then
    // moves exactly with its pusher, docs/simulation.md. Not for elastic rows: kept there, the
    // pusher-blocks example's run diverged — session 75 (jam75) found why: the exact symmetric
    // motion keeps the blocks in line, the pusher squeezes them into the wall, and at the closing
    // instant the chain is locked but for the rows' ~1e-25 rad rounding, so the exact LCP answers
    // with 1.4e47 N s impulses: the pusher's work, no impact gains energy (docs/simulation.md
    // Session 75))
    bool all_plastic = true;
    for (Eigen::Index r = 0; r < m; ++r) all_plastic = all_plastic && restitution(r) == 0;
    const std::optional<simulation::FrictionalSolution> exact =
        simulation::exact_impact_lcp(J, minv, v, h_exact, lcp, nullptr, all_plastic);
    if (exact) lcp.solved = exact->solved;
    if (!lcp.solved) refuse_jam(time, contact);   // (session 69: a jam, named, where it is one)
    if (!lcp.solved) throw NumericError(where(time) + ": the impact problem has no solution");
    // (session 75, jam75) the exact energy balance on the held set decided exactly (the doubles'
    // where exact_impact_lcp kept them: the same rows have impulses)
    refuse_energy_gain(time, contact, J, minv, v, restitution, h_exact, exact ? exact->lambda : lcp.lambda);
    lambda = exact ? exact->lambda : lcp.lambda;
    after_v = exact ? exact->x : Eigen::VectorXd(v + minv.asDiagonal() * (J.transpose() * lcp.lambda));
  } else {   // Coulomb-limited tangential impulses, as the single planar part's impacts
    std::vector<simulation::Friction> friction(static_cast<std::size_t>(m));
    for (std::size_t r = 0; r < friction.size(); ++r) {
      const Pair& pair = pairs[row_pair[r]];
      friction[r].on = pair.mu_static > 0;
      friction[r].T = contact.T[r];
      friction[r].mu_static = pair.mu_static;
      friction[r].mu_kinetic = pair.mu_kinetic;
    }
    bool limited = false;
    simulation::FrictionalSolution sol;
    try {
      sol = frictional_impact(J, minv, v, b - before, friction, collinear_groups(friction, row_pair), where(time),
                              named_pairs(row_pair), limited, &h_exact);
    } catch (const NumericError&) {
      // a geometric lock does not depend on the friction: the jam's contacts named where the exact
      // test finds them (as the frictionless branch above), else the impact's own message
      refuse_jam(time, contact);
      throw;
    }
    if (limited) ++stats.restitution_limited;
    lambda = sol.lambda;
    tangential = sol.f;
    after_v = sol.x;
  }
  Eigen::VectorXd after = J * after_v;
  set_velocity(k, after_v);
  // one impact event per pair, at its row of largest impulse
  std::vector<bool> done(pairs.size(), false);
  for (std::size_t r = 0; r < row_pair.size(); ++r) {
    std::size_t i = row_pair[r];
    if (done[i]) continue;
    done[i] = true;
    SimulationEvent e;
    e.kind = SimulationEvent::Kind::impact;
    e.time = time / time_scale;
    e.pair = pairs[i].index;
    e.first_part = model.parts[pairs[i].first].name;
    e.second_part = model.parts[pairs[i].second].name;
    auto top = static_cast<Eigen::Index>(r);
    double total = 0;
    for (std::size_t s = 0; s < row_pair.size(); ++s)
      if (row_pair[s] == i) {
        auto row = static_cast<Eigen::Index>(s);
        e.features.push_back(contact.feature[s].label);
        total += lambda(row);
        e.tangential_impulse += tangential(row) / (force_scale * time_scale);
        if (lambda(row) > lambda(top)) top = row;
      }
    e.impulse = total / (force_scale * time_scale);
    e.normal_speed_before = before(top) * time_scale;
    e.normal_speed_after = after(top) * time_scale;
    const auto& fr = frames[static_cast<std::size_t>(top)];
    e.point = {fr[0], fr[1]};
    e.normal = {fr[2], fr[3]};
    events.push_back(std::move(e));
  }
  // hold every contact left without separating speed (vertex–segment contacts); one involving
  // an arc cannot be held between moving parts: the class of inputs ends there
  // (exact decisions, held_resolution.hpp: the rows at the exact configuration, the velocities,
  // masses and speeds as the exact values of their doubles)
  std::vector<Rational> v_exact, minv_exact, reach_exact;
  for (Eigen::Index c = 0; c < n; ++c) {
    v_exact.push_back(finite_exact(after_v(c), where(time), "the velocity after the impact"));
    minv_exact.emplace_back(minv(c));
  }
  for (const Body& b : bodies) reach_exact.emplace_back(b.reach);
  const Rational rest = finite_exact(rest_speed, where(time), "the rest speed");
  std::vector<bool> candidate(row_pair.size(), false);
  for (std::size_t r = 0; r < row_pair.size(); ++r) {
    const auto row = static_cast<Eigen::Index>(r);
    if (simulation::separating_faster_than(contact.exact[r], v_exact, rest)) continue;   // separating
    const Pair& p = pairs[row_pair[r]];
    if (!world_gap(p, contact.feature[r], k).defined) {
      if (before(row) >= 0) continue;   // not approaching: the free search watches it
      throw NumericError(where(time) + ": '" + model.parts[p.first].name + "' and '" + model.parts[p.second].name +
                         "' would stay in contact at " + contact.feature[r].label +
                         " (an arc): sustained contact on arcs is not supported when several planar parts move "
                         "(docs/simulation.md)");
    }
    candidate[r] = true;
  }
  const std::vector<bool> keep = simulation::held_at_resolution(
      candidate, contact.exact, minv_exact, v_exact, [&](std::size_t b) { return reach_exact[b]; }, rest);
  std::vector<Held> now;
  for (std::size_t r = 0; r < row_pair.size(); ++r) {
    if (!keep[r]) continue;
    // its friction state is decided afresh by the next step's problem (as for a single part): a
    // state kept from before the impact could contradict the velocities the impact leaves (a
    // sticking contact made to slip), and the projection below would then mix inconsistent rows
    Held c{row_pair[r], contact.feature[r], simulation::frictionless};
    bool repeated = false;
    for (const Held& h : now)
      repeated = repeated || (h.pair == c.pair && h.feature.fixed == c.feature.fixed && h.feature.free == c.feature.free);
    if (!repeated) now.push_back(c);
  }
  std::vector<Held> previous = std::move(held);
  held = std::move(now);
  if (held.empty()) return;
  project(k, false);   // the plastic remainder of the normal speeds removed (mass-weighted)
  for (const Held& c : held) {
    bool was = false;
    for (const Held& h : previous)
      was = was || (h.pair == c.pair && h.feature.fixed == c.feature.fixed && h.feature.free == c.feature.free);
    if (!was) events.push_back(held_event(SimulationEvent::Kind::contact, c, held_frame(c, k), 0, 0));
  }
}

bool PlanarSystemSimulation::Impl::advance(double span) {
  using namespace boost::numeric::odeint;
  if (resting) {   // every part at rest on its held contacts, the loads constant: it stays
    t += span;
    return false;
  }
  // a driver's speed profile: the step ends at its next point; within it the velocity is linear
  // (the segment's slope is the driver's acceleration) and set to the profile's value at its start
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    if (b.profile.empty()) continue;
    std::size_t j = 0;
    while (j + 1 < b.profile.size() && b.profile[j + 1][0] <= t + 1e-12 * std::max(1.0, std::abs(t))) ++j;
    const std::array<double, 4>& p0 = b.profile[j];
    double v[3] = {p0[1], p0[2], p0[3]};
    for (double& a : b.drive_accel) a = 0;
    if (j + 1 < b.profile.size()) {
      const std::array<double, 4>& p1 = b.profile[j + 1];
      const double dt = p1[0] - p0[0];
      for (int c = 0; c < 3; ++c) {
        b.drive_accel[c] = (p1[1 + c] - p0[1 + c]) / dt;
        v[c] = p0[1 + c] + b.drive_accel[c] * (t - p0[0]);
      }
      span = std::min(span, std::max(p1[0] - t, 0.0));
    }
    k[i].vx = v[0];
    k[i].vy = v[1];
    k[i].omega = v[2];
  }
  if (!(span > 0)) return false;
  // a change of the held set or of a state is a step of its own (its events at its time)
  if (decide()) return true;
  if (resting) return true;
  const std::vector<Kinematic> k0 = k;
  const std::vector<SlicedConfiguration> q0 = q;
  auto f = [this](const StateN& x, StateN& dx, double) { held_rhs(x, dx); };
  double h = step_guess > 0 ? std::min(step_guess, span)
                            : first_trial(pack(k0), [this](const StateN& x, StateN& dx) { held_rhs(x, dx); }, span);
  std::vector<SlicedConfiguration> rel0;
  std::vector<bool> flip;
  // the held feature pairs of each pair: their own surface is what the motion follows
  std::vector<std::vector<std::pair<FeatureIdentity, FeatureIdentity>>> ignored(pairs.size());
  for (const Held& c : held) ignored[c.pair].emplace_back(c.feature.fixed, c.feature.free);
  for (const Pair& p : pairs) {
    rel0.push_back(relative(p, q0));
    flip.push_back(std::abs(wrap(relative_angle(p, k0))) > std::numbers::pi / 2);
  }
  for (int attempt = 0; attempt < 200; ++attempt) {
    auto stepper = make_controlled(accuracy, accuracy, runge_kutta_dopri5<StateN>());
    StateN y = pack(k0);
    double tt = 0, trial = h;
    for (int tries = 0; stepper.try_step(f, y, tt, trial) == fail; ++tries)
      if (tries > 200 || !(trial > 0)) throw NumericError(where(t) + ": the integration fails");
    double end = tt;
    step_guess = trial;
    std::vector<Kinematic> k1 = unpack(y);
    std::vector<unsigned> bits;
    if (!held.empty()) {
      project(k1, true);
      cut_at_first_violation(
          end, k1, [&](double s) { return fixed_step(k0, s); },
          [&](const std::vector<Kinematic>& at, std::vector<unsigned>* b) { return violated(at, b); }, bits);
    }
    std::vector<SlicedConfiguration> q1;
    for (const Kinematic& b : k1) q1.push_back(configuration_of(b.x, b.y, b.theta));
    // far test per pair (certified for the chord: the exact sweep bound against features_near's
    // certified distance; the integrated path kept apart by twice its travel bound plus delta)
    std::vector<bool> far(pairs.size(), false);
    std::vector<SlicedConfiguration> rel1;
    double cap = std::numeric_limits<double>::infinity(), h_far = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const Pair& p = pairs[i];
      rel1.push_back(relative(p, q1));
      std::optional<Rational> sweep = simulation::motion_sweep_bound(rel0[i], rel1[i], flip[i], bodies[p.body_b].reach_bound);
      double move = travel(p, k0, k1, end);
      Rational radius = finite_exact(2 * move + delta, where(t), "the distance a step covers");
      if (sweep && *sweep > radius) radius = *sweep;
      ++stats.distance_queries;
      double nearest = std::numeric_limits<double>::infinity();
      std::optional<Rational> nearest_exact;
      for (const SlicedNearFeature& nf : p.space.features_near(rel0[i], radius)) {
        if (is_held(i, nf.pair)) continue;
        nearest = std::min(nearest, to_d(nf.distance_lower));
        if (!nearest_exact || nf.distance_lower < *nearest_exact) nearest_exact = nf.distance_lower;
      }
      far[i] = sweep && (!nearest_exact || *nearest_exact > *sweep) && nearest > 2 * move + delta;
      if (!far[i]) {
        cap = std::min(cap, chord_cap(p, k0, k1));
        // a step short enough to be far (the travel grows about linearly with the step)
        if (nearest > delta && move > 0) h_far = std::min(h_far, 0.5 * (nearest - delta) / move * end * (1 - 1e-6));
      }
    }
    if (h_far > cap && h_far < end) {
      h = step_guess = h_far;
      continue;
    }
    if (end > cap * (1 + 1e-9)) {
      h = step_guess = cap;
      continue;
    }
    // the held contacts at the new state: exactly apart from their segments' lines
    for (const Held& c : held) {
      const Pair& p = pairs[c.pair];
      if (sgn(contact_gap(p.frame_model ? *p.frame_model : model, c.feature, pose_of(pivot_of(p.second), rel1[c.pair]))
                  .gap) <= 0)
        throw NumericError(where(t + end) + ": a held contact's projected state is not exactly apart (internal error)");
    }
    std::vector<std::pair<std::size_t, SlicedMotionCrossing>> crossings;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (far[i]) continue;
      ++stats.chord_tests;
      SlicedMotionCrossing c = pairs[i].space.first_crossing(SlicedMotion{rel0[i], rel1[i], flip[i], ignored[i]},
                                                             CrossingOptions{options.crossing_bits});
      if (c.status == CrossingStatus::starts_in_contact)
        throw NumericError(where(t) + " '" + model.parts[pairs[i].second].name + "' starts a chord in contact with '" +
                           model.parts[pairs[i].first].name + "' (an internal error)");
      if (c.status == CrossingStatus::crossing) crossings.emplace_back(i, std::move(c));
    }
    if (crossings.empty()) {
      // (session 75, jam75; Issue 11, review74 M1) the pairs with held contacts: the sweep ignores
      // their held feature pairs, and the check above sees only each held vertex against its own
      // segment's line. The whole pair located exactly at the step's end (SlicedSpace::locate on
      // the exact configurations the step publishes): a step that leaves one blocked is not
      // accepted but halved (as the far and chord caps above), so no accepted state has a held
      // pair overlapping — by construction, not by the tested cases. One locate per held pair
      // per accepted step (docs/simulation.md, Session 75)
      bool blocked = false;
      for (std::size_t i = 0; i < pairs.size() && !blocked; ++i)
        blocked = !ignored[i].empty() && pairs[i].space.locate(rel1[i]).kind == SlicedLocation::Kind::blocked;
      if (blocked) {
        h = step_guess = 0.5 * end;
        continue;
      }
      ++stats.advancement_steps;
      t += end;
      k = k1;
      q = q1;
      // contacts reaching the end of their segment end; lift-offs and stick/slip changes are
      // decided by the next step's problem
      return end_held_at_edges(held, bits, [&](const Held& c) {
        events.push_back(held_event(SimulationEvent::Kind::edge_end, c, held_frame(c, k), 0, 0));
      });
    }
    std::size_t best = 0;
    for (std::size_t c = 1; c < crossings.size(); ++c)
      if (crossings[c].second.u_lower < crossings[best].second.u_lower) best = c;
    const double u = to_d(crossings[best].second.u_lower);
    // the state at the contact, backed off in time until every pair is exactly free there
    // (the path is within delta/2 of the chords)
    std::vector<Kinematic> at;
    std::vector<SlicedConfiguration> q_at;
    double s_contact = u * end;
    // back-off steps of 2^j delta / rate: the time in which no point moves farther than 2^j delta
    double rate = 0;
    for (const std::vector<Kinematic>* ks : std::array<const std::vector<Kinematic>*, 2>{&k0, &k1})
      for (std::size_t i = 0; i < bodies.size(); ++i)
        rate = std::max(rate, std::hypot((*ks)[i].vx, (*ks)[i].vy) + std::abs((*ks)[i].omega) * bodies[i].reach);
    rate = 2 * std::max(rate, std::numeric_limits<double>::min());
    // a point speed beyond half the doubles' range (a driver at 1.8e308 mm/s): the back-off steps
    // delta / rate are 0 and no free state was found, "(an internal error)" until session 63
    if (!std::isfinite(rate))
      throw NumericError(where(t) + ": the parts' point speeds before the contact are not finite in doubles "
                                    "(twice the fastest exceeds 1.8e308 mm/s)");
    bool free_everywhere = false;
    for (int back = 0; back < 80 && !free_everywhere; ++back) {
      double s = back == 0 ? s_contact : s_contact - std::ldexp(delta / rate, back - 1);
      if (s <= 0) s = 0;
      at = s > 0 ? fixed_step(k0, s) : k0;
      q_at.clear();
      for (const Kinematic& b : at) q_at.push_back(s > 0 ? configuration_of(b.x, b.y, b.theta) : q0[&b - at.data()]);
      free_everywhere = true;
      for (const Pair& p : pairs)
        free_everywhere = free_everywhere && p.space.locate(relative(p, q_at)).kind == SlicedLocation::Kind::free;
      if (free_everywhere) s_contact = s;
      if (s == 0) break;
    }
    if (!free_everywhere) throw NumericError(where(t) + ": no free state before the contact (an internal error)");
    // how far the back-off moved any point (rate is twice the fastest point speed)
    const double backed = 0.5 * rate * (u * end - s_contact);
    // every pair whose bracket meets the earliest, and feature pairs within 2 delta of touching
    // the path there (a face meeting a face, tilted by round-off, meets all its corners at once)
    std::vector<std::pair<std::size_t, SlicedFeaturePair>> touching;
    for (const auto& [i, c] : crossings)
      if (c.u_lower <= crossings[best].second.u_upper)
        for (const SlicedFeaturePair& fp : c.features) touching.emplace_back(i, fp);
    for (std::size_t i = 0; i < pairs.size(); ++i)
      for (const SlicedNearFeature& nf : pairs[i].space.features_near(
               relative(pairs[i], q_at), finite_exact(2 * delta + backed, where(t), "the distance a step covers"))) {
        if (behind_segment(pairs[i].frame_model ? *pairs[i].frame_model : model, nf.pair, pivot_of(pairs[i].second),
                           relative(pairs[i], q_at)))
          continue;
        bool listed = false;
        for (const auto& [j, fp] : touching) listed = listed || (j == i && fp.label == nf.pair.label);
        if (!listed) touching.emplace_back(i, nf.pair);
      }
    for (const Held& c : held) {   // the held contacts join the impact (plastic)
      bool listed = false;
      for (const auto& [j, fp] : touching) listed = listed || (j == c.pair && fp.label == c.feature.label);
      if (!listed) touching.emplace_back(c.pair, c.feature);
    }
    if (!held.empty() && attempt < 40) {
      // a contact the path leaves (the chord cut its corner): a shorter chord
      const std::vector<Kinematic> keep = k;
      const std::vector<SlicedConfiguration> keep_q = q;
      k = at;
      q = q_at;
      Rows rows = contact_rows(touching);
      const Eigen::VectorXd v_at = velocity(at);
      double approach = 0;
      for (std::size_t r = 0; r < rows.J.size(); ++r)
        if (!is_held(rows.pair[r], rows.feature[r])) approach = std::min(approach, rows.J[r].dot(v_at));
      k = keep;
      q = keep_q;
      if (approach >= 0) {
        h = std::max(end / 4, 1e-300);
        continue;
      }
    }
    t += s_contact;
    k = at;
    q = q_at;
    step_guess = 0;
    impact(t, touching);
    return true;
  }
  throw NumericError(where(t) + ": no step could be certified");
}

PlanarSystemSimulation::PlanarSystemSimulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PlanarSystemSimulation::PlanarSystemSimulation(PlanarSystemSimulation&&) noexcept = default;
PlanarSystemSimulation& PlanarSystemSimulation::operator=(PlanarSystemSimulation&&) noexcept = default;
PlanarSystemSimulation::~PlanarSystemSimulation() = default;

PlanarSystemSimulation PlanarSystemSimulation::create(const Model& model, const SimulationOptions& options) {
  check_simulator_range(model);
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  SimulationSpec spec = simulation::start_simulation(s, model, options);
  const double fs = s.force_scale, ts = s.time_scale;
  s.body_of.assign(model.parts.size(), no_index);
  double max_reach = 0, max_accel = 0;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    if (part.motion.kind == Motion::Kind::fixed) continue;
    if (part.motion.kind != Motion::Kind::planar)
      throw ModelError(part.motion.pointer, "part '" + part.name + "': several planar parts move among fixed parts only");
    // a driver needs no inertia (it never gives way): unit placeholders, no loads
    bool driven = false;
    for (const auto& d : spec.drivers) driven = driven || d.part == p;
    static const Dynamics driver_dynamics{Rational(1), Rational(1), {}, {}, {}, {}, {}};
    const Dynamics& dyn = driven ? driver_dynamics : checked_planar_dynamics(part);
    Impl::Body b;
    b.part = p;
    simulation::set_planar_loads(b, dyn, fs, ts, s.g);
    b.pivot[0] = to_d(part.motion.pivot.x);
    b.pivot[1] = to_d(part.motion.pivot.y);
    PlanarReach reach = planar_reach(part);
    b.reach = reach.reach;
    b.reach_bound = reach.bound;
    max_reach = std::max(max_reach, b.reach);
    max_accel = std::max(max_accel, std::hypot(b.accel[0], b.accel[1]) + std::abs(b.alpha) * b.reach);
    s.body_of[p] = s.bodies.size();
    s.bodies.push_back(b);
    Kinematic kin = initial_kinematic(model, p, spec, ts);
    s.k.push_back(kin);
    s.q.push_back(configuration_of(kin.x, kin.y, kin.theta));
  }
  if (s.bodies.empty()) throw ModelError("", "the model has no planar part to simulate");
  // drivers of planar parts: a constant velocity or a speed profile, three entries vx, vy, omega (the reader's)
  for (std::size_t d = 0; d < spec.drivers.size(); d += 3) {
    const std::size_t body = s.body_of[spec.drivers[d].part];
    if (body == no_index || d + 2 >= spec.drivers.size())
      throw ModelError(spec.drivers[d].pointer, "the planar simulator drives planar parts only");
    Impl::Body& b = s.bodies[body];
    b.driven = true;
    s.k[body].vx = to_d(spec.drivers[d].speed) / ts;
    s.k[body].vy = to_d(spec.drivers[d + 1].speed) / ts;
    s.k[body].omega = to_d(spec.drivers[d + 2].speed) / ts;
    b.speed = {spec.drivers[d].speed, spec.drivers[d + 1].speed, spec.drivers[d + 2].speed};
    for (std::size_t p = 0; p < spec.drivers[d].profile.size(); ++p)   // the reader's three equal-length profiles
      b.profile.push_back({to_d(spec.drivers[d].profile[p].first) * ts, to_d(spec.drivers[d].profile[p].second) / ts,
                           to_d(spec.drivers[d + 1].profile[p].second) / ts, to_d(spec.drivers[d + 2].profile[p].second) / ts});
  }
  for (const auto& coupling : spec.couplings) {
    Impl::Spring sp;
    const std::size_t ends[2] = {coupling.first, coupling.second};
    const Point* points[2] = {&coupling.first_point, &coupling.second_point};
    for (int e = 0; e < 2; ++e) {
      sp.body[e] = s.body_of[ends[e]];
      const Point& pivot = model.parts[ends[e]].motion.pivot;
      sp.point[e][0] = to_d(sp.body[e] == no_index ? points[e]->x : points[e]->x - pivot.x);
      sp.point[e][1] = to_d(sp.body[e] == no_index ? points[e]->y : points[e]->y - pivot.y);
    }
    if (sp.body[0] == no_index && sp.body[1] == no_index) continue;   // two fixed parts: acts on nothing
    sp.k = to_d(coupling.stiffness) * fs;
    sp.rest = to_d(coupling.rest_length);
    sp.c = to_d(coupling.damping) * fs * ts;
    s.springs.push_back(sp);
  }
  s.accuracy = simulation::simulation_accuracy(options, spec);
  s.delta = options.chord_deviation > 0 ? options.chord_deviation : s.accuracy * std::max(max_reach, 1.0);
  s.rest_speed = std::sqrt(2 * max_accel * s.delta);
  s.hold_gap = 0.75 * s.delta;
  for (std::size_t i = 0; i < model.pairs.size(); ++i) {
    const PairSpec& pair = model.pairs[i];
    std::size_t a = s.body_of[pair.first], b = s.body_of[pair.second];
    if (a == no_index && b == no_index) continue;
    Impl::Pair p;
    p.index = i;
    p.restitution = pair.restitution ? to_d(*pair.restitution) : 0.0;
    if (pair.friction) {
      p.mu_static = to_d(*pair.friction);
      p.mu_kinetic = pair.kinetic_friction ? to_d(*pair.kinetic_friction) : p.mu_static;
    }
    if (a == no_index || b == no_index) {
      p.first = a == no_index ? pair.first : pair.second;
      p.second = a == no_index ? pair.second : pair.first;
      p.body_b = s.body_of[p.second];
      p.space = SlicedSpace::build(model, model.parts[p.first].name, model.parts[p.second].name, SlicedBuildOptions{false, {}});
    } else {
      p.first = pair.first;
      p.second = pair.second;
      p.body_a = a;
      p.body_b = b;
      // the first part held fixed at its zero configuration: the pair's space in its frame
      auto frame = std::make_shared<Model>(model);
      frame->parts[p.first].motion.kind = Motion::Kind::fixed;
      frame->parts[p.first].initial = PartConfiguration{};
      p.space = SlicedSpace::build(*frame, model.parts[p.first].name, model.parts[p.second].name,
                                   SlicedBuildOptions{false, {}});
      p.frame_model = std::move(frame);
    }
    SlicedLocation where = p.space.locate(s.relative(p, s.q));
    if (where.kind != SlicedLocation::Kind::free) {
      const Part& part = model.parts[p.second];
      throw ModelError(part.pointer + "/initial", "planar part '" + part.name + "' starts " +
                                                      (where.kind == SlicedLocation::Kind::blocked ? "overlapping"
                                                                                                   : "touching") +
                                                      " part '" + model.parts[p.first].name + "'" +
                                                      (model.parts[p.first].motion.kind == Motion::Kind::fixed
                                                           ? std::string()
                                                           : " (its initial configuration: " +
                                                                 model.parts[p.first].pointer + "/initial)") +
                                                      ": it must start apart");
    }
    s.pairs.push_back(std::move(p));
  }
  for (const Impl::Body& b : s.bodies) s.public_state.parts.push_back(b.part);
  s.public_state.states.resize(s.bodies.size());
  s.publish();
  PlanarSystemSimulation simulated(std::move(impl));
  // (session 72, jam72) an initial state beyond the doubles: bad input at its datum, nothing run
  simulation::refuse_initial_energy(model, simulated.energy());
  return simulated;
}

void PlanarSystemSimulation::step(double t_limit) {
  Impl& s = *impl_;
  double limit = 0;
  const double span = next_span(s, t_limit, limit);
  if (!(span > 0)) return;
  double before = s.t;
  bool event = false;
  naming_the_data(s.model, [&] {
    event = s.advance(span);
    if (!std::isfinite(energy())) {   // (session 65, sim65) a stop, not "energy null" and exit 0
      std::ostringstream parts;
      const char* separator = "";
      for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        const Part& p = s.model.parts[s.bodies[i].part];
        parts << separator << "part '" << p.name << "' (" << p.pointer << "/dynamics, " << p.pointer << "/initial; at ("
              << s.k[i].x << ", " << s.k[i].y << ") mm, moving at "
              << std::hypot(s.k[i].vx, s.k[i].vy) * s.time_scale << " mm/" << s.time_unit << " and "
              << s.k[i].omega * s.time_scale << " rad/" << s.time_unit << ")";
        separator = ", ";
      }
      throw NumericError(simulation::energy_overflow_message(s.where(s.t), parts.str()));
    }
  });
  // the last step of a run ends at its limit exactly (the integrator's sum may differ by an ulp)
  if (!event && std::abs(s.t - limit) <= 1e-12 * std::max(std::abs(limit), 1e-300) && before + span >= limit) s.t = limit;
  s.publish();
}

void PlanarSystemSimulation::run_until(double t_end, const std::function<void(double)>& progress) {
  run_steps(*impl_, t_end, progress, [&] { step(t_end); });
}

const PlanarSystemState& PlanarSystemSimulation::state() const { return impl_->public_state; }
const std::vector<SimulationEvent>& PlanarSystemSimulation::events() const { return impl_->events; }
std::size_t PlanarSystemSimulation::steps() const { return impl_->steps; }
const PlanarStatistics& PlanarSystemSimulation::statistics() const { return impl_->stats; }
double PlanarSystemSimulation::chord_deviation() const { return impl_->delta; }
const Model& PlanarSystemSimulation::model() const { return impl_->model; }
const std::string& PlanarSystemSimulation::time_unit() const { return impl_->time_unit; }
const std::string& PlanarSystemSimulation::force_unit() const { return impl_->force_unit; }

double PlanarSystemSimulation::energy() const {
  const Impl& s = *impl_;
  double e = 0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Impl::Body& b = s.bodies[i];
    const Kinematic& k = s.k[i];
    if (b.driven) continue;   // a driver's energy is its motor's (as the fixed-axis simulator)
    e += 0.5 * b.mass * (k.vx * k.vx + k.vy * k.vy) + 0.5 * b.inertia * k.omega * k.omega;
    e -= (b.mass * s.g[0] + b.force[0]) * k.x + (b.mass * s.g[1] + b.force[1]) * k.y + b.torque * k.theta;
    e += 0.5 * b.torsion_k * (k.theta - b.torsion_rest) * (k.theta - b.torsion_rest);
  }
  for (const Impl::Spring& sp : s.springs) {
    double p0[2], v0[2], r0[2], p1[2], v1[2], r1[2];
    s.spring_end(sp, 0, s.k, p0, v0, r0);
    s.spring_end(sp, 1, s.k, p1, v1, r1);
    double L = std::hypot(p0[0] - p1[0], p0[1] - p1[1]);
    e += 0.5 * sp.k * (L - sp.rest) * (L - sp.rest);
  }
  return e / s.force_scale;
}

}  // namespace hipair
