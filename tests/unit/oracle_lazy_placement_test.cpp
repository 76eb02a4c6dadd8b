// Session 47 (gear47): PairOverlap::classify places its first part lazily — the part's edges in
// blocks of eight consecutive edges, each block's body-frame disk posed by one interval product,
// an edge's interval geometry made only when its block's box meets what a test asks about (the
// second part's box, a probe's ray, a point); the second part's edge boxes skipped a block at a
// time. On generated spur-gear pairs (random tooth counts, backlash and centre distance), at
// random chart points of every chart pair and at points bisected towards the boundary between
// apart and overlapping (where the edges the blocks skip are nearest to the other part), the
// lazy route's answer must be the eager route's (every edge placed: set_lazy_placement(false))
// and classify_overlap's (a fresh analysis without blocks); the lazy placements must have left
// most edges unplaced.
#include "curves/contact_curves.hpp"
#include "oracle/overlap.hpp"
#include "oracle/filter_counts.hpp"
#include "spur_gear_pairs.hpp"
#include "test_seed.hpp"
#include "algebra/exact_real.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

Rational between(const cspace::ChartAxis& axis, std::mt19937_64& random, long cells) {
  Rational r = axis.lo + (axis.hi - axis.lo) * Rational(static_cast<long>(random() % (cells + 1)), cells);
  r.canonicalize();
  return r;
}

const char* name_of(cspace::Overlap relation) {
  return relation == cspace::Overlap::apart ? "apart" : relation == cspace::Overlap::overlapping ? "overlapping" : "touching";
}

TEST(OracleLazyPlacement, LazyClassifyIsTheEagerOracleOnGeneratedGearPairs) {
  std::mt19937_64 random(4701);
  std::size_t asked = 0, apart = 0, overlapping = 0, touching = 0, near_boundary = 0;
  const auto before = cspace::lazy_placement_counts();
  for (int trial = 0; trial < 4; ++trial) {
    const long z1 = 6 + static_cast<long>(random() % 25), z2 = 6 + static_cast<long>(random() % 25);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    const cspace::PairOverlap oracle(model, axes);
    auto check = [&](const cspace::ChartAxis& x, const cspace::ChartAxis& y, const cspace::ChartPoint& q) {
      cspace::set_lazy_placement(true);
      const cspace::Overlap lazy = oracle.classify(x, y, q);
      cspace::set_lazy_placement(false);
      const cspace::Overlap eager = oracle.classify(x, y, q);
      cspace::set_lazy_placement(true);
      const cspace::Overlap fresh = cspace::classify_overlap(model, axes, x, y, q);
      EXPECT_EQ(lazy, eager) << "at (" << q.x.get_str() << ", " << q.y.get_str() << "): lazy " << name_of(lazy)
                             << ", eager " << name_of(eager);
      EXPECT_EQ(lazy, fresh) << "at (" << q.x.get_str() << ", " << q.y.get_str() << ")";
      ++asked;
      (lazy == cspace::Overlap::apart ? apart : lazy == cspace::Overlap::overlapping ? overlapping : touching) += 1;
      return lazy;
    };
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts) {
        for (int k = 0; k < 40; ++k) {
          cspace::ChartPoint q;
          q.x = between(x, random, 4096);
          q.y = between(y, random, 4096);
          check(x, y, q);
        }
        // along a random column: neighbours of a 64-step grid with different answers, bisected
        // 24 times towards the boundary between them (every point asked on the way)
        for (int column = 0; column < 3; ++column) {
          cspace::ChartPoint q;
          q.x = between(x, random, 4096);
          Rational previous_y = y.lo;
          q.y = previous_y;
          cspace::Overlap previous = check(x, y, q);
          int bisected = 0;
          for (long j = 1; j <= 64 && bisected < 3; ++j) {
            Rational yj = y.lo + (y.hi - y.lo) * Rational(j, 64);
            yj.canonicalize();
            q.y = yj;
            const cspace::Overlap here = check(x, y, q);
            if (here != previous && here != cspace::Overlap::touching && previous != cspace::Overlap::touching) {
              Rational lo = previous_y, hi = yj;
              for (int step = 0; step < 24; ++step) {
                Rational mid = (lo + hi) / 2;
                mid.canonicalize();
                q.y = mid;
                const cspace::Overlap m = check(x, y, q);
                if (m == cspace::Overlap::touching) break;
                (m == previous ? lo : hi) = mid;
                ++near_boundary;
              }
              ++bisected;
            }
            previous = here;
            previous_y = yj;
          }
        }
      }
  }
  const auto after = cspace::lazy_placement_counts();
  const auto lazy_calls = after[0] - before[0], edges = after[1] - before[1], placed = after[2] - before[2];
  EXPECT_GT(apart, asked / 20) << "of " << asked;
  EXPECT_GT(overlapping, asked / 10) << "of " << asked;
  EXPECT_GT(near_boundary, 500u);
  // every lazy classify counted, and most edges never placed
  EXPECT_EQ(lazy_calls, asked);
  EXPECT_LT(placed * 2, edges) << placed << " of " << edges << " edges placed";
  std::printf("[lazy placement] %zu points (%zu apart, %zu overlapping, %zu touching, %zu bisected), %llu of %llu edges placed\n",
              asked, apart, overlapping, touching, near_boundary, static_cast<unsigned long long>(placed),
              static_cast<unsigned long long>(edges));
}

