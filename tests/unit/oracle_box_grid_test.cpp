// Session 74 (growth74): the overlap oracles' broad phase through grids of boxes (BoxGrid,
// src/oracle/box_grid.hpp) instead of scans of the other part — PairOverlap::classify's edge
// pairs (a lazy block of the first part at a time against the grid of the second part's edge
// boxes), PairOverlap::certainly_overlapping's blocks (the first part's blocks asked of a grid of
// their body-frame disks with the second part's box brought back, the second part's blocks of a
// grid of its block boxes) and the algebraic oracle's curved relation (its candidate edge pairs
// from a grid of the second part's posed boxes).
//
//  1. BoxGrid itself: on generated boxes (clustered, spread, degenerate, huge, not finite) and
//     queries, every box meeting the query is listed, ascending, once; a box with a bound not
//     finite is listed for every query. Mutants caught: the last column or row of a span left
//     out, the cell index rounded instead of floored.
//  2. On generated gear pairs of several tooth counts, at random chart points and at points
//     bisected to 2^-40 of the chart from the boundary between apart and overlapping (planted
//     near-touching configurations, where the most edge pairs are near and the exact tests run),
//     the gridded classify and the gridded algebraic relation equal the unfiltered exact oracle
//     (analyse_overlap with exact_only: no interval filter, no blocks, no grid), and the
//     algebraic relation with every pair tested (set_lazy_placement(false)); the filter over
//     boxes about those points is the eager filter's answer (every edge posed), and where it
//     answers, the exact oracle at the box's middle says overlapping. Mutants caught: the
//     first part's blocks windowed by a wrong inverse map (a sign of the rotation flipped), a
//     classify block skipped when its partners are not empty.
#include "algebra/exact_real.hpp"
#include "curves/algebraic_overlap.hpp"
#include "curves/contact_curves.hpp"
#include "oracle/box_grid.hpp"
#include "oracle/filter_counts.hpp"
#include "oracle/overlap.hpp"
#include "spur_gear_pairs.hpp"
#include "test_seed.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Bounds = cspace::BoxGrid::Bounds;

bool finite(const Bounds& b) {
  for (double v : b)
    if (!std::isfinite(v)) return false;
  return true;
}

// closed boxes sharing a point (both finite)
bool meets(const Bounds& a, const Bounds& b) {
  return a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3];
}

TEST(OracleBoxGrid, ListsEveryBoxMeetingTheQueryAscendingOnce) {
  std::mt19937_64 random(test::test_seed(7401));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity(),
               nan = std::numeric_limits<double>::quiet_NaN();
  // (the listing's size is bounded for the spread and clustered sets only: a few very wide boxes
  // stretch a uniform grid over empty space)
  std::size_t queries = 0, listed_total = 0, meeting_total = 0;
  for (int trial = 0; trial < 60; ++trial) {
    // a scale and an offset far from 0 sometimes (rounding in (v - origin) / size)
    const double scale = std::ldexp(1.0, static_cast<int>(random() % 80) - 40);
    const double offset =
        (random() % 3 == 0) ? std::ldexp(1.0, static_cast<int>(random() % 60)) : 0.0;
    const std::size_t n = 1 + random() % 400;
    const int kind =
        static_cast<int>(trial % 4);  // spread, clustered along a circle, degenerate, mixed
    std::vector<Bounds> boxes;
    for (std::size_t i = 0; i < n; ++i) {
      double x, y, w, h;
      if (kind == 1) {
        const double t = unit(random) * 6.283185307179586;
        x = std::cos(t), y = std::sin(t);
        w = h = 0.02 * unit(random);
      } else {
        x = unit(random), y = unit(random);
        w = (kind == 2 && random() % 2) ? 0.0 : 0.1 * unit(random) * unit(random);
        h = (kind == 2 && random() % 2) ? 0.0 : 0.1 * unit(random) * unit(random);
      }
      Bounds b{offset + scale * x, offset + scale * (x + w), offset + scale * y,
               offset + scale * (y + h)};
      if (kind == 3 && random() % 40 == 0) b[1] = scale * 1e3;  // a few wide ones
      if (kind == 3 && random() % 60 == 0)
        b[random() % 4] = (random() % 2) ? nan : (random() % 2 ? inf : -inf);
      boxes.push_back(b);
    }
    const cspace::BoxGrid grid(boxes);
    ASSERT_EQ(grid.size(), n);
    std::vector<std::size_t> listed;
    for (int k = 0; k < 200; ++k) {
      Bounds q;
      if (k % 3 == 0) {
        q = boxes[random() % n];  // a filed box itself (shares its own bounds)
      } else {
        const double x = -0.2 + 1.4 * unit(random), y = -0.2 + 1.4 * unit(random);
        const double w = (k % 5 == 0) ? 0.0 : 0.2 * unit(random) * unit(random),
                     h = (k % 7 == 0) ? 0.0 : 0.2 * unit(random);
        q = Bounds{offset + scale * x, offset + scale * (x + w), offset + scale * y,
                   offset + scale * (y + h)};
      }
      if (k == 199) q[0] = nan;  // a query not finite lists everything
      grid.query(q, listed);
      ++queries;
      for (std::size_t i = 1; i < listed.size(); ++i)
        ASSERT_LT(listed[i - 1], listed[i]) << "not ascending or repeated";
      for (std::size_t i : listed) ASSERT_LT(i, n);
      auto has = [&](std::size_t i) { return std::binary_search(listed.begin(), listed.end(), i); };
      for (std::size_t i = 0; i < n; ++i) {
        const bool must = !finite(q) || !finite(boxes[i]) || meets(q, boxes[i]);
        if (must && kind < 2) ++meeting_total;
        if (must && !has(i))
          FAIL() << "trial " << trial << " query " << k << ": box " << i << " [" << boxes[i][0]
                 << ", " << boxes[i][1] << "] x [" << boxes[i][2] << ", " << boxes[i][3]
                 << "] meets [" << q[0] << ", " << q[1] << "] x [" << q[2] << ", " << q[3]
                 << "] and is not listed";
      }
      if (kind < 2) listed_total += listed.size();
    }
  }
  // the grid lists few beyond the boxes that meet (it is a broad phase, not a scan)
  EXPECT_LT(listed_total, 3 * meeting_total + 2 * queries)
      << listed_total << " listed, " << meeting_total << " meeting";
  std::printf("[box grid] %zu queries: %zu listed, %zu meeting\n", queries, listed_total,
              meeting_total);
}

