// Session 46 (tol46): the case split's bound (src/tolerance/mean_value.hpp case_split_bound,
// chain.cpp compose_over; docs/tolerance.md "The case split at a widened mesh") on generated
// chains of maps where a later stage is NOT monotone in its driver and where the widened stage's
// far end carries the output beyond the holder case — the two halves of the split that the gear
// trains cannot reach (their later meshes are monotone, and at 0.195 rad the far end's output
// lies inside the holder case's enclosure), so that tol45's mutants "monotonicity check skipped"
// and "upper case dropped" survived ChainCaseSplit.*.
//
// A chain over the box [-1, 1]^n: stage 0 widened on side sigma — its follower
// y_0(p) = the sigma-most of its holder's root h(p) and a competitor q(p) = h(p) + sigma mu
// (p_j - theta) (which takes over on part of the box, as another tooth pair does); its envelope's
// far end E bounds q over the box. Then stages s = 1 .. L, y_s = g_s(p, t_s) with t_s = phi(y_s-1),
// phi(v) = v + sin(v)/2 increasing (a chart change), g_s(p, t) = alpha t + sum_i beta_i p_i +
// gamma sin(omega t + shift): monotone in t when |gamma omega| < |alpha|, else possibly not. On a
// third of the chains the last stage widens too (y_L the sigma_L-most of g_L and a competitor),
// its bridge the envelope over box x the cases' driver hull. Each stage's enclosures in outward
// rounded intervals, the slopes dg_s/dt over box x the hull of the two cases' driver ranges as
// interval jets — what chain.cpp's monotone_between gets from CurveSolver::root_partials — and
// the bound from the chain's own function. Every sampled point's value (the chain evaluated at
// the point, outward rounded) must lie inside the bound wherever the bound is given.
#include "model/parametric/number_traits.hpp"
#include "tolerance/jet.hpp"
#include "tolerance/mean_value.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using model_detail::Arithmetic;
using IJet = tolerance_detail::Jet<Interval>;

template <class T>
T constant(int numerator, int denominator) {
  return Arithmetic<T>::constant(Rational(numerator, denominator));
}

// phi(v) = v + sin(v) / 2 (phi' >= 1/2: increasing)
template <class T>
T phi(const T& v) {
  return v + constant<T>(1, 2) * Arithmetic<T>::sin(v);
}

// g(p, t) = alpha t + sum_i beta_i p_i + gamma sin(omega t + shift) (alpha, gamma, omega, shift
// in eighths, beta_i in 32nds)
struct Stage {
  int alpha = 8, gamma = 0, omega = 8, shift = 0;
  std::vector<int> beta;
  // the last stage's competitor (when `competes`): c(p, t) = g(p, t) + sigma nu (p_m - theta)
  bool competes = false;
  int sigma = 1, nu = 0, theta = 0;
  std::size_t m = 0;
};

template <class T>
T holder(const Stage& g, const std::vector<T>& p, const T& t) {
  T v = constant<T>(g.alpha, 8) * t;
  for (std::size_t i = 0; i < p.size(); ++i) v = v + constant<T>(g.beta[i], 32) * p[i];
  return v + constant<T>(g.gamma, 8) * Arithmetic<T>::sin(T(constant<T>(g.omega, 8) * t + constant<T>(g.shift, 8)));
}

template <class T>
T competitor(const Stage& g, const std::vector<T>& p, const T& t) {
  return holder(g, p, t) + constant<T>(g.sigma * g.nu, 8) * (p[g.m] - constant<T>(g.theta, 8));
}

// The sigma-most of two enclosures (the follower held by whichever pushes it further).
Interval sigma_most(int sigma, const Interval& a, const Interval& b) {
  return sigma > 0 ? Arithmetic<Interval>::max(a, b) : Arithmetic<Interval>::min(a, b);
}

// The widened stage 0: h(p) = c0 + sum_i a_i p_i, q(p) = h(p) + sigma mu (p_j - theta).
struct Widened {
  int c0 = 0, sigma = 1, mu = 8, theta = 0;
  std::vector<int> a;
  std::size_t j = 0;
  Interval h(const std::vector<Interval>& p) const {
    Interval v = constant<Interval>(c0, 8);
    for (std::size_t i = 0; i < p.size(); ++i) v = v + constant<Interval>(a[i], 32) * p[i];
    return v;
  }
  Interval q(const std::vector<Interval>& p) const {
    return h(p) + constant<Interval>(sigma * mu, 8) * (p[j] - constant<Interval>(theta, 8));
  }
  Interval y(const std::vector<Interval>& p) const { return sigma_most(sigma, h(p), q(p)); }
};