// Session 63 (perf63): PairOverlap::certainly_overlapping (the certified filter in front of the
// algebraic oracle) poses the first part a block at a time too — an edge's interval geometry
// made only in blocks whose posed disk meets the second part's box — where it posed every edge.
// On generated spur-gear pairs, over boxes of every chart pair (narrow boxes about random points,
// as the builder's vertices have, and wider ones up to 1/8 of the chart), the answer must be the
// eager route's (set_lazy_placement(false)); where it answers, the exact oracle at the box's
// corners and middle says "overlapping". Mutants: a block skipped when its disk meets the second
// part's box (the test inverted), or the blocks' disks posed at the box's middle only, fail it.
TEST(OracleLazyPlacement, LazyFilterIsTheEagerFilterOnGeneratedGearPairs) {
  std::mt19937_64 random(hipair::test::test_seed(6301));
  std::size_t asked = 0, decided = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const long z1 = 6 + static_cast<long>(random() % 35), z2 = 6 + static_cast<long>(random() % 35);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z1, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    const cspace::PairOverlap oracle(model, axes);
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts)
        for (int k = 0; k < 150; ++k) {
          // a box about a random point: from a few doubles wide to 1/8 of the chart
          const Rational px = between(x, random, 1 << 20), py = between(y, random, 1 << 20);
          const int shrink = 3 + static_cast<int>(random() % 48);
          const Rational wx = Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink);
          const Rational wy = Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink);
          Rational xlo = std::max(Rational(px - wx), x.lo), xhi = std::min(Rational(px + wx), x.hi);
          Rational ylo = std::max(Rational(py - wy), y.lo), yhi = std::min(Rational(py + wy), y.hi);
          for (Rational* r : {&xlo, &xhi, &ylo, &yhi}) r->canonicalize();
          const kernels::Interval bx(cspace::algebra::lower_double(xlo), cspace::algebra::upper_double(xhi));
          const kernels::Interval by(cspace::algebra::lower_double(ylo), cspace::algebra::upper_double(yhi));
          cspace::set_lazy_placement(false);
          const bool eager = oracle.certainly_overlapping(x, y, bx, by);
          cspace::set_lazy_placement(true);
          const bool lazy = oracle.certainly_overlapping(x, y, bx, by);
          ++asked;
          EXPECT_EQ(lazy, eager) << "over [" << xlo.get_str() << ", " << xhi.get_str() << "] x [" << ylo.get_str()
                                 << ", " << yhi.get_str() << "]";
          if (!lazy) continue;
          ++decided;
          Rational mx = (xlo + xhi) / 2, my = (ylo + yhi) / 2;
          mx.canonicalize();
          my.canonicalize();
          for (const auto& [qx, qy] : {std::pair{xlo, ylo}, std::pair{xhi, yhi}, std::pair{xlo, yhi}, std::pair{mx, my}})
            EXPECT_EQ(oracle.classify(x, y, cspace::ChartPoint{qx, qy}), cspace::Overlap::overlapping)
                << "at (" << qx.get_str() << ", " << qy.get_str() << "), where the filter said overlapping";
        }
  }
  // the filter answers on a good share of the boxes (most of a chart is blocked) and not on all
  EXPECT_GT(decided * 5, asked) << decided << " of " << asked;
  EXPECT_LT(decided, asked);
  std::printf("[lazy filter] %zu boxes, %zu decided overlapping\n", asked, decided);
}

