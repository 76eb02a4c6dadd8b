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
//  3. (session 75) Exact touching configurations planted on gear pairs (the second gear moved
//     along the line of the pivots into a first contact at a vertex of either gear, exactly):
//     every gridded route says touching there, as the unfiltered exact oracle does, and the
//     filter declines over every box holding one. Mutant caught (not by 2): the algebraic
//     relation's second-part vertices given no candidate edges (near_[1] left empty).
//  4. (session 75) The filter's memo of the edge pairs that certified its last crossings, along
//     walks of small boxes through the charts: the eager filter's answer at every box. Mutant
//     caught: a memo pair accepted on meeting boxes without its certified crossing.
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

// Session 75 (growth75, review74 growth74 M1): exact touching configurations planted on gear
// pairs, where the routes whose pair sets the grids changed for the touching case are reached
// for certain — classify's touch points through grid_pairs, the algebraic relation's
// vertex_overlaps / common_ through near_ (a vertex of either gear exactly on the other's
// boundary), and the filter, which must decline over every box holding a touching point.
//
// The construction: at a rational chart point q where the gears are apart, the second gear is
// translated towards the first along the line of the pivots (u = pivot1 - pivot2) until their
// boundaries first meet. The translation is linear in its length s, so a vertex meeting a
// segment does so at a rational s (solved exactly); a vertex meeting an arc at a point P chosen
// exactly on the arc's circle (rational points of a circle with a rational point, here its end:
// the other end of a rational chord through it) next to where the ray from the vertex meets it,
// the translation being P - vertex. The gear moved (its loops, arc centres and pivot: posed at
// any chart value it is the former one posed there and moved) is a model of its own, posed at q.
// The first contact is found in doubles over every vertex–edge, arc–arc and segment–arc pair;
// only vertex contacts are planted, and kept where the unfiltered exact oracle (analyse_overlap
// with exact_only) says touching — that oracle is the truth the gridded routes are compared with.
namespace hipair {
namespace {

// set_lazy_placement(false) for a scope (every route's scan), restored however the scope ends
struct LazyPlacementOff {
  LazyPlacementOff() { cspace::set_lazy_placement(false); }
  ~LazyPlacementOff() { cspace::set_lazy_placement(true); }
  LazyPlacementOff(const LazyPlacementOff&) = delete;
  LazyPlacementOff& operator=(const LazyPlacementOff&) = delete;
};

struct D2 {
  double x, y;
};
D2 to_d2(const Point& p) { return D2{p.x.get_d(), p.y.get_d()}; }
D2 operator-(D2 a, D2 b) { return D2{a.x - b.x, a.y - b.y}; }
D2 operator+(D2 a, D2 b) { return D2{a.x + b.x, a.y + b.y}; }
D2 operator*(double s, D2 a) { return D2{s * a.x, s * a.y}; }
double dot(D2 a, D2 b) { return a.x * b.x + a.y * b.y; }
double cross(D2 a, D2 b) { return a.x * b.y - a.y * b.x; }

// a posed edge in doubles (and its exact posed ends and centre)
struct PosedEdge {
  Edge exact;
  D2 s, t, c;
  double r = 0;
};

std::vector<PosedEdge> posed_edges(const Part& part, const cspace::RigidMap& map) {
  std::vector<PosedEdge> out;
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      PosedEdge p;
      p.exact = edge;
      p.exact.source = map.apply(edge.source);
      p.exact.target = map.apply(edge.target);
      if (edge.is_arc()) p.exact.center = map.apply(edge.center);
      p.s = to_d2(p.exact.source), p.t = to_d2(p.exact.target), p.c = to_d2(p.exact.center);
      if (edge.is_arc()) p.r = std::sqrt(edge.radius_squared.get_d());
      out.push_back(std::move(p));
    }
  return out;
}

// a point of an arc's circle within its span (doubles; a little slack at the ends)
bool within_arc(const PosedEdge& e, D2 p) {
  if (e.exact.is_full_circle()) return true;
  const double tau = 6.283185307179586;
  auto angle = [&](D2 q) { return std::atan2(q.y - e.c.y, q.x - e.c.x); };
  double span = angle(e.t) - angle(e.s), at = angle(p) - angle(e.s);
  if (!e.exact.ccw) span = -span, at = -at;
  span = std::fmod(span + 2 * tau, tau), at = std::fmod(at + 2 * tau, tau);
  return at <= span + 1e-12 || at >= tau - 1e-12;
}

// the smallest s > 0 at which the point v + s d lies on edge e (doubles), or infinity
double ray_hit(D2 v, D2 d, const PosedEdge& e) {
  double best = HUGE_VAL;
  if (!e.exact.is_arc()) {
    const D2 ab = e.t - e.s;
    const double den = cross(d, ab);
    if (den == 0) return best;
    const double s = cross(e.s - v, ab) / den, lambda = cross(e.s - v, d) / den;
    if (s > 0 && lambda >= 0 && lambda <= 1) best = s;
    return best;
  }
  const D2 w = v - e.c;
  const double a = dot(d, d), b = 2 * dot(d, w), c = dot(w, w) - e.r * e.r;
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return best;
  for (double s : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)})
    if (s > 0 && s < best && within_arc(e, v + s * d)) best = s;
  return best;
}

