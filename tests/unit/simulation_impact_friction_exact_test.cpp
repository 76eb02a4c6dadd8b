// The frictional impacts' last decisions in doubles made exact (session 70, exact70):
// held_friction.hpp's fixed_axis_frictional_impulses (the fixed-axis simulator's composition, its
// refusal), exact_assignment beyond 12 contacts (Lemke's algorithm on the states' exact LCP, then
// the exact LP), creates_energy's energy test where the impact creates energy by less than the
// doubles' round-off, and kinetic_exceeds (the comparison on the doubles' x behind a certified
// filter).
//
// The oracle, in the test and in rationals on the same doubles: for a held set H and states
// (stick, slip +-1) of its frictional contacts, the unknowns lambda_H and the sticking frictions
// f_S solve G_H x + h_H = 0 and T_S x = 0 with x = v + M^-1 (sum_H lambda_k W_k + sum_S f_k T_k),
// W_k = G_k - sigma mu_k T_k for a slip; consistent where lambda >= 0, |f| <= mu_s lambda, a slip
// keeps its direction (sigma T x >= 0) and no open gap closes (G_o x + h_o >= 0). An open contact
// imposes nothing tangentially (any tangential speed is a stick's 0 or a slip's direction).
#include <gtest/gtest.h>

#include "simulation/friction.hpp"
#include "simulation/friction_names.hpp"
#include "simulation/held_friction.hpp"
#include "held_oracle_support.hpp"
#include "test_seed.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace hipair {
namespace {

using held_oracle::Rng;
using simulation::held_force_detail::Matrix;

Rational q(double d) { return simulation::held_force_detail::exact_value(d); }

int oracle_undetermined = 0;   // held sets whose velocities after the oracle found not unique

struct Impact {
  Eigen::MatrixXd G;
  Eigen::VectorXd minv, v;
  std::vector<Rational> h;   // the exact velocity terms of the normal rows
  std::vector<simulation::Friction> friction;
  Eigen::MatrixXd M;           // given (not empty): a full mass matrix in place of minv
  std::vector<Rational> bias;  // given: the tangent rows' constants (T x + bias), by contact
};

// the exact velocities after for held set `held` at states `state` (per contact; frictionless:
// no tangential unknown), none where the system is singular or a condition fails
std::optional<std::vector<Rational>> oracle_x(const Impact& p, const std::vector<bool>& held,
                                              const std::vector<int>& state) {
  const auto m = static_cast<std::size_t>(p.G.rows()), n = static_cast<std::size_t>(p.G.cols());
  struct Unknown {
    std::size_t contact;
    bool tangent;
  };
  std::vector<Unknown> unknowns;
  for (std::size_t k = 0; k < m; ++k)
    if (held[k]) unknowns.push_back({k, false});
  for (std::size_t k = 0; k < m; ++k)
    if (held[k] && p.friction[k].on && state[k] == simulation::stick) unknowns.push_back({k, true});
  auto row_of = [&](std::size_t k, bool tangent) {
    std::vector<Rational> r(n);
    for (std::size_t i = 0; i < n; ++i)
      r[i] = tangent ? q(p.friction[k].T(Eigen::Index(i))) : q(p.G(Eigen::Index(k), Eigen::Index(i)));
    return r;
  };
  // each unknown's direction M^-1 (force row)
  std::vector<std::vector<Rational>> direction;
  for (const Unknown& u : unknowns) {
    std::vector<Rational> d = row_of(u.contact, u.tangent);
    const simulation::Friction& c = p.friction[u.contact];
    const int st = state[u.contact];
    if (!u.tangent && c.on && (st == simulation::slip_positive || st == simulation::slip_negative)) {
      const std::vector<Rational> t = row_of(u.contact, true);
      for (std::size_t i = 0; i < n; ++i) d[i] -= st * q(c.mu_kinetic) * t[i];
    }
    if (p.M.size() == 0) {
      for (std::size_t i = 0; i < n; ++i) d[i] *= q(p.minv(Eigen::Index(i)));
    } else {   // M^-1 d exactly
      Matrix<Rational> mass(n, std::vector<Rational>(n)), rhs(n, std::vector<Rational>(1));
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) mass[i][j] = q(p.M(Eigen::Index(i), Eigen::Index(j)));
        rhs[i][0] = d[i];
      }
      const auto solved = simulation::held_force_detail::solve(std::move(mass), std::move(rhs));
      for (std::size_t i = 0; i < n; ++i) d[i] = (*solved)[i][0];
    }
    direction.push_back(d);
  }
  auto dot = [](const std::vector<Rational>& a, const std::vector<Rational>& b) {
    Rational s = 0;
    for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
    return s;
  };
  std::vector<Rational> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = q(p.v(Eigen::Index(i)));
  auto tangent_constant = [&](std::size_t k) { return p.bias.empty() ? Rational(0) : p.bias[k]; };
  const std::size_t u = unknowns.size();
  Matrix<Rational> E(u, std::vector<Rational>(u + 1));   // [E | rhs]
  for (std::size_t r = 0; r < u; ++r) {   // the equation of unknown r's contact (gap or tangent)
    const std::vector<Rational> row = row_of(unknowns[r].contact, unknowns[r].tangent);
    for (std::size_t j = 0; j < u; ++j) E[r][j] = dot(row, direction[j]);
    E[r][u] = -dot(row, v) - (unknowns[r].tangent ? tangent_constant(unknowns[r].contact) : p.h[unknowns[r].contact]);
  }
  // (session 71, exact71: the system may be singular — two sticking contacts of a plastic impact
  // over 2 coordinates stop the part, x = 0, with the multipliers left open (the session-61 cusp):
  // until then the oracle skipped every singular held set, so such a consistent solution, which
  // full_form_impulses finds first (the largest held set first), matched none of its solutions.)
  // z = z0 + N t: the equations' solutions by reduced row echelon form in rationals
  std::vector<std::size_t> pivot_of_row;
  std::vector<bool> is_pivot(u, false);
  for (std::size_t col = 0, row = 0; col < u && row < u; ++col) {
    std::size_t r = row;
    while (r < u && sgn(E[r][col]) == 0) ++r;
    if (r == u) continue;
    std::swap(E[r], E[row]);
    const Rational pivot = E[row][col];
    for (Rational& e : E[row]) e /= pivot;
    for (std::size_t o = 0; o < u; ++o)
      if (o != row && sgn(E[o][col]) != 0) {
        const Rational factor = E[o][col];
        for (std::size_t j = 0; j <= u; ++j) E[o][j] -= factor * E[row][j];
      }
    pivot_of_row.push_back(col);
    is_pivot[col] = true;
    ++row;
  }
  for (std::size_t r = pivot_of_row.size(); r < u; ++r)
    if (sgn(E[r][u]) != 0) return std::nullopt;   // inconsistent equations
  std::vector<std::size_t> free_columns;
  for (std::size_t j = 0; j < u; ++j)
    if (!is_pivot[j]) free_columns.push_back(j);
  const std::size_t d = free_columns.size();
  // z_j = zc[j] + sum_f zn[j][f] t_f
  std::vector<Rational> zc(u);
  std::vector<std::vector<Rational>> zn(u, std::vector<Rational>(d));
  for (std::size_t f = 0; f < d; ++f) zn[free_columns[f]][f] = 1;
  for (std::size_t r = 0; r < pivot_of_row.size(); ++r) {
    zc[pivot_of_row[r]] = E[r][u];
    for (std::size_t f = 0; f < d; ++f) zn[pivot_of_row[r]][f] = -E[r][free_columns[f]];
  }
  // x = xc + sum_f xn[f] t_f; the oracle publishes x only where it is unique (xn = 0)
  std::vector<Rational> x = v;
  for (std::size_t j = 0; j < u; ++j)
    for (std::size_t i = 0; i < n; ++i) x[i] += zc[j] * direction[j][i];
  for (std::size_t f = 0; f < d; ++f)
    for (std::size_t i = 0; i < n; ++i) {
      Rational xn = 0;
      for (std::size_t j = 0; j < u; ++j) xn += zn[j][f] * direction[j][i];
      if (sgn(xn) != 0) {
        ++oracle_undetermined;   // (the test asserts none: every plant's x is unique)
        return std::nullopt;
      }
    }
  // the conditions as inequalities a . t + b >= 0 (with x fixed, those on x are constants)
  struct Inequality {
    std::vector<Rational> a;
    Rational b;
  };
  std::vector<Inequality> conditions;
  auto on_z = [&](const std::vector<Rational>& c) {   // c . z as a . t + b
    Inequality q{std::vector<Rational>(d), Rational(0)};
    for (std::size_t j = 0; j < u; ++j) {
      if (sgn(c[j]) == 0) continue;
      q.b += c[j] * zc[j];
      for (std::size_t f = 0; f < d; ++f) q.a[f] += c[j] * zn[j][f];
    }
    conditions.push_back(q);
  };
  for (std::size_t j = 0; j < u; ++j) {
    std::vector<Rational> c(u);
    if (!unknowns[j].tangent) {   // lambda >= 0
      c[j] = 1;
      on_z(c);
      continue;
    }
    std::size_t normal = u;   // mu_s lambda -+ f >= 0
    for (std::size_t i = 0; i < u; ++i)
      if (unknowns[i].contact == unknowns[j].contact && !unknowns[i].tangent) normal = i;
    for (int side : {1, -1}) {
      c.assign(u, Rational(0));
      c[normal] = q(p.friction[unknowns[j].contact].mu_static);
      c[j] = -side;
      on_z(c);
    }
  }
  for (std::size_t k = 0; k < m; ++k) {
    const simulation::Friction& c = p.friction[k];
    const int st = state[k];
    if (!held[k] && dot(row_of(k, false), x) + p.h[k] < 0) return std::nullopt;
    if (held[k] && c.on && (st == simulation::slip_positive || st == simulation::slip_negative) &&
        st * (dot(row_of(k, true), x) + tangent_constant(k)) < 0)
      return std::nullopt;
  }
  // feasibility of the t-system by Fourier-Motzkin elimination (d <= 2 here)
  for (std::size_t f = d; f-- > 0;) {
    std::vector<Inequality> next, lower, upper;
    for (Inequality& c : conditions) {
      const int sign = sgn(c.a[f]);
      (sign == 0 ? next : sign > 0 ? lower : upper).push_back(c);
    }
    for (const Inequality& lo : lower)     // t_f >= -(b + a' t') / a_f
      for (const Inequality& hi : upper) { // t_f <= (b + a' t') / -a_f
        Inequality c{std::vector<Rational>(d), lo.b * -hi.a[f] + hi.b * lo.a[f]};
        for (std::size_t g = 0; g < f; ++g) c.a[g] = lo.a[g] * -hi.a[f] + hi.a[g] * lo.a[f];
        next.push_back(std::move(c));
      }
    conditions = std::move(next);
  }
  for (const Inequality& c : conditions)
    if (sgn(c.b) < 0) return std::nullopt;
  return x;
}

