// The two decisions of the hand-over envelope's search (src/tolerance/handover.hpp; docs/tolerance.md
// "Hand-overs") on generated cases against oracles that know the zeros exactly:
//   - the walk (walk_window) over synthetic candidates, each a union of closed intervals where it
//     may push: the envelope's end E may never stop short of the point the candidates' zeros reach
//     from the holder's end without a gap (the follower can be carried there: the oracle), and
//     does not run more than one finest leaf past the reach with gaps below two finest leaves
//     bridged;
//   - the monotone exclusion (monotone_without_zero) for contact functions F(v, p) =
//     sigma k (v - r(p)) whose roots r(p) fill a known interval R: it may exclude a leaf only when
//     R misses it.
// Mutations that fail them (session 27): the walk ignoring the candidate it found pushing last
// (the first test), the monotone test with its two ends swapped (the second); chain26 named both
// as caught by no test.
#include "tolerance/handover.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace hipair {
namespace {

using tolerance_detail::Interval;

struct Zeros {
  double lo, hi;
};

// How far (sigma-wards) the zeros reach from `start`: the largest x with [start, x] (or [x,
// start]) covered by the zeros, gaps up to `bridge` counted as covered.
double reach_of(const std::vector<std::vector<Zeros>>& candidates, double start, int sigma, double bridge) {
  double x = start;
  for (bool moved = true; moved;) {
    moved = false;
    for (const std::vector<Zeros>& c : candidates)
      for (const Zeros& z : c) {
        if (sigma > 0 && z.lo <= x + bridge && z.hi > x) {
          x = z.hi;
          moved = true;
        }
        if (sigma < 0 && z.hi >= x - bridge && z.lo < x) {
          x = z.lo;
          moved = true;
        }
      }
  }
  return x;
}

TEST(HandoverWalk, NeverStopsShortOfTheCandidatesConnectedZeros) {
  std::mt19937 rng(2727);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t bounded = 0, beyond_start = 0, unbounded = 0, long_single = 0;
  constexpr int levels = 4;
  for (int trial = 0; trial < 4000; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const int sigma = (rng() & 1) ? 1 : -1;
    const double start = 4 * unit(rng) - 2, reach = 0.01 + unit(rng);
    const Interval window = sigma > 0 ? Interval(start, start + reach) : Interval(start - reach, start);
    const double coarse = reach / 8, finest = coarse / 16;
    std::vector<std::vector<Zeros>> candidates(1 + rng() % 5);
    for (std::vector<Zeros>& c : candidates) {
      std::size_t count = rng() % 4;
      for (std::size_t j = 0; j < count; ++j) {
        // from a quarter of the window behind the start to a fifth beyond its far end; widths from
        // far below a finest leaf to a third of the window
        double from = -0.25 * reach + 1.45 * reach * unit(rng);
        double width = reach * (unit(rng) < 0.3 ? 0.01 * unit(rng) : 0.33 * unit(rng));
        double a = start + sigma * from, b = a + sigma * width;
        c.push_back({std::min(a, b), std::max(a, b)});
      }
    }
    // often a candidate's zeros from the holder's end on (the hand-over the walk must follow)
    if (rng() % 2 == 0) {
      double width = reach * (0.05 + 0.9 * unit(rng));
      candidates[rng() % candidates.size()].push_back(
          sigma > 0 ? Zeros{start - 0.01 * reach, start + width} : Zeros{start - width, start + 0.01 * reach});
    }
    std::size_t evaluations = 0;
    auto may_push = [&](std::size_t i, const Interval& y) {
      ++evaluations;
      return std::any_of(candidates[i].begin(), candidates[i].end(),
                         [&](const Zeros& z) { return z.lo <= y.hi && z.hi >= y.lo; });
    };
    tolerance_detail::WindowWalk walk =
        tolerance_detail::walk_window(start, window, sigma, coarse, levels, candidates.size(), may_push);
    const double reached = reach_of(candidates, start, sigma, 0.0);
    const double far = sigma > 0 ? window.hi : window.lo;
    // a zero reaching the window's far end: the follower may leave the window
    if (sigma * (reached - far) >= 0) {
      EXPECT_FALSE(walk.bounded) << "the zeros reach the window's end " << far;
      ++unbounded;
      continue;
    }
    if (!walk.bounded) {
      // only where the zeros, gaps below two finest leaves bridged (a gap shorter than that may
      // hold no whole leaf of the walk's grid), come within a finest leaf of the end
      EXPECT_GE(sigma * (reach_of(candidates, start, sigma, 2 * finest) - far), -finest * (1 + 1e-9));
      ++unbounded;
      continue;
    }
    ++bounded;
    beyond_start += reached != start;
    // the single candidate whose zeros the walk must follow over several finest leaves alone
    for (const std::vector<Zeros>& c : candidates)
      for (const Zeros& z : c) long_single += (z.hi - z.lo) > 3 * finest && candidates.size() == 1;
    EXPECT_GE(sigma * (walk.edge - reached), 0.0)
        << "sigma " << sigma << ": the walk ends at " << walk.edge << ", the zeros reach " << reached;
    EXPECT_LE(sigma * (walk.edge - reach_of(candidates, start, sigma, 2 * finest)), finest * (1 + 1e-9))
        << "sigma " << sigma << ": the walk ends at " << walk.edge << ", further than the zeros";
    if (reached != start) EXPECT_LT(walk.last, candidates.size());
    EXPECT_GT(evaluations, 0u);
  }
  std::printf("[ walk ] %zu bounded (%zu carried beyond the holder's end, %zu with one candidate's long zeros), "
              "%zu unbounded\n",
              bounded, beyond_start, long_single, unbounded);
  EXPECT_GE(beyond_start, 500u);
  EXPECT_GE(long_single, 100u);
  EXPECT_GE(unbounded, 50u);
}

TEST(HandoverWalk, MonotoneExclusionOnlyWhereTheRootsMissTheLeaf) {
  std::mt19937 rng(1227);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t excluded = 0, straddling = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int sigma = (rng() & 1) ? 1 : -1;
    // R: the roots over the box (every r in R is some vector's root)
    const double r0 = 2 * unit(rng) - 1, r1 = r0 + (unit(rng) < 0.2 ? 0.0 : unit(rng));
    const double y0 = 3 * unit(rng) - 1.5, y1 = y0 + unit(rng);
    const Interval y(y0, y1);
    // F's certain sign at v over the box, blurred by `blur` (an enclosure that is not sharp)
    const double blur = unit(rng) < 0.5 ? 0.0 : 0.1 * unit(rng);
    auto sign_at = [&](double v) {
      if (v < r0 - blur) return -sigma;   // F = sigma k (v - r) with v - r < 0 for every r
      if (v > r1 + blur) return sigma;
      return 0;
    };
    const bool roots_in_leaf = r0 <= y1 && r1 >= y0;
    const bool out = tolerance_detail::monotone_without_zero(sigma, y, sign_at);
    straddling += roots_in_leaf;
    excluded += out;
    if (roots_in_leaf)
      EXPECT_FALSE(out) << "sigma " << sigma << ": roots [" << r0 << ", " << r1 << "] meet the leaf [" << y0 << ", "
                        << y1 << "], excluded";
    // without blur every leaf the roots miss is excluded
    if (!roots_in_leaf && blur == 0.0) EXPECT_TRUE(out) << "sigma " << sigma << ": a leaf without roots kept";
  }
  EXPECT_GE(excluded, 5000u);
  EXPECT_GE(straddling, 2000u);
}