// tangencies of a moving arc or segment `m` (moved by s d) with a fixed arc `f`: the smallest
// s > 0 (doubles), or infinity
double tangency_hit(const PosedEdge& m, D2 d, const PosedEdge& f) {
  double best = HUGE_VAL;
  if (!f.exact.is_arc()) return best;
  if (m.exact.is_arc()) {
    // |m.c + s d - f.c| = r_f + r_m or |r_f - r_m|
    const D2 w = m.c - f.c;
    for (double rr : {f.r + m.r, std::abs(f.r - m.r)}) {
      const double a = dot(d, d), b = 2 * dot(d, w), c = dot(w, w) - rr * rr, disc = b * b - 4 * a * c;
      if (disc < 0) continue;
      for (double s : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
        if (!(s > 0) || s >= best) continue;
        const D2 centre = m.c + s * d, between = centre - f.c;
        const double length = std::sqrt(dot(between, between));
        if (length == 0) continue;
        for (double sign : {1.0, -1.0}) {
          const D2 p = f.c + (sign * f.r / length) * between;
          const D2 q = p - centre;
          if (std::abs(std::sqrt(dot(q, q)) - m.r) < 1e-9 * (1 + m.r) && within_arc(f, p)) {
            PosedEdge moved = m;
            moved.s = m.s + s * d, moved.t = m.t + s * d, moved.c = centre;
            if (within_arc(moved, p)) best = s;
          }
        }
      }
    }
    return best;
  }
  // the segment's line at distance r_f from f.c: n . (f.c - (m.s + s d)) = +- r_f
  const D2 ab = m.t - m.s;
  const double length = std::sqrt(dot(ab, ab));
  const D2 n{-ab.y / length, ab.x / length};
  const double nd = dot(n, d);
  if (nd == 0) return best;
  for (double side : {1.0, -1.0}) {
    const double s = (dot(n, f.c - m.s) - side * f.r) / nd;
    if (!(s > 0) || s >= best) continue;
    const D2 p = f.c + (-side * f.r) * n;   // the foot of f.c on the moved line
    const double lambda = dot(p - (m.s + s * d), ab) / (length * length);
    if (lambda >= 0 && lambda <= 1 && within_arc(f, p)) best = s;
  }
  return best;
}

// a rational point of the arc's circle next to h: the other end of the chord from one of the
// arc's (rational) ends in the direction of h, the slope rounded to a double
std::optional<Point> rational_point_near(const Edge& arc, D2 h) {
  const Point& e = (dot(to_d2(arc.source) - h, to_d2(arc.source) - h) >= dot(to_d2(arc.target) - h, to_d2(arc.target) - h))
                       ? arc.source
                       : arc.target;
  const D2 d = h - to_d2(e);
  if (d.x == 0 && d.y == 0) return std::nullopt;
  Point dir = std::abs(d.x) >= std::abs(d.y) ? Point{Rational(1), Rational(d.y / d.x)}
                                             : Point{Rational(d.x / d.y), Rational(1)};
  const Rational tau = Rational(-2) * ((e.x - arc.center.x) * dir.x + (e.y - arc.center.y) * dir.y) /
                       (dir.x * dir.x + dir.y * dir.y);
  return Point{Rational(e.x + tau * dir.x), Rational(e.y + tau * dir.y)};
}