// Session 70 (growth70): certainly_overlapping skips a block of the first part whose posed box
// meets no block box of the second part (not only the second part's whole box, which holds a
// quarter of a gear's teeth): the edges it poses per call no longer grow with the tooth count
// (they did linearly: n^1.8 of the operating region's classification). On generated spur-gear
// pairs of 16, 32 and 64 teeth, over narrow boxes about random points of every chart pair and
// boxes of 2^-30 of the chart about points of the contact boundary (where the builder's vertices
// ask, and where the filter declines and so visits every block it does not skip), the answer
// must be the eager route's (every edge posed, set_lazy_placement(false)). It cannot fail on the
// base (the same route as the eager one there); a window that drops blocks it must keep (the
// mutant "half of the mate's meeting blocks kept") fails it 349 times. The edges posed
// per declining call are printed (windowed 29 / 38 / 46 at 16 / 32 / 64 teeth, the base's route
// 34 / 51 / 65: the meshing zone itself grows about as the square root of the tooth count).
TEST(OracleLazyPlacement, FilterWindowedByTheMatesBlocksIsTheEagerFilterAtAnyToothCount) {
  std::mt19937_64 random(hipair::test::test_seed(7001));
  std::vector<double> posed_per_call;
  for (const long z : {16L, 32L, 64L}) {
    const long z2 = z + static_cast<long>(random() % 5);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    const cspace::PairOverlap oracle(model, axes);
    std::uint64_t calls = 0, posed = 0;
    // the filter over [xlo, xhi] x [ylo, yhi], lazy (windowed) and eager; `count`: its posed edges
    // counted where it declines (a call that finds a crossing stops early; one that finds none
    // visits every block it does not skip, as at the builder's vertices)
    auto ask = [&](const cspace::ChartAxis& x, const cspace::ChartAxis& y, Rational xlo, Rational xhi, Rational ylo,
                   Rational yhi, bool count) {
      xlo = std::max(xlo, x.lo), xhi = std::min(xhi, x.hi), ylo = std::max(ylo, y.lo), yhi = std::min(yhi, y.hi);
      for (Rational* r : {&xlo, &xhi, &ylo, &yhi}) r->canonicalize();
      const kernels::Interval bx(cspace::algebra::lower_double(xlo), cspace::algebra::upper_double(xhi));
      const kernels::Interval by(cspace::algebra::lower_double(ylo), cspace::algebra::upper_double(yhi));
      cspace::set_lazy_placement(false);
      const bool eager = oracle.certainly_overlapping(x, y, bx, by);
      cspace::set_lazy_placement(true);
      const std::uint64_t before = cspace::overlap_filter_posed_edges();
      const bool lazy = oracle.certainly_overlapping(x, y, bx, by);
      if (count && !lazy) {
        posed += cspace::overlap_filter_posed_edges() - before;
        ++calls;
      }
      EXPECT_EQ(lazy, eager) << "over [" << xlo.get_str() << ", " << xhi.get_str() << "] x [" << ylo.get_str() << ", "
                             << yhi.get_str() << "]";
    };
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts) {
        // boxes about random points (most deep in blocked space: the filter decides there)
        for (int k = 0; k < 60; ++k) {
          const Rational px = between(x, random, 1 << 20), py = between(y, random, 1 << 20);
          // (at most 2^-16 of the chart: a pose uncertainty below a tooth at every tooth count)
          const int shrink = 16 + static_cast<int>(random() % 24);
          const Rational wx = Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink);
          const Rational wy = Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink);
          ask(x, y, px - wx, px + wx, py - wy, py + wy, false);
        }
        // boxes of 2^-30 of the chart about points of the contact boundary (a random column's
        // change between apart and overlapping, bisected 30 times): where the builder asks
        for (int column = 0; column < 8; ++column) {
          const Rational px = between(x, random, 1 << 20);
          std::optional<cspace::Overlap> previous;
          Rational previous_y = y.lo;
          for (long j = 0; j <= 48; ++j) {
            Rational yj = y.lo + (y.hi - y.lo) * Rational(j, 48);
            yj.canonicalize();
            const cspace::Overlap here = oracle.classify(x, y, cspace::ChartPoint{px, yj});
            if (previous && here != *previous && here != cspace::Overlap::touching &&
                *previous != cspace::Overlap::touching) {
              Rational lo = previous_y, hi = yj;
              for (int step = 0; step < 30; ++step) {
                Rational mid = (lo + hi) / 2;
                mid.canonicalize();
                const cspace::Overlap m = oracle.classify(x, y, cspace::ChartPoint{px, mid});
                if (m == cspace::Overlap::touching) break;
                (m == *previous ? lo : hi) = mid;
              }
              const Rational wx = Rational(x.hi - x.lo) / Rational(mpz_class(1) << 30);
              const Rational wy = Rational(y.hi - y.lo) / Rational(mpz_class(1) << 30);
              ask(x, y, px - wx, px + wx, lo - wy, lo + wy, true);
              ask(x, y, px - wx, px + wx, hi - wy, hi + wy, true);
            }
            previous = here;
            previous_y = yj;
          }
        }
      }
    ASSERT_GT(calls, 24u);
    posed_per_call.push_back(static_cast<double>(posed) / static_cast<double>(calls));
    std::printf("[windowed filter] %ld x %ld teeth: %.1f edges posed per declining call (%llu calls)\n", z, z2,
                posed_per_call.back(), static_cast<unsigned long long>(calls));
  }
  EXPECT_GT(posed_per_call.front(), 0.0);
}

}  // namespace
}  // namespace hipair
