// Impacts on nearly dependent contacts (docs/simulation.md, "Impacts on nearly dependent
// contacts"; issue 11, session 53 esc53). A square thrown past a bump smaller than the chord
// deviation (about 7e-9 mm here) met it with every feature pair of the bump within that distance,
// including pairs whose vertex lies behind its segment's line (the bump's bottom edge against the
// square's corner, the square's right side against the bump's left vertices): rows facing every
// way, an infeasible impact problem ("the impact problem has no solution", base53, bumps 1e-9 ...
// 1e-14 mm) or one that pinned the square in mid-air (bumps <= 1e-16 mm: at rest on nothing).
// Such pairs are now left out, exactly (their gap's sign).
// Oracles: the closed form of the single contact for two rows 10^-k apart (h -> 0), Newton's law
// at every row (post-impact normal speed = -e x pre-impact speed where the impulse acts, not
// approaching elsewhere), the momentum balance; at the simulation level a throw past bumps
// 10^-k mm high (k from 0 to 30) that runs through, never gains energy and never rests on the bump,
// and a square dropped flat on exactly coincident and nearly coincident corners (first impact at
// sqrt(2 H / g), rebound -e times the approach, rest with forces summing to m g).
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include "simulation/held_resolution.hpp"
#include "simulation/lcp.hpp"
#include "simulation_planar_support.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

// Two contacts on one face of a planar body: normal n (unit), points p and p + h t (t the face's
// tangent), arms relative to the centre of mass; pre-impact velocity (vx, vy, w) approaching.
TEST(SimulationImpactResolution, NearlyDependentRowsSolveAgainstTheClosedForm) {
  Lcg rng{53};
  int cases = 0;
  for (int k = 0; k <= 30; ++k)
    for (int draw = 0; draw < 20; ++draw) {
      const double m = rng.uniform(1e-3, 1), I = m * rng.uniform(1, 100), e = draw % 5 == 0 ? 0.0 : rng.uniform(0, 1);
      const double phi = rng.uniform(0, 6.283185307179586), nx = std::cos(phi), ny = std::sin(phi);
      const double tx = -ny, ty = nx, L = rng.uniform(1, 10), s_along = rng.uniform(-L, L), h = L * std::pow(10.0, -k);
      // the face's points: centre of mass at the origin, the face at distance L along -n
      const double p1x = -L * nx + s_along * tx, p1y = -L * ny + s_along * ty, p2x = p1x + h * tx, p2y = p1y + h * ty;
      Eigen::MatrixXd J(2, 3);
      J << nx, ny, p1x * ny - p1y * nx, nx, ny, p2x * ny - p2y * nx;
      const Eigen::Vector3d minv(1 / m, 1 / m, 1 / I);
      // approaching: the face's normal speed at p1 negative
      const double speed = rng.uniform(1, 1000), w = rng.uniform(-1, 1) * speed / L;
      const double along = rng.uniform(-1, 1) * speed;
      const double un = -speed - (p1x * ny - p1y * nx) * w;   // n . v so that J v at p1 = -speed
      const Eigen::Vector3d v(un * nx + along * tx, un * ny + along * ty, w);
      const Eigen::VectorXd before = J * v;
      const Eigen::MatrixXd A = J * minv.asDiagonal() * J.transpose();
      const Eigen::VectorXd b = (1 + e) * before;
      // the solve's resolution: the LCP's own tolerance (lcp_tolerance, 1e-10 of |b|)
      const simulation::LcpSolution s = simulation::solve_lcp(A, b);
      const double sigma = 10 * s.tolerance;
      SCOPED_TRACE("k " + std::to_string(k) + " draw " + std::to_string(draw));
      ASSERT_TRUE(s.solved);
      const Eigen::Vector3d after = v + minv.asDiagonal() * (J.transpose() * s.lambda);
      const Eigen::VectorXd u = J * after;
      for (int r = 0; r < 2; ++r) {
        EXPECT_GE(s.lambda(r), 0.0);
        // Newton: not approaching faster than -e u-, and exactly -e u- where the impulse acts
        EXPECT_GE(u(r) + e * before(r), -sigma * (1 + 1e-9));
        if (s.lambda(r) > 0) EXPECT_LE(std::abs(u(r) + e * before(r)), sigma * (1 + 1e-9));
      }
      // the closed form of the single contact at p1: impulse (1 + e) speed / A11. The second
      // contact's approach differs by h |w| <= h speed / L and its A22 by 2 h arm / I + h^2 / I, so
      // the total impulse agrees to those relative amounts and sigma's
      const double P = (1 + e) * speed / A(0, 0);
      const double arm = std::abs(p1x * ny - p1y * nx) + L;
      const double slack = 4 * sigma / A(0, 0) + P * (2 * h / L + 4 * h * (arm + h) / (I * A(0, 0))) + 1e-9 * P;
      if (h < 1e-6 * L) EXPECT_NEAR(s.lambda.sum(), P, slack);
      // momentum: m dv = (sum lambda) n, I dw = sum lambda r x n
      EXPECT_NEAR(m * (after(0) - v(0)), s.lambda.sum() * nx, 1e-12 * (P + m * speed));
      EXPECT_NEAR(m * (after(1) - v(1)), s.lambda.sum() * ny, 1e-12 * (P + m * speed));
      // energy: a Newton impact with e <= 1 at contacts of one normal creates none (to sigma's order)
      const double k0 = 0.5 * (m * v.head<2>().squaredNorm() + I * w * w);
      const double k1 = 0.5 * (m * after.head<2>().squaredNorm() + I * after(2) * after(2));
      EXPECT_LE(k1, k0 * (1 + 1e-9) + 4 * sigma * P);
      ++cases;
    }
  EXPECT_EQ(cases, 31 * 20);
}