// every consistent (held set, states) of a small impact (m <= 2): its exact velocities after
std::vector<std::vector<Rational>> oracle_all(const Impact& p) {
  const auto m = static_cast<std::size_t>(p.G.rows());
  std::vector<std::vector<Rational>> out;
  for (std::size_t code = 0; code < (std::size_t{1} << m); ++code) {
    std::vector<bool> held(m);
    for (std::size_t k = 0; k < m; ++k) held[k] = (code >> k) & 1;
    std::size_t combinations = 1;
    for (std::size_t k = 0; k < m; ++k) combinations *= 3;
    for (std::size_t s = 0; s < combinations; ++s) {
      std::vector<int> state(m);
      std::size_t rest = s;
      for (std::size_t k = 0; k < m; ++k, rest /= 3) {
        static constexpr int digit[3] = {simulation::stick, simulation::slip_positive, simulation::slip_negative};
        state[k] = p.friction[k].on ? digit[rest % 3] : simulation::frictionless;
      }
      if (auto x = oracle_x(p, held, state)) out.push_back(*x);
    }
  }
  return out;
}

simulation::Friction coulomb(const Eigen::VectorXd& T, double mu_s, double mu_k) {
  simulation::Friction f;
  f.on = true;
  f.T = T;
  f.mu_static = mu_s;
  f.mu_kinetic = mu_k;
  return f;
}