Rational between(const cspace::ChartAxis& axis, std::mt19937_64& random, long cells) {
  Rational r =
      axis.lo + (axis.hi - axis.lo) * Rational(static_cast<long>(random() % (cells + 1)), cells);
  r.canonicalize();
  return r;
}

const char* name_of(cspace::Overlap relation) {
  return relation == cspace::Overlap::apart         ? "apart"
         : relation == cspace::Overlap::overlapping ? "overlapping"
                                                    : "touching";
}

TEST(OracleBoxGrid, GriddedOraclesAreTheExactOracleNearContactOnGearPairs) {
  std::mt19937_64 random(test::test_seed(7402));
  std::size_t asked = 0, near_contact = 0, algebraic = 0, filtered = 0, filter_true = 0;
  std::size_t by_relation[3] = {0, 0, 0};
  for (const long z : {12L, 24L, 48L}) {
    const long z2 = z + static_cast<long>(random() % 5);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    const cspace::PairOverlap oracle(model, axes);
    cspace::OverlapOptions exact_only;
    exact_only.exact_only = true;
    // every route at q against the unfiltered exact oracle; `full`: the algebraic relation too
    auto check = [&](const cspace::ChartAxis& x, const cspace::ChartAxis& y,
                     const cspace::ChartPoint& q, bool full) {
      const std::string at = "at (" + q.x.get_str() + ", " + q.y.get_str() + ")";
      const cspace::Overlap exact =
          cspace::analyse_overlap(model, axes, x, y, q, exact_only).relation;
      const cspace::Overlap gridded = oracle.classify(x, y, q);
      EXPECT_EQ(gridded, exact) << at << ": gridded classify " << name_of(gridded) << ", exact "
                                << name_of(exact);
      ++asked;
      ++by_relation[exact == cspace::Overlap::apart         ? 0
                    : exact == cspace::Overlap::overlapping ? 1
                                                            : 2];
      if (full) {
        const auto rx = cspace::algebra::Real::from_rational(q.x),
                   ry = cspace::algebra::Real::from_rational(q.y);
        const std::optional<cspace::Overlap> relation =
            cspace::algebraic_overlap(model, axes, x, y, rx, ry);
        cspace::set_lazy_placement(false);
        const std::optional<cspace::Overlap> every_pair =
            cspace::algebraic_overlap(model, axes, x, y, rx, ry);
        cspace::set_lazy_placement(true);
        EXPECT_EQ(relation, every_pair) << at;
        if (relation) {
          EXPECT_EQ(*relation, exact) << at << ": gridded algebraic relation " << name_of(*relation)
                                      << ", exact " << name_of(exact);
          ++algebraic;
        }
      }
      return exact;
    };
    // the filter over a box of 2^-shrink of the chart about q: lazy (gridded) = eager; where it
    // answers, the exact oracle at q (inside the box) says overlapping
    auto filter = [&](const cspace::ChartAxis& x, const cspace::ChartAxis& y,
                      const cspace::ChartPoint& q, int shrink) {
      Rational xlo = q.x - Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink),
               xhi = q.x + Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink);
      Rational ylo = q.y - Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink),
               yhi = q.y + Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink);
      xlo = std::max(xlo, x.lo), xhi = std::min(xhi, x.hi), ylo = std::max(ylo, y.lo),
      yhi = std::min(yhi, y.hi);
      const kernels::Interval bx(cspace::algebra::lower_double(xlo),
                                 cspace::algebra::upper_double(xhi));
      const kernels::Interval by(cspace::algebra::lower_double(ylo),
                                 cspace::algebra::upper_double(yhi));
      cspace::set_lazy_placement(false);
      const bool eager = oracle.certainly_overlapping(x, y, bx, by);
      cspace::set_lazy_placement(true);
      const bool gridded = oracle.certainly_overlapping(x, y, bx, by);
      EXPECT_EQ(gridded, eager) << "filter about (" << q.x.get_str() << ", " << q.y.get_str()
                                << ") at 2^-" << shrink;
      if (gridded)
        EXPECT_EQ(cspace::analyse_overlap(model, axes, x, y, q, exact_only).relation,
                  cspace::Overlap::overlapping);
      ++filtered;
      filter_true += gridded;
    };
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts) {
        for (int k = 0; k < 6; ++k) {
          const cspace::ChartPoint q{between(x, random, 1 << 20), between(y, random, 1 << 20)};
          check(x, y, q, k < 2);
          filter(x, y, q, 12 + static_cast<int>(random() % 20));
        }
        // a random column's changes between apart and overlapping on a 32-step grid, bisected 40
        // times: both ends within 2^-45 of the chart of the contact boundary
        for (int column = 0; column < 6; ++column) {
          const cspace::ChartPoint start{between(x, random, 1 << 20), y.lo};
          std::optional<cspace::Overlap> previous;
          Rational previous_y = y.lo;
          int bisected = 0;
          for (long j = 0; j <= 32 && bisected < 2; ++j) {
            Rational yj = y.lo + (y.hi - y.lo) * Rational(j, 32);
            yj.canonicalize();
            const cspace::Overlap here = oracle.classify(x, y, cspace::ChartPoint{start.x, yj});
            if (previous && here != *previous && here != cspace::Overlap::touching &&
                *previous != cspace::Overlap::touching) {
              Rational lo = previous_y, hi = yj;
              for (int step = 0; step < 40; ++step) {
                Rational mid = (lo + hi) / 2;
                mid.canonicalize();
                const cspace::Overlap m = oracle.classify(x, y, cspace::ChartPoint{start.x, mid});
                if (m == cspace::Overlap::touching) break;
                (m == *previous ? lo : hi) = mid;
              }
              for (const Rational* end : {&lo, &hi}) {
                const cspace::ChartPoint q{start.x, *end};
                check(x, y, q, true);
                filter(x, y, q, 30);
                ++near_contact;
              }
              ++bisected;
            }
            previous = here;
            previous_y = yj;
          }
        }
      }
  }
  EXPECT_GT(near_contact, 20u);
  EXPECT_GT(by_relation[0], 10u);
  EXPECT_GT(by_relation[1], 10u);
  EXPECT_GT(algebraic, 30u);
  EXPECT_GT(filter_true, 5u);
  EXPECT_LT(filter_true, filtered);
  std::printf(
      "[gridded oracles] %zu points (%zu apart, %zu overlapping, %zu touching; %zu near contact), "
      "%zu algebraic, "
      "filter %zu of %zu\n",
      asked, by_relation[0], by_relation[1], by_relation[2], near_contact, algebraic, filter_true,
      filtered);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Integrator (review74 growth74 M2): finite boxes whose spread overflows the doubles (area beyond
// 1e308 from coordinates about 1e154, a side beyond it from coordinates about 1e308) made the grid
// ask for (2^20 + 1)^2 cells (a bad_alloc abort); generated sets at such coordinates, with and
// without ordinary boxes among them, list every box meeting each query, ascending, once, from a
// grid of at most one cell per few items.
TEST(OracleBoxGrid, BoxesWhoseSpreadOverflowsTheDoublesAreListedFromOneCell) {
  std::mt19937_64 random(test::test_seed(7402));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double far = std::ldexp(1.0, 500 + static_cast<int>(random() % 524));   // 2^500 .. 2^1023
    std::vector<Bounds> boxes;
    const std::size_t n = 2 + random() % 200;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = (i % 3 == 0) ? unit(random) * 10 : unit(random) * far;
      const double y = (i % 3 == 0) ? unit(random) * 10 : unit(random) * far;
      const double w = std::abs(unit(random)) * (i % 2 ? 1.0 : far * 1e-3);
      const double h = std::abs(unit(random)) * (i % 2 ? 1.0 : far * 1e-3);
      boxes.push_back({x, x + w, y, y + h});
    }
    boxes.push_back({-far, -far, -far, -far});
    boxes.push_back({far, far, far, far});
    cspace::BoxGrid grid(boxes);
    std::vector<std::size_t> listed;
    for (int q = 0; q < 50; ++q) {
      const double x = unit(random) * (q % 2 ? 10.0 : far), y = unit(random) * (q % 2 ? 10.0 : far);
      const double w = std::abs(unit(random)) * (q % 3 ? 5.0 : far);
      const Bounds query{x, x + w, y, y + w};
      grid.query(query, listed);
      ASSERT_TRUE(std::is_sorted(listed.begin(), listed.end()));
      ASSERT_TRUE(std::adjacent_find(listed.begin(), listed.end()) == listed.end());
      for (std::size_t i = 0; i < boxes.size(); ++i)
        if (meets(boxes[i], query))
          ASSERT_TRUE(std::binary_search(listed.begin(), listed.end(), i))
              << "trial " << trial << " query " << q << ": box " << i << " meets the query and is not listed";
    }
  }
}

}  // namespace
}  // namespace hipair