// The exact rows and vectors of double ones (a double is an exact rational).
std::vector<simulation::ExactRow> exact_rows(const Eigen::MatrixXd& J) {
  std::vector<simulation::ExactRow> rows;
  for (Eigen::Index r = 0; r < J.rows(); ++r) {
    simulation::ExactRow row;
    for (Eigen::Index c = 0; c < J.cols(); ++c) row.a.emplace_back(J(r, c));
    row.norm2 = row.a[0] * row.a[0] + row.a[1] * row.a[1];
    rows.push_back(std::move(row));
  }
  return rows;
}
std::vector<Rational> exact_vector(const Eigen::VectorXd& x) {
  std::vector<Rational> out;
  for (Eigen::Index i = 0; i < x.size(); ++i) out.emplace_back(x(i));
  return out;
}

// held_at_resolution's thresholds (session 54; docs/simulation.md, "Why held_at_resolution's
// thresholds are what they are"). A planar body (mass m, inertia I, reach R) left by an impact
// with two contacts below the rest speed. Oracles, closed forms of the mass-weighted projection
// onto J v = 0:
// - two contacts on one face with the same normal n, moment arms c and c + h (h = 10^-k L,
//   k = 1 ... 30): J v = 0 on both leaves no normal speed and no turning, so the projection changes
//   the body's point velocity by exactly |n . v| + |omega| R, for every h > 0; both are held iff
//   that is at most 2 rest speeds, else only the slower one (the one separating fastest is freed);
// - two contacts with normals 60 ... 120 degrees apart (a corner): the 2 x 2 system solved by
//   Cramer's rule; both held iff its change is at most 2 rest speeds;
// - no decision changes for any solve fraction from 1e-9 to 1e-4 of the rest speed (below the
//   accuracy's limit, held_resolution.hpp): the rows are either solved to about 1e-16 kappa or
//   merged with a residual of the order of the speeds;
// - the decisions are the same at every scale of the speeds (rest speed 10^-6 ... 10^6).
TEST(SimulationImpactResolution, HeldContactsFollowTheClosedFormOfTheProjection) {
  Lcg rng{54};
  int both = 0, one = 0, cases = 0;
  auto decide = [](const Eigen::MatrixXd& J, const Eigen::Vector3d& minv, const Eigen::Vector3d& v, double R,
                   double rest, double fraction) {
    return simulation::held_at_resolution(std::vector<bool>{true, true}, exact_rows(J), exact_vector(minv),
                                          exact_vector(v), [&](std::size_t) { return Rational(R); }, Rational(rest),
                                          fraction);
  };
  // k <= 5 here (the double rows' closed form); nearer contacts, 0 apart included, and scales
  // beyond the doubles: HeldContactsOfNearlyCoincidentPointsDecideExactlyAtEveryScale below
  for (int k = 1; k <= 5; ++k)
    for (int draw = 0; draw < 240; ++draw) {
      const double scale = std::pow(10.0, rng.uniform(-6, 6));   // the speeds' unit
      const double m = rng.uniform(1e-3, 1), L = rng.uniform(1, 10), I = m * L * L * rng.uniform(0.05, 1);
      const double R = L * rng.uniform(1, 2), rest = scale;
      const Eigen::Vector3d minv(1 / m, 1 / m, 1 / I);
      const double phi = rng.uniform(0, 6.283185307179586), nx = std::cos(phi), ny = std::sin(phi), tx = -ny, ty = nx;
      Eigen::MatrixXd J(2, 3);
      Eigen::Vector3d v;
      double closed_change = 0;
      bool corner = draw % 4 == 3;
      if (!corner) {
        // one face: p1 = -L n + s t, p2 = p1 + h t; arms c = p x n
        const double s_along = rng.uniform(-L, L), h = L * std::pow(10.0, -k);
        const double p1x = -L * nx + s_along * tx, p1y = -L * ny + s_along * ty, p2x = p1x + h * tx, p2y = p1y + h * ty;
        const double c1 = p1x * ny - p1y * nx, c2 = p2x * ny - p2y * nx;
        J << nx, ny, c1, nx, ny, c2;
        // turning from 1e-4 to 1e4 rest speeds at the reach, normal speeds within [0, rest]
        double w = std::pow(10.0, rng.uniform(-4, 4)) * rest / R * (draw % 2 ? 1 : -1);
        const double u1 = rng.uniform(0, 1) * rest;
        if (std::abs(w * (c2 - c1)) > rest - u1) w = (rest - u1) / (c2 - c1) * rng.uniform(-1, 1);
        const double un = u1 - c1 * w, along = rng.uniform(-1, 1) * rest;
        v << un * nx + along * tx, un * ny + along * ty, w;
        closed_change = std::abs(un) + std::abs(w) * R;
      } else {
        // a corner: the second normal 60 ... 120 degrees from the first, its point elsewhere
        const double psi = phi + rng.uniform(1.0471975511965976, 2.0943951023931953);
        const double mx = std::cos(psi), my = std::sin(psi);
        const double p1x = -L * nx, p1y = -L * ny, p2x = -L * mx + rng.uniform(-L, L) * -my, p2y = -L * my + rng.uniform(-L, L) * mx;
        J << nx, ny, p1x * ny - p1y * nx, mx, my, p2x * my - p2y * mx;
        // a velocity with both normal speeds in [0, rest] and a free tangential part
        const Eigen::Vector2d u(rng.uniform(0, 1) * rest, rng.uniform(0, 1) * rest);
        const Eigen::Vector3d base = J.transpose() * (J * J.transpose()).inverse() * u;
        Eigen::Vector3d free = Eigen::Vector3d(J.row(0)).cross(Eigen::Vector3d(J.row(1)));
        v = base + free.normalized() * rng.uniform(-1, 1) * rest;
        // Cramer: G = J M^-1 J^T, lambda = G^-1 (J v), dv = -M^-1 J^T lambda
        const double g11 = J.row(0).dot(minv.cwiseProduct(Eigen::Vector3d(J.row(0)))),
                     g12 = J.row(0).dot(minv.cwiseProduct(Eigen::Vector3d(J.row(1)))),
                     g22 = J.row(1).dot(minv.cwiseProduct(Eigen::Vector3d(J.row(1))));
        const double a1 = J.row(0).dot(v), a2 = J.row(1).dot(v), det = g11 * g22 - g12 * g12;
        const double l1 = (g22 * a1 - g12 * a2) / det, l2 = (g11 * a2 - g12 * a1) / det;
        const Eigen::Vector3d dv = -minv.cwiseProduct(Eigen::Vector3d(J.row(0)) * l1 + Eigen::Vector3d(J.row(1)) * l2);
        closed_change = std::hypot(dv(0), dv(1)) + std::abs(dv(2)) * R;
      }
      // away from the boundary itself (the decision there is the rounding's)
      if (std::abs(closed_change - 2 * rest) < 1e-6 * rest) continue;
      const Eigen::VectorXd after = J * v;
      const bool expect_both = closed_change <= 2 * rest;
      const std::vector<bool> keep = decide(J, minv, v, R, rest, simulation::held_solve_fraction);
      const std::string what = std::string(corner ? "corner" : "face") + " k=" + std::to_string(k) + " draw=" +
                               std::to_string(draw) + " change/rest=" + num(closed_change / rest);
      if (expect_both) {
        EXPECT_TRUE(keep[0] && keep[1]) << what;
      } else {
        // the slower one held, the one separating fastest freed
        const std::size_t slower = after(0) <= after(1) ? 0 : 1;
        EXPECT_TRUE(keep[slower] && !keep[1 - slower]) << what << " after " << num(after(0) / rest) << " "
                                                       << num(after(1) / rest);
      }
      (expect_both ? both : one) += 1;
      for (double fraction : {1e-9, 1e-7, 1e-5, 1e-4})
        EXPECT_EQ(decide(J, minv, v, R, rest, fraction), keep) << what << " fraction " << fraction;
      ++cases;
    }
  EXPECT_GT(cases, 1100);   // of 1 200
  EXPECT_GT(both, 100);   // both kinds of decision are exercised
  EXPECT_GT(one, 100);
}

