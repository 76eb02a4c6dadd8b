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

}  // namespace
}  // namespace hipair