// A Painleve-type frictional impact exactly without a consistent stick/slip solution, at the
// function level: one contact over two coordinates whose normal and tangent rows couple,
// K = [G; T] M^-1 [G; T]^T = [[a, b], [b, c]] with b > 0, the tangential speed T v >= 0, and
// mu_k > a / b > b / c > mu_s: the slip that would stop the tangential motion has a negative
// effective mass (a - mu_k b < 0: no impulse >= 0), the other slip reverses the tangential speed,
// and sticking needs |f| = (b d + a T v) / det > mu_s lambda = mu_s (c d + b T v) / det. (A model
// cannot give it: the reader requires mu_k <= mu_s, and then one contact always has a consistent
// solution — a stick when b <= mu_s c, else the slip against b, whose effective mass a + mu_k b and
// whose tangential speed after are then of the right signs.) Two such contacts on separate
// coordinates (pairs 0 and 1): the fixed-axis composition refuses the impact, and the simulator's
// message names both pairs.
// (session 72, jam72; review71 exact71 M1) The planar simulators' frictional impact
// (limited_frictional_impulses, planar.cpp's frictional_impact) on impact `p` with restitutions
// `e`: where it finds no solution its `unsolved` callback is called with the unsolved solution,
// whose `exhausted` must be `complete` (the exact search complete: 2 contacts; not: 9 frictional),
// and the planar refusal's words (friction_names.hpp's frictional_refusal) a verdict only then.
// Until session 72 the callback took no argument and the planar words were always "has no
// consistent solution (a Painlevé-type inconsistency of Coulomb friction, or more than 8
// contacts)". Returns whether it refused.
bool planar_refusal(const Impact& p, const Eigen::VectorXd& e, bool complete, int trial) {
  const Eigen::Index m = p.G.rows();
  Eigen::VectorXd h(m);
  const Eigen::VectorXd gv = p.G * p.v;
  for (Eigen::Index k = 0; k < m; ++k) h(k) = (1 + e(k)) * gv(k) - gv(k);
  const std::vector<Rational> h_exact = simulation::exact_restitution_terms(p.G, p.v, e, false);
  std::vector<std::size_t> group(static_cast<std::size_t>(m));
  for (std::size_t k = 0; k < group.size(); ++k) group[k] = k;
  bool limited = false;
  std::optional<bool> exhausted;
  const simulation::FrictionalSolution s = simulation::limited_frictional_impulses(
      p.G, p.minv, p.v, h, p.friction, group, {}, &h_exact, limited,
      [&](const simulation::FrictionalSolution& unsolved) { exhausted = unsolved.exhausted; });
  if (s.solved) {
    EXPECT_FALSE(complete) << trial << ": the planar composition solved an impact that has no solution";
    return false;
  }
  EXPECT_TRUE(exhausted.has_value()) << trial << ": no unsolved callback";
  if (!exhausted) return true;
  EXPECT_EQ(*exhausted, complete) << trial;
  const std::string words = simulation::frictional_refusal("the frictional impact problem", *exhausted);
  EXPECT_EQ(words, complete ? "the frictional impact problem has no consistent solution (a Painlevé-type inconsistency "
                              "of Coulomb friction)"
                            : "no consistent solution was found for the frictional impact problem (the search is "
                              "complete only up to 12 contacts with at most 8 of them frictional: this is not a proof "
                              "that none exists)")
      << trial;
  return true;
}

TEST(FixedAxisFrictionalImpact, AnInconsistentImpactIsRefusedNamingItsPairs) {
  Rng rng{test::test_seed(7001)};
  Model model;
  for (const char* name : {"wheel", "pawl", "frame"}) {
    Part part;
    part.name = name;
    part.pointer = std::string("/parts/") + std::to_string(model.parts.size());
    model.parts.push_back(part);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    PairSpec pair;
    pair.first = i;
    pair.second = 2;
    pair.pointer = "/pairs/" + std::to_string(i);
    pair.friction = Rational(1, 10);
    pair.kinetic_friction = Rational(3, 1);
    model.pairs.push_back(pair);
  }
  int refused = 0;
  // (session 71, exact71: 400 trials, until then 200 — the plant holds in about 1 in 9, and at
  // seed 4 only 14 of 200 were planted, below the count asserted)
  for (int trial = 0; trial < 400; ++trial) {
    Impact p;
    p.G = Eigen::MatrixXd::Zero(2, 4);
    p.minv.resize(4);
    p.v.resize(4);
    p.friction.resize(2);
    Eigen::VectorXd e(2);
    for (Eigen::Index k = 0; k < 2; ++k) {
      const Eigen::Index c = 2 * k;
      const double g0 = rng.uniform(0.2, 1), g1 = rng.uniform(-1, 1), t0 = rng.uniform(-1, 1), t1 = rng.uniform(0.2, 1);
      p.G(k, c) = g0;
      p.G(k, c + 1) = g1;
      p.minv(c) = rng.uniform(0.3, 3);
      p.minv(c + 1) = rng.uniform(0.3, 3);
      Eigen::VectorXd T = Eigen::VectorXd::Zero(4);
      T(c) = t0;
      T(c + 1) = t1;
      const double a = g0 * g0 * p.minv(c) + g1 * g1 * p.minv(c + 1);
      double b = g0 * t0 * p.minv(c) + g1 * t1 * p.minv(c + 1);
      if (b < 0) {   // b > 0: the tangent row's sign
        T = -T;
        b = -b;
      }
      const double cc = T(c) * T(c) * p.minv(c) + T(c + 1) * T(c + 1) * p.minv(c + 1);
      // mu_s below b / c, mu_k above a / b (margins far beyond the doubles' rounding)
      p.friction[std::size_t(k)] = coulomb(T, 0.5 * b / cc, 2 * a / std::max(b, 1e-3));
      // approaching (G v < 0) with T v >= 0: v = -alpha G^T + beta (component along T)
      const double alpha = rng.uniform(0.5, 2), beta = rng.uniform(0, 1);
      p.v(c) = -alpha * g0 + beta * T(c);
      p.v(c + 1) = -alpha * g1 + beta * T(c + 1);
      e(k) = rng.uniform(0, 1);
    }
    // the plant, checked by the oracle: G v < 0, T v >= 0 and no consistent (held set, states)
    p.h = simulation::exact_restitution_terms(p.G, p.v, e);
    bool planted = true;
    for (Eigen::Index k = 0; k < 2 && planted; ++k) {
      Rational gv = 0, tv = 0;
      for (Eigen::Index i = 0; i < 4; ++i) {
        gv += q(p.G(k, i)) * q(p.v(i));
        tv += q(p.friction[std::size_t(k)].T(i)) * q(p.v(i));
      }
      planted = sgn(gv) < 0 && sgn(tv) >= 0;
    }
    if (!planted || !oracle_all(p).empty()) continue;
    ++refused;
    const simulation::FrictionalSolution s =
        simulation::fixed_axis_frictional_impulses(p.G, p.minv, p.v, e, p.friction);
    EXPECT_FALSE(s.solved) << trial;
    EXPECT_TRUE(s.exhausted) << trial << ": 2 contacts, the exact search is complete";
    const std::string message = simulation::inconsistent_frictional_impact("0.25 s", 2, model, {0, 1, 0}, s.exhausted);
    EXPECT_EQ(message,
              "simulation: at t = 0.25 s the impact problem of 2 simultaneous contacts with Coulomb friction has no "
              "consistent stick/slip solution; pairs involved: (wheel /parts/0, frame /parts/2) (/pairs/0, friction "
              "0.1, kinetic 3); (pawl /parts/1, frame /parts/2) (/pairs/1, friction 0.1, kinetic 3)");
    // (session 72, jam72; review71 exact71 M1) the planar simulators' composition on the same
    // impact (every row its restitution term, b = (1 + e) J v): its `unsolved` callback gets the
    // unsolved solution, exhausted (2 contacts), and the planar refusal reads as a verdict
    planar_refusal(p, e, true, trial);
  }
  std::cout << "inconsistent frictional impacts refused: " << refused << " of 400\n";
  EXPECT_GE(refused, 20);
}