// The chain's output at the point p (outward rounded).
Interval value_at(const Widened& w, const std::vector<Stage>& stages, const std::vector<Interval>& p) {
  Interval y = w.y(p);
  for (const Stage& g : stages) {
    Interval t = phi(y);
    y = holder(g, p, t);
    if (g.competes) y = sigma_most(g.sigma, y, competitor(g, p, t));
  }
  return y;
}

bool inside(const Interval& x, const Interval& bound) { return x.lo >= bound.lo && x.hi <= bound.hi; }
// The value x encloses is certainly outside the bound (an enclosure only meeting the bound's end
// is a value at the end within the rounding of the two evaluations: a corner of the box where
// the bound is exact).
bool certainly_outside(const Interval& x, const Interval& bound) { return x.lo > bound.hi || x.hi < bound.lo; }

TEST(ChainCaseSplitMaps, HullOfTheCasesHoldsEveryValueOnlyUnderMonotoneLaterStages) {
  std::mt19937_64 random(4646);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  std::size_t chains = 0, bounded = 0, refused = 0, values = 0, outside = 0;
  std::size_t edge = 0;             // values whose enclosure meets the bound's end (rounding)
  std::size_t refused_needed = 0;   // refused chains with a value outside the bound the slopes unchecked would give
  std::size_t upper_needed = 0;     // bounded chains with a value outside the bound the holder case alone would give
  std::size_t bridge_needed = 0;    // bounded chains with a value beyond the cases' hull, inside the bridge
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("chain " + std::to_string(trial));
    ++chains;
    const std::size_t n = static_cast<std::size_t>(uniform(2, 4));
    const std::size_t later = static_cast<std::size_t>(uniform(1, 3));
    Widened w;
    w.c0 = uniform(-8, 8);
    w.sigma = uniform(0, 1) ? 1 : -1;
    w.mu = uniform(4, 16);
    w.theta = uniform(-4, 4);
    w.j = static_cast<std::size_t>(uniform(0, static_cast<int>(n) - 1));
    for (std::size_t i = 0; i < n; ++i) w.a.push_back(uniform(-2, 2));
    std::vector<Stage> stages(later);
    for (std::size_t s = 0; s < later; ++s) {
      Stage& g = stages[s];
      g.alpha = uniform(4, 8) * (uniform(0, 1) ? 1 : -1);
      // half the chains monotone by construction (|gamma omega| < |alpha|), half possibly not
      bool steep = trial % 2 == 1;
      g.omega = uniform(4, 16);
      g.gamma = steep ? uniform(4, 16) : uniform(0, (std::abs(g.alpha) * 8 - 1) / g.omega);
      g.shift = uniform(-16, 16);
      for (std::size_t i = 0; i < n; ++i) g.beta.push_back(uniform(-2, 2));
    }
    Stage& last = stages.back();
    if (trial % 3 == 2) {
      last.competes = true;
      last.sigma = uniform(0, 1) ? 1 : -1;
      last.nu = uniform(2, 8);
      last.theta = uniform(-4, 4);
      last.m = static_cast<std::size_t>(uniform(0, static_cast<int>(n) - 1));
    }

    // The box and the widened stage's enclosures: the holder's Y, the envelope's far end E.
    const std::vector<Interval> box(n, Interval(-1.0, 1.0));
    const Interval y_holder = w.h(box);
    const Interval q_box = w.q(box);
    const double far_end = w.sigma > 0 ? std::max(q_box.hi, y_holder.hi) : std::min(q_box.lo, y_holder.lo);
    // The two cases (the later stages' holders only, as compose_once's overrides): the driver
    // ranges and the last enclosures.
    std::vector<Interval> lower_t(later), upper_t(later);
    Interval lower = y_holder, upper = Interval::point(far_end);
    for (std::size_t s = 0; s < later; ++s) {
      lower_t[s] = phi(lower);
      upper_t[s] = phi(upper);
      lower = holder(stages[s], box, lower_t[s]);
      upper = holder(stages[s], box, upper_t[s]);
    }
    // The slopes over box x the hull of the cases' driver ranges; the last stage's bridge.
    std::vector<Interval> slopes;
    for (std::size_t s = 0; s < later; ++s) {
      std::vector<IJet> jp(n);
      for (std::size_t i = 0; i < n; ++i) jp[i] = IJet(box[i]);
      IJet jt = IJet::variable(kernels::hull(lower_t[s], upper_t[s]), 0, 1);
      slopes.push_back(holder(stages[s], jp, jt).partial(0));
    }
    const Interval hull_t = kernels::hull(lower_t.back(), upper_t.back());
    Interval bridge = holder(last, box, hull_t);
    bool extended = false;
    if (last.competes) {
      Interval c = competitor(last, box, hull_t);
      Interval widened = kernels::hull(bridge, c);
      extended = last.sigma > 0 ? widened.hi > bridge.hi : widened.lo < bridge.lo;
      if (extended) bridge = last.sigma > 0 ? Interval(bridge.lo, widened.hi) : Interval(widened.lo, bridge.hi);
    }
    Interval met;
    const bool given = tolerance_detail::case_split_bound(slopes, lower, upper, bridge, extended, last.sigma, met);
    given ? ++bounded : ++refused;

    // What the bound would be without each half of the split: the slopes not checked, the upper
    // case dropped (the holder case's enclosure alone).
    Interval unchecked, holder_only;
    tolerance_detail::case_split_bound({}, lower, upper, bridge, extended, last.sigma, unchecked);
    tolerance_detail::case_split_bound({}, lower, lower, bridge, extended, last.sigma, holder_only);
    const Interval cases = kernels::hull(lower, upper);

    // Sampled points: the box's corners, then points along the competitor's parameter p_j (where
    // the widened stage hands over), then uniform points.
    bool outside_unchecked = false, outside_holder_only = false, beyond_cases = false;
    const int corners = 1 << n;
    for (int k = 0; k < corners + 96; ++k) {
      std::vector<Interval> p(n);
      for (std::size_t i = 0; i < n; ++i) {
        double x = k < corners ? ((k >> i) & 1 ? 1.0 : -1.0) : std::uniform_real_distribution<double>(-1.0, 1.0)(random);
        if (k >= corners && k < corners + 32 && i == w.j) x = -1.0 + 2.0 * (k - corners) / 31.0;
        p[i] = Interval::point(x);
      }
      const Interval v = value_at(w, stages, p);
      if (certainly_outside(v, unchecked)) outside_unchecked = true;
      if (certainly_outside(v, holder_only)) outside_holder_only = true;
      if (certainly_outside(v, cases) && inside(v, met)) beyond_cases = true;
      if (!given) continue;
      ++values;
      if (!inside(v, met)) ++edge;
      if (certainly_outside(v, met)) {
        if (++outside <= 5)
          ADD_FAILURE() << "value [" << v.lo << ", " << v.hi << "] outside the bound [" << met.lo << ", " << met.hi
                        << "] (cases [" << lower.lo << ", " << lower.hi << "] / [" << upper.lo << ", " << upper.hi
                        << "])";
      }
    }
    if (!given && outside_unchecked) ++refused_needed;
    if (given && outside_holder_only) ++upper_needed;
    if (given && extended && beyond_cases) ++bridge_needed;
  }
  std::printf("%zu chains: bound given on %zu (%zu values; outside %zu, at an end within the rounding %zu), refused on %zu (a value outside the unchecked "
              "bound on %zu); the upper case needed on %zu, the bridge on %zu\n",
              chains, bounded, values, outside, edge, refused, refused_needed, upper_needed, bridge_needed);
  EXPECT_EQ(outside, 0u);
  // The test's reach: chains where each half of the split decides the verdict.
  EXPECT_GE(bounded, 100u);
  EXPECT_GE(refused_needed, 20u);   // the monotonicity check is what keeps them sound
  EXPECT_GE(upper_needed, 20u);     // the upper case is what holds their values
  EXPECT_GE(bridge_needed, 5u);     // the last stage's widening beyond the cases
}

}  // namespace
}  // namespace hipair