// the model with part `moved` translated by w (its loops, arc centres and pivot)
Model translated_part(const Model& model, std::size_t moved, const Point& w) {
  Model out = model;
  Part& part = out.parts.at(moved);
  auto shift = [&](Point& p) { p = Point{Rational(p.x + w.x), Rational(p.y + w.y)}; };
  for (Loop& loop : part.loops)
    for (Edge& edge : loop.edges) {
      shift(edge.source);
      shift(edge.target);
      if (edge.is_arc()) shift(edge.center);
    }
  shift(part.motion.pivot);
  return out;
}

// The translation of the pair's second part along the line of the pivots that brings the parts
// from apart (the second part moved back by the pivots' distance: its centre as far again) into
// a first contact at a vertex of either part; nullopt where the first contact found is not at a
// vertex. (At q the parts may overlap: the contact is then at a wider centre distance.)
std::optional<Point> planted_contact(const Model& model, const cspace::PairAxes& axes, const cspace::ChartAxis& x,
                                     const cspace::ChartAxis& y, const cspace::ChartPoint& q) {
  const Part& first = model.parts.at(axes.first);
  const Part& second = model.parts.at(axes.second);
  const cspace::RigidMap first_map = cspace::world_map(first, axes.first_moves, x, q.x);
  const cspace::RigidMap second_map =
      cspace::world_map(second, axes.second_moves, axes.first_moves ? y : x, axes.first_moves ? q.y : q.x);
  const std::vector<PosedEdge> a = posed_edges(first, first_map);
  const Point u{Rational(first.motion.pivot.x - second.motion.pivot.x),
                Rational(first.motion.pivot.y - second.motion.pivot.y)};
  const D2 ud = to_d2(u), back{-ud.x, -ud.y};
  // the second part moved back by u (doubles): its moves s u (s > 0) are translations (s - 1) u
  std::vector<PosedEdge> b = posed_edges(second, second_map);
  for (PosedEdge& e : b) e.s = e.s + back, e.t = e.t + back, e.c = e.c + back;
  // (kind 0: a vertex of the second part on an edge of the first; 1: a vertex of the first on
  // an edge of the second; 2: a tangency, not planted)
  double best = HUGE_VAL;
  int kind = 2;
  std::size_t vertex = 0, edge = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = 0; j < a.size(); ++j) {
      if (const double s = ray_hit(b[i].s, ud, a[j]); s < best) best = s, kind = 0, vertex = i, edge = j;
      if (const double s = ray_hit(a[j].s, back, b[i]); s < best) best = s, kind = 1, vertex = j, edge = i;
      if (const double s = tangency_hit(b[i], ud, a[j]); s < best) best = s, kind = 2;
      if (const double s = tangency_hit(a[j], back, b[i]); s < best) best = s, kind = 2;
    }
  if (kind == 2 || !std::isfinite(best)) return std::nullopt;
  // kind 0: the second part's vertex v moves by w onto the first's edge e; kind 1: the second
  // part's edge e moves by w onto the first's vertex v (exact posed geometry, not moved back)
  const std::vector<PosedEdge> exact_b = posed_edges(second, second_map);
  const PosedEdge& v = kind == 0 ? exact_b[vertex] : a[vertex];
  const PosedEdge& e = kind == 0 ? a[edge] : exact_b[edge];
  const Point& p = v.exact.source;
  if (!e.exact.is_arc()) {
    // p + s u' on the line of e (u' = u, or -u for kind 1): the contact's exact translation s u
    const Rational ex = e.exact.target.x - e.exact.source.x, ey = e.exact.target.y - e.exact.source.y;
    const Rational den = u.x * ey - u.y * ex;
    if (sgn(den) == 0) return std::nullopt;
    Rational s = ((e.exact.source.x - p.x) * ey - (e.exact.source.y - p.y) * ex) / den;
    if (kind == 1) s = -s;
    return Point{Rational(s * u.x), Rational(s * u.y)};
  }
  // the contact point on e where e is unmoved (doubles), then a rational point of e's circle there
  const D2 hit = kind == 0 ? to_d2(p) + (best - 1) * ud : to_d2(p) + best * back + ud;
  const std::optional<Point> on = rational_point_near(e.exact, hit);
  if (!on) return std::nullopt;
  return kind == 0 ? Point{Rational(on->x - p.x), Rational(on->y - p.y)}
                   : Point{Rational(p.x - on->x), Rational(p.y - on->y)};
}