// More than 8 frictional contacts (session 71, exact71; review70 M1): solve_frictional tries no
// stick/slip assignment there (at most 3^8), so the fixed-axis composition finds none — but one
// exists: 9 frictional contacts (rows 9 to 12, the rest frictionless), each on its own 2
// coordinates, mu_k <= mu_s, so the impact splits into one-contact impacts, each of which the
// oracle solves (a one-contact impact with mu_k <= mu_s always has a consistent solution). The
// refusal must not read as a verdict: `exhausted` false, and the message says none was found and
// that this is no proof (until session 71 "has no consistent stick/slip solution").
TEST(FixedAxisFrictionalImpact, NineFrictionalContactsAreRefusedWithoutAVerdict) {
  Rng rng{test::test_seed(7007)};
  Model model;
  for (const char* name : {"wheel", "frame"}) {
    Part part;
    part.name = name;
    part.pointer = std::string("/parts/") + std::to_string(model.parts.size());
    model.parts.push_back(part);
  }
  PairSpec pair;
  pair.first = 0;
  pair.second = 1;
  pair.pointer = "/pairs/0";
  pair.friction = Rational(1, 2);
  model.pairs.push_back(pair);
  int cases = 0, planar_refusals = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Eigen::Index m = 9 + trial % 4, n = 2 * m;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m, n);
    Eigen::VectorXd minv(n), v(n), e(m);
    std::vector<simulation::Friction> friction(static_cast<std::size_t>(m));
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index c = 2 * k;
      Impact one;   // the contact on its own two coordinates, for the oracle
      one.G.resize(1, 2);
      one.minv.resize(2);
      one.v.resize(2);
      Eigen::VectorXd T = Eigen::VectorXd::Zero(n), t(2);
      for (Eigen::Index i = 0; i < 2; ++i) {
        G(k, c + i) = one.G(0, i) = rng.uniform(-1, 1);
        minv(c + i) = one.minv(i) = rng.uniform(0.3, 3);
        v(c + i) = one.v(i) = rng.uniform(-2, 2);
        T(c + i) = t(i) = rng.uniform(-1, 1);
      }
      e(k) = rng.uniform(0, 1);
      const double mu_s = rng.uniform(0.05, 1.5), mu_k = mu_s * rng.uniform(0.3, 1);
      if (k < 9) {
        friction[std::size_t(k)] = coulomb(T, mu_s, mu_k);
        one.friction.push_back(coulomb(t, mu_s, mu_k));
      } else {
        one.friction.resize(1);
      }
      one.h = simulation::exact_restitution_terms(one.G, one.v, e.segment(k, 1));
      ASSERT_FALSE(oracle_all(one).empty()) << trial << " contact " << k << ": the plant";
    }
    ++cases;
    {   // (session 72, jam72) the planar composition on the same impact: a refusal, no verdict
      Impact all;
      all.G = G;
      all.minv = minv;
      all.v = v;
      all.friction = friction;
      planar_refusals += planar_refusal(all, e, false, trial);
    }
    const simulation::FrictionalSolution s = simulation::fixed_axis_frictional_impulses(G, minv, v, e, friction);
    // the contract, not today's limit: a solution found is fine (the plant exists); a refusal
    // must not claim that the search was complete
    if (s.solved) continue;
    EXPECT_FALSE(s.exhausted) << trial << ": " << m << " contacts, 9 frictional: the search was not complete";
    const std::string message =
        simulation::inconsistent_frictional_impact("0.5 s", std::size_t(m), model, {0}, s.exhausted);
    EXPECT_EQ(message, "simulation: at t = 0.5 s no consistent stick/slip solution was found for the impact problem "
                       "of " + std::to_string(m) + " simultaneous contacts with Coulomb friction (the search is "
                       "complete only up to 12 contacts with at most 8 of them frictional: this is not a proof that "
                       "none exists); pairs involved: (wheel /parts/0, frame /parts/1) (/pairs/0, friction 0.5)")
        << trial;
  }
  EXPECT_EQ(cases, 12);
  EXPECT_EQ(planar_refusals, 12);   // (nothing is tried beyond 8 frictional contacts: every one refused)
}

