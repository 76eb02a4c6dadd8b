// The builder's certainly-blocked tester (src/oracle/blocked_tester.hpp) against the exact
// overlap oracle. A box the tester calls blocked must contain no free and no touching
// configuration:
//  - random boxes of the example pairs' charts (fixed seed): where the tester says "blocked",
//    the parts overlap (exactly) at the box's corners and at random rational configurations;
//  - generated tangencies at scales from 1e-200 to 1e200: a rotating bar whose extreme corner
//    touches a translating wall at an exact rational configuration; no box around it, however
//    thin, is blocked, and random boxes nearby are checked as above;
//  - a part whose boundary makes a double ray-parity test count an arc junction twice (two
//    arcs meeting on the ray): the old double tester took empty space beside it for material
//    and culled the curves bounding the free channel; the C-space built from the certified
//    tester agrees with the oracle.
#include "oracle/blocked_tester.hpp"
#include "curves/contact_curves.hpp"
#include "oracle/overlap.hpp"
#include "kernels/interval.hpp"
#include "test_paths.hpp"
#include "chart_sub_axis.hpp"
#include "test_seed.hpp"
#include "random_rationals.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>

namespace hipair::cspace {
// The tester's disk sweep (private) on generated posed disks, against the test of every pair.
struct BlockedTesterProbe {
  using Set = BlockedTester::PosedSet;
  static Set make(std::vector<std::array<double, 3>> disks) {
    std::sort(disks.begin(), disks.end());
    Set set;
    set.widest = -std::numeric_limits<double>::infinity();
    for (const auto& [x, y, reach] : disks) {
      set.disks.push_back(BlockedTester::PosedDisk{x, y, reach});
      set.xs.push_back(x);
      set.widest = std::max(set.widest, reach);
    }
    return set;
  }
  static bool sweep(const Set& a, const Set& b) { return BlockedTester::overlapping(a, b); }
  // disks {x, y, reach, outer}, numbered in the order given
  static Set make_posed(const std::vector<std::array<double, 4>>& disks) {
    std::vector<BlockedTester::PosedDisk> sorted;
    for (std::size_t k = 0; k < disks.size(); ++k)
      sorted.push_back({disks[k][0], disks[k][1], disks[k][2], disks[k][3], static_cast<std::uint32_t>(k)});
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
    Set set;
    set.widest = -std::numeric_limits<double>::infinity();
    for (const auto& d : sorted) {
      set.disks.push_back(d);
      set.xs.push_back(d.x);
      set.widest = std::max(set.widest, d.reach);
    }
    return set;
  }
  static bool gather(const Set& a, const Set& b, std::vector<BlockedTester::DiskPair>& out) {
    return BlockedTester::gather(a, b, out);
  }
  // The candidate loop of BlockedTester::blocked (a list of candidates, `narrowed` wanted) by
  // its definition, on disks posed afresh for the box: each pair of the list in order, both
  // disks posed with the parts' pose bounds over the box (a pair with a disk not finite is
  // skipped); the answer is "blocked" when some pair passes the certified test; otherwise the
  // kept pairs are those whose posed centres are within the outer sum (may_certify_inside's
  // double test), the pairs whose nominal disks overlap first, each group in list order.
  static bool candidate_loop(const BlockedTester& tester, const ChartAxis& x_axis, const ChartAxis& y_axis,
                             const algebra::Interval& x, const algebra::Interval& y,
                             const std::vector<BlockedTester::DiskPair>& candidates,
                             std::vector<BlockedTester::DiskPair>& kept) {
    using kernels::interval_detail::down;
    using kernels::interval_detail::up;
    kept.clear();
    BlockedTester::PoseBound poses[2];
    bool x_used = false;
    for (int k = 0; k < 2; ++k) {
      const bool use_x = !x_used;
      if (tester.moves_[k]) x_used = true;
      poses[k] = tester.pose_bound(k, use_x ? x_axis : y_axis, use_x ? x : y);
      if (!poses[k].usable) return false;
    }
    std::vector<BlockedTester::DiskPair> later;
    for (const auto& pair : candidates) {
      BlockedTester::PosedDisk a, b;
      if (!tester.pose_disk(0, poses[0], pair.first, a) || !tester.pose_disk(1, poses[1], pair.second, b)) continue;
      const double dx = up(std::fabs(a.x - b.x)), dy = up(std::fabs(a.y - b.y));
      const double reach = down(a.reach + b.reach);
      if (reach > 0 && up(up(dx * dx) + up(dy * dy)) < down(reach * reach)) {
        kept.clear();
        return true;
      }
      const double ex = a.x - b.x, ey = a.y - b.y, outer = a.outer + b.outer;
      if (!(outer > 0) || !(ex * ex + ey * ey <= outer * outer * (1 + 0x1p-20) + 0x1p-1000)) continue;
      const double nominal = 0.5 * (a.outer + b.outer + a.reach + b.reach);
      (nominal > 0 && ex * ex + ey * ey < nominal * nominal ? kept : later).push_back(pair);
    }
    kept.insert(kept.end(), later.begin(), later.end());
    return false;
  }
  // every pair, the certified test of the tester's definition
  static bool all_pairs(const Set& first, const Set& second) {
    using kernels::interval_detail::down;
    using kernels::interval_detail::up;
    for (const auto& a : first.disks)
      for (const auto& b : second.disks) {
        double dx = up(std::fabs(a.x - b.x)), dy = up(std::fabs(a.y - b.y));
        double reach = down(a.reach + b.reach);
        if (reach > 0 && up(up(dx * dx) + up(dy * dy)) < down(reach * reach)) return true;
      }
    return false;
  }
};
}  // namespace hipair::cspace