// Held contacts decided exactly (session 56; docs/simulation.md, "Held contacts decided exactly").
// Two contacts on one face of a planar body (mass m, inertia I, reach R), h = 10^-k L apart
// (k = 6 ... 15) or exactly 0 apart (two features at one point), at the scales 1, 10^-300 and
// 10^400 (every length, speed and the rest speed times s, the inertia times s^2: no double holds
// the latter two). Oracles, the closed forms of the mass-weighted projection onto J v = 0:
// - h > 0: no normal speed and no turning remain, the change is |n . v| / |n| + |omega| R;
// - h = 0: one row a = [n, c], the change is |a . v| / G (|n| / m + |c| R / I), G = a M^-1 a^T;
// both are held iff the change is at most 2 rest speeds (or neither separates faster than the
// solve fraction); otherwise the one separating faster is freed (one of two equal ones at h = 0).
// The decisions are the same at every scale. Before (base56: the rows rounded to doubles, the
// projection solved in doubles) 438 of these 1 320 decisions at scale 1 differed from the closed
// form (k = 7 ... 15; 1, 26, 49 ... 68 of 120 per k), and the other scales cannot be written in
// doubles at all (docs/simulation.md).
TEST(SimulationImpactResolution, HeldContactsOfNearlyCoincidentPointsDecideExactlyAtEveryScale) {
  Lcg rng{56};
  int both = 0, one = 0, cases = 0;
  auto power10 = [](int e) {
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
    return e < 0 ? Rational(1) / Rational(p) : Rational(p);
  };
  // |x| <= limit - y for x, y >= 0 given x^2 (exactly)
  auto within = [](const Rational& x2, const Rational& y, const Rational& limit) {
    return cmp(y, limit) <= 0 && cmp(x2, (limit - y) * (limit - y)) <= 0;
  };
  for (int k = 6; k <= 16; ++k)   // k = 16: the two contacts exactly 0 apart
    for (int draw = 0; draw < 120; ++draw) {
      const bool coincident = k == 16;
      const double m = rng.uniform(1e-3, 1), Ld = rng.uniform(1, 10), Id = m * Ld * Ld * rng.uniform(0.05, 1);
      const double Rd = Ld * rng.uniform(1, 2), restd = std::pow(10.0, rng.uniform(-6, 6));
      const double phi = rng.uniform(0, 6.283185307179586), nxd = std::cos(phi), nyd = std::sin(phi);
      const double s_along = rng.uniform(-Ld, Ld);
      const double wd = std::pow(10.0, rng.uniform(-4, 4)) * restd / Rd * (draw % 2 ? 1 : -1);
      const double u1 = rng.uniform(0, 1) * restd, along = rng.uniform(-1, 1) * restd;
      const Rational nx(nxd), ny(nyd), N = nx * nx + ny * ny, tx = -ny, ty = nx;
      std::vector<bool> decided;
      for (int E : {0, -300, 400}) {
        const Rational s = power10(E), L = Rational(Ld) * s, R = Rational(Rd) * s, rest = Rational(restd) * s;
        const Rational h = coincident ? Rational(0) : L * power10(-k);
        const Rational p1x = -L * nx + Rational(s_along) * s * tx, p1y = -L * ny + Rational(s_along) * s * ty;
        const Rational p2x = p1x + h * tx, p2y = p1y + h * ty;
        const Rational c1 = p1x * ny - p1y * nx, c2 = p2x * ny - p2y * nx;
        // the turning kept small enough that the second contact is not separating either
        Rational w(wd);
        if (!coincident && std::abs(wd) * to_double(h / s) > restd - u1) w = Rational((restd - u1) * 0.5) / (h / s) * (wd > 0 ? 1 : -1);
        const Rational an = (Rational(u1) * s - c1 * w) / N;   // n . v = an N: the first contact's speed ~ u1
        const std::vector<Rational> v{an * nx + Rational(along) * s * tx, an * ny + Rational(along) * s * ty, w};
        const std::vector<Rational> minv{Rational(1) / Rational(m), Rational(1) / Rational(m),
                                         Rational(1) / (Rational(Id) * s * s)};
        const std::vector<simulation::ExactRow> rows{{{nx, ny, c1}, N}, {{nx, ny, c2}, N}};
        const std::vector<bool> keep = simulation::held_at_resolution(
            std::vector<bool>{true, true}, rows, minv, v, [&](std::size_t) { return R; }, rest);
        // the closed form
        const Rational nv = v[0] * nx + v[1] * ny, a1v = nv + c1 * w, a2v = nv + c2 * w;
        bool expect_both;
        if (!coincident) {
          expect_both = within(nv * nv / N, abs(w) * R, 2 * rest);
        } else {
          const Rational G = N * minv[0] + c1 * c1 * minv[2];
          const Rational lin = abs(a1v) / G * minv[0], turn = abs(a1v) / G * abs(c1) * minv[2] * R;
          expect_both = within(lin * lin * N, turn, 2 * rest);
        }
        // neither separating faster than the solve fraction: the projection stands
        const Rational slow = Rational(simulation::held_solve_fraction) * rest;
        const Rational fastest = cmp(a1v, a2v) >= 0 ? a1v : a2v;
        if (sgn(fastest) <= 0 || cmp(fastest * fastest, slow * slow * N) <= 0) expect_both = true;
        const std::string what = "k=" + std::to_string(k) + " draw=" + std::to_string(draw) + " scale 10^" + std::to_string(E);
        if (expect_both) {
          EXPECT_TRUE(keep[0] && keep[1]) << what;
        } else if (coincident) {
          EXPECT_TRUE(keep[0] != keep[1]) << what;
        } else {
          const std::size_t slower = cmp(a1v, a2v) <= 0 ? 0 : 1;
          EXPECT_TRUE(keep[slower] && !keep[1 - slower]) << what;
        }
        if (E == 0) {
          decided = keep;
          (expect_both ? both : one) += 1;
          ++cases;
        } else {
          EXPECT_EQ(keep, decided) << what;
        }
      }
    }
  EXPECT_EQ(cases, 11 * 120);
  EXPECT_GT(both, 100);   // both kinds of decision are exercised
  EXPECT_GT(one, 100);
}