// Generated fixed-axis impacts (1 contact over 3 coordinates or 2 over 5, one sometimes driven;
// mu_k <= mu_s): solved exactly when the oracle's enumeration finds a consistent
// (held set, states), and its velocities after are one of those solutions'.
TEST(FixedAxisFrictionalImpact, GeneratedImpactsAgreeWithTheExactEnumeration) {
  Rng rng{test::test_seed(7002)};
  oracle_undetermined = 0;
  int solved = 0, cases = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Index m = 1 + trial % 2, n = 2 * m + 1;   // (two sticking contacts: 4 rows on 5 coordinates)
    Impact p;
    p.G.resize(m, n);
    p.minv.resize(n);
    p.v.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      p.minv(i) = rng.uniform(0.3, 3);
      p.v(i) = rng.uniform(-2, 2);
    }
    if (trial % 5 == 0) p.minv(n - 1) = 0;   // a driven coordinate
    Eigen::VectorXd e(m);
    for (Eigen::Index k = 0; k < m; ++k) {
      Eigen::VectorXd T(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        p.G(k, i) = rng.uniform(-1, 1);
        T(i) = rng.uniform(-1, 1);
      }
      const double mu_s = rng.uniform(0, 1.5);
      p.friction.push_back(coulomb(T, mu_s, mu_s * rng.uniform(0.3, 1)));
      e(k) = trial % 3 == 0 ? 0.0 : rng.uniform(0, 1);
    }
    p.h = simulation::exact_restitution_terms(p.G, p.v, e);
    ++cases;
    const std::vector<std::vector<Rational>> all = oracle_all(p);
    const simulation::FrictionalSolution s = simulation::fixed_axis_frictional_impulses(p.G, p.minv, p.v, e, p.friction);
    ASSERT_EQ(s.solved, !all.empty()) << trial;
    if (!s.solved) continue;
    ++solved;
    double reach = p.v.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < n; ++i) reach = std::max(reach, std::abs(s.x(i)));
    bool matched = false;
    for (const std::vector<Rational>& x : all) {
      bool same = true;
      for (Eigen::Index i = 0; i < n && same; ++i)
        same = std::abs(s.x(i) - to_double(x[std::size_t(i)])) <= 0x1p-36 * reach;
      matched = matched || same;
    }
    EXPECT_TRUE(matched) << trial << ": the velocities after are no consistent solution's";
  }
  std::cout << "generated fixed-axis frictional impacts: " << cases << ", solved " << solved << "\n";
  EXPECT_GE(solved, cases * 9 / 10);
  EXPECT_EQ(oracle_undetermined, 0) << "a held set whose velocities after are not unique: the oracle cannot decide";
}

// Beyond 12 contacts (the exact enumeration's bound): one frictional contact over 3 coordinates
// (random rows, mu_k <= mu_s) and 12 frictionless ones on 12 more coordinates, each separating by
// 2^-50 — inside the doubles' LCP tolerance, so the doubles hold them, while exactly each would
// need a negative impulse. Until session 70 every assignment the doubles' filter rejected was left
// undecided there (exact_assignment's bound) and the fixed-axis simulator fell back to the
// doubles' session-36 rule; now the exact LCP (Lemke) finds the held set, and the published
// solution is exactly consistent: the oracle's, on its held set (w = 0) and states, rounded.
TEST(FixedAxisFrictionalImpact, BeyondTwelveContactsTheSolutionIsExactlyConsistent) {
  Rng rng{test::test_seed(7006)};
  int cases = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Index m = 13, n = 15;
    Impact p;
    p.G = Eigen::MatrixXd::Zero(m, n);
    p.minv.resize(n);
    p.v = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i) p.minv(i) = rng.uniform(0.3, 3);
    Eigen::VectorXd T = Eigen::VectorXd::Zero(n), e = Eigen::VectorXd::Zero(m);
    for (Eigen::Index i = 0; i < 3; ++i) {
      p.G(0, i) = rng.uniform(-1, 1);
      T(i) = rng.uniform(-1, 1);
      p.v(i) = rng.uniform(-2, 2);
    }
    e(0) = rng.uniform(0, 1);
    const double mu_s = rng.uniform(0.05, 1.5);
    p.friction.assign(static_cast<std::size_t>(m), simulation::Friction{});
    p.friction[0] = coulomb(T, mu_s, mu_s * rng.uniform(0.3, 1));
    for (Eigen::Index k = 1; k < m; ++k) {
      p.G(k, 2 + k) = 1;
      p.v(2 + k) = 0x1p-50;
      e(k) = 0.5;
    }
    p.h = simulation::exact_restitution_terms(p.G, p.v, e);
    ++cases;
    const simulation::FrictionalSolution s = simulation::fixed_axis_frictional_impulses(p.G, p.minv, p.v, e, p.friction);
    ASSERT_TRUE(s.solved) << trial;
    ASSERT_EQ(s.x_exact.size(), std::size_t(n)) << trial;   // an exact decision's solution
    std::vector<bool> held(static_cast<std::size_t>(m));
    for (Eigen::Index k = 0; k < m; ++k) held[std::size_t(k)] = s.w(k) == 0;
    for (Eigen::Index k = 1; k < m; ++k) EXPECT_FALSE(held[std::size_t(k)]) << trial << " contact " << k;
    const std::optional<std::vector<Rational>> x = oracle_x(p, held, s.state);
    ASSERT_TRUE(x) << trial << ": the published held set and states are not exactly consistent";
    for (Eigen::Index i = 0; i < n; ++i) EXPECT_EQ(s.x(i), to_double((*x)[std::size_t(i)])) << trial << " " << i;
  }
  EXPECT_EQ(cases, 40);
}