namespace hipair {
namespace {

// The sweep's windows (twice each disk's own reach, from either side) leave out no pair that
// passes the certified test: the same answer as testing every pair, on generated sets with
// reaches from tiny to one huge disk, negative reaches (boundary points), near-tangent pairs
// and coordinates far from the origin.
TEST(BlockedTester, DiskSweepAnswersAsEveryPair) {
  using Probe = cspace::BlockedTesterProbe;
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> unit(0, 1);
  int overlapping = 0, apart = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double offset = trial % 3 == 0 ? 0 : std::ldexp(unit(random) - 0.5, static_cast<int>(trial % 60));
    const double scale = std::ldexp(1.0, static_cast<int>(trial % 40) - 20);
    std::vector<std::array<double, 3>> sets[2];
    for (auto& set : sets) {
      const int count = 1 + static_cast<int>(unit(random) * 40);
      for (int k = 0; k < count; ++k) {
        double reach = scale * (unit(random) < 0.2 ? -unit(random) * 0.01 : unit(random) * 0.05);
        if (unit(random) < 0.05) reach = scale * (1 + 4 * unit(random));   // a hub
        set.push_back({offset + scale * 4 * unit(random), scale * 4 * unit(random), reach});
      }
    }
    // a pair made nearly tangent: centre distance r_a + r_b times (1 +- 2^-40)
    if (trial % 2 == 1 && sets[0][0][2] > 0 && sets[1][0][2] > 0) {
      double distance = (sets[0][0][2] + sets[1][0][2]) * (1 + (trial % 4 == 1 ? 1 : -1) * 0x1p-40);
      double angle = 6.283185307179586 * unit(random);
      sets[1][0][0] = sets[0][0][0] + distance * std::cos(angle);
      sets[1][0][1] = sets[0][0][1] + distance * std::sin(angle);
    }
    const auto a = Probe::make(sets[0]), b = Probe::make(sets[1]);
    const bool expected = Probe::all_pairs(a, b);
    ASSERT_EQ(Probe::sweep(a, b), expected) << "trial " << trial;
    ASSERT_EQ(Probe::sweep(b, a), expected) << "trial " << trial;
    (expected ? overlapping : apart) += 1;
  }
  EXPECT_GT(overlapping, 400);
  EXPECT_GT(apart, 400);
}

// The gathered candidate list of a box (BlockedTester::blocked with `narrowed`, no candidates:
// the two sweeps of gather, each pair from the side of its larger outer bound) against every
// pair: "blocked" exactly when some pair passes the certified test, and otherwise exactly the
// pairs whose posed centres are closer than the sum of their outer bounds (the double test of
// the tester's definition, may_certify_inside), each once, sorted by (first, second). Generated
// sets: outer bounds from tiny to a hub's, equal outer bounds across the parts (ties), pairs
// nearly at the kept distance (1 +- 2^-30 of the outer sum), coordinates far from the origin.
TEST(BlockedTester, GatheredCandidatesAreEveryPairThatMayCertifyInside) {
  using Probe = cspace::BlockedTesterProbe;
  using kernels::interval_detail::down;
  using kernels::interval_detail::up;
  using Pair = cspace::BlockedTester::DiskPair;
  std::mt19937_64 random(20261130);
  std::uniform_real_distribution<double> unit(0, 1);
  int certified = 0, listed = 0, ties = 0, near = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double offset = trial % 3 == 0 ? 0 : std::ldexp(unit(random) - 0.5, static_cast<int>(trial % 60));
    const double scale = std::ldexp(1.0, static_cast<int>(trial % 40) - 20);
    std::vector<std::array<double, 4>> sets[2];
    for (auto& set : sets) {
      const int count = 1 + static_cast<int>(unit(random) * 40);
      for (int k = 0; k < count; ++k) {
        const double r = scale * (unit(random) < 0.2 ? 0 : unit(random) * 0.05);
        const double error = scale * unit(random) * (trial % 2 ? 0.002 : 0.04);
        double reach = r - error, outer = r + error;
        if (unit(random) < 0.05) reach = outer = scale * (1 + 4 * unit(random));   // a hub
        set.push_back({offset + scale * 4 * unit(random), scale * 4 * unit(random), reach, outer});
      }
    }
    if (trial % 4 == 1) {   // ties: outer bounds equal across the parts
      for (std::size_t k = 0; k < std::min(sets[0].size(), sets[1].size()); k += 2)
        if (sets[1][k][2] <= sets[0][k][3]) sets[1][k][3] = sets[0][k][3];   // (reach <= outer kept)
    }
    if (trial % 4 == 3) {   // a pair at the kept distance, times 1 +- 2^-30
      const double distance = (sets[0][0][3] + sets[1][0][3]) * (1 + (trial % 8 == 3 ? 1 : -1) * 0x1p-30);
      const double angle = 6.283185307179586 * unit(random);
      sets[1][0][0] = sets[0][0][0] + distance * std::cos(angle);
      sets[1][0][1] = sets[0][0][1] + distance * std::sin(angle);
    }
    const auto a = Probe::make_posed(sets[0]), b = Probe::make_posed(sets[1]);
    bool expected_blocked = false;
    std::vector<Pair> expected;
    for (const auto& p : a.disks)
      for (const auto& q : b.disks) {
        ties += p.outer == q.outer;
        // the certified test (certifies) and the kept test (may_certify_inside) of blocked_tester.cpp
        const double plain_dx = p.x - q.x, plain_dy = p.y - q.y, plain_reach = p.reach + q.reach;
        if (plain_reach > 0 && plain_dx * plain_dx + plain_dy * plain_dy < plain_reach * plain_reach) {
          const double dx = up(std::fabs(plain_dx)), dy = up(std::fabs(plain_dy));
          const double reach = down(p.reach + q.reach);
          if (reach > 0 && up(up(dx * dx) + up(dy * dy)) < down(reach * reach)) expected_blocked = true;
        }
        const double s = p.outer + q.outer;
        if (s > 0 && plain_dx * plain_dx + plain_dy * plain_dy <= s * s * (1 + 0x1p-20) + 0x1p-1000)
          expected.push_back({p.index, q.index});
      }
    std::sort(expected.begin(), expected.end(),
              [](const Pair& p, const Pair& q) { return p.first != q.first ? p.first < q.first : p.second < q.second; });
    near += trial % 4 == 3;
    std::vector<Pair> got;
    const bool got_blocked = Probe::gather(a, b, got);
    ASSERT_EQ(got_blocked, expected_blocked) << "trial " << trial;
    if (got_blocked) {
      ++certified;
      continue;
    }
    ASSERT_EQ(got.size(), expected.size()) << "trial " << trial;
    // the list runs over A's disks in groups (each first disk's pairs together: the candidate
    // loop poses a first disk once per run); its order decides only the work, so it is compared
    // as a set
    for (std::size_t k = 1; k < got.size(); ++k)
      if (got[k].first != got[k - 1].first)
        for (std::size_t m = 0; m + 1 < k; ++m)
          ASSERT_NE(got[m].first, got[k].first) << "trial " << trial << ": disk " << got[k].first << " in two runs";
    std::sort(got.begin(), got.end(),
              [](const Pair& p, const Pair& q) { return p.first != q.first ? p.first < q.first : p.second < q.second; });
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].first, expected[k].first) << "trial " << trial << " pair " << k;
      ASSERT_EQ(got[k].second, expected[k].second) << "trial " << trial << " pair " << k;
    }
    listed += !got.empty();
  }
  std::cout << certified << " blocked, " << listed << " with candidates, " << ties << " tied pairs\n";
  EXPECT_GT(certified, 400);
  EXPECT_GT(listed, 150);
  EXPECT_GT(ties, 1000);
  EXPECT_GT(near, 500);
}

using Random = std::mt19937_64;
using cspace::algebra::Interval;

struct Counts {
  int boxes = 0, blocked = 0, points = 0;
};

// A rational in the double interval [a, b].
Rational pick(Random& random, const Interval& range) {
  Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
  u.canonicalize();
  return Rational(Rational(range.lo) + u * (Rational(range.hi) - Rational(range.lo)));
}