TEST(OracleBoxGrid, GriddedOraclesAreTheExactOracleAtPlantedContactsOnGearPairs) {
  std::mt19937_64 random(test::test_seed(7501));
  std::size_t tried = 0, planted = 0, touching = 0, second_vertex = 0, first_vertex = 0, algebraic_touching = 0,
              filtered = 0;
  for (const long z : {12L, 24L}) {
    const long z2 = z + static_cast<long>(random() % 5);
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z, z2, name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    cspace::OverlapOptions exact_only;
    exact_only.exact_only = true;
    exact_only.want_touches = true;
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts)
        for (int k = 0, kept = 0; k < 40 && kept < 3; ++k) {
          const cspace::ChartPoint q{between(x, random, 1 << 20), between(y, random, 1 << 20)};
          ++tried;
          const std::optional<Point> w = planted_contact(model, axes, x, y, q);
          if (!w) continue;
          ++planted;
          const Model moved = translated_part(model, axes.second, *w);
          const std::string at = "at (" + q.x.get_str() + ", " + q.y.get_str() + "), the second part moved by (" +
                                 w->x.get_str() + ", " + w->y.get_str() + ")";
          const cspace::OverlapReport exact = cspace::analyse_overlap(moved, axes, x, y, q, exact_only);
          if (exact.relation != cspace::Overlap::touching) continue;   // (another contact first)
          ++touching;
          ++kept;
          bool at_second_vertex = false, at_first_vertex = false;
          for (const cspace::TouchPoint& touch : exact.touches) {
            for (const cspace::TouchEdge& edge : touch.second_edges) at_second_vertex |= edge.at_source || edge.at_target;
            for (const cspace::TouchEdge& edge : touch.first_edges) at_first_vertex |= edge.at_source || edge.at_target;
          }
          second_vertex += at_second_vertex;
          first_vertex += at_first_vertex;
          // every route at the planted contact against the exact oracle
          const cspace::PairOverlap planted_oracle(moved, axes);
          EXPECT_EQ(planted_oracle.classify(x, y, q), cspace::Overlap::touching) << at << ": gridded classify";
          const auto rx = cspace::algebra::Real::from_rational(q.x), ry = cspace::algebra::Real::from_rational(q.y);
          const std::optional<cspace::Overlap> relation = cspace::algebraic_overlap(moved, axes, x, y, rx, ry);
          std::optional<cspace::Overlap> every_pair;
          {
            LazyPlacementOff off;
            every_pair = cspace::algebraic_overlap(moved, axes, x, y, rx, ry);
          }
          EXPECT_EQ(relation, every_pair) << at;
          if (relation) {
            EXPECT_EQ(*relation, cspace::Overlap::touching) << at << ": gridded algebraic relation " << name_of(*relation);
            algebraic_touching += *relation == cspace::Overlap::touching;
          }
          // the filter over boxes about q: q is not overlapping, so no box holding it is certainly
          // overlapping (gridded and eager)
          for (const int shrink : {12, 24, 40}) {
            const Rational hx = Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink),
                           hy = Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink);
            const kernels::Interval bx(cspace::algebra::lower_double(Rational(q.x - hx)),
                                       cspace::algebra::upper_double(Rational(q.x + hx)));
            const kernels::Interval by(cspace::algebra::lower_double(Rational(q.y - hy)),
                                       cspace::algebra::upper_double(Rational(q.y + hy)));
            EXPECT_FALSE(planted_oracle.certainly_overlapping(x, y, bx, by)) << at << " 2^-" << shrink;
            {
              LazyPlacementOff off;
              EXPECT_FALSE(planted_oracle.certainly_overlapping(x, y, bx, by)) << at << " 2^-" << shrink << " eager";
            }
            ++filtered;
          }
        }
  }
  // enough planted contacts of each kind reached every route (the seed is fixed per run)
  EXPECT_GE(touching, 12u) << tried << " chart points tried, " << planted << " planted";
  EXPECT_GE(second_vertex, 3u);
  EXPECT_GE(first_vertex, 3u);
  EXPECT_GE(algebraic_touching, 8u);
  RecordProperty("planted_touching", static_cast<int>(touching));
  RecordProperty("second_part_vertex", static_cast<int>(second_vertex));
  RecordProperty("first_part_vertex", static_cast<int>(first_vertex));
  RecordProperty("algebraic_touching", static_cast<int>(algebraic_touching));
  RecordProperty("filter_boxes", static_cast<int>(filtered));
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// Session 75 (growth75): PairOverlap::certainly_overlapping tries the edge pairs that certified
// its last crossings first (a memo per pair and thread). On generated gear pairs, walks of small
// boxes through each chart (consecutive boxes near each other, as the builder's vertices of one
// region of blocked space are; now and then a jump to a random point, so the memo holds pairs
// that certify nothing there): the filter with its memo is the eager filter (every edge posed, no
// memo) at every box, and where it answers the exact oracle at the box's middle says
// overlapping. The memo must answer some calls (the route is reached) and not all.
TEST(OracleBoxGrid, FilterMemoOfCertifiedPairsIsTheEagerFilterAlongWalks) {
  std::mt19937_64 random(test::test_seed(7502));
  std::size_t asked = 0, answered = 0, exact_checked = 0;
  const auto memo_before = cspace::overlap_filter_memo_counts();
  for (const long z : {16L, 40L}) {
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, z, z + static_cast<long>(random() % 3), name);
    SCOPED_TRACE(name);
    const cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
    const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    const cspace::PairOverlap oracle(model, axes);
    cspace::OverlapOptions exact_only;
    exact_only.exact_only = true;
    for (const cspace::ChartAxis& x : layout.x_charts)
      for (const cspace::ChartAxis& y : layout.y_charts) {
        cspace::ChartPoint q{between(x, random, 1 << 20), between(y, random, 1 << 20)};
        for (int step = 0; step < 80; ++step) {
          if (step % 16 == 15) {
            q = cspace::ChartPoint{between(x, random, 1 << 20), between(y, random, 1 << 20)};
          } else {
            // a step of up to 2^-9 of the chart, kept inside it
            auto move = [&](Rational v, const cspace::ChartAxis& axis) {
              v += (axis.hi - axis.lo) * Rational(static_cast<long>(random() % 33) - 16, 16 * 512);
              v = std::min(std::max(v, axis.lo), axis.hi);
              v.canonicalize();
              return v;
            };
            q = cspace::ChartPoint{move(q.x, x), move(q.y, y)};
          }
          const int shrink = 14 + static_cast<int>(random() % 16);
          const Rational hx = Rational(x.hi - x.lo) / Rational(mpz_class(1) << shrink),
                         hy = Rational(y.hi - y.lo) / Rational(mpz_class(1) << shrink);
          const kernels::Interval bx(cspace::algebra::lower_double(Rational(q.x - hx)),
                                     cspace::algebra::upper_double(Rational(q.x + hx)));
          const kernels::Interval by(cspace::algebra::lower_double(Rational(q.y - hy)),
                                     cspace::algebra::upper_double(Rational(q.y + hy)));
          const bool with_memo = oracle.certainly_overlapping(x, y, bx, by);
          bool eager;
          {
            LazyPlacementOff off;
            eager = oracle.certainly_overlapping(x, y, bx, by);
          }
          const std::string at = "box of 2^-" + std::to_string(shrink) + " about (" + q.x.get_str() + ", " +
                                 q.y.get_str() + ")";
          ASSERT_EQ(with_memo, eager) << at;
          ++asked;
          if (with_memo && step % 4 == 0) {
            EXPECT_EQ(cspace::analyse_overlap(model, axes, x, y, q, exact_only).relation, cspace::Overlap::overlapping)
                << at;
            ++exact_checked;
          }
        }
      }
  }
  const auto memo_after = cspace::overlap_filter_memo_counts();
  answered = memo_after[1] - memo_before[1];
  EXPECT_GT(answered, asked / 8) << "the memo answered " << answered << " of " << asked << " calls";
  EXPECT_LT(answered, asked);
  EXPECT_GT(exact_checked, 20u);
  RecordProperty("asked", static_cast<int>(asked));
  RecordProperty("memo_answered", static_cast<int>(answered));
}

}  // namespace
}  // namespace hipair