// A coupled frictional impact that creates energy by less than the round-off. One contact at a
// corner of a turning part (3 coordinates: x, y, theta), normal and tangent rows coupled
// (K = [J; T] M^-1 [J; T]^T with b = J M^-1 T^T != 0), J v = -2^k (so e J v is exact), a small
// tangential speed of the sign that makes a stick create energy at e = 1; mu_s large (the stick
// consistent). The stick's energy change, exactly, 1/2 (u+^T K^-1 u+ - u^T K^-1 u) with u = [J v,
// T v] and u+ = [-e J v, 0], is 0 at an irrational e*: e is the double just above it (created by
// about 2^-52 of the energy) and the double just below (none created). `extra` adds 12 frictionless
// contacts on 12 more coordinates, each separating by 2^-50 (inside the doubles' LCP tolerance, so
// the doubles hold them; exactly each would need a negative impulse): 13 contacts, beyond the
// exact enumeration's 12 — the exact LCP (Lemke) finds their held set.
struct CoupledImpact {
  Impact p;
  Eigen::VectorXd e;
  Eigen::VectorXd h;
  Rational created;   // the energy change x M x - v M v, exactly (the oracle's stick)
};

std::optional<CoupledImpact> coupled_impact(Rng& rng, bool extra, bool above) {
  const Eigen::Index m = extra ? 13 : 1, n = extra ? 15 : 3;
  CoupledImpact c;
  Impact& p = c.p;
  p.G = Eigen::MatrixXd::Zero(m, n);
  p.minv = Eigen::VectorXd::Zero(n);
  p.v = Eigen::VectorXd::Zero(n);
  const double mass = rng.uniform(0.5, 2), inertia = rng.uniform(0.1, 1);
  p.minv.head(3) << 1 / mass, 1 / mass, 1 / inertia;
  const double rx = rng.uniform(-1, 1), ry = rng.uniform(-1, 1);   // the corner from the centre
  // n = (0, 1), t = (-1, 0): J = (0, 1, rx), T = (-1, 0, ry) (gap and tangential speed rates)
  Eigen::VectorXd T = Eigen::VectorXd::Zero(n);
  p.G(0, 1) = 1;
  p.G(0, 2) = rx;
  T(0) = -1;
  T(2) = ry;
  // v: J v = -2^k exactly (vy = -2^k - rx w with w = 0), a tangential speed vx of either sign
  const double jv = -std::ldexp(1.0, rng.below(4) - 1);
  p.v(1) = jv;
  p.v(0) = std::ldexp(std::round(rng.uniform(-64, 64)), -9);
  // the 2 x 2 K exactly and e* in doubles: e*^2 = (u^T K^-1 u) / (J v^2 (K^-1)_00)
  const Rational a = q(p.minv(1)) + q(rx) * q(rx) * q(p.minv(2)), b = q(rx) * q(ry) * q(p.minv(2)),
                 cc = q(p.minv(0)) + q(ry) * q(ry) * q(p.minv(2));
  const Rational det = a * cc - b * b;
  const Rational ia = cc / det, ib = -b / det, ic = a / det;   // K^-1
  const Rational u0 = q(jv), u1 = -q(p.v(0));                  // T v = -vx
  const Rational before = ia * u0 * u0 + 2 * ib * u0 * u1 + ic * u1 * u1;
  const double e2 = to_double(before / (ia * u0 * u0));
  if (!(e2 > 0.01 && e2 < 0.98)) return std::nullopt;
  auto change = [&](double e) -> Rational {   // 2 x the stick's energy change, exactly (a Rational:
    // the GMP expression would hold the local `up` beyond its life)
    const Rational up = -q(e) * u0;
    return ia * up * up - before;
  };
  double e = std::sqrt(e2);
  while (sgn(change(e)) > 0) e = std::nextafter(e, 0.0);
  while (sgn(change(e)) <= 0) e = std::nextafter(e, 2.0);   // the least double creating energy
  if (!above) e = std::nextafter(e, 0.0);
  // the stick consistent: lambda >= 0 and |f| <= mu_s lambda for P = K^-1 (u+ - u)
  const Rational d0 = -q(e) * u0 - u0, d1 = -u1;
  const Rational lambda = ia * d0 + ib * d1, f = ib * d0 + ic * d1;
  if (sgn(lambda) <= 0) return std::nullopt;
  const double mu = 1.5 * to_double(abs(f) / lambda) + 0.1;
  p.friction.assign(static_cast<std::size_t>(m), simulation::Friction{});
  p.friction[0] = coulomb(T, mu, mu);
  c.e = Eigen::VectorXd::Constant(m, e);
  c.h = Eigen::VectorXd::Zero(m);
  c.h(0) = (1 + e) * jv - jv;   // the planar simulators' rounded b - J v
  if (extra)
    for (Eigen::Index k = 1; k < m; ++k) {
      p.G(k, 2 + k) = 1;
      p.minv(2 + k) = rng.uniform(0.5, 2);
      p.v(2 + k) = 0x1p-50;   // separating slowly
      c.e(k) = 0.5;
      c.h(k) = 0.5 * 0x1p-50;
    }
  p.h = simulation::exact_restitution_terms(p.G, p.v, c.e, false);
  c.created = change(e);
  return c;
}