// The square of the needle case (simulation_planar_needle_test.cpp) thrown at 600 mm/s past a
// bump d = 10^-k mm wide and high, written in exact decimals (the bump is below a double's
// resolution of its position from k = 16 on). base53 stopped at the first impact for k = 9 ... 14
// and left the square at rest in mid-air from k = 16 on.
std::string needle(int k, bool friction = false) {
  const std::string d = "1e-" + std::to_string(k);
  auto at = [&](const std::string& base, const std::string& times) { return "\"" + base + " + " + times + " * " + d + "\""; };
  const std::string x0 = at("21.8", "-0.4"), x1 = at("21.8", "0.6"), yb = at("47.15448", "-2.3"),
                    yt = at("47.15448", "-1.3");
  return R"({ "hipair": 1, "name": "needle", "units": { "length": "mm", "angle": "rad" },
    "parts": [
      { "name": "bump", "motion": "fixed", "loops": [ { "label": "bump", "start": [)" + x0 + ", " + yb +
         R"(], "edges": [ { "line_to": [)" + x1 + ", " + yb + R"(] }, { "line_to": [)" + x1 + ", " + yt +
         R"(] }, { "line_to": [)" + x0 + ", " + yt + R"(] }, { "line_to": [)" + x0 + ", " + yb + R"(] } ] } ] },
      { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "initial": { "x": 0, "y": 56, "angle": 0 },
        "dynamics": { "mass": 0.008, "moment_of_inertia": 0.1333 },
        "loops": [ { "label": "peg", "start": [-5, -5], "edges": [ { "line_to": [5, -5], "label": "peg bottom" },
          { "line_to": [5, 5] }, { "line_to": [-5, 5] }, { "line_to": [-5, -5] } ] } ] } ],
    "pairs": [ { "parts": ["bump", "peg"], "restitution": 0.5)" +
         std::string(friction ? R"(, "friction": { "static": 0.4, "kinetic": 0.3 })" : "") + R"( } ],
    "simulation": { "units": { "time": "s", "force": "N" }, "gravity": [0, -9810],
      "velocities": { "peg": { "x": 600, "y": 0, "angle": 0 } } } })";
}

TEST(SimulationImpactResolution, ThrowPastBumpsOfEveryHeightRunsThrough) {
  const double t_end = 0.034, g = 9810, m = 0.008;
  // every k around the chord deviation (7e-9 mm) and the doubles' resolution of the bump's place
  // (1e-15 mm), a few beyond (the runs with k <= 8 take ~0.3 s CPU each, the others ~0.1 s)
  for (int k : {0, 4, 8, 9, 10, 11, 12, 13, 14, 15, 16, 20, 25, 30}) {
    SCOPED_TRACE("bump 1e-" + std::to_string(k) + " mm");
    PlanarSimulation sim = PlanarSimulation::create(read_model(needle(k)));
    const double rest = std::sqrt(2 * g * sim.chord_deviation());
    const double e0 = sim.energy();
    ASSERT_NO_THROW(sim.run_until(t_end));
    EXPECT_EQ(sim.state().time, t_end);
    EXPECT_LE(sim.steps(), 2000u);
    // frictionless, e = 1/2: the energy never grows (kinetic + gravity's potential, N mm)
    EXPECT_LE(sim.energy(), e0 * (1 + 1e-9) + m * rest * rest);
    int impacts = 0;
    for (const SimulationEvent& ev : sim.events()) {
      if (ev.kind != SimulationEvent::Kind::impact) continue;
      ++impacts;
      EXPECT_LT(ev.normal_speed_before, 0);
      EXPECT_GT(ev.impulse, 0);
      // Newton at the row of largest impulse: -e times the approach, to the rest speed
      if (-ev.normal_speed_before > rest) EXPECT_NEAR(ev.normal_speed_after, -0.5 * ev.normal_speed_before, rest);
    }
    EXPECT_GE(impacts, 1);
    // the square's centre is 5 mm beside the bump: it cannot rest there
    EXPECT_FALSE(sim.state().resting);
    EXPECT_GT(std::abs(sim.state().vx) + std::abs(sim.state().vy), 1.0);
  }
}

// The same with peg-throw.json's Coulomb friction (0.4 static, 0.3 kinetic): base53 stopped at the
// first impact for k = 9 ... 13 ("a held contact's projected state is not exactly apart", "the
// frictional impact problem has no consistent solution").
TEST(SimulationImpactResolution, FrictionalThrowPastTinyBumpsRunsThrough) {
  const double t_end = 0.034, g = 9810, m = 0.008;
  for (int k : {9, 10, 12, 13, 16, 30}) {
    SCOPED_TRACE("bump 1e-" + std::to_string(k) + " mm");
    PlanarSimulation sim = PlanarSimulation::create(read_model(needle(k, true)));
    const double rest = std::sqrt(2 * g * sim.chord_deviation());
    const double e0 = sim.energy();
    ASSERT_NO_THROW(sim.run_until(t_end));
    EXPECT_EQ(sim.state().time, t_end);
    EXPECT_LE(sim.energy(), e0 * (1 + 1e-9) + m * rest * rest);   // friction and e = 1/2 only dissipate
    EXPECT_FALSE(sim.state().resting);
    EXPECT_GT(std::abs(sim.state().vx) + std::abs(sim.state().vy), 1.0);
  }
}

// A square dropped flat from H onto a platform of two fixed blocks that share an edge: the shared
// top corner is two exactly coincident contacts (one per pair), beside the platform's two outer
// top corners (w = 10^-k mm apart when k > 0: nearly dependent rows as well). Closed forms: the first
// impact at sqrt(2 H / g) with approach g t, the rebound -e times it, x and the angle unchanged,
// and at rest the contact forces sum to m g.
TEST(SimulationImpactResolution, DropOnCoincidentAndNearlyCoincidentCornersBouncesAndRests) {
  const double g = 9810, m = 0.008, H = 1, e = 0.5;
  for (int k : {0, 3, 6, 9, 10, 11, 12, 13, 20, 30}) {
    SCOPED_TRACE("platform half-width 1e-" + std::to_string(k) + " mm");
    const std::string w = "\"1e-" + std::to_string(k) + "\"", mw = "\"-1e-" + std::to_string(k) + "\"";
    auto block = [&](const std::string& name, const std::string& x0, const std::string& x1) {
      return R"({ "name": ")" + name + R"(", "motion": "fixed", "loops": [ { "label": ")" + name + R"(", "start": [)" + x0 +
             R"(, -1], "edges": [ { "line_to": [)" + x1 + R"(, -1] }, { "line_to": [)" + x1 + R"(, 0] }, { "line_to": [)" +
             x0 + R"(, 0] }, { "line_to": [)" + x0 + R"(, -1] } ] } ] })";
    };
    const std::string json = R"({ "hipair": 1, "name": "drop", "units": { "length": "mm", "angle": "rad" },
      "parts": [ )" + block("left", mw, "0") + ", " + block("right", "0", w) + R"(,
        { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "initial": { "x": 0, "y": )" + num(5 + H) +
                             R"(, "angle": 0 },
          "dynamics": { "mass": )" + num(m) + R"(, "moment_of_inertia": 0.1333 },
          "loops": [ { "label": "peg", "start": [-5, -5], "edges": [ { "line_to": [5, -5], "label": "peg bottom" },
            { "line_to": [5, 5] }, { "line_to": [-5, 5] }, { "line_to": [-5, -5] } ] } ] } ],
      "pairs": [ { "parts": ["left", "peg"], "restitution": )" + num(e) + R"( },
                 { "parts": ["right", "peg"], "restitution": )" + num(e) + R"( } ],
      "simulation": { "units": { "time": "s", "force": "N" }, "gravity": [0, )" + num(-g) + R"(] } })";
    PlanarSimulation sim = PlanarSimulation::create(read_model(json));
    const double rest = std::sqrt(2 * g * sim.chord_deviation());
    ASSERT_NO_THROW(sim.run_until(0.3));
    const double t1 = std::sqrt(2 * H / g);
    bool first = true, rested = false;
    double force = 0, rest_time = -1;
    for (const SimulationEvent& ev : sim.events()) {
      if (ev.kind == SimulationEvent::Kind::impact && first) {
        first = false;
        EXPECT_NEAR(ev.time, t1, 1e-9);
        EXPECT_NEAR(ev.normal_speed_before, -g * t1, 1e-6 * g * t1);
        EXPECT_NEAR(ev.normal_speed_after, e * g * t1, 1e-6 * g * t1);
      }
      if (ev.kind == SimulationEvent::Kind::contact && ev.normal_force > 0) {
        if (rest_time < 0) rest_time = ev.time;
        if (ev.time == rest_time) {
          force += ev.normal_force;
          rested = true;
        }
      }
    }
    EXPECT_FALSE(first);
    ASSERT_TRUE(rested);
    EXPECT_NEAR(force, m * g / 1000, 1e-9 * m * g / 1000);   // N: kg mm/s^2 / 1000
    EXPECT_LE(std::abs(sim.state().vx) + std::abs(sim.state().vy) + 5 * std::abs(sim.state().omega), rest);
    EXPECT_NEAR(sim.state().x, 0, 1e-9);
    EXPECT_TRUE(sim.state().resting);
    EXPECT_NEAR(sim.state().y, 5, 1e-6);
  }
}

}  // namespace
}  // namespace hipair