// The driver's form split for the walk's Taylor models (split_driver, session 28): generated
// quadratic maps t(p) = a_0 + sum_i a_i p_i + b_i p_i^2 + e p_0 p_1 over boxes with dyadic
// centres and half widths (some parameters fixed), their mean-value form t(c) + sum_i D_i
// [B_i - c_i] (D_i: the gradient enclosed over the box in interval arithmetic) plus a remainder
// holding 0, and a random subset of the parameters as the Taylor models' variables. The oracle:
// at vectors p = c + h xi of the box (xi on a dyadic grid and at the corners, so xi is exact),
// t(p) enclosed in interval arithmetic must meet lumped + sum_b coefficients_b xi_b. Mutations
// that fail it: the other parameters' terms left out of `lumped`; a coefficient without its
// half width h.
TEST(HandoverDriverForm, SplitHoldsTheDriverAtEveryVectorOfTheBox) {
  std::mt19937 rng(2828);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const std::size_t n = 2 + rng() % 6;
    tolerance_detail::Box box;
    std::vector<double> c(n), h(n), a(n), b(n);
    for (std::size_t i = 0; i < n; ++i) {
      c[i] = std::ldexp(static_cast<double>(static_cast<int>(rng() % 2049) - 1024), -8);
      h[i] = rng() % 5 == 0 ? 0.0 : std::ldexp(static_cast<double>(1 + rng() % 64), -static_cast<int>(4 + rng() % 8));
      box.lo.push_back(c[i] - h[i]);
      box.hi.push_back(c[i] + h[i]);
      a[i] = 4 * unit(rng) - 2;
      b[i] = unit(rng) < 0.5 ? 0.0 : 2 * unit(rng) - 1;
    }
    const double a0 = 2 * unit(rng) - 1, e = unit(rng) < 0.5 ? 0.0 : 2 * unit(rng) - 1;
    auto t_of = [&](const std::vector<Interval>& p) {
      Interval t = Interval::point(a0) + Interval::point(e) * p[0] * p[1];
      for (std::size_t i = 0; i < n; ++i) t = t + Interval::point(a[i]) * p[i] + Interval::point(b[i]) * p[i] * p[i];
      return t;
    };
    std::vector<Interval> whole(n), at_center(n);
    for (std::size_t i = 0; i < n; ++i) {
      whole[i] = Interval(box.lo[i], box.hi[i]);
      at_center[i] = Interval::point(c[i]);
    }
    tolerance_detail::DriverForm form;
    const double r = unit(rng) < 0.5 ? 0.0 : 0.01 * unit(rng);
    form.value = t_of(at_center) + Interval(-r, r);
    for (std::size_t i = 0; i < n; ++i) {
      Interval g = Interval::point(a[i]) + Interval(2) * Interval::point(b[i]) * whole[i];
      if (i == 0) g = g + Interval::point(e) * whole[1];
      if (i == 1) g = g + Interval::point(e) * whole[0];
      form.gradient.push_back(g);
    }
    std::vector<std::size_t> variables;
    for (std::size_t i = 0; i < n; ++i)
      if (h[i] > 0 && (rng() & 1)) variables.push_back(i);
    tolerance_detail::DriverSplit split = tolerance_detail::split_driver(form, box, variables);
    ASSERT_EQ(split.coefficients.size(), variables.size());
    for (int sample = 0; sample < 40; ++sample) {
      std::vector<double> xi(n);
      for (std::size_t i = 0; i < n; ++i)
        xi[i] = sample < 8 ? ((rng() & 1) ? 1.0 : -1.0) : std::ldexp(static_cast<double>(static_cast<int>(rng() % 17) - 8), -3);
      std::vector<Interval> p(n);
      for (std::size_t i = 0; i < n; ++i) p[i] = Interval::point(c[i] + h[i] * xi[i]);   // exact: dyadic
      Interval truth = t_of(p);
      Interval s = split.lumped;
      for (std::size_t v = 0; v < variables.size(); ++v) s = s + split.coefficients[v] * Interval::point(xi[variables[v]]);
      EXPECT_TRUE(s.lo <= truth.hi && truth.lo <= s.hi)
          << "t(p) in [" << truth.lo << ", " << truth.hi << "], the split gives [" << s.lo << ", " << s.hi << "]";
      ++checked;
    }
  }
  EXPECT_EQ(checked, 80000u);
}

}  // namespace
}  // namespace hipair