TEST(ImpactEnergy, EnergyCreatedBelowTheRoundOffIsCaught) {
  Rng rng{test::test_seed(7003)};
  int cases = 0, creating = 0, old_missed = 0, extra_cases = 0;
  for (int trial = 0; trial < 600; ++trial) {
    // (session 71, exact71: the 13-contact rows — each a restitution limit's bisection of up to 30
    // exact LCPs on 13 contacts — cut from half the trials to 60 of 600, 30 creating and 30 not:
    // the test ran beyond 60 s; 600 trials, 240 before, since about 1 in 5 plants holds)
    const bool extra = trial % 40 >= 36, above = trial % 2 == 0;
    const std::optional<CoupledImpact> c = coupled_impact(rng, extra, above);
    if (!c) continue;
    ++cases;
    extra_cases += extra;
    const Impact& p = c->p;
    std::vector<std::size_t> own(p.friction.size());
    for (std::size_t k = 0; k < own.size(); ++k) own[k] = k;
    const simulation::FrictionalSolution full =
        simulation::frictional_impulses(p.G, p.minv, p.v, c->h, p.friction, own, {}, &p.h);
    ASSERT_TRUE(full.solved) << trial << (extra ? " (13 contacts)" : "");
    ASSERT_EQ(full.state[0], simulation::stick) << trial;
    // the oracle's velocities after (the stick, the extra contacts open)
    std::vector<bool> held(p.friction.size(), false);
    held[0] = true;
    std::vector<int> state(p.friction.size(), simulation::frictionless);
    state[0] = simulation::stick;
    const std::optional<std::vector<Rational>> x = oracle_x(p, held, state);
    ASSERT_TRUE(x) << trial;
    double reach = p.v.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < p.v.size(); ++i) {
      reach = std::max(reach, std::abs(to_double((*x)[std::size_t(i)])));
      EXPECT_NEAR(full.x(i), to_double((*x)[std::size_t(i)]), 0x1p-44 * reach) << trial << " coordinate " << i;
    }
    const bool creates = sgn(c->created) > 0;
    ASSERT_EQ(creates, above) << trial;   // the plant
    creating += creates;
    EXPECT_EQ(simulation::creates_energy(p.G, p.minv, p.v, c->h, p.friction, own, full, &p.h), creates) << trial;
    bool limited = !creates;
    double scale = -1;
    const simulation::FrictionalSolution sol = simulation::limited_frictional_impulses(
        p.G, p.minv, p.v, c->h, p.friction, own, {}, &p.h, limited, {}, &scale);
    ASSERT_TRUE(sol.solved) << trial;
    EXPECT_EQ(limited, creates) << trial;
    if (creates) EXPECT_LT(scale, 1.0) << trial;
    else EXPECT_EQ(scale, 1.0) << trial;
    // the rounded test (before session 69) on the published x: where it reads no energy created
    auto kinetic = [&](const Eigen::VectorXd& u) {
      return 0.5 * (p.minv.array() > 0).select(u.array().square() / p.minv.array(), 0.0).sum();
    };
    old_missed += creates && !(kinetic(full.x) > kinetic(p.v));
  }
  std::cout << "coupled impacts at the energy's tie: " << cases << " (" << creating << " creating by about 2^-52 "
            << "of the energy; " << extra_cases << " with 13 contacts); the rounded test read " << old_missed
            << " of those as creating none\n";
  EXPECT_GE(cases, 100);
  EXPECT_GE(extra_cases, 6);
  if (std::getenv("HIPAIR_TEST_SEED") == nullptr) EXPECT_GT(old_missed, 0) << "the plant should reach the rounded test's error";
}