// Wherever the tester says the box is blocked, the oracle says overlapping at its corners and
// at `samples` random rational configurations in it.
void check_blocked_box(const Model& model, const cspace::PairAxes& axes, const cspace::ChartAxis& x,
                       const cspace::ChartAxis& y, const Interval& bx, const Interval& by, bool two_d, int samples,
                       Random& random, Counts& counts, const std::string& what) {
  std::vector<cspace::ChartPoint> points;
  for (double cx : {bx.lo, bx.hi})
    for (double cy : {by.lo, by.hi}) points.push_back({Rational(cx), two_d ? Rational(cy) : Rational(0)});
  for (int k = 0; k < samples; ++k) points.push_back({pick(random, bx), two_d ? pick(random, by) : Rational(0)});
  for (const auto& q : points) {
    ++counts.points;
    EXPECT_EQ(cspace::classify_overlap(model, axes, x, y, q), cspace::Overlap::overlapping)
        << what << " box [" << bx.lo << ", " << bx.hi << "] x [" << by.lo << ", " << by.hi << "] at " << q.x << ", "
        << q.y;
  }
}

Counts check_pair(const std::string& file, const std::string& first, const std::string& second, int boxes, int samples,
                  std::uint64_t seed) {
  Counts counts;
  std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
  if (!std::filesystem::exists(path)) return counts;
  Model model = read_model_file(path);
  cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part(first), *model.find_part(second));
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  cspace::BlockedTester tester(model, axes);
  EXPECT_TRUE(tester.usable()) << file;
  const bool two_d = !layout.y_charts.empty();
  Random random(seed);
  auto unit = [&] { return std::ldexp(static_cast<double>(random() >> 11), -53); };   // [0, 1)
  // a double box [a, b] inside [lo, hi], of width (hi - lo) 2^-k, k in 1..9
  auto box = [&](const Rational& lo, const Rational& hi) {
    double l = lo.get_d(), h = hi.get_d();
    double width = (h - l) * std::ldexp(1.0, -static_cast<int>(1 + random() % 9));
    double a = l + unit() * (h - l - width);
    double b = a + width;
    return Interval{a, std::max(a, b)};
  };
  for (int i = 0; i < boxes; ++i) {
    const cspace::ChartAxis& x = layout.x_charts[random() % layout.x_charts.size()];
    cspace::ChartAxis y = two_d ? layout.y_charts[random() % layout.y_charts.size()]
                                : cspace::ChartAxis{cspace::ChartAxis::Kind::translation, false, Rational(0), Rational(0)};
    Interval bx = box(x.lo, x.hi);
    Interval by = two_d ? box(y.lo, y.hi) : Interval{0, 0};
    ++counts.boxes;
    if (!tester.blocked(x, y, bx, by)) continue;
    ++counts.blocked;
    check_blocked_box(model, axes, x, y, bx, by, two_d, samples, random, counts, file);
  }
  return counts;
}

TEST(BlockedTester, BlockedBoxesOfTheExamplesOverlapEverywhere) {
  struct Pair {
    const char* file;
    const char* first;
    const char* second;
    int boxes;
  };
  for (const Pair& pair : {Pair{"geneva.json", "driver", "wheel", 400}, Pair{"ratchet.json", "wheel", "pawl", 400},
                           Pair{"cam-follower.json", "cam", "follower", 400},
                           Pair{"spur-gears.json", "pinion", "gear", 150}}) {
    Counts counts = check_pair(pair.file, pair.first, pair.second, pair.boxes, 6, 20261124);
    if (counts.boxes == 0) continue;   // example not shipped
    // the property must not hold vacuously
    EXPECT_GT(counts.blocked, 20) << pair.file;
    std::cout << pair.file << ": " << counts.blocked << " of " << counts.boxes << " boxes blocked, " << counts.points
              << " configurations checked\n";
  }
}

// ---------------------------------------------------------------- generated tangencies

// A random rational in [lo, hi] with a denominator up to `den`.
using test_numbers::random_rational;

std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }

// A bar [0, L] x [-w, w] rotating about the origin and a wall (body: x in [0, D], |y| <= H)
// translating along x. Lengths are multiplied by `scale`.
std::string bar_and_wall(const Rational& L, const Rational& w, const Rational& D, const Rational& H,
                         const Rational& reach) {
  auto point = [](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
  return R"({ "hipair": 1, "name": "bar-and-wall",
    "parts": [
      { "name": "bar", "motion": { "rotation": { "pivot": [0, 0] } },
        "loops": [ { "start": )" + point(0, -w) + R"(, "edges": [ { "line_to": )" + point(L, -w) +
         R"( }, { "line_to": )" + point(L, w) + R"( }, { "line_to": )" + point(0, w) + R"( }, { "line_to": )" +
         point(0, -w) + R"( } ] } ] },
      { "name": "wall", "motion": { "translation": { "direction": [1, 0], "limits": [)" + text(-reach) + ", " +
         text(reach) + R"(] } },
        "loops": [ { "start": )" + point(0, -H) + R"(, "edges": [ { "line_to": )" + point(D, -H) +
         R"( }, { "line_to": )" + point(D, H) + R"( }, { "line_to": )" + point(0, H) + R"( }, { "line_to": )" +
         point(0, -H) + R"( } ] } ] } ],
    "pairs": [ { "parts": ["bar", "wall"] } ] })";
}

TEST(BlockedTester, NoBoxAroundATangencyIsBlockedAtAnyScale) {
  Random random(20261124);
  int thin_boxes = 0, blocked_nearby = 0;
  Counts counts;
  for (int exponent : {-200, -30, -3, 0, 3, 30, 200}) {
    Rational scale = 1;
    mpz_class power;
    mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(exponent)));
    scale = exponent >= 0 ? Rational(power) : Rational(mpz_class(1), power);
    scale.canonicalize();
    for (int trial = 0; trial < 6; ++trial) {
      Rational L = scale * random_rational(random, 2, 10), w = scale * random_rational(random, Rational(1, 10), 1);
      Rational D = scale * random_rational(random, Rational(1, 2), 3);
      Rational H = 2 * (L + w), reach = 2 * (L + w + D);
      Model model = read_model(bar_and_wall(L, w, D, H, reach));
      cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
      cspace::ChartLayout layout = cspace::chart_layout(model, axes);
      cspace::BlockedTester tester(model, axes);
      ASSERT_TRUE(tester.usable());
      const cspace::ChartAxis& x = layout.x_charts[random() % layout.x_charts.size()];
      const cspace::ChartAxis& y = layout.y_charts[0];
      // the tangency: t0 in the chart, the wall's face on the bar's extreme corner
      Rational t0 = random_rational(random, x.lo, x.hi, 1000);
      Rational t2 = t0 * t0;
      Rational c = (1 - t2) / (1 + t2), s = 2 * t0 / (1 + t2);
      if (x.half_turn) {
        c = -c;
        s = -s;
      }
      Rational s0;
      bool first = true;
      for (const auto& [px, py] : {std::pair{Rational(0), Rational(-w)}, std::pair{L, Rational(-w)},
                                   std::pair{L, w}, std::pair{Rational(0), w}}) {
        Rational rx = c * px - s * py;
        if (first || rx > s0) s0 = rx;
        first = false;
      }
      s0.canonicalize();
      const cspace::ChartPoint touch{t0, s0};
      ASSERT_EQ(cspace::classify_overlap(model, axes, x, y, touch), cspace::Overlap::touching)
          << "the generated configuration is a tangency";
      const kernels::Interval ex = kernels::Interval::enclose(t0), ey = kernels::Interval::enclose(s0);
      // boxes around the tangency, from 2^-1 down to 2^-60 of the chart wide (and degenerate)
      for (int k = 1; k <= 60; k += 3) {
        double wx = std::ldexp(Rational(x.hi - x.lo).get_d(), -k), wy = std::ldexp(Rational(y.hi - y.lo).get_d(), -k);
        for (int side = 0; side < 4; ++side) {
          double ax = side & 1 ? wx : 0, ay = side & 2 ? wy : 0;
          Interval bx{ex.lo - ax, ex.hi + (wx - ax)}, by{ey.lo - ay, ey.hi + (wy - ay)};
          if (k == 58) bx = {ex.lo, ex.hi}, by = {ey.lo, ey.hi};
          ++thin_boxes;
          EXPECT_FALSE(tester.blocked(x, y, bx, by))
              << "scale 1e" << exponent << ": a box around the tangency (" << t0 << ", " << s0 << ") is blocked";
        }
      }
      // boxes beside the tangency (on the wall's side, into the overlap): when blocked, overlapping
      for (int k = 2; k <= 40; k += 2) {
        double wx = std::ldexp(Rational(x.hi - x.lo).get_d(), -k), wy = std::ldexp(Rational(y.hi - y.lo).get_d(), -k);
        double gap = std::ldexp(wy, -(static_cast<int>(random() % 8)));
        Interval bx{ex.lo - 0.5 * wx, ex.hi + 0.5 * wx}, by{ey.lo - gap - wy, ey.lo - gap};
        if (!tester.blocked(x, y, bx, by)) continue;
        ++blocked_nearby;
        check_blocked_box(model, axes, x, y, bx, by, true, 2, random, counts, "bar and wall");
      }
    }
  }
  EXPECT_GT(thin_boxes, 1000);
  EXPECT_GT(blocked_nearby, 20) << "the boxes beside the tangency must sometimes be blocked (not vacuous)";
  std::cout << thin_boxes << " boxes around tangencies, " << blocked_nearby << " blocked boxes beside them\n";
}

// ---------------------------------------------------------------- ray parity at an arc junction

// A frame rotating about (17.5, 19.5): a bar [0, 10] x [0, 40] and a disk of radius 5 about
// (30, 19.5) drawn as two arcs meeting at (25, 19.5), on the row y = 19.5 of candidate disk
// centres; a square slider translating along x in the channel between them. Every point of the
// row between the bar and the disk is outside the frame, but a double parity test counts the
// junction once per arc.
const char* const parity_model = R"({ "hipair": 1, "name": "arc-junction",
  "parts": [
    { "name": "frame", "motion": { "rotation": { "pivot": [17.5, 19.5] } },
      "loops": [
        { "start": [0, 0], "edges": [ { "line_to": [10, 0] }, { "line_to": [10, 40] }, { "line_to": [0, 40] }, { "line_to": [0, 0] } ] },
        { "start": [25, 19.5], "edges": [ { "arc_to": [30, 14.5], "center": [30, 19.5], "dir": "ccw" },
                                          { "arc_to": [25, 19.5], "center": [30, 19.5], "dir": "ccw" } ] } ] },
    { "name": "slider", "motion": { "translation": { "direction": [1, 0], "limits": [6, 29] } }, "initial": { "offset": 17.5 },
      "loops": [ { "start": [-1, 18.5], "edges": [ { "line_to": [1, 18.5] }, { "line_to": [1, 20.5] }, { "line_to": [-1, 20.5] }, { "line_to": [-1, 18.5] } ] } ] } ],
  "pairs": [ { "parts": ["frame", "slider"] } ] })";

TEST(BlockedTester, EmptySpaceBesideAnArcJunctionIsNotMaterial) {
  Model model = read_model(parity_model);
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  cspace::BlockedTester tester(model, axes);
  // the frame at angle 0 (t = 0) with the slider anywhere in the channel: free
  const cspace::ChartAxis& x = layout.x_charts[0];
  const cspace::ChartAxis& y = layout.y_charts[0];
  ASSERT_FALSE(x.half_turn);
  ASSERT_EQ(cspace::classify_overlap(model, axes, x, y, {Rational(0), Rational(35, 2)}), cspace::Overlap::apart);
  for (double s : {13.0, 15.0, 17.5, 20.0, 22.0})
    EXPECT_FALSE(tester.blocked(x, y, Interval{-1e-6, 1e-6}, Interval{s - 1e-6, s + 1e-6})) << "slider at " << s;
}

TEST(BlockedTester, CSpaceBesideAnArcJunctionAgreesWithTheOracle) {
  Model model = read_model(parity_model);
  CSpace space = CSpace::build(model, "frame", "slider");
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  const std::size_t y_count = layout.y_charts.size();
  Random random(20261124);
  int free = 0, blocked = 0;
  for (int i = 0; i < 1500; ++i) {
    std::size_t c = random() % space.charts().size();
    const CSpaceChart& chart = space.charts()[c];
    auto pick_in = [&](const Rational& lo, const Rational& hi) {
      Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
      u.canonicalize();
      return Rational(lo + u * (hi - lo));
    };
    ChartPoint q{c, pick_in(chart.x_lo, chart.x_hi), pick_in(chart.y_lo, chart.y_hi)};
    Location location = space.locate(q);
    cspace::Overlap overlap = cspace::classify_overlap(model, axes, layout.x_charts[c / y_count],
                                                       layout.y_charts[c % y_count], cspace::ChartPoint{q.x, q.y});
    if (location.kind == Location::Kind::free) {
      ++free;
      EXPECT_EQ(overlap, cspace::Overlap::apart) << "chart " << c << " at " << q.x << ", " << q.y;
    } else if (location.kind == Location::Kind::blocked) {
      ++blocked;
      EXPECT_EQ(overlap, cspace::Overlap::overlapping) << "chart " << c << " at " << q.x << ", " << q.y;
    }
  }
  EXPECT_GT(free, 100);
  EXPECT_GT(blocked, 100);
}

// The cache of posed disks (one per chart, as the builder's culling and the region flood use
// it) gives the same answer as the uncached test on every box of a grid of nested boxes (the
// quadtree's pattern: each column and row interval shared by many boxes), on the examples'
// charts.
// Calls f(file, model, axes, layout) for each example pair {file, first, second} with a 2-D C-space.
template <class F>
void for_each_two_d_pair(std::initializer_list<std::tuple<const char*, const char*, const char*>> pairs, F&& f) {
  for (const auto& [file, first, second] : pairs) {
    std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
    if (!std::filesystem::exists(path)) continue;
    Model model = read_model_file(path);
    auto a = model.find_part(first), b = model.find_part(second);
    if (!a || !b) continue;
    cspace::PairAxes axes = cspace::pair_axes(model, *a, *b);
    cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    if (layout.y_charts.empty()) continue;
    f(std::string(file), model, axes, layout);
  }
}

// `check(what, model, axes, layout, count)` on the examples' two-dimensional pairs (Geneva,
// ratchet, escapement: `example_count` each) and on two generated bar-and-wall pairs (random
// rationals) at each of the scales 1e-200, 1 and 1e200 (`bar_count` each).
template <class F>
void on_examples_and_bar_walls(Random& random, int example_count, int bar_count, F&& check) {
  for_each_two_d_pair({{"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"},
                       {"escapement.json", "escape-wheel", "anchor"}},
                      [&](const std::string& file, const Model& model, const cspace::PairAxes& axes,
                          const cspace::ChartLayout& layout) { check(file, model, axes, layout, example_count); });
  for (int exponent : {-200, 0, 200}) {
    mpz_class power;
    mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(exponent)));
    Rational scale = exponent >= 0 ? Rational(power) : Rational(mpz_class(1), power);
    scale.canonicalize();
    for (int trial = 0; trial < 2; ++trial) {
      Rational L = scale * random_rational(random, 2, 10), w = scale * random_rational(random, Rational(1, 10), 1);
      Rational D = scale * random_rational(random, Rational(1, 2), 3);
      Model model = read_model(bar_and_wall(L, w, D, 2 * (L + w), 2 * (L + w + D)));
      cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
      check("bar and wall 1e" + std::to_string(exponent), model, axes, cspace::chart_layout(model, axes), bar_count);
    }
  }
}

TEST(BlockedTester, CachedAnswersEqualUncachedOnes) {
  int blocked = 0, boxes = 0;
  for_each_two_d_pair({{"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"},
                       {"scotch-yoke.json", "crank", "yoke"}},
                      [&](const std::string& file, const Model& model, const cspace::PairAxes& axes,
                          const cspace::ChartLayout& layout) {
    cspace::BlockedTester tester(model, axes);
    for (const auto& x : layout.x_charts)
      for (const auto& y : layout.y_charts) {
        cspace::BlockedTester::Cache cache;
        const double x_lo = x.lo.get_d(), x_hi = x.hi.get_d(), y_lo = y.lo.get_d(), y_hi = y.hi.get_d();
        for (int depth : {3, 4, 5}) {
          const int n = 1 << depth;
          for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
              Interval bx{x_lo + (x_hi - x_lo) * i / n, x_lo + (x_hi - x_lo) * (i + 1) / n};
              Interval by{y_lo + (y_hi - y_lo) * j / n, y_lo + (y_hi - y_lo) * (j + 1) / n};
              const bool plain = tester.blocked(x, y, bx, by);
              EXPECT_EQ(tester.blocked(x, y, bx, by, cache), plain) << file << " box " << i << ", " << j << " at depth " << depth;
              ++boxes;
              blocked += plain;
            }
        }
      }
  });
  std::cout << blocked << " of " << boxes << " boxes blocked\n";
  EXPECT_GT(blocked, 100);
}


// The disk sweep bucketed by cell (BlockedCells: each cell tests only the candidate pairs its
// nearest tested ancestor left, BlockedTester::blocked with `narrowed`) gives the answer of the
// full sweep on every cell of a quadtree, tested depth first as the builder does (to depth 6,
// every depth or every other depth), on the examples' charts; a cell's list is part of its
// parent's.
TEST(BlockedTester, CandidateListsOfEnclosingCellsGiveTheSweepsAnswers) {
  int blocked = 0, cells = 0;
  std::size_t pairs = 0;
  for_each_two_d_pair({{"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"},
                       {"escapement.json", "escape-wheel", "anchor"}, {"scotch-yoke.json", "crank", "yoke"}},
                      [&](const std::string& file, const Model& model, const cspace::PairAxes& axes,
                          const cspace::ChartLayout& layout) {
    auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
    for (int step : {1, 2})
      for (const auto& x : layout.x_charts)
        for (const auto& y : layout.y_charts) {
          cspace::BlockedCells grid(tester, x, y, 2, 6);
          cspace::BlockedTester::Cache cache;
          // depth first over the quadtree, the cells of depths 1, 1 + step, ... tested
          std::function<void(int, long, long, const std::vector<cspace::BlockedTester::DiskPair>*)> visit =
              [&](int depth, long i, long j, const std::vector<cspace::BlockedTester::DiskPair>* parent_list) {
                const Interval bx = grid.cell_x(depth, i), by = grid.cell_y(depth, j);
                const bool plain = tester->blocked(x, y, bx, by);
                const bool gridded = grid.blocked(depth, i, j);
                ++cells;
                // (no cell visited lies inside a blocked one: the grid tests each)
                EXPECT_EQ(gridded, plain) << file << " cell " << depth << ", " << i << ", " << j;
                std::vector<cspace::BlockedTester::DiskPair> list;
                const bool listed = tester->blocked(x, y, bx, by, cache, parent_list, &list);
                EXPECT_EQ(listed, plain) << file << " cell " << depth << ", " << i << ", " << j;
                if (parent_list) {
                  // every pair of this cell's list is in the parent's (narrowing only drops pairs)
                  for (const auto& p : list)
                    EXPECT_TRUE(std::any_of(parent_list->begin(), parent_list->end(), [&](const auto& q) {
                      return q.first == p.first && q.second == p.second;
                    }));
                }
                pairs += list.size();
                blocked += plain;
                if (plain || depth + step > 6) return;
                for (long di = 0; di < (1L << step); ++di)
                  for (long dj = 0; dj < (1L << step); ++dj) visit(depth + step, (i << step) + di, (j << step) + dj, &list);
              };
          for (long i = 0; i < 2; ++i)
            for (long j = 0; j < 2; ++j) visit(1, i, j, nullptr);
        }
  });
  std::cout << blocked << " of " << cells << " cells blocked, " << pairs << " candidate pairs kept\n";
  EXPECT_GT(blocked, 100);
}

// The posed disks kept per pose (BlockedTester::Cache: a candidate disk posed once for every
// cell of the column or row sharing its pose) answer as disks posed afresh: cells of every
// depth to 8, visited in random order with one cache per chart, each tested with the candidate
// list of an enclosing cell both with the shared cache and with a fresh cache of its own —
// the same answer and the same narrowed list (pairs and order), the answer that of the full
// sweep, and where blocked, the parts overlap (the exact oracle) at a random rational
// configuration of the cell. On the examples' charts and on generated bar-and-wall pairs
// (random rationals) at scales 1e-200 to 1e200.
TEST(BlockedTester, PosedDisksKeptPerPoseAnswerAsFreshPoses) {
  using Pair = cspace::BlockedTester::DiskPair;
  Random random(20261201);
  int cells = 0, blocked = 0, reused = 0;
  Counts counts;
  auto check = [&](const std::string& what, const Model& model, const cspace::PairAxes& axes,
                   const cspace::ChartLayout& layout, int count) {
    auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
    for (const auto& x : layout.x_charts)
      for (const auto& y : layout.y_charts) {
        cspace::BlockedCells grid(tester, x, y, 2, 8);
        cspace::BlockedTester::Cache shared;
        // the candidate lists of the cells at depth 2 (full sweeps), then cells below them
        // (a blocked cell has no list: the cells inside it are blocked without a test)
        std::vector<std::vector<Pair>> lists(16);
        std::vector<char> parent_blocked(16);
        for (long i = 0; i < 4; ++i)
          for (long j = 0; j < 4; ++j) {
            cspace::BlockedTester::Cache fresh;
            parent_blocked[static_cast<std::size_t>(4 * i + j)] = tester->blocked(
                x, y, grid.cell_x(2, i), grid.cell_y(2, j), fresh, nullptr, &lists[static_cast<std::size_t>(4 * i + j)]);
          }
        std::map<std::pair<int, long>, int> columns;
        for (int k = 0; k < count; ++k) {
          const int depth = 3 + static_cast<int>(random() % 6);
          const long n = 1L << depth;
          // few columns and rows per depth: their poses are shared by many cells
          const long i = static_cast<long>(random() % static_cast<unsigned long>(std::min(n, 12L))) * (n / std::min(n, 12L));
          const long j = static_cast<long>(random() % static_cast<unsigned long>(n));
          const auto enclosing = static_cast<std::size_t>(4 * (i >> (depth - 2)) + (j >> (depth - 2)));
          if (parent_blocked[enclosing]) continue;
          const auto& parent = lists[enclosing];
          const Interval bx = grid.cell_x(depth, i), by = grid.cell_y(depth, j);
          std::vector<Pair> kept, again;
          const bool answer = tester->blocked(x, y, bx, by, shared, &parent, &kept);
          cspace::BlockedTester::Cache fresh;
          const bool fresh_answer = tester->blocked(x, y, bx, by, fresh, &parent, &again);
          ++cells;
          reused += columns[{depth, i}]++ > 0;
          ASSERT_EQ(answer, fresh_answer) << what << " cell " << depth << ", " << i << ", " << j;
          ASSERT_EQ(answer, tester->blocked(x, y, bx, by)) << what << " cell " << depth << ", " << i << ", " << j;
          ASSERT_EQ(kept.size(), again.size()) << what << " cell " << depth << ", " << i << ", " << j;
          for (std::size_t m = 0; m < kept.size(); ++m) {
            ASSERT_EQ(kept[m].first, again[m].first) << what;
            ASSERT_EQ(kept[m].second, again[m].second) << what;
          }
          if (!answer) continue;
          ++blocked;
          if (blocked % 8 == 0) check_blocked_box(model, axes, x, y, bx, by, true, 1, random, counts, what);
        }
      }
  };
  on_examples_and_bar_walls(random, 1500, 300, check);
  std::cout << blocked << " of " << cells << " cells blocked, " << reused << " in a column tested before, "
            << counts.points << " configurations of blocked cells checked with the oracle\n";
  EXPECT_GT(blocked, 1000);
  EXPECT_GT(reused, cells / 2);
}


// BlockedTester::blocked's candidate loop (session 44: the second part's posed disks read from
// the pose's slot table made whole before the loop, and the outer-sum test first, which decides
// the pairs that can neither certify nor be kept) against its definition on disks posed afresh
// (BlockedTesterProbe::candidate_loop): the same answer and, where not blocked, the same
// narrowed list, pairs and order. Cells of depths 3 to 9 of the examples' charts in random
// order, each with the list of an enclosing cell (the full sweep's of its depth-2 cell, or the
// narrowed list of a depth-5 cell tested before), one cache per chart (disks posed by earlier
// cells reused, new ones posed in the loop) and the lists of the builder's grid order.
TEST(BlockedTester, CandidateLoopKeepsTheDefinitionsPairsInOrder) {
  using Pair = cspace::BlockedTester::DiskPair;
  using Probe = cspace::BlockedTesterProbe;
  Random random(20261202);
  int cells = 0, blocked = 0, kept_pairs = 0, nonempty = 0;
  for_each_two_d_pair({{"geneva.json", "driver", "wheel"}, {"ratchet.json", "wheel", "pawl"},
                       {"escapement.json", "escape-wheel", "anchor"}, {"scotch-yoke.json", "crank", "yoke"}},
                      [&](const std::string& file, const Model& model, const cspace::PairAxes& axes,
                          const cspace::ChartLayout& layout) {
    auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
    if (!tester->usable()) return;
    for (const auto& x : layout.x_charts)
      for (const auto& y : layout.y_charts) {
        cspace::BlockedCells grid(tester, x, y, 2, 9);
        cspace::BlockedTester::Cache cache;
        std::vector<std::vector<Pair>> lists(16);
        std::vector<char> list_blocked(16);
        for (long i = 0; i < 4; ++i)
          for (long j = 0; j < 4; ++j) {
            cspace::BlockedTester::Cache fresh;
            const auto k = static_cast<std::size_t>(4 * i + j);
            list_blocked[k] = tester->blocked(x, y, grid.cell_x(2, i), grid.cell_y(2, j), fresh, nullptr, &lists[k]);
          }
        std::map<std::pair<long, long>, std::vector<Pair>> depth5;   // narrowed lists of depth-5 cells
        for (int n = 0; n < 700; ++n) {
          const int depth = 3 + static_cast<int>(random() % 7);
          const long count = 1L << depth;
          const long i = static_cast<long>(random() % static_cast<unsigned long>(count));
          const long j = static_cast<long>(random() % static_cast<unsigned long>(count));
          const auto enclosing = static_cast<std::size_t>(4 * (i >> (depth - 2)) + (j >> (depth - 2)));
          if (list_blocked[enclosing]) continue;
          const std::vector<Pair>* parent = &lists[enclosing];
          if (depth > 5) {
            auto it = depth5.find({i >> (depth - 5), j >> (depth - 5)});
            if (it != depth5.end()) parent = &it->second;
          }
          const Interval bx = grid.cell_x(depth, i), by = grid.cell_y(depth, j);
          std::vector<Pair> kept, expected;
          const bool answer = tester->blocked(x, y, bx, by, cache, parent, &kept);
          const bool expected_answer = Probe::candidate_loop(*tester, x, y, bx, by, *parent, expected);
          ++cells;
          ASSERT_EQ(answer, expected_answer) << file << " cell " << depth << ", " << i << ", " << j;
          ASSERT_EQ(answer, tester->blocked(x, y, bx, by)) << file << " cell " << depth << ", " << i << ", " << j;
          // without `narrowed`: the same answer
          ASSERT_EQ(tester->blocked(x, y, bx, by, cache, parent, nullptr), answer) << file;
          if (answer) {
            ++blocked;
            continue;
          }
          ASSERT_EQ(kept.size(), expected.size()) << file << " cell " << depth << ", " << i << ", " << j;
          for (std::size_t m = 0; m < kept.size(); ++m) {
            ASSERT_EQ(kept[m].first, expected[m].first) << file << " cell " << depth << ", " << i << ", " << j << " pair " << m;
            ASSERT_EQ(kept[m].second, expected[m].second) << file << " cell " << depth << ", " << i << ", " << j << " pair " << m;
          }
          kept_pairs += static_cast<int>(kept.size());
          nonempty += !kept.empty() && kept.size() < parent->size();
          if (depth == 5) depth5.emplace(std::make_pair(i, j), kept);
        }
      }
  });
  std::cout << cells << " cells, " << blocked << " blocked, " << kept_pairs << " pairs kept, " << nonempty
            << " lists narrowed\n";
  EXPECT_GT(blocked, 200);
  EXPECT_GT(nonempty, 200);   // lists that keep some pairs and drop others
}

// One step of a cell walk mixing the generator's and the builder's orders: every `every`-th step
// a new place (depth 2 to 14), else the next column, the next row or a child of the last cell.
void next_walk_cell(Random& random, int n, int every, int& depth, long& i, long& j) {
  const long side = 1L << depth;
  if (n % every == 0) {   // a new place
    depth = 2 + static_cast<int>(random() % 13);
    i = static_cast<long>(random() % (1UL << depth));
    j = static_cast<long>(random() % (1UL << depth));
  } else if (random() % 3 == 0) {
    i = std::min(side - 1, i + 1);   // the next column
  } else if (random() % 2 == 0) {
    j = std::min(side - 1, j + 1);   // the next row
  } else if (depth < 14) {           // a child
    ++depth;
    i = 2 * i + static_cast<long>(random() % 2);
    j = 2 * j + static_cast<long>(random() % 2);
  }
}

// Asks `grid` (of chart box x, y or a tile of it) `count` cells in turn, as the curve
// generator's and the builder's walks mix them: every fourth a new place (depth 2 to 14), else
// the next column, the next row or a child of the last cell. A cell the grid calls free must be
// free to the plain tester (a fresh sweep of the cell alone), a cell it calls blocked blocked to
// it or inside a cell the grid called blocked before (`inherited`); at a random rational
// configuration of every fourth blocked cell the parts overlap (the exact oracle). Returns the
// wrong answers.
int walk_grid(cspace::BlockedCells& grid, const cspace::BlockedTester& tester, const Model& model,
              const cspace::PairAxes& axes, const cspace::ChartAxis& x, const cspace::ChartAxis& y, int count,
              Random& random, Counts& counts, int& cells, int& blocked, int& inherited, const std::string& what) {
  int wrong = 0;
  std::set<std::tuple<int, long, long>> said_blocked;
  auto inside_blocked = [&](int depth, long i, long j) {
    for (int up = 1; up <= depth; ++up)
      if (said_blocked.count({depth - up, i >> up, j >> up})) return true;
    return false;
  };
  int depth = 2;
  long i = 0, j = 0;
  for (int n = 0; n < count; ++n) {
    next_walk_cell(random, n, 4, depth, i, j);
    const Interval bx = grid.cell_x(depth, i), by = grid.cell_y(depth, j);
    const bool answer = grid.blocked(depth, i, j);
    const bool plain = tester.blocked(x, y, bx, by);
    ++cells;
    const std::string where = what + " cell " + std::to_string(depth) + ", " + std::to_string(i) + ", " +
                              std::to_string(j);
    if (!answer) {
      EXPECT_FALSE(plain) << where << ": the grid calls free a blocked cell";
      wrong += plain;
      continue;
    }
    ++blocked;
    said_blocked.insert({depth, i, j});
    if (!plain) {
      const bool in = inside_blocked(depth, i, j);
      EXPECT_TRUE(in) << where << ": the grid calls blocked a cell the sweep does not";
      inherited += in;
      wrong += !in;
    }
    if (blocked % 4 == 0) check_blocked_box(model, axes, x, y, bx, by, true, 1, random, counts, where);
  }
  return wrong;
}

// `check(what, model, axes, tester, x, y, count)` on every chart of the pairs of
// on_examples_and_bar_walls with a usable tester.
template <class F>
void on_every_chart(Random& random, int example_count, int bar_count, F&& check) {
  on_examples_and_bar_walls(random, example_count, bar_count,
                            [&](const std::string& what, const Model& model, const cspace::PairAxes& axes,
                                const cspace::ChartLayout& layout, int count) {
                              auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
                              if (!tester->usable()) return;
                              for (const auto& x : layout.x_charts)
                                for (const auto& y : layout.y_charts) check(what, model, axes, tester, x, y, count);
                            });
}

// The grid (BlockedCells) asked in any order — runs of neighbouring cells, children and
// grandchildren of the last cell and cells at random, of depths 2 to 14, as the curve
// generator's and the builder's walks mix them: a cell the grid calls free is free to the
// plain tester (a fresh sweep of the cell alone), a cell it calls blocked is blocked to the
// plain tester or lies inside a cell the grid called blocked before, and at a random rational
// configuration of every fourth blocked cell the parts overlap (the exact oracle). Exercises the
// poses the grid finds by cell index (BlockedTester::Cache::by_cell_) and by the cell's ends past
// the indexed depths, and the candidate lists of every ancestor depth. On the examples' charts
// and on generated bar-and-wall pairs at scales 1e-200 to 1e200.
TEST(BlockedTester, GridAnswersInAnyOrderAreTheSweepsAndOverlapExactly) {
  Random random(20261203);
  int cells = 0, blocked = 0, inherited = 0, wrong = 0;
  Counts counts;
  on_every_chart(random, 1200, 400, [&](const std::string& what, const Model& model, const cspace::PairAxes& axes,
                                        const std::shared_ptr<cspace::BlockedTester>& tester, const cspace::ChartAxis& x,
                                        const cspace::ChartAxis& y, int count) {
    cspace::BlockedCells grid(tester, x, y, 2, 9);
    wrong += walk_grid(grid, *tester, model, axes, x, y, count, random, counts, cells, blocked, inherited, what);
  });
  std::cout << cells << " cells, " << blocked << " blocked (" << inherited << " inside a blocked cell), " << wrong
            << " wrong, " << counts.points << " configurations of blocked cells checked with the oracle\n";
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(blocked, 1000);
}


// An operating-region tile's grid given the candidate list of a box holding the tile
// (BlockedCells::enclose: the list the flood made for the tile or its block) answers as the
// sweep: on tiles (1/4 to 1/16 of a chart per axis) of the examples' charts and of generated
// bar-and-wall pairs at 1e-200 to 1e200, the list of a random box holding the tile (the
// tile's own enclosure or wider, up to the chart), cells asked in any order at depths 2-14:
// a cell the grid calls free is free to a fresh plain sweep, a blocked one is blocked to it or
// inside a cell the grid called blocked before, and at a random rational configuration of every
// fourth blocked cell the parts overlap (the exact oracle). A list of a box that does not hold
// the tile (a box beside it) is refused, and the grid offered it answers as the sweep.
TEST(BlockedTester, TileGridsOnAnEnclosingBoxsListAreTheSweeps) {
  Random random(20261204);
  int cells = 0, blocked = 0, inherited = 0, wrong = 0, tiles = 0, accepted = 0, refused = 0;
  Counts counts;
  on_every_chart(random, 120, 120, [&](const std::string& what, const Model& model, const cspace::PairAxes& axes,
                                      const std::shared_ptr<cspace::BlockedTester>& tester, const cspace::ChartAxis& x,
                                      const cspace::ChartAxis& y, int count) {
    for (int t = 0; t < 3; ++t) {
      const long side = 4L << (random() % 3);
      const long tx = static_cast<long>(random() % static_cast<unsigned long>(side));
      const long ty = static_cast<long>(random() % static_cast<unsigned long>(side));
      const cspace::ChartAxis tile_x = test_charts::sub_axis(x, tx, 1, side);
      const cspace::ChartAxis tile_y = test_charts::sub_axis(y, ty, 1, side);
      // a box holding the tile: its enclosure widened by 0 to a tile on each side, within the chart
      const Interval chart_x{cspace::algebra::lower_double(x.lo), cspace::algebra::upper_double(x.hi)};
      const Interval chart_y{cspace::algebra::lower_double(y.lo), cspace::algebra::upper_double(y.hi)};
      auto widened = [&](const cspace::ChartAxis& tile, const Interval& chart) {
        const double lo = cspace::algebra::lower_double(tile.lo), hi = cspace::algebra::upper_double(tile.hi);
        const double step = (hi - lo) / 4;
        return Interval{std::max(chart.lo, lo - step * static_cast<double>(random() % 5)),
                        std::min(chart.hi, hi + step * static_cast<double>(random() % 5))};
      };
      const Interval ex = widened(tile_x, chart_x), ey = widened(tile_y, chart_y);
      cspace::BlockedTester::Cache cache;
      auto pairs = std::make_shared<std::vector<cspace::BlockedTester::DiskPair>>();
      if (tester->blocked(x, y, ex, ey, cache, nullptr, pairs.get())) continue;   // no list
      ++tiles;
      // the list of a box beside the tile (the tile moved by half the chart in x; its pairs
      // are other disks')
      const double half = 0.5 * (chart_x.hi - chart_x.lo);
      const double shift = 0.5 * (ex.lo + ex.hi) < chart_x.lo + half ? half : -half;
      const Interval cut{ex.lo + shift, ex.hi + shift};
      auto cut_pairs = std::make_shared<std::vector<cspace::BlockedTester::DiskPair>>();
      tester->blocked(x, y, cut, ey, cache, nullptr, cut_pairs.get());
      for (bool holds : {true, false}) {
        cspace::BlockedCells grid(tester, tile_x, tile_y, 2, 9);
        const bool kept = grid.enclose(holds ? ex : cut, ey, holds ? pairs : cut_pairs);
        EXPECT_EQ(kept, holds) << what << (holds ? ": a list of a box holding the tile refused"
                                                 : ": a list of a box not holding the tile kept");
        (kept ? accepted : refused) += 1;
        wrong += walk_grid(grid, *tester, model, axes, tile_x, tile_y, count, random, counts, cells, blocked,
                           inherited,
                           what + " tile " + std::to_string(tx) + ", " + std::to_string(ty) + " of " +
                               std::to_string(side) + (holds ? "" : " (offered a list of a box beside it)"));
      }
    }
  });
  std::cout << tiles << " tiles (" << accepted << " lists kept, " << refused << " refused), " << cells << " cells, "
            << blocked << " blocked (" << inherited << " inside a blocked cell), " << wrong << " wrong, " << counts.points
            << " configurations of blocked cells checked with the oracle\n";
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(blocked, 500);
  EXPECT_GT(tiles, 40);
}

// Grids that share their parts' poses (SharedPoses: the builder's charts with one axis in common,
// the operating-region tiles of one column) answer as grids with their own caches: for every
// pair of on_examples_and_bar_walls, the charts' grids made one after the other with one pool (two
// passes over the charts, then tiles 1/4 of a chart per axis, some in one column or row, as the
// builder's boxes come), each asked the same cells in the same order as a grid over the same box
// with a cache of its own — runs of neighbours, children and random cells of depths 2 to 14: the
// same answer at every cell; a cell called free is free to a plain sweep of the cell alone; and at
// a random rational configuration of every 16th blocked cell the parts overlap (the exact
// oracle). Pools keeping one and two axes per part (the first evicts and makes poses again).
// Seeded (HIPAIR_TEST_SEED).
TEST(BlockedTester, GridsSharingPosesAnswerAsGridsWithTheirOwnCaches) {
  const std::uint64_t seed = test::test_seed(20261205);
  Random random(seed);
  int cells = 0, blocked = 0, differ = 0, unsound = 0;
  std::size_t reused = 0;
  Counts counts;
  on_examples_and_bar_walls(random, 160, 80, [&](const std::string& what, const Model& model, const cspace::PairAxes& axes,
                                                  const cspace::ChartLayout& layout, int count) {
    auto tester = std::make_shared<cspace::BlockedTester>(model, axes);
    if (!tester->usable()) return;
    for (std::size_t kept : {std::size_t{1}, std::size_t{2}}) {
      cspace::SharedPoses pool(kept);
      // the boxes in the builder's order: every chart twice, then tiles of each chart
      std::vector<std::pair<cspace::ChartAxis, cspace::ChartAxis>> boxes;
      for (int pass = 0; pass < 2; ++pass)
        for (const auto& x : layout.x_charts)
          for (const auto& y : layout.y_charts) boxes.emplace_back(x, y);
      for (const auto& x : layout.x_charts)
        for (const auto& y : layout.y_charts)
          for (long tx = 0; tx < 2; ++tx)
            for (long ty = 0; ty < 2; ++ty)
              boxes.emplace_back(test_charts::sub_axis(x, tx, 1, 4), test_charts::sub_axis(y, 1 + ty, 1, 4));
      for (const auto& [x, y] : boxes) {
        cspace::BlockedCells shared(tester, x, y, 2, 9, &pool), own(tester, x, y, 2, 9);
        int depth = 2;
        long i = 0, j = 0;
        for (int n = 0; n < count; ++n) {
          next_walk_cell(random, n, 5, depth, i, j);
          const std::string where = what + " (seed " + std::to_string(seed) + ", " + std::to_string(kept) +
                                    " kept) cell " + std::to_string(depth) + ", " + std::to_string(i) + ", " +
                                    std::to_string(j);
          const bool answer = shared.blocked(depth, i, j), expected = own.blocked(depth, i, j);
          ++cells;
          EXPECT_EQ(answer, expected) << where << ": a grid sharing poses answers otherwise";
          differ += answer != expected;
          const Interval bx = shared.cell_x(depth, i), by = shared.cell_y(depth, j);
          if (!answer) {
            const bool plain = tester->blocked(x, y, bx, by);
            EXPECT_FALSE(plain) << where << ": the grid calls free a blocked cell";
            unsound += plain;
            continue;
          }
          if (++blocked % 16 == 0) check_blocked_box(model, axes, x, y, bx, by, true, 1, random, counts, where);
        }
      }
      reused += pool.reused();
    }
  });
  std::cout << cells << " cells, " << blocked << " blocked, " << differ << " answered otherwise, " << unsound
            << " free cells blocked to the sweep, " << reused << " parts' poses taken from another grid, "
            << counts.points << " configurations of blocked cells checked with the oracle\n";
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(unsound, 0);
  EXPECT_GT(blocked, 1000);
  EXPECT_GT(reused, 20u);
}

}  // namespace
}  // namespace hipair