// The pin-slot simulator's Coulomb impacts on the full form (held_friction.hpp's
// full_form_impulses and kinetic_grows, as pin_slot_simulation.cpp composes them): coordinates
// (s, psi) or (s, psi, x) with M = [[m, m c, 0], [m c, m c^2 + I, 0], [0, 0, m_x]] (the pin-slot
// part's coupling), 1 or 2 contacts with rows G and tangent rows T over them, a driver's normal
// and tangential speeds sometimes; the doubles solved as the simulator does on the rows of M's
// Cholesky factor (G L^-T, L^-1 T, L^T q'-). The oracle: every consistent (held set, states) on
// M itself in rationals; the published solution's exact change is one of them, exactly, and the
// energy test is the oracle's. Counted: the velocities after that the Cholesky solution gave
// (L^-T x, the call before session 70) against the exact ones rounded.
TEST(FullFormImpact, PinSlotCoulombImpactsAreDecidedOnTheMassMatrix) {
  Rng rng{test::test_seed(7005)};
  oracle_undetermined = 0;
  int cases = 0, solved = 0, rounded_differs = 0, energy_checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Index n = 2 + trial % 2, m = 1 + (trial / 2) % 2;
    Impact p;
    const double mass = rng.uniform(0.5, 2), c = rng.uniform(-2, 2), inertia = rng.uniform(0.05, 1);
    p.M = Eigen::MatrixXd::Zero(n, n);
    p.M(0, 0) = mass;
    p.M(0, 1) = p.M(1, 0) = mass * c;
    p.M(1, 1) = mass * c * c + inertia;
    if (n == 3) p.M(2, 2) = rng.uniform(0.3, 3);
    const Eigen::LLT<Eigen::MatrixXd> llt(p.M);
    ASSERT_EQ(llt.info(), Eigen::Success);
    p.G.resize(m, n);
    p.v.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) p.v(i) = rng.uniform(-2, 2);
    Eigen::VectorXd e(m), v_other = Eigen::VectorXd::Zero(m), t_other = Eigen::VectorXd::Zero(m);
    std::vector<Eigen::VectorXd> T(static_cast<std::size_t>(m), Eigen::VectorXd(n));
    for (Eigen::Index k = 0; k < m; ++k) {
      for (Eigen::Index i = 0; i < n; ++i) {
        p.G(k, i) = rng.uniform(-1, 1);
        T[std::size_t(k)](i) = rng.uniform(-1, 1);
      }
      e(k) = trial % 3 == 0 ? 0.0 : rng.uniform(0, 1);
      if (trial % 4 == 1) {   // a driver's surface speeds
        v_other(k) = rng.uniform(-0.5, 0.5);
        t_other(k) = rng.uniform(-0.5, 0.5);
      }
    }
    // the pin-slot's terms: speed G q' - v_other, its restitution e (speed) where it approaches
    std::vector<Rational> speed(static_cast<std::size_t>(m)), restitution(static_cast<std::size_t>(m));
    Eigen::VectorXd before(m), hv(m);
    p.h.resize(static_cast<std::size_t>(m));
    p.bias.resize(static_cast<std::size_t>(m));
    for (Eigen::Index k = 0; k < m; ++k) {
      Rational sp = -q(v_other(k)), tb = -q(t_other(k));
      for (Eigen::Index i = 0; i < n; ++i) {
        sp += q(p.G(k, i)) * q(p.v(i));
        tb += q(T[std::size_t(k)](i)) * q(p.v(i));
      }
      speed[std::size_t(k)] = sp;
      restitution[std::size_t(k)] = sgn(sp) < 0 ? q(e(k)) * sp : Rational(0);
      before(k) = to_double(sp);
      hv(k) = -v_other(k) + (sgn(sp) < 0 ? e(k) * before(k) : 0.0);
      p.h[std::size_t(k)] = -q(v_other(k)) + restitution[std::size_t(k)];   // G x + h, x = q'+
      p.bias[std::size_t(k)] = -q(t_other(k));
    }
    std::vector<simulation::Friction> fz, fq;
    for (Eigen::Index k = 0; k < m; ++k) {
      const double mu_s = rng.uniform(0.05, 1.2);
      simulation::Friction f = coulomb(llt.matrixL().solve(T[std::size_t(k)]), mu_s, mu_s * rng.uniform(0.3, 1));
      f.bias = -t_other(k);
      fz.push_back(f);
      f.T = T[std::size_t(k)];
      f.bias = 0;
      fq.push_back(f);
      p.friction.push_back(f);
    }
    ++cases;
    const Eigen::MatrixXd Gz = llt.matrixL().solve(p.G.transpose()).transpose();
    const Eigen::VectorXd vz = llt.matrixU() * p.v, unit = Eigen::VectorXd::Ones(n);
    // (the filter in doubles only, as the simulator since session 71)
    const simulation::FrictionalSolution filter = simulation::solve_frictional(Gz, unit, vz, hv, fz);
    simulation::FullMass full{p.G, p.M, Eigen::VectorXd::Zero(n), fq};
    std::vector<Rational> h_full(static_cast<std::size_t>(m)), t_exact(static_cast<std::size_t>(m));
    for (std::size_t k = 0; k < std::size_t(m); ++k) {
      h_full[k] = speed[k] + restitution[k];
      Rational tb = -q(t_other(Eigen::Index(k)));
      for (Eigen::Index i = 0; i < n; ++i) tb += q(T[k](i)) * q(p.v(i));
      t_exact[k] = tb;
    }
    const simulation::FrictionalSolution s = simulation::full_form_impulses(filter, full, h_full, t_exact);
    const std::vector<std::vector<Rational>> all = oracle_all(p);
    ASSERT_EQ(s.solved, !all.empty()) << trial;
    if (!s.solved) {
      EXPECT_TRUE(s.exhausted) << trial;   // (at most 2 contacts: the search is complete)
      continue;
    }
    ++solved;
    ASSERT_EQ(s.x_exact.size(), std::size_t(n)) << trial;
    std::vector<Rational> x(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < std::size_t(n); ++i) x[i] = q(p.v(Eigen::Index(i))) + s.x_exact[i];
    bool matched = false;
    for (const std::vector<Rational>& o : all) matched = matched || o == x;
    EXPECT_TRUE(matched) << trial << ": the exact velocities after are no consistent solution's";
    // the energy test: x^T M x > v^T M v exactly
    Rational after = 0, before_energy = 0;
    for (std::size_t i = 0; i < std::size_t(n); ++i)
      for (std::size_t j = 0; j < std::size_t(n); ++j) {
        const Rational mij = q(p.M(Eigen::Index(i), Eigen::Index(j)));
        after += x[i] * mij * x[j];
        before_energy += q(p.v(Eigen::Index(i))) * mij * q(p.v(Eigen::Index(j)));
      }
    EXPECT_EQ(simulation::kinetic_grows(p.M, p.v, s.x_exact), after > before_energy) << trial;
    ++energy_checked;
    // the velocities after: exact_sum (the simulator's since session 70) against the Cholesky
    // solution's L^-T x (before)
    const Eigen::VectorXd published = simulation::exact_sum(p.v, s.x_exact);
    for (std::size_t i = 0; i < std::size_t(n); ++i) EXPECT_EQ(published(Eigen::Index(i)), to_double(x[i])) << trial;
    if (filter.solved) {
      const Eigen::VectorXd old = llt.matrixU().solve(filter.x);
      bool differs = false;
      for (std::size_t i = 0; i < std::size_t(n); ++i) differs = differs || old(Eigen::Index(i)) != to_double(x[i]);
      rounded_differs += differs;
    }
  }
  std::cout << "pin-slot Coulomb impacts: " << cases << ", solved " << solved << "; the Cholesky solution's "
            << "velocities after differ from the exact ones rounded in " << rounded_differs << "\n";
  EXPECT_GE(solved, cases * 9 / 10);
  EXPECT_EQ(energy_checked, solved);
  EXPECT_EQ(oracle_undetermined, 0) << "a held set whose velocities after are not unique: the oracle cannot decide";
}

// kinetic_exceeds (creates_energy's comparison where no exact x is found) against the rationals:
// near-ties x = v permuted with a last coordinate nudged by an ulp, random inverse masses.
TEST(ImpactEnergy, KineticComparisonOnTheDoublesIsExact) {
  Rng rng{test::test_seed(7004)};
  int rounded_wrong = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Index n = 2 + trial % 5;
    Eigen::VectorXd v(n), x(n), minv(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      v(i) = rng.uniform(-3, 3);
      minv(i) = trial % 7 == 0 && i == 0 ? 0.0 : std::ldexp(1.0, rng.below(5) - 2);   // powers of two
    }
    x = v;
    for (Eigen::Index i = 0; i + 1 < n; i += 2)   // swap pairs with equal inverse masses
      if (minv(i) == minv(i + 1)) std::swap(x(i), x(i + 1));
    const Eigen::Index last = n - 1;
    const int nudge = rng.below(3) - 1;
    if (nudge != 0) x(last) = std::nextafter(x(last), nudge * std::copysign(10.0, x(last)));
    Rational exact = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (minv(i) > 0) exact += (q(x(i)) * q(x(i)) - q(v(i)) * q(v(i))) / q(minv(i));
    EXPECT_EQ(simulation::kinetic_exceeds(x, v, minv), sgn(exact) > 0) << trial;
    auto kinetic = [&](const Eigen::VectorXd& u) {
      return 0.5 * (minv.array() > 0).select(u.array().square() / minv.array(), 0.0).sum();
    };
    rounded_wrong += (kinetic(x) > kinetic(v)) != (sgn(exact) > 0);
  }
  std::cout << "kinetic comparisons: the rounded sums wrong in " << rounded_wrong << " of 2000\n";
  if (std::getenv("HIPAIR_TEST_SEED") == nullptr) EXPECT_GT(rounded_wrong, 0);
}

}  // namespace
}  // namespace hipair
